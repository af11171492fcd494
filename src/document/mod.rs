//! The format-neutral document: one view of a scene's page that every printer reads. The HTML
//! page and the handouts (`render`), `derive` and `derive --json` (`report`) print a [`Page`];
//! it decides what a page holds and in what order, and each printer decides only how it looks.
//! Formulas stay trees ([`Formula`], [`Value`], [`Prose`]) and numbers stay numbers: nothing
//! here is printed, and there is no file I/O.

mod claim_sides;
pub mod course;
pub mod files;
pub mod handout;
mod problems;
pub mod quiz;
mod results;
pub mod roster;
pub mod words;

pub use problems::{
    KEY_FIGURES, Problem, ROUNDED_FIGURES, SharedAnswer, Sheet, SheetProblem, SheetVariant,
    Variant, answer_order, answer_words, problem, sheet,
};
pub use results::{At, ListResult, PrincipalAxis, PrincipalValues, Quantity};

use crate::cas::Expr;
use crate::model::fidelity::Fidelity;
use crate::model::figure::Accuracy;
use crate::model::prose::Prose;
use crate::model::value::Value;
use crate::notation::Formula;
use crate::numeric::Work;
use crate::pipeline::SceneReport;
use crate::verify::variants::VariantCheck;
use crate::verify::{ClaimResult, EigenCheck, QuantityCheck, RegressionResult, StepCheck};
use std::collections::BTreeMap;
use std::path::PathBuf;

/// One scene's page: heading, derivation, results, checks, claims and figures.
#[derive(Debug, Clone)]
pub struct Page {
    pub id: String,
    pub title: String,
    pub lecture: String,
    pub section: String,
    /// The notes' equation numbers the scene reproduces.
    pub equations: Vec<String>,
    /// The scene file, and the line of its `id`.
    pub source: PathBuf,
    pub line: usize,
    pub fidelity: Fidelity,
    /// Each symbol and what it stands for.
    pub symbols: Vec<(String, String)>,
    /// Each generalised coordinate and what it measures.
    pub coordinates: Vec<(String, String)>,
    /// The declared units of symbols and coordinates, by name, as written.
    pub units: std::collections::BTreeMap<String, String>,
    /// The names that take either sign (coordinates, their rates, negative values), for the
    /// random points at which the build checks what the page shows.
    pub signed: std::collections::BTreeSet<String>,
    /// How the scene typesets its names (name -> LaTeX), where it says.
    pub tex: std::collections::BTreeMap<String, String>,
    /// The same, read once: what every printer of the page sets each name as.
    pub names: crate::notation::Names,
    /// The scene's abbreviations (`lambda = M/(2*pi*R)`), which its claims and steps use.
    pub definitions: Vec<(String, Expr)>,
    /// Each body in words: its shape, mass, rotations and shift.
    pub bodies: Vec<Prose>,
    pub steps: Vec<Step>,
    /// Every derived quantity, in the catalogue's order.
    pub quantities: Vec<Quantity>,
    /// Each result that is a number only, by its name (`Omega_5` of a `frequency` with no
    /// closed form): at the scene's values, in the derivation's order.
    pub numeric_results: Vec<(String, f64)>,
    /// Each state of rest of several coordinates and the minors about it.
    pub list_results: Vec<ListResult>,
    /// The exact principal moments with their axes.
    pub principal_axes: Vec<PrincipalAxis>,
    /// The principal moments at the scene's values, by both routes.
    pub principal_values: Option<PrincipalValues>,
    /// The quadrature runs that check the exact tensor.
    pub numeric: Vec<NumericRow>,
    /// The eigen-solver against the exact principal axes.
    pub eigen: Option<EigenCheck>,
    pub claims: Vec<ClaimResult>,
    /// Each exact quantity against its numeric route.
    pub exact_vs_numeric: Vec<QuantityCheck>,
    pub regressions: Vec<RegressionResult>,
    pub variants: Vec<VariantCheck>,
    /// The problem's answers as the author wrote them (label, unit), in the variants' order.
    pub answers: Vec<crate::scene::Answer>,
    /// Each of the author's steps against its numeric route.
    pub step_checks: Vec<StepCheck>,
    pub figures: Vec<FigureBlock>,
    /// Each stage, and why it ran (`None`: nothing asked for it).
    pub stages: Vec<(&'static str, Option<Vec<String>>)>,
    pub cost: Cost,
    /// The claims where the notes disagree with the derivation.
    pub errata: usize,
    pub passed: bool,
    pub prev: Option<Link>,
    pub next: Option<Link>,
}

/// A derivation step: its statement, and its reason after the scene's citation for it.
#[derive(Debug, Clone)]
pub struct Step {
    pub title: Prose,
    pub statement: Formula,
    pub why: Prose,
    /// The step's citation key, and the scene's citation for it ("eq (51)") if it has one.
    pub key: String,
    pub citation: Option<String>,
    /// For an author's step: its numeric check.
    pub check: Option<StepCheck>,
    /// The author's step this line shows, by name; `None` for a built-in step.
    pub author: Option<String>,
    /// The notes' equation the author's step reproduces (its `eq`), if it names one.
    pub eq: Option<String>,
    /// The page's claims that are this step's `gives` (indices into `Page::claims`), on the
    /// step's last line.
    pub claims: Vec<usize>,
    /// The exact result as derived, where `statement` prints it in a textbook's form.
    pub exact: Option<Formula>,
    /// A built-in step that checks an earlier one by another route: the student's handout
    /// leaves it out.
    pub second_route: bool,
    /// A built-in step of working (a body's integrals): the student's handout leaves it out.
    pub working: bool,
    /// For an author's step: what this line must show, which the build reads back and checks
    /// (`render/guard.rs`).
    pub stands_for: Option<crate::derive::step_names::Stands>,
    /// The name of the result this line states (`Omega_2`, or the author's `slow`), if any.
    pub result: Option<String>,
    /// The line of the author's step in the scene file (0 for a built-in step).
    pub line: usize,
    /// The reason a student's summary gives, where it says less than `why`.
    pub student_why: Option<Prose>,
}

impl Step {
    /// The reason as one sentence: the citation first, if any.
    pub fn why_cited(&self) -> Prose {
        self.cited(&self.why)
    }

