//! `assume`: a scene's domain. Its random points keep to it and the engine decides signs by it,
//! so a claim true only there is decided, and decided the same for every seed; a wrong form
//! still disagrees.

use super::{mechbook, scratch, stdout};

/// A ball of radius r in a bowl of radius R: two claims true where R > r, and one wrong.
fn bowl(assume: &str, seed: u64) -> String {
    format!(
        r#"id = "bowl-domain"
title = "Roots that need R > r"
notes = {{ lecture = "x" }}
{assume}
[symbols]
R = "radius of the bowl"
r = "radius of the ball"
g = "gravitational acceleration"

[[claim]]
eq = "1"
statement = "a root of a square"
quantity = "sqrt((R - r)^2)"
value = "R - r"

[[claim]]
eq = "2"
statement = "the period as the inverse of a frequency"
quantity = "2*pi/sqrt(5*g/(7*(R - r)))"
value = "2*pi*sqrt(7*(R - r)/(5*g))"

[[claim]]
eq = "3"
statement = "a period with its fraction upside down"
quantity = "2*pi/sqrt(5*g/(7*(R - r)))"
value = "2*pi*sqrt(5*(R - r)/(7*g))"

[numeric]
values = {{ R = 0.5, r = 0.02, g = 9.81 }}
seed = {seed}
"#
    )
}

/// Each claim's verdict, by `derive --json` in a folder of its own (`name`).
pub(super) fn verdicts(text: &str, name: &str) -> Vec<String> {
    let dir = scratch(name);
    let path = dir.join("bowl.toml");
    std::fs::write(&path, text).unwrap();
    let out = mechbook(&["derive", "--json", path.to_str().unwrap()]);
    let json: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    json["claims"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["verdict"].as_str().unwrap().to_string())
        .collect()
}

#[test]
fn a_claim_true_in_the_domain_is_decided_for_every_seed() {
    for seed in 1..=6 {
        assert_eq!(
            verdicts(
                &bowl("assume = [\"R > r\"]", seed),
                &format!("domain-{seed}")
            ),
            ["agrees", "agrees", "disagrees"],
            "seed {seed}"
        );
    }
    // Without the domain, |R − r| is not R − r; the period agrees by its squares (both sides
    // roots, never negative), and only where both sides are real, which the claim says.
    let free = verdicts(&bowl("", 1), "domain-free");
    assert!(free[0] != "agrees" && free[1] == "agrees", "{free:?}");
    let dir = scratch("domain-free-json");
    let path = dir.join("bowl.toml");
    std::fs::write(&path, bowl("", 1)).unwrap();
    let out = mechbook(&["derive", "--json", path.to_str().unwrap()]);
    let json: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let where_real: Vec<bool> = json["claims"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["where_real"].as_bool().unwrap_or(false))
        .collect();
    assert_eq!(where_real, [false, true, false]);
}

/// Textbook identities over positive symbols, and an even power under a root of a signed
/// coordinate's sine, each decided; a wrong form of each of two still disagrees.
#[test]
fn textbook_identities_agree_and_their_wrong_forms_do_not() {
    let claim = |eq: usize, quantity: &str, value: &str| {
        format!(
            "[[claim]]\neq = \"{eq}\"\nstatement = \"an identity\"\nquantity = \"{quantity}\"\nvalue = \"{value}\"\n\n"
        )
    };
    let text = format!(
        "id = \"identities\"\ntitle = \"Textbook identities\"\nnotes = {{ lecture = \"x\" }}\n\n\
         [symbols]\nL = \"a length\"\na = \"one\"\nb = \"another\"\nX = \"a positive quantity\"\n\n\
         [coordinates]\ntheta = \"an angle\"\n\n{}{}{}{}{}{}\
         [numeric]\nvalues = {{ L = 1.0, a = 2.0, b = 3.0, X = 2.0 }}\n",
        claim(1, "L/sqrt(12)", "sqrt(3)*L/6"),
        claim(2, "sqrt(a)/sqrt(b)", "sqrt(a/b)"),
        claim(3, "sqrt(a)*sqrt(b)", "sqrt(a*b)"),
        claim(4, "sqrt(sin(theta)^4*X)", "sin(theta)^2*sqrt(X)"),
        claim(5, "L/sqrt(12)", "sqrt(2)*L/6"),
        claim(6, "sqrt(sin(theta)^4*X)", "sin(theta)*sqrt(X)"),
    );
    assert_eq!(
        verdicts(&text, "identities"),
        [
            "agrees",
            "agrees",
            "agrees",
            "agrees",
            "disagrees",
            "disagrees"
        ]
    );
}
