//! Printed is proved: each entry of a list `gives` printed beside
//! its own result, never the first entry's form beside a later one; a product of a number and a
//! power of a variant's decimal keeps its times sign (3 ⋅ 0.4⁴, once "30.4⁴").

use super::{mechbook, mechbook_in, scratch, stderr, stdout};
use std::path::Path;

fn scene(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// Two pendulums joined by a spring (the issue's reproducer): Ω₂ was printed √(g/l), the form
/// the list gives Ω₁, beside its value √(g/l + 2k/m), and a quadratic's r₂ was printed a.
#[test]
fn each_entry_of_a_list_gives_is_printed_beside_its_own_result() {
    let dir = scratch("list-gives");
    let scenes = dir.join("scenes");
    std::fs::create_dir_all(&scenes).unwrap();
    let coupled = scene(
        &scenes,
        "coupled.toml",
        r#"id = "coupled"
title = "Two coupled pendulums"
notes = { lecture = "1" }
symbols = { m = "mass", l = "length", g = "gravity", k = "spring constant", t = "time" }

[coordinates]
phi1 = { meaning = "angle of the first pendulum", unit = "rad" }
phi2 = { meaning = "angle of the second pendulum", unit = "rad" }

[outputs]
want = []

[[step]]
name = "Lag"
tex = "L"
be = "m*l^2/2*(phi1'^2 + phi2'^2) + m*g*l*(cos(phi1) + cos(phi2)) - k*l^2/2*(sin(phi1) - sin(phi2))^2"
why = "the Lagrangian"

[[step]]
name = "eom"
lagrange = "Lag"
why = "the equations"

[[step]]
name = "small"
linearise = "eom"
about = { phi1 = "0", phi2 = "0" }
why = "small angles"

[[step]]
name = "Omega"
frequency = "small"
gives = ["sqrt(g/l)", "sqrt(g/l + 2*k/m)"]
why = "the normal modes"
expect = "agrees"

[numeric]
values = { m = 0.2, l = 0.5, g = 9.81, k = 0.5 }
"#,
    );
    let roots = scene(
        &scenes,
        "roots.toml",
        r#"id = "roots"
title = "Two roots"
notes = { lecture = "1" }
assume = ["b > a"]
symbols = { a = "a length", b = "another", x = "the unknown" }

[outputs]
want = []

[numeric]
values = { a = 1.0, b = 2.0 }

[[step]]
name = "f"
be = "(x - a)*(x - 2*b)"
why = "a product"

[[step]]
name = "r"
solve = "f"
for = "x"
gives = ["a", "2*b"]
why = "its roots"
expect = "agrees"
"#,
    );
    for (file, lines) in [
        (
            &coupled,
            ["Omega_1 = sqrt(g/l)\n", "Omega_2 = sqrt(g/l + 2*k/m)\n"],
        ),
        (&roots, ["r_1 = a\n", "r_2 = 2*b\n"]),
    ] {
        let out = mechbook(&["derive", file]);
        let said = stdout(&out);
        assert!(out.status.success(), "{file}: {}", stderr(&out));
        for line in lines {
            assert!(said.contains(line), "{file}: {line} not in\n{said}");
        }
    }
    // The page, its spoken form included.
    let site = dir.join("site");
    let out = mechbook(&[
        "build",
        &coupled,
        "--no-cache",
        "--out",
        site.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let page = std::fs::read_to_string(site.join("coupled.html")).unwrap();
    assert!(
        page.contains(
            "alttext=\"capital omega sub 2 equals the square root of g over l plus fraction 2 k \
             over m, end fraction, end root\""
        ),
        "{page}"
    );
    assert!(
        !page.contains("alttext=\"capital omega sub 2 equals the square root of g over l, end"),
        "{page}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

/// A variant's decimal raised to a power, after a number: the key's exact column printed
/// 3 0.5⁴ (read as thirty point five to the fourth) and spoke it "3 0.5 to the power 4".
#[test]
fn a_number_before_a_power_of_a_decimal_keeps_its_times_sign() {
    let dir = scratch("decimal-power");
    std::fs::create_dir_all(dir.join("lectures/w1")).unwrap();
    std::fs::write(dir.join("mechbook.toml"), "title = \"Decimals\"\n").unwrap();
    scene(
        &dir.join("lectures/w1"),
        "r4.toml",
        r#"id = "r4"
title = "A power of a decimal"
notes = { lecture = "1" }
symbols = { R = "radius" }

[outputs]
want = []

[numeric]
values = { R = 0.4 }

[[step]]
name = "J"
be = "3*R^4"
why = "the moment"

[problem]
statement = "Take R = {R}."
answers = ["J"]

[variants]
count = 2
seed = 1
R = ["0.4", "0.5", "0.6"]
"#,
    );
    let run = |args: &[&str]| {
        let out = mechbook_in(&dir, args);
        assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    };
    run(&["check", "--bless"]);
    run(&["build", "--no-cache"]);
    let key =
        std::fs::read_to_string(dir.join("site/handouts/lecture-1-problems-key.html")).unwrap();
    assert!(
        key.contains("<mn>3</mn><mo>⋅</mo><msup><mn>0.5</mn>"),
        "{key}"
    );
    assert!(
        key.contains("alttext=\"3 times 0.5 to the power 4\""),
        "{key}"
    );
    assert!(!key.contains("<mn>3</mn><msup>"), "{key}");
    std::fs::remove_dir_all(dir).unwrap();
}
