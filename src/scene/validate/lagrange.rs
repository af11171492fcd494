//! The fields of the Lagrangian steps beyond the operation: a `lagrange` step's constraints,
//! each under its multiplier's name, and a `routh` step's cyclic coordinates, each with its
//! momentum's symbol.

use super::{Validator, content_start};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::raw::RawStep;
use std::collections::{BTreeMap, BTreeSet};

impl Validator<'_> {
    /// A `routh` step's cyclic coordinates, each with its momentum's symbol, declared in
    /// [symbols] and not a coordinate.
    pub(super) fn cyclic(
        &self,
        s: &RawStep,
        offset: usize,
        field: &str,
        coordinates: &BTreeMap<String, String>,
    ) -> Result<Vec<(String, String)>, SceneError> {
        if s.cyclic.is_empty() {
            return Err(self.err(
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
                return Err(self.err(
                    q.span().start,
                    &key,
                    format!(
                        "`{}` is not a coordinate (the coordinates are {})",
                        q.get_ref(),
                        coordinates.keys().cloned().collect::<Vec<_>>().join(", ")
                    ),
                ));
            }
            if !self.declared.contains(p.get_ref()) || coordinates.contains_key(p.get_ref()) {
                return Err(self.err(
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

    /// A `lagrange` step's constraints: each multiplier a symbol declared in [symbols] and
    /// used nowhere else in them, each constraint an expression of the coordinates, their rates
    /// (a velocity constraint, linear in them: the derivation checks) and the scene's symbols;
    /// no acceleration and no t.
    pub(super) fn constraints(
        &self,
        s: &RawStep,
        field: &str,
        scope: &BTreeSet<String>,
        coordinates: &BTreeMap<String, String>,
    ) -> Result<Vec<(String, Expr)>, SceneError> {
        let multipliers: BTreeSet<&String> = s.constraints.keys().map(|k| k.get_ref()).collect();
        let mut out = Vec::new();
        for (name, text) in &s.constraints {
            let (lambda, key) = (
                name.get_ref(),
                format!("{field}.constraints.{}", name.get_ref()),
            );
            if !self.declared.contains(lambda) {
                return Err(self.err(
                    name.span().start,
                    &key,
                    format!(
                        "the multiplier `{lambda}` is not a symbol: declare it under [symbols] with \
                         its meaning and unit (a tension: `{lambda} = {{ meaning = \"tension in \
                         the string\", unit = \"N\" }}`), and give it no value"
                    ),
                ));
            }
            let allowed: BTreeSet<String> = self
                .declared
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
                return Err(self.err(
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
            let f = self.claim_expr(text, &key, &allowed)?;
            if !f
                .symbols()
                .iter()
                .any(|n| coordinates.contains_key(n.trim_end_matches('\'')))
            {
                return Err(self.err(
                    content_start(text),
                    &key,
                    "the constraint names no coordinate: it constrains nothing",
                ));
            }
            out.push((lambda.clone(), f));
        }
        Ok(out)
    }
}
