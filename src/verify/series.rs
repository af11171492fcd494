//! A `series` step checked without the engine: the expression as written against its series
//! at four steps h, h/2, h/4, h/8 from the point; the remainder must shrink like h^(order+1).

use super::step_check::{CheckError, StepCheck, at};
use crate::base::format::text_number;
use crate::cas::Expr;
use crate::scene::Scene;

/// The first step from the point, relative to its size (at least 1): small enough to stay
/// inside a root's radius of convergence, as √(I₃² − 4bε²) needs.
const FIRST_STEP: f64 = 1e-2;
/// The remainder's observed order may fall this far short of order + 1: over a halving of h
/// the next-but-one term changes the ratio by O(h).
const ORDER_SLACK: f64 = 0.3;
/// A remainder below this, relative to the expression, is rounding: the series is exact there.
const ROUNDING: f64 = 1e-12;

/// The remainder of `series` against `f` at four steps from x0, and its observed order.
pub(crate) fn remainder_check(
    scene: &Scene,
    f: &Expr,
    series: &Expr,
    var: &str,
    x0: f64,
    order: u32,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.tolerance = ORDER_SLACK;
    let mut point = scene.values.clone();
    let mut remainders = Vec::new();
    let first = FIRST_STEP * x0.abs().max(1.0);
    for k in 0..4 {
        let h = first / f64::from(1 << k);
        point.insert(var.to_string(), x0 + h);
        let (exact, approx) = (at(f, &point)?, at(series, &point)?);
        check.evaluations += 2;
        if !exact.is_finite() || !approx.is_finite() {
            return Err(CheckError::NotFinite { at: x0 + h });
        }
        remainders.push(((exact - approx).abs(), exact.abs()));
    }
    let (r1, f1) = remainders[2];
    let (r2, f2) = remainders[3];
    let observed = if r2 <= ROUNDING * f2.max(1e-300) || r1 <= ROUNDING * f1.max(1e-300) {
        f64::INFINITY
    } else {
        (r1 / r2).log2()
    };
    check.error = (f64::from(order + 1) - observed).max(0.0);
    check.method = format!(
        "the expression as written against the series at {var} = x0 + h for h = {} to \
         {}: the remainder falls {} (order + 1 = {} wanted, {ORDER_SLACK} short allowed)",
        text_number(&format!("{first:e}")),
        text_number(&format!("{:e}", first / 8.0)),
        if observed.is_finite() {
            format!("like h^{observed:.2}")
        } else {
            "to rounding: the series is exact there".to_string()
        },
        order + 1
    );
    Ok(())
}
