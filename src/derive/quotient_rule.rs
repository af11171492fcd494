//! The derivative of a rational function with its denominator kept factored: for
//! f = N/D with D = c·Π fᵢ^kᵢ, f' = (N' Π fᵢ − N Σ kᵢ fᵢ' Π_{j≠i} fⱼ)/(D Π fᵢ). The quotient
//! rule as written squares D, whose expansion an effective potential's second derivative puts
//! past the engine's budget (degree 32 for (p_φ − p_ψ cos θ)²/(2(I₁ + Ml²) sin²θ)); this form's
//! denominator grows by the factors once.

use super::DeriveError;
use crate::cas::{self, Expr};

/// f' by the rule above, simplified; `derivative` is ∂/∂x or d/dt through the coordinates.
pub fn derivative_of_quotient(
    f: &Expr,
    derivative: &dyn Fn(&Expr) -> Result<Expr, DeriveError>,
) -> Result<Expr, DeriveError> {
    let (n, d) = cas::fraction_all(vec![f.clone()])?.remove(0);
    let factored = cas::factor_all(vec![d])?.remove(0);
    let listed = match &factored {
        Expr::Mul(v) => v.clone(),
        other => vec![other.clone()],
    };
    // Each factor that is not a number, with its power.
    let factors: Vec<(Expr, i64)> = listed
        .into_iter()
        .filter_map(|f| match f {
            Expr::Num(_) => None,
            Expr::Pow(b, k) => match k.as_ref() {
                Expr::Num(r) => r.to_i64().map(|k| (*b, k)),
                _ => Some((Expr::Pow(b, k), 1)),
            },
            other => Some((other, 1)),
        })
        .collect();
    let product = |skip: Option<usize>| {
        Expr::mul(
            factors
                .iter()
                .enumerate()
                .filter(|(j, _)| Some(*j) != skip)
                .map(|(_, (b, _))| b.clone())
                .collect(),
        )
    };
    let mut terms = vec![Expr::mul(vec![derivative(&n)?, product(None)])];
    for (i, (b, k)) in factors.iter().enumerate() {
        terms.push(Expr::mul(vec![
            Expr::int(-i128::from(*k)),
            n.clone(),
            derivative(b)?,
            product(Some(i)),
        ]));
    }
    let numerator = cas::simplify(&Expr::add(terms))?;
    Ok(cas::simplify(&Expr::over(
        numerator,
        Expr::mul(vec![factored, product(None)]),
    ))?)
}
