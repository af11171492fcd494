//! The drift of the invariants 2T and |L| against time for each integrator.

use super::accuracy::run_accuracy;
use super::frame::{body_text, fig};
use super::{ERROR_FLOOR, FigureError};
use crate::base::format::{sci, short};
use crate::model::fidelity::Fidelity;
use crate::model::figure::{Figure, Legend, Mark, Scale, Series};
use crate::model::moments::Moments;
use crate::numeric::free_body::invariants;
use crate::numeric::integrators::{Method, Resolution, integrate};
use nalgebra::Vector3;

pub(super) fn drift(
    i: &Moments,
    w0: Vector3<f64>,
    t_end: f64,
    fid: &Fidelity,
) -> Result<Figure, FigureError> {
    let (t0, l0) = invariants(i, &w0);
    let (h, tol) = (fid.ode_step(0.05), fid.ode_tolerance(1e-9));
    let runs = runs(h, tol);
    let mut series = Vec::new();
    let mut parts = Vec::new();
    let mut accuracy = Vec::new();
    for (k, (name, m, r)) in runs.into_iter().enumerate() {
        let run = integrate(i, w0, t_end, m, r, fid.samples(200))?;
        accuracy.push(run_accuracy("ω(t)", name.clone(), &run, i, &w0));
        let energy: Vec<(f64, f64)> = run
            .trace
            .iter()
            .filter(|(t, ..)| *t > 0.0)
            .map(|(t, w, _)| (*t, ((invariants(i, w).0 - t0).abs() / t0).max(ERROR_FLOOR)))
            .collect();
        let length: Vec<(f64, f64)> = run
            .trace
            .iter()
            .filter(|(t, ..)| *t > 0.0)
            .map(|(t, w, _)| (*t, ((invariants(i, w).1 - l0).abs() / l0).max(ERROR_FLOOR)))
            .collect();
        parts.push(format!(
            "{name}: energy {} and |L| {} at the end, {} right-hand sides",
            sci(energy.last().map_or(0.0, |p| p.1)),
            sci(length.last().map_or(0.0, |p| p.1)),
            run.rhs_evaluations
        ));
        series.push(Series {
            name: format!("{name}: energy"),
            mark: Mark::Line,
            colour: k,
            points: energy,
        });
        series.push(Series {
            name: String::new(),
            mark: Mark::Dashed,
            colour: k,
            points: length,
        });
    }
    let desc = format!(
        "Relative error of the energy 2T (solid) and of |L| (dashed) against time for the free body \
         with {}, log scale; errors below {} are drawn at that floor. {}. RK4 and Dormand–Prince \
         drift; the splittings keep |L| at round-off and their energy error bounded.",
        body_text(i, &w0),
        sci(ERROR_FLOOR),
        parts.join("; ")
    );
    let mut f = fig(
        "drift",
        "Invariant drift of each integrator".into(),
        desc,
        "t",
        "relative error",
        series,
    );
    f.y_scale = Scale::Log;
    f.legend = Legend::LowerRight;
    f.accuracy = accuracy;
    Ok(f)
}

/// The four integrators compared: RK4 and the splittings at step `h`, Dormand–Prince at `tol`.
fn runs(h: f64, tol: f64) -> [(String, Method, Resolution); 4] {
    [
        (format!("RK4 h = {h}"), Method::Rk4, Resolution::Step(h)),
        (
            format!("Dormand–Prince tol {}", short(tol)),
            Method::Dopri,
            Resolution::Tolerance(tol),
        ),
        (
            format!("Strang splitting h = {h}"),
            Method::Splitting,
            Resolution::Step(h),
        ),
        (
            format!("triple jump h = {h}"),
            Method::Splitting4,
            Resolution::Step(h),
        ),
    ]
}
