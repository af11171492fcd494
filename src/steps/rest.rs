//! The author's states of rest, checked without the engine: each exact equilibrium at the
//! scene's values against a scan of the static equation for its sign changes, and each
//! equilibrium's Ω² against central differences of the equation there.

use super::check::{CheckError, H, StepCheck, at};
use crate::cas::{Expr, Zero};
use crate::derive::step_names::{Stability, Stable};
use crate::scene::Scene;
use std::collections::BTreeMap;
use std::f64::consts::PI;

/// Points of the scan over one turn: zeros closer than 2π/3600 = 0.1° apart would merge.
const SCAN_POINTS: usize = 3600;
/// Bisection halves the bracket to far below this; an exact angle evaluates to within ε.
const ANGLE_AGREEMENT: f64 = 1e-9;
/// At a bisected zero the equation is at rounding level, ~1e-16 of its size at the bracket's
/// (finite) ends; at a bisected pole (or where rounding flips the sign of a vanishing
/// denominator, as 1 + 2 cos θ + cos² θ does near π) it is far larger than at the ends.
const POLE_RATIO: f64 = 1e-6;
/// A central difference with Richardson extrapolation at h = 1e-3: O(h⁴) ≈ 1e-12 in
/// truncation and about ε|R|/h ≈ 1e-13 in rounding, relative.
const CURVATURE_AGREEMENT: f64 = 1e-7;

/// The static residual R(q) with every rate and acceleration 0 (or the acceleration `accel`).
fn residual(
    r: &Expr,
    q: &str,
    values: &BTreeMap<String, f64>,
    x: f64,
    accel: f64,
) -> Result<f64, CheckError> {
    let mut p = values.clone();
    p.insert(q.to_string(), x);
    p.insert(format!("{q}'"), 0.0);
    p.insert(format!("{q}''"), accel);
    at(r, &p)
}

/// An angle in [−π, π).
fn wrap(x: f64) -> f64 {
    (x + PI).rem_euclid(2.0 * PI) - PI
}

/// The angular distance between two angles.
fn apart(a: f64, b: f64) -> f64 {
    let d = wrap(a - b).abs();
    d.min(2.0 * PI - d)
}

/// Each exact equilibrium at the scene's values: the equation vanishes there, its cosine and
/// sine are the angle's, and for an angle the scan of one turn finds the same zeros, no more.
pub(crate) fn equilibria_check(
    scene: &Scene,
    r: &Expr,
    q: &str,
    zeros: &[Zero],
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.tolerance = ANGLE_AGREEMENT;
    let values = &scene.values;
    let f = |x: f64| residual(r, q, values, x, 0.0);
    let mut exact = Vec::new();
    let mut not_real = 0;
    for z in zeros {
        let v = at(&z.value, values)?;
        check.evaluations += 1;
        if !v.is_finite() {
            not_real += 1;
            continue;
        }
        if let Some((c, s)) = &z.trig {
            let (c, s) = (at(c, values)?, at(s, values)?);
            check.error = check
                .error
                .max((c - v.cos()).abs())
                .max((s - v.sin()).abs());
        }
        exact.push(v);
    }
    let angle = zeros.iter().any(|z| z.trig.is_some());
    let skipped = if not_real > 0 {
        format!("; {not_real} not real at these values")
    } else {
        String::new()
    };
    if !angle {
        check.method =
            format!("the static equation at each equilibrium, at the scene's values{skipped}");
        let scale = exact.iter().map(|x| x.abs()).fold(1.0, f64::max);
        for v in &exact {
            check.error = check.error.max(f(*v)?.abs() / scale);
        }
        return Ok(());
    }
    check.method = format!(
        "the zeros of the static equation over one turn ({SCAN_POINTS} points, sign changes \
         bisected, poles set aside), at the scene's values, against the exact equilibria\
         {skipped}; their cosines and sines against the angles'"
    );
    let found = zeros_over_one_turn(&f, &mut check.evaluations)?;
    for x in &found {
        let nearest = exact
            .iter()
            .map(|v| apart(*v, *x))
            .fold(f64::INFINITY, f64::min);
        if nearest > ANGLE_AGREEMENT {
            return Err(CheckError::MissedZero { at: *x });
        }
        check.error = check.error.max(nearest);
    }
    for v in &exact {
        if !found.iter().any(|x| apart(*v, *x) <= ANGLE_AGREEMENT) {
            return Err(CheckError::NotAZero { at: *v });
        }
    }
    Ok(())
}

