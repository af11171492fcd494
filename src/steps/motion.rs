//! The author's steps that describe a motion, checked along it: the equations of motion
//! integrated (Dormand–Prince) with the energy function watched, the linear equations against
//! the full ones near rest, and the measured period against 2π/Ω.

use super::check::{CheckError, H, StepCheck, at, random_point};
use crate::base::format::{sci, short};
use crate::base::rng::Rng;
use crate::cas::Expr;
use crate::derive::constraints::is_velocity_constraint;
use crate::numeric::compiled::Program;
use crate::numeric::motion::{
    MOTION_STEPS, MOTION_TOLERANCE, MotionSystem, split_rows, state, state_slots,
};
use crate::numeric::ode::dormand_prince;
use crate::numeric::random_points::CONFIRMATION_POINTS;
use crate::scene::{AuthorStep, Scene};
use std::collections::BTreeMap;

/// The energy function may drift this much, relative to its size, over an integration at
/// [`MOTION_TOLERANCE`]: Dormand–Prince keeps the local error to the tolerance, so the drift
/// over a few hundred steps stays near 1e-8; a wrong equation of motion drifts by order one.
pub(crate) const ENERGY_AGREEMENT: f64 = 1e-6;
/// The integrated motion's length, in the scene's unit of time.
pub(crate) const MOTION_TIME: f64 = 10.0;

/// The motion of a Lagrangian's equations, integrated from a step's start at the scene's values.
pub(crate) struct Integrated<'a> {
    /// The scene's values with the start's.
    pub(super) params: BTreeMap<String, f64>,
    /// The coordinates that have an equation (a constraint may have eliminated others).
    pub(super) coords: Vec<&'a String>,
    /// Each state: the coordinates, then their rates.
    pub(super) states: Vec<Vec<f64>>,
    pub(super) evaluations: u64,
}

/// An expression of the state compiled once for every state of a motion, and its source for
/// the message when its value is not finite.
pub(crate) struct OnMotion<'e> {
    /// The rates and accelerations (slots n on) vary alone in a momentum's differences.
    compiled: Program,
    source: &'e Expr,
}

impl OnMotion<'_> {
    fn finite(&self, v: f64) -> Result<f64, CheckError> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(CheckError::Undefined {
                expression: self.source.to_text(),
                value: v,
            })
        }
    }
}

impl Integrated<'_> {
    /// `e` with the scene's values and the start's put in, the state's names left to fill.
    pub(super) fn compile<'e>(&self, e: &'e Expr) -> Result<OnMotion<'e>, CheckError> {
        let slots = state_slots(&self.coords);
        Ok(OnMotion {
            compiled: Program::new(&[e], &slots, &self.params, self.coords.len())?,
            source: e,
        })
    }

    /// The slots of state `y`, accelerations 0 (a momentum or energy has none).
    fn slots(&self, y: &[f64]) -> Vec<f64> {
        let mut x = y.to_vec();
        x.resize(3 * self.coords.len(), 0.0);
        x
    }

    /// `f` at state `y`; an infinite or undefined value is an error: a check that compared it
    /// would see inf − inf as NaN, which every `max` passes over, and agree "to 0".
    pub(super) fn value(&self, f: &OnMotion, y: &[f64]) -> Result<f64, CheckError> {
        f.finite(f.compiled.eval(&self.slots(y), &mut Vec::new())[0])
    }

    /// ∂L/∂q'_k at state x by a central difference of L itself, `registers` holding L at a
    /// state with x's coordinates.
    fn momentum_at(
        &self,
        lagrangian: &OnMotion,
        x: &mut [f64],
        registers: &mut [f64],
        k: usize,
    ) -> Result<f64, CheckError> {
        let n = self.coords.len();
        let rate = x[n + k];
        let h = H * rate.abs().max(1.0);
        x[n + k] = rate + h;
        let up = lagrangian.finite(lagrangian.compiled.eval_varying(x, registers)[0])?;
        x[n + k] = rate - h;
        let down = lagrangian.finite(lagrangian.compiled.eval_varying(x, registers)[0])?;
        x[n + k] = rate;
        Ok((up - down) / (2.0 * h))
    }

    /// ∂L/∂q'_k at state y.
    pub(super) fn momentum(
        &self,
        lagrangian: &OnMotion,
        y: &[f64],
        k: usize,
    ) -> Result<f64, CheckError> {
        let mut x = self.slots(y);
        let mut registers = Vec::new();
        lagrangian.compiled.eval(&x, &mut registers);
        self.momentum_at(lagrangian, &mut x, &mut registers, k)
    }

    /// The energy function Σ q'·∂L/∂q' − L at state y, its momenta by differences.
    fn energy(&self, lagrangian: &OnMotion, y: &[f64]) -> Result<f64, CheckError> {
        let n = self.coords.len();
        let mut x = self.slots(y);
        let mut registers = Vec::new();
        let mut e = -lagrangian.finite(lagrangian.compiled.eval(&x, &mut registers)[0])?;
        for k in 0..n {
            e += y[n + k] * self.momentum_at(lagrangian, &mut x, &mut registers, k)?;
        }
        Ok(e)
    }
}

