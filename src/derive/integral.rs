//! `integrate`: an author's definite integral, exactly, with the engine's rules for the bodies:
//! a polynomial in a variable over any range, or a polynomial in the cosine and sine of an angle
//! over 0 to 2π, π or π/2.

use super::DeriveError;
use crate::cas::{self, AngleSpan, Expr, Integral};

/// The integral of `f` over the ranges, innermost first, simplified, and the integrals the
/// engine did (for the page).
pub fn integral(
    f: &Expr,
    over: &[(String, Expr, Expr)],
) -> Result<(Expr, Vec<Integral>), DeriveError> {
    let mut integrals = Vec::new();
    for (var, lo, hi) in over {
        let angle = f.symbols().contains(var) && has_trig_of(f, var);
        let span = match cas::pi_multiple(&cas::simplify(hi)?) {
            Some(r) if angle && lo.is_zero() => [
                (AngleSpan::Full, 2, 1),
                (AngleSpan::Half, 1, 1),
                (AngleSpan::Quarter, 1, 2),
            ]
            .into_iter()
            .find(|(_, n, d)| cas::Rational::new(*n, *d) == Some(r.clone()))
            .map(|(s, _, _)| s),
            _ => None,
        };
        integrals.push(match span {
            Some(span) => Integral::Trig {
                var: var.clone(),
                span,
            },
            None if angle => {
                return Err(DeriveError::NotDerivable(format!(
                    "the integrand has sin or cos of `{var}`: integrate it from 0 to 2*pi, pi or \
                     pi/2"
                )));
            }
            None => Integral::Poly {
                var: var.clone(),
                lo: lo.clone(),
                hi: hi.clone(),
            },
        });
    }
    let mut result = cas::integrate_all(vec![f.clone()], integrals.clone())?;
    Ok((cas::simplify(&result.remove(0))?, integrals))
}

/// Whether `e` has sin or cos of an argument that holds `var`.
fn has_trig_of(e: &Expr, var: &str) -> bool {
    match e {
        Expr::Call(name, args) if name == "sin" || name == "cos" => {
            args.iter().any(|a| a.symbols().iter().any(|s| s == var))
        }
        Expr::Call(_, v) | Expr::Add(v) | Expr::Mul(v) | Expr::List(v) => {
            v.iter().any(|x| has_trig_of(x, var))
        }
        Expr::Pow(b, k) => has_trig_of(b, var) || has_trig_of(k, var),
        _ => false,
    }
}
