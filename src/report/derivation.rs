//! `derive` without `--json`: one scene's steps, numeric checks, principal axes, claims and
//! variants as text for the terminal.

use crate::base::format::sci;
use crate::document::Page;
use crate::numeric::eigen::Space;
use std::fmt::Write;

/// `derive` without --json: the steps, the results and the checks of one scene.
pub fn derivation_text(page: &Page) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{} ({}; lecture {}, section {})",
        page.title, page.id, page.lecture, page.section
    );
    for (i, step) in page.steps.iter().enumerate() {
        let _ = writeln!(
            out,
            "\n{:>2}. {}\n    {}\n    because: {}",
            i + 1,
            step.title.to_plain(&page.names),
            step.statement.to_text(),
            step.why_cited()
        );
    }
    numeric_text(&mut out, page);
    step_checks_text(&mut out, page);
    eigen_text(&mut out, page);
    claims_text(&mut out, page);
    variants_text(&mut out, page);
    out
}

/// The numeric cross-check of the inertia tensor, quadrature by quadrature.
fn numeric_text(out: &mut String, page: &Page) {
    if !page.numeric.is_empty() {
        let _ = writeln!(
            out,
            "\nNumeric cross-check (relative errors against the exact tensor):"
        );
        let _ = writeln!(
            out,
            "  {:<10} {:<20} {:>8} {:>10} {:>10} {:>10}",
            "body", "method", "points", "error", "predicted", "seconds"
        );
        for q in &page.numeric {
            let _ = writeln!(
                out,
                "  {:<10} {:<20} {:>8} {:>10} {:>10} {:>10.2e}",
                q.body,
                q.method,
                q.points,
                sci(q.error),
                sci(q.predicted_error),
                q.seconds
            );
        }
    }
}

/// Each author's step against its numeric route.
fn step_checks_text(out: &mut String, page: &Page) {
    if !page.step_checks.is_empty() {
        let _ = writeln!(out, "\nSteps against their numeric routes:");
        for c in &page.step_checks {
            let _ = match &c.problem {
                Some(p) => writeln!(out, "  {:<12} FAILED: {p}", c.step),
                None => writeln!(
                    out,
                    "  {:<12} {} {} (within {}; {} evaluations): {}",
                    c.step,
                    if c.passed() {
                        "agrees to"
                    } else {
                        "FAILS: differs by"
                    },
                    sci(c.error),
                    sci(c.tolerance),
                    c.evaluations,
                    c.method
                ),
            };
        }
    }
}

/// The principal axes the eigen-solver finds, and how they agree with the exact ones.
fn eigen_text(out: &mut String, page: &Page) {
    if let Some(e) = &page.eigen {
        let _ = writeln!(out, "\nPrincipal axes, numeric (SymmetricEigen):");
        for sp in &e.numeric {
            let what = match &sp.space {
                Space::Axis(v) => format!("axis ({:.6}, {:.6}, {:.6})", v.x, v.y, v.z),
                Space::PlaneNormalTo(v) => {
                    format!("plane normal to ({:.6}, {:.6}, {:.6})", v.x, v.y, v.z)
                }
                Space::All => "every axis".into(),
            };
            let _ = writeln!(out, "  {:.15} ×{}  {what}", sp.value, sp.multiplicity);
        }
        let _ = writeln!(
            out,
            "  against exact: values {}, axes {}",
            sci(e.value_error),
            sci(e.axis_error)
        );
    }
}

/// The notes' claims with their verdicts.
fn claims_text(out: &mut String, page: &Page) {
    if !page.claims.is_empty() {
        let _ = writeln!(out, "\nClaims of the notes:");
        for c in &page.claims {
            let _ = writeln!(
                out,
                "  ({}) {:<13} {}",
                c.eq,
                c.verdict.as_str(),
                c.statement
            );
            if !c.positive.is_empty() {
                let _ = writeln!(out, "        for positive {}", c.positive.join(", "));
            }
            if c.where_real {
                let _ = writeln!(out, "        where both sides are real");
            }
            for d in &c.differences {
                let _ = writeln!(out, "        {d}");
            }
            if let Some(p) = c.precision.as_ref().filter(|_| c.differences.is_empty()) {
                let _ = writeln!(out, "        {p}");
            }
            if let Some(p) = &c.problem {
                let _ = writeln!(out, "        problem: {p}");
            }
        }
    }
}

/// A problem's variants: their values and answers.
fn variants_text(out: &mut String, page: &Page) {
    if !page.variants.is_empty() {
        let _ = writeln!(
            out,
            "\nVariants of the problem (each answer exact, then against its numeric route):"
        );
        for v in &page.variants {
            let values: Vec<String> = v
                .values
                .iter()
                .map(|(n, e)| format!("{n} = {}", e.to_text()))
                .collect();
            let _ = writeln!(out, "  {:>3}. {}", v.number, values.join(", "));
            for a in &v.answers {
                let _ = writeln!(
                    out,
                    "       {} = {}  ({} {})",
                    a.quantity,
                    a.exact.to_text(),
                    if a.passed() {
                        "agrees to"
                    } else {
                        "FAILS: differs by"
                    },
                    sci(a.error)
                );
            }
        }
    }
}
