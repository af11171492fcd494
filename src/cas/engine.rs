//! The Symbolica side of `cas`. Everything here runs on the worker thread (see `mod.rs`).
//!
//! Expressions go in as text in Symbolica's input syntax and come back as printed text that our
//! own parser reads. Every symbol is renamed with a prefix on the way in, so that scene names can
//! never collide with Symbolica's built-in names (`pi`, `e`, `i`, ...); π is therefore an
//! ordinary symbol here, which is sound for exact algebra because π is transcendental.

pub(super) use super::atoms::{from_atom, to_atom, var_atom};
pub use super::engine_error::{EngineError, MAX_DEGREE, MAX_ROOT_DIGITS, MAX_TERMS};
use super::expr::Expr;
use super::rational::Rational;
use super::trig;
use super::{AngleSpan, Integral};
use symbolica::prelude::*;

/// The digits of a number with more than [`MAX_ROOT_DIGITS`] of them under a fractional power
/// or `sqrt`, if any; `under_root` says whether `e` itself is under one.
fn large_number_under_a_root(e: &Expr, under_root: bool) -> Option<usize> {
    let walk = |v: &[Expr], under_root| {
        v.iter()
            .find_map(|x| large_number_under_a_root(x, under_root))
    };
    let too_large = |r: &Rational| {
        let (n, d) = r.abs_parts();
        let digits = n.to_string().len().max(d.to_string().len());
        (digits > MAX_ROOT_DIGITS).then_some(digits)
    };
    // The engine folds the numbers of a numeric sum or product before it takes the root: 1 +
    // 10^-13 under a root is a 14-digit number, and a variant's sides of 14 digits gave one of
    // 53 digits, which took the engine over 10 minutes to factor.
    if under_root
        && !matches!(e, Expr::Num(_) | Expr::Sym(_))
        && let Some(r) = e.eval_rational(&|_| None)
    {
        return too_large(&r);
    }
    match e {
        Expr::Num(r) if under_root => too_large(r),
        Expr::Num(_) | Expr::Sym(_) => None,
        Expr::Pow(b, x) => {
            let root = matches!(x.as_ref(), Expr::Num(k) if !k.is_integer());
            large_number_under_a_root(b, under_root || root)
                .or_else(|| large_number_under_a_root(x, under_root))
        }
        Expr::Call(name, v) => walk(v, under_root || name == "sqrt"),
        Expr::Add(v) | Expr::Mul(v) | Expr::List(v) => walk(v, under_root),
        Expr::Index(a, b) => large_number_under_a_root(a, under_root)
            .or_else(|| large_number_under_a_root(b, under_root)),
    }
}

/// `e` expanded, unless its expansion could exceed the budget: then an error that says so.
pub(super) fn expand(e: &Expr) -> Result<Atom, EngineError> {
    if let Some(digits) = large_number_under_a_root(e, false) {
        return Err(EngineError::LargeRoot { digits });
    }
    let size = e.expansion_size();
    if size.degree > MAX_DEGREE || size.terms > MAX_TERMS {
        return Err(EngineError::OverBudget {
            degree: size.degree,
            terms: size.terms,
        });
    }
    Ok(to_atom(e).expand())
}

/// The atom's symbols and functions in the order of their printed names, as a polynomial's
/// variables. Without a map the engine orders them by when it first made each symbol, which
/// depends on what was derived before in the same process; the sign a factor is given, and so
/// the order a sum prints in, would too (a scene derived alone printed `r − R` for `R − r`).
pub(super) fn variables_by_name(atom: &Atom) -> std::sync::Arc<Vec<PolyVariable>> {
    let mut named: Vec<(String, PolyVariable)> = atom
        .get_all_indeterminates(false)
        .into_iter()
        .filter_map(|v| {
            let variable = match v {
                AtomView::Var(s) => PolyVariable::Symbol(s.get_symbol()),
                AtomView::Fun(f) => PolyVariable::Function(f.get_symbol(), v.to_owned()),
                _ => return None,
            };
            Some((v.to_string(), variable))
        })
        .collect();
    named.sort_by(|a, b| a.0.cmp(&b.0));
    std::sync::Arc::new(named.into_iter().map(|(_, v)| v).collect())
}

