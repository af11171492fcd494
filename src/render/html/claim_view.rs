//! A claim of the notes as the templates show it: its statement, the notes' side and the
//! derived side as MathML, and whether the derived side is worth showing beside an agreement.

use super::guard::Guard;
use super::math;
use super::prose::{author_html, prose_html};
use crate::document::words::number;
use crate::document::words::{claim_lead, claim_shows_formula};
use crate::model::catalogue::quantity_symbol;
use crate::model::value::Value;
use crate::notation::{Formula, Names, Tex, linebreak};
use crate::render::RenderError;
use crate::scene::Verdict;
use crate::verify::ClaimResult;
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ClaimView {
    /// The notes' equation the claim is, empty where it names none.
    pub eq: String,
    pub statement: String,
    /// The statement as HTML: its `$…$` mathematics as MathML.
    pub statement_html: String,
    pub verdict: String,
    /// The quantity claimed, the notes' formula for it and the derived one, as MathML (empty
    /// when not checkable).
    pub quantity: String,
    pub notes: String,
    pub derived: String,
    /// An agreeing claim whose derived form is longer than the notes' (and equal to it).
    pub derived_equal: bool,
    /// Each as HTML, its formulas as MathML.
    pub differences: Vec<String>,
    /// For a number the notes give roughly: how it was rounded to compare.
    pub precision: Option<String>,
    /// The symbols an agreement takes to be positive, as MathML, `, ` between them; empty
    /// where it rests on no such assumption.
    pub positive: String,
    /// The agreement holds where both sides are real (`ClaimResult::where_real`).
    pub where_real: bool,
    /// `notes` or `mistake`.
    pub role: String,
    /// The statement as a lead to its formula (a capital first, no closing full stop), for a
    /// scalar claim whose statement writes no equation of its own.
    pub lead_html: Option<String>,
    /// Both sides are words (a sign), which take no left side.
    pub words: bool,
    /// A scalar claim's notes' and derived sides as displayed formulas, each after the
    /// claim's left side (empty for any other claim).
    pub notes_block: String,
    pub derived_block: String,
}

/// A claim as the templates show it: its statement and its formulas as MathML.
pub(super) fn claim_view(
    page: &crate::document::Page,
    i: usize,
    guard: &mut Guard,
) -> Result<ClaimView, RenderError> {
    let c = &page.claims[i];
    let names = &page.names;
    let render = |e: Option<&crate::cas::Expr>| {
        e.map(|e| math::inline(&e.to_tex_named(names, &quantity_symbol)))
            .transpose()
            .map(Option::unwrap_or_default)
    };
    let notes_tex = c
        .notes
        .as_ref()
        .map(|e| e.to_tex_named(names, &quantity_symbol));
    // The derived side in the form the page prints its result (`Page::claim_derived`).
    let derived_tex =
        c.derived.as_ref().map(
            |v| match page.claim_derived(i).filter(|_| c.precision.is_none()) {
                Some(form) => form.to_tex(names),
                None => derived_tex(v, c.precision.is_some(), names),
            },
        );
    let (same, derived_equal) = derived_beside(c, notes_tex.as_ref(), derived_tex.as_ref());
    read_back_sides(guard, c, notes_tex.as_ref(), derived_tex.as_ref())?;
    let mut derived = match &derived_tex {
        Some(tex) if !derived_equal && !same => math::inline(tex)?,
        _ => String::new(),
    };
    let notes_block = displayed(page, i, notes_tex.as_ref())?;
    let derived_block = displayed(page, i, derived_tex.as_ref())?;
    let mut notes = render(c.notes.as_ref())?;
    let words = c.sign_words().is_some();
    if let Some((said, found)) = c.sign_words() {
        notes = tera::escape_html(said);
        derived = tera::escape_html(found);
    }
    Ok(ClaimView {
        quantity: left_side(page, i)?,
        notes_block,
        derived_block,
        // The notes' equation, as the handouts name it: none for a step's `gives` that cites
        // none (its `eq` is then the step's name, which a reader must not see).
        eq: page.claim_equation(i).unwrap_or_default(),
        statement: c.statement.clone(),
        statement_html: author_html(&c.statement)?,
        lead_html: claim_lead(&c.statement)
            .filter(|_| claim_shows_formula(page, i))
            .map(|l| author_html(&l))
            .transpose()?,
        words,
        verdict: c.verdict.as_str().into(),
        notes,
        derived,
        derived_equal,
        differences: c
            .differences
            .iter()
            .map(|p| prose_html(p, names))
            .collect::<Result<_, _>>()?,
        precision: c.precision.clone(),
        positive: c
            .positive
            .iter()
            .map(|n| math::inline(&crate::cas::Expr::sym(n).to_tex(names)))
            .collect::<Result<Vec<_>, _>>()?
            .join(", "),
        where_real: c.where_real,
        role: match c.role {
            crate::scene::ClaimRole::Notes => "notes",
            crate::scene::ClaimRole::Mistake => "mistake",
        }
        .into(),
    })
}

