//! States of rest of several coordinates, and their stability: the static equations (every rate
//! and acceleration 0) solved one coordinate at a time, each state put into the others, and
//! about each state the stiffness matrix K, positive definite exactly when every frequency² of
//! a natural system (no terms in the rates) is positive.

use super::DeriveError;
use super::sign::{Sign, signs_over_positive};
use super::step_result::{Stable, StateStability};
use crate::cas::{self, Expr, Zero};

/// The most states of rest a step gives: beyond, the page would be a table of them.
pub const MAX_STATES: usize = 16;

/// `e` with every coordinate's rate and acceleration 0.
pub fn static_form(e: &Expr, coordinates: &[String]) -> Expr {
    e.substitute(&|s| {
        coordinates
            .iter()
            .any(|q| s == format!("{q}'") || s == format!("{q}''"))
            .then(|| Expr::int(0))
    })
}

/// `e` at a state: each coordinate's zero put in.
pub fn put_state(e: &Expr, coordinates: &[String], state: &[Zero]) -> Expr {
    coordinates
        .iter()
        .zip(state)
        .fold(e.clone(), |e, (q, z)| z.put_into(&e, q))
}

/// The states of rest of several coordinates: a zero per coordinate in the equations' order,
/// and the roots set aside as real for no values of the symbols (coordinate, root).
#[derive(Debug)]
pub struct RestStates {
    pub coordinates: Vec<String>,
    pub states: Vec<Vec<Zero>>,
    pub excluded: Vec<(String, Expr)>,
}

/// Every state of rest of the equations of several coordinates.
pub fn rest_states(eqs: &[(String, Expr)]) -> Result<RestStates, DeriveError> {
    let coordinates: Vec<String> = eqs.iter().map(|(q, _)| q.clone()).collect();
    let statics: Vec<Expr> = eqs
        .iter()
        .map(|(_, r)| static_form(r, &coordinates))
        .collect();
    let mut excluded = Vec::new();
    let found = solve_static(statics, &coordinates, &mut excluded)?;
    if found.is_empty() {
        let besides = match excluded.is_empty() {
            true => "",
            false => " (the roots set aside are real for no values of the symbols)",
        };
        return Err(DeriveError::NotDerivable(format!(
            "the static equations have no common real solution{besides}: there is no equilibrium"
        )));
    }
    if found.len() > MAX_STATES {
        return Err(DeriveError::NotDerivable(format!(
            "the static equations have {} states of rest, more than the {MAX_STATES} a step shows",
            found.len()
        )));
    }
    let states = found
        .into_iter()
        .map(|pairs| {
            coordinates
                .iter()
                .map(|q| {
                    pairs
                        .iter()
                        .find(|(p, _)| p == q)
                        .map(|(_, z)| z.clone())
                        .ok_or_else(|| {
                            DeriveError::Inconsistent(format!("a state of rest without `{q}`"))
                        })
                })
                .collect::<Result<Vec<Zero>, _>>()
        })
        .collect::<Result<_, _>>()?;
    Ok(RestStates {
        coordinates,
        states,
        excluded,
    })
}

/// The common zeros of `eqs` in the coordinates `free`: an equation in one of them alone gives
/// its zeros, each put into the others, which are solved in turn. A zero real for no positive
/// values of the symbols (r = √(−r₀²)) is no state of rest: set aside in `excluded`.
fn solve_static(
    eqs: Vec<Expr>,
    free: &[String],
    excluded: &mut Vec<(String, Expr)>,
) -> Result<Vec<Vec<(String, Zero)>>, DeriveError> {
    let eqs: Vec<Expr> = cas::simplify_all(eqs)?
        .into_iter()
        .filter(|e| !e.is_zero())
        .collect();
    let holds = |e: &Expr| -> Vec<String> {
        let symbols = e.symbols();
        free.iter()
            .filter(|q| symbols.contains(*q))
            .cloned()
            .collect()
    };
    // An equation left without a free coordinate and not zero: this branch has no state.
    if eqs.iter().any(|e| holds(e).is_empty()) {
        return Ok(Vec::new());
    }
    if eqs.is_empty() {
        if let Some(q) = free.first() {
            return Err(DeriveError::NotDerivable(format!(
                "the static equations leave `{q}` free: a continuum of states of rest, which \
                 `equilibria` does not list"
            )));
        }
        return Ok(vec![Vec::new()]);
    }
    let Some((k, q)) = eqs
        .iter()
        .enumerate()
        .find_map(|(k, e)| match &holds(e)[..] {
            [q] => Some((k, q.clone())),
            _ => None,
        })
    else {
        return coupled_state(&eqs, free);
    };
    let found = cas::zeros(&eqs[k], &q)?;
    if let Some(f) = found.unsolved.first() {
        return Err(DeriveError::NotDerivable(format!(
            "the static equation has the factor {} = 0, whose solutions have no closed form here \
             (a polynomial of degree at most 2 in `{q}`, in sin({q}) or in cos({q}))",
            f.to_text()
        )));
    }
    let rest_free: Vec<String> = free.iter().filter(|p| **p != q).cloned().collect();
    let mut states = Vec::new();
    for z in found.zeros {
        if super::lagrangian::never_real(&z.value) {
            excluded.push((q.clone(), z.value));
            continue;
        }
        let positive = |e: &Expr| cas::pull_squares(e, &|_| true);
        let z = Zero {
            value: positive(&z.value),
            trig: z.trig.map(|(c, s)| (positive(&c), positive(&s))),
        };
        let others: Vec<Expr> = eqs
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != k)
            .map(|(_, e)| z.put_into(e, &q))
            .collect();
        for mut state in solve_static(others, &rest_free, excluded)? {
            state.insert(0, (q.clone(), z.clone()));
            states.push(state);
        }
    }
    Ok(states)
}

