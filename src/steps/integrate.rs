//! `integrate = "…"`, `over = { x = ["0", "L"] }`: a definite integral, innermost variable first,
//! shown with its limits.
//!
//! - Exact rule: `integral`, the engine's rules for the bodies.
//! - Numeric route: nested Gauss–Legendre quadrature at the scene's values (`quadrature_check`).

use super::check::{CheckError, StepCheck, at};
use super::{Checking, Context, Rule};
use crate::cas::{self, AngleSpan, Expr, Integral};
use crate::derive::DeriveError;
use crate::derive::step_names::{StepResult, expand_names, expand_ranges};
use crate::notation::Formula;
use crate::numeric::quadrature::gauss_legendre;
use crate::scene::operations::Integrate;
use std::collections::BTreeMap;

impl Rule for Integrate {
    /// The integral, and the statement the page shows: the integral with its limits.
    fn derive(&self, cx: Context, shown: &mut Option<Formula>) -> Result<StepResult, DeriveError> {
        let of: &Expr = &self.of;
        let over: &[(String, Expr, Expr)] = &self.over;
        let f = expand_names(cx.scene, cx.d, cx.step, of)?;
        let over = expand_ranges(cx.scene, cx.d, cx.step, over)?;
        let (value, domain) = integral(&f, &over)?;
        *shown = Some(crate::derive::inertia::integral_formula(
            Formula::Expr(Expr::sym(&cx.step.name)),
            &f,
            &domain,
            &value,
        ));
        Ok(StepResult::Expr(value))
    }

    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError> {
        let of: &Expr = &self.of;
        let over: &[(String, Expr, Expr)] = &self.over;
        let StepResult::Expr(exact) = cx.result else {
            return Err(CheckError::NotDerived);
        };
        let f = expand_names(cx.scene, cx.d, cx.step, of)?;
        let over = expand_ranges(cx.scene, cx.d, cx.step, over)?;
        quadrature_check(&cx.scene.values, &f, &over, exact, check)
    }
}

// An `integrate` step checked without the engine: nested Gauss–Legendre quadrature of the
// integrand as written, each range's limits evaluated at the outer variables, at the scene's
// values.

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

// `integrate`: an author's definite integral, exactly, with the engine's rules for the bodies:
// a polynomial in a variable over any range, or a polynomial in the cosine and sine of an angle
// over 0 to 2π, π or π/2.

/// The integral of `f` over the ranges, innermost first, simplified, and the integrals the
/// engine did (for the page).
pub fn integral(
    f: &Expr,
    over: &[(String, Expr, Expr)],
) -> Result<(Expr, Vec<Integral>), DeriveError> {
    let mut integrals = Vec::new();
    for (var, lo, hi) in over {
        let angle = f.symbols().contains(var) && has_trig_of(f, var);
        let span = match cas::pi_multiple(&cas::simplify(hi)?) {
            Some(r) if angle && lo.is_zero() => [
                (AngleSpan::Full, 2, 1),
                (AngleSpan::Half, 1, 1),
                (AngleSpan::Quarter, 1, 2),
            ]
            .into_iter()
            .find(|(_, n, d)| cas::Rational::new(*n, *d) == Some(r.clone()))
            .map(|(s, _, _)| s),
            _ => None,
        };
        integrals.push(match span {
            Some(span) => Integral::Trig {
                var: var.clone(),
                span,
            },
            None if angle => {
                return Err(DeriveError::NotDerivable(format!(
                    "the integrand has sin or cos of `{var}`: integrate it from 0 to 2*pi, pi or \
                     pi/2"
                )));
            }
            None => Integral::Poly {
                var: var.clone(),
                lo: lo.clone(),
                hi: hi.clone(),
            },
        });
    }
    let mut result = cas::integrate_all(vec![f.clone()], integrals.clone())?;
    Ok((cas::simplify(&result.remove(0))?, integrals))
}

/// Whether `e` has sin or cos of an argument that holds `var`.
fn has_trig_of(e: &Expr, var: &str) -> bool {
    match e {
        Expr::Call(name, args) if name == "sin" || name == "cos" => {
            args.iter().any(|a| a.symbols().iter().any(|s| s == var))
        }
        Expr::Call(_, v) | Expr::Add(v) | Expr::Mul(v) | Expr::List(v) => {
            v.iter().any(|x| has_trig_of(x, var))
        }
        Expr::Pow(b, k) => has_trig_of(b, var) || has_trig_of(k, var),
        _ => false,
    }
}
