//! A problem's answers for one variant, exactly: the scene's derivation is done once with
//! symbols, and each variant substitutes its exact values into the results. Rational answers
//! are folded here, without the engine; the others (roots, angles) are simplified by it.

use super::algebra::{Env, evaluate};
use super::{Derivation, DeriveError};
use crate::cas::{self, Expr, special_angles};
use crate::model::catalogue::{Kind, find, quantity, routed_quantities};
use crate::model::value::Value;
use crate::scene::operations::Frequency;
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
pub fn step_values(scene: &Scene, d: &Derivation) -> BTreeMap<String, Expr> {
    d.named
        .iter()
        .flat_map(|(name, r)| r.values(scene.result_names(name)))
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
    // A mode with no closed form stays a name here: each variant puts in its own value
    // (`with_numeric_modes`).
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
    let steps = step_values(scene, d);
    problem
        .answers
        .iter()
        .map(|a| general_answer(scene, d, &steps, a))
        .collect()
}

/// The general answers with each mode that has no closed form (`Omega_5` of a 6-link
/// `frequency`) put in as its value at `variant`'s values: √λ of the pencil (K, M) of the
/// step's linear equations there, by Sturm bisection (`modes::frequencies_at`), as the
/// shortest decimal that reads back to that double, so the key shows it as ≈ its value. The
/// answer's second route is nalgebra's Schur decomposition of M⁻¹K
/// (`verify/answer_routes.rs`).
pub fn with_numeric_modes<'a>(
    scene: &Scene,
    d: &Derivation,
    general: &'a [Value],
    variant: &Variant,
) -> Result<std::borrow::Cow<'a, [Value]>, DeriveError> {
    let names = d.numeric_names(scene);
    let named: std::collections::BTreeSet<String> = general
        .iter()
        .flat_map(|g| g.entries())
        .flat_map(|e| e.symbols())
        .filter(|s| names.contains_key(s))
        .collect();
    if named.is_empty() {
        return Ok(std::borrow::Cow::Borrowed(general));
    }
    let numbers = variant.numbers();
    let mut values: BTreeMap<String, Expr> = BTreeMap::new();
    for step in named.iter().map(|n| &names[n]) {
        let linear = scene
            .steps
            .iter()
            .find_map(|s| match &s.op {
                crate::scene::Operation::Frequency(Frequency { of }) if &s.name == step => {
                    d.named.get(of)
                }
                _ => None,
            })
            .and_then(super::step_names::StepResult::equations)
            .ok_or_else(|| {
                DeriveError::Inconsistent(format!("step `{step}` has no linear equations"))
            })?;
        for (k, w) in super::modes::frequencies_at(linear, &numbers)?
            .into_iter()
            .enumerate()
        {
            let exact = cas::Rational::parse_decimal(&format!("{w:e}")).ok_or_else(|| {
                DeriveError::Inconsistent(format!("the frequency {w} is not a finite number"))
            })?;
            values.insert(scene.result_names(step).kth(k), Expr::Num(exact));
        }
    }
    Ok(std::borrow::Cow::Owned(
        general
            .iter()
            .map(|g| {
                let entries: Vec<Expr> = g
                    .entries()
                    .iter()
                    .map(|e| e.substitute(&|s| values.get(s).cloned()))
                    .collect();
                g.with_entries(&entries)
            })
            .collect(),
    ))
}

/// Every answer of `problem` at `variant`, in the order the problem lists them, from their
/// [`general_answers`] (with [`with_numeric_modes`] put in).
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
            ascending(&mut row, &|_| None);
        }
        out.push(ExactAnswer {
            quantity: name.clone(),
            value: general.with_entries(&row),
        });
    }
    Ok(out)
}

/// Entries in ascending order of their values (`at` gives a symbol's), ties by their text.
fn ascending(row: &mut [Expr], at: &dyn Fn(&str) -> Option<f64>) {
    row.sort_by(|a, b| {
        let (x, y) = (a.eval(at), b.eval(at));
        x.unwrap_or(f64::NAN)
            .total_cmp(&y.unwrap_or(f64::NAN))
            .then_with(|| a.to_text().cmp(&b.to_text()))
    });
}

