//! The fuzz suite: every scene under `lectures/` and `tests/fixtures/valid/` mutated with a
//! seeded generator, then parsed, derived, verified and rendered in this process. No mutant may
//! panic, abort or hang, and every error must be located (`file:line:col:` with line and
//! column ≥ 1, on one line).
//!
//! Every mutant that ever failed is kept in `tests/fixtures/fuzz/` and replayed first. A
//! failing mutant is written there (as `found-<seed>-<n>.toml`) for the next run to keep.
//!
//! It is its own test binary: it runs Symbolica in-process, so it holds the per-user lock while
//! it lives, and the CLI tests' child processes must not wait for it.
//!
//! Besides byte-level mutations, a problem's `[variants]` is mutated a third of the time: its
//! count, a symbol's range or list, its `require` (`mutate_variants`).
//!
//! Quick run (part of `cargo test --release`): 40 mutants per scene. Longer run:
//! `MECHBOOK_FUZZ_MUTANTS=300 MECHBOOK_FUZZ_SEED=7 cargo test --release --test fuzz -- --ignored --nocapture`.

use mechbook::model::fidelity::Fidelity;
use mechbook::pipeline;
use mechbook::scene::Scene;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// A mutant that takes longer than this is a hang.
const HANG: Duration = Duration::from_secs(60);

/// xorshift64*: small, seeded, the same on every machine.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }

    fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len())]
    }
}

/// Numbers an instructor or an attacker might write.
const NUMBERS: &[&str] = &[
    "0",
    "-1",
    "1e-10",
    "1e20",
    "1e-20",
    "1e30",
    "1e308",
    "1e-320",
    "5e-324",
    "1e5000",
    "99999999999999999999999999999999999999999",
    "0.000000000000000000000000000000000001",
    "nan",
    "inf",
    "-0.0",
    "1.5",
    "3",
    "1e9",
    "1e-300",
];

/// Expressions that stress the parser and the engine.
const EXPRESSIONS: &[&str] = &[
    "",
    "(",
    "((((((((((a))))))))))",
    "1/(a-a)",
    "sqrt(-1)",
    "a^a^a^a",
    "(a+b+c)^40",
    "(m+a)^5",
    "\\sin x",
    "2l",
    "tan(x)",
    "sin(sin(sin(sin(sin(x)))))",
    "m*a^2*[[1,0],[0,1]]",
    "1e-10*m",
    "inertia_tensor[3][0]",
    "cross(a, b)",
    "-(-(-(-a)))",
    "a/0",
    "0^-1",
    "x^(1/3)",
    "é",
    "a\u{1}b",
    "[[1,2,3],[4,5,6],[7,8,9]]",
    "sqrt(a^2)",
    "cos(pi/2 - theta)^2",
];

/// Raw bytes that break TOML or UTF-8.
const BYTES: &[&[u8]] = &[
    b"\"",
    b"[",
    b"]]",
    b"=",
    b"\n[[body]]\n",
    b"\xff",
    b"\x00",
    b"\x01",
    b"#",
    b"{",
    b"\r",
    b"\n[outputs]\nwant = []\n",
    b"\nkind = \"cone\"\n",
    b"\norigin = \"apex\"\n",
];

const COUNTS: &[&str] = &[
    "0",
    "1",
    "-3",
    "10000",
    "10001",
    "999999999999",
    "1.5",
    "\"12\"",
    "[1]",
];

