//! States of rest of several coordinates, checked without the engine: each exact state put into
//! every static equation at the scene's values, and, when every coordinate is an angle, Newton's
//! method from a grid over the torus finding the same states, no more; about each state the
//! stiffness K by central differences against the exact one, and the eigenvalues of M⁻¹K (M the
//! change of the equations with the accelerations) against the verdict.

use super::check::{CheckError, H, StepCheck, at};
use crate::cas::{Expr, Zero};
use crate::derive::step_names::{Stable, StateStability};
use crate::scene::Scene;
use std::collections::BTreeMap;
use std::f64::consts::PI;

/// An exact state and one Newton found are the same within this (radians).
const STATE_AGREEMENT: f64 = 1e-9;
/// K by Richardson-extrapolated central differences: O(h⁴) ≈ 1e-12, relative.
const STIFFNESS_AGREEMENT: f64 = 1e-7;

/// The residuals at rest with the coordinates at `x` and the accelerations at `a`.
fn residuals(
    eqs: &[(String, Expr)],
    values: &BTreeMap<String, f64>,
    x: &[f64],
    a: &[f64],
) -> Result<Vec<f64>, CheckError> {
    let mut p = values.clone();
    for (k, (q, _)) in eqs.iter().enumerate() {
        p.insert(q.clone(), x[k]);
        p.insert(format!("{q}'"), 0.0);
        p.insert(format!("{q}''"), a[k]);
    }
    eqs.iter().map(|(_, r)| at(r, &p)).collect()
}

/// The Jacobian ∂R_i/∂q_j at rest by central differences with step h.
fn jacobian(
    eqs: &[(String, Expr)],
    values: &BTreeMap<String, f64>,
    x: &[f64],
    h: f64,
) -> Result<nalgebra::DMatrix<f64>, CheckError> {
    let n = x.len();
    let zero = vec![0.0; n];
    let mut j = nalgebra::DMatrix::zeros(n, n);
    for c in 0..n {
        let (mut up, mut down) = (x.to_vec(), x.to_vec());
        up[c] += h;
        down[c] -= h;
        let (fu, fd) = (
            residuals(eqs, values, &up, &zero)?,
            residuals(eqs, values, &down, &zero)?,
        );
        for r in 0..n {
            j[(r, c)] = (fu[r] - fd[r]) / (2.0 * h);
        }
    }
    Ok(j)
}

fn wrap(x: f64) -> f64 {
    (x + PI).rem_euclid(2.0 * PI) - PI
}

/// The distance between two states, each angle taken round the circle.
fn apart(a: &[f64], b: &[f64], angles: bool) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            if angles {
                let d = wrap(x - y).abs();
                d.min(2.0 * PI - d)
            } else {
                (x - y).abs()
            }
        })
        .fold(0.0, f64::max)
}

/// Each exact state at the scene's values, put back; for angles, the states Newton finds from a
/// grid over the torus against them.
pub(crate) fn states_check(
    scene: &Scene,
    eqs: &[(String, Expr)],
    states: &[Vec<Zero>],
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.tolerance = STATE_AGREEMENT;
    let values = &scene.values;
    let n = eqs.len();
    let zero = vec![0.0; n];
    let mut exact: Vec<Vec<f64>> = Vec::new();
    for state in states {
        let x: Vec<f64> = state
            .iter()
            .map(|z| at(&z.value, values))
            .collect::<Result<_, _>>()?;
        if x.iter().all(|v| v.is_finite()) {
            let r = residuals(eqs, values, &x, &zero)?;
            let scale = jacobian(eqs, values, &x, H)?.amax().max(1.0);
            check.evaluations += 1 + 2 * n as u64;
            check.error = check
                .error
                .max(r.iter().fold(0.0, |m, v| f64::max(m, v.abs())) / scale);
            exact.push(x);
        }
    }
    let angles = states.iter().flatten().all(|z| z.trig.is_some());
    if !angles {
        check.method = "every static equation at each state of rest, at the scene's values".into();
        return Ok(());
    }
    // A grid of 256 starts for two coordinates, fewer a coordinate for more.
    let per: usize = [0, 0, 16, 7, 4][n.min(4)];
    check.method = format!(
        "every static equation at each state of rest, and Newton's method from a grid of \
         {per}^{n} starts over the torus at the scene's values, against the exact states"
    );
    let mut found: Vec<Vec<f64>> = Vec::new();
    for index in 0..per.pow(n as u32) {
        let start: Vec<f64> = (0..n)
            .map(|k| {
                -PI + 2.0 * PI * (((index / per.pow(k as u32)) % per) as f64 + 0.5) / per as f64
            })
            .collect();
        let x = newton_on_torus(eqs, values, start, check)?;
        if let Some(x) = x.filter(|x| !found.iter().any(|f| apart(f, x, true) < 1e-6)) {
            found.push(x);
        }
    }
    for f in &found {
        let nearest = exact
            .iter()
            .map(|e| apart(e, f, true))
            .fold(f64::INFINITY, f64::min);
        if nearest > 1e-6 {
            return Err(CheckError::MissedState {
                at: format!("{f:.9?}"),
            });
        }
        check.error = check.error.max(nearest);
    }
    for e in &exact {
        if !found.iter().any(|f| apart(e, f, true) < 1e-6) {
            return Err(CheckError::NotAState {
                at: format!("{e:.9?}"),
            });
        }
    }
    Ok(())
}

