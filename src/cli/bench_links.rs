//! `mechbook bench --links-only`: the n-link pendulum (n = 1 to 10) from its Lagrangian to its
//! normal modes, mechbook's whole process against SymPy's LagrangesMethod and linearize in the
//! same run, and each one's modes against the eigenvalues of the textbook's M⁻¹K.

use crate::verify::n_link::{n_link_scene, textbook_modes};
use anyhow::{Context, Result, bail};
use std::fmt::Write;
use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// The SymPy side, run by the caller's Python (docs/bench/n_link_sympy.py).
const SYMPY_SCRIPT: &str = include_str!("../../docs/bench/n_link_sympy.py");

/// The largest n measured: SymPy takes about 28 s at 10 on this kind of machine, mechbook
/// about 0.3 s.
pub const MAX_LINKS: usize = 10;

/// What mechbook's whole process must take at n = [`MAX_LINKS`], at most: the report says
/// whether it did.
const LINKS_TARGET_SECONDS: f64 = 1.0;

/// The modes mechbook derives for the scene, at its values.
fn mechbook_modes(file: &Path) -> Result<Vec<f64>> {
    use crate::derive::step_names::StepResult;
    let scene = crate::scene::Scene::from_file(file)?;
    let r = crate::pipeline::run_scene(scene, None)?;
    if let Some(failed) = r.verification.steps.iter().find(|c| !c.passed()) {
        bail!("a step's numeric check failed: {failed:?}");
    }
    let at =
        |e: &crate::cas::Expr| -> Result<f64> { Ok(e.eval(&|s| r.scene.values.get(s).copied())?) };
    match r.derivation.named.get("Omega") {
        Some(StepResult::Expr(e)) => Ok(vec![at(e)?]),
        Some(StepResult::Modes(modes)) => modes.iter().map(at).collect(),
        Some(StepResult::NumericModes { frequencies, .. }) => Ok(frequencies.clone()),
        other => bail!("the frequency step gave {other:?}"),
    }
}

/// The largest relative difference between two lists of frequencies (∞ when their lengths
/// differ).
fn worst(a: &[f64], b: &[f64]) -> f64 {
    if a.len() != b.len() {
        return f64::INFINITY;
    }
    a.iter()
        .zip(b)
        .map(|(x, y)| ((x - y) / y).abs())
        .fold(0.0, f64::max)
}

/// One SymPy run: its whole process's seconds, the mechanics' own, its frequencies and its
/// peak memory (MiB).
struct SympyRun {
    seconds: f64,
    mechanics: f64,
    frequencies: Vec<f64>,
    peak: f64,
}

fn sympy_run(python: &Path, script: &Path, n: usize) -> Result<SympyRun> {
    let start = Instant::now();
    let out = Command::new(python)
        .arg(script)
        .arg(n.to_string())
        .output()
        .with_context(|| format!("cannot run {}", python.display()))?;
    let seconds = start.elapsed().as_secs_f64();
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        bail!("{}", err.lines().last().unwrap_or("failed").trim());
    }
    let line: serde_json::Value = serde_json::from_slice(&out.stdout)?;
    let number = |k: &str| line[k].as_f64().context("SymPy's line lacks a number");
    Ok(SympyRun {
        seconds,
        mechanics: number("mechanics_seconds")?,
        peak: number("peak_mib").unwrap_or(f64::NAN),
        frequencies: line["frequencies"]
            .as_array()
            .context("SymPy's line lacks its frequencies")?
            .iter()
            .filter_map(|v| v.as_f64())
            .collect(),
    })
}

/// mechbook's whole process (`mechbook derive`, a fresh cache each run): its fastest seconds
/// and its largest peak memory (MiB, as the child prints it).
fn mechbook_run(file: &Path, cache: &Path, repeats: usize) -> Result<(f64, f64)> {
    let exe = std::env::current_exe()?;
    let mut fastest = f64::INFINITY;
    let mut peak = f64::NAN;
    for run in 0..repeats {
        let fresh = cache.join(run.to_string());
        let start = Instant::now();
        let out = Command::new(&exe)
            .arg("derive")
            .arg(file)
            .env("SYMBOLICA_HIDE_BANNER", "1")
            .env("XDG_CACHE_HOME", &fresh)
            .env(super::PEAK_MEMORY_ENV, "1")
            .output()
            .context("cannot run mechbook derive")?;
        fastest = fastest.min(start.elapsed().as_secs_f64());
        if !out.status.success() {
            bail!(
                "mechbook derive {} failed: {}",
                file.display(),
                String::from_utf8_lossy(&out.stderr)
            );
        }
        let _ = std::fs::remove_dir_all(&fresh);
        let printed = super::bench_timing::printed_peak(&String::from_utf8_lossy(&out.stderr));
        peak = peak.max(printed.unwrap_or(f64::NAN));
    }
    Ok((fastest, peak))
}

