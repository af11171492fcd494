//! How much rounding an expression's evaluation in f64 can pick up, relative to its value: a
//! running error bound in units of the machine epsilon. A difference of close numbers (the
//! beat 2π/(ω₂ − ω₁) of two nearly equal frequencies) multiplies the rounding of its terms by
//! (|a| + |b|)/|a − b|, so a fixed tolerance of a few epsilons fails such a right answer.

use crate::cas::Expr;

/// The relative rounding error bound of `e` at `env`, in units of `f64::EPSILON`, with its
/// value; `None` where it does not evaluate. Each leaf is taken as rounded once, and each
/// operation adds one rounding.
pub fn relative_rounding(e: &Expr, env: &dyn Fn(&str) -> Option<f64>) -> Option<(f64, f64)> {
    let value = e.eval(env).ok()?;
    let bound = match e {
        Expr::Num(_) | Expr::Sym(_) => 1.0,
        Expr::Add(terms) => {
            let mut weighted = 0.0;
            for t in terms {
                let (v, r) = relative_rounding(t, env)?;
                weighted += v.abs() * r;
            }
            weighted / value.abs() + terms.len() as f64
        }
        Expr::Mul(factors) => {
            let mut sum = 0.0;
            for f in factors {
                sum += relative_rounding(f, env)?.1;
            }
            sum + factors.len() as f64
        }
        Expr::Pow(b, k) => {
            let (base, rb) = relative_rounding(b, env)?;
            let (power, rk) = relative_rounding(k, env)?;
            // d(b^k)/b^k = k db/b + k ln(b) dk/k.
            power.abs() * rb + (power * base.abs().ln()).abs() * rk + 1.0
        }
        Expr::Call(name, args) if args.len() == 1 => {
            let (x, r) = relative_rounding(&args[0], env)?;
            let gain = match name.as_str() {
                "sqrt" => 0.5,
                "sin" => (x * x.cos() / x.sin()).abs(),
                "cos" => (x * x.sin() / x.cos()).abs(),
                "tan" => (x / (x.sin() * x.cos())).abs(),
                "exp" => x.abs(),
                "ln" | "log" => 1.0 / x.ln().abs(),
                // asin, acos, atan and the rest: their derivative over their value.
                _ => {
                    let h = 1e-6 * x.abs().max(1e-6);
                    let at = |y: f64| {
                        Expr::Call(name.clone(), vec![Expr::Sym("x".into())])
                            .eval(&|s| (s == "x").then_some(y))
                            .ok()
                    };
                    let slope = (at(x + h)? - at(x - h)?) / (2.0 * h);
                    (slope * x / value).abs()
                }
            };
            gain * r + 1.0
        }
        _ => 1.0,
    };
    bound.is_finite().then_some((value, bound))
}

#[cfg(test)]
mod tests {
    use super::relative_rounding;
    use crate::cas::parse;

    fn bound(text: &str, vars: &[(&str, f64)]) -> f64 {
        let e = parse(text).unwrap().expr;
        relative_rounding(&e, &|s| vars.iter().find(|(n, _)| *n == s).map(|(_, v)| *v))
            .unwrap()
            .1
    }

    #[test]
    fn a_difference_of_close_numbers_amplifies_rounding() {
        let far = bound("2*pi/(a - b)", &[("a", 2.0), ("b", 1.0)]);
        let near = bound("2*pi/(a - b)", &[("a", 1.0 + 1e-3), ("b", 1.0)]);
        // A few roundings per operation where nothing cancels; (|a| + |b|)/|a − b| ≈ 2000
        // times the terms' roundings where a and b agree to three digits.
        assert!(far < 20.0, "{far}");
        assert!(near > 2000.0 && near / far > 200.0, "{near} against {far}");
        // And the bound holds: the rounding actually made is within it.
        let (a, b) = (1.0 + 1e-13_f64, 1.0_f64);
        let computed = 1.0 / (a - b);
        let exact = 1.0 / 1e-13;
        let error = (computed - exact).abs() / exact / f64::EPSILON;
        assert!(
            error <= bound("1/(a - b)", &[("a", a), ("b", b)]),
            "{error}"
        );
    }
}
