//! `mechbook bench`: what the speed–accuracy trade costs, measured. Four parts:
//!
//! - the integrators on REFERENCE.md's case (the table of `spin::bench_table`);
//! - error against cost for every integrator and every quadrature method, with Pareto fronts;
//! - whole-site builds run as a user runs them (a child `mechbook build`, timed from outside):
//!   cold, warm, after a one-scene edit, and at each fidelity, with each child's peak memory;
//! - the symbolic stage alone, in this process, after the children (one Symbolica user at once).
//!
//! `measure` only measures; `run` prints the report and, with `--out`, hands it and its SVGs to
//! `site` to write.

use super::bench_timing::{Timing, timed};
use crate::base::format::sci;
use crate::model::fidelity::Fidelity;
use crate::model::figure::Figure;
use crate::model::moments::Moments;
use crate::numeric::body::{NumBody, NumShape};
use crate::numeric::free_body::ExactSolution;
use crate::site::scratch;
use anyhow::{Context, Result, anyhow, bail};
use nalgebra::{Matrix3, Vector3};
use std::fmt::Write;
use std::io::{IsTerminal, Write as _};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::process::ExitCode;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    /// Write bench.md, integrators-pareto.svg and quadrature-pareto.svg here (the folder
    /// is replaced whole), e.g. docs/bench.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// The scenes to build (a copy is built, never these files).
    #[arg(long, default_value = "lectures")]
    pub lectures: PathBuf,
    /// Runs of each build; the report gives the fastest and the median.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=50))]
    pub repeats: u64,
    /// Measure only the problem variants: this many variants of the box problem, drawn,
    /// derived once, then each substituted and cross-checked (a few seconds at 1000).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=10_000))]
    pub variants_only: Option<u64>,
    /// Measure only the author's steps of the scenes in this folder (such as
    /// tests/course/dynamics): each scene derived, then each step checked on its numeric route.
    #[arg(long)]
    pub steps_only: Option<PathBuf>,
    /// Measure only the n-link pendulum, n = 1 to 10 (Lagrangian, equations, linearisation,
    /// normal modes): mechbook's whole process against SymPy's LagrangesMethod and linearize,
    /// each tool's modes checked against the eigenvalues of M⁻¹K. SymPy runs under --python;
    /// `bash docs/bench/links.sh` makes one with SymPy and runs this.
    #[arg(long)]
    pub links_only: bool,
    /// Measure only a course at a term's scale (such as tests/course): `check`, `build
    /// --no-cache`, the same with a roster of 25 students, a build after one scene's edit, and
    /// 10,000 variants of a nearly symmetric top; each a child process, with its peak memory.
    #[arg(long)]
    pub course_only: Option<PathBuf>,
    /// Measure only rosters of these sizes (such as 250,1000,5000): for each, the box problem
    /// with that many variants, then `build --no-cache --roster` of as many students, with the
    /// time per student and the peak memory; then a site whose sheet has 10,000 variants.
    #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u64).range(1..=10_000))]
    pub roster_only: Vec<u64>,
    /// The Python, with SymPy, that --links-only runs.
    #[arg(long, default_value = "python3", requires = "links_only")]
    pub python: PathBuf,
}

/// The box problem of the variant benchmark; `{count}` is replaced by the number of variants.
/// Its ranges span 18,480 combinations, most with a < b < c.
const VARIANT_SCENE: &str = include_str!("scenes/box-variants.toml");

