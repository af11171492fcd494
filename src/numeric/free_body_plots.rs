//! Plots of the torque-free body (Lecture 3/9): ω(t), polhodes, invariant drift, the tennis
//! racket's flips, the herpolhode and Earth's polar motion. Each description quotes what was
//! measured, next to what the exact solution predicts.

use super::fidelity::Fidelity;
use super::free_body::{ExactSolution, Moments, invariants};
use super::integrators::{Method, Resolution, Run, integrate};
use super::plots::{ERROR_FLOOR, plane_basis, project};
use crate::figure::{Accuracy, Figure, Legend, Mark, Scale, Series};
use crate::report::{sci, short};
use crate::scene::FreeBodyPlot;
use nalgebra::Vector3;
use std::f64::consts::PI;

pub fn figure(
    kind: FreeBodyPlot,
    inertia: [f64; 3],
    omega: [f64; 3],
    t: f64,
    fidelity: &Fidelity,
) -> Result<Figure, String> {
    let i = Moments::new(inertia)?;
    let w0 = Vector3::from(omega);
    let f = fidelity;
    match kind {
        FreeBodyPlot::OmegaVsTime => omega_vs_time(&i, w0, t, f),
        FreeBodyPlot::Polhodes => polhodes(&i, w0, f),
        FreeBodyPlot::Drift => drift(&i, w0, t, f),
        FreeBodyPlot::Flip => flip(&i, w0, t, f),
        FreeBodyPlot::AxisSpins => axis_spins(&i, w0, t, f),
        FreeBodyPlot::Herpolhode => herpolhode(&i, w0, t, f),
        FreeBodyPlot::PolarMotion => polar_motion(&i, w0, f),
        FreeBodyPlot::Cones => cones(&i, w0, t, f),
        FreeBodyPlot::IntegratorPareto => integrator_pareto(&i, w0, t, f),
    }
}

