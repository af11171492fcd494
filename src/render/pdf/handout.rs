//! A lecture's handouts as Typst: each [`Part`] of the course's documents, as the HTML
//! handout (`templates/handout.html`) shows it. What a part holds is decided in
//! `document::handout`: the student's summary (setup, the author's steps under their reasons,
//! the claims that agree and the marked mistakes and errata) and the instructor's worked
//! solutions (contents, every step with its reason and check, the results, the figures).

use super::markup::{Markup, expr, formula, said_equation, said_symbol, symbol};
use super::quantities::{said_unit, unit_typst};
use crate::cas::Expr;
use crate::document::handout::{Mark, Part, ShownClaim, ShownStep};
use crate::document::{At, Page, PrincipalAxis, PrincipalValues, Quantity, words};
use crate::model::catalogue::quantity_symbol;
use crate::model::value::Value;
use crate::notation::{Formula, Names, Op, Tex};
use crate::render::RenderError;

/// The body of a handout: one section per page.
pub fn handout(
    m: &mut Markup,
    parts: &[(&Part, &Page)],
    instructor: bool,
) -> Result<(), RenderError> {
    if parts.is_empty() {
        m.text("This lecture's scenes are all problems: they are on its problem sheet.")
            .par();
    }
    if instructor && parts.len() > 1 {
        m.raw("#outline(title: [Contents], depth: 2)\n#pagebreak(weak: true)\n");
    }
    for (part, page) in parts {
        m.scene_part(&page.source, page.line, &page.names, |m| {
            section(m, part, page)
        })
        .map_err(|e| e.in_scene(&page.source))?;
    }
    Ok(())
}

fn section(m: &mut Markup, part: &Part, page: &Page) -> Result<(), RenderError> {
    let names = &page.names;
    m.heading(2, &page.title)?;
    if !page.section.is_empty() || !page.equations.is_empty() {
        m.raw("#text(9pt)[");
        m.text(&format!(
            "Notes, lecture {}{}{}",
            page.lecture,
            if page.section.is_empty() {
                String::new()
            } else {
                format!(", section {}", page.section)
            },
            if page.equations.is_empty() {
                String::new()
            } else {
                format!(", eqs. ({})", page.equations.join(", "))
            }
        ));
        m.raw("]\n\n");
    }
    for b in &page.bodies {
        m.raw("- ").prose(b)?.line();
    }
    setup(m, page)?;
    for (name, e) in &page.definitions {
        let definition = Formula::Row(vec![
            Formula::Expr(Expr::sym(name)),
            Formula::Op(Op::Equals),
            Formula::Expr(e.clone()),
        ]);
        m.raw("- ")
            .inline(
                &formula(&definition, names)?,
                &said_equation(name, &e.to_tex(names).spoken(), names),
            )
            .line();
    }
    for (k, step) in part.steps.iter().enumerate() {
        shown_step(m, page, k + 1, step)?;
    }
    results(m, part, page)?;
    if part.figures {
        for f in &page.figures {
            m.raw(&format!(
                "\n#figure(image({}, width: 100%, alt: {}), caption: [",
                crate::base::literal::typst_string(&f.file),
                crate::base::literal::typst_string(&f.title)
            ));
            m.prose(&f.desc)?.raw("])\n");
        }
    }
    claims(m, part, page)
}

/// The coordinates and symbols, each with what it stands for (and its unit).
fn setup(m: &mut Markup, page: &Page) -> Result<(), RenderError> {
    let names = &page.names;
    if page.coordinates.is_empty() && page.symbols.is_empty() {
        return Ok(());
    }
    m.raw("#grid(columns: (auto, 1fr), column-gutter: 1em, row-gutter: 0.5em,\n");
    for (name, meaning) in page.coordinates.iter().chain(&page.symbols) {
        m.raw("[")
            .inline(&symbol(name, names), &said_symbol(name, names))
            .raw("], [");
        m.author(meaning)?;
        if let Some(u) = page.units.get(name) {
            // Typeset as the pages and the sheets set units: kg m², not kg m^2.
            m.text(" (")
                .inline(&unit_typst(u), said_unit(u).trim())
                .text(")");
        }
        m.raw("],\n");
    }
    m.raw(")\n\n");
    Ok(())
}

