//! Symbolic derivations as ordered steps. Each step is a statement in our own expression type
//! plus a one-line justification, so a reader sees how a result is reached.
//!
//! Nothing here is looked up in a table of answers: every result comes out of an integral, a
//! product, a determinant or a factorisation computed by the engine.

pub mod algebra;
pub mod bodies;
mod body_moments;
pub mod constraints;
pub mod earth;
pub mod euler;
pub mod free_top;
pub(crate) mod inertia;
mod kinematics;
pub mod lagrangian;
pub mod modes;
pub mod poinsot;
pub mod present;
mod principal;
pub mod rest_states;
pub mod result_order;
pub mod sign;
pub(crate) mod solve;
pub mod stability;
pub mod step_names;
mod step_result;
pub(crate) mod undefined;
pub mod variants;

pub use principal::{CubicRoots, ExactBasis, ExactEigen, ExactSpace, LAMBDA};

use crate::cas::{self, CasError, DiffError, EvalError, Expr};
use crate::model::catalogue::quantity;
use crate::model::catalogue::{self, Stage};
use crate::model::prose::Prose;
use crate::notation::Formula;
use crate::plan::Plan;
use crate::scene::Scene;
use algebra::Value;
use std::collections::BTreeMap;

#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct Step {
    /// The step's heading: words, and its formulas as trees (an author's `$…$` read once).
    pub title: Prose,
    /// What the step finds, as a formula each output prints with its own printer.
    pub statement: Formula,
    /// Why it follows, in one line, in general terms: no course's equation numbers.
    pub why: Prose,
    /// The key by which a scene's `[cite]` table names its own notes' equations for this step.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub cite: String,
    /// The author's `[[step]]` this shows, by name; `None` for a built-in step.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub author: Option<String>,
    /// The exact result as derived, where `statement` prints it in another form (see
    /// `cas::present_all`): kept for `--json`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exact: Option<Formula>,
    /// A step that checks an earlier one by another route (the definition against the tensor):
    /// the instructor's handout shows it, the student's leaves it out.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub second_route: bool,
    /// A step of the working a student's summary leaves out (a body's integrals, a
    /// characteristic polynomial that does not factor): the instructor's handout shows it.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub working: bool,
    /// For an author's step: the result this line states, which the build checks it shows.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stands_for: Option<step_names::StandsFor>,
    /// The reason a student's summary gives, where it says less than `why` (the roots set
    /// aside as real for no values of the symbols are the instructor's working).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub student_why: Option<Prose>,
}

/// A step's reason, with the citation key a scene may map to its notes' equations.
pub struct Why {
    pub key: &'static str,
    pub prose: Prose,
}

/// A reason that a scene may cite: `[cite] key = "eq (51)"` prints "eq (51): text".
pub fn cited(key: &'static str, why: impl Into<Why>) -> Why {
    Why { key, ..why.into() }
}

impl From<Prose> for Why {
    fn from(prose: Prose) -> Why {
        Why { key: "", prose }
    }
}

/// A built-in reason as text, its mathematics in `$…$` as an author's is.
impl From<&str> for Why {
    fn from(text: &str) -> Why {
        Why::from(crate::model::prose::author(text))
    }
}

impl From<&String> for Why {
    fn from(text: &String) -> Why {
        Why::from(text.as_str())
    }
}

impl From<String> for Why {
    fn from(text: String) -> Why {
        Why::from(text.as_str())
    }
}

impl Step {
    /// `lhs = value`, with `lhs` in the notation of [`Formula::parse`].
    pub fn equation(title: &str, lhs: &str, value: &Value, why: impl Into<Why>) -> Step {
        let statement = Formula::equation(Formula::parse(lhs, &[]), value.to_expr());
        Step::note(title, statement, why)
    }

    /// A step headed by `title`, written as an author writes (its formulas in `$…$`).
    pub fn note(title: &str, statement: Formula, why: impl Into<Why>) -> Step {
        Step::titled(crate::model::prose::author(title), statement, why)
    }

