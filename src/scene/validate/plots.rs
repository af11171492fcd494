//! `[[plot]]`: the plots a scene asks for, with their ranges and free-body settings.

use super::{MAX_PLOT_RADIANS, MAX_PLOT_TIME, MAX_PLOTS, Validator, content_start};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawPlot, RawScene};
use crate::scene::step::AuthorStep;
use crate::scene::types::{FreeBodyPlot, FreeInertia, PlotRequest};
use std::collections::{BTreeMap, BTreeSet};
use toml::Spanned;

impl Validator<'_> {
    /// Every plot, in order.
    pub(super) fn plots(
        &self,
        raw: &RawScene,
        symbols: &BTreeMap<String, String>,
        values: &BTreeMap<String, f64>,
        steps: &[AuthorStep],
        coordinates: &BTreeMap<String, String>,
    ) -> Result<Vec<PlotRequest>, SceneError> {
        if let Some(p) = raw.plots.get(MAX_PLOTS) {
            return Err(self.err(
                p.span().start,
                &format!("plot[{MAX_PLOTS}]"),
                format!(
                    "a scene draws at most {MAX_PLOTS} plots, and this one has {}: split them \
                     across scenes",
                    raw.plots.len()
                ),
            ));
        }
        let mut plots = Vec::new();
        for (i, p) in raw.plots.iter().enumerate() {
            let field = format!("plot[{i}]");
            if p.get_ref().kind.get_ref() != "expression" && !p.get_ref().at.is_empty() {
                return Err(self.err(
                    p.span().start,
                    &format!("{field}.at"),
                    "`at` belongs to an expression plot",
                ));
            }
            plots.push(match p.get_ref().kind.get_ref().as_str() {
                "motion" => self.motion_plot(p, &field, steps, coordinates)?,
                "expression" => self.expression_plot(p, &field, steps, symbols, coordinates)?,
                _ => self.plot(p, &field, symbols, values)?,
            });
        }
        Ok(plots)
    }

    fn plot(
        &self,
        p: &Spanned<RawPlot>,
        field: &str,
        symbols: &BTreeMap<String, String>,
        values: &BTreeMap<String, f64>,
    ) -> Result<PlotRequest, SceneError> {
        let rp = p.get_ref();
        let start = p.span().start;
        if rp.step.is_some() || rp.linear.is_some() || !rp.start.is_empty() {
            return Err(self.err(
                start,
                field,
                "`step`, `linear` and `start` belong to a motion plot (and `step` to an expression \
                 plot)",
            ));
        }
        let sweep_fields = rp.over.is_some() || rp.range.is_some() || rp.samples.is_some();
        let body_fields = rp.inertia.is_some() || rp.omega.is_some() || rp.t.is_some();
        if let Some((_, kind)) = FreeBodyPlot::ALL
            .iter()
            .find(|(n, _)| n == rp.kind.get_ref())
        {
            if sweep_fields {
                return Err(self.err(
                    start,
                    field,
                    "`over`, `range` and `samples` belong to a tensor-sweep",
                ));
            }
            return self.free_body_plot(p, field, *kind, symbols, values);
        }
        if body_fields {
            return Err(self.err(
                start,
                field,
                "`inertia`, `omega` and `t` belong to the free-body plot kinds",
            ));
        }
        let request = match rp.kind.get_ref().as_str() {
            "tensor-sweep" => self.tensor_sweep(p, field, symbols)?,
            "convergence" => PlotRequest::Convergence,
            "principal-axes" => PlotRequest::PrincipalAxes,
            other => {
                return Err(self.err(
                    content_start(&rp.kind),
                    &format!("{field}.kind"),
                    format!(
                        "unknown plot kind `{other}`{}; the kinds are {}",
                        crate::base::suggest::did_you_mean(
                            other,
                            PlotRequest::KINDS.iter().copied()
                        ),
                        PlotRequest::KINDS.join(", ")
                    ),
                ));
            }
        };
        if sweep_fields && !matches!(request, PlotRequest::TensorSweep { .. }) {
            return Err(self.err(
                start,
                field,
                format!(
                    "`over`, `range` and `samples` belong to a tensor-sweep, not a {}",
                    request.kind()
                ),
            ));
        }
        Ok(request)
    }

    /// A plot of the free body's motion: its moments (given, or the scene's principal ones),
    /// ω(0) and the end time, each within what a plot integrates.
    fn free_body_plot(
        &self,
        p: &Spanned<RawPlot>,
        field: &str,
        kind: FreeBodyPlot,
        symbols: &BTreeMap<String, String>,
        values: &BTreeMap<String, f64>,
    ) -> Result<PlotRequest, SceneError> {
        let rp = p.get_ref();
        let start = p.span().start;
        let inertia = match rp.inertia.as_ref() {
            Some(v) if v.get_ref().as_str() == Some("principal") => FreeInertia::Principal,
            _ => {
                let inertia = self.free_body_triple(p, field, "inertia", symbols, values)?;
                crate::model::moments::Moments::new(inertia).map_err(|m| {
                    self.err(
                        rp.inertia.as_ref().map_or(start, |v| v.span().start),
                        &format!("{field}.inertia"),
                        m.to_string(),
                    )
                })?;
                FreeInertia::Given(inertia)
            }
        };
        let omega = self.free_body_triple(p, field, "omega", symbols, values)?;
        let omega_at = rp.omega.as_ref().map_or(start, |v| v.span().start);
        if omega.iter().all(|x| *x == 0.0) {
            return Err(self.err(
                omega_at,
                &format!("{field}.omega"),
                "omega must not be zero",
            ));
        }
        // The scene's own moments are checked against ω(0) when they are known (figures).
        if let FreeInertia::Given(inertia) = inertia {
            let moments = crate::model::moments::Moments(inertia);
            let w0 = nalgebra::Vector3::from(omega);
            if let Some(why) = crate::model::moments::beyond_double_precision(&moments, &w0) {
                return Err(self.err(omega_at, &format!("{field}.omega"), why.to_string()));
            }
        }
        let t = rp.t.as_ref().ok_or_else(|| {
            self.err(
                start,
                &format!("{field}.t"),
                format!("a {} plot needs `t`, the end time", kind.name()),
            )
        })?;
        if !(t.get_ref().is_finite() && *t.get_ref() > 0.0) {
            return Err(self.err(
                t.span().start,
                &format!("{field}.t"),
                "the end time must be a positive number",
            ));
        }
        // The plots integrate with fixed steps of about 0.05 (a quarter of that at
        // reference fidelity) and draw a few hundred points: these bounds keep every plot
        // within a few million steps and its curves readable.
        let turns = t.get_ref() * omega.iter().fold(0.0f64, |m, w| m.max(w.abs()));
        if *t.get_ref() > MAX_PLOT_TIME || turns > MAX_PLOT_RADIANS {
            return Err(self.err(
                t.span().start,
                &format!("{field}.t"),
                format!(
                    "t = {} (t·|ω| = {turns:.3e} radians) is beyond what a plot integrates: \
                     keep t ≤ {MAX_PLOT_TIME:e} and t·|ω| ≤ {MAX_PLOT_RADIANS:e}, or use \
                     `mechbook spin` for long runs",
                    t.get_ref()
                ),
            ));
        }
        Ok(PlotRequest::FreeBody {
            kind,
            inertia,
            omega,
            t: *t.get_ref(),
        })
    }

    /// A tensor-sweep over a declared symbol's range.
    fn tensor_sweep(
        &self,
        p: &Spanned<RawPlot>,
        field: &str,
        symbols: &BTreeMap<String, String>,
    ) -> Result<PlotRequest, SceneError> {
        let start = p.span().start;
        let rp = p.get_ref();
        let over = rp.over.as_ref().ok_or_else(|| {
            self.err(
                start,
                &format!("{field}.over"),
                "a tensor-sweep needs `over`, the symbol on the x axis",
            )
        })?;
        if !symbols.contains_key(over.get_ref()) {
            return Err(self.err(
                content_start(over),
                &format!("{field}.over"),
                format!("`{}` is not a declared symbol", over.get_ref()),
            ));
        }
        let (from, to) = self.plot_range(p, field, "a tensor-sweep")?;
        let samples = self.plot_samples(p, field, 7)?;
        Ok(PlotRequest::TensorSweep {
            over: over.get_ref().clone(),
            from,
            to,
            samples,
        })
    }

    /// A plot's `range = [from, to]`: two expressions of numbers and π, from < to.
    pub(super) fn plot_range(
        &self,
        p: &Spanned<RawPlot>,
        field: &str,
        what: &str,
    ) -> Result<(f64, f64), SceneError> {
        let range = p.get_ref().range.as_ref().ok_or_else(|| {
            self.err(
                p.span().start,
                &format!("{field}.range"),
                format!("{what} needs `range = [from, to]`"),
            )
        })?;
        let ends: Vec<f64> = range
            .get_ref()
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let f = format!("{field}.range[{i}]");
                let e = self.expr_str(
                    t.get_ref(),
                    content_start(t),
                    &f,
                    &BTreeSet::from(["pi".to_string()]),
                )?;
                e.eval(&|_| None)
                    .map_err(|m| self.err(content_start(t), &f, m.to_string()))
            })
            .collect::<Result<_, _>>()?;
        if ends.len() != 2 || !ends.iter().all(|x| x.is_finite()) || ends[0] >= ends[1] {
            return Err(self.err(
                range.span().start,
                &format!("{field}.range"),
                "expected two numbers [from, to] with from < to",
            ));
        }
        Ok((ends[0], ends[1]))
    }

    /// A plot's `samples`: 2 to 1000, `default` when not given.
    pub(super) fn plot_samples(
        &self,
        p: &Spanned<RawPlot>,
        field: &str,
        default: usize,
    ) -> Result<usize, SceneError> {
        p.get_ref().samples.as_ref().map_or(Ok(default), |n| {
            usize::try_from(*n.get_ref())
                .ok()
                .filter(|k| (2..=1000).contains(k))
                .ok_or_else(|| {
                    self.err(
                        n.span().start,
                        &format!("{field}.samples"),
                        "samples is a whole number from 2 to 1000",
                    )
                })
        })
    }

    /// A free-body plot's `inertia` or `omega`: three numbers, or expressions of the scene's
    /// symbols evaluated at their `[numeric]` values; finite and not subnormal.
    fn free_body_triple(
        &self,
        p: &Spanned<RawPlot>,
        field: &str,
        name: &str,
        symbols: &BTreeMap<String, String>,
        values: &BTreeMap<String, f64>,
    ) -> Result<[f64; 3], SceneError> {
        let rp = p.get_ref();
        let v = if name == "inertia" {
            &rp.inertia
        } else {
            &rp.omega
        };
        let field = format!("{field}.{name}");
        let principal = if name == "inertia" {
            ", or \"principal\" for the scene's own body"
        } else {
            ""
        };
        let v = v.as_ref().ok_or_else(|| {
            self.err(
                p.span().start,
                &field,
                format!(
                    "a {} plot needs `{name} = [x, y, z]`{principal}",
                    rp.kind.get_ref()
                ),
            )
        })?;
        let at = v.span().start;
        let wrong = || {
            self.err(
                at,
                &field,
                format!(
                    "expected three numbers or expressions of the scene's symbols, such as \
                     [1, 2, \"3*m*a^2\"]{principal}"
                ),
            )
        };
        let items = v.get_ref().as_array().ok_or_else(wrong)?;
        if items.len() != 3 {
            return Err(self.err(
                at,
                &field,
                format!("expected 3 components, found {}", items.len()),
            ));
        }
        let mut allowed: BTreeSet<String> = symbols.keys().cloned().collect();
        allowed.insert("pi".into());
        let mut arr = [0.0; 3];
        for (k, item) in items.iter().enumerate() {
            let f = format!("{field}[{k}]");
            arr[k] = match item {
                toml::Value::Integer(n) => *n as f64,
                toml::Value::Float(x) => *x,
                toml::Value::String(text) => {
                    let e = self.expr_str(text, at, &f, &allowed)?;
                    e.eval(&|s| values.get(s).copied()).map_err(|m| match m {
                        crate::cas::EvalError::NoValue(s) => self.err(
                            at,
                            &f,
                            format!("`{s}` has no value: give it one under [numeric] values"),
                        ),
                        m => self.err(at, &f, m.to_string()),
                    })?
                }
                _ => return Err(wrong()),
            };
        }
        self.full_precision(arr, at, &field)
    }

    /// Three numbers that are finite and keep their digits: a subnormal one has lost some, and
    /// every product with it is wrong.
    fn full_precision(
        &self,
        arr: [f64; 3],
        at: usize,
        field: &str,
    ) -> Result<[f64; 3], SceneError> {
        if arr.iter().any(|x| !x.is_finite()) {
            return Err(self.err(at, field, "the values must be finite numbers"));
        }
        if let Some(x) = crate::base::float::first_subnormal(&arr).map(|k| arr[k]) {
            return Err(self.err(
                at,
                field,
                format!(
                    "{x:e} is below {:e}, where double precision keeps its digits: write 0, or \
                     use other units",
                    f64::MIN_POSITIVE
                ),
            ));
        }
        Ok(arr)
    }
}
