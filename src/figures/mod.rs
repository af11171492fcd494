//! Figures: the data of every plot a scene asks for (`[[plot]]`), one file per plot kind.
//! Numeric code computes the numbers; each figure here draws them and writes its title and
//! description from them, so the alt text says what the picture shows.

mod accuracy;
mod axis_spins;
mod cones;
pub mod convergence;
mod drift;
mod expression;
mod flip;
mod frame;
mod herpolhode;
pub mod integrator_pareto;
mod motion;
mod omega_vs_time;
pub mod polar_motion;
mod polhodes;
mod principal_axes;
mod projection;
mod tensor_sweep;

use crate::cas::EvalError;
use crate::derive::{Derivation, DeriveError};
use crate::model::fidelity::Fidelity;
use crate::model::figure::Figure;
use crate::model::moments::{Moments, MomentsError};
use crate::model::prose::Piece;
use crate::numeric::body::NumBody;
use crate::numeric::integrators::IntegrationError;
use crate::scene::{FreeBodyPlot, FreeInertia, PlotRequest, Scene};
use nalgebra::Vector3;

/// Why a figure could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    #[error(transparent)]
    Eval(#[from] EvalError),
    #[error(transparent)]
    Moments(#[from] MomentsError),
    #[error(transparent)]
    Integration(#[from] IntegrationError),
    #[error(transparent)]
    Derive(#[from] Box<DeriveError>),
    #[error("a convergence plot needs a continuous body, not point masses")]
    PointMasses,
    #[error("axis-spins needs one component of omega larger than the other two")]
    NoLargestComponent,
    #[error("the flip needs three different moments")]
    FlipNeedsThreeMoments,
    #[error("polhodes need unequal moments (a sphere has none)")]
    SphereHasNoPolhodes,
    #[error("the cones need a symmetric body: exactly two equal moments")]
    NotSymmetric,
    #[error("polar motion needs a wobble (ω1 or ω2 non-zero)")]
    NoWobble,
    #[error("a motion plot draws equations, and step `{step}` gives none")]
    NoEquations { step: String },
    #[error("step `{step}` gives no single expression to draw")]
    NotAnExpression { step: String },
    #[error(
        "`{name}` in step `{step}` has no value: give it one in the plot's `at = {{ {name} = … }}` \
         or under [numeric] values"
    )]
    NoValueAt { step: String, name: String },
    #[error("the motion could not be integrated: {0}")]
    Motion(#[from] crate::numeric::ode::OdeError),
    #[error(
        "plot `{slug}`: its data is not all finite numbers: the body or ω(0) is beyond double \
         precision; check the plot's inertia, omega and t"
    )]
    NotFinite { slug: String },
    #[error(
        "plot `{slug}`: nothing to draw: every value is zero or not a number on its axes (the \
         scene's values underflow double precision?); give the quantities in units nearer 1"
    )]
    Empty { slug: String },
    #[error("no integrator settings")]
    NoSettings,
    #[error("the principal-axes plot needs the exact eigenspaces")]
    NoEigenspaces,
}

/// Colour roles: indices into the renderer's palette (`render::plot`), so that a law and its
/// measurement, or one axis across several curves, share a colour.
mod colour {
    /// Blue: the main measured curve, or the first of a family.
    pub const PRIMARY: usize = 0;
    /// Vermilion: what stands against the main curve (a separatrix, a second body axis).
    pub const CONTRAST: usize = 1;
    /// Green: a third curve, or motion about the other end axis.
    pub const SECONDARY: usize = 2;
    /// Ochre: markers placed over the curves.
    pub const ACCENT: usize = 4;
    /// Grey: a reference drawn under the data (an ellipsoid, a law, the Pareto front).
    pub const REFERENCE: usize = 5;
}

/// A series' legend entry: only the first series of a family is named, so that the legend
/// lists the family once.
fn legend_entry(first: bool, name: &str) -> String {
    if first { name.into() } else { String::new() }
}

/// Curve resolution of exact functions.
const CURVE_POINTS: usize = 181;

