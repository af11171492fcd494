//! `inertia = "principal"` for Euler's equations, the axes' stability and Poinsot's construction:
//! their results with the body's own moments, by routes that use only numbers: the quadrature's
//! tensor moved to the centre of mass, and Euler's equations as matrix arithmetic on it.

use crate::derive::Derivation;
use crate::model::catalogue::quantity;
use crate::scene::Scene;
use nalgebra::{Matrix3, Vector3};

/// ω̇ = −I⁻¹(ω × Iω), and its Jacobian in ω: J v = −I⁻¹(v × Iω + ω × Iv).
struct FreeBody {
    inertia: Matrix3<f64>,
    inverse: Matrix3<f64>,
}

impl FreeBody {
    fn rates(&self, w: &Vector3<f64>) -> Vector3<f64> {
        -self.inverse * w.cross(&(self.inertia * w))
    }
    fn jacobian(&self, w: &Vector3<f64>) -> Matrix3<f64> {
        let column = |v: Vector3<f64>| {
            -self.inverse * (v.cross(&(self.inertia * w)) + w.cross(&(self.inertia * v)))
        };
        Matrix3::from_columns(&[
            column(Vector3::x()),
            column(Vector3::y()),
            column(Vector3::z()),
        ])
    }
}

/// The numeric values of the results the scene derived, at its values: the torque-free rates,
/// 2T and L² at ω = (w1, w2, w3); Ω_k² = −J_ab J_ba of the Jacobian at ω = w_k e_k, and the
/// growth rate² −Ω₂². Empty when the route cannot run (no ω, a singular tensor).
pub(super) fn body_family_values(
    scene: &Scene,
    d: &Derivation,
    t: &Matrix3<f64>,
) -> Vec<(&'static str, Vec<f64>)> {
    let vals = &scene.values;
    let (Ok(inertia), Some(w)) = (
        d.about_centre_at(t, vals),
        ["w1", "w2", "w3"]
            .iter()
            .map(|n| vals.get(*n).copied())
            .collect::<Option<Vec<f64>>>(),
    ) else {
        return Vec::new();
    };
    let Some(inverse) = inertia.try_inverse() else {
        return Vec::new();
    };
    let body = FreeBody { inertia, inverse };
    let w = Vector3::from_column_slice(&w);
    let l = inertia * w;
    let omega_squared: Vec<f64> = (0..3)
        .map(|k| {
            let (a, b) = ((k + 1) % 3, (k + 2) % 3);
            let j = body.jacobian(&(Vector3::ith(k, 1.0) * w[k]));
            -j[(a, b)] * j[(b, a)]
        })
        .collect();
    let mut out = vec![
        (
            quantity::TORQUE_FREE_RATES,
            body.rates(&w).iter().copied().collect(),
        ),
        (quantity::TWICE_ENERGY, vec![w.dot(&l)]),
        (quantity::MOMENTUM_SQUARED, vec![l.norm_squared()]),
        (quantity::GROWTH_RATE_SQUARED, vec![-omega_squared[1]]),
    ];
    out.push((quantity::OSCILLATION_FREQUENCY_SQUARED, omega_squared));
    out.retain(|(name, _)| d.quantities.contains_key(*name));
    out
}
