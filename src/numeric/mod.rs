//! The numeric stage: quadrature of every body with error laws and cost, and the principal axes
//! by `SymmetricEigen`. It evaluates the scene's geometry at its values and never reads a
//! symbolic result except to measure its own error against it.

pub mod answers;
pub mod body;
pub mod budget;
pub mod compiled;
pub mod eigen;
pub mod elliptic;
pub mod free_body;
pub mod integrators;
pub mod motion;
pub mod ode;
pub mod pareto;
pub mod quadrature;
pub(crate) mod random_points;
pub mod rounding;

use crate::cas::EvalError;
use crate::model::fidelity::Fidelity;
use crate::model::value::Value;
use crate::scene::Scene;
use body::{NumBody, relative_error};
use nalgebra::Matrix3;
use quadrature::{QuadratureRun, climb, reference_rule, run};

/// Numeric work done on this thread so far: proof, in `derive --explain`, that a scene ran only
/// the integrations and quadratures it asked for. Thread-local, so parallel tests do not mix.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Work {
    pub ode_integrations: u64,
    pub rhs_evaluations: u64,
    pub quadrature_runs: u64,
    pub quadrature_points: u64,
}

thread_local! {
    static WORK: std::cell::Cell<Work> = const { std::cell::Cell::new(Work {
        ode_integrations: 0,
        rhs_evaluations: 0,
        quadrature_runs: 0,
        quadrature_points: 0,
    }) };
}

impl Work {
    pub fn so_far() -> Work {
        WORK.with(|w| w.get())
    }

    fn plus(self, other: Work) -> Work {
        Work {
            ode_integrations: self.ode_integrations + other.ode_integrations,
            rhs_evaluations: self.rhs_evaluations + other.rhs_evaluations,
            quadrature_runs: self.quadrature_runs + other.quadrature_runs,
            quadrature_points: self.quadrature_points + other.quadrature_points,
        }
    }

    /// The work done since `before`.
    pub fn since(before: Work) -> Work {
        let now = Work::so_far();
        Work {
            ode_integrations: now.ode_integrations - before.ode_integrations,
            rhs_evaluations: now.rhs_evaluations - before.rhs_evaluations,
            quadrature_runs: now.quadrature_runs - before.quadrature_runs,
            quadrature_points: now.quadrature_points - before.quadrature_points,
        }
    }

    fn add(f: impl FnOnce(&mut Work)) {
        WORK.with(|w| {
            let mut v = w.get();
            f(&mut v);
            w.set(v);
        });
    }

    pub fn count_integration(rhs_evaluations: u64) {
        Work::add(|w| {
            w.ode_integrations += 1;
            w.rhs_evaluations += rhs_evaluations;
        });
    }

    pub fn count_quadrature(points: usize) {
        Work::add(|w| {
            w.quadrature_runs += 1;
            w.quadrature_points += points as u64;
        });
    }

    /// `f` of each item on both cores, in the items' order (`base::in_order`), with the work
    /// done on the other threads counted on this one, as if it had all been done here.
    pub fn map_in_order<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
        let here = std::thread::current().id();
        let made = crate::base::in_order::map_in_order(items, |item| {
            let before = Work::so_far();
            let r = f(item);
            let elsewhere = std::thread::current().id() != here;
            (r, elsewhere.then(|| Work::since(before)))
        });
        made.into_iter()
            .map(|(r, done)| {
                if let Some(d) = done {
                    Work::add(|w| *w = w.plus(d));
                }
                r
            })
            .collect()
    }
}

/// The numeric results for a scene.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct NumericReport {
    pub runs: Vec<QuadratureRun>,
    /// The whole scene's tensor from each body's exact rule, and its error.
    pub tensor: Matrix3<f64>,
    pub tensor_error: f64,
    pub seconds: f64,
}

/// Climbs every method's ladder for every body at the fidelity, and sums each body's exact rule.
pub fn quadrature_checks(
    scene: &Scene,
    exact_parts: &[Value],
    exact_total: &Value,
    fidelity: &Fidelity,
) -> Result<NumericReport, EvalError> {
    let start = std::time::Instant::now();
    let mut runs = Vec::new();
    let mut total = Matrix3::zeros();
    for (i, body) in scene.bodies.iter().enumerate() {
        let nb = NumBody::from_scene(body, &scene.values)?;
        let exact = exact_parts[i].matrix_at(&scene.values)?;
        runs.extend(climb(
            &nb,
            &exact,
            fidelity,
            scene.seed.wrapping_add((i * 1000) as u64),
        ));
        let (method, level) = reference_rule(&nb.shape);
        total += run(&nb, method, level, &exact, scene.seed).tensor;
    }
    let exact_total = exact_total.matrix_at(&scene.values)?;
    Ok(NumericReport {
        runs,
        tensor_error: relative_error(&total, &exact_total),
        tensor: total,
        seconds: start.elapsed().as_secs_f64(),
    })
}
