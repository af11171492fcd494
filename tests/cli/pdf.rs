//! The PDFs, read back with poppler (`pdftotext`, `pdfinfo`, `pdffonts`; `.ci/run` installs
//! them): no student's PDF holds an answer, the key holds every one, every page is on the
//! course's paper, every font is embedded and no character lacks a glyph, two builds give the
//! same bytes, and a roster gives each student a paper with their name on every page.

use super::{mechbook, mechbook_in, scratch, stderr, stdout};
use mechbook::base::format::figures;
use serde_json::Value as Json;
use std::path::Path;
use std::process::Command;

/// Whether poppler is here; on CI it must be.
fn poppler() -> bool {
    let here = Command::new("pdftotext").arg("-v").output().is_ok();
    assert!(
        here || std::env::var_os("CI").is_none(),
        "CI needs poppler-utils (pdftotext) for the PDF checks"
    );
    if !here {
        eprintln!("skipped: no pdftotext (install poppler-utils)");
    }
    here
}

fn tool(name: &str, args: &[&str]) -> String {
    let out = Command::new(name).args(args).output().expect(name);
    assert!(out.status.success(), "{name} {args:?}: {}", stderr(&out));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// A PDF's text, its pages apart (pdftotext ends each page with a form feed).
fn pages(pdf: &Path) -> Vec<String> {
    let text = tool("pdftotext", &["-layout", pdf.to_str().unwrap(), "-"]);
    let mut pages: Vec<String> = text.split('\u{c}').map(str::to_string).collect();
    if pages.last().is_some_and(|p| p.trim().is_empty()) {
        pages.pop();
    }
    pages
}

fn text(pdf: &Path) -> String {
    pages(pdf).join("\n")
}

fn derived(scene: &str) -> Json {
    let out = mechbook(&["derive", "--json", scene]);
    assert!(out.status.success(), "{scene}: {}", stderr(&out));
    serde_json::from_str(&stdout(&out)).unwrap()
}

/// An answer's entry as the key prints it: four figures, without its sign (a minus is set
/// apart), the mantissa of a power of ten.
fn on_key(x: f64) -> String {
    let s = figures(x, 4);
    let s = s.trim_start_matches('-');
    s.split(['e', 'E']).next().unwrap().to_string()
}

const PROBLEMS: &[&str] = &[
    "lectures/lecture-3-4/10-problem-box.toml",
    "lectures/lecture-3-4/11-problem-tilted-hoop.toml",
    "lectures/lecture-3-9/06-problem-top.toml",
];

fn lecture_pdf(site: &Path, scene: &Json, kind: &str) -> std::path::PathBuf {
    let lecture = scene["notes"]["lecture"]
        .as_str()
        .unwrap()
        .replace('/', "-");
    site.join(format!("pdf/lecture-{lecture}-{kind}.pdf"))
}

#[test]
fn student_pdfs_hold_no_answer_and_the_key_holds_every_one() {
    if !poppler() {
        return;
    }
    let dir = scratch("pdf-answers");
    let site = dir.join("site");
    let out = mechbook(&[
        "build",
        "lectures",
        "--no-cache",
        "--out",
        site.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(!stderr(&out).contains("warning"), "{}", stderr(&out));
    for scene in PROBLEMS {
        let json = derived(scene);
        let student = text(&lecture_pdf(&site, &json, "problems-student"));
        let handout = text(&lecture_pdf(&site, &json, "student"));
        let key = text(&lecture_pdf(&site, &json, "problems-key"));
        // The student's handout leaves the problems to the sheet.
        let title = json["title"].as_str().unwrap();
        assert!(
            !handout.contains(title),
            "{scene}: on the student's handout"
        );
        let variants = json["variants"].as_array().unwrap();
        for v in variants {
            assert!(
                student.contains(&format!("Variant {}", v["number"])),
                "{scene}: no variant {}",
                v["number"]
            );
            for a in v["answers"].as_array().unwrap() {
                for x in super::problems::numbers(a) {
                    let d = on_key(x);
                    assert!(key.contains(&d), "{scene}: the key lacks {d}");
                    // A decimal of four figures is an answer's, not a given value's.
                    if x != 0.0 && d.contains('.') && d.len() >= 5 {
                        assert!(!student.contains(&d), "{scene}: {d} on the student's sheet");
                    }
                }
            }
        }
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// Every PDF of a site: on `paper` (pdfinfo's name for it), fonts embedded.
fn check_paper_and_fonts(site: &Path, paper: &str) -> usize {
    let mut count = 0;
    for e in std::fs::read_dir(site.join("pdf")).unwrap() {
        let pdf = e.unwrap().path();
        let p = pdf.to_str().unwrap();
        let info = tool("pdfinfo", &["-l", "999", p]);
        let sizes: Vec<&str> = info
            .lines()
            .filter(|l| l.starts_with("Page") && l.contains(" size:"))
            .collect();
        assert!(!sizes.is_empty(), "{p}: no page size");
        for s in &sizes {
            assert!(s.contains(paper), "{p}: {s}");
        }
        let fonts = tool("pdffonts", &[p]);
        for line in fonts.lines().skip(2) {
            let cols: Vec<&str> = line.split_whitespace().collect();
            let n = cols.len();
            assert!(
                n >= 5 && cols[n - 5] == "yes",
                "{p}: a font not embedded: {line}"
            );
        }
        count += 1;
    }
    count
}

#[test]
fn pdfs_are_on_the_courses_paper_with_every_glyph_and_the_same_bytes_twice() {
    if !poppler() {
        return;
    }
    let dir = scratch("pdf-paper");
    let (a, b) = (dir.join("a"), dir.join("b"));
    let cache = dir.join("cache");
    for out in [&a, &b] {
        let run = mechbook(&[
            "build",
            "lectures",
            "--cache",
            cache.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(run.status.success(), "{}", stderr(&run));
        assert!(!stderr(&run).contains("no font has"), "{}", stderr(&run));
    }
    // The second build took every PDF from the cache: the same bytes as typeset afresh.
    let fresh = dir.join("fresh");
    let run = mechbook(&[
        "build",
        "lectures",
        "--no-cache",
        "--out",
        fresh.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let (ta, tb, tf) = (
        super::read_tree(&a.join("pdf")),
        super::read_tree(&b.join("pdf")),
        super::read_tree(&fresh.join("pdf")),
    );
    assert_eq!(ta.len(), 8, "{:?}", ta.keys().collect::<Vec<_>>());
    assert!(ta == tb && ta == tf, "two builds gave different PDFs");
    assert_eq!(check_paper_and_fonts(&a, "(A4)"), 8);
    // The index and the handouts link to them.
    let index = std::fs::read_to_string(a.join("index.html")).unwrap();
    for name in ta.keys() {
        // Tera writes the `/` of a path as `&#x2F;`, which a browser reads back as `/`.
        assert!(
            index.contains(&format!("href=\"pdf&#x2F;{name}\"")),
            "{name}"
        );
        let html = name.replace(".pdf", ".html");
        let page = std::fs::read_to_string(a.join("handouts").join(&html)).unwrap();
        assert!(
            page.contains(&format!("href=\"../pdf&#x2F;{name}\"")),
            "{html}"
        );
    }
    // Letter paper, from mechbook.toml.
    let course = dir.join("course");
    let init = mechbook(&["init", course.to_str().unwrap()]);
    assert!(init.status.success(), "{}", stderr(&init));
    let toml = course.join("mechbook.toml");
    let text = std::fs::read_to_string(&toml).unwrap();
    std::fs::write(&toml, format!("paper = \"letter\"\n{text}")).unwrap();
    let letter = dir.join("letter");
    let run = mechbook(&[
        "build",
        course.to_str().unwrap(),
        "--no-cache",
        "--out",
        letter.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert!(check_paper_and_fonts(&letter, "(letter)") >= 2);
    std::fs::remove_dir_all(dir).unwrap();
}

fn roster(n: usize) -> String {
    let mut s = String::from("id,name,email\n");
    for i in 0..n {
        s.push_str(&format!(
            "S{:04},\"Student {i}, Name\",s{i}@example.org\n",
            100 + i
        ));
    }
    s
}

#[test]
fn a_roster_gives_each_student_a_named_paper_and_the_key_their_answers() {
    if !poppler() {
        return;
    }
    let dir = scratch("pdf-roster");
    let csv = dir.join("students.csv");
    // Lecture 3/4's sheet has 12 variants: 9 students take 9 of them.
    std::fs::write(&csv, roster(9)).unwrap();
    let (site, papers) = (dir.join("site"), dir.join("papers"));
    // Without a cache, or with the one named.
    let build_cached = |seed: &str, papers: &Path, cache: Option<&Path>| {
        let mut args = vec![
            "build",
            "lectures",
            "--out",
            site.to_str().unwrap(),
            "--roster",
            csv.to_str().unwrap(),
            "--papers",
            papers.to_str().unwrap(),
            "--seed",
            seed,
        ];
        match cache {
            Some(dir) => args.extend(["--cache", dir.to_str().unwrap()]),
            None => args.push("--no-cache"),
        }
        mechbook(&args)
    };
    let build = |seed: &str, papers: &Path| build_cached(seed, papers, None);
    let run = build("1", &papers);
    assert!(run.status.success(), "{}", stderr(&run));
    // Each paper names its variant: the site, which may be published, holds no variant's
    // answers: no key, page or PDF, no Moodle quiz or other LMS export, no link to
    // one, and no JSON report of a scene with variants.
    let published = super::read_tree(&site);
    for (path, bytes) in &published {
        assert!(
            !path.contains("problems-key")
                && (!path.starts_with("export/") || path.starts_with("export/json/")),
            "{path} in a site built with a roster"
        );
        if path.starts_with("export/json/") && path != "export/json/course.json" {
            let report: serde_json::Value = serde_json::from_slice(bytes).unwrap();
            let variants = report["variants"].as_array().unwrap();
            assert!(
                variants.is_empty(),
                "{path}: variants in a site built with a roster"
            );
        }
    }
    assert!(
        published.keys().any(|p| p.starts_with("export/json/")),
        "the scenes without variants have their JSON reports"
    );
    let index = String::from_utf8_lossy(&published["index.html"]).into_owned();
    assert!(!index.contains("problems-key"), "{index}");
    assert!(index.contains("problems-student"), "{index}");
    let table = std::fs::read_to_string(papers.join("variants.csv")).unwrap();
    let rows: Vec<&str> = table.lines().skip(1).collect();
    // One row per student and lecture with a sheet.
    assert_eq!(rows.len(), 9 * 2, "{table}");
    let scenes: Vec<Json> = PROBLEMS.iter().map(|s| derived(s)).collect();
    let key = text(&papers.join("key.pdf"));
    for i in 0..9 {
        let id = format!("S{:04}", 100 + i);
        let name = format!("Student {i}, Name");
        let file = papers.join(format!("{:03}-{id}.pdf", i + 1));
        let paper = pages(&file);
        assert!(paper.len() >= 2, "{id}: {} pages", paper.len());
        for (k, page) in paper.iter().enumerate() {
            assert!(
                page.contains(&name) && page.contains(&id),
                "{id}: page {} lacks the name or id",
                k + 1
            );
        }
        let whole = paper.join("\n");
        for row in rows.iter().filter(|r| r.contains(&id)) {
            // name (quoted), id, lecture, variant, paper
            let cols: Vec<&str> = row.rsplitn(4, ',').collect();
            let (variant, lecture) = (cols[1], cols[2]);
            assert!(whole.contains(&format!("Variant {variant}")), "{id}: {row}");
            for json in scenes.iter().filter(|j| j["notes"]["lecture"] == lecture) {
                // A problem with fewer variants than the sheet cycles through them.
                let all = json["variants"].as_array().unwrap();
                let v = &all[(variant.parse::<usize>().unwrap() - 1) % all.len()];
                for a in v["answers"].as_array().unwrap() {
                    for x in super::problems::numbers(a) {
                        let d = on_key(x);
                        assert!(key.contains(&d), "{id}: key lacks {d}");
                        if x != 0.0 && d.contains('.') && d.len() >= 5 {
                            assert!(!whole.contains(&d), "{id}: {d} on their paper");
                        }
                    }
                }
            }
        }
        assert!(
            key.contains(&name) && key.contains(&id),
            "{id} not in the key"
        );
    }
    // The same seed deals the same variants; another deals them anew.
    let again = dir.join("again");
    let run = build("1", &again);
    assert!(run.status.success(), "{}", stderr(&run));
    assert_eq!(
        std::fs::read_to_string(again.join("variants.csv")).unwrap(),
        table
    );
    assert_eq!(
        std::fs::read(again.join("key.pdf")).unwrap(),
        std::fs::read(papers.join("key.pdf")).unwrap()
    );
    let other = dir.join("other");
    let run = build("2", &other);
    assert!(run.status.success(), "{}", stderr(&run));
    assert_ne!(
        std::fs::read_to_string(other.join("variants.csv")).unwrap(),
        table
    );
    // More students than lecture 3/4's 12 variants: refused before anything is typeset (the
    // cache holds no PDF), nothing written.
    std::fs::write(&csv, roster(13)).unwrap();
    let (refused, cache) = (dir.join("refused"), dir.join("cache"));
    let run = build_cached("1", &refused, Some(&cache));
    assert_eq!(run.status.code(), Some(1), "{}", stderr(&run));
    assert!(
        stderr(&run).contains("13 students, but lecture 3/4's problem sheet has 12 variants"),
        "{}",
        stderr(&run)
    );
    assert!(!refused.exists());
    let typeset: Vec<String> = std::fs::read_dir(&cache)
        .into_iter()
        .flatten()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.contains(".pdf."))
        .collect();
    assert!(
        typeset.is_empty(),
        "typeset before the refusal: {typeset:?}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_bad_roster_is_refused_at_its_line_and_the_papers_stay_out_of_the_site() {
    let dir = scratch("pdf-roster-bad");
    let csv = dir.join("students.csv");
    std::fs::write(&csv, "name,id\nAda,1\nAlan,1\n").unwrap();
    let site = dir.join("site");
    let run = mechbook(&[
        "build",
        "lectures",
        "--out",
        site.to_str().unwrap(),
        "--roster",
        csv.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(1));
    assert!(
        stderr(&run).contains("students.csv:3: the id `1` is listed twice (first at line 2)"),
        "{}",
        stderr(&run)
    );
    std::fs::write(&csv, roster(2)).unwrap();
    let run = mechbook(&[
        "build",
        "lectures",
        "--out",
        site.to_str().unwrap(),
        "--roster",
        csv.to_str().unwrap(),
        "--papers",
        site.join("papers").to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(1));
    assert!(stderr(&run).contains("overlap"), "{}", stderr(&run));
    assert!(!site.exists());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn thirty_students_get_thirty_papers_with_their_names_on_every_page() {
    if !poppler() {
        return;
    }
    let dir = scratch("pdf-thirty");
    let course = dir.join("course");
    let scenes = course.join("lectures");
    std::fs::create_dir_all(&scenes).unwrap();
    // Lecture 3/4's two problems, with 30 variants each, recorded afresh by --bless.
    for f in ["10-problem-box.toml", "11-problem-tilted-hoop.toml"] {
        let text = std::fs::read_to_string(Path::new("lectures/lecture-3-4").join(f)).unwrap();
        let text: Vec<&str> = text
            .lines()
            .filter(|l| !l.starts_with("variants = "))
            .map(|l| {
                if l.starts_with("count = ") {
                    "count = 30"
                } else {
                    l
                }
            })
            .collect();
        std::fs::write(scenes.join(f), text.join("\n") + "\n").unwrap();
    }
    std::fs::write(
        course.join("mechbook.toml"),
        "title = \"Thirty students\"\n",
    )
    .unwrap();
    let bless = mechbook(&["check", "--bless", course.to_str().unwrap()]);
    assert!(bless.status.success(), "{}", stderr(&bless));
    let csv = dir.join("students.csv");
    std::fs::write(&csv, roster(30)).unwrap();
    let (site, papers) = (dir.join("site"), dir.join("papers"));
    let run = mechbook(&[
        "build",
        course.to_str().unwrap(),
        "--no-cache",
        "--out",
        site.to_str().unwrap(),
        "--roster",
        csv.to_str().unwrap(),
        "--papers",
        papers.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert!(
        stderr(&run).contains("30 students' papers"),
        "{}",
        stderr(&run)
    );
    let table = std::fs::read_to_string(papers.join("variants.csv")).unwrap();
    let mut variants: Vec<&str> = table
        .lines()
        .skip(1)
        .map(|r| r.rsplit(',').nth(1).unwrap())
        .collect();
    assert_eq!(variants.len(), 30);
    variants.sort_unstable();
    variants.dedup();
    assert_eq!(variants.len(), 30, "a variant went to two students");
    for i in 0..30 {
        let id = format!("S{:04}", 100 + i);
        let paper = pages(&papers.join(format!("{:03}-{id}.pdf", i + 1)));
        assert!(!paper.is_empty());
        for page in &paper {
            assert!(
                page.contains(&format!("Student {i}, Name")) && page.contains(&id),
                "{id}"
            );
        }
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// The lines of a PDF set below 60 % of its body's size (the median line's height, from
/// pdftotext's word boxes), and all its lines: a formula scaled to fit instead of broken.
fn shrunk_lines(pdf: &Path) -> (usize, usize) {
    let layout = tool("pdftotext", &["-bbox-layout", pdf.to_str().unwrap(), "-"]);
    let mut heights = Vec::new();
    for line in layout.split("<line ").skip(1) {
        let line = line.split("</line>").next().unwrap_or("");
        let words = line.split("<word ").skip(1).filter_map(|w| {
            let attr = |name: &str| -> Option<f64> {
                let at = w.find(&format!("{name}=\""))? + name.len() + 2;
                w[at..].split('"').next()?.parse().ok()
            };
            Some(attr("yMax")? - attr("yMin")?)
        });
        if let Some(h) = words.reduce(f64::max) {
            heights.push(h);
        }
    }
    let mut sorted = heights.clone();
    sorted.sort_by(f64::total_cmp);
    let body = sorted.get(sorted.len() / 2).copied().unwrap_or(0.0);
    (
        heights.iter().filter(|h| **h < 0.6 * body).count(),
        heights.len(),
    )
}

/// A display formula wider than the line is broken across lines, not scaled: on the shipped
/// lectures 533 of 6,095 lines were set below 60 % of the body (the smallest at 27 %, 8.7 %
/// of the lines). Now none of the lectures' 6,577, of tests/course's 8,263 or of the `init`
/// starter's 971 is: a fraction inside a fraction is on the line, an exponent in an integral's
/// limit is at the limit's size, a plot's one-letter axis label is upright. No text runs past
/// the paper's edge.
#[test]
fn wide_formulas_are_broken_not_shrunk() {
    if !poppler() {
        return;
    }
    let starter = scratch("pdf-shrink-starter");
    let made = mechbook(&["init", starter.join("course").to_str().unwrap()]);
    assert!(made.status.success(), "{}", stderr(&made));
    let starter = starter.join("course");
    for (course, most, least) in [
        ("lectures", 0, 5000),
        ("tests/course", 0, 5000),
        (starter.to_str().unwrap(), 0, 500),
    ] {
        let dir = scratch("pdf-shrink");
        let run = mechbook(&[
            "build",
            course,
            "--no-cache",
            "--out",
            dir.join("site").to_str().unwrap(),
        ]);
        assert!(run.status.success(), "{}", stderr(&run));
        // No text past the paper's edge, no missing glyph: no warning at all. (The starter's
        // cos φ once ran past it: a long fraction with its sum's first term after it.)
        assert!(!stderr(&run).contains("warning"), "{}", stderr(&run));
        // The pages scale a formula down on phones only as a last resort, never below 85 %,
        // and the build names each one (the lectures' triple integrals over a box).
        let said = stderr(&run);
        let notes: Vec<&str> = said.lines().filter(|l| l.contains("on phones")).collect();
        for note in &notes {
            // Each size stands before " % ".
            let parts: Vec<&str> = note.split(" % ").collect();
            for part in &parts[..parts.len() - 1] {
                let p: u32 = part.rsplit(' ').next().unwrap().parse().unwrap();
                assert!((85..100).contains(&p), "{note}");
            }
        }
        if course == "lectures" {
            // Each piece quoted in plain text, not its glyphs run together (`=∫−a2a2∫…`, the
            // same for the three moments).
            let cube = notes
                .iter()
                .find(|n| n.contains("05b-cube-centre.toml"))
                .unwrap_or_else(|| panic!("{}", stderr(&run)));
            for moment in ["m(y²+z²)/a³", "m(x²+z²)/a³", "m(x²+y²)/a³"] {
                assert!(
                    cube.contains(&format!(
                        "85 % `=∫_(−a/2)^(a/2)∫_(−a/2)^(a/2)∫_(−a/2)^(a/2){moment} dx dy dz`"
                    )),
                    "{cube}"
                );
            }
        }
        let (mut shrunk, mut lines) = (0, 0);
        for entry in std::fs::read_dir(dir.join("site/pdf")).unwrap() {
            let pdf = entry.unwrap().path();
            // No name of mechbook's is typeset: the notes' side of an erratum printed
            // `inertia_tensor` where the page prints I_xx.
            let leaked: Vec<String> = text(&pdf)
                .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .filter(|w| {
                    w.split_once('_').is_some_and(|(a, b)| {
                        a.len() > 2 && b.len() > 2 && a.chars().all(|c| c.is_ascii_lowercase())
                    })
                })
                .map(String::from)
                .collect();
            assert!(leaked.is_empty(), "{}: {leaked:?}", pdf.display());
            let (s, l) = shrunk_lines(&pdf);
            shrunk += s;
            lines += l;
        }
        assert!(lines > least, "{course}: {lines} lines");
        assert!(
            shrunk <= most,
            "{course}: {shrunk} of {lines} lines below 60 % of the body"
        );
        std::fs::remove_dir_all(dir).unwrap();
    }
    std::fs::remove_dir_all(starter.parent().unwrap()).unwrap();
}

/// The headings of an HTML handout, as text (those with mathematics left out: MathML and the
/// PDF's glyphs spell a letter differently).
fn html_headings(html: &str) -> Vec<String> {
    let mut out = Vec::new();
    for level in html.split("<h").skip(1) {
        let Some(rest) = level.strip_prefix(|c: char| ('2'..='4').contains(&c)) else {
            continue;
        };
        let body = rest.split_once('>').map_or("", |(_, b)| b);
        let body = body.split("</h").next().unwrap_or("");
        if body.contains("<math") {
            continue;
        }
        let mut text = String::new();
        let mut in_tag = false;
        for c in body.chars() {
            match c {
                '<' => in_tag = true,
                '>' => in_tag = false,
                c if !in_tag => text.push(c),
                _ => {}
            }
        }
        let text = text
            .replace("&#x27;", "'")
            .replace("&#x2F;", "/")
            .replace("&quot;", "\"")
            .replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&amp;", "&");
        out.push(text.trim().to_string());
    }
    out
}

fn words(s: &str) -> String {
    s.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .to_lowercase()
}

/// Each handout's HTML and PDF show the same sections, steps, claims and problems: every
/// heading of the HTML is in the PDF's text, in the same order. (The PDF key once answered a
/// problem with fewer variants than the sheet under every variant, where the HTML key and the
/// docs answer each of its variants once, in a section of its own.)
#[test]
fn each_handouts_html_and_pdf_show_the_same_sections() {
    if !poppler() {
        return;
    }
    let dir = scratch("pdf-same-sections");
    for (name, folder) in [("lectures", "lectures"), ("course", "tests/course")] {
        let out = dir.join(name);
        let run = mechbook(&[
            "build",
            folder,
            "--no-cache",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(
            run.status.success() || run.status.code() == Some(1),
            "{}",
            stderr(&run)
        );
        let mut compared = 0;
        for entry in std::fs::read_dir(out.join("handouts")).unwrap() {
            let html = entry.unwrap().path();
            let stem = html.file_stem().unwrap().to_str().unwrap().to_string();
            let pdf = out.join("pdf").join(format!("{stem}.pdf"));
            assert!(pdf.exists(), "{} has no PDF", html.display());
            let headings = html_headings(&std::fs::read_to_string(&html).unwrap());
            let text = words(&pages(&pdf).join(" "));
            let mut at = 0;
            for h in &headings {
                let found = text[at..].find(&words(h));
                assert!(
                    found.is_some(),
                    "{stem}: the HTML's heading `{h}` is not in the PDF after what came before"
                );
                at += found.unwrap();
            }
            compared += headings.len();
        }
        assert!(compared > 100, "{name}: {compared} headings");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// A PDF string as text: UTF-16 after its byte-order mark, else PDFDocEncoding (ASCII here).
fn pdf_text(bytes: &[u8]) -> String {
    match bytes.strip_prefix(&[0xfe, 0xff]) {
        Some(utf16) => {
            let units: Vec<u16> = utf16
                .chunks(2)
                .map(|c| u16::from_be_bytes([c[0], *c.get(1).unwrap_or(&0)]))
                .collect();
            String::from_utf16_lossy(&units)
        }
        None => String::from_utf8_lossy(bytes).into_owned(),
    }
}

/// The alternative text of each formula in a PDF's structure tree (`None` where a formula has
/// none), read with lopdf.
fn formula_alts(pdf: &Path) -> Vec<Option<String>> {
    let doc = lopdf::Document::load(pdf).unwrap_or_else(|e| panic!("{}: {e}", pdf.display()));
    doc.objects
        .values()
        .filter_map(|o| o.as_dict().ok())
        .filter(|d| matches!(d.get(b"S"), Ok(lopdf::Object::Name(n)) if n == b"Formula"))
        .map(|d| match d.get(b"Alt") {
            Ok(lopdf::Object::String(s, _)) => Some(pdf_text(s)),
            _ => None,
        })
        .collect()
}

#[test]
fn every_formula_in_the_pdfs_is_tagged_with_its_spoken_form() {
    if !poppler() {
        return;
    }
    let dir = scratch("pdf-alt");
    let site = dir.join("site");
    let run = mechbook(&[
        "build",
        "lectures",
        "--no-cache",
        "--out",
        site.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let mut formulas = 0;
    let mut pdfs = 0;
    for entry in std::fs::read_dir(site.join("pdf")).unwrap() {
        let pdf = entry.unwrap().path();
        let info = tool("pdfinfo", &[pdf.to_str().unwrap()]);
        assert!(
            info.contains("Tagged:          yes"),
            "{}: {info}",
            pdf.display()
        );
        // PDF/UA-1, declared in the document's metadata.
        let bytes = std::fs::read(&pdf).unwrap();
        assert!(
            bytes
                .windows(14)
                .any(|w| w == b"pdfuaid:part>1" || w == b"pdfuaid:part=\""),
            "{}: no PDF/UA identification",
            pdf.display()
        );
        let alts = formula_alts(&pdf);
        assert!(!alts.is_empty(), "{}: no formula tagged", pdf.display());
        for alt in &alts {
            let alt = alt.as_deref().unwrap_or("");
            assert!(
                !alt.trim().is_empty(),
                "{}: a formula without alt text",
                pdf.display()
            );
            // Words, not Typst or LaTeX.
            assert!(
                !alt.contains('\\') && !alt.contains("frac(") && !alt.contains('$'),
                "{}: {alt}",
                pdf.display()
            );
        }
        formulas += alts.len();
        pdfs += 1;
    }
    assert_eq!(pdfs, 8);
    // The summary of lecture 3/9 says Euler's equations in words.
    let summary = formula_alts(&site.join("pdf").join("lecture-3-9-student.pdf"));
    assert!(
        summary
            .iter()
            .flatten()
            .any(|a| a.contains("omega") && a.contains("equals")),
        "{summary:?}"
    );
    eprintln!("{formulas} formulas in {pdfs} PDFs, each with its spoken form");
    std::fs::remove_dir_all(dir).unwrap();
}

/// Typst holds a document's whole layout until its PDF is made, so a class key of 1,000
/// students or a sheet of 1,000 variants in one document peaked at over 800 MiB: past 200, each
/// is typeset in parts of 200, each its own PDF, named for its part and saying what it holds.
#[test]
fn a_class_key_and_a_sheet_past_200_are_typeset_in_parts() {
    if !poppler() {
        return;
    }
    let dir = scratch("pdf-parts");
    let run = |args: &[&str]| {
        let out = mechbook_in(&dir, args);
        assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    };
    run(&["init"]);
    let scene = dir.join("lectures/lecture-1/02-problem-box.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    assert!(
        text.contains("\ncount = 6\n"),
        "the starter's box problem changed"
    );
    let text: String = text
        .replace("\ncount = 6\n", "\ncount = 201\n")
        .lines()
        .filter(|l| !l.starts_with("variants = "))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(&scene, text).unwrap();
    std::fs::write(dir.join("students.csv"), roster(201)).unwrap();
    run(&["check", "--bless"]);
    run(&["build", "--no-cache", "--roster", "students.csv"]);
    let papers = dir.join("papers");
    assert!(!papers.join("key.pdf").exists());
    let (first, second) = (
        pages(&papers.join("key-1.pdf")),
        pages(&papers.join("key-2.pdf")),
    );
    // A student's key is a page: 200 in the first part, the 201st alone in the second.
    assert_eq!((first.len(), second.len()), (200, 1));
    assert!(first[199].contains("Student 199, Name"), "{}", first[199]);
    assert!(second[0].contains("Student 200, Name"), "{}", second[0]);
    let title = tool("pdfinfo", &[papers.join("key-2.pdf").to_str().unwrap()]);
    assert!(
        title.contains("answer key for the class, student 201"),
        "{title}"
    );
    // The site's sheet (its key is left out beside a roster): variants 1–200, then 201.
    let site = dir.join("site");
    let sheet = |k: usize| site.join(format!("pdf/lecture-1-problems-student-{k}.pdf"));
    assert!(!site.join("pdf/lecture-1-problems-student.pdf").exists());
    assert_eq!((pages(&sheet(1)).len(), pages(&sheet(2)).len()), (200, 1));
    assert!(pages(&sheet(2))[0].contains("Variant 201"));
    let index = std::fs::read_to_string(site.join("index.html")).unwrap();
    for link in [
        "lecture-1-problems-student-1.pdf\">variants 1–200</a>",
        "lecture-1-problems-student-2.pdf\">variant 201</a>",
    ] {
        assert!(index.contains(link), "{link} not in {index}");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// A PDF with a warning (a character no font has) is kept in the cache like any other: a warm
/// build typesets nothing, says the same warnings, and writes the same bytes.
#[test]
fn a_pdf_with_a_warning_is_cached_and_its_warning_said_again() {
    let dir = scratch("pdf-warned");
    assert!(mechbook_in(&dir, &["init"]).status.success());
    let scene = dir.join("lectures/lecture-1/01-book.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    let marked = text.replacen(
        "title = \"A book as a uniform box\"",
        "title = \"A book as a uniform box \u{13000}\"",
        1,
    );
    assert_ne!(marked, text, "the starter's title moved");
    std::fs::write(&scene, marked).unwrap();
    let build = |out: &str| {
        let r = mechbook_in(&dir, &["build", "--cache", "cache", "--out", out]);
        assert!(r.status.success(), "{}", stderr(&r));
        let said = stderr(&r);
        let warnings: Vec<String> = said
            .lines()
            .filter(|l| l.starts_with("mechbook: warning:"))
            .map(str::to_string)
            .collect();
        (said, warnings, super::read_tree(&dir.join(out)))
    };
    let (cold, cold_warnings, a) = build("a");
    assert!(
        cold.contains("4 PDFs (4 typeset, 0 from the cache)"),
        "{cold}"
    );
    assert_eq!(cold_warnings.len(), 2, "{cold}");
    assert!(
        cold_warnings
            .iter()
            .all(|w| w.contains("no font has `\u{13000}`")),
        "{cold}"
    );
    let (warm, warm_warnings, b) = build("b");
    assert!(
        warm.contains("4 PDFs (0 typeset, 4 from the cache)"),
        "{warm}"
    );
    assert_eq!(warm_warnings, cold_warnings);
    assert_eq!(a, b, "the cached site differs from the typeset one");
}
