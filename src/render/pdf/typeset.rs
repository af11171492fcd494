//! Typst in-process: a small world over one document's markup and its pictures, with the
//! fonts built into the binary, no clock (`today` is `None`) and a fixed document identifier,
//! so the same markup gives the same bytes on every machine.

use super::PdfSource;
use std::sync::OnceLock;
use typst::diag::{FileError, FileResult, Warned};
use typst::foundations::{Bytes, Datetime, Duration, Smart};
use typst::syntax::{FileId, RootedPath, Source, VirtualPath, VirtualRoot};
use typst::text::{Font, FontBook};
use typst::utils::LazyHash;
use typst::{Library, LibraryExt, World};
use typst_layout::PagedDocument;

/// Why a document could not be typeset: Typst's errors, each with the markup it points at
/// (a bug of mechbook's printers, since every author's text is a string literal), and the
/// scene (file:line) whose part of the document the first of them falls in, if any.
#[derive(Debug, Clone, thiserror::Error)]
#[error(
    "{}{path}: Typst cannot typeset it: {}{}",
    scene.as_ref().map_or(String::new(), |s| format!("{s}: ")),
    messages.join("; "),
    if scene.is_some() {
        " (in this scene's part of the document, which `check` accepts: rewrite the mathematics \
         or name Typst points at, and please report the scene as a mechbook bug)"
    } else {
        ""
    }
)]
pub struct TypesetError {
    pub path: String,
    pub messages: Vec<String>,
    pub scene: Option<String>,
}

/// The scene whose part of the markup holds byte `at`, if one does.
fn scene_at(origins: &[(usize, String)], at: usize) -> Option<String> {
    origins
        .iter()
        .rev()
        .find(|(start, _)| *start <= at)
        .map(|(_, scene)| scene.clone())
        .filter(|scene| !scene.is_empty())
}

/// The font files built into the binary: New Computer Modern (text and math), Libertinus and
/// DejaVu Sans Mono. Every reader of them goes through here: `typst_assets::fonts()` is made of
/// constants, which the compiler copies into each part of the program that names them, and the
/// binary had carried them twice (9.7 MB).
pub(super) fn font_files() -> &'static [&'static [u8]] {
    static FILES: OnceLock<Vec<&'static [u8]>> = OnceLock::new();
    FILES.get_or_init(|| typst_assets::fonts().collect())
}

/// The fonts, read once.
fn fonts() -> &'static (LazyHash<FontBook>, Vec<Font>) {
    static FONTS: OnceLock<(LazyHash<FontBook>, Vec<Font>)> = OnceLock::new();
    FONTS.get_or_init(|| {
        let fonts: Vec<Font> = font_files()
            .iter()
            .flat_map(|data| Font::iter(Bytes::new(*data)))
            .collect();
        (LazyHash::new(FontBook::from_fonts(&fonts)), fonts)
    })
}

pub(super) fn library() -> &'static LazyHash<Library> {
    static LIBRARY: OnceLock<LazyHash<Library>> = OnceLock::new();
    LIBRARY.get_or_init(|| LazyHash::new(Library::builder().build()))
}

struct Document<'a> {
    main: Source,
    source: &'a PdfSource,
}

fn file_id(path: &str) -> Option<FileId> {
    Some(RootedPath::new(VirtualRoot::Project, VirtualPath::new(path).ok()?).intern())
}

impl World for Document<'_> {
    fn library(&self) -> &LazyHash<Library> {
        library()
    }
    fn book(&self) -> &LazyHash<FontBook> {
        &fonts().0
    }
    fn main(&self) -> FileId {
        self.main.id()
    }
    fn source(&self, id: FileId) -> FileResult<Source> {
        if id == self.main.id() {
            Ok(self.main.clone())
        } else {
            Err(FileError::AccessDenied)
        }
    }
    fn file(&self, id: FileId) -> FileResult<Bytes> {
        self.source
            .images
            .iter()
            .find(|(path, _)| file_id(path) == Some(id))
            .map(|(_, bytes)| Bytes::new(bytes.clone()))
            .ok_or(FileError::AccessDenied)
    }
    fn font(&self, index: usize) -> Option<Font> {
        fonts().1.get(index).cloned()
    }
    fn today(&self, _: Option<Duration>) -> Option<Datetime> {
        None
    }
}

/// A typeset document: its PDF, its page count, the characters no font had, the pages (from
/// 1) with text past the paper's edge, and the scenes (file:line) whose part that text is in.
pub struct Typeset {
    pub pdf: Vec<u8>,
    pub pages: usize,
    pub missing_glyphs: Vec<char>,
    pub past_the_edge: Vec<usize>,
    pub past_the_edge_in: Vec<String>,
}

