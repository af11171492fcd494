//! Every variant of a problem, checked: its exact answers (the derivation with the variant's
//! values substituted) against the independent numeric routes at the variant's numbers.

use super::answer_routes::{AnswerRouteError, AnswerRoutes};
use super::dimensions::answer_scale;
use super::exact_vs_numeric;
use super::principal::PRINCIPAL_AGREEMENT;
use crate::base::float::max_relative_error;
use crate::cas::Expr;
use crate::cas::Rational;
use crate::derive::variants::{
    exact_answers, general_answers, has_long_number, shown_answers, with_numeric_modes,
};
use crate::derive::{Derivation, DeriveError};
use crate::model::catalogue::quantity;
use crate::model::value::Value;
use crate::numeric::answers::RouteError;
use crate::numeric::budget::Deadline;
use crate::scene::{Problem, Scene};
use std::collections::BTreeMap;

/// How closely the precession rate integrated at tolerance 1e-12 must match the exact rate
/// (relative): a hundred times the integrator's tolerance. The shipped variants agree to 2e-15.
pub const PRECESSION_AGREEMENT: f64 = 1e-10;

/// One variant: its values and each answer, exact and numeric.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct VariantCheck {
    pub number: usize,
    /// Each symbol's exact value, the varying ones and the fixed ones.
    pub values: Vec<(String, Expr)>,
    /// The names whose values the author wrote in decimals.
    #[serde(default)]
    pub decimal: Vec<String>,
    pub answers: Vec<AnswerCheck>,
}

#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct AnswerCheck {
    /// The answer as the author wrote it: a quantity's name or an expression.
    pub quantity: String,
    pub exact: Value,
    /// The exact answer as the key shows it, where it uses a value the author wrote as a
    /// decimal: that value as written (`derive::variants::shown_answers`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shown: Option<Value>,
    /// The shown form has a number of more digits than a reader takes in
    /// (`derive::variants::has_long_number`): the key gives the answer to
    /// `document::ROUNDED_FIGURES` figures in its exact column, and `--json` the exact
    /// value.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub rounded: bool,
    /// The answer names a mode with no closed form (`Omega_5` of six links): its "exact" value
    /// is the variant's by Sturm bisection (`derive::variants::with_numeric_modes`), a number.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub numeric_mode: bool,
    /// The exact answer's entries in f64, and the numeric route's.
    pub exact_numbers: Vec<f64>,
    pub numeric: Vec<f64>,
    pub error: f64,
    pub tolerance: f64,
}

impl AnswerCheck {
    /// The value the key prints in its exact column.
    pub fn shown_or_exact(&self) -> &Value {
        self.shown.as_ref().unwrap_or(&self.exact)
    }

    pub fn passed(&self) -> bool {
        self.error <= self.tolerance
    }
}

impl VariantCheck {
    pub fn passed(&self) -> bool {
        self.answers.iter().all(AnswerCheck::passed)
    }
}

/// A variant that could not be checked.
#[derive(Debug, thiserror::Error)]
#[error("variant {number}: {source}")]
pub struct VariantError {
    pub number: usize,
    pub source: VariantFailure,
}

