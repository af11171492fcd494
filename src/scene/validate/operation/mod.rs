//! What a `[[step]]` does: exactly one operation of the table (`scene/operations.rs`), its
//! operands checked against the scene's names, the coordinates and the earlier steps by the
//! operation's own file here, and no field of another operation.

mod differentiate;
mod integrate;
mod lagrange;
mod linearise;
mod momentum;
mod routh;
mod series;
mod solve;
mod substitute;

use super::{Validator, content_start};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::operations::{
    Holds, OPERATION_FIELDS, OPERATIONS, OperationKind, Several, stray_field_message,
};
use crate::scene::raw::{RawStep, Text};
use crate::scene::step::Operation;
use std::collections::{BTreeMap, BTreeSet};

/// What a step's operation is checked against: where the step is, the names before it, what
/// each earlier step holds, and the coordinates with their meanings.
pub(super) struct StepContext<'a> {
    pub offset: usize,
    pub field: &'a str,
    pub scope: &'a BTreeSet<String>,
    pub earlier: &'a BTreeMap<String, Holds>,
    pub coordinates: &'a BTreeMap<String, String>,
}

/// Whether the step gives the key of the operation `name`.
fn gives_key(s: &RawStep, name: &str) -> bool {
    match name {
        "be" => s.be.is_some(),
        "differentiate" => s.differentiate.is_some(),
        "substitute" => s.substitute.is_some(),
        "lagrange" => s.lagrange.is_some(),
        "routh" => s.routh.is_some(),
        "momentum" => s.momentum.is_some(),
        "energy" => s.energy.is_some(),
        "linearise" => s.linearise.is_some(),
        "frequency" => s.frequency.is_some(),
        "solve" => s.solve.is_some(),
        "series" => s.series.is_some(),
        "integrate" => s.integrate.is_some(),
        "equilibria" => s.equilibria.is_some(),
        "stability" => s.stability.is_some(),
        _ => unreachable!("`{name}` is not in the table of operations"),
    }
}

/// Whether the step gives the field `name` of some operations (`OPERATION_FIELDS`).
fn gives_field(s: &RawStep, name: &str) -> bool {
    match name {
        "by" => s.by.is_some(),
        "set" => !s.set.is_empty(),
        "for" => s.unknown.is_some(),
        "about" => !s.about.is_empty(),
        "over" => !s.over.is_empty(),
        "order" => s.order.is_some(),
        "cyclic" => !s.cyclic.is_empty(),
        "constraints" => !s.constraints.is_empty(),
        "of" => s.of.is_some(),
        "start" => !s.start.is_empty(),
        _ => unreachable!("`{name}` is not a field of the table of operations"),
    }
}

