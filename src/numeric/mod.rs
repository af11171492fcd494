//! The numeric stage: quadrature of every body with error laws and cost, and the principal axes
//! by `SymmetricEigen`. It evaluates the scene's geometry at its values and never reads a
//! symbolic result except to measure its own error against it.

pub mod body;
pub mod eigen;
pub mod elliptic;
pub mod free_body;
pub mod free_body_plots;
pub mod integrators;
pub mod plots;
pub mod quadrature;

use crate::derive::algebra::Value;
use crate::scene::Scene;
use body::{NumBody, relative_error};
use nalgebra::Matrix3;
use quadrature::{QuadratureRun, reference_rule, run, schedule};
use std::collections::BTreeMap;

/// The numeric results for a scene.
#[derive(Debug, Clone)]
pub struct NumericReport {
    pub runs: Vec<QuadratureRun>,
    /// The whole scene's tensor from each body's exact rule, and its error.
    pub tensor: Matrix3<f64>,
    pub tensor_error: f64,
    pub seconds: f64,
}

/// Evaluates an exact matrix value at the scene's values.
pub fn matrix_at(value: &Value, values: &BTreeMap<String, f64>) -> Result<Matrix3<f64>, String> {
    let env = |s: &str| values.get(s).copied();
    let e = value.entries();
    if e.len() != 9 {
        return Err("not a matrix".into());
    }
    let mut m = Matrix3::zeros();
    for (k, x) in e.iter().enumerate() {
        m[(k / 3, k % 3)] = x.eval(&env)?;
    }
    Ok(m)
}

/// Runs every method of every body, and the composite with each body's exact rule.
pub fn quadrature_checks(
    scene: &Scene,
    exact_parts: &[Value],
    exact_total: &Value,
) -> Result<NumericReport, String> {
    let start = std::time::Instant::now();
    let mut runs = Vec::new();
    let mut total = Matrix3::zeros();
    for (i, body) in scene.bodies.iter().enumerate() {
        let nb = NumBody::from_scene(body, &scene.values)?;
        let exact = matrix_at(&exact_parts[i], &scene.values)?;
        for (method, level) in schedule(&nb.shape) {
            runs.push(run(
                &nb,
                method,
                level,
                &exact,
                scene.seed.wrapping_add((i * 1000 + level) as u64),
            ));
        }
        let (method, level) = reference_rule(&nb.shape);
        total += run(&nb, method, level, &exact, scene.seed).tensor;
    }
    let exact_total = matrix_at(exact_total, &scene.values)?;
    Ok(NumericReport {
        runs,
        tensor_error: relative_error(&total, &exact_total),
        tensor: total,
        seconds: start.elapsed().as_secs_f64(),
    })
}
