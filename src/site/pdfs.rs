//! The PDFs of a build: each document typeset by Typst, or taken from the build cache when its
//! markup and pictures are unchanged (a warm build typesets nothing). The bytes go to the
//! caller, which writes them with the site.

use super::cache::Cache;
use crate::render::pdf::PdfSource;
use std::path::PathBuf;

/// What typesetting made: each file, and what to tell the user.
#[derive(Default)]
pub struct Typeset {
    pub files: Vec<(PathBuf, Vec<u8>)>,
    pub from_cache: usize,
    /// Characters no font has, by document; and cache entries that could not be used or kept.
    pub warnings: Vec<String>,
    /// The documents Typst could not typeset, each with why: the rest are still written.
    pub failed: Vec<String>,
    /// The documents left to a later build ([`from_cache_only`]): not in the cache.
    pub pending: Vec<String>,
}

/// How many documents are typeset at once: Typst does not touch the engine, so each core takes
/// one.
#[cfg(feature = "pdf")]
fn workers() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get().min(MAX_WORKERS))
}

/// Each worker holds a document's layout in memory: two keep a course's build near one's peak.
#[cfg(feature = "pdf")]
const MAX_WORKERS: usize = 2;

/// Typesets `sources`, under `prefix` in the cache's names (`site`, `papers`); `progress` is
/// told of each document before it is made (done, total, path). The documents not in the cache
/// are typeset on one thread per core; the files, warnings and failures come in the sources'
/// order whatever the threads' order, so a build's output and messages do not depend on it.
#[cfg(feature = "pdf")]
pub fn typeset_all(
    sources: &[PdfSource],
    cache: Option<&Cache>,
    prefix: &str,
    progress: &mut dyn FnMut(usize, usize, &str),
) -> Typeset {
    use std::sync::atomic::{AtomicUsize, Ordering};
    let mut out = Typeset::default();
    // From the cache first, in order; the rest are typeset below.
    let mut made = from_cache(sources, cache, prefix, &mut out);
    let todo: Vec<usize> = (0..sources.len()).filter(|&i| made[i].is_none()).collect();
    // The workers take the next document and say when they start and finish it; this thread
    // tells `progress`, which need not be shared between threads.
    let next = AtomicUsize::new(0);
    let (tell, told) = std::sync::mpsc::channel();
    std::thread::scope(|scope| {
        for _ in 0..workers().min(todo.len()) {
            let tell = tell.clone();
            let (next, todo) = (&next, &todo);
            scope.spawn(move || {
                loop {
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    let Some(&i) = todo.get(k) else { break };
                    let _ = tell.send(Worker::Starts(k, i));
                    let done = crate::render::pdf::typeset::typeset(&sources[i]);
                    let _ = tell.send(Worker::Made(i, Box::new(done)));
                }
            });
        }
        drop(tell);
        for message in told {
            match message {
                Worker::Starts(k, i) => progress(k, todo.len(), &sources[i].path),
                Worker::Made(i, done) => made[i] = Some(Made::Typeset(*done)),
            }
        }
    });
    for (s, m) in sources.iter().zip(made) {
        let done = match m.expect("every document is made or from the cache") {
            Made::Cached(pdf) => {
                out.files.push((PathBuf::from(&s.path), pdf));
                out.from_cache += 1;
                continue;
            }
            Made::Typeset(Ok(done)) => done,
            Made::Typeset(Err(e)) => {
                // The error names the document.
                out.failed.push(e.to_string());
                continue;
            }
        };
        if !done.past_the_edge.is_empty() {
            // Named at the scenes whose formulas run past it, where known.
            let scenes = if done.past_the_edge_in.is_empty() {
                String::new()
            } else {
                format!(" (from {})", done.past_the_edge_in.join(", "))
            };
            out.warnings.push(format!(
                "{}: text runs past the paper's edge on page(s) {}{scenes}",
                s.path,
                done.past_the_edge
                    .iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        if !done.missing_glyphs.is_empty() {
            out.warnings.push(format!(
                "{}: no font has {}: they are left out of the PDF",
                s.path,
                done.missing_glyphs
                    .iter()
                    .map(|c| format!("`{c}` (U+{:04X})", u32::from(*c)))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        if done.missing_glyphs.is_empty()
            && done.past_the_edge.is_empty()
            && let Some(cache) = cache
            && let Err(e) = cache.store_pdf(&cache_name(prefix, s), inputs_hash(s), &done.pdf)
        {
            out.warnings.push(format!("the cache is not updated: {e}"));
        }
        out.files.push((PathBuf::from(&s.path), done.pdf));
    }
    out
}

/// The documents of `sources` that the cache has, and nothing typeset: the rest are named in
/// `pending`, for a later build to typeset (`serve` reloads the page first, and its PDFs
/// follow).
#[cfg(feature = "pdf")]
pub fn from_cache_only(sources: &[PdfSource], cache: Option<&Cache>, prefix: &str) -> Typeset {
    let mut out = Typeset::default();
    let made = from_cache(sources, cache, prefix, &mut out);
    for (s, m) in sources.iter().zip(made) {
        match m {
            Some(Made::Cached(pdf)) => {
                out.files.push((PathBuf::from(&s.path), pdf));
                out.from_cache += 1;
            }
            _ => out.pending.push(s.path.clone()),
        }
    }
    out
}

/// The name of a document's entry in the cache.
#[cfg(feature = "pdf")]
fn cache_name(prefix: &str, s: &PdfSource) -> String {
    format!(
        "{prefix}-{}",
        s.path.trim_end_matches(".pdf").replace('/', "-")
    )
}

/// Each document's PDF from the cache, in the sources' order, or `None` to typeset it; a
/// damaged entry is said in `out`'s warnings.
#[cfg(feature = "pdf")]
fn from_cache(
    sources: &[PdfSource],
    cache: Option<&Cache>,
    prefix: &str,
    out: &mut Typeset,
) -> Vec<Option<Made>> {
    let mut made: Vec<Option<Made>> = Vec::with_capacity(sources.len());
    for s in sources {
        let mut from_cache = None;
        if let Some(cache) = cache {
            use super::cache::Lookup;
            match cache.load_pdf(&cache_name(prefix, s), inputs_hash(s)) {
                Lookup::Hit(pdf) => from_cache = Some(pdf),
                Lookup::Miss => {}
                Lookup::Damaged(path, why) => out.warnings.push(format!(
                    "the cache entry {} is damaged ({why}): {} was typeset again",
                    path.display(),
                    s.path
                )),
            }
        }
        made.push(from_cache.map(Made::Cached));
    }
    made
}

#[cfg(feature = "pdf")]
type Typesetting =
    Result<crate::render::pdf::typeset::Typeset, crate::render::pdf::typeset::TypesetError>;

/// A document's PDF from the cache, or as Typst made it.
#[cfg(feature = "pdf")]
enum Made {
    Cached(Vec<u8>),
    Typeset(Typesetting),
}

/// What a typesetting worker tells the thread that started it: the k-th document to typeset
/// (the i-th source) starts, or is made.
#[cfg(feature = "pdf")]
enum Worker {
    Starts(usize, usize),
    Made(usize, Box<Typesetting>),
}

/// Without the feature `pdf` there is nothing to typeset.
#[cfg(not(feature = "pdf"))]
pub fn typeset_all(
    _: &[PdfSource],
    _: Option<&Cache>,
    _: &str,
    _: &mut dyn FnMut(usize, usize, &str),
) -> Typeset {
    Typeset::default()
}

/// Without the feature `pdf` there is nothing to typeset.
#[cfg(not(feature = "pdf"))]
pub fn from_cache_only(_: &[PdfSource], _: Option<&Cache>, _: &str) -> Typeset {
    Typeset::default()
}

/// The hash of everything a document's bytes depend on but the program (which the cache's
/// key has already).
#[cfg_attr(not(feature = "pdf"), allow(dead_code))]
fn inputs_hash(s: &PdfSource) -> u64 {
    let mut bytes = s.path.as_bytes().to_vec();
    bytes.push(0);
    bytes.extend_from_slice(s.markup.as_bytes());
    for (path, image) in &s.images {
        bytes.push(0);
        bytes.extend_from_slice(path.as_bytes());
        bytes.push(0);
        bytes.extend_from_slice(&crate::base::hash::word_hash(image).to_le_bytes());
    }
    crate::base::hash::word_hash(&bytes)
}

#[cfg(all(test, feature = "pdf"))]
mod tests {
    use super::typeset_all;
    use crate::render::pdf::PdfSource;

    fn source(path: &str, markup: &str) -> PdfSource {
        PdfSource {
            path: path.into(),
            markup: markup.into(),
            images: Vec::new(),
            origins: Vec::new(),
        }
    }

    #[test]
    fn a_document_typst_cannot_set_is_named_and_the_others_are_still_made() {
        let made = typeset_all(
            &[
                // A title, as PDF/UA-1 asks of every document.
                source("pdf/a.pdf", "#set document(title: \"A\")\nHello"),
                source("pdf/b.pdf", "#panic(\"broken\")"),
                source("pdf/c.pdf", "#set document(title: \"C\")\nWorld"),
            ],
            None,
            "test",
            &mut |_, _, _| {},
        );
        let paths: Vec<String> = made
            .files
            .iter()
            .map(|(p, _)| p.display().to_string())
            .collect();
        assert_eq!(paths, ["pdf/a.pdf", "pdf/c.pdf"]);
        assert_eq!(made.failed.len(), 1, "{:?}", made.failed);
        assert!(
            made.failed[0].starts_with("pdf/b.pdf: Typst cannot typeset it"),
            "{:?}",
            made.failed
        );
    }

    /// An error in a scene's part of a document is reported at that scene's line; one in
    /// mechbook's own markup between scenes names the document alone.
    #[test]
    fn a_typst_error_is_located_at_the_scene_whose_part_it_is_in() {
        let markup = "Head #[one] #panic(\"two\") #[mine] #panic(\"three\")";
        let at = |s: &str| markup.find(s).unwrap();
        let mut in_scene = source("pdf/d.pdf", markup);
        in_scene.origins = vec![
            (at("#[one]"), "lectures/one.toml:3".into()),
            (at(" #[mine]"), String::new()),
        ];
        let made = typeset_all(&[in_scene.clone()], None, "test", &mut |_, _, _| {});
        assert_eq!(made.failed.len(), 1, "{:?}", made.failed);
        let e = &made.failed[0];
        assert!(
            e.starts_with(
                "lectures/one.toml:3: pdf/d.pdf: Typst cannot typeset it: panicked with: two"
            ) && e.contains("report the scene"),
            "{e}"
        );
        // The same error in mechbook's own markup.
        in_scene.markup = markup.replace("#panic(\"two\")", "#[two]");
        let made = typeset_all(&[in_scene], None, "test", &mut |_, _, _| {});
        let e = &made.failed[0];
        assert!(
            e.starts_with("pdf/d.pdf: Typst cannot typeset it: panicked with: three"),
            "{e}"
        );
    }

    /// On two workers a long document first finishes after the short ones behind it: the
    /// files still come in the sources' order, each the bytes a one-at-a-time typesetting
    /// makes, and `progress` hears of each document once.
    #[test]
    fn documents_typeset_at_once_come_out_in_order_with_the_same_bytes() {
        let long = format!(
            "#set document(title: \"Long\")\n{}",
            "A line of the long document.\n\n".repeat(2000)
        );
        let mut sources = vec![source("pdf/0.pdf", &long)];
        for k in 1..6 {
            sources.push(source(
                &format!("pdf/{k}.pdf"),
                &format!("#set document(title: \"{k}\")\nShort {k}"),
            ));
        }
        let mut told = Vec::new();
        let made = typeset_all(&sources, None, "test", &mut |_, total, path| {
            told.push((total, path.to_string()));
        });
        let paths: Vec<String> = made
            .files
            .iter()
            .map(|(p, _)| p.display().to_string())
            .collect();
        let wanted: Vec<String> = sources.iter().map(|s| s.path.clone()).collect();
        assert_eq!(paths, wanted);
        told.sort();
        assert_eq!(
            told,
            wanted.iter().map(|p| (6, p.clone())).collect::<Vec<_>>()
        );
        for (s, (_, pdf)) in sources.iter().zip(&made.files) {
            let alone = crate::render::pdf::typeset::typeset(s).unwrap().pdf;
            assert!(
                alone == *pdf,
                "{} differs from its one-at-a-time bytes",
                s.path
            );
        }
    }
}
