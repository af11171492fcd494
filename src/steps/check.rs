//! One step's numeric check and what the routes share: its record, why it could not run, and
//! the evaluation of an expression at a point without the engine.

use crate::base::rng::Rng;
use crate::cas::Expr;
use crate::derive::Derivation;
use crate::derive::step_names::StepResult;
use crate::numeric::random_points::{
    CONFIRMATION_POINTS, DOMAIN_TRIES, SAMPLE_FROM, compare_in_domain,
};
use std::collections::BTreeMap;

/// Why a step's numeric route could not run.
#[derive(Debug, thiserror::Error)]
pub enum CheckError {
    #[error(transparent)]
    Eval(#[from] crate::cas::EvalError),
    #[error(
        "the printed form of the step's result {number} differs from its exact result at random \
         points: a fault in mechbook's presentation pass, please report it (`--json` keeps the \
         exact form)"
    )]
    PrintedDiffers { number: usize },
    #[error("`{expression}` is {value} on the way: the check cannot compare it")]
    Undefined { expression: String, value: f64 },
    #[error(
        "the expressions are undefined or infinite at the random points: too few of {tries} \
         drawn could be compared"
    )]
    NoPointInDomain { tries: usize },
    #[error(transparent)]
    Step(#[from] crate::derive::step_names::StepError),
    #[error(transparent)]
    Motion(#[from] crate::numeric::ode::OdeError),
    #[error(transparent)]
    OverBudget(#[from] crate::numeric::budget::OverBudget),
    #[error(transparent)]
    Equations(#[from] crate::derive::DeriveError),
    #[error(
        "the static equation also vanishes at {at:.9} (at the scene's values), where no exact \
         equilibrium is"
    )]
    MissedZero { at: f64 },
    #[error(
        "the exact equilibrium {at:.9} (at the scene's values) is not where the static equation \
         changes sign"
    )]
    NotAZero { at: f64 },
    #[error("about {at:.9}, Ω² is {square:e} at the scene's values, against the stated verdict")]
    WrongVerdict { at: f64, square: f64 },
    #[error(
        "the static equations also vanish at {at} (at the scene's values), where no exact state \
         of rest is"
    )]
    MissedState { at: String },
    #[error(
        "the exact state of rest {at} (at the scene's values) is not one Newton's method finds"
    )]
    NotAState { at: String },
    #[error(
        "about {at}, the eigenvalues of M⁻¹K are {squares} at the scene's values, against the \
         stated verdict"
    )]
    WrongStateVerdict { at: String, squares: String },
    #[error(
        "no solution is real at the random points or at the scene's values: nothing to put back"
    )]
    NoRealRoot,
    #[error(
        "the expression or its series is not a finite number at {at:e} (at the scene's values)"
    )]
    NotFinite { at: f64 },
    #[error(
        "the expression as written, or the result, has a finite value at none of the random \
         points (0/0 or a pole where the replacement puts it)"
    )]
    NoValue,
    #[error("the equations cannot be solved for the accelerations here (a singular mass matrix)")]
    Singular,
    #[error("the eigenvalues of the linear equations did not converge")]
    NoEigenvalues,
    #[error(
        "the motion from the step's start stays where it is (a state of rest), which tests \
         nothing: give the step a `start` away from rest, such as start = {{ {coordinate} = 0.3 }}"
    )]
    AtRest { coordinate: String },
    #[error(
        "the Lagrangian depends on t: the numeric check integrates time-independent motions only"
    )]
    TimeDependent,
    #[error(
        "the step's start is off the constraint of `{multiplier}`: its {what} is {value:e} there, \
         not 0; give a `start` whose coordinates satisfy every constraint and whose rates move \
         along them"
    )]
    OffConstraint {
        multiplier: String,
        /// "value" or "rate of change".
        what: &'static str,
        value: f64,
    },
    #[error(
        "the motion started off rest did not cross rest twice in three periods: it does not oscillate there"
    )]
    NoOscillation,
    /// The step or one it names has no result of its kind: a bug, the derivation ran first.
    #[error("internal inconsistency: the step's result is missing or of another kind")]
    NotDerived,
}

