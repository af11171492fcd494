//! Where an expression in one coordinate vanishes, exactly: the equilibria of an equation of
//! motion. A polynomial in q gives its roots; a polynomial in sin q and cos q is factored, and
//! each factor in sin q alone or cos q alone of degree at most two gives its angles, each with
//! its exact cosine and sine, so that later steps can put it into other expressions without
//! an inverse function ever reaching the engine.

use super::engine::{self, EngineError};
use super::expr::Expr;
use super::polynomial;
use super::trig;

/// The names cos q and sin q take while the expression is factored.
const C: &str = "c__";
const S: &str = "s__";

/// One zero: the coordinate's value and, for an angle, its cosine and sine.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Zero {
    pub value: Expr,
    pub trig: Option<(Expr, Expr)>,
}

impl Zero {
    /// `e` (an expression in q, its sin and its cos) at this zero.
    pub fn put_into(&self, e: &Expr, q: &str) -> Expr {
        match &self.trig {
            None => e.substitute(&|s| (s == q).then(|| self.value.clone())),
            Some((c, s)) => trig::name_trig_of(&trig::expand_multiple_angles(e), q, C, S)
                .substitute(&|name| match name {
                    C => Some(c.clone()),
                    S => Some(s.clone()),
                    _ => None,
                }),
        }
    }
}

/// The zeros found, and the factors whose zeros have no closed form here.
#[derive(Debug, Clone, Default)]
pub struct Zeros {
    pub zeros: Vec<Zero>,
    pub unsolved: Vec<Expr>,
}

/// The zeros of `e` in the coordinate `q`, every other symbol a parameter (factors in the
/// parameters alone are taken to be non-zero).
pub fn zeros(e: &Expr, q: &str) -> Result<Zeros, EngineError> {
    let expanded = trig::reduce_sin_powers(&trig::expand_multiple_angles(e));
    let named = trig::name_trig_of(&expanded, q, C, S);
    let symbols = named.symbols();
    let has = |name: &str| symbols.iter().any(|s| s == name);
    let mut out = Zeros::default();
    if !has(C) && !has(S) {
        let roots = polynomial::roots(e, q)?;
        out.zeros = roots
            .roots
            .into_iter()
            .map(|(value, _)| Zero { value, trig: None })
            .collect();
        out.unsolved = roots.unsolved.into_iter().map(|(f, _)| f).collect();
        return Ok(out);
    }
    if has(q) {
        out.unsolved.push(e.clone());
        return Ok(out);
    }
    let (factors, denominator) = engine::numerator_factors(&named)?;
    for f in factors {
        let symbols = f.symbols();
        let (has_c, has_s) = (
            symbols.iter().any(|s| s == C),
            symbols.iter().any(|s| s == S),
        );
        let found = match (has_c, has_s) {
            (false, false) => continue,
            (true, false) => cos_zeros(&f)?,
            (false, true) => sin_zeros(&f)?,
            (true, true) => None,
        };
        match found {
            Some(zs) => {
                for z in zs {
                    // Where the denominator vanishes too, the expression has a pole or is 0/0
                    // (θ = π in a²(1 − cos θ)/(1 + cos θ)): not a zero.
                    let pole = match &z.trig {
                        Some((c, s)) => {
                            engine::simplify(&denominator.substitute(&|name| match name {
                                C => Some(c.clone()),
                                S => Some(s.clone()),
                                _ => None,
                            }))?
                            .is_zero()
                        }
                        None => false,
                    };
                    if !pole && !out.zeros.contains(&z) {
                        out.zeros.push(z);
                    }
                }
            }
            None => out.unsolved.push(back(&f, q)),
        }
    }
    Ok(out)
}

/// A factor put back in terms of cos q and sin q, for a message.
fn back(f: &Expr, q: &str) -> Expr {
    f.substitute(&|name| match name {
        C => Some(Expr::call("cos", Expr::sym(q))),
        S => Some(Expr::call("sin", Expr::sym(q))),
        _ => None,
    })
}

/// The angles of a factor in cos q alone (degree ≤ 2): for each root c, ±acos c.
fn cos_zeros(f: &Expr) -> Result<Option<Vec<Zero>>, EngineError> {
    let roots = polynomial::roots(f, C)?;
    if !roots.unsolved.is_empty() {
        return Ok(None);
    }
    let mut out = Vec::new();
    for (c, _) in roots.roots {
        let c = engine::simplify(&c)?;
        let zero = |value: Expr, s: Expr| Zero {
            value,
            trig: Some((c.clone(), s)),
        };
        let half_pi = Expr::mul(vec![Expr::rat(1, 2), Expr::sym("pi")]);
        if c.is_one() {
            out.push(zero(Expr::int(0), Expr::int(0)));
        } else if c == Expr::int(-1) {
            out.push(zero(Expr::sym("pi"), Expr::int(0)));
        } else if c.is_zero() {
            out.push(zero(half_pi.clone(), Expr::int(1)));
            out.push(zero(Expr::negate(half_pi), Expr::int(-1)));
        } else {
            let s = complement(&c)?;
            let acos = Expr::call("acos", c.clone());
            out.push(zero(acos.clone(), s.clone()));
            out.push(zero(Expr::negate(acos), Expr::negate(s)));
        }
    }
    Ok(Some(out))
}

/// The angles of a factor linear in sin q alone: for its root s, asin s and π − asin s.
fn sin_zeros(f: &Expr) -> Result<Option<Vec<Zero>>, EngineError> {
    let terms = engine::coefficients(f, S)?;
    let coeff = |k: u32| {
        terms
            .iter()
            .find(|(p, _)| *p == k)
            .map(|(_, c)| c.clone())
            .unwrap_or_else(|| Expr::int(0))
    };
    if terms.iter().any(|(p, _)| *p > 1) {
        return Ok(None);
    }
    let s = engine::simplify(&Expr::negate(Expr::over(coeff(0), coeff(1))))?;
    let zero = |value: Expr, c: Expr| Zero {
        value,
        trig: Some((c, s.clone())),
    };
    let half_pi = Expr::mul(vec![Expr::rat(1, 2), Expr::sym("pi")]);
    Ok(Some(if s.is_zero() {
        vec![
            zero(Expr::int(0), Expr::int(1)),
            zero(Expr::sym("pi"), Expr::int(-1)),
        ]
    } else if s.is_one() {
        vec![zero(half_pi, Expr::int(0))]
    } else if s == Expr::int(-1) {
        vec![zero(Expr::negate(half_pi), Expr::int(0))]
    } else {
        let c = complement(&s)?;
        let asin = Expr::call("asin", s.clone());
        vec![
            zero(asin.clone(), c.clone()),
            zero(Expr::minus(Expr::sym("pi"), asin), Expr::negate(c)),
        ]
    }))
}

/// √(1 − x²), simplified: the sine of the angle whose cosine is x, or the other way round.
fn complement(x: &Expr) -> Result<Expr, EngineError> {
    engine::simplify(&Expr::pow(
        Expr::minus(Expr::int(1), Expr::pow(x.clone(), Expr::int(2))),
        Expr::rat(1, 2),
    ))
}
