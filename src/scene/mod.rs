//! Scene files: TOML text -> a validated [`Scene`].
//!
//! Parsing is separate from reading (`Scene::parse` / `Scene::from_file`), so tests need no disk.
//! Every error names the file, line, column and field.

mod error;
mod load;
mod raw;

pub use error::{Locator, SceneError};
pub use load::MAX_SCENE_BYTES;
use load::{read_scene_file, toml_error};

use crate::cas::{Expr, parse_input as parse_expr};
use raw::{RawBody, RawScene, Text};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use toml::Spanned;

#[derive(Debug, Clone)]
pub struct Scene {
    pub id: String,
    pub title: String,
    /// The path the scene was read from, as given (never made absolute).
    pub source: PathBuf,
    /// A hash of the file's bytes: with the fidelity and the program, the key of the build cache.
    pub content_hash: u64,
    /// Where `id` and `notes.lecture` are written (line, column), for errors found across files.
    pub id_at: (usize, usize),
    pub lecture_at: (usize, usize),
    pub notes: NotesRef,
    /// Symbol name -> its meaning.
    pub symbols: BTreeMap<String, String>,
    /// Abbreviations used in claims, such as `lambda = M/(2*pi*R)`.
    pub definitions: BTreeMap<String, Expr>,
    pub vectors: BTreeMap<String, [Expr; 3]>,
    pub omega: Option<[Expr; 3]>,
    pub axis: Option<[Expr; 3]>,
    pub bodies: Vec<Body>,
    pub claims: Vec<Claim>,
    pub wants: Vec<Output>,
    pub plots: Vec<PlotRequest>,
    pub values: BTreeMap<String, f64>,
    pub seed: u64,
    /// `[numeric] fidelity`: this scene's default, which `--fidelity` overrides.
    pub fidelity: Option<crate::numeric::fidelity::Fidelity>,
    /// Recorded results: quantity name -> expected exact value (the regression record).
    pub expect: BTreeMap<String, Expr>,
}

#[derive(Debug, Clone)]
pub struct NotesRef {
    pub lecture: String,
    pub section: String,
    pub equations: Vec<String>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    X,
    Y,
    Z,
}

impl Axis {
    pub fn index(self) -> usize {
        self as usize
    }
    pub fn name(self) -> &'static str {
        ["x", "y", "z"][self as usize]
    }
}

#[derive(Debug, Clone)]
pub struct Body {
    pub label: String,
    pub shape: Shape,
    /// Total mass; for point sets, the sum of the point masses.
    pub mass: Expr,
    /// Applied in order to the body's own coordinates, then `shift`.
    pub rotations: Vec<(Axis, Expr)>,
    pub shift: [Expr; 3],
}

#[derive(Debug, Clone)]
pub enum Shape {
    /// Sides along x, y, z; the body's origin at a corner or at the centre.
    Box {
        size: [Expr; 3],
        centred: bool,
    },
    /// A thin rod along an axis, from its end or centred.
    Rod {
        length: Expr,
        along: Axis,
        centred: bool,
    },
    /// A thin hoop (ring) of radius R in the xy-plane, centred.
    Hoop {
        radius: Expr,
    },
    /// A thin uniform disk in the xy-plane, centred.
    Disk {
        radius: Expr,
    },
    /// A solid cylinder about z, centred.
    Cylinder {
        radius: Expr,
        height: Expr,
    },
    Sphere {
        radius: Expr,
    },
    /// A thin spherical shell.
    Shell {
        radius: Expr,
    },
    Points(Vec<(Expr, [Expr; 3])>),
}

impl Shape {
    pub fn kind(&self) -> &'static str {
        match self {
            Shape::Box { .. } => "box",
            Shape::Rod { .. } => "rod",
            Shape::Hoop { .. } => "hoop",
            Shape::Disk { .. } => "disk",
            Shape::Cylinder { .. } => "cylinder",
            Shape::Sphere { .. } => "sphere",
            Shape::Shell { .. } => "shell",
            Shape::Points(_) => "points",
        }
    }

    /// The names of the shape's integration variables; scene symbols may not reuse them.
    pub fn variables(&self) -> &'static [&'static str] {
        match self {
            Shape::Box { .. } => &["x", "y", "z"],
            Shape::Rod { .. } => &["s"],
            Shape::Hoop { .. } => &["theta"],
            Shape::Disk { .. } => &["r", "theta"],
            Shape::Cylinder { .. } => &["r", "theta", "z"],
            Shape::Sphere { .. } => &["r", "theta", "phi"],
            Shape::Shell { .. } => &["theta", "phi"],
            Shape::Points(_) => &[],
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    Agrees,
    Disagrees,
    NotCheckable,
}

impl Verdict {
    pub fn as_str(self) -> &'static str {
        match self {
            Verdict::Agrees => "agrees",
            Verdict::Disagrees => "disagrees",
            Verdict::NotCheckable => "not-checkable",
        }
    }
}

#[derive(Debug, Clone)]
pub struct Claim {
    pub eq: String,
    pub statement: String,
    /// The derived side, in the claim language (`inertia_tensor[0][1]`, `cross(a, b)`).
    pub quantity: Option<Expr>,
    /// The notes' side, restated.
    pub value: Option<Expr>,
    /// Set when the notes give a number to this many significant figures: both sides are then
    /// numbers, and they agree when the derived one rounds to the notes' value.
    pub figures: Option<u32>,
    pub expect: Verdict,
    pub line: usize,
}

