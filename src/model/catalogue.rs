//! The shared vocabulary of the pipeline: what a scene may ask for (outputs), the stages that
//! compute it, and the names of the derived quantities, each with the stage that produces it.
//! Scene validation, the plan, the derivations, verification and the pages all read it here.

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
    /// Symbolic: the author's own `[[step]]`s, each with its numeric check.
    Steps,
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
        Stage::Steps,
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
            Stage::Steps => "steps",
            Stage::Quadrature => "numeric-quadrature",
            Stage::NumericEigen => "numeric-eigen",
            Stage::Plots => "plots",
            Stage::Claims => "claims",
            Stage::Regression => "regression",
        }
    }

    /// The stages this one needs first.
    pub fn requires(self) -> &'static [Stage] {
        match self {
            Stage::Tensor
            | Stage::Claims
            | Stage::Regression
            | Stage::EulerEquations
            | Stage::SymmetricTop
            | Stage::AxisStability
            | Stage::Poinsot
            | Stage::EarthPrecession
            | Stage::Steps => &[],
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

/// Which stage derives a quantity.
pub fn stage_for_quantity(name: &str) -> Option<Stage> {
    find(name).map(|q| q.stage)
}

/// What a scene asks for. Each one pulls in the stages it needs (see `plan`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Output {
    InertiaTensor,
    ParallelAxis,
    PrincipalAxes,
    AngularMomentum,
    KineticEnergy,
    MomentAboutAxis,
    Gyration,
    Numeric,
    EulerEquations,
    SymmetricTop,
    AxisStability,
    Poinsot,
    EarthPrecession,
}

impl Output {
    pub const ALL: &'static [(&'static str, Output)] = &[
        ("inertia_tensor", Output::InertiaTensor),
        ("parallel_axis", Output::ParallelAxis),
        ("principal_axes", Output::PrincipalAxes),
        ("angular_momentum", Output::AngularMomentum),
        ("kinetic_energy", Output::KineticEnergy),
        ("moment_about_axis", Output::MomentAboutAxis),
        ("gyration", Output::Gyration),
        ("numeric", Output::Numeric),
        ("euler_equations", Output::EulerEquations),
        ("symmetric_top", Output::SymmetricTop),
        ("axis_stability", Output::AxisStability),
        ("poinsot", Output::Poinsot),
        ("earth_precession", Output::EarthPrecession),
    ];

    pub fn name(self) -> &'static str {
        Output::ALL.iter().find(|(_, o)| *o == self).unwrap().0
    }

    /// The symbols a free-body derivation writes its results in, which the scene must declare;
    /// `None` for the outputs computed from the scene's bodies.
    pub fn free_body_symbols(self) -> Option<&'static [&'static str]> {
        Some(match self {
            Output::EulerEquations => EULER_SYMBOLS,
            Output::SymmetricTop => SYMMETRIC_TOP_SYMBOLS,
            Output::AxisStability => STABILITY_SYMBOLS,
            Output::Poinsot => POINSOT_SYMBOLS,
            Output::EarthPrecession => EARTH_SYMBOLS,
            _ => return None,
        })
    }
}

