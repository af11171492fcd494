//! Reports -> the site's files (HTML, CSS) through the Tera templates, as bytes in memory.
//! Writing them is `site`'s job.

use super::RenderError;
use super::{PageView, figure_file, page_file, page_view, plot, problems};
use crate::pipeline::SceneReport;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The site as relative path -> contents, sorted: what `site` writes.
pub type SiteFiles = BTreeMap<PathBuf, Vec<u8>>;

/// The templates, embedded as defaults; a user's folder overrides them file by file.
const DEFAULTS: &[(&str, &str)] = &[
    ("page.html", include_str!("../../templates/page.html")),
    ("index.html", include_str!("../../templates/index.html")),
    ("handout.html", include_str!("../../templates/handout.html")),
    (
        "problems-student.html",
        include_str!("../../templates/problems-student.html"),
    ),
    (
        "problems-key.html",
        include_str!("../../templates/problems-key.html"),
    ),
    ("style.css", include_str!("../../templates/style.css")),
];

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
    /// Titles of the lectures: `[[lecture]] id = "3/4"`, `title = "The inertia tensor"`.
    #[serde(default, rename = "lecture")]
    pub lectures: Vec<LectureTitle>,
    /// The file, and where each lecture's `id` is in it, for errors about the lectures.
    #[serde(skip)]
    pub source: Option<(PathBuf, Vec<(usize, usize)>)>,
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
    ) -> Option<RenderError> {
        let (i, l) = self
            .lectures
            .iter()
            .enumerate()
            .find(|(_, l)| !lectures.contains(l.id.as_str()))?;
        let (path, lines) = self.source.as_ref()?;
        let (line, column) = lines.get(i).copied().unwrap_or((0, 0));
        let known: Vec<&str> = lectures.iter().copied().collect();
        Some(RenderError::Course {
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
            lectures: Vec::new(),
            source: None,
        }
    }
}

impl Course {
    /// Reads `path` if it exists; errors name the file, line and column.
    pub fn load(path: &Path) -> Result<Course, RenderError> {
        match std::fs::read_to_string(path) {
            Ok(text) => {
                let at = |offset: usize, message: String| {
                    let (line, column) =
                        crate::scene::Locator { path, text: &text }.line_col(offset);
                    RenderError::Course {
                        path: path.to_path_buf(),
                        line,
                        column,
                        message,
                    }
                };
                let mut course: Course = toml::from_str(&text).map_err(|e| {
                    at(
                        e.span().map_or(0, |s| s.start),
                        e.message().trim().to_string(),
                    )
                })?;
                if let Some((offset, why)) = prose_problem(&text) {
                    return Err(at(offset, why));
                }
                if !course.base_url.is_empty() {
                    course.base_url = web_address(&course.base_url).map_err(|why| {
                        let offset = toml_edit::ImDocument::parse(text.as_str())
                            .ok()
                            .and_then(|d| d.get("base_url").and_then(toml_edit::Item::span))
                            .map_or(0, |s| s.start + 1);
                        at(offset, format!("field `base_url`: {why}"))
                    })?;
                }
                let id_offsets = lecture_id_offsets(&text);
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
                let loc = crate::scene::Locator { path, text: &text };
                let lines = id_offsets.iter().map(|o| loc.line_col(*o)).collect();
                course.source = Some((path.to_path_buf(), lines));
                Ok(course)
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(Course::default()),
            Err(error) => Err(RenderError::Read {
                path: path.to_path_buf(),
                error,
            }),
        }
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
        let why = crate::scene::control_character(value, text.get(span.clone())?, false)?;
        Some((span.start + 1, format!("field `{field}`: {why}")))
    })
}

#[derive(Serialize)]
struct PageLink {
    href: String,
    title: String,
    errata: usize,
}

#[derive(Serialize)]
struct LectureView {
    name: String,
    heading: String,
    student: String,
    instructor: String,
    /// The problem sheet and its key, when the lecture has problems.
    problems: Option<(String, String)>,
    pages: Vec<PageLink>,
}

fn templates(dir: Option<&Path>) -> Result<(tera::Tera, String), RenderError> {
    let mut tera = tera::Tera::default();
    let mut css = String::new();
    for (name, default) in DEFAULTS {
        let text = match dir.map(|d| d.join(name)).filter(|p| p.exists()) {
            Some(p) => std::fs::read_to_string(&p).map_err(|error| RenderError::Read {
                path: p.clone(),
                error,
            })?,
            None => default.to_string(),
        };
        if *name == "style.css" {
            css = text;
        } else {
            tera.add_raw_template(name, &text)
                .map_err(|e| RenderError::Template {
                    name: name.to_string(),
                    message: format!("{e:?}"),
                })?;
        }
    }
    Ok((tera, css))
}

fn render(tera: &tera::Tera, name: &str, ctx: &tera::Context) -> Result<Vec<u8>, RenderError> {
    tera.render(name, ctx).map(String::into_bytes).map_err(|e| {
        let mut message = e.to_string();
        let mut source = std::error::Error::source(&e);
        while let Some(s) = source {
            message.push_str(&format!(": {s}"));
            source = s.source();
        }
        RenderError::Template {
            name: name.to_string(),
            message,
        }
    })
}

