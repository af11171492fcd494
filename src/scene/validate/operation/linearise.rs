//! `linearise = "eom"`, `about = { q = "value" }`: the equations of motion to first order about
//! a state at rest, each coordinate's value there (0 when not named).

use super::{StepContext, Validator, names_only};
use crate::scene::error::SceneError;
use crate::scene::operations::Holds;
use crate::scene::raw::{RawStep, Text};
use crate::scene::step::Operation;
use std::collections::BTreeMap;

impl Validator<'_> {
    pub(super) fn linearise(
        &self,
        of: &Text,
        s: &RawStep,
        cx: &StepContext,
    ) -> Result<Operation, SceneError> {
        let of = self.taken(of, "linearise", Holds::Motion, cx)?;
        let mut about = BTreeMap::new();
        for (q, value) in &s.about {
            let key = format!("{}.about.{}", cx.field, q.get_ref());
            if !cx.coordinates.contains_key(q.get_ref()) {
                return Err(self.err(
                    q.span().start,
                    &key,
                    format!(
                        "`{}` is not a coordinate; `about` gives each coordinate's value at the \
                         state of rest (the coordinates are {})",
                        q.get_ref(),
                        cx.coordinates
                            .keys()
                            .cloned()
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ));
            }
            about.insert(
                q.get_ref().clone(),
                self.claim_expr(value, &key, &names_only(cx))?,
            );
        }
        Ok(Operation::Linearise { of, about })
    }
}
