//! Each author's step's results against those `check --bless` recorded under the step's name
//! in `[expect]`: `check` fails at the step's line when its physics changes, and never when
//! only its words do (a reason, a title, a `gives`: none of them is a result).

use crate::cas::{self, Expr};
use crate::derive::Derivation;
use crate::derive::step_names::Recordable;
use crate::scene::{NOT_DERIVED, Scene};

/// The relative difference within which a numeric result (a mode with no closed form) is as
/// recorded: far above an eigen-solver's round-off, far below any change of the physics.
pub const NUMBER_AGREEMENT: f64 = 1e-9;

/// One step's results against its record.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StepRecord {
    pub step: String,
    /// The step's line, where `check` reports a change.
    pub line: usize,
    /// As recorded, and the line of the `[expect]` key; `None` before the step is recorded.
    pub recorded: Option<(Vec<String>, usize)>,
    /// As derived now, written as `check --bless` records them; none for a record of a step
    /// the scene no longer has.
    pub derived: Vec<String>,
    /// The results (from 0) that differ from the record; each of them when the step gives
    /// another number of results than recorded.
    pub differing: Vec<usize>,
}

impl StepRecord {
    pub fn unchanged(&self) -> bool {
        self.recorded.is_some() && self.differing.is_empty()
    }
}

/// Every step with a result, against its record; the exact results compared in one call of
/// the engine.
pub fn check_step_records(scene: &Scene, d: &Derivation) -> Result<Vec<StepRecord>, cas::CasError> {
    let mut out: Vec<StepRecord> = Vec::new();
    let mut differences = Vec::new();
    let mut owners = Vec::new();
    for step in &scene.steps {
        let Some(result) = d.named.get(&step.name) else {
            continue;
        };
        let derived = result.recordables();
        if derived.is_empty() {
            continue;
        }
        let recorded = scene.step_records.get(&step.name);
        let mut differing = Vec::new();
        match recorded {
            None => {}
            Some(r) if r.values.len() != derived.len() => {
                differing = (0..derived.len().max(r.values.len())).collect();
            }
            Some(r) => {
                for (k, (now, then)) in derived.iter().zip(&r.values).enumerate() {
                    match now {
                        Recordable::Exact(e) => match cas::parse(then) {
                            Ok(p) if then != NOT_DERIVED => match entry_pairs(e, p.expr) {
                                Some(pairs) => {
                                    for (a, b) in pairs {
                                        differences.push(Expr::minus(a, b));
                                        owners.push((out.len(), k));
                                    }
                                }
                                None => differing.push(k),
                            },
                            _ => differing.push(k),
                        },
                        Recordable::Number(x) => {
                            if !then.trim().parse::<f64>().is_ok_and(|y| same_number(*x, y)) {
                                differing.push(k);
                            }
                        }
                        Recordable::NotDerived => {
                            if then != NOT_DERIVED {
                                differing.push(k);
                            }
                        }
                    }
                }
            }
        }
        out.push(StepRecord {
            step: step.name.clone(),
            line: step.line,
            recorded: recorded.map(|r| (r.values.clone(), r.line)),
            derived: derived.iter().map(Recordable::text).collect(),
            differing,
        });
    }
    // A record of a step the scene no longer has (renamed or removed).
    for (name, r) in &scene.step_records {
        if !scene.steps.iter().any(|s| s.name == *name) {
            out.push(StepRecord {
                step: name.clone(),
                line: r.line,
                recorded: Some((r.values.clone(), r.line)),
                derived: Vec::new(),
                differing: (0..r.values.len()).collect(),
            });
        }
    }
    for (zero, (i, k)) in cas::is_zero_all(differences)?.into_iter().zip(owners) {
        if !zero {
            out[i].differing.push(k);
        }
    }
    for r in &mut out {
        r.differing.sort_unstable();
        r.differing.dedup();
    }
    Ok(out)
}

/// The derived and recorded values entry by entry: one pair for an expression, one a
/// member for lists of the same length; `None` when their shapes differ.
fn entry_pairs(derived: &Expr, recorded: Expr) -> Option<Vec<(Expr, Expr)>> {
    match (derived, recorded) {
        (Expr::List(a), Expr::List(b)) if a.len() == b.len() => {
            Some(a.iter().cloned().zip(b).collect())
        }
        (Expr::List(_), _) | (_, Expr::List(_)) => None,
        (a, b) => Some(vec![(a.clone(), b)]),
    }
}

fn same_number(x: f64, y: f64) -> bool {
    (x - y).abs() <= NUMBER_AGREEMENT * x.abs().max(y.abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_agree_to_their_round_off_and_no_further() {
        assert!(same_number(0.0, 0.0));
        assert!(same_number(1.7320508075688772, 1.7320508075688774));
        assert!(!same_number(1.7320508075688772, 1.7320508));
        assert!(!same_number(0.0, 1e-300));
    }
}
