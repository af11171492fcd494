//! The author's own derivation: each `[[step]]` names the exact result of one operation
//! (`be`, `differentiate`, `lagrange`, ...) on the scene's names and the steps before it. The
//! mechanics is in `lagrangian.rs`; the numeric check of each step in `verify/steps.rs`.

use super::algebra::{Env, Value, evaluate};
use super::constraints::with_multipliers;
use super::lagrangian::{
    energy, equilibria, euler_lagrange, frequency, linearise, momentum, simplify_two, stability,
    time_derivative,
};
use super::modes::normal_modes;
use super::sign::{Sign, signs_over_positive};
pub use super::solve::equation_with;
use super::solve::{solve, solve_system};
use super::step_page::page_steps;
pub use super::step_result::{Stability, Stable, StateStability, StepResult};
use super::{Derivation, DeriveError};
use crate::cas::{self, Expr};
use crate::notation::Formula;
use crate::scene::{AuthorStep, Operation, Scene};
use std::collections::BTreeMap;

/// Why a step could not be derived, at its line.
#[derive(Debug, thiserror::Error)]
pub enum StepError {
    #[error("step `{step}`: its result is {kind}; a step's result is a scalar")]
    NotScalar {
        step: String,
        line: usize,
        kind: &'static str,
    },
    #[error("step `{step}`: {message}")]
    Operation {
        step: String,
        line: usize,
        message: String,
    },
}

impl StepError {
    /// The line of the step at fault.
    pub fn line(&self) -> usize {
        match self {
            StepError::NotScalar { line, .. } | StepError::Operation { line, .. } => *line,
        }
    }
}

/// The names a step's expressions may use: the scene's definitions and vectors, the derived
/// quantities, and the results of the steps before it.
fn env(scene: &Scene, d: &Derivation) -> Env {
    let mut env = Env::new();
    for (name, e) in &scene.definitions {
        env.insert(name.clone(), Value::Scalar(e.clone()));
    }
    for (name, v) in &scene.vectors {
        env.insert(name.clone(), Value::Vector(v.clone()));
    }
    for (name, v) in &d.quantities {
        env.insert(name.clone(), v.clone());
    }
    for (name, r) in &d.named {
        for (name, e) in r.values(name) {
            env.insert(name, Value::Scalar(e));
        }
    }
    env
}

/// An expression with every name bound in the environment replaced by its value, unsimplified:
/// the form the numeric checks evaluate, independent of the engine.
pub fn expand_names(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    e: &Expr,
) -> Result<Expr, StepError> {
    if let Some((name, of)) = d.numeric_name_in(e) {
        return Err(StepError::Operation {
            step: step.name.clone(),
            line: step.line,
            message: numeric_only(&name, &of),
        });
    }
    match evaluate(e, &env(scene, d)) {
        Ok(Value::Scalar(x)) => Ok(x),
        Ok(other) => Err(StepError::NotScalar {
            step: step.name.clone(),
            line: step.line,
            kind: other.kind(),
        }),
        Err(e) => Err(StepError::Operation {
            step: step.name.clone(),
            line: step.line,
            message: e.to_string(),
        }),
    }
}

/// Why a name whose result is a number only cannot be used as an expression.
pub fn numeric_only(name: &str, step: &str) -> String {
    format!(
        "`{name}` has no exact form: step `{step}` found its modes as numbers at the scene's \
         values (the page says why), and a later step, a claim or a graded answer needs an exact \
         form"
    )
}

/// `of` with each name of `set` replaced by its expression (names of earlier steps put in
/// first), unsimplified.
pub fn substituted(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    of: &Expr,
    set: &BTreeMap<String, Expr>,
) -> Result<Expr, StepError> {
    let f = expand_names(scene, d, step, of)?;
    let values = replacements(scene, d, step, set)?;
    Ok(f.substitute(&|s| values.get(s).cloned()))
}

/// Each name of a `substitute` step's `set` and its replacement, earlier steps put in.
pub fn replacements(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    set: &BTreeMap<String, Expr>,
) -> Result<BTreeMap<String, Expr>, StepError> {
    set.iter()
        .map(|(name, e)| Ok((name.clone(), expand_names(scene, d, step, e)?)))
        .collect()
}

