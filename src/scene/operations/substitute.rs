//! `substitute = "expr"`, `set = { "theta'" = "x'/R" }`: an expression, or equations, with
//! names replaced.

use super::{OperationType, StepFields};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text};
use std::collections::BTreeMap;

/// An expression with names replaced (a constraint such as θ' = x'/R).
#[derive(Debug, Clone, PartialEq)]
pub struct Substitute {
    pub of: Expr,
    pub set: BTreeMap<String, Expr>,
}

impl OperationType for Substitute {
    fn read(of: &Text, s: &RawStep, f: &impl StepFields) -> Result<Self, SceneError> {
        if s.set.is_empty() {
            return Err(f.err(
                f.offset(),
                f.field(),
                "`substitute` needs `set`: each name and its replacement, as \
                 set = { \"theta'\" = \"x'/R\" }",
            ));
        }
        let mut set = BTreeMap::new();
        for (name, value) in &s.set {
            if !f.own_name(name.get_ref()) {
                return Err(f.err(
                    name.span().start,
                    &format!("{}.set.{}", f.field(), name.get_ref()),
                    format!(
                        "cannot substitute for `{}`: not a symbol, coordinate or rate of this \
                         scene",
                        name.get_ref()
                    ),
                ));
            }
            set.insert(
                name.get_ref().clone(),
                f.operand(value, &format!("set.{}", name.get_ref()))?,
            );
        }
        Ok(Substitute {
            of: f.operand(of, "substitute")?,
            set,
        })
    }

    fn operands(&self) -> Vec<&Expr> {
        std::iter::once(&self.of).chain(self.set.values()).collect()
    }
}
