//! Principal moments and axes (eqs 47–52): the exact roots of det(I − λ𝟙) = 0 where the
//! characteristic polynomial factors, and for each root its eigenspace: an axis from the cross
//! product of two independent rows of I − λ𝟙 (rank 2), a plane normal to the one independent row
//! (rank 1), or every direction (rank 0).

use super::algebra::{Mat3, Value, Vec3, cross, det};
use super::{Derivation, DeriveError, Step, cited};
use crate::cas::{self, Expr, pull_squares};
use crate::model::catalogue::quantity;
use crate::model::value::{Values, eval_at};
use crate::notation::Formula;
use crate::scene::{Scene, Shape};
use std::collections::BTreeSet;

/// The λ of the characteristic polynomial; `__` never occurs in scene names.
pub const LAMBDA: &str = "lambda__";

#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct ExactEigen {
    pub characteristic: Expr,
    pub spaces: Vec<ExactSpace>,
    /// Irreducible factors of degree ≥ 3 whose roots are left to the numerics.
    pub unsolved: Vec<(Expr, u32)>,
    /// When the whole cubic is irreducible: its three real roots in trigonometric form.
    #[serde(default)]
    pub closed_form: Option<CubicRoots>,
    /// The TeX name of the eigenvalue's letter, `lambda` or `mu` ([`eigenvalue_letter`]), so
    /// that the pages print the letter the steps use without asking the scene again.
    #[serde(default)]
    pub letter: String,
}

/// The three real roots of λ³ − e₁λ² + e₂λ − e₃ (a symmetric tensor's characteristic cubic) by
/// Viète's trigonometric method: λ_k = e₁/3 + 2ρ cos(φ/3 − 2πk/3), k = 0, 1, 2, where
/// ρ = √(−p/3), cos φ = −q/(2ρ³), and t³ + pt + q is the cubic depressed by λ = t + e₁/3.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct CubicRoots {
    pub centre: Expr,
    pub rho: Expr,
    pub cos_phi: Expr,
}

impl CubicRoots {
    /// The three roots at the scene's values, ascending.
    pub fn at(&self, values: &Values) -> Result<[f64; 3], crate::cas::EvalError> {
        let (c, rho) = (eval_at(&self.centre, values)?, eval_at(&self.rho, values)?);
        // Round-off may put cos φ a hair outside [−1, 1] at a double root.
        let phi = eval_at(&self.cos_phi, values)?.clamp(-1.0, 1.0).acos();
        let mut roots = [0, 1, 2].map(|k| {
            c + 2.0 * rho * (phi / 3.0 - 2.0 * std::f64::consts::PI * k as f64 / 3.0).cos()
        });
        roots.sort_by(f64::total_cmp);
        Ok(roots)
    }
}

/// The symbols known to be positive: those of a body's mass or dimension written as a product
/// of symbols with a positive coefficient, positive at the scene's values (a mass m, a side 2a).
/// √(m² a⁴) may then be written m a².
pub fn positive_symbols(scene: &Scene) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for b in &scene.bodies {
        for e in b.dimensions() {
            let monomial = match e {
                Expr::Sym(_) => true,
                Expr::Mul(fs) => fs.iter().all(|f| match f {
                    Expr::Num(r) => r.is_positive(),
                    Expr::Sym(_) => true,
                    Expr::Pow(b, k) => matches!(**b, Expr::Sym(_)) && matches!(**k, Expr::Num(_)),
                    _ => false,
                }),
                _ => false,
            };
            if monomial {
                out.extend(
                    e.symbols()
                        .into_iter()
                        .filter(|s| scene.values.get(s).is_some_and(|v| *v > 0.0)),
                );
            }
        }
    }
    out
}

#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct ExactSpace {
    pub value: Expr,
    pub multiplicity: u32,
    pub basis: ExactBasis,
}

#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub enum ExactBasis {
    Axis(Vec3),
    PlaneNormalTo(Vec3),
    All,
}

fn shifted(m: &Mat3, lambda: &Expr) -> Mat3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            if i == j {
                Expr::minus(m[i][j].clone(), lambda.clone())
            } else {
                m[i][j].clone()
            }
        })
    })
}

/// The first vector that is not identically zero, with its common factor removed.
fn first_nonzero(candidates: Vec<Vec3>) -> Result<Option<Vec3>, DeriveError> {
    for v in candidates {
        let v: Vec<Expr> = cas::simplify_all(v.to_vec())?;
        if !cas::is_zero_all(v.clone())?.into_iter().all(|z| z) {
            let p = cas::primitive_part(v)?;
            return Ok(Some([p[0].clone(), p[1].clone(), p[2].clone()]));
        }
    }
    Ok(None)
}

