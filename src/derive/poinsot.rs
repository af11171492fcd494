//! Poinsot's construction (eqs 77–87): ρ = ω/√(2T) on the inertia ellipsoid F(ρ) = 1, the normal
//! ∇F parallel to L, the fixed distance √(2T)/L to the invariable plane, the energy ellipsoid and
//! the L-sphere in L-space, the bounds on L², and which polhodes close.

use super::algebra::{Mat3, Value, Vec3, diag, dot, mat_vec};
use super::euler::{moments, omega, rate_along, torque_free_rates};
use super::stability::classify;
use super::{Derivation, DeriveError, Step, cited, factored};
use crate::cas::{self, Expr};
use crate::model::catalogue::quantity;
use crate::model::prose::Prose;
use crate::notation::Formula;

fn scalar(d: &mut Derivation, name: &str, e: Expr) -> Result<Expr, DeriveError> {
    let e = cas::simplify(&e)?;
    d.set(name, Value::Scalar(e.clone()))?;
    Ok(e)
}

fn sq(e: &Expr) -> Expr {
    Expr::pow(e.clone(), Expr::int(2))
}

pub fn poinsot(d: &mut Derivation) -> Result<(), DeriveError> {
    let i = moments();
    let inertia = diag(i.clone());
    let (two_t, l_squared) = invariants(d, &i, &inertia)?;
    ellipsoid(d, &i, &inertia, &two_t, &l_squared)?;
    let conic = momentum_space(d, &i, &two_t, &l_squared)?;
    let product = polhode_conics(d, &conic)?;
    closure_and_separatrix(d, &conic, &product)
}

/// 2T and L², both constant along the torque-free motion (eq 78).
fn invariants(d: &mut Derivation, i: &Vec3, inertia: &Mat3) -> Result<(Expr, Expr), DeriveError> {
    let w = omega();
    let l = mat_vec(inertia, &w);
    let two_t = scalar(d, quantity::TWICE_ENERGY, dot(&w, &l))?;
    let l_squared = scalar(d, quantity::MOMENTUM_SQUARED, dot(&l, &l))?;
    d.steps.push(Step::equation(
        "Twice the kinetic energy",
        "2T",
        &Value::Scalar(two_t.clone()),
        cited(
            "twice-energy",
            Prose::default().math("2T = vec(omega) · vec(L) = vec(omega)^T ten(I) ~ vec(omega)"),
        ),
    ));
    d.steps.push(Step::equation(
        "Angular momentum squared",
        "L^2",
        &Value::Scalar(l_squared.clone()),
        cited(
            "momentum-squared",
            Prose::default().math("L_i = I_i ~ omega_i"),
        ),
    ));
    let rates = torque_free_rates(i, &w);
    let invariant_rates = cas::simplify_all(vec![
        rate_along(&two_t, &rates)?,
        rate_along(&l_squared, &rates)?,
    ])?;
    if !invariant_rates.iter().all(Expr::is_zero) {
        return Err(DeriveError::Inconsistent(
            "2T or L² changes along the torque-free motion".into(),
        ));
    }
    d.steps.push(Step::note(
        "Both are constant",
        Formula::parse("(d(2T))/(dt) = 0, quad (d(L^2))/(dt) = 0", &[]),
        "differentiated along the torque-free Euler equations by the chain rule: both vanish \
         identically",
    ));
    Ok((two_t, l_squared))
}

