//! The thin orchestrator: scene -> plan -> derive -> numeric -> verify. Each stage takes a value
//! and returns a value; nothing here writes files. Results kept between runs come and go
//! through a [`ResultStore`], which the build cache (`site::cache`) implements.

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
use std::collections::BTreeMap;
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

#[cfg(test)]
mod test_support {
    impl super::SceneReport {
        /// Fails the calling test, listing the checks, unless every author's step passed.
        #[track_caller]
        pub fn assert_steps_pass(&self) {
            let steps = &self.verification.steps;
            assert!(steps.iter().all(|c| c.passed()), "{steps:?}");
        }

        /// A step's value (`acc_3`, a mode, a momentum) at a state, the scene's values for
        /// the rest.
        pub fn value_at(&self, name: &str, state: &[(&str, f64)]) -> f64 {
            let values = crate::derive::variants::step_values(&self.scene, &self.derivation);
            values[name]
                .eval(&|s| {
                    let given = state.iter().find(|(n, _)| *n == s).map(|(_, v)| *v);
                    given.or_else(|| self.scene.values.get(s).copied())
                })
                .unwrap()
        }
    }
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

impl RunError {
    /// `source`, located at the scene's `id`.
    fn in_scene(scene: &Scene, source: StageError) -> RunError {
        RunError {
            path: scene.source.clone(),
            id: scene.id.clone(),
            at: scene.id_at,
            plot: None,
            source: Box::new(source),
        }
    }
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
    /// An expression whose dimensions do not fit, at its line.
    #[error(transparent)]
    Dimension(verify::dimensions::DimensionFault),
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
    #[serde(default)]
    pub step_records: Vec<verify::StepRecord>,
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
    let fail = |source: StageError| RunError::in_scene(scene, source);
    // The built-in derivation, then the author's own steps on it.
    let derivation = derive::derive(scene, plan).and_then(|mut d| {
        if plan.runs(Stage::Steps) {
            crate::steps::derive_steps(scene, &mut d)?;
        }
        Ok(d)
    });
    let derivation = derivation.map_err(|e| {
        // An author's step is located at its own line.
        let at = match &e {
            derive::DeriveError::Step(s) => (s.line(), 1),
            _ => scene.id_at,
        };
        RunError {
            at,
            ..fail(e.into())
        }
    })?;
    verify::dimensions::check_dimensions(scene, &derivation).map_err(|f| RunError {
        at: (f.line, 1),
        ..fail(StageError::Dimension(f))
    })?;
    let checks = verify::verify_symbolic(scene, &derivation, plan).map_err(|e| fail(e.into()))?;
    let mut claims = checks.claims;
    for (line, mismatch) in verify::dimensions::claim_notes(scene, &derivation) {
        if let Some(c) = claims
            .iter_mut()
            .find(|c| c.line == line && c.step.is_none())
        {
            let why = mismatch.text();
            c.differences
                .push(mismatch.said(&scene.names(), c.tex.as_ref()));
            if c.verdict == crate::scene::Verdict::Agrees {
                c.problem = Some(format!(
                    "the two sides agree, yet differ in dimension ({why}): check the symbols' \
                     units"
                ));
            }
            c.dimension = Some(why);
        }
    }
    let (engine_after, calls_after) = crate::cas::stats();
    Ok(Symbolic {
        derivation,
        claims,
        regressions: checks.regressions,
        step_records: checks.step_records,
        seconds: engine_after - engine_before,
        engine_calls: calls_after - calls_before,
    })
}

/// Where finished results wait between runs. The build cache (`site::cache::Cache`) is one;
/// [`NoStore`] keeps nothing.
pub trait ResultStore {
    /// Why a stored result could not be used or kept: told to the user, never fatal.
    type Warning: std::fmt::Display;
    /// What is stored for `scene`: its whole report at `fidelity`, or with `None` its symbolic
    /// results. A damaged entry is a warning and a miss.
    fn get(
        &self,
        scene: &Scene,
        fidelity: Option<&Fidelity>,
        warnings: &mut Vec<Self::Warning>,
    ) -> Option<Vec<u8>>;
    /// What to say when bytes that `get` gave back do not decode (the scene runs again).
    fn unreadable(&self, scene: &Scene, fidelity: Option<&Fidelity>) -> Self::Warning;
    fn put(
        &self,
        scene: &Scene,
        fidelity: Option<&Fidelity>,
        bytes: &[u8],
    ) -> Result<(), Self::Warning>;
}

/// A store that keeps nothing: every scene runs in full (`check`, `--no-cache`).
pub struct NoStore;

impl ResultStore for NoStore {
    type Warning = std::convert::Infallible;
    fn get(&self, _: &Scene, _: Option<&Fidelity>, _: &mut Vec<Self::Warning>) -> Option<Vec<u8>> {
        None
    }
    fn unreadable(&self, _: &Scene, _: Option<&Fidelity>) -> Self::Warning {
        unreachable!("NoStore gives back no bytes to decode")
    }
    fn put(&self, _: &Scene, _: Option<&Fidelity>, _: &[u8]) -> Result<(), Self::Warning> {
        Ok(())
    }
}

/// What a store gave back for a scene: its whole report, or what is left to run (with its
/// stored symbolic results, when it had them).
// One per scene, moved once: the size of either variant costs nothing.
#[allow(clippy::large_enum_variant)]
enum Lookup {
    Done(SceneReport),
    Run(Scene, Option<Symbolic>),
}

/// A scene's stored results: its whole report at `fid`, else its symbolic results.
fn look_up<S: ResultStore>(
    store: &S,
    scene: Scene,
    fid: &Fidelity,
    warnings: &mut Vec<S::Warning>,
) -> Lookup {
    if let Some(bytes) = store.get(&scene, Some(fid), warnings) {
        match from_cache(scene.clone(), &bytes) {
            Some(r) => return Lookup::Done(r),
            None => warnings.push(store.unreadable(&scene, Some(fid))),
        }
    }
    let symbolic = match store.get(&scene, None, warnings) {
        Some(bytes) => match serde_json::from_slice(&bytes) {
            Ok(s) => Some(s),
            Err(_) => {
                warnings.push(store.unreadable(&scene, None));
                None
            }
        },
        None => None,
    };
    Lookup::Run(scene, symbolic)
}

/// Keeps what a run computed: the whole report, and the symbolic results when they are new.
fn store_report<S: ResultStore>(store: &S, r: &SceneReport, warnings: &mut Vec<S::Warning>) {
    let mut stored = store.put(&r.scene, Some(&r.fidelity), &to_cache(r));
    if r.from_cache == FromCache::Nothing && stored.is_ok() {
        let symbolic = serde_json::to_vec(&symbolic_part(r)).expect("a report serializes");
        stored = store.put(&r.scene, None, &symbolic);
    }
    if let Err(w) = stored {
        warnings.push(w);
    }
}

/// One scene through `store`: its whole report when stored for this fidelity, else its stored
/// symbolic results with only the numeric stage run again, else everything; what is new is
/// stored. Comes back with the report and what the store had to say.
pub fn run_scene_stored<S: ResultStore>(
    store: &S,
    scene: Scene,
    fidelity: Option<Fidelity>,
) -> Result<(SceneReport, Vec<S::Warning>), RunError> {
    let fid = scene.fidelity_given(fidelity);
    let mut warnings = Vec::new();
    let (scene, symbolic) = match look_up(store, scene, &fid, &mut warnings) {
        Lookup::Done(r) => return Ok((r, warnings)),
        Lookup::Run(scene, symbolic) => (scene, symbolic),
    };
    let r = numeric_stage(derived(scene, symbolic)?, Some(fid))?;
    store_report(store, &r, &mut warnings);
    Ok((r, warnings))
}

/// What a run of many scenes tells as it goes, for the command line to show.
pub enum Progress<'a> {
    /// `done` of `total` scenes are started; `id` is next.
    Starting {
        done: usize,
        total: usize,
        id: &'a str,
    },
    Warning(String),
    /// A scene could not be run: the whole error, located.
    Failed(String),
    Finished,
}

