//! The names an author's step works in: the scene's definitions and vectors, the derived
//! quantities and the results of the steps before it, put into a step's expressions unsimplified
//! (the form the numeric checks evaluate), and the errors of a step at its line. Each
//! operation's exact rule and numeric check are in `src/steps/`, one file per operation.

use super::Derivation;
use super::algebra::{Env, Value, evaluate};
pub use super::solve::equation_with;
pub use super::step_result::{
    Recordable, Stability, Stable, Stands, StandsFor, StateStability, StepResult,
};
use crate::cas::Expr;
use crate::scene::operations::Equilibria;
use crate::scene::{AuthorStep, Operation, Scene};
use std::collections::BTreeMap;

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
/// quantities, and the results of the steps before it (a claim's, with ω and the axis).
pub fn names_env(scene: &Scene, d: &Derivation) -> Env {
    env_of(scene, d, false)
}

/// The names' environment; `printed`: each step's result in the form its page prints.
fn env_of(scene: &Scene, d: &Derivation, printed: bool) -> Env {
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
        let r = d.printed.get(name).filter(|_| printed).unwrap_or(r);
        for (name, e) in r.values(scene.result_names(name)) {
            env.insert(name, Value::Scalar(e));
        }
    }
    env
}

/// An expression as written, each earlier step put in by the form its page prints (see
/// `expand_names`): what a reader of the page would write next.
pub fn expand_printed_names(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    e: &Expr,
) -> Result<Expr, StepError> {
    // Anything the printed forms cannot give, the derived ones do, or say why not.
    match evaluate(e, &env_of(scene, d, true)) {
        Ok(Value::Scalar(x)) if d.numeric_name_in(scene, e).is_none() => Ok(x),
        _ => expand_names(scene, d, step, e),
    }
}

/// An expression with every name bound in the environment replaced by its value, unsimplified:
/// the form the numeric checks evaluate, independent of the engine.
pub fn expand_names(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    e: &Expr,
) -> Result<Expr, StepError> {
    if let Some((name, of)) = d.numeric_name_in(scene, e) {
        return Err(StepError::Operation {
            step: step.name.clone(),
            line: step.line,
            message: numeric_only(&name, &of),
        });
    }
    match evaluate(e, &names_env(scene, d)) {
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

/// Why a name whose result is a number only cannot be used as an expression.
pub fn numeric_only(name: &str, step: &str) -> String {
    format!(
        "`{name}` has no exact form: step `{step}` found its modes as numbers at the scene's \
         values (the page says why), and a later step, a claim or a graded answer needs an exact \
         form"
    )
}

/// `of` with each name of `set` replaced by its expression (names of earlier steps put in
/// first), unsimplified.
pub fn substituted(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    of: &Expr,
    set: &BTreeMap<String, Expr>,
) -> Result<Expr, StepError> {
    let f = expand_names(scene, d, step, of)?;
    let values = replacements(scene, d, step, set)?;
    Ok(f.substitute(&|s| values.get(s).cloned()))
}

/// Each name of a `substitute` step's `set` and its replacement, earlier steps put in.
pub fn replacements(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    set: &BTreeMap<String, Expr>,
) -> Result<BTreeMap<String, Expr>, StepError> {
    set.iter()
        .map(|(name, e)| Ok((name.clone(), expand_names(scene, d, step, e)?)))
        .collect()
}

/// The equations a `substitute` step works on, when it names an earlier step of equations.
pub fn substituted_equations<'a>(d: &'a Derivation, of: &Expr) -> Option<&'a [(String, Expr)]> {
    match of {
        Expr::Sym(name) => match d.named.get(name) {
            Some(StepResult::Equations(eqs)) => Some(eqs),
            _ => None,
        },
        _ => None,
    }
}

/// An `integrate` step's ranges with earlier steps put into their limits.
pub fn expand_ranges(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    over: &[(String, Expr, Expr)],
) -> Result<Vec<(String, Expr, Expr)>, StepError> {
    over.iter()
        .map(|(v, lo, hi)| {
            Ok((
                v.clone(),
                expand_names(scene, d, step, lo)?,
                expand_names(scene, d, step, hi)?,
            ))
        })
        .collect()
}

/// The equations of motion whose states of rest the `equilibria` step `of` found.
pub fn equilibria_source<'a>(scene: &'a Scene, of: &str) -> Option<&'a str> {
    scene.steps.iter().find_map(|s| match &s.op {
        Operation::Equilibria(Equilibria { of: m }) if s.name == of => Some(m.as_str()),
        _ => None,
    })
}
