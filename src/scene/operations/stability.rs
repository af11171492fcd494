//! `stability = "step"`: whether each of the named equilibria is stable.

use super::{Holds, OperationType, StepFields};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text};

/// Whether each of the named equilibria is stable.
#[derive(Debug, Clone, PartialEq)]
pub struct Stability {
    pub of: String,
}

impl OperationType for Stability {
    fn read(of: &Text, _: &RawStep, f: &impl StepFields) -> Result<Self, SceneError> {
        Ok(Stability {
            of: f.taken(of, "stability", Holds::Equilibria)?,
        })
    }
}