/// Every scene through `store`, in order: the reports, and the errors of those that failed.
///
/// Both cores work: while the engine derives a scene on this thread, a second thread checks
/// the scene before it numerically (an engine call of a numeric route waits for the engine's
/// one worker, as every call does). Each scene's report, warnings and error are told in the scenes' order, whichever
/// thread finished first, so the output is that of a run on one thread.
pub fn run_all<S: ResultStore>(
    scenes: Vec<Scene>,
    fidelity: Option<Fidelity>,
    store: &S,
    tell: &mut dyn FnMut(Progress),
) -> (Vec<SceneReport>, Vec<String>) {
    let total = scenes.len();
    let mut told = InOrder::default();
    std::thread::scope(|scope| {
        // One scene waits while another is checked: the derivations held stay few.
        let (check, to_check) = std::sync::mpsc::sync_channel::<(usize, Derived)>(1);
        let (give_back, checked) = std::sync::mpsc::channel();
        scope.spawn(move || {
            for (i, d) in to_check {
                let fid = Some(d.scene.fidelity_given(fidelity));
                if give_back.send((i, numeric_stage(d, fid))).is_err() {
                    break;
                }
            }
        });
        for (i, scene) in scenes.into_iter().enumerate() {
            tell(Progress::Starting {
                done: i,
                total,
                id: &scene.id,
            });
            let fid = scene.fidelity_given(fidelity);
            let mut warnings = Vec::new();
            let outcome = match look_up(store, scene, &fid, &mut warnings) {
                Lookup::Done(r) => Some(Ok(r)),
                Lookup::Run(scene, symbolic) => match derived(scene, symbolic) {
                    Ok(d) => {
                        check.send((i, d)).expect("the numeric thread runs");
                        None
                    }
                    Err(e) => Some(Err(e)),
                },
            };
            told.warnings.insert(i, warnings);
            if let Some(outcome) = outcome {
                told.outcomes.insert(i, outcome);
            }
            for (j, r) in checked.try_iter() {
                told.outcomes.insert(j, r);
            }
            told.tell_ready(store, tell);
        }
        drop(check);
        for (j, r) in checked {
            told.outcomes.insert(j, r);
        }
        told.tell_ready(store, tell);
    });
    tell(Progress::Finished);
    (told.reports, told.failed)
}

