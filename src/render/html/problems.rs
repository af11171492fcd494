//! A lecture's problem sheet ([`Sheet`]) in HTML: the student's (statements with each variant's
//! values, space to work, and no answer) and the key (each variant's answers, exact and to four
//! figures).

use super::math;
use super::prose::{author_html, prose_html, unit_html};
use crate::base::format::figures;
use crate::cas::Expr;
use crate::document::words::{listed, numbers_formula};
use crate::document::{KEY_FIGURES, Problem, ROUNDED_FIGURES, Sheet, Variant, answer_words};
use crate::model::catalogue::{quantity, quantity_symbol};
use crate::model::prose::Prose;
use crate::model::value::Value;
use crate::notation::{Formula, Names, Op};
use crate::render::RenderError;
use crate::render::memo::Recall;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

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
pub fn statement_html(statement: &Prose, names: &Names) -> Result<String, RenderError> {
    prose_html(statement, names)
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
            cells
                .iter()
                .map(|&(v, shared)| make(number, p, &p.variants[v], shared))
                .collect::<Result<Vec<P>, RenderError>>()
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

/// The student's sheet: built from the statements and values alone, so no answer reaches it.
pub fn student_sheet(
    sheet: &Sheet,
    memo: &mut Recall,
) -> Result<Vec<SheetVariant<StudentProblem>>, RenderError> {
    sheet_views(sheet, memo, |number, p, v, _| {
        Ok(StudentProblem {
            number,
            title: p.title.clone(),
            title_html: author_html(&p.title)?,
            variant: v.number,
            statement: statement_html(&v.statement, &p.names)?,
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
            let mut answered = key_problem(number, p, &p.variants[a.variant])
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
                title_html: author_html(&p.title)?,
                variant: v.number,
            }
        } else {
            KeyEntry::Answers(key_problem(number, p, v)?)
        })
    })?;
    Ok(AnswerKey { shared, variants })
}

fn key_problem(number: usize, p: &Problem, v: &Variant) -> Result<KeyProblem, RenderError> {
    let names = &p.names;
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
                decimals(&a.exact, &a.exact_numbers, ROUNDED_FIGURES).to_tex(names),
                Some(ROUNDED_FIGURES),
            ),
            false => (a.shown_or_exact().to_tex(names), None),
        };
        let decimal = decimals(&a.exact, &a.exact_numbers, KEY_FIGURES).to_tex(names);
        // Each column read back: the number a grader reads is the variant's answer.
        if let [value] = a.exact_numbers.as_slice() {
            super::guard::printed_number(&exact, *value, figures, spec.line)?;
            super::guard::printed_number(&decimal, *value, Some(KEY_FIGURES), spec.line)?;
        }
        answers.push(KeyAnswer {
            label: spec_label(spec, names)?,
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
        title_html: author_html(&p.title)?,
        variant: v.number,
        values: math::inline(&listed(values).to_tex(names))?,
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
    numbers_formula(shape, n)
}

/// An answer's label as HTML: the author's words, a bare quantity's own, or the expression.
fn spec_label(a: &crate::scene::Answer, names: &Names) -> Result<String, RenderError> {
    match (&a.label, a.bare_quantity()) {
        (Some(words), _) => author_html(&crate::base::format::capitalised(words)),
        (None, Some(q)) => answer_label(q),
        (None, None) => math::inline(&a.value.to_tex(names)),
    }
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
        crate::base::literal::css_string(&format!("{course} · {sheet}"))
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
