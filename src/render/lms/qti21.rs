//! A lecture's questions as QTI 2.1 content packages: `imsmanifest.xml` and one
//! `assessmentItem` per quiz part and variant (`items/<part>-v<n>.xml`), 5,000 items a package. Each item states the
//! variant's problem with MathML, holds each given value as a template variable (its number,
//! for a system that shows or reuses it), and asks for one float in a `textEntryInteraction`,
//! with the unit after it; its response processing gives the mark to an answer within the
//! part's absolute tolerance of mechbook's exact answer (QTI's `equal`, `toleranceMode`
//! absolute). Each item is valid against the QTI 2.1 schema (tests/cli/lms.rs).

use super::{escape, number, unit_xhtml, xhtml};
use crate::document::quiz::{PartVariant, QuizPart, split_file};
use crate::model::prose::author;
use crate::render::RenderError;
use std::fmt::Write;

const NAMESPACE: &str = "http://www.imsglobal.org/xsd/imsqti_v2p1";
const SCHEMA: &str = "http://www.imsglobal.org/xsd/qti/qtiv2p1/imsqti_v2p1p2.xsd";

/// Items a package: far below a zip's 65,535 files, and a size an LMS's upload takes (about
/// 3 KB an item).
pub const ITEMS_A_PACKAGE: usize = 5_000;

/// The packages of a lecture's parts: `<slug>.zip`, then `<slug>-2.zip`, … of at most
/// [`ITEMS_A_PACKAGE`] items each, as names and zips' bytes.
pub fn packages(slug: &str, parts: &[QuizPart]) -> Result<Vec<(String, Vec<u8>)>, RenderError> {
    let items: Vec<(&QuizPart, &PartVariant)> = parts
        .iter()
        .flat_map(|part| part.variants.iter().map(move |v| (part, v)))
        .collect();
    items
        .chunks(ITEMS_A_PACKAGE)
        .enumerate()
        .map(|(k, chunk)| Ok((split_file(slug, k, "zip"), package(slug, chunk)?)))
        .collect()
}

/// One package of items, as a zip's bytes.
fn package(slug: &str, items: &[(&QuizPart, &PartVariant)]) -> Result<Vec<u8>, RenderError> {
    let mut files = Vec::new();
    let mut resources = String::new();
    for (part, v) in items {
        let id = item_id(part, v);
        let href = format!("items/{id}.xml");
        let _ = writeln!(
            resources,
            "    <resource identifier=\"{id}\" type=\"imsqti_item_xmlv2p1\" href=\"{href}\">\n      \
             <file href=\"{href}\"/>\n    </resource>"
        );
        files.push((href, item(part, v, &id)?.into_bytes()));
    }
    let manifest = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
         <manifest xmlns=\"http://www.imsglobal.org/xsd/imscp_v1p1\" identifier=\"manifest-{slug}\">\n  \
         <metadata>\n    <schema>QTIv2.1 Package</schema>\n    <schemaversion>1.0.0</schemaversion>\n  \
         </metadata>\n  <organizations/>\n  <resources>\n{resources}  </resources>\n</manifest>\n"
    );
    files.insert(0, ("imsmanifest.xml".to_string(), manifest.into_bytes()));
    Ok(crate::base::zip::stored(&files))
}

/// An item's identifier: an XML name, unique in the package.
fn item_id(part: &QuizPart, v: &PartVariant) -> String {
    format!("item-{}-v{}", part.id(), v.variant.number)
}