/// Outcomes that came back out of order, told and kept in the scenes' order.
struct InOrder<W> {
    next: usize,
    warnings: BTreeMap<usize, Vec<W>>,
    outcomes: BTreeMap<usize, Result<SceneReport, RunError>>,
    reports: Vec<SceneReport>,
    failed: Vec<String>,
}

impl<W> Default for InOrder<W> {
    fn default() -> Self {
        InOrder {
            next: 0,
            warnings: BTreeMap::new(),
            outcomes: BTreeMap::new(),
            reports: Vec::new(),
            failed: Vec::new(),
        }
    }
}

impl<W: std::fmt::Display> InOrder<W> {
    /// Stores and tells each outcome whose scenes before it are all told.
    fn tell_ready<S: ResultStore<Warning = W>>(
        &mut self,
        store: &S,
        tell: &mut dyn FnMut(Progress),
    ) {
        while let Some(outcome) = self.outcomes.remove(&self.next) {
            let mut warnings = self.warnings.remove(&self.next).unwrap_or_default();
            match outcome {
                Ok(r) => {
                    if r.from_cache != FromCache::Everything {
                        store_report(store, &r, &mut warnings);
                    }
                    for w in warnings {
                        tell(Progress::Warning(w.to_string()));
                    }
                    self.reports.push(r);
                }
                Err(e) => {
                    for w in warnings {
                        tell(Progress::Warning(w.to_string()));
                    }
                    let message = e.to_string();
                    tell(Progress::Failed(message.clone()));
                    self.failed.push(message);
                }
            }
            self.next += 1;
        }
    }
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
    numeric_stage(derived(scene, symbolic)?, fidelity)
}

/// A scene with its symbolic stage done: what the numeric stage starts from.
struct Derived {
    scene: Scene,
    plan: Plan,
    symbolic: Symbolic,
    from_cache: FromCache,
    /// The symbolic stage's wall time (zero when it came from the cache).
    seconds: f64,
}

