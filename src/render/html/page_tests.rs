//! The result at the scene's numbers, as a page prints it.

use super::*;

#[test]
fn a_result_at_the_numbers_prints_six_figures_and_names_its_symbols() {
    let v = Value::Scalar(Expr::mul(vec![
        Expr::int(2),
        Expr::sym("pi"),
        Expr::sym("R"),
    ]));
    let at = At {
        symbols: vec![("R".into(), 2.0)],
        numbers: vec![4.0 * std::f64::consts::PI],
        units: [("R".to_string(), "m".to_string())].into(),
        unit: Some("m".into()),
    };
    let html = at_numbers_html(&v, &at, Names::none()).unwrap();
    assert!(html.starts_with("at <math"), "{html}");
    crate::base::assert_says(&html, &["<mi>R</mi>", "<mn>12.5664</mn>"]);
    // Each number with its unit: R = 2 m, and the result's 12.5664 m.
    assert_eq!(html.matches(">m</mi>").count(), 2, "{html}");
}
