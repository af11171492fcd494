//! Derivations of every body kind, each checked two ways: against the independent numeric
//! quadrature at the scene's values (≤ 1e-14 relative), and by an invariant that needs no
//! numbers (perpendicular axes, additivity, rotation covariance, symmetry).

use super::algebra::{Value, mat_mul, rotation, transpose};
use super::values_equal;
use crate::pipeline::{SceneReport, run_scene};
use crate::scene::Scene;
use std::path::Path;

fn run(body: &str, symbols: &str, values: &str, want: &str) -> SceneReport {
    let text = format!(
        "id = \"t\"\ntitle = \"t\"\nnotes = {{ lecture = \"x\" }}\nsymbols = {{ {symbols} }}\n{body}\n[outputs]\nwant = [{want}]\n[numeric]\nvalues = {{ {values} }}\n"
    );
    let scene =
        Scene::parse(&text, Path::new("test.toml")).unwrap_or_else(|e| panic!("{e}\n{text}"));
    run_scene(scene, None).unwrap()
}

fn tensor(r: &SceneReport) -> Value {
    r.derivation.quantities["inertia_tensor"].clone()
}

fn entry(r: &SceneReport, i: usize, j: usize) -> crate::cas::Expr {
    match tensor(r) {
        Value::Matrix(m) => m[i][j].clone(),
        _ => unreachable!(),
    }
}

/// The exact tensor equals the numeric one within 1e-14, and every check of the scene passes.
fn assert_cross_checked(r: &SceneReport) {
    assert!(r.verification.verified(), "{:#?}", r.verification);
    let q = r
        .verification
        .quantities
        .iter()
        .find(|q| q.name == "inertia_tensor")
        .expect("numeric check ran");
    assert!(q.error <= 1e-14, "exact vs numeric: {}", q.error);
}

const ALL: &str = "\"inertia_tensor\", \"principal_axes\", \"numeric\"";

#[test]
fn every_body_kind_matches_its_numeric_quadrature() {
    let cases = [
        (
            "[[body]]\nkind = \"box\"\nsize = [\"a\", \"b\", \"c\"]\nmass = \"M\"\n",
            "M = \"m\", a = \"a\", b = \"b\", c = \"c\"",
            "M = 2.0, a = 1.0, b = 2.0, c = 3.0",
        ),
        (
            "[[body]]\nkind = \"rod\"\nlength = \"L\"\nalong = \"x\"\nmass = \"M\"\norigin = \"centre\"\n",
            "M = \"m\", L = \"l\"",
            "M = 2.0, L = 3.0",
        ),
        (
            "[[body]]\nkind = \"ring\"\nradius = \"R\"\nmass = \"M\"\n",
            "M = \"m\", R = \"r\"",
            "M = 2.0, R = 0.5",
        ),
        (
            "[[body]]\nkind = \"disk\"\nradius = \"R\"\nmass = \"M\"\n",
            "M = \"m\", R = \"r\"",
            "M = 2.0, R = 0.5",
        ),
        (
            "[[body]]\nkind = \"cylinder\"\nradius = \"R\"\nheight = \"h\"\nmass = \"M\"\n",
            "M = \"m\", R = \"r\", h = \"h\"",
            "M = 2.0, R = 0.5, h = 3.0",
        ),
        (
            "[[body]]\nkind = \"sphere\"\nradius = \"R\"\nmass = \"M\"\n",
            "M = \"m\", R = \"r\"",
            "M = 2.0, R = 0.5",
        ),
        (
            "[[body]]\nkind = \"shell\"\nradius = \"R\"\nmass = \"M\"\n",
            "M = \"m\", R = \"r\"",
            "M = 2.0, R = 0.5",
        ),
        (
            "[[body]]\nkind = \"points\"\npoints = [{ mass = \"M\", at = [\"d\", \"0\", \"0\"] }, { mass = \"2*M\", at = [\"0\", \"d\", \"d\"] }]\n",
            "M = \"m\", d = \"d\"",
            "M = 2.0, d = 0.5",
        ),
    ];
    for (body, symbols, values) in cases {
        let r = run(body, symbols, values, ALL);
        assert_cross_checked(&r);
        // A tensor is symmetric and its diagonal obeys the triangle inequality I1 + I2 >= I3.
        let m = tensor(&r).matrix_at(&r.scene.values).unwrap();
        assert_eq!(m, m.transpose());
        for (i, j, k) in [(0, 1, 2), (1, 2, 0), (2, 0, 1)] {
            assert!(m[(i, i)] + m[(j, j)] >= m[(k, k)] - 1e-15);
        }
    }
}

