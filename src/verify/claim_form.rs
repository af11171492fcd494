//! The derived side of a claim as a box prints it beside the notes' or a mistaken form: in the
//! form a textbook prints (`cas::present_all`), as a step's result is, not the raw substitution
//! of the claim's quantity (√(g m/(7m/5 (R² − 2rR + r²)) (R − r)) for √(5g/(7(R − r)))).
//! The form never changes the value: the build's guard reads the printed form back and checks
//! it against `derived`.

use super::ClaimResult;
use crate::cas::{self, CasError};
use crate::derive::algebra::Value;
use crate::scene::{Scene, Verdict};

/// Sets `shown` on every claim whose derived side a page prints (one that does not agree, a
/// single formula, not rounded, not a sign in words), where the presented form differs.
pub fn present_claims(scene: &Scene, claims: &mut [ClaimResult]) -> Result<(), CasError> {
    let wanted: Vec<(usize, cas::Expr)> = claims
        .iter()
        .enumerate()
        .filter(|(_, c)| {
            c.verdict != Verdict::Agrees
                && c.precision.is_none()
                && c.problem.is_none()
                && c.sign_words().is_none()
        })
        .filter_map(|(i, c)| match &c.derived {
            Some(Value::Scalar(e)) => Some((i, e.clone())),
            _ => None,
        })
        .collect();
    if wanted.is_empty() {
        return Ok(());
    }
    let exprs = wanted.iter().map(|(_, e)| e.clone()).collect();
    let forms = cas::present_all(
        exprs,
        scene.signed_names(),
        scene.declared.clone(),
        crate::notation::printed_length,
    )?;
    for ((i, derived), form) in wanted.into_iter().zip(forms) {
        if form != derived {
            claims[i].shown = Some(form);
        }
    }
    Ok(())
}
