//! `mechbook check`: every scene derived and verified, as a regression test.

use super::{FidelityArg, default_paths, find, load, run_all};
use crate::pipeline::SceneReport;
use crate::report;
use crate::site::bless;
use anyhow::{Context, Result};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct CheckArgs {
    /// Scene files or folders to search for `*.toml` (default: lectures/).
    pub paths: Vec<PathBuf>,
    /// Print JSON, `{"scenes": [...]}`, instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Record what was derived as the new expectation: each scene's `[expect]` (created when
    /// missing) and each claim's `expect` verdict are rewritten in the scene file, comments and
    /// layout kept, and every change is printed. Review the changes before committing them.
    /// Exact-against-numeric disagreements are never recorded: they still fail.
    #[arg(long, conflicts_with = "json")]
    pub bless: bool,
    #[command(flatten)]
    pub fidelity: FidelityArg,
}

pub fn run(args: CheckArgs) -> Result<ExitCode> {
    let CheckArgs {
        paths,
        json,
        bless,
        fidelity: FidelityArg { fidelity },
    } = args;
    let Some(scenes) = load(&find(&default_paths(paths)?)?) else {
        return Ok(ExitCode::from(1));
    };
    let (reports, errors) = run_all(scenes, fidelity, None)?;
    if bless {
        return bless_all(&reports, errors.len());
    }
    let errors = errors.len();
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

/// `--bless`: rewrites each scene whose record differs from what was derived, prints each
/// change, and fails only on what blessing cannot fix.
fn bless_all(reports: &[SceneReport], errors: usize) -> Result<ExitCode> {
    let mut out = String::new();
    let mut files = 0;
    let mut changes = 0;
    for r in reports {
        let path = &r.scene.source;
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        let (new_text, blessed) = bless::blessed_text(&text, r)?;
        if blessed.is_empty() {
            continue;
        }
        crate::site::replace_file(path, new_text.as_bytes())?;
        files += 1;
        changes += blessed.len();
        for b in blessed {
            let at = if b.line > 0 {
                format!("{}:{}", path.display(), b.line)
            } else {
                path.display().to_string()
            };
            out.push_str(&format!("{at}: {}\n", b.what));
        }
    }
    out.push_str(&format!(
        "blessed: {changes} change(s) in {files} of {} scene file(s)\n",
        reports.len()
    ));
    std::io::stdout().write_all(out.as_bytes())?;
    // What a record cannot settle: a failed check of the check itself, or exact against numeric.
    let unfixable: Vec<report::Failure> = reports
        .iter()
        .flat_map(report::failures)
        .filter(|f| !f.recordable)
        .collect();
    for f in &unfixable {
        eprintln!("mechbook: not blessed, still failing: {f}");
    }
    if errors > 0 {
        eprintln!(
            "mechbook: {errors} scene(s) could not be derived (errors above); they were not blessed"
        );
    }
    Ok(if unfixable.is_empty() && errors == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
