//! A value put in where the expression has none: 0/0 is named, with the `series` step that
//! takes its limit (which then gives the limit); a pole is named as one; a divisor that is 0
//! as written is refused; a value where the expression has one is put in as before.

use crate::derive::variants::step_values;
use crate::pipeline::{SceneReport, run_scene};
use crate::scene::Scene;
use std::path::Path;

fn scene(f: &str, last: &str) -> String {
    include_str!("../../tests/fixtures/unit/value-at-special-point.toml")
        .replace("{f}", f)
        .replace("{last}", last)
}

fn run(text: &str) -> Result<SceneReport, String> {
    run_scene(Scene::parse(text, Path::new("p.toml")).unwrap(), None).map_err(|e| e.to_string())
}

fn f0(r: &SceneReport) -> f64 {
    step_values(&r.scene, &r.derivation)["f0"]
        .eval(&|s| r.scene.values.get(s).copied())
        .unwrap()
}

#[test]
fn zero_over_zero_is_named_with_the_limit_that_takes_it() {
    let err = run(&scene(
        "a*sin(x)/x",
        "substitute = \"f\"\nset = { x = \"0\" }",
    ))
    .unwrap_err();
    assert!(err.contains("at x = 0, `f` is 0/0"), "{err}");
    let suggested = err
        .split("step, ")
        .nth(1)
        .expect("a suggested step")
        .replace('`', "")
        .replace(", about", "\nabout")
        .replace(", order", "\norder");
    assert_eq!(
        suggested,
        "series = \"f\"\nabout = { x = \"0\" }\norder = 0"
    );
    // The suggested step, as written, gives the limit a (2 at the scene's values).
    let r = run(&scene("a*sin(x)/x", &suggested)).unwrap();
    assert!((f0(&r) - 2.0).abs() < 1e-15, "{}", f0(&r));
    r.assert_steps_pass();
    // (1 − cos x)/x² is 0/0 too; its limit is a/2.
    let err = run(&scene(
        "a*(1 - cos(x))/x^2",
        "substitute = \"f\"\nset = { x = \"0\" }",
    ))
    .unwrap_err();
    assert!(err.contains("is 0/0"), "{err}");
    let r = run(&scene("a*(1 - cos(x))/x^2", &suggested)).unwrap();
    assert!((f0(&r) - 1.0).abs() < 1e-15, "{}", f0(&r));
}

#[test]
fn a_pole_and_a_divisor_zero_as_written_are_refused_and_a_value_is_put_in() {
    let err = run(&scene("a/x", "substitute = \"f\"\nset = { x = \"0\" }")).unwrap_err();
    crate::base::assert_says(&err, &["the divisor x of `f` vanishes", "a pole there"]);
    let err = run(&scene(
        "a*sin(0)/sin(0)",
        "substitute = \"f\"\nset = { x = \"1\" }",
    ))
    .unwrap_err();
    crate::base::assert_says(&err, &["the divisor sin(0) of", "is 0 as written"]);
    let r = run(&scene(
        "a*sin(x)/x",
        "substitute = \"f\"\nset = { x = \"1\" }",
    ))
    .unwrap();
    assert!((f0(&r) - 2.0 * 1f64.sin()).abs() < 1e-15, "{}", f0(&r));
}
