//! Dimensions checked everywhere a scene with units writes an expression: each step as
//! written and the form it `gives`, each claim against its quantity, and each answer against
//! its unit. The derived quantities carry the dimensions of the symbols they are derived from
//! (a tensor is mass × length²), so they need no table. A name without a unit is not checked.

use super::claim_env;
use crate::cas::{Expr, Rational};
use crate::derive::Derivation;
use crate::derive::algebra::evaluate;
use crate::derive::step_names::{StepResult, expand_names};
use crate::derive::variants::{general_answer, step_values};
use crate::model::catalogue::quantity_symbol;
use crate::model::prose::{Piece, Prose};
use crate::model::units::{Dimension, DimensionError, Measure, UNLIKE_SUM_ADVICE, measure_of};
use crate::model::value::Value;
use crate::notation::Formula;
use crate::scene::operations::{Be, Differentiate, Integrate, Series, Substitute};
use crate::scene::{Answer, Claim, Operation, Scene};

/// A dimension error at a line of the scene.
#[derive(Debug, thiserror::Error)]
#[error("{what}: {why}")]
pub struct DimensionFault {
    pub line: usize,
    pub what: String,
    pub why: String,
}

/// What a name measures: a symbol or coordinate by its unit, a rate by its coordinate's per
/// second, the time `t` in seconds unless the scene gives it a unit; anything else is not known.
fn names<'a>(scene: &'a Scene) -> impl Fn(&str) -> Option<Measure> + 'a {
    move |s: &str| {
        if let Some(unit) = scene.units.get(s) {
            return Some(Measure::of(unit));
        }
        if s == "t" {
            return Some(Measure::of(&crate::model::units::Unit::parse("s").ok()?));
        }
        if let Some(q) = s.strip_suffix("''") {
            return Some(names(scene)(q)?.per_second().per_second());
        }
        if let Some(q) = s.strip_suffix('\'') {
            return Some(names(scene)(q)?.per_second());
        }
        None
    }
}

/// The unit a result's number at the scene's values is in: a unit the scene declares of that
/// dimension and size (N/m, rad/s), else SI base units with whole powers (`m s^-2`); none where
/// a name in it has no unit, the number is not in coherent SI units (a length in cm times one
/// in m), or it is a pure number.
pub fn unit_of(scene: &Scene, e: &Expr) -> Option<String> {
    let m = measure(scene, e).ok()??;
    if m.dimension.is_none() {
        return None;
    }
    let declared = scene
        .units
        .values()
        .find(|u| u.dimension == m.dimension && u.scale == m.scale);
    match declared {
        Some(u) => Some(u.text.clone()),
        None if m.scale == Rational::ONE => m.dimension.base_units(),
        None => None,
    }
}

fn measure(scene: &Scene, e: &Expr) -> Result<Option<Measure>, DimensionError> {
    measure_of(e, &names(scene))
}

/// Every expression of the scene checked; the first fault, in the file's order of steps and
/// answers. A scene without units has nothing to check. Claims are not refused here: a claim
/// whose sides differ in dimension disagrees, with the reason beside it ([`claim_notes`]).
pub fn check_dimensions(scene: &Scene, d: &Derivation) -> Result<(), DimensionFault> {
    if scene.units.is_empty() {
        return Ok(());
    }
    // The bodies' tensor: a size given in a mass, say, shows as a sum of unlike terms.
    if let Some(tensor) = d
        .quantities
        .get(crate::model::catalogue::quantity::INERTIA_TENSOR)
    {
        for e in tensor.entries() {
            measure(scene, &e).map_err(|e| DimensionFault {
                line: scene.id_at.0,
                what: "the bodies' inertia tensor".into(),
                why: format!("{e}; check the bodies' sizes, positions and masses"),
            })?;
        }
    }
    for step in &scene.steps {
        let what = format!("step `{}`", step.name);
        let fault = |why: String| DimensionFault {
            line: step.line,
            what: what.clone(),
            why,
        };
        let written: Vec<&Expr> = match &step.op {
            Operation::Be(Be(e)) => vec![e],
            Operation::Differentiate(Differentiate { of, .. })
            | Operation::Integrate(Integrate { of, .. }) => vec![of],
            Operation::Series(Series { of, .. }) => vec![of],
            _ => vec![],
        };
        for e in written {
            if let Ok(x) = expand_names(scene, d, step, e) {
                measure(scene, &x).map_err(|e| fault(e.to_string()))?;
            }
        }
        let Some(gives) = &step.gives else { continue };
        let Ok(notes) = expand_names(scene, d, step, gives) else {
            continue;
        };
        let stated = measure(scene, &notes).map_err(|e| fault(format!("`gives`: {e}")))?;
        if let (Some(stated), Some(StepResult::Expr(result))) = (stated, d.named.get(&step.name))
            && let Ok(Some(derived)) = measure(scene, result)
            && stated.dimension != derived.dimension
            && !notes.is_zero()
        {
            return Err(fault(format!(
                "`gives` is in {}, but the step's result is in {}: they differ by {}; check \
                 `gives`, or the symbols' units",
                stated.dimension,
                derived.dimension,
                stated.dimension.over(&derived.dimension)
            )));
        }
    }
    if let Some(problem) = &scene.problem {
        let steps = step_values(scene, d);
        for a in &problem.answers {
            if let Ok(general) = general_answer(scene, d, &steps, a) {
                answer_scale(scene, a, &general)?;
            }
        }
    }
    Ok(())
}