/// The symbolic stage of `scene`, unless `symbolic` gives its results.
fn derived(scene: Scene, symbolic: Option<Symbolic>) -> Result<Derived, RunError> {
    let start = Instant::now();
    let plan = Plan::for_scene(&scene);
    let (symbolic, from_cache) = match symbolic {
        Some(s) => (s, FromCache::Symbolic),
        None => (symbolic_stage(&scene, &plan)?, FromCache::Nothing),
    };
    Ok(Derived {
        scene,
        plan,
        symbolic,
        from_cache,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// The numeric stage: quadrature, figures, the numeric routes of claims, steps and variants.
/// `fidelity` (from the command line) overrides the scene's own setting.
fn numeric_stage(d: Derived, fidelity: Option<Fidelity>) -> Result<SceneReport, RunError> {
    let Derived {
        scene,
        plan,
        symbolic,
        from_cache,
        seconds: symbolic_wall,
    } = d;
    let fidelity = scene.fidelity_given(fidelity);
    let start = Instant::now();
    let work_before = numeric::Work::so_far();
    let fail = |source: StageError| RunError::in_scene(&scene, source);
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
            at: scene.plot_at.get(e.index).copied().unwrap_or(scene.id_at),
            plot: Some(e.index),
            ..RunError::in_scene(&scene, e.source.into())
        })?
    } else {
        Vec::new()
    };
    let mut verification = Verification {
        claims: symbolic.claims,
        regressions: symbolic.regressions,
        step_records: symbolic.step_records,
        ..Verification::default()
    };
    // The steps' checks and the variants' share one budget.
    let deadline = crate::numeric::budget::Deadline::checks();
    verify::verify_numeric(
        &scene,
        derivation,
        numeric.as_ref(),
        &plan,
        &mut verification,
    )
    .map_err(|e| fail(e.into()))?;
    if plan.runs(Stage::Steps) {
        verification.steps = crate::steps::check_steps(&scene, derivation, &deadline);
    }
    if let Some(problem) = &scene.problem {
        verification.variants =
            verify::variants::check_variants(&scene, derivation, problem, &deadline)
                .map_err(|e| fail(StageError::Variant(Box::new(e))))?;
        verification.pin = Some(verify::variants::Pin::new(&scene, problem));
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
        seconds: symbolic_wall + start.elapsed().as_secs_f64(),
        from_cache,
    })
}

