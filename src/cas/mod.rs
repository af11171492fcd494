//! The computer-algebra layer: the ONLY module that touches Symbolica.
//!
//! Without a licence Symbolica allows one thread per user; a second one aborts the process. So
//! every engine call runs on one worker thread owned by this module, and callers exchange only
//! plain owned data with it: our own [`Expr`], strings and booleans. A per-user advisory file
//! lock, held while the worker lives, makes a second `mechbook` process wait with a message
//! instead of aborting. Another engine could replace `engine.rs` without touching the derivations.

mod angles;
mod atoms;
mod closed_form;
mod engine;
mod engine_error;
mod exact_values;
mod exponentials;
mod expr;
mod factor;
mod factor_order;
mod functions;
mod matrix_form;
mod parse;
mod polynomial;
mod positive;
mod present;
mod print;
mod symbol_latex;
pub use symbol_latex::{GREEK, Head, NameForm, greek_letter, name_form, numbered, prints_as_word};
mod radical;
mod rational;
mod series_form;
mod size;
mod trig;
mod trig_pairs;
mod written;

pub use angles::{Zero, Zeros};
pub use closed_form::NoClosedForm;
pub use engine::{EngineError, MAX_DEGREE, MAX_TERMS};
pub use expr::{DiffError, EvalError, Expr};
/// The layout decisions every printer of an expression shares (where a product's fraction bar
/// goes, a term's sign, an index chain's axes, a sum's common factor), for the tree printer in
/// `notation`.
pub use factor::{common_factor, printed_common_factor};
pub use factor_order::{Declared, order_factors};
pub use functions::{SCALAR_FUNCTIONS, arity, needs_dimensionless, textbook_name};
pub use matrix_form::{MatrixForm, factor_and_rows};
pub use parse::{ParseError, Parsed, parse, parse_input};
pub use present::PrintedLength;
pub use print::{
    Prec, Style, index_chain, page_factors, page_fraction, split_sign, write, write_separated,
};
/// The printing walk, for the LaTeX and Typst printers in `notation`.
pub use radical::pull_squares;
pub use rational::Rational;
pub use size::ExpansionSize;
pub use trig::{pi_multiple, special_angles};

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::fs::File;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::OnceLock;
use std::sync::mpsc::{Sender, channel};
use std::time::Instant;

/// A failure inside the engine, or a reason it cannot run. It is a bug in mechbook or a limit of
/// the engine, never bad input.
#[derive(Debug, Clone, thiserror::Error)]
#[error("computer algebra failed: {reason}")]
pub struct CasError {
    pub reason: CasFailure,
}

#[derive(Debug, Clone, thiserror::Error)]
pub enum CasFailure {
    #[error("{0}")]
    Engine(EngineError),
    /// What the engine logged or panicked with, in words (see `engine_message`).
    #[error("{0}")]
    Reported(String),
    #[error("the Symbolica worker has stopped")]
    Stopped,
    #[error(
        "neither HOME nor XDG_CACHE_HOME names a folder: Symbolica keeps its per-user permit in \
         the user's cache folder, so set HOME (or XDG_CACHE_HOME)"
    )]
    NoCacheFolder,
    #[error(
        "cannot create {}: {error}. Symbolica keeps its per-user permit in this cache folder and \
         stops the process when it cannot write there: make the folder writable, or set \
         XDG_CACHE_HOME to a writable folder",
        path.display()
    )]
    LockUnwritable {
        path: std::path::PathBuf,
        error: String,
    },
}

impl From<CasFailure> for CasError {
    fn from(reason: CasFailure) -> CasError {
        CasError { reason }
    }
}

/// One integration, applied to an integrand in order.
#[derive(Debug, Clone)]
pub enum Integral {
    /// ∫ from `lo` to `hi` d`var` of a polynomial in `var`.
    Poly { var: String, lo: Expr, hi: Expr },
    /// ∫ over [0, 2π], [0, π] or [0, π/2] d`var` of a polynomial in cos(var), sin(var).
    Trig { var: String, span: AngleSpan },
}

/// The range of an angle integral, from 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AngleSpan {
    /// [0, 2π].
    Full,
    /// [0, π].
    Half,
    /// [0, π/2].
    Quarter,
}

impl AngleSpan {
    pub fn upper(self) -> f64 {
        match self {
            AngleSpan::Full => 2.0 * std::f64::consts::PI,
            AngleSpan::Half => std::f64::consts::PI,
            AngleSpan::Quarter => std::f64::consts::FRAC_PI_2,
        }
    }
}

/// The exact roots of a polynomial, found by factoring it over the rationals.
#[derive(Debug, Clone)]
pub struct Roots {
    /// (root, multiplicity), for every linear and quadratic factor and quartic in var².
    pub roots: Vec<(Expr, u32)>,
    /// The other irreducible factors of degree three or more, with their multiplicity.
    pub unsolved: Vec<(Expr, u32)>,
}

