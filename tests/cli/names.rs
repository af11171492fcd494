//! Under a name the author chose: no name of mechbook's or of a scene file
//! (`plane_distance_squared`, a step `Lag`) is typeset on a page, spoken by a screen reader, or
//! heads a step, on the three sites mechbook ships; and `check` warns at its line on a step
//! whose result would print as a word, or as another's symbol.

use super::{mechbook, mechbook_in, scratch, stderr};
use std::path::Path;

/// Every HTML file under `dir`.
fn pages(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            pages(&path, out);
        } else if path.extension().is_some_and(|e| e == "html") {
            out.push(path);
        }
    }
}

/// The `<math>` elements of a page: each its start tag's alttext and its body.
fn formulas(page: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut rest = page;
    while let Some(start) = rest.find("<math") {
        let Some(end) = rest[start..].find("</math>") else {
            break;
        };
        let element = &rest[start..start + end];
        let tag_end = element.find('>').unwrap();
        let alt = element[..tag_end]
            .split("alttext=\"")
            .nth(1)
            .and_then(|a| a.split('"').next())
            .unwrap_or("")
            .to_string();
        out.push((alt, element[tag_end..].to_string()));
        rest = &rest[start + end..];
    }
    out
}

/// The identifiers of a formula, one after another (`<mi>` and `<mtext>` contents).
fn identifiers(body: &str) -> String {
    let mut out = String::new();
    for tag in ["<mi", "<mtext"] {
        for piece in body.split(tag).skip(1) {
            if let Some(text) = piece.split_once('>').map(|(_, t)| t) {
                out.push_str(text.split('<').next().unwrap_or(""));
                out.push(' ');
            }
        }
    }
    out
}

/// A name spelled with an underscore (`bulge_km`, `w_min`), or spelled out letter by letter
/// round one in a spoken form ("p r e c e s s i o n _ r a t e"). (Single letters in a row alone
/// are no sign: "d x d y d z" is an integral's.)
fn internal_name(text: &str) -> Option<String> {
    let words: Vec<&str> = text.split_whitespace().collect();
    if let Some(w) = words.iter().find(|w| {
        let w = w.trim_matches(|c: char| !c.is_alphanumeric() && c != '_');
        w.contains('_') && w.split('_').all(|p| !p.is_empty())
    }) {
        return Some(w.to_string());
    }
    let letter = |x: &str| x.len() == 1 && x.chars().all(|c| c.is_ascii_alphabetic());
    words
        .windows(3)
        .find(|w| letter(w[0]) && w[1] == "_" && letter(w[2]))
        .map(|w| w.join(" "))
}

/// A step's name set as a word of its own (`<mtext>Lfree</mtext>`): a name no English word
/// could be (a capital, a digit or an underscore in it; `slow` may be a subscript's word).
fn step_name_as_word(body: &str, steps: &[String]) -> Option<String> {
    let coined = |n: &str| !n.chars().all(|c| c.is_ascii_lowercase());
    body.split("<mtext>")
        .skip(1)
        .filter_map(|t| t.split('<').next())
        .find(|t| t.chars().count() > 1 && coined(t) && steps.iter().any(|n| n == t))
        .map(str::to_string)
}

/// The step names of a course's scene files (`name = "…"` under a `[[step]]`).
fn step_names(dir: &Path, out: &mut Vec<String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            step_names(&path, out);
        } else if path.extension().is_some_and(|e| e == "toml") {
            let text = std::fs::read_to_string(&path).unwrap();
            for block in text.split("[[step]]").skip(1) {
                if let Some(name) = block
                    .lines()
                    .find_map(|l| l.trim().strip_prefix("name = \""))
                    .and_then(|l| l.split('"').next())
                {
                    out.push(name.to_string());
                }
            }
        }
    }
}

