//! The author's steps, checked. Each result is compared with a numeric route that does not go
//! through the engine: `be` with the unsimplified expression at random points, `differentiate`
//! with central differences, `lagrange` by integrating its equations of motion and watching the
//! energy function Σ q'·∂L/∂q' − L, itself found by differences. A step's `gives` is a claim of
//! the notes, with a verdict.

use super::{
    CONFIRMATION_POINTS, ClaimResult, NUMERICALLY_ZERO, SAMPLE_FROM, check_claim, claim_env,
    numerically_zero, unchecked,
};
use crate::base::rng::Rng;
use crate::cas::{self, Expr};
use crate::derive::Derivation;
use crate::derive::steps::{StepResult, expand_names};
use crate::model::prose::Prose;
use crate::numeric::ode::dormand_prince;
use crate::scene::{AuthorStep, Claim, Operation, Scene, Verdict};
use std::collections::BTreeMap;

/// Why a step's numeric route could not run.
#[derive(Debug, thiserror::Error)]
pub enum CheckError {
    #[error(transparent)]
    Eval(#[from] crate::cas::EvalError),
    #[error(transparent)]
    Step(#[from] crate::derive::steps::StepError),
    #[error(transparent)]
    Motion(#[from] crate::numeric::ode::OdeError),
    #[error("the equations cannot be solved for the accelerations here (a singular mass matrix)")]
    Singular,
    #[error("the Lagrangian depends on t, so its energy is not conserved: no energy to watch")]
    TimeDependent,
    #[error(
        "the motion started off rest did not cross rest twice in three periods: it does not oscillate there"
    )]
    NoOscillation,
    /// The step or one it names has no result of its kind: a bug, the derivation ran first.
    #[error("internal inconsistency: the step's result is missing or of another kind")]
    NotDerived,
}

/// One step's numeric check: what it compared, how far apart, and what it cost.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct StepCheck {
    pub step: String,
    pub line: usize,
    /// The route, in words: "central differences", "energy along an integrated motion".
    pub method: String,
    /// The largest relative difference found, and the most it may be.
    pub error: f64,
    pub tolerance: f64,
    /// Evaluations of the step's expressions (or of the right-hand side).
    pub evaluations: u64,
    /// Why the check could not run, if it could not.
    pub problem: Option<String>,
}

impl StepCheck {
    pub fn passed(&self) -> bool {
        self.problem.is_none() && self.error <= self.tolerance
    }
}

/// Central differences with Richardson extrapolation err by O(h⁴) in truncation and about
/// ε·|f|/h in rounding; with h = 1e-3 both stay far below this, relative to the derivative.
const DIFFERENCE_AGREEMENT: f64 = 1e-7;
/// The difference step of [`DIFFERENCE_AGREEMENT`].
const H: f64 = 1e-3;
/// The energy function may drift this much, relative to its size, over an integration at
/// [`MOTION_TOLERANCE`]: Dormand–Prince keeps the local error to the tolerance, so the drift
/// over a few hundred steps stays near 1e-8; a wrong equation of motion drifts by order one.
const ENERGY_AGREEMENT: f64 = 1e-6;
const MOTION_TOLERANCE: f64 = 1e-10;
/// The integrated motion's length, in the scene's unit of time, and its step cap.
const MOTION_TIME: f64 = 10.0;
const MOTION_STEPS: u64 = 200_000;
/// A coordinate's default start (at rest), when the step gives none.
const DEFAULT_START: f64 = 0.5;

/// Each step's numeric check, in order.
pub fn check_steps(scene: &Scene, d: &Derivation) -> Vec<StepCheck> {
    scene
        .steps
        .iter()
        .enumerate()
        .map(|(i, step)| {
            let mut check = StepCheck {
                step: step.name.clone(),
                line: step.line,
                method: String::new(),
                error: 0.0,
                tolerance: 0.0,
                evaluations: 0,
                problem: None,
            };
            let seed = scene.seed.wrapping_add(1000 + i as u64);
            if let Err(problem) = check_step(scene, d, step, seed, &mut check) {
                check.problem = Some(problem.to_string());
            }
            check
        })
        .collect()
}

