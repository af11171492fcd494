//! Euler's equations in the principal body frame (eqs 60–65), derived component by component
//! from dL/dt|space = dL/dt|body + ω × L = N with L = Iω; and the torque-free rates that the
//! symmetric top, the stability analysis and Poinsot's construction start from.

use super::algebra::{Value, Vec3, add_vec, cross, diag, mat_vec, sub_vec};
use super::{Derivation, DeriveError, Step, cited, factored, simplify_value, simplify_vec};
use crate::cas::Expr;
use crate::model::catalogue::quantity;

fn vector(names: [&str; 3]) -> Vec3 {
    names.map(Expr::sym)
}

/// The principal moments I1, I2, I3.
pub fn moments() -> [Expr; 3] {
    vector(["I1", "I2", "I3"])
}

/// The names of ω's body-frame components.
const OMEGA: [&str; 3] = ["w1", "w2", "w3"];

/// ω in the body frame.
pub fn omega() -> Vec3 {
    vector(OMEGA)
}

/// The torque-free rates ω̇ = −I⁻¹(ω × Iω) for principal moments `i`, before simplification.
pub fn torque_free_rates(i: &[Expr; 3], w: &Vec3) -> Vec3 {
    let gyroscopic = cross(w, &mat_vec(&diag(i.clone()), w));
    std::array::from_fn(|a| Expr::negate(Expr::over(gyroscopic[a].clone(), i[a].clone())))
}

/// The time derivative of `f(ω)` along the motion ω̇ = `rates`, by the chain rule over the
/// components of [`omega`].
pub fn rate_along(f: &Expr, rates: &Vec3) -> Result<Expr, DeriveError> {
    let mut terms = Vec::new();
    for (name, ri) in OMEGA.iter().zip(rates) {
        let partial = f.diff(name).map_err(DeriveError::from)?;
        terms.push(Expr::mul(vec![partial, ri.clone()]));
    }
    Ok(Expr::add(terms))
}

pub fn euler_equations(d: &mut Derivation) -> Result<(), DeriveError> {
    let inertia = diag(moments());
    let (w, wd, n) = (
        omega(),
        vector(["wd1", "wd2", "wd3"]),
        vector(["N1", "N2", "N3"]),
    );
    let lv = simplify_vec(&mat_vec(&inertia, &w))?;
    let l = Value::Vector(lv.clone());
    d.steps.push(Step::equation(
        "Angular momentum in the principal frame",
        "vec(L)",
        &l,
        cited(
            "principal-frame-momentum",
            "the tensor is diagonal in the principal frame, so $L_j = I_j \\omega_j$ (no sum)",
        ),
    ));
    let br = simplify_vec(&mat_vec(&inertia, &wd))?;
    let body_rate = Value::Vector(br.clone());
    d.steps.push(Step::equation(
        "Rate of $\\vec L$ relative to the body",
        "((d vec(L))/(dt))|_body",
        &body_rate,
        "the principal moments are constant in the body frame, so only $\\vec\\omega$ changes",
    ));
    let g = simplify_vec(&cross(&w, &lv))?;
    let gyroscopic = Value::Vector(g.clone());
    d.steps.push(Step::equation(
        "Turning of the body frame",
        "vec(omega) × vec(L)",
        &gyroscopic,
        "$(\\vec\\omega \\times \\vec L)_i = \\epsilon_{ijk}\\,\\omega_j L_k$",
    ));
    let lhs = simplify_value(&Value::Vector(add_vec(&br, &g)))?;
    d.steps.push(Step::equation(
        "Euler's equations",
        "((d vec(L))/(dt))|_body + vec(omega) × vec(L)",
        &lhs,
        cited(
            "euler-equations",
            "this sum is the rate of $\\vec L$ in space, which equals the torque $\\vec N$; \
         component by component these are Euler's equations",
        ),
    ));
    let body_rate_of_momentum = simplify_value(&Value::Vector(sub_vec(&n, &g)))?;
    d.steps.push(Step::equation(
        "The body-frame rate, solved from (60)",
        "((d vec(L))/(dt))|_body",
        &body_rate_of_momentum,
        "$\\vec N - \\vec\\omega \\times \\vec L$: the torque minus the turning of the frame, not $\\epsilon_{ijk}\\,\\omega_j L_k$ alone",
    ));
    d.steps.push(Step::equation(
        "Steady rotation without torque",
        "vec(omega) × vec(L)",
        &factored(&gyroscopic)?,
        "with $\\vec N = 0$ a constant $\\vec\\omega$ needs $\\vec\\omega \\times \\vec L = 0$; with \
         distinct moments each component vanishes only if a product $\\omega_j \\omega_k$ does, so \
         two components of $\\vec\\omega$ are zero: $\\vec\\omega$ lies along a principal axis",
    ));
    d.set(quantity::PRINCIPAL_MOMENTUM, l.clone())?;
    d.set(quantity::GYROSCOPIC_TERM, gyroscopic.clone())?;
    d.set(quantity::EULER_EQUATIONS, lhs)?;
    d.set(quantity::BODY_RATE_OF_MOMENTUM, body_rate_of_momentum)?;
    let rates = simplify_value(&Value::Vector(torque_free_rates(&moments(), &w)))?;
    d.steps.push(Step::equation(
        "Torque-free rates",
        "dot(vec(omega))",
        &factored(&rates)?,
        cited(
            "torque-free-rates",
            "Euler's equations with $\\vec N = 0$, each divided by its moment",
        ),
    ));
    d.set(quantity::TORQUE_FREE_RATES, rates)?;
    Ok(())
}
