//! Facts about f64 inputs that decide whether a computation can be trusted.

/// The largest entry-wise distance between `approx` and `exact`, relative to the largest
/// entry of `exact`: the error measure of every numeric cross-check.
pub fn max_relative_error(approx: &[f64], exact: &[f64]) -> f64 {
    let scale = exact
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()))
        .max(f64::MIN_POSITIVE);
    exact
        .iter()
        .zip(approx)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / scale
}

/// The first value that is subnormal (nonzero, below f64::MIN_POSITIVE): it has lost digits,
/// so every product with it is wrong.
pub fn first_subnormal(v: &[f64]) -> Option<usize> {
    v.iter()
        .position(|x| *x != 0.0 && x.abs() < f64::MIN_POSITIVE)
}

/// The most QR sweeps the Schur form of a general matrix may take: nalgebra's own
/// `complex_eigenvalues` has no bound, and the companion matrix of r⁶ − 2 never converges
/// under it.
const SCHUR_SWEEPS: usize = 10_000;

/// The eigenvalues of a general square matrix, complex in general; `None` when its Schur form
/// does not converge within [`SCHUR_SWEEPS`] sweeps (or a value is not finite).
pub fn complex_eigenvalues(m: nalgebra::DMatrix<f64>) -> Option<Vec<nalgebra::Complex<f64>>> {
    if !m.iter().all(|x| x.is_finite()) {
        return None;
    }
    let schur = nalgebra::linalg::Schur::try_new(m, f64::EPSILON, SCHUR_SWEEPS)?;
    Some(schur.complex_eigenvalues().iter().copied().collect())
}

#[cfg(test)]
mod eigen_tests {
    use super::complex_eigenvalues;
    use nalgebra::DMatrix;

    #[test]
    fn a_schur_form_that_does_not_converge_is_given_up_not_waited_for() {
        // The companion matrix of x⁶ − 2: nalgebra's unbounded `complex_eigenvalues` never
        // returned on it. Bounded, it returns; any roots it gives are sixth roots of 2.
        let m = DMatrix::from_fn(6, 6, |i, j| match (i, j) {
            (0, 5) => 2.0,
            (i, j) if i == j + 1 => 1.0,
            _ => 0.0,
        });
        if let Some(roots) = complex_eigenvalues(m) {
            for z in roots {
                assert!((z.norm().powi(6) - 2.0).abs() < 1e-9, "{z}");
            }
        }
        // A rotation's eigenvalues are ±i.
        let rotation = DMatrix::from_row_slice(2, 2, &[0.0, -1.0, 1.0, 0.0]);
        let e = complex_eigenvalues(rotation).unwrap();
        assert!(
            e.iter()
                .all(|z| z.re.abs() < 1e-12 && (z.im.abs() - 1.0).abs() < 1e-12),
            "{e:?}"
        );
        assert!(complex_eigenvalues(DMatrix::from_element(1, 1, f64::NAN)).is_none());
    }
}
