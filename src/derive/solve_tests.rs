//! `solve` beyond one linear equation: quartics in u², the numeric roots of a factor it cannot
//! solve, and linear systems; each result checked against numbers computed here.

use super::DeriveError;
use super::solve::{solve, solve_system};
use crate::cas::parse;
use crate::pipeline::run_scene;
use crate::scene::Scene;
use std::collections::BTreeMap;
use std::path::Path;

fn eqs(list: &[(&str, &str)]) -> Vec<(String, crate::cas::Expr)> {
    list.iter()
        .map(|(q, e)| (q.to_string(), parse(e).unwrap().expr))
        .collect()
}

fn values(list: &[(&str, f64)]) -> BTreeMap<String, f64> {
    list.iter().map(|(k, v)| (k.to_string(), *v)).collect()
}

/// x⁴ − 5a x² + 4a² = (x² − a)(x² − 4a) factors over the rationals; x⁴ − 2a x² − b does not,
/// and is solved as a quadratic in x²: ±√(a ± √(a² + b)). Each root makes the quartic vanish
/// at several values, and there are four.
#[test]
fn a_quartic_in_the_square_gives_four_roots() {
    for quartic in ["x^4 - 5*a*x^2 + 4*a^2", "x^4 - 2*a*x^2 - b"] {
        let vals = values(&[("a", 1.3), ("b", 0.7)]);
        let roots = solve(&eqs(&[("x", quartic)]), "x", &vals).unwrap();
        assert_eq!(roots.len(), 4, "{quartic}: {roots:?}");
        let poly = parse(quartic).unwrap().expr;
        for (a, b) in [(1.3, 0.7), (0.4, 2.5), (3.0, 0.1)] {
            let mut real = 0;
            for root in &roots {
                let at = |s: &str| match s {
                    "a" => Some(a),
                    "b" => Some(b),
                    _ => None,
                };
                let Ok(x) = root.eval(&at) else { continue };
                if !x.is_finite() {
                    continue;
                }
                let p = poly
                    .eval(&|s| if s == "x" { Some(x) } else { at(s) })
                    .unwrap();
                assert!(
                    p.abs() < 1e-12 * (1.0 + x.powi(4)),
                    "{quartic} at x = {x}: {p}"
                );
                real += 1;
            }
            // Two real roots for the second (a² + b > a²), four for the first.
            assert!(real >= 2, "{quartic}: {real} real roots at a = {a}");
        }
    }
}

/// A quintic the engine cannot factor: the error names the factor, its degree and its roots at
/// the scene's values, the one real root among them a zero of the quintic.
#[test]
fn an_unsolvable_factor_names_its_numeric_roots() {
    let vals = values(&[("k", 3.0), ("a", 1.0), ("b", 0.5)]);
    let Err(DeriveError::NotDerivable(message)) =
        solve(&eqs(&[("x", "k*x^5 - a*x - b")]), "x", &vals)
    else {
        panic!("solved a quintic")
    };
    assert!(message.contains("of degree 5 in `x`"), "{message}");
    let (_, list) = message
        .split_once("its roots are ")
        .unwrap_or_else(|| panic!("{message}"));
    let reals: Vec<f64> = list
        .split(", ")
        .filter(|r| !r.contains('i'))
        .map(|r| r.parse().unwrap())
        .collect();
    assert_eq!(list.split(", ").count(), 5, "{list}");
    assert_eq!(reals.len(), 1, "{list}");
    let x = reals[0];
    assert!((3.0 * x.powi(5) - x - 0.5).abs() < 1e-5, "{x}");
}