/// A job is told why the engine may not run, when it may not; it then calls nothing.
type Job = Box<dyn FnOnce(Option<&CasError>) + Send>;

/// The worker thread's name: the panic hook and the log writer recognise it.
const WORKER_NAME: &str = "symbolica";

thread_local! {
    /// What the engine logged during the current job (on the worker thread only).
    static ENGINE_LOG: RefCell<String> = const { RefCell::new(String::new()) };
}

/// Where Symbolica's log goes: the job's buffer on the worker thread, so that a warning becomes
/// part of that job's error; standard error on any other thread. Never standard output, which
/// carries `--json`.
struct EngineLog;

impl std::io::Write for EngineLog {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if std::thread::current().name() == Some(WORKER_NAME) {
            ENGINE_LOG.with(|l| l.borrow_mut().push_str(&String::from_utf8_lossy(buf)));
            Ok(buf.len())
        } else {
            std::io::stderr().write(buf)
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Installs, before the engine's first call, the process's log subscriber (warnings and
/// errors, plain text, to [`EngineLog`]) and a panic hook that keeps the worker's panics quiet:
/// `run` catches them and reports them as errors.
fn contain_the_engine() {
    let _ = tracing_subscriber::fmt()
        .with_writer(|| EngineLog)
        .with_ansi(false)
        .without_time()
        .with_target(false)
        .with_max_level(tracing_subscriber::filter::LevelFilter::WARN)
        .try_init();
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if std::thread::current().name() != Some(WORKER_NAME) {
            previous(info);
        }
    }));
}

/// The engine's own words made into one line of ours: what it logged, else its panic message.
fn engine_message(log: &str, panic: Option<&str>) -> String {
    let logged = log
        .lines()
        .map(|l| {
            l.trim()
                .trim_start_matches("WARN")
                .trim_start_matches("ERROR")
                .trim()
        })
        .find(|l| !l.is_empty());
    let text = logged.or(panic).unwrap_or("the engine stopped");
    if text.contains("infinity") {
        format!("division by zero ({})", text.trim_end_matches('.'))
    } else {
        text.lines().next().unwrap_or(text).to_string()
    }
}

static WORKER: OnceLock<Sender<Job>> = OnceLock::new();

thread_local! {
    /// The engine's time and calls asked for by this thread: a scene's symbolic stage counts
    /// its own, while another thread checks the scene before it numerically.
    static ASKED: std::cell::Cell<(u64, u64)> = const { std::cell::Cell::new((0, 0)) };
}

/// The per-user lock file that serialises mechbook processes: `mechbook/symbolica.lock` in the
/// user's cache folder (`$XDG_CACHE_HOME`, else `$HOME/.cache`). That is where Symbolica keeps
/// its own per-user thread permit (observed: `symbolica/locks/` there), so two processes share
/// this lock exactly when they would share the permit, whatever their `TMPDIR` or `USER`.
pub fn lock_path() -> Result<std::path::PathBuf, CasError> {
    let absolute =
        |v: Option<std::ffi::OsString>| v.map(std::path::PathBuf::from).filter(|p| p.is_absolute());
    let cache = absolute(std::env::var_os("XDG_CACHE_HOME"))
        .or_else(|| absolute(std::env::var_os("HOME")).map(|h| h.join(".cache")))
        .ok_or(CasError::from(CasFailure::NoCacheFolder))?;
    Ok(cache.join("mechbook").join("symbolica.lock"))
}

/// Takes the lock, waiting with a message while another mechbook process holds it. Fails, with
/// what to do, where the cache folder cannot be written: Symbolica would then abort the process
/// when it cannot place its permit there.
fn take_process_lock() -> Result<File, CasError> {
    let path = lock_path()?;
    let unwritable = |e: std::io::Error| {
        CasError::from(CasFailure::LockUnwritable {
            path: path.clone(),
            error: e.to_string(),
        })
    };
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(unwritable)?;
    }
    let file = File::options()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .map_err(unwritable)?;
    if file.try_lock().is_err() {
        eprintln!(
            "mechbook: waiting for another mechbook process to finish (Symbolica allows one \
             process per user without a licence; lock {})",
            path.display()
        );
        file.lock().map_err(unwritable)?;
    }
    Ok(file)
}

/// Whether the engine can run in this process: the lock is taken (or being waited for) and the
/// cache folder is writable. Commands call it first, so that a refusal is one clear line.
pub fn ready() -> Result<(), CasError> {
    run(|| Ok(()))
}

