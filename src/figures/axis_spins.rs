//! The same small wobble started about each principal axis: only the intermediate one departs.

use super::FigureError;
use super::accuracy::{exact_accuracy, merged};
use super::frame::{fig, sorted_axes, times};
use crate::model::fidelity::Fidelity;
use crate::model::figure::{Figure, Mark, Series};
use crate::model::moments::Moments;
use crate::numeric::free_body::ExactSolution;
use nalgebra::Vector3;

/// The largest component of ω(0) is the spin and the other two the wobble; the same start is
/// turned onto each principal axis in turn, and the exact solution gives ω's angle from it.
pub(super) fn axis_spins(
    i: &Moments,
    w0: Vector3<f64>,
    t_end: f64,
    fid: &Fidelity,
) -> Result<Figure, FigureError> {
    let k0 = w0.iamax();
    let (spin, wobble) = (w0[k0], [w0[(k0 + 1) % 3], w0[(k0 + 2) % 3]]);
    if wobble.iter().any(|x| x.abs() >= spin.abs()) {
        return Err(FigureError::NoLargestComponent);
    }
    let [small, middle, large] = sorted_axes(i);
    let n = fid.samples(600);
    let mut series = Vec::new();
    let mut exact_runs = Vec::new();
    let mut largest = [0.0f64; 3];
    for k in 0..3 {
        let mut w = Vector3::zeros();
        w[k] = spin;
        w[(k + 1) % 3] = wobble[0];
        w[(k + 2) % 3] = wobble[1];
        let sol = ExactSolution::new(i, w);
        exact_runs.push(exact_accuracy("", i, &w, &times(t_end, n)));
        let points: Vec<(f64, f64)> = (0..=n)
            .map(|j| {
                let t = t_end * j as f64 / n as f64;
                let wt = sol.omega(t);
                let deg = (wt[k] / wt.norm()).clamp(-1.0, 1.0).acos().to_degrees();
                largest[k] = largest[k].max(deg);
                (t, deg)
            })
            .collect();
        series.push(Series {
            name: format!("about axis {} (I{} = {})", k + 1, k + 1, i.0[k]),
            mark: if k == middle {
                Mark::Line
            } else {
                Mark::Dashed
            },
            colour: k,
            points,
        });
    }
    let desc = description(i, spin, wobble, t_end, largest, [small, middle, large]);
    let mut f = fig(
        "axis-spins",
        "Spin about each principal axis".into(),
        desc,
        "t",
        "angle from the starting axis / degrees",
        series,
    );
    f.accuracy = vec![merged("angle from each axis", exact_runs)];
    Ok(f)
}

/// The caption: the start, and each axis's largest angle with its rank among the moments.
fn description(
    i: &Moments,
    spin: f64,
    wobble: [f64; 2],
    t_end: f64,
    largest: [f64; 3],
    [small, middle, large]: [usize; 3],
) -> String {
    let rank = |k: usize| {
        if k == middle {
            "intermediate, unstable"
        } else if k == small {
            "smallest, stable"
        } else {
            debug_assert_eq!(k, large);
            "largest, stable"
        }
    };
    format!(
        "Spin {spin} about each principal axis of I = ({}, {}, {}) in turn, with {} and {} on the \
         other two axes; the exact solution gives the angle between ω and the axis it started on \
         (180° is a full reversal). Largest angle over t ≤ {t_end}: axis 1 ({}) {:.3}°, axis 2 \
         ({}) {:.3}°, axis 3 ({}) {:.3}°. Only the axis with the intermediate moment departs, as \
         the sign of Ω² in the linearised equations predicts.",
        i.0[0],
        i.0[1],
        i.0[2],
        wobble[0],
        wobble[1],
        rank(0),
        largest[0],
        rank(1),
        largest[1],
        rank(2),
        largest[2]
    )
}
