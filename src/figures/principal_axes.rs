//! The principal-axes figure: the body's outline with its principal axes, projected.

use super::projection::{outline, plane_basis, project, segment};
use super::{FigureError, colour, legend_entry};
use crate::base::format::sci;
use crate::derive::{CubicRoots, Derivation, ExactBasis, ExactSpace};
use crate::model::figure::{Accuracy, Figure, Legend, Mark, Scale, Series};
use crate::model::prose::Prose;
use crate::model::value::{eval_at, vector_at};
use crate::numeric::body::NumBody;
use crate::numeric::eigen::{Space, principal_axes};
use crate::numeric::quadrature::{reference_rule, run};
use crate::scene::Scene;
use nalgebra::{Matrix3, Vector3};

/// The principal axes through the frame origin in a projected 3-D view of the body: exact axes as
/// lines, and the numeric `SymmetricEigen` axes of the reference quadrature as dots at their tips.
pub(super) fn principal_view(scene: &Scene, d: &Derivation) -> Result<Figure, FigureError> {
    let eigen = d.eigen.as_ref().ok_or(FigureError::NoEigenspaces)?;
    let q = reference_quadrature(scene, d)?;
    let (mut series, mut labels) = (Vec::new(), Vec::new());
    let reach = outlines_and_frame(&q.bodies, &mut series, &mut labels);
    let mut exact = ExactAxes::default();
    for (colour, sp) in eigen.spaces.iter().enumerate() {
        exact.space(scene, sp, colour, reach, &mut series)?;
    }
    // An irreducible cubic: its roots are in closed form but its axes are not, so the axes drawn
    // are those of the exact tensor at the scene's values, found by SymmetricEigen.
    if eigen.spaces.is_empty()
        && let Some(c) = &eigen.closed_form
    {
        exact.closed_form(scene, d, c, reach, &mut series)?;
    }
    // The numeric single axes, found independently from the quadrature tensor.
    let mut worst_angle: f64 = 0.0;
    let mut tips = Vec::new();
    for sp in principal_axes(&q.tensor) {
        if let Space::Axis(u) = sp.space {
            let best = exact
                .dirs
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
        crate::model::prose::plain(&scene.title).to_lowercase(),
        scene
            .values
            .iter()
            .map(|(k, v)| format!("{} = {v}", super::plain_name(k)))
            .collect::<Vec<_>>()
            .join(", "),
        exact.parts.join("; ")
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
            colour: colour::ACCENT,
            points: tips,
        });
    }
    Ok(Figure {
        slug: "principal-axes".into(),
        title: "Principal axes".into(),
        desc: Prose::default().text(&desc),
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
            method: format!("SymmetricEigen of the {} tensor", q.rules.join(" + ")),
            true_error: axes_found.then_some(worst_angle),
            estimated_error: None,
            cost: q.points,
            unit: "points".into(),
            seconds: q.seconds,
        }],
    })
}

/// The bodies at the scene's values, and their tensor by each body's reference quadrature, with
/// its cost.
struct Quadrature {
    bodies: Vec<NumBody>,
    tensor: Matrix3<f64>,
    points: u64,
    seconds: f64,
    rules: Vec<&'static str>,
}

fn reference_quadrature(scene: &Scene, d: &Derivation) -> Result<Quadrature, FigureError> {
    let mut q = Quadrature {
        bodies: Vec::new(),
        tensor: Matrix3::zeros(),
        points: 0,
        seconds: 0.0,
        rules: Vec::new(),
    };
    for (i, body) in scene.bodies.iter().enumerate() {
        let nb = NumBody::from_scene(body, &scene.values)?;
        let (m, l) = reference_rule(&nb.shape);
        let part = d.part_tensors[i].matrix_at(&scene.values)?;
        let r = run(&nb, m, l, &part, scene.seed);
        q.tensor += r.tensor;
        (q.points, q.seconds) = (q.points + r.points as u64, q.seconds + r.seconds);
        q.rules.push(m.name());
        q.bodies.push(nb);
    }
    Ok(q)
}

