//! Reports -> the site's files (HTML, CSS) through the Tera templates, as bytes in memory.
//! Writing them is `site`'s job.

use super::RenderError;
use super::{PageView, page_view, plot, problems};
use crate::document::{figure_file, page_file};
use crate::pipeline::SceneReport;
use crate::scene::Course;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// The site as relative path -> contents, sorted: what `site` writes.
pub type SiteFiles = BTreeMap<PathBuf, Vec<u8>>;

/// Adds a file to the site; one that is already there is an error, never replaced.
fn add(files: &mut SiteFiles, path: impl Into<PathBuf>, bytes: Vec<u8>) -> Result<(), RenderError> {
    use std::collections::btree_map::Entry;
    match files.entry(path.into()) {
        Entry::Vacant(v) => {
            v.insert(bytes);
            Ok(())
        }
        Entry::Occupied(o) => Err(RenderError::Collision {
            path: o.key().clone(),
        }),
    }
}

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

#[derive(Serialize)]
struct PageLink {
    href: String,
    title: String,
    title_html: String,
    errata: usize,
    /// A problem scene: listed under the lecture's problems, after its derivations.
    problem: bool,
}

#[derive(Serialize)]
struct LectureView {
    name: String,
    heading: String,
    student: String,
    instructor: String,
    /// The problem sheet and its key (none when the answers are private), when the lecture
    /// has problems.
    problems: Option<(String, Option<String>)>,
    /// The same as PDFs, when this mechbook writes them.
    pdf: Option<super::pdf::LecturePdfs>,
    pages: Vec<PageLink>,
}

/// A user's own templates: name -> text, each replacing the default of that name.
pub type TemplateTexts = BTreeMap<String, String>;

/// The template files a user's folder may replace, by name.
pub fn template_names() -> impl Iterator<Item = &'static str> {
    DEFAULTS.iter().map(|(name, _)| *name)
}

