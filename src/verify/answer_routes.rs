//! An expression answer at one variant's numbers, by routes that do not go through the
//! engine: each derived quantity it uses by its own numeric route (quadrature, the
//! eigen-solver, Euler's equations integrated), each step's result by the step's own numeric
//! value (`be`: its expression as written; `frequency`: the period of the integrated motion;
//! `solve`: Newton's method on the equation), and the symbols by the variant's values.

use crate::cas::Expr;
use crate::derive::Derivation;
use crate::derive::step_names::{equation_with, expand_names, expand_ranges};
use crate::derive::variants::{placeholder_of, resolve_expr};
use crate::numeric::answers::{RouteError, Routes};
use crate::scene::operations::{Be, Frequency, Integrate, Linearise, Solve};
use crate::scene::{Operation, Scene, step_named};
use crate::steps::check::CheckError;
use crate::steps::check::{equations_of, solvable_of};
use crate::steps::integrate::{QUADRATURE_AGREEMENT, quadrature};
use crate::steps::motion::{MODES_AGREEMENT, PERIOD_AGREEMENT, measured_period, numeric_modes};
use std::collections::BTreeMap;

/// How closely Newton's method must put a root back: it converges quadratically to rounding,
/// so only the conditioning of the equation is left.
const NEWTON_AGREEMENT: f64 = 1e-9;
/// Newton's method starts this far (relatively) from the derived root, so that a wrong root is
/// not found where it was put.
const NEWTON_OFFSET: f64 = 0.1;
const NEWTON_ITERATIONS: usize = 60;

/// A number from a numeric route with the relative error that route allows.
#[derive(Debug, Clone, Copy)]
pub struct Routed {
    pub value: f64,
    pub tolerance: f64,
}

#[derive(Debug, thiserror::Error)]
pub enum AnswerRouteError {
    #[error(transparent)]
    Route(#[from] RouteError),
    #[error(transparent)]
    Check(#[from] CheckError),
    #[error("the step `{0}` has no numeric value of its own at a variant's values")]
    NoStepRoute(String),
    #[error("Newton's method on the equation of `{step}` did not converge from {start}")]
    Newton { step: String, start: f64 },
    #[error("{0}")]
    Shape(String),
}

/// An expression answer's routes at one variant: the variant's numbers (symbol -> f64).
pub struct AnswerRoutes<'a> {
    scene: &'a Scene,
    d: &'a Derivation,
    numbers: &'a BTreeMap<String, f64>,
    pub routes: Routes<'a>,
    /// Each step's value, once per variant.
    steps: BTreeMap<String, Routed>,
    /// The quantities' relative agreement with the exact route, by name.
    agreement: &'a dyn Fn(&str) -> f64,
}

impl<'a> AnswerRoutes<'a> {
    pub fn new(
        scene: &'a Scene,
        d: &'a Derivation,
        numbers: &'a BTreeMap<String, f64>,
        agreement: &'a dyn Fn(&str) -> f64,
    ) -> AnswerRoutes<'a> {
        AnswerRoutes {
            scene,
            d,
            numbers,
            routes: Routes::new(scene, numbers),
            steps: BTreeMap::new(),
            agreement,
        }
    }