/// A lecture's problem sheet and answer key, when it has problems: their paths.
fn problem_sheets(
    tera: &tera::Tera,
    course: &Course,
    lecture: &str,
    reports: &[&SceneReport],
    files: &mut SiteFiles,
) -> Result<Option<(String, String)>, RenderError> {
    let count = problems::sheet_variants(reports);
    if count == 0 {
        return Ok(None);
    }
    let slug = crate::scene::lecture_slug(lecture);
    let heading = course.lecture_heading(lecture);
    let mut paths = Vec::new();
    for (kind, title) in [("student", "problem sheet"), ("key", "answer key")] {
        let mut ctx = tera::Context::new();
        ctx.insert("site", course);
        ctx.insert(
            "lecture",
            &serde_json::json!({ "name": lecture, "heading": heading }),
        );
        ctx.insert(
            "problems",
            &reports.iter().filter(|r| r.scene.problem.is_some()).count(),
        );
        let mut css = problems::print_css(&course.title, &format!("{heading}: {title}"), count);
        // The student's sheet is built from statements and values alone: no answer reaches it.
        if kind == "student" {
            ctx.insert("variants", &problems::student_sheet(reports)?);
        } else {
            let key = problems::answer_key(reports)?;
            if !key.shared.is_empty() {
                css.push_str(&problems::shared_css(count));
            }
            ctx.insert("shared", &key.shared);
            ctx.insert("variants", &key.variants);
        }
        ctx.insert("print_css", &css);
        let path = format!("handouts/{slug}-problems-{kind}.html");
        files.insert(
            PathBuf::from(&path),
            render(tera, &format!("problems-{kind}.html"), &ctx)?,
        );
        paths.push(path);
    }
    Ok(Some((paths[0].clone(), paths[1].clone())))
}

/// Every file of the site: index, one page per scene, its plots, two handouts per lecture, the
/// stylesheet.
pub fn site_files(
    reports: &[SceneReport],
    course: &Course,
    template_dir: Option<&Path>,
    timings: bool,
) -> Result<SiteFiles, RenderError> {
    let (tera, css) = templates(template_dir)?;
    let mut files = SiteFiles::new();
    files.insert(PathBuf::from("style.css"), css.into_bytes());
    let mut pages: Vec<PageView> = Vec::new();
    for (i, r) in reports.iter().enumerate() {
        let prev = i.checked_sub(1).map(|j| &reports[j]);
        let view = page_view(r, prev, reports.get(i + 1), timings).map_err(|e| e.in_scene(r))?;
        for fig in &r.figures {
            let svg = plot::svg(fig).map_err(|e| e.in_scene(r))?;
            files.insert(PathBuf::from(figure_file(r, fig)), svg.into_bytes());
        }
        let mut ctx = tera::Context::new();
        ctx.insert("site", course);
        ctx.insert("page", &view);
        ctx.insert("lecture_heading", &course.lecture_heading(&view.lecture));
        files.insert(
            PathBuf::from(page_file(r)),
            render(&tera, "page.html", &ctx)?,
        );
        pages.push(view);
    }
    // Lectures in the order their first scene appears.
    let mut lectures: BTreeMap<usize, LectureView> = BTreeMap::new();
    let mut by_lecture: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (i, r) in reports.iter().enumerate() {
        by_lecture
            .entry(r.scene.notes.lecture.clone())
            .or_default()
            .push(i);
    }
    for (name, idx) in &by_lecture {
        let slug = crate::scene::lecture_slug(name);
        for instructor in [false, true] {
            let mut ctx = tera::Context::new();
            ctx.insert("site", course);
            ctx.insert(
                "lecture",
                &serde_json::json!({ "name": name, "heading": course.lecture_heading(name) }),
            );
            ctx.insert("instructor", &instructor);
            let chosen: Vec<&PageView> = idx.iter().map(|&i| &pages[i]).collect();
            ctx.insert("pages", &chosen);
            let file = format!(
                "handouts/{slug}-{}.html",
                if instructor { "instructor" } else { "student" }
            );
            files.insert(PathBuf::from(file), render(&tera, "handout.html", &ctx)?);
        }
        let chosen: Vec<&SceneReport> = idx.iter().map(|&i| &reports[i]).collect();
        let problems = problem_sheets(&tera, course, name, &chosen, &mut files)?;
        lectures.insert(
            idx[0],
            LectureView {
                name: name.clone(),
                heading: course.lecture_heading(name),
                student: format!("handouts/{slug}-student.html"),
                instructor: format!("handouts/{slug}-instructor.html"),
                problems,
                pages: idx
                    .iter()
                    .map(|&i| PageLink {
                        href: page_file(&reports[i]),
                        title: pages[i].title.clone(),
                        errata: pages[i].errata,
                    })
                    .collect(),
            },
        );
    }
    for r in reports {
        let solution =
            (!course.base_url.is_empty()).then(|| format!("{}/{}", course.base_url, page_file(r)));
        if let Some(xml) = super::moodle::quiz(r, solution.as_deref()) {
            files.insert(
                PathBuf::from(format!("export/moodle/{}.xml", r.scene.id)),
                xml.into_bytes(),
            );
        }
    }
    let mut ctx = tera::Context::new();
    ctx.insert("site", course);
    ctx.insert("lectures", &lectures.into_values().collect::<Vec<_>>());
    files.insert(
        PathBuf::from("index.html"),
        render(&tera, "index.html", &ctx)?,
    );
    Ok(files)
}
