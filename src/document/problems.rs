//! A scene's problem and a lecture's problem sheet, format-neutral: the student's sheet, the
//! answer key and the Moodle quiz all print these. Sheet variant k gives every problem its own
//! variant k, cycling through a problem's fewer ones; the key answers each problem's variant
//! once.

use super::page_file;
use crate::model::catalogue::quantity;
use crate::model::prose::Prose;
use crate::notation::Formula;
use crate::pipeline::SceneReport;
use crate::verify::variants::{AnswerCheck, VariantCheck};

/// A scene's problem: its variants, each with its statement and checked answers.
#[derive(Debug, Clone)]
pub struct Problem {
    pub id: String,
    /// The scene file and its `[problem]`'s line, for errors.
    pub source: std::path::PathBuf,
    pub line: usize,
    pub title: String,
    /// The worked solution (with symbols), relative to the site's root.
    pub page: String,
    /// A quiz answer's tolerance, relative to the answer.
    pub tolerance: f64,
    /// What each answer is: its value as written, label, unit and tolerance.
    pub answers: Vec<crate::scene::Answer>,
    pub variants: Vec<Variant>,
    /// How the scene typesets its names (name -> LaTeX), where it says.
    pub tex: std::collections::BTreeMap<String, String>,
    /// The same, read once: what every printer of the problem sets each name as.
    pub names: crate::notation::Names,
    /// The statement with each value's place marked `[name]`, for the LMSs that put in each
    /// variant's values themselves (Canvas's calculated question).
    pub template: Prose,
}

#[derive(Debug, Clone)]
pub struct Variant {
    pub number: usize,
    /// The statement with each `{name}` given by this variant's value.
    pub statement: Prose,
    /// The values the statement names, in its order, for the key.
    pub given: Vec<Given>,
    pub answers: Vec<AnswerCheck>,
}

/// A value the statement gives: its name, as the author wrote it, and its unit's text.
#[derive(Debug, Clone)]
pub struct Given {
    pub name: String,
    pub value: Formula,
    /// The value in f64, for the LMSs that store it as a number.
    pub number: f64,
    pub unit: Option<String>,
}

impl Variant {
    /// The largest relative difference of an answer from its numeric route.
    pub fn worst_error(&self) -> f64 {
        self.answers.iter().map(|a| a.error).fold(0.0f64, f64::max)
    }
}

/// The problem of a scene that has one.
pub fn problem(r: &SceneReport) -> Option<Problem> {
    let p = r.scene.problem.as_ref()?;
    Some(Problem {
        id: r.scene.id.clone(),
        source: r.scene.source.clone(),
        line: p.at.0,
        title: r.scene.title.clone(),
        page: page_file(r),
        tolerance: p.tolerance,
        answers: p.answers.clone(),
        tex: r.scene.tex.clone(),
        names: r.scene.names(),
        template: template_statement(&p.statement, &p.given),
        variants: r
            .verification
            .variants
            .iter()
            .map(|v| Variant {
                number: v.number,
                statement: fill_statement(&p.statement, v),
                given: p
                    .given
                    .iter()
                    .cloned()
                    .filter_map(|name| {
                        Some(Given {
                            value: shown(v, &name)?,
                            number: number(v, &name),
                            unit: r.scene.units.get(&name).map(|u| u.text.clone()),
                            name,
                        })
                    })
                    .collect(),
                answers: v.answers.clone(),
            })
            .collect(),
    })
}

/// The statement with each `{name}` replaced by the variant's value, and its `$…$`
/// mathematics kept as the author's LaTeX (a `{name}` inside it given the value's LaTeX).
pub(super) fn fill_statement(statement: &str, v: &VariantCheck) -> Prose {
    let mut out = Prose::default();
    for (k, part) in crate::model::prose::dollar_split(statement)
        .iter()
        .enumerate()
    {
        if k % 2 == 1 {
            out = out.formula(filled_math(part, v));
            continue;
        }
        let mut rest = part.as_str();
        while let Some(open) = rest.find('{') {
            let close = open + rest[open..].find('}').unwrap_or(rest.len() - open);
            out = out.text(&rest[..open]);
            let name = rest.get(open + 1..close).unwrap_or("");
            out = match shown(v, name) {
                Some(f) => out.formula(f),
                // Validation allows only declared symbols, and every symbol in a statement has
                // a value in each variant; a template's own text is shown as written.
                None => out.text(&format!("{{{name}}}")),
            };
            rest = rest.get(close + 1..).unwrap_or("");
        }
        if !rest.is_empty() {
            out = out.text(rest);
        }
    }
    out
}

/// An author's `$…$` at a variant's values: read once, with each `{name}` of a value marked,
/// and the values' trees put in at the marks; its source (for Moodle and `--json`) is the LaTeX
/// with each value's LaTeX in its braces.
fn filled_math(latex: &str, v: &VariantCheck) -> Formula {
    use crate::notation::{Tex, latex};
    let none = crate::notation::Names::none();
    let source = fill_math(latex, v, &mut |f| format!("{{{}}}", f.to_latex(none)));
    let mut values = Vec::new();
    let marked = fill_math(latex, v, &mut |f| {
        values.push(f.to_tex(none).nodes);
        latex::mark(values.len() - 1)
    });
    match Tex::read(&marked) {
        Ok(t) => Formula::Tex(Tex {
            source,
            nodes: latex::fill_marks(&t.nodes, &values),
        }),
        // Validation has read every `$…$` of a statement already.
        Err(_) => Formula::author(&source),
    }
}