#[test]
fn planar_bodies_obey_the_perpendicular_axis_theorem() {
    for kind in ["hoop", "disk"] {
        let r = run(
            &format!("[[body]]\nkind = \"{kind}\"\nradius = \"R\"\nmass = \"M\"\n"),
            "M = \"m\", R = \"r\"",
            "M = 1.0, R = 1.0",
            "\"inertia_tensor\"",
        );
        let sum = crate::cas::Expr::add(vec![entry(&r, 0, 0), entry(&r, 1, 1)]);
        assert!(
            values_equal(&Value::Scalar(sum), &Value::Scalar(entry(&r, 2, 2))).unwrap(),
            "{kind}"
        );
    }
}

#[test]
fn a_composite_is_the_sum_of_its_parts() {
    // Two a×b×c boxes side by side along x are one 2a×b×c box of twice the mass.
    let two = run(
        "[[body]]\nkind = \"box\"\nsize = [\"a\", \"b\", \"c\"]\nmass = \"M\"\n[[body]]\nkind = \"box\"\nsize = [\"a\", \"b\", \"c\"]\nmass = \"M\"\nshift = [\"a\", \"0\", \"0\"]\n",
        "M = \"m\", a = \"a\", b = \"b\", c = \"c\"",
        "M = 1.0, a = 1.0, b = 2.0, c = 3.0",
        ALL,
    );
    assert_cross_checked(&two);
    let one = run(
        "[[body]]\nkind = \"box\"\nsize = [\"2*a\", \"b\", \"c\"]\nmass = \"2*M\"\n",
        "M = \"m\", a = \"a\", b = \"b\", c = \"c\"",
        "M = 1.0, a = 1.0, b = 2.0, c = 3.0",
        "\"inertia_tensor\"",
    );
    assert!(values_equal(&tensor(&two), &tensor(&one)).unwrap());
}

#[test]
fn rotating_a_body_rotates_its_tensor() {
    let body = "[[body]]\nkind = \"cylinder\"\nradius = \"R\"\nheight = \"h\"\nmass = \"M\"\n";
    let syms = "M = \"m\", R = \"r\", h = \"h\", t = \"angle\"";
    let vals = "M = 1.0, R = 0.5, h = 2.0, t = 0.7";
    let flat = run(body, syms, vals, "\"inertia_tensor\"");
    let turned = run(
        &format!("{body}rotate = [{{ axis = \"x\", angle = \"t\" }}]\n"),
        syms,
        vals,
        ALL,
    );
    assert_cross_checked(&turned);
    let Value::Matrix(i0) = tensor(&flat) else {
        unreachable!()
    };
    let q = rotation(0, &crate::cas::Expr::sym("t"));
    let expected = Value::Matrix(mat_mul(&mat_mul(&q, &i0), &transpose(&q)));
    assert!(values_equal(&tensor(&turned), &expected).unwrap());
}

#[test]
fn a_quarter_turn_leaves_no_cosine_of_pi_over_two() {
    let body = "[[body]]\nkind = \"box\"\nsize = [\"a\", \"b\", \"c\"]\nmass = \"m\"\n";
    let turned = run(
        &format!(
            "{body}rotate = [{{ axis = \"y\", angle = \"pi/2\" }}, {{ axis = \"z\", angle = \"pi/6\" }}]\n"
        ),
        "m = \"m\", a = \"a\", b = \"b\", c = \"c\"",
        "m = 1.0, a = 1.0, b = 2.0, c = 3.0",
        ALL,
    );
    assert_cross_checked(&turned);
    let text = tensor(&turned).to_text();
    assert!(!text.contains("cos") && !text.contains("sin"), "{text}");
    // No step shows the turn's angles (the Viète form of the moments has its own cosines).
    for step in &turned.derivation.steps {
        let shown = step.statement.to_text();
        for angle in ["π/2", "π/6", "1/2*pi", "1/6*pi", "1/2 π", "1/6 π"] {
            assert!(!shown.contains(angle), "{shown}");
        }
    }
}

#[test]
fn a_sphere_is_isotropic_and_a_shell_has_more_inertia() {
    let r = run(
        "[[body]]\nkind = \"sphere\"\nradius = \"R\"\nmass = \"M\"\n",
        "M = \"m\", R = \"r\"",
        "M = 1.0, R = 1.0",
        ALL,
    );
    let e = r.derivation.eigen.as_ref().unwrap();
    assert_eq!(e.spaces.len(), 1);
    assert_eq!(e.spaces[0].multiplicity, 3);
    assert!(matches!(e.spaces[0].basis, super::ExactBasis::All));
    let s = run(
        "[[body]]\nkind = \"shell\"\nradius = \"R\"\nmass = \"M\"\n",
        "M = \"m\", R = \"r\"",
        "M = 1.0, R = 1.0",
        "\"inertia_tensor\"",
    );
    let at = |r: &SceneReport| {
        entry(r, 0, 0)
            .eval(&|x| r.scene.values.get(x).copied())
            .unwrap()
    };
    // All of the shell's mass sits at the largest radius.
    assert!(at(&s) > at(&r));
}