/// The name of every derived quantity, as claims, recorded results and reports write it.
pub mod quantity {
    pub const MASS: &str = "mass";
    pub const CENTRE_OF_MASS: &str = "centre_of_mass";
    pub const INERTIA_TENSOR: &str = "inertia_tensor";
    pub const INERTIA_CM: &str = "inertia_cm";
    pub const PRINCIPAL_MOMENTS: &str = "principal_moments";
    pub const ANGULAR_MOMENTUM: &str = "angular_momentum";
    pub const ANGULAR_MOMENTUM_DIRECT: &str = "angular_momentum_direct";
    pub const KINETIC_ENERGY: &str = "kinetic_energy";
    pub const KINETIC_ENERGY_DIRECT: &str = "kinetic_energy_direct";
    pub const MOMENT_ABOUT_AXIS: &str = "moment_about_axis";
    pub const MOMENT_ABOUT_AXIS_DIRECT: &str = "moment_about_axis_direct";
    pub const RADIUS_OF_GYRATION: &str = "radius_of_gyration";
    pub const INTEGRAND: &str = "integrand";
    pub const POSITION: &str = "position";
    pub const PRINCIPAL_MOMENTUM: &str = "principal_momentum";
    pub const GYROSCOPIC_TERM: &str = "gyroscopic_term";
    pub const EULER_EQUATIONS: &str = "euler_equations";
    pub const BODY_RATE_OF_MOMENTUM: &str = "body_rate_of_momentum";
    pub const TORQUE_FREE_RATES: &str = "torque_free_rates";
    pub const W1_SECOND_DERIVATIVE: &str = "w1_second_derivative";
    pub const SYMMETRIC_SOLUTION: &str = "symmetric_solution";
    pub const SYMMETRIC_RESIDUAL: &str = "symmetric_residual";
    pub const OMEGA_SQUARED: &str = "omega_squared";
    pub const PRECESSION_RATE: &str = "precession_rate";
    pub const TOP_TWICE_ENERGY: &str = "top_twice_energy";
    pub const TOP_MOMENTUM_SQUARED: &str = "top_momentum_squared";
    pub const TWICE_ENERGY: &str = "twice_energy";
    pub const MOMENTUM_SQUARED: &str = "momentum_squared";
    pub const BODY_CONE_TAN_SQUARED: &str = "body_cone_tan_squared";
    pub const SPACE_CONE_COS_SQUARED: &str = "space_cone_cos_squared";
    pub const MOMENTUM_TILT_TAN_SQUARED: &str = "momentum_tilt_tan_squared";
    pub const CONE_ORDER: &str = "cone_order";
    pub const OSCILLATION_FREQUENCY_SQUARED: &str = "oscillation_frequency_squared";
    pub const AMPLITUDE_RATIO_SQUARED: &str = "amplitude_ratio_squared";
    pub const STABILITY: &str = "stability";
    pub const GROWTH_RATE_SQUARED: &str = "growth_rate_squared";
    pub const ELLIPSOID_VALUE: &str = "ellipsoid_value";
    pub const GRADIENT_FACTOR_SQUARED: &str = "gradient_factor_squared";
    pub const PLANE_DISTANCE_SQUARED: &str = "plane_distance_squared";
    pub const ENERGY_FROM_MOMENTUM: &str = "energy_from_momentum";
    pub const MOMENTUM_GAP: &str = "momentum_gap";
    pub const POLHODE_CONIC_PRODUCT: &str = "polhode_conic_product";
    pub const POLHODE_CLOSURE: &str = "polhode_closure";
    pub const SEPARATRIX_SLOPE_SQUARED: &str = "separatrix_slope_squared";
    pub const EARTH_BETA: &str = "earth_beta";
    pub const EULER_PERIOD_SIDEREAL_DAYS: &str = "euler_period_sidereal_days";
    pub const EULER_PERIOD_SOLAR_DAYS: &str = "euler_period_solar_days";
    pub const CHANDLER_RATIO: &str = "chandler_ratio";
    pub const BULGE_KM: &str = "bulge_km";
    pub const BULGE_FRACTION: &str = "bulge_fraction";
}

/// The quantities a problem may ask for, each with the output that derives it. Each has a
/// numeric route independent of the derivation, on which every variant's answer is checked.
pub const ANSWERS: &[(&str, Output)] = &[
    (quantity::INERTIA_TENSOR, Output::InertiaTensor),
    (quantity::PRINCIPAL_MOMENTS, Output::PrincipalAxes),
    (quantity::ANGULAR_MOMENTUM, Output::AngularMomentum),
    (quantity::KINETIC_ENERGY, Output::KineticEnergy),
    (quantity::MOMENT_ABOUT_AXIS, Output::MomentAboutAxis),
    (quantity::RADIUS_OF_GYRATION, Output::Gyration),
    (quantity::PRECESSION_RATE, Output::SymmetricTop),
];

/// The derived quantities an expression answer may use: the mass and the centre of mass, and
/// every quantity of [`ANSWERS`]. `numeric::answers::Routes` has a route for each.
pub fn routed_quantities() -> impl Iterator<Item = &'static str> {
    [quantity::MASS, quantity::CENTRE_OF_MASS]
        .into_iter()
        .chain(ANSWERS.iter().map(|(q, _)| *q))
}

