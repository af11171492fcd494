//! The author's step operations, one file per operation: its exact rule (`derive`) beside its
//! numeric route (`check`), which does not go through the engine, as `impl Rule` for the
//! operation's type. The type, its row of the table (name, fields, what each holds and gives)
//! and the checks of its fields are its file of the same name under `scene/operations/`; how a
//! result shows on the page is `page.rs`, in the words each rule gives (`Rule::wording`).
//! A step's `gives` is a claim of the notes, checked in `verify/gives.rs`.
//!
//! The stage sits above `derive` and `numeric`, whose mechanics the operations share, and
//! below `verify`, which reads its checks: the numeric routes of the steps (`check.rs`, and
//! `motion.rs`, `rest.rs`, `rest_states.rs` shared by the operations on equations of motion)
//! live here, not in `verify`. The pipeline runs it after the built-in derivation and checks.

mod be;
pub(crate) mod check;
mod differentiate;
mod energy;
mod equation_form;
mod equilibria;
mod frequency;
pub(crate) mod integrate;
mod lagrange;
mod linearise;
mod momentum;
pub(crate) mod motion;
mod page;
pub(crate) mod rest;
pub(crate) mod rest_states;
pub(crate) mod routh;
pub(crate) mod series;
pub(crate) mod solve;
mod stability;
mod substitute;

use crate::cas::{self, Expr};
use crate::derive::lagrangian::simplify_two;
use crate::derive::step_names::{StepError, StepResult};
use crate::derive::{Derivation, DeriveError};
use crate::notation::Formula;
use crate::numeric::budget::Deadline;
use crate::numeric::random_points::CONFIRMATION_POINTS;
use crate::numeric::random_points::{numerically_zero, signed_names};
use crate::scene::{AuthorStep, Operation, Scene};
use check::equations_of;
pub use check::{CheckError, StepCheck};

/// The step at hand: its scene, the derivation up to it, and the step.
#[derive(Clone, Copy)]
struct Context<'a> {
    scene: &'a Scene,
    d: &'a Derivation,
    step: &'a AuthorStep,
}

/// A step's numeric check at hand: the step in its context, its derived result, and the seed
/// of its random points.
#[derive(Clone, Copy)]
struct Checking<'a> {
    scene: &'a Scene,
    d: &'a Derivation,
    step: &'a AuthorStep,
    result: &'a StepResult,
    seed: u64,
}

/// Derives every step in order, each simplified by the engine, and writes its page steps.
pub fn derive_steps(scene: &Scene, d: &mut Derivation) -> Result<(), DeriveError> {
    let start = std::time::Instant::now();
    for step in &scene.steps {
        // Each step is within the engine's budget; the scene as a whole within this one.
        if start.elapsed() > STEPS_TIME_BUDGET {
            return Err(locate(
                step,
                DeriveError::NotDerivable(format!(
                    "the scene's steps before this one took {:.0} s, past the {} s a scene's \
                     derivation may take: split the scene",
                    start.elapsed().as_secs_f64(),
                    STEPS_TIME_BUDGET.as_secs()
                )),
            ));
        }
        // A statement other than `name = result`: an integral shown with its limits.
        let mut shown: Option<Formula> = None;
        let result = derive_step(scene, d, step, &mut shown).map_err(|e| locate(step, e))?;
        named_as_listed(step, &result).map_err(|e| locate(step, e))?;
        let printed = rule_of(&step.op)
            .printed(Context { scene, d, step }, &result, &mut shown)
            .map_err(|e| locate(step, e))?;
        let mut steps = page::page_steps(scene, step, printed.as_ref().unwrap_or(&result));
        if printed.is_some() {
            for (shown, exact) in steps.iter_mut().zip(page::page_steps(scene, step, &result)) {
                if shown.statement != exact.statement {
                    shown.exact = Some(exact.statement);
                }
            }
        }
        if let (Some(formula), [only]) = (shown, &mut steps[..]) {
            only.statement = formula;
        }
        d.steps.extend(steps);
        if let Some(printed) = printed {
            d.printed.insert(step.name.clone(), printed);
        }
        d.named.insert(step.name.clone(), result);
    }
    Ok(())
}

/// The author's `names`, one for each result the step gives.
fn named_as_listed(step: &AuthorStep, result: &StepResult) -> Result<(), DeriveError> {
    let listed = step.names.len();
    let given = match result.scalar() {
        Some(_) => 1,
        None => result.count(step.result_names()),
    };
    if listed == 0 || (listed == given && result.scalar().is_none()) {
        return Ok(());
    }
    Err(DeriveError::NotDerivable(match result.scalar() {
        Some(_) => format!(
            "the step gives one result, named `{}` by its `name`: leave out `names`",
            step.name
        ),
        None => format!(
            "the step gives {given} results, and `names` lists {listed}: list one name for each, \
             in the step's order (without `names`, the page numbers them)"
        ),
    }))
}

