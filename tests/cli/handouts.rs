//! The handouts a lecture prints: the student's marks the notes' mistakes and errata, leaves
//! the problems to the sheet, and every page prints on the course's paper.

use super::{mechbook, scratch, stderr, toml_files};
use std::path::Path;

fn read(site: &Path, file: &str) -> String {
    std::fs::read_to_string(site.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"))
}

#[test]
fn the_student_handout_marks_mistakes_and_errata_and_leaves_problems_to_the_sheet() {
    let dir = scratch("handouts-marked");
    let site = dir.join("site");
    let built = mechbook(&["build", "lectures", "--out", site.to_str().unwrap()]);
    assert_eq!(built.status.code(), Some(0), "{}", stderr(&built));
    let student = read(&site, "handouts/lecture-3-4-student.html");
    let instructor = read(&site, "handouts/lecture-3-4-instructor.html");
    // Eq (4) is an erratum of the notes: marked, with the correct form; never listed as a claim.
    assert!(
        student.contains("Erratum: eq. (4) of the notes is wrong"),
        "{student}"
    );
    assert!(
        !student.contains("<li>(4) "),
        "an erratum listed as the notes' claim"
    );
    assert!(student.matches("<dd>Correct: ").count() >= 4);
    // An agreeing claim is listed as it is.
    assert!(student.contains("<li>(3) "));
    // The problems are on the sheet, not in the summary; the instructor keeps them.
    assert!(!student.contains("A box about its centre"));
    assert!(instructor.contains("A box about its centre"));
    assert!(student.contains("summary</h1>"));
    // A4 unless the course says otherwise, on every page that prints.
    for file in [
        "handouts/lecture-3-4-student.html",
        "handouts/lecture-3-4-problems-student.html",
        "handouts/lecture-3-4-problems-key.html",
        "cube-corner.html",
        "index.html",
    ] {
        assert!(read(&site, file).contains("@page { size: a4; }"), "{file}");
    }
    // The instructor's opens with its contents, a link to each scene's section.
    let contents = instructor.split("</nav>").next().unwrap();
    assert!(contents.contains("<h2>Contents</h2>"));
    assert!(
        contents.contains("<a href=\"#cube-corner\">") && instructor.contains("id=\"cube-corner\"")
    );
    // The index lists each lecture's derivations, then its problems under their own heading.
    let index = read(&site, "index.html");
    let lecture = index.split("<h2>Lecture 3&#x2F;9").next().unwrap();
    let problems = lecture
        .find("<h3>Problems</h3>")
        .expect("a Problems heading");
    assert!(lecture.find("A box about its centre").unwrap() > problems);
    assert!(lecture.find("Homogeneous cube about a corner").unwrap() < problems);
    // A scene's abbreviations are in its setup: the hoop's line density.
    let hoop = read(&site, "hoop.html");
    assert!(
        hoop.contains("<p class=\"definitions\">Abbreviations: <math"),
        "{hoop}"
    );
    let sheet = read(&site, "handouts/lecture-3-4-problems-student.html");
    assert!(
        sheet.contains("<p class=\"name-line\">Name <span></span> Student ID <span></span></p>")
    );

    // A course of its own: a deliberate mistake is marked as one, and `paper = "letter"`.
    let course = dir.join("course");
    std::fs::create_dir_all(&course).unwrap();
    std::fs::copy(
        "tests/course/bodies/03-cone.toml",
        course.join("03-cone.toml"),
    )
    .unwrap();
    std::fs::write(
        course.join("mechbook.toml"),
        "title = \"Cones\"\npaper = \"letter\"\n",
    )
    .unwrap();
    let out = dir.join("out");
    let built = mechbook(&[
        "build",
        course.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(built.status.code(), Some(0), "{}", stderr(&built));
    let student = read(&out, "handouts/lecture-Bodies-of-revolution-student.html");
    assert!(
        student.contains("A common mistake, not the notes&#x27; claim"),
        "{student}"
    );
    assert!(student.contains("@page { size: letter; }"));
    // An unknown paper is an error at its line.
    std::fs::write(
        course.join("mechbook.toml"),
        "title = \"Cones\"\npaper = \"a5\"\n",
    )
    .unwrap();
    let refused = mechbook(&[
        "build",
        course.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(refused.status.code(), Some(1));
    assert!(
        stderr(&refused).contains("mechbook.toml:2:"),
        "{}",
        stderr(&refused)
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_step_at_a_multiple_of_pi_over_twelve_is_worked_out_exactly() {
    let dir = scratch("handouts-special-angles");
    let course = dir.join("course");
    let made = mechbook(&["init", course.to_str().unwrap()]);
    assert_eq!(made.status.code(), Some(0), "{}", stderr(&made));
    let scene = course.join("lectures/lecture-1/01-book.toml");
    let text = std::fs::read_to_string(&scene).unwrap().replace(
        "[outputs]",
        "[[step]]\nname = \"proj\"\ntex = \"p\"\nbe = \"m*cos(pi/2) + m*sin(pi/6) + m*cos(5*pi/12)\"\n\
         why = \"exact values\"\n\n[outputs]",
    );
    std::fs::write(&scene, text).unwrap();
    let site = dir.join("site");
    let built = mechbook(&[
        "build",
        course.to_str().unwrap(),
        "--out",
        site.to_str().unwrap(),
    ]);
    assert_eq!(built.status.code(), Some(0), "{}", stderr(&built));
    let page = read(&site, "book.html");
    let step = &page[page
        .find("<strong><math display=\"inline\" alttext=\"p\">")
        .expect("the step")..];
    let step = &step[..step.find("</li>").unwrap()];
    // m/2 + m(√6 − √2)/4: no sine or cosine is left.
    assert!(
        !step.contains("<mi>cos</mi>") && !step.contains("<mi>sin</mi>"),
        "{step}"
    );
    assert!(
        step.contains("<msqrt><mrow><mn>6</mn></mrow></msqrt>"),
        "{step}"
    );
}

/// The text a reader sees in a page: its MathML, style and tags left out, entities read.
fn visible_text(html: &str) -> String {
    let mut out = String::new();
    let mut rest = html;
    while let Some(start) = rest.find('<') {
        out.push_str(&rest[..start]);
        rest = &rest[start..];
        let skip_to = ["<math", "<style", "<title"]
            .iter()
            .zip(["</math>", "</style>", "</title>"])
            .find(|(open, _)| rest.starts_with(**open))
            .map(|(_, close)| close);
        let end = match skip_to {
            Some(close) => rest.find(close).map(|e| e + close.len()),
            None => rest.find('>').map(|e| e + 1),
        }
        .unwrap_or(rest.len());
        out.push(' ');
        rest = &rest[end..];
    }
    out.push_str(rest);
    out.replace("&#x27;", "'")
        .replace("&#x2F;", "/")
        .replace("&amp;", "&")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
}

/// ASCII mathematics a reader would see as such: a backtick, a power, `sqrt(`, a Greek
/// letter's name, a name with `_`, a `*` between two operands; and mathematics written in
/// Unicode text, untypeset: a Greek letter, a superscript, a letter and a digit (`I3`).
fn ascii_maths(text: &str) -> Vec<String> {
    const GREEK: &[&str] = &[
        "alpha", "beta", "gamma", "delta", "epsilon", "eps", "theta", "lambda", "rho", "sigma",
        "tau", "phi", "psi", "omega", "Omega", "Theta", "Phi", "Psi",
    ];
    let mut found = Vec::new();
    for word in text.split_whitespace() {
        let bare = word.trim_matches(|c: char| ",.;:()[]".contains(c));
        let letters = |s: &str| !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric());
        // A backslash is LaTeX that was not read.
        let suspicious = word.contains('`')
            || word.contains('\\')
            || word.contains('^')
            || word.contains("sqrt(")
            || GREEK.contains(&bare.trim_end_matches(|c: char| c.is_ascii_digit()))
            || bare
                .split_once('_')
                .is_some_and(|(a, b)| letters(a) && letters(b))
            || bare
                .split_once('*')
                .is_some_and(|(a, b)| letters(a) && letters(b))
            // Mathematics in Unicode text is not typeset either: ω1, βω3, L², I3; a unit (m/s²),
            // a number (4.1×10⁻¹⁶) and a paper size (A4) are text.
            || word.chars().any(|c| ('\u{0391}'..='\u{03c9}').contains(&c))
            || (bare.chars().any(|c| "²³".contains(c))
                && !is_unit(bare)
                && !bare.starts_with(|c: char| c.is_ascii_digit()))
            || {
                let b = bare.as_bytes();
                b.len() == 2
                    && b[0].is_ascii_alphabetic()
                    && b[1].is_ascii_digit()
                    && !["A4", "A5"].contains(&bare)
            };
        if suspicious {
            found.push(word.to_string());
        }
    }
    found
}

/// A unit as the pages print it: kg m², m/s², each piece a unit's symbol and its power.
fn is_unit(word: &str) -> bool {
    word.split('/')
        .all(|u| ["kg", "m", "s", "N", "J", "rad"].contains(&u.trim_end_matches(['²', '³'])))
}

#[test]
fn the_ascii_check_of_a_handout_finds_what_a_reader_would_see() {
    let html =
        "<p>step `Ip` gives 1/2*Mp*R^2, <math><mi>ω</mi></math> at omega, I_xx and p_phi</p>";
    assert_eq!(
        ascii_maths(&visible_text(html)),
        ["`Ip`", "1/2*Mp*R^2,", "omega,", "I_xx", "p_phi"]
    );
    let unicode = "<p>so ω3 is constant, βω3, L², and I3 &gt; I1 (in kg m² and m/s², A4)</p>";
    assert_eq!(
        ascii_maths(&visible_text(unicode)),
        ["ω3", "βω3,", "L²,", "I3", "I1"]
    );
    let clean = "<p>(6.4) The rod&#x27;s moment <math><msup><mi>r</mi><mn>2</mn></msup></math>, a step.</p>";
    assert!(ascii_maths(&visible_text(clean)).is_empty());
}

/// Each student summary of a scene with steps shows them in the scene's order, each under the
/// author's reason, with its equations of motion as equations; its headings are the author's
/// words, never a step's name; no student handout shows a backtick or ASCII mathematics.
#[test]
fn the_student_summary_teaches_each_derivation_in_the_authors_order() {
    let dir = scratch("handouts-teach");
    for source in ["tests/course", "lectures"] {
        let site = dir.join(source.replace('/', "-"));
        let built = mechbook(&["build", source, "--out", site.to_str().unwrap()]);
        assert_eq!(built.status.code(), Some(0), "{}", stderr(&built));
        let mut students = Vec::new();
        for entry in std::fs::read_dir(site.join("handouts")).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if name.ends_with("-student.html") {
                let html = std::fs::read_to_string(&path).unwrap();
                let ascii = ascii_maths(&visible_text(&html));
                assert!(ascii.is_empty(), "{source}: {name} shows {ascii:?}");
                students.push((name, html));
            }
        }
        assert!(students.len() >= 4, "{source}: {}", students.len());
        let mut scenes_with_steps = 0;
        let folders = std::fs::read_dir(source)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.is_dir());
        let files = folders.flat_map(|d| toml_files(&d));
        for file in files {
            let scene: toml::Table = toml::from_str(&std::fs::read_to_string(&file).unwrap())
                .unwrap_or_else(|e| panic!("{}: {e}", file.display()));
            let Some(steps) = scene.get("step").and_then(|s| s.as_array()) else {
                continue;
            };
            if scene.contains_key("problem") {
                continue;
            }
            scenes_with_steps += 1;
            let id = scene["id"].as_str().unwrap();
            let anchor = format!("<section class=\"problem\" id=\"{id}\">");
            let (_, html) = students
                .iter()
                .find(|(_, h)| h.contains(&anchor))
                .unwrap_or_else(|| panic!("{id}: in no student handout"));
            let section = html.split(&anchor).nth(1).unwrap();
            let section = section.split("</section>").next().unwrap();
            let shown = visible_text(section);
            // Each reason's first words, in the scene's order.
            let mut at = 0;
            for step in steps {
                let name = step["name"].as_str().unwrap();
                let why = step.get("why").and_then(|w| w.as_str()).unwrap_or_default();
                let words: String = why
                    .split('$')
                    .step_by(2)
                    .find(|t| t.trim().len() > 3)
                    .map(|t| t.trim().chars().skip(1).take(24).collect())
                    .unwrap_or_default();
                if !words.is_empty() {
                    let found = shown[at..].find(words.trim()).unwrap_or_else(|| {
                        panic!(
                            "{id}: step `{name}`'s reason `{words}` is not after the step before"
                        )
                    });
                    at += found;
                }
                // No heading is a step's name.
                for h in ["<h2>", "<h3>"] {
                    assert!(
                        !section.contains(&format!("{h}{name}<")),
                        "{id}: a heading is the step name `{name}`"
                    );
                }
            }
            // An equation of motion is shown as one: `… = 0`.
            if steps.iter().any(|s| s.get("lagrange").is_some()) {
                assert!(
                    section.contains("<mo>=</mo><mn>0</mn>"),
                    "{id}: no equation of motion"
                );
            }
        }
        assert!(
            source == "lectures" || scenes_with_steps >= 8,
            "{source}: {scenes_with_steps}"
        );
    }
}

/// An inertia scene summarised for students: the tensor, centre of mass and principal moments
/// once, none of the body's integrals, no characteristic polynomial that does not factor, no
/// numeric check; the instructor's handout keeps them all. The starter's book alone prints on
/// one A4 page.
#[test]
fn an_inertia_scene_is_summarised_for_students_on_one_page() {
    let dir = scratch("inertia-summary");
    assert!(super::mechbook_in(&dir, &["init"]).status.success());
    std::fs::remove_file(dir.join("lectures/lecture-1/02-problem-box.toml")).unwrap();
    let r = super::mechbook_in(&dir, &["build", "--no-cache"]);
    assert!(r.status.success(), "{}", stderr(&r));
    let site = dir.join("site");
    let student = read(&site, "handouts/lecture-1-student.html");
    let instructor = read(&site, "handouts/lecture-1-instructor.html");
    for working in [
        "position of a mass element",
        "mass element",
        "total mass",
        "Irreducible factor",
        "eigen-solver",
        "Principal moments at the scene",
    ] {
        assert!(!student.contains(working), "the student's has {working}");
        assert!(
            instructor.contains(working),
            "the instructor's lacks {working}"
        );
    }
    for shown in [
        "The inertia tensor",
        "Centre of mass",
        "Principal moments in closed form",
    ] {
        assert_eq!(student.matches(shown).count(), 1, "{shown}");
    }
    assert!(!student.contains(">?<"), "a question mark typeset");
    let pdf = site.join("pdf/lecture-1-student.pdf");
    match std::process::Command::new("pdfinfo").arg(&pdf).output() {
        Ok(out) => {
            let info = String::from_utf8_lossy(&out.stdout).into_owned();
            let pages = info
                .lines()
                .find_map(|l| l.strip_prefix("Pages:"))
                .map(|n| n.trim().to_string());
            assert_eq!(pages.as_deref(), Some("1"), "{info}");
        }
        Err(_) => assert!(
            std::env::var_os("CI").is_none(),
            "CI needs poppler-utils (pdfinfo)"
        ),
    }
}