/// The trigonometric form of the roots of the tensor's characteristic cubic.
fn cubic_roots(tensor: &Mat3, positive: &dyn Fn(&str) -> bool) -> Result<CubicRoots, DeriveError> {
    let t = |i: usize, j: usize| tensor[i][j].clone();
    let prod = |a: Expr, b: Expr| Expr::mul(vec![a, b]);
    let e1 = Expr::add(vec![t(0, 0), t(1, 1), t(2, 2)]);
    let e2 = Expr::add(vec![
        prod(t(0, 0), t(1, 1)),
        prod(t(1, 1), t(2, 2)),
        prod(t(0, 0), t(2, 2)),
        Expr::negate(prod(t(0, 1), t(0, 1))),
        Expr::negate(prod(t(1, 2), t(1, 2))),
        Expr::negate(prod(t(0, 2), t(0, 2))),
    ]);
    let e3 = det(tensor);
    let pw = |e: &Expr, n: i128| Expr::pow(e.clone(), Expr::int(n));
    // p = e₂ − e₁²/3, q = −2e₁³/27 + e₁e₂/3 − e₃.
    let p = Expr::minus(e2.clone(), Expr::mul(vec![Expr::rat(1, 3), pw(&e1, 2)]));
    let q = Expr::add(vec![
        Expr::mul(vec![Expr::rat(-2, 27), pw(&e1, 3)]),
        Expr::mul(vec![Expr::rat(1, 3), e1.clone(), e2]),
        Expr::negate(e3),
    ]);
    let minus_p_third = cas::simplify(&Expr::mul(vec![Expr::rat(-1, 3), p]))?;
    let rho = pull_squares(&Expr::pow(minus_p_third, Expr::rat(1, 2)), positive);
    let cos_phi = cas::simplify(&Expr::over(
        Expr::negate(q),
        Expr::mul(vec![Expr::int(2), pw(&rho, 3)]),
    ))?;
    Ok(CubicRoots {
        centre: cas::simplify(&Expr::mul(vec![Expr::rat(1, 3), e1]))?,
        rho,
        cos_phi: pull_squares(&cos_phi, positive),
    })
}

/// The eigenvalue's letter on a page, as a symbol name: `lambda`, or `mu` where a rod's or a
/// hoop's line density is λ already (so that no letter means two things on one page).
pub fn eigenvalue_letter(scene: &Scene) -> &'static str {
    let line_density = scene
        .bodies
        .iter()
        .any(|b| matches!(b.shape, Shape::Rod { .. } | Shape::Hoop { .. }));
    if line_density { "mu" } else { "lambda" }
}

/// The characteristic polynomial det(I − λ𝟙), factored as (λ₁ − λ)(λ₂ − λ)(λ₃ − λ) over its
/// roots in ascending order where every root was found (the product is checked to multiply
/// back to the determinant); else expanded, as working that a student's summary leaves out.
fn characteristic_step(
    scene: &Scene,
    characteristic: &Expr,
    roots: &cas::Roots,
    ev_name: &str,
) -> Result<Step, DeriveError> {
    let lhs = format!("det big(ten(I) - {ev_name} one) = $0");
    let why = || {
        cited(
            "characteristic-polynomial",
            "the principal moments are the roots",
        )
    };
    let shown = |e: &Expr| e.substitute(&|s| (s == LAMBDA).then(|| Expr::sym(ev_name)));
    if !roots.unsolved.is_empty() || roots.roots.is_empty() {
        let line = Formula::parse(&lhs, &[shown(characteristic)]);
        return Ok(Step::note("Characteristic polynomial", line, why()).working());
    }
    let factor = |value: &Expr, with: &Expr, multiplicity: u32| {
        let difference = Expr::minus(value.clone(), with.clone());
        match multiplicity {
            1 => difference,
            m => Expr::pow(difference, Expr::int(i128::from(m))),
        }
    };
    let product = |with: &Expr| {
        Expr::mul(
            roots
                .roots
                .iter()
                .map(|(value, m)| factor(value, with, *m))
                .collect(),
        )
    };
    let difference = Expr::minus(product(&Expr::sym(LAMBDA)), characteristic.clone());
    if !cas::is_zero_all(vec![difference])?[0] {
        return Err(DeriveError::Inconsistent(format!(
            "the principal moments' product does not give back the characteristic polynomial {characteristic}"
        )));
    }
    // Each moment as its own line prints it, 3M(R² + 4h²)/20, not the engine's 3MR²/20 +
    // 3Mh²/5 (proven equal, so the product is the one checked above).
    let moments = cas::present_all(
        roots.roots.iter().map(|(v, _)| v.clone()).collect(),
        scene.signed_names(),
        scene.declared.clone(),
        crate::notation::printed_length,
    )?;
    let ev = Expr::sym(ev_name);
    let shown_product = Expr::mul(
        moments
            .iter()
            .zip(&roots.roots)
            .map(|(value, (_, m))| factor(value, &ev, *m))
            .collect(),
    );
    let line = Formula::parse(&lhs, &[shown_product]);
    Ok(Step::note("Characteristic polynomial", line, why()))
}

