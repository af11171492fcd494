//! Each body as a mass distribution: where a mass element sits, how much mass it carries, and
//! the domain of its parameters. Uniform density: density = M / (length, area or volume).

use super::algebra::{Vec3, add_vec, mat_vec, rotation};
use crate::cas::{AngleSpan, Expr, Integral};
use crate::scene::{Axis, Body, ConeOrigin, Shape};

/// A continuous body: dm = `density_jacobian` · d(params) at `local` (body coordinates).
pub struct Continuum {
    /// ρ times the Jacobian of the parametrisation, as a function of the parameters.
    pub density_jacobian: Expr,
    /// The density alone and the Jacobian alone, for the printed steps.
    pub density: Expr,
    pub jacobian: Expr,
    /// Symbol the notes use for the density: ρ, σ or λ.
    pub density_name: &'static str,
    pub local: Vec3,
    /// Innermost first: the trigonometric integrals, then the polynomial ones.
    pub domain: Vec<Integral>,
}

// Built once per body and consumed at once: the size difference does not matter.
#[allow(clippy::large_enum_variant)]
pub enum MassModel {
    Continuum(Continuum),
    Points(Vec<(Expr, Vec3)>),
}

fn e(s: &str) -> Expr {
    Expr::sym(s)
}

fn half(x: &Expr) -> Expr {
    Expr::mul(vec![Expr::rat(1, 2), x.clone()])
}

fn pow(x: &Expr, n: i128) -> Expr {
    Expr::pow(x.clone(), Expr::int(n))
}

fn poly(var: &str, lo: Expr, hi: Expr) -> Integral {
    Integral::Poly {
        var: var.into(),
        lo,
        hi,
    }
}

fn period(var: &str, span: AngleSpan) -> Integral {
    Integral::Trig {
        var: var.into(),
        span,
    }
}

/// A side of length `len` along `var`: [0, len], or centred on 0.
fn side(var: &str, len: &Expr, centred: bool) -> Integral {
    if centred {
        poly(var, Expr::negate(half(len)), half(len))
    } else {
        poly(var, Expr::int(0), len.clone())
    }
}

/// R² − r², or R³ − r³: what a hole of radius r leaves of the full disk or ball.
fn radial_span(radius: &Expr, inner: &Option<Expr>, power: i128) -> Expr {
    match inner {
        None => pow(radius, power),
        Some(r) => Expr::minus(pow(radius, power), pow(r, power)),
    }
}

fn inner_or_zero(inner: &Option<Expr>) -> Expr {
    inner.clone().unwrap_or_else(|| Expr::int(0))
}

fn cos(v: &str) -> Expr {
    Expr::call("cos", e(v))
}

fn sin(v: &str) -> Expr {
    Expr::call("sin", e(v))
}

/// The mass model of one body in its own coordinates, over the integration variables the
/// scene gave it (`r_1` where the scene has an `r` of its own).
pub fn mass_model(body: &Body) -> MassModel {
    match &body.shape {
        Shape::Box { size, centred } => cuboid(body, size, *centred),
        Shape::Plate { size, centred } => plate(body, size, *centred),
        Shape::Rod {
            length,
            along,
            centred,
        } => rod(body, length, *along, *centred),
        Shape::Hoop { radius } => hoop(body, radius),
        Shape::Disk { radius, inner } => disk(body, radius, inner),
        Shape::Cylinder {
            radius,
            height,
            inner,
        } => cylinder(body, radius, height, inner),
        Shape::Sphere { radius, inner } => sphere(body, radius, inner),
        Shape::Hemisphere { radius, centred } => hemisphere(body, radius, *centred),
        Shape::Cone {
            radius,
            height,
            origin,
        } => cone(body, radius, height, *origin),
        Shape::Shell { radius } => shell(body, radius),
        Shape::Points(pts) => MassModel::Points(pts.clone()),
    }
}

/// A continuum of density `density` (named `name` on the page) over `domain`, its volume
/// element `jacobian`, at the body's own point `local`.
fn continuum(
    density: Expr,
    jacobian: Expr,
    name: &'static str,
    local: Vec3,
    domain: Vec<Integral>,
) -> MassModel {
    MassModel::Continuum(Continuum {
        density_jacobian: Expr::mul(vec![density.clone(), jacobian.clone()]),
        density,
        jacobian,
        density_name: name,
        local,
        domain,
    })
}

