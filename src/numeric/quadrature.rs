//! Numeric inertia tensors by quadrature, each with its error law and its cost.
//!
//! Every rule is a set of weighted points in the body's own coordinates (weights sum to 1); the
//! tensor is M·Σ w (r²𝟙 − r rᵀ) in the scene frame. The predicted error comes from the rule's
//! error law, written as the error it makes in the first and second moments of the body
//! coordinates (REFERENCE.md, "Quadrature"), then carried into the frame.

use super::body::{NumBody, NumShape, relative_error, tensor_of_points};
use crate::base::rng::Rng;
use nalgebra::{Matrix3, Vector2, Vector3};
use std::f64::consts::PI;
use std::time::Instant;

#[derive(
    Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub enum Method {
    /// Gauss–Legendre in each Cartesian or radial direction (with the periodic trapezoid in angles
    /// for round bodies); exact for the quadratic moments from 2 or 3 points.
    GaussLegendre,
    /// Equispaced angles: exact for trigonometric polynomials of degree below N.
    PeriodicTrapezoid,
    /// n points per side at cell midpoints, equal masses.
    MidpointLattice,
    /// (n+1) points per side on cell vertices, equal masses: only first order.
    VertexLattice,
    MonteCarlo,
    /// Point masses: the sum itself.
    DirectSum,
}

impl Method {
    pub fn name(self) -> &'static str {
        match self {
            Method::GaussLegendre => "gauss-legendre",
            Method::PeriodicTrapezoid => "periodic-trapezoid",
            Method::MidpointLattice => "midpoint-lattice",
            Method::VertexLattice => "vertex-lattice",
            Method::MonteCarlo => "monte-carlo",
            Method::DirectSum => "direct-sum",
        }
    }
}

/// One quadrature run: the tensor, its true and predicted relative errors, and its cost.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct QuadratureRun {
    pub body: String,
    pub method: Method,
    pub level: usize,
    pub points: usize,
    pub tensor: Matrix3<f64>,
    /// Relative max-norm error against the exact tensor.
    pub error: f64,
    /// What the error law predicts (for Monte Carlo: one estimated standard error).
    pub predicted_error: f64,
    pub seconds: f64,
    /// Where this run left its method's ladder (`Climbing` outside a fidelity's climb).
    pub stop: Stop,
}

/// The levels a method may climb for a body, cheapest first. A fidelity climbs each ladder
/// until the error law meets its target or the next rung would exceed its cost cap.
pub fn ladder(shape: &NumShape) -> Vec<(Method, Vec<usize>)> {
    use Method::*;
    let lattice = vec![4, 8, 16, 32, 64, 128];
    let mc = (MonteCarlo, vec![1_000, 10_000, 100_000, 1_000_000]);
    let mut s = match shape {
        NumShape::Box { .. } | NumShape::Plate { .. } | NumShape::Rod { .. } => vec![
            (GaussLegendre, vec![1, 2, 3, 4]),
            (MidpointLattice, lattice.clone()),
            (VertexLattice, lattice),
        ],
        NumShape::Hoop { .. } => vec![(PeriodicTrapezoid, vec![1, 2, 3, 8])],
        NumShape::Points(_) => return vec![(DirectSum, vec![1])],
        _ => vec![(GaussLegendre, vec![3, 4, 5])],
    };
    s.push(mc);
    s
}

/// How many points a rule uses, known before it runs (for the cost cap).
pub fn point_count(shape: &NumShape, method: Method, n: usize) -> usize {
    let per_side = if method == Method::VertexLattice {
        n + 1
    } else {
        n
    };
    match (shape, method) {
        (NumShape::Points(p), _) => p.len(),
        (_, Method::MonteCarlo) => n,
        (NumShape::Box { .. }, _) => per_side.pow(3),
        (NumShape::Plate { .. }, _) => per_side.pow(2),
        (NumShape::Rod { .. } | NumShape::Hoop { .. }, _) => per_side,
        (NumShape::Disk { .. } | NumShape::Shell { .. }, _) => 4 * n,
        (
            NumShape::Cylinder { .. }
            | NumShape::Sphere { .. }
            | NumShape::Cone { .. }
            | NumShape::Hemisphere { .. },
            _,
        ) => 4 * n * n,
    }
}

