//! A step's `gives`, the notes' form of its result, as a claim with a verdict: the same
//! expression, for equations of motion the same equation up to a constant factor, and for a
//! step with several results (a list) each entry against its result's name.

use super::{
    CONFIRMATION_POINTS, ClaimResult, check_claim, claim_env, numerically_zero, signed_names,
    unchecked,
};
use crate::cas::{self, Expr};
use crate::derive::Derivation;
use crate::derive::step_names::{StepResult, expand_names};
use crate::model::prose::Prose;
use crate::scene::operations::Solve;
use crate::scene::{AuthorStep, Claim, Scene, Verdict};

/// Each step's `gives`, as a claim of the notes: the same expression, or for equations of
/// motion the same equation up to a non-zero constant factor.
pub fn check_gives(scene: &Scene, d: &Derivation) -> Result<Vec<ClaimResult>, cas::CasError> {
    let env = claim_env(scene, d);
    let mut out = Vec::new();
    for (i, step) in scene.steps.iter().enumerate() {
        out.extend(check_gives_each(scene, d, &env, i)?);
        let Some(gives) = &step.gives else {
            continue;
        };
        let claim = Claim {
            eq: step.eq.clone().unwrap_or_else(|| step.name.clone()),
            // The step's reason: the pages show the claim's formula beside it.
            statement: if step.why.is_empty() {
                "the form the notes give for this step".to_string()
            } else {
                step.why.clone()
            },
            quantity: Some(Expr::sym(&step.name)),
            value: Some(gives.clone()),
            figures: None,
            expect: step.expect,
            role: step.role,
            tex: None,
            line: step.line,
        };
        let mut r = match d.named.get(&step.name) {
            Some(StepResult::Equations(eqs)) => same_equation(scene, d, step, &claim, eqs, gives)?,
            Some(
                several @ (StepResult::Modes(_)
                | StepResult::NumericModes { .. }
                | StepResult::Roots(_)
                | StepResult::Solution(_)),
            ) => {
                let names = step.result_names();
                let n = several.count(names);
                let mut r = unchecked(&claim);
                r.problem = Some(format!(
                    "this step gives {n} values, named {} to {}: state each in a claim on its \
                     name instead of `gives`",
                    names.kth(0),
                    names.kth(n.max(1) - 1),
                ));
                r
            }
            _ => check_claim(scene, &env, 10_000 + i, &claim)?,
        };
        r.step = Some(i);
        out.push(r);
    }
    Ok(out)
}

/// A list `gives` of a step with several results: each entry a claim on its result's name
/// (`Omega_1`, `Omega_2`, … in order); a list of another length than the results is a problem.
fn check_gives_each(
    scene: &Scene,
    d: &Derivation,
    env: &crate::derive::algebra::Env,
    i: usize,
) -> Result<Vec<ClaimResult>, cas::CasError> {
    let step = &scene.steps[i];
    let count = d
        .named
        .get(&step.name)
        .map_or(0, |r| r.count(step.result_names()));
    let numeric = d.numeric_names(scene);
    let names = scene.names();
    let mut out = Vec::new();
    for (k, value) in step.gives_each.iter().enumerate() {
        let name = step.result_names().kth(k);
        let claim = Claim {
            eq: step.eq.clone().unwrap_or_else(|| step.name.clone()),
            // The result's name as the page sets it (Ω₁), never as the scene spells it.
            statement: format!(
                "{} (${}$)",
                if step.why.is_empty() {
                    "the form the notes give for this step"
                } else {
                    &step.why
                },
                Expr::sym(&name).to_latex(&names)
            ),
            quantity: Some(Expr::sym(&name)),
            value: Some(value.clone()),
            figures: None,
            expect: step.expect,
            role: step.role,
            // Several unknowns print as themselves (T = …, ẍ = …), not as the step's `sol_2`.
            tex: match &step.op {
                crate::scene::Operation::Solve(Solve { unknowns, .. }) if unknowns.len() > 1 => {
                    unknowns.get(k).map(|u| Expr::sym(u).to_tex(&names))
                }
                _ => None,
            },
            line: step.line,
        };
        let mut r = if step.gives_each.len() != count {
            let mut r = unchecked(&claim);
            r.problem = Some(format!(
                "`gives` lists {} forms, but step `{}` gives {count} results: list one per \
                 result, in order",
                step.gives_each.len(),
                step.name
            ));
            r
        } else if let Some(of) = numeric.get(&name) {
            let mut r = unchecked(&claim);
            r.problem = Some(crate::derive::step_names::numeric_only(&name, of));
            r
        } else {
            check_claim(scene, env, 20_000 + 100 * i + k, &claim)?
        };
        r.step = Some(i);
        out.push(r);
    }
    Ok(out)
}

