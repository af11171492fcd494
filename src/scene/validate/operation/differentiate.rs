//! `differentiate = "expr"`, `by = "x"`: a partial derivative, or by `t` the total time
//! derivative through the coordinates.

use super::{StepContext, Validator, content_start};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text};
use crate::scene::step::Operation;

impl Validator<'_> {
    pub(super) fn differentiate(
        &self,
        of: &Text,
        s: &RawStep,
        cx: &StepContext,
    ) -> Result<Operation, SceneError> {
        let Some(by) = &s.by else {
            return Err(self.err(
                cx.offset,
                cx.field,
                "`differentiate` needs `by`: a symbol, a coordinate or its rate, or `t` for \
                 the time derivative",
            ));
        };
        if !self.own_name(by.get_ref(), cx) {
            return Err(self.err(
                content_start(by),
                &format!("{}.by", cx.field),
                format!(
                    "cannot differentiate by `{}`: not a symbol, coordinate, rate or `t` of this \
                     scene",
                    by.get_ref()
                ),
            ));
        }
        Ok(Operation::Differentiate {
            of: self.operand(of, "differentiate", cx)?,
            by: by.get_ref().clone(),
        })
    }
}
