//! The data of the plots a scene asks for (`[[plot]]`). Each figure's description is written
//! from its own numbers, so the alt text says what the picture shows.

use super::body::{NumBody, NumShape};
use super::eigen::{Space, principal_axes};
use super::fidelity::Fidelity;
use super::matrix_at;
use super::quadrature::{Method, QuadratureRun, point_count, reference_rule, run};
use crate::derive::{Derivation, ExactBasis, algebra::Value};
use crate::figure::{Accuracy, Figure, Legend, Mark, Scale, Series};
use crate::report::sci;
use crate::scene::{PlotRequest, Scene};
use nalgebra::{Matrix3, Vector3};
use std::collections::BTreeMap;

/// Curve resolution of exact functions.
const CURVE_POINTS: usize = 181;
/// Errors below this are drawn at it: a log axis cannot show an exact zero.
pub const ERROR_FLOOR: f64 = 1e-17;

pub fn figures(scene: &Scene, d: &Derivation, fidelity: &Fidelity) -> Result<Vec<Figure>, String> {
    let mut out = Vec::new();
    for p in &scene.plots {
        match p {
            PlotRequest::TensorSweep {
                over,
                from,
                to,
                samples,
            } => out.push(tensor_sweep(scene, d, over, *from, *to, *samples)?),
            PlotRequest::Convergence => {
                for (i, body) in scene.bodies.iter().enumerate() {
                    let nb = NumBody::from_scene(body, &scene.values)?;
                    let exact = matrix_at(&d.part_tensors[i], &scene.values)?;
                    let slug = if scene.bodies.len() == 1 {
                        "convergence".to_string()
                    } else {
                        format!("convergence-{}", i + 1)
                    };
                    out.push(convergence(&nb, &exact, scene.seed, slug, fidelity)?);
                }
            }
            PlotRequest::PrincipalAxes => out.push(principal_view(scene, d)?),
            PlotRequest::FreeBody {
                kind,
                inertia,
                omega,
                t,
            } => out.push(super::free_body_plots::figure(
                *kind, *inertia, *omega, *t, fidelity,
            )?),
        }
        // Two plots of one kind in a scene get distinct file names.
        let last = out.len() - 1;
        let taken = |slug: &str| out[..last].iter().any(|f| f.slug == slug);
        if taken(&out[last].slug) {
            let base = out[last].slug.clone();
            let n = (2..).find(|n| !taken(&format!("{base}-{n}"))).unwrap();
            out[last].slug = format!("{base}-{n}");
        }
    }
    Ok(out)
}

const ENTRIES: [(usize, usize, &str); 6] = [
    (0, 0, "I_xx"),
    (1, 1, "I_yy"),
    (2, 2, "I_zz"),
    (0, 1, "I_xy"),
    (0, 2, "I_xz"),
    (1, 2, "I_yz"),
];

fn values_with(scene: &Scene, name: &str, v: f64) -> BTreeMap<String, f64> {
    let mut values = scene.values.clone();
    values.insert(name.to_string(), v);
    values
}

