//! Numeric inertia tensors by quadrature, each with its error law and its cost.
//!
//! Every rule is a set of weighted points in the body's own coordinates (weights sum to 1); the
//! tensor is M·Σ w (r²𝟙 − r rᵀ) in the scene frame. The predicted error comes from the rule's
//! error law, written as the error it makes in the first and second moments of the body
//! coordinates (REFERENCE.md, "Quadrature"), then carried into the frame.

mod rules;

use super::body::{NumBody, NumShape, relative_error, tensor_of_points};
use crate::base::rng::Rng;
use nalgebra::{Matrix3, Vector3};
use std::time::Instant;

pub use rules::gauss_legendre;
use rules::rule;

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
    use nalgebra::Vector2;

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