/// Whether the derived side is the notes' own (`same`), or is equal to them but much wider
/// (`derived_equal`), beside a claim that agrees. The derived form is shown when it says
/// something the notes' form does not and is about as short; a longer one is equal to the
/// notes' form (their difference simplifies to 0), which the page says instead. It is in
/// `check --json` either way.
fn derived_beside(c: &ClaimResult, notes: Option<&Tex>, derived: Option<&Tex>) -> (bool, bool) {
    let notes_width = notes.map_or(0.0, math::width);
    let agrees = c.verdict == Verdict::Agrees && c.precision.is_none();
    let same =
        agrees && derived.map(|t| &t.source) == Some(notes.map_or(&String::new(), |t| &t.source));
    let derived_equal = agrees
        && !same
        && match derived {
            Some(tex) => math::width(tex) > (2.0 * notes_width).max(linebreak::PHONE),
            None => false,
        };
    (same, derived_equal)
}

/// Each side read back and checked to be what it prints (the notes' formula as the scene
/// writes it; the derived value), the rounded decimal aside.
fn read_back_sides(
    guard: &mut Guard,
    c: &ClaimResult,
    notes: Option<&Tex>,
    derived: Option<&Tex>,
) -> Result<(), RenderError> {
    if let (Some(tex), Some(e)) = (notes, &c.notes) {
        guard.printed(tex, e, c.line)?;
    }
    match (derived, &c.derived, &c.precision) {
        (Some(tex), Some(Value::Scalar(e)), None) => guard.printed(tex, e, c.line)?,
        (Some(tex), Some(v @ Value::Matrix(_)), None) => guard.printed_value(tex, v, c.line)?,
        _ => {}
    }
    Ok(())
}

/// A scalar claim's side as a displayed formula with its left side (`T = …`), which the
/// handouts set on a line of its own: an inline fraction is small on paper and phones.
fn displayed(
    page: &crate::document::Page,
    i: usize,
    side: Option<&Tex>,
) -> Result<String, RenderError> {
    let c = &page.claims[i];
    let scalar = matches!(c.derived, Some(Value::Scalar(_))) && c.sign_words().is_none();
    match (side, scalar) {
        (Some(tex), true) => {
            let row = page.claim_row(i, Formula::Tex(tex.clone()));
            math::block(&row.to_tex(&page.names))
        }
        _ => Ok(String::new()),
    }
}

/// A claim's left side as MathML (`Page::claim_left`), empty where it has none.
fn left_side(page: &crate::document::Page, i: usize) -> Result<String, RenderError> {
    let names = &page.names;
    match page.claim_left(i) {
        Some(f) => math::inline(&f.to_tex(names)),
        None => Ok(String::new()),
    }
}

/// The derived side of a claim; a number the notes give roughly as a decimal (303.6246, not a
/// fraction of 30 digits).
fn derived_tex(v: &Value, rough: bool, names: &Names) -> Tex {
    match v {
        Value::Scalar(e) if rough => match e.eval(&|_| None) {
            Ok(x) => number(x, 7).to_tex(names),
            Err(_) => v.to_tex(names),
        },
        _ => v.to_tex(names),
    }
}
