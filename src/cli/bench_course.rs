//! `mechbook bench --course-only DIR`: a course at the scale a term needs, timed as a user runs
//! it: `check`, `build --no-cache`, the same with a roster of 25 students, a build after one
//! scene's edit, and 10,000 variants of a nearly symmetric top (I₃ = I₁(1 + 10⁻⁵)). Each is a
//! child process timed from outside, with the peak memory it prints as it exits.

use super::bench_timing::{Timing, timed};
use crate::site::scratch;
use anyhow::{Context, Result, bail};
use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

/// A free top within 10⁻⁵ of symmetric, at 10,000 spins: the precession route's worst case.
const NEAR_SYMMETRIC_TOP: &str = include_str!("scenes/near-symmetric-top.toml");

/// The students of the roster row: 25, as a class.
const STUDENTS: usize = 25;

/// Runs `mechbook ARGS` in `dir` with its own cache folder: its wall-clock seconds, timed from
/// outside, and the peak memory in MiB it prints as it exits (Linux's VmHWM), asked for by
/// `PEAK_MEMORY_ENV`.
pub(super) fn child(args: &[&str], dir: &Path) -> Result<(f64, f64)> {
    let exe = std::env::current_exe()?;
    let start = Instant::now();
    let out = Command::new(exe)
        .args(args)
        .current_dir(dir)
        .env("SYMBOLICA_HIDE_BANNER", "1")
        .env("XDG_CACHE_HOME", dir.join("xdg"))
        .env(super::PEAK_MEMORY_ENV, "1")
        .stdout(Stdio::null())
        .output()
        .context("cannot run mechbook")?;
    let seconds = start.elapsed().as_secs_f64();
    let err = String::from_utf8_lossy(&out.stderr);
    if !finished(args, out.status.code()) {
        bail!("mechbook {} failed: {err}", args.join(" "));
    }
    let peak_mib = super::bench_timing::printed_peak(&err).unwrap_or(f64::NAN);
    Ok((seconds, peak_mib))
}

/// Whether a child ran to its end: `check` exits 1 when a claim disagrees, and the bench times
/// it all the same; anything else must succeed, or its row would time a build that stopped
/// early (the roster row once timed a roster refused after the site's PDFs).
fn finished(args: &[&str], code: Option<i32>) -> bool {
    match code {
        Some(0) => true,
        Some(1) => args.first() == Some(&"check"),
        _ => false,
    }
}

/// Each row of the course's table, measured on a copy of `course`.
pub fn course_bench(
    course: &Path,
    repeats: usize,
    progress: &mut impl FnMut(&str),
) -> Result<String> {
    let dir = scratch::folder("bench-course")?;
    let result = course_rows(course, &dir, repeats, progress);
    scratch::remove(&dir);
    result
}

/// The course copied into `dir`, with a roster and the near-symmetric top beside it; the
/// copy's folder and its number of scenes.
fn prepare(course: &Path, dir: &Path) -> Result<(PathBuf, usize)> {
    let scenes = dir.join("course");
    scratch::copy_tree(course, &scenes)?;
    let roster = dir.join("students.csv");
    let mut csv = String::from("name,id\n");
    for k in 1..=STUDENTS {
        let _ = writeln!(csv, "Student {k},{}", 1000 + k);
    }
    scratch::write_file(&roster, &csv)?;
    let top = dir.join("near-symmetric-top.toml");
    scratch::write_file(&top, NEAR_SYMMETRIC_TOP)?;
    let count = crate::scene::find_scenes(std::slice::from_ref(&scenes))?.len();
    Ok((scenes, count))
}

/// Each row's timing, run in `dir`, as the section's Markdown.
fn course_rows(
    course: &Path,
    dir: &Path,
    repeats: usize,
    progress: &mut impl FnMut(&str),
) -> Result<String> {
    let (scenes, count) = prepare(course, dir)?;
    let (site, papers, cache) = ("site", "papers", "cache");
    let mut rows: Vec<(String, Timing)> = Vec::new();
    let mut row = |name: String, args: &[&str]| -> Result<()> {
        progress(&name);
        let t = timed(repeats, || child(args, dir))?;
        rows.push((name, t));
        Ok(())
    };
    row(
        format!("`check` of the {count} scenes"),
        &["check", "course"],
    )?;
    row(
        "`build --no-cache`".into(),
        &["build", "course", "--no-cache", "--out", site],
    )?;
    row(
        format!("`build --no-cache --roster` ({STUDENTS} students)"),
        &[
            "build",
            "course",
            "--no-cache",
            "--out",
            site,
            "--roster",
            "students.csv",
            "--papers",
            papers,
        ],
    )?;
    // Its results and variants recorded first, as an author's scene has them.
    child(&["check", "--bless", "near-symmetric-top.toml"], dir)?;
    row(
        "`check` of 10,000 variants of a top with I₃ = I₁(1 + 10⁻⁵)".into(),
        &["check", "near-symmetric-top.toml"],
    )?;
    // The cache primed, then the last scene in name order edited before each build.
    progress("one scene edited");
    child(&["build", "course", "--out", site, "--cache", cache], dir)?;
    let edited = crate::scene::find_scenes(std::slice::from_ref(&scenes))?
        .pop()
        .context("no scene to edit")?;
    let mut edits = 0;
    let t = timed(repeats, || {
        edits += 1;
        scratch::append_line(&edited, &format!("# bench edit {edits}"))?;
        child(&["build", "course", "--out", site, "--cache", cache], dir)
    })?;
    rows.push((
        format!(
            "`build` after one scene's edit ({} of {count} from the cache)",
            count - 1
        ),
        t,
    ));
    progress("serve: an edit saved");
    let serve = super::bench_serve::serve_edits(dir, "course", &edited, repeats)?;
    rows.push((
        "`serve`: a scene saved → the open page told to reload".into(),
        serve.reload,
    ));
    rows.push((
        "`serve`: a scene saved → its lecture's PDFs ready (after the reload)".into(),
        serve.pdfs,
    ));
    Ok(table(course, count, repeats, &rows))
}

/// The rows as a Markdown table under the section's heading and words.
fn table(course: &Path, count: usize, repeats: usize, rows: &[(String, Timing)]) -> String {
    let mut md = format!(
        "## A course\n\nEach row is a separate `mechbook` process on a copy of `{}` ({count} \
         scenes), timed from outside (start-up included); {} each. Peak memory is the one \
         each process prints as it exits (Linux's VmHWM).\n\n\
         | what | fastest s | median s | peak MiB |\n|---|---|---|---|\n",
        course.display(),
        crate::base::format::count(repeats, "run")
    );
    for (name, t) in rows {
        // serve's rows time a page's reload, not one process: no peak of theirs.
        let peak = if t.peak.is_nan() {
            "–".to_owned()
        } else {
            format!("{:.0}", t.peak)
        };
        let _ = writeln!(
            md,
            "| {name} | {:.2} | {:.2} | {peak} |",
            t.fastest, t.median
        );
    }
    md
}

#[cfg(test)]
mod tests {
    use super::finished;

    #[test]
    fn only_check_may_time_a_run_that_exits_one() {
        assert!(finished(&["check", "course"], Some(0)));
        assert!(finished(&["check", "course"], Some(1)));
        assert!(finished(&["build", "course"], Some(0)));
        assert!(!finished(
            &["build", "course", "--roster", "s.csv"],
            Some(1)
        ));
        assert!(!finished(&["check", "course"], Some(2)));
        assert!(!finished(&["check", "course"], None));
    }
}
