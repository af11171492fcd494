//! Trigonometric rewriting on our own tree, before anything reaches the engine.
//!
//! Multiple angles are expanded (sin 2α = 2 sin α cos α), and then each distinct argument x is
//! replaced by the half-angle tangent t: cos x = (1 − t²)/(1 + t²), sin x = 2t/(1 + t²). The result
//! is a rational function, zero exactly when the trigonometric expression is identically zero
//! (for independent arguments).

use super::expr::Expr;
use super::rational::Rational;

/// sin(k·x), cos(k·x) for integer k → polynomials in sin x, cos x; sin 0 = 0, cos 0 = 1.
pub fn expand_multiple_angles(e: &Expr) -> Expr {
    match e {
        Expr::Call(name, args) if (name == "sin" || name == "cos") && args.len() == 1 => {
            let arg = expand_multiple_angles(&args[0]);
            // A shift by a multiple of π/2 swaps sin and cos with a sign: cos(π/2 − θ) = sin θ.
            if let Some((quarters, rest)) = split_quarter_turns(&arg) {
                let (swap, sign) = match (name.as_str(), quarters) {
                    ("sin", 0) | ("cos", 0) => (false, 1),
                    ("sin", 1) => (true, 1),
                    ("cos", 1) => (true, -1),
                    (_, 2) => (false, -1),
                    ("sin", _) => (true, -1),
                    _ => (true, 1),
                };
                let other = if name == "sin" { "cos" } else { "sin" };
                let f = if swap { other } else { name.as_str() };
                return Expr::mul(vec![
                    Expr::int(sign),
                    expand_multiple_angles(&Expr::call(f, rest)),
                ]);
            }
            let (k, rest) = split_integer_factor(&arg);
            if k == 0 {
                return Expr::int(if name == "sin" { 0 } else { 1 });
            }
            let (s, c) = sin_cos_multiple(k.unsigned_abs() as u32, &rest);
            let sign = if k < 0 && name == "sin" { -1 } else { 1 };
            Expr::mul(vec![Expr::int(sign), if name == "sin" { s } else { c }])
        }
        Expr::Call(name, args) => Expr::Call(
            name.clone(),
            args.iter().map(expand_multiple_angles).collect(),
        ),
        Expr::Add(v) => Expr::add(v.iter().map(expand_multiple_angles).collect()),
        Expr::Mul(v) => Expr::mul(v.iter().map(expand_multiple_angles).collect()),
        Expr::Pow(a, b) => Expr::pow(expand_multiple_angles(a), expand_multiple_angles(b)),
        other => other.clone(),
    }
}

/// sin and cos of a multiple of π/12 replaced by their exact values (cos π/6 = √3/2), so
/// that a variant's angle such as `pi/6` gives an exact answer; other calls are kept. A rational
/// multiple of π loses its whole turns first, exactly, so that no float ever sees 1e20·π + π/6
/// (where f64 has no digit of the π/6 left).
pub fn special_angles(e: &Expr) -> Expr {
    match e {
        Expr::Call(name, args) if (name == "sin" || name == "cos") && args.len() == 1 => {
            let arg = without_whole_turns(&special_angles(&args[0]));
            // Any form of qπ: `pi/6`, `5*pi/12`, `pi*5/12`.
            let twelfths = pi_multiple(&arg).and_then(|q| q.mul(&Rational::int(12)).to_i64());
            // sin x = cos(π/2 − x): six twelfths of π.
            let k = twelfths.map(|k| if name == "sin" { 6 - k } else { k });
            match k.and_then(cos_twelfths) {
                Some(v) => v,
                None => Expr::Call(name.clone(), vec![arg]),
            }
        }
        Expr::Call(name, args) => {
            Expr::Call(name.clone(), args.iter().map(special_angles).collect())
        }
        Expr::Add(v) => Expr::add(v.iter().map(special_angles).collect()),
        Expr::Mul(v) => Expr::mul(v.iter().map(special_angles).collect()),
        Expr::Pow(a, b) => Expr::pow(special_angles(a), special_angles(b)),
        other => other.clone(),
    }
}

/// q when `e` is exactly qπ with q rational (`1e20*pi + pi/6` as written, or folded).
pub fn pi_multiple(e: &Expr) -> Option<Rational> {
    let at = |x: i128| e.eval_rational(&|s| (s == "pi").then(|| Rational::int(x)));
    let (zero, q, two) = (at(0)?, at(1)?, at(2)?);
    (zero.is_zero() && two == q.mul(&Rational::int(2))).then_some(q)
}

