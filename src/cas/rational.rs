//! Exact rational numbers for our own expression tree.
//!
//! The numbers that appear in these derivations are small (1/2, 11/12, 2/3), so an `i128` pair is
//! plenty; arithmetic is checked and an overflow is reported instead of wrapping.

use std::fmt;

/// A reduced fraction `num/den` with `den > 0`.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub struct Rational {
    num: i128,
    den: i128,
}

fn gcd(mut a: i128, mut b: i128) -> i128 {
    a = a.abs();
    b = b.abs();
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

impl Rational {
    pub const ZERO: Rational = Rational { num: 0, den: 1 };
    pub const ONE: Rational = Rational { num: 1, den: 1 };

    /// `num/den`, reduced. `None` when `den` is zero.
    pub fn new(num: i128, den: i128) -> Option<Rational> {
        if den == 0 {
            return None;
        }
        let g = gcd(num, den).max(1);
        let sign = if den < 0 { -1 } else { 1 };
        Some(Rational {
            num: sign * num / g,
            den: sign * den / g,
        })
    }

    pub fn int(n: i128) -> Rational {
        Rational { num: n, den: 1 }
    }

    pub fn numer(self) -> i128 {
        self.num
    }

    pub fn denom(self) -> i128 {
        self.den
    }

    pub fn is_zero(self) -> bool {
        self.num == 0
    }

    pub fn is_integer(self) -> bool {
        self.den == 1
    }

    pub fn to_f64(self) -> f64 {
        self.num as f64 / self.den as f64
    }

    pub fn negated(self) -> Rational {
        Rational {
            num: -self.num,
            den: self.den,
        }
    }

    pub fn checked_mul(self, o: Rational) -> Option<Rational> {
        Rational::new(self.num.checked_mul(o.num)?, self.den.checked_mul(o.den)?)
    }

    pub fn checked_add(self, o: Rational) -> Option<Rational> {
        let num = self
            .num
            .checked_mul(o.den)?
            .checked_add(o.num.checked_mul(self.den)?)?;
        Rational::new(num, self.den.checked_mul(o.den)?)
    }

    /// Parses a decimal such as `12`, `0.25` or `1e-3` exactly.
    pub fn parse_decimal(text: &str) -> Option<Rational> {
        let (mantissa, exponent) = match text.find(['e', 'E']) {
            Some(i) => (&text[..i], text[i + 1..].parse::<i32>().ok()?),
            None => (text, 0),
        };
        let (int_part, frac_part) = match mantissa.find('.') {
            Some(i) => (&mantissa[..i], &mantissa[i + 1..]),
            None => (mantissa, ""),
        };
        if int_part.is_empty() && frac_part.is_empty() {
            return None;
        }
        let digits = format!("{int_part}{frac_part}");
        if !digits.chars().all(|c| c.is_ascii_digit()) {
            return None;
        }
        let num: i128 = digits.parse().ok()?;
        let scale = exponent - frac_part.len() as i32;
        let ten = 10i128.checked_pow(scale.unsigned_abs())?;
        if scale >= 0 {
            Rational::new(num.checked_mul(ten)?, 1)
        } else {
            Rational::new(num, ten)
        }
    }
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.den == 1 {
            write!(f, "{}", self.num)
        } else {
            write!(f, "{}/{}", self.num, self.den)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reduces_and_normalises_sign() {
        assert_eq!(Rational::new(6, -8).unwrap().to_string(), "-3/4");
        assert!(Rational::new(1, 0).is_none());
    }

    #[test]
    fn parses_decimals_exactly() {
        assert_eq!(Rational::parse_decimal("0.25"), Rational::new(1, 4));
        assert_eq!(Rational::parse_decimal("1e-3"), Rational::new(1, 1000));
        assert_eq!(Rational::parse_decimal("2.5e1"), Rational::new(25, 1));
        assert_eq!(Rational::parse_decimal("."), None);
    }

    #[test]
    fn checked_arithmetic() {
        let h = Rational::new(1, 2).unwrap();
        let t = Rational::new(1, 3).unwrap();
        assert_eq!(h.checked_add(t), Rational::new(5, 6));
        assert_eq!(h.checked_mul(t), Rational::new(1, 6));
        assert_eq!(Rational::int(i128::MAX).checked_mul(Rational::int(2)), None);
    }
}
