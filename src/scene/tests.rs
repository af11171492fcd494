use super::*;
use crate::model::catalogue::Output;
use std::path::Path;

fn parse(text: &str) -> Result<Scene, SceneError> {
    Scene::parse(text, Path::new("lectures/x.toml"))
}

const MINIMAL: &str = r#"id = "cube"
title = "Cube"
notes = { lecture = "3/4", section = "1.5.1", equations = ["31"] }
symbols = { m = "mass", a = "side" }

[[body]]
kind = "box"
size = ["a", "a", "a"]
mass = "m"

[outputs]
want = ["inertia_tensor"]

[numeric]
values = { m = 1.0, a = 2.0 }
"#;

#[test]
fn a_minimal_scene_parses() {
    let s = parse(MINIMAL).unwrap();
    assert_eq!(s.id, "cube");
    assert_eq!(s.bodies.len(), 1);
    assert!(matches!(
        s.bodies[0].shape,
        Shape::Box { centred: false, .. }
    ));
    assert_eq!(s.wants, vec![Output::InertiaTensor]);
    assert_eq!(s.values["a"], 2.0);
}

#[test]
fn unknown_keys_point_at_their_line() {
    let text = MINIMAL.replace("mass = \"m\"", "mass = \"m\"\ncolour = \"red\"");
    let e = parse(&text).unwrap_err();
    assert_eq!((e.line, e.column), (10, 1), "{e}");
    assert!(e.message.contains("unknown field `colour`"), "{e}");
}

#[test]
fn undefined_symbols_point_at_their_column() {
    let text = MINIMAL.replace(
        "size = [\"a\", \"a\", \"a\"]",
        "size = [\"a\", \"a\", \"b\"]",
    );
    let e = parse(&text).unwrap_err();
    assert_eq!((e.line, e.column), (8, 20), "{e}");
    assert_eq!(e.field, "body[0].size[2]");
    assert!(e.message.contains("undefined symbol `b`"));
}

#[test]
fn malformed_expressions_point_inside_the_string() {
    let text = MINIMAL.replace("mass = \"m\"", "mass = \"2*(m\"");
    let e = parse(&text).unwrap_err();
    assert_eq!((e.line, e.column), (9, 13), "{e}");
    assert!(e.message.contains("malformed expression"));
}

#[test]
fn sizes_and_masses_must_be_positive_and_finite() {
    for (from, to) in [
        ("a = 2.0", "a = -2.0"),
        ("a = 2.0", "a = 0.0"),
        ("a = 2.0", "a = nan"),
        ("a = 2.0", "a = inf"),
    ] {
        let e = parse(&MINIMAL.replace(from, to)).unwrap_err();
        assert!(
            e.message.contains("positive and finite") || e.message.contains("finite number"),
            "{to}: {e}"
        );
    }
    let e = parse(&MINIMAL.replace("mass = \"m\"", "mass = \"-1\"")).unwrap_err();
    assert_eq!(e.field, "body[0].mass");
}

#[test]
fn a_body_integrates_over_names_of_its_own() {
    // The scene's `x` is its own; the box integrates over `x_1` (`x_2` if `x_1` is taken too).
    let text = MINIMAL.replace("a = \"side\" }", "a = \"side\", x = \"a length\" }");
    let s = parse(&text).unwrap();
    assert_eq!(s.bodies[0].variables, ["x_1", "y", "z"]);
    let text = MINIMAL.replace(
        "a = \"side\" }",
        "a = \"side\", x = \"a length\", x_1 = \"another\" }",
    );
    let s = parse(&text).unwrap();
    assert_eq!(s.bodies[0].variables, ["x_2", "y", "z"]);
    assert_eq!(parse(MINIMAL).unwrap().bodies[0].variables, ["x", "y", "z"]);
}

/// A definition is held to the engine's budget, not to the bodies' degree 6: the gyroscope's
/// M g d/((M R²/2) w) (degree 7 as the validator counts) loads.
#[test]
fn a_definition_of_degree_seven_loads() {
    let text = MINIMAL.replace(
        "a = \"side\" }",
        "a = \"side\", g = \"gravity\", d = \"arm\", R = \"radius\", w = \"spin\" }\n[definitions]\nOmega = \"m*g*d/((m*R^2/2)*w)\"",
    );
    let s = parse(&text).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.definitions.contains_key("Omega"));
    let too_much = MINIMAL.replace(
        "a = \"side\" }",
        "a = \"side\" }\n[definitions]\nhuge = \"(a + m)^40\"",
    );
    let e = parse(&too_much).unwrap_err();
    assert!(e.message.contains("beyond the engine's budget"), "{e}");
}

/// A definition's table sets how its name is typeset; a `tex` that cannot be set is refused at
/// its line, as a symbol's is.
#[test]
fn a_definition_may_say_how_its_name_is_typeset() {
    let with = |def: &str| {
        MINIMAL.replace(
            "a = \"side\" }",
            &format!("a = \"side\", t = \"time\" }}\n[definitions]\n{def}"),
        )
    };
    let s = parse(&with(r#"w1s = { be = "a*cos(t)", tex = "\\omega_1" }"#)).unwrap();
    assert!(s.definitions.contains_key("w1s"));
    assert_eq!(s.tex.get("w1s").map(String::as_str), Some("\\omega_1"));
    let plain = parse(&with(r#"w1s = "a*cos(t)""#)).unwrap();
    assert!(!plain.tex.contains_key("w1s"));
    let e = parse(&with(r#"w1s = { be = "a*cos(t)", tex = "\\frac{1" }"#)).unwrap_err();
    assert!(e.message.contains("cannot be typeset"), "{e}");
    let e = parse(&with(r#"w1s = { tex = "\\omega_1" }"#)).unwrap_err();
    assert!(e.message.contains("be"), "{e}");
}
