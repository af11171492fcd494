//! `energy = "Lag"`: the energy function Σ q'·∂L/∂q' − L, conserved when ∂L/∂t is identically 0.
//!
//! - Exact rule: `derive/lagrangian.rs`.
//! - Numeric route: the motion of L integrated, the energy's drift watched (`motion.rs`).

use super::{Checking, Context, conserved, scalar, scalar_of};
use crate::derive::DeriveError;
use crate::derive::lagrangian::energy;
use crate::derive::step_names::StepResult;
use crate::steps::check::{CheckError, StepCheck};
use crate::steps::motion::{Conserved, conserved_check};

pub(super) fn derive(cx: Context, of: &str) -> Result<StepResult, DeriveError> {
    let (e, rate) = energy(scalar(cx.d, of)?, &cx.scene.coordinates)?;
    conserved(e, rate)
}

pub(super) fn check(cx: Checking, of: &str, check: &mut StepCheck) -> Result<(), CheckError> {
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
        Conserved::Energy,
        check,
    )
}
