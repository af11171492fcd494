//! `frequency = "lin"`: the angular frequency of linear equations of motion, or the normal modes
//! of several coordinates.
//!
//! - Exact rule: Ω² = K/M for one coordinate (`derive/lagrangian.rs`); for several, the roots
//!   of det(K − λM) in closed form, or the pencil's eigenvalues at the scene's values by Sturm
//!   bisection where there is none (`derive/modes.rs`).
//! - Numeric route: one coordinate, the period measured on the full motion integrated about
//!   the state of rest; several, each mode against √λ of M⁻¹K by nalgebra's Schur
//!   decomposition (`motion.rs`).

use super::{Checking, Context, Rule, equations};
use crate::derive::DeriveError;
use crate::derive::lagrangian::frequency;
use crate::derive::modes::normal_modes;
use crate::derive::result_order::stable_order;
use crate::derive::step_names::StepResult;
use crate::notation::Formula;
use crate::scene::Operation;
use crate::scene::operations::Frequency;
use crate::scene::operations::Linearise;
use crate::steps::check::{CheckError, StepCheck, equations_of};
use crate::steps::motion::{modes_agreement, modes_check, period_check};

impl Rule for Frequency {
    fn derive(&self, cx: Context, _: &mut Option<Formula>) -> Result<StepResult, DeriveError> {
        let of: &str = &self.of;
        Ok(match equations(cx.d, of)? {
            eqs @ [_] => StepResult::Expr(frequency(eqs)?),
            eqs => match normal_modes(eqs, &cx.scene.values)? {
                StepResult::Modes(mut modes) => {
                    stable_order(&mut modes, cx.scene);
                    StepResult::Modes(modes)
                }
                numeric => numeric,
            },
        })
    }

    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError> {
        let of: &str = &self.of;
        let scene = cx.scene;
        match cx.result {
            StepResult::Modes(modes) => modes_check(scene, equations_of(cx.d, of)?, modes, check),
            StepResult::NumericModes { frequencies, .. } => {
                modes_agreement(scene, equations_of(cx.d, of)?, frequencies, check)
            }
            StepResult::Expr(omega) => {
                let source = scene.steps.iter().find(|s| s.name == of);
                let Some(Operation::Linearise(Linearise {
                    of: motion_of,
                    about,
                })) = source.map(|s| &s.op)
                else {
                    return Err(CheckError::NotDerived);
                };
                period_check(scene, equations_of(cx.d, motion_of)?, about, omega, check)
            }
            _ => Err(CheckError::NotDerived),
        }
    }
}
