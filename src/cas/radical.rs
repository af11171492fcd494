//! Square roots with their square factors taken out: √(3321 m² a⁴) = 9√41 m a². A pure rewrite
//! of our own tree, no engine call. An odd power of a symbol leaves the root only when the
//! caller knows the symbol is positive (a mass or a length), since √(x²) = |x| in general.

use super::expr::Expr;
use super::rational::Rational;

/// Takes every square factor out of every square root in `e`: rational squares always, and
/// even powers of the symbols for which `positive` holds.
pub fn pull_squares(e: &Expr, positive: &dyn Fn(&str) -> bool) -> Expr {
    let walk = |x: &Expr| pull_squares(x, positive);
    match e {
        Expr::Pow(base, exp) if **exp == Expr::rat(1, 2) => root_of(&walk(base), positive),
        Expr::Call(name, args) if name == "sqrt" && args.len() == 1 => {
            root_of(&walk(&args[0]), positive)
        }
        Expr::Add(terms) => Expr::add(terms.iter().map(walk).collect()),
        Expr::Mul(factors) => Expr::mul(factors.iter().map(walk).collect()),
        Expr::Pow(base, exp) => Expr::pow(walk(base), walk(exp)),
        Expr::Call(name, args) => Expr::Call(name.clone(), args.iter().map(walk).collect()),
        other => other.clone(),
    }
}

/// √`base` as (what leaves the root) · √(what stays).
fn root_of(base: &Expr, positive: &dyn Fn(&str) -> bool) -> Expr {
    let mut factors = Vec::new();
    flatten(base, &mut factors);
    // −(9/100)·(a − b) is (9/100)·(b − a): the sign goes into a sum, so the number leaves.
    let negative = factors
        .iter()
        .position(|f| matches!(f, Expr::Num(r) if r.is_negative()));
    let sum = factors.iter().position(|f| matches!(f, Expr::Add(_)));
    if let (Some(n), Some(k)) = (negative, sum) {
        if let Expr::Num(r) = &factors[n] {
            factors[n] = Expr::Num(r.negated());
        }
        if let Expr::Add(terms) = &factors[k] {
            factors[k] = Expr::add(terms.iter().cloned().map(Expr::negate).collect());
        }
    }
    let mut outside = Vec::new();
    let mut inside = Vec::new();
    for f in factors {
        match &f {
            Expr::Num(r) if !r.is_negative() => match square_part(r) {
                Some((out, rest)) => {
                    outside.push(Expr::Num(out));
                    inside.push(Expr::Num(rest));
                }
                None => inside.push(f),
            },
            Expr::Pow(b, k) if matches!(&**b, Expr::Sym(_)) => match (k.as_ref(), &**b) {
                (Expr::Num(n), Expr::Sym(s)) if n.is_integer() && n.to_i64().is_some() => {
                    // √(x^2j) = x^j needs x > 0 unless j is even: √(x⁴) = x² for every x.
                    let n = n.to_i64().unwrap_or(0);
                    let step = if positive(s) { 2 } else { 4 };
                    let q = n.div_euclid(step);
                    outside.push(Expr::pow(
                        (**b).clone(),
                        Expr::int(i128::from(q * step / 2)),
                    ));
                    inside.push(Expr::pow(
                        (**b).clone(),
                        Expr::int(i128::from(n - q * step)),
                    ));
                }
                _ => inside.push(f),
            },
            // √(b^2j) = b^j for a b that is positive wherever the symbols are (a sum of
            // positive terms such as R² + 4h²), or for any b when j is even.
            Expr::Pow(b, k) => match k.as_ref() {
                Expr::Num(n)
                    if n.is_integer()
                        && n.to_i64().is_some_and(|n| n % 2 == 0)
                        && (n.to_i64().is_some_and(|n| n % 4 == 0) || is_positive(b, positive)) =>
                {
                    let n = n.to_i64().unwrap_or(0);
                    outside.push(Expr::pow((**b).clone(), Expr::int(i128::from(n / 2))));
                }
                _ => inside.push(f),
            },
            _ => inside.push(f),
        }
    }
    let inside = Expr::mul(inside);
    if !inside.is_one() {
        outside.push(Expr::pow(inside, Expr::rat(1, 2)));
    }
    Expr::mul(outside)
}

