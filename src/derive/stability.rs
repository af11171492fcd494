//! Rotation about each principal axis of an asymmetric body (eqs 72–76): Euler's equations
//! linearised about ω = ω_k e_k, the oscillation frequency Ω_k² and amplitude ratio, and the sign
//! of Ω_k² for every ordering of the moments, which classifies each axis as stable or unstable.

use super::algebra::{Mat3, Value};
use super::euler::{moments, omega, torque_free_rates};
use super::sign::{Sign, signs_over_positive};
use super::{Derivation, DeriveError, Step, cited, factored, simplify_vec};
use crate::cas::{self, Expr};
use crate::model::catalogue::quantity;
use crate::model::moments::ORDERINGS;
use crate::model::prose::Prose;
use crate::notation::Formula;

/// Columns of the stability table: the axis has the largest, the smallest or the middle moment.
pub const CLASSES: [&str; 3] = ["largest", "smallest", "intermediate"];

fn words(sign: Sign) -> &'static str {
    match sign {
        Sign::Positive => "stable",
        Sign::Negative => "unstable",
        Sign::NotFixed => "undecided",
    }
}

/// An ordering of the axes (smallest, middle, largest) and the sign of each axis's expression.
pub type OrderingSigns = ([usize; 3], Vec<Sign>);

/// The sign of each axis's expression for every ordering of the moments (smallest = s,
/// middle = s + p, largest = s + p + q, with s, p, q > 0), and the table of those signs by the
/// rank of the axis's moment: row k is axis k, the columns follow [`CLASSES`]. Both orderings
/// that give an axis the same rank must agree, and every sign must be fixed.
pub fn classify(
    per_axis: &[Expr; 3],
    what: &str,
) -> Result<(Mat3, Vec<OrderingSigns>), DeriveError> {
    let moments = moments();
    let mut table: [[Option<Sign>; 3]; 3] = [[None; 3]; 3];
    let mut by_order = Vec::new();
    for order in ORDERINGS {
        let rank = |axis: usize| order.iter().position(|x| *x == axis).unwrap();
        let value = |axis: usize| -> Expr {
            Expr::add([Expr::sym("s"), Expr::sym("p"), Expr::sym("q")][..=rank(axis)].to_vec())
        };
        let substituted: Vec<Expr> = per_axis
            .iter()
            .map(|e| {
                e.substitute(&|n| {
                    moments
                        .iter()
                        .position(|x| matches!(x, Expr::Sym(m) if m == n))
                        .map(value)
                })
            })
            .collect();
        let signs = signs_over_positive(&substituted)?;
        for axis in 0..3 {
            let class = match rank(axis) {
                2 => 0,
                0 => 1,
                _ => 2,
            };
            let cell = &mut table[axis][class];
            if cell.is_some_and(|c| c != signs[axis]) || signs[axis] == Sign::NotFixed {
                return Err(DeriveError::Inconsistent(format!(
                    "axis {}: {what} has no fixed sign when its moment is the {}",
                    axis + 1,
                    CLASSES[class]
                )));
            }
            *cell = Some(signs[axis]);
        }
        by_order.push((order, signs));
    }
    let table = std::array::from_fn(|axis| {
        std::array::from_fn(|class| {
            Expr::int(
                table[axis][class]
                    .expect("every ordering was classified")
                    .as_int(),
            )
        })
    });
    Ok((table, by_order))
}

pub fn axis_stability(d: &mut Derivation) -> Result<(), DeriveError> {
    let i = moments();
    let w = omega();
    let r = simplify_vec(&torque_free_rates(&i, &w))?;
    let rates = Value::Vector(r.clone());
    d.steps.push(Step::equation(
        "Torque-free Euler equations",
        "dot(vec(omega))",
        &factored(&rates)?,
        cited(
            "stability-rates",
            "Euler's equations with $\\vec N = 0$, solved for the rates",
        ),
    ));
    let mut omega_sq: [Expr; 3] = std::array::from_fn(|_| Expr::int(0));
    let mut ratio: [Expr; 3] = std::array::from_fn(|_| Expr::int(0));
    for k in 0..3 {
        (omega_sq[k], ratio[k]) = about_axis(d, &r, k)?;
    }
    d.set(
        quantity::OSCILLATION_FREQUENCY_SQUARED,
        Value::Vector(omega_sq.clone()),
    )?;
    d.set(quantity::AMPLITUDE_RATIO_SQUARED, Value::Vector(ratio))?;

    let stability = by_ordering(d, &omega_sq)?;
    d.steps.push(Step::equation(
        "Stability of each axis",
        "rm(stability)",
        &Value::Matrix(stability.clone()),
        "row k: axis k; columns: its moment is the largest, the smallest, the intermediate; \
         1 stable, −1 unstable. The same for every axis: only the intermediate axis is unstable",
    ));
    d.set(quantity::STABILITY, Value::Matrix(stability))?;
    let growth = cas::simplify(&Expr::negate(omega_sq[1].clone()))?;
    d.steps.push(Step::equation(
        "Growth rate about the intermediate axis 2",
        "sigma^2",
        &factored(&Value::Scalar(growth.clone()))?,
        Prose::default()
            .text("for ")
            .math("I_1 < I_2 < I_3")
            .text(", ")
            .math("Omega_2^2 < 0")
            .text(" and a small deviation grows as ")
            .math("e^(sigma t)")
            .text(" with ")
            .math("sigma^2 = -Omega_2^2"),
    ));
    d.set(quantity::GROWTH_RATE_SQUARED, Value::Scalar(growth))?;
    Ok(())
}

