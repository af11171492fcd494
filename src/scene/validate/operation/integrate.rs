//! `integrate = "expr"`, `over = [["x", "0", "a"]]`: a definite integral, innermost variable
//! first, whose limits may use the variables after it.

use super::{StepContext, Validator, content_start};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, Text};
use crate::scene::step::Operation;

/// The most nested integrals of one `integrate` step.
const MAX_RANGES: usize = 3;

impl Validator<'_> {
    pub(super) fn integrate(
        &self,
        of: &Text,
        s: &RawStep,
        cx: &StepContext,
    ) -> Result<Operation, SceneError> {
        let over = self.ranges(s, cx)?;
        let mut inner = cx.scope.clone();
        inner.extend(over.iter().map(|(v, _, _)| v.clone()));
        Ok(Operation::Integrate {
            of: self.claim_expr(of, &format!("{}.integrate", cx.field), &inner)?,
            over,
        })
    }

    /// An `integrate` step's `over`: [variable, from, to], innermost first, each variable a new
    /// name, each range's limits in the scene's names and the variables after it.
    fn ranges(
        &self,
        s: &RawStep,
        cx: &StepContext,
    ) -> Result<Vec<(String, Expr, Expr)>, SceneError> {
        let key = format!("{}.over", cx.field);
        if s.over.is_empty() || s.over.len() > MAX_RANGES {
            return Err(self.err(
                cx.offset,
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
                return Err(self.err(range.span().start, &key, "a range is [variable, from, to]"));
            };
            let v = var.get_ref();
            // A symbol declared for it (x, "distance along the rod", with its unit) is bound by
            // the integral: the result does not depend on it.
            let taken = cx.scope.contains(v) && !self.declared.contains(v);
            if !super::super::is_identifier(v) || taken || vars.contains(v) {
                return Err(self.err(
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
                return Err(self.err(range.span().start, &key, "a range is [variable, from, to]"));
            };
            // Limits use the scene's names and the variables integrated after this one.
            let mut names = cx.scope.clone();
            names.extend(vars[k + 1..].iter().cloned());
            out.push((
                vars[k].clone(),
                self.claim_expr(lo, &key, &names)?,
                self.claim_expr(hi, &key, &names)?,
            ));
        }
        Ok(out)
    }
}
