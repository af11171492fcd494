//! The form a textbook prints: a pass between an exact result and the printers. It never changes
//! a value: a candidate form is kept only when the engine proves it equal to the result with
//! every symbol but the signed ones positive, and the step checks then compare the two at random
//! points.
//!
//! The tidied form (`tidy`) is a rewrite of our own tree: c − c·cos²x as c·sin²x, a negative
//! root of a quotient as the root of its inverse (2π/√(3g/2L) as 2π√(2L/3g)), √X/X as 1/√X, a
//! power of a sum with a common factor split ((a − a cos θ)² as a²(1 − cos θ)²), a sum over a
//! common denominator written over it once, a sum led by a positive term and a negative product
//! with its sign taken into a difference. It is kept when it prints at most a tenth longer. The
//! engine's candidates (the result cancelled, factored, its roots' radicands factored, divided
//! out in a cosine, its terms grouped by their constants) are kept when they print at least a
//! tenth shorter, so that a form is not traded for another of the same length.

use super::engine::{self, EngineError};
use super::expr::Expr;
use super::factor::common_factor;
use super::positive;
use super::print::split_sign;
use super::radical::is_positive;
use super::rational::Rational;
use super::series_form::leading_term;

pub(super) type Positive<'a> = &'a dyn Fn(&str) -> bool;

/// How long a form prints: the characters of the LaTeX a page sets for it, without spaces and
/// `\left`/`\right` (`notation::printed_length`; the engine's side prints no LaTeX).
pub type PrintedLength = fn(&Expr) -> usize;

/// The printed form of `e`: the shortest proven-equal candidate, else `e` itself.
pub fn present(e: &Expr, positive: Positive, length: PrintedLength) -> Result<Expr, EngineError> {
    if matches!(e, Expr::Num(_) | Expr::Sym(_)) || has_list(e) {
        return Ok(e.clone());
    }
    let original = size(e, length);
    let mut candidates = vec![(tidy(e, positive), true)];
    let (simplified, factored) = (engine::simplify(e), engine::factor(e));
    // A series as its leading term times 1 + …, from the result or its factored form: the
    // form a textbook prints, taken first even where its fractions make it a little longer.
    for form in [Some(e.clone()), factored.clone().ok()]
        .into_iter()
        .flatten()
    {
        if let Some(series) = leading_term(&form).map(|s| tidy(&s, positive))
            && size(&series, length) * 2 <= original * 3
            && positive::is_zero(
                &Expr::add(vec![series.clone(), Expr::negate(e.clone())]),
                positive,
            )
            .unwrap_or(false)
        {
            return Ok(series);
        }
    }
    let engine_forms = [
        simplified.clone(),
        factored.clone(),
        simplified.and_then(|s| positive::roots_over_positive(&s, positive)),
        factored.and_then(|f| positive::roots_over_positive(&f, positive)),
        radicands_factored(e),
        apart(e, false),
        apart(e, true),
        grouped(e, positive),
    ];
    for form in engine_forms.into_iter().flatten() {
        // A number taken out of a sum is the printer's to show (3627u/10 − 344u² stays).
        if !matches!(&form, Expr::Mul(f) if f.len() == 2 && matches!(f[1], Expr::Add(_))) {
            candidates.push((tidy(&form, positive), false));
        }
    }
    let mut sized: Vec<(usize, Expr)> = candidates
        .into_iter()
        .filter(|(c, _)| c != e)
        .map(|(c, tidied)| (size(&c, length), c, tidied))
        // The tidied form is what a physicist writes, kept even a little longer: a²(1 − cos θ)²
        // for (a − a cos θ)². The engine's forms are taken where they are clearly shorter.
        .filter(|(n, _, tidied)| {
            if *tidied {
                *n <= original + original / 10 + 2
            } else {
                *n * 10 < original * 9
            }
        })
        .map(|(n, c, _)| (n, c))
        .collect();
    sized.sort_by_key(|(n, _)| *n);
    sized.dedup_by(|a, b| a.1 == b.1);
    for (_, candidate) in sized {
        let difference = Expr::add(vec![candidate.clone(), Expr::negate(e.clone())]);
        if positive::is_zero(&difference, positive).unwrap_or(false) {
            return Ok(candidate);
        }
    }
    Ok(e.clone())
}

/// The printed length of a form (`length`). A sum is measured with its common factor out, as
/// the shortest a printer could set it, whether or not the printer takes it out (it keeps a sum
/// of bracketed terms term by term).
pub(super) fn size(e: &Expr, length: PrintedLength) -> usize {
    let factored = match e {
        Expr::Add(terms) => {
            common_factor(terms).map(|(f, rest)| Expr::mul(vec![f, Expr::Add(rest)]))
        }
        _ => None,
    };
    length(factored.as_ref().unwrap_or(e))
}