/// The tensor's entries against one symbol: exact curves, and at `samples` values the sum of
/// each body's reference quadrature rule.
fn tensor_sweep(
    scene: &Scene,
    d: &Derivation,
    over: &str,
    from: f64,
    to: f64,
    samples: usize,
) -> Result<Figure, String> {
    let exact = &d.quantities["inertia_tensor"];
    let at = |k: usize, n: usize| from + (to - from) * k as f64 / (n - 1) as f64;
    let curve: Vec<(f64, Matrix3<f64>)> = (0..CURVE_POINTS)
        .map(|k| {
            let x = at(k, CURVE_POINTS);
            Ok((x, matrix_at(exact, &values_with(scene, over, x))?))
        })
        .collect::<Result<_, String>>()?;
    let mut numeric = Vec::new();
    let mut worst: f64 = 0.0;
    let mut rule_names = Vec::new();
    let (mut points, mut predicted, mut seconds) = (0u64, 0.0f64, 0.0);
    for k in 0..samples {
        let x = at(k, samples);
        let values = values_with(scene, over, x);
        let mut total = Matrix3::zeros();
        for (i, body) in scene.bodies.iter().enumerate() {
            let nb = NumBody::from_scene(body, &values)?;
            let (method, level) = reference_rule(&nb.shape);
            let part = matrix_at(&d.part_tensors[i], &values)?;
            let r = run(&nb, method, level, &part, scene.seed);
            points += r.points as u64;
            predicted = predicted.max(r.predicted_error);
            seconds += r.seconds;
            if k == 0 {
                rule_names.push(format!("{}, {} points", method.name(), r.points));
            }
            total += r.tensor;
        }
        worst = worst.max((total - matrix_at(exact, &values)?).amax());
        numeric.push((x, total));
    }
    let scale = curve.iter().map(|(_, m)| m.amax()).fold(0.0, f64::max);
    let mut series = Vec::new();
    let mut shown = Vec::new();
    let mut zero = Vec::new();
    for (colour, (i, j, name)) in ENTRIES.iter().enumerate() {
        let ys: Vec<f64> = curve.iter().map(|(_, m)| m[(*i, *j)]).collect();
        // An entry that is zero along the whole range is named in the description, not drawn.
        if ys
            .iter()
            .all(|y| y.abs() <= 1e-14 * scale.max(f64::MIN_POSITIVE))
        {
            zero.push(*name);
            continue;
        }
        let (lo, hi) = ys
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
                (a.min(*y), b.max(*y))
            });
        shown.push(format!("{name} from {lo:.3} to {hi:.3}"));
        series.push(Series {
            name: format!("{name} exact"),
            mark: Mark::Line,
            colour,
            points: curve.iter().map(|(x, m)| (*x, m[(*i, *j)])).collect(),
        });
        series.push(Series {
            name: String::new(),
            mark: Mark::Points,
            colour,
            points: numeric.iter().map(|(x, m)| (*x, m[(*i, *j)])).collect(),
        });
    }
    let fixed: Vec<String> = scene
        .values
        .iter()
        .filter(|(k, _)| k.as_str() != over)
        .map(|(k, v)| format!("{k} = {v}"))
        .collect();
    let desc = format!(
        "Inertia tensor entries of {} against {over} from {} to {}, at {}. Over this range {}{}. \
         Dots: {samples} values of {over} by quadrature with {}, at most {} from the exact curves.",
        scene.title.to_lowercase(),
        trim_num(from),
        trim_num(to),
        fixed.join(", "),
        shown.join("; "),
        if zero.is_empty() {
            String::new()
        } else {
            format!("; {} stay zero", zero.join(", "))
        },
        rule_names.join(", "),
        sci(worst),
    );
    Ok(Figure {
        slug: format!("tensor-vs-{over}"),
        title: format!("Tensor entries against {over}"),
        desc,
        x_label: over.to_string(),
        y_label: "entry".into(),
        x_scale: Scale::Linear,
        y_scale: Scale::Linear,
        equal_aspect: false,
        series,
        labels: Vec::new(),
        legend: Legend::MiddleRight,
        accuracy: vec![Accuracy {
            result: format!("tensor at {samples} values of {over}"),
            method: rule_names.join(", "),
            true_error: Some(worst / scale.max(f64::MIN_POSITIVE)),
            estimated_error: Some(predicted),
            cost: points,
            unit: "points".into(),
            seconds,
        }],
    })
}

fn trim_num(x: f64) -> String {
    if (x - std::f64::consts::PI).abs() < 1e-12 {
        "π".into()
    } else {
        format!("{x:.4}")
            .trim_end_matches('0')
            .trim_end_matches('.')
            .into()
    }
}

