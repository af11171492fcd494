//! The elementary functions (exp, log, asin, acos, atan, atan2, sinh, cosh, tanh, abs) in
//! claims and in an author's steps: identities decided, wrong forms disagreeing, and a Morse
//! oscillator derived from its Lagrangian to its textbook frequency.

use super::domain::verdicts;
use super::{mechbook, scratch, stdout};

/// Each identity agrees, for every seed, and each wrong form beside it disagrees.
#[test]
fn elementary_function_identities_agree_and_their_wrong_forms_do_not() {
    let cases = [
        ("log(exp(a*b))", "a*b", "agrees"),
        ("exp(log(a))", "a", "agrees"),
        ("exp(a*b)*exp(-a*b)", "1", "agrees"),
        ("exp(a*b)*exp(a*b)", "1", "disagrees"),
        ("cosh(a*b)^2 - sinh(a*b)^2", "1", "agrees"),
        ("cosh(a*b)^2 + sinh(a*b)^2", "1", "disagrees"),
        ("sin(asin(a/(a + b)))", "a/(a + b)", "agrees"),
        ("sin(asin(a/(a + b)))", "b/(a + b)", "disagrees"),
        ("cos(asin(1/(1 + a)))", "sqrt(a*(a + 2))/(1 + a)", "agrees"),
        ("diff(atan(a*b), b)", "a/(1 + a^2*b^2)", "agrees"),
        ("diff(tanh(a*b), b)", "a/cosh(a*b)^2", "agrees"),
        ("diff(tanh(a*b), b)", "a/cosh(a*b)", "disagrees"),
        ("diff(log(b), b)", "1/b", "agrees"),
        ("diff(atan2(a, a*b), b)", "-1/(1 + b^2)", "agrees"),
        ("abs(-a*b)", "a*b", "agrees"),
        ("abs(-a*b)", "-a*b", "disagrees"),
        ("atan2(a, a)", "pi/4", "agrees"),
        ("atan2(a, a)", "pi/3", "disagrees"),
        ("acos(1/2)", "pi/3", "agrees"),
    ];
    let claims: String = cases
        .iter()
        .enumerate()
        .map(|(k, (quantity, value, _))| {
            format!(
                "[[claim]]\neq = \"{}\"\nstatement = \"an identity\"\nquantity = \"{quantity}\"\nvalue = \"{value}\"\n\n",
                k + 1
            )
        })
        .collect();
    let want: Vec<&str> = cases.iter().map(|c| c.2).collect();
    for seed in 1..=4 {
        let text = format!(
            "id = \"functions\"\ntitle = \"Elementary functions\"\nnotes = {{ lecture = \"x\" }}\n\n\
             [symbols]\na = \"one\"\nb = \"another\"\n\n{claims}\
             [numeric]\nvalues = {{ a = 2.0, b = 3.0 }}\nseed = {seed}\n"
        );
        assert_eq!(
            verdicts(&text, &format!("functions-{seed}")),
            want,
            "seed {seed}"
        );
    }
}

/// A particle in Morse's potential D(1 − e^(−a(x − x₀)))².
const MORSE: &str = r#"id = "morse"
title = "A particle in a Morse potential"
notes = { lecture = "Oscillations", section = "2" }

[symbols]
m = { meaning = "mass of the particle", unit = "kg" }
D = { meaning = "depth of the well", unit = "J" }
a = { meaning = "inverse width of the well", unit = "1/m" }
x0 = { meaning = "position of the minimum", unit = "m" }

[coordinates]
x = { meaning = "distance from the centre", unit = "m" }

[[step]]
name = "Lag"
tex = "L"
be = "m*x'^2/2 - D*(1 - exp(-a*(x - x0)))^2"
why = "$T - V$"

[[step]]
name = "eom"
lagrange = "Lag"
why = "the Euler–Lagrange equation of $x$"

[[step]]
name = "small"
linearise = "eom"
about = { x = "x0" }
why = "small displacements about the minimum"

[[step]]
name = "Omega"
tex = "\\Omega"
frequency = "small"
why = "the angular frequency of the linear equation"
gives = "a*sqrt(2*D/m)"
expect = "agrees"

[[step]]
name = "V"
be = "D*(1 - exp(-a*(x - x0)))^2"
why = "the potential"

[[step]]
name = "V3"
tex = "V_3"
series = "V"
about = { x = "x0" }
order = 3
why = "near the minimum"
gives = "D*a^2*(x - x0)^2 - D*a^3*(x - x0)^3"
expect = "agrees"

[[step]]
name = "F"
be = "a*x0*exp(-x/x0)*cosh(a*x) + atan(a*x) + a*abs(x - x0) + tanh(a*x)"
why = "each function at once"

[[step]]
name = "dF"
tex = "F'"
differentiate = "F"
by = "x"
why = "each derivative"

[outputs]
want = []

[numeric]
values = { m = 0.5, D = 2, a = 1.5, x0 = 1 }
"#;

/// Derived, blessed and checked again for several seeds: every step's own numeric route
/// (the integrated period for Ω, the series' remainder, the derivative at random points)
/// agrees, and Ω at the scene's values is the textbook's a√(2D/m), computed here.
#[test]
fn a_morse_oscillator_is_derived_to_its_textbook_frequency() {
    let dir = scratch("morse");
    let path = dir.join("morse.toml");
    let at = path.to_str().unwrap();
    std::fs::write(&path, MORSE).unwrap();
    let blessed = mechbook(&["check", "--bless", at]);
    assert_eq!(blessed.status.code(), Some(0), "{}", stdout(&blessed));
    let recorded = std::fs::read_to_string(&path).unwrap();
    assert!(recorded.contains("dF = "), "{recorded}");
    for seed in 2..=4 {
        let seeded = recorded.replace(
            "values = { m = 0.5, D = 2, a = 1.5, x0 = 1 }",
            &format!("values = {{ m = 0.5, D = 2, a = 1.5, x0 = 1 }}\nseed = {seed}"),
        );
        std::fs::write(&path, seeded).unwrap();
        let out = mechbook(&["check", at]);
        assert_eq!(out.status.code(), Some(0), "seed {seed}: {}", stdout(&out));
        assert!(stdout(&out).contains("all as recorded"), "{}", stdout(&out));
    }
    let out = mechbook(&["derive", "--json", at]);
    let json: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    let textbook = 1.5 * (2.0f64 * 2.0 / 0.5).sqrt();
    let value = json["quantities"]["Omega"]["numeric"]
        .as_f64()
        .unwrap_or_else(|| panic!("{json:#}"));
    assert!(
        (value - textbook).abs() < 1e-12 * textbook,
        "{value} vs {textbook}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