/// The symbol a page prints for a derived quantity a claim names, where one is standard and
/// clashes with no scene symbol: a claim's `inertia_tensor[0][1]` reads I_{xy}. Other names
/// print as upright words.
pub fn quantity_symbol(name: &str) -> Option<&'static str> {
    match name {
        // A scene's unit `axis`, which claims name beside the quantities.
        "axis" => Some("\\hat{n}"),
        _ => find(name).and_then(|q| q.symbol),
    }
}

/// A derived quantity's heading on a page: its name in words, a Greek letter's name as the
/// letter (`omega_squared` is "ω squared").
pub fn heading(name: &str) -> String {
    let words = match name {
        quantity::OMEGA_SQUARED => "ω squared".to_string(),
        quantity::EARTH_BETA => "β of the Earth".to_string(),
        quantity::W1_SECOND_DERIVATIVE => "Second derivative of ω₁".to_string(),
        _ => name.replace('_', " "),
    };
    // A heading opens with a capital; a Greek letter is a symbol and keeps its case (ω is not Ω).
    let mut c = words.chars();
    match c.next() {
        Some(f) if f.is_ascii_lowercase() => f.to_ascii_uppercase().to_string() + c.as_str(),
        _ => words,
    }
}

/// What `[expect]` records of a scene: every derived result, but the intermediate integrands
/// and positions. A scene without `[expect]` has these not yet recorded, which `check` fails on
/// until `check --bless` writes them in.
pub fn recorded_by_default(name: &str) -> bool {
    name != quantity::INTEGRAND && name != quantity::POSITION
}

/// The names `[expect]` records by default, in the catalogue's order.
pub fn recorded_names() -> impl Iterator<Item = &'static str> {
    CATALOGUE
        .iter()
        .map(|q| q.name)
        .filter(|name| recorded_by_default(name))
}

/// What a derived quantity's value is: one expression, three, or three by three.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Scalar,
    Vector,
    Matrix,
}

/// A derived quantity: its name (as claims, `[expect]` and reports write it), its kind, the one
/// stage that derives it, and the symbol a page prints for it where one is standard.
#[derive(Debug)]
pub struct Quantity {
    pub name: &'static str,
    pub kind: Kind,
    pub stage: Stage,
    pub symbol: Option<&'static str>,
}

const fn q(name: &'static str, kind: Kind, stage: Stage) -> Quantity {
    Quantity {
        name,
        kind,
        stage,
        symbol: None,
    }
}

const fn with_symbol(
    name: &'static str,
    kind: Kind,
    stage: Stage,
    symbol: &'static str,
) -> Quantity {
    Quantity {
        name,
        kind,
        stage,
        symbol: Some(symbol),
    }
}

