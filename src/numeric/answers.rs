//! A problem's answers at one variant's numbers, by routes that share nothing with the
//! derivation: the bodies' tensor by their exact quadrature rules, the principal moments by
//! `SymmetricEigen`, and the symmetric top's precession rate by integrating Euler's equations
//! for ω.

use super::body::NumBody;
use super::free_body::euler_rhs;
use super::integrators::MAX_STEPS;
use super::ode::{OdeError, dormand_prince};
use super::quadrature::{centre_of_mass, reference_rule, run};
use crate::cas::EvalError;
use crate::model::catalogue::quantity;
use crate::model::moments::{Moments, MomentsError};
use crate::model::value::{Values, vector_at};
use crate::scene::Scene;
use nalgebra::{Matrix3, Vector3};

/// The Dormand–Prince tolerance of the precession route.
pub const PRECESSION_TOLERANCE: f64 = 1e-14;

#[derive(Debug, thiserror::Error)]
pub enum RouteError {
    #[error(transparent)]
    Eval(#[from] EvalError),
    #[error(transparent)]
    Moments(#[from] MomentsError),
    #[error(transparent)]
    Integration(#[from] OdeError),
    #[error("`{0}` has no numeric route")]
    NoRoute(String),
}

/// The numeric routes at one variant's values; the tensor is computed once.
pub struct Routes<'a> {
    scene: &'a Scene,
    values: &'a Values,
    tensor: Option<Matrix3<f64>>,
}

impl<'a> Routes<'a> {
    pub fn new(scene: &'a Scene, values: &'a Values) -> Routes<'a> {
        Routes {
            scene,
            values,
            tensor: None,
        }
    }

    /// The answer's entries in row-major order (principal moments ascending).
    pub fn answer(&mut self, name: &str) -> Result<Vec<f64>, RouteError> {
        let vec_at = |v: &Option<[crate::cas::Expr; 3]>| -> Result<Vector3<f64>, RouteError> {
            let v = v.as_ref().ok_or_else(|| RouteError::NoRoute(name.into()))?;
            Ok(vector_at(v, self.values)?)
        };
        Ok(match name {
            quantity::INERTIA_TENSOR => self.tensor()?.transpose().iter().copied().collect(),
            quantity::PRINCIPAL_MOMENTS => {
                let mut m: Vec<f64> = self
                    .tensor()?
                    .symmetric_eigenvalues()
                    .iter()
                    .copied()
                    .collect();
                m.sort_by(f64::total_cmp);
                m
            }
            quantity::ANGULAR_MOMENTUM => {
                let w = vec_at(&self.scene.omega)?;
                (self.tensor()? * w).iter().copied().collect()
            }
            quantity::KINETIC_ENERGY => {
                let w = vec_at(&self.scene.omega)?;
                vec![0.5 * w.dot(&(self.tensor()? * w))]
            }
            quantity::MOMENT_ABOUT_AXIS => {
                let n = vec_at(&self.scene.axis)?;
                vec![n.dot(&(self.tensor()? * n))]
            }
            quantity::RADIUS_OF_GYRATION => {
                let n = vec_at(&self.scene.axis)?;
                let t = self.tensor()?;
                vec![(n.dot(&(t * n)) / self.mass()?).sqrt()]
            }
            quantity::PRECESSION_RATE => vec![self.precession_rate()?],
            quantity::MASS => vec![self.mass()?],
            quantity::CENTRE_OF_MASS => self.centre_of_mass()?.iter().copied().collect(),
            other => return Err(RouteError::NoRoute(other.into())),
        })
    }

    /// Each body by its exact rule (Gauss–Legendre, the periodic trapezoid, a direct sum).
    fn tensor(&mut self) -> Result<Matrix3<f64>, RouteError> {
        if let Some(t) = self.tensor {
            return Ok(t);
        }
        let mut total = Matrix3::zeros();
        for body in &self.scene.bodies {
            let nb = NumBody::from_scene(body, self.values)?;
            let (method, level) = reference_rule(&nb.shape);
            // `run` measures its error against a given tensor; this route wants the tensor only.
            total += run(&nb, method, level, &Matrix3::identity(), self.scene.seed).tensor;
        }
        self.tensor = Some(total);
        Ok(total)
    }

    /// Σ m_i c_i / Σ m_i over the bodies, each centre by its body's reference rule.
    fn centre_of_mass(&self) -> Result<Vector3<f64>, RouteError> {
        let (mut moment, mut mass) = (Vector3::zeros(), 0.0);
        for body in &self.scene.bodies {
            let nb = NumBody::from_scene(body, self.values)?;
            moment += nb.mass * centre_of_mass(&nb, self.scene.seed);
            mass += nb.mass;
        }
        Ok(moment / mass)
    }

    fn mass(&self) -> Result<f64, RouteError> {
        let mut m = 0.0;
        for body in &self.scene.bodies {
            m += NumBody::from_scene(body, self.values)?.mass;
        }
        Ok(m)
    }

    /// The rate at which (ω1, ω2) turns about the symmetry axis, measured on an integration of
    /// Euler's equations for ω alone: first over 1/|ω3|, then over a quarter turn at the rate
    /// found. The attitude is left out: it turns at ω3, and following it would cost about
    /// I1/|I3 − I1| steps a turn, ten million for a top within 10⁻⁷ of symmetric.
    fn precession_rate(&self) -> Result<f64, RouteError> {
        let value = |s: &str| {
            self.values
                .get(s)
                .copied()
                .ok_or_else(|| RouteError::Eval(EvalError::NoValue(s.into())))
        };
        let (i1, i3, w3) = (value("I1")?, value("I3")?, value("w3")?);
        let moments = Moments::new([i1, i1, i3])?;
        if w3 == 0.0 {
            return Ok(0.0);
        }
        // The transverse amplitude does not change the rate: a tenth of the spin. In units
        // where the largest moment and |ω(0)| are near 1 (powers of two, so exact).
        let (moments, w0, rate_unit) =
            crate::model::moments::units(&moments, &Vector3::new(0.1 * w3.abs(), 0.0, w3));
        let turned = |t: f64| -> Result<f64, RouteError> {
            let f = |_t: f64, w: &[f64]| {
                let d = euler_rhs(&moments, &Vector3::new(w[0], w[1], w[2]));
                Ok::<_, std::convert::Infallible>(vec![d.x, d.y, d.z])
            };
            let run = dormand_prince(&f, w0.as_slice(), t, PRECESSION_TOLERANCE, MAX_STEPS)?;
            let (_, w) = run.states.last().expect("a run keeps its start");
            super::Work::count_integration(run.evaluations);
            Ok(w[1].atan2(w[0]))
        };
        // Over 1/|ω3| the pair turns by (I3 − I1)/I1 radians, at most 1 in size (I3 ≤ 2 I1).
        let t1 = 1.0 / w0.z.abs();
        let rate = turned(t1)? / t1;
        if rate == 0.0 {
            return Ok(0.0);
        }
        let t2 = std::f64::consts::FRAC_PI_2 / rate.abs();
        Ok(turned(t2)? / t2 * rate_unit)
    }
}
