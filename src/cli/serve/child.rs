//! Each build `serve` runs, as a child process: started, waited for by a thread that tells the
//! build loop, and stopped when a later edit replaces it.

use crate::cli::build::{BuildArgs, Outcome};
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// What wakes the build loop.
pub(super) enum Wake {
    Changed(notify::Result<notify::Event>),
    /// A child build has finished: an edit's page-first build, or the full build that typesets
    /// the PDFs after it (its number, and what it did).
    Built(u64, Outcome),
    Stop,
}

/// Which of an edit's two builds a child runs.
#[derive(Clone, Copy, PartialEq)]
pub(super) enum Stage {
    /// The pages, with the PDFs that are not in the cache left out (`--pdfs-later`).
    PageFirst,
    /// Everything: the scenes from the cache, and the PDFs typeset.
    Full,
}

/// A child build running: an edit's page-first build, or the full build after it. A thread
/// waits for it and tells the build loop.
pub(super) struct ChildRun {
    pub(super) run: u64,
    out: PathBuf,
    pub(super) started: Instant,
    child: std::sync::Arc<std::sync::Mutex<std::process::Child>>,
    waiter: std::thread::JoinHandle<Outcome>,
}

impl ChildRun {
    /// Stops the build, if it is still running: a later edit's build replaces it. The site is
    /// written whole or not at all, so a stopped build leaves the site as it was.
    pub(super) fn cancel(self) {
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
    pub(super) fn finish(self) -> Outcome {
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
pub(super) struct ChildBuild {
    exe: PathBuf,
    args: Vec<std::ffi::OsString>,
    status: PathBuf,
    /// The full build's report, apart: it runs while the next page-first build may start.
    full_status: PathBuf,
    scratch: PathBuf,
    out: PathBuf,
}

impl ChildBuild {
    pub(super) fn new(args: &BuildArgs, out: &Path) -> Result<ChildBuild> {
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
    pub(super) fn start(
        &self,
        run: u64,
        stage: Stage,
        wake: mpsc::Sender<Wake>,
    ) -> Result<ChildRun> {
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
pub(super) fn not_started(e: anyhow::Error) -> Outcome {
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
