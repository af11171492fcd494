//! `[problem]` and `[variants]`: the statement's placeholders, the answers, each varying
//! symbol's range or list, the requirements, and the variants drawn from them.

use super::{Validator, content_start};
use crate::model::catalogue::Output;
use crate::scene::AuthorStep;
use crate::scene::error::SceneError;
use crate::scene::raw::RawScene;
use crate::scene::raw::answer_value;
use crate::scene::types::{Answer, Body, Problem};
use std::collections::{BTreeMap, BTreeSet};
use toml::Spanned;

/// A Moodle answer's tolerance when the scene sets none: 1% of the answer.
pub const DEFAULT_TOLERANCE: f64 = 0.01;
/// The longest statement, in bytes.
pub const MAX_STATEMENT: usize = 4000;

impl Validator<'_> {
    pub(super) fn problem(
        &self,
        raw: &RawScene,
        symbols: &BTreeMap<String, String>,
        values: &BTreeMap<String, f64>,
        wants: &[Output],
        bodies: &[Body],
        (names, steps, coordinates): (&BTreeSet<String>, &[AuthorStep], usize),
    ) -> Result<Option<Problem>, SceneError> {
        let Some(p) = &raw.problem else {
            if let Some(v) = &raw.variants {
                return Err(self.err(
                    v.span().start,
                    "variants",
                    "[variants] without [problem]: add a [problem] with a statement and answers",
                ));
            }
            return Ok(None);
        };
        let at = p.span().start;
        let p = p.get_ref();
        let placeholders = self.statement(&p.statement, symbols)?;
        let tolerance = self.problem_tolerance(&p.tolerance)?;
        let mut answers: Vec<Answer> = Vec::new();
        for (i, a) in p.answers.get_ref().iter().enumerate() {
            let answer = self.answer(
                a,
                &format!("problem.answers[{i}]"),
                names,
                wants,
                (steps, coordinates),
                tolerance,
            )?;
            if answers.iter().any(|b| b.value == answer.value) {
                return Err(self.err(
                    content_start(&answer_value(a)),
                    &format!("problem.answers[{i}]"),
                    format!("`{}` is listed twice", answer.written),
                ));
            }
            answers.push(answer);
        }
        if answers.is_empty() {
            return Err(self.err(
                p.answers.span().start,
                "problem.answers",
                "a problem needs at least one answer, such as [\"inertia_tensor\"]",
            ));
        }
        let variants = self.variants(raw, symbols, values, bodies)?;
        if let Some((name, at)) = placeholders
            .iter()
            .find(|(name, _)| !variants[0].values.contains_key(name))
        {
            return Err(self.err(
                *at,
                "problem.statement",
                format!(
                    "`{{{name}}}` has no value to put in: give `{name}` a range under [variants] \
                     or a value under [numeric] values"
                ),
            ));
        }
        let mut given: Vec<String> = Vec::new();
        for (name, _) in placeholders {
            if !given.contains(&name) {
                given.push(name);
            }
        }
        Ok(Some(Problem {
            statement: p.statement.get_ref().clone(),
            given,
            answers,
            tolerance,
            variants,
            at: self.loc.line_col(at),
        }))
    }

    /// The problem's relative tolerance: between 0 and 1, 1% when not given.
    fn problem_tolerance(&self, tolerance: &Option<Spanned<f64>>) -> Result<f64, SceneError> {
        Ok(match tolerance {
            Some(t) if !(t.get_ref().is_finite() && *t.get_ref() > 0.0 && *t.get_ref() < 1.0) => {
                return Err(self.err(
                    t.span().start,
                    "problem.tolerance",
                    "the tolerance is relative to the answer: a number between 0 and 1, such as \
                     0.01 for 1%",
                ));
            }
            Some(t) => *t.get_ref(),
            None => DEFAULT_TOLERANCE,
        })
    }

    /// Every `{name}` must be a symbol; braces come only in such pairs. The placeholders, each
    /// with its offset in the file.
    fn statement(
        &self,
        s: &Spanned<String>,
        symbols: &BTreeMap<String, String>,
    ) -> Result<Vec<(String, usize)>, SceneError> {
        let mut found = Vec::new();
        let text = s.get_ref();
        let field = "problem.statement";
        if text.len() > MAX_STATEMENT {
            return Err(self.err(
                content_start(s),
                field,
                format!(
                    "the statement is {} bytes; at most {MAX_STATEMENT}",
                    text.len()
                ),
            ));
        }
        // Outside `$…$` every brace is a placeholder's; inside, `{name}` of a symbol is one and
        // any other brace is the mathematics' own grouping.
        let bytes = text.as_bytes();
        let mut in_math = false;
        let mut i = 0;
        while i < bytes.len() {
            let at = content_start(s) + i;
            match bytes[i] {
                b'\\' if bytes.get(i + 1) == Some(&b'$') => i += 1,
                b'$' => in_math = !in_math,
                b'}' if !in_math => return Err(self.err(at, field, "a `}` without its `{`")),
                b'{' => {
                    let close = text[i..].find('}').map(|c| i + c);
                    let name = close.map(|c| &text[i + 1..c]);
                    match (name, in_math) {
                        (Some(name), _) if symbols.contains_key(name) => {
                            found.push((name.to_string(), at));
                            i = close.expect("found with the name");
                        }
                        (_, true) => {}
                        (None, false) => {
                            return Err(self.err(
                                at,
                                field,
                                "a `{` without its `}`: write `{symbol}`",
                            ));
                        }
                        (Some(name), false) => {
                            return Err(self.err(
                                at,
                                field,
                                format!(
                                    "`{{{name}}}` is not a declared symbol; placeholders name \
                                     symbols"
                                ),
                            ));
                        }
                    }
                }
                _ => {}
            }
            i += 1;
        }
        Ok(found)
    }
}
