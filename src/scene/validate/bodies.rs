//! `[[body]]`: shapes, dimensions, masses, rotations and shifts.

use super::{Validator, content_start};
use crate::cas::{Expr, parse_input as parse_expr};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawBody, RawScene, Text};
use crate::scene::types::{Axis, Body, ConeOrigin, Shape};

/// The body kinds a scene may name.
pub const BODY_KINDS: &[&str] = &[
    "box",
    "plate",
    "rod",
    "hoop",
    "ring",
    "disk",
    "cylinder",
    "sphere",
    "shell",
    "cone",
    "hemisphere",
    "points",
];
use std::collections::{BTreeMap, BTreeSet};
use toml::Spanned;

impl Validator<'_> {
    /// Every body. Its integration variables are its own: where the scene names a symbol,
    /// coordinate, definition, vector, step or step's integration variable `r`, the body
    /// integrates over `r_1` instead.
    pub(super) fn bodies(
        &self,
        raw: &RawScene,
        allowed: &BTreeSet<String>,
    ) -> Result<Vec<Body>, SceneError> {
        let taken: BTreeSet<&str> = raw
            .symbols
            .keys()
            .chain(raw.coordinates.keys())
            .chain(raw.definitions.keys())
            .chain(raw.vectors.keys())
            .map(|k| k.get_ref().as_str())
            .chain(
                raw.steps
                    .iter()
                    .map(|s| s.get_ref().name.get_ref().as_str()),
            )
            // An `integrate` step's own variables.
            .chain(raw.steps.iter().flat_map(|s| {
                s.get_ref()
                    .over
                    .iter()
                    .filter_map(|range| range.get_ref().first().map(|v| v.get_ref().as_str()))
            }))
            .collect();
        let mut bodies = Vec::new();
        for (i, b) in raw.bodies.iter().enumerate() {
            let mut body = self.body(b, &format!("body[{i}]"), allowed)?;
            body.variables = body
                .shape
                .variables()
                .iter()
                .map(|v| own_name(v, &taken))
                .collect();
            bodies.push(body);
        }
        Ok(bodies)
    }

    fn body(
        &self,
        b: &Spanned<RawBody>,
        field: &str,
        allowed: &BTreeSet<String>,
    ) -> Result<Body, SceneError> {
        let start = b.span().start;
        let rb = b.get_ref();
        let kind = rb.kind.get_ref().as_str();
        let req = |t: &Option<Text>, name: &str| -> Result<Expr, SceneError> {
            match t {
                Some(t) => self.expr(t, &format!("{field}.{name}"), allowed),
                None => Err(self.err(
                    start,
                    &format!("{field}.{name}"),
                    format!("missing field `{name}` for a {kind}"),
                )),
            }
        };
        // Fields that do not apply to this kind are errors, not silently ignored.
        let present: Vec<(&str, bool)> = vec![
            ("size", rb.size.is_some()),
            ("radius", rb.radius.is_some()),
            ("length", rb.length.is_some()),
            ("height", rb.height.is_some()),
            ("inner_radius", rb.inner_radius.is_some()),
            ("origin", rb.origin.is_some()),
            ("along", rb.along.is_some()),
            ("points", !rb.points.is_empty()),
            ("mass", rb.mass.is_some()),
        ];
        let applies: &[&str] = match kind {
            "box" | "plate" => &["size", "origin", "mass"],
            "rod" => &["length", "along", "origin", "mass"],
            "hoop" | "ring" | "shell" => &["radius", "mass"],
            "disk" | "sphere" => &["radius", "inner_radius", "mass"],
            "cylinder" => &["radius", "height", "inner_radius", "mass"],
            "cone" => &["radius", "height", "origin", "mass"],
            "hemisphere" => &["radius", "origin", "mass"],
            "points" => &["points"],
            other => {
                return Err(self.err(
                    content_start(&rb.kind),
                    &format!("{field}.kind"),
                    format!(
                        "unknown body kind `{other}`{}; the kinds are {}",
                        crate::base::suggest::did_you_mean(other, BODY_KINDS.iter().copied()),
                        BODY_KINDS.join(", ")
                    ),
                ));
            }
        };
        if let Some((name, _)) = present.iter().find(|(n, p)| *p && !applies.contains(n)) {
            return Err(self.err(
                start,
                &format!("{field}.{name}"),
                format!("field `{name}` does not apply to a {kind}"),
            ));
        }
        // The first choice is the default; `center` is accepted for `centre`.
        let origin_choice = |choices: &[&str]| -> Result<usize, SceneError> {
            let Some(o) = &rb.origin else { return Ok(0) };
            let given = match o.get_ref().as_str() {
                "center" => "centre",
                g => g,
            };
            choices.iter().position(|c| *c == given).ok_or_else(|| {
                let quoted: Vec<String> = choices.iter().map(|c| format!("`{c}`")).collect();
                let (last, rest) = quoted.split_last().expect("two choices or more");
                self.err(
                    content_start(o),
                    &format!("{field}.origin"),
                    format!("expected {} or {last} for a {kind}", rest.join(", ")),
                )
            })
        };
        let origin =
            |choices: [&str; 2]| -> Result<bool, SceneError> { Ok(origin_choice(&choices)? == 1) };
        let inner = || -> Result<Option<Expr>, SceneError> {
            rb.inner_radius
                .as_ref()
                .map(|t| self.expr(t, &format!("{field}.inner_radius"), allowed))
                .transpose()
        };
        let shape = match kind {
            "box" => {
                let Some(size) = &rb.size else {
                    return Err(self.err(
                        start,
                        &format!("{field}.size"),
                        "missing field `size` for a box",
                    ));
                };
                Shape::Box {
                    size: self.vec3(size, &format!("{field}.size"), allowed)?,
                    centred: origin(["corner", "centre"])?,
                }
            }
            "rod" => {
                let along = match rb.along.as_ref().map(|a| a.get_ref().as_str()) {
                    None | Some("z") => Axis::Z,
                    Some("x") => Axis::X,
                    Some("y") => Axis::Y,
                    Some(_) => {
                        return Err(self.err(
                            content_start(rb.along.as_ref().unwrap()),
                            &format!("{field}.along"),
                            "expected x, y or z",
                        ));
                    }
                };
                Shape::Rod {
                    length: req(&rb.length, "length")?,
                    along,
                    centred: origin(["end", "centre"])?,
                }
            }
            "plate" => {
                let Some(size) = &rb.size else {
                    return Err(self.err(
                        start,
                        &format!("{field}.size"),
                        "missing field `size = [a, b]` for a plate",
                    ));
                };
                Shape::Plate {
                    size: self.vec2(size, &format!("{field}.size"), allowed)?,
                    centred: origin(["corner", "centre"])?,
                }
            }
            "hoop" | "ring" => Shape::Hoop {
                radius: req(&rb.radius, "radius")?,
            },
            "disk" => Shape::Disk {
                radius: req(&rb.radius, "radius")?,
                inner: inner()?,
            },
            "cylinder" => Shape::Cylinder {
                radius: req(&rb.radius, "radius")?,
                height: req(&rb.height, "height")?,
                inner: inner()?,
            },
            "sphere" => Shape::Sphere {
                radius: req(&rb.radius, "radius")?,
                inner: inner()?,
            },
            "cone" => Shape::Cone {
                radius: req(&rb.radius, "radius")?,
                height: req(&rb.height, "height")?,
                origin: [ConeOrigin::Apex, ConeOrigin::Base, ConeOrigin::Centre]
                    [origin_choice(&["apex", "base", "centre"])?],
            },
            "hemisphere" => Shape::Hemisphere {
                radius: req(&rb.radius, "radius")?,
                centred: origin(["base", "centre"])?,
            },
            "shell" => Shape::Shell {
                radius: req(&rb.radius, "radius")?,
            },
            _ => {
                if rb.points.is_empty() {
                    return Err(self.err(
                        start,
                        &format!("{field}.points"),
                        "a point set needs at least one [[body.points]]",
                    ));
                }
                let mut pts = Vec::new();
                for (j, p) in rb.points.iter().enumerate() {
                    let f = format!("{field}.points[{j}]");
                    pts.push((
                        self.expr(&p.get_ref().mass, &format!("{f}.mass"), allowed)?,
                        self.vec3(&p.get_ref().at, &format!("{f}.at"), allowed)?,
                    ));
                }
                Shape::Points(pts)
            }
        };
        let subtract = rb.subtract.unwrap_or(false);
        // A hole carries its removed mass with a minus sign, so every sum over bodies is right.
        let signed = |m: Expr| if subtract { Expr::negate(m) } else { m };
        let (shape, mass) = match shape {
            Shape::Points(pts) => {
                let pts: Vec<(Expr, [Expr; 3])> =
                    pts.into_iter().map(|(m, at)| (signed(m), at)).collect();
                let mass = Expr::add(pts.iter().map(|(m, _)| m.clone()).collect());
                (Shape::Points(pts), mass)
            }
            shape => (shape, signed(req(&rb.mass, "mass")?)),
        };
        let mut rotations = Vec::new();
        for (j, r) in rb.rotate.iter().enumerate() {
            let f = format!("{field}.rotate[{j}]");
            let axis = match r.get_ref().axis.get_ref().as_str() {
                "x" => Axis::X,
                "y" => Axis::Y,
                "z" => Axis::Z,
                _ => {
                    return Err(self.err(
                        content_start(&r.get_ref().axis),
                        &format!("{f}.axis"),
                        "expected x, y or z",
                    ));
                }
            };
            rotations.push((
                axis,
                self.expr(&r.get_ref().angle, &format!("{f}.angle"), allowed)?,
            ));
        }
        let shift = match &rb.shift {
            Some(s) => self.vec3(s, &format!("{field}.shift"), allowed)?,
            None => [Expr::int(0), Expr::int(0), Expr::int(0)],
        };
        Ok(Body {
            label: rb
                .label
                .as_ref()
                .map_or_else(|| shape.kind().to_string(), |l| l.get_ref().clone()),
            shape,
            mass,
            subtract,
            rotations,
            shift,
            variables: Vec::new(),
        })
    }

    /// The first rule of the bodies that `values` break, if any: sizes and masses positive
    /// and finite, inner radii below radii, holes lighter than what they are cut from. The same
    /// rules hold at the scene's values and in every variant.
    pub(super) fn broken_rule(
        &self,
        raw: &RawScene,
        bodies: &[Body],
        values: &BTreeMap<String, f64>,
    ) -> Option<Broken> {
        raw.bodies
            .iter()
            .enumerate()
            .find_map(|(i, rb)| positive(rb.get_ref(), &format!("body[{i}]"), values))
            .or_else(|| total_mass(raw, bodies, values))
    }
}

