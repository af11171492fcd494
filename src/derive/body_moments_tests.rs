//! `inertia = "principal"`: the free top with the moments of the scene's own body, against the
//! textbook's cone moments in floating point and an integration of Euler's equations; a body
//! that is not a symmetric top, or not along the axes, is an error that says so.

use crate::model::catalogue::quantity;
use crate::pipeline::{SceneReport, run_scene};
use crate::scene::{Scene, Verdict};
use std::path::Path;

fn scene(text: &str) -> Result<SceneReport, String> {
    let s = Scene::parse(text, Path::new("t.toml")).map_err(|e| e.to_string())?;
    run_scene(s, None).map_err(|e| e.to_string())
}

fn free_cone(body: &str) -> String {
    let text = std::fs::read_to_string("tests/course/dynamics/10-free-cone.toml").unwrap();
    let start = text.find("[[body]]").unwrap();
    let end = text.find("[outputs]").unwrap();
    format!("{}{body}\n{}", &text[..start], &text[end..])
}

fn rate_at(r: &SceneReport) -> f64 {
    r.derivation
        .scalar(quantity::PRECESSION_RATE)
        .unwrap()
        .eval(&|s| r.scene.values.get(s).copied())
        .unwrap()
}

#[test]
fn a_cone_is_a_free_top_with_its_own_moments() {
    let r = scene(&free_cone(
        "[[body]]\nkind = \"cone\"\nradius = \"R\"\nheight = \"h\"\nmass = \"M\"\norigin = \"centre\"",
    ))
    .unwrap();
    assert!(
        r.verification
            .claims
            .iter()
            .all(|c| c.verdict == Verdict::Agrees)
    );
    // β ω3 with the textbook's cone about its centre of mass: I1 = 3/80 M (4R² + h²),
    // I3 = 3/10 M R².
    let (m, rr, h, w3) = (1.0f64, 0.3f64, 0.4f64, 2.0f64);
    let (i1, i3) = (3.0 / 80.0 * m * (4.0 * rr * rr + h * h), 0.3 * m * rr * rr);
    let rate = rate_at(&r);
    assert!((rate - (i3 - i1) / i1 * w3).abs() < 1e-14, "{rate}");
    // The numeric route integrates Euler's equations with the quadrature's moments.
    let check = r
        .verification
        .quantities
        .iter()
        .find(|q| q.name == quantity::PRECESSION_RATE)
        .expect("the precession rate is checked numerically");
    assert!(check.passed && check.error < 1e-12, "{check:?}");
    // The same cone off its centre: the moments are still about the centre of mass.
    let apex = scene(&free_cone(
        "[[body]]\nkind = \"cone\"\nradius = \"R\"\nheight = \"h\"\nmass = \"M\"\norigin = \"apex\"",
    ))
    .unwrap();
    let apex_rate = rate_at(&apex);
    assert!((apex_rate - rate).abs() < 1e-14);
}

#[test]
fn a_body_that_is_no_symmetric_top_is_an_error() {
    let brick = free_cone(
        "[[body]]\nkind = \"box\"\nsize = [\"R\", \"2*R\", \"h\"]\nmass = \"M\"\norigin = \"centre\"",
    );
    let e = scene(&brick).unwrap_err();
    assert!(e.contains("the body is not a symmetric top"), "{e}");
    let tilted = free_cone(
        "[[body]]\nkind = \"cone\"\nradius = \"R\"\nheight = \"h\"\nmass = \"M\"\norigin = \"centre\"\nrotate = [{ axis = \"x\", angle = \"pi/6\" }]",
    );
    let e = scene(&tilted).unwrap_err();
    assert!(e.contains("symmetry axes are x, y and z"), "{e}");
}

#[test]
fn inertia_principal_is_checked_where_it_is_written() {
    let text = free_cone(
        "[[body]]\nkind = \"cone\"\nradius = \"R\"\nheight = \"h\"\nmass = \"M\"\norigin = \"centre\"",
    );
    let with_symbol = text.replace("symbols = { M", "symbols = { I1 = \"a moment\", M");
    let e = scene(&with_symbol).unwrap_err();
    assert!(e.contains("`I1` cannot also be a symbol"), "{e}");
    let other = text.replace("inertia = \"principal\"", "inertia = \"given\"");
    let e = scene(&other).unwrap_err();
    assert!(e.contains("the one choice is \"principal\""), "{e}");
    let without = text.replace("\"symmetric_top\", ", "");
    let e = scene(&without).unwrap_err();
    assert!(e.contains("add one of them to want"), "{e}");
}

