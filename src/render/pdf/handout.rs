//! A lecture's handouts as Typst: the student's summary (setup, results, the claims that agree
//! and the marked mistakes and errata, each with its correct form) and the instructor's worked
//! solutions (contents, every step with its reason and check, the figures). The same choices
//! as the HTML handouts (`templates/handout.html`), from the same [`Page`]s.

use super::markup::{Markup, formula_and_broken, number, symbol};
use crate::base::format::sci;
use crate::derive::ExactBasis;
use crate::document::{At, Page};
use crate::model::catalogue::quantity_symbol;
use crate::model::value::Value;
use crate::notation::symbol_tex;
use crate::render::RenderError;
use crate::scene::{ClaimRole, Verdict};

/// The body of a handout: one section per page.
pub fn handout(m: &mut Markup, pages: &[&Page], instructor: bool) -> Result<(), RenderError> {
    if pages.is_empty() {
        m.text("This lecture's scenes are all problems: they are on its problem sheet.")
            .par();
    }
    if instructor && pages.len() > 1 {
        m.raw("#outline(title: [Contents], depth: 2)\n#pagebreak(weak: true)\n");
    }
    for page in pages {
        m.scene_part(&page.source, page.line, |m| {
            crate::notation::typeset_as(&page.tex, || section(m, page, instructor))
        })
        .map_err(|e| e.in_scene(&page.source))?;
    }
    Ok(())
}

fn section(m: &mut Markup, page: &Page, instructor: bool) -> Result<(), RenderError> {
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
        m.raw("- ").text(b).line();
    }
    for (name, e) in &page.definitions {
        m.raw("- ")
            .inline(&format!("{} = {}", symbol(name), e.to_typst()))
            .line();
    }
    if instructor {
        steps(m, page)?;
    }
    results(m, page)?;
    if instructor {
        for f in &page.figures {
            m.raw(&format!(
                "\n#figure(image({}, width: 100%, alt: {}), caption: [",
                crate::base::typst::typst_string(&f.file),
                crate::base::typst::typst_string(&f.title)
            ));
            m.text(&f.desc).raw("])\n");
        }
    }
    claims(m, page, instructor)
}

fn steps(m: &mut Markup, page: &Page) -> Result<(), RenderError> {
    for (i, st) in page.steps.iter().enumerate() {
        m.raw(&format!(
            "\n#block(width: 100%, breakable: true)[*{}. ",
            i + 1
        ))
        .text(&st.title)
        .raw("*");
        let (whole, broken) = formula_and_broken(&st.statement)?;
        m.block(&whole, &broken);
        m.raw("#text(9.5pt)[");
        m.prose(&st.why_cited())?;
        if let Some(c) = &st.check {
            m.raw(" — ").text(&crate::render::check_sentence(c));
        }
        m.raw("]]\n");
    }
    Ok(())
}

fn results(m: &mut Markup, page: &Page) -> Result<(), RenderError> {
    for q in page.quantities.iter().filter(|q| q.is_result) {
        m.heading(
            3,
            &crate::render::problems::capitalised(&q.name.replace('_', " ")),
        )?;
        let value = q.value.to_expr();
        m.block(&value.to_typst(), &value.to_typst_breakable());
        if let Some(at) = &q.at {
            at_numbers(m, &q.value, at);
        }
    }
    for sp in &page.principal_axes {
        m.heading(
            3,
            &format!("Principal moment (multiplicity {})", sp.multiplicity),
        )?;
        let dir = match &sp.basis {
            ExactBasis::Axis(a) => format!(
                "quad \"along\" {}",
                Value::Vector(a.clone()).to_expr().to_typst()
            ),
            ExactBasis::PlaneNormalTo(n) => format!(
                "quad \"every axis\" perp {}",
                Value::Vector(n.clone()).to_expr().to_typst()
            ),
            ExactBasis::All => "quad \"every axis\"".into(),
        };
        let line = format!("{} {dir}", sp.value.to_typst());
        m.block(&line, &line);
    }
    if let Some(p) = &page.principal_values {
        m.heading(3, "Principal moments at the scene's values")?;
        let values: Vec<String> = p.exact.iter().map(|v| number(*v, 6)).collect();
        let line = format!("{} = {}", symbol(&p.letter), values.join("\\, thin "));
        m.block(&line, &line);
        m.raw("#text(9.5pt)[").text(&format!(
            "at {}: the eigen-solver on the exact tensor agrees to {} (relative)",
            p.values
                .iter()
                .map(|(k, x)| format!("{k} = {x}"))
                .collect::<Vec<_>>()
                .join(", "),
            sci(p.error)
        ));
        m.raw("]\n");
    }
    Ok(())
}