    pub fn titled(title: Prose, statement: Formula, why: impl Into<Why>) -> Step {
        let why = why.into();
        Step {
            title,
            statement,
            why: why.prose,
            cite: why.key.to_string(),
            author: None,
            exact: None,
            second_route: false,
            working: false,
            stands_for: None,
            student_why: None,
        }
    }

    /// The step with the shorter reason a student's summary gives.
    pub fn for_students(self, why: Prose) -> Step {
        Step {
            student_why: Some(why),
            ..self
        }
    }

    /// The line as a statement of the result `s` (see [`step_names::StandsFor`]).
    pub fn standing_for(self, s: step_names::StandsFor) -> Step {
        Step {
            stands_for: Some(s),
            ..self
        }
    }

    /// The step as a second route to an earlier one.
    pub fn second_route(self) -> Step {
        Step {
            second_route: true,
            ..self
        }
    }

    /// The step as working that a student's summary leaves out.
    pub fn working(self) -> Step {
        Step {
            working: true,
            ..self
        }
    }

    /// The scene's citation for this step, if it has one: "eq (51)".
    pub fn citation<'a>(&self, cites: &'a BTreeMap<String, String>) -> Option<&'a str> {
        cites
            .get(&self.cite)
            .filter(|_| !self.cite.is_empty())
            .map(String::as_str)
    }
}

#[derive(Debug, thiserror::Error)]
pub enum DeriveError {
    #[error(transparent)]
    Cas(#[from] CasError),
    /// Two routes that must agree did not: a bug, never a property of the input.
    #[error("internal inconsistency: {0}")]
    Inconsistent(String),
    #[error("cannot decide the sign of `{expr}` for positive values of its symbols")]
    UndecidedSign { expr: String },
    #[error(transparent)]
    Eval(#[from] EvalError),
    #[error(transparent)]
    Diff(#[from] DiffError),
    /// Why an author's step cannot be derived, in words (wrapped in [`step_names::StepError`] with
    /// the step's name and line).
    #[error("{0}")]
    NotDerivable(String),
    /// An author's step that could not be derived, at its line.
    #[error(transparent)]
    Step(#[from] step_names::StepError),
    /// A stage read a quantity that an earlier stage should have set: a bug in the plan.
    #[error("internal inconsistency: quantity `{0}` was not derived")]
    Missing(&'static str),
    /// A problem asks for the principal moments of a tensor whose characteristic cubic does
    /// not factor: they have no exact form to grade.
    #[error(
        "the principal moments have no exact form here: the characteristic cubic does not \
         factor over the rationals, so there is nothing exact to grade; take \
         `principal_moments` out of the problem's answers (the worked solution gives the moments \
         in Viète's form), or ask for `inertia_tensor`"
    )]
    NoExactMoments,
    /// A problem's answer still has a symbol once a variant's values are in.
    #[error(
        "the answer `{quantity}` depends on `{symbol}`, which has no value: give it a range \
         under [variants] or a value under [numeric] values"
    )]
    NoVariantValue { quantity: String, symbol: String },
}

/// Everything the symbolic stage produced for a scene.
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub struct Derivation {
    pub steps: Vec<Step>,
    /// Exact results by name (`inertia_tensor`, `principal_moments`, ...), simplified.
    pub quantities: BTreeMap<String, Value>,
    /// Each body's own tensor about the frame origin, for the per-body numeric checks.
    pub part_tensors: Vec<Value>,
    pub eigen: Option<ExactEigen>,
    /// The results of the author's own steps, by the step's name.
    #[serde(default)]
    pub named: BTreeMap<String, step_names::StepResult>,
    /// The printed form of each step whose result a textbook writes otherwise (see
    /// `cas::present_all`), by the step's name; its check compares it with `named`.
    #[serde(default)]
    pub printed: BTreeMap<String, step_names::StepResult>,
    /// Each matrix quantity with a common factor to take out, as its page prints it
    /// (`present::present_matrices`).
    #[serde(default)]
    pub matrices: BTreeMap<String, crate::cas::MatrixForm>,
}

impl Derivation {
    /// The names of results that are numbers at the scene's values, with no exact form for a
    /// later step or a claim (`Omega_5` of a 6-coordinate `frequency`), and the step of each.
    pub fn numeric_names(&self, scene: &Scene) -> BTreeMap<String, String> {
        let mut out = BTreeMap::new();
        for (step, r) in &self.named {
            if let step_names::StepResult::NumericModes { frequencies, .. } = r {
                for k in 0..frequencies.len() {
                    out.insert(scene.result_names(step).kth(k), step.clone());
                }
            }
        }
        out
    }