/// One variant of one part as an `assessmentItem`.
fn item(part: &QuizPart, v: &PartVariant, id: &str) -> Result<String, RenderError> {
    let problem = part.problem;
    let title = format!(
        "{} — variant {}: {}",
        crate::model::prose::plain(&problem.title),
        v.variant.number,
        crate::model::prose::plain(&part.label)
    );
    let mut out = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
         <assessmentItem xmlns=\"{NAMESPACE}\" xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" \
         xsi:schemaLocation=\"{NAMESPACE} {SCHEMA}\" identifier=\"{id}\" title=\"{}\" \
         adaptive=\"false\" timeDependent=\"false\">\n  \
         <responseDeclaration identifier=\"RESPONSE\" cardinality=\"single\" baseType=\"float\">\n    \
         <correctResponse>\n      <value>{}</value>\n    </correctResponse>\n  </responseDeclaration>\n  \
         <outcomeDeclaration identifier=\"SCORE\" cardinality=\"single\" baseType=\"float\">\n    \
         <defaultValue>\n      <value>0</value>\n    </defaultValue>\n  </outcomeDeclaration>\n",
        escape(&title),
        number(v.answer)
    );
    for given in &v.variant.given {
        let _ = writeln!(
            out,
            "  <templateDeclaration identifier=\"given_{}\" cardinality=\"single\" baseType=\"float\" \
             paramVariable=\"false\" mathVariable=\"false\">\n    <defaultValue>\n      \
             <value>{}</value>\n    </defaultValue>\n  </templateDeclaration>",
            given.name,
            number(given.number)
        );
    }
    let unit = part.unit.as_deref().map_or(String::new(), |u| {
        format!(" <span class=\"unit\">{}</span>", unit_xhtml(u))
    });
    let _ = write!(
        out,
        "  <itemBody>\n    <div>{}</div>\n    <p>{}: <textEntryInteraction \
         responseIdentifier=\"RESPONSE\" expectedLength=\"20\"/>{unit}</p>\n  </itemBody>\n  \
         <responseProcessing>\n    <responseCondition>\n      <responseIf>\n        \
         <equal toleranceMode=\"absolute\" tolerance=\"{tol} {tol}\">\n          \
         <variable identifier=\"RESPONSE\"/>\n          <correct identifier=\"RESPONSE\"/>\n        \
         </equal>\n        <setOutcomeValue identifier=\"SCORE\">\n          \
         <baseValue baseType=\"float\">1</baseValue>\n        </setOutcomeValue>\n      \
         </responseIf>\n    </responseCondition>\n  </responseProcessing>\n</assessmentItem>\n",
        xhtml(&v.variant.statement, &problem.names)?,
        xhtml(&author(&part.label), crate::notation::Names::none())?,
        tol = number(v.tolerance),
    );
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cas::Expr;
    use crate::document::quiz::quiz_parts;
    use crate::document::{Problem, Variant};
    use crate::model::prose::Prose;
    use crate::model::value::Value;
    use crate::verify::variants::AnswerCheck;

    /// A problem of `n` variants whose one answer is the variant's number.
    fn problem(n: usize) -> Problem {
        let answer = |k: usize| AnswerCheck {
            quantity: "x".into(),
            exact: Value::Scalar(Expr::int(k as i128)),
            shown: None,
            rounded: false,
            numeric_mode: false,
            exact_numbers: vec![k as f64],
            numeric: vec![k as f64],
            error: 0.0,
            tolerance: 0.0,
        };
        Problem {
            id: "problem-x".into(),
            source: "x.toml".into(),
            line: 1,
            title: "X".into(),
            page: "problem-x.html".into(),
            tolerance: 0.01,
            answers: vec![crate::scene::Answer {
                value: Expr::sym("x"),
                written: "x".into(),
                label: None,
                unit: None,
                tolerance: 0.01,
                line: 1,
            }],
            tex: Default::default(),
            names: Default::default(),
            template: Prose::default(),
            variants: (1..=n)
                .map(|number| Variant {
                    number,
                    statement: Prose::default().text("Find x."),
                    given: Vec::new(),
                    answers: vec![answer(number)],
                })
                .collect(),
        }
    }

    #[test]
    fn a_lecture_of_more_items_than_a_package_takes_is_split() {
        let p = problem(ITEMS_A_PACKAGE + 1);
        let packages = packages("lecture-1", &quiz_parts(&p)).unwrap();
        let names: Vec<&str> = packages.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["lecture-1.zip", "lecture-1-2.zip"]);
        // The end record's count: the manifest and the items.
        let count = |zip: &[u8]| u16::from_le_bytes([zip[zip.len() - 12], zip[zip.len() - 11]]);
        assert_eq!(count(&packages[0].1) as usize, ITEMS_A_PACKAGE + 1);
        assert_eq!(count(&packages[1].1), 2);
        let last = String::from_utf8_lossy(&packages[1].1).into_owned();
        assert!(last.contains(&format!("item-problem-x-1-v{}", ITEMS_A_PACKAGE + 1)));
    }
}
