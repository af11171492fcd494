//! Each body as a mass distribution: where a mass element sits, how much mass it carries, and
//! the domain of its parameters. Uniform density: density = M / (length, area or volume).

use super::algebra::{Vec3, add_vec, mat_vec, rotation};
use crate::cas::{AngleSpan, Expr, Integral};
use crate::scene::{Body, ConeOrigin, Shape};

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
    let v = |shape_name| variable(body, shape_name);
    let m = &body.mass;
    let pi = e("pi");
    let zero = Expr::int(0);
    let continuum = |density: Expr, jacobian: Expr, name, local: Vec3, domain| {
        MassModel::Continuum(Continuum {
            density_jacobian: Expr::mul(vec![density.clone(), jacobian.clone()]),
            density,
            jacobian,
            density_name: name,
            local,
            domain,
        })
    };
    let full = AngleSpan::Full;
    match &body.shape {
        Shape::Box { size, centred } => continuum(
            Expr::over(m.clone(), Expr::mul(size.to_vec())),
            Expr::int(1),
            "rho",
            [e(v("x")), e(v("y")), e(v("z"))],
            vec![
                side(v("x"), &size[0], *centred),
                side(v("y"), &size[1], *centred),
                side(v("z"), &size[2], *centred),
            ],
        ),
        Shape::Plate { size, centred } => continuum(
            Expr::over(m.clone(), Expr::mul(size.to_vec())),
            Expr::int(1),
            "sigma",
            [e(v("x")), e(v("y")), zero],
            vec![
                side(v("x"), &size[0], *centred),
                side(v("y"), &size[1], *centred),
            ],
        ),
        Shape::Rod {
            length,
            along,
            centred,
        } => {
            let mut local = [zero.clone(), zero.clone(), zero.clone()];
            local[along.index()] = e(v("s"));
            let (lo, hi) = if *centred {
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
        Shape::Hoop { radius } => continuum(
            // λ = M/(2πR), the line density of eq (32); the arc element is R dθ.
            Expr::over(m.clone(), Expr::mul(vec![Expr::int(2), pi, radius.clone()])),
            radius.clone(),
            "lambda",
            [
                Expr::mul(vec![radius.clone(), cos(v("theta"))]),
                Expr::mul(vec![radius.clone(), sin(v("theta"))]),
                zero,
            ],
            vec![period(v("theta"), full)],
        ),
        Shape::Disk { radius, inner } => continuum(
            Expr::over(
                m.clone(),
                Expr::mul(vec![pi, radial_span(radius, inner, 2)]),
            ),
            e(v("r")),
            "sigma",
            [
                Expr::mul(vec![e(v("r")), cos(v("theta"))]),
                Expr::mul(vec![e(v("r")), sin(v("theta"))]),
                zero,
            ],
            vec![
                period(v("theta"), full),
                poly(v("r"), inner_or_zero(inner), radius.clone()),
            ],
        ),
        Shape::Cylinder {
            radius,
            height,
            inner,
        } => continuum(
            Expr::over(
                m.clone(),
                Expr::mul(vec![pi, radial_span(radius, inner, 2), height.clone()]),
            ),
            e(v("r")),
            "rho",
            [
                Expr::mul(vec![e(v("r")), cos(v("theta"))]),
                Expr::mul(vec![e(v("r")), sin(v("theta"))]),
                e(v("z")),
            ],
            vec![
                period(v("theta"), full),
                poly(v("r"), inner_or_zero(inner), radius.clone()),
                poly(v("z"), Expr::negate(half(height)), half(height)),
            ],
        ),
        Shape::Sphere { radius, inner } => continuum(
            Expr::over(
                Expr::mul(vec![Expr::int(3), m.clone()]),
                Expr::mul(vec![Expr::int(4), pi, radial_span(radius, inner, 3)]),
            ),
            Expr::mul(vec![pow(&e(v("r")), 2), sin(v("theta"))]),
            "rho",
            spherical(&e(v("r")), v("theta"), v("phi")),
            vec![
                period(v("phi"), full),
                period(v("theta"), AngleSpan::Half),
                poly(v("r"), inner_or_zero(inner), radius.clone()),
            ],
        ),
        Shape::Hemisphere { radius, centred } => {
            // θ over [0, π/2]: the dome towards +z. The centre of mass is 3R/8 above the face.
            let mut local = spherical(&e(v("r")), v("theta"), v("phi"));
            if *centred {
                local[2] = Expr::minus(
                    local[2].clone(),
                    Expr::mul(vec![Expr::rat(3, 8), radius.clone()]),
                );
            }
            continuum(
                Expr::over(
                    Expr::mul(vec![Expr::int(3), m.clone()]),
                    Expr::mul(vec![Expr::int(2), pi, pow(radius, 3)]),
                ),
                Expr::mul(vec![pow(&e(v("r")), 2), sin(v("theta"))]),
                "rho",
                local,
                vec![
                    period(v("phi"), full),
                    period(v("theta"), AngleSpan::Quarter),
                    poly(v("r"), Expr::int(0), radius.clone()),
                ],
            )
        }
        Shape::Cone {
            radius,
            height,
            origin,
        } => {
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
                    Expr::mul(vec![pi, pow(radius, 2), height.clone()]),
                ),
                Expr::mul(vec![e(v("s")), pow(&section, 2)]),
                "rho",
                [
                    Expr::mul(vec![e(v("s")), section.clone(), cos(v("theta"))]),
                    Expr::mul(vec![e(v("s")), section, sin(v("theta"))]),
                    along,
                ],
                vec![
                    period(v("theta"), full),
                    poly(v("s"), Expr::int(0), Expr::int(1)),
                    poly(v("z"), Expr::int(0), height.clone()),
                ],
            )
        }
        Shape::Shell { radius } => continuum(
            Expr::over(m.clone(), Expr::mul(vec![Expr::int(4), pi, pow(radius, 2)])),
            Expr::mul(vec![pow(radius, 2), sin(v("theta"))]),
            "sigma",
            spherical(radius, v("theta"), v("phi")),
            vec![period(v("phi"), full), period(v("theta"), AngleSpan::Half)],
        ),
        Shape::Points(pts) => MassModel::Points(pts.clone()),
    }
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
