//! Page views for the templates: plain data built from the reports, with the math already
//! converted to MathML. No file I/O here.

mod linebreak;
#[cfg(test)]
mod linebreak_tests;
pub mod math;
pub mod moodle;
pub mod plot;
pub mod problems;
mod site_files;

pub use site_files::{SiteFiles, TemplateTexts, site_files, template_names};

use crate::base::format::sci;
use crate::cas::Expr;
use crate::derive::ExactBasis;
use crate::model::catalogue::{quantity, quantity_symbol};
use crate::model::value::Value;
use crate::pipeline::SceneReport;
use crate::scene::Verdict;
use serde::Serialize;
use std::path::PathBuf;

#[derive(Debug, Clone, Serialize)]
pub struct Link {
    pub href: String,
    pub title: String,
}

#[derive(Debug, Clone, Serialize)]
pub struct StepView {
    pub title: String,
    pub math: String,
    pub why: String,
    /// A result at the scene's numbers: "at m = 1, a = 2:" and its MathML (empty for a step,
    /// for a number, or where a symbol has no value).
    pub at: String,
}

#[derive(Debug, Clone, Serialize)]
pub struct ClaimView {
    pub eq: String,
    pub statement: String,
    pub verdict: String,
    /// The quantity claimed, the notes' formula for it and the derived one, as MathML (empty
    /// when not checkable).
    pub quantity: String,
    pub notes: String,
    pub derived: String,
    /// Each as HTML, its formulas as MathML.
    pub differences: Vec<String>,
    /// For a number the notes give roughly: how it was rounded to compare.
    pub precision: Option<String>,
    /// `notes` or `mistake`.
    pub role: &'static str,
}

#[derive(Debug, Clone, Serialize)]
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

#[derive(Debug, Clone, Serialize)]
pub struct AccuracyRow {
    pub result: String,
    pub method: String,
    pub true_error: String,
    pub estimated_error: String,
    pub cost: String,
    pub seconds: Option<String>,
}

#[derive(Debug, Clone, Serialize)]
pub struct FigureView {
    /// Relative to the site root: `plots/<scene>-<slug>.svg`.
    pub file: String,
    pub title: String,
    pub desc: String,
    /// The error and cost of each numeric result drawn.
    pub accuracy: Vec<AccuracyRow>,
}

#[derive(Debug, Clone, Serialize)]
pub struct PageView {
    pub id: String,
    pub title: String,
    pub lecture: String,
    pub section: String,
    pub equations: String,
    /// The scene's file name only: the build machine's paths never reach a page.
    pub source: String,
    /// The numeric fidelity, with its target and cost cap.
    pub fidelity: String,
    pub fidelity_name: String,
    pub symbols: Vec<(String, String)>,
    pub bodies: Vec<String>,
    pub steps: Vec<StepView>,
    pub results: Vec<StepView>,
    pub numeric: Vec<NumericRow>,
    pub claims: Vec<ClaimView>,
    pub figures: Vec<FigureView>,
    pub errata: usize,
    pub passed: bool,
    pub prev: Option<Link>,
    pub next: Option<Link>,
}

/// The file a scene's plot is written to, relative to the site root.
pub fn figure_file(r: &SceneReport, fig: &crate::model::figure::Figure) -> String {
    format!("plots/{}-{}.svg", r.scene.id, fig.slug)
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
    /// Any of the above, in one scene's page.
    #[error("{}: {error}", path.display())]
    InScene {
        path: PathBuf,
        error: Box<RenderError>,
    },
}

impl RenderError {
    fn in_scene(self, r: &SceneReport) -> RenderError {
        RenderError::InScene {
            path: r.scene.source.clone(),
            error: Box::new(self),
        }
    }
}

/// The file a scene's page is written to.
pub fn page_file(r: &SceneReport) -> String {
    format!("{}.html", r.scene.id)
}

/// A sentence as HTML: its text escaped, its formulas as MathML.
fn prose_html(prose: &crate::model::prose::Prose) -> Result<String, RenderError> {
    use crate::model::prose::Piece;
    let mut out = String::new();
    for piece in &prose.0 {
        match piece {
            Piece::Text(t) => out.push_str(&tera::escape_html(t)),
            Piece::Math(f) => out.push_str(&math::inline(&f.to_latex())?),
        }
    }
    Ok(out)
}

/// A step's reason as HTML: its text escaped, its formulas as MathML, after the scene's
/// citation for the step if it has one.
fn why_html(
    st: &crate::derive::Step,
    cites: &std::collections::BTreeMap<String, String>,
) -> Result<String, RenderError> {
    let cite = st
        .citation(cites)
        .map(|c| tera::escape_html(&format!("{c}: ")))
        .unwrap_or_default();
    Ok(format!("{cite}{}", prose_html(&st.why)?))
}

fn value_math(v: &Value) -> Result<String, RenderError> {
    math::block(&v.to_latex())
}