    /// A scalar expression of the claim language, with the error its leaves' routes allow,
    /// carried to the result to first order (each leaf moved by its own tolerance in turn).
    pub fn expression(&mut self, e: &Expr) -> Result<Routed, AnswerRouteError> {
        let resolved =
            resolve_expr(self.scene, e).map_err(|e| AnswerRouteError::Shape(e.to_string()))?;
        let crate::model::value::Value::Scalar(resolved) = resolved else {
            return Err(AnswerRouteError::Shape(format!(
                "`{}` is not one number",
                e.to_text()
            )));
        };
        let mut leaves: BTreeMap<String, Routed> = BTreeMap::new();
        for name in resolved.symbols() {
            if name == "pi" {
                continue;
            }
            let leaf = self.leaf(&name)?;
            leaves.insert(name, leaf);
        }
        let at = |moved: Option<(&str, f64)>| -> Result<f64, AnswerRouteError> {
            Ok(resolved
                .eval(&|s| {
                    let r = leaves.get(s)?;
                    Some(match moved {
                        Some((m, factor)) if m == s => r.value * factor,
                        _ => r.value,
                    })
                })
                .map_err(CheckError::from)?)
        };
        let value = at(None)?;
        // Rounding, amplified where the expression cancels (2π/(ω₂ − ω₁) of a weak spring).
        let rounding = crate::numeric::rounding::relative_rounding(&resolved, &|s| {
            leaves.get(s).map(|r| r.value)
        })
        .map_or(0.0, |(_, bound)| bound * f64::EPSILON);
        let mut tolerance = rounding;
        for (name, r) in &leaves {
            if r.tolerance > 0.0 {
                let moved = at(Some((name, 1.0 + r.tolerance)))?;
                tolerance += (moved - value).abs() / value.abs().max(f64::MIN_POSITIVE);
            }
        }
        Ok(Routed { value, tolerance })
    }

    /// One name of a resolved answer: a quantity's entry, a step's result or a symbol.
    fn leaf(&mut self, name: &str) -> Result<Routed, AnswerRouteError> {
        if let Some((q, k)) = placeholder_of(name) {
            let entries = self.routes.answer(q)?;
            let value = *entries
                .get(k)
                .ok_or_else(|| AnswerRouteError::Shape(format!("`{q}` has no entry {k}")))?;
            return Ok(Routed {
                value,
                tolerance: (self.agreement)(q),
            });
        }
        if let Some(&value) = self.numbers.get(name) {
            return Ok(Routed {
                value,
                tolerance: 0.0,
            });
        }
        if let Some(r) = self.steps.get(name) {
            return Ok(*r);
        }
        let r = self.step(name)?;
        self.steps.insert(name.to_string(), r);
        Ok(r)
    }

    /// A step's result (its own name, or `x_k` of one with several) by the step's own route.
    fn step(&mut self, name: &str) -> Result<Routed, AnswerRouteError> {
        let scene = self.scene;
        let step = step_named(&scene.steps, scene.coordinates.len(), name)
            .ok_or_else(|| AnswerRouteError::NoStepRoute(name.to_string()))?;
        match &step.op {
            Operation::Be(Be(e)) => self.expression(e),
            // A mode of n ≥ 2 coordinates (`Omega_2`): the √λ of M⁻¹K at the variant's numbers
            // of the same rank among the modes as this one among the step's exact modes there
            // (their names keep an order that need not be slowest first at every variant);
            // a mode with no closed form is the k-th slowest.
            Operation::Frequency(Frequency { of }) if name != step.name => {
                let modes = numeric_modes(equations_of(self.d, of)?, self.numbers)?;
                let k = (0..modes.len())
                    .position(|k| step.result_names().kth(k) == name)
                    .ok_or_else(|| AnswerRouteError::NoStepRoute(name.to_string()))?;
                let rank = self.mode_rank(&step.name, k)?;
                let value = *modes
                    .get(rank)
                    .ok_or_else(|| AnswerRouteError::NoStepRoute(name.to_string()))?;
                Ok(Routed {
                    value,
                    tolerance: MODES_AGREEMENT,
                })
            }
            Operation::Frequency(Frequency { of }) => {
                let Some(Operation::Linearise(Linearise { of: motion, about })) =
                    scene.steps.iter().find(|s| &s.name == of).map(|s| &s.op)
                else {
                    return Err(AnswerRouteError::NoStepRoute(name.to_string()));
                };
                let derived = self.derived(name)?;
                let full = equations_of(self.d, motion)?;
                let period = 2.0 * std::f64::consts::PI / derived;
                let (measured, _) = measured_period(full, about, self.numbers, period)?;
                Ok(Routed {
                    value: 2.0 * std::f64::consts::PI / measured,
                    tolerance: PERIOD_AGREEMENT,
                })
            }
            Operation::Solve(Solve { of, unknowns }) if unknowns.len() == 1 => {
                let unknown = &unknowns[0];
                let equations = solvable_of(self.d, of)?;
                let (_, residual) = equation_with(&equations, unknown).map_err(CheckError::from)?;
                let derived = self.derived(name)?;
                let value = newton(residual, unknown, self.numbers, derived).ok_or_else(|| {
                    AnswerRouteError::Newton {
                        step: name.to_string(),
                        start: derived,
                    }
                })?;
                Ok(Routed {
                    value,
                    tolerance: NEWTON_AGREEMENT,
                })
            }
            Operation::Integrate(Integrate { of, over }) => {
                let f = expand_names(scene, self.d, step, of).map_err(CheckError::from)?;
                let over = expand_ranges(scene, self.d, step, over).map_err(CheckError::from)?;
                let (value, _) = quadrature(self.numbers, &f, &over)?;
                Ok(Routed {
                    value,
                    tolerance: QUADRATURE_AGREEMENT,
                })
            }
            _ => Err(AnswerRouteError::NoStepRoute(name.to_string())),
        }
    }