    /// The first name in `e` whose result is numeric only, and its step.
    pub fn numeric_name_in(&self, scene: &Scene, e: &Expr) -> Option<(String, String)> {
        // Most derivations have no numeric modes: nothing to look up.
        if !self
            .named
            .values()
            .any(|r| matches!(r, step_names::StepResult::NumericModes { .. }))
        {
            return None;
        }
        let names = self.numeric_names(scene);
        e.symbols()
            .into_iter()
            .find_map(|s| names.get(&s).map(|step| (s.clone(), step.clone())))
    }

    /// Records a derived quantity: one in the catalogue, of its kind, and written once (two
    /// stages that wrote one name used to keep the last silently).
    fn set(&mut self, name: &str, value: Value) -> Result<(), DeriveError> {
        let entry = catalogue::find(name).ok_or_else(|| {
            DeriveError::Inconsistent(format!("quantity `{name}` is not in the catalogue"))
        })?;
        if entry.kind != value.kind_of() {
            return Err(DeriveError::Inconsistent(format!(
                "quantity `{name}` is {}, but the catalogue says {:?}",
                value.kind(),
                entry.kind
            )));
        }
        if self.quantities.contains_key(name) {
            return Err(DeriveError::Inconsistent(format!(
                "quantity `{name}` is derived twice"
            )));
        }
        self.quantities.insert(name.to_string(), value);
        Ok(())
    }

    /// A derived quantity by name; missing means a stage ran before the one that sets it.
    pub fn get(&self, name: &'static str) -> Result<&Value, DeriveError> {
        self.quantities.get(name).ok_or(DeriveError::Missing(name))
    }

    /// A derived scalar: [`Derivation::set`] keeps each quantity of its catalogued kind, so
    /// another kind is an internal inconsistency, never a panic.
    pub fn scalar(&self, name: &'static str) -> Result<&Expr, DeriveError> {
        match self.get(name)? {
            Value::Scalar(e) => Ok(e),
            other => Err(wrong_kind(name, other)),
        }
    }

    /// A derived vector.
    pub fn vector(&self, name: &'static str) -> Result<&algebra::Vec3, DeriveError> {
        match self.get(name)? {
            Value::Vector(v) => Ok(v),
            other => Err(wrong_kind(name, other)),
        }
    }

    /// A derived matrix.
    pub fn matrix(&self, name: &'static str) -> Result<&algebra::Mat3, DeriveError> {
        match self.get(name)? {
            Value::Matrix(m) => Ok(m),
            other => Err(wrong_kind(name, other)),
        }
    }

