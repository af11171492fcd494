//! The built-in steps' printed forms against their exact results at random points: the second
//! route beside the engine's proof (`derive::present`) for each form a page prints; and the
//! build's guard, which takes what a page shows, read back from its printed tree, for the result
//! it stands for (`render/guard.rs`).

use super::{CONFIRMATION_POINTS, StepCheck};
use crate::cas::Expr;
use crate::derive::Derivation;
use crate::derive::present::shown_entries;
use crate::numeric::random_points::{
    NUMERICALLY_ZERO, SAMPLE_FROM, compare_in_domain, largest_differences,
};
use std::collections::{BTreeMap, BTreeSet};

/// One check for each built-in step printed in another form than derived, in the steps' order:
/// every symbol drawn with either sign, as the presentation assumed.
pub fn check_printed_forms(d: &Derivation, seed: u64) -> Vec<StepCheck> {
    d.steps
        .iter()
        .filter(|s| s.author.is_none())
        .filter_map(|s| Some((s, s.exact.clone()?)))
        .map(|(s, exact)| {
            let exact = shown_entries(&exact);
            let diffs: Vec<Expr> = shown_entries(&s.statement)
                .into_iter()
                .zip(&exact)
                .map(|(p, e)| Expr::minus(p, e.clone()))
                .collect();
            let signed: BTreeSet<String> = exact.iter().flat_map(Expr::symbols).collect();
            let mut check = StepCheck {
                // A built-in step's title is words and an author's `$…$`: no scene names.
                step: s.title.to_author_text(crate::notation::Names::none()),
                line: 0,
                method: format!(
                    "its printed form against its exact result at {CONFIRMATION_POINTS} random \
                     points"
                ),
                error: 0.0,
                tolerance: NUMERICALLY_ZERO,
                evaluations: (CONFIRMATION_POINTS * 2 * diffs.len()) as u64,
                problem: None,
            };
            match largest_differences(&diffs, &exact, seed, &signed, &|_| true) {
                Ok(d) => check.error = d.into_iter().fold(0.0, f64::max),
                Err(e) => check.problem = Some(e.to_string()),
            }
            check
        })
        .collect()
}

/// Whether a formula a page shows, read back from its printed tree, is the result it stands
/// for: equal at random points (every symbol drawn as the presentation assumed, the `signed`
/// ones with either sign), else, where the points differ or say nothing, by the engine over
/// positive symbols. `Err` carries the largest relative difference found.
pub fn shown_is_result(
    shown: &Expr,
    result: &Expr,
    signed: &BTreeSet<String>,
) -> Result<(), ShownDiffers> {
    let diff = Expr::minus(shown.clone(), result.clone());
    let at_points = largest_differences(
        std::slice::from_ref(&diff),
        std::slice::from_ref(result),
        1,
        signed,
        &|_| true,
    )
    .ok()
    .and_then(|d| d.first().copied())
    .filter(|d| d.is_finite());
    if at_points.is_some_and(|d| d <= NUMERICALLY_ZERO) {
        return Ok(());
    }
    // The engine settles what the points cannot: a form defined nowhere in [0.4, 1.4), or one
    // equal only where the presentation took a symbol positive.
    let proved = crate::cas::is_zero_over_positive(vec![diff], signed.clone())
        .is_ok_and(|z| z.first() == Some(&true));
    match proved {
        true => Ok(()),
        false => Err(ShownDiffers {
            by: at_points.unwrap_or(f64::NAN),
        }),
    }
}

/// A shown formula that is not its result, and by how much at random points (NaN where no
/// point was defined).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShownDiffers {
    pub by: f64,
}

