//! The symmetric top's body and space cones, with their measured half-angles.

use super::accuracy::run_accuracy;
use super::frame::dopri_trace;
use super::frame::fig;
use super::projection::project;
use super::{FigureError, colour};
use crate::base::format::short;
use crate::model::fidelity::Fidelity;
use crate::model::figure::{Accuracy, Figure, Mark, Series};
use crate::model::moments::Moments;
use crate::numeric::free_body::invariants;
use crate::numeric::integrators::Run;
use nalgebra::{Matrix3, Vector3};

/// The symmetric top (eqs 69–71): in space, ω sweeps the space cone about the fixed L while the
/// symmetry axis e3 and ω go round together; in the body, ω sweeps the body cone about e3. The
/// half-angles are measured from the integrated attitude and compared with the derivation:
/// tan α_b = A/ω3, cos α_s = 2T/(ωL), and tan θ_L = (I1/I3) tan α_b for the angle of L from e3.
pub(super) fn cones(
    i: &Moments,
    w0: Vector3<f64>,
    t_end: f64,
    fid: &Fidelity,
) -> Result<Figure, FigureError> {
    let v = i.0;
    let c = (0..3)
        .find(|&c| v[(c + 1) % 3] == v[(c + 2) % 3] && v[c] != v[(c + 1) % 3])
        .ok_or(FigureError::NotSymmetric)?;
    let (i1, i3) = (v[(c + 1) % 3], v[c]);
    let (two_t, l) = invariants(i, &w0);
    let w = w0.norm();
    let e3 = Vector3::ith(c, 1.0);
    let l_body = Vector3::new(v[0] * w0.x, v[1] * w0.y, v[2] * w0.z);
    let (dp, tol) = dopri_trace(i, w0, t_end, fid, 400)?;
    let (body_angle, space_angle, rims) = cone_rims(&dp.trace, &e3, &l_body);
    let ab = angle(&w0, &e3);
    let predicted_s = (two_t / (w * l)).clamp(-1.0, 1.0).acos();
    let theta_l = ((i1 / i3) * ab.tan()).atan();
    let shape = if i3 < i1 {
        "prolate (I3 < I1)"
    } else {
        "oblate (I3 > I1)"
    };
    let relation = if ab < predicted_s {
        "α_b < α_s"
    } else {
        "α_b > α_s"
    };
    let deg = |x: f64| x.to_degrees();
    let series = cone_series(&l_body, rims);
    let desc = format!(
        "Symmetric top, {shape}: I = ({}, {}, {}), ω(0) = ({}, {}, {}), unit vectors in an oblique \
         view. Measured from Dormand–Prince with the attitude: the body-cone half-angle α_b (ω to \
         the symmetry axis) stays {:.6}°–{:.6}°, the space-cone half-angle α_s (ω to L) \
         {:.6}°–{:.6}°. Derived: tan α_b = A/ω3 gives {:.6}°, cos α_s = 2T/(ωL) gives {:.6}°, and L \
         lies at θ_L = {:.6}° from the axis (tan θ_L = (I1/I3) tan α_b), so α_s = |θ_L − α_b| and \
         here {relation}.",
        v[0],
        v[1],
        v[2],
        w0.x,
        w0.y,
        w0.z,
        deg(body_angle.0),
        deg(body_angle.1),
        deg(space_angle.0),
        deg(space_angle.1),
        deg(ab),
        deg(predicted_s),
        deg(theta_l)
    );
    let slug = if i3 < i1 {
        "cones-prolate"
    } else {
        "cones-oblate"
    };
    let mut f = fig(
        slug,
        format!(
            "Body and space cones, {}",
            &shape[..shape.find(' ').unwrap()]
        ),
        desc,
        "",
        "",
        series,
    );
    f.equal_aspect = true;
    f.accuracy = cone_accuracy(&dp, tol, i, &w0, (space_angle, predicted_s));
    Ok(f)
}

/// Curves of projected points: ω in space, the symmetry axis in space, ω in the body.
type Rims = [Vec<(f64, f64)>; 3];

/// The angle between two vectors.
fn angle(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    a.normalize().dot(&b.normalize()).clamp(-1.0, 1.0).acos()
}

/// Along the traced motion: the ranges of the body-cone and space-cone half-angles, and the
/// rims traced in space by ω and the symmetry axis and in the body by ω.
fn cone_rims(
    trace: &[(f64, Vector3<f64>, Matrix3<f64>)],
    e3: &Vector3<f64>,
    l_body: &Vector3<f64>,
) -> ((f64, f64), (f64, f64), Rims) {
    let mut body_angle = (f64::INFINITY, 0.0f64);
    let mut space_angle = (f64::INFINITY, 0.0f64);
    let (mut space_rim, mut axis_rim, mut body_rim) = (Vec::new(), Vec::new(), Vec::new());
    for (_, wb, q) in trace {
        let ws = q * wb;
        let ab = angle(wb, e3);
        let a_s = angle(&ws, l_body);
        body_angle = (body_angle.0.min(ab), body_angle.1.max(ab));
        space_angle = (space_angle.0.min(a_s), space_angle.1.max(a_s));
        space_rim.push(project(&ws.normalize()));
        axis_rim.push(project(&(q * e3)));
        body_rim.push(project(&wb.normalize()));
    }
    (body_angle, space_angle, [space_rim, axis_rim, body_rim])
}

/// L, and the three rims, as the figure's series.
fn cone_series(l_body: &Vector3<f64>, [space_rim, axis_rim, body_rim]: Rims) -> Vec<Series> {
    vec![
        Series {
            name: "L (fixed)".into(),
            mark: Mark::Line,
            colour: colour::REFERENCE,
            points: vec![project(&Vector3::zeros()), project(&l_body.normalize())],
        },
        Series {
            name: "ω in space: space cone".into(),
            mark: Mark::Line,
            colour: colour::PRIMARY,
            points: space_rim,
        },
        Series {
            name: "symmetry axis in space".into(),
            mark: Mark::Dashed,
            colour: colour::SECONDARY,
            points: axis_rim,
        },
        Series {
            name: "ω in the body: body cone".into(),
            mark: Mark::Points,
            colour: colour::CONTRAST,
            points: body_rim,
        },
    ]
}

/// The accuracy of the traced ω, and of the space cone's half-angle against its derived value.
fn cone_accuracy(
    dp: &Run,
    tol: f64,
    i: &Moments,
    w0: &Vector3<f64>,
    (space_angle, predicted_s): ((f64, f64), f64),
) -> Vec<Accuracy> {
    let setting = format!("Dormand–Prince 5(4) with the attitude, tol {}", short(tol));
    let mut space_cone = run_accuracy("space-cone half-angle", setting.clone(), dp, i, w0);
    space_cone.true_error = Some(
        (space_angle.0 - predicted_s)
            .abs()
            .max((space_angle.1 - predicted_s).abs())
            / predicted_s.max(f64::MIN_POSITIVE),
    );
    vec![
        run_accuracy("ω in the body", setting, dp, i, w0),
        space_cone,
    ]
}
