//! Polhodes on the energy ellipsoid in L-space, with the separatrix.

use super::accuracy::{exact_accuracy, merged};
use super::frame::{fig, sorted_axes, times};
use super::projection::project;
use super::{FigureError, colour, legend_entry};
use crate::model::fidelity::Fidelity;
use crate::model::figure::{Accuracy, Figure, Mark, Series};
use crate::model::moments::Moments;
use crate::numeric::free_body::{ExactSolution, invariants};
use nalgebra::Vector3;
use std::f64::consts::PI;

pub(super) fn polhodes(
    i: &Moments,
    w0: Vector3<f64>,
    fid: &Fidelity,
) -> Result<Figure, FigureError> {
    let n = fid.samples(240);
    let [a, b, c] = sorted_axes(i);
    let (ia, ib, ic) = (i.0[a], i.0[b], i.0[c]);
    if ia == ic {
        return Err(FigureError::SphereHasNoPolhodes);
    }
    let (two_t, _) = invariants(i, &w0);
    let mut series = Vec::new();
    energy_sections(i, two_t, &mut series);
    let (closed, exact_runs) = polhode_curves(i, two_t, n, [a, b, c], &mut series);
    let sep_text = separatrix(two_t, [a, b, c], (ia, ib, ic), &mut series);
    let n_max = closed.iter().filter(|&&x| x == c).count();
    let desc = format!(
        "Polhodes: the paths of L in the body frame on the energy ellipsoid 2T = {two_t:.4} \
         (I = ({}, {}, {})), for six values of L² between 2T·I{} and 2T·I{}, each traced by the \
         exact solution over one period, with its mirror image. {} close around the axis of the \
         largest moment (I{}) and {} around the smallest (I{}); none close around the middle \
         axis (I{}): {sep_text}. Oblique view, azimuth 25°, elevation 20°.",
        i.0[0],
        i.0[1],
        i.0[2],
        a + 1,
        c + 1,
        n_max,
        c + 1,
        closed.len() - n_max,
        a + 1,
        b + 1
    );
    let mut f = fig(
        "polhodes",
        "Polhodes on the energy ellipsoid".into(),
        desc,
        "",
        "",
        series,
    );
    f.equal_aspect = true;
    f.labels = (0..3)
        .map(|k| {
            let mut l = Vector3::zeros();
            l[k] = 1.08 * (two_t * i.0[k]).sqrt();
            (format!("L{}", k + 1), project(&l))
        })
        .collect();
    f.accuracy = vec![merged("polhodes", exact_runs)];
    Ok(f)
}

/// The energy ellipsoid's three principal sections, for orientation.
fn energy_sections(i: &Moments, two_t: f64, series: &mut Vec<Series>) {
    for (p, q) in [(0, 1), (1, 2), (0, 2)] {
        let pts: Vec<(f64, f64)> = (0..=120)
            .map(|k| {
                let s = k as f64 * 2.0 * PI / 120.0;
                let mut l = Vector3::zeros();
                l[p] = (two_t * i.0[p]).sqrt() * s.cos();
                l[q] = (two_t * i.0[q]).sqrt() * s.sin();
                project(&l)
            })
            .collect();
        series.push(Series {
            name: legend_entry(p == 0 && q == 1, "energy ellipsoid"),
            mark: Mark::Dashed,
            colour: colour::REFERENCE,
            points: pts,
        });
    }
}

/// Six polhodes, L² from near 2T·I_min to near 2T·I_max, each over one period of the exact
/// solution and mirrored; the axis each closes around, and the exact solution's accuracy runs.
fn polhode_curves(
    i: &Moments,
    two_t: f64,
    n: usize,
    [a, b, c]: [usize; 3],
    series: &mut Vec<Series>,
) -> (Vec<usize>, Vec<Accuracy>) {
    let (ia, ib, ic) = (i.0[a], i.0[b], i.0[c]);
    let l_of = |w: &Vector3<f64>| Vector3::new(i.0[0] * w.x, i.0[1] * w.y, i.0[2] * w.z);
    let mut exact_runs = Vec::new();
    let mut closed = Vec::new();
    for f in [0.05, 0.25, 0.45, 0.55, 0.75, 0.95] {
        // L² between 2T·I_min and 2T·I_max; start on the plane ω_mid = 0.
        let l2 = two_t * (ia + f * (ic - ia));
        if (l2 - two_t * ib).abs() < 1e-9 * l2 {
            continue;
        }
        let mut w = Vector3::zeros();
        w[a] = ((two_t * ic - l2) / (ia * (ic - ia))).max(0.0).sqrt();
        w[c] = ((l2 - two_t * ia) / (ic * (ic - ia))).max(0.0).sqrt();
        let sol = ExactSolution::new(i, w);
        let period = sol.period().unwrap_or(2.0 * PI);
        let around = if l2 > two_t * ib { c } else { a };
        closed.push(around);
        exact_runs.push(exact_accuracy("", i, &w, &times(period, n)));
        for sign in [1.0, -1.0] {
            series.push(Series {
                name: legend_entry(f == 0.05 && sign > 0.0, "polhodes"),
                mark: Mark::Line,
                colour: if around == c {
                    colour::PRIMARY
                } else {
                    colour::SECONDARY
                },
                points: (0..=n)
                    .map(|k| project(&(l_of(&sol.omega(period * k as f64 / n as f64)) * sign)))
                    .collect(),
            });
        }
    }
    (closed, exact_runs)
}

/// The separatrix through the middle axis, where there is one, and its words.
fn separatrix(
    two_t: f64,
    [a, b, c]: [usize; 3],
    (ia, ib, ic): (f64, f64, f64),
    series: &mut Vec<Series>,
) -> String {
    let mut sep_text = String::from("no separatrix (two equal moments)");
    if ib > ia && ib < ic {
        // d = 0: (I_c − I_b) L_c² / I_c = (I_b − I_a) L_a² / I_a, two planes through the middle
        // axis; on the sphere |L|² = 2T·I_b they are great circles.
        let k = ((ib - ia) * ic / ((ic - ib) * ia)).sqrt();
        let radius = (two_t * ib).sqrt();
        for (j, sign) in [1.0, -1.0].into_iter().enumerate() {
            let mut u = Vector3::zeros();
            u[a] = 1.0;
            u[c] = sign * k;
            let u = u.normalize();
            let e = Vector3::ith(b, 1.0);
            series.push(Series {
                name: legend_entry(j == 0, "separatrix"),
                mark: Mark::Line,
                colour: colour::CONTRAST,
                points: (0..=240)
                    .map(|n| {
                        let s = n as f64 * 2.0 * PI / 240.0;
                        project(&((u * s.cos() + e * s.sin()) * radius))
                    })
                    .collect(),
            });
        }
        sep_text = format!(
            "the separatrix, L² = 2T·I{} = {:.4}, is two great circles through the ±L{} points",
            b + 1,
            two_t * ib,
            b + 1
        );
    }
    sep_text
}
