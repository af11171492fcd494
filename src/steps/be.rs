//! `be = "…"`: an expression of the scene's names and the earlier steps.
//!
//! - Exact rule: the names put in, simplified by the engine; a divisor that is 0 as written is
//!   refused.
//! - Numeric route: the simplified form against the expression as written at random points.

use super::Context;
use crate::base::rng::Rng;
use crate::cas::{self, Expr};
use crate::derive::DeriveError;
use crate::derive::step_names::{StepResult, expand_names};
use crate::verify::CONFIRMATION_POINTS;
use crate::verify::random_points::{DOMAIN_TRIES, NUMERICALLY_ZERO, rational_at};
use crate::verify::step_check::{CheckError, StepCheck, at, random_point};
use std::collections::BTreeMap;

pub(super) fn derive(cx: Context, e: &Expr) -> Result<StepResult, DeriveError> {
    let x = expand_names(cx.scene, cx.d, cx.step, e).map_err(DeriveError::Step)?;
    crate::derive::undefined::refuse_no_value(&x, e, &BTreeMap::new(), &BTreeMap::new())?;
    Ok(StepResult::Expr(cas::simplify(&x)?))
}

pub(super) fn check(
    cx: Context,
    e: &Expr,
    result: &StepResult,
    seed: u64,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    let StepResult::Expr(r) = result else {
        return Err(CheckError::NotDerived);
    };
    let raw = expand_names(cx.scene, cx.d, cx.step, e)?;
    check.method = format!(
        "the simplified form against the expression as written, at {CONFIRMATION_POINTS} \
         random points"
    );
    check.tolerance = NUMERICALLY_ZERO;
    let mut rng = Rng::new(seed);
    let mut compared = 0;
    for _ in 0..CONFIRMATION_POINTS * DOMAIN_TRIES {
        if compared == CONFIRMATION_POINTS {
            break;
        }
        let point = random_point(&[&raw, r], &mut rng);
        let (a, b) = (at(&raw, &point)?, at(r, &point)?);
        check.evaluations += 2;
        // Where either is undefined or infinite, nothing is compared (inf − inf is NaN, which
        // `max` would pass over): another point is drawn.
        if !a.is_finite() || !b.is_finite() {
            continue;
        }
        compared += 1;
        let scale = a.abs().max(b.abs()).max(1.0);
        let mut error = (a - b).abs() / scale;
        // Apart in double precision: exactly, where both are rational functions of the point
        // (an expanded (x − a)^30 against the power as written cancels its digits away).
        if error > NUMERICALLY_ZERO
            && let (Some(x), Some(y)) = (rational_at(&raw, &point), rational_at(r, &point))
        {
            error = x.add(&y.negated()).to_f64().abs() / scale;
        }
        check.error = check.error.max(error);
    }
    if compared < CONFIRMATION_POINTS {
        return Err(CheckError::NoPointInDomain {
            tries: CONFIRMATION_POINTS * DOMAIN_TRIES,
        });
    }
    Ok(())
}
