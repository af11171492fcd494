//! What a validated scene holds: its bodies, claims, plots and requests.

use crate::cas::Expr;
use crate::model::catalogue::Output;
use crate::model::fidelity::Fidelity;
use crate::model::units::Unit;
use crate::scene::step::AuthorStep;
pub use crate::scene::verdict::{ClaimRole, Verdict};
use std::collections::{BTreeMap, BTreeSet};
use std::path::PathBuf;

#[derive(Debug, Clone)]
pub struct Scene {
    pub id: String,
    pub title: String,
    /// What the scene's author should look at but may leave: ASCII mathematics in its prose,
    /// each at its place (`check` and `build` print them).
    pub warnings: Vec<crate::scene::error::SceneError>,
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
    /// The symbols and the coordinates in the order the file declares them: the order of a
    /// printed product's factors (M g l where the author declares M, g, l).
    pub declared: crate::cas::Declared,
    /// Abbreviations used in claims, such as `lambda = M/(2*pi*R)`.
    pub definitions: BTreeMap<String, Expr>,
    pub vectors: BTreeMap<String, [Expr; 3]>,
    pub omega: Option<[Expr; 3]>,
    pub axis: Option<[Expr; 3]>,
    pub bodies: Vec<Body>,
    pub claims: Vec<Claim>,
    /// Generalised coordinate -> its meaning.
    pub coordinates: BTreeMap<String, String>,
    /// The author's own derivation, in order.
    pub steps: Vec<AuthorStep>,
    pub wants: Vec<Output>,
    pub plots: Vec<PlotRequest>,
    /// The line of each `[expect]` key, for a changed result's message.
    pub expect_lines: BTreeMap<String, usize>,
    /// Where each plot's `[[plot]]` starts (line, column), for errors about it.
    pub plot_at: Vec<(usize, usize)>,
    pub values: BTreeMap<String, f64>,
    pub seed: u64,
    /// `[numeric] fidelity`: this scene's default, which `--fidelity` overrides.
    pub fidelity: Option<Fidelity>,
    /// Recorded results: quantity name -> expected exact value (the regression record).
    pub expect: BTreeMap<String, Expr>,
    /// Each author's step's results as `check --bless` recorded them under its name in
    /// `[expect]`, by the step's name.
    pub step_records: BTreeMap<String, RecordedStep>,
    /// Step key -> how this course's notes cite it, such as `eq (51)`.
    pub cite: BTreeMap<String, String>,
    /// A problem for students, with its variants.
    pub problem: Option<Problem>,
    /// `[outputs] inertia = "principal"`: `symmetric_top` takes I1 = I2 and I3 from the
    /// bodies' moments about their centre of mass, not from symbols.
    pub moments_from_bodies: bool,
    /// `[expect] variants`: the problem's variants as `check --bless` recorded them (one
    /// hash each, in order), and the key's line.
    pub pinned_variants: Option<(Vec<String>, usize)>,
    /// The declared units of symbols and coordinates; a name without one is not checked.
    pub units: BTreeMap<String, Unit>,
    /// How symbols and coordinates are typeset when the scene says (`tex = "\\Omega"`), as
    /// LaTeX that has been read at load.
    pub tex: BTreeMap<String, String>,
    /// `assume`: the physics' domain, each inequality `smaller < larger`.
    pub assumptions: Vec<Assumption>,
}

/// One inequality of a scene's domain: `smaller < larger` (a `<=` is taken as `<`: the random
/// points never land on the boundary, and the engine's signs are strict).
#[derive(Debug, Clone, PartialEq)]
pub struct Assumption {
    pub smaller: Expr,
    pub larger: Expr,
    /// As the author wrote it, for messages.
    pub text: String,
    pub line: usize,
}

/// A problem: a statement whose `{symbol}` placeholders each variant fills in, and the derived
/// quantities that answer it.
#[derive(Debug, Clone)]
pub struct Problem {
    pub statement: String,
    /// The symbols the statement names, each once, in the order it first names them.
    pub given: Vec<String>,
    pub answers: Vec<Answer>,
    /// A Moodle answer's tolerance, relative to the answer.
    pub tolerance: f64,
    pub variants: Vec<Variant>,
    /// Where `[problem]` is (line, column), for errors found when its variants are derived.
    pub at: (usize, usize),
}

/// One answer of a problem: a derived quantity, a named step, or an expression of them and of
/// the scene's symbols, with the words and unit a student sees.
#[derive(Debug, Clone)]
pub struct Answer {
    pub value: Expr,
    /// As the author wrote it: the catalogue's name for a bare quantity.
    pub written: String,
    /// The author's words for it; a bare quantity has the catalogue's own.
    pub label: Option<String>,
    pub unit: Option<Unit>,
    /// A quiz answer's tolerance, relative to the answer.
    pub tolerance: f64,
    pub line: usize,
}

