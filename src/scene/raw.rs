//! The scene file as TOML sees it: a strict schema (`deny_unknown_fields`) with spans on every
//! value that `Scene::parse` validates further. `docs/scenes.md` documents each field.

use serde::Deserialize;
use std::collections::BTreeMap;
use toml::Spanned;

pub type Text = Spanned<String>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    pub id: Text,
    pub title: Text,
    pub notes: RawNotes,
    #[serde(default)]
    pub symbols: BTreeMap<Spanned<String>, Spanned<RawMeaning>>,
    #[serde(default)]
    pub definitions: BTreeMap<Spanned<String>, Spanned<RawDefinition>>,
    #[serde(default)]
    pub vectors: BTreeMap<Spanned<String>, Spanned<Vec<Text>>>,
    #[serde(default)]
    pub omega: Option<Spanned<Vec<Text>>>,
    #[serde(default)]
    pub axis: Option<Spanned<Vec<Text>>>,
    #[serde(default, rename = "body")]
    pub bodies: Vec<Spanned<RawBody>>,
    #[serde(default, rename = "claim")]
    pub claims: Vec<Spanned<RawClaim>>,
    /// Generalised coordinates: functions of the time `t`, with their rates `q'` and `q''`.
    #[serde(default)]
    pub coordinates: BTreeMap<Spanned<String>, Spanned<RawMeaning>>,
    /// The author's own derivation, a named step at a time.
    #[serde(default, rename = "step")]
    pub steps: Vec<Spanned<RawStep>>,
    #[serde(default, rename = "plot")]
    pub plots: Vec<Spanned<RawPlot>>,
    /// Absent in a scene of steps or claims only.
    #[serde(default)]
    pub outputs: Option<RawOutputs>,
    #[serde(default)]
    pub numeric: RawNumeric,
    /// The physics' domain: inequalities between the scene's names (`"R > r"`, `"0 < beta <
    /// beta0"`), which the random points keep to and the engine uses to decide signs.
    #[serde(default)]
    pub assume: Vec<Text>,
    /// Recorded results: a quantity's exact value, or a step's result (a list for a step
    /// with several), as `check --bless` writes them.
    #[serde(default)]
    pub expect: BTreeMap<Spanned<String>, Spanned<RawRecorded>>,
    /// Step key -> the notes' citation for it (`characteristic-polynomial = "eq (51)"`).
    #[serde(default)]
    pub cite: BTreeMap<Spanned<String>, Text>,
    #[serde(default)]
    pub problem: Option<Spanned<RawProblem>>,
    /// `count`, `seed`, `require`, and a range or list for each symbol that varies: read as
    /// TOML values, since the symbols' names are the scene's own.
    #[serde(default)]
    pub variants: Option<Spanned<BTreeMap<Spanned<String>, Spanned<toml::Value>>>>,
}

/// A symbol's or a coordinate's meaning: a string, or `{ meaning = "...", unit = "kg" }`.
pub enum RawMeaning {
    Words(String),
    WithUnit {
        meaning: Text,
        unit: Option<Text>,
        /// How the name is typeset, in LaTeX: `tex = "\\Omega"`.
        tex: Option<Text>,
    },
}

/// The meaning, located: the string itself, or the table's `meaning`.
pub fn meaning_of(m: &Spanned<RawMeaning>) -> Text {
    match m.get_ref() {
        RawMeaning::Words(w) => Spanned::new(m.span(), w.clone()),
        RawMeaning::WithUnit { meaning, .. } => meaning.clone(),
    }
}

/// How the name is typeset, if the table says.
pub fn tex_of(m: &Spanned<RawMeaning>) -> Option<&Text> {
    match m.get_ref() {
        RawMeaning::Words(_) => None,
        RawMeaning::WithUnit { tex, .. } => tex.as_ref(),
    }
}

/// A definition: its expression, or `{ be = "...", tex = "\\omega_1(t)" }` to set its name.
pub enum RawDefinition {
    Expr(String),
    WithTex { be: Text, tex: Option<Text> },
}

