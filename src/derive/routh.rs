//! Routh's procedure: for cyclic coordinates φ (∂L/∂φ = 0) with conserved momenta
//! p = ∂L/∂φ', the Routhian R = L − Σ p φ' with each φ' solved from its momentum, a function
//! of the remaining coordinates, their rates and the momenta as constants.

use super::DeriveError;
use super::solve::solve_system;
use crate::cas::{self, Expr};

/// The Routhian of `lagrangian` for the `cyclic` coordinates, each with its momentum's symbol.
pub fn routhian(lagrangian: &Expr, cyclic: &[(String, String)]) -> Result<Expr, DeriveError> {
    for (q, _) in cyclic {
        let force = cas::simplify(&lagrangian.diff(q)?)?;
        if !force.is_zero() {
            return Err(DeriveError::NotDerivable(format!(
                "`{q}` is not cyclic: the Lagrangian depends on it (∂L/∂{q} = {}), so its \
                 momentum is not conserved",
                force.to_text()
            )));
        }
    }
    // p = ∂L/∂φ' for each: linear in the rates, as L is quadratic in them.
    let mut eqs = Vec::new();
    for (q, p) in cyclic {
        let momentum = lagrangian.diff(&format!("{q}'"))?;
        eqs.push((p.clone(), Expr::minus(momentum, Expr::sym(p))));
    }
    let rates: Vec<String> = cyclic.iter().map(|(q, _)| format!("{q}'")).collect();
    let solved = solve_system(&eqs, &rates)?;
    let mut terms = vec![lagrangian.clone()];
    for (q, p) in cyclic {
        terms.push(Expr::mul(vec![
            Expr::int(-1),
            Expr::sym(p),
            Expr::sym(&format!("{q}'")),
        ]));
    }
    let routhian = Expr::add(terms)
        .substitute(&|s| solved.iter().find(|(u, _)| u == s).map(|(_, v)| v.clone()));
    Ok(cas::simplify(&routhian)?)
}
