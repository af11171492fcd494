//! The projections behind the 3-D views: an oblique view of a point, a basis of a plane, and
//! the outline of a body.

use crate::numeric::body::{NumBody, NumShape};
use nalgebra::Vector3;

/// A fixed oblique view: azimuth 25°, elevation 20°, chosen so that no frame axis or body
/// diagonal points at the viewer.
pub(super) fn project(p: &Vector3<f64>) -> (f64, f64) {
    let (az, el) = (25f64.to_radians(), 20f64.to_radians());
    let right = Vector3::new(-az.sin(), az.cos(), 0.0);
    let up = Vector3::new(-el.sin() * az.cos(), -el.sin() * az.sin(), el.cos());
    (p.dot(&right), p.dot(&up))
}

/// Two unit vectors spanning the plane normal to `n`.
pub(super) fn plane_basis(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let n = n.normalize();
    let e = Vector3::ith(n.iamin(), 1.0);
    let u = n.cross(&e).normalize();
    (u, n.cross(&u))
}

pub(super) fn segment(a: Vector3<f64>, b: Vector3<f64>) -> [(f64, f64); 2] {
    [project(&a), project(&b)]
}

/// Polylines of the body's outline in the scene frame, broken into separate segments.
pub(super) fn outline(nb: &NumBody) -> Vec<Vec<Vector3<f64>>> {
    match &nb.shape {
        NumShape::Box { size, centred } => box_edges(nb, size, *centred),
        NumShape::Plate { size, centred } => {
            let lo = if *centred { -size / 2.0 } else { size * 0.0 };
            let corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.0, 0.0)];
            vec![
                corners
                    .iter()
                    .map(|(i, j)| {
                        nb.place(&Vector3::new(lo.x + i * size.x, lo.y + j * size.y, 0.0))
                    })
                    .collect(),
            ]
        }
        NumShape::Hoop { radius } => vec![circle(nb, *radius, 0.0)],
        NumShape::Disk { radius, inner } => {
            let mut lines = vec![circle(nb, *radius, 0.0)];
            if *inner > 0.0 {
                lines.push(circle(nb, *inner, 0.0));
            }
            lines
        }
        NumShape::Cone {
            radius,
            height,
            apex,
            direction,
        } => {
            // The base's rim and four lines from the apex to it.
            let base = apex + direction * height;
            let mut lines = vec![circle(nb, *radius, base)];
            for k in 0..4 {
                let t = k as f64 * std::f64::consts::FRAC_PI_2;
                lines.push(vec![
                    nb.place(&Vector3::new(0.0, 0.0, *apex)),
                    nb.place(&Vector3::new(radius * t.cos(), radius * t.sin(), base)),
                ]);
            }
            lines
        }
        NumShape::Hemisphere { radius, face } => {
            // The rim of the flat face and two meridians over the dome.
            let mut lines = vec![circle(nb, *radius, *face)];
            for (cx, cy) in [(1.0, 0.0), (0.0, 1.0)] {
                lines.push(
                    (0..=36)
                        .map(|k| {
                            let t = k as f64 * std::f64::consts::PI / 36.0;
                            let (h, z) = (radius * t.cos(), radius * t.sin());
                            nb.place(&Vector3::new(cx * h, cy * h, face + z))
                        })
                        .collect(),
                );
            }
            lines
        }
        _ => Vec::new(),
    }
}

/// A box's twelve edges, in the scene frame.
fn box_edges(nb: &NumBody, size: &Vector3<f64>, centred: bool) -> Vec<Vec<Vector3<f64>>> {
    let lo = if centred {
        -size / 2.0
    } else {
        Vector3::zeros()
    };
    let corner = |k: usize| {
        Vector3::new(
            lo.x + size.x * (k & 1) as f64,
            lo.y + size.y * ((k >> 1) & 1) as f64,
            lo.z + size.z * ((k >> 2) & 1) as f64,
        )
    };
    let mut edges = Vec::new();
    for a in 0..8usize {
        for bit in [1, 2, 4] {
            if a & bit == 0 {
                edges.push(vec![nb.place(&corner(a)), nb.place(&corner(a | bit))]);
            }
        }
    }
    edges
}

/// A circle of radius `r` about the z axis at height `z`, in the scene frame.
fn circle(nb: &NumBody, r: f64, z: f64) -> Vec<Vector3<f64>> {
    (0..=72)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / 72.0;
            nb.place(&Vector3::new(r * t.cos(), r * t.sin(), z))
        })
        .collect()
}
