//! A problem's answers for one variant, exactly: the scene's derivation is done once with
//! symbols, and each variant substitutes its exact values into the results. Rational answers
//! are folded here, without the engine; the others (roots, angles) are simplified by it.

use super::algebra::{Env, evaluate};
use super::{Derivation, DeriveError};
use crate::cas::{self, Expr, special_angles};
use crate::model::catalogue::{Kind, find, quantity, routed_quantities};
use crate::model::value::Value;
use crate::scene::{Answer, Problem, Scene, Variant};
use std::collections::BTreeMap;

/// One answer of one variant: the quantity and its exact value there.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct ExactAnswer {
    pub quantity: String,
    pub value: Value,
}

/// The placeholder for entry `k` (row-major) of a derived quantity in a resolved answer:
/// `inertia_tensor__4`. No scene name has a double underscore.
pub fn placeholder(quantity: &str, k: usize) -> String {
    format!("{quantity}__{k}")
}

/// The quantity and entry a placeholder stands for.
pub fn placeholder_of(name: &str) -> Option<(&str, usize)> {
    let (q, k) = name.rsplit_once("__")?;
    Some((q, k.parse().ok()?))
}

/// An answer's value with the claim language worked out (dot products, indices, lists): an
/// expression of the scene's symbols, the steps' names, and placeholders for the entries of
/// the derived quantities it uses, which the exact and the numeric routes each fill in.
pub fn resolve(scene: &Scene, answer: &Answer) -> Result<Value, DeriveError> {
    let value = resolve_expr(scene, &answer.value).map_err(|e| {
        DeriveError::NotDerivable(format!(
            "the answer `{}` (line {}): {e}",
            answer.written, answer.line
        ))
    })?;
    if answer.bare_quantity().is_none() && !matches!(value, Value::Scalar(_)) {
        return Err(DeriveError::NotDerivable(format!(
            "the answer `{}` (line {}) is {}; an expression answer is one number (a derived \
             vector or matrix is an answer by its name alone, or one entry of it, such as \
             `centre_of_mass[2]`)",
            answer.written,
            answer.line,
            value.kind()
        )));
    }
    Ok(value)
}

/// [`resolve`] of any expression of the claim language.
pub fn resolve_expr(scene: &Scene, e: &Expr) -> Result<Value, super::algebra::ClaimError> {
    let mut env = Env::new();
    for (name, e) in &scene.definitions {
        env.insert(name.clone(), Value::Scalar(e.clone()));
    }
    for (name, v) in &scene.vectors {
        env.insert(name.clone(), Value::Vector(v.clone()));
    }
    for (name, v) in [("omega", &scene.omega), ("axis", &scene.axis)] {
        if let Some(v) = v {
            env.insert(name.into(), Value::Vector(v.clone()));
        }
    }
    for name in routed_quantities() {
        let p = |k| Expr::sym(&placeholder(name, k));
        let value = match find(name).map(|q| q.kind) {
            Some(Kind::Vector) => Value::Vector(std::array::from_fn(p)),
            Some(Kind::Matrix) => Value::Matrix(std::array::from_fn(|i| {
                std::array::from_fn(|j| p(3 * i + j))
            })),
            _ => Value::Scalar(p(0)),
        };
        env.insert(name.to_string(), value);
    }
    evaluate(e, &env)
}

/// Every step's named result, by name (`a`, `Omega`, `x_1`, ...).
pub fn step_values(d: &Derivation) -> BTreeMap<String, Expr> {
    d.named
        .iter()
        .flat_map(|(name, r)| r.values(name))
        .collect()
}