/// Expanded, with rational functions brought to one reduced fraction.
fn normal_form(e: &Expr) -> Result<Expr, EngineError> {
    let atom = expand(e)?;
    let expanded = from_atom(&atom)?;
    if !has_symbolic_denominator(&expanded) || trig::has_fractional_power(e) {
        return Ok(expanded);
    }
    let rat: RationalPolynomial<_, u16> =
        atom.to_rational_polynomial(&Q, &Z, variables_by_name(&atom));
    let num = from_atom(&rat.numerator.to_expression().expand())?;
    let den = from_atom(&rat.denominator.to_expression().expand())?;
    Ok(Expr::over(num, den))
}

/// A rational function in the engine's form; an expression with a fractional power is not one.
pub(super) fn rational_function(
    e: &Expr,
) -> Result<RationalPolynomial<IntegerRing, u16>, EngineError> {
    if trig::has_fractional_power(e) {
        return Err(EngineError::NotRational { expr: e.to_text() });
    }
    let atom = expand(e)?;
    Ok(atom.to_rational_polynomial(&Q, &Z, variables_by_name(&atom)))
}

/// The expanded numerator and denominator of a rational function (no fractional powers).
pub fn fraction(e: &Expr) -> Result<(Expr, Expr), EngineError> {
    let rat = rational_function(e)?;
    Ok((
        from_atom(&rat.numerator.to_expression().expand())?,
        from_atom(&rat.denominator.to_expression().expand())?,
    ))
}

/// The distinct irreducible factors of a rational function's numerator over the rationals,
/// and its denominator: where it vanishes, and where it has poles.
pub fn numerator_factors(e: &Expr) -> Result<(Vec<Expr>, Expr), EngineError> {
    let rat = rational_function(e)?;
    let factors = rat
        .numerator
        .factor()
        .into_iter()
        .map(|(f, _)| from_atom(&f.to_expression()))
        .collect::<Result<_, _>>()?;
    Ok((factors, from_atom(&rat.denominator.to_expression())?))
}

/// A rational function as a product of irreducible factors over the rationals, numerator over
/// denominator, so that a step can show where an expression vanishes or changes sign.
pub fn factor(e: &Expr) -> Result<Expr, EngineError> {
    let rat = rational_function(e)?;
    let product = |poly: &MultivariatePolynomial<_, u16>| -> Result<Expr, EngineError> {
        if poly.is_constant() {
            return from_atom(&poly.to_expression());
        }
        let mut factors = Vec::new();
        for (f, mult) in poly.factor() {
            factors.push(Expr::pow(
                from_atom(&f.to_expression())?,
                Expr::int(mult as i128),
            ));
        }
        Ok(Expr::ordered_product(factors))
    };
    Ok(Expr::over(
        product(&rat.numerator)?,
        product(&rat.denominator)?,
    ))
}

/// A negative power of anything but a number: the expression is not a polynomial.
fn has_symbolic_denominator(e: &Expr) -> bool {
    match e {
        Expr::Pow(b, x) => {
            (matches!(x.as_ref(), Expr::Num(r) if r.is_negative())
                && !matches!(b.as_ref(), Expr::Num(_)))
                || has_symbolic_denominator(b)
        }
        Expr::Add(v) | Expr::Mul(v) | Expr::Call(_, v) | Expr::List(v) => {
            v.iter().any(has_symbolic_denominator)
        }
        Expr::Index(a, b) => has_symbolic_denominator(a) || has_symbolic_denominator(b),
        Expr::Num(_) | Expr::Sym(_) => false,
    }
}

/// A canonical expanded form: sin powers reduced with sin² = 1 − cos², fractions combined.
pub fn simplify(e: &Expr) -> Result<Expr, EngineError> {
    let first = normal_form(e)?;
    let reduced = trig::reduce_sin_powers(&first);
    if reduced == first {
        Ok(first)
    } else {
        normal_form(&reduced)
    }
}