/// Why a method stopped climbing its ladder where it did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Stop {
    /// A later rung ran.
    Climbing,
    /// The error law says the target is met.
    TargetMet,
    /// The next rung would use more points than the fidelity allows: the target is not met.
    CostCap,
    /// The ladder has no higher rung: the target is not met.
    LadderTop,
}

impl Stop {
    pub fn describe(self) -> &'static str {
        match self {
            Stop::Climbing => "",
            Stop::TargetMet => "target met",
            Stop::CostCap => "cost cap: target not met",
            Stop::LadderTop => "top rung: target not met",
        }
    }
}

/// Climbs each method's ladder for one body at one fidelity. Every rung is compared with the
/// exact tensor, so each run reports its true error next to its law's estimate.
pub fn climb(
    body: &NumBody,
    exact: &Matrix3<f64>,
    fidelity: &crate::model::fidelity::Fidelity,
    seed: u64,
) -> Vec<QuadratureRun> {
    let mut runs = Vec::new();
    for (method, levels) in ladder(&body.shape) {
        for (k, &level) in levels.iter().enumerate() {
            let mut r = run(body, method, level, exact, seed.wrapping_add(level as u64));
            let next = levels.get(k + 1).copied();
            r.stop = if r.predicted_error <= fidelity.tolerance {
                Stop::TargetMet
            } else if let Some(n) = next {
                if point_count(&body.shape, method, n) > fidelity.max_points() {
                    Stop::CostCap
                } else {
                    Stop::Climbing
                }
            } else {
                Stop::LadderTop
            };
            let done = r.stop != Stop::Climbing;
            runs.push(r);
            if done {
                break;
            }
        }
    }
    runs
}

/// The exact rule used for the principal-axes cross-check and the composite sum.
pub fn reference_rule(shape: &NumShape) -> (Method, usize) {
    match shape {
        NumShape::Hoop { .. } => (Method::PeriodicTrapezoid, 8),
        NumShape::Points(_) => (Method::DirectSum, 1),
        _ => (Method::GaussLegendre, 4),
    }
}

