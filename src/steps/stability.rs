//! `stability = "rest"`: about each state of rest, Ω² and the verdict (stable always, never, or
//! where a condition holds).
//!
//! - Exact rule: one coordinate, Ω² from the linearised equation and its sign over positive
//!   symbols (`derive/lagrangian.rs`, `derive/sign.rs`); several, the eigenvalues of M⁻¹K
//!   (`derive/rest_states.rs`).
//! - Numeric route: Ω² against central differences of the equation at each state
//!   (`rest.rs`); several, the stiffness by central differences and the eigenvalues of
//!   M⁻¹K against the verdict (`rest_states.rs`).

use super::{Checking, Context, Rule, equations, single_equation};
use crate::derive::DeriveError;
use crate::derive::lagrangian::stability;
use crate::derive::sign::{Sign, signs_over_positive};
use crate::derive::step_names::{Stability, Stable, StepResult, equilibria_source};
use crate::notation::Formula;
use crate::scene::operations;
use crate::steps::check::{CheckError, StepCheck, equations_of};
use crate::steps::rest::stability_check;
use crate::steps::rest_states::rest_stability_check;

impl Rule for operations::Stability {
    fn derive(&self, cx: Context, _: &mut Option<Formula>) -> Result<StepResult, DeriveError> {
        let of: &str = &self.of;
        let (scene, d) = (cx.scene, cx.d);
        if let Some(StepResult::RestStates {
            coordinates,
            states,
            ..
        }) = d.named.get(of)
        {
            let eqs = equations(d, equilibria_source(scene, of).unwrap_or(""))?;
            return Ok(StepResult::RestStability {
                coordinates: coordinates.clone(),
                cases: crate::derive::rest_states::rest_stability(eqs, coordinates, states)?,
            });
        }
        let Some(StepResult::Equilibria {
            coordinate, zeros, ..
        }) = d.named.get(of)
        else {
            return Err(DeriveError::Inconsistent(format!(
                "step `{of}` was validated as earlier equilibria"
            )));
        };
        let eqs = equations(d, equilibria_source(scene, of).unwrap_or(""))?;
        let cases = zeros
            .iter()
            .zip(stability(eqs, zeros)?)
            .map(|(z, w2)| Stability {
                at: z.clone(),
                // A sign the rational test cannot decide (a root in Ω²) leaves the condition.
                verdict: match &w2 {
                    None => Stable::Unknown,
                    Some(w2) => match signs_over_positive(std::slice::from_ref(w2)) {
                        Ok(s) if s[0] == Sign::Positive => Stable::Always,
                        Ok(s) if s[0] == Sign::Negative => Stable::Never,
                        _ => Stable::Where,
                    },
                },
                omega_squared: w2,
            })
            .collect();
        Ok(StepResult::Stability {
            coordinate: coordinate.clone(),
            cases,
        })
    }

    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError> {
        let of: &str = &self.of;
        let motion = equilibria_source(cx.scene, of).ok_or(CheckError::NotDerived)?;
        match cx.result {
            StepResult::Stability { coordinate, cases } => {
                let r = single_equation(cx.d, motion, coordinate)?;
                stability_check(cx.scene, r, coordinate, cases, check)
            }
            StepResult::RestStability { cases, .. } => {
                rest_stability_check(cx.scene, equations_of(cx.d, motion)?, cases, check)
            }
            _ => Err(CheckError::NotDerived),
        }
    }
}