/// The text of each step heading (`<li><strong>…</strong>`), its mathematics left out.
fn step_headings(page: &str) -> Vec<String> {
    page.split("<li><strong>")
        .skip(1)
        .filter_map(|h| h.split("</strong>").next())
        .map(|h| {
            let mut text = String::new();
            let mut rest = h;
            while let Some(start) = rest.find("<math") {
                text.push_str(&rest[..start]);
                rest = rest[start..].split_once("</math>").map_or("", |(_, r)| r);
            }
            text.push_str(rest);
            text
        })
        .collect()
}

/// What a built site shows that it should not: formulas setting a name, and step headings
/// opening with a step's name.
fn findings(site: &Path, steps: &[String]) -> Vec<String> {
    let mut files = Vec::new();
    pages(site, &mut files);
    assert!(!files.is_empty(), "{} has pages", site.display());
    let mut found = Vec::new();
    for file in files {
        let page = std::fs::read_to_string(&file).unwrap();
        let at = file.strip_prefix(site).unwrap().display().to_string();
        for (alt, body) in formulas(&page) {
            let named = [identifiers(&body), alt.clone()]
                .iter()
                .find_map(|text| internal_name(text))
                .or_else(|| step_name_as_word(&body, steps));
            if let Some(name) = named {
                found.push(format!("{at}: formula `{alt}` sets `{name}`"));
            }
        }
        for heading in step_headings(&page) {
            let opens = |n: &String| {
                n.chars().count() > 1
                    && heading
                        .strip_prefix(n.as_str())
                        .is_some_and(|r| r.is_empty() || r.starts_with(':') || r.starts_with(" ("))
            };
            if let Some(name) = steps.iter().find(|n| opens(n)) {
                found.push(format!("{at}: step heading `{heading}` shows `{name}`"));
            }
        }
    }
    found
}

/// The shipped lectures, tests/course and a new course from `init`: no formula sets an
/// internal name or speaks one letter by letter, no step is headed by its name, and building
/// them warns of no step's name.
#[test]
fn no_internal_name_is_typeset_spoken_or_a_heading_on_the_three_sites() {
    let dir = scratch("names-three-sites");
    let starter = dir.join("starter");
    assert!(
        mechbook(&["init", starter.to_str().unwrap()])
            .status
            .success()
    );
    let root = std::env::current_dir().unwrap();
    // tests/course is its scenes' folder, which `build .` takes.
    let sites = [
        (root.clone(), root.join("lectures"), None),
        (
            root.join("tests/course"),
            root.join("tests/course"),
            Some("."),
        ),
        (starter.clone(), starter.clone(), None),
    ];
    for (k, (course, scenes, folder)) in sites.iter().enumerate() {
        let out_dir = dir.join(format!("site-{k}"));
        let mut args = vec!["build"];
        args.extend(folder);
        args.extend(["--no-cache", "--out", out_dir.to_str().unwrap()]);
        let out = mechbook_in(course, &args);
        let err = stderr(&out);
        assert!(out.status.success(), "{}: {err}", course.display());
        assert!(
            !err.contains("has no `tex`") && !err.contains("a reader cannot tell"),
            "{}: {err}",
            course.display()
        );
        let mut steps = Vec::new();
        step_names(scenes, &mut steps);
        let found = findings(&out_dir, &steps);
        assert!(
            found.is_empty(),
            "{}:\n{}",
            course.display(),
            found.join("\n")
        );
    }
}

/// The test's own finder, on what the sites once printed: it can fail.
#[test]
fn the_finder_catches_the_names_the_sites_once_printed() {
    let spelled = "o s c i l l a t i o n _ f r e q u e n c y _ s q u a r e d sub 2";
    assert!(internal_name(spelled).is_some());
    assert!(internal_name("bulge_km equals 30").is_some());
    assert!(internal_name("w _ m i n 2").is_some());
    assert!(internal_name("I sub 1 omega sub 1 squared plus I sub 2").is_none());
    assert!(internal_name("d x d y d z").is_none());
    let steps = ["Lfree".to_string(), "E".to_string()];
    let set = "<mi>T</mi><mo>=</mo><mtext>Lfree</mtext>";
    assert_eq!(step_name_as_word(set, &steps).as_deref(), Some("Lfree"));
    assert_eq!(step_name_as_word("<mtext>kg</mtext>", &steps), None);
    let slow = ["slow".to_string()];
    assert_eq!(step_name_as_word("<mtext>slow</mtext>", &slow), None);
    assert!(internal_name("omega sub body").is_none());
    let headings = step_headings(
        "<li><strong>Lag</strong> <li><strong>acc: acc_1, the value of <math>x</math></strong>",
    );
    assert_eq!(headings, ["Lag", "acc: acc_1, the value of "]);
}

