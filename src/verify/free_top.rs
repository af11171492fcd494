//! The free top whose moments are its body's (`inertia = "principal"`): its precession rate
//! by a route that shares nothing with the family's formula.

use crate::derive::Derivation;
use crate::model::catalogue::quantity;
use crate::scene::Scene;

/// The free top's precession rate with the bodies' own moments, by a route that shares nothing
/// with the family's formula: the quadrature tensor moved to the centre of mass, its eigenvalues
/// (the closest two are I1 = I2), and Euler's equations integrated until ω's transverse part has
/// turned (NaN when the route fails, which then fails the check).
pub(super) fn body_precession_rate(
    scene: &Scene,
    d: &Derivation,
    t: &nalgebra::Matrix3<f64>,
) -> f64 {
    let vals = &scene.values;
    let Ok(about_cm) = d.about_centre_at(t, vals) else {
        return f64::NAN;
    };
    let mut e: Vec<f64> = about_cm.symmetric_eigenvalues().iter().copied().collect();
    e.sort_by(f64::total_cmp);
    // The equal pair: the lower two, or the upper two.
    let (i1, i3) = if (e[1] - e[0]).abs() <= (e[2] - e[1]).abs() {
        ((e[0] + e[1]) / 2.0, e[2])
    } else {
        ((e[1] + e[2]) / 2.0, e[0])
    };
    let mut with_moments = vals.clone();
    with_moments.insert("I1".into(), i1);
    with_moments.insert("I3".into(), i3);
    crate::numeric::answers::Routes::new(scene, &with_moments)
        .answer(quantity::PRECESSION_RATE)
        .map_or(f64::NAN, |r| r[0])
}
