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
    pub fn requires(self) -> &'static [Stage] {
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
pub fn stage_for_quantity(name: &str) -> Option<Stage> {
    use quantity::*;
    Some(match name {
        MASS | INERTIA_TENSOR | INTEGRAND | POSITION => Stage::Tensor,
        CENTRE_OF_MASS => Stage::CentreOfMass,
        INERTIA_CM => Stage::ParallelAxis,
        PRINCIPAL_MOMENTS => Stage::Principal,
        ANGULAR_MOMENTUM | ANGULAR_MOMENTUM_DIRECT => Stage::AngularMomentum,
        KINETIC_ENERGY | KINETIC_ENERGY_DIRECT => Stage::KineticEnergy,
        MOMENT_ABOUT_AXIS | MOMENT_ABOUT_AXIS_DIRECT => Stage::MomentAboutAxis,
        RADIUS_OF_GYRATION => Stage::Gyration,
        PRINCIPAL_MOMENTUM
        | GYROSCOPIC_TERM
        | EULER_EQUATIONS
        | BODY_RATE_OF_MOMENTUM
        | TORQUE_FREE_RATES => Stage::EulerEquations,
        W1_SECOND_DERIVATIVE
        | SYMMETRIC_SOLUTION
        | SYMMETRIC_RESIDUAL
        | OMEGA_SQUARED
        | PRECESSION_RATE
        | BODY_CONE_TAN_SQUARED
        | SPACE_CONE_COS_SQUARED
        | MOMENTUM_TILT_TAN_SQUARED
        | CONE_ORDER => Stage::SymmetricTop,
        OSCILLATION_FREQUENCY_SQUARED
        | AMPLITUDE_RATIO_SQUARED
        | STABILITY
        | GROWTH_RATE_SQUARED => Stage::AxisStability,
        ELLIPSOID_VALUE
        | GRADIENT_FACTOR_SQUARED
        | PLANE_DISTANCE_SQUARED
        | ENERGY_FROM_MOMENTUM
        | MOMENTUM_GAP
        | POLHODE_CONIC_PRODUCT
        | POLHODE_CLOSURE
        | SEPARATRIX_SLOPE_SQUARED => Stage::Poinsot,
        EARTH_BETA
        | EULER_PERIOD_SIDEREAL_DAYS
        | EULER_PERIOD_SOLAR_DAYS
        | CHANDLER_RATIO
        | BULGE_KM
        | BULGE_FRACTION => Stage::EarthPrecession,
        _ => return None,
    })
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

/// The symbol a page prints for a derived quantity a claim names, where one is standard and
/// clashes with no scene symbol: a claim's `inertia_tensor[0][1]` reads I_{xy}. Other names
/// print as upright words.
pub fn quantity_symbol(name: &str) -> Option<&'static str> {
    Some(match name {
        quantity::INERTIA_TENSOR => "I",
        quantity::INERTIA_CM => "I^{\\mathrm{cm}}",
        quantity::ANGULAR_MOMENTUM | quantity::ANGULAR_MOMENTUM_DIRECT => "L",
        quantity::KINETIC_ENERGY | quantity::KINETIC_ENERGY_DIRECT => "T",
        quantity::MOMENT_ABOUT_AXIS | quantity::MOMENT_ABOUT_AXIS_DIRECT => "I_{n}",
        quantity::CENTRE_OF_MASS => "R^{\\mathrm{cm}}",
        quantity::POSITION => "\\vec{r}",
        // The integrand of I_xx is the I_xx per unit of the integration variable.
        quantity::INTEGRAND => "dI",
        _ => return None,
    })
}

/// Names a claim may use for derived quantities, and the functions of the claim language.
/// What `[expect]` records of a scene: every derived result, but the intermediate integrands
/// and positions. A scene without `[expect]` has these not yet recorded, which `check` fails on
/// until `check --bless` writes them in.
pub fn recorded_by_default(name: &str) -> bool {
    name != quantity::INTEGRAND && name != quantity::POSITION
}

pub const QUANTITIES: &[&str] = &[
    quantity::MASS,
    quantity::CENTRE_OF_MASS,
    quantity::INERTIA_TENSOR,
    quantity::INERTIA_CM,
    quantity::PRINCIPAL_MOMENTS,
    quantity::ANGULAR_MOMENTUM,
    quantity::ANGULAR_MOMENTUM_DIRECT,
    quantity::KINETIC_ENERGY,
    quantity::KINETIC_ENERGY_DIRECT,
    quantity::MOMENT_ABOUT_AXIS,
    quantity::MOMENT_ABOUT_AXIS_DIRECT,
    quantity::RADIUS_OF_GYRATION,
    quantity::INTEGRAND,
    quantity::POSITION,
];
/// Quantities of the free-body derivations (Lecture 3/9), which need no body.
pub const DYNAMICS_QUANTITIES: &[&str] = &[
    quantity::PRINCIPAL_MOMENTUM,
    quantity::GYROSCOPIC_TERM,
    quantity::EULER_EQUATIONS,
    quantity::BODY_RATE_OF_MOMENTUM,
    quantity::TORQUE_FREE_RATES,
    quantity::W1_SECOND_DERIVATIVE,
    quantity::SYMMETRIC_SOLUTION,
    quantity::SYMMETRIC_RESIDUAL,
    quantity::OMEGA_SQUARED,
    quantity::PRECESSION_RATE,
    quantity::TWICE_ENERGY,
    quantity::MOMENTUM_SQUARED,
    quantity::BODY_CONE_TAN_SQUARED,
    quantity::SPACE_CONE_COS_SQUARED,
    quantity::MOMENTUM_TILT_TAN_SQUARED,
    quantity::CONE_ORDER,
    quantity::OSCILLATION_FREQUENCY_SQUARED,
    quantity::AMPLITUDE_RATIO_SQUARED,
    quantity::STABILITY,
    quantity::GROWTH_RATE_SQUARED,
    quantity::ELLIPSOID_VALUE,
    quantity::GRADIENT_FACTOR_SQUARED,
    quantity::PLANE_DISTANCE_SQUARED,
    quantity::ENERGY_FROM_MOMENTUM,
    quantity::MOMENTUM_GAP,
    quantity::POLHODE_CONIC_PRODUCT,
    quantity::POLHODE_CLOSURE,
    quantity::SEPARATRIX_SLOPE_SQUARED,
    quantity::EARTH_BETA,
    quantity::EULER_PERIOD_SIDEREAL_DAYS,
    quantity::EULER_PERIOD_SOLAR_DAYS,
    quantity::CHANDLER_RATIO,
    quantity::BULGE_KM,
    quantity::BULGE_FRACTION,
];

/// A name of a derived quantity, from a body or from a free-body derivation.
pub fn is_quantity(name: &str) -> bool {
    QUANTITIES.contains(&name) || DYNAMICS_QUANTITIES.contains(&name)
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