/// A plot a scene asks for; `numeric::plots` computes its data.
#[derive(Debug, Clone, PartialEq)]
pub enum PlotRequest {
    /// The tensor's entries against one symbol: exact curves, with quadrature at sample values.
    TensorSweep {
        over: String,
        from: f64,
        to: f64,
        samples: usize,
    },
    /// Quadrature error against points for every method, with each method's error law.
    Convergence,
    /// The principal axes in a projected 3-D view of the body.
    PrincipalAxes,
    /// A torque-free body given by its principal moments and ω(0), integrated to `t`.
    FreeBody {
        kind: FreeBodyPlot,
        inertia: [f64; 3],
        omega: [f64; 3],
        t: f64,
    },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FreeBodyPlot {
    /// ω(t) by the exact solution, with Dormand–Prince points.
    OmegaVsTime,
    /// Polhodes on the energy ellipsoid in L-space, with the separatrix.
    Polhodes,
    /// Energy and |L| drift against time for each integrator, log scale.
    Drift,
    /// The tennis racket: ω along the intermediate axis flips; flip times measured vs predicted.
    Flip,
    /// The same small wobble started about each principal axis: only the intermediate one departs.
    AxisSpins,
    /// The herpolhode: ω's tip traced on the invariable plane in space.
    Herpolhode,
    /// Earth's polar motion over one Euler period (symmetric top with the given moments).
    PolarMotion,
    /// The symmetric top's body and space cones, with their measured half-angles.
    Cones,
    /// Error at `t` against right-hand-side evaluations for every integrator and step, with
    /// the Pareto front.
    IntegratorPareto,
}

impl FreeBodyPlot {
    pub const ALL: &'static [(&'static str, FreeBodyPlot)] = &[
        ("omega-vs-time", FreeBodyPlot::OmegaVsTime),
        ("polhodes", FreeBodyPlot::Polhodes),
        ("drift", FreeBodyPlot::Drift),
        ("flip", FreeBodyPlot::Flip),
        ("axis-spins", FreeBodyPlot::AxisSpins),
        ("herpolhode", FreeBodyPlot::Herpolhode),
        ("polar-motion", FreeBodyPlot::PolarMotion),
        ("cones", FreeBodyPlot::Cones),
        ("integrator-pareto", FreeBodyPlot::IntegratorPareto),
    ];

    pub fn name(self) -> &'static str {
        FreeBodyPlot::ALL
            .iter()
            .find(|(_, k)| *k == self)
            .unwrap()
            .0
    }
}

impl PlotRequest {
    pub const KINDS: &'static [&'static str] = &[
        "tensor-sweep",
        "convergence",
        "principal-axes",
        "omega-vs-time",
        "polhodes",
        "drift",
        "flip",
        "axis-spins",
        "herpolhode",
        "polar-motion",
        "cones",
        "integrator-pareto",
    ];

    pub fn kind(&self) -> &'static str {
        match self {
            PlotRequest::TensorSweep { .. } => "tensor-sweep",
            PlotRequest::Convergence => "convergence",
            PlotRequest::PrincipalAxes => "principal-axes",
            PlotRequest::FreeBody { kind, .. } => kind.name(),
        }
    }

    /// Plots of a body's tensor need a `[[body]]`; free-body plots carry their own.
    pub fn needs_body(&self) -> bool {
        !matches!(self, PlotRequest::FreeBody { .. })
    }
}

/// What a scene asks for. Each one pulls in the stages it needs (see `plan`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Output {
    InertiaTensor,
    ParallelAxis,
    PrincipalAxes,
    AngularMomentum,
    KineticEnergy,
    MomentAboutAxis,
    Gyration,
    Numeric,
    EulerEquations,
    SymmetricTop,
    AxisStability,
    Poinsot,
    EarthPrecession,
}

impl Output {
    pub const ALL: &'static [(&'static str, Output)] = &[
        ("inertia_tensor", Output::InertiaTensor),
        ("parallel_axis", Output::ParallelAxis),
        ("principal_axes", Output::PrincipalAxes),
        ("angular_momentum", Output::AngularMomentum),
        ("kinetic_energy", Output::KineticEnergy),
        ("moment_about_axis", Output::MomentAboutAxis),
        ("gyration", Output::Gyration),
        ("numeric", Output::Numeric),
        ("euler_equations", Output::EulerEquations),
        ("symmetric_top", Output::SymmetricTop),
        ("axis_stability", Output::AxisStability),
        ("poinsot", Output::Poinsot),
        ("earth_precession", Output::EarthPrecession),
    ];

    pub fn name(self) -> &'static str {
        Output::ALL.iter().find(|(_, o)| *o == self).unwrap().0
    }

    /// The symbols a free-body derivation writes its results in, which the scene must declare;
    /// `None` for the outputs computed from the scene's bodies.
    pub fn free_body_symbols(self) -> Option<&'static [&'static str]> {
        use crate::derive::{earth, euler, free_top, poinsot, stability};
        Some(match self {
            Output::EulerEquations => euler::SYMBOLS,
            Output::SymmetricTop => free_top::SYMBOLS,
            Output::AxisStability => stability::SYMBOLS,
            Output::Poinsot => poinsot::SYMBOLS,
            Output::EarthPrecession => earth::SYMBOLS,
            _ => return None,
        })
    }
}

/// Names a claim may use for derived quantities, and the functions of the claim language.
pub const QUANTITIES: &[&str] = &[
    "mass",
    "centre_of_mass",
    "inertia_tensor",
    "inertia_cm",
    "principal_moments",
    "angular_momentum",
    "angular_momentum_direct",
    "kinetic_energy",
    "kinetic_energy_direct",
    "moment_about_axis",
    "moment_about_axis_direct",
    "radius_of_gyration",
    "integrand",
    "position",
];
/// Quantities of the free-body derivations (Lecture 3/9), which need no body.
pub const DYNAMICS_QUANTITIES: &[&str] = &[
    "principal_momentum",
    "gyroscopic_term",
    "euler_equations",
    "body_rate_of_momentum",
    "torque_free_rates",
    "w1_second_derivative",
    "symmetric_solution",
    "symmetric_residual",
    "omega_squared",
    "precession_rate",
    "twice_energy",
    "momentum_squared",
    "body_cone_tan_squared",
    "space_cone_cos_squared",
    "momentum_tilt_tan_squared",
    "cone_order",
    "oscillation_frequency_squared",
    "amplitude_ratio_squared",
    "stability",
    "growth_rate_squared",
    "ellipsoid_value",
    "gradient_factor_squared",
    "plane_distance_squared",
    "energy_from_momentum",
    "momentum_gap",
    "polhode_conic_product",
    "polhode_closure",
    "separatrix_slope_squared",
    "earth_beta",
    "euler_period_sidereal_days",
    "euler_period_solar_days",
    "chandler_ratio",
    "bulge_km",
    "bulge_fraction",
];

