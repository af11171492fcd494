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
    Holds, OPERATION_FIELDS, OPERATIONS, OperationId, OperationKind, Several, stray_field_message,
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

impl Validator<'_> {
    /// The one operation of a step.
    pub(super) fn operation(&self, s: &RawStep, cx: &StepContext) -> Result<Operation, SceneError> {
        let (offset, field) = (cx.offset, cx.field);
        let given: Vec<&OperationKind> =
            OPERATIONS.iter().filter(|k| (k.key)(s).is_some()).collect();
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
        for f in OPERATION_FIELDS {
            if (f.given)(s) && !kind.fields.contains(&f.name) {
                let message = stray_field_message(f.name).expect("a field of the table");
                return Err(self.err(offset, &format!("{field}.{}", f.name), message));
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
        use OperationId as Id;
        let key = (kind.key)(s).expect("the step gives its operation's key");
        Ok(match kind.id {
            Id::Be => Operation::Be(self.operand(key, "be", cx)?),
            Id::Differentiate => self.differentiate(key, s, cx)?,
            Id::Substitute => self.substitute(key, s, cx)?,
            Id::Lagrange => Operation::Lagrange {
                of: self.lagrangian(key, "lagrange", cx)?,
                constraints: self.constraints(s, cx)?,
            },
            Id::Routh => Operation::Routh {
                of: self.lagrangian(key, "routh", cx)?,
                cyclic: self.cyclic(s, cx)?,
            },
            Id::Momentum => self.momentum(key, s, cx)?,
            Id::Energy => Operation::Energy {
                of: self.lagrangian(key, "energy", cx)?,
            },
            Id::Linearise => self.linearise(key, s, cx)?,
            Id::Frequency => Operation::Frequency {
                of: self.taken(key, "frequency", Holds::Linear, cx)?,
            },
            Id::Solve => self.solve(key, s, cx)?,
            Id::Series => self.series(key, s, cx)?,
            Id::Integrate => self.integrate(key, s, cx)?,
            Id::Equilibria => Operation::Equilibria {
                of: self.taken(key, "equilibria", Holds::Motion, cx)?,
            },
            Id::Stability => Operation::Stability {
                of: self.taken(key, "stability", Holds::Equilibria, cx)?,
            },
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
mod table_tests;
