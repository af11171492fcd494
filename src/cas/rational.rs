//! Exact rational numbers for our own expression tree.
//!
//! Arbitrary precision (malachite, which Symbolica's pure-Rust feature set already builds): a
//! point at 1e-10 m, a mass of 1e30 kg or a long decimal in `[expect]` stays exact, and no
//! arithmetic can overflow. Numbers that fit in an `i64` pair, as almost all of these
//! derivations' numbers do, cross to the engine directly.

use malachite_base::num::arithmetic::traits::{Abs, Pow, Reciprocal, Sign};
use malachite_base::num::basic::traits::{One, Zero};
use malachite_base::num::conversion::traits::{IsInteger, RoundingFrom};
use malachite_base::rounding_modes::RoundingMode;
use malachite_nz::integer::Integer;
use malachite_nz::natural::Natural;
use std::cmp::Ordering;
use std::fmt;
use std::str::FromStr;

/// The most digits, and the largest decimal exponent, a number in a scene may have. Far beyond
/// any physical quantity (f64 holds 17 digits and ends at 1e308), and small enough that every
/// number stays cheap: a mass of 990 digits once took a 12-minute build.
pub const MAX_DIGITS: usize = 100;
pub const MAX_EXPONENT: i64 = 1000;
/// The most bits of an exact power ([`Rational::pow`]): about the engine's 100,000 digits.
pub const MAX_POWER_BITS: u64 = 400_000;
/// The most digits of a number the engine gives back: its products of a scene's numbers.
pub const MAX_ENGINE_DIGITS: usize = 100_000;

/// A reduced fraction.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Rational(malachite_q::Rational);

impl Rational {
    pub const ZERO: Rational = Rational(malachite_q::Rational::ZERO);
    pub const ONE: Rational = Rational(malachite_q::Rational::ONE);

    /// `num/den`, reduced. `None` when `den` is zero.
    pub fn new(num: i128, den: i128) -> Option<Rational> {
        if den == 0 {
            return None;
        }
        Some(Rational(malachite_q::Rational::from_integers(
            Integer::from(num),
            Integer::from(den),
        )))
    }

    pub fn int(n: i128) -> Rational {
        Rational(malachite_q::Rational::from(n))
    }

    pub fn is_zero(&self) -> bool {
        self.0 == 0u32
    }

    pub fn is_negative(&self) -> bool {
        self.0.sign() == Ordering::Less
    }

    pub fn is_positive(&self) -> bool {
        self.0.sign() == Ordering::Greater
    }

    pub fn is_integer(&self) -> bool {
        (&self.0).is_integer()
    }

    /// The value as an `i64` when it is an integer that fits.
    pub fn to_i64(&self) -> Option<i64> {
        i64::try_from(&self.0).ok()
    }

    /// x mod m for a positive m, in [0, m), exactly: whole turns taken off an angle of any size.
    pub fn rem_euclid(&self, m: &Rational) -> Rational {
        use malachite_base::num::arithmetic::traits::Floor;
        let turns = (&self.0 / &m.0).floor();
        Rational(&self.0 - malachite_q::Rational::from(turns) * &m.0)
    }

    /// ⌊x⌋ as a `u64` when it is non-negative and fits.
    pub fn floor_to_u64(&self) -> Option<u64> {
        use malachite_base::num::arithmetic::traits::Floor;
        u64::try_from(&(&self.0).floor()).ok()
    }

    /// The numerator, with the sign, and the (positive) denominator, as `i64`s when both fit.
    pub fn to_i64_pair(&self) -> Option<(i64, i64)> {
        let (n, d) = self.0.numerator_and_denominator_ref();
        let n = i64::try_from(n).ok()?;
        let d = i64::try_from(d).ok()?;
        Some((if self.is_negative() { -n } else { n }, d))
    }

    /// |numerator| and the denominator.
    pub fn abs_parts(&self) -> (Rational, Rational) {
        let (n, d) = self.0.to_numerator_and_denominator();
        (Rational::natural(n), Rational::natural(d))
    }

    fn natural(n: Natural) -> Rational {
        Rational(malachite_q::Rational::from(n))
    }

    /// The limbs of |numerator| and of the denominator, least significant first, in base 2^32:
    /// how a large number is handed to the engine without text.
    pub fn abs_parts_base_2_32(&self) -> (Vec<u32>, Vec<u32>) {
        let halves = |n: &Natural| {
            n.to_limbs_asc()
                .into_iter()
                .flat_map(|l| [l as u32, (l >> 32) as u32])
                .collect()
        };
        let (n, d) = self.0.numerator_and_denominator_ref();
        (halves(n), halves(d))
    }

    /// The nearest f64 (beyond its range: ±f64::MAX, or a signed zero).
    pub fn to_f64(&self) -> f64 {
        // Both parts exact in f64: one division, correctly rounded, as it always was.
        if let Some((n, d)) = self.to_i64_pair()
            && n.unsigned_abs() <= 1 << 53
            && d <= 1 << 53
        {
            return n as f64 / d as f64;
        }
        f64::rounding_from(&self.0, RoundingMode::Nearest).0
    }

    /// The exact value of a finite f64 (every one is a fraction over a power of 2); `None`
    /// for an infinity or NaN.
    pub fn from_f64(x: f64) -> Option<Rational> {
        malachite_q::Rational::try_from(x).ok().map(Rational)
    }

    pub fn negated(&self) -> Rational {
        Rational(-&self.0)
    }

    pub fn abs(&self) -> Rational {
        Rational((&self.0).abs())
    }

