//! An author's equations of motion against time: each coordinate integrated from the plot's
//! start (Dormand–Prince), with a step's linear equations from the same start beside them.

use super::FigureError;
use super::frame::fig;
use crate::base::format::{sci, short};
use crate::derive::Derivation;
use crate::derive::step_names::StepResult;
use crate::model::figure::{Accuracy, Figure, Legend, Mark, Series};
use crate::numeric::motion::{MOTION_STEPS, MOTION_TOLERANCE, MotionSystem, split_rows, start};
use crate::numeric::ode::dormand_prince;
use crate::scene::Scene;
use std::collections::BTreeMap;

/// Samples drawn along the motion.
const SAMPLES: usize = 240;

/// The equations of a step, by coordinate.
fn equations<'a>(
    d: &'a Derivation,
    step: &str,
) -> Result<&'a [(String, crate::cas::Expr)], FigureError> {
    d.named
        .get(step)
        .and_then(StepResult::equations)
        .ok_or_else(|| FigureError::NoEquations {
            step: step.to_string(),
        })
}

/// The state at each of [`SAMPLES`] + 1 times from 0 to `t_end`, integrated piece by piece at
/// `tol`, and the right-hand sides it took.
fn sampled(
    eqs: &[(String, crate::cas::Expr)],
    coordinates: &BTreeMap<String, String>,
    params: &BTreeMap<String, f64>,
    t_end: f64,
    tol: f64,
) -> Result<(Vec<Vec<f64>>, u64), FigureError> {
    let (coords, multipliers) = split_rows(eqs, coordinates);
    let system = MotionSystem::new(eqs, params, &coords, &multipliers)?;
    let rhs = |_t: f64, y: &[f64]| system.rates(y);
    let mut y = start(params, &coords);
    let mut out = vec![y.clone()];
    let mut evaluations = 0;
    let dt = t_end / SAMPLES as f64;
    for _ in 0..SAMPLES {
        let run = dormand_prince(&rhs, &y, dt, tol, MOTION_STEPS)?;
        evaluations += run.evaluations;
        y = run.states.last().map_or(y, |(_, s)| s.clone());
        out.push(y.clone());
    }
    Ok((out, evaluations))
}

pub(super) fn motion(
    scene: &Scene,
    d: &Derivation,
    step: &str,
    linear: Option<&str>,
    from: &BTreeMap<String, f64>,
    t_end: f64,
) -> Result<Figure, FigureError> {
    let full = equations(d, step)?;
    // A constraint's row (under its multiplier's name) is no coordinate to plot.
    let n = split_rows(full, &scene.coordinates).0.len();
    let mut params = scene.values.clone();
    params.extend(from.iter().map(|(k, v)| (k.clone(), *v)));
    let (states, cost) = sampled(full, &scene.coordinates, &params, t_end, MOTION_TOLERANCE)?;
    // The same motion at a hundredth of the tolerance: their difference estimates the error.
    let (finer, _) = sampled(
        full,
        &scene.coordinates,
        &params,
        t_end,
        MOTION_TOLERANCE / 100.0,
    )?;
    let error = largest_difference(&states, &finer, n);
    let time = |j: usize| t_end * j as f64 / SAMPLES as f64;
    let mut series = Vec::new();
    for (k, (q, _)) in full.iter().take(n).enumerate() {
        series.push(Series {
            name: super::plain_name(q),
            mark: Mark::Line,
            colour: k,
            points: states
                .iter()
                .enumerate()
                .map(|(j, y)| (time(j), y[k]))
                .collect(),
        });
    }
    let apart = match linear {
        Some(linear) => {
            let eqs = equations(d, linear)?;
            let lin = sampled(eqs, &scene.coordinates, &params, t_end, MOTION_TOLERANCE)?.0;
            linear_overlay(full, eqs, &states, &lin, t_end, &mut series)
        }
        None => String::new(),
    };
    let start_text = start_words(full, &states[0], n);
    let coordinates: Vec<String> = full.iter().map(|(q, _)| super::plain_name(q)).collect();
    let coordinates = coordinates.join(", ");
    let desc = format!(
        "The equations of motion integrated from {} over 0 ≤ t ≤ {} at the scene's values \
         (Dormand–Prince 5(4), tolerance {}, {cost} right-hand sides; against a run at a \
         hundredth of the tolerance the coordinates differ by at most {} of their size).{apart}",
        start_text,
        t_end,
        short(MOTION_TOLERANCE),
        sci(error)
    );
    let mut f = fig(
        &format!("motion-{step}"),
        format!("The motion of {coordinates}"),
        desc,
        "t",
        "coordinate",
        series,
    );
    f.legend = Legend::LowerRight;
    f.accuracy = vec![Accuracy {
        result: format!("the motion of {coordinates}"),
        method: format!("Dormand–Prince 5(4), tol {}", short(MOTION_TOLERANCE)),
        true_error: None,
        estimated_error: Some(error),
        cost,
        unit: "right-hand sides".into(),
        seconds: 0.0,
    }];
    Ok(f)
}

/// The largest difference between two runs' coordinates (the first `n` entries of each state),
/// relative to the largest coordinate.
fn largest_difference(states: &[Vec<f64>], finer: &[Vec<f64>], n: usize) -> f64 {
    let size = states
        .iter()
        .flat_map(|y| y[..n].iter())
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    states
        .iter()
        .zip(finer)
        .flat_map(|(a, b)| a[..n].iter().zip(&b[..n]))
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / size
}

/// The linear equations' motion (`lin`) dashed beside the full one's, each coordinate in its
/// colour; the words that say how far apart they are.
fn linear_overlay(
    full: &[(String, crate::cas::Expr)],
    eqs: &[(String, crate::cas::Expr)],
    states: &[Vec<f64>],
    lin: &[Vec<f64>],
    t_end: f64,
    series: &mut Vec<Series>,
) -> String {
    let time = |j: usize| t_end * j as f64 / SAMPLES as f64;
    let mut gap = 0.0f64;
    for (k, (q, _)) in eqs.iter().enumerate() {
        let Some(kf) = full.iter().position(|(p, _)| p == q) else {
            continue;
        };
        gap = states
            .iter()
            .zip(lin)
            .fold(gap, |m, (a, b)| m.max((a[kf] - b[k]).abs()));
        series.push(Series {
            name: format!("{} (linear)", super::plain_name(q)),
            mark: Mark::Dashed,
            colour: kf,
            points: lin
                .iter()
                .enumerate()
                .map(|(j, y)| (time(j), y[k]))
                .collect(),
        });
    }
    format!(
        " Dashed: the linear equations from the same start, at most {} from the full \
         motion.",
        sci(gap)
    )
}

/// The start, in words: each coordinate's value and rate.
fn start_words(full: &[(String, crate::cas::Expr)], start: &[f64], n: usize) -> String {
    let words: Vec<String> = full
        .iter()
        .enumerate()
        .map(|(k, (q, _))| {
            format!(
                "{} = {}, {} = {}",
                super::plain_name(q),
                start[k],
                super::plain_name(&format!("{q}'")),
                start[n + k]
            )
        })
        .collect();
    words.join(", ")
}