/// A varying symbol's range or list: empty, reversed, zero steps, negative and zero masses,
/// values beyond double precision, angles far from zero, division by zero.
const OPTIONS: &[&str] = &[
    "{ from = \"-1\", to = \"3\", step = \"1/2\" }",
    "{ from = \"0\", to = \"0\", step = \"1\" }",
    "{ from = \"1\", to = \"1e30\", step = \"1\" }",
    "{ from = \"1\", to = \"2\", step = \"0\" }",
    "{ from = \"3\", to = \"1\", step = \"1\" }",
    "{ from = \"1\", to = \"2\" }",
    "{ from = \"1e-400\", to = \"1\", step = \"1/7\" }",
    "[\"1e1000\", \"2\"]",
    "[\"0\"]",
    "[\"1/0\"]",
    "[\"-2\", \"-1\"]",
    "[\"pi/6\", \"1e20*pi + pi/6\", \"1000000*pi\"]",
    "[\"1e-160\", \"1\"]",
    "[]",
    "[\"1\", \"1\"]",
    "\"3\"",
    "[0.5, 1.5]",
];

const REQUIRES: &[&str] = &[
    "[\"1/(a-a) > 0\"]",
    "[\"sqrt(2)*sqrt(2) == 2\"]",
    "[\"a <\"]",
    "[\"a < b < c\"]",
    "[\"x > 1\"]",
    "[\"sin(1/0) > 0\"]",
    "[\"2 > 1\", \"1 > 2\"]",
    "[\"\"]",
    "\"a < b\"",
    "[\"pi*1e400 > 1\"]",
];

/// A mutation of a scene's `[variants]`: its count, a varying symbol's range or list, or its
/// `require`; `None` for a scene without one.
fn mutate_variants(text: &[u8], rng: &mut Rng) -> Option<Vec<u8>> {
    let text = String::from_utf8(text.to_vec()).ok()?;
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let start = lines.iter().position(|l| l.trim() == "[variants]")?;
    let end = lines[start + 1..]
        .iter()
        .position(|l| l.trim_start().starts_with('['))
        .map_or(lines.len(), |k| start + 1 + k);
    let key_of = |l: &str| l.split_once('=').map(|(k, _)| k.trim().to_owned());
    let find = |lines: &[String], pred: &dyn Fn(&str) -> bool| {
        (start + 1..end).find(|&i| key_of(&lines[i]).is_some_and(|k| pred(&k)))
    };
    let (key, value) = match rng.below(3) {
        0 => ("count".to_owned(), rng.pick(COUNTS).to_owned()),
        1 => {
            let symbols: Vec<String> = (start + 1..end)
                .filter_map(|i| key_of(&lines[i]))
                .filter(|k| !["count", "seed", "require"].contains(&k.as_str()))
                .collect();
            let name = match symbols.len() {
                0 => "m".to_owned(),
                n => symbols[rng.below(n)].clone(),
            };
            (name, rng.pick(OPTIONS).to_owned())
        }
        _ => ("require".to_owned(), rng.pick(REQUIRES).to_owned()),
    };
    let line = format!("{key} = {value}");
    match find(&lines, &|k| k == key) {
        Some(i) => lines[i] = line,
        None => lines.insert(end, line),
    }
    Some((lines.join("\n") + "\n").into_bytes())
}

/// Author mathematics and prose with HTML, XML and Typst specials: each must reach no page as
/// markup, leave every Moodle file well-formed and every PDF typeset, or be refused at its line.
const AUTHOR_SPECIALS: &[&str] = &[
    r"A box $\\operatorname{</math><script>alert(1)</script>}$",
    r"$a<b$ and $b>c$ & more",
    r"$\\mathrm{<img src=x onerror=alert(1)>}$",
    r"<svg onload=alert(1)> $x$",
    r"$\\text{]]>}$ ]]> <![CDATA[",
    r"$\\sqrt{)}$",
    r"m/s$^2$",
    r"$\\mathrm{kg\\,m^2}$",
    r"$)$ and $($",
    "$\\\\text{\\\"); #panic(1) //}$",
    r"#let x = 1; #panic() $#$",
    r"\uFFFE \uFFFF",
    r"$\\frac{(}{)}$",
    r"$\\vec{\\omega}_x \\cdot \\hat n \\ne \\sqrt[3]{\\alpha}$ and $\\left.x\\right|_{0}$",
    r"$\\begin{cases} a & x > 0 \\\\ b & x \\le 0 \\end{cases}$",
    r"$\\overbrace{a} \\not< \\{a\\} \\|v\\| \\Bigl( x \\Bigr) 1{,}000 f'$",
    r"$\\color{red} x$",
    r"$\\vec\\vec\\vec\\vec\\vec\\vec x$ $a\\!b\\qquad c~d$",
];

