//! The built-in steps' results in the forms a textbook prints: each exact entry of a step's
//! statement through the presentation pass (`cas::present_all`), as an author's step is. The
//! lectures' own scenes say nothing of their symbols' signs (an angular velocity's components,
//! a particle's coordinates), so every symbol is taken to have either sign: only rewrites true
//! for all values are made, and the engine proves each form equal to the result. The exact
//! statement stays in `Step::exact` for `--json`, and `verify` compares the two at random points.

use super::{Derivation, DeriveError};
use crate::cas::{self, Expr};
use crate::notation::{Formula, Op};
use std::collections::BTreeSet;

/// Each built-in step's statement in its printed form; the exact one kept where they differ.
pub fn present_builtin_steps(
    d: &mut Derivation,
    declared: &cas::Declared,
) -> Result<(), DeriveError> {
    let mut exprs = Vec::new();
    let mut signed = BTreeSet::new();
    for step in d.steps.iter_mut().filter(|s| s.author.is_none()) {
        for e in scalars(&mut step.statement) {
            signed.extend(e.symbols());
            exprs.push(e.clone());
        }
    }
    if exprs.is_empty() {
        return Ok(());
    }
    let mut forms = cas::present_all(exprs, signed, declared.clone())?.into_iter();
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

/// A scalar, or each entry of a vector. A matrix (a tensor) stays as derived: its entries are
/// set side by side, where a form over one denominator runs past the paper's edge.
fn entries(e: &mut Expr) -> Vec<&mut Expr> {
    match e {
        Expr::List(items) if items.iter().any(|i| matches!(i, Expr::List(_))) => Vec::new(),
        Expr::List(items) => items.iter_mut().collect(),
        _ => vec![e],
    }
}