/// Why a claim's two sides differ in dimension: the dimensions, with the quantity that has the
/// derived one, so that a page can print it as its symbol (I_xz, never `inertia_tensor[0][2]`).
#[derive(Debug, Clone, PartialEq)]
pub enum Mismatch {
    /// The claim's value is in one dimension, its quantity in another.
    Sides(Box<Sides>),
    /// The claim's value cannot be measured (a sum of unlike terms).
    Value(DimensionError),
}

/// The claim's value is in `stated`, but `quantity` is in `derived`.
#[derive(Debug, Clone, PartialEq)]
pub struct Sides {
    pub stated: Dimension,
    pub quantity: Expr,
    pub derived: Dimension,
    pub ratio: Dimension,
}

impl Mismatch {
    /// In words, the quantity as the author wrote it (for `check` and `--json`).
    pub fn text(&self) -> String {
        match self {
            Mismatch::Sides(s) => format!(
                "the claim's value is in {}, but `{}` is in {}: they differ by {}",
                s.stated,
                s.quantity.to_text(),
                s.derived,
                s.ratio
            ),
            Mismatch::Value(why) => why.to_string(),
        }
    }

    /// As a page says it: the quantity by its symbol in the scene's names (I_xz, never
    /// `inertia_tensor[0][2]`). A name with no symbol stays as the author wrote it: set as a
    /// word it reads no better.
    /// `symbol` is the claim's own for its quantity (`tex = "d^{2}"`), which names it first.
    pub fn said(
        &self,
        names: &crate::notation::Names,
        symbol: Option<&crate::notation::Tex>,
    ) -> Prose {
        // A name with no symbol prints as a word: set as mathematics it reads no better.
        let has_word = |e: &Expr| {
            e.symbols().iter().any(|s| {
                quantity_symbol(s).is_none()
                    && crate::cas::prints_as_word(s, &|n| names.typesets(n))
            })
        };
        let math = |e: &Expr| Piece::Math(Formula::Tex(e.to_tex_named(names, &quantity_symbol)));
        let said = |pieces: Vec<Piece>| {
            Prose::default()
                .run_on("the two sides differ in dimension: ")
                .then(Prose(pieces))
        };
        let plain = || said(vec![Piece::Text(self.text())]);
        match self {
            Mismatch::Sides(sides) => {
                let Sides {
                    stated,
                    quantity,
                    derived,
                    ratio,
                } = sides.as_ref();
                let quantity = match symbol {
                    Some(tex) => Piece::Math(Formula::Tex(tex.clone())),
                    None if has_word(quantity) => return plain(),
                    None => math(quantity),
                };
                said(vec![
                    Piece::Text("the claim's value is in ".into()),
                    unit(stated),
                    Piece::Text(", but ".into()),
                    quantity,
                    Piece::Text(" is in ".into()),
                    unit(derived),
                    Piece::Text(": they differ by ".into()),
                    unit(ratio),
                ])
            }
            // The notes' value adds unlike terms: each term set as a formula, in its unit.
            Mismatch::Value(DimensionError::UnlikeSum(terms))
                if !has_word(&terms.left) && !has_word(&terms.right) =>
            {
                said(vec![
                    math(&terms.left),
                    Piece::Text(" is in ".into()),
                    unit(&terms.left_dim),
                    Piece::Text(" but ".into()),
                    math(&terms.right),
                    Piece::Text(" is in ".into()),
                    unit(&terms.right_dim),
                    Piece::Text(format!(": {UNLIKE_SUM_ADVICE}")),
                ])
            }
            Mismatch::Value(_) => plain(),
        }
    }
}

/// A dimension set as its unit is (kg⁻¹ m⁻²); a pure number in words.
fn unit(d: &Dimension) -> Piece {
    match d.formula() {
        Some(f) => Piece::Math(f),
        None => Piece::Text(d.to_string()),
    }
}

