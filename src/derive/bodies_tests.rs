//! The bodies added for courses beyond the shipped notes: plate, cone, hemisphere, the hollow
//! disk, cylinder and sphere, and holes. Each exact tensor is checked three ways: against the
//! numeric quadrature (its own parametrisation, ≤ 1e-14), against the closed forms of a standard
//! table (Goldstein; Marion & Thornton), and by the centre of mass where the origin claims it.

use super::algebra::Value;
use super::values_equal;
use crate::cas::parse;
use crate::model::catalogue::quantity;
use crate::pipeline::{SceneReport, run_scene};
use crate::scene::Scene;
use std::path::Path;

fn run(body: &str, want: &str) -> SceneReport {
    let text = format!(
        "id = \"t\"\ntitle = \"t\"\nnotes = {{ lecture = \"x\" }}\nsymbols = {{ M = \"mass\", R = \"radius\", r0 = \"inner radius\", h = \"height\", a = \"side\", b = \"side\", k = \"mass per unit of radius cubed\" }}\n{body}\n[outputs]\nwant = [{want}]\n[numeric]\nvalues = {{ M = 2.0, R = 0.7, r0 = 0.3, h = 1.9, a = 1.1, b = 0.6, k = 1.3 }}\n"
    );
    let scene =
        Scene::parse(&text, Path::new("test.toml")).unwrap_or_else(|e| panic!("{e}\n{text}"));
    run_scene(scene, None).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

const CHECKED: &str = "\"inertia_tensor\", \"parallel_axis\", \"principal_axes\", \"numeric\"";

fn matrix(rows: [[&str; 3]; 3]) -> Value {
    Value::Matrix(rows.map(|row| row.map(|e| parse(e).unwrap().expr)))
}

fn diagonal(xx: &str, yy: &str, zz: &str) -> Value {
    matrix([[xx, "0", "0"], ["0", yy, "0"], ["0", "0", zz]])
}

/// The exact tensor equals the numeric quadrature within 1e-14, every check of the scene passes,
/// and the tensor is the table's.
fn assert_body(body: &str, table: Value) {
    let r = run(body, CHECKED);
    assert!(r.verification.verified(), "{body}\n{:#?}", r.verification);
    let q = r
        .verification
        .quantities
        .iter()
        .find(|q| q.name == quantity::INERTIA_TENSOR)
        .expect("the numeric check ran");
    assert!(q.error <= 1e-14, "{body}: exact vs numeric {}", q.error);
    let tensor = r.derivation.get(quantity::INERTIA_TENSOR).unwrap();
    assert!(
        values_equal(tensor, &table).unwrap(),
        "{body}: derived {tensor:?}"
    );
}

fn centre_of_mass(body: &str) -> Value {
    run(body, "\"parallel_axis\"")
        .derivation
        .get(quantity::CENTRE_OF_MASS)
        .unwrap()
        .clone()
}

fn origin_vector(z: &str) -> Value {
    Value::Vector(["0", "0", z].map(|e| parse(e).unwrap().expr))
}

#[test]
fn a_plate_matches_the_table_about_its_corner_and_its_centre() {
    assert_body(
        "[[body]]\nkind = \"plate\"\nsize = [\"a\", \"b\"]\nmass = \"M\"\n",
        matrix([
            ["M*b^2/3", "-M*a*b/4", "0"],
            ["-M*a*b/4", "M*a^2/3", "0"],
            ["0", "0", "M*(a^2 + b^2)/3"],
        ]),
    );
    assert_body(
        "[[body]]\nkind = \"plate\"\nsize = [\"a\", \"b\"]\nmass = \"M\"\norigin = \"centre\"\n",
        diagonal("M*b^2/12", "M*a^2/12", "M*(a^2 + b^2)/12"),
    );
}

#[test]
fn a_cone_matches_the_table_about_its_apex_base_and_centre() {
    let cone = "[[body]]\nkind = \"cone\"\nradius = \"R\"\nheight = \"h\"\nmass = \"M\"\n";
    let across = |h2: &str| format!("3/20*M*R^2 + {h2}*M*h^2");
    assert_body(cone, diagonal(&across("3/5"), &across("3/5"), "3/10*M*R^2"));
    assert_body(
        &format!("{cone}origin = \"base\"\n"),
        diagonal(&across("1/10"), &across("1/10"), "3/10*M*R^2"),
    );
    assert_body(
        &format!("{cone}origin = \"centre\"\n"),
        diagonal(&across("3/80"), &across("3/80"), "3/10*M*R^2"),
    );
    assert!(values_equal(&centre_of_mass(cone), &origin_vector("3/4*h")).unwrap());
    assert!(
        values_equal(
            &centre_of_mass(&format!("{cone}origin = \"centre\"\n")),
            &origin_vector("0")
        )
        .unwrap()
    );
}

#[test]
fn a_hemisphere_matches_the_table_about_its_face_and_its_centre() {
    let dome = "[[body]]\nkind = \"hemisphere\"\nradius = \"R\"\nmass = \"M\"\n";
    assert_body(dome, diagonal("2/5*M*R^2", "2/5*M*R^2", "2/5*M*R^2"));
    assert_body(
        &format!("{dome}origin = \"centre\"\n"),
        diagonal("83/320*M*R^2", "83/320*M*R^2", "2/5*M*R^2"),
    );
    assert!(values_equal(&centre_of_mass(dome), &origin_vector("3/8*R")).unwrap());
}

#[test]
fn hollow_bodies_match_the_table() {
    assert_body(
        "[[body]]\nkind = \"disk\"\nradius = \"R\"\ninner_radius = \"r0\"\nmass = \"M\"\n",
        diagonal("M*(R^2 + r0^2)/4", "M*(R^2 + r0^2)/4", "M*(R^2 + r0^2)/2"),
    );
    assert_body(
        "[[body]]\nkind = \"cylinder\"\nradius = \"R\"\nheight = \"h\"\ninner_radius = \"r0\"\nmass = \"M\"\n",
        diagonal(
            "M*(3*(R^2 + r0^2) + h^2)/12",
            "M*(3*(R^2 + r0^2) + h^2)/12",
            "M*(R^2 + r0^2)/2",
        ),
    );
    let shell = "2/5*M*(R^5 - r0^5)/(R^3 - r0^3)";
    assert_body(
        "[[body]]\nkind = \"sphere\"\nradius = \"R\"\ninner_radius = \"r0\"\nmass = \"M\"\n",
        diagonal(shell, shell, shell),
    );
}

#[test]
fn a_ball_less_a_concentric_ball_is_the_thick_shell() {
    // Uniform density: a ball of radius R has mass k R³, its core of radius r0 mass k r0³.
    let holed = "[[body]]\nkind = \"sphere\"\nradius = \"R\"\nmass = \"k*R^3\"\n[[body]]\nkind = \"sphere\"\nradius = \"r0\"\nmass = \"k*r0^3\"\nsubtract = true\n";
    let shell = "2/5*k*(R^5 - r0^5)";
    assert_body(holed, diagonal(shell, shell, shell));
    let mass = run(holed, "\"inertia_tensor\"");
    let total = mass.derivation.get(quantity::MASS).unwrap();
    let expected = Value::Scalar(parse("k*(R^3 - r0^3)").unwrap().expr);
    assert!(values_equal(total, &expected).unwrap());
}

#[test]
fn a_plate_with_a_square_hole_off_centre() {
    // The hole's tensor about the plate's corner, by the parallel-axis theorem by hand:
    // a side-s square of mass m centred at (c, c) has I_xx = m s²/12 + m c², I_xy = −m c².
    let body = "[[body]]\nkind = \"plate\"\nsize = [\"a\", \"a\"]\nmass = \"M\"\n[[body]]\nkind = \"plate\"\nsize = [\"a/4\", \"a/4\"]\nmass = \"M/16\"\norigin = \"centre\"\nshift = [\"a/2\", \"a/2\", \"0\"]\nsubtract = true\n";
    let (m, s, c) = ("(M/16)", "(a/4)", "(a/2)");
    let xx = format!("M*a^2/3 - ({m}*{s}^2/12 + {m}*{c}^2)");
    let xy = format!("-M*a^2/4 + {m}*{c}^2");
    let zz = format!("2*M*a^2/3 - ({m}*{s}^2/6 + 2*{m}*{c}^2)");
    assert_body(
        body,
        matrix([[&xx, &xy, "0"], [&xy, &xx, "0"], ["0", "0", &zz]]),
    );
}

/// A scene may name its own symbols `r` and `theta` (a disk of radius r, a tilt theta): the disk
/// integrates over `r_1` and `theta_1`, and its tensor is still the table's M r²/4, M r²/4,
/// M r²/2, equal to the numeric quadrature; the integrand is written in the body's names.
#[test]
fn a_disk_of_radius_r_beside_a_symbol_theta() {
    let text = "id = \"t\"\ntitle = \"t\"\nnotes = { lecture = \"x\" }\nsymbols = { M = \"mass\", r = \"radius\", theta = \"a tilt\" }\n[[body]]\nkind = \"disk\"\nradius = \"r\"\nmass = \"M\"\nrotate = [{ axis = \"x\", angle = \"theta\" }]\n[outputs]\nwant = [\"inertia_tensor\", \"numeric\"]\n[numeric]\nvalues = { M = 2.0, r = 0.7, theta = 0.4 }\n";
    let r = run_scene(Scene::parse(text, Path::new("t.toml")).unwrap(), None).unwrap();
    assert_eq!(r.scene.bodies[0].variables, ["r_1", "theta_1"]);
    assert!(r.verification.verified(), "{:#?}", r.verification);
    let q = r
        .verification
        .quantities
        .iter()
        .find(|q| q.name == quantity::INERTIA_TENSOR)
        .unwrap();
    assert!(q.error <= 1e-14, "exact vs numeric {}", q.error);
    // The disk tilted by theta about x: Iyy and Izz mix, Iyz = -(M r²/4) sin θ cos θ.
    let table = matrix([
        ["M*r^2/4", "0", "0"],
        [
            "0",
            "M*r^2/4*cos(theta)^2 + M*r^2/2*sin(theta)^2",
            "-M*r^2/4*sin(theta)*cos(theta)",
        ],
        [
            "0",
            "-M*r^2/4*sin(theta)*cos(theta)",
            "M*r^2/4*sin(theta)^2 + M*r^2/2*cos(theta)^2",
        ],
    ]);
    let tensor = r.derivation.get(quantity::INERTIA_TENSOR).unwrap();
    assert!(values_equal(tensor, &table).unwrap(), "{tensor:?}");
    let integrand = r.derivation.get(quantity::INTEGRAND).unwrap().entries();
    let names: std::collections::BTreeSet<String> =
        integrand.iter().flat_map(|e| e.symbols()).collect();
    assert!(names.contains("r_1") && names.contains("theta_1") && names.contains("theta"));
}
