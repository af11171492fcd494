//! What an author's step found, and the names it gives later steps and claims.

use crate::cas::{self, Expr};
use crate::scene::{MAX_NAMED_STATES, ResultNames};

/// What a step found: an expression, or equations of motion (each coordinate's residual, which
/// the motion keeps at zero).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum StepResult {
    Expr(Expr),
    /// A generalised momentum or the energy function, and whether the motion conserves it.
    Conserved {
        value: Expr,
        conserved: bool,
    },
    Equations(Vec<(String, Expr)>),
    /// The normal-mode angular frequencies of n ≥ 2 coordinates, in the order of
    /// `derive/result_order.rs` (slowest first where that holds across the domain).
    Modes(Vec<Expr>),
    /// The normal-mode angular frequencies at the scene's values, slowest first, where they
    /// have no closed form, and why.
    NumericModes {
        frequencies: Vec<f64>,
        reason: crate::model::prose::Prose,
    },
    /// Every root of a `solve` that has more than one, in the order of
    /// `derive/result_order.rs` (smallest first where that holds across the domain).
    Roots(Vec<Expr>),
    /// The value of each unknown of a `solve` of several, in the order of `for`.
    Solution(Vec<(String, Expr)>),
    /// The states of rest of one coordinate.
    Equilibria {
        coordinate: String,
        zeros: Vec<cas::Zero>,
        /// The static equation's roots that are not real at the scene's values, set aside.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        excluded: Vec<Expr>,
    },
    /// About each equilibrium, the squared frequency of small oscillations and its sign.
    Stability {
        coordinate: String,
        cases: Vec<Stability>,
    },
    /// The states of rest of several coordinates: a zero of each, in `coordinates`' order.
    RestStates {
        coordinates: Vec<String>,
        states: Vec<Vec<cas::Zero>>,
        /// Roots of the static equations real for no values of the symbols, set aside:
        /// (coordinate, root).
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        excluded: Vec<(String, Expr)>,
    },
    /// About each of those states, its stiffness and whether it is stable.
    RestStability {
        coordinates: Vec<String>,
        cases: Vec<StateStability>,
    },
}

/// One state of rest of several coordinates: K = ∂R/∂q there (row-major), its leading
/// principal minors, and the verdict (stable where every minor is positive).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StateStability {
    pub at: Vec<cas::Zero>,
    pub stiffness: Vec<Expr>,
    pub minors: Vec<Expr>,
    pub verdict: Stable,
}

/// One equilibrium's stability: Ω² = k/m there, stable where it is positive.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Stability {
    pub at: cas::Zero,
    /// None where its exact form would expand beyond the engine's budget.
    pub omega_squared: Option<Expr>,
    pub verdict: Stable,
}

/// Whether an equilibrium is stable, for positive values of every symbol.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Stable {
    Always,
    Never,
    /// Where Ω² > 0: the condition is the page's.
    Where,
    /// Ω² not derived (beyond the engine's budget): its value at the scene's values is the
    /// numeric check's.
    Unknown,
}

impl StepResult {
    /// Every expression the page prints, for the presentation pass to rewrite in place.
    pub fn printed_mut(&mut self) -> Vec<&mut Expr> {
        match self {
            StepResult::Expr(e) | StepResult::Conserved { value: e, .. } => vec![e],
            StepResult::Equations(eqs) | StepResult::Solution(eqs) => {
                eqs.iter_mut().map(|(_, e)| e).collect()
            }
            StepResult::Modes(v) | StepResult::Roots(v) => v.iter_mut().collect(),
            StepResult::Equilibria { zeros, .. } => {
                zeros.iter_mut().map(|z| &mut z.value).collect()
            }
            StepResult::Stability { cases, .. } => cases
                .iter_mut()
                .filter_map(|c| c.omega_squared.as_mut())
                .collect(),
            StepResult::NumericModes { .. }
            | StepResult::RestStates { .. }
            | StepResult::RestStability { .. } => Vec::new(),
        }
    }

    /// How many results the step gives: one per name in [`StepResult::values`], and one per
    /// numeric mode and state of several coordinates (which have no one exact value to name).
    pub fn count(&self, names: ResultNames) -> usize {
        match self {
            StepResult::NumericModes { frequencies, .. } => frequencies.len(),
            StepResult::RestStates { states, .. } => states.len(),
            StepResult::RestStability { cases, .. } => cases.len(),
            StepResult::Stability { cases, .. } => cases.len(),
            _ => self.values(names).len(),
        }
    }

    /// The one expression a later step may use by this step's name.
    pub fn scalar(&self) -> Option<&Expr> {
        match self {
            StepResult::Expr(e) | StepResult::Conserved { value: e, .. } => Some(e),
            StepResult::Equations(_)
            | StepResult::Modes(_)
            | StepResult::NumericModes { .. }
            | StepResult::Roots(_)
            | StepResult::Solution(_)
            | StepResult::Equilibria { .. }
            | StepResult::Stability { .. }
            | StepResult::RestStates { .. }
            | StepResult::RestStability { .. } => None,
        }
    }

    /// The equations of motion, linear equations or steady state a step holds.
    pub fn equations(&self) -> Option<&[(String, Expr)]> {
        match self {
            StepResult::Equations(eqs) => Some(eqs),
            _ => None,
        }
    }

