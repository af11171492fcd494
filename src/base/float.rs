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
