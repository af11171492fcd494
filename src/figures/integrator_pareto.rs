//! The integrator Pareto figure: error at the end time against right-hand-side evaluations
//! for every integrator and step, with the Pareto front.

use super::frame::{body_text, fig};
use super::{ERROR_FLOOR, FigureError, colour};
use crate::base::format::{sci, short};
use crate::model::fidelity::Fidelity;
use crate::model::figure::{Accuracy, Figure, Legend, Mark, Scale, Series};
use crate::model::moments::Moments;
use crate::numeric::free_body::ExactSolution;
use crate::numeric::integrators::{Method, Resolution, integrate};
use crate::numeric::pareto::pareto_front;
use nalgebra::Vector3;

/// The integrators compared, as the figure names them.
const METHODS: [(&str, Method); 4] = [
    ("RK4", Method::Rk4),
    ("Strang splitting", Method::Splitting),
    ("triple jump", Method::Splitting4),
    ("Dormand–Prince 5(4)", Method::Dopri),
];

/// Every integrator over a ladder of steps (tolerances for Dormand–Prince): its error at
/// `t_end` against the exact solution, relative to |ω(0)|, against its right-hand-side
/// evaluations, and the Pareto front over all of them. The fidelity sets the finest rung.
pub fn integrator_pareto(
    i: &Moments,
    w0: Vector3<f64>,
    t_end: f64,
    fid: &Fidelity,
) -> Result<Figure, FigureError> {
    let exact = ExactSolution::new(i, w0).omega(t_end);
    let (steps, tols) = settings(fid);
    let mut series = Vec::new();
    let mut accuracy = Vec::new();
    let mut sentences = Vec::new();
    let mut all = Vec::new();
    for (colour, (name, method)) in METHODS.into_iter().enumerate() {
        let settings: Vec<Resolution> = if method == Method::Dopri {
            tols.iter().map(|t| Resolution::Tolerance(*t)).collect()
        } else {
            steps.iter().map(|h| Resolution::Step(*h)).collect()
        };
        let (points, sentence, run_accuracy) =
            method_runs(i, w0, (t_end, exact), name, method, settings)?;
        sentences.push(sentence);
        accuracy.push(run_accuracy);
        all.extend(points.iter().copied());
        series.push(Series {
            name: name.into(),
            mark: Mark::Points,
            colour,
            points,
        });
    }
    let front = pareto_front(&all);
    series.push(Series {
        name: "Pareto front".into(),
        mark: Mark::Line,
        colour: colour::REFERENCE,
        points: front.clone(),
    });
    let desc = format!(
        "Error of ω({t_end}) against the exact solution, relative to |ω(0)|, against the \
         right-hand-side evaluations it cost, log-log, for {} with every integrator at steps {} \
         and Dormand–Prince at tolerances {}. Finest settings: {}. The Pareto front (the runs no \
         other run beats on both error and cost) has {} of the {} runs. Errors below {} are drawn \
         at that floor.",
        body_text(i, &w0),
        steps
            .iter()
            .map(|h| h.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        tols.iter()
            .map(|t| short(*t))
            .collect::<Vec<_>>()
            .join(", "),
        sentences.join("; "),
        front.len(),
        all.len(),
        sci(ERROR_FLOOR)
    );
    let mut f = fig(
        "integrator-pareto",
        "Integrators: error against cost".into(),
        desc,
        "right-hand-side evaluations",
        "relative error at the end",
        series,
    );
    f.x_scale = Scale::Log;
    f.y_scale = Scale::Log;
    f.legend = Legend::LowerLeft;
    f.accuracy = accuracy;
    Ok(f)
}

/// An integrator's (cost, error) points, the sentence on its finest setting, and that setting's
/// accuracy.
type MethodRuns = (Vec<(f64, f64)>, String, Accuracy);

/// One integrator at each of its settings: its (cost, error) points, the sentence on its finest
/// setting, and that setting's accuracy.
fn method_runs(
    i: &Moments,
    w0: Vector3<f64>,
    (t_end, exact): (f64, Vector3<f64>),
    name: &str,
    method: Method,
    settings: Vec<Resolution>,
) -> Result<MethodRuns, FigureError> {
    let mut points = Vec::new();
    let mut runs = Vec::new();
    for r in settings {
        let run = integrate(i, w0, t_end, method, r, 0)?;
        let error = (run.omega - exact).norm() / w0.norm();
        points.push((run.rhs_evaluations as f64, error.max(ERROR_FLOOR)));
        runs.push((r, run, error));
    }
    let (r, finest, error) = runs.last().ok_or(FigureError::NoSettings)?;
    let setting = match r {
        Resolution::Step(h) => format!("{name}, h = {h}"),
        Resolution::Tolerance(t) => format!("{name}, tol {}", short(*t)),
    };
    let sentence = format!(
        "{setting}: {} in {} right-hand sides",
        sci(*error),
        finest.rhs_evaluations
    );
    let accuracy = Accuracy {
        result: format!("ω({t_end}), {} settings, the finest", runs.len()),
        method: setting,
        true_error: Some(*error),
        estimated_error: Some(finest.energy_drift.max(finest.momentum_drift)),
        cost: runs.iter().map(|(_, r, _)| r.rhs_evaluations).sum(),
        unit: "right-hand sides".into(),
        seconds: runs.iter().map(|(_, r, _)| r.seconds).sum(),
    };
    Ok((points, sentence, accuracy))
}

/// The fixed steps and the tolerances tried, down to the fidelity's finest.
fn settings(fid: &Fidelity) -> (Vec<f64>, Vec<f64>) {
    let finest_step = fid.ode_step(0.005) * 0.999;
    let finest_tol = fid.ode_tolerance(1e-12) * 0.999;
    let steps: Vec<f64> = [0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.0025, 0.00125]
        .into_iter()
        .filter(|h| *h >= finest_step)
        .collect();
    let tols: Vec<f64> = [1e-3, 1e-5, 1e-7, 1e-9, 1e-11, 1e-13]
        .into_iter()
        .filter(|t| *t >= finest_tol)
        .collect();
    (steps, tols)
}
