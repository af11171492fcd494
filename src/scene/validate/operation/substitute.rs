//! `substitute = "expr"`, `set = { "theta'" = "x'/R" }`: an expression, or equations, with
//! names replaced.

use super::{StepContext, Validator};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text};
use crate::scene::step::Operation;
use std::collections::BTreeMap;

impl Validator<'_> {
    pub(super) fn substitute(
        &self,
        of: &Text,
        s: &RawStep,
        cx: &StepContext,
    ) -> Result<Operation, SceneError> {
        if s.set.is_empty() {
            return Err(self.err(
                cx.offset,
                cx.field,
                "`substitute` needs `set`: each name and its replacement, as \
                 set = { \"theta'\" = \"x'/R\" }",
            ));
        }
        let mut set = BTreeMap::new();
        for (name, value) in &s.set {
            if !self.own_name(name.get_ref(), cx) {
                return Err(self.err(
                    name.span().start,
                    &format!("{}.set.{}", cx.field, name.get_ref()),
                    format!(
                        "cannot substitute for `{}`: not a symbol, coordinate or rate of this \
                         scene",
                        name.get_ref()
                    ),
                ));
            }
            set.insert(
                name.get_ref().clone(),
                self.operand(value, &format!("set.{}", name.get_ref()), cx)?,
            );
        }
        Ok(Operation::Substitute {
            of: self.operand(of, "substitute", cx)?,
            set,
        })
    }
}