fn check_step(
    scene: &Scene,
    d: &Derivation,
    step: &AuthorStep,
    seed: u64,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    let result = d.named.get(&step.name).ok_or(CheckError::NotDerived)?;
    match (&step.op, result) {
        (Operation::Be(e), StepResult::Expr(r)) => {
            let raw = expand_names(scene, d, step, e)?;
            check.method = format!(
                "the simplified form against the expression as written, at {CONFIRMATION_POINTS} \
                 random points"
            );
            check.tolerance = NUMERICALLY_ZERO;
            let mut rng = Rng::new(seed);
            for _ in 0..CONFIRMATION_POINTS {
                let point = random_point(&[&raw, r], &mut rng);
                let (a, b) = (at(&raw, &point)?, at(r, &point)?);
                check.evaluations += 2;
                check.error = check
                    .error
                    .max((a - b).abs() / a.abs().max(b.abs()).max(1.0));
            }
        }
        (Operation::Differentiate { of, by }, StepResult::Expr(r)) => {
            let f = expand_names(scene, d, step, of)?;
            check.method = format!(
                "central differences (h = {H}, Richardson-extrapolated) at {CONFIRMATION_POINTS} \
                 random points"
            );
            check.tolerance = DIFFERENCE_AGREEMENT;
            let mut rng = Rng::new(seed);
            for _ in 0..CONFIRMATION_POINTS {
                let mut point = random_point(&[&f, r], &mut rng);
                let mut accel = BTreeMap::new();
                for q in scene.coordinates.keys() {
                    for name in [q.clone(), format!("{q}'"), format!("{q}''")] {
                        point
                            .entry(name)
                            .or_insert_with(|| SAMPLE_FROM + rng.uniform());
                    }
                    accel.insert(q.clone(), SAMPLE_FROM + rng.uniform());
                }
                point.entry("t".into()).or_insert(SAMPLE_FROM);
                // Along x = x0 + s (a partial derivative), or along the motion through the
                // point (d/dt): q + s q' + s² q''/2, q' + s q'', t + s.
                let moved = |s: f64| -> BTreeMap<String, f64> {
                    let mut p = point.clone();
                    if by == "t" {
                        for q in scene.coordinates.keys() {
                            let (v, a) = (point[&format!("{q}'")], point[&format!("{q}''")]);
                            *p.get_mut(q).expect("set above") += s * v + s * s * a / 2.0;
                            *p.get_mut(&format!("{q}'")).expect("set above") += s * a;
                        }
                        *p.get_mut("t").expect("set above") += s;
                    } else {
                        *p.entry(by.clone()).or_insert(SAMPLE_FROM) += s;
                    }
                    p
                };
                let central = |h: f64| -> Result<f64, CheckError> {
                    Ok((at(&f, &moved(h))? - at(&f, &moved(-h))?) / (2.0 * h))
                };
                let (d1, d2) = (central(H)?, central(H / 2.0)?);
                let numeric = (4.0 * d2 - d1) / 3.0;
                let exact = at(r, &point)?;
                check.evaluations += 5;
                check.error = check
                    .error
                    .max((exact - numeric).abs() / exact.abs().max(numeric.abs()).max(1.0));
            }
        }
        (Operation::Lagrange { of }, StepResult::Equations(eqs)) => {
            let Some(StepResult::Expr(lagrangian)) = d.named.get(of) else {
                return Err(CheckError::NotDerived);
            };
            energy_check(scene, step, lagrangian, eqs, check)?;
        }
        (Operation::Linearise { of, about }, StepResult::Equations(linear)) => {
            let Some(StepResult::Equations(full)) = d.named.get(of) else {
                return Err(CheckError::NotDerived);
            };
            linear_check(scene, full, linear, about, seed, check)?;
        }
        (Operation::Frequency { of }, StepResult::Expr(omega)) => {
            let source = scene.steps.iter().find(|s| &s.name == of);
            let Some(Operation::Linearise {
                of: motion_of,
                about,
            }) = source.map(|s| &s.op)
            else {
                return Err(CheckError::NotDerived);
            };
            let Some(StepResult::Equations(full)) = d.named.get(motion_of) else {
                return Err(CheckError::NotDerived);
            };
            period_check(scene, full, about, omega, check)?;
        }
        _ => return Err(CheckError::NotDerived),
    }
    Ok(())
}

