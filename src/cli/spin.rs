//! `mechbook spin`: the free rigid body integrated by one method and measured against the exact
//! elliptic solution; and the table of every method side by side that `bench` prints.

use crate::base::format::sci;
use crate::model::moments::Moments;
use crate::numeric::free_body::ExactSolution;
use crate::numeric::integrators::{
    MAX_STEPS, Method, Resolution, Run, integrate, integrate_capped,
};
use anyhow::{Result, anyhow, bail};
use nalgebra::Vector3;
use std::io::Write;
use std::process::ExitCode;
use std::time::Instant;

#[derive(clap::Args, Debug, Clone)]
pub struct SpinArgs {
    /// The principal moments I1,I2,I3: positive, each at most the sum of the other two.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required = true
    )]
    pub inertia: Vec<f64>,
    /// ω(0) in the body frame, w1,w2,w3.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required = true
    )]
    pub omega: Vec<f64>,
    /// The end time T.
    #[arg(long, allow_hyphen_values = true)]
    pub t: f64,
    /// exact, rk4, dopri, splitting or splitting4.
    #[arg(long, default_value = "exact")]
    pub method: String,
    /// Fixed step h (rk4, splitting, splitting4).
    #[arg(long, conflicts_with = "tol")]
    pub step: Option<f64>,
    /// Error tolerance per step (dopri), at least 1e-15.
    #[arg(long)]
    pub tol: Option<f64>,
    /// The most steps to take: a request that needs more is refused (fixed steps) or
    /// stopped (dopri) with a message. 1e7 steps take about 1.3 s with RK4 and 5 s with
    /// dopri here.
    #[arg(long, default_value_t = MAX_STEPS * 2)]
    pub max_steps: u64,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

fn three(name: &str, v: &[f64]) -> Result<[f64; 3]> {
    <[f64; 3]>::try_from(v)
        .map_err(|_| anyhow!("--{name} takes 3 comma-separated numbers, got {}", v.len()))
}

/// Runs one integration and prints it.
pub fn run(args: SpinArgs) -> Result<ExitCode> {
    let text = text(&args)?;
    std::io::stdout().write_all(text.as_bytes())?;
    Ok(ExitCode::SUCCESS)
}

/// Runs one integration and formats it; every bad input is an error message.
pub fn text(a: &SpinArgs) -> Result<String> {
    let (i, w) = inputs(a)?;
    let w0 = Vector3::from(w);
    let (method, resolution) = method_of(a)?;
    let r = integrate_capped(&i, w0, a.t, method, resolution, 0, a.max_steps)?;
    let exact = ExactSolution::new(&i, w0).omega(a.t);
    // Whatever slipped past the checks above: never print NaN as an answer.
    if let Some(bad) = [r.omega, exact]
        .iter()
        .flat_map(|v| v.iter())
        .find(|x| !x.is_finite())
    {
        return Err(anyhow!(
            "the result is not a finite number ({bad}): the inputs are beyond what double \
             precision can integrate; rescale the moments or ω(0)"
        ));
    }
    // Divided by the largest component first: |ω|² of ω ~ 1e200 would overflow.
    let scale = exact.amax().max(f64::MIN_POSITIVE);
    let error = ((r.omega - exact) / scale).norm() / (exact / scale).norm();
    if a.json {
        return spin_json(a, &i, w, method, resolution, &r, exact, error);
    }
    Ok(spin_table(method, &r, error))
}

/// The moments and ω(0), each refused with what to do where double precision cannot hold them.
fn inputs(a: &SpinArgs) -> Result<(Moments, [f64; 3])> {
    let i = Moments::new(three("inertia", &a.inertia)?)?;
    let w = three("omega", &a.omega)?;
    if let Some(k) = w.iter().position(|x| !x.is_finite()) {
        return Err(anyhow!(
            "--omega component {} = {} is not a finite number",
            k + 1,
            w[k]
        ));
    }
    // Subnormal numbers carry fewer than 53 bits: every product with them loses precision.
    for (name, v) in [("inertia", i.0), ("omega", w)] {
        if let Some(k) = crate::base::float::first_subnormal(&v) {
            return Err(anyhow!(
                "--{name} component {} = {:e} is below {:e}, where double precision keeps \
                 its digits: express the quantities in other units",
                k + 1,
                v[k],
                f64::MIN_POSITIVE
            ));
        }
    }
    if !a.t.is_finite() || a.t < 0.0 {
        return Err(anyhow!(
            "the end time --t {} must be a finite number ≥ 0",
            a.t
        ));
    }
    if let Some(why) = crate::model::moments::beyond_double_precision(&i, &Vector3::from(w)) {
        return Err(why.into());
    }
    Ok((i, w))
}

/// The integrator asked for, and its step or tolerance.
fn method_of(a: &SpinArgs) -> Result<(Method, Resolution)> {
    let method = Method::ALL
        .iter()
        .find(|(n, _)| *n == a.method)
        .map(|(_, m)| *m)
        .ok_or_else(|| {
            let names: Vec<&str> = Method::ALL.iter().map(|(n, _)| *n).collect();
            anyhow!(
                "unknown method `{}`{}; the methods are {}",
                a.method,
                crate::base::suggest::did_you_mean(&a.method, names.iter().copied()),
                names.join(", ")
            )
        })?;
    let resolution = match (method, a.step, a.tol) {
        (Method::Dopri, Some(_), _) => bail!("dopri takes --tol, not --step"),
        (Method::Dopri, None, tol) => Resolution::Tolerance(tol.unwrap_or(1e-9)),
        (Method::Exact, ..) => Resolution::Step(1.0),
        (_, _, Some(_)) => return Err(anyhow!("{} takes --step, not --tol", a.method)),
        (_, step, None) => Resolution::Step(step.unwrap_or(0.01)),
    };
    Ok((method, resolution))
}

