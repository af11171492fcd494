//! The inertia tensor by exact integration, I_jk = ∫ρ(r²δ_jk − x_j x_k)dV (eqs 9–10, 26), and
//! the parallel-axis theorem proved both ways (eqs 20–22).

use super::algebra::{
    Mat3, Value, Vec3, inertia_kernel, mat_add, mat_scale, scale_vec, sub_vec, sum_mats, sum_vecs,
    zero3,
};
use super::bodies::{Continuum, MassModel, mass_model, place};
use super::{
    Derivation, DeriveError, Step, cited, simplify_mat, simplify_value, simplify_vec, values_equal,
};
use crate::cas::{self, AngleSpan, Expr, Integral};
use crate::model::catalogue::quantity;
use crate::model::prose::Prose;
use crate::notation::Formula;
use crate::scene::{Body, Scene};

/// The six independent entries of a symmetric tensor, and their labels.
const UNIQUE: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];
const AXES: [&str; 3] = ["x", "y", "z"];

fn symmetric(entries: &[Expr]) -> Mat3 {
    let mut m: Mat3 = std::array::from_fn(|_| zero3());
    for (k, (i, j)) in UNIQUE.iter().enumerate() {
        m[*i][*j] = entries[k].clone();
        m[*j][*i] = entries[k].clone();
    }
    m
}

/// The ranges of integration: "x from −a/2 to a/2, θ over [0, 2π]", the ends as formulas.
fn describe(mut prose: Prose, domain: &[Integral]) -> Prose {
    for (k, i) in domain.iter().enumerate() {
        if k > 0 {
            prose = prose.text(", ");
        }
        prose = match i {
            Integral::Poly { var, lo, hi } => prose
                .expr(&Expr::sym(var))
                .text(" from ")
                .expr(lo)
                .text(" to ")
                .expr(hi),
            Integral::Trig { var, span } => {
                prose.expr(&Expr::sym(var)).text(" over ").math(match span {
                    AngleSpan::Full => "[0, 2pi]",
                    AngleSpan::Half => "[0, pi]",
                    AngleSpan::Quarter => "[0, pi/2]",
                })
            }
        };
    }
    prose
}

fn span_notation(span: AngleSpan) -> &'static str {
    match span {
        AngleSpan::Full => "2pi",
        AngleSpan::Half => "pi",
        AngleSpan::Quarter => "pi/2",
    }
}

/// `I_xy = ∫_{lo}^{hi} … f dx dy = result`: the limits outermost first, the differentials
/// innermost first. `lhs` is a tree, never notation text: an author's step name (`Ix`,
/// `I1cone`) is a symbol, printed by the symbol printers on the page and in the PDF alike.
pub(crate) fn integral_formula(
    lhs: Formula,
    integrand: &Expr,
    domain: &[Integral],
    result: &Expr,
) -> Formula {
    let mut exprs = vec![integrand.clone(), result.clone()];
    let mut put = |e: &Expr| {
        exprs.push(e.clone());
        format!("${}", exprs.len() - 1)
    };
    let mut notation = String::new();
    for i in domain.iter().rev() {
        let (lo, hi) = match i {
            Integral::Poly { lo, hi, .. } => (put(lo), put(hi)),
            Integral::Trig { span, .. } => ("0".into(), span_notation(*span).into()),
        };
        notation.push_str(&format!("int_({lo})^({hi}) "));
    }
    notation.push_str("$0");
    for i in domain {
        let var = match i {
            Integral::Poly { var, .. } | Integral::Trig { var, .. } => var,
        };
        notation.push_str(&format!(" ~ d {}", put(&Expr::sym(var))));
    }
    notation.push_str(" = $1");
    Formula::Row(vec![
        lhs,
        Formula::Op(crate::notation::Op::Equals),
        Formula::parse(&notation, &exprs),
    ])
}