/// The pieces random LaTeX is made of: what an author writes, and what once crashed the
/// reader (a number or a unit before a wide space, `\\char` before a non-ASCII letter), made
/// Moodle blanks (`{1:NUMERICAL:…}`), control characters (`\\char0`) or Typst's named
/// arguments (`a:b` first in an argument), or headings with no text (`\\hat{}`).
const LATEX_PIECES: &[&str] = &[
    "a",
    "x_1",
    "\\omega",
    "é",
    "1.5",
    "2",
    ":",
    "a:b",
    "{",
    "}",
    "^",
    "_",
    "&",
    "\\\\",
    "\\frac{",
    "\\sqrt{",
    "\\vec{",
    "\\hat{",
    "\\underset{a}{",
    "\\operatorname{",
    "\\mathrm{",
    "\\text{",
    "\\char",
    "\\char\"41",
    "\\char65",
    "\\char0",
    "\\char27",
    "\\kern1em",
    "\\mkern1mu",
    "\\hskip1pt",
    "\\kern{",
    "\u{a0}",
    "\u{2003}",
    "\u{3000}",
    " ",
    "\\begin{pmatrix}",
    "\\end{pmatrix}",
    "\\left(",
    "\\right)",
    "{1:NUMERICAL:=0:0}",
    "{1:SHORTANSWER:=x}",
    "]]>",
    "<",
    ">",
    "&amp;",
    "\"",
    "#",
    "%",
    "~",
    "'",
    "\\color{#aééb}",
    "\\begin{alignat}{é}",
    "\\not=",
    "<=",
    "->",
    ")",
    "(",
    ",",
    "\\,",
    "\\!",
    "\\{",
    "\\}",
    "\\mu",
    "\\cdot",
    "=",
];

/// Random LaTeX: 1 to 12 pieces, its braces closed half the time.
fn random_latex(rng: &mut Rng) -> String {
    let mut out = String::new();
    for _ in 0..1 + rng.below(12) {
        out.push_str(rng.pick(LATEX_PIECES));
    }
    if rng.below(2) == 0 {
        let open = out
            .matches('{')
            .count()
            .saturating_sub(out.matches('}').count());
        out.push_str(&"}".repeat(open));
    }
    out
}

/// Where a field that takes mathematics starts its quoted text: prose takes `$…$`, a
/// symbol's or a step's `tex` is LaTeX throughout. Each as (where the text starts, where it
/// ends, whether it is `tex`).
fn math_fields(text: &str) -> Vec<(usize, usize, bool)> {
    let mut out = Vec::new();
    for key in ["title", "statement", "label", "why", "meaning", "tex"] {
        for (at, _) in text.match_indices(&format!("{key} = \"")) {
            // A key of its own, not the end of a longer one (`subtitle`).
            if text[..at].ends_with(|c: char| c.is_ascii_alphanumeric() || c == '_') {
                continue;
            }
            let start = at + key.len() + 4;
            // A multi-line string (`"""`) is passed over.
            if text[start..].starts_with('"') {
                continue;
            }
            let mut end = start;
            let bytes = text.as_bytes();
            while end < bytes.len() && bytes[end] != b'"' && bytes[end] != b'\n' {
                end += if bytes[end] == b'\\' { 2 } else { 1 };
            }
            if end < bytes.len() && bytes[end] == b'"' {
                out.push((start, end, key == "tex"));
            }
        }
    }
    out.sort();
    out
}