/// Why a claim's two sides differ in dimension, if they do (its value's own unlike sum
/// included).
fn claim_mismatch(scene: &Scene, env: &crate::derive::algebra::Env, c: &Claim) -> Option<Mismatch> {
    let (Some(q), Some(v)) = (&c.quantity, &c.value) else {
        return None;
    };
    let (Ok(q), Ok(v)) = (evaluate(q, env), evaluate(v, env)) else {
        return None;
    };
    for (derived, stated) in q.entries().iter().zip(v.entries()) {
        let stated_m = match measure(scene, &stated) {
            Ok(m) => m,
            Err(e) => return Some(Mismatch::Value(e)),
        };
        if let (Ok(Some(derived_m)), Some(stated_m)) = (measure(scene, derived), stated_m)
            && derived_m.dimension != stated_m.dimension
            && !stated.is_zero()
            && !derived.is_zero()
        {
            return Some(Mismatch::Sides(Box::new(Sides {
                ratio: stated_m.dimension.over(&derived_m.dimension),
                stated: stated_m.dimension,
                quantity: c.quantity.clone()?,
                derived: derived_m.dimension,
            })));
        }
    }
    None
}

/// The claims whose sides differ in dimension, by line, each with why: such a claim
/// disagrees, and the reason is a line of its erratum.
pub fn claim_notes(scene: &Scene, d: &Derivation) -> Vec<(usize, Mismatch)> {
    if scene.units.is_empty() {
        return Vec::new();
    }
    let env = claim_env(scene, d);
    scene
        .claims
        .iter()
        .filter_map(|c| Some((c.line, claim_mismatch(scene, &env, c)?)))
        .collect()
}

/// Whether a unit counts cycles: `Hz`, `kHz`, `MHz`, alone or in a product.
fn in_hertz(unit: &crate::model::units::Unit) -> bool {
    unit.text
        .split(|c: char| c.is_whitespace() || c == '/' || c == '*' || c == '^')
        .any(|t| t.ends_with("Hz"))
}

/// The name through which `e` is an angular frequency, if it is one: a `frequency` step's
/// result, a name whose unit is in radians per second, or a step whose expression holds one of
/// those without a π (which ω/(2π) has). Radians are dimensionless in SI, so the dimension
/// check alone takes rad/s for Hz and would publish ω as a frequency 2π times too large.
fn angular_name(scene: &Scene, e: &Expr) -> Option<String> {
    let mut angular: Vec<String> = scene
        .units
        .iter()
        .filter(|(_, u)| {
            u.text.contains("rad") && u.dimension == Dimension::time().power(&Rational::int(-1))
        })
        .map(|(n, _)| n.clone())
        .collect();
    for step in &scene.steps {
        let through = |x: &Expr| {
            let names = x.symbols();
            !names.iter().any(|n| n == "pi") && names.iter().any(|n| angular.contains(n))
        };
        let is_angular = match &step.op {
            Operation::Frequency(_) => true,
            Operation::Be(Be(x)) => through(x),
            Operation::Substitute(Substitute { of, .. }) => through(of),
            _ => false,
        };
        if is_angular {
            angular.extend(step.names_given(scene.coordinates.len()));
        }
    }
    let names = e.symbols();
    if names.iter().any(|n| n == "pi") {
        return None;
    }
    names.into_iter().find(|n| angular.contains(n))
}

/// What an answer's derived value is multiplied by to be in its unit: the size of the unit its
/// symbols give it over the size of the unit asked for (100 for an answer in cm of symbols in
/// m). `None` when the answer has no unit or its symbols have none.
pub fn answer_scale(
    scene: &Scene,
    a: &Answer,
    general: &Value,
) -> Result<Option<Rational>, DimensionFault> {
    let Some(unit) = &a.unit else {
        return Ok(None);
    };
    let fault = |why: String| DimensionFault {
        line: a.line,
        what: format!("the answer `{}`", a.written),
        why,
    };
    if in_hertz(unit)
        && let Some(name) = angular_name(scene, &a.value)
    {
        return Err(fault(format!(
            "it is an angular frequency (rad/s, through `{name}`), but its unit `{}` counts \
             cycles per second, 2π times fewer: give it the unit rad/s, or divide it by 2*pi \
             for the frequency in Hz",
            unit.text
        )));
    }
    let mut found: Option<Measure> = None;
    for e in general.entries() {
        if let Some(m) = measure(scene, &e).map_err(|e| fault(e.to_string()))?
            && !e.is_zero()
        {
            found = Some(m);
        }
    }
    let Some(m) = found else {
        return Ok(None);
    };
    if m.dimension != unit.dimension {
        return Err(fault(format!(
            "it is in {}, but its unit `{}` is in {}: give it a unit of {}",
            m.dimension, unit.text, unit.dimension, m.dimension
        )));
    }
    Ok(Some(
        m.scale
            .mul(&unit.scale.recip().expect("a unit is not zero")),
    ))
}