/// The report: per n, each tool's fastest whole process of `repeats`, SymPy's mechanics alone,
/// the ratio, and each tool's worst difference from the textbook's M⁻¹K.
pub fn links_bench(
    python: &Path,
    repeats: usize,
    mut progress: impl FnMut(&str),
) -> Result<String> {
    let dir = std::env::temp_dir().join(format!("mechbook-bench-links-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let result = measure(python, repeats, &dir, &mut progress);
    let _ = std::fs::remove_dir_all(&dir);
    result
}

fn measure(
    python: &Path,
    repeats: usize,
    dir: &Path,
    progress: &mut impl FnMut(&str),
) -> Result<String> {
    let script = dir.join("n_link_sympy.py");
    std::fs::write(&script, SYMPY_SCRIPT)?;
    let mut md = format!(
        "\n## The n-link pendulum against SymPy\n\nLagrangian, equations of motion, linearisation \
         about rest and normal modes at m = 1, l = 1, g = 9.81, fastest of {repeats}. mechbook: \
         the whole process `mechbook derive` (start-up, derivation, every step's numeric check), \
         a fresh cache each run. SymPy: `{}` running docs/bench/n_link_sympy.py \
         (physics.mechanics: LagrangesMethod, linearize with A_and_B, mpmath's eigenvalues), \
         the whole process and the mechanics alone. Each tool's modes against √λ of the \
         textbook's M⁻¹K (nalgebra). Peak memory: each process's own (Linux VmHWM for \
         mechbook, ru_maxrss for Python).\n\n| n | mechbook | SymPy whole | SymPy mechanics | \
         whole / whole | mechanics / whole | mechbook vs M⁻¹K | SymPy vs M⁻¹K | mechbook peak | \
         SymPy peak |\n|---|---|---|---|---|---|---|---|---|---|\n",
        python.display()
    );
    let mut sympy_missing = None;
    let mut largest = None;
    for n in 1..=MAX_LINKS {
        progress(&format!("{n}-link pendulum"));
        let file = dir.join(format!("links-{n}.toml"));
        std::fs::write(&file, n_link_scene(n))?;
        let (ours, our_peak) = mechbook_run(&file, &dir.join("cache"), repeats)?;
        if n == MAX_LINKS {
            largest = Some(ours);
        }
        let reference = textbook_modes(n);
        let ours_error = worst(&mechbook_modes(&file)?, &reference);
        let sympy = if sympy_missing.is_none() {
            fastest_sympy(python, &script, n, repeats, &mut sympy_missing)
        } else {
            None
        };
        let _ = writeln!(
            md,
            "{}",
            row(n, (ours, our_peak, ours_error), sympy.as_ref(), &reference)
        );
    }
    if let Some(seconds) = largest {
        let verdict = if seconds < LINKS_TARGET_SECONDS {
            "under"
        } else {
            "NOT under"
        };
        let _ = writeln!(
            md,
            "\nAt n = {MAX_LINKS}, mechbook's whole pipeline (equations, linearisation, modes, \
             every step's numeric check) took {seconds:.3} s: {verdict} the \
             {LINKS_TARGET_SECONDS} s it must."
        );
    }
    if let Some(why) = sympy_missing {
        let _ = writeln!(
            md,
            "\nSymPy did not run ({why}): `bash docs/bench/links.sh` makes a Python with SymPy \
             1.14.0 and passes it as `--python`."
        );
    }
    Ok(md)
}

/// SymPy's fastest of `repeats` runs on the `n`-link pendulum; none, with why in `missing`, when
/// it does not run.
fn fastest_sympy(
    python: &Path,
    script: &Path,
    n: usize,
    repeats: usize,
    missing: &mut Option<String>,
) -> Option<SympyRun> {
    let mut sympy: Option<SympyRun> = None;
    for _ in 0..repeats {
        match sympy_run(python, script, n) {
            Ok(run) => {
                if sympy.as_ref().is_none_or(|best| run.seconds < best.seconds) {
                    sympy = Some(run);
                }
            }
            Err(e) => {
                *missing = Some(e.to_string());
                break;
            }
        }
    }
    sympy
}

/// One row of the table: mechbook's time, peak and error against M⁻¹K's modes, and SymPy's
/// where it ran.
fn row(
    n: usize,
    (ours, our_peak, ours_error): (f64, f64, f64),
    sympy: Option<&SympyRun>,
    reference: &[f64],
) -> String {
    let (whole, mechanics, ratio, ratio_mechanics, theirs, their_peak) = match sympy {
        Some(s) => (
            format!("{:.3} s", s.seconds),
            format!("{:.3} s", s.mechanics),
            format!("{:.0}×", s.seconds / ours),
            format!("{:.0}×", s.mechanics / ours),
            crate::base::format::sci(worst(&s.frequencies, reference)),
            format!("{:.0} MiB", s.peak),
        ),
        None => Default::default(),
    };
    let dash = |s: String| if s.is_empty() { "—".to_string() } else { s };
    format!(
        "| {n} | {:.3} s | {} | {} | {} | {} | {} | {} | {:.0} MiB | {} |",
        ours,
        dash(whole),
        dash(mechanics),
        dash(ratio),
        dash(ratio_mechanics),
        crate::base::format::sci(ours_error),
        dash(theirs),
        our_peak,
        dash(their_peak),
    )
}
