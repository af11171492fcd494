//! Equations of motion R(q, q', q'') = 0 as a first-order system for an integrator: each
//! residual is linear in the accelerations, so at every state they solve M a = −R(a = 0), M's
//! columns R(a = e_j) − R(0). Shared by the steps' checks and the motion plots.

use super::compiled::Program;
use super::ode::OdeError;
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

/// Equations of motion compiled for an integrator: each residual with the scene's values folded
/// in and the state read from slots (coordinates, rates, then accelerations).
pub struct MotionSystem {
    residuals: Program,
    n: usize,
    /// The multipliers solved with the accelerations (slots 3n on), one per constraint row.
    m: usize,
}

impl MotionSystem {
    /// A name without a value is the integrator's error at the start, where evaluating the
    /// residuals would first meet it.
    pub fn new(
        eqs: &[(String, Expr)],
        params: &BTreeMap<String, f64>,
        coords: &[&String],
        multipliers: &[&String],
    ) -> Result<MotionSystem, OdeError> {
        let mut slots = state_slots(coords);
        for (j, lambda) in multipliers.iter().enumerate() {
            slots.insert((*lambda).clone(), 3 * coords.len() + j);
        }
        let exprs: Vec<&Expr> = eqs.iter().map(|(_, e)| e).collect();
        // The accelerations and multipliers (slots 2n on) are all that change between the
        // evaluations of one state.
        let residuals =
            Program::new(&exprs, &slots, params, 2 * coords.len()).map_err(|e| OdeError::Rhs {
                t: 0.0,
                message: MotionError::from(e).to_string(),
            })?;
        Ok(MotionSystem {
            residuals,
            n: coords.len(),
            m: multipliers.len(),
        })
    }

    /// y' at state y: the rates, then the accelerations (solved with the multipliers, every
    /// residual being linear in both).
    pub fn rates(&self, y: &[f64]) -> Result<Vec<f64>, MotionError> {
        let (n, size) = (self.n, self.n + self.m);
        let mut x = Vec::with_capacity(2 * n + size);
        x.extend_from_slice(&y[..2 * n]);
        x.resize(2 * n + size, 0.0);
        let mut registers = Vec::new();
        let f0 = self.residuals.eval(&x, &mut registers);
        let mut m = nalgebra::DMatrix::zeros(size, size);
        for j in 0..size {
            x[2 * n + j] = 1.0;
            let fj = self.residuals.eval_varying(&x, &mut registers);
            x[2 * n + j] = 0.0;
            for i in 0..size {
                m[(i, j)] = fj[i] - f0[i];
            }
        }
        let a = m
            .lu()
            .solve(&nalgebra::DVector::from_iterator(
                size,
                f0.iter().map(|x| -x),
            ))
            .ok_or(MotionError::Singular)?;
        Ok(y[n..2 * n]
            .iter()
            .copied()
            .chain(a.iter().take(n).copied())
            .collect())
    }
}

/// The rows of equations of motion that are coordinates' (first), and those that are
/// constraints' under their multipliers' names (after).
pub fn split_rows<'a>(
    eqs: &'a [(String, Expr)],
    coordinates: &BTreeMap<String, String>,
) -> (Vec<&'a String>, Vec<&'a String>) {
    eqs.iter()
        .map(|(q, _)| q)
        .partition(|q| coordinates.contains_key(*q))
}

/// Each state name's slot: coordinate k at k, its rate at n + k, its acceleration at 2n + k.
pub fn state_slots(coords: &[&String]) -> BTreeMap<String, usize> {
    let n = coords.len();
    let mut slots = BTreeMap::new();
    for (k, q) in coords.iter().enumerate() {
        slots.insert((*q).clone(), k);
        slots.insert(format!("{q}'"), n + k);
        slots.insert(format!("{q}''"), 2 * n + k);
    }
    slots
}
