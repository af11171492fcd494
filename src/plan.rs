//! Requested outputs -> the stages that must run, and nothing more.
//!
//! A scene's `outputs.want`, the quantities its claims mention and its recorded results decide
//! the stages. `derive --explain` prints the plan: what ran, and what was skipped and why.

use crate::cas::Expr;
use crate::scene::{Output, PlotRequest, Scene};
use std::collections::BTreeSet;

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Stage {
    /// Symbolic: ∫dm and I_jk for every body (eqs 9–10, 26).
    Tensor,
    /// Symbolic: the centre of mass and the tensor about it.
    CentreOfMass,
    /// Symbolic: I_cm + M(d²𝟙 − ddᵀ) proved equal to direct integration (eqs 20–22).
    ParallelAxis,
    /// Symbolic: exact roots of det(I − λ𝟙) and their eigenspaces (eqs 47–52).
    Principal,
    /// Symbolic: L = Iω, and for point masses L = Σ m r×(ω×r) proved equal (eqs 3–8).
    AngularMomentum,
    /// Symbolic: T = ½ωᵀIω, and for point masses ½Σm|ω×r|² proved equal (eqs 16–18, 23–25).
    KineticEnergy,
    /// Symbolic: I_n = nᵀIn, and for point masses Σm|r×n|² proved equal (eqs 19–20, 55).
    MomentAboutAxis,
    /// Symbolic: radius of gyration and the inertia ellipsoid (eqs 53–59).
    Gyration,
    /// Symbolic: Euler's equations from dL/dt|body + ω × L = N (eqs 60–65).
    EulerEquations,
    /// Symbolic: the torque-free symmetric top, its solution and cones (eqs 66–71).
    SymmetricTop,
    /// Symbolic: linearisation about each principal axis and its stability (eqs 72–76).
    AxisStability,
    /// Symbolic: Poinsot's construction, the bounds on L² and the polhodes (eqs 77–87).
    Poinsot,
    /// Symbolic: Earth's Euler period from cited constants (after eq 89).
    EarthPrecession,
    /// Numeric: quadrature of every body, with error laws and cost.
    Quadrature,
    /// Numeric: SymmetricEigen against the exact principal moments.
    NumericEigen,
    /// Numeric: the data of the scene's `[[plot]]`s (sweeps, convergence runs, projections).
    Plots,
    /// Verify the notes' claims.
    Claims,
    /// Compare with the results recorded in the scene.
    Regression,
}

impl Stage {
    pub const ALL: &'static [Stage] = &[
        Stage::Tensor,
        Stage::CentreOfMass,
        Stage::ParallelAxis,
        Stage::Principal,
        Stage::AngularMomentum,
        Stage::KineticEnergy,
        Stage::MomentAboutAxis,
        Stage::Gyration,
        Stage::EulerEquations,
        Stage::SymmetricTop,
        Stage::AxisStability,
        Stage::Poinsot,
        Stage::EarthPrecession,
        Stage::Quadrature,
        Stage::NumericEigen,
        Stage::Plots,
        Stage::Claims,
        Stage::Regression,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Stage::Tensor => "tensor",
            Stage::CentreOfMass => "centre-of-mass",
            Stage::ParallelAxis => "parallel-axis",
            Stage::Principal => "principal-axes",
            Stage::AngularMomentum => "angular-momentum",
            Stage::KineticEnergy => "kinetic-energy",
            Stage::MomentAboutAxis => "moment-about-axis",
            Stage::Gyration => "gyration",
            Stage::EulerEquations => "euler-equations",
            Stage::SymmetricTop => "symmetric-top",
            Stage::AxisStability => "axis-stability",
            Stage::Poinsot => "poinsot",
            Stage::EarthPrecession => "earth-precession",
            Stage::Quadrature => "numeric-quadrature",
            Stage::NumericEigen => "numeric-eigen",
            Stage::Plots => "plots",
            Stage::Claims => "claims",
            Stage::Regression => "regression",
        }
    }

    /// The stages this one needs first.
    fn requires(self) -> &'static [Stage] {
        match self {
            Stage::Tensor
            | Stage::Claims
            | Stage::Regression
            | Stage::EulerEquations
            | Stage::SymmetricTop
            | Stage::AxisStability
            | Stage::Poinsot
            | Stage::EarthPrecession => &[],
            Stage::CentreOfMass => &[Stage::Tensor],
            Stage::ParallelAxis => &[Stage::CentreOfMass],
            Stage::Principal
            | Stage::AngularMomentum
            | Stage::KineticEnergy
            | Stage::MomentAboutAxis
            | Stage::Quadrature => &[Stage::Tensor],
            Stage::Plots => &[],
            Stage::Gyration => &[Stage::MomentAboutAxis, Stage::Principal],
            Stage::NumericEigen => &[Stage::Principal, Stage::Quadrature],
        }
    }
}

