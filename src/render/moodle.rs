//! A problem as a Moodle XML quiz: one question per variant. A variant with one scalar answer
//! is a `numerical` question; any other is a `cloze` question with one NUMERICAL blank per
//! entry. Values in the text are TeX between `\(` and `\)`, which Moodle's MathJax filter
//! typesets. Each blank's tolerance is absolute: the problem's relative tolerance times the
//! largest entry of its answer, so that a zero entry is not asked for exactly.

use super::RenderError;
use super::renderer::{Context, Plots, Rendered, Renderer};
use crate::document::course::Documents;
use crate::document::quiz::{answer_label, tolerance};
use crate::document::{Problem, Variant};
use crate::model::prose::{Piece, Prose};
use crate::model::value::Value;
use crate::notation::Names;
use std::fmt::Write;

/// Significant figures of an answer and its tolerance in the file.
const DIGITS: usize = 12;

/// Each problem's quiz, `export/moodle/<scene id>.xml`.
pub struct Moodle;

impl Renderer for Moodle {
    fn render(&self, docs: &Documents, _: &Plots, cx: &Context) -> Result<Rendered, RenderError> {
        let mut out = Rendered::default();
        // A quiz holds every variant's answers: none in a site whose answers are private.
        if cx.course.answers_private {
            return Ok(out);
        }
        let base = &cx.course.base_url;
        for (i, problem) in &docs.problems {
            let solution = (!base.is_empty()).then(|| format!("{base}/{}", docs.files[*i]));
            super::renderer::add(
                &mut out.files,
                format!("export/moodle/{}.xml", problem.id),
                quiz(problem, solution.as_deref()).into_bytes(),
            )?;
        }
        Ok(out)
    }
}

/// The quiz of a scene's problem. `solution` is the published address of the scene's worked
/// solution (the course's `base_url`), which the feedback links to.
pub fn quiz(problem: &Problem, solution: Option<&str>) -> String {
    let mut out = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<quiz>\n");
    let _ = writeln!(
        out,
        "  <question type=\"category\">\n    <category><text>$course$/top/mechbook/{}</text></category>\n  </question>",
        xml_text(&problem.id)
    );
    for v in &problem.variants {
        out.push_str(&question(problem, v, solution));
    }
    out.push_str("</quiz>\n");
    out
}

fn question(problem: &Problem, v: &Variant, solution: Option<&str>) -> String {
    let name = format!(
        "{} — variant {}",
        crate::model::prose::plain(&problem.title),
        v.number
    );
    let statement = statement_tex(&v.statement, &problem.names);
    let scalars: usize = v.answers.iter().map(|a| a.exact_numbers.len()).sum();
    let feedback = feedback(problem, v, solution);
    match (v.answers.as_slice(), problem.answers.as_slice()) {
        ([a], [spec]) if scalars == 1 => numerical(&name, &statement, &feedback, a, spec),
        _ => cloze(&name, &statement, &feedback, problem, v),
    }
}

/// A variant of one number: Moodle's numerical question, its unit graded.
fn numerical(
    name: &str,
    statement: &str,
    feedback: &str,
    a: &crate::verify::variants::AnswerCheck,
    spec: &crate::scene::Answer,
) -> String {
    let mut out = String::new();
    let units = match &spec.unit {
        // Graded: a missing or wrong unit costs a tenth of the mark, typed after the number
        // (Moodle's qtype_numerical: unitgradingtype 1 = UNITGRADEDOUTOFMARK, showunits
        // 0 = UNITINPUT, read by its XML import's import_numerical).
        Some(u) => format!(
            "    <unitgradingtype>1</unitgradingtype>\n    <unitpenalty>0.1</unitpenalty>\n    \
             <showunits>0</showunits>\n    <unitsleft>0</unitsleft>\n    <units><unit>\
             <multiplier>1</multiplier><unit_name>{}</unit_name></unit></units>\n",
            xml_text(&u.text)
        ),
        None => String::new(),
    };
    let _ = write!(
        out,
        "  <question type=\"numerical\">\n    <name><text>{}</text></name>\n    \
         <questiontext format=\"html\"><text>{}</text></questiontext>\n    \
         <generalfeedback format=\"html\"><text>{}</text></generalfeedback>\n    \
         <defaultgrade>1</defaultgrade>\n    <penalty>0.3333333</penalty>\n    <hidden>0</hidden>\n    \
         <answer fraction=\"100\" format=\"moodle_auto_format\"><text>{}</text>\
         <feedback format=\"html\"><text></text></feedback><tolerance>{}</tolerance></answer>\n\
         {units}  </question>\n",
        xml_text(name),
        cdata(&format!("<p>{statement}</p>")),
        cdata(feedback),
        number(a.exact_numbers[0]),
        number(tolerance(spec.tolerance, &a.exact_numbers)),
    );
    out
}