/// A step whose result prints under a word (`period`), and one whose `tex` is a symbol's
/// (`L`, the rod's length): `check` warns of each at its line, with the `tex` to write.
#[test]
fn check_warns_at_its_line_of_a_step_printed_as_a_word_or_as_another_symbol() {
    let dir = scratch("names-warn");
    std::fs::create_dir_all(dir.join("scenes")).unwrap();
    std::fs::write(
        dir.join("scenes/rod.toml"),
        r#"id = "rod"
title = "A rod on a pivot"
notes = { lecture = "1" }
symbols = { M = "mass", L = "length", g = "gravity" }

[coordinates]
phi = { meaning = "angle from the downward vertical", unit = "rad" }

[outputs]
want = []

[[step]]
name = "Lag"
tex = "L"
be = "M*L^2/6*phi'^2 + M*g*L/2*cos(phi)"
why = "the Lagrangian"

[[step]]
name = "slow_rate"
be = "sqrt(3*g/(2*L))"
why = "the small oscillations' frequency"

[numeric]
values = { M = 2.0, L = 1.5, g = 9.81 }
"#,
    )
    .unwrap();
    let out = mechbook_in(&dir, &["check", "scenes/rod.toml"]);
    let err = stderr(&out);
    assert!(
        err.contains("rod.toml:13:9")
            && err.contains("step `Lag` prints as `L`, as the symbol `L`"),
        "{err}"
    );
    assert!(
        err.contains("rod.toml:19:9")
            && err.contains("step `slow_rate` has no `tex`")
            && err.contains(r#"tex = "s_{\\mathrm{rate}}""#),
        "{err}"
    );
    // Given their symbols, the scene checks without a warning of either.
    let text = std::fs::read_to_string(dir.join("scenes/rod.toml")).unwrap();
    let fixed = text
        .replace("tex = \"L\"", "tex = \"\\\\mathcal{L}\"")
        .replace(
            "name = \"slow_rate\"\n",
            "name = \"slow_rate\"\ntex = \"\\\\Omega\"\n",
        );
    std::fs::write(dir.join("scenes/rod.toml"), fixed).unwrap();
    let out = mechbook_in(&dir, &["check", "scenes/rod.toml"]);
    let err = stderr(&out);
    assert!(
        !err.contains("has no `tex`") && !err.contains("prints as"),
        "{err}"
    );
}

/// `derive --json` (and the site's JSON export) prints each name as the scene typesets it, as
/// the page does: the puck's Lagrangian `Lag` (`tex = "L"`) is L, its momentum `p`
/// (`tex = "p_\phi"`) is p_φ. The export used to ignore the scene's `tex` (\mathrm{Lag}).
#[test]
fn the_json_report_prints_the_scenes_own_names() {
    let r = mechbook(&[
        "derive",
        "tests/course/dynamics/17-puck-and-hanging-mass.toml",
        "--json",
    ]);
    assert_eq!(r.status.code(), Some(0), "{}", stderr(&r));
    let text = super::stdout(&r);
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let latex: Vec<String> = json["steps"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|s| s["latex"].as_str().map(str::to_string))
        .collect();
    assert!(
        latex.iter().any(|l| l.starts_with("L = ")),
        "no step states L = …: {latex:#?}"
    );
    assert!(latex.iter().any(|l| l.contains("p_\\phi")), "{latex:#?}");
    assert!(!text.contains("\\mathrm{Lag}"), "a name printed as a word");
}
