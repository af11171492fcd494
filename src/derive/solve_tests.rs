//! `solve` beyond one linear equation: quartics in u², cubics and quartics in closed form, the
//! numeric roots of a factor it cannot solve, and linear systems; each result checked against
//! numbers computed here.

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

/// The real roots of a polynomial from nalgebra's eigenvalues of its companion matrix (a route
/// without the engine), sorted; coefficients from the constant up.
fn companion_real_roots(c: &[f64]) -> Vec<f64> {
    let n = c.len() - 1;
    let m = nalgebra::DMatrix::from_fn(n, n, |i, j| {
        if j == n - 1 {
            -c[i] / c[n]
        } else if i == j + 1 {
            1.0
        } else {
            0.0
        }
    });
    let mut real: Vec<f64> = m
        .complex_eigenvalues()
        .iter()
        .filter(|z| z.im.abs() < 1e-9)
        .map(|z| z.re)
        .collect();
    real.sort_by(f64::total_cmp);
    real
}

/// Cubics and quartics the engine cannot factor, solved in closed form: three real roots (the
/// trigonometric form), one (Cardano's real cube roots, either sign of q), and a general
/// quartic (Ferrari's) with two and with four real roots. Each root list equals the companion
/// matrix's real eigenvalues at the scene's values, and at other values where the same form is
/// real.
#[test]
fn cubics_and_quartics_in_closed_form() {
    // (polynomial in x, its coefficients from the constant up as a function of a and b,
    // (a, b) values where the chosen form stays real)
    type Coeffs = fn(f64, f64) -> Vec<f64>;
    type Case = (&'static str, Coeffs, [(f64, f64); 2]);
    let cases: [Case; 5] = [
        (
            "x^3 - 3*a*x + b",
            |a, b| vec![b, -3.0 * a, 0.0, 1.0],
            [(1.0, 1.0), (2.0, 0.5)],
        ),
        (
            "a*x^3 + x^2 - b",
            |a, b| vec![-b, 0.0, 1.0, a],
            [(1.0, 3.0), (0.5, 2.0)],
        ),
        (
            "x^3 + a*x + b",
            |a, b| vec![b, a, 0.0, 1.0],
            [(1.0, 1.0), (0.3, 2.0)],
        ),
        (
            "x^4 + a*x^3 - 5*x^2 + b*x + 1",
            |a, b| vec![1.0, b, -5.0, a, 1.0],
            [(0.5, 0.7), (0.2, 0.3)],
        ),
        (
            "x^4 - a*x - b",
            |a, b| vec![-b, -a, 0.0, 0.0, 1.0],
            [(1.0, 1.0), (2.0, 0.5)],
        ),
    ];
    let expected_count = [3, 1, 1, 4, 2];
    for ((poly, coeffs, points), count) in cases.iter().zip(expected_count) {
        let (a0, b0) = points[0];
        let vals = values(&[("a", a0), ("b", b0)]);
        let roots = solve(&eqs(&[("x", poly)]), "x", &vals).unwrap();
        assert_eq!(roots.len(), count, "{poly}: {roots:?}");
        for &(a, b) in points {
            let at = |s: &str| match s {
                "a" => Some(a),
                "b" => Some(b),
                _ => None,
            };
            let got: Vec<f64> = roots.iter().map(|r| r.eval(&at).unwrap()).collect();
            let want = companion_real_roots(&coeffs(a, b));
            assert_eq!(
                got.len(),
                want.len(),
                "{poly} at a = {a}, b = {b}: {got:?} {want:?}"
            );
            for (g, w) in got.iter().zip(&want) {
                assert!(
                    (g - w).abs() < 1e-9 * (1.0 + w.abs()),
                    "{poly}: {got:?} vs {want:?}"
                );
            }
        }
    }
    // q changes sign between the two: the other Cardano form, still the one real root.
    let vals = values(&[("a", 1.0), ("b", -1.0)]);
    let roots = solve(&eqs(&[("x", "x^3 + a*x + b")]), "x", &vals).unwrap();
    let want = companion_real_roots(&[-1.0, 1.0, 0.0, 1.0]);
    assert!((roots[0].eval(&|s| vals.get(s).copied()).unwrap() - want[0]).abs() < 1e-12);
}

/// A cubic's form depends on a name with no value: the error says which quantity decides it.
#[test]
fn a_cubic_without_values_says_what_decides_its_form() {
    let Err(DeriveError::NotDerivable(message)) = solve(
        &eqs(&[("x", "x^3 - 3*a*x + b")]),
        "x",
        &values(&[("a", 1.0)]),
    ) else {
        panic!("solved without b")
    };
    crate::base::assert_says(
        &message,
        &["depends on the sign of", "give each of its names a value"],
    );
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
    use crate::derive::step_names::StepResult;
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

/// The heavy top of tests/course/dynamics/11-nutation.toml turns where the cubic f(u) vanishes:
/// its closed-form roots at the scene's values against the turning points of cos θ on the
/// top's own equations of motion, integrated (Dormand–Prince, 1e-11) from a state with the
/// scene's constants a, b and α. Between accepted steps where θ' changes sign, θ is read off
/// the cubic Hermite interpolant at the zero of θ'.
#[test]
fn nutation_turns_at_the_cubics_roots() {
    use crate::derive::step_names::StepResult;
    use crate::numeric::{motion, ode};
    let text = std::fs::read_to_string("tests/course/dynamics/11-nutation.toml").unwrap();
    let scene = Scene::parse(&text, Path::new("n.toml")).unwrap();
    let vals = scene.values.clone();
    let r = run_scene(scene, None).unwrap();
    let StepResult::Roots(roots) = &r.derivation.named["turn"] else {
        panic!("{:?}", r.derivation.named["turn"])
    };
    let u: Vec<f64> = roots
        .iter()
        .map(|e| e.eval(&|s| vals.get(s).copied()).unwrap())
        .collect();
    assert_eq!(u.len(), 3, "{u:?}");
    assert!(
        -1.0 < u[0] && u[0] < u[1] && u[1] < 1.0 && u[2] > 1.0,
        "{u:?}"
    );
    let v = |s: &str| vals[s];
    let (a, b, alpha, i1, i3) = (v("a"), v("b"), v("alpha"), v("I1"), v("I3"));
    let beta = 2.0 * v("M") * v("g") * v("l") / i1;
    let f = |u: f64| (1.0 - u * u) * (alpha - beta * u) - (b - a * u).powi(2);
    let c = 0.5f64.cos();
    let s2 = 1.0 - c * c;
    assert!(f(c) > 0.0, "θ = 0.5 lies outside the nutation");
    let phi_rate = (b - a * c) / s2;
    let y0 = [
        0.5,
        0.0,
        0.0,
        (f(c) / s2).sqrt(),
        phi_rate,
        i1 * a / i3 - phi_rate * c,
    ];
    let eqs = r.derivation.named["eom"].equations().unwrap();
    let names: Vec<String> = ["theta", "phi", "psi"].map(String::from).to_vec();
    let coords: Vec<&String> = names.iter().collect();
    let system = motion::MotionSystem::new(eqs, &vals, &coords, &[]).unwrap();
    let run =
        ode::dormand_prince(&|_, y: &[f64]| system.rates(y), &y0, 3.0, 1e-11, 1_000_000).unwrap();
    let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut turns = 0;
    for pair in run.states.windows(2) {
        let ((t0, y0), (t1, y1)) = (&pair[0], &pair[1]);
        let (v0, v1) = (y0[3], y1[3]);
        if v0 * v1 > 0.0 {
            continue;
        }
        let h = t1 - t0;
        let s = v0 / (v0 - v1);
        let hermite = (2.0 * s.powi(3) - 3.0 * s * s + 1.0) * y0[0]
            + (s.powi(3) - 2.0 * s * s + s) * h * v0
            + (-2.0 * s.powi(3) + 3.0 * s * s) * y1[0]
            + (s.powi(3) - s * s) * h * v1;
        low = low.min(hermite.cos());
        high = high.max(hermite.cos());
        turns += 1;
    }
    assert!(turns >= 4, "{turns} turns in 3 s");
    assert!(
        (low - u[0]).abs() < 1e-8,
        "lowest cos θ {low} against u1 = {}",
        u[0]
    );
    assert!(
        (high - u[1]).abs() < 1e-8,
        "highest cos θ {high} against u2 = {}",
        u[1]
    );
}

/// `solve` of an expression solves it for where it is zero (x takes either sign here, from its
/// value, so both roots); of a step that gives several roots, it is an error at the step's
/// line that says what `solve` takes.
#[test]
fn solve_takes_an_expression_but_not_several_roots() {
    let scene = |last: &str| {
        format!(
            "id = \"s\"\ntitle = \"s\"\nnotes = {{ lecture = \"6\" }}\n\
             symbols = {{ a = \"a\", x = \"x\" }}\n\n\
             [[step]]\nname = \"f\"\nbe = \"x^2 - a\"\n\n\
             [[step]]\nname = \"r\"\nsolve = \"f\"\nfor = \"x\"\n\n{last}\
             [numeric]\nvalues = {{ a = 2.0, x = -1.0 }}\n"
        )
    };
    let r = run_scene(Scene::parse(&scene(""), Path::new("s.toml")).unwrap(), None).unwrap();
    let roots = r.derivation.named["r"].values(r.scene.result_names("r"));
    let at = |e: &crate::cas::Expr| e.eval(&|s| (s == "a").then_some(2.0)).unwrap();
    assert_eq!(roots.len(), 2);
    assert!((at(&roots[0].1) + 2f64.sqrt()).abs() < 1e-15);
    assert!((at(&roots[1].1) - 2f64.sqrt()).abs() < 1e-15);
    let again = scene("[[step]]\nname = \"s\"\nsolve = \"r\"\nfor = \"a\"\n\n");
    let Err(err) = run_scene(Scene::parse(&again, Path::new("s.toml")).unwrap(), None) else {
        panic!("solved several roots")
    };
    let err = err.to_string();
    crate::base::assert_says(&err, &["`r` gives several results", "s.toml:15:1"]);
}