fn why_integrate(domain: &[Integral]) -> Prose {
    let trig = domain.iter().any(|i| matches!(i, Integral::Trig { .. }));
    let poly = domain.iter().any(|i| matches!(i, Integral::Poly { .. }));
    let mut why = String::from("expand, then ");
    if trig {
        why.push_str(
            "integrate each monomial $\\cos^p \\sin^q$ over its period by the beta-function formula",
        );
    }
    if trig && poly {
        why.push_str(", and ");
    }
    if poly {
        why.push_str("integrate the polynomial term by term");
    }
    describe(Prose::default().words(&format!("{why} (")), domain).text(")")
}

/// What one body contributes: its mass, tensor about the frame origin and first moment ∫x dm.
struct Part {
    mass: Expr,
    tensor: Mat3,
    first_moment: Option<Vec3>,
}

fn body_part(
    body: &Body,
    index: usize,
    first_moment: bool,
    d: &mut Derivation,
) -> Result<Part, DeriveError> {
    let label = format!("{} (body {})", body.label, index + 1);
    match mass_model(body) {
        MassModel::Points(points) => point_part(d, body, &label, &points, first_moment),
        MassModel::Continuum(c) => continuum_part(d, body, index, &label, &c, first_moment),
    }
}

/// A point set's tensor: the sum over its masses.
fn point_part(
    d: &mut Derivation,
    body: &Body,
    label: &str,
    points: &[(Expr, Vec3)],
    first_moment: bool,
) -> Result<Part, DeriveError> {
    let placed: Vec<(Expr, Vec3)> = points
        .iter()
        .map(|(m, r)| (m.clone(), place(body, r)))
        .collect();
    let tensor = sum_mats(placed.iter().map(|(m, r)| mat_scale(m, &inertia_kernel(r))));
    let tensor = simplify_mat(&tensor)?;
    d.steps.push(
        Step::equation(
            &format!("{label}: sum over the point masses"),
            "I",
            &Value::Matrix(tensor.clone()),
            cited(
                "point-tensor",
                Prose::default()
                    .text("the tensor's integral replaced by ")
                    .math("sum_i m_i big(r_i^2 one - vec(r_i) vec(r_i)^T)"),
            ),
        )
        .working(),
    );
    let moment = first_moment.then(|| sum_vecs(placed.iter().map(|(m, r)| scale_vec(m, r))));
    Ok(Part {
        mass: body.mass.clone(),
        tensor,
        first_moment: moment,
    })
}

/// A continuum's tensor: the integrals of each entry over its domain, with ∫dm checked against
/// its mass.
fn continuum_part(
    d: &mut Derivation,
    body: &Body,
    index: usize,
    label: &str,
    c: &Continuum,
    first_moment: bool,
) -> Result<Part, DeriveError> {
    let r = simplify_vec(&place(body, &c.local))?;
    let position = element_steps(d, body, label, c, &r)?;
    let kernel = inertia_kernel(&r);
    let integrands: Vec<Expr> = UNIQUE
        .iter()
        .map(|(i, j)| Expr::mul(vec![c.density_jacobian.clone(), kernel[*i][*j].clone()]))
        .collect();
    let integrands = cas::simplify_all(integrands)?;

    // ∫dm must give back the mass: a check of the parametrisation, not a formality.
    let mut jobs = vec![c.density_jacobian.clone()];
    jobs.extend(integrands.iter().cloned());
    if first_moment {
        jobs.extend(
            r.iter()
                .map(|x| Expr::mul(vec![c.density_jacobian.clone(), x.clone()])),
        );
    }
    let results = cas::simplify_all(cas::integrate_all(jobs, c.domain.clone())?)?;
    if !cas::is_zero_all(vec![Expr::minus(results[0].clone(), body.mass.clone())])?[0] {
        return Err(DeriveError::Inconsistent(format!(
            "∫dm over {} gives {}, not the mass {}",
            body.label, results[0], body.mass
        )));
    }
    d.steps.push(
        Step::equation(
            &format!("{label}: total mass"),
            "int dm",
            &Value::Scalar(results[0].clone()),
            why_integrate(&c.domain),
        )
        .working(),
    );
    entry_steps(d, label, &integrands, &results, &c.domain);
    if index == 0 {
        // The first body's integrand and position, for claims about the notes' integrals.
        d.set(quantity::INTEGRAND, Value::Matrix(symmetric(&integrands)))?;
        d.set(quantity::POSITION, position)?;
    }
    let moment = first_moment.then(|| std::array::from_fn(|i| results[7 + i].clone()));
    Ok(Part {
        mass: results[0].clone(),
        tensor: symmetric(&results[1..7]),
        first_moment: moment,
    })
}

