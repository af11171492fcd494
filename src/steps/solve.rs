//! `solve = "eom"`, `for = ["x''"]`: equations solved for one unknown (its roots, an angle inside
//! sin and cos too), or for several at once (Cramer's rule, after eliminating unknowns with a
//! numeric coefficient past four).
//!
//! - Exact rule: `derive/solve.rs`.
//! - Numeric route: each solution put back into its equations at random points and at the
//!   scene's values (`verify/solve.rs`).

use super::{Checking, Context};
use crate::cas::Expr;
use crate::derive::DeriveError;
use crate::derive::result_order::{positive_roots, stable_order};
use crate::derive::solve::{solve, solve_system};
use crate::derive::step_names::{StepResult, equation_with};
use crate::verify::solve::{roots_check, system_check};
use crate::verify::step_check::{CheckError, StepCheck, solvable_of};

pub(super) fn derive(
    cx: Context,
    of: &str,
    unknowns: &[String],
) -> Result<StepResult, DeriveError> {
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

pub(super) fn check(
    cx: Checking,
    of: &str,
    unknowns: &[String],
    check: &mut StepCheck,
) -> Result<(), CheckError> {
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