    /// What `solve` takes from the step `name`: its equations, or its expression e as e = 0.
    pub fn solvable(&self, name: &str) -> Option<std::borrow::Cow<'_, [(String, Expr)]>> {
        match (self.equations(), self.scalar()) {
            (Some(eqs), _) => Some(eqs.into()),
            (None, Some(e)) => Some(vec![(name.to_string(), e.clone())].into()),
            (None, None) => None,
        }
    }

    /// The names later steps and claims use: the step's own name for an expression, and
    /// `Omega_1`, `Omega_2`, ... (or the author's `names`) for the modes of a step `Omega`.
    pub fn values(&self, names: ResultNames) -> Vec<(String, Expr)> {
        let name = names.step;
        match self {
            StepResult::Equilibria { zeros, .. } => zeros
                .iter()
                .take(MAX_NAMED_STATES)
                .enumerate()
                .map(|(k, z)| (names.kth(k), z.value.clone()))
                .collect(),
            // Ω² about each state, where it was derived.
            StepResult::Stability { cases, .. } => cases
                .iter()
                .take(MAX_NAMED_STATES)
                .enumerate()
                .filter_map(|(k, c)| Some((names.kth(k), c.omega_squared.clone()?)))
                .collect(),
            StepResult::Solution(pairs) => pairs
                .iter()
                .enumerate()
                .map(|(k, (_, value))| (names.kth(k), value.clone()))
                .collect(),
            StepResult::Modes(values) | StepResult::Roots(values) => values
                .iter()
                .enumerate()
                .map(|(k, w)| (names.kth(k), w.clone()))
                .collect(),
            _ => self
                .scalar()
                .map(|e| vec![(name.to_string(), e.clone())])
                .unwrap_or_default(),
        }
    }

    /// Every result the step gives, in order, as `check --bless` records them: each value,
    /// root, mode, unknown and equation of motion (its residual); each state of rest's
    /// coordinates (a list), and about each state its Ω² or its stiffness's leading minors (a
    /// list).
    pub fn recordables(&self) -> Vec<Recordable> {
        let exact = |e: &Expr| Recordable::Exact(e.clone());
        match self {
            StepResult::Expr(e) | StepResult::Conserved { value: e, .. } => vec![exact(e)],
            StepResult::Equations(eqs) | StepResult::Solution(eqs) => {
                eqs.iter().map(|(_, e)| exact(e)).collect()
            }
            StepResult::Modes(v) | StepResult::Roots(v) => v.iter().map(exact).collect(),
            StepResult::NumericModes { frequencies, .. } => {
                frequencies.iter().map(|w| Recordable::Number(*w)).collect()
            }
            StepResult::Equilibria { zeros, .. } => zeros.iter().map(|z| exact(&z.value)).collect(),
            StepResult::Stability { cases, .. } => cases
                .iter()
                .map(|c| {
                    c.omega_squared
                        .as_ref()
                        .map_or(Recordable::NotDerived, exact)
                })
                .collect(),
            StepResult::RestStates { states, .. } => states
                .iter()
                .map(|s| Recordable::Exact(Expr::List(s.iter().map(|z| z.value.clone()).collect())))
                .collect(),
            StepResult::RestStability { cases, .. } => cases
                .iter()
                .map(|c| Recordable::Exact(Expr::List(c.minors.clone())))
                .collect(),
        }
    }

    /// What a printed line that stands for `s` must show (see [`StandsFor`]).
    pub fn stood_for(&self, names: ResultNames, s: &StandsFor) -> Option<Stands> {
        match (s, self) {
            (StandsFor::Equation(q), StepResult::Equations(eqs)) => eqs
                .iter()
                .find(|(c, _)| c == q)
                .map(|(_, e)| Stands::Residual(e.clone())),
            (StandsFor::Result(name), StepResult::NumericModes { frequencies, .. }) => frequencies
                .iter()
                .enumerate()
                .find(|(k, _)| names.kth(*k) == *name)
                .map(|(_, w)| Stands::Number(*w)),
            (StandsFor::Result(name), _) => self
                .values(names)
                .into_iter()
                .find(|(n, _)| n == name)
                .map(|(_, e)| Stands::Value(e)),
            (StandsFor::Equation(_), _) => None,
        }
    }
}

/// One result of a step as `check --bless` records it in `[expect]`.
#[derive(Debug, Clone, PartialEq)]
pub enum Recordable {
    Exact(Expr),
    /// A numeric result (a mode with no closed form): its value at the scene's values.
    Number(f64),
    /// A result the engine did not derive (an Ω² beyond its budget).
    NotDerived,
}

impl Recordable {
    /// As `[expect]` writes it: an exact form, a number to all its digits (Rust's shortest
    /// form that reads back to the same `f64`), or [`crate::scene::NOT_DERIVED`].
    pub fn text(&self) -> String {
        match self {
            Recordable::Exact(e) => e.to_text(),
            Recordable::Number(x) => format!("{x}"),
            Recordable::NotDerived => crate::scene::NOT_DERIVED.to_string(),
        }
    }
}

/// What one printed line of an author's step states, by the name the derivation gives it: set
/// where the line is made (`steps/page.rs`), so that the build can read the line back, after
/// every later change of form, and check it against the result (`render/guard.rs`).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum StandsFor {
    /// `symbol = value`: the result of that name (the step's own, or its k-th: `Omega_2`).
    Result(String),
    /// `… = 0`: the equation of motion of that coordinate.
    Equation(String),
}

/// What a printed line must show: an exact value, a number to its printed figures, or an
/// equation whose residual is in proportion to this one.
#[derive(Debug, Clone, PartialEq)]
pub enum Stands {
    Value(Expr),
    Number(f64),
    Residual(Expr),
}
