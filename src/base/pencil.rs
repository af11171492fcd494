//! The eigenvalues λ of a symmetric pencil K x = λ M x (M positive definite) by Sturm
//! bisection: M = LLᵀ, A = L⁻¹ K L⁻ᵀ reduced to tridiagonal form, and each λ_k found where
//! the count of eigenvalues below σ (the sign changes of the Sturm sequence) passes k. It
//! shares no step with the QR iteration on M⁻¹K, so each checks the other.

use nalgebra::DMatrix;

/// Why a pencil has no eigenvalues by this route.
#[derive(Debug, Clone, PartialEq)]
pub enum PencilError {
    /// An entry is not a finite number.
    NotFinite,
    /// `matrix` ('K' or 'M') differs from its transpose at (row, column), counted from 1.
    NotSymmetric {
        matrix: char,
        row: usize,
        column: usize,
    },
    /// M has no Cholesky factor: a coordinate without inertia, or a negative one.
    NotPositiveDefinite,
}

impl std::fmt::Display for PencilError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PencilError::NotFinite => write!(f, "an entry of M or K is not a finite number"),
            PencilError::NotSymmetric {
                matrix,
                row,
                column,
            } => write!(
                f,
                "{matrix} is not symmetric (entries ({row}, {column}) and ({column}, {row}) \
                 differ)"
            ),
            PencilError::NotPositiveDefinite => write!(f, "M is not positive definite"),
        }
    }
}

/// How far a symmetric matrix's entries may differ from its transpose's, relative to its
/// largest entry: rounding in the entries' evaluation, not a modelling asymmetry.
const SYMMETRY: f64 = 1e-10;

/// The most halvings of one eigenvalue's bracket: from the Gershgorin interval to adjacent
/// floating-point numbers takes about 60 for any interval within f64's range.
const HALVINGS: usize = 200;

/// The n eigenvalues of K x = λ M x, ascending, each to a few units in the last place of the
/// largest.
pub fn symmetric_pencil_eigenvalues(
    k: &DMatrix<f64>,
    m: &DMatrix<f64>,
) -> Result<Vec<f64>, PencilError> {
    if k.iter().chain(m.iter()).any(|x| !x.is_finite()) {
        return Err(PencilError::NotFinite);
    }
    symmetric('K', k)?;
    symmetric('M', m)?;
    let l = m
        .clone()
        .cholesky()
        .ok_or(PencilError::NotPositiveDefinite)?
        .l();
    // A = L⁻¹ K L⁻ᵀ: two triangular solves, then made exactly symmetric.
    let x = l
        .solve_lower_triangular(k)
        .ok_or(PencilError::NotPositiveDefinite)?;
    let a = l
        .solve_lower_triangular(&x.transpose())
        .ok_or(PencilError::NotPositiveDefinite)?;
    let a = (&a + a.transpose()) * 0.5;
    let (d, e) = nalgebra::linalg::SymmetricTridiagonal::new(a).unpack_tridiagonal();
    let (d, e): (Vec<f64>, Vec<f64>) = (d.iter().copied().collect(), e.iter().copied().collect());
    // Gershgorin's discs hold every eigenvalue.
    let radius = |i: usize| {
        let before = if i > 0 { e[i - 1].abs() } else { 0.0 };
        before + e.get(i).map_or(0.0, |x| x.abs())
    };
    let lo = (0..d.len())
        .map(|i| d[i] - radius(i))
        .fold(f64::MAX, f64::min);
    let hi = (0..d.len())
        .map(|i| d[i] + radius(i))
        .fold(f64::MIN, f64::max);
    Ok((0..d.len())
        .map(|index| bisect(&d, &e, index, lo, hi))
        .collect())
}

/// `matrix` equals its transpose within [`SYMMETRY`].
fn symmetric(name: char, matrix: &DMatrix<f64>) -> Result<(), PencilError> {
    let scale = matrix.amax().max(f64::MIN_POSITIVE);
    for i in 0..matrix.nrows() {
        for j in i + 1..matrix.ncols() {
            if (matrix[(i, j)] - matrix[(j, i)]).abs() > SYMMETRY * scale {
                return Err(PencilError::NotSymmetric {
                    matrix: name,
                    row: i + 1,
                    column: j + 1,
                });
            }
        }
    }
    Ok(())
}

