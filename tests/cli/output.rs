//! `build --out`: only a new, empty or mechbook-written folder is replaced; a folder that holds
//! the build's inputs is refused; and a build killed at any instant leaves a whole site, the
//! old one or the new one.

use super::{mechbook, read_tree as tree, scratch, stderr};
use std::path::{Path, PathBuf};
use std::process::Command;

#[test]
fn folders_mechbook_did_not_write_are_refused_and_left_untouched() {
    let dir = scratch("refuse");
    std::fs::create_dir_all(dir.join("notes")).unwrap();
    std::fs::write(dir.join("notes/keep.txt"), "mine").unwrap();
    std::fs::write(dir.join("notes.txt"), "mine too").unwrap();
    let cwd = std::env::current_dir().unwrap();
    let cases: [(PathBuf, &str); 6] = [
        (dir.join("notes"), "not written by mechbook"),
        (dir.join("notes.txt"), "is a file, not a folder"),
        ("lectures".into(), "is or contains `lectures`"),
        (
            "lectures/lecture-3-4".into(),
            "is or contains `lectures/lecture-3-4/",
        ),
        (cwd.clone(), "is or contains `lectures`"),
        (cwd.join("src/.."), "is or contains `lectures`"),
    ];
    let before = tree(Path::new("lectures"));
    for (out, why) in cases {
        let r = mechbook(&["build", "--out", out.to_str().unwrap()]);
        assert_eq!(
            r.status.code(),
            Some(1),
            "{}: {}",
            out.display(),
            stderr(&r)
        );
        assert!(
            stderr(&r).contains(why),
            "{}: {}",
            out.display(),
            stderr(&r)
        );
        let said: Vec<_> = stderr(&r)
            .lines()
            .filter(|l| !l.starts_with("mechbook: waiting"))
            .map(String::from)
            .collect();
        assert_eq!(said.len(), 1, "{said:?}");
    }
    assert_eq!(
        std::fs::read_to_string(dir.join("notes/keep.txt")).unwrap(),
        "mine"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("notes.txt")).unwrap(),
        "mine too"
    );
    assert!(before == tree(Path::new("lectures")), "the scenes changed");
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(
        names.len(),
        2,
        "something was left beside the refused outputs: {names:?}"
    );

    // An empty folder is taken, and then, marked, replaced.
    std::fs::create_dir(dir.join("empty")).unwrap();
    let scene = "lectures/lecture-3-4/01-angular-momentum.toml";
    let out = dir.join("empty");
    for _ in 0..2 {
        let r = mechbook(&["build", scene, "--no-cache", "--out", out.to_str().unwrap()]);
        assert_eq!(r.status.code(), Some(0), "{}", stderr(&r));
    }
    assert!(out.join(".mechbook-site").is_file() && out.join("index.html").is_file());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Kills `build` at the N-th call of each system call that writes the site (strace's fault
/// injection), and checks that the output folder then holds the old site or the new one, whole.
/// The next build removes what the killed one left beside it.
#[test]
fn a_build_killed_at_any_instant_leaves_a_whole_site() {
    if Command::new("strace").arg("-V").output().is_err() {
        assert!(
            std::env::var_os("CI").is_none(),
            "CI must have strace (.ci/run installs it)"
        );
        eprintln!("skipped: strace is not installed (apt-get install strace)");
        return;
    }
    let dir = scratch("killed");
    let out = dir.join("site");
    let scenes = "lectures/lecture-3-4";
    let build = |fidelity: &str| {
        let r = mechbook(&[
            "build",
            scenes,
            "--no-cache",
            "--fidelity",
            fidelity,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(r.status.code(), Some(0), "{}", stderr(&r));
        tree(&out)
    };
    // The pages state their fidelity, so the two sites differ.
    let new = build("standard");
    let old = build("draft");
    assert!(old != new);
    let mut kills = 0;
    for (call, points) in [
        ("mkdir", &[1, 2, 10, 30][..]),
        ("openat", &[40, 60, 80, 100, 120][..]),
        // An unchanged file is linked from the old site rather than written.
        ("linkat,link", &[1, 5][..]),
        ("renameat2,rename,renameat", &[1][..]),
        ("unlinkat,unlink,rmdir", &[1, 10, 30][..]),
    ] {
        for when in points {
            let r = Command::new("strace")
                .args(["-f", "-qq", "-o", "/dev/null", "-e"])
                .arg(format!("inject={call}:signal=SIGKILL:when={when}"))
                .arg(env!("CARGO_BIN_EXE_mechbook"))
                .args([
                    "build",
                    scenes,
                    "--no-cache",
                    "--out",
                    out.to_str().unwrap(),
                ])
                .env("SYMBOLICA_HIDE_BANNER", "1")
                .output()
                .unwrap();
            kills += usize::from(!r.status.success());
            let now = tree(&out);
            assert!(
                now == old || now == new,
                "killed at {call} #{when}: the site is neither the old nor the new one"
            );
            // Back to the old site for the next kill.
            if now == new {
                build("draft");
            }
        }
    }
    assert!(kills >= 10, "only {kills} of the builds were killed");
    build("standard");
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(
        left,
        vec![std::ffi::OsString::from("site")],
        "stale folders were not removed"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
