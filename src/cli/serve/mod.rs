//! `mechbook serve`: build, serve on 127.0.0.1, and rebuild and reload on every edit.

mod child;
mod relevant;

use super::build::{Build, BuildArgs, Outcome};
use crate::base::format::count;
use crate::serve::Server;
use anyhow::{Context, Result};
use child::{ChildBuild, ChildRun, Stage, Wake, not_started};
use notify::Watcher;
use relevant::Relevant;
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
    let mut serving = Serving {
        server: &server,
        builder: &builder,
        wake: &wake,
        needs_papers: args.build.roster.is_some(),
        runs: 0,
        pdfs: None,
        page: None,
    };
    serving.first_build();
    let url = announce(&build, &server);
    if args.open {
        open_in_browser(&url);
    }
    let relevant = Relevant::new(&build.watched(), &build.written());
    let mut watcher = watch(&relevant, &wake)?;
    loop {
        let first = match woken.recv() {
            Ok(Wake::Changed(Ok(event))) => event,
            Ok(Wake::Changed(Err(e))) => {
                eprintln!("mechbook: warning: watching: {e}");
                continue;
            }
            Ok(Wake::Built(run, outcome)) => {
                serving.built(run, outcome);
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
        if told_to_stop_while_settling(&woken) {
            break;
        }
        let changed = first
            .paths
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ");
        eprintln!("mechbook: changed: {changed}");
        watch_again(&mut watcher, &relevant);
        serving.rebuild(seen);
    }
    serving.stop(build.out());
    eprintln!("mechbook: stopping");
    drop(watcher);
    server.stop();
    Ok(ExitCode::SUCCESS)
}

/// Says where the site is served and what is watched; the site's address.
fn announce(build: &Build, server: &Server) -> String {
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
    url
}

/// A watcher of every path that can call for a build, waking the build loop.
fn watch(relevant: &Relevant, wake: &mpsc::Sender<Wake>) -> Result<notify::RecommendedWatcher> {
    let mut watcher = notify::recommended_watcher({
        let wake = wake.clone();
        move |event| {
            let _ = wake.send(Wake::Changed(event));
        }
    })
    .context("cannot watch the files for changes")?;
    for (target, mode) in relevant.watches() {
        watcher
            .watch(&target, mode)
            .with_context(|| format!("cannot watch {}", target.display()))?;
    }
    Ok(watcher)
}

/// Takes the rest of an edit's save, so that it starts one build; whether serve was told to
/// stop meanwhile. A build that finishes meanwhile is stopped by the edit's build (its finish
/// unheard): that build replaces it.
fn told_to_stop_while_settling(woken: &mpsc::Receiver<Wake>) -> bool {
    while let Ok(w) = woken.recv_timeout(SETTLE) {
        if matches!(w, Wake::Stop) {
            return true;
        }
    }
    false
}

/// A folder that was deleted and made again (a `git checkout`) lost its watch: watches it anew
/// before the build reads it, so that no later edit goes unseen. Its parent's watch saw it come
/// back.
fn watch_again(watcher: &mut notify::RecommendedWatcher, relevant: &Relevant) {
    for (target, mode) in relevant.watches() {
        let _ = watcher.unwatch(&target);
        if let Err(e) = watcher.watch(&target, mode)
            && target.exists()
        {
            eprintln!("mechbook: warning: cannot watch {}: {e}", target.display());
        }
    }
}

/// The build loop's state between wakes: the child builds under way, and how many were
/// started. Each edit's page comes first, from a build that leaves the PDFs not in the cache to
/// a full build after it; that one is stopped by the next edit.
struct Serving<'a> {
    server: &'a Server,
    builder: &'a ChildBuild,
    wake: &'a mpsc::Sender<Wake>,
    needs_papers: bool,
    runs: u64,
    /// The full build that typesets the PDFs after a page, while it runs.
    pdfs: Option<ChildRun>,
    /// The edit's page-first build while it runs, and when the edit that started it was seen.
    page: Option<(ChildRun, Instant)>,
}

