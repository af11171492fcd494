//! `kind = "motion"`: an author's equations of motion drawn against time, with linear ones
//! beside them.

use super::{MAX_PLOT_TIME, Validator, content_start};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::operations::Operation;
use crate::scene::operations::Substitute;
use crate::scene::raw::RawPlot;
use crate::scene::step::AuthorStep;
use crate::scene::types::PlotRequest;
use std::collections::BTreeMap;
use toml::Spanned;

/// What a step of equations holds: `Some(false)` equations of motion, `Some(true)` linear
/// ones, `None` no equations.
fn equations_kind(steps: &[AuthorStep], name: &str) -> Option<bool> {
    let step = steps.iter().find(|s| s.name == name)?;
    match &step.op {
        Operation::Lagrange(_) => Some(false),
        Operation::Linearise(_) => Some(true),
        Operation::Substitute(Substitute {
            of: Expr::Sym(n), ..
        }) => equations_kind(steps, n),
        _ => None,
    }
}

impl Validator<'_> {
    pub(super) fn motion_plot(
        &self,
        p: &Spanned<RawPlot>,
        field: &str,
        steps: &[AuthorStep],
        coordinates: &BTreeMap<String, String>,
    ) -> Result<PlotRequest, SceneError> {
        let rp = p.get_ref();
        let start = p.span().start;
        if rp.over.is_some() || rp.range.is_some() || rp.samples.is_some() {
            return Err(self.err(
                start,
                field,
                "`over`, `range` and `samples` belong to a tensor-sweep or an expression plot",
            ));
        }
        if rp.inertia.is_some() || rp.omega.is_some() {
            return Err(self.err(
                start,
                field,
                "`inertia` and `omega` belong to the free-body plot kinds",
            ));
        }
        let step = rp.step.as_ref().ok_or_else(|| {
            self.err(
                start,
                &format!("{field}.step"),
                "a motion plot needs `step`, a step of equations of motion (from `lagrange`)",
            )
        })?;
        let name = |t: &crate::scene::raw::Text, want_linear: bool, key: &str| {
            let what = if want_linear {
                "linear equations (from `linearise`)"
            } else {
                "equations of motion (from `lagrange`, or `substitute` of them)"
            };
            match equations_kind(steps, t.get_ref()) {
                Some(linear) if linear == want_linear => Ok(t.get_ref().clone()),
                _ => Err(self.err(
                    content_start(t),
                    &format!("{field}.{key}"),
                    format!("`{}` is not a step of {what}", t.get_ref()),
                )),
            }
        };
        let step = name(step, false, "step")?;
        let linear = rp
            .linear
            .as_ref()
            .map(|l| name(l, true, "linear"))
            .transpose()?;
        let from = self.motion_start(rp, field, coordinates)?;
        let t = rp.t.as_ref().ok_or_else(|| {
            self.err(
                start,
                &format!("{field}.t"),
                "a motion plot needs `t`, the end time",
            )
        })?;
        if !(t.get_ref().is_finite() && *t.get_ref() > 0.0 && *t.get_ref() <= MAX_PLOT_TIME) {
            return Err(self.err(
                t.span().start,
                &format!("{field}.t"),
                format!("the end time must be a positive number up to {MAX_PLOT_TIME:e}"),
            ));
        }
        Ok(PlotRequest::Motion {
            step,
            linear,
            start: from,
            t: *t.get_ref(),
        })
    }

    /// A motion plot's `start`: a finite value for each coordinate or rate it gives.
    fn motion_start(
        &self,
        rp: &RawPlot,
        field: &str,
        coordinates: &BTreeMap<String, String>,
    ) -> Result<BTreeMap<String, f64>, SceneError> {
        let mut from = BTreeMap::new();
        for (k, v) in &rp.start {
            let q = k.get_ref();
            let base = q.trim_end_matches('\'');
            if !coordinates.contains_key(base) || q.len() > base.len() + 1 {
                return Err(self.err(
                    k.span().start,
                    &format!("{field}.start"),
                    format!("`{q}` is not a coordinate or its rate (q or q')"),
                ));
            }
            if !v.get_ref().is_finite() {
                return Err(self.err(
                    v.span().start,
                    &format!("{field}.start"),
                    "a start must be a finite number",
                ));
            }
            from.insert(q.clone(), *v.get_ref());
        }
        Ok(from)
    }
}
