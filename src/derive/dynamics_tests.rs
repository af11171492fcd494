//! The Lecture 3/9 derivations against routes that share no code with them: the hand-written
//! f64 Euler right-hand side, the exact elliptic solution, an integrator, finite-difference
//! Jacobians and plain f64 geometry.

use super::algebra::Value;
use super::{Derivation, earth, euler, free_top, poinsot, stability};
use crate::cas::Expr;
use crate::model::moments::Moments;
use crate::numeric::free_body::{ExactSolution, euler_rhs, invariants};
use crate::numeric::integrators::{Method, Resolution, integrate};
use nalgebra::{Matrix3, Vector3};
use std::collections::BTreeMap;

fn derived(f: fn(&mut Derivation) -> Result<(), super::DeriveError>) -> Derivation {
    let mut d = Derivation::default();
    f(&mut d).unwrap();
    d
}

fn at(e: &Expr, values: &[(&str, f64)]) -> f64 {
    let map: BTreeMap<&str, f64> = values.iter().copied().collect();
    e.eval(&|s| map.get(s).copied())
        .unwrap_or_else(|m| panic!("{e}: {m}"))
}

fn entries(d: &Derivation, name: &str) -> Vec<Expr> {
    d.quantities[name].entries()
}

/// Moments and ω as (name, value) pairs for evaluation.
fn point(i: [f64; 3], w: [f64; 3]) -> Vec<(&'static str, f64)> {
    vec![
        ("I1", i[0]),
        ("I2", i[1]),
        ("I3", i[2]),
        ("w1", w[0]),
        ("w2", w[1]),
        ("w3", w[2]),
    ]
}

#[test]
fn euler_rates_match_the_numeric_right_hand_side() {
    let d = derived(euler::euler_equations);
    let rates = entries(&d, "torque_free_rates");
    for (i, w) in [
        ([1.0, 2.0, 3.0], [1.0, 0.1, 0.5]),
        ([2.5, 0.7, 2.2], [-0.3, 1.7, 0.9]),
    ] {
        let numeric = euler_rhs(&Moments::new(i).unwrap(), &Vector3::from(w));
        for k in 0..3 {
            let exact = at(&rates[k], &point(i, w));
            assert!((exact - numeric[k]).abs() <= 1e-15 * numeric.norm(), "{k}");
        }
    }
    // With N = 0 and ω̇ = the rates, Euler's equations must balance.
    let lhs = entries(&d, "euler_equations");
    let (i, w) = ([1.3, 2.1, 0.8], [0.4, -1.1, 0.6]);
    let wd = euler_rhs(&Moments::new(i).unwrap(), &Vector3::from(w));
    let mut values = point(i, w);
    values.extend([("wd1", wd.x), ("wd2", wd.y), ("wd3", wd.z)]);
    for e in &lhs {
        assert!(at(e, &values).abs() < 1e-14);
    }
}