/// `count` variants of the box problem: the time to draw them (parsing the scene), to derive
/// the problem once, and to substitute and cross-check every variant; all in this process.
pub fn variants_bench(count: usize) -> Result<String> {
    let text = VARIANT_SCENE.replace("{count}", &count.to_string());
    let start = Instant::now();
    let scene = crate::scene::Scene::parse(&text, Path::new("bench-box-variants.toml"))?;
    let draw = start.elapsed().as_secs_f64();
    let plan = crate::plan::Plan::for_scene(&scene);
    let start = Instant::now();
    let symbolic = crate::pipeline::symbolic_stage(&scene, &plan)?;
    let derive = start.elapsed().as_secs_f64();
    let problem = scene
        .problem
        .as_ref()
        .context("the bench scene has a problem")?;
    let start = Instant::now();
    let checks = crate::verify::variants::check_variants(
        &scene,
        &symbolic.derivation,
        problem,
        &crate::numeric::budget::Deadline::checks(),
    )?;
    let check = start.elapsed().as_secs_f64();
    let worst = checks
        .iter()
        .flat_map(|v| v.answers.iter().map(|a| a.error))
        .fold(0.0f64, f64::max);
    let failed = checks.iter().filter(|v| !v.passed()).count();
    if failed > 0 {
        bail!("{failed} of {count} bench variants failed their numeric check");
    }
    let peak = super::peak_memory_mib().map_or("—".into(), |m| format!("{m:.0} MiB"));
    Ok(format!(
        "\n## Problem variants\n\n{count} variants of a box about its centre (inertia tensor and \
         principal moments): drawn in {:.1} ms, derived once in {:.1} ms, then each variant's \
         answers substituted exactly and checked against quadrature and `SymmetricEigen` in \
         {:.1} ms ({:.1} µs a variant); {:.1} ms in all. Largest relative difference {}; peak \
         memory of this process {peak}.\n",
        draw * 1e3,
        derive * 1e3,
        check * 1e3,
        check * 1e6 / count as f64,
        (draw + derive + check) * 1e3,
        sci(worst),
    ))
}

/// Each scene with `[[step]]`s in `folder`: the time to derive it (its bodies and steps, in
/// this process), and then for each step its numeric route's time, evaluations and error.
pub fn steps_bench(folder: &Path) -> Result<String> {
    let files = crate::scene::find_scenes(&[folder.to_path_buf()])?;
    let mut md = String::from(
        "\n## Author's steps\n\n| scene | step | operation | numeric route: error (tolerance) | \
         evaluations | ms |\n|---|---|---|---|---|---|\n",
    );
    let mut totals = (0.0, 0.0, 0u64);
    for file in files {
        let scene = crate::scene::Scene::from_file(&file)?;
        if scene.steps.is_empty() {
            continue;
        }
        let plan = crate::plan::Plan::for_scene(&scene);
        let start = Instant::now();
        let symbolic = crate::pipeline::symbolic_stage(&scene, &plan)?;
        let derive = start.elapsed().as_secs_f64();
        let _ = writeln!(
            md,
            "| {} | (derived, with its claims) | | | | {:.1} |",
            scene.id,
            derive * 1e3
        );
        totals.0 += derive;
        for (i, step) in scene.steps.iter().enumerate() {
            let start = Instant::now();
            let check = crate::steps::check_step(&scene, &symbolic.derivation, i);
            let seconds = start.elapsed().as_secs_f64();
            totals.1 += seconds;
            totals.2 += check.evaluations;
            let result = match &check.problem {
                Some(p) => format!("failed: {p}"),
                None => format!("{} ({})", sci(check.error), sci(check.tolerance)),
            };
            let _ = writeln!(
                md,
                "| | {} | {} | {result} | {} | {:.1} |",
                step.name,
                step.op.name(),
                check.evaluations,
                seconds * 1e3
            );
        }
    }
    let _ = writeln!(
        md,
        "\nIn all: derived in {:.1} ms, checked in {:.1} ms ({} evaluations); peak memory of this \
         process {}.",
        totals.0 * 1e3,
        totals.1 * 1e3,
        totals.2,
        super::peak_memory_mib().map_or("—".into(), |m| format!("{m:.0} MiB"))
    );
    Ok(md)
}