/// Two linear equations in two unknowns: Cramer's rule, each value put back here; a singular
/// system and a non-linear one are errors that say so.
#[test]
fn a_linear_system_by_cramers_rule() {
    // Rolling without slipping with the friction force F as an unknown: M a = M g s − F,
    // I a = F R² (I about the axis), so a = M g s R²/(M R² + I), F = I M g s/(M R² + I).
    let system = eqs(&[("x", "M*a - M*g*s + F"), ("phi", "I*a - F*R^2")]);
    let unknowns = ["a".to_string(), "F".to_string()];
    let solution = solve_system(&system, &unknowns).unwrap();
    let (m, g, s, i, r) = (2.0, 9.81, 0.4, 0.3, 0.5);
    let at = |name: &str| match name {
        "M" => Some(m),
        "g" => Some(g),
        "s" => Some(s),
        "I" => Some(i),
        "R" => Some(r),
        _ => None,
    };
    let a = solution[0].1.eval(&at).unwrap();
    let f = solution[1].1.eval(&at).unwrap();
    assert_eq!(solution[0].0, "a");
    assert!((a - m * g * s * r * r / (m * r * r + i)).abs() < 1e-14);
    assert!((f - i * m * g * s / (m * r * r + i)).abs() < 1e-14);
    let singular = eqs(&[("x", "a + F - 1"), ("y", "2*a + 2*F - 3")]);
    let Err(DeriveError::NotDerivable(m)) = solve_system(&singular, &unknowns) else {
        panic!()
    };
    assert!(m.contains("determinant in the unknowns is zero"), "{m}");
    let curved = eqs(&[("x", "a*F - 1"), ("y", "a - F")]);
    let Err(DeriveError::NotDerivable(m)) = solve_system(&curved, &unknowns) else {
        panic!()
    };
    assert!(m.contains("is not linear in a, F"), "{m}");
    let short = eqs(&[("x", "a + F - 1"), ("y", "g - 1")]);
    let Err(DeriveError::NotDerivable(m)) = solve_system(&short, &unknowns) else {
        panic!()
    };
    assert!(
        m.contains("takes as many equations that contain them, and 1 do"),
        "{m}"
    );
}

/// The double pendulum of tests/course solved for both accelerations: the textbook's explicit
/// form for equal masses and lengths at several states, and the check that puts them back.
#[test]
fn double_pendulum_accelerations() {
    use crate::derive::steps::StepResult;
    let text = std::fs::read_to_string("tests/course/dynamics/03-double-pendulum.toml").unwrap();
    let r = run_scene(Scene::parse(&text, Path::new("d.toml")).unwrap(), None).unwrap();
    let StepResult::Solution(solution) = &r.derivation.named["acc"] else {
        panic!("{:?}", r.derivation.named["acc"])
    };
    let check = r
        .verification
        .steps
        .iter()
        .find(|c| c.step == "acc")
        .unwrap();
    assert!(check.passed() && check.error < 1e-12, "{check:?}");
    let (g, l) = (9.81f64, 1.0f64);
    for (p1, p2, w1, w2) in [
        (0.3, -0.2, 0.0, 0.0),
        (1.2, 2.0, 0.7, -1.5),
        (-2.5, 0.4, 3.0, 1.0),
    ] {
        let at = |s: &str| match s {
            "phi1" => Some(p1),
            "phi2" => Some(p2),
            "phi1'" => Some(w1),
            "phi2'" => Some(w2),
            _ => r.scene.values.get(s).copied(),
        };
        let d = p1 - p2;
        let den = l * (3.0 - (2.0 * d).cos());
        let a1 = (-3.0 * g * p1.sin()
            - g * (p1 - 2.0 * p2).sin()
            - 2.0 * d.sin() * (w2 * w2 * l + w1 * w1 * l * d.cos()))
            / den;
        let a2 =
            2.0 * d.sin() * (2.0 * w1 * w1 * l + 2.0 * g * p1.cos() + w2 * w2 * l * d.cos()) / den;
        let got: Vec<f64> = solution.iter().map(|(_, e)| e.eval(&at).unwrap()).collect();
        assert!(
            (got[0] - a1).abs() < 1e-12 * (1.0 + a1.abs()),
            "{got:?} {a1}"
        );
        assert!(
            (got[1] - a2).abs() < 1e-12 * (1.0 + a2.abs()),
            "{got:?} {a2}"
        );
    }
}