/// qπ as (q mod 2)π: the same sine and cosine. Other arguments are kept.
fn without_whole_turns(arg: &Expr) -> Expr {
    let Some(q) = pi_multiple(arg) else {
        return arg.clone();
    };
    let pi = Expr::sym("pi");
    let two = Rational::int(2);
    if q.compare(&Rational::ZERO).is_ge() && q.compare(&two).is_lt() {
        return arg.clone();
    }
    Expr::mul(vec![Expr::Num(q.rem_euclid(&two)), pi])
}

#[cfg(test)]
mod turns {
    use super::*;
    use crate::cas::parse;

    #[test]
    fn every_multiple_of_pi_over_twelve_is_exact_and_agrees_with_f64() {
        let e = |s: &str| parse(s).unwrap().expr;
        for k in -30..=30 {
            for (name, f) in [("sin", f64::sin as fn(f64) -> f64), ("cos", f64::cos)] {
                // Written three ways: kπ/12, k*pi/12 and pi*k/12.
                for text in [
                    format!("{name}({k}/12*pi)"),
                    format!("{name}({k}*pi/12)"),
                    format!("{name}(pi*{k}/12)"),
                ] {
                    let exact = special_angles(&e(&text));
                    assert!(
                        !exact.to_text().contains(name),
                        "{text} kept: {}",
                        exact.to_text()
                    );
                    let value = exact.eval(&|_| None).unwrap();
                    // The float route's own error: its argument is off by about |x|ε.
                    let x = k as f64 * std::f64::consts::PI / 12.0;
                    let float = f(x);
                    let bound = 4.0 * f64::EPSILON * (1.0 + x.abs());
                    assert!(
                        (value - float).abs() <= bound,
                        "{text}: {value} against {float}"
                    );
                }
            }
        }
    }

    #[test]
    fn whole_turns_come_off_exactly_before_the_special_angles() {
        let e = |s: &str| parse(s).unwrap().expr;
        // cos(1e20 π + π/6) = cos(π/6); in f64 the argument has no digit of π/6 left.
        let folded = special_angles(&e("cos(100000000000000000000*pi + pi/6)"));
        assert_eq!(folded, special_angles(&e("cos(pi/6)")));
        assert_eq!(folded.to_text(), "1/2*sqrt(3)");
        let kept = special_angles(&e("sin(14000001/7*pi)"));
        assert_eq!(kept, e("sin(1/7*pi)"), "{}", kept.to_text());
        assert_eq!(
            pi_multiple(&e("100000000000000000000*pi + pi/6")).unwrap(),
            {
                let r = parse("600000000000000000001/6").unwrap().expr;
                r.eval_rational(&|_| None).unwrap()
            }
        );
        assert_eq!(pi_multiple(&e("pi + 1")), None);
        assert_eq!(pi_multiple(&e("pi^2")), None);
    }
}

/// cos(kπ/12) exactly: cos(π/12) = (√6 + √2)/4 and cos(5π/12) = (√6 − √2)/4 besides the
/// familiar ones.
fn cos_twelfths(k: i64) -> Option<Expr> {
    let k = k.rem_euclid(24);
    let k = if k > 12 { 24 - k } else { k };
    let (sign, k) = if k > 6 { (-1, 12 - k) } else { (1, k) };
    let half_root = |n: i128| Expr::mul(vec![Expr::rat(1, 2), Expr::call("sqrt", Expr::int(n))]);
    let magnitude = match k {
        0 => Expr::int(1),
        1 | 5 => {
            let root = |n: i128| Expr::mul(vec![Expr::rat(1, 4), Expr::call("sqrt", Expr::int(n))]);
            let second = Expr::mul(vec![Expr::int(if k == 1 { 1 } else { -1 }), root(2)]);
            Expr::add(vec![root(6), second])
        }
        2 => half_root(3),
        3 => half_root(2),
        4 => Expr::rat(1, 2),
        6 => Expr::int(0),
        _ => return None,
    };
    Some(Expr::mul(vec![Expr::int(sign), magnitude]))
}

/// x + cπ with 2c an integer → (2c mod 4, x): the shift in quarter turns. `None` without such
/// a term.
fn split_quarter_turns(arg: &Expr) -> Option<(i64, Expr)> {
    let terms: Vec<Expr> = match arg {
        Expr::Add(v) => v.clone(),
        other => vec![other.clone()],
    };
    let mut halves = 0i64;
    let mut found = false;
    let mut rest = Vec::new();
    for t in terms {
        let c = match &t {
            Expr::Sym(p) if p == "pi" => Some(Rational::ONE),
            Expr::Mul(v) if v.len() == 2 && v[1] == Expr::sym("pi") => match &v[0] {
                Expr::Num(r) => Some(r.clone()),
                _ => None,
            },
            _ => None,
        };
        match c.and_then(|c| c.mul(&Rational::int(2)).to_i64()) {
            Some(h) => {
                halves += h;
                found = true;
            }
            _ => rest.push(t),
        }
    }
    found.then(|| (halves.rem_euclid(4), Expr::add(rest)))
}