/// The (cost, error) points that no other point beats on both: sorted by cost, each with a
/// smaller error than every cheaper one.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut sorted: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(c, e)| c.is_finite() && e.is_finite())
        .collect();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut front: Vec<(f64, f64)> = Vec::new();
    for p in sorted {
        if front.last().is_none_or(|last| p.1 < last.1) {
            front.push(p);
        }
    }
    front
}

/// The levels swept per method: about one per factor of 2–10 in points, up to ~3·10⁵ points.
fn sweep(shape: &NumShape) -> Result<Vec<(Method, Vec<usize>)>, String> {
    use Method::*;
    let mc = (MonteCarlo, vec![100, 1_000, 10_000, 100_000, 1_000_000]);
    Ok(match shape {
        NumShape::Box { .. } => vec![
            (GaussLegendre, vec![1, 2, 3, 4]),
            (MidpointLattice, vec![2, 4, 8, 16, 32, 64, 128]),
            (VertexLattice, vec![2, 4, 8, 16, 32, 64, 128]),
            mc,
        ],
        NumShape::Rod { .. } => vec![
            (GaussLegendre, vec![1, 2, 3, 4]),
            (MidpointLattice, vec![2, 8, 32, 128, 512, 2048]),
            (VertexLattice, vec![2, 8, 32, 128, 512, 2048]),
            mc,
        ],
        NumShape::Hoop { .. } => vec![(PeriodicTrapezoid, (1..=8).collect()), mc],
        NumShape::Points(_) => {
            return Err("a convergence plot needs a continuous body, not point masses".into());
        }
        _ => vec![(GaussLegendre, vec![1, 2, 3, 4, 5]), mc],
    })
}

/// Slope of log(error) against log(points) between the first and last runs above round-off,
/// when at least three runs are.
fn slope(runs: &[QuadratureRun]) -> Option<f64> {
    let above: Vec<&QuadratureRun> = runs.iter().filter(|r| r.error > 1e-13).collect();
    if above.len() < 3 {
        return None;
    }
    let (a, b) = (above.first()?, above.last()?);
    (b.points > a.points)
        .then(|| (b.error / a.error).log10() / (b.points as f64 / a.points as f64).log10())
}

pub fn convergence(
    nb: &NumBody,
    exact: &Matrix3<f64>,
    seed: u64,
    slug: String,
    fidelity: &Fidelity,
) -> Result<Figure, String> {
    let mut series = Vec::new();
    let mut sentences = Vec::new();
    let mut accuracy = Vec::new();
    for (colour, (method, levels)) in sweep(&nb.shape)?.into_iter().enumerate() {
        // The fidelity's cost cap bounds the sweep (at least two levels, to show a slope).
        let cap = fidelity.max_points();
        let runs: Vec<QuadratureRun> = levels
            .iter()
            .enumerate()
            .filter(|(k, l)| *k < 2 || point_count(&nb.shape, method, **l) <= cap)
            .map(|(_, &l)| run(nb, method, l, exact, seed.wrapping_add(l as u64)))
            .collect();
        series.push(Series {
            name: method.name().into(),
            mark: Mark::Points,
            colour,
            points: runs
                .iter()
                .map(|r| (r.points as f64, r.error.max(ERROR_FLOOR)))
                .collect(),
        });
        series.push(Series {
            name: String::new(),
            mark: Mark::Dashed,
            colour,
            points: runs
                .iter()
                .map(|r| (r.points as f64, r.predicted_error.max(ERROR_FLOOR)))
                .collect(),
        });
        let (first, last) = (&runs[0], &runs[runs.len() - 1]);
        accuracy.push(Accuracy {
            result: format!("{} runs, the finest", runs.len()),
            method: method.name().into(),
            true_error: Some(last.error),
            estimated_error: Some(last.predicted_error),
            cost: runs.iter().map(|r| r.points as u64).sum(),
            unit: "points".into(),
            seconds: runs.iter().map(|r| r.seconds).sum(),
        });
        let mut s = format!(
            "{}: {} at {} point(s) to {} at {}",
            method.name(),
            sci(first.error),
            first.points,
            sci(last.error),
            last.points
        );
        if let Some(k) = slope(&runs) {
            s.push_str(&format!(", slope {k:.2}"));
        }
        if let Some(exact_from) = runs.iter().find(|r| r.error <= 1e-13) {
            s.push_str(&format!(", round-off from {} points", exact_from.points));
        }
        sentences.push(s);
    }
    let all: Vec<(f64, f64)> = series
        .iter()
        .filter(|s| s.mark == Mark::Points)
        .flat_map(|s| s.points.iter().copied())
        .collect();
    series.push(Series {
        name: "Pareto front".into(),
        mark: Mark::Line,
        colour: 5,
        points: pareto_front(&all),
    });
    Ok(Figure {
        slug,
        title: format!("Quadrature convergence: {}", nb.label),
        desc: format!(
            "Relative error of the inertia tensor of {} against the number of points, log-log; \
             dots measured, dashed lines the error law (Monte Carlo: one standard error). {}. \
             Errors below {} are drawn at that floor.",
            nb.label,
            sentences.join("; "),
            sci(ERROR_FLOOR)
        ),
        x_label: "points".into(),
        y_label: "relative error".into(),
        x_scale: Scale::Log,
        y_scale: Scale::Log,
        equal_aspect: false,
        series,
        labels: Vec::new(),
        legend: Legend::LowerRight,
        accuracy,
    })
}

