//! `lagrange = "Lag"`, `constraints = { T = "l - x1 - x2" }`: the Euler–Lagrange equations of
//! the named Lagrangian, with each constraint under its multiplier's name.

use super::{OperationType, StepFields};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text, content_start};
use std::collections::BTreeSet;

/// The Euler–Lagrange equation of each coordinate, from the named Lagrangian, with each
/// constraint's multiplier λ: d/dt ∂L/∂q' − ∂L/∂q − Σ λ ∂f/∂q = 0, and each constraint
/// f(q) = 0 differentiated twice, an equation under its multiplier's name.
#[derive(Debug, Clone, PartialEq)]
pub struct Lagrange {
    pub of: String,
    pub constraints: Vec<(String, Expr)>,
}

impl OperationType for Lagrange {
    fn read(of: &Text, s: &RawStep, f: &impl StepFields) -> Result<Self, SceneError> {
        Ok(Lagrange {
            of: f.lagrangian(of, "lagrange")?,
            constraints: constraints(s, f)?,
        })
    }
}

/// A `lagrange` step's constraints: each multiplier a symbol declared in [symbols] and
/// used nowhere else in them, each constraint an expression of the coordinates, their rates
/// (a velocity constraint, linear in them: the derivation checks) and the scene's symbols;
/// no acceleration and no t.
fn constraints(s: &RawStep, f: &impl StepFields) -> Result<Vec<(String, Expr)>, SceneError> {
    let (field, scope, coordinates) = (f.field(), f.scope(), f.coordinates());
    let multipliers: BTreeSet<&String> = s.constraints.keys().map(|k| k.get_ref()).collect();
    let mut out = Vec::new();
    for (name, text) in &s.constraints {
        let (lambda, key) = (
            name.get_ref(),
            format!("{field}.constraints.{}", name.get_ref()),
        );
        if !f.declared().contains(lambda) {
            return Err(f.err(
                name.span().start,
                &key,
                format!(
                    "the multiplier `{lambda}` is not a symbol: declare it under [symbols] with \
                     its meaning and unit (a tension: `{lambda} = {{ meaning = \"tension in \
                     the string\", unit = \"N\" }}`), and give it no value"
                ),
            ));
        }
        let allowed: BTreeSet<String> = f
            .declared()
            .iter()
            .filter(|n| !multipliers.contains(n) && scope.contains(*n))
            .cloned()
            .chain(
                coordinates
                    .keys()
                    .flat_map(|q| [q.clone(), format!("{q}'")]),
            )
            .collect();
        let parsed = crate::cas::parse_input(text.get_ref()).ok();
        let rate = parsed.as_ref().and_then(|p| {
            p.symbols
                .iter()
                .find(|(n, _)| n == "t" || n.ends_with("''"))
                .cloned()
        });
        if let Some((found, offset)) = rate {
            return Err(f.err(
                content_start(text) + offset,
                &key,
                if found == "t" {
                    "a constraint that depends on the time t (a moving support) is not \
                     supported: write it in the coordinates and symbols alone"
                        .to_string()
                } else {
                    format!(
                        "`{found}` is an acceleration: a constraint is f(q) = 0 in the \
                         coordinates, or a velocity constraint Σ a(q) q' = 0 linear in their \
                         rates (a rolling coin's)"
                    )
                },
            ));
        }
        let constraint = f.expression(text, &key, &allowed)?;
        if !constraint
            .symbols()
            .iter()
            .any(|n| coordinates.contains_key(n.trim_end_matches('\'')))
        {
            return Err(f.err(
                content_start(text),
                &key,
                "the constraint names no coordinate: it constrains nothing",
            ));
        }
        out.push((lambda.clone(), constraint));
    }
    Ok(out)
}
