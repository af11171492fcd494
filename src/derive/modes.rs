//! The normal modes of n ≥ 2 linear equations M q'' + K (q − q₀) = 0: exact where every
//! factor of det(K − λM) has a closed form within the engine's budget (degree four at most),
//! otherwise numeric at the scene's values, as the eigenvalues of the pencil (K, M) by Sturm
//! bisection (`base::pencil`), which the step's check compares with the QR route on M⁻¹K.

use super::DeriveError;
use super::lagrangian::{closed_roots, sort_by_value};
use super::step_result::StepResult;
use crate::base::pencil::symmetric_pencil_eigenvalues;
use crate::cas::{self, Expr};
use crate::model::prose::Prose;
use crate::model::value::eval_at;
use std::collections::BTreeMap;

/// The root variable of the characteristic polynomial: a name no scene can write.
const LAMBDA: &str = "lambda__";

/// The most coordinates whose det(K − λM) is expanded in symbols: its degree is n, `solve`'s
/// closed forms stop at four, and the expansion has n! terms.
pub const MAX_EXACT_MODES: usize = 4;

/// The normal-mode angular frequencies of n ≥ 2 linear equations M q'' + K (q − q₀) = 0: each
/// √λ for the roots λ of det(K − λM) = 0, ordered by their value at `values`: in closed form
/// (`StepResult::Modes`), or at the scene's values with the reason (`NumericModes`).
pub fn normal_modes(
    eqs: &[(String, Expr)],
    values: &BTreeMap<String, f64>,
) -> Result<StepResult, DeriveError> {
    let n = eqs.len();
    let (mass, stiffness) = matrices(eqs)?;
    if n > MAX_EXACT_MODES {
        let reason = Prose::default()
            .math("det(K - lambda M)")
            .text(&format!(" of {n} coordinates has degree {n} in "))
            .math("lambda")
            .text(", and closed forms stop at degree four");
        return numeric_modes(&mass, &stiffness, n, values, reason);
    }
    let lambda = Expr::sym(LAMBDA);
    let entries: Vec<Expr> = mass
        .iter()
        .zip(&stiffness)
        .map(|(m, k)| Expr::minus(k.clone(), Expr::mul(vec![lambda.clone(), m.clone()])))
        .collect();
    let characteristic = cas::simplify(&super::lagrangian::determinant(&entries, n))?;
    let mut roots = cas::roots(&characteristic, LAMBDA)?;
    // A cubic or quartic factor (the 3-link pendulum): its roots in the closed form `solve`
    // gives, real at the scene's values as a conservative system's λ all are.
    for (factor, multiplicity) in std::mem::take(&mut roots.unsolved) {
        let shown = factor.substitute(&|s| (s == LAMBDA).then(|| Expr::sym("lambda")));
        let closed = match closed_roots(&factor, LAMBDA, values) {
            // Ferrari's form of a quartic in symbols can pass the engine's budget (the 4-link
            // pendulum): the frequencies at the scene's values instead.
            Err(cas::CasError {
                reason: cas::CasFailure::Engine(cas::EngineError::OverBudget { .. }),
            }) => {
                let reason = Prose::default()
                    .text("the closed form of the factor ")
                    .expr(&shown)
                    .text(" of ")
                    .math("det(K - lambda M)")
                    .text(" is beyond the engine's budget");
                return numeric_modes(&mass, &stiffness, n, values, reason);
            }
            other => other?,
        };
        match closed {
            Ok(found) => roots
                .roots
                .extend(found.into_iter().map(|root| (root, multiplicity))),
            Err(cas::NoClosedForm::Degree(degree)) => {
                let reason = Prose::default()
                    .math("det(K - lambda M)")
                    .text(" has the factor ")
                    .expr(&shown)
                    .text(&format!(" of degree {degree} in "))
                    .math("lambda")
                    .text(", and closed forms stop at degree four");
                return numeric_modes(&mass, &stiffness, n, values, reason);
            }
            Err(cas::NoClosedForm::NoValue(part)) => {
                return Err(DeriveError::NotDerivable(format!(
                    "det(K - lambda M) has the factor {} in lambda, whose closed form depends on \
                     the sign of {}, which has no value at the scene's values: give each of its \
                     names a value in [numeric]",
                    shown.to_text(),
                    part.to_text()
                )));
            }
        }
    }
    frequencies(roots.roots, n, values)
}

/// The angular frequencies √λ of the `n` roots λ (with their multiplicities), each a square
/// pulled out of its root, ordered by their value at `values`.
fn frequencies(
    roots: Vec<(Expr, u32)>,
    n: usize,
    values: &BTreeMap<String, f64>,
) -> Result<StepResult, DeriveError> {
    let mut modes = Vec::new();
    for (root, multiplicity) in roots {
        // Every symbol of a scene is positive: √(8 g² l²) = 2√2 g l.
        let root = cas::pull_squares(&cas::simplify(&root)?, &|_| true);
        let omega = cas::simplify(&Expr::pow(root, Expr::rat(1, 2)))?;
        modes.extend(std::iter::repeat_n(omega, multiplicity as usize));
    }
    if modes.len() != n {
        return Err(DeriveError::NotDerivable(format!(
            "det(K - lambda M) has {} roots, not {n}: the equations are degenerate (a \
             coordinate without inertia)",
            modes.len()
        )));
    }
    sort_by_value(&mut modes, values);
    Ok(StepResult::Modes(modes))
}

