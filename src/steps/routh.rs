//! `routh = "Lag"`, `cyclic = { phi = "p" }`: Routh's procedure, R = L − Σ p φ' with each φ'
//! solved from p = ∂L/∂φ'.
//!
//! - Exact rule: `routhian`.
//! - Numeric route: the full motion of L integrated, R against L − p φ' at every state and p's
//!   drift watched (`routh_check`).

use super::check::{CheckError, StepCheck};
use super::motion::{ENERGY_AGREEMENT, MOTION_TIME, integrate};
use super::{Checking, Context, Rule, scalar, scalar_of};
use crate::base::format::short;
use crate::cas::{self, Expr};
use crate::derive::DeriveError;
use crate::derive::solve::solve_system;
use crate::derive::step_names::StepResult;
use crate::notation::Formula;
use crate::numeric::compiled::Program;
use crate::numeric::motion::{MOTION_TOLERANCE, state_slots};
use crate::scene::operations::Routh;
use crate::scene::{AuthorStep, Scene};

impl Rule for Routh {
    fn derive(&self, cx: Context, _: &mut Option<Formula>) -> Result<StepResult, DeriveError> {
        let of: &str = &self.of;
        let cyclic: &[(String, String)] = &self.cyclic;
        Ok(StepResult::Expr(routhian(scalar(cx.d, of)?, cyclic)?))
    }

    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError> {
        let of: &str = &self.of;
        let cyclic: &[(String, String)] = &self.cyclic;
        let StepResult::Expr(routhian) = cx.result else {
            return Err(CheckError::NotDerived);
        };
        let lagrangian = scalar_of(cx.d, of)?;
        routh_check(cx.scene, cx.step, lagrangian, routhian, cyclic, check)
    }
}

// A `routh` step against the full motion: its Lagrangian's equations integrated from the
// step's start, and at every state the Routhian, given each momentum p = ∂L/∂φ' found by
// differences of L there, against L − Σ p φ' from the state itself; each p must also keep its
// value (the coordinate is cyclic).

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

// Routh's procedure: for cyclic coordinates φ (∂L/∂φ = 0) with conserved momenta
// p = ∂L/∂φ', the Routhian R = L − Σ p φ' with each φ' solved from its momentum, a function
// of the remaining coordinates, their rates and the momenta as constants.

/// The Routhian of `lagrangian` for the `cyclic` coordinates, each with its momentum's symbol.
pub fn routhian(lagrangian: &Expr, cyclic: &[(String, String)]) -> Result<Expr, DeriveError> {
    for (q, _) in cyclic {
        let force = cas::simplify(&lagrangian.diff(q)?)?;
        if !force.is_zero() {
            return Err(DeriveError::NotDerivable(format!(
                "`{q}` is not cyclic: the Lagrangian depends on it (∂L/∂{q} = {}), so its \
                 momentum is not conserved",
                force.to_text()
            )));
        }
    }
    // p = ∂L/∂φ' for each: linear in the rates, as L is quadratic in them.
    let mut eqs = Vec::new();
    for (q, p) in cyclic {
        let momentum = lagrangian.diff(&format!("{q}'"))?;
        eqs.push((p.clone(), Expr::minus(momentum, Expr::sym(p))));
    }
    let rates: Vec<String> = cyclic.iter().map(|(q, _)| format!("{q}'")).collect();
    let solved = solve_system(&eqs, &rates)?;
    let mut terms = vec![lagrangian.clone()];
    for (q, p) in cyclic {
        terms.push(Expr::mul(vec![
            Expr::int(-1),
            Expr::sym(p),
            Expr::sym(&format!("{q}'")),
        ]));
    }
    let routhian = Expr::add(terms)
        .substitute(&|s| solved.iter().find(|(u, _)| u == s).map(|(_, v)| v.clone()));
    Ok(cas::simplify(&routhian)?)
}
