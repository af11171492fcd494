//! `solve`: the one equation of a step that contains the unknown, solved exactly: linear, or
//! every root of its polynomial factors up to degree two.

use super::DeriveError;
use crate::cas::{self, Expr};
use std::collections::BTreeMap;

/// The one equation R = 0 solved for `unknown`: −R(0)/(∂R/∂u) when it is linear, else every
/// root of the polynomial R in `unknown` (factors of degree up to two), ordered by their values
/// at `values`.
pub fn solve(
    eqs: &[(String, Expr)],
    unknown: &str,
    values: &BTreeMap<String, f64>,
) -> Result<Vec<Expr>, DeriveError> {
    let (_, r) = equation_with(eqs, unknown)?;
    let slope = r.diff(unknown)?;
    if !cas::simplify(&slope.diff(unknown)?)?.is_zero() {
        // sin θ and cos θ are parameters here: named, so the engine solves a plain polynomial.
        let (named, calls) = name_calls(&cas::simplify(r)?, unknown);
        let back = |e: &Expr| {
            e.substitute(&|s| calls.iter().find(|(n, _)| n == s).map(|(_, c)| c.clone()))
        };
        let mut roots = cas::roots(&named, unknown)?;
        for (root, _) in roots.roots.iter_mut().chain(roots.unsolved.iter_mut()) {
            *root = back(root);
        }
        if let Some((factor, _)) = roots.unsolved.first() {
            return Err(DeriveError::NotDerivable(format!(
                "the equation has the factor {} of degree {} in `{unknown}`: `solve` gives \
                 closed forms of factors up to degree two",
                factor.to_text(),
                degree(factor, unknown)?
            )));
        }
        // Every symbol of a scene is positive: √(4 a² b) = 2 a √b.
        let mut found: Vec<Expr> = Vec::new();
        for (root, _) in roots.roots {
            let root = cas::simplify(&cas::pull_squares(&root, &|_| true))?;
            if !found.contains(&root) {
                found.push(root);
            }
        }
        if found.is_empty() {
            return Err(DeriveError::NotDerivable(format!(
                "the equation has no root in `{unknown}`"
            )));
        }
        super::lagrangian::sort_by_value(&mut found, values);
        return Ok(found);
    }
    let slope = cas::simplify(&slope)?;
    if slope.is_zero() {
        return Err(DeriveError::NotDerivable(format!(
            "the equation does not contain `{unknown}`"
        )));
    }
    let rest = r.substitute(&|s| (s == unknown).then(|| Expr::int(0)));
    Ok(vec![cas::simplify(&Expr::negate(Expr::over(rest, slope)))?])
}

/// The degree of a polynomial in `x`: how many derivatives leave something.
fn degree(p: &Expr, x: &str) -> Result<usize, DeriveError> {
    let mut d = p.clone();
    for k in 0..=MAX_DEGREE_SHOWN {
        d = cas::simplify(&d.diff(x)?)?;
        if d.is_zero() {
            return Ok(k);
        }
    }
    Err(DeriveError::NotDerivable(format!(
        "`solve` of a polynomial of degree over {MAX_DEGREE_SHOWN} in `{x}`"
    )))
}

/// The highest degree a message about an unsolved factor names.
const MAX_DEGREE_SHOWN: usize = 30;

/// `e` with each function call (sin θ, cos θ) that does not hold the unknown replaced by a
/// name of its own, and the calls by name.
fn name_calls(e: &Expr, unknown: &str) -> (Expr, Vec<(String, Expr)>) {
    let walk_in = |e: &Expr, calls: &mut Vec<(String, Expr)>| walk(e, unknown, calls);
    fn walk(e: &Expr, unknown: &str, calls: &mut Vec<(String, Expr)>) -> Expr {
        match e {
            Expr::Call(..) if !e.symbols().iter().any(|s| s == unknown) => {
                if let Some((n, _)) = calls.iter().find(|(_, c)| c == e) {
                    return Expr::sym(n);
                }
                let n = format!("call__{}", calls.len());
                calls.push((n.clone(), e.clone()));
                Expr::sym(&n)
            }
            Expr::Add(v) => Expr::add(v.iter().map(|x| walk(x, unknown, calls)).collect()),
            Expr::Mul(v) => Expr::mul(v.iter().map(|x| walk(x, unknown, calls)).collect()),
            Expr::Pow(b, k) => Expr::pow(walk(b, unknown, calls), walk(k, unknown, calls)),
            other => other.clone(),
        }
    }
    let mut calls = Vec::new();
    let named = walk_in(e, &mut calls);
    (named, calls)
}

/// The one equation of several that contains the unknown a `solve` step solves for.
pub fn equation_with<'a>(
    eqs: &'a [(String, Expr)],
    unknown: &str,
) -> Result<&'a (String, Expr), DeriveError> {
    let with: Vec<&(String, Expr)> = eqs
        .iter()
        .filter(|(_, e)| e.symbols().iter().any(|s| s == unknown))
        .collect();
    match with[..] {
        [one] => Ok(one),
        [] => Err(DeriveError::NotDerivable(format!(
            "no equation of the step contains `{unknown}`"
        ))),
        _ => Err(DeriveError::NotDerivable(format!(
            "`solve` takes one equation, and {} of these contain `{unknown}` (those of {})",
            with.len(),
            with.iter()
                .map(|(q, _)| q.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ))),
    }
}