/// A name of a derived quantity, from a body or from a free-body derivation.
pub fn is_quantity(name: &str) -> bool {
    QUANTITIES.contains(&name) || DYNAMICS_QUANTITIES.contains(&name)
}
pub const CLAIM_FUNCTIONS: &[&str] = &[
    "diff",
    "sin",
    "cos",
    "sqrt",
    "dot",
    "cross",
    "outer",
    "transpose",
    "eye",
    "diag",
    "rot_x",
    "rot_y",
    "rot_z",
    "trace",
    "det",
    "sign",
    "subs",
];
const RESERVED: &[&str] = &["pi"];

/// The largest degree and number of terms a dimension, mass or value expression may expand
/// to: the derivations raise a dimension to the fifth power at most, and the engine's own
/// budget is degree 30 (`cas`).
pub const MAX_INPUT_DEGREE: f64 = 6.0;
pub const MAX_INPUT_TERMS: f64 = 100.0;

/// The longest free-body plot: its end time, and the radians ω turns through by then. The
/// shipped lectures reach t = 400 and 2.5e3 radians (Earth's polar motion).
pub const MAX_PLOT_TIME: f64 = 1e4;
pub const MAX_PLOT_RADIANS: f64 = 1e4;

/// Ids that would collide with the site's own files and folders (compared without case, as
/// some file systems do).
pub const RESERVED_IDS: &[&str] = &["index", "plots", "handouts", "export", "style"];

/// The longest id or lecture name: file names are made from them with up to ~40 more
/// characters, and file systems allow 255 bytes.
pub const MAX_NAME: usize = 64;

/// "3/4" -> "lecture-3-4": the file name of a lecture's handouts.
pub fn lecture_slug(name: &str) -> String {
    let clean: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect();
    format!("lecture-{}", clean.trim_matches('-'))
}

impl Scene {
    /// Reads and parses a scene file: a regular file of at most [`MAX_SCENE_BYTES`], in UTF-8.
    pub fn from_file(path: &Path) -> Result<Scene, SceneError> {
        let bytes = read_scene_file(path).map_err(|message| SceneError {
            path: path.to_path_buf(),
            line: 1,
            column: 1,
            field: String::new(),
            message,
        })?;
        match std::str::from_utf8(&bytes) {
            Ok(text) => Scene::parse(text, path),
            Err(e) => {
                let valid = std::str::from_utf8(&bytes[..e.valid_up_to()]).unwrap_or("");
                let loc = Locator { path, text: valid };
                Err(loc.error(
                    valid.len(),
                    "",
                    format!(
                        "invalid UTF-8 (byte 0x{:02x} at byte offset {}): save the file as UTF-8",
                        bytes[e.valid_up_to()],
                        e.valid_up_to()
                    ),
                ))
            }
        }
    }

    pub fn parse(text: &str, path: &Path) -> Result<Scene, SceneError> {
        let loc = Locator { path, text };
        let raw: RawScene = toml::from_str(text).map_err(|e| {
            let offset = e.span().map(|s| s.start).unwrap_or(0);
            toml_error(&loc, offset, e.message())
        })?;
        Validator { loc: &loc }.scene(raw)
    }
}

struct Validator<'a> {
    loc: &'a Locator<'a>,
}

