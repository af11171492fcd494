//! A lecture's problem sheet and answer key as Typst, from the same [`Sheet`] as the HTML: the
//! student's sheet is written from the statements and values alone, so no answer reaches it.
//! Each sheet variant starts a page and names itself at the top of its pages; a student's
//! paper (from a roster) has their name and ID at the top of every page.

use super::markup::{Markup, formula, said_equation, symbol};
use super::quantities::{numbers_typst, said_unit, unit_typst};
use crate::base::format::capitalised;
use crate::document::{KEY_FIGURES, ROUNDED_FIGURES, answer_words};
use crate::document::{Problem, Sheet, SheetProblem, Variant};
use crate::render::RenderError;
use crate::render::memo::Recall;

use crate::scene::roster::Student;

/// Starts sheet variant `k` (the `i`th of its document) on a new page, headed with the
/// document's `head` on the left and `Variant k`, or the student's name, ID and variant, on the
/// right; returns that right-hand head. The variant is a scoped block (`#[`, closed by
/// [`end_variant`]): its page rule then ends with it, where a plain `#set` would style all that
/// follows, every later variant nested one level deeper, which Typst laid out in quadratic time
/// (a key of 5,000 variants ran for over ten minutes at 3 GB).
fn start_variant(
    m: &mut Markup,
    head: &str,
    sheet: &Sheet,
    (i, k, student): (usize, usize, Option<&Student>),
) -> String {
    let number = sheet.variants[k].number;
    if i > 0 {
        m.raw("#pagebreak()\n");
    }
    let right = match student {
        Some(s) => format!("{} · {} · Variant {number}", s.name, s.id),
        None => format!("Variant {number}"),
    };
    m.raw(&format!(
        "#[\n#set page(header: [#set text(8.5pt); #{}#h(1fr)*#{}*])\n",
        crate::base::literal::typst_string(head),
        crate::base::literal::typst_string(&right)
    ));
    right
}

/// A sheet's headings start at level 1, as a tagged PDF's must (PDF/UA-1), set at the sizes of
/// a handout's levels 2 and 3: a problem's heading, and a key's problem under its variant.
///
/// Once a document: a roster's key holds a sheet a student, and each rule set again at the
/// top level styles all that follows it, every later student one level deeper (a key of
/// 1,000 students took 118 s, of 5,000 over ten minutes).
fn sheet_headings(m: &mut Markup) {
    if std::mem::replace(&mut m.sheet_headings, true) {
        return;
    }
    m.raw("#show heading.where(level: 1): set text(12.5pt)\n");
    m.raw("#show heading.where(level: 2): set text(10.5pt)\n");
}

/// Sheet variant `k`'s problems, each as `columns` wrote it, then the end of its block.
fn variant_problems(m: &mut Markup, sheet: &Sheet, k: usize, columns: &mut Columns) {
    for sp in &sheet.variants[k].problems {
        let (_, p) = sheet.problem(sp.problem);
        let part = columns.next(sp.problem);
        m.scene_part(&p.source, p.line, &p.names, |m| {
            m.raw(&part);
        });
    }
    end_variant(m);
}

/// Closes the block [`start_variant`] opened.
fn end_variant(m: &mut Markup) {
    m.raw("\n]\n");
}

/// The student's sheet: sheet variants `which` (all of them, or one student's), each from a
/// new page, with a line for a name and ID, or the student's own.
pub fn student_sheet(
    m: &mut Markup,
    head: &str,
    sheet: &Sheet,
    which: &[(usize, Option<&Student>)],
    recall: Option<&mut Recall>,
) -> Result<(), RenderError> {
    let mut columns = Columns::new(sheet, which, recall, |m, n, p, v, _| problem(m, n, p, v))?;
    sheet_headings(m);
    for (i, (k, student)) in which.iter().enumerate() {
        start_variant(m, head, sheet, (i, *k, *student));
        match student {
            Some(s) => {
                m.raw("#grid(columns: (1fr, auto), [*Name:* ")
                    .text(&s.name)
                    .raw("], [*ID:* ")
                    .text(&s.id)
                    .raw("])\n");
            }
            None => {
                m.raw(
                    "#grid(columns: (1fr, auto), [*Name:* #box(width: 6cm, repeat[.])], [*ID:* #box(width: 3.5cm, repeat[.])])\n",
                );
            }
        }
        variant_problems(m, sheet, *k, &mut columns);
    }
    Ok(())
}

