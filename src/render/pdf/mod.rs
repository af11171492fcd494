//! The PDF printer of the documents: each lecture's handouts, problem sheet and key, and one
//! paper per student of a roster, written as Typst markup from the same document model as the
//! HTML (formulas by the Typst printers of the expression tree), then typeset in-process
//! (`typeset.rs`, with the cargo feature `pdf`). No file I/O here: `site` writes the bytes.

#[cfg(feature = "pdf")]
mod display_width;
mod handout;
mod markup;
mod sheet;
#[cfg(feature = "pdf")]
pub mod typeset;

use super::memo::Kept;
use super::problems::Recall;
use super::renderer::{Context, Rendered, Renderer};
use super::{RenderError, SiteFiles};
use crate::document::course::Documents;
use crate::document::roster::TooFewVariants;
use crate::scene::Course;
use crate::scene::roster::Roster;
use crate::scene::roster::Student;
use markup::{Markup, preamble};

/// One document to typeset: where it goes, its markup, and the pictures it shows.
#[derive(Debug, Clone)]
pub struct PdfSource {
    /// Relative to the output folder: `pdf/lecture-3-4-student.pdf`.
    pub path: String,
    pub markup: String,
    /// Path (as the markup names it) -> bytes: the plots of an instructor's handout.
    pub images: Vec<(String, Vec<u8>)>,
    /// Where each scene's part of the markup starts (a byte offset), and the scene's file and
    /// line: a Typst error is reported at the scene it falls in.
    pub origins: Vec<(usize, String)>,
}

/// A lecture's PDFs, relative to the site's root.
#[derive(Debug, Clone, serde::Serialize)]
pub struct LecturePdfs {
    pub student: String,
    pub instructor: String,
    /// The problem sheet and its key (none when the course's answers are private), when the
    /// lecture has problems.
    pub problems: Option<(String, Option<String>)>,
}

pub fn lecture_pdfs(slug: &str, has_problems: bool, course: &Course) -> LecturePdfs {
    LecturePdfs {
        student: format!("pdf/{slug}-student.pdf"),
        instructor: format!("pdf/{slug}-instructor.pdf"),
        problems: has_problems.then(|| {
            (
                format!("pdf/{slug}-problems-student.pdf"),
                (!course.answers_private).then(|| format!("pdf/{slug}-problems-key.pdf")),
            )
        }),
    }
}

/// Whether this mechbook writes PDFs (the cargo feature `pdf`).
pub const ENABLED: bool = cfg!(feature = "pdf");

/// Each lecture's handouts, problem sheet and key, as Typst markup: `site/pdfs.rs` typesets
/// them. The instructor's handout shows the HTML's plots (the HTML renderer runs first).
pub struct Pdf;

impl Renderer for Pdf {
    fn render(
        &self,
        docs: &Documents,
        cx: &Context,
        out: &mut Rendered,
    ) -> Result<(), RenderError> {
        if ENABLED {
            for made in site_documents(docs, cx, &out.files)? {
                match made {
                    Lectured::Written(source, kept) => {
                        out.typeset.push(source);
                        out.kept.extend(kept);
                    }
                    Lectured::Later(path) => out.later.push(path),
                }
            }
        }
        Ok(())
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

/// Every lecture's handouts, problem sheet and key, in order. `site` holds the plots the
/// instructor's handout shows.
fn site_documents(
    docs: &Documents,
    cx: &Context,
    site: &SiteFiles,
) -> Result<Vec<Lectured>, RenderError> {
    // Each lecture's documents on both cores, in the lectures' order.
    let made = crate::base::in_order::map_in_order(&docs.lectures, |lecture| {
        lecture_documents(docs, cx, site, lecture)
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
    cx: &Context,
    site: &SiteFiles,
    lecture: &crate::document::course::Lecture,
) -> Result<Vec<Lectured>, RenderError> {
    let course = cx.course;
    let mut out = Vec::new();
    let heading = &lecture.heading;
    let sheet = &lecture.sheet;
    let paths = lecture_pdfs(&lecture.slug, sheet.is_some(), course);
    for handout in &lecture.handouts {
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
            out.push(Lectured::Later(path.clone()));
            continue;
        };
        let images = if instructor {
            parts
                .iter()
                .filter(|(part, _)| part.figures)
                .flat_map(|(_, p)| &p.figures)
                .filter_map(|f| {
                    let bytes = site.get(std::path::Path::new(&f.file))?;
                    Some((f.file.clone(), bytes.clone()))
                })
                .collect()
        } else {
            Vec::new()
        };
        out.push(Lectured::Written(
            made.source(path, images),
            kept.into_iter().collect(),
        ));
    }
    if let (Some(sheet), Some((student, key))) = (sheet, &paths.problems) {
        let all: Vec<(usize, Option<&Student>)> =
            (0..sheet.variants.len()).map(|k| (k, None)).collect();
        // The sheet, then its key (none when the answers are private): written alike.
        let documents: [(Option<&String>, &str, WriteSheet); 2] = [
            (Some(student), "problem sheet", sheet::student_sheet),
            (key.as_ref(), "answer key", sheet::key),
        ];
        for (path, title, write) in documents {
            let Some(path) = path else { continue };
            let mut columns = Recall::of(cx.memo, path);
            let made = written(cx, path, &[heading, sheet], || {
                let head = format!("{} · {heading}: {title}", course.title);
                let mut m =
                    Markup::new(preamble(course, &format!("{heading}: {title}"), &head, ""));
                write(&mut m, &head, sheet, &all, Some(&mut columns))?;
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
    Ok(out)
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
/// their name and ID on every page, the key to all of them in the roster's order, and
/// `variants.csv` (name, id, lecture, variant, paper) for grading. Paths are relative to the
/// papers' folder. Lecture `k`'s variants are dealt with the seed `seed + k`.
pub fn roster_documents(
    docs: &Documents,
    course: &Course,
    roster: &Roster,
    seed: u64,
) -> Result<(Vec<PdfSource>, Vec<u8>), RosterPapersError> {
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
    let mut out = Vec::new();
    let mut csv = String::from("name,id,lecture,variant,paper\n");
    let mut key = Markup::new(preamble(
        course,
        &format!("{}: answer key for the class", course.title),
        &format!("{} · answer key", course.title),
        "",
    ));
    for (i, s) in roster.students.iter().enumerate() {
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
            if i > 0 || j > 0 {
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
    out.push(key.source("key.pdf", Vec::new()));
    Ok((out, csv.into_bytes()))
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