/// A body's centre of mass in the scene frame by its reference rule: exact, since the rule
/// integrates the quadratic tensor integrand and so the linear first moment too. Points are
/// weighed by their masses.
pub fn centre_of_mass(body: &NumBody, seed: u64) -> Vector3<f64> {
    match &body.shape {
        NumShape::Points(pts) => {
            let total: f64 = pts.iter().map(|(m, _)| m).sum();
            pts.iter()
                .map(|(m, r)| *m * body.place(r))
                .sum::<Vector3<f64>>()
                / total
        }
        shape => {
            let (method, level) = reference_rule(shape);
            rule(shape, method, level, &mut Rng::new(seed))
                .into_iter()
                .map(|(w, r)| w * body.place(&r))
                .sum()
        }
    }
}

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
fn rule(shape: &NumShape, method: Method, n: usize, rng: &mut Rng) -> Vec<(f64, Vector3<f64>)> {
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

/// The error law: (error of the second-moment matrix, error of the mean) per unit mass in body
/// coordinates. `None` for Monte Carlo, whose error is estimated from the sample.
fn moment_errors(
    shape: &NumShape,
    method: Method,
    n: usize,
) -> Option<(Matrix3<f64>, Vector3<f64>)> {
    let nf = n as f64;
    let zero = (Matrix3::zeros(), Vector3::zeros());
    // Variance error of a 1-D rule on a side of length l (its mean is exact).
    let side = |l: f64| match (method, n) {
        (Method::GaussLegendre, 1) | (Method::MidpointLattice, _) => -l * l / (12.0 * nf * nf),
        (Method::VertexLattice, _) => l * l / (6.0 * nf),
        _ => 0.0,
    };
    Some(match shape {
        _ if method == Method::MonteCarlo => return None,
        NumShape::Box { size, .. } => (
            Matrix3::from_diagonal(&Vector3::new(side(size.x), side(size.y), side(size.z))),
            Vector3::zeros(),
        ),
        NumShape::Plate { size, .. } => (
            Matrix3::from_diagonal(&Vector3::new(side(size.x), side(size.y), 0.0)),
            Vector3::zeros(),
        ),
        NumShape::Rod { length, along, .. } => (
            Matrix3::from_diagonal(&Vector3::ith(*along, side(*length))),
            Vector3::zeros(),
        ),
        NumShape::Hoop { radius } => {
            // Equispaced angles alias cos 2θ to a constant when N divides 2, and cos θ when N = 1.
            let r2 = radius * radius;
            let alias2 = if 2 % n == 0 { r2 / 2.0 } else { 0.0 };
            let mean = if n == 1 {
                Vector3::new(*radius, 0.0, 0.0)
            } else {
                Vector3::zeros()
            };
            (
                Matrix3::from_diagonal(&Vector3::new(alias2, -alias2, 0.0)),
                mean,
            )
        }
        _ => zero,
    })
}

/// Carries moment errors into the frame: ΔI = M (tr ΔC 𝟙 − ΔC), ΔC = QΔCQᵀ + QΔm sᵀ + s(QΔm)ᵀ.
fn tensor_error(body: &NumBody, dc: &Matrix3<f64>, dm: &Vector3<f64>) -> Matrix3<f64> {
    let q = &body.rotation;
    let qm = q * dm;
    let c = q * dc * q.transpose() + qm * body.shift.transpose() + body.shift * qm.transpose();
    body.mass * (Matrix3::identity() * c.trace() - c)
}

/// Runs one method at one level and compares it with the exact tensor.
pub fn run(
    body: &NumBody,
    method: Method,
    level: usize,
    exact: &Matrix3<f64>,
    seed: u64,
) -> QuadratureRun {
    let start = Instant::now();
    let mut rng = Rng::new(seed);
    let (tensor, points, mc_sigma) = match &body.shape {
        NumShape::Points(pts) => {
            let t = tensor_of_points(pts.iter().map(|(m, r)| (*m, body.place(r))));
            (t, pts.len(), None)
        }
        shape => {
            // Placed in place: a reference-level lattice has millions of points.
            let placed: Vec<(f64, Vector3<f64>)> = rule(shape, method, level, &mut rng)
                .into_iter()
                .map(|(w, r)| (body.mass * w, body.place(&r)))
                .collect();
            let t = tensor_of_points(placed.iter().copied());
            let sigma =
                (method == Method::MonteCarlo).then(|| monte_carlo_sigma(&placed, body.mass, &t));
            (t, placed.len(), sigma)
        }
    };
    let seconds = start.elapsed().as_secs_f64();
    super::Work::count_quadrature(points);
    let scale = exact.amax().max(f64::MIN_POSITIVE);
    let roundoff = points as f64 * f64::EPSILON;
    let predicted_error = match mc_sigma {
        Some(sigma) => sigma / scale,
        None => match moment_errors(&body.shape, method, level) {
            Some((dc, dm)) => tensor_error(body, &dc, &dm).amax() / scale + roundoff,
            None => roundoff,
        },
    };
    QuadratureRun {
        body: body.label.clone(),
        method,
        level,
        points,
        error: relative_error(&tensor, exact),
        tensor,
        predicted_error,
        seconds,
        stop: Stop::Climbing,
    }
}

/// The largest estimated standard error over the tensor entries of a Monte Carlo sum. The
/// deviations are squared in units of the mean's largest entry: squared as they are, those of a
/// body of mass 1e-160 underflow, and the law would promise an error of 0.
fn monte_carlo_sigma(placed: &[(f64, Vector3<f64>)], mass: f64, mean: &Matrix3<f64>) -> f64 {
    let n = placed.len() as f64;
    let unit = mean.amax().max(f64::MIN_POSITIVE);
    let mut var = Matrix3::<f64>::zeros();
    for (_, r) in placed {
        let k = mass * (Matrix3::identity() * r.norm_squared() - r * r.transpose());
        let d = (k - mean) / unit;
        var += d.component_mul(&d);
    }
    (var / (n - 1.0) / n).map(f64::sqrt).amax() * unit
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_monte_carlo_law_holds_for_a_tiny_mass() {
        // The same sample, mass 1 and mass 1e-160: the relative law is the same, never 0.
        let mut tiny = cube(true);
        tiny.mass = 1e-160;
        let centre = Matrix3::identity() / 6.0;
        let one = run(&cube(true), Method::MonteCarlo, 10_000, &centre, 7);
        let small = run(&tiny, Method::MonteCarlo, 10_000, &(centre * 1e-160), 7);
        assert!(small.predicted_error > 0.0);
        assert!(
            (small.predicted_error / one.predicted_error - 1.0).abs() < 1e-9,
            "{} against {}",
            small.predicted_error,
            one.predicted_error
        );
        assert!(small.error < 5.0 * small.predicted_error);
    }

    fn cube(centred: bool) -> NumBody {
        NumBody {
            label: "cube".into(),
            shape: NumShape::Box {
                size: Vector3::new(1.0, 1.0, 1.0),
                centred,
            },
            mass: 1.0,
            rotation: Matrix3::identity(),
            shift: Vector3::zeros(),
        }
    }

    /// The corner tensor of a unit cube, from its centre tensor 𝟙/6 and the parallel-axis shift
    /// by d = (½,½,½): an independent route to the exact value.
    fn corner_exact() -> Matrix3<f64> {
        let d = Vector3::new(0.5, 0.5, 0.5);
        Matrix3::identity() / 6.0 + Matrix3::identity() * d.norm_squared() - d * d.transpose()
    }

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        for n in 1..=6 {
            let rule = gauss_legendre(n);
            for p in 0..(2 * n) {
                let got: f64 = rule.iter().map(|(x, w)| w * x.powi(p as i32)).sum();
                let want = if p % 2 == 1 {
                    0.0
                } else {
                    2.0 / (p as f64 + 1.0)
                };
                assert!((got - want).abs() < 1e-14, "n={n} p={p}: {got} vs {want}");
            }
        }
    }

    #[test]
    fn lattice_errors_follow_their_laws() {
        let exact = corner_exact();
        for n in [4, 16] {
            let mid = run(&cube(false), Method::MidpointLattice, n, &exact, 1);
            let law = -1.0 / (6.0 * (n * n) as f64);
            assert!(
                ((mid.tensor - exact)[(0, 0)] - law).abs() < 1e-13,
                "midpoint n={n}"
            );
            let ver = run(&cube(false), Method::VertexLattice, n, &exact, 1);
            let law = 1.0 / (3.0 * n as f64);
            assert!(
                ((ver.tensor - exact)[(0, 0)] - law).abs() < 1e-13,
                "vertex n={n}"
            );
            // The predicted error is the law relative to the largest entry (2/3), plus the
            // round-off allowance of the sum.
            let roundoff = ver.points as f64 * f64::EPSILON;
            assert!((ver.predicted_error - roundoff - law / (2.0 / 3.0)).abs() < 1e-15);
        }
    }

    #[test]
    fn monte_carlo_spread_matches_the_reference_law() {
        // REFERENCE.md: σ(I_xx) = √(8/45)·M a²/√N for the cube about its corner (the largest
        // entry's spread), relative to the largest entry 2/3 M a².
        let n = 100_000;
        let r = run(&cube(false), Method::MonteCarlo, n, &corner_exact(), 7);
        let law = (8.0f64 / 45.0).sqrt() / (n as f64).sqrt() / (2.0 / 3.0);
        // The sample estimate of σ itself has a relative spread of about 1/√N.
        assert!(
            (r.predicted_error / law - 1.0).abs() < 0.02,
            "{} vs {law}",
            r.predicted_error
        );
        assert!(r.error < 5.0 * r.predicted_error);
        // About its centre the spread is M a²/√(90 N): Var(y²) = a⁴/180 for y uniform on ±a/2.
        let centre = Matrix3::identity() / 6.0;
        let c = run(&cube(true), Method::MonteCarlo, n, &centre, 7);
        let law = 1.0 / (90.0 * n as f64).sqrt() / (1.0 / 6.0);
        assert!(
            (c.predicted_error / law - 1.0).abs() < 0.02,
            "{} vs {law}",
            c.predicted_error
        );
    }

    #[test]
    fn trapezoid_is_exact_for_a_hoop_from_three_points() {
        let hoop = NumBody {
            label: "hoop".into(),
            shape: NumShape::Hoop { radius: 1.0 },
            mass: 1.0,
            rotation: Matrix3::identity(),
            shift: Vector3::zeros(),
        };
        let exact = Matrix3::from_diagonal(&Vector3::new(0.5, 0.5, 1.0));
        for n in [3, 4, 8] {
            assert!(run(&hoop, Method::PeriodicTrapezoid, n, &exact, 1).error < 1e-15);
        }
        let two = run(&hoop, Method::PeriodicTrapezoid, 2, &exact, 1);
        assert!(
            (two.error - two.predicted_error).abs() < 1e-14,
            "aliasing law"
        );
    }

    #[test]
    fn monte_carlo_samples_of_the_new_bodies_agree_with_gauss_legendre() {
        // Two independent routes through each parametrisation: the sampler draws points by
        // inverting the volume law, Gauss–Legendre weights the same law; they must agree within
        // five standard errors, and the table's I_zz must come out of Gauss–Legendre.
        let shapes = [
            (
                NumShape::Cone {
                    radius: 0.7,
                    height: 1.9,
                    apex: 0.0,
                    direction: 1.0,
                },
                0.3 * 0.49,
            ),
            (
                NumShape::Cone {
                    radius: 0.7,
                    height: 1.9,
                    apex: 1.425,
                    direction: -1.0,
                },
                0.3 * 0.49,
            ),
            (
                NumShape::Hemisphere {
                    radius: 0.7,
                    face: -0.2625,
                },
                0.4 * 0.49,
            ),
            (
                NumShape::Disk {
                    radius: 0.7,
                    inner: 0.3,
                },
                (0.49 + 0.09) / 2.0,
            ),
            (
                NumShape::Cylinder {
                    radius: 0.7,
                    height: 1.9,
                    inner: 0.3,
                },
                (0.49 + 0.09) / 2.0,
            ),
            (
                NumShape::Sphere {
                    radius: 0.7,
                    inner: 0.3,
                },
                0.4 * (0.7f64.powi(5) - 0.3f64.powi(5)) / (0.7f64.powi(3) - 0.3f64.powi(3)),
            ),
            (
                NumShape::Plate {
                    size: Vector2::new(1.1, 0.6),
                    centred: false,
                },
                (1.21 + 0.36) / 3.0,
            ),
        ];
        for (shape, izz) in shapes {
            let body = NumBody {
                label: "b".into(),
                shape: shape.clone(),
                mass: 1.0,
                rotation: Matrix3::identity(),
                shift: Vector3::zeros(),
            };
            let gauss = run(&body, Method::GaussLegendre, 5, &Matrix3::zeros(), 1).tensor;
            assert!(
                (gauss[(2, 2)] - izz).abs() < 1e-14,
                "{shape:?}: I_zz {}",
                gauss[(2, 2)]
            );
            let mc = run(&body, Method::MonteCarlo, 200_000, &gauss, 3);
            assert!(
                mc.error < 5.0 * mc.predicted_error,
                "{shape:?}: {} vs {}",
                mc.error,
                mc.predicted_error
            );
        }
    }
}
