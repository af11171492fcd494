//! Angular momentum, kinetic energy, the moment about an axis and the radius of gyration, from
//! the tensor; and for point masses also from their definitions, proved equal (eqs 3–8, 16–20,
//! 23–25, 53–59).

use super::algebra::{Value, Vec3, cross, dot, mat_vec, scale_vec, sum_vecs};
use super::bodies::place;
use super::{Derivation, DeriveError, Step, cited, simplify_value, values_equal};
use crate::cas::{self, Expr};
use crate::model::catalogue::quantity;
use crate::model::prose::Prose;
use crate::notation::Formula;
use crate::scene::{Scene, Shape};

/// Every point mass of the scene in the frame, or `None` if a body is continuous.
fn point_masses(scene: &Scene) -> Option<Vec<(Expr, Vec3)>> {
    let mut all = Vec::new();
    for b in &scene.bodies {
        let Shape::Points(pts) = &b.shape else {
            return None;
        };
        all.extend(pts.iter().map(|(m, r)| (m.clone(), place(b, r))));
    }
    Some(all)
}

fn tensor(d: &Derivation) -> Result<super::algebra::Mat3, DeriveError> {
    Ok(d.matrix(quantity::INERTIA_TENSOR)?.clone())
}

/// Records `name` from the tensor route and, for point masses, `name_direct` from the
/// definition, after proving them equal.
fn two_routes(
    d: &mut Derivation,
    name: &str,
    from_tensor: Value,
    direct: Option<(Value, &str, super::Why)>,
) -> Result<(), DeriveError> {
    if let Some((direct, what, why)) = direct {
        let direct = simplify_value(&direct)?;
        d.steps.push(
            Step::titled(
                Prose::default().math(what).text(", from the definition"),
                Formula::equation(Formula::parse(what, &[]), direct.to_expr()),
                why,
            )
            .second_route(),
        );
        if !values_equal(&direct, &from_tensor)? {
            return Err(DeriveError::Inconsistent(format!(
                "{name}: the definition and the tensor route differ"
            )));
        }
        d.quantities.insert(format!("{name}_direct"), direct);
    }
    d.quantities.insert(name.to_string(), from_tensor);
    Ok(())
}

pub fn angular_momentum(scene: &Scene, d: &mut Derivation) -> Result<(), DeriveError> {
    let omega = scene.omega.clone().expect("validated: omega is given");
    let l = simplify_value(&Value::Vector(mat_vec(&tensor(d)?, &omega)))?;
    d.steps.push(Step::equation(
        "Angular momentum from the tensor",
        "vec(L)",
        &l,
        cited(
            "angular-momentum",
            Prose::default().math("vec(L) = ten(I) ~ vec(omega)"),
        ),
    ));
    let direct = point_masses(scene).map(|pts| {
        let sum = sum_vecs(
            pts.iter()
                .map(|(m, r)| scale_vec(m, &cross(r, &cross(&omega, r)))),
        );
        (
            Value::Vector(sum),
            "vec(L)",
            cited(
                "angular-momentum-direct",
                Prose::default()
                    .math("vec(L) = sum m ~ vec(r) × (vec(omega) × vec(r))")
                    .text(", expanded; equal to ")
                    .math("ten(I) ~ vec(omega)")
                    .text(" entry by entry"),
            ),
        )
    });
    two_routes(d, quantity::ANGULAR_MOMENTUM, l, direct)
}

