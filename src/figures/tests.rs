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
    assert!(fig.desc.contains("midpoint-lattice") && fig.desc.contains("slope -0.6"));
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