/// Each answer of `problem` at `variant` as the key shows it where it uses a value the author
/// wrote as a decimal: that value kept as written, the others put in exactly, so the key reads
/// 2π/√(3 ⋅ 9.81) where the exact value is 20π/(3√327) (g = 9.81 read as 981/100). `None` for
/// an answer that uses no such value: its exact value is the one shown.
pub fn shown_answers(
    general: &[Value],
    problem: &Problem,
    variant: &Variant,
) -> Result<Vec<Option<Value>>, DeriveError> {
    let written: BTreeMap<&str, (crate::cas::Rational, String)> = variant
        .decimal
        .iter()
        .filter_map(|name| match variant.values.get(name) {
            Some(Expr::Num(r)) => {
                let digits = crate::scene::terminating_decimal(&r.abs())?;
                Some((name.as_str(), (r.clone(), digits)))
            }
            _ => None,
        })
        .collect();
    let mut pending: Vec<(usize, Vec<Expr>)> = Vec::new();
    for (i, general) in general.iter().enumerate() {
        let row: Vec<Expr> = general
            .entries()
            .iter()
            .map(|e| {
                special_angles(&e.substitute(&|s| {
                    if written.contains_key(s) {
                        None
                    } else {
                        variant.values.get(s).cloned()
                    }
                }))
            })
            .collect();
        let uses = row
            .iter()
            .any(|e| e.symbols().iter().any(|s| written.contains_key(s.as_str())));
        if uses {
            pending.push((i, row));
        }
    }
    let mut out = vec![None; general.len()];
    if pending.is_empty() {
        return Ok(out);
    }
    let signed = written
        .iter()
        .filter(|(_, (r, _))| r.is_negative())
        .map(|(name, _)| name.to_string())
        .collect();
    let flat: Vec<Expr> = pending.iter().flat_map(|(_, row)| row.clone()).collect();
    let mut presented = cas::present_all(
        cas::simplify_all(flat)?,
        signed,
        Default::default(),
        crate::notation::printed_length,
    )?
    .into_iter();
    let at = |s: &str| written.get(s).map(|(r, _)| r.to_f64());
    for (i, row) in pending {
        let mut row: Vec<Expr> = presented.by_ref().take(row.len()).collect();
        if problem.answers[i].bare_quantity() == Some(quantity::PRINCIPAL_MOMENTS) {
            ascending(&mut row, &at);
        }
        let row: Vec<Expr> = row
            .iter()
            .map(|e| {
                numerals_first(&e.substitute(&|s| {
                    let (r, digits) = written.get(s)?;
                    let numeral = Expr::numeral(digits);
                    Some(if r.is_negative() {
                        Expr::mul(vec![Expr::int(-1), numeral])
                    } else {
                        numeral
                    })
                }))
            })
            .collect();
        out[i] = Some(general[i].with_entries(&row));
    }
    Ok(out)
}

/// More digits than a reader takes in at a glance: the numerator or denominator of a number
/// in `e` is over [`READABLE_DIGITS`] digits (a cubic's root at the author's values, a
/// nine-digit rational under a radical).
pub fn has_long_number(e: &Expr) -> bool {
    match e {
        Expr::Num(r) => {
            let (n, d) = r.abs_parts();
            n.to_string().len() > READABLE_DIGITS || d.to_string().len() > READABLE_DIGITS
        }
        Expr::Sym(_) => false,
        Expr::Add(v) | Expr::Mul(v) | Expr::List(v) | Expr::Call(_, v) => {
            v.iter().any(has_long_number)
        }
        Expr::Pow(a, b) | Expr::Index(a, b) => has_long_number(a) || has_long_number(b),
    }
}

/// The most digits of a number an exact answer in the key may have (999999/1000000 is read).
pub const READABLE_DIGITS: usize = 6;

/// Each product's numerals just after its number: 3 ⋅ 9.81 M, not 3M ⋅ 9.81.
fn numerals_first(e: &Expr) -> Expr {
    match e {
        Expr::Mul(v) => {
            let v: Vec<Expr> = v.iter().map(numerals_first).collect();
            let (mut front, back): (Vec<Expr>, Vec<Expr>) =
                v.into_iter().partition(Expr::is_number_like);
            front.extend(back);
            Expr::Mul(front)
        }
        Expr::Add(v) => Expr::Add(v.iter().map(numerals_first).collect()),
        Expr::Pow(a, b) => Expr::Pow(Box::new(numerals_first(a)), Box::new(numerals_first(b))),
        Expr::Call(n, v) => Expr::Call(n.clone(), v.iter().map(numerals_first).collect()),
        other => other.clone(),
    }
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
