//! `be = "expr"`: an expression of the scene's names and earlier steps.

use super::{OperationType, StepFields};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text};

/// An expression of the scene's names and earlier steps.
#[derive(Debug, Clone, PartialEq)]
pub struct Be(pub Expr);

impl OperationType for Be {
    fn read(key: &Text, _: &RawStep, f: &impl StepFields) -> Result<Self, SceneError> {
        Ok(Be(f.operand(key, "be")?))
    }

    fn operands(&self) -> Vec<&Expr> {
        vec![&self.0]
    }
}
