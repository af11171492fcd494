//! `mechbook init`: a new course that builds at once.

use anyhow::Result;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct InitArgs {
    /// The folder for the course: new or empty (default: the working folder).
    #[arg(default_value = ".")]
    pub dir: PathBuf,
}

pub fn run(args: InitArgs) -> Result<ExitCode> {
    let files = crate::site::init::init_course(&args.dir)?;
    for f in &files {
        eprintln!("  created {}", f.display());
    }
    let cd = if args.dir == std::path::Path::new(".") {
        String::new()
    } else {
        format!("cd {} && ", args.dir.display())
    };
    eprintln!(
        "mechbook: a new course in {}: {} files. Next: `{cd}mechbook serve --open` to see it, and \
         edit lectures/lecture-1/01-book.toml (README.md says what each file is)",
        args.dir.display(),
        files.len()
    );
    Ok(ExitCode::SUCCESS)
}
