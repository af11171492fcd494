//! The course file, `mechbook.toml` at the course root: the site's title, author, address,
//! output folder and lecture titles. Read with the scenes; every error names its line.

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Why the course file cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum CourseError {
    #[error("{}:{line}:{column}: {message}", path.display())]
    At {
        path: PathBuf,
        line: usize,
        column: usize,
        message: String,
    },
    #[error("cannot read {}: {error}", path.display())]
    Read {
        path: PathBuf,
        error: std::io::Error,
    },
}

/// Course settings, from an optional `mechbook.toml` at the course root.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Course {
    #[serde(default = "default_title")]
    pub title: String,
    #[serde(default)]
    pub author: String,
    /// Where the site will be published (`https://…`, no trailing `/`): the Moodle quizzes
    /// link each question to its worked solution there. The site's own links stay relative.
    #[serde(default)]
    pub base_url: String,
    /// The output folder (default `site`).
    #[serde(default)]
    pub output: Option<PathBuf>,
    /// The paper handouts, sheets and pages print on: `"a4"` (the default) or `"letter"`.
    #[serde(default)]
    pub paper: Paper,
    /// Titles of the lectures: `[[lecture]] id = "3/4"`, `title = "The inertia tensor"`.
    #[serde(default, rename = "lecture")]
    pub lectures: Vec<LectureTitle>,
    /// The file, and where each lecture's `id` is in it, for errors about the lectures.
    #[serde(skip)]
    pub source: Option<(PathBuf, Vec<(usize, usize)>)>,
    /// Set by a build with a roster (never read from the file): the site leaves out every
    /// answer of the variants (the keys and the Moodle quizzes), since the students' papers
    /// name their variants and the site may be published.
    #[serde(skip_deserializing)]
    pub answers_private: bool,
}

/// A paper size, as CSS's `@page { size }` names it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Paper {
    #[default]
    A4,
    Letter,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LectureTitle {
    /// The `notes.lecture` of its scenes.
    pub id: String,
    pub title: String,
}

impl Course {
    /// A `[[lecture]]` whose id no scene has (a typo, or a lecture since renamed), as an error
    /// at its line; `lectures` are the scenes' `notes.lecture`.
    pub fn unused_lecture(
        &self,
        lectures: &std::collections::BTreeSet<&str>,
    ) -> Option<CourseError> {
        let (i, l) = self
            .lectures
            .iter()
            .enumerate()
            .find(|(_, l)| !lectures.contains(l.id.as_str()))?;
        let (path, lines) = self.source.as_ref()?;
        let (line, column) = lines.get(i).copied().unwrap_or((0, 0));
        let known: Vec<&str> = lectures.iter().copied().collect();
        Some(CourseError::At {
            path: path.clone(),
            line,
            column,
            message: format!(
                "field `lecture[{i}].id`: no scene is in lecture `{}`{}; the scenes' lectures \
                 (notes.lecture) are {}: correct the id, or remove this [[lecture]]",
                l.id,
                crate::base::suggest::did_you_mean(&l.id, known.iter().copied()),
                known.join(", ")
            ),
        })
    }

    /// Lecture ids in the course's order: those `mechbook.toml` titles in its order, then the
    /// others in `appearance` order (the order their first scene is found in).
    pub fn lecture_order<'a>(&self, appearance: &[&'a str]) -> Vec<&'a str> {
        let mut out: Vec<&'a str> = Vec::new();
        for id in appearance {
            if !out.contains(id) {
                out.push(id);
            }
        }
        let rank = |id: &str| {
            self.lectures
                .iter()
                .position(|l| l.id == id)
                .unwrap_or(usize::MAX)
        };
        // A stable sort: the untitled keep their order of appearance.
        out.sort_by_key(|id| rank(id));
        out
    }

    /// A lecture's heading: its title from `mechbook.toml`, else "Lecture 3/4" for an id that
    /// starts with a digit, else the id itself ("Bodies of revolution").
    pub fn lecture_heading(&self, id: &str) -> String {
        match self.lectures.iter().find(|l| l.id == id) {
            Some(l) => l.title.clone(),
            None if id.starts_with(|c: char| c.is_ascii_digit()) => format!("Lecture {id}"),
            None => id.to_string(),
        }
    }
}

fn default_title() -> String {
    "Rigid-body mechanics: verified workbook".into()
}

impl Default for Course {
    fn default() -> Course {
        Course {
            title: default_title(),
            author: String::new(),
            base_url: String::new(),
            output: None,
            paper: Paper::A4,
            lectures: Vec::new(),
            source: None,
            answers_private: false,
        }
    }
}

impl Course {
    /// Reads `path` if it exists (the defaults if not); errors name the file, line and column.
    pub fn load(path: &Path) -> Result<Course, CourseError> {
        match std::fs::read_to_string(path) {
            Ok(text) => Course::parse(&text, path),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(Course::default()),
            Err(error) => Err(CourseError::Read {
                path: path.to_path_buf(),
                error,
            }),
        }
    }

