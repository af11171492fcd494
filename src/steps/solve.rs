//! `solve = "eom"`, `for = ["x''"]`: equations solved for one unknown (its roots, an angle inside
//! sin and cos too), or for several at once (Cramer's rule, after eliminating unknowns with a
//! numeric coefficient past four).
//!
//! - Exact rule: `derive/solve.rs`, shared with the rest states and Routh's procedure.
//! - Numeric route: each solution put back into its equations at random points and at the
//!   scene's values (`roots_check`, `system_check`).

use super::check::{CheckError, StepCheck, at, random_point, solvable_of};
use super::{Checking, Context, Rule};
use crate::base::rng::Rng;
use crate::cas::Expr;
use crate::derive::DeriveError;
use crate::derive::result_order::{positive_roots, stable_order};
use crate::derive::solve::{solve, solve_system};
use crate::derive::step_names::{StepResult, equation_with};
use crate::notation::Formula;
use crate::numeric::random_points::{CONFIRMATION_POINTS, NUMERICALLY_ZERO};
use crate::scene::Scene;
use crate::scene::operations::Solve;
use std::collections::BTreeMap;

impl Rule for Solve {
    fn derive(&self, cx: Context, _: &mut Option<Formula>) -> Result<StepResult, DeriveError> {
        let of: &str = &self.of;
        let unknowns: &[String] = &self.unknowns;
        let earlier = cx.d.named.get(of).ok_or_else(|| {
            DeriveError::Inconsistent(format!("step `{of}` was validated as an earlier step"))
        })?;
        let eqs = &*earlier.solvable(of).ok_or_else(|| {
            DeriveError::NotDerivable(format!(
                "`{of}` gives several results: `solve` takes equations, or one expression (solved \
             for where it is zero)"
            ))
        })?;
        Ok(match unknowns {
            [unknown] => {
                let mut roots =
                    positive_roots(solve(eqs, unknown, &cx.scene.values)?, unknown, cx.scene);
                stable_order(&mut roots, cx.scene);
                match roots.len() {
                    1 => StepResult::Expr(roots.remove(0)),
                    _ => StepResult::Roots(roots),
                }
            }
            _ => StepResult::Solution(solve_system(eqs, unknowns)?),
        })
    }

    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError> {
        let of: &str = &self.of;
        let unknowns: &[String] = &self.unknowns;
        match cx.result {
            StepResult::Expr(_) | StepResult::Roots(_) => {
                let unknown = &unknowns[0];
                let all = solvable_of(cx.d, of)?;
                let eqs = std::slice::from_ref(equation_with(&all, unknown)?);
                let roots: Vec<&Expr> = match cx.result {
                    StepResult::Roots(roots) => roots.iter().collect(),
                    _ => cx.result.scalar().into_iter().collect(),
                };
                roots_check(cx.scene, eqs, &roots, unknown, cx.seed, check)
            }
            StepResult::Solution(solution) => {
                let eqs: Vec<(String, Expr)> = solvable_of(cx.d, of)?
                    .iter()
                    .filter(|(_, e)| e.symbols().iter().any(|s| unknowns.contains(s)))
                    .cloned()
                    .collect();
                system_check(cx.scene, &eqs, solution, cx.seed, check)
            }
            _ => Err(CheckError::NotDerived),
        }
    }
}

// `solve`, checked without the engine: each solution put back into its equations at random
// points and at the scene's values, where it is real.

/// The points a solution is put back at: random ones over the names of `exprs`, then the
/// scene's values.
fn points(scene: &Scene, exprs: &[&Expr], seed: u64) -> Vec<BTreeMap<String, f64>> {
    let mut rng = Rng::new(seed);
    let mut points: Vec<BTreeMap<String, f64>> = (0..CONFIRMATION_POINTS)
        .map(|_| random_point(exprs, &mut rng, scene))
        .collect();
    points.push(scene.values.clone());
    points
}

/// Each root of one unknown put back into its equation: the residual relative to the
/// equation's size with the unknown at 0.
pub(crate) fn roots_check(
    scene: &Scene,
    eqs: &[(String, Expr)],
    roots: &[&Expr],
    unknown: &str,
    seed: u64,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.method = format!(
        "each solution put back into the equation, at {CONFIRMATION_POINTS} random points \
         and the scene's values (where it is real)"
    );
    check.tolerance = NUMERICALLY_ZERO;
    let exprs: Vec<&Expr> = eqs
        .iter()
        .map(|(_, e)| e)
        .chain(roots.iter().copied())
        .collect();
    let mut real = 0;
    for mut point in points(scene, &exprs, seed) {
        for root in roots {
            let Ok(u) = at(root, &point) else { continue };
            if !u.is_finite() {
                continue;
            }
            point.insert(unknown.to_string(), 0.0);
            let scale = eqs
                .iter()
                .map(|(_, e)| at(e, &point))
                .sum::<Result<f64, _>>()?;
            point.insert(unknown.to_string(), u);
            for (_, e) in eqs {
                check.evaluations += 2;
                check.error = check.error.max(at(e, &point)?.abs() / scale.abs().max(1.0));
            }
            real += 1;
        }
    }
    if real == 0 {
        return Err(CheckError::NoRealRoot);
    }
    Ok(())
}

/// The values of several unknowns put back into every equation together: each residual
/// relative to the sum of the sizes of its terms' parts (the equation with the unknowns at 0,
/// and each unknown's term).
pub(crate) fn system_check(
    scene: &Scene,
    eqs: &[(String, Expr)],
    solution: &[(String, Expr)],
    seed: u64,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.method = format!(
        "the values of all the unknowns put back into every equation at once, at \
         {CONFIRMATION_POINTS} random points and the scene's values"
    );
    check.tolerance = NUMERICALLY_ZERO;
    let exprs: Vec<&Expr> = eqs
        .iter()
        .map(|(_, e)| e)
        .chain(solution.iter().map(|(_, v)| v))
        .collect();
    let mut put_back = 0;
    for mut point in points(scene, &exprs, seed) {
        let values: Vec<f64> = match solution.iter().map(|(_, v)| at(v, &point)).collect() {
            Ok(v) => v,
            Err(_) => continue,
        };
        if !values.iter().all(|v| v.is_finite()) {
            continue;
        }
        for (u, _) in solution {
            point.insert(u.clone(), 0.0);
        }
        let rests: Vec<f64> = eqs
            .iter()
            .map(|(_, e)| at(e, &point))
            .collect::<Result<_, _>>()?;
        for ((u, _), v) in solution.iter().zip(&values) {
            point.insert(u.clone(), *v);
        }
        for ((_, e), rest) in eqs.iter().zip(rests) {
            check.evaluations += 2;
            let scale = rest.abs().max(1.0);
            check.error = check.error.max(at(e, &point)?.abs() / scale);
        }
        put_back += 1;
    }
    if put_back == 0 {
        return Err(CheckError::NoRealRoot);
    }
    Ok(())
}