/// tests/course/dynamics/12-tumbling-box.toml: Euler's equations, the axes' stability and
/// Poinsot's construction with a box's own moments. Each Ω_k² against the textbook's box
/// moments in floating point (I1 = M(b² + c²)/12 about x, …), and each result that has a
/// numeric route (the quadrature's tensor and Euler's equations as matrix arithmetic) within
/// 1e-13 of it.
#[test]
fn a_box_tumbles_with_its_own_moments() {
    let text = std::fs::read_to_string("tests/course/dynamics/12-tumbling-box.toml").unwrap();
    let r = scene(&text).unwrap();
    assert!(
        r.verification
            .claims
            .iter()
            .all(|c| c.verdict == Verdict::Agrees)
    );
    let v = |s: &str| r.scene.values[s];
    let (m, a, b, c) = (v("M"), v("a"), v("b"), v("c"));
    let i = [
        m * (b * b + c * c) / 12.0,
        m * (a * a + c * c) / 12.0,
        m * (a * a + b * b) / 12.0,
    ];
    let w = [v("w1"), v("w2"), v("w3")];
    let exact = r
        .derivation
        .quantities
        .get(quantity::OSCILLATION_FREQUENCY_SQUARED)
        .unwrap()
        .numbers_at(&r.scene.values)
        .unwrap();
    for k in 0..3 {
        let (p, q) = ((k + 1) % 3, (k + 2) % 3);
        let textbook = w[k] * w[k] * (i[k] - i[p]) * (i[k] - i[q]) / (i[p] * i[q]);
        assert!(
            (exact[k] - textbook).abs() < 1e-13 * textbook.abs(),
            "axis {}: {} against {textbook}",
            k + 1,
            exact[k]
        );
    }
    // The middle axis y is the unstable one: Ω₂² < 0 < Ω₁², Ω₃².
    assert!(
        exact[1] < 0.0 && exact[0] > 0.0 && exact[2] > 0.0,
        "{exact:?}"
    );
    let checked: Vec<&str> = r
        .verification
        .quantities
        .iter()
        .map(|q| q.name.as_str())
        .collect();
    for name in [
        quantity::TORQUE_FREE_RATES,
        quantity::TWICE_ENERGY,
        quantity::MOMENTUM_SQUARED,
        quantity::OSCILLATION_FREQUENCY_SQUARED,
        quantity::GROWTH_RATE_SQUARED,
    ] {
        assert!(
            checked.contains(&name),
            "{name} has no numeric route: {checked:?}"
        );
    }
    for q in &r.verification.quantities {
        assert!(q.passed && q.error < 1e-13, "{q:?}");
    }
}

/// With Euler's equations beside the free top, I1, I2 and I3 are the moments about x, y and z,
/// so a cone must stand along z; along x it is an error that says so.
#[test]
fn with_the_other_families_a_top_stands_along_z() {
    let text = std::fs::read_to_string("tests/course/dynamics/10-free-cone.toml").unwrap();
    let both = text
        .replace(
            "want = [\"symmetric_top\", \"numeric\"]",
            "want = [\"symmetric_top\", \"euler_equations\", \"numeric\"]",
        )
        .replace(
            "symbols = { M",
            "symbols = { wd1 = \"r\", wd2 = \"r\", wd3 = \"r\", N1 = \"n\", N2 = \"n\", N3 = \"n\", M",
        )
        .replace("values = { M", "values = { wd1 = 0.0, wd2 = 0.0, wd3 = 0.0, N1 = 0.0, N2 = 0.0, N3 = 0.0, M");
    let r = scene(&both).unwrap();
    assert!(
        r.derivation
            .quantities
            .contains_key(quantity::TORQUE_FREE_RATES)
    );
    let along_x = both.replace(
        "origin = \"centre\"",
        "origin = \"centre\"\nrotate = [{ axis = \"y\", angle = \"pi/2\" }]",
    );
    let e = scene(&along_x).unwrap_err();
    assert!(e.contains("two equal moments about x and y"), "{e}");
}