    /// The course file's `text`; `path` is where errors say it is.
    pub fn parse(text: &str, path: &Path) -> Result<Course, CourseError> {
        let loc = super::Locator { path, text };
        let at = |offset: usize, message: String| {
            let (line, column) = loc.line_col(offset);
            CourseError::At {
                path: path.to_path_buf(),
                line,
                column,
                message,
            }
        };
        let mut course: Course = toml::from_str(text).map_err(|e| {
            at(
                e.span().map_or(0, |s| s.start),
                e.message().trim().to_string(),
            )
        })?;
        if let Some((offset, why)) = prose_problem(text) {
            return Err(at(offset, why));
        }
        if !course.base_url.is_empty() {
            course.base_url = web_address(&course.base_url).map_err(|why| {
                let offset = toml_edit::ImDocument::parse(text)
                    .ok()
                    .and_then(|d| d.get("base_url").and_then(toml_edit::Item::span))
                    .map_or(0, |s| s.start + 1);
                at(offset, format!("field `base_url`: {why}"))
            })?;
        }
        let id_offsets = lecture_id_offsets(text);
        for (i, l) in course.lectures.iter().enumerate() {
            if let Some(first) = course.lectures[..i].iter().position(|f| f.id == l.id) {
                return Err(at(
                    id_offsets.get(i).copied().unwrap_or(0),
                    format!(
                        "field `lecture[{i}].id`: lecture `{}` is titled twice (first as \
                         lecture[{first}]): keep one",
                        l.id
                    ),
                ));
            }
        }
        let lines = id_offsets.iter().map(|o| loc.line_col(*o)).collect();
        course.source = Some((path.to_path_buf(), lines));
        Ok(course)
    }
}

/// Why `base_url` is not a web address.
#[derive(Debug, thiserror::Error)]
enum BadAddress {
    #[error(
        "`{0}` is not a web address: write where the site is published, such as \
         \"https://example.edu/mechanics\""
    )]
    NotHttp(String),
    #[error("`{0}` is not a web address: it needs a host and no spaces, quotes or brackets")]
    Malformed(String),
}

/// `base_url` checked: an absolute http(s) address, given back without a trailing `/`.
fn web_address(url: &str) -> Result<String, BadAddress> {
    let rest = url
        .strip_prefix("https://")
        .or_else(|| url.strip_prefix("http://"))
        .ok_or_else(|| BadAddress::NotHttp(url.to_string()))?;
    let host = rest.split('/').next().unwrap_or("");
    if host.is_empty()
        || url
            .chars()
            .any(|c| c.is_whitespace() || c.is_control() || "\"<>\\^`{|}".contains(c))
    {
        return Err(BadAddress::Malformed(url.to_string()));
    }
    Ok(url.trim_end_matches('/').to_string())
}

/// Where each `[[lecture]]`'s id is in a course file (the start of its text).
fn lecture_id_offsets(text: &str) -> Vec<usize> {
    let Ok(doc) = toml_edit::ImDocument::parse(text) else {
        return Vec::new();
    };
    doc.get("lecture")
        .and_then(toml_edit::Item::as_array_of_tables)
        .map(|a| {
            a.iter()
                .map(|t| {
                    t.get("id")
                        .and_then(toml_edit::Item::span)
                        .map_or(0, |s| s.start + 1)
                })
                .collect()
        })
        .unwrap_or_default()
}

/// The first title or author in a course file with a control character (TeX that TOML read
/// as an escape), where it is and why: the same rule as a scene's prose.
fn prose_problem(text: &str) -> Option<(usize, String)> {
    let doc = toml_edit::ImDocument::parse(text).ok()?;
    let mut fields: Vec<(String, &toml_edit::Item)> = ["title", "author"]
        .iter()
        .filter_map(|k| doc.get(k).map(|i| (k.to_string(), i)))
        .collect();
    if let Some(lectures) = doc
        .get("lecture")
        .and_then(toml_edit::Item::as_array_of_tables)
    {
        for (i, l) in lectures.iter().enumerate() {
            if let Some(t) = l.get("title") {
                fields.push((format!("lecture[{i}].title"), t));
            }
        }
    }
    fields.into_iter().find_map(|(field, item)| {
        let value = item.as_str()?;
        let span = item.span()?;
        let why = super::control_character(value, text.get(span.clone())?, false)?;
        Some((span.start + 1, format!("field `{field}`: {why}")))
    })
}

#[cfg(test)]
mod tests {
    use super::{Course, CourseError};
    use std::path::Path;

    #[test]
    fn a_course_file_is_read_from_text_with_its_errors_located() {
        let path = Path::new("mechbook.toml");
        let course = Course::parse(
            "title = \"Mechanics\"\n[[lecture]]\nid = \"3/4\"\ntitle = \"Inertia\"\n",
            path,
        )
        .unwrap();
        assert_eq!(course.lecture_heading("3/4"), "Inertia");
        assert_eq!(course.lecture_heading("3/9"), "Lecture 3/9");
        // Titled lectures first, in the course file's order; the rest as they appear.
        assert_eq!(
            course.lecture_order(&["10", "3/9", "6", "3/4", "10"]),
            ["3/4", "10", "3/9", "6"]
        );
        let twice =
            "[[lecture]]\nid = \"3/4\"\ntitle = \"A\"\n[[lecture]]\nid = \"3/4\"\ntitle = \"B\"\n";
        match Course::parse(twice, path) {
            Err(CourseError::At { line, message, .. }) => {
                assert_eq!(line, 5);
                assert!(message.contains("titled twice"), "{message}");
            }
            other => panic!("expected an error at line 5, got {other:?}"),
        }
        assert!(matches!(
            Course::parse("base_url = \"example.edu\"\n", path),
            Err(CourseError::At { line: 1, .. })
        ));
    }
}
