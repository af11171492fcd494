//! `check --json`: the reports' summary, each scene as the JSON renderer prints its page.

use super::failures;
use crate::pipeline::SceneReport;
use crate::render::json::scene_json;
use crate::scene::Verdict;
use serde_json::{Value as Json, json};

/// `check --json`: whether everything passed, the counts a CI summary needs, every failure on
/// one located line, and each scene. `not_derived` are the scenes that could not be derived.
pub fn check_json(reports: &[SceneReport], not_derived: &[String]) -> Json {
    let failures: Vec<String> = reports
        .iter()
        .flat_map(failures)
        .map(|f| f.text)
        .chain(not_derived.iter().cloned())
        .collect();
    let claims = reports.iter().flat_map(|r| &r.verification.claims);
    let count = |v: Verdict| claims.clone().filter(|c| c.verdict == v).count();
    json!({
        "passed": failures.is_empty(),
        "counts": {
            "scenes": reports.len() + not_derived.len(),
            "scenes_passed": reports.iter().filter(|r| r.passed()).count(),
            "scenes_failed": reports.iter().filter(|r| !r.passed()).count(),
            "scenes_not_derived": not_derived.len(),
            "claims": claims.clone().count(),
            "agree": count(Verdict::Agrees),
            "disagree": count(Verdict::Disagrees),
            "failures": failures.len(),
        },
        "failures": failures,
        "scenes": reports
            .iter()
            .map(|r| scene_json(&crate::document::page(r, None, None)))
            .collect::<Vec<_>>(),
    })
}
