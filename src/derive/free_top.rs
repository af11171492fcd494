//! The torque-free symmetric top, I1 = I2 (eqs 66–71): the rates, the second-order equation,
//! its closed-form solution checked by substitution, the precession rate βω3, and the body and
//! space cones, with the inequality between their half-angles worked out from the formulas.

use super::algebra::{Mat3, Value, Vec3, cross, diag, dot, mat_vec};
use super::euler::{omega, rate_along, torque_free_rates};
use super::sign::{Sign, sign_over_positive};
use super::{
    Derivation, DeriveError, Step, cited, factored, simplify_value, simplify_vec, values_equal,
};
use crate::cas::{self, Expr};
use crate::model::catalogue::quantity;
use crate::model::prose::Prose;
use crate::notation::Formula;

fn s(name: &str) -> Expr {
    Expr::sym(name)
}

fn scalar(e: Expr) -> Result<Expr, DeriveError> {
    Ok(cas::simplify(&e)?)
}

/// tan² of a vector's angle from the symmetry axis 3: (v1² + v2²)/v3².
fn tan_squared_from_axis(v: &Vec3) -> Expr {
    let sq = |e: &Expr| Expr::pow(e.clone(), Expr::int(2));
    Expr::over(Expr::add(vec![sq(&v[0]), sq(&v[1])]), sq(&v[2]))
}

fn sign_words(sign: Sign) -> &'static str {
    match sign {
        Sign::Positive => "positive for every choice",
        Sign::Negative => "negative for every choice",
        Sign::NotFixed => "positive for some choices and negative for others",
    }
}

pub fn symmetric_top(d: &mut Derivation) -> Result<(), DeriveError> {
    let i = [s("I1"), s("I1"), s("I3")];
    let inertia = diag(i.clone());
    let beta = symmetric_rates(d, &i)?;
    let (solution, derivative, l) = closed_form(d, &inertia, &beta)?;
    let omega_squared = magnitude_and_precession(d, &solution, &derivative)?;
    let (two_t, l_squared) = cones(d, &solution, &l, &omega_squared)?;
    wider_cone(d, two_t, l_squared)
}

/// Euler's equations with I2 = I1 and no torque, with β (eqs 66–68), and ω1's second
/// derivative: an oscillator (eq 69). Returns β.
fn symmetric_rates(d: &mut Derivation, i: &Vec3) -> Result<Expr, DeriveError> {
    let w = omega();
    let r = simplify_vec(&torque_free_rates(i, &w))?;
    let rates = Value::Vector(r.clone());
    d.steps.push(Step::equation(
        "Euler's equations with $I_2 = I_1$ and $\\vec N = 0$",
        "dot(vec(omega))",
        &factored(&rates)?,
        cited(
            "symmetric-rates",
            "Euler's equations solved for the rates; the third vanishes, so $\\omega_3$ is constant",
        ),
    ));
    // β = (I3 − I1)/I1 turns the rates into −βω3ω2 and βω3ω1, eqs (67)–(68).
    let beta = Expr::over(Expr::minus(s("I3"), s("I1")), s("I1"));
    let with_beta = Value::Vector([
        Expr::negate(Expr::mul(vec![beta.clone(), s("w3"), s("w2")])),
        Expr::mul(vec![beta.clone(), s("w3"), s("w1")]),
        Expr::int(0),
    ]);
    if !values_equal(&rates, &with_beta)? {
        return Err(DeriveError::Inconsistent(
            "the symmetric-top rates are not ±βω3 times ω2, ω1".into(),
        ));
    }
    d.steps.push(Step::note(
        "With $\\beta = (I_3 - I_1)/I_1$",
        Formula::parse(
            "dot(omega_1) = -beta ~ omega_3 ~ omega_2, quad dot(omega_2) = beta ~ omega_3 ~ omega_1",
            &[],
        ),
        cited(
            "symmetric-beta-rates",
            "equal to the rates above term by term",
        ),
    ));
    let second = scalar(rate_along(&r[0], &r)?)?;
    d.steps.push(Step::equation(
        "Second derivative of $\\omega_1$",
        "ddot(omega_1)",
        &factored(&Value::Scalar(second.clone()))?,
        cited(
            "symmetric-oscillator",
            Prose::default()
                .words("differentiate $\\dot\\omega_1$ along the motion and use $\\dot\\omega_2$; this is ")
                .math("-beta^2 omega_3^2 ~ omega_1")
                .words(", a harmonic oscillator of angular frequency $\\beta\\omega_3$"),
        ),
    ));
    d.set(quantity::W1_SECOND_DERIVATIVE, Value::Scalar(second))?;
    Ok(beta)
}

