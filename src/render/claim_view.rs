//! A claim of the notes as the templates show it: its statement, the notes' side and the
//! derived side as MathML, and whether the derived side is worth showing beside an agreement.

use super::guard::Guard;
use super::{ClaimView, RenderError, author_html, math, number, prose_html};
use crate::model::catalogue::quantity_symbol;
use crate::model::value::Value;
use crate::notation::{Tex, linebreak};
use crate::scene::Verdict;

/// A claim as the templates show it: its statement and its formulas as MathML.
pub(super) fn claim_view(
    c: &crate::verify::ClaimResult,
    guard: &mut Guard,
) -> Result<ClaimView, RenderError> {
    let render = |e: Option<&crate::cas::Expr>| {
        e.map(|e| math::inline(&e.to_tex_named(&quantity_symbol)))
            .transpose()
            .map(Option::unwrap_or_default)
    };
    let notes_tex = c.notes.as_ref().map(|e| e.to_tex_named(&quantity_symbol));
    let derived_tex = c
        .derived
        .as_ref()
        .map(|v| derived_tex(v, c.precision.is_some()));
    // Beside a claim that agrees, the derived form is shown when it says something the
    // notes' form does not and is about as short; a longer one is equal to the notes' form
    // (their difference simplifies to 0), which the page says instead. It is in
    // `check --json` either way.
    let notes_width = notes_tex.as_ref().map_or(0.0, math::width);
    let agrees = c.verdict == Verdict::Agrees && c.precision.is_none();
    let same = agrees
        && derived_tex.as_ref().map(|t| &t.source)
            == Some(notes_tex.as_ref().map_or(&String::new(), |t| &t.source));
    let derived_equal = agrees
        && !same
        && match &derived_tex {
            Some(tex) => math::width(tex) > (2.0 * notes_width).max(linebreak::PHONE),
            None => false,
        };
    // Each side read back and checked to be what it prints (the notes' formula as the scene
    // writes it; the derived value), the rounded decimal aside.
    if let (Some(tex), Some(e)) = (&notes_tex, &c.notes) {
        guard.printed(tex, e, c.line)?;
    }
    if let (Some(tex), Some(Value::Scalar(e)), None) = (&derived_tex, &c.derived, &c.precision) {
        guard.printed(tex, e, c.line)?;
    }
    let mut derived = match &derived_tex {
        Some(tex) if !derived_equal && !same => math::inline(tex)?,
        _ => String::new(),
    };
    let mut notes = render(c.notes.as_ref())?;
    if let Some((said, found)) = c.sign_words() {
        notes = tera::escape_html(said);
        derived = tera::escape_html(found);
    }
    Ok(ClaimView {
        quantity: left_side(c)?,
        eq: c.eq.clone(),
        statement: c.statement.clone(),
        statement_html: author_html(&c.statement)?,
        verdict: c.verdict.as_str().into(),
        notes,
        derived,
        derived_equal,
        differences: c
            .differences
            .iter()
            .map(prose_html)
            .collect::<Result<_, _>>()?,
        precision: c.precision.clone(),
        positive: c
            .positive
            .iter()
            .map(|n| math::inline(&crate::cas::Expr::sym(n).to_tex()))
            .collect::<Result<Vec<_>, _>>()?
            .join(", "),
        role: match c.role {
            crate::scene::ClaimRole::Notes => "notes",
            crate::scene::ClaimRole::Mistake => "mistake",
        }
        .into(),
    })
}

/// A claim's left side: the symbol its author gives it, else its quantity where every name in
/// it prints as a symbol (I₁₁, L², the scene's own), else none, and the page prints the
/// claim's formula alone: never a name of mechbook's (`plane_distance_squared`) as a word.
fn left_side(c: &crate::verify::ClaimResult) -> Result<String, RenderError> {
    if let Some(latex) = &c.tex {
        // Scene validation read it; a claim from elsewhere (a cache) is read again here.
        let tex = Tex::read(latex).map_err(|e| RenderError::Math {
            latex: latex.clone(),
            message: e.to_string(),
        })?;
        return math::inline(&tex);
    }
    match &c.quantity {
        Some(q) if !names_a_word(q) => math::inline(&q.to_tex_named(&quantity_symbol)),
        _ => Ok(String::new()),
    }
}

/// Whether an expression names something that would print as a word: a derived quantity with
/// no symbol, or a step's result the scene gives no `tex`.
fn names_a_word(e: &crate::cas::Expr) -> bool {
    e.symbols().iter().any(|s| {
        quantity_symbol(s).is_none() && crate::cas::prints_as_word(s, &crate::cas::typesets)
    })
}

/// The derived side of a claim; a number the notes give roughly as a decimal (303.6246, not a
/// fraction of 30 digits).
fn derived_tex(v: &Value, rough: bool) -> Tex {
    match v {
        Value::Scalar(e) if rough => match e.eval(&|_| None) {
            Ok(x) => number(x, 7).to_tex(),
            Err(_) => v.to_tex(),
        },
        _ => v.to_tex(),
    }
}
