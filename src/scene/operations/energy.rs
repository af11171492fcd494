//! `energy = "Lag"`: the energy function of the named Lagrangian.

use super::{OperationType, StepFields};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text};

/// The energy function Σ q'·∂L/∂q' − L of the named Lagrangian.
#[derive(Debug, Clone, PartialEq)]
pub struct Energy {
    pub of: String,
}

impl OperationType for Energy {
    fn read(of: &Text, _: &RawStep, f: &impl StepFields) -> Result<Self, SceneError> {
        Ok(Energy {
            of: f.lagrangian(of, "energy")?,
        })
    }
}
