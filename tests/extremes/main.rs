//! Numerical stability at the edges of parameter space. The runs of a million steps or more
//! are `#[ignore]`d: `cargo test --release --test extremes -- --ignored` runs them. Each test asserts an
//! error bound: exact quadrature rules stay within a few ulps of the exact tensor at any tilt and
//! any scale, and the free-body solution is scale-invariant and continuous in its moments.

use mechbook::model::catalogue::quantity;
use mechbook::model::moments::Moments;
use mechbook::numeric::free_body::ExactSolution;
use mechbook::numeric::integrators::{Method, Resolution, integrate};
use mechbook::pipeline::{SceneReport, run_scene};
use mechbook::scene::Scene;
use nalgebra::Vector3;
use std::path::Path;

/// Exact (Gauss–Legendre, periodic trapezoid) quadrature against the exact tensor, relative to
/// its largest entry: the bound the foundation issue sets, `verify::EXACT_VS_NUMERIC`.
const EXACT_RULES: f64 = mechbook::verify::EXACT_VS_NUMERIC;

fn scene(text: &str) -> SceneReport {
    let s = Scene::parse(text, Path::new("extreme.toml")).unwrap_or_else(|e| panic!("{e}"));
    run_scene(s, None).unwrap()
}

fn tensor_error(r: &SceneReport) -> f64 {
    r.verification
        .quantities
        .iter()
        .find(|q| q.name == quantity::INERTIA_TENSOR)
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
        assert!(r.verification.verified(), "alpha {alpha:e}");
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
        assert!(
            r.verification.verified(),
            "m {m:e} a {a:e}: {:#?}",
            r.verification
        );
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
fn far_beyond_overflow_every_route_works_in_its_own_units() {
    // I ω² at I = 1e300, ω = 1e200 is 1e700: without nondimensionalizing it overflows to inf and
    // the integrators return NaN. Each route must give the unit body's answer, scaled.
    let unit = Moments::new([1.0, 2.0, 3.0]).unwrap();
    let w0 = Vector3::new(1.0, 0.1, 0.5);
    let reference = ExactSolution::new(&unit, w0).omega(20.0);
    for (c, k) in [
        (1e300, 1e200),
        (1e-300, 1e-200),
        (1e300, 1e-200),
        (1e-300, 1e200),
    ] {
        let body = Moments::new([c, 2.0 * c, 3.0 * c]).unwrap();
        let exact = ExactSolution::new(&body, w0 * k).omega(20.0 / k) / k;
        let err = (exact - reference).norm() / reference.norm();
        assert!(err <= 1e-13, "exact at c {c:e} k {k:e}: {err:e}");
        for (m, r) in [
            (Method::Rk4, Resolution::Step(0.01 / k)),
            (Method::Dopri, Resolution::Tolerance(1e-12)),
            (Method::Splitting4, Resolution::Step(0.01 / k)),
        ] {
            let run = integrate(&body, w0 * k, 20.0 / k, m, r, 0).unwrap();
            let err = (run.omega / k - reference).norm() / reference.norm();
            assert!(err <= 1e-8, "{m:?} at c {c:e} k {k:e}: {err:e}");
            assert!(run.energy_drift.is_finite() && run.energy_drift <= 1e-8);
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

// 10⁶ RK4 steps: `cargo test --release --test extremes -- --ignored`.
#[test]
#[ignore]
fn earth_small_beta_over_ten_thousand_days() {
    // β = 3.3e-3: the wobble turns at βω3 ≈ 0.021 rad per day while ω3 = 2π per day. RK4 with
    // h = 0.01 day over 10⁴ rotation periods (10⁶ steps) against the closed form, measured on
    // the wobble itself (1e-6 of ω), where a loss of precision in I3 − I1 would show first.
    let beta =
        mechbook::figures::polar_motion::EARTH_H / (1.0 - mechbook::figures::polar_motion::EARTH_H);
    let body = Moments::new([1.0, 1.0, 1.0 + beta]).unwrap();
    let w0 = Vector3::new(1e-6, 0.0, 2.0 * std::f64::consts::PI);
    let t = 1e4;
    let exact = ExactSolution::new(&body, w0).omega(t);
    let run = integrate(&body, w0, t, Method::Rk4, Resolution::Step(0.01), 0).unwrap();
    let wobble_error = (run.omega.xy() - exact.xy()).norm() / 1e-6;
    eprintln!(
        "Earth, 1e4 days, RK4 h = 0.01: wobble error {wobble_error:e}, energy drift {:e}",
        run.energy_drift
    );
    // A million steps of round-off, each ~1e-16 of the wobble, adding up like a random walk:
    // about √N ε = 1e-13. β computed with cancellation (1e-13 relative) would shift the phase by
    // βω3 t · 1e-13 ≈ 2e-11 and fail this bound.
    assert!(wobble_error <= 1e-12, "{wobble_error:e}");
    assert!(run.energy_drift <= 1e-12, "{:e}", run.energy_drift);
}

// 6.3·10⁶ RK4 steps: `cargo test --release --test extremes -- --ignored`.
#[test]
#[ignore]
fn earth_small_beta_over_ten_thousand_euler_periods() {
    // 10⁴ Euler periods of 1/β ≈ 304 days: 3.0e6 days, 6.3e4 rad of wobble phase. RK4 at
    // Ωh = 0.01 (h ≈ 0.48 day, 6.3e6 steps) has a phase error of about N (Ωh)⁵/120 = 5e-6
    // over the run; the attitude is not needed (it would need steps 300× smaller).
    let beta =
        mechbook::figures::polar_motion::EARTH_H / (1.0 - mechbook::figures::polar_motion::EARTH_H);
    let body = Moments::new([1.0, 1.0, 1.0 + beta]).unwrap();
    let w3 = 2.0 * std::f64::consts::PI;
    let w0 = Vector3::new(1e-6, 0.0, w3);
    let rate = beta * w3;
    let t = 1e4 * 2.0 * std::f64::consts::PI / rate;
    let h = 0.01 / rate;
    let exact = ExactSolution::new(&body, w0).omega(t);
    // The closed form by hand, as a second route at this large a phase.
    let by_hand = Vector3::new(1e-6 * (rate * t).cos(), 1e-6 * (rate * t).sin(), w3);
    let routes = (exact.xy() - by_hand.xy()).norm() / 1e-6;
    let run = integrate(&body, w0, t, Method::Rk4, Resolution::Step(h), 0).unwrap();
    let wobble_error = (run.omega.xy() - exact.xy()).norm() / 1e-6;
    eprintln!(
        "Earth, 1e4 Euler periods ({} steps): RK4 wobble error {wobble_error:e}, exact vs closed \
         form {routes:e}, energy drift {:e}",
        run.steps, run.energy_drift
    );
    assert!(run.steps > 6_000_000);
    // The body is given as (1, 1, 1 + β): rounding 1 + β changes β by up to 1.1e-16/β = 3.4e-14
    // of itself, which over 6.3e4 rad of phase is 2.1e-9. The routes agree to that, no worse.
    assert!(routes <= 2.2e-9, "{routes:e}");
    assert!(wobble_error <= 2e-5, "{wobble_error:e}");
    assert!(
        (run.omega.z - w3).abs() <= 1e-12 * w3,
        "ω3 must stay constant"
    );
}

mod properties {
    use super::*;
    use proptest::prelude::*;
    use proptest::test_runner::{Config, RngSeed};

    fn config() -> Config {
        // A fixed seed: CI sees the same cases every run.
        Config {
            cases: 200,
            rng_seed: RngSeed::Fixed(0x3_09),
            failure_persistence: None,
            ..Config::default()
        }
    }

    /// Moments that a body can have: positive, each at most the sum of the other two.
    fn moments() -> impl Strategy<Value = [f64; 3]> {
        (0.1f64..10.0, 0.1f64..10.0, 0.0f64..1.0)
            .prop_map(|(a, b, u)| [a, b, (a - b).abs() + u * (a + b - (a - b).abs())])
            .prop_filter("strict triangle", |i| Moments::new(*i).is_ok())
    }

    proptest! {
        #![proptest_config(config())]

        /// For any body and any ω(0), the exact solution keeps 2T and |L| to round-off at any
        /// time, and satisfies Euler's equations by a difference quotient.
        #[test]
        fn the_exact_solution_keeps_its_invariants(
            i in moments(),
            w in prop::array::uniform3(-3.0f64..3.0),
            t in 0.0f64..200.0,
        ) {
            let w0 = Vector3::from(w);
            prop_assume!(w0.norm() > 1e-3);
            let body = Moments::new(i).unwrap();
            let sol = ExactSolution::new(&body, w0);
            let (t0, l0) = mechbook::numeric::free_body::invariants(&body, &w0);
            let wt = sol.omega(t);
            let (tt, lt) = mechbook::numeric::free_body::invariants(&body, &wt);
            prop_assert!((tt - t0).abs() <= 1e-12 * t0, "2T {} vs {}", tt, t0);
            prop_assert!((lt - l0).abs() <= 1e-12 * l0, "|L| {} vs {}", lt, l0);
            let h = 1e-5;
            let derivative = (sol.omega(t + h) - sol.omega(t - h)) / (2.0 * h);
            let rhs = mechbook::numeric::free_body::euler_rhs(&body, &wt);
            prop_assert!(
                (derivative - rhs).norm() <= 1e-6 * (1.0 + rhs.norm()) * w0.norm().max(1.0).powi(2),
                "dω/dt {:?} vs {:?}", derivative, rhs
            );
        }
    }
}
