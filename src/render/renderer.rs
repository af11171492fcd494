//! The renderers' interface: each output format prints the course's documents
//! ([`Documents`]) behind one trait, as mdBook's renderers each take one context. A new format
//! is a file with a [`Renderer`] and a line in `RENDERERS` (`render/mod.rs`).

use super::RenderError;
use super::memo::{Kept, Memo, PageKeys};
use crate::document::course::Documents;
use crate::scene::Course;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// The site as relative path -> contents, sorted: what `site` writes.
pub type SiteFiles = BTreeMap<PathBuf, Vec<u8>>;

/// A user's own templates: name -> text, each replacing the default of that name.
pub type TemplateTexts = BTreeMap<String, String>;

/// Adds a file to the site; one that is already there is an error, never replaced.
pub fn add(
    files: &mut SiteFiles,
    path: impl Into<PathBuf>,
    bytes: Vec<u8>,
) -> Result<(), RenderError> {
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

/// What every renderer is given besides the documents.
pub struct Context<'a> {
    pub course: &'a Course,
    /// The user's own templates, by name (the HTML's).
    pub templates: &'a TemplateTexts,
    /// Measured seconds in the numeric tables.
    pub timings: bool,
    /// What earlier builds rendered: units made from the same inputs are taken from it.
    pub memo: &'a dyn Memo,
    /// Each page's key for the memo, made once (`Default::default()`).
    pub keys: PageKeys,
    /// The page first (`build --pdfs-later`): a PDF whose markup is not in the memo is not
    /// written now but left to the full build that follows ([`Rendered::later`]); the edited
    /// lecture's markup is most of what a page-first build would render for paper.
    pub pdfs_later: bool,
}

/// What the renderers made: the site's files, the documents Typst is to set (`site` typesets
/// and caches them), what the build should tell the user, and the units made fresh, for the
/// memo.
#[derive(Default)]
pub struct Rendered {
    pub files: SiteFiles,
    pub typeset: Vec<PdfSource>,
    pub notes: Vec<String>,
    pub kept: Vec<Kept>,
    /// The PDFs (their paths in the site) left to a later build ([`Context::pdfs_later`]).
    pub later: Vec<String>,
}

/// The course's plots, drawn once before any renderer runs: each file (relative to the site's
/// root) and its SVG. The HTML shows them and the instructor's handouts print them.
pub type Plots = BTreeMap<String, String>;

/// One output format.
pub trait Renderer: Sync {
    /// The documents in this format: its own files and documents to typeset, made from the
    /// documents and the plots alone (no renderer reads what another made).
    fn render(
        &self,
        docs: &Documents,
        plots: &Plots,
        cx: &Context,
    ) -> Result<Rendered, RenderError>;
}

impl Rendered {
    /// Takes in what another renderer made; a file both made is an error, never replaced.
    pub fn absorb(&mut self, other: Rendered) -> Result<(), RenderError> {
        for (path, bytes) in other.files {
            add(&mut self.files, path, bytes)?;
        }
        self.typeset.extend(other.typeset);
        self.notes.extend(other.notes);
        self.kept.extend(other.kept);
        self.later.extend(other.later);
        Ok(())
    }
}

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
