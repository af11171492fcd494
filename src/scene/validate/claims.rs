//! `[[claim]]` and `[expect]`: statements in the claim language, and recorded results.

use super::{Validator, content_start};
use crate::cas::Expr;
use crate::model::catalogue::{body_quantities, free_body_quantities, is_quantity};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawClaim, RawRecorded, RawScene, Text};
use crate::scene::types::{Claim, ClaimRole, NOT_DERIVED, RecordedStep, Verdict};
use std::collections::{BTreeMap, BTreeSet};

/// `[expect]`: each quantity's recorded value, the line of each key, and each step's record.
type Recorded = (
    BTreeMap<String, Expr>,
    BTreeMap<String, usize>,
    BTreeMap<String, RecordedStep>,
);

/// The symmetric top's quantities that once had the names Poinsot's construction now has (an
/// old scene's `momentum_squared` meant L² of the top, and now means L² in I1, I2 and I3): the
/// old name and the new one.
const RENAMED_FOR_THE_TOP: &[(&str, &str)] = &[
    ("momentum_squared", "top_momentum_squared"),
    ("twice_energy", "top_twice_energy"),
];

/// In a scene that wants the symmetric top and not Poinsot's construction, a name whose
/// meaning changed: the old name and the new one.
fn renamed(name: &str, wanted: &[&str]) -> Option<(&'static str, &'static str)> {
    if !wanted.contains(&"symmetric_top") || wanted.contains(&"poinsot") {
        return None;
    }
    RENAMED_FOR_THE_TOP
        .iter()
        .copied()
        .find(|(old, _)| *old == name)
}

/// Why an old name of the symmetric top's is refused, and what to `do` instead (write it, or
/// rename the key).
fn renamed_message(old: &str, new: &str, what: &str) -> String {
    format!(
        "`{old}` is Poinsot's (in I1, I2 and I3) since the symmetric top's was renamed; in a \
         `symmetric_top` scene {what} `{new}` (or add `poinsot` to [outputs] want, for Poinsot's)"
    )
}

/// The `[expect]` key that pins a problem's variants.
pub const PINNED_VARIANTS: &str = "variants";

