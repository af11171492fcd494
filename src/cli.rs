//! The command line (clap derive): the doc comments are the help text.

use crate::numeric::fidelity::Fidelity;
use crate::pipeline::{self, SceneReport};
use crate::report;
use crate::site::cache::Cache;
use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use std::io::{IsTerminal, Write};
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
    /// Derive and verify every scene; print a summary table; fail when anything changed.
    ///
    /// A scene records the verdict it expects for each claim of the notes and, optionally, its
    /// exact results. `check` exits with 1 when a verdict or a result differs from the record,
    /// or when exact and numeric results disagree: a regression test for the derivations.
    /// It writes no files.
    Check {
        /// Scene files or folders to search for `*.toml` (default: lectures/).
        paths: Vec<PathBuf>,
        /// Print JSON, `{"scenes": [...]}`, instead of the table.
        #[arg(long)]
        json: bool,
        /// draft, standard, reference, or a target tolerance such as 1e-6: overrides each
        /// scene's `[numeric] fidelity` (default standard).
        #[arg(long, value_parser = parse_fidelity)]
        fidelity: Option<Fidelity>,
    },
    /// Build the course site: an index, one page per scene, and per lecture a student and an
    /// instructor handout for printing.
    ///
    /// Course settings (title, author, base_url, output) come from mechbook.toml when it
    /// exists. The site is written to a temporary folder beside the output and renamed into
    /// place, so a failed build leaves the previous site untouched; the same scenes give the same
    /// bytes. Exits with 1 (after writing) when a check of the scenes fails.
    Build {
        /// Scene files or folders (default: lectures/).
        paths: Vec<PathBuf>,
        /// The output folder (default: `output` from mechbook.toml, else site/).
        #[arg(long)]
        out: Option<PathBuf>,
        /// A folder whose templates (page.html, index.html, handout.html, style.css) replace
        /// the built-in ones, file by file.
        #[arg(long)]
        templates: Option<PathBuf>,
        /// Add measured seconds to the numeric tables (the pages then differ between builds).
        #[arg(long)]
        timings: bool,
        /// draft, standard, reference, or a target tolerance such as 1e-6: overrides each
        /// scene's `[numeric] fidelity` (default standard).
        #[arg(long, value_parser = parse_fidelity)]
        fidelity: Option<Fidelity>,
        /// Where computed scenes are kept between builds, keyed by a hash of the scene file,
        /// the fidelity and this program: an unchanged scene is not derived again.
        #[arg(long, default_value = ".mechbook-cache")]
        cache: PathBuf,
        /// Derive every scene afresh, and neither read nor write the cache (overrides --cache).
        #[arg(long)]
        no_cache: bool,
    },
    /// Integrate a free rigid body's Euler equations and compare with the exact solution.
    ///
    /// The body frame is principal: give the three principal moments and ω(0) in it. Methods:
    /// `exact` (Jacobi elliptic functions: the reference), `rk4` and the splittings `splitting`
    /// (Strang, 2nd order) and `splitting4` (triple jump, 4th order) with a fixed `--step`
    /// (default 0.01), `dopri` (adaptive Dormand–Prince 5(4)) with `--tol` (default 1e-9).
    /// Prints ω(T), its error against the exact solution, the largest drift of the energy and
    /// of |L| along the way, the right-hand-side evaluations and the seconds.
    Spin {
        /// The principal moments I1,I2,I3: positive, each at most the sum of the other two.
        #[arg(
            long,
            value_delimiter = ',',
            allow_hyphen_values = true,
            required = true
        )]
        inertia: Vec<f64>,
        /// ω(0) in the body frame, w1,w2,w3.
        #[arg(
            long,
            value_delimiter = ',',
            allow_hyphen_values = true,
            required = true
        )]
        omega: Vec<f64>,
        /// The end time T.
        #[arg(long, allow_hyphen_values = true)]
        t: f64,
        /// exact, rk4, dopri, splitting or splitting4.
        #[arg(long, default_value = "exact")]
        method: String,
        /// Fixed step h (rk4, splitting, splitting4).
        #[arg(long, conflicts_with = "tol")]
        step: Option<f64>,
        /// Error tolerance per step (dopri), at least 1e-15.
        #[arg(long)]
        tol: Option<f64>,
        /// The most steps to take: a request that needs more is refused (fixed steps) or
        /// stopped (dopri) with a message. 1e7 steps take about 1.3 s with RK4 and 5 s with
        /// dopri here.
        #[arg(long, default_value_t = crate::numeric::integrators::MAX_STEPS * 2)]
        max_steps: u64,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Measure the speed–accuracy trade and print a Markdown report.
    ///
    /// The integrators side by side on REFERENCE.md's case (I = 1,2,3, ω(0) = 1,0.1,0.5, 100
    /// periods); error against cost for every integrator and quadrature method, with Pareto
    /// fronts; whole-site builds in child processes (cold at each fidelity, warm, after a
    /// one-scene edit, numerics only) with their peak memory; and the symbolic stage alone.
    /// Takes about a minute. With --out, writes bench.md and the SVGs into that folder.
    Bench {
        /// Write bench.md, integrators-pareto.svg and quadrature-pareto.svg here (the folder
        /// is replaced whole), e.g. docs/bench.
        #[arg(long)]
        out: Option<PathBuf>,
        /// The scenes to build (a copy is built, never these files).
        #[arg(long, default_value = "lectures")]
        lectures: PathBuf,
        /// Runs of each build; the report gives the fastest and the median.
        #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=50))]
        repeats: u64,
    },
    /// Derive one scene and print its steps, results, numeric cross-check and claims.
    Derive {
        /// The scene file.
        scene: PathBuf,
        /// Print the scene as JSON.
        #[arg(long)]
        json: bool,
        /// Show which stages ran and which were skipped, and why.
        #[arg(long)]
        explain: bool,
        /// draft, standard, reference, or a target tolerance such as 1e-6: overrides the
        /// scene's `[numeric] fidelity` (default standard).
        #[arg(long, value_parser = parse_fidelity)]
        fidelity: Option<Fidelity>,
    },
}

