//! The author's steps, checked. Each result is compared with a numeric route that does not go
//! through the engine: `be` with the unsimplified expression at random points, `differentiate`
//! with central differences, `lagrange` by integrating its equations of motion and watching the
//! energy function Σ q'·∂L/∂q' − L, itself found by differences. A step's `gives` is a claim of
//! the notes, with a verdict.

use super::budget::Deadline;
use super::integral::quadrature_check;
use super::motion::{
    Conserved, conserved_check, energy_check, linear_check, modes_agreement, modes_check,
    period_check,
};
use super::rest::{equilibria_check, stability_check};
use super::rest_states::{rest_stability_check, states_check};
use super::series::remainder_check;
use super::solve::{roots_check, system_check};
pub use super::step_check::{CheckError, StepCheck};
use super::step_check::{H, at, random_point};
use super::{
    CONFIRMATION_POINTS, DOMAIN_TRIES, NUMERICALLY_ZERO, SAMPLE_FROM, numerically_zero,
    signed_names,
};
use crate::base::rng::Rng;
use crate::cas::Expr;
use crate::derive::Derivation;
use crate::derive::steps::{
    StepResult, equation_with, equilibria_source, expand_names, expand_ranges, replacements,
    substituted_equations,
};
use crate::scene::{AuthorStep, Operation, Scene};
use std::collections::BTreeMap;

/// Central differences with Richardson extrapolation err by O(h⁴) in truncation and about
/// ε·|f|/h in rounding; with h = 1e-3 both stay far below this, relative to the derivative.
const DIFFERENCE_AGREEMENT: f64 = 1e-7;

/// The derivative at 0 of `f(x)` (None where undefined) by central differences with Richardson
/// extrapolation, and the evaluations spent. Near a singularity (acos at 1) the truncation
/// error of h = 1e-3 is large, or a step leaves the domain: h is quartered until two successive
/// estimates agree to the check's tolerance (the coarser of the two is returned: the one a
/// smooth function gets at h = 1e-3), or h reaches 1e-7, where rounding ε/h would pass it.
/// `None` when no step size gives a finite estimate.
fn richardson(f: &dyn Fn(f64) -> Option<f64>) -> Option<(f64, u64)> {
    let central = |h: f64| Some((f(h)? - f(-h)?) / (2.0 * h)).filter(|d| d.is_finite());
    let estimate = |h: f64| Some((4.0 * central(h / 2.0)? - central(h)?) / 3.0);
    // At h = 1e-3 the two central differences already agree to the tolerance for a smooth
    // function: their Richardson extrapolation is then far more accurate still.
    if let (Some(d1), Some(d2)) = (central(H), central(H / 2.0))
        && (d1 - d2).abs() <= DIFFERENCE_AGREEMENT * d1.abs().max(d2.abs()).max(1.0)
    {
        return Some(((4.0 * d2 - d1) / 3.0, 4));
    }
    let mut evaluations = 4;
    let mut h = H;
    let mut last: Option<f64> = None;
    while h >= 1e-7 {
        evaluations += 4;
        let next = estimate(h);
        match (last, next) {
            (Some(a), Some(b))
                if (a - b).abs() <= DIFFERENCE_AGREEMENT * a.abs().max(b.abs()).max(1.0) =>
            {
                return Some((a, evaluations));
            }
            (None, None) => {}
            (_, Some(b)) => last = Some(b),
            (Some(_), None) => return last.map(|a| (a, evaluations)),
        }
        h /= 4.0;
    }
    last.map(|a| (a, evaluations))
}

/// Each step's numeric check, in order; those after the deadline are not checked, and say so.
pub fn check_steps(scene: &Scene, d: &Derivation, deadline: &Deadline) -> Vec<StepCheck> {
    (0..scene.steps.len())
        .map(|i| match deadline.check() {
            Ok(()) => check_step(scene, d, i),
            Err(over) => StepCheck {
                problem: Some(CheckError::from(over).to_string()),
                ..not_yet_checked(&scene.steps[i])
            },
        })
        .collect()
}