/// `spin --json`: the run, its error against the exact solution, its drifts and its cost.
#[allow(clippy::too_many_arguments)]
fn spin_json(
    a: &SpinArgs,
    i: &Moments,
    w: [f64; 3],
    method: Method,
    resolution: Resolution,
    r: &Run,
    exact: Vector3<f64>,
    error: f64,
) -> Result<String> {
    let j = serde_json::json!({
        "method": method.name(),
        "inertia": i.0,
        "omega0": w,
        "t": a.t,
        "step": match resolution { Resolution::Step(h) if method != Method::Exact => Some(h), _ => None },
        "tol": match resolution { Resolution::Tolerance(t) => Some(t), _ => None },
        "omega": [r.omega.x, r.omega.y, r.omega.z],
        "omega_exact": [exact.x, exact.y, exact.z],
        "error": error,
        "energy_drift": r.energy_drift,
        "momentum_drift": r.momentum_drift,
        "space_momentum_drift": if r.space_momentum_drift.is_finite() { Some(r.space_momentum_drift) } else { None },
        "steps": r.steps,
        "rhs_evaluations": r.rhs_evaluations,
        "seconds": r.seconds,
    });
    Ok(serde_json::to_string_pretty(&j)? + "\n")
}

/// The run as a table of lines for the terminal.
fn spin_table(method: Method, r: &Run, error: f64) -> String {
    let mut out = format!(
        "method           {}\nomega(T)         [{:.17e}, {:.17e}, {:.17e}]\n",
        method.name(),
        r.omega.x,
        r.omega.y,
        r.omega.z
    );
    if method != Method::Exact {
        out.push_str(&format!("error vs exact   {}\n", sci(error)));
    }
    out.push_str(&format!(
        "energy drift     {}\n|L| drift        {}\n",
        sci(r.energy_drift),
        sci(r.momentum_drift)
    ));
    if r.space_momentum_drift.is_finite() {
        out.push_str(&format!(
            "L_space drift    {}\n",
            sci(r.space_momentum_drift)
        ));
    }
    out.push_str(&format!(
        "steps            {}\nrhs evaluations  {}\nseconds          {:.3e}\n",
        r.steps, r.rhs_evaluations, r.seconds
    ));
    out
}

/// One row of the integrator table.
struct Row {
    label: String,
    run: Run,
    error: f64,
    ns_per_step: f64,
}

/// REFERENCE.md's test case, 100 periods, every method at the reference's steps and tolerances,
/// in one process and one run. `progress` is told which row is running.
pub fn bench_table(mut progress: impl FnMut(&str)) -> String {
    let i = Moments::new([1.0, 2.0, 3.0]).expect("valid moments");
    let w0 = Vector3::new(1.0, 0.1, 0.5);
    let sol = ExactSolution::new(&i, w0);
    let t_end = 100.0 * sol.period().expect("periodic");
    let exact = sol.omega(t_end);
    let mut rows = Vec::new();
    let mut add = |label: String, method: Method, res: Resolution| {
        progress(&label);
        // Best of 3 for the time; the numbers themselves are deterministic.
        let mut best: Option<Run> = None;
        for _ in 0..3 {
            let r = integrate(&i, w0, t_end, method, res, 0).expect("valid run");
            if best.as_ref().is_none_or(|b| r.seconds < b.seconds) {
                best = Some(r);
            }
        }
        let run = best.expect("one run");
        rows.push(Row {
            label,
            error: (run.omega - exact).norm() / exact.norm(),
            ns_per_step: run.seconds * 1e9 / run.steps.max(1) as f64,
            run,
        });
    };
    for (name, method) in [
        ("RK4", Method::Rk4),
        ("Strang splitting 1-2-3-2-1", Method::Splitting),
        ("triple-jump splitting (4th order)", Method::Splitting4),
    ] {
        for h in [0.1, 0.05, 0.025] {
            add(format!("{name}, h = {h}"), method, Resolution::Step(h));
        }
    }
    for tol in [1e-6, 1e-9, 1e-12] {
        add(
            format!("Dormand–Prince 5(4), tol = {tol:e}"),
            Method::Dopri,
            Resolution::Tolerance(tol),
        );
    }
    // The exact solution: the time of one evaluation at a time in the run, best of 3 × 10⁵.
    let evals = 100_000;
    let mut best = f64::INFINITY;
    let mut sink = 0.0;
    for _ in 0..3 {
        let start = Instant::now();
        for k in 0..evals {
            sink += sol.omega(t_end * k as f64 / evals as f64).x;
        }
        best = best.min(start.elapsed().as_secs_f64());
    }
    std::hint::black_box(sink);

    let mut out = format!(
        "Free rigid body, I = (1, 2, 3), ω(0) = (1, 0.1, 0.5), T = 100 periods = {t_end:.6}. \
         Error: |ω(T) − ω_exact(T)| / |ω_exact(T)|. Drifts: the largest relative change of 2T and \
         of |L| over all steps. Time: best of 3 runs.\n\n\
         | method | steps | RHS evaluations | error at T | energy drift | \\|L\\| drift | ns/step |\n\
         |---|---|---|---|---|---|---|\n"
    );
    for r in &rows {
        out.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {:.0} |\n",
            r.label,
            r.run.steps,
            r.run.rhs_evaluations,
            sci(r.error),
            sci(r.run.energy_drift),
            sci(r.run.momentum_drift),
            r.ns_per_step
        ));
    }
    out.push_str(&format!(
        "| exact elliptic solution | – | – | (reference) | – | – | {:.0} ns per evaluation |\n\n\
         Splitting RHS evaluations count elementary axis rotations.\n",
        best * 1e9 / evals as f64
    ));
    out
}
