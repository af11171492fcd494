//! `be = "…"`: an expression of the scene's names and the earlier steps.
//!
//! - Exact rule: the names put in, simplified by the engine; a divisor that is 0 as written is
//!   refused.
//! - Numeric route: the simplified form against the expression as written at random points.
//! - On the page: the expression as written, then its value.

use super::{Checking, Context, Rule};
use crate::base::rng::Rng;
use crate::cas::{self, Expr};
use crate::derive::DeriveError;
use crate::derive::step_names::{StepResult, expand_names, expand_printed_names};
use crate::notation::Formula;
use crate::numeric::random_points::CONFIRMATION_POINTS;
use crate::numeric::random_points::{NUMERICALLY_ZERO, rational_at};
use crate::scene::operations::Be;
use crate::steps::check::{CheckError, StepCheck, at, compare_at_points, random_point};
use std::collections::BTreeMap;

impl Rule for Be {
    fn derive(&self, cx: Context, _: &mut Option<Formula>) -> Result<StepResult, DeriveError> {
        let e: &Expr = &self.0;
        let x = expand_names(cx.scene, cx.d, cx.step, e).map_err(DeriveError::Step)?;
        crate::derive::undefined::refuse_no_value(&x, e, &BTreeMap::new(), &BTreeMap::new())?;
        Ok(StepResult::Expr(cas::simplify(&x)?))
    }

    /// The author's expression as written, its names kept where they print as symbols
    /// (T_beat = 2π/(Ω₂ − Ω₁) = …), then put in.
    fn printed(
        &self,
        cx: Context,
        result: &StepResult,
        shown: &mut Option<Formula>,
    ) -> Result<Option<StepResult>, DeriveError> {
        let StepResult::Expr(exact) = result else {
            return super::printed_form(cx.scene, result);
        };
        let form = printed(cx, &self.0, exact)?;
        if let Some(named) = as_named(cx, &self.0).filter(|n| *n != form) {
            *shown = Some(Formula::Row(vec![
                Formula::Expr(Expr::sym(&cx.step.name)),
                Formula::Op(crate::notation::Op::Equals),
                Formula::Expr(named),
                Formula::Op(crate::notation::Op::Equals),
                Formula::Expr(form.clone()),
            ]));
        }
        Ok((form != *exact).then_some(StepResult::Expr(form)))
    }

    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError> {
        let e: &Expr = &self.0;
        let StepResult::Expr(r) = cx.result else {
            return Err(CheckError::NotDerived);
        };
        let raw = expand_names(cx.scene, cx.d, cx.step, e)?;
        check.method = format!(
            "the simplified form against the expression as written, at {CONFIRMATION_POINTS} \
         random points"
        );
        check.tolerance = NUMERICALLY_ZERO;
        let mut rng = Rng::new(cx.seed);
        compare_at_points(|| {
            let point = random_point(&[&raw, r], &mut rng, cx.scene);
            let (a, b) = (at(&raw, &point)?, at(r, &point)?);
            check.evaluations += 2;
            // Where either is undefined or infinite, nothing is compared (inf − inf is NaN, which
            // `max` would pass over): another point is drawn.
            if !a.is_finite() || !b.is_finite() {
                return Ok(false);
            }
            let scale = a.abs().max(b.abs()).max(1.0);
            let mut error = (a - b).abs() / scale;
            // Apart in double precision: exactly, where both are rational functions of the point
            // (an expanded (x − a)^30 against the power as written cancels its digits away).
            if error > NUMERICALLY_ZERO
                && let (Some(x), Some(y)) = (rational_at(&raw, &point), rational_at(r, &point))
            {
                error = x.add(&y.negated()).to_f64().abs() / scale;
            }
            check.error = check.error.max(error);
            Ok(true)
        })
    }
}

/// The form the page prints: the author's expression as written, each earlier step put in by
/// the form its page prints, where the engine proves it equal (`cas::present_written`).
fn printed(cx: Context, e: &Expr, exact: &Expr) -> Result<Expr, DeriveError> {
    let written = expand_printed_names(cx.scene, cx.d, cx.step, e).map_err(DeriveError::Step)?;
    Ok(cas::present_written(
        written,
        exact.clone(),
        cx.scene.signed_names(),
        cx.scene.declared.clone(),
        crate::notation::printed_length,
    )?)
}

/// The author's expression with its names, where it names an earlier step's result and every
/// name in it prints as a symbol: T_beat = 2π/(Ω₂ − Ω₁) before its value, as a textbook
/// writes L = T − V before putting T and V in.
fn as_named(cx: Context, e: &Expr) -> Option<Expr> {
    let results: Vec<String> =
        cx.d.named
            .iter()
            .flat_map(|(name, r)| {
                let mut names = vec![name.clone()];
                names.extend(
                    r.values(cx.scene.result_names(name))
                        .into_iter()
                        .map(|(n, _)| n),
                );
                names
            })
            .collect();
    let scene = cx.scene;
    let own = |n: &str| {
        scene.symbols.contains_key(n)
            || ["t", "pi"].contains(&n)
            || scene.coordinates.contains_key(n.trim_end_matches('\''))
    };
    let symbols = e.symbols();
    let names_a_result = symbols.iter().any(|s| results.contains(s));
    let each_a_symbol = symbols.iter().all(|s| {
        own(s) || (results.contains(s) && !cas::prints_as_word(s, &|n| scene.tex.contains_key(n)))
    });
    let mut plain = true;
    e.walk(&mut |x| {
        plain &= match x {
            Expr::Call(f, args) => cas::arity(f) == Some(args.len()),
            Expr::List(_) | Expr::Index(..) => false,
            _ => true,
        }
    });
    (names_a_result && each_a_symbol && plain && !matches!(e, Expr::Sym(_)))
        .then(|| cas::as_written(e, &scene.signed_names()))
}