/// Poinsot's point on the inertia ellipsoid, its normal along L and the invariable plane's
/// distance (eqs 77, 79–81).
fn ellipsoid(
    d: &mut Derivation,
    i: &Vec3,
    inertia: &Mat3,
    two_t: &Expr,
    l_squared: &Expr,
) -> Result<(), DeriveError> {
    // ρ = c ω with c = 1/√(2T); every result below is even in c, so c² = 1/(2T) is exact.
    let c2 = Expr::pow(two_t.clone(), Expr::int(-1));
    let f = scalar(
        d,
        quantity::ELLIPSOID_VALUE,
        Expr::mul(vec![c2.clone(), two_t.clone()]),
    )?;
    d.steps.push(Step::equation(
        "The point $\\vec\\rho = \\vec\\omega/\\sqrt{2T}$ lies on the inertia ellipsoid",
        "F(vec(rho)) = vec(rho)^T I vec(rho)",
        &Value::Scalar(f),
        cited(
            "ellipsoid-point",
            Prose::default()
                .math("vec(rho)^T ten(I) ~ vec(rho) = (vec(omega)^T ten(I) ~ vec(omega))/(2T)"),
        ),
    ));
    // ∇F = 2Iρ = 2c L: the factor squared is 4c² = 2/T.
    let rho_names = ["r1", "r2", "r3"].map(Expr::sym);
    let f_rho = dot(&rho_names, &mat_vec(inertia, &rho_names));
    let grad: Vec<Expr> = ["r1", "r2", "r3"]
        .iter()
        .map(|x| f_rho.diff(x).map_err(DeriveError::from))
        .collect::<Result<_, _>>()?;
    // ∇F_i / L_i with ρ_i = c ω_i, squared, then c² = 1/(2T).
    let factors: Vec<Expr> = (0..3)
        .map(|k| {
            let ratio = Expr::over(
                grad[k].clone(),
                Expr::mul(vec![rho_names[k].clone(), i[k].clone()]),
            );
            Expr::mul(vec![sq(&ratio), c2.clone()])
        })
        .collect();
    let factors = cas::simplify_all(factors)?;
    if !(factors[0] == factors[1] && factors[1] == factors[2]) {
        return Err(DeriveError::Inconsistent("∇F is not parallel to L".into()));
    }
    let gradient = scalar(d, quantity::GRADIENT_FACTOR_SQUARED, factors[0].clone())?;
    d.steps.push(Step::equation(
        "The normal to the ellipsoid is along $\\vec L$",
        "((nabla_rho F)/vec(L))^2",
        &Value::Scalar(gradient),
        cited(
            "ellipsoid-gradient",
            Prose::default()
                .math("nabla F = 2 ten(I) ~ vec(rho) = (2 vec(L))/sqrt(2T)")
                .text(", the same factor for all three components, so ")
                .math("nabla F || vec(L)")
                .text("; the factor is ")
                .math("sqrt(2/T)"),
        ),
    ));
    // The distance ρ·L/L = c ω·L/L = c 2T/L, squared.
    let distance = scalar(
        d,
        quantity::PLANE_DISTANCE_SQUARED,
        Expr::over(Expr::mul(vec![c2.clone(), sq(two_t)]), l_squared.clone()),
    )?;
    d.steps.push(Step::equation(
        "Distance to the invariable plane",
        "((vec(rho) · vec(L))/L)^2",
        &Value::Scalar(distance),
        cited(
            "invariable-plane",
            Prose::default()
                .math("(vec(rho) · vec(L))/L = (vec(omega) · vec(L))/(L sqrt(2T)) = sqrt(2T)/L")
                .words(", constant because $T$ and $L$ are"),
        ),
    ));
    Ok(())
}

/// The energy ellipsoid in L-space and L² − 2T I_k as a conic in the other two components
/// (eqs 82–85); returns the conics.
fn momentum_space(
    d: &mut Derivation,
    i: &Vec3,
    two_t: &Expr,
    l_squared: &Expr,
) -> Result<Vec<Expr>, DeriveError> {
    // L-space: ω_i = L_i/I_i.
    let big_l = ["L1", "L2", "L3"].map(Expr::sym);
    let in_l = |e: &Expr| {
        e.substitute(&|n| {
            (0..3)
                .find(|k| n == format!("w{}", k + 1))
                .map(|k| Expr::over(big_l[k].clone(), i[k].clone()))
        })
    };
    let energy = scalar(
        d,
        quantity::ENERGY_FROM_MOMENTUM,
        Expr::mul(vec![Expr::rat(1, 2), in_l(two_t)]),
    )?;
    d.steps.push(Step::equation(
        "Energy in terms of L",
        "T",
        &Value::Scalar(energy),
        cited(
            "energy-ellipsoid",
            Prose::default()
                .math("T = sum_i L_i^2/(2I_i)")
                .text("; with 2T fixed this is the energy ellipsoid, semi-axes ")
                .math("sqrt(2T ~ I_i)"),
        ),
    ));
    let gap: Vec3 = std::array::from_fn(|k| {
        Expr::minus(
            l_squared.clone(),
            Expr::mul(vec![two_t.clone(), i[k].clone()]),
        )
    });
    let gap = cas::simplify_all(gap.to_vec())?;
    d.set(
        quantity::MOMENTUM_GAP,
        Value::Vector([gap[0].clone(), gap[1].clone(), gap[2].clone()]),
    )?;
    d.steps.push(Step::equation(
        "How far $L^2$ is from $2T I_k$",
        "L^2 - 2T I_k",
        &Value::Vector([gap[0].clone(), gap[1].clone(), gap[2].clone()]),
        Prose::default()
            .words("entry $k$ is ")
            .math("sum_i I_i big(I_i - I_k) omega_i^2")
            .words(": non-negative when $I_k$ is the smallest moment and non-positive when it is the largest, so ")
            .math("2T ~ I_min <= L^2 <= 2T ~ I_max")
            .text(" (eq 85)"),
    ));
    // L² − 2T I_k in L-space: a conic in the two components other than L_k.
    Ok(cas::simplify_all(gap.iter().map(&in_l).collect())?)
}

