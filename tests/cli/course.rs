//! A course written from docs/scenes.md alone (tests/course): new bodies, a box a × 2a × 3a and
//! three point masses whose characteristic cubics do not factor. Their principal moments must
//! reach the page and `--json`, equal to an eigen-solver run here on tensors written by hand.

use crate::{mechbook, scratch, stdout};
use nalgebra::{Matrix3, SymmetricEigen, Vector3};

fn moments(t: Matrix3<f64>) -> Vec<f64> {
    let mut v: Vec<f64> = SymmetricEigen::new(t).eigenvalues.iter().copied().collect();
    v.sort_by(f64::total_cmp);
    v
}

#[test]
fn irreducible_cubics_show_their_moments_in_json_and_on_the_page() {
    let out = mechbook(&["check", "--json", "tests/course"]);
    assert_eq!(out.status.code(), Some(0), "{}", crate::stderr(&out));
    let json: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    let scene = |id: &str| {
        json["scenes"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["id"] == id)
            .unwrap_or_else(|| panic!("no scene {id}"))
            .clone()
    };
    // The box [0,1]×[0,2]×[0,3] of unit mass about its corner: I_xx = (b² + c²)/3,
    // I_xy = −ab/4, and so on.
    let (a, b, c) = (1.0, 2.0, 3.0);
    let box_tensor = Matrix3::new(
        (b * b + c * c) / 3.0,
        -a * b / 4.0,
        -a * c / 4.0,
        -a * b / 4.0,
        (a * a + c * c) / 3.0,
        -b * c / 4.0,
        -a * c / 4.0,
        -b * c / 4.0,
        (a * a + b * b) / 3.0,
    );
    // Σ m (r² 𝟙 − r rᵀ) over the three points of 02-three-points.toml at m = d = 1.
    let points = [
        (1.0, Vector3::new(1.0, 0.0, 0.0)),
        (2.0, Vector3::new(0.0, 1.0, 1.0)),
        (3.0, Vector3::new(1.0, 2.0, 0.0)),
    ];
    let point_tensor = points.iter().fold(Matrix3::zeros(), |t, (m, r)| {
        t + *m * (Matrix3::identity() * r.norm_squared() - r * r.transpose())
    });
    let build = scratch("course-site");
    let site = build.join("site");
    let built = mechbook(&["build", "tests/course", "--out", site.to_str().unwrap()]);
    assert_eq!(built.status.code(), Some(0), "{}", crate::stderr(&built));
    for (id, tensor) in [("box-123", box_tensor), ("three-points", point_tensor)] {
        let s = scene(id);
        assert_eq!(s["passed"], true, "{id}");
        let p = &s["principal_moments"];
        assert_eq!(p["closed_form"], true, "{id}: the cubic should not factor");
        let expected = moments(tensor);
        for (k, want) in expected.iter().enumerate() {
            let got = p["values"][k].as_f64().unwrap();
            assert!(
                (got - want).abs() < 1e-13 * want.abs().max(1.0),
                "{id} λ{k}: {got} vs {want}"
            );
        }
        let page = std::fs::read_to_string(site.join(format!("{id}.html"))).unwrap();
        assert!(page.contains("Principal moments at the scene"), "{id}");
        for want in &expected {
            let shown = format!("<mn>{}</mn>", mechbook::base::format::significant(*want, 6));
            assert!(page.contains(&shown), "{id}: {shown} not on the page");
        }
        // The closed form is a step of the worked solution.
        assert!(page.contains("Principal moments in closed form"), "{id}");
    }
    // The box's principal-axes plot draws three axes, not floating dots.
    let svg = std::fs::read_to_string(site.join("plots/box-123-principal-axes.svg")).unwrap();
    assert!(
        svg.contains("I = 0.5689") && svg.contains("I = 4.5556"),
        "axes missing"
    );
    let _ = std::fs::remove_dir_all(build);
}

#[test]
fn the_check_table_keeps_its_columns_with_lectures_named_in_words() {
    let out = mechbook(&["check", "tests/course"]);
    let text = stdout(&out);
    assert_eq!(out.status.code(), Some(0), "{text}");
    // "Bodies of revolution" is wider than the header's "lect": every row still ends its status
    // in the header's last column.
    let rows: Vec<&str> = text.lines().take_while(|l| !l.is_empty()).collect();
    assert!(rows.len() >= 8, "{text}");
    let width = rows[0].chars().count();
    for row in &rows[1..] {
        assert_eq!(row.chars().count(), width, "misaligned: {row}\n{text}");
    }
}

