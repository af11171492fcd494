//! (cos x + 1)(cos x − 1) as −sin²x in a product, and (sin x + 1)(sin x − 1) as −cos²x: the
//! engine factors 1 − cos²x over the rationals, which leaves a Routhian's p²/sin²θ printed as
//! p²/((cos θ + 1)(cos θ − 1)). A rewrite of our own tree, for the printed form only.

use super::expr::Expr;

/// A factor s·(f(x) + c) with s, c each ±1 and f sin or cos: (s, f, x, c).
fn unit_shift(e: &Expr) -> Option<(i64, &'static str, Expr, i64)> {
    let Expr::Add(terms) = e else {
        return None;
    };
    let [a, b] = terms.as_slice() else {
        return None;
    };
    let one = |t: &Expr| match t {
        Expr::Num(r) => match r.to_i64() {
            Some(k @ (1 | -1)) => Some(k),
            _ => None,
        },
        _ => None,
    };
    let call = |t: &Expr| -> Option<(i64, &'static str, Expr)> {
        let (sign, t) = match t {
            Expr::Mul(v) if v.len() == 2 && one(&v[0]) == Some(-1) => (-1, &v[1]),
            other => (1, other),
        };
        match t {
            Expr::Call(f, args) if args.len() == 1 => {
                let f = match f.as_str() {
                    "cos" => "cos",
                    "sin" => "sin",
                    _ => return None,
                };
                Some((sign, f, args[0].clone()))
            }
            _ => None,
        }
    };
    let ((s, f, x), c) = match (call(a), one(b), call(b), one(a)) {
        (Some(fx), Some(c), _, _) | (_, _, Some(fx), Some(c)) => (fx, c),
        _ => return None,
    };
    // s f + c = s (f + c/s).
    Some((s, f, x, c * s))
}

/// A factor as (base, integer exponent).
fn base_and_power(e: &Expr) -> (Expr, i64) {
    match e {
        Expr::Pow(b, k) => match k.as_ref() {
            Expr::Num(r) => match r.to_i64() {
                Some(k) => ((**b).clone(), k),
                None => (e.clone(), 1),
            },
            _ => (e.clone(), 1),
        },
        other => (other.clone(), 1),
    }
}

/// The product's factors with each pair (f x + 1)^a (f x − 1)^b (a, b of one sign) taken
/// down by k = ±min(|a|, |b|): the pair's k-th power is (−1)^k times the other function's
/// 2k-th, sin²x for cos.
pub(super) fn pythagorean_pairs(factors: Vec<Expr>) -> Vec<Expr> {
    // A product among the factors (a tidied denominator) taken in.
    let factors = match Expr::mul(factors) {
        Expr::Mul(v) => v,
        other => return vec![other],
    };
    let flat = split_powers(&factors, &|v: &[Expr]| {
        v.iter().any(|g| unit_shift(&base_and_power(g).0).is_some())
    });
    let paired = pair_up(flat.clone());
    let paired = if paired == flat { factors } else { paired };
    cancel_calls(paired)
}

/// Each integer power of a product whose factors pass `split` as the product of the powers:
/// 1/((c + 1)(c − 1)) as (c + 1)⁻¹(c − 1)⁻¹.
fn split_powers(factors: &[Expr], split: &dyn Fn(&[Expr]) -> bool) -> Vec<Expr> {
    factors
        .iter()
        .flat_map(|f| match f {
            Expr::Pow(b, k) if matches!(k.as_ref(), Expr::Num(r) if r.to_i64().is_some()) => {
                match b.as_ref() {
                    Expr::Mul(v) if split(v) => v
                        .iter()
                        .map(|g| Expr::pow(g.clone(), (**k).clone()))
                        .collect(),
                    _ => vec![f.clone()],
                }
            }
            _ => vec![f.clone()],
        })
        .collect()
}

/// sin θ beside 1/(m l² sin⁴θ) as 1/(m l² sin³θ): powers of one function of one argument, in
/// the product or in a power of a product beside it, taken together.
fn cancel_calls(factors: Vec<Expr>) -> Vec<Expr> {
    let call_of = |f: &Expr| {
        let (b, _) = base_and_power(f);
        matches!(b, Expr::Call(..)).then_some(b)
    };
    let outer: Vec<Expr> = factors.iter().filter_map(call_of).collect();
    let split = split_powers(&factors, &|v: &[Expr]| {
        v.iter().filter_map(call_of).any(|c| outer.contains(&c))
    });
    let mut powers: Vec<(Expr, i64)> = Vec::new();
    let mut rest = Vec::new();
    for f in &split {
        match call_of(f) {
            Some(c) => {
                let k = base_and_power(f).1;
                match powers.iter_mut().find(|(b, _)| *b == c) {
                    Some((_, total)) => *total += k,
                    None => powers.push((c, k)),
                }
            }
            None => rest.push(f.clone()),
        }
    }
    let calls = split.iter().filter(|f| call_of(f).is_some()).count();
    if calls == powers.len() {
        return factors;
    }
    rest.extend(
        powers
            .into_iter()
            .filter(|(_, k)| *k != 0)
            .map(|(b, k)| Expr::pow(b, Expr::int(k.into()))),
    );
    match Expr::mul(rest) {
        Expr::Mul(v) => v,
        other => vec![other],
    }
}