impl Validator<'_> {
    /// Every claim, its names checked against what the scene defines and derives.
    pub(super) fn claims(
        &self,
        raw: &RawScene,
        claim_names: &BTreeSet<String>,
    ) -> Result<Vec<Claim>, SceneError> {
        let mut claims = Vec::new();
        let wanted: Vec<&str> = raw.wanted().iter().map(|w| w.get_ref().as_str()).collect();
        for (i, c) in raw.claims.iter().enumerate() {
            let claim = self.claim(
                c.get_ref(),
                c.span().start,
                &format!("claim[{i}]"),
                claim_names,
            )?;
            let named = claim.quantity.iter().chain(&claim.value);
            if let Some((old, new)) = named
                .flat_map(|e| e.symbols())
                .find_map(|n| renamed(&n, &wanted))
            {
                return Err(self.err(
                    content_start(&c.get_ref().statement),
                    &format!("claim[{i}]"),
                    renamed_message(old, new, "write"),
                ));
            }
            claims.push(claim);
        }
        Ok(claims)
    }

    /// `[expect]`: recorded results, by quantity, and each author's step's, by its name.
    pub(super) fn expect(
        &self,
        raw: &RawScene,
        allowed: &BTreeSet<String>,
        variables: &BTreeSet<String>,
        steps: &[String],
    ) -> Result<Recorded, SceneError> {
        let mut expect = BTreeMap::new();
        let mut lines = BTreeMap::new();
        let mut step_records = BTreeMap::new();
        let wanted: Vec<&str> = raw.wanted().iter().map(|w| w.get_ref().as_str()).collect();
        for (name, value) in &raw.expect {
            let n = name.get_ref();
            // The problem's pinned variants: read by `pinned_variants`.
            if n == PINNED_VARIANTS {
                continue;
            }
            let line = self.loc.line_col(name.span().start).0;
            // A key that names no quantity in a scene of steps is a step's record: a step
            // renamed or removed since, which `check` reports and `--bless` removes.
            if steps.contains(n) || (!steps.is_empty() && !is_quantity(n)) {
                step_records.insert(
                    n.clone(),
                    RecordedStep {
                        values: self.step_record(value, n)?,
                        line,
                    },
                );
                continue;
            }
            if !is_quantity(n) {
                return Err(self.err(
                    name.span().start,
                    &format!("expect.{n}"),
                    not_a_quantity(n, steps),
                ));
            }
            // A scene written before the rename records the top's L² under Poinsot's name:
            // read as Poinsot's it would "change", and `--bless` could not record it (Poinsot's
            // is in I2, which a top's scene does not declare).
            if let Some((old, new)) = renamed(n, &wanted) {
                return Err(self.err(
                    name.span().start,
                    &format!("expect.{n}"),
                    renamed_message(old, new, "rename the key to"),
                ));
            }
            let RawRecorded::One(text) = value.get_ref() else {
                return Err(self.err(
                    value.span().start,
                    &format!("expect.{n}"),
                    format!("`{n}` records one value: write it as one string, not a list"),
                ));
            };
            let text = toml::Spanned::new(value.span(), text.clone());
            let mut scope = allowed.clone();
            scope.extend(variables.iter().cloned());
            expect.insert(
                n.clone(),
                self.claim_expr(&text, &format!("expect.{n}"), &scope)?,
            );
            lines.insert(n.clone(), line);
        }
        Ok((expect, lines, step_records))
    }

    /// A step's recorded results, each of which must read as an expression (or be
    /// [`NOT_DERIVED`]); the names are not checked here: a wrong one reads as a changed result.
    fn step_record(
        &self,
        value: &toml::Spanned<RawRecorded>,
        step: &str,
    ) -> Result<Vec<String>, SceneError> {
        let values = match value.get_ref() {
            RawRecorded::One(text) => vec![text.clone()],
            RawRecorded::Many(list) => list.clone(),
        };
        for (k, v) in values.iter().enumerate() {
            if v == NOT_DERIVED {
                continue;
            }
            if let Err(e) = crate::cas::parse(v) {
                return Err(self.err(
                    value.span().start,
                    &format!("expect.{step}"),
                    format!(
                        "the recorded result {} of step `{step}` cannot be read ({}): remove the \
                         key and run `mechbook check --bless` to record it again",
                        k + 1,
                        e.message
                    ),
                ));
            }
        }
        Ok(values)
    }

    /// `[expect] variants`: one 8-digit hex hash per variant, as `check --bless` writes them;
    /// only in a scene with a `[problem]`.
    pub(super) fn pinned_variants(
        &self,
        raw: &RawScene,
        has_problem: bool,
    ) -> Result<Option<(Vec<String>, usize)>, SceneError> {
        let Some((name, value)) = raw
            .expect
            .iter()
            .find(|(n, _)| n.get_ref() == PINNED_VARIANTS)
        else {
            return Ok(None);
        };
        let field = format!("expect.{PINNED_VARIANTS}");
        if !has_problem {
            return Err(self.err(
                name.span().start,
                &field,
                "`variants` pins a problem's variants, and this scene has no [problem]: remove it",
            ));
        }
        let text = match value.get_ref() {
            RawRecorded::One(text) => text.as_str(),
            RawRecorded::Many(_) => "",
        };
        let hashes: Vec<String> = text.split_whitespace().map(String::from).collect();
        if hashes.is_empty()
            || !hashes
                .iter()
                .all(|h| h.len() == 8 && h.chars().all(|c| c.is_ascii_hexdigit()))
        {
            return Err(self.err(
                content_start(value),
                &field,
                "`variants` holds the hashes `check --bless` writes (8 hex digits a variant); \
                 remove it and run `mechbook check --bless` to record them again",
            ));
        }
        Ok(Some((hashes, self.loc.line_col(name.span().start).0)))
    }

    fn claim(
        &self,
        c: &RawClaim,
        offset: usize,
        field: &str,
        names: &BTreeSet<String>,
    ) -> Result<Claim, SceneError> {
        let eq = self.equation_number(&c.eq, field)?;
        let role = self.role(c.role.as_ref(), field)?;
        let expect = self.verdict(c.expect.as_ref(), field)?;
        let quantity = c
            .quantity
            .as_ref()
            .map(|q| self.claim_expr(q, &format!("{field}.quantity"), names))
            .transpose()?;
        let value = c
            .value
            .as_ref()
            .map(|v| self.claim_expr(v, &format!("{field}.value"), names))
            .transpose()?;
        if expect != Some(Verdict::NotCheckable) && (quantity.is_none() || value.is_none()) {
            return Err(self.err(
                offset,
                field,
                "a checkable claim needs both `quantity` and `value` (or expect = \"not-checkable\")",
            ));
        }
        let figures = match &c.figures {
            None => None,
            Some(f) if (1..=15).contains(f.get_ref()) => Some(*f.get_ref() as u32),
            Some(f) => {
                return Err(self.err(
                    f.span().start,
                    &format!("{field}.figures"),
                    "significant figures are a whole number from 1 to 15",
                ));
            }
        };
        let tex = match &c.tex {
            Some(t) => {
                let refused = |why: String| {
                    self.err(
                        content_start(t),
                        &format!("{field}.tex"),
                        format!("`{}` cannot be typeset: {why}", t.get_ref()),
                    )
                };
                if let Some(why) = super::text::latex_problem(t.get_ref()) {
                    return Err(refused(why));
                }
                // Read once, here: every printer takes the tree.
                let read = crate::notation::Tex::read(t.get_ref().trim());
                Some(read.map_err(|e| refused(e.to_string()))?)
            }
            None => None,
        };
        Ok(Claim {
            eq,
            statement: c.statement.get_ref().clone(),
            quantity,
            value,
            figures,
            expect,
            role,
            tex,
            line: self.loc.line_col(offset).0,
        })
    }

    /// A claim's or a step's `eq`: the notes' equation number.
    pub(super) fn equation_number(&self, eq: &Text, field: &str) -> Result<String, SceneError> {
        let text = eq.get_ref();
        // Digits in dot-separated groups, then at most one letter: 31, 22a, 5.1, 5.1a, 3.2.4.
        let digits = text.trim_end_matches(|ch: char| ch.is_ascii_lowercase());
        if digits.is_empty()
            || text.len() > 16
            || !digits
                .split('.')
                .all(|g| !g.is_empty() && g.chars().all(|ch| ch.is_ascii_digit()))
            || text.len() - digits.len() > 1
        {
            return Err(self.err(content_start(eq), &format!("{field}.eq"), "an equation number is digits, in groups separated by dots, with at most one letter after them, as \"31\", \"22a\" or \"5.1a\""));
        }
        Ok(text.clone())
    }

    /// A claim's or a step's `role`: the notes' own statement (the default) or a mistake.
    pub(super) fn role(&self, role: Option<&Text>, field: &str) -> Result<ClaimRole, SceneError> {
        match role.map(|r| r.get_ref().as_str()) {
            None | Some("notes") => Ok(ClaimRole::Notes),
            Some("mistake") => Ok(ClaimRole::Mistake),
            Some(other) => Err(self.err(
                content_start(role.expect("present")),
                &format!("{field}.role"),
                format!("unknown role `{other}`{}; expected `notes` (the notes' statement, the default) or `mistake` (a common mistake for students to spot)", crate::base::suggest::did_you_mean(other, ["notes", "mistake"])),
            )),
        }
    }

    /// A claim's or a step's recorded `expect` verdict.
    pub(super) fn verdict(
        &self,
        expect: Option<&Text>,
        field: &str,
    ) -> Result<Option<Verdict>, SceneError> {
        expect
            .map(|e| match e.get_ref().as_str() {
                "agrees" => Ok(Verdict::Agrees),
                "disagrees" => Ok(Verdict::Disagrees),
                "not-checkable" => Ok(Verdict::NotCheckable),
                "undecided" => Ok(Verdict::Undecided),
                other => Err(self.err(
                    content_start(e),
                    &format!("{field}.expect"),
                    format!(
                        "unknown verdict `{other}`{}; the verdicts are agrees, disagrees, \
                         not-checkable and undecided",
                        crate::base::suggest::did_you_mean(
                            other,
                            ["agrees", "disagrees", "not-checkable", "undecided"]
                        )
                    ),
                )),
            })
            .transpose()
    }

    pub(super) fn claim_expr(
        &self,
        t: &Text,
        field: &str,
        names: &BTreeSet<String>,
    ) -> Result<Expr, SceneError> {
        self.parse_checked(t.get_ref(), content_start(t), field, names, true)
    }
}

