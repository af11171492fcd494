//! `momentum = "q"`, `of = "Lag"`: the generalised momentum ∂L/∂q' of one coordinate.

use super::{Holds, OperationType, StepFields};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text, content_start};

/// The generalised momentum ∂L/∂q' of one coordinate, from the named Lagrangian.
#[derive(Debug, Clone, PartialEq)]
pub struct Momentum {
    pub of: String,
    pub coordinate: String,
}

impl OperationType for Momentum {
    fn read(q: &Text, s: &RawStep, f: &impl StepFields) -> Result<Self, SceneError> {
        if !f.coordinates().contains_key(q.get_ref()) {
            return Err(f.err(
                content_start(q),
                &format!("{}.momentum", f.field()),
                format!(
                    "`{}` is not a coordinate{}: `momentum` names the coordinate whose \
                     momentum it is (its Lagrangian under `of`)",
                    q.get_ref(),
                    crate::base::suggest::did_you_mean(
                        q.get_ref(),
                        f.coordinates().keys().map(String::as_str)
                    )
                ),
            ));
        }
        let Some(of) = &s.of else {
            return Err(f.err(
                f.offset(),
                f.field(),
                "`momentum` needs `of`: the step that holds the Lagrangian, such as of = \"Lag\"",
            ));
        };
        Ok(Momentum {
            of: f.taken(of, "of", Holds::Expression)?,
            coordinate: q.get_ref().clone(),
        })
    }
}
