//! `differentiate = "…"`, `by = "x"` (or `"t"`, along the motion): a partial or a total
//! derivative.
//!
//! - Exact rule: the engine's derivative, simplified; past the engine's budget, the quotient
//!   rule over the factored denominator (`derivative_of_quotient`).
//! - Numeric route: central differences with Richardson extrapolation at random points, along
//!   x or along the motion through the point.

use super::check::{CheckError, H, StepCheck, at, compare_at_points, random_point};
use super::{Checking, Context, Rule};
use crate::base::rng::Rng;
use crate::cas::{self, Expr};
use crate::derive::DeriveError;
use crate::derive::lagrangian::time_derivative;
use crate::derive::step_names::{StepResult, expand_names};
use crate::notation::Formula;
use crate::numeric::random_points::CONFIRMATION_POINTS;
use crate::numeric::random_points::SAMPLE_FROM;
use crate::scene::operations::Differentiate;
use std::collections::BTreeMap;

/// Central differences with Richardson extrapolation err by O(h⁴) in truncation and about
/// ε·|f|/h in rounding; with h = 1e-3 both stay far below this, relative to the derivative.
const DIFFERENCE_AGREEMENT: f64 = 1e-7;

impl Rule for Differentiate {
    fn derive(&self, cx: Context, _: &mut Option<Formula>) -> Result<StepResult, DeriveError> {
        let of: &Expr = &self.of;
        let by: &str = &self.by;
        let f = expand_names(cx.scene, cx.d, cx.step, of).map_err(DeriveError::Step)?;
        let derivative = |f: &Expr| -> Result<Expr, DeriveError> {
            Ok(if by == "t" {
                time_derivative(f, &cx.scene.coordinates)?
            } else {
                f.diff(by)?
            })
        };
        Ok(match cas::simplify(&derivative(&f)?) {
            Ok(r) => StepResult::Expr(r),
            // A rational function's expanded denominator, squared by the quotient rule, is past
            // the budget (an effective potential's second derivative): the quotient rule over the
            // factored denominator, which grows by its factors only.
            Err(cas::CasError {
                reason: cas::CasFailure::Engine(cas::EngineError::OverBudget { .. }),
            }) => StepResult::Expr(derivative_of_quotient(&f, &derivative)?),
            Err(e) => return Err(e.into()),
        })
    }

    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError> {
        let of: &Expr = &self.of;
        let by: &str = &self.by;
        let StepResult::Expr(r) = cx.result else {
            return Err(CheckError::NotDerived);
        };
        let f = expand_names(cx.scene, cx.d, cx.step, of)?;
        check.method = format!(
            "central differences (h = {H}, Richardson-extrapolated) at {CONFIRMATION_POINTS} \
             random points"
        );
        check.tolerance = DIFFERENCE_AGREEMENT;
        let mut rng = Rng::new(cx.seed);
        compare_at_points(|| {
            let mut point = random_point(&[&f, r], &mut rng, cx.scene);
            let mut accel = BTreeMap::new();
            for q in cx.scene.coordinates.keys() {
                for name in [q.clone(), format!("{q}'"), format!("{q}''")] {
                    point
                        .entry(name)
                        .or_insert_with(|| SAMPLE_FROM + rng.uniform());
                }
                accel.insert(q.clone(), SAMPLE_FROM + rng.uniform());
            }
            point.entry("t".into()).or_insert(SAMPLE_FROM);
            // Along x = x0 + s (a partial derivative), or along the motion through the
            // point (d/dt): q + s q' + s² q''/2, q' + s q'', t + s.
            let moved = |s: f64| -> BTreeMap<String, f64> {
                let mut p = point.clone();
                if by == "t" {
                    for q in cx.scene.coordinates.keys() {
                        let (v, a) = (point[&format!("{q}'")], point[&format!("{q}''")]);
                        *p.get_mut(q).expect("set above") += s * v + s * s * a / 2.0;
                        *p.get_mut(&format!("{q}'")).expect("set above") += s * a;
                    }
                    *p.get_mut("t").expect("set above") += s;
                } else {
                    *p.entry(by.to_string()).or_insert(SAMPLE_FROM) += s;
                }
                p
            };
            // A point outside the expression's domain (acos of more than 1) is drawn again.
            let exact = at(r, &point)?;
            if !exact.is_finite() || !at(&f, &point)?.is_finite() {
                return Ok(false);
            }
            let value = |x: f64| at(&f, &moved(x)).ok().filter(|v| v.is_finite());
            let Some((numeric, evaluations)) = richardson(&value) else {
                return Ok(false);
            };
            check.evaluations += evaluations + 1;
            check.error = check
                .error
                .max((exact - numeric).abs() / exact.abs().max(numeric.abs()).max(1.0));
            Ok(true)
        })
    }
}

