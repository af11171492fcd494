//! `linearise = "eom"`, `about = { q = "value" }`: the equations of motion to first order about
//! a state at rest, each coordinate's value there (0 when not named).

use super::{Holds, OperationType, StepFields};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text};
use std::collections::BTreeMap;

/// The named equations of motion to first order about a state at rest (each coordinate's
/// value there; 0 when not named).
#[derive(Debug, Clone, PartialEq)]
pub struct Linearise {
    pub of: String,
    pub about: BTreeMap<String, Expr>,
}

impl OperationType for Linearise {
    fn read(of: &Text, s: &RawStep, f: &impl StepFields) -> Result<Self, SceneError> {
        let of = f.taken(of, "linearise", Holds::Motion)?;
        let mut about = BTreeMap::new();
        for (q, value) in &s.about {
            let key = format!("{}.about.{}", f.field(), q.get_ref());
            if !f.coordinates().contains_key(q.get_ref()) {
                return Err(f.err(
                    q.span().start,
                    &key,
                    format!(
                        "`{}` is not a coordinate; `about` gives each coordinate's value at the \
                         state of rest (the coordinates are {})",
                        q.get_ref(),
                        f.coordinates()
                            .keys()
                            .cloned()
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ));
            }
            about.insert(
                q.get_ref().clone(),
                f.expression(value, &key, &f.names_only())?,
            );
        }
        Ok(Linearise { of, about })
    }

    fn operands(&self) -> Vec<&Expr> {
        self.about.values().collect()
    }
}
