//! `mechbook derive`: one scene's steps, results, numeric cross-check and claims.

use super::{FidelityArg, find, load};
use crate::pipeline;
use crate::report;
use anyhow::Result;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct DeriveArgs {
    /// The scene file.
    pub scene: PathBuf,
    /// Print the scene as JSON.
    #[arg(long)]
    pub json: bool,
    /// Show which stages ran and which were skipped, and why.
    #[arg(long)]
    pub explain: bool,
    #[command(flatten)]
    pub fidelity: FidelityArg,
}

pub fn run(args: DeriveArgs) -> Result<ExitCode> {
    let DeriveArgs {
        scene,
        json,
        explain,
        fidelity: FidelityArg { fidelity },
    } = args;
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
    let page = crate::document::page(&r, None, None);
    let text = if json {
        serde_json::to_string_pretty(&report::scene_json(&page))? + "\n"
    } else {
        let mut t = report::derivation_text(&page);
        if explain {
            t.push('\n');
            t.push_str(&report::explain_text(&page));
        }
        t
    };
    std::io::stdout().write_all(text.as_bytes())?;
    if r.verification.passed_but_for_new_steps() {
        let new = r
            .verification
            .step_records
            .iter()
            .filter(|s| s.recorded.is_none())
            .count();
        if new > 0 {
            eprintln!(
                "mechbook: {} of `{}` not yet recorded: once you have reviewed them, \
                 `mechbook check --bless {}` records them, so that `check` sees a change",
                crate::base::format::count(new, "step"),
                r.scene.id,
                scene.display()
            );
        }
        return Ok(ExitCode::SUCCESS);
    }
    // Standard output is the derivation; why it fails goes to standard error, as `check` says it.
    let failures = report::failures(&r);
    eprintln!(
        "mechbook: scene `{}` failed {}:",
        r.scene.id,
        crate::base::format::count(failures.len(), "check")
    );
    for f in failures {
        eprintln!("  {f}");
    }
    eprintln!(
        "mechbook: once you have reviewed the changes, `mechbook check --bless {}` records them",
        scene.display()
    );
    Ok(ExitCode::from(1))
}