/// The `index`-th smallest eigenvalue of the tridiagonal (d, e), within [lo, hi].
fn bisect(d: &[f64], e: &[f64], index: usize, mut lo: f64, mut hi: f64) -> f64 {
    for _ in 0..HALVINGS {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if below(d, e, mid) > index {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

/// How many eigenvalues of the tridiagonal (d, e) lie below σ: the negative pivots of the
/// LDLᵀ factors of T − σI (Sylvester's law of inertia), which are the Sturm sequence's ratios.
fn below(d: &[f64], e: &[f64], sigma: f64) -> usize {
    let scale = d
        .iter()
        .chain(e)
        .fold(sigma.abs(), |a, x| a.max(x.abs()))
        .max(f64::MIN_POSITIVE);
    let mut count = 0;
    let mut q = 1.0;
    for i in 0..d.len() {
        let coupling = if i > 0 { e[i - 1] * e[i - 1] / q } else { 0.0 };
        q = d[i] - sigma - coupling;
        // A pivot of exactly zero: move it off by a rounding error's size, as LAPACK's dstebz.
        if q == 0.0 {
            q = -f64::EPSILON * scale;
        }
        if q < 0.0 {
            count += 1;
        }
    }
    count
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 3-link pendulum (M = [[3,2,1],[2,2,1],[1,1,1]], K = diag(3,2,1) g/l with g/l = 1):
    /// its λ are the roots of λ³ − 9λ² + 18λ − 6, which the bisection finds to 1e-14, and
    /// which equal nalgebra's QR eigenvalues of M⁻¹K.
    #[test]
    fn the_three_link_pendulum_has_the_roots_of_its_characteristic_cubic() {
        let m = DMatrix::from_row_slice(3, 3, &[3.0, 2.0, 1.0, 2.0, 2.0, 1.0, 1.0, 1.0, 1.0]);
        let k = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![3.0, 2.0, 1.0]));
        let found = symmetric_pencil_eigenvalues(&k, &m).unwrap();
        for l in &found {
            let p = l.powi(3) - 9.0 * l.powi(2) + 18.0 * l - 6.0;
            assert!(p.abs() < 1e-12, "λ = {l}: p(λ) = {p}");
        }
        let mut qr: Vec<f64> = (m.clone().lu().solve(&k).unwrap())
            .complex_eigenvalues()
            .iter()
            .map(|z| z.re)
            .collect();
        qr.sort_by(f64::total_cmp);
        for (a, b) in found.iter().zip(&qr) {
            assert!((a / b - 1.0).abs() < 1e-13, "{a} {b}");
        }
        // Three distinct roots, ascending.
        assert!(found[0] < found[1] && found[1] < found[2], "{found:?}");
    }

    /// A repeated eigenvalue (two equal uncoupled oscillators) is found twice, and a
    /// negative one (an unstable direction) as negative.
    #[test]
    fn repeated_and_negative_eigenvalues() {
        let m = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![2.0, 2.0, 1.0]));
        let k = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![8.0, 8.0, -3.0]));
        let found = symmetric_pencil_eigenvalues(&k, &m).unwrap();
        let want = [-3.0, 4.0, 4.0];
        for (a, b) in found.iter().zip(&want) {
            assert!((a - b).abs() < 1e-14, "{found:?}");
        }
    }

    /// A non-symmetric K and a singular M are refused by name, not answered.
    #[test]
    fn a_non_symmetric_or_singular_pencil_is_refused() {
        let m = DMatrix::identity(2, 2);
        let k = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 0.0, 1.0]);
        assert_eq!(
            symmetric_pencil_eigenvalues(&k, &m),
            Err(PencilError::NotSymmetric {
                matrix: 'K',
                row: 1,
                column: 2
            })
        );
        let singular = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 1.0]);
        assert_eq!(
            symmetric_pencil_eigenvalues(&DMatrix::identity(2, 2), &singular),
            Err(PencilError::NotPositiveDefinite)
        );
    }
}