    /// The reason as a student's summary gives it, the citation first.
    pub fn student_why_cited(&self) -> Prose {
        self.cited(self.student_why.as_ref().unwrap_or(&self.why))
    }

    fn cited(&self, why: &Prose) -> Prose {
        match &self.citation {
            Some(c) => {
                let mut p = Prose::from(format!("{c}: "));
                p.0.extend(why.0.iter().cloned());
                p
            }
            None => why.clone(),
        }
    }
}

impl Page {
    /// The notes' equation claim `i` is about: a `[[claim]]`'s `eq`, or the `eq` of the step
    /// whose `gives` it is (`None` when that step names none).
    pub fn claim_equation(&self, i: usize) -> Option<String> {
        if self.claims[i].step.is_none() {
            return Some(self.claims[i].eq.clone());
        }
        self.steps
            .iter()
            .find(|s| s.claims.contains(&i))
            .and_then(|s| s.eq.clone())
    }
}

/// One quadrature run against the exact tensor, and whether its error kept to its law.
#[derive(Debug, Clone)]
pub struct NumericRow {
    pub body: String,
    pub method: &'static str,
    pub points: usize,
    pub error: f64,
    pub predicted_error: f64,
    pub within_law: bool,
    /// Where the method left its ladder at this fidelity.
    pub stop: &'static str,
    pub seconds: f64,
}

#[derive(Debug, Clone)]
pub struct FigureBlock {
    pub slug: String,
    /// Relative to the site root: `plots/<scene>-<slug>.svg`.
    pub file: String,
    pub title: String,
    pub desc: Prose,
    pub accuracy: Vec<Accuracy>,
}

/// What the scene cost: the symbolic engine's time and calls, the numeric work, the whole.
#[derive(Debug, Clone)]
pub struct Cost {
    pub symbolic_seconds: f64,
    pub engine_calls: u64,
    pub numeric_work: Work,
    pub seconds: f64,
}

#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct Link {
    pub href: String,
    pub title: String,
}

