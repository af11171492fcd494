//! The PDFs of a build: each document typeset by Typst, or taken from a store of earlier PDFs
//! (`site`'s build cache) when its markup and pictures are unchanged, so that a warm build
//! typesets nothing. Each PDF goes to the caller's `keep` as soon as it is made, which puts it
//! in the site or writes it (a roster's papers are not all held at once).

use super::PdfSource;
#[cfg(feature = "pdf")]
use super::queue;
use std::path::PathBuf;

/// Where each PDF goes once it is made or read from the store: its path and its bytes.
pub type Keep<'a, E> = dyn FnMut(PathBuf, Vec<u8>) -> Result<(), E> + 'a;

/// What a store has of a document made from given inputs.
pub enum Stored {
    /// Its PDF, and what was said of it when it was typeset.
    Hit {
        pdf: Vec<u8>,
        warnings: Vec<String>,
    },
    Miss,
    /// An entry that cannot be used: what to say of it (it is typeset again).
    Damaged(String),
}

/// Why a store could not keep a document: said as a warning, since the PDF is still made.
pub type StoreError = Box<dyn std::error::Error + Send + Sync>;

/// Earlier builds' PDFs, by the document's path and the hash of its inputs ([`inputs_hash`]):
/// `site`'s build cache, as the result store serves the pipeline.
pub trait PdfStore {
    fn load(&self, path: &str, inputs: u64) -> Stored;
    /// Keeps a PDF and what is said of it (its warnings first: a PDF found has them too).
    fn store(
        &self,
        path: &str,
        inputs: u64,
        pdf: &[u8],
        warnings: &[String],
    ) -> Result<(), StoreError>;
}

