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

/// Where a body is and what it may name, for its fields' errors.
struct BodyAt<'a> {
    start: usize,
    field: &'a str,
    kind: &'a str,
    allowed: &'a BTreeSet<String>,
}

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
        let rb = b.get_ref();
        let at = BodyAt {
            start: b.span().start,
            field,
            kind: rb.kind.get_ref().as_str(),
            allowed,
        };
        self.fields_apply(rb, &at)?;
        let shape = self.shape(rb, &at)?;
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
            shape => (shape, signed(self.required(&rb.mass, "mass", &at)?)),
        };
        let mut rotations = Vec::new();
        for (j, r) in rb.rotate.iter().enumerate() {
            let f = format!("{field}.rotate[{j}]");
            rotations.push((
                self.axis(&r.get_ref().axis, &format!("{f}.axis"))?,
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

    /// Refuses a field that does not apply to the body's kind, and a kind that is not one.
    fn fields_apply(&self, rb: &RawBody, at: &BodyAt) -> Result<(), SceneError> {
        let (field, kind) = (at.field, at.kind);
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
                at.start,
                &format!("{field}.{name}"),
                format!("field `{name}` does not apply to a {kind}"),
            ));
        }
        Ok(())
    }

    /// The body's shape with its dimensions, by its kind (one that `fields_apply` let through).
    fn shape(&self, rb: &RawBody, at: &BodyAt) -> Result<Shape, SceneError> {
        let (field, allowed) = (at.field, at.allowed);
        let req = |t: &Option<Text>, name: &str| self.required(t, name, at);
        let origin = |choices: [&str; 2]| -> Result<bool, SceneError> {
            Ok(self.origin_choice(rb, &choices, at)? == 1)
        };
        let inner = || -> Result<Option<Expr>, SceneError> {
            rb.inner_radius
                .as_ref()
                .map(|t| self.expr(t, &format!("{field}.inner_radius"), allowed))
                .transpose()
        };
        let size = |what: &str| {
            rb.size.as_ref().ok_or_else(|| {
                self.err(
                    at.start,
                    &format!("{field}.size"),
                    format!("missing field `{what}` for a {}", at.kind),
                )
            })
        };
        Ok(match at.kind {
            "box" => Shape::Box {
                size: self.vec3(size("size")?, &format!("{field}.size"), allowed)?,
                centred: origin(["corner", "centre"])?,
            },
            "rod" => {
                let along = match &rb.along {
                    None => Axis::Z,
                    Some(a) => self.axis(a, &format!("{field}.along"))?,
                };
                Shape::Rod {
                    length: req(&rb.length, "length")?,
                    along,
                    centred: origin(["end", "centre"])?,
                }
            }
            "plate" => Shape::Plate {
                size: self.vec2(size("size = [a, b]")?, &format!("{field}.size"), allowed)?,
                centred: origin(["corner", "centre"])?,
            },
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
                    [self.origin_choice(rb, &["apex", "base", "centre"], at)?],
            },
            "hemisphere" => Shape::Hemisphere {
                radius: req(&rb.radius, "radius")?,
                centred: origin(["base", "centre"])?,
            },
            "shell" => Shape::Shell {
                radius: req(&rb.radius, "radius")?,
            },
            _ => self.point_set(rb, at)?,
        })
    }

    /// A point set's masses and places: at least one.
    fn point_set(&self, rb: &RawBody, at: &BodyAt) -> Result<Shape, SceneError> {
        if rb.points.is_empty() {
            return Err(self.err(
                at.start,
                &format!("{}.points", at.field),
                "a point set needs at least one [[body.points]]",
            ));
        }
        let mut pts = Vec::new();
        for (j, p) in rb.points.iter().enumerate() {
            let f = format!("{}.points[{j}]", at.field);
            pts.push((
                self.expr(&p.get_ref().mass, &format!("{f}.mass"), at.allowed)?,
                self.vec3(&p.get_ref().at, &format!("{f}.at"), at.allowed)?,
            ));
        }
        Ok(Shape::Points(pts))
    }

    /// A field the body's kind needs.
    fn required(&self, t: &Option<Text>, name: &str, at: &BodyAt) -> Result<Expr, SceneError> {
        match t {
            Some(t) => self.expr(t, &format!("{}.{name}", at.field), at.allowed),
            None => Err(self.err(
                at.start,
                &format!("{}.{name}", at.field),
                format!("missing field `{name}` for a {}", at.kind),
            )),
        }
    }

    /// Which of `choices` the body's `origin` is; the first is the default, and `center` is
    /// accepted for `centre`.
    fn origin_choice(
        &self,
        rb: &RawBody,
        choices: &[&str],
        at: &BodyAt,
    ) -> Result<usize, SceneError> {
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
                &format!("{}.origin", at.field),
                format!("expected {} or {last} for a {}", rest.join(", "), at.kind),
            )
        })
    }

    /// An axis named x, y or z.
    fn axis(&self, t: &Text, at: &str) -> Result<Axis, SceneError> {
        match t.get_ref().as_str() {
            "x" => Ok(Axis::X),
            "y" => Ok(Axis::Y),
            "z" => Ok(Axis::Z),
            _ => Err(self.err(content_start(t), at, "expected x, y or z")),
        }
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