/// The numeric check of step `i` (each step draws its random points from its own seed).
pub fn check_step(scene: &Scene, d: &Derivation, i: usize) -> StepCheck {
    let step = &scene.steps[i];
    let mut check = not_yet_checked(step);
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
    let agree = numerically_zero(&diffs, &exact, seed, &signed_names(scene))?;
    check.evaluations += (CONFIRMATION_POINTS * 2 * diffs.len()) as u64;
    check.method.push_str(&format!(
        "; its printed form against its exact result at {CONFIRMATION_POINTS} random points"
    ));
    match agree.iter().position(|&zero| !zero) {
        Some(k) => Err(CheckError::PrintedDiffers { number: k + 1 }),
        None => Ok(()),
    }
}

/// A step's check before its route has run: no method, no error, no work.
fn not_yet_checked(step: &AuthorStep) -> StepCheck {
    StepCheck {
        step: step.name.clone(),
        line: step.line,
        method: String::new(),
        error: 0.0,
        tolerance: 0.0,
        evaluations: 0,
        problem: None,
    }
}

fn route(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    seed: u64,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    let result = d.named.get(&step.name).ok_or(CheckError::NotDerived)?;
    match (&step.op, result) {
        (Operation::Be(e), StepResult::Expr(r)) => {
            let raw = expand_names(scene, d, step, e)?;
            check.method = format!(
                "the simplified form against the expression as written, at {CONFIRMATION_POINTS} \
                 random points"
            );
            check.tolerance = NUMERICALLY_ZERO;
            let mut rng = Rng::new(seed);
            let mut compared = 0;
            for _ in 0..CONFIRMATION_POINTS * DOMAIN_TRIES {
                if compared == CONFIRMATION_POINTS {
                    break;
                }
                let point = random_point(&[&raw, r], &mut rng);
                let (a, b) = (at(&raw, &point)?, at(r, &point)?);
                check.evaluations += 2;
                // Where either is undefined or infinite, nothing is compared (inf − inf is
                // NaN, which `max` would pass over): another point is drawn.
                if !a.is_finite() || !b.is_finite() {
                    continue;
                }
                compared += 1;
                check.error = check
                    .error
                    .max((a - b).abs() / a.abs().max(b.abs()).max(1.0));
            }
            if compared < CONFIRMATION_POINTS {
                return Err(CheckError::NoPointInDomain {
                    tries: CONFIRMATION_POINTS * DOMAIN_TRIES,
                });
            }
        }
        (Operation::Differentiate { of, by }, StepResult::Expr(r)) => {
            let f = expand_names(scene, d, step, of)?;
            check.method = format!(
                "central differences (h = {H}, Richardson-extrapolated) at {CONFIRMATION_POINTS} \
                 random points"
            );
            check.tolerance = DIFFERENCE_AGREEMENT;
            let mut rng = Rng::new(seed);
            let mut checked = 0;
            for _ in 0..CONFIRMATION_POINTS * DOMAIN_TRIES {
                if checked == CONFIRMATION_POINTS {
                    break;
                }
                let mut point = random_point(&[&f, r], &mut rng);
                let mut accel = BTreeMap::new();
                for q in scene.coordinates.keys() {
                    for name in [q.clone(), format!("{q}'"), format!("{q}''")] {
                        point
                            .entry(name)
                            .or_insert_with(|| SAMPLE_FROM + rng.uniform());
                    }
                    accel.insert(q.clone(), SAMPLE_FROM + rng.uniform());
                }
                point.entry("t".into()).or_insert(SAMPLE_FROM);
                // Along x = x0 + s (a partial derivative), or along the motion through the
                // point (d/dt): q + s q' + s² q''/2, q' + s q'', t + s.
                let moved = |s: f64| -> BTreeMap<String, f64> {
                    let mut p = point.clone();
                    if by == "t" {
                        for q in scene.coordinates.keys() {
                            let (v, a) = (point[&format!("{q}'")], point[&format!("{q}''")]);
                            *p.get_mut(q).expect("set above") += s * v + s * s * a / 2.0;
                            *p.get_mut(&format!("{q}'")).expect("set above") += s * a;
                        }
                        *p.get_mut("t").expect("set above") += s;
                    } else {
                        *p.entry(by.clone()).or_insert(SAMPLE_FROM) += s;
                    }
                    p
                };
                // A point outside the expression's domain (acos of more than 1) is drawn again.
                let exact = at(r, &point)?;
                if !exact.is_finite() || !at(&f, &point)?.is_finite() {
                    continue;
                }
                let value = |x: f64| at(&f, &moved(x)).ok().filter(|v| v.is_finite());
                let Some((numeric, evaluations)) = richardson(&value) else {
                    continue;
                };
                check.evaluations += evaluations + 1;
                check.error = check
                    .error
                    .max((exact - numeric).abs() / exact.abs().max(numeric.abs()).max(1.0));
                checked += 1;
            }
            if checked < CONFIRMATION_POINTS {
                return Err(CheckError::NoPointInDomain {
                    tries: CONFIRMATION_POINTS * DOMAIN_TRIES,
                });
            }
        }
        (Operation::Lagrange { of, constraints }, StepResult::Equations(eqs)) => {
            energy_check(scene, step, scalar_of(d, of)?, eqs, constraints, check)?;
        }
        (Operation::Routh { of, cyclic }, StepResult::Expr(routhian)) => {
            let lagrangian = scalar_of(d, of)?;
            super::routh::routh_check(scene, step, lagrangian, routhian, cyclic, check)?;
        }
        (
            Operation::Momentum { of, .. } | Operation::Energy { of },
            StepResult::Conserved { value, conserved },
        ) => {
            let lagrangian = scalar_of(d, of)?;
            let what = match &step.op {
                Operation::Momentum { coordinate, .. } => Conserved::Momentum(coordinate),
                _ => Conserved::Energy,
            };
            conserved_check(scene, step, lagrangian, value, *conserved, what, check)?;
        }
        (Operation::Integrate { of, over }, StepResult::Expr(exact)) => {
            let f = expand_names(scene, d, step, of)?;
            let over = expand_ranges(scene, d, step, over)?;
            quadrature_check(&scene.values, &f, &over, exact, check)?;
        }
        (
            Operation::Series {
                of,
                var,
                about,
                order,
            },
            StepResult::Expr(s),
        ) => {
            let f = expand_names(scene, d, step, of)?;
            let x0 = at(&expand_names(scene, d, step, about)?, &scene.values)?;
            remainder_check(scene, &f, s, var, x0, *order, check)?;
        }
        (
            Operation::Equilibria { of },
            StepResult::Equilibria {
                coordinate, zeros, ..
            },
        ) => {
            let r = single_equation(d, of, coordinate)?;
            equilibria_check(scene, r, coordinate, zeros, check)?;
        }
        (Operation::Stability { of }, StepResult::Stability { coordinate, cases }) => {
            let motion = equilibria_source(scene, of).ok_or(CheckError::NotDerived)?;
            let r = single_equation(d, motion, coordinate)?;
            stability_check(scene, r, coordinate, cases, check)?;
        }
        (Operation::Equilibria { of }, StepResult::RestStates { states, .. }) => {
            states_check(scene, equations_of(d, of)?, states, check)?;
        }
        (Operation::Stability { of }, StepResult::RestStability { cases, .. }) => {
            let motion = equilibria_source(scene, of).ok_or(CheckError::NotDerived)?;
            rest_stability_check(scene, equations_of(d, motion)?, cases, check)?;
        }
        (Operation::Frequency { of }, StepResult::Modes(modes)) => {
            modes_check(scene, equations_of(d, of)?, modes, check)?;
        }
        (Operation::Frequency { of }, StepResult::NumericModes { frequencies, .. }) => {
            modes_agreement(scene, equations_of(d, of)?, frequencies, check)?;
        }
        (Operation::Linearise { of, about }, StepResult::Equations(linear)) => {
            linear_check(scene, equations_of(d, of)?, linear, about, seed, check)?;
        }
        (Operation::Frequency { of }, StepResult::Expr(omega)) => {
            let source = scene.steps.iter().find(|s| &s.name == of);
            let Some(Operation::Linearise {
                of: motion_of,
                about,
            }) = source.map(|s| &s.op)
            else {
                return Err(CheckError::NotDerived);
            };
            period_check(scene, equations_of(d, motion_of)?, about, omega, check)?;
        }
        (Operation::Substitute { of, set }, result) => {
            // Each expression as written beside its result: one, or one per equation.
            let pairs: Vec<(Expr, &Expr)> = match (substituted_equations(d, of), result) {
                (Some(before), StepResult::Equations(after)) => before
                    .iter()
                    .zip(after)
                    .map(|((_, b), (_, a))| (b.clone(), a))
                    .collect(),
                (None, StepResult::Expr(r)) => vec![(expand_names(scene, d, step, of)?, r)],
                _ => return Err(CheckError::NotDerived),
            };
            let values = replacements(scene, d, step, set)?;
            check.method = format!(
                "the expression as written, each replaced name given its replacement's value, at \
                 {CONFIRMATION_POINTS} random points"
            );
            check.tolerance = NUMERICALLY_ZERO;
            let mut rng = Rng::new(seed);
            let mut valued = 0;
            for _ in 0..CONFIRMATION_POINTS {
                let exprs: Vec<&Expr> = pairs
                    .iter()
                    .flat_map(|(f, r)| [f, *r])
                    .chain(values.values())
                    .collect();
                let point = random_point(&exprs, &mut rng);
                // All at once, as the exact rule replaces: a replacement that names another
                // replaced name takes that name's value before the replacement. The result is
                // in the names as they were (after a swap, x stands where y stood).
                let mut replaced = point.clone();
                for (name, e) in &values {
                    replaced.insert(name.clone(), at(e, &point)?);
                }
                for (f, r) in &pairs {
                    let (a, b) = (at(f, &replaced)?, at(r, &point)?);
                    check.evaluations += 2;
                    // A point outside a root's domain (√ of a negative) tells nothing.
                    if a.is_finite() && b.is_finite() {
                        valued += 1;
                        check.error = check
                            .error
                            .max((a - b).abs() / a.abs().max(b.abs()).max(1.0));
                    }
                }
                check.evaluations += values.len() as u64;
            }
            if valued == 0 {
                return Err(CheckError::NoValue);
            }
        }
        (Operation::Solve { of, unknowns }, StepResult::Expr(_) | StepResult::Roots(_)) => {
            let unknown = &unknowns[0];
            let all = solvable_of(d, of)?;
            let eqs = std::slice::from_ref(equation_with(&all, unknown)?);
            let roots: Vec<&Expr> = match result {
                StepResult::Roots(roots) => roots.iter().collect(),
                _ => result.scalar().into_iter().collect(),
            };
            roots_check(scene, eqs, &roots, unknown, seed, check)?;
        }
        (Operation::Solve { of, unknowns }, StepResult::Solution(solution)) => {
            let eqs: Vec<(String, Expr)> = solvable_of(d, of)?
                .iter()
                .filter(|(_, e)| e.symbols().iter().any(|s| unknowns.contains(s)))
                .cloned()
                .collect();
            system_check(scene, &eqs, solution, seed, check)?;
        }
        _ => return Err(CheckError::NotDerived),
    }
    Ok(())
}

/// The equations of the named step.
pub(super) fn equations_of<'a>(
    d: &'a Derivation,
    of: &str,
) -> Result<&'a [(String, Expr)], CheckError> {
    d.named
        .get(of)
        .and_then(StepResult::equations)
        .ok_or(CheckError::NotDerived)
}

/// What a `solve` step took from the named step: its equations, or its expression as e = 0.
pub(super) fn solvable_of<'a>(
    d: &'a Derivation,
    of: &str,
) -> Result<std::borrow::Cow<'a, [(String, Expr)]>, CheckError> {
    d.named
        .get(of)
        .and_then(|r| r.solvable(of))
        .ok_or(CheckError::NotDerived)
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