/// A fixed oblique view: azimuth 25°, elevation 20°, chosen so that no frame axis or body
/// diagonal points at the viewer.
pub(super) fn project(p: &Vector3<f64>) -> (f64, f64) {
    let (az, el) = (25f64.to_radians(), 20f64.to_radians());
    let right = Vector3::new(-az.sin(), az.cos(), 0.0);
    let up = Vector3::new(-el.sin() * az.cos(), -el.sin() * az.sin(), el.cos());
    (p.dot(&right), p.dot(&up))
}

fn segment(a: Vector3<f64>, b: Vector3<f64>) -> [(f64, f64); 2] {
    [project(&a), project(&b)]
}

/// Two unit vectors spanning the plane normal to `n`.
pub(super) fn plane_basis(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let n = n.normalize();
    let e = Vector3::ith(n.iamin(), 1.0);
    let u = n.cross(&e).normalize();
    (u, n.cross(&u))
}

/// Polylines of the body's outline in the scene frame, broken into separate segments.
fn outline(nb: &NumBody) -> Vec<Vec<Vector3<f64>>> {
    match &nb.shape {
        NumShape::Box { size, centred } => {
            let lo = if *centred {
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
        NumShape::Hoop { radius } | NumShape::Disk { radius } => vec![
            (0..=72)
                .map(|k| {
                    let t = k as f64 * std::f64::consts::TAU / 72.0;
                    nb.place(&Vector3::new(radius * t.cos(), radius * t.sin(), 0.0))
                })
                .collect(),
        ],
        _ => Vec::new(),
    }
}

/// The principal axes through the frame origin in a projected 3-D view of the body: exact axes as
/// lines, and the numeric `SymmetricEigen` axes of the reference quadrature as dots at their tips.
fn principal_view(scene: &Scene, d: &Derivation) -> Result<Figure, String> {
    let eigen = d
        .eigen
        .as_ref()
        .ok_or("the principal-axes plot needs the exact eigenspaces")?;
    let env = |s: &str| scene.values.get(s).copied();
    let mut bodies = Vec::new();
    let mut numeric_tensor = Matrix3::zeros();
    let (mut points, mut seconds, mut rules) = (0u64, 0.0, Vec::new());
    for (i, body) in scene.bodies.iter().enumerate() {
        let nb = NumBody::from_scene(body, &scene.values)?;
        let (m, l) = reference_rule(&nb.shape);
        let part = matrix_at(&d.part_tensors[i], &scene.values)?;
        let r = run(&nb, m, l, &part, scene.seed);
        numeric_tensor += r.tensor;
        (points, seconds) = (points + r.points as u64, seconds + r.seconds);
        rules.push(m.name());
        bodies.push(nb);
    }
    let mut reach: f64 = 0.0;
    let mut series = Vec::new();
    let mut edges = Vec::new();
    for nb in &bodies {
        for line in outline(nb) {
            reach = line.iter().map(|p| p.norm()).fold(reach, f64::max);
            edges.push(line);
        }
    }
    let reach = if reach > 0.0 { 1.25 * reach } else { 1.0 };
    for (k, line) in edges.into_iter().enumerate() {
        series.push(Series {
            name: if k == 0 { "body".into() } else { String::new() },
            mark: Mark::Line,
            colour: 5,
            points: line.iter().map(project).collect(),
        });
    }
    let mut labels = Vec::new();
    for (k, name) in ["x", "y", "z"].into_iter().enumerate() {
        labels.push((name.to_string(), project(&Vector3::ith(k, 0.85 * reach))));
        series.push(Series {
            name: if k == 0 {
                "frame axes x, y, z".into()
            } else {
                String::new()
            },
            mark: Mark::Dashed,
            colour: 5,
            points: segment(Vector3::zeros(), Vector3::ith(k, 0.8 * reach)).to_vec(),
        });
    }
    let mut parts = Vec::new();
    let mut exact_dirs: Vec<Vector3<f64>> = Vec::new();
    for (colour, sp) in eigen.spaces.iter().enumerate() {
        let value = sp.value.eval(&env)?;
        let v3 = |v: &[crate::cas::Expr; 3]| -> Result<Vector3<f64>, String> {
            Ok(Vector3::new(v[0].eval(&env)?, v[1].eval(&env)?, v[2].eval(&env)?).normalize())
        };
        let (dirs, what) = match &sp.basis {
            ExactBasis::Axis(a) => {
                let u = v3(a)?;
                exact_dirs.push(u);
                (
                    vec![u],
                    format!("axis {}", Value::Vector(a.clone()).to_text()),
                )
            }
            ExactBasis::PlaneNormalTo(n) => {
                let (u, w) = plane_basis(&v3(n)?);
                (
                    vec![u, w],
                    format!(
                        "every axis perpendicular to {}",
                        Value::Vector(n.clone()).to_text()
                    ),
                )
            }
            ExactBasis::All => (
                (0..3).map(|k| Vector3::ith(k, 1.0)).collect(),
                "every axis".to_string(),
            ),
        };
        parts.push(format!(
            "moment {} ({value:.4}): {what}",
            sp.value.to_text()
        ));
        for (j, u) in dirs.iter().enumerate() {
            series.push(Series {
                name: if j == 0 {
                    format!("I = {}", sp.value.to_text())
                } else {
                    String::new()
                },
                mark: Mark::Line,
                colour,
                points: segment(-u * reach, u * reach).to_vec(),
            });
        }
    }
    // The numeric single axes, found independently from the quadrature tensor.
    let mut worst_angle: f64 = 0.0;
    let mut tips = Vec::new();
    for sp in principal_axes(&numeric_tensor) {
        if let Space::Axis(u) = sp.space {
            let best = exact_dirs
                .iter()
                .map(|e| e.dot(&u).abs().min(1.0).acos())
                .fold(f64::INFINITY, f64::min);
            worst_angle = worst_angle.max(best);
            tips.push(project(&(u * reach)));
            tips.push(project(&(-u * reach)));
        }
    }
    let axes_found = !tips.is_empty();
    let mut desc = format!(
        "Principal axes of {} through the frame origin, in an oblique view (azimuth 25°, \
         elevation 20°) at {}: {}.",
        scene.title.to_lowercase(),
        scene
            .values
            .iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect::<Vec<_>>()
            .join(", "),
        parts.join("; ")
    );
    if !tips.is_empty() {
        desc.push_str(&format!(
            " Dots: the single axes found numerically by SymmetricEigen from the quadrature tensor, \
             within {} rad of the exact ones.",
            sci(worst_angle)
        ));
        series.push(Series {
            name: "numeric axis".into(),
            mark: Mark::Points,
            colour: 4,
            points: tips,
        });
    }
    Ok(Figure {
        slug: "principal-axes".into(),
        title: "Principal axes".into(),
        desc,
        x_label: String::new(),
        y_label: String::new(),
        x_scale: Scale::Linear,
        y_scale: Scale::Linear,
        equal_aspect: true,
        series,
        labels,
        legend: Legend::UpperRight,
        accuracy: vec![Accuracy {
            result: "single principal axes (angle to the exact ones, rad)".into(),
            method: format!("SymmetricEigen of the {} tensor", rules.join(" + ")),
            true_error: axes_found.then_some(worst_angle),
            estimated_error: None,
            cost: points,
            unit: "points".into(),
            seconds,
        }],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_cube() -> NumBody {
        NumBody {
            label: "cube".into(),
            shape: NumShape::Box {
                size: Vector3::new(1.0, 1.0, 1.0),
                centred: true,
            },
            mass: 1.0,
            rotation: Matrix3::identity(),
            shift: Vector3::zeros(),
        }
    }

    #[test]
    fn convergence_slopes_follow_each_law() {
        // Centred unit cube: exact tensor 𝟙/6, independent of any quadrature.
        let fig = convergence(
            &unit_cube(),
            &(Matrix3::identity() / 6.0),
            7,
            "c".into(),
            &Fidelity::STANDARD,
        )
        .unwrap();
        let measured = |name: &str| {
            fig.series
                .iter()
                .find(|s| s.name == name)
                .unwrap()
                .points
                .clone()
        };
        // Midpoint: error ∝ 1/n² = N^(-2/3); vertex: ∝ 1/n = N^(-1/3).
        for (name, want) in [
            ("midpoint-lattice", -2.0 / 3.0),
            ("vertex-lattice", -1.0 / 3.0),
        ] {
            let p = measured(name);
            let (a, b) = (p[2], p[p.len() - 1]);
            let k = (b.1 / a.1).log10() / (b.0 / a.0).log10();
            assert!((k - want).abs() < 0.03, "{name}: slope {k}");
        }
        // Gauss–Legendre is exact for the quadratic integrand from 2 points per axis.
        let gl = measured("gauss-legendre");
        assert!(gl[0].1 > 0.1 && gl[1..].iter().all(|p| p.1 < 1e-14));
        assert!(fig.desc.contains("midpoint-lattice") && fig.desc.contains("slope -0.6"));
    }

    #[test]
    fn the_pareto_front_keeps_only_undominated_points() {
        let pts = [
            (10.0, 1e-3),
            (5.0, 1e-2),
            (20.0, 1e-3),
            (40.0, 1e-8),
            (30.0, 1e-1),
        ];
        assert_eq!(
            pareto_front(&pts),
            vec![(5.0, 1e-2), (10.0, 1e-3), (40.0, 1e-8)]
        );
        // Every dropped point is beaten on both counts by a kept one.
        for p in pts {
            let front = pareto_front(&pts);
            assert!(front.contains(&p) || front.iter().any(|q| q.0 <= p.0 && q.1 <= p.1));
        }
    }

    #[test]
    fn plane_basis_is_orthonormal_and_normal() {
        let n = Vector3::new(1.0, 1.0, 1.0);
        let (u, w) = plane_basis(&n);
        for (a, b) in [
            (u.dot(&n), 0.0),
            (w.dot(&n), 0.0),
            (u.dot(&w), 0.0),
            (u.norm(), 1.0),
            (w.norm(), 1.0),
        ] {
            assert!((a - b).abs() < 1e-15);
        }
    }
}
