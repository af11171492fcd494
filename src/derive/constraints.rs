//! Constraints with Lagrange multipliers. A holonomic constraint f(q) = 0 adds the generalised
//! force λ ∂f/∂q to each coordinate's equation and, differentiated twice, an equation linear
//! in the accelerations; a velocity constraint Σ a_k(q) q_k' = 0 (a rolling coin's, which need
//! not integrate) adds λ a_k and, differentiated once, the same kind of equation. Accelerations
//! and multipliers are then solved together (`solve` with `for = ["x1''", "x2''", "T"]`).

use super::DeriveError;
use super::lagrangian::time_derivative;
use crate::cas::{self, Expr};
use std::collections::BTreeMap;

/// Whether a constraint is on the velocities: it names a coordinate's rate.
pub fn is_velocity_constraint(f: &Expr, coordinates: &BTreeMap<String, String>) -> bool {
    f.symbols().iter().any(|s| {
        s.strip_suffix('\'')
            .is_some_and(|q| coordinates.contains_key(q))
    })
}

/// The Euler–Lagrange residuals `eqs` with each constraint's force taken over,
/// d/dt ∂L/∂q' − ∂L/∂q − Σ_j λ_j a_jq (a_jq = ∂f_j/∂q, or ∂g_j/∂q' for a velocity
/// constraint), in the coordinates' order (a coordinate only a constraint names has the force
/// alone), then each constraint differentiated until it holds an acceleration (f'', g') under
/// its multiplier's name; unsimplified.
pub fn with_multipliers(
    eqs: Vec<(String, Expr)>,
    constraints: &[(String, Expr)],
    coordinates: &BTreeMap<String, String>,
) -> Result<Vec<(String, Expr)>, DeriveError> {
    if constraints.is_empty() {
        return Ok(eqs);
    }
    let mut residuals: BTreeMap<String, Expr> = eqs.into_iter().collect();
    for (lambda, f) in constraints {
        if is_velocity_constraint(f, coordinates) {
            linear_in_rates(lambda, f, coordinates)?;
        }
        for q in f.symbols() {
            let q = q.trim_end_matches('\'').to_string();
            if coordinates.contains_key(&q) {
                residuals.entry(q).or_insert_with(|| Expr::int(0));
            }
        }
    }
    let mut out = Vec::new();
    for (q, r) in residuals {
        let mut terms = vec![r];
        for (lambda, f) in constraints {
            let slope = match is_velocity_constraint(f, coordinates) {
                true => f.diff(&format!("{q}'"))?,
                false => f.diff(&q)?,
            };
            terms.push(Expr::mul(vec![Expr::int(-1), Expr::sym(lambda), slope]));
        }
        out.push((q, Expr::add(terms)));
    }
    for (lambda, f) in constraints {
        let mut row = time_derivative(f, coordinates)?;
        if !is_velocity_constraint(f, coordinates) {
            row = time_derivative(&row, coordinates)?;
        }
        out.push((lambda.clone(), row));
    }
    Ok(out)
}

/// A velocity constraint is Σ a_k(q) q_k' = 0: linear in the rates, with nothing left when
/// they are 0 (else it is not a constraint on the velocities alone).
fn linear_in_rates(
    lambda: &str,
    g: &Expr,
    coordinates: &BTreeMap<String, String>,
) -> Result<(), DeriveError> {
    let rates: Vec<String> = coordinates.keys().map(|q| format!("{q}'")).collect();
    let at_rest = g.substitute(&|s| rates.iter().any(|r| r == s).then(|| Expr::int(0)));
    let mut parts = vec![at_rest];
    for a in &rates {
        let slope = g.diff(a)?;
        for b in &rates {
            parts.push(slope.diff(b)?);
        }
    }
    if cas::simplify_all(parts)?.iter().any(|p| !p.is_zero()) {
        return Err(DeriveError::NotDerivable(format!(
            "the constraint of `{lambda}`, {} = 0, is not of the form Σ a(q) q' = 0: a velocity \
             constraint must be linear in the rates, with no term free of them",
            g.to_text()
        )));
    }
    Ok(())
}

/// Whether the velocity constraint q' = Σ_j a_j(q) q_j' (`rate` replaced by `value`) fails to
/// integrate to a relation among the coordinates: the form ω = dq − Σ a_j dq_j has
/// ω ∧ dω ≠ 0 (Frobenius). A rolling disk's x' = r q3' cos q1 does not integrate; a wheel's
/// θ' = x'/R does. A replacement that is not linear in the rates, or has a term free of them,
/// is not a velocity constraint: `false`.
pub fn does_not_integrate(
    rate: &str,
    value: &Expr,
    coordinates: &BTreeMap<String, String>,
) -> Result<bool, DeriveError> {
    let Some(q) = rate
        .strip_suffix('\'')
        .filter(|q| coordinates.contains_key(*q))
    else {
        return Ok(false);
    };
    let names: Vec<&String> = coordinates.keys().collect();
    // ω's component on each coordinate: 1 on q, −∂value/∂q_j' on each.
    let mut omega = Vec::new();
    for c in &names {
        let a = value.diff(&format!("{c}'"))?;
        let own = if c.as_str() == q {
            Expr::int(1)
        } else {
            Expr::int(0)
        };
        omega.push(Expr::minus(own, a));
    }
    let omega = cas::simplify_all(omega)?;
    let rates_of = |e: &Expr| {
        e.symbols().iter().any(|s| {
            s.strip_suffix('\'')
                .is_some_and(|c| coordinates.contains_key(c))
        })
    };
    // Linear in the rates with no free term: value = Σ a_j q_j'.
    let rebuilt = Expr::add(
        names
            .iter()
            .zip(&omega)
            .filter(|(c, _)| c.as_str() != q)
            .map(|(c, w)| Expr::mul(vec![Expr::negate(w.clone()), Expr::sym(&format!("{c}'"))]))
            .collect(),
    );
    if omega.iter().any(rates_of) || !cas::simplify(&Expr::minus(value.clone(), rebuilt))?.is_zero()
    {
        return Ok(false);
    }
    let d = |k: usize, j: usize| omega[k].diff(names[j]);
    let mut wedges = Vec::new();
    for i in 0..names.len() {
        for j in i + 1..names.len() {
            for l in j + 1..names.len() {
                wedges.push(Expr::add(vec![
                    Expr::mul(vec![omega[i].clone(), Expr::minus(d(l, j)?, d(j, l)?)]),
                    Expr::mul(vec![omega[j].clone(), Expr::minus(d(i, l)?, d(l, i)?)]),
                    Expr::mul(vec![omega[l].clone(), Expr::minus(d(j, i)?, d(i, j)?)]),
                ]));
            }
        }
    }
    Ok(cas::simplify_all(wedges)?.iter().any(|w| !w.is_zero()))
}
