//! The built-in steps' printed forms against their exact results at random points: the second
//! route beside the engine's proof (`derive::present`) for each form a page prints.

use super::random_points::{NUMERICALLY_ZERO, largest_differences};
use super::{CONFIRMATION_POINTS, StepCheck};
use crate::cas::Expr;
use crate::derive::Derivation;
use crate::derive::present::scalars;
use std::collections::BTreeSet;

/// One check for each built-in step printed in another form than derived, in the steps' order:
/// every symbol drawn with either sign, as the presentation assumed.
pub fn check_printed_forms(d: &Derivation, seed: u64) -> Vec<StepCheck> {
    d.steps
        .iter()
        .filter(|s| s.author.is_none())
        .filter_map(|s| Some((s, s.exact.clone()?)))
        .map(|(s, mut exact)| {
            let mut printed = s.statement.clone();
            let exact: Vec<Expr> = scalars(&mut exact).into_iter().map(|e| e.clone()).collect();
            let diffs: Vec<Expr> = scalars(&mut printed)
                .into_iter()
                .zip(&exact)
                .map(|(p, e)| Expr::minus(p.clone(), e.clone()))
                .collect();
            let signed: BTreeSet<String> = exact.iter().flat_map(Expr::symbols).collect();
            let mut check = StepCheck {
                step: s.title.clone(),
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
            match largest_differences(&diffs, &exact, seed, &signed) {
                Ok(d) => check.error = d.into_iter().fold(0.0, f64::max),
                Err(e) => check.problem = Some(e.to_string()),
            }
            check
        })
        .collect()
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
        present::present_builtin_steps(&mut d).unwrap();
        d
    }

    #[test]
    fn the_space_cone_is_printed_factored_and_agrees_at_random_points() {
        let d = symmetric_top();
        let cone = d.steps.iter().find(|s| s.title == "Space cone").unwrap();
        let (printed, exact) = (cone.statement.to_text(), cone.exact.as_ref().unwrap());
        // (I1 A² + I3 ω3²)² over (A² + ω3²)(I1² A² + I3² ω3²): a square above, two factors below.
        assert!(printed.len() < exact.to_text().len(), "{printed}");
        assert!(printed.contains(")^2/("), "{printed}");
        let checks = check_printed_forms(&d, 7);
        assert!(!checks.is_empty());
        assert!(checks.iter().all(StepCheck::passed), "{checks:?}");
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