/// A rule the values break: at which field (its offset in the file), what, and the symbols the
/// field uses. Its message reads `{before} {where}{after}`, where `where` says which values.
pub(super) struct Broken {
    pub at: usize,
    pub field: String,
    pub symbols: BTreeSet<String>,
    before: String,
    after: String,
}

impl Broken {
    pub fn message(&self, at_which_values: &str) -> String {
        format!("{} {at_which_values}{}", self.before, self.after)
    }
}

/// Sizes and masses must be positive and finite; an inner radius less than the radius.
fn positive(rb: &RawBody, field: &str, values: &BTreeMap<String, f64>) -> Option<Broken> {
    let env = |s: &str| values.get(s).copied();
    let parsed = |t: &Text| parse_expr(t.get_ref()).expect("validated").expr;
    let mut checks: Vec<(&Text, String)> = Vec::new();
    if let Some(m) = &rb.mass {
        checks.push((m, format!("{field}.mass")));
    }
    for (name, t) in [
        ("radius", &rb.radius),
        ("inner_radius", &rb.inner_radius),
        ("length", &rb.length),
        ("height", &rb.height),
    ] {
        if let Some(t) = t {
            checks.push((t, format!("{field}.{name}")));
        }
    }
    if let Some(size) = &rb.size {
        for (i, t) in size.get_ref().iter().enumerate() {
            checks.push((t, format!("{field}.size[{i}]")));
        }
    }
    for (j, p) in rb.points.iter().enumerate() {
        checks.push((&p.get_ref().mass, format!("{field}.points[{j}].mass")));
    }
    let broken = |t: &Text, field: String, before: String, after: &str| Broken {
        at: content_start(t),
        field,
        symbols: parsed(t).symbols().into_iter().collect(),
        before,
        after: after.to_string(),
    };
    for (t, f) in checks {
        match parsed(t).eval(&env) {
            Err(m) => return Some(broken(t, f, m.to_string(), "")),
            Ok(v) if !(v.is_finite() && v > 0.0) => {
                return Some(broken(
                    t,
                    f,
                    format!("must be positive and finite, but is {v}"),
                    "",
                ));
            }
            Ok(_) => {}
        }
    }
    if let (Some(inner), Some(outer)) = (&rb.inner_radius, &rb.radius)
        && let (Ok(i), Ok(o)) = (parsed(inner).eval(&env), parsed(outer).eval(&env))
        && i >= o
    {
        let mut b = broken(
            inner,
            format!("{field}.inner_radius"),
            format!("must be less than `radius`, but is {i} against {o}"),
            "",
        );
        b.symbols.extend(parsed(outer).symbols());
        return Some(b);
    }
    None
}

