//! The terminal and JSON printers: `check`'s summary of the reports, and a scene's [`Page`] for
//! `derive`. Pure functions to strings: no I/O here.

use crate::base::format::{count, sci};
use crate::document::Page;
use crate::pipeline::SceneReport;
use crate::scene::Verdict;
use crate::verify::ClaimResult;
use std::fmt::Write;

mod derivation;
mod json;
pub use crate::render::json::scene_json;
pub use derivation::derivation_text;
pub use json::check_json;

/// The relative difference of every variant's every answer from its numeric route.
fn variant_errors(r: &SceneReport) -> impl Iterator<Item = f64> + '_ {
    r.verification
        .variants
        .iter()
        .flat_map(|v| v.answers.iter().map(|a| a.error))
}

/// A heading with the count, then each claim with its scene and the lines that explain it,
/// their mathematics as a terminal reads it (I_xx = ρ a³), not the author's LaTeX.
fn list_claims(out: &mut String, heading: &str, claims: &[(&SceneReport, &ClaimResult)]) {
    if claims.is_empty() {
        return;
    }
    let _ = writeln!(out, "\n{heading} ({}):", claims.len());
    for (r, c) in claims {
        let statement = crate::model::prose::plain(&c.statement);
        let _ = writeln!(out, "  eq ({}) [{}] {statement}", c.eq, r.scene.id);
        let names = r.scene.names();
        for d in &c.differences {
            let _ = writeln!(out, "      {}", d.to_plain(&names));
        }
    }
}

/// One reason a scene fails, on one located line.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    pub text: String,
    /// A verdict or a recorded result that differs from the derivation: `check --bless`
    /// records the new one. Any other failure is not settled by a record.
    pub recordable: bool,
    /// A step not yet recorded: `check` fails on it, a build and `derive` do not (the author
    /// may still be writing it).
    pub new_step: bool,
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

/// What failed in one scene: the reasons `check` and `derive` exit with 1.
pub fn failures(r: &SceneReport) -> Vec<Failure> {
    let mut failures = Vec::new();
    claim_failures(r, &mut failures);
    record_failures(r, &mut failures);
    numeric_failures(r, &mut failures);
    failures
}

/// Each claim whose verdict is not the one recorded, or has a problem.
fn claim_failures(r: &SceneReport, failures: &mut Vec<Failure>) {
    let src = r.scene.source.display();
    for c in r.verification.claims.iter().filter(|c| !c.passed()) {
        let recordable = c.problem.is_none();
        let mut why = c.problem.clone().unwrap_or_else(|| match c.expected {
            Some(expected) => format!(
                "verdict {} but the scene records {}",
                c.verdict.as_str(),
                expected.as_str()
            ),
            None => format!(
                "verdict {}, not yet recorded: review it, then add expect = \"{}\" or run \
                 `mechbook check --bless`",
                c.verdict.as_str(),
                c.verdict.as_str()
            ),
        });
        if let Some(dimension) = &c.dimension {
            why.push_str(&format!("; the two sides differ in dimension: {dimension}"));
        }
        failures.push(Failure {
            text: format!("{src}:{}: claim ({}): {why}", c.line, c.eq),
            recordable,
            new_step: false,
        });
    }
}

