//! The results a scene recorded in `[expect]` against those derived now: `check` fails when a
//! derivation changes, and before anything is recorded each result waits for review.

use super::{RegressionResult, claim_env};
use crate::cas;
use crate::derive::Derivation;
use crate::derive::algebra::evaluate;
use crate::model::catalogue::recorded_names;
use crate::scene::Scene;

pub fn check_regressions(
    scene: &Scene,
    d: &Derivation,
) -> Result<Vec<RegressionResult>, cas::CasError> {
    let env = claim_env(scene, d);
    let mut out = Vec::new();
    if scene.expect.is_empty() {
        // Nothing recorded yet: each result fails until it is reviewed, as an unrecorded
        // claim does.
        for name in recorded_names() {
            if let Some(v) = d.quantities.get(name) {
                out.push(RegressionResult {
                    quantity: name.to_string(),
                    recorded: None,
                    line: scene.id_at.0,
                    derived: Some(v.clone()),
                    unchanged: false,
                });
            }
        }
        return Ok(out);
    }
    for (name, recorded) in &scene.expect {
        let derived = d.quantities.get(name);
        let recorded_value = evaluate(recorded, &env);
        let unchanged = match (derived, &recorded_value) {
            (Some(a), Ok(b)) if std::mem::discriminant(a) == std::mem::discriminant(b) => {
                crate::derive::values_equal(a, b)?
            }
            _ => false,
        };
        out.push(RegressionResult {
            quantity: name.clone(),
            recorded: Some(recorded.clone()),
            line: scene
                .expect_lines
                .get(name)
                .copied()
                .unwrap_or(scene.id_at.0),
            derived: derived.cloned(),
            unchanged,
        });
    }
    Ok(out)
}
