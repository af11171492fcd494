//! The author's own derivation: each `[[step]]` names the exact result of one operation
//! (`be`, `differentiate`, `lagrange`) on the scene's names and the steps before it. The
//! numeric check of each step is in `verify/steps.rs`.
//!
//! A coordinate q is a function of the time t; its rates are the names `q'` and `q''`, so an
//! expression in them is an ordinary expression and the time derivative is the chain rule
//! d/dt f = ∂f/∂t + Σ_q (∂f/∂q · q' + ∂f/∂q' · q'').

use super::algebra::{Env, Value, evaluate};
use super::{Derivation, DeriveError, Step};
use crate::cas::{self, Expr, Formula};
use crate::model::prose::Prose;
use crate::scene::{AuthorStep, Operation, Scene};
use std::collections::BTreeMap;

/// What a step found: an expression, or equations of motion (each coordinate's residual, which
/// the motion keeps at zero).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum StepResult {
    Expr(Expr),
    Equations(Vec<(String, Expr)>),
}

/// Why a step could not be derived, at its line.
#[derive(Debug, thiserror::Error)]
pub enum StepError {
    #[error("step `{step}`: its result is {kind}; a step's result is a scalar")]
    NotScalar {
        step: String,
        line: usize,
        kind: &'static str,
    },
    #[error("step `{step}`: {message}")]
    Operation {
        step: String,
        line: usize,
        message: String,
    },
}

impl StepError {
    /// The line of the step at fault.
    pub fn line(&self) -> usize {
        match self {
            StepError::NotScalar { line, .. } | StepError::Operation { line, .. } => *line,
        }
    }
}

/// The names a step's expressions may use: the scene's definitions and vectors, the derived
/// quantities, and the results of the steps before it.
fn env(scene: &Scene, d: &Derivation) -> Env {
    let mut env = Env::new();
    for (name, e) in &scene.definitions {
        env.insert(name.clone(), Value::Scalar(e.clone()));
    }
    for (name, v) in &scene.vectors {
        env.insert(name.clone(), Value::Vector(v.clone()));
    }
    for (name, v) in &d.quantities {
        env.insert(name.clone(), v.clone());
    }
    for (name, r) in &d.named {
        if let StepResult::Expr(e) = r {
            env.insert(name.clone(), Value::Scalar(e.clone()));
        }
    }
    env
}

/// An expression with every name bound in the environment replaced by its value, unsimplified:
/// the form the numeric checks evaluate, independent of the engine.
pub fn expand_names(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    e: &Expr,
) -> Result<Expr, StepError> {
    match evaluate(e, &env(scene, d)) {
        Ok(Value::Scalar(x)) => Ok(x),
        Ok(other) => Err(StepError::NotScalar {
            step: step.name.clone(),
            line: step.line,
            kind: other.kind(),
        }),
        Err(e) => Err(StepError::Operation {
            step: step.name.clone(),
            line: step.line,
            message: e.to_string(),
        }),
    }
}

/// d/dt of `f` through the coordinates: ∂f/∂t + Σ_q (∂f/∂q · q' + ∂f/∂q' · q''). A second
/// rate in `f` would need a third, which the language does not have.
pub fn time_derivative(
    f: &Expr,
    coordinates: &BTreeMap<String, String>,
) -> Result<Expr, DeriveError> {
    let mut terms = vec![f.diff("t")?];
    for q in coordinates.keys() {
        let (rate, accel) = (format!("{q}'"), format!("{q}''"));
        if f.symbols().contains(&accel) {
            return Err(DeriveError::NotDerivable(format!(
                "the time derivative of an expression in `{accel}` needs a third derivative"
            )));
        }
        terms.push(Expr::mul(vec![f.diff(q)?, Expr::sym(&rate)]));
        terms.push(Expr::mul(vec![f.diff(&rate)?, Expr::sym(&accel)]));
    }
    Ok(Expr::add(terms))
}

