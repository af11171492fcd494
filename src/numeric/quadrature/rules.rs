//! The point rules of the quadrature, by shape: Gauss–Legendre, the midpoint rule and Monte
//! Carlo on a line, an angle's equal steps, and each shape's product of them.

use super::Method;
use crate::base::rng::Rng;
use crate::numeric::body::NumShape;
use nalgebra::{Vector2, Vector3};
use std::f64::consts::PI;

/// Gauss–Legendre nodes and weights on [-1, 1] by Newton's method on P_n.
///
/// n nodes integrate polynomials up to degree 2n − 1 exactly, so two points per axis already
/// give the exact inertia tensor of a box (its integrand is quadratic).
///
/// ```
/// let rule = mechbook::numeric::quadrature::gauss_legendre(2);
/// let integral_of_x2: f64 = rule.iter().map(|(x, w)| w * x * x).sum();
/// assert!((integral_of_x2 - 2.0 / 3.0).abs() < 1e-15);
/// ```
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (1..=n)
        .map(|i| {
            let mut x = (PI * (i as f64 - 0.25) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let k = k as f64;
                    (p0, p1) = (p1, ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k);
                }
                if n == 1 {
                    p1 = x;
                    p0 = 1.0;
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// Points on [lo, lo+len]: Gauss–Legendre, midpoint or vertex rule, weights summing to 1.
fn line(method: Method, n: usize, lo: f64, len: f64) -> Vec<(f64, f64)> {
    match method {
        Method::GaussLegendre => gauss_legendre(n)
            .into_iter()
            .map(|(x, w)| (w / 2.0, lo + len * (x + 1.0) / 2.0))
            .collect(),
        Method::MidpointLattice => (0..n)
            .map(|i| (1.0 / n as f64, lo + len * (i as f64 + 0.5) / n as f64))
            .collect(),
        Method::VertexLattice => (0..=n)
            .map(|i| (1.0 / (n + 1) as f64, lo + len * i as f64 / n as f64))
            .collect(),
        _ => unreachable!("not a line rule"),
    }
}

/// N equispaced angles on [0, 2π), equal weights.
fn circle(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|j| (1.0 / n as f64, 2.0 * PI * j as f64 / n as f64))
        .collect()
}

/// The rule's weighted points in body coordinates (weights sum to 1).
pub(super) fn rule(
    shape: &NumShape,
    method: Method,
    n: usize,
    rng: &mut Rng,
) -> Vec<(f64, Vector3<f64>)> {
    if method == Method::MonteCarlo {
        let w = 1.0 / n as f64;
        return (0..n).map(|_| (w, sample(shape, rng))).collect();
    }
    match shape {
        NumShape::Box { size, centred } => box_rule(size, *centred, method, n),
        NumShape::Plate { size, centred } => {
            let lo = if *centred {
                -size / 2.0
            } else {
                Vector2::zeros()
            };
            let mut pts = Vec::new();
            for (wx, x) in line(method, n, lo.x, size.x) {
                for (wy, y) in line(method, n, lo.y, size.y) {
                    pts.push((wx * wy, Vector3::new(x, y, 0.0)));
                }
            }
            pts
        }
        NumShape::Rod {
            length,
            along,
            centred,
        } => {
            let lo = if *centred { -length / 2.0 } else { 0.0 };
            line(method, n, lo, *length)
                .into_iter()
                .map(|(w, s)| (w, Vector3::ith(*along, s)))
                .collect()
        }
        NumShape::Hoop { radius } => circle(n)
            .into_iter()
            .map(|(w, t)| (w, Vector3::new(radius * t.cos(), radius * t.sin(), 0.0)))
            .collect(),
        NumShape::Disk { radius, inner } => round_rule(*radius, *inner, None, n),
        NumShape::Cylinder {
            radius,
            height,
            inner,
        } => round_rule(*radius, *inner, Some(*height), n),
        NumShape::Cone {
            radius,
            height,
            apex,
            direction,
        } => cone_rule(*radius, *height, (*apex, *direction), n),
        NumShape::Sphere { radius, inner } => spherical_rule(*radius, *inner, true, -1.0, 0.0, n),
        NumShape::Hemisphere { radius, face } => spherical_rule(*radius, 0.0, true, 0.0, *face, n),
        NumShape::Shell { radius } => spherical_rule(*radius, 0.0, false, -1.0, 0.0, n),
        NumShape::Points(_) => unreachable!("point sets are summed directly"),
    }
}

/// A box's product rule: `n` points a side.
fn box_rule(
    size: &Vector3<f64>,
    centred: bool,
    method: Method,
    n: usize,
) -> Vec<(f64, Vector3<f64>)> {
    let lo = if centred {
        -size / 2.0
    } else {
        Vector3::zeros()
    };
    let (lx, ly, lz) = (
        line(method, n, lo.x, size.x),
        line(method, n, lo.y, size.y),
        line(method, n, lo.z, size.z),
    );
    let mut pts = Vec::new();
    for (wx, x) in &lx {
        for (wy, y) in &ly {
            for (wz, z) in &lz {
                pts.push((wx * wy * wz, Vector3::new(*x, *y, *z)));
            }
        }
    }
    pts
}

/// A disk's rule, or a cylinder's of `height`, annular from `inner`: Gauss–Legendre in r (and
/// z), four points in the angle.
fn round_rule(radius: f64, inner: f64, height: Option<f64>, n: usize) -> Vec<(f64, Vector3<f64>)> {
    // Area element r dr dθ on [inner, R]: the radial weight carries r / ((R² − inner²)/2).
    let radial = line(Method::GaussLegendre, n, inner, radius - inner);
    let area = (radius * radius - inner * inner) / 2.0;
    let zs = match height {
        Some(h) => line(Method::GaussLegendre, n, -h / 2.0, h),
        None => vec![(1.0, 0.0)],
    };
    let mut pts = Vec::new();
    for (wr, r) in &radial {
        for (wt, t) in circle(4) {
            for (wz, z) in &zs {
                let w = wr * r * (radius - inner) / area * wt * wz;
                pts.push((w, Vector3::new(r * t.cos(), r * t.sin(), *z)));
            }
        }
    }
    pts
}

/// A solid cone's rule, its apex at `apex` on z and opening towards `direction` (±1).
fn cone_rule(
    radius: f64,
    height: f64,
    (apex, direction): (f64, f64),
    n: usize,
) -> Vec<(f64, Vector3<f64>)> {
    // t = distance from the apex: the section's area grows as t², so t carries 3t²/h³;
    // the radius within the section is a fraction f of Rt/h, with weight 2f.
    let mut pts = Vec::new();
    for (wt, t) in line(Method::GaussLegendre, n, 0.0, height) {
        let wt = wt * 3.0 * t * t / (height * height);
        for (wf, f) in line(Method::GaussLegendre, n, 0.0, 1.0) {
            let r = f * radius * t / height;
            for (wa, a) in circle(4) {
                pts.push((
                    wt * wf * 2.0 * f * wa,
                    Vector3::new(r * a.cos(), r * a.sin(), apex + direction * t),
                ));
            }
        }
    }
    pts
}

/// A ball's rule (`solid`, hollow from `inner`), a hemisphere's (u from `u_lo` = 0, raised by
/// `lift`) or a thin shell's.
fn spherical_rule(
    radius: f64,
    inner: f64,
    solid: bool,
    u_lo: f64,
    lift: f64,
    n: usize,
) -> Vec<(f64, Vector3<f64>)> {
    // u = cos θ is uniform on [u_lo, 1] for all three; r² dr carries 3r²/(R³ − inner³)
    // for the solids.
    let radial = if solid {
        line(Method::GaussLegendre, n, inner, radius - inner)
    } else {
        vec![(1.0, radius)]
    };
    let volume = (radius.powi(3) - inner.powi(3)) / 3.0;
    let mut pts = Vec::new();
    for (wr, r) in &radial {
        let wr = if solid {
            wr * r * r * (radius - inner) / volume
        } else {
            *wr
        };
        for (wu, u) in line(Method::GaussLegendre, n, u_lo, 1.0 - u_lo) {
            let s = (1.0 - u * u).sqrt();
            for (wp, p) in circle(4) {
                pts.push((
                    wr * wu * wp,
                    Vector3::new(r * s * p.cos(), r * s * p.sin(), r * u + lift),
                ));
            }
        }
    }
    pts
}

/// One uniformly distributed point of the body.
fn sample(shape: &NumShape, rng: &mut Rng) -> Vector3<f64> {
    let mut u = || rng.uniform();
    match shape {
        NumShape::Box { size, centred } => {
            let p = Vector3::new(u() * size.x, u() * size.y, u() * size.z);
            if *centred { p - size / 2.0 } else { p }
        }
        NumShape::Plate { size, centred } => {
            let p = Vector2::new(u() * size.x, u() * size.y);
            let p = if *centred { p - size / 2.0 } else { p };
            Vector3::new(p.x, p.y, 0.0)
        }
        NumShape::Rod {
            length,
            along,
            centred,
        } => {
            let s = u() * length - if *centred { length / 2.0 } else { 0.0 };
            Vector3::ith(*along, s)
        }
        NumShape::Hoop { radius } => {
            let t = 2.0 * PI * u();
            Vector3::new(radius * t.cos(), radius * t.sin(), 0.0)
        }
        NumShape::Disk { radius, inner } | NumShape::Cylinder { radius, inner, .. } => {
            // r² is uniform on [inner², R²].
            let r = (inner * inner + u() * (radius * radius - inner * inner)).sqrt();
            let t = 2.0 * PI * u();
            let z = if let NumShape::Cylinder { height, .. } = shape {
                (u() - 0.5) * height
            } else {
                0.0
            };
            Vector3::new(r * t.cos(), r * t.sin(), z)
        }
        NumShape::Sphere { radius, inner } => {
            // r³ is uniform on [inner³, R³]; cos θ is uniform on [−1, 1].
            let r = (inner.powi(3) + u() * (radius.powi(3) - inner.powi(3))).cbrt();
            let (z, p) = (2.0 * u() - 1.0, 2.0 * PI * u());
            let s = (1.0 - z * z).sqrt();
            Vector3::new(r * s * p.cos(), r * s * p.sin(), r * z)
        }
        NumShape::Shell { radius } => {
            let (z, p) = (2.0 * u() - 1.0, 2.0 * PI * u());
            let s = (1.0 - z * z).sqrt();
            Vector3::new(radius * s * p.cos(), radius * s * p.sin(), radius * z)
        }
        NumShape::Hemisphere { radius, face } => {
            let r = radius * u().cbrt();
            let (z, p) = (u(), 2.0 * PI * u());
            let s = (1.0 - z * z).sqrt();
            Vector3::new(r * s * p.cos(), r * s * p.sin(), r * z + face)
        }
        NumShape::Cone {
            radius,
            height,
            apex,
            direction,
        } => {
            // The distance from the apex has density ∝ t²; within a section r² is uniform.
            let t = height * u().cbrt();
            let r = radius * t / height * u().sqrt();
            let a = 2.0 * PI * u();
            Vector3::new(r * a.cos(), r * a.sin(), apex + direction * t)
        }
        NumShape::Points(_) => unreachable!(),
    }
}