/// The functions a claim may call: the elementary ones and those of vectors and matrices.
pub const CLAIM_FUNCTIONS: &[&str] = &[
    "sin",
    "cos",
    "tan",
    "sqrt",
    "exp",
    "log",
    "ln",
    "asin",
    "acos",
    "atan",
    "atan2",
    "sinh",
    "cosh",
    "tanh",
    "abs",
    "diff",
    "subs",
    "dot",
    "cross",
    "outer",
    "transpose",
    "eye",
    "diag",
    "rot_x",
    "rot_y",
    "rot_z",
    "trace",
    "det",
    "sign",
];

/// Checks that every call names a known function with the right number of arguments.
/// A call, list or index the expression's language does not have.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub(super) enum CallError {
    #[error(
        "unknown function `{name}`{hint}; the functions are {}",
        allowed.join(", ")
    )]
    Unknown {
        name: String,
        hint: String,
        allowed: Vec<&'static str>,
    },
    #[error("`{name}` takes {}, got {got}", crate::base::format::count(.arity, "argument"))]
    Arity {
        name: String,
        arity: usize,
        got: usize,
    },
    #[error("a list is not allowed here")]
    List,
    #[error("indexing is not allowed here")]
    Index,
}

pub(super) fn check_calls(e: &Expr, claim_language: bool) -> Result<(), CallError> {
    let mut result = Ok(());
    let allowed: &[&'static str] = if claim_language {
        CLAIM_FUNCTIONS
    } else {
        crate::cas::SCALAR_FUNCTIONS
    };
    fn walk(e: &Expr, allowed: &[&'static str], claim: bool, out: &mut Result<(), CallError>) {
        match e {
            Expr::Call(name, args) => {
                if !allowed.contains(&name.as_str()) {
                    *out = Err(CallError::Unknown {
                        name: name.clone(),
                        hint: super::hints::sympy(name).map_or_else(
                            || crate::base::suggest::did_you_mean(name, allowed.iter().copied()),
                            String::from,
                        ),
                        allowed: allowed.to_vec(),
                    });
                    return;
                }
                let arity = match name.as_str() {
                    "dot" | "cross" | "outer" | "diff" | "atan2" => 2,
                    "diag" | "subs" => 3,
                    "eye" => 0,
                    _ => 1,
                };
                if name != "eye" && args.len() != arity {
                    *out = Err(CallError::Arity {
                        name: name.clone(),
                        arity,
                        got: args.len(),
                    });
                }
                args.iter().for_each(|a| walk(a, allowed, claim, out));
            }
            Expr::List(v) | Expr::Add(v) | Expr::Mul(v) => {
                if !claim && matches!(e, Expr::List(_)) {
                    *out = Err(CallError::List);
                }
                v.iter().for_each(|a| walk(a, allowed, claim, out));
            }
            Expr::Index(a, b) => {
                if !claim {
                    *out = Err(CallError::Index);
                }
                walk(a, allowed, claim, out);
                walk(b, allowed, claim, out);
            }
            Expr::Pow(a, b) => {
                walk(a, allowed, claim, out);
                walk(b, allowed, claim, out);
            }
            Expr::Num(_) | Expr::Sym(_) => {}
        }
    }
    walk(e, allowed, claim_language, &mut result);
    result
}

/// Why `n` in `[expect]` is neither a quantity nor one of `steps`, with the names it may be.
fn not_a_quantity(n: &str, steps: &[String]) -> String {
    format!(
        "`{n}` is not a derived quantity or a step{}; the quantities are {}, {}{}",
        crate::base::suggest::did_you_mean(
            n,
            steps.iter().map(String::as_str).chain(
                body_quantities()
                    .chain(free_body_quantities())
                    .map(|q| -> &str { q })
            )
        ),
        body_quantities().collect::<Vec<_>>().join(", "),
        free_body_quantities().collect::<Vec<_>>().join(", "),
        if steps.is_empty() {
            String::new()
        } else {
            format!("; the steps are {}", steps.join(", "))
        }
    )
}
