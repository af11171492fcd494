//! Every variant of a problem, checked: its exact answers (the derivation with the variant's
//! values substituted) against the independent numeric routes at the variant's numbers.

use super::answer_routes::{AnswerRouteError, AnswerRoutes};
use super::dimensions::answer_scale;
use super::exact_vs_numeric;
use super::principal::PRINCIPAL_AGREEMENT;
use crate::base::float::max_relative_error;
use crate::cas::Expr;
use crate::cas::Rational;
use crate::derive::variants::{exact_answers, general_answers};
use crate::derive::{Derivation, DeriveError};
use crate::model::catalogue::quantity;
use crate::model::value::Value;
use crate::numeric::answers::RouteError;
use crate::scene::{Problem, Scene};

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
    /// The exact answer's entries in f64, and the numeric route's.
    pub exact_numbers: Vec<f64>,
    pub numeric: Vec<f64>,
    pub error: f64,
    pub tolerance: f64,
}

impl AnswerCheck {
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
}

/// How closely a route must agree: the quadrature rules are exact for these integrands, so
/// only rounding separates them; the eigen-solver and the integrator have their own errors.
pub fn agreement(scene: &Scene, name: &str) -> f64 {
    match name {
        quantity::PRINCIPAL_MOMENTS => PRINCIPAL_AGREEMENT.max(exact_vs_numeric(scene)),
        quantity::PRECESSION_RATE => PRECESSION_AGREEMENT,
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

pub fn check_variants(
    scene: &Scene,
    d: &Derivation,
    problem: &Problem,
) -> Result<Vec<VariantCheck>, VariantError> {
    let mut out = Vec::new();
    let angles = scene.whole_turn_symbols();
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
    for v in &problem.variants {
        let fail = |source: VariantFailure| VariantError {
            number: v.number,
            source,
        };
        let exact = exact_answers(&general, problem, v).map_err(|e| fail(e.into()))?;
        let numbers = v.numbers_within_a_turn(&angles);
        let agree = |name: &str| agreement(scene, name);
        let mut routes = AnswerRoutes::new(scene, d, &numbers, &agree);
        let mut answers = Vec::new();
        for ((answer, a), scale) in problem.answers.iter().zip(exact).zip(&scales) {
            let (numeric, tolerance) = match answer.bare_quantity() {
                Some(q) => (
                    routes.routes.answer(q).map_err(|e| fail(e.into()))?,
                    agreement(scene, q),
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
            answers.push(AnswerCheck {
                tolerance,
                quantity: a.quantity,
                exact: a.value,
                exact_numbers,
                numeric,
                // NaN (an answer with no number) fails every comparison: count it as infinite.
                error: if error.is_nan() { f64::INFINITY } else { error },
            });
        }
        out.push(VariantCheck {
            number: v.number,
            values: v
                .values
                .iter()
                .map(|(k, e)| (k.clone(), e.clone()))
                .collect(),
            decimal: v.decimal.iter().cloned().collect(),
            answers,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cas::parse;
    use crate::pipeline::run_scene;
    use std::path::Path;

    const BOX: &str = r#"
id = "b"
title = "b"
notes = { lecture = "x" }
symbols = { m = "mass", a = "side", b = "side", c = "side" }
[[body]]
kind = "box"
size = ["a", "b", "c"]
mass = "m"
origin = "centre"
[outputs]
want = ["inertia_tensor", "principal_axes"]
[numeric]
values = { m = 1.0, a = 1.0, b = 2.0, c = 3.0 }
[problem]
statement = "A box of mass {m} kg, sides {a}, {b}, {c}."
answers = ["inertia_tensor", "principal_moments"]
[variants]
count = 6
m = ["1", "2", "3"]
a = ["1/2", "1"]
b = ["2", "5/2"]
c = ["3", "7/2"]
require = ["a < b"]
"#;

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
        let checks = check_variants(&scene, &wrong, problem).unwrap();
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
        let e = check_variants(&scene, &report.derivation, &problem).unwrap_err();
        assert_eq!(e.number, 1);
        assert!(e.to_string().contains("depends on `c`"), "{e}");
    }
}
