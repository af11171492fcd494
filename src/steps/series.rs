//! `series = "…"`, `about = { x = "0" }`, `order = n`: a Taylor series to the n-th power.
//!
//! - Exact rule: `series`, from the derivatives at the point.
//! - Numeric route: the expression as written against its series at four steps h, h/2, h/4,
//!   h/8 from the point, the remainder shrinking like h^(order+1) (`remainder_check`).

use super::check::{CheckError, StepCheck, at};
use super::{Checking, Context, Rule};
use crate::base::format::text_number;
use crate::cas::{self, Expr};
use crate::derive::DeriveError;
use crate::derive::step_names::{StepResult, expand_names};
use crate::notation::Formula;
use crate::scene::Scene;
use crate::scene::operations::Series;

impl Rule for Series {
    fn derive(&self, cx: Context, _: &mut Option<Formula>) -> Result<StepResult, DeriveError> {
        let of: &Expr = &self.of;
        let var: &str = &self.var;
        let about: &Expr = &self.about;
        let order: u32 = self.order;
        let f = expand_names(cx.scene, cx.d, cx.step, of).map_err(DeriveError::Step)?;
        let x0 = expand_names(cx.scene, cx.d, cx.step, about).map_err(DeriveError::Step)?;
        Ok(StepResult::Expr(series(&f, var, &x0, order)?))
    }

    fn check(&self, cx: Checking, check: &mut StepCheck) -> Result<(), CheckError> {
        let of: &Expr = &self.of;
        let var: &str = &self.var;
        let about: &Expr = &self.about;
        let order: u32 = self.order;
        let StepResult::Expr(s) = cx.result else {
            return Err(CheckError::NotDerived);
        };
        let f = expand_names(cx.scene, cx.d, cx.step, of)?;
        let x0 = at(
            &expand_names(cx.scene, cx.d, cx.step, about)?,
            &cx.scene.values,
        )?;
        remainder_check(cx.scene, &f, s, var, x0, order, check)
    }
}

// A `series` step checked without the engine: the expression as written against its series
// at four steps h, h/2, h/4, h/8 from the point; the remainder must shrink like h^(order+1).

/// The first step from the point, relative to its size (at least 1): small enough to stay
/// inside a root's radius of convergence, as √(I₃² − 4bε²) needs.
const FIRST_STEP: f64 = 1e-2;
/// The remainder's observed order may fall this far short of order + 1: over a halving of h
/// the next-but-one term changes the ratio by O(h).
const ORDER_SLACK: f64 = 0.3;
/// A remainder below this, relative to the expression, is rounding: the series is exact there.
const ROUNDING: f64 = 1e-12;

/// The remainder of `series` against `f` at four steps from x0, and its observed order.
pub(crate) fn remainder_check(
    scene: &Scene,
    f: &Expr,
    series: &Expr,
    var: &str,
    x0: f64,
    order: u32,
    check: &mut StepCheck,
) -> Result<(), CheckError> {
    check.tolerance = ORDER_SLACK;
    let mut point = scene.values.clone();
    let mut remainders = Vec::new();
    let first = FIRST_STEP * x0.abs().max(1.0);
    for k in 0..4 {
        let h = first / f64::from(1 << k);
        point.insert(var.to_string(), x0 + h);
        let (exact, approx) = (at(f, &point)?, at(series, &point)?);
        check.evaluations += 2;
        if !exact.is_finite() || !approx.is_finite() {
            return Err(CheckError::NotFinite { at: x0 + h });
        }
        remainders.push(((exact - approx).abs(), exact.abs()));
    }
    let (r1, f1) = remainders[2];
    let (r2, f2) = remainders[3];
    let observed = if r2 <= ROUNDING * f2.max(1e-300) || r1 <= ROUNDING * f1.max(1e-300) {
        f64::INFINITY
    } else {
        (r1 / r2).log2()
    };
    check.error = (f64::from(order + 1) - observed).max(0.0);
    check.method = format!(
        "the expression as written against the series at {var} = x0 + h for h = {} to \
         {}: the remainder falls {} (order + 1 = {} wanted, {ORDER_SLACK} short allowed)",
        text_number(&format!("{first:e}")),
        text_number(&format!("{:e}", first / 8.0)),
        if observed.is_finite() {
            format!("like h^{observed:.2}")
        } else {
            "to rounding: the series is exact there".to_string()
        },
        order + 1
    );
    Ok(())
}

// A Taylor series of an author's expression about a value, exactly, from its derivatives
// there; about 0, an expression that is 0/0 there (the slow precession
// (I₃/ε − √(I₃²/ε² − 4b))/(2c) at ε = 0) is first multiplied by the power of ε it divides by.

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