fn worker() -> &'static Sender<Job> {
    WORKER.get_or_init(|| {
        contain_the_engine();
        let (tx, rx) = channel::<Job>();
        std::thread::Builder::new()
            .name(WORKER_NAME.into())
            .spawn(move || {
                // Held until the process exits.
                let lock = take_process_lock();
                let refusal = lock.as_ref().err();
                for job in rx {
                    job(refusal);
                }
            })
            .expect("spawn the Symbolica worker thread");
        tx
    })
}

/// Runs `f` on the worker and returns its result. A panic inside the engine becomes an error.
pub(crate) fn run<T: Send + 'static>(
    f: impl FnOnce() -> Result<T, EngineError> + Send + 'static,
) -> Result<T, CasError> {
    let (tx, rx) = channel();
    let job: Job = Box::new(move |refusal| {
        if let Some(e) = refusal {
            let _ = tx.send((Ok(Err(e.clone())), String::new(), 0));
            return;
        }
        let start = Instant::now();
        ENGINE_LOG.with(|l| l.borrow_mut().clear());
        let result = catch_unwind(AssertUnwindSafe(f))
            .map(|r| r.map_err(|e| CasError::from(CasFailure::Engine(e))));
        let log = ENGINE_LOG.with(|l| std::mem::take(&mut *l.borrow_mut()));
        let _ = tx.send((result, log, start.elapsed().as_nanos() as u64));
    });
    worker()
        .send(job)
        .map_err(|_| CasError::from(CasFailure::Stopped))?;
    let answer = rx.recv().map(|(result, log, nanos)| {
        ASKED.with(|a| {
            let (busy, calls) = a.get();
            a.set((busy + nanos, calls + 1));
        });
        (result, log)
    });
    match answer {
        // A warning means the result is not to be trusted (infinity, a failed conversion).
        Ok((Ok(Ok(_)), log)) if !log.trim().is_empty() => {
            Err(CasFailure::Reported(engine_message(&log, None)).into())
        }
        Ok((Ok(r), _)) => r,
        Ok((Err(panic), log)) => {
            let msg = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()));
            Err(CasFailure::Reported(engine_message(&log, msg.as_deref())).into())
        }
        Err(_) => Err(CasFailure::Stopped.into()),
    }
}

/// Engine time and call count so far asked for by the calling thread: the cost of the
/// symbolic stage.
pub fn stats() -> (f64, u64) {
    let (busy, calls) = ASKED.with(|a| a.get());
    (busy as f64 * 1e-9, calls)
}

