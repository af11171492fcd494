//! Principal moments and axes with nalgebra's `SymmetricEigen`, reporting a repeated eigenvalue
//! as an eigenspace rather than an arbitrary basis of it.

use nalgebra::{Matrix3, SymmetricEigen, Vector3};

/// A principal moment with its multiplicity and the eigenspace it spans.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Eigenspace {
    pub value: f64,
    pub multiplicity: usize,
    pub space: Space,
}

#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Space {
    /// A single axis (sign chosen so that the largest component is positive).
    Axis(Vector3<f64>),
    /// Every direction perpendicular to this unit normal.
    PlaneNormalTo(Vector3<f64>),
    /// Every direction: the tensor is a multiple of the identity.
    All,
}

/// Eigenvalues closer than this, relative to the largest, count as equal. A backward-stable
/// symmetric solver perturbs eigenvalues by a small multiple of ε‖I‖, so 64ε leaves a wide
/// margin above round-off while still separating a genuine relative gap of 1e-13.
pub const DEGENERACY_TOLERANCE: f64 = 64.0 * f64::EPSILON;

/// A symmetric matrix's eigenvalues in ascending order, each as the solver gives it.
pub fn sorted_eigenvalues(tensor: &Matrix3<f64>) -> [f64; 3] {
    let mut values: [f64; 3] = SymmetricEigen::new(*tensor).eigenvalues.into();
    values.sort_by(f64::total_cmp);
    values
}

/// Principal moments in ascending order, grouped into eigenspaces.
///
/// A uniform cube about its corner has I = m a² [[2/3, −1/4, −1/4], …] (eq 31): its diagonal
/// (1, 1, 1) is a principal axis with moment m a²/6, and every axis perpendicular to it has
/// 11 m a²/12.
///
/// ```
/// use mechbook::numeric::eigen::{principal_axes, Space};
/// let t = nalgebra::Matrix3::new(8.0, -3.0, -3.0, -3.0, 8.0, -3.0, -3.0, -3.0, 8.0) / 12.0;
/// let spaces = principal_axes(&t);
/// assert!((spaces[0].value - 1.0 / 6.0).abs() < 1e-15);
/// assert_eq!(spaces[1].multiplicity, 2);
/// assert!(matches!(spaces[1].space, Space::PlaneNormalTo(_)));
/// ```
pub fn principal_axes(tensor: &Matrix3<f64>) -> Vec<Eigenspace> {
    let eig = SymmetricEigen::new(*tensor);
    let mut pairs: Vec<(f64, Vector3<f64>)> = (0..3)
        .map(|i| (eig.eigenvalues[i], eig.eigenvectors.column(i).into_owned()))
        .collect();
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let scale = pairs
        .iter()
        .map(|p| p.0.abs())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let same = |a: f64, b: f64| (a - b).abs() <= DEGENERACY_TOLERANCE * scale;

    let mut groups: Vec<Vec<usize>> = Vec::new();
    for i in 0..3 {
        match groups.last_mut() {
            Some(g) if same(pairs[g[0]].0, pairs[i].0) => g.push(i),
            _ => groups.push(vec![i]),
        }
    }
    groups
        .iter()
        .map(|g| {
            let value = g.iter().map(|&i| pairs[i].0).sum::<f64>() / g.len() as f64;
            let space = match g.len() {
                1 => Space::Axis(canonical_sign(pairs[g[0]].1)),
                2 => {
                    let other = (0..3).find(|i| !g.contains(i)).unwrap();
                    Space::PlaneNormalTo(canonical_sign(pairs[other].1))
                }
                _ => Space::All,
            };
            Eigenspace {
                value,
                multiplicity: g.len(),
                space,
            }
        })
        .collect()
}

/// Flips a vector so that its largest-magnitude component is positive: a deterministic sign.
pub fn canonical_sign(v: Vector3<f64>) -> Vector3<f64> {
    let k = v.iamax();
    if v[k] < 0.0 { -v } else { v }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_corner_has_a_double_eigenvalue_and_the_diagonal_axis() {
        // m a² [[2/3, -1/4, -1/4], ...]: independent check against its trace and the diagonal.
        let t = Matrix3::new(
            2.0 / 3.0,
            -0.25,
            -0.25,
            -0.25,
            2.0 / 3.0,
            -0.25,
            -0.25,
            -0.25,
            2.0 / 3.0,
        );
        let spaces = principal_axes(&t);
        assert_eq!(spaces.len(), 2);
        assert_eq!(spaces[0].multiplicity, 1);
        assert_eq!(spaces[1].multiplicity, 2);
        let Space::Axis(a) = &spaces[0].space else {
            panic!()
        };
        let d = Vector3::new(1.0, 1.0, 1.0).normalize();
        assert!((a - d).norm() < 1e-14);
        assert!((t * d - spaces[0].value * d).norm() < 1e-14);
        let trace: f64 = spaces.iter().map(|s| s.value * s.multiplicity as f64).sum();
        assert!((trace - 2.0).abs() < 1e-14);
        let Space::PlaneNormalTo(n) = &spaces[1].space else {
            panic!()
        };
        assert!((n - d).norm() < 1e-14);
    }

    #[test]
    fn isotropic_and_nearly_degenerate_tensors() {
        let spaces = principal_axes(&(Matrix3::identity() * 0.4));
        assert_eq!(spaces.len(), 1);
        assert_eq!((spaces[0].multiplicity, &spaces[0].space), (3, &Space::All));
        assert!((spaces[0].value - 0.4).abs() < 4.0 * f64::EPSILON);
        // A relative gap of 1e-12 is resolved, not merged.
        let t = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0 + 1e-12, 2.0));
        assert_eq!(principal_axes(&t).len(), 3);
    }
}
