//! Identities that hold when every symbol is positive, as a scene's are: a square root's
//! radicand factored and its square factors taken out, so that √(X/(4 I1²)) = √X/(2 I1) and
//! √(g²) = g.

use super::engine::{self, EngineError};
use super::expr::Expr;
use super::radical::pull_squares;

/// `e` with every square root's radicand factored over the rationals and its square factors
/// taken out. A radicand that is not a rational function (a root inside a root, a sine) stays.
pub fn roots_over_positive(e: &Expr) -> Result<Expr, EngineError> {
    let walk = |xs: &[Expr]| -> Result<Vec<Expr>, EngineError> {
        xs.iter().map(roots_over_positive).collect()
    };
    Ok(match e {
        Expr::Pow(base, exp) if **exp == Expr::rat(1, 2) => {
            let base = roots_over_positive(base)?;
            match engine::factor(&base) {
                Ok(factored) => pull_squares(&Expr::pow(factored, Expr::rat(1, 2)), &|_| true),
                Err(_) => Expr::pow(base, Expr::rat(1, 2)),
            }
        }
        // X^(−1/2) = 1/√X.
        Expr::Pow(base, exp) if **exp == Expr::rat(-1, 2) => Expr::pow(
            roots_over_positive(&Expr::pow((**base).clone(), Expr::rat(1, 2)))?,
            Expr::int(-1),
        ),
        Expr::Pow(base, exp) => Expr::pow(roots_over_positive(base)?, roots_over_positive(exp)?),
        Expr::Add(v) => Expr::add(walk(v)?),
        Expr::Mul(v) => Expr::mul(walk(v)?),
        Expr::Call(name, args) => Expr::Call(name.clone(), walk(args)?),
        other => other.clone(),
    })
}

/// Whether `e` is identically zero once its roots are taken over positive symbols.
pub fn is_zero(e: &Expr) -> Result<bool, EngineError> {
    engine::is_zero(&roots_over_positive(e)?)
}