/// A step: the student's under its reason; the instructor's under its title, with its reason
/// and numeric check below.
fn shown_step(m: &mut Markup, page: &Page, n: usize, s: &ShownStep) -> Result<(), RenderError> {
    let names = &page.names;
    let first = &page.steps[s.lines[0]];
    let last = &page.steps[*s.lines.last().unwrap()];
    m.raw(&format!("\n#block(width: 100%, breakable: true)[*{n}.* "));
    if s.reason_first {
        m.prose(&first.student_why_cited().capitalised())?;
        m.raw("\n");
    } else {
        m.raw("*").prose(&last.title)?.raw("*");
    }
    for ((&l, at), approx) in s.lines.iter().zip(&s.at).zip(&s.approx) {
        // A number no student reads exactly is shown to six figures.
        let statement = approx.as_ref().unwrap_or(&page.steps[l].statement);
        let tex = statement.to_tex(names);
        m.block(&tex, &tex.spoken())?;
        if let Some(q) = at.map(|q| &page.quantities[q])
            && let Some(at) = &q.at
        {
            at_numbers(m, &q.value, at, names)?;
        }
    }
    if !s.reason_first {
        m.raw("#text(9.5pt)[");
        m.prose(&last.why_cited())?;
        if let Some(c) = last.check.as_ref().filter(|_| s.checks) {
            m.raw(" — ").text(&words::check_sentence(c));
        }
        m.raw("]\n");
    }
    for c in &s.claims {
        match &c.mark {
            Mark::Agrees => {
                m.raw("#text(9.5pt)[");
                m.text(&match page.claim_equation(c.claim) {
                    Some(eq) => format!("As in the notes, eq. ({eq})"),
                    None => "As in the notes".to_string(),
                });
                // The symbols whose positivity the agreement rests on.
                positive(m, &page.claims[c.claim], names);
                m.text(".");
                m.raw("]\n");
            }
            _ => shown_claim(m, page, c)?,
        }
    }
    m.raw("]\n");
    Ok(())
}

fn results(m: &mut Markup, part: &Part, page: &Page) -> Result<(), RenderError> {
    let names = &page.names;
    for q in part.results.iter().map(|&i| &page.quantities[i]) {
        quantity(m, q, names)?;
    }
    if !part.principal {
        return Ok(());
    }
    for sp in &page.principal_axes {
        principal_axis(m, sp, names)?;
    }
    if let Some(p) = &page.principal_values {
        principal_values(m, p, names)?;
    }
    Ok(())
}

/// One result: a step's by its own equation, any other under its heading; at the scene's
/// numbers where it has them.
fn quantity(m: &mut Markup, q: &Quantity, names: &Names) -> Result<(), RenderError> {
    match &q.symbol {
        // A step's result, named by its own equation (`ẍ₁ = …`).
        Some(symbol) => {
            let statement = words::result_equation(symbol, &q.value);
            let tex = statement.to_tex(names);
            m.block(&tex, &tex.spoken())?;
        }
        None => {
            m.heading(3, &words::result_heading(q))?;
            match &q.matrix {
                Some(_) => {
                    let value = q.formula();
                    let tex = value.to_tex(names);
                    m.block(&tex, &tex.spoken())?;
                }
                None => {
                    let tex = q.value.to_expr().to_tex(names);
                    m.block(&tex, &tex.spoken())?;
                }
            }
        }
    }
    if let Some(at) = &q.at {
        at_numbers(m, &q.value, at, names)?;
    }
    Ok(())
}

/// A principal moment with its axis, its plane of axes, or every axis, as the page prints it.
fn principal_axis(m: &mut Markup, sp: &PrincipalAxis, names: &Names) -> Result<(), RenderError> {
    m.heading(3, &words::principal_axis_heading(sp))?;
    let tex = words::principal_axis(sp).to_tex(names);
    m.block(&tex, &tex.spoken())?;
    Ok(())
}

/// The principal moments at the scene's values, and the eigen-solver's agreement with them.
fn principal_values(m: &mut Markup, p: &PrincipalValues, names: &Names) -> Result<(), RenderError> {
    m.heading(3, words::PRINCIPAL_VALUES_HEADING)?;
    let tex = words::principal_values(p).to_tex(names);
    m.block(&tex, &tex.spoken())?;
    m.raw("#text(9.5pt)[").text("at ");
    let values = words::values_at(&p.values, &p.units);
    m.inline(
        &super::markup::formula(&values, names)?,
        &values.to_tex(names).spoken(),
    );
    m.text(&format!(": {}", words::principal_values_agree(p)));
    m.raw("]\n");
    Ok(())
}

/// A result at the scene's numbers, to six significant figures, as the page prints it.
fn at_numbers(m: &mut Markup, v: &Value, at: &At, names: &Names) -> Result<(), RenderError> {
    let symbols = words::at_symbols(at).to_tex(names);
    let value = words::at_value(v, at).to_tex(names);
    m.text("at ")
        .inline(&super::markup::math(&symbols)?, &symbols.spoken())
        .text(": ")
        .display(&super::markup::math(&value)?, &value.spoken())
        .par();
    Ok(())
}

fn claims(m: &mut Markup, part: &Part, page: &Page) -> Result<(), RenderError> {
    if part.claims.is_empty() {
        return Ok(());
    }
    m.heading(3, "The notes claim")?;
    for c in &part.claims {
        m.raw("- ");
        shown_claim(m, page, c)?;
    }
    Ok(())
}

