//! A lecture's problem sheet ([`Sheet`]) in HTML: the student's (statements with each variant's
//! values, space to work, and no answer) and the key (each variant's answers, exact and to four
//! figures).

use super::memo::{Kept, Memo};
use super::{RenderError, math};
use crate::base::format::figures;
use crate::cas::Expr;
use crate::document::{Problem, Sheet, Variant};
use crate::model::catalogue::{quantity, quantity_symbol};
use crate::model::prose::Prose;
use crate::model::value::Value;
use crate::notation::{Formula, Op};
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

/// Significant figures of the key's decimals.
pub const KEY_FIGURES: usize = 4;

/// The figures of an exact answer too long to read (`AnswerCheck::rounded`), in the key's exact
/// column: more than the decimal column's, so a grader can tell a rounding slip from an error.
pub const ROUNDED_FIGURES: usize = 6;

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct SheetVariant<P> {
    pub number: usize,
    pub problems: Vec<P>,
}

/// A problem as the student sees it: no answer, not even hidden.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct StudentProblem {
    pub number: usize,
    pub title: String,
    pub title_html: String,
    /// The problem's own variant that this sheet variant uses.
    pub variant: usize,
    /// HTML: the text escaped, each value as MathML.
    pub statement: String,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct KeyProblem {
    pub number: usize,
    pub title: String,
    pub title_html: String,
    pub variant: usize,
    /// The variant's values, as MathML.
    pub values: String,
    pub answers: Vec<KeyAnswer>,
    /// The worked solution (with symbols), relative to the site's root.
    pub page: String,
    /// The largest relative difference of an answer from its numeric route.
    pub checked: String,
    /// The sheet variants that use this answer when it is shared (none when it is answered in
    /// its sheet variant): picked at one of them, the key shows it alone of its problem.
    pub serves: Vec<usize>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct KeyAnswer {
    pub label: String,
    pub exact: String,
    pub decimal: String,
}

/// A statement as HTML: the text escaped, each value as MathML.
pub fn statement_html(statement: &Prose) -> Result<String, RenderError> {
    super::prose_html(statement)
}

/// The sheet's variants, each with every problem's `make` at its variant on that sheet. Each
/// problem's column (its views in every sheet variant) is a unit of the memo: an edit to one
/// problem makes only its own views again.
fn sheet_views<P: Serialize + DeserializeOwned>(
    sheet: &Sheet,
    memo: &mut Recall,
    make: impl Fn(usize, &Problem, &Variant, bool) -> Result<P, RenderError>,
) -> Result<Vec<SheetVariant<P>>, RenderError> {
    let mut columns = Vec::new();
    for j in 0..sheet.problems.len() {
        let (number, p) = sheet.problem(j);
        let cells: Vec<(usize, bool)> = sheet
            .variants
            .iter()
            .flat_map(|sv| sv.problems.iter().filter(|sp| sp.problem == j))
            .map(|sp| (sp.variant, sp.shared))
            .collect();
        let column = memo.recall_or(&format!("{number}"), &[p, &cells], || {
            crate::notation::typeset_as(&p.tex, || {
                cells
                    .iter()
                    .map(|&(v, shared)| make(number, p, &p.variants[v], shared))
                    .collect::<Result<Vec<P>, RenderError>>()
            })
            .map_err(|e| e.in_scene(&p.source))
        })?;
        columns.push(column.into_iter());
    }
    sheet
        .variants
        .iter()
        .map(|sv| {
            let problems = sv
                .problems
                .iter()
                .map(|sp| columns[sp.problem].next().expect("a view for each cell"))
                .collect();
            Ok(SheetVariant {
                number: sv.number,
                problems,
            })
        })
        .collect()
}

/// A sheet's units in the memo, named `<sheet>-<problem number>` and keyed by their inputs,
/// and those made fresh.
pub struct Recall<'a> {
    pub memo: &'a dyn Memo,
    /// The sheet's file, as its unit names start (`lecture-1-problems-key`).
    pub sheet: String,
    pub kept: Vec<Kept>,
}