/// Integrates the equations of motion (each residual is linear in the accelerations: solved at
/// every evaluation) from the step's start at the scene's values, and measures the drift of the
/// energy function, whose momenta ∂L/∂q' are central differences of L itself.
pub(super) fn energy_check(
    scene: &Scene,
    step: &AuthorStep,
    lagrangian: &Expr,
    eqs: &[(String, Expr)],
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.method = format!(
        "the energy Σ q'·∂L/∂q' − L along the motion integrated from the start for t = \
         {MOTION_TIME} (Dormand–Prince, tolerance {MOTION_TOLERANCE:e})"
    );
    check.tolerance = ENERGY_AGREEMENT;
    if lagrangian.symbols().iter().any(|s| s == "t") {
        return Err(CheckError::TimeDependent);
    }
    let coords: Vec<&String> = scene.coordinates.keys().collect();
    let n = coords.len();
    let mut params: BTreeMap<String, f64> = scene.values.clone();
    for (k, v) in &step.start {
        params.insert(k.clone(), *v);
    }
    let start: Vec<f64> = coords
        .iter()
        .map(|q| params.get(*q).copied().unwrap_or(DEFAULT_START))
        .chain(
            coords
                .iter()
                .map(|q| params.get(&format!("{q}'")).copied().unwrap_or(0.0)),
        )
        .collect();
    let state = |y: &[f64], a: &[f64]| state(&params, &coords, y, a);
    let rhs = |_t: f64, y: &[f64]| motion(eqs, &params, &coords, y);
    let run = dormand_prince(&rhs, &start, MOTION_TIME, MOTION_TOLERANCE, MOTION_STEPS)?;
    let energy = |y: &[f64]| -> Result<f64, CheckError> {
        let zero = vec![0.0; n];
        let l = |y: &[f64]| at(lagrangian, &state(y, &zero));
        let mut e = -l(y)?;
        for k in 0..n {
            let h = H * y[n + k].abs().max(1.0);
            let mut up = y.to_vec();
            let mut down = y.to_vec();
            up[n + k] += h;
            down[n + k] -= h;
            e += y[n + k] * (l(&up)? - l(&down)?) / (2.0 * h);
        }
        Ok(e)
    };
    let e0 = energy(&start)?;
    let mut scale = e0.abs();
    let mut drift: f64 = 0.0;
    for (_, y) in &run.states {
        let e = energy(y)?;
        scale = scale.max(at(lagrangian, &state(y, &vec![0.0; n]))?.abs());
        drift = drift.max((e - e0).abs());
    }
    check.evaluations =
        run.evaluations * (n as u64 + 1) + run.states.len() as u64 * (2 * n as u64 + 1);
    check.error = drift / scale.max(f64::MIN_POSITIVE);
    Ok(())
}

/// The amplitude at which a linearisation is compared with the full equations.
const AMPLITUDE: f64 = 1e-3;
/// At [`AMPLITUDE`] the full and linear equations differ by O(amplitude²), relative O(amplitude):
/// about 1e-3 times a coefficient ratio; a wrong coefficient differs by order one.
const LINEAR_AGREEMENT: f64 = 1e-1;
/// The start's distance from rest for the measured period: its relative error from 2π/Ω is
/// O(amplitude²) (1/16 of it for a pendulum), far below this.
const PERIOD_AMPLITUDE: f64 = 1e-2;
const PERIOD_AGREEMENT: f64 = 1e-3;

