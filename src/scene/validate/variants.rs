//! `[variants]`: each varying symbol's range or list, the requirements, and the variants drawn
//! from them, each within the bodies' rules.

use super::Validator;
use crate::cas::{Expr, Rational};
use crate::scene::error::SceneError;
use crate::scene::raw::RawScene;
use crate::scene::types::{Body, Variant};
use crate::scene::variants::{
    Comparison, DrawError, MAX_COMBINATIONS, MAX_VARIANTS, Requirement, draw, range,
};
use std::collections::{BTreeMap, BTreeSet};
use toml::Spanned;

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

/// What `[variants]` says, each with where it is written: how many, the seed, the
/// requirements and each varying symbol's values.
struct VariantsTable {
    at: usize,
    count: Option<usize>,
    count_at: usize,
    seed: u64,
    require: Vec<Requirement>,
    require_at: usize,
    options: Vec<(String, Vec<Expr>)>,
    option_at: BTreeMap<String, usize>,
}

impl Validator<'_> {
    /// The variants: one, at the scene's values, without `[variants]`. Each obeys the bodies'
    /// rules as the scene's own values do; a range or list that breaks one is refused at its
    /// line, with the value and the variant.
    pub(super) fn variants(
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
        let t = self.variants_table(table, symbols, &mut decimal)?;
        let count = t
            .count
            .ok_or_else(|| self.err(t.at, "variants.count", "say how many variants: count = 12"))?;
        let combinations = t
            .options
            .iter()
            .try_fold(1usize, |n, (_, o)| n.checked_mul(o.len()))
            .filter(|n| *n <= MAX_COMBINATIONS);
        let Some(combinations) = combinations else {
            return Err(self.err(
                t.at,
                "variants",
                format!(
                    "the ranges give more than {MAX_COMBINATIONS} combinations of values; use \
                     larger steps or fewer values"
                ),
            ));
        };
        let mut variants = draw(&t.options, &fixed, &t.require, count, t.seed)
            .map_err(|e| self.draw_error(e, &t, count, combinations))?;
        for v in &mut variants {
            v.decimal = decimal.clone();
        }
        self.within_bodies_rules(raw, bodies, &variants, &t)?;
        Ok(variants)
    }

    /// The entries of `[variants]`, each checked; a varying symbol's values written in
    /// decimals join `decimal`, others leave it.
    fn variants_table(
        &self,
        table: &Spanned<BTreeMap<Spanned<String>, Spanned<toml::Value>>>,
        symbols: &BTreeMap<String, String>,
        decimal: &mut BTreeSet<String>,
    ) -> Result<VariantsTable, SceneError> {
        let at = table.span().start;
        let mut t = VariantsTable {
            at,
            count: None,
            count_at: at,
            seed: 1,
            require: Vec::new(),
            require_at: at,
            options: Vec::new(),
            option_at: BTreeMap::new(),
        };
        let entries: Vec<Entry> = table.get_ref().clone().into_iter().collect();
        for (key, value) in &entries {
            let name = key.get_ref().as_str();
            let field = format!("variants.{name}");
            let at = value.span().start;
            match name {
                "count" => {
                    t.count = Some(self.count(value, &field)?);
                    t.count_at = key.span().start;
                }
                "seed" => {
                    t.seed = value
                        .get_ref()
                        .as_integer()
                        .and_then(|s| u64::try_from(s).ok())
                        .ok_or_else(|| {
                            self.err(at, &field, "the seed is a non-negative integer, such as 7")
                        })?
                }
                "require" => {
                    t.require_at = at;
                    t.require = self.requirements(value, &field, symbols)?;
                }
                _ if symbols.contains_key(name) => {
                    t.option_at.insert(name.to_string(), at);
                    if written_in_decimals(value.get_ref()) {
                        decimal.insert(name.to_string());
                    } else {
                        decimal.remove(name);
                    }
                    t.options
                        .push((name.to_string(), self.options(value, &field)?))
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
        Ok(t)
    }

    /// Why `count` variants could not be drawn: a requirement undecided at some values, or too
    /// few combinations that meet the requirements.
    fn draw_error(
        &self,
        e: DrawError,
        t: &VariantsTable,
        count: usize,
        combinations: usize,
    ) -> SceneError {
        let short = match e {
            DrawError::Short(short) => short,
            DrawError::Undecided { index, values, why } => {
                let at_values: Vec<String> = t
                    .options
                    .iter()
                    .filter_map(|(n, _)| values.get(n).map(|v| format!("{n} = {}", v.to_text())))
                    .collect();
                return self.err(
                    t.require_at,
                    &format!("variants.require[{index}]"),
                    format!(
                        "`{}` cannot be decided at {}: {why}; write it so that it can be \
                         decided, for example with both sides rational",
                        t.require[index].text,
                        at_values.join(", ")
                    ),
                );
            }
        };
        let mut why = if t.require.is_empty() {
            String::new()
        } else {
            " meet `require`".to_string()
        };
        if short.public_left_out {
            why.push_str(if why.is_empty() { " " } else { " and " });
            why.push_str("are not the scene's own [numeric] values (its page shows their answers)");
        }
        self.err(
            t.count_at,
            "variants.count",
            format!(
                "count = {count}, but only {} of the {combinations} combinations of values{why}: \
                 lower the count{}",
                short.met,
                if t.require.is_empty() {
                    " or widen the ranges"
                } else {
                    ", widen the ranges or relax `require`"
                }
            ),
        )
    }

    /// Refuses the first variant at which a body breaks its rules, at the range of a varying
    /// symbol the broken field uses.
    fn within_bodies_rules(
        &self,
        raw: &RawScene,
        bodies: &[Body],
        variants: &[Variant],
        t: &VariantsTable,
    ) -> Result<(), SceneError> {
        for v in variants {
            let numbers = v.numbers();
            let Some(b) = self.broken_rule(raw, bodies, &numbers) else {
                continue;
            };
            let (name, at) = t
                .options
                .iter()
                .find(|(n, _)| b.symbols.contains(n))
                .or(t.options.first())
                .map(|(n, _)| (n.clone(), t.option_at[n]))
                .unwrap_or_else(|| (String::new(), t.at));
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
        Ok(())
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
        let out = match value.get_ref() {
            toml::Value::Array(items) => self.listed_options(items, at, field)?,
            toml::Value::Table(t) => self.range_options(t, at, field)?,
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

    /// One exact value of a list or range, written as a string or an integer (a TOML float is
    /// binary, so refused).
    fn exact_option(&self, v: &toml::Value, at: usize, f: &str) -> Result<Expr, SceneError> {
        let text = match v {
            toml::Value::String(s) => s.clone(),
            toml::Value::Integer(n) => n.to_string(),
            toml::Value::Float(x) => {
                return Err(self.err(
                    at,
                    f,
                    format!(
                        "write {x} as a string, \"{x}\", so that it stays exact (a TOML float is \
                         binary)"
                    ),
                ));
            }
            _ => return Err(self.err(at, f, "a value is a string such as \"3/2\"")),
        };
        self.expr_str(&text, at, f, &BTreeSet::from(["pi".to_string()]))
    }

    /// A list's values: numbers, none twice.
    fn listed_options(
        &self,
        items: &[toml::Value],
        at: usize,
        field: &str,
    ) -> Result<Vec<Expr>, SceneError> {
        let mut out: Vec<Expr> = Vec::new();
        for (i, item) in items.iter().enumerate() {
            let e = self.exact_option(item, at, &format!("{field}[{i}]"))?;
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
        Ok(out)
    }

    /// A range's values, from `from` to `to` by a positive rational `step`.
    fn range_options(
        &self,
        t: &toml::Table,
        at: usize,
        field: &str,
    ) -> Result<Vec<Expr>, SceneError> {
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
                    format!("a range needs `{k}`: {{ from = \"1\", to = \"10\", step = \"1\" }}"),
                )
            })?;
            match self.exact_option(v, at, &f)?.eval_rational(&|_| None) {
                Some(r) => Ok(r),
                None => Err(self.err(at, &f, "a range's ends and step are rational numbers")),
            }
        };
        let (from, to, step) = (part("from")?, part("to")?, part("step")?);
        if !step.is_positive() {
            return Err(self.err(at, &format!("{field}.step"), "the step must be positive"));
        }
        range(&from, &to, &step, MAX_COMBINATIONS).ok_or_else(|| {
            self.err(
                at,
                field,
                format!("this range has more than {MAX_COMBINATIONS} values"),
            )
        })
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
