//! A Taylor series of an author's expression about a value, exactly, from its derivatives
//! there; about 0, an expression that is 0/0 there (the slow precession
//! (I₃/ε − √(I₃²/ε² − 4b))/(2c) at ε = 0) is first multiplied by the power of ε it divides by.

use super::DeriveError;
use crate::cas::{self, Expr};

/// The most powers of 1/var an expression may carry into a series about 0.
const MAX_ZERO_ORDER: usize = 4;

/// The most negative power of `var` in `e` (0 if none).
fn pole_order(e: &Expr, var: &str) -> i64 {
    match e {
        Expr::Pow(b, k) if **b == Expr::sym(var) => match &**k {
            Expr::Num(r) if r.is_integer() => (-r.to_i64().unwrap_or(0)).max(0),
            _ => 0,
        },
        Expr::Pow(b, k) => pole_order(b, var).max(pole_order(k, var)),
        Expr::Add(v) | Expr::Mul(v) | Expr::Call(_, v) | Expr::List(v) => {
            v.iter().map(|x| pole_order(x, var)).max().unwrap_or(0)
        }
        _ => 0,
    }
}

/// f^(k)(x0)/k! for k = 0..=n, each simplified with its roots over positive symbols.
fn coefficients(f: &Expr, var: &str, x0: &Expr, n: usize) -> Result<Vec<Expr>, DeriveError> {
    let mut out = Vec::new();
    let mut derivative = f.clone();
    let mut factorial: i128 = 1;
    for k in 0..=n {
        if k > 0 {
            derivative = derivative.diff(var)?;
            factorial *= k as i128;
        }
        let at = derivative.substitute(&|s| (s == var).then(|| x0.clone()));
        let at = cas::roots_over_positive(&cas::simplify(&at)?)?;
        out.push(cas::simplify(&Expr::mul(vec![
            Expr::rat(1, factorial),
            at,
        ]))?);
    }
    Ok(out)
}

/// The Taylor polynomial of `f` in `var` about `x0` to `order`, simplified. About 0, an
/// expression with powers of 1/var (once square roots are taken over positive symbols) is
/// multiplied by var^m first, and its series divided by it after: the first m coefficients must
/// vanish, else it has a pole there.
pub fn series(f: &Expr, var: &str, x0: &Expr, order: u32) -> Result<Expr, DeriveError> {
    let order = order as usize;
    let f = cas::roots_over_positive(f)?;
    let m = if x0.is_zero() {
        pole_order(&f, var) as usize
    } else {
        0
    };
    if m > MAX_ZERO_ORDER {
        return Err(DeriveError::NotDerivable(format!(
            "the expression has 1/{var}^{m} in it: no series about {var} = 0 here"
        )));
    }
    let g = cas::simplify(&Expr::mul(vec![
        Expr::pow(Expr::sym(var), Expr::int(m as i128)),
        f.clone(),
    ]))?;
    let g = cas::roots_over_positive(&g)?;
    if pole_order(&g, var) > 0 {
        return Err(DeriveError::NotDerivable(format!(
            "`{var}` stays in a denominator: no Taylor series about {var} = {}",
            x0.to_text()
        )));
    }
    let c = coefficients(&g, var, x0, order + m)?;
    if let Some(k) = c[..m].iter().position(|c| !c.is_zero()) {
        return Err(DeriveError::NotDerivable(format!(
            "the expression has a pole at {var} = {} (it grows like 1/{var}^{}): no Taylor \
             series there",
            x0.to_text(),
            m - k
        )));
    }
    let h = Expr::minus(Expr::sym(var), x0.clone());
    let terms = c[m..]
        .iter()
        .enumerate()
        .map(|(j, c)| Expr::mul(vec![c.clone(), Expr::pow(h.clone(), Expr::int(j as i128))]))
        .collect();
    Ok(cas::simplify(&Expr::add(terms))?)
}
