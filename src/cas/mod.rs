//! The computer-algebra layer: the ONLY module that touches Symbolica.
//!
//! Without a licence Symbolica allows one thread per user; a second one aborts the process. So
//! every engine call runs on one worker thread owned by this module, and callers exchange only
//! plain owned data with it: our own [`Expr`], strings and booleans. A per-user advisory file
//! lock, held while the worker lives, makes a second `mechbook` process wait with a message
//! instead of aborting. Another engine could replace `engine.rs` without touching the derivations.

mod engine;
mod expr;
mod rational;
mod trig;

pub use expr::{Expr, ParseError, Parsed, SCALAR_FUNCTIONS, parse};
pub use rational::Rational;

use std::fs::File;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::OnceLock;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{Sender, channel};
use std::time::Instant;

/// A failure inside the engine. It is a bug in mechbook or a limit of the engine, never bad input.
#[derive(Debug, Clone, thiserror::Error)]
#[error("computer algebra failed: {0}")]
pub struct CasError(pub String);

/// One integration, applied to an integrand in order.
#[derive(Debug, Clone)]
pub enum Integral {
    /// ∫ from `lo` to `hi` d`var` of a polynomial in `var`.
    Poly { var: String, lo: Expr, hi: Expr },
    /// ∫ over [0, 2π] (or [0, π] when `half`) d`var` of a polynomial in cos(var), sin(var).
    Trig { var: String, half: bool },
}

/// The exact roots of a polynomial, found by factoring it over the rationals.
#[derive(Debug, Clone)]
pub struct Roots {
    /// (root, multiplicity), for every linear and quadratic factor.
    pub roots: Vec<(Expr, u32)>,
    /// Irreducible factors of degree three or more, with their multiplicity.
    pub unsolved: Vec<(Expr, u32)>,
}

type Job = Box<dyn FnOnce() + Send>;

static WORKER: OnceLock<Sender<Job>> = OnceLock::new();
static BUSY_NANOS: AtomicU64 = AtomicU64::new(0);
static CALLS: AtomicU64 = AtomicU64::new(0);

/// The per-user lock file that serialises mechbook processes.
pub fn lock_path() -> std::path::PathBuf {
    let user = std::env::var("USER")
        .or_else(|_| std::env::var("LOGNAME"))
        .unwrap_or_else(|_| "user".into());
    std::env::temp_dir().join(format!("mechbook-symbolica-{user}.lock"))
}

fn take_process_lock() -> Option<File> {
    let path = lock_path();
    let file = File::options()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .ok()?;
    match file.try_lock() {
        Ok(()) => Some(file),
        Err(_) => {
            eprintln!(
                "mechbook: waiting for another mechbook process to finish (Symbolica allows one \
                 process per user without a licence; lock {})",
                path.display()
            );
            file.lock().ok().map(|_| file)
        }
    }
}

fn worker() -> &'static Sender<Job> {
    WORKER.get_or_init(|| {
        let (tx, rx) = channel::<Job>();
        std::thread::Builder::new()
            .name("symbolica".into())
            .spawn(move || {
                // Held until the process exits. Without a lock file (read-only temp dir) we still
                // run; only the cross-process wait is lost.
                let _lock = take_process_lock();
                for job in rx {
                    job();
                }
            })
            .expect("spawn the Symbolica worker thread");
        tx
    })
}

/// Runs `f` on the worker and returns its result. A panic inside the engine becomes an error.
fn run<T: Send + 'static>(
    f: impl FnOnce() -> Result<T, String> + Send + 'static,
) -> Result<T, CasError> {
    let (tx, rx) = channel();
    let job: Job = Box::new(move || {
        let start = Instant::now();
        let result = catch_unwind(AssertUnwindSafe(f));
        BUSY_NANOS.fetch_add(start.elapsed().as_nanos() as u64, Ordering::Relaxed);
        CALLS.fetch_add(1, Ordering::Relaxed);
        let _ = tx.send(result);
    });
    worker()
        .send(job)
        .map_err(|_| CasError("the Symbolica worker has stopped".into()))?;
    match rx.recv() {
        Ok(Ok(r)) => r.map_err(CasError),
        Ok(Err(panic)) => {
            let msg = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "panic".into());
            Err(CasError(format!("engine panicked: {msg}")))
        }
        Err(_) => Err(CasError("the Symbolica worker has stopped".into())),
    }
}

/// Engine time and call count so far in this process: the cost of the symbolic stage.
pub fn stats() -> (f64, u64) {
    (
        BUSY_NANOS.load(Ordering::Relaxed) as f64 * 1e-9,
        CALLS.load(Ordering::Relaxed),
    )
}

/// Expands and normalises each expression to a canonical sum of terms.
pub fn simplify_all(exprs: Vec<Expr>) -> Result<Vec<Expr>, CasError> {
    run(move || exprs.iter().map(engine::simplify).collect())
}

pub fn simplify(e: &Expr) -> Result<Expr, CasError> {
    Ok(simplify_all(vec![e.clone()])?.remove(0))
}

/// Integrates each integrand over the same domain, exactly.
pub fn integrate_all(integrands: Vec<Expr>, over: Vec<Integral>) -> Result<Vec<Expr>, CasError> {
    run(move || {
        integrands
            .iter()
            .map(|e| engine::integrate(e, &over))
            .collect()
    })
}

/// Decides whether each expression is identically zero, treating sin and cos of the same
/// argument as related (sin² + cos² = 1, multiple angles expanded). A `true` is a proof; a
/// `false` can also mean that a relation between different arguments was missed, which is why
/// callers confirm at random points.
pub fn is_zero_all(exprs: Vec<Expr>) -> Result<Vec<bool>, CasError> {
    run(move || exprs.iter().map(engine::is_zero).collect())
}

/// The expanded numerator and denominator of each rational function.
pub fn fraction_all(exprs: Vec<Expr>) -> Result<Vec<(Expr, Expr)>, CasError> {
    run(move || exprs.iter().map(engine::fraction).collect())
}

/// Each rational function factored over the rationals, numerator over denominator.
pub fn factor_all(exprs: Vec<Expr>) -> Result<Vec<Expr>, CasError> {
    run(move || exprs.iter().map(engine::factor).collect())
}

/// The exact roots in `var` of a polynomial whose other symbols are parameters.
pub fn roots(poly: &Expr, var: &str) -> Result<Roots, CasError> {
    let (poly, var) = (poly.clone(), var.to_string());
    run(move || engine::roots(&poly, &var))
}

/// The entries divided by their common factor (with a deterministic sign): a direction in its
/// simplest exact form, such as (1, 1, 1) for a cube's diagonal.
pub fn primitive_part(entries: Vec<Expr>) -> Result<Vec<Expr>, CasError> {
    run(move || engine::primitive_part(&entries))
}

#[cfg(test)]
mod tests;
