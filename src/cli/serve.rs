//! `mechbook serve`: build, serve on 127.0.0.1, and rebuild and reload on every edit.

use super::build::{Build, BuildArgs, Outcome};
use crate::serve::{Server, is_hidden};
use anyhow::{Context, Result};
use notify::Watcher;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::mpsc;
use std::time::{Duration, Instant};

#[derive(clap::Args, Debug)]
pub struct ServeArgs {
    #[command(flatten)]
    pub build: BuildArgs,
    /// The port on 127.0.0.1 (default: a free one, printed at the start).
    #[arg(long, default_value_t = 0)]
    pub port: u16,
    /// Open the index in a browser: `$BROWSER` when it is set, else the desktop's default
    /// (xdg-open; open on macOS).
    #[arg(long)]
    pub open: bool,
}

/// What wakes the build loop.
enum Wake {
    Changed(notify::Result<notify::Event>),
    /// A child build has finished: an edit's page-first build, or the full build that typesets
    /// the PDFs after it (its number, and what it did).
    Built(u64, Outcome),
    Stop,
}

/// Edits that arrive within this of each other start one build: an editor's save is several
/// events (write, rename, chmod) within a millisecond or two, and "save all" touches several
/// files. It is part of every reload's wait. An edit that comes soon after, while the page's
/// build has only just started, stops that build (it may have read a file half-saved) and
/// starts another, so the wait need not cover a slow save (it was 30 ms).
const SETTLE: Duration = Duration::from_millis(5);

/// A page's build younger than this is stopped by an edit; an older one runs to its end and is
/// shown, and the edit's build follows it: saves in quick succession (an editor saving as one
/// types) still show, rather than each stopping the last.
const RESTART_WITHIN: Duration = Duration::from_millis(30);

