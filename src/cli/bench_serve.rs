//! The `serve` rows of the course bench: a scene saved under `mechbook serve`, timed from the
//! save to the moment an open page hears "reload" on its event stream (as a browser does), and
//! to the moment serve says the PDFs that the edit changed are ready.

use super::bench_timing::Timing;
use anyhow::{Context, Result, bail};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// What serve's edits took: to the page's reload, and to the PDFs.
pub(super) struct ServeTimes {
    pub reload: Timing,
    pub pdfs: Timing,
}

/// How long the first build and each edit's PDFs may take before the bench gives up.
const PATIENCE: Duration = Duration::from_secs(300);

/// A running `serve`, stopped when dropped.
struct Serving(Child);

impl Drop for Serving {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Serves `course` (a folder inside `dir`) and saves `edited` `repeats` times, each once the
/// last edit's PDFs are ready.
pub(super) fn serve_edits(
    dir: &Path,
    course: &str,
    edited: &Path,
    repeats: usize,
) -> Result<ServeTimes> {
    let exe = std::env::current_exe()?;
    let mut child = Command::new(exe)
        .args([
            "serve",
            course,
            "--out",
            "serve-site",
            "--cache",
            "serve-cache",
        ])
        .current_dir(dir)
        .env("SYMBOLICA_HIDE_BANNER", "1")
        .env("XDG_CACHE_HOME", dir.join("xdg"))
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .context("cannot run mechbook serve")?;
    let err = child.stderr.take().context("serve's messages")?;
    let serving = Serving(child);
    let (tell, lines) = mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(err).lines().map_while(Result::ok) {
            if tell.send(line).is_err() {
                break;
            }
        }
    });
    let until = |what: &str| -> Result<String> {
        let deadline = Instant::now() + PATIENCE;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match lines.recv_timeout(left) {
                Ok(line) if line.contains(what) => return Ok(line),
                Ok(_) => {}
                Err(_) => bail!("serve did not say \"{what}\" within {PATIENCE:?}"),
            }
        }
    };
    const AT: &str = "serving http://127.0.0.1:";
    let line = until(AT)?;
    let rest = &line[line.find(AT).map_or(0, |a| a + AT.len())..];
    let port: u16 = rest[..rest.find('/').unwrap_or(rest.len())]
        .parse()
        .context("serve's port")?;
    until(PDFS_READY)?;
    // A title the page and its PDFs show, changed at each save: a comment would change no
    // output, and leave no PDF to typeset.
    let original = std::fs::read_to_string(edited)?;
    if !original.contains(TITLE) {
        bail!("{} has no `{TITLE}` to edit", edited.display());
    }
    let (mut reloads, mut pdfs) = (Vec::new(), Vec::new());
    for k in 1..=repeats.max(1) {
        let generation = generation(port)?;
        let mut events = listen(port, generation)?;
        let retitled = original.replacen(TITLE, &format!("{TITLE}Edit {k}: "), 1);
        crate::site::scratch::write_file(edited, &retitled)?;
        let saved = Instant::now();
        hear_reload(&mut events)?;
        reloads.push((saved.elapsed().as_secs_f64(), f64::NAN));
        until(PDFS_READY)?;
        pdfs.push((saved.elapsed().as_secs_f64(), f64::NAN));
    }
    drop(serving);
    crate::site::scratch::write_file(edited, &original)?;
    Ok(ServeTimes {
        reload: Timing::of(&reloads),
        pdfs: Timing::of(&pdfs),
    })
}

/// Where the edited scene's title begins.
const TITLE: &str = "title = \"";

/// What serve prints when a full build has made the PDFs.
const PDFS_READY: &str = "the PDFs are ready";

/// The build generation the served index page was made at (its reload script's `since`).
fn generation(port: u16) -> Result<u64> {
    let mut s = connect(port)?;
    write!(
        s,
        "GET /index.html HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\n\r\n"
    )?;
    let mut page = String::new();
    s.read_to_string(&mut page)?;
    let at = page
        .find("?since=")
        .context("no reload script in the index")?;
    let digits: String = page[at + 7..]
        .chars()
        .take_while(char::is_ascii_digit)
        .collect();
    Ok(digits.parse()?)
}

/// An open page's event stream, from `generation` on; returns once the server has answered,
/// so that it is listening before the edit.
fn listen(port: u16, generation: u64) -> Result<TcpStream> {
    let mut s = connect(port)?;
    write!(
        s,
        "GET {}?since={generation} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n",
        crate::serve::page::EVENTS_PATH
    )?;
    let mut head = Vec::new();
    let mut byte = [0u8; 1];
    while !head.ends_with(b"\r\n\r\n") {
        if s.read(&mut byte)? == 0 {
            bail!("the event stream closed before it began");
        }
        head.push(byte[0]);
    }
    Ok(s)
}

/// Reads the stream until its "reload".
fn hear_reload(s: &mut TcpStream) -> Result<()> {
    let mut got = Vec::new();
    let mut buf = [0u8; 512];
    while !String::from_utf8_lossy(&got).contains("data: reload") {
        let n = s.read(&mut buf)?;
        if n == 0 {
            bail!("the event stream closed without a reload");
        }
        got.extend_from_slice(&buf[..n]);
    }
    Ok(())
}

fn connect(port: u16) -> Result<TcpStream> {
    let s = TcpStream::connect(("127.0.0.1", port)).context("cannot reach serve")?;
    s.set_read_timeout(Some(PATIENCE))?;
    Ok(s)
}
