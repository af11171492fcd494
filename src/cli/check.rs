//! `mechbook check`: every scene derived and verified, as a regression test.

use super::{FidelityArg, default_paths, find, load, run_all};
use crate::base::format::count;
use crate::pipeline::SceneReport;
use crate::report;
use crate::site::bless;
use anyhow::Result;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct CheckArgs {
    /// Scene files or folders to search for `*.toml` (default: lectures/).
    pub paths: Vec<PathBuf>,
    /// Print JSON instead of the table: `{"passed": true, "counts": {...}, "failures": [...],
    /// "scenes": [...]}`. Symbolica's licence banner also goes to standard output; for a file
    /// that holds the JSON alone, use --json-file.
    #[arg(long)]
    pub json: bool,
    /// Also write the JSON report to this file (for a course's CI: it needs no environment
    /// variable). The table or --json still goes to standard output.
    #[arg(long, value_name = "FILE", conflicts_with = "bless")]
    pub json_file: Option<PathBuf>,
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
        json_file,
        bless,
        fidelity: FidelityArg { fidelity },
    } = args;
    let paths = default_paths(paths)?;
    let files = find(&paths)?;
    if let Some(path) = &json_file {
        // Checked before anything is derived: the report never takes a source's place.
        let (course_file, _) = super::build::course_file(&paths);
        crate::site::Sources::of_course(&paths, &files, &course_file, None, None).check_apart(
            "--json-file",
            path,
            "check.json",
        )?;
    }
    let Some(scenes) = load(&files) else {
        return Ok(ExitCode::from(1));
    };
    let (reports, errors) = run_all(scenes, fidelity, &crate::pipeline::NoStore);
    if bless {
        return bless_all(&reports, errors.len());
    }
    let passed = errors.is_empty() && reports.iter().all(SceneReport::passed);
    // Made once, for standard output, the file, or both.
    let document = (json || json_file.is_some())
        .then(|| serde_json::to_string_pretty(&report::check_json(&reports, &errors)))
        .transpose()?
        .map(|d| d + "\n");
    if let (Some(path), Some(doc)) = (&json_file, &document) {
        crate::site::replace_file(path, doc.as_bytes())?;
    }
    let errors = errors.len();
    let text = match document {
        Some(doc) if json => doc,
        _ => report::check_table(&reports),
    };
    std::io::stdout().write_all(text.as_bytes())?;
    if errors > 0 {
        eprintln!(
            "mechbook: {} could not be derived (errors above); {} checked",
            count(errors, "scene"),
            match reports.len() {
                1 => "the other was".to_string(),
                n => format!("the other {n} were"),
            }
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
    let mut refused = Vec::new();
    for r in reports {
        let blessed = match bless::bless_scene(r) {
            Ok(b) if b.is_empty() => continue,
            Ok(b) => b,
            Err(e) => {
                refused.push(e);
                continue;
            }
        };
        files += 1;
        changes += blessed.len();
        let path = &r.scene.source;
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
        "blessed: {} in {files} of {}\n",
        count(changes, "change"),
        count(reports.len(), "scene file")
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
    for e in &refused {
        eprintln!("mechbook: error: {e}");
    }
    if errors > 0 {
        eprintln!(
            "mechbook: {} could not be derived (errors above); they were not blessed",
            count(errors, "scene")
        );
    }
    Ok(
        if unfixable.is_empty() && refused.is_empty() && errors == 0 {
            ExitCode::SUCCESS
        } else {
            ExitCode::from(1)
        },
    )
}