#[test]
fn a_course_of_its_own_cites_no_equation_of_the_shipped_notes() {
    let build = scratch("course-neutral");
    let site = build.join("site");
    let built = mechbook(&["build", "tests/course", "--out", site.to_str().unwrap()]);
    assert_eq!(built.status.code(), Some(0), "{}", crate::stderr(&built));
    let mut pages = 0;
    for entry in walk(&site) {
        if entry.extension().is_some_and(|x| x == "html") {
            let text = std::fs::read_to_string(&entry).unwrap();
            for needle in ["eq (", "eqs (", "as in the notes", "Lecture Sheet"] {
                assert!(!text.contains(needle), "{}: `{needle}`", entry.display());
            }
            pages += 1;
        }
    }
    assert!(pages >= 7, "{pages} pages");
    // Titles from the course's mechbook.toml, or the lecture's own name; the course and its
    // author on every handout.
    let index = std::fs::read_to_string(site.join("index.html")).unwrap();
    assert!(index.contains("<h2>Sheet 1: bodies whose moments do not factor</h2>"));
    assert!(index.contains("<h2>Bodies of revolution</h2>"));
    let handout = std::fs::read_to_string(site.join("handouts/lecture-1-student.html")).unwrap();
    assert!(handout.contains("Moments of inertia beyond the lecture notes · A. Instructor"));
    // A common mistake written on purpose is shown as one, and counted as no erratum.
    let cone = std::fs::read_to_string(site.join("cone-apex.html")).unwrap();
    assert!(cone.contains("A common mistake, and why it is wrong"));
    assert!(!cone.contains("Erratum"));
    assert!(
        !index.contains("errat"),
        "the index counts a deliberate mistake as an erratum"
    );
    let _ = std::fs::remove_dir_all(build);
}

fn walk(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(walk(&p));
        } else {
            out.push(p);
        }
    }
    out
}

#[test]
fn a_conflict_between_the_two_tests_is_undecided_never_an_erratum() {
    // sin(π/3 + θ) = sin θ/2 + √3 cos θ/2 is true, but the symbolic test expands only quarter
    // turns: it says "not zero" while every random point says zero.
    let dir = scratch("undecided");
    let scene = dir.join("third.toml");
    std::fs::write(
        &scene,
        "id = \"third\"\ntitle = \"t\"\nnotes = { lecture = \"T\" }\nsymbols = { theta = \"angle\" }\n[outputs]\nwant = []\n[[claim]]\neq = \"1\"\nstatement = \"a third of a turn\"\nquantity = \"sin(pi/3 + theta)\"\nvalue = \"sin(theta)/2 + sqrt(3)*cos(theta)/2\"\nexpect = \"agrees\"\n",
    )
    .unwrap();
    let out = mechbook(&["check", scene.to_str().unwrap()]);
    let text = stdout(&out);
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(
        text.contains("Undecided: the symbolic and random-point tests disagree (1)"),
        "{text}"
    );
    assert!(
        text.contains("says the difference is not zero, the test at 3 random points says zero"),
        "{text}"
    );
    assert!(
        text.contains("verdict undecided but the scene records agrees"),
        "{text}"
    );
    assert!(!text.contains("Where the notes disagree"), "{text}");
    let _ = std::fs::remove_dir_all(dir);
}

/// 07-book-flip.toml's flip plot takes `inertia = "principal"`: the moments in its caption are
/// the table's m(w² + d²)/12, m(h² + d²)/12, m(w² + h²)/12 for a box about its centre, although
/// the scene's box sits on its corner.
#[test]
fn a_flip_plot_takes_the_books_own_moments() {
    let build = scratch("course-book");
    let site = build.join("site");
    let built = mechbook(&["build", "tests/course", "--out", site.to_str().unwrap()]);
    assert_eq!(built.status.code(), Some(0), "{}", crate::stderr(&built));
    let svg = std::fs::read_to_string(site.join("plots/book-flip-flip.svg")).unwrap();
    let after = svg.split("of I = (").nth(1).expect("the caption names I");
    let shown: Vec<f64> = after[..after.find(')').unwrap()]
        .split(", ")
        .map(|x| x.parse().unwrap())
        .collect();
    let (m, w, h, d): (f64, f64, f64, f64) = (0.4, 0.17, 0.24, 0.03);
    let table = [
        m * (w * w + d * d) / 12.0,
        m * (h * h + d * d) / 12.0,
        m * (w * w + h * h) / 12.0,
    ];
    // The caption gives six significant figures (0.000993333): half a unit in the sixth. The
    // moments about the corner differ from these in the first figure.
    for (got, want) in shown.iter().zip(table) {
        assert!((got - want).abs() <= 5e-6 * want, "{shown:?} vs {table:?}");
    }
    assert!(svg.contains("flips"), "no flips measured");
    let _ = std::fs::remove_dir_all(build);
}