/// The closed form the notes give after eq 69, substituted into Euler's equations; returns ω
/// its rate and L = Iω.
fn closed_form(
    d: &mut Derivation,
    inertia: &Mat3,
    beta: &Expr,
) -> Result<(Vec3, Vec3, Vec3), DeriveError> {
    // The closed form, substituted back into all three of Euler's equations.
    let phase = Expr::add(vec![
        Expr::mul(vec![beta.clone(), s("w3"), s("t")]),
        s("theta"),
    ]);
    let solution: Vec3 = [
        Expr::mul(vec![s("A"), Expr::call("cos", phase.clone())]),
        Expr::mul(vec![s("A"), Expr::call("sin", phase)]),
        s("w3"),
    ];
    let derivative: Vec3 = solution
        .clone()
        .map(|e| e.diff("t").expect("sin, cos and powers differentiate"));
    let l = mat_vec(inertia, &solution);
    let residual: Vec<Expr> = mat_vec(inertia, &derivative)
        .iter()
        .zip(cross(&solution, &l))
        .map(|(a, b)| Expr::add(vec![a.clone(), b]))
        .collect();
    if !cas::is_zero_all(residual.clone())?.into_iter().all(|z| z) {
        return Err(DeriveError::Inconsistent(
            "the symmetric-top solution leaves a residual".into(),
        ));
    }
    let residual = simplify_value(&Value::Vector([
        residual[0].clone(),
        residual[1].clone(),
        residual[2].clone(),
    ]))?;
    d.steps.push(Step::equation(
        "The solution, substituted",
        "I dot(vec(omega)) + vec(omega) × I vec(omega)",
        &residual,
        "$\\omega_1 = A\\cos(\\beta\\omega_3 t + \\theta)$, $\\omega_2 = A\\sin(\\beta\\omega_3 t + \\theta)$, \
         $\\omega_3$ constant: the residual of Euler's equations reduces to zero",
    ));
    d.set(
        quantity::SYMMETRIC_SOLUTION,
        Value::Vector(solution.clone()),
    )?;
    d.set(quantity::SYMMETRIC_RESIDUAL, residual)?;
    Ok((solution, derivative, l))
}

/// |ω|² constant (eq 70), and ω's precession about the axis at βω3; returns ω².
fn magnitude_and_precession(
    d: &mut Derivation,
    solution: &Vec3,
    derivative: &Vec3,
) -> Result<Expr, DeriveError> {
    let omega_squared = scalar(dot(solution, solution))?;
    d.steps.push(Step::equation(
        "Magnitude of $\\vec\\omega$",
        "omega^2",
        &Value::Scalar(omega_squared.clone()),
        cited(
            "symmetric-omega-constant",
            Prose::default()
                .math("sin^2 + cos^2 = 1")
                .words(", so $\\omega$ is constant"),
        ),
    ));
    d.set(
        quantity::OMEGA_SQUARED,
        Value::Scalar(omega_squared.clone()),
    )?;

    // The angle of (ω1, ω2) advances at (ω1 ω̇2 − ω2 ω̇1)/(ω1² + ω2²).
    let turning = Expr::over(
        Expr::minus(
            Expr::mul(vec![solution[0].clone(), derivative[1].clone()]),
            Expr::mul(vec![solution[1].clone(), derivative[0].clone()]),
        ),
        Expr::add(vec![
            Expr::pow(solution[0].clone(), Expr::int(2)),
            Expr::pow(solution[1].clone(), Expr::int(2)),
        ]),
    );
    let precession = scalar(turning)?;
    d.steps.push(Step::equation(
        "Precession of $\\vec\\omega$ about the symmetry axis",
        "(omega_1 dot(omega_2) - omega_2 dot(omega_1))/(omega_1^2 + omega_2^2)",
        &Value::Scalar(precession.clone()),
        "the angle of $(\\omega_1, \\omega_2)$ in the body advances at $\\beta\\omega_3$: the body cone",
    ));
    d.set(quantity::PRECESSION_RATE, Value::Scalar(precession))?;
    Ok(omega_squared)
}

