//! A lecture's questions as Canvas Classic Quizzes import them: a QTI 1.2 zip (`imsmanifest.xml`
//! and the assessment, `<lecture>/<lecture>.xml`) with one `calculated_question` per quiz part.
//! Its text is the problem's statement with each given value's place as Canvas's `[name]`, and
//! its `var_sets` hold every variant's values with mechbook's own answer, so Canvas computes
//! nothing (its importer, `Qti::CalculatedInteraction` in canvas-lms, reads `answer_tolerance`,
//! `vars` and `var_sets`; a tolerance ending in `%` is relative). No formula is given: Canvas
//! would generate new variants from one and lose the verified answers.

use super::{escape, number, unit_xhtml, xhtml};
use crate::document::quiz::QuizPart;
use crate::model::prose::author;
use crate::render::RenderError;
use std::fmt::Write;

/// The package of a lecture's parts, as a zip's bytes.
pub fn package(slug: &str, title: &str, parts: &[QuizPart]) -> Result<Vec<u8>, RenderError> {
    let mut items = String::new();
    for part in parts {
        items.push_str(&item(part)?);
    }
    let assessment = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
         <questestinterop xmlns=\"http://www.imsglobal.org/xsd/ims_qtiasiv1p2\">\n  \
         <assessment ident=\"{slug}\" title=\"{}\">\n    <section ident=\"root_section\">\n{items}    \
         </section>\n  </assessment>\n</questestinterop>\n",
        escape(title)
    );
    let manifest = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
         <manifest xmlns=\"http://www.imsglobal.org/xsd/imsccv1p1/imscp_v1p1\" identifier=\"manifest-{slug}\">\n  \
         <metadata>\n    <schema>IMS Content</schema>\n    <schemaversion>1.1.3</schemaversion>\n  \
         </metadata>\n  <organizations/>\n  <resources>\n    \
         <resource identifier=\"{slug}\" type=\"imsqti_xmlv1p2\">\n      \
         <file href=\"{slug}/{slug}.xml\"/>\n    </resource>\n  </resources>\n</manifest>\n"
    );
    Ok(crate::base::zip::stored(&[
        ("imsmanifest.xml".to_string(), manifest.into_bytes()),
        (format!("{slug}/{slug}.xml"), assessment.into_bytes()),
    ]))
}

/// One part as a calculated question, every variant a `var_set`.
fn item(part: &QuizPart) -> Result<String, RenderError> {
    let problem = part.problem;
    let unit = part.unit.as_deref().map_or(String::new(), |u| {
        format!(" (in <span class=\"unit\">{}</span>)", unit_xhtml(u))
    });
    let text = format!(
        "<p>{}</p><p>{}{unit}</p>",
        xhtml(&problem.template, &problem.names)?,
        xhtml(&author(&part.label), crate::notation::Names::none())?
    );
    let mut out = format!(
        "      <item ident=\"{}\" title=\"{}\">\n        <itemmetadata>\n          <qtimetadata>\n            \
         <qtimetadatafield>\n              <fieldlabel>question_type</fieldlabel>\n              \
         <fieldentry>calculated_question</fieldentry>\n            </qtimetadatafield>\n            \
         <qtimetadatafield>\n              <fieldlabel>points_possible</fieldlabel>\n              \
         <fieldentry>1.0</fieldentry>\n            </qtimetadatafield>\n          </qtimetadata>\n        \
         </itemmetadata>\n        <presentation>\n          <material>\n            \
         <mattext texttype=\"text/html\">{}</mattext>\n          </material>\n          \
         <response_str ident=\"response1\" rcardinality=\"Single\">\n            \
         <render_fib fibtype=\"Decimal\">\n              <response_label ident=\"answer1\"/>\n            \
         </render_fib>\n          </response_str>\n        </presentation>\n        <resprocessing>\n          \
         <outcomes>\n            <decvar maxvalue=\"100\" minvalue=\"0\" varname=\"SCORE\" vartype=\"Decimal\"/>\n          \
         </outcomes>\n          <respcondition title=\"correct\">\n            <conditionvar>\n              \
         <other/>\n            </conditionvar>\n            <setvar varname=\"SCORE\" action=\"Set\">100</setvar>\n          \
         </respcondition>\n        </resprocessing>\n        <itemproc_extension>\n          <calculated>\n            \
         <answer_tolerance>{}</answer_tolerance>\n            <vars>\n",
        part.id(),
        escape(&format!(
            "{}: {}",
            crate::model::prose::plain(&problem.title),
            crate::model::prose::plain(&part.label)
        )),
        escape(&text),
        answer_tolerance(part),
    );
    out.push_str(&vars(part));
    out.push_str("            </vars>\n            <var_sets>\n");
    for v in &part.variants {
        let _ = writeln!(
            out,
            "              <var_set ident=\"{}\">",
            v.variant.number
        );
        for given in &v.variant.given {
            let _ = writeln!(
                out,
                "                <var name=\"{}\">{}</var>",
                given.name,
                number(given.number)
            );
        }
        let _ = writeln!(
            out,
            "                <answer>{}</answer>\n              </var_set>",
            number(v.answer)
        );
    }
    out.push_str("            </var_sets>\n          </calculated>\n        </itemproc_extension>\n      </item>\n");
    Ok(out)
}

/// The part's tolerance for Canvas: a percentage where the problem's relative agreement is one
/// of the entry itself at every variant (a scalar answer), else the smallest absolute
/// tolerance of the variants (Canvas takes one for all of them).
fn answer_tolerance(part: &QuizPart) -> String {
    if part.relative_is_exact() {
        return format!("{}%", number(part.relative * 100.0));
    }
    let least = part
        .variants
        .iter()
        .map(|v| v.tolerance)
        .fold(f64::INFINITY, f64::min);
    number(least)
}

/// Each given value's range over the variants, and the decimals it is shown with.
fn vars(part: &QuizPart) -> String {
    let Some(first) = part.variants.first() else {
        return String::new();
    };
    let mut out = String::new();
    for (k, given) in first.variant.given.iter().enumerate() {
        let values: Vec<f64> = part
            .variants
            .iter()
            .filter_map(|v| v.variant.given.get(k).map(|g| g.number))
            .collect();
        let min = values.iter().copied().fold(f64::INFINITY, f64::min);
        let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let scale = values.iter().map(|x| decimals(*x)).max().unwrap_or(0);
        let _ = writeln!(
            out,
            "              <var name=\"{}\" scale=\"{scale}\">\n                <min>{}</min>\n                \
             <max>{}</max>\n              </var>",
            given.name,
            number(min),
            number(max)
        );
    }
    out
}

/// The decimals of a value as written here, at most 10.
fn decimals(x: f64) -> usize {
    let s = number(x);
    match (s.find('.'), s.contains('e')) {
        (Some(dot), false) => (s.len() - dot - 1).min(10),
        _ => 10,
    }
}