fn problem(m: &mut Markup, number: usize, p: &Problem, v: &Variant) -> Result<(), RenderError> {
    m.raw("\n#block(breakable: false)[\n#heading(level: 1)[")
        .text(&format!("Problem {number}: "));
    m.author(&p.title)?;
    m.raw("]\n");
    m.prose(&v.statement)?;
    m.raw("\n#block(width: 100%, height: 7cm, stroke: (paint: luma(180), thickness: 0.5pt), inset: 6pt)[#text(8pt, fill: luma(120))[Working]]\n]\n");
    Ok(())
}

/// The answer key: for each sheet variant in `which`, its problems' values and answers, exact
/// and to four figures, each from a new page, headed with the student it went to, if any.
pub fn key(
    m: &mut Markup,
    head: &str,
    sheet: &Sheet,
    which: &[(usize, Option<&Student>)],
    recall: Option<&mut Recall>,
) -> Result<(), RenderError> {
    // The site's key answers a problem with fewer variants than the sheet once, in a section
    // of its own, as the HTML key does (the sheet's choice, `document::Sheet::shared`); a
    // student's key answers their own variant where it is asked.
    let whole_sheet = which.iter().all(|(_, student)| student.is_none());
    let mut columns = Columns::new(sheet, which, recall, |m, n, p, _, sp| {
        key_entry(m, whole_sheet, sp, n, p)
    })?;
    sheet_headings(m);
    if whole_sheet && !sheet.shared.is_empty() {
        m.raw("\n#heading(level: 1)[")
            .text(SHARED)
            .raw("]\n#text(9pt)[")
            .text("Each of their variants is answered once here, and each sheet variant says which one it uses.")
            .raw("]\n");
        for answer in &sheet.shared {
            let (n, p) = sheet.problem(answer.problem);
            let v = &p.variants[answer.variant];
            let heading = format!("Problem {n}, its variant {}", v.number);
            m.scene_part(&p.source, p.line, &p.names, |m| {
                key_problem(m, &heading, p, v)
            })
            .map_err(|e| e.in_scene(&p.source))?;
        }
    }
    for (i, (k, student)) in which.iter().enumerate() {
        let right = start_variant(m, head, sheet, (i, *k, *student));
        m.raw("\n#heading(level: 1)[").text(&right).raw("]\n");
        variant_problems(m, sheet, *k, &mut columns);
    }
    Ok(())
}

/// A problem in a sheet variant of the key: its answers, or where its shared variant is
/// answered.
fn key_entry(
    m: &mut Markup,
    whole_sheet: bool,
    sp: &SheetProblem,
    n: usize,
    p: &Problem,
) -> Result<(), RenderError> {
    let v = &p.variants[sp.variant];
    if whole_sheet && sp.shared {
        shared_pointer(m, n, p, v)
    } else if sp.shared {
        // A student's own variant of a shared problem, answered here.
        key_problem(m, &format!("Problem {n}, its variant {}", v.number), p, v)
    } else {
        key_problem(m, &format!("Problem {n}"), p, v)
    }
}

/// Each problem's part of a sheet variant, written once per problem for all the sheet variants
/// written (a problem's column): with a memo, a column whose problem is unchanged is recalled.
/// The parts are then taken in the order they are written. The site's documents pass a memo;
/// a roster's papers, each written for one student, do not.
struct Columns {
    parts: Vec<std::vec::IntoIter<String>>,
}

impl Columns {
    fn new(
        sheet: &Sheet,
        which: &[(usize, Option<&Student>)],
        mut recall: Option<&mut Recall>,
        write: impl Fn(&mut Markup, usize, &Problem, &Variant, &SheetProblem) -> Result<(), RenderError>,
    ) -> Result<Columns, RenderError> {
        let mut parts = Vec::new();
        for j in 0..sheet.problems.len() {
            let (n, p) = sheet.problem(j);
            let cells: Vec<SheetProblem> = which
                .iter()
                .flat_map(|(k, _)| sheet.variants[*k].problems.iter())
                .filter(|sp| sp.problem == j)
                .copied()
                .collect();
            let make = || {
                cells
                    .iter()
                    .map(|sp| {
                        let mut m = Markup::of_scene(&p.names);
                        write(&mut m, n, p, &p.variants[sp.variant], sp)?;
                        Ok(m.text)
                    })
                    .collect::<Result<Vec<String>, RenderError>>()
                    .map_err(|e| e.in_scene(&p.source))
            };
            let column = match recall.as_deref_mut() {
                Some(r) => r.recall_or(&format!("{n}"), &[p, &cells], make)?,
                None => make()?,
            };
            parts.push(column.into_iter());
        }
        Ok(Columns { parts })
    }

    /// The next part of problem `j` (an index into the sheet's problems).
    fn next(&mut self, j: usize) -> String {
        self.parts[j].next().expect("a part for each cell")
    }
}

