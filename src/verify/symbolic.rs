//! The symbolic checks of a scene: its claims and `gives` against the derivation, and its
//! record (`[expect]`) against what was derived now.

use super::{
    ClaimResult, RegressionResult, StepRecord, check_claims, check_regressions, check_step_records,
    claim_form, gives,
};
use crate::derive::Derivation;
use crate::model::catalogue::Stage;
use crate::scene::Scene;

/// The symbolic checks: the notes' claims and the recorded results. They depend on the scene
/// and its derivation only, never on the fidelity.
pub fn verify_symbolic(
    scene: &Scene,
    d: &Derivation,
    plan: &crate::plan::Plan,
) -> Result<SymbolicChecks, crate::derive::DeriveError> {
    let mut claims = if plan.runs(Stage::Claims) {
        check_claims(scene, d)?
    } else {
        Vec::new()
    };
    if plan.runs(Stage::Steps) {
        claims.extend(gives::check_gives(scene, d)?);
    }
    claim_form::present_claims(scene, &mut claims)?;
    let regressions = if plan.runs(Stage::Regression) {
        check_regressions(scene, d)?
    } else {
        Vec::new()
    };
    let step_records = if plan.runs(Stage::Regression) && plan.runs(Stage::Steps) {
        check_step_records(scene, d)?
    } else {
        Vec::new()
    };
    Ok(SymbolicChecks {
        claims,
        regressions,
        step_records,
    })
}

/// What [`verify_symbolic`] finds.
pub struct SymbolicChecks {
    pub claims: Vec<ClaimResult>,
    pub regressions: Vec<RegressionResult>,
    pub step_records: Vec<StepRecord>,
}
