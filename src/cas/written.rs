//! An author's expression printed as written: a `be` step's result in the author's own form,
//! each earlier step put in by the form its page prints (T − V with T and V in as the page
//! states them, ½kl²(sin φ₁ − sin φ₂)² kept a square), not the engine's expansion.

use super::engine::EngineError;
use super::expr::Expr;
use super::positive;
use super::present::{Positive, PrintedLength, present, size};
use super::rational::Rational;

/// `written` as a page prints it: like factors merged and numbers multiplied out in the
/// author's order (nothing expanded), a negated sum's sign taken into its terms, through the
/// presentation pass. It is kept where the engine proves it equal to `exact` and it prints at
/// most a quarter longer than `exact`'s own presented form (a derivative as written can be far
/// longer than its simplified value), which is returned otherwise.
pub fn present_written(
    written: &Expr,
    exact: &Expr,
    positive: Positive,
    length: PrintedLength,
) -> Result<Expr, EngineError> {
    let presented = present(exact, positive, length)?;
    let form = present(&light(written, true), positive, length)?;
    if form == presented || size(&form, length) * 4 > size(&presented, length) * 5 + 8 {
        return Ok(presented);
    }
    let difference = Expr::add(vec![form.clone(), Expr::negate(exact.clone())]);
    match positive::is_zero(&difference, positive) {
        Ok(true) => Ok(form),
        _ => Ok(presented),
    }
}

/// The light normal form, bottom up: a product's numbers multiplied and its powers of one base
/// merged (L²·L⁻¹ as L), a sum's like terms collected, each where it first stands, and
/// −(a + b) as −a − b wherever it stands as a sum's term or alone (T − V printed with V's
/// terms, not minus a bracket). `powers`: (ab)ᵏ as aᵏbᵏ too, for a whole k, so that
/// r²((R − r)φ̇/r)² cancels its r; an author's own expression keeps its bracket.
fn light(e: &Expr, powers: bool) -> Expr {
    let light = |e: &Expr| light(e, powers);
    let e = match e {
        Expr::Add(terms) => sum(terms
            .iter()
            .map(&light)
            .flat_map(|t| negated_sum(&t).unwrap_or_else(|| vec![t]))
            .collect()),
        Expr::Mul(f) => product(f.iter().map(&light).collect()),
        Expr::Pow(b, k) => match (light(b), light(k)) {
            (Expr::Mul(f), Expr::Num(k)) if powers && k.is_integer() => product(
                f.into_iter()
                    .map(|f| Expr::pow(f, Expr::Num(k.clone())))
                    .collect(),
            ),
            (b, k) => Expr::pow(b, k),
        },
        Expr::Call(name, args) => Expr::Call(name.clone(), args.iter().map(&light).collect()),
        other => other.clone(),
    };
    match negated_sum(&e) {
        Some(terms) => sum(terms),
        None => e,
    }
}

/// The terms of −(a + b): −a, −b.
fn negated_sum(e: &Expr) -> Option<Vec<Expr>> {
    match e {
        Expr::Mul(f) if f.len() == 2 && f[0] == Expr::Num(Rational::int(-1)) => match &f[1] {
            Expr::Add(terms) => Some(terms.iter().map(|t| Expr::negate(t.clone())).collect()),
            _ => None,
        },
        _ => None,
    }
}

/// A number and the rest of a term: 3x²/2 as (3/2, x²).
fn coefficient(t: &Expr) -> (Rational, Expr) {
    match t {
        Expr::Num(r) => (r.clone(), Expr::int(1)),
        Expr::Mul(f) => match &f[0] {
            Expr::Num(r) => (r.clone(), Expr::mul(f[1..].to_vec())),
            _ => (Rational::ONE, t.clone()),
        },
        other => (Rational::ONE, other.clone()),
    }
}

/// The author's expression with its names, as a page prints it: like factors merged and
/// numbers multiplied out in the author's order, a sum led by a positive term.
pub fn as_written(e: &Expr, positive: Positive) -> Expr {
    super::present::tidy(&light(e, false), positive)
}

/// Like terms collected where the first of them stands; a number too.
fn sum(terms: Vec<Expr>) -> Expr {
    let mut out: Vec<(Rational, Expr)> = Vec::new();
    for t in terms.into_iter().flat_map(|t| match t {
        Expr::Add(inner) => inner,
        other => vec![other],
    }) {
        let (c, rest) = coefficient(&t);
        match out.iter_mut().find(|(_, r)| *r == rest) {
            Some((k, _)) => *k = k.add(&c),
            None => out.push((c, rest)),
        }
    }
    let terms: Vec<Expr> = out
        .into_iter()
        .filter(|(c, _)| !c.is_zero())
        .map(|(c, rest)| match rest {
            Expr::Num(r) => Expr::Num(c.mul(&r)),
            rest => Expr::mul(vec![Expr::Num(c), rest]),
        })
        .collect();
    match terms.len() {
        0 => Expr::int(0),
        1 => terms.into_iter().next().unwrap_or_else(|| Expr::int(0)),
        _ => Expr::Add(terms),
    }
}

/// Numbers multiplied out and the powers of one base merged, where the first of them stands.
fn product(factors: Vec<Expr>) -> Expr {
    let mut number = Rational::ONE;
    let mut out: Vec<(Expr, Expr)> = Vec::new();
    for f in factors.into_iter().flat_map(|f| match f {
        Expr::Mul(inner) => inner,
        other => vec![other],
    }) {
        let (base, k) = match f {
            Expr::Num(r) => {
                number = number.mul(&r);
                continue;
            }
            Expr::Pow(b, k) => (*b, *k),
            other => (other, Expr::int(1)),
        };
        match out.iter_mut().find(|(b, _)| *b == base) {
            Some((_, sum_k)) => *sum_k = Expr::add(vec![sum_k.clone(), k]),
            None => out.push((base, k)),
        }
    }
    let mut factors = vec![Expr::Num(number)];
    factors.extend(out.into_iter().map(|(b, k)| Expr::pow(b, k)));
    Expr::mul(factors)
}
