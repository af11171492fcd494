//! ω(t) by the exact solution, with Dormand–Prince points.

use super::FigureError;
use super::accuracy::{exact_accuracy, run_accuracy};
use super::frame::{body_text, fig, motion_text, times};
use crate::base::format::{sci, short};
use crate::model::fidelity::Fidelity;
use crate::model::figure::{Figure, Legend, Mark, Series};
use crate::model::moments::Moments;
use crate::numeric::free_body::ExactSolution;
use crate::numeric::integrators::{Method, Resolution, integrate};
use nalgebra::Vector3;

pub(super) fn omega_vs_time(
    i: &Moments,
    w0: Vector3<f64>,
    t_end: f64,
    fid: &Fidelity,
) -> Result<Figure, FigureError> {
    let sol = ExactSolution::new(i, w0);
    let n = fid.samples(400);
    let tol = fid.ode_tolerance(1e-10);
    let mut series = Vec::new();
    let dp = integrate(i, w0, t_end, Method::Dopri, Resolution::Tolerance(tol), 24)?;
    for (k, name) in ["ω1", "ω2", "ω3"].into_iter().enumerate() {
        series.push(Series {
            name: format!("{name} exact"),
            mark: Mark::Line,
            colour: k,
            points: (0..=n)
                .map(|j| {
                    let t = t_end * j as f64 / n as f64;
                    (t, sol.omega(t)[k])
                })
                .collect(),
        });
        series.push(Series {
            name: String::new(),
            mark: Mark::Points,
            colour: k,
            points: dp.trace.iter().map(|(t, w, _)| (*t, w[k])).collect(),
        });
    }
    let dots = run_accuracy(
        "ω(t) dots",
        format!("Dormand–Prince 5(4), tol {}", short(tol)),
        &dp,
        i,
        &w0,
    );
    let desc = format!(
        "Body-frame angular velocity of the free body with {} over 0 ≤ t ≤ {t_end}: {}. Lines: \
         the exact solution; dots: Dormand–Prince 5(4) at tol {} ({} right-hand sides), at most \
         {} from it relative to |ω(0)|.",
        body_text(i, &w0),
        motion_text(&sol),
        short(tol),
        dp.rhs_evaluations,
        sci(dots.true_error.unwrap_or(0.0))
    );
    let mut f = fig(
        "omega-vs-time",
        "Angular velocity in the body frame".into(),
        desc,
        "t",
        "ω",
        series,
    );
    f.legend = Legend::LowerRight;
    f.accuracy = vec![
        exact_accuracy("ω(t) curves", i, &w0, &times(t_end, n)),
        dots,
    ];
    Ok(f)
}