/// An equation of motion against the notes' form: the notes' residual g equals c·r for the
/// derived residual r and a constant c ≠ 0, where c is the ratio of their coefficients of the
/// first acceleration.
fn same_equation(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    claim: &Claim,
    eqs: &[(String, Expr)],
    gives: &Expr,
) -> Result<ClaimResult, cas::CasError> {
    let mut r = unchecked(claim);
    let [(q, residual)] = eqs else {
        r.problem = Some(format!(
            "`gives` states one equation; this step derives {} (one per coordinate): compare \
             them with claims",
            eqs.len()
        ));
        return Ok(r);
    };
    r.derived = Some(crate::model::value::Value::Scalar(residual.clone()));
    let notes = match expand_names(scene, d, step, gives) {
        Ok(x) => x,
        Err(e) => {
            r.problem = Some(e.to_string());
            return Ok(r);
        }
    };
    let accel = format!("{q}''");
    let ratio = (|| {
        let num = notes.diff(&accel).ok()?;
        let den = residual.diff(&accel).ok()?;
        Some(Expr::over(num, den))
    })();
    let Some(ratio) = ratio else {
        r.problem = Some("cannot differentiate the equations by the acceleration".into());
        return Ok(r);
    };
    let ratio = cas::simplify(&ratio)?;
    let state_free = !ratio
        .symbols()
        .iter()
        .any(|s| s == "t" || s == q || *s == format!("{q}'") || *s == accel);
    let difference = Expr::minus(
        notes.clone(),
        Expr::mul(vec![ratio.clone(), residual.clone()]),
    );
    let symbolic = state_free && !ratio.is_zero() && cas::is_zero_all(vec![difference.clone()])?[0];
    let scale = Expr::add(vec![notes.clone(), residual.clone()]);
    let numeric = numerically_zero(
        &[difference],
        &[scale],
        scene.seed.wrapping_add(20_000),
        &signed_names(scene),
        &|p| scene.in_domain(p),
    )
    .map(|z| z[0] && state_free && !ratio.is_zero());
    decide(&mut r, symbolic, numeric, residual, &notes)?;
    Ok(r)
}

/// The verdict on two equations found the same or not by the engine (`symbolic`) and at random
/// points (`numeric`): two routes that disagree leave it undecided.
fn decide(
    r: &mut ClaimResult,
    symbolic: bool,
    numeric: Result<bool, crate::cas::EvalError>,
    residual: &Expr,
    notes: &Expr,
) -> Result<(), cas::CasError> {
    match numeric {
        Ok(n) if n != symbolic => {
            r.verdict = Verdict::Undecided;
            r.differences.push(
                format!(
                    "the symbolic test says the equations are {}, the test at \
                     {CONFIRMATION_POINTS} random points says {}; check this step by hand",
                    if symbolic { "the same" } else { "different" },
                    if n { "the same" } else { "different" }
                )
                .into(),
            );
            return Ok(());
        }
        Ok(_) => {}
        Err(e) => r.problem = Some(format!("cannot evaluate at random points: {e}")),
    }
    r.verdict = if symbolic {
        Verdict::Agrees
    } else {
        Verdict::Disagrees
    };
    if !symbolic {
        r.differences.push(
            Prose::default()
                .text("derived ")
                .expr(residual)
                .text(" = 0, notes ")
                .expr(&cas::simplify(notes)?)
                .text(" = 0: not one a constant multiple of the other"),
        );
    }
    Ok(())
}
