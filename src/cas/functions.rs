//! The elementary functions an expression may call, in one table: each one's number of
//! arguments, derivative and value. The parser, the engine, the evaluators and the checks of
//! units all read it, so that a function known to one stage is known to all.
//!
//! `tan x` and `tanh x` are read as `sin x / cos x` and `sinh x / cosh x` (see `parse`), `ln` as
//! `log`: every later stage sees only these.

use super::expr::Expr;

/// The scalar functions the engine and the evaluators understand.
pub const SCALAR_FUNCTIONS: &[&str] = &[
    "sin", "cos", "sqrt", "exp", "log", "asin", "acos", "atan", "atan2", "sinh", "cosh", "abs",
];

/// The number of arguments of elementary function `name`; `None` for any other name.
pub fn arity(name: &str) -> Option<usize> {
    match name {
        "atan2" => Some(2),
        n if SCALAR_FUNCTIONS.contains(&n) => Some(1),
        _ => None,
    }
}

/// The function's name as a textbook sets it: arcsin, arccos, arctan, ln; the others as
/// written.
pub fn textbook_name(name: &str) -> &str {
    match name {
        "asin" => "arcsin",
        "acos" => "arccos",
        "atan" => "arctan",
        "log" => "ln",
        other => other,
    }
}

/// Whether the function takes only a pure number (an angle, a ratio) and gives one: `sqrt` and
/// `abs` keep their argument's unit, `atan2` takes two of one unit.
pub fn needs_dimensionless(name: &str) -> bool {
    matches!(
        name,
        "sin" | "cos" | "exp" | "log" | "asin" | "acos" | "atan" | "sinh" | "cosh"
    )
}

/// The derivative of `name(args)` with respect to its `k`-th argument, by the textbook rules;
/// `None` for a name that is not elementary. The chain rule is the caller's.
pub fn partial(name: &str, args: &[Expr], k: usize) -> Option<Expr> {
    let u = args.first()?.clone();
    let square = |e: Expr| Expr::pow(e, Expr::int(2));
    let one_minus_square_root =
        |u: Expr| Expr::pow(Expr::minus(Expr::int(1), square(u)), Expr::rat(1, 2));
    Some(match (name, k) {
        ("sin", 0) => Expr::call("cos", u),
        ("cos", 0) => Expr::negate(Expr::call("sin", u)),
        ("sqrt", 0) => Expr::over(
            Expr::int(1),
            Expr::mul(vec![Expr::int(2), Expr::call("sqrt", u)]),
        ),
        ("exp", 0) => Expr::call("exp", u),
        ("log", 0) => Expr::over(Expr::int(1), u),
        // d asin u = du/√(1 − u²), d acos u = −du/√(1 − u²).
        ("asin", 0) => Expr::over(Expr::int(1), one_minus_square_root(u)),
        ("acos", 0) => Expr::over(Expr::int(-1), one_minus_square_root(u)),
        ("atan", 0) => Expr::over(Expr::int(1), Expr::add(vec![Expr::int(1), square(u)])),
        ("sinh", 0) => Expr::call("cosh", u),
        ("cosh", 0) => Expr::call("sinh", u),
        // d|u| = u/|u| du, away from u = 0.
        ("abs", 0) => Expr::over(u.clone(), Expr::call("abs", u)),
        // atan2(y, x), the angle of the point (x, y): ∂/∂y = x/(x² + y²), ∂/∂x = −y/(x² + y²).
        ("atan2", 0 | 1) => {
            let x = args.get(1)?.clone();
            let r2 = Expr::add(vec![square(x.clone()), square(u.clone())]);
            if k == 0 {
                Expr::over(x, r2)
            } else {
                Expr::over(Expr::negate(u), r2)
            }
        }
        _ => return None,
    })
}

/// The value of `name` at `args`; `None` for a name that is not elementary or a wrong number of
/// arguments. Outside a function's real domain the value is NaN, as f64's own.
pub fn value(name: &str, args: &[f64]) -> Option<f64> {
    Some(match (name, args) {
        ("sin", [x]) => x.sin(),
        ("cos", [x]) => x.cos(),
        ("sqrt", [x]) => x.sqrt(),
        ("exp", [x]) => x.exp(),
        ("log", [x]) => x.ln(),
        ("asin", [x]) => x.asin(),
        ("acos", [x]) => x.acos(),
        ("atan", [x]) => x.atan(),
        ("atan2", [y, x]) => y.atan2(*x),
        ("sinh", [x]) => x.sinh(),
        ("cosh", [x]) => x.cosh(),
        ("abs", [x]) => x.abs(),
        _ => return None,
    })
}

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
    use super::*;

    /// Each derivative against a central difference of the function's value, at points inside
    /// every domain: an independent route, which a wrong sign or factor fails.
    #[test]
    fn each_derivative_is_the_slope_of_its_value() {
        let at = |e: &Expr, x: f64, y: f64| {
            e.eval(&|s| match s {
                "x" => Some(x),
                "y" => Some(y),
                _ => None,
            })
            .unwrap()
        };
        for &name in SCALAR_FUNCTIONS {
            let n = arity(name).unwrap();
            let args: Vec<Expr> = ["x", "y"][..n].iter().map(|s| Expr::sym(s)).collect();
            for (x, y) in [(0.3, 0.7), (0.55, -0.4), (0.8, 1.9)] {
                for k in 0..n {
                    let d = partial(name, &args, k).unwrap();
                    let h = 1e-6;
                    let shift = |s: f64| {
                        let mut p = [x, y];
                        p[k] += s;
                        value(name, &p[..n]).unwrap()
                    };
                    let slope = (shift(h) - shift(-h)) / (2.0 * h);
                    let exact = at(&d, x, y);
                    assert!(
                        (slope - exact).abs() < 1e-7 * exact.abs().max(1.0),
                        "d{name}/d(arg {k}) at ({x}, {y}): {exact} by the rule, {slope} by the slope"
                    );
                }
            }
        }
    }

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
