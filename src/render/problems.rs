//! A lecture's problem sheets: the student's (statements with each variant's values, space to
//! work, and no answer) and the key (each variant's answers, exact and to four figures). Sheet
//! variant k gives every problem its own variant k, cycling through a problem's fewer ones; the
//! key answers each problem's variant once.

use super::{RenderError, math, page_file};
use crate::base::format::figures;
use crate::model::catalogue::{quantity, quantity_symbol};
use crate::model::value::Value;
use crate::pipeline::SceneReport;
use crate::verify::variants::VariantCheck;
use serde::Serialize;

/// Significant figures of the key's decimals.
pub const KEY_FIGURES: usize = 4;

#[derive(Debug, Clone, Serialize)]
pub struct SheetVariant<P> {
    pub number: usize,
    pub problems: Vec<P>,
}

/// A problem as the student sees it: no answer, not even hidden.
#[derive(Debug, Clone, Serialize)]
pub struct StudentProblem {
    pub number: usize,
    pub title: String,
    /// The problem's own variant that this sheet variant uses.
    pub variant: usize,
    /// HTML: the text escaped, each value as MathML.
    pub statement: String,
}

#[derive(Debug, Clone, Serialize)]
pub struct KeyProblem {
    pub number: usize,
    pub title: String,
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

#[derive(Debug, Clone, Serialize)]
pub struct KeyAnswer {
    pub label: String,
    pub exact: String,
    pub decimal: String,
}

/// The reports with a problem, in the order given.
fn with_problems<'a>(reports: &[&'a SceneReport]) -> Vec<&'a SceneReport> {
    reports
        .iter()
        .copied()
        .filter(|r| r.scene.problem.is_some() && !r.verification.variants.is_empty())
        .collect()
}

/// How many variants the sheet has: as many as its problem with the most.
pub fn sheet_variants(reports: &[&SceneReport]) -> usize {
    with_problems(reports)
        .iter()
        .map(|r| r.verification.variants.len())
        .max()
        .unwrap_or(0)
}

/// Problem `r`'s variant on sheet variant `k` (1-based).
fn variant_on_sheet(r: &SceneReport, k: usize) -> &VariantCheck {
    let v = &r.verification.variants;
    &v[(k - 1) % v.len()]
}

/// The statement with each `{name}` given by `value` (from the variant's LaTeX) and the text
/// between by `text`: for a page, MathML and escaped HTML; for Moodle, TeX and escaped HTML.
pub fn fill_statement(
    statement: &str,
    v: &VariantCheck,
    value: impl Fn(&str) -> Result<String, RenderError>,
    text: impl Fn(&str) -> String,
) -> Result<String, RenderError> {
    let mut out = String::new();
    let mut rest = statement;
    while let Some(open) = rest.find('{') {
        let close = open + rest[open..].find('}').unwrap_or(rest.len() - open);
        out.push_str(&text(&rest[..open]));
        let name = rest.get(open + 1..close).unwrap_or("");
        match v.values.iter().find(|(n, _, _)| n == name) {
            Some((_, _, latex)) => out.push_str(&value(latex)?),
            // Validation allows only declared symbols, and every symbol in a statement has a
            // value in each variant; a template's own text is shown as written.
            None => out.push_str(&text(&format!("{{{name}}}"))),
        }
        rest = rest.get(close + 1..).unwrap_or("");
    }
    out.push_str(&text(rest));
    Ok(out)
}

/// The statement with `{name}` replaced by the variant's value, typeset.
pub fn statement_html(statement: &str, v: &VariantCheck) -> Result<String, RenderError> {
    fill_statement(statement, v, math::inline, tera::escape_html)
}

/// The sheet's variants, each with every problem's `make` at its variant on that sheet.
fn sheet<P>(
    reports: &[&SceneReport],
    make: impl Fn(&SceneReport, usize, &VariantCheck) -> Result<P, RenderError>,
) -> Result<Vec<SheetVariant<P>>, RenderError> {
    let problems = with_problems(reports);
    (1..=sheet_variants(reports))
        .map(|k| {
            let problems = problems
                .iter()
                .enumerate()
                .map(|(i, r)| make(r, i + 1, variant_on_sheet(r, k)).map_err(|e| e.in_scene(r)))
                .collect::<Result<_, RenderError>>()?;
            Ok(SheetVariant {
                number: k,
                problems,
            })
        })
        .collect()
}

/// The student's sheet: built from the statements and values alone, so no answer reaches it.
pub fn student_sheet(
    reports: &[&SceneReport],
) -> Result<Vec<SheetVariant<StudentProblem>>, RenderError> {
    sheet(reports, |r, number, v| {
        let statement = &r.scene.problem.as_ref().expect("filtered").statement;
        Ok(StudentProblem {
            number,
            title: r.scene.title.clone(),
            variant: v.number,
            statement: statement_html(statement, v)?,
        })
    })
}

