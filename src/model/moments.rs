//! Validated principal moments, the units the free body is integrated in, and the starts that
//! double precision cannot follow.

use nalgebra::Vector3;

/// Validated principal moments.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Moments(pub [f64; 3]);

/// Why three numbers are not a real body's principal moments (axes numbered from 1).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MomentsError {
    #[error("moment I{axis} = {value} is not a finite number")]
    NotFinite { axis: usize, value: f64 },
    #[error("moment I{axis} = {value} must be positive")]
    NotPositive { axis: usize, value: f64 },
    #[error("{}", triangle_message(.moments, .axis))]
    TriangleInequality { moments: [f64; 3], axis: usize },
}

fn triangle_message(i: &[f64; 3], k: &usize) -> String {
    let (k, a, b) = (*k, (k + 1) % 3, (k + 2) % 3);
    format!(
        "moments ({}, {}, {}) break the triangle inequality: I{} = {} > I{} + I{} = {}",
        i[0],
        i[1],
        i[2],
        k + 1,
        i[k],
        a + 1,
        b + 1,
        i[a] + i[b]
    )
}

impl Moments {
    /// Positive, finite, and each at most the sum of the other two (a real body's moments obey
    /// the triangle inequality, since I_a + I_b − I_c = 2∫ρ x_c² dV ≥ 0).
    pub fn new(i: [f64; 3]) -> Result<Moments, MomentsError> {
        for (k, v) in i.iter().enumerate() {
            if !v.is_finite() {
                return Err(MomentsError::NotFinite {
                    axis: k + 1,
                    value: *v,
                });
            }
            if *v <= 0.0 {
                return Err(MomentsError::NotPositive {
                    axis: k + 1,
                    value: *v,
                });
            }
        }
        for k in 0..3 {
            let (a, b) = (i[(k + 1) % 3], i[(k + 2) % 3]);
            // A relative slack of a few ε lets a thin rod or a lamina (equality) through.
            if i[k] > (a + b) * (1.0 + 4.0 * f64::EPSILON) {
                return Err(MomentsError::TriangleInequality {
                    moments: i,
                    axis: k,
                });
            }
        }
        Ok(Moments(i))
    }
}

/// Every ordering of the axes, as (smallest, middle, largest).
pub const ORDERINGS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
];

/// The nearest power of two: scaling by it is exact, so nondimensionalizing loses no bits.
fn power_of_two_near(x: f64) -> f64 {
    if x.is_finite() && x > 0.0 {
        2f64.powi(x.log2().round() as i32)
    } else {
        1.0
    }
}

/// Units that keep every intermediate (I ω², I ω, ...) far from overflow and underflow: the
/// free body is unchanged by I → I/c, and ω → ω/s with t → t·s maps solutions onto solutions.
/// Returns the scaled moments, the scaled ω(0) and s. Powers of two, so nothing is rounded.
pub fn units(i: &Moments, w0: &Vector3<f64>) -> (Moments, Vector3<f64>, f64) {
    let c = power_of_two_near(i.0.iter().copied().fold(0.0, f64::max));
    let s = power_of_two_near(w0.amax());
    (Moments(i.0.map(|x| x / c)), w0 / s, s)
}

/// Why the exact solution cannot be trusted for this start, when it cannot: ω(0) so close to
/// the intermediate axis that the squares of its other components underflow, so that 1 − m
/// (the distance from the separatrix) is lost and the motion would be taken for the separatrix
/// itself. In double precision that happens below about 1.5e-154 of |ω|.
pub fn beyond_double_precision(i: &Moments, w0: &Vector3<f64>) -> Option<NearSeparatrix> {
    let (i, w, _) = units(i, w0);
    let mut order = [0usize, 1, 2];
    order.sort_by(|a, b| i.0[*a].total_cmp(&i.0[*b]));
    let [i1, i2, i3] = order.map(|k| i.0[k]);
    if i1 == i2 || i2 == i3 {
        return None;
    }
    let [w1, w2, w3] = order.map(|k| w[k]);
    let t1 = i1 * (i2 - i1) * w1 * w1;
    let t3 = i3 * (i3 - i2) * w3 * w3;
    (w2 != 0.0 && (w1 != 0.0 || w3 != 0.0) && t1 < f64::MIN_POSITIVE && t3 < f64::MIN_POSITIVE)
        .then_some(NearSeparatrix {
            omega: [w0.x, w0.y, w0.z],
        })
}

/// A start within 1.5e-154 of the intermediate axis (see [`beyond_double_precision`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "ω(0) = ({:e}, {:e}, {:e}) lies within 1.5e-154 of the intermediate axis: the squares of its \
     small components underflow, so its distance from the separatrix (1 − m) is beyond double \
     precision and the exact solution cannot follow it; give those components as 0 (the \
     separatrix) or larger",
    .omega[0], .omega[1], .omega[2]
)]
pub struct NearSeparatrix {
    pub omega: [f64; 3],
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_moments_are_rejected_with_a_reason() {
        assert!(
            Moments::new([0.0, 1.0, 1.0])
                .unwrap_err()
                .to_string()
                .contains("positive")
        );
        assert!(
            Moments::new([f64::NAN, 1.0, 1.0])
                .unwrap_err()
                .to_string()
                .contains("finite")
        );
        assert!(
            Moments::new([1.0, 1.0, 3.0])
                .unwrap_err()
                .to_string()
                .contains("triangle")
        );
        assert!(Moments::new([1.0, 1.0, 2.0]).is_ok(), "a lamina is a body");
    }

    #[test]
    fn the_triangle_message_names_the_axis_and_the_sum() {
        let e = Moments::new([1.0, 4.0, 2.0]).unwrap_err();
        assert_eq!(
            e,
            MomentsError::TriangleInequality {
                moments: [1.0, 4.0, 2.0],
                axis: 1
            }
        );
        assert_eq!(
            e.to_string(),
            "moments (1, 4, 2) break the triangle inequality: I2 = 4 > I3 + I1 = 3"
        );
    }
}
