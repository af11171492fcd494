//! The notes' claims against the derivation: each claim's two sides evaluated, then decided
//! equal symbolically and at random points, over positive symbols, under the scene's
//! assumptions and by their squares; where the two tests disagree, undecided.

use super::rounding::rounded_agreement;
use super::{CONFIRMATION_POINTS, ClaimResult, assumed, result_names, squares};
use crate::cas::{self, Expr};
use crate::derive::algebra::{Env, Value, evaluate};
use crate::derive::{Derivation, simplify_value};
use crate::model::prose::Prose;
use crate::numeric::random_points::{numerically_zero, signed_names};
use crate::scene::{Scene, Verdict};

/// The names a claim may use, bound to their values: a step's (`derive::step_names`), and the
/// scene's ω and axis.
pub fn claim_env(scene: &Scene, d: &Derivation) -> Env {
    let mut env = crate::derive::step_names::names_env(scene, d);
    // A quantity or a step's result of the same name wins, as it was bound after these.
    if let Some(w) = &scene.omega {
        env.entry("omega".into())
            .or_insert_with(|| Value::Vector(w.clone()));
    }
    if let Some(n) = &scene.axis {
        env.entry("axis".into())
            .or_insert_with(|| Value::Vector(n.clone()));
    }
    env
}

pub fn check_claims(scene: &Scene, d: &Derivation) -> Result<Vec<ClaimResult>, cas::CasError> {
    let env = claim_env(scene, d);
    let mut out = Vec::new();
    for (i, claim) in scene.claims.iter().enumerate() {
        let numeric = [&claim.quantity, &claim.value]
            .into_iter()
            .flatten()
            .find_map(|e| d.numeric_name_in(scene, e));
        let unbound = [&claim.quantity, &claim.value]
            .into_iter()
            .flatten()
            .find_map(|e| result_names::unbound_result(scene, &env, e));
        let problem = numeric
            .map(|(name, step)| crate::derive::step_names::numeric_only(&name, &step))
            .or(unbound);
        if let Some(problem) = problem {
            let mut r = unchecked(claim);
            r.problem = Some(problem);
            out.push(r);
            continue;
        }
        // An engine failure on one claim is that claim's problem, located at its line; the
        // other claims are still checked.
        out.push(check_claim(scene, &env, i, claim).unwrap_or_else(|e| {
            let mut r = unchecked(claim);
            r.problem = Some(format!(
                "the algebra engine failed on this claim: {}",
                e.reason
            ));
            r
        }));
    }
    Ok(out)
}

/// A claim's result before any check: not checkable, with nothing derived.
pub(super) fn unchecked(claim: &crate::scene::Claim) -> ClaimResult {
    ClaimResult {
        eq: claim.eq.clone(),
        statement: claim.statement.clone(),
        quantity: claim.quantity.clone(),
        notes: claim.value.clone(),
        derived: None,
        verdict: Verdict::NotCheckable,
        expected: claim.expect,
        differences: Vec::new(),
        problem: None,
        precision: None,
        role: claim.role,
        line: claim.line,
        step: None,
        dimension: None,
        positive: Vec::new(),
        where_real: false,
        tex: claim.tex.clone(),
        shown: None,
    }
}

pub(super) fn check_claim(
    scene: &Scene,
    env: &Env,
    i: usize,
    claim: &crate::scene::Claim,
) -> Result<ClaimResult, cas::CasError> {
    let mut r = unchecked(claim);
    let Some((as_written, derived, notes)) = sides(claim, env, &mut r)? else {
        return Ok(r);
    };
    if let Some(figures) = claim.figures {
        rounded_verdict(&mut r, &derived, &notes, figures, scene);
        return Ok(r);
    }
    if std::mem::discriminant(&derived) != std::mem::discriminant(&notes) {
        r.verdict = Verdict::Disagrees;
        r.differences.push(
            format!(
                "the notes give {}, the derivation {}",
                notes.kind(),
                derived.kind()
            )
            .into(),
        );
        return Ok(r);
    }
    let (de, ne) = (derived.entries(), notes.entries());
    let diffs: Vec<Expr> = de
        .iter()
        .zip(&ne)
        .map(|(a, b)| Expr::minus(a.clone(), b.clone()))
        .collect();
    let mut symbolic = cas::is_zero_all(diffs.clone())?;
    let scale: Vec<Expr> = de
        .iter()
        .zip(&ne)
        .map(|(a, b)| Expr::add(vec![a.clone(), b.clone()]))
        .collect();
    let signed = signed_names(scene);
    let in_domain = |p: &std::collections::BTreeMap<String, f64>| scene.in_domain(p);
    let seed = scene.seed.wrapping_add(i as u64);
    match numerically_zero(&diffs, &scale, seed, &signed, &in_domain) {
        Ok(numeric) => {
            // Not zero as written but zero at every random point: perhaps once roots are taken
            // over positive symbols, as a scene's are (√(g²) = g).
            r.positive = zero_over_positive(&diffs, &numeric, &mut symbolic, &signed)?;
            let written: Vec<Expr> = (as_written.entries().into_iter().zip(&ne))
                .map(|(a, b)| Expr::minus(a, b.clone()))
                .collect();
            assumed::second_chance(scene, [&diffs, &written], &numeric, &mut symbolic, &signed)?;
            // Both sides never negative: their squares (√a √b against √(ab), a's sign unknown).
            r.where_real = squares::third_chance(&de, &ne, &numeric, &mut symbolic, &signed)?;
            // The two tests contradict each other: report both and decide nothing. The
            // engine may have missed an identity (a "non-zero" that is zero), or the random
            // points may all have missed where the difference lives.
            let conflicts: Vec<usize> = (0..diffs.len())
                .filter(|&k| symbolic[k] != numeric[k])
                .collect();
            if !conflicts.is_empty() {
                r.verdict = Verdict::Undecided;
                for k in conflicts {
                    r.differences
                        .push(conflict(&derived.entry_label(k), symbolic[k], numeric[k]));
                }
                return Ok(r);
            }
        }
        Err(e) => r.problem = Some(format!("cannot evaluate at random points: {e}")),
    }
    r.verdict = agreement(symbolic.iter().all(|z| *z));
    if r.verdict == Verdict::Disagrees {
        r.differences
            .extend(differences(&derived, &diffs, &ne, &symbolic)?);
    }
    Ok(r)
}

