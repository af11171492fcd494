//! `energy = "Lag"`: the energy function Σ q'·∂L/∂q' − L, conserved when ∂L/∂t is identically 0.
//!
//! - Exact rule: `derive/lagrangian.rs`.
//! - Numeric route: the motion of L integrated, the energy's drift watched (`motion.rs`).

use super::{Checking, Context, Rule, conserved, conserved_route, scalar};
use crate::derive::DeriveError;
use crate::derive::lagrangian::energy;
use crate::derive::step_names::StepResult;
use crate::notation::Formula;
use crate::scene::operations::Energy;
use crate::steps::check::{CheckError, StepCheck};
use crate::steps::motion::Conserved;

impl Rule for Energy {
    fn derive(&self, cx: Context, _: &mut Option<Formula>) -> Result<StepResult, DeriveError> {
        let of: &str = &self.of;
        let (e, rate) = energy(scalar(cx.d, of)?, &cx.scene.coordinates)?;
        conserved(e, rate)
    }

    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError> {
        let of: &str = &self.of;
        conserved_route(cx, of, Conserved::Energy, check)
    }
}