pub fn derive_principal(scene: &Scene, d: &mut Derivation) -> Result<(), DeriveError> {
    let positive_set = positive_symbols(scene);
    let positive = |s: &str| positive_set.contains(s);
    let ev_name = eigenvalue_letter(scene);
    let tensor = d.matrix(quantity::INERTIA_TENSOR)?.clone();
    let lambda = Expr::sym(LAMBDA);
    let characteristic = cas::simplify(&det(&shifted(&tensor, &lambda)))?;
    let shown = |e: &Expr| e.substitute(&|s| (s == LAMBDA).then(|| Expr::sym(ev_name)));
    let roots = sorted_roots(scene, &characteristic, &positive)?;
    d.steps.push(characteristic_step(
        scene,
        &characteristic,
        &roots,
        ev_name,
    )?);
    let mut spaces = Vec::new();
    for (value, multiplicity) in &roots.roots {
        let basis = eigenspace(&tensor, value, *multiplicity)?;
        d.steps.push(space_step(
            ev_name,
            spaces.len() + 1,
            value,
            *multiplicity,
            &basis,
        ));
        spaces.push(ExactSpace {
            value: value.clone(),
            multiplicity: *multiplicity,
            basis,
        });
    }
    for (factor, mult) in &roots.unsolved {
        d.steps.push(
            Step::note(
                "Irreducible factor",
                // A simple factor has no exponent: (…), not (…)¹.
                Formula::parse(
                    &if *mult > 1 {
                        format!("big($0)^{mult}")
                    } else {
                        "$0".to_string()
                    },
                    &[shown(factor)],
                ),
                "no factorisation over the rationals: no root is rational in the symbols",
            )
            .working(),
        );
    }
    // A symmetric tensor's cubic has three real roots: when it does not factor, Viète's
    // trigonometric form gives them exactly.
    let closed_form = if roots.roots.is_empty() && roots.unsolved.len() == 1 {
        Some(closed_form(scene, d, &tensor, &positive, ev_name)?)
    } else {
        None
    };
    if roots.unsolved.is_empty() {
        let moments: Vec<Expr> = spaces
            .iter()
            .flat_map(|s| std::iter::repeat_n(s.value.clone(), s.multiplicity as usize))
            .collect();
        if moments.len() == 3 {
            d.set(
                quantity::PRINCIPAL_MOMENTS,
                Value::Vector([moments[0].clone(), moments[1].clone(), moments[2].clone()]),
            )?;
        }
    }
    d.eigen = Some(ExactEigen {
        characteristic,
        spaces,
        unsolved: roots.unsolved,
        closed_form,
        letter: ev_name.to_string(),
    });
    Ok(())
}

/// The characteristic polynomial's roots, squares pulled out of roots where the symbols are
/// positive. The factoriser's order of factors differs between builds: the moments are put in
/// ascending order at the scene's values (those it cannot evaluate last), ties by their text.
fn sorted_roots(
    scene: &Scene,
    characteristic: &Expr,
    positive: &dyn Fn(&str) -> bool,
) -> Result<cas::Roots, DeriveError> {
    let mut roots = cas::roots(characteristic, LAMBDA)?;
    for (value, _) in roots.roots.iter_mut() {
        *value = pull_squares(value, positive);
    }
    let key = |e: &Expr| (eval_at(e, &scene.values).ok(), e.to_text());
    roots.roots.sort_by(|(a, _), (b, _)| {
        let ((va, ta), (vb, tb)) = (key(a), key(b));
        let by_value = match (va, vb) {
            (Some(x), Some(y)) => x.total_cmp(&y),
            _ => std::cmp::Ordering::Equal,
        };
        (va.is_none().cmp(&vb.is_none()))
            .then(by_value)
            .then(ta.cmp(&tb))
    });
    roots.unsolved.sort_by_key(|(factor, _)| factor.to_text());
    Ok(roots)
}

