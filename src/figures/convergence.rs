//! The convergence figure: quadrature error against points for every method, with each
//! method's error law and the Pareto front.

use super::{ERROR_FLOOR, FigureError, colour};
use crate::base::format::{count, sci};
use crate::model::fidelity::Fidelity;
use crate::model::figure::{Accuracy, Figure, Legend, Mark, Scale, Series};
use crate::model::prose::Prose;
use crate::numeric::body::{NumBody, NumShape};
use crate::numeric::pareto::pareto_front;
use crate::numeric::quadrature::{Method, QuadratureRun, point_count, run};
use nalgebra::Matrix3;

/// The levels swept per method: about one per factor of 2–10 in points, up to ~3·10⁵ points.
pub(super) fn sweep(shape: &NumShape) -> Result<Vec<(Method, Vec<usize>)>, FigureError> {
    use Method::*;
    let mc = (MonteCarlo, vec![100, 1_000, 10_000, 100_000, 1_000_000]);
    Ok(match shape {
        NumShape::Box { .. } | NumShape::Plate { .. } => vec![
            (GaussLegendre, vec![1, 2, 3, 4]),
            (MidpointLattice, vec![2, 4, 8, 16, 32, 64, 128]),
            (VertexLattice, vec![2, 4, 8, 16, 32, 64, 128]),
            mc,
        ],
        NumShape::Rod { .. } => vec![
            (GaussLegendre, vec![1, 2, 3, 4]),
            (MidpointLattice, vec![2, 8, 32, 128, 512, 2048]),
            (VertexLattice, vec![2, 8, 32, 128, 512, 2048]),
            mc,
        ],
        NumShape::Hoop { .. } => vec![(PeriodicTrapezoid, (1..=8).collect()), mc],
        NumShape::Points(_) => {
            return Err(FigureError::PointMasses);
        }
        _ => vec![(GaussLegendre, vec![1, 2, 3, 4, 5]), mc],
    })
}

/// Slope of log(error) against log(points) between the first and last runs above round-off,
/// when at least three runs are.
pub(super) fn slope(runs: &[QuadratureRun]) -> Option<f64> {
    let above: Vec<&QuadratureRun> = runs.iter().filter(|r| r.error > 1e-13).collect();
    if above.len() < 3 {
        return None;
    }
    let (a, b) = (above.first()?, above.last()?);
    (b.points > a.points)
        .then(|| (b.error / a.error).log10() / (b.points as f64 / a.points as f64).log10())
}

pub fn convergence(
    nb: &NumBody,
    exact: &Matrix3<f64>,
    seed: u64,
    slug: String,
    fidelity: &Fidelity,
) -> Result<Figure, FigureError> {
    let mut series = Vec::new();
    let mut sentences = Vec::new();
    let mut accuracy = Vec::new();
    for (colour, (method, levels)) in sweep(&nb.shape)?.into_iter().enumerate() {
        // The fidelity's cost cap bounds the sweep (at least two levels, to show a slope).
        let cap = fidelity.max_points();
        let runs: Vec<QuadratureRun> = levels
            .iter()
            .enumerate()
            .filter(|(k, l)| *k < 2 || point_count(&nb.shape, method, **l) <= cap)
            .map(|(_, &l)| run(nb, method, l, exact, seed.wrapping_add(l as u64)))
            .collect();
        series.push(Series {
            name: method.name().into(),
            mark: Mark::Points,
            colour,
            points: runs
                .iter()
                .map(|r| (r.points as f64, r.error.max(ERROR_FLOOR)))
                .collect(),
        });
        series.push(Series {
            name: String::new(),
            mark: Mark::Dashed,
            colour,
            points: runs
                .iter()
                .map(|r| (r.points as f64, r.predicted_error.max(ERROR_FLOOR)))
                .collect(),
        });
        accuracy.push(method_accuracy(method, &runs));
        sentences.push(method_sentence(method, &runs));
    }
    let all: Vec<(f64, f64)> = series
        .iter()
        .filter(|s| s.mark == Mark::Points)
        .flat_map(|s| s.points.iter().copied())
        .collect();
    series.push(Series {
        name: "Pareto front".into(),
        mark: Mark::Line,
        colour: colour::REFERENCE,
        points: pareto_front(&all),
    });
    Ok(Figure {
        slug,
        title: format!("Quadrature convergence: {}", nb.label),
        desc: Prose::default().text(&format!(
            "Relative error of the inertia tensor of {} against the number of points, log-log; \
             dots measured, dashed lines the error law (Monte Carlo: one standard error). {}. \
             Errors below {} are drawn at that floor.",
            nb.label,
            sentences.join("; "),
            sci(ERROR_FLOOR)
        )),
        x_label: "points".into(),
        y_label: "relative error".into(),
        x_scale: Scale::Log,
        y_scale: Scale::Log,
        equal_aspect: false,
        series,
        labels: Vec::new(),
        legend: Legend::LowerRight,
        accuracy,
    })
}

/// A rule's accuracy at its finest level, and the cost of all its levels.
fn method_accuracy(method: Method, runs: &[QuadratureRun]) -> Accuracy {
    let last = &runs[runs.len() - 1];
    Accuracy {
        result: format!("{} runs, the finest", runs.len()),
        method: method.name().into(),
        true_error: Some(last.error),
        estimated_error: Some(last.predicted_error),
        cost: runs.iter().map(|r| r.points as u64).sum(),
        unit: "points".into(),
        seconds: runs.iter().map(|r| r.seconds).sum(),
    }
}

/// A rule's errors from its coarsest to its finest level, its slope, and where round-off starts.
fn method_sentence(method: Method, runs: &[QuadratureRun]) -> String {
    let (first, last) = (&runs[0], &runs[runs.len() - 1]);
    let mut s = format!(
        "{}: {} at {} to {} at {}",
        method.name(),
        sci(first.error),
        count(first.points, "point"),
        sci(last.error),
        last.points
    );
    if let Some(k) = slope(runs) {
        s.push_str(&format!(", slope {k:.2}"));
    }
    if let Some(exact_from) = runs.iter().find(|r| r.error <= 1e-13) {
        s.push_str(&format!(
            ", round-off from {}",
            count(exact_from.points, "point")
        ));
    }
    s
}
