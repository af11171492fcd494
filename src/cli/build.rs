//! `mechbook build`: the course site. `serve` runs the same build on every edit.

use super::{FidelityArg, default_paths, find, run_all};

mod stages;
use crate::model::fidelity::Fidelity;
use crate::site::cache::Cache;
use anyhow::Result;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(clap::Args, Debug, Clone)]
pub struct BuildArgs {
    /// Scene files or folders (default: lectures/).
    pub paths: Vec<PathBuf>,
    /// The output folder (default: `output` from mechbook.toml, else site/).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// A folder whose templates (page.html, index.html, handout.html, style.css) replace
    /// the built-in ones, file by file.
    #[arg(long)]
    pub templates: Option<PathBuf>,
    /// Add measured seconds to the numeric tables (the pages then differ between builds).
    #[arg(long)]
    pub timings: bool,
    #[command(flatten)]
    pub fidelity: FidelityArg,
    /// Where computed scenes are kept between builds, keyed by a hash of the scene file,
    /// the fidelity and this program: an unchanged scene is not derived again.
    #[arg(long, default_value = ".mechbook-cache")]
    pub cache: PathBuf,
    /// Derive every scene afresh, and neither read nor write the cache (overrides --cache).
    #[arg(long)]
    pub no_cache: bool,
    /// A class roster (CSV with the columns `name` and `id`, docs/papers.md): one paper per
    /// student, with their own variant of every problem sheet and their name and ID on every
    /// page, a key in the roster's order, and variants.csv for grading. They go to --papers,
    /// not into the site, which may be public.
    #[arg(long, value_name = "CSV")]
    pub roster: Option<PathBuf>,
    /// Where the roster's papers go (replaced whole, like the site).
    #[arg(
        long,
        value_name = "DIR",
        default_value = "papers",
        requires = "roster"
    )]
    pub papers: PathBuf,
    /// The seed that deals the sheet variants to the roster's students: the same roster and
    /// seed give every student the same variant again.
    #[arg(long, default_value_t = 1, requires = "roster")]
    pub seed: u64,
    /// Also write the outcome as JSON to this file: `serve` runs each build as a child
    /// process, so that it never holds the engine, and reads what happened here.
    #[arg(long, hide = true)]
    pub status_file: Option<PathBuf>,
    /// Write the site with the PDFs the cache has, and leave the rest (and a roster's papers)
    /// to the next build: `serve` reloads the page first, and runs the full build after it.
    #[arg(long, hide = true)]
    pub pdfs_later: bool,
}

impl BuildArgs {
    /// The same build on a command line, for a child process (`serve`); the output folder as
    /// this build settled it.
    pub fn command_line(&self, out: &Path) -> Vec<std::ffi::OsString> {
        let mut a: Vec<std::ffi::OsString> = vec!["build".into()];
        a.extend(self.paths.iter().map(|p| p.clone().into_os_string()));
        a.extend(["--out".into(), out.as_os_str().to_owned()]);
        if let Some(t) = &self.templates {
            a.extend(["--templates".into(), t.as_os_str().to_owned()]);
        }
        if self.timings {
            a.push("--timings".into());
        }
        if let Some(f) = self.fidelity.fidelity {
            a.extend(["--fidelity".into(), f.argument().into()]);
        }
        if let Some(r) = &self.roster {
            a.extend(["--roster".into(), r.as_os_str().to_owned()]);
            a.extend(["--papers".into(), self.papers.as_os_str().to_owned()]);
            a.extend(["--seed".into(), self.seed.to_string().into()]);
        }
        if self.no_cache {
            a.push("--no-cache".into());
        } else {
            a.extend(["--cache".into(), self.cache.as_os_str().to_owned()]);
        }
        a
    }
}

/// What a build did, as `--status-file` records it for `serve`.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Outcome {
    /// Whether the site was written.
    pub written: bool,
    /// Why it was not (located messages), or the checks that failed in the site it wrote.
    pub problems: Vec<String>,
    /// With `--pdfs-later`: the site's PDFs left out, for the full build to typeset.
    #[serde(default)]
    pub pdfs_pending: Vec<String>,
}

impl Outcome {
    fn of(result: &Result<Built, NotBuilt>) -> Outcome {
        match result {
            Ok(built) => Outcome {
                written: true,
                problems: built.failures.clone(),
                pdfs_pending: built.pdfs_pending.clone(),
            },
            Err(not_built) => Outcome {
                written: false,
                problems: not_built.messages(),
                pdfs_pending: Vec::new(),
            },
        }
    }
}

/// A build settled before anything is derived: what to read and where to write.
pub struct Build {
    paths: Vec<PathBuf>,
    /// mechbook.toml: in a folder named, or the nearest above the scenes, or in the working
    /// folder.
    course_file: PathBuf,
    /// Whether every scene of the course is built (no paths were given, or a folder named
    /// holds the course file): then a `[[lecture]]` that no scene has is an error.
    whole_course: bool,
    out: PathBuf,
    templates: Option<PathBuf>,
    timings: bool,
    fidelity: Option<Fidelity>,
    cache: Option<Cache>,
    /// The roster, the papers' folder and the seed, with `--roster`.
    roster: Option<(crate::scene::roster::Roster, PathBuf, u64)>,
    pdfs_later: bool,
}

