//! `momentum = "q"`, `of = "Lag"`: the generalised momentum ∂L/∂q', conserved when ∂L/∂q is
//! identically 0.
//!
//! - Exact rule: `derive/lagrangian.rs`.
//! - Numeric route: the motion of L integrated, the momentum's drift watched (or its change
//!   against the force, when it is not conserved) (`motion.rs`).

use super::{Checking, Context, conserved, scalar, scalar_of};
use crate::derive::DeriveError;
use crate::derive::lagrangian::momentum;
use crate::derive::step_names::StepResult;
use crate::steps::check::{CheckError, StepCheck};
use crate::steps::motion::{Conserved, conserved_check};

pub(super) fn derive(cx: Context, of: &str, coordinate: &str) -> Result<StepResult, DeriveError> {
    let (p, force) = momentum(scalar(cx.d, of)?, coordinate)?;
    conserved(p, force)
}

pub(super) fn check(
    cx: Checking,
    of: &str,
    coordinate: &str,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    let StepResult::Conserved { value, conserved } = cx.result else {
        return Err(CheckError::NotDerived);
    };
    let lagrangian = scalar_of(cx.d, of)?;
    conserved_check(
        cx.scene,
        cx.step,
        lagrangian,
        value,
        *conserved,
        Conserved::Momentum(coordinate),
        check,
    )
}
