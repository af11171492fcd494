//! The renderers of the course's documents (`renderer.rs`): HTML (`html.rs`, and here the
//! page views for its templates, built from a [`Page`] with the math already converted to
//! MathML), Moodle's quizzes (`moodle.rs`) and the PDFs' markup (`pdf/`). The files are made
//! in memory: no file I/O here.

#[cfg(test)]
mod claim_form_tests;
mod claim_view;
mod guard;
#[cfg(test)]
mod guard_tests;
pub mod handout;
pub mod html;
pub mod json;
pub mod math;
pub mod memo;
pub mod moodle;
pub mod pdf;
pub mod plot;
pub mod problems;
pub mod renderer;

pub use claim_view::ClaimView;
pub(crate) use claim_view::{lead as claim_lead, shows_formula as claim_shows_formula};
pub use html::template_names;
pub use renderer::{Context, Rendered, Renderer, SiteFiles, TemplateTexts};

/// Every format a build writes, in order (the PDFs take the HTML's plots).
pub const RENDERERS: &[&dyn Renderer] =
    &[&html::Html, &moodle::Moodle, &json::JsonReport, &pdf::Pdf];

/// The documents printed by every renderer.
pub fn render(
    docs: &crate::document::course::Documents,
    cx: &Context,
) -> Result<Rendered, RenderError> {
    let mut out = Rendered::default();
    for r in RENDERERS {
        r.render(docs, cx, &mut out)?;
    }
    Ok(out)
}