/// The one state of static equations that each hold several coordinates, linearly: by
/// Cramer's rule; not linear, refused.
fn coupled_state(eqs: &[Expr], free: &[String]) -> Result<Vec<Vec<(String, Zero)>>, DeriveError> {
    let named: Vec<(String, Expr)> = eqs.iter().map(|e| (String::new(), e.clone())).collect();
    match super::solve::solve_system(&named, free) {
        Ok(solution) => Ok(vec![
            solution
                .into_iter()
                .map(|(q, value)| (q, Zero { value, trig: None }))
                .collect(),
        ]),
        Err(_) => Err(DeriveError::NotDerivable(format!(
            "each static equation holds several of {}, and they are not linear in them: \
             `equilibria` solves equations that give one coordinate at a time (a static \
             equation in one coordinate alone, then the others with it put in), or a linear \
             system",
            free.join(", ")
        ))),
    }
}

/// About each state: K = ∂R/∂q there, its leading principal minors, and the verdict. A natural
/// system's mass matrix is positive definite, so every frequency² (the eigenvalues of M⁻¹K) is
/// positive exactly when every minor of K is (Sylvester's criterion). Equations with terms in
/// the rates at rest (gyroscopic coupling) are refused: K alone does not decide them.
pub fn rest_stability(
    eqs: &[(String, Expr)],
    coordinates: &[String],
    states: &[Vec<Zero>],
) -> Result<Vec<StateStability>, DeriveError> {
    let n = coordinates.len();
    let mut stiffness = Vec::new();
    let mut rates = Vec::new();
    for (_, r) in eqs {
        for q in coordinates {
            stiffness.push(static_form(&r.diff(q)?, coordinates));
            // The rate terms at rest: the derivative in q' with the other rates at 0.
            rates.push(static_form(&r.diff(&format!("{q}'"))?, coordinates));
        }
    }
    let stiffness = cas::simplify_all(stiffness)?;
    let rates = cas::simplify_all(rates)?;
    let mut out = Vec::new();
    for state in states {
        let at = |e: &Expr| put_state(e, coordinates, state);
        let gyroscopic = cas::simplify_all(rates.iter().map(at).collect())?;
        if let Some(g) = gyroscopic.iter().find(|g| !g.is_zero()) {
            return Err(DeriveError::NotDerivable(format!(
                "the equations have a term {} in a rate at rest (a gyroscopic coupling), so the \
                 stiffness alone does not decide stability: eliminate the conserved momenta \
                 first (Routh), as tests/course/dynamics/04-heavy-top.toml does",
                g.to_text()
            )));
        }
        let k: Vec<Expr> = cas::simplify_all(stiffness.iter().map(at).collect())?;
        let minors: Vec<Expr> = (1..=n)
            .map(|m| {
                let sub: Vec<Expr> = (0..m)
                    .flat_map(|i| (0..m).map(move |j| (i, j)))
                    .map(|(i, j)| k[i * n + j].clone())
                    .collect();
                super::lagrangian::determinant(&sub, m)
            })
            .collect();
        let minors = cas::simplify_all(minors)?;
        let verdict = match signs_over_positive(&minors) {
            Ok(signs) if signs.iter().all(|s| *s == Sign::Positive) => Stable::Always,
            Ok(signs) if signs.contains(&Sign::Negative) => Stable::Never,
            _ => Stable::Where,
        };
        out.push(StateStability {
            at: state.clone(),
            stiffness: k,
            minors,
            verdict,
        });
    }
    Ok(out)
}