/// Zero for every value of the symbols. Multiple angles are expanded, everything is brought over
/// one denominator, and the numerator is reduced with sin² = 1 − cos²: the powers of cos, and sin
/// times them, are a basis modulo sin² + cos² = 1, so the reduced numerator is zero exactly when
/// the expression is (for independent angles).
pub fn is_zero(e: &Expr) -> Result<bool, EngineError> {
    let e = trig::expand_multiple_angles(&trig::common_angle_base(e));
    let atom = expand(&e)?;
    let numerator = if trig::has_fractional_power(&e) {
        atom
    } else {
        let rat: RationalPolynomial<_, u16> =
            atom.to_rational_polynomial(&Q, &Z, variables_by_name(&atom));
        if rat.numerator.is_zero() {
            return Ok(true);
        }
        rat.numerator.to_expression()
    };
    let reduced = trig::reduce_sin_powers(&from_atom(&numerator)?);
    Ok(expand(&reduced)?.is_zero())
}

/// The exponent of `var` in a coefficient-list key such as `1`, `mbx` or `mbx^3`.
fn key_exponent(key: &Atom, var: &str) -> Result<u32, EngineError> {
    let not_polynomial = || EngineError::NotPolynomial {
        var: var.into(),
        key: key.to_string(),
    };
    match from_atom(key)? {
        Expr::Num(r) if r == Rational::ONE => Ok(0),
        Expr::Sym(s) if s == var => Ok(1),
        Expr::Pow(b, x) => match (*b, *x) {
            (Expr::Sym(s), Expr::Num(n))
                if s == var
                    && n.to_i64()
                        .is_some_and(|k| k > 0 && k <= i64::from(u32::MAX)) =>
            {
                Ok(n.to_i64().unwrap_or(0) as u32)
            }
            _ => Err(not_polynomial()),
        },
        _ => Err(not_polynomial()),
    }
}

/// (power of `var`, coefficient) pairs of an expanded polynomial in `var`.
pub(super) fn coefficients(e: &Expr, var: &str) -> Result<Vec<(u32, Expr)>, EngineError> {
    let atom = expand(e)?;
    let x = var_atom(var);
    let mut out = Vec::new();
    for (key, coeff) in atom.coefficient_list::<i8>(std::slice::from_ref(&x)) {
        let coeff = from_atom(&coeff)?;
        if coeff.symbols().iter().any(|s| s == var) {
            return Err(EngineError::VariableInCoefficient {
                var: var.into(),
                coeff: coeff.to_text(),
            });
        }
        out.push((key_exponent(&key, var)?, coeff));
    }
    Ok(out)
}

/// (n)!! with (−1)!! = 0!! = 1, exactly (80!! is beyond i128).
fn double_factorial(n: i64) -> Rational {
    (1..=n.max(0))
        .rev()
        .step_by(2)
        .fold(Rational::ONE, |acc, k| {
            acc.mul(&Rational::int(i128::from(k)))
        })
}

/// ∫ cosᵖθ sinᵠθ dθ over [0, 2π], [0, π] or [0, π/2], by the beta-function formula: over
/// [0, π/2] it is (p−1)!!(q−1)!!/(p+q)!!, times π/2 when p and q are both even; the longer
/// ranges add copies of it with signs.
pub fn trig_moment(p: u32, q: u32, span: AngleSpan) -> Expr {
    let (p, q) = (p as i64, q as i64);
    let ratio = || {
        let num = double_factorial(p - 1).mul(&double_factorial(q - 1));
        let den = double_factorial(p + q);
        Expr::Num(num.mul(&den.recip().expect("n!! is positive")))
    };
    let pi = Expr::sym("pi");
    let half = match span {
        AngleSpan::Quarter if p % 2 == 0 && q % 2 == 0 => {
            return Expr::mul(vec![Expr::rat(1, 2), pi, ratio()]);
        }
        AngleSpan::Quarter => return ratio(),
        AngleSpan::Half => true,
        AngleSpan::Full => false,
    };
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

pub fn integrate(integrand: &Expr, domain: &[Integral]) -> Result<Expr, EngineError> {
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
                            let span = Expr::minus(
                                Expr::pow(hi.clone(), k1.clone()),
                                Expr::pow(lo.clone(), k1.clone()),
                            );
                            Expr::mul(vec![c, span, Expr::rat(1, k as i128 + 1)])
                        })
                        .collect(),
                )
            }
            Integral::Trig { var, span } => {
                let (c, s) = ("c__", "s__");
                let named = trig::name_trig_of(&current, var, c, s);
                let mut total = Vec::new();
                for (p, coeff_c) in coefficients(&named, c)? {
                    for (q, coeff) in coefficients(&coeff_c, s)? {
                        if coeff.symbols().iter().any(|x| x == var) {
                            return Err(EngineError::NotTrigPolynomial {
                                var: var.clone(),
                                coeff: coeff.to_text(),
                            });
                        }
                        total.push(Expr::mul(vec![coeff, trig_moment(p, q, *span)]));
                    }
                }
                Expr::add(total)
            }
        };
        current = normal_form(&current)?;
    }
    Ok(current)
}