/// 2T and L² along the solution, and the body and space cones (eq 71); returns 2T and L².
fn cones(
    d: &mut Derivation,
    solution: &Vec3,
    l: &Vec3,
    omega_squared: &Expr,
) -> Result<(Expr, Expr), DeriveError> {
    let two_t = scalar(dot(solution, l))?;
    let l_squared = scalar(dot(l, l))?;
    d.steps.push(Step::equation(
        "Twice the kinetic energy",
        "2T = vec(omega) · vec(L)",
        &Value::Scalar(two_t.clone()),
        Prose::default()
            .math("vec(omega)^T ten(I) ~ vec(omega)")
            .text(" along the solution: constant"),
    ));
    d.steps.push(Step::equation(
        "Angular momentum squared",
        "L^2",
        &Value::Scalar(l_squared.clone()),
        Prose::default()
            .math("|ten(I) ~ vec(omega)|^2")
            .text(" along the solution: constant, as it must be without torque"),
    ));
    d.set(quantity::TOP_TWICE_ENERGY, Value::Scalar(two_t.clone()))?;
    d.set(
        quantity::TOP_MOMENTUM_SQUARED,
        Value::Scalar(l_squared.clone()),
    )?;

    let body_tan2 = scalar(tan_squared_from_axis(solution))?;
    d.steps.push(Step::equation(
        "Body cone",
        "tan^2 alpha_b",
        &Value::Scalar(body_tan2.clone()),
        Prose::default()
            .math("alpha_b")
            .words(" is the angle between $\\vec\\omega$ and the symmetry axis: ")
            .math("tan alpha_b = A/omega_3"),
    ));
    let space_cos2 = scalar(Expr::over(
        Expr::pow(two_t.clone(), Expr::int(2)),
        Expr::mul(vec![omega_squared.clone(), l_squared.clone()]),
    ))?;
    d.steps.push(Step::equation(
        "Space cone",
        "cos^2 alpha_s",
        &Value::Scalar(space_cos2.clone()),
        cited(
            "space-cone",
            Prose::default()
                .math("alpha_s")
                .words(" is the angle between $\\vec\\omega$ and the fixed $\\vec L$, ")
                .math("cos alpha_s = (vec(omega) · vec(L))/(omega L) = (2T)/(omega L)"),
        ),
    ));
    let tilt_tan2 = scalar(tan_squared_from_axis(l))?;
    d.steps.push(Step::equation(
        "Tilt of $\\vec L$ from the symmetry axis",
        "tan^2 theta_L",
        &Value::Scalar(tilt_tan2.clone()),
        "$(I_1/I_3)^2 \\tan^2\\alpha_b$: $\\vec L$ leans further from the axis than $\\vec\\omega$ when \
         $I_3 < I_1$, less when $I_3 > I_1$; $\\vec\\omega$, $\\vec L$ and the axis lie in one plane",
    ));
    d.set(quantity::BODY_CONE_TAN_SQUARED, Value::Scalar(body_tan2))?;
    d.set(quantity::SPACE_CONE_COS_SQUARED, Value::Scalar(space_cos2))?;
    d.set(
        quantity::MOMENTUM_TILT_TAN_SQUARED,
        Value::Scalar(tilt_tan2),
    )?;
    Ok((two_t, l_squared))
}

/// Which cone is wider, for an oblate and a prolate top.
fn wider_cone(d: &mut Derivation, two_t: Expr, l_squared: Expr) -> Result<(), DeriveError> {
    // α_b > α_s ⟺ cos α_s > cos α_b = ω3/ω ⟺ 2T > ω3 L ⟺ (2T)² − ω3² L² > 0 (both sides positive).
    let cone_order = scalar(Expr::minus(
        Expr::pow(two_t, Expr::int(2)),
        Expr::mul(vec![Expr::pow(s("w3"), Expr::int(2)), l_squared]),
    ))?;
    let in_tan =
        cas::factor_all(vec![cone_order.substitute(&|n| {
            (n == "A").then(|| Expr::mul(vec![s("tau"), s("w3")]))
        })])?
        .remove(0);
    d.steps.push(Step::equation(
        "Which cone is wider",
        "(2T)^2 - omega_3^2 L^2",
        &Value::Scalar(in_tan),
        "with $A = \\tau\\omega_3$, $\\tau = \\tan\\alpha_b$: $\\alpha_b > \\alpha_s$ exactly when this is \
         positive, since $\\cos\\alpha_s = 2T/(\\omega L)$ and $\\cos\\alpha_b = \\omega_3/\\omega$",
    ));
    let oblate = sign_over_positive(
        &cone_order.substitute(&|n| (n == "I3").then(|| Expr::add(vec![s("I1"), s("p")]))),
    )?;
    let prolate = sign_over_positive(
        &cone_order.substitute(&|n| (n == "I1").then(|| Expr::add(vec![s("I3"), s("p")]))),
    )?;
    d.steps.push(Step::note(
        "Oblate and prolate",
        Formula::parse(
            &format!(
                "I_3 > I_1: ~~ \"{}\"; quad I_3 < I_1: ~~ \"{}\"",
                sign_words(oblate),
                sign_words(prolate)
            ),
            &[],
        ),
        "the sign of $(2T)^2 - \\omega_3^2 L^2$ over all positive $I_1$, $p$, $A$, $\\omega_3$: a \
         disc-shaped (oblate) top, $I_3 > I_1$, always has $\\alpha_b > \\alpha_s$; a cigar-shaped \
         (prolate) one, $I_3 < I_1$, has $\\alpha_b < \\alpha_s$ only when \
         $2I_3 < I_1(1 - \\tan^2\\alpha_b)$",
    ));
    d.set(quantity::CONE_ORDER, Value::Scalar(cone_order))?;
    Ok(())
}