use crate::base::format::sci;
use crate::cas::Expr;
use crate::derive::ExactBasis;
use crate::document::{At, Link, Page, PrincipalValues};
use crate::model::value::Value;
use crate::notation::{Formula, Op};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct StepView {
    pub title: String,
    pub math: String,
    pub why: String,
    /// A result at the scene's numbers: "at m = 1, a = 2:" and its MathML (empty for a step,
    /// for a number, or where a symbol has no value).
    pub at: String,
    /// An author's step's numeric check, as HTML (empty for a built-in step).
    pub check: String,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct NumericRow {
    pub body: String,
    pub method: String,
    pub points: usize,
    pub error: String,
    pub predicted: String,
    pub within_law: bool,
    /// Where the method left its ladder at this fidelity (empty for a rung below the last).
    pub stop: String,
    /// Measured wall time, only when the build asks for timings (it makes pages vary).
    pub seconds: Option<String>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct AccuracyRow {
    pub result: String,
    pub method: String,
    pub true_error: String,
    pub estimated_error: String,
    pub cost: String,
    pub seconds: Option<String>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct FigureView {
    /// Relative to the site root: `plots/<scene>-<slug>.svg`.
    pub file: String,
    pub title: String,
    pub desc: String,
    /// The error and cost of each numeric result drawn.
    pub accuracy: Vec<AccuracyRow>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PageView {
    /// How many of its formulas the build's guard read back and checked, and could not read
    /// (in this build; none for a page recalled from the cache, checked when it was made).
    #[serde(skip)]
    pub guarded: guard::Counts,
    pub id: String,
    pub title: String,
    /// The title as HTML: its `$…$` mathematics as MathML.
    pub title_html: String,
    pub lecture: String,
    pub section: String,
    pub equations: String,
    /// The scene's file name only: the build machine's paths never reach a page.
    pub source: String,
    /// The numeric fidelity, with its target and cost cap.
    pub fidelity: String,
    pub fidelity_name: String,
    /// Each symbol as MathML, its meaning as written, and its meaning as HTML with its unit.
    pub symbols: Vec<(String, String, String)>,
    /// Each abbreviation the scene defines, as MathML: `λ = M/(2πR)`.
    pub definitions: Vec<String>,
    /// Each coordinate as MathML, and what it measures as HTML.
    pub coordinates: Vec<(String, String)>,
    /// Each body in words, as HTML.
    pub bodies: Vec<String>,
    /// One per `Page::steps`.
    pub steps: Vec<StepView>,
    /// The results the page lists: `quantities` that are results, then `principal`.
    pub results: Vec<StepView>,
    /// One per `Page::quantities`: `None` for working quantities (an integrand, a position).
    pub quantities: Vec<Option<StepView>>,
    /// The exact principal axes, then the principal moments at the scene's values.
    pub principal: Vec<StepView>,
    pub numeric: Vec<NumericRow>,
    pub claims: Vec<ClaimView>,
    pub figures: Vec<FigureView>,
    pub errata: usize,
    pub passed: bool,
    pub prev: Option<Link>,
    pub next: Option<Link>,
}

/// Why a page, a plot or the course settings could not be rendered.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error("template {name}: {message}")]
    Template { name: String, message: String },
    #[error("cannot render `{latex}`: {message}")]
    Math { latex: String, message: String },
    #[error("`{latex}` gives a malformed <msup>: write `{{\\op}}^{{k}}`")]
    MalformedPower { latex: String },
    #[error("plot `{slug}`: {message}")]
    Plot { slug: String, message: String },
    /// Two of the site's files would have one name (one would silently replace the other).
    #[error("two files of the site would both be `{}`: rename a scene or a lecture", path.display())]
    Collision { path: PathBuf },
    /// A formula the page would show that is not the result it stands for: mechbook's bug,
    /// caught before anything is written (`guard.rs`).
    #[error(
        "line {line}: mechbook would print `{printed}`, which reads back as {read}, for the \
         derived result {result} (they differ by {by:.1e} at random points); this is a bug in \
         mechbook's printing, not in the scene: please report it with this scene"
    )]
    Misprinted {
        line: usize,
        printed: String,
        read: String,
        result: String,
        by: f64,
    },
    /// Any of the above, in one scene's page.
    #[error("{}: {error}", path.display())]
    InScene {
        path: PathBuf,
        error: Box<RenderError>,
    },
}

impl RenderError {
    fn in_scene(self, source: &std::path::Path) -> RenderError {
        RenderError::InScene {
            path: source.to_path_buf(),
            error: Box::new(self),
        }
    }
}

/// A link whose text is a page's title, the title's mathematics as plain text (a link's text
/// in the page's navigation holds no markup).
fn plain_link(l: &Link) -> Link {
    Link {
        href: l.href.clone(),
        title: crate::model::prose::plain(&l.title),
    }
}

/// A sentence as HTML: its text escaped, its formulas as MathML.
fn prose_html(prose: &crate::model::prose::Prose) -> Result<String, RenderError> {
    use crate::model::prose::Piece;
    let mut out = String::new();
    for piece in &prose.0 {
        match piece {
            Piece::Text(t) => out.push_str(&tera::escape_html(t)),
            // An author's mathematics is set from the tree read at load, mechbook's from the
            // tree it builds.
            Piece::Math(f) => out.push_str(&math::inline(&f.to_tex())?),
        }
    }
    Ok(out)
}

/// An author's text as HTML: escaped, its `$…$` mathematics as MathML.
pub fn author_html(text: &str) -> Result<String, RenderError> {
    prose_html(&crate::model::prose::author(text))
}

/// A result's heading: a catalogue quantity's name in words; none for a step's result, whose
/// equation names it (`ẍ₁ = …`).
pub fn result_heading(q: &crate::document::Quantity) -> String {
    match q.symbol {
        Some(_) => String::new(),
        None => crate::model::catalogue::heading(&q.name),
    }
}

/// A step's result as the page states it: `symbol = value`.
pub fn result_equation(symbol: &Expr, value: &Value) -> Formula {
    Formula::equation(Formula::Expr(symbol.clone()), value.to_expr())
}

/// A result at the scene's numbers, to six significant figures: "at m = 1, a = 2:" (the values
/// of the symbols it contains) and the number, vector or matrix as MathML.
fn at_numbers_html(v: &Value, at: &At) -> Result<String, RenderError> {
    let n: Vec<Formula> = at_entries(at).into_iter().map(|x| number(x, 6)).collect();
    let symbols = at.symbols.iter().map(|(k, x)| {
        with_unit(
            Formula::Row(vec![
                Formula::Expr(Expr::sym(k)),
                Formula::Op(Op::Equals),
                number(*x, 6),
            ]),
            at.units.get(k),
        )
    });
    Ok(format!(
        "at {}: {}",
        math::inline(&listed(symbols).to_tex())?,
        math::inline(&with_unit(numbers_formula(v, n), at.unit.as_ref()).to_tex())?
    ))
}

/// A number followed by its unit, a thin space between: 9.81 m/s².
fn with_unit(f: Formula, unit: Option<&String>) -> Formula {
    match unit {
        Some(u) => Formula::Row(vec![
            f,
            Formula::Op(Op::Thin),
            crate::model::units::unit_formula(u),
        ]),
        None => f,
    }
}

/// Formulas one after another, set apart by a comma and a space: `a = 1,\; b = 2`.
pub(crate) fn listed(items: impl IntoIterator<Item = Formula>) -> Formula {
    let mut row = Vec::new();
    for item in items {
        if !row.is_empty() {
            row.extend([Formula::Op(Op::Comma), Formula::Op(Op::Medium)]);
        }
        row.push(item);
    }
    Formula::Row(row)
}

/// Numbers (`n`, row-major) in the shape of `v`: a number, a column or a matrix.
pub(crate) fn numbers_formula(v: &Value, mut n: Vec<Formula>) -> Formula {
    match v {
        Value::Scalar(_) => n.swap_remove(0),
        Value::Vector(_) => Formula::Matrix(vec![n]),
        Value::Matrix(_) => Formula::Matrix(n.chunks(3).map(<[Formula]>::to_vec).collect()),
    }
}

/// A computed number to `digits` significant figures (4.6875 × 10⁻⁶, never e-notation).
fn number(x: f64, digits: usize) -> Formula {
    Formula::decimal(&crate::base::format::significant(x, digits))
}

/// An author's step's numeric check in one sentence (escaped for HTML).
fn check_text(c: &crate::verify::StepCheck) -> String {
    tera::escape_html(&check_sentence(c))
}

/// An author's step's numeric check in one sentence, for every printer.
pub(crate) fn check_sentence(c: &crate::verify::StepCheck) -> String {
    match &c.problem {
        Some(p) => format!("Not checked numerically: {p}"),
        None => format!(
            "Checked numerically, by {}: {} {} (within {}), {} evaluations.",
            c.method,
            if c.passed() {
                "agrees to"
            } else {
                "FAILS, differs by"
            },
            sci(c.error),
            sci(c.tolerance),
            c.evaluations
        ),
    }
}

/// A result's entries at the scene's numbers, an entry below the rounding of the largest
/// (cos(π/2) in floats, 6e-17) made zero.
pub(crate) fn at_entries(at: &At) -> Vec<f64> {
    let largest = at.numbers.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    at.numbers
        .iter()
        .map(|x| {
            if x.abs() <= 64.0 * f64::EPSILON * largest {
                0.0
            } else {
                *x
            }
        })
        .collect()
}

/// The HTML view of one page, its names typeset as the scene says. `timings` adds measured
/// seconds to the numeric table.
pub fn page_view(page: &Page, timings: bool) -> Result<PageView, RenderError> {
    crate::notation::typeset_as(&page.tex, || scene_page_view(page, timings))
}

fn scene_page_view(page: &Page, timings: bool) -> Result<PageView, RenderError> {
    let mut guard = guard::Guard::for_page(page);
    let steps = page
        .steps
        .iter()
        .map(|st| {
            let tex = st.statement.to_tex();
            guard.step(st, &tex)?;
            Ok(StepView {
                title: author_html(&st.title)?,
                math: math::block(&tex)?,
                why: prose_html(&st.why_cited())?,
                at: String::new(),
                check: st.check.as_ref().map(check_text).unwrap_or_default(),
            })
        })
        .collect::<Result<Vec<_>, RenderError>>()?;
    let mut quantities = Vec::new();
    for q in &page.quantities {
        quantities.push(match q.is_result {
            true => Some(StepView {
                title: result_heading(q),
                math: match &q.symbol {
                    Some(symbol) => {
                        let tex = result_equation(symbol, &q.value).to_tex();
                        if let Value::Scalar(derived) = &q.derived {
                            guard.printed(&tex, derived, page.line)?;
                        }
                        math::block(&tex)?
                    }
                    None => {
                        let tex = q.formula().to_tex();
                        guard.printed_value(&tex, &q.derived, page.line)?;
                        math::block(&tex)?
                    }
                },
                why: String::new(),
                at: match &q.at {
                    Some(at) => at_numbers_html(&q.value, at)?,
                    None => String::new(),
                },
                check: String::new(),
            }),
            false => None,
        });
    }
    let mut principal = Vec::new();
    for sp in &page.principal_axes {
        let vector = |v: &[Expr; 3]| Formula::Expr(Value::Vector(v.clone()).to_expr());
        let mut row = vec![Formula::Expr(sp.value.clone())];
        match &sp.basis {
            ExactBasis::Axis(a) => row.extend([Formula::Text(" along ".into()), vector(a)]),
            ExactBasis::PlaneNormalTo(n) => row.extend([
                Formula::Text(", every axis ".into()),
                Formula::Op(Op::Perp),
                vector(n),
            ]),
            ExactBasis::All => row.push(Formula::Text(", every axis".into())),
        }
        principal.push(StepView {
            title: format!("Principal moment (multiplicity {})", sp.multiplicity),
            math: math::block(&Formula::Row(row).to_tex())?,
            why: String::new(),
            at: String::new(),
            check: String::new(),
        });
    }
    if let Some(p) = &page.principal_values {
        principal.push(principal_values_view(p)?);
    }
    let results = quantities
        .iter()
        .flatten()
        .chain(&principal)
        .cloned()
        .collect();
    let numeric = page
        .numeric
        .iter()
        .map(|q| NumericRow {
            body: q.body.clone(),
            method: q.method.into(),
            points: q.points,
            error: sci(q.error),
            predicted: sci(q.predicted_error),
            within_law: q.within_law,
            stop: q.stop.into(),
            seconds: timings.then(|| format!("{:.1e}", q.seconds)),
        })
        .collect();
    let claims = (0..page.claims.len())
        .map(|i| claim_view::claim_view(page, i, &mut guard))
        .collect::<Result<_, RenderError>>()?;
    Ok(PageView {
        guarded: guard.counts,
        id: page.id.clone(),
        title: crate::model::prose::plain(&page.title),
        title_html: author_html(&page.title)?,
        lecture: page.lecture.clone(),
        section: page.section.clone(),
        equations: page.equations.join(", "),
        source: page
            .source
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_default(),
        fidelity: page.fidelity.to_string(),
        fidelity_name: page.fidelity.name(),
        symbols: page
            .symbols
            .iter()
            .map(|(k, v)| {
                let unit = page
                    .units
                    .get(k)
                    .map_or(String::new(), |u| format!(" ({})", problems::unit_html(u)));
                Ok((
                    math::mathml(&Expr::sym(k).to_tex(), false)?,
                    v.clone(),
                    format!("{}{unit}", author_html(v)?),
                ))
            })
            .collect::<Result<_, RenderError>>()?,
        definitions: page
            .definitions
            .iter()
            .map(|(k, e)| {
                math::inline(&Formula::equation(Formula::Expr(Expr::sym(k)), e.clone()).to_tex())
            })
            .collect::<Result<_, RenderError>>()?,
        coordinates: page
            .coordinates
            .iter()
            .map(|(k, v)| {
                // With its unit, as the PDF's setup and the symbols give theirs.
                let unit = page
                    .units
                    .get(k)
                    .map_or(String::new(), |u| format!(" ({})", problems::unit_html(u)));
                Ok((
                    math::mathml(&Expr::sym(k).to_tex(), false)?,
                    format!("{}{unit}", author_html(v)?),
                ))
            })
            .collect::<Result<_, RenderError>>()?,
        bodies: page
            .bodies
            .iter()
            .map(prose_html)
            .collect::<Result<_, RenderError>>()?,
        steps,
        results,
        quantities,
        principal,
        numeric,
        errata: page.errata,
        claims,
        figures: page
            .figures
            .iter()
            .map(|f| FigureView {
                file: f.file.clone(),
                title: f.title.clone(),
                desc: f.desc.clone(),
                accuracy: f
                    .accuracy
                    .iter()
                    .map(|a| AccuracyRow {
                        result: a.result.clone(),
                        method: a.method.clone(),
                        true_error: a.true_error.map_or("—".into(), sci),
                        estimated_error: a.estimated_error.map_or("—".into(), sci),
                        cost: format!("{} {}", a.cost, a.unit),
                        seconds: timings.then(|| format!("{:.1e}", a.seconds)),
                    })
                    .collect(),
            })
            .collect(),
        passed: page.passed,
        prev: page.prev.as_ref().map(plain_link),
        next: page.next.as_ref().map(plain_link),
    })
}

/// The scene's values, `M = 1, α = 0.6`, as one formula.
pub(crate) fn values_at(values: &[(String, f64)]) -> Formula {
    let mut row = Vec::new();
    for (k, (name, x)) in values.iter().enumerate() {
        if k > 0 {
            row.extend([Formula::Op(Op::Comma), Formula::Op(Op::Quad)]);
        }
        row.extend([
            Formula::Expr(Expr::sym(name)),
            Formula::Op(Op::Equals),
            Formula::decimal(&x.to_string()),
        ]);
    }
    Formula::Row(row)
}

/// The principal moments as numbers, with the axes when only the numerics give them, and how
/// well the two routes agree.
fn principal_values_view(p: &PrincipalValues) -> Result<StepView, RenderError> {
    use crate::numeric::eigen::Space;
    let letter = Formula::Name(crate::notation::Name::letter(&p.letter));
    let mut row = vec![
        letter,
        Formula::Op(Op::Equals),
        listed(p.exact.iter().map(|v| number(*v, 6))),
    ];
    if p.closed_form {
        let axes: Vec<Formula> = p
            .numeric
            .iter()
            .filter_map(|e| match &e.space {
                Space::Axis(v) => Some(Formula::Paren(
                    Box::new(Formula::Row(vec![
                        number(v.x, 4),
                        Formula::Op(Op::Comma),
                        number(v.y, 4),
                        Formula::Op(Op::Comma),
                        number(v.z, 4),
                    ])),
                    true,
                )),
                _ => None,
            })
            .collect();
        if !axes.is_empty() {
            row.extend([
                Formula::Op(Op::Quad),
                Formula::Text("axes ".into()),
                listed(axes),
            ]);
        }
    }
    let route = if p.closed_form {
        "the closed form above"
    } else {
        "the exact roots"
    };
    Ok(StepView {
        at: String::new(),
        check: String::new(),
        title: "Principal moments at the scene's values".into(),
        math: math::block(&Formula::Row(row).to_tex())?,
        why: format!(
            "at {}: {}",
            math::inline(&values_at(&p.values).to_tex())?,
            tera::escape_html(&format!(
                "{route} evaluated, and the eigen-solver on the exact tensor agrees to {} \
                 (relative)",
                sci(p.error)
            ))
        ),
    })
}

#[cfg(test)]
mod tests;
