//! The hostile-input trial's reproducers: each is refused with a located line and exit 1, or
//! handled, and none panics, aborts or hangs.

use super::{mechbook, scratch, stderr, stdout};
use std::path::Path;
use std::process::Command;

fn copy_scene(from: &str, to: &Path, edit: impl Fn(String) -> String) {
    let text = std::fs::read_to_string(from).unwrap();
    std::fs::write(to, edit(text)).unwrap();
}

#[test]
fn a_duplicate_id_points_at_the_second_id_line() {
    let dir = scratch("dup-id");
    let hoop = "lectures/lecture-3-4/06-hoop.toml";
    copy_scene(hoop, &dir.join("a.toml"), |t| t);
    copy_scene(hoop, &dir.join("b.toml"), |t| format!("# a copy\n\n{t}"));
    let r = mechbook(&["check", dir.to_str().unwrap()]);
    assert_eq!(r.status.code(), Some(1));
    let id_line = std::fs::read_to_string(hoop)
        .unwrap()
        .lines()
        .position(|l| l.starts_with("id ="))
        .unwrap()
        + 3;
    let want = format!("b.toml:{id_line}:7: field `id`: duplicate scene id `hoop`");
    assert!(stderr(&r).contains(&want), "{}", stderr(&r));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn lectures_that_share_a_handout_file_are_an_error() {
    let dir = scratch("lecture-names");
    for (k, lecture) in ["3/4", "3-4", "3.4"].iter().enumerate() {
        copy_scene(
            "lectures/lecture-3-4/06-hoop.toml",
            &dir.join(format!("s{k}.toml")),
            |t| {
                t.replace("id = \"hoop\"", &format!("id = \"hoop{k}\""))
                    .replace("lecture = \"3/4\"", &format!("lecture = \"{lecture}\""))
            },
        );
    }
    let r = mechbook(&["check", dir.to_str().unwrap()]);
    assert_eq!(r.status.code(), Some(1));
    let err = stderr(&r);
    assert_eq!(
        err.matches("would share the handout file name `lecture-3-4-student`")
            .count(),
        2,
        "{err}"
    );
    assert!(err.contains("field `notes.lecture`"), "{err}");
    assert!(r.stdout.is_empty() || !stdout(&r).contains("scene "));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn devices_fifos_and_link_loops_are_not_read() {
    let r = mechbook(&["check", "/dev/zero"]);
    assert_eq!(r.status.code(), Some(1));
    assert!(
        stderr(&r).contains("/dev/zero:1:1: not a regular file"),
        "{}",
        stderr(&r)
    );

    let dir = scratch("fifo");
    let fifo = dir.join("scene.toml");
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let r = mechbook(&["check", fifo.to_str().unwrap()]);
    assert_eq!(r.status.code(), Some(1));
    assert!(stderr(&r).contains("not a regular file"), "{}", stderr(&r));
    // Inside a folder, a FIFO is passed over like any other non-file.
    copy_scene(
        "lectures/lecture-3-4/06-hoop.toml",
        &dir.join("hoop.toml"),
        |t| t,
    );
    std::os::unix::fs::symlink("..", dir.join("up")).unwrap();
    std::os::unix::fs::symlink(".", dir.join("here")).unwrap();
    std::os::unix::fs::symlink("/", dir.join("root")).unwrap();
    // The FIFO, the links out of the folder (`up`, `root`) and the loop (`here`) add nothing.
    let r = mechbook(&["check", dir.to_str().unwrap()]);
    assert_eq!(r.status.code(), Some(0), "{}", stderr(&r));
    assert!(stdout(&r).contains("1 scene,"), "{}", stdout(&r));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn engine_failures_are_located_and_the_other_scenes_still_run() {
    let r = mechbook(&[
        "check",
        "--json",
        "tests/fixtures/engine",
        "lectures/lecture-3-4/06-hoop.toml",
    ]);
    assert_eq!(r.status.code(), Some(1));
    let json: serde_json::Value = serde_json::from_str(&stdout(&r)).expect("valid JSON");
    let scenes = json["scenes"].as_array().unwrap();
    let ids: Vec<&str> = scenes.iter().map(|s| s["id"].as_str().unwrap()).collect();
    assert_eq!(ids, ["hoop", "engine-rejects"]);
    let problems: Vec<&str> = scenes[1]["claims"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["problem"].as_str().unwrap_or(""))
        .collect();
    assert!(problems[0].contains("division by zero"), "{problems:?}");
    assert!(problems[1].contains("complex number"), "{problems:?}");
    let err = stderr(&r);
    assert!(
        err.contains("over-budget.toml:3:7: scene `over-budget` could not be derived"),
        "{err}"
    );
    assert!(err.contains("beyond the engine's budget"), "{err}");
    for bad in ["panicked", "WARN", "RUST_BACKTRACE", "\u{1b}["] {
        assert!(
            !err.contains(bad) && !stdout(&r).contains(bad),
            "{bad}: {err}"
        );
    }
    let errors = err.lines().filter(|l| l.starts_with("mechbook: error:"));
    assert_eq!(errors.count(), 1, "{err}");
    assert!(err.contains("1 scene could not be derived"), "{err}");
}

#[test]
fn valid_fixtures_pass_including_extreme_numbers() {
    let r = mechbook(&["check", "tests/fixtures/valid"]);
    assert_eq!(r.status.code(), Some(0), "{}\n{}", stdout(&r), stderr(&r));
    assert!(stdout(&r).contains("extreme-numbers"));
}

/// Symbolica stops the process when it cannot place its permit in the user's cache folder;
/// mechbook must say so first. Needs a user without write access anywhere: root drops to
/// nobody with setpriv.
#[test]
fn an_unwritable_cache_folder_is_a_clear_error() {
    let is_root = Command::new("id")
        .arg("-u")
        .output()
        .map(|o| o.stdout == b"0\n");
    let has_setpriv = Command::new("setpriv").arg("--version").output().is_ok();
    if is_root.ok() != Some(true) || !has_setpriv {
        assert!(
            std::env::var_os("CI").is_none(),
            "CI runs as root with setpriv"
        );
        eprintln!("skipped: needs root and setpriv");
        return;
    }
    let dir = scratch("nobody");
    let exe = dir.join("mechbook");
    std::fs::copy(env!("CARGO_BIN_EXE_mechbook"), &exe).unwrap();
    copy_scene(
        "lectures/lecture-3-4/06-hoop.toml",
        &dir.join("hoop.toml"),
        |t| t,
    );
    Command::new("chmod")
        .args(["-R", "a+rX"])
        .arg(&dir)
        .status()
        .unwrap();
    for home in ["/nonexistent", "/"] {
        let r = Command::new("setpriv")
            .args([
                "--reuid=65534",
                "--regid=65534",
                "--clear-groups",
                "env",
                "-u",
                "XDG_CACHE_HOME",
            ])
            .arg(format!("HOME={home}"))
            .arg(&exe)
            .args(["check", dir.join("hoop.toml").to_str().unwrap()])
            .output()
            .unwrap();
        assert_eq!(r.status.code(), Some(1), "HOME={home}: {}", stderr(&r));
        assert!(
            stderr(&r).contains("set XDG_CACHE_HOME to a writable folder"),
            "{}",
            stderr(&r)
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
