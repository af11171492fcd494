//! `solve`: the one equation of a step that contains the unknown, solved exactly: linear, or
//! every root of its polynomial factors up to degree two and of quartics in u², and the real
//! roots of cubic and quartic factors in closed form; several unknowns, the linear system of the
//! equations that contain them (unknowns with numeric coefficients eliminated past four, then
//! Cramer's rule).

use super::DeriveError;
use crate::cas::{self, Expr};
use std::collections::BTreeMap;

/// The one equation R = 0 solved for `unknown`: −R(0)/(∂R/∂u) when it is linear, else every
/// root of the polynomial R in `unknown` (factors of degree up to two, quartics in its square;
/// of a cubic or quartic factor, the roots real at `values`), ordered by their values there.
pub fn solve(
    eqs: &[(String, Expr)],
    unknown: &str,
    values: &BTreeMap<String, f64>,
) -> Result<Vec<Expr>, DeriveError> {
    let (_, r) = equation_with(eqs, unknown)?;
    // An angle inside sin and cos (a ladder's force, zero where 3 cos θ = 2 cos θ₀): the zeros
    // of each factor in sin θ alone or cos θ alone, as `equilibria` finds them.
    if super::lagrangian::has_call_of(r, unknown) {
        return trigonometric(r, unknown, values);
    }
    let slope = r.diff(unknown)?;
    if !cas::simplify(&slope.diff(unknown)?)?.is_zero() {
        // sin θ and cos θ are parameters here: named, so the engine solves a plain polynomial.
        let (named, calls) = name_calls(&cas::simplify(r)?, unknown);
        let back = |e: &Expr| {
            e.substitute(&|s| calls.iter().find(|(n, _)| n == s).map(|(_, c)| c.clone()))
        };
        let mut roots = cas::roots(&named, unknown)?;
        for (root, _) in roots.roots.iter_mut() {
            *root = back(root);
        }
        // Cubics and quartics: the closed form that is real at the scene's values.
        let mut closed = Vec::new();
        for (factor, _) in &roots.unsolved {
            let factor = back(factor);
            match cas::closed_form_roots(&factor, unknown, values)? {
                Ok(found) => closed.extend(found),
                Err(why) => return Err(no_closed_form(&factor, unknown, values, why)?),
            }
        }
        // Every symbol of a scene is positive: √(4 a² b) = 2 a √b.
        let mut found: Vec<Expr> = Vec::new();
        for (root, _) in roots.roots {
            let root = cas::simplify(&cas::pull_squares(&root, &|_| true))?;
            if !found.contains(&root) {
                found.push(root);
            }
        }
        found.extend(closed);
        if found.is_empty() {
            return Err(DeriveError::NotDerivable(format!(
                "the equation has no real root in `{unknown}` at the scene's values"
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

/// The zeros in `unknown` of R, an expression in sin and cos of it: each factor's in closed
/// form (q = 0 and π, ±acos c, asin s and π − asin s), ordered by their values at `values`.
fn trigonometric(
    r: &Expr,
    unknown: &str,
    values: &BTreeMap<String, f64>,
) -> Result<Vec<Expr>, DeriveError> {
    let found = cas::zeros(&cas::simplify(r)?, unknown)?;
    if let Some(f) = found.unsolved.first() {
        return Err(DeriveError::NotDerivable(format!(
            "the equation has the factor {} = 0, whose solutions in `{unknown}` have no closed \
             form here (a polynomial of degree at most 2 in sin({unknown}) or cos({unknown}))",
            f.to_text()
        )));
    }
    let mut roots: Vec<Expr> = Vec::new();
    for z in found.zeros {
        let root = cas::simplify(&cas::pull_squares(&z.value, &|_| true))?;
        if !roots.contains(&root) {
            roots.push(root);
        }
    }
    if roots.is_empty() {
        return Err(DeriveError::NotDerivable(format!(
            "the equation has no solution in `{unknown}`"
        )));
    }
    super::lagrangian::sort_by_value(&mut roots, values);
    Ok(roots)
}

/// Why a factor has no closed form here, with its roots at the scene's values when it has them.
fn no_closed_form(
    factor: &Expr,
    unknown: &str,
    values: &BTreeMap<String, f64>,
    why: cas::NoClosedForm,
) -> Result<DeriveError, DeriveError> {
    let terms = cas::coefficients(factor, unknown)?;
    let numeric = super::lagrangian::numeric_roots(&terms, values)
        .map(|r| format!("; at the scene's values its roots are {r}"))
        .unwrap_or_default();
    Ok(DeriveError::NotDerivable(match why {
        cas::NoClosedForm::Degree(degree) => format!(
            "the equation has the factor {} of degree {degree} in `{unknown}`: `solve` gives \
             closed forms up to degree four{numeric}",
            factor.to_text()
        ),
        cas::NoClosedForm::NoValue(part) => format!(
            "the equation has the factor {} in `{unknown}`, whose closed form depends on the \
             sign of {}, and that has no value at the scene's values: give each of its names a \
             value in [numeric]",
            factor.to_text(),
            part.to_text()
        ),
    }))
}

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

/// The linear system of the equations that contain the unknowns, one equation an unknown,
/// solved by Cramer's rule: each unknown's value, in the order of `unknowns`.
pub fn solve_system(
    eqs: &[(String, Expr)],
    unknowns: &[String],
) -> Result<Vec<(String, Expr)>, DeriveError> {
    let with: Vec<&(String, Expr)> = eqs
        .iter()
        .filter(|(_, e)| e.symbols().iter().any(|s| unknowns.contains(s)))
        .collect();
    if with.len() != unknowns.len() {
        return Err(DeriveError::NotDerivable(format!(
            "`solve` of {} unknowns takes as many equations that contain them, and {} do{}",
            unknowns.len(),
            with.len(),
            if with.is_empty() {
                String::new()
            } else {
                format!(
                    " (those of {})",
                    with.iter()
                        .map(|(q, _)| q.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            }
        )));
    }
    let rows: Vec<Expr> = with.iter().map(|(_, r)| r.clone()).collect();
    if let Some(k) = nonlinear_row(&rows, unknowns)? {
        let (q, _) = with[k];
        return Err(DeriveError::NotDerivable(format!(
            "the equation of {q} is not linear in {}: `solve` of several unknowns takes a \
             linear system; solve for one unknown at a time instead",
            unknowns.join(", ")
        )));
    }
    // Past four unknowns Cramer's rule grows as n!: first take out each unknown that some
    // equation holds with a numeric coefficient (a rolling constraint's x'', a multiplier's
    // ±1), then solve what is left by Cramer's rule and substitute back.
    let (rows, rest, eliminated) = eliminate_numeric_pivots(rows, unknowns.to_vec())?;
    let mut known: BTreeMap<String, Expr> =
        rest.iter().cloned().zip(cramer(&rows, &rest)?).collect();
    for (u, e) in eliminated.into_iter().rev() {
        let value = cas::simplify(&e.substitute(&|s| known.get(s).cloned()))?;
        known.insert(u, value);
    }
    Ok(unknowns
        .iter()
        .map(|u| (u.clone(), known[u].clone()))
        .collect())
}

/// The first row that is not linear in the unknowns (a slope that holds one).
fn nonlinear_row(rows: &[Expr], unknowns: &[String]) -> Result<Option<usize>, DeriveError> {
    let n = unknowns.len();
    let mut curvatures = Vec::new();
    for r in rows {
        for u in unknowns {
            let a = r.diff(u)?;
            for v in unknowns {
                curvatures.push(a.diff(v)?);
            }
        }
    }
    let curvatures = cas::simplify_all(curvatures)?;
    Ok(curvatures
        .iter()
        .position(|c| !c.is_zero())
        .map(|k| k / (n * n)))
}

/// While more than four unknowns remain, solve the first equation that holds an unknown with a
/// numeric coefficient for it and substitute it into the others: the equations left, their
/// unknowns, and each eliminated unknown's value in terms of those after it.
#[allow(clippy::type_complexity)]
fn eliminate_numeric_pivots(
    mut rows: Vec<Expr>,
    mut unknowns: Vec<String>,
) -> Result<(Vec<Expr>, Vec<String>, Vec<(String, Expr)>), DeriveError> {
    let mut eliminated = Vec::new();
    while unknowns.len() > 4 {
        let mut pivot = None;
        'search: for (i, r) in rows.iter().enumerate() {
            for (j, u) in unknowns.iter().enumerate() {
                let slope = cas::simplify(&r.diff(u)?)?;
                if matches!(slope, Expr::Num(_)) && !slope.is_zero() {
                    pivot = Some((i, j, slope));
                    break 'search;
                }
            }
        }
        let Some((i, j, slope)) = pivot else {
            break;
        };
        let row = rows.remove(i);
        let u = unknowns.remove(j);
        // R = c u + rest, so u = u − R/c.
        let value = cas::simplify(&Expr::minus(Expr::sym(&u), Expr::over(row, slope)))?;
        rows = cas::simplify_all(
            rows.iter()
                .map(|r| r.substitute(&|s| (s == u).then(|| value.clone())))
                .collect(),
        )?;
        eliminated.push((u, value));
    }
    Ok((rows, unknowns, eliminated))
}

/// The linear system R_i = Σ_j a_ij u_j + b_i = 0 by Cramer's rule: each unknown's value.
fn cramer(rows: &[Expr], unknowns: &[String]) -> Result<Vec<Expr>, DeriveError> {
    let n = unknowns.len();
    let mut slopes = Vec::new();
    for r in rows {
        for u in unknowns {
            slopes.push(r.diff(u)?);
        }
    }
    let a: Vec<Expr> = cas::simplify_all(slopes)?;
    let zero_unknowns =
        |e: &Expr| e.substitute(&|s| unknowns.contains(&s.to_string()).then(|| Expr::int(0)));
    let minus_b: Vec<Expr> = rows
        .iter()
        .map(|r| Expr::negate(zero_unknowns(r)))
        .collect();
    let matrix: Vec<Vec<Expr>> = (0..n).map(|i| a[i * n..(i + 1) * n].to_vec()).collect();
    let det = cas::simplify(&determinant(&matrix))?;
    if det.is_zero() {
        return Err(DeriveError::NotDerivable(format!(
            "the equations do not determine {}: their determinant in the unknowns is zero",
            unknowns.join(", ")
        )));
    }
    let numerators: Vec<Expr> = (0..n)
        .map(|j| {
            let replaced: Vec<Vec<Expr>> = matrix
                .iter()
                .zip(&minus_b)
                .map(|(row, b)| {
                    let mut row = row.clone();
                    row[j] = b.clone();
                    row
                })
                .collect();
            Expr::over(determinant(&replaced), det.clone())
        })
        .collect();
    Ok(cas::simplify_all(numerators)?)
}

/// The determinant by expansion along the first row (at most 4 × 4 after elimination).
fn determinant(m: &[Vec<Expr>]) -> Expr {
    if m.len() == 1 {
        return m[0][0].clone();
    }
    Expr::add(
        (0..m.len())
            .map(|j| {
                let minor: Vec<Vec<Expr>> = m[1..]
                    .iter()
                    .map(|row| {
                        row.iter()
                            .enumerate()
                            .filter(|(k, _)| *k != j)
                            .map(|(_, e)| e.clone())
                            .collect()
                    })
                    .collect();
                let sign = if j % 2 == 0 { 1 } else { -1 };
                Expr::mul(vec![Expr::int(sign), m[0][j].clone(), determinant(&minor)])
            })
            .collect(),
    )
}
