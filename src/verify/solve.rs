//! `solve`, checked without the engine: each solution put back into its equations at random
//! points and at the scene's values, where it is real.

use super::step_check::{CheckError, StepCheck, at, random_point};
use super::{CONFIRMATION_POINTS, NUMERICALLY_ZERO};
use crate::base::rng::Rng;
use crate::cas::Expr;
use crate::scene::Scene;
use std::collections::BTreeMap;

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
