//! A problem's answers: a derived quantity by itself (the seven of old, each with its numeric
//! route), or any expression of the scene's symbols, the derived quantities that have a numeric
//! route, and the named results of steps that have one; with a label, a unit and a tolerance.

use super::{Validator, content_start};
use crate::cas::Expr;
use crate::model::catalogue::{ANSWERS, Output, find, routed_quantities};
use crate::model::units::Unit;
use crate::scene::error::SceneError;
use crate::scene::raw::{RawAnswer, answer_value};
use crate::scene::types::Answer;
use crate::scene::{AuthorStep, Operation};
use std::collections::BTreeSet;
use toml::Spanned;

/// The steps whose result has a numeric value of its own at any values: `be` (the expression
/// as written, its names by their own routes), `frequency` of one coordinate (the period of the
/// integrated motion), `solve` (Newton's method on the equation) and `integrate` (quadrature).
pub fn step_has_route(op: &Operation) -> bool {
    op.kind().graded
}

/// The largest relative tolerance a quiz answer may have: 50%.
const MAX_TOLERANCE: f64 = 0.5;

impl Validator<'_> {
    pub(super) fn answer(
        &self,
        a: &Spanned<RawAnswer>,
        field: &str,
        names: &BTreeSet<String>,
        wants: &[Output],
        (steps, coordinates): (&[AuthorStep], usize),
        default_tolerance: f64,
    ) -> Result<Answer, SceneError> {
        let text = answer_value(a);
        let at = content_start(&text);
        let value = self.parse_checked(text.get_ref(), at, field, names, true)?;
        let raw = a.get_ref();
        // A bare quantity of old must be among the outputs wanted, as before.
        if let Expr::Sym(name) = &value
            && let Some((_, output)) = ANSWERS.iter().find(|(q, _)| q == name)
            && !wants.contains(output)
        {
            return Err(self.err(
                at,
                field,
                format!(
                    "the answer `{name}` is derived by the output `{}`: add it to outputs.want",
                    output.name()
                ),
            ));
        }
        self.routed(&value, at, field, (steps, coordinates))?;
        let unit = match &raw.unit {
            Some(u) => Some(Unit::parse(u.get_ref()).map_err(|e| {
                self.err(content_start(u), &format!("{field}.unit"), e.to_string())
            })?),
            None => None,
        };
        let label = match &raw.label {
            Some(l) if l.get_ref().trim().is_empty() || l.get_ref().len() > 200 => {
                return Err(self.err(
                    content_start(l),
                    &format!("{field}.label"),
                    "a label is a few words, at most 200 bytes, such as \"period of small \
                     oscillations\"",
                ));
            }
            Some(l) => {
                self.prose(l, &format!("{field}.label"), false)?;
                Some(l.get_ref().clone())
            }
            None => None,
        };
        let tolerance = match &raw.tolerance {
            Some(t) => self.tolerance(t, &format!("{field}.tolerance"))?,
            None => default_tolerance,
        };
        Ok(Answer {
            written: text.get_ref().trim().to_string(),
            value,
            label,
            unit,
            tolerance,
            line: self.loc.line_col(at).0,
        })
    }

    /// Every name of an answer has a numeric route to check each variant on: a routed
    /// quantity, a symbol, or a step with a value of its own.
    fn routed(
        &self,
        value: &Expr,
        at: usize,
        field: &str,
        (steps, coordinates): (&[AuthorStep], usize),
    ) -> Result<(), SceneError> {
        for name in value.symbols() {
            if find(&name).is_some() && !routed_quantities().any(|q| q == name) {
                return Err(self.err(
                    at,
                    field,
                    format!(
                        "`{name}` has no numeric route to check each variant's answer on; an \
                         answer may use {}, the scene's symbols and the results of `be`, \
                         `frequency`, `solve` and `integrate` steps",
                        routed_quantities().collect::<Vec<_>>().join(", ")
                    ),
                ));
            }
            if let Some(step) = step_named(steps, coordinates, &name)
                && !step_has_route(&step.op)
            {
                return Err(self.err(
                    at,
                    field,
                    format!(
                        "the step `{}` (line {}) has no numeric value of its own to check each \
                         variant's answer on; an answer may use the results of `be`, \
                         `frequency`, `solve` and `integrate` steps",
                        step.name, step.line
                    ),
                ));
            }
        }
        Ok(())
    }

    /// `"0.5%"`, or a number such as 0.005: relative to the answer.
    fn tolerance(&self, t: &Spanned<toml::Value>, field: &str) -> Result<f64, SceneError> {
        let x = match t.get_ref() {
            toml::Value::Float(x) => Some(*x),
            toml::Value::String(s) => match s.trim().strip_suffix('%') {
                Some(p) => p.trim().parse::<f64>().ok().map(|p| p / 100.0),
                None => s.trim().parse::<f64>().ok(),
            },
            _ => None,
        };
        match x {
            Some(x) if x.is_finite() && x > 0.0 && x <= MAX_TOLERANCE => Ok(x),
            _ => Err(self.err(
                t.span().start,
                field,
                "a tolerance is relative to the answer: a percentage such as \"0.5%\", or a \
                 number between 0 and 0.5 such as 0.005",
            )),
        }
    }
}

/// The step that gives `name`: its own name, or `x_k` of a step `x` with several results.
pub fn step_named<'a>(
    steps: &'a [AuthorStep],
    coordinates: usize,
    name: &str,
) -> Option<&'a AuthorStep> {
    steps
        .iter()
        .find(|s| s.names_given(coordinates).iter().any(|n| n == name))
}