/// The answer key: each variant of each problem answered once. A problem with as many variants
/// as the sheet is answered in its sheet variant; one with fewer is answered once per variant
/// of its own in `shared`, and the sheet variants name which of them they use (picked at a
/// sheet variant, the key shows just those). (Repeating them cost 20 small problems beside one of 10,000
/// variants a 520 MB key.)
#[derive(Debug, Clone, Serialize)]
pub struct AnswerKey {
    pub shared: Vec<KeyProblem>,
    pub variants: Vec<SheetVariant<KeyEntry>>,
}

/// A problem in a sheet variant of the key: its answers, or which of its shared variants.
#[derive(Debug, Clone, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum KeyEntry {
    Answers(KeyProblem),
    Shared {
        number: usize,
        title: String,
        variant: usize,
    },
}

pub fn answer_key(reports: &[&SceneReport]) -> Result<AnswerKey, RenderError> {
    let count = sheet_variants(reports);
    let mut shared = Vec::new();
    for (i, r) in with_problems(reports).iter().enumerate() {
        if r.verification.variants.len() < count {
            let n = r.verification.variants.len();
            for (j, v) in r.verification.variants.iter().enumerate() {
                let mut answered = key_problem(r, i + 1, v).map_err(|e| e.in_scene(r))?;
                answered.serves = (1..=count).filter(|k| (k - 1) % n == j).collect();
                shared.push(answered);
            }
        }
    }
    let variants = sheet(reports, |r, number, v| {
        Ok(if r.verification.variants.len() < count {
            KeyEntry::Shared {
                number,
                title: r.scene.title.clone(),
                variant: v.number,
            }
        } else {
            KeyEntry::Answers(key_problem(r, number, v)?)
        })
    })?;
    Ok(AnswerKey { shared, variants })
}

fn key_problem(
    r: &SceneReport,
    number: usize,
    v: &VariantCheck,
) -> Result<KeyProblem, RenderError> {
    let values: Vec<String> = v
        .values
        .iter()
        .filter(|(name, _, _)| {
            r.scene
                .problem
                .as_ref()
                .is_some_and(|p| p.statement.contains(&format!("{{{name}}}")))
        })
        .map(|(name, _, latex)| format!("{} = {latex}", crate::cas::Expr::sym(name).to_latex()))
        .collect();
    let mut answers = Vec::new();
    for a in &v.answers {
        answers.push(KeyAnswer {
            label: answer_label(&a.quantity)?,
            exact: math::inline(&a.exact.to_latex())?,
            decimal: math::inline(&decimals(&a.exact, &a.exact_numbers))?,
        });
    }
    let worst = v.answers.iter().map(|a| a.error).fold(0.0f64, f64::max);
    Ok(KeyProblem {
        number,
        title: r.scene.title.clone(),
        variant: v.number,
        values: math::inline(&values.join(",\\; "))?,
        answers,
        page: page_file(r),
        checked: crate::base::format::sci(worst),
        serves: Vec::new(),
    })
}

/// The answer's numbers to [`KEY_FIGURES`] figures, in the shape of the exact value.
pub fn decimals(shape: &Value, numbers: &[f64]) -> String {
    let n: Vec<String> = numbers.iter().map(|x| figures(*x, KEY_FIGURES)).collect();
    super::numbers_latex(shape, &n)
}

/// "Inertia tensor" and its symbol, as HTML.
fn answer_label(name: &str) -> Result<String, RenderError> {
    let (words, symbol) = match name {
        quantity::PRINCIPAL_MOMENTS => ("Principal moments", Some("I_1 \\le I_2 \\le I_3")),
        quantity::PRECESSION_RATE => ("Precession rate", Some("\\Omega")),
        quantity::RADIUS_OF_GYRATION => ("Radius of gyration", Some("k")),
        _ => (
            match name {
                quantity::INERTIA_TENSOR => "Inertia tensor",
                quantity::ANGULAR_MOMENTUM => "Angular momentum",
                quantity::KINETIC_ENERGY => "Kinetic energy",
                quantity::MOMENT_ABOUT_AXIS => "Moment about the axis",
                _ => name,
            },
            quantity_symbol(name),
        ),
    };
    Ok(match symbol {
        Some(s) => format!("{words} {}", math::inline(s)?),
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
/// empty marker before `<main>`), the sheet shows and prints variant N alone: one student's.
pub fn print_css(course: &str, sheet: &str, variants: usize) -> String {
    let mut css = format!(
        "@page {{ margin: 18mm 15mm; @top-left {{ content: {}; font-size: 9pt; }} @bottom-right {{ content: \
         \"page \" counter(page); font-size: 9pt; }} }}\n.pick {{ display: none; }}\n",
        css_string(&format!("{course} · {sheet}"))
    );
    for k in 1..=variants {
        css.push_str(&format!(
            ".variant-{k} {{ page: variant-{k}; }} @page variant-{k} {{ @top-right {{ content: \
             \"Variant {k}\"; font-size: 9pt; font-weight: bold; }} }}\n\
             #variant-{k}:target ~ main .variant:not(.variant-{k}) {{ display: none; }}\n"
        ));
    }
    css
}