/// Each result, step and variant pin that differs from what the scene records.
fn record_failures(r: &SceneReport, failures: &mut Vec<Failure>) {
    let src = r.scene.source.display();
    for g in r.verification.regressions.iter().filter(|g| !g.unchanged) {
        let text = match &g.recorded {
            Some(recorded) => format!(
                "{src}:{}: `{}` changed: recorded {}, derived {}",
                g.line,
                g.quantity,
                recorded.to_text(),
                crate::render::json::derived_text(g)
            ),
            None => format!(
                "{src}:{}: `{}` not yet recorded (derived {}): review it, then run `mechbook \
                 check --bless`, which writes the scene's [expect]",
                g.line,
                g.quantity,
                crate::render::json::derived_text(g)
            ),
        };
        failures.push(Failure {
            text,
            recordable: true,
            new_step: false,
        });
    }
    for s in r
        .verification
        .step_records
        .iter()
        .filter(|s| !s.unchanged())
    {
        failures.push(Failure {
            text: format!("{src}:{}: {}", s.line, step_record_failure(s)),
            recordable: true,
            new_step: s.recorded.is_none(),
        });
    }
    if let Some(pin) = r.verification.pin.as_ref().filter(|p| !p.unchanged()) {
        let text = match &pin.recorded {
            None => format!(
                "{src}:{}: the problem's {} not yet recorded: review them, then run \
                 `mechbook check --bless`, which pins them in the scene's [expect]",
                pin.line,
                match pin.derived.len() {
                    1 => "1 variant is".to_string(),
                    n => format!("{n} variants are"),
                }
            ),
            Some(recorded) => {
                let differ = pin.differing();
                format!(
                    "{src}:{}: the problem's variants changed since they were recorded: {} of {} \
                     students' sheets differ (variant{} {}); if no sheet has been handed out, \
                     run `mechbook check --bless` to record the new ones",
                    pin.line,
                    differ.len(),
                    recorded.len().max(pin.derived.len()),
                    if differ.len() == 1 { "" } else { "s" },
                    differ
                        .iter()
                        .map(|k| k.to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            }
        };
        failures.push(Failure {
            text,
            recordable: true,
            new_step: false,
        });
    }
}

/// Each exact result that its numeric route does not confirm, and each quadrature beyond its law.
fn numeric_failures(r: &SceneReport, failures: &mut Vec<Failure>) {
    let src = r.scene.source.display();
    for q in r.verification.quantities.iter().filter(|q| !q.passed) {
        failures.push(unrecordable(format!(
            "{src}: `{}`: exact and numeric differ by {} (relative)",
            q.name,
            sci(q.error)
        )));
    }
    if let Some(e) = r.verification.eigen.as_ref().filter(|e| !e.passed) {
        failures.push(unrecordable(format!(
            "{src}: principal axes: exact and numeric differ (values {}, axes {})",
            sci(e.value_error),
            sci(e.axis_error)
        )));
    }
    for v in &r.verification.variants {
        for a in v.answers.iter().filter(|a| !a.passed()) {
            failures.push(unrecordable(format!(
                "{src}: variant {}: `{}`: exact and numeric differ by {} (relative), beyond {}",
                v.number,
                a.quantity,
                sci(a.error),
                sci(a.tolerance)
            )));
        }
    }
    for c in r.verification.steps.iter().filter(|c| !c.passed()) {
        failures.push(unrecordable(match &c.problem {
            Some(p) => format!(
                "{src}:{}: step `{}`: its numeric check failed: {p}",
                c.line, c.step
            ),
            None => format!(
                "{src}:{}: step `{}`: exact and numeric differ by {} (relative), beyond {} ({})",
                c.line,
                c.step,
                sci(c.error),
                sci(c.tolerance),
                c.method
            ),
        }));
    }
    if let Some(n) = &r.numeric {
        for (q, ok) in n.runs.iter().zip(&r.verification.within_law) {
            if !ok {
                failures.push(unrecordable(format!(
                    "{src}: {} {} ({} points): error {} beyond its law {}",
                    q.body,
                    q.method.name(),
                    q.points,
                    sci(q.error),
                    sci(q.predicted_error)
                )));
            }
        }
    }
}

fn unrecordable(text: String) -> Failure {
    Failure {
        text,
        recordable: false,
        new_step: false,
    }
}

/// The summary table printed by `check`, with the notes' errata and every failure below it.
pub fn check_table(reports: &[SceneReport]) -> String {
    let mut out = scene_rows(reports);
    claims_and_failures(&mut out, reports);
    problems_line(&mut out, reports);
    totals_line(&mut out, reports);
    out
}

/// The table's header and a row per scene.
fn scene_rows(reports: &[SceneReport]) -> String {
    let mut out = String::new();
    // Columns as wide as their longest entry: a course may name its lectures in words.
    let id_width = reports
        .iter()
        .map(|r| r.scene.id.len())
        .fold(28, usize::max);
    let lecture_width = reports
        .iter()
        .map(|r| r.scene.notes.lecture.chars().count())
        .fold(4, usize::max);
    let _ = writeln!(
        out,
        "{:<id_width$} {:>lecture_width$} {:>7} {:>6} {:>9} {:>5} {:>11} {:>9} {:>6}",
        "scene", "lect", "results", "agree", "disagree", "n/c", "exact~num", "symb ms", "status"
    );
    for r in reports {
        let worst = r
            .verification
            .quantities
            .iter()
            .map(|q| q.error)
            .chain(variant_errors(r))
            .fold(None, |m: Option<f64>, e| Some(m.map_or(e, |m| m.max(e))));
        let _ = writeln!(
            out,
            "{:<id_width$} {:>lecture_width$} {:>7} {:>6} {:>9} {:>5} {:>11} {:>9.2} {:>6}",
            r.scene.id,
            r.scene.notes.lecture,
            r.derivation.quantities.len() + r.derivation.named.len(),
            r.verification.count(Verdict::Agrees),
            r.verification.count(Verdict::Disagrees),
            r.verification.count(Verdict::NotCheckable),
            worst.map(sci).unwrap_or_else(|| "-".into()),
            r.symbolic_seconds * 1e3,
            if r.passed() { "ok" } else { "FAILED" }
        );
    }
    out
}

/// The errata, the undecided claims, and the failures with what to do about them.
fn claims_and_failures(out: &mut String, reports: &[SceneReport]) {
    let errata: Vec<_> = reports
        .iter()
        .flat_map(|r| r.verification.errata().map(move |c| (r, c)))
        .collect();
    list_claims(out, "Where the notes disagree with the derivation", &errata);
    let undecided: Vec<_> = reports
        .iter()
        .flat_map(|r| {
            r.verification
                .claims
                .iter()
                .filter(|c| c.verdict == Verdict::Undecided)
                .map(move |c| (r, c))
        })
        .collect();
    list_claims(
        out,
        "Undecided: the symbolic and random-point tests disagree",
        &undecided,
    );
    let failures: Vec<Failure> = reports.iter().flat_map(failures).collect();
    if !failures.is_empty() {
        let _ = writeln!(out, "\nFailures ({}):", failures.len());
        for f in failures {
            let _ = writeln!(out, "  {f}");
        }
        let _ = writeln!(
            out,
            "Once you have reviewed them, `mechbook check --bless` records the derived results \
             and verdicts in the scenes."
        );
    }
}

/// The problems' line: their variants, and how their answers were cross-checked.
fn problems_line(out: &mut String, reports: &[SceneReport]) {
    let problems = reports.iter().filter(|r| r.scene.problem.is_some()).count();
    if problems > 0 {
        let variants: usize = reports.iter().map(|r| r.verification.variants.len()).sum();
        let answers = reports
            .iter()
            .flat_map(|r| &r.verification.variants)
            .flat_map(|v| &v.answers);
        let failed = answers.clone().filter(|a| !a.passed()).count();
        // The worst of those that passed: a failed one is listed above with its own difference
        // (which may be infinite).
        let worst = answers
            .clone()
            .filter(|a| a.passed())
            .map(|a| a.error)
            .fold(0.0f64, f64::max);
        // A mode with no closed form is graded on its value at each variant: not exact.
        let by_numbers = answers.clone().filter(|a| a.numeric_mode).count();
        let total = answers.clone().count();
        let exact = match by_numbers {
            0 => "every answer exact".to_string(),
            k if k == total => "every answer a mode with no closed form, found at its \
                                variant's values by Sturm bisection,"
                .to_string(),
            k => format!(
                "{} exact and {} with no closed form, found at their variant's values by Sturm \
                 bisection,",
                count(total - k, "answer"),
                count(k, "mode")
            ),
        };
        let _ = if failed == 0 {
            writeln!(
                out,
                "\n{}, {}: {exact} and cross-checked numerically, worst relative difference {}",
                count(problems, "problem"),
                count(variants, "variant"),
                sci(worst)
            )
        } else {
            writeln!(
                out,
                "\n{}, {}: {failed} of {} FAILED their numeric cross-check (listed above); the \
                 others agree to {}",
                count(problems, "problem"),
                count(variants, "variant"),
                count(answers.count(), "answer"),
                sci(worst)
            )
        };
    }
}

/// The course's totals: scenes, claims by verdict, the symbolic stage's cost, and the status.
fn totals_line(out: &mut String, reports: &[SceneReport]) {
    let claims: usize = reports.iter().map(|r| r.verification.claims.len()).sum();
    // A fold from +0: an empty f64 sum is −0, printed "-0.0 ms".
    let symbolic = reports.iter().fold(0.0, |acc, r| acc + r.symbolic_seconds);
    let calls: u64 = reports.iter().map(|r| r.engine_calls).sum();
    let verdicts = |v: Verdict| -> usize { reports.iter().map(|r| r.verification.count(v)).sum() };
    let undecided = match verdicts(Verdict::Undecided) {
        0 => String::new(),
        n => format!(", {n} undecided"),
    };
    let _ = writeln!(
        out,
        "\n{}, {}: {} agree, {} disagree, {} not checkable{undecided}; symbolic stage {:.1} ms in {}; {}",
        count(reports.len(), "scene"),
        count(claims, "claim"),
        verdicts(Verdict::Agrees),
        verdicts(Verdict::Disagrees),
        verdicts(Verdict::NotCheckable),
        symbolic * 1e3,
        count(calls, "engine call"),
        if reports.iter().all(SceneReport::passed) {
            "all as recorded"
        } else {
            "FAILED"
        }
    );
}

/// `derive --explain`: which stages ran, and why; which were skipped.
pub fn explain_text(page: &Page) -> String {
    let mut out = String::from("Stages:\n");
    for (stage, why) in &page.stages {
        match why {
            Some(reasons) => {
                let _ = writeln!(
                    out,
                    "  ran      {:<18} because {}",
                    stage,
                    reasons.join("; ")
                );
            }
            None => {
                let _ = writeln!(out, "  skipped  {:<18} nothing asked for it", stage);
            }
        }
    }
    let c = &page.cost;
    let _ = writeln!(
        out,
        "Symbolic engine: {}, {:.2} ms; whole scene {:.2} ms",
        count(c.engine_calls, "call"),
        c.symbolic_seconds * 1e3,
        c.seconds * 1e3
    );
    let _ = writeln!(out, "Numeric fidelity: {}", page.fidelity);
    let w = &c.numeric_work;
    let _ = writeln!(
        out,
        "Numeric work: {}, {}; {}, {}",
        count(w.ode_integrations, "ODE integration"),
        count(w.rhs_evaluations, "right-hand-side evaluation"),
        count(w.quadrature_runs, "quadrature run"),
        count(w.quadrature_points, "point")
    );
    out
}

/// Why a step's results fail `check`: not yet recorded, or which of them changed.
fn step_record_failure(s: &crate::verify::StepRecord) -> String {
    let Some((recorded, line)) = &s.recorded else {
        return format!(
            "step `{}` not yet recorded (derived {}): review it, then run `mechbook check \
             --bless`, which records it in the scene's [expect]",
            s.step,
            s.derived.join(", ")
        );
    };
    if s.derived.is_empty() {
        return format!(
            "[expect] records `{}`, which names no step or quantity of this scene (a step \
             renamed or removed?): `mechbook check --bless` removes it",
            s.step
        );
    }
    if recorded.len() != s.derived.len() {
        return format!(
            "step `{}` changed: it gives {}, and {} recorded (line {line}): derived {}",
            s.step,
            count(s.derived.len(), "result"),
            match recorded.len() {
                1 => "1 was".to_string(),
                n => format!("{n} were"),
            },
            s.derived.join(", ")
        );
    }
    let changes: Vec<String> = s
        .differing
        .iter()
        .map(|&k| {
            let which = if s.derived.len() == 1 {
                String::new()
            } else {
                format!("result {} ", k + 1)
            };
            format!("{which}recorded {}, derived {}", recorded[k], s.derived[k])
        })
        .collect();
    format!(
        "step `{}` changed since it was recorded (line {line}): {}; if the change is meant, run \
         `mechbook check --bless`",
        s.step,
        changes.join("; ")
    )
}

#[cfg(test)]
mod tests {
    use crate::model::fidelity::Fidelity;
    use crate::pipeline::run_scene;
    use crate::scene::Scene;

    /// `check` lists an erratum as a terminal reads it: the notes' statement and the note on
    /// its dimensions with their mathematics in Unicode (the cube's eq. (28)), never the
    /// LaTeX an author writes between dollars or mechbook sets on a page.
    #[test]
    fn the_terminal_lists_the_errata_without_latex() {
        let path = format!(
            "{}/lectures/lecture-3-4/05-cube-corner.toml",
            env!("CARGO_MANIFEST_DIR")
        );
        let scene = Scene::from_file(std::path::Path::new(&path)).unwrap();
        let report = run_scene(scene, Some(Fidelity::DRAFT)).unwrap();
        let table = super::check_table(&[report]);
        let line = |eq: &str| {
            let start = format!("eq ({eq}) [cube-corner] ");
            table
                .lines()
                .position(|l| l.trim_start().starts_with(&start))
        };
        let at = line("28").unwrap_or_else(|| panic!("eq. (28) is an erratum:\n{table}"));
        let notes = table.lines().skip(at + 1);
        let notes = notes.take_while(|l| l.starts_with("      "));
        let erratum: Vec<&str> = std::iter::once(table.lines().nth(at).unwrap())
            .chain(notes)
            .collect();
        for l in &erratum {
            assert!(!l.contains('$') && !l.contains('\\'), "{l}");
        }
        assert!(
            erratum[0].contains("I_xx = ρa(zy³/3 + yz³/a) evaluated"),
            "{}",
            erratum[0]
        );
        let dimension = erratum.iter().find(|l| l.contains("differ in dimension"));
        let dimension = dimension.unwrap_or_else(|| panic!("a note on dimension: {erratum:?}"));
        assert!(
            dimension.contains("aa³/3 is in m⁴ but aa³/a is in m³"),
            "{dimension}"
        );
    }
}
