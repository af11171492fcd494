//! A derivative whose quotient rule would expand past the engine's budget: the second
//! derivative of a heavy top's effective potential with (I₁ + M l²) in its denominator
//! (degree 32 as written) is derived with the denominator kept factored, agrees with the form
//! worked by hand, passes its central-difference check, and a wrong form disagrees.

use crate::pipeline::run_scene;
use crate::scene::{Scene, Verdict};
use std::path::Path;

fn scene(gives: &str) -> String {
    include_str!("../../tests/fixtures/unit/effective-potential-curvature.toml")
        .replace("{gives}", gives)
}

/// By hand, with c = cos θ, s = sin θ and I = I₁ + M l²:
/// U'' = ((pφ² + pψ²)(1 + 2c²) − pφ pψ c (5 + c²))/(I s⁴) − M g l c.
#[test]
fn an_effective_potentials_curvature_stays_within_the_budget() {
    let right = "((pphi^2 + ppsi^2)*(1 + 2*cos(theta)^2) - pphi*ppsi*cos(theta)*(5 + cos(theta)^2))/((I1 + M*l^2)*sin(theta)^4) - M*g*l*cos(theta)";
    let r = run_scene(
        Scene::parse(&scene(right), Path::new("p.toml")).unwrap(),
        None,
    )
    .unwrap();
    r.assert_steps_pass();
    let gives = |r: &crate::pipeline::SceneReport| {
        r.verification
            .claims
            .iter()
            .find(|c| c.quantity == Some(crate::cas::Expr::sym("ddU")))
            .map(|c| c.verdict)
    };
    assert_eq!(gives(&r), Some(Verdict::Agrees));
    // The hand form with 4 for 5: disagrees.
    let wrong = right.replace("(5 + cos", "(4 + cos");
    let r = run_scene(
        Scene::parse(&scene(&wrong), Path::new("p.toml")).unwrap(),
        None,
    )
    .unwrap();
    assert_eq!(gives(&r), Some(Verdict::Disagrees));
}
