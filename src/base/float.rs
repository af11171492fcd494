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

/// The roots of Σ c_k x^k (c_n ≠ 0) by the Aberth–Ehrlich iteration, which refines all n
/// together and converges where the companion matrix's Schur form may not (equal moduli, as
/// in x⁶ − 2). `None` when it has not settled within 500 sweeps.
pub fn polynomial_roots(c: &[f64]) -> Option<Vec<nalgebra::Complex<f64>>> {
    use nalgebra::Complex;
    let n = c.len().checked_sub(1)?;
    let lead = c[n];
    if n == 0 || lead == 0.0 || !c.iter().all(|x| x.is_finite()) {
        return None;
    }
    // Every root lies within Cauchy's bound; start on a circle inside it, turned off the axes
    // so that no start is a symmetric point of the polynomial.
    let radius = 1.0 + c[..n].iter().fold(0.0f64, |m, x| m.max((x / lead).abs()));
    let mut z: Vec<Complex<f64>> = (0..n)
        .map(|k| {
            let angle = std::f64::consts::TAU * (k as f64 + 0.25) / n as f64 + 0.4;
            Complex::from_polar(radius / 2.0, angle)
        })
        .collect();
    let value_and_slope = |x: Complex<f64>| {
        let (mut p, mut dp) = (Complex::new(lead, 0.0), Complex::new(0.0, 0.0));
        for coefficient in c[..n].iter().rev() {
            dp = dp * x + p;
            p = p * x + coefficient;
        }
        (p, dp)
    };
    for _ in 0..500 {
        let mut moved = 0.0f64;
        for k in 0..n {
            let (p, dp) = value_and_slope(z[k]);
            if p == Complex::new(0.0, 0.0) {
                continue;
            }
            let ratio = p / dp;
            let repulsion: Complex<f64> = (0..n)
                .filter(|j| *j != k)
                .map(|j| (z[k] - z[j]).inv())
                .sum();
            let step = ratio / (Complex::new(1.0, 0.0) - ratio * repulsion);
            if !step.re.is_finite() || !step.im.is_finite() {
                return None;
            }
            z[k] -= step;
            moved = moved.max(step.norm() / z[k].norm().max(f64::MIN_POSITIVE));
        }
        if moved <= 4.0 * f64::EPSILON {
            return Some(z);
        }
    }
    None
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

    /// x⁶ − 2 (whose companion matrix's Schur form need not converge) has the six sixth
    /// roots of 2; (x − 1)(x − 2)(x + 3) = x³ − 7x + 6 has 1, 2, −3.
    #[test]
    fn polynomial_roots_where_the_schur_form_fails_and_where_it_works() {
        use super::polynomial_roots;
        let roots = polynomial_roots(&[-2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]).unwrap();
        assert_eq!(roots.len(), 6);
        let mut angles: Vec<f64> = roots
            .iter()
            .map(|z| {
                assert!((z.norm() - 2f64.powf(1.0 / 6.0)).abs() < 1e-14, "{z}");
                z.arg().rem_euclid(std::f64::consts::TAU)
            })
            .collect();
        angles.sort_by(f64::total_cmp);
        for (k, a) in angles.iter().enumerate() {
            let expected = std::f64::consts::FRAC_PI_3 * k as f64;
            assert!((a - expected).abs() < 1e-13, "{a} against {expected}");
        }
        let mut real: Vec<f64> = polynomial_roots(&[6.0, -7.0, 0.0, 1.0])
            .unwrap()
            .iter()
            .map(|z| {
                assert!(z.im.abs() < 1e-14, "{z}");
                z.re
            })
            .collect();
        real.sort_by(f64::total_cmp);
        for (r, e) in real.iter().zip([-3.0, 1.0, 2.0]) {
            assert!((r - e).abs() < 1e-14, "{r} against {e}");
        }
        assert!(polynomial_roots(&[1.0, 0.0]).is_none(), "no leading term");
    }
}
