//! The JSON report of each page: what `derive --json` prints and what a build writes to
//! `export/json/`, one file a scene, with the course's lectures in `export/json/course.json`.

use super::RenderError;
use super::renderer::{Context, Plots, Rendered, Renderer};
use crate::cas::Expr;
use crate::derive::ExactBasis;
use crate::document::course::Documents;
use crate::document::{Page, Quantity, Step};
use crate::model::prose::{Piece, Prose};
use crate::model::value::Value;
use crate::notation::Names;
use crate::numeric::eigen::Space;
use serde_json::{Value as Json, json};

/// Each scene's page, `export/json/<scene id>.json`, and the lectures in order,
/// `export/json/course.json`. Measured seconds are left out unless the build shows timings, so
/// that a build's files are the same each time.
pub struct JsonReport;

impl Renderer for JsonReport {
    fn render(&self, docs: &Documents, _: &Plots, cx: &Context) -> Result<Rendered, RenderError> {
        let mut out = Rendered::default();
        // A problem's page holds every variant's answers: none where answers are private.
        let published: Vec<usize> = (0..docs.pages.len())
            .filter(|&i| !(cx.course.answers_private && docs.is_problem(i)))
            .collect();
        // Each page's file on both cores, added in the pages' order.
        let files = crate::base::in_order::map_in_order(&published, |&i| {
            let page = &docs.pages[i];
            let unit = super::memo::key(&[&"json", &cx.keys.of(docs, i), &cx.timings]);
            super::memo::recall_or(cx.memo, format!("{}.json", page.id), unit, || {
                let mut j = scene_json(page);
                if !cx.timings {
                    without_seconds(&mut j);
                }
                Ok::<_, RenderError>(pretty(&j))
            })
        });
        for (&i, made) in published.iter().zip(files) {
            let (text, kept) = made?;
            out.kept.extend(kept);
            super::renderer::add(
                &mut out.files,
                format!("export/json/{}.json", docs.pages[i].id),
                text.into_bytes(),
            )?;
        }
        let lectures: Vec<Json> = docs
            .lectures
            .iter()
            .map(|l| {
                json!({
                    "lecture": l.name,
                    "heading": l.heading,
                    "scenes": l.pages.iter().filter(|i| published.contains(i))
                        .map(|i| &docs.pages[*i].id).collect::<Vec<_>>(),
                })
            })
            .collect();
        let course = json!({ "title": cx.course.title, "lectures": lectures });
        super::renderer::add(
            &mut out.files,
            "export/json/course.json",
            pretty(&course).into_bytes(),
        )?;
        Ok(out)
    }
}

fn pretty(j: &Json) -> String {
    let mut text = serde_json::to_string_pretty(j).expect("JSON values print");
    text.push('\n');
    text
}

/// The report with every measured time (`seconds`, `symbolic_seconds`) taken out.
fn without_seconds(j: &mut Json) {
    match j {
        Json::Object(map) => {
            map.remove("seconds");
            map.remove("symbolic_seconds");
            map.values_mut().for_each(without_seconds);
        }
        Json::Array(items) => items.iter_mut().for_each(without_seconds),
        _ => {}
    }
}

/// Numbers as JSON; a non-finite value becomes null rather than invalid JSON.
fn num(x: f64) -> Json {
    serde_json::Number::from_f64(x)
        .map(Json::Number)
        .unwrap_or(Json::Null)
}

/// A quantity's entries at the scene's values, in its shape.
/// Numbers as JSON, null where there is none.
fn numbers_json(numbers: &[Option<f64>]) -> Vec<Json> {
    numbers
        .iter()
        .map(|x| x.map(num).unwrap_or(Json::Null))
        .collect()
}

fn numeric_entries(q: &Quantity) -> Json {
    let vals = numbers_json(&q.numbers);
    match q.value {
        Value::Scalar(_) => vals.into_iter().next().unwrap_or(Json::Null),
        Value::Vector(_) => Json::Array(vals),
        Value::Matrix(_) => Json::Array(vals.chunks(3).map(|c| Json::Array(c.to_vec())).collect()),
    }
}

fn vec_text(v: &[crate::cas::Expr; 3]) -> String {
    Value::Vector(v.clone()).to_text()
}

/// A step: its statement and reason, each formula printed as text and as LaTeX.
fn step_json(st: &Step, names: &Names) -> Json {
    let mut j = json!({
        "title": st.title.to_author_text(names),
        "text": st.statement.to_text(),
        "latex": st.statement.to_latex(names),
        "why": st.why.to_text(),
    });
    if !st.key.is_empty() {
        j["cite"] = json!(st.key);
    }
    // The exact result as derived, where the statement prints it in a textbook's form.
    if let Some(exact) = &st.exact {
        j["exact"] = json!({ "text": exact.to_text(), "latex": exact.to_latex(names) });
    }
    if st.why.0.iter().any(|p| matches!(p, Piece::Math(_))) {
        j["why_math"] = prose_json(&st.why, names);
    }
    j
}

