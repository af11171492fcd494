//! The HTML renderer: the documents -> the site's pages, handouts, sheets, plots and style
//! sheet through the Tera templates, as bytes in memory. Writing them is `site`'s job.

#[cfg(test)]
mod claim_form_tests;
mod claim_view;
mod guard;
#[cfg(test)]
mod guard_tests;
pub mod handout;
pub mod math;
pub mod page;
mod phone_note;
pub mod problems;
mod prose;

pub use claim_view::ClaimView;
pub use page::{PageView, StepView, page_view};

use super::RenderError;
use super::memo;
use super::renderer::{Context, Plots, Rendered, Renderer, TemplateTexts, add};
use crate::document::course::{Documents, Lecture};
use crate::document::files::{LecturePdfs, PDFS};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use std::sync::OnceLock;

/// The templates, embedded as defaults; a user's folder overrides them file by file.
const DEFAULTS: &[(&str, &str)] = &[
    ("page.html", include_str!("../../../templates/page.html")),
    ("index.html", include_str!("../../../templates/index.html")),
    (
        "handout.html",
        include_str!("../../../templates/handout.html"),
    ),
    (
        "problems-student.html",
        include_str!("../../../templates/problems-student.html"),
    ),
    (
        "problems-key.html",
        include_str!("../../../templates/problems-key.html"),
    ),
    ("style.css", include_str!("../../../templates/style.css")),
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
    pdf: Option<LecturePdfs>,
    pages: Vec<PageLink>,
}

/// The template files a user's folder may replace, by name.
pub fn template_names() -> impl Iterator<Item = &'static str> {
    DEFAULTS.iter().map(|(name, _)| *name)
}

/// The templates: each default, or the user's own text of it (by name), each compiled when
/// first used. A build whose pages, handouts and sheets all come from the memo compiles only
/// the index's; a unit's key holds the user's templates, so a changed one is always used.
struct Templates {
    each: Vec<(&'static str, String, OnceLock<tera::Tera>)>,
}

impl Templates {
    /// The templates, and the style sheet's text.
    fn new(overrides: &TemplateTexts) -> (Templates, String) {
        let mut css = String::new();
        let mut each = Vec::new();
        for (name, default) in DEFAULTS {
            let text = overrides.get(*name).map_or(*default, String::as_str);
            if *name == "style.css" {
                css = text.to_string();
            } else {
                each.push((*name, text.to_string(), OnceLock::new()));
            }
        }
        (Templates { each }, css)
    }

