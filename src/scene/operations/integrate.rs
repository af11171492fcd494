//! `integrate = "expr"`, `over = [["x", "0", "a"]]`: a definite integral, innermost variable
//! first, whose limits may use the variables after it.

use super::{OperationType, StepFields};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text, content_start, is_identifier};

/// The most nested integrals of one `integrate` step.
const MAX_RANGES: usize = 3;

/// A definite integral, innermost variable first: each (variable, from, to), whose limits
/// may use the variables after it.
#[derive(Debug, Clone, PartialEq)]
pub struct Integrate {
    pub of: Expr,
    pub over: Vec<(String, Expr, Expr)>,
}

impl OperationType for Integrate {
    fn read(of: &Text, s: &RawStep, f: &impl StepFields) -> Result<Self, SceneError> {
        let over = ranges(s, f)?;
        let mut inner = f.scope().clone();
        inner.extend(over.iter().map(|(v, _, _)| v.clone()));
        Ok(Integrate {
            of: f.expression(of, &format!("{}.integrate", f.field()), &inner)?,
            over,
        })
    }

    fn operands(&self) -> Vec<&Expr> {
        std::iter::once(&self.of)
            .chain(self.over.iter().flat_map(|(_, lo, hi)| [lo, hi]))
            .collect()
    }
}

/// An `integrate` step's `over`: [variable, from, to], innermost first, each variable a new
/// name, each range's limits in the scene's names and the variables after it.
fn ranges(s: &RawStep, f: &impl StepFields) -> Result<Vec<(String, Expr, Expr)>, SceneError> {
    let key = format!("{}.over", f.field());
    if s.over.is_empty() || s.over.len() > MAX_RANGES {
        return Err(f.err(
            f.offset(),
            &key,
            format!(
                "`integrate` needs `over`: one to {MAX_RANGES} ranges [variable, from, to], \
                 innermost first, such as over = [[\"x\", \"0\", \"a\"]]"
            ),
        ));
    }
    let mut vars: Vec<String> = Vec::new();
    for range in &s.over {
        let [var, ..] = &range.get_ref()[..] else {
            return Err(f.err(range.span().start, &key, "a range is [variable, from, to]"));
        };
        let v = var.get_ref();
        // A symbol declared for it (x, "distance along the rod", with its unit) is bound by
        // the integral: the result does not depend on it.
        let taken = f.scope().contains(v) && !f.declared().contains(v);
        if !is_identifier(v) || taken || vars.contains(v) {
            return Err(f.err(
                content_start(var),
                &key,
                format!(
                    "`{v}` cannot be an integration variable: it needs a name of its own or \
                     one declared in [symbols], not a definition, coordinate or step of this \
                     scene, nor another range's"
                ),
            ));
        }
        vars.push(v.clone());
    }
    let mut out = Vec::new();
    for (k, range) in s.over.iter().enumerate() {
        let [_, lo, hi] = &range.get_ref()[..] else {
            return Err(f.err(range.span().start, &key, "a range is [variable, from, to]"));
        };
        // Limits use the scene's names and the variables integrated after this one.
        let mut names = f.scope().clone();
        names.extend(vars[k + 1..].iter().cloned());
        out.push((
            vars[k].clone(),
            f.expression(lo, &key, &names)?,
            f.expression(hi, &key, &names)?,
        ));
    }
    Ok(out)
}
