//! The course as documents: every scene's page, each lecture's two handouts and its problem
//! sheet, each problem for Moodle. What each shows is decided here, once; the renderers (HTML,
//! PDF, Moodle) print these documents and decide only how they look.

use super::files::{LecturePdfs, lecture_pdfs};
use super::handout::{Part, part};
use super::{Page, Problem, Sheet, figure_file, page_file, pages, problem, sheet};
use crate::model::figure::Figure;
use crate::pipeline::SceneReport;
use crate::scene::{Course, lecture_slug};

/// The course's documents, built once per build.
pub struct Documents<'a> {
    /// Every scene's page, in the order of the reports.
    pub pages: Vec<Page>,
    /// Each page's file, relative to the site's root (`pages[i]`'s is `files[i]`).
    pub files: Vec<String>,
    /// Each plot: the page it is on, its file, and its data.
    pub figures: Vec<(usize, String, &'a Figure)>,
    /// The lectures in the course's order.
    pub lectures: Vec<Lecture>,
    /// Each problem scene's problem, with its page: one Moodle quiz each.
    pub problems: Vec<(usize, Problem)>,
}

/// One lecture: its pages, its handouts and its problem sheet.
pub struct Lecture {
    /// The lecture's id, as the scenes give it (`3/4`).
    pub name: String,
    /// Its id in file names (`lecture-3-4`).
    pub slug: String,
    pub heading: String,
    /// Its pages, in order (indices into [`Documents::pages`]).
    pub pages: Vec<usize>,
    /// The student's handout, then the instructor's.
    pub handouts: [Handout; 2],
    /// The sheet of its problems' variants, when it has problems with variants.
    pub sheet: Option<Sheet>,
    /// Its PDFs' paths, which the HTML links to when this mechbook writes PDFs.
    pub pdfs: LecturePdfs,
}

/// A lecture's handout: the part of each page it shows, in order.
pub struct Handout {
    pub instructor: bool,
    /// A student's handout leaves the problems to the problem sheet; the instructor's shows
    /// every page. What each part shows of its page is [`handout::part`]'s choice.
    pub parts: Vec<Part>,
}

impl Handout {
    /// `student` or `instructor`, as the handout's file names say.
    pub fn kind(&self) -> &'static str {
        if self.instructor {
            "instructor"
        } else {
            "student"
        }
    }
}

impl Documents<'_> {
    /// Whether page `i` is a problem's.
    pub fn is_problem(&self, i: usize) -> bool {
        self.problems.iter().any(|(j, _)| *j == i)
    }
}

/// The course's documents from the scenes' reports.
pub fn documents<'a>(reports: &'a [SceneReport], course: &Course) -> Documents<'a> {
    let figures = reports
        .iter()
        .enumerate()
        .flat_map(|(i, r)| r.figures.iter().map(move |f| (i, figure_file(r, f), f)))
        .collect();
    let problems: Vec<(usize, Problem)> = reports
        .iter()
        .enumerate()
        .filter_map(|(i, r)| Some((i, problem(r)?)))
        .collect();
    let is_problem = |i: usize| problems.iter().any(|(j, _)| *j == i);
    let pages = pages(reports);
    let lectures = lecture_order(reports, course)
        .into_iter()
        .map(|(name, scenes)| {
            let handout = |instructor: bool| Handout {
                instructor,
                parts: scenes
                    .iter()
                    .copied()
                    .filter(|&i| instructor || !is_problem(i))
                    .map(|i| part(i, &pages[i], instructor))
                    .collect(),
            };
            let sheet = sheet(
                problems
                    .iter()
                    .filter(|(i, _)| scenes.contains(i))
                    .map(|(_, p)| p.clone())
                    .collect(),
            );
            let slug = lecture_slug(&name);
            let variants = sheet.as_ref().map(|s| s.variants.len());
            Lecture {
                pdfs: lecture_pdfs(&slug, variants, course),
                slug,
                heading: course.lecture_heading(&name),
                handouts: [handout(false), handout(true)],
                pages: scenes,
                sheet,
                name,
            }
        })
        .collect();
    Documents {
        pages,
        files: reports.iter().map(page_file).collect(),
        figures,
        lectures,
        problems,
    }
}

/// The lectures in the course's order (`Course::lecture_order`): each lecture's id and the
/// indices of its scenes in `reports`, in their order.
fn lecture_order(reports: &[SceneReport], course: &Course) -> Vec<(String, Vec<usize>)> {
    let appearance: Vec<&str> = reports
        .iter()
        .map(|r| r.scene.notes.lecture.as_str())
        .collect();
    course
        .lecture_order(&appearance)
        .into_iter()
        .map(|name| {
            let scenes = (0..reports.len())
                .filter(|&i| appearance[i] == name)
                .collect();
            (name.to_string(), scenes)
        })
        .collect()
}