impl Answer {
    /// The catalogue quantity it is, when it is one by itself (the 7 answers of old).
    pub fn bare_quantity(&self) -> Option<&str> {
        match &self.value {
            Expr::Sym(s) if crate::model::catalogue::ANSWERS.iter().any(|(q, _)| q == s) => Some(s),
            _ => None,
        }
    }
}

/// One variant of a problem: every symbol with a value, exactly.
#[derive(Debug, Clone, PartialEq)]
pub struct Variant {
    /// 1-based.
    pub number: usize,
    pub values: BTreeMap<String, Expr>,
    /// The names whose values the author wrote in decimals: shown so where they end.
    pub decimal: BTreeSet<String>,
}

impl Variant {
    /// Eight hex digits of a hash of its values (names and exact values in name order): what
    /// a student's sheet holds, recorded by `check --bless` to pin it.
    pub fn pin(&self) -> String {
        let text: String = self
            .values
            .iter()
            .map(|(name, value)| format!("{name}={};", value.to_text()))
            .collect();
        format!(
            "{:08x}",
            crate::base::hash::content_hash(text.as_bytes()) >> 32
        )
    }

    /// The values in f64 (π known), for the numeric routes.
    pub fn numbers(&self) -> BTreeMap<String, f64> {
        self.values
            .iter()
            .map(|(k, e)| (k.clone(), e.eval(&|_| None).unwrap_or(f64::NAN)))
            .collect()
    }

    /// [`Variant::numbers`], with the whole turns taken off, exactly, the value qπ of each of
    /// `angles` (the scene's [`Scene::whole_turn_symbols`]): f64 has no digit of the π/6 in
    /// 1e20·π + π/6 left.
    pub fn numbers_within_a_turn(&self, angles: &BTreeSet<String>) -> BTreeMap<String, f64> {
        let mut out = self.numbers();
        for name in angles {
            let turn = self
                .values
                .get(name)
                .and_then(crate::cas::pi_multiple)
                .map(|q| q.rem_euclid(&crate::cas::Rational::int(2)));
            if let Some(q) = turn {
                out.insert(name.clone(), q.to_f64() * std::f64::consts::PI);
            }
        }
        out
    }
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
    /// Signed mass: negative for a hole (`subtract = true`), whose removed mass is its negation.
    /// For point sets, the sum of the (signed) point masses.
    pub mass: Expr,
    /// A hole: material removed from the bodies before it.
    pub subtract: bool,
    /// Applied in order to the body's own coordinates, then `shift`.
    pub rotations: Vec<(Axis, Expr)>,
    pub shift: [Expr; 3],
    /// The names of its integration variables in this scene, in the order of
    /// [`Shape::variables`]: the shape's own, or `r_1` when the scene has a name `r` of its own.
    pub variables: Vec<String>,
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
    /// A thin rectangle [0,a]×[0,b] in the xy-plane, or centred.
    Plate {
        size: [Expr; 2],
        centred: bool,
    },
    /// A thin uniform disk in the xy-plane, centred; an annulus when `inner` is given.
    Disk {
        radius: Expr,
        inner: Option<Expr>,
    },
    /// A solid cylinder about z, centred; a tube when `inner` is given.
    Cylinder {
        radius: Expr,
        height: Expr,
        inner: Option<Expr>,
    },
    /// A solid ball, centred; a thick shell when `inner` is given.
    Sphere {
        radius: Expr,
        inner: Option<Expr>,
    },
    /// A solid cone about z of base radius R and height h.
    Cone {
        radius: Expr,
        height: Expr,
        origin: ConeOrigin,
    },
    /// A solid half ball, its dome towards +z; the origin at the flat face's centre, or at the
    /// centre of mass (3R/8 above the face).
    Hemisphere {
        radius: Expr,
        centred: bool,
    },
    /// A thin spherical shell.
    Shell {
        radius: Expr,
    },
    Points(Vec<(Expr, [Expr; 3])>),
}

/// A step's result recorded where none was derived (an Ω² beyond the engine's budget).
pub const NOT_DERIVED: &str = "not derived";

/// A step's results as recorded in `[expect]`: each as written (an exact form, the number of a
/// numeric result, or [`NOT_DERIVED`]), and the line of its key.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordedStep {
    pub values: Vec<String>,
    pub line: usize,
}

impl Scene {
    /// The fidelity a run uses: the command line's (`--fidelity`), else the scene's own, else
    /// standard. The one place this rule is written.
    pub fn fidelity_given(&self, command_line: Option<Fidelity>) -> Fidelity {
        command_line.or(self.fidelity).unwrap_or_default()
    }
}