#[test]
fn only_requested_stages_run() {
    let r = run(
        "[[body]]\nkind = \"box\"\nsize = [\"a\", \"a\", \"a\"]\nmass = \"M\"\n",
        "M = \"m\", a = \"a\"",
        "M = 1.0, a = 1.0",
        "\"inertia_tensor\"",
    );
    assert!(r.numeric.is_none());
    assert!(r.derivation.eigen.is_none());
    assert!(!r.derivation.quantities.contains_key("centre_of_mass"));
    assert!(r.verification.quantities.is_empty());
}

#[test]
fn the_eigenvalue_takes_another_letter_where_lambda_is_a_line_density() {
    let letters = |body: &str| {
        let r = run(body, "M = \"m\", R = \"r\"", "M = 2.0, R = 1.0", ALL);
        let latex: String = r
            .derivation
            .steps
            .iter()
            .map(|s| s.statement.to_latex(crate::notation::Names::none()))
            .collect();
        (latex.contains("\\lambda"), latex.contains("\\mu"))
    };
    // A hoop's mass element is λ R dθ: the characteristic polynomial is in μ.
    let hoop = "[[body]]\nkind = \"hoop\"\nradius = \"R\"\nmass = \"M\"\n";
    assert_eq!(letters(hoop), (true, true));
    let r = run(hoop, "M = \"m\", R = \"r\"", "M = 2.0, R = 1.0", ALL);
    let polynomial = r
        .derivation
        .steps
        .iter()
        .find(|s| s.title.to_text() == "Characteristic polynomial")
        .unwrap()
        .statement
        .to_latex(crate::notation::Names::none());
    assert!(polynomial.contains("- \\mu\\mathbb{1}"), "{polynomial}");
    assert!(!polynomial.contains("\\lambda"), "{polynomial}");
    // A sphere has no line density: λ as usual.
    let sphere = "[[body]]\nkind = \"sphere\"\nradius = \"R\"\nmass = \"M\"\n";
    assert_eq!(letters(sphere), (true, false));
}

#[test]
fn principal_moments_come_in_ascending_order_and_match_the_eigen_solver() {
    // Cases whose characteristic cubic factors into several pieces, which the factoriser may
    // list in any order: an L of three squares, a box, a disk on a rod.
    let cases = [
        (
            "[[body]]\nkind = \"plate\"\nsize = [\"2*a\", \"a\"]\nmass = \"2*M\"\n\
             [[body]]\nkind = \"plate\"\nsize = [\"a\", \"a\"]\nmass = \"M\"\nshift = [\"0\", \"a\", \"0\"]\n",
            "M = \"m\", a = \"a\"",
            "M = 1.0, a = 1.0",
        ),
        (
            "[[body]]\nkind = \"box\"\nsize = [\"3*a\", \"a\", \"2*a\"]\nmass = \"M\"\norigin = \"centre\"\n",
            "M = \"m\", a = \"a\"",
            "M = 1.0, a = 1.0",
        ),
        (
            "[[body]]\nkind = \"plate\"\nsize = [\"a\", \"2*a\"]\nmass = \"M\"\norigin = \"centre\"\n",
            "M = \"m\", a = \"a\"",
            "M = 2.0, a = 0.5",
        ),
    ];
    for (body, symbols, values) in cases {
        let r = run(body, symbols, values, ALL);
        let Value::Vector(moments) = &r.derivation.quantities["principal_moments"] else {
            panic!("no principal moments for {body}")
        };
        let exact: Vec<f64> = moments
            .iter()
            .map(|m| crate::model::value::eval_at(m, &r.scene.values).unwrap())
            .collect();
        let numeric = tensor(&r).matrix_at(&r.scene.values).unwrap();
        let eigen = crate::numeric::eigen::sorted_eigenvalues(&numeric);
        for (x, e) in exact.iter().zip(&eigen) {
            assert!(
                (x - e).abs() <= 1e-13 * e.abs().max(1.0),
                "{exact:?} vs {eigen:?}"
            );
        }
    }
}