/// One mutation of `text`.
fn mutate(text: &[u8], rng: &mut Rng) -> Vec<u8> {
    let mut t = text.to_vec();
    let at = |rng: &mut Rng, t: &[u8]| rng.below(t.len() + 1);
    // A problem's variants, a third of the time when it has them.
    if rng.below(3) == 0
        && let Some(v) = mutate_variants(&t, rng)
    {
        return v;
    }
    match rng.below(10) {
        // Replace a quoted string's content with hostile author text (a title, a statement, a
        // label, a meaning), its `$…$` included.
        9 => {
            let quotes: Vec<usize> = (0..t.len()).filter(|&i| t[i] == b'"').collect();
            if quotes.len() >= 2 {
                let k = rng.below(quotes.len() - 1);
                let (a, b) = (quotes[k] + 1, quotes[k + 1]);
                t.splice(a..b, rng.pick(AUTHOR_SPECIALS).bytes());
            }
        }
        // Replace a quoted string's content with a hostile expression.
        0 | 1 => {
            let quotes: Vec<usize> = (0..t.len()).filter(|&i| t[i] == b'"').collect();
            if quotes.len() >= 2 {
                let k = rng.below(quotes.len() - 1);
                let (a, b) = (quotes[k] + 1, quotes[k + 1]);
                let e = rng.pick(EXPRESSIONS).as_bytes().to_vec();
                t.splice(a..b, e);
            }
        }
        // Replace a number (inside or outside quotes) with a hostile one.
        2 | 3 => {
            let starts: Vec<usize> = (0..t.len())
                .filter(|&i| t[i].is_ascii_digit() && (i == 0 || !t[i - 1].is_ascii_alphanumeric()))
                .collect();
            if !starts.is_empty() {
                let s = starts[rng.below(starts.len())];
                let mut e = s;
                while e < t.len() && (t[e].is_ascii_alphanumeric() || t[e] == b'.' || t[e] == b'-')
                {
                    e += 1;
                }
                t.splice(s..e, rng.pick(NUMBERS).bytes());
            }
        }
        // Delete a span.
        4 => {
            let a = at(rng, &t);
            let b = (a + rng.below(40)).min(t.len());
            t.drain(a..b);
        }
        // Duplicate a span (a repeated key, a repeated table).
        5 => {
            let a = at(rng, &t);
            let b = (a + rng.below(120)).min(t.len());
            let span = t[a..b].to_vec();
            let c = at(rng, &t);
            t.splice(c..c, span);
        }
        // Insert raw bytes.
        6 => {
            let c = at(rng, &t);
            let b = BYTES[rng.below(BYTES.len())];
            t.splice(c..c, b.iter().copied());
        }
        // Swap two lines.
        7 => {
            let mut lines: Vec<Vec<u8>> = t.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect();
            let (a, b) = (rng.below(lines.len()), rng.below(lines.len()));
            lines.swap(a, b);
            t = lines.join(&b'\n');
        }
        // Truncate.
        _ => {
            let a = at(rng, &t);
            t.truncate(a);
        }
    }
    t
}

#[derive(Debug)]
enum Outcome {
    /// The scene was refused: the error's kind.
    Refused(&'static str),
    /// Parsed, but the pipeline could not derive it (located at the scene).
    Failed,
    /// Derived, verified and rendered.
    Ran,
}

/// `file:line:col: message` with line and column ≥ 1, one line.
fn located(message: &str, path: &Path) -> bool {
    let Some(rest) = message.strip_prefix(&format!("{}:", path.display())) else {
        return false;
    };
    let mut parts = rest.splitn(3, ':');
    let number = |p: Option<&str>| {
        p.and_then(|s| s.parse::<usize>().ok())
            .is_some_and(|n| n >= 1)
    };
    number(parts.next())
        && number(parts.next())
        && parts.next().is_some_and(|m| m.trim().len() > 3)
        && !message.contains('\n')
}

fn kind_of(message: &str) -> &'static str {
    let kinds = [
        (
            mechbook::notation::latex::READER_FAULT,
            "latex reader fault",
        ),
        ("field `variants", "variants"),
        ("field `problem", "problem"),
        ("invalid UTF-8", "not UTF-8"),
        ("control character", "control character"),
        ("malformed expression", "malformed expression"),
        ("undefined", "undefined name"),
        ("unknown field", "unknown field"),
        ("missing field", "missing field"),
        ("invalid type", "wrong type"),
        ("duplicate", "duplicate key"),
        ("expands to degree", "expression limit"),
        ("beyond what a plot", "plot limit"),
        ("must be", "out of range"),
        ("expected", "TOML syntax"),
    ];
    kinds
        .iter()
        .find(|(k, _)| message.contains(k))
        .map_or("other", |(_, v)| v)
}

