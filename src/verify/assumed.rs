//! The engine's test under a scene's `assume`: each symbol assumed larger than an expression
//! is written as that expression plus a new positive symbol, so that the signs the domain
//! fixes are the engine's too (R > r: √((R − r)²) = R − r).

use crate::cas::{self, Expr};
use crate::scene::Scene;
use std::collections::BTreeSet;

/// The gap names: `__` is never in a scene's names, so none is taken.
fn gap(k: usize) -> String {
    format!("assumed__gap{k}")
}

/// Whether each difference is zero over the scene's domain: every symbol but the `signed`
/// ones positive, and each assumption `x > e` (x a symbol of either kind that `e` does not
/// contain) put in as x = e + g, g > 0. Assumptions of another shape are the random points'
/// alone.
pub(crate) fn is_zero_in_domain(
    scene: &Scene,
    diffs: Vec<Expr>,
    signed: &BTreeSet<String>,
) -> Result<Vec<bool>, cas::CasError> {
    let mut diffs = diffs;
    let mut substituted = false;
    for (k, a) in scene.assumptions.iter().enumerate() {
        let Expr::Sym(x) = &a.larger else {
            continue;
        };
        if a.smaller.symbols().contains(x) {
            continue;
        }
        let value = Expr::add(vec![a.smaller.clone(), Expr::sym(&gap(k))]);
        substituted = true;
        diffs = diffs
            .iter()
            .map(|d| d.substitute(&|s| (s == x).then(|| value.clone())))
            .collect();
    }
    // (r + g) − r is g before the roots are taken apart; with nothing put in, the form is
    // kept (the simplifier would expand sin⁴θ).
    if substituted {
        diffs = cas::simplify_all(diffs)?;
    }
    cas::is_zero_over_positive(diffs, signed.clone())
}

/// Each difference still not zero but zero at every random point, tried once more over the
/// domain: as simplified, and as written (the simplifier expands sin⁴θ under √(sin⁴θ X),
/// whose square factor sin²θ then no longer leaves the root).
pub(crate) fn second_chance(
    scene: &Scene,
    [simplified, written]: [&[Expr]; 2],
    numeric: &[bool],
    symbolic: &mut [bool],
    signed: &BTreeSet<String>,
) -> Result<(), cas::CasError> {
    let still: Vec<usize> = (0..symbolic.len())
        .filter(|&k| !symbolic[k] && numeric[k])
        .collect();
    if still.is_empty() {
        return Ok(());
    }
    let tried: Vec<Expr> = still
        .iter()
        .flat_map(|&k| [simplified[k].clone(), written[k].clone()])
        .collect();
    let again = is_zero_in_domain(scene, tried, signed)?;
    for (i, k) in still.into_iter().enumerate() {
        symbolic[k] |= again[2 * i] || again[2 * i + 1];
    }
    Ok(())
}