/// A result at the scene's numbers, to six significant figures.
fn at_numbers(m: &mut Markup, v: &Value, at: &At) {
    let n: Vec<String> = crate::render::at_entries(at)
        .into_iter()
        .map(|x| number(x, 6))
        .collect();
    let symbols: Vec<String> = at
        .symbols
        .iter()
        .map(|(k, x)| format!("{} = {}", symbol(k), number(*x, 6)))
        .collect();
    m.text("at ")
        .inline(&symbols.join("\\, thin "))
        .text(": ")
        .display(&numbers_typst(v, &n))
        .par();
}

/// Numbers in the shape of `v`: a number, a row or a matrix.
pub fn numbers_typst(v: &Value, n: &[String]) -> String {
    match v {
        Value::Scalar(_) => n[0].clone(),
        Value::Vector(_) => format!("mat({})", n.join(", ")),
        Value::Matrix(_) => format!(
            "mat({})",
            n.chunks(3)
                .map(|row| row.join(", "))
                .collect::<Vec<_>>()
                .join("; ")
        ),
    }
}

fn claims(m: &mut Markup, page: &Page, instructor: bool) -> Result<(), RenderError> {
    if page.claims.is_empty() {
        return Ok(());
    }
    m.heading(3, "The notes claim")?;
    for c in &page.claims {
        let notes = c
            .notes
            .as_ref()
            .map(|e| {
                e.to_typst_named(&|q| {
                    quantity_symbol(q).and_then(|t| symbol_tex(t).to_typst().ok())
                })
            })
            .unwrap_or_default();
        let derived = c.derived.as_ref().map(|v| match v {
            Value::Scalar(e) if c.precision.is_some() => {
                let x = e
                    .eval(&|_| None)
                    .map_or_else(|_| e.to_typst(), |x| number(x, 7));
                (x.clone(), x)
            }
            _ => {
                let e = v.to_expr();
                (e.to_typst(), e.to_typst_breakable())
            }
        });
        let (derived, derived_broken) = derived.unwrap_or_default();
        let mistake = c.role == ClaimRole::Mistake;
        let disagrees = c.verdict == Verdict::Disagrees;
        if !instructor && !mistake && !disagrees && c.verdict != Verdict::Agrees {
            continue;
        }
        m.raw("- ");
        if mistake || disagrees {
            let head = match (mistake, instructor) {
                (true, false) => "A common mistake, not the notes' claim".to_string(),
                (true, true) => "A common mistake".to_string(),
                (false, false) => format!("Erratum: eq. ({}) of the notes is wrong", c.eq),
                (false, true) => format!("Erratum, eq. ({})", c.eq),
            };
            m.raw("#block(stroke: 0.6pt, inset: 6pt, radius: 2pt, breakable: false)[*")
                .text(&head)
                .raw("* \\\n");
            m.author(&c.statement)?;
            m.raw(" \\\n")
                .text(if mistake {
                    "The mistaken form: "
                } else {
                    "The notes: "
                })
                .block(&notes, &notes)
                .text(if instructor { "Derived: " } else { "Correct: " })
                .block(&derived, &derived_broken)
                .raw("]\n");
        } else {
            m.text(&format!("({}) ", c.eq));
            m.author(&c.statement)?;
            if instructor {
                m.text(&format!(" — {}", c.verdict.as_str()));
            }
            m.line();
        }
    }
    Ok(())
}
