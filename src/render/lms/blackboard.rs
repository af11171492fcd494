//! A lecture's questions as Blackboard's question upload: a tab-separated text file, one `NUM`
//! record a line (`NUM`, the question, the answer, its absolute tolerance), one record per
//! quiz part and variant. Blackboard asks for at most 250 records a file in Ultra (500 in
//! Original), so a lecture with more is split: `<lecture>.txt`, `<lecture>-2.txt`, …. The
//! question is plain text (the upload has no mathematics): the statement with its formulas as
//! text, then what to give and its unit, with `&`, `<` and `>` as HTML's entities.

use super::number;
use crate::document::quiz::{QuizPart, split_file};
use crate::model::prose::{Piece, Prose};
use crate::notation::Names;

/// Records a file, as Blackboard Ultra asks.
pub const RECORDS_A_FILE: usize = 250;

/// The lecture's upload files: name and contents.
pub fn files(slug: &str, parts: &[QuizPart]) -> Vec<(String, Vec<u8>)> {
    let records: Vec<String> = parts
        .iter()
        .flat_map(|part| {
            part.variants.iter().map(move |v| {
                let unit = part
                    .unit
                    .as_deref()
                    .map_or(String::new(), |u| format!(" (in {})", u.replace('*', " ")));
                let question = format!(
                    "{} Answer: {}{unit}. [{}, variant {}]",
                    plain(&v.variant.statement, &part.problem.names),
                    crate::model::prose::plain(&part.label),
                    crate::model::prose::plain(&part.problem.title),
                    v.variant.number,
                );
                format!(
                    "NUM\t{}\t{}\t{}\n",
                    one_field(&question),
                    number(v.answer),
                    number(v.tolerance)
                )
            })
        })
        .collect();
    records
        .chunks(RECORDS_A_FILE)
        .enumerate()
        .map(|(k, chunk)| (split_file(slug, k, "txt"), chunk.concat().into_bytes()))
        .collect()
}

/// A sentence as plain text, each formula as it reads (`ω⃗ = (2, 0, 2)`).
fn plain(prose: &Prose, names: &Names) -> String {
    prose
        .0
        .iter()
        .map(|piece| match piece {
            Piece::Text(t) => t.clone(),
            Piece::Math(f) => f.to_tex(names).to_plain(),
        })
        .collect()
}

/// Text as one field of a record: no tab or line break of the author's may end it, and no
/// `<` of theirs starts markup (Blackboard shows a question's text as HTML).
fn one_field(s: &str) -> String {
    s.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
