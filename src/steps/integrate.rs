//! `integrate = "…"`, `over = { x = ["0", "L"] }`: a definite integral, innermost variable first,
//! shown with its limits.
//!
//! - Exact rule: `derive/integral.rs`.
//! - Numeric route: adaptive quadrature at the scene's values (`verify/integral.rs`).

use super::{Checking, Context};
use crate::cas::Expr;
use crate::derive::DeriveError;
use crate::derive::step_names::{StepResult, expand_names, expand_ranges};
use crate::notation::Formula;
use crate::verify::integral::quadrature_check;
use crate::verify::step_check::{CheckError, StepCheck};

/// The integral, and the statement the page shows: the integral with its limits.
pub(super) fn derive(
    cx: Context,
    of: &Expr,
    over: &[(String, Expr, Expr)],
    shown: &mut Option<Formula>,
) -> Result<StepResult, DeriveError> {
    let f = expand_names(cx.scene, cx.d, cx.step, of)?;
    let over = expand_ranges(cx.scene, cx.d, cx.step, over)?;
    let (value, domain) = crate::derive::integral::integral(&f, &over)?;
    *shown = Some(crate::derive::inertia::integral_formula(
        Formula::Expr(Expr::sym(&cx.step.name)),
        &f,
        &domain,
        &value,
    ));
    Ok(StepResult::Expr(value))
}

pub(super) fn check(
    cx: Checking,
    of: &Expr,
    over: &[(String, Expr, Expr)],
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    let StepResult::Expr(exact) = cx.result else {
        return Err(CheckError::NotDerived);
    };
    let f = expand_names(cx.scene, cx.d, cx.step, of)?;
    let over = expand_ranges(cx.scene, cx.d, cx.step, over)?;
    quadrature_check(&cx.scene.values, &f, &over, exact, check)
}
