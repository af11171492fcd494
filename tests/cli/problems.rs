//! The shipped problem sheets: no student file holds an answer, every key answer matches a
//! route of this test's own (closed forms and an RK4 integration written here), and the Moodle
//! quizzes parse as XML and carry the key's numbers.

use super::{mechbook, scratch, stderr, stdout};
use mechbook::base::format::{figures, significant};
use mechbook::notation::Tex;
use mechbook::render::html::math::inline;
use nalgebra::{Matrix3, Vector3};
use serde_json::Value as Json;
use std::path::{Path, PathBuf};

const PROBLEMS: &[&str] = &[
    "lectures/lecture-3-4/10-problem-box.toml",
    "lectures/lecture-3-4/11-problem-tilted-hoop.toml",
    "lectures/lecture-3-9/06-problem-top.toml",
];

fn derived(scene: &str) -> Json {
    let out = mechbook(&["derive", "--json", scene]);
    assert!(out.status.success(), "{scene}: {}", stderr(&out));
    serde_json::from_str(&stdout(&out)).unwrap()
}

fn build(name: &str) -> (PathBuf, PathBuf) {
    let dir = scratch(name);
    let site = dir.join("site");
    let out = mechbook(&["build", "lectures", "--out", site.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    (dir, site)
}

fn sheet(site: &Path, scene: &Json, kind: &str) -> String {
    let lecture = scene["notes"]["lecture"]
        .as_str()
        .unwrap()
        .replace('/', "-");
    let path = site.join(format!("handouts/lecture-{lecture}-problems-{kind}.html"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

pub fn numbers(a: &Json) -> Vec<f64> {
    a["numeric"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn value(v: &Json, name: &str) -> f64 {
    v["values"][name]["numeric"].as_f64().unwrap()
}

#[test]
fn no_student_sheet_contains_any_answer_exact_or_decimal() {
    let (dir, site) = build("problems-student");
    let scenes: Vec<Json> = PROBLEMS.iter().map(|s| derived(s)).collect();
    for json in &scenes {
        let scene = json["id"].as_str().unwrap();
        let student = sheet(&site, json, "student");
        let key = sheet(&site, json, "key");
        // Every formula on a student sheet is a value of a variant of one of its problems:
        // take those out, and no formula may be left.
        let mut stripped = student.clone();
        for other in &scenes {
            for v in other["variants"].as_array().unwrap() {
                for (_, x) in v["values"].as_object().unwrap() {
                    let math = inline(&Tex::read(x["latex"].as_str().unwrap()).unwrap()).unwrap();
                    stripped = stripped.replace(&math, "");
                }
            }
        }
        // And the statements' own mathematics (`$y$ axis`, `$\alpha = {alpha}$`), at each
        // variant's values: the LaTeX with each value's LaTeX in its braces.
        for (file, other) in PROBLEMS.iter().zip(&scenes) {
            let text: toml::Value =
                toml::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
            let statement = text["problem"]["statement"].as_str().unwrap();
            let parts = mechbook::model::prose::dollar_split(statement);
            for math in parts.iter().skip(1).step_by(2) {
                for v in other["variants"].as_array().unwrap() {
                    let mut filled = math.clone();
                    for (name, x) in v["values"].as_object().unwrap() {
                        let value = format!("{{{}}}", x["latex"].as_str().unwrap());
                        filled = filled.replace(&format!("{{{name}}}"), &value);
                    }
                    let math = inline(&Tex::read(&filled).unwrap()).unwrap();
                    stripped = stripped.replace(&math, "");
                }
            }
        }
        assert!(
            !stripped.contains("<math"),
            "{scene}: a formula on the student sheet is not a variant's value"
        );
        let variants = json["variants"].as_array().unwrap();
        assert!(variants.len() >= 9, "{scene}: {} variants", variants.len());
        for v in variants {
            for a in v["answers"].as_array().unwrap() {
                // An integer's text is in any page ("variant-1"): the formulas are checked above.
                let exact = a["exact"].as_str().unwrap();
                if exact.contains(['/', '^']) {
                    assert!(!student.contains(exact), "{scene}: exact answer {exact}");
                }
                for x in numbers(a) {
                    let decimals = [figures(x, 4), significant(x, 6)];
                    for decimal in decimals.iter().filter(|d| x != 0.0 && d.contains('.')) {
                        let digits = decimal.trim_start_matches('-');
                        assert!(
                            !stripped.contains(digits),
                            "{scene}: variant {}: {decimal} on the student sheet",
                            v["number"]
                        );
                    }
                    // The key does give it: so the test above would see a leak.
                    assert!(key.contains(on_key(x).as_str()), "{scene}: key lacks {x}");
                }
            }
        }
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// A number as the key's MathML has it: its four figures, the sign set apart as an operator.
fn on_key(x: f64) -> String {
    format!(">{}<", figures(x, 4).trim_start_matches('-'))
}

/// The symmetric top's precession rate by RK4 on Euler's equations (I2 = I1) over 1/|ω3|:
/// the angle (ω1, ω2) turns through, over the time.
fn precession_by_rk4(i1: f64, i3: f64, w3: f64) -> f64 {
    let rhs =
        |w: Vector3<f64>| Vector3::new((i1 - i3) / i1 * w.y * w.z, (i3 - i1) / i1 * w.z * w.x, 0.0);
    let t = 1.0 / w3.abs();
    let n = 20_000;
    let h = t / n as f64;
    let mut w = Vector3::new(0.1 * w3.abs(), 0.0, w3);
    for _ in 0..n {
        let k1 = rhs(w);
        let k2 = rhs(w + k1 * (h / 2.0));
        let k3 = rhs(w + k2 * (h / 2.0));
        let k4 = rhs(w + k3 * h);
        w += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0);
    }
    w.y.atan2(w.x) / t
}

fn sorted_eigenvalues(m: Matrix3<f64>) -> Vec<f64> {
    let mut e: Vec<f64> = m.symmetric_eigenvalues().iter().copied().collect();
    e.sort_by(f64::total_cmp);
    e
}

/// The answers of one variant by this test's routes: the box's textbook moments, the hoop's
/// moments in its own frame turned by R_y(α), the top's integration.
fn own_route(id: &str, v: &Json, quantity: &str) -> Vec<f64> {
    let tensor = match id {
        "problem-box" => {
            let (m, a, b, c) = (value(v, "m"), value(v, "a"), value(v, "b"), value(v, "c"));
            Matrix3::from_diagonal(&Vector3::new(
                m * (b * b + c * c) / 12.0,
                m * (a * a + c * c) / 12.0,
                m * (a * a + b * b) / 12.0,
            ))
        }
        "problem-tilted-hoop" => {
            let (m, r, t) = (value(v, "M"), value(v, "R"), value(v, "alpha"));
            let own =
                Matrix3::from_diagonal(&Vector3::new(m * r * r / 2.0, m * r * r / 2.0, m * r * r));
            let turn = Matrix3::new(t.cos(), 0.0, t.sin(), 0.0, 1.0, 0.0, -t.sin(), 0.0, t.cos());
            turn * own * turn.transpose()
        }
        "problem-top" => {
            return vec![precession_by_rk4(
                value(v, "I1"),
                value(v, "I3"),
                value(v, "w3"),
            )];
        }
        other => panic!("no route for {other}"),
    };
    match quantity {
        "inertia_tensor" => tensor.transpose().iter().copied().collect(),
        "principal_moments" => sorted_eigenvalues(tensor),
        other => panic!("no route for {other}"),
    }
}

#[test]
fn each_key_answer_matches_a_route_of_this_tests_own() {
    let (dir, site) = build("problems-key");
    let mut checked = 0;
    for scene in PROBLEMS {
        let json = derived(scene);
        let id = json["id"].as_str().unwrap();
        let key = sheet(&site, &json, "key");
        for v in json["variants"].as_array().unwrap() {
            for a in v["answers"].as_array().unwrap() {
                let quantity = a["quantity"].as_str().unwrap();
                let ours = own_route(id, v, quantity);
                let theirs = numbers(a);
                let scale = ours.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                for (x, y) in ours.iter().zip(&theirs) {
                    assert!(
                        (x - y).abs() <= 1e-9 * scale,
                        "{id} variant {} {quantity}: ours {x}, the key's {y}",
                        v["number"]
                    );
                    assert!(key.contains(on_key(*x).as_str()), "{id}: key lacks {x}");
                }
                checked += ours.len();
            }
        }
    }
    // 12 boxes and 9 hoops of 12 numbers each, and 12 tops.
    assert_eq!(checked, 12 * 12 + 9 * 12 + 12);
    std::fs::remove_dir_all(dir).unwrap();
}

/// `{1:NUMERICAL:=answer:tolerance}` blanks of a cloze text, in order.
fn cloze_blanks(text: &str) -> Vec<(f64, f64)> {
    text.split("{1:NUMERICAL:=")
        .skip(1)
        .map(|rest| {
            let body = &rest[..rest.find('}').expect("a closed blank")];
            let (answer, tol) = body.split_once(':').expect("answer:tolerance");
            (answer.parse().unwrap(), tol.parse().unwrap())
        })
        .collect()
}

#[test]
fn moodle_quizzes_parse_and_carry_the_key_answers() {
    let (dir, site) = build("problems-moodle");
    for scene in PROBLEMS {
        let json = derived(scene);
        let id = json["id"].as_str().unwrap();
        let text = std::fs::read_to_string(site.join(format!("export/moodle/{id}.xml"))).unwrap();
        let doc = roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("{id}: {e}"));
        let quiz = doc.root_element();
        assert_eq!(quiz.tag_name().name(), "quiz");
        let questions: Vec<_> = quiz
            .children()
            .filter(|n| n.has_tag_name("question") && n.attribute("type") != Some("category"))
            .collect();
        let variants = json["variants"].as_array().unwrap();
        assert_eq!(
            questions.len(),
            variants.len(),
            "{id}: one question a variant"
        );
        for (q, v) in questions.iter().zip(variants) {
            let child_text = |path: &[&str]| -> String {
                let mut node = *q;
                for p in path {
                    node = node
                        .children()
                        .find(|n| n.has_tag_name(*p))
                        .unwrap_or_else(|| panic!("{id}: no <{p}>"));
                }
                node.text().unwrap_or("").to_string()
            };
            assert!(child_text(&["name", "text"]).contains(&format!("variant {}", v["number"])));
            let expected: Vec<f64> = v["answers"]
                .as_array()
                .unwrap()
                .iter()
                .flat_map(numbers)
                .collect();
            let given: Vec<(f64, f64)> = match q.attribute("type") {
                Some("numerical") => {
                    let answer = q.children().find(|n| n.has_tag_name("answer")).unwrap();
                    assert_eq!(answer.attribute("fraction"), Some("100"));
                    let field = |name: &str| -> f64 {
                        let n = answer.children().find(|n| n.has_tag_name(name)).unwrap();
                        n.text().unwrap().parse().unwrap()
                    };
                    vec![(field("text"), field("tolerance"))]
                }
                Some("cloze") => cloze_blanks(&child_text(&["questiontext", "text"])),
                other => panic!("{id}: question type {other:?}"),
            };
            assert_eq!(given.len(), expected.len(), "{id}: one blank an entry");
            for ((answer, tol), x) in given.iter().zip(&expected) {
                assert!(
                    (answer - x).abs() <= 1e-10 * x.abs().max(1.0),
                    "{id}: {answer} vs {x}"
                );
                assert!(
                    *tol >= 0.0
                        && *tol <= 0.011 * expected.iter().fold(0.0f64, |m, y| m.max(y.abs()))
                );
            }
            // A tolerance that rejects the right answer, or accepts every answer, is no blank.
            assert!(given.iter().any(|(_, t)| *t > 0.0));
            // Each blank is labelled in words, a list with the order it takes; no internal
            // name shows.
            let question = child_text(&["questiontext", "text"]);
            assert!(!question.contains('_'), "{id}: {question}");
            for a in v["answers"].as_array().unwrap() {
                let label = match a["quantity"].as_str().unwrap() {
                    "principal_moments" => "Principal moments (in ascending order, I1 ≤ I2 ≤ I3):",
                    "inertia_tensor" => "Inertia tensor (rows and columns x, y, z):",
                    "moment_about_axis" => "Moment about the axis:",
                    _ => continue,
                };
                if q.attribute("type") == Some("cloze") {
                    assert!(question.contains(label), "{id}: {question}");
                }
            }
        }
    }
    std::fs::remove_dir_all(dir).unwrap();
}
