//! A problem's variants: distinct choices of the varying symbols' values, drawn from their
//! ranges by a seeded shuffle, each meeting every `require`. The same scene and seed give the
//! same variants on every machine.

use super::types::Variant;
use crate::base::rng::Rng;
use crate::cas::{Expr, Rational};
use std::cmp::Ordering;
use std::collections::BTreeMap;

/// The most variants a problem may have, and the most combinations of values its ranges may
/// span (each tried at most once, so an impossible `require` is found in bounded time).
pub const MAX_VARIANTS: usize = 10_000;
pub const MAX_COMBINATIONS: usize = 1_000_000;

/// `lhs op rhs`, such as `a < b`.
#[derive(Debug, Clone)]
pub struct Requirement {
    pub text: String,
    pub lhs: Expr,
    pub op: Comparison,
    pub rhs: Expr,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Comparison {
    Less,
    LessOrEqual,
    Greater,
    GreaterOrEqual,
    Equal,
    NotEqual,
}

impl Comparison {
    /// The operators, two-character ones first so that `<=` is not read as `<`.
    pub const ALL: [(&'static str, Comparison); 6] = [
        ("<=", Comparison::LessOrEqual),
        (">=", Comparison::GreaterOrEqual),
        ("==", Comparison::Equal),
        ("!=", Comparison::NotEqual),
        ("<", Comparison::Less),
        (">", Comparison::Greater),
    ];

    fn holds(self, o: Ordering) -> bool {
        match self {
            Comparison::Less => o.is_lt(),
            Comparison::LessOrEqual => o.is_le(),
            Comparison::Greater => o.is_gt(),
            Comparison::GreaterOrEqual => o.is_ge(),
            Comparison::Equal => o.is_eq(),
            Comparison::NotEqual => o.is_ne(),
        }
    }
}

/// Why a requirement could not be decided for some values.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Undecided {
    #[error("it cannot be evaluated there ({0})")]
    Unevaluable(String),
    #[error(
        "its two sides agree to double precision there, and the engine cannot show them \
         equal or different"
    )]
    TooClose,
}

/// Sides closer than this, relative to their size, are compared exactly by the engine: f64
/// cannot tell `sqrt(2)*sqrt(2)` from 2.
const NEAR: f64 = 1e-9;

impl Requirement {
    /// Compared exactly: as rationals when both sides are, else in f64 when the sides are far
    /// apart, else by the engine, which simplifies their difference. A side that is infinite
    /// or undefined (`1/(a-a)`) is never met: it is refused.
    pub fn holds(&self, values: &BTreeMap<String, Expr>) -> Result<bool, Undecided> {
        let exact = |e: &Expr| {
            e.eval_rational(&|s| match values.get(s) {
                Some(Expr::Num(r)) => Some(r.clone()),
                _ => None,
            })
        };
        if let (Some(a), Some(b)) = (exact(&self.lhs), exact(&self.rhs)) {
            return Ok(self.op.holds(a.compare(&b)));
        }
        let env = |s: &str| values.get(s).and_then(|e| e.eval(&|_| None).ok());
        let side = |e: &Expr| match e.eval(&env) {
            Ok(x) if x.is_finite() => Ok(x),
            Ok(x) => Err(Undecided::Unevaluable(format!("a side is {x}"))),
            Err(m) => Err(Undecided::Unevaluable(m.to_string())),
        };
        let (a, b) = (side(&self.lhs)?, side(&self.rhs)?);
        let scale = a.abs().max(b.abs()).max(f64::MIN_POSITIVE);
        if (a - b).abs() > NEAR * scale {
            return Ok(self.op.holds(a.total_cmp(&b)));
        }
        let difference = Expr::Add(vec![
            self.lhs.clone(),
            Expr::Mul(vec![Expr::int(-1), self.rhs.clone()]),
        ])
        .substitute(&|s| values.get(s).cloned());
        match crate::cas::is_zero_all(vec![difference]) {
            Ok(z) if z == [true] => Ok(self.op.holds(Ordering::Equal)),
            _ => Err(Undecided::TooClose),
        }
    }
}