/// The PDF of one document.
pub fn typeset(source: &PdfSource) -> Result<Typeset, TypesetError> {
    // Typst applies each `#set page(...)` to all that follows it, recursively: a sheet of
    // thousands of variants, one set rule each, nests that deep, past the main thread's 8 MiB
    // (5,000 variants overflowed it). Its own thread has room for the 10,000 pages a sheet
    // may have; the stack is only reserved, not used, until it is needed.
    std::thread::scope(|scope| {
        std::thread::Builder::new()
            .name("typst".into())
            .stack_size(TYPESET_STACK)
            .spawn_scoped(scope, || typeset_here(source))
            .map_err(|e| TypesetError {
                path: source.path.clone(),
                messages: vec![format!("cannot start the typesetting thread: {e}")],
                scene: None,
            })?
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    })
}

/// Typst memoises layout and shaping in a global cache that grows with every document: without
/// eviction a build held every handout's memos to the end. Called after each document: when
/// no other is being typeset (`alone`) every memo is dropped; else those that the next
/// `MEMO_AGE` documents do not use, since the other document's are in use.
pub fn evict_memos(alone: bool) {
    typst::comemo::evict(if alone { 0 } else { MEMO_AGE });
}

/// How many documents a memo outlives without being used, while another document is typeset.
/// Measured on tests/course's 16 PDFs (docs/performance.md, "A course"): no eviction peaked at 311 MiB;
/// ages 0, 1 and 2 at 198 to 215 MiB in the same time within the noise; 4 at 252 to 269 MiB.
/// With documents typeset within a memory budget (fffa3ff), age 0 here too made the build
/// 0.8 s slower (four runs each: 6.9 to 7.3 s against 5.9 to 6.6 s) at the same peak.
const MEMO_AGE: usize = 1;

/// The typesetting thread's stack: 1 GiB of address space.
const TYPESET_STACK: usize = 1 << 30;

fn typeset_here(source: &PdfSource) -> Result<Typeset, TypesetError> {
    let world = Document {
        main: Source::detached(source.markup.clone()),
        source,
    };
    let fail = |messages: Vec<String>, scene: Option<String>| failed(source, messages, scene);
    let Warned { output, .. } = typst::compile::<PagedDocument>(&world);
    let document = output.map_err(|errors| {
        let ranges: Vec<_> = errors
            .iter()
            .map(|e| typst::WorldExt::range(&world, e.span))
            .collect();
        let scene = ranges
            .iter()
            .flatten()
            .find_map(|r| scene_at(&source.origins, r.start));
        fail(
            errors
                .iter()
                .zip(&ranges)
                .map(|(e, r)| {
                    let at = r
                        .clone()
                        .and_then(|r| world.main.text().get(r))
                        .unwrap_or("");
                    format!("{} at `{at}`", e.message)
                })
                .collect(),
            scene,
        )
    })?;
    let pdf = tagged_pdf(&document, source)?;
    // A character no font has is set as the font's "notdef": found in the laid-out pages, not
    // in Typst's warnings' wording.
    let mut missing = missing_glyphs_in(&document);
    missing.sort_unstable();
    missing.dedup();
    // Text past the edge, by page, and the scenes whose part of the markup it came from.
    let scene_of = |span: typst::syntax::Span| {
        typst::WorldExt::range(&world, span).and_then(|r| scene_at(&source.origins, r.start))
    };
    let overflow = past_the_edge(&document, &scene_of);
    let mut past_the_edge_in: Vec<String> = Vec::new();
    for scene in overflow.iter().flat_map(|(_, scenes)| scenes) {
        if !past_the_edge_in.contains(scene) {
            past_the_edge_in.push(scene.clone());
        }
    }
    Ok(Typeset {
        pdf,
        pages: document.pages().len(),
        missing_glyphs: missing,
        past_the_edge: overflow.iter().map(|(page, _)| *page).collect(),
        past_the_edge_in,
    })
}

/// A typesetting error of `source`'s PDF.
fn failed(source: &PdfSource, messages: Vec<String>, scene: Option<String>) -> TypesetError {
    TypesetError {
        path: source.path.clone(),
        messages,
        scene,
    }
}