/// The Euler–Lagrange residual of each coordinate: d/dt(∂L/∂q') − ∂L/∂q, unsimplified.
pub fn euler_lagrange(
    lagrangian: &Expr,
    coordinates: &BTreeMap<String, String>,
) -> Result<Vec<(String, Expr)>, DeriveError> {
    coordinates
        .keys()
        .map(|q| {
            let momentum = lagrangian.diff(&format!("{q}'"))?;
            let rate = time_derivative(&momentum, coordinates)?;
            Ok((q.clone(), Expr::minus(rate, lagrangian.diff(q)?)))
        })
        .collect()
}

/// The equations a validated earlier step holds.
fn equations<'a>(d: &'a Derivation, of: &str) -> Result<&'a [(String, Expr)], DeriveError> {
    match d.named.get(of) {
        Some(StepResult::Equations(eqs)) => Ok(eqs),
        _ => Err(DeriveError::Inconsistent(format!(
            "step `{of}` was validated as earlier equations of motion"
        ))),
    }
}

/// Each coordinate's value at the state of rest `about` (0 where not named); rates are 0.
fn rest_value(
    q: &str,
    about: &BTreeMap<String, Expr>,
    coordinates: &BTreeMap<String, String>,
) -> Option<Expr> {
    if coordinates.contains_key(q) {
        return Some(about.get(q).cloned().unwrap_or_else(|| Expr::int(0)));
    }
    let base = q.trim_end_matches('\'');
    (base != q && coordinates.contains_key(base)).then(|| Expr::int(0))
}

/// Each equation to first order about the state of rest: R(rest) (which must vanish) and
/// Σ_q ∂R/∂q·(q − q₀) + ∂R/∂q'·q' + ∂R/∂q''·q'', the derivatives taken at rest. Unsimplified.
#[allow(clippy::type_complexity)]
pub fn linearise(
    eqs: &[(String, Expr)],
    about: &BTreeMap<String, Expr>,
    coordinates: &BTreeMap<String, String>,
) -> Result<(Vec<Expr>, Vec<(String, Expr)>), DeriveError> {
    let at_rest = |e: &Expr| e.substitute(&|s| rest_value(s, about, coordinates));
    let mut rest = Vec::new();
    let mut linear = Vec::new();
    for (q, r) in eqs {
        rest.push(at_rest(r));
        let mut terms = Vec::new();
        for c in coordinates.keys() {
            let q0 = about.get(c).cloned().unwrap_or_else(|| Expr::int(0));
            terms.push(Expr::mul(vec![
                at_rest(&r.diff(c)?),
                Expr::minus(Expr::sym(c), q0),
            ]));
            for rate in [format!("{c}'"), format!("{c}''")] {
                terms.push(Expr::mul(vec![at_rest(&r.diff(&rate)?), Expr::sym(&rate)]));
            }
        }
        linear.push((q.clone(), Expr::add(terms)));
    }
    Ok((rest, linear))
}

/// The angular frequency Ω = √(k/m) of one linear equation m q'' + k (q − q₀) = 0.
fn frequency(eqs: &[(String, Expr)]) -> Result<Expr, DeriveError> {
    let [(q, r)] = eqs else {
        return Err(DeriveError::NotDerivable(format!(
            "`frequency` of {} coordinates (normal modes) is not supported yet: one coordinate",
            eqs.len()
        )));
    };
    let m = cas::simplify(&r.diff(&format!("{q}''"))?)?;
    let c = cas::simplify(&r.diff(&format!("{q}'"))?)?;
    let k = cas::simplify(&r.diff(q)?)?;
    if !c.is_zero() {
        return Err(DeriveError::NotDerivable(format!(
            "the equation has a term in `{q}'` ({}): a damped or driven motion has no single \
             frequency",
            c.to_text()
        )));
    }
    if m.is_zero() {
        return Err(DeriveError::NotDerivable(format!(
            "the equation has no term in `{q}''`: it is not an equation of motion"
        )));
    }
    let omega = Expr::pow(Expr::over(k, m), Expr::rat(1, 2));
    Ok(cas::simplify(&omega)?)
}