/// The derivative at 0 of `f(x)` (None where undefined) by central differences with Richardson
/// extrapolation, and the evaluations spent. Near a singularity (acos at 1) the truncation
/// error of h = 1e-3 is large, or a step leaves the domain: h is quartered until two successive
/// estimates agree to the check's tolerance (the coarser of the two is returned: the one a
/// smooth function gets at h = 1e-3), or h reaches 1e-7, where rounding ε/h would pass it.
/// `None` when no step size gives a finite estimate.
fn richardson(f: &dyn Fn(f64) -> Option<f64>) -> Option<(f64, u64)> {
    let central = |h: f64| Some((f(h)? - f(-h)?) / (2.0 * h)).filter(|d| d.is_finite());
    let estimate = |h: f64| Some((4.0 * central(h / 2.0)? - central(h)?) / 3.0);
    // At h = 1e-3 the two central differences already agree to the tolerance for a smooth
    // function: their Richardson extrapolation is then far more accurate still.
    if let (Some(d1), Some(d2)) = (central(H), central(H / 2.0))
        && (d1 - d2).abs() <= DIFFERENCE_AGREEMENT * d1.abs().max(d2.abs()).max(1.0)
    {
        return Some(((4.0 * d2 - d1) / 3.0, 4));
    }
    let mut evaluations = 4;
    let mut h = H;
    let mut last: Option<f64> = None;
    while h >= 1e-7 {
        evaluations += 4;
        let next = estimate(h);
        match (last, next) {
            (Some(a), Some(b))
                if (a - b).abs() <= DIFFERENCE_AGREEMENT * a.abs().max(b.abs()).max(1.0) =>
            {
                return Some((a, evaluations));
            }
            (None, None) => {}
            (_, Some(b)) => last = Some(b),
            (Some(_), None) => return last.map(|a| (a, evaluations)),
        }
        h /= 4.0;
    }
    last.map(|a| (a, evaluations))
}

// The derivative of a rational function with its denominator kept factored: for
// f = N/D with D = c·Π fᵢ^kᵢ, f' = (N' Π fᵢ − N Σ kᵢ fᵢ' Π_{j≠i} fⱼ)/(D Π fᵢ). The quotient
// rule as written squares D, whose expansion an effective potential's second derivative puts
// past the engine's budget (degree 32 for (p_φ − p_ψ cos θ)²/(2(I₁ + Ml²) sin²θ)); this form's
// denominator grows by the factors once.

/// f' by the rule above, simplified; `derivative` is ∂/∂x or d/dt through the coordinates.
pub fn derivative_of_quotient(
    f: &Expr,
    derivative: &dyn Fn(&Expr) -> Result<Expr, DeriveError>,
) -> Result<Expr, DeriveError> {
    let (n, d) = cas::fraction_all(vec![f.clone()])?.remove(0);
    let factored = cas::factor_all(vec![d])?.remove(0);
    let listed = match &factored {
        Expr::Mul(v) => v.clone(),
        other => vec![other.clone()],
    };
    // Each factor that is not a number, with its power.
    let factors: Vec<(Expr, i64)> = listed
        .into_iter()
        .filter_map(|f| match f {
            Expr::Num(_) => None,
            Expr::Pow(b, k) => match k.as_ref() {
                Expr::Num(r) => r.to_i64().map(|k| (*b, k)),
                _ => Some((Expr::Pow(b, k), 1)),
            },
            other => Some((other, 1)),
        })
        .collect();
    let product = |skip: Option<usize>| {
        Expr::mul(
            factors
                .iter()
                .enumerate()
                .filter(|(j, _)| Some(*j) != skip)
                .map(|(_, (b, _))| b.clone())
                .collect(),
        )
    };
    let mut terms = vec![Expr::mul(vec![derivative(&n)?, product(None)])];
    for (i, (b, k)) in factors.iter().enumerate() {
        terms.push(Expr::mul(vec![
            Expr::int(-i128::from(*k)),
            n.clone(),
            derivative(b)?,
            product(Some(i)),
        ]));
    }
    let numerator = cas::simplify(&Expr::add(terms))?;
    Ok(cas::simplify(&Expr::over(
        numerator,
        Expr::mul(vec![factored, product(None)]),
    ))?)
}