/// Integrates the equations of motion (each residual is linear in the accelerations: solved at
/// every evaluation) from the step's start (each coordinate [`DEFAULT_START`] and at rest where
/// it says nothing) for [`MOTION_TIME`].
pub(crate) fn integrate<'a>(
    scene: &Scene,
    step: &AuthorStep,
    lagrangian: &Expr,
    eqs: &'a [(String, Expr)],
    constraints: &[(String, Expr)],
) -> Result<Integrated<'a>, CheckError> {
    if lagrangian.symbols().iter().any(|s| s == "t") {
        return Err(CheckError::TimeDependent);
    }
    let (coords, multipliers) = split_rows(eqs, &scene.coordinates);
    let mut params: BTreeMap<String, f64> = scene.values.clone();
    for (k, v) in &step.start {
        params.insert(k.clone(), *v);
    }
    let start = crate::numeric::motion::start(&params, &coords);
    on_constraints(&coords, &scene.coordinates, &params, &start, constraints)?;
    let system = MotionSystem::new(eqs, &params, &coords, &multipliers)?;
    let rhs = |_t: f64, y: &[f64]| system.rates(y);
    let run = dormand_prince(&rhs, &start, MOTION_TIME, MOTION_TOLERANCE, MOTION_STEPS)?;
    // A start at rest in an equilibrium never moves: every conservation law holds trivially.
    let moved = run.states.iter().any(|(_, y)| {
        y.iter()
            .zip(&start)
            .any(|(a, b)| (a - b).abs() > 1e-9 * b.abs().max(1.0))
    });
    if !moved {
        return Err(CheckError::AtRest {
            coordinate: coords[0].clone(),
        });
    }
    let evaluations = run.evaluations * (coords.len() as u64 + 1);
    Ok(Integrated {
        states: run.states.into_iter().map(|(_, y)| y).collect(),
        params,
        coords,
        evaluations,
    })
}

/// How far a start may be off a constraint, relative to the coordinates' and rates' sizes:
/// the integration keeps f'' = 0, so an offset at the start stays, and grows with time.
const ON_CONSTRAINT: f64 = 1e-9;

/// The start (coordinates, then rates) satisfies each constraint f = 0, and, for one on the
/// coordinates alone, moves along it (f' = ∇f · q' = 0, by a central difference along q').
fn on_constraints(
    coords: &[&String],
    coordinates: &BTreeMap<String, String>,
    params: &BTreeMap<String, f64>,
    start: &[f64],
    constraints: &[(String, Expr)],
) -> Result<(), CheckError> {
    let n = coords.len();
    let slots = state_slots(coords);
    let (q, rates) = start.split_at(n);
    let size = |v: &[f64]| v.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    let h = 1e-6 / size(rates);
    for (lambda, f) in constraints {
        let program = Program::new(&[f], &slots, params, usize::MAX)?;
        let at = |shift: f64| {
            let mut x: Vec<f64> = (0..n).map(|k| q[k] + shift * rates[k]).collect();
            x.extend(rates);
            x.resize(3 * n, 0.0);
            program.eval(&x, &mut Vec::new())[0]
        };
        let velocity = is_velocity_constraint(f, coordinates);
        let value = at(0.0);
        let rate = (at(h) - at(-h)) / (2.0 * h);
        // NaN is off too.
        let off = |v: f64, scale: f64| v.is_nan() || v.abs() > ON_CONSTRAINT * scale;
        let what = if off(value, if velocity { size(rates) } else { size(q) }) {
            Some(("value", value))
        } else if !velocity && off(rate, size(q) * size(rates) * 1e3) {
            Some(("rate of change", rate))
        } else {
            None
        };
        if let Some((what, value)) = what {
            return Err(CheckError::OffConstraint {
                multiplier: lambda.clone(),
                what,
                value,
            });
        }
    }
    Ok(())
}

