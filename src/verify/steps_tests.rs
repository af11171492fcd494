//! The author's steps: each `gives` in an equivalent form agrees and in a wrong one disagrees at
//! its own line; each numeric route passes a right result and fails a wrong one.

use super::steps::*;
use crate::cas::parse;
use crate::pipeline::{SceneReport, run_scene};
use crate::scene::{Scene, Verdict};
use std::path::Path;

/// The physical pendulum of tests/course, with `gives` of the caller's choosing for the
/// moment (`ip`), the equation of motion (`eom`), the momentum (`p`) and the frequency (`w`).
fn pendulum(ip: &str, eom: &str, p: &str, w: &str) -> String {
    format!(
        r#"
id = "pendulum"
title = "The physical pendulum"
notes = {{ lecture = "6" }}
symbols = {{ M = "mass", L = "length", g = "gravity" }}
axis = ["0", "0", "1"]
[coordinates]
phi = "angle from the downward vertical"
[[body]]
kind = "rod"
length = "L"
mass = "M"
origin = "end"
along = "x"
[[step]]
name = "Ip"
be = "moment_about_axis"
gives = "{ip}"
[[step]]
name = "Lag"
be = "Ip*phi'^2/2 + M*g*(L/2)*cos(phi)"
[[step]]
name = "eom"
lagrange = "Lag"
gives = "{eom}"
[[step]]
name = "p_phi"
differentiate = "Lag"
by = "phi'"
gives = "{p}"
[[step]]
name = "small"
linearise = "eom"
about = {{ phi = "0" }}
[[step]]
name = "Omega"
frequency = "small"
gives = "{w}"
[outputs]
want = ["moment_about_axis"]
[numeric]
values = {{ M = 2.0, L = 1.5, g = 9.81 }}
"#
    )
}

fn run(text: &str) -> SceneReport {
    run_scene(Scene::parse(text, Path::new("p.toml")).unwrap(), None).unwrap()
}

/// The verdict of each step's `gives`, by step name, with its line.
fn verdicts(r: &SceneReport) -> Vec<(String, Verdict, usize)> {
    r.verification
        .claims
        .iter()
        .filter_map(|c| {
            let step = &r.scene.steps[c.step?];
            Some((step.name.clone(), c.verdict, c.line))
        })
        .collect()
}

#[test]
fn equivalent_forms_agree() {
    let r = run(&pendulum(
        "(M*L^2/12 + M*(L/2)^2)",
        "2*Ip*phi'' + M*g*L*sin(phi) = 0",
        "M*L^2*phi'/3",
        "sqrt(3*g/(2*L))",
    ));
    for (name, verdict, _) in verdicts(&r) {
        assert_eq!(
            verdict,
            Verdict::Agrees,
            "{name}: {:?}",
            r.verification.claims
        );
    }
    // The same again, in the notes' other forms: a factor moved, the equation as rhs = lhs.
    let r = run(&pendulum(
        "M*(L^2/12 + L^2/4)",
        "-M*g*L/2*sin(phi) = Ip*phi''",
        "Ip*phi'",
        "(3*g/(2*L))^(1/2)",
    ));
    for (name, verdict, _) in verdicts(&r) {
        assert_eq!(verdict, Verdict::Agrees, "{name}");
    }
}

#[test]
fn wrong_forms_disagree_at_their_own_lines() {
    let r = run(&pendulum(
        "M*L^2/12",
        "Ip*phi'' + M*g*L/2*cos(phi) = 0",
        "Ip*phi'/2",
        "sqrt(g/L)",
    ));
    let found = verdicts(&r);
    assert_eq!(found.len(), 4);
    for (name, verdict, line) in &found {
        assert_eq!(*verdict, Verdict::Disagrees, "{name}");
        let step = r.scene.steps.iter().find(|s| &s.name == name).unwrap();
        assert_eq!(*line, step.line, "{name}");
    }
    // The linearised equation is not the full one, even though they agree at small angles.
    let r = run(&pendulum(
        "M*L^2/3",
        "Ip*phi'' + M*g*L/2*phi = 0",
        "Ip*phi'",
        "sqrt(3*g/(2*L))",
    ));
    let eom = verdicts(&r).into_iter().find(|v| v.0 == "eom").unwrap();
    assert_eq!(eom.1, Verdict::Disagrees);
}

/// Every step passes its numeric route, and the measured period's difference from 2π/Ω is the
/// pendulum's own anharmonic correction: T = T₀(1 + a²/16 + …) for an amplitude a (Landau &
/// Lifshitz, Mechanics §28), 6.25e-6 at a = 0.01.
#[test]
fn each_step_passes_its_numeric_route_and_the_period_shows_the_anharmonic_correction() {
    let r = run(&pendulum(
        "M*L^2/3",
        "Ip*phi'' + M*g*L/2*sin(phi) = 0",
        "Ip*phi'",
        "sqrt(3*g/(2*L))",
    ));
    assert_eq!(r.verification.steps.len(), 6);
    for c in &r.verification.steps {
        assert!(c.passed(), "{c:?}");
        assert!(c.evaluations > 0, "{c:?}");
    }
    let omega = r
        .verification
        .steps
        .iter()
        .find(|c| c.step == "Omega")
        .unwrap();
    let expected = 0.01f64.powi(2) / 16.0;
    assert!(
        (omega.error - expected).abs() < 0.05 * expected,
        "period error {} against a²/16 = {expected}",
        omega.error
    );
}

/// A wrong equation of motion does not keep the energy: the same check on the pendulum with
/// the gravity term's sign flipped drifts by order one; so does a wrong linearisation and a
/// wrong frequency.
#[test]
fn the_numeric_routes_fail_wrong_results() {
    let r = run(&pendulum(
        "M*L^2/3",
        "Ip*phi'' + M*g*L/2*sin(phi) = 0",
        "Ip*phi'",
        "sqrt(3*g/(2*L))",
    ));
    let scene = &r.scene;
    let lag = parse("M*L^2/6*phi'^2 + M*g*L/2*cos(phi)").unwrap().expr;
    let wrong = vec![(
        "phi".to_string(),
        parse("M*L^2/3*phi'' - M*g*L/2*sin(phi)").unwrap().expr,
    )];
    let step = scene.steps.iter().find(|s| s.name == "eom").unwrap();
    let mut check = blank();
    energy_check(scene, step, &lag, &wrong, &mut check).unwrap();
    assert!(check.error > 1e-2, "{check:?}");
    let right = vec![(
        "phi".to_string(),
        parse("M*L^2/3*phi'' + M*g*L/2*sin(phi)").unwrap().expr,
    )];
    let mut check = blank();
    energy_check(scene, step, &lag, &right, &mut check).unwrap();
    assert!(check.passed(), "{check:?}");

    let linear_wrong = vec![(
        "phi".to_string(),
        parse("M*L^2/3*phi'' + M*g*L*phi").unwrap().expr,
    )];
    let mut check = blank();
    linear_check(
        scene,
        &right,
        &linear_wrong,
        &Default::default(),
        7,
        &mut check,
    )
    .unwrap();
    assert!(!check.passed(), "{check:?}");

    let mut check = blank();
    let too_fast = parse("1.01*sqrt(3*g/(2*L))").unwrap().expr;
    period_check(scene, &right, &Default::default(), &too_fast, &mut check).unwrap();
    assert!(!check.passed() && check.error > 5e-3, "{check:?}");
}

fn blank() -> StepCheck {
    StepCheck {
        step: "s".into(),
        line: 1,
        method: String::new(),
        error: 0.0,
        tolerance: 0.0,
        evaluations: 0,
        problem: None,
    }
}
