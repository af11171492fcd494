//! Validation: a raw scene's fields checked part by part (symbols, bodies, claims, plots),
//! each error located at its field.

mod answers;
mod ascii_math;
mod assumptions;
mod bodies;
mod claims;
mod expression_plot;
mod hints;
mod motion_plot;
mod operation;
mod outputs;
mod plots;
mod problem;
mod requests;
mod steps;
mod symbol_names;
mod symbols;
mod text;
mod variants;
mod whole;

pub use answers::{step_has_route, step_named};
pub use claims::PINNED_VARIANTS;
pub use symbol_names::{prints_its_name, suggested_tex};
pub use text::control_character;

use super::error::{Locator, SceneError};
pub(super) use super::raw::content_start;
use super::raw::{RawScene, Text, is_identifier};
use crate::cas::{Expr, parse_input as parse_expr};

pub use claims::CLAIM_FUNCTIONS;
use claims::check_calls;
use std::collections::{BTreeMap, BTreeSet};
use toml::Spanned;

const RESERVED: &[&str] = &["pi"];

/// The largest degree and number of terms a dimension, mass or value expression may expand
/// to: the derivations raise a dimension to the fifth power at most, and the engine's own
/// budget is degree 30 (`cas`).
pub const MAX_INPUT_DEGREE: f64 = 6.0;
pub const MAX_INPUT_TERMS: f64 = 100.0;

/// The longest free-body plot: its end time, and the radians ω turns through by then. The
/// shipped lectures reach t = 400 and 2.5e3 radians (Earth's polar motion).
pub const MAX_PLOT_TIME: f64 = 1e4;
/// The most plots a scene draws: each may integrate up to [`MAX_PLOT_TIME`], and a scene of
/// 7,000 plots once ran for a day.
pub const MAX_PLOTS: usize = 24;
pub const MAX_PLOT_RADIANS: f64 = 1e4;

/// Ids that would collide with the site's own files and folders (compared without case, as
/// some file systems do).
pub const RESERVED_IDS: &[&str] = &["index", "plots", "handouts", "export", "style"];

/// The longest id or lecture name: file names are made from them with up to ~40 more
/// characters, and file systems allow 255 bytes.
pub const MAX_NAME: usize = 64;

pub(super) struct Validator<'a> {
    pub(super) loc: &'a Locator<'a>,
    /// The names the author declared in [symbols]: an `integrate` step may run over one.
    pub(super) declared: BTreeSet<String>,
}

/// Step key -> the notes' citation for it.
type Citations = BTreeMap<String, String>;

