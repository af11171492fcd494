//! insta snapshots of the main content of a few pages, and of tests/course's documents of every
//! kind (a student's handout, a problem sheet, its key, a Moodle quiz, a scene's JSON, a QTI 2.1
//! item, a Canvas quiz, a Blackboard upload): a change
//! in a derivation, its MathML, a verdict or a plot's description shows up as a reviewable diff
//! (`cargo insta review`). The PDFs' Typst markup has its own snapshot beside the renderer
//! (`src/render/pdf/tests.rs`).

use super::{mechbook, scratch, stderr};

/// The `<main>` element, one block element per line so that diffs stay readable.
fn main_content(html: &str) -> String {
    let start = html.find("<main>").expect("<main>");
    let end = html.find("</main>").expect("</main>") + "</main>".len();
    let mut out = String::new();
    for part in html[start..end].split_inclusive('\n') {
        out.push_str(
            &part
                .replace("<li>", "\n<li>")
                .replace("<h3>", "\n<h3>")
                .replace("<tr>", "\n<tr>"),
        );
    }
    out
}

#[test]
fn main_content_of_key_pages() {
    let dir = scratch("snapshots");
    let out = dir.join("site");
    let r = mechbook(&["build", "--out", out.to_str().unwrap()]);
    assert_eq!(r.status.code(), Some(0), "{}", stderr(&r));
    for page in ["cube-corner", "tilted-hoop", "parallel-axis"] {
        let html = std::fs::read_to_string(out.join(format!("{page}.html"))).unwrap();
        insta::assert_snapshot!(page, main_content(&html));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// tests/course's documents of each kind, from one build.
#[test]
fn every_kind_of_document_of_the_course() {
    let dir = scratch("snapshots-course");
    let out = dir.join("site");
    let r = mechbook(&["build", "tests/course", "--out", out.to_str().unwrap()]);
    assert_eq!(r.status.code(), Some(0), "{}", stderr(&r));
    let read = |path: &str| std::fs::read_to_string(out.join(path)).unwrap();
    for (name, path) in [
        (
            "handout",
            "handouts/lecture-Bodies-of-revolution-student.html",
        ),
        (
            "sheet",
            "handouts/lecture-Composite-bodies-problems-student.html",
        ),
        ("key", "handouts/lecture-Composite-bodies-problems-key.html"),
    ] {
        insta::assert_snapshot!(name, main_content(&read(path)));
    }
    insta::assert_snapshot!("moodle", read("export/moodle/problem-centre-of-mass.xml"));
    let json: serde_json::Value = serde_json::from_str(&read("export/json/l-plate.json")).unwrap();
    insta::assert_snapshot!("json", serde_json::to_string_pretty(&json).unwrap());
    // The other LMSs': a QTI 2.1 item, Canvas's assessment and Blackboard's upload.
    let unzip = |path: &str| super::lms::unzip(&std::fs::read(out.join(path)).unwrap());
    let qti = unzip("export/qti21/lecture-Composite-bodies.zip");
    insta::assert_snapshot!("qti21", qti["items/item-problem-centre-of-mass-1-v1.xml"]);
    let canvas = unzip("export/canvas/lecture-Composite-bodies.zip");
    insta::assert_snapshot!(
        "canvas",
        canvas["lecture-Composite-bodies/lecture-Composite-bodies.xml"]
    );
    insta::assert_snapshot!(
        "blackboard",
        read("export/blackboard/lecture-Composite-bodies.txt")
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
