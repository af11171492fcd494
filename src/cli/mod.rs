//! The command line (clap derive): one file per command, each an args struct and a `run`; the
//! doc comments are the help text.

mod bench;
mod bench_course;
mod bench_links;
mod bench_roster;
mod bench_serve;
mod bench_timing;
mod build;
mod check;
mod completions;
mod derive;
mod init;
mod serve;
mod spin;

use crate::model::fidelity::{Fidelity, FidelityError};
use crate::pipeline::{self, Progress, SceneReport};
use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

/// Reproduce every derivation of a rigid-body mechanics course twice, exactly (Symbolica) and
/// numerically (nalgebra), and check both against what the lecture notes claim.
///
/// Scenes are TOML files, one per derivation (see docs/scenes.md). Exit status: 0 when every
/// check passes, 1 when a check fails or an input is bad, 2 when the command line is wrong.
#[derive(Parser, Debug)]
#[command(name = "mechbook", version, about, long_about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Start a new course in a new or empty folder: mechbook.toml, one lecture with an example
    /// scene, a problem sheet and a free-body plot, a .gitignore and a README saying what to
    /// edit. It builds at once.
    Init(init::InitArgs),
    /// Derive and verify every scene; print a summary table; fail when anything changed.
    ///
    /// A scene records the verdict it expects for each claim of the notes, optionally its exact
    /// results, and a problem's variants (so that students' sheets cannot change unnoticed).
    /// `check` exits with 1 when a verdict, a result or a variant differs from the record, or
    /// when one has no record yet, or when exact and numeric results disagree: a regression
    /// test for the derivations. It writes no files, unless `--bless` is given.
    Check(check::CheckArgs),
    /// Build the course site: an index, one page per scene, and per lecture a student and an
    /// instructor handout for printing, a problem sheet with its answer key, a Moodle quiz per
    /// problem, and each lecture's problems for Canvas, Blackboard and QTI 2.1 systems
    /// (docs/lms.md).
    ///
    /// Course settings (title, author, base_url, output) come from mechbook.toml when it
    /// exists. The site is written to a temporary folder beside the output and renamed into
    /// place, so a failed build leaves the previous site untouched; the same scenes give the same
    /// bytes. Exits with 1 (after writing) when a check of the scenes fails.
    Build(build::BuildArgs),
    /// Integrate a free rigid body's Euler equations and compare with the exact solution.
    ///
    /// The body frame is principal: give the three principal moments and ω(0) in it. Methods:
    /// `exact` (Jacobi elliptic functions: the reference), `rk4` and the splittings `splitting`
    /// (Strang, 2nd order) and `splitting4` (triple jump, 4th order) with a fixed `--step`
    /// (default 0.01), `dopri` (adaptive Dormand–Prince 5(4)) with `--tol` (default 1e-9).
    /// Prints ω(T), its error against the exact solution, the largest drift of the energy and
    /// of |L| along the way, the right-hand-side evaluations and the seconds.
    Spin(spin::SpinArgs),
    /// Measure the speed–accuracy trade and print a Markdown report.
    ///
    /// The integrators side by side on REFERENCE.md's case (I = 1,2,3, ω(0) = 1,0.1,0.5, 100
    /// periods); error against cost for every integrator and quadrature method, with Pareto
    /// fronts; whole-site builds in child processes (cold at each fidelity, warm, after a
    /// one-scene edit, numerics only) with their peak memory; and the symbolic stage alone.
    /// Takes about a minute. With --out, writes bench.md and the SVGs into that folder.
    Bench(bench::BenchArgs),
    /// Derive one scene and print its steps, results, numeric cross-check and claims.
    Derive(derive::DeriveArgs),
    /// Build the site, serve it on 127.0.0.1, and rebuild and reload open pages on every edit.
    ///
    /// Watches the scenes, the templates and mechbook.toml; only the scenes that changed are
    /// derived again (the build cache). A build that fails keeps the last good site served and
    /// shows the error, with file:line:column, at the top of every page until it is fixed. The
    /// pages are the same bytes as `build`'s, but for a small live-reload script. Stop with
    /// Ctrl-C.
    Serve(serve::ServeArgs),
    /// Print a tab-completion script for a shell, for example
    /// `mechbook completions bash > ~/.local/share/bash-completion/completions/mechbook`.
    Completions(completions::CompletionsArgs),
}

/// `--fidelity`, shared by the commands that run the numeric stage.
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct FidelityArg {
    /// draft, standard, reference, or a target tolerance such as 1e-6: overrides each scene's
    /// `[numeric] fidelity` (default standard).
    #[arg(long, value_parser = parse_fidelity)]
    pub fidelity: Option<Fidelity>,
}

/// The process's peak resident memory (Linux's VmHWM), for the build summary and `bench`.
pub fn peak_memory_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

fn parse_fidelity(s: &str) -> Result<Fidelity, FidelityError> {
    Fidelity::parse(s)
}

/// Parses the command line and runs it. Usage errors exit with 2 (clap's convention).
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let code = match run(cli) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("mechbook: error: {}", one_line(&e));
            ExitCode::from(1)
        }
    };
    // `bench --course-only` reads each child's own peak from its last line.
    if std::env::var_os(PEAK_MEMORY_ENV).is_some()
        && let Some(m) = peak_memory_mib()
    {
        eprintln!("mechbook: peak memory {m:.1} MiB");
    }
    code
}

/// Set in a child's environment by `bench`: the child prints its peak memory as it exits.
pub const PEAK_MEMORY_ENV: &str = "MECHBOOK_PRINT_PEAK_MEMORY";

