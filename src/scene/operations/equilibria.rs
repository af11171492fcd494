//! `equilibria = "step"`: the states of rest of the named equation of motion (one coordinate).

use super::{Holds, OperationType, StepFields};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text};

/// The states of rest of the named equation of motion (one coordinate).
#[derive(Debug, Clone, PartialEq)]
pub struct Equilibria {
    pub of: String,
}

impl OperationType for Equilibria {
    fn read(of: &Text, _: &RawStep, f: &impl StepFields) -> Result<Self, SceneError> {
        Ok(Equilibria {
            of: f.taken(of, "equilibria", Holds::Motion)?,
        })
    }
}
