//! The herpolhode: ω's tip traced on the invariable plane in space.

use super::accuracy::run_accuracy;
use super::frame::{body_text, dopri_trace, fig};
use super::projection::plane_basis;
use super::{FigureError, colour};
use crate::base::format::{sci, short};
use crate::model::fidelity::Fidelity;
use crate::model::figure::{Figure, Mark, Series};
use crate::model::moments::Moments;
use crate::numeric::free_body::invariants;
use nalgebra::Vector3;

pub(super) fn herpolhode(
    i: &Moments,
    w0: Vector3<f64>,
    t_end: f64,
    fid: &Fidelity,
) -> Result<Figure, FigureError> {
    let (two_t, l) = invariants(i, &w0);
    let l_space = Vector3::new(i.0[0] * w0.x, i.0[1] * w0.y, i.0[2] * w0.z);
    let n = l_space.normalize();
    let (u, v) = plane_basis(&n);
    let (dp, tol) = dopri_trace(i, w0, t_end, fid, 3000)?;
    let mut height_dev: f64 = 0.0;
    let expected = two_t.sqrt() / l;
    let pts: Vec<(f64, f64)> = dp
        .trace
        .iter()
        .map(|(_, w, q)| {
            let rho = q * w / two_t.sqrt();
            height_dev = height_dev.max((rho.dot(&n) - expected).abs() / expected);
            (rho.dot(&u), rho.dot(&v))
        })
        .collect();
    let desc = format!(
        "Herpolhode: the tip of ρ = ω/√(2T) in space, projected on the invariable plane (normal to \
         the fixed L), for {} over 0 ≤ t ≤ {t_end}, from Dormand–Prince 5(4) at tol {} with the \
         attitude. The plane's distance from the centre stays √(2T)/L = {expected:.6} to {} \
         (eq 81), and L stays fixed in space to {}.",
        body_text(i, &w0),
        short(tol),
        sci(height_dev),
        sci(dp.space_momentum_drift)
    );
    let mut f = fig(
        "herpolhode",
        "Herpolhode on the invariable plane".into(),
        desc,
        "",
        "",
        vec![Series {
            name: "herpolhode".into(),
            mark: Mark::Line,
            colour: colour::PRIMARY,
            points: pts,
        }],
    );
    f.equal_aspect = true;
    let mut acc = run_accuracy(
        "herpolhode",
        format!("Dormand–Prince 5(4) with the attitude, tol {}", short(tol)),
        &dp,
        i,
        &w0,
    );
    // The attitude has no cheap exact value; L's drift in space is its error estimate.
    acc.estimated_error = acc.estimated_error.map(|e| e.max(dp.space_momentum_drift));
    f.accuracy = vec![acc];
    Ok(f)
}
