//! The values of the elementary functions a textbook knows exactly, and an inverse under its
//! own function undone: the engine holds these functions opaque (`atoms.rs`), so these are put
//! in before it sees them.

use super::expr::Expr;

/// `name(args)` with an inverse applied to its own function undone, where that holds for every
/// real argument the inner function takes: sin(asin u) = u, cos(acos u) = u,
/// cos(asin u) = sin(acos u) = √(1 − u²), exp(log u) = u, log(exp u) = u. `None` when there is
/// nothing to undo.
pub fn undo_inverse(name: &str, args: &[Expr]) -> Option<Expr> {
    let [Expr::Call(inner, inner_args)] = args else {
        return None;
    };
    let [u] = inner_args.as_slice() else {
        return None;
    };
    let root = || {
        Expr::pow(
            Expr::minus(Expr::int(1), Expr::pow(u.clone(), Expr::int(2))),
            Expr::rat(1, 2),
        )
    };
    Some(match (name, inner.as_str()) {
        ("sin", "asin") | ("cos", "acos") | ("exp", "log") | ("log", "exp") => u.clone(),
        ("cos", "asin") | ("sin", "acos") => root(),
        _ => return None,
    })
}

/// The exact value of `name(args)` at the numbers where a textbook knows it: exp 0 = 1,
/// log 1 = 0, asin 0 = atan 0 = sinh 0 = acos 1 = 0, cosh 0 = 1, the absolute value of a
/// number, and atan2(0, x) = 0 for x > 0. The engine holds these functions opaque, so a series
/// about 0 would keep exp(0) without it.
pub fn exact_at(name: &str, args: &[Expr]) -> Option<Expr> {
    let number = |k: usize| match args.get(k) {
        Some(Expr::Num(r)) => Some(r.clone()),
        _ => None,
    };
    let x = number(0)?;
    let zero = x.is_zero();
    let one = x == super::rational::Rational::ONE;
    if let Some(angle) = inverse_at(name, &x) {
        return Some(angle);
    }
    Some(match name {
        "exp" | "cosh" if zero => Expr::int(1),
        "log" | "acos" if one => Expr::int(0),
        "asin" | "atan" | "sinh" if zero => Expr::int(0),
        "abs" => Expr::Num(x.abs()),
        "atan2" if zero && number(1).is_some_and(|r| r.is_positive()) => Expr::int(0),
        _ => return None,
    })
}

/// asin, acos and atan at 0, ±1/2 and ±1 (atan at ±1 only): multiples of π/6 and π/4.
fn inverse_at(name: &str, x: &super::rational::Rational) -> Option<Expr> {
    let sixths = |k: i128| Expr::mul(vec![Expr::rat(k, 6), Expr::sym("pi")]);
    let halves = [
        (Expr::rat(-1, 1), -3),
        (Expr::rat(-1, 2), -1),
        (Expr::int(0), 0),
        (Expr::rat(1, 2), 1),
        (Expr::int(1), 3),
    ];
    let (_, k) = halves
        .iter()
        .find(|(v, _)| matches!(v, Expr::Num(r) if r == x))?;
    Some(match name {
        "asin" => sixths(*k),
        "acos" => sixths(3 - k),
        "atan" if k.abs() == 3 => Expr::mul(vec![Expr::rat(k.signum(), 4), Expr::sym("pi")]),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::super::functions::{SCALAR_FUNCTIONS, value};
    use super::*;

    /// Each exact value against the function's own value.
    #[test]
    fn exact_values_are_the_functions_values() {
        let mut checked = 0;
        for &name in SCALAR_FUNCTIONS {
            for x in [-1.0, -0.5, 0.0, 0.5, 1.0, 2.0, -3.0] {
                let arg = Expr::Num(super::super::rational::Rational::from_f64(x).unwrap());
                let args = if name == "atan2" {
                    vec![Expr::int(0), arg]
                } else {
                    vec![arg]
                };
                if let Some(exact) = exact_at(name, &args) {
                    let want = if name == "atan2" {
                        value(name, &[0.0, x])
                    } else {
                        value(name, &[x])
                    };
                    let got = exact.eval(&|_| None).unwrap();
                    assert!((got - want.unwrap()).abs() < 1e-15, "{name}({x}): {got}");
                    checked += 1;
                }
            }
        }
        assert!(checked >= 20, "{checked} exact values");
    }

    #[test]
    fn an_inverse_is_undone_only_under_its_own_function() {
        let x = Expr::sym("x");
        let asin = vec![Expr::call("asin", x.clone())];
        assert_eq!(undo_inverse("sin", &asin), Some(x.clone()));
        assert_eq!(
            undo_inverse("exp", &[Expr::call("log", x.clone())]),
            Some(x)
        );
        assert_eq!(
            undo_inverse("sin", &[Expr::call("acos", Expr::sym("x"))])
                .map(|e| e.eval(&|_| Some(0.6)).unwrap()),
            Some(0.8)
        );
        // asin(sin u) is u only for |u| ≤ π/2: left as written.
        assert_eq!(
            undo_inverse("asin", &[Expr::call("sin", Expr::sym("x"))]),
            None
        );
        assert_eq!(undo_inverse("cos", &asin[..0]), None);
    }
}
