//! How an author's step shows on the page: `name = result`, each equation of motion `… = 0`,
//! each state of rest and each mode, with the author's reason and what the derivation adds.

use crate::cas::Expr;
use crate::derive::Step;
use crate::derive::step_names::{Stable, StandsFor, StepResult};
use crate::model::prose::Prose;
use crate::notation::Formula;
use crate::scene::{AuthorStep, Scene};

/// The words an operation's result takes on the page where they are its own, given by its
/// rule (`Rule::wording`, in the operation's file); the rest is by the kind of result.
#[derive(Default)]
pub(super) struct Wording<'a> {
    /// What a conserved quantity's Lagrangian does not depend on: a momentum's coordinate;
    /// else time.
    pub conserved_in: Option<&'a str>,
    /// An equation of motion's noun and what follows its coordinate: ("linearised
    /// equation", ""), ("equation", ", substituted"); else ("equation", "").
    pub equation: Option<(&'static str, &'static str)>,
    /// The constraints whose multipliers have an equation of their own.
    pub constraints: &'a [(String, Expr)],
}

/// After a mode's title where its frequency is zero: what a zero mode is.
const ZERO_MODE: &str = ", a zero mode: a free motion, with no restoring force";

/// A state of rest of several coordinates: q1 = v1, q2 = v2, …
fn state_formula(coordinates: &[String], state: &[crate::cas::Zero]) -> Formula {
    let mut row = Vec::new();
    for (k, (q, z)) in coordinates.iter().zip(state).enumerate() {
        if k > 0 {
            row.push(Formula::Op(crate::notation::Op::Quad));
        }
        row.push(Formula::Expr(Expr::sym(q)));
        row.push(Formula::Op(crate::notation::Op::Equals));
        row.push(Formula::Expr(z.value.clone()));
    }
    Formula::Row(row)
}

/// The author's reason, then what the derivation adds ("conserved: ..."), after a semicolon.
fn with_reason(step: &AuthorStep, why: &Prose, added: Prose) -> Prose {
    if step.why.is_empty() {
        return added;
    }
    let mut out = why.clone().text("; ");
    out.0.extend(added.0);
    out
}

/// A step as the page shows it: `name = result`, or each equation of motion `… = 0`.
pub(super) fn page_steps(scene: &Scene, step: &AuthorStep, result: &StepResult) -> Vec<Step> {
    let mut steps = page_statements(scene, step, result);
    for s in &mut steps {
        s.author = Some(step.name.clone());
    }
    steps
}

/// A name as the page typesets it, for a title: its symbol (φ₁, or the scene's own `tex`).
fn typeset(name: &str) -> Prose {
    Prose::default().expr(&Expr::sym(name))
}

/// Whether a name prints as a word on the scene's pages (see `cas::prints_as_word`).
fn is_word(scene: &Scene, name: &str) -> bool {
    crate::cas::prints_as_word(name, &|n| scene.tex.contains_key(n))
}

/// Whether a step is headed by the symbol its result prints as (`$L$`); else by what it does
/// ("Equations of motion"), where its page prints no name of its own or it would print as a
/// word: never by the step's name as the author's file spells it (`Lag`, `eom`).
fn headed_by_symbol(scene: &Scene, step: &AuthorStep) -> bool {
    crate::scene::prints_its_name(step, &scene.steps) && !is_word(scene, &step.name)
}

/// What an author's step states on the page, line by line, for each kind of result.
fn page_statements(scene: &Scene, step: &AuthorStep, result: &StepResult) -> Vec<Step> {
    let by_symbol = headed_by_symbol(scene, step);
    let mut lines = Lines {
        scene,
        step,
        by_symbol,
        title: Prose::default(),
        names: step.result_names(),
        wording: super::rule_of(&step.op).wording(),
    };
    lines.title = lines.cited(if by_symbol {
        typeset(&step.name)
    } else {
        Prose::default().text(step.op.heading())
    });
    // The author's reason, its `$…$` mathematics typeset.
    let why = &crate::model::prose::author(&step.why);
    match result {
        StepResult::Expr(e) => {
            vec![
                Step::titled(lines.title.clone(), lines.named(e), why.clone())
                    .standing_for(lines.own()),
            ]
        }
        StepResult::Conserved { value, conserved } => vec![lines.conserved(value, *conserved, why)],
        StepResult::Equilibria {
            coordinate,
            zeros,
            excluded,
        } => lines.equilibria(coordinate, zeros, excluded, why),
        StepResult::Stability { coordinate, cases } => lines.stability(coordinate, cases, why),
        StepResult::RestStates {
            coordinates,
            states,
            excluded,
        } => lines.rest_states(coordinates, states, excluded, why),
        StepResult::RestStability { coordinates, cases } => {
            lines.rest_stability(coordinates, cases, why)
        }
        StepResult::Solution(pairs) => lines.solution(pairs, why),
        StepResult::Modes(values) => lines.modes_or_roots(values, true, why),
        StepResult::Roots(values) => lines.modes_or_roots(values, false, why),
        StepResult::NumericModes {
            frequencies,
            reason,
        } => lines.numeric_modes(frequencies, reason, why),
        StepResult::Equations(eqs) => lines.equations(eqs, why),
    }
}

