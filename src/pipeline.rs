//! The thin orchestrator: scene -> plan -> derive -> numeric -> verify. Each stage takes a value
//! and returns a value; nothing here writes files.

use crate::cas::EvalError;
use crate::derive::{self, Derivation, DeriveError};
use crate::figures::FigureError;
use crate::model::catalogue::Stage;
use crate::model::catalogue::quantity;
use crate::model::fidelity::Fidelity;
use crate::model::figure::Figure;
use crate::numeric::{self, NumericReport};
use crate::plan::Plan;
use crate::scene::Scene;
use crate::verify::{self, Verification};
use std::path::PathBuf;
use std::time::Instant;

/// Everything computed for one scene.
#[derive(Debug, Clone)]
pub struct SceneReport {
    pub scene: Scene,
    pub plan: Plan,
    pub derivation: Derivation,
    pub numeric: Option<NumericReport>,
    pub figures: Vec<Figure>,
    /// The fidelity the numeric stage ran at: `--fidelity`, else the scene's, else standard.
    pub fidelity: Fidelity,
    pub verification: Verification,
    /// Time spent inside the symbolic engine for this scene, and its number of calls.
    pub symbolic_seconds: f64,
    pub engine_calls: u64,
    /// Integrations and quadratures this scene ran (zero for stages it did not ask for).
    pub numeric_work: numeric::Work,
    pub seconds: f64,
    /// What came from the build cache; the counters and seconds of a cached part are those of
    /// the run that stored it.
    pub from_cache: FromCache,
}

impl SceneReport {
    pub fn passed(&self) -> bool {
        self.verification.passed()
    }
}

/// A scene that could not be derived: located at the scene's `id` (the scene as a whole), or
/// at the `[[plot]]` that could not be drawn, on one line. A failure inside one claim is not
/// this: it is that claim's problem, at its line.
#[derive(Debug, thiserror::Error)]
#[error("{}:{}:{}: {}: {source}", path.display(), at.0, at.1, match plot {
    Some(i) => format!("plot[{i}] of scene `{id}` could not be drawn"),
    None => format!("scene `{id}` could not be derived"),
})]
pub struct RunError {
    pub path: PathBuf,
    pub id: String,
    pub at: (usize, usize),
    /// The plot at fault, when it is one.
    pub plot: Option<usize>,
    /// Boxed: the error travels up through every stage.
    pub source: Box<StageError>,
}

