//! A handout's parts as the HTML template shows them: each [`Part`] of the course's documents
//! read off its page's view. What a part shows is decided in `document::handout`; this only
//! looks the pieces up.

use super::prose::prose_html;
use super::{ClaimView, PageView, StepView};
use crate::document::Page;
use crate::document::handout::{Mark, Part, ShownClaim, ShownStep};
use crate::render::RenderError;
use serde::Serialize;

#[derive(Serialize)]
pub struct PartView<'a> {
    pub page: &'a PageView,
    pub steps: Vec<ShownStepView<'a>>,
    pub results: Vec<&'a StepView>,
    pub principal: &'a [StepView],
    pub figures: bool,
    pub claims: Vec<ShownClaimView<'a>>,
}

#[derive(Serialize)]
pub struct ShownStepView<'a> {
    /// The author's reason as a lead, its first letter a capital (the student's handout).
    pub reason: Option<String>,
    /// The step's title, and its reason under the formula (the instructor's handout).
    pub title: Option<String>,
    pub why: Option<String>,
    /// Each line's formula, and its value at the scene's numbers as HTML (empty where it has
    /// none).
    pub lines: Vec<(String, String)>,
    pub check: String,
    pub claims: Vec<ShownClaimView<'a>>,
}

#[derive(Serialize)]
pub struct ShownClaimView<'a> {
    pub claim: &'a ClaimView,
    /// `agrees`, `verdict` or `boxed`.
    pub mark: &'static str,
    pub heading: String,
    pub wrong: &'static str,
    pub right: &'static str,
    pub verdict: bool,
    /// The notes' equation, where the claim names one.
    pub eq: Option<String>,
}

/// The part `part` of `page`, from its view.
pub fn part_view<'a>(
    part: &Part,
    page: &Page,
    view: &'a PageView,
) -> Result<PartView<'a>, RenderError> {
    Ok(PartView {
        page: view,
        steps: part
            .steps
            .iter()
            .map(|s| step_view(s, page, view))
            .collect::<Result<_, _>>()?,
        results: part
            .results
            .iter()
            .filter_map(|&i| view.quantities[i].as_ref())
            .collect(),
        principal: if part.principal { &view.principal } else { &[] },
        figures: part.figures,
        claims: part
            .claims
            .iter()
            .map(|c| claim_view(c, page, view))
            .collect(),
    })
}

fn step_view<'a>(
    s: &ShownStep,
    page: &Page,
    view: &'a PageView,
) -> Result<ShownStepView<'a>, RenderError> {
    let first = &page.steps[s.lines[0]];
    let last = &view.steps[*s.lines.last().unwrap()];
    let (reason, title, why) = if s.reason_first {
        let reason = match first.why.is_empty() {
            true => None,
            false => Some(prose_html(
                &first.student_why_cited().capitalised(),
                &page.names,
            )?),
        };
        (reason, None, None)
    } else {
        (None, Some(last.title.clone()), Some(last.why.clone()))
    };
    Ok(ShownStepView {
        reason,
        title,
        why,
        lines: s
            .lines
            .iter()
            .zip(&s.at)
            .zip(&s.approx)
            .map(|((&l, q), approx)| {
                let at = q
                    .and_then(|q| view.quantities[q].as_ref())
                    .map_or(String::new(), |v| v.at.clone());
                // A number no student reads exactly is shown to six figures.
                let math = match approx {
                    // In the scene's own typesetting, as the page's lines are (`turn_1` is ū₁).
                    Some(f) => super::math::block(&f.to_tex(&page.names))?,
                    None => view.steps[l].math.clone(),
                };
                Ok((math, at))
            })
            .collect::<Result<_, RenderError>>()?,
        check: if s.checks {
            last.check.clone()
        } else {
            String::new()
        },
        claims: s.claims.iter().map(|c| claim_view(c, page, view)).collect(),
    })
}

fn claim_view<'a>(c: &ShownClaim, page: &Page, view: &'a PageView) -> ShownClaimView<'a> {
    let (mark, heading, wrong, right, verdict) = match &c.mark {
        Mark::Agrees => ("agrees", String::new(), "", "", false),
        Mark::Verdict => ("verdict", String::new(), "", "", true),
        Mark::Boxed {
            heading,
            wrong,
            right,
            verdict,
        } => ("boxed", heading.clone(), *wrong, *right, *verdict),
    };
    ShownClaimView {
        claim: &view.claims[c.claim],
        mark,
        heading,
        wrong,
        right,
        verdict,
        eq: page.claim_equation(c.claim),
    }
}
