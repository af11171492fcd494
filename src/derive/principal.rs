//! Principal moments and axes (eqs 47–52): the exact roots of det(I − λ𝟙) = 0 where the
//! characteristic polynomial factors, and for each root its eigenspace: an axis from the cross
//! product of two independent rows of I − λ𝟙 (rank 2), a plane normal to the one independent row
//! (rank 1), or every direction (rank 0).

use super::algebra::{Mat3, Value, Vec3, cross, det};
use super::{Derivation, DeriveError, Step};
use crate::cas::{self, Expr};
use crate::model::catalogue::quantity;

/// The λ of the characteristic polynomial; `__` never occurs in scene names.
pub const LAMBDA: &str = "lambda__";

#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct ExactEigen {
    pub characteristic: Expr,
    pub spaces: Vec<ExactSpace>,
    /// Irreducible factors of degree ≥ 3 whose roots are left to the numerics.
    pub unsolved: Vec<(Expr, u32)>,
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

pub fn derive_principal(d: &mut Derivation) -> Result<(), DeriveError> {
    let Value::Matrix(tensor) = d.get(quantity::INERTIA_TENSOR)?.clone() else {
        unreachable!()
    };
    let lambda = Expr::sym(LAMBDA);
    let characteristic = cas::simplify(&det(&shifted(&tensor, &lambda)))?;
    let shown = |e: &Expr| e.substitute(&|s| (s == LAMBDA).then(|| Expr::sym("lambda")));
    d.steps.push(Step::note(
        "Characteristic polynomial",
        format!("det(I − λ𝟙) = {}", shown(&characteristic)),
        format!(
            "\\det\\left(\\overleftrightarrow{{I}} - \\lambda \\mathbb{{1}}\\right) = {}",
            shown(&characteristic).to_latex()
        ),
        "eq (51): the principal moments are the roots",
    ));
    let roots = cas::roots(&characteristic, LAMBDA)?;
    let mut spaces = Vec::new();
    for (value, multiplicity) in &roots.roots {
        let m = shifted(&tensor, value);
        let basis = match multiplicity {
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
        };
        let (text, latex, why) = match &basis {
            ExactBasis::Axis(a) => (
                format!("axis along {}", Value::Vector(a.clone()).to_text()),
                format!(
                    "\\text{{axis along }} {}",
                    Value::Vector(a.clone()).to_latex()
                ),
                "eq (52): the cross product of two independent rows of I − λ𝟙 spans its null space",
            ),
            ExactBasis::PlaneNormalTo(n) => (
                format!(
                    "every axis perpendicular to {}",
                    Value::Vector(n.clone()).to_text()
                ),
                format!(
                    "\\text{{every axis}} \\perp {}",
                    Value::Vector(n.clone()).to_latex()
                ),
                "a double root: I − λ𝟙 has rank 1, so its null space is the plane normal to its one independent row",
            ),
            ExactBasis::All => (
                "every axis".into(),
                "\\text{every axis}".into(),
                "a triple root: I is a multiple of the identity",
            ),
        };
        d.steps.push(Step::note(
            &format!(
                "Principal moment {} (multiplicity {multiplicity})",
                spaces.len() + 1
            ),
            format!("λ = {value}: {text}"),
            format!("\\lambda = {}: \\; {latex}", value.to_latex()),
            why,
        ));
        spaces.push(ExactSpace {
            value: value.clone(),
            multiplicity: *multiplicity,
            basis,
        });
    }
    for (factor, mult) in &roots.unsolved {
        d.steps.push(Step::note(
            "Irreducible factor",
            format!("({})^{mult}", shown(factor)),
            format!("\\left({}\\right)^{{{mult}}}", shown(factor).to_latex()),
            "no rational factorisation: its roots are left to the numeric eigen-solver",
        ));
    }
    if roots.unsolved.is_empty() {
        let moments: Vec<Expr> = spaces
            .iter()
            .flat_map(|s| std::iter::repeat_n(s.value.clone(), s.multiplicity as usize))
            .collect();
        if moments.len() == 3 {
            d.set(
                quantity::PRINCIPAL_MOMENTS,
                Value::Vector([moments[0].clone(), moments[1].clone(), moments[2].clone()]),
            );
        }
    }
    d.eigen = Some(ExactEigen {
        characteristic,
        spaces,
        unsolved: roots.unsolved,
    });
    Ok(())
}