/// The product of each conic's two coefficients: an ellipse where positive.
fn polhode_conics(d: &mut Derivation, conic: &[Expr]) -> Result<Vec3, DeriveError> {
    // Near axis k, eliminate L_k: L² − 2T I_k = Σ_{i≠k} L_i² (1 − I_k/I_i), a conic in the
    // other two components. An ellipse (closed polhode) when both coefficients share a sign.
    let mut product: [Expr; 3] = std::array::from_fn(|_| Expr::int(0));
    for k in 0..3 {
        let coeff = |x: usize| -> Result<Expr, DeriveError> {
            conic[k]
                .diff(&format!("L{}", x + 1))
                .and_then(|e| e.diff(&format!("L{}", x + 1)))
                .map_err(DeriveError::from)
        };
        let (a, b) = ((k + 1) % 3, (k + 2) % 3);
        let c = cas::simplify_all(vec![coeff(k)?, coeff(a)?, coeff(b)?])?;
        if !c[0].is_zero() {
            return Err(DeriveError::Inconsistent(format!(
                "L{} does not drop out of L² − 2T I{}",
                k + 1,
                k + 1
            )));
        }
        // Halve the second derivatives to get the coefficients.
        product[k] = cas::simplify(&Expr::mul(vec![
            Expr::rat(1, 4),
            c[1].clone(),
            c[2].clone(),
        ]))?;
    }
    d.steps.push(Step::equation(
        "The polhode near each axis",
        "c_a ~ c_b",
        &factored(&Value::Vector(product.clone()))?,
        Prose::default()
            .words("near axis $k$ the sphere and the ellipsoid meet where ")
            .math("c_a L_a^2 + c_b L_b^2 = L^2 - 2T ~ I_k")
            .text(" with ")
            .math("c_i = 1 - I_k/I_i")
            .words(": entry $k$ is ")
            .math("c_a c_b")
            .words(", positive for an ellipse (the polhode closes around axis $k$) and negative for a hyperbola (it does not)"),
    ));
    d.set(
        quantity::POLHODE_CONIC_PRODUCT,
        Value::Vector(product.clone()),
    )?;
    Ok(product)
}

/// Which polhodes close (eqs 86, 87), and the separatrix through the intermediate axis.
fn closure_and_separatrix(
    d: &mut Derivation,
    conic: &[Expr],
    product: &Vec3,
) -> Result<(), DeriveError> {
    let (closure, _) = classify(product, "the polhode conic")?;
    d.steps.push(Step::equation(
        "Which polhodes close",
        "rm(closure)",
        &Value::Matrix(closure.clone()),
        "row k: axis k; columns: its moment is the largest, the smallest, the intermediate; \
         1 closed curves around it, −1 none. Curves close around the largest and the smallest \
         axis (eqs 86, 87) and cross at the intermediate one: the separatrix",
    ));
    d.set(quantity::POLHODE_CLOSURE, Value::Matrix(closure))?;

    // The separatrix L² = 2T I2: c1 L1² + c3 L3² = 0, two planes through axis 2.
    let slope = cas::simplify(&Expr::negate(Expr::over(
        conic[1]
            .diff("L1")
            .and_then(|e| e.diff("L1"))
            .map_err(DeriveError::from)?,
        conic[1]
            .diff("L3")
            .and_then(|e| e.diff("L3"))
            .map_err(DeriveError::from)?,
    )))?;
    d.steps.push(Step::equation(
        "The separatrix",
        "(L_3/L_1)^2",
        &factored(&Value::Scalar(slope.clone()))?,
        Prose::default()
            .text("on ")
            .math("L^2 = 2T ~ I_2")
            .text(" the ")
            .math("L_2^2")
            .text(" terms cancel and ")
            .math("c_1 L_1^2 + c_3 L_3^2 = 0")
            .words(": two planes through axis 2, real when $I_2$ lies between $I_1$ and $I_3$"),
    ));
    d.set(quantity::SEPARATRIX_SLOPE_SQUARED, Value::Scalar(slope))?;
    Ok(())
}
