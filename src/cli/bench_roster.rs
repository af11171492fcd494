//! `mechbook bench --roster-only 250,1000,5000`: a roster's papers as the class grows. For each
//! size N, the box problem with N variants, recorded (`check --bless`), then `build --no-cache
//! --roster` of N students, each a child process timed from outside with its peak memory; and
//! last a site whose sheet has 10,000 variants, the most a problem may have. Time per student
//! should stay flat and memory bounded, since the class key and a long sheet are typeset in
//! parts (`document::files::VARIANTS_A_DOCUMENT`).

use super::bench_course::child;
use super::bench_timing::{Timing, timed};
use crate::site::scratch;
use anyhow::Result;
use std::fmt::Write;
use std::path::Path;

/// The variants of the sheet-only row: the most a problem may have.
const SHEET_VARIANTS: usize = 10_000;

/// A course of one lecture whose problem (`scene`, `{count}` replaced) has `count` variants,
/// in `dir`, its variants recorded as an author's are.
fn course(dir: &Path, scene: &str, count: usize) -> Result<()> {
    scratch::write_file(&dir.join("mechbook.toml"), "title = \"Roster bench\"\n")?;
    scratch::write_file(
        &dir.join("lectures/lecture-1/box.toml"),
        &scene.replace("{count}", &count.to_string()),
    )?;
    child(&["check", "--bless"], dir)?;
    Ok(())
}

/// The table: for each roster size, the build's fastest and median seconds, the median per
/// student, and its peak memory; then the 10,000-variant sheet. `scene` is the problem, its
/// variants' count written `{count}` (the box problem of `--variants-only`).
pub fn roster_bench(
    scene: &str,
    sizes: &[usize],
    repeats: usize,
    progress: &mut impl FnMut(&str),
) -> Result<String> {
    let mut md = format!(
        "## Rosters\n\nFor each class of N students: the box problem with N variants (recorded \
         first), then `mechbook build --no-cache --roster` of N students, a separate process \
         timed from outside; {} each. Peak memory is the one each process prints as it exits \
         (Linux's VmHWM).\n\n\
         | students | fastest s | median s | median ms a student | peak MiB |\n\
         |---|---|---|---|---|\n",
        crate::base::format::count(repeats, "run")
    );
    for &n in sizes {
        progress(&format!("{n} students"));
        let dir = scratch::folder("bench-roster")?;
        let result = (|| -> Result<Timing> {
            course(&dir, scene, n)?;
            let mut csv = String::from("name,id\n");
            for k in 1..=n {
                let _ = writeln!(csv, "Student {k},{}", 100_000 + k);
            }
            scratch::write_file(&dir.join("roster.csv"), &csv)?;
            timed(repeats, || {
                child(&["build", "--no-cache", "--roster", "roster.csv"], &dir)
            })
        })();
        scratch::remove(&dir);
        let t = result?;
        let _ = writeln!(
            md,
            "| {n} | {:.2} | {:.2} | {:.1} | {:.0} |",
            t.fastest,
            t.median,
            t.median * 1e3 / n as f64,
            t.peak
        );
    }
    progress(&format!("a sheet of {SHEET_VARIANTS} variants"));
    let dir = scratch::folder("bench-sheet")?;
    let result = (|| {
        course(&dir, scene, SHEET_VARIANTS)?;
        timed(repeats, || child(&["build", "--no-cache"], &dir))
    })();
    scratch::remove(&dir);
    let t = result?;
    let _ = write!(
        md,
        "\n`mechbook build --no-cache` of the same course with {SHEET_VARIANTS} variants and no \
         roster (the site's sheet and key, in parts): fastest {:.2} s, median {:.2} s, peak \
         {:.0} MiB.\n",
        t.fastest, t.median, t.peak
    );
    Ok(md)
}