impl Validator<'_> {
    /// `axis` is a direction: a non-unit vector would scale I_n by its squared length.
    fn unit_axis(
        &self,
        n: &[Expr; 3],
        at: usize,
        values: &BTreeMap<String, f64>,
    ) -> Result<(), SceneError> {
        let env = |s: &str| values.get(s).copied();
        let mut squared = 0.0;
        for e in n {
            let v = e
                .eval(&env)
                .map_err(|m| self.err(at, "axis", m.to_string()))?;
            squared += v * v;
        }
        if (squared.sqrt() - 1.0).abs() > 1e-12 {
            return Err(self.err(
                at,
                "axis",
                format!(
                    "the axis must be a unit vector, but its length is {} at the scene's values; divide each component by the length, or write it as [\"sin(u)*cos(v)\", \"sin(u)*sin(v)\", \"cos(u)\"]",
                    crate::base::format::significant(squared.sqrt(), 6)
                ),
            ));
        }
        Ok(())
    }

    /// `[cite]`: each key must name a step that cites, and each citation be one short line.
    fn cites(&self, raw: &RawScene) -> Result<Citations, SceneError> {
        use crate::model::catalogue::CITABLE_STEPS;
        let mut out = BTreeMap::new();
        for (key, text) in &raw.cite {
            let field = format!("cite.{}", key.get_ref());
            if !CITABLE_STEPS.contains(&key.get_ref().as_str()) {
                return Err(self.err(
                    key.span().start,
                    &field,
                    format!(
                        "no step is called `{}`; the steps a scene may cite are {}",
                        key.get_ref(),
                        CITABLE_STEPS.join(", ")
                    ),
                ));
            }
            let t = text.get_ref();
            if t.trim().is_empty() || t.len() > 80 || t.chars().any(char::is_control) {
                return Err(self.err(
                    content_start(text),
                    &field,
                    "a citation is one line of at most 80 characters, such as \"eq (51)\"",
                ));
            }
            out.insert(key.get_ref().clone(), t.clone());
        }
        Ok(out)
    }

    /// The id and the lecture name, which name files.
    fn names(&self, raw: &RawScene) -> Result<(), SceneError> {
        let id = raw.id.get_ref();
        if !is_identifier(&id.replace('-', "_")) {
            return Err(self.err(
                content_start(&raw.id),
                "id",
                "an id is letters, digits, `-` and `_`, starting with a letter",
            ));
        }
        if id.len() > MAX_NAME {
            return Err(self.err(
                content_start(&raw.id),
                "id",
                format!(
                    "an id of {} characters; the limit is {MAX_NAME}, so that every file name \
                     made from it fits any file system",
                    id.len()
                ),
            ));
        }
        if RESERVED_IDS.contains(&id.to_ascii_lowercase().as_str()) {
            return Err(self.err(
                content_start(&raw.id),
                "id",
                format!(
                    "`{id}` is reserved for the site's own {}; choose another id",
                    if id.eq_ignore_ascii_case("index") {
                        "index page"
                    } else {
                        "folder"
                    }
                ),
            ));
        }
        let lecture = raw.notes.lecture.get_ref();
        if lecture.len() > MAX_NAME || !lecture.chars().any(|c| c.is_ascii_alphanumeric()) {
            return Err(self.err(
                content_start(&raw.notes.lecture),
                "notes.lecture",
                format!(
                    "a lecture name has a letter or digit and at most {MAX_NAME} characters, \
                     such as \"3/4\""
                ),
            ));
        }
        Ok(())
    }

    /// The byte offset where a 1-based line starts.
    pub(super) fn line_offset(&self, line: usize) -> usize {
        self.loc
            .text
            .split_inclusive('\n')
            .take(line.saturating_sub(1))
            .map(str::len)
            .sum()
    }

    pub(super) fn err(&self, offset: usize, field: &str, msg: impl Into<String>) -> SceneError {
        self.loc.error(offset, field, msg)
    }

    /// Parses an expression and checks that every symbol is one of `allowed`.
    pub(super) fn expr(
        &self,
        t: &Text,
        field: &str,
        allowed: &BTreeSet<String>,
    ) -> Result<Expr, SceneError> {
        self.expr_str(t.get_ref(), content_start(t), field, allowed)
    }

    /// Parses `text`, which starts at byte `start` of the file.
    pub(super) fn expr_str(
        &self,
        text: &str,
        start: usize,
        field: &str,
        allowed: &BTreeSet<String>,
    ) -> Result<Expr, SceneError> {
        let e = self.parse_checked(text, start, field, allowed, false)?;
        let size = e.expansion_size();
        if size.degree > MAX_INPUT_DEGREE || size.terms > MAX_INPUT_TERMS {
            return Err(self.err(
                start,
                field,
                format!(
                    "this expression expands to degree {} with up to {:.0} terms; a scene's \
                     dimensions and masses stay within degree {MAX_INPUT_DEGREE} and \
                     {MAX_INPUT_TERMS} terms, so that the derivations stay fast: introduce a \
                     symbol for it",
                    size.degree, size.terms
                ),
            ));
        }
        Ok(e)
    }

    /// A definition: an expression of the scene's names that claims and steps use, within the
    /// engine's own budget (the bodies' tighter limits do not apply).
    pub(super) fn definition_expr(
        &self,
        t: &Text,
        field: &str,
        allowed: &BTreeSet<String>,
    ) -> Result<Expr, SceneError> {
        let e = self.parse_checked(t.get_ref(), content_start(t), field, allowed, false)?;
        let size = e.expansion_size();
        if size.degree > crate::cas::MAX_DEGREE || size.terms > crate::cas::MAX_TERMS {
            return Err(self.err(
                content_start(t),
                field,
                format!(
                    "this definition would expand to degree {} with up to {:.0} terms, beyond \
                     the engine's budget of degree {} and {:.0} terms: define its parts under \
                     names of their own",
                    size.degree,
                    size.terms,
                    crate::cas::MAX_DEGREE,
                    crate::cas::MAX_TERMS
                ),
            ));
        }
        Ok(e)
    }

    /// Parses `text` (at byte `start` of the file), checks its names against `names` and its
    /// calls against the scalar functions, or the claim language's when `claim` is set.
    pub(super) fn parse_checked(
        &self,
        text: &str,
        start: usize,
        field: &str,
        names: &BTreeSet<String>,
        claim: bool,
    ) -> Result<Expr, SceneError> {
        let parsed = parse_expr(text).map_err(|e| {
            self.err(
                start + e.offset,
                field,
                format!("malformed expression: {}", e.message),
            )
        })?;
        if let Some((name, offset)) = parsed.symbols.iter().find(|(n, _)| !names.contains(n)) {
            let message = hints::undefined_name(name, names, claim);
            return Err(self.err(start + offset, field, message));
        }
        check_calls(&parsed.expr, claim).map_err(|m| self.err(start, field, m.to_string()))?;
        if let Some(message) = hints::time_derivative(&parsed.expr, names) {
            return Err(self.err(start, field, message));
        }
        Ok(parsed.expr)
    }

    pub(super) fn vec2(
        &self,
        v: &Spanned<Vec<Text>>,
        field: &str,
        allowed: &BTreeSet<String>,
    ) -> Result<[Expr; 2], SceneError> {
        let items = self.exprs(v, 2, field, allowed)?;
        Ok([items[0].clone(), items[1].clone()])
    }

    pub(super) fn vec3(
        &self,
        v: &Spanned<Vec<Text>>,
        field: &str,
        allowed: &BTreeSet<String>,
    ) -> Result<[Expr; 3], SceneError> {
        let items = self.exprs(v, 3, field, allowed)?;
        Ok([items[0].clone(), items[1].clone(), items[2].clone()])
    }

    /// A list of exactly `n` expressions.
    fn exprs(
        &self,
        v: &Spanned<Vec<Text>>,
        n: usize,
        field: &str,
        allowed: &BTreeSet<String>,
    ) -> Result<Vec<Expr>, SceneError> {
        if v.get_ref().len() != n {
            return Err(self.err(
                v.span().start,
                field,
                format!("expected {n} components, found {}", v.get_ref().len()),
            ));
        }
        v.get_ref()
            .iter()
            .enumerate()
            .map(|(i, t)| self.expr(t, &format!("{field}[{i}]"), allowed))
            .collect()
    }
}
