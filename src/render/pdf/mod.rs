//! The PDF printer of the documents: each lecture's handouts, problem sheet and key, and one
//! paper per student of a roster, written as Typst markup from the same document model as the
//! HTML (formulas by the Typst printers of the expression tree), then typeset in-process
//! (`typeset.rs`, with the cargo feature `pdf`). No file I/O here: `site` writes the bytes.

pub mod batch;
#[cfg(feature = "pdf")]
mod display_width;
#[cfg(feature = "pdf")]
mod glyphs;
mod handout;
mod markup;
mod quantities;
#[cfg(feature = "pdf")]
mod queue;
mod sheet;
#[cfg(feature = "pdf")]
pub mod typeset;

use super::RenderError;
use super::memo::Kept;
use super::memo::Recall;
use super::renderer::{Context, Plots, Rendered, Renderer};
use crate::document::course::Documents;
use crate::document::roster::TooFewVariants;
use crate::scene::Course;
use crate::scene::roster::Roster;
use crate::scene::roster::Student;
use markup::{Markup, preamble};

pub use super::renderer::PdfSource;
use crate::document::files::{PDFS, VARIANTS_A_DOCUMENT, parts};

/// What a part holds, as its title says: `variants 201 to 400`, or `variant 401` alone.
fn which_of(noun: &str, first: usize, last: usize) -> String {
    if first == last {
        format!("{noun} {first}")
    } else {
        format!("{noun}s {first} to {last}")
    }
}

/// Each lecture's handouts, problem sheet and key, as Typst markup: `site/pdfs.rs` typesets
/// them. The instructor's handout shows the course's plots.
pub struct Pdf;

impl Renderer for Pdf {
    fn render(
        &self,
        docs: &Documents,
        plots: &Plots,
        cx: &Context,
    ) -> Result<Rendered, RenderError> {
        let mut out = Rendered::default();
        if PDFS {
            for made in site_documents(docs, plots, cx)? {
                match made {
                    Lectured::Written(source, kept) => {
                        out.typeset.push(source);
                        out.kept.extend(kept);
                    }
                    Lectured::Later(path) => out.later.push(path),
                }
            }
        }
        Ok(out)
    }
}

/// A lecture's document, as this build leaves it.
enum Lectured {
    /// Its markup, with the units made fresh for it (for the memo).
    Written(PdfSource, Vec<Kept>),
    /// Its path: its markup is not in the memo and the build is page-first
    /// ([`Context::pdfs_later`]).
    Later(String),
}

/// Every lecture's handouts, problem sheet and key, in order, with the plots the instructor's
/// handouts show.
fn site_documents(
    docs: &Documents,
    plots: &Plots,
    cx: &Context,
) -> Result<Vec<Lectured>, RenderError> {
    // Each lecture's documents on both cores, in the lectures' order.
    let made = crate::base::in_order::map_in_order(&docs.lectures, |lecture| {
        lecture_documents(docs, plots, cx, lecture)
    });
    let mut all = Vec::new();
    for m in made {
        all.extend(m?);
    }
    Ok(all)
}

/// A document's markup, and where each scene's part of it starts: what the memo keeps of it.
#[derive(serde::Serialize, serde::Deserialize)]
struct Written {
    markup: String,
    origins: Vec<(usize, String)>,
}

impl Written {
    fn of(m: Markup) -> Written {
        let s = m.source("", Vec::new());
        Written {
            markup: s.markup,
            origins: s.origins,
        }
    }

    fn source(self, path: &str, images: Vec<(String, Vec<u8>)>) -> PdfSource {
        PdfSource {
            path: path.to_string(),
            markup: self.markup,
            images,
            origins: self.origins,
        }
    }
}

/// The document at `path` from the memo when its inputs are unchanged, else `write`'s; `None`
/// when it is not in the memo and the build is page-first.
fn written(
    cx: &Context,
    path: &str,
    inputs: &[&dyn std::fmt::Debug],
    write: impl FnOnce() -> Result<Markup, RenderError>,
) -> Result<Option<(Written, Option<Kept>)>, RenderError> {
    let mut all: Vec<&dyn std::fmt::Debug> = vec![&"pdf", &path, cx.course];
    all.extend_from_slice(inputs);
    let unit = super::memo::key(&all);
    let name = path.replace('/', ".");
    if cx.pdfs_later {
        return Ok(super::memo::recall(cx.memo, &name, unit).map(|w| (w, None)));
    }
    super::memo::recall_or(cx.memo, name, unit, || write().map(Written::of)).map(Some)
}

/// How a problem sheet or its key is written (`sheet::student_sheet`, `sheet::key`).
type WriteSheet = fn(
    &mut Markup,
    &str,
    &crate::document::Sheet,
    &[(usize, Option<&Student>)],
    Option<&mut Recall>,
) -> Result<(), RenderError>;