/// The equations a `substitute` step works on, when it names an earlier step of equations.
pub fn substituted_equations<'a>(d: &'a Derivation, of: &Expr) -> Option<&'a [(String, Expr)]> {
    match of {
        Expr::Sym(name) => match d.named.get(name) {
            Some(StepResult::Equations(eqs)) => Some(eqs),
            _ => None,
        },
        _ => None,
    }
}

/// A momentum or energy, conserved when the force on it (∂L/∂q, or ∂L/∂t) is identically 0.
fn conserved(value: Expr, force: Expr) -> Result<StepResult, DeriveError> {
    let (value, force) = simplify_two(value, force)?;
    Ok(StepResult::Conserved {
        value,
        conserved: force.is_zero(),
    })
}

/// The expression a validated earlier step holds.
fn scalar<'a>(d: &'a Derivation, of: &str) -> Result<&'a Expr, DeriveError> {
    d.named.get(of).and_then(StepResult::scalar).ok_or_else(|| {
        DeriveError::Inconsistent(format!(
            "step `{of}` was validated as an earlier scalar step"
        ))
    })
}

/// A Lagrangian built (through `be`, `differentiate` and `substitute` steps) from a
/// substitution of a velocity constraint that does not integrate gives equations that are not
/// the motion's (SymPy's rolling-disc example by Lagrange's method is one such): refused, with
/// the constraint's right place, on the `lagrange` step.
fn refuse_substituted_rolling(scene: &Scene, d: &Derivation, of: &str) -> Result<(), DeriveError> {
    let mut pending = vec![of.to_string()];
    let mut seen = std::collections::BTreeSet::new();
    while let Some(name) = pending.pop() {
        if !seen.insert(name.clone()) {
            continue;
        }
        let Some(step) = scene.steps.iter().find(|s| s.name == name) else {
            continue;
        };
        let used = match &step.op {
            Operation::Be(e) | Operation::Differentiate { of: e, .. } => e,
            Operation::Substitute { of: e, set } => {
                for (rate, value) in replacements(scene, d, step, set)? {
                    if super::constraints::does_not_integrate(&rate, &value, &scene.coordinates)? {
                        return Err(DeriveError::NotDerivable(format!(
                            "its Lagrangian comes from step `{}` (line {}), which puts in {rate} = {}, \
                             a velocity constraint that does not integrate to a relation among the \
                             coordinates: Lagrange's equations of the substituted L are not the \
                             motion's. Take L before the substitution and write the constraint on \
                             this step, `constraints = {{ lam = \"{rate} - ({})\" }}`, with `lam` \
                             a symbol declared in [symbols] (docs/scenes.md, `lagrange` with \
                             constraints)",
                            step.name,
                            step.line,
                            value.to_text(),
                            value.to_text()
                        )));
                    }
                }
                e
            }
            _ => continue,
        };
        pending.extend(used.symbols());
    }
    Ok(())
}

/// Equations with each residual simplified (in one call to the engine), their names kept.
fn simplified(eqs: Vec<(String, Expr)>) -> Result<StepResult, DeriveError> {
    let (names, exprs): (Vec<String>, Vec<Expr>) = eqs.into_iter().unzip();
    let exprs = cas::simplify_all(exprs)?;
    Ok(StepResult::Equations(
        names.into_iter().zip(exprs).collect(),
    ))
}

/// An `integrate` step's ranges with earlier steps put into their limits.
pub fn expand_ranges(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    over: &[(String, Expr, Expr)],
) -> Result<Vec<(String, Expr, Expr)>, StepError> {
    over.iter()
        .map(|(v, lo, hi)| {
            Ok((
                v.clone(),
                expand_names(scene, d, step, lo)?,
                expand_names(scene, d, step, hi)?,
            ))
        })
        .collect()
}