/// A box: ρ = M/(abc) over its three sides.
fn cuboid(body: &Body, size: &[Expr; 3], centred: bool) -> MassModel {
    let v = |shape_name| variable(body, shape_name);
    let m = &body.mass;
    continuum(
        Expr::over(m.clone(), Expr::mul(size.to_vec())),
        Expr::int(1),
        "rho",
        [e(v("x")), e(v("y")), e(v("z"))],
        vec![
            side(v("x"), &size[0], centred),
            side(v("y"), &size[1], centred),
            side(v("z"), &size[2], centred),
        ],
    )
}

/// A plate: σ = M/(ab) over its two sides, in the xy-plane.
fn plate(body: &Body, size: &[Expr; 2], centred: bool) -> MassModel {
    let v = |shape_name| variable(body, shape_name);
    let m = &body.mass;
    continuum(
        Expr::over(m.clone(), Expr::mul(size.to_vec())),
        Expr::int(1),
        "sigma",
        [e(v("x")), e(v("y")), Expr::int(0)],
        vec![
            side(v("x"), &size[0], centred),
            side(v("y"), &size[1], centred),
        ],
    )
}

/// A thin rod: λ = M/l along its axis.
fn rod(body: &Body, length: &Expr, along: Axis, centred: bool) -> MassModel {
    let v = |shape_name| variable(body, shape_name);
    let m = &body.mass;
    let mut local = [Expr::int(0), Expr::int(0), Expr::int(0)];
    local[along.index()] = e(v("s"));
    let (lo, hi) = if centred {
        (Expr::negate(half(length)), half(length))
    } else {
        (Expr::int(0), length.clone())
    };
    continuum(
        Expr::over(m.clone(), length.clone()),
        Expr::int(1),
        "lambda",
        local,
        vec![poly(v("s"), lo, hi)],
    )
}

/// A hoop of radius R: λ = M/(2πR) over the angle.
fn hoop(body: &Body, radius: &Expr) -> MassModel {
    let v = |shape_name| variable(body, shape_name);
    let m = &body.mass;
    continuum(
        // λ = M/(2πR), the line density of eq (32); the arc element is R dθ.
        Expr::over(
            m.clone(),
            Expr::mul(vec![Expr::int(2), e("pi"), radius.clone()]),
        ),
        radius.clone(),
        "lambda",
        [
            Expr::mul(vec![radius.clone(), cos(v("theta"))]),
            Expr::mul(vec![radius.clone(), sin(v("theta"))]),
            Expr::int(0),
        ],
        vec![period(v("theta"), AngleSpan::Full)],
    )
}

/// A disk, or an annulus: σ over r and θ.
fn disk(body: &Body, radius: &Expr, inner: &Option<Expr>) -> MassModel {
    let v = |shape_name| variable(body, shape_name);
    let m = &body.mass;
    continuum(
        Expr::over(
            m.clone(),
            Expr::mul(vec![e("pi"), radial_span(radius, inner, 2)]),
        ),
        e(v("r")),
        "sigma",
        [
            Expr::mul(vec![e(v("r")), cos(v("theta"))]),
            Expr::mul(vec![e(v("r")), sin(v("theta"))]),
            Expr::int(0),
        ],
        vec![
            period(v("theta"), AngleSpan::Full),
            poly(v("r"), inner_or_zero(inner), radius.clone()),
        ],
    )
}

/// A cylinder, or a tube: ρ over r, θ and z.
fn cylinder(body: &Body, radius: &Expr, height: &Expr, inner: &Option<Expr>) -> MassModel {
    let v = |shape_name| variable(body, shape_name);
    let m = &body.mass;
    continuum(
        Expr::over(
            m.clone(),
            Expr::mul(vec![e("pi"), radial_span(radius, inner, 2), height.clone()]),
        ),
        e(v("r")),
        "rho",
        [
            Expr::mul(vec![e(v("r")), cos(v("theta"))]),
            Expr::mul(vec![e(v("r")), sin(v("theta"))]),
            e(v("z")),
        ],
        vec![
            period(v("theta"), AngleSpan::Full),
            poly(v("r"), inner_or_zero(inner), radius.clone()),
            poly(v("z"), Expr::negate(half(height)), half(height)),
        ],
    )
}

/// A ball, or a thick shell: ρ over r, θ and φ.
fn sphere(body: &Body, radius: &Expr, inner: &Option<Expr>) -> MassModel {
    let v = |shape_name| variable(body, shape_name);
    let m = &body.mass;
    continuum(
        Expr::over(
            Expr::mul(vec![Expr::int(3), m.clone()]),
            Expr::mul(vec![Expr::int(4), e("pi"), radial_span(radius, inner, 3)]),
        ),
        Expr::mul(vec![pow(&e(v("r")), 2), sin(v("theta"))]),
        "rho",
        spherical(&e(v("r")), v("theta"), v("phi")),
        vec![
            period(v("phi"), AngleSpan::Full),
            period(v("theta"), AngleSpan::Half),
            poly(v("r"), inner_or_zero(inner), radius.clone()),
        ],
    )
}

