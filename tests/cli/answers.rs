//! Problems that grade any expression, with units (tests/course/problems): every key answer
//! against a closed form written here, no answer on a student's sheet, the Moodle quizzes
//! parsed with their units, and each dimension error located.

use super::problems::numbers;
use super::{mechbook, scratch, stderr, stdout};
use mechbook::base::format::{figures, significant};
use mechbook::notation::Tex;
use mechbook::render::html::math::inline;
use nalgebra::{Matrix3, Vector3};
use serde_json::Value as Json;
use std::collections::BTreeMap;
use std::path::Path;

const COURSE: &str = "tests/course/problems";

fn checked() -> Vec<Json> {
    let out = mechbook(&["check", "--json", COURSE]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json: Json = serde_json::from_str(&stdout(&out)).unwrap();
    json["scenes"].as_array().unwrap().clone()
}

fn values(v: &Json) -> BTreeMap<String, f64> {
    v["values"]
        .as_object()
        .unwrap()
        .iter()
        .map(|(k, x)| (k.clone(), x["numeric"].as_f64().unwrap()))
        .collect()
}

/// Each answer of each variant by a closed form of this test's own, in the answer's unit.
fn expected(id: &str, x: &BTreeMap<String, f64>) -> Vec<Vec<f64>> {
    let g = |k: &str| x[k];
    match id {
        "problem-pendulum" => vec![
            vec![g("M") * g("L").powi(2) / 3.0],
            vec![2.0 * std::f64::consts::PI * (2.0 * g("L") / (3.0 * g("g"))).sqrt()],
        ],
        "problem-angle-l-omega" => {
            let (a, b, c) = (g("a"), g("b"), g("c"));
            let tensor =
                Matrix3::from_diagonal(&Vector3::new(b * b + c * c, a * a + c * c, a * a + b * b))
                    * (g("m") / 12.0);
            let w = Vector3::new(g("w"), 0.0, g("w"));
            let l = tensor * w;
            let angle = (l.dot(&w) / (l.norm() * w.norm())).acos();
            vec![l.iter().copied().collect(), vec![angle]]
        }
        "problem-rolling" => vec![vec![2.0 / 3.0 * g("g") * g("alpha").sin()]],
        "problem-critical-spin" => {
            vec![vec![
                2.0 * (g("I1") * g("M") * g("g") * g("l")).sqrt() / g("I3"),
            ]]
        }
        // In centimetres: the cylinder's centre at H/2, the cone's at H + h/4.
        "problem-centre-of-mass" => vec![vec![
            100.0 * (g("m") * g("H") / 2.0 + g("k") * (g("H") + g("h") / 4.0)) / (g("m") + g("k")),
        ]],
        // The double pendulum's modes, √((2 ∓ √2) g/l), slowest first.
        "problem-normal-modes" => [-1.0, 1.0]
            .iter()
            .map(|s| vec![((2.0 + s * 2f64.sqrt()) * g("g") / g("l")).sqrt()])
            .collect(),
        // Five links: no closed form, so the textbook's M⁻¹K (M_ij = n − max(i, j),
        // K = (g/l) diag(n, …, 1)) by nalgebra; the slowest mode, and the fastest over it.
        "problem-five-links" => {
            let n = 5;
            let m = nalgebra::DMatrix::from_fn(n, n, |i, j| (n - i.max(j)) as f64);
            let k = nalgebra::DMatrix::from_fn(n, n, |i, j| {
                if i == j {
                    g("g") / g("l") * (n - i) as f64
                } else {
                    0.0
                }
            });
            let mut w: Vec<f64> = m
                .lu()
                .solve(&k)
                .unwrap()
                .complex_eigenvalues()
                .iter()
                .map(|l| l.re.sqrt())
                .collect();
            w.sort_by(f64::total_cmp);
            vec![vec![w[0]], vec![w[n - 1] / w[0]]]
        }
        // A solid ball: I = 2MR²/5 rolls down at 5g sin α/7.
        "problem-rolling-ball" => vec![
            vec![0.4 * g("M") * g("R").powi(2)],
            vec![5.0 / 7.0 * g("g") * g("alpha").sin()],
        ],
        // A rod about a pivot d from its centre: I = ML²/12 + Md², T = 2π√(I/(Mgd)).
        "problem-offset-pivot" => {
            let i = g("M") * (g("L").powi(2) / 12.0 + g("d").powi(2));
            vec![
                vec![i],
                vec![2.0 * std::f64::consts::PI * (i / (g("M") * g("g") * g("d"))).sqrt()],
            ]
        }
        // Newton on each mass and on the pulley: (m1 − m2)g = (m1 + m2 + I/R²)a, I = MR²/2.
        "problem-atwood-pulley" => {
            let i = g("M") * g("R").powi(2) / 2.0;
            vec![
                vec![i],
                vec![(g("m1") - g("m2")) * g("g") / (g("m1") + g("m2") + i / g("R").powi(2))],
            ]
        }
        // A ball rolling in a bowl: Ω² = g/((R − r)(1 + 2/5)).
        "problem-ball-in-bowl" => {
            let w = (g("g") / ((g("R") - g("r")) * 1.4)).sqrt();
            vec![vec![w], vec![2.0 * std::f64::consts::PI / w]]
        }
        other => panic!("no closed form for {other}"),
    }
}

#[test]
fn every_key_answer_matches_a_closed_form_and_none_reaches_a_student() {
    let scenes = checked();
    assert_eq!(scenes.len(), 11);
    let dir = scratch("answers-site");
    let site = dir.join("site");
    let built = mechbook(&["build", COURSE, "--out", site.to_str().unwrap()]);
    assert_eq!(built.status.code(), Some(0), "{}", stderr(&built));
    let mut answers = 0;
    for s in &scenes {
        let id = s["id"].as_str().unwrap();
        assert_eq!(s["passed"], true, "{id}");
        let lecture = s["notes"]["lecture"].as_str().unwrap().replace(' ', "-");
        let sheet = |kind: &str| {
            let path = site.join(format!("handouts/lecture-{lecture}-problems-{kind}.html"));
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        };
        let (student, key) = (sheet("student"), sheet("key"));
        // This problem's parts of the student's sheet: another problem's given values (l = 3/4
        // m) may read as this one's answer.
        // (By the title's words before any mathematics, which the sheet typesets.)
        let title = s["title"].as_str().unwrap().split('$').next().unwrap();
        let student: String = student
            .split("<article class=\"sheet-problem\">")
            .filter(|part| part.contains(&format!(": {title}")))
            .collect();
        assert!(
            !student.is_empty(),
            "{id}: no part of the sheet is titled {title}"
        );
        for v in s["variants"].as_array().unwrap() {
            let want = expected(id, &values(v));
            let given = v["answers"].as_array().unwrap();
            assert_eq!(given.len(), want.len(), "{id}");
            for (a, w) in given.iter().zip(&want) {
                assert_eq!(a["passed"], true, "{id}: {a}");
                for (got, w) in numbers(a).iter().zip(w) {
                    assert!(
                        (got - w).abs() <= 1e-12 * w.abs().max(1.0),
                        "{id} variant {}: {} is {got}, the closed form {w}",
                        v["number"],
                        a["quantity"]
                    );
                    answers += 1;
                    // The key gives it to four figures; the student's sheet nowhere.
                    assert!(key.contains(&figures(*got, 4)), "{id}: key lacks {got}");
                    for decimal in [figures(*got, 4), significant(*got, 6)] {
                        if decimal.contains('.') && *got != 0.0 {
                            assert!(!student.contains(&decimal), "{id}: {decimal} on a sheet");
                        }
                    }
                }
                // A mode with no closed form has no exact form to keep from the sheet: its
                // number is checked above.
                let Some(latex) = a["latex"].as_str() else {
                    assert_eq!(a["numeric_only"], true, "{id}: {a}");
                    continue;
                };
                let exact = inline(&Tex::read(latex).unwrap()).unwrap();
                assert!(!student.contains(&exact), "{id}: {exact} on a sheet");
            }
        }
    }
    assert!(answers >= 40, "{answers} answers");
    // The five links' 8 answers are counted apart from the exact ones.
    let text = stdout(&mechbook(&["check", COURSE]));
    assert!(
        text.contains("answers exact and 8 modes with no closed form, found at their variant's"),
        "{text}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn moodle_questions_carry_units_labels_and_blanks_for_every_answer() {
    let dir = scratch("answers-moodle");
    let site = dir.join("site");
    let built = mechbook(&["build", COURSE, "--out", site.to_str().unwrap()]);
    assert_eq!(built.status.code(), Some(0), "{}", stderr(&built));
    let read =
        |id: &str| std::fs::read_to_string(site.join(format!("export/moodle/{id}.xml"))).unwrap();
    // One answer: a numerical question whose unit Moodle grades.
    let text = read("problem-rolling");
    let doc = roxmltree::Document::parse(&text).unwrap();
    let questions: Vec<_> = doc
        .descendants()
        .filter(|n| n.has_tag_name("question") && n.attribute("type") == Some("numerical"))
        .collect();
    assert_eq!(questions.len(), 6);
    for q in &questions {
        let unit = q
            .descendants()
            .find(|n| n.has_tag_name("unit_name"))
            .and_then(|n| n.text());
        assert_eq!(unit, Some("m/s^2"));
        let multiplier = q.descendants().find(|n| n.has_tag_name("multiplier"));
        assert_eq!(multiplier.and_then(|n| n.text()), Some("1"));
        let grading = q.children().find(|n| n.has_tag_name("unitgradingtype"));
        assert_eq!(grading.and_then(|n| n.text()), Some("1"));
    }
    // Two answers: a cloze question, each blank with its label before it and unit after it.
    let text = read("problem-pendulum");
    let doc = roxmltree::Document::parse(&text).unwrap();
    for q in doc
        .descendants()
        .filter(|n| n.has_tag_name("question") && n.attribute("type") == Some("cloze"))
    {
        let body = q
            .descendants()
            .find(|n| n.has_tag_name("questiontext"))
            .and_then(|n| n.descendants().find(|n| n.has_tag_name("text")))
            .and_then(|n| n.text())
            .unwrap();
        assert!(
            body.contains("<p>Moment of inertia about the pivot:</p>"),
            "{body}"
        );
        assert!(
            body.contains("<p>Period of small oscillations:</p>"),
            "{body}"
        );
        assert_eq!(body.matches("{1:NUMERICAL:=").count(), 2, "{body}");
        assert_eq!(body.matches("} kg m^2</p>").count(), 1, "{body}");
        assert_eq!(body.matches("} s</p>").count(), 1, "{body}");
        // The statement's $…$ is TeX for Moodle's filter, its values put in, its braces as
        // character references (no author's brace starts a blank).
        assert!(body.contains("\\(M = &#123;"), "{body}");
        assert!(!body.contains('$'), "{body}");
    }
    // A label's $…$ is TeX for Moodle too.
    let text = read("problem-angle-l-omega");
    roxmltree::Document::parse(&text).unwrap();
    assert_eq!(
        text.matches(
            "<p>Angle between \\(\\vec&#123;L&#125;\\) and \\(\\vec&#123;\\omega&#125;\\):</p>"
        )
        .count(),
        6,
        "{text}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn each_dimension_error_is_located_and_says_what_to_do() {
    let dir = Path::new("tests/fixtures/dimensions");
    let fixtures = super::bad_input::fixtures(dir);
    assert_eq!(fixtures.len(), 4);
    for (f, want) in fixtures {
        let out = mechbook(&["check", f.to_str().unwrap()]);
        // A refused step or answer is on stderr; a claim's failure is in the report.
        let err = format!("{}{}", stdout(&out), stderr(&out));
        assert_eq!(out.status.code(), Some(1), "{}: {err}", f.display());
        assert!(
            err.contains(&format!("{}/{}", dir.display(), want.trim())),
            "{}:\n want: {}\n got:  {err}",
            f.display(),
            want.trim()
        );
    }
}

/// HTML with every `alttext="…"` attribute taken out.
fn without_alttext(html: &str) -> String {
    let mut out = String::with_capacity(html.len());
    let mut rest = html;
    while let Some(at) = rest.find(" alttext=\"") {
        out.push_str(&rest[..at]);
        let value = &rest[at + 10..];
        rest = &value[value.find('"').map_or(value.len(), |end| end + 1)..];
    }
    out.push_str(rest);
    out
}

#[test]
fn a_symbol_is_typeset_as_its_scene_says_on_the_page_and_the_key() {
    // problem-angle-l-omega declares w with tex = "\\omega".
    let dir = scratch("answers-tex");
    let site = dir.join("site");
    let built = mechbook(&["build", COURSE, "--out", site.to_str().unwrap()]);
    assert_eq!(built.status.code(), Some(0), "{}", stderr(&built));
    // The MathML as set, without the spoken forms (`alttext`, tested in notation::spoken).
    let read = |file: &str| without_alttext(&std::fs::read_to_string(site.join(file)).unwrap());
    let page = read("problem-angle-l-omega.html");
    assert!(
        page.contains("<tr><td><math display=\"inline\"><mi>ω</mi></math></td><td>each non-zero"),
        "the setup table"
    );
    assert!(!page.contains("<mi>w</mi>"), "w left as w on the page");
    let key = read("handouts/lecture-Rotational-dynamics-problems-key.html");
    let ours = &key[key.find("The angle between").expect("the problem")..];
    let ours = &ours[..ours.find("</article>").unwrap()];
    assert!(
        ours.contains("<mi>ω</mi></math> <math display=\"inline\"><mrow></mrow><mo>=</mo>"),
        "{ours}"
    );
    assert!(!ours.contains("<mi>w</mi>"), "{ours}");
    // g, written 9.81, stays 9.81 in the key's exact column: 2π/√(3 ⋅ 9.81), not 20π/(3√327).
    let period = &key[key
        .find("Period of small oscillations")
        .expect("the period")..];
    let exact = &period[..period.find("</td>").unwrap()];
    assert!(
        exact.contains("<mo>⋅</mo><mn>9.81</mn>") && !exact.contains("327"),
        "{exact}"
    );
    // Other scenes are not touched: the pendulum's own names are as before.
    assert!(read("problem-pendulum.html").contains("<mi>M</mi>"));
    // A scene with a radius R calls its centre of mass R⃗_cm, not R⃗ (cm one upright word).
    let centre = read("problem-centre-of-mass.html");
    let step = &centre[centre.find("Centre of mass</strong>").unwrap()..];
    assert!(
        step.starts_with(
            "Centre of mass</strong><math display=\"block\"><msub><mover><mrow><mi>R</mi></mrow><mi>→</mi></mover><mrow><mrow><mtext>cm</mtext>"
        ),
        "{}",
        &step[..300]
    );
    std::fs::remove_dir_all(dir).unwrap();
}