/// The drift of the energy function along the integrated motion of a `lagrange` step's
/// equations, relative to the size of the energy and the Lagrangian.
pub(crate) fn energy_check(
    scene: &Scene,
    step: &AuthorStep,
    lagrangian: &Expr,
    eqs: &[(String, Expr)],
    constraints: &[(String, Expr)],
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.method = format!(
        "the energy Σ q'·∂L/∂q' − L along the motion integrated from the start for t = \
         {MOTION_TIME} (Dormand–Prince, tolerance {}){}",
        short(MOTION_TOLERANCE),
        if constraints.is_empty() {
            ""
        } else {
            ", and each constraint f(q) along it, relative to the coordinates' size (the \
             accelerations and multipliers solved together at every step)"
        }
    );
    check.tolerance = ENERGY_AGREEMENT;
    let m = integrate(scene, step, lagrangian, eqs, constraints)?;
    let n = m.coords.len() as u64;
    let l = m.compile(lagrangian)?;
    let e0 = m.energy(&l, &m.states[0])?;
    let mut scale = e0.abs();
    let mut drift: f64 = 0.0;
    for y in &m.states {
        let e = m.energy(&l, y)?;
        scale = scale.max(m.value(&l, y)?.abs());
        drift = drift.max((e - e0).abs());
    }
    check.evaluations = m.evaluations + m.states.len() as u64 * (2 * n + 1);
    check.error = drift / scale.max(f64::MIN_POSITIVE);
    // The constraints are kept only through f'' = 0 (g' = 0 for one on the velocities): the
    // integration's errors move f itself, relative to the coordinates' size (the rates').
    let n = m.coords.len();
    let size = |part: std::ops::Range<usize>| {
        m.states
            .iter()
            .flat_map(|y| y[part.clone()].iter())
            .fold(f64::MIN_POSITIVE, |s, x| s.max(x.abs()))
    };
    for (_, f) in constraints {
        let size = match is_velocity_constraint(f, &scene.coordinates) {
            true => size(n..2 * n),
            false => size(0..n),
        };
        let f = m.compile(f)?;
        for y in &m.states {
            check.error = check.error.max(m.value(&f, y)?.abs() / size);
        }
        check.evaluations += m.states.len() as u64;
    }
    Ok(())
}

/// Which conserved-or-not quantity a step states.
pub(crate) enum Conserved<'a> {
    /// The momentum of this coordinate.
    Momentum(&'a str),
    Energy,
}

