//! Numerical stability at the edges of parameter space (issue 5, part 3). Each test asserts an
//! error bound: exact quadrature rules stay within a few ulps of the exact tensor at any tilt and
//! any scale, and the free-body solution is scale-invariant and continuous in its moments.

use crate::numeric::free_body::{ExactSolution, Moments};
use crate::numeric::integrators::{Method, Resolution, integrate};
use crate::pipeline::{SceneReport, run_scene};
use crate::scene::Scene;
use nalgebra::Vector3;
use std::path::Path;

/// Exact (Gauss–Legendre, periodic trapezoid) quadrature against the exact tensor, relative to
/// its largest entry: the bound the foundation issue sets, `verify::EXACT_VS_NUMERIC`.
const EXACT_RULES: f64 = crate::verify::EXACT_VS_NUMERIC;

fn scene(text: &str) -> SceneReport {
    let s = Scene::parse(text, Path::new("extreme.toml")).unwrap_or_else(|e| panic!("{e}"));
    run_scene(s).unwrap()
}

fn tensor_error(r: &SceneReport) -> f64 {
    r.verification
        .quantities
        .iter()
        .find(|q| q.name == "inertia_tensor")
        .expect("the numeric check ran")
        .error
}

#[test]
fn tilted_hoop_at_the_edges_of_the_tilt() {
    let half = std::f64::consts::FRAC_PI_2;
    for alpha in [
        0.0,
        1e-12,
        half - 1e-12,
        half,
        half + 1e-12,
        std::f64::consts::PI,
    ] {
        let r = scene(&format!(
            "id = \"tilt\"\ntitle = \"t\"\nnotes = {{ lecture = \"3/4\" }}\n\
             symbols = {{ M = \"m\", R = \"r\", alpha = \"tilt\" }}\n\
             [[body]]\nkind = \"hoop\"\nradius = \"R\"\nmass = \"M\"\n\
             rotate = [{{ axis = \"y\", angle = \"alpha\" }}]\n\
             [outputs]\nwant = [\"inertia_tensor\", \"principal_axes\", \"numeric\"]\n\
             [numeric]\nvalues = {{ M = 1.0, R = 1.0, alpha = {alpha:e} }}\n"
        ));
        assert!(
            tensor_error(&r) <= EXACT_RULES,
            "alpha {alpha:e}: {}",
            tensor_error(&r)
        );
        let eig = r.verification.eigen.as_ref().expect("eigen check ran");
        eprintln!(
            "tilt {alpha:e}: tensor {:e}, moments {:e}, axis {:e}",
            tensor_error(&r),
            eig.value_error,
            eig.axis_error
        );
        assert!(
            eig.value_error <= EXACT_RULES,
            "alpha {alpha:e}: {}",
            eig.value_error
        );
        // Moments (1, 1/2, 1/2) M R²: the axis of the single moment is the hoop's normal, which
        // SymmetricEigen must find to round-off however close the tilt is to a special angle.
        assert!(
            eig.axis_error <= 1e-14,
            "alpha {alpha:e}: {}",
            eig.axis_error
        );
        assert!(r.passed(), "alpha {alpha:e}");
    }
}

#[test]
fn tiny_and_huge_bodies_keep_their_relative_accuracy() {
    for (m, a) in [(1e-30, 1e-9), (1e-30, 1e9), (1e30, 1e-9), (1e30, 1e9)] {
        let r = scene(&format!(
            "id = \"scale\"\ntitle = \"t\"\nnotes = {{ lecture = \"3/4\" }}\n\
             symbols = {{ m = \"mass\", a = \"side\" }}\n\
             [[body]]\nkind = \"box\"\nsize = [\"a\", \"2*a\", \"3*a\"]\nmass = \"m\"\n\
             origin = \"corner\"\n\
             [outputs]\nwant = [\"inertia_tensor\", \"principal_axes\", \"parallel_axis\", \"numeric\"]\n\
             [numeric]\nvalues = {{ m = {m:e}, a = {a:e} }}\n"
        ));
        eprintln!("m {m:e} a {a:e}: tensor {:e}", tensor_error(&r));
        assert!(
            tensor_error(&r) <= EXACT_RULES,
            "m {m:e} a {a:e}: {}",
            tensor_error(&r)
        );
        assert!(r.passed(), "m {m:e} a {a:e}: {:#?}", r.verification);
    }
}

#[test]
fn the_free_body_solution_is_scale_invariant_over_sixty_orders() {
    // Scaling every moment by s leaves Euler's equations unchanged; scaling ω by k and t by 1/k
    // maps solutions onto solutions. Neither may cost accuracy at s = 1e±30, k = 1e±9.
    let base = ExactSolution::new(
        &Moments::new([1.0, 2.0, 3.0]).unwrap(),
        Vector3::new(1.0, 0.1, 0.5),
    );
    let reference = base.omega(100.0);
    for s in [1e-30, 1e30] {
        for k in [1e-9, 1e9] {
            let body = Moments::new([s, 2.0 * s, 3.0 * s]).unwrap();
            let sol = ExactSolution::new(&body, Vector3::new(k, 0.1 * k, 0.5 * k));
            let w = sol.omega(100.0 / k) / k;
            let err = (w - reference).norm() / reference.norm();
            eprintln!("s {s:e} k {k:e}: {err:e}");
            assert!(err <= 1e-13, "s {s:e} k {k:e}: {err:e}");
        }
    }
}

#[test]
fn nearly_equal_moments_approach_the_symmetric_solution() {
    // A relative gap of 1e-12 between two moments: the elliptic solution (m → 0 or 1 − m → 0)
    // must stay within O(gap · ω t) of the closed-form symmetric one and of an integrator.
    let w0 = Vector3::new(0.3, 0.4, 1.0);
    for (nearly, exactly) in [
        ([1.0, 1.0 + 1e-12, 1.5], [1.0, 1.0, 1.5]),
        ([1.0, 1.5, 1.5 * (1.0 + 1e-12)], [1.0, 1.5, 1.5]),
    ] {
        let a = ExactSolution::new(&Moments::new(nearly).unwrap(), w0);
        let b = ExactSolution::new(&Moments::new(exactly).unwrap(), w0);
        let dp = integrate(
            &Moments::new(nearly).unwrap(),
            w0,
            20.0,
            Method::Dopri,
            Resolution::Tolerance(1e-13),
            0,
        )
        .unwrap();
        let (wa, wb) = (a.omega(20.0), b.omega(20.0));
        let to_symmetric = (wa - wb).norm() / wb.norm();
        let to_integrator = (wa - dp.omega).norm() / wb.norm();
        eprintln!("{nearly:?}: to symmetric {to_symmetric:e}, to Dopri {to_integrator:e}");
        assert!(to_symmetric <= 1e-10, "{nearly:?}: {to_symmetric:e}");
        assert!(to_integrator <= 1e-10, "{nearly:?}: {to_integrator:e}");
    }
}
