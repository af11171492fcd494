//! A step's expression against a coordinate or a symbol: the exact result as a curve at the
//! scene's values, and at sample values a second route that does not use it: the expression
//! as written (`be`, `substitute`), or central differences of the expression differentiated.

use super::{CURVE_POINTS, FigureError, trim_num};
use crate::base::format::sci;
use crate::cas::Expr;
use crate::derive::Derivation;
use crate::derive::step_names::{expand_names, substituted};
use crate::model::figure::{Accuracy, Figure, Legend, Mark, Scale, Series};
use crate::scene::{Operation, Scene};
use std::collections::BTreeMap;

/// The central-difference step of the differentiated route, halved once for Richardson's
/// extrapolation (error O(h⁴) ≈ 1e-12 of the scale).
const H: f64 = 1e-3;

/// How the dots are computed, and the function they evaluate at a value of `over`.
type Route<'a> = (
    String,
    Box<dyn Fn(&BTreeMap<String, f64>) -> Result<f64, FigureError> + 'a>,
);

/// The second route of a step, where it has one.
fn second_route<'a>(scene: &'a Scene, d: &'a Derivation, step: &str) -> Option<Route<'a>> {
    let s = scene.steps.iter().find(|s| s.name == step)?;
    let eval = |e: &Expr, env: &BTreeMap<String, f64>| -> Result<f64, FigureError> {
        Ok(e.eval(&|n| env.get(n).copied().filter(|_| n != "pi"))?)
    };
    match &s.op {
        Operation::Be(e) => {
            let written = expand_names(scene, d, s, e).ok()?;
            Some((
                "the expression as written".into(),
                Box::new(move |env| eval(&written, env)),
            ))
        }
        Operation::Substitute { of, set } => {
            let written = substituted(scene, d, s, of, set).ok()?;
            Some((
                "the expression as written, with its replacements".into(),
                Box::new(move |env| eval(&written, env)),
            ))
        }
        Operation::Differentiate { of, by } if by != "t" => {
            let f = expand_names(scene, d, s, of).ok()?;
            let by = by.clone();
            Some((
                format!(
                    "central differences in {by} of the expression differentiated (Richardson, h = {H})"
                ),
                Box::new(move |env| {
                    let x = *env.get(&by).ok_or_else(|| FigureError::NoValueAt {
                        step: String::new(),
                        name: by.clone(),
                    })?;
                    let mut shifted = env.clone();
                    let mut at = |v: f64| {
                        shifted.insert(by.clone(), v);
                        eval(&f, &shifted)
                    };
                    let central = |h: f64, at: &mut dyn FnMut(f64) -> Result<f64, FigureError>| {
                        Ok::<f64, FigureError>((at(x + h)? - at(x - h)?) / (2.0 * h))
                    };
                    let (coarse, fine) = (central(H, &mut at)?, central(H / 2.0, &mut at)?);
                    Ok((4.0 * fine - coarse) / 3.0)
                }),
            ))
        }
        _ => None,
    }
}