#[test]
fn symmetric_top_precesses_at_the_derived_rate() {
    let d = derived(free_top::symmetric_top);
    let rate = &d.quantities["precession_rate"].entries()[0];
    let (i, w0) = ([2.0, 2.0, 3.0], Vector3::new(0.4, 0.0, 1.0));
    let exact = at(rate, &[("I1", 2.0), ("I3", 3.0), ("w3", 1.0)]);
    // The angle of (ω1, ω2) after integrating Euler's equations by RK4, wrapped to (−π, π].
    let run = integrate(
        &Moments::new(i).unwrap(),
        w0,
        7.0,
        Method::Rk4,
        Resolution::Step(1e-3),
        0,
    )
    .unwrap();
    let angle = run.omega.y.atan2(run.omega.x);
    let expected = (exact * 7.0 + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
        - std::f64::consts::PI;
    assert!((angle - expected).abs() < 1e-9, "{angle} vs {expected}");
}

/// The half-angles from f64 vectors: α_b between ω and the axis, α_s between ω and L.
fn cone_angles(i1: f64, i3: f64, a: f64, w3: f64) -> (f64, f64) {
    let w = Vector3::new(a, 0.0, w3);
    let l = Vector3::new(i1 * a, 0.0, i3 * w3);
    (w.angle(&Vector3::z()), w.angle(&l))
}

#[test]
fn the_cone_inequality_follows_the_sign_of_cone_order() {
    let d = derived(free_top::symmetric_top);
    let order = &d.quantities["cone_order"].entries()[0];
    let mut seen = [false; 2];
    for (i1, i3, a, w3) in [
        (2.0, 0.8, 0.2, 1.0),
        (2.0, 1.9, 0.5, 1.0),
        (2.0, 3.0, 0.5, 1.0),
        (1.0, 0.3, 0.9, 0.7),
        (1.0, 0.45, 0.3, 1.0),
    ] {
        let (alpha_b, alpha_s) = cone_angles(i1, i3, a, w3);
        let sign = at(order, &[("I1", i1), ("I3", i3), ("A", a), ("w3", w3)]);
        assert_eq!(sign > 0.0, alpha_b > alpha_s, "I1={i1} I3={i3} A={a}");
        seen[usize::from(sign > 0.0)] = true;
    }
    assert!(seen[0] && seen[1], "both orders occur among the cases");
}

/// A finite-difference Jacobian of the f64 right-hand side at ω.
fn jacobian(i: &Moments, w: Vector3<f64>) -> Matrix3<f64> {
    let h = 1e-6;
    Matrix3::from_fn(|r, c| {
        let mut e = Vector3::zeros();
        e[c] = h;
        (euler_rhs(i, &(w + e))[r] - euler_rhs(i, &(w - e))[r]) / (2.0 * h)
    })
}

#[test]
fn the_stability_table_matches_numeric_eigenvalues_for_every_ordering() {
    let d = derived(stability::axis_stability);
    let Value::Matrix(table) = &d.quantities["stability"] else {
        panic!("a matrix")
    };
    let omega_sq = entries(&d, "oscillation_frequency_squared");
    let base = [1.0, 2.0, 2.7];
    for perm in crate::model::moments::ORDERINGS {
        let i = [base[perm[0]], base[perm[1]], base[perm[2]]];
        let moments = Moments::new(i).unwrap();
        for k in 0..3 {
            let mut w = Vector3::zeros();
            w[k] = 1.3;
            let eig = jacobian(&moments, w).complex_eigenvalues();
            let growth = eig.iter().map(|z| z.re).fold(f64::MIN, f64::max);
            let frequency = eig.iter().map(|z| z.im.abs()).fold(0.0, f64::max);
            // Ω² from the derivation against the numeric spectrum: ±iΩ or ±√(−Ω²).
            let mut values = point(i, [0.0; 3]);
            values[3 + k].1 = 1.3;
            let om2 = at(&omega_sq[k], &values);
            let numeric = if growth > 1e-6 {
                -growth * growth
            } else {
                frequency * frequency
            };
            assert!(
                (om2 - numeric).abs() < 1e-6 * om2.abs(),
                "axis {k}: {om2} vs {numeric}"
            );
            let rank = {
                let mut sorted = i;
                sorted.sort_by(f64::total_cmp);
                sorted.iter().position(|x| *x == i[k]).unwrap()
            };
            let class = [1, 2, 0][rank];
            let stable = at(&table[k][class], &[]) > 0.0;
            assert_eq!(stable, growth < 1e-6, "I = {i:?}, axis {k}");
        }
    }
}

#[test]
fn the_intermediate_axis_grows_at_the_derived_rate() {
    let d = derived(stability::axis_stability);
    let sigma2 = at(
        &d.quantities["growth_rate_squared"].entries()[0],
        &point([1.0, 2.0, 3.0], [0.0, 1.0, 0.0]),
    );
    // A spin about axis 2 with a 1e-9 wobble: |ω1| grows as exp(σ t) while it is small.
    let moments = Moments::new([1.0, 2.0, 3.0]).unwrap();
    let w0 = Vector3::new(1e-9, 1.0, 1e-9);
    let r1 = integrate(&moments, w0, 10.0, Method::Rk4, Resolution::Step(1e-3), 0).unwrap();
    let r2 = integrate(&moments, w0, 14.0, Method::Rk4, Resolution::Step(1e-3), 0).unwrap();
    let measured = (r2.omega.x.abs() / r1.omega.x.abs()).ln() / 4.0;
    assert!(
        (measured - sigma2.sqrt()).abs() < 1e-4 * sigma2.sqrt(),
        "{measured} vs {}",
        sigma2.sqrt()
    );
}

#[test]
fn poinsot_gaps_and_separatrix_agree_with_the_invariants() {
    let d = derived(poinsot::poinsot);
    let gaps = entries(&d, "momentum_gap");
    let (i, w) = ([1.0, 2.0, 3.0], [1.0, 0.1, 0.5]);
    let (two_t, l) = invariants(&Moments::new(i).unwrap(), &Vector3::from(w));
    for k in 0..3 {
        let exact = at(&gaps[k], &point(i, w));
        assert!((exact - (l * l - two_t * i[k])).abs() < 1e-14, "{k}");
    }
    // REFERENCE.md's check values: 2T = 177/100, L² = 329/100.
    assert!((two_t - 1.77).abs() < 1e-15 && (l * l - 3.29).abs() < 1e-14);
    // A state with (L3/L1)² at the derived slope lies on the separatrix L² = 2T I2, and the
    // exact solution keeps the ratio as it runs to the unstable axis.
    let slope = at(
        &entries(&d, "separatrix_slope_squared")[0],
        &point(i, [0.0; 3]),
    );
    let w0 = Vector3::new(0.3, 0.05, 0.3 * i[0] * slope.sqrt() / i[2]);
    let moments = Moments::new(i).unwrap();
    let (t0, l0) = invariants(&moments, &w0);
    assert!((l0 * l0 - t0 * i[1]).abs() < 1e-15);
    let later = ExactSolution::new(&moments, w0).omega(3.0);
    let ratio = (i[2] * later.z / (i[0] * later.x)).powi(2);
    assert!((ratio - slope).abs() < 1e-12 * slope, "{ratio} vs {slope}");
}

#[test]
fn earth_euler_period_matches_the_exact_solution() {
    let d = derived(earth::earth_precession);
    let sidereal = at(
        &d.quantities["euler_period_sidereal_days"].entries()[0],
        &[],
    );
    let beta = at(&d.quantities["earth_beta"].entries()[0], &[]);
    let w3 = 2.0 * std::f64::consts::PI;
    let body = Moments::new([1.0, 1.0, 1.0 + beta]).unwrap();
    let period = ExactSolution::new(&body, Vector3::new(1e-6, 0.0, w3))
        .period()
        .unwrap();
    assert!(
        (period - sidereal).abs() < 1e-12 * sidereal,
        "{period} vs {sidereal}"
    );
    // REFERENCE.md's figures, to the digits it gives.
    assert_eq!(format!("{sidereal:.3}"), "304.456");
    let solar = at(&d.quantities["euler_period_solar_days"].entries()[0], &[]);
    assert_eq!(format!("{solar:.3}"), "303.625");
    assert_eq!(format!("{beta:.7e}"), "3.2845478e-3");
}
