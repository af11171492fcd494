//! The order of a step's several results (the roots of `solve`, the modes of `frequency`), and
//! so their names `x_1`, `x_2`, …: an order that does not depend on the scene's values, so
//! that changing a value never renumbers what claims and answers refer to.
//!
//! - Smallest first, where that order is the same at every one of [`ORDER_POINTS`] points of
//!   the scene's domain (its `assume`), drawn as the random-point tests draw theirs but from a
//!   seed of their own: √(g/l) before √(g/l + 2k/m) for every g, l, k, m.
//! - Else (two results cross inside the domain, or are defined at too few points) in the order
//!   of their forms as text, which no value changes.
//!
//! Of several roots of a `solve` for a symbol the scene takes positive (ω₃ = ±2√(I₁Mgl)/I₃),
//! those zero or negative for every positive value of the symbols are left out, unless that
//! leaves none.

use super::sign::{Sign, signs_over_positive};
use crate::base::rng::Rng;
use crate::cas::Expr;
use crate::scene::operations::Lagrange;
use crate::scene::{SAMPLE_FROM, Scene};
use std::collections::BTreeMap;

/// The points at which the order must hold.
pub const ORDER_POINTS: usize = 8;

/// Points drawn, at most, per point wanted: some fall outside the domain, or where a result
/// is not real.
const TRIES: usize = 20;

/// The points' own seed: not the scene's `[numeric] seed`, which the checks use.
const ORDER_SEED: u64 = 0x006f_7264_6572;

/// `exprs` in the order described above.
pub fn stable_order(exprs: &mut [Expr], scene: &Scene) {
    exprs.sort_by_cached_key(|e| e.to_text());
    if exprs.len() < 2 {
        return;
    }
    let mut names: Vec<String> = exprs
        .iter()
        .flat_map(|e| e.symbols())
        .filter(|s| s != "pi")
        .collect();
    names.sort();
    names.dedup();
    let signed = scene.signed_names();
    let mut rng = Rng::new(ORDER_SEED);
    let mut order: Option<Vec<usize>> = None;
    let mut found = 0;
    for _ in 0..ORDER_POINTS * TRIES {
        if found == ORDER_POINTS {
            break;
        }
        let point: BTreeMap<String, f64> = names
            .iter()
            .map(|n| {
                let x = SAMPLE_FROM + rng.uniform();
                let negative = signed.contains(n) && rng.uniform() < 0.5;
                (n.clone(), if negative { -x } else { x })
            })
            .collect();
        if !scene.in_domain(&point) {
            continue;
        }
        let at: Option<Vec<f64>> = exprs
            .iter()
            .map(|e| {
                e.eval(&|s| point.get(s).copied())
                    .ok()
                    .filter(|x| x.is_finite())
            })
            .collect();
        let Some(at) = at else { continue };
        let mut here: Vec<usize> = (0..exprs.len()).collect();
        here.sort_by(|&a, &b| at[a].total_cmp(&at[b]));
        found += 1;
        match &order {
            None => order = Some(here),
            // The results cross inside the domain: their order is no property of theirs.
            Some(first) if *first != here => return,
            Some(_) => {}
        }
    }
    if let (Some(order), ORDER_POINTS) = (order, found) {
        let sorted: Vec<Expr> = order.iter().map(|&k| exprs[k].clone()).collect();
        exprs.clone_from_slice(&sorted);
    }
}

/// The several roots of a `solve` for `unknown` where the scene takes `unknown` positive (a
/// symbol no value or variant makes negative, not a coordinate nor a constraint's multiplier):
/// those that are zero or negative for every positive value of the symbols left out, unless
/// every one is.
pub fn positive_roots(roots: Vec<Expr>, unknown: &str, scene: &Scene) -> Vec<Expr> {
    let multiplier = scene.steps.iter().any(|s| match &s.op {
        crate::scene::Operation::Lagrange(Lagrange { constraints, .. }) => {
            constraints.iter().any(|(m, _)| m == unknown)
        }
        _ => false,
    });
    let signed = scene.signed_names();
    if roots.len() < 2
        || multiplier
        || !scene.symbols.contains_key(unknown)
        || signed.contains(unknown)
    {
        return roots;
    }
    let kept: Vec<Expr> = roots
        .iter()
        .filter(|r| {
            // A root in a coordinate, which takes either sign, keeps its sign open; one the
            // engine cannot decide (a root with arccos in it) is kept.
            if r.symbols().iter().any(|s| signed.contains(s)) {
                return true;
            }
            let never_positive = r.is_zero()
                || matches!(
                    signs_over_positive(std::slice::from_ref(r)).as_deref(),
                    Ok([Sign::Negative])
                );
            !never_positive
        })
        .cloned()
        .collect();
    if kept.is_empty() { roots } else { kept }
}
