//! A `routh` step against the full motion: its Lagrangian's equations integrated from the
//! step's start, and at every state the Routhian, given each momentum p = ∂L/∂φ' found by
//! differences of L there, against L − Σ p φ' from the state itself; each p must also keep its
//! value (the coordinate is cyclic).

use super::motion::{ENERGY_AGREEMENT, MOTION_TIME, integrate};
use super::step_check::{CheckError, StepCheck};
use crate::base::format::short;
use crate::cas::Expr;
use crate::numeric::compiled::Program;
use crate::numeric::motion::{MOTION_TOLERANCE, state_slots};
use crate::scene::{AuthorStep, Scene};

pub(crate) fn routh_check(
    scene: &Scene,
    step: &AuthorStep,
    lagrangian: &Expr,
    routhian: &Expr,
    cyclic: &[(String, String)],
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.method = format!(
        "the Routhian against L − Σ p φ' along the full motion of L integrated from the start \
         for t = {MOTION_TIME} (Dormand–Prince, tolerance {}), each momentum p = ∂L/∂φ' by \
         differences of L, and each p's drift",
        short(MOTION_TOLERANCE)
    );
    check.tolerance = ENERGY_AGREEMENT;
    let eqs = crate::derive::lagrangian::euler_lagrange(lagrangian, &scene.coordinates)?;
    let m = integrate(scene, step, lagrangian, &eqs, &[])?;
    let n = m.coords.len();
    let l = m.compile(lagrangian)?;
    // The Routhian reads the state and, in the slots after it, each momentum.
    let mut slots = state_slots(&m.coords);
    let mut cyclic_at = Vec::new();
    for (j, (q, p)) in cyclic.iter().enumerate() {
        slots.insert(p.clone(), 3 * n + j);
        let k = m
            .coords
            .iter()
            .position(|c| *c == q)
            .ok_or(CheckError::NotDerived)?;
        cyclic_at.push(k);
    }
    let r = Program::new(&[routhian], &slots, &m.params, usize::MAX)?;
    let (mut mismatch, mut drift, mut scale, mut p_scale) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut first: Option<Vec<f64>> = None;
    for y in &m.states {
        let momenta = cyclic_at
            .iter()
            .map(|&k| m.momentum(&l, y, k))
            .collect::<Result<Vec<f64>, _>>()?;
        let mut x = y.to_vec();
        x.resize(3 * n, 0.0);
        x.extend(&momenta);
        let value = r.eval(&x, &mut Vec::new())[0];
        let lag = m.value(&l, y)?;
        let reference = lag
            - cyclic_at
                .iter()
                .zip(&momenta)
                .map(|(&k, p)| p * y[n + k])
                .sum::<f64>();
        mismatch = mismatch.max(if value.is_finite() {
            (value - reference).abs()
        } else {
            f64::INFINITY
        });
        scale = scale.max(lag.abs()).max(reference.abs());
        let start = first.get_or_insert_with(|| momenta.clone());
        for (p, p0) in momenta.iter().zip(start.iter()) {
            drift = drift.max((p - p0).abs());
            p_scale = p_scale.max(p.abs());
        }
    }
    check.evaluations = m.evaluations + m.states.len() as u64 * (2 * cyclic.len() as u64 + 2);
    check.error =
        (mismatch / scale.max(f64::MIN_POSITIVE)).max(drift / p_scale.max(f64::MIN_POSITIVE));
    Ok(())
}