/// Which derived quantity needs which stage.
fn stage_for_quantity(name: &str) -> Option<Stage> {
    Some(match name {
        "mass" | "inertia_tensor" | "integrand" | "position" => Stage::Tensor,
        "centre_of_mass" => Stage::CentreOfMass,
        "inertia_cm" => Stage::ParallelAxis,
        "principal_moments" => Stage::Principal,
        "angular_momentum" | "angular_momentum_direct" => Stage::AngularMomentum,
        "kinetic_energy" | "kinetic_energy_direct" => Stage::KineticEnergy,
        "moment_about_axis" | "moment_about_axis_direct" => Stage::MomentAboutAxis,
        "radius_of_gyration" => Stage::Gyration,
        "principal_momentum"
        | "gyroscopic_term"
        | "euler_equations"
        | "body_rate_of_momentum"
        | "torque_free_rates" => Stage::EulerEquations,
        "w1_second_derivative"
        | "symmetric_solution"
        | "symmetric_residual"
        | "omega_squared"
        | "precession_rate"
        | "body_cone_tan_squared"
        | "space_cone_cos_squared"
        | "momentum_tilt_tan_squared"
        | "cone_order" => Stage::SymmetricTop,
        "oscillation_frequency_squared"
        | "amplitude_ratio_squared"
        | "stability"
        | "growth_rate_squared" => Stage::AxisStability,
        "ellipsoid_value"
        | "gradient_factor_squared"
        | "plane_distance_squared"
        | "energy_from_momentum"
        | "momentum_gap"
        | "polhode_conic_product"
        | "polhode_closure"
        | "separatrix_slope_squared" => Stage::Poinsot,
        "earth_beta"
        | "euler_period_sidereal_days"
        | "euler_period_solar_days"
        | "chandler_ratio"
        | "bulge_km"
        | "bulge_fraction" => Stage::EarthPrecession,
        _ => return None,
    })
}

#[derive(Debug, Clone)]
pub struct Plan {
    pub stages: BTreeSet<Stage>,
    /// Why each stage runs, for `--explain`.
    pub reasons: Vec<(Stage, String)>,
}

impl Plan {
    pub fn for_scene(scene: &Scene) -> Plan {
        let mut wanted: Vec<(Stage, String)> = Vec::new();
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
        for p in &scene.plots {
            let why = format!("plot `{}`", p.kind());
            wanted.push((Stage::Plots, why.clone()));
            if p.needs_body() {
                wanted.push((Stage::Tensor, why.clone()));
            }
            if *p == PlotRequest::PrincipalAxes {
                wanted.push((Stage::Principal, why));
            }
        }
        for c in &scene.claims {
            for e in c.quantity.iter().chain(c.value.iter()) {
                for name in referenced_quantities(e) {
                    if let Some(s) = stage_for_quantity(&name) {
                        wanted.push((s, format!("claim ({}) uses `{name}`", c.eq)));
                    }
                }
            }
        }
        if !scene.claims.is_empty() {
            wanted.push((Stage::Claims, format!("{} claim(s)", scene.claims.len())));
        }
        for name in scene.expect.keys() {
            if let Some(s) = stage_for_quantity(name) {
                wanted.push((s, format!("recorded result `{name}`")));
            }
        }
        if !scene.expect.is_empty() {
            wanted.push((
                Stage::Regression,
                format!("{} recorded result(s)", scene.expect.len()),
            ));
        }

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

/// Names of derived quantities an expression mentions, sorted.
pub fn referenced_quantities(e: &Expr) -> Vec<String> {
    e.symbols()
        .into_iter()
        .filter(|s| crate::scene::is_quantity(s))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn scene(body: &str) -> Scene {
        Scene::parse(body, Path::new("t.toml")).unwrap()
    }

    const HEAD: &str = r#"
id = "t"
title = "t"
notes = { lecture = "3/4" }
symbols = { m = "mass", a = "side" }
axis = ["1", "0", "0"]
[[body]]
kind = "box"
size = ["a", "a", "a"]
mass = "m"
[numeric]
values = { m = 1.0, a = 1.0 }
"#;

    #[test]
    fn tensor_alone_runs_nothing_else() {
        let s = scene(&format!("{HEAD}[outputs]\nwant = [\"inertia_tensor\"]\n"));
        let p = Plan::for_scene(&s);
        assert_eq!(
            p.stages.iter().copied().collect::<Vec<_>>(),
            vec![Stage::Tensor]
        );
        let skipped = p.explain().iter().filter(|(_, r)| r.is_none()).count();
        assert_eq!(skipped, Stage::ALL.len() - 1);
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
