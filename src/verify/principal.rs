//! The principal moments at the scene's values, by two routes: the exact roots (or the closed
//! form of an irreducible cubic) evaluated, and the eigen-solver on the exact tensor; and the
//! exact eigenspaces against the eigen-solver on the quadrature tensor.

use super::{EXACT_VS_NUMERIC, EigenCheck};
use crate::cas::EvalError;
use crate::derive::Derivation;
use crate::derive::ExactBasis;
use crate::model::catalogue::quantity;
use crate::model::value::eval_at;
use crate::model::value::vector_at;
use crate::numeric::eigen::Space;
use crate::numeric::eigen::{Eigenspace, principal_axes};
use crate::scene::Scene;
use nalgebra::{Matrix3, Vector3};

/// The principal moments at the scene's values, computed whenever the principal axes are: the
/// eigen-solver on the exact tensor at those values, against the exact roots or their closed form.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct PrincipalValues {
    /// SymmetricEigen of the exact tensor at the scene's values, ascending.
    pub numeric: Vec<Eigenspace>,
    /// The exact moments at the values, ascending, each repeated by its multiplicity.
    pub exact: Vec<f64>,
    /// The largest |exact − numeric|, relative to the largest moment.
    pub error: f64,
    /// True when `exact` comes from the trigonometric closed form of an irreducible cubic.
    pub closed_form: bool,
}

/// How far the eigen-solver's moments may sit from the exact ones, relative to the largest. A
/// backward-stable solver errs by a few ε‖I‖; the closed form loses a little more through its
/// arccos near a double root, so this leaves room for both without hiding a wrong root.
pub const PRINCIPAL_AGREEMENT: f64 = 1e-12;

/// The principal moments at the scene's values, by two routes.
pub fn principal_values(
    scene: &Scene,
    d: &Derivation,
) -> Result<Option<PrincipalValues>, EvalError> {
    let (Some(eigen), Ok(tensor)) = (&d.eigen, d.get(quantity::INERTIA_TENSOR)) else {
        return Ok(None);
    };
    let numeric = principal_axes(&tensor.matrix_at(&scene.values)?);
    let mut exact: Vec<f64> = Vec::new();
    for s in &eigen.spaces {
        let v = eval_at(&s.value, &scene.values)?;
        exact.extend(std::iter::repeat_n(v, s.multiplicity as usize));
    }
    let closed_form = exact.is_empty();
    if let Some(c) = &eigen.closed_form {
        exact = c.at(&scene.values)?.to_vec();
    }
    exact.sort_by(f64::total_cmp);
    let flat: Vec<f64> = numeric
        .iter()
        .flat_map(|e| std::iter::repeat_n(e.value, e.multiplicity))
        .collect();
    let scale = flat
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let error = if exact.len() == flat.len() {
        exact
            .iter()
            .zip(&flat)
            .fold(0.0f64, |m, (e, n)| m.max((e - n).abs() / scale))
    } else {
        f64::INFINITY
    };
    Ok(Some(PrincipalValues {
        numeric,
        exact,
        error,
        closed_form,
    }))
}

/// Exact principal moments that are distinct but equal at double precision (4e30 + 9e-20 and
/// 4e30 + 1e-20) are one eigenspace to any numeric solver: merge them as it does, with the
/// same tolerance, so that the two are compared like with like. Two axes merge into the plane
/// they span (its normal is their cross product); anything larger is every direction.
fn merge_equal_in_f64(
    exact: Vec<(f64, u32, Option<Vector3<f64>>)>,
) -> Vec<(f64, u32, Option<Vector3<f64>>)> {
    use crate::numeric::eigen::DEGENERACY_TOLERANCE;
    let scale = exact.iter().fold(0.0f64, |m, e| m.max(e.0.abs()));
    let mut out: Vec<(f64, u32, Option<Vector3<f64>>)> = Vec::new();
    for e in exact {
        match out.last_mut() {
            Some(last) if (e.0 - last.0).abs() <= DEGENERACY_TOLERANCE * scale => {
                let direction = match (last.1, e.1, last.2, e.2) {
                    (1, 1, Some(u), Some(v)) => Some(u.cross(&v)),
                    _ => None,
                };
                *last = (last.0, last.1 + e.1, direction);
            }
            _ => out.push(e),
        }
    }
    out
}

pub fn check_eigen(
    scene: &Scene,
    d: &Derivation,
    tensor: &Matrix3<f64>,
) -> Result<Option<EigenCheck>, EvalError> {
    let Some(eigen) = &d.eigen else {
        return Ok(None);
    };
    let env = |s: &str| scene.values.get(s).copied();
    let numeric = principal_axes(tensor);
    if !eigen.unsolved.is_empty() {
        // No exact roots: each numeric eigenvalue must be a root of the exact characteristic
        // polynomial. Near a simple root |p(λ)| ≈ |p'(λ)|·|Δλ| ≤ 3‖I‖²·ε‖I‖, so the residual is
        // measured relative to ‖I‖³.
        let scale = numeric.iter().fold(0.0f64, |m, e| m.max(e.value.abs()));
        let mut residual = 0.0f64;
        for e in &numeric {
            let at_root = |s: &str| {
                if s == crate::derive::LAMBDA {
                    Some(e.value)
                } else {
                    env(s)
                }
            };
            let p = eigen.characteristic.eval(&at_root)?;
            residual = residual.max(p.abs() / scale.max(f64::MIN_POSITIVE).powi(3));
        }
        return Ok(Some(EigenCheck {
            exact: Vec::new(),
            numeric,
            value_error: residual,
            axis_error: 0.0,
            passed: residual <= EXACT_VS_NUMERIC,
        }));
    }
    // (value, multiplicity, the axis or plane normal if any) at the scene's values.
    let mut exact: Vec<(f64, u32, Option<Vector3<f64>>)> = Vec::new();
    for s in &eigen.spaces {
        let direction = match &s.basis {
            ExactBasis::Axis(v) | ExactBasis::PlaneNormalTo(v) => {
                Some(vector_at(v, &scene.values)?)
            }
            ExactBasis::All => None,
        };
        exact.push((eval_at(&s.value, &scene.values)?, s.multiplicity, direction));
    }
    exact.sort_by(|a, b| a.0.total_cmp(&b.0));
    let exact = merge_equal_in_f64(exact);
    let structure = exact.len() == numeric.len()
        && exact
            .iter()
            .zip(&numeric)
            .all(|(e, n)| e.1 as usize == n.multiplicity)
        && eigen.unsolved.is_empty();
    let scale = exact
        .iter()
        .fold(0.0f64, |m, e| m.max(e.0.abs()))
        .max(f64::MIN_POSITIVE);
    let mut value_error = 0.0f64;
    let mut axis_error = 0.0f64;
    if structure {
        for (e, n) in exact.iter().zip(&numeric) {
            value_error = value_error.max((e.0 - n.value).abs() / scale);
            let num_dir = match &n.space {
                Space::Axis(v) | Space::PlaneNormalTo(v) => Some(*v),
                Space::All => None,
            };
            if let (Some(v), Some(u)) = (e.2, num_dir) {
                axis_error = axis_error.max(1.0 - (v.normalize().dot(&u)).abs());
            }
        }
    }
    Ok(Some(EigenCheck {
        exact: exact.iter().map(|e| (e.0, e.1)).collect(),
        numeric,
        value_error,
        axis_error,
        passed: structure && value_error <= EXACT_VS_NUMERIC && axis_error <= EXACT_VS_NUMERIC,
    }))
}
