//! A second mechbook process waits for the first instead of aborting (Symbolica allows one
//! process per user without a licence).

use super::{lecture, mechbook, stderr};
use std::process::{Command, Stdio};
use std::time::Duration;

#[test]
fn a_second_process_waits_for_the_lock_with_a_message() {
    let path = mechbook::cas::lock_path().unwrap();
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    let lock = std::fs::File::options()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .unwrap();
    lock.lock().unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_mechbook"))
        .args(["derive", lecture("06-hoop.toml").to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    assert!(
        child.try_wait().unwrap().is_none(),
        "mechbook ran while another process held the lock"
    );
    lock.unlock().unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert!(
        stderr(&out).contains("waiting for another mechbook process"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn concurrent_runs_all_succeed() {
    let handles: Vec<_> = (0..3)
        .map(|_| std::thread::spawn(|| mechbook(&["check", "lectures/lecture-3-4/06-hoop.toml"])))
        .collect();
    for h in handles {
        let out = h.join().unwrap();
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    }
}

/// Processes that differ in TMPDIR and USER share Symbolica's permit (it lives in the user's
/// cache folder), so they must share mechbook's lock too: each waits, none aborts.
#[test]
fn processes_with_different_tmpdir_and_user_wait_instead_of_aborting() {
    let handles: Vec<_> = (0..3)
        .map(|k| {
            std::thread::spawn(move || {
                let tmp = std::env::temp_dir().join(format!("mechbook-tmpdir-{k}"));
                std::fs::create_dir_all(&tmp).unwrap();
                Command::new(env!("CARGO_BIN_EXE_mechbook"))
                    .args(["check", "lectures/lecture-3-4/06-hoop.toml"])
                    .env("TMPDIR", &tmp)
                    .env("USER", format!("someone-{k}"))
                    .output()
                    .unwrap()
            })
        })
        .collect();
    for h in handles {
        let out = h.join().unwrap();
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    }
}
