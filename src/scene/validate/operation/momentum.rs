//! `momentum = "q"`, `of = "Lag"`: the generalised momentum ∂L/∂q' of one coordinate.

use super::{StepContext, Validator, content_start};
use crate::scene::error::SceneError;
use crate::scene::operations::Holds;
use crate::scene::raw::{RawStep, Text};
use crate::scene::step::Operation;

impl Validator<'_> {
    pub(super) fn momentum(
        &self,
        q: &Text,
        s: &RawStep,
        cx: &StepContext,
    ) -> Result<Operation, SceneError> {
        if !cx.coordinates.contains_key(q.get_ref()) {
            return Err(self.err(
                content_start(q),
                &format!("{}.momentum", cx.field),
                format!(
                    "`{}` is not a coordinate{}: `momentum` names the coordinate whose \
                     momentum it is (its Lagrangian under `of`)",
                    q.get_ref(),
                    crate::base::suggest::did_you_mean(
                        q.get_ref(),
                        cx.coordinates.keys().map(String::as_str)
                    )
                ),
            ));
        }
        let Some(of) = &s.of else {
            return Err(self.err(
                cx.offset,
                cx.field,
                "`momentum` needs `of`: the step that holds the Lagrangian, such as of = \"Lag\"",
            ));
        };
        Ok(Operation::Momentum {
            of: self.taken(of, "of", Holds::Expression, cx)?,
            coordinate: q.get_ref().clone(),
        })
    }
}
