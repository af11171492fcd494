//! A sum's common factor, for the pages: ½MR²(2 − cos²α) rather than MR² − ½MR²cos²α. Display
//! only: the engine and the parser read the expanded text.

use super::expr::Expr;
use super::rational::Rational;

/// A term as its coefficient and its factors with integer exponents (x² → (x, 2)).
fn split(term: &Expr) -> (Rational, Vec<(Expr, Rational)>) {
    let factors = match term {
        Expr::Mul(v) => v.as_slice(),
        other => std::slice::from_ref(other),
    };
    let mut coefficient = Rational::ONE;
    let mut bases: Vec<(Expr, Rational)> = Vec::new();
    for f in factors {
        let (base, exponent) = match f {
            Expr::Num(r) => {
                coefficient = coefficient.mul(r);
                continue;
            }
            Expr::Pow(b, e) => match e.as_ref() {
                Expr::Num(r) if r.is_integer() => (b.as_ref().clone(), r.clone()),
                _ => (f.clone(), Rational::ONE),
            },
            other => (other.clone(), Rational::ONE),
        };
        match bases.iter_mut().find(|(b, _)| *b == base) {
            Some((_, e)) => *e = e.add(&exponent),
            None => bases.push((base, exponent)),
        }
    }
    (coefficient, bases)
}

/// The factor a printer takes out of a sum (see [`common_factor`]): none where a term carries
/// brackets of its own (a sum, or a power of one, among its factors), which a textbook prints
/// term by term: ½ml²(φ̇₁² + φ̇₂²) + mgl(cos φ₁ + cos φ₂), not l/2 (ml(…) + 2mg(…)).
pub fn printed_common_factor(terms: &[Expr]) -> Option<(Expr, Vec<Expr>)> {
    let bracketed = |f: &Expr| match f {
        Expr::Add(_) => true,
        Expr::Pow(b, _) => matches!(b.as_ref(), Expr::Add(_)),
        _ => false,
    };
    let has_brackets = |t: &Expr| match t {
        Expr::Mul(f) => f.iter().any(bracketed),
        other => bracketed(other),
    };
    if terms.iter().any(has_brackets) {
        return None;
    }
    common_factor(terms)
}

/// The factor common to every term of a sum, and the terms divided by it; `None` when there is
/// nothing worth taking out. The factor is the gcd of the coefficients (negative when every term
/// is) times each base that every term has, to its smallest power of one sign. A bare number is
/// taken out only when every coefficient is a fraction (a²/12 + b²/12), so that π/2 − θ stays.
pub fn common_factor(terms: &[Expr]) -> Option<(Expr, Vec<Expr>)> {
    if terms.len() < 2 {
        return None;
    }
    let parts: Vec<_> = terms.iter().map(split).collect();
    let mut gcd = parts[0].0.abs();
    for (c, _) in &parts[1..] {
        gcd = gcd.gcd(c);
    }
    if parts.iter().all(|(c, _)| c.is_negative()) {
        gcd = gcd.negated();
    }
    let mut common: Vec<(Expr, Rational)> = Vec::new();
    for (base, exponent) in &parts[0].1 {
        let mut least = exponent.clone();
        let everywhere = parts[1..].iter().all(|(_, bases)| {
            bases.iter().any(|(b, e)| {
                let same_sign = e.is_negative() == exponent.is_negative();
                if b == base && same_sign {
                    if e.abs() < least.abs() {
                        least = e.clone();
                    }
                    true
                } else {
                    false
                }
            })
        });
        if everywhere {
            common.push((base.clone(), least));
        }
    }
    let fractional = parts.iter().all(|(c, _)| !c.is_integer());
    let worth = !common.is_empty() || (fractional && gcd.abs() != Rational::ONE);
    if !worth {
        return None;
    }
    let inverse = gcd.recip()?;
    let rest = parts
        .iter()
        .map(|(c, bases)| {
            let mut factors = vec![Expr::Num(c.mul(&inverse))];
            for (b, e) in bases {
                let taken = common
                    .iter()
                    .find(|(cb, _)| cb == b)
                    .map_or(Rational::ZERO, |(_, k)| k.clone());
                factors.push(Expr::pow(b.clone(), Expr::Num(e.add(&taken.negated()))));
            }
            Expr::mul(factors)
        })
        .collect();
    let mut factor = vec![Expr::Num(gcd)];
    factor.extend(common.into_iter().map(|(b, e)| Expr::pow(b, Expr::Num(e))));
    Some((Expr::mul(factor), rest))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cas::parse;

    fn p(s: &str) -> Expr {
        parse(s).unwrap().expr
    }

    fn factored(s: &str) -> Option<(String, String)> {
        let Expr::Add(terms) = p(s) else {
            panic!("{s} is not a sum")
        };
        common_factor(&terms).map(|(f, rest)| (f.to_text(), Expr::Add(rest).to_text()))
    }

    #[test]
    fn the_hoop_moment_takes_out_half_m_r_squared() {
        let (f, rest) = factored("M*R^2 - M*R^2*cos(alpha)^2/2").unwrap();
        assert_eq!(f, "1/2*M*R^2");
        assert_eq!(rest, "2 - cos(alpha)^2");
    }

    #[test]
    fn fractions_share_their_denominator_and_negatives_their_sign() {
        let (f, rest) = factored("m*a^2/12 + m*b^2/12").unwrap();
        assert_eq!((f.as_str(), rest.as_str()), ("1/12*m", "a^2 + b^2"));
        let (f, rest) = factored("-a^2/4 - b^2/6").unwrap();
        assert_eq!((f.as_str(), rest.as_str()), ("-1/12", "3*a^2 + 2*b^2"));
        let (f, rest) = factored("x^3/y^2 + x^2/y^3").unwrap();
        assert_eq!((f.as_str(), rest.as_str()), ("x^2/y^2", "x + y^(-1)"));
    }

    #[test]
    fn nothing_worth_taking_out_is_left_alone() {
        assert_eq!(factored("pi/2 - theta"), None);
        assert_eq!(factored("a + b"), None);
        assert_eq!(factored("2*a + 4*b"), None);
    }

    #[test]
    fn the_factor_times_the_rest_is_the_sum() {
        for s in [
            "M*R^2 - M*R^2*cos(alpha)^2/2",
            "m*a^2/12 + m*b^2/12 - m*a*b*c/3",
            "-a^2/4 - b^2/6",
        ] {
            let Expr::Add(terms) = p(s) else { panic!() };
            let (f, rest) = common_factor(&terms).unwrap();
            let back = Expr::mul(vec![f, Expr::add(rest)]);
            let at = |e: &Expr| {
                e.eval(&|n| {
                    Some(match n {
                        "M" | "m" => 1.7,
                        "R" => 0.9,
                        "alpha" => 0.4,
                        "a" => 1.3,
                        "b" => 0.6,
                        _ => 2.2,
                    })
                })
                .unwrap()
            };
            assert!((at(&back) - at(&p(s))).abs() < 1e-12, "{s}");
        }
    }
}