/// The byte offset of a string's first character inside its quotes.
/// FNV-1a, 64 bits: stable across runs, platforms and Rust releases (std's hasher is not).
pub fn content_hash(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(*b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

fn content_start<T>(s: &Spanned<T>) -> usize {
    s.span().start + 1
}

fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
        && !s.contains("__")
}

impl Validator<'_> {
    /// The byte offset where a 1-based line starts.
    fn line_offset(&self, line: usize) -> usize {
        self.loc
            .text
            .split_inclusive('\n')
            .take(line.saturating_sub(1))
            .map(str::len)
            .sum()
    }

    fn err(&self, offset: usize, field: &str, msg: impl Into<String>) -> SceneError {
        self.loc.error(offset, field, msg)
    }

    /// Parses an expression and checks that every symbol is one of `allowed`.
    fn expr(&self, t: &Text, field: &str, allowed: &BTreeSet<String>) -> Result<Expr, SceneError> {
        self.expr_str(t.get_ref(), content_start(t), field, allowed)
    }

    /// Parses `text`, which starts at byte `start` of the file.
    fn expr_str(
        &self,
        text: &str,
        start: usize,
        field: &str,
        allowed: &BTreeSet<String>,
    ) -> Result<Expr, SceneError> {
        self.parse_checked(text, start, field, allowed, false)
    }

    /// Parses `text` (at byte `start` of the file), checks its names against `names` and its
    /// calls against the scalar functions, or the claim language's when `claim` is set.
    fn parse_checked(
        &self,
        text: &str,
        start: usize,
        field: &str,
        names: &BTreeSet<String>,
        claim: bool,
    ) -> Result<Expr, SceneError> {
        let parsed = parse_expr(text).map_err(|e| {
            self.err(
                start + e.offset,
                field,
                format!("malformed expression: {}", e.message),
            )
        })?;
        if let Some((name, offset)) = parsed.symbols.iter().find(|(n, _)| !names.contains(n)) {
            let message = if claim {
                format!(
                    "undefined name `{name}` (not a symbol, definition, vector or derived quantity)"
                )
            } else {
                format!("undefined symbol `{name}` (declare it under [symbols])")
            };
            return Err(self.err(start + offset, field, message));
        }
        check_calls(&parsed.expr, claim).map_err(|m| self.err(start, field, m))?;
        let size = parsed.expr.expansion_size();
        if !claim && (size.degree > MAX_INPUT_DEGREE || size.terms > MAX_INPUT_TERMS) {
            return Err(self.err(
                start,
                field,
                format!(
                    "this expression expands to degree {} with up to {:.0} terms; a scene's \
                     dimensions and masses stay within degree {MAX_INPUT_DEGREE} and \
                     {MAX_INPUT_TERMS} terms, so that the derivations stay fast: introduce a \
                     symbol for it",
                    size.degree, size.terms
                ),
            ));
        }
        Ok(parsed.expr)
    }

    fn vec3(
        &self,
        v: &Spanned<Vec<Text>>,
        field: &str,
        allowed: &BTreeSet<String>,
    ) -> Result<[Expr; 3], SceneError> {
        if v.get_ref().len() != 3 {
            return Err(self.err(
                v.span().start,
                field,
                format!("expected 3 components, found {}", v.get_ref().len()),
            ));
        }
        let items: Vec<Expr> = v
            .get_ref()
            .iter()
            .enumerate()
            .map(|(i, t)| self.expr(t, &format!("{field}[{i}]"), allowed))
            .collect::<Result<_, _>>()?;
        Ok([items[0].clone(), items[1].clone(), items[2].clone()])
    }

    fn scene(&self, raw: RawScene) -> Result<Scene, SceneError> {
        let id = raw.id.get_ref();
        if !is_identifier(&id.replace('-', "_")) {
            return Err(self.err(
                content_start(&raw.id),
                "id",
                "an id is letters, digits, `-` and `_`, starting with a letter",
            ));
        }
        if id.len() > MAX_NAME {
            return Err(self.err(
                content_start(&raw.id),
                "id",
                format!(
                    "an id of {} characters; the limit is {MAX_NAME}, so that every file name \
                     made from it fits any file system",
                    id.len()
                ),
            ));
        }
        if RESERVED_IDS.contains(&id.to_ascii_lowercase().as_str()) {
            return Err(self.err(
                content_start(&raw.id),
                "id",
                format!(
                    "`{id}` is reserved for the site's own {}; choose another id",
                    if id.eq_ignore_ascii_case("index") {
                        "index page"
                    } else {
                        "folder"
                    }
                ),
            ));
        }
        let lecture = raw.notes.lecture.get_ref();
        if lecture.len() > MAX_NAME || !lecture.chars().any(|c| c.is_ascii_alphanumeric()) {
            return Err(self.err(
                content_start(&raw.notes.lecture),
                "notes.lecture",
                format!(
                    "a lecture name has a letter or digit and at most {MAX_NAME} characters, \
                     such as \"3/4\""
                ),
            ));
        }

        // Symbols.
        let mut symbols = BTreeMap::new();
        for (name, meaning) in &raw.symbols {
            let n = name.get_ref();
            if !is_identifier(n)
                || RESERVED.contains(&n.as_str())
                || is_quantity(n)
                || CLAIM_FUNCTIONS.contains(&n.as_str())
            {
                return Err(self.err(
                    name.span().start,
                    &format!("symbols.{n}"),
                    format!("`{n}` cannot be a symbol name"),
                ));
            }
            symbols.insert(n.clone(), meaning.clone());
        }
        let mut allowed: BTreeSet<String> = symbols.keys().cloned().collect();
        allowed.insert("pi".into());

        // Bodies first: their integration variables may not be symbols.
        let mut bodies = Vec::new();
        for (i, b) in raw.bodies.iter().enumerate() {
            bodies.push(self.body(b, &format!("body[{i}]"), &allowed)?);
        }
        for (i, b) in bodies.iter().enumerate() {
            for v in b.shape.variables() {
                if let Some((name, _)) = raw.symbols.iter().find(|(n, _)| n.get_ref() == v) {
                    return Err(self.err(name.span().start, &format!("symbols.{v}"), format!("`{v}` is the integration variable of body[{i}] ({}); choose another name", b.shape.kind())));
                }
            }
        }
        let variables: BTreeSet<String> = bodies
            .iter()
            .flat_map(|b| b.shape.variables().iter().map(|s| s.to_string()))
            .collect();

        let mut definitions = BTreeMap::new();
        let mut claim_names = allowed.clone();
        for (name, value) in &raw.definitions {
            let n = name.get_ref();
            if !is_identifier(n) || allowed.contains(n) {
                return Err(self.err(
                    name.span().start,
                    &format!("definitions.{n}"),
                    format!("`{n}` cannot be defined here (not a name, or already a symbol)"),
                ));
            }
            let mut scope = allowed.clone();
            scope.extend(variables.iter().cloned());
            definitions.insert(
                n.clone(),
                self.expr(value, &format!("definitions.{n}"), &scope)?,
            );
            claim_names.insert(n.clone());
        }

        let mut vectors = BTreeMap::new();
        for (name, v) in &raw.vectors {
            let n = name.get_ref();
            if !is_identifier(n) || claim_names.contains(n) {
                return Err(self.err(
                    name.span().start,
                    &format!("vectors.{n}"),
                    format!("`{n}` cannot name a vector (not a name, or already used)"),
                ));
            }
            vectors.insert(n.clone(), self.vec3(v, &format!("vectors.{n}"), &allowed)?);
        }
        claim_names.extend(vectors.keys().cloned());
        claim_names.extend(variables.iter().cloned());
        claim_names.extend(
            QUANTITIES
                .iter()
                .chain(DYNAMICS_QUANTITIES)
                .map(|s| s.to_string()),
        );

        let omega = raw
            .omega
            .as_ref()
            .map(|v| self.vec3(v, "omega", &allowed))
            .transpose()?;
        let axis = raw
            .axis
            .as_ref()
            .map(|v| self.vec3(v, "axis", &allowed))
            .transpose()?;
        if omega.is_some() {
            claim_names.insert("omega".into());
        }
        if axis.is_some() {
            claim_names.insert("axis".into());
        }

        let mut claims = Vec::new();
        for (i, c) in raw.claims.iter().enumerate() {
            claims.push(self.claim(
                c.get_ref(),
                c.span().start,
                &format!("claim[{i}]"),
                &claim_names,
            )?);
        }

        let mut wants = Vec::new();
        for (i, w) in raw.outputs.want.get_ref().iter().enumerate() {
            let Some((_, o)) = Output::ALL.iter().find(|(n, _)| n == w.get_ref()) else {
                let names: Vec<&str> = Output::ALL.iter().map(|(n, _)| *n).collect();
                return Err(self.err(
                    content_start(w),
                    &format!("outputs.want[{i}]"),
                    format!(
                        "unknown output `{}`; expected one of: {}",
                        w.get_ref(),
                        names.join(", ")
                    ),
                ));
            };
            wants.push(*o);
        }
        wants.sort();
        wants.dedup();
        let mut plots = Vec::new();
        for (i, p) in raw.plots.iter().enumerate() {
            plots.push(self.plot(p, &format!("plot[{i}]"), &symbols)?);
        }
        if let Some(k) = plots.iter().position(|p| p.needs_body())
            && bodies.is_empty()
        {
            return Err(self.err(
                raw.plots[k].span().start,
                &format!("plot[{k}]"),
                format!("a {} plot needs at least one [[body]]", plots[k].kind()),
            ));
        }
        if wants.is_empty() && claims.is_empty() && plots.is_empty() {
            return Err(self.err(
                raw.outputs_span(),
                "outputs.want",
                "the scene asks for nothing: list at least one output or claim",
            ));
        }
        for w in &wants {
            let Some(needed) = w.free_body_symbols() else {
                continue;
            };
            if let Some(missing) = needed.iter().find(|n| !symbols.contains_key(**n)) {
                return Err(self.err(
                    raw.outputs_span(),
                    "outputs.want",
                    format!(
                        "output `{}` writes its results in {}; declare `{missing}` under [symbols]",
                        w.name(),
                        needed.join(", ")
                    ),
                ));
            }
        }
        if bodies.is_empty() {
            if let Some(w) = wants.iter().find(|w| w.free_body_symbols().is_none()) {
                return Err(self.err(
                    raw.outputs_span(),
                    "outputs.want",
                    format!("output `{}` needs at least one [[body]]", w.name()),
                ));
            }
            let uses_body = |c: &&Claim| {
                c.quantity
                    .iter()
                    .chain(c.value.iter())
                    .any(|e| e.symbols().iter().any(|s| QUANTITIES.contains(&s.as_str())))
            };
            if let Some(c) = claims.iter().find(uses_body) {
                return Err(self.err(
                    self.line_offset(c.line),
                    "claim",
                    format!(
                        "claim ({}) uses a derived quantity, but the scene has no [[body]]",
                        c.eq
                    ),
                ));
            }
        }
        if (wants.contains(&Output::AngularMomentum) || wants.contains(&Output::KineticEnergy))
            && omega.is_none()
        {
            return Err(self.err(
                raw.outputs_span(),
                "omega",
                "angular_momentum and kinetic_energy need `omega = [..]`",
            ));
        }
        if (wants.contains(&Output::MomentAboutAxis) || wants.contains(&Output::Gyration))
            && axis.is_none()
        {
            return Err(self.err(
                raw.outputs_span(),
                "axis",
                "moment_about_axis and gyration need `axis = [..]`",
            ));
        }

        // Numeric values: finite, one per symbol the bodies, omega and axis use.
        let mut values = BTreeMap::new();
        for (name, v) in &raw.numeric.values {
            let n = name.get_ref();
            let field = format!("numeric.values.{n}");
            if !symbols.contains_key(n) {
                return Err(self.err(
                    name.span().start,
                    &field,
                    format!("`{n}` is not a declared symbol"),
                ));
            }
            if !v.get_ref().is_finite() {
                return Err(self.err(v.span().start, &field, "the value must be a finite number"));
            }
            values.insert(n.clone(), *v.get_ref());
        }
        let mut used: BTreeSet<String> = BTreeSet::new();
        for b in &bodies {
            used.extend(body_symbols(b));
        }
        for v in omega.iter().chain(axis.iter()) {
            v.iter().for_each(|e| used.extend(e.symbols()));
        }
        used.remove("pi");
        for s in &used {
            if !values.contains_key(s) {
                let declared = raw.symbols.keys().find(|k| k.get_ref() == s);
                return Err(self.err(
                    declared.map_or(0, |k| k.span().start),
                    "numeric.values",
                    format!("no numeric value for symbol `{s}`"),
                ));
            }
        }
        for (i, rb) in raw.bodies.iter().enumerate() {
            self.check_positive(rb.get_ref(), &format!("body[{i}]"), &values)?;
        }

        let fidelity = match &raw.numeric.fidelity {
            Some(f) => Some(
                crate::numeric::fidelity::Fidelity::parse(f.get_ref())
                    .map_err(|m| self.err(content_start(f), "numeric.fidelity", m))?,
            ),
            None => None,
        };
        let mut expect = BTreeMap::new();
        for (name, value) in &raw.expect {
            let n = name.get_ref();
            if !is_quantity(n) {
                return Err(self.err(
                    name.span().start,
                    &format!("expect.{n}"),
                    format!(
                        "`{n}` is not a derived quantity; expected one of: {}, {}",
                        QUANTITIES.join(", "),
                        DYNAMICS_QUANTITIES.join(", ")
                    ),
                ));
            }
            let mut scope = allowed.clone();
            scope.extend(variables.iter().cloned());
            expect.insert(
                n.clone(),
                self.claim_expr(value, &format!("expect.{n}"), &scope)?,
            );
        }

        Ok(Scene {
            id_at: self.loc.line_col(content_start(&raw.id)),
            lecture_at: self.loc.line_col(content_start(&raw.notes.lecture)),
            id: raw.id.into_inner(),
            title: raw.title,
            source: self.loc.path.to_path_buf(),
            content_hash: content_hash(self.loc.text.as_bytes()),
            notes: NotesRef {
                lecture: raw.notes.lecture.into_inner(),
                section: raw.notes.section,
                equations: raw.notes.equations,
            },
            symbols,
            definitions,
            vectors,
            omega,
            axis,
            bodies,
            claims,
            wants,
            plots,
            values,
            seed: raw.numeric.seed.unwrap_or(1),
            fidelity,
            expect,
        })
    }

    fn claim(
        &self,
        c: &raw::RawClaim,
        offset: usize,
        field: &str,
        names: &BTreeSet<String>,
    ) -> Result<Claim, SceneError> {
        let eq = c.eq.get_ref();
        let digits = eq.trim_end_matches(|ch: char| ch.is_ascii_lowercase());
        if digits.is_empty()
            || !digits.chars().all(|ch| ch.is_ascii_digit())
            || eq.len() - digits.len() > 1
        {
            return Err(self.err(content_start(&c.eq), &format!("{field}.eq"), "an equation number is digits with at most one letter after them, as \"31\" or \"22a\""));
        }
        let expect = match c.expect.get_ref().as_str() {
            "agrees" => Verdict::Agrees,
            "disagrees" => Verdict::Disagrees,
            "not-checkable" => Verdict::NotCheckable,
            other => {
                return Err(self.err(
                    content_start(&c.expect),
                    &format!("{field}.expect"),
                    format!(
                        "unknown verdict `{other}`; expected agrees, disagrees or not-checkable"
                    ),
                ));
            }
        };
        let quantity = c
            .quantity
            .as_ref()
            .map(|q| self.claim_expr(q, &format!("{field}.quantity"), names))
            .transpose()?;
        let value = c
            .value
            .as_ref()
            .map(|v| self.claim_expr(v, &format!("{field}.value"), names))
            .transpose()?;
        if expect != Verdict::NotCheckable && (quantity.is_none() || value.is_none()) {
            return Err(self.err(
                offset,
                field,
                "a checkable claim needs both `quantity` and `value`",
            ));
        }
        let figures = match &c.figures {
            None => None,
            Some(f) if (1..=15).contains(f.get_ref()) => Some(*f.get_ref() as u32),
            Some(f) => {
                return Err(self.err(
                    f.span().start,
                    &format!("{field}.figures"),
                    "significant figures are a whole number from 1 to 15",
                ));
            }
        };
        Ok(Claim {
            eq: eq.clone(),
            statement: c.statement.clone(),
            quantity,
            value,
            figures,
            expect,
            line: self.loc.line_col(offset).0,
        })
    }

    fn plot(
        &self,
        p: &Spanned<raw::RawPlot>,
        field: &str,
        symbols: &BTreeMap<String, String>,
    ) -> Result<PlotRequest, SceneError> {
        let rp = p.get_ref();
        let start = p.span().start;
        let sweep_fields = rp.over.is_some() || rp.range.is_some() || rp.samples.is_some();
        let body_fields = rp.inertia.is_some() || rp.omega.is_some() || rp.t.is_some();
        if let Some((_, kind)) = FreeBodyPlot::ALL
            .iter()
            .find(|(n, _)| n == rp.kind.get_ref())
        {
            if sweep_fields {
                return Err(self.err(
                    start,
                    field,
                    "`over`, `range` and `samples` belong to a tensor-sweep",
                ));
            }
            let triple = |v: &Option<Spanned<Vec<f64>>>,
                          name: &str|
             -> Result<[f64; 3], SceneError> {
                let v = v.as_ref().ok_or_else(|| {
                    self.err(
                        start,
                        &format!("{field}.{name}"),
                        format!("a {} plot needs `{name} = [x, y, z]`", kind.name()),
                    )
                })?;
                let arr = <[f64; 3]>::try_from(v.get_ref().as_slice()).map_err(|_| {
                    self.err(
                        v.span().start,
                        &format!("{field}.{name}"),
                        format!("expected 3 numbers, found {}", v.get_ref().len()),
                    )
                })?;
                if arr.iter().any(|x| !x.is_finite()) {
                    return Err(self.err(
                        v.span().start,
                        &format!("{field}.{name}"),
                        "the values must be finite numbers",
                    ));
                }
                // Subnormal numbers have lost digits: every product with them is wrong.
                if let Some(x) = crate::numeric::free_body::first_subnormal(&arr).map(|k| arr[k]) {
                    return Err(self.err(
                        v.span().start,
                        &format!("{field}.{name}"),
                        format!(
                            "{x:e} is below {:e}, where double precision keeps its digits: \
                                 write 0, or use other units",
                            f64::MIN_POSITIVE
                        ),
                    ));
                }
                Ok(arr)
            };
            let inertia = triple(&rp.inertia, "inertia")?;
            crate::numeric::free_body::Moments::new(inertia).map_err(|m| {
                self.err(
                    rp.inertia.as_ref().map_or(start, |v| v.span().start),
                    &format!("{field}.inertia"),
                    m,
                )
            })?;
            let omega = triple(&rp.omega, "omega")?;
            if omega.iter().all(|x| *x == 0.0) {
                return Err(self.err(
                    rp.omega.as_ref().map_or(start, |v| v.span().start),
                    &format!("{field}.omega"),
                    "omega must not be zero",
                ));
            }
            let moments = crate::numeric::free_body::Moments(inertia);
            let w0 = nalgebra::Vector3::from(omega);
            if let Some(why) = crate::numeric::free_body::beyond_double_precision(&moments, &w0) {
                return Err(self.err(
                    rp.omega.as_ref().map_or(start, |v| v.span().start),
                    &format!("{field}.omega"),
                    why,
                ));
            }
            let t = rp.t.as_ref().ok_or_else(|| {
                self.err(
                    start,
                    &format!("{field}.t"),
                    format!("a {} plot needs `t`, the end time", kind.name()),
                )
            })?;
            if !(t.get_ref().is_finite() && *t.get_ref() > 0.0) {
                return Err(self.err(
                    t.span().start,
                    &format!("{field}.t"),
                    "the end time must be a positive number",
                ));
            }
            // The plots integrate with fixed steps of about 0.05 (a quarter of that at
            // reference fidelity) and draw a few hundred points: these bounds keep every plot
            // within a few million steps and its curves readable.
            let turns = t.get_ref() * omega.iter().fold(0.0f64, |m, w| m.max(w.abs()));
            if *t.get_ref() > MAX_PLOT_TIME || turns > MAX_PLOT_RADIANS {
                return Err(self.err(
                    t.span().start,
                    &format!("{field}.t"),
                    format!(
                        "t = {} (t·|ω| = {turns:.3e} radians) is beyond what a plot integrates: \
                         keep t ≤ {MAX_PLOT_TIME:e} and t·|ω| ≤ {MAX_PLOT_RADIANS:e}, or use \
                         `mechbook spin` for long runs",
                        t.get_ref()
                    ),
                ));
            }
            return Ok(PlotRequest::FreeBody {
                kind: *kind,
                inertia,
                omega,
                t: *t.get_ref(),
            });
        }
        if body_fields {
            return Err(self.err(
                start,
                field,
                "`inertia`, `omega` and `t` belong to the free-body plot kinds",
            ));
        }
        let request = match rp.kind.get_ref().as_str() {
            "tensor-sweep" => {
                let over = rp.over.as_ref().ok_or_else(|| {
                    self.err(
                        start,
                        &format!("{field}.over"),
                        "a tensor-sweep needs `over`, the symbol on the x axis",
                    )
                })?;
                if !symbols.contains_key(over.get_ref()) {
                    return Err(self.err(
                        content_start(over),
                        &format!("{field}.over"),
                        format!("`{}` is not a declared symbol", over.get_ref()),
                    ));
                }
                let range = rp.range.as_ref().ok_or_else(|| {
                    self.err(
                        start,
                        &format!("{field}.range"),
                        "a tensor-sweep needs `range = [from, to]`",
                    )
                })?;
                let ends: Vec<f64> = range
                    .get_ref()
                    .iter()
                    .enumerate()
                    .map(|(i, t)| {
                        let f = format!("{field}.range[{i}]");
                        let e = self.expr_str(
                            t.get_ref(),
                            content_start(t),
                            &f,
                            &BTreeSet::from(["pi".to_string()]),
                        )?;
                        e.eval(&|_| None)
                            .map_err(|m| self.err(content_start(t), &f, m))
                    })
                    .collect::<Result<_, _>>()?;
                if ends.len() != 2 || !ends.iter().all(|x| x.is_finite()) || ends[0] >= ends[1] {
                    return Err(self.err(
                        range.span().start,
                        &format!("{field}.range"),
                        "expected two numbers [from, to] with from < to",
                    ));
                }
                let samples = rp.samples.as_ref().map_or(Ok(7), |n| {
                    usize::try_from(*n.get_ref())
                        .ok()
                        .filter(|k| (2..=1000).contains(k))
                        .ok_or_else(|| {
                            self.err(
                                n.span().start,
                                &format!("{field}.samples"),
                                "samples is a whole number from 2 to 1000",
                            )
                        })
                })?;
                PlotRequest::TensorSweep {
                    over: over.get_ref().clone(),
                    from: ends[0],
                    to: ends[1],
                    samples,
                }
            }
            "convergence" => PlotRequest::Convergence,
            "principal-axes" => PlotRequest::PrincipalAxes,
            other => {
                return Err(self.err(
                    content_start(&rp.kind),
                    &format!("{field}.kind"),
                    format!(
                        "unknown plot kind `{other}`; expected one of: {}",
                        PlotRequest::KINDS.join(", ")
                    ),
                ));
            }
        };
        if sweep_fields && !matches!(request, PlotRequest::TensorSweep { .. }) {
            return Err(self.err(
                start,
                field,
                format!(
                    "`over`, `range` and `samples` belong to a tensor-sweep, not a {}",
                    request.kind()
                ),
            ));
        }
        Ok(request)
    }

    fn claim_expr(
        &self,
        t: &Text,
        field: &str,
        names: &BTreeSet<String>,
    ) -> Result<Expr, SceneError> {
        self.parse_checked(t.get_ref(), content_start(t), field, names, true)
    }

    fn body(
        &self,
        b: &Spanned<RawBody>,
        field: &str,
        allowed: &BTreeSet<String>,
    ) -> Result<Body, SceneError> {
        let start = b.span().start;
        let rb = b.get_ref();
        let kind = rb.kind.get_ref().as_str();
        let req = |t: &Option<Text>, name: &str| -> Result<Expr, SceneError> {
            match t {
                Some(t) => self.expr(t, &format!("{field}.{name}"), allowed),
                None => Err(self.err(
                    start,
                    &format!("{field}.{name}"),
                    format!("missing field `{name}` for a {kind}"),
                )),
            }
        };
        // Fields that do not apply to this kind are errors, not silently ignored.
        let present: Vec<(&str, bool)> = vec![
            ("size", rb.size.is_some()),
            ("radius", rb.radius.is_some()),
            ("length", rb.length.is_some()),
            ("height", rb.height.is_some()),
            ("origin", rb.origin.is_some()),
            ("along", rb.along.is_some()),
            ("points", !rb.points.is_empty()),
            ("mass", rb.mass.is_some()),
        ];
        let applies: &[&str] = match kind {
            "box" => &["size", "origin", "mass"],
            "rod" => &["length", "along", "origin", "mass"],
            "hoop" | "ring" | "disk" | "sphere" | "shell" => &["radius", "mass"],
            "cylinder" => &["radius", "height", "mass"],
            "points" => &["points"],
            other => {
                return Err(self.err(content_start(&rb.kind), &format!("{field}.kind"), format!("unknown body kind `{other}`; expected box, rod, hoop, ring, disk, cylinder, sphere, shell or points")));
            }
        };
        if let Some((name, _)) = present.iter().find(|(n, p)| *p && !applies.contains(n)) {
            return Err(self.err(
                start,
                &format!("{field}.{name}"),
                format!("field `{name}` does not apply to a {kind}"),
            ));
        }
        let origin = |choices: [&str; 2]| -> Result<bool, SceneError> {
            match &rb.origin {
                None => Ok(false),
                Some(o) if o.get_ref() == choices[0] => Ok(false),
                Some(o) if o.get_ref() == "centre" || o.get_ref() == "center" => Ok(true),
                Some(o) => Err(self.err(
                    content_start(o),
                    &format!("{field}.origin"),
                    format!("expected `{}` or `centre`", choices[0]),
                )),
            }
        };
        let shape = match kind {
            "box" => {
                let Some(size) = &rb.size else {
                    return Err(self.err(
                        start,
                        &format!("{field}.size"),
                        "missing field `size` for a box",
                    ));
                };
                Shape::Box {
                    size: self.vec3(size, &format!("{field}.size"), allowed)?,
                    centred: origin(["corner", "centre"])?,
                }
            }
            "rod" => {
                let along = match rb.along.as_ref().map(|a| a.get_ref().as_str()) {
                    None | Some("z") => Axis::Z,
                    Some("x") => Axis::X,
                    Some("y") => Axis::Y,
                    Some(_) => {
                        return Err(self.err(
                            content_start(rb.along.as_ref().unwrap()),
                            &format!("{field}.along"),
                            "expected x, y or z",
                        ));
                    }
                };
                Shape::Rod {
                    length: req(&rb.length, "length")?,
                    along,
                    centred: origin(["end", "centre"])?,
                }
            }
            "hoop" | "ring" => Shape::Hoop {
                radius: req(&rb.radius, "radius")?,
            },
            "disk" => Shape::Disk {
                radius: req(&rb.radius, "radius")?,
            },
            "cylinder" => Shape::Cylinder {
                radius: req(&rb.radius, "radius")?,
                height: req(&rb.height, "height")?,
            },
            "sphere" => Shape::Sphere {
                radius: req(&rb.radius, "radius")?,
            },
            "shell" => Shape::Shell {
                radius: req(&rb.radius, "radius")?,
            },
            _ => {
                if rb.points.is_empty() {
                    return Err(self.err(
                        start,
                        &format!("{field}.points"),
                        "a point set needs at least one [[body.points]]",
                    ));
                }
                let mut pts = Vec::new();
                for (j, p) in rb.points.iter().enumerate() {
                    let f = format!("{field}.points[{j}]");
                    pts.push((
                        self.expr(&p.get_ref().mass, &format!("{f}.mass"), allowed)?,
                        self.vec3(&p.get_ref().at, &format!("{f}.at"), allowed)?,
                    ));
                }
                Shape::Points(pts)
            }
        };
        let mass = match &shape {
            Shape::Points(pts) => Expr::add(pts.iter().map(|(m, _)| m.clone()).collect()),
            _ => req(&rb.mass, "mass")?,
        };
        let mut rotations = Vec::new();
        for (j, r) in rb.rotate.iter().enumerate() {
            let f = format!("{field}.rotate[{j}]");
            let axis = match r.get_ref().axis.get_ref().as_str() {
                "x" => Axis::X,
                "y" => Axis::Y,
                "z" => Axis::Z,
                _ => {
                    return Err(self.err(
                        content_start(&r.get_ref().axis),
                        &format!("{f}.axis"),
                        "expected x, y or z",
                    ));
                }
            };
            rotations.push((
                axis,
                self.expr(&r.get_ref().angle, &format!("{f}.angle"), allowed)?,
            ));
        }
        let shift = match &rb.shift {
            Some(s) => self.vec3(s, &format!("{field}.shift"), allowed)?,
            None => [Expr::int(0), Expr::int(0), Expr::int(0)],
        };
        Ok(Body {
            label: rb.label.clone().unwrap_or_else(|| shape.kind().to_string()),
            shape,
            mass,
            rotations,
            shift,
        })
    }

    /// Sizes and masses must be positive and finite at the scene's numeric values.
    fn check_positive(
        &self,
        rb: &RawBody,
        field: &str,
        values: &BTreeMap<String, f64>,
    ) -> Result<(), SceneError> {
        let env = |s: &str| values.get(s).copied();
        let mut checks: Vec<(&Text, String)> = Vec::new();
        if let Some(m) = &rb.mass {
            checks.push((m, format!("{field}.mass")));
        }
        for (name, t) in [
            ("radius", &rb.radius),
            ("length", &rb.length),
            ("height", &rb.height),
        ] {
            if let Some(t) = t {
                checks.push((t, format!("{field}.{name}")));
            }
        }
        if let Some(size) = &rb.size {
            for (i, t) in size.get_ref().iter().enumerate() {
                checks.push((t, format!("{field}.size[{i}]")));
            }
        }
        for (j, p) in rb.points.iter().enumerate() {
            checks.push((&p.get_ref().mass, format!("{field}.points[{j}].mass")));
        }
        for (t, f) in checks {
            let e = parse_expr(t.get_ref()).expect("validated").expr;
            let v = e
                .eval(&env)
                .map_err(|m| self.err(content_start(t), &f, m))?;
            if !(v.is_finite() && v > 0.0) {
                return Err(self.err(
                    content_start(t),
                    &f,
                    format!("must be positive and finite, but is {v} at the scene's values"),
                ));
            }
        }
        Ok(())
    }
}

