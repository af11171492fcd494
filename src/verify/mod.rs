//! Symbolic vs numeric vs the notes' claims -> verdicts.
//!
//! A claim agrees when every entry of (derived − notes) simplifies to zero. Each verdict is then
//! confirmed at random parameter points in f64; if the two routes ever disagree, that is reported
//! as a problem rather than silently trusted.

use crate::base::float::max_relative_error;
use crate::cas::EvalError;
use crate::cas::Expr;
use crate::derive::Derivation;
use crate::derive::algebra::Value;
use crate::model::catalogue::Stage;
use crate::model::catalogue::quantity;
use crate::model::prose::Prose;
use crate::model::value::vector_at;
use crate::numeric::NumericReport;
use crate::numeric::eigen::Eigenspace;
use crate::numeric::quadrature::{Method, QuadratureRun};
use crate::scene::{ClaimRole, Scene, Verdict};

/// Exact and numeric values of the same quantity must agree this closely (relative), the
/// accuracy the foundation issue asks of exact quadrature rules.
pub const EXACT_VS_NUMERIC: f64 = 1e-14;

/// [`EXACT_VS_NUMERIC`], grown with the terms the numeric route adds up: n products summed in
/// f64 may be off by about 4nε of the largest entry (each term's rounding and the sum's), so
/// 10,000 point masses get 8.9e-12. Up to 11 terms (every shipped scene) it stays 1e-14.
pub fn exact_vs_numeric(scene: &Scene) -> f64 {
    let terms: usize = scene
        .bodies
        .iter()
        .map(|b| match &b.shape {
            crate::scene::Shape::Points(points) => points.len(),
            _ => 1,
        })
        .sum();
    EXACT_VS_NUMERIC.max(4.0 * terms as f64 * f64::EPSILON)
}
/// A Monte Carlo estimate further than this many standard errors from the exact value fails.
pub const MONTE_CARLO_SIGMAS: f64 = 5.0;
pub(crate) use crate::numeric::random_points::CONFIRMATION_POINTS;

#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct ClaimResult {
    pub eq: String,
    pub statement: String,
    /// The claim's two sides as the scene writes them (its `quantity` and the notes' `value`),
    /// and the derived value of its `quantity`: trees, printed only by an output's printer.
    pub quantity: Option<Expr>,
    pub notes: Option<Expr>,
    pub derived: Option<Value>,
    pub verdict: Verdict,
    /// The scene's reviewed verdict; `None` when none is recorded yet.
    pub expected: Option<Verdict>,
    /// For a disagreement: each entry that differs, with both sides and their difference.
    pub differences: Vec<Prose>,
    /// A problem with the check itself (the two routes disagree, a type error), if any.
    pub problem: Option<String>,
    /// For a number the notes give roughly: the derived value, rounded as the notes round.
    pub precision: Option<String>,
    #[serde(default)]
    pub role: ClaimRole,
    pub line: usize,
    /// The author's step whose `gives` this is (its index), or `None` for a `[[claim]]`.
    #[serde(default)]
    pub step: Option<usize>,
    /// Why its two sides differ in dimension, where they do (a scene with units).
    #[serde(default)]
    pub dimension: Option<String>,
    /// The symbols whose positivity the agreement rests on (√(g²) = g, (x y)^(1/3) = ∛x ∛y),
    /// where the engine's test alone did not decide it; said beside the verdict.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub positive: Vec<String>,
    /// The agreement holds where both sides are real: decided by their squares, both sides
    /// being never negative (`squares.rs`); said beside the verdict.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub where_real: bool,
    /// The symbol the author gives its quantity, printed as its left side: its tree (stored
    /// as its LaTeX), or a symbol's as mechbook sets it (`T` for a `solve` step's unknown).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tex: Option<crate::notation::Tex>,
    /// The derived side in the form a textbook prints, where a box shows it and it differs
    /// from `derived` (`claim_form.rs`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shown: Option<Expr>,
}

impl ClaimResult {
    pub fn passed(&self) -> bool {
        self.expected == Some(self.verdict) && self.problem.is_none()
    }

    /// A claim on a sign (`sign(…)` is 1, −1, or 0 where it takes both): the notes' side and the
    /// derived one in words, as a reader says them, where ±1 would mean nothing.
    pub fn sign_words(&self) -> Option<(&'static str, &'static str)> {
        let (Some(Expr::Call(f, _)), Some(notes), Some(Value::Scalar(derived))) =
            (&self.quantity, &self.notes, &self.derived)
        else {
            return None;
        };
        let words = |e: &Expr| {
            let Expr::Num(r) = e else { return None };
            [
                (1, "positive for every choice"),
                (-1, "negative for every choice"),
                (0, "positive for some choices and negative for others"),
            ]
            .into_iter()
            .find(|(k, _)| *r == crate::cas::Rational::int(*k))
            .map(|(_, w)| w)
        };
        (f == "sign").then_some((words(notes)?, words(derived)?))
    }
}