/// The zeros of `f` over one turn: sign changes on [`SCAN_POINTS`] points, bisected, those
/// through a pole set aside. Counts its evaluations.
fn zeros_over_one_turn(
    f: &dyn Fn(f64) -> Result<f64, CheckError>,
    evaluations: &mut u64,
) -> Result<Vec<f64>, CheckError> {
    let grid: Vec<f64> = (0..SCAN_POINTS)
        .map(|i| -PI + 2.0 * PI * i as f64 / SCAN_POINTS as f64)
        .collect();
    let samples: Vec<f64> = grid.iter().map(|x| f(*x)).collect::<Result<_, _>>()?;
    *evaluations += SCAN_POINTS as u64;
    let mut found = Vec::new();
    for i in 0..SCAN_POINTS {
        let (a, b) = (grid[i], grid[i] + 2.0 * PI / SCAN_POINTS as f64);
        let (fa, fb) = (samples[i], samples[(i + 1) % SCAN_POINTS]);
        if fa == 0.0 {
            found.push(a);
        } else if fa * fb < 0.0 {
            let (mut lo, mut hi, mut flo) = (a, b, fa);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                let fm = f(mid)?;
                *evaluations += 1;
                if (fm < 0.0) == (flo < 0.0) {
                    (lo, flo) = (mid, fm);
                } else {
                    hi = mid;
                }
            }
            // A sign change through a pole (1/(1 + cos θ) at π) is not a zero: there the
            // equation grows without bound instead of vanishing.
            let x = 0.5 * (lo + hi);
            let ends = [fa, fb].into_iter().filter(|y| y.is_finite());
            let bound = ends.fold(0.0f64, |m, y| m.max(y.abs()));
            if f(x)?.abs() <= POLE_RATIO * bound {
                found.push(wrap(x));
            }
        }
    }
    Ok(found)
}

/// Each equilibrium's Ω² at the scene's values against k/m by differences: k a central
/// difference (Richardson-extrapolated) of the static equation, m its change with q''.
pub(crate) fn stability_check(
    scene: &Scene,
    r: &Expr,
    q: &str,
    cases: &[Stability],
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.tolerance = CURVATURE_AGREEMENT;
    check.method = format!(
        "Ω² at each equilibrium against k/m at the scene's values, k by central differences \
         (h = {H}, Richardson-extrapolated) and m the change of the equation with q''; and its \
         sign against the verdict"
    );
    let values = &scene.values;
    let mut unknown = Vec::new();
    for c in cases {
        let v = at(&c.at.value, values)?;
        if !v.is_finite() {
            continue;
        }
        let f = |x: f64| residual(r, q, values, x, 0.0);
        let central =
            |h: f64| -> Result<f64, CheckError> { Ok((f(v + h)? - f(v - h)?) / (2.0 * h)) };
        let k = (4.0 * central(H / 2.0)? - central(H)?) / 3.0;
        let m = residual(r, q, values, v, 1.0)? - f(v)?;
        check.evaluations += 6;
        let numeric = k / m;
        let Some(w2) = &c.omega_squared else {
            // No exact Ω² to compare: its value here is the check's to give.
            unknown.push(format!("{v:.6}: {numeric:.6e}"));
            continue;
        };
        let exact = at(w2, values)?;
        let scale = numeric.abs().max(exact.abs()).max(f64::MIN_POSITIVE);
        check.error = check.error.max((numeric - exact).abs() / scale);
        let wrong = match c.verdict {
            Stable::Always => exact <= 0.0,
            Stable::Never => exact >= 0.0,
            Stable::Where | Stable::Unknown => false,
        };
        if wrong {
            return Err(CheckError::WrongVerdict {
                at: v,
                square: exact,
            });
        }
    }
    if !unknown.is_empty() {
        check.method += &format!(
            "; Ω² by differences where it has no exact form (equilibrium: Ω²): {}",
            unknown.join(", ")
        );
    }
    Ok(())
}