/// Holes may not remove more than there is: the bodies' total mass must stay positive.
fn total_mass(raw: &RawScene, bodies: &[Body], values: &BTreeMap<String, f64>) -> Option<Broken> {
    if !bodies.iter().any(|b| b.subtract) {
        return None;
    }
    let env = |s: &str| values.get(s).copied();
    let total: f64 = bodies
        .iter()
        .map(|b| b.mass.eval(&env).unwrap_or(f64::NAN))
        .sum();
    if total.is_finite() && total > 0.0 {
        return None;
    }
    let at = raw
        .bodies
        .iter()
        .rposition(|b| b.get_ref().subtract == Some(true));
    Some(Broken {
        at: at.map_or(0, |i| raw.bodies[i].span().start),
        field: format!("body[{}].mass", at.unwrap_or(0)),
        symbols: bodies.iter().flat_map(|b| b.mass.symbols()).collect(),
        before: format!("the holes remove more than the bodies hold: the total mass is {total}"),
        after: "; it must stay positive".to_string(),
    })
}

pub(super) fn body_symbols(b: &Body) -> BTreeSet<String> {
    let mut exprs: Vec<&Expr> = b.dimensions();
    exprs.extend(b.shift.iter());
    exprs.extend(b.rotations.iter().map(|(_, a)| a));
    if let Shape::Points(pts) = &b.shape {
        pts.iter().for_each(|(_, at)| exprs.extend(at.iter()));
    }
    exprs.iter().flat_map(|e| e.symbols()).collect()
}

/// `v` if the scene does not use it, else the first of `v_1`, `v_2`, ... that it does not.
fn own_name(v: &str, taken: &BTreeSet<&str>) -> String {
    if !taken.contains(v) {
        return v.to_string();
    }
    (1..)
        .map(|k| format!("{v}_{k}"))
        .find(|n| !taken.contains(n.as_str()))
        .expect("a scene names finitely many things")
}
