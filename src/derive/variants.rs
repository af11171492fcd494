//! A problem's answers for one variant, exactly: the scene's derivation is done once with
//! symbols, and each variant substitutes its exact values into the results. Rational answers
//! are folded here, without the engine; the others (roots, angles) are simplified by it.

use super::{Derivation, DeriveError};
use crate::cas::{self, Expr, special_angles};
use crate::model::catalogue::quantity;
use crate::model::value::Value;
use crate::scene::{Problem, Variant};

/// One answer of one variant: the quantity and its exact value there.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct ExactAnswer {
    pub quantity: String,
    pub value: Value,
}

/// Every answer of `problem` at `variant`, in the order the problem lists them.
pub fn exact_answers(
    d: &Derivation,
    problem: &Problem,
    variant: &Variant,
) -> Result<Vec<ExactAnswer>, DeriveError> {
    let mut entries: Vec<Vec<Expr>> = Vec::new();
    let mut for_engine: Vec<(usize, usize, Expr)> = Vec::new();
    for (i, name) in problem.answers.iter().enumerate() {
        let general = d.quantities.get(name).ok_or_else(|| missing(d, name))?;
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
    for (name, mut row) in problem.answers.iter().zip(entries) {
        // The roots were ordered at the scene's values; a variant orders its own.
        if name == quantity::PRINCIPAL_MOMENTS {
            row.sort_by(|a, b| {
                let (x, y) = (a.eval(&|_| None), b.eval(&|_| None));
                x.unwrap_or(f64::NAN)
                    .total_cmp(&y.unwrap_or(f64::NAN))
                    .then_with(|| a.to_text().cmp(&b.to_text()))
            });
        }
        out.push(ExactAnswer {
            quantity: name.clone(),
            value: d.quantities[name].with_entries(&row),
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
        DeriveError::Missing(answer_name(name))
    }
}

/// The catalogue's own name for a quantity, for `DeriveError::Missing`.
fn answer_name(name: &str) -> &'static str {
    crate::model::catalogue::ANSWERS
        .iter()
        .find(|(q, _)| *q == name)
        .map_or("answer", |(q, _)| q)
}
