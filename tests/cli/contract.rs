//! The error contract for a course's own files and its CI: the JSON report in a file, the
//! course file found above the scenes, its lectures and `base_url` checked, names that differ
//! only in case, and a plot's error at the plot.

use super::{mechbook, read_tree, scratch, stderr, stdout};
use std::path::{Path, PathBuf};

/// A course made by `init` in a scratch folder: (the folder, the course).
fn course(name: &str) -> (PathBuf, PathBuf) {
    let dir = scratch(name);
    let course = dir.join("course");
    let out = mechbook(&["init", course.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    (dir, course)
}

fn arg(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn check_writes_its_json_report_to_a_file_with_a_verdict_and_counts() {
    let (dir, course) = course("json-file");
    let lectures = course.join("lectures");
    let report = dir.join("report.json");
    let out = mechbook(&["check", arg(&lectures), "--json-file", arg(&report)]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    // The table still goes to standard output; the file holds the JSON alone.
    assert!(stdout(&out).contains("all as recorded"), "{}", stdout(&out));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&report).unwrap()).expect("the file is JSON");
    assert_eq!(json["passed"], true);
    assert_eq!(json["counts"]["scenes"], 2);
    assert_eq!(json["counts"]["scenes_passed"], 2);
    assert_eq!(json["counts"]["claims"], 2);
    assert_eq!(json["counts"]["disagree"], 1);
    assert_eq!(json["failures"].as_array().unwrap().len(), 0);
    assert_eq!(json["scenes"].as_array().unwrap().len(), 2);

    // A recorded verdict spoiled: the file says so, with the located failure.
    let scene = lectures.join("lecture-1/01-book.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    std::fs::write(
        &scene,
        text.replacen("expect = \"agrees\"", "expect = \"disagrees\"", 1),
    )
    .unwrap();
    let out = mechbook(&["check", arg(&lectures), "--json-file", arg(&report)]);
    assert_eq!(out.status.code(), Some(1));
    let json: serde_json::Value = serde_json::from_slice(&std::fs::read(&report).unwrap()).unwrap();
    assert_eq!(json["passed"], false);
    assert_eq!(json["counts"]["scenes_failed"], 1);
    let failure = json["failures"][0].as_str().unwrap();
    assert!(
        failure.contains("01-book.toml:")
            && failure.contains("verdict agrees but the scene records disagrees"),
        "{failure}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_course_file_is_found_above_the_scenes_and_its_lectures_are_checked() {
    let (dir, course) = course("course-file");
    // Built from outside the course: the course's own title, not another's.
    let out_dir = dir.join("site");
    let out = mechbook(&[
        "build",
        arg(&course.join("lectures")),
        "--out",
        arg(&out_dir),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let index = String::from_utf8(read_tree(&out_dir)["index.html"].clone()).unwrap();
    assert!(index.contains("My rigid-body course"), "{index}");

    let file = course.join("mechbook.toml");
    let text = std::fs::read_to_string(&file).unwrap();
    let build_course = || {
        let out = mechbook(&["build", arg(&course), "--out", arg(&out_dir)]);
        (out.status.code(), stderr(&out))
    };
    // A lecture titled twice.
    std::fs::write(
        &file,
        format!("{text}\n[[lecture]]\nid = \"1\"\ntitle = \"Again\"\n"),
    )
    .unwrap();
    let (code, err) = build_course();
    assert_eq!(code, Some(1));
    assert!(
        err.contains("mechbook.toml:11:7: field `lecture[1].id`: lecture `1` is titled twice"),
        "{err}"
    );
    // A lecture no scene has.
    std::fs::write(
        &file,
        format!("{text}\n[[lecture]]\nid = \"2\"\ntitle = \"Week 2\"\n"),
    )
    .unwrap();
    let (code, err) = build_course();
    assert_eq!(code, Some(1));
    assert!(
        err.contains("mechbook.toml:11:7: field `lecture[1].id`: no scene is in lecture `2`"),
        "{err}"
    );
    // TeX in a title that TOML read as an escape.
    std::fs::write(
        &file,
        text.replace("My rigid-body course", "Tops and \\beta decay"),
    )
    .unwrap();
    let (code, err) = build_course();
    assert_eq!(code, Some(1));
    assert!(
        err.contains("field `title`: `\\beta` was read as a backspace"),
        "{err}"
    );
    // base_url must be a web address; given, every Moodle question links its worked solution.
    std::fs::write(&file, format!("base_url = \"course.example\"\n{text}")).unwrap();
    let (code, err) = build_course();
    assert_eq!(code, Some(1));
    assert!(
        err.contains("mechbook.toml:1:13: field `base_url`: `course.example` is not a web address"),
        "{err}"
    );
    std::fs::write(
        &file,
        format!("base_url = \"https://course.example/mech/\"\n{text}"),
    )
    .unwrap();
    let (code, err) = build_course();
    assert_eq!(code, Some(0), "{err}");
    let quiz =
        String::from_utf8(read_tree(&out_dir)["export/moodle/problem-box.xml"].clone()).unwrap();
    roxmltree::Document::parse(&quiz).expect("the quiz is XML");
    assert_eq!(
        quiz.matches(
            "<a href=\"https://course.example/mech/problem-box.html\">The worked solution</a>"
        )
        .count(),
        6,
        "one link per variant"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn ids_and_lectures_that_differ_only_in_case_are_refused() {
    let (dir, course) = course("case");
    let lecture = course.join("lectures/lecture-1");
    let text = std::fs::read_to_string(lecture.join("01-book.toml")).unwrap();
    std::fs::write(
        lecture.join("03-book.toml"),
        text.replace("id = \"book\"", "id = \"Book\""),
    )
    .unwrap();
    let out = mechbook(&["check", arg(&course.join("lectures"))]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("03-book.toml:3:6: field `id`: scene ids `book` and `Book`")
            || stderr(&out).contains("scene ids `Book` and `book`"),
        "{}",
        stderr(&out)
    );
    assert!(
        stderr(&out).contains("differ only in case"),
        "{}",
        stderr(&out)
    );
    std::fs::write(
        lecture.join("03-book.toml"),
        text.replace("id = \"book\"", "id = \"book-a\"")
            .replace("lecture = \"1\"", "lecture = \"A\""),
    )
    .unwrap();
    std::fs::write(
        lecture.join("04-book.toml"),
        text.replace("id = \"book\"", "id = \"book-b\"")
            .replace("lecture = \"1\"", "lecture = \"a\""),
    )
    .unwrap();
    let out = mechbook(&["check", arg(&course.join("lectures"))]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("would share the handout file name"),
        "{}",
        stderr(&out)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_plot_that_cannot_be_drawn_is_located_at_the_plot() {
    let dir = scratch("plot-at");
    let scene = dir.join("cube.toml");
    // A cube about its centre has three equal moments: no flip to draw.
    std::fs::write(
        &scene,
        "id = \"cube\"\ntitle = \"A cube\"\nnotes = { lecture = \"1\" }\n\
         symbols = { m = \"mass\", a = \"side\" }\n\n[[body]]\nkind = \"box\"\n\
         size = [\"a\", \"a\", \"a\"]\nmass = \"m\"\norigin = \"centre\"\n\n\
         [outputs]\nwant = [\"inertia_tensor\"]\n\n[numeric]\nvalues = { m = 1.0, a = 1.0 }\n\n\
         [[plot]]\nkind = \"polar-motion\"\ninertia = [1.0, 1.0, 2.0]\nomega = [0.1, 0.0, 1.0]\nt = 10.0\n\n\
         [[plot]]\nkind = \"flip\"\ninertia = \"principal\"\nomega = [0.05, 10.0, 0.05]\nt = 8.0\n",
    )
    .unwrap();
    let out = mechbook(&["derive", arg(&scene)]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("cube.toml:24:1: plot[1] of scene `cube` could not be drawn: the flip needs three different moments"),
        "{}",
        stderr(&out)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_problem_sheet_beyond_its_page_budget_is_refused_at_the_largest_problem() {
    let (dir, course) = course("sheet-budget");
    let lecture = course.join("lectures/lecture-1");
    let problem = lecture.join("02-problem-box.toml");
    let text = std::fs::read_to_string(&problem).unwrap();
    // 5,001 variants beside a second problem: 10,002 pages, over 10,000.
    let big = another_problem(&text, "problem-box", "1", 5001);
    std::fs::write(&problem, &big).unwrap();
    std::fs::write(
        lecture.join("03-problem-box.toml"),
        text.replace("id = \"problem-box\"", "id = \"problem-box-2\""),
    )
    .unwrap();
    let out = mechbook(&["check", arg(&course.join("lectures"))]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(
        err.contains("02-problem-box.toml:")
            && err.contains(
                "lecture `1`'s problem sheet would have 5001 variants (this problem's count) of 2 \
                 problems, 10002 pages; at most 10000"
            ),
        "{err}"
    );
    // One problem fewer fits.
    std::fs::remove_file(lecture.join("03-problem-box.toml")).unwrap();
    let out = mechbook(&["check", arg(&course.join("lectures"))]);
    assert!(
        !stderr(&out).contains("problem sheet would have"),
        "{}",
        stderr(&out)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn angles_lose_their_whole_turns_exactly_before_any_float_sees_them() {
    let dir = scratch("turns");
    let scene = dir.join("hoop.toml");
    let shipped = std::fs::read_to_string(super::lecture("11-problem-tilted-hoop.toml")).unwrap();
    let turned = shipped.replace(
        "alpha = [\"pi/6\", \"pi/4\", \"pi/3\"]",
        "alpha = [\"pi/6\", \"100000000000000000000*pi + pi/6\", \"1000000*pi + pi/3\"]",
    );
    assert_ne!(turned, shipped);
    std::fs::write(&scene, &turned).unwrap();
    // New variants: pinned first, so that the run below checks the answers alone.
    let blessed = mechbook(&["check", "--bless", arg(&scene)]);
    assert_eq!(blessed.status.code(), Some(0), "{}", stdout(&blessed));
    let out = mechbook(&["derive", "--json", arg(&scene)]);
    // 1e6·π + π/3 used to fail a right answer by 2.3e-10; 1e20·π + π/6 passed a wrong one.
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    let tensor = |values: &str| {
        json["variants"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|v| v["values"]["alpha"]["exact"] == values)
            .map(|v| {
                let scale = v["values"]["M"]["numeric"].as_f64().unwrap()
                    * v["values"]["R"]["numeric"].as_f64().unwrap().powi(2);
                let a = &v["answers"][0];
                assert_eq!(a["passed"], true, "{a}");
                a["numeric"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().unwrap() / scale)
                    .collect::<Vec<f64>>()
            })
            .collect::<Vec<_>>()
    };
    // The tensor per unit M R²: the same at π/6 and at π/6 plus 5e19 turns, exactly.
    let at_sixth = tensor("1/6*pi");
    let far = tensor("100000000000000000000*pi + 1/6*pi");
    assert!(!far.is_empty() && !at_sixth.is_empty());
    for t in &far {
        for (x, y) in t.iter().zip(&at_sixth[0]) {
            assert!((x - y).abs() < 1e-15, "{t:?} against {:?}", at_sixth[0]);
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Writes lecture `n`'s folder with `problems` (file name, text), and titles the lecture in
/// the course file's text `file` when `untitled` (not titled there yet).
fn add_lecture(
    lectures: &Path,
    file: &mut String,
    n: usize,
    untitled: bool,
    problems: &[(String, String)],
) {
    let folder = lectures.join(format!("lecture-{n}"));
    std::fs::create_dir_all(&folder).unwrap();
    for (name, text) in problems {
        std::fs::write(folder.join(name), text).unwrap();
    }
    if untitled {
        file.push_str(&format!(
            "\n[[lecture]]\nid = \"{n}\"\ntitle = \"Lecture {n}\"\n"
        ));
    }
}

/// The starter's problem box, made another problem: its id, lecture and variant count changed.
fn another_problem(text: &str, id: &str, lecture: &str, count: usize) -> String {
    let out = text
        .replace("id = \"problem-box\"", &format!("id = \"{id}\""))
        .replace("lecture = \"1\"", &format!("lecture = \"{lecture}\""))
        .replace("count = 6", &format!("count = {count}"))
        .replace(
            "m = { from = \"1\", to = \"10\", step = \"1\" }",
            "m = { from = \"1\", to = \"1000\", step = \"1\" }",
        );
    assert!(out.contains(&format!("count = {count}")) && out.contains("to = \"1000\""));
    // Other variants than the starter's: their pin is recorded by `check --bless`.
    out.lines()
        .filter(|l| !l.starts_with("variants = "))
        .map(|l| format!("{l}\n"))
        .collect()
}

#[test]
fn the_variants_and_pages_of_a_whole_course_have_a_budget() {
    let (dir, course) = course("course-budget");
    let lectures = course.join("lectures");
    let text = std::fs::read_to_string(lectures.join("lecture-1/02-problem-box.toml")).unwrap();
    // Three lectures of 7,000 variants each: every sheet is within its 10,000 pages, but the
    // course has 21,000 variants to derive, over 20,000.
    let mut file = std::fs::read_to_string(course.join("mechbook.toml")).unwrap();
    for n in 1..=3 {
        let problem = another_problem(&text, &format!("problem-{n}"), &n.to_string(), 7000);
        add_lecture(
            &lectures,
            &mut file,
            n,
            n > 1,
            &[("02-problem-box.toml".into(), problem)],
        );
    }
    std::fs::write(course.join("mechbook.toml"), file).unwrap();
    let out = mechbook(&["check", arg(&lectures)]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(
        err.contains("02-problem-box.toml:")
            && err.contains(
                "the course's 3 problems would have 21000 variants in all; at most 20000: lower \
                 the counts"
            ),
        "{err}"
    );
    // Six lectures of one problem of 1,666 variants beside five of one: each sheet has 9,996
    // pages, within 10,000, and the course 10,026 variants, but 59,976 pages, over 50,000.
    for n in 1..=3 {
        std::fs::remove_dir_all(lectures.join(format!("lecture-{n}"))).unwrap();
    }
    let mut file = std::fs::read_to_string(course.join("mechbook.toml")).unwrap();
    for n in 1..=6 {
        let problems: Vec<(String, String)> = (0..6)
            .map(|k| {
                let count = if k == 0 { 1666 } else { 1 };
                let id = format!("p-{n}-{k}");
                (
                    format!("p{k}.toml"),
                    another_problem(&text, &id, &n.to_string(), count),
                )
            })
            .collect();
        add_lecture(&lectures, &mut file, n, n > 3, &problems);
    }
    std::fs::write(course.join("mechbook.toml"), file).unwrap();
    let out = mechbook(&["check", arg(&lectures)]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(
        err.contains(
            "the course's 36 problems would have problem sheets of 59976 pages in all; \
                       at most 50000"
        ) && !err.contains("problem sheet would have"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_problem_with_fewer_variants_than_the_sheet_is_answered_once_in_the_key() {
    let (dir, course) = course("key-once");
    let lecture = course.join("lectures/lecture-1");
    let text = std::fs::read_to_string(lecture.join("02-problem-box.toml")).unwrap();
    std::fs::write(
        lecture.join("03-problem-once.toml"),
        another_problem(&text, "problem-once", "1", 1),
    )
    .unwrap();
    let site = dir.join("site");
    let blessed = mechbook(&["check", "--bless", arg(&course.join("lectures"))]);
    assert_eq!(blessed.status.code(), Some(0), "{}", stdout(&blessed));
    let out = mechbook(&["build", arg(&course.join("lectures")), "--out", arg(&site)]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let key = std::fs::read_to_string(site.join("handouts/lecture-1-problems-key.html")).unwrap();
    let student =
        std::fs::read_to_string(site.join("handouts/lecture-1-problems-student.html")).unwrap();
    // Every student's copy has both problems; the key answers problem 2's one variant once,
    // and each of the 6 sheet variants says it uses it.
    assert_eq!(student.matches("<h2>Problem 2: ").count(), 6);
    assert_eq!(key.matches("<h3>Problem 2, its variant 1: ").count(), 1);
    assert_eq!(key.matches("Its variant 1: answered under").count(), 6);
    assert_eq!(key.matches("<h3>Problem 1: ").count(), 6);
    assert_eq!(key.matches("<table class=\"key stack\">").count(), 6 + 1);
    // Picked at any sheet variant, the key shows that one answer (the print rules hide the
    // shared answers a variant does not use).
    assert!(key.contains("<article class=\"key-problem s-1 s-2 s-3 s-4 s-5 s-6\">"));
    assert!(key.contains("#variant-6:target ~ main .shared .key-problem:not(.s-6)"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_problem_that_cannot_be_answered_exactly_says_why_at_once() {
    let dir = scratch("no-exact");
    let corner = r#"
id = "corner-box"
title = "A box about its corner"
notes = { lecture = "1" }
symbols = { m = "mass", a = "side x", b = "side y", c = "side z" }
[[body]]
kind = "box"
size = ["a", "b", "c"]
mass = "m"
origin = "corner"
[outputs]
want = ["inertia_tensor", "principal_axes"]
[numeric]
values = { m = 6.0, a = 0.75, b = 2.0, c = 3.0 }
[problem]
statement = "A box of mass {m} and sides {a}, {b}, {c}."
answers = ["principal_moments"]
[variants]
count = 4
m = ["1", "2"]
a = ["1", "2"]
b = ["3", "4"]
c = ["5", "6"]
"#;
    std::fs::write(dir.join("corner.toml"), corner).unwrap();
    // Its cubic does not factor: once "internal inconsistency" at every variant.
    let out = mechbook(&["check", arg(&dir)]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(
        err.contains("corner.toml:")
            && err.contains("the principal moments have no exact form here")
            && err.contains("take `principal_moments` out of the problem's answers")
            && !err.contains("internal inconsistency"),
        "{err}"
    );
    // A plate about its corner has roots; sides of 17 digits put a 32-digit number under
    // one, which the engine took over ten minutes to factor: refused at once.
    let plate = r#"
id = "near-plate"
title = "A plate about its corner"
notes = { lecture = "1" }
symbols = { m = "mass", a = "side x", b = "side y" }
[[body]]
kind = "plate"
size = ["a", "b"]
mass = "m"
[outputs]
want = ["inertia_tensor", "principal_axes"]
[numeric]
values = { m = 6.0, a = 0.75, b = 2.0 }
[problem]
statement = "A plate of mass {m} and sides {a} and {b}."
answers = ["principal_moments"]
[variants]
count = 3
m = ["1", "2"]
a = ["1.0000000000000001", "1.0000000000000002"]
b = ["1.0000000000000003", "1.0000000000000004"]
"#;
    std::fs::remove_file(dir.join("corner.toml")).unwrap();
    std::fs::write(dir.join("plate.toml"), plate).unwrap();
    let out = mechbook(&["check", arg(&dir)]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(
        err.contains("plate.toml:")
            && err.contains("variant 1: computer algebra failed: a root of a number with")
            && err.contains("give the values (and a problem's variants) fewer digits"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_exact_and_numeric_agreement_grows_with_the_point_masses_summed() {
    let dir = scratch("many-points");
    // A unit mass, then 10,000 masses of 0.6 of an f64 step at 1: each addition rounds up by
    // 0.4 of a step, so the f64 sum is off by 9.2e-13 however it is computed in order. The
    // exact sum is right; 1e-14 failed it, 4nε (8.9e-12) does not.
    let light = "{ mass = \"0.00000000000000013\", at = [\"1\", \"0\", \"0\"] }";
    let mut points = vec!["{ mass = \"1\", at = [\"1\", \"0\", \"0\"] }"];
    points.extend(std::iter::repeat_n(light, 10_000));
    let scene = format!(
        "id = \"many-points\"\ntitle = \"Many point masses\"\nnotes = {{ lecture = \"1\" }}\n\
         [[body]]\nkind = \"points\"\npoints = [{}]\n[outputs]\nwant = [\"inertia_tensor\", \
         \"numeric\"]\n",
        points.join(", ")
    );
    std::fs::write(dir.join("points.toml"), scene).unwrap();
    // Beside the scenes' folder: a report is never written among the scenes.
    let report = dir.with_extension("report.json");
    let out = mechbook(&["check", arg(&dir), "--json-file", arg(&report)]);
    let json: serde_json::Value = serde_json::from_slice(&std::fs::read(&report).unwrap()).unwrap();
    let failures: Vec<&str> = json["failures"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap())
        .collect();
    // Only the unrecorded results fail: the numeric check passes.
    assert!(
        !failures.is_empty() && failures.iter().all(|f| f.contains("not yet recorded")),
        "{failures:?}\n{}",
        stderr(&out)
    );
    let check = &json["scenes"][0]["exact_vs_numeric"][0];
    assert_eq!(check["quantity"], "inertia_tensor");
    assert_eq!(check["passed"], true, "{check}");
    let error = check["error"].as_f64().unwrap();
    assert!(
        error > 1e-14 && error < 4.0 * 10_001.0 * f64::EPSILON,
        "{error}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
    std::fs::remove_file(&report).unwrap();
}

#[test]
fn bless_on_a_full_disk_leaves_the_scene_as_it_was_and_nothing_beside_it() {
    let (dir, course) = course("bless-full");
    let lecture = course.join("lectures/lecture-1");
    let scene = lecture.join("02-problem-box.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    let unrecorded = &text[..text.find("[expect]").unwrap()];
    std::fs::write(&scene, unrecorded).unwrap();
    // No byte may be written (as on a full disk): writes fail with EFBIG, not a signal.
    let out = std::process::Command::new("sh")
        .arg("-c")
        .arg("trap '' XFSZ; ulimit -f 0; exec \"$0\" check --bless \"$1\"")
        .arg(env!("CARGO_BIN_EXE_mechbook"))
        .arg(course.join("lectures"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains("02-problem-box.toml: File too large (os error 27)"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&scene).unwrap(), unrecorded);
    let names: Vec<String> = std::fs::read_dir(&lecture)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_angle_inside_the_axis_loses_its_whole_turns_in_the_numeric_route_too() {
    let dir = scratch("axis-turns");
    let scene = r#"
id = "axis-turns"
title = "A box about a tilted axis"
notes = { lecture = "1" }
symbols = { m = "mass", a = "side", alpha = "tilt of the axis" }
axis = ["cos(alpha)", "0", "sin(alpha)"]
[[body]]
kind = "box"
size = ["a", "2*a", "3*a"]
mass = "m"
origin = "centre"
[outputs]
want = ["inertia_tensor", "moment_about_axis"]
[numeric]
values = { m = 1.0, a = 1.0, alpha = 0.5 }
[problem]
statement = "A box of mass {m} and side {a} turns about an axis tilted by {alpha}."
answers = ["moment_about_axis"]
[variants]
count = 2
m = ["1", "2"]
a = ["1"]
alpha = ["100000000000000000000*pi + pi/6", "1000000*pi + pi/3"]
[expect]
mass = "m"
inertia_tensor = "[[13/12*m*a^2, 0, 0], [0, 5/6*m*a^2, 0], [0, 0, 5/12*m*a^2]]"
moment_about_axis = "5/12*m*a^2 + 2/3*m*a^2*cos(alpha)^2"
"#;
    std::fs::write(dir.join("axis.toml"), scene).unwrap();
    let blessed = mechbook(&["check", "--bless", arg(&dir.join("axis.toml"))]);
    assert_eq!(blessed.status.code(), Some(0), "{}", stdout(&blessed));
    let out = mechbook(&["derive", "--json", arg(&dir.join("axis.toml"))]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    // In f64 the first angle had no digit of π/6 left (6.9e-2 apart), the second 4.1e-10.
    let variants = json["variants"].as_array().unwrap();
    assert_eq!(variants.len(), 2);
    for v in variants {
        let a = &v["answers"][0];
        assert_eq!(a["passed"], true, "{a}");
        assert!(a["error"].as_f64().unwrap() < 1e-15, "{a}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
