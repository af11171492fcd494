//! The thin orchestrator: scene -> plan -> derive -> numeric -> verify. Each stage takes a value
//! and returns a value; nothing here writes files.

use crate::derive::{self, Derivation, DeriveError};
use crate::figure::Figure;
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
    pub verification: Verification,
    /// Time spent inside the symbolic engine for this scene, and its number of calls.
    pub symbolic_seconds: f64,
    pub engine_calls: u64,
    /// Integrations and quadratures this scene ran (zero for stages it did not ask for).
    pub numeric_work: numeric::Work,
    pub seconds: f64,
}

impl SceneReport {
    pub fn passed(&self) -> bool {
        self.verification.passed()
    }
}

#[derive(Debug, thiserror::Error)]
#[error("{}: {source}", path.display())]
pub struct RunError {
    pub path: PathBuf,
    #[source]
    pub source: DeriveError,
}

pub fn run_scene(scene: Scene) -> Result<SceneReport, RunError> {
    let start = Instant::now();
    let (engine_before, calls_before) = crate::cas::stats();
    let work_before = numeric::Work::so_far();
    let fail = |source| RunError {
        path: scene.source.clone(),
        source,
    };
    let plan = Plan::for_scene(&scene);
    let derivation = derive::derive(&scene, &plan).map_err(fail)?;
    let numeric = if plan.runs(Stage::Quadrature) {
        let parts = &derivation.part_tensors;
        let total = &derivation.quantities["inertia_tensor"];
        Some(
            numeric::quadrature_checks(&scene, parts, total)
                .map_err(|e| fail(DeriveError::Unsupported(e)))?,
        )
    } else {
        None
    };
    let figures = if plan.runs(Stage::Plots) {
        numeric::plots::figures(&scene, &derivation)
            .map_err(|e| fail(DeriveError::Unsupported(e)))?
    } else {
        Vec::new()
    };
    let verification =
        verify::verify(&scene, &derivation, numeric.as_ref(), &plan).map_err(fail)?;
    let (engine_after, calls_after) = crate::cas::stats();
    Ok(SceneReport {
        scene,
        plan,
        derivation,
        numeric,
        figures,
        verification,
        symbolic_seconds: engine_after - engine_before,
        engine_calls: calls_after - calls_before,
        numeric_work: numeric::Work::since(work_before),
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// Every `.toml` scene under the given folders, plus the files named directly (taken as given,
/// so a missing or unreadable one is reported), sorted and without duplicates.
pub fn find_scenes(paths: &[PathBuf]) -> std::io::Result<Vec<PathBuf>> {
    fn collect(dir: &Path, out: &mut Vec<PathBuf>) -> std::io::Result<()> {
        for entry in std::fs::read_dir(dir)? {
            let path = entry?.path();
            if path.is_dir() {
                collect(&path, out)?;
            } else if path.extension().is_some_and(|x| x == "toml") {
                out.push(path);
            }
        }
        Ok(())
    }
    let mut out = Vec::new();
    for p in paths {
        if p.is_dir() {
            collect(p, &mut out)?;
        } else {
            out.push(p.clone());
        }
    }
    out.sort();
    out.dedup();
    Ok(out)
}

/// Loads every scene first, so that one bad file stops the run before any output.
pub fn load_all(paths: &[PathBuf]) -> Result<Vec<Scene>, Vec<SceneError>> {
    let mut scenes = Vec::new();
    let mut errors = Vec::new();
    for p in paths {
        match Scene::from_file(p) {
            Ok(s) => scenes.push(s),
            Err(e) => errors.push(e),
        }
    }
    let mut ids: Vec<(&str, &Path)> = scenes
        .iter()
        .map(|s| (s.id.as_str(), s.source.as_path()))
        .collect();
    ids.sort();
    for w in ids.windows(2) {
        if w[0].0 == w[1].0 {
            errors.push(SceneError {
                path: w[1].1.to_path_buf(),
                line: 1,
                column: 1,
                field: "id".into(),
                message: format!(
                    "duplicate scene id `{}` (also in {})",
                    w[0].0,
                    w[0].1.display()
                ),
            });
        }
    }
    if errors.is_empty() {
        Ok(scenes)
    } else {
        Err(errors)
    }
}