/// Divides the entries by their common factor: the factors of a + z1·b + z2·c (fresh
/// z's) that do not contain the z's are exactly the common content of a, b and c.
pub fn primitive_part(entries: &[Expr]) -> Result<Vec<Expr>, EngineError> {
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

fn divide_by_content(entries: &[Expr]) -> Result<Vec<Expr>, EngineError> {
    let content = content(entries)?;
    entries
        .iter()
        .map(|e| normal_form(&Expr::over(e.clone(), content.clone())))
        .collect()
}

/// The entries' common factor: the factors of a + z1·b + z2·c (fresh z's) that do not contain
/// the z's, over the common denominator.
pub fn content(entries: &[Expr]) -> Result<Expr, EngineError> {
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
    let atom = expand(&combined)?;
    let rat: RationalPolynomial<_, u16> =
        atom.to_rational_polynomial(&Q, &Z, variables_by_name(&atom));
    let mut content = vec![from_atom(&rat.denominator.to_expression())?];
    content[0] = Expr::over(Expr::int(1), content[0].clone());
    for (factor, mult) in rat.numerator.factor() {
        let f = from_atom(&factor.to_expression())?;
        if !f.symbols().iter().any(|s| s == "z__") {
            content.push(Expr::pow(f, Expr::int(mult as i128)));
        }
    }
    Ok(Expr::mul(content))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trig_moments_follow_the_beta_function() {
        // Checked against direct numeric integration, not a table.
        for p in 0..5u32 {
            for q in 0..5u32 {
                for span in [AngleSpan::Full, AngleSpan::Half, AngleSpan::Quarter] {
                    let upper = span.upper();
                    let n = 20_000;
                    let h = upper / n as f64;
                    let numeric: f64 = (0..n)
                        .map(|i| {
                            let t = (i as f64 + 0.5) * h;
                            t.cos().powi(p as i32) * t.sin().powi(q as i32) * h
                        })
                        .sum();
                    let exact = trig_moment(p, q, span).eval(&|_| None).unwrap();
                    assert!(
                        (numeric - exact).abs() < 1e-7,
                        "p={p} q={q} {span:?}: {numeric} vs {exact}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_root_is_measured_by_the_number_the_engine_would_fold() {
        // Two 17-digit sides: each number under the root is small, the sum of their squares
        // (32 digits) is not. The engine factored such sums for over ten minutes before they
        // were measured whole.
        let parse = |t: &str| crate::cas::parse(t).unwrap().expr;
        let e = parse(
            "sqrt((10000000000000001/10000000000000000)^2 + (10000000000000003/10000000000000000)^2)",
        );
        assert_eq!(large_number_under_a_root(&e, false), Some(32));
        let big = parse("sqrt(10000000000001^4/10000000000000^4 + 1)");
        assert!(large_number_under_a_root(&big, false).is_some_and(|d| d > MAX_ROOT_DIGITS));
        assert!(matches!(expand(&big), Err(EngineError::LargeRoot { .. })));
        // Small sums, and numbers outside any root, pass.
        for ok in [
            "sqrt(1/3 + 2/7)",
            "(1/3 + 2/7)*x^(1/2)",
            "10000000000001^4 + sqrt(2)*x",
        ] {
            assert_eq!(large_number_under_a_root(&parse(ok), false), None, "{ok}");
        }
    }
}
