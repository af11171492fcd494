//! A step of the author's own derivation, as validated: its name, its one operation and the
//! notes' form of its result.

use super::operations::{Holds, MAX_UNKNOWNS, Operation, Several};
use super::verdict::{ClaimRole, Verdict};
use crate::cas::Expr;
use crate::scene::operations::Substitute;
use std::collections::BTreeMap;

/// A step of the author's derivation: a new name for the result of one operation.
#[derive(Debug, Clone, PartialEq)]
pub struct AuthorStep {
    pub name: String,
    pub op: Operation,
    /// The reason printed on the page.
    pub why: String,
    /// The notes' equation this step reproduces, if any.
    pub eq: Option<String>,
    /// The notes' form of the result: an expression, or for an equation its residual
    /// (`lhs - rhs`); agrees when it is the same (an equation, up to a non-zero factor).
    pub gives: Option<Expr>,
    /// The notes' form of each result of a step that gives several (`Omega_1`, `Omega_2`, …),
    /// in order: a list `gives`.
    pub gives_each: Vec<Expr>,
    /// The author's names for its several results (`names = ["slow", "fast"]`), in the order
    /// the step gives them; empty: `Omega_1`, `Omega_2`, ….
    pub names: Vec<String>,
    pub expect: Option<Verdict>,
    pub role: ClaimRole,
    /// For `lagrange`, `momentum` and `energy`: the state their numeric check integrates from,
    /// by coordinate and rate name.
    pub start: BTreeMap<String, f64>,
    pub line: usize,
}

impl AuthorStep {
    /// The names this step gives later steps and claims: its own, for a `frequency` of n ≥ 2
    /// coordinates its modes `Omega_1` ... `Omega_n`, one per coordinate, for a `solve` its
    /// roots or unknowns when it has several, and for `equilibria` and `stability` each state.
    pub fn names_given(&self, coordinates: usize) -> Vec<String> {
        let more = match self.op.kind().several {
            Several::None => 0,
            Several::Modes if coordinates >= 2 => coordinates,
            Several::Modes => 0,
            // A `solve` with several roots or unknowns names them `x_1`, `x_2`, ...
            Several::Roots => MAX_UNKNOWNS,
            // Each state of rest `rest_1`, ..., and its Ω² under the `stability` step's name.
            Several::States => MAX_NAMED_STATES,
        };
        if !self.names.is_empty() {
            return std::iter::once(self.name.clone())
                .chain(self.names.iter().cloned())
                .collect();
        }
        std::iter::once(self.name.clone())
            .chain((0..more).map(|k| mode_name(&self.name, k)))
            .collect()
    }

    /// What it holds for later steps (its row in `operations/`), a substitution's resolved from its
    /// operand among `earlier`: equations with names replaced are still equations of their
    /// kind; any other substitution gives an expression.
    pub fn holding(&self, earlier: &[AuthorStep]) -> Holds {
        match (self.op.kind().holds, &self.op) {
            (
                Holds::Operand,
                Operation::Substitute(Substitute {
                    of: Expr::Sym(n), ..
                }),
            ) => earlier
                .iter()
                .find(|s| s.name == *n)
                .map(|s| s.holding(earlier))
                .filter(|h| matches!(h, Holds::Motion | Holds::Linear))
                .unwrap_or(Holds::Expression),
            (Holds::Operand, _) => Holds::Expression,
            (holds, _) => holds,
        }
    }

    /// The names of its several results.
    pub fn result_names(&self) -> ResultNames<'_> {
        ResultNames {
            step: &self.name,
            own: &self.names,
        }
    }
}

/// The names of a step's several results: the author's `names`, else the step's name
/// numbered from 1 (`Omega_1`, `Omega_2`, …).
#[derive(Debug, Clone, Copy)]
pub struct ResultNames<'a> {
    pub step: &'a str,
    pub own: &'a [String],
}

impl ResultNames<'_> {
    /// A result of a step that names none of its own: `Omega_1` for the first of `Omega`.
    pub fn numbered(step: &str) -> ResultNames<'_> {
        ResultNames { step, own: &[] }
    }

    /// The name of the k-th result (from 0).
    pub fn kth(&self, k: usize) -> String {
        match self.own.get(k) {
            Some(name) => name.clone(),
            None => mode_name(self.step, k),
        }
    }
}

/// The most states of rest (and their Ω²) a step names for later steps and claims.
pub const MAX_NAMED_STATES: usize = 8;

/// The name of a `frequency` step's k-th normal mode, or a `solve` step's k-th root (from 0):
/// `Omega_1` for the first of `Omega`.
pub fn mode_name(step: &str, k: usize) -> String {
    format!("{step}_{}", k + 1)
}
