//! `routh = "Lag"`, `cyclic = { phi = "p" }`: Routh's procedure, R = L − Σ p φ' with each φ'
//! solved from p = ∂L/∂φ'.
//!
//! - Exact rule: `derive/routh.rs`.
//! - Numeric route: the full motion of L integrated, R against L − p φ' at every state and p's
//!   drift watched (`verify/routh.rs`).

use super::{Checking, Context, scalar, scalar_of};
use crate::derive::DeriveError;
use crate::derive::step_names::StepResult;
use crate::verify::step_check::{CheckError, StepCheck};

pub(super) fn derive(
    cx: Context,
    of: &str,
    cyclic: &[(String, String)],
) -> Result<StepResult, DeriveError> {
    Ok(StepResult::Expr(crate::derive::routh::routhian(
        scalar(cx.d, of)?,
        cyclic,
    )?))
}

pub(super) fn check(
    cx: Checking,
    of: &str,
    cyclic: &[(String, String)],
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    let StepResult::Expr(routhian) = cx.result else {
        return Err(CheckError::NotDerived);
    };
    let lagrangian = scalar_of(cx.d, of)?;
    crate::verify::routh::routh_check(cx.scene, cx.step, lagrangian, routhian, cyclic, check)
}
