//! A scene's page as the HTML templates see it ([`PageView`]): its steps, results, numbers,
//! claims and figures, each formula converted to MathML.

use super::claim_view::ClaimView;
use super::prose::{author_html, prose_html, unit_html};
use super::{guard, math};
use crate::base::format::sci;
use crate::cas::Expr;
use crate::document::words::{self, check_sentence, result_equation, result_heading, values_at};
use crate::document::{At, Link, Page, PrincipalValues};
use crate::model::value::Value;
use crate::notation::{Formula, Names};
use crate::render::RenderError;
use serde::{Deserialize, Serialize};

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
    /// The caption as HTML, its formulas as MathML.
    pub desc: String,
    /// The caption in plain text, for the image's alt text.
    pub alt: String,
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

/// A link whose text is a page's title, the title's mathematics as plain text (a link's text
/// in the page's navigation holds no markup).
pub(super) fn plain_link(l: &Link) -> Link {
    Link {
        href: l.href.clone(),
        title: crate::model::prose::plain(&l.title),
    }
}

/// A result at the scene's numbers, to six significant figures: "at m = 1, a = 2:" (the values
/// of the symbols it contains) and the number, vector or matrix as MathML.
fn at_numbers_html(v: &Value, at: &At, names: &Names) -> Result<String, RenderError> {
    Ok(format!(
        "at {}: {}",
        math::inline(&words::at_symbols(at).to_tex(names))?,
        math::inline(&words::at_value(v, at).to_tex(names))?
    ))
}

/// A symbol or coordinate as MathML, and what it stands for as HTML with its unit.
fn named_with_unit(
    page: &Page,
    name: &str,
    meaning: &str,
) -> Result<(String, String), RenderError> {
    let unit = page
        .units
        .get(name)
        .map_or(String::new(), |u| format!(" ({})", unit_html(u)));
    Ok((
        math::mathml(&Expr::sym(name).to_tex(&page.names), false)?,
        format!("{}{unit}", author_html(meaning)?),
    ))
}

/// An author's step's numeric check in one sentence (escaped for HTML).
fn check_text(c: &crate::verify::StepCheck) -> String {
    tera::escape_html(&check_sentence(c))
}

/// The HTML view of one page, its names typeset as the scene says. `timings` adds measured
/// seconds to the numeric table.
pub fn page_view(page: &Page, timings: bool) -> Result<PageView, RenderError> {
    let names = &page.names;
    let mut guard = guard::Guard::for_page(page);
    let steps = step_views(page, &mut guard)?;
    let quantities = quantity_views(page, &mut guard)?;
    let principal = principal_views(page)?;
    let results = quantities
        .iter()
        .flatten()
        .chain(&principal)
        .cloned()
        .collect();
    let numeric = numeric_rows(page, timings);
    let claims = (0..page.claims.len())
        .map(|i| super::claim_view::claim_view(page, i, &mut guard))
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
                let (symbol, meaning) = named_with_unit(page, k, v)?;
                Ok((symbol, v.clone(), meaning))
            })
            .collect::<Result<_, RenderError>>()?,
        definitions: page
            .definitions
            .iter()
            .map(|(k, e)| {
                math::inline(
                    &Formula::equation(Formula::Expr(Expr::sym(k)), e.clone()).to_tex(names),
                )
            })
            .collect::<Result<_, RenderError>>()?,
        coordinates: page
            .coordinates
            .iter()
            // With its unit, as the PDF's setup and the symbols give theirs.
            .map(|(k, v)| named_with_unit(page, k, v))
            .collect::<Result<_, RenderError>>()?,
        bodies: page
            .bodies
            .iter()
            .map(|p| prose_html(p, names))
            .collect::<Result<_, RenderError>>()?,
        steps,
        results,
        quantities,
        principal,
        numeric,
        errata: page.errata,
        claims,
        figures: figure_views(page, names, timings)?,
        passed: page.passed,
        prev: page.prev.as_ref().map(plain_link),
        next: page.next.as_ref().map(plain_link),
    })
}

/// The derivation's lines, each read back by the guard.
fn step_views(page: &Page, guard: &mut guard::Guard) -> Result<Vec<StepView>, RenderError> {
    let names = &page.names;
    page.steps
        .iter()
        .map(|st| {
            let tex = st.statement.to_tex(names);
            guard.step(st, &tex)?;
            Ok(StepView {
                title: prose_html(&st.title, names)?,
                math: math::block(&tex)?,
                why: prose_html(&st.why_cited(), names)?,
                at: String::new(),
                check: st.check.as_ref().map(check_text).unwrap_or_default(),
            })
        })
        .collect()
}

/// Each quantity the page lists as a result (none for a working quantity), read back by the
/// guard.
fn quantity_views(
    page: &Page,
    guard: &mut guard::Guard,
) -> Result<Vec<Option<StepView>>, RenderError> {
    let names = &page.names;
    let mut quantities = Vec::new();
    for q in &page.quantities {
        quantities.push(match q.is_result {
            true => Some(StepView {
                title: result_heading(q),
                math: match &q.symbol {
                    Some(symbol) => {
                        let tex = result_equation(symbol, &q.value).to_tex(names);
                        if let Value::Scalar(derived) = &q.derived {
                            guard.printed(&tex, derived, page.line)?;
                        }
                        math::block(&tex)?
                    }
                    None => {
                        let tex = q.formula().to_tex(names);
                        guard.printed_value(&tex, &q.derived, page.line)?;
                        math::block(&tex)?
                    }
                },
                why: String::new(),
                at: match &q.at {
                    Some(at) => at_numbers_html(&q.value, at, names)?,
                    None => String::new(),
                },
                check: String::new(),
            }),
            false => None,
        });
    }
    Ok(quantities)
}

/// The exact principal axes, then the principal moments at the scene's values.
fn principal_views(page: &Page) -> Result<Vec<StepView>, RenderError> {
    let names = &page.names;
    let mut principal = Vec::new();
    for sp in &page.principal_axes {
        principal.push(StepView {
            title: words::principal_axis_heading(sp),
            math: math::block(&words::principal_axis(sp).to_tex(names))?,
            why: String::new(),
            at: String::new(),
            check: String::new(),
        });
    }
    if let Some(p) = &page.principal_values {
        principal.push(principal_values_view(p, names)?);
    }
    Ok(principal)
}

/// The numeric table: each quadrature's body, method, points and errors.
fn numeric_rows(page: &Page, timings: bool) -> Vec<NumericRow> {
    page.numeric
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
        .collect()
}

/// Each plot with the error and cost of each numeric result it draws.
fn figure_views(page: &Page, names: &Names, timings: bool) -> Result<Vec<FigureView>, RenderError> {
    page.figures
        .iter()
        .map(|f| {
            Ok(FigureView {
                file: f.file.clone(),
                title: f.title.clone(),
                desc: prose_html(&f.desc, names)?,
                alt: f.desc.to_plain(names),
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
        })
        .collect()
}

/// The principal moments as numbers, with the axes when only the numerics give them, and how
/// well the two routes agree.
fn principal_values_view(p: &PrincipalValues, names: &Names) -> Result<StepView, RenderError> {
    let row = words::principal_values(p);
    Ok(StepView {
        at: String::new(),
        check: String::new(),
        title: words::PRINCIPAL_VALUES_HEADING.into(),
        math: math::block(&row.to_tex(names))?,
        why: format!(
            "at {}: {}",
            math::inline(&values_at(&p.values, &p.units).to_tex(names))?,
            tera::escape_html(&words::principal_values_agree(p))
        ),
    })
}

#[cfg(test)]
#[path = "page_tests.rs"]
mod tests;