/// Every symbol that appears in a sine or cosine argument with a fractional coefficient (θ/2 beside
/// θ), replaced by a multiple of a fresh symbol u so that each argument is an integer multiple:
/// θ → 2u. The expression is zero exactly when the result is, so this serves `is_zero` only.
pub fn common_angle_base(e: &Expr) -> Expr {
    let mut denominators: std::collections::BTreeMap<String, i64> = Default::default();
    collect_fractional_angles(e, &mut denominators);
    if denominators.is_empty() {
        return e.clone();
    }
    e.substitute(&|s| {
        denominators.get(s).map(|l| {
            Expr::mul(vec![
                Expr::int(i128::from(*l)),
                Expr::sym(&format!("{s}__base")),
            ])
        })
    })
}

fn collect_fractional_angles(e: &Expr, out: &mut std::collections::BTreeMap<String, i64>) {
    match e {
        Expr::Call(name, args) if (name == "sin" || name == "cos") && args.len() == 1 => {
            let terms: Vec<&Expr> = match &args[0] {
                Expr::Add(v) => v.iter().collect(),
                other => vec![other],
            };
            for t in terms {
                if let Expr::Mul(v) = t
                    && let [Expr::Num(r), Expr::Sym(s)] = v.as_slice()
                    && s != "pi"
                    && !r.is_integer()
                    && let Some((_, den)) = r.to_i64_pair()
                    && den <= 12
                {
                    let l = out.entry(s.clone()).or_insert(1);
                    *l = lcm(*l, den.abs());
                }
            }
            collect_fractional_angles(&args[0], out);
        }
        Expr::Call(_, v) | Expr::Add(v) | Expr::Mul(v) => {
            v.iter().for_each(|x| collect_fractional_angles(x, out))
        }
        Expr::Pow(a, b) => {
            collect_fractional_angles(a, out);
            collect_fractional_angles(b, out);
        }
        _ => {}
    }
}

fn lcm(a: i64, b: i64) -> i64 {
    let gcd = |mut x: i64, mut y: i64| {
        while y != 0 {
            (x, y) = (y, x % y);
        }
        x
    };
    a / gcd(a, b) * b
}

/// `k*x` → (k, x) for a small integer k; anything else → (1, e); zero → (0, 0).
fn split_integer_factor(e: &Expr) -> (i64, Expr) {
    match e {
        Expr::Num(r) if r.is_zero() => (0, Expr::int(0)),
        Expr::Mul(v) => match v.first() {
            Some(Expr::Num(r)) if r.to_i64().is_some_and(|k| k.abs() <= 12) => {
                (r.to_i64().unwrap_or(1), Expr::mul(v[1..].to_vec()))
            }
            _ => (1, e.clone()),
        },
        _ => (1, e.clone()),
    }
}

/// (sin kx, cos kx) by the addition formulas.
fn sin_cos_multiple(k: u32, x: &Expr) -> (Expr, Expr) {
    let (s1, c1) = (Expr::call("sin", x.clone()), Expr::call("cos", x.clone()));
    let (mut s, mut c) = (s1.clone(), c1.clone());
    for _ in 1..k {
        let s_next = Expr::add(vec![
            Expr::mul(vec![s.clone(), c1.clone()]),
            Expr::mul(vec![c.clone(), s1.clone()]),
        ]);
        let c_next = Expr::minus(
            Expr::mul(vec![c.clone(), c1.clone()]),
            Expr::mul(vec![s.clone(), s1.clone()]),
        );
        (s, c) = (s_next, c_next);
    }
    (s, c)
}

/// Replaces cos(var) and sin(var) by the symbols `c` and `s`, for integration over var.
pub fn name_trig_of(e: &Expr, var: &str, c: &str, s: &str) -> Expr {
    match e {
        Expr::Call(name, a)
            if a.len() == 1 && a[0] == Expr::sym(var) && (name == "cos" || name == "sin") =>
        {
            Expr::sym(if name == "cos" { c } else { s })
        }
        Expr::Call(name, a) => Expr::Call(
            name.clone(),
            a.iter().map(|x| name_trig_of(x, var, c, s)).collect(),
        ),
        Expr::Add(v) => Expr::add(v.iter().map(|x| name_trig_of(x, var, c, s)).collect()),
        Expr::Mul(v) => Expr::mul(v.iter().map(|x| name_trig_of(x, var, c, s)).collect()),
        Expr::Pow(a, b) => Expr::pow(name_trig_of(a, var, c, s), name_trig_of(b, var, c, s)),
        other => other.clone(),
    }
}