#[derive(Debug, thiserror::Error)]
pub enum VariantFailure {
    #[error(transparent)]
    Derive(#[from] DeriveError),
    #[error("the numeric route failed: {0}")]
    Route(#[from] RouteError),
    #[error("the numeric route failed: {0}")]
    AnswerRoute(#[from] AnswerRouteError),
    #[error(transparent)]
    Dimension(super::dimensions::DimensionFault),
    #[error(transparent)]
    OverBudget(#[from] crate::numeric::budget::OverBudget),
}

/// How closely a route must agree at these numbers: the quadrature rules are exact for these
/// integrands, so only rounding separates them; the eigen-solver and the integrator have their
/// own errors. The precession route also loses I/|I3 − I1| of precision to the difference
/// of two near moments, as the rounded inputs do (a top near symmetric).
pub fn agreement(scene: &Scene, name: &str, numbers: &BTreeMap<String, f64>) -> f64 {
    match name {
        quantity::PRINCIPAL_MOMENTS => PRINCIPAL_AGREEMENT.max(exact_vs_numeric(scene)),
        quantity::PRECESSION_RATE => {
            let cancellation = match (numbers.get("I1"), numbers.get("I3")) {
                (Some(i1), Some(i3)) if i1 != i3 => {
                    8.0 * f64::EPSILON * i1.abs().max(i3.abs()) / (i3 - i1).abs()
                }
                _ => 0.0,
            };
            PRECESSION_AGREEMENT + cancellation
        }
        _ => exact_vs_numeric(scene),
    }
}

/// A problem's variants as pinned in `[expect] variants` and as derived now, one hash each.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Pin {
    pub recorded: Option<Vec<String>>,
    pub derived: Vec<String>,
    /// The `variants` key's line, or the `[problem]`'s when nothing is recorded.
    pub line: usize,
}

impl Pin {
    pub fn new(scene: &Scene, problem: &Problem) -> Pin {
        let derived = problem.variants.iter().map(|v| v.pin()).collect();
        match &scene.pinned_variants {
            Some((hashes, line)) => Pin {
                recorded: Some(hashes.clone()),
                derived,
                line: *line,
            },
            None => Pin {
                recorded: None,
                derived,
                line: problem.at.0,
            },
        }
    }

    pub fn unchanged(&self) -> bool {
        self.recorded.as_ref() == Some(&self.derived)
    }

    /// The numbers (from 1) of the variants whose sheet differs from the recorded one: a
    /// changed variant, and one added or taken away.
    pub fn differing(&self) -> Vec<usize> {
        let recorded = self.recorded.as_deref().unwrap_or(&[]);
        (0..recorded.len().max(self.derived.len()))
            .filter(|&k| recorded.get(k) != self.derived.get(k))
            .map(|k| k + 1)
            .collect()
    }
}

/// Each variant's answers, exact and by their numeric routes, until the deadline (a variant
/// reached after it fails the sheet, with the budget named).
pub fn check_variants(
    scene: &Scene,
    d: &Derivation,
    problem: &Problem,
    deadline: &Deadline,
) -> Result<Vec<VariantCheck>, VariantError> {
    // What does not depend on the variant, once: each answer in symbols, in its unit (its
    // derived value times its symbols' unit's size over the unit asked for). A failure here is
    // the first variant's, where it would first show.
    let first = problem.variants.first().map_or(1, |v| v.number);
    let fail_first = |source: VariantFailure| VariantError {
        number: first,
        source,
    };
    let mut general = general_answers(scene, d, problem).map_err(|e| fail_first(e.into()))?;
    let mut scales = Vec::new();
    for (answer, g) in problem.answers.iter().zip(&mut general) {
        let scale = answer_scale(scene, answer, g)
            .map_err(|f| fail_first(VariantFailure::Dimension(f)))?
            .filter(|s| *s != Rational::ONE);
        if let Some(s) = &scale {
            let entries: Vec<Expr> = g
                .entries()
                .into_iter()
                .map(|e| Expr::mul(vec![Expr::Num(s.clone()), e]))
                .collect();
            *g = g.with_entries(&entries);
        }
        scales.push(scale.map_or(1.0, |s| s.to_f64()));
    }
    // Which answers name a mode with no closed form: the same for every variant.
    let numeric_modes: Vec<bool> = general
        .iter()
        .map(|g| {
            g.entries()
                .iter()
                .any(|e| d.numeric_name_in(scene, e).is_some())
        })
        .collect();
    // Each variant on its own, on both cores: one thread's engine calls (its exact answers)
    // overlap the other's numeric routes. In the variants' order; the first failure is told.
    let answers = Answers {
        general,
        scales,
        numeric_modes,
        angles: scene.whole_turn_symbols(),
    };
    let checked = crate::numeric::Work::map_in_order(&problem.variants, |v| {
        check_variant(scene, d, problem, &answers, v, deadline)
    });
    checked.into_iter().collect()
}

/// What the answers are the same in for every variant.
struct Answers {
    /// Each answer in symbols, in its unit.
    general: Vec<Value>,
    /// The size of the answer's symbols' unit over the unit asked for.
    scales: Vec<f64>,
    /// Which answers name a mode with no closed form.
    numeric_modes: Vec<bool>,
    /// The scene's angles, put within a turn (`Variant::numbers_within_a_turn`).
    angles: std::collections::BTreeSet<String>,
}

/// One variant's answers, exact and by their numeric routes.
fn check_variant(
    scene: &Scene,
    d: &Derivation,
    problem: &Problem,
    same: &Answers,
    v: &crate::scene::Variant,
    deadline: &Deadline,
) -> Result<VariantCheck, VariantError> {
    let fail = |source: VariantFailure| VariantError {
        number: v.number,
        source,
    };
    deadline.check().map_err(|e| fail(e.into()))?;
    let general = with_numeric_modes(scene, d, &same.general, v).map_err(|e| fail(e.into()))?;
    let exact = exact_answers(&general, problem, v).map_err(|e| fail(e.into()))?;
    let shown = shown_answers(&general, problem, v).map_err(|e| fail(e.into()))?;
    let numbers = v.numbers_within_a_turn(&same.angles);
    let agree = |name: &str| agreement(scene, name, &numbers);
    let mut routes = AnswerRoutes::new(scene, d, &numbers, &agree);
    let mut answers = Vec::new();
    for ((((answer, a), scale), shown), numeric_mode) in problem
        .answers
        .iter()
        .zip(exact)
        .zip(&same.scales)
        .zip(shown)
        .zip(same.numeric_modes.iter().copied())
    {
        let (numeric, tolerance) = match answer.bare_quantity() {
            Some(q) => (
                routes.routes.answer(q).map_err(|e| fail(e.into()))?,
                agree(q),
            ),
            None => {
                let r = routes
                    .expression(&answer.value)
                    .map_err(|e| fail(e.into()))?;
                // The routes' own errors carried to the answer, and rounding beside them.
                (vec![r.value], r.tolerance + exact_vs_numeric(scene))
            }
        };
        let numeric: Vec<f64> = numeric.iter().map(|x| x * scale).collect();
        let exact_numbers: Vec<f64> = a
            .value
            .entries()
            .iter()
            .map(|e| e.eval(&|_| None).unwrap_or(f64::NAN))
            .collect();
        let error = max_relative_error(&numeric, &exact_numbers);
        let rounded = shown
            .as_ref()
            .unwrap_or(&a.value)
            .entries()
            .iter()
            .any(has_long_number);
        answers.push(AnswerCheck {
            tolerance,
            quantity: a.quantity,
            exact: a.value,
            shown,
            rounded,
            numeric_mode,
            exact_numbers,
            numeric,
            // NaN (an answer with no number) fails every comparison: count it as infinite.
            error: if error.is_nan() { f64::INFINITY } else { error },
        });
    }
    Ok(VariantCheck {
        number: v.number,
        values: v
            .values
            .iter()
            .map(|(k, e)| (k.clone(), e.clone()))
            .collect(),
        decimal: v.decimal.iter().cloned().collect(),
        answers,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cas::parse;
    use crate::pipeline::run_scene;
    use std::path::Path;

    const BOX: &str = include_str!("../../tests/fixtures/unit/box-variants.toml");

    #[test]
    fn every_variant_agrees_with_quadrature_and_a_wrong_derivation_does_not() {
        let scene = Scene::parse(BOX, Path::new("b.toml")).unwrap();
        let report = run_scene(scene.clone(), None).unwrap();
        let checks = &report.verification.variants;
        assert_eq!(checks.len(), 6);
        assert!(report.verification.verified());
        for v in checks {
            for a in &v.answers {
                assert!(
                    a.error <= 1e-15,
                    "variant {}: {} {}",
                    v.number,
                    a.quantity,
                    a.error
                );
            }
        }
        // The same problem with the tensor's I_xx made (b² + c²)/6: every variant must fail.
        let mut wrong = report.derivation.clone();
        let tensor = wrong.quantities["inertia_tensor"].clone();
        let mut entries = tensor.entries();
        entries[0] = parse("m*(b^2 + c^2)/6").unwrap().expr;
        wrong
            .quantities
            .insert("inertia_tensor".into(), tensor.with_entries(&entries));
        let problem = scene.problem.as_ref().unwrap();
        let checks = check_variants(&scene, &wrong, problem, &Deadline::checks()).unwrap();
        assert!(checks.iter().all(|v| !v.passed()));
        assert!(
            checks.iter().all(|v| v.answers[1].passed()),
            "the moments are untouched"
        );
    }

    #[test]
    fn an_answer_left_with_a_symbol_is_an_error_that_says_which() {
        let scene = Scene::parse(BOX, Path::new("b.toml")).unwrap();
        let report = run_scene(scene.clone(), None).unwrap();
        let mut problem = scene.problem.clone().unwrap();
        problem.variants[0].values.remove("c");
        let e =
            check_variants(&scene, &report.derivation, &problem, &Deadline::checks()).unwrap_err();
        assert_eq!(e.number, 1);
        assert!(e.to_string().contains("depends on `c`"), "{e}");
    }

    /// A top within 10⁻⁸ of symmetric: the precession route follows ω alone, so each variant
    /// costs a few hundred evaluations (following the attitude too had cost about 10⁸), and
    /// its tolerance grows with the cancellation in I3 − I1. A wrong rate still fails.
    #[test]
    fn a_nearly_symmetric_top_is_checked_cheaply_and_a_wrong_rate_fails() {
        const TOP: &str = include_str!("../../tests/fixtures/unit/near-symmetric-top.toml");
        let scene = Scene::parse(TOP, Path::new("t.toml")).unwrap();
        let before = crate::numeric::Work::so_far().rhs_evaluations;
        let report = run_scene(scene.clone(), None).unwrap();
        let evaluations = crate::numeric::Work::so_far().rhs_evaluations - before;
        let checks = &report.verification.variants;
        assert_eq!(checks.len(), 40);
        assert!(checks.iter().all(VariantCheck::passed), "{checks:#?}");
        assert!(evaluations < 40 * 5_000, "{evaluations} evaluations");
        // I1 = 3 against I3 ≈ 1 is far from symmetric; I1 = 1 is within 4·10⁻⁷ of it.
        let worst = checks
            .iter()
            .map(|v| v.answers[0].error)
            .fold(0.0, f64::max);
        assert!(worst > 0.0 && worst < 1e-6, "{worst}");
        let problem = scene.problem.as_ref().unwrap();
        for wrong_rate in ["(I3 - I1)*w3/(2*I1)", "(I1 - I3)*w3/I1"] {
            let mut wrong = report.derivation.clone();
            let rate = wrong.quantities["precession_rate"].clone();
            wrong.quantities.insert(
                "precession_rate".into(),
                rate.with_entries(&[parse(wrong_rate).unwrap().expr]),
            );
            let checks = check_variants(&scene, &wrong, problem, &Deadline::checks()).unwrap();
            assert!(checks.iter().all(|v| !v.passed()), "{wrong_rate}");
        }
    }

    /// g written 9.81 stays 9.81 in the key's form of the answer (2π√(L/9.81), not 20π/(3√327)),
    /// with the same value as the exact answer; an answer of seven-digit numbers is rounded.
    #[test]
    fn the_keys_form_keeps_the_authors_decimals_and_rounds_long_numbers() {
        const SWING: &str = include_str!("../../tests/fixtures/unit/keys-decimals.toml");
        let scene = Scene::parse(SWING, Path::new("s.toml")).unwrap();
        let report = run_scene(scene, None).unwrap();
        let checks = &report.verification.variants;
        assert!(checks.iter().all(VariantCheck::passed), "{checks:#?}");
        // A numeral read back as the number its digits say.
        let read_back = |e: &Expr| {
            e.substitute(&|s| {
                s.starts_with(|c: char| c.is_ascii_digit())
                    .then(|| parse(s).unwrap().expr)
            })
            .eval(&|_| None)
            .unwrap()
        };
        let (mut rounded, mut exact) = (0, 0);
        for v in checks {
            let period = &v.answers[0];
            let shown = period.shown.as_ref().expect("g is a decimal").entries()[0].clone();
            assert!(
                shown.symbols().contains(&"9.81".to_string()),
                "{}",
                shown.to_text()
            );
            assert!(!shown.to_text().contains("327"), "{}", shown.to_text());
            let relative = (read_back(&shown) / period.exact_numbers[0] - 1.0).abs();
            assert!(relative < 1e-15, "{} {relative}", shown.to_text());
            assert!(!period.rounded);
            // sqrt(k) uses no decimal: its exact value is the one shown.
            assert!(v.answers[2].shown.is_none());
            let long = v.values.iter().any(|(n, e)| n == "k" && e.to_text() != "2");
            for a in &v.answers[1..] {
                assert_eq!(a.rounded, long, "{}", a.exact.to_expr().to_text());
                if a.rounded { rounded += 1 } else { exact += 1 }
            }
        }
        assert!(rounded > 0 && exact > 0, "{rounded} {exact}");
    }

    /// Past the scene's budget a sheet is refused at the variant it reached, with the reason.
    #[test]
    fn variants_past_the_scenes_budget_fail_with_the_budget_named() {
        let scene = Scene::parse(BOX, Path::new("b.toml")).unwrap();
        let report = run_scene(scene.clone(), None).unwrap();
        let problem = scene.problem.as_ref().unwrap();
        let spent = Deadline::after(std::time::Duration::ZERO);
        let e = check_variants(&scene, &report.derivation, problem, &spent).unwrap_err();
        assert_eq!(e.number, 1);
        assert!(e.to_string().contains("past the 0 s"), "{e}");
    }
}
