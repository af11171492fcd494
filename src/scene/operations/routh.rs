//! `routh = "Lag"`, `cyclic = { phi = "p" }`: Routh's procedure, each cyclic coordinate's rate
//! replaced by its conserved momentum.

use super::{OperationType, StepFields};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text, content_start};

/// Routh's procedure on the named Lagrangian: R = L − Σ p φ' with each cyclic coordinate φ's
/// rate solved from p = ∂L/∂φ', its conserved momentum p a symbol.
#[derive(Debug, Clone, PartialEq)]
pub struct Routh {
    pub of: String,
    /// Each cyclic coordinate and its momentum's symbol.
    pub cyclic: Vec<(String, String)>,
}

impl OperationType for Routh {
    fn read(of: &Text, s: &RawStep, f: &impl StepFields) -> Result<Self, SceneError> {
        Ok(Routh {
            of: f.lagrangian(of, "routh")?,
            cyclic: cyclic(s, f)?,
        })
    }
}

/// A `routh` step's cyclic coordinates, each with its momentum's symbol, declared in
/// [symbols] and not a coordinate.
fn cyclic(s: &RawStep, f: &impl StepFields) -> Result<Vec<(String, String)>, SceneError> {
    let (offset, field, coordinates) = (f.offset(), f.field(), f.coordinates());
    if s.cyclic.is_empty() {
        return Err(f.err(
            offset,
            field,
            "`routh` needs `cyclic`: each cyclic coordinate and the symbol of its conserved \
             momentum, such as cyclic = { phi = \"p\" }",
        ));
    }
    let mut out = Vec::new();
    for (q, p) in &s.cyclic {
        let key = format!("{field}.cyclic.{}", q.get_ref());
        if !coordinates.contains_key(q.get_ref()) {
            return Err(f.err(
                q.span().start,
                &key,
                format!(
                    "`{}` is not a coordinate (the coordinates are {})",
                    q.get_ref(),
                    coordinates.keys().cloned().collect::<Vec<_>>().join(", ")
                ),
            ));
        }
        if !f.declared().contains(p.get_ref()) || coordinates.contains_key(p.get_ref()) {
            return Err(f.err(
                content_start(p),
                &key,
                format!(
                    "the momentum `{}` is not a symbol: declare it under [symbols] with its \
                     meaning and unit (`{} = {{ meaning = \"angular momentum about the \
                     axis\", unit = \"kg m^2/s\" }}`); a value under [numeric] is the \
                     one later steps' checks use",
                    p.get_ref(),
                    p.get_ref()
                ),
            ));
        }
        out.push((q.get_ref().clone(), p.get_ref().clone()));
    }
    Ok(out)
}
