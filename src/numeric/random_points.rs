//! The random-point test: whether a difference of two expressions vanishes at a few random
//! values of its symbols, the second route beside the engine's for every claim and `gives`.

use crate::base::rng::Rng;
use crate::cas::{EvalError, Expr, Rational};
use crate::scene::Scene;
use std::collections::{BTreeMap, BTreeSet};

pub(crate) use crate::scene::SAMPLE_FROM;

/// Random points at which each symbolic verdict is confirmed.
pub(crate) const CONFIRMATION_POINTS: usize = 3;

/// A difference below this, relative to its scale (at least 1), counts as zero at a random
/// point. The expressions are sums of at most the engine's 20,000 terms of size about 1 there,
/// so rounding leaves at most about 20,000 · 2.2e-16 ≈ 4.4e-12; a nonzero difference of
/// rationals and roots of small numbers is far above 1e-9 at a random point. The margin of
/// 200 covers cancellation among the terms.
pub(crate) const NUMERICALLY_ZERO: f64 = 1e-9;

/// Random points drawn per point tested, at most, to find points where an expression is
/// defined.
pub(crate) const DOMAIN_TRIES: usize = 20;

/// Calls `compare` at fresh random points until it has compared [`CONFIRMATION_POINTS`] of them
/// (it says `false` for a point outside the expressions' domain, which tells nothing), drawing
/// at most [`DOMAIN_TRIES`] times that many: how many it compared.
pub(crate) fn compare_in_domain<E>(
    mut compare: impl FnMut() -> Result<bool, E>,
) -> Result<usize, E> {
    let mut compared = 0;
    for _ in 0..CONFIRMATION_POINTS * DOMAIN_TRIES {
        if compared == CONFIRMATION_POINTS {
            break;
        }
        if compare()? {
            compared += 1;
        }
    }
    Ok(compared)
}

/// Whether a point lies in the domain the random points keep to: a scene's `assume`
/// (`Scene::in_domain`), or everywhere.
pub(crate) type Domain<'a> = dyn Fn(&BTreeMap<String, f64>) -> bool + 'a;

/// The names that take either sign (see [`Scene::signed_names`]).
pub(crate) fn signed_names(scene: &Scene) -> BTreeSet<String> {
    scene.signed_names()
}

/// The exact value of `e` at `point` (each f64 taken as the fraction it is), when `e` is built
/// from numbers and the point's names with `+`, `*` and integer powers; `None` otherwise (π,
/// a root, a function) or at a pole. It settles what double precision cannot: a difference of
/// two forms of a high power, whose terms cancel to far below their size.
pub(crate) fn rational_at(e: &Expr, point: &BTreeMap<String, f64>) -> Option<Rational> {
    e.eval_rational(&|name| {
        point
            .get(name)
            .filter(|_| name != "pi")
            .and_then(|x| Rational::from_f64(*x))
    })
}

/// Whether each difference vanishes at [`CONFIRMATION_POINTS`] random points (see
/// [`largest_differences`]).
pub(crate) fn numerically_zero(
    diffs: &[Expr],
    scale: &[Expr],
    seed: u64,
    signed: &BTreeSet<String>,
    domain: &Domain<'_>,
) -> Result<Vec<bool>, EvalError> {
    Ok(largest_differences(diffs, scale, seed, signed, domain)?
        .into_iter()
        .map(|d| d <= NUMERICALLY_ZERO)
        .collect())
}

/// Each difference's largest size, relative to its scale (at least 1), at [`CONFIRMATION_POINTS`]
/// random points: zero within [`NUMERICALLY_ZERO`]. The `signed`
/// names are drawn with either sign (the first point positive, the second negative, the rest
/// at random), so that |p| is not taken for p.
pub(crate) fn largest_differences(
    diffs: &[Expr],
    scale: &[Expr],
    seed: u64,
    signed: &BTreeSet<String>,
    domain: &Domain<'_>,
) -> Result<Vec<f64>, EvalError> {
    let mut rng = Rng::new(seed);
    let mut largest = vec![0.0f64; diffs.len()];
    let mut names: Vec<String> = diffs
        .iter()
        .chain(scale)
        .flat_map(|e| e.symbols())
        .collect();
    names.sort();
    names.dedup();
    // A point where an entry is undefined (the square root of a negative number at random
    // values) says nothing of it: more points are drawn, until each entry has been tested at
    // CONFIRMATION_POINTS points or DOMAIN_TRIES times that many were drawn. An entry defined
    // nowhere keeps 0: the symbolic test decides it, or conflicts with it.
    let mut tested = vec![0usize; diffs.len()];
    for k in 0..CONFIRMATION_POINTS * DOMAIN_TRIES {
        if tested.iter().all(|&n| n >= CONFIRMATION_POINTS) {
            break;
        }
        let point: BTreeMap<String, f64> = names
            .iter()
            .map(|n| {
                let x = SAMPLE_FROM + rng.uniform();
                let negative = signed.contains(n)
                    && match k {
                        0 => false,
                        1 => true,
                        _ => rng.uniform() < 0.5,
                    };
                (n.clone(), if negative { -x } else { x })
            })
            .collect();
        // Outside the physics' domain (`assume`) a point says nothing: another is drawn.
        if !domain(&point) {
            continue;
        }
        let env = |s: &str| point.get(s).copied().filter(|_| s != "pi");
        for (j, d) in diffs.iter().enumerate() {
            if tested[j] >= CONFIRMATION_POINTS {
                continue;
            }
            let mut v = d.eval(&env)?;
            let s = scale[j].eval(&env)?.abs().max(1.0);
            if !v.is_finite() || !s.is_finite() {
                continue;
            }
            // Not zero in double precision: exactly, where the difference is a rational function
            // of the point (an expanded (x − a)^30 loses its digits to cancellation).
            if v.abs() / s > NUMERICALLY_ZERO
                && let Some(exact) = rational_at(d, &point)
            {
                v = exact.to_f64();
            }
            tested[j] += 1;
            largest[j] = largest[j].max(v.abs() / s);
        }
    }
    Ok(largest)
}
