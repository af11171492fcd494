//! Requested outputs -> the stages that must run, and nothing more.
//!
//! A scene's `outputs.want`, the quantities its claims mention and its recorded results decide
//! the stages. `derive --explain` prints the plan: what ran, and what was skipped and why.

use crate::base::format::count;
use crate::cas::Expr;
use crate::model::catalogue::{Output, Stage, is_quantity, stage_for_quantity};
use crate::scene::{FreeInertia, PlotRequest, Scene};
use std::collections::BTreeSet;

#[derive(Debug, Clone)]
pub struct Plan {
    pub stages: BTreeSet<Stage>,
    /// Why each stage runs, for `--explain`.
    pub reasons: Vec<(Stage, String)>,
}

impl Plan {
    pub fn for_scene(scene: &Scene) -> Plan {
        let mut wanted: Vec<(Stage, String)> = Vec::new();
        wanted_by_outputs(scene, &mut wanted);
        if scene.moments_from_bodies {
            wanted.push((
                Stage::ParallelAxis,
                "`inertia = \"principal\"`: the free top's moments about the centre of mass".into(),
            ));
        }
        wanted_by_plots(scene, &mut wanted);
        wanted_by_names(scene, &mut wanted);
        if !scene.steps.is_empty() {
            wanted.push((Stage::Steps, count(scene.steps.len(), "step")));
        }
        if !scene.claims.is_empty() {
            wanted.push((Stage::Claims, count(scene.claims.len(), "claim")));
        }
        for name in scene.expect.keys() {
            if let Some(s) = stage_for_quantity(name) {
                wanted.push((s, format!("recorded result `{name}`")));
            }
        }
        wanted.push((
            Stage::Regression,
            if scene.expect.is_empty() {
                "no recorded results: each result fails until it is recorded".to_string()
            } else {
                count(scene.expect.len(), "recorded result")
            },
        ));

        let mut plan = Plan {
            stages: BTreeSet::new(),
            reasons: Vec::new(),
        };
        for (stage, why) in wanted {
            plan.add(stage, why);
        }
        plan
    }

    fn add(&mut self, stage: Stage, why: String) {
        if !self.reasons.iter().any(|(s, w)| *s == stage && *w == why) {
            self.reasons.push((stage, why));
        }
        if self.stages.insert(stage) {
            for req in stage.requires() {
                self.add(*req, format!("needed by {}", stage.name()));
            }
        }
    }

    pub fn runs(&self, stage: Stage) -> bool {
        self.stages.contains(&stage)
    }

    /// Each stage with `Some(reasons)` if it runs, `None` if it is skipped.
    pub fn explain(&self) -> Vec<(Stage, Option<Vec<String>>)> {
        Stage::ALL
            .iter()
            .map(|s| {
                let reasons: Vec<String> = self
                    .reasons
                    .iter()
                    .filter(|(t, _)| t == s)
                    .map(|(_, w)| w.clone())
                    .collect();
                (*s, self.runs(*s).then_some(reasons))
            })
            .collect()
    }
}

/// The stages each wanted output needs.
fn wanted_by_outputs(scene: &Scene, wanted: &mut Vec<(Stage, String)>) {
    for w in &scene.wants {
        let why = format!("output `{}`", w.name());
        let stages: &[Stage] = match w {
            Output::InertiaTensor => &[Stage::Tensor],
            Output::ParallelAxis => &[Stage::ParallelAxis],
            Output::PrincipalAxes => &[Stage::Principal],
            Output::AngularMomentum => &[Stage::AngularMomentum],
            Output::KineticEnergy => &[Stage::KineticEnergy],
            Output::MomentAboutAxis => &[Stage::MomentAboutAxis],
            Output::Gyration => &[Stage::Gyration],
            Output::Numeric => &[Stage::Quadrature],
            Output::EulerEquations => &[Stage::EulerEquations],
            Output::SymmetricTop => &[Stage::SymmetricTop],
            Output::AxisStability => &[Stage::AxisStability],
            Output::Poinsot => &[Stage::Poinsot],
            Output::EarthPrecession => &[Stage::EarthPrecession],
        };
        wanted.extend(stages.iter().map(|s| (*s, why.clone())));
    }
    // Numeric eigenvalues only when both the principal axes and the numerics are wanted.
    if scene.wants.contains(&Output::Numeric) && scene.wants.contains(&Output::PrincipalAxes) {
        wanted.push((
            Stage::NumericEigen,
            "outputs `principal_axes` and `numeric`".into(),
        ));
    }
}