impl<'a> Recall<'a> {
    /// The units of the sheet written to `path` (a site path: its `/` become `.`).
    pub fn of(memo: &'a dyn Memo, path: &str) -> Recall<'a> {
        Recall {
            memo,
            sheet: path.replace('/', "."),
            kept: Vec::new(),
        }
    }

    pub(crate) fn recall_or<T: Serialize + DeserializeOwned>(
        &mut self,
        unit: &str,
        inputs: &[&dyn std::fmt::Debug],
        make: impl FnOnce() -> Result<T, RenderError>,
    ) -> Result<T, RenderError> {
        let mut all: Vec<&dyn std::fmt::Debug> = vec![&"sheet-column", &self.sheet];
        all.extend_from_slice(inputs);
        let key = super::memo::key(&all);
        let name = format!("{}-{unit}", self.sheet);
        let (made, kept) = super::memo::recall_or(self.memo, name, key, make)?;
        self.kept.extend(kept);
        Ok(made)
    }
}

/// The student's sheet: built from the statements and values alone, so no answer reaches it.
pub fn student_sheet(
    sheet: &Sheet,
    memo: &mut Recall,
) -> Result<Vec<SheetVariant<StudentProblem>>, RenderError> {
    sheet_views(sheet, memo, |number, p, v, _| {
        Ok(StudentProblem {
            number,
            title: p.title.clone(),
            title_html: super::author_html(&p.title)?,
            variant: v.number,
            statement: statement_html(&v.statement)?,
        })
    })
}

/// The answer key: each variant of each problem answered once. A problem with as many variants
/// as the sheet is answered in its sheet variant; one with fewer is answered once per variant
/// of its own in `shared`, and the sheet variants name which of them they use (picked at a
/// sheet variant, the key shows just those).
#[derive(Debug, Clone, Serialize)]
pub struct AnswerKey {
    pub shared: Vec<KeyProblem>,
    pub variants: Vec<SheetVariant<KeyEntry>>,
}

/// A problem in a sheet variant of the key: its answers, or which of its shared variants.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum KeyEntry {
    Answers(KeyProblem),
    Shared {
        number: usize,
        title: String,
        title_html: String,
        variant: usize,
    },
}

pub fn answer_key(sheet: &Sheet, memo: &mut Recall) -> Result<AnswerKey, RenderError> {
    let shared = sheet
        .shared
        .iter()
        .map(|a| {
            let (number, p) = sheet.problem(a.problem);
            let mut answered = crate::notation::typeset_as(&p.tex, || {
                key_problem(number, p, &p.variants[a.variant])
            })
            .map_err(|e| e.in_scene(&p.source))?;
            answered.serves = a.serves.clone();
            Ok(answered)
        })
        .collect::<Result<_, RenderError>>()?;
    let variants = sheet_views(sheet, memo, |number, p, v, shared| {
        Ok(if shared {
            KeyEntry::Shared {
                number,
                title: p.title.clone(),
                title_html: super::author_html(&p.title)?,
                variant: v.number,
            }
        } else {
            KeyEntry::Answers(key_problem(number, p, v)?)
        })
    })?;
    Ok(AnswerKey { shared, variants })
}

fn key_problem(number: usize, p: &Problem, v: &Variant) -> Result<KeyProblem, RenderError> {
    let values = v.given.iter().map(|g| {
        let mut row = vec![
            Formula::Expr(Expr::sym(&g.name)),
            Formula::Op(Op::Equals),
            g.value.clone(),
        ];
        if let Some(u) = g.unit.as_deref() {
            row.extend([Formula::Op(Op::Thin), crate::model::units::unit_formula(u)]);
        }
        Formula::Row(row)
    });
    let mut answers = Vec::new();
    for (spec, a) in p.answers.iter().zip(&v.answers) {
        let unit = spec
            .unit
            .as_ref()
            .map_or(String::new(), |u| format!(" {}", unit_html(&u.text)));
        let (exact, figures) = match a.rounded {
            true => (
                decimals(&a.exact, &a.exact_numbers, ROUNDED_FIGURES).to_tex(),
                Some(ROUNDED_FIGURES),
            ),
            false => (a.shown_or_exact().to_tex(), None),
        };
        let decimal = decimals(&a.exact, &a.exact_numbers, KEY_FIGURES).to_tex();
        // Each column read back: the number a grader reads is the variant's answer.
        if let [value] = a.exact_numbers.as_slice() {
            super::guard::printed_number(&exact, *value, figures, spec.line)?;
            super::guard::printed_number(&decimal, *value, Some(KEY_FIGURES), spec.line)?;
        }
        answers.push(KeyAnswer {
            label: spec_label(spec)?,
            exact: format!(
                "{}{}{unit}",
                if a.rounded { "≈ " } else { "" },
                math::inline(&exact)?
            ),
            decimal: format!("{}{unit}", math::inline(&decimal)?),
        });
    }
    Ok(KeyProblem {
        number,
        title: p.title.clone(),
        title_html: super::author_html(&p.title)?,
        variant: v.number,
        values: math::inline(&super::listed(values).to_tex())?,
        answers,
        page: p.page.clone(),
        checked: crate::base::format::sci(v.worst_error()),
        serves: Vec::new(),
    })
}

/// The answer's numbers to `digits` figures, in the shape of the exact value.
pub fn decimals(shape: &Value, numbers: &[f64], digits: usize) -> Formula {
    let n: Vec<Formula> = numbers
        .iter()
        .map(|x| Formula::decimal(&figures(*x, digits)))
        .collect();
    super::numbers_formula(shape, n)
}