/// A definition's expression, located: the string itself, or the table's `be`.
pub fn definition_of(d: &Spanned<RawDefinition>) -> Text {
    match d.get_ref() {
        RawDefinition::Expr(e) => Spanned::new(d.span(), e.clone()),
        RawDefinition::WithTex { be, .. } => be.clone(),
    }
}

/// How a definition's name is typeset, if its table says.
pub fn definition_tex(d: &Spanned<RawDefinition>) -> Option<&Text> {
    match d.get_ref() {
        RawDefinition::Expr(_) => None,
        RawDefinition::WithTex { tex, .. } => tex.as_ref(),
    }
}

impl<'de> Deserialize<'de> for RawDefinition {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visit;
        impl<'de> serde::de::Visitor<'de> for Visit {
            type Value = RawDefinition;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("an expression, or { be = \"...\", tex = \"...\" }")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<RawDefinition, E> {
                Ok(RawDefinition::Expr(v.to_string()))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                mut m: A,
            ) -> Result<RawDefinition, A::Error> {
                let (mut be, mut tex) = (None, None);
                while let Some(key) = m.next_key::<String>()? {
                    match key.as_str() {
                        "be" if be.is_none() => be = Some(m.next_value()?),
                        "tex" if tex.is_none() => tex = Some(m.next_value()?),
                        "be" | "tex" => {
                            return Err(serde::de::Error::custom(format!("`{key}` given twice")));
                        }
                        other => {
                            return Err(serde::de::Error::unknown_field(other, &["be", "tex"]));
                        }
                    }
                }
                let be = be.ok_or_else(|| serde::de::Error::missing_field("be"))?;
                Ok(RawDefinition::WithTex { be, tex })
            }
        }
        d.deserialize_any(Visit)
    }
}

/// The unit, if the table gives one.
pub fn unit_of(m: &Spanned<RawMeaning>) -> Option<&Text> {
    match m.get_ref() {
        RawMeaning::Words(_) => None,
        RawMeaning::WithUnit { unit, .. } => unit.as_ref(),
    }
}

impl<'de> Deserialize<'de> for RawMeaning {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visit;
        impl<'de> serde::de::Visitor<'de> for Visit {
            type Value = RawMeaning;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(
                    "a meaning in words, or { meaning = \"...\", unit = \"...\", tex = \"...\" }",
                )
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<RawMeaning, E> {
                Ok(RawMeaning::Words(v.to_string()))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                mut m: A,
            ) -> Result<RawMeaning, A::Error> {
                let (mut meaning, mut unit, mut tex) = (None, None, None);
                while let Some(key) = m.next_key::<String>()? {
                    match key.as_str() {
                        "meaning" if meaning.is_none() => meaning = Some(m.next_value()?),
                        "unit" if unit.is_none() => unit = Some(m.next_value()?),
                        "tex" if tex.is_none() => tex = Some(m.next_value()?),
                        "meaning" | "unit" | "tex" => {
                            return Err(serde::de::Error::custom(format!("`{key}` given twice")));
                        }
                        other => {
                            return Err(serde::de::Error::unknown_field(
                                other,
                                &["meaning", "unit", "tex"],
                            ));
                        }
                    }
                }
                let meaning = meaning.ok_or_else(|| serde::de::Error::missing_field("meaning"))?;
                Ok(RawMeaning::WithUnit { meaning, unit, tex })
            }
        }
        d.deserialize_any(Visit)
    }
}

/// A problem's answer: a name or an expression, or a table
/// `{ value = "...", label = "...", unit = "...", tolerance = "0.5%" }`.
pub struct RawAnswer {
    pub value: Text,
    pub label: Option<Text>,
    pub unit: Option<Text>,
    /// A number (0.005) or a percentage (`"0.5%"`), relative to the answer.
    pub tolerance: Option<Spanned<toml::Value>>,
}