/// Every derived quantity, once: the lists of names, the stage a claim pulls in, the symbols
/// and the check on what a stage writes all read it here. Bodies' quantities first, then the
/// free-body derivations'.
pub const CATALOGUE: &[Quantity] = {
    use Kind::*;
    use quantity::*;
    &[
        with_symbol(MASS, Scalar, Stage::Tensor, "M"),
        with_symbol(
            CENTRE_OF_MASS,
            Vector,
            Stage::CentreOfMass,
            "R^{\\mathrm{cm}}",
        ),
        with_symbol(INERTIA_TENSOR, Matrix, Stage::Tensor, "I"),
        with_symbol(INERTIA_CM, Matrix, Stage::ParallelAxis, "I^{\\mathrm{cm}}"),
        q(PRINCIPAL_MOMENTS, Vector, Stage::Principal),
        with_symbol(ANGULAR_MOMENTUM, Vector, Stage::AngularMomentum, "L"),
        with_symbol(ANGULAR_MOMENTUM_DIRECT, Vector, Stage::AngularMomentum, "L"),
        with_symbol(KINETIC_ENERGY, Scalar, Stage::KineticEnergy, "T"),
        with_symbol(KINETIC_ENERGY_DIRECT, Scalar, Stage::KineticEnergy, "T"),
        with_symbol(MOMENT_ABOUT_AXIS, Scalar, Stage::MomentAboutAxis, "I_{n}"),
        with_symbol(
            MOMENT_ABOUT_AXIS_DIRECT,
            Scalar,
            Stage::MomentAboutAxis,
            "I_{n}",
        ),
        with_symbol(RADIUS_OF_GYRATION, Scalar, Stage::Gyration, "R_{0}"),
        // The integrand of I_xx is the I_xx per unit of the integration variable.
        with_symbol(INTEGRAND, Matrix, Stage::Tensor, "dI"),
        with_symbol(POSITION, Vector, Stage::Tensor, "\\vec{r}"),
        q(PRINCIPAL_MOMENTUM, Vector, Stage::EulerEquations),
        q(GYROSCOPIC_TERM, Vector, Stage::EulerEquations),
        q(EULER_EQUATIONS, Vector, Stage::EulerEquations),
        q(BODY_RATE_OF_MOMENTUM, Vector, Stage::EulerEquations),
        q(TORQUE_FREE_RATES, Vector, Stage::EulerEquations),
        q(W1_SECOND_DERIVATIVE, Scalar, Stage::SymmetricTop),
        q(SYMMETRIC_SOLUTION, Vector, Stage::SymmetricTop),
        q(SYMMETRIC_RESIDUAL, Vector, Stage::SymmetricTop),
        with_symbol(OMEGA_SQUARED, Scalar, Stage::SymmetricTop, "\\omega^{2}"),
        q(PRECESSION_RATE, Scalar, Stage::SymmetricTop),
        with_symbol(TOP_TWICE_ENERGY, Scalar, Stage::SymmetricTop, "2T"),
        with_symbol(TOP_MOMENTUM_SQUARED, Scalar, Stage::SymmetricTop, "L^{2}"),
        q(BODY_CONE_TAN_SQUARED, Scalar, Stage::SymmetricTop),
        q(SPACE_CONE_COS_SQUARED, Scalar, Stage::SymmetricTop),
        q(MOMENTUM_TILT_TAN_SQUARED, Scalar, Stage::SymmetricTop),
        q(CONE_ORDER, Scalar, Stage::SymmetricTop),
        q(OSCILLATION_FREQUENCY_SQUARED, Vector, Stage::AxisStability),
        q(AMPLITUDE_RATIO_SQUARED, Vector, Stage::AxisStability),
        q(STABILITY, Matrix, Stage::AxisStability),
        with_symbol(
            GROWTH_RATE_SQUARED,
            Scalar,
            Stage::AxisStability,
            "\\sigma^{2}",
        ),
        with_symbol(TWICE_ENERGY, Scalar, Stage::Poinsot, "2T"),
        with_symbol(MOMENTUM_SQUARED, Scalar, Stage::Poinsot, "L^{2}"),
        q(ELLIPSOID_VALUE, Scalar, Stage::Poinsot),
        q(GRADIENT_FACTOR_SQUARED, Scalar, Stage::Poinsot),
        q(PLANE_DISTANCE_SQUARED, Scalar, Stage::Poinsot),
        with_symbol(ENERGY_FROM_MOMENTUM, Scalar, Stage::Poinsot, "T"),
        q(MOMENTUM_GAP, Vector, Stage::Poinsot),
        q(POLHODE_CONIC_PRODUCT, Vector, Stage::Poinsot),
        q(POLHODE_CLOSURE, Matrix, Stage::Poinsot),
        q(SEPARATRIX_SLOPE_SQUARED, Scalar, Stage::Poinsot),
        with_symbol(EARTH_BETA, Scalar, Stage::EarthPrecession, "\\beta"),
        q(EULER_PERIOD_SIDEREAL_DAYS, Scalar, Stage::EarthPrecession),
        q(EULER_PERIOD_SOLAR_DAYS, Scalar, Stage::EarthPrecession),
        q(CHANDLER_RATIO, Scalar, Stage::EarthPrecession),
        q(BULGE_KM, Scalar, Stage::EarthPrecession),
        q(BULGE_FRACTION, Scalar, Stage::EarthPrecession),
    ]
};

/// The catalogue's entry for a name.
pub fn find(name: &str) -> Option<&'static Quantity> {
    CATALOGUE.iter().find(|q| q.name == name)
}