fn has_list(e: &Expr) -> bool {
    let mut found = false;
    e.walk(&mut |x| found |= matches!(x, Expr::List(_) | Expr::Index(..)));
    found
}

/// The tree rewrites, bottom up.
pub fn tidy(e: &Expr, positive: Positive) -> Expr {
    match e {
        Expr::Add(terms) => {
            let terms: Vec<Expr> = terms.iter().map(|t| tidy(t, positive)).collect();
            tidy_sum(terms, positive)
        }
        Expr::Mul(factors) => {
            let factors: Vec<Expr> = factors.iter().map(|f| tidy(f, positive)).collect();
            tidy_product(factors)
        }
        Expr::Pow(base, k) => tidy_power(tidy(base, positive), (**k).clone(), positive),
        Expr::Call(f, args) => {
            Expr::Call(f.clone(), args.iter().map(|a| tidy(a, positive)).collect())
        }
        other => other.clone(),
    }
}

fn tidy_sum(terms: Vec<Expr>, positive: Positive) -> Expr {
    let terms = pythagoras(terms);
    if terms.len() == 1 {
        return terms.into_iter().next().unwrap();
    }
    // Terms over a common denominator: written over it once.
    if let Some((factor, rest)) = common_factor(&terms)
        && has_denominator(&factor)
    {
        let rest: Vec<Expr> = rest.iter().map(|t| tidy(t, positive)).collect();
        return tidy_product(vec![factor, tidy_sum(rest, positive)]);
    }
    Expr::Add(positive_first(terms))
}

/// A symbol or a function under a negative power: a fraction's denominator.
fn has_denominator(e: &Expr) -> bool {
    let factors = match e {
        Expr::Mul(v) => v.as_slice(),
        other => std::slice::from_ref(other),
    };
    factors.iter().any(|f| {
        matches!(f, Expr::Pow(b, k)
            if !matches!(b.as_ref(), Expr::Num(_))
            && matches!(k.as_ref(), Expr::Num(r) if r.is_negative()))
    })
}

/// The terms with the first that is not negative moved to the front: g − R w², not −R w² + g.
fn positive_first(mut terms: Vec<Expr>) -> Vec<Expr> {
    if let Some(i) = terms.iter().position(|t| !split_sign(t).0)
        && i > 0
    {
        let t = terms.remove(i);
        terms.insert(0, t);
    }
    terms
}

/// A term and a term that is minus it times cos²x (sin²x) as one term times sin²x (cos²x).
fn pythagoras(mut terms: Vec<Expr>) -> Vec<Expr> {
    'again: loop {
        for j in 0..terms.len() {
            let Some((rest, arg, of)) = without_trig_square(&terms[j]) else {
                continue;
            };
            let minus = key(&Expr::negate(rest));
            if let Some(i) = (0..terms.len()).find(|&i| i != j && key(&terms[i]) == minus) {
                let other = if of == "cos" { "sin" } else { "cos" };
                let square = Expr::pow(Expr::call(other, arg), Expr::int(2));
                terms[i] = Expr::mul(vec![terms[i].clone(), square]);
                terms.remove(j);
                continue 'again;
            }
        }
        return terms;
    }
}

/// A term with one factor cos²x or sin²x taken out: (the rest, x, "cos" or "sin").
fn without_trig_square(term: &Expr) -> Option<(Expr, Expr, &'static str)> {
    let factors = match term {
        Expr::Mul(v) => v.clone(),
        other => vec![other.clone()],
    };
    for (i, f) in factors.iter().enumerate() {
        if let Expr::Pow(b, k) = f
            && let (Expr::Call(name, args), Expr::Num(k)) = (b.as_ref(), k.as_ref())
            && args.len() == 1
            && (name == "cos" || name == "sin")
            && k.is_integer()
            && k.to_i64().is_some_and(|k| k >= 2)
        {
            let of = if name == "cos" { "cos" } else { "sin" };
            let mut rest = factors.clone();
            rest[i] = Expr::pow((**b).clone(), Expr::Num(k.add(&Rational::int(-2))));
            return Some((Expr::mul(rest), args[0].clone(), of));
        }
    }
    None
}