/// The page's lines of one author's step: its title, and the names its results go by.
struct Lines<'a> {
    scene: &'a Scene,
    step: &'a AuthorStep,
    /// Headed by the symbol its result prints as, not by what it does.
    by_symbol: bool,
    title: Prose,
    names: crate::scene::ResultNames<'a>,
    wording: Wording<'a>,
}

impl Lines<'_> {
    /// A title with the notes' equation number, where the step cites one.
    fn cited(&self, s: Prose) -> Prose {
        match &self.step.eq {
            Some(eq) => s.run_on(&format!(" (eq {eq})")),
            None => s,
        }
    }

    /// The title, then `more` after a colon: `L: the equation of motion of φ`.
    fn title_and(&self, more: Prose) -> Prose {
        self.title.clone().run_on(": ").then(more)
    }

    /// `name = e`.
    fn named(&self, e: &Expr) -> Formula {
        Formula::equation(Formula::Expr(Expr::sym(&self.step.name)), e.clone())
    }

    /// What a line states, by the derivation's name for it: the build reads it back.
    fn own(&self) -> StandsFor {
        StandsFor::Result(self.step.name.clone())
    }

    /// The k-th of the step's several results.
    fn kth(&self, k: usize) -> StandsFor {
        StandsFor::Result(self.names.kth(k))
    }

    fn conserved(&self, value: &Expr, conserved: bool, why: &Prose) -> Step {
        let step = self.step;
        let of = self.wording.conserved_in.unwrap_or("t");
        // The derivation's verdict after the author's reason, said once: a reason that
        // says it is conserved is enough; one that already says why ("$L$ does not depend
        // on $x$") takes "conserved"; any other, the verdict with its why.
        let says_why = ["does not depend on", "cyclic", "does not appear in"]
            .iter()
            .any(|w| step.why.contains(w));
        let why = if conserved && step.why.contains("conserved") {
            why.clone()
        } else if conserved && says_why {
            with_reason(step, why, Prose::default().text("conserved"))
        } else {
            let verdict = if conserved {
                "conserved: the Lagrangian does not depend on "
            } else {
                "not conserved: the Lagrangian depends on "
            };
            with_reason(
                step,
                why,
                Prose::default().text(verdict).expr(&Expr::sym(of)),
            )
        };
        Step::titled(self.title.clone(), self.named(value), why).standing_for(self.own())
    }

    fn equilibria(
        &self,
        coordinate: &str,
        zeros: &[crate::cas::Zero],
        excluded: &[Expr],
        why: &Prose,
    ) -> Vec<Step> {
        let step = self.step;
        // The roots set aside, named after the last state of rest.
        let pairs: Vec<(String, Expr)> = excluded
            .iter()
            .map(|e| (coordinate.to_string(), e.clone()))
            .collect();
        let last_why = with_set_aside(step, why, &pairs);
        let n = zeros.len();
        zeros
            .iter()
            .enumerate()
            .map(|(k, z)| {
                let line = Step::titled(
                    self.title_and(Prose::default().text(&format!("equilibrium {}", k + 1))),
                    Formula::equation(Formula::Expr(Expr::sym(coordinate)), z.value.clone()),
                    if k + 1 == n {
                        last_why.clone()
                    } else {
                        why.clone()
                    },
                )
                .standing_for(self.kth(k));
                // The roots set aside are the instructor's working.
                match k + 1 == n && !excluded.is_empty() {
                    true => line.for_students(why.clone()),
                    false => line,
                }
            })
            .collect()
    }

    fn stability(
        &self,
        coordinate: &str,
        cases: &[crate::derive::step_names::Stability],
        why: &Prose,
    ) -> Vec<Step> {
        let step = self.step;
        let omega2 = Formula::Expr(Expr::pow(Expr::sym("Omega"), Expr::int(2)));
        cases
            .iter()
            .enumerate()
            .map(|(k, c)| {
                let verdict = match c.verdict {
                    Stable::Always => "stable for all values",
                    Stable::Never => "unstable for all values",
                    Stable::Where => "stable where the right-hand side is positive",
                    Stable::Unknown => {
                        "its exact Ω² would expand beyond the engine's budget; where this \
                     state of rest exists at the scene's values, the numeric check gives Ω²"
                    }
                };
                let at = Prose::default()
                    .text("about ")
                    .formula(Formula::equation(
                        Formula::Expr(Expr::sym(coordinate)),
                        c.at.value.clone(),
                    ))
                    .text(&format!(": {verdict}"));
                let why = with_reason(step, why, at);
                match &c.omega_squared {
                    Some(w2) => {
                        let line = Formula::equation(omega2.clone(), w2.clone());
                        Step::titled(self.title.clone(), line, why).standing_for(self.kth(k))
                    }
                    // No exact Ω² to print: the line states the state of rest, and
                    // its reason says why.
                    None => Step::titled(
                        self.title.clone(),
                        Formula::equation(Formula::Expr(Expr::sym(coordinate)), c.at.value.clone()),
                        why,
                    ),
                }
            })
            .collect()
    }

    fn rest_states(
        &self,
        coordinates: &[String],
        states: &[Vec<crate::cas::Zero>],
        excluded: &[(String, Expr)],
        why: &Prose,
    ) -> Vec<Step> {
        let step = self.step;
        let last_why = with_set_aside(step, why, excluded);
        let n = states.len();
        states
            .iter()
            .enumerate()
            .map(|(k, state)| {
                let line = Step::titled(
                    self.title_and(Prose::default().text(&format!("equilibrium {}", k + 1))),
                    state_formula(coordinates, state),
                    if k + 1 == n {
                        last_why.clone()
                    } else {
                        why.clone()
                    },
                );
                match k + 1 == n && !excluded.is_empty() {
                    true => line.for_students(why.clone()),
                    false => line,
                }
            })
            .collect()
    }

    fn rest_stability(
        &self,
        coordinates: &[String],
        cases: &[crate::derive::step_names::StateStability],
        why: &Prose,
    ) -> Vec<Step> {
        let step = self.step;
        cases
            .iter()
            .map(|c| {
                let verdict = match c.verdict {
                    Stable::Always => "stable for all values",
                    Stable::Never => "unstable for all values",
                    Stable::Where | Stable::Unknown => "stable where every minor is positive",
                };
                let at = Prose::default()
                .text("about ")
                .formula(state_formula(coordinates, &c.at))
                .text(": the leading minors of the stiffness ")
                .formula(Formula::author(r"K = \partial R / \partial q"))
                .text(&format!(
                    " there; every squared frequency is positive exactly when they all are (the \
                     mass matrix being positive definite): {verdict}"
                ));
                let mut row = Vec::new();
                for (k, m) in c.minors.iter().enumerate() {
                    if k > 0 {
                        row.push(Formula::Op(crate::notation::Op::Quad));
                    }
                    row.push(Formula::Name(crate::notation::Name {
                        base: "Delta".into(),
                        sub: Some((k + 1).to_string()),
                        accent: crate::notation::Accent::None,
                        prime: false,
                    }));
                    row.push(Formula::Op(crate::notation::Op::Equals));
                    row.push(Formula::Expr(m.clone()));
                }
                Step::titled(
                    self.title.clone(),
                    Formula::Row(row),
                    with_reason(step, why, at),
                )
            })
            .collect()
    }

    /// Each unknown = its value, titled with the name later steps use.
    fn solution(&self, pairs: &[(String, Expr)], why: &Prose) -> Vec<Step> {
        let scene = self.scene;
        pairs
            .iter()
            .enumerate()
            .map(|(k, (unknown, value))| {
                // The name later steps give it, where it prints as a symbol (a₁ of `tex = "a"`).
                let named = self.names.kth(k);
                let own = if is_word(scene, &named) {
                    Prose::default()
                } else {
                    typeset(&named).text(", ")
                };
                let what = own.run_on("the value of ").then(typeset(unknown));
                Step::titled(
                    self.title_and(what),
                    Formula::equation(Formula::Expr(Expr::sym(unknown)), value.clone()),
                    why.clone(),
                )
                .standing_for(self.kth(k))
            })
            .collect()
    }

    fn modes_or_roots(&self, values: &[Expr], modes: bool, why: &Prose) -> Vec<Step> {
        values
            .iter()
            .enumerate()
            .map(|(k, w)| {
                let sub = Expr::sym(&self.names.kth(k));
                let what = if modes { "normal mode" } else { "root" };
                let zero = modes && w.is_zero();
                Step::titled(
                    self.title_and(Prose::default().text(&format!(
                        "{what} {}{}",
                        k + 1,
                        if zero { ZERO_MODE } else { "" }
                    ))),
                    Formula::equation(Formula::Expr(sub), w.clone()),
                    why.clone(),
                )
                .standing_for(self.kth(k))
            })
            .collect()
    }

    /// Ω_k ≈ its value: no closed form, so a number, with the reason beside it.
    fn numeric_modes(&self, frequencies: &[f64], reason: &Prose, why: &Prose) -> Vec<Step> {
        let step = self.step;
        frequencies
            .iter()
            .enumerate()
            .map(|(k, w)| {
                let mut added = Prose::default()
                    .text("at the scene's values, the eigenvalues of K and M by Sturm bisection: ");
                added.0.extend(reason.0.iter().cloned());
                Step::titled(
                    self.title_and(Prose::default().text(&format!(
                        "normal mode {}{}",
                        k + 1,
                        if *w == 0.0 { ZERO_MODE } else { "" }
                    ))),
                    Formula::Row(vec![
                        Formula::Expr(Expr::sym(&self.names.kth(k))),
                        Formula::Op(crate::notation::Op::Approx),
                        Formula::Number(crate::base::format::significant(*w, 6)),
                    ]),
                    with_reason(step, why, added),
                )
                .standing_for(self.kth(k))
            })
            .collect()
    }

    fn equations(&self, eqs: &[(String, Expr)], why: &Prose) -> Vec<Step> {
        let (scene, by_symbol) = (self.scene, self.by_symbol);
        eqs.iter()
            .map(|(coordinate, e)| {
                let q = coordinate;
                // A constraint on the coordinates is differentiated twice to reach the
                // accelerations, one on the rates (rolling) once.
                let constraint = self
                    .wording
                    .constraints
                    .iter()
                    .find(|(lambda, _)| lambda == q)
                    .map(|(_, f)| {
                        crate::derive::constraints::is_velocity_constraint(f, &scene.coordinates)
                    });
                let q = typeset(q);
                let (of, after) = self.wording.equation.unwrap_or(("equation", ""));
                let what = match constraint {
                    Some(on_rates) => Prose::default()
                        .text("the constraint of the multiplier ")
                        .then(q)
                        .run_on(if on_rates {
                            ", differentiated once"
                        } else {
                            ", differentiated twice"
                        }),
                    None => Prose::default()
                        .text(&format!("the {of} of motion of "))
                        .then(q)
                        .run_on(after),
                };
                // Under a symbol, `L: the equation of motion of φ`; else the words alone.
                let line = if by_symbol {
                    self.title_and(what)
                } else {
                    self.cited(what.capitalised())
                };
                let parameter = |s: &str| scene.symbols.contains_key(s);
                Step::titled(
                    line,
                    Formula::Row(vec![
                        Formula::Expr(super::equation_form::equation_form(
                            e, coordinate, &parameter,
                        )),
                        Formula::Op(crate::notation::Op::Equals),
                        Formula::Number("0".into()),
                    ]),
                    why.clone(),
                )
                .standing_for(StandsFor::Equation(coordinate.clone()))
            })
            .collect()
    }
}

/// The step's reason, and after it the roots set aside as real for no values of the symbols
/// (q = √(−3r₀²)), when there are any.
fn with_set_aside(step: &AuthorStep, why: &Prose, excluded: &[(String, Expr)]) -> Prose {
    if excluded.is_empty() {
        return why.clone();
    }
    let mut set_aside = Prose::default();
    for (k, (q, e)) in excluded.iter().enumerate() {
        if k > 0 {
            set_aside = set_aside.text(", ");
        }
        set_aside = set_aside.formula(Formula::equation(Formula::Expr(Expr::sym(q)), e.clone()));
    }
    let said = if excluded.len() == 1 { "is" } else { "are" };
    set_aside = set_aside.text(&format!(
        " {said} real for no values of the symbols: no state of rest"
    ));
    with_reason(step, why, set_aside)
}
