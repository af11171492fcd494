//! The Symbolica side of `cas`. Everything here runs on the worker thread (see `mod.rs`).
//!
//! Expressions go in as text in Symbolica's input syntax and come back as printed text that our
//! own parser reads. Every symbol is renamed with a prefix on the way in, so that scene names can
//! never collide with Symbolica's built-in names (`pi`, `e`, `i`, ...); π is therefore an
//! ordinary symbol here, which is sound for exact algebra because π is transcendental.

use super::expr::{Expr, parse};
use super::rational::Rational;
use super::trig;
use super::{Integral, Roots};
use symbolica::prelude::*;

const PREFIX: &str = "mb";

fn to_atom(e: &Expr) -> Atom {
    let text = e.to_text_with(&|s| format!("{PREFIX}{s}"));
    parse!(text.as_str())
}

fn from_text(text: &str) -> Result<Expr, String> {
    let parsed = parse(text)
        .map_err(|e| format!("cannot read the engine's output `{text}`: {}", e.message))?;
    if let Some((name, _)) = parsed.symbols.iter().find(|(s, _)| !s.starts_with(PREFIX)) {
        return Err(format!(
            "unexpected name `{name}` in the engine's output `{text}`"
        ));
    }
    Ok(parsed
        .expr
        .substitute(&|s| s.strip_prefix(PREFIX).map(Expr::sym)))
}

fn from_atom(a: &Atom) -> Result<Expr, String> {
    from_text(&a.to_string())
}

fn var_atom(name: &str) -> Atom {
    Atom::var(symbol!(format!("{PREFIX}{name}").as_str()))
}

/// Expanded, with rational functions brought to one reduced fraction.
fn normal_form(e: &Expr) -> Result<Expr, String> {
    let atom = to_atom(e).expand();
    if trig::has_fractional_power(e) {
        return from_atom(&atom);
    }
    let rat: RationalPolynomial<_, u16> = atom.to_rational_polynomial(&Q, &Z, None);
    if rat.denominator.is_constant() {
        return from_atom(&atom);
    }
    let num = from_atom(&rat.numerator.to_expression().expand())?;
    let den = from_atom(&rat.denominator.to_expression().expand())?;
    Ok(Expr::div(num, den))
}

/// A canonical expanded form: sin powers reduced with sin² = 1 − cos², fractions combined.
pub fn simplify(e: &Expr) -> Result<Expr, String> {
    let first = normal_form(e)?;
    let reduced = trig::reduce_sin_powers(&first);
    if reduced == first {
        Ok(first)
    } else {
        normal_form(&reduced)
    }
}

/// Zero for every value of the symbols: trigonometric functions go to half-angle tangents, and the
/// numerator of the resulting rational function must vanish.
pub fn is_zero(e: &Expr) -> Result<bool, String> {
    let (h, _) = trig::to_half_angle(e);
    let atom = to_atom(&h).expand();
    if trig::has_fractional_power(&h) {
        return Ok(atom.to_string() == "0");
    }
    let rat: RationalPolynomial<_, u16> = atom.to_rational_polynomial(&Q, &Z, None);
    Ok(rat.numerator.is_zero())
}

/// The exponent of `var` in a coefficient-list key such as `1`, `mbx` or `mbx^3`.
fn key_exponent(key: &Atom, var: &str) -> Result<u32, String> {
    match from_atom(key)? {
        Expr::Num(r) if r == Rational::ONE => Ok(0),
        Expr::Sym(s) if s == var => Ok(1),
        Expr::Pow(b, x) => match (*b, *x) {
            (Expr::Sym(s), Expr::Num(n)) if s == var && n.is_integer() && n.numer() > 0 => {
                Ok(n.numer() as u32)
            }
            _ => Err(format!("not a polynomial in {var}: `{key}`")),
        },
        _ => Err(format!("not a polynomial in {var}: `{key}`")),
    }
}

