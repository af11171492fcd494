//! The expression plot of an effective potential: the curve is the derived result, its
//! lowest point is where the derived slope vanishes (found here by bisection), the second
//! route's dots agree with it, a wrong result is caught by them, and the plot's fields are
//! checked where they are written.

use crate::cas::parse;
use crate::derive::step_names::StepResult;
use crate::model::fidelity::Fidelity;
use crate::pipeline::{SceneReport, run_scene};
use crate::scene::Scene;
use std::path::Path;

fn scene(plots: &str) -> Result<SceneReport, String> {
    let text = include_str!("../../tests/fixtures/unit/effective-potential-plot.toml")
        .replace("{plots}", plots);
    let s = Scene::parse(&text, Path::new("p.toml")).map_err(|e| e.to_string())?;
    run_scene(s, None).map_err(|e| e.to_string())
}

const PLOTS: &str = r#"
[[plot]]
kind = "expression"
step = "U"
over = "theta"
range = ["0.3", "pi - 0.3"]
[[plot]]
kind = "expression"
step = "dU"
over = "theta"
range = ["0.3", "pi - 0.3"]
samples = 5
"#;

#[test]
fn the_curve_is_the_result_and_its_lowest_point_is_where_the_slope_vanishes() {
    let r = scene(PLOTS).unwrap();
    let u = &r.figures[0];
    assert_eq!(u.slug, "U-vs-theta");
    let exact = r.derivation.named["U"].scalar().unwrap();
    let at = |e: &crate::cas::Expr, x: f64| {
        e.eval(&|s| {
            if s == "theta" {
                Some(x)
            } else {
                r.scene.values.get(s).copied()
            }
        })
        .unwrap()
    };
    for (x, y) in &u.series[0].points {
        assert_eq!(*y, at(exact, *x));
    }
    assert_eq!(u.series[0].points.len(), 181);
    // The second route: the expression as written (9 dots), and for dU central differences
    // of U (5 dots); both agree with the curve.
    assert_eq!(u.series[1].points.len(), 9);
    assert!(
        u.accuracy[0].true_error.unwrap() < 1e-14,
        "{:?}",
        u.accuracy
    );
    let du = &r.figures[1];
    assert_eq!(du.series[1].points.len(), 5);
    assert!(
        du.accuracy[0].true_error.unwrap() < 1e-8,
        "{:?}",
        du.accuracy
    );
    // The lowest point drawn is within one grid step of the zero of the derived slope,
    // bisected on the expression written by hand.
    let slope = parse("-I1*(a - b*cos(theta))*(a*cos(theta) - b)/sin(theta)^3 - M*g*l*sin(theta)")
        .unwrap()
        .expr;
    let (mut lo, mut hi) = (0.3, std::f64::consts::PI - 0.3);
    assert!(at(&slope, lo) < 0.0 && at(&slope, hi) > 0.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if at(&slope, mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let lowest = u.series[0]
        .points
        .iter()
        .min_by(|p, q| p.1.total_cmp(&q.1))
        .unwrap()
        .0;
    let step = (std::f64::consts::PI - 0.6) / 180.0;
    assert!((lowest - lo).abs() <= step, "{lowest} against {lo}");
    assert!(
        u.desc.to_text().contains(&format!("at θ = {lowest:.4}")),
        "{}",
        u.desc
    );
}

/// A wrong result (the potential's gravity term with the wrong sign) is drawn, but the dots of
/// the expression as written stand away from it, and the accuracy says by how much.
#[test]
fn the_second_route_catches_a_wrong_result() {
    let r = scene(PLOTS).unwrap();
    let mut d = r.derivation.clone();
    let wrong = parse("I1*(a - b*cos(theta))^2/(2*sin(theta)^2) - M*g*l*cos(theta)")
        .unwrap()
        .expr;
    d.named.insert("U".into(), StepResult::Expr(wrong));
    let figures = crate::figures::figures(&r.scene, &d, &Fidelity::default()).unwrap();
    let error = figures[0].accuracy[0].true_error.unwrap();
    assert!(error > 0.1, "{error}");
}

#[test]
fn an_expression_plots_fields_are_checked_where_they_are_written() {
    let plot = |body: &str| scene(&format!("[[plot]]\nkind = \"expression\"\n{body}")).unwrap_err();
    let e = plot("over = \"theta\"\nrange = [\"0.3\", \"1\"]");
    assert!(e.contains("needs `step`"), "{e}");
    let e = plot("step = \"U\"\nover = \"phi\"\nrange = [\"0.3\", \"1\"]");
    assert!(
        e.contains("`phi` is not a coordinate, a rate or a declared symbol"),
        "{e}"
    );
    let e = plot("step = \"U\"\nover = \"theta\"\nrange = [\"1\", \"0.3\"]");
    assert!(e.contains("from < to"), "{e}");
    let e =
        plot("step = \"U\"\nover = \"theta\"\nrange = [\"0.3\", \"1\"]\nstart = { theta = 1.0 }");
    assert!(e.contains("takes `at`"), "{e}");
    let e = scene(
        "[[plot]]\nkind = \"tensor-sweep\"\nover = \"theta\"\nrange = [\"0\", \"1\"]\nat = { a = 1.0 }",
    )
    .unwrap_err();
    assert!(e.contains("`at` belongs to an expression plot"), "{e}");
    // A name without a value, found when drawing: the message says where to give it, and
    // giving it there draws the plot.
    let e = scene(
        "[[plot]]\nkind = \"expression\"\nstep = \"U\"\nover = \"a\"\nrange = [\"0.3\", \"1\"]",
    )
    .unwrap_err();
    assert!(e.contains("p.toml:22:1: plot[0]"), "{e}");
    assert!(
        e.contains(
            "`theta` in step `U` has no value: give it one in the plot's `at = { theta = … }`"
        ),
        "{e}"
    );
    let r = scene(
        "[[plot]]\nkind = \"expression\"\nstep = \"U\"\nover = \"a\"\nrange = [\"0.3\", \"1\"]\nat = { theta = 0.5 }",
    )
    .unwrap();
    assert_eq!(r.figures[0].series[0].points.len(), 181);
}