/// Expands and normalises each expression to a canonical sum of terms, with the sine and
/// cosine of every multiple of π/12 put in exactly (no step keeps cos(π/2)).
pub fn simplify_all(exprs: Vec<Expr>) -> Result<Vec<Expr>, CasError> {
    let exprs: Vec<Expr> = exprs.iter().map(trig::special_angles).collect();
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

/// As [`is_zero_all`], with every symbol but the `signed` ones taken to be positive, so that
/// √(g²) = g and √(X/(4 I1²)) = √X/(2 I1): a scene's symbols are masses, lengths, constants;
/// its coordinates and rates (`signed`) take either sign, so √(p²) stays |p|.
pub fn is_zero_over_positive(
    exprs: Vec<Expr>,
    signed: std::collections::BTreeSet<String>,
) -> Result<Vec<bool>, CasError> {
    run(move || {
        let positive = |s: &str| !signed.contains(s);
        exprs
            .iter()
            .map(|e| positive::is_zero(e, &positive))
            .collect()
    })
}

/// Each expression with its exponentials (and sinh, cosh through them) as powers of new
/// positive symbols `exp__k`, one per monomial of their exponents, so that
/// [`is_zero_over_positive`] decides exp(u)·exp(−u) = 1 and cosh²u − sinh²u = 1. An
/// expression whose exponent is past the engine's budget is returned as it is.
pub fn exponentials_as_powers(exprs: Vec<Expr>) -> Result<Vec<Expr>, CasError> {
    run(move || {
        Ok(exprs
            .iter()
            .map(|e| exponentials::as_powers(e).unwrap_or_else(|_| e.clone()))
            .collect())
    })
}

/// `e` with each square root's radicand factored and its square factors taken out, every
/// symbol positive: √(I₃²/ε² − b) = √(I₃² − b ε²)/ε.
pub fn roots_over_positive(e: &Expr) -> Result<Expr, CasError> {
    let e = e.clone();
    run(move || positive::roots_over_positive(&e, &|_| true))
}

/// Each expression in the form a textbook prints (see `present.rs`), proven equal to it by the
/// engine with every symbol but the `signed` ones positive, its products' factors in the
/// scene's `declared` order (`factor_order.rs`); an expression with no shorter proven form is
/// returned as it is, its factors ordered.
pub fn present_all(
    exprs: Vec<Expr>,
    signed: std::collections::BTreeSet<String>,
    declared: Declared,
    length: PrintedLength,
) -> Result<Vec<Expr>, CasError> {
    run(move || {
        let positive = |s: &str| !signed.contains(s);
        exprs
            .iter()
            .map(|e| present::present(e, &positive, length).map(|f| order_factors(&f, &declared)))
            .collect()
    })
}

/// Each matrix with its entries' common factor out (`matrix_form.rs`), its parts presented as
/// `present_all` presents a scalar, or as its author wrote it (`factor*[[…]]`) where proven
/// equal; `None` for a matrix with no factor to take out.
pub fn matrix_forms(
    matrices: Vec<(Vec<Vec<Expr>>, Option<Expr>)>,
    signed: std::collections::BTreeSet<String>,
    declared: Declared,
    length: PrintedLength,
) -> Result<Vec<Option<MatrixForm>>, CasError> {
    run(move || {
        let positive = |s: &str| !signed.contains(s);
        let order = |e: &Expr| order_factors(e, &declared);
        matrices
            .iter()
            .map(|(rows, written)| {
                matrix_form::matrix_form(rows, written.as_ref(), &positive, length).map(|form| {
                    form.map(|f| MatrixForm {
                        factor: order(&f.factor),
                        rows: f
                            .rows
                            .iter()
                            .map(|r| r.iter().map(order).collect())
                            .collect(),
                    })
                })
            })
            .collect()
    })
}

/// An author's expression as written, its names put in (`written`), in the form a page prints
/// it where the engine proves it equal to `exact`, else `exact`'s presented form (see
/// `written.rs`); its products' factors in the scene's `declared` order.
pub fn present_written(
    written: Expr,
    exact: Expr,
    signed: std::collections::BTreeSet<String>,
    declared: Declared,
    length: PrintedLength,
) -> Result<Expr, CasError> {
    run(move || {
        let positive = |s: &str| !signed.contains(s);
        written::present_written(&written, &exact, &positive, length)
            .map(|f| order_factors(&f, &declared))
    })
}

/// An author's expression with its names kept, as a page prints it (`written.rs`): no engine,
/// nothing expanded.
pub fn as_written(e: &Expr, signed: &std::collections::BTreeSet<String>) -> Expr {
    written::as_written(e, &|s: &str| !signed.contains(s))
}

/// The expanded numerator and denominator of each rational function.
pub fn fraction_all(exprs: Vec<Expr>) -> Result<Vec<(Expr, Expr)>, CasError> {
    run(move || exprs.iter().map(engine::fraction).collect())
}

/// Each rational function factored over the rationals, numerator over denominator.
pub fn factor_all(exprs: Vec<Expr>) -> Result<Vec<Expr>, CasError> {
    run(move || exprs.iter().map(engine::factor).collect())
}

/// (power of `var`, coefficient) pairs of a polynomial in `var`, expanded.
pub fn coefficients(poly: &Expr, var: &str) -> Result<Vec<(u32, Expr)>, CasError> {
    let (poly, var) = (poly.clone(), var.to_string());
    run(move || engine::coefficients(&poly, &var))
}

/// The exact roots in `var` of a polynomial whose other symbols are parameters.
pub fn roots(poly: &Expr, var: &str) -> Result<Roots, CasError> {
    let (poly, var) = (poly.clone(), var.to_string());
    run(move || polynomial::roots(&poly, &var))
}

/// The real roots at `values` of an irreducible cubic or quartic in `var`, in the closed form
/// that is real there (Cardano's, the trigonometric, Ferrari's); or why there is none.
pub fn closed_form_roots(
    poly: &Expr,
    var: &str,
    values: &BTreeMap<String, f64>,
) -> Result<Result<Vec<Expr>, NoClosedForm>, CasError> {
    let (poly, var, values) = (poly.clone(), var.to_string(), values.clone());
    run(move || closed_form::real_roots(&poly, &var, &values))
}

/// Where an expression in the coordinate `q` vanishes: its roots, or for an expression in sin q
/// and cos q its angles with their cosines and sines.
pub fn zeros(e: &Expr, q: &str) -> Result<Zeros, CasError> {
    let (e, q) = (e.clone(), q.to_string());
    run(move || angles::zeros(&e, &q))
}

/// The entries divided by their common factor (with a deterministic sign): a direction in its
/// simplest exact form, such as (1, 1, 1) for a cube's diagonal.
pub fn primitive_part(entries: Vec<Expr>) -> Result<Vec<Expr>, CasError> {
    run(move || engine::primitive_part(&entries))
}

#[cfg(test)]
mod expr_tests;
#[cfg(test)]
mod tests;