/// An answer's name in words, as a student reads it: "Moment about the axis".
pub fn answer_words(name: &str) -> &str {
    match name {
        quantity::PRINCIPAL_MOMENTS => "Principal moments",
        quantity::PRECESSION_RATE => "Precession rate",
        quantity::RADIUS_OF_GYRATION => "Radius of gyration",
        quantity::INERTIA_TENSOR => "Inertia tensor",
        quantity::ANGULAR_MOMENTUM => "Angular momentum",
        quantity::KINETIC_ENERGY => "Kinetic energy",
        quantity::MOMENT_ABOUT_AXIS => "Moment about the axis",
        _ => name,
    }
}

/// The order a list or matrix answer's entries are asked in, for a blank per entry.
pub fn answer_order(name: &str) -> Option<&'static str> {
    match name {
        quantity::PRINCIPAL_MOMENTS => Some("in ascending order, I1 ≤ I2 ≤ I3"),
        quantity::ANGULAR_MOMENTUM => Some("its x, y and z components"),
        quantity::INERTIA_TENSOR => Some("rows and columns x, y, z"),
        _ => None,
    }
}

/// An answer's label as HTML: the author's words, a bare quantity's own, or the expression.
fn spec_label(a: &crate::scene::Answer) -> Result<String, RenderError> {
    match (&a.label, a.bare_quantity()) {
        (Some(words), _) => super::author_html(&crate::base::format::capitalised(words)),
        (None, Some(q)) => answer_label(q),
        (None, None) => math::inline(&a.value.to_tex()),
    }
}

/// A unit as HTML: `kg m^2/s` as kg m<sup>2</sup>/s, a `*` as a space.
pub fn unit_html(text: &str) -> String {
    let escaped = tera::escape_html(text).replace('*', " ");
    let mut out = String::new();
    let mut rest = escaped.as_str();
    while let Some(i) = rest.find('^') {
        out.push_str(&rest[..i]);
        let power: String = rest[i + 1..]
            .chars()
            .take_while(|c| c.is_ascii_digit() || *c == '-')
            .collect();
        out.push_str(&format!("<sup>{}</sup>", power.replace('-', "−")));
        rest = &rest[i + 1 + power.len()..];
    }
    out.push_str(rest);
    format!("<span class=\"unit\">{out}</span>")
}

/// "Inertia tensor" and its symbol, as HTML.
fn answer_label(name: &str) -> Result<String, RenderError> {
    let words = answer_words(name);
    let symbol = match name {
        quantity::PRINCIPAL_MOMENTS => Some("I_1 \\le I_2 \\le I_3"),
        quantity::PRECESSION_RATE => Some("\\Omega"),
        quantity::RADIUS_OF_GYRATION => Some("k"),
        _ => quantity_symbol(name),
    };
    Ok(match symbol {
        Some(s) => format!("{words} {}", math::inline(&crate::notation::symbol_tex(s))?),
        None => tera::escape_html(words),
    })
}

/// A CSS string literal: quotes and backslashes escaped, and `<` so that no `</style>` ends it.
pub fn css_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' | '\\' => {
                out.push('\\');
                out.push(c);
            }
            '<' => out.push_str("\\3C "),
            '\n' | '\r' => out.push(' '),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// The key's rules for its shared answers: picked at sheet variant k, it shows of each shared
/// problem the one variant that k uses.
pub fn shared_css(variants: usize) -> String {
    (1..=variants)
        .map(|k| {
            format!(
                "#variant-{k}:target ~ main .shared .key-problem:not(.s-{k}) {{ display: none; }}\n"
            )
        })
        .collect()
}

/// The sheet's print rules: the course and sheet title at the top of every page, and the
/// variant's number at its top right (a named page per variant). Opened at `#variant-N` (an
/// empty marker before `<main>`), the sheet shows and prints variant N alone: one student's,
/// its shared answers (on a key) and its own run on, on pages headed with its number, rather
/// than the shared ones on a page of their own, and without the pointers to them.
pub fn print_css(course: &str, sheet: &str, variants: usize) -> String {
    let mut css = format!(
        "@page {{ margin: 18mm 15mm; @top-left {{ content: {}; font-size: 9pt; }} @bottom-right {{ content: \
         \"page \" counter(page); font-size: 9pt; }} }}\n.pick {{ display: none; }}\n\
         .pick:target ~ main .pointer {{ display: none; }}\n",
        css_string(&format!("{course} · {sheet}"))
    );
    for k in 1..=variants {
        css.push_str(&format!(
            ".variant-{k} {{ page: variant-{k}; }} @page variant-{k} {{ @top-right {{ content: \
             \"Variant {k}\"; font-size: 9pt; font-weight: bold; }} }}\n\
             #variant-{k}:target ~ main .variant:not(.variant-{k}) {{ display: none; }}\n\
             #variant-{k}:target ~ main .shared {{ page: variant-{k}; }}\n\
             #variant-{k}:target ~ main .variant-{k} {{ break-before: auto; page-break-before: auto; }}\n"
        ));
    }
    css
}