    /// The rank, slowest first at the variant's numbers, of the `k`-th exact mode of the step
    /// `step`; a mode with no closed form keeps its own `k`.
    fn mode_rank(&self, step: &str, k: usize) -> Result<usize, AnswerRouteError> {
        let Some(crate::derive::step_names::StepResult::Modes(exact)) = self.d.named.get(step)
        else {
            return Ok(k);
        };
        let at = |e: &Expr| {
            e.eval(&|s| self.numbers.get(s).copied())
                .map_err(CheckError::from)
        };
        let own = at(&exact[k])?;
        let mut below = 0;
        for e in exact {
            below += usize::from(at(e)? < own);
        }
        Ok(below)
    }

    /// The derived value of a step's result at the variant's numbers: where Newton's method
    /// starts from, and how long a motion is integrated for.
    fn derived(&self, name: &str) -> Result<f64, AnswerRouteError> {
        let values = self
            .d
            .named
            .iter()
            .flat_map(|(n, r)| r.values(self.scene.result_names(n)))
            .find(|(n, _)| n == name)
            .map(|(_, e)| e)
            .ok_or_else(|| AnswerRouteError::NoStepRoute(name.to_string()))?;
        Ok(values
            .eval(&|s| self.numbers.get(s).copied())
            .map_err(CheckError::from)?)
    }
}

/// A root of `residual` in `unknown` by Newton's method with central-difference slopes,
/// started [`NEWTON_OFFSET`] away from `near`.
fn newton(
    residual: &Expr,
    unknown: &str,
    numbers: &BTreeMap<String, f64>,
    near: f64,
) -> Option<f64> {
    let f = |x: f64| {
        residual
            .eval(&|s| {
                if s == unknown {
                    Some(x)
                } else {
                    numbers.get(s).copied()
                }
            })
            .ok()
    };
    let mut x = if near == 0.0 {
        NEWTON_OFFSET
    } else {
        near * (1.0 + NEWTON_OFFSET)
    };
    for _ in 0..NEWTON_ITERATIONS {
        let h = 1e-6 * x.abs().max(1e-3);
        let slope = (f(x + h)? - f(x - h)?) / (2.0 * h);
        if slope == 0.0 || !slope.is_finite() {
            return None;
        }
        let step = f(x)? / slope;
        x -= step;
        if step.abs() <= 4.0 * f64::EPSILON * x.abs().max(f64::MIN_POSITIVE) {
            return Some(x);
        }
    }
    // Quadratic convergence stalls at rounding: accept a last step at that level.
    (f(x)?.abs() <= 1e-12 * x.abs().max(1.0)).then_some(x)
}
