//! `equilibria = "eom"`: the states of rest of equations of motion, the real ones only (those
//! real for no values of the symbols set aside and named).
//!
//! - Exact rule: one coordinate, the zeros of the static equation (`derive/lagrangian.rs`);
//!   several, the static system solved (`derive/rest_states.rs`).
//! - Numeric route: one coordinate, a scan of the static equation for its sign changes at the
//!   scene's values (`rest.rs`); several, each state put into every static equation, and
//!   Newton's method from a grid finding the same states, no more (`rest_states.rs`).

use super::{Checking, Context, Rule, free_equations, single_equation};
use crate::derive::DeriveError;
use crate::derive::lagrangian::equilibria;
use crate::derive::step_names::StepResult;
use crate::notation::Formula;
use crate::scene::operations::Equilibria;
use crate::steps::check::{CheckError, StepCheck, equations_of};
use crate::steps::rest::equilibria_check;
use crate::steps::rest_states::states_check;

impl Rule for Equilibria {
    fn derive(&self, cx: Context, _: &mut Option<Formula>) -> Result<StepResult, DeriveError> {
        let of: &str = &self.of;
        let eqs = free_equations(cx.scene, cx.d, of, "equilibria")?;
        if eqs.len() > 1 {
            let found = crate::derive::rest_states::rest_states(eqs)?;
            return Ok(StepResult::RestStates {
                coordinates: found.coordinates,
                states: found.states,
                excluded: found.excluded,
            });
        }
        let found = equilibria(eqs, &cx.scene.values)?;
        Ok(StepResult::Equilibria {
            coordinate: found.coordinate,
            zeros: found.zeros,
            excluded: found.excluded,
        })
    }

    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError> {
        let of: &str = &self.of;
        match cx.result {
            StepResult::Equilibria {
                coordinate, zeros, ..
            } => {
                let r = single_equation(cx.d, of, coordinate)?;
                equilibria_check(cx.scene, r, coordinate, zeros, check)
            }
            StepResult::RestStates { states, .. } => {
                states_check(cx.scene, equations_of(cx.d, of)?, states, check)
            }
            _ => Err(CheckError::NotDerived),
        }
    }
}