/// Whether an equation a page shows, `shown = 0` read back, is the equation of motion whose
/// residual is `residual`: the two in proportion, by a factor free of the `varying` names (the
/// coordinates and their rates), as a page may divide out a mass or multiply out a denominator.
/// The ratio is compared at points that share every other symbol's value.
pub fn shown_is_equation(
    shown: &Expr,
    residual: &Expr,
    varying: &BTreeSet<String>,
) -> Result<(), ShownDiffers> {
    // An equation a substitution satisfies identically (steady precession's ψ equation):
    // `0 = 0` stands for the residual 0, which has no ratio to compare.
    if residual.is_zero() {
        return match shown.is_zero() {
            true => Ok(()),
            false => Err(ShownDiffers { by: f64::INFINITY }),
        };
    }
    let mut rng = crate::base::rng::Rng::new(1);
    let mut names: Vec<String> = shown
        .symbols()
        .into_iter()
        .chain(residual.symbols())
        .collect();
    names.sort();
    names.dedup();
    let mut fixed = BTreeMap::new();
    for n in names.iter().filter(|n| !varying.contains(*n)) {
        fixed.insert(n.clone(), SAMPLE_FROM + rng.uniform());
    }
    let mut ratios = Vec::new();
    let Ok(_) = compare_in_domain::<std::convert::Infallible>(|| {
        let mut point = fixed.clone();
        for n in names.iter().filter(|n| varying.contains(*n)) {
            // Either sign: a coordinate or rate is not positive.
            point.insert(n.clone(), 2.0 * rng.uniform() - 1.0);
        }
        let env = |s: &str| point.get(s).copied().filter(|_| s != "pi");
        let (Ok(a), Ok(b)) = (shown.eval(&env), residual.eval(&env)) else {
            return Ok(false);
        };
        let compared = a.is_finite() && b.is_finite() && b.abs() > 1e-6;
        if compared {
            ratios.push(a / b);
        }
        Ok(compared)
    });
    let Some(first) = ratios.first().copied().filter(|r| *r != 0.0) else {
        return Err(ShownDiffers { by: f64::NAN });
    };
    let by = ratios
        .iter()
        .map(|r| (r - first).abs() / first.abs())
        .fold(0.0, f64::max);
    match by <= NUMERICALLY_ZERO {
        true => Ok(()),
        false => Err(ShownDiffers { by }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::derive::algebra::Value;
    use crate::derive::{Step, free_top, present};
    use crate::notation::Formula;

    fn symmetric_top() -> Derivation {
        let mut d = Derivation::default();
        free_top::symmetric_top(&mut d).unwrap();
        present::present_builtin_steps(&mut d, &Default::default(), &[]).unwrap();
        d
    }

    #[test]
    fn the_space_cone_is_printed_factored_and_agrees_at_random_points() {
        let d = symmetric_top();
        let cone = d
            .steps
            .iter()
            .find(|s| s.title.to_text() == "Space cone")
            .unwrap();
        let (printed, exact) = (cone.statement.to_text(), cone.exact.as_ref().unwrap());
        // (I1 A² + I3 ω3²)² over (A² + ω3²)(I1² A² + I3² ω3²): a square above, two factors below.
        assert!(printed.len() < exact.to_text().len(), "{printed}");
        assert!(printed.contains(")^2/("), "{printed}");
        let checks = check_printed_forms(&d, 7);
        assert!(!checks.is_empty());
        assert!(checks.iter().all(StepCheck::passed), "{checks:?}");
    }

    #[test]
    fn an_equation_satisfied_identically_is_shown_as_zero_equals_zero_only() {
        let none = BTreeSet::new();
        let x = Expr::sym("x");
        assert_eq!(
            shown_is_equation(&Expr::int(0), &Expr::int(0), &none),
            Ok(())
        );
        let infinite = Err(ShownDiffers { by: f64::INFINITY });
        assert_eq!(shown_is_equation(&x, &Expr::int(0), &none), infinite);
        // x against the residual 0 has no ratio at any point: it differs by NaN.
        let e = shown_is_equation(&Expr::int(0), &x, &none).unwrap_err();
        assert!(e.by.is_nan(), "{e:?}");
    }

    #[test]
    fn a_printed_form_that_is_not_the_result_fails() {
        let mut d = symmetric_top();
        let step = d.steps.iter_mut().find(|s| s.exact.is_some()).unwrap();
        let wrong = Step::equation(
            "wrong",
            "x",
            &Value::Scalar(Expr::add(vec![Expr::sym("A"), Expr::sym("w3")])),
            "",
        );
        step.exact = Some(Formula::equation(
            Formula::parse("x", &[]),
            Expr::minus(Expr::sym("A"), Expr::sym("w3")),
        ));
        step.statement = wrong.statement;
        let failed = check_printed_forms(&d, 7)
            .into_iter()
            .filter(|c| !c.passed())
            .count();
        assert_eq!(failed, 1);
    }
}
