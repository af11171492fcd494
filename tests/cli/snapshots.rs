//! insta snapshots of the main content of a few pages: a change in a derivation, its MathML, a
//! verdict or a plot's description shows up as a reviewable diff (`cargo insta review`).

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
