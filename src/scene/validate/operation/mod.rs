//! What a `[[step]]` does: exactly one operation of the table (`scene/operations/`), its fields
//! read and checked by the operation's own file there against what this validator knows at
//! the step (the scene's names, the coordinates and the earlier steps), and no field of
//! another operation.

use super::{Validator, content_start};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::operations::{
    Holds, OPERATION_FIELDS, OPERATIONS, Operation, OperationId, Several, StepFields,
    read_operation, stray_field_message,
};
use crate::scene::raw::{RawStep, Text};
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

/// The validator at one step: what an operation's file reads its fields through.
struct AtStep<'a> {
    v: &'a Validator<'a>,
    cx: &'a StepContext<'a>,
}

impl Validator<'_> {
    /// The one operation of a step.
    pub(super) fn operation(&self, s: &RawStep, cx: &StepContext) -> Result<Operation, SceneError> {
        let (offset, field) = (cx.offset, cx.field);
        let given: Vec<(OperationId, &Text)> = OperationId::ALL
            .iter()
            .filter_map(|&id| (id.kind().key)(s).map(|key| (id, key)))
            .collect();
        let [(id, key)] = given[..] else {
            return Err(self.err(
                offset,
                field,
                format!(
                    "a step does one thing: give exactly one of {} (this one gives {})",
                    OPERATIONS
                        .iter()
                        .map(|k| k.name)
                        .collect::<Vec<_>>()
                        .join(", "),
                    if given.is_empty() {
                        "none".to_string()
                    } else {
                        given
                            .iter()
                            .map(|(id, _)| id.kind().name)
                            .collect::<Vec<_>>()
                            .join(" and ")
                    }
                ),
            ));
        };
        let kind = id.kind();
        let op = read_operation(id, key, s, &AtStep { v: self, cx })?;
        // A field of another operation than this step's: said before anything else about it.
        for f in OPERATION_FIELDS {
            if (f.given)(s) && !kind.fields.contains(&f.name) {
                let message = stray_field_message(f.name).unwrap_or_default();
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
}

impl StepFields for AtStep<'_> {
    fn err(&self, at: usize, field: &str, message: impl Into<String>) -> SceneError {
        self.v.err(at, field, message)
    }

    fn offset(&self) -> usize {
        self.cx.offset
    }

    fn field(&self) -> &str {
        self.cx.field
    }

    fn scope(&self) -> &BTreeSet<String> {
        self.cx.scope
    }

    fn earlier(&self) -> &BTreeMap<String, Holds> {
        self.cx.earlier
    }

    fn coordinates(&self) -> &BTreeMap<String, String> {
        self.cx.coordinates
    }

    fn declared(&self) -> &BTreeSet<String> {
        &self.v.declared
    }

    fn expression(
        &self,
        t: &Text,
        key: &str,
        names: &BTreeSet<String>,
    ) -> Result<Expr, SceneError> {
        self.v.claim_expr(t, key, names)
    }

    fn operand(&self, t: &Text, key: &str) -> Result<Expr, SceneError> {
        let at = format!("{}.{key}", self.cx.field);
        self.v.rates_of_coordinates(t, &at, self.cx.coordinates)?;
        self.v.claim_expr(t, &at, self.cx.scope)
    }

    fn taken(&self, of: &Text, op: &str, needs: Holds) -> Result<String, SceneError> {
        self.v
            .earlier(of, self.cx.field, op, needs, self.cx.earlier)?;
        Ok(of.get_ref().clone())
    }

    fn lagrangian(&self, of: &Text, op: &str) -> Result<String, SceneError> {
        self.taken(of, op, Holds::Expression)?;
        if self.cx.coordinates.is_empty() {
            return Err(self.err(
                content_start(of),
                &format!("{}.{op}", self.cx.field),
                format!("`{op}` needs generalised coordinates: name them under [coordinates]"),
            ));
        }
        Ok(of.get_ref().clone())
    }
}

#[cfg(test)]
mod table_tests;
