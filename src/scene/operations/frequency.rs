//! `frequency = "step"`: the angular frequency of small oscillations of the named linear equation.

use super::{Holds, OperationType, StepFields};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text};

/// The angular frequency of small oscillations of the named linear equation.
#[derive(Debug, Clone, PartialEq)]
pub struct Frequency {
    pub of: String,
}

impl OperationType for Frequency {
    fn read(of: &Text, _: &RawStep, f: &impl StepFields) -> Result<Self, SceneError> {
        Ok(Frequency {
            of: f.taken(of, "frequency", Holds::Linear)?,
        })
    }
}