/// What one build did.
pub struct Built {
    pub summary: String,
    /// The checks that failed: the site was written, and they are listed here.
    pub failures: Vec<String>,
    /// With `--pdfs-later`: the site's PDFs not in the cache, left out of it.
    pub pdfs_pending: Vec<String>,
}

/// Why a build wrote nothing; the scene messages are located (file:line:column).
#[derive(Debug)]
pub enum NotBuilt {
    /// Bad scene files: nothing was derived.
    Scenes(Vec<String>),
    /// Scenes that could not be derived (`run_all` has printed them).
    Derive(Vec<String>),
    /// The course file, the output folder, the templates or the writing.
    Other(anyhow::Error),
}

impl NotBuilt {
    /// Every reason, a line each, for the page `serve` shows.
    pub fn messages(&self) -> Vec<String> {
        match self {
            NotBuilt::Scenes(m) | NotBuilt::Derive(m) => m.clone(),
            NotBuilt::Other(e) => vec![super::one_line(e)],
        }
    }
}

impl Build {
    pub fn new(args: BuildArgs) -> Result<Build> {
        let BuildArgs {
            paths,
            out,
            templates,
            timings,
            fidelity: FidelityArg { fidelity },
            cache,
            no_cache,
            roster,
            papers,
            seed,
            status_file: _,
            pdfs_later,
        } = args;
        if roster.is_some() && !crate::document::files::PDFS {
            anyhow::bail!(
                "--roster makes PDFs, and this mechbook was built without them: build it with \
                 the default features (`cargo build --release`)"
            );
        }
        let roster = match roster {
            Some(path) => Some((
                crate::scene::roster::Roster::from_file(&path)?,
                papers,
                seed,
            )),
            None => None,
        };
        // No paths: the course's lectures/, all of it.
        let defaulted = paths.is_empty();
        let paths = default_paths(paths)?;
        let (course_file, named) = course_file(&paths);
        let whole_course = named || defaulted;
        let course = crate::scene::Course::load(&course_file)?;
        let out = out
            .or(course.output.clone())
            .unwrap_or_else(|| PathBuf::from("site"));
        Ok(Build {
            paths,
            course_file,
            whole_course,
            out,
            templates,
            timings,
            fidelity,
            cache: (!no_cache).then(|| Cache::new(&cache)),
            roster,
            pdfs_later,
        })
    }

    /// Derives every scene (or takes it from the cache) and writes the site, or writes nothing
    /// and says why.
    pub fn run(&self) -> Result<Built, NotBuilt> {
        let start = std::time::Instant::now();
        let (course, scenes) = self.load()?;
        let (reports, cached) = self.derive(scenes)?;
        let templates =
            crate::site::read_templates(self.templates.as_deref()).map_err(stages::other)?;
        let mut made = self.render(reports, &course, &templates)?;
        let mut site = std::mem::take(&mut made.rendered.files);
        let mut warnings = std::mem::take(&mut made.warnings);
        let mut pdfs = self.typeset_site(&mut made.rendered, &mut site, &mut warnings)?;
        let papers = self.typeset_papers(made.papers.take(), &mut warnings, &mut pdfs.failed)?;
        for n in &made.rendered.notes {
            eprintln!("mechbook: note: {n}");
        }
        for w in &warnings {
            eprintln!("mechbook: warning: {w}");
        }
        crate::site::write_site(&self.out, &site).map_err(stages::other)?;
        let papers = match papers {
            Some((dir, staging, students)) => {
                staging.finish().map_err(stages::other)?;
                Some((dir, students))
            }
            None => None,
        };
        for f in &pdfs.failed {
            eprintln!("mechbook: error: {f}");
        }
        let seconds = start.elapsed().as_secs_f64();
        let summary = self.summary(&site, &made, &cached, &pdfs, papers, seconds);
        let mut failures = std::mem::take(&mut made.failures);
        failures.extend(pdfs.failed);
        Ok(Built {
            summary,
            failures,
            pdfs_pending: pdfs.pending,
        })
    }