/// The templates: each default, or the user's own text of it from `overrides` (by name).
fn templates(overrides: &TemplateTexts) -> Result<(tera::Tera, String), RenderError> {
    let mut tera = tera::Tera::default();
    let mut css = String::new();
    for (name, default) in DEFAULTS {
        let text = overrides.get(*name).map_or(*default, String::as_str);
        if *name == "style.css" {
            css = text.to_string();
        } else {
            tera.add_raw_template(name, text)
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
) -> Result<Option<(String, Option<String>)>, RenderError> {
    let Some(sheet) = crate::document::sheet(
        reports
            .iter()
            .filter_map(|r| crate::document::problem(r))
            .collect(),
    ) else {
        return Ok(None);
    };
    let count = sheet.variants.len();
    let slug = crate::scene::lecture_slug(lecture);
    let heading = course.lecture_heading(lecture);
    let mut paths = Vec::new();
    for (kind, title) in [("student", "problem sheet"), ("key", "answer key")] {
        if kind == "key" && course.answers_private {
            continue;
        }
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
            ctx.insert("variants", &problems::student_sheet(&sheet)?);
        } else {
            let key = problems::answer_key(&sheet)?;
            if !key.shared.is_empty() {
                css.push_str(&problems::shared_css(count));
            }
            ctx.insert("shared", &key.shared);
            ctx.insert("variants", &key.variants);
        }
        ctx.insert("print_css", &css);
        ctx.insert(
            "pdf",
            &super::pdf::ENABLED.then(|| format!("pdf/{slug}-problems-{kind}.pdf")),
        );
        let path = format!("handouts/{slug}-problems-{kind}.html");
        add(
            files,
            PathBuf::from(&path),
            render(tera, &format!("problems-{kind}.html"), &ctx)?,
        )?;
        paths.push(path);
    }
    Ok(Some((paths[0].clone(), paths.get(1).cloned())))
}

/// Every file of the site: index, one page per scene, its plots, two handouts per lecture, the
/// stylesheet.
pub fn site_files(
    reports: &[SceneReport],
    course: &Course,
    template_overrides: &TemplateTexts,
    timings: bool,
) -> Result<SiteFiles, RenderError> {
    let (tera, css) = templates(template_overrides)?;
    let mut files = SiteFiles::new();
    add(&mut files, PathBuf::from("style.css"), css.into_bytes())?;
    let mut pages: Vec<PageView> = Vec::new();
    for (r, page) in reports.iter().zip(crate::document::pages(reports)) {
        let view = page_view(&page, timings).map_err(|e| e.in_scene(&page.source))?;
        for fig in &r.figures {
            let svg = plot::svg(fig).map_err(|e| e.in_scene(&page.source))?;
            add(
                &mut files,
                PathBuf::from(figure_file(r, fig)),
                svg.into_bytes(),
            )?;
        }
        let mut ctx = tera::Context::new();
        ctx.insert("site", course);
        ctx.insert("page", &view);
        ctx.insert("lecture_heading", &course.lecture_heading(&view.lecture));
        add(
            &mut files,
            PathBuf::from(page_file(r)),
            render(&tera, "page.html", &ctx)?,
        )?;
        pages.push(view);
    }
    // Lectures in the course's order: as mechbook.toml lists them, the rest as they appear.
    let mut lectures: Vec<LectureView> = Vec::new();
    for (name, idx) in &super::lectures(reports, course) {
        let slug = crate::scene::lecture_slug(name);
        for instructor in [false, true] {
            let mut ctx = tera::Context::new();
            ctx.insert("site", course);
            ctx.insert(
                "lecture",
                &serde_json::json!({ "name": name, "heading": course.lecture_heading(name) }),
            );
            ctx.insert("instructor", &instructor);
            // A student's handout leaves the problems to the problem sheet.
            let chosen: Vec<&PageView> = idx
                .iter()
                .filter(|&&i| instructor || reports[i].scene.problem.is_none())
                .map(|&i| &pages[i])
                .collect();
            ctx.insert("pages", &chosen);
            let kind = if instructor { "instructor" } else { "student" };
            ctx.insert(
                "pdf",
                &super::pdf::ENABLED.then(|| format!("pdf/{slug}-{kind}.pdf")),
            );
            let file = format!(
                "handouts/{slug}-{}.html",
                if instructor { "instructor" } else { "student" }
            );
            add(
                &mut files,
                PathBuf::from(file),
                render(&tera, "handout.html", &ctx)?,
            )?;
        }
        let chosen: Vec<&SceneReport> = idx.iter().map(|&i| &reports[i]).collect();
        let problems = problem_sheets(&tera, course, name, &chosen, &mut files)?;
        lectures.push(LectureView {
            name: name.clone(),
            heading: course.lecture_heading(name),
            student: format!("handouts/{slug}-student.html"),
            instructor: format!("handouts/{slug}-instructor.html"),
            pdf: super::pdf::ENABLED
                .then(|| super::pdf::lecture_pdfs(&slug, problems.is_some(), course)),
            problems,
            pages: idx
                .iter()
                .map(|&i| {
                    Ok(PageLink {
                        href: page_file(&reports[i]),
                        title: pages[i].title.clone(),
                        title_html: super::author_html(&pages[i].title)?,
                        errata: pages[i].errata,
                        problem: reports[i].scene.problem.is_some(),
                    })
                })
                .collect::<Result<_, RenderError>>()?,
        });
    }
    // Moodle's quizzes hold every variant's answers: not in a site whose answers are private.
    for r in reports.iter().filter(|_| !course.answers_private) {
        let solution =
            (!course.base_url.is_empty()).then(|| format!("{}/{}", course.base_url, page_file(r)));
        if let Some(xml) =
            crate::document::problem(r).map(|p| super::moodle::quiz(&p, solution.as_deref()))
        {
            add(
                &mut files,
                PathBuf::from(format!("export/moodle/{}.xml", r.scene.id)),
                xml.into_bytes(),
            )?;
        }
    }
    let mut ctx = tera::Context::new();
    ctx.insert("site", course);
    ctx.insert("lectures", &lectures);
    add(
        &mut files,
        PathBuf::from("index.html"),
        render(&tera, "index.html", &ctx)?,
    )?;
    Ok(files)
}