/// A claim: in a list, with its verdict for the instructor, or with its formula as in the
/// notes for the student; or boxed with both forms.
fn shown_claim(m: &mut Markup, page: &Page, shown: &ShownClaim) -> Result<(), RenderError> {
    let names = &page.names;
    let i = shown.claim;
    let c = &page.claims[i];
    // A scalar claim's notes' side after its left side; a vector's or a matrix's as a column
    // of its own (below).
    let scalar = matches!(c.derived, Some(Value::Scalar(_)));
    let notes = c
        .notes
        .as_ref()
        .filter(|_| scalar)
        // Its catalogue names as their symbols (I_xx for `inertia_tensor[0][0]`), as the page.
        .map(|e| page.claim_row(i, Formula::Tex(e.to_tex_named(names, &quantity_symbol))));
    let Mark::Boxed {
        heading,
        wrong,
        right,
        verdict,
    } = &shown.mark
    else {
        return claim_in_list(m, page, shown, notes);
    };
    m.raw("#block(stroke: 0.6pt, inset: 6pt, radius: 2pt, breakable: false)[*")
        .text(heading)
        .raw("*");
    if *verdict {
        m.text(&format!(" — {}", c.verdict.as_str()));
    }
    m.raw(" \\\n");
    m.author(&c.statement)?;
    m.raw(" \\\n");
    if let Some((said, found)) = c.sign_words() {
        // A sign in words: "negative for every choice", not −1.
        m.text(&format!("{wrong}: {said}. {right}: {found}."))
            .raw("]\n");
        return Ok(());
    }
    m.text(&format!("{wrong}: "));
    if let Some(notes) = notes {
        let tex = notes.to_tex(names);
        m.block(&tex, &tex.spoken())?;
    } else if let Some(e) = &c.notes {
        let tex = e.to_tex_named(names, &quantity_symbol);
        m.block(&tex, &tex.spoken())?;
    }
    m.text(&format!("{right}: "));
    let derived = derived_side(page, i);
    if let Some(derived) = derived {
        let tex = derived?;
        m.block(&tex, &tex.spoken())?;
    }
    m.raw("]\n");
    Ok(())
}

/// A claim in the list of claims: the statement and its verdict, or, where it agrees and
/// leads into its formula, the statement, the formula displayed and "As in the notes".
fn claim_in_list(
    m: &mut Markup,
    page: &Page,
    shown: &ShownClaim,
    notes: Option<Formula>,
) -> Result<(), RenderError> {
    let names = &page.names;
    let i = shown.claim;
    let c = &page.claims[i];
    let lead = words::claim_lead(&c.statement).filter(|_| words::claim_shows_formula(page, i));
    if let (Mark::Agrees, Some(notes), None, Some(lead)) =
        (&shown.mark, notes, c.sign_words(), lead)
    {
        // "The tension in the string:", T = 2m₁m₂g/(m₁ + m₂) displayed, "As in the notes,
        // eq. (9.1)."
        // One block, so that the formula and the sentence after it stay in the list item.
        m.raw("#block[");
        m.author(&lead)?.text(":");
        let tex = notes.to_tex(names);
        m.block(&tex, &tex.spoken())?;
        m.text("As in the notes");
        if let Some(eq) = page.claim_equation(i) {
            m.text(&format!(", eq. ({eq})"));
        }
        positive(m, c, names);
        m.text(".");
        m.raw("]");
        m.line();
        return Ok(());
    }
    if let Some(eq) = page.claim_equation(i) {
        m.text(&format!("({eq}) "));
    }
    m.author(&c.statement)?;
    if shown.mark == Mark::Verdict {
        m.text(&format!(" — {}", c.verdict.as_str()));
    }
    m.line();
    Ok(())
}

/// A boxed claim's derived side, as its tree.
fn derived_side(page: &Page, i: usize) -> Option<Result<Tex, RenderError>> {
    let names = &page.names;
    let c = &page.claims[i];
    c.derived.as_ref().map(|v| match v {
        Value::Scalar(e) if c.precision.is_some() => Ok(match e.eval(&|_| None) {
            Ok(x) if x.is_finite() => words::number(x, 7).to_tex(Names::none()),
            _ => e.to_tex(names),
        }),
        // The form the page prints for the result (`Page::claim_derived`).
        Value::Scalar(_) => {
            let side = page
                .claim_derived(i)
                .unwrap_or_else(|| Formula::Expr(v.to_expr()));
            Ok(page.claim_row(i, side).to_tex(names))
        }
        // A vector or a matrix as a column of its own, without a left side; a matrix with its
        // factor out as its result prints.
        _ => Ok(
            match page
                .claim_derived(i)
                .filter(|_| matches!(v, Value::Matrix(_)))
            {
                Some(f) => f.to_tex(names),
                None => v.to_expr().to_tex(names),
            },
        ),
    })
}

/// ", for positive g, l": the symbols an agreement rests on being positive, and ", where both
/// sides are real" where it rests on that.
fn positive(m: &mut Markup, c: &crate::verify::ClaimResult, names: &Names) {
    for (k, name) in c.positive.iter().enumerate() {
        m.text(if k == 0 { ", for positive " } else { ", " });
        let e = crate::cas::Expr::sym(name);
        m.inline(&expr(&e, names), &e.to_tex(names).spoken());
    }
    if c.where_real {
        m.text(", where both sides are real");
    }
}