    /// Template `name` (one of [`DEFAULTS`]) filled from `ctx`.
    fn render(&self, name: &str, ctx: &tera::Context) -> Result<String, RenderError> {
        let (_, text, once) = self
            .each
            .iter()
            .find(|(n, ..)| *n == name)
            .expect("a template of DEFAULTS");
        let tera = match once.get() {
            Some(tera) => tera,
            None => {
                let mut tera = tera::Tera::default();
                tera.add_raw_template(name, text)
                    .map_err(|e| RenderError::Template {
                        name: name.to_string(),
                        message: format!("{e:?}"),
                    })?;
                once.get_or_init(|| tera)
            }
        };
        render(tera, name, ctx)
    }
}

fn render(tera: &tera::Tera, name: &str, ctx: &tera::Context) -> Result<String, RenderError> {
    tera.render(name, ctx).map_err(|e| {
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
    tera: &Templates,
    cx: &Context,
    docs: &Documents,
    lecture: &Lecture,
    out: &mut Rendered,
) -> Result<Option<(String, Option<String>)>, RenderError> {
    let course = cx.course;
    let Some(sheet) = &lecture.sheet else {
        return Ok(None);
    };
    let slug = &lecture.slug;
    let heading = &lecture.heading;
    let count = sheet.variants.len();
    let mut paths = Vec::new();
    for (kind, title) in [("student", "problem sheet"), ("key", "answer key")] {
        if kind == "key" && course.answers_private {
            continue;
        }
        let problem_count = lecture
            .pages
            .iter()
            .filter(|&&i| docs.is_problem(i))
            .count();
        let page = format!("{slug}-problems-{kind}");
        let unit = memo::key(&[
            &"sheet",
            &page,
            sheet,
            &lecture.name,
            heading,
            &problem_count,
            course,
            cx.templates,
        ]);
        let mut columns = memo::Recall::of(cx.memo, &page);
        let (html, kept) = memo::recall_or(cx.memo, format!("{page}.html"), unit, || {
            let mut ctx = tera::Context::new();
            ctx.insert("site", course);
            ctx.insert(
                "lecture",
                &serde_json::json!({ "name": lecture.name, "heading": heading }),
            );
            ctx.insert("problems", &problem_count);
            let mut css = problems::print_css(&course.title, &format!("{heading}: {title}"), count);
            // The student's sheet is built from statements and values alone: no answer
            // reaches it.
            if kind == "student" {
                ctx.insert("variants", &problems::student_sheet(sheet, &mut columns)?);
            } else {
                let key = problems::answer_key(sheet, &mut columns)?;
                if !key.shared.is_empty() {
                    css.push_str(&problems::shared_css(count));
                }
                ctx.insert("shared", &key.shared);
                ctx.insert("variants", &key.variants);
            }
            ctx.insert("print_css", &css);
            // A sheet in parts links to its first part's PDF; the index lists every part.
            let pdf = lecture.pdfs.problems.as_ref().and_then(|(sheet, key)| {
                if kind == "student" {
                    Some(sheet)
                } else {
                    key.as_ref()
                }
            });
            ctx.insert("pdf", &pdf.filter(|_| PDFS));
            tera.render(&format!("problems-{kind}.html"), &ctx)
        })?;
        out.kept.extend(kept);
        out.kept.extend(columns.kept);
        let path = format!("handouts/{page}.html");
        add(&mut out.files, PathBuf::from(&path), html.into_bytes())?;
        paths.push(path);
    }
    Ok(Some((paths[0].clone(), paths.get(1).cloned())))
}

/// The site's HTML: index, one page per scene, its plots, two handouts per lecture, each
/// lecture's problem sheet and key, the style sheet.
pub struct Html;

impl Renderer for Html {
    fn render(
        &self,
        docs: &Documents,
        plots: &Plots,
        cx: &Context,
    ) -> Result<Rendered, RenderError> {
        let mut out = Rendered::default();
        html(docs, plots, cx, &mut out)?;
        Ok(out)
    }
}

/// A scene's page as made: its view (which the handouts and the index read), its HTML, and
/// what the build says of it.
#[derive(Serialize, Deserialize)]
struct PageMade {
    view: PageView,
    html: String,
    note: Option<String>,
}

fn html(
    docs: &Documents,
    plots: &Plots,
    cx: &Context,
    out: &mut Rendered,
) -> Result<(), RenderError> {
    let course = cx.course;
    let (tera, css) = Templates::new(cx.templates);
    add(&mut out.files, PathBuf::from("style.css"), css.into_bytes())?;
    for (file, svg) in plots {
        add(
            &mut out.files,
            PathBuf::from(file),
            svg.clone().into_bytes(),
        )?;
    }
    let pages = scene_pages(&tera, docs, cx, out)?;
    let mut lectures: Vec<LectureView> = Vec::new();
    for lecture in &docs.lectures {
        for handout in &lecture.handouts {
            handout_page(&tera, docs, cx, lecture, handout, &pages, out)?;
        }
        let problems = problem_sheets(&tera, cx, docs, lecture, out)?;
        lectures.push(lecture_view(docs, lecture, &pages, problems)?);
    }
    let mut ctx = tera::Context::new();
    ctx.insert("site", course);
    ctx.insert("lectures", &lectures);
    add(
        &mut out.files,
        PathBuf::from("index.html"),
        tera.render("index.html", &ctx)?.into_bytes(),
    )?;
    Ok(())
}

/// Each scene's page, made on both cores and added in the pages' order; their views, which
/// the handouts and the index read.
fn scene_pages(
    tera: &Templates,
    docs: &Documents,
    cx: &Context,
    out: &mut Rendered,
) -> Result<Vec<PageView>, RenderError> {
    let course = cx.course;
    let indices: Vec<usize> = (0..docs.pages.len()).collect();
    let made = crate::base::in_order::map_in_order(&indices, |&i| {
        let page = &docs.pages[i];
        let unit = memo::key(&[
            &"page",
            &cx.keys.of(docs, i),
            course,
            cx.templates,
            &cx.timings,
        ]);
        memo::recall_or(cx.memo, format!("{}.page", page.id), unit, || {
            let view = page_view(page, cx.timings).map_err(|e| e.in_scene(&page.source))?;
            let mut ctx = tera::Context::new();
            ctx.insert("site", course);
            ctx.insert("page", &view);
            ctx.insert("lecture_heading", &course.lecture_heading(&view.lecture));
            let html = tera.render("page.html", &ctx)?;
            let note = phone_note::phone_scaled(page, &html);
            Ok::<_, RenderError>(PageMade { view, html, note })
        })
    });
    let mut pages: Vec<PageView> = Vec::new();
    for (made, file) in made.into_iter().zip(&docs.files) {
        let (made, kept) = made?;
        out.kept.extend(kept);
        out.notes.extend(made.note);
        add(&mut out.files, PathBuf::from(file), made.html.into_bytes())?;
        pages.push(made.view);
    }
    Ok(pages)
}

/// A lecture's handout as a page of the site.
fn handout_page(
    tera: &Templates,
    docs: &Documents,
    cx: &Context,
    lecture: &Lecture,
    handout: &crate::document::course::Handout,
    pages: &[PageView],
    out: &mut Rendered,
) -> Result<(), RenderError> {
    let course = cx.course;
    let slug = &lecture.slug;
    let kind = handout.kind();
    let name = format!("{slug}-{kind}");
    // Its parts, and the pages they are parts of (their views follow from them).
    let parts = cx.keys.of_parts(docs, &handout.parts);
    let unit = memo::key(&[
        &"handout",
        &name,
        &lecture.name,
        &lecture.heading,
        &handout.instructor,
        &parts,
        course,
        cx.templates,
        &cx.timings,
    ]);
    let (html, kept) = memo::recall_or(cx.memo, format!("handouts.{name}.html"), unit, || {
        let mut ctx = tera::Context::new();
        ctx.insert("site", course);
        ctx.insert(
            "lecture",
            &serde_json::json!({ "name": lecture.name, "heading": lecture.heading }),
        );
        ctx.insert("instructor", &handout.instructor);
        let parts = handout
            .parts
            .iter()
            .map(|p| {
                handout::part_view(p, &docs.pages[p.page], &pages[p.page])
                    .map_err(|e| e.in_scene(&docs.pages[p.page].source))
            })
            .collect::<Result<Vec<_>, RenderError>>()?;
        ctx.insert("parts", &parts);
        let pdf = if handout.instructor {
            &lecture.pdfs.instructor
        } else {
            &lecture.pdfs.student
        };
        ctx.insert("pdf", &PDFS.then_some(pdf));
        tera.render("handout.html", &ctx)
    })?;
    out.kept.extend(kept);
    add(
        &mut out.files,
        PathBuf::from(format!("handouts/{name}.html")),
        html.into_bytes(),
    )?;
    Ok(())
}

/// A lecture as the index lists it: its handouts, problem sheets, PDFs and pages.
fn lecture_view(
    docs: &Documents,
    lecture: &Lecture,
    pages: &[PageView],
    problems: Option<(String, Option<String>)>,
) -> Result<LectureView, RenderError> {
    let slug = &lecture.slug;
    Ok(LectureView {
        name: lecture.name.clone(),
        heading: lecture.heading.clone(),
        student: format!("handouts/{slug}-student.html"),
        instructor: format!("handouts/{slug}-instructor.html"),
        pdf: PDFS.then(|| lecture.pdfs.clone()),
        problems,
        pages: lecture
            .pages
            .iter()
            .map(|&i| {
                Ok(PageLink {
                    href: docs.files[i].clone(),
                    title: crate::model::prose::plain(&pages[i].title),
                    title_html: prose::author_html(&pages[i].title)?,
                    errata: pages[i].errata,
                    problem: docs.is_problem(i),
                })
            })
            .collect::<Result<_, RenderError>>()?,
    })
}
