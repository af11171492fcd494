//! `build`: the site and the handouts, byte-identical rebuilds, atomic replacement, relative
//! links and no build-machine paths in the output.

use super::{mechbook, read_tree, scratch, stderr, stdout};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// A scratch folder with the lectures' site built into `site/` inside it.
fn built_site(name: &str) -> (PathBuf, PathBuf) {
    let dir = scratch(name);
    let out = dir.join("site");
    let r = mechbook(&["build", "--out", out.to_str().unwrap()]);
    assert_eq!(r.status.code(), Some(0), "{}", stderr(&r));
    (dir, out)
}

/// The JSON report renderer writes each scene's page as `derive --json` prints it, without
/// the measured seconds (so that a rebuild is byte-identical), and the lectures in order.
#[test]
fn the_json_report_is_each_scenes_derive_json_and_the_lectures_in_order() {
    let (dir, out) = built_site("json-report");
    let read = |rel: &str| -> serde_json::Value {
        serde_json::from_slice(&std::fs::read(out.join(rel)).unwrap()).unwrap()
    };
    let course = read("export/json/course.json");
    let lectures = course["lectures"].as_array().unwrap();
    assert_eq!(lectures.len(), 2, "{course}");
    let scenes: Vec<&str> = lectures
        .iter()
        .flat_map(|l| l["scenes"].as_array().unwrap())
        .map(|s| s.as_str().unwrap())
        .collect();
    assert_eq!(scenes.len(), 18, "{scenes:?}");
    assert_eq!(scenes[0], "angular-momentum");
    for (id, file) in [
        ("hoop", "lectures/lecture-3-4/06-hoop.toml"),
        ("problem-box", "lectures/lecture-3-4/10-problem-box.toml"),
    ] {
        let r = mechbook(&["derive", file, "--json"]);
        assert_eq!(r.status.code(), Some(0), "{}", stderr(&r));
        let mut derived: serde_json::Value = serde_json::from_str(&stdout(&r)).unwrap();
        assert!(
            derived["symbolic_seconds"].is_number(),
            "derive --json keeps its timings"
        );
        drop_seconds(&mut derived);
        let written = read(&format!("export/json/{id}.json"));
        assert!(written.get("symbolic_seconds").is_none());
        assert_eq!(written, derived, "{id}");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

fn drop_seconds(j: &mut serde_json::Value) {
    match j {
        serde_json::Value::Object(map) => {
            map.remove("seconds");
            map.remove("symbolic_seconds");
            map.values_mut().for_each(drop_seconds);
        }
        serde_json::Value::Array(items) => items.iter_mut().for_each(drop_seconds),
        _ => {}
    }
}

#[test]
fn build_writes_the_site_and_rebuilds_it_identically() {
    let dir = scratch("build");
    let out = dir.join("site");
    let first = mechbook(&["build", "--out", out.to_str().unwrap()]);
    assert_eq!(first.status.code(), Some(0), "{}", stderr(&first));
    assert!(
        stderr(&first).contains(if cfg!(feature = "pdf") {
            "built 19 pages, 16 plots and 8 handouts, 8 PDFs ("
        } else {
            "built 19 pages, 16 plots and 8 handouts from 18 scenes"
        }),
        "{}",
        stderr(&first)
    );
    let a = read_tree(&out);
    for f in [
        "index.html",
        "style.css",
        "cube-corner.html",
        "tilted-hoop.html",
        "plots/tilted-hoop-tensor-vs-alpha.svg",
        "plots/cube-corner-convergence.svg",
        "plots/cube-corner-principal-axes.svg",
        "plots/hoop-convergence.svg",
        "handouts/lecture-3-4-student.html",
        "handouts/lecture-3-4-instructor.html",
        "handouts/lecture-3-9-student.html",
        "handouts/lecture-3-9-instructor.html",
        "symmetric-top.html",
        "plots/poinsot-polhodes.svg",
        "plots/earth-precession-polar-motion.svg",
        "handouts/lecture-3-4-problems-student.html",
        "handouts/lecture-3-9-problems-key.html",
        "export/moodle/problem-box.xml",
        "export/qti21/lecture-3-4.zip",
        "export/canvas/lecture-3-9.zip",
        "export/blackboard/lecture-3-4.txt",
        "export/json/course.json",
        "export/json/problem-box.json",
    ] {
        assert!(a.contains_key(f), "{f} missing: {:?}", a.keys());
    }
    let second = mechbook(&["build", "--out", out.to_str().unwrap()]);
    assert_eq!(second.status.code(), Some(0));
    assert!(a == read_tree(&out), "a rebuild changed the bytes");

    let cwd = std::env::current_dir().unwrap();
    for (name, bytes) in &a {
        // Tera escapes `/` as `&#x2F;`, which browsers decode in attributes and text alike.
        let Ok(text) = String::from_utf8(bytes.clone()) else {
            // The PDFs: their text is compressed, and tests/cli/pdf.rs reads it; the LMS
            // packages are zips, which tests/cli/lms.rs reads.
            assert!(
                name.ends_with(".pdf") || name.ends_with(".zip"),
                "{name} is not UTF-8"
            );
            continue;
        };
        let text = text.replace("&#x2F;", "/");
        assert!(
            !text.contains(cwd.to_str().unwrap()) && !text.contains(dir.to_str().unwrap()),
            "{name} contains a machine path"
        );
        let links = text.split("href=\"").skip(1);
        let sources = text.split("src=\"").skip(1);
        for href in links.chain(sources).map(|s| s.split('"').next().unwrap()) {
            assert!(
                !href.starts_with('/') && !href.contains("://"),
                "{name}: link {href} is not relative"
            );
            // A link within the page names an element of it.
            if let Some(id) = href.strip_prefix('#') {
                assert!(
                    text.contains(&format!("id=\"{id}\"")),
                    "{name}: broken link {href}"
                );
                continue;
            }
            let target = Path::new(name).parent().unwrap().join(href);
            let target = target.to_string_lossy().replace("handouts/../", "");
            assert!(a.contains_key(&target), "{name}: broken link {href}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn pages_carry_math_errata_and_the_numeric_table() {
    let (dir, out) = built_site("pages");
    let hoop = std::fs::read_to_string(out.join("hoop.html")).unwrap();
    assert!(hoop.contains("<math display=\"block\" alttext=\"") && !hoop.contains("<merror"));
    assert!(hoop.contains("Erratum, eq. (39)") && hoop.contains("Erratum, eq. (36)"));
    assert!(hoop.contains("periodic-trapezoid"));
    assert!(!hoop.contains("<script"));
    let student = std::fs::read_to_string(out.join("handouts/lecture-3-4-student.html")).unwrap();
    let instructor =
        std::fs::read_to_string(out.join("handouts/lecture-3-4-instructor.html")).unwrap();
    // The student's summary shows the derivation's steps, without their numeric checks or the
    // second routes that check them, and shows each erratum as one, corrected.
    assert!(student.contains("class=\"steps\""), "the derivation");
    assert!(
        !student.contains("numeric check") && !student.contains("from the definition"),
        "the student handout shows the checks"
    );
    assert!(
        instructor.contains("from the definition"),
        "the second route"
    );
    // A claim on a sign says it in words, never ±1.
    let tops = std::fs::read_to_string(out.join("handouts/lecture-3-9-student.html")).unwrap();
    assert!(
        tops.contains(
            "<dd>The notes: negative for every choice</dd><dd>Correct: positive for every choice</dd>"
        ),
        "the cone order's erratum"
    );
    assert!(student.contains("Erratum: eq. (39) of the notes is wrong"));
    assert!(instructor.contains("class=\"steps\"") && instructor.contains("erratum"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// True when the text quotes a decimal number such as `0.7335` or `3.5e-6`.
fn has_decimal(text: &str) -> bool {
    let c: Vec<char> = text.chars().collect();
    c.windows(3)
        .any(|w| w[0].is_ascii_digit() && w[1] == '.' && w[2].is_ascii_digit())
}

#[test]
fn every_plot_is_an_accessible_svg_shown_on_its_page() {
    let (dir, out) = built_site("plots");
    let site = read_tree(&out);
    let plots: Vec<&String> = site.keys().filter(|k| k.starts_with("plots/")).collect();
    assert_eq!(plots.len(), 16, "{plots:?}");
    for name in plots {
        let svg = String::from_utf8(site[name].clone()).unwrap();
        assert!(
            svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"),
            "{name}"
        );
        let title = svg
            .split("<title>")
            .nth(1)
            .and_then(|t| t.split("</title>").next());
        let desc = svg
            .split("<desc>")
            .nth(1)
            .and_then(|t| t.split("</desc>").next());
        assert!(title.is_some_and(|t| !t.is_empty()), "{name}: no <title>");
        // The description is written from the data: it quotes measured numbers.
        assert!(
            desc.is_some_and(|d| d.len() > 80 && has_decimal(d)),
            "{name}: {desc:?}"
        );
        let page = name.trim_start_matches("plots/");
        let scene = site
            .keys()
            .filter_map(|k| k.strip_suffix(".html"))
            .filter(|s| !s.contains('/') && page.starts_with(&format!("{s}-")))
            .max_by_key(|s| s.len())
            .unwrap_or_else(|| panic!("no page for {page}"));
        let html = String::from_utf8(site[&format!("{scene}.html")].clone()).unwrap();
        assert!(
            html.replace("&#x2F;", "/")
                .contains(&format!("src=\"{name}\"")),
            "{name} not on {scene}.html"
        );
    }
    let sweep = String::from_utf8(site["plots/tilted-hoop-tensor-vs-alpha.svg"].clone()).unwrap();
    assert!(sweep.contains("I_xy, I_yz stay zero"), "{sweep}");
    // Earth's Euler period from the exact solution, against REFERENCE.md's 304.456 sidereal
    // and 303.625 mean solar days.
    let earth = String::from_utf8(site["plots/earth-precession-polar-motion.svg"].clone()).unwrap();
    assert!(
        earth.contains("304.456 sidereal days = 303.625 mean solar days"),
        "{earth}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_failed_build_leaves_the_previous_site() {
    let (dir, out) = built_site("failed-build");
    let before = read_tree(&out);
    let templates = dir.join("templates");
    std::fs::create_dir_all(&templates).unwrap();
    std::fs::write(templates.join("page.html"), "{{ page.no_such_field }}").unwrap();
    let failed = mechbook(&[
        "build",
        "--out",
        out.to_str().unwrap(),
        "--templates",
        templates.to_str().unwrap(),
    ]);
    assert_eq!(failed.status.code(), Some(1), "{}", stderr(&failed));
    assert!(
        stderr(&failed).contains("template page.html"),
        "{}",
        stderr(&failed)
    );
    assert!(before == read_tree(&out), "the previous site changed");
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert_eq!(names.len(), 2, "leftover staging folders: {names:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn templates_override_file_by_file() {
    let dir = scratch("override");
    let templates = dir.join("templates");
    std::fs::create_dir_all(&templates).unwrap();
    std::fs::write(templates.join("style.css"), "body { color: teal; }\n").unwrap();
    let out = dir.join("site");
    let r = mechbook(&[
        "build",
        "--out",
        out.to_str().unwrap(),
        "--templates",
        templates.to_str().unwrap(),
    ]);
    assert_eq!(r.status.code(), Some(0), "{}", stderr(&r));
    assert_eq!(
        std::fs::read_to_string(out.join("style.css")).unwrap(),
        "body { color: teal; }\n"
    );
    assert!(
        std::fs::read_to_string(out.join("index.html"))
            .unwrap()
            .contains("Lecture 3&#x2F;4")
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A copy of the shipped lectures in `dir/lectures`, to edit.
fn copy_lectures(dir: &Path) -> PathBuf {
    let lectures = dir.join("lectures");
    for sub in ["lecture-3-4", "lecture-3-9"] {
        std::fs::create_dir_all(lectures.join(sub)).unwrap();
        for e in std::fs::read_dir(Path::new("lectures").join(sub)).unwrap() {
            let p = e.unwrap().path();
            std::fs::copy(&p, lectures.join(sub).join(p.file_name().unwrap())).unwrap();
        }
    }
    lectures
}

/// The cache: a second build reads every scene from it and writes the same bytes; after one
/// scene changes, only that scene runs again; a new fidelity reuses the symbolic results.
#[test]
fn the_cache_rebuilds_only_what_changed() {
    let dir = scratch("cache");
    let lectures = copy_lectures(&dir);
    let cache = dir.join("cache");
    let build = |out: &str, extra: &[&str]| {
        let out = dir.join(out);
        let mut args = vec![
            "build",
            lectures.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--cache",
            cache.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let r = mechbook(&args);
        assert_eq!(r.status.code(), Some(0), "{}", stderr(&r));
        (stderr(&r), read_tree(&out))
    };
    let (first, a) = build("a", &[]);
    assert!(
        first.contains("(0 from the cache, 0 re-run numerically"),
        "{first}"
    );
    let (second, b) = build("b", &[]);
    assert!(
        second.contains("(18 from the cache, 0 re-run numerically"),
        "{second}"
    );
    assert_eq!(a, b, "a site from the cache differs from a derived one");
    let fresh = dir.join("fresh");
    let r = mechbook(&[
        "build",
        lectures.to_str().unwrap(),
        "--out",
        fresh.to_str().unwrap(),
        "--no-cache",
    ]);
    assert_eq!(r.status.code(), Some(0), "{}", stderr(&r));
    assert_eq!(
        read_tree(&fresh),
        a,
        "--no-cache differs from the cached build"
    );

    // One scene changes (a comment): only it runs again, and the pages stay the same.
    let earth = lectures.join("lecture-3-9/05-earth.toml");
    let text = std::fs::read_to_string(&earth).unwrap();
    std::fs::write(&earth, format!("# edited\n{text}")).unwrap();
    let (third, c) = build("c", &[]);
    assert!(
        third.contains("(17 from the cache, 0 re-run numerically"),
        "{third}"
    );
    assert_eq!(a, c);

    // Two entries swapped, and a value edited inside a third: each is seen, reported and
    // derived again, and the pages are still the derived ones.
    let entry = |id: &str| {
        std::fs::read_dir(&cache)
            .unwrap()
            .map(|e| e.unwrap().path())
            .find(|p| {
                let n = p.file_name().unwrap().to_string_lossy().into_owned();
                n.starts_with(&format!("{id}.report."))
            })
            .unwrap_or_else(|| panic!("no report entry for {id}"))
    };
    let (cube, hoop, earth_entry) = (
        entry("cube-corner"),
        entry("hoop"),
        entry("earth-precession"),
    );
    let (x, y) = (std::fs::read(&cube).unwrap(), std::fs::read(&hoop).unwrap());
    std::fs::write(&cube, &y).unwrap();
    std::fs::write(&hoop, &x).unwrap();
    // One digit of the stored results changed (past the entry's first line).
    let mut e = std::fs::read(&earth_entry).unwrap();
    let body = e.iter().position(|&b| b == b'\n').unwrap() + 1;
    let at = body + e[body..].iter().position(u8::is_ascii_digit).unwrap();
    e[at] = if e[at] == b'7' { b'8' } else { b'7' };
    std::fs::write(&earth_entry, e).unwrap();
    let (mended, m) = build("m", &[]);
    assert_eq!(a, m, "a damaged entry reached the site");
    for id in ["cube-corner", "hoop", "earth-precession"] {
        assert!(
            mended.contains(&format!("{id}.report.")) && mended.contains("is damaged"),
            "{id}: {mended}"
        );
    }
    assert!(mended.contains("stored for another scene"), "{mended}");
    assert!(mended.contains("checksum"), "{mended}");
    assert!(
        mended.contains("(15 from the cache, 3 re-run numerically"),
        "{mended}"
    );
    let (again, _) = build("n", &[]);
    assert!(
        again.contains("(18 from the cache") && !again.contains("damaged"),
        "the damaged entries were not mended: {again}"
    );

    // Another fidelity: the symbolic results come from the cache, the numerics run again.
    let (draft, d) = build("d", &["--fidelity", "draft"]);
    assert!(
        draft.contains("(0 from the cache, 18 re-run numerically"),
        "{draft}"
    );
    let page = String::from_utf8(d["cube-centre.html"].clone()).unwrap();
    assert!(
        page.contains("Numeric fidelity: draft (target relative error 10⁻³"),
        "{page}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The renderers' memo (`render::memo`): after one scene's title changes, the pages, JSON,
/// sheets and markups the edit did not touch are taken from the cache, not made again; the
/// site is the one a build with no cache writes; a damaged unit, or another template, makes
/// the pages afresh.
#[test]
fn the_renderers_redo_only_what_an_edit_changed() {
    let dir = scratch("render-memo");
    let lectures = copy_lectures(&dir);
    let cache = dir.join("cache");
    // What a build said, and the site it wrote.
    let build_said = |out: &str, extra: &[&str]| {
        let out = dir.join(out);
        let mut args = vec!["build", lectures.to_str().unwrap(), "--out"];
        args.push(out.to_str().unwrap());
        args.extend_from_slice(extra);
        let r = mechbook(&args);
        assert_eq!(r.status.code(), Some(0), "{}", stderr(&r));
        (stderr(&r), read_tree(&out))
    };
    let build = |out: &str, extra: &[&str]| build_said(out, extra).1;
    let cached = ["--cache", cache.to_str().unwrap()];
    // Each kept unit's file, by name, with its bytes.
    let units = || -> BTreeMap<String, (String, Vec<u8>)> {
        std::fs::read_dir(&cache)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter_map(|p| {
                let file = p.file_name()?.to_string_lossy().into_owned();
                let (name, _) = file.split_once(".render.")?;
                Some((name.to_string(), (file.clone(), std::fs::read(&p).unwrap())))
            })
            .collect()
    };
    build("a", &cached);
    let before = units();
    for name in [
        "cube-corner.page",
        "cube-corner.json",
        "earth-precession.page",
        "pdf.lecture-3-4-student.pdf",
        "handouts.lecture-3-4-student.html",
        "handouts.lecture-3-9-instructor.html",
    ] {
        assert!(
            before.contains_key(name),
            "no unit {name}: {:?}",
            before.keys()
        );
    }
    assert!(
        before.keys().any(|k| k.starts_with("plots.")),
        "{:?}",
        before.keys()
    );

    let earth = lectures.join("lecture-3-9/05-earth.toml");
    let text = std::fs::read_to_string(&earth).unwrap();
    std::fs::write(&earth, text.replacen("title = \"", "title = \"Edited: ", 1)).unwrap();
    let edited = build("b", &cached);
    let after = units();
    let fresh = build("fresh", &["--no-cache"]);
    assert_eq!(
        edited, fresh,
        "a site from the memo differs from a fresh one"
    );
    let page = String::from_utf8(edited["earth-precession.html"].clone()).unwrap();
    assert!(
        page.contains("Edited: Earth"),
        "the edit is not on its page"
    );
    // The edited scene's units are new; the other lecture's are the same files, untouched.
    for name in [
        "earth-precession.page",
        "earth-precession.json",
        "pdf.lecture-3-9-student.pdf",
        "handouts.lecture-3-9-student.html",
        "handouts.lecture-3-9-instructor.html",
    ] {
        assert_ne!(
            before.get(name),
            after.get(name),
            "{name} was not made again"
        );
    }
    for name in [
        "cube-corner.page",
        "cube-corner.json",
        "pdf.lecture-3-4-student.pdf",
        "handouts.lecture-3-4-student.html",
        "handouts.lecture-3-4-instructor.html",
    ] {
        assert_eq!(before.get(name), after.get(name), "{name} was made again");
    }

    // One problem of a sheet edited: the sheets are made again, but of their problems' parts
    // only the edited problem's; the other problem's are recalled.
    let hoop = lectures.join("lecture-3-4/11-problem-tilted-hoop.toml");
    let text = std::fs::read_to_string(&hoop).unwrap();
    std::fs::write(&hoop, text.replacen("title = \"", "title = \"Edited: ", 1)).unwrap();
    let edited = build("e", &cached);
    let fresh = build("fresh-e", &["--no-cache"]);
    assert_eq!(
        edited, fresh,
        "a sheet from the memo differs from a fresh one"
    );
    let sheet =
        String::from_utf8(edited["handouts/lecture-3-4-problems-key.html"].clone()).unwrap();
    assert!(sheet.contains("Edited: "), "the edit is not on the key");
    let (before, after) = (after, units());
    for sheet in [
        "lecture-3-4-problems-student",
        "lecture-3-4-problems-key",
        "pdf.lecture-3-4-problems-student.pdf",
        "pdf.lecture-3-4-problems-key.pdf",
    ] {
        for (part, made_again) in [("", true), ("-2", true), ("-1", false)] {
            let name = match part {
                "" if !sheet.starts_with("pdf.") => format!("{sheet}.html"),
                _ => format!("{sheet}{part}"),
            };
            assert!(
                after.contains_key(&name),
                "no unit {name}: {:?}",
                after.keys()
            );
            assert_eq!(
                before.get(&name) != after.get(&name),
                made_again,
                "{name}: made again {}",
                !made_again
            );
        }
    }

    // A damaged unit is made again: the page is still the right one.
    let (file, bytes) = &after["cube-corner.page"];
    std::fs::write(cache.join(file), &bytes[..bytes.len() / 2]).unwrap();
    assert_eq!(
        build("c", &cached),
        fresh,
        "a damaged unit reached the site"
    );
    assert_eq!(
        &units()["cube-corner.page"].1,
        bytes,
        "the damaged unit was not mended"
    );

    // A page-first build (`--pdfs-later`, what `serve` runs on a save) writes no markup for
    // the edited lecture: its two handouts are left to the full build, which makes them.
    let text = std::fs::read_to_string(&earth).unwrap();
    std::fs::write(&earth, text.replacen("Edited: ", "Edited twice: ", 1)).unwrap();
    let before = units();
    let (said, _) = build_said("f", &["--cache", cache.to_str().unwrap(), "--pdfs-later"]);
    assert!(said.contains("(2 left to typeset next)"), "{said}");
    let after = units();
    assert_ne!(
        before.get("earth-precession.page"),
        after.get("earth-precession.page")
    );
    for name in [
        "pdf.lecture-3-9-student.pdf",
        "pdf.lecture-3-9-instructor.pdf",
    ] {
        assert_eq!(
            before.get(name),
            after.get(name),
            "{name} was written page-first"
        );
    }
    let full = build("g", &cached);
    assert_ne!(
        after.get("pdf.lecture-3-9-student.pdf"),
        units().get("pdf.lecture-3-9-student.pdf"),
        "the full build did not write the markup"
    );
    assert_eq!(full, build("fresh-g", &["--no-cache"]));

    // Another page template: every page is made with it, none recalled from the memo.
    let templates = dir.join("templates");
    std::fs::create_dir_all(&templates).unwrap();
    let page = include_str!("../../templates/page.html").replacen("<body", "<body data-t=\"1\"", 1);
    std::fs::write(templates.join("page.html"), page).unwrap();
    let mut args = cached.to_vec();
    args.extend(["--templates", templates.to_str().unwrap()]);
    let themed = build("d", &args);
    for (file, bytes) in &themed {
        if file.ends_with(".html") && !file.contains('/') && file != "index.html" {
            let text = String::from_utf8_lossy(bytes);
            assert!(
                text.contains("data-t=\"1\""),
                "{file} was recalled from the memo"
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
