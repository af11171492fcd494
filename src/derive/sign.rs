//! The sign of an expression when every symbol in it is positive: the tool behind the stability
//! table, the polhode classification and the cone inequality.
//!
//! A rational function whose expanded numerator and denominator each have terms of one sign is
//! positive or negative everywhere: that is a proof. Otherwise two sample points, one where it is
//! positive and one where it is negative, prove that the sign is not fixed. Anything else is
//! reported as undecided rather than guessed.

use super::DeriveError;
use crate::base::rng::Rng;
use crate::cas::{self, Expr};

/// Points tried when looking for a positive and a negative value.
const WITNESS_POINTS: usize = 200;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sign {
    Positive,
    Negative,
    /// Zero everywhere, or positive somewhere and negative elsewhere.
    NotFixed,
}

impl Sign {
    /// 1, −1 or 0, the value of `sign(..)` in the claim language.
    pub fn as_int(self) -> i128 {
        match self {
            Sign::Positive => 1,
            Sign::Negative => -1,
            Sign::NotFixed => 0,
        }
    }
}

/// The sign of one term of an expanded polynomial in positive symbols, if it is plain.
fn term_sign(t: &Expr) -> Option<i8> {
    match t {
        Expr::Num(r) if !r.is_zero() => Some(if r.is_positive() { 1 } else { -1 }),
        // Every symbol is positive, π included.
        Expr::Sym(_) => Some(1),
        // A positive base to any real power is positive.
        Expr::Pow(b, _) if matches!(b.as_ref(), Expr::Sym(_)) => Some(1),
        Expr::Mul(f) => f.iter().try_fold(1i8, |s, x| term_sign(x).map(|y| s * y)),
        _ => None,
    }
}

/// The sign of a product of non-zero numbers, symbols, powers of products of them and sums of
/// positive such terms, if `e` is one: every symbol is positive, so each such power and sum is
/// (3 p² (g M m/p²)^(4/3)/(m (M + m)), whose fractional power the engine's rational functions
/// do not take).
fn positive_product(e: &Expr) -> Option<i8> {
    match e {
        Expr::Num(r) if !r.is_zero() => Some(if r.is_positive() { 1 } else { -1 }),
        Expr::Sym(_) => Some(1),
        Expr::Add(v) => v
            .iter()
            .all(|x| positive_product(x) == Some(1))
            .then_some(1),
        Expr::Pow(b, _) if positive_product(b) == Some(1) => Some(1),
        Expr::Mul(f) => f
            .iter()
            .try_fold(1i8, |s, x| positive_product(x).map(|y| s * y)),
        _ => None,
    }
}

/// The common sign of every term, if there is one.
fn uniform_sign(poly: &Expr) -> Option<i8> {
    let terms: Vec<Expr> = match poly {
        Expr::Add(v) => v.clone(),
        other => vec![other.clone()],
    };
    let signs: Option<Vec<i8>> = terms.iter().map(term_sign).collect();
    let signs = signs?;
    let first = *signs.first()?;
    signs.iter().all(|s| *s == first).then_some(first)
}

/// The sign of each expression over all positive values of its symbols.
pub fn signs_over_positive(exprs: &[Expr]) -> Result<Vec<Sign>, DeriveError> {
    // A product of positive factors and powers of them is positive as written: 3k/(m∛p), whose
    // fractional power the engine's rational functions do not take.
    let plain: Vec<Option<i8>> = exprs.iter().map(positive_product).collect();
    let rest: Vec<Expr> = exprs
        .iter()
        .zip(&plain)
        .filter(|(_, s)| s.is_none())
        .map(|(e, _)| e.clone())
        .collect();
    let mut fractions = cas::fraction_all(rest)?.into_iter();
    exprs
        .iter()
        .zip(plain)
        .map(|(e, plain)| {
            if let Some(s) = plain {
                return Ok(if s > 0 {
                    Sign::Positive
                } else {
                    Sign::Negative
                });
            }
            let (num, den) = fractions.next().ok_or_else(|| {
                DeriveError::Inconsistent("a fraction for each expression".into())
            })?;
            if num.is_zero() {
                return Ok(Sign::NotFixed);
            }
            if let (Some(a), Some(b)) = (uniform_sign(&num), uniform_sign(&den)) {
                return Ok(if a * b > 0 {
                    Sign::Positive
                } else {
                    Sign::Negative
                });
            }
            if takes_both_signs(&num, &den)? {
                Ok(Sign::NotFixed)
            } else {
                Err(DeriveError::UndecidedSign { expr: e.to_text() })
            }
        })
        .collect()
}