/// The equations of motion whose states of rest the `equilibria` step `of` found.
pub fn equilibria_source<'a>(scene: &'a Scene, of: &str) -> Option<&'a str> {
    scene.steps.iter().find_map(|s| match &s.op {
        Operation::Equilibria { of: m } if s.name == of => Some(m.as_str()),
        _ => None,
    })
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
        let printed = printed_form(scene, &result).map_err(|e| locate(step, e))?;
        let mut steps = page_steps(step, printed.as_ref().unwrap_or(&result));
        if printed.is_some() {
            for (shown, exact) in steps.iter_mut().zip(page_steps(step, &result)) {
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

/// The result in the forms a textbook prints (`cas::present_all`), where any differs from the
/// exact result; the step's check compares the two at random points.
fn printed_form(scene: &Scene, result: &StepResult) -> Result<Option<StepResult>, DeriveError> {
    let mut printed = result.clone();
    let exact: Vec<Expr> = printed
        .printed_mut()
        .into_iter()
        .map(|e| e.clone())
        .collect();
    let forms = cas::present_all(exact.clone(), scene.signed_names())?;
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

/// One step's result, derived by the engine (its errors located by the caller).
fn derive_step(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    shown: &mut Option<Formula>,
) -> Result<StepResult, DeriveError> {
    Ok(match &step.op {
        Operation::Be(e) => {
            let x = expand_names(scene, d, step, e).map_err(DeriveError::Step)?;
            super::undefined::refuse_no_value(&x, e, &BTreeMap::new(), &BTreeMap::new())?;
            StepResult::Expr(cas::simplify(&x)?)
        }
        Operation::Differentiate { of, by } => {
            let f = expand_names(scene, d, step, of).map_err(DeriveError::Step)?;
            let derivative = |f: &Expr| -> Result<Expr, DeriveError> {
                Ok(if by == "t" {
                    time_derivative(f, &scene.coordinates)?
                } else {
                    f.diff(by)?
                })
            };
            match cas::simplify(&derivative(&f)?) {
                Ok(r) => StepResult::Expr(r),
                // A rational function's expanded denominator, squared by the quotient rule,
                // is past the budget (an effective potential's second derivative): the
                // quotient rule over the factored denominator, which grows by its factors only.
                Err(cas::CasError {
                    reason: cas::CasFailure::Engine(cas::EngineError::OverBudget { .. }),
                }) => StepResult::Expr(super::quotient_rule::derivative_of_quotient(
                    &f,
                    &derivative,
                )?),
                Err(e) => return Err(e.into()),
            }
        }
        Operation::Lagrange { of, constraints } => {
            refuse_substituted_rolling(scene, d, of)?;
            let eqs = euler_lagrange(scalar(d, of)?, &scene.coordinates)?;
            simplified(with_multipliers(eqs, constraints, &scene.coordinates)?)?
        }
        Operation::Linearise { of, about } => {
            let eqs = free_equations(scene, d, of, "linearise")?;
            let (rest, linear) = linearise(eqs, about, &scene.coordinates)?;
            // A state of rest leaves nothing over: else it is not an equilibrium.
            let left = cas::simplify_all(rest)?;
            if let Some((k, r)) = left.iter().enumerate().find(|(_, r)| !r.is_zero()) {
                return Err(DeriveError::NotDerivable(format!(
                    "the state given by `about` is not at rest: the equation of `{}` leaves \
                     {} there, not 0; give an equilibrium",
                    eqs[k].0,
                    r.to_text()
                )));
            }
            simplified(linear)?
        }
        Operation::Frequency { of } => match equations(d, of)? {
            eqs @ [_] => StepResult::Expr(frequency(eqs)?),
            eqs => normal_modes(eqs, &scene.values)?,
        },
        Operation::Integrate { of, over } => {
            let f = expand_names(scene, d, step, of)?;
            let over = expand_ranges(scene, d, step, over)?;
            let (value, domain) = super::integral::integral(&f, &over)?;
            *shown = Some(super::inertia::integral_formula(
                Formula::Expr(Expr::sym(&step.name)),
                &f,
                &domain,
                &value,
            ));
            StepResult::Expr(value)
        }
        Operation::Series {
            of,
            var,
            about,
            order,
        } => {
            let f = expand_names(scene, d, step, of).map_err(DeriveError::Step)?;
            let x0 = expand_names(scene, d, step, about).map_err(DeriveError::Step)?;
            StepResult::Expr(super::series::series(&f, var, &x0, *order)?)
        }
        Operation::Equilibria { of } => {
            let eqs = free_equations(scene, d, of, "equilibria")?;
            if eqs.len() > 1 {
                let found = super::rest_states::rest_states(eqs)?;
                return Ok(StepResult::RestStates {
                    coordinates: found.coordinates,
                    states: found.states,
                    excluded: found.excluded,
                });
            }
            let found = equilibria(eqs, &scene.values)?;
            StepResult::Equilibria {
                coordinate: found.coordinate,
                zeros: found.zeros,
                excluded: found.excluded,
            }
        }
        Operation::Stability { of } => {
            if let Some(StepResult::RestStates {
                coordinates,
                states,
                ..
            }) = d.named.get(of)
            {
                let eqs = equations(d, equilibria_source(scene, of).unwrap_or(""))?;
                return Ok(StepResult::RestStability {
                    coordinates: coordinates.clone(),
                    cases: super::rest_states::rest_stability(eqs, coordinates, states)?,
                });
            }
            let Some(StepResult::Equilibria {
                coordinate, zeros, ..
            }) = d.named.get(of)
            else {
                return Err(DeriveError::Inconsistent(format!(
                    "step `{of}` was validated as earlier equilibria"
                )));
            };
            let eqs = equations(d, equilibria_source(scene, of).unwrap_or(""))?;
            let cases = zeros
                .iter()
                .zip(stability(eqs, zeros)?)
                .map(|(z, w2)| Stability {
                    at: z.clone(),
                    // A sign the rational test cannot decide (a root in Ω²) leaves the
                    // condition.
                    verdict: match &w2 {
                        None => Stable::Unknown,
                        Some(w2) => match signs_over_positive(std::slice::from_ref(w2)) {
                            Ok(s) if s[0] == Sign::Positive => Stable::Always,
                            Ok(s) if s[0] == Sign::Negative => Stable::Never,
                            _ => Stable::Where,
                        },
                    },
                    omega_squared: w2,
                })
                .collect();
            StepResult::Stability {
                coordinate: coordinate.clone(),
                cases,
            }
        }
        Operation::Routh { of, cyclic } => {
            StepResult::Expr(super::routh::routhian(scalar(d, of)?, cyclic)?)
        }
        Operation::Momentum { of, coordinate } => {
            let (p, force) = momentum(scalar(d, of)?, coordinate)?;
            conserved(p, force)?
        }
        Operation::Energy { of } => {
            let (e, rate) = energy(scalar(d, of)?, &scene.coordinates)?;
            conserved(e, rate)?
        }
        Operation::Substitute { of, set } => match substituted_equations(d, of) {
            // Equations of motion with names replaced: a steady state (θ'' = θ' = 0), a
            // conserved rate put in.
            Some(eqs) => {
                let values = replacements(scene, d, step, set)?;
                for (_, e) in eqs {
                    super::undefined::refuse_no_value(e, of, set, &values)?;
                }
                simplified(
                    eqs.iter()
                        .map(|(q, e)| (q.clone(), e.substitute(&|s| values.get(s).cloned())))
                        .collect(),
                )?
            }
            None => {
                // The names expanded and the replacements found once, for the refusal and
                // the result (what `substituted` does).
                let f = expand_names(scene, d, step, of).map_err(DeriveError::Step)?;
                let values = replacements(scene, d, step, set)?;
                super::undefined::refuse_no_value(&f, of, set, &values)?;
                StepResult::Expr(cas::simplify(&f.substitute(&|s| values.get(s).cloned()))?)
            }
        },
        Operation::Solve { of, unknowns } => {
            let earlier = d.named.get(of).ok_or_else(|| {
                DeriveError::Inconsistent(format!("step `{of}` was validated as an earlier step"))
            })?;
            let eqs = &*earlier.solvable(of).ok_or_else(|| {
                DeriveError::NotDerivable(format!(
                    "`{of}` gives several results: `solve` takes equations, or one expression \
                     (solved for where it is zero)"
                ))
            })?;
            match &unknowns[..] {
                [unknown] => {
                    let mut roots = solve(eqs, unknown, &scene.values)?;
                    match roots.len() {
                        1 => StepResult::Expr(roots.remove(0)),
                        _ => StepResult::Roots(roots),
                    }
                }
                _ => StepResult::Solution(solve_system(eqs, unknowns)?),
            }
        }
    })
}

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
