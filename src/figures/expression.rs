//! A step's expression against a coordinate or a symbol: the exact result as a curve at the
//! scene's values, and at sample values a second route that does not use it: the expression
//! as written (`be`, `substitute`), or central differences of the expression differentiated.

use super::{CURVE_POINTS, FigureError, trim_num};
use crate::base::format::sci;
use crate::cas::Expr;
use crate::derive::Derivation;
use crate::derive::step_names::{expand_names, substituted};
use crate::model::figure::{Accuracy, Figure, Legend, Mark, Scale, Series};
use crate::model::prose::Prose;
use crate::scene::operations::{Be, Differentiate, Substitute};
use crate::scene::{Operation, Scene};
use std::collections::BTreeMap;

/// The central-difference step of the differentiated route, halved once for Richardson's
/// extrapolation (error O(h⁴) ≈ 1e-12 of the scale).
const H: f64 = 1e-3;

/// A route's value at the names' values.
type AtValues<'a> = dyn Fn(&BTreeMap<String, f64>) -> Result<f64, FigureError> + 'a;

/// How the dots are computed, and the function they evaluate at a value of `over`.
type Route<'a> = (String, Box<AtValues<'a>>);

/// The second route of a step, where it has one.
fn second_route<'a>(scene: &'a Scene, d: &'a Derivation, step: &str) -> Option<Route<'a>> {
    let s = scene.steps.iter().find(|s| s.name == step)?;
    let eval = |e: &Expr, env: &BTreeMap<String, f64>| -> Result<f64, FigureError> {
        Ok(e.eval(&|n| env.get(n).copied().filter(|_| n != "pi"))?)
    };
    match &s.op {
        Operation::Be(Be(e)) => {
            let written = expand_names(scene, d, s, e).ok()?;
            Some((
                "the expression as written".into(),
                Box::new(move |env| eval(&written, env)),
            ))
        }
        Operation::Substitute(Substitute { of, set }) => {
            let written = substituted(scene, d, s, of, set).ok()?;
            Some((
                "the expression as written, with its replacements".into(),
                Box::new(move |env| eval(&written, env)),
            ))
        }
        Operation::Differentiate(Differentiate { of, by }) if by != "t" => {
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
    let curve_of = CurveOf {
        exact,
        env: &env,
        step,
        over,
        from,
        to,
    };
    let Sampled {
        curve,
        poles,
        low,
        high,
    } = curve_of.sample()?;
    let dotted = curve_of.dotted(second_route(scene, d, step), samples)?;
    // The file keeps the names as written; the reader sees them as symbols.
    let slug = slug(&format!("{step}-vs-{over}"));
    let (step, over) = (&super::plain_name(step), &super::plain_name(over));
    let desc = curve_of.description((low, high), poles, dotted.as_ref());
    let legend = free_corner(&curve, (from, to), (low.1, high.1));
    let mut series = vec![Series {
        name: format!("{step} exact"),
        mark: Mark::Line,
        colour: super::colour::PRIMARY,
        points: curve,
    }];
    let mut accuracy = Vec::new();
    if let Some(d) = dotted {
        series.push(Series {
            name: "second route".into(),
            mark: Mark::Points,
            colour: super::colour::ACCENT,
            points: d.dots,
        });
        accuracy.push(Accuracy {
            result: format!("{step} at {samples} values of {over}"),
            method: d.method,
            true_error: Some(d.worst),
            estimated_error: None,
            cost: samples as u64,
            unit: "values".into(),
            seconds: d.seconds,
        });
    }
    Ok(Figure {
        slug,
        title: format!("{step} against {over}"),
        desc: Prose::default().text(&desc),
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

/// The second route's values as dots: how they are computed, their largest distance from the
/// curve, and their time.
struct Dotted {
    method: String,
    dots: Vec<(f64, f64)>,
    worst: f64,
    seconds: f64,
}

/// The exact curve, and where it is lowest and highest.
struct Sampled {
    curve: Vec<(f64, f64)>,
    poles: usize,
    low: (f64, f64),
    high: (f64, f64),
}

/// A step's exact result as a function of `over` from `from` to `to`, the other names at
/// their values in `env`.
struct CurveOf<'a> {
    exact: &'a Expr,
    env: &'a BTreeMap<String, f64>,
    step: &'a str,
    over: &'a str,
    from: f64,
    to: f64,
}

impl CurveOf<'_> {
    /// The `k`th of `n` evenly spaced values of `over`, ends included.
    fn x_at(&self, k: usize, n: usize) -> f64 {
        self.from + (self.to - self.from) * k as f64 / (n - 1) as f64
    }

    /// The exact result at [`CURVE_POINTS`] values of `over`, its poles left out, and its
    /// lowest and highest points.
    fn sample(&self) -> Result<Sampled, FigureError> {
        let mut curve = Vec::new();
        let mut poles = 0;
        for k in 0..CURVE_POINTS {
            let x = self.x_at(k, CURVE_POINTS);
            match self.value(x)? {
                y if y.is_finite() => curve.push((x, y)),
                _ => poles += 1,
            }
        }
        let (low, high) = curve.iter().fold(
            ((f64::NAN, f64::INFINITY), (f64::NAN, f64::NEG_INFINITY)),
            |(lo, hi), &(x, y)| {
                (
                    if y < lo.1 { (x, y) } else { lo },
                    if y > hi.1 { (x, y) } else { hi },
                )
            },
        );
        Ok(Sampled {
            curve,
            poles,
            low,
            high,
        })
    }

    /// What the figure shows, in words: the range, the other names' values, the lowest and
    /// highest points, the poles, and the dots (`dotted`).
    fn description(
        &self,
        (low, high): ((f64, f64), (f64, f64)),
        poles: usize,
        dotted: Option<&Dotted>,
    ) -> String {
        let fixed: Vec<String> = self
            .env
            .iter()
            .filter(|(k, _)| k.as_str() != self.over && self.exact.symbols().contains(k))
            .map(|(k, v)| format!("{} = {v}", super::plain_name(k)))
            .collect();
        let (step, over) = (&super::plain_name(self.step), &super::plain_name(self.over));
        let (from, to) = (self.from, self.to);
        let dotted = match dotted {
            Some(d) => format!(
                " Dots: {} values of {over} by {}, at most {} (relative) from the curve.",
                d.dots.len(),
                d.method,
                sci(d.worst)
            ),
            None => " The curve is the exact result; the step's own numeric check is in its \
                     derivation."
                .to_string(),
        };
        format!(
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
        )
    }

    /// The names' values with `over` at `x`.
    fn env_at(&self, x: f64) -> BTreeMap<String, f64> {
        let mut e = self.env.clone();
        e.insert(self.over.to_string(), x);
        e
    }

    /// A missing value, said with the step it is missing from.
    fn located(&self, e: FigureError) -> FigureError {
        match e {
            FigureError::Eval(crate::cas::EvalError::NoValue(name))
            | FigureError::NoValueAt { name, .. } => FigureError::NoValueAt {
                step: self.step.to_string(),
                name,
            },
            other => other,
        }
    }

    fn value(&self, x: f64) -> Result<f64, FigureError> {
        let env = self.env_at(x);
        self.exact
            .eval(&|n| env.get(n).copied().filter(|_| n != "pi"))
            .map_err(|e| self.located(e.into()))
    }

    /// The dots of the step's second route, where it has one, timed.
    fn dotted(&self, route: Option<Route>, samples: usize) -> Result<Option<Dotted>, FigureError> {
        let started = std::time::Instant::now();
        let Some((method, f)) = route else {
            return Ok(None);
        };
        let (dots, worst) = self.second_route(f.as_ref(), samples)?;
        Ok(Some(Dotted {
            method,
            dots,
            worst,
            seconds: started.elapsed().as_secs_f64(),
        }))
    }

    /// The second route at `samples` values of `over` where both are finite, and its largest
    /// distance (relative, at least to 1) from the exact result.
    fn second_route(
        &self,
        f: &AtValues<'_>,
        samples: usize,
    ) -> Result<(Vec<(f64, f64)>, f64), FigureError> {
        let mut dots = Vec::new();
        let mut worst: f64 = 0.0;
        for k in 0..samples {
            let x = self.x_at(k, samples);
            let (a, b) = (
                f(&self.env_at(x)).map_err(|e| self.located(e))?,
                self.value(x)?,
            );
            if a.is_finite() && b.is_finite() {
                worst = worst.max((a - b).abs() / a.abs().max(b.abs()).max(1.0));
                dots.push((x, a));
            }
        }
        Ok((dots, worst))
    }
}

/// A file's name made of letters, digits, `-` and `_`.
fn slug(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '-'
            }
        })
        .collect()
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
