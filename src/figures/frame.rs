//! What the free-body figures share: sample times, the figure frame, the text that names the
//! body and its motion, and the Dormand–Prince run several of them draw.

use crate::base::format::sci;
use crate::model::fidelity::Fidelity;
use crate::model::figure::{Figure, Legend, Scale, Series};
use crate::model::moments::Moments;
use crate::model::prose::Prose;
use crate::numeric::free_body::ExactSolution;
use crate::numeric::integrators::{IntegrationError, Method, Resolution, Run, integrate};
use nalgebra::Vector3;

pub(super) fn times(t_end: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|j| t_end * j as f64 / n as f64).collect()
}

pub(super) fn fig(
    slug: &str,
    title: String,
    desc: String,
    x: &str,
    y: &str,
    series: Vec<Series>,
) -> Figure {
    Figure {
        slug: slug.into(),
        title,
        desc: Prose::default().text(&desc),
        x_label: x.into(),
        y_label: y.into(),
        x_scale: Scale::Linear,
        y_scale: Scale::Linear,
        equal_aspect: false,
        series,
        labels: Vec::new(),
        legend: Legend::UpperRight,
        accuracy: Vec::new(),
    }
}

pub(super) fn body_text(i: &Moments, w0: &Vector3<f64>) -> String {
    format!(
        "I = ({}, {}, {}), ω(0) = ({}, {}, {})",
        i.0[0], i.0[1], i.0[2], w0.x, w0.y, w0.z
    )
}

pub(super) fn motion_text(sol: &ExactSolution) -> String {
    let mut s = String::new();
    if let Some((m, mc)) = sol.parameter() {
        s.push_str(&format!("m = {m:.6} (1 − m = {}), ", sci(mc)));
    }
    match sol.period() {
        Some(p) => s.push_str(&format!("period of ω {p:.6}")),
        None => s.push_str("steady rotation"),
    }
    s
}

/// Indices of the smallest, middle and largest moments.
pub(super) fn sorted_axes(i: &Moments) -> [usize; 3] {
    let mut o = [0, 1, 2];
    o.sort_by(|a, b| i.0[*a].total_cmp(&i.0[*b]));
    o
}

/// Dormand–Prince at the fidelity's tolerance (1e-11 at standard), with the trace sampled at
/// `samples` points at standard fidelity: the attitude-following run several figures draw.
pub(super) fn dopri_trace(
    i: &Moments,
    w0: Vector3<f64>,
    t_end: f64,
    fid: &Fidelity,
    samples: usize,
) -> Result<(Run, f64), IntegrationError> {
    let tol = fid.ode_tolerance(1e-11);
    let run = integrate(
        i,
        w0,
        t_end,
        Method::Dopri,
        Resolution::Tolerance(tol),
        fid.samples(samples),
    )?;
    Ok((run, tol))
}