/// Errors below this are drawn at it: a log axis cannot show an exact zero.
pub const ERROR_FLOOR: f64 = 1e-17;

pub fn figures(
    scene: &Scene,
    d: &Derivation,
    fidelity: &Fidelity,
) -> Result<Vec<Figure>, PlotFailure> {
    let mut out = Vec::new();
    for (index, p) in scene.plots.iter().enumerate() {
        let first = out.len();
        plot(scene, d, fidelity, p, &mut out).map_err(|source| PlotFailure { index, source })?;
        // A plot of NaN or infinity is a failure of the inputs' precision, said here, at the
        // plot, rather than a broken picture or a renderer's error.
        // A caption's negative numbers as a textbook sets them (−0.67, not -0.67).
        for f in &mut out[first..] {
            for piece in &mut f.desc.0 {
                if let Piece::Text(t) = piece {
                    *t = crate::base::format::minus_signs(t);
                }
            }
        }
        for f in &out[first..] {
            let finite = |(x, y): &(f64, f64)| x.is_finite() && y.is_finite();
            if !f.series.iter().all(|s| s.points.iter().all(finite))
                || !f.labels.iter().all(|(_, p)| finite(p))
            {
                let source = FigureError::NotFinite {
                    slug: f.slug.clone(),
                };
                return Err(PlotFailure { index, source });
            }
            if f.bounds().is_none() {
                let source = FigureError::Empty {
                    slug: f.slug.clone(),
                };
                return Err(PlotFailure { index, source });
            }
        }
    }
    Ok(out)
}

/// A plot that could not be drawn: `plot[index]` of the scene.
#[derive(Debug, thiserror::Error)]
#[error("{source}")]
pub struct PlotFailure {
    pub index: usize,
    pub source: FigureError,
}

/// The figures of one plot request, appended to `out`.
fn plot(
    scene: &Scene,
    d: &Derivation,
    fidelity: &Fidelity,
    p: &PlotRequest,
    out: &mut Vec<Figure>,
) -> Result<(), FigureError> {
    {
        match p {
            PlotRequest::TensorSweep {
                over,
                from,
                to,
                samples,
            } => out.push(tensor_sweep::tensor_sweep(
                scene, d, over, *from, *to, *samples,
            )?),
            PlotRequest::Convergence => out.extend(convergences(scene, d, fidelity)?),
            PlotRequest::PrincipalAxes => out.push(principal_axes::principal_view(scene, d)?),
            PlotRequest::FreeBody {
                kind,
                inertia,
                omega,
                t,
            } => {
                let inertia = match inertia {
                    FreeInertia::Given(i) => *i,
                    FreeInertia::Principal => own_principal_moments(scene, d)?,
                };
                out.push(free_body_figure(*kind, inertia, *omega, *t, fidelity)?)
            }
            PlotRequest::Motion {
                step,
                linear,
                start,
                t,
            } => out.push(motion::motion(
                scene,
                d,
                step,
                linear.as_deref(),
                start,
                *t,
            )?),
            PlotRequest::Expression {
                step,
                over,
                from,
                to,
                samples,
                at,
            } => out.push(expression::expression(
                scene,
                d,
                step,
                over,
                (*from, *to),
                *samples,
                at,
            )?),
        }
        distinct_slug(out);
    }
    Ok(())
}

/// The quadrature's convergence for each body: `convergence`, or `convergence-k` of several.
fn convergences(
    scene: &Scene,
    d: &Derivation,
    fidelity: &Fidelity,
) -> Result<Vec<Figure>, FigureError> {
    let mut out = Vec::new();
    for (i, body) in scene.bodies.iter().enumerate() {
        let nb = NumBody::from_scene(body, &scene.values)?;
        let exact = d.part_tensors[i].matrix_at(&scene.values)?;
        let slug = if scene.bodies.len() == 1 {
            "convergence".to_string()
        } else {
            format!("convergence-{}", i + 1)
        };
        out.push(convergence::convergence(
            &nb, &exact, scene.seed, slug, fidelity,
        )?);
    }
    Ok(out)
}

