//! The tensor-sweep figure: the tensor's entries against one symbol, exact curves with
//! quadrature at sample values.

use super::{CURVE_POINTS, FigureError, trim_num};
use crate::base::format::sci;
use crate::cas::{EvalError, Expr};
use crate::derive::Derivation;
use crate::model::catalogue::quantity;
use crate::model::figure::{Accuracy, Figure, Legend, Mark, Scale, Series};
use crate::model::prose::Prose;
use crate::model::value::Value;
use crate::notation::Formula;
use crate::numeric::body::NumBody;
use crate::numeric::quadrature::{reference_rule, run};
use crate::scene::Scene;
use nalgebra::Matrix3;
use std::collections::BTreeMap;

pub(super) const ENTRIES: [(usize, usize, &str); 6] = [
    (0, 0, "I_xx"),
    (1, 1, "I_yy"),
    (2, 2, "I_zz"),
    (0, 1, "I_xy"),
    (0, 2, "I_xz"),
    (1, 2, "I_yz"),
];

/// An entry's name (`I_xx`, as the legend writes it) as the formula a caption sets: I with xx
/// below, as the notation names `Ixx`.
fn entry(name: &str) -> Formula {
    Formula::Expr(Expr::sym(&name.replace('_', "")))
}

pub(super) fn values_with(scene: &Scene, name: &str, v: f64) -> BTreeMap<String, f64> {
    let mut values = scene.values.clone();
    values.insert(name.to_string(), v);
    values
}

/// The tensor's entries against one symbol: exact curves, and at `samples` values the sum of
/// each body's reference quadrature rule.
pub(super) fn tensor_sweep(
    scene: &Scene,
    d: &Derivation,
    over: &str,
    from: f64,
    to: f64,
    samples: usize,
) -> Result<Figure, FigureError> {
    let exact = d.get(quantity::INERTIA_TENSOR).map_err(Box::new)?;
    let at = |k: usize, n: usize| from + (to - from) * k as f64 / (n - 1) as f64;
    let curve: Vec<(f64, Matrix3<f64>)> = (0..CURVE_POINTS)
        .map(|k| {
            let x = at(k, CURVE_POINTS);
            Ok((x, exact.matrix_at(&values_with(scene, over, x))?))
        })
        .collect::<Result<_, EvalError>>()?;
    let q = quadrature_sweep(scene, d, exact, over, (0..samples).map(|k| at(k, samples)))?;
    let scale = curve.iter().map(|(_, m)| m.amax()).fold(0.0, f64::max);
    let mut series = Vec::new();
    let (shown, zero) = entry_series(&curve, &q.numeric, scale, &mut series);
    let fixed: Vec<String> = scene
        .values
        .iter()
        .filter(|(k, _)| k.as_str() != over)
        .map(|(k, v)| format!("{} = {v}", super::plain_name(k)))
        .collect();
    // The file keeps the name as written; the reader sees it as its symbol (α, not alpha).
    let slug = format!("tensor-vs-{over}");
    let over = &super::plain_name(over);
    let mut desc = Prose::default().run_on(&format!(
        "Inertia tensor entries of {} against {over} from {} to {}, at {}. Over this range ",
        crate::model::prose::plain(&scene.title).to_lowercase(),
        trim_num(from),
        trim_num(to),
        fixed.join(", "),
    ));
    for (k, (name, range)) in shown.iter().enumerate() {
        desc = desc
            .run_on(if k == 0 { "" } else { "; " })
            .formula(entry(name))
            .run_on(range);
    }
    if !zero.is_empty() {
        for (k, name) in zero.iter().enumerate() {
            desc = desc
                .run_on(if k == 0 { "; " } else { ", " })
                .formula(entry(name));
        }
        desc = desc.run_on(" stay zero");
    }
    let desc = desc.run_on(&format!(
        ". Dots: {samples} values of {over} by quadrature with {}, at most {} from the exact \
         curves.",
        q.rule_names.join(", "),
        sci(q.worst),
    ));
    Ok(Figure {
        slug,
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
            method: q.rule_names.join(", "),
            true_error: Some(q.worst / scale.max(f64::MIN_POSITIVE)),
            estimated_error: Some(q.predicted),
            cost: q.points,
            unit: "points".into(),
            seconds: q.seconds,
        }],
    })
}

/// The tensor by each body's reference quadrature at each value of the swept symbol, its
/// largest distance from the exact one, and its cost.
struct Sweep {
    numeric: Vec<(f64, Matrix3<f64>)>,
    worst: f64,
    rule_names: Vec<String>,
    points: u64,
    predicted: f64,
    seconds: f64,
}

fn quadrature_sweep(
    scene: &Scene,
    d: &Derivation,
    exact: &Value,
    over: &str,
    xs: impl Iterator<Item = f64>,
) -> Result<Sweep, FigureError> {
    let mut q = Sweep {
        numeric: Vec::new(),
        worst: 0.0,
        rule_names: Vec::new(),
        points: 0,
        predicted: 0.0,
        seconds: 0.0,
    };
    for (k, x) in xs.enumerate() {
        let values = values_with(scene, over, x);
        let mut total = Matrix3::zeros();
        for (i, body) in scene.bodies.iter().enumerate() {
            let nb = NumBody::from_scene(body, &values)?;
            let (method, level) = reference_rule(&nb.shape);
            let part = d.part_tensors[i].matrix_at(&values)?;
            let r = run(&nb, method, level, &part, scene.seed);
            q.points += r.points as u64;
            q.predicted = q.predicted.max(r.predicted_error);
            q.seconds += r.seconds;
            if k == 0 {
                q.rule_names
                    .push(format!("{}, {} points", method.name(), r.points));
            }
            total += r.tensor;
        }
        q.worst = q.worst.max((total - exact.matrix_at(&values)?).amax());
        q.numeric.push((x, total));
    }
    Ok(q)
}

/// Each entry that is not zero along the range, exact as a line and by quadrature as dots, into
/// `series`; the entries shown, with their ranges, and those that stay zero.
fn entry_series(
    curve: &[(f64, Matrix3<f64>)],
    numeric: &[(f64, Matrix3<f64>)],
    scale: f64,
    series: &mut Vec<Series>,
) -> (Vec<(&'static str, String)>, Vec<&'static str>) {
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
        shown.push((*name, format!(" from {lo:.3} to {hi:.3}")));
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
    (shown, zero)
}
