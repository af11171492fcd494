//! `momentum = "q"`, `of = "Lag"`: the generalised momentum ∂L/∂q', conserved when ∂L/∂q is
//! identically 0.
//!
//! - Exact rule: `derive/lagrangian.rs`.
//! - Numeric route: the motion of L integrated, the momentum's drift watched (or its change
//!   against the force, when it is not conserved) (`motion.rs`).
//! - On the page: p = …, conserved when the Lagrangian does not depend on the coordinate.

use super::page::Wording;
use super::{Checking, Context, Rule, conserved, conserved_route, scalar};
use crate::derive::DeriveError;
use crate::derive::lagrangian::momentum;
use crate::derive::step_names::StepResult;
use crate::notation::Formula;
use crate::scene::operations::Momentum;
use crate::steps::check::{CheckError, StepCheck};
use crate::steps::motion::Conserved;

impl Rule for Momentum {
    fn derive(&self, cx: Context, _: &mut Option<Formula>) -> Result<StepResult, DeriveError> {
        let of: &str = &self.of;
        let coordinate: &str = &self.coordinate;
        let (p, force) = momentum(scalar(cx.d, of)?, coordinate)?;
        conserved(p, force)
    }

    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError> {
        let of: &str = &self.of;
        let coordinate: &str = &self.coordinate;
        conserved_route(cx, of, Conserved::Momentum(coordinate), check)
    }

    /// Conserved when L does not depend on its coordinate.
    fn wording(&self) -> Wording<'_> {
        Wording {
            conserved_in: Some(&self.coordinate),
            ..Wording::default()
        }
    }
}
