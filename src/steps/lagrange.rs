//! `lagrange = "Lag"`, with `constraints = { T = "…" }` if any: the Euler–Lagrange equations,
//! d/dt ∂L/∂q' − ∂L/∂q − Σ λ ∂f/∂q = 0, each constraint differentiated to the accelerations
//! under its multiplier's name.
//!
//! - Exact rule: `derive/lagrangian.rs` and `derive/constraints.rs`; a Lagrangian built by
//!   substituting a velocity constraint that does not integrate is refused.
//! - Numeric route: the motion integrated from the start, the energy Σ q'·∂L/∂q' − L (found by
//!   differences) and each constraint's drift watched (`motion.rs`).
//! - On the page: each equation of motion `… = 0`, and each multiplier's constraint.

use super::page::Wording;
use super::{Checking, Context, Rule, scalar, scalar_of, simplified};
use crate::cas::Expr;
use crate::derive::constraints::{does_not_integrate, with_multipliers};
use crate::derive::lagrangian::euler_lagrange;
use crate::derive::step_names::{StepResult, replacements};
use crate::derive::{Derivation, DeriveError};
use crate::notation::Formula;
use crate::scene::operations::Lagrange;
use crate::scene::operations::{Be, Differentiate, Substitute};
use crate::scene::{Operation, Scene};
use crate::steps::check::{CheckError, StepCheck};
use crate::steps::motion::energy_check;

impl Rule for Lagrange {
    fn derive(&self, cx: Context, _: &mut Option<Formula>) -> Result<StepResult, DeriveError> {
        let of: &str = &self.of;
        let constraints: &[(String, Expr)] = &self.constraints;
        refuse_substituted_rolling(cx.scene, cx.d, of)?;
        let eqs = euler_lagrange(scalar(cx.d, of)?, &cx.scene.coordinates)?;
        simplified(with_multipliers(eqs, constraints, &cx.scene.coordinates)?)
    }

    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError> {
        let of: &str = &self.of;
        let constraints: &[(String, Expr)] = &self.constraints;
        let StepResult::Equations(eqs) = cx.result else {
            return Err(CheckError::NotDerived);
        };
        energy_check(
            cx.scene,
            cx.step,
            scalar_of(cx.d, of)?,
            eqs,
            constraints,
            check,
        )
    }

    /// A multiplier's equation is its constraint, differentiated.
    fn wording(&self) -> Wording<'_> {
        Wording {
            constraints: &self.constraints,
            ..Wording::default()
        }
    }
}

/// A Lagrangian built (through `be`, `differentiate` and `substitute` steps) from a
/// substitution of a velocity constraint that does not integrate gives equations that are not
/// the motion's (SymPy's rolling-disc example by Lagrange's method is one such): refused, with
/// the constraint's right place, on the `lagrange` step.
fn refuse_substituted_rolling(scene: &Scene, d: &Derivation, of: &str) -> Result<(), DeriveError> {
    let mut pending = vec![of.to_string()];
    let mut seen = std::collections::BTreeSet::new();
    while let Some(name) = pending.pop() {
        if !seen.insert(name.clone()) {
            continue;
        }
        let Some(step) = scene.steps.iter().find(|s| s.name == name) else {
            continue;
        };
        let used = match &step.op {
            Operation::Be(Be(e)) | Operation::Differentiate(Differentiate { of: e, .. }) => e,
            Operation::Substitute(Substitute { of: e, set }) => {
                for (rate, value) in replacements(scene, d, step, set)? {
                    if does_not_integrate(&rate, &value, &scene.coordinates)? {
                        return Err(DeriveError::NotDerivable(format!(
                            "its Lagrangian comes from step `{}` (line {}), which puts in {rate} = {}, \
                             a velocity constraint that does not integrate to a relation among the \
                             coordinates: Lagrange's equations of the substituted L are not the \
                             motion's. Take L before the substitution and write the constraint on \
                             this step, `constraints = {{ lam = \"{rate} - ({})\" }}`, with `lam` \
                             a symbol declared in [symbols] (docs/scenes.md, `lagrange` with \
                             constraints)",
                            step.name,
                            step.line,
                            value.to_text(),
                            value.to_text()
                        )));
                    }
                }
                e
            }
            _ => continue,
        };
        pending.extend(used.symbols());
    }
    Ok(())
}