/// The file a scene's page is written to, relative to the site root.
pub fn page_file(r: &SceneReport) -> String {
    format!("{}.html", r.scene.id)
}

/// The file a scene's plot is written to, relative to the site root.
pub fn figure_file(r: &SceneReport, fig: &crate::model::figure::Figure) -> String {
    format!("plots/{}-{}.svg", r.scene.id, fig.slug)
}

/// The page of one scene, linked to the scenes before and after it.
pub fn page(r: &SceneReport, prev: Option<&SceneReport>, next: Option<&SceneReport>) -> Page {
    let mut page = derived_page(r, prev, next);
    let mut lines: BTreeMap<String, usize> = BTreeMap::new();
    for step in &mut page.steps {
        let Some(author) = step.author.clone() else {
            continue;
        };
        let line = lines.entry(author.clone()).or_default();
        let on = claims_on_line(r, &author, *line, &step.claims, &page.claims);
        *line += 1;
        if let Some(form) = authors_form(step, &on, &page.claims) {
            step.statement = form;
        }
    }
    page
}

/// The claims whose form line `k` of the author's step `author` may print. Line k of a step
/// of several results shows its k-th (Ω_k, r_k, or the k-th unknown), and a list `gives`
/// states each as a claim on its own name (`Omega_2`): that claim alone. Else a single
/// `gives`, which sits on the step's last line (`on_last`); an entry of a list for another
/// result never (Ω₃ was once printed in the form the list gives Ω₁).
fn claims_on_line(
    r: &SceneReport,
    author: &str,
    k: usize,
    on_last: &[usize],
    claims: &[ClaimResult],
) -> Vec<usize> {
    let Some(index) = r.scene.steps.iter().position(|s| s.name == author) else {
        return Vec::new();
    };
    let results = r.scene.steps[index].gives_each.len();
    let names = r.scene.steps[index].result_names();
    let entry = |m: usize| Some(Expr::sym(&names.kth(m)));
    let of_step = |j: &usize| claims[*j].step == Some(index);
    let own: Vec<usize> = (0..claims.len())
        .filter(of_step)
        .filter(|&j| claims[j].quantity == entry(k))
        .collect();
    if !own.is_empty() {
        return own;
    }
    on_last
        .iter()
        .copied()
        .filter(|&j| !(0..results).any(|m| claims[j].quantity == entry(m)))
        .collect()
}

/// A step's statement in the form its `gives` writes, where that agrees with the derivation:
/// the author's form is the one printed (the derived form stays in the claim, for `--json`).
/// `on` are the claims this line may print (see [`claims_on_line`]).
fn authors_form(step: &Step, on: &[usize], claims: &[ClaimResult]) -> Option<Formula> {
    let gives = on.iter().map(|&i| &claims[i]).find(|c| {
        c.verdict == crate::scene::Verdict::Agrees
            && c.problem.is_none()
            && c.precision.is_none()
            && c.role == crate::scene::ClaimRole::Notes
    })?;
    let notes = Formula::Expr(gives.notes.clone()?);
    let Formula::Row(row) = &step.statement else {
        return None;
    };
    match row.as_slice() {
        // An equation of motion, `… = 0`.
        [Formula::Expr(_), eq, zero @ Formula::Number(n)] if n == "0" => {
            Some(Formula::Row(vec![notes, eq.clone(), zero.clone()]))
        }
        // `name = value`.
        [name, eq, Formula::Expr(_)] => Some(Formula::Row(vec![name.clone(), eq.clone(), notes])),
        // `name = the author's expression = value`.
        [name, eq, named, eq2, Formula::Expr(_)] => Some(Formula::Row(vec![
            name.clone(),
            eq.clone(),
            named.clone(),
            eq2.clone(),
            notes,
        ])),
        _ => None,
    }
}