/// Measures, prints the report, and with `--out` writes it and its figures.
pub fn run(args: BenchArgs) -> Result<ExitCode> {
    let BenchArgs {
        out,
        lectures,
        repeats,
        variants_only,
        steps_only,
        links_only,
        course_only,
        roster_only,
        python,
    } = args;
    if !roster_only.is_empty() {
        let sizes: Vec<usize> = roster_only.iter().map(|&n| n as usize).collect();
        return print_part(|p| {
            super::bench_roster::roster_bench(
                VARIANT_SCENE,
                &sizes,
                repeats as usize,
                &mut |l: &str| p(l),
            )
        });
    }
    if let Some(course) = course_only {
        return print_part(|p| {
            super::bench_course::course_bench(&course, repeats as usize, &mut |l: &str| p(l))
        });
    }
    if links_only {
        return print_part(|p| {
            super::bench_links::links_bench(&python, repeats as usize, |l: &str| p(l))
        });
    }
    if let Some(n) = variants_only {
        std::io::stdout().write_all(variants_bench(n as usize)?.as_bytes())?;
        return Ok(ExitCode::SUCCESS);
    }
    if let Some(folder) = steps_only {
        std::io::stdout().write_all(steps_bench(&folder)?.as_bytes())?;
        return Ok(ExitCode::SUCCESS);
    }
    if let Some(out) = &out {
        crate::site::Sources::of_course(
            std::slice::from_ref(&lectures),
            &[],
            std::path::Path::new("mechbook.toml"),
            None,
            None,
        )
        .check_apart("--out folder", out, "docs/bench")?;
        crate::site::check_output(out, &[lectures.clone(), PathBuf::from(".")])?;
    }
    let tty = std::io::stderr().is_terminal();
    let bench = measure(&lectures, repeats as usize, |line| {
        if tty {
            eprint!("\r\x1b[2Kbench: {line}");
        }
    })?;
    if tty {
        eprint!("\r\x1b[2K");
    }
    if let Some(out) = out {
        let mut files = crate::render::SiteFiles::new();
        files.insert("bench.md".into(), bench.markdown.clone().into_bytes());
        for f in &bench.figures {
            let svg = crate::render::plot::svg(f)?;
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

/// Runs one part of the bench with its progress on a terminal's last line, then prints its
/// Markdown.
fn print_part(part: impl FnOnce(&mut dyn FnMut(&str)) -> Result<String>) -> Result<ExitCode> {
    let tty = std::io::stderr().is_terminal();
    let md = part(&mut |line: &str| {
        if tty {
            eprint!("\r\x1b[2Kbench: {line}");
        }
    })?;
    if tty {
        eprint!("\r\x1b[2K");
    }
    std::io::stdout().write_all(md.as_bytes())?;
    Ok(ExitCode::SUCCESS)
}

/// The benchmark's results: the Markdown report and the figures it draws.
pub struct Bench {
    pub markdown: String,
    pub figures: Vec<Figure>,
}

/// Runs every part. `lectures` is the folder of scenes to build; `repeats` runs each build
/// that many times and reports the fastest and the median.
pub fn measure(lectures: &Path, repeats: usize, mut progress: impl FnMut(&str)) -> Result<Bench> {
    let mut md = String::from("# mechbook bench\n\n");
    let _ = writeln!(
        md,
        "Measured by `mechbook bench` on {}; times are wall-clock seconds.\n",
        crate::base::format::count(
            std::thread::available_parallelism().map_or(1, |n| n.get()),
            "core"
        )
    );

    progress("integrators");
    md.push_str("## Integrators\n\n");
    md.push_str(&super::spin::bench_table(&mut progress));

    progress("error against cost");
    let figures = pareto_figures()?;
    md.push_str("\n## Error against cost\n\n");
    for f in &figures {
        let _ = writeln!(md, "![{}]({}.svg)\n\n{}\n", f.title, f.slug, f.desc);
        md.push_str("| result | method | true error | estimated error | cost | seconds |\n");
        md.push_str("|---|---|---|---|---|---|\n");
        for a in &f.accuracy {
            let _ = writeln!(
                md,
                "| {} | {} | {} | {} | {} {} | {:.2e} |",
                a.result,
                a.method,
                a.true_error.map_or("—".into(), sci),
                a.estimated_error.map_or("—".into(), sci),
                a.cost,
                a.unit,
                a.seconds
            );
        }
        md.push('\n');
    }

    md.push_str(&builds(lectures, repeats, &mut progress)?);

    progress("symbolic stage");
    md.push_str(&symbolic_stage(lectures, repeats)?);
    progress("problem variants");
    md.push_str(&variants_bench(1000)?);
    if let Some(m) = super::peak_memory_mib() {
        let _ = writeln!(md, "\nPeak memory of the bench process itself: {m:.0} MiB.");
    }
    Ok(Bench {
        markdown: md,
        figures,
    })
}

/// The integrators on REFERENCE.md's case over 100 periods at reference fidelity, and the
/// quadrature methods on the notes' cube about its corner.
fn pareto_figures() -> Result<Vec<Figure>> {
    let i = Moments::new([1.0, 2.0, 3.0])?;
    let w0 = Vector3::new(1.0, 0.1, 0.5);
    let period = ExactSolution::new(&i, w0)
        .period()
        .context("not periodic")?;
    let mut integrators = crate::figures::integrator_pareto::integrator_pareto(
        &i,
        w0,
        100.0 * period,
        &Fidelity::REFERENCE,
    )?;
    integrators.slug = "integrators-pareto".into();
    let cube = NumBody {
        label: "the unit cube about its corner".into(),
        shape: NumShape::Box {
            size: Vector3::new(1.0, 1.0, 1.0),
            centred: true,
        },
        mass: 1.0,
        rotation: Matrix3::identity(),
        shift: Vector3::new(0.5, 0.5, 0.5),
    };
    // Eq (35): I = M a² [[2/3, −1/4, −1/4], …] about a corner.
    let exact = Matrix3::from_fn(|r, c| if r == c { 2.0 / 3.0 } else { -0.25 });
    let quadrature = crate::figures::convergence::convergence(
        &cube,
        &exact,
        1,
        "quadrature-pareto".into(),
        &Fidelity::REFERENCE,
    )?;
    Ok(vec![integrators, quadrature])
}

/// One child build: its wall time and the peak memory it printed.
fn child_build(args: &[&str]) -> Result<(f64, f64)> {
    let exe = std::env::current_exe()?;
    let start = Instant::now();
    let out = Command::new(exe)
        .arg("build")
        .args(args)
        .env("SYMBOLICA_HIDE_BANNER", "1")
        .output()
        .context("cannot run mechbook build")?;
    let seconds = start.elapsed().as_secs_f64();
    let err = String::from_utf8_lossy(&out.stderr);
    if !out.status.success() {
        bail!("mechbook build {} failed: {err}", args.join(" "));
    }
    let peak = super::bench_timing::printed_peak(&err).unwrap_or(f64::NAN);
    Ok((seconds, peak))
}

/// Whole-site builds of a copy of `lectures`, each in a fresh child process.
fn builds(lectures: &Path, repeats: usize, progress: &mut impl FnMut(&str)) -> Result<String> {
    let dir = scratch::folder("bench")?;
    let result = build_rows(lectures, &dir, repeats, progress);
    scratch::remove(&dir);
    result
}

/// Each build's timing, on a copy of the lectures in `dir`, as the section's Markdown.
fn build_rows(
    lectures: &Path,
    dir: &Path,
    repeats: usize,
    progress: &mut impl FnMut(&str),
) -> Result<String> {
    let scenes = dir.join("lectures");
    scratch::copy_tree(lectures, &scenes)?;
    let s = |p: &PathBuf| p.to_string_lossy().into_owned();
    let (scenes_arg, site, cache) = (s(&scenes), s(&dir.join("site")), s(&dir.join("cache")));
    let base = [
        scenes_arg.as_str(),
        "--out",
        site.as_str(),
        "--cache",
        cache.as_str(),
    ];
    let with = |extra: &[&str]| -> Vec<String> {
        base.iter().chain(extra).map(|x| x.to_string()).collect()
    };
    let build = |args: Vec<String>| {
        let a: Vec<&str> = args.iter().map(String::as_str).collect();
        child_build(&a)
    };
    let mut rows: Vec<(String, Timing)> = Vec::new();
    for (name, fidelity) in [
        ("cold, draft", "draft"),
        ("cold, standard", "standard"),
        ("cold, reference", "reference"),
    ] {
        progress(name);
        rows.push((
            format!("{name}: no cache, every stage runs"),
            timed(repeats, || {
                build(with(&["--no-cache", "--fidelity", fidelity]))
            })?,
        ));
    }
    progress("warm");
    build(with(&[]))?;
    rows.push((
        "warm, standard: every scene from the cache".into(),
        timed(repeats, || build(with(&[])))?,
    ));
    progress("one scene changed");
    // The last scene in name order: the same one on every machine.
    let edited = crate::scene::find_scenes(std::slice::from_ref(&scenes))?
        .pop()
        .context("no scene to edit")?;
    let mut edits = 0;
    rows.push((
        format!(
            "one scene edited ({}), standard: it alone runs",
            edited.file_name().unwrap_or_default().to_string_lossy()
        ),
        timed(repeats, || {
            edits += 1;
            scratch::append_line(&edited, &format!("# bench edit {edits}"))?;
            build(with(&[]))
        })?,
    ));
    for fidelity in ["draft", "reference"] {
        progress(fidelity);
        rows.push((
            format!("{fidelity}, symbolic results cached: only the numerics run"),
            timed(repeats, || {
                scratch::drop_reports(&dir.join("cache"))?;
                build(with(&["--fidelity", fidelity]))
            })?,
        ));
    }
    let count = crate::scene::find_scenes(std::slice::from_ref(&scenes)).map_or(0, |v| v.len());
    Ok(builds_table(count, repeats, &rows))
}

/// The builds' rows as a Markdown table under the section's heading, and the ratios of the
/// reference fidelity's time to the draft's.
fn builds_table(count: usize, repeats: usize, rows: &[(String, Timing)]) -> String {
    let mut md = format!(
        "## Whole-site builds\n\nEach build is a separate `mechbook build` process of the {} \
         lecture scenes, timed from outside (start-up included); {} each. Peak memory is the \
         largest the build printed (Linux VmHWM).\n\n\
         | build | fastest s | median s | peak MiB |\n|---|---|---|---|\n",
        count,
        crate::base::format::count(repeats, "run")
    );
    for (name, t) in rows {
        let _ = writeln!(
            md,
            "| {name} | {:.3} | {:.3} | {:.0} |",
            t.fastest, t.median, t.peak
        );
    }
    let ratio = |a: &str, b: &str| {
        let get = |k: &str| {
            rows.iter()
                .find(|(n, _)| n.starts_with(k))
                .map(|(_, t)| t.median)
        };
        get(a).zip(get(b)).map_or(f64::NAN, |(x, y)| x / y)
    };
    let _ = writeln!(
        md,
        "\nReference over draft (medians): {:.1}× with no cache, {:.1}× with the symbolic \
         results cached.",
        ratio("cold, reference", "cold, draft"),
        ratio("reference, symbolic", "draft, symbolic")
    );
    md
}

/// The symbolic stage alone: derivation, claims and recorded results of every scene, in this
/// process; the fastest of `repeats` passes.
fn symbolic_stage(lectures: &Path, repeats: usize) -> Result<String> {
    let files = crate::scene::find_scenes(&[lectures.to_path_buf()])?;
    let scenes = crate::scene::load_all(&files).map_err(|errors| {
        anyhow!(
            "{}",
            errors
                .iter()
                .map(|e| e.to_string())
                .collect::<Vec<_>>()
                .join("; ")
        )
    })?;
    let mut best = f64::INFINITY;
    let (mut calls, mut engine) = (0, 0.0);
    for _ in 0..repeats.max(1) {
        let start = Instant::now();
        let (mut c, mut e) = (0, 0.0);
        for scene in &scenes {
            let plan = crate::plan::Plan::for_scene(scene);
            let s = crate::pipeline::symbolic_stage(scene, &plan)?;
            (c, e) = (c + s.engine_calls, e + s.seconds);
        }
        let wall = start.elapsed().as_secs_f64();
        if wall < best {
            (best, calls, engine) = (wall, c, e);
        }
    }
    Ok(format!(
        "\n## The symbolic stage alone\n\nEvery scene's derivation, claims and recorded results, \
         in one process, fastest of {repeats}: {:.1} ms for {} scenes, of which {:.1} ms in {calls} \
         Symbolica calls. `bash tests/sympy/compare.sh` times SymPy on REFERENCE.md's set against \
         the same stage.\n",
        best * 1e3,
        scenes.len(),
        engine * 1e3
    ))
}