/// (power of `var`, coefficient) pairs of an expanded polynomial in `var`.
fn coefficients(e: &Expr, var: &str) -> Result<Vec<(u32, Expr)>, String> {
    let atom = to_atom(e).expand();
    let x = var_atom(var);
    let mut out = Vec::new();
    for (key, coeff) in atom.coefficient_list::<i8>(std::slice::from_ref(&x)) {
        let coeff = from_atom(&coeff)?;
        if coeff.symbols().iter().any(|s| s == var) {
            return Err(format!("cannot integrate: {var} also appears as `{coeff}`"));
        }
        out.push((key_exponent(&key, var)?, coeff));
    }
    Ok(out)
}

/// (n)!! with (−1)!! = 0!! = 1.
fn double_factorial(n: i64) -> i128 {
    (1..=n.max(0)).rev().step_by(2).map(|k| k as i128).product()
}

/// ∫ cosᵖθ sinᵠθ dθ over [0, 2π] (or [0, π]), by the beta-function formula.
pub fn trig_moment(p: u32, q: u32, half: bool) -> Expr {
    let (p, q) = (p as i64, q as i64);
    let ratio = || {
        Expr::rat(
            double_factorial(p - 1) * double_factorial(q - 1),
            double_factorial(p + q),
        )
    };
    let pi = Expr::sym("pi");
    if p % 2 == 1 || (!half && q % 2 == 1) {
        Expr::int(0)
    } else if !half {
        Expr::mul(vec![Expr::int(2), pi, ratio()])
    } else if q % 2 == 0 {
        Expr::mul(vec![pi, ratio()])
    } else {
        Expr::mul(vec![Expr::int(2), ratio()])
    }
}

pub fn integrate(integrand: &Expr, domain: &[Integral]) -> Result<Expr, String> {
    let mut current = integrand.clone();
    for integral in domain {
        current = match integral {
            Integral::Poly { var, lo, hi } => {
                let terms = coefficients(&current, var)?;
                Expr::add(
                    terms
                        .into_iter()
                        .map(|(k, c)| {
                            let k1 = Expr::int(k as i128 + 1);
                            let span = Expr::sub(
                                Expr::pow(hi.clone(), k1.clone()),
                                Expr::pow(lo.clone(), k1.clone()),
                            );
                            Expr::mul(vec![c, span, Expr::rat(1, k as i128 + 1)])
                        })
                        .collect(),
                )
            }
            Integral::Trig { var, half } => {
                let (c, s) = ("c__", "s__");
                let named = trig::name_trig_of(&current, var, c, s);
                let mut total = Vec::new();
                for (p, coeff_c) in coefficients(&named, c)? {
                    for (q, coeff) in coefficients(&coeff_c, s)? {
                        if coeff.symbols().iter().any(|x| x == var) {
                            return Err(format!(
                                "cannot integrate over {var}: `{coeff}` is not a polynomial in cos {var}, sin {var}"
                            ));
                        }
                        total.push(Expr::mul(vec![coeff, trig_moment(p, q, *half)]));
                    }
                }
                Expr::add(total)
            }
        };
        current = normal_form(&current)?;
    }
    Ok(current)
}

pub fn roots(poly: &Expr, var: &str) -> Result<Roots, String> {
    let (h, args) = trig::to_half_angle(poly);
    let rat: RationalPolynomial<_, u16> = to_atom(&h).expand().to_rational_polynomial(&Q, &Z, None);
    let mut out = Roots {
        roots: Vec::new(),
        unsolved: Vec::new(),
    };
    let back = |e: Expr| -> Result<Expr, String> { simplify(&trig::from_half_angle(&e, &args)) };
    for (factor, mult) in rat.numerator.factor() {
        let factor = from_text(&factor.to_string())?;
        let mut c = [Expr::int(0), Expr::int(0), Expr::int(0)];
        let terms = coefficients(&factor, var)?;
        let degree = terms.iter().map(|(k, _)| *k).max().unwrap_or(0);
        if degree == 0 {
            continue;
        }
        if degree > 2 {
            out.unsolved.push((back(factor)?, mult as u32));
            continue;
        }
        for (k, coeff) in terms {
            c[k as usize] = coeff;
        }
        if degree == 1 {
            out.roots.push((
                back(Expr::neg(Expr::div(c[0].clone(), c[1].clone())))?,
                mult as u32,
            ));
        } else {
            // (−b ± √(b² − 4ac)) / 2a
            let disc = Expr::sub(
                Expr::pow(c[1].clone(), Expr::int(2)),
                Expr::mul(vec![Expr::int(4), c[2].clone(), c[0].clone()]),
            );
            let sqrt = Expr::pow(simplify(&disc)?, Expr::rat(1, 2));
            for sign in [-1, 1] {
                let num = Expr::add(vec![
                    Expr::neg(c[1].clone()),
                    Expr::mul(vec![Expr::int(sign), sqrt.clone()]),
                ]);
                out.roots.push((
                    back(Expr::div(num, Expr::mul(vec![Expr::int(2), c[2].clone()])))?,
                    mult as u32,
                ));
            }
        }
    }
    Ok(out)
}

