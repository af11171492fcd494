//! `series = "expr"`, `about = { eps = "0" }`, `order = 2`: the Taylor series in one name about
//! a value.

use super::{StepContext, Validator, names_only};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text};
use crate::scene::step::Operation;

/// The highest order of a `series`: each order is one more derivative of the expression.
const MAX_ORDER: i64 = 6;

impl Validator<'_> {
    pub(super) fn series(
        &self,
        of: &Text,
        s: &RawStep,
        cx: &StepContext,
    ) -> Result<Operation, SceneError> {
        let field = cx.field;
        let [(var, value)] = s.about.iter().collect::<Vec<_>>()[..] else {
            return Err(self.err(
                cx.offset,
                &format!("{field}.about"),
                "`series` needs `about` with one name and its value, such as about = { eps = \
                 \"0\" }",
            ));
        };
        let key = format!("{field}.about.{}", var.get_ref());
        if !self.own_name(var.get_ref(), cx) {
            return Err(self.err(
                var.span().start,
                &key,
                format!(
                    "cannot expand in `{}`: not a symbol, coordinate, rate or `t` of this scene",
                    var.get_ref()
                ),
            ));
        }
        let order = match &s.order {
            None => 1,
            Some(o) if (0..=MAX_ORDER).contains(o.get_ref()) => *o.get_ref() as u32,
            Some(o) => {
                return Err(self.err(
                    o.span().start,
                    &format!("{field}.order"),
                    format!("`order` is a whole number from 0 to {MAX_ORDER}"),
                ));
            }
        };
        Ok(Operation::Series {
            of: self.operand(of, "series", cx)?,
            var: var.get_ref().clone(),
            about: self.claim_expr(value, &key, &names_only(cx))?,
            order,
        })
    }
}