/// A variant of several numbers: a cloze question, a blank for each.
fn cloze(name: &str, statement: &str, feedback: &str, problem: &Problem, v: &Variant) -> String {
    let mut out = String::new();
    // Moodle reads a blank wherever the text has `{N:TYPE:`, so what the author wrote (the
    // statement, a label, a unit) has its braces as character references: shown and typeset
    // the same, never read as a blank the key does not have.
    let mut text = format!("<p>{}</p>\n", no_blanks(statement));
    for (spec, a) in problem.answers.iter().zip(&v.answers) {
        let tol = tolerance(spec.tolerance, &a.exact_numbers);
        let unit = spec.unit.as_ref().map_or(String::new(), |u| {
            format!(" {}", no_blanks(&html_escape(&u.text)))
        });
        let blank = |x: f64| format!("{{1:NUMERICAL:={}:{}}}{unit}", number(x), number(tol));
        let _ = writeln!(text, "<p>{}:</p>", no_blanks(&label_tex(spec)));
        match &a.exact {
            Value::Scalar(_) => {
                let _ = writeln!(text, "<p>{}</p>", blank(a.exact_numbers[0]));
            }
            Value::Vector(_) => {
                let cells: Vec<String> = a.exact_numbers.iter().map(|x| blank(*x)).collect();
                let _ = writeln!(text, "<p>( {} )</p>", cells.join(" , "));
            }
            Value::Matrix(_) => {
                text.push_str("<table>\n");
                for row in a.exact_numbers.chunks(3) {
                    let cells: Vec<String> = row
                        .iter()
                        .map(|x| format!("<td>{}</td>", blank(*x)))
                        .collect();
                    let _ = writeln!(text, "<tr>{}</tr>", cells.concat());
                }
                text.push_str("</table>\n");
            }
        }
    }
    let _ = write!(
        out,
        "  <question type=\"cloze\">\n    <name><text>{}</text></name>\n    \
         <questiontext format=\"html\"><text>{}</text></questiontext>\n    \
         <generalfeedback format=\"html\"><text>{}</text></generalfeedback>\n    \
         <penalty>0.3333333</penalty>\n    <hidden>0</hidden>\n  </question>\n",
        xml_text(name),
        cdata(&text),
        cdata(feedback),
    );
    out
}

/// The exact answers, shown after the attempt, and a link to the worked solution when the site's
/// address is known.
fn feedback(problem: &Problem, v: &Variant, solution: Option<&str>) -> String {
    let parts: Vec<String> = problem
        .answers
        .iter()
        .zip(&v.answers)
        .map(|(spec, a)| {
            let unit = spec
                .unit
                .as_ref()
                .map_or(String::new(), |u| format!(" {}", html_escape(&u.text)));
            format!(
                "{}: {}{unit}",
                label_tex(spec),
                tex(&a.exact.to_expr().to_latex(&problem.names))
            )
        })
        .collect();
    let link = solution.map_or(String::new(), |url| {
        format!(
            "<p><a href=\"{}\">The worked solution</a></p>",
            html_escape(url)
        )
    });
    format!("<p>Exactly: {}.</p>{link}", parts.join("; "))
}

/// A label for Moodle's HTML: escaped, its `$…$` as TeX between `\(` and `\)`.
fn label_tex(spec: &crate::scene::Answer) -> String {
    statement_tex(
        &crate::model::prose::author(&answer_label(spec)),
        Names::none(),
    )
}

/// The statement with each value as TeX, the rest escaped for HTML.
fn statement_tex(statement: &Prose, names: &Names) -> String {
    statement
        .0
        .iter()
        .map(|piece| match piece {
            Piece::Text(t) => html_escape(t),
            Piece::Math(f) => tex(&f.to_latex(names)),
        })
        .collect()
}

/// A number as Moodle reads it: plain decimal or `1.5e-7`, never `inf` or `NaN` (those answers
/// fail their check before a quiz is written).
fn number(x: f64) -> String {
    let s = crate::base::format::significant(x, DIGITS);
    if s == "-0" { "0".into() } else { s }
}

/// TeX between `\(` and `\)` in the question's HTML, escaped: Moodle's filter reads the text,
/// so `a<b` must be `a&lt;b` there, not the start of an element.
fn tex(latex: &str) -> String {
    format!("\\({}\\)", html_escape(latex))
}

fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Text for a cloze question's HTML with every brace a character reference, so that none
/// starts a blank (Moodle's `{N:TYPE:…}`).
fn no_blanks(s: &str) -> String {
    s.replace('{', "&#123;").replace('}', "&#125;")
}

fn xml_text(s: &str) -> String {
    html_escape(s)
}

/// Text in a CDATA section; a `]]>` inside is split across two sections.
fn cdata(s: &str) -> String {
    format!("<![CDATA[{}]]>", s.replace("]]>", "]]]]><![CDATA[>"))
}
