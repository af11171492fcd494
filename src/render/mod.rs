//! The renderers of the course's documents, siblings behind one trait (`renderer.rs`): the
//! HTML site (`html/`), Moodle's quizzes (`moodle.rs`), the other LMSs' (`lms/`), the JSON
//! export (`json.rs`) and the PDFs (`pdf/`, with their typesetting). None imports another: what they share is the
//! documents, the plots drawn once (`plot.rs`) and the memo (`memo.rs`). The files are made in
//! memory: no file I/O here.

pub mod html;
pub mod json;
pub mod lms;
pub mod memo;
pub mod moodle;
pub mod pdf;
pub mod plot;
pub mod renderer;

pub use html::template_names;
pub use renderer::{Context, Rendered, Renderer, SiteFiles, TemplateTexts};

/// Every format a build writes.
pub const RENDERERS: &[&dyn Renderer] = &[
    &html::Html,
    &moodle::Moodle,
    &lms::Lms,
    &json::JsonReport,
    &pdf::Pdf,
];

/// The documents printed by every renderer, with the plots drawn once for all of them.
pub fn render(
    docs: &crate::document::course::Documents,
    cx: &Context,
) -> Result<Rendered, RenderError> {
    let (plots, kept) = plot::draw_all(docs, cx)?;
    let mut out = Rendered {
        kept,
        ..Rendered::default()
    };
    for r in RENDERERS {
        out.absorb(r.render(docs, &plots, cx)?)?;
    }
    Ok(out)
}

/// Why a page, a plot or the course settings could not be rendered.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error("template {name}: {message}")]
    Template { name: String, message: String },
    #[error("cannot render `{latex}`: {message}")]
    Math { latex: String, message: String },
    #[error("`{latex}` gives a malformed <msup>: write `{{\\op}}^{{k}}`")]
    MalformedPower { latex: String },
    #[error("plot `{slug}`: {message}")]
    Plot { slug: String, message: String },
    /// Two of the site's files would have one name (one would silently replace the other).
    #[error("two files of the site would both be `{}`: rename a scene or a lecture", path.display())]
    Collision { path: std::path::PathBuf },
    /// A formula the page would show that is not the result it stands for: mechbook's bug,
    /// caught before anything is written (`guard.rs`).
    #[error(
        "line {line}: mechbook would print `{printed}`, which reads back as {read}, for the \
         derived result {result} (they differ by {by:.1e} at random points); this is a bug in \
         mechbook's printing, not in the scene: please report it with this scene"
    )]
    Misprinted {
        line: usize,
        printed: String,
        read: String,
        result: String,
        by: f64,
    },
    /// Any of the above, in one scene's page.
    #[error("{}: {error}", path.display())]
    InScene {
        path: std::path::PathBuf,
        error: Box<RenderError>,
    },
}

impl RenderError {
    fn in_scene(self, source: &std::path::Path) -> RenderError {
        RenderError::InScene {
            path: source.to_path_buf(),
            error: Box::new(self),
        }
    }
}