pub fn run(args: ServeArgs) -> Result<ExitCode> {
    let build = Build::new(args.build.clone())?;
    // Editing a scene cannot fix a refused output folder, and one that is not the site's must
    // not be served: stop before serving anything.
    build.check_output()?;
    let (wake, woken) = mpsc::channel();
    let on_interrupt = {
        let wake = wake.clone();
        move || {
            let _ = wake.send(Wake::Stop);
        }
    };
    // The port first: a taken one is said at once, before any build.
    let server = Server::start(build.out(), args.port, on_interrupt)?;
    let builder = ChildBuild::new(&args.build, build.out())?;
    // Each edit's page first, from a build that leaves the PDFs not in the cache to a full
    // build after it; that one is stopped by the next edit.
    let needs_papers = args.build.roster.is_some();
    let mut runs = 0u64;
    // Run 0, waited for here: its `Built` message is for no run awaited.
    let first = builder
        .start(0, Stage::PageFirst, wake.clone())
        .map_or_else(not_started, ChildRun::finish);
    let follow = pdfs_follow(&first, needs_papers);
    server.built(first.written, first.problems, first.pdfs_pending);
    let mut pdfs = follow
        .then(|| start_pdfs(&builder, &mut runs, &wake))
        .flatten();
    let url = format!("http://{}/", server.addr());
    eprintln!(
        "mechbook: serving {url} from {} (Ctrl-C to stop); watching {}",
        build.out().display(),
        build
            .watched()
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    if args.open {
        open_in_browser(&url);
    }
    let mut watcher = notify::recommended_watcher({
        let wake = wake.clone();
        move |event| {
            let _ = wake.send(Wake::Changed(event));
        }
    })
    .context("cannot watch the files for changes")?;
    let watched = build.watched();
    let relevant = Relevant::new(&watched, &build.written());
    for (target, mode) in relevant.watches() {
        watcher
            .watch(&target, mode)
            .with_context(|| format!("cannot watch {}", target.display()))?;
    }
    // The edit's page-first build while it runs, and when the edit that started it was seen.
    let mut page: Option<(ChildRun, Instant)> = None;
    loop {
        let first = match woken.recv() {
            Ok(Wake::Changed(Ok(event))) => event,
            Ok(Wake::Changed(Err(e))) => {
                eprintln!("mechbook: warning: watching: {e}");
                continue;
            }
            Ok(Wake::Built(run, outcome)) => {
                if let Some((p, seen)) = page.take_if(|(p, _)| p.run == run) {
                    let _ = p.finish();
                    let follow = page_built(&server, outcome, seen, needs_papers);
                    pdfs = follow
                        .then(|| start_pdfs(&builder, &mut runs, &wake))
                        .flatten();
                } else if pdfs.as_ref().is_some_and(|p| p.run == run) {
                    let made = pdfs.take().map(|p| {
                        let made = p.started.elapsed();
                        let _ = p.finish();
                        made
                    });
                    server.built(outcome.written, outcome.problems, Vec::new());
                    if let Some(made) = made {
                        eprintln!(
                            "mechbook: the PDFs are ready, {} ms after the page; {} open page(s) told to reload",
                            made.as_millis(),
                            server.listeners()
                        );
                    }
                }
                continue;
            }
            Ok(Wake::Stop) | Err(_) => break,
        };
        // Reading a file is an event too (the build reads them all): only writes count.
        let is_edit = matches!(
            first.kind,
            notify::EventKind::Create(_)
                | notify::EventKind::Modify(_)
                | notify::EventKind::Remove(_)
        );
        if !is_edit || !relevant.any(&first.paths) {
            continue;
        }
        let seen = Instant::now();
        let mut stop = false;
        // Take the rest of this save, then build once. A build that finishes meanwhile is
        // stopped below (its finish unheard): this edit's build replaces it.
        while let Ok(w) = woken.recv_timeout(SETTLE) {
            if matches!(w, Wake::Stop) {
                stop = true;
                break;
            }
        }
        if stop {
            break;
        }
        let changed = first
            .paths
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ");
        eprintln!("mechbook: changed: {changed}");
        // A folder that was deleted and made again (a `git checkout`) lost its watch: watch
        // it anew before the build reads it, so that no later edit goes unseen. Its parent's
        // watch saw it come back.
        for (target, mode) in relevant.watches() {
            let _ = watcher.unwatch(&target);
            if let Err(e) = watcher.watch(&target, mode)
                && target.exists()
            {
                eprintln!("mechbook: warning: cannot watch {}: {e}", target.display());
            }
        }
        // The last edit's PDFs are out of date, and its page too if it is still being built:
        // this build makes them.
        if let Some(p) = pdfs.take() {
            p.cancel();
        }
        if let Some((p, seen)) = page.take() {
            if p.started.elapsed() < RESTART_WITHIN {
                eprintln!("mechbook: the build of the last edit's page is stopped for this one");
                p.cancel();
            } else {
                // Shown, with no PDFs to follow: this edit's build makes them.
                let outcome = p.finish();
                page_built(&server, outcome, seen, needs_papers);
            }
        }
        runs += 1;
        match builder.start(runs, Stage::PageFirst, wake.clone()) {
            Ok(p) => page = Some((p, seen)),
            Err(e) => {
                let outcome = not_started(e);
                eprintln!("mechbook: error: {}", outcome.problems.join("; "));
                server.built(false, outcome.problems, Vec::new());
            }
        }
    }
    if let Some((p, _)) = page.take() {
        p.cancel();
    }
    if let Some(p) = pdfs.take() {
        p.cancel();
        eprintln!(
            "mechbook: stopped before the PDFs were typeset: {} lacks them until `mechbook \
             build` (or serve) runs again",
            build.out().display()
        );
    }
    eprintln!("mechbook: stopping");
    drop(watcher);
    server.stop();
    Ok(ExitCode::SUCCESS)
}

/// Tells the pages that an edit's page-first build has finished (`seen`: when the edit was
/// seen), and says so; whether the full build is to follow it.
fn page_built(server: &Server, outcome: Outcome, seen: Instant, needs_papers: bool) -> bool {
    if !outcome.written {
        eprintln!("mechbook: still serving the last good site, with the error on every page");
    }
    let follow = pdfs_follow(&outcome, needs_papers);
    server.built(outcome.written, outcome.problems, outcome.pdfs_pending);
    eprintln!(
        "mechbook: {} ms from the change to telling {} open page(s) to reload",
        seen.elapsed().as_millis(),
        server.listeners()
    );
    follow
}

/// Whether a page-first build is followed by the full one: it wrote the site and left PDFs
/// (or a roster's papers) out of it.
fn pdfs_follow(outcome: &Outcome, needs_papers: bool) -> bool {
    let follow = outcome.written && (!outcome.pdfs_pending.is_empty() || needs_papers);
    if follow {
        eprintln!(
            "mechbook: the page first; then {} PDF(s){}",
            outcome.pdfs_pending.len(),
            if needs_papers { " and the papers" } else { "" }
        );
    }
    follow
}

/// Starts the full build that typesets the PDFs a page-first build left out.
fn start_pdfs(builder: &ChildBuild, runs: &mut u64, wake: &mpsc::Sender<Wake>) -> Option<ChildRun> {
    *runs += 1;
    builder
        .start(*runs, Stage::Full, wake.clone())
        .map_err(|e| eprintln!("mechbook: warning: cannot start the build of the PDFs: {e:#}"))
        .ok()
}

/// Which of an edit's two builds a child runs.
#[derive(Clone, Copy, PartialEq)]
enum Stage {
    /// The pages, with the PDFs that are not in the cache left out (`--pdfs-later`).
    PageFirst,
    /// Everything: the scenes from the cache, and the PDFs typeset.
    Full,
}

/// A child build running: an edit's page-first build, or the full build after it. A thread
/// waits for it and tells the build loop.
struct ChildRun {
    run: u64,
    out: PathBuf,
    started: Instant,
    child: std::sync::Arc<std::sync::Mutex<std::process::Child>>,
    waiter: std::thread::JoinHandle<Outcome>,
}

impl ChildRun {
    /// Stops the build, if it is still running: a later edit's build replaces it. The site is
    /// written whole or not at all, so a stopped build leaves the site as it was.
    fn cancel(self) {
        {
            let mut child = self.child.lock().unwrap_or_else(|p| p.into_inner());
            if matches!(child.try_wait(), Ok(None)) {
                let _ = child.kill();
            }
        }
        let _ = self.waiter.join();
        crate::site::remove_leftovers(&self.out);
    }

    /// Waits for the build to end, and what it did. Its `Built` message is sent all the same:
    /// a caller that waits here has stopped awaiting its run.
    fn finish(self) -> Outcome {
        self.waiter
            .join()
            .unwrap_or_else(|p| std::panic::resume_unwind(p))
    }
}

/// How often the waiter looks whether a build whose output has closed has ended (the process
/// closes its files a moment before its parent can see that it ended).
const POLL: Duration = Duration::from_millis(1);

/// Each build runs as a child process, `mechbook build` with serve's options, so that this
/// process never holds the engine: `check`, `derive` and another `build` wait at most for one
/// rebuild. The cache makes a rebuild cheap: only the edited scenes are derived.
struct ChildBuild {
    exe: PathBuf,
    args: Vec<std::ffi::OsString>,
    status: PathBuf,
    /// The full build's report, apart: it runs while the next page-first build may start.
    full_status: PathBuf,
    scratch: PathBuf,
    out: PathBuf,
}

impl ChildBuild {
    fn new(args: &BuildArgs, out: &Path) -> Result<ChildBuild> {
        let exe = std::env::current_exe().context("cannot find this program to run its builds")?;
        let scratch = crate::site::scratch::folder("serve")
            .context("cannot make a temporary folder for the builds' reports")?;
        // `--no-cache` leaves the course's cache unread and unwritten. Serve's own builds still
        // share a cache of their own, in its temporary folder (removed with it when serve
        // stops): without one each edit derived every scene twice, for the page and again for
        // its PDFs.
        let mut args = args.clone();
        if args.no_cache {
            args.no_cache = false;
            args.cache = scratch.join("cache");
        }
        Ok(ChildBuild {
            exe,
            args: args.command_line(out),
            status: scratch.join("status.json"),
            full_status: scratch.join("status-full.json"),
            scratch,
            out: out.to_path_buf(),
        })
    }

    fn command(&self, status: &Path) -> std::process::Command {
        crate::site::scratch::remove_file(status);
        let mut c = std::process::Command::new(&self.exe);
        c.args(&self.args)
            .arg("--status-file")
            .arg(status)
            .stdin(std::process::Stdio::null());
        die_with_parent(&mut c);
        c
    }

    /// A build started as `run`: a thread waits for it and sends its outcome. The page-first
    /// build's messages go to this terminal as it prints them; the full build's notes are the
    /// page-first build's, said already, and the rest (typesetting's warnings and errors, the
    /// summary) go on to this terminal.
    fn start(&self, run: u64, stage: Stage, wake: mpsc::Sender<Wake>) -> Result<ChildRun> {
        let status = match stage {
            Stage::PageFirst => self.status.clone(),
            Stage::Full => self.full_status.clone(),
        };
        let mut command = self.command(&status);
        if stage == Stage::PageFirst {
            command.arg("--pdfs-later");
        } else {
            command.stderr(std::process::Stdio::piped());
        }
        // A build prints nothing on standard output: the pipe closes when it ends, which the
        // waiter hears at once, where polling for its end cost a reload up to 10 ms.
        let mut child = command
            .stdout(std::process::Stdio::piped())
            .spawn()
            .with_context(|| format!("cannot run {}", self.exe.display()))?;
        let ended_pipe = child.stdout.take();
        if let Some(err) = child.stderr.take() {
            std::thread::spawn(move || {
                use std::io::BufRead;
                for line in std::io::BufReader::new(err).lines().map_while(Result::ok) {
                    if !line.starts_with("mechbook: note: ") {
                        eprintln!("{line}");
                    }
                }
            });
        }
        let child = std::sync::Arc::new(std::sync::Mutex::new(child));
        let exe = self.exe.clone();
        let waiter = std::thread::spawn({
            let child = child.clone();
            move || {
                if let Some(mut pipe) = ended_pipe {
                    let _ = std::io::copy(&mut pipe, &mut std::io::sink());
                }
                let ended = loop {
                    let polled = child.lock().unwrap_or_else(|p| p.into_inner()).try_wait();
                    match polled {
                        Ok(None) => std::thread::sleep(POLL),
                        Ok(Some(s)) => break Ok(s),
                        Err(e) => break Err(e),
                    }
                };
                let outcome = outcome(ended, &status, &exe);
                let _ = wake.send(Wake::Built(run, outcome.clone()));
                outcome
            }
        });
        Ok(ChildRun {
            run,
            out: self.out.clone(),
            started: Instant::now(),
            child,
            waiter,
        })
    }
}

/// A build outlives a serve that is killed outright (SIGKILL, which serve cannot hear): it went
/// on writing the site, into a folder its owner may be removing. On Linux the kernel sends it
/// SIGTERM when the serve thread that started it ends: the loop thread, which lives as long as
/// serve does.
fn die_with_parent(command: &mut std::process::Command) {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::process::CommandExt;
        // SAFETY: between fork and exec the closure calls only prctl, which is
        // async-signal-safe and touches no memory of the parent's.
        #[allow(unsafe_code)]
        unsafe {
            command.pre_exec(|| {
                if libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGTERM) == -1 {
                    return Err(std::io::Error::last_os_error());
                }
                Ok(())
            });
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = command;
}

/// A build that could not be started, as the pages say it.
fn not_started(e: anyhow::Error) -> Outcome {
    Outcome {
        written: false,
        problems: vec![format!("cannot start the build: {e:#}")],
        pdfs_pending: Vec::new(),
    }
}

/// What a child build did: its report, or why there is none.
fn outcome(ran: std::io::Result<std::process::ExitStatus>, status: &Path, exe: &Path) -> Outcome {
    let report = std::fs::read(status)
        .ok()
        .and_then(|bytes| serde_json::from_slice::<Outcome>(&bytes).ok());
    match (ran, report) {
        (_, Some(outcome)) => outcome,
        (Ok(status), None) => Outcome {
            written: false,
            problems: vec![format!(
                "the build stopped ({status}) without saying why: see serve's terminal"
            )],
            pdfs_pending: Vec::new(),
        },
        (Err(e), None) => Outcome {
            written: false,
            problems: vec![format!("cannot run {}: {e}", exe.display())],
            pdfs_pending: Vec::new(),
        },
    }
}

impl Drop for ChildBuild {
    fn drop(&mut self) {
        crate::site::scratch::remove(&self.scratch);
    }
}

/// The folder holding `path`, or `.` for a bare file name.
fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Which changed paths call for a build: inside a watched folder or the course file itself,
/// never in what the builds write (the output, the cache, the papers), and never under a hidden
/// name (the default cache, the site's staging folders, an editor's swap files) or an editor's
/// backup.
struct Relevant {
    folders: Vec<PathBuf>,
    files: Vec<PathBuf>,
    written: Vec<PathBuf>,
}

impl Relevant {
    fn new(watched: &[PathBuf], written: &[PathBuf]) -> Relevant {
        let absolute = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
        let (folders, files): (Vec<PathBuf>, Vec<PathBuf>) = watched
            .iter()
            .map(|p| absolute(p))
            .partition(|p| p.is_dir());
        Relevant {
            folders,
            files,
            written: written.iter().map(|p| absolute(p)).collect(),
        }
    }

    /// What to watch: each folder with all below it, and the folder holding each file or
    /// folder (without what is below), which sees a folder deleted and made again, and an
    /// editor replacing a file when it saves it. A parent inside a watched folder is left
    /// out: one watch of a path replaces another.
    fn watches(&self) -> Vec<(PathBuf, notify::RecursiveMode)> {
        let mut w: Vec<(PathBuf, notify::RecursiveMode)> = self
            .folders
            .iter()
            .map(|d| (d.clone(), notify::RecursiveMode::Recursive))
            .collect();
        for p in self.folders.iter().chain(&self.files) {
            let parent = folder_of(p);
            let covered = self.folders.iter().any(|d| parent.starts_with(d))
                || w.iter().any(|(q, _)| *q == parent);
            if !covered {
                w.push((parent, notify::RecursiveMode::NonRecursive));
            }
        }
        w
    }

    fn any(&self, paths: &[PathBuf]) -> bool {
        paths.iter().any(|p| self.is_relevant(p))
    }

    fn is_relevant(&self, path: &Path) -> bool {
        let backup = path
            .file_name()
            .is_some_and(|n| n.to_string_lossy().ends_with('~'));
        if backup || self.written.iter().any(|w| path.starts_with(w)) {
            return false;
        }
        self.files.iter().any(|f| f == path)
            || self
                .folders
                .iter()
                .any(|d| path.strip_prefix(d).is_ok_and(|rel| !is_hidden(rel)))
    }
}

/// Asks the desktop to open `url`; says so when it cannot, and goes on serving.
fn open_in_browser(url: &str) {
    let (program, args) = browser_command(std::env::var("BROWSER").ok().as_deref(), url);
    let spawned = std::process::Command::new(&program)
        .args(&args)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn();
    if spawned.is_err() {
        eprintln!("mechbook: warning: cannot run {program}; open {url} in a browser yourself");
    }
}

/// The command that opens `url`: `$BROWSER` when set (its first `:`-separated entry, with
/// `%s` standing for the address, or the address appended, as xdg-open reads it), else the
/// desktop's opener.
fn browser_command(browser: Option<&str>, url: &str) -> (String, Vec<String>) {
    if let Some(entry) = browser.and_then(|b| b.split(':').find(|e| !e.trim().is_empty())) {
        let mut words = entry.split_whitespace().map(str::to_owned);
        if let Some(program) = words.next() {
            let mut args: Vec<String> = words.collect();
            if args.iter().any(|a| a.contains("%s")) {
                args = args.iter().map(|a| a.replace("%s", url)).collect();
            } else {
                args.push(url.to_owned());
            }
            return (program, args);
        }
    }
    let opener = if cfg!(target_os = "macos") {
        "open"
    } else {
        "xdg-open"
    };
    (opener.to_owned(), vec![url.to_owned()])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_edits_of_inputs_call_for_a_build() {
        // `serve .`: the output, the cache and the build's staging folders are inside the
        // watched folder, and must not start a build (each build writes them: a loop), nor a
        // cache or papers' folder given a name that is not hidden.
        let r = Relevant {
            folders: vec![PathBuf::from("/c"), PathBuf::from("/c/templates")],
            files: vec![PathBuf::from("/c/mechbook.toml")],
            written: ["/c/site", "/c/cache", "/c/papers"]
                .map(PathBuf::from)
                .to_vec(),
        };
        assert!(r.is_relevant(Path::new("/c/lectures/l1/01-book.toml")));
        assert!(r.is_relevant(Path::new("/c/./mechbook.toml")));
        assert!(r.is_relevant(Path::new("/c/templates/page.html")));
        for ignored in [
            "/c/site/index.html",
            "/c/.site.building-42/index.html",
            "/c/.mechbook-cache/ab12/report.json",
            "/c/cache/book.report.0123456789abcdef.json",
            "/c/papers/001.pdf",
            "/c/lectures/.01-book.toml.swp",
            "/c/lectures/01-book.toml~",
            "/elsewhere/x.toml",
        ] {
            assert!(!r.is_relevant(Path::new(ignored)), "{ignored}");
        }
    }

    #[test]
    fn the_browser_comes_from_browser_when_set() {
        let url = "http://127.0.0.1:8000/";
        let words = |b: Option<&str>| {
            let (p, a) = browser_command(b, url);
            std::iter::once(p).chain(a).collect::<Vec<_>>().join(" ")
        };
        assert_eq!(words(Some("firefox")), "firefox http://127.0.0.1:8000/");
        assert_eq!(
            words(Some("chromium --new-window %s:firefox")),
            "chromium --new-window http://127.0.0.1:8000/"
        );
        assert_eq!(words(Some(" ")), words(None));
        assert!(words(None).ends_with("open http://127.0.0.1:8000/"));
    }
}