/// The stages each plot needs.
fn wanted_by_plots(scene: &Scene, wanted: &mut Vec<(Stage, String)>) {
    for p in &scene.plots {
        let why = format!("plot `{}`", p.kind());
        wanted.push((Stage::Plots, why.clone()));
        if p.needs_body() {
            wanted.push((Stage::Tensor, why.clone()));
        }
        if *p == PlotRequest::PrincipalAxes {
            wanted.push((Stage::Principal, why.clone()));
        }
        // The body's own moments are taken about its centre of mass.
        if let PlotRequest::FreeBody {
            inertia: FreeInertia::Principal,
            ..
        } = p
        {
            wanted.push((Stage::CentreOfMass, why));
        }
    }
}

/// The stages of the quantities that claims, steps and answers name.
fn wanted_by_names(scene: &Scene, wanted: &mut Vec<(Stage, String)>) {
    for c in &scene.claims {
        for e in c.quantity.iter().chain(c.value.iter()) {
            for name in referenced_quantities(e) {
                if let Some(s) = stage_for_quantity(&name) {
                    wanted.push((s, format!("claim ({}) uses `{name}`", c.eq)));
                }
            }
        }
    }
    for s in &scene.steps {
        let exprs = s.op.operands();
        for e in exprs.into_iter().chain(s.gives.iter()).chain(&s.gives_each) {
            for name in referenced_quantities(e) {
                if let Some(st) = stage_for_quantity(&name) {
                    wanted.push((st, format!("step `{}` uses `{name}`", s.name)));
                }
            }
        }
    }
    for a in scene.problem.iter().flat_map(|p| &p.answers) {
        for name in referenced_quantities(&a.value) {
            if let Some(st) = stage_for_quantity(&name) {
                wanted.push((st, format!("the answer `{}` uses `{name}`", a.written)));
            }
        }
    }
}

/// Names of derived quantities an expression mentions, sorted.
pub fn referenced_quantities(e: &Expr) -> Vec<String> {
    e.symbols().into_iter().filter(|s| is_quantity(s)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn scene(body: &str) -> Scene {
        Scene::parse(body, Path::new("t.toml")).unwrap()
    }

    const HEAD: &str = include_str!("../tests/fixtures/unit/plan-head.toml");

    #[test]
    fn tensor_alone_runs_nothing_else() {
        let s = scene(&format!("{HEAD}[outputs]\nwant = [\"inertia_tensor\"]\n"));
        let p = Plan::for_scene(&s);
        // The record is always checked: with none, each result fails until it is recorded.
        assert_eq!(
            p.stages.iter().copied().collect::<Vec<_>>(),
            vec![Stage::Tensor, Stage::Regression]
        );
        let skipped = p.explain().iter().filter(|(_, r)| r.is_none()).count();
        assert_eq!(skipped, Stage::ALL.len() - 2);
    }

    #[test]
    fn claims_pull_in_the_stages_they_mention() {
        let s = scene(&format!(
            "{HEAD}[outputs]\nwant = []\n[[claim]]\neq = \"1\"\nstatement = \"s\"\nquantity = \"principal_moments[0]\"\nvalue = \"m*a^2/6\"\nexpect = \"agrees\"\n"
        ));
        let p = Plan::for_scene(&s);
        assert!(p.runs(Stage::Principal) && p.runs(Stage::Tensor) && p.runs(Stage::Claims));
        assert!(!p.runs(Stage::Quadrature) && !p.runs(Stage::ParallelAxis));
    }

    #[test]
    fn gyration_needs_the_moment_and_the_principal_axes() {
        let s = scene(&format!("{HEAD}[outputs]\nwant = [\"gyration\"]\n"));
        let p = Plan::for_scene(&s);
        for st in [
            Stage::Gyration,
            Stage::MomentAboutAxis,
            Stage::Principal,
            Stage::Tensor,
        ] {
            assert!(p.runs(st), "{st:?}");
        }
        assert!(!p.runs(Stage::NumericEigen));
    }
}