/// The steps that place a mass element and give its mass; the element's position.
fn element_steps(
    d: &mut Derivation,
    body: &Body,
    label: &str,
    c: &Continuum,
    r: &Vec3,
) -> Result<Value, DeriveError> {
    let position = Value::Vector(r.clone());
    d.steps.push(
        Step::equation(
            &format!("{label}: position of a mass element"),
            "vec(r)",
            &position,
            &if body.rotations.is_empty() {
                "the body's own parametrisation".to_string()
            } else {
                "the body's parametrisation, rotated as the scene says, then shifted".to_string()
            },
        )
        .working(),
    );
    let shown = cas::simplify_all(vec![c.density.clone(), c.jacobian.clone()])?;
    let (density, jacobian) = (&shown[0], &shown[1]);
    d.steps.push(
        Step::note(
            &format!("{label}: mass element"),
            Formula::parse(
                "dm = $0 · $1, quad $0 = $2",
                &[Expr::sym(c.density_name), jacobian.clone(), density.clone()],
            ),
            "uniform density: the mass divided by the length, area or volume; times the Jacobian",
        )
        .working(),
    );
    Ok(position)
}

/// One step a unique entry of the tensor: its integral and value.
fn entry_steps(
    d: &mut Derivation,
    label: &str,
    integrands: &[Expr],
    results: &[Expr],
    domain: &[Integral],
) {
    for (k, (i, j)) in UNIQUE.iter().enumerate() {
        let name = format!("I{}{}", AXES[*i], AXES[*j]);
        // Titled as a page sets it (I_xx typeset, not the name `Ixx`).
        let what = if i == j {
            "moment"
        } else {
            "product of inertia"
        };
        let typeset = format!("${}_{{{}}}$", &name[..1], &name[1..]);
        d.steps.push(
            Step::note(
                &format!("{label}: the {what} {typeset}"),
                integral_formula(
                    Formula::parse(&format!("{}_{}", &name[..1], &name[1..]), &[]),
                    &integrands[k],
                    domain,
                    &results[k + 1],
                ),
                why_integrate(domain),
            )
            .working(),
        );
    }
}

pub fn derive_tensor(
    scene: &Scene,
    first_moment: bool,
    d: &mut Derivation,
) -> Result<(), DeriveError> {
    let mut parts = Vec::new();
    for (i, body) in scene.bodies.iter().enumerate() {
        parts.push(body_part(body, i, first_moment, d)?);
    }
    d.part_tensors = parts
        .iter()
        .map(|p| Value::Matrix(p.tensor.clone()))
        .collect();
    let tensor = sum_mats(parts.iter().map(|p| p.tensor.clone()));
    let tensor = simplify_value(&Value::Matrix(tensor))?;
    let mass = cas::simplify(&Expr::add(parts.iter().map(|p| p.mass.clone()).collect()))?;
    d.steps.push(Step::equation(
        "The inertia tensor",
        "ten(I)",
        &tensor,
        if parts.len() > 1 {
            "the sum of the parts' tensors about the same origin"
        } else {
            "each entry the body's integral over its mass (a sum, for point masses); $\\overleftrightarrow{I}$ is symmetric"
        },
    ));
    d.set(quantity::INERTIA_TENSOR, tensor)?;
    d.set(quantity::MASS, Value::Scalar(mass.clone()))?;
    if first_moment {
        let sum = sum_vecs(
            parts
                .iter()
                .map(|p| p.first_moment.clone().expect("asked for")),
        );
        let centre = simplify_value(&Value::Vector(std::array::from_fn(|i| {
            Expr::over(sum[i].clone(), mass.clone())
        })))?;
        let r = centre_name(scene);
        d.steps.push(Step::equation(
            "Centre of mass",
            &format!("vec({r})"),
            &centre,
            Prose::default()
                .math(&format!("vec({r}) = 1/M int vec(r) ~ dm"))
                .text(", from the same integrals"),
        ));
        d.set(quantity::CENTRE_OF_MASS, centre)?;
    }
    Ok(())
}