/// A term's coefficient and its factors in a fixed order, so that equal terms compare equal.
fn key(term: &Expr) -> (Rational, Vec<String>) {
    let factors = match term {
        Expr::Mul(v) => v.as_slice(),
        other => std::slice::from_ref(other),
    };
    let mut coefficient = Rational::ONE;
    let mut rest = Vec::new();
    for f in factors {
        match f {
            Expr::Num(r) => coefficient = coefficient.mul(r),
            other => rest.push(other.to_text()),
        }
    }
    rest.sort();
    (coefficient, rest)
}

fn tidy_product(factors: Vec<Expr>) -> Expr {
    let factors = match Expr::mul(super::trig_pairs::pythagorean_pairs(factors)) {
        Expr::Mul(f) => f,
        other => return other,
    };
    // Functions after the symbols they multiply: g l M cos θ.
    let (mut factors, calls): (Vec<Expr>, Vec<Expr>) =
        merge_roots(factors).into_iter().partition(|f| !is_call(f));
    factors.extend(calls);
    // A denominator of more negative terms than positive ones: its sign taken out,
    // −mg cos α sin α/(M + m sin²α), not mg cos α sin α/(−M − m sin²α); a difference
    // (Ω₂ − Ω₁) is left as written.
    for f in factors.iter_mut() {
        if let Expr::Pow(b, k) = f
            && let (Expr::Add(t), Expr::Num(k)) = (b.as_ref(), k.as_ref())
            && k.is_negative()
            && k.to_i64().is_some_and(|k| k % 2 != 0)
            && 2 * t.iter().filter(|x| split_sign(x).0).count() > t.len()
        {
            let negated = t.iter().map(|x| Expr::negate(x.clone())).collect();
            *f = Expr::mul(vec![
                Expr::int(-1),
                Expr::pow(Expr::Add(positive_first(negated)), Expr::Num(k.clone())),
            ]);
        }
    }
    let product = Expr::mul(factors);
    let Expr::Mul(mut factors) = product else {
        return product;
    };
    // A negative product with a sum among its factors that has more negative terms than
    // positive ones (or as many, and a negative first): the sign taken into it.
    if let Expr::Num(c) = factors[0].clone()
        && c.is_negative()
        && let Some(i) = factors
            .iter()
            .position(|f| matches!(f, Expr::Add(t) if mostly_negative(t)))
    {
        let Expr::Add(terms) = &factors[i] else {
            unreachable!()
        };
        let negated = terms.iter().map(|t| Expr::negate(t.clone())).collect();
        factors[i] = Expr::Add(positive_first(negated));
        factors[0] = Expr::Num(c.negated());
        return Expr::mul(factors);
    }
    Expr::Mul(factors)
}

/// A function or a power of one: cos θ, sin²θ.
fn is_call(f: &Expr) -> bool {
    match f {
        Expr::Call(..) => true,
        Expr::Pow(b, _) => matches!(b.as_ref(), Expr::Call(..)),
        _ => false,
    }
}

/// At least as many negative terms as positive ones: −x(c − 1) is x(1 − c), one sign fewer.
fn mostly_negative(terms: &[Expr]) -> bool {
    let negative = terms.iter().filter(|t| split_sign(t).0).count();
    2 * negative >= terms.len()
}

/// √X beside X⁻¹ (each factor of X under a power −1) as X^(−1/2): I₃ω₃√(Mgl)/(Mgl) = I₃ω₃/√(Mgl).
fn merge_roots(mut factors: Vec<Expr>) -> Vec<Expr> {
    for i in 0..factors.len() {
        let Expr::Pow(base, k) = &factors[i] else {
            continue;
        };
        if **k != Expr::rat(1, 2) {
            continue;
        }
        let parts: Vec<Expr> = match base.as_ref() {
            Expr::Mul(v) => v.clone(),
            Expr::Sym(_) => vec![(**base).clone()],
            _ => continue,
        };
        if parts.iter().any(|p| !matches!(p, Expr::Sym(_))) {
            continue;
        }
        // X⁻¹ as one factor, or each factor of X under a power −1.
        let whole = Expr::pow((**base).clone(), Expr::int(-1));
        if let Some(j) = factors.iter().position(|f| *f == whole) {
            factors[i] = Expr::pow((**base).clone(), Expr::rat(-1, 2));
            factors.remove(j);
            return factors;
        }
        let inverse = |p: &Expr| Expr::pow(p.clone(), Expr::int(-1));
        let at: Option<Vec<usize>> = parts
            .iter()
            .map(|p| factors.iter().position(|f| *f == inverse(p)))
            .collect();
        let Some(mut at) = at else { continue };
        let merged = Expr::pow((**base).clone(), Expr::rat(-1, 2));
        factors[i] = merged;
        at.sort_unstable();
        for j in at.into_iter().rev() {
            factors.remove(j);
        }
        return factors;
    }
    factors
}