/// LaTeX with each `{name}` of a value replaced by `paste(its formula)`; other groups as
/// written.
fn fill_math(latex: &str, v: &VariantCheck, paste: &mut dyn FnMut(Formula) -> String) -> String {
    let mut out = String::new();
    let mut rest = latex;
    while let Some(open) = rest.find('{') {
        out.push_str(&rest[..open]);
        let after = &rest[open + 1..];
        match after
            .find('}')
            .and_then(|c| Some((c, shown(v, &after[..c])?)))
        {
            Some((close, value)) => {
                out.push_str(&paste(value));
                rest = &after[close + 1..];
            }
            None => {
                out.push('{');
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// A variant's value in f64 (every value a variant draws is a number; NaN would say otherwise,
/// and no LMS export could hold it).
fn number(v: &VariantCheck, name: &str) -> f64 {
    v.values
        .iter()
        .find(|(n, _)| n == name)
        .and_then(|(_, e)| e.eval(&|_| None).ok())
        .unwrap_or(f64::NAN)
}

/// The statement with each `{name}` of a value given (`given`) as `[name]`: in text as
/// written, in `$…$` as `\text{[name]}`.
fn template_statement(statement: &str, given: &[String]) -> Prose {
    let mark = |part: &str, math: bool| {
        given.iter().fold(part.to_string(), |s, name| {
            let place = format!("[{name}]");
            s.replace(
                &format!("{{{name}}}"),
                &if math {
                    format!("\\text{{{place}}}")
                } else {
                    place
                },
            )
        })
    };
    let mut out = Prose::default();
    for (k, part) in crate::model::prose::dollar_split(statement)
        .iter()
        .enumerate()
    {
        out = if k % 2 == 1 {
            out.formula(Formula::author(&mark(part, true)))
        } else if part.is_empty() {
            out
        } else {
            out.text(&mark(part, false))
        };
    }
    out
}

/// A variant's value as the author wrote it (see [`crate::scene::shown_value`]).
fn shown(v: &VariantCheck, name: &str) -> Option<Formula> {
    let (_, e) = v.values.iter().find(|(n, _)| n == name)?;
    let decimal = v.decimal.iter().any(|d| d == name);
    Some(crate::scene::shown_value(e, decimal))
}

/// A lecture's problem sheet: as many variants as its problem with the most.
#[derive(Debug, Clone)]
pub struct Sheet {
    /// The problems with a variant, in order: problem `i` is number `i + 1` on the sheet.
    pub problems: Vec<Problem>,
    pub variants: Vec<SheetVariant>,
    /// The variants of the problems with fewer variants than the sheet, each answered once in
    /// the key. (Repeating them cost 20 small problems beside one of 10,000 variants a 520 MB
    /// key.)
    pub shared: Vec<SharedAnswer>,
}

/// Sheet variant `number`: each problem at one of its variants.
#[derive(Debug, Clone)]
pub struct SheetVariant {
    pub number: usize,
    pub problems: Vec<SheetProblem>,
}

/// A problem on one sheet variant: indices into [`Sheet::problems`] and its variants.
#[derive(Debug, Clone, Copy)]
pub struct SheetProblem {
    pub problem: usize,
    pub variant: usize,
    /// Whether the key answers it among the shared answers, not in this sheet variant.
    pub shared: bool,
}

/// A shared variant, and the sheet variants that use it.
#[derive(Debug, Clone)]
pub struct SharedAnswer {
    pub problem: usize,
    pub variant: usize,
    pub serves: Vec<usize>,
}

impl Sheet {
    /// A problem's number on the sheet, and the problem.
    pub fn problem(&self, i: usize) -> (usize, &Problem) {
        (i + 1, &self.problems[i])
    }
}

/// The sheet of a lecture's problems, in the order given; `None` when none has a variant.
pub fn sheet(problems: Vec<Problem>) -> Option<Sheet> {
    let problems: Vec<Problem> = problems
        .into_iter()
        .filter(|p| !p.variants.is_empty())
        .collect();
    let count = problems.iter().map(|p| p.variants.len()).max()?;
    let variants = (1..=count)
        .map(|k| SheetVariant {
            number: k,
            problems: problems
                .iter()
                .enumerate()
                .map(|(i, p)| SheetProblem {
                    problem: i,
                    variant: (k - 1) % p.variants.len(),
                    shared: p.variants.len() < count,
                })
                .collect(),
        })
        .collect();
    let mut shared = Vec::new();
    for (i, p) in problems.iter().enumerate() {
        let n = p.variants.len();
        if n < count {
            for j in 0..n {
                shared.push(SharedAnswer {
                    problem: i,
                    variant: j,
                    serves: (1..=count).filter(|k| (k - 1) % n == j).collect(),
                });
            }
        }
    }
    Some(Sheet {
        problems,
        variants,
        shared,
    })
}

/// Significant figures of the key's decimals.
pub const KEY_FIGURES: usize = 4;

/// The figures of an exact answer too long to read (`AnswerCheck::rounded`), in the key's exact
/// column: more than the decimal column's, so a grader can tell a rounding slip from an error.
pub const ROUNDED_FIGURES: usize = 6;

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
