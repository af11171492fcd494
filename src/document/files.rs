//! The course's file names that more than one renderer writes or links to: each lecture's
//! PDFs (the HTML links them, the PDF renderer makes them), decided once with the documents.

use crate::scene::Course;

/// Whether this mechbook writes PDFs (the cargo feature `pdf`).
pub const PDFS: bool = cfg!(feature = "pdf");

/// A lecture's PDFs, relative to the site's root.
#[derive(Debug, Clone, serde::Serialize)]
pub struct LecturePdfs {
    pub student: String,
    pub instructor: String,
    /// The problem sheet and its key (none when the course's answers are private), when the
    /// lecture has problems: the first part's, when they are typeset in parts.
    pub problems: Option<(String, Option<String>)>,
    /// A sheet of more than [`VARIANTS_A_DOCUMENT`] variants: each part's sheet and key and the
    /// variants it holds; empty when the sheet is one document.
    pub problem_parts: Vec<SheetPart>,
    /// Every document of the problem sheet, one or more parts (none without problems).
    #[serde(skip)]
    pub sheets: Vec<SheetPart>,
}

/// One part of a long problem sheet: its sheet, its key, and its first and last variants.
#[derive(Debug, Clone, serde::Serialize)]
pub struct SheetPart {
    pub sheet: String,
    pub key: Option<String>,
    pub first: usize,
    pub last: usize,
}

/// At most this many sheet variants (or a roster's students) are typeset as one document: Typst
/// holds a document's whole layout until its PDF is made, about 0.8 MiB a page, so a sheet of
/// 1,000 variants in one document peaked at 837 MiB, and of 10,000 at 6.9 GB. A longer sheet,
/// or a roster's key, is typeset in parts of this many, each its own PDF.
pub const VARIANTS_A_DOCUMENT: usize = 200;

/// The parts of `n` variants or students: each part's first index and its end (exclusive).
pub fn parts(n: usize) -> Vec<std::ops::Range<usize>> {
    (0..n.div_ceil(VARIANTS_A_DOCUMENT).max(1))
        .map(|k| k * VARIANTS_A_DOCUMENT..((k + 1) * VARIANTS_A_DOCUMENT).min(n))
        .collect()
}

/// The documents of the sheet of `n` variants of the lecture `slug`: one sheet and key, or
/// parts with their number after their name (`lecture-1-problems-student-2.pdf` holds
/// variants 201 to 400).
fn sheet_documents(slug: &str, n: usize, course: &Course) -> Vec<SheetPart> {
    let all = parts(n);
    let one = all.len() == 1;
    all.into_iter()
        .enumerate()
        .map(|(k, range)| {
            let part = if one {
                String::new()
            } else {
                format!("-{}", k + 1)
            };
            SheetPart {
                sheet: format!("pdf/{slug}-problems-student{part}.pdf"),
                key: (!course.answers_private)
                    .then(|| format!("pdf/{slug}-problems-key{part}.pdf")),
                first: range.start + 1,
                last: range.end,
            }
        })
        .collect()
}

/// The PDFs of the lecture `slug`, whose problem sheet has `variants` variants (none when it
/// has no problems).
pub fn lecture_pdfs(slug: &str, variants: Option<usize>, course: &Course) -> LecturePdfs {
    let parts = variants.map_or_else(Vec::new, |n| sheet_documents(slug, n, course));
    LecturePdfs {
        student: format!("pdf/{slug}-student.pdf"),
        instructor: format!("pdf/{slug}-instructor.pdf"),
        problems: parts.first().map(|p| (p.sheet.clone(), p.key.clone())),
        problem_parts: if parts.len() > 1 {
            parts.clone()
        } else {
            Vec::new()
        },
        sheets: parts,
    }
}