/// The result in the forms a textbook prints (`cas::present_all`), where any differs from the
/// exact result; the step's check compares the two at random points.
fn printed_form(scene: &Scene, result: &StepResult) -> Result<Option<StepResult>, DeriveError> {
    let mut printed = result.clone();
    let exact: Vec<Expr> = printed
        .printed_mut()
        .into_iter()
        .map(|e| e.clone())
        .collect();
    let forms = cas::present_all(
        exact.clone(),
        scene.signed_names(),
        scene.declared.clone(),
        crate::notation::printed_length,
    )?;
    if forms == exact {
        return Ok(None);
    }
    for (slot, form) in printed.printed_mut().into_iter().zip(forms) {
        *slot = form;
    }
    Ok(Some(printed))
}

/// The most time a scene's own steps may take to derive, checked before each step: a course's
/// scenes take milliseconds to a few seconds.
pub const STEPS_TIME_BUDGET: std::time::Duration = std::time::Duration::from_secs(120);

/// One step's result, derived by its operation's exact rule (its errors located by the
/// caller); `shown` takes a statement other than `name = result` (an integral with its limits).
fn derive_step(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    shown: &mut Option<Formula>,
) -> Result<StepResult, DeriveError> {
    rule_of(&step.op).derive(Context { scene, d, step }, shown)
}

/// What an operation does, in its file of the same name here: its exact rule, its numeric
/// route, and the words and form its result takes on the page.
trait Rule {
    /// Its result by the exact rule (its errors located by the caller); `shown` takes a
    /// statement other than `name = result` (an integral with its limits).
    fn derive(&self, cx: Context, shown: &mut Option<Formula>) -> Result<StepResult, DeriveError>;

    /// Its result checked by the numeric route, which does not go through the engine.
    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError>;

    /// The result as the page prints it, where that differs from the exact result: by
    /// default the forms a textbook prints (`printed_form`); `shown` as in `derive`.
    fn printed(
        &self,
        cx: Context,
        result: &StepResult,
        _shown: &mut Option<Formula>,
    ) -> Result<Option<StepResult>, DeriveError> {
        printed_form(cx.scene, result)
    }

    /// The words its result takes on the page, where they are its own (`page::Wording`).
    fn wording(&self) -> page::Wording<'_> {
        page::Wording::default()
    }
}

/// Each operation's file, and its rule, from the one list of operations.
macro_rules! rules {
    ($($op:ident $file:ident $row:tt,)*) => {
        /// The rule of a step's operation.
        fn rule_of(op: &Operation) -> &dyn Rule {
            match op {
                $(Operation::$op(o) => o,)*
            }
        }
    };
}
crate::scene::operations::with_operations!(rules);

/// An error of a step, at the step's line; an expansion over the engine's budget says what to
/// do about a step, not about a body.
fn locate(step: &AuthorStep, e: DeriveError) -> DeriveError {
    let message = match &e {
        DeriveError::Step(_) | DeriveError::Inconsistent(_) | DeriveError::Missing(_) => {
            return e;
        }
        DeriveError::Cas(cas::CasError {
            reason: cas::CasFailure::Engine(cas::EngineError::OverBudget { degree, terms }),
        }) => format!(
            "its expressions would expand to degree {degree} with {terms:.0e} terms, beyond the \
             engine's budget: split the step into smaller ones, or give a part a name of its \
             own under [definitions]"
        ),
        other => other.to_string(),
    };
    DeriveError::Step(StepError::Operation {
        step: step.name.clone(),
        line: step.line,
        message,
    })
}

/// A momentum or energy, conserved when the force on it (∂L/∂q, or ∂L/∂t) is identically 0.
fn conserved(value: Expr, force: Expr) -> Result<StepResult, DeriveError> {
    let (value, force) = simplify_two(value, force)?;
    Ok(StepResult::Conserved {
        value,
        conserved: force.is_zero(),
    })
}

/// A momentum's or energy's numeric route: along the motion of the named Lagrangian
/// (`motion::conserved_check`).
fn conserved_route(
    cx: Checking,
    of: &str,
    what: motion::Conserved,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    let StepResult::Conserved { value, conserved } = cx.result else {
        return Err(CheckError::NotDerived);
    };
    let lagrangian = scalar_of(cx.d, of)?;
    motion::conserved_check(
        cx.scene, cx.step, lagrangian, value, *conserved, what, check,
    )
}

/// The expression a validated earlier step holds.
fn scalar<'a>(d: &'a Derivation, of: &str) -> Result<&'a Expr, DeriveError> {
    d.named.get(of).and_then(StepResult::scalar).ok_or_else(|| {
        DeriveError::Inconsistent(format!(
            "step `{of}` was validated as an earlier scalar step"
        ))
    })
}