pub(super) fn expression(
    scene: &Scene,
    d: &Derivation,
    step: &str,
    over: &str,
    (from, to): (f64, f64),
    samples: usize,
    at: &BTreeMap<String, f64>,
) -> Result<Figure, FigureError> {
    let exact =
        d.named
            .get(step)
            .and_then(|r| r.scalar())
            .ok_or_else(|| FigureError::NotAnExpression {
                step: step.to_string(),
            })?;
    let mut env = scene.values.clone();
    env.extend(at.iter().map(|(k, v)| (k.clone(), *v)));
    let with = |x: f64| {
        let mut e = env.clone();
        e.insert(over.to_string(), x);
        e
    };
    let located = |e: FigureError| match e {
        FigureError::Eval(crate::cas::EvalError::NoValue(name))
        | FigureError::NoValueAt { name, .. } => FigureError::NoValueAt {
            step: step.to_string(),
            name,
        },
        other => other,
    };
    let value = |x: f64| -> Result<f64, FigureError> {
        let env = with(x);
        Ok(exact.eval(&|n| env.get(n).copied().filter(|_| n != "pi"))?)
    };
    let x_at = |k: usize, n: usize| from + (to - from) * k as f64 / (n - 1) as f64;
    let mut curve = Vec::new();
    let mut poles = 0;
    for k in 0..CURVE_POINTS {
        let x = x_at(k, CURVE_POINTS);
        match value(x).map_err(located)? {
            y if y.is_finite() => curve.push((x, y)),
            _ => poles += 1,
        }
    }
    let started = std::time::Instant::now();
    let mut dots = Vec::new();
    let mut worst: f64 = 0.0;
    let route = second_route(scene, d, step);
    if let Some((_, f)) = &route {
        for k in 0..samples {
            let x = x_at(k, samples);
            let (a, b) = (f(&with(x)).map_err(located)?, value(x).map_err(located)?);
            if a.is_finite() && b.is_finite() {
                worst = worst.max((a - b).abs() / a.abs().max(b.abs()).max(1.0));
                dots.push((x, a));
            }
        }
    }
    let seconds = started.elapsed().as_secs_f64();
    let (low, high) = curve.iter().fold(
        ((f64::NAN, f64::INFINITY), (f64::NAN, f64::NEG_INFINITY)),
        |(lo, hi), &(x, y)| {
            (
                if y < lo.1 { (x, y) } else { lo },
                if y > hi.1 { (x, y) } else { hi },
            )
        },
    );
    let fixed: Vec<String> = env
        .iter()
        .filter(|(k, _)| k.as_str() != over && exact.symbols().contains(k))
        .map(|(k, v)| format!("{} = {v}", super::plain_name(k)))
        .collect();
    // The file keeps the names as written; the reader sees them as symbols.
    let file_name = format!("{step}-vs-{over}");
    let (step, over) = (&super::plain_name(step), &super::plain_name(over));
    let dotted = match &route {
        Some((method, _)) => format!(
            " Dots: {} values of {over} by {method}, at most {} (relative) from the curve.",
            dots.len(),
            sci(worst)
        ),
        None => " The curve is the exact result; the step's own numeric check is in its \
                 derivation."
            .to_string(),
    };
    let desc = format!(
        "{step} against {over} from {} to {}{}. Lowest {:.4} at {over} = {:.4}, highest {:.4} at \
         {over} = {:.4}.{}{dotted}",
        trim_num(from),
        trim_num(to),
        if fixed.is_empty() {
            String::new()
        } else {
            format!(", at {}", fixed.join(", "))
        },
        low.1,
        low.0,
        high.1,
        high.0,
        if poles > 0 {
            format!(
                " {poles} of {CURVE_POINTS} points have no finite value (a pole) and are left out."
            )
        } else {
            String::new()
        },
    );
    let legend = free_corner(&curve, (from, to), (low.1, high.1));
    let mut series = vec![Series {
        name: format!("{step} exact"),
        mark: Mark::Line,
        colour: super::colour::PRIMARY,
        points: curve,
    }];
    let mut accuracy = Vec::new();
    if let Some((method, _)) = route {
        series.push(Series {
            name: "second route".into(),
            mark: Mark::Points,
            colour: super::colour::ACCENT,
            points: dots,
        });
        accuracy.push(Accuracy {
            result: format!("{step} at {samples} values of {over}"),
            method,
            true_error: Some(worst),
            estimated_error: None,
            cost: samples as u64,
            unit: "values".into(),
            seconds,
        });
    }
    let slug: String = file_name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '-'
            }
        })
        .collect();
    Ok(Figure {
        slug,
        title: format!("{step} against {over}"),
        desc,
        x_label: over.to_string(),
        y_label: step.to_string(),
        x_scale: Scale::Linear,
        y_scale: Scale::Linear,
        equal_aspect: false,
        series,
        labels: Vec::new(),
        legend,
        accuracy,
    })
}

/// The first corner the curve leaves empty (the outer third across, quarter up or down), so
/// that the legend hides no point.
fn free_corner(curve: &[(f64, f64)], (x0, x1): (f64, f64), (y0, y1): (f64, f64)) -> Legend {
    let (w, h) = (x1 - x0, (y1 - y0).max(f64::MIN_POSITIVE));
    let right = |x: f64| x > x1 - w / 3.0;
    let left = |x: f64| x < x0 + w / 3.0;
    let top = |y: f64| y > y1 - h / 4.0;
    let bottom = |y: f64| y < y0 + h / 4.0;
    let empty = |inside: &dyn Fn(f64, f64) -> bool| !curve.iter().any(|&(x, y)| inside(x, y));
    if empty(&|x, y| right(x) && top(y)) {
        Legend::UpperRight
    } else if empty(&|x, y| left(x) && top(y)) {
        Legend::UpperLeft
    } else if empty(&|x, y| right(x) && bottom(y)) {
        Legend::LowerRight
    } else if empty(&|x, y| left(x) && bottom(y)) {
        Legend::LowerLeft
    } else {
        Legend::MiddleRight
    }
}
