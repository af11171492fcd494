//! The one integration-test binary: it runs the `mechbook` executable as a user would.
//!
//! This process never calls Symbolica itself, so the child processes it starts never meet a
//! second Symbolica user in it; concurrent children wait for each other on mechbook's lock.

mod answers;
mod authoring;
mod bad_input;
mod build;
mod catalogue;
mod check;
mod classics;
mod contract;
mod course;
mod domain;
mod functions;
mod handouts;
mod hostile;
mod lms;
mod lock;
mod names;
mod output;
#[cfg(feature = "pdf")]
mod pdf;
mod printed;
mod problems;
mod records;
mod reliability;
mod reliability5;
mod result_names;
mod serve;
mod snapshots;
mod spin;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// `mechbook ARGS` run in `dir`, as a user in a course's folder runs it.
pub fn mechbook_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mechbook"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run mechbook")
}

pub fn mechbook(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mechbook"))
        .args(args)
        .output()
        .expect("run mechbook")
}

/// Standard output without Symbolica's restricted-mode banner (a box drawn at the top; users
/// may hide it with SYMBOLICA_HIDE_BANNER=1, and the tests must pass either way).
pub fn stdout(out: &Output) -> String {
    let text = String::from_utf8(out.stdout.clone()).expect("UTF-8 output");
    let lines = text.lines();
    let mut kept = Vec::new();
    let mut in_banner = false;
    for line in lines {
        if kept.is_empty() && line.starts_with('┌') {
            in_banner = true;
        }
        if in_banner {
            in_banner = !line.starts_with('└');
            continue;
        }
        kept.push(line);
    }
    let mut s = kept.join("\n");
    if text.ends_with('\n') {
        s.push('\n');
    }
    s
}

pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A course of one problem scene, `text`, at DIR/problems/p.toml (with tests/course's
/// mechbook.toml), built afresh into DIR/site: the site's folder and the outcome.
pub fn build_problem(dir: &Path, text: &str) -> (PathBuf, Output) {
    std::fs::create_dir_all(dir.join("problems")).unwrap();
    std::fs::write(dir.join("problems/p.toml"), text).unwrap();
    std::fs::copy("tests/course/mechbook.toml", dir.join("mechbook.toml")).unwrap();
    let site = dir.join("site");
    let out = mechbook(&[
        "build",
        dir.join("problems").to_str().unwrap(),
        "--no-cache",
        "--out",
        site.to_str().unwrap(),
    ]);
    (site, out)
}

/// A fresh scratch folder for one test, removed by the caller.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mechbook-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The scene files (`*.toml`) directly in `dir`, sorted.
pub fn toml_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    files
}

pub fn lecture(name: &str) -> PathBuf {
    Path::new("lectures/lecture-3-4").join(name)
}

/// Every file under `root`, by its path relative to `root`, with its bytes.
pub fn read_tree(root: &Path) -> BTreeMap<String, Vec<u8>> {
    fn walk(dir: &Path, root: &Path, out: &mut BTreeMap<String, Vec<u8>>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(&p, root, out);
            } else {
                out.insert(
                    p.strip_prefix(root).unwrap().to_string_lossy().into_owned(),
                    std::fs::read(&p).unwrap(),
                );
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(root, root, &mut out);
    out
}
