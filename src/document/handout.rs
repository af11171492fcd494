//! What each handout shows of a scene's page, decided once for the HTML handout and the PDF.
//!
//! The student's summary teaches the derivation: the scene's setup, then the author's steps in
//! their order, each under its reason with its result typeset and the notes' form beside it
//! where the notes give one; a scene of the notes' own derivation (the lectures) shows its
//! built-in steps under their titles and reasons, without their numeric checks and without the
//! steps that only check another by a second route; a scene with no step at all shows its
//! results.
//! Claims that agree are listed; a mistake or an erratum is marked with its correct form. The
//! instructor's worked solutions keep everything: every step with its numeric check, every
//! result, the figures, every claim with its verdict.

use super::Page;
use crate::cas::{Expr, Rational};
use crate::notation::{Formula, Op};
use crate::scene::{ClaimRole, Verdict};

/// One scene's part of a handout (`page` indexes the course's pages).
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    pub page: usize,
    /// The steps shown, in the scene's order.
    pub steps: Vec<ShownStep>,
    /// The derived quantities shown as results (indices into `Page::quantities`).
    pub results: Vec<usize>,
    /// The exact principal axes and the principal moments at the scene's values.
    pub principal: bool,
    pub figures: bool,
    /// The claims shown after the derivation.
    pub claims: Vec<ShownClaim>,
}