/// Parses, derives, verifies and renders one scene text; `Err` is a defect. A refusal that
/// the LaTeX reader's backstop gave (its panic caught) is a defect too: mechbook must steer
/// the reader around it.
fn run_one(bytes: &[u8], path: &Path) -> Result<Outcome, String> {
    let r = run_one_unchecked(bytes, path);
    if let Ok(Outcome::Refused(kind)) = &r
        && *kind == "latex reader fault"
    {
        return Err("the LaTeX reader panicked (caught by its backstop)".into());
    }
    r
}

fn run_one_unchecked(bytes: &[u8], path: &Path) -> Result<Outcome, String> {
    let text = match std::str::from_utf8(bytes) {
        Ok(t) => t.to_string(),
        Err(_) => {
            // The reader's route for files: write it out and read it back.
            std::fs::write(path, bytes).map_err(|e| e.to_string())?;
            let e = Scene::from_file(path)
                .err()
                .ok_or("non-UTF-8 text was accepted")?;
            let m = e.to_string();
            return located(&m, path)
                .then_some(Outcome::Refused(kind_of(&m)))
                .ok_or(format!("unlocated error: {m}"));
        }
    };
    let scene = match Scene::parse(&text, path) {
        Ok(s) => s,
        Err(e) => {
            let m = e.to_string();
            return located(&m, path)
                .then_some(Outcome::Refused(kind_of(&m)))
                .ok_or(format!("unlocated error: {m}"));
        }
    };
    match pipeline::run_scene(scene, Some(Fidelity::DRAFT)) {
        Ok(report) => {
            let reports = [report];
            let course = Default::default();
            let documents = mechbook::document::course::documents(&reports, &course);
            let cx = mechbook::render::Context {
                course: &course,
                templates: &Default::default(),
                timings: false,
                memo: &mechbook::render::memo::Forget,
                keys: Default::default(),
                pdfs_later: false,
            };
            let rendered = mechbook::render::render(&documents, &cx)
                .map_err(|e| format!("rendering failed: {e}"))?;
            // Nothing an author wrote is markup on a page; every Moodle file is XML; every
            // JSON report is JSON (data, holding the author's text as written).
            for (file, bytes) in &rendered.files {
                if file.extension().is_some_and(|x| x == "json") {
                    serde_json::from_slice::<serde_json::Value>(bytes)
                        .map_err(|e| format!("{}: not JSON: {e}", file.display()))?;
                    continue;
                }
                let text = String::from_utf8_lossy(bytes);
                for markup in ["<script", "<img src=x", "<svg onload"] {
                    if text.contains(markup) {
                        return Err(format!("{} holds `{markup}`", file.display()));
                    }
                }
                if file.extension().is_some_and(|x| x == "xml") {
                    roxmltree::Document::parse(&text)
                        .map_err(|e| format!("{}: not well-formed XML: {e}", file.display()))?;
                }
            }
            // And typeset as PDF: whatever the author wrote, Typst must read the markup.
            #[cfg(feature = "pdf")]
            for doc in &rendered.typeset {
                mechbook::render::pdf::typeset::typeset(doc)
                    .map_err(|e| format!("typesetting failed: {e}"))?;
            }
            Ok(Outcome::Ran)
        }
        Err(e) => {
            let m = e.to_string();
            if m.contains(mechbook::notation::latex::READER_FAULT) {
                return Err(format!("the LaTeX reader panicked: {m}"));
            }
            located(&m, path)
                .then_some(Outcome::Failed)
                .ok_or(format!("unlocated error: {m}"))
        }
    }
}

