//! How hard the numeric stage works: a target relative error, and the cost it may spend to
//! reach it. One setting picks the quadrature ladder, the integrators' steps and tolerances and
//! the plot sampling, so that a draft build is quick and a reference build is thorough, and
//! every result says which it was.

use std::fmt;

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Level {
    Draft,
    Standard,
    Reference,
    /// An explicit target tolerance, with the cost caps of the nearest level.
    Target,
}

/// A fidelity that is not one.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FidelityError {
    #[error(
        "the target tolerance {0:e} must lie in [1e-15, 1): below 1e-15 round-off alone exceeds it"
    )]
    Tolerance(f64),
    #[error("unknown fidelity `{0}`: use {names}", names = Fidelity::NAMES)]
    Unknown(String),
}

#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Fidelity {
    pub level: Level,
    /// The relative error each numeric result aims for.
    pub tolerance: f64,
}

/// The standard level's tolerance: the plots' steps and tolerances were tuned at it, and the
/// other levels scale them from there.
const STANDARD_TOLERANCE: f64 = 1e-8;

impl Fidelity {
    pub const DRAFT: Fidelity = Fidelity {
        level: Level::Draft,
        tolerance: 1e-3,
    };
    pub const STANDARD: Fidelity = Fidelity {
        level: Level::Standard,
        tolerance: STANDARD_TOLERANCE,
    };
    pub const REFERENCE: Fidelity = Fidelity {
        level: Level::Reference,
        tolerance: 1e-12,
    };
    pub const NAMES: &'static str = "draft, standard, reference, or a tolerance such as 1e-6";

    /// `draft`, `standard`, `reference`, or a target tolerance strictly between 1e-15 and 1.
    pub fn parse(s: &str) -> Result<Fidelity, FidelityError> {
        match s.trim() {
            "draft" => Ok(Fidelity::DRAFT),
            "standard" => Ok(Fidelity::STANDARD),
            "reference" => Ok(Fidelity::REFERENCE),
            other => match other.parse::<f64>() {
                Ok(t) if t.is_finite() && (1e-15..1.0).contains(&t) => Ok(Fidelity {
                    level: Level::Target,
                    tolerance: t,
                }),
                Ok(t) => Err(FidelityError::Tolerance(t)),
                Err(_) => Err(FidelityError::Unknown(other.to_string())),
            },
        }
    }

    /// The level whose cost caps apply: an explicit tolerance borrows the nearest level's.
    fn tier(&self) -> Level {
        match self.level {
            Level::Target if self.tolerance >= 1e-5 => Level::Draft,
            Level::Target if self.tolerance >= 1e-10 => Level::Standard,
            Level::Target => Level::Reference,
            l => l,
        }
    }

    /// The most points one quadrature run may use.
    pub fn max_points(&self) -> usize {
        match self.tier() {
            Level::Draft => 20_000,
            Level::Standard => 300_000,
            _ => 3_000_000,
        }
    }

    /// Samples for a plotted curve that has `at_standard` of them at the standard level.
    pub fn samples(&self, at_standard: usize) -> usize {
        match self.tier() {
            Level::Draft => (at_standard / 4).max(24),
            Level::Standard => at_standard,
            _ => at_standard * 2,
        }
    }

    /// An adaptive integrator's tolerance, given the one a plot uses at the standard level:
    /// scaled with the target, never below what double precision can honour.
    pub fn ode_tolerance(&self, at_standard: f64) -> f64 {
        (at_standard * self.tolerance / STANDARD_TOLERANCE).clamp(1e-14, 1e-2)
    }

    /// A fixed step, given the one a plot uses at the standard level. The plots' fixed-step
    /// runs compare integrators, so the step follows the target as a fourth-order method's would
    /// (h ∝ tol^¼), kept within 4× either way so that every method stays stable and visible.
    pub fn ode_step(&self, at_standard: f64) -> f64 {
        let scale = (self.tolerance / STANDARD_TOLERANCE)
            .powf(0.25)
            .clamp(0.25, 4.0);
        at_standard * scale
    }

    /// The `--fidelity` argument that gives this fidelity back, exactly.
    pub fn argument(&self) -> String {
        match self.level {
            Level::Target => self.tolerance.to_string(),
            _ => self.name(),
        }
    }

    /// The name as a scene or the command line gives it.
    pub fn name(&self) -> String {
        match self.level {
            Level::Draft => "draft".into(),
            Level::Standard => "standard".into(),
            Level::Reference => "reference".into(),
            Level::Target => format!("target {}", crate::base::format::short(self.tolerance)),
        }
    }
}

impl Default for Fidelity {
    fn default() -> Fidelity {
        Fidelity::STANDARD
    }
}

impl fmt::Display for Fidelity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} (target relative error {}, at most {} points per quadrature run)",
            self.name(),
            crate::base::format::short(self.tolerance),
            self.max_points()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_argument_parses_back_to_the_same_fidelity() {
        for f in ["draft", "standard", "reference", "1e-6", "3.3e-9", "0.25"] {
            let fid = Fidelity::parse(f).unwrap();
            assert_eq!(Fidelity::parse(&fid.argument()), Ok(fid), "{f}");
        }
    }

    #[test]
    fn names_and_tolerances_parse() {
        assert_eq!(Fidelity::parse("draft"), Ok(Fidelity::DRAFT));
        assert_eq!(Fidelity::parse("reference"), Ok(Fidelity::REFERENCE));
        let t = Fidelity::parse("1e-6").unwrap();
        assert_eq!((t.level, t.tolerance), (Level::Target, 1e-6));
        assert_eq!(t.max_points(), Fidelity::STANDARD.max_points());
        for bad in ["fast", "0", "-1e-3", "1", "nan", "inf", "1e-16"] {
            let e = Fidelity::parse(bad).unwrap_err();
            let expected = match bad {
                "fast" => matches!(e, FidelityError::Unknown(_)),
                _ => matches!(e, FidelityError::Tolerance(_)),
            };
            assert!(expected, "{bad}: {e:?}");
        }
    }

    #[test]
    fn the_levels_order_cost_and_accuracy() {
        let [d, s, r] = [Fidelity::DRAFT, Fidelity::STANDARD, Fidelity::REFERENCE];
        assert!(d.tolerance > s.tolerance && s.tolerance > r.tolerance);
        assert!(d.max_points() < s.max_points() && s.max_points() < r.max_points());
        assert!(d.samples(400) < s.samples(400) && s.samples(400) < r.samples(400));
        assert!(d.ode_step(0.05) > s.ode_step(0.05) && s.ode_step(0.05) > r.ode_step(0.05));
        assert!(d.ode_tolerance(1e-10) > r.ode_tolerance(1e-10));
        // The standard level reproduces the plots' own settings exactly.
        assert_eq!(s.ode_step(0.05), 0.05);
        assert_eq!(s.ode_tolerance(1e-10), 1e-10);
        assert_eq!(r.ode_tolerance(1e-11), 1e-14);
    }
}