/// Newton's method on the static equations from `x`, each angle kept in (−π, π]: the state it
/// converges to, or none.
fn newton_on_torus(
    eqs: &[(String, Expr)],
    values: &BTreeMap<String, f64>,
    mut x: Vec<f64>,
    check: &mut StepCheck,
) -> Result<Option<Vec<f64>>, CheckError> {
    let n = eqs.len();
    let zero = vec![0.0; n];
    for _ in 0..40 {
        let r = residuals(eqs, values, &x, &zero)?;
        let j = jacobian(eqs, values, &x, 1e-6)?;
        check.evaluations += 1 + 2 * n as u64;
        let Some(step) = j.lu().solve(&nalgebra::DVector::from_vec(r)) else {
            break;
        };
        for k in 0..n {
            x[k] = wrap(x[k] - step[k]);
        }
        if step.amax() < 1e-14 {
            break;
        }
    }
    let r = residuals(eqs, values, &x, &zero)?;
    let scale = jacobian(eqs, values, &x, H)?.amax().max(1.0);
    Ok(r.iter().all(|v| v.abs() < 1e-12 * scale).then_some(x))
}

/// About each state real at the scene's values: K by central differences (Richardson) against
/// the exact stiffness, and the eigenvalues of M⁻¹K against the verdict.
pub(crate) fn rest_stability_check(
    scene: &Scene,
    eqs: &[(String, Expr)],
    cases: &[StateStability],
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.tolerance = STIFFNESS_AGREEMENT;
    check.method = format!(
        "the stiffness K at each state of rest against central differences of the static \
         equations (h = {H}, Richardson-extrapolated) at the scene's values, and the signs of \
         the eigenvalues of M⁻¹K (M the change of the equations with the accelerations) against \
         the verdict"
    );
    let values = &scene.values;
    let n = eqs.len();
    for c in cases {
        let x: Vec<f64> =
            c.at.iter()
                .map(|z| at(&z.value, values))
                .collect::<Result<_, _>>()?;
        if !x.iter().all(|v| v.is_finite()) {
            continue;
        }
        let k = (jacobian(eqs, values, &x, H / 2.0)? * 4.0 - jacobian(eqs, values, &x, H)?) / 3.0;
        let exact = nalgebra::DMatrix::from_iterator(
            n,
            n,
            c.stiffness
                .iter()
                .map(|e| at(e, values))
                .collect::<Result<Vec<f64>, _>>()?,
        )
        .transpose();
        check.evaluations += 4 * n as u64 + n as u64 * n as u64;
        let scale = exact.amax().max(f64::MIN_POSITIVE);
        check.error = check.error.max((&k - &exact).amax() / scale);
        let zero = vec![0.0; n];
        let base = residuals(eqs, values, &x, &zero)?;
        let mut m = nalgebra::DMatrix::zeros(n, n);
        for j in 0..n {
            let mut unit = zero.clone();
            unit[j] = 1.0;
            let r = residuals(eqs, values, &x, &unit)?;
            for i in 0..n {
                m[(i, j)] = r[i] - base[i];
            }
        }
        let Some(m_inv) = m.try_inverse() else {
            return Err(CheckError::Singular);
        };
        let eigen =
            crate::base::float::complex_eigenvalues(m_inv * &k).ok_or(CheckError::NoEigenvalues)?;
        let all_positive = eigen
            .iter()
            .all(|z| z.re > 0.0 && z.im.abs() <= 1e-9 * z.re.abs().max(1.0));
        let wrong = match c.verdict {
            Stable::Always => !all_positive,
            Stable::Never => all_positive,
            Stable::Where | Stable::Unknown => false,
        };
        if wrong {
            return Err(CheckError::WrongStateVerdict {
                at: format!("{x:.9?}"),
                squares: format!(
                    "{:?}",
                    eigen.iter().map(|z| (z.re, z.im)).collect::<Vec<_>>()
                ),
            });
        }
    }
    Ok(())
}
