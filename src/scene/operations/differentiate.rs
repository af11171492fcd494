//! `differentiate = "expr"`, `by = "x"`: a partial derivative, or by `t` the total time
//! derivative through the coordinates.

use super::{OperationType, StepFields};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text, content_start};

/// A partial derivative; by `t`, the total time derivative through the coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Differentiate {
    pub of: Expr,
    pub by: String,
}

impl OperationType for Differentiate {
    fn read(of: &Text, s: &RawStep, f: &impl StepFields) -> Result<Self, SceneError> {
        let Some(by) = &s.by else {
            return Err(f.err(
                f.offset(),
                f.field(),
                "`differentiate` needs `by`: a symbol, a coordinate or its rate, or `t` for \
                 the time derivative",
            ));
        };
        if !f.own_name(by.get_ref()) {
            return Err(f.err(
                content_start(by),
                &format!("{}.by", f.field()),
                format!(
                    "cannot differentiate by `{}`: not a symbol, coordinate, rate or `t` of this \
                     scene",
                    by.get_ref()
                ),
            ));
        }
        Ok(Differentiate {
            of: f.operand(of, "differentiate")?,
            by: by.get_ref().clone(),
        })
    }

    fn operands(&self) -> Vec<&Expr> {
        vec![&self.of]
    }
}