/// The full and linear equations at random states near rest, at [`AMPLITUDE`].
pub(super) fn linear_check(
    scene: &Scene,
    full: &[(String, Expr)],
    linear: &[(String, Expr)],
    about: &BTreeMap<String, Expr>,
    seed: u64,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.method = format!(
        "the full equations against the linear ones at {CONFIRMATION_POINTS} random states \
         {AMPLITUDE:e} from rest (they differ by O(amplitude²))"
    );
    check.tolerance = LINEAR_AGREEMENT;
    let mut rng = Rng::new(seed);
    for _ in 0..CONFIRMATION_POINTS {
        let exprs: Vec<&Expr> = full.iter().chain(linear).map(|(_, e)| e).collect();
        let mut point = random_point(&exprs, &mut rng);
        for q in scene.coordinates.keys() {
            let q0 = match about.get(q) {
                Some(e) => at(e, &point)?,
                None => 0.0,
            };
            let mut step = || AMPLITUDE * (2.0 * rng.uniform() - 1.0);
            point.insert(q.clone(), q0 + step());
            point.insert(format!("{q}'"), step());
            point.insert(format!("{q}''"), step());
        }
        for ((_, f), (_, l)) in full.iter().zip(linear) {
            let (a, b) = (at(f, &point)?, at(l, &point)?);
            check.evaluations += 2;
            check.error = check
                .error
                .max((a - b).abs() / b.abs().max(f64::MIN_POSITIVE));
        }
    }
    Ok(())
}

/// The period of the full motion started [`PERIOD_AMPLITUDE`] from rest, measured between
/// upward crossings of rest (each found on the cubic through the two steps around it), against
/// 2π/Ω at the scene's values.
pub(super) fn period_check(
    scene: &Scene,
    full: &[(String, Expr)],
    about: &BTreeMap<String, Expr>,
    omega: &Expr,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.tolerance = PERIOD_AGREEMENT;
    let params = scene.values.clone();
    let coords: Vec<&String> = scene.coordinates.keys().collect();
    let [q] = coords.as_slice() else {
        return Err(CheckError::NotDerived);
    };
    let q0 = match about.get(*q) {
        Some(e) => at(e, &params)?,
        None => 0.0,
    };
    let w = at(omega, &params)?;
    let period = 2.0 * std::f64::consts::PI / w;
    check.method = format!(
        "the period of the full motion from {PERIOD_AMPLITUDE} off rest, integrated for three \
         periods (Dormand–Prince, tolerance {MOTION_TOLERANCE:e}), against 2π/Ω"
    );
    let rhs = |_t: f64, y: &[f64]| motion(full, &params, &coords, y);
    let run = dormand_prince(
        &rhs,
        &[q0 + PERIOD_AMPLITUDE, 0.0],
        3.0 * period,
        MOTION_TOLERANCE,
        MOTION_STEPS,
    )?;
    let mut crossings = Vec::new();
    for pair in run.states.windows(2) {
        let ((t0, a), (t1, b)) = (&pair[0], &pair[1]);
        let (x0, x1) = (a[0] - q0, b[0] - q0);
        if x0 < 0.0 && x1 >= 0.0 {
            // Cubic Hermite on [t0, t1] through the positions and rates; bisection for its root.
            let h = t1 - t0;
            let p = |s: f64| {
                let (s2, s3) = (s * s, s * s * s);
                (2.0 * s3 - 3.0 * s2 + 1.0) * x0
                    + (s3 - 2.0 * s2 + s) * h * a[1]
                    + (-2.0 * s3 + 3.0 * s2) * x1
                    + (s3 - s2) * h * b[1]
            };
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if p(mid) < 0.0 { lo = mid } else { hi = mid }
            }
            crossings.push(t0 + 0.5 * (lo + hi) * h);
        }
    }
    check.evaluations = run.evaluations * 2;
    let (Some(first), Some(last)) = (crossings.first(), crossings.last()) else {
        return Err(CheckError::NoOscillation);
    };
    if crossings.len() < 2 {
        return Err(CheckError::NoOscillation);
    }
    let measured = (last - first) / (crossings.len() - 1) as f64;
    check.error = (measured - period).abs() / period;
    Ok(())
}