/// A claim's derived side as written and simplified, and the notes' side; `None` where one
/// does not evaluate, which `r` then says.
fn sides(
    claim: &crate::scene::Claim,
    env: &Env,
    r: &mut ClaimResult,
) -> Result<Option<(Value, Value, Value)>, cas::CasError> {
    let (Some(q), Some(v)) = (&claim.quantity, &claim.value) else {
        return Ok(None);
    };
    let (as_written, derived) = match evaluate(q, env) {
        Ok(x) => (x.clone(), simplify_value(&x)?),
        Err(e) => {
            r.problem = Some(format!("the derived side does not evaluate: {e}"));
            return Ok(None);
        }
    };
    r.derived = Some(derived.clone());
    match evaluate(v, env) {
        Ok(notes) => Ok(Some((as_written, derived, notes))),
        Err(e) => {
            r.verdict = Verdict::Disagrees;
            r.differences
                .push(format!("the notes' formula is ill-formed: {e}").into());
            Ok(None)
        }
    }
}

/// Agrees, or disagrees.
fn agreement(agrees: bool) -> Verdict {
    if agrees {
        Verdict::Agrees
    } else {
        Verdict::Disagrees
    }
}

/// A claim the notes give to some figures: agreed when the derived value rounds to them.
fn rounded_verdict(
    r: &mut ClaimResult,
    derived: &Value,
    notes: &Value,
    figures: u32,
    scene: &Scene,
) {
    match rounded_agreement(derived, notes, figures, &scene.values) {
        Ok((agrees, detail)) => {
            r.verdict = agreement(agrees);
            if !agrees {
                r.differences.push(detail.clone().into());
            }
            r.precision = Some(detail);
        }
        Err(e) => r.problem = Some(e.to_string()),
    }
}

/// Differences not zero as written but zero at every random point, tried again with roots
/// taken over positive symbols, as a scene's are (√(g²) = g): each that is then zero is, and
/// the symbols its agreement takes to be positive are returned.
fn zero_over_positive(
    diffs: &[Expr],
    numeric: &[bool],
    symbolic: &mut [bool],
    signed: &std::collections::BTreeSet<String>,
) -> Result<Vec<String>, cas::CasError> {
    let retry: Vec<usize> = (0..diffs.len())
        .filter(|&k| !symbolic[k] && numeric[k])
        .collect();
    let mut positive = std::collections::BTreeSet::new();
    if retry.is_empty() {
        return Ok(Vec::new());
    }
    let again = cas::is_zero_over_positive(
        retry.iter().map(|&k| diffs[k].clone()).collect(),
        signed.clone(),
    )?;
    for (k, zero) in retry.into_iter().zip(again) {
        symbolic[k] |= zero;
        if zero {
            positive.extend(
                diffs[k]
                    .symbols()
                    .into_iter()
                    .filter(|s| s != "pi" && !signed.contains(s)),
            );
        }
    }
    Ok(positive.into_iter().collect())
}

/// The sentence for an entry whose symbolic and random-point tests disagree.
fn conflict(label: &str, symbolic: bool, numeric: bool) -> Prose {
    format!(
        "entry{}: the symbolic test says the difference is {}, the test at {CONFIRMATION_POINTS} random points says {}; check this claim by hand or restate it",
        if label.is_empty() { String::new() } else { format!(" {label}") },
        if symbolic { "zero" } else { "not zero" },
        if numeric { "zero" } else { "not zero" }
    )
    .into()
}

/// Each entry that differs: derived, the notes' (simplified) and their difference (simplified).
fn differences(
    derived: &Value,
    diffs: &[Expr],
    notes: &[Expr],
    symbolic: &[bool],
) -> Result<Vec<Prose>, cas::CasError> {
    let de = derived.entries();
    let simplified = cas::simplify_all(diffs.to_vec())?;
    let notes_simple = cas::simplify_all(notes.to_vec())?;
    let mut out = Vec::new();
    for k in (0..diffs.len()).filter(|&k| !symbolic[k]) {
        let label = derived.entry_label(k);
        let label = if label.is_empty() {
            String::new()
        } else {
            format!(" {label}")
        };
        out.push(
            Prose::default()
                .text(&format!("entry{label}: derived "))
                .expr(&de[k])
                .text(", notes ")
                .expr(&notes_simple[k])
                .text(", difference ")
                .expr(&simplified[k]),
        );
    }
    Ok(out)
}
