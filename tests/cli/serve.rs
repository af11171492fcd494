//! `mechbook serve` driven as a user would: start it on a free port, fetch pages, edit a scene
//! and see the change, break it and see the error in the page, fix it, and stop with Ctrl-C.

use super::{read_tree, scratch};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// A GET over plain HTTP/1.1: the status code and the body.
fn get(port: u16, path: &str) -> (u16, Vec<u8>) {
    let mut s = TcpStream::connect(("127.0.0.1", port)).expect("connect");
    s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    write!(
        s,
        "GET {path} HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let mut raw = Vec::new();
    s.read_to_end(&mut raw).unwrap();
    let end = raw
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("headers");
    let head = String::from_utf8_lossy(&raw[..end]).into_owned();
    let status = head.split_whitespace().nth(1).unwrap().parse().unwrap();
    (status, raw[end + 4..].to_vec())
}

fn page(port: u16, path: &str) -> String {
    String::from_utf8(get(port, path).1).unwrap()
}

/// Polls `page` until `ok` holds, for at most `limit`; the time it took.
fn within(limit: Duration, mut ok: impl FnMut() -> bool) -> Option<Duration> {
    let start = Instant::now();
    while start.elapsed() < limit {
        if ok() {
            return Some(start.elapsed());
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    None
}

/// How long a rebuild may take to show: its child build may first wait for other tests'
/// mechbook processes.
const EDIT: Duration = Duration::from_secs(60);

/// A GET with a `Host` header of the test's choosing: the status code.
fn get_as(port: u16, host: &str, path: &str) -> u16 {
    let mut s = TcpStream::connect(("127.0.0.1", port)).expect("connect");
    s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    write!(
        s,
        "GET {path} HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let mut raw = Vec::new();
    s.read_to_end(&mut raw).unwrap();
    let head = String::from_utf8_lossy(&raw);
    head.split_whitespace().nth(1).unwrap().parse().unwrap()
}

struct Serving {
    child: Child,
    port: u16,
    lines: mpsc::Receiver<String>,
}

/// A failed assertion must not leave a server running (it holds mechbook's lock).
/// SIGTERM first, as a service manager stops it: serve stops its build and removes its
/// scratch folder before it ends. SIGKILL only if it has not ended in 20 s.
impl Drop for Serving {
    fn drop(&mut self) {
        let pid = self.child.id().to_string();
        let _ = Command::new("kill").args(["-TERM", &pid]).status();
        let deadline = Instant::now() + Duration::from_secs(20);
        while Instant::now() < deadline {
            if !matches!(self.child.try_wait(), Ok(None)) {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A scratch folder with a course made by `mechbook init` in it: (the folder, the course).
fn new_course(name: &str) -> (PathBuf, PathBuf) {
    let dir = scratch(name);
    let course = dir.join("course");
    let out = super::mechbook(&["init", course.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", super::stderr(&out));
    (dir, course)
}

fn serve(course: &Path) -> Serving {
    serve_with(course, &[], &[])
}

fn serve_with(course: &Path, args: &[&str], env: &[(&str, &Path)]) -> Serving {
    let mut child = Command::new(env!("CARGO_BIN_EXE_mechbook"))
        .arg("serve")
        .args(args)
        .envs(env.iter().copied())
        .current_dir(course)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let (tx, lines) = mpsc::channel();
    let err = child.stderr.take().unwrap();
    std::thread::spawn(move || {
        for line in BufReader::new(err).lines() {
            let Ok(line) = line else { break };
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    // The build may wait for another test's mechbook first (one Symbolica process at a time).
    let deadline = Instant::now() + Duration::from_secs(120);
    let port = loop {
        let line = lines
            .recv_timeout(deadline.saturating_duration_since(Instant::now()))
            .expect("serve printed no address");
        if let Some(at) = line.find("serving http://127.0.0.1:") {
            let rest = &line[at + "serving http://127.0.0.1:".len()..];
            break rest[..rest.find('/').unwrap()].parse().unwrap();
        }
    };
    Serving { child, port, lines }
}

/// Waits for serve to print a line holding `what`; the lines before it.
fn said(s: &Serving, what: &str) -> Vec<String> {
    let deadline = Instant::now() + Duration::from_secs(120);
    let mut seen = Vec::new();
    loop {
        let line = s
            .lines
            .recv_timeout(deadline.saturating_duration_since(Instant::now()))
            .unwrap_or_else(|_| panic!("serve never said {what:?}: {seen:#?}"));
        if line.contains(what) {
            return seen;
        }
        seen.push(line);
    }
}

/// Saves the starter's book scene with its title `from` changed to `to`.
fn retitle_book(course: &Path, from: &str, to: &str) {
    let scene = course.join("lectures/lecture-1/01-book.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    assert!(text.contains(from), "{text}");
    std::fs::write(&scene, text.replace(from, to)).unwrap();
}

/// The lines of `log` that start with `prefix`.
fn starting(log: &[String], prefix: &str) -> Vec<String> {
    log.iter()
        .filter(|l| l.starts_with(prefix))
        .cloned()
        .collect()
}

/// What serve prints when the PDFs a page-first build left out are made.
const PDFS_READY: &str = "the PDFs are ready";

fn interrupt(child: &mut Child) -> Option<i32> {
    Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    let start = Instant::now();
    while start.elapsed() < Duration::from_secs(10) {
        if let Some(status) = child.try_wait().unwrap() {
            return status.code();
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let _ = child.kill();
    None
}

#[test]
fn serve_rebuilds_on_edit_shows_errors_in_the_page_and_stops_on_ctrl_c() {
    let (dir, course) = new_course("serve");
    let mut s = serve(&course);
    let port = s.port;
    // The page first, then its PDFs: the site is whole after both.
    said(&s, PDFS_READY);

    // The served pages are build's bytes, with only the reload script added.
    let site = read_tree(&course.join("site"));
    for (path, bytes) in &site {
        if path == ".mechbook-site" {
            continue;
        }
        let (status, body) = get(port, &format!("/{path}"));
        assert_eq!(status, 200, "{path}");
        if path.ends_with(".html") {
            let text = String::from_utf8(body).unwrap();
            let at = text
                .find("<script>/* mechbook serve: live reload */")
                .expect(path);
            let end = text[at..].find("</script>").unwrap() + at + "</script>".len();
            let without = format!("{}{}", &text[..at], &text[end..]);
            assert_eq!(without.as_bytes(), &bytes[..], "{path}");
        } else {
            assert_eq!(&body, bytes, "{path}");
        }
    }
    assert_eq!(get(port, "/").1, get(port, "/index.html").1);
    // The marker is the build's, not the site's.
    assert!(site.contains_key(".mechbook-site"));
    assert_eq!(get(port, "/.mechbook-site").0, 404);
    // A path out of the site is refused before any file is looked at.
    assert_eq!(get(port, "/../../etc/passwd").0, 400);
    assert_eq!(get(port, "/plots/%2e%2e/%2e%2e/mechbook.toml").0, 400);
    assert_eq!(get(port, "/no-such-page.html").0, 404);

    // An edit is served. Each rebuild is a child process that may wait for another test's
    // mechbook (one engine process at a time): the browser test measures the real latency.
    let scene = course.join("lectures/lecture-1/01-book.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    std::fs::write(
        &scene,
        text.replace("A book as a uniform box", "A paperback as a box"),
    )
    .unwrap();
    let took = within(EDIT, || {
        page(port, "/book.html").contains("A paperback as a box")
    });
    assert!(took.is_some(), "the edit was not served within {EDIT:?}");

    // A broken scene: the last good page stays, with the located error at its top.
    std::fs::write(
        &scene,
        text.replace(
            "value = \"m*(h^2 + d^2)/3\"",
            "value = \"m*(h^2 + 2d^2)/3\"",
        ),
    )
    .unwrap();
    let shown = within(EDIT, || {
        page(port, "/book.html").contains("mechbook-serve-error")
    });
    assert!(shown.is_some(), "the error was not shown within {EDIT:?}");
    let broken = page(port, "/book.html");
    assert!(
        broken.contains("01-book.toml:33:20: field `claim[0].value`"),
        "{broken}"
    );
    assert!(broken.contains("write `2*d`"));
    assert!(
        broken.contains("A paperback as a box"),
        "the last good page is gone"
    );

    // Fixed: the page comes back without the error.
    std::fs::write(&scene, &text).unwrap();
    let back = within(EDIT, || {
        let p = page(port, "/book.html");
        !p.contains("mechbook-serve-error") && p.contains("A book as a uniform box")
    });
    assert!(
        back.is_some(),
        "the fixed page did not come back within {EDIT:?}"
    );

    // An open page is told to reload after each build: the event stream's first event.
    let mut events = TcpStream::connect(("127.0.0.1", port)).unwrap();
    events
        .set_read_timeout(Some(Duration::from_secs(5)))
        .unwrap();
    write!(
        events,
        "GET /__mechbook/events?since=0 HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n"
    )
    .unwrap();
    let mut buf = [0u8; 4096];
    let mut got = String::new();
    while !got.contains("data: reload") {
        let n = events.read(&mut buf).expect("an event");
        assert!(n > 0, "the stream closed: {got}");
        got.push_str(&String::from_utf8_lossy(&buf[..n]));
    }

    // Ctrl-C ends the open stream and the server, with exit 0.
    assert_eq!(
        interrupt(&mut s.child),
        Some(0),
        "serve did not stop cleanly"
    );
    let log: Vec<String> = s.lines.try_iter().collect();
    assert!(log.iter().any(|l| l.contains("stopping")), "{log:?}");
    assert!(
        log.iter()
            .any(|l| l.contains("ms from the change to telling")),
        "{log:?}"
    );
    // Nothing is left beside the site.
    let leftovers: Vec<_> = std::fs::read_dir(&course)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".building-") || n.contains(".previous-"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A save reloads the page from a build that leaves the PDFs not in the cache to the full
/// build after it; then the site is byte for byte what `mechbook build` writes.
#[test]
fn serve_reloads_the_page_first_and_its_pdfs_follow_as_build_makes_them() {
    let (dir, course) = new_course("serve-pdfs-later");
    let s = serve(&course);
    // The first build's page, then its PDFs (said before the address, which `serve` read).
    said(&s, PDFS_READY);
    let built = |name: &str| {
        let out = dir.join(name);
        let run = Command::new(env!("CARGO_BIN_EXE_mechbook"))
            .args(["build", "--no-cache", "--out", out.to_str().unwrap()])
            .current_dir(&course)
            .output()
            .unwrap();
        assert_eq!(run.status.code(), Some(0), "{}", super::stderr(&run));
        read_tree(&out)
    };
    let served = read_tree(&course.join("site"));
    assert_eq!(served.keys().filter(|p| p.ends_with(".pdf")).count(), 4);
    assert!(served == built("built"), "serve's site is not build's");

    // An edit of a title the PDFs show: the page reloads first, then two PDFs follow.
    let scene = course.join("lectures/lecture-1/01-book.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    std::fs::write(
        &scene,
        text.replace("A book as a uniform box", "A paperback as a box"),
    )
    .unwrap();
    let log = said(&s, PDFS_READY);
    let page_first = log
        .iter()
        .position(|l| l.contains("the page first; then"))
        .unwrap_or_else(|| panic!("{log:#?}"));
    let reload = log
        .iter()
        .position(|l| l.contains("ms from the change to telling"))
        .unwrap_or_else(|| panic!("{log:#?}"));
    assert!(page_first < reload, "{log:#?}");
    assert!(
        log[page_first].contains("then 2 PDFs"),
        "the lecture's student and instructor handouts: {log:#?}"
    );
    let served = read_tree(&course.join("site"));
    assert!(
        served == built("built-after-edit"),
        "serve's site after the edit is not build's"
    );
    assert!(page(s.port, "/book.html").contains("A paperback as a box"));
    assert!(!page(s.port, "/book.html").contains("mechbook-serve-pdfs"));
    drop(s);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_save_early_in_the_last_saves_page_build_stops_it_and_the_page_shows_the_later() {
    let (dir, course) = new_course("serve-edit-while-building");
    let s = serve(&course);
    said(&s, PDFS_READY);
    retitle_book(&course, "A book as a uniform box", "A first edit");
    // The page's build starts as serve says this; the second save comes a few ms into it.
    said(&s, "mechbook: changed: ");
    retitle_book(&course, "A first edit", "A second edit");
    let log = said(&s, PDFS_READY);
    let reloads = log
        .iter()
        .filter(|l| l.contains("ms from the change to telling"))
        .count();
    // Stopped (the usual case): the pages were told to reload once, for the second edit. Not
    // stopped: the second save came before the build read the file (one build), or the host
    // was too slow to stop the build within 30 ms of its start (it is shown, then the next).
    let stopped = "the build of the last edit's page is stopped for this one";
    if log.iter().any(|l| l.contains(stopped)) {
        assert_eq!(reloads, 1, "{log:#?}");
    } else {
        assert!((1..=2).contains(&reloads), "{log:#?}");
    }
    assert_eq!(
        log.iter()
            .filter(|l| l.contains("the page first; then"))
            .count(),
        reloads,
        "{log:#?}"
    );
    let book = page(s.port, "/book.html");
    assert!(book.contains("A second edit"), "{book}");
    assert!(!book.contains("mechbook-serve-error"), "{book}");
    let leftovers: Vec<_> = std::fs::read_dir(&course)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".building-"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
    drop(s);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_edit_late_in_the_last_edits_page_build_waits_for_it_and_both_are_shown() {
    // An editor saving as one types: each save must not stop the build before it, or no page
    // would show until the typing stops.
    let (dir, course) = new_course("serve-edit-late-in-building");
    let s = serve(&course);
    said(&s, PDFS_READY);
    let book = course.join("lectures/lecture-1/01-book.toml");
    let text = std::fs::read_to_string(&book).unwrap();
    // A heavier first edit, so that its build is still running 60 ms in: a numeric fidelity
    // of 1e-12 makes the check's integrations long.
    let heavy = text
        .replace("A book as a uniform box", "A first edit")
        .replace("[numeric]\n", "[numeric]\nfidelity = \"1e-12\"\n");
    assert_ne!(
        heavy,
        text.replace("A book as a uniform box", "A first edit")
    );
    std::fs::write(&book, &heavy).unwrap();
    said(&s, "mechbook: changed: ");
    std::thread::sleep(Duration::from_millis(60));
    std::fs::write(&book, heavy.replace("A first edit", "A second edit")).unwrap();
    let log = said(&s, PDFS_READY);
    assert!(
        !log.iter().any(|l| l.contains("is stopped for this one")),
        "{log:#?}"
    );
    assert!(starting(&log, "mechbook: built ").len() >= 2, "{log:#?}");
    assert!(page(s.port, "/book.html").contains("A second edit"));
    drop(s);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `serve --no-cache` neither reads nor writes the course's cache, yet derives each scene once:
/// the build of the PDFs after the page-first one, and each edit, take the scenes from serve's
/// own cache, which goes with serve.
#[test]
fn serve_is_not_woken_by_its_own_cache_in_a_plainly_named_folder_of_the_course() {
    // `serve . --cache cache`: the cache is inside the watched folder, every build writes it,
    // and serve once took those writes for edits and built again and again (11 builds for one
    // edit of the starter, where 4 are due).
    let (dir, course) = new_course("serve-own-cache");
    let mut s = serve_with(&course, &[".", "--cache", "cache"], &[]);
    said(&s, PDFS_READY);
    retitle_book(&course, "A book as a uniform box", "A box");
    let log = said(&s, PDFS_READY);
    let changed = |log: &[String]| starting(log, "mechbook: changed: ");
    assert_eq!(changed(&log).len(), 1, "{log:#?}");
    assert!(changed(&log)[0].ends_with("01-book.toml"), "{log:#?}");
    assert!(std::fs::read_dir(course.join("cache")).unwrap().count() > 0);
    // Nothing more is built once the edit's PDFs are ready.
    let mut after = Vec::new();
    while let Ok(line) = s.lines.recv_timeout(Duration::from_millis(1500)) {
        after.push(line);
    }
    assert!(changed(&after).is_empty(), "{after:#?}");
    assert_eq!(interrupt(&mut s.child), Some(0));
    drop(s);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn serve_no_cache_derives_each_scene_once_and_leaves_no_cache_behind() {
    let (dir, course) = new_course("serve-no-cache");
    let mut s = serve_with(&course, &["--no-cache"], &[]);
    let built = |log: &[String]| starting(log, "mechbook: built ");
    let log = said(&s, PDFS_READY);
    // The page-first build's line was said before the address; the PDFs' build's after it.
    let pdfs = built(&log);
    assert_eq!(pdfs.len(), 1, "{log:#?}");
    assert!(
        pdfs[0].contains("from 2 scenes (2 from the cache"),
        "the PDFs' build derived again: {}",
        pdfs[0]
    );
    let scene = course.join("lectures/lecture-1/01-book.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    std::fs::write(&scene, text.replace("A book as a uniform box", "A box")).unwrap();
    let log = said(&s, PDFS_READY);
    let builds = built(&log);
    assert_eq!(builds.len(), 2, "{log:#?}");
    assert!(builds[0].contains("(1 from the cache"), "{}", builds[0]);
    assert!(builds[1].contains("(2 from the cache"), "{}", builds[1]);
    assert!(page(s.port, "/book.html").contains("A box"));
    assert_eq!(interrupt(&mut s.child), Some(0));
    assert!(
        !course.join(".mechbook-cache").exists(),
        "--no-cache wrote the course's cache"
    );
    let pid = s.child.id();
    let scratch = std::env::temp_dir().join(format!("mechbook-serve-{pid}"));
    assert!(!scratch.exists(), "{} left behind", scratch.display());
    drop(s);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn serve_holds_no_engine_sees_a_replaced_folder_and_keeps_to_its_site_and_host() {
    let (dir, course) = new_course("serve-child");
    let s = serve(&course);
    let port = s.port;

    // While it serves, `check` from a second process runs: serve's builds are child processes,
    // and serve itself never takes the engine's lock.
    let start = Instant::now();
    let check = Command::new(env!("CARGO_BIN_EXE_mechbook"))
        .arg("check")
        .current_dir(&course)
        .output()
        .unwrap();
    let took = start.elapsed();
    assert_eq!(check.status.code(), Some(0), "{}", super::stderr(&check));
    assert!(took < EDIT, "check waited {took:?} beside serve");
    eprintln!("check beside serve: {took:?}");

    // Only the loopback names at its port are answered (DNS rebinding).
    assert_eq!(get_as(port, &format!("127.0.0.1:{port}"), "/"), 200);
    assert_eq!(get_as(port, &format!("localhost:{port}"), "/"), 200);
    assert_eq!(get_as(port, &format!("evil.example:{port}"), "/"), 421);
    assert_eq!(get_as(port, "127.0.0.1:1", "/"), 421);
    assert_eq!(
        get_as(port, "evil.example", "/__mechbook/events?since=0"),
        421
    );

    // A link inside the site that leads out of it is not followed.
    let secret = dir.join("secret.txt");
    std::fs::write(&secret, "private").unwrap();
    std::os::unix::fs::symlink(&secret, course.join("site/leak.txt")).unwrap();
    std::os::unix::fs::symlink(&dir, course.join("site/up")).unwrap();
    assert_eq!(get(port, "/leak.txt").0, 404);
    assert_eq!(get(port, "/up/secret.txt").0, 404);

    // A check that fails shows on the page: the site is written, the failure on top.
    let scene = course.join("lectures/lecture-1/01-book.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    let failing = text.replacen("expect = \"agrees\"", "expect = \"disagrees\"", 1);
    assert_ne!(failing, text);
    std::fs::write(&scene, &failing).unwrap();
    let shown = within(EDIT, || {
        let p = page(port, "/book.html");
        p.contains("but these checks failed") && p.contains("verdict")
    });
    assert!(shown.is_some(), "{}", page(port, "/book.html"));

    // The lectures folder deleted and made again, as `git checkout` does: the new folder is
    // built, and an edit inside it after that is seen too.
    let lectures = course.join("lectures");
    let moved = dir.join("lectures-old");
    std::fs::rename(&lectures, &moved).unwrap();
    std::thread::sleep(Duration::from_millis(300));
    std::fs::create_dir_all(lectures.join("lecture-1")).unwrap();
    for e in std::fs::read_dir(moved.join("lecture-1")).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, lectures.join("lecture-1").join(p.file_name().unwrap())).unwrap();
    }
    std::fs::write(
        &scene,
        text.replace("A book as a uniform box", "A book of the new branch"),
    )
    .unwrap();
    let rebuilt = within(EDIT, || {
        page(port, "/book.html").contains("A book of the new branch")
    });
    assert!(rebuilt.is_some(), "the replaced folder was not built");
    std::fs::write(
        &scene,
        text.replace("A book as a uniform box", "Edited after the swap"),
    )
    .unwrap();
    let seen = within(EDIT, || {
        page(port, "/book.html").contains("Edited after the swap")
    });
    assert!(
        seen.is_some(),
        "an edit in the replaced folder was not seen"
    );
    assert!(!page(port, "/book.html").contains("mechbook-serve-error"));
    drop(s);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn serve_refuses_a_port_in_use_and_says_what_to_do() {
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port().to_string();
    let (dir, course) = new_course("serve-port");
    let out = Command::new(env!("CARGO_BIN_EXE_mechbook"))
        .args(["serve", "--port", &port])
        .current_dir(&course)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = super::stderr(&out);
    assert!(
        err.contains(&format!("cannot listen on 127.0.0.1:{port}")),
        "{err}"
    );
    assert!(err.contains("choose another --port"), "{err}");
    // At once: before any build.
    assert!(!course.join("site").exists(), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn serve_refuses_an_output_folder_that_is_not_a_site_and_serves_none_of_it() {
    let (dir, course) = new_course("serve-out");
    let notes = dir.join("notes");
    std::fs::create_dir_all(&notes).unwrap();
    std::fs::write(notes.join("private.txt"), "mine").unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_mechbook"))
        .args(["serve", "--out", notes.to_str().unwrap()])
        .current_dir(&course)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Were it served, serve would run until stopped: wait a bounded time.
    let exited = within(Duration::from_secs(60), || {
        child.try_wait().unwrap().is_some()
    });
    if exited.is_none() {
        let _ = child.kill();
    }
    let out = child.wait_with_output().unwrap();
    assert!(exited.is_some(), "serve did not stop");
    assert_eq!(out.status.code(), Some(1));
    let err = super::stderr(&out);
    assert!(err.contains("was not written by mechbook"), "{err}");
    assert!(!err.contains("serving http"), "{err}");
    assert_eq!(read_tree(&notes).len(), 1);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn serve_open_starts_the_browser_named_by_browser_at_the_served_address() {
    let (dir, course) = new_course("serve-open");
    // A "browser" that writes down the address it was asked to open.
    let opened = dir.join("opened.txt");
    let browser = dir.join("browser.sh");
    std::fs::write(
        &browser,
        format!("#!/bin/sh\nprintf '%s' \"$1\" > '{}'\n", opened.display()),
    )
    .unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&browser, std::fs::Permissions::from_mode(0o755)).unwrap();
    let mut s = serve_with(&course, &["--open"], &[("BROWSER", &browser)]);
    let asked = within(Duration::from_secs(10), || {
        std::fs::read_to_string(&opened).is_ok_and(|t| !t.is_empty())
    });
    assert!(asked.is_some(), "the browser was not started");
    let url = std::fs::read_to_string(&opened).unwrap();
    assert_eq!(url, format!("http://127.0.0.1:{}/", s.port));
    assert_eq!(get(s.port, "/").0, 200);
    assert_eq!(interrupt(&mut s.child), Some(0));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The processes whose parent is `pid`, read from /proc.
#[cfg(target_os = "linux")]
fn children_of(pid: u32) -> Vec<u32> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir("/proc").unwrap().map_while(Result::ok) {
        let Ok(stat) = std::fs::read_to_string(entry.path().join("stat")) else {
            continue;
        };
        // pid (comm) state ppid …: the name may hold spaces, the fields after its ')' do not.
        let after = stat.rsplit_once(')').map_or("", |(_, rest)| rest);
        let ppid = after.split_whitespace().nth(1);
        if ppid == Some(pid.to_string().as_str())
            && let Ok(child) = entry.file_name().to_string_lossy().parse()
        {
            found.push(child);
        }
    }
    found
}

/// Whether process `pid` still runs (a zombie waiting for its reaper has ended).
#[cfg(target_os = "linux")]
fn runs(pid: u32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/stat"))
        .ok()
        .and_then(|s| {
            s.rsplit_once(')')
                .map(|(_, rest)| rest.trim_start().starts_with('Z'))
        })
        .is_some_and(|zombie| !zombie)
}

#[test]
#[cfg(target_os = "linux")]
fn a_serve_killed_outright_takes_its_build_with_it() {
    let (dir, course) = new_course("serve-killed");
    // The engine's lock held here: serve's first build (no cache) waits for it, and would go on
    // waiting, then write the site, after serve is gone.
    let cache = dir.join("xdg");
    std::fs::create_dir_all(cache.join("mechbook")).unwrap();
    let lock = std::fs::File::create(cache.join("mechbook/symbolica.lock")).unwrap();
    lock.lock().unwrap();
    let mut serve = Command::new(env!("CARGO_BIN_EXE_mechbook"))
        .args(["serve", "--no-cache"])
        .env("XDG_CACHE_HOME", &cache)
        .current_dir(&course)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let serve_pid = serve.id();
    let started = within(Duration::from_secs(30), || {
        !children_of(serve_pid).is_empty()
    });
    let builds = children_of(serve_pid);
    // SIGKILL: serve cannot stop its build itself.
    let _ = serve.kill();
    let _ = serve.wait();
    assert!(started.is_some(), "serve started no build");
    let ended = within(Duration::from_secs(5), || !builds.iter().any(|&b| runs(b)));
    drop(lock);
    assert!(
        ended.is_some(),
        "build {builds:?} still runs after serve was killed"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