/// An error and its causes on one line, `a: b: c`, each said once: many of our errors already
/// name their cause ("cannot write x: No space left on device"), which a plain `{:#}` would
/// print again.
pub fn one_line(e: &anyhow::Error) -> String {
    let mut out = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if out.contains(&text) {
            continue;
        }
        if !out.is_empty() {
            out.push_str(": ");
        }
        out.push_str(&text);
    }
    out
}

/// The scene files under `paths`; none at all is an error.
fn find(paths: &[PathBuf]) -> Result<Vec<PathBuf>> {
    let files = crate::scene::find_scenes(paths).context("cannot list the scene files")?;
    if files.is_empty() {
        anyhow::bail!(
            "no scene files (*.toml) found in {}",
            paths
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    Ok(files)
}

/// The scenes in `files`, or `None` when any is bad: every problem is reported, one located
/// line each, and nothing is derived (bad input prints nothing on standard output).
fn load(files: &[PathBuf]) -> Option<Vec<crate::scene::Scene>> {
    match crate::scene::load_all(files) {
        Ok(s) => {
            warn(&s);
            Some(s)
        }
        Err(errors) => {
            for e in &errors {
                eprintln!("mechbook: error: {e}");
            }
            eprintln!(
                "mechbook: {}; nothing was derived",
                crate::base::format::count(errors.len(), "bad scene file")
            );
            None
        }
    }
}

/// The scenes' warnings on stderr, one located line each: what loads, but an author would fix.
fn warn(scenes: &[crate::scene::Scene]) {
    for w in scenes.iter().flat_map(|s| &s.warnings) {
        eprintln!("mechbook: warning: {w}");
    }
}

/// One frame of the progress bar: `[#####·····] 5/10 scene-id`.
fn progress_bar(done: usize, total: usize, label: &str) -> String {
    const WIDTH: usize = 24;
    let filled = (done * WIDTH).checked_div(total).unwrap_or(WIDTH);
    format!(
        "[{}{}] {done}/{total} {label}",
        "#".repeat(filled),
        "·".repeat(WIDTH - filled)
    )
}

/// Every scene through the pipeline (and `store`), with a progress bar on stderr when it is a
/// terminal. A scene that fails is reported on stderr, one located line, and the others still
/// run; the failed scenes' messages come back with the reports.
fn run_all<S: pipeline::ResultStore>(
    scenes: Vec<crate::scene::Scene>,
    fidelity: Option<Fidelity>,
    store: &S,
) -> (Vec<SceneReport>, Vec<String>) {
    let progress = std::io::stderr().is_terminal();
    let clear = || {
        if progress {
            eprint!("\r\x1b[2K");
        }
    };
    pipeline::run_all(scenes, fidelity, store, &mut |event| match event {
        Progress::Starting { done, total, id } => {
            if progress {
                eprint!("\r\x1b[2K{}", progress_bar(done, total, id));
            }
        }
        Progress::Warning(w) => {
            clear();
            eprintln!("mechbook: warning: {w}");
        }
        Progress::Failed(e) => {
            clear();
            eprintln!("mechbook: error: {e}");
        }
        Progress::Finished => clear(),
    })
}

/// The paths given, or `lectures/` when none: a course's scenes live there.
fn default_paths(paths: Vec<PathBuf>) -> Result<Vec<PathBuf>> {
    if !paths.is_empty() {
        return Ok(paths);
    }
    let lectures = PathBuf::from("lectures");
    if !lectures.exists() {
        anyhow::bail!(
            "no lectures/ here ({}): run `mechbook init` to start a course, change to a \
             course's folder, or pass the scene files or folders",
            std::env::current_dir()
                .map(|d| d.display().to_string())
                .unwrap_or_else(|_| "the working folder".into())
        );
    }
    Ok(vec![lectures])
}

pub fn run(cli: Cli) -> Result<ExitCode> {
    // `serve` never holds the engine: its builds are child processes.
    if matches!(
        cli.command,
        Command::Build { .. } | Command::Check { .. } | Command::Derive { .. }
    ) {
        crate::cas::ready()?;
    }
    match cli.command {
        Command::Check(args) => check::run(args),
        Command::Build(args) => build::run(args),
        Command::Spin(args) => spin::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Derive(args) => derive::run(args),
        Command::Init(args) => init::run(args),
        Command::Serve(args) => serve::run(args),
        Command::Completions(args) => completions::run(args),
    }
}

#[cfg(test)]
mod tests {
    use super::{one_line, progress_bar};

    #[test]
    fn an_os_error_is_said_once() {
        let io = std::io::Error::new(std::io::ErrorKind::StorageFull, "No space left on device");
        let e = crate::site::SiteError::Io {
            path: "x".into(),
            source: io,
        };
        let e = anyhow::Error::from(e).context("cannot record the verdicts");
        assert_eq!(
            one_line(&e),
            "cannot record the verdicts: cannot write x: No space left on device"
        );
        assert_eq!(
            format!("{e:#}").matches("No space").count(),
            2,
            "the case fixed"
        );
    }

    #[test]
    fn the_progress_bar_fills_in_proportion() {
        assert_eq!(
            progress_bar(0, 4, "a"),
            format!("[{}] 0/4 a", "·".repeat(24))
        );
        assert_eq!(
            progress_bar(1, 4, "b"),
            format!("[{}{}] 1/4 b", "#".repeat(6), "·".repeat(18))
        );
        assert_eq!(
            progress_bar(4, 4, "c"),
            format!("[{}] 4/4 c", "#".repeat(24))
        );
        assert_eq!(progress_bar(0, 0, ""), format!("[{}] 0/0 ", "#".repeat(24)));
    }
}
