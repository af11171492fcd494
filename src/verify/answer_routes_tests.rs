//! Expression answers: every variant of the course's problems agrees with its routes, and a
//! derivation made wrong in one step fails on every variant, by the step's own route.

use super::variants::check_variants;
use crate::cas::parse;
use crate::derive::step_names::StepResult;
use crate::pipeline::{SceneReport, run_scene};
use crate::scene::Scene;
use std::path::Path;

fn report(file: &str) -> SceneReport {
    let path = Path::new("tests/course/problems").join(file);
    let scene = Scene::from_file(&path).unwrap_or_else(|e| panic!("{e}"));
    run_scene(scene, None).unwrap_or_else(|e| panic!("{e}"))
}

/// The report's variants, each asserted to pass.
fn passing_variants(r: &SceneReport) -> &[crate::verify::variants::VariantCheck] {
    for v in &r.verification.variants {
        assert!(v.passed(), "variant {}: {:?}", v.number, v.answers);
    }
    &r.verification.variants
}

/// Asserts that every variant fails once step `name`'s result is replaced by `wrong`.
fn fails_with_wrong_step(r: &SceneReport, name: &str, wrong: StepResult) {
    let passed = with_wrong_step(r, name, wrong);
    assert!(passed.iter().all(|p| !p), "{passed:?}");
}

/// The report's variants, checked again with step `name`'s result replaced by `wrong`.
fn with_wrong_step(r: &SceneReport, name: &str, wrong: StepResult) -> Vec<bool> {
    let mut d = r.derivation.clone();
    assert!(d.named.contains_key(name), "no step {name}");
    d.named.insert(name.into(), wrong);
    let problem = r.scene.problem.as_ref().unwrap();
    check_variants(
        &r.scene,
        &d,
        problem,
        &crate::numeric::budget::Deadline::checks(),
    )
    .unwrap()
    .iter()
    .map(|v| v.passed())
    .collect()
}

fn expr(text: &str) -> StepResult {
    StepResult::Expr(parse(text).unwrap().expr)
}

#[test]
fn a_period_is_checked_on_the_integrated_motion_and_a_wrong_frequency_fails() {
    let r = report("01-pendulum-period.toml");
    let variants = &r.verification.variants;
    assert_eq!(variants.len(), 6);
    for v in variants {
        let period = &v.answers[1];
        assert!(period.passed(), "variant {}: {period:?}", v.number);
        // The measured period of a swing 0.01 rad wide is longer than 2π/Ω by a²/16 (the
        // pendulum's first anharmonic term): the route is independent, and that close.
        let expected = 1e-4 / 16.0;
        assert!(
            (period.error - expected).abs() < 0.05 * expected,
            "variant {}: {} vs a²/16 = {expected}",
            v.number,
            period.error
        );
        // The tolerance is Ω's measured one carried through 2π/Ω, and no looser.
        assert!(period.tolerance < 1.01e-3, "{}", period.tolerance);
    }
    // A simple pendulum's frequency put in place of the rod's: every period is wrong by
    // √(3/2) and fails.
    fails_with_wrong_step(&r, "Omega", expr("sqrt(g/L)"));
}

#[test]
fn a_solved_acceleration_is_put_back_by_newton_and_a_wrong_one_fails() {
    let r = report("03-rolling-acceleration.toml");
    for v in passing_variants(&r) {
        assert!(v.answers[0].error < 1e-12, "{}", v.answers[0].error);
    }
    // Sliding without rolling: g sin(alpha) is not a root of the rolling equation.
    fails_with_wrong_step(&r, "acc", expr("g*sin(alpha)"));
}

#[test]
fn a_critical_spin_is_found_again_from_ten_percent_off() {
    let r = report("04-critical-spin.toml");
    for v in passing_variants(&r) {
        let values: std::collections::BTreeMap<&str, f64> = v
            .values
            .iter()
            .map(|(k, e)| (k.as_str(), e.eval(&|_| None).unwrap()))
            .collect();
        // The textbook's sleeping-top condition I3 w3 = 2 sqrt(I1 M g l), in floats.
        let want =
            2.0 * (values["I1"] * values["M"] * values["g"] * values["l"]).sqrt() / values["I3"];
        let got = v.answers[0].exact_numbers[0];
        assert!((got - want).abs() < 1e-13 * want, "{got} vs {want}");
    }
    // Half the critical spin is no root: Newton, started 10% off it, finds the true one. (The
    // spin is positive, so `solve` gives its positive root alone.)
    let StepResult::Expr(root) = &r.derivation.named["spin"] else {
        panic!("one root expected");
    };
    let halved = crate::cas::Expr::mul(vec![crate::cas::Expr::rat(1, 2), root.clone()]);
    fails_with_wrong_step(&r, "spin", StepResult::Expr(halved));
}

#[test]
fn a_centre_of_mass_asked_in_centimetres_is_a_hundred_times_the_metres() {
    let r = report("05-centre-of-mass.toml");
    for v in passing_variants(&r) {
        let x = |k: &str| {
            v.values
                .iter()
                .find(|(n, _)| n == k)
                .unwrap()
                .1
                .eval(&|_| None)
                .unwrap()
        };
        // The cylinder's centre at H/2, the cone's at H + h/4 above the bottom (in m).
        let z = (x("m") * x("H") / 2.0 + x("k") * (x("H") + x("h") / 4.0)) / (x("m") + x("k"));
        let got = v.answers[0].exact_numbers[0];
        assert!(
            (got - 100.0 * z).abs() < 1e-12 * got,
            "{got} vs {}",
            100.0 * z
        );
    }
}

#[test]
fn an_angle_between_vectors_is_worked_from_the_quadrature_tensor() {
    let r = report("02-angle-l-omega.toml");
    for v in passing_variants(&r) {
        let angle = &v.answers[1];
        assert!(angle.error < 1e-13, "{}", angle.error);
        assert!(angle.exact_numbers[0] > 0.0 && angle.exact_numbers[0] < 1.6);
    }
}

#[test]
fn each_normal_mode_is_graded_by_the_eigenvalues_of_m_inverse_k_and_a_wrong_one_fails() {
    let r = report("06-normal-modes.toml");
    let variants = passing_variants(&r);
    assert_eq!(variants.len(), 4);
    for v in variants {
        // √((2 ∓ √2) g/l), by the textbook, at the variant's l: both routes land on it.
        let l = v
            .values
            .iter()
            .find(|(n, _)| n == "l")
            .unwrap()
            .1
            .eval(&|_| None)
            .unwrap();
        for (a, sign) in v.answers.iter().zip([-1.0, 1.0]) {
            let textbook = ((2.0 + sign * 2f64.sqrt()) * 9.81 / l).sqrt();
            assert!((a.numeric[0] / textbook - 1.0).abs() < 1e-12, "{a:?}");
            assert!((a.exact_numbers[0] / textbook - 1.0).abs() < 1e-15, "{a:?}");
        }
    }
    // Two independent pendulums' frequencies, √(g/l) and √(3g/l), in place of the coupled ones.
    let wrong = StepResult::Modes(vec![
        parse("sqrt(g/l)").unwrap().expr,
        parse("sqrt(3*g/l)").unwrap().expr,
    ]);
    fails_with_wrong_step(&r, "Omega", wrong);
}
