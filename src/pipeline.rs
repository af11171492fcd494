//! The thin orchestrator: scene -> plan -> derive -> numeric -> verify. Each stage takes a value
//! and returns a value; nothing here writes files.

use crate::derive::{self, Derivation, DeriveError};
use crate::figure::Figure;
use crate::numeric::fidelity::Fidelity;
use crate::numeric::{self, NumericReport};
use crate::plan::{Plan, Stage};
use crate::scene::{Scene, SceneError};
use crate::verify::{self, Verification};
use std::path::{Path, PathBuf};
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

/// A scene that could not be derived: located at the scene's `id` (the scene as a whole), on
/// one line. A failure inside one claim is not this: it is that claim's problem, at its line.
#[derive(Debug, thiserror::Error)]
#[error("{}:{}:{}: scene `{id}` could not be derived: {source}", path.display(), at.0, at.1)]
pub struct RunError {
    pub path: PathBuf,
    pub id: String,
    pub at: (usize, usize),
    pub source: DeriveError,
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
    let fail = |source| RunError {
        path: scene.source.clone(),
        id: scene.id.clone(),
        at: scene.id_at,
        source,
    };
    let derivation = derive::derive(scene, plan).map_err(fail)?;
    let (claims, regressions) = verify::verify_symbolic(scene, &derivation, plan).map_err(fail)?;
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
    let fidelity = fidelity.or(scene.fidelity).unwrap_or_default();
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
    let fail = |source| RunError {
        path: scene.source.clone(),
        id: scene.id.clone(),
        at: scene.id_at,
        source,
    };
    let derivation = &symbolic.derivation;
    let numeric = if plan.runs(Stage::Quadrature) {
        let parts = &derivation.part_tensors;
        let total = &derivation.quantities["inertia_tensor"];
        Some(
            numeric::quadrature_checks(&scene, parts, total, &fidelity)
                .map_err(|e| fail(DeriveError::Unsupported(e)))?,
        )
    } else {
        None
    };
    let figures = if plan.runs(Stage::Plots) {
        numeric::plots::figures(&scene, derivation, &fidelity)
            .map_err(|e| fail(DeriveError::Unsupported(e)))?
    } else {
        Vec::new()
    };
    // A plot of NaN or infinity is a failure of the inputs' precision, said here, located,
    // rather than a broken picture or a renderer's error.
    for f in &figures {
        let finite = |(x, y): &(f64, f64)| x.is_finite() && y.is_finite();
        if !f.series.iter().all(|s| s.points.iter().all(finite))
            || !f.labels.iter().all(|(_, p)| finite(p))
        {
            return Err(fail(DeriveError::Unsupported(format!(
                "plot `{}`: its data is not all finite numbers: the body or ω(0) is beyond \
                 double precision; check the plot's inertia, omega and t",
                f.slug
            ))));
        }
    }
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
    .map_err(fail)?;
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

/// The most folder levels `find_scenes` descends.
pub const MAX_DEPTH: usize = 16;

/// Every `.toml` scene under the given folders, plus the files named directly (taken as given,
/// so a missing or unreadable one is reported), sorted and without duplicates. A symbolic link
/// to a folder is followed only when the folder lies inside the one being searched and was not
/// visited yet (so `up -> ..` or `here -> .` add nothing); only regular files are taken, and
/// the walk goes at most [`MAX_DEPTH`] folders deep.
pub fn find_scenes(paths: &[PathBuf]) -> std::io::Result<Vec<PathBuf>> {
    use std::collections::BTreeSet;
    fn collect(
        dir: &Path,
        root: &Path,
        depth: usize,
        seen: &mut BTreeSet<PathBuf>,
        out: &mut Vec<PathBuf>,
    ) -> std::io::Result<()> {
        let real = dir.canonicalize()?;
        if depth > MAX_DEPTH || !real.starts_with(root) || !seen.insert(real) {
            return Ok(());
        }
        for entry in std::fs::read_dir(dir)? {
            let path = entry?.path();
            // A dangling link or an unreadable entry is skipped, as `find` would.
            let Ok(meta) = std::fs::metadata(&path) else {
                continue;
            };
            if meta.is_dir() {
                collect(&path, root, depth + 1, seen, out)?;
            } else if meta.is_file() && path.extension().is_some_and(|x| x == "toml") {
                out.push(path);
            }
        }
        Ok(())
    }
    let mut out = Vec::new();
    let mut seen = BTreeSet::new();
    for p in paths {
        if p.is_dir() {
            collect(p, &p.canonicalize()?, 0, &mut seen, &mut out)?;
        } else {
            out.push(p.clone());
        }
    }
    out.sort();
    out.dedup();
    Ok(out)
}

/// Loads every scene first, so that one bad file stops the run before any output; every bad one
/// is reported. Ids must be unique, and two lecture names must not make the same handout file
/// name.
pub fn load_all(paths: &[PathBuf]) -> Result<Vec<Scene>, Vec<SceneError>> {
    let mut scenes = Vec::new();
    let mut errors = Vec::new();
    for p in paths {
        match Scene::from_file(p) {
            Ok(s) => scenes.push(s),
            Err(e) => errors.push(e),
        }
    }
    let located =
        |s: &Scene, (line, column): (usize, usize), field: &str, message: String| SceneError {
            path: s.source.clone(),
            line,
            column,
            field: field.into(),
            message,
        };
    let mut by_id: Vec<&Scene> = scenes.iter().collect();
    by_id.sort_by(|a, b| (&a.id, &a.source).cmp(&(&b.id, &b.source)));
    for w in by_id.windows(2) {
        if w[0].id == w[1].id {
            let message = format!(
                "duplicate scene id `{}` (also in {}): page file names come from ids",
                w[0].id,
                w[0].source.display()
            );
            errors.push(located(w[1], w[1].id_at, "id", message));
        }
    }
    let mut by_slug: std::collections::BTreeMap<String, &Scene> = Default::default();
    for s in by_id {
        let slug = crate::scene::lecture_slug(&s.notes.lecture);
        match by_slug.get(&slug) {
            Some(first) if first.notes.lecture != s.notes.lecture => {
                let message = format!(
                    "lecture `{}` and lecture `{}` (in {}) would share the handout file name \
                     `{slug}`: name them so that they differ in a letter or digit",
                    s.notes.lecture,
                    first.notes.lecture,
                    first.source.display()
                );
                errors.push(located(s, s.lecture_at, "notes.lecture", message));
            }
            Some(_) => {}
            None => {
                by_slug.insert(slug, s);
            }
        }
    }
    if errors.is_empty() {
        Ok(scenes)
    } else {
        Err(errors)
    }
}