/// Why the variants could not be drawn.
#[derive(Debug, Clone, PartialEq)]
pub enum DrawError {
    /// Fewer combinations meet the requirements than variants were asked for.
    Short(Shortfall),
    /// Requirement `index` could not be decided at `values`.
    Undecided {
        index: usize,
        values: BTreeMap<String, Expr>,
        why: Undecided,
    },
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Shortfall {
    pub met: usize,
    pub combinations: usize,
    /// Whether one combination that met them was the scene's own point, and left out.
    pub public_left_out: bool,
}

/// `count` distinct variants: each varying symbol takes one of its `options` (in the order
/// given), the others their `fixed` value. Combinations are visited in a seeded random order
/// (a Fisher–Yates shuffle drawn as it goes) and kept when they meet every requirement and
/// are not the scene's own point: `fixed` holds every symbol's `[numeric]` value, at which
/// the scene's public page shows the answers.
pub fn draw(
    options: &[(String, Vec<Expr>)],
    fixed: &BTreeMap<String, Expr>,
    require: &[Requirement],
    count: usize,
    seed: u64,
) -> Result<Vec<Variant>, DrawError> {
    let combinations: usize = options.iter().map(|(_, o)| o.len()).product();
    let mut order: Vec<u32> = (0..combinations as u32).collect();
    let mut rng = Rng::new(seed);
    let mut out = Vec::with_capacity(count);
    let mut public_left_out = false;
    for i in 0..combinations {
        if out.len() == count {
            break;
        }
        let j =
            i + ((rng.uniform() * (combinations - i) as f64) as usize).min(combinations - i - 1);
        order.swap(i, j);
        let mut index = order[i] as usize;
        let mut values = fixed.clone();
        for (name, opts) in options {
            values.insert(name.clone(), opts[index % opts.len()].clone());
            index /= opts.len();
        }
        let mut met = true;
        for (index, r) in require.iter().enumerate() {
            match r.holds(&values) {
                Ok(true) => {}
                Ok(false) => {
                    met = false;
                    break;
                }
                Err(why) => return Err(DrawError::Undecided { index, values, why }),
            }
        }
        if !met {
            continue;
        }
        if is_public(options, &values, fixed) {
            public_left_out = true;
        } else {
            out.push(Variant {
                decimal: Default::default(),
                number: out.len() + 1,
                values,
            });
        }
    }
    if out.len() < count {
        return Err(DrawError::Short(Shortfall {
            met: out.len(),
            combinations,
            public_left_out,
        }));
    }
    Ok(out)
}

/// Whether every varying symbol has its `[numeric]` value, as the numbers the scene's page
/// is computed at (`pi/3` against 1.0471975511965976).
fn is_public(
    options: &[(String, Vec<Expr>)],
    values: &BTreeMap<String, Expr>,
    fixed: &BTreeMap<String, Expr>,
) -> bool {
    let number = |m: &BTreeMap<String, Expr>, name: &str| m.get(name)?.eval(&|_| None).ok();
    options.iter().all(
        |(name, _)| match (number(values, name), number(fixed, name)) {
            (Some(a), Some(b)) => (a - b).abs() <= 1e-12 * a.abs().max(b.abs()),
            _ => false,
        },
    )
}

/// `from`, `from + step`, … up to `to` inclusive, or `None` when that is more than `limit`
/// values (the count is found before any is made).
pub fn range(from: &Rational, to: &Rational, step: &Rational, limit: usize) -> Option<Vec<Expr>> {
    let span = to.add(&from.negated()).mul(&step.recip()?);
    if span.is_negative() {
        return Some(Vec::new());
    }
    let steps = span
        .floor_to_u64()
        .filter(|n| (*n as u128) < limit as u128)?;
    Some(
        (0..=steps)
            .map(|k| Expr::Num(from.add(&step.mul(&Rational::int(k as i128)))))
            .collect(),
    )
}

/// `e` as a formula: a terminating decimal (`0.3`, `-2.25`) when `decimal` and it has one.
pub fn shown_value(e: &Expr, decimal: bool) -> crate::notation::Formula {
    if decimal
        && let Expr::Num(r) = e
        && let Some(text) = terminating_decimal(r)
    {
        return crate::notation::Formula::Number(text);
    }
    crate::notation::Formula::Expr(e.clone())
}

/// A rational's decimal expansion when it ends within 30 digits: 3/8 is 0.375, 1/3 has none.
pub fn terminating_decimal(r: &crate::cas::Rational) -> Option<String> {
    let (n, d) = r.to_i64_pair()?;
    let (mut twos, mut fives, mut rest) = (0u32, 0u32, d);
    while rest % 2 == 0 {
        rest /= 2;
        twos += 1;
    }
    while rest % 5 == 0 {
        rest /= 5;
        fives += 1;
    }
    let places = twos.max(fives);
    if rest != 1 || places > 30 {
        return None;
    }
    // n/d = n·(10^places/d) / 10^places.
    let scaled = (n as i128) * (10i128.checked_pow(places)? / d as i128);
    let sign = if scaled < 0 { "-" } else { "" };
    let digits = scaled.unsigned_abs().to_string();
    if places == 0 {
        return Some(format!("{sign}{digits}"));
    }
    let padded = format!("{digits:0>width$}", width = places as usize + 1);
    let (whole, frac) = padded.split_at(padded.len() - places as usize);
    Some(format!("{sign}{whole}.{frac}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cas::parse;

    fn r(s: &str) -> Rational {
        match parse(s).unwrap().expr {
            Expr::Num(r) => r,
            Expr::Mul(v) => match v.as_slice() {
                [Expr::Num(a), Expr::Pow(b, e)] if **e == Expr::int(-1) => match b.as_ref() {
                    Expr::Num(b) => a.mul(&b.recip().unwrap()),
                    _ => panic!(),
                },
                _ => panic!("{s}"),
            },
            other => panic!("{other:?}"),
        }
    }

    fn requirement(lhs: &str, op: Comparison, rhs: &str) -> Requirement {
        Requirement {
            text: String::new(),
            lhs: parse(lhs).unwrap().expr,
            op,
            rhs: parse(rhs).unwrap().expr,
        }
    }

    #[test]
    fn a_range_includes_both_ends_and_steps_exactly() {
        let v = range(&r("1"), &r("4"), &r("1/2"), 100).unwrap();
        let text: Vec<String> = v.iter().map(|e| e.to_text()).collect();
        assert_eq!(text, ["1", "3/2", "2", "5/2", "3", "7/2", "4"]);
        assert!(range(&r("0"), &r("1"), &r("1/1000000"), 1000).is_none());
        assert!(range(&r("2"), &r("1"), &r("1"), 10).unwrap().is_empty());
    }

    #[test]
    fn variants_are_distinct_meet_the_requirements_and_repeat_with_the_seed() {
        let opts = |n: i128| (1..=n).map(Expr::int).collect::<Vec<_>>();
        let options = vec![("a".to_string(), opts(6)), ("b".to_string(), opts(6))];
        let require = [requirement("a", Comparison::Less, "b")];
        let draw_with = |seed| draw(&options, &BTreeMap::new(), &require, 15, seed).unwrap();
        let v = draw_with(7);
        assert_eq!(v.len(), 15);
        for x in &v {
            let n = x.numbers();
            assert!(n["a"] < n["b"], "{x:?}");
        }
        let mut seen: Vec<_> = v.iter().map(|x| x.values.clone()).collect();
        seen.sort_by_key(|m| format!("{m:?}"));
        seen.dedup();
        assert_eq!(seen.len(), 15, "all 15 pairs a < b of 1..6, each once");
        assert_eq!(v, draw_with(7));
        assert_ne!(v, draw_with(8));
        // One more than the 15 pairs with a < b cannot be drawn.
        let short = draw(&options, &BTreeMap::new(), &require, 16, 7).unwrap_err();
        assert_eq!(
            short,
            DrawError::Short(Shortfall {
                met: 15,
                combinations: 36,
                public_left_out: false,
            })
        );
    }

    #[test]
    fn a_requirement_with_pi_is_compared_in_floating_point() {
        let mut values = BTreeMap::new();
        values.insert("t".to_string(), parse("pi/3").unwrap().expr);
        assert_eq!(
            requirement("t", Comparison::Greater, "1").holds(&values),
            Ok(true)
        );
        assert_eq!(
            requirement("t", Comparison::Greater, "11/10").holds(&values),
            Ok(false)
        );
    }

    #[test]
    fn a_requirement_is_decided_exactly_or_refused() {
        let values = BTreeMap::from([("a".to_string(), Expr::int(2))]);
        // f64 has sqrt(2)*sqrt(2) = 2.0000000000000004: the engine decides.
        assert_eq!(
            requirement("sqrt(a)*sqrt(a)", Comparison::Equal, "2").holds(&values),
            Ok(true)
        );
        assert_eq!(
            requirement("sqrt(a)*sqrt(a)", Comparison::Greater, "2").holds(&values),
            Ok(false)
        );
        assert_eq!(
            requirement("sqrt(a)*sqrt(a)", Comparison::NotEqual, "a").holds(&values),
            Ok(false)
        );
        // 1/(a-a) is infinite in f64: refused, never met.
        assert!(matches!(
            requirement("1/(a-a)", Comparison::Greater, "0").holds(&values),
            Err(Undecided::Unevaluable(_))
        ));
    }

    #[test]
    fn the_scenes_own_numbers_are_never_a_variant() {
        // The scene's page shows the answers at its [numeric] values: a variant there would
        // hand a student their answer. Its value, 3/2, is written 1.5 and compared as a number.
        let options = vec![(
            "a".to_string(),
            (1..=4)
                .map(|n| parse(&format!("{n}/2")).unwrap().expr)
                .collect(),
        )];
        let fixed = BTreeMap::from([("a".to_string(), parse("1.5").unwrap().expr)]);
        let v = draw(&options, &fixed, &[], 3, 7).unwrap();
        let numbers: Vec<f64> = v.iter().map(|x| x.numbers()["a"]).collect();
        assert!(!numbers.contains(&1.5), "{numbers:?}");
        assert_eq!(numbers.len(), 3);
        let short = draw(&options, &fixed, &[], 4, 7).unwrap_err();
        assert_eq!(
            short,
            DrawError::Short(Shortfall {
                met: 3,
                combinations: 4,
                public_left_out: true,
            })
        );
    }
}