/// Divides the entries by their common factor: the factors of a + z1·b + z2·c (fresh
/// z's) that do not contain the z's are exactly the common content of a, b and c.
pub fn primitive_part(entries: &[Expr]) -> Result<Vec<Expr>, String> {
    // A common factor can hide behind sin² = 1 − cos² (sin²α written as 1 − cos²α), so try the
    // entries as they are and with either square rewritten, and keep the shortest result.
    let forms = [
        entries.to_vec(),
        entries.iter().map(trig::reduce_sin_powers).collect(),
        entries.iter().map(trig::reduce_cos_powers).collect(),
    ];
    let mut best: Option<Vec<Expr>> = None;
    for form in forms {
        let normal: Vec<Expr> = form.iter().map(normal_form).collect::<Result<_, _>>()?;
        let reduced = divide_by_content(&normal)?;
        let len = |v: &[Expr]| v.iter().map(|e| e.to_text().len()).sum::<usize>();
        if best.as_ref().is_none_or(|b| len(&reduced) < len(b)) {
            best = Some(reduced);
        }
    }
    Ok(best.expect("three forms were tried"))
}

fn divide_by_content(entries: &[Expr]) -> Result<Vec<Expr>, String> {
    let combined = Expr::add(
        entries
            .iter()
            .enumerate()
            .map(|(i, e)| {
                Expr::mul(vec![
                    Expr::pow(Expr::sym("z__"), Expr::int(i as i128)),
                    e.clone(),
                ])
            })
            .collect(),
    );
    let rat: RationalPolynomial<_, u16> = to_atom(&combined)
        .expand()
        .to_rational_polynomial(&Q, &Z, None);
    let mut content = vec![from_atom(&rat.denominator.to_expression())?];
    content[0] = Expr::div(Expr::int(1), content[0].clone());
    for (factor, mult) in rat.numerator.factor() {
        let f = from_text(&factor.to_string())?;
        if !f.symbols().iter().any(|s| s == "z__") {
            content.push(Expr::pow(f, Expr::int(mult as i128)));
        }
    }
    let content = Expr::mul(content);
    entries
        .iter()
        .map(|e| normal_form(&Expr::div(e.clone(), content.clone())))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trig_moments_follow_the_beta_function() {
        // Checked against direct numeric integration, not a table.
        for p in 0..5u32 {
            for q in 0..5u32 {
                for half in [false, true] {
                    let upper = if half {
                        std::f64::consts::PI
                    } else {
                        2.0 * std::f64::consts::PI
                    };
                    let n = 20_000;
                    let h = upper / n as f64;
                    let numeric: f64 = (0..n)
                        .map(|i| {
                            let t = (i as f64 + 0.5) * h;
                            t.cos().powi(p as i32) * t.sin().powi(q as i32) * h
                        })
                        .sum();
                    let exact = trig_moment(p, q, half).eval(&|_| None).unwrap();
                    assert!(
                        (numeric - exact).abs() < 1e-7,
                        "p={p} q={q} half={half}: {numeric} vs {exact}"
                    );
                }
            }
        }
    }
}