pub fn sign_over_positive(e: &Expr) -> Result<Sign, DeriveError> {
    Ok(signs_over_positive(std::slice::from_ref(e))?[0])
}

/// Looks for a point where num/den is clearly positive and one where it is clearly negative,
/// with the symbols spread over six orders of magnitude.
fn takes_both_signs(num: &Expr, den: &Expr) -> Result<bool, DeriveError> {
    let mut names = num.symbols();
    names.extend(den.symbols());
    names.sort();
    names.dedup();
    let terms: Vec<Expr> = match num {
        Expr::Add(v) => v.clone(),
        other => vec![other.clone()],
    };
    let mut rng = Rng::new(0x5167);
    let (mut positive, mut negative) = (false, false);
    for _ in 0..WITNESS_POINTS {
        let point: Vec<(String, f64)> = names
            .iter()
            .map(|n| (n.clone(), 10f64.powf(6.0 * rng.uniform() - 3.0)))
            .collect();
        let env = |s: &str| point.iter().find(|(n, _)| n == s).map(|(_, v)| *v);
        let value = num.eval(&env)?;
        let d = den.eval(&env)?;
        // Clearly non-zero: far above the round-off of the sum of the terms' sizes.
        let size: f64 = terms
            .iter()
            .map(|t| t.eval(&env).map(f64::abs))
            .sum::<Result<f64, _>>()?;
        if value.abs() > 1e-9 * size && d != 0.0 {
            if value * d > 0.0 {
                positive = true;
            } else {
                negative = true;
            }
        }
        if positive && negative {
            return Ok(true);
        }
    }
    Ok(false)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cas::parse;

    fn sign(text: &str) -> Result<Sign, DeriveError> {
        sign_over_positive(&parse(text).unwrap().expr)
    }

    #[test]
    fn fixed_signs_are_proved_and_mixed_ones_found() {
        assert_eq!(sign("(p + q)*q/(s*(s + p))").unwrap(), Sign::Positive);
        assert_eq!(sign("-p*q*w^2/(s*(s + p + q))").unwrap(), Sign::Negative);
        // Cancels to −1 only after the fraction is reduced.
        assert_eq!(sign("(a*b - a*b - a)/(a)").unwrap(), Sign::Negative);
        assert_eq!(sign("p - q").unwrap(), Sign::NotFixed);
        assert_eq!(sign("a - a").unwrap(), Sign::NotFixed);
        // Semi-definite: never negative, zero at p = q. Neither proof applies, so it is refused.
        let e = sign("(p - q)^2").unwrap_err();
        assert!(matches!(e, DeriveError::UndecidedSign { .. }), "{e:?}");
        // A root is no rational function: the engine says so.
        let e = sign("sqrt(p) - q").unwrap_err();
        assert!(e.to_string().contains("sqrt(p) - q"), "{e:?}");
        assert!(matches!(e, DeriveError::Cas(_)), "{e:?}");
        // Powers of positive products, fractional ones too, without the engine.
        assert_eq!(sign("3*p^(-1/3)*k/m").unwrap(), Sign::Positive);
        assert_eq!(sign("-2*(a*b)^(1/3)/c").unwrap(), Sign::Negative);
        assert_eq!(sign("(a - b)^(1/3)").ok(), None);
    }
}