#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct RegressionResult {
    pub quantity: String,
    /// The scene's `[expect]` value; `None` when the scene records no results yet.
    pub recorded: Option<Expr>,
    /// The line of its `[expect]` key, or of the scene's id when there is none.
    pub line: usize,
    /// `None` when the scene's plan did not derive it.
    pub derived: Option<Value>,
    pub unchanged: bool,
}

/// An exact quantity evaluated at the scene's values against the same quantity from numerics.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct QuantityCheck {
    pub name: String,
    pub exact: Vec<f64>,
    pub numeric: Vec<f64>,
    pub error: f64,
    pub passed: bool,
}

#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct EigenCheck {
    /// Exact principal moments at the scene's values, with multiplicities, ascending.
    pub exact: Vec<(f64, u32)>,
    pub numeric: Vec<Eigenspace>,
    pub value_error: f64,
    /// 1 − |cos| of the angle between exact and numeric axes (or plane normals), the largest.
    pub axis_error: f64,
    pub passed: bool,
}

#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub struct Verification {
    pub claims: Vec<ClaimResult>,
    pub regressions: Vec<RegressionResult>,
    pub quantities: Vec<QuantityCheck>,
    pub eigen: Option<EigenCheck>,
    #[serde(default)]
    pub principal: Option<PrincipalValues>,
    /// For each quadrature run: did it stay within its error law?
    pub within_law: Vec<bool>,
    /// A problem's variants, each answer exact against its numeric route.
    #[serde(default)]
    pub variants: Vec<variants::VariantCheck>,
    /// Each of the author's steps against its numeric route.
    #[serde(default)]
    pub steps: Vec<StepCheck>,
    /// Each built-in step printed in another form than derived, against its exact result.
    #[serde(default)]
    pub printed: Vec<StepCheck>,
    /// A problem's variants against those `check --bless` pinned.
    #[serde(default)]
    pub pin: Option<variants::Pin>,
    /// Each author's step's results against those `check --bless` recorded.
    #[serde(default)]
    pub step_records: Vec<StepRecord>,
}

impl Verification {
    /// The claims that received verdict `v`.
    pub fn count(&self, v: Verdict) -> usize {
        self.claims.iter().filter(|c| c.verdict == v).count()
    }

    /// The notes' errata: the notes' own claims the derivation disagrees with (a common
    /// mistake written down on purpose is not one).
    pub fn errata(&self) -> impl Iterator<Item = &ClaimResult> {
        self.claims
            .iter()
            .filter(|c| c.verdict == Verdict::Disagrees && c.role == ClaimRole::Notes)
    }

    pub fn passed(&self) -> bool {
        self.step_records.iter().all(StepRecord::unchanged) && self.passed_but_for_new_steps()
    }

    /// As [`Verification::passed`], except that a step not yet recorded passes: what `derive`
    /// asks of a derivation still being written (`check` asks for the record).
    pub fn passed_but_for_new_steps(&self) -> bool {
        self.regressions.iter().all(|r| r.unchanged)
            && self
                .step_records
                .iter()
                .all(|s| s.unchanged() || s.recorded.is_none())
            && self.pin.as_ref().is_none_or(variants::Pin::unchanged)
            && self.verified()
    }

    /// Whether every check of the derivation passed, leaving out the recorded results (which
    /// a scene without `[expect]` has not recorded yet).
    pub fn verified(&self) -> bool {
        self.claims.iter().all(ClaimResult::passed)
            && self.quantities.iter().all(|q| q.passed)
            && self.eigen.as_ref().is_none_or(|e| e.passed)
            && self
                .principal
                .as_ref()
                .is_none_or(|p| p.error <= PRINCIPAL_AGREEMENT)
            && self.within_law.iter().all(|w| *w)
            && self.variants.iter().all(variants::VariantCheck::passed)
            && self.steps.iter().all(StepCheck::passed)
            && self.printed.iter().all(StepCheck::passed)
    }
}