    /// A tensor about the frame's origin at `values` (exact or by quadrature) moved to the
    /// centre of mass, with the derived mass and centre there: I_cm = I − M(R²𝟙 − R Rᵀ).
    pub fn about_centre_at(
        &self,
        tensor: &nalgebra::Matrix3<f64>,
        values: &crate::model::value::Values,
    ) -> Result<nalgebra::Matrix3<f64>, DeriveError> {
        let m = crate::model::value::eval_at(self.scalar(quantity::MASS)?, values)?;
        let r = crate::model::value::vector_at(self.vector(quantity::CENTRE_OF_MASS)?, values)?;
        Ok(tensor - m * (r.norm_squared() * nalgebra::Matrix3::identity() - r * r.transpose()))
    }
}

/// A vector simplified entry by entry, with one engine call.
pub fn simplify_vec(v: &algebra::Vec3) -> Result<algebra::Vec3, CasError> {
    // One simplified entry per entry given.
    let s = cas::simplify_all(v.to_vec())?;
    Ok(std::array::from_fn(|i| s[i].clone()))
}

fn wrong_kind(name: &str, v: &Value) -> DeriveError {
    DeriveError::Inconsistent(format!("quantity `{name}` is {}", v.kind()))
}

/// A matrix simplified entry by entry, with one engine call.
pub fn simplify_mat(m: &algebra::Mat3) -> Result<algebra::Mat3, CasError> {
    let s = cas::simplify_all(m.iter().flatten().cloned().collect())?;
    Ok(std::array::from_fn(|i| {
        std::array::from_fn(|j| s[3 * i + j].clone())
    }))
}

/// Simplifies every entry of a value with one engine call.
pub fn simplify_value(v: &Value) -> Result<Value, CasError> {
    let entries = cas::simplify_all(v.entries())?;
    Ok(v.with_entries(&entries))
}

/// Every entry factored over the rationals, for display: (I1 − I3)(I2 − I3) reads better than
/// its expansion. Results are stored simplified, not factored.
pub fn factored(v: &Value) -> Result<Value, CasError> {
    let entries = cas::factor_all(v.entries())?;
    Ok(v.with_entries(&entries))
}

/// True when `a − b` is identically zero, entry by entry.
pub fn values_equal(a: &Value, b: &Value) -> Result<bool, CasError> {
    let diffs: Vec<Expr> = a
        .entries()
        .into_iter()
        .zip(b.entries())
        .map(|(x, y)| Expr::minus(x, y))
        .collect();
    Ok(cas::is_zero_all(diffs)?.into_iter().all(|z| z))
}

/// Runs the symbolic stages the plan asks for, in pipeline order.
pub fn derive(scene: &Scene, plan: &Plan) -> Result<Derivation, DeriveError> {
    let mut d = Derivation::default();
    if plan.runs(Stage::Tensor) && !scene.bodies.is_empty() {
        inertia::derive_tensor(scene, plan.runs(Stage::CentreOfMass), &mut d)?;
    }
    if plan.runs(Stage::ParallelAxis) {
        inertia::derive_parallel_axis(scene, &mut d)?;
    }
    if plan.runs(Stage::Principal) && d.quantities.contains_key(quantity::INERTIA_TENSOR) {
        principal::derive_principal(scene, &mut d)?;
    }
    if plan.runs(Stage::AngularMomentum) {
        kinematics::angular_momentum(scene, &mut d)?;
    }
    if plan.runs(Stage::KineticEnergy) {
        kinematics::kinetic_energy(scene, &mut d)?;
    }
    if plan.runs(Stage::MomentAboutAxis) {
        kinematics::moment_about_axis(scene, &mut d)?;
    }
    if plan.runs(Stage::Gyration) {
        kinematics::gyration(&mut d)?;
    }
    if plan.runs(Stage::EulerEquations) {
        euler::euler_equations(&mut d)?;
    }
    if plan.runs(Stage::SymmetricTop) {
        free_top::symmetric_top(&mut d)?;
    }
    if plan.runs(Stage::AxisStability) {
        stability::axis_stability(&mut d)?;
    }
    if plan.runs(Stage::Poinsot) {
        poinsot::poinsot(&mut d)?;
    }
    if scene.moments_from_bodies {
        body_moments::moments_from_bodies(&mut d)?;
    }
    if plan.runs(Stage::EarthPrecession) {
        earth::earth_precession(&mut d)?;
    }
    present::present_builtin_steps(&mut d, &scene.declared, &scene.claims)?;
    Ok(d)
}

#[cfg(test)]
mod bodies_tests;
#[cfg(test)]
mod body_moments_tests;
#[cfg(test)]
mod dynamics_tests;
#[cfg(test)]
mod rest_states_tests;
#[cfg(test)]
mod solve_tests;
#[cfg(test)]
mod tests;