/// The page as derived, every step in the derivation's form.
fn derived_page(r: &SceneReport, prev: Option<&SceneReport>, next: Option<&SceneReport>) -> Page {
    let s = &r.scene;
    let link = |o: Option<&SceneReport>| {
        o.map(|o| Link {
            href: page_file(o),
            title: o.scene.title.clone(),
        })
    };
    Page {
        id: s.id.clone(),
        title: s.title.clone(),
        lecture: s.notes.lecture.clone(),
        section: s.notes.section.clone(),
        equations: s.notes.equations.clone(),
        source: s.source.clone(),
        line: s.id_at.0,
        fidelity: r.fidelity,
        symbols: s
            .symbols
            .iter()
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect(),
        coordinates: s
            .coordinates
            .iter()
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect(),
        tex: s.tex.clone(),
        names: s.names(),
        signed: s.signed_names(),
        units: s
            .units
            .iter()
            .map(|(k, u)| (k.clone(), u.text.clone()))
            .collect(),
        definitions: s
            .definitions
            .iter()
            .map(|(k, e)| (k.clone(), e.clone()))
            .collect(),
        bodies: s.bodies.iter().map(describe_body).collect(),
        steps: (0..r.derivation.steps.len())
            .map(|i| page_step(r, i))
            .collect(),
        quantities: results::quantities(r),
        principal_axes: results::principal_axes(r),
        principal_values: results::principal_values(r),
        numeric: numeric_rows(r),
        eigen: r.verification.eigen.clone(),
        claims: r.verification.claims.clone(),
        exact_vs_numeric: r.verification.quantities.clone(),
        regressions: r.verification.regressions.clone(),
        numeric_results: numeric_results(r),
        list_results: results::list_results(r),
        variants: r.verification.variants.clone(),
        answers: r
            .scene
            .problem
            .as_ref()
            .map_or(Vec::new(), |p| p.answers.clone()),
        step_checks: r.verification.steps.clone(),
        figures: figure_blocks(r),
        stages: r
            .plan
            .explain()
            .into_iter()
            .map(|(stage, why)| (stage.name(), why))
            .collect(),
        cost: Cost {
            symbolic_seconds: r.symbolic_seconds,
            engine_calls: r.engine_calls,
            numeric_work: r.numeric_work,
            seconds: r.seconds,
        },
        errata: r.verification.errata().count(),
        passed: r.passed(),
        prev: link(prev),
        next: link(next),
    }
}

/// The derivation's line `i` as the page shows it: what it states and stands for, its check,
/// and the claims under an author's step's last line.
fn page_step(r: &SceneReport, i: usize) -> Step {
    let s = &r.scene;
    let st = &r.derivation.steps[i];
    let last = r
        .derivation
        .steps
        .get(i + 1)
        .and_then(|n| n.author.as_ref())
        != st.author.as_ref();
    let author = st
        .author
        .as_ref()
        .and_then(|name| s.steps.iter().position(|a| &a.name == name));
    Step {
        title: st.title.clone(),
        statement: st.statement.clone(),
        exact: st.exact.clone(),
        second_route: st.second_route,
        working: st.working,
        student_why: st.student_why.clone(),
        line: author.map_or(0, |k| s.steps[k].line),
        stands_for: match (&st.author, &st.stands_for) {
            (Some(name), Some(stands)) => r
                .derivation
                .named
                .get(name)
                .and_then(|result| result.stood_for(s.result_names(name), stands)),
            _ => None,
        },
        result: match &st.stands_for {
            Some(crate::derive::step_names::StandsFor::Result(n)) => Some(n.clone()),
            _ => None,
        },
        why: st.why.clone(),
        key: st.cite.clone(),
        citation: st.citation(&s.cite).map(str::to_string),
        // An author's step of several lines (equilibria, modes) shows its one check
        // under its last line.
        check: if st.author.is_none() {
            // A built-in step's check is of its printed form, in the steps' order.
            let k = r.derivation.steps[..i]
                .iter()
                .filter(|s| s.author.is_none() && s.exact.is_some())
                .count();
            st.exact
                .as_ref()
                .and_then(|_| r.verification.printed.get(k).cloned())
        } else {
            st.author
                .as_ref()
                .filter(|name| {
                    r.derivation
                        .steps
                        .get(i + 1)
                        .and_then(|n| n.author.as_ref())
                        != Some(*name)
                })
                .and_then(|name| {
                    r.verification
                        .steps
                        .iter()
                        .find(|c| &c.step == name)
                        .cloned()
                })
        },
        author: st.author.clone(),
        eq: author.and_then(|k| s.steps[k].eq.clone()),
        claims: match author {
            Some(k) if last => (0..r.verification.claims.len())
                .filter(|&j| r.verification.claims[j].step == Some(k))
                .collect(),
            _ => Vec::new(),
        },
    }
}