/// What failed inside a scene's run: the symbolic stage, an evaluation at the scene's values,
/// or a figure.
#[derive(Debug, thiserror::Error)]
pub enum StageError {
    #[error(transparent)]
    Derive(#[from] DeriveError),
    #[error(transparent)]
    Eval(#[from] EvalError),
    #[error(transparent)]
    Figure(#[from] FigureError),
    /// Boxed: a variant's error carries a derivation's or an integration's.
    #[error(transparent)]
    Variant(Box<verify::variants::VariantError>),
}

/// What the symbolic stage produced: it depends on the scene file alone (never on the fidelity),
/// so the build cache keeps it apart from the numeric results.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct Symbolic {
    pub derivation: Derivation,
    pub claims: Vec<verify::ClaimResult>,
    pub regressions: Vec<verify::RegressionResult>,
    pub seconds: f64,
    pub engine_calls: u64,
}

/// How much of a report came from the build cache.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FromCache {
    Nothing,
    /// The symbolic stage's results: only the numeric stage ran.
    Symbolic,
    /// Everything: nothing ran.
    Everything,
}

/// The symbolic stage: the derivation, then the claims and the recorded results checked on it.
pub fn symbolic_stage(scene: &Scene, plan: &Plan) -> Result<Symbolic, RunError> {
    let (engine_before, calls_before) = crate::cas::stats();
    let fail = |source: StageError| RunError {
        path: scene.source.clone(),
        id: scene.id.clone(),
        at: scene.id_at,
        plot: None,
        source: Box::new(source),
    };
    let derivation = derive::derive(scene, plan).map_err(|e| fail(e.into()))?;
    let (claims, regressions) =
        verify::verify_symbolic(scene, &derivation, plan).map_err(|e| fail(e.into()))?;
    let (engine_after, calls_after) = crate::cas::stats();
    Ok(Symbolic {
        derivation,
        claims,
        regressions,
        seconds: engine_after - engine_before,
        engine_calls: calls_after - calls_before,
    })
}

/// Runs one scene. `fidelity` (from the command line) overrides the scene's own setting.
pub fn run_scene(scene: Scene, fidelity: Option<Fidelity>) -> Result<SceneReport, RunError> {
    run_scene_with(scene, fidelity, None)
}

/// Runs one scene, taking the symbolic stage's results from `symbolic` when given.
pub fn run_scene_with(
    scene: Scene,
    fidelity: Option<Fidelity>,
    symbolic: Option<Symbolic>,
) -> Result<SceneReport, RunError> {
    let fidelity = scene.fidelity_given(fidelity);
    let start = Instant::now();
    let work_before = numeric::Work::so_far();
    let plan = Plan::for_scene(&scene);
    let from_cache = if symbolic.is_some() {
        FromCache::Symbolic
    } else {
        FromCache::Nothing
    };
    let symbolic = match symbolic {
        Some(s) => s,
        None => symbolic_stage(&scene, &plan)?,
    };
    let fail = |source: StageError| RunError {
        path: scene.source.clone(),
        id: scene.id.clone(),
        at: scene.id_at,
        plot: None,
        source: Box::new(source),
    };
    let derivation = &symbolic.derivation;
    let numeric = if plan.runs(Stage::Quadrature) {
        let parts = &derivation.part_tensors;
        let total = derivation
            .get(quantity::INERTIA_TENSOR)
            .map_err(|e| fail(e.into()))?;
        Some(
            numeric::quadrature_checks(&scene, parts, total, &fidelity)
                .map_err(|e| fail(e.into()))?,
        )
    } else {
        None
    };
    let figures = if plan.runs(Stage::Plots) {
        crate::figures::figures(&scene, derivation, &fidelity).map_err(|e| RunError {
            path: scene.source.clone(),
            id: scene.id.clone(),
            at: scene.plot_at.get(e.index).copied().unwrap_or(scene.id_at),
            plot: Some(e.index),
            source: Box::new(e.source.into()),
        })?
    } else {
        Vec::new()
    };
    let mut verification = Verification {
        claims: symbolic.claims,
        regressions: symbolic.regressions,
        ..Verification::default()
    };
    verify::verify_numeric(
        &scene,
        derivation,
        numeric.as_ref(),
        &plan,
        &mut verification,
    )
    .map_err(|e| fail(e.into()))?;
    if let Some(problem) = &scene.problem {
        verification.variants = verify::variants::check_variants(&scene, derivation, problem)
            .map_err(|e| fail(StageError::Variant(Box::new(e))))?;
    }
    Ok(SceneReport {
        scene,
        plan,
        derivation: symbolic.derivation,
        numeric,
        figures,
        fidelity,
        verification,
        symbolic_seconds: symbolic.seconds,
        engine_calls: symbolic.engine_calls,
        numeric_work: numeric::Work::since(work_before),
        seconds: start.elapsed().as_secs_f64(),
        from_cache,
    })
}

/// The symbolic part of a report, for the cache.
pub fn symbolic_part(r: &SceneReport) -> Symbolic {
    Symbolic {
        derivation: r.derivation.clone(),
        claims: r.verification.claims.clone(),
        regressions: r.verification.regressions.clone(),
        seconds: r.symbolic_seconds,
        engine_calls: r.engine_calls,
    }
}

/// The computed part of a report, as the build cache stores it: the scene and its plan are
/// rebuilt from the file.
type Computed = (
    Derivation,
    Option<NumericReport>,
    Vec<Figure>,
    Fidelity,
    Verification,
    (f64, u64),
    numeric::Work,
    f64,
);

/// A report as cache bytes.
pub fn to_cache(r: &SceneReport) -> Vec<u8> {
    let computed = (
        &r.derivation,
        &r.numeric,
        &r.figures,
        &r.fidelity,
        &r.verification,
        (r.symbolic_seconds, r.engine_calls),
        &r.numeric_work,
        r.seconds,
    );
    serde_json::to_vec(&computed).expect("a report serializes")
}

/// A report from cache bytes, or `None` when they do not parse (then the scene runs again).
pub fn from_cache(scene: Scene, bytes: &[u8]) -> Option<SceneReport> {
    let (
        derivation,
        numeric,
        figures,
        fidelity,
        verification,
        (symbolic_seconds, engine_calls),
        numeric_work,
        seconds,
    ): Computed = serde_json::from_slice(bytes).ok()?;
    Some(SceneReport {
        plan: Plan::for_scene(&scene),
        scene,
        derivation,
        numeric,
        figures,
        fidelity,
        verification,
        symbolic_seconds,
        engine_calls,
        numeric_work,
        seconds,
        from_cache: FromCache::Everything,
    })
}