/// A solid hemisphere, its dome towards +z.
fn hemisphere(body: &Body, radius: &Expr, centred: bool) -> MassModel {
    let v = |shape_name| variable(body, shape_name);
    let m = &body.mass;
    // θ over [0, π/2]: the dome towards +z. The centre of mass is 3R/8 above the face.
    let mut local = spherical(&e(v("r")), v("theta"), v("phi"));
    if centred {
        local[2] = Expr::minus(
            local[2].clone(),
            Expr::mul(vec![Expr::rat(3, 8), radius.clone()]),
        );
    }
    continuum(
        Expr::over(
            Expr::mul(vec![Expr::int(3), m.clone()]),
            Expr::mul(vec![Expr::int(2), e("pi"), pow(radius, 3)]),
        ),
        Expr::mul(vec![pow(&e(v("r")), 2), sin(v("theta"))]),
        "rho",
        local,
        vec![
            period(v("phi"), AngleSpan::Full),
            period(v("theta"), AngleSpan::Quarter),
            poly(v("r"), Expr::int(0), radius.clone()),
        ],
    )
}

/// A solid cone about z.
fn cone(body: &Body, radius: &Expr, height: &Expr, origin: ConeOrigin) -> MassModel {
    let v = |shape_name| variable(body, shape_name);
    let m = &body.mass;
    // z runs from the apex; the cross-section there has radius Rz/h, and s ∈ [0, 1] is
    // the fraction of it, so every limit is constant: dV = s (Rz/h)² ds dθ dz.
    let section = Expr::over(Expr::mul(vec![radius.clone(), e(v("z"))]), height.clone());
    let along = match origin {
        ConeOrigin::Apex => e(v("z")),
        ConeOrigin::Base => Expr::minus(height.clone(), e(v("z"))),
        ConeOrigin::Centre => {
            Expr::minus(Expr::mul(vec![Expr::rat(3, 4), height.clone()]), e(v("z")))
        }
    };
    continuum(
        Expr::over(
            Expr::mul(vec![Expr::int(3), m.clone()]),
            Expr::mul(vec![e("pi"), pow(radius, 2), height.clone()]),
        ),
        Expr::mul(vec![e(v("s")), pow(&section, 2)]),
        "rho",
        [
            Expr::mul(vec![e(v("s")), section.clone(), cos(v("theta"))]),
            Expr::mul(vec![e(v("s")), section, sin(v("theta"))]),
            along,
        ],
        vec![
            period(v("theta"), AngleSpan::Full),
            poly(v("s"), Expr::int(0), Expr::int(1)),
            poly(v("z"), Expr::int(0), height.clone()),
        ],
    )
}

/// A thin spherical shell: σ over θ and φ.
fn shell(body: &Body, radius: &Expr) -> MassModel {
    let v = |shape_name| variable(body, shape_name);
    let m = &body.mass;
    continuum(
        Expr::over(
            m.clone(),
            Expr::mul(vec![Expr::int(4), e("pi"), pow(radius, 2)]),
        ),
        Expr::mul(vec![pow(radius, 2), sin(v("theta"))]),
        "sigma",
        spherical(radius, v("theta"), v("phi")),
        vec![
            period(v("phi"), AngleSpan::Full),
            period(v("theta"), AngleSpan::Half),
        ],
    )
}

/// The body's name for one of its shape's variables.
fn variable<'a>(body: &'a Body, shape_name: &'static str) -> &'a str {
    body.shape
        .variables()
        .iter()
        .position(|x| *x == shape_name)
        .and_then(|i| body.variables.get(i))
        .map_or(shape_name as &str, |own| own.as_str())
}

/// (r sinθ cosφ, r sinθ sinφ, r cosθ).
fn spherical(r: &Expr, theta: &str, phi: &str) -> Vec3 {
    [
        Expr::mul(vec![r.clone(), sin(theta), cos(phi)]),
        Expr::mul(vec![r.clone(), sin(theta), sin(phi)]),
        Expr::mul(vec![r.clone(), cos(theta)]),
    ]
}

/// Body coordinates -> frame coordinates: the rotations in order, then the shift.
pub fn place(body: &Body, local: &Vec3) -> Vec3 {
    let mut p = local.clone();
    for (axis, angle) in &body.rotations {
        p = mat_vec(&rotation(axis.index(), angle), &p);
    }
    add_vec(&p, &body.shift)
}