impl<'de> Deserialize<'de> for RawAnswer {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visit;
        impl<'de> serde::de::Visitor<'de> for Visit {
            type Value = RawAnswer;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(
                    "a quantity's name or an expression, or { value = \"...\", label = \"...\", \
                     unit = \"...\", tolerance = \"...\" }",
                )
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<RawAnswer, E> {
                // The caller locates the string by the answer's own span.
                Ok(RawAnswer {
                    value: Spanned::new(0..0, v.to_string()),
                    label: None,
                    unit: None,
                    tolerance: None,
                })
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                mut m: A,
            ) -> Result<RawAnswer, A::Error> {
                const FIELDS: &[&str] = &["value", "label", "unit", "tolerance"];
                let (mut value, mut label, mut unit, mut tolerance) = (None, None, None, None);
                while let Some(key) = m.next_key::<String>()? {
                    let twice = || serde::de::Error::custom(format!("`{key}` given twice"));
                    match key.as_str() {
                        "value" if value.is_none() => value = Some(m.next_value()?),
                        "label" if label.is_none() => label = Some(m.next_value()?),
                        "unit" if unit.is_none() => unit = Some(m.next_value()?),
                        "tolerance" if tolerance.is_none() => tolerance = Some(m.next_value()?),
                        "value" | "label" | "unit" | "tolerance" => return Err(twice()),
                        other => return Err(serde::de::Error::unknown_field(other, FIELDS)),
                    }
                }
                let value = value.ok_or_else(|| serde::de::Error::missing_field("value"))?;
                Ok(RawAnswer {
                    value,
                    label,
                    unit,
                    tolerance,
                })
            }
        }
        d.deserialize_any(Visit)
    }
}

/// An answer's value, located: a plain string is located by the answer's own span.
pub fn answer_value(a: &Spanned<RawAnswer>) -> Text {
    let v = &a.get_ref().value;
    if v.span() == (0..0) {
        Spanned::new(a.span(), v.get_ref().clone())
    } else {
        v.clone()
    }
}

impl RawScene {
    /// Where `outputs.want` is (or the file's start), for errors about the scene as a whole.
    pub fn outputs_span(&self) -> usize {
        self.outputs.as_ref().map_or(0, |o| o.want.span().start)
    }

    /// The outputs the scene lists, none when it has no [outputs].
    pub fn wanted(&self) -> &[Text] {
        self.outputs
            .as_ref()
            .map_or(&[], |o| o.want.get_ref().as_slice())
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawNotes {
    pub lecture: Text,
    #[serde(default)]
    pub section: String,
    #[serde(default)]
    pub equations: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBody {
    pub kind: Text,
    #[serde(default)]
    pub label: Option<Text>,
    #[serde(default)]
    pub mass: Option<Text>,
    #[serde(default)]
    pub size: Option<Spanned<Vec<Text>>>,
    #[serde(default)]
    pub radius: Option<Text>,
    #[serde(default)]
    pub length: Option<Text>,
    #[serde(default)]
    pub height: Option<Text>,
    /// The hole's radius of an annulus, a tube or a thick shell.
    #[serde(default)]
    pub inner_radius: Option<Text>,
    /// A hole: its `mass` is the mass removed.
    #[serde(default)]
    pub subtract: Option<bool>,
    /// Where the body's own origin sits: `corner` or `centre` for a box, `end` or `centre` for a rod.
    #[serde(default)]
    pub origin: Option<Text>,
    /// The rod's direction: `x`, `y` or `z`.
    #[serde(default)]
    pub along: Option<Text>,
    #[serde(default)]
    pub points: Vec<Spanned<RawPoint>>,
    #[serde(default)]
    pub rotate: Vec<Spanned<RawRotation>>,
    #[serde(default)]
    pub shift: Option<Spanned<Vec<Text>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPoint {
    pub mass: Text,
    pub at: Spanned<Vec<Text>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRotation {
    pub axis: Text,
    pub angle: Text,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawClaim {
    pub eq: Text,
    pub statement: Text,
    #[serde(default)]
    pub quantity: Option<Text>,
    #[serde(default)]
    pub value: Option<Text>,
    /// For a number the notes give roughly: how many significant figures they give.
    #[serde(default)]
    pub figures: Option<Spanned<i64>>,
    /// The reviewed verdict; absent until `check --bless` records it.
    #[serde(default)]
    pub expect: Option<Text>,
    /// `notes` (default): the notes' own statement; `mistake`: a common mistake for students.
    #[serde(default)]
    pub role: Option<Text>,
    /// The symbol its quantity is printed as, in LaTeX (`tex = "d^2"`), where the quantity is a
    /// name of mechbook's (`plane_distance_squared`) that a page would not print.
    #[serde(default)]
    pub tex: Option<Text>,
}

/// A `solve` step's unknowns: one name, or a list of them for a linear system.
#[derive(Deserialize)]
#[serde(
    untagged,
    expecting = "`for` takes the unknown's name, or a list of names such as [\"x''\", \"F\"]"
)]
pub enum RawUnknowns {
    One(String),
    Many(Vec<String>),
}

/// An `[expect]` value: one result, or a step's several results in order.
#[derive(Deserialize)]
#[serde(
    untagged,
    expecting = "an `[expect]` value is what `check --bless` writes: a result's exact form, such \
                 as \"m*a^2/6\", or a list of them, such as [\"sqrt(g/l)\", \"sqrt(3*g/l)\"], for a \
                 step with several results"
)]
pub enum RawRecorded {
    One(String),
    Many(Vec<String>),
}

/// A step's `gives`: the notes' form of its result, or of each of several results in order.
#[derive(Deserialize)]
#[serde(
    untagged,
    expecting = "`gives` takes the notes' form of the step's result, or a list of them, one per \
                 result of a step that gives several (modes, roots, unknowns)"
)]
pub enum RawGives {
    One(String),
    Many(Vec<String>),
}