/// What typesetting made: how many documents, and what to tell the user.
#[derive(Default)]
pub struct Typeset {
    /// The documents kept, typeset or from the cache.
    pub made: usize,
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

/// Two: each worker holds a document's layout in memory, and the budget below seldom has room
/// for a third.
#[cfg(feature = "pdf")]
const MAX_WORKERS: usize = 2;

/// How much is typeset at once, in bytes of markup and pictures. Typst holds a document's
/// layout until its PDF is made, about 0.35 MiB for each KB of markup: tests/course's largest
/// handout (388 KB and two plots) peaks 145 to 164 MiB above the build's 44 MiB. Within this
/// budget that handout is typeset alone and the others in pairs, and the build peaks at 189 to
/// 193 MiB, where it peaked at 301 to 342 (docs/performance.md, "Typesetting within a memory budget").
#[cfg(feature = "pdf")]
const TYPESET_AT_ONCE: usize = 300_000;

/// A document's size for the budget: its markup and its pictures.
#[cfg(feature = "pdf")]
fn size(s: &PdfSource) -> usize {
    s.markup.len() + s.images.iter().map(|(_, bytes)| bytes.len()).sum::<usize>()
}

/// Typesets `sources`, those not in the store `cache`; `progress` is
/// told of each document before it is made (done, total, path), and `keep` is given each PDF as
/// soon as it is made. The documents not in the cache are typeset on one thread per core; the
/// warnings and failures come in the sources' order whatever the threads' order, so a build's
/// output and messages do not depend on it. When `keep` fails, no further document is started
/// and its error is returned.
#[cfg(feature = "pdf")]
pub fn typeset_all<E>(
    sources: &[PdfSource],
    cache: Option<&dyn PdfStore>,
    progress: &mut dyn FnMut(usize, usize, &str),
    keep: &mut Keep<E>,
) -> Result<Typeset, E> {
    let mut out = Typeset::default();
    // From the cache first, in order; the rest are typeset below.
    let cached = from_cache(sources, cache, &mut out, keep)?;
    let todo: Vec<usize> = (0..sources.len()).filter(|&i| !cached[i]).collect();
    if !todo.is_empty() {
        // What the build freed before typesetting goes back to the system, not kept beside
        // the layouts, which Typst's threads allocate elsewhere.
        give_back_freed_memory();
    }
    let mut notes: Vec<Notes> = (0..sources.len()).map(|_| Notes::default()).collect();
    let mut kept = Ok(());
    // The workers take the next document and say when they start and finish it; this thread
    // tells `progress` and `keep`, which need not be shared between threads.
    let sizes = sources.iter().map(size).collect();
    let queue = queue::Queue::new(sizes, &todo, TYPESET_AT_ONCE, give_back);
    let (tell, told) = std::sync::mpsc::channel();
    std::thread::scope(|scope| {
        for _ in 0..workers().min(todo.len()) {
            let tell = tell.clone();
            let queue = &queue;
            scope.spawn(move || {
                while let Some(turn) = queue.next() {
                    let i = turn.source;
                    let _ = tell.send(Worker::Starts(turn.k, i));
                    let done = super::typeset::typeset(&sources[i]);
                    drop(turn);
                    let _ = tell.send(Worker::Made(i, Box::new(done)));
                }
            });
        }
        drop(tell);
        for message in told {
            match message {
                Worker::Starts(k, i) => progress(k, todo.len(), &sources[i].path),
                Worker::Made(i, done) => {
                    let (said, pdf) = finished(&sources[i], *done, cache);
                    notes[i] = said;
                    if let (Some(pdf), Ok(())) = (pdf, &kept) {
                        out.made += 1;
                        kept = keep(PathBuf::from(&sources[i].path), pdf);
                        if kept.is_err() {
                            // Nothing more is started; what is under way is let finish.
                            queue.stop();
                        }
                    }
                }
            }
        }
    });
    kept?;
    for n in notes {
        out.warnings.extend(n.warnings);
        out.failed.extend(n.failed);
    }
    Ok(out)
}

/// What a build says of one typeset document: its warnings, or why it failed.
#[cfg(feature = "pdf")]
#[derive(Default)]
struct Notes {
    warnings: Vec<String>,
    failed: Option<String>,
}

/// A document as Typst made it: what to say of it, and its PDF (none when it failed). The PDF is
/// stored in the cache with what is said of it.
#[cfg(feature = "pdf")]
fn finished(
    s: &PdfSource,
    done: Typesetting,
    cache: Option<&dyn PdfStore>,
) -> (Notes, Option<Vec<u8>>) {
    let mut notes = Notes::default();
    let done = match done {
        Ok(done) => done,
        Err(e) => {
            // The error names the document.
            notes.failed = Some(e.to_string());
            return (notes, None);
        }
    };
    if !done.past_the_edge.is_empty() {
        // Named at the scenes whose formulas run past it, where known.
        let scenes = if done.past_the_edge_in.is_empty() {
            String::new()
        } else {
            format!(" (from {})", done.past_the_edge_in.join(", "))
        };
        notes.warnings.push(format!(
            "{}: text runs past the paper's edge on {} {}{scenes}",
            s.path,
            if done.past_the_edge.len() == 1 {
                "page"
            } else {
                "pages"
            },
            done.past_the_edge
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    if !done.missing_glyphs.is_empty() {
        notes.warnings.push(format!(
            "{}: no font has {}: they are left out of the PDF",
            s.path,
            done.missing_glyphs
                .iter()
                .map(|c| format!("`{c}` (U+{:04X})", u32::from(*c)))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    if let Some(cache) = cache {
        let stored = cache.store(&s.path, inputs_hash(s), &done.pdf, &notes.warnings);
        if let Err(e) = stored {
            notes
                .warnings
                .push(format!("the cache is not updated: {e}"));
        }
    }
    (notes, Some(done.pdf))
}

/// The documents of `sources` that the cache has, each given to `keep`, and nothing typeset:
/// the rest are named in `pending`, for a later build to typeset (`serve` reloads the page
/// first, and its PDFs follow).
#[cfg(feature = "pdf")]
pub fn from_cache_only<E>(
    sources: &[PdfSource],
    cache: Option<&dyn PdfStore>,
    keep: &mut Keep<E>,
) -> Result<Typeset, E> {
    let mut out = Typeset::default();
    let cached = from_cache(sources, cache, &mut out, keep)?;
    for (s, cached) in sources.iter().zip(cached) {
        if !cached {
            out.pending.push(s.path.clone());
        }
    }
    Ok(out)
}

/// Gives `keep` each document's PDF that the cache has, in the sources' order, and says which
/// they were (the rest are to be typeset); a damaged entry is said in `out`'s warnings.
#[cfg(feature = "pdf")]
fn from_cache<E>(
    sources: &[PdfSource],
    cache: Option<&dyn PdfStore>,
    out: &mut Typeset,
    keep: &mut Keep<E>,
) -> Result<Vec<bool>, E> {
    let mut cached = Vec::with_capacity(sources.len());
    for s in sources {
        let mut hit = false;
        if let Some(cache) = cache {
            match cache.load(&s.path, inputs_hash(s)) {
                Stored::Hit { pdf, warnings } => {
                    // Said again, as when it was typeset.
                    out.warnings.extend(warnings);
                    keep(PathBuf::from(&s.path), pdf)?;
                    out.made += 1;
                    out.from_cache += 1;
                    hit = true;
                }
                Stored::Miss => {}
                Stored::Damaged(entry) => out
                    .warnings
                    .push(format!("{entry}: {} was typeset again", s.path)),
            }
        }
        cached.push(hit);
    }
    Ok(cached)
}

/// After a document of `size` bytes: Typst's memos are dropped (all of them when no other
/// document is under way, else those the other has not used lately), and the memory freed goes
/// back once a handout's worth of markup has been typeset since it last went back.
#[cfg(feature = "pdf")]
fn give_back(alone: bool, size: usize) {
    use std::sync::atomic::Ordering::Relaxed;
    super::typeset::evict_memos(alone);
    if TYPESET_SINCE_TRIM.fetch_add(size, Relaxed) + size >= TRIM_AFTER {
        TYPESET_SINCE_TRIM.store(0, Relaxed);
        give_back_freed_memory();
    }
}

/// Markup typeset since the freed memory last went back.
#[cfg(feature = "pdf")]
static TYPESET_SINCE_TRIM: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// The markup typeset between two returns of freed memory. A return walks the allocator's
/// whole heap, which holds every variant of a roster's sheet: after each of a class's small
/// papers it made the roster quadratic (`perf`: 28 % of a 1,000-student build in `malloc_trim`
/// and the unmapping it does), while a paper's memory is reused by the next.
#[cfg(feature = "pdf")]
const TRIM_AFTER: usize = 256 << 10;

/// Returns the free pages of the allocator's heaps to the system. glibc keeps what a thread
/// frees in that thread's arena, so a finished document's layout would stay resident beside
/// the next document's, typeset on another arena (docs/performance.md, "Typesetting within a memory
/// budget").
#[cfg(feature = "pdf")]
fn give_back_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc_trim only releases free memory; it reads and writes no caller's data.
    #[allow(unsafe_code)]
    unsafe {
        libc::malloc_trim(0);
    }
}

#[cfg(feature = "pdf")]
type Typesetting = Result<super::typeset::Typeset, super::typeset::TypesetError>;

/// What a typesetting worker tells the thread that started it: the k-th document to typeset
/// (the i-th source) starts, or is made.
#[cfg(feature = "pdf")]
enum Worker {
    Starts(usize, usize),
    Made(usize, Box<Typesetting>),
}

/// Without the feature `pdf` there is nothing to typeset.
#[cfg(not(feature = "pdf"))]
pub fn typeset_all<E>(
    _: &[PdfSource],
    _: Option<&dyn PdfStore>,
    _: &mut dyn FnMut(usize, usize, &str),
    _: &mut Keep<E>,
) -> Result<Typeset, E> {
    Ok(Typeset::default())
}

/// Without the feature `pdf` there is nothing to typeset.
#[cfg(not(feature = "pdf"))]
pub fn from_cache_only<E>(
    _: &[PdfSource],
    _: Option<&dyn PdfStore>,
    _: &mut Keep<E>,
) -> Result<Typeset, E> {
    Ok(Typeset::default())
}

/// The hash of everything a document's bytes depend on but the program (which the cache's
/// key has already).
#[cfg_attr(not(feature = "pdf"), allow(dead_code))]
pub fn inputs_hash(s: &PdfSource) -> u64 {
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
    use crate::render::pdf::PdfSource;
    use std::collections::BTreeMap;
    use std::path::PathBuf;

    /// The documents typeset, each PDF kept in the order it came, and what was said.
    fn typeset_all(
        sources: &[PdfSource],
        progress: &mut dyn FnMut(usize, usize, &str),
    ) -> (Vec<(PathBuf, Vec<u8>)>, super::Typeset) {
        let mut kept = Vec::new();
        let made = super::typeset_all::<()>(sources, None, progress, &mut |path, pdf| {
            kept.push((path, pdf));
            Ok(())
        })
        .unwrap();
        (kept, made)
    }

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
        let (files, made) = typeset_all(
            &[
                // A title, as PDF/UA-1 asks of every document.
                source("pdf/a.pdf", "#set document(title: \"A\")\nHello"),
                source("pdf/b.pdf", "#panic(\"broken\")"),
                source("pdf/c.pdf", "#set document(title: \"C\")\nWorld"),
            ],
            &mut |_, _, _| {},
        );
        let mut paths: Vec<String> = files.iter().map(|(p, _)| p.display().to_string()).collect();
        paths.sort();
        assert_eq!(paths, ["pdf/a.pdf", "pdf/c.pdf"]);
        assert_eq!(made.made, 2);
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
        let (_, made) = typeset_all(&[in_scene.clone()], &mut |_, _, _| {});
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
        let (_, made) = typeset_all(&[in_scene], &mut |_, _, _| {});
        let e = &made.failed[0];
        assert!(
            e.starts_with("pdf/d.pdf: Typst cannot typeset it: panicked with: three"),
            "{e}"
        );
    }

    /// On two workers a long document first finishes after the short ones behind it: each PDF
    /// is kept as soon as it is made (not held for the long one), each the bytes a
    /// one-at-a-time typesetting makes, the failures still said in the sources' order, and
    /// `progress` hears of each document once.
    #[test]
    fn documents_typeset_at_once_are_kept_as_made_with_the_same_bytes() {
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
        sources.push(source("pdf/6.pdf", "#panic(\"six\")"));
        sources.push(source("pdf/7.pdf", "#panic(\"seven\")"));
        let mut told = Vec::new();
        let (files, made) = typeset_all(&sources, &mut |_, total, path| {
            told.push((total, path.to_string()));
        });
        if super::workers() > 1 {
            assert_ne!(
                files[0].0,
                PathBuf::from("pdf/0.pdf"),
                "the short documents wait for the long one"
            );
        }
        let files: BTreeMap<PathBuf, Vec<u8>> = files.into_iter().collect();
        let wanted: Vec<String> = sources.iter().map(|s| s.path.clone()).collect();
        assert_eq!(
            files
                .keys()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>(),
            wanted[..6]
        );
        assert!(made.failed[0].starts_with("pdf/6.pdf") && made.failed[1].starts_with("pdf/7.pdf"));
        told.sort();
        assert_eq!(
            told,
            wanted.iter().map(|p| (8, p.clone())).collect::<Vec<_>>()
        );
        for s in &sources[..6] {
            let alone = crate::render::pdf::typeset::typeset(s).unwrap().pdf;
            assert!(
                alone == files[&PathBuf::from(&s.path)],
                "{} differs from its one-at-a-time bytes",
                s.path
            );
        }
    }

    /// A failed write stops the typesetting and is what the caller hears.
    #[test]
    fn a_failed_keep_stops_the_rest_and_is_returned() {
        let sources: Vec<PdfSource> = (0..12)
            .map(|k| {
                source(
                    &format!("pdf/{k}.pdf"),
                    &format!("#set document(title: \"{k}\")\nShort {k}"),
                )
            })
            .collect();
        let mut started = 0;
        let result = super::typeset_all(
            &sources,
            None,
            &mut |_, _, _| started += 1,
            &mut |path, _| Err(path),
        );
        // The first PDF made is the one whose keeping failed.
        assert!(
            matches!(&result, Err(p) if p.extension() == Some("pdf".as_ref())),
            "{:?}",
            result.err()
        );
        assert!(
            started < 12,
            "all {started} documents were started after the write failed"
        );
    }
}
