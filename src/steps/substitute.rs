//! `substitute = "…"`, `set = { x = "…" }`: an expression, or earlier equations of motion, with
//! names replaced by expressions all at once (a steady state θ'' = θ' = 0, a conserved rate).
//!
//! - Exact rule: the replacements put in and simplified; a value that makes a divisor 0 is
//!   refused as 0/0 or a pole, with the `series` step that takes the limit.
//! - Numeric route: the expression as written, each replaced name given its replacement's
//!   value, at random points.
//! - On the page: `name = result`, or each equation of motion, substituted, `… = 0`.

use super::page::Wording;
use super::{Checking, Context, Rule, simplified};
use crate::base::rng::Rng;
use crate::cas::{self, Expr};
use crate::derive::DeriveError;
use crate::derive::step_names::{StepResult, expand_names, replacements, substituted_equations};
use crate::derive::undefined::refuse_no_value;
use crate::notation::Formula;
use crate::numeric::random_points::CONFIRMATION_POINTS;
use crate::numeric::random_points::NUMERICALLY_ZERO;
use crate::scene::operations::Substitute;
use crate::steps::check::{CheckError, StepCheck, at, random_point};
use std::collections::BTreeMap;

impl Rule for Substitute {
    fn derive(&self, cx: Context, _: &mut Option<Formula>) -> Result<StepResult, DeriveError> {
        let of: &Expr = &self.of;
        let set: &BTreeMap<String, Expr> = &self.set;
        let (scene, d, step) = (cx.scene, cx.d, cx.step);
        match substituted_equations(d, of) {
            // Equations of motion with names replaced: a steady state (θ'' = θ' = 0), a conserved
            // rate put in.
            Some(eqs) => {
                let values = replacements(scene, d, step, set)?;
                for (_, e) in eqs {
                    refuse_no_value(e, of, set, &values)?;
                }
                simplified(
                    eqs.iter()
                        .map(|(q, e)| (q.clone(), e.substitute(&|s| values.get(s).cloned())))
                        .collect(),
                )
            }
            None => {
                // The names expanded and the replacements found once, for the refusal and the
                // result (what `substituted` does).
                let f = expand_names(scene, d, step, of).map_err(DeriveError::Step)?;
                let values = replacements(scene, d, step, set)?;
                refuse_no_value(&f, of, set, &values)?;
                Ok(StepResult::Expr(cas::simplify(
                    &f.substitute(&|s| values.get(s).cloned()),
                )?))
            }
        }
    }

    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError> {
        let of: &Expr = &self.of;
        let set: &BTreeMap<String, Expr> = &self.set;
        // Each expression as written beside its result: one, or one per equation.
        let pairs: Vec<(Expr, &Expr)> = match (substituted_equations(cx.d, of), cx.result) {
            (Some(before), StepResult::Equations(after)) => before
                .iter()
                .zip(after)
                .map(|((_, b), (_, a))| (b.clone(), a))
                .collect(),
            (None, StepResult::Expr(r)) => vec![(expand_names(cx.scene, cx.d, cx.step, of)?, r)],
            _ => return Err(CheckError::NotDerived),
        };
        let values = replacements(cx.scene, cx.d, cx.step, set)?;
        check.method = format!(
            "the expression as written, each replaced name given its replacement's value, at \
         {CONFIRMATION_POINTS} random points"
        );
        check.tolerance = NUMERICALLY_ZERO;
        let mut rng = Rng::new(cx.seed);
        let mut valued = 0;
        for _ in 0..CONFIRMATION_POINTS {
            let exprs: Vec<&Expr> = pairs
                .iter()
                .flat_map(|(f, r)| [f, *r])
                .chain(values.values())
                .collect();
            let point = random_point(&exprs, &mut rng, cx.scene);
            // All at once, as the exact rule replaces: a replacement that names another
            // replaced name takes that name's value before the replacement. The cx.result is
            // in the names as they were (after a swap, x stands where y stood).
            let mut replaced = point.clone();
            for (name, e) in &values {
                replaced.insert(name.clone(), at(e, &point)?);
            }
            for (f, r) in &pairs {
                let (a, b) = (at(f, &replaced)?, at(r, &point)?);
                check.evaluations += 2;
                // A point outside a root's domain (√ of a negative) tells nothing.
                if a.is_finite() && b.is_finite() {
                    valued += 1;
                    check.error = check
                        .error
                        .max((a - b).abs() / a.abs().max(b.abs()).max(1.0));
                }
            }
            check.evaluations += values.len() as u64;
        }
        if valued == 0 {
            return Err(CheckError::NoValue);
        }
        Ok(())
    }

    fn wording(&self) -> Wording<'_> {
        Wording {
            equation: Some(("equation", ", substituted")),
            ..Wording::default()
        }
    }
}
