//! The tennis racket: ω along the intermediate axis flips; flip times measured against the
//! prediction.

use super::accuracy::{exact_accuracy, run_accuracy};
use super::frame::{dopri_trace, fig, sorted_axes, times};
use super::{FigureError, colour};
use crate::base::format::{sci, short};
use crate::model::fidelity::Fidelity;
use crate::model::figure::{Figure, Legend, Mark, Series};
use crate::model::moments::Moments;
use crate::numeric::free_body::{ExactSolution, invariants};
use crate::numeric::integrators::Run;
use nalgebra::Vector3;

/// Times where component `k` changes sign, by linear interpolation between trace samples.
pub(super) fn sign_changes(run: &Run, k: usize) -> Vec<f64> {
    run.trace
        .windows(2)
        .filter(|w| w[0].1[k] * w[1].1[k] < 0.0)
        .map(|w| {
            let (t0, y0, t1, y1) = (w[0].0, w[0].1[k], w[1].0, w[1].1[k]);
            t0 + (t1 - t0) * y0 / (y0 - y1)
        })
        .collect()
}

/// A moment or a rate as a caption gives it, to six figures: a moment computed from
/// its body (m(b² + c²)/12) reads 0.000993333, not 0.000993333333333333.
fn six_figures(x: f64) -> String {
    crate::base::format::text_number(&crate::base::format::significant(x, 6))
}

pub(super) fn flip(
    i: &Moments,
    w0: Vector3<f64>,
    t_end: f64,
    fid: &Fidelity,
) -> Result<Figure, FigureError> {
    let [a, b, c] = sorted_axes(i);
    let (ia, ib, ic) = (i.0[a], i.0[b], i.0[c]);
    if !(ia < ib && ib < ic) {
        return Err(FigureError::FlipNeedsThreeMoments);
    }
    let sol = ExactSolution::new(i, w0);
    let (_, mc) = sol.parameter().ok_or(FigureError::FlipNeedsThreeMoments)?;
    let period = sol.period().ok_or(FigureError::FlipNeedsThreeMoments)?;
    let (two_t, _) = invariants(i, &w0);
    // REFERENCE.md: σ = ω2 √((I3 − I2)(I2 − I1)/(I1 I3)) with ω2 = √(2T/I2), the separatrix's
    // limit; flips every 2K/λ ≈ ln(16/(1 − m))/σ.
    let sigma = (two_t / ib).sqrt() * ((ic - ib) * (ib - ia) / (ia * ic)).sqrt();
    let approx = (16.0 / mc).ln() / sigma;
    let (dp, tol) = dopri_trace(i, w0, t_end, fid, 4000)?;
    let flips = sign_changes(&dp, b);
    let measured = if flips.len() >= 2 {
        Some((flips[flips.len() - 1] - flips[0]) / (flips.len() - 1) as f64)
    } else {
        None
    };
    let n = fid.samples(600);
    let series = flip_series(&sol, b, t_end, n, &flips);
    let desc = format!(
        "Tennis racket: spin started near the middle axis (I{} = {}) of I = ({}, {}, {}), \
         ω(0) = ({}, {}, {}). The component ω{} reverses again and again. Measured from Dormand–Prince \
         (tol {}) sign changes: {}, every {}; predicted: exactly 2K/λ = {:.6}, and \
         approximately ln(16/(1 − m))/σ = {:.6} with 1 − m = {} and σ = {:.6}.",
        b + 1,
        six_figures(ib),
        six_figures(i.0[0]),
        six_figures(i.0[1]),
        six_figures(i.0[2]),
        six_figures(w0.x),
        six_figures(w0.y),
        six_figures(w0.z),
        b + 1,
        short(tol),
        crate::base::format::count(flips.len(), "flip"),
        measured.map_or(
            "(fewer than two flips in the window)".to_string(),
            |m| format!("{m:.6}")
        ),
        period / 2.0,
        approx,
        sci(mc),
        sigma
    );
    let mut f = fig(
        "flip",
        "Intermediate-axis flips".into(),
        desc,
        "t",
        &format!("ω{}", b + 1),
        series,
    );
    f.legend = Legend::LowerRight;
    let setting = format!("Dormand–Prince 5(4), tol {}", short(tol));
    let mut flip_period = run_accuracy("time between flips", setting.clone(), &dp, i, &w0);
    flip_period.true_error = measured.map(|m| (m - period / 2.0).abs() / (period / 2.0));
    flip_period.estimated_error = None;
    f.accuracy = vec![
        exact_accuracy(&format!("ω{} curve", b + 1), i, &w0, &times(t_end, n)),
        run_accuracy(&format!("ω{} integrated", b + 1), setting, &dp, i, &w0),
        flip_period,
    ];
    Ok(f)
}

/// The exact middle component over the window, and the flips measured, as dots on the axis.
fn flip_series(sol: &ExactSolution, b: usize, t_end: f64, n: usize, flips: &[f64]) -> Vec<Series> {
    vec![
        Series {
            name: format!("ω{} exact", b + 1),
            mark: Mark::Line,
            colour: colour::PRIMARY,
            points: (0..=n)
                .map(|j| {
                    let t = t_end * j as f64 / n as f64;
                    (t, sol.omega(t)[b])
                })
                .collect(),
        },
        Series {
            name: "flips measured (Dormand–Prince)".into(),
            mark: Mark::Points,
            colour: colour::CONTRAST,
            points: flips.iter().map(|t| (*t, 0.0)).collect(),
        },
    ]
}
