//! Where a `substitute` step puts in a value at which its expression has no value: a divisor
//! that vanishes there, with the rest of its product (0/0, whose limit a `series` step takes)
//! or without it (a pole), and the error that names it. Found before the engine, which would
//! fold sin(0)/0 to 0.

use super::DeriveError;
use crate::cas::{self, Expr};
use std::collections::BTreeMap;

/// A divisor of `f` that the replacements `values` make 0.
#[derive(Debug)]
pub struct VanishingDivisor {
    pub divisor: Expr,
    /// The rest of the product it divides vanishes too: 0/0.
    pub zero_over_zero: bool,
}

/// The first divisor of `f` (a negative power's base) that is 0 once `values` are put in.
pub fn vanishing_divisor(
    f: &Expr,
    values: &BTreeMap<String, Expr>,
) -> Result<Option<VanishingDivisor>, DeriveError> {
    let put = |e: &Expr| e.substitute(&|s| values.get(s).cloned());
    let mut products: Vec<Vec<Expr>> = Vec::new();
    f.walk(&mut |x| match x {
        Expr::Mul(v) => products.push(v.clone()),
        Expr::Pow(..) => products.push(vec![x.clone()]),
        _ => {}
    });
    for factors in products {
        for (k, factor) in factors.iter().enumerate() {
            let Expr::Pow(base, exponent) = factor else {
                continue;
            };
            if !matches!(exponent.as_ref(), Expr::Num(r) if r.is_negative()) {
                continue;
            }
            // Screened at a point first, so that a divisor which is not 0 costs no engine call.
            let divisor = put(base);
            if !near_zero_somewhere(&divisor) || !cas::simplify(&divisor)?.is_zero() {
                continue;
            }
            let rest: Vec<Expr> = factors
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != k)
                .map(|(_, e)| put(e))
                .collect();
            let zero_over_zero = !rest.is_empty() && cas::simplify(&Expr::mul(rest))?.is_zero();
            return Ok(Some(VanishingDivisor {
                divisor: (**base).clone(),
                zero_over_zero,
            }));
        }
    }
    Ok(None)
}

/// Whether `e` is within 1e-9 of 0 at a fixed point (each symbol 0.4 + k/7 in alphabetical
/// order, π itself), or cannot be evaluated there: only then is the engine asked.
fn near_zero_somewhere(e: &Expr) -> bool {
    let names = e.symbols();
    let value = e.eval(&|s| {
        names
            .iter()
            .position(|n| n == s)
            .filter(|_| s != "pi")
            .map(|k| 0.4 + k as f64 / 7.0)
    });
    !matches!(value, Ok(v) if v.abs() > 1e-9)
}

/// A substitution that puts in a value where `f` has none: 0/0, with the `series` step that
/// takes its limit, or a pole.
pub fn refuse_no_value(
    f: &Expr,
    of: &Expr,
    set: &BTreeMap<String, Expr>,
    values: &BTreeMap<String, Expr>,
) -> Result<(), DeriveError> {
    let Some(found) = vanishing_divisor(f, values)? else {
        return Ok(());
    };
    let at = set
        .iter()
        .map(|(name, e)| format!("{name} = {}", e.to_text()))
        .collect::<Vec<_>>()
        .join(", ");
    if set.is_empty() {
        return Err(DeriveError::NotDerivable(format!(
            "the divisor {} of `{}` is 0 as written, so the expression has no value (0/0 or a \
             pole): write the value or limit you mean",
            found.divisor.to_text(),
            of.to_text()
        )));
    }
    Err(DeriveError::NotDerivable(if found.zero_over_zero {
        let (name, e) = set.iter().next().expect("a substitution names a value");
        format!(
            "at {at}, `{}` is 0/0: its divisor {} and the rest of its product both vanish, so \
             it has no value there, only a limit; take the limit with a `series` step, \
             `series = \"{}\"`, `about = {{ {name} = \"{}\" }}`, `order = 0`",
            of.to_text(),
            found.divisor.to_text(),
            of.to_text(),
            e.to_text()
        )
    } else {
        format!(
            "at {at}, the divisor {} of `{}` vanishes and the rest of its product does not: \
             the expression has a pole there, with no finite value",
            found.divisor.to_text(),
            of.to_text()
        )
    }))
}