/// Checks that every call names a known function with the right number of arguments.
fn check_calls(e: &Expr, claim_language: bool) -> Result<(), String> {
    let mut result = Ok(());
    let allowed: &[&str] = if claim_language {
        CLAIM_FUNCTIONS
    } else {
        crate::cas::SCALAR_FUNCTIONS
    };
    fn walk(e: &Expr, allowed: &[&str], claim: bool, out: &mut Result<(), String>) {
        match e {
            Expr::Call(name, args) => {
                if !allowed.contains(&name.as_str()) {
                    *out = Err(format!("unknown function `{name}`"));
                    return;
                }
                let arity = match name.as_str() {
                    "dot" | "cross" | "outer" | "diff" => 2,
                    "diag" | "subs" => 3,
                    "eye" => 0,
                    _ => 1,
                };
                if name != "eye" && args.len() != arity {
                    *out = Err(format!(
                        "`{name}` takes {arity} argument(s), got {}",
                        args.len()
                    ));
                }
                args.iter().for_each(|a| walk(a, allowed, claim, out));
            }
            Expr::List(v) | Expr::Add(v) | Expr::Mul(v) => {
                if !claim && matches!(e, Expr::List(_)) {
                    *out = Err("a list is not allowed here".into());
                }
                v.iter().for_each(|a| walk(a, allowed, claim, out));
            }
            Expr::Index(a, b) => {
                if !claim {
                    *out = Err("indexing is not allowed here".into());
                }
                walk(a, allowed, claim, out);
                walk(b, allowed, claim, out);
            }
            Expr::Pow(a, b) => {
                walk(a, allowed, claim, out);
                walk(b, allowed, claim, out);
            }
            Expr::Num(_) | Expr::Sym(_) => {}
        }
    }
    walk(e, allowed, claim_language, &mut result);
    result
}

fn body_symbols(b: &Body) -> BTreeSet<String> {
    let mut exprs: Vec<&Expr> = vec![&b.mass];
    exprs.extend(b.shift.iter());
    exprs.extend(b.rotations.iter().map(|(_, a)| a));
    match &b.shape {
        Shape::Box { size, .. } => exprs.extend(size.iter()),
        Shape::Rod { length, .. } => exprs.push(length),
        Shape::Hoop { radius }
        | Shape::Disk { radius }
        | Shape::Sphere { radius }
        | Shape::Shell { radius } => exprs.push(radius),
        Shape::Cylinder { radius, height } => exprs.extend([radius, height]),
        Shape::Points(pts) => pts.iter().for_each(|(m, at)| {
            exprs.push(m);
            exprs.extend(at.iter());
        }),
    }
    exprs.iter().flat_map(|e| e.symbols()).collect()
}

#[cfg(test)]
mod tests;
