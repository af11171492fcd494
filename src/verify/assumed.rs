//! The engine's test under a scene's `assume`: each symbol assumed larger than an expression
//! is written as that expression plus a new positive symbol, so that the signs the domain
//! fixes are the engine's too (R > r: √((R − r)²) = R − r).

use crate::cas::{self, Expr};
use crate::derive::sign::Sign;
use crate::scene::Scene;
use std::collections::BTreeSet;

/// The gap names: `__` is never in a scene's names, so none is taken.
fn gap(k: usize) -> String {
    format!("assumed__gap{k}")
}

/// Whether each difference is zero over the scene's domain: every symbol but the `signed`
/// ones positive, and each assumption `x > e` (x a symbol of either kind that `e` does not
/// contain) put in as x = e + g, g > 0. Assumptions of another shape are the random points'
/// alone. Exponentials are then powers of positive symbols (`cas::exponentials_as_powers`),
/// and |u| and atan2(y, x) are written by their argument's sign where it is fixed.
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
    let exponential = |d: &Expr| {
        let mut found = false;
        d.walk(&mut |x| {
            found |= matches!(x, Expr::Call(f, _) if ["exp", "sinh", "cosh"].contains(&f.as_str()))
        });
        found
    };
    if diffs.iter().any(exponential) {
        diffs = cas::exponentials_as_powers(diffs)?;
    }
    let diffs = diffs.iter().map(|d| by_fixed_signs(d, signed)).collect();
    cas::is_zero_over_positive(diffs, signed.clone())
}

/// The sign of `u` when it is the same for all positive values of its symbols, none of them
/// `signed` and none inside a function (whose sign the proof does not see).
fn fixed_sign(u: &Expr, signed: &BTreeSet<String>) -> Option<Sign> {
    let mut plain = true;
    u.walk(&mut |x| plain &= !matches!(x, Expr::Call(..) | Expr::List(_) | Expr::Index(..)));
    let free = u.symbols().iter().all(|s| !signed.contains(s));
    if !(plain && free) {
        return None;
    }
    crate::derive::sign::sign_over_positive(u)
        .ok()
        .filter(|s| *s != Sign::NotFixed)
}

/// `e` with each |u| written as u or −u where u's sign is the same for all positive values of
/// its symbols: |−m x₀| = m x₀; and atan2(y, x) as atan(y/x) where x > 0.
fn by_fixed_signs(e: &Expr, signed: &BTreeSet<String>) -> Expr {
    let each = |v: &[Expr]| v.iter().map(|x| by_fixed_signs(x, signed)).collect();
    match e {
        Expr::Call(f, args) if f == "abs" && args.len() == 1 => {
            let u = by_fixed_signs(&args[0], signed);
            match fixed_sign(&u, signed) {
                Some(Sign::Positive) => u,
                Some(Sign::Negative) => Expr::negate(u),
                _ => Expr::call("abs", u),
            }
        }
        // atan2(y, x) = atan(y/x) for x > 0: atan2(D, D) = atan 1 = π/4.
        Expr::Call(f, args) if f == "atan2" && args.len() == 2 => {
            let [y, x] = [0, 1].map(|k| by_fixed_signs(&args[k], signed));
            match fixed_sign(&x, signed) {
                Some(Sign::Positive) => Expr::call("atan", Expr::over(y, x)),
                _ => Expr::Call(f.clone(), vec![y, x]),
            }
        }
        Expr::Call(f, args) => Expr::Call(f.clone(), each(args)),
        Expr::Add(v) => Expr::add(each(v)),
        Expr::Mul(v) => Expr::mul(each(v)),
        Expr::Pow(a, b) => Expr::pow(by_fixed_signs(a, signed), by_fixed_signs(b, signed)),
        _ => e.clone(),
    }
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