/// A result at the scene's numbers, to six significant figures: "at m = 1, a = 2:" (the values
/// of the symbols it contains) and the number, vector or matrix as MathML. Empty when the result
/// is a number already or a symbol in it has no value.
fn value_at_numbers(
    v: &Value,
    values: &crate::model::value::Values,
) -> Result<String, RenderError> {
    use crate::base::format::significant;
    // π is a number, not one of the scene's symbols.
    let symbols: std::collections::BTreeSet<String> = v
        .entries()
        .iter()
        .flat_map(|e| e.symbols())
        .filter(|s| values.contains_key(s))
        .collect();
    let Ok(numbers) = v.numbers_at(values) else {
        return Ok(String::new());
    };
    // A number or a bare symbol (a mass M) says nothing new at the numbers.
    let plain = v
        .entries()
        .iter()
        .all(|e| matches!(e, Expr::Num(_) | Expr::Sym(_)));
    if symbols.is_empty() || plain {
        return Ok(String::new());
    }
    let n: Vec<String> = numbers.iter().map(|x| significant(*x, 6)).collect();
    let latex = numbers_latex(v, &n);
    let at: Vec<String> = symbols
        .iter()
        .map(|k| {
            format!(
                "{} = {}",
                Expr::sym(k).to_latex(),
                significant(values[k], 6)
            )
        })
        .collect();
    Ok(format!(
        "at {}: {}",
        math::inline(&at.join(",\\; "))?,
        math::inline(&latex)?
    ))
}

/// Numbers written out (`n`, row-major) in the shape of `v`: a number, a column or a matrix.
pub(crate) fn numbers_latex(v: &Value, n: &[String]) -> String {
    match v {
        Value::Scalar(_) => n[0].clone(),
        Value::Vector(_) => format!("\\begin{{pmatrix}}{}\\end{{pmatrix}}", n.join(" & ")),
        Value::Matrix(_) => format!(
            "\\begin{{pmatrix}}{}\\end{{pmatrix}}",
            n.chunks(3)
                .map(|row| row.join(" & "))
                .collect::<Vec<_>>()
                .join(" \\\\ ")
        ),
    }
}