impl RawStep {
    /// A single `gives`, as text at its place in the file.
    pub fn single_gives(&self) -> Option<Text> {
        let g = self.gives.as_ref()?;
        match g.get_ref() {
            RawGives::One(text) => Some(Spanned::new(g.span(), text.clone())),
            RawGives::Many(_) => None,
        }
    }

    /// A list `gives`, each entry at the list's place in the file.
    pub fn listed_gives(&self) -> Vec<Text> {
        match self.gives.as_ref() {
            Some(g) => match g.get_ref() {
                RawGives::Many(list) => list
                    .iter()
                    .map(|text| Spanned::new(g.span(), text.clone()))
                    .collect(),
                RawGives::One(_) => Vec::new(),
            },
            None => Vec::new(),
        }
    }
}

/// One step of an author's derivation: a name, one operation, and optionally the notes' form
/// of its result (`gives`), checked like a claim.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStep {
    pub name: Text,
    #[serde(default)]
    pub be: Option<Text>,
    #[serde(default)]
    pub differentiate: Option<Text>,
    #[serde(default)]
    pub by: Option<Text>,
    #[serde(default)]
    pub lagrange: Option<Text>,
    /// The Routhian of the named Lagrangian, each cyclic coordinate's rate replaced by its
    /// conserved momentum (`cyclic`).
    #[serde(default)]
    pub routh: Option<Text>,
    /// For `routh`: each cyclic coordinate and the symbol, declared in [symbols], of its
    /// conserved momentum (`cyclic = { phi = "p" }`).
    #[serde(default)]
    pub cyclic: BTreeMap<Spanned<String>, Text>,
    /// For `lagrange`: each holonomic constraint f(q) = 0 under the name of its multiplier λ,
    /// a symbol declared in [symbols] (`T = "l - x1 - x2"`); the generalised constraint force on
    /// q is λ ∂f/∂q.
    #[serde(default)]
    pub constraints: BTreeMap<Spanned<String>, Text>,
    #[serde(default)]
    pub linearise: Option<Text>,
    /// For `linearise`: the state about which, by coordinate (unnamed ones about 0).
    #[serde(default)]
    pub about: BTreeMap<Spanned<String>, Text>,
    #[serde(default)]
    pub frequency: Option<Text>,
    #[serde(default)]
    pub substitute: Option<Text>,
    /// For `substitute`: each name and what replaces it (`"theta'" = "x'/R"`).
    #[serde(default)]
    pub set: BTreeMap<Spanned<String>, Text>,
    /// Solve the named equations of motion for one unknown, or a list of them (`for`).
    #[serde(default)]
    pub solve: Option<Text>,
    #[serde(default, rename = "for")]
    pub unknown: Option<Spanned<RawUnknowns>>,
    /// The generalised momentum of this coordinate, from the Lagrangian named by `of`.
    #[serde(default)]
    pub momentum: Option<Text>,
    #[serde(default)]
    pub of: Option<Text>,
    /// The energy function of the named Lagrangian.
    #[serde(default)]
    pub energy: Option<Text>,
    /// A definite integral `over` [variable, from, to] ranges, innermost first.
    #[serde(default)]
    pub integrate: Option<Text>,
    #[serde(default)]
    pub over: Vec<Spanned<Vec<Text>>>,
    /// The Taylor series of an expression, `about` one name's value, to `order`.
    #[serde(default)]
    pub series: Option<Text>,
    #[serde(default)]
    pub order: Option<Spanned<i64>>,
    /// The states of rest of the named equation of motion.
    #[serde(default)]
    pub equilibria: Option<Text>,
    /// Whether each of the named equilibria is stable.
    #[serde(default)]
    pub stability: Option<Text>,
    /// For `lagrange`, `momentum` and `energy`: the initial state their numeric check
    /// integrates from (coordinates and their rates, `"phi'" = 0.1`).
    #[serde(default)]
    pub start: BTreeMap<Spanned<String>, Spanned<f64>>,
    #[serde(default)]
    pub gives: Option<Spanned<RawGives>>,
    /// The author's names for a step's several results, in order (`names = ["slow", "fast"]`).
    #[serde(default)]
    pub names: Option<Spanned<Vec<String>>>,
    #[serde(default)]
    pub why: Option<Text>,
    /// How the step's name is typeset, in LaTeX: `tex = "I_p"`.
    #[serde(default)]
    pub tex: Option<Text>,
    #[serde(default)]
    pub eq: Option<Text>,
    #[serde(default)]
    pub expect: Option<Text>,
    #[serde(default)]
    pub role: Option<Text>,
}

