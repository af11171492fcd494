//! `linearise = "eom"`, `about = { theta = "0" }`: the equations of motion to first order about
//! a state of rest.
//!
//! - Exact rule: `derive/lagrangian.rs`; a state that leaves anything over is not at rest and
//!   is refused.
//! - Numeric route: the full equations against the linear ones at random states near the
//!   state of rest (`motion.rs`).
//! - On the page: each linearised equation of motion `… = 0`.

use super::page::Wording;
use super::{Checking, Context, Rule, free_equations, simplified};
use crate::cas::{self, Expr};
use crate::derive::DeriveError;
use crate::derive::lagrangian::linearise;
use crate::derive::step_names::StepResult;
use crate::notation::Formula;
use crate::scene::operations::Linearise;
use crate::steps::check::{CheckError, StepCheck, equations_of};
use crate::steps::motion::linear_check;
use std::collections::BTreeMap;

impl Rule for Linearise {
    fn derive(&self, cx: Context, _: &mut Option<Formula>) -> Result<StepResult, DeriveError> {
        let of: &str = &self.of;
        let about: &BTreeMap<String, Expr> = &self.about;
        let eqs = free_equations(cx.scene, cx.d, of, "linearise")?;
        let (rest, linear) = linearise(eqs, about, &cx.scene.coordinates)?;
        // A state of rest leaves nothing over: else it is not an equilibrium.
        let left = cas::simplify_all(rest)?;
        if let Some((k, r)) = left.iter().enumerate().find(|(_, r)| !r.is_zero()) {
            return Err(DeriveError::NotDerivable(format!(
                "the state given by `about` is not at rest: the equation of `{}` leaves {} there, \
             not 0; give an equilibrium",
                eqs[k].0,
                r.to_text()
            )));
        }
        simplified(linear)
    }

    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError> {
        let of: &str = &self.of;
        let about: &BTreeMap<String, Expr> = &self.about;
        let StepResult::Equations(linear) = cx.result else {
            return Err(CheckError::NotDerived);
        };
        linear_check(
            cx.scene,
            equations_of(cx.d, of)?,
            linear,
            about,
            cx.seed,
            check,
        )
    }

    fn wording(&self) -> Wording<'_> {
        Wording {
            equation: Some(("linearised equation", "")),
            ..Wording::default()
        }
    }
}