/// The physical pendulum, written as the instructor's own steps: each derived and checked by a
/// numeric route, the notes' forms agreeing at their lines, and Ω equal to √(3g/2L) computed
/// here at the scene's values; the page shows φ̇ and φ̈ and each step's numeric check.
#[test]
fn the_pendulum_is_derived_step_by_step_and_each_step_is_checked() {
    let scene = "tests/course/dynamics/01-physical-pendulum.toml";
    let out = mechbook(&["derive", "--json", scene]);
    assert_eq!(out.status.code(), Some(0), "{}", crate::stderr(&out));
    let json: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    let (g, l) = (9.81f64, 1.5f64);
    let omega = json["quantities"]["Omega"]["numeric"].as_f64().unwrap();
    assert!(
        (omega - (3.0 * g / (2.0 * l)).sqrt()).abs() < 1e-12,
        "{omega}"
    );
    let checks = json["step_checks"].as_array().unwrap();
    let names: Vec<&str> = checks.iter().map(|c| c["step"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        ["Ip", "Lag", "eom", "p_phi", "small", "Omega", "period"]
    );
    for c in checks {
        assert_eq!(c["passed"], true, "{c}");
        assert!(
            c["error"].as_f64().unwrap() <= c["tolerance"].as_f64().unwrap(),
            "{c}"
        );
    }
    // The moment, the frequency and the period in its textbook form, 2π√(2L/(3g)); the
    // simple pendulum's period set beside them as a common mistake.
    let claims = json["claims"].as_array().unwrap();
    assert_eq!(claims.len(), 5);
    assert!(
        claims.iter().all(|c| c["passed"] == true
            && c["verdict"]
                == if c["eq"] == "6.6" {
                    "disagrees"
                } else {
                    "agrees"
                }),
        "{claims:?}"
    );

    let build = scratch("course-pendulum");
    let site = build.join("site");
    let built = mechbook(&["build", "tests/course", "--out", site.to_str().unwrap()]);
    assert_eq!(built.status.code(), Some(0), "{}", crate::stderr(&built));
    let page = std::fs::read_to_string(site.join("physical-pendulum.html")).unwrap();
    assert!(
        page.contains("<mi>ϕ</mi></mrow><mi>˙</mi>"),
        "no φ̇ on the page"
    );
    assert!(
        page.contains("<mi>ϕ</mi></mrow><mi>¨</mi>"),
        "no φ̈ on the page"
    );
    // The author's steps' checks, and the tensor's: printed with M L²/3 in front, its line is
    // compared entry by entry with the exact tensor.
    assert_eq!(page.matches("<summary>numeric check</summary>").count(), 8);
    let _ = std::fs::remove_dir_all(build);
}

/// A step that cannot be derived (a linearisation about a state that is not at rest) stops its
/// scene with one message at the step's own line, naming what is left over.
#[test]
fn a_step_that_cannot_be_derived_is_reported_at_its_line() {
    let out = mechbook(&["check", "tests/fixtures/step-not-at-rest.toml"]);
    let err = crate::stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains(
            "tests/fixtures/step-not-at-rest.toml:26:1: scene `bead` could not be derived: step \
             `small`: the state given by `about` is not at rest: the equation of `x` leaves k \
             there, not 0; give an equilibrium"
        ),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}

/// `solve` of an irreducible quintic stops the scene at the step's line, naming the factor, its
/// degree (closed forms go to degree two) and its roots at the scene's values.
#[test]
fn solve_of_degree_five_is_reported_at_its_line() {
    let out = mechbook(&["check", "tests/fixtures/step-solve-degree-5.toml"]);
    let err = crate::stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains(
            "tests/fixtures/step-solve-degree-5.toml:24:1: scene `quintic` could not be derived: \
             step `x0`: the equation has the factor a*x + b - k*x^5 of degree 5 in `x`"
        ),
        "{err}"
    );
    // Its one real root at k = 3, a = 1, b = 0.5 (3x⁵ − x − 0.5 = 0 by bisection: 0.852744…).
    assert!(
        err.contains("at the scene's values its roots are") && err.contains(", 0.852744"),
        "{err}"
    );
}
