use crate::pipeline::run_scene;
use crate::scene::{Scene, Verdict};
use std::collections::BTreeMap;
use std::path::Path;

const SCENE: &str = include_str!("../../tests/fixtures/unit/verify-claims.toml");

fn claims(claims: &str) -> Vec<super::ClaimResult> {
    let s = Scene::parse(&format!("{SCENE}{claims}"), Path::new("t.toml")).unwrap();
    run_scene(s, None).unwrap().verification.claims
}

fn claim(quantity: &str, value: &str, expect: &str) -> String {
    format!(
        "[[claim]]\neq = \"1\"\nstatement = \"s\"\nquantity = \"{quantity}\"\nvalue = \"{value}\"\nexpect = \"{expect}\"\n"
    )
}

#[test]
fn agreeing_and_disagreeing_claims() {
    let r = claims(
        &[
            claim("inertia_tensor", "m*a^2/6*eye()", "agrees"),
            claim("inertia_tensor[0][0]", "m*a^2/12", "disagrees"),
        ]
        .concat(),
    );
    assert_eq!(r[0].verdict, Verdict::Agrees);
    assert!(r[0].passed() && r[0].differences.is_empty());
    assert_eq!(r[1].verdict, Verdict::Disagrees);
    assert!(r[1].passed());
    assert!(
        r[1].differences[0]
            .to_text()
            .contains("difference 1/12*m*a^2"),
        "{:?}",
        r[1].differences
    );
}

#[test]
fn a_wrong_recorded_verdict_fails_the_check() {
    let r = claims(&claim("inertia_tensor[1][1]", "m*a^2/6", "disagrees"));
    assert_eq!(r[0].verdict, Verdict::Agrees);
    assert!(!r[0].passed());
}

#[test]
fn ill_formed_and_mismatched_claims_disagree() {
    let r = claims(
        &[
            claim("inertia_tensor", "cross(r, dot(r, r))", "disagrees"),
            claim("inertia_tensor", "m*a^2", "disagrees"),
        ]
        .concat(),
    );
    assert!(
        r[0].differences[0].to_text().contains("ill-formed"),
        "{:?}",
        r[0].differences
    );
    assert!(
        r[1].differences[0].to_text().contains("a scalar")
            && r[1].differences[0].to_text().contains("a matrix")
    );
    assert!(r.iter().all(|c| c.passed()));
}

#[test]
fn a_derived_side_that_does_not_evaluate_is_a_problem() {
    let r = claims(&claim("r*r", "0", "agrees"));
    assert!(r[0].problem.as_ref().unwrap().contains("does not evaluate"));
    assert!(!r[0].passed());
}

#[test]
fn rough_numbers_agree_only_at_the_precision_given() {
    assert_eq!(super::round_to_figures(303.6246, 1), 300.0);
    assert_eq!(super::round_to_figures(303.6246, 3), 304.0);
    assert_eq!(super::round_to_figures(3.2845e-3, 2), 3.3e-3);
    assert_eq!(super::round_to_figures(-21.38, 1), -20.0);
    // The Earth period, 303.62 days, is "about 300" at one figure but not at three.
    let rough = |figures: u32| {
        format!(
            "[[claim]]\neq = \"89\"\nstatement = \"s\"\nquantity = \"euler_period_solar_days\"\nvalue = \"300\"\nfigures = {figures}\nexpect = \"agrees\"\n"
        )
    };
    let scene = |figures: u32| {
        format!(
            "id = \"e\"\ntitle = \"e\"\nnotes = {{ lecture = \"3/9\" }}\nsymbols = {{ A = \"a\", C = \"c\", H = \"h\" }}\n[outputs]\nwant = []\n{}",
            rough(figures)
        )
    };
    let verdict = |figures| {
        let s = Scene::parse(&scene(figures), Path::new("e.toml")).unwrap();
        run_scene(s, None).unwrap().verification.claims[0].verdict
    };
    assert_eq!(verdict(1), Verdict::Agrees);
    assert_eq!(verdict(2), Verdict::Agrees);
    assert_eq!(verdict(3), Verdict::Disagrees);
}

#[test]
fn rounded_claims_tell_apart_every_figure_they_state() {
    use super::rounding::rounded_agreement;
    use crate::cas::parse;
    use crate::model::value::Value;
    let value = |t: &str| Value::Scalar(parse(t).unwrap().expr);
    // 14 figures that differ in the last: 1e-13 apart, which a fixed 1e-12 called equal.
    let derived = value("12345678901234/10000000000000");
    let (agrees, _) =
        rounded_agreement(&derived, &value("1.2345678901235"), 14, &BTreeMap::new()).unwrap();
    assert!(!agrees);
    let (agrees, _) =
        rounded_agreement(&derived, &value("1.2345678901234"), 14, &BTreeMap::new()).unwrap();
    assert!(agrees);
    // At 3 figures the same two agree, and so does a value that rounds the same way.
    let (agrees, why) = rounded_agreement(&derived, &value("1.23"), 3, &BTreeMap::new()).unwrap();
    assert!(agrees, "{why}");
    let (agrees, _) =
        rounded_agreement(&value("2/3"), &value("0.6667"), 4, &BTreeMap::new()).unwrap();
    assert!(agrees);
    let (agrees, _) =
        rounded_agreement(&value("2/3"), &value("0.6666"), 4, &BTreeMap::new()).unwrap();
    assert!(!agrees);
}

/// A pin names the variants whose sheet differs: a changed one, and one added or removed.
#[test]
fn a_pin_names_the_sheets_that_differ() {
    let pin = |recorded: &[&str], derived: &[&str]| super::variants::Pin {
        recorded: Some(recorded.iter().map(|s| s.to_string()).collect()),
        derived: derived.iter().map(|s| s.to_string()).collect(),
        line: 1,
    };
    let same = pin(&["a", "b"], &["a", "b"]);
    assert!(same.unchanged() && same.differing().is_empty());
    assert_eq!(
        pin(&["a", "b", "c"], &["a", "x", "c", "d"]).differing(),
        [2, 4]
    );
    assert_eq!(pin(&["a", "b", "c"], &["a"]).differing(), [2, 3]);
    let unrecorded = super::variants::Pin {
        recorded: None,
        ..same
    };
    assert!(!unrecorded.unchanged());
}

/// A claim given to figures is evaluated at the scene's [numeric] values: the rod's period of
/// 2.006 s is "about 2 s" at one figure, not "about 3 s", and the page says at which values.
#[test]
fn a_rough_claim_is_read_at_the_scenes_values() {
    let text = include_str!("../../tests/fixtures/unit/rough-claim.toml");
    let r = run_scene(Scene::parse(text, Path::new("p.toml")).unwrap(), None).unwrap();
    let claim = &r.verification.claims[0];
    assert_eq!(claim.verdict, Verdict::Agrees, "{claim:?}");
    let precision = claim.precision.as_deref().unwrap_or_default();
    assert!(
        precision.contains("2.006") && precision.contains("at the scene's values"),
        "{precision}"
    );
    let three = text
        .replace("value = \"2\"", "value = \"3\"")
        .replace("\"agrees\"", "\"disagrees\"");
    let r = run_scene(Scene::parse(&three, Path::new("p.toml")).unwrap(), None).unwrap();
    assert_eq!(r.verification.claims[0].verdict, Verdict::Disagrees);
}