/// Two plots of one kind in a scene get distinct file names: the last one's slug takes the
/// first free `-n`.
fn distinct_slug(out: &mut [Figure]) {
    let last = out.len() - 1;
    let taken = |slug: &str| out[..last].iter().any(|f| f.slug == slug);
    if taken(&out[last].slug) {
        let base = out[last].slug.clone();
        let n = (2..).find(|n| !taken(&format!("{base}-{n}"))).unwrap();
        out[last].slug = format!("{base}-{n}");
    }
}

/// A free-body figure: each kind is drawn by its own file.
fn free_body_figure(
    kind: FreeBodyPlot,
    inertia: [f64; 3],
    omega: [f64; 3],
    t: f64,
    fidelity: &Fidelity,
) -> Result<Figure, FigureError> {
    let i = Moments::new(inertia)?;
    let w0 = Vector3::from(omega);
    let f = fidelity;
    match kind {
        FreeBodyPlot::OmegaVsTime => omega_vs_time::omega_vs_time(&i, w0, t, f),
        FreeBodyPlot::Polhodes => polhodes::polhodes(&i, w0, f),
        FreeBodyPlot::Drift => drift::drift(&i, w0, t, f),
        FreeBodyPlot::Flip => flip::flip(&i, w0, t, f),
        FreeBodyPlot::AxisSpins => axis_spins::axis_spins(&i, w0, t, f),
        FreeBodyPlot::Herpolhode => herpolhode::herpolhode(&i, w0, t, f),
        FreeBodyPlot::PolarMotion => polar_motion::polar_motion(&i, w0, f),
        FreeBodyPlot::Cones => cones::cones(&i, w0, t, f),
        FreeBodyPlot::IntegratorPareto => integrator_pareto::integrator_pareto(&i, w0, t, f),
    }
}

/// The principal moments of the scene's bodies about their centre of mass, at the scene's
/// values, ascending: I_cm = I − M(R²𝟙 − R Rᵀ) from the exact tensor, mass and centre.
fn own_principal_moments(scene: &Scene, d: &Derivation) -> Result<[f64; 3], FigureError> {
    use crate::model::catalogue::quantity;
    let derived = |e| FigureError::Derive(Box::new(e));
    let tensor = d
        .get(quantity::INERTIA_TENSOR)
        .map_err(derived)?
        .matrix_at(&scene.values)?;
    let about_centre = d.about_centre_at(&tensor, &scene.values).map_err(derived)?;
    let moments = crate::numeric::eigen::sorted_eigenvalues(&about_centre);
    // To 15 significant figures, the eigen-solver's own accuracy: the captions then print
    // 0.00195, not 0.0019499999999999995.
    let round = |x: f64| format!("{x:.14e}").parse::<f64>().unwrap_or(x);
    let moments = [round(moments[0]), round(moments[1]), round(moments[2])];
    crate::model::moments::Moments::new(moments)?;
    Ok(moments)
}

/// A symbol's or a step's name as a reader writes it, for a caption, an axis or a legend (plain
/// text, where no formula goes): `theta` is θ, `phi'` ϕ̇.
fn plain_name(name: &str) -> String {
    plain_formula(&crate::cas::Expr::sym(name))
}

/// An exact result as a reader writes it in plain text: `11/12*m*a^2` is 11ma²/12, from the
/// tree the pages set.
fn plain_formula(e: &crate::cas::Expr) -> String {
    e.to_tex(crate::notation::Names::none()).to_plain()
}

/// An exact vector in plain text: (−1, 1, 0).
fn plain_vector(v: &[crate::cas::Expr]) -> String {
    let parts: Vec<String> = v.iter().map(plain_formula).collect();
    format!("({})", parts.join(", "))
}

fn trim_num(x: f64) -> String {
    if (x - std::f64::consts::PI).abs() < 1e-12 {
        "π".into()
    } else {
        format!("{x:.4}")
            .trim_end_matches('0')
            .trim_end_matches('.')
            .into()
    }
}

#[cfg(test)]
mod expression_tests;
#[cfg(test)]
mod free_body_tests;
#[cfg(test)]
mod motion_tests;
#[cfg(test)]
mod tests;