/// A lecture's handouts, problem sheet and key.
fn lecture_documents(
    docs: &Documents,
    plots: &Plots,
    cx: &Context,
    lecture: &crate::document::course::Lecture,
) -> Result<Vec<Lectured>, RenderError> {
    let mut out = Vec::new();
    for handout in &lecture.handouts {
        out.push(handout_document(docs, plots, cx, lecture, handout)?);
    }
    if let Some(sheet) = &lecture.sheet {
        sheet_documents(cx, lecture, sheet, &mut out)?;
    }
    Ok(out)
}

/// A lecture's handout for the student or the instructor, with the plots the instructor's
/// shows.
fn handout_document(
    docs: &Documents,
    plots: &Plots,
    cx: &Context,
    lecture: &crate::document::course::Lecture,
    handout: &crate::document::course::Handout,
) -> Result<Lectured, RenderError> {
    let course = cx.course;
    let heading = &lecture.heading;
    let paths = &lecture.pdfs;
    let instructor = handout.instructor;
    let (title, right, path) = if instructor {
        (
            format!("{heading}: worked solutions and errata"),
            "Instructor",
            &paths.instructor,
        )
    } else {
        (format!("{heading}: summary"), "Student", &paths.student)
    };
    let parts: Vec<(&crate::document::handout::Part, &crate::document::Page)> = handout
        .parts
        .iter()
        .map(|p| (p, &docs.pages[p.page]))
        .collect();
    let keyed = cx.keys.of_parts(docs, &handout.parts);
    let made = written(cx, path, &[&title, heading, &right, &keyed], || {
        let mut m = Markup::new(preamble(
            course,
            &title,
            &course_head(course, heading),
            right,
        ));
        m.heading(1, &title)?;
        handout::handout(&mut m, &parts, instructor)?;
        Ok(m)
    })?;
    let Some((made, kept)) = made else {
        return Ok(Lectured::Later(path.clone()));
    };
    let images = if instructor {
        parts
            .iter()
            .filter(|(part, _)| part.figures)
            .flat_map(|(_, p)| &p.figures)
            .filter_map(|f| {
                let svg = plots.get(&f.file)?;
                Some((f.file.clone(), svg.clone().into_bytes()))
            })
            .collect()
    } else {
        Vec::new()
    };
    Ok(Lectured::Written(
        made.source(path, images),
        kept.into_iter().collect(),
    ))
}

/// The lecture's problem sheet and its key, in parts when it is long.
fn sheet_documents(
    cx: &Context,
    lecture: &crate::document::course::Lecture,
    sheet: &crate::document::Sheet,
    out: &mut Vec<Lectured>,
) -> Result<(), RenderError> {
    let course = cx.course;
    let heading = &lecture.heading;
    let parts = &lecture.pdfs.sheets;
    let in_parts = parts.len() > 1;
    for part in parts {
        let which: Vec<(usize, Option<&Student>)> =
            (part.first - 1..part.last).map(|k| (k, None)).collect();
        // Which variants, when the sheet is in parts.
        let of = if in_parts {
            format!(", {}", which_of("variant", part.first, part.last))
        } else {
            String::new()
        };
        // The sheet, then its key (none when the answers are private): written alike.
        let documents: [(Option<&String>, &str, WriteSheet); 2] = [
            (Some(&part.sheet), "problem sheet", sheet::student_sheet),
            (part.key.as_ref(), "answer key", sheet::key),
        ];
        for (path, title, write) in documents {
            let Some(path) = path else { continue };
            let mut columns = Recall::of(cx.memo, path);
            let made = written(cx, path, &[heading, sheet], || {
                let head = format!("{} · {heading}: {title}{of}", course.title);
                let mut m = Markup::new(preamble(
                    course,
                    &format!("{heading}: {title}{of}"),
                    &head,
                    "",
                ));
                write(&mut m, &head, sheet, &which, Some(&mut columns))?;
                Ok(m)
            })?;
            let Some((made, kept)) = made else {
                out.push(Lectured::Later(path.clone()));
                continue;
            };
            columns.kept.extend(kept);
            out.push(Lectured::Written(
                made.source(path, Vec::new()),
                columns.kept,
            ));
        }
    }
    Ok(())
}

fn course_head(course: &Course, heading: &str) -> String {
    format!("{} · {heading}", course.title)
}

/// Why a roster's papers could not be made.
#[derive(Debug, thiserror::Error)]
pub enum RosterPapersError {
    #[error(transparent)]
    TooFewVariants(#[from] TooFewVariants),
    #[error(
        "{}: no lecture has a problem sheet, so there is nothing to hand out: give a scene a \
         [problem] with variants",
        .0.display()
    )]
    NoSheet(std::path::PathBuf),
    #[error(transparent)]
    Render(#[from] RenderError),
}

