//! `series = "expr"`, `about = { eps = "0" }`, `order = 2`: the Taylor series in one name about
//! a value.

use super::{OperationType, StepFields};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text};

/// The highest order of a `series`: each order is one more derivative of the expression.
const MAX_ORDER: i64 = 6;

/// The Taylor series of an expression in one name about a value, to the given order.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub of: Expr,
    pub var: String,
    pub about: Expr,
    pub order: u32,
}

impl OperationType for Series {
    fn read(of: &Text, s: &RawStep, f: &impl StepFields) -> Result<Self, SceneError> {
        let field = f.field();
        let [(var, value)] = s.about.iter().collect::<Vec<_>>()[..] else {
            return Err(f.err(
                f.offset(),
                &format!("{field}.about"),
                "`series` needs `about` with one name and its value, such as about = { eps = \
             \"0\" }",
            ));
        };
        let key = format!("{field}.about.{}", var.get_ref());
        if !f.own_name(var.get_ref()) {
            return Err(f.err(
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
                return Err(f.err(
                    o.span().start,
                    &format!("{field}.order"),
                    format!("`order` is a whole number from 0 to {MAX_ORDER}"),
                ));
            }
        };
        Ok(Series {
            of: f.operand(of, "series")?,
            var: var.get_ref().clone(),
            about: f.expression(value, &key, &f.names_only())?,
            order,
        })
    }

    fn operands(&self) -> Vec<&Expr> {
        vec![&self.of, &self.about]
    }
}
