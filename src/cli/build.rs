//! `mechbook build`: the course site.

use super::{FidelityArg, default_paths, find, load, peak_memory_mib, run_all};
use crate::pipeline;
use crate::site::cache::Cache;
use anyhow::Result;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
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
}

pub fn run(args: BuildArgs) -> Result<ExitCode> {
    let BuildArgs {
        paths,
        out,
        templates,
        timings,
        fidelity: FidelityArg { fidelity },
        cache,
        no_cache,
    } = args;
    let start = std::time::Instant::now();
    let paths = default_paths(paths);
    // The course's settings sit beside its scenes (`build my-course/`), or in the working folder.
    let beside = paths
        .iter()
        .map(|p| p.join("mechbook.toml"))
        .find(|p| p.is_file());
    let course = crate::render::Course::load(
        beside
            .as_deref()
            .unwrap_or(std::path::Path::new("mechbook.toml")),
    )?;
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
        eprintln!("mechbook: {errors} scene(s) could not be derived; the site was not written");
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
    let files = crate::render::site_files(&reports, &course, templates.as_deref(), timings)?;
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
