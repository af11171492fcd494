//! The handouts a lecture prints: the student's marks the notes' mistakes and errata, leaves
//! the problems to the sheet, and every page prints on the course's paper.

use super::{mechbook, scratch, stderr};
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
        student.contains("A common mistake, not the notes' claim"),
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
        "[[step]]\nname = \"proj\"\nbe = \"m*cos(pi/2) + m*sin(pi/6) + m*cos(5*pi/12)\"\n\
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
    let step = &page[page.find("<strong>proj</strong>").expect("the step")..];
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