/// One step's numeric check: what it compared, how far apart, and what it cost.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct StepCheck {
    pub step: String,
    pub line: usize,
    /// The route, in words: "central differences", "energy along an integrated motion".
    pub method: String,
    /// The largest relative difference found, and the most it may be.
    pub error: f64,
    pub tolerance: f64,
    /// Evaluations of the step's expressions (or of the right-hand side).
    pub evaluations: u64,
    /// Why the check could not run, if it could not.
    pub problem: Option<String>,
}

impl From<crate::numeric::motion::MotionError> for CheckError {
    fn from(e: crate::numeric::motion::MotionError) -> CheckError {
        match e {
            crate::numeric::motion::MotionError::Eval(e) => CheckError::Eval(e),
            crate::numeric::motion::MotionError::Singular => CheckError::Singular,
        }
    }
}

impl StepCheck {
    /// A check of step `step` (at `line`) before its route has run: no method, no error, no
    /// work.
    pub fn not_yet_run(step: &str, line: usize) -> StepCheck {
        StepCheck {
            step: step.into(),
            line,
            method: String::new(),
            error: 0.0,
            tolerance: 0.0,
            evaluations: 0,
            problem: None,
        }
    }

    pub fn passed(&self) -> bool {
        self.problem.is_none() && self.error.is_finite() && self.error <= self.tolerance
    }
}

/// The step of the central differences that check a derivative, a momentum or a curvature.
pub(crate) const H: f64 = 1e-3;

/// Every symbol of the expressions at a random value in [0.4, 1.4) (π is π).
pub(crate) fn random_point(
    exprs: &[&Expr],
    rng: &mut Rng,
    scene: &crate::scene::Scene,
) -> BTreeMap<String, f64> {
    let mut names: Vec<String> = exprs.iter().flat_map(|e| e.symbols()).collect();
    names.sort();
    names.dedup();
    names.retain(|s| s != "pi");
    let mut draw = || -> BTreeMap<String, f64> {
        names
            .iter()
            .map(|s| (s.clone(), SAMPLE_FROM + rng.uniform()))
            .collect()
    };
    // Inside the physics' domain (`assume`), where a scene states one: the load checked that
    // such points exist; should these draws all miss, the last is compared, and says so.
    let mut point = draw();
    for _ in 1..crate::numeric::random_points::DOMAIN_TRIES {
        if scene.in_domain(&point) {
            break;
        }
        point = draw();
    }
    point
}

/// Runs `compare` at random points until three fall in the domain
/// ([`compare_in_domain`]); when too few do, the check cannot run.
pub(crate) fn compare_at_points(
    compare: impl FnMut() -> Result<bool, CheckError>,
) -> Result<(), CheckError> {
    if compare_in_domain(compare)? < CONFIRMATION_POINTS {
        return Err(CheckError::NoPointInDomain {
            tries: CONFIRMATION_POINTS * DOMAIN_TRIES,
        });
    }
    Ok(())
}

pub(crate) fn at(e: &Expr, point: &BTreeMap<String, f64>) -> Result<f64, CheckError> {
    Ok(e.eval(&|s| point.get(s).copied().filter(|_| s != "pi"))?)
}

/// The equations of the named step.
pub(crate) fn equations_of<'a>(
    d: &'a Derivation,
    of: &str,
) -> Result<&'a [(String, Expr)], CheckError> {
    d.named
        .get(of)
        .and_then(StepResult::equations)
        .ok_or(CheckError::NotDerived)
}

/// What a `solve` step took from the named step: its equations, or its expression as e = 0.
pub(crate) fn solvable_of<'a>(
    d: &'a Derivation,
    of: &str,
) -> Result<std::borrow::Cow<'a, [(String, Expr)]>, CheckError> {
    d.named
        .get(of)
        .and_then(|r| r.solvable(of))
        .ok_or(CheckError::NotDerived)
}
