//! Identities that hold when every symbol is positive, as a scene's are: a square root's
//! radicand factored and its square factors taken out, so that √(X/(4 I1²)) = √X/(2 I1) and
//! √(g²) = g.

use super::engine::{self, EngineError};
use super::expr::Expr;
use super::radical::{is_positive, pull_squares};

/// `e` with every square root's radicand factored over the rationals and its square factors
/// taken out. A radicand that is not a rational function (a root inside a root, a sine) stays.
pub fn roots_over_positive(e: &Expr, positive: &dyn Fn(&str) -> bool) -> Result<Expr, EngineError> {
    let walk = |xs: &[Expr]| -> Result<Vec<Expr>, EngineError> {
        xs.iter()
            .map(|x| roots_over_positive(x, positive))
            .collect()
    };
    Ok(match e {
        Expr::Pow(base, exp) if **exp == Expr::rat(1, 2) => {
            let base = roots_over_positive(base, positive)?;
            match engine::factor(&base) {
                Ok(factored) => pull_squares(&Expr::pow(factored, Expr::rat(1, 2)), positive),
                Err(_) => Expr::pow(base, Expr::rat(1, 2)),
            }
        }
        // X^(−1/2) = 1/√X.
        Expr::Pow(base, exp) if **exp == Expr::rat(-1, 2) => Expr::pow(
            roots_over_positive(&Expr::pow((**base).clone(), Expr::rat(1, 2)), positive)?,
            Expr::int(-1),
        ),
        Expr::Pow(base, exp) => Expr::pow(
            roots_over_positive(base, positive)?,
            roots_over_positive(exp, positive)?,
        ),
        Expr::Add(v) => Expr::add(walk(v)?),
        Expr::Mul(v) => Expr::mul(walk(v)?),
        Expr::Call(name, args) if name == "sqrt" && args.len() == 1 => {
            roots_over_positive(&Expr::pow(args[0].clone(), Expr::rat(1, 2)), positive)?
        }
        Expr::Call(name, args) => Expr::Call(name.clone(), walk(args)?),
        other => other.clone(),
    })
}

/// Whether `e` is identically zero once its roots are taken over positive symbols. Each root
/// left is then named, so that fractions over the same √X combine as fractions over a symbol.
pub fn is_zero(e: &Expr, positive: &dyn Fn(&str) -> bool) -> Result<bool, EngineError> {
    let e = roots_over_positive(&inverse_roots(e, positive), positive)?;
    let mut roots = Vec::new();
    let named = name_roots(&e, &mut roots)?;
    if !roots.is_empty() && engine::is_zero(&named)? || engine::is_zero(&e)? {
        return Ok(true);
    }
    // A fractional power of a product, each factor's own power: (g M m/p²)^(4/3) as
    // g^(4/3) M^(4/3) m^(4/3) p^(−8/3), which the engine combines with M g/∛(p²/(g M m)).
    Ok(!roots.is_empty() && engine::is_zero(&powers_of_factors(&e, positive))?)
}

/// `e` with each fractional power of a product of positive symbols, positive numbers and
/// powers of them written as the product of each factor's power, (x^a y)^q = x^(a q) y^q: true
/// when every symbol is positive, as a scene's are.
fn powers_of_factors(e: &Expr, positive: &dyn Fn(&str) -> bool) -> Expr {
    let walk = |xs: &[Expr]| xs.iter().map(|x| powers_of_factors(x, positive)).collect();
    match e {
        Expr::Pow(b, q) if matches!(q.as_ref(), Expr::Num(r) if !r.is_integer()) => {
            let b = powers_of_factors(b, positive);
            spread(&b, q, positive).map_or_else(|| Expr::pow(b, (**q).clone()), Expr::mul)
        }
        Expr::Pow(b, k) => Expr::pow(powers_of_factors(b, positive), (**k).clone()),
        Expr::Add(v) => Expr::add(walk(v)),
        Expr::Mul(v) => Expr::mul(walk(v)),
        Expr::Call(f, args) => Expr::Call(f.clone(), walk(args)),
        other => other.clone(),
    }
}

/// `b^q` as a product of each positive factor's own power, if `b` is such a product.
fn spread(b: &Expr, q: &Expr, positive: &dyn Fn(&str) -> bool) -> Option<Vec<Expr>> {
    match b {
        Expr::Sym(s) if positive(s) => Some(vec![Expr::pow(b.clone(), q.clone())]),
        Expr::Num(r) if r.is_positive() => Some(vec![Expr::pow(b.clone(), q.clone())]),
        Expr::Pow(x, k) if matches!(k.as_ref(), Expr::Num(_)) => {
            spread(x, &Expr::mul(vec![(**k).clone(), q.clone()]), positive)
        }
        Expr::Mul(v) => {
            let parts: Option<Vec<Vec<Expr>>> = v.iter().map(|f| spread(f, q, positive)).collect();
            Some(parts?.concat())
        }
        _ => None,
    }
}

/// `e` with each negative root of a positive quotient written as the root of its inverse,
/// 1/√(3g/(2L)) as √(2L/(3g)), so that both name one radicand.
pub(super) fn inverse_roots(e: &Expr, positive: &dyn Fn(&str) -> bool) -> Expr {
    let walk = |xs: &[Expr]| xs.iter().map(|x| inverse_roots(x, positive)).collect();
    match e {
        Expr::Pow(b, k)
            if matches!(k.as_ref(), Expr::Num(r) if r.is_negative() && !r.is_integer())
                && is_positive(b, positive) =>
        {
            let inverse = Expr::pow(inverse_roots(b, positive), Expr::int(-1));
            Expr::pow(inverse, Expr::negate((**k).clone()))
        }
        Expr::Pow(b, k) => Expr::pow(inverse_roots(b, positive), (**k).clone()),
        Expr::Add(v) => Expr::add(walk(v)),
        Expr::Mul(v) => Expr::mul(walk(v)),
        Expr::Call(f, args) => Expr::Call(f.clone(), walk(args)),
        other => other.clone(),
    }
}

/// `e` with each fractional power replaced by a name of its own, the same power of the same
/// radicand (in the engine's normal form, whatever order and signs it was written in) by the
/// same name; `roots` collects them.
fn name_roots(e: &Expr, roots: &mut Vec<(Expr, Expr)>) -> Result<Expr, EngineError> {
    let mut walk = |xs: &[Expr]| -> Result<Vec<Expr>, EngineError> {
        xs.iter().map(|x| name_roots(x, roots)).collect()
    };
    Ok(match e {
        Expr::Pow(b, k) if matches!(k.as_ref(), Expr::Num(n) if !n.is_integer()) => {
            let key = (engine::simplify(b)?, (**k).clone());
            let at = roots.iter().position(|r| *r == key).unwrap_or_else(|| {
                roots.push(key);
                roots.len() - 1
            });
            Expr::sym(&format!("root__{at}"))
        }
        Expr::Add(v) => Expr::add(walk(v)?),
        Expr::Mul(v) => Expr::mul(walk(v)?),
        Expr::Pow(b, k) => Expr::pow(name_roots(b, roots)?, (**k).clone()),
        Expr::Call(f, args) => Expr::Call(f.clone(), walk(args)?),
        other => other.clone(),
    })
}
