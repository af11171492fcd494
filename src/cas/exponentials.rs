//! Exponentials as powers of new positive symbols, so that an identity among exponentials is
//! one among rational functions, which the engine decides: exp(u + v) = exp(u)·exp(v),
//! cosh²u − sinh²u = 1, d tanh u = du/cosh²u. The engine holds exp opaque (`functions.rs`), so
//! without this exp(ax)·exp(−ax) = 1 was undecided.

use super::engine::{self, EngineError};
use super::expr::Expr;
use std::collections::BTreeMap;

/// The symbols that stand for exponentials: `__` is never in a scene's names.
fn name(k: usize) -> String {
    format!("exp__{k}")
}

/// `e` with sinh u and cosh u written through exp, and each exp(Σ cᵢ tᵢ) (cᵢ numbers, tᵢ
/// distinct monomials once expanded) as Π Eᵢ^cᵢ, where Eᵢ is a new symbol for exp(tᵢ), one per
/// monomial. Each Eᵢ is positive, as exp is.
pub(super) fn as_powers(e: &Expr) -> Result<Expr, EngineError> {
    let mut monomials = BTreeMap::new();
    rewrite(&hyperbolic_as_exp(e), &mut monomials)
}

/// sinh u = (exp u − exp(−u))/2, cosh u = (exp u + exp(−u))/2, from the leaves up.
fn hyperbolic_as_exp(e: &Expr) -> Expr {
    let each = |v: &[Expr]| v.iter().map(hyperbolic_as_exp).collect::<Vec<_>>();
    match e {
        Expr::Call(f, args) if (f == "sinh" || f == "cosh") && args.len() == 1 => {
            let u = hyperbolic_as_exp(&args[0]);
            let down = Expr::call("exp", Expr::negate(u.clone()));
            let down = if f == "sinh" {
                Expr::negate(down)
            } else {
                down
            };
            Expr::mul(vec![
                Expr::rat(1, 2),
                Expr::add(vec![Expr::call("exp", u), down]),
            ])
        }
        Expr::Call(f, args) => Expr::Call(f.clone(), each(args)),
        Expr::Add(v) => Expr::add(each(v)),
        Expr::Mul(v) => Expr::mul(each(v)),
        Expr::List(v) => Expr::List(each(v)),
        Expr::Pow(a, b) => Expr::pow(hyperbolic_as_exp(a), hyperbolic_as_exp(b)),
        Expr::Index(a, b) => Expr::Index(
            Box::new(hyperbolic_as_exp(a)),
            Box::new(hyperbolic_as_exp(b)),
        ),
        Expr::Num(_) | Expr::Sym(_) => e.clone(),
    }
}

/// `e` with each exp(…) a product of powers of the monomials' symbols.
fn rewrite(e: &Expr, monomials: &mut BTreeMap<String, String>) -> Result<Expr, EngineError> {
    let mut each = |v: &[Expr]| -> Result<Vec<Expr>, EngineError> {
        v.iter().map(|x| rewrite(x, monomials)).collect()
    };
    Ok(match e {
        Expr::Call(f, args) if f == "exp" && args.len() == 1 => {
            let exponent = engine::from_atom(&engine::expand(&rewrite(&args[0], monomials)?)?)?;
            let terms = match exponent {
                Expr::Add(v) => v,
                other => vec![other],
            };
            let mut factors = Vec::new();
            for term in terms {
                let (c, monomial) = split_coefficient(term);
                let next = name(monomials.len());
                let symbol = monomials.entry(monomial.to_text()).or_insert(next);
                factors.push(Expr::pow(Expr::sym(symbol), Expr::Num(c)));
            }
            Expr::mul(factors)
        }
        Expr::Call(f, args) => Expr::Call(f.clone(), each(args)?),
        Expr::Add(v) => Expr::add(each(v)?),
        Expr::Mul(v) => Expr::mul(each(v)?),
        Expr::List(v) => Expr::List(each(v)?),
        Expr::Pow(a, b) => Expr::pow(rewrite(a, monomials)?, rewrite(b, monomials)?),
        Expr::Index(a, b) => Expr::Index(
            Box::new(rewrite(a, monomials)?),
            Box::new(rewrite(b, monomials)?),
        ),
        Expr::Num(_) | Expr::Sym(_) => e.clone(),
    })
}

/// A term as its number and the rest: 3ax → (3, ax); 5 → (5, 1).
fn split_coefficient(term: Expr) -> (super::rational::Rational, Expr) {
    use super::rational::Rational;
    match term {
        Expr::Num(c) => (c, Expr::int(1)),
        Expr::Mul(factors) => {
            let mut c = Rational::ONE;
            let mut rest = Vec::new();
            for f in factors {
                match f {
                    Expr::Num(n) => c = c.mul(&n),
                    other => rest.push(other),
                }
            }
            (c, Expr::mul(rest))
        }
        other => (Rational::ONE, other),
    }
}