/// A sentence: its words, and its formulas as text and LaTeX.
fn prose_json(p: &Prose, names: &Names) -> Json {
    p.0.iter()
        .map(|piece| match piece {
            Piece::Text(t) => json!({ "Text": t }),
            Piece::Math(f) => {
                json!({ "Math": { "text": f.to_text(), "latex": f.to_latex(names) } })
            }
        })
        .collect()
}

/// A recorded result's derived side as the reports print it.
pub fn derived_text(g: &crate::verify::RegressionResult) -> String {
    g.derived
        .as_ref()
        .map_or_else(|| "(not derived)".into(), Value::to_text)
}

/// One scene's page as JSON, in the shape docs/usage.md gives (`--json`).
pub fn scene_json(page: &Page) -> Json {
    // Each name as the scene typesets it, as on the page.
    let names = &page.names;
    let quantities = quantities_json(page);
    let claims = claims_json(page);
    let numeric_checks = numeric_checks_json(page);
    let principal = principal_axes_json(page);
    let stages: Vec<Json> = page
        .stages
        .iter()
        .map(|(st, why)| json!({ "stage": st, "ran": why.is_some(), "because": why.clone().unwrap_or_default() }))
        .collect();
    let cost = &page.cost;
    json!({
        "id": page.id,
        "title": page.title,
        "source": page.source.to_string_lossy(),
        "notes": { "lecture": page.lecture, "section": page.section, "equations": page.equations },
        "passed": page.passed,
        "quantities": quantities,
        "principal_axes": principal,
        "principal_moments": principal_moments_json(page),
        "claims": claims,
        "numeric_checks": numeric_checks,
        "exact_vs_numeric": page.exact_vs_numeric.iter().map(|q| json!({
            "quantity": q.name, "error": num(q.error), "passed": q.passed })).collect::<Vec<_>>(),
        "eigen_check": page.eigen.as_ref().map(|e| json!({
            "value_error": num(e.value_error), "axis_error": num(e.axis_error), "passed": e.passed })),
        "regressions": page.regressions.iter().map(|g| json!({
            "quantity": g.quantity, "recorded": g.recorded.as_ref().map(Expr::to_text), "derived": derived_text(g),  "unchanged": g.unchanged })).collect::<Vec<_>>(),
        "variants": variants_json(page),
        "steps": page.steps.iter().map(|s| step_json(s, names)).collect::<Vec<_>>(),
        "step_checks": page.step_checks.iter().map(|c| json!({
            "step": c.step, "method": c.method, "error": num(c.error), "tolerance": num(c.tolerance),
            "evaluations": c.evaluations, "problem": c.problem, "passed": c.passed() })).collect::<Vec<_>>(),
        "stages": stages,
        "symbolic_seconds": num(cost.symbolic_seconds),
        "engine_calls": cost.engine_calls,
        "numeric_work": cost.numeric_work,
        "fidelity": { "name": page.fidelity.name(), "tolerance": page.fidelity.tolerance, "max_points": page.fidelity.max_points() },
        "figures": page.figures.iter().map(|f| json!({
            "slug": f.slug,
            "accuracy": f.accuracy.iter().map(|a| json!({
                "result": a.result, "method": a.method, "true_error": a.true_error.map(num),
                "estimated_error": a.estimated_error.map(num), "cost": a.cost, "unit": a.unit,
                "seconds": num(a.seconds) })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
    })
}

/// Each body's quadrature: its rule, points, errors and time.
fn numeric_checks_json(page: &Page) -> Vec<Json> {
    page.numeric
        .iter()
        .map(|q| {
            json!({
                "body": q.body,
                "method": q.method,
                "points": q.points,
                "error": num(q.error),
                "predicted_error": num(q.predicted_error),
                "seconds": num(q.seconds),
                "within_law": q.within_law,
                "stop": q.stop,
            })
        })
        .collect()
}

/// Each principal moment, exact and at the scene's values, with its eigenspace.
fn principal_axes_json(page: &Page) -> Vec<Json> {
    page.principal_axes
        .iter()
        .map(|sp| {
            let (kind, dir) = match &sp.basis {
                ExactBasis::Axis(a) => ("axis", Some(vec_text(a))),
                ExactBasis::PlaneNormalTo(n) => ("plane-normal-to", Some(vec_text(n))),
                ExactBasis::All => ("all", None),
            };
            json!({
                "value": sp.value.to_text(),
                "numeric": sp.number.map(num).unwrap_or(Json::Null),
                "multiplicity": sp.multiplicity,
                "eigenspace": kind,
                "direction": dir,
            })
        })
        .collect()
}

/// The principal moments at the scene's values, exact and by the eigen-solver, with its axes.
fn principal_moments_json(page: &Page) -> Option<Json> {
    page.principal_values.as_ref().map(|p| json!({
        "values": p.exact.iter().map(|v| num(*v)).collect::<Vec<_>>(),
        "closed_form": p.closed_form,
        "numeric": p.numeric.iter().flat_map(|e| std::iter::repeat_n(num(e.value), e.multiplicity)).collect::<Vec<_>>(),
        "axes": p.numeric.iter().map(|e| match &e.space {
            Space::Axis(v) => json!({ "axis": ([v.x, v.y, v.z].map(num)) }),
            Space::PlaneNormalTo(v) => json!({ "plane_normal_to": ([v.x, v.y, v.z].map(num)) }),
            Space::All => json!("all"),
        }).collect::<Vec<_>>(),
        "error": num(p.error),
    }))
}

/// Each quantity's exact form, LaTeX and numbers; a number with no exact form, and a list.
fn quantities_json(page: &Page) -> serde_json::Map<String, Json> {
    let names = &page.names;
    let mut quantities = serde_json::Map::new();
    for q in &page.quantities {
        quantities.insert(
            q.name.clone(),
            json!({ "exact": q.value.to_text(), "latex": q.value.to_expr().to_latex(names), "numeric": numeric_entries(q) }),
        );
    }
    // A number with no exact form: no `exact` text that would be a float in disguise.
    for (name, w) in &page.numeric_results {
        quantities.insert(
            name.clone(),
            json!({ "exact": null, "latex": null, "numeric": [num(*w)], "numeric_only": true }),
        );
    }
    // A state of rest of several coordinates, or the minors about it: a list, and its numbers.
    for list in &page.list_results {
        let exact = Expr::List(list.entries.clone());
        quantities.insert(
            list.name.clone(),
            json!({ "exact": exact.to_text(), "latex": exact.to_latex(names), "numeric": numbers_json(&list.numbers) }),
        );
    }
    quantities
}

/// Each claim, its sides as text and its verdict.
fn claims_json(page: &Page) -> Vec<Json> {
    page.claims
        .iter()
        .map(|c| {
            let mut claim = json!({
                "eq": c.eq,
                "statement": c.statement,
                "notes": c.notes.as_ref().map(Expr::to_text).unwrap_or_default(),
                "derived": c.derived.as_ref().map(Value::to_text).unwrap_or_default(),
                "verdict": c.verdict.as_str(),
                "expected": c.expected.map(|v| v.as_str()),
                "passed": c.passed(),
                "differences": c.differences.iter().map(|d| d.to_text()).collect::<Vec<_>>(),
                "problem": c.problem,
                "precision": c.precision,
            });
            // The symbols an agreement takes to be positive, where it rests on that.
            if c.where_real {
                claim["where_real"] = json!(true);
            }
            if !c.positive.is_empty() {
                claim["positive"] = json!(c.positive);
            }
            claim
        })
        .collect()
}

/// Each variant's values and answers, exact and in numbers, with their tolerance.
fn variants_json(page: &Page) -> Vec<Json> {
    let names = &page.names;
    // An answer on a numeric result has a number at each variant, not an exact form.
    let numeric_only = |e: &Expr| {
        e.symbols()
            .iter()
            .any(|s| page.numeric_results.iter().any(|(n, _)| n == s))
    };
    page.variants.iter().map(|v| json!({
        "number": v.number,
        "values": v.values.iter().map(|(name, e)| (name.clone(), json!({
            "exact": e.to_text(),
            "latex": e.to_latex(names),
            "numeric": e.eval(&|_| None).ok().map(num),
        }))).collect::<serde_json::Map<_, _>>(),
        "passed": v.passed(),
        "answers": v.answers.iter().zip(&page.answers).map(|(a, spec)| json!({
            "quantity": a.quantity,
            "label": spec.label,
            "unit": spec.unit.as_ref().map(|u| &u.text),
            // An answer on a numeric mode has its number at each variant, not an exact form.
            "exact": (!numeric_only(&spec.value)).then(|| a.exact.to_text()),
            "latex": (!numeric_only(&spec.value)).then(|| a.exact.to_expr().to_latex(names)),
            "entries": if numeric_only(&spec.value) { Vec::new() } else { a.exact.entries().iter().map(|e| e.to_latex(names)).collect::<Vec<_>>() },
            "numeric_only": numeric_only(&spec.value),
            "numeric": a.exact_numbers.iter().map(|x| num(*x)).collect::<Vec<_>>(),
            "independent": a.numeric.iter().map(|x| num(*x)).collect::<Vec<_>>(),
            "error": num(a.error),
            "tolerance": num(a.tolerance),
            // A quiz's agreement, relative to the answer's largest entry (the LMS exports').
            "quiz_tolerance": num(spec.tolerance),
            "passed": a.passed(),
        })).collect::<Vec<_>>(),
    })).collect::<Vec<_>>()
}
