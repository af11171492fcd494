//! The names a scene declares: symbols, definitions, vectors, and the numeric values of the
//! symbols its bodies use.

use super::bodies::body_symbols;
use super::{RESERVED, Validator, is_identifier};
use crate::cas::Expr;
use crate::model::catalogue::{CATALOGUE, is_quantity};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawScene, definition_of, definition_tex, meaning_of, tex_of, unit_of};
use crate::scene::types::Body;
use crate::scene::validate::CLAIM_FUNCTIONS;
use std::collections::{BTreeMap, BTreeSet};

/// Symbol name -> its meaning.
type Meanings = BTreeMap<String, String>;

/// Definitions, vectors, and every name a claim may use.
type ClaimNames = (
    BTreeMap<String, Expr>,
    BTreeMap<String, [Expr; 3]>,
    BTreeSet<String>,
);

impl Validator<'_> {
    /// `[symbols]`: names that are not reserved, quantities or functions.
    pub(super) fn symbols(&self, raw: &RawScene) -> Result<Meanings, SceneError> {
        let mut symbols = BTreeMap::new();
        for (name, meaning) in &raw.symbols {
            let n = name.get_ref();
            if !is_identifier(n)
                || RESERVED.contains(&n.as_str())
                || is_quantity(n)
                || CLAIM_FUNCTIONS.contains(&n.as_str())
            {
                return Err(self.err(
                    name.span().start,
                    &format!("symbols.{n}"),
                    format!("`{n}` cannot be a symbol name"),
                ));
            }
            symbols.insert(n.clone(), meaning_of(meaning).into_inner());
        }
        Ok(symbols)
    }

    /// The units declared on symbols and coordinates (`{ meaning = "...", unit = "kg" }`).
    pub(super) fn units(
        &self,
        raw: &RawScene,
    ) -> Result<BTreeMap<String, crate::model::units::Unit>, SceneError> {
        let mut out = BTreeMap::new();
        for (table, kind) in [(&raw.symbols, "symbols"), (&raw.coordinates, "coordinates")] {
            for (name, meaning) in table {
                if let Some(u) = unit_of(meaning) {
                    let unit = crate::model::units::Unit::parse(u.get_ref()).map_err(|e| {
                        self.err(
                            u.span().start + 1,
                            &format!("{kind}.{}.unit", name.get_ref()),
                            e.to_string(),
                        )
                    })?;
                    out.insert(name.get_ref().clone(), unit);
                }
            }
        }
        Ok(out)
    }

    /// How symbols, coordinates, steps and definitions are typeset (`{ meaning = "...", tex =
    /// "\\Omega" }`, a step's `tex = "I_p"`, `{ be = "...", tex = "\\omega_1" }`): LaTeX that the
    /// pages' reader can set, without `$` signs.
    pub(super) fn typesetting(
        &self,
        raw: &RawScene,
    ) -> Result<BTreeMap<String, String>, SceneError> {
        let mut out = BTreeMap::new();
        let steps = raw.steps.iter().enumerate().filter_map(|(i, s)| {
            let s = s.get_ref();
            Some((s.name.get_ref(), s.tex.as_ref()?, format!("step[{i}]")))
        });
        let names = [(&raw.symbols, "symbols"), (&raw.coordinates, "coordinates")]
            .into_iter()
            .flat_map(|(table, kind)| {
                table.iter().filter_map(move |(name, meaning)| {
                    Some((
                        name.get_ref(),
                        tex_of(meaning)?,
                        format!("{kind}.{}", name.get_ref()),
                    ))
                })
            });
        let definitions = raw.definitions.iter().filter_map(|(name, d)| {
            Some((
                name.get_ref(),
                definition_tex(d)?,
                format!("definitions.{}", name.get_ref()),
            ))
        });
        {
            for (name, tex, field) in names.chain(steps).chain(definitions) {
                let problem = if tex.get_ref().contains('$') {
                    Some("it is LaTeX already: leave out the `$` signs".to_string())
                } else {
                    super::text::latex_problem(tex.get_ref())
                };
                if let Some(why) = problem {
                    return Err(self.err(
                        tex.span().start + 1,
                        &format!("{field}.tex"),
                        format!("`{}` cannot be typeset: {why}", tex.get_ref()),
                    ));
                }
                out.insert(name.clone(), tex.get_ref().trim().to_string());
            }
        }
        // The author's names of a step's results print as the step's symbol with the name
        // below it: `names = ["slow", "fast"]` of `tex = "\\dot\\phi"` as φ̇ with "slow".
        for s in &raw.steps {
            let s = s.get_ref();
            let (Some(tex), Some(names)) = (&s.tex, &s.names) else {
                continue;
            };
            for name in names.get_ref() {
                out.entry(name.clone()).or_insert_with(|| {
                    format!("{{{}}}_{{\\mathrm{{{name}}}}}", tex.get_ref().trim())
                });
            }
        }
        Ok(out)
    }

    /// `[definitions]` and `[vectors]`, and with them the names a claim may use.
    pub(super) fn definitions_and_vectors(
        &self,
        raw: &RawScene,
        allowed: &BTreeSet<String>,
        variables: &BTreeSet<String>,
    ) -> Result<ClaimNames, SceneError> {
        let mut definitions = BTreeMap::new();
        let mut claim_names = allowed.clone();
        for (name, value) in &raw.definitions {
            let n = name.get_ref();
            if !is_identifier(n) || allowed.contains(n) {
                return Err(self.err(
                    name.span().start,
                    &format!("definitions.{n}"),
                    format!("`{n}` cannot be defined here (not a name, or already a symbol)"),
                ));
            }
            let mut scope = allowed.clone();
            scope.extend(variables.iter().cloned());
            definitions.insert(
                n.clone(),
                self.definition_expr(&definition_of(value), &format!("definitions.{n}"), &scope)?,
            );
            claim_names.insert(n.clone());
        }

        let mut vectors = BTreeMap::new();
        for (name, v) in &raw.vectors {
            let n = name.get_ref();
            if !is_identifier(n) || claim_names.contains(n) {
                return Err(self.err(
                    name.span().start,
                    &format!("vectors.{n}"),
                    format!("`{n}` cannot name a vector (not a name, or already used)"),
                ));
            }
            vectors.insert(n.clone(), self.vec3(v, &format!("vectors.{n}"), allowed)?);
        }
        claim_names.extend(vectors.keys().cloned());
        claim_names.extend(variables.iter().cloned());
        claim_names.extend(CATALOGUE.iter().map(|q| q.name.to_string()));
        Ok((definitions, vectors, claim_names))
    }

    /// `[numeric] values`: finite, one per symbol the bodies, `omega` and `axis` use, and any
    /// coordinate's.
    pub(super) fn values<'e>(
        &self,
        raw: &RawScene,
        symbols: &BTreeMap<String, String>,
        bodies: &[Body],
        vectors: impl Iterator<Item = &'e [Expr; 3]>,
    ) -> Result<BTreeMap<String, f64>, SceneError> {
        // Numeric values: finite, one per symbol the bodies, omega and axis use.
        let mut values = BTreeMap::new();
        for (name, v) in &raw.numeric.values {
            let n = name.get_ref();
            let field = format!("numeric.values.{n}");
            // A coordinate may have a value too: the state at which a step's results are
            // evaluated (and a `lagrange` step's motion starts).
            let coordinate = raw.coordinates.keys().any(|k| k.get_ref() == n);
            if !symbols.contains_key(n) && !coordinate {
                return Err(self.err(
                    name.span().start,
                    &field,
                    format!("`{n}` is not a declared symbol or coordinate"),
                ));
            }
            if !v.get_ref().is_finite() {
                return Err(self.err(v.span().start, &field, "the value must be a finite number"));
            }
            if *v.get_ref() != 0.0 && !v.get_ref().is_normal() {
                return Err(self.err(
                    v.span().start,
                    &field,
                    format!(
                        "{:e} is below double precision's normal range (about 2.2e-308), where \
                         it has lost its digits: give the quantity in units nearer 1",
                        v.get_ref()
                    ),
                ));
            }
            values.insert(n.clone(), *v.get_ref());
        }
        let mut used: BTreeSet<String> = BTreeSet::new();
        for b in bodies {
            used.extend(body_symbols(b));
        }
        for v in vectors {
            v.iter().for_each(|e| used.extend(e.symbols()));
        }
        used.remove("pi");
        for s in &used {
            if !values.contains_key(s) {
                let declared = raw.symbols.keys().find(|k| k.get_ref() == s);
                return Err(self.err(
                    declared.map_or(0, |k| k.span().start),
                    "numeric.values",
                    format!("no numeric value for symbol `{s}`"),
                ));
            }
        }
        if let Some(b) = self.broken_rule(raw, bodies, &values) {
            return Err(self.err(b.at, &b.field, b.message("at the scene's values")));
        }
        Ok(values)
    }
}

/// The symbols and the coordinates in the order the file declares them (by where each key is
/// written), the order of a printed product's factors.
pub(super) fn declared_order(raw: &crate::scene::raw::RawScene) -> crate::cas::Declared {
    type Table = std::collections::BTreeMap<
        toml::Spanned<String>,
        toml::Spanned<crate::scene::raw::RawMeaning>,
    >;
    let in_file_order = |m: &Table| {
        let mut names: Vec<(usize, String)> = m
            .keys()
            .map(|k| (k.span().start, k.get_ref().clone()))
            .collect();
        names.sort();
        names.into_iter().map(|(_, n)| n).collect()
    };
    crate::cas::Declared {
        symbols: in_file_order(&raw.symbols),
        coordinates: in_file_order(&raw.coordinates),
    }
}
