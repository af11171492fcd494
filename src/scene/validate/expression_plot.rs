//! `kind = "expression"`: a step's expression drawn against a coordinate or a symbol (an
//! effective potential against its angle).

use super::{Validator, content_start};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::operations::Operation;
use crate::scene::operations::Substitute;
use crate::scene::operations::{Holds, Several};
use crate::scene::raw::RawPlot;
use crate::scene::step::AuthorStep;
use crate::scene::types::PlotRequest;
use std::collections::BTreeMap;
use toml::Spanned;

/// Whether a step's result is one expression (not equations, states or several roots), from
/// the table of operations.
fn gives_an_expression(steps: &[AuthorStep], name: &str) -> bool {
    let Some(step) = steps.iter().find(|s| s.name == name) else {
        return false;
    };
    let kind = step.op.kind();
    match (kind.holds, &step.op) {
        // `substitute` of a step of equations gives equations.
        (
            Holds::Operand,
            Operation::Substitute(Substitute {
                of: Expr::Sym(n), ..
            }),
        ) if steps.iter().any(|s| s.name == *n) => gives_an_expression(steps, n),
        (Holds::Operand, _) => true,
        (Holds::Expression, _) => kind.several == Several::None,
        _ => false,
    }
}

impl Validator<'_> {
    pub(super) fn expression_plot(
        &self,
        p: &Spanned<RawPlot>,
        field: &str,
        steps: &[AuthorStep],
        symbols: &BTreeMap<String, String>,
        coordinates: &BTreeMap<String, String>,
    ) -> Result<PlotRequest, SceneError> {
        let rp = p.get_ref();
        let start = p.span().start;
        if rp.linear.is_some() || !rp.start.is_empty() {
            return Err(self.err(
                start,
                field,
                "`linear` and `start` belong to a motion plot; an expression plot takes `at` for \
                 the values of names without one",
            ));
        }
        if rp.inertia.is_some() || rp.omega.is_some() || rp.t.is_some() {
            return Err(self.err(
                start,
                field,
                "`inertia`, `omega` and `t` belong to the free-body plot kinds",
            ));
        }
        let step = rp.step.as_ref().ok_or_else(|| {
            self.err(
                start,
                &format!("{field}.step"),
                "an expression plot needs `step`, a step whose result is one expression",
            )
        })?;
        if !gives_an_expression(steps, step.get_ref()) {
            return Err(self.err(
                content_start(step),
                &format!("{field}.step"),
                format!(
                    "`{}` is not a step whose result is one expression (`be`, `differentiate`, \
                     `substitute` of an expression, `integrate`, `series`, `routh`, `momentum`, \
                     `energy`)",
                    step.get_ref()
                ),
            ));
        }
        let is_name = |n: &str| {
            symbols.contains_key(n)
                || coordinates.contains_key(n.trim_end_matches('\''))
                    && n.trim_end_matches('\'').len() + 1 >= n.len()
        };
        let over = rp.over.as_ref().ok_or_else(|| {
            self.err(
                start,
                &format!("{field}.over"),
                "an expression plot needs `over`, the coordinate or symbol on the x axis",
            )
        })?;
        if !is_name(over.get_ref()) {
            return Err(self.err(
                content_start(over),
                &format!("{field}.over"),
                format!(
                    "`{}` is not a coordinate, a rate or a declared symbol",
                    over.get_ref()
                ),
            ));
        }
        let (from, to) = self.plot_range(p, field, "an expression plot")?;
        let samples = self.plot_samples(p, field, 9)?;
        let at = self.values_at(rp, field, over.get_ref(), &is_name)?;
        Ok(PlotRequest::Expression {
            step: step.get_ref().clone(),
            over: over.get_ref().clone(),
            from,
            to,
            samples,
            at,
        })
    }

    /// An expression plot's `at`: a finite value for each name it gives, a coordinate, a rate
    /// or a declared symbol other than `over`.
    fn values_at(
        &self,
        rp: &RawPlot,
        field: &str,
        over: &str,
        is_name: &dyn Fn(&str) -> bool,
    ) -> Result<BTreeMap<String, f64>, SceneError> {
        let mut at = BTreeMap::new();
        for (k, v) in &rp.at {
            if !is_name(k.get_ref()) || k.get_ref() == over {
                return Err(self.err(
                    k.span().start,
                    &format!("{field}.at"),
                    format!(
                        "`{}` is not a coordinate, a rate or a declared symbol other than `over`",
                        k.get_ref()
                    ),
                ));
            }
            if !v.get_ref().is_finite() {
                return Err(self.err(
                    v.span().start,
                    &format!("{field}.at"),
                    "a value must be a finite number",
                ));
            }
            at.insert(k.get_ref().clone(), *v.get_ref());
        }
        Ok(at)
    }
}