impl Stage {
    /// Whether the stage derives from the scene's bodies (the others are free-body
    /// derivations, which need none).
    pub fn needs_body(self) -> bool {
        !matches!(
            self,
            Stage::EulerEquations
                | Stage::SymmetricTop
                | Stage::AxisStability
                | Stage::Poinsot
                | Stage::EarthPrecession
        )
    }
}

/// The names of the quantities derived from bodies, in the catalogue's order.
pub fn body_quantities() -> impl Iterator<Item = &'static str> {
    CATALOGUE
        .iter()
        .filter(|q| q.stage.needs_body())
        .map(|q| q.name)
}

/// The names of the free-body derivations' quantities (Lecture 3/9), which need no body.
pub fn free_body_quantities() -> impl Iterator<Item = &'static str> {
    CATALOGUE
        .iter()
        .filter(|q| !q.stage.needs_body())
        .map(|q| q.name)
}

/// A name of a derived quantity, from a body or from a free-body derivation.
pub fn is_quantity(name: &str) -> bool {
    find(name).is_some()
}

/// The symbols each free-body derivation writes its results in; a scene that asks for one
/// declares them.
pub const EULER_SYMBOLS: &[&str] = &[
    "I1", "I2", "I3", "w1", "w2", "w3", "wd1", "wd2", "wd3", "N1", "N2", "N3",
];
pub const SYMMETRIC_TOP_SYMBOLS: &[&str] = &["I1", "I3", "w1", "w2", "w3", "A", "t", "theta"];
pub const STABILITY_SYMBOLS: &[&str] = &["I1", "I2", "I3", "w1", "w2", "w3"];
pub const POINSOT_SYMBOLS: &[&str] = &["I1", "I2", "I3", "w1", "w2", "w3", "L1", "L2", "L3"];
pub const EARTH_SYMBOLS: &[&str] = &["A", "C", "H"];

/// The keys of every step a scene may cite, for validating `[cite]`; derive's steps carry them.
pub const CITABLE_STEPS: &[&str] = &[
    "angular-momentum",
    "angular-momentum-direct",
    "characteristic-polynomial",
    "earth-beta",
    "ellipsoid-gradient",
    "ellipsoid-point",
    "energy-ellipsoid",
    "euler-equations",
    "gyration",
    "inertia-ellipsoid",
    "invariable-plane",
    "kinetic-energy",
    "kinetic-energy-direct",
    "moment-about-axis",
    "moment-about-axis-direct",
    "momentum-squared",
    "parallel-axis",
    "point-tensor",
    "principal-axis",
    "principal-frame-momentum",
    "space-cone",
    "stability-rates",
    "symmetric-beta-rates",
    "symmetric-omega-constant",
    "symmetric-oscillator",
    "symmetric-rates",
    "torque-free-rates",
    "twice-energy",
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_quantity_name_is_in_the_catalogue_once() {
        // The names of `mod quantity`, read from this file's source: a name added there
        // without a catalogue entry (its kind and stage) fails here.
        let source = include_str!("catalogue.rs");
        let block = &source[source.find("pub mod quantity {").unwrap()..];
        let block = &block[..block.find("\n}").unwrap()];
        let names: Vec<&str> = block
            .lines()
            .filter_map(|l| l.trim().strip_prefix("pub const "))
            .map(|l| l.split('"').nth(1).unwrap())
            .collect();
        assert_eq!(names.len(), CATALOGUE.len());
        for name in &names {
            assert_eq!(
                CATALOGUE.iter().filter(|q| q.name == *name).count(),
                1,
                "{name}"
            );
        }
        // Each free-body quantity pulls in a stage that needs no body, and back.
        assert!(free_body_quantities().all(|n| !stage_for_quantity(n).unwrap().needs_body()));
        assert_eq!(
            body_quantities().count() + free_body_quantities().count(),
            names.len()
        );
        assert_eq!(
            stage_for_quantity(quantity::TWICE_ENERGY),
            Some(Stage::Poinsot)
        );
        assert_eq!(
            stage_for_quantity(quantity::TOP_TWICE_ENERGY),
            Some(Stage::SymmetricTop)
        );
    }
}