/// Whether `e` is positive wherever the symbols for which `positive` holds are: built from
/// positive numbers and those symbols by sums, products and powers.
pub(super) fn is_positive(e: &Expr, positive: &dyn Fn(&str) -> bool) -> bool {
    match e {
        Expr::Num(r) => !r.is_negative() && !r.is_zero(),
        Expr::Sym(s) => positive(s),
        Expr::Add(xs) | Expr::Mul(xs) => xs.iter().all(|x| is_positive(x, positive)),
        Expr::Pow(b, k) => matches!(k.as_ref(), Expr::Num(_)) && is_positive(b, positive),
        _ => false,
    }
}

/// The factors of a product, with integer powers of products distributed: 3/(m²a⁴) is
/// 3 · m⁻² · a⁻⁴.
fn flatten(e: &Expr, out: &mut Vec<Expr>) {
    match e {
        Expr::Mul(fs) => fs.iter().for_each(|f| flatten(f, out)),
        Expr::Pow(b, k) if matches!(&**k, Expr::Num(n) if n.is_integer()) => match &**b {
            Expr::Mul(fs) => fs
                .iter()
                .for_each(|f| flatten(&Expr::pow(f.clone(), (**k).clone()), out)),
            Expr::Num(r) if k.as_ref() == &Expr::int(-1) => {
                out.push(Expr::Num(r.recip().unwrap_or_else(|| r.clone())))
            }
            _ => out.push(e.clone()),
        },
        other => out.push(other.clone()),
    }
}

/// r = out² · rest with rest square-free (as far as trial division by primes below 10⁴ sees),
/// for numerators and denominators that fit an i64; `None` when nothing comes out.
fn square_part(r: &Rational) -> Option<(Rational, Rational)> {
    let (num, den) = r.to_i64_pair()?;
    // √(n/d) = √(n d)/d: one integer to split.
    let n = i128::from(num).checked_mul(i128::from(den))?;
    let (out, rest) = split_integer(n);
    if out == 1 && den == 1 {
        return None;
    }
    Some((Rational::new(out, i128::from(den))?, Rational::int(rest)))
}

/// n = out² · rest.
fn split_integer(mut n: i128) -> (i128, i128) {
    let mut out = 1;
    let mut p = 2;
    while p < 10_000 && p * p <= n {
        while n % (p * p) == 0 {
            n /= p * p;
            out *= p;
        }
        p += 1;
    }
    let s = isqrt(n);
    if s * s == n {
        return (out * s, 1);
    }
    (out, n)
}

fn isqrt(n: i128) -> i128 {
    let mut s = (n as f64).sqrt() as i128;
    while s * s > n {
        s -= 1;
    }
    while (s + 1) * (s + 1) <= n {
        s += 1;
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cas::parse;

    fn pulled(s: &str) -> Expr {
        pull_squares(&parse(s).unwrap().expr, &|x| x == "m" || x == "a")
    }

    fn value(e: &Expr) -> f64 {
        e.eval(&|s| match s {
            "m" => Some(1.7),
            "a" => Some(0.3),
            "t" => Some(-0.4),
            _ => None,
        })
        .unwrap()
    }

    #[test]
    fn square_factors_leave_the_root_and_the_value_stays() {
        // The expected forms as the printer writes them; each is also checked by value.
        for (input, expected) in [
            ("(3321*m^2*a^4)^(1/2)/72", "1/8*m*a^2*41^(1/2)"),
            ("sqrt(12)", "2*3^(1/2)"),
            ("sqrt(1/8)", "1/4*2^(1/2)"),
            ("sqrt(49/4*m^3)", "7/2*m*m^(1/2)"),
            ("sqrt(3/(m^2*a^4))", "3^(1/2)/(m*a^2)"),
        ] {
            let got = pulled(input);
            assert_eq!(got.to_text(), expected, "{input}");
            let before = value(&parse(input).unwrap().expr);
            assert!(
                (value(&got) - before).abs() < 1e-12 * before,
                "{input}: the value changed"
            );
        }
    }

    #[test]
    fn a_symbol_of_unknown_sign_stays_inside() {
        // √(t²) is |t|, not t: t = −0.4 here. √(t⁴) is t² for every t.
        let e = pulled("sqrt(t^2)");
        assert!((value(&e) - 0.4).abs() < 1e-15, "{e}");
        let e = pulled("sqrt(t^6)");
        assert!((value(&e) - 0.4f64.powi(3)).abs() < 1e-15, "{e}");
        assert_eq!(pulled("sqrt(61*t^4)").to_text(), "t^2*61^(1/2)");
    }
}