/// A `momentum` or `energy` step along the motion of its Lagrangian's equations: at every state
/// its exact value against differences of L (the momentum ∂L/∂q', or Σ q'·∂L/∂q' − L), and, if
/// the step says it is conserved, its drift from the start.
pub(crate) fn conserved_check(
    scene: &Scene,
    step: &AuthorStep,
    lagrangian: &Expr,
    value: &Expr,
    conserved: bool,
    what: Conserved,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    let eqs = crate::derive::lagrangian::euler_lagrange(lagrangian, &scene.coordinates)?;
    check.tolerance = ENERGY_AGREEMENT;
    let m = integrate(scene, step, lagrangian, &eqs, &[])?;
    let l = m.compile(lagrangian)?;
    let reference = |y: &[f64]| match what {
        Conserved::Momentum(q) => match m.coords.iter().position(|c| *c == q) {
            Some(k) => m.momentum(&l, y, k),
            // A coordinate the Lagrangian does not depend on has no momentum: 0.
            None => Ok(0.0),
        },
        Conserved::Energy => m.energy(&l, y),
    };
    let exact = m.compile(value)?;
    let v0 = m.value(&exact, &m.states[0])?;
    let (mut scale, mut mismatch, mut drift) = (v0.abs(), 0.0f64, 0.0f64);
    for y in &m.states {
        let v = m.value(&exact, y)?;
        let r = reference(y)?;
        scale = scale.max(r.abs()).max(m.value(&l, y)?.abs());
        mismatch = mismatch.max((v - r).abs());
        drift = drift.max((v - v0).abs());
    }
    let scale = scale.max(f64::MIN_POSITIVE);
    let route = match what {
        Conserved::Momentum(_) => "the momentum ∂L/∂q' by differences of L",
        Conserved::Energy => "the energy Σ q'·∂L/∂q' − L by differences of L",
    };
    check.method = format!(
        "the exact value against {route} along the motion integrated from the start for t = \
         {MOTION_TIME} (Dormand–Prince, tolerance {}){}",
        short(MOTION_TOLERANCE),
        if conserved {
            ", and its drift from the start".to_string()
        } else {
            format!(
                "; it changes by {} of its size along it",
                sci(drift / scale)
            )
        }
    );
    check.evaluations = m.evaluations + m.states.len() as u64 * (2 * m.coords.len() as u64 + 3);
    check.error = if conserved {
        mismatch.max(drift) / scale
    } else {
        mismatch / scale
    };
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
pub(crate) const PERIOD_AGREEMENT: f64 = 1e-3;

/// The full and linear equations at random states near rest, at [`AMPLITUDE`].
pub(crate) fn linear_check(
    scene: &Scene,
    full: &[(String, Expr)],
    linear: &[(String, Expr)],
    about: &BTreeMap<String, Expr>,
    seed: u64,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.method = format!(
        "the full equations against the linear ones at {CONFIRMATION_POINTS} random states \
         {} from rest (they differ by O(amplitude²))",
        short(AMPLITUDE)
    );
    check.tolerance = LINEAR_AGREEMENT;
    let mut rng = Rng::new(seed);
    for _ in 0..CONFIRMATION_POINTS {
        let exprs: Vec<&Expr> = full.iter().chain(linear).map(|(_, e)| e).collect();
        let mut point = random_point(&exprs, &mut rng, scene);
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
            // On the size of the linear equation's terms, not of their sum: at a random state
            // the terms can all but cancel (m x'' + k x ≈ 0), and the difference, of order
            // amplitude², then looked large beside it for some seeds.
            let terms = match l {
                Expr::Add(v) => v.iter(),
                other => std::slice::from_ref(other).iter(),
            };
            let mut size = 0.0f64;
            for t in terms {
                size += at(t, &point)?.abs();
            }
            check.evaluations += 2;
            check.error = check.error.max((a - b).abs() / size.max(f64::MIN_POSITIVE));
        }
    }
    Ok(())
}

/// The period of the full motion started [`PERIOD_AMPLITUDE`] from rest, measured between
/// upward crossings of rest (each found on the cubic through the two steps around it), against
/// 2π/Ω at the scene's values.
pub(crate) fn period_check(
    scene: &Scene,
    full: &[(String, Expr)],
    about: &BTreeMap<String, Expr>,
    omega: &Expr,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.tolerance = PERIOD_AGREEMENT;
    let w = at(omega, &scene.values)?;
    let period = 2.0 * std::f64::consts::PI / w;
    check.method = format!(
        "the period of the full motion from {PERIOD_AMPLITUDE} off rest, integrated for three \
         periods (Dormand–Prince, tolerance {}), against 2π/Ω",
        short(MOTION_TOLERANCE)
    );
    let (measured, evaluations) = measured_period(full, about, &scene.values, period)?;
    check.evaluations = evaluations;
    check.error = (measured - period).abs() / period;
    Ok(())
}