/// M = ∂R/∂q'' and K = ∂R/∂q of the linear residuals R, row-major; a term in a rate is
/// refused (a damped or driven motion has no normal modes).
fn matrices(eqs: &[(String, Expr)]) -> Result<(Vec<Expr>, Vec<Expr>), DeriveError> {
    let (mut mass, mut stiffness) = (Vec::new(), Vec::new());
    for (_, r) in eqs {
        for (q, _) in eqs {
            let damping = cas::simplify(&r.diff(&format!("{q}'"))?)?;
            if !damping.is_zero() {
                return Err(DeriveError::NotDerivable(format!(
                    "the equations have a term in `{q}'` ({}): a damped or driven motion has \
                     no normal modes",
                    damping.to_text()
                )));
            }
            mass.push(r.diff(&format!("{q}''"))?);
            stiffness.push(r.diff(q)?);
        }
    }
    Ok((mass, stiffness))
}

/// An eigenvalue λ of (K, M) within this fraction of the largest |λ| is a zero mode (a free
/// motion, which has no restoring force): round-off of an exact zero is about 1e-16 of it, and
/// a mode a million times slower than its companions would be 1e-12.
pub const ZERO_MODE: f64 = 1e-12;

/// The frequencies at the scene's values: √λ for the eigenvalues of the pencil (K, M), which
/// must be symmetric with M positive definite (equations from `lagrange` are), and λ ≥ 0 (a
/// zero mode is a free motion).
fn numeric_modes(
    mass: &[Expr],
    stiffness: &[Expr],
    n: usize,
    values: &BTreeMap<String, f64>,
    reason: Prose,
) -> Result<StepResult, DeriveError> {
    let frequencies = pencil_frequencies(mass, stiffness, n, values, &reason.to_text(), "scene")?;
    Ok(StepResult::NumericModes {
        frequencies,
        reason,
    })
}

/// The frequencies of linear equations at `values` (a variant's), slowest first, as
/// [`normal_modes`] finds them where they have no closed form: what a graded answer on such a
/// mode takes at each variant.
pub fn frequencies_at(
    eqs: &[(String, Expr)],
    values: &BTreeMap<String, f64>,
) -> Result<Vec<f64>, DeriveError> {
    let (mass, stiffness) = matrices(eqs)?;
    pencil_frequencies(
        &mass,
        &stiffness,
        eqs.len(),
        values,
        "the modes have no closed form",
        "variant",
    )
}

/// √λ for the eigenvalues of the pencil (K, M) at `values`, the `whose` (scene's or
/// variant's) values; `said` is why they are numbers, for the errors.
fn pencil_frequencies(
    mass: &[Expr],
    stiffness: &[Expr],
    n: usize,
    values: &BTreeMap<String, f64>,
    said: &str,
    whose: &str,
) -> Result<Vec<f64>, DeriveError> {
    let at = |entries: &[Expr]| -> Result<nalgebra::DMatrix<f64>, DeriveError> {
        let mut out = Vec::with_capacity(entries.len());
        for e in entries {
            out.push(eval_at(e, values).map_err(|err| {
                DeriveError::NotDerivable(format!(
                    "{said}, so the modes are found at the {whose}'s values; but {err}: give \
                     each name a value in [numeric]"
                ))
            })?);
        }
        Ok(nalgebra::DMatrix::from_row_slice(n, n, &out))
    };
    let (m, k) = (at(mass)?, at(stiffness)?);
    let lambdas = symmetric_pencil_eigenvalues(&k, &m).map_err(|e| {
        DeriveError::NotDerivable(format!(
            "{said}, so the modes are found at the {whose}'s values, as the eigenvalues of K \
             and M; but there {e}: the equations must come from `lagrange`"
        ))
    })?;
    let scale = lambdas.iter().fold(0.0_f64, |a, l| a.max(l.abs()));
    let mut frequencies = Vec::with_capacity(n);
    for (k, lambda) in lambdas.iter().enumerate() {
        // A free motion (a cart's translation): a zero mode, to the round-off of the others.
        if lambda.abs() <= ZERO_MODE * scale {
            frequencies.push(0.0);
            continue;
        }
        if *lambda <= 0.0 {
            return Err(DeriveError::NotDerivable(format!(
                "at the {whose}'s values, mode {} has lambda = {lambda:.6}, not positive: the \
                 state of `linearise` is not stable, so it has no normal mode there",
                k + 1
            )));
        }
        frequencies.push(lambda.sqrt());
    }
    Ok(frequencies)
}