    /// Refuses an output folder that a build must not replace (one with other content, or
    /// holding the inputs: the scene files, the folders named, the templates, the current
    /// folder); returns the scene files.
    pub fn check_output(&self) -> Result<Vec<PathBuf>> {
        let files = find(&self.paths)?;
        let mut inputs = self.paths.clone();
        inputs.extend(files.iter().cloned());
        inputs.extend(self.templates.clone());
        inputs.push(PathBuf::from("."));
        // Nothing written is, or lies inside, what the course is read from.
        let sources = crate::site::Sources::of_course(
            &self.paths,
            &files,
            &self.course_file,
            self.templates.as_deref(),
            self.roster.as_ref().map(|(r, _, _)| r.source.as_path()),
        );
        if let Some(cache) = &self.cache {
            crate::site::guard::check_holds_no_input(cache.dir(), &inputs)?;
            sources.check_apart("--cache folder", cache.dir(), ".mechbook-cache")?;
        }
        if let Some((roster, papers, _)) = &self.roster {
            inputs.push(roster.source.clone());
            crate::site::check_output(papers, &inputs)?;
            sources.check_apart("--papers folder", papers, "papers/")?;
            let (site, papers_at) = (
                crate::site::guard::resolve(&self.out),
                crate::site::guard::resolve(papers),
            );
            if site.starts_with(&papers_at) || papers_at.starts_with(&site) {
                anyhow::bail!(
                    "--papers {} and the site's folder {} overlap: the papers have students' \
                     names and the site may be published, so give them folders apart",
                    papers.display(),
                    self.out.display()
                );
            }
        }
        crate::site::check_output(&self.out, &inputs)?;
        sources.check_apart("output folder", &self.out, "site/")?;
        Ok(files)
    }

    /// The files and folders a change to which calls for a new build.
    pub fn watched(&self) -> Vec<PathBuf> {
        let mut w = self.paths.clone();
        w.push(self.course_file.clone());
        w.extend(self.templates.clone());
        w
    }

    pub fn out(&self) -> &Path {
        &self.out
    }

    /// The folders a build writes: the output, the cache and the roster's papers.
    pub fn written(&self) -> Vec<PathBuf> {
        let mut w = vec![self.out.clone()];
        w.extend(self.cache.as_ref().map(|c| c.dir().to_path_buf()));
        w.extend(self.roster.as_ref().map(|(_, dir, _)| dir.clone()));
        w
    }
}

/// The course file for `paths`: `mechbook.toml` in a folder named (and then the whole course is
/// built), else the nearest one in a folder above the first path (`build course/lectures` finds
/// `course/mechbook.toml`), else the working folder's.
pub(super) fn course_file(paths: &[PathBuf]) -> (PathBuf, bool) {
    if let Some(f) = paths
        .iter()
        .map(|p| p.join("mechbook.toml"))
        .find(|p| p.is_file())
    {
        return (f, true);
    }
    let above = paths
        .first()
        .and_then(|p| std::path::absolute(p).ok())
        .and_then(|p| {
            p.ancestors()
                .skip(1)
                .map(|a| a.join("mechbook.toml"))
                .find(|f| f.is_file())
        });
    (
        above.unwrap_or_else(|| PathBuf::from("mechbook.toml")),
        false,
    )
}

pub fn run(args: BuildArgs) -> Result<ExitCode> {
    let status_file = args.status_file.clone();
    let result = Build::new(args)
        .map_err(NotBuilt::Other)
        .and_then(|build| build.run());
    if let Some(path) = &status_file {
        let json = serde_json::to_vec(&Outcome::of(&result))?;
        crate::site::replace_file(path, &json)?;
    }
    match result {
        Ok(built) => {
            eprintln!("mechbook: {}", built.summary);
            Ok(if built.failures.is_empty() {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            })
        }
        Err(not_built) => {
            report_not_built(not_built)?;
            Ok(ExitCode::from(1))
        }
    }
}

/// Prints why nothing was built: each bad scene, then a count. Scenes that could not be
/// derived were printed as they failed; any other reason is returned, for `main` to print.
pub fn report_not_built(not_built: NotBuilt) -> Result<()> {
    match not_built {
        NotBuilt::Scenes(messages) => {
            for m in &messages {
                eprintln!("mechbook: error: {m}");
            }
            eprintln!(
                "mechbook: {}; nothing was derived",
                crate::base::format::count(messages.len(), "bad scene file")
            );
        }
        NotBuilt::Derive(messages) => eprintln!(
            "mechbook: {} could not be derived; the site was not written",
            crate::base::format::count(messages.len(), "scene")
        ),
        NotBuilt::Other(e) => return Err(e),
    }
    Ok(())
}

/// The documents typeset (or taken from the cache), with a progress bar on a terminal: a
/// roster's papers can take a while.
fn typeset_with_progress(
    sources: &[crate::render::pdf::PdfSource],
    store: Option<&dyn crate::render::pdf::batch::PdfStore>,
    keep: &mut crate::render::pdf::batch::Keep<crate::site::SiteError>,
) -> Result<crate::render::pdf::batch::Typeset, crate::site::SiteError> {
    use std::io::IsTerminal;
    let terminal = std::io::stderr().is_terminal();
    let mut progress = |done: usize, total: usize, path: &str| {
        if terminal {
            eprint!("\r\x1b[2K{}", super::progress_bar(done, total, path));
        }
    };
    let made = crate::render::pdf::batch::typeset_all(sources, store, &mut progress, keep);
    if terminal {
        eprint!("\r\x1b[2K");
    }
    made
}