/// The laid-out document as a PDF, tagged for PDF/UA-1: a reader's assistive technology gets the
/// structure, the language and each formula's spoken form (its alternative description).
fn tagged_pdf(document: &PagedDocument, source: &PdfSource) -> Result<Vec<u8>, TypesetError> {
    let fail = |messages: Vec<String>, scene: Option<String>| failed(source, messages, scene);
    let standards = typst_pdf::PdfStandards::new(&[typst_pdf::PdfStandard::Ua_1])
        .map_err(|e| fail(vec![e.message().to_string()], None))?;
    let options = typst_pdf::PdfOptions {
        ident: Smart::Custom(source.path.clone()),
        creator: Smart::Custom(Some("mechbook (Typst)".into())),
        timestamp: None,
        standards,
        ..Default::default()
    };
    let pdf = match typst_pdf::pdf(document, &options) {
        Ok(pdf) => pdf,
        // A character no font has (a student's name in another script) cannot be set as
        // PDF/UA-1 asks: the PDF is still tagged, without the claim, and the character is
        // named in a warning (`missing_glyphs`).
        Err(errors)
            if errors
                .iter()
                .all(|e| e.message.contains("could not be displayed with font")) =>
        {
            let tagged = typst_pdf::PdfOptions {
                standards: typst_pdf::PdfStandards::default(),
                ..options
            };
            typst_pdf::pdf(document, &tagged).map_err(|errors| {
                fail(errors.iter().map(|e| e.message.to_string()).collect(), None)
            })?
        }
        Err(errors) => {
            return Err(fail(
                errors.iter().map(|e| e.message.to_string()).collect(),
                None,
            ));
        }
    };
    Ok(pdf)
}

/// The pages (from 1) where a piece of text reaches past the paper's left or right edge, each
/// with the scenes (`scene_of` a glyph's source) of the text that does.
fn past_the_edge(
    document: &PagedDocument,
    scene_of: &dyn Fn(typst::syntax::Span) -> Option<String>,
) -> Vec<(usize, Vec<String>)> {
    use typst::layout::{Abs, Frame, FrameItem, Point, Transform};
    fn walk(
        frame: &Frame,
        ts: Transform,
        width: Abs,
        scene_of: &dyn Fn(typst::syntax::Span) -> Option<String>,
        found: &mut Option<Vec<String>>,
    ) {
        for (pos, item) in frame.items() {
            let ts = ts.pre_concat(Transform::translate(pos.x, pos.y));
            match item {
                FrameItem::Group(g) => {
                    walk(&g.frame, ts.pre_concat(g.transform), width, scene_of, found)
                }
                FrameItem::Text(t) => {
                    let (start, end) = (
                        Point::zero().transform(ts).x,
                        Point::new(t.width(), Abs::zero()).transform(ts).x,
                    );
                    let slack = Abs::pt(0.5);
                    if start.min(end) < -slack || start.max(end) > width + slack {
                        let scenes = found.get_or_insert_with(Vec::new);
                        let scene = t.glyphs.iter().find_map(|g| scene_of(g.span.0));
                        if let Some(s) = scene
                            && !scenes.contains(&s)
                        {
                            scenes.push(s);
                        }
                    }
                }
                _ => {}
            }
        }
    }
    document
        .pages()
        .iter()
        .enumerate()
        .filter_map(|(i, p)| {
            let mut found = None;
            walk(
                &p.frame,
                Transform::identity(),
                p.frame.width(),
                scene_of,
                &mut found,
            );
            found.map(|scenes| (i + 1, scenes))
        })
        .collect()
}

/// The characters set with no glyph (a font's "notdef", glyph 0) anywhere in the document.
fn missing_glyphs_in(document: &PagedDocument) -> Vec<char> {
    let mut out = Vec::new();
    each_text(document, &mut |t| {
        for g in &t.glyphs {
            if g.id == 0 {
                out.extend(t.text[g.range()].chars());
            }
        }
    });
    out
}

/// Each piece of text set on the document's pages, in order.
fn each_text(document: &PagedDocument, f: &mut dyn FnMut(&typst::text::TextItem)) {
    use typst::layout::{Frame, FrameItem};
    fn walk(frame: &Frame, f: &mut dyn FnMut(&typst::text::TextItem)) {
        for (_, item) in frame.items() {
            match item {
                FrameItem::Group(g) => walk(&g.frame, f),
                FrameItem::Text(t) => f(t),
                _ => {}
            }
        }
    }
    for page in document.pages() {
        walk(&page.frame, f);
    }
}

/// The text Typst sets on the pages of `markup`, piece by piece in order: for tests that read
/// back what a document measured.
#[cfg(test)]
pub fn texts(markup: &str) -> Vec<String> {
    let source = PdfSource {
        path: "test.pdf".into(),
        markup: markup.into(),
        images: Vec::new(),
        origins: Vec::new(),
    };
    let world = Document {
        main: Source::detached(markup.to_string()),
        source: &source,
    };
    let document = typst::compile::<PagedDocument>(&world)
        .output
        .unwrap_or_else(|e| panic!("{e:?}"));
    let mut out = Vec::new();
    each_text(&document, &mut |t| out.push(t.text.to_string()));
    out
}
