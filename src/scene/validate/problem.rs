//! `[problem]` and `[variants]`: the statement's placeholders, the answers, each varying
//! symbol's range or list, the requirements, and the variants drawn from them.

use super::{Validator, content_start};
use crate::cas::{Expr, Rational};
use crate::model::catalogue::Output;
use crate::scene::AuthorStep;
use crate::scene::error::SceneError;
use crate::scene::raw::RawScene;
use crate::scene::raw::answer_value;
use crate::scene::types::{Answer, Body, Problem, Variant};
use crate::scene::variants::{
    Comparison, DrawError, MAX_COMBINATIONS, MAX_VARIANTS, Requirement, draw, range,
};
use std::collections::{BTreeMap, BTreeSet};
use toml::Spanned;

/// A Moodle answer's tolerance when the scene sets none: 1% of the answer.
pub const DEFAULT_TOLERANCE: f64 = 0.01;
/// The longest statement, in bytes.
pub const MAX_STATEMENT: usize = 4000;

type Entry = (Spanned<String>, Spanned<toml::Value>);

/// The most digits in a variant's value, numerator or denominator: longer ones are beyond what
/// the numeric check can follow, and slow every exact step.
pub const MAX_VALUE_DIGITS: usize = 30;

/// Whether a range or list is written in decimals (`"0.3"`, not `"3/10"`): its values are then
/// shown so.
fn written_in_decimals(v: &toml::Value) -> bool {
    match v {
        toml::Value::String(s) => s.contains('.'),
        toml::Value::Array(items) => items.iter().any(written_in_decimals),
        toml::Value::Table(t) => t.values().any(written_in_decimals),
        _ => false,
    }
}

