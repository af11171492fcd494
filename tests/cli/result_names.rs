//! The names of a step's several results (`x_1`, `Omega_2`) do not depend on
//! the scene's values; an author may name them (`names = [...]`); a `solve` for a symbol the
//! scene takes positive gives its positive roots only.

use super::{mechbook, scratch, stderr, stdout};

/// `derive --json` of a scene text, in a folder of its own (`name`): the JSON, or the error.
fn derive(text: &str, name: &str) -> Result<serde_json::Value, String> {
    let dir = scratch(name);
    let path = dir.join("s.toml");
    std::fs::write(&path, text).unwrap();
    let out = mechbook(&["derive", "--json", path.to_str().unwrap()]);
    std::fs::remove_dir_all(&dir).unwrap();
    match out.status.success() {
        true => Ok(serde_json::from_str(&stdout(&out)).unwrap()),
        false => Err(stderr(&out)),
    }
}

/// A `solve` of `equation` = 0 for `x`, with `extra` (a `names`, claims) after the step.
fn solving(equation: &str, x: &str, values: &str, extra: &str) -> String {
    format!(
        r#"id = "roots"
title = "Roots"
notes = {{ lecture = "x" }}

[symbols]
a = "a length"
b = "another length"
{x} = "the unknown"

[[step]]
name = "r"
be = "{equation}"
why = "the equation"

[[step]]
name = "x"
solve = "r"
for = "{x}"
why = "its roots"
{extra}
[numeric]
values = {{ {values} }}
"#
    )
}

/// Each named result's exact form, by name.
fn exact(json: &serde_json::Value, name: &str) -> String {
    json["quantities"][name]["exact"]
        .as_str()
        .unwrap_or_else(|| panic!("no quantity `{name}` in {}", json["quantities"]))
        .to_string()
}

#[test]
fn roots_are_numbered_smallest_first_where_that_holds_for_every_value() {
    // a < 3a for every positive a: x_1 = a at any value of a, though "3*a" comes first as
    // text. Numbered by value at the scene's values, or as text, this would differ.
    for (k, a) in ["0.5", "7.0"].iter().enumerate() {
        let text = solving(
            "(y - a)*(y - 3*a)",
            "y",
            &format!("a = {a}, b = 1.0, y = 1.0"),
            "",
        );
        let json = derive(&text, &format!("names-ascending-{k}")).unwrap();
        assert_eq!(exact(&json, "x_1"), "a", "a = {a}");
        assert_eq!(exact(&json, "x_2"), "3*a", "a = {a}");
    }
}

#[test]
fn roots_that_cross_keep_their_names_when_the_values_change() {
    // a and b cross as the values change: each keeps its name at a < b and at a > b.
    let names = |a: f64, b: f64, tag: &str| {
        let text = solving(
            "(y - a)*(y - b)",
            "y",
            &format!("a = {a:?}, b = {b:?}, y = 1.0"),
            "",
        );
        let json = derive(&text, tag).unwrap();
        (exact(&json, "x_1"), exact(&json, "x_2"))
    };
    let below = names(1.0, 2.0, "names-cross-below");
    let above = names(2.0, 1.0, "names-cross-above");
    assert_eq!(below, above);
    assert_ne!(below.0, below.1);
}

#[test]
fn a_positive_unknown_takes_its_positive_root_and_a_coordinate_both() {
    // y is a symbol of the scene, so positive: √a alone, named `x`.
    let json = derive(
        &solving("y^2 - a", "y", "a = 2.0, b = 1.0, y = 1.0", ""),
        "names-positive",
    )
    .unwrap();
    assert_eq!(exact(&json, "x"), "a^(1/2)");
    assert!(json["quantities"].get("x_1").is_none());
    // A value that makes y negative in [numeric] makes it signed: both roots.
    let json = derive(
        &solving("y^2 - a", "y", "a = 2.0, b = 1.0, y = -1.0", ""),
        "names-signed",
    )
    .unwrap();
    assert_eq!(exact(&json, "x_1"), "-a^(1/2)");
    assert_eq!(exact(&json, "x_2"), "a^(1/2)");
}

#[test]
fn an_author_names_the_roots_and_claims_use_those_names() {
    let extra = r#"names = ["near", "far"]

[[claim]]
eq = "1"
statement = "the far root"
quantity = "far"
value = "3*a"
expect = "agrees"

[[claim]]
eq = "2"
statement = "the far root, said wrong"
quantity = "far"
value = "2*a"
expect = "disagrees"
"#;
    let json = derive(
        &solving("(y - a)*(y - 3*a)", "y", "a = 0.5, b = 1.0, y = 1.0", extra),
        "names-own",
    )
    .unwrap();
    assert_eq!(exact(&json, "near"), "a");
    assert_eq!(exact(&json, "far"), "3*a");
    assert!(json["quantities"].get("x_1").is_none());
    let verdicts: Vec<&str> = json["claims"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["verdict"].as_str().unwrap())
        .collect();
    assert_eq!(verdicts, ["agrees", "disagrees"]);
}

#[test]
fn names_of_the_wrong_count_or_on_a_single_result_are_refused_at_their_line() {
    let err = derive(
        &solving(
            "(y - a)*(y - 3*a)",
            "y",
            "a = 0.5, b = 1.0, y = 1.0",
            "names = [\"near\", \"middle\", \"far\"]\n",
        ),
        "names-count",
    )
    .unwrap_err();
    assert!(err.contains("s.toml:15"), "{err}");
    assert!(
        err.contains("gives 2 results, and `names` lists 3"),
        "{err}"
    );
    let err = derive(
        &solving(
            "y - a",
            "y",
            "a = 0.5, b = 1.0, y = 1.0",
            "names = [\"only\"]\n",
        ),
        "names-single",
    )
    .unwrap_err();
    assert!(err.contains("leave out `names`"), "{err}");
    // On a step of one result by its operation, at load.
    let text = solving("y - a", "y", "a = 0.5, b = 1.0, y = 1.0", "").replace(
        "why = \"the equation\"",
        "why = \"the equation\"\nnames = [\"one\"]",
    );
    let err = derive(&text, "names-be").unwrap_err();
    assert!(err.contains("step[0].names"), "{err}");
    assert!(err.contains("`be` gives one"), "{err}");
}