/// The heading of the key's section of shared answers, as on the HTML key.
const SHARED: &str = "Problems with fewer variants than the sheet";

/// A shared problem in a sheet variant of the key: which of its variants, answered where.
fn shared_pointer(
    m: &mut Markup,
    number: usize,
    p: &Problem,
    v: &Variant,
) -> Result<(), RenderError> {
    m.raw("\n#heading(level: 2)[")
        .text(&format!("Problem {number}: "));
    m.author(&p.title)?;
    m.raw("]\n").text(&format!(
        "Its variant {}: answered under {SHARED}.",
        v.number
    ));
    m.raw("\n");
    Ok(())
}

fn key_problem(m: &mut Markup, heading: &str, p: &Problem, v: &Variant) -> Result<(), RenderError> {
    let names = &p.names;
    m.raw("\n#heading(level: 2)[").text(&format!("{heading}: "));
    m.author(&p.title)?;
    m.raw("]\n");
    let given = given_values(v, names)?;
    if !given.is_empty() {
        let (typst, said): (Vec<String>, Vec<String>) = given.into_iter().unzip();
        // Kept on the page of the table that follows, as the heading is kept with it.
        m.raw("#block(sticky: true)[")
            .text("Given: ")
            .inline(&typst.join("\\, quad "), &said.join(", "))
            .raw("]\n");
    }
    // A header row, which Typst keeps with the first row (never alone at a page's foot) and
    // tags as the table's header.
    m.raw("#table(columns: (auto, 1fr, auto), stroke: 0.4pt, inset: 5pt, table.header([*Answer*], [*Exact*], [*Decimal*]),\n");
    for (spec, a) in p.answers.iter().zip(&v.answers) {
        let unit = spec
            .unit
            .as_ref()
            .map_or(String::new(), |u| format!(" thin {}", unit_typst(&u.text)));
        m.raw("[");
        match (&spec.label, spec.bare_quantity()) {
            (Some(words), _) => {
                m.author(&capitalised(words))?;
            }
            (None, Some(q)) => {
                m.text(answer_words(q));
            }
            (None, None) => {
                m.inline(
                    &super::markup::expr(&spec.value, names),
                    &spec.value.to_tex(names).spoken(),
                );
            }
        }
        let said_unit = spec
            .unit
            .as_ref()
            .map_or(String::new(), |u| said_unit(&u.text));
        let exact = a.shown_or_exact().to_expr();
        let numbers = decimals(&a.exact_numbers, KEY_FIGURES);
        m.raw("], [");
        if a.rounded {
            let rounded = decimals(&a.exact_numbers, ROUNDED_FIGURES);
            m.display(
                &format!("approx {}{unit}", numbers_typst(&a.exact, &rounded)),
                &format!("about {}{said_unit}", rounded.join(", ")),
            );
        } else {
            m.display(
                &format!("{}{unit}", super::markup::expr(&exact, names)),
                &format!("{}{said_unit}", exact.to_tex(names).spoken()),
            );
        }
        m.raw("], [")
            .display(
                &format!("{}{unit}", numbers_typst(&a.exact, &numbers)),
                &format!("{}{said_unit}", numbers.join(", ")),
            )
            .raw("],\n");
    }
    m.raw(")\n");
    m.raw("#text(9pt)[").text(&format!(
        "Each answer agrees with its numeric route to {} (relative).",
        crate::base::format::sci(v.worst_error())
    ));
    m.raw("]\n");
    Ok(())
}

/// Each value a variant gives, as Typst and as it is said: `m = 2 thin "kg"`.
fn given_values(
    v: &Variant,
    names: &crate::notation::Names,
) -> Result<Vec<(String, String)>, RenderError> {
    v.given
        .iter()
        .map(|g| {
            let unit = g
                .unit
                .as_deref()
                .map_or(String::new(), |u| format!(" thin {}", unit_typst(u)));
            let said_unit = g.unit.as_deref().map_or(String::new(), said_unit);
            let typst = format!(
                "{} = {}{unit}",
                symbol(&g.name, names),
                formula(&g.value, names)?
            );
            let said = said_equation(&g.name, &g.value.to_tex(names).spoken(), names);
            Ok((typst, format!("{said}{said_unit}")))
        })
        .collect()
}

/// The answer's numbers to `digits` figures, in Typst's math.
pub fn decimals(numbers: &[f64], digits: usize) -> Vec<String> {
    numbers
        .iter()
        .map(|x| {
            if !x.is_finite() {
                return crate::base::literal::typst_string(&x.to_string());
            }
            let f = crate::notation::Formula::decimal(&crate::base::format::figures(*x, digits));
            super::markup::decimal_typst(&f)
        })
        .collect()
}