impl Validator<'_> {
    /// The one operation of a step.
    pub(super) fn operation(&self, s: &RawStep, cx: &StepContext) -> Result<Operation, SceneError> {
        let (offset, field) = (cx.offset, cx.field);
        let given: Vec<&OperationKind> =
            OPERATIONS.iter().filter(|k| gives_key(s, k.name)).collect();
        let [kind] = given[..] else {
            return Err(self.err(
                offset,
                field,
                format!(
                    "a step does one thing: give exactly one of {} (this one gives {})",
                    OPERATIONS.map(|k| k.name).join(", "),
                    if given.is_empty() {
                        "none".to_string()
                    } else {
                        given
                            .iter()
                            .map(|k| k.name)
                            .collect::<Vec<_>>()
                            .join(" and ")
                    }
                ),
            ));
        };
        let op = self.operand_of(s, kind, cx)?;
        // A field of another operation than this step's: said before anything else about it.
        for (name, _) in OPERATION_FIELDS {
            if gives_field(s, name) && !kind.fields.contains(&name) {
                let message = stray_field_message(name).expect("a field of the table");
                return Err(self.err(offset, &format!("{field}.{name}"), message));
            }
        }
        // (A `frequency` of several coordinates is known only once derived: its `gives` is
        // then a claim with a problem that says to use the modes' names.)
        if let (Several::States, Some(g)) = (kind.several, &s.gives) {
            return Err(self.err(
                g.span().start,
                &format!("{field}.gives"),
                format!(
                    "`gives` states one result, and `{}` finds one per state of rest: leave \
                     `gives` out and state each in a [[claim]] on its name ({name}_1, \
                     {name}_2, …, for one coordinate)",
                    kind.name,
                    name = s.name.get_ref(),
                ),
            ));
        }
        Ok(op)
    }

    /// The operation `kind` with its operands, each checked by the operation's own rules.
    fn operand_of(
        &self,
        s: &RawStep,
        kind: &OperationKind,
        cx: &StepContext,
    ) -> Result<Operation, SceneError> {
        // The key's own text: `gives_key` found it.
        let key = |t: &Option<Text>| t.clone().expect("the step gives its operation's key");
        Ok(match kind.name {
            "be" => Operation::Be(self.operand(&key(&s.be), "be", cx)?),
            "differentiate" => self.differentiate(&key(&s.differentiate), s, cx)?,
            "substitute" => self.substitute(&key(&s.substitute), s, cx)?,
            "lagrange" => Operation::Lagrange {
                of: self.lagrangian(&key(&s.lagrange), "lagrange", cx)?,
                constraints: self.constraints(s, cx)?,
            },
            "routh" => Operation::Routh {
                of: self.lagrangian(&key(&s.routh), "routh", cx)?,
                cyclic: self.cyclic(s, cx)?,
            },
            "momentum" => self.momentum(&key(&s.momentum), s, cx)?,
            "energy" => Operation::Energy {
                of: self.lagrangian(&key(&s.energy), "energy", cx)?,
            },
            "linearise" => self.linearise(&key(&s.linearise), s, cx)?,
            "frequency" => Operation::Frequency {
                of: self.taken(&key(&s.frequency), "frequency", Holds::Linear, cx)?,
            },
            "solve" => self.solve(&key(&s.solve), s, cx)?,
            "series" => self.series(&key(&s.series), s, cx)?,
            "integrate" => self.integrate(&key(&s.integrate), s, cx)?,
            "equilibria" => Operation::Equilibria {
                of: self.taken(&key(&s.equilibria), "equilibria", Holds::Motion, cx)?,
            },
            "stability" => Operation::Stability {
                of: self.taken(&key(&s.stability), "stability", Holds::Equilibria, cx)?,
            },
            other => unreachable!("`{other}` is not in the table of operations"),
        })
    }

    /// An operand written by the author under `key`: an expression of the names in scope, in
    /// which a coordinate's rate is named as such.
    fn operand(&self, t: &Text, key: &str, cx: &StepContext) -> Result<Expr, SceneError> {
        let at = format!("{}.{key}", cx.field);
        self.rates_of_coordinates(t, &at, cx.coordinates)?;
        self.claim_expr(t, &at, cx.scope)
    }

    /// The earlier step that `op` takes, holding what it needs.
    fn taken(
        &self,
        of: &Text,
        op: &str,
        needs: Holds,
        cx: &StepContext,
    ) -> Result<String, SceneError> {
        self.earlier(of, cx.field, op, needs, cx.earlier)?;
        Ok(of.get_ref().clone())
    }

    /// The earlier step holding the Lagrangian that `op` takes, in a scene with coordinates.
    fn lagrangian(&self, of: &Text, op: &str, cx: &StepContext) -> Result<String, SceneError> {
        self.earlier(of, cx.field, op, Holds::Expression, cx.earlier)?;
        if cx.coordinates.is_empty() {
            return Err(self.err(
                content_start(of),
                &format!("{}.{op}", cx.field),
                format!("`{op}` needs generalised coordinates: name them under [coordinates]"),
            ));
        }
        Ok(of.get_ref().clone())
    }

    /// A name the operation works in (`by`, a `set` name, a `series` variable): one of the
    /// scene's symbols, coordinates, rates or `t`, not an earlier step's.
    fn own_name(&self, name: &str, cx: &StepContext) -> bool {
        cx.scope.contains(name) && !cx.earlier.contains_key(name)
    }
}

/// The scene's names without the coordinates, their rates and the time: a state of rest is
/// given in them.
fn names_only(cx: &StepContext) -> BTreeSet<String> {
    cx.scope
        .iter()
        .filter(|n| *n != "t" && !n.ends_with('\'') && !cx.coordinates.contains_key(*n))
        .cloned()
        .collect()
}

#[cfg(test)]
mod tests {
    use super::{gives_field, gives_key};
    use crate::scene::operations::{OPERATION_FIELDS, OPERATIONS};
    use crate::scene::raw::RawStep;

    /// Every row of the table has its key read from a step, and every field too (an unknown
    /// name panics).
    #[test]
    fn every_operation_and_field_of_the_table_is_read_from_a_step() {
        let step: RawStep = toml::from_str("name = \"x\"").unwrap();
        for k in OPERATIONS {
            assert!(!gives_key(&step, k.name));
        }
        for (f, _) in OPERATION_FIELDS {
            assert!(!gives_field(&step, f));
        }
    }
}

#[cfg(test)]
mod table_tests;
