//! The author's steps: each `gives` in an equivalent form agrees and in a wrong one disagrees at
//! its own line; each numeric route passes a right result and fails a wrong one.

use super::*;
use crate::cas::parse;
use crate::pipeline::{SceneReport, run_scene};
use crate::scene::operations::{Integrate, Series};
use crate::scene::{Scene, Verdict};
use crate::steps::motion::*;
use std::collections::BTreeMap;
use std::path::Path;

/// The physical pendulum of tests/course, with `gives` of the caller's choosing for the
/// moment (`ip`), the equation of motion (`eom`), the momentum (`p`) and the frequency (`w`).
fn pendulum(ip: &str, eom: &str, p: &str, w: &str) -> String {
    include_str!("../../tests/fixtures/unit/pendulum-steps.toml")
        .replace("{ip}", ip)
        .replace("{eom}", eom)
        .replace("{p}", p)
        .replace("{w}", w)
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

/// Asserts that step `name`'s `gives` disagrees, reported at the step's own line.
fn assert_disagrees_at_its_line(r: &SceneReport, name: &str) {
    let step_line = r.scene.steps.iter().find(|s| s.name == name).unwrap().line;
    let found = verdicts(r).into_iter().find(|v| v.0 == name);
    assert_eq!(
        found,
        Some((name.to_string(), Verdict::Disagrees, step_line))
    );
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

/// The steps share the scene's budget: past it, each remaining step is not checked, fails,
/// and says why at its own line.
#[test]
fn steps_past_the_scenes_budget_fail_at_their_lines() {
    let r = run(&pendulum(
        "M*L^2/3",
        "Ip*phi'' + M*g*L/2*sin(phi) = 0",
        "Ip*phi'",
        "sqrt(3*g/(2*L))",
    ));
    let spent = crate::numeric::budget::Deadline::after(std::time::Duration::ZERO);
    let checks = check_steps(&r.scene, &r.derivation, &spent);
    assert_eq!(checks.len(), 6);
    for (c, step) in checks.iter().zip(&r.scene.steps) {
        assert!(!c.passed(), "{c:?}");
        assert_eq!(c.line, step.line);
        let problem = c.problem.as_deref().unwrap();
        assert!(
            problem.contains("not checked") && problem.contains("past the 0 s"),
            "{problem}"
        );
    }
    let in_time = check_steps(
        &r.scene,
        &r.derivation,
        &crate::numeric::budget::Deadline::checks(),
    );
    assert!(in_time.iter().all(StepCheck::passed), "{in_time:?}");
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
    let mut check = StepCheck::not_yet_run("s", 1);
    energy_check(scene, step, &lag, &wrong, &[], &mut check).unwrap();
    assert!(check.error > 1e-2, "{check:?}");
    let right = vec![(
        "phi".to_string(),
        parse("M*L^2/3*phi'' + M*g*L/2*sin(phi)").unwrap().expr,
    )];
    let mut check = StepCheck::not_yet_run("s", 1);
    energy_check(scene, step, &lag, &right, &[], &mut check).unwrap();
    assert!(check.passed(), "{check:?}");

    let linear_wrong = vec![(
        "phi".to_string(),
        parse("M*L^2/3*phi'' + M*g*L*phi").unwrap().expr,
    )];
    let mut check = StepCheck::not_yet_run("s", 1);
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

    let mut check = StepCheck::not_yet_run("s", 1);
    let too_fast = parse("1.01*sqrt(3*g/(2*L))").unwrap().expr;
    period_check(scene, &right, &Default::default(), &too_fast, &mut check).unwrap();
    assert!(!check.passed() && check.error > 5e-3, "{check:?}");
}

/// The rolling cylinder of tests/course: the constraint substituted, the equation solved for
/// the acceleration. The notes' a = g sin α/(1 + I/(M R²)) agrees; a sliding block's g sin α
/// does not; each step passes its numeric route.
#[test]
fn a_constraint_substituted_and_an_equation_solved() {
    let scene = |gives: &str| {
        let text = std::fs::read_to_string("tests/course/dynamics/02-rolling-cylinder.toml")
            .unwrap()
            .replace(
                "gives = \"g*sin(alpha)/(1 + I/(M*R^2))\"",
                &format!("gives = \"{gives}\""),
            );
        run(&text)
    };
    let r = scene("g*sin(alpha)/(1 + I/(M*R^2))");
    let a = verdicts(&r).into_iter().find(|v| v.0 == "a").unwrap();
    assert_eq!(a.1, Verdict::Agrees);
    r.assert_steps_pass();
    // The independent route: a at the scene's values from the textbook formula for a solid
    // cylinder, (2/3) g sin α.
    let named = &r.derivation.named["a"];
    let crate::derive::step_names::StepResult::Expr(e) = named else {
        panic!("{named:?}")
    };
    let value = e.eval(&|s| r.scene.values.get(s).copied()).unwrap();
    assert!(
        (value - 2.0 / 3.0 * 9.81 * 0.5f64.sin()).abs() < 1e-12,
        "{value}"
    );
    let r = scene("g*sin(alpha)");
    let a = verdicts(&r).into_iter().find(|v| v.0 == "a").unwrap();
    assert_eq!(a.1, Verdict::Disagrees);
}

/// A scene of tests/course with one text replaced (the test fails if it is not there).
fn course_scene(file: &str, from: &str, to: &str) -> SceneReport {
    let text = std::fs::read_to_string(format!("tests/course/dynamics/{file}")).unwrap();
    assert!(text.contains(from), "{file} has no `{from}`");
    run(&text.replace(from, to))
}

/// The heavy top of tests/course: p_ψ, p_φ and E conserved along the integrated motion, p_θ
/// not; each against the textbook's formula at a state; a wrong `gives` disagrees at its line,
/// and the numeric route fails a momentum that is not conserved but said to be.
#[test]
fn heavy_top_momenta_and_energy() {
    let r = course_scene(
        "04-heavy-top.toml",
        "p_psi*cos(theta)\"",
        "p_psi*cos(theta)\"",
    );
    r.assert_steps_pass();
    let conserved = |name: &str| match &r.derivation.named[name] {
        crate::derive::step_names::StepResult::Conserved { conserved, .. } => *conserved,
        other => panic!("{other:?}"),
    };
    assert!(conserved("p_psi") && conserved("p_phi") && conserved("E"));
    assert!(!conserved("p_theta"));
    // Textbook forms at one state (Goldstein 5.7): p_φ = I1 φ' sin²θ + I3 (ψ' + φ' cos θ) cos θ.
    let state = [
        ("theta", 0.7),
        ("phi'", 1.3),
        ("psi'", 17.0),
        ("theta'", 0.4),
    ];
    let (i1, i3, mgl) = (0.02, 0.01, 9.81 * 0.1);
    let (th, dphi, dpsi, dth) = (0.7f64, 1.3, 17.0, 0.4);
    let spin = dpsi + dphi * th.cos();
    let p_phi = i1 * dphi * th.sin().powi(2) + i3 * spin * th.cos();
    let energy = i1 / 2.0 * (dth * dth + (dphi * th.sin()).powi(2))
        + i3 / 2.0 * spin * spin
        + mgl * th.cos();
    assert!((r.value_at("p_phi", &state) - p_phi).abs() < 1e-12 * p_phi.abs());
    assert!((r.value_at("E", &state) - energy).abs() < 1e-12 * energy.abs());
    assert!((r.value_at("p_psi", &state) - i3 * spin).abs() < 1e-12);
    // The sleeping top (Goldstein 5.7): upright is stable while I3² w3² > 4 I1 M g l, its
    // Ω² = (I3² w3² − 4 I1 M g l)/(4 I1²); the pair of tilted states is not real at w3 = 30.
    let crate::derive::step_names::StepResult::Stability { cases, .. } =
        &r.derivation.named["upright"]
    else {
        panic!()
    };
    let upright = &cases[0];
    assert_eq!(upright.at.value, crate::cas::Expr::int(0));
    assert_eq!(upright.verdict, crate::derive::step_names::Stable::Where);
    let w3 = 30.0;
    let textbook = ((i3 * w3).powi(2) - 4.0 * i1 * mgl) / (4.0 * i1 * i1);
    let exact = upright.omega_squared.as_ref().unwrap();
    let exact = exact.eval(&|s| r.scene.values.get(s).copied()).unwrap();
    assert!(
        (exact - textbook).abs() < 1e-12 * textbook,
        "{exact} {textbook}"
    );

    let r = course_scene(
        "04-heavy-top.toml",
        "gives = \"I1*phi'*sin(theta)^2 + p_psi*cos(theta)\"",
        "gives = \"I1*phi'*sin(theta)^2\"",
    );
    assert_disagrees_at_its_line(&r, "p_phi");

    // The tilt's momentum said to be conserved: it drifts by order one along the motion.
    let step = r.scene.steps.iter().find(|s| s.name == "p_theta").unwrap();
    let Some(crate::derive::step_names::StepResult::Expr(lag)) = r.derivation.named.get("Lag")
    else {
        panic!()
    };
    let value = r.derivation.named["p_theta"].scalar().unwrap();
    let mut check = StepCheck::not_yet_run("s", 1);
    conserved_check(
        &r.scene,
        step,
        lag,
        value,
        true,
        Conserved::Momentum("theta"),
        &mut check,
    )
    .unwrap();
    assert!(check.error > 1e-3, "{check:?}");
}

/// The pendulum on a free cart of tests/course: nothing pulls the cart back, so its slow mode
/// is zero, a result, which the eigenvalue route confirms on its companion's scale; the other is
/// the textbook's √((M + m)g/(Ml)). A mode said to be slow but not zero fails that route, and
/// the page names the zero mode.
#[test]
fn a_free_system_has_a_zero_mode() {
    let r = course_scene(
        "20-pendulum-on-cart.toml",
        "gives = [\"0\"",
        "gives = [\"0\"",
    );
    let omega = r
        .verification
        .steps
        .iter()
        .find(|c| c.step == "Omega")
        .unwrap();
    assert!(omega.passed() && omega.error < 1e-12, "{omega:?}");
    let crate::derive::step_names::StepResult::Modes(modes) = &r.derivation.named["Omega"] else {
        panic!("{:?}", r.derivation.named["Omega"])
    };
    assert!(modes[0].is_zero(), "{:?}", modes[0]);
    let v = |s: &str| r.scene.values[s];
    let textbook = ((v("M") + v("m")) * v("g") / (v("M") * v("l"))).sqrt();
    let fast = modes[1].eval(&|s| r.scene.values.get(s).copied()).unwrap();
    assert!(
        (fast - textbook).abs() < 1e-13 * textbook,
        "{fast} {textbook}"
    );
    assert!(
        r.verification
            .claims
            .iter()
            .all(|c| c.verdict == Verdict::Agrees),
        "{:?}",
        r.verification.claims
    );
    let Some(crate::derive::step_names::StepResult::Equations(linear)) =
        r.derivation.named.get("small")
    else {
        panic!()
    };
    for wrong in [
        vec![parse("1/1000").unwrap().expr, modes[1].clone()],
        vec![modes[1].clone(), modes[0].clone()],
    ] {
        let mut check = StepCheck::not_yet_run("s", 1);
        modes_check(&r.scene, linear, &wrong, &mut check).unwrap();
        assert!(check.error > 1e-4, "{wrong:?}: {check:?}");
    }
    let step = r.scene.steps.iter().find(|s| s.name == "Omega").unwrap();
    let titles: Vec<String> = super::page::page_steps(&r.scene, step, &r.derivation.named["Omega"])
        .into_iter()
        .map(|s| s.title.to_author_text(crate::notation::Names::none()))
        .collect();
    assert!(
        titles[0].ends_with("normal mode 1, a zero mode: a free motion, with no restoring force")
            && !titles[1].contains("zero mode"),
        "{titles:?}"
    );
}

/// The double pendulum of tests/course: its two modes are √((2 ∓ √2) g/l) (the textbook's,
/// computed here in floating point), the claims agree, and a wrong mode disagrees; the
/// eigenvalue route fails modes that are swapped.
#[test]
fn double_pendulum_modes() {
    let r = course_scene("03-double-pendulum.toml", "(2 + sqrt(2))", "(2 + sqrt(2))");
    r.assert_steps_pass();
    let crate::derive::step_names::StepResult::Modes(modes) = &r.derivation.named["Omega"] else {
        panic!("{:?}", r.derivation.named["Omega"])
    };
    let (g, l) = (9.81f64, 1.0);
    for (mode, sign) in modes.iter().zip([-1.0, 1.0]) {
        let x = mode.eval(&|s| r.scene.values.get(s).copied()).unwrap();
        let textbook = ((2.0 + sign * 2f64.sqrt()) * g / l).sqrt();
        assert!((x - textbook).abs() < 1e-13 * textbook, "{x} {textbook}");
    }
    assert!(
        r.verification
            .claims
            .iter()
            .all(|c| c.verdict == Verdict::Agrees)
    );
    let wrong = course_scene("03-double-pendulum.toml", "(2 + sqrt(2))", "(2 + sqrt(3))");
    let verdicts: Vec<Verdict> = wrong
        .verification
        .claims
        .iter()
        .map(|c| c.verdict)
        .collect();
    assert!(verdicts.contains(&Verdict::Disagrees), "{verdicts:?}");
    let Some(crate::derive::step_names::StepResult::Equations(linear)) =
        r.derivation.named.get("small")
    else {
        panic!()
    };
    let swapped = vec![modes[1].clone(), modes[0].clone()];
    let mut check = StepCheck::not_yet_run("s", 1);
    modes_check(&r.scene, linear, &swapped, &mut check).unwrap();
    assert!(check.error > 0.1, "{check:?}");
}

/// The bead on a rotating hoop of tests/course: θ = 0, π, ±acos(g/(R w²)); θ = π never
/// stable, the others where Ω² > 0, with Ω² the textbook's g/R − w² and w² − g²/(R² w²). Below
/// the critical speed the scan finds two zeros, as the exact equilibria real there; an exact
/// set missing one fails.
#[test]
fn bead_on_hoop_equilibria_and_stability() {
    use crate::derive::step_names::{Stable, StepResult};
    let r = course_scene("05-bead-on-hoop.toml", "w = 6.0", "w = 6.0");
    r.assert_steps_pass();
    let StepResult::Stability { cases, .. } = &r.derivation.named["stable"] else {
        panic!()
    };
    // Each state and its Ω² under a name of its own, against floats computed here.
    let (g, rr, w) = (9.81f64, 0.5f64, 6.0f64);
    let named: BTreeMap<String, f64> = ["rest", "stable"]
        .iter()
        .flat_map(|s| r.derivation.named[*s].values(r.scene.result_names(s)))
        .map(|(n, e)| (n, e.eval(&|s| r.scene.values.get(s).copied()).unwrap()))
        .collect();
    let c = g / (rr * w * w);
    let want = [
        ("rest_1", 0.0),
        ("rest_2", std::f64::consts::PI),
        ("rest_3", c.acos()),
        ("rest_4", -c.acos()),
        ("stable_1", g / rr - w * w),
        ("stable_2", -g / rr - w * w),
        ("stable_3", w * w * (1.0 - c * c)),
    ];
    for (name, value) in want {
        assert!(
            (named[name] - value).abs() < 1e-12 * value.abs().max(1.0),
            "{name}"
        );
    }
    for claim in r.verification.claims.iter().filter(|c| c.step.is_none()) {
        assert_eq!(claim.verdict, Verdict::Agrees, "{claim:?}");
    }
    let verdicts: Vec<Stable> = cases.iter().map(|c| c.verdict).collect();
    assert_eq!(
        verdicts,
        [Stable::Where, Stable::Never, Stable::Where, Stable::Where]
    );
    let (g, radius, w) = (9.81f64, 0.5, 6.0);
    let textbook = [
        g / radius - w * w,
        -g / radius - w * w,
        w * w - (g / (radius * w)).powi(2),
        w * w - (g / (radius * w)).powi(2),
    ];
    for (c, t) in cases.iter().zip(textbook) {
        let x = c
            .omega_squared
            .as_ref()
            .unwrap()
            .eval(&|s| r.scene.values.get(s).copied())
            .unwrap();
        assert!((x - t).abs() < 1e-12 * t.abs(), "{x} {t}");
    }
    // Below the critical speed √(g/R) ≈ 4.43 only the top and the bottom are at rest.
    let slow = course_scene("05-bead-on-hoop.toml", "w = 6.0", "w = 3.0");
    slow.assert_steps_pass();
    let StepResult::Equilibria { zeros, .. } = &r.derivation.named["rest"] else {
        panic!()
    };
    let Some(StepResult::Equations(eqs)) = r.derivation.named.get("eom") else {
        panic!()
    };
    let mut check = StepCheck::not_yet_run("s", 1);
    let missing =
        crate::steps::rest::equilibria_check(&r.scene, &eqs[0].1, "theta", &zeros[..2], &mut check);
    assert!(
        matches!(missing, Err(CheckError::MissedZero { .. })),
        "{missing:?}"
    );
}

/// The gyroscope of tests/course: the steady-precession equation solved for both rates (each
/// put back), the slow one's series in ε = 1/ω₃ and the textbook's M g l/(I₃ ω₃) agree; a wrong
/// leading term disagrees at its line; the remainder check fails a series missing a term.
#[test]
fn gyroscope_series_and_roots() {
    use crate::derive::step_names::StepResult;
    let r = course_scene("06-gyroscope.toml", "order = 1", "order = 1");
    r.assert_steps_pass();
    let StepResult::Roots(roots) = &r.derivation.named["rate"] else {
        panic!("{:?}", r.derivation.named["rate"])
    };
    assert_eq!(roots.len(), 2);
    // Both roots of I1 cos θ φ'² − I3 w3 φ' + M g l = 0 at the scene's values, in floating point.
    let (i1, i3, mgl, w3, c) = (0.02f64, 0.01f64, 9.81 * 0.1, 100.0f64, 0.8f64.cos());
    let disc = ((i3 * w3).powi(2) - 4.0 * i1 * c * mgl).sqrt();
    let want = [
        (i3 * w3 - disc) / (2.0 * i1 * c),
        (i3 * w3 + disc) / (2.0 * i1 * c),
    ];
    for (root, w) in roots.iter().zip(want) {
        let x = root.eval(&|s| r.scene.values.get(s).copied()).unwrap();
        assert!((x - w).abs() < 1e-12 * w, "{x} {w}");
    }
    for (name, verdict, _) in verdicts(&r) {
        assert_eq!(verdict, Verdict::Agrees, "{name}");
    }
    let wrong = course_scene("06-gyroscope.toml", "M*g*l*eps/I3\"", "M*g*l*eps/I1\"");
    assert_disagrees_at_its_line(&wrong, "slow");
    // The slow rate against 0 (its series with the leading term dropped): the remainder is
    // then of order 1, not 2.
    let step = r.scene.steps.iter().find(|s| s.name == "slow").unwrap();
    let crate::scene::Operation::Series(Series { of, .. }) = &step.op else {
        panic!()
    };
    let f = crate::derive::step_names::expand_names(&r.scene, &r.derivation, step, of).unwrap();
    let mut check = StepCheck::not_yet_run("s", 1);
    crate::steps::series::remainder_check(
        &r.scene,
        &f,
        &crate::cas::Expr::int(0),
        "eps",
        0.0,
        1,
        &mut check,
    )
    .unwrap();
    assert!(!check.passed(), "{check:?}");
}

/// The paraboloid of tests/course: its volume and moments by `integrate` are the textbook's
/// (π R² h/2, M R²/3, M R²/6 + M h²/2 about the vertex); a wrong moment disagrees at its line;
/// the quadrature route fails a wrong exact result; sin θ over half a turn is refused.
#[test]
fn paraboloid_by_integration() {
    let r = course_scene(
        "07-paraboloid.toml",
        "gives = \"M*R^2/3\"",
        "gives = \"M*R^2/3\"",
    );
    r.assert_steps_pass();
    let (m, radius, h) = (2.0f64, 0.5f64, 1.2f64);
    for (name, textbook) in [
        ("V", std::f64::consts::PI * radius * radius * h / 2.0),
        ("Iz", m * radius * radius / 3.0),
        ("Ix", m * radius * radius / 6.0 + m * h * h / 2.0),
    ] {
        let x = r.value_at(name, &[]);
        assert!(
            (x - textbook).abs() < 1e-14 * textbook,
            "{name}: {x} {textbook}"
        );
    }
    for (name, verdict, _) in verdicts(&r) {
        assert_eq!(verdict, Verdict::Agrees, "{name}");
    }
    let wrong = course_scene(
        "07-paraboloid.toml",
        "gives = \"M*R^2/3\"",
        "gives = \"M*R^2/2\"",
    );
    assert_disagrees_at_its_line(&wrong, "Iz");
    let step = r.scene.steps.iter().find(|s| s.name == "Iz").unwrap();
    let crate::scene::Operation::Integrate(Integrate { of, over }) = &step.op else {
        panic!()
    };
    let f = crate::derive::step_names::expand_names(&r.scene, &r.derivation, step, of).unwrap();
    let mut check = StepCheck::not_yet_run("s", 1);
    crate::steps::integrate::quadrature_check(
        &r.scene.values,
        &f,
        over,
        &parse("M*R^2/2").unwrap().expr,
        &mut check,
    )
    .unwrap();
    assert!(!check.passed(), "{check:?}");
    let half = crate::scene::Scene::parse(
        &std::fs::read_to_string("tests/course/dynamics/07-paraboloid.toml")
            .unwrap()
            .replace(
                "[\"theta\", \"0\", \"2*pi\"]]\nwhy = \"about",
                "[\"theta\", \"0\", \"pi/3\"]]\nwhy = \"about",
            ),
        Path::new("p.toml"),
    )
    .unwrap();
    let err = run_scene(half, None).unwrap_err().to_string();
    assert!(
        err.contains("integrate it from 0 to 2*pi, pi or pi/2"),
        "{err}"
    );
}

/// A step whose expansion is beyond the engine's budget says so at its own line, with advice
/// about the step (not about a body's dimensions).
#[test]
fn a_step_over_the_engines_budget_says_what_to_do_at_its_line() {
    let text = include_str!("../../tests/fixtures/unit/step-over-budget.toml");
    let err = run_scene(Scene::parse(text, Path::new("p.toml")).unwrap(), None)
        .unwrap_err()
        .to_string();
    crate::base::assert_says(&err, &["step `P`", "split the step into smaller ones"]);
    assert!(!err.contains("body"), "{err}");
}

/// The free top of tests/course, derived from its Lagrangian in Euler angles, reaches the rate
/// the built-in family derives from Euler's equations (the lecture's symmetric top, eq (69)):
/// the same expression exactly, and the same number at several tops. A wrong rate disagrees.
#[test]
fn free_top_steps_reach_the_built_in_precession_rate() {
    use crate::model::catalogue::quantity;
    let steps = course_scene("08-free-top.toml", "Lag", "Lag");
    for (name, verdict, _) in verdicts(&steps) {
        assert_eq!(verdict, Verdict::Agrees, "{name}");
    }
    steps.assert_steps_pass();
    let text = std::fs::read_to_string("lectures/lecture-3-9/02-symmetric-top.toml").unwrap();
    let family = run(&text);
    let built_in = family
        .derivation
        .scalar(quantity::PRECESSION_RATE)
        .unwrap()
        .clone();
    let derived = steps.derivation.named["body_rate"]
        .scalar()
        .unwrap()
        .clone();
    let difference = crate::cas::Expr::minus(derived.clone(), built_in.clone());
    assert!(crate::cas::simplify(&difference).unwrap().is_zero());
    for (i1, i3, w3) in [(2.0, 3.0, 1.0), (5.0, 0.5, -2.0), (1.0, 1.0, 7.0)] {
        let at = |s: &str| match s {
            "I1" => Some(i1),
            "I3" => Some(i3),
            "w3" => Some(w3),
            _ => None,
        };
        let (a, b) = (derived.eval(&at).unwrap(), built_in.eval(&at).unwrap());
        assert!((a - b).abs() <= 1e-15 * a.abs().max(1.0), "{a} {b}");
        assert!((a - (i3 - i1) / i1 * w3).abs() <= 1e-15 * a.abs().max(1.0));
    }
    let wrong = course_scene(
        "08-free-top.toml",
        "\"(I3 - I1)/I1*w3\"",
        "\"(I1 - I3)/I1*w3\"",
    );
    let body = verdicts(&wrong)
        .into_iter()
        .find(|v| v.0 == "body_rate")
        .unwrap();
    assert_eq!(body.1, Verdict::Disagrees);
}

/// The cone of tests/course spins on its apex with Euler angles theta, phi, psi beside a body
/// whose own angle is then theta_1: its moments come from the body, every `gives` agrees, and
/// the wobble frequency is the textbook's with the cone's moments (3/20 M R² + 3/5 M h²,
/// 3/10 M R², l = 3h/4) in floating point. A `lagrange` check that starts at rest fails and
/// says to give a start.
#[test]
fn sleeping_cone_takes_its_moments_from_its_body() {
    let r = course_scene("09-sleeping-cone.toml", "Lag", "Lag");
    assert_eq!(r.scene.bodies[0].variables, ["s", "theta_1", "z"]);
    for (name, verdict, _) in verdicts(&r) {
        assert_eq!(verdict, Verdict::Agrees, "{name}");
    }
    r.assert_steps_pass();
    let (m, rr, h, g, w3) = (0.2f64, 0.03f64, 0.04f64, 9.81f64, 150.0f64);
    let (i1, i3, l) = (
        0.15 * m * rr * rr + 0.6 * m * h * h,
        0.3 * m * rr * rr,
        0.75 * h,
    );
    let want = ((i3 * w3).powi(2) - 4.0 * i1 * m * g * l).sqrt() / (2.0 * i1);
    let omega = r.value_at("Omega", &[]);
    assert!((omega - want).abs() < 1e-12 * want, "{omega} {want}");
    let at_rest = course_scene("09-sleeping-cone.toml", "start = { theta = 0.2 }\n", "");
    let tilt = at_rest
        .verification
        .steps
        .iter()
        .find(|c| c.step == "tilt")
        .unwrap();
    assert!(
        tilt.problem
            .as_deref()
            .is_some_and(|p| p.contains("give the step a `start`")),
        "{tilt:?}"
    );
}

/// The system check fails the double pendulum's accelerations swapped, and passes them as
/// derived.
#[test]
fn the_system_check_fails_a_wrong_solution() {
    use crate::derive::step_names::StepResult;
    let r = course_scene("03-double-pendulum.toml", "Lag", "Lag");
    let StepResult::Solution(solution) = &r.derivation.named["acc"] else {
        panic!()
    };
    let eqs = match &r.derivation.named["eom"] {
        StepResult::Equations(eqs) => eqs.clone(),
        other => panic!("{other:?}"),
    };
    let mut right = StepCheck::not_yet_run("s", 1);
    crate::steps::solve::system_check(&r.scene, &eqs, solution, 7, &mut right).unwrap();
    assert!(right.passed(), "{right:?}");
    let swapped = vec![
        (solution[0].0.clone(), solution[1].1.clone()),
        (solution[1].0.clone(), solution[0].1.clone()),
    ];
    let mut wrong = StepCheck::not_yet_run("s", 1);
    crate::steps::solve::system_check(&r.scene, &eqs, &swapped, 7, &mut wrong).unwrap();
    assert!(!wrong.passed(), "{wrong:?}");
}

/// The double pendulum of tests/course at rest: four states (each string down or up), only
/// both down stable, with K = diag(2mgl, mgl) there (textbook, in floats). Newton's search over
/// the torus fails a set missing a state, and the eigenvalue check fails a wrong verdict.
#[test]
fn double_pendulum_states_of_rest() {
    use crate::derive::step_names::{Stable, StepResult};
    let r = course_scene("03-double-pendulum.toml", "m = ", "m = ");
    r.assert_steps_pass();
    let StepResult::RestStates { states, .. } = &r.derivation.named["rest"] else {
        panic!("{:?}", r.derivation.named["rest"])
    };
    let pi = std::f64::consts::PI;
    let at = |e: &crate::cas::Expr| e.eval(&|s| r.scene.values.get(s).copied()).unwrap();
    let values: Vec<Vec<f64>> = states
        .iter()
        .map(|s| s.iter().map(|z| at(&z.value)).collect())
        .collect();
    assert_eq!(
        values,
        [[0.0, 0.0], [0.0, pi], [pi, 0.0], [pi, pi]].map(|s| s.to_vec())
    );
    let StepResult::RestStability { cases, .. } = &r.derivation.named["upright"] else {
        panic!()
    };
    let verdicts: Vec<Stable> = cases.iter().map(|c| c.verdict).collect();
    assert_eq!(
        verdicts,
        [Stable::Always, Stable::Never, Stable::Never, Stable::Never]
    );
    let (m, g, l) = (
        r.scene.values["m"],
        r.scene.values["g"],
        r.scene.values["l"],
    );
    let k: Vec<f64> = cases[0].stiffness.iter().map(at).collect();
    let textbook = [2.0 * m * g * l, 0.0, 0.0, m * g * l];
    for (x, t) in k.iter().zip(textbook) {
        assert!((x - t).abs() < 1e-12 * t.abs().max(1.0), "{k:?}");
    }
    let Some(StepResult::Equations(eqs)) = r.derivation.named.get("eom") else {
        panic!()
    };
    let mut check = StepCheck::not_yet_run("s", 1);
    let missing = crate::steps::rest_states::states_check(&r.scene, eqs, &states[..3], &mut check);
    assert!(
        matches!(missing, Err(CheckError::MissedState { .. })),
        "{missing:?}"
    );
    let mut wrong = cases.to_vec();
    wrong[1].verdict = Stable::Always;
    let mut check = StepCheck::not_yet_run("s", 1);
    let verdict =
        crate::steps::rest_states::rest_stability_check(&r.scene, eqs, &wrong, &mut check);
    assert!(
        matches!(verdict, Err(CheckError::WrongStateVerdict { .. })),
        "{verdict:?}"
    );
}

/// A radial motion whose static equation is r³ = r₀³ (k(r₀³/r³ − 1) = 0): only the real root is
/// a state of rest, the two complex ones are set aside by name, and stability goes on; with p
/// for r₀³ the cubic is solved in closed form, r = ∛p. Each agrees with its numeric check, and
/// Ω² = 3k/(m r) at the state of rest with the textbook's.
#[test]
fn only_real_states_of_rest_and_a_cubic_in_closed_form() {
    use crate::cas::Expr;
    use crate::derive::step_names::StepResult;
    let scene = |potential: &str, symbol: &str, value: &str| {
        include_str!("../../tests/fixtures/unit/orbit-states-of-rest.toml")
            .replace("{symbol}", symbol)
            .replace("{potential}", potential)
            .replace("{value}", value)
    };
    for (text, radius) in [
        (scene("r0^3/(2*r^2)", "r0", "1.5"), 1.5f64),
        (scene("p/(2*r^2)", "p", "3.375"), 1.5f64),
    ] {
        let r = run(&text);
        r.assert_steps_pass();
        let StepResult::Equilibria {
            zeros, excluded, ..
        } = &r.derivation.named["rest"]
        else {
            panic!("{:?}", r.derivation.named["rest"])
        };
        let at = |e: &Expr| e.eval(&|s| r.scene.values.get(s).copied()).unwrap();
        assert_eq!(zeros.len(), 1, "{zeros:?}");
        assert!((at(&zeros[0].value) - radius).abs() < 1e-12);
        let StepResult::Stability { cases, .. } = &r.derivation.named["st"] else {
            panic!()
        };
        let w2 = at(cases[0].omega_squared.as_ref().unwrap());
        assert!((w2 - 3.0 * 2.0 / radius).abs() < 1e-12, "{w2}");
        if text.contains("r0") {
            // The quadratic factor r² + r r₀ + r₀²: both roots named, neither real.
            assert_eq!(excluded.len(), 2, "{excluded:?}");
            assert!(excluded.iter().all(|e| at(e).is_nan()), "{excluded:?}");
            let page = &r
                .derivation
                .steps
                .iter()
                .find(|s| s.title.to_text().contains("equilibrium 1"));
            let why = format!("{:?}", page.unwrap().why);
            assert!(why.contains("real for no values of the symbols"), "{why}");
            // The instructor's working: the student's summary gives the reason alone.
            let student = format!("{:?}", page.unwrap().student_why);
            assert!(student.starts_with("Some"), "{student}");
            assert!(!student.contains("real for no values"), "{student}");
        }
        // Ω² = 3k/(m r) is positive for every positive value, ∛p among them.
        assert_eq!(
            cases[0].verdict,
            crate::derive::step_names::Stable::Always,
            "{:?}",
            cases[0].omega_squared
        );
        if text.contains("p/") {
            assert_eq!(zeros[0].value.to_text(), "p^(1/3)");
        }
    }
}

/// The n-link pendulum, n = 1 to 6: each mode agrees with √λ of the textbook's M⁻¹K
/// (M_ij = (n − max(i, j)) m l², K = m g l diag(n, …, 1)), computed here by nalgebra, to 1e-12.
/// n = 3 is exact (det(K − λM) an irreducible cubic, in the trigonometric form); from n = 4
/// (Ferrari's quartic past the engine's budget, then degrees past four) the modes are numeric,
/// by Sturm bisection, with the reason on the page and no internal name. The step's check fails
/// a numeric mode moved by one part in 10⁶.
#[test]
fn the_n_link_pendulums_modes_agree_with_m_inverse_k() {
    use crate::derive::step_names::StepResult;
    use crate::verify::n_link::{n_link_scene as links, textbook_modes};
    for n in 1..=6 {
        let r = run(&links(n));
        assert!(
            r.verification.steps.iter().all(|c| c.passed()),
            "{n}: {:?}",
            r.verification.steps
        );
        let want = textbook_modes(n);
        let at = |e: &crate::cas::Expr| e.eval(&|s| r.scene.values.get(s).copied()).unwrap();
        let found: Vec<f64> = match &r.derivation.named["Omega"] {
            StepResult::Expr(omega) if n == 1 => vec![at(omega)],
            StepResult::Modes(modes) if n <= 3 => modes.iter().map(at).collect(),
            StepResult::NumericModes {
                frequencies,
                reason,
            } if n >= 4 => {
                let why = reason.to_text();
                assert!(
                    why.contains(if n == 4 { "budget" } else { "degree" }) && !why.contains("__"),
                    "{why}"
                );
                frequencies.clone()
            }
            other => panic!("{n}: {other:?}"),
        };
        assert_eq!(found.len(), n);
        for (x, w) in found.iter().zip(&want) {
            assert!((x / w - 1.0).abs() < 1e-12, "{n}: {x} {w}");
        }
        if n == 5 {
            // A name with no exact form is refused by a later step and a claim.
            let text = links(5);
            let later = format!("{text}\n[[step]]\nname = \"T1\"\nbe = \"2*pi/Omega_1\"\n");
            let scene = Scene::parse(&later, Path::new("p.toml")).unwrap();
            let message = run_scene(scene, None).err().unwrap().to_string();
            assert!(message.contains("`Omega_1` has no exact form"), "{message}");
            let claim = format!(
                "{text}\n[[claim]]\neq = \"1\"\nstatement = \"slow\"\nquantity = \"Omega_1\"\nvalue = \"sqrt(g/l)\"\n"
            );
            let r = run(&claim);
            let problem = r.verification.claims[0].problem.clone().unwrap();
            assert!(problem.contains("`Omega_1` has no exact form"), "{problem}");
            // A graded answer takes each variant's own modes: Sturm bisection of (K, M) at its
            // values, checked by the Schur route, and here against the textbook's M⁻¹K, whose
            // modes scale as √(g/l).
            let graded = text
                .replace("id = \"links-5\"", "id = \"problem-links\"")
                .replace(
                    "symbols = { m = \"mass of each bob\", l = \"length of each link\", g = \"gravitational acceleration\" }",
                    "[symbols]\nm = { meaning = \"mass\", unit = \"kg\" }\nl = { meaning = \"length\", unit = \"m\" }\ng = { meaning = \"gravity\", unit = \"m/s^2\" }\n",
                )
                + "\n[problem]\nstatement = \"Find them.\"\nanswers = [{ value = \"Omega_1\", unit = \"rad/s\" }, { value = \"Omega_5/Omega_1\" }]\n[variants]\ncount = 3\nl = [\"1/2\", \"3/2\", \"2\"]\n";
            let scene = Scene::parse(&graded, Path::new("p.toml")).unwrap();
            let r = run_scene(scene, None).unwrap();
            assert_eq!(r.verification.variants.len(), 3);
            for v in &r.verification.variants {
                let l = v
                    .values
                    .iter()
                    .find(|(k, _)| k == "l")
                    .unwrap()
                    .1
                    .eval(&|_| None)
                    .unwrap();
                let (slow, ratio) = (&v.answers[0], &v.answers[1]);
                assert!(slow.passed() && ratio.passed(), "{v:?}");
                assert!(
                    slow.rounded,
                    "a numeric mode is shown as ≈ its value: {slow:?}"
                );
                let want = want[0] / l.sqrt();
                assert!(
                    (slow.exact_numbers[0] / want - 1.0).abs() < 1e-12,
                    "{l}: {slow:?}"
                );
                assert!((slow.numeric[0] / want - 1.0).abs() < 1e-9, "{l}: {slow:?}");
                let want_ratio = textbook_modes(5)[4] / textbook_modes(5)[0];
                assert!(
                    (ratio.exact_numbers[0] / want_ratio - 1.0).abs() < 1e-12,
                    "{ratio:?}"
                );
            }
        }
        if n == 6 {
            let mut d = r.derivation.clone();
            let Some(StepResult::NumericModes { frequencies, .. }) = d.named.get_mut("Omega")
            else {
                unreachable!()
            };
            frequencies[2] *= 1.0 + 1e-6;
            let checks = check_steps(&r.scene, &d, &crate::numeric::budget::Deadline::checks());
            let omega = checks.last().unwrap();
            assert!(!omega.passed(), "{omega:?}");
            assert!(omega.error > 5e-7, "{omega:?}");
        }
    }
}

/// A claim may name a coordinate and its rates: p = M L² φ'/3 agrees, a sign slip in the
/// generalised force disagrees, each at random values of φ and φ' as well as by the engine.
#[test]
fn a_claim_names_a_coordinate_and_its_rate() {
    let text = include_str!("../../tests/fixtures/unit/claim-coordinate-rate.toml");
    let r = run(text);
    let verdicts: Vec<Verdict> = r.verification.claims.iter().map(|c| c.verdict).collect();
    assert_eq!(
        verdicts,
        [Verdict::Agrees, Verdict::Disagrees],
        "{:?}",
        r.verification.claims
    );
    assert!(r.verification.claims.iter().all(|c| c.problem.is_none()));
}

/// An `integrate` step may run over a symbol declared for it (x, the distance along the rod):
/// ∫₀ᴸ (M/L) x² dx = M L²/3 agrees, by the engine and by quadrature, and M L²/2 does not; a
/// definition's name is still refused as a variable.
#[test]
fn an_integral_runs_over_a_declared_symbol() {
    let scene = |gives: &str| {
        include_str!("../../tests/fixtures/unit/integral-over-symbol.toml")
            .replace("{gives}", gives)
    };
    let right = run(&scene("M*L^2/3"));
    right.assert_steps_pass();
    assert_eq!(verdicts(&right)[0].1, Verdict::Agrees);
    let wrong = run(&scene("M*L^2/2"));
    assert_eq!(verdicts(&wrong)[0].1, Verdict::Disagrees);
    let defined = scene("M*L^2/3")
        .replace(", x = \"distance along the rod\" }", " }")
        .replace("[[step]]", "[definitions]\nx = \"L/2\"\n[[step]]");
    let e = Scene::parse(&defined, Path::new("p.toml")).unwrap_err();
    assert!(
        e.to_string().contains("cannot be an integration variable"),
        "{e}"
    );
}

/// `gives` as a list on a step with several results: the double pendulum's two modes, each
/// entry a claim on `Omega_1`, `Omega_2` in order. The textbook's √((2 ∓ √2) g/l) agree; the
/// uncoupled √(g/l), √(3g/l) disagree, each at the step's line; a list of three is a problem
/// that says so; a list on a step with one result is refused where it is written.
#[test]
fn a_list_gives_states_each_result_of_a_step() {
    let text = crate::verify::n_link::n_link_scene(2).replace(
        "why = \"the normal modes\"",
        "why = \"the normal modes\"\ngives = [\"sqrt((2 - sqrt(2))*g/l)\", \"sqrt((2 + sqrt(2))*g/l)\"]",
    );
    let verdicts = |text: &str| -> Vec<(Verdict, usize, Option<String>)> {
        run(text)
            .verification
            .claims
            .iter()
            .map(|c| (c.verdict, c.line, c.problem.clone()))
            .collect()
    };
    let line = text
        .lines()
        .position(|l| l.starts_with("frequency ="))
        .unwrap()
        - 1;
    let right = verdicts(&text);
    assert_eq!(right.len(), 2, "{right:?}");
    // Each claim names its result as the page sets it, never by the scene's `Omega_1`.
    let statements: Vec<String> = run(&text)
        .verification
        .claims
        .iter()
        .map(|c| c.statement.clone())
        .collect();
    assert_eq!(
        statements,
        [
            "the normal modes ($\\Omega_{1}$)",
            "the normal modes ($\\Omega_{2}$)"
        ]
    );
    assert!(
        right
            .iter()
            .all(|(v, l, _)| *v == Verdict::Agrees && *l == line),
        "{right:?} {line}"
    );
    let wrong = text
        .replace("sqrt((2 - sqrt(2))*g/l)", "sqrt(g/l)")
        .replace("sqrt((2 + sqrt(2))*g/l)", "sqrt(3*g/l)");
    assert!(
        verdicts(&wrong)
            .iter()
            .all(|(v, _, _)| *v == Verdict::Disagrees)
    );
    let three = text.replace(
        "\"sqrt((2 + sqrt(2))*g/l)\"]",
        "\"sqrt((2 + sqrt(2))*g/l)\", \"g\"]",
    );
    let problems = verdicts(&three);
    assert!(
        problems
            .iter()
            .all(|(_, _, p)| p.as_deref().is_some_and(|p| p.contains("lists 3 forms"))),
        "{problems:?}"
    );
    let on_one = text.replace(
        "why = \"$T - V$\"",
        "why = \"$T - V$\"\ngives = [\"1\", \"2\"]",
    );
    let e = Scene::parse(&on_one, Path::new("p.toml")).unwrap_err();
    assert!(e.message.contains("a list in `gives`"), "{e}");
}

/// A step's titles name coordinates, multipliers and unknowns as the page typesets them (a
/// title's `$…$` is read by every renderer), not by their names in the scene: the rolling
/// disk's equations of motion of q₁ and its friction constraints, differentiated once (they
/// are on the rates); the Atwood machine's tension, differentiated twice. No title shows a
/// step's name (`eom`): a step is headed by its symbol or by what it does.
#[test]
fn step_titles_typeset_coordinates_and_say_how_a_constraint_is_differentiated() {
    let disk = run(&std::fs::read_to_string("tests/course/dynamics/16-rolling-disk.toml").unwrap());
    let titles: Vec<String> = disk
        .derivation
        .steps
        .iter()
        .map(|s| s.title.to_author_text(crate::notation::Names::none()))
        .collect();
    assert!(
        titles.contains(&"The equation of motion of $q_{1}$".to_string()),
        "{titles:?}"
    );
    assert!(titles.iter().all(|t| !t.contains("of q1")), "{titles:?}");
    assert!(
        titles
            .iter()
            .all(|t| !t.starts_with("eom") && !t.starts_with("Lag")),
        "{titles:?}"
    );
    let once: Vec<&String> = titles
        .iter()
        .filter(|t| t.contains("constraint of the multiplier"))
        .collect();
    assert_eq!(once.len(), 2, "{titles:?}");
    assert!(
        once.iter().all(|t| t.ends_with("differentiated once")),
        "{once:?}"
    );
    let atwood = run(&std::fs::read_to_string("tests/course/dynamics/13-atwood.toml").unwrap());
    let twice = atwood
        .derivation
        .steps
        .iter()
        .find(|s| s.title.to_text().contains("constraint of the multiplier"))
        .unwrap();
    assert!(
        twice.title.to_text().ends_with("differentiated twice"),
        "{}",
        twice.title
    );
    // The page reads the title's mathematics: no dollar sign reaches it.
    let plain = crate::model::prose::plain(&titles[titles.len() - 1]);
    assert!(!plain.contains('$'), "{plain}");
}

/// A cube root over positive symbols: the puck's steady circle r = ∛(p²/(m M g)) (a cubic with
/// one real root), its Ω² = 3 p² (g M m/p²)^(4/3)/(m (M + m)) decided stable for all values,
/// and the textbook's 3 M g/((m + M) r) agreeing with it once each fractional power of a
/// product is taken factor by factor; a wrong coefficient disagrees.
#[test]
fn a_cube_root_over_positive_symbols_agrees_and_its_square_frequency_is_positive() {
    use crate::derive::step_names::{Stable, StepResult};
    let text =
        std::fs::read_to_string("tests/course/dynamics/17-puck-and-hanging-mass.toml").unwrap();
    let r = run(&text);
    let StepResult::Stability { cases, .. } = &r.derivation.named["wobble"] else {
        panic!("{:?}", r.derivation.named["wobble"])
    };
    assert_eq!(cases.len(), 1);
    assert_eq!(cases[0].verdict, Stable::Always);
    let claim = |statement: &str| {
        r.verification
            .claims
            .iter()
            .find(|c| c.statement.contains(statement))
            .unwrap()
            .verdict
    };
    assert_eq!(claim("radius of the steady circle"), Verdict::Agrees);
    assert_eq!(claim("squared frequency"), Verdict::Agrees);
    // The agreement that rests on positive symbols says which; the Routhian's does not.
    let positive = |statement: &str| {
        r.verification
            .claims
            .iter()
            .find(|c| c.statement.contains(statement))
            .unwrap()
            .positive
            .clone()
    };
    assert_eq!(positive("squared frequency"), ["M", "g", "m", "p"]);
    assert!(positive("is cyclic").is_empty());
    let wrong = run(&text.replace(
        "value = \"3*M*g/((m + M)*circle_1)\"",
        "value = \"2*M*g/((m + M)*circle_1)\"",
    ));
    let verdict = wrong
        .verification
        .claims
        .iter()
        .find(|c| c.statement.contains("squared frequency"))
        .unwrap()
        .verdict;
    assert_eq!(verdict, Verdict::Disagrees);
}

/// A momentum's reason says "conserved" once: the author's reason that says it is kept alone,
/// one that says why takes "conserved", another takes the verdict with its why.
#[test]
fn a_conserved_momentum_is_said_conserved_once() {
    let reason = |r: &SceneReport, name: &str| {
        let step = r
            .derivation
            .steps
            .iter()
            .find(|s| s.author.as_deref() == Some(name));
        step.expect("the step's line").why.to_text()
    };
    let cart = std::fs::read_to_string("tests/course/dynamics/20-pendulum-on-cart.toml").unwrap();
    let r = run(&cart);
    assert_eq!(reason(&r, "px"), "$L$ does not depend on $x$; conserved");
    let said = cart.replace(
        "why = \"$L$ does not depend on $x$\"",
        "why = \"the cart's momentum, conserved\"",
    );
    assert_ne!(said, cart);
    assert_eq!(reason(&run(&said), "px"), "the cart's momentum, conserved");
    let other = cart.replace(
        "why = \"$L$ does not depend on $x$\"",
        "why = \"the cart's momentum\"",
    );
    assert_eq!(
        reason(&run(&other), "px"),
        "the cart's momentum; conserved: the Lagrangian does not depend on x"
    );
}

/// Each operation's own words reach its page lines (`Rule::wording`): the linearised equation
/// says so, the full one does not, and a substitution into equations says it is substituted.
#[test]
fn a_step_is_worded_by_its_operation() {
    let text = pendulum(
        "(M*L^2/12 + M*(L/2)^2)",
        "2*Ip*phi'' + M*g*L*sin(phi) = 0",
        "M*L^2*phi'/3",
        "sqrt(3*g/(2*L))",
    )
    .replace(
        "[outputs]",
        "[[step]]\nname = \"still\"\nsubstitute = \"eom\"\nset = { g = \"0\" }\n[outputs]",
    );
    let r = run(&text);
    let title = |author: &str| -> String {
        let step = r
            .derivation
            .steps
            .iter()
            .find(|s| s.author.as_deref() == Some(author));
        step.unwrap_or_else(|| panic!("no line of {author}"))
            .title
            .to_text()
    };
    assert_eq!(
        [title("eom"), title("small"), title("still")],
        [
            "The equation of motion of phi",
            "The linearised equation of motion of phi",
            "The equation of motion of phi, substituted",
        ]
    );
}