/// Each quadrature of the numeric table, with whether its error is within its law.
fn numeric_rows(r: &SceneReport) -> Vec<NumericRow> {
    let within_law = &r.verification.within_law;
    r.numeric
        .iter()
        .flat_map(|n| n.runs.iter().zip(within_law))
        .map(|(q, ok)| NumericRow {
            body: q.body.clone(),
            method: q.method.name(),
            points: q.points,
            error: q.error,
            predicted_error: q.predicted_error,
            within_law: *ok,
            stop: q.stop.describe(),
            seconds: q.seconds,
        })
        .collect()
}

/// Each plot of the scene, with its file and the accuracy of what it draws.
fn figure_blocks(r: &SceneReport) -> Vec<FigureBlock> {
    r.figures
        .iter()
        .map(|f| FigureBlock {
            slug: f.slug.clone(),
            file: figure_file(r, f),
            title: f.title.clone(),
            desc: f.desc.clone(),
            accuracy: f.accuracy.clone(),
        })
        .collect()
}

/// Every scene's page, each linked to its neighbours in the order given.
pub fn pages(reports: &[SceneReport]) -> Vec<Page> {
    (0..reports.len())
        .map(|i| {
            let prev = i.checked_sub(1).map(|j| &reports[j]);
            page(&reports[i], prev, reports.get(i + 1))
        })
        .collect()
}

/// A body in words, its mass, angles and shift typeset: "cone, mass M, rotated by θ about y".
fn describe_body(b: &crate::scene::Body) -> Prose {
    let mut d = if b.label == b.shape.kind() {
        Prose::default().text(&b.label)
    } else {
        Prose::default().text(&format!("{} ({})", b.label, b.shape.kind()))
    };
    d = if b.subtract {
        d.text(", a hole removing mass ")
            .expr(&Expr::negate(b.mass.clone()))
    } else {
        d.text(", mass ").expr(&b.mass)
    };
    for (axis, angle) in &b.rotations {
        d = d
            .text(", rotated by ")
            .expr(angle)
            .text(&format!(" about {}", axis.name()));
    }
    if b.shift.iter().any(|e| !e.is_zero()) {
        d = d
            .text(", shifted by ")
            .expr(&Value::Vector(b.shift.clone()).to_expr());
    }
    d
}

#[cfg(test)]
mod tests;

/// Each numeric mode under its name, the scene's steps in order.
fn numeric_results(r: &SceneReport) -> Vec<(String, f64)> {
    let mut out = Vec::new();
    for step in &r.scene.steps {
        if let Some(crate::derive::step_names::StepResult::NumericModes { frequencies, .. }) =
            r.derivation.named.get(&step.name)
        {
            for (k, w) in frequencies.iter().enumerate() {
                out.push((step.result_names().kth(k), *w));
            }
        }
    }
    out
}
