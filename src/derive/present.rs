//! The built-in steps' results in the forms a textbook prints: each exact entry of a step's
//! statement through the presentation pass (`cas::present_all`), as an author's step is. The
//! lectures' own scenes say nothing of their symbols' signs (an angular velocity's components,
//! a particle's coordinates), so every symbol is taken to have either sign: only rewrites true
//! for all values are made, and the engine proves each form equal to the result. The exact
//! statement stays in `Step::exact` for `--json`, and `verify` compares the two at random points.

use super::{Derivation, DeriveError};
use crate::cas::{self, Expr};
use crate::model::value::Value;
use crate::notation::{Formula, Op};
use std::collections::BTreeSet;

/// Each built-in step's statement in its printed form; the exact one kept where they differ.
pub fn present_builtin_steps(
    d: &mut Derivation,
    declared: &cas::Declared,
    claims: &[crate::scene::Claim],
) -> Result<(), DeriveError> {
    let mut exprs = Vec::new();
    let mut signed = BTreeSet::new();
    for step in d.steps.iter_mut().filter(|s| s.author.is_none()) {
        for e in scalars(&mut step.statement) {
            signed.extend(e.symbols());
            exprs.push(e.clone());
        }
    }
    present_matrices(d, declared, claims)?;
    if exprs.is_empty() {
        return Ok(());
    }
    let mut forms = cas::present_all(
        exprs,
        signed,
        declared.clone(),
        crate::notation::printed_length,
    )?
    .into_iter();
    for step in d.steps.iter_mut().filter(|s| s.author.is_none()) {
        let exact = step.statement.clone();
        let mut changed = false;
        for slot in scalars(&mut step.statement) {
            let form = forms.next().expect("one form for each entry");
            changed |= *slot != form;
            *slot = form;
        }
        if changed {
            step.exact = Some(exact);
        }
    }
    Ok(())
}

/// Each matrix a built-in step states, and each matrix quantity, with its entries' common
/// factor out (`cas::matrix_forms`): a step's line prints `I = factor (rows)`, its exact
/// statement kept, and the page's results print the quantity so (`Derivation::matrices`).
fn present_matrices(
    d: &mut Derivation,
    declared: &cas::Declared,
    claims: &[crate::scene::Claim],
) -> Result<(), DeriveError> {
    let in_steps: Vec<usize> = (0..d.steps.len())
        .filter(|&i| d.steps[i].author.is_none() && matrix_rows(&d.steps[i].statement).is_some())
        .collect();
    let quantities: Vec<String> = d
        .quantities
        .iter()
        .filter(|(_, v)| matches!(v, Value::Matrix(_)))
        .map(|(k, _)| k.clone())
        .collect();
    let mut matrices: Vec<Vec<Vec<Expr>>> = in_steps
        .iter()
        .filter_map(|&i| matrix_rows(&d.steps[i].statement))
        .collect();
    matrices.extend(quantities.iter().map(|k| match &d.quantities[k] {
        Value::Matrix(m) => m.iter().map(|r| r.to_vec()).collect(),
        _ => unreachable!("only matrices were taken"),
    }));
    if matrices.is_empty() {
        return Ok(());
    }
    // A claim's own form (`m*a^2*[[2/3, -1/4, …], …]`) for the matrix it names,
    // wherever a line prints that matrix; the engine proves it equal or it is not taken.
    let written: Vec<(Vec<Vec<Expr>>, Expr)> = claims
        .iter()
        .filter_map(|c| match (&c.quantity, &c.value) {
            (Some(Expr::Sym(k)), Some(v)) => match d.quantities.get(k) {
                Some(Value::Matrix(m)) if cas::factor_and_rows(v).is_some() => {
                    Some((m.iter().map(|r| r.to_vec()).collect(), v.clone()))
                }
                _ => None,
            },
            _ => None,
        })
        .collect();
    let matrices: Vec<(Vec<Vec<Expr>>, Option<Expr>)> = matrices
        .into_iter()
        .map(|rows| {
            let hint = written
                .iter()
                .find(|(m, _)| *m == rows)
                .map(|(_, v)| v.clone());
            (rows, hint)
        })
        .collect();
    // A tensor's symbols are a body's masses and lengths, or a frame's angles: every one
    // taken with either sign, as the lectures' scenes say nothing of their signs.
    let signed: BTreeSet<String> = matrices
        .iter()
        .flat_map(|(rows, _)| rows.iter().flatten().flat_map(Expr::symbols))
        .collect();
    let mut forms = cas::matrix_forms(
        matrices,
        signed,
        declared.clone(),
        crate::notation::printed_length,
    )?
    .into_iter();
    for i in in_steps {
        let form = forms.next().expect("one form for each matrix");
        if let (Some(form), Formula::Row(items)) = (form, &d.steps[i].statement) {
            let lhs = items[0].clone();
            let exact = std::mem::replace(
                &mut d.steps[i].statement,
                Formula::Row(vec![lhs, Formula::Op(Op::Equals), matrix_formula(&form)]),
            );
            d.steps[i].exact.get_or_insert(exact);
        }
    }
    for k in quantities {
        if let Some(form) = forms.next().expect("one form for each matrix") {
            d.matrices.insert(k, form);
        }
    }
    Ok(())
}