impl Body {
    /// The mass and the lengths that size the body (not its placement), as written.
    pub fn dimensions(&self) -> Vec<&Expr> {
        let mut out = vec![&self.mass];
        match &self.shape {
            Shape::Box { size, .. } => out.extend(size.iter()),
            Shape::Plate { size, .. } => out.extend(size.iter()),
            Shape::Rod { length, .. } => out.push(length),
            Shape::Hoop { radius } | Shape::Shell { radius } | Shape::Hemisphere { radius, .. } => {
                out.push(radius)
            }
            Shape::Disk { radius, inner } | Shape::Sphere { radius, inner } => {
                out.push(radius);
                out.extend(inner);
            }
            Shape::Cylinder {
                radius,
                height,
                inner,
            } => {
                out.extend([radius, height]);
                out.extend(inner);
            }
            Shape::Cone { radius, height, .. } => out.extend([radius, height]),
            Shape::Points(pts) => out.extend(pts.iter().map(|(m, _)| m)),
        }
        out
    }
}

impl Shape {
    pub fn kind(&self) -> &'static str {
        match self {
            Shape::Box { .. } => "box",
            Shape::Rod { .. } => "rod",
            Shape::Hoop { .. } => "hoop",
            Shape::Plate { .. } => "plate",
            Shape::Disk { .. } => "disk",
            Shape::Cylinder { .. } => "cylinder",
            Shape::Sphere { .. } => "sphere",
            Shape::Shell { .. } => "shell",
            Shape::Cone { .. } => "cone",
            Shape::Hemisphere { .. } => "hemisphere",
            Shape::Points(_) => "points",
        }
    }

    /// The names of the shape's integration variables; a body takes others where the scene
    /// uses these (`Body::variables`).
    pub fn variables(&self) -> &'static [&'static str] {
        match self {
            Shape::Box { .. } => &["x", "y", "z"],
            Shape::Rod { .. } => &["s"],
            Shape::Hoop { .. } => &["theta"],
            Shape::Plate { .. } => &["x", "y"],
            Shape::Disk { .. } => &["r", "theta"],
            Shape::Cylinder { .. } => &["r", "theta", "z"],
            Shape::Sphere { .. } => &["r", "theta", "phi"],
            Shape::Shell { .. } => &["theta", "phi"],
            Shape::Cone { .. } => &["s", "theta", "z"],
            Shape::Hemisphere { .. } => &["r", "theta", "phi"],
            Shape::Points(_) => &[],
        }
    }
}

/// Where a cone's own origin sits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConeOrigin {
    /// The apex at the origin, the base at z = h.
    Apex,
    /// The base's centre at the origin, the apex at z = h.
    Base,
    /// The centre of mass at the origin (h/4 above the base), the apex at z = 3h/4.
    Centre,
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
    /// The reviewed verdict; `None` until one is recorded (`check` fails until then, and
    /// `check --bless` records the derived one).
    pub expect: Option<Verdict>,
    pub role: ClaimRole,
    /// The symbol its quantity is printed as, where the author gives one: its LaTeX read.
    pub tex: Option<crate::notation::Tex>,
    pub line: usize,
}

/// A plot a scene asks for; `figures` draws it from the numbers `numeric` computes.
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
        inertia: FreeInertia,
        omega: [f64; 3],
        t: f64,
    },
    /// An author's equations of motion integrated from `start` to `t`, each coordinate against
    /// time, with a step's linear equations from the same start beside them.
    Motion {
        step: String,
        linear: Option<String>,
        start: BTreeMap<String, f64>,
        t: f64,
    },
    /// A step's expression against a coordinate or a symbol (an effective potential against
    /// its angle): the exact result as a curve, with a second route at sample values.
    Expression {
        step: String,
        over: String,
        from: f64,
        to: f64,
        samples: usize,
        at: BTreeMap<String, f64>,
    },
}

/// A free-body plot's principal moments: given, or those of the scene's own bodies about their
/// centre of mass (known only once the tensor is derived).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FreeInertia {
    Given([f64; 3]),
    Principal,
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
        "motion",
        "expression",
    ];

    pub fn kind(&self) -> &'static str {
        match self {
            PlotRequest::TensorSweep { .. } => "tensor-sweep",
            PlotRequest::Convergence => "convergence",
            PlotRequest::PrincipalAxes => "principal-axes",
            PlotRequest::FreeBody { kind, .. } => kind.name(),
            PlotRequest::Motion { .. } => "motion",
            PlotRequest::Expression { .. } => "expression",
        }
    }

    pub fn is_free_body(&self) -> bool {
        matches!(self, PlotRequest::FreeBody { .. })
    }

    /// Plots of a body's tensor need a `[[body]]`; free-body plots carry their own, unless they
    /// take the principal moments of the scene's body.
    pub fn needs_body(&self) -> bool {
        !matches!(
            self,
            PlotRequest::FreeBody {
                inertia: FreeInertia::Given(_),
                ..
            } | PlotRequest::Motion { .. }
                | PlotRequest::Expression { .. }
        )
    }
}

/// "3/4" -> "lecture-3-4": the file name of a lecture's handouts.
pub fn lecture_slug(name: &str) -> String {
    let clean: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect();
    format!("lecture-{}", clean.trim_matches('-'))
}
