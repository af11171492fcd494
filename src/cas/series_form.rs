//! A power series as a textbook prints it: its leading term times 1 + … (see `present.rs`).

use super::expr::Expr;
use super::rational::Rational;

/// c(k + b xⁿ + d xᵐ …) as c k (1 + (b/k) xⁿ + (d/k) xᵐ …): a power series in one symbol led by
/// its constant term k, as a textbook writes 2π√(l/g)(1 + a²/16 + 11a⁴/3072). Only a product
/// of symbols with such a sum of three or more terms is touched.
pub(super) fn leading_term(e: &Expr) -> Option<Expr> {
    let Expr::Mul(factors) = e else {
        return None;
    };
    let at = factors.iter().position(|f| matches!(f, Expr::Add(_)))?;
    // A leading term with a symbol in it (2π√(l/g)), not a number taken out of a polynomial.
    if !factors
        .iter()
        .enumerate()
        .any(|(i, f)| i != at && !matches!(f, Expr::Num(_)))
    {
        return None;
    }
    let Expr::Add(terms) = &factors[at] else {
        return None;
    };
    let constant = terms.iter().find_map(|t| match t {
        Expr::Num(k) if !k.is_zero() && *k != Rational::ONE => Some(k.clone()),
        _ => None,
    })?;
    // Every other term a number times a positive power of one symbol.
    let power_of = |t: &Expr| -> Option<String> {
        let parts = match t {
            Expr::Mul(v) => v.as_slice(),
            other => std::slice::from_ref(other),
        };
        let mut symbol = None;
        for f in parts {
            match f {
                Expr::Num(_) => {}
                Expr::Sym(s) if symbol.is_none() => symbol = Some(s.clone()),
                Expr::Pow(b, k) if symbol.is_none() => match (b.as_ref(), k.as_ref()) {
                    (Expr::Sym(s), Expr::Num(k)) if k.is_integer() && !k.is_negative() => {
                        symbol = Some(s.clone())
                    }
                    _ => return None,
                },
                _ => return None,
            }
        }
        symbol
    };
    let others: Vec<&Expr> = terms
        .iter()
        .filter(|t| !matches!(t, Expr::Num(_)))
        .collect();
    if others.len() < 2 || others.len() + 1 != terms.len() {
        return None;
    }
    let first = power_of(others[0])?;
    if !others.iter().all(|t| power_of(t).as_ref() == Some(&first)) {
        return None;
    }
    let inverse = Expr::Num(constant.recip()?);
    let mut series = vec![Expr::int(1)];
    series.extend(
        others
            .iter()
            .map(|t| Expr::mul(vec![inverse.clone(), (*t).clone()])),
    );
    let mut out: Vec<Expr> = factors.clone();
    out[at] = Expr::Add(series);
    out.push(Expr::Num(constant));
    Some(Expr::mul(out))
}