impl Serving<'_> {
    /// Run 0, waited for here: its `Built` message is for no run awaited.
    fn first_build(&mut self) {
        let first = self
            .builder
            .start(0, Stage::PageFirst, self.wake.clone())
            .map_or_else(not_started, ChildRun::finish);
        let follow = pdfs_follow(&first, self.needs_papers);
        self.server
            .built(first.written, first.problems, first.pdfs_pending);
        self.pdfs = follow.then(|| self.start_pdfs()).flatten();
    }

    /// A child build has finished: the edit's page, then its PDFs; any other run is one
    /// stopped, whose finish is not awaited.
    fn built(&mut self, run: u64, outcome: Outcome) {
        if let Some((p, seen)) = self.page.take_if(|(p, _)| p.run == run) {
            let _ = p.finish();
            let follow = page_built(self.server, outcome, seen, self.needs_papers);
            self.pdfs = follow.then(|| self.start_pdfs()).flatten();
        } else if self.pdfs.as_ref().is_some_and(|p| p.run == run) {
            let made = self.pdfs.take().map(|p| {
                let made = p.started.elapsed();
                let _ = p.finish();
                made
            });
            self.server
                .built(outcome.written, outcome.problems, Vec::new());
            if let Some(made) = made {
                eprintln!(
                    "mechbook: the PDFs are ready, {} ms after the page; {} told to reload",
                    made.as_millis(),
                    count(self.server.listeners(), "open page")
                );
            }
        }
    }

    /// Starts an edit's page-first build (`seen`: when the edit was seen). The last edit's
    /// PDFs are out of date, and its page too if it is still being built: this build makes
    /// them.
    fn rebuild(&mut self, seen: Instant) {
        if let Some(p) = self.pdfs.take() {
            p.cancel();
        }
        if let Some((p, seen)) = self.page.take() {
            if p.started.elapsed() < RESTART_WITHIN {
                eprintln!("mechbook: the build of the last edit's page is stopped for this one");
                p.cancel();
            } else {
                // Shown, with no PDFs to follow: this edit's build makes them.
                let outcome = p.finish();
                page_built(self.server, outcome, seen, self.needs_papers);
            }
        }
        self.runs += 1;
        match self
            .builder
            .start(self.runs, Stage::PageFirst, self.wake.clone())
        {
            Ok(p) => self.page = Some((p, seen)),
            Err(e) => {
                let outcome = not_started(e);
                eprintln!("mechbook: error: {}", outcome.problems.join("; "));
                self.server.built(false, outcome.problems, Vec::new());
            }
        }
    }

    /// Starts the full build that typesets the PDFs a page-first build left out.
    fn start_pdfs(&mut self) -> Option<ChildRun> {
        self.runs += 1;
        self.builder
            .start(self.runs, Stage::Full, self.wake.clone())
            .map_err(|e| eprintln!("mechbook: warning: cannot start the build of the PDFs: {e:#}"))
            .ok()
    }

    /// Stops the builds still running, saying what the site lacks for it.
    fn stop(mut self, out: &std::path::Path) {
        if let Some((p, _)) = self.page.take() {
            p.cancel();
        }
        if let Some(p) = self.pdfs.take() {
            p.cancel();
            eprintln!(
                "mechbook: stopped before the PDFs were typeset: {} lacks them until `mechbook \
                 build` (or serve) runs again",
                out.display()
            );
        }
    }
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
        "mechbook: {} ms from the change to telling {} to reload",
        seen.elapsed().as_millis(),
        count(server.listeners(), "open page")
    );
    follow
}

/// Whether a page-first build is followed by the full one: it wrote the site and left PDFs
/// (or a roster's papers) out of it.
fn pdfs_follow(outcome: &Outcome, needs_papers: bool) -> bool {
    let follow = outcome.written && (!outcome.pdfs_pending.is_empty() || needs_papers);
    if follow {
        eprintln!(
            "mechbook: the page first; then {}{}",
            count(outcome.pdfs_pending.len(), "PDF"),
            if needs_papers { " and the papers" } else { "" }
        );
    }
    follow
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
