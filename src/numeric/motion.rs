//! Equations of motion R(q, q', q'') = 0 as a first-order system for an integrator: each
//! residual is linear in the accelerations, so at every state they solve M a = −R(a = 0), M's
//! columns R(a = e_j) − R(0). Shared by the steps' checks and the motion plots.

use crate::cas::{EvalError, Expr};
use std::collections::BTreeMap;

/// Dormand–Prince's tolerance along a motion, and its step cap.
pub const MOTION_TOLERANCE: f64 = 1e-10;
pub const MOTION_STEPS: u64 = 200_000;
/// A coordinate's default start (at rest), when none is given.
pub const DEFAULT_START: f64 = 0.5;

#[derive(Debug, thiserror::Error)]
pub enum MotionError {
    #[error(transparent)]
    Eval(#[from] EvalError),
    #[error("the equations cannot be solved for the accelerations here (a singular mass matrix)")]
    Singular,
}

/// `e` at a point (π stays the number).
fn at(e: &Expr, point: &BTreeMap<String, f64>) -> Result<f64, EvalError> {
    e.eval(&|s| point.get(s).copied().filter(|_| s != "pi"))
}

/// The names at a state: the parameters, each coordinate and rate from `y` (coordinates, then
/// rates), each acceleration from `a`.
pub fn state(
    params: &BTreeMap<String, f64>,
    coords: &[&String],
    y: &[f64],
    a: &[f64],
) -> BTreeMap<String, f64> {
    let n = coords.len();
    let mut p = params.clone();
    for (k, q) in coords.iter().enumerate() {
        p.insert((*q).clone(), y[k]);
        p.insert(format!("{q}'"), y[n + k]);
        p.insert(format!("{q}''"), a[k]);
    }
    p
}

/// The start: each coordinate's value in `params` (else [`DEFAULT_START`]), then each rate's
/// (else 0).
pub fn start(params: &BTreeMap<String, f64>, coords: &[&String]) -> Vec<f64> {
    coords
        .iter()
        .map(|q| params.get(*q).copied().unwrap_or(DEFAULT_START))
        .chain(
            coords
                .iter()
                .map(|q| params.get(&format!("{q}'")).copied().unwrap_or(0.0)),
        )
        .collect()
}

/// y' for the equations of motion at state y: the rates, then the accelerations.
pub fn rates(
    eqs: &[(String, Expr)],
    params: &BTreeMap<String, f64>,
    coords: &[&String],
    y: &[f64],
) -> Result<Vec<f64>, MotionError> {
    let n = coords.len();
    let residuals = |a: &[f64]| -> Result<Vec<f64>, MotionError> {
        let p = state(params, coords, y, a);
        Ok(eqs
            .iter()
            .map(|(_, e)| at(e, &p))
            .collect::<Result<_, _>>()?)
    };
    let zero = vec![0.0; n];
    let f0 = residuals(&zero)?;
    let mut m = nalgebra::DMatrix::zeros(n, n);
    for j in 0..n {
        let mut unit = zero.clone();
        unit[j] = 1.0;
        let fj = residuals(&unit)?;
        for i in 0..n {
            m[(i, j)] = fj[i] - f0[i];
        }
    }
    let a = m
        .lu()
        .solve(&nalgebra::DVector::from_iterator(n, f0.iter().map(|x| -x)))
        .ok_or(MotionError::Singular)?;
    Ok(y[n..].iter().copied().chain(a.iter().copied()).collect())
}
