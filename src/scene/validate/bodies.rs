//! `[[body]]`: shapes, dimensions, masses, rotations and shifts.

use super::{Validator, content_start};
use crate::cas::{Expr, parse_input as parse_expr};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawBody, RawScene, Text};
use crate::scene::types::{Axis, Body, Shape};
use std::collections::{BTreeMap, BTreeSet};
use toml::Spanned;

impl Validator<'_> {
    /// Every body; a symbol may not take the name of a body's integration variable.
    pub(super) fn bodies(
        &self,
        raw: &RawScene,
        allowed: &BTreeSet<String>,
    ) -> Result<Vec<Body>, SceneError> {
        let mut bodies = Vec::new();
        for (i, b) in raw.bodies.iter().enumerate() {
            bodies.push(self.body(b, &format!("body[{i}]"), allowed)?);
        }
        for (i, b) in bodies.iter().enumerate() {
            for v in b.shape.variables() {
                if let Some((name, _)) = raw.symbols.iter().find(|(n, _)| n.get_ref() == v) {
                    return Err(self.err(name.span().start, &format!("symbols.{v}"), format!("`{v}` is the integration variable of body[{i}] ({}); choose another name", b.shape.kind())));
                }
            }
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
            ("origin", rb.origin.is_some()),
            ("along", rb.along.is_some()),
            ("points", !rb.points.is_empty()),
            ("mass", rb.mass.is_some()),
        ];
        let applies: &[&str] = match kind {
            "box" => &["size", "origin", "mass"],
            "rod" => &["length", "along", "origin", "mass"],
            "hoop" | "ring" | "disk" | "sphere" | "shell" => &["radius", "mass"],
            "cylinder" => &["radius", "height", "mass"],
            "points" => &["points"],
            other => {
                return Err(self.err(content_start(&rb.kind), &format!("{field}.kind"), format!("unknown body kind `{other}`; expected box, rod, hoop, ring, disk, cylinder, sphere, shell or points")));
            }
        };
        if let Some((name, _)) = present.iter().find(|(n, p)| *p && !applies.contains(n)) {
            return Err(self.err(
                start,
                &format!("{field}.{name}"),
                format!("field `{name}` does not apply to a {kind}"),
            ));
        }
        let origin = |choices: [&str; 2]| -> Result<bool, SceneError> {
            match &rb.origin {
                None => Ok(false),
                Some(o) if o.get_ref() == choices[0] => Ok(false),
                Some(o) if o.get_ref() == "centre" || o.get_ref() == "center" => Ok(true),
                Some(o) => Err(self.err(
                    content_start(o),
                    &format!("{field}.origin"),
                    format!("expected `{}` or `centre`", choices[0]),
                )),
            }
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
            "hoop" | "ring" => Shape::Hoop {
                radius: req(&rb.radius, "radius")?,
            },
            "disk" => Shape::Disk {
                radius: req(&rb.radius, "radius")?,
            },
            "cylinder" => Shape::Cylinder {
                radius: req(&rb.radius, "radius")?,
                height: req(&rb.height, "height")?,
            },
            "sphere" => Shape::Sphere {
                radius: req(&rb.radius, "radius")?,
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
        let mass = match &shape {
            Shape::Points(pts) => Expr::add(pts.iter().map(|(m, _)| m.clone()).collect()),
            _ => req(&rb.mass, "mass")?,
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
            label: rb.label.clone().unwrap_or_else(|| shape.kind().to_string()),
            shape,
            mass,
            rotations,
            shift,
        })
    }

    /// Sizes and masses must be positive and finite at the scene's numeric values.
    pub(super) fn check_positive(
        &self,
        rb: &RawBody,
        field: &str,
        values: &BTreeMap<String, f64>,
    ) -> Result<(), SceneError> {
        let env = |s: &str| values.get(s).copied();
        let mut checks: Vec<(&Text, String)> = Vec::new();
        if let Some(m) = &rb.mass {
            checks.push((m, format!("{field}.mass")));
        }
        for (name, t) in [
            ("radius", &rb.radius),
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
        for (t, f) in checks {
            let e = parse_expr(t.get_ref()).expect("validated").expr;
            let v = e
                .eval(&env)
                .map_err(|m| self.err(content_start(t), &f, m.to_string()))?;
            if !(v.is_finite() && v > 0.0) {
                return Err(self.err(
                    content_start(t),
                    &f,
                    format!("must be positive and finite, but is {v} at the scene's values"),
                ));
            }
        }
        Ok(())
    }
}

pub(super) fn body_symbols(b: &Body) -> BTreeSet<String> {
    let mut exprs: Vec<&Expr> = vec![&b.mass];
    exprs.extend(b.shift.iter());
    exprs.extend(b.rotations.iter().map(|(_, a)| a));
    match &b.shape {
        Shape::Box { size, .. } => exprs.extend(size.iter()),
        Shape::Rod { length, .. } => exprs.push(length),
        Shape::Hoop { radius }
        | Shape::Disk { radius }
        | Shape::Sphere { radius }
        | Shape::Shell { radius } => exprs.push(radius),
        Shape::Cylinder { radius, height } => exprs.extend([radius, height]),
        Shape::Points(pts) => pts.iter().for_each(|(m, at)| {
            exprs.push(m);
            exprs.extend(at.iter());
        }),
    }
    exprs.iter().flat_map(|e| e.symbols()).collect()
}