    /// 1/x, `None` for zero.
    pub fn recip(&self) -> Option<Rational> {
        (!self.is_zero()).then(|| Rational((&self.0).reciprocal()))
    }

    pub fn add(&self, o: &Rational) -> Rational {
        Rational(&self.0 + &o.0)
    }

    pub fn mul(&self, o: &Rational) -> Rational {
        Rational(&self.0 * &o.0)
    }

    /// x^k for an integer k; `None` for 0 to a negative power.
    /// `self^k`; `None` for 0^-k, and for a power of more than [`MAX_POWER_BITS`] bits, which
    /// would not fit in memory ((1/1000)^(10^12)).
    pub fn pow(&self, k: i64) -> Option<Rational> {
        use malachite_base::num::logic::traits::SignificantBits;
        let bits = self
            .0
            .numerator_ref()
            .significant_bits()
            .max(self.0.denominator_ref().significant_bits());
        if bits > 1 && bits.saturating_mul(k.unsigned_abs()) > MAX_POWER_BITS {
            return None;
        }
        let base = if k < 0 { self.recip()? } else { self.clone() };
        Some(Rational((&base.0).pow(k.unsigned_abs())))
    }

    /// The order of two rationals.
    pub fn compare(&self, o: &Rational) -> Ordering {
        self.0.cmp(&o.0)
    }

    /// The largest positive rational of which both are integer multiples: the gcd of the
    /// numerators over the lcm of the denominators (gcd(1/4, 1/6) = 1/12).
    pub fn gcd(&self, o: &Rational) -> Rational {
        use malachite_base::num::arithmetic::traits::{Gcd, Lcm};
        let n = self.0.numerator_ref().gcd(o.0.numerator_ref());
        let d = self.0.denominator_ref().lcm(o.0.denominator_ref());
        Rational(malachite_q::Rational::from_naturals(n, d))
    }

    /// Parses a decimal such as `12`, `0.25` or `1e-3` exactly; `None` when it is not one, or
    /// has more than [`MAX_DIGITS`] digits or an exponent beyond ±[`MAX_EXPONENT`].
    pub fn parse_decimal(text: &str) -> Option<Rational> {
        Rational::parse_decimal_within(text, MAX_DIGITS)
    }

    /// [`Rational::parse_decimal`] with at most `max_digits` digits.
    pub fn parse_decimal_within(text: &str, max_digits: usize) -> Option<Rational> {
        let (mantissa, exponent) = match text.find(['e', 'E']) {
            Some(i) => (&text[..i], text[i + 1..].parse::<i64>().ok()?),
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
        if !digits.chars().all(|c| c.is_ascii_digit())
            || digits.len() > max_digits
            || exponent.abs() > MAX_EXPONENT
        {
            return None;
        }
        let num = Natural::from_str(&digits).ok()?;
        let scale = exponent - frac_part.len() as i64;
        let ten = malachite_q::Rational::from(10u32).pow(scale);
        Some(Rational(malachite_q::Rational::from(num) * ten))
    }
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.0, f)
    }
}

/// Stored as its text (`-3/4`), so the cache reads back any size.
impl serde::Serialize for Rational {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.0.to_string())
    }
}

impl<'de> serde::Deserialize<'de> for Rational {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Rational, D::Error> {
        let text = String::deserialize(d)?;
        malachite_q::Rational::from_str(&text)
            .map(Rational)
            .map_err(|_| serde::de::Error::custom(format!("not a rational: `{text}`")))
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
        // Beyond i128: exact all the same.
        let tiny = Rational::parse_decimal("1e-40").unwrap();
        assert_eq!(tiny.to_string(), format!("1/1{}", "0".repeat(40)));
        assert_eq!(tiny.to_f64(), 1e-40);
        assert_eq!(Rational::parse_decimal("1e300").unwrap().to_f64(), 1e300);
        assert_eq!(Rational::parse_decimal("1e1001"), None);
        assert_eq!(Rational::parse_decimal(&"9".repeat(101)), None);
        assert!(Rational::parse_decimal(&"9".repeat(100)).is_some());
    }

    #[test]
    fn arithmetic_never_overflows() {
        let h = Rational::new(1, 2).unwrap();
        let t = Rational::new(1, 3).unwrap();
        assert_eq!(h.add(&t), Rational::new(5, 6).unwrap());
        assert_eq!(h.mul(&t), Rational::new(1, 6).unwrap());
        let big = Rational::int(i128::MAX).mul(&Rational::int(i128::MAX));
        assert_eq!(
            big.mul(&Rational::int(2)).to_f64(),
            2.0 * (i128::MAX as f64).powi(2)
        );
        assert_eq!(big.to_i64(), None);
        assert_eq!(Rational::int(-7).to_i64_pair(), Some((-7, 1)));
    }

    #[test]
    fn large_parts_split_into_base_2_32_limbs() {
        let x = Rational::parse_decimal("1e20").unwrap().negated();
        let (n, d) = x.abs_parts_base_2_32();
        let value: u128 = n
            .iter()
            .rev()
            .fold(0, |acc, &l| (acc << 32) | u128::from(l));
        assert_eq!(value, 100_000_000_000_000_000_000);
        assert_eq!(d.first(), Some(&1));
    }

    #[test]
    fn round_trips_through_serde() {
        let x = Rational::parse_decimal("1.5e-30").unwrap().negated();
        let json = serde_json::to_string(&x).unwrap();
        assert_eq!(serde_json::from_str::<Rational>(&json).unwrap(), x);
    }
}
