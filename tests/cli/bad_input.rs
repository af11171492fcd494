//! Every invalid fixture gives its expected error: file, line, column and field, exit 1, no panic
//! and nothing on standard output.

use super::{mechbook, stderr};
use std::path::Path;

/// The scene files of a fixture folder, each with its expected message (its `.expected`).
pub fn fixtures(dir: &Path) -> Vec<(std::path::PathBuf, String)> {
    super::toml_files(dir)
        .into_iter()
        .map(|f| {
            let expected = std::fs::read_to_string(f.with_extension("expected"))
                .unwrap_or_else(|_| panic!("{} has no .expected", f.display()));
            (f, expected.trim().to_string())
        })
        .collect()
}

#[test]
fn each_invalid_fixture_gives_its_message() {
    let fixtures = fixtures(Path::new("tests/fixtures/invalid"));
    assert!(fixtures.len() >= 15, "fixtures missing");
    for (f, expected) in fixtures {
        let out = mechbook(&["check", f.to_str().unwrap()]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{}: {err}", f.display());
        assert!(
            out.stdout.is_empty(),
            "{}: partial output {:?}",
            f.display(),
            String::from_utf8_lossy(&out.stdout)
        );
        assert!(
            err.contains(expected.trim()),
            "{}:\n want: {}\n got:  {err}",
            f.display(),
            expected.trim()
        );
        assert!(!err.contains("panicked"), "{err}");
    }
}

#[test]
fn one_bad_scene_stops_the_whole_run_before_any_output() {
    let out = mechbook(&[
        "check",
        "lectures",
        "tests/fixtures/invalid/negative-size.toml",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(out.stdout.is_empty());
    assert!(stderr(&out).contains("1 bad scene file(s); nothing was derived"));
}

#[test]
fn a_missing_file_is_named() {
    let out = mechbook(&["derive", "lectures/no-such-scene.toml"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("lectures/no-such-scene.toml:1:1: cannot read the scene file"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn command_line_misuse_exits_with_2() {
    for args in [
        vec!["frobnicate"],
        vec!["check", "--nope"],
        vec!["derive"],
        vec![],
    ] {
        let out = mechbook(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
    }
}

#[test]
fn help_explains_the_commands() {
    let out = mechbook(&["--help"]);
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8(out.stdout).unwrap();
    for word in ["check", "derive", "Exit status"] {
        assert!(text.contains(word), "{text}");
    }
    let out = mechbook(&["check", "--help"]);
    assert!(
        String::from_utf8(out.stdout)
            .unwrap()
            .contains("regression test")
    );
}