/// The bodies' outlines and the frame's axes into `series`, with the axes' labels; how far the
/// drawing reaches from the origin.
fn outlines_and_frame(
    bodies: &[NumBody],
    series: &mut Vec<Series>,
    labels: &mut Vec<(String, (f64, f64))>,
) -> f64 {
    let mut reach: f64 = 0.0;
    let mut edges = Vec::new();
    for nb in bodies {
        for line in outline(nb) {
            reach = line.iter().map(|p| p.norm()).fold(reach, f64::max);
            edges.push(line);
        }
    }
    let reach = if reach > 0.0 { 1.25 * reach } else { 1.0 };
    for (k, line) in edges.into_iter().enumerate() {
        series.push(Series {
            name: legend_entry(k == 0, "body"),
            mark: Mark::Line,
            colour: colour::REFERENCE,
            points: line.iter().map(project).collect(),
        });
    }
    for (k, name) in ["x", "y", "z"].into_iter().enumerate() {
        labels.push((name.to_string(), project(&Vector3::ith(k, 0.85 * reach))));
        series.push(Series {
            name: legend_entry(k == 0, "frame axes x, y, z"),
            mark: Mark::Dashed,
            colour: colour::REFERENCE,
            points: segment(Vector3::zeros(), Vector3::ith(k, 0.8 * reach)).to_vec(),
        });
    }
    reach
}

/// The exact axes drawn: each moment's words for the description, and the single axes' unit
/// directions, which the numeric ones are measured against.
#[derive(Default)]
struct ExactAxes {
    parts: Vec<String>,
    dirs: Vec<Vector3<f64>>,
}

impl ExactAxes {
    /// One exact eigenspace: its axis, or two axes of its plane, or the frame's three.
    fn space(
        &mut self,
        scene: &Scene,
        sp: &ExactSpace,
        colour: usize,
        reach: f64,
        series: &mut Vec<Series>,
    ) -> Result<(), FigureError> {
        let value = eval_at(&sp.value, &scene.values)?;
        let v3 = |v: &[crate::cas::Expr; 3]| -> Result<Vector3<f64>, FigureError> {
            Ok(vector_at(v, &scene.values)?.normalize())
        };
        let (dirs, what) = match &sp.basis {
            ExactBasis::Axis(a) => {
                let u = v3(a)?;
                self.dirs.push(u);
                (vec![u], format!("axis {}", super::plain_vector(a)))
            }
            ExactBasis::PlaneNormalTo(n) => {
                let (u, w) = plane_basis(&v3(n)?);
                (
                    vec![u, w],
                    format!("every axis perpendicular to {}", super::plain_vector(n)),
                )
            }
            ExactBasis::All => (
                (0..3).map(|k| Vector3::ith(k, 1.0)).collect(),
                "every axis".to_string(),
            ),
        };
        let moment = super::plain_formula(&sp.value);
        self.parts
            .push(format!("moment {moment} ({value:.4}): {what}"));
        for (j, u) in dirs.iter().enumerate() {
            series.push(Series {
                name: if j == 0 {
                    format!("I = {moment}")
                } else {
                    String::new()
                },
                mark: Mark::Line,
                colour,
                points: segment(-u * reach, u * reach).to_vec(),
            });
        }
        Ok(())
    }

    /// The axes of the exact tensor at the scene's values, its moments the cubic's roots.
    fn closed_form(
        &mut self,
        scene: &Scene,
        d: &Derivation,
        c: &CubicRoots,
        reach: f64,
        series: &mut Vec<Series>,
    ) -> Result<(), FigureError> {
        let exact = d
            .get(crate::model::catalogue::quantity::INERTIA_TENSOR)
            .map_err(|e| FigureError::Derive(Box::new(e)))?
            .matrix_at(&scene.values)?;
        let roots = c.at(&scene.values)?;
        for (colour, sp) in principal_axes(&exact).into_iter().enumerate() {
            let Space::Axis(u) = sp.space else { continue };
            self.dirs.push(u);
            let value = roots[colour.min(2)];
            self.parts.push(format!(
                "moment {value:.4} (closed form), axis ({:.4}, {:.4}, {:.4})",
                u.x, u.y, u.z
            ));
            series.push(Series {
                name: format!("I = {value:.4}"),
                mark: Mark::Line,
                colour,
                points: segment(-u * reach, u * reach).to_vec(),
            });
        }
        Ok(())
    }
}