/// Runs `run_one` on a thread, so that a panic is caught and a hang is seen. After a hang the
/// engine's one worker is still busy with it, so the caller stops: every later mutant would
/// only wait behind it.
fn guarded(bytes: Vec<u8>, path: PathBuf) -> Result<Outcome, String> {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let r = std::panic::catch_unwind(|| run_one(&bytes, &path));
        let _ = tx.send(r);
    });
    match rx.recv_timeout(HANG) {
        Ok(Ok(r)) => r,
        Ok(Err(_)) => Err("panicked".into()),
        Err(_) => Err(format!("hung for more than {} s", HANG.as_secs())),
    }
}

fn scenes() -> Vec<(PathBuf, Vec<u8>)> {
    let mut files =
        mechbook::scene::find_scenes(&["lectures".into(), "tests/fixtures/valid".into()])
            .expect("the scene folders");
    files.sort();
    files
        .into_iter()
        .map(|p| (p.clone(), std::fs::read(&p).unwrap()))
        .collect()
}

#[derive(Default)]
struct Tally {
    mutants: usize,
    ran: usize,
    failed: usize,
    refused: BTreeMap<&'static str, usize>,
    defects: Vec<String>,
}

impl Tally {
    /// Counts one mutant's outcome; a defect's input is kept at `keep` (unless it already is).
    fn record(&mut self, bytes: &[u8], keep: &Path, r: Result<Outcome, String>) {
        self.mutants += 1;
        match r {
            Ok(Outcome::Ran) => self.ran += 1,
            Ok(Outcome::Failed) => self.failed += 1,
            Ok(Outcome::Refused(k)) => *self.refused.entry(k).or_default() += 1,
            Err(e) => {
                if !keep.exists() {
                    let _ = std::fs::write(keep, bytes);
                }
                self.defects.push(format!("{}: {e}", keep.display()));
            }
        }
    }
}

