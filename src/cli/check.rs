//! `mechbook check`: every scene derived and verified, as a regression test.

use super::{FidelityArg, default_paths, find, load, run_all};
use crate::pipeline::SceneReport;
use crate::report;
use anyhow::Result;
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
    #[command(flatten)]
    pub fidelity: FidelityArg,
}

pub fn run(args: CheckArgs) -> Result<ExitCode> {
    let CheckArgs {
        paths,
        json,
        fidelity: FidelityArg { fidelity },
    } = args;
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