/// The process's peak resident memory (Linux's VmHWM), for the build summary and `bench`.
pub fn peak_memory_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

fn parse_fidelity(s: &str) -> Result<Fidelity, String> {
    Fidelity::parse(s)
}

/// Parses the command line and runs it. Usage errors exit with 2 (clap's convention).
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("mechbook: error: {e:#}");
            ExitCode::from(1)
        }
    }
}

/// The scene files under `paths`; none at all is an error.
fn find(paths: &[PathBuf]) -> Result<Vec<PathBuf>> {
    let files = pipeline::find_scenes(paths).context("cannot list the scene files")?;
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
    match pipeline::load_all(files) {
        Ok(s) => Some(s),
        Err(errors) => {
            for e in &errors {
                eprintln!("mechbook: error: {e}");
            }
            eprintln!(
                "mechbook: {} bad scene file(s); nothing was derived",
                errors.len()
            );
            None
        }
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

/// Runs every scene, or takes it from the cache, with a progress bar on stderr when it is a
/// terminal. A scene that fails is reported on stderr, one located line, and the others still
/// run; the count of failed scenes comes back with the reports.
fn run_all(
    scenes: Vec<crate::scene::Scene>,
    fidelity: Option<Fidelity>,
    cache: Option<&Cache>,
) -> Result<(Vec<SceneReport>, usize)> {
    let progress = std::io::stderr().is_terminal();
    let total = scenes.len();
    let mut reports = Vec::new();
    let mut failed = 0;
    for (i, scene) in scenes.into_iter().enumerate() {
        if progress {
            eprint!("\r\x1b[2K{}", progress_bar(i, total, &scene.id));
        }
        match run_one(scene, fidelity, cache) {
            Ok(r) => reports.push(r),
            Err(e) => {
                if progress {
                    eprint!("\r\x1b[2K");
                }
                eprintln!("mechbook: error: {e}");
                failed += 1;
            }
        }
    }
    if progress {
        eprint!("\r\x1b[2K");
    }
    Ok((reports, failed))
}

/// One scene, from the cache when it holds it.
fn run_one(
    scene: crate::scene::Scene,
    fidelity: Option<Fidelity>,
    cache: Option<&Cache>,
) -> Result<SceneReport, pipeline::RunError> {
    let Some(cache) = cache else {
        return pipeline::run_scene(scene, fidelity);
    };
    let (id, hash) = (scene.id.clone(), scene.content_hash);
    let fid = fidelity.or(scene.fidelity).unwrap_or_default();
    let whole = cache
        .load(&id, hash, Some(&fid))
        .and_then(|bytes| pipeline::from_cache(scene.clone(), &bytes));
    let report = match whole {
        Some(r) => r,
        None => {
            let symbolic = cache
                .load(&id, hash, None)
                .and_then(|bytes| serde_json::from_slice(&bytes).ok());
            let r = pipeline::run_scene_with(scene, Some(fid), symbolic)?;
            let mut stored = cache.store(&id, hash, Some(&fid), &pipeline::to_cache(&r));
            if r.from_cache == pipeline::FromCache::Nothing && stored.is_ok() {
                let symbolic =
                    serde_json::to_vec(&pipeline::symbolic_part(&r)).expect("a report serializes");
                stored = cache.store(&id, hash, None, &symbolic);
            }
            if let Err(e) = stored {
                eprintln!("mechbook: warning: the cache is not updated: {e}");
            }
            r
        }
    };
    Ok(report)
}

fn default_paths(paths: Vec<PathBuf>) -> Vec<PathBuf> {
    if paths.is_empty() {
        vec![PathBuf::from("lectures")]
    } else {
        paths
    }
}

pub fn run(cli: Cli) -> Result<ExitCode> {
    if matches!(
        cli.command,
        Command::Build { .. } | Command::Check { .. } | Command::Derive { .. }
    ) {
        crate::cas::ready()?;
    }
    match cli.command {
        Command::Build {
            paths,
            out,
            templates,
            timings,
            fidelity,
            cache,
            no_cache,
        } => {
            let start = std::time::Instant::now();
            let course = crate::render::Course::load(std::path::Path::new("mechbook.toml"))
                .map_err(anyhow::Error::msg)?;
            let paths = default_paths(paths);
            let out = out
                .or(course.output.clone())
                .unwrap_or_else(|| PathBuf::from("site"));
            // Refused before anything is derived, so a refused build touches nothing. The
            // inputs are the scene files themselves, and the folders named.
            let files = find(&paths)?;
            let mut inputs = paths.clone();
            inputs.extend(files.iter().cloned());
            inputs.extend(templates.clone());
            inputs.push(PathBuf::from("."));
            crate::site::check_output(&out, &inputs)?;
            let Some(scenes) = load(&files) else {
                return Ok(ExitCode::from(1));
            };
            let cache = (!no_cache).then(|| Cache::new(&cache));
            let (reports, errors) = run_all(scenes, fidelity, cache.as_ref())?;
            if errors > 0 {
                eprintln!(
                    "mechbook: {errors} scene(s) could not be derived; the site was not written"
                );
                return Ok(ExitCode::from(1));
            }
            let cached = reports
                .iter()
                .filter(|r| r.from_cache == pipeline::FromCache::Everything)
                .count();
            let symbolic_cached = reports
                .iter()
                .filter(|r| r.from_cache == pipeline::FromCache::Symbolic)
                .count();
            let files = crate::render::site_files(&reports, &course, templates.as_deref(), timings)
                .map_err(anyhow::Error::msg)?;
            crate::site::write_site(&out, &files)?;
            let handouts = files.keys().filter(|p| p.starts_with("handouts")).count();
            let plots = files.keys().filter(|p| p.starts_with("plots")).count();
            let failed = reports.iter().filter(|r| !r.passed()).count();
            eprintln!(
                "mechbook: built {} pages, {plots} plots and {handouts} handouts from {} scenes ({cached} from the cache, {symbolic_cached} re-run numerically on cached symbolic results) into {} in {:.2} s{}{}",
                reports.len() + 1,
                reports.len(),
                out.display(),
                start.elapsed().as_secs_f64(),
                peak_memory_mib().map_or(String::new(), |m| format!(", peak memory {m:.0} MiB")),
                if failed > 0 {
                    format!("; {failed} scene(s) FAILED their checks (run `mechbook check`)")
                } else {
                    String::new()
                }
            );
            Ok(if failed == 0 {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            })
        }
        Command::Check {
            paths,
            json,
            fidelity,
        } => {
            let Some(scenes) = load(&find(&default_paths(paths))?) else {
                return Ok(ExitCode::from(1));
            };
            let (reports, errors) = run_all(scenes, fidelity, None)?;
            let passed = errors == 0 && reports.iter().all(SceneReport::passed);
            let text = if json {
                let scenes: Vec<_> = reports.iter().map(report::scene_json).collect();
                serde_json::to_string_pretty(&serde_json::json!({ "scenes": scenes }))? + "\n"
            } else {
                report::check_table(&reports)
            };
            std::io::stdout().write_all(text.as_bytes())?;
            if errors > 0 {
                eprintln!(
                    "mechbook: {errors} scene(s) could not be derived (errors above); the other \
                     {} were checked",
                    reports.len()
                );
            }
            Ok(if passed {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            })
        }
        Command::Spin {
            inertia,
            omega,
            t,
            method,
            step,
            tol,
            max_steps,
            json,
        } => {
            let text = crate::spin::run(&crate::spin::SpinArgs {
                inertia,
                omega,
                t,
                method,
                step,
                tol,
                max_steps,
                json,
            })
            .map_err(anyhow::Error::msg)?;
            std::io::stdout().write_all(text.as_bytes())?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Bench {
            out,
            lectures,
            repeats,
        } => {
            if let Some(out) = &out {
                crate::site::check_output(out, &[lectures.clone(), PathBuf::from(".")])?;
            }
            let tty = std::io::stderr().is_terminal();
            let bench = crate::bench::run(&lectures, repeats as usize, |line| {
                if tty {
                    eprint!("\r\x1b[2Kbench: {line}");
                }
            })
            .map_err(anyhow::Error::msg)?;
            if tty {
                eprint!("\r\x1b[2K");
            }
            if let Some(out) = out {
                let mut files = crate::site::SiteFiles::new();
                files.insert("bench.md".into(), bench.markdown.clone().into_bytes());
                for f in &bench.figures {
                    let svg = crate::render::plot::svg(f).map_err(anyhow::Error::msg)?;
                    files.insert(format!("{}.svg", f.slug).into(), svg.into_bytes());
                }
                crate::site::write_site(&out, &files)?;
                eprintln!(
                    "mechbook: wrote bench.md and {} SVGs into {}",
                    bench.figures.len(),
                    out.display()
                );
            }
            std::io::stdout().write_all(bench.markdown.as_bytes())?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Derive {
            scene,
            json,
            explain,
            fidelity,
        } => {
            let Some(mut scenes) = load(&find(std::slice::from_ref(&scene))?) else {
                return Ok(ExitCode::from(1));
            };
            let r = match pipeline::run_scene(scenes.remove(0), fidelity) {
                Ok(r) => r,
                Err(e) => {
                    eprintln!("mechbook: error: {e}");
                    return Ok(ExitCode::from(1));
                }
            };
            let text = if json {
                serde_json::to_string_pretty(&report::scene_json(&r))? + "\n"
            } else {
                let mut t = report::derivation_text(&r);
                if explain {
                    t.push('\n');
                    t.push_str(&report::explain_text(&r));
                }
                t
            };
            std::io::stdout().write_all(text.as_bytes())?;
            Ok(if r.passed() {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::progress_bar;

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