/// The roster's papers: one PDF per student with their variant of every lecture's sheet and
/// their name and ID on every page, the key to all of them in the roster's order (`key.pdf`,
/// or `key-1.pdf`, `key-2.pdf`, … of [`VARIANTS_A_DOCUMENT`] students each), and
/// `variants.csv` (name, id, lecture, variant, paper) for grading. Paths are relative to the
/// papers' folder. Lecture `k`'s variants are dealt with the seed `seed + k`.
pub fn roster_documents(
    docs: &Documents,
    course: &Course,
    roster: &Roster,
    seed: u64,
) -> Result<(Vec<PdfSource>, Vec<u8>), RosterPapersError> {
    let sheets = dealt_sheets(docs, roster, seed)?;
    let mut out = Vec::new();
    let mut csv = String::from("name,id,lecture,variant,paper\n");
    // The class key, in parts of at most VARIANTS_A_DOCUMENT students (`key-2.pdf` holds
    // students 201 to 400), each typeset alone, so that memory does not grow with the class.
    let key_parts = parts(roster.students.len());
    let in_parts = key_parts.len() > 1;
    let key_part = |k: usize| {
        let (first, last) = (key_parts[k].start + 1, key_parts[k].end);
        let of = if in_parts {
            format!(", {}", which_of("student", first, last))
        } else {
            String::new()
        };
        Markup::new(preamble(
            course,
            &format!("{}: answer key for the class{of}", course.title),
            &format!("{} · answer key{of}", course.title),
            "",
        ))
    };
    let key_file = |k: usize| {
        if in_parts {
            format!("key-{}.pdf", k + 1)
        } else {
            "key.pdf".to_string()
        }
    };
    let mut key = key_part(0);
    let mut keys = Vec::new();
    for (i, s) in roster.students.iter().enumerate() {
        let part = i / VARIANTS_A_DOCUMENT;
        if i > 0 && i % VARIANTS_A_DOCUMENT == 0 {
            let done = std::mem::replace(&mut key, key_part(part));
            keys.push(done.source(&key_file(part - 1), Vec::new()));
        }
        let first_of_part = i % VARIANTS_A_DOCUMENT == 0;
        let file = format!("{:03}-{}.pdf", i + 1, file_safe(&s.id));
        let mut paper = Markup::new(preamble(
            course,
            &format!("{}: problems for {}", course.title, s.name),
            &course.title,
            "",
        ));
        for (j, (name, sheet, given)) in sheets.iter().enumerate() {
            let heading = course.lecture_heading(name);
            let head = format!("{} · {heading}", course.title);
            if j > 0 {
                paper.raw("#pagebreak()\n");
            }
            sheet::student_sheet(&mut paper, &head, sheet, &[(given[i], Some(s))], None)?;
            if !first_of_part || j > 0 {
                key.raw("#pagebreak()\n");
            }
            sheet::key(&mut key, &head, sheet, &[(given[i], Some(s))], None)?;
            csv.push_str(&format!(
                "{},{},{},{},{file}\n",
                csv_field(&s.name),
                csv_field(&s.id),
                csv_field(name),
                sheet.variants[given[i]].number
            ));
        }
        out.push(paper.source(&file, Vec::new()));
    }
    keys.push(key.source(&key_file(key_parts.len() - 1), Vec::new()));
    out.extend(keys);
    Ok((out, csv.into_bytes()))
}

/// A lecture's name, its sheet, and each student's variant of it (by the roster's order).
type DealtSheet<'a> = (&'a String, &'a crate::document::Sheet, Vec<usize>);

/// Each lecture's sheet with the variant each student of the roster has of it; none is an
/// error, since a roster is for the problem sheets.
fn dealt_sheets<'a>(
    docs: &'a Documents,
    roster: &Roster,
    seed: u64,
) -> Result<Vec<DealtSheet<'a>>, RosterPapersError> {
    let mut sheets = Vec::new();
    for (k, lecture) in docs.lectures.iter().enumerate() {
        if let Some(sheet) = &lecture.sheet {
            let given = crate::document::roster::assign(
                roster,
                sheet,
                &lecture.name,
                seed.wrapping_add(k as u64),
            )?;
            sheets.push((&lecture.name, sheet, given));
        }
    }
    if sheets.is_empty() {
        return Err(RosterPapersError::NoSheet(roster.source.clone()));
    }
    Ok(sheets)
}

/// An id as part of a file name: letters, digits, `-`, `_` and `.` kept, the rest `_`.
fn file_safe(id: &str) -> String {
    let s: String = id
        .chars()
        .take(40)
        .map(|c| {
            if c.is_ascii_alphanumeric() || "-_".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() { "student".into() } else { s }
}

/// A CSV field, quoted when it needs to be. A field a spreadsheet would take for a formula
/// (`=…`, `+…`, `-…`, `@…`) starts with `'`, so that opening the file runs nothing.
fn csv_field(s: &str) -> String {
    let s = if s.starts_with(['=', '+', '-', '@', '\t', '\r']) {
        format!("'{s}")
    } else {
        s.to_string()
    };
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s
    }
}

#[cfg(all(test, feature = "pdf"))]
mod tests;
