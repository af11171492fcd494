//! Constraints with multipliers on a `lagrange` step: the Atwood machine's tension and the
//! ladder's wall force come out as multipliers, each against the textbook and an independent
//! integration; a wrong constrained equation, a start off the constraint and a constraint in
//! the wrong form are each refused. Routh's procedure on the spherical pendulum, against the
//! textbook's Routhian and the full motion; a wrong Routhian and a coordinate that is not
//! cyclic fail.

use crate::cas::Expr;
use crate::derive::step_names::StepResult;
use crate::pipeline::{SceneReport, run_scene};
use crate::scene::operations::{Lagrange, Routh};
use crate::scene::{Operation, Scene, Verdict};
use crate::steps::check::StepCheck;
use crate::steps::motion::energy_check;
use std::path::Path;

fn course(file: &str) -> String {
    std::fs::read_to_string(format!("tests/course/dynamics/{file}")).unwrap()
}

fn run(text: &str) -> SceneReport {
    run_scene(Scene::parse(text, Path::new("p.toml")).unwrap(), None).unwrap()
}

/// Every step passes its numeric route and every claim (and `gives`) of the notes agrees; a
/// common mistake the scene sets beside them disagrees.
fn all_pass_and_agree(r: &SceneReport) {
    r.assert_steps_pass();
    assert!(
        r.verification.claims.iter().all(|c| c.verdict
            == match c.role {
                crate::scene::ClaimRole::Notes => Verdict::Agrees,
                crate::scene::ClaimRole::Mistake => Verdict::Disagrees,
            }),
        "{:?}",
        r.verification.claims
    );
}

/// Why a step's numeric check could not run, or "".
fn problem_of(r: &SceneReport, step: &str) -> String {
    r.verification
        .steps
        .iter()
        .find(|c| c.step == step)
        .and_then(|c| c.problem.clone())
        .unwrap_or_default()
}

/// The Atwood machine: the tension T, the multiplier of x1 + x2 = l, is 2 m1 m2 g/(m1 + m2),
/// here 13.08 N at m1 = 2, m2 = 1; every step passes its numeric route (the constrained motion
/// integrated, its energy and the string's length watched). The same equations with the
/// tension left out of one mass's equation keep the string's length but not the energy, and
/// fail; a start with a slack string is refused, naming the multiplier.
#[test]
fn the_atwood_machines_tension_is_its_multiplier() {
    let text = course("13-atwood.toml");
    let r = run(&text);
    all_pass_and_agree(&r);
    let tension = r.value_at("acc_3", &[]);
    assert!(
        (tension - 2.0 * 2.0 * 1.0 * 9.81 / 3.0).abs() < 1e-12,
        "{tension}"
    );

    let step = r.scene.steps.iter().find(|s| s.name == "eom").unwrap();
    let Operation::Lagrange(Lagrange { constraints, .. }) = &step.op else {
        panic!("{:?}", step.op)
    };
    let lagrangian = r.derivation.named["Lag"].scalar().unwrap();
    let StepResult::Equations(eqs) = &r.derivation.named["eom"] else {
        panic!()
    };
    let mut check = StepCheck::not_yet_run("eom", 1);
    energy_check(&r.scene, step, lagrangian, eqs, constraints, &mut check).unwrap();
    assert!(check.passed() && check.error < 1e-9, "{check:?}");
    let wrong: Vec<(String, Expr)> = eqs
        .iter()
        .map(|(q, e)| {
            let e = match q.as_str() {
                "x1" => e.substitute(&|s| (s == "T").then(|| Expr::int(0))),
                _ => e.clone(),
            };
            (q.clone(), e)
        })
        .collect();
    let mut check = StepCheck::not_yet_run("eom", 1);
    energy_check(&r.scene, step, lagrangian, &wrong, constraints, &mut check).unwrap();
    assert!(!check.passed() && check.error > 1e-2, "{check:?}");

    let slack = text.replace(
        "start = { x1 = 0.4, x2 = 0.6 }",
        "start = { x1 = 0.4, x2 = 0.5 }",
    );
    let r = run(&slack);
    let problem = problem_of(&r, "eom");
    assert!(
        problem.contains("off the constraint of `T`") && problem.contains("its value is"),
        "{problem}"
    );
}

