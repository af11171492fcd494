//! An `integrate` step checked without the engine: nested Gauss–Legendre quadrature of the
//! integrand as written, each range's limits evaluated at the outer variables, at the scene's
//! values.

use super::step_check::{CheckError, StepCheck, at};
use crate::cas::Expr;
use crate::numeric::quadrature::gauss_legendre;
use std::collections::BTreeMap;

/// Points per range: exact for polynomials of degree up to 47 in each variable; on a trig
/// polynomial over its period the error falls like a power of the degree over 48, far below
/// [`QUADRATURE_AGREEMENT`] for the degrees a body's integrand has.
const POINTS: usize = 24;
/// Rounding over 24³ weighted terms of size about 1 stays near 1e-13; a wrong factor or limit
/// is off by order one.
pub(crate) const QUADRATURE_AGREEMENT: f64 = 1e-10;

/// The exact integral at the scene's values against the quadrature of the integrand.
pub(crate) fn quadrature_check(
    values: &BTreeMap<String, f64>,
    f: &Expr,
    over: &[(String, Expr, Expr)],
    exact: &Expr,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.method = format!(
        "the integrand as written by nested Gauss-Legendre quadrature ({POINTS} points a range, \
         limits at the outer variables) at the scene's values"
    );
    check.tolerance = QUADRATURE_AGREEMENT;
    let rule = gauss_legendre(POINTS);
    let numeric = nested(f, over, values.clone(), &rule, &mut check.evaluations)?;
    let x = at(exact, values)?;
    check.error = (x - numeric).abs() / x.abs().max(numeric.abs()).max(f64::MIN_POSITIVE);
    Ok(())
}

/// The integral at `values` by the same nested rule, with its evaluations: the numeric value
/// of an `integrate` step where a problem's answer uses it.
pub(crate) fn quadrature(
    values: &BTreeMap<String, f64>,
    f: &Expr,
    over: &[(String, Expr, Expr)],
) -> Result<(f64, u64), CheckError> {
    let mut evaluations = 0;
    let x = nested(
        f,
        over,
        values.clone(),
        &gauss_legendre(POINTS),
        &mut evaluations,
    )?;
    Ok((x, evaluations))
}

/// ∫ over the outermost remaining range of the integral over the others.
fn nested(
    f: &Expr,
    over: &[(String, Expr, Expr)],
    point: BTreeMap<String, f64>,
    rule: &[(f64, f64)],
    evaluations: &mut u64,
) -> Result<f64, CheckError> {
    let Some(((var, lo, hi), inner)) = over.split_last() else {
        *evaluations += 1;
        return at(f, &point);
    };
    let (a, b) = (at(lo, &point)?, at(hi, &point)?);
    let (mid, half) = ((a + b) / 2.0, (b - a) / 2.0);
    let mut sum = 0.0;
    for (x, w) in rule {
        let mut p = point.clone();
        p.insert(var.clone(), mid + half * x);
        sum += w * nested(f, inner, p, rule, evaluations)?;
    }
    Ok(sum * half)
}