/// Why a value cannot be a variant's, if it cannot: it has more than [`MAX_VALUE_DIGITS`]
/// digits, or its size is beyond double precision, where the numeric check would see infinity
/// or zero instead of it (never clamped).
fn beyond_double(e: &Expr) -> Option<String> {
    let mut shown = e.to_text();
    if shown.len() > 40 {
        shown = format!("{}… ({} characters)", &shown[..30], shown.len());
    }
    let exact = e.eval_rational(&|_| None);
    if let Some(r) = &exact {
        let (n, d) = r.abs_parts();
        let digits = n.to_string().len().max(d.to_string().len());
        if digits > MAX_VALUE_DIGITS {
            return Some(format!(
                "{shown} has {digits} digits; a value has at most {MAX_VALUE_DIGITS}: give the \
                 quantity in units where it has fewer"
            ));
        }
    }
    let x = e.eval(&|_| None).ok()?;
    let zero = exact.is_some_and(|r| r.is_zero());
    if !x.is_finite() || (!x.is_normal() && !zero) {
        return Some(format!(
            "{shown} is beyond double precision (sizes from about 2.2e-308 to 1.8e308), which \
             the numeric check needs: give the quantity in units where it is nearer 1"
        ));
    }
    None
}

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
        let tolerance = match &p.tolerance {
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
        };
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

    /// The variants: one, at the scene's values, without `[variants]`. Each obeys the bodies'
    /// rules as the scene's own values do; a range or list that breaks one is refused at its
    /// line, with the value and the variant.
    fn variants(
        &self,
        raw: &RawScene,
        symbols: &BTreeMap<String, String>,
        values: &BTreeMap<String, f64>,
        bodies: &[Body],
    ) -> Result<Vec<Variant>, SceneError> {
        // A symbol without a range keeps its [numeric] value, exactly as written in decimal.
        let fixed: BTreeMap<String, Expr> = values
            .iter()
            .filter_map(|(k, v)| {
                Rational::parse_decimal(&format!("{:e}", v.abs()))
                    .map(|r| (k.clone(), Expr::Num(if *v < 0.0 { r.negated() } else { r })))
            })
            .collect();
        // TOML's numbers are written in decimals; a range or list below says how it is written.
        let mut decimal: BTreeSet<String> = fixed.keys().cloned().collect();
        let Some(table) = &raw.variants else {
            return Ok(vec![Variant {
                number: 1,
                values: fixed,
                decimal,
            }]);
        };
        let table_at = table.span().start;
        let mut count = None;
        let mut count_at = table_at;
        let mut seed = 1u64;
        let mut require = Vec::new();
        let mut require_at = table_at;
        let mut options: Vec<(String, Vec<Expr>)> = Vec::new();
        let mut option_at: BTreeMap<String, usize> = BTreeMap::new();
        let entries: Vec<Entry> = table.get_ref().clone().into_iter().collect();
        for (key, value) in &entries {
            let name = key.get_ref().as_str();
            let field = format!("variants.{name}");
            let at = value.span().start;
            match name {
                "count" => {
                    count = Some(self.count(value, &field)?);
                    count_at = key.span().start;
                }
                "seed" => {
                    seed = value
                        .get_ref()
                        .as_integer()
                        .and_then(|s| u64::try_from(s).ok())
                        .ok_or_else(|| {
                            self.err(at, &field, "the seed is a non-negative integer, such as 7")
                        })?
                }
                "require" => {
                    require_at = at;
                    require = self.requirements(value, &field, symbols)?;
                }
                _ if symbols.contains_key(name) => {
                    option_at.insert(name.to_string(), at);
                    if written_in_decimals(value.get_ref()) {
                        decimal.insert(name.to_string());
                    } else {
                        decimal.remove(name);
                    }
                    options.push((name.to_string(), self.options(value, &field)?))
                }
                _ => {
                    return Err(self.err(
                        key.span().start,
                        &field,
                        format!(
                            "`{name}` is not a declared symbol (nor count, seed or require); \
                             declare it under [symbols] to vary it"
                        ),
                    ));
                }
            }
        }
        let count = count.ok_or_else(|| {
            self.err(
                table_at,
                "variants.count",
                "say how many variants: count = 12",
            )
        })?;
        let combinations = options
            .iter()
            .try_fold(1usize, |n, (_, o)| n.checked_mul(o.len()))
            .filter(|n| *n <= MAX_COMBINATIONS);
        let Some(combinations) = combinations else {
            return Err(self.err(
                table_at,
                "variants",
                format!(
                    "the ranges give more than {MAX_COMBINATIONS} combinations of values; use \
                     larger steps or fewer values"
                ),
            ));
        };
        let mut variants = draw(&options, &fixed, &require, count, seed).map_err(|e| {
            let short = match e {
                DrawError::Short(short) => short,
                DrawError::Undecided { index, values, why } => {
                    let at_values: Vec<String> = options
                        .iter()
                        .filter_map(|(n, _)| values.get(n).map(|v| format!("{n} = {}", v.to_text())))
                        .collect();
                    return self.err(
                        require_at,
                        &format!("variants.require[{index}]"),
                        format!(
                            "`{}` cannot be decided at {}: {why}; write it so that it can be \
                             decided, for example with both sides rational",
                            require[index].text,
                            at_values.join(", ")
                        ),
                    );
                }
            };
            let mut why = if require.is_empty() {
                String::new()
            } else {
                " meet `require`".to_string()
            };
            if short.public_left_out {
                why.push_str(if why.is_empty() { " " } else { " and " });
                why.push_str(
                    "are not the scene's own [numeric] values (its page shows their answers)",
                );
            }
            self.err(
                count_at,
                "variants.count",
                format!(
                    "count = {count}, but only {} of the {combinations} combinations of values{why}: \
                     lower the count{}",
                    short.met,
                    if require.is_empty() {
                        " or widen the ranges"
                    } else {
                        ", widen the ranges or relax `require`"
                    }
                ),
            )
        })?;
        for v in &mut variants {
            v.decimal = decimal.clone();
        }
        for v in &variants {
            let numbers = v.numbers();
            let Some(b) = self.broken_rule(raw, bodies, &numbers) else {
                continue;
            };
            // At the range of a varying symbol the broken field uses.
            let (name, at) = options
                .iter()
                .find(|(n, _)| b.symbols.contains(n))
                .or(options.first())
                .map(|(n, _)| (n.clone(), option_at[n]))
                .unwrap_or_else(|| (String::new(), table_at));
            let field = if name.is_empty() {
                "variants".to_string()
            } else {
                format!("variants.{name}")
            };
            let value = v.values.get(&name).map(Expr::to_text).unwrap_or_default();
            return Err(self.err(
                at,
                &field,
                format!(
                    "{name} = {value} (variant {}) breaks `{}`: {}; keep the range or list \
                     within the bodies' rules (or add a `require`)",
                    v.number,
                    b.field,
                    b.message("in that variant")
                ),
            ));
        }
        Ok(variants)
    }

    fn count(&self, value: &Spanned<toml::Value>, field: &str) -> Result<usize, SceneError> {
        value
            .get_ref()
            .as_integer()
            .and_then(|n| usize::try_from(n).ok())
            .filter(|n| (1..=MAX_VARIANTS).contains(n))
            .ok_or_else(|| {
                self.err(
                    value.span().start,
                    field,
                    format!("count is a whole number from 1 to {MAX_VARIANTS}"),
                )
            })
    }

    /// A list of exact values to choose from, or `{ from, to, step }`.
    fn options(&self, value: &Spanned<toml::Value>, field: &str) -> Result<Vec<Expr>, SceneError> {
        let at = value.span().start;
        let no_symbols = BTreeSet::from(["pi".to_string()]);
        let exact = |v: &toml::Value, f: &str| -> Result<Expr, SceneError> {
            let text = match v {
                toml::Value::String(s) => s.clone(),
                toml::Value::Integer(n) => n.to_string(),
                toml::Value::Float(x) => {
                    return Err(self.err(
                        at,
                        f,
                        format!(
                            "write {x} as a string, \"{x}\", so that it stays exact (a TOML \
                             float is binary)"
                        ),
                    ));
                }
                _ => return Err(self.err(at, f, "a value is a string such as \"3/2\"")),
            };
            self.expr_str(&text, at, f, &no_symbols)
        };
        let out = match value.get_ref() {
            toml::Value::Array(items) => {
                let mut out: Vec<Expr> = Vec::new();
                for (i, item) in items.iter().enumerate() {
                    let e = exact(item, &format!("{field}[{i}]"))?;
                    if e.eval(&|_| None).is_err() {
                        return Err(self.err(at, field, "a value is a number"));
                    }
                    if out.contains(&e) {
                        return Err(self.err(
                            at,
                            &format!("{field}[{i}]"),
                            format!("{} is listed twice", e.to_text()),
                        ));
                    }
                    out.push(e);
                }
                out
            }
            toml::Value::Table(t) => {
                if let Some(k) = t
                    .keys()
                    .find(|k| !["from", "to", "step"].contains(&k.as_str()))
                {
                    return Err(self.err(
                        at,
                        field,
                        format!("`{k}`: a range has only from, to and step"),
                    ));
                }
                let part = |k: &str| -> Result<Rational, SceneError> {
                    let f = format!("{field}.{k}");
                    let v = t.get(k).ok_or_else(|| {
                        self.err(
                            at,
                            &f,
                            format!(
                                "a range needs `{k}`: {{ from = \"1\", to = \"10\", step = \"1\" }}"
                            ),
                        )
                    })?;
                    match exact(v, &f)?.eval_rational(&|_| None) {
                        Some(r) => Ok(r),
                        None => {
                            Err(self.err(at, &f, "a range's ends and step are rational numbers"))
                        }
                    }
                };
                let (from, to, step) = (part("from")?, part("to")?, part("step")?);
                if !step.is_positive() {
                    return Err(self.err(
                        at,
                        &format!("{field}.step"),
                        "the step must be positive",
                    ));
                }
                range(&from, &to, &step, MAX_COMBINATIONS).ok_or_else(|| {
                    self.err(
                        at,
                        field,
                        format!("this range has more than {MAX_COMBINATIONS} values"),
                    )
                })?
            }
            _ => {
                return Err(self.err(
                    at,
                    field,
                    "give a list of values, [\"1/2\", \"1\"], or a range, { from = \"1\", to = \
                     \"10\", step = \"1\" }",
                ));
            }
        };
        if out.is_empty() {
            return Err(self.err(at, field, "this range or list has no values"));
        }
        if let Some(why) = out.iter().find_map(beyond_double) {
            return Err(self.err(at, field, why));
        }
        Ok(out)
    }

    fn requirements(
        &self,
        value: &Spanned<toml::Value>,
        field: &str,
        symbols: &BTreeMap<String, String>,
    ) -> Result<Vec<Requirement>, SceneError> {
        let at = value.span().start;
        let Some(items) = value.get_ref().as_array() else {
            return Err(self.err(at, field, "require is a list such as [\"a < b\"]"));
        };
        let mut names: BTreeSet<String> = symbols.keys().cloned().collect();
        names.insert("pi".into());
        let mut out = Vec::new();
        for (i, item) in items.iter().enumerate() {
            let f = format!("{field}[{i}]");
            let Some(text) = item.as_str() else {
                return Err(self.err(at, &f, "a requirement is a string such as \"a < b\""));
            };
            let Some((op_text, op)) = Comparison::ALL
                .iter()
                .find(|(t, _)| text.contains(t))
                .copied()
            else {
                return Err(self.err(
                    at,
                    &f,
                    "a requirement compares two expressions with <, <=, >, >=, == or !=",
                ));
            };
            let (lhs, rhs) = text.split_once(op_text).expect("found above");
            out.push(Requirement {
                text: text.to_string(),
                lhs: self.expr_str(lhs, at, &f, &names)?,
                op,
                rhs: self.expr_str(rhs, at, &f, &names)?,
            });
        }
        Ok(out)
    }
}