/// Whether a quadrature run stayed within its law.
pub fn within_law(run: &QuadratureRun) -> bool {
    match run.method {
        Method::MonteCarlo => run.error <= MONTE_CARLO_SIGMAS * run.predicted_error,
        // The law is exact for these polynomial integrands, so only round-off may separate them.
        _ => run.error <= run.predicted_error + 16.0 * f64::EPSILON,
    }
}

/// Every exact quantity that follows from the tensor, against the same from the numeric tensor.
pub fn check_quantities(
    scene: &Scene,
    d: &Derivation,
    numeric: &NumericReport,
) -> Result<Vec<QuantityCheck>, EvalError> {
    let vals = &scene.values;
    let t = numeric.tensor;
    let vec_at = |v: &[Expr; 3]| vector_at(v, vals);
    let mut numeric_of: Vec<(&str, Vec<f64>)> = vec![(
        quantity::INERTIA_TENSOR,
        t.transpose().iter().copied().collect(),
    )];
    let mass = match &d.quantities.get(quantity::MASS) {
        Some(m) => m.numbers_at(vals)?[0],
        None => 0.0,
    };
    if let Some(w) = &scene.omega {
        let w = vec_at(w)?;
        numeric_of.push((
            quantity::ANGULAR_MOMENTUM,
            (t * w).iter().copied().collect(),
        ));
        numeric_of.push((quantity::KINETIC_ENERGY, vec![0.5 * w.dot(&(t * w))]));
    }
    if let Some(n) = &scene.axis {
        let n = vec_at(n)?;
        let i_n = n.dot(&(t * n));
        numeric_of.push((quantity::MOMENT_ABOUT_AXIS, vec![i_n]));
        numeric_of.push((quantity::RADIUS_OF_GYRATION, vec![(i_n / mass).sqrt()]));
    }
    if scene.moments_from_bodies && d.quantities.contains_key(quantity::PRECESSION_RATE) {
        numeric_of.push((
            quantity::PRECESSION_RATE,
            vec![free_top::body_precession_rate(scene, d, &t)],
        ));
    }
    if scene.moments_from_bodies {
        numeric_of.extend(body_moments::body_family_values(scene, d, &t));
    }
    let mut out = Vec::new();
    for (name, num) in numeric_of {
        let Some(exact) = d.quantities.get(name) else {
            continue;
        };
        let exact = exact.numbers_at(vals)?;
        let error = max_relative_error(&num, &exact);
        out.push(QuantityCheck {
            name: name.to_string(),
            exact,
            numeric: num,
            error,
            passed: error <= variants::agreement(scene, name, vals),
        });
    }
    Ok(out)
}

/// The numeric checks: each quadrature run against its law, the exact quantities against the
/// numeric ones, and the principal axes against `SymmetricEigen`.
pub fn verify_numeric(
    scene: &Scene,
    d: &Derivation,
    numeric: Option<&NumericReport>,
    plan: &crate::plan::Plan,
    v: &mut Verification,
) -> Result<(), EvalError> {
    if plan.runs(Stage::Principal) {
        v.principal = principal_values(scene, d)?;
    }
    v.printed = printed::check_printed_forms(d, scene.seed.wrapping_add(999));
    if let Some(n) = numeric {
        v.within_law = n.runs.iter().map(within_law).collect();
        v.quantities = check_quantities(scene, d, n)?;
        if plan.runs(Stage::NumericEigen) {
            v.eigen = check_eigen(scene, d, &n.tensor)?;
        }
    }
    Ok(())
}

mod answer_routes;
mod assumed;
mod body_moments;
mod claim_form;
mod claims;
pub mod dimensions;
mod free_top;
mod gives;
pub mod n_link;
mod principal;
mod printed;
mod regressions;
mod result_names;
mod rounding;
mod squares;
mod step_records;
mod symbolic;
pub mod variants;

use crate::numeric::random_points::{numerically_zero, signed_names};
pub use crate::steps::StepCheck;
use claims::{check_claim, unchecked};
pub use claims::{check_claims, claim_env};
pub use principal::{PRINCIPAL_AGREEMENT, PrincipalValues, check_eigen, principal_values};
pub use printed::{ShownDiffers, shown_is_equation, shown_is_result};
pub use regressions::check_regressions;
pub use rounding::round_to_figures;
pub use step_records::{NUMBER_AGREEMENT, StepRecord, check_step_records};
pub use symbolic::{SymbolicChecks, verify_symbolic};

#[cfg(test)]
mod answer_routes_tests;
#[cfg(test)]
mod budget_tests;
#[cfg(test)]
mod constraints_tests;
#[cfg(test)]
mod printed_tests;
#[cfg(test)]
mod rolling_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod undefined_tests;
