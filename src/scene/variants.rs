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

impl Requirement {
    /// Compared exactly when both sides are rational, in f64 otherwise (π, roots).
    pub fn holds(&self, values: &BTreeMap<String, Expr>) -> bool {
        let exact = |e: &Expr| {
            e.eval_rational(&|s| match values.get(s) {
                Some(Expr::Num(r)) => Some(r.clone()),
                _ => None,
            })
        };
        let order = match (exact(&self.lhs), exact(&self.rhs)) {
            (Some(a), Some(b)) => a.compare(&b),
            _ => {
                let env = |s: &str| values.get(s).and_then(|e| e.eval(&|_| None).ok());
                match (self.lhs.eval(&env), self.rhs.eval(&env)) {
                    (Ok(a), Ok(b)) => match a.partial_cmp(&b) {
                        Some(o) => o,
                        None => return false,
                    },
                    _ => return false,
                }
            }
        };
        self.op.holds(order)
    }
}

/// Fewer combinations meet the requirements than variants were asked for.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Shortfall {
    pub met: usize,
    pub combinations: usize,
}

/// `count` distinct variants: each varying symbol takes one of its `options` (in the order
/// given), the others their `fixed` value. Combinations are visited in a seeded random order
/// (a Fisher–Yates shuffle drawn as it goes) and kept when they meet every requirement.
pub fn draw(
    options: &[(String, Vec<Expr>)],
    fixed: &BTreeMap<String, Expr>,
    require: &[Requirement],
    count: usize,
    seed: u64,
) -> Result<Vec<Variant>, Shortfall> {
    let combinations: usize = options.iter().map(|(_, o)| o.len()).product();
    let mut order: Vec<u32> = (0..combinations as u32).collect();
    let mut rng = Rng::new(seed);
    let mut out = Vec::with_capacity(count);
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
        if require.iter().all(|r| r.holds(&values)) {
            out.push(Variant {
                number: out.len() + 1,
                values,
            });
        }
    }
    if out.len() < count {
        return Err(Shortfall {
            met: out.len(),
            combinations,
        });
    }
    Ok(out)
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
            Shortfall {
                met: 15,
                combinations: 36
            }
        );
    }

    #[test]
    fn a_requirement_with_pi_is_compared_in_floating_point() {
        let mut values = BTreeMap::new();
        values.insert("t".to_string(), parse("pi/3").unwrap().expr);
        assert!(requirement("t", Comparison::Greater, "1").holds(&values));
        assert!(!requirement("t", Comparison::Greater, "11/10").holds(&values));
    }
}
