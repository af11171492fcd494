use super::convergence::convergence;
use super::projection::plane_basis;
use crate::model::fidelity::Fidelity;
use crate::numeric::body::{NumBody, NumShape};
use crate::numeric::pareto::pareto_front;
use nalgebra::{Matrix3, Vector3};

fn unit_cube() -> NumBody {
    NumBody {
        label: "cube".into(),
        shape: NumShape::Box {
            size: Vector3::new(1.0, 1.0, 1.0),
            centred: true,
        },
        mass: 1.0,
        rotation: Matrix3::identity(),
        shift: Vector3::zeros(),
    }
}

#[test]
fn convergence_slopes_follow_each_law() {
    // Centred unit cube: exact tensor 𝟙/6, independent of any quadrature.
    let fig = convergence(
        &unit_cube(),
        &(Matrix3::identity() / 6.0),
        7,
        "c".into(),
        &Fidelity::STANDARD,
    )
    .unwrap();
    let measured = |name: &str| {
        fig.series
            .iter()
            .find(|s| s.name == name)
            .unwrap()
            .points
            .clone()
    };
    // Midpoint: error ∝ 1/n² = N^(-2/3); vertex: ∝ 1/n = N^(-1/3).
    for (name, want) in [
        ("midpoint-lattice", -2.0 / 3.0),
        ("vertex-lattice", -1.0 / 3.0),
    ] {
        let p = measured(name);
        let (a, b) = (p[2], p[p.len() - 1]);
        let k = (b.1 / a.1).log10() / (b.0 / a.0).log10();
        assert!((k - want).abs() < 0.03, "{name}: slope {k}");
    }
    // Gauss–Legendre is exact for the quadratic integrand from 2 points per axis.
    let gl = measured("gauss-legendre");
    assert!(gl[0].1 > 0.1 && gl[1..].iter().all(|p| p.1 < 1e-14));
    assert!(
        fig.desc.to_text().contains("midpoint-lattice")
            && fig.desc.to_text().contains("slope -0.6")
    );
}

#[test]
fn the_pareto_front_keeps_only_undominated_points() {
    let pts = [
        (10.0, 1e-3),
        (5.0, 1e-2),
        (20.0, 1e-3),
        (40.0, 1e-8),
        (30.0, 1e-1),
    ];
    assert_eq!(
        pareto_front(&pts),
        vec![(5.0, 1e-2), (10.0, 1e-3), (40.0, 1e-8)]
    );
    // Every dropped point is beaten on both counts by a kept one.
    for p in pts {
        let front = pareto_front(&pts);
        assert!(front.contains(&p) || front.iter().any(|q| q.0 <= p.0 && q.1 <= p.1));
    }
}

#[test]
fn plane_basis_is_orthonormal_and_normal() {
    let n = Vector3::new(1.0, 1.0, 1.0);
    let (u, w) = plane_basis(&n);
    for (a, b) in [
        (u.dot(&n), 0.0),
        (w.dot(&n), 0.0),
        (u.dot(&w), 0.0),
        (u.norm(), 1.0),
        (w.norm(), 1.0),
    ] {
        assert!((a - b).abs() < 1e-15);
    }
}

/// A scene's figure, from the scene derived as the build derives it.
fn figure_of(scene: &str, slug: &str) -> crate::model::figure::Figure {
    let s = crate::scene::Scene::from_file(std::path::Path::new(scene)).unwrap();
    let r = crate::pipeline::run_scene(s, None).unwrap();
    r.figures
        .into_iter()
        .find(|f| f.slug == slug)
        .unwrap_or_else(|| panic!("{scene} has no figure {slug}"))
}

#[test]
fn a_caption_gives_exact_moments_and_axes_as_a_physicist_writes_them() {
    let f = figure_of("tests/course/bodies/05-l-plate.toml", "principal-axes");
    // Was `moment 19/4*m*a^2 (4.7500): axis [−1, 1, 0]`.
    for part in [
        "moment 5ma²/4 (1.2500): axis (1, 1, 0)",
        "moment 19ma²/4 (4.7500): axis (−1, 1, 0)",
        "moment 6ma² (6.0000): axis (0, 0, 1)",
    ] {
        assert!(f.desc.to_text().contains(part), "{part} in {}", f.desc);
    }
    assert!(!f.desc.to_text().contains(['*', '^', '[']), "{}", f.desc);
    let legends: Vec<&str> = f.series.iter().map(|s| s.name.as_str()).collect();
    assert!(legends.contains(&"I = 19ma²/4"), "{legends:?}");
}

#[test]
fn the_tennis_racket_caption_gives_its_moments_to_six_figures() {
    let f = figure_of("tests/course/bodies/07-book-flip.toml", "flip");
    // Was `I = (0.000993333333333333, 0.00195, 0.00288333333333333)`.
    assert!(
        f.desc
            .to_text()
            .contains("(I2 = 0.00195) of I = (0.000993333, 0.00195, 0.00288333)"),
        "{}",
        f.desc
    );
}

/// The swept symbol and the fixed ones are written as they print (α, not `alpha`), in the
/// caption, the title and the axis; the file keeps the name as written.
#[test]
fn a_tensor_sweep_names_its_symbols_as_they_print() {
    let f = figure_of(
        "lectures/lecture-3-4/07-tilted-hoop.toml",
        "tensor-vs-alpha",
    );
    assert!(
        f.desc.to_text().contains("against α from 0 to π"),
        "{}",
        f.desc
    );
    assert!(f.desc.to_text().contains("9 values of α"), "{}", f.desc);
    assert!(!f.desc.to_text().contains("alpha"), "{}", f.desc);
    assert_eq!(f.title, "Tensor entries against α");
    assert_eq!(f.x_label, "α");
}

/// The sweep's caption sets each entry it names as a formula (I with xx below), never as
/// text with an underscore; the plain form the alt text and `<desc>` read keeps every entry.
#[test]
fn a_tensor_sweep_sets_its_entries_as_formulas() {
    use crate::model::prose::Piece;
    use crate::notation::Names;
    let f = figure_of(
        "lectures/lecture-3-4/07-tilted-hoop.toml",
        "tensor-vs-alpha",
    );
    let formulas: Vec<String> = f
        .desc
        .0
        .iter()
        .filter_map(|p| match p {
            Piece::Math(m) => Some(m.to_latex(Names::none())),
            Piece::Text(_) => None,
        })
        .collect();
    // Tilted about y, the hoop mixes x and z: I_xz varies with the diagonal; I_xy and I_yz
    // stay zero.
    assert_eq!(
        formulas,
        ["I_{xx}", "I_{yy}", "I_{zz}", "I_{xz}", "I_{xy}", "I_{yz}"],
        "{}",
        f.desc
    );
    assert!(
        f.desc
            .0
            .iter()
            .all(|p| !matches!(p, Piece::Text(t) if t.contains('_'))),
        "{:?}",
        f.desc
    );
    let plain = f.desc.to_plain(Names::none());
    assert!(plain.contains("; I_xy, I_yz stay zero. Dots:"), "{plain}");
}