/// Every integrator over a ladder of steps (tolerances for Dormand–Prince): its error at
/// `t_end` against the exact solution, relative to |ω(0)|, against its right-hand-side
/// evaluations, and the Pareto front over all of them. The fidelity sets the finest rung.
pub fn integrator_pareto(
    i: &Moments,
    w0: Vector3<f64>,
    t_end: f64,
    fid: &Fidelity,
) -> Result<Figure, String> {
    let exact = ExactSolution::new(i, w0).omega(t_end);
    let finest_step = fid.ode_step(0.005) * 0.999;
    let finest_tol = fid.ode_tolerance(1e-12) * 0.999;
    let steps: Vec<f64> = [0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.0025, 0.00125]
        .into_iter()
        .filter(|h| *h >= finest_step)
        .collect();
    let tols: Vec<f64> = [1e-3, 1e-5, 1e-7, 1e-9, 1e-11, 1e-13]
        .into_iter()
        .filter(|t| *t >= finest_tol)
        .collect();
    let methods = [
        ("RK4", Method::Rk4),
        ("Strang splitting", Method::Splitting),
        ("triple jump", Method::Splitting4),
        ("Dormand–Prince 5(4)", Method::Dopri),
    ];
    let mut series = Vec::new();
    let mut accuracy = Vec::new();
    let mut sentences = Vec::new();
    let mut all = Vec::new();
    for (colour, (name, method)) in methods.into_iter().enumerate() {
        let settings: Vec<Resolution> = if method == Method::Dopri {
            tols.iter().map(|t| Resolution::Tolerance(*t)).collect()
        } else {
            steps.iter().map(|h| Resolution::Step(*h)).collect()
        };
        let mut points = Vec::new();
        let mut runs = Vec::new();
        for r in settings {
            let run = integrate(i, w0, t_end, method, r, 0)?;
            let error = (run.omega - exact).norm() / w0.norm();
            points.push((run.rhs_evaluations as f64, error.max(ERROR_FLOOR)));
            runs.push((r, run, error));
        }
        let (r, finest, error) = runs.last().ok_or("no integrator settings")?;
        let setting = match r {
            Resolution::Step(h) => format!("{name}, h = {h}"),
            Resolution::Tolerance(t) => format!("{name}, tol {}", short(*t)),
        };
        sentences.push(format!(
            "{setting}: {} in {} right-hand sides",
            sci(*error),
            finest.rhs_evaluations
        ));
        accuracy.push(Accuracy {
            result: format!("ω({t_end}), {} settings, the finest", runs.len()),
            method: setting,
            true_error: Some(*error),
            estimated_error: Some(finest.energy_drift.max(finest.momentum_drift)),
            cost: runs.iter().map(|(_, r, _)| r.rhs_evaluations).sum(),
            unit: "right-hand sides".into(),
            seconds: runs.iter().map(|(_, r, _)| r.seconds).sum(),
        });
        all.extend(points.iter().copied());
        series.push(Series {
            name: name.into(),
            mark: Mark::Points,
            colour,
            points,
        });
    }
    let front = super::plots::pareto_front(&all);
    series.push(Series {
        name: "Pareto front".into(),
        mark: Mark::Line,
        colour: 5,
        points: front.clone(),
    });
    let desc = format!(
        "Error of ω({t_end}) against the exact solution, relative to |ω(0)|, against the \
         right-hand-side evaluations it cost, log-log, for {} with every integrator at steps {} \
         and Dormand–Prince at tolerances {}. Finest settings: {}. The Pareto front (the runs no \
         other run beats on both error and cost) has {} of the {} runs. Errors below {} are drawn \
         at that floor.",
        body_text(i, &w0),
        steps
            .iter()
            .map(|h| h.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        tols.iter()
            .map(|t| short(*t))
            .collect::<Vec<_>>()
            .join(", "),
        sentences.join("; "),
        front.len(),
        all.len(),
        sci(ERROR_FLOOR)
    );
    let mut f = fig(
        "integrator-pareto",
        "Integrators: error against cost".into(),
        desc,
        "right-hand-side evaluations",
        "relative error at the end",
        series,
    );
    f.x_scale = Scale::Log;
    f.y_scale = Scale::Log;
    f.legend = Legend::LowerLeft;
    f.accuracy = accuracy;
    Ok(f)
}

/// The exact solution sampled at `times`: it is the reference, so its own error shows only as
/// the drift of 2T and |L| along the samples (round-off in the elliptic functions).
fn exact_accuracy(result: &str, i: &Moments, w0: &Vector3<f64>, times: &[f64]) -> Accuracy {
    let start = std::time::Instant::now();
    let sol = ExactSolution::new(i, *w0);
    let (t0, l0) = invariants(i, w0);
    let drift = times
        .iter()
        .map(|t| {
            let (tt, l) = invariants(i, &sol.omega(*t));
            ((tt - t0) / t0).abs().max(((l - l0) / l0).abs())
        })
        .fold(0.0, f64::max);
    Accuracy {
        result: result.into(),
        method: "exact (Jacobi elliptic functions)".into(),
        true_error: None,
        estimated_error: Some(drift),
        cost: times.len() as u64,
        unit: "evaluations".into(),
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// An integration's accuracy: its error against the exact solution at every traced sample
/// (relative to |ω(0)|), and the invariant drift it would show without one.
fn run_accuracy(
    result: &str,
    setting: String,
    run: &Run,
    i: &Moments,
    w0: &Vector3<f64>,
) -> Accuracy {
    let sol = ExactSolution::new(i, *w0);
    let true_error = run
        .trace
        .iter()
        .map(|(t, w, _)| (w - sol.omega(*t)).norm() / w0.norm())
        .chain([(run.omega - sol.omega(run.trace.last().map_or(0.0, |p| p.0))).norm() / w0.norm()])
        .fold(0.0, f64::max);
    Accuracy {
        result: result.into(),
        method: setting,
        true_error: Some(true_error),
        estimated_error: Some(run.energy_drift.max(run.momentum_drift)),
        cost: run.rhs_evaluations,
        unit: "right-hand sides".into(),
        seconds: run.seconds,
    }
}

/// Several runs of one method drawn as one result: the worst errors and the total cost.
fn merged(result: &str, parts: Vec<Accuracy>) -> Accuracy {
    let worst = |f: fn(&Accuracy) -> Option<f64>| parts.iter().filter_map(f).reduce(f64::max);
    Accuracy {
        result: format!("{result} ({} runs)", parts.len()),
        method: parts.first().map_or(String::new(), |p| p.method.clone()),
        true_error: worst(|a| a.true_error),
        estimated_error: worst(|a| a.estimated_error),
        cost: parts.iter().map(|a| a.cost).sum(),
        unit: parts.first().map_or(String::new(), |p| p.unit.clone()),
        seconds: parts.iter().map(|a| a.seconds).sum(),
    }
}

fn times(t_end: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|j| t_end * j as f64 / n as f64).collect()
}

fn fig(slug: &str, title: String, desc: String, x: &str, y: &str, series: Vec<Series>) -> Figure {
    Figure {
        slug: slug.into(),
        title,
        desc,
        x_label: x.into(),
        y_label: y.into(),
        x_scale: Scale::Linear,
        y_scale: Scale::Linear,
        equal_aspect: false,
        series,
        labels: Vec::new(),
        legend: Legend::UpperRight,
        accuracy: Vec::new(),
    }
}

fn body_text(i: &Moments, w0: &Vector3<f64>) -> String {
    format!(
        "I = ({}, {}, {}), ω(0) = ({}, {}, {})",
        i.0[0], i.0[1], i.0[2], w0.x, w0.y, w0.z
    )
}

fn motion_text(sol: &ExactSolution) -> String {
    let mut s = String::new();
    if let Some((m, mc)) = sol.parameter() {
        s.push_str(&format!("m = {m:.6} (1 − m = {}), ", sci(mc)));
    }
    match sol.period() {
        Some(p) => s.push_str(&format!("period of ω {p:.6}")),
        None => s.push_str("steady rotation"),
    }
    s
}

fn omega_vs_time(
    i: &Moments,
    w0: Vector3<f64>,
    t_end: f64,
    fid: &Fidelity,
) -> Result<Figure, String> {
    let sol = ExactSolution::new(i, w0);
    let n = fid.samples(400);
    let tol = fid.ode_tolerance(1e-10);
    let mut series = Vec::new();
    let dp = integrate(i, w0, t_end, Method::Dopri, Resolution::Tolerance(tol), 24)?;
    for (k, name) in ["ω1", "ω2", "ω3"].into_iter().enumerate() {
        series.push(Series {
            name: format!("{name} exact"),
            mark: Mark::Line,
            colour: k,
            points: (0..=n)
                .map(|j| {
                    let t = t_end * j as f64 / n as f64;
                    (t, sol.omega(t)[k])
                })
                .collect(),
        });
        series.push(Series {
            name: String::new(),
            mark: Mark::Points,
            colour: k,
            points: dp.trace.iter().map(|(t, w, _)| (*t, w[k])).collect(),
        });
    }
    let dots = run_accuracy(
        "ω(t) dots",
        format!("Dormand–Prince 5(4), tol {}", short(tol)),
        &dp,
        i,
        &w0,
    );
    let desc = format!(
        "Body-frame angular velocity of the free body with {} over 0 ≤ t ≤ {t_end}: {}. Lines: \
         the exact solution; dots: Dormand–Prince 5(4) at tol {} ({} right-hand sides), at most \
         {} from it relative to |ω(0)|.",
        body_text(i, &w0),
        motion_text(&sol),
        short(tol),
        dp.rhs_evaluations,
        sci(dots.true_error.unwrap_or(0.0))
    );
    let mut f = fig(
        "omega-vs-time",
        "Angular velocity in the body frame".into(),
        desc,
        "t",
        "ω",
        series,
    );
    f.legend = Legend::LowerRight;
    f.accuracy = vec![
        exact_accuracy("ω(t) curves", i, &w0, &times(t_end, n)),
        dots,
    ];
    Ok(f)
}

/// Indices of the smallest, middle and largest moments.
fn sorted_axes(i: &Moments) -> [usize; 3] {
    let mut o = [0, 1, 2];
    o.sort_by(|a, b| i.0[*a].total_cmp(&i.0[*b]));
    o
}

fn polhodes(i: &Moments, w0: Vector3<f64>, fid: &Fidelity) -> Result<Figure, String> {
    let n = fid.samples(240);
    let mut exact_runs = Vec::new();
    let [a, b, c] = sorted_axes(i);
    let (ia, ib, ic) = (i.0[a], i.0[b], i.0[c]);
    if ia == ic {
        return Err("polhodes need unequal moments (a sphere has none)".into());
    }
    let (two_t, _) = invariants(i, &w0);
    let mut series = Vec::new();
    let l_of = |w: &Vector3<f64>| Vector3::new(i.0[0] * w.x, i.0[1] * w.y, i.0[2] * w.z);
    // The energy ellipsoid's three principal sections, for orientation.
    for (p, q) in [(0, 1), (1, 2), (0, 2)] {
        let pts: Vec<(f64, f64)> = (0..=120)
            .map(|k| {
                let s = k as f64 * 2.0 * PI / 120.0;
                let mut l = Vector3::zeros();
                l[p] = (two_t * i.0[p]).sqrt() * s.cos();
                l[q] = (two_t * i.0[q]).sqrt() * s.sin();
                project(&l)
            })
            .collect();
        series.push(Series {
            name: if p == 0 && q == 1 {
                "energy ellipsoid".into()
            } else {
                String::new()
            },
            mark: Mark::Dashed,
            colour: 5,
            points: pts,
        });
    }
    let mut closed = Vec::new();
    for f in [0.05, 0.25, 0.45, 0.55, 0.75, 0.95] {
        // L² between 2T·I_min and 2T·I_max; start on the plane ω_mid = 0.
        let l2 = two_t * (ia + f * (ic - ia));
        if (l2 - two_t * ib).abs() < 1e-9 * l2 {
            continue;
        }
        let mut w = Vector3::zeros();
        w[a] = ((two_t * ic - l2) / (ia * (ic - ia))).max(0.0).sqrt();
        w[c] = ((l2 - two_t * ia) / (ic * (ic - ia))).max(0.0).sqrt();
        let sol = ExactSolution::new(i, w);
        let period = sol.period().unwrap_or(2.0 * PI);
        let around = if l2 > two_t * ib { c } else { a };
        closed.push(around);
        exact_runs.push(exact_accuracy("", i, &w, &times(period, n)));
        for sign in [1.0, -1.0] {
            series.push(Series {
                name: if f == 0.05 && sign > 0.0 {
                    "polhodes".into()
                } else {
                    String::new()
                },
                mark: Mark::Line,
                colour: if around == c { 0 } else { 2 },
                points: (0..=n)
                    .map(|k| project(&(l_of(&sol.omega(period * k as f64 / n as f64)) * sign)))
                    .collect(),
            });
        }
    }
    let mut sep_text = String::from("no separatrix (two equal moments)");
    if ib > ia && ib < ic {
        // d = 0: (I_c − I_b) L_c² / I_c = (I_b − I_a) L_a² / I_a, two planes through the middle
        // axis; on the sphere |L|² = 2T·I_b they are great circles.
        let k = ((ib - ia) * ic / ((ic - ib) * ia)).sqrt();
        let radius = (two_t * ib).sqrt();
        for (j, sign) in [1.0, -1.0].into_iter().enumerate() {
            let mut u = Vector3::zeros();
            u[a] = 1.0;
            u[c] = sign * k;
            let u = u.normalize();
            let e = Vector3::ith(b, 1.0);
            series.push(Series {
                name: if j == 0 {
                    "separatrix".into()
                } else {
                    String::new()
                },
                mark: Mark::Line,
                colour: 1,
                points: (0..=240)
                    .map(|n| {
                        let s = n as f64 * 2.0 * PI / 240.0;
                        project(&((u * s.cos() + e * s.sin()) * radius))
                    })
                    .collect(),
            });
        }
        sep_text = format!(
            "the separatrix, L² = 2T·I{} = {:.4}, is two great circles through the ±L{} points",
            b + 1,
            two_t * ib,
            b + 1
        );
    }
    let n_max = closed.iter().filter(|&&x| x == c).count();
    let desc = format!(
        "Polhodes: the paths of L in the body frame on the energy ellipsoid 2T = {two_t:.4} \
         (I = ({}, {}, {})), for six values of L² between 2T·I{} and 2T·I{}, each traced by the \
         exact solution over one period, with its mirror image. {} close around the axis of the \
         largest moment (I{}) and {} around the smallest (I{}); none close around the middle \
         axis (I{}): {sep_text}. Oblique view, azimuth 25°, elevation 20°.",
        i.0[0],
        i.0[1],
        i.0[2],
        a + 1,
        c + 1,
        n_max,
        c + 1,
        closed.len() - n_max,
        a + 1,
        b + 1
    );
    let mut f = fig(
        "polhodes",
        "Polhodes on the energy ellipsoid".into(),
        desc,
        "",
        "",
        series,
    );
    f.equal_aspect = true;
    f.labels = (0..3)
        .map(|k| {
            let mut l = Vector3::zeros();
            l[k] = 1.08 * (two_t * i.0[k]).sqrt();
            (format!("L{}", k + 1), project(&l))
        })
        .collect();
    f.accuracy = vec![merged("polhodes", exact_runs)];
    Ok(f)
}

fn drift(i: &Moments, w0: Vector3<f64>, t_end: f64, fid: &Fidelity) -> Result<Figure, String> {
    let (t0, l0) = invariants(i, &w0);
    let (h, tol) = (fid.ode_step(0.05), fid.ode_tolerance(1e-9));
    let runs = [
        (format!("RK4 h = {h}"), Method::Rk4, Resolution::Step(h)),
        (
            format!("Dormand–Prince tol {}", short(tol)),
            Method::Dopri,
            Resolution::Tolerance(tol),
        ),
        (
            format!("Strang splitting h = {h}"),
            Method::Splitting,
            Resolution::Step(h),
        ),
        (
            format!("triple jump h = {h}"),
            Method::Splitting4,
            Resolution::Step(h),
        ),
    ];
    let mut series = Vec::new();
    let mut parts = Vec::new();
    let mut accuracy = Vec::new();
    for (k, (name, m, r)) in runs.into_iter().enumerate() {
        let run = integrate(i, w0, t_end, m, r, fid.samples(200))?;
        accuracy.push(run_accuracy("ω(t)", name.clone(), &run, i, &w0));
        let energy: Vec<(f64, f64)> = run
            .trace
            .iter()
            .filter(|(t, ..)| *t > 0.0)
            .map(|(t, w, _)| (*t, ((invariants(i, w).0 - t0).abs() / t0).max(ERROR_FLOOR)))
            .collect();
        let length: Vec<(f64, f64)> = run
            .trace
            .iter()
            .filter(|(t, ..)| *t > 0.0)
            .map(|(t, w, _)| (*t, ((invariants(i, w).1 - l0).abs() / l0).max(ERROR_FLOOR)))
            .collect();
        parts.push(format!(
            "{name}: energy {} and |L| {} at the end, {} right-hand sides",
            sci(energy.last().map_or(0.0, |p| p.1)),
            sci(length.last().map_or(0.0, |p| p.1)),
            run.rhs_evaluations
        ));
        series.push(Series {
            name: format!("{name}: energy"),
            mark: Mark::Line,
            colour: k,
            points: energy,
        });
        series.push(Series {
            name: String::new(),
            mark: Mark::Dashed,
            colour: k,
            points: length,
        });
    }
    let desc = format!(
        "Relative error of the energy 2T (solid) and of |L| (dashed) against time for the free body \
         with {}, log scale; errors below {} are drawn at that floor. {}. RK4 and Dormand–Prince \
         drift; the splittings keep |L| at round-off and their energy error bounded.",
        body_text(i, &w0),
        sci(ERROR_FLOOR),
        parts.join("; ")
    );
    let mut f = fig(
        "drift",
        "Invariant drift of each integrator".into(),
        desc,
        "t",
        "relative error",
        series,
    );
    f.y_scale = Scale::Log;
    f.legend = Legend::LowerRight;
    f.accuracy = accuracy;
    Ok(f)
}

/// Times where component `k` changes sign, by linear interpolation between trace samples.
fn sign_changes(run: &Run, k: usize) -> Vec<f64> {
    run.trace
        .windows(2)
        .filter(|w| w[0].1[k] * w[1].1[k] < 0.0)
        .map(|w| {
            let (t0, y0, t1, y1) = (w[0].0, w[0].1[k], w[1].0, w[1].1[k]);
            t0 + (t1 - t0) * y0 / (y0 - y1)
        })
        .collect()
}

fn flip(i: &Moments, w0: Vector3<f64>, t_end: f64, fid: &Fidelity) -> Result<Figure, String> {
    let [a, b, c] = sorted_axes(i);
    let (ia, ib, ic) = (i.0[a], i.0[b], i.0[c]);
    if !(ia < ib && ib < ic) {
        return Err("the flip needs three different moments".into());
    }
    let sol = ExactSolution::new(i, w0);
    let (_, mc) = sol
        .parameter()
        .ok_or("the flip needs the asymmetric solution")?;
    let period = sol.period().ok_or("the motion is not periodic")?;
    let (two_t, _) = invariants(i, &w0);
    // REFERENCE.md: σ = ω2 √((I3 − I2)(I2 − I1)/(I1 I3)) with ω2 = √(2T/I2), the separatrix's
    // limit; flips every 2K/λ ≈ ln(16/(1 − m))/σ.
    let sigma = (two_t / ib).sqrt() * ((ic - ib) * (ib - ia) / (ia * ic)).sqrt();
    let approx = (16.0 / mc).ln() / sigma;
    let tol = fid.ode_tolerance(1e-11);
    let dp = integrate(
        i,
        w0,
        t_end,
        Method::Dopri,
        Resolution::Tolerance(tol),
        fid.samples(4000),
    )?;
    let flips = sign_changes(&dp, b);
    let measured = if flips.len() >= 2 {
        Some((flips[flips.len() - 1] - flips[0]) / (flips.len() - 1) as f64)
    } else {
        None
    };
    let n = fid.samples(600);
    let series = vec![
        Series {
            name: format!("ω{} exact", b + 1),
            mark: Mark::Line,
            colour: 0,
            points: (0..=n)
                .map(|j| {
                    let t = t_end * j as f64 / n as f64;
                    (t, sol.omega(t)[b])
                })
                .collect(),
        },
        Series {
            name: "flips measured (Dormand–Prince)".into(),
            mark: Mark::Points,
            colour: 1,
            points: flips.iter().map(|t| (*t, 0.0)).collect(),
        },
    ];
    let desc = format!(
        "Tennis racket: spin started near the middle axis (I{} = {ib}) of I = ({}, {}, {}), \
         ω(0) = ({}, {}, {}). The component ω{} reverses again and again. Measured from Dormand–Prince \
         (tol {}) sign changes: {} flips, every {}; predicted: exactly 2K/λ = {:.6}, and \
         approximately ln(16/(1 − m))/σ = {:.6} with 1 − m = {} and σ = {:.6}.",
        b + 1,
        i.0[0],
        i.0[1],
        i.0[2],
        w0.x,
        w0.y,
        w0.z,
        b + 1,
        short(tol),
        flips.len(),
        measured.map_or(
            "(fewer than two flips in the window)".to_string(),
            |m| format!("{m:.6}")
        ),
        period / 2.0,
        approx,
        sci(mc),
        sigma
    );
    let mut f = fig(
        "flip",
        "Intermediate-axis flips".into(),
        desc,
        "t",
        &format!("ω{}", b + 1),
        series,
    );
    f.legend = Legend::LowerRight;
    let setting = format!("Dormand–Prince 5(4), tol {}", short(tol));
    let mut flip_period = run_accuracy("time between flips", setting.clone(), &dp, i, &w0);
    flip_period.true_error = measured.map(|m| (m - period / 2.0).abs() / (period / 2.0));
    flip_period.estimated_error = None;
    f.accuracy = vec![
        exact_accuracy(&format!("ω{} curve", b + 1), i, &w0, &times(t_end, n)),
        run_accuracy(&format!("ω{} integrated", b + 1), setting, &dp, i, &w0),
        flip_period,
    ];
    Ok(f)
}

/// The largest component of ω(0) is the spin and the other two the wobble; the same start is
/// turned onto each principal axis in turn, and the exact solution gives ω's angle from it.
fn axis_spins(i: &Moments, w0: Vector3<f64>, t_end: f64, fid: &Fidelity) -> Result<Figure, String> {
    let k0 = w0.iamax();
    let (spin, wobble) = (w0[k0], [w0[(k0 + 1) % 3], w0[(k0 + 2) % 3]]);
    if wobble.iter().any(|x| x.abs() >= spin.abs()) {
        return Err("axis-spins needs one component of omega larger than the other two".into());
    }
    let [small, middle, large] = sorted_axes(i);
    let n = fid.samples(600);
    let mut series = Vec::new();
    let mut exact_runs = Vec::new();
    let mut largest = [0.0f64; 3];
    for k in 0..3 {
        let mut w = Vector3::zeros();
        w[k] = spin;
        w[(k + 1) % 3] = wobble[0];
        w[(k + 2) % 3] = wobble[1];
        let sol = ExactSolution::new(i, w);
        exact_runs.push(exact_accuracy("", i, &w, &times(t_end, n)));
        let points: Vec<(f64, f64)> = (0..=n)
            .map(|j| {
                let t = t_end * j as f64 / n as f64;
                let wt = sol.omega(t);
                let deg = (wt[k] / wt.norm()).clamp(-1.0, 1.0).acos().to_degrees();
                largest[k] = largest[k].max(deg);
                (t, deg)
            })
            .collect();
        series.push(Series {
            name: format!("about axis {} (I{} = {})", k + 1, k + 1, i.0[k]),
            mark: if k == middle {
                Mark::Line
            } else {
                Mark::Dashed
            },
            colour: k,
            points,
        });
    }
    let rank = |k: usize| {
        if k == middle {
            "intermediate, unstable"
        } else if k == small {
            "smallest, stable"
        } else {
            debug_assert_eq!(k, large);
            "largest, stable"
        }
    };
    let desc = format!(
        "Spin {spin} about each principal axis of I = ({}, {}, {}) in turn, with {} and {} on the \
         other two axes; the exact solution gives the angle between ω and the axis it started on \
         (180° is a full reversal). Largest angle over t ≤ {t_end}: axis 1 ({}) {:.3}°, axis 2 \
         ({}) {:.3}°, axis 3 ({}) {:.3}°. Only the axis with the intermediate moment departs, as \
         the sign of Ω² in eqs (72)–(73) predicts.",
        i.0[0],
        i.0[1],
        i.0[2],
        wobble[0],
        wobble[1],
        rank(0),
        largest[0],
        rank(1),
        largest[1],
        rank(2),
        largest[2]
    );
    let mut f = fig(
        "axis-spins",
        "Spin about each principal axis".into(),
        desc,
        "t",
        "angle from the starting axis / degrees",
        series,
    );
    f.accuracy = vec![merged("angle from each axis", exact_runs)];
    Ok(f)
}

fn herpolhode(i: &Moments, w0: Vector3<f64>, t_end: f64, fid: &Fidelity) -> Result<Figure, String> {
    let (two_t, l) = invariants(i, &w0);
    let l_space = Vector3::new(i.0[0] * w0.x, i.0[1] * w0.y, i.0[2] * w0.z);
    let n = l_space.normalize();
    let (u, v) = plane_basis(&n);
    let tol = fid.ode_tolerance(1e-11);
    let dp = integrate(
        i,
        w0,
        t_end,
        Method::Dopri,
        Resolution::Tolerance(tol),
        fid.samples(3000),
    )?;
    let mut height_dev: f64 = 0.0;
    let expected = two_t.sqrt() / l;
    let pts: Vec<(f64, f64)> = dp
        .trace
        .iter()
        .map(|(_, w, q)| {
            let rho = q * w / two_t.sqrt();
            height_dev = height_dev.max((rho.dot(&n) - expected).abs() / expected);
            (rho.dot(&u), rho.dot(&v))
        })
        .collect();
    let desc = format!(
        "Herpolhode: the tip of ρ = ω/√(2T) in space, projected on the invariable plane (normal to \
         the fixed L), for {} over 0 ≤ t ≤ {t_end}, from Dormand–Prince 5(4) at tol {} with the \
         attitude. The plane's distance from the centre stays √(2T)/L = {expected:.6} to {} \
         (eq 81), and L stays fixed in space to {}.",
        body_text(i, &w0),
        short(tol),
        sci(height_dev),
        sci(dp.space_momentum_drift)
    );
    let mut f = fig(
        "herpolhode",
        "Herpolhode on the invariable plane".into(),
        desc,
        "",
        "",
        vec![Series {
            name: "herpolhode".into(),
            mark: Mark::Line,
            colour: 0,
            points: pts,
        }],
    );
    f.equal_aspect = true;
    let mut acc = run_accuracy(
        "herpolhode",
        format!("Dormand–Prince 5(4) with the attitude, tol {}", short(tol)),
        &dp,
        i,
        &w0,
    );
    // The attitude has no cheap exact value; L's drift in space is its error estimate.
    acc.estimated_error = acc.estimated_error.map(|e| e.max(dp.space_momentum_drift));
    f.accuracy = vec![acc];
    Ok(f)
}

use crate::derive::earth;
/// Mean solar days per sidereal day: a tropical year holds one more sidereal day than solar days.
const SOLAR_PER_SIDEREAL: f64 = {
    let year = earth::TROPICAL_YEAR_DAYS.0 as f64 / earth::TROPICAL_YEAR_DAYS.1 as f64;
    year / (year + 1.0)
};
/// The dynamical ellipticity H = (C − A)/C and the observed Chandler period in days, as cited in
/// `derive::earth`.
pub const EARTH_H: f64 =
    earth::DYNAMICAL_ELLIPTICITY.0 as f64 / earth::DYNAMICAL_ELLIPTICITY.1 as f64;
pub const CHANDLER_DAYS: f64 = earth::CHANDLER_DAYS as f64;

/// ω in radians per sidereal day: ω3 = 2π is one turn per sidereal day.
fn polar_motion(i: &Moments, w0: Vector3<f64>, fid: &Fidelity) -> Result<Figure, String> {
    let sol = ExactSolution::new(i, w0);
    let period = sol
        .period()
        .ok_or("polar motion needs a wobble (ω1 or ω2 non-zero)")?;
    let (ia, ic) = (i.0[0], i.0[2]);
    let beta = (ic - ia) / ia;
    let euler_sidereal = period * w0.z / (2.0 * PI);
    let euler_solar = euler_sidereal * SOLAR_PER_SIDEREAL;
    let n = fid.samples(200);
    let pts: Vec<(f64, f64)> = (0..=n)
        .map(|k| {
            let w = sol.omega(period * k as f64 / n as f64);
            (w.x / w.z, w.y / w.z)
        })
        .collect();
    let months: Vec<(f64, f64)> = (0..12)
        .map(|k| {
            let days = 30.4375 * k as f64 / SOLAR_PER_SIDEREAL;
            let w = sol.omega(days * 2.0 * PI / w0.z);
            (w.x / w.z, w.y / w.z)
        })
        .collect();
    let desc = format!(
        "Earth's free (Euler) wobble: the rotation axis in the body frame, (ω1/ω3, ω2/ω3), for \
         I = ({}, {}, {}) (so β = (C − A)/A = {beta:.7e}) and one turn per sidereal day. The exact \
         solution closes after {euler_sidereal:.3} sidereal days = {euler_solar:.3} mean solar days \
         (1/β sidereal days); dots mark 12 months. The observed Chandler period is about \
         {CHANDLER_DAYS} days, {:.3} times longer, because Earth is not rigid.",
        i.0[0],
        i.0[1],
        i.0[2],
        CHANDLER_DAYS / euler_solar
    );
    let mut f = fig(
        "polar-motion",
        "Euler's free precession of Earth's axis".into(),
        desc,
        "ω1/ω3",
        "ω2/ω3",
        vec![
            Series {
                name: "one Euler period".into(),
                mark: Mark::Line,
                colour: 0,
                points: pts,
            },
            Series {
                name: "monthly".into(),
                mark: Mark::Points,
                colour: 1,
                points: months,
            },
        ],
    );
    f.equal_aspect = true;
    f.accuracy = vec![exact_accuracy("wobble path", i, &w0, &times(period, n))];
    Ok(f)
}

/// The symmetric top (eqs 69–71): in space, ω sweeps the space cone about the fixed L while the
/// symmetry axis e3 and ω go round together; in the body, ω sweeps the body cone about e3. The
/// half-angles are measured from the integrated attitude and compared with the derivation:
/// tan α_b = A/ω3, cos α_s = 2T/(ωL), and tan θ_L = (I1/I3) tan α_b for the angle of L from e3.
fn cones(i: &Moments, w0: Vector3<f64>, t_end: f64, fid: &Fidelity) -> Result<Figure, String> {
    let v = i.0;
    let c = (0..3)
        .find(|&c| v[(c + 1) % 3] == v[(c + 2) % 3] && v[c] != v[(c + 1) % 3])
        .ok_or("the cones need a symmetric body: exactly two equal moments")?;
    let (i1, i3) = (v[(c + 1) % 3], v[c]);
    let (two_t, l) = invariants(i, &w0);
    let w = w0.norm();
    let e3 = Vector3::ith(c, 1.0);
    let l_body = Vector3::new(v[0] * w0.x, v[1] * w0.y, v[2] * w0.z);
    let tol = fid.ode_tolerance(1e-11);
    let dp = integrate(
        i,
        w0,
        t_end,
        Method::Dopri,
        Resolution::Tolerance(tol),
        fid.samples(400),
    )?;
    let angle = |a: &Vector3<f64>, b: &Vector3<f64>| {
        a.normalize().dot(&b.normalize()).clamp(-1.0, 1.0).acos()
    };
    let mut body_angle = (f64::INFINITY, 0.0f64);
    let mut space_angle = (f64::INFINITY, 0.0f64);
    let (mut space_rim, mut axis_rim, mut body_rim) = (Vec::new(), Vec::new(), Vec::new());
    for (_, wb, q) in &dp.trace {
        let ws = q * wb;
        let ab = angle(wb, &e3);
        let a_s = angle(&ws, &l_body);
        body_angle = (body_angle.0.min(ab), body_angle.1.max(ab));
        space_angle = (space_angle.0.min(a_s), space_angle.1.max(a_s));
        space_rim.push(project(&ws.normalize()));
        axis_rim.push(project(&(q * e3)));
        body_rim.push(project(&wb.normalize()));
    }
    let ab = angle(&w0, &e3);
    let predicted_s = (two_t / (w * l)).clamp(-1.0, 1.0).acos();
    let theta_l = ((i1 / i3) * ab.tan()).atan();
    let shape = if i3 < i1 {
        "prolate (I3 < I1)"
    } else {
        "oblate (I3 > I1)"
    };
    let relation = if ab < predicted_s {
        "α_b < α_s"
    } else {
        "α_b > α_s"
    };
    let deg = |x: f64| x.to_degrees();
    let series = vec![
        Series {
            name: "L (fixed)".into(),
            mark: Mark::Line,
            colour: 5,
            points: vec![project(&Vector3::zeros()), project(&l_body.normalize())],
        },
        Series {
            name: "ω in space: space cone".into(),
            mark: Mark::Line,
            colour: 0,
            points: space_rim,
        },
        Series {
            name: "symmetry axis in space".into(),
            mark: Mark::Dashed,
            colour: 2,
            points: axis_rim,
        },
        Series {
            name: "ω in the body: body cone".into(),
            mark: Mark::Points,
            colour: 1,
            points: body_rim,
        },
    ];
    let desc = format!(
        "Symmetric top, {shape}: I = ({}, {}, {}), ω(0) = ({}, {}, {}), unit vectors in an oblique \
         view. Measured from Dormand–Prince with the attitude: the body-cone half-angle α_b (ω to \
         the symmetry axis) stays {:.6}°–{:.6}°, the space-cone half-angle α_s (ω to L) \
         {:.6}°–{:.6}°. Derived: tan α_b = A/ω3 gives {:.6}°, cos α_s = 2T/(ωL) gives {:.6}°, and L \
         lies at θ_L = {:.6}° from the axis (tan θ_L = (I1/I3) tan α_b), so α_s = |θ_L − α_b| and \
         here {relation}.",
        v[0],
        v[1],
        v[2],
        w0.x,
        w0.y,
        w0.z,
        deg(body_angle.0),
        deg(body_angle.1),
        deg(space_angle.0),
        deg(space_angle.1),
        deg(ab),
        deg(predicted_s),
        deg(theta_l)
    );
    let slug = if i3 < i1 {
        "cones-prolate"
    } else {
        "cones-oblate"
    };
    let mut f = fig(
        slug,
        format!(
            "Body and space cones, {}",
            &shape[..shape.find(' ').unwrap()]
        ),
        desc,
        "",
        "",
        series,
    );
    f.equal_aspect = true;
    let setting = format!("Dormand–Prince 5(4) with the attitude, tol {}", short(tol));
    let mut space_cone = run_accuracy("space-cone half-angle", setting.clone(), &dp, i, &w0);
    space_cone.true_error = Some(
        (space_angle.0 - predicted_s)
            .abs()
            .max((space_angle.1 - predicted_s).abs())
            / predicted_s.max(f64::MIN_POSITIVE),
    );
    f.accuracy = vec![
        run_accuracy("ω in the body", setting, &dp, i, &w0),
        space_cone,
    ];
    Ok(f)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cone inequality worked out from tan θ_L = (I1/I3) tan α_b, measured on the integrated
    /// attitude: oblate bodies always have α_b > α_s; prolate ones can have either.
    #[test]
    fn cone_angles_oblate_always_bigger_body_cone_prolate_either() {
        for (i, w, relation) in [
            ([2.0, 2.0, 3.0], [0.5, 0.0, 1.0], "α_b > α_s"),
            ([2.0, 2.0, 1.9], [0.5, 0.0, 1.0], "α_b > α_s"),
            ([2.0, 2.0, 0.8], [0.2, 0.0, 1.0], "α_b < α_s"),
        ] {
            let f = figure(FreeBodyPlot::Cones, i, w, 20.0, &Fidelity::STANDARD).unwrap();
            assert!(f.desc.contains(relation), "{i:?}: {}", f.desc);
        }
        assert!(
            figure(
                FreeBodyPlot::Cones,
                [1.0, 2.0, 2.5],
                [1.0, 0.0, 0.0],
                1.0,
                &Fidelity::STANDARD
            )
            .is_err()
        );
    }

    #[test]
    fn only_the_intermediate_axis_departs() {
        let f = figure(
            FreeBodyPlot::AxisSpins,
            [1.0, 2.0, 3.0],
            [1.0, 0.01, 0.01],
            60.0,
            &Fidelity::STANDARD,
        )
        .unwrap();
        let top = |k: usize| {
            f.series[k]
                .points
                .iter()
                .map(|p| p.1)
                .fold(0.0f64, f64::max)
        };
        // A 0.01 wobble about a stable axis stays within a couple of degrees; the middle axis
        // reverses (flip time about 2K/λ ≈ 14 here).
        assert!(top(0) < 3.0 && top(2) < 3.0, "{} {}", top(0), top(2));
        assert!(top(1) > 170.0, "{}", top(1));
        assert!(
            figure(
                FreeBodyPlot::AxisSpins,
                [1.0, 2.0, 3.0],
                [1.0, 1.0, 0.0],
                1.0,
                &Fidelity::STANDARD
            )
            .is_err()
        );
    }
}