/// The ladder: the wall's force N1 along a fall from rest at θ₀ is the notes' (3/4) m g sin θ
/// (3 cos θ − 2 cos θ₀), zero at θ = arccos((2/3) cos θ₀). Independently, the textbook's
/// θ'' = (3g/2l) sin θ integrated from θ₀ = 0.3 at rest (Dormand–Prince), with the derived N1
/// (before the energy is put in: a function of θ and θ') read along it, changes sign where
/// the derived angle says, to 1e-8.
#[test]
fn the_ladder_leaves_the_wall_where_its_multiplier_vanishes() {
    let r = run(&course("14-ladder.toml"));
    all_pass_and_agree(&r);
    let leaves = r.value_at("leave_3", &[]);
    let (g, l, theta0) = (9.81, 1.0, 0.3f64);
    assert!((leaves - (2.0 * theta0.cos() / 3.0).acos()).abs() < 1e-14);
    let rhs = |_t: f64, y: &[f64]| -> Result<Vec<f64>, String> {
        Ok(vec![y[1], 1.5 * g / l * y[0].sin()])
    };
    let run =
        crate::numeric::ode::dormand_prince(&rhs, &[theta0, 0.0], 2.0, 1e-12, 100_000).unwrap();
    let wall = |y: &[f64]| r.value_at("acc_4", &[("theta", y[0]), ("theta'", y[1])]);
    let (t_a, a, t_b) = run
        .states
        .windows(2)
        .find(|w| wall(&w[0].1) > 0.0 && wall(&w[1].1) <= 0.0)
        .map(|w| (w[0].0, w[0].1.clone(), w[1].0))
        .expect("the wall's force changes sign along the fall");
    // Between the two accepted steps, the time where N1 = 0 by bisection, each trial state
    // integrated afresh from the earlier step.
    let state_after = |dt: f64| {
        crate::numeric::ode::dormand_prince(&rhs, &a, dt, 1e-13, 100_000)
            .unwrap()
            .states
            .last()
            .unwrap()
            .1
            .clone()
    };
    let (mut lo, mut hi) = (0.0, t_b - t_a);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if wall(&state_after(mid)) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let theta = state_after(0.5 * (lo + hi))[0];
    assert!((theta - leaves).abs() < 1e-8, "{theta} {leaves}");
}

/// A multiplier that is not a declared symbol, a constraint on accelerations, and
/// `constraints` on a step that is not `lagrange` are refused at their lines, each saying what
/// to write instead; a velocity constraint not linear in the rates, and `linearise` of the
/// equations with a multiplier, are refused when derived.
#[test]
fn constraints_in_the_wrong_form_are_refused() {
    let text = course("13-atwood.toml");
    let undeclared = text.replace("constraints = { T = ", "constraints = { F = ");
    let e = Scene::parse(&undeclared, Path::new("p.toml")).unwrap_err();
    assert!(
        e.message.contains("the multiplier `F` is not a symbol"),
        "{e}"
    );
    let accelerating = text.replace("\"l - x1 - x2\"", "\"x1'' - x2''\"");
    let e = Scene::parse(&accelerating, Path::new("p.toml")).unwrap_err();
    assert!(e.message.contains("is an acceleration"), "{e}");
    let quadratic = text.replace("\"l - x1 - x2\"", "\"x1'^2 - x2'\"");
    let message = run_scene(Scene::parse(&quadratic, Path::new("p.toml")).unwrap(), None)
        .err()
        .unwrap()
        .to_string();
    assert!(message.contains("must be linear in the rates"), "{message}");
    let stray = text.replace(
        "why = \"the accelerations and the tension together\"",
        "why = \"x\"\nconstraints = { T = \"x1\" }",
    );
    let e = Scene::parse(&stray, Path::new("p.toml")).unwrap_err();
    assert!(e.field.contains("constraints"), "{e}");
    let linear = format!(
        "{text}\n[[step]]\nname = \"lin\"\nlinearise = \"eom\"\nabout = {{ x1 = \"0\" }}\nwhy = \"x\"\n"
    );
    let message = run_scene(Scene::parse(&linear, Path::new("p.toml")).unwrap(), None)
        .err()
        .unwrap()
        .to_string();
    assert!(message.contains("carry the multiplier `T`"), "{message}");
}