/// sinⁿx with n ≥ 2 → sin^(n mod 2) x · (1 − cos²x)^(n div 2): with expansion after it, a
/// canonical form (a polynomial in cos plus sin times one) for polynomials in sin and cos.
pub fn reduce_sin_powers(e: &Expr) -> Expr {
    reduce_powers(e, "sin", "cos")
}

/// The mirror image: cosⁿx → cos^(n mod 2) x · (1 − sin²x)^(n div 2).
pub fn reduce_cos_powers(e: &Expr) -> Expr {
    reduce_powers(e, "cos", "sin")
}

fn reduce_powers(e: &Expr, from: &str, to: &str) -> Expr {
    let rec = |x: &Expr| reduce_powers(x, from, to);
    match e {
        Expr::Pow(a, b) => {
            let base = rec(a);
            if let (Expr::Call(name, args), Expr::Num(n)) = (&base, b.as_ref())
                && name == from
                && let Some(k) = n.to_i64().map(i128::from)
                && k >= 2
            {
                let other2 = Expr::pow(Expr::call(to, args[0].clone()), Expr::int(2));
                return Expr::mul(vec![
                    Expr::pow(base.clone(), Expr::int(k % 2)),
                    Expr::pow(Expr::minus(Expr::int(1), other2), Expr::int(k / 2)),
                ]);
            }
            Expr::pow(base, rec(b))
        }
        Expr::Call(name, a) => Expr::Call(name.clone(), a.iter().map(rec).collect()),
        Expr::Add(v) => Expr::add(v.iter().map(rec).collect()),
        Expr::Mul(v) => Expr::mul(v.iter().map(rec).collect()),
        other => other.clone(),
    }
}

/// True if any power has a non-integer exponent (a square root, say).
pub fn has_fractional_power(e: &Expr) -> bool {
    match e {
        Expr::Pow(a, b) => {
            !matches!(b.as_ref(), Expr::Num(r) if r.is_integer()) || has_fractional_power(a)
        }
        Expr::Call(n, a) => n == "sqrt" || a.iter().any(has_fractional_power),
        Expr::Add(v) | Expr::Mul(v) | Expr::List(v) => v.iter().any(has_fractional_power),
        Expr::Index(a, b) => has_fractional_power(a) || has_fractional_power(b),
        Expr::Num(_) | Expr::Sym(_) => false,
    }
}

/// The name of the half-angle variable for argument number `i`. `__` never appears in scene names.
pub fn half_angle_name(i: usize) -> String {
    format!("t__{i}")
}

/// Replaces sin and cos of each distinct argument by rational functions of a fresh t.
/// Returns the new expression and the arguments, in the order of their t's.
pub fn to_half_angle(e: &Expr) -> (Expr, Vec<Expr>) {
    let mut args = Vec::new();
    let out = replace(&expand_multiple_angles(e), &mut args);
    (out, args)
}

fn replace(e: &Expr, args: &mut Vec<Expr>) -> Expr {
    match e {
        Expr::Call(name, a) if (name == "sin" || name == "cos") && a.len() == 1 => {
            let arg = replace(&a[0], args);
            let i = match args.iter().position(|x| *x == arg) {
                Some(i) => i,
                None => {
                    args.push(arg);
                    args.len() - 1
                }
            };
            let t = Expr::Sym(half_angle_name(i));
            let t2 = Expr::pow(t.clone(), Expr::int(2));
            let den = Expr::add(vec![Expr::int(1), t2.clone()]);
            let num = if name == "cos" {
                Expr::minus(Expr::int(1), t2)
            } else {
                Expr::mul(vec![Expr::int(2), t])
            };
            Expr::over(num, den)
        }
        Expr::Call(name, a) => {
            Expr::Call(name.clone(), a.iter().map(|x| replace(x, args)).collect())
        }
        Expr::Add(v) => Expr::add(v.iter().map(|x| replace(x, args)).collect()),
        Expr::Mul(v) => Expr::mul(v.iter().map(|x| replace(x, args)).collect()),
        Expr::Pow(a, b) => Expr::pow(replace(a, args), replace(b, args)),
        other => other.clone(),
    }
}