/// The names at a state: the parameters, each coordinate and rate from `y` (coordinates, then
/// rates), each acceleration from `a`.
fn state(
    params: &BTreeMap<String, f64>,
    coords: &[&String],
    y: &[f64],
    a: &[f64],
) -> BTreeMap<String, f64> {
    let n = coords.len();
    let mut p = params.clone();
    for (k, q) in coords.iter().enumerate() {
        p.insert((*q).clone(), y[k]);
        p.insert(format!("{q}'"), y[n + k]);
        p.insert(format!("{q}''"), a[k]);
    }
    p
}

/// y' for the equations of motion at state y: each residual is linear in the accelerations, so
/// they solve M a = −R(a = 0), M's columns R(a = e_j) − R(0).
fn motion(
    eqs: &[(String, Expr)],
    params: &BTreeMap<String, f64>,
    coords: &[&String],
    y: &[f64],
) -> Result<Vec<f64>, CheckError> {
    let n = coords.len();
    let residuals = |a: &[f64]| -> Result<Vec<f64>, CheckError> {
        let p = state(params, coords, y, a);
        eqs.iter().map(|(_, e)| at(e, &p)).collect()
    };
    let zero = vec![0.0; n];
    let f0 = residuals(&zero)?;
    let mut m = nalgebra::DMatrix::zeros(n, n);
    for j in 0..n {
        let mut unit = zero.clone();
        unit[j] = 1.0;
        let fj = residuals(&unit)?;
        for i in 0..n {
            m[(i, j)] = fj[i] - f0[i];
        }
    }
    let a = m
        .lu()
        .solve(&nalgebra::DVector::from_iterator(n, f0.iter().map(|x| -x)))
        .ok_or(CheckError::Singular)?;
    Ok(y[n..].iter().copied().chain(a.iter().copied()).collect())
}

/// Every symbol of the expressions at a random value in [0.4, 1.4) (π is π).
fn random_point(exprs: &[&Expr], rng: &mut Rng) -> BTreeMap<String, f64> {
    let mut names: Vec<String> = exprs.iter().flat_map(|e| e.symbols()).collect();
    names.sort();
    names.dedup();
    names
        .into_iter()
        .filter(|s| s != "pi")
        .map(|s| (s, SAMPLE_FROM + rng.uniform()))
        .collect()
}

fn at(e: &Expr, point: &BTreeMap<String, f64>) -> Result<f64, CheckError> {
    Ok(e.eval(&|s| point.get(s).copied().filter(|_| s != "pi"))?)
}

/// Each step's `gives`, as a claim of the notes: the same expression, or for equations of
/// motion the same equation up to a non-zero constant factor.
pub fn check_gives(scene: &Scene, d: &Derivation) -> Result<Vec<ClaimResult>, cas::CasError> {
    let env = claim_env(scene, d);
    let mut out = Vec::new();
    for (i, step) in scene.steps.iter().enumerate() {
        let Some(gives) = &step.gives else {
            continue;
        };
        let claim = Claim {
            eq: step.eq.clone().unwrap_or_else(|| step.name.clone()),
            statement: match step.op {
                Operation::Lagrange { .. } => {
                    format!("step `{}` gives {} = 0", step.name, gives.to_text())
                }
                _ => format!("step `{}` gives {}", step.name, gives.to_text()),
            },
            quantity: Some(Expr::sym(&step.name)),
            value: Some(gives.clone()),
            figures: None,
            expect: step.expect,
            role: step.role,
            line: step.line,
        };
        let mut r = match d.named.get(&step.name) {
            Some(StepResult::Equations(eqs)) => same_equation(scene, d, step, &claim, eqs, gives)?,
            _ => check_claim(scene, &env, 10_000 + i, &claim)?,
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
    let numeric = numerically_zero(&[difference], &[scale], scene.seed.wrapping_add(20_000))
        .map(|z| z[0] && state_free && !ratio.is_zero());
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
            return Ok(r);
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
                .expr(&cas::simplify(&notes)?)
                .text(" = 0: not one a constant multiple of the other"),
        );
    }
    Ok(r)
}
