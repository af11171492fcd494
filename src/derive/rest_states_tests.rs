//! States of rest of several coordinates: coupled linear springs (one state, by Cramer's rule),
//! static equations that leave a coordinate free, coupled non-linear ones, and a rotating
//! frame whose Coriolis terms K alone cannot judge; roots real for no values set aside.

use super::DeriveError;
use super::rest_states::{rest_stability, rest_states};
use crate::cas::parse;
use crate::derive::step_result::Stable;

fn eqs(list: &[(&str, &str)]) -> Vec<(String, crate::cas::Expr)> {
    list.iter()
        .map(|(q, e)| (q.to_string(), parse(e).unwrap().expr))
        .collect()
}

fn message(r: Result<impl std::fmt::Debug, DeriveError>) -> String {
    match r {
        Err(DeriveError::NotDerivable(m)) => m,
        other => panic!("{other:?}"),
    }
}

/// Two masses between three springs, the middle one pulled by a force F: the static
/// equations couple x and y linearly; the one state is x = 2F/(3k), y = F/(3k) (by hand), and
/// stable, K = [[2k, −k], [−k, 2k]] having minors 2k and 3k².
#[test]
fn coupled_springs_have_one_stable_state() {
    let e = eqs(&[
        ("x", "m*x'' + 2*k*x - k*y - F"),
        ("y", "m*y'' + 2*k*y - k*x"),
    ]);
    let found = rest_states(&e).unwrap();
    let (coordinates, states) = (found.coordinates, found.states);
    assert_eq!(states.len(), 1);
    let at = |ex: &crate::cas::Expr| {
        ex.eval(&|s| match s {
            "F" => Some(3.0),
            "k" => Some(2.0),
            "m" => Some(1.0),
            _ => None,
        })
        .unwrap()
    };
    assert!((at(&states[0][0].value) - 1.0).abs() < 1e-15);
    assert!((at(&states[0][1].value) - 0.5).abs() < 1e-15);
    let cases = rest_stability(&e, &coordinates, &states).unwrap();
    assert_eq!(cases[0].verdict, Stable::Always);
    assert!((at(&cases[0].minors[1]) - 12.0).abs() < 1e-14);
}

/// A coordinate that no static equation fixes is a continuum; coupled non-linear equations
/// have no closed form here; a rotating frame's Coriolis terms refuse the stiffness test.
#[test]
fn what_equilibria_of_several_coordinates_refuses() {
    let free = eqs(&[("x", "m*x'' + k*x"), ("y", "m*y''")]);
    assert!(message(rest_states(&free)).contains("leave `y` free"));
    let coupled = eqs(&[("x", "m*x'' + k*sin(x + y)"), ("y", "m*y'' + k*sin(x - y)")]);
    assert!(message(rest_states(&coupled)).contains("not linear in them"));
    // m(x'' − 2Ωy' − Ω²x) + kx = 0 and m(y'' + 2Ωx' − Ω²y) + ky = 0.
    let rotating = eqs(&[
        ("x", "m*x'' - 2*m*W*y' - m*W^2*x + k*x"),
        ("y", "m*y'' + 2*m*W*x' - m*W^2*y + k*y"),
    ]);
    let found = rest_states(&rotating).unwrap();
    let (coordinates, states) = (found.coordinates, found.states);
    assert!(message(rest_stability(&rotating, &coordinates, &states)).contains("gyroscopic"));
}

/// A radial equation k r (r² + r₀²) = 0 beside a spring in z: r = 0 is the one state of rest
/// (with z = h); r = ±√(−r₀²) are real for no positive r₀, set aside and named, not states.
/// With only such roots there is no equilibrium, and the error says why.
#[test]
fn roots_real_for_no_values_are_set_aside() {
    let e = eqs(&[
        ("r", "m*r'' + k*r^3 + k*r0^2*r"),
        ("z", "m*z'' + c*(z - h)"),
    ]);
    let found = rest_states(&e).unwrap();
    assert_eq!(found.states.len(), 1, "{found:?}");
    assert!(found.states[0][0].value.is_zero());
    assert_eq!(found.states[0][1].value, parse("h").unwrap().expr);
    assert_eq!(found.excluded.len(), 2, "{found:?}");
    assert!(found.excluded.iter().all(|(q, _)| q == "r"));
    let none = eqs(&[("r", "m*r'' + k*r^2 + k*r0^2"), ("z", "m*z'' + c*(z - h)")]);
    let m = message(rest_states(&none));
    crate::base::assert_says(&m, &["no common real solution", "real for no values"]);
}
