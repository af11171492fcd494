//! A general first-order system y' = f(t, y), for the equations of motion an author derives:
//! Dormand–Prince 5(4) with local extrapolation and the standard step controller (Hairer,
//! Nørsett & Wanner, Solving ODE I, II.4–5), error per step ≤ tol·(1 + |y|). The rigid body's
//! own integrators are in `integrators.rs`; this one knows nothing of the system it solves.

/// Why a run stopped before its end time.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OdeError {
    #[error("the right-hand side cannot be evaluated at t = {t}: {message}")]
    Rhs { t: f64, message: String },
    #[error(
        "more than {cap} steps before t = {t_end} (the motion may blow up); stopped at t = {t}"
    )]
    StepsOverCap { cap: u64, t_end: f64, t: f64 },
    #[error("the step shrank below {h:e} at t = {t}: the solution may be singular there")]
    StepUnderflow { t: f64, h: f64 },
}

/// Every accepted step's time and state, from the start, and the work done.
#[derive(Debug, Clone)]
pub struct OdeRun {
    pub states: Vec<(f64, Vec<f64>)>,
    pub evaluations: u64,
}

/// The Dormand–Prince 5(4) tableau (Hairer, Nørsett & Wanner, Solving ODE I, II.5): the stages'
/// weights, the sixth row the fifth-order solution's; shared with the free rigid body's
/// integrator (`integrators.rs`).
pub(super) const A: [[f64; 6]; 6] = [
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
const C: [f64; 6] = [1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
/// b5 − b4, for the error estimate (the seventh stage is f at the new point).
pub(super) const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

/// A system's right-hand side: y' at (t, y), or why it has none there.
pub type Rhs<'a, E> = dyn Fn(f64, &[f64]) -> Result<Vec<f64>, E> + 'a;

/// Integrates from (0, y0) to `t_end`.
pub fn dormand_prince<E: std::fmt::Display>(
    f: &Rhs<'_, E>,
    y0: &[f64],
    t_end: f64,
    tol: f64,
    max_steps: u64,
) -> Result<OdeRun, OdeError> {
    let n = y0.len();
    let mut evaluations = 0u64;
    let mut eval = |t: f64, y: &[f64]| {
        evaluations += 1;
        f(t, y).map_err(|e| OdeError::Rhs {
            t,
            message: e.to_string(),
        })
    };
    let (mut t, mut y) = (0.0, y0.to_vec());
    let mut states = vec![(t, y.clone())];
    let mut k0 = eval(t, &y)?;
    let mut h = (t_end / 100.0).min(0.01 * (1.0 + norm(&y)) / (norm(&k0) + 1e-300));
    let mut steps = 0u64;
    while t < t_end {
        if steps >= max_steps {
            return Err(OdeError::StepsOverCap {
                cap: max_steps,
                t_end,
                t,
            });
        }
        // t + (t_end − t) can fall an ulp short of t_end: that sliver is the end reached, not
        // a step shrunk by a singularity (a free top's precession over 1/|ω3| stopped there).
        if t_end - t <= 4.0 * f64::EPSILON * t_end {
            states.last_mut().expect("a run keeps its start").0 = t_end;
            break;
        }
        h = h.min(t_end - t);
        // The step to the end lands on it, not an ulp either side.
        let to_the_end = h == t_end - t;
        if h < 1e-14 * t_end.max(1.0) {
            return Err(OdeError::StepUnderflow { t, h });
        }
        let mut k = vec![k0.clone()];
        for (s, row) in A.iter().enumerate() {
            let yi: Vec<f64> = (0..n)
                .map(|j| y[j] + h * (0..=s).map(|m| row[m] * k[m][j]).sum::<f64>())
                .collect();
            k.push(eval(t + C[s] * h, &yi)?);
        }
        // The sixth row is the fifth-order solution; k[6] is f there (first same as last).
        let y_new: Vec<f64> = (0..n)
            .map(|j| y[j] + h * (0..6).map(|m| A[5][m] * k[m][j]).sum::<f64>())
            .collect();
        let err = (0..n)
            .map(|j| {
                let e = h * (0..7).map(|m| E[m] * k[m][j]).sum::<f64>();
                (e / (tol * (1.0 + y[j].abs().max(y_new[j].abs())))).powi(2)
            })
            .sum::<f64>();
        let err = (err / n as f64).sqrt();
        steps += 1;
        if err <= 1.0 {
            t = if to_the_end { t_end } else { t + h };
            y = y_new;
            k0 = k.swap_remove(6);
            states.push((t, y.clone()));
        }
        let factor = if err == 0.0 {
            5.0
        } else {
            (0.9 * err.powf(-0.2)).clamp(0.2, 5.0)
        };
        h *= factor;
    }
    Ok(OdeRun {
        states,
        evaluations,
    })
}

fn norm(y: &[f64]) -> f64 {
    y.iter().map(|x| x * x).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The harmonic oscillator x'' = −x from (1, 0): x(t) = cos t, and the error follows the
    /// tolerance down.
    #[test]
    fn an_oscillator_follows_its_exact_solution_within_its_tolerance() {
        let f = |_t: f64, y: &[f64]| Ok::<_, String>(vec![y[1], -y[0]]);
        let mut last = f64::INFINITY;
        for tol in [1e-6, 1e-9, 1e-12] {
            let run = dormand_prince(&f, &[1.0, 0.0], 10.0, tol, 100_000).unwrap();
            let (t, y) = run.states.last().unwrap();
            assert_eq!(*t, 10.0);
            let error = (y[0] - 10f64.cos()).abs().max((y[1] + 10f64.sin()).abs());
            assert!(error < 100.0 * tol, "tol {tol}: error {error}");
            assert!(error < last, "tol {tol}: error {error} not below {last}");
            last = error;
        }
    }

    /// A constant solution takes steps growing fivefold; for 248 of these 5000 ends the last
    /// one fell an ulp short of t_end (58.82… = 1/0.017 is the first), which was refused as a
    /// step shrunk by a singularity, and for others it passed t_end by an ulp (27.027…). Each
    /// now ends at t_end exactly.
    #[test]
    fn an_end_reached_within_rounding_is_the_end() {
        let f = |_t: f64, _y: &[f64]| Ok::<_, String>(vec![0.0]);
        for k in 1..5000 {
            let t_end = 1.0 / (k as f64 / 1000.0);
            let run = dormand_prince(&f, &[1.0], t_end, 1e-10, 1000)
                .unwrap_or_else(|e| panic!("t_end {t_end}: {e}"));
            assert_eq!(run.states.last().unwrap().0, t_end);
        }
        // (A blow-up before the end is still refused: `a_blow_up_stops_with_its_reason`.)
    }

    /// A time-dependent right-hand side: y' = cos t gives sin t.
    #[test]
    fn the_stage_times_are_right() {
        let f = |t: f64, _y: &[f64]| Ok::<_, String>(vec![t.cos()]);
        let run = dormand_prince(&f, &[0.0], 3.0, 1e-10, 100_000).unwrap();
        let (_, y) = run.states.last().unwrap();
        assert!((y[0] - 3f64.sin()).abs() < 1e-8, "{}", y[0]);
    }

    #[test]
    fn a_blow_up_stops_with_its_reason() {
        // y' = y², y(0) = 1: y = 1/(1 − t) blows up at t = 1.
        let f = |_t: f64, y: &[f64]| Ok::<_, String>(vec![y[0] * y[0]]);
        let e = dormand_prince(&f, &[1.0], 2.0, 1e-9, 10_000).unwrap_err();
        assert!(
            matches!(
                e,
                OdeError::StepsOverCap { .. } | OdeError::StepUnderflow { .. }
            ),
            "{e:?}"
        );
    }
}