/// The pairs rewritten, until none is left.
fn pair_up(factors: Vec<Expr>) -> Vec<Expr> {
    let mut factors = factors;
    'again: loop {
        for i in 0..factors.len() {
            let (bi, ai) = base_and_power(&factors[i]);
            let Some((si, fi, xi, ci)) = unit_shift(&bi) else {
                continue;
            };
            for j in 0..factors.len() {
                let (bj, aj) = base_and_power(&factors[j]);
                let Some((sj, fj, xj, cj)) = unit_shift(&bj) else {
                    continue;
                };
                if i == j
                    || fi != fj
                    || xi != xj
                    || ci != 1
                    || cj != -1
                    || ai.signum() != aj.signum()
                {
                    continue;
                }
                let k = ai.signum() * ai.abs().min(aj.abs());
                let other = if fi == "cos" { "sin" } else { "cos" };
                // The pair's k-th powers are s_i^k s_j^k (−1)^k other^2k (the leftover powers
                // keep their own signs): each sign ±1, so only the parity counts.
                let sign = if (if si < 0 { k } else { 0 } + if sj < 0 { k } else { 0 } + k) % 2 == 0
                {
                    1
                } else {
                    -1
                };
                let shifted = |s: i64, f: &str, c: i64| {
                    Expr::add(vec![
                        Expr::mul(vec![Expr::int(s.into()), Expr::call(f, xi.clone())]),
                        Expr::int((s * c).into()),
                    ])
                };
                let mut rest: Vec<Expr> = factors
                    .iter()
                    .enumerate()
                    .filter(|(n, _)| *n != i && *n != j)
                    .map(|(_, f)| f.clone())
                    .collect();
                if ai != k {
                    rest.push(Expr::pow(shifted(si, fi, 1), Expr::int((ai - k).into())));
                }
                if aj != k {
                    rest.push(Expr::pow(shifted(sj, fj, -1), Expr::int((aj - k).into())));
                }
                rest.push(Expr::pow(
                    Expr::call(other, xi.clone()),
                    Expr::int((2 * k).into()),
                ));
                if sign < 0 {
                    rest.push(Expr::int(-1));
                }
                factors = match Expr::mul(rest) {
                    Expr::Mul(v) => v,
                    other => vec![other],
                };
                continue 'again;
            }
        }
        return factors;
    }
}

#[cfg(test)]
mod tests {
    use super::pythagorean_pairs;
    use crate::cas::{Expr, parse};

    fn at(e: &Expr, x: f64) -> f64 {
        e.eval(&|s| match s {
            "x" => Some(x),
            "p" => Some(1.3),
            "a" => Some(0.7),
            "b" => Some(2.1),
            _ => None,
        })
        .unwrap()
    }

    /// Each rewritten product has the value of the original at several angles, and the pairs
    /// are gone: (c + 1)²(c − 1)² in a denominator, (1 − c)(1 + c), (1 − s)³(s + 1)⁻¹ mixed
    /// signs left alone, sin's pair.
    #[test]
    fn pairs_become_squares_of_the_other_function_with_the_value_kept() {
        for (text, shown) in [
            ("p^2/((cos(x) + 1)^2*(cos(x) - 1)^2)", Some("p^2/sin(x)^4")),
            ("a*(1 - cos(x))*(1 + cos(x))", Some("a*sin(x)^2")),
            (
                "(cos(x) - 1)^3*(cos(x) + 1)",
                Some("-(cos(x) - 1)^2*sin(x)^2"),
            ),
            (
                "(1 - cos(x))^-1*(cos(x) + 1)^-3",
                Some("1/((cos(x) + 1)^2*sin(x)^2)"),
            ),
            ("(sin(x) + 1)*(sin(x) - 1)*b", Some("-b*cos(x)^2")),
            // A Routhian's force: sin θ over sin⁴θ.
            (
                "p^2*cos(x)*sin(x)/(a*(cos(x) + 1)^2*(cos(x) - 1)^2)",
                Some("p^2*cos(x)/(a*sin(x)^3)"),
            ),
            // One sign up and one down: no pair.
            ("(1 - cos(x))^3/(cos(x) + 1)", None),
        ] {
            let e = parse(text).unwrap().expr;
            let Expr::Mul(factors) = e.clone() else {
                panic!("{text}")
            };
            let out = Expr::mul(pythagorean_pairs(factors));
            for x in [0.3, 1.1, 2.0, -0.7] {
                let (a, b) = (at(&e, x), at(&out, x));
                assert!(
                    (a - b).abs() <= 1e-12 * a.abs().max(1.0),
                    "{text}: {a} vs {}",
                    out.to_text()
                );
            }
            match shown {
                Some(form) => assert_eq!(out.to_text(), form, "{text}"),
                None => assert_eq!(out, e, "{text}"),
            }
        }
    }
}