/// The spherical pendulum: `routh` gives R = m l² θ'²/2 + m g l cos θ − p²/(2 m l² sin²θ), the
/// textbook's (its `gives` agrees), and its check along the full motion passes (R against
/// L − p φ' with p by differences of L, p's drift); the equation of θ from R alone keeps its
/// energy. The Routhian with the centrifugal term's sign flipped fails the same check by order
/// one; `routh` on θ, which is not cyclic, is refused.
#[test]
fn the_spherical_pendulums_routhian() {
    let text = course("15-spherical-pendulum.toml");
    let r = run(&text);
    r.assert_steps_pass();
    let gives: Vec<Verdict> = r.verification.claims.iter().map(|c| c.verdict).collect();
    assert_eq!(gives, vec![Verdict::Agrees]);
    let step = r.scene.steps.iter().find(|s| s.name == "R").unwrap();
    let Operation::Routh(Routh { cyclic, .. }) = &step.op else {
        panic!("{:?}", step.op)
    };
    let lagrangian = r.derivation.named["Lag"].scalar().unwrap();
    let routhian = r.derivation.named["R"].scalar().unwrap();
    let mut check = StepCheck::not_yet_run("eom", 1);
    crate::steps::routh::routh_check(&r.scene, step, lagrangian, routhian, cyclic, &mut check)
        .unwrap();
    assert!(check.passed() && check.error < 1e-8, "{check:?}");
    let wrong =
        crate::cas::parse("m*l^2*theta'^2/2 + m*g*l*cos(theta) + p^2/(2*m*l^2*sin(theta)^2)")
            .unwrap()
            .expr;
    let mut check = StepCheck::not_yet_run("eom", 1);
    crate::steps::routh::routh_check(&r.scene, step, lagrangian, &wrong, cyclic, &mut check)
        .unwrap();
    assert!(!check.passed() && check.error > 1e-2, "{check:?}");
    let not_cyclic = text.replace("cyclic = { phi = \"p\" }", "cyclic = { theta = \"p\" }");
    let message = run_scene(
        Scene::parse(&not_cyclic, Path::new("p.toml")).unwrap(),
        None,
    )
    .err()
    .unwrap()
    .to_string();
    assert!(message.contains("`theta` is not cyclic"), "{message}");
}

/// The knife edge on a plane, a velocity constraint that does not integrate: the sideways
/// velocity y' cos φ − x' sin φ is 0. The multiplier F, the blade's sideways force, is
/// m φ' (x' cos φ + y' sin φ), the textbook's m v ω; the motion from the derived accelerations,
/// integrated from x' = v, φ' = ω, runs on the circle of radius v/ω, x = (v/ω) sin ωt,
/// y = (v/ω)(1 − cos ωt), to 1e-9; and a start that slides sideways is refused.
#[test]
fn the_knife_edges_sideways_force_is_its_multiplier() {
    let text = include_str!("../../tests/fixtures/unit/knife-edge.toml");
    let r = run(text);
    r.assert_steps_pass();
    assert_eq!(r.verification.claims[0].verdict, Verdict::Agrees);
    let (v, omega) = (1.5, 0.8);
    let names = ["x", "y", "phi", "x'", "y'", "phi'"];
    let rhs = |_t: f64, s: &[f64]| -> Result<Vec<f64>, String> {
        let at: Vec<(&str, f64)> = names.iter().copied().zip(s.iter().copied()).collect();
        let a: Vec<f64> = ["acc_1", "acc_2", "acc_3"]
            .iter()
            .map(|k| r.value_at(k, &at))
            .collect();
        Ok(vec![s[3], s[4], s[5], a[0], a[1], a[2]])
    };
    let t = 2.0;
    let run = crate::numeric::ode::dormand_prince(
        &rhs,
        &[0.0, 0.0, 0.0, v, 0.0, omega],
        t,
        1e-12,
        100_000,
    )
    .unwrap();
    let end = &run.states.last().unwrap().1;
    let radius = v / omega;
    assert!(
        (end[0] - radius * (omega * t).sin()).abs() < 1e-9,
        "{end:?}"
    );
    assert!(
        (end[1] - radius * (1.0 - (omega * t).cos())).abs() < 1e-9,
        "{end:?}"
    );
    let sliding = text.replace("\"x'\" = 1.5,", "\"x'\" = 1.5, \"y'\" = 0.1,");
    let r = self::run(&sliding);
    let problem = problem_of(&r, "eom");
    assert!(problem.contains("off the constraint of `F`"), "{problem}");
}