/// Builds the view of one page. `timings` adds measured seconds to the numeric table.
pub fn page_view(
    r: &SceneReport,
    prev: Option<&SceneReport>,
    next: Option<&SceneReport>,
    timings: bool,
) -> Result<PageView, RenderError> {
    let s = &r.scene;
    let link = |o: Option<&SceneReport>| {
        o.map(|o| Link {
            href: page_file(o),
            title: o.scene.title.clone(),
        })
    };
    let steps = r
        .derivation
        .steps
        .iter()
        .map(|st| {
            Ok(StepView {
                title: st.title.clone(),
                math: math::block(&st.statement.to_latex())?,
                why: why_html(st, &s.cite)?,
                at: String::new(),
            })
        })
        .collect::<Result<Vec<_>, RenderError>>()?;
    let mut results = Vec::new();
    for (name, v) in &r.derivation.quantities {
        if name == quantity::INTEGRAND || name == quantity::POSITION {
            continue;
        }
        results.push(StepView {
            title: name.replace('_', " "),
            math: value_math(v)?,
            why: String::new(),
            at: value_at_numbers(v, &s.values)?,
        });
    }
    if let Some(e) = &r.derivation.eigen {
        for sp in &e.spaces {
            let dir = match &sp.basis {
                ExactBasis::Axis(a) => {
                    format!("\\text{{ along }} {}", Value::Vector(a.clone()).to_latex())
                }
                ExactBasis::PlaneNormalTo(n) => format!(
                    "\\text{{, every axis }} \\perp {}",
                    Value::Vector(n.clone()).to_latex()
                ),
                ExactBasis::All => "\\text{, every axis}".into(),
            };
            results.push(StepView {
                title: format!("principal moment (multiplicity {})", sp.multiplicity),
                math: math::block(&format!("{}{dir}", sp.value.to_latex()))?,
                why: String::new(),
                at: String::new(),
            });
        }
    }
    if let Some(p) = &r.verification.principal {
        let letter = r.derivation.eigen.as_ref().map_or("lambda", |e| &e.letter);
        results.push(principal_values_view(s, p, letter)?);
    }
    let numeric = r
        .numeric
        .iter()
        .flat_map(|n| n.runs.iter().zip(&r.verification.within_law))
        .map(|(q, ok)| NumericRow {
            body: q.body.clone(),
            method: q.method.name().into(),
            points: q.points,
            error: sci(q.error),
            predicted: sci(q.predicted_error),
            within_law: *ok,
            stop: q.stop.describe().into(),
            seconds: timings.then(|| format!("{:.1e}", q.seconds)),
        })
        .collect();
    let mut claims = Vec::new();
    for c in &r.verification.claims {
        let render = |e: Option<&crate::cas::Expr>| {
            e.map(|e| math::inline(&e.to_latex_named(&quantity_symbol)))
                .transpose()
                .map(Option::unwrap_or_default)
        };
        let derived = match &c.derived {
            None => String::new(),
            Some(v) => {
                let latex = v.to_latex();
                // Beside a claim that agrees, the derived form is a courtesy: left out when it
                // would fill more than three lines (it is in `check --json`).
                if c.verdict == Verdict::Agrees && !math::fits_lines(&latex, 3) {
                    String::new()
                } else {
                    math::inline(&latex)?
                }
            }
        };
        claims.push(ClaimView {
            eq: c.eq.clone(),
            statement: c.statement.clone(),
            verdict: c.verdict.as_str().into(),
            quantity: render(c.quantity.as_ref())?,
            notes: render(c.notes.as_ref())?,
            derived,
            differences: c
                .differences
                .iter()
                .map(prose_html)
                .collect::<Result<_, _>>()?,
            precision: c.precision.clone(),
            role: match c.role {
                crate::scene::ClaimRole::Notes => "notes",
                crate::scene::ClaimRole::Mistake => "mistake",
            },
        });
    }
    Ok(PageView {
        id: s.id.clone(),
        title: s.title.clone(),
        lecture: s.notes.lecture.clone(),
        section: s.notes.section.clone(),
        equations: s.notes.equations.join(", "),
        source: s
            .source
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_default(),
        fidelity: r.fidelity.to_string(),
        fidelity_name: r.fidelity.name(),
        symbols: s
            .symbols
            .iter()
            .map(|(k, v)| {
                Ok((
                    math::mathml(&crate::cas::Expr::sym(k).to_latex(), false)?,
                    v.clone(),
                ))
            })
            .collect::<Result<_, RenderError>>()?,
        bodies: s.bodies.iter().map(describe_body).collect(),
        steps,
        results,
        numeric,
        errata: r.verification.errata().count(),
        claims,
        figures: r
            .figures
            .iter()
            .map(|f| FigureView {
                file: figure_file(r, f),
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
        passed: r.passed(),
        prev: link(prev),
        next: link(next),
    })
}

/// The principal moments as numbers, with the axes when only the numerics give them, and how
/// well the two routes agree.
fn principal_values_view(
    s: &crate::scene::Scene,
    p: &crate::verify::PrincipalValues,
    letter: &str,
) -> Result<StepView, RenderError> {
    use crate::base::format::significant;
    use crate::numeric::eigen::Space;
    let values: Vec<String> = p.exact.iter().map(|v| significant(*v, 6)).collect();
    let symbols: Vec<String> = s.values.keys().cloned().collect();
    let mut latex = format!("\\{letter} = {}", values.join(",\\; "));
    if p.closed_form {
        let axes: Vec<String> = p
            .numeric
            .iter()
            .filter_map(|e| match &e.space {
                Space::Axis(v) => Some(format!(
                    "\\left({}, {}, {}\\right)",
                    significant(v.x, 4),
                    significant(v.y, 4),
                    significant(v.z, 4)
                )),
                _ => None,
            })
            .collect();
        if !axes.is_empty() {
            latex.push_str(&format!("\\quad \\text{{axes }} {}", axes.join(",\\; ")));
        }
    }
    let route = if p.closed_form {
        "the closed form above"
    } else {
        "the exact roots"
    };
    Ok(StepView {
        at: String::new(),
        title: "principal moments at the scene's values".into(),
        math: math::block(&latex)?,
        why: tera::escape_html(&format!(
            "at {}: {route} evaluated, and the eigen-solver on the exact tensor agrees to {} (relative)",
            symbols
                .iter()
                .map(|k| format!("{k} = {}", s.values[k]))
                .collect::<Vec<_>>()
                .join(", "),
            sci(p.error)
        )),
    })
}

fn describe_body(b: &crate::scene::Body) -> String {
    let mass = if b.subtract {
        format!("a hole removing mass {}", Expr::negate(b.mass.clone()))
    } else {
        format!("mass {}", b.mass)
    };
    let mut d = if b.label == b.shape.kind() {
        format!("{}, {mass}", b.label)
    } else {
        format!("{} ({}), {mass}", b.label, b.shape.kind())
    };
    for (axis, angle) in &b.rotations {
        d.push_str(&format!(", rotated by {angle} about {}", axis.name()));
    }
    if b.shift.iter().any(|e| !e.is_zero()) {
        d.push_str(&format!(
            ", shifted by {}",
            Value::Vector(b.shift.clone()).to_text()
        ));
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_result_at_the_numbers_names_its_symbols_but_not_pi() {
        let values = [("R".to_string(), 2.0), ("M".to_string(), 3.0)].into();
        let two_pi_r = Expr::mul(vec![Expr::int(2), Expr::sym("pi"), Expr::sym("R")]);
        let at = value_at_numbers(&Value::Scalar(two_pi_r), &values).unwrap();
        assert!(at.starts_with("at <math"), "{at}");
        assert!(at.contains("<mn>12.5664</mn>"), "{at}");
        assert!(!at.contains("<mi>M</mi>") && !at.contains("π"), "{at}");
        // A bare symbol or a number has nothing to add.
        assert_eq!(
            value_at_numbers(&Value::Scalar(Expr::sym("M")), &values).unwrap(),
            ""
        );
        assert_eq!(
            value_at_numbers(&Value::Scalar(Expr::int(4)), &values).unwrap(),
            ""
        );
    }
}