/// The null space of I − λ𝟙 at a root of `multiplicity`: an axis, a plane, or every axis.
fn eigenspace(tensor: &Mat3, value: &Expr, multiplicity: u32) -> Result<ExactBasis, DeriveError> {
    let m = shifted(tensor, value);
    Ok(match multiplicity {
        1 => match first_nonzero(vec![
            cross(&m[0], &m[1]),
            cross(&m[0], &m[2]),
            cross(&m[1], &m[2]),
        ])? {
            Some(axis) => ExactBasis::Axis(axis),
            None => {
                return Err(DeriveError::Inconsistent(format!(
                    "no eigenvector for the simple root {value}"
                )));
            }
        },
        2 => match first_nonzero(m.to_vec())? {
            Some(normal) => ExactBasis::PlaneNormalTo(normal),
            None => {
                return Err(DeriveError::Inconsistent(format!(
                    "I − λ𝟙 vanishes at the double root {value}"
                )));
            }
        },
        _ => ExactBasis::All,
    })
}

/// The step that states the `number`th principal moment and its eigenspace.
fn space_step(
    ev_name: &str,
    number: usize,
    value: &Expr,
    multiplicity: u32,
    basis: &ExactBasis,
) -> Step {
    let (space, vector, why) = match basis {
        ExactBasis::Axis(a) => (
            "\"axis along \" $1",
            Some(Value::Vector(a.clone()).to_expr()),
            cited(
                "principal-axis",
                format!("the cross product of two independent rows of $\\overleftrightarrow{{I}} - \\{ev_name}\\mathbb{{1}}$ spans its null space"),
            ),
        ),
        ExactBasis::PlaneNormalTo(n) => (
            "\"every axis\" perp $1",
            Some(Value::Vector(n.clone()).to_expr()),
            format!("a double root: $\\overleftrightarrow{{I}} - \\{ev_name}\\mathbb{{1}}$ has rank 1, so its null space is the plane normal to its one independent row").as_str().into(),
        ),
        ExactBasis::All => (
            "\"every axis\"",
            None,
            "a triple root: $\\overleftrightarrow{I}$ is a multiple of the identity".into(),
        ),
    };
    Step::note(
        &format!("Principal moment {number} (multiplicity {multiplicity})"),
        Formula::parse(
            &format!("{ev_name} = $0: ~~ {space}"),
            &[value.clone()]
                .into_iter()
                .chain(vector)
                .collect::<Vec<_>>(),
        ),
        why,
    )
}

/// The three real roots of a cubic that does not factor, in Viète's trigonometric form, and
/// their step.
fn closed_form(
    scene: &Scene,
    d: &mut Derivation,
    tensor: &Mat3,
    positive: &dyn Fn(&str) -> bool,
    ev_name: &str,
) -> Result<CubicRoots, DeriveError> {
    let c = cubic_roots(tensor, positive)?;
    let two_rho = Expr::mul(vec![Expr::int(2), c.rho.clone()]);
    // In the form a textbook prints: the masses cancel from cos φ, squares leave the root.
    let parts = vec![c.centre.clone(), two_rho, c.cos_phi.clone()];
    let signed = parts
        .iter()
        .flat_map(|e| e.symbols())
        .filter(|s| !positive(s))
        .collect();
    let parts = cas::present_all(
        parts,
        signed,
        scene.declared.clone(),
        crate::notation::printed_length,
    )?;
    d.steps.push(Step::note(
        "Principal moments in closed form",
        Formula::parse(
            &format!(
                "{ev_name}_k = $0 + big($1) cos big(varphi/3 - (2pi k)/3), ~~ k = 0, 1, 2, \
                 quad cos varphi = $2"
            ),
            &parts,
        ),
        format!("three real roots ($\\overleftrightarrow{{I}}$ is symmetric): depress the cubic by $\\{ev_name} = t + \\operatorname{{tr}} \\overleftrightarrow{{I}}/3$ to $t^3 + pt + q$, then $t = 2\\rho\\cos\\theta$ with $\\rho = \\sqrt{{-p/3}}$ turns it into $\\cos 3\\theta = -q/(2\\rho^3)$ (Viète)").as_str(),
    ));
    Ok(c)
}
