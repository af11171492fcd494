//! The accuracy rows of the free-body figures: the exact solution's own drift, an
//! integration's error against it, and several runs merged into one row.

use crate::model::figure::Accuracy;
use crate::model::moments::Moments;
use crate::numeric::free_body::{ExactSolution, invariants};
use crate::numeric::integrators::Run;
use nalgebra::Vector3;

/// The exact solution sampled at `times`: it is the reference, so its own error shows only as
/// the drift of 2T and |L| along the samples (round-off in the elliptic functions).
pub(super) fn exact_accuracy(
    result: &str,
    i: &Moments,
    w0: &Vector3<f64>,
    times: &[f64],
) -> Accuracy {
    let start = std::time::Instant::now();
    let sol = ExactSolution::new(i, *w0);
    let (t0, l0) = invariants(i, w0);
    let drift = times
        .iter()
        .map(|t| {
            let (tt, l) = invariants(i, &sol.omega(*t));
            ((tt - t0) / t0).abs().max(((l - l0) / l0).abs())
        })
        .fold(0.0, f64::max);
    Accuracy {
        result: result.into(),
        method: "exact (Jacobi elliptic functions)".into(),
        true_error: None,
        estimated_error: Some(drift),
        cost: times.len() as u64,
        unit: "evaluations".into(),
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// An integration's accuracy: its error against the exact solution at every traced sample
/// (relative to |ω(0)|), and the invariant drift it would show without one.
pub(super) fn run_accuracy(
    result: &str,
    setting: String,
    run: &Run,
    i: &Moments,
    w0: &Vector3<f64>,
) -> Accuracy {
    let sol = ExactSolution::new(i, *w0);
    let true_error = run
        .trace
        .iter()
        .map(|(t, w, _)| (w - sol.omega(*t)).norm() / w0.norm())
        .chain([(run.omega - sol.omega(run.trace.last().map_or(0.0, |p| p.0))).norm() / w0.norm()])
        .fold(0.0, f64::max);
    Accuracy {
        result: result.into(),
        method: setting,
        true_error: Some(true_error),
        estimated_error: Some(run.energy_drift.max(run.momentum_drift)),
        cost: run.rhs_evaluations,
        unit: "right-hand sides".into(),
        seconds: run.seconds,
    }
}

/// Several runs of one method drawn as one result: the worst errors and the total cost.
pub(super) fn merged(result: &str, parts: Vec<Accuracy>) -> Accuracy {
    let worst = |f: fn(&Accuracy) -> Option<f64>| parts.iter().filter_map(f).reduce(f64::max);
    Accuracy {
        result: format!("{result} ({} runs)", parts.len()),
        method: parts.first().map_or(String::new(), |p| p.method.clone()),
        true_error: worst(|a| a.true_error),
        estimated_error: worst(|a| a.estimated_error),
        cost: parts.iter().map(|a| a.cost).sum(),
        unit: parts.first().map_or(String::new(), |p| p.unit.clone()),
        seconds: parts.iter().map(|a| a.seconds).sum(),
    }
}
