//! `series = "…"`, `about = { x = "0" }`, `order = n`: a Taylor series to the n-th power.
//!
//! - Exact rule: `derive/series.rs`.
//! - Numeric route: the expression as written against its series at four steps h, h/2, h/4,
//!   h/8 from the point, the remainder shrinking like h^(order+1) (`verify/series.rs`).

use super::{Checking, Context};
use crate::cas::Expr;
use crate::derive::DeriveError;
use crate::derive::step_names::{StepResult, expand_names};
use crate::verify::series::remainder_check;
use crate::verify::step_check::{CheckError, StepCheck, at};

pub(super) fn derive(
    cx: Context,
    of: &Expr,
    var: &str,
    about: &Expr,
    order: u32,
) -> Result<StepResult, DeriveError> {
    let f = expand_names(cx.scene, cx.d, cx.step, of).map_err(DeriveError::Step)?;
    let x0 = expand_names(cx.scene, cx.d, cx.step, about).map_err(DeriveError::Step)?;
    Ok(StepResult::Expr(crate::derive::series::series(
        &f, var, &x0, order,
    )?))
}

pub(super) fn check(
    cx: Checking,
    of: &Expr,
    var: &str,
    about: &Expr,
    order: u32,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    let StepResult::Expr(s) = cx.result else {
        return Err(CheckError::NotDerived);
    };
    let f = expand_names(cx.scene, cx.d, cx.step, of)?;
    let x0 = at(
        &expand_names(cx.scene, cx.d, cx.step, about)?,
        &cx.scene.values,
    )?;
    remainder_check(cx.scene, &f, s, var, x0, order, check)
}