/// A problem for students: its statement with `{symbol}` placeholders and the derived
/// quantities that answer it.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawProblem {
    pub statement: Text,
    pub answers: Spanned<Vec<Spanned<RawAnswer>>>,
    /// A Moodle answer's tolerance, relative to the answer (0.01 is 1%).
    #[serde(default)]
    pub tolerance: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOutputs {
    pub want: Spanned<Vec<Text>>,
    /// `"principal"`: the free top's moments are the bodies' own, about their centre of mass.
    #[serde(default)]
    pub inertia: Option<Text>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct RawNumeric {
    #[serde(default)]
    pub values: BTreeMap<Spanned<String>, Spanned<f64>>,
    #[serde(default)]
    pub seed: Option<u64>,
    /// `draft`, `standard`, `reference` or a target tolerance as a string (`"1e-6"`).
    #[serde(default)]
    pub fidelity: Option<Text>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPlot {
    pub kind: Text,
    /// For `tensor-sweep` and `expression`: the name on the x axis, its range and the numeric
    /// sample count.
    pub over: Option<Text>,
    pub range: Option<Spanned<Vec<Text>>>,
    pub samples: Option<Spanned<i64>>,
    /// For the free-body kinds: principal moments, ω(0) in the body frame, and the end time.
    /// Each of the three is a number or an expression of the scene's symbols; `inertia` may
    /// also be "principal" (the scene's own body). Read as TOML values for errors that say which.
    pub inertia: Option<Spanned<toml::Value>>,
    pub omega: Option<Spanned<toml::Value>>,
    pub t: Option<Spanned<f64>>,
    /// For `motion`: the step of equations of motion drawn, the linear ones drawn beside it,
    /// and the state both start from. For `expression`: the step whose result is drawn.
    pub step: Option<Text>,
    pub linear: Option<Text>,
    #[serde(default)]
    pub start: BTreeMap<Spanned<String>, Spanned<f64>>,
    /// For `expression`: values of the names the step's result holds besides `over` that have
    /// none under `[numeric]` (a rate, a coordinate).
    #[serde(default)]
    pub at: BTreeMap<Spanned<String>, Spanned<f64>>,
}

/// The byte offset of a string's first character inside its quotes.
pub fn content_start<T>(s: &Spanned<T>) -> usize {
    s.span().start + 1
}

/// A name an author may give: a letter, then letters, digits and single underscores.
pub fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
        && !s.contains("__")
}