#[test]
fn a_quantity_is_set_once_by_its_kind_and_only_if_catalogued() {
    use super::{Derivation, DeriveError};
    use crate::cas::Expr;
    use crate::model::catalogue::quantity;
    let mut d = Derivation::default();
    let energy = Value::Scalar(Expr::sym("E"));
    d.set(quantity::TWICE_ENERGY, energy.clone()).unwrap();
    // A second writer used to replace the first silently.
    let again = d.set(quantity::TWICE_ENERGY, Value::Scalar(Expr::int(2)));
    assert!(matches!(again, Err(DeriveError::Inconsistent(m)) if m.contains("derived twice")));
    assert_eq!(d.quantities[quantity::TWICE_ENERGY], energy);
    let scalar_as_matrix = d.set(quantity::INERTIA_TENSOR, energy.clone());
    assert!(
        matches!(scalar_as_matrix, Err(DeriveError::Inconsistent(m)) if m.contains("catalogue says Matrix"))
    );
    let unknown = d.set("energy", energy);
    assert!(
        matches!(unknown, Err(DeriveError::Inconsistent(m)) if m.contains("not in the catalogue"))
    );
}

/// An author's integration step is shown under its own name as a symbol, so the page's LaTeX
/// and the PDF's Typst print it alike (`Ix` was italic "Ix" on the page and upright in the
/// PDF; `I1cone` was a product of letters on the page).
#[test]
fn an_integration_steps_name_prints_alike_on_the_page_and_in_the_pdf() {
    for (name, latex, typst) in [
        ("Ix", "I_{x} = ", "attach(I, b: x)\\="),
        ("I1cone", "I_{1cone} = ", "attach(I, b: 1 c o n e)\\="),
    ] {
        let text = format!(
            "id = \"t\"\ntitle = \"t\"\nnotes = {{ lecture = \"x\" }}\nsymbols = {{ M = \"mass\", R = \"radius\" }}\n\
             [[step]]\nname = \"{name}\"\nintegrate = \"M*r\"\nover = [[\"r\", \"0\", \"R\"]]\nwhy = \"w\"\n\
             [numeric]\nvalues = {{ M = 1.0, R = 1.0 }}\n"
        );
        let scene = Scene::parse(&text, Path::new("t.toml")).unwrap_or_else(|e| panic!("{e}"));
        let report = run_scene(scene, None).unwrap();
        let step = report
            .derivation
            .steps
            .iter()
            .find(|s| {
                s.statement
                    .to_latex(crate::notation::Names::none())
                    .contains("\\int")
            })
            .expect("the integral's step");
        let (l, t) = (
            step.statement.to_latex(crate::notation::Names::none()),
            step.statement
                .to_tex(crate::notation::Names::none())
                .to_typst()
                .unwrap(),
        );
        assert!(l.starts_with(latex), "{l}");
        assert!(t.starts_with(typst), "{t}");
    }
}

/// The definition's route is headed by its symbol set as mathematics (`L⃗`, `I_n`), and states
/// the same vector the tensor's route does: never a name printed as text ("I_n, from the
/// definition").
#[test]
fn the_definitions_route_is_headed_by_its_symbol_as_mathematics() {
    let text = "id = \"t\"\ntitle = \"t\"\nnotes = { lecture = \"x\" }\n\
        symbols = { M = \"m\", d = \"d\", w = \"w\" }\n\
        omega = [\"0\", \"0\", \"w\"]\naxis = [\"0\", \"0\", \"1\"]\n\
        [[body]]\nkind = \"points\"\n\
        points = [{ mass = \"M\", at = [\"d\", \"0\", \"0\"] }, { mass = \"2*M\", at = [\"0\", \"d\", \"d\"] }]\n\
        [outputs]\nwant = [\"angular_momentum\", \"kinetic_energy\", \"moment_about_axis\"]\n\
        [numeric]\nvalues = { M = 1.0, d = 1.0, w = 2.0 }\n";
    let scene = Scene::parse(text, Path::new("test.toml")).unwrap_or_else(|e| panic!("{e}"));
    let r = run_scene(scene, None).unwrap();
    let routes: Vec<_> = r
        .derivation
        .steps
        .iter()
        .filter(|s| s.second_route)
        .collect();
    assert_eq!(routes.len(), 3);
    let none = crate::notation::Names::none();
    for s in &routes {
        let crate::model::prose::Piece::Math(symbol) = &s.title.0[0] else {
            panic!("a heading that opens with text: {:?}", s.title);
        };
        let crate::notation::Formula::Row(sides) = &s.statement else {
            panic!("not an equation: {:?}", s.statement);
        };
        assert_eq!(symbol.to_latex(none), sides[0].to_latex(none));
    }
    let symbols: Vec<String> = routes
        .iter()
        .map(|s| s.title.0[0].clone())
        .map(|p| match p {
            crate::model::prose::Piece::Math(f) => f.to_latex(none),
            crate::model::prose::Piece::Text(t) => t,
        })
        .collect();
    assert_eq!(symbols, ["\\vec{L}", "T", "I_{n}"]);
}
