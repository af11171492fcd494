//! A claim that names a step's result the derivation did not give: `acc_5` of a `solve` with
//! two unknowns, or `rest_2` of a state of several coordinates, which claims cannot name yet.
//! Left unbound, the name stood for itself and the claim "disagreed" with it.

use crate::derive::algebra::Env;
use crate::scene::Scene;

/// Why `e` cannot be checked: the first name a step would give that is not bound in `env`,
/// with the names that step did give.
pub(super) fn unbound_result(scene: &Scene, env: &Env, e: &crate::cas::Expr) -> Option<String> {
    let coordinates = scene.coordinates.len();
    e.symbols().into_iter().find_map(|name| {
        if env.contains_key(&name) {
            return None;
        }
        let step = scene
            .steps
            .iter()
            .find(|s| s.names_given(coordinates).contains(&name))?;
        let given: Vec<String> = step
            .names_given(coordinates)
            .into_iter()
            .filter(|n| env.contains_key(n))
            .collect();
        Some(if given.is_empty() {
            format!(
                "`{name}` is no result of step `{}`, which gives none a claim can name (a state \
                 of several coordinates is named by its `linearise` step's `about`)",
                step.name
            )
        } else {
            format!(
                "`{name}` is no result of step `{}`, which gives {}",
                step.name,
                given.join(", ")
            )
        })
    })
}