fn fuzz(per_scene: usize, seed: u64) -> Tally {
    let work = std::env::temp_dir().join(format!("mechbook-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&work).unwrap();
    let mut tally = Tally::default();
    // Every failure found so far, first.
    let mut kept: Vec<PathBuf> = std::fs::read_dir("tests/fixtures/fuzz")
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    kept.retain(|p| p.extension().is_some_and(|x| x == "toml"));
    kept.sort();
    for p in kept {
        let bytes = std::fs::read(&p).unwrap();
        let r = guarded(bytes.clone(), work.join("kept.toml"));
        let hung = matches!(&r, Err(e) if e.starts_with("hung"));
        tally.record(&bytes, &p, r);
        if hung {
            return tally;
        }
    }
    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    for (path, text) in scenes() {
        for n in 0..per_scene {
            let mut bytes = mutate(&text, &mut rng);
            // Now and then a second mutation on top of the first.
            if rng.below(3) == 0 {
                bytes = mutate(&bytes, &mut rng);
            }
            let target = work.join(path.file_name().unwrap());
            let r = guarded(bytes.clone(), target);
            let hung = matches!(&r, Err(e) if e.starts_with("hung"));
            let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
            let keep =
                Path::new("tests/fixtures/fuzz").join(format!("found-{seed}-{stem}-{n}.toml"));
            tally.record(&bytes, &keep, r);
            if hung {
                let _ = std::fs::remove_dir_all(&work);
                return tally;
            }
        }
    }
    let _ = std::fs::remove_dir_all(&work);
    tally
}

fn report(t: &Tally, seconds: f64) {
    eprintln!(
        "fuzz: {} mutants in {seconds:.1} s: {} derived and rendered, {} refused by the \
         pipeline (located), {} refused at loading; {} defects",
        t.mutants,
        t.ran,
        t.failed,
        t.refused.values().sum::<usize>(),
        t.defects.len()
    );
    for (k, n) in &t.refused {
        eprintln!("  refused: {k}: {n}");
    }
}

fn check(per_scene: usize, seed: u64) {
    let start = Instant::now();
    let tally = fuzz(per_scene, seed);
    report(&tally, start.elapsed().as_secs_f64());
    assert!(tally.mutants > per_scene, "too few mutants ran");
    assert!(
        tally.ran > 0 && tally.refused.len() > 3,
        "the mutants do not reach every stage"
    );
    assert!(
        tally.defects.is_empty(),
        "defects (kept in tests/fixtures/fuzz/):\n{}",
        tally.defects.join("\n")
    );
}

/// Random LaTeX in every field that takes mathematics, in every scene: read or refused at its
/// line, never a panic (or a caught one); and every export of what is read well-formed (every
/// Moodle file XML) and every PDF typeset (`run_one`).
fn latex_fuzz(per_scene: usize, seed: u64) -> Tally {
    let work = std::env::temp_dir().join(format!("mechbook-latex-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&work).unwrap();
    let mut tally = Tally::default();
    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    for (path, bytes) in scenes() {
        let Ok(text) = String::from_utf8(bytes) else {
            continue;
        };
        let fields = math_fields(&text);
        if fields.is_empty() {
            continue;
        }
        for n in 0..per_scene {
            let (start, end, tex) = fields[rng.below(fields.len())];
            let latex = random_latex(&mut rng);
            let value = if tex {
                latex
            } else {
                format!("Words ${latex}$ and more")
            };
            // As the content of a TOML basic string.
            let value = value.replace('\\', "\\\\").replace('"', "\\\"");
            let mutant = format!("{}{value}{}", &text[..start], &text[end..]);
            let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
            let keep =
                Path::new("tests/fixtures/fuzz").join(format!("latex-{seed}-{stem}-{n}.toml"));
            let r = guarded(
                mutant.clone().into_bytes(),
                work.join(path.file_name().unwrap()),
            );
            let hung = matches!(&r, Err(e) if e.starts_with("hung"));
            tally.record(mutant.as_bytes(), &keep, r);
            if hung {
                return tally;
            }
        }
    }
    let _ = std::fs::remove_dir_all(&work);
    tally
}

#[test]
fn random_latex_in_every_math_field_is_read_or_refused_and_every_export_is_well_formed() {
    let start = Instant::now();
    let tally = latex_fuzz(10, 1);
    report(&tally, start.elapsed().as_secs_f64());
    assert!(
        tally.ran > 0,
        "no mutant was read: the fields are not reached"
    );
    assert!(
        tally.defects.is_empty(),
        "defects (kept in tests/fixtures/fuzz/):\n{}",
        tally.defects.join("\n")
    );
}

#[test]
#[ignore = "long: MECHBOOK_FUZZ_MUTANTS=60 cargo test --release --test fuzz the_long_latex -- --ignored --nocapture"]
fn the_long_latex_fuzz_run() {
    let start = Instant::now();
    let tally = latex_fuzz(
        from_env("MECHBOOK_FUZZ_MUTANTS", 60),
        from_env("MECHBOOK_FUZZ_SEED", 7),
    );
    report(&tally, start.elapsed().as_secs_f64());
    assert!(tally.defects.is_empty(), "{}", tally.defects.join("\n"));
}

/// A long run's setting from the environment, else `default`.
fn from_env<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

#[test]
fn mutated_scenes_never_panic_hang_or_go_unlocated() {
    check(40, 1);
}

#[test]
#[ignore = "long: MECHBOOK_FUZZ_MUTANTS=300 cargo test --release --test fuzz -- --ignored --nocapture"]
fn the_long_fuzz_run() {
    check(
        from_env("MECHBOOK_FUZZ_MUTANTS", 300),
        from_env("MECHBOOK_FUZZ_SEED", 7),
    );
}