/// Maps half-angle variables back: t = sin x / (1 + cos x).
pub fn from_half_angle(e: &Expr, args: &[Expr]) -> Expr {
    e.substitute(&|name| {
        let i: usize = name.strip_prefix("t__")?.parse().ok()?;
        let x = args.get(i)?.clone();
        Some(Expr::over(
            Expr::call("sin", x.clone()),
            Expr::add(vec![Expr::int(1), Expr::call("cos", x)]),
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cas::parse;

    fn at(e: &Expr, a: f64) -> f64 {
        e.eval(&|s| match s {
            "a" => Some(a),
            "t__0" => Some((a / 2.0).tan()),
            _ => None,
        })
        .unwrap()
    }

    #[test]
    fn multiple_angles_agree_numerically() {
        for s in [
            "sin(2*a)",
            "cos(3*a)",
            "sin(-2*a)",
            "cos(0)",
            "sin(a)*cos(4*a)",
        ] {
            let e = parse(s).unwrap().expr;
            let x = expand_multiple_angles(&e);
            assert!((at(&e, 0.37) - at(&x, 0.37)).abs() < 1e-14, "{s} -> {x}");
        }
    }

    #[test]
    fn special_angles_are_exact_and_agree_in_value() {
        for (k, d) in [
            (0, 1),
            (1, 6),
            (1, 4),
            (1, 3),
            (1, 2),
            (2, 3),
            (3, 4),
            (5, 6),
            (1, 1),
            (7, 6),
            (-1, 4),
            (11, 6),
        ] {
            for f in ["sin", "cos"] {
                let e = parse(&format!("{f}({k}*pi/{d})")).unwrap().expr;
                let exact = special_angles(&e);
                assert!(
                    exact.symbols().iter().all(|s| s != "pi"),
                    "{f}({k}π/{d}) -> {exact}"
                );
                let (a, b) = (e.eval(&|_| None).unwrap(), exact.eval(&|_| None).unwrap());
                assert!((a - b).abs() < 1e-15, "{f}({k}π/{d}): {a} vs {b}");
            }
        }
        // π/5 has no such value here: it stays as it is.
        let e = parse("cos(pi/5)").unwrap().expr;
        assert_eq!(special_angles(&e), e);
    }

    #[test]
    fn half_angle_substitution_is_exact_in_value() {
        let e = parse("sin(a)^2 + 3*cos(2*a)*sin(a)").unwrap().expr;
        let (h, args) = to_half_angle(&e);
        assert_eq!(args, vec![parse("a").unwrap().expr]);
        assert!(h.symbols().iter().all(|s| s == "t__0"));
        assert!((at(&e, 0.9) - at(&h, 0.9)).abs() < 1e-14);
        let back = from_half_angle(&Expr::sym("t__0"), &args);
        assert!((at(&back, 0.9) - (0.45f64).tan()).abs() < 1e-14);
    }
}

#[cfg(test)]
mod shift_tests {
    use super::*;
    use crate::cas::parse;

    fn value(e: &Expr, theta: f64) -> f64 {
        e.eval(&|s| match s {
            "theta" => Some(theta),
            "theta__base" => Some(theta / 2.0),
            _ => None,
        })
        .unwrap()
    }

    #[test]
    fn shifts_by_quarter_turns_become_sin_or_cos_of_the_rest() {
        // Checked by value at several angles, against the unrewritten expression.
        for (input, expected) in [
            ("cos(pi/2 - theta)", "sin(theta)"),
            ("sin(pi - theta)", "sin(theta)"),
            ("cos(theta + pi)", "-cos(theta)"),
            ("sin(theta - pi/2)", "-cos(theta)"),
            ("cos(3*pi/2 + theta)", "sin(theta)"),
            ("sin(5*pi/2)", "1"),
        ] {
            let got = expand_multiple_angles(&parse(input).unwrap().expr);
            assert_eq!(got, parse(expected).unwrap().expr, "{input}");
            for t in [0.3, 1.1, -2.0] {
                let before = value(&parse(input).unwrap().expr, t);
                assert!((value(&got, t) - before).abs() < 1e-14, "{input} at {t}");
            }
        }
        // A third of a turn is left alone: its sine is not rational.
        let third = parse("sin(pi/3 + theta)").unwrap().expr;
        assert_eq!(expand_multiple_angles(&third), third);
    }

    #[test]
    fn half_angles_share_a_base_with_whole_ones() {
        let e = parse("cos(theta/2)^2 - (1 + cos(theta))/2").unwrap().expr;
        let based = common_angle_base(&e);
        assert!(
            based.symbols().contains(&"theta__base".to_string()),
            "{based}"
        );
        for t in [0.3, 1.1] {
            assert!((value(&based, t) - value(&e, t)).abs() < 1e-14);
        }
    }
}