/// A step as a handout shows it: one or more lines of the page's steps (an author's step of
/// several results, equilibria or modes, is one step with a line each).
#[derive(Debug, Clone, PartialEq)]
pub struct ShownStep {
    /// Indices into `Page::steps`, in order.
    pub lines: Vec<usize>,
    /// The student's handout leads with the author's reason; the instructor's with the step's
    /// title, its reason under the formula.
    pub reason_first: bool,
    /// Each line's numeric check.
    pub checks: bool,
    /// The line's value at the scene's numbers (an index into `Page::quantities`), where it has one.
    pub at: Vec<Option<usize>>,
    /// The notes' claims on this step (its `gives`), each with how it is marked.
    pub claims: Vec<ShownClaim>,
    /// The student's form of a line whose exact value is a number no student reads (radicals
    /// of rationals of many digits): `name ≈ 0.583422` to the figures of the values beside
    /// every step. The instructor's handout and `--json` keep the exact form.
    pub approx: Vec<Option<Formula>>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct ShownClaim {
    /// An index into `Page::claims`.
    pub claim: usize,
    pub mark: Mark,
}

/// How a claim is shown.
#[derive(Debug, Clone, PartialEq)]
pub enum Mark {
    /// A claim that agrees, in a list of them.
    Agrees,
    /// The instructor's: the claim with its verdict.
    Verdict,
    /// A box with a heading, the claim, the mistaken form and the right one.
    Boxed {
        heading: String,
        /// "The mistaken form" or "The notes".
        wrong: &'static str,
        /// "Correct" for the student, "Derived" for the instructor.
        right: &'static str,
        /// The instructor's box gives the verdict too.
        verdict: bool,
    },
}

/// What the handout shows of `page` (the course's page `index`).
pub fn part(index: usize, page: &Page, instructor: bool) -> Part {
    if instructor {
        return Part {
            page: index,
            steps: groups(page, |_| true)
                .into_iter()
                .flat_map(|lines| {
                    let at = values_at(page, &lines);
                    lines
                        .into_iter()
                        .zip(at)
                        .map(|(line, at)| titled_line(line, true, at))
                })
                .collect(),
            results: results(page),
            principal: true,
            figures: true,
            claims: (0..page.claims.len())
                .filter_map(|i| shown_claim(page, i, true))
                .collect(),
        };
    }
    let authored = page.steps.iter().any(|s| s.author.is_some());
    let on_steps: Vec<usize> = page.steps.iter().flat_map(|s| s.claims.clone()).collect();
    // A scene with the author's steps shows those (a body's quantities only where a step uses
    // them); a scene of the notes' own derivation shows its built-in steps, under their titles
    // with their reasons; a scene with neither (a body's tensor and axes) lists its results.
    let steps: Vec<ShownStep> = if authored {
        groups(page, |s| s.author.is_some())
            .into_iter()
            .map(|lines| student_step(page, lines))
            .collect()
    } else {
        (0..page.steps.len())
            .filter(|&line| !(page.steps[line].second_route || page.steps[line].working))
            .map(|line| titled_line(line, false, None))
            .collect()
    };
    Part {
        page: index,
        results: if steps.is_empty() {
            results(page)
        } else {
            Vec::new()
        },
        steps,
        // The principal moments and axes are the built-in steps' own: shown once, without
        // the eigen-solver's numeric check.
        principal: false,
        figures: false,
        claims: (0..page.claims.len())
            .filter(|i| !on_steps.contains(i))
            .filter_map(|i| shown_claim(page, i, false))
            .collect(),
    }
}

/// The results a page lists: every derived quantity but the working ones and the author's
/// steps' own values (which their steps show).
fn results(page: &Page) -> Vec<usize> {
    let steps: Vec<&str> = page
        .steps
        .iter()
        .filter_map(|s| s.author.as_deref())
        .collect();
    page.quantities
        .iter()
        .enumerate()
        .filter(|(_, q)| q.is_result && !is_step_value(&q.name, &steps))
        .map(|(i, _)| i)
        .collect()
}

/// One line of the page's steps under its title, its reason below, as the worked solutions
/// show every step and the student's summary a built-in one.
fn titled_line(line: usize, checks: bool, at: Option<usize>) -> ShownStep {
    ShownStep {
        lines: vec![line],
        reason_first: false,
        checks,
        at: vec![at],
        claims: Vec::new(),
        approx: vec![None],
    }
}

/// Whether `name` is a step's value: its own name, or `step_k` of a step of several results.
fn is_step_value(name: &str, steps: &[&str]) -> bool {
    steps.iter().any(|s| {
        name == *s
            || name
                .strip_prefix(s)
                .and_then(|r| r.strip_prefix('_'))
                .is_some_and(|k| k.parse::<usize>().is_ok())
    })
}

/// The page's steps that `keep` keeps, consecutive lines of one author's step together.
fn groups(page: &Page, keep: impl Fn(&super::Step) -> bool) -> Vec<Vec<usize>> {
    let mut out: Vec<Vec<usize>> = Vec::new();
    for (i, s) in page.steps.iter().enumerate().filter(|(_, s)| keep(s)) {
        let joins = out.last().is_some_and(|g| {
            let last = &page.steps[*g.last().unwrap()];
            g.last() == Some(&(i - 1)) && last.author.is_some() && last.author == s.author
        });
        if joins {
            out.last_mut().unwrap().push(i);
        } else {
            out.push(vec![i]);
        }
    }
    out
}

/// Each line's value at the scene's numbers: the quantity of an author's step's name (of a
/// step of several results, `name_k`), where the numbers say something the exact form does not.
fn values_at(page: &Page, lines: &[usize]) -> Vec<Option<usize>> {
    let Some(author) = page.steps[lines[0]].author.as_deref() else {
        return vec![None; lines.len()];
    };
    (0..lines.len())
        .map(|k| {
            let name = match &page.steps[lines[k]].result {
                Some(result) if lines.len() > 1 => result.clone(),
                _ => author.to_string(),
            };
            page.quantities
                .iter()
                .position(|q| q.name == name && q.at.is_some())
        })
        .collect()
}

fn student_step(page: &Page, lines: Vec<usize>) -> ShownStep {
    let at = values_at(page, &lines);
    // Claims that agree with one equation of the notes, on the same condition, said once: a
    // list `gives` of three modes is "As in the notes, eq. (11.12)" once, not three times.
    let mut said = Vec::new();
    let claims = lines
        .iter()
        .flat_map(|&l| page.steps[l].claims.clone())
        .filter_map(|i| shown_claim(page, i, false))
        .filter(|c| {
            let agreement = (
                page.claim_equation(c.claim),
                page.claims[c.claim].positive.clone(),
            );
            !matches!(c.mark, Mark::Agrees) || {
                let new = !said.contains(&agreement);
                said.push(agreement);
                new
            }
        })
        .collect();
    let approx = lines
        .iter()
        .map(|&l| decimal_form(&page.steps[l].statement))
        .collect();
    ShownStep {
        lines,
        reason_first: true,
        checks: false,
        at,
        claims,
        approx,
    }
}

/// The digits beyond which a rational in an exact number is too long to read.
const LONG_RATIONAL: i128 = 1_000_000;

/// Significant figures of a number printed for one too long to read exactly: those of the
/// values at the scene's numbers.
const DECIMAL_FIGURES: usize = 6;

fn has_long_rational(e: &Expr) -> bool {
    let limit = Rational::int(LONG_RATIONAL);
    let mut long = false;
    e.walk(&mut |x| {
        if let Expr::Num(r) = x {
            let (n, d) = r.abs_parts();
            long |= n >= limit || d >= limit;
        }
    });
    long
}

/// `name ≈ x` for `name = v` where v is a number with no symbol whose rationals run to more
/// than six digits (the trigonometric roots of a cubic at an author's numbers).
fn decimal_form(statement: &Formula) -> Option<Formula> {
    let Formula::Row(items) = statement else {
        return None;
    };
    let [lhs, Formula::Op(Op::Equals), Formula::Expr(v)] = items.as_slice() else {
        return None;
    };
    if v.symbols().iter().any(|s| s != "pi") || matches!(v, Expr::Num(_)) {
        return None;
    }
    let x = v.eval(&|_| None).ok()?;
    (has_long_rational(v) && x.is_finite()).then(|| {
        Formula::Row(vec![
            lhs.clone(),
            Formula::Op(Op::Approx),
            Formula::decimal(&crate::base::format::significant(x, DECIMAL_FIGURES)),
        ])
    })
}

/// How claim `i` is shown, or `None` when the student's handout leaves it out (a claim not
/// yet reviewed, or one whose check has a problem).
fn shown_claim(page: &Page, i: usize, instructor: bool) -> Option<ShownClaim> {
    let c = &page.claims[i];
    let mistake = c.role == ClaimRole::Mistake;
    let erratum = c.verdict == Verdict::Disagrees;
    let eq = page.claim_equation(i);
    let mark = if mistake || erratum {
        let heading = match (mistake, instructor, &eq) {
            (true, false, _) => "A common mistake, not the notes' claim".to_string(),
            (true, true, _) => "A common mistake".to_string(),
            (false, false, Some(eq)) => format!("Erratum: eq. ({eq}) of the notes is wrong"),
            (false, false, None) => "Erratum: the notes are wrong here".to_string(),
            (false, true, Some(eq)) => format!("Erratum, eq. ({eq})"),
            (false, true, None) => "Erratum".to_string(),
        };
        Mark::Boxed {
            heading,
            wrong: if mistake {
                "The mistaken form"
            } else {
                "The notes"
            },
            right: if instructor { "Derived" } else { "Correct" },
            verdict: instructor,
        }
    } else if instructor {
        Mark::Verdict
    } else if c.verdict == Verdict::Agrees {
        Mark::Agrees
    } else {
        return None;
    };
    Some(ShownClaim { claim: i, mark })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_value_is_its_name_or_a_numbered_result() {
        let steps = ["rest", "Omega"];
        assert!(is_step_value("rest_2", &steps));
        assert!(is_step_value("Omega", &steps));
        assert!(!is_step_value("Omega_min", &steps));
        assert!(!is_step_value("inertia_tensor", &steps));
    }
}

#[cfg(test)]
mod agreement_tests {
    use super::*;
    use crate::scene::Scene;

    /// Two coupled pendulums whose two modes the notes' one equation gives as a list.
    fn modes() -> String {
        include_str!("../../tests/fixtures/coupled-modes-list.toml")
            .replace("gives = [", "eq = \"11.12\"\ngives = [")
    }

    /// Both modes agree with eq. (11.12): the student's summary says so once, the
    /// instructor's gives each claim its verdict.
    #[test]
    fn claims_agreeing_with_one_equation_are_said_once() {
        let scene = Scene::parse(&modes(), std::path::Path::new("modes.toml")).unwrap();
        let report = crate::pipeline::run_scene(scene, None).unwrap();
        let page = crate::document::page(&report, None, None);
        let student = part(0, &page, false);
        let said: Vec<&ShownClaim> = student.steps.iter().flat_map(|s| &s.claims).collect();
        assert_eq!(said.len(), 1, "{said:?}");
        assert!(matches!(said[0].mark, Mark::Agrees));
        // The instructor's list of claims keeps each, with its verdict.
        let instructor = part(0, &page, true);
        let verdicts = instructor
            .claims
            .iter()
            .filter(|c| matches!(c.mark, Mark::Verdict));
        assert_eq!(verdicts.count(), 2);
    }
}