/// A matrix with its factor out, as the printers set it: `factor (rows)`.
pub fn matrix_formula(form: &cas::MatrixForm) -> Formula {
    Formula::Row(vec![
        Formula::Expr(form.factor.clone()),
        Formula::Matrix(
            form.rows
                .iter()
                .map(|r| r.iter().cloned().map(Formula::Expr).collect())
                .collect(),
        ),
    ])
}

/// Whether a statement gives a matrix: `lhs = (rows)`, or its factor out `lhs = f (rows)`.
pub fn is_matrix_statement(f: &Formula) -> bool {
    matrix_rows(f).is_some() || factored_entries(f).is_some()
}

/// The rows of a statement `lhs = matrix`.
fn matrix_rows(f: &Formula) -> Option<Vec<Vec<Expr>>> {
    match f {
        Formula::Row(items) => match items.as_slice() {
            [_, Formula::Op(Op::Equals), Formula::Expr(e @ Expr::List(_))] => {
                cas::factor_and_rows(e).map(|(_, rows)| rows)
            }
            _ => None,
        },
        _ => None,
    }
}

/// The entries of a statement `lhs = f (rows)` (`matrix_formula`), the factor put into each.
fn factored_entries(f: &Formula) -> Option<Vec<Expr>> {
    let Formula::Row(items) = f else { return None };
    let [_, Formula::Op(Op::Equals), Formula::Row(form)] = items.as_slice() else {
        return None;
    };
    let [Formula::Expr(factor), Formula::Matrix(rows)] = form.as_slice() else {
        return None;
    };
    rows.iter()
        .flatten()
        .map(|cell| match cell {
            Formula::Expr(e) => Some(Expr::mul(vec![factor.clone(), e.clone()])),
            _ => None,
        })
        .collect()
}

/// Every entry a statement `lhs = value` gives, as its line prints it: a scalar, a vector's
/// or a matrix's entries, a matrix with its factor out as that factor times each entry. The
/// printed check compares these with the exact statement's, one by one.
pub fn shown_entries(f: &Formula) -> Vec<Expr> {
    if let Some(rows) = matrix_rows(f) {
        return rows.into_iter().flatten().collect();
    }
    if let Some(entries) = factored_entries(f) {
        return entries;
    }
    scalars(&mut f.clone())
        .into_iter()
        .map(|e| e.clone())
        .collect()
}

/// The exact scalars a step gives as its result: each entry of the value of a statement
/// `lhs = value` (as `Step::equation` makes it). A note's formula stays as its route wrote it
/// (an integral's integrand, a characteristic polynomial set out for its roots).
pub fn scalars(f: &mut Formula) -> Vec<&mut Expr> {
    match f {
        Formula::Row(items) => match items.as_mut_slice() {
            [_, Formula::Op(Op::Equals), Formula::Expr(e)] => entries(e),
            _ => Vec::new(),
        },
        _ => Vec::new(),
    }
}

/// A scalar, or each entry of a vector. A matrix (a tensor) is presented whole, its common
/// factor out (`present_matrices`): each entry over its own denominator runs past the edge.
fn entries(e: &mut Expr) -> Vec<&mut Expr> {
    match e {
        Expr::List(items) if items.iter().any(|i| matches!(i, Expr::List(_))) => Vec::new(),
        Expr::List(items) => items.iter_mut().collect(),
        _ => vec![e],
    }
}
