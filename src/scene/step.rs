//! A step of the author's own derivation, as validated: its name, its one operation and the
//! notes' form of its result.

use super::operations::{Holds, OperationId, OperationKind, Several};
use super::verdict::{ClaimRole, Verdict};
use crate::cas::Expr;
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

    /// What it holds for later steps (`operations.rs`), a substitution's resolved from its
    /// operand among `earlier`: equations with names replaced are still equations of their
    /// kind; any other substitution gives an expression.
    pub fn holding(&self, earlier: &[AuthorStep]) -> Holds {
        match (self.op.kind().holds, &self.op) {
            (
                Holds::Operand,
                Operation::Substitute {
                    of: Expr::Sym(n), ..
                },
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

/// The most unknowns of one `solve` (a rolling disk's five coordinates and two multipliers,
/// and one more), and of the roots it names: `x_1` to `x_8`.
pub const MAX_UNKNOWNS: usize = 8;

/// The most states of rest (and their Ω²) a step names for later steps and claims.
pub const MAX_NAMED_STATES: usize = 8;

/// The name of a `frequency` step's k-th normal mode, or a `solve` step's k-th root (from 0):
/// `Omega_1` for the first of `Omega`.
pub fn mode_name(step: &str, k: usize) -> String {
    format!("{step}_{}", k + 1)
}

/// What a step does.
#[derive(Debug, Clone, PartialEq)]
pub enum Operation {
    /// An expression of the scene's names and earlier steps.
    Be(Expr),
    /// A partial derivative; by `t`, the total time derivative through the coordinates.
    Differentiate { of: Expr, by: String },
    /// The Euler–Lagrange equation of each coordinate, from the named Lagrangian, with each
    /// constraint's multiplier λ: d/dt ∂L/∂q' − ∂L/∂q − Σ λ ∂f/∂q = 0, and each constraint
    /// f(q) = 0 differentiated twice, an equation under its multiplier's name.
    Lagrange {
        of: String,
        constraints: Vec<(String, Expr)>,
    },
    /// Routh's procedure on the named Lagrangian: R = L − Σ p φ' with each cyclic coordinate φ's
    /// rate solved from p = ∂L/∂φ', its conserved momentum p a symbol.
    Routh {
        of: String,
        /// Each cyclic coordinate and its momentum's symbol.
        cyclic: Vec<(String, String)>,
    },
    /// The named equations of motion to first order about a state at rest (each coordinate's
    /// value there; 0 when not named).
    Linearise {
        of: String,
        about: BTreeMap<String, Expr>,
    },
    /// The angular frequency of small oscillations of the named linear equation.
    Frequency { of: String },
    /// An expression with names replaced (a constraint such as θ' = x'/R).
    Substitute {
        of: Expr,
        set: BTreeMap<String, Expr>,
    },
    /// The named equations of motion solved: for one unknown, the equation that contains it
    /// (every root); for several, the linear system of the equations that contain them.
    Solve { of: String, unknowns: Vec<String> },
    /// The generalised momentum ∂L/∂q' of one coordinate, from the named Lagrangian.
    Momentum { of: String, coordinate: String },
    /// The energy function Σ q'·∂L/∂q' − L of the named Lagrangian.
    Energy { of: String },
    /// A definite integral, innermost variable first: each (variable, from, to), whose limits
    /// may use the variables after it.
    Integrate {
        of: Expr,
        over: Vec<(String, Expr, Expr)>,
    },
    /// The Taylor series of an expression in one name about a value, to the given order.
    Series {
        of: Expr,
        var: String,
        about: Expr,
        order: u32,
    },
    /// The states of rest of the named equation of motion (one coordinate).
    Equilibria { of: String },
    /// Whether each of the named equilibria is stable.
    Stability { of: String },
}

impl Operation {
    /// Which operation it is.
    pub fn id(&self) -> OperationId {
        match self {
            Operation::Be(_) => OperationId::Be,
            Operation::Differentiate { .. } => OperationId::Differentiate,
            Operation::Lagrange { .. } => OperationId::Lagrange,
            Operation::Routh { .. } => OperationId::Routh,
            Operation::Linearise { .. } => OperationId::Linearise,
            Operation::Frequency { .. } => OperationId::Frequency,
            Operation::Substitute { .. } => OperationId::Substitute,
            Operation::Solve { .. } => OperationId::Solve,
            Operation::Momentum { .. } => OperationId::Momentum,
            Operation::Energy { .. } => OperationId::Energy,
            Operation::Series { .. } => OperationId::Series,
            Operation::Integrate { .. } => OperationId::Integrate,
            Operation::Equilibria { .. } => OperationId::Equilibria,
            Operation::Stability { .. } => OperationId::Stability,
        }
    }

    /// The operation's row in the table of operations.
    pub fn kind(&self) -> &'static OperationKind {
        self.id().kind()
    }

    /// What the step does, in words: its heading on a page where its name is no symbol.
    pub fn heading(&self) -> &'static str {
        self.kind().heading
    }

    pub fn name(&self) -> &'static str {
        self.kind().name
    }

    /// The expressions the author wrote as its operands (an integral's limits, a series'
    /// point, a substitution's replacements): an operation that takes an earlier step by
    /// name has none.
    pub fn operands(&self) -> Vec<&Expr> {
        match self {
            Operation::Be(e) => vec![e],
            Operation::Differentiate { of, .. } => vec![of],
            Operation::Linearise { about, .. } => about.values().collect(),
            Operation::Series { of, about, .. } => vec![of, about],
            Operation::Integrate { of, over } => std::iter::once(of)
                .chain(over.iter().flat_map(|(_, lo, hi)| [lo, hi]))
                .collect(),
            Operation::Substitute { of, set } => std::iter::once(of).chain(set.values()).collect(),
            Operation::Lagrange { .. }
            | Operation::Routh { .. }
            | Operation::Frequency { .. }
            | Operation::Solve { .. }
            | Operation::Momentum { .. }
            | Operation::Energy { .. }
            | Operation::Equilibria { .. }
            | Operation::Stability { .. } => vec![],
        }
    }
}