/// Equations with each residual simplified (in one call to the engine), their names kept.
fn simplified(eqs: Vec<(String, Expr)>) -> Result<StepResult, DeriveError> {
    let (names, exprs): (Vec<String>, Vec<Expr>) = eqs.into_iter().unzip();
    let exprs = cas::simplify_all(exprs)?;
    Ok(StepResult::Equations(
        names.into_iter().zip(exprs).collect(),
    ))
}

/// The equations a validated earlier step holds.
fn equations<'a>(d: &'a Derivation, of: &str) -> Result<&'a [(String, Expr)], DeriveError> {
    d.named
        .get(of)
        .and_then(StepResult::equations)
        .ok_or_else(|| {
            DeriveError::Inconsistent(format!(
                "step `{of}` was validated as earlier equations of motion"
            ))
        })
}

/// The equations of `of`, each a coordinate's: equations that carry a constraint's
/// multiplier are refused (its motion is the coordinates' that remain once it is eliminated).
fn free_equations<'a>(
    scene: &Scene,
    d: &'a Derivation,
    of: &str,
    op: &str,
) -> Result<&'a [(String, Expr)], DeriveError> {
    let eqs = equations(d, of)?;
    if let Some((lambda, _)) = eqs.iter().find(|(q, _)| !scene.coordinates.contains_key(q)) {
        return Err(DeriveError::NotDerivable(format!(
            "the equations of `{of}` carry the multiplier `{lambda}` of a constraint: `{op}` \
             takes the equations of independent coordinates, so write the Lagrangian in \
             coordinates the constraint leaves free and take `{op}` of those"
        )));
    }
    Ok(eqs)
}

/// Each step's numeric check, in order; those after the deadline are not checked, and say so.
pub fn check_steps(scene: &Scene, d: &Derivation, deadline: &Deadline) -> Vec<StepCheck> {
    (0..scene.steps.len())
        .map(|i| match deadline.check() {
            Ok(()) => check_step(scene, d, i),
            Err(over) => StepCheck {
                problem: Some(CheckError::from(over).to_string()),
                ..StepCheck::not_yet_run(&scene.steps[i].name, scene.steps[i].line)
            },
        })
        .collect()
}

/// The numeric check of step `i` (each step draws its random points from its own seed).
pub fn check_step(scene: &Scene, d: &Derivation, i: usize) -> StepCheck {
    let step = &scene.steps[i];
    let mut check = StepCheck::not_yet_run(&step.name, step.line);
    let seed = scene.seed.wrapping_add(1000 + i as u64);
    if let Err(problem) = route(scene, d, step, seed, &mut check) {
        check.problem = Some(problem.to_string());
    }
    if let Err(problem) = printed_check(scene, d, step, seed, &mut check) {
        check.problem.get_or_insert(problem.to_string());
    }
    check
}

/// The printed form of a step's result (see `cas::present_all`, where the engine proved it
/// equal) against the exact result at random points, the coordinates of either sign.
fn printed_check(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    seed: u64,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    let (Some(printed), Some(exact)) = (d.printed.get(&step.name), d.named.get(&step.name)) else {
        return Ok(());
    };
    let (mut printed, mut exact) = (printed.clone(), exact.clone());
    let exact: Vec<Expr> = exact.printed_mut().into_iter().map(|e| e.clone()).collect();
    let diffs: Vec<Expr> = printed
        .printed_mut()
        .into_iter()
        .zip(&exact)
        .map(|(p, e)| Expr::minus(p.clone(), e.clone()))
        .collect();
    let agree = numerically_zero(&diffs, &exact, seed, &signed_names(scene), &|p| {
        scene.in_domain(p)
    })?;
    check.evaluations += (CONFIRMATION_POINTS * 2 * diffs.len()) as u64;
    check.method.push_str(&format!(
        "; its printed form against its exact result at {CONFIRMATION_POINTS} random points"
    ));
    match agree.iter().position(|&zero| !zero) {
        Some(k) => Err(CheckError::PrintedDiffers { number: k + 1 }),
        None => Ok(()),
    }
}

/// Step `i`'s numeric route, by its operation.
fn route(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    seed: u64,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    let result = d.named.get(&step.name).ok_or(CheckError::NotDerived)?;
    let cx = Checking {
        scene,
        d,
        step,
        result,
        seed,
    };
    rule_of(&step.op).check(cx, check)
}

/// The expression of the named step (a Lagrangian).
fn scalar_of<'a>(d: &'a Derivation, of: &str) -> Result<&'a Expr, CheckError> {
    d.named
        .get(of)
        .and_then(StepResult::scalar)
        .ok_or(CheckError::NotDerived)
}

/// The equation of motion of `q` in the named step.
fn single_equation<'a>(d: &'a Derivation, of: &str, q: &str) -> Result<&'a Expr, CheckError> {
    equations_of(d, of)?
        .iter()
        .find(|(c, _)| c == q)
        .map(|(_, e)| e)
        .ok_or(CheckError::NotDerived)
}

#[cfg(test)]
mod tests;