/// The symbolic part of a report, for the cache.
pub fn symbolic_part(r: &SceneReport) -> Symbolic {
    Symbolic {
        derivation: r.derivation.clone(),
        claims: r.verification.claims.clone(),
        regressions: r.verification.regressions.clone(),
        step_records: r.verification.step_records.clone(),
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

#[cfg(test)]
mod tests {
    use super::{FromCache, Progress, ResultStore, run_all, run_scene_stored};
    use crate::model::fidelity::Fidelity;
    use crate::scene::Scene;
    use std::cell::RefCell;
    use std::collections::BTreeMap;

    /// A store in memory, keyed by scene and fidelity name ("" for the symbolic results).
    #[derive(Default)]
    struct Memory(RefCell<BTreeMap<(String, String), Vec<u8>>>);

    fn key(scene: &Scene, fidelity: Option<&Fidelity>) -> (String, String) {
        (
            scene.id.clone(),
            fidelity.map(|f| f.name()).unwrap_or_default(),
        )
    }

    impl ResultStore for Memory {
        type Warning = String;
        fn get(&self, s: &Scene, f: Option<&Fidelity>, _: &mut Vec<String>) -> Option<Vec<u8>> {
            self.0.borrow().get(&key(s, f)).cloned()
        }
        fn unreadable(&self, s: &Scene, f: Option<&Fidelity>) -> String {
            format!("unreadable {:?}", key(s, f))
        }
        fn put(&self, s: &Scene, f: Option<&Fidelity>, bytes: &[u8]) -> Result<(), String> {
            self.0.borrow_mut().insert(key(s, f), bytes.to_vec());
            Ok(())
        }
    }

    fn hoop() -> Scene {
        lecture("lecture-3-4/06-hoop.toml")
    }

    /// A lecture scene's claims whose two sides differ in dimension, at draft fidelity.
    fn differing_in_dimension(path: &str) -> Vec<crate::verify::ClaimResult> {
        let report = super::run_scene(lecture(path), Some(Fidelity::DRAFT)).unwrap();
        let claims = report.verification.claims.into_iter();
        claims.filter(|c| c.dimension.is_some()).collect()
    }

    /// A claim whose sides differ in dimension says so on the page with the quantity as its
    /// symbol (the tilted hoop's eq. (45): I_xz), never as mechbook's name for it; the terminal
    /// keeps the name the author wrote.
    #[test]
    fn a_difference_in_dimension_names_the_quantity_by_its_symbol() {
        use crate::model::prose::Piece;
        use crate::notation::{Formula, Names};
        let claims = differing_in_dimension("lecture-3-4/07-tilted-hoop.toml");
        let claim = claims.first().expect("eq. (45) differs in dimension");
        assert!(
            claim
                .dimension
                .as_deref()
                .unwrap()
                .contains("`inertia_tensor[0][2]`")
        );
        let said = claim.differences.last().unwrap();
        let symbol = said.0.iter().find_map(|p| match p {
            Piece::Math(Formula::Tex(t)) => Some(t.source.clone()),
            _ => None,
        });
        assert_eq!(symbol.as_deref(), Some("{I}_{xz}"));
        let plain = said.to_plain(Names::none());
        assert!(!plain.contains("inertia_tensor"), "{plain}");
    }

    /// A quantity the scene spells as a word (`plane_distance_squared`) is named by the symbol
    /// the claim gives it (`tex = "d^{2}"`), never by its name in backticks.
    #[test]
    fn a_difference_in_dimension_names_a_word_by_the_claims_symbol() {
        use crate::notation::Names;
        let claims = differing_in_dimension("lecture-3-9/04-poinsot.toml");
        let said: Vec<String> = claims
            .iter()
            .map(|c| c.differences.last().unwrap().to_plain(Names::none()))
            .collect();
        assert!(!said.is_empty());
        for s in &said {
            assert!(!s.contains("plane_distance_squared"), "{s}");
        }
        assert!(said.iter().any(|s| s.contains("but d² is in")), "{said:?}");
        // The dimensions are set as units, not written as the terminal's text (kg^-1), and
        // read so in the JSON export's text too.
        let text: Vec<String> = claims
            .iter()
            .map(|c| c.differences.last().unwrap().to_text())
            .collect();
        assert!(
            text.iter()
                .any(|s| s.contains("is in kg⁻¹ m⁻²: they differ by kg m² s⁻²")),
            "{text:?}"
        );
        assert!(
            said.iter()
                .any(|s| s.contains("is in s⁻², but d² is in kg⁻¹ m⁻²: they differ by kg m² s⁻²")),
            "{said:?}"
        );
    }

    /// A notes' value that adds terms of unlike dimension (the cube's eq. (28): a⁴ beside a³)
    /// sets each term as a formula and its dimension as a unit on the page, never the engine's
    /// text in backticks (`a*a^3/a`) or the terminal's units (m^4).
    #[test]
    fn an_unlike_sum_in_the_notes_sets_its_terms_and_units_as_mathematics() {
        use crate::model::prose::Piece;
        use crate::notation::Names;
        let claims = differing_in_dimension("lecture-3-4/05-cube-corner.toml");
        let claim = claims
            .iter()
            .find(|c| c.eq == "28")
            .expect("eq. (28) adds unlike terms");
        let said = claim.differences.last().unwrap();
        let formulas = said
            .0
            .iter()
            .filter(|p| matches!(p, Piece::Math(_)))
            .count();
        assert_eq!(formulas, 4, "two terms and two units: {said:?}");
        let plain = said.to_plain(Names::none());
        assert!(!plain.contains('`') && !plain.contains('^'), "{plain}");
        crate::base::assert_says(
            &plain,
            &[
                " is in m⁴ but ",
                " is in m³: a sum's terms must have one dimension",
            ],
        );
    }

    #[test]
    fn the_store_gives_back_whole_reports_then_symbolic_parts_and_survives_damage() {
        let store = Memory::default();
        let draft = Some(Fidelity::DRAFT);
        let (first, w) = run_scene_stored(&store, hoop(), draft).unwrap();
        assert!(w.is_empty());
        assert_eq!(first.from_cache, FromCache::Nothing);
        // The report at this fidelity and the symbolic results, nothing else.
        assert_eq!(store.0.borrow().len(), 2);
        let (again, _) = run_scene_stored(&store, hoop(), draft).unwrap();
        assert_eq!(again.from_cache, FromCache::Everything);
        assert_eq!(
            super::to_cache(&again),
            super::to_cache(&first),
            "a stored report comes back as it was"
        );
        // Another fidelity reruns only the numeric stage, on the same exact results.
        let (other, _) = run_scene_stored(&store, hoop(), Some(Fidelity::STANDARD)).unwrap();
        assert_eq!(other.from_cache, FromCache::Symbolic);
        assert_eq!(other.derivation.quantities, first.derivation.quantities);
        // A damaged report is said and run again, from the stored symbolic results.
        let k = key(&hoop(), Some(&Fidelity::DRAFT));
        store.0.borrow_mut().insert(k, b"not json".to_vec());
        let (rerun, w) = run_scene_stored(&store, hoop(), draft).unwrap();
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(rerun.from_cache, FromCache::Symbolic);
    }

    fn lecture(path: &str) -> Scene {
        let path = format!("{}/lectures/{path}", env!("CARGO_MANIFEST_DIR"));
        Scene::parse(
            &std::fs::read_to_string(&path).unwrap(),
            std::path::Path::new(&path),
        )
        .unwrap()
    }

    /// A scene whose step is beyond the engine's budget: it fails in its symbolic stage.
    fn too_big() -> Scene {
        let text = "id = \"big\"\ntitle = \"Too big\"\nnotes = { lecture = \"6\" }\n\
                    symbols = { x = \"one\", y = \"other\" }\n[[step]]\nname = \"P\"\n\
                    be = \"(x + y)^40\"\n[numeric]\nvalues = { x = 1.0, y = 2.0 }\n";
        Scene::parse(text, std::path::Path::new("big.toml")).unwrap()
    }

    /// A run of many scenes on two threads gives each scene's report, warning and error in the
    /// scenes' order, the same as running them one by one; one scene's failure stops no other.
    #[test]
    fn many_scenes_on_two_threads_come_back_in_order_as_one_by_one() {
        let scenes = || {
            vec![
                // The slowest numeric stage first: the scenes behind it finish their symbolic
                // stage before it is checked.
                lecture("lecture-3-9/03-asymmetric-top.toml"),
                hoop(),
                too_big(),
                lecture("lecture-3-4/05-cube-corner.toml"),
                lecture("lecture-3-9/02-symmetric-top.toml"),
            ]
        };
        let draft = Some(Fidelity::DRAFT);
        let one_by_one: Vec<_> = scenes()
            .into_iter()
            .map(|s| run_scene_stored(&Memory::default(), s, draft).map(|(r, _)| r))
            .collect();
        // One stored report damaged: its warning is told in its place.
        let store = Memory::default();
        store
            .0
            .borrow_mut()
            .insert(key(&hoop(), Some(&Fidelity::DRAFT)), b"not json".to_vec());
        let mut told = Vec::new();
        let (reports, failed) = run_all(scenes(), draft, &store, &mut |p| match p {
            Progress::Warning(w) => told.push(format!("warning {w}")),
            Progress::Failed(e) => told.push(format!("failed {}", e.split(':').next().unwrap())),
            Progress::Starting { .. } | Progress::Finished => {}
        });
        assert_eq!(
            told,
            [
                "warning unreadable (\"hoop\", \"draft\")".to_string(),
                "failed big.toml".into()
            ]
        );
        assert_eq!(failed.len(), 1);
        let ids: Vec<_> = reports.iter().map(|r| r.scene.id.as_str()).collect();
        let expected: Vec<_> = one_by_one
            .iter()
            .flatten()
            .map(|r| r.scene.id.as_str())
            .collect();
        assert_eq!(ids, expected);
        let e = one_by_one[2].as_ref().unwrap_err();
        assert!(e.to_string().contains("beyond the engine's budget"), "{e}");
        for (r, alone) in reports.iter().zip(one_by_one.iter().flatten()) {
            // What was computed, less the times it took.
            fn timeless(v: &mut serde_json::Value) {
                match v {
                    serde_json::Value::Object(o) => {
                        o.remove("seconds");
                        o.values_mut().for_each(timeless);
                    }
                    serde_json::Value::Array(a) => a.iter_mut().for_each(timeless),
                    _ => {}
                }
            }
            let json = |r: &super::SceneReport| {
                let mut v =
                    serde_json::to_value((&r.derivation, &r.verification, &r.figures)).unwrap();
                timeless(&mut v);
                v
            };
            assert!(json(r) == json(alone), "{} differs", r.scene.id);
            assert_eq!(r.engine_calls, alone.engine_calls, "{}", r.scene.id);
            assert_eq!(
                r.numeric_work.rhs_evaluations, alone.numeric_work.rhs_evaluations,
                "{}",
                r.scene.id
            );
        }
        // Each report was stored, whole and symbolic.
        assert_eq!(store.0.borrow().len(), 2 * reports.len());
    }
}