/// An answer in the scene's symbols: a bare quantity's derived value, or the resolved
/// expression with each quantity's entries and each step's result put in. `steps` is
/// [`step_values`] of `d`.
pub fn general_answer(
    scene: &Scene,
    d: &Derivation,
    steps: &BTreeMap<String, Expr>,
    answer: &Answer,
) -> Result<Value, DeriveError> {
    if let Some(q) = answer.bare_quantity() {
        return Ok(d.quantities.get(q).ok_or_else(|| missing(d, q))?.clone());
    }
    let resolved = resolve(scene, answer)?;
    let failed = std::cell::RefCell::new(None);
    let filled = resolved.entries()[0].substitute(&|s| {
        if let Some((q, k)) = placeholder_of(s) {
            let found = d.quantities.get(q).map(|v| v.entries()[k].clone());
            if found.is_none() {
                *failed.borrow_mut() = Some(q.to_string());
            }
            return found;
        }
        steps.get(s).cloned()
    });
    if let Some(q) = failed.into_inner() {
        return Err(missing(d, &q));
    }
    Ok(Value::Scalar(filled))
}

/// Every answer of `problem` in the scene's symbols ([`general_answer`]), in its order: worked
/// out once, then each variant's values put in.
pub fn general_answers(
    scene: &Scene,
    d: &Derivation,
    problem: &Problem,
) -> Result<Vec<Value>, DeriveError> {
    let steps = step_values(d);
    problem
        .answers
        .iter()
        .map(|a| general_answer(scene, d, &steps, a))
        .collect()
}

/// Every answer of `problem` at `variant`, in the order the problem lists them, from their
/// [`general_answers`].
pub fn exact_answers(
    general: &[Value],
    problem: &Problem,
    variant: &Variant,
) -> Result<Vec<ExactAnswer>, DeriveError> {
    let mut entries: Vec<Vec<Expr>> = Vec::new();
    let mut for_engine: Vec<(usize, usize, Expr)> = Vec::new();
    for (i, (answer, general)) in problem.answers.iter().zip(general).enumerate() {
        let name = &answer.written;
        let mut row = Vec::new();
        for (k, e) in general.entries().iter().enumerate() {
            let e = special_angles(&e.substitute(&|s| variant.values.get(s).cloned()));
            if let Some(symbol) = e.symbols().into_iter().find(|s| s != "pi") {
                return Err(DeriveError::NoVariantValue {
                    quantity: name.clone(),
                    symbol,
                });
            }
            match e.eval_rational(&|_| None) {
                Some(r) => row.push(Expr::Num(r)),
                None => {
                    row.push(Expr::int(0));
                    for_engine.push((i, k, e));
                }
            }
        }
        entries.push(row);
    }
    if !for_engine.is_empty() {
        let simplified = cas::simplify_all(for_engine.iter().map(|(_, _, e)| e.clone()).collect())?;
        for ((i, k, _), e) in for_engine.iter().zip(simplified) {
            entries[*i][*k] = e;
        }
    }
    let mut out = Vec::new();
    for ((answer, general), mut row) in problem.answers.iter().zip(general).zip(entries) {
        let name = &answer.written;
        // The roots were ordered at the scene's values; a variant orders its own.
        if answer.bare_quantity() == Some(quantity::PRINCIPAL_MOMENTS) {
            row.sort_by(|a, b| {
                let (x, y) = (a.eval(&|_| None), b.eval(&|_| None));
                x.unwrap_or(f64::NAN)
                    .total_cmp(&y.unwrap_or(f64::NAN))
                    .then_with(|| a.to_text().cmp(&b.to_text()))
            });
        }
        out.push(ExactAnswer {
            quantity: name.clone(),
            value: general.with_entries(&row),
        });
    }
    Ok(out)
}

/// Why answer `name` was not derived: the principal moments of an irreducible cubic have no
/// exact form; anything else is a bug in the plan.
fn missing(d: &Derivation, name: &str) -> DeriveError {
    let unsolved = d.eigen.as_ref().is_some_and(|e| !e.unsolved.is_empty());
    if unsolved && name == quantity::PRINCIPAL_MOMENTS {
        DeriveError::NoExactMoments
    } else {
        DeriveError::Missing(find(name).map_or("answer", |q| q.name))
    }
}