/// A sum's terms grouped by their constants (the factors in positive symbols), each group
/// factored: ½I₁(θ'² + φ'² sin²θ) + ½I₃(ψ' + φ' cos θ)² − Mgl cos θ.
fn grouped(e: &Expr, positive: Positive) -> Result<Expr, EngineError> {
    let Expr::Add(terms) = e else {
        return Err(EngineError::NotRational { expr: e.to_text() });
    };
    let constants = |t: &Expr| -> Vec<String> {
        let factors = match t {
            Expr::Mul(v) => v.as_slice(),
            other => std::slice::from_ref(other),
        };
        let mut names: Vec<String> = factors
            .iter()
            .filter(|f| match f {
                Expr::Sym(s) => positive(s),
                Expr::Pow(b, _) => matches!(b.as_ref(), Expr::Sym(s) if positive(s)),
                _ => false,
            })
            .map(|f| f.to_text())
            .collect();
        names.sort();
        names
    };
    let mut groups: Vec<(Vec<String>, Vec<Expr>)> = Vec::new();
    for t in terms {
        let key = constants(t);
        match groups.iter_mut().find(|(k, _)| *k == key) {
            Some((_, members)) => members.push(t.clone()),
            None => groups.push((key, vec![t.clone()])),
        }
    }
    if groups.len() == terms.len() {
        return Err(EngineError::NotRational { expr: e.to_text() });
    }
    let parts = groups
        .into_iter()
        .map(|(_, members)| match members.as_slice() {
            [one] => Ok(one.clone()),
            _ => engine::factor(&Expr::add(members)),
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Expr::Add(parts))
}

/// The name a kernel (cos θ, sin θ) takes while a fraction is divided out in it.
const KERNEL: &str = "kernel__";

/// A fraction N/D whose denominator is a polynomial in one sine or cosine c, as the quotient
/// and the remainder's fraction: N = Q D + R with R of lower degree in c. With `in_c_only`,
/// only the quotient's terms in c are taken out, so that (A(1 − c) + B c(1 + c))/(2I(1 + c)) is
/// A(1 − c)/(2I(1 + c)) + B c/(2I).
fn apart(e: &Expr, in_c_only: bool) -> Result<Expr, EngineError> {
    let (n, d) = engine::fraction(e)?;
    let not_apart = || EngineError::NotRational { expr: e.to_text() };
    let mut kernels = Vec::new();
    d.walk(&mut |x| {
        if matches!(x, Expr::Call(f, _) if f == "cos" || f == "sin") && !kernels.contains(x) {
            kernels.push(x.clone());
        }
    });
    let [kernel] = kernels.as_slice() else {
        return Err(not_apart());
    };
    let named = |x: &Expr| replace(x, kernel, &Expr::sym(KERNEL));
    let (n, d) = (named(&n), named(&d));
    let degree =
        |p: &Expr| -> Result<Vec<(u32, Expr)>, EngineError> { engine::coefficients(p, KERNEL) };
    let top = |cs: &[(u32, Expr)]| cs.iter().max_by_key(|(k, _)| *k).cloned();
    let (Some((dd, lead)), mut rest) = (top(&degree(&d)?), n) else {
        return Err(not_apart());
    };
    if dd == 0 {
        return Err(not_apart());
    }
    let mut quotient = Vec::new();
    while let Some((k, c)) = top(&degree(&rest)?)
        && k >= dd
        && !c.is_zero()
    {
        let term = engine::simplify(&Expr::mul(vec![
            c,
            Expr::pow(lead.clone(), Expr::int(-1)),
            Expr::pow(Expr::sym(KERNEL), Expr::int(i128::from(k - dd))),
        ]))?;
        rest = engine::simplify(&Expr::minus(rest, Expr::mul(vec![term.clone(), d.clone()])))?;
        quotient.push(term);
    }
    if in_c_only {
        // The quotient's terms free of c go back over the denominator.
        let (free, with_c): (Vec<Expr>, Vec<Expr>) = quotient
            .iter()
            .flat_map(|q| match q {
                Expr::Add(v) => v.clone(),
                other => vec![other.clone()],
            })
            .partition(|t| !t.symbols().iter().any(|s| s == KERNEL));
        rest = engine::simplify(&Expr::add(vec![
            rest,
            Expr::mul(vec![Expr::add(free), d.clone()]),
        ]))?;
        quotient = with_c;
    }
    if quotient.is_empty() || rest.is_zero() {
        return Err(not_apart());
    }
    let remainder = engine::factor(&Expr::mul(vec![rest, Expr::pow(d, Expr::int(-1))]))?;
    let back = |x: &Expr| x.substitute(&|s| (s == KERNEL).then(|| kernel.clone()));
    let mut terms: Vec<Expr> = quotient.iter().map(back).collect();
    terms.insert(0, back(&remainder));
    Ok(Expr::add(terms))
}

/// `e` with every occurrence of `from` replaced by `to`.
fn replace(e: &Expr, from: &Expr, to: &Expr) -> Expr {
    if e == from {
        return to.clone();
    }
    let walk = |xs: &[Expr]| xs.iter().map(|x| replace(x, from, to)).collect();
    match e {
        Expr::Add(v) => Expr::add(walk(v)),
        Expr::Mul(v) => Expr::mul(walk(v)),
        Expr::Pow(b, k) => Expr::pow(replace(b, from, to), replace(k, from, to)),
        Expr::Call(f, args) => Expr::Call(f.clone(), walk(args)),
        other => other.clone(),
    }
}

/// Each root's radicand cancelled and factored by the engine, its square factors left in:
/// √(5g/(7(R − r))) where the mass divides out.
fn radicands_factored(e: &Expr) -> Result<Expr, EngineError> {
    let walk = |xs: &[Expr]| {
        xs.iter()
            .map(radicands_factored)
            .collect::<Result<Vec<_>, _>>()
    };
    Ok(match e {
        Expr::Pow(base, k) if matches!(k.as_ref(), Expr::Num(r) if !r.is_integer()) => {
            let base = radicands_factored(base)?;
            let factored = engine::factor(&base).unwrap_or(base);
            Expr::pow(factored, (**k).clone())
        }
        Expr::Pow(base, k) => Expr::pow(radicands_factored(base)?, (**k).clone()),
        Expr::Add(v) => Expr::add(walk(v)?),
        Expr::Mul(v) => Expr::mul(walk(v)?),
        Expr::Call(f, args) => Expr::Call(f.clone(), walk(args)?),
        other => other.clone(),
    })
}

fn tidy_power(base: Expr, k: Expr, positive: Positive) -> Expr {
    let Expr::Num(r) = &k else {
        return Expr::pow(base, k);
    };
    // A negative root of a positive quotient: the root of its inverse.
    if r.is_negative() && !r.is_integer() && is_quotient(&base) && is_positive(&base, positive) {
        let inverse = tidy(&invert(&base), positive);
        return Expr::pow(inverse, Expr::Num(r.negated()));
    }
    // An integer power of a product: each factor's power, (2I₁)⁻¹ as 1/(2 I₁).
    if r.is_integer()
        && let Expr::Mul(factors) = &base
    {
        let power = |f: &Expr| match (f, r.to_i64()) {
            (Expr::Num(n), Some(k)) if k.abs() <= 8 => n
                .pow(k)
                .map_or_else(|| Expr::pow(f.clone(), Expr::int(k.into())), Expr::Num),
            _ => Expr::pow(f.clone(), k.clone()),
        };
        let powers = factors.iter().map(power);
        return Expr::mul(powers.collect());
    }
    // An integer power of a sum with a common factor: the factor's power times the sum's.
    if r.is_integer()
        && let Expr::Add(terms) = &base
        && let Some((factor, rest)) = common_factor(terms)
    {
        let rest = tidy_sum(rest, positive);
        return Expr::mul(vec![
            tidy_power(factor, k.clone(), positive),
            Expr::pow(rest, k.clone()),
        ]);
    }
    Expr::pow(base, k)
}

/// A product with a factor under a negative power, or a fraction.
fn is_quotient(e: &Expr) -> bool {
    match e {
        Expr::Num(r) => !r.is_integer(),
        Expr::Mul(v) => v.iter().any(is_quotient),
        Expr::Pow(_, k) => matches!(k.as_ref(), Expr::Num(r) if r.is_negative()),
        _ => false,
    }
}

fn invert(e: &Expr) -> Expr {
    match e {
        Expr::Num(r) => r.recip().map_or_else(|| e.clone(), Expr::Num),
        Expr::Mul(v) => Expr::mul(v.iter().map(invert).collect()),
        Expr::Pow(b, k) => Expr::pow((**b).clone(), Expr::negate((**k).clone())),
        other => Expr::pow(other.clone(), Expr::int(-1)),
    }
}

#[cfg(test)]
#[path = "present_tests.rs"]
mod tests;
