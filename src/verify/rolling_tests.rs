//! The rolling disk of tests/course (two velocity constraints that do not integrate, their
//! multipliers the friction) against SymPy's rolling-disc example: the accelerations at eight
//! seeded random states, from SymPy's Kane's method, stored in tests/fixtures by
//! tests/sympy/rolling_disc.py. The same file holds SymPy's Lagrange's-method example, whose
//! Lagrangian has the rolling constraint substituted in; its yaw and spin accelerations are
//! not the disk's, which is why mechbook refuses that substitution.

use crate::pipeline::{SceneReport, run_scene};
use crate::scene::Scene;
use std::path::Path;

const SCENE: &str = "tests/course/dynamics/16-rolling-disk.toml";

fn run(text: &str) -> SceneReport {
    run_scene(Scene::parse(text, Path::new(SCENE)).unwrap(), None).unwrap()
}

/// mechbook's q1'', q2'', q3'' (the solve step's 3rd to 5th unknowns) at a SymPy state
/// (q1, q2, q3, q1', q2', q3'), the contact point at the origin moving with the rim.
fn accelerations(r: &SceneReport, s: &[f64]) -> Vec<f64> {
    let radius = r.scene.values["r"];
    let at = [
        ("x", 0.0),
        ("y", 0.0),
        ("q1", s[0]),
        ("q2", s[1]),
        ("q3", s[2]),
        ("x'", radius * s[5] * s[0].cos()),
        ("y'", radius * s[5] * s[0].sin()),
        ("q1'", s[3]),
        ("q2'", s[4]),
        ("q3'", s[5]),
    ];
    ["acc_3", "acc_4", "acc_5"]
        .iter()
        .map(|k| r.value_at(k, &at))
        .collect()
}

/// The largest relative difference of mechbook's accelerations from one of the fixture's
/// routes, over its states.
fn largest_difference(r: &SceneReport, route: &str) -> f64 {
    let fixture: serde_json::Value =
        serde_json::from_str(include_str!("../../tests/fixtures/rolling_disc_sympy.json")).unwrap();
    let mut worst: f64 = 0.0;
    for state in fixture["states"].as_array().unwrap() {
        let q: Vec<f64> = state["q"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let theirs: Vec<f64> = state[route]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        for (a, b) in accelerations(r, &q).iter().zip(&theirs) {
            worst = worst.max((a - b).abs() / b.abs().max(1.0));
        }
    }
    worst
}

/// The disk's yaw, lean and spin accelerations agree with SymPy's Kane's method at all eight
/// states to 1e-12 (relative), and every step passes its numeric route (the constrained
/// motion integrated, energy and both constraints watched). SymPy's Lagrangian with the
/// constraint substituted differs by more than 0.1; and a disk with a wrong moment about its
/// axis (m r²/3 for m r²/2) differs from Kane's by more than 1e-2.
#[test]
fn the_rolling_disk_agrees_with_sympys_kane_method() {
    let text = std::fs::read_to_string(SCENE).unwrap();
    let r = run(&text);
    r.assert_steps_pass();
    let kane = largest_difference(&r, "kane");
    assert!(kane < 1e-12, "{kane:e}");
    let substituted = largest_difference(&r, "lagrange_substituted");
    assert!(substituted > 0.1, "{substituted:e}");

    let wrong = text.replace(
        "m*r^2*(q3' + q1'*sin(q2))^2/4",
        "m*r^2*(q3' + q1'*sin(q2))^2/6",
    );
    assert_ne!(wrong, text);
    let off = largest_difference(&run(&wrong), "kane");
    assert!(off > 1e-2, "{off:e}");
}

/// The rolling constraints substituted into the disk's L before `lagrange` (what SymPy's
/// Lagrange's-method example does) are refused on the `lagrange` step, naming the substitute
/// step, its line and the constraint's right form; a wheel's θ' = x'/R, which integrates,
/// substituted the same way, is not.
#[test]
fn a_substituted_rolling_constraint_is_refused_and_an_integrable_one_is_not() {
    let text = std::fs::read_to_string(SCENE).unwrap();
    let at = text.find("[[step]]\nname = \"eom\"").unwrap();
    let substituted = format!(
        "{}{}",
        &text[..at],
        r#"[[step]]
name = "Lrolled"
substitute = "Lag"
set = { "x'" = "r*q3'*cos(q1)", "y'" = "r*q3'*sin(q1)" }
why = "rolling put in"

[[step]]
name = "eom"
lagrange = "Lrolled"
why = "the substituted Lagrangian"
"#
    );
    let err = run_scene(Scene::parse(&substituted, Path::new(SCENE)).unwrap(), None)
        .map(|_| ())
        .expect_err("refused")
        .to_string();
    let line = substituted[..substituted.find("name = \"Lrolled\"").unwrap()]
        .lines()
        .count();
    assert!(err.contains("step `Lrolled` (line"), "{err}");
    assert!(err.contains(&format!("(line {line})")), "{err}");
    crate::base::assert_says(
        &err,
        &["does not integrate", "constraints = { lam = \"x' - "],
    );

    let wheel = include_str!("../../tests/fixtures/unit/rolling-wheel.toml");
    let r = run(wheel);
    r.assert_steps_pass();
}