pub fn kinetic_energy(scene: &Scene, d: &mut Derivation) -> Result<(), DeriveError> {
    let omega = scene.omega.clone().expect("validated: omega is given");
    let half = Expr::rat(1, 2);
    let t = cas::simplify(&Expr::mul(vec![
        half.clone(),
        dot(&omega, &mat_vec(&tensor(d)?, &omega)),
    ]))?;
    d.steps.push(Step::equation(
        "Kinetic energy from the tensor",
        "T",
        &Value::Scalar(t.clone()),
        cited(
            "kinetic-energy",
            Prose::default().math("T = 1/2 vec(omega)^T ten(I) ~ vec(omega)"),
        ),
    ));
    let direct = point_masses(scene).map(|pts| {
        let sum = Expr::add(
            pts.iter()
                .map(|(m, r)| {
                    let v = cross(&omega, r);
                    Expr::mul(vec![half.clone(), m.clone(), dot(&v, &v)])
                })
                .collect(),
        );
        (
            Value::Scalar(sum),
            "T",
            cited(
                "kinetic-energy-direct",
                Prose::default()
                    .math("T = 1/2 sum m ~ |vec(omega) × vec(r)|^2")
                    .text("; equal to ")
                    .math("1/2 vec(omega)^T ten(I) ~ vec(omega)"),
            ),
        )
    });
    two_routes(d, quantity::KINETIC_ENERGY, Value::Scalar(t), direct)
}

pub fn moment_about_axis(scene: &Scene, d: &mut Derivation) -> Result<(), DeriveError> {
    let n = scene.axis.clone().expect("validated: axis is given");
    let moment = cas::simplify(&dot(&n, &mat_vec(&tensor(d)?, &n)))?;
    d.steps.push(Step::equation(
        "Moment of inertia about the axis $\\hat n$",
        "I_n",
        &Value::Scalar(moment.clone()),
        cited(
            "moment-about-axis",
            Prose::default().math("I_n = vec(n)^T ten(I) ~ vec(n)"),
        ),
    ));
    let direct = point_masses(scene).map(|pts| {
        let sum = Expr::add(
            pts.iter()
                .map(|(m, r)| {
                    let c = cross(r, &n);
                    Expr::mul(vec![m.clone(), dot(&c, &c)])
                })
                .collect(),
        );
        (
            Value::Scalar(sum),
            "I_n",
            cited(
                "moment-about-axis-direct",
                Prose::default()
                    .math("I_n = sum m ~ |vec(r) × vec(n)|^2")
                    .text(", the squared distance from the axis; equal to ")
                    .math("vec(n)^T ten(I) ~ vec(n)"),
            ),
        )
    });
    two_routes(
        d,
        quantity::MOMENT_ABOUT_AXIS,
        Value::Scalar(moment),
        direct,
    )
}

pub fn gyration(d: &mut Derivation) -> Result<(), DeriveError> {
    let moment = d.scalar(quantity::MOMENT_ABOUT_AXIS)?.clone();
    let mass = d.scalar(quantity::MASS)?.clone();
    let r0 = Expr::pow(cas::simplify(&Expr::over(moment, mass))?, Expr::rat(1, 2));
    d.steps.push(Step::equation(
        "Radius of gyration about $\\hat n$",
        "R_0",
        &Value::Scalar(r0.clone()),
        cited("gyration", Prose::default().math("R_0^2 = I_n/M")),
    ));
    d.quantities
        .insert(quantity::RADIUS_OF_GYRATION.into(), Value::Scalar(r0));
    if let Some(Value::Vector(moments)) = d.quantities.get(quantity::PRINCIPAL_MOMENTS).cloned() {
        let semi: Vec<Expr> = moments
            .iter()
            .map(|i| Expr::pow(i.clone(), Expr::rat(-1, 2)))
            .collect();
        d.steps.push(Step::note(
            "Inertia ellipsoid",
            Formula::parse(
                "I_1 rho_1^2 + I_2 rho_2^2 + I_3 rho_3^2 = 1, quad \"semi-axes \" $0, $1, $2",
                &semi,
            ),
            cited(
                "inertia-ellipsoid",
                Prose::default()
                    .text("with ")
                    .math("vec(rho) = vec(n)/sqrt(I_n)")
                    .text(", the ellipsoid's semi-axis along principal axis i is ")
                    .math("1/sqrt(I_i)"),
            ),
        ));
    }
    Ok(())
}