/// Derives every step in order, each simplified by the engine, and writes its page steps.
pub fn derive_steps(scene: &Scene, d: &mut Derivation) -> Result<(), DeriveError> {
    for step in &scene.steps {
        let located = |e: DeriveError| -> DeriveError {
            DeriveError::Step(StepError::Operation {
                step: step.name.clone(),
                line: step.line,
                message: e.to_string(),
            })
        };
        let result = match &step.op {
            Operation::Be(e) => {
                let x = expand_names(scene, d, step, e).map_err(DeriveError::Step)?;
                StepResult::Expr(cas::simplify(&x)?)
            }
            Operation::Differentiate { of, by } => {
                let f = expand_names(scene, d, step, of).map_err(DeriveError::Step)?;
                let raw = if by == "t" {
                    time_derivative(&f, &scene.coordinates).map_err(located)?
                } else {
                    f.diff(by).map_err(|e| located(e.into()))?
                };
                StepResult::Expr(cas::simplify(&raw)?)
            }
            Operation::Lagrange { of } => {
                let Some(StepResult::Expr(l)) = d.named.get(of) else {
                    return Err(DeriveError::Inconsistent(format!(
                        "step `{of}` was validated as an earlier scalar step"
                    )));
                };
                let residuals = euler_lagrange(l, &scene.coordinates).map_err(located)?;
                let exprs: Vec<Expr> = residuals.iter().map(|(_, e)| e.clone()).collect();
                let simplified = cas::simplify_all(exprs)?;
                StepResult::Equations(
                    residuals
                        .into_iter()
                        .zip(simplified)
                        .map(|((q, _), e)| (q, e))
                        .collect(),
                )
            }
            Operation::Linearise { of, about } => {
                let eqs = equations(d, of)?;
                let (rest, linear) = linearise(eqs, about, &scene.coordinates).map_err(located)?;
                // A state of rest leaves nothing over: else it is not an equilibrium.
                let left = cas::simplify_all(rest)?;
                if let Some((k, r)) = left.iter().enumerate().find(|(_, r)| !r.is_zero()) {
                    return Err(located(DeriveError::NotDerivable(format!(
                        "the state given by `about` is not at rest: the equation of `{}` leaves \
                         {} there, not 0; give an equilibrium",
                        eqs[k].0,
                        r.to_text()
                    ))));
                }
                let simplified =
                    cas::simplify_all(linear.iter().map(|(_, e)| e.clone()).collect())?;
                StepResult::Equations(
                    linear
                        .into_iter()
                        .zip(simplified)
                        .map(|((q, _), e)| (q, e))
                        .collect(),
                )
            }
            Operation::Frequency { of } => {
                let eqs = equations(d, of)?;
                StepResult::Expr(frequency(eqs).map_err(located)?)
            }
        };
        d.steps.extend(page_steps(step, &result));
        d.named.insert(step.name.clone(), result);
    }
    Ok(())
}

/// A step as the page shows it: `name = result`, or each equation of motion `… = 0`.
fn page_steps(step: &AuthorStep, result: &StepResult) -> Vec<Step> {
    let mut steps = page_statements(step, result);
    for s in &mut steps {
        s.author = Some(step.name.clone());
    }
    steps
}

fn page_statements(step: &AuthorStep, result: &StepResult) -> Vec<Step> {
    let why = Prose::default().text(&step.why);
    let title = match &step.eq {
        Some(eq) => format!("{} (eq {eq})", step.name),
        None => step.name.clone(),
    };
    match result {
        StepResult::Expr(e) => vec![Step::note(
            &title,
            Formula::equation(Formula::Expr(Expr::sym(&step.name)), e.clone()),
            why,
        )],
        StepResult::Equations(eqs) => eqs
            .iter()
            .map(|(q, e)| {
                Step::note(
                    &format!("{title}: the equation of motion of {q}"),
                    Formula::Row(vec![
                        Formula::Expr(e.clone()),
                        Formula::Op(crate::cas::Op::Equals),
                        Formula::Number("0".into()),
                    ]),
                    why.clone(),
                )
            })
            .collect(),
    }
}
