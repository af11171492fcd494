use super::*;

fn case() -> (Moments, Vector3<f64>) {
    (
        Moments::new([1.0, 2.0, 3.0]).unwrap(),
        Vector3::new(1.0, 0.1, 0.5),
    )
}

fn error(run: &Run, exact: &Vector3<f64>) -> f64 {
    (run.omega - exact).norm() / exact.norm()
}

/// Halving the step divides the error by 2^order: the methods have their stated orders.
#[test]
fn time_steppers_converge_at_their_orders() {
    let (i, w0) = case();
    let exact = ExactSolution::new(&i, w0).omega(20.0);
    for (method, order) in [
        (Method::Rk4, 4.0),
        (Method::Splitting, 2.0),
        (Method::Splitting4, 4.0),
    ] {
        let e = |h: f64| {
            error(
                &integrate(&i, w0, 20.0, method, Resolution::Step(h), 0).unwrap(),
                &exact,
            )
        };
        let (a, b) = (e(0.02), e(0.01));
        let observed = (a / b).log2();
        assert!(
            (observed - order).abs() < 0.3,
            "{method:?}: order {observed} ({a:e}, {b:e})"
        );
    }
}

#[test]
fn dormand_prince_error_follows_its_tolerance() {
    let (i, w0) = case();
    let exact = ExactSolution::new(&i, w0).omega(100.0);
    let mut last = f64::INFINITY;
    for tol in [1e-6, 1e-9, 1e-12] {
        let r = integrate(&i, w0, 100.0, Method::Dopri, Resolution::Tolerance(tol), 0).unwrap();
        let e = error(&r, &exact);
        assert!(e < 1e4 * tol && e < last / 30.0, "tol {tol}: error {e}");
        last = e;
    }
}

#[test]
fn splitting_keeps_the_length_of_l_and_its_direction_in_space() {
    let (i, w0) = case();
    let r = integrate(&i, w0, 1000.0, Method::Splitting, Resolution::Step(0.05), 0).unwrap();
    assert!(r.momentum_drift < 1e-14, "{}", r.momentum_drift);
    assert!(r.space_momentum_drift < 1e-12, "{}", r.space_momentum_drift);
    // The energy is not conserved exactly, but stays bounded (no drift).
    assert!(
        r.energy_drift > 1e-8 && r.energy_drift < 1e-3,
        "{}",
        r.energy_drift
    );
    let q = r.attitude;
    assert!((q.transpose() * q - Matrix3::identity()).amax() < 1e-13);
}

#[test]
fn splitting_keeps_l_to_round_off_over_a_million_steps() {
    let (i, w0) = case();
    let r = integrate(
        &i,
        w0,
        1e6 * 0.025,
        Method::Splitting,
        Resolution::Step(0.025),
        0,
    )
    .unwrap();
    assert_eq!(r.steps, 1_000_000);
    assert!(r.momentum_drift <= 1e-14, "{}", r.momentum_drift);
    assert!(r.space_momentum_drift < 1e-11, "{}", r.space_momentum_drift);
}

#[test]
fn rk4_attitude_keeps_l_fixed_in_space() {
    let (i, w0) = case();
    let r = integrate(&i, w0, 50.0, Method::Rk4, Resolution::Step(0.01), 0).unwrap();
    assert!(r.space_momentum_drift < 1e-8, "{}", r.space_momentum_drift);
}

#[test]
fn bad_resolutions_are_errors() {
    let (i, w0) = case();
    let says = |e: IntegrationError, words: &str| {
        assert!(e.to_string().contains(words), "{e} (wanted {words:?})");
    };
    let e = |m, r| integrate(&i, w0, 1.0, m, r, 0).unwrap_err();
    for (m, r, words) in [
        (Method::Rk4, Resolution::Step(-0.1), "positive"),
        (Method::Rk4, Resolution::Step(f64::NAN), "positive"),
        (Method::Dopri, Resolution::Step(0.1), "--tol"),
        (Method::Dopri, Resolution::Tolerance(0.0), "between"),
        (Method::Dopri, Resolution::Tolerance(1e-300), "below"),
        (
            Method::Rk4,
            Resolution::Step(1e-300),
            "needs 1.000e300 steps",
        ),
    ] {
        says(e(m, r), words);
    }
    let long = |m, r| integrate(&i, w0, 1e300, m, r, 0).unwrap_err();
    for m in [Method::Rk4, Method::Splitting, Method::Splitting4] {
        says(long(m, Resolution::Step(0.01)), "more than the cap");
    }
    says(long(Method::Exact, Resolution::Step(1.0)), "2^52");
    says(long(Method::Dopri, Resolution::Tolerance(1e-9)), "2^52");
    let fast = |m, r| integrate(&i, w0 * 1e300, 1.0, m, r, 0).unwrap_err();
    says(fast(Method::Rk4, Resolution::Step(0.5)), "2^52");
    let capped = integrate_capped(
        &i,
        w0,
        500.0,
        Method::Dopri,
        Resolution::Tolerance(1e-9),
        0,
        1000,
    );
    assert!(
        capped
            .unwrap_err()
            .to_string()
            .contains("reached the cap of 1000 steps")
    );
    let refused = integrate_capped(
        &i,
        w0,
        1e6,
        Method::Dopri,
        Resolution::Tolerance(1e-9),
        0,
        1000,
    );
    assert!(
        refused
            .unwrap_err()
            .to_string()
            .contains("at least that many steps")
    );
    let e = integrate(
        &i,
        w0,
        f64::INFINITY,
        Method::Exact,
        Resolution::Step(0.1),
        0,
    )
    .unwrap_err();
    assert!(matches!(e, IntegrationError::EndTime { .. }), "{e:?}");
}