/// The period of the full motion of one coordinate at `params`, started [`PERIOD_AMPLITUDE`]
/// from its state of rest `about` and integrated for three periods of the `expected` length:
/// the mean time between upward crossings of the state of rest. With the right-hand sides
/// evaluated (twice a step: the rates and the crossings' Hermite slopes).
pub(crate) fn measured_period(
    full: &[(String, Expr)],
    about: &BTreeMap<String, Expr>,
    params: &BTreeMap<String, f64>,
    expected: f64,
) -> Result<(f64, u64), CheckError> {
    let coords: Vec<&String> = full.iter().map(|(q, _)| q).collect();
    let [q] = coords.as_slice() else {
        return Err(CheckError::NotDerived);
    };
    let q0 = match about.get(*q) {
        Some(e) => at(e, params)?,
        None => 0.0,
    };
    let system = MotionSystem::new(full, params, &coords, &[])?;
    let rhs = |_t: f64, y: &[f64]| system.rates(y);
    let run = dormand_prince(
        &rhs,
        &[q0 + PERIOD_AMPLITUDE, 0.0],
        3.0 * expected,
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
    let (Some(first), Some(last)) = (crossings.first(), crossings.last()) else {
        return Err(CheckError::NoOscillation);
    };
    if crossings.len() < 2 {
        return Err(CheckError::NoOscillation);
    }
    Ok((
        (last - first) / (crossings.len() - 1) as f64,
        run.evaluations * 2,
    ))
}

/// The engine's normal-mode frequencies against the eigenvalues of M⁻¹K by nalgebra's Schur
/// decomposition: backward stable, so for modes a few percent apart they agree to about 1e-13;
/// a wrong root is off by order one.
pub(crate) const MODES_AGREEMENT: f64 = 1e-9;

/// A `frequency` step of n ≥ 2 coordinates: its modes at the scene's values against √λ for
/// the eigenvalues λ of M⁻¹K, M and K read off the linear equations numerically.
pub(crate) fn modes_check(
    scene: &Scene,
    linear: &[(String, Expr)],
    modes: &[Expr],
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    let derived = modes
        .iter()
        .map(|e| at(e, &scene.values))
        .collect::<Result<Vec<f64>, CheckError>>()?;
    modes_agreement(scene, linear, &derived, check)
}

/// The frequencies a step found at the scene's values (exact ones evaluated, or the Sturm
/// bisection's) against √λ of M⁻¹K by the Schur decomposition.
pub(crate) fn modes_agreement(
    scene: &Scene,
    linear: &[(String, Expr)],
    derived: &[f64],
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.method = "each frequency against √λ for the eigenvalues λ of M⁻¹K at the scene's \
                    values (M, K read off the linear equations; nalgebra's Schur decomposition)"
        .into();
    check.tolerance = MODES_AGREEMENT;
    let n = linear.len();
    check.evaluations = (n * (2 * n + 1)) as u64;
    let numeric = numeric_modes(linear, &scene.values)?;
    if numeric.len() != derived.len() {
        check.error = f64::INFINITY;
    }
    // A zero mode is compared on its companions' scale: relative to itself it has none.
    let fastest = numeric.iter().fold(0.0_f64, |a, w| a.max(w.abs()));
    for (w, x) in numeric.iter().zip(derived) {
        let scale = if *w == 0.0 { fastest } else { w.abs() };
        let error = (x - w).abs() / scale;
        check.error = check
            .error
            .max(if error.is_nan() { f64::INFINITY } else { error });
    }
    Ok(())
}

/// The normal-mode frequencies of linear equations of n coordinates at `params`, slowest first:
/// √λ for the eigenvalues λ of M⁻¹K, M and K read off the equations by their change from one
/// unit of each acceleration and coordinate, λ by nalgebra's Schur decomposition (NaN for a λ
/// that is not real). No engine: the route a mode's answer and the step's check both take.
pub(crate) fn numeric_modes(
    linear: &[(String, Expr)],
    params: &BTreeMap<String, f64>,
) -> Result<Vec<f64>, CheckError> {
    let coords: Vec<&String> = linear.iter().map(|(q, _)| q).collect();
    let n = coords.len();
    // The equations are affine in the state: a column is the change from one unit of one name.
    let residuals = |name: Option<String>| -> Result<Vec<f64>, CheckError> {
        let mut p = state(params, &coords, &vec![0.0; 2 * n], &vec![0.0; n]);
        if let Some(name) = name {
            p.insert(name, 1.0);
        }
        linear.iter().map(|(_, e)| at(e, &p)).collect()
    };
    let base = residuals(None)?;
    let (mut m, mut k) = (
        nalgebra::DMatrix::zeros(n, n),
        nalgebra::DMatrix::zeros(n, n),
    );
    for (j, q) in coords.iter().enumerate() {
        let (rm, rk) = (
            residuals(Some(format!("{q}''")))?,
            residuals(Some((*q).clone()))?,
        );
        for i in 0..n {
            m[(i, j)] = rm[i] - base[i];
            k[(i, j)] = rk[i] - base[i];
        }
    }
    let a = m.lu().solve(&k).ok_or(CheckError::Singular)?;
    let lambdas = crate::base::float::complex_eigenvalues(a).ok_or(CheckError::NoEigenvalues)?;
    let scale = lambdas.iter().fold(0.0_f64, |a, l| a.max(l.norm()));
    let mut numeric: Vec<f64> = lambdas
        .iter()
        .map(|l| {
            if l.norm() <= crate::derive::modes::ZERO_MODE * scale {
                // A free motion: λ is zero to the round-off of its companions.
                0.0
            } else if l.im.abs() <= 1e-12 * l.norm() {
                l.re.sqrt()
            } else {
                f64::NAN
            }
        })
        .collect();
    numeric.sort_by(f64::total_cmp);
    Ok(numeric)
}