/// The rates linearised about rotation on axis `k` (a Jacobian of first-order terms), and the
/// frequency squared and amplitude ratio squared of the motion they give.
fn about_axis(d: &mut Derivation, r: &[Expr; 3], k: usize) -> Result<(Expr, Expr), DeriveError> {
    let name = |k: usize| format!("w{}", k + 1);
    let (a, b) = ((k + 1) % 3, (k + 2) % 3);
    // First order in the small components ω_a, ω_b: the Jacobian at ω = ω_k e_k.
    let on_axis =
        |e: &Expr| e.substitute(&|s| (s == name(a) || s == name(b)).then(|| Expr::int(0)));
    let partial = |f: &Expr, x: usize| -> Result<Expr, DeriveError> {
        Ok(on_axis(&f.diff(&name(x)).map_err(DeriveError::from)?))
    };
    let entries = vec![
        partial(&r[a], a)?,
        partial(&r[a], b)?,
        partial(&r[b], a)?,
        partial(&r[b], b)?,
        partial(&r[k], a)?,
        partial(&r[k], b)?,
    ];
    let j = cas::simplify_all(entries)?;
    if !(j[0].is_zero() && j[3].is_zero() && j[4].is_zero() && j[5].is_zero()) {
        return Err(DeriveError::Inconsistent(format!(
            "the linearisation about axis {} has unexpected terms",
            k + 1
        )));
    }
    let (jab, jba) = (j[1].clone(), j[2].clone());
    let shown = cas::factor_all(vec![jab.clone(), jba.clone()])?;
    let (ta, tb) = (a + 1, b + 1);
    d.steps.push(Step::note(
        &format!("Linearised about axis {}", k + 1),
        Formula::parse(
            &format!(
                "dot(omega_{ta}) = $0 ~ omega_{tb}, quad dot(omega_{tb}) = $1 ~ omega_{ta}"
            ),
            &shown,
        ),
        format!(
            "$\\vec\\omega = \\omega_{} \\hat e_{}$ plus small $\\omega_{ta}$, $\\omega_{tb}$: keep \
             first-order terms; $\\dot\\omega_{}$, of order $\\omega_{ta}\\omega_{tb}$, is second \
             order and dropped",
            k + 1,
            k + 1,
            k + 1
        ),
    ));
    // ω_a = a cos(Ωt + θ), ω_b = b sin(Ωt + θ): −aΩ = J_ab b and bΩ = J_ba a.
    let both = cas::simplify_all(vec![
        Expr::negate(Expr::mul(vec![jab.clone(), jba.clone()])),
        Expr::negate(Expr::over(jab, jba)),
    ])?;
    d.steps.push(Step::equation(
        &format!("Frequency about axis {}", k + 1),
        &format!("Omega_{}^2", k + 1),
        &factored(&Value::Scalar(both[0].clone()))?,
        {
            let ratio = factored(&Value::Scalar(both[1].clone()))?;
            Prose::default()
                .words(&format!(
                    "$\\omega_{ta} = a\\cos(\\Omega t + \\theta)$, \
                     $\\omega_{tb} = b\\sin(\\Omega t + \\theta)$ solve the pair when \
                     $\\Omega^2$ is minus the product of the two coefficients; then "
                ))
                .formula(Formula::parse("(a/b)^2 = $0", &[ratio.to_expr()]))
        },
    ));
    Ok((both[0].clone(), both[1].clone()))
}

/// Each axis's verdict for each ordering of the moments, by the signs of Ω²; the stability
/// matrix.
fn by_ordering(d: &mut Derivation, omega_sq: &[Expr; 3]) -> Result<Mat3, DeriveError> {
    let (stability, by_order) = classify(omega_sq, "Ω²")?;
    // `I2` as LaTeX, `I_2`, for the titles and reasons.
    let tex = |label: &str| label.replace('I', "I_");
    for (order, signs) in by_order {
        let label = |k: usize| format!("I{}", order[k] + 1);
        let verdicts: Vec<String> = (0..3)
            .map(|axis| format!("axis {} {}", axis + 1, words(signs[axis])))
            .collect();
        d.steps.push(Step::note(
            &format!(
                "${} < {} < {}$",
                tex(&label(0)),
                tex(&label(1)),
                tex(&label(2))
            ),
            Formula::parse(
                &format!(
                    "{} < {} < {}: ~~ \"{}\"",
                    label(0).replace('I', "I_"),
                    label(1).replace('I', "I_"),
                    label(2).replace('I', "I_"),
                    verdicts.join(", ")
                ),
                &[],
            ),
            format!(
                "${} = s$, ${} = s + p$, ${} = s + p + q$ with $s, p, q > 0$: each $\\Omega_k^2$ then \
                 has terms of one sign ($\\Omega^2 > 0$: oscillation, stable; $\\Omega^2 < 0$: \
                 exponential growth, unstable)",
                tex(&label(0)),
                tex(&label(1)),
                tex(&label(2))
            ),
        ));
    }
    Ok(stability)
}