/// The centre of mass's name: R, or R_cm in a scene that has an R of its own (a radius), so
/// that no name means two things on its page.
fn centre_name(scene: &Scene) -> &'static str {
    if scene.symbols.contains_key("R") || scene.coordinates.contains_key("R") {
        "R_cm"
    } else {
        "R"
    }
}

/// Proves I_origin = I_cm + M(d²𝟙 − ddᵀ), with I_cm integrated directly about the centre of mass.
pub fn derive_parallel_axis(scene: &Scene, d: &mut Derivation) -> Result<(), DeriveError> {
    let Some(Value::Vector(centre)) = d.quantities.get(quantity::CENTRE_OF_MASS).cloned() else {
        return Err(DeriveError::Inconsistent(
            "parallel axis without a centre of mass".into(),
        ));
    };
    let Some(Value::Scalar(mass)) = d.quantities.get(quantity::MASS).cloned() else {
        return Err(DeriveError::Inconsistent(
            "parallel axis without a mass".into(),
        ));
    };
    // Route 1: integrate again with every body shifted so that the centre of mass is the origin.
    let shifted: Vec<Body> = scene
        .bodies
        .iter()
        .map(|b| {
            let mut b = b.clone();
            b.shift = sub_vec(&b.shift, &centre);
            b
        })
        .collect();
    let mut scratch = Derivation::default();
    let mut about_cm: Option<Mat3> = None;
    for (i, b) in shifted.iter().enumerate() {
        let part = body_part(b, i, false, &mut scratch)?;
        about_cm = Some(match about_cm {
            None => part.tensor,
            Some(t) => mat_add(&t, &part.tensor),
        });
    }
    let cm = simplify_mat(&about_cm.unwrap())?;
    let r = centre_name(scene);
    let about_cm = Value::Matrix(cm.clone());
    d.steps.push(Step::equation(
        "Tensor about the centre of mass, by direct integration",
        "I_cm",
        &about_cm,
        format!(
            "the same integrals with $\\vec r$ measured from $\\vec{{{}}}$",
            r.replace("_cm", "_{\\mathrm{cm}}")
        ),
    ));
    // Route 2: the theorem, I_cm + M(d²𝟙 − ddᵀ) with d = R.
    let shift_term = mat_scale(&mass, &inertia_kernel(&centre));
    let theorem = simplify_value(&Value::Matrix(mat_add(&cm, &shift_term)))?;
    let parallel_axis = format!("I_cm + M big({r}^2 one - vec({r}) vec({r})^T)");
    d.steps.push(Step::equation(
        "Parallel-axis theorem",
        &parallel_axis,
        &theorem,
        cited(
            "parallel-axis",
            Prose::default()
                .text("in tensor form; the cross term vanishes because ")
                .math("sum m ~ vec(r)' = 0")
                .text(" about the centre of mass"),
        ),
    ));
    let direct = d.get(quantity::INERTIA_TENSOR)?.clone();
    if !values_equal(&theorem, &direct)? {
        return Err(DeriveError::Inconsistent(
            "the parallel-axis theorem does not reproduce the direct tensor".into(),
        ));
    }
    d.steps.push(
        Step::note(
            "Both routes agree",
            Formula::parse(&format!("{parallel_axis} - ten(I) = 0"), &[]),
            "every entry of the difference simplifies to zero",
        )
        .second_route(),
    );
    d.set(quantity::INERTIA_CM, about_cm)?;
    Ok(())
}
