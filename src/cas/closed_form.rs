//! Cardano's and Ferrari's closed forms: the real roots of a cubic or a quartic whose
//! coefficients hold parameters. Which form is real depends on the sign of the discriminant, so
//! the form is chosen at the scene's values; each root is then exact wherever it is real.

use super::engine::{EngineError, coefficients, simplify};
use super::expr::Expr;
use super::polynomial;
use super::rational::Rational;
use std::collections::BTreeMap;

/// What a closed form could not be chosen for.
#[derive(Debug, Clone, PartialEq)]
pub enum NoClosedForm {
    /// Degree five or more, or below three (those are factored, not solved here).
    Degree(u32),
    /// A coefficient's sign decides the form, and it has no finite value at the scene's values.
    NoValue(Expr),
}

/// The real roots at `values` of an irreducible cubic or quartic in `var`, in closed form: the
/// trigonometric form for a cubic with three real roots, Cardano's real cube roots for one,
/// Ferrari's with a positive root of the resolvent cubic for a quartic.
pub fn real_roots(
    poly: &Expr,
    var: &str,
    values: &BTreeMap<String, f64>,
) -> Result<Result<Vec<Expr>, NoClosedForm>, EngineError> {
    let terms = coefficients(poly, var)?;
    let degree = terms.iter().map(|(k, _)| *k).max().unwrap_or(0);
    let mut c = vec![Expr::int(0); degree as usize + 1];
    for (k, coeff) in terms {
        c[k as usize] = coeff;
    }
    match degree {
        3 => cubic(&c, values),
        4 => quartic(&c, values),
        d => Ok(Err(NoClosedForm::Degree(d))),
    }
}

/// `e`'s value at the scene's values, if finite.
fn value(e: &Expr, values: &BTreeMap<String, f64>) -> Result<f64, NoClosedForm> {
    e.eval(&|s| values.get(s).copied())
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| NoClosedForm::NoValue(e.clone()))
}

/// `e`'s exact value at the scene's values, when it is a rational function of them.
fn exact_at(e: &Expr, values: &BTreeMap<String, f64>) -> Option<Rational> {
    e.eval_rational(&|s| values.get(s).and_then(|x| Rational::from_f64(*x)))
}

fn sqrt(e: Expr) -> Expr {
    Expr::pow(e, Expr::rat(1, 2))
}

fn div(a: Expr, b: Expr) -> Result<Expr, EngineError> {
    simplify(&Expr::over(a, b))
}

/// c₃x³ + c₂x² + c₁x + c₀ with x = t − c₂/(3c₃): t³ + p t + q. Three real roots (4p³ + 27q² ≤ 0)
/// are 2√(−p/3) cos((φ − 2πk)/3) with cos φ = −(q/2)(−p/3)^(−3/2); one is ∛A − p/(3∛A) with
/// A = −q/2 + √(q²/4 + p³/27), or its mirror −∛B + p/(3∛B), B = q/2 + √(…), whichever radicand
/// is positive.
fn cubic(
    c: &[Expr],
    values: &BTreeMap<String, f64>,
) -> Result<Result<Vec<Expr>, NoClosedForm>, EngineError> {
    let (a, b, k, d) = (&c[3], &c[2], &c[1], &c[0]);
    let p = div(
        Expr::minus(
            Expr::mul(vec![Expr::int(3), a.clone(), k.clone()]),
            Expr::pow(b.clone(), Expr::int(2)),
        ),
        Expr::mul(vec![Expr::int(3), Expr::pow(a.clone(), Expr::int(2))]),
    )?;
    let q = div(
        Expr::add(vec![
            Expr::mul(vec![Expr::int(2), Expr::pow(b.clone(), Expr::int(3))]),
            Expr::mul(vec![Expr::int(-9), a.clone(), b.clone(), k.clone()]),
            Expr::mul(vec![
                Expr::int(27),
                Expr::pow(a.clone(), Expr::int(2)),
                d.clone(),
            ]),
        ]),
        Expr::mul(vec![Expr::int(27), Expr::pow(a.clone(), Expr::int(3))]),
    )?;
    let shift = div(
        Expr::negate(b.clone()),
        Expr::mul(vec![Expr::int(3), a.clone()]),
    )?;
    let (pv, qv) = match (value(&p, values), value(&q, values)) {
        (Ok(pv), Ok(qv)) => (pv, qv),
        (Err(e), _) | (_, Err(e)) => return Ok(Err(e)),
    };
    let minus_p_third = simplify(&Expr::over(Expr::negate(p.clone()), Expr::int(3)))?;
    // The signs that choose the form, exactly where p and q are rational at the scene's values
    // (each f64 taken as the fraction it is): in double precision 2 + 10⁻¹⁷ is 2, and a double
    // root that has split into a complex pair was taken for two real roots, acos(−1 − ε) and all.
    let (three_real, q_positive) = match (exact_at(&p, values), exact_at(&q, values)) {
        (Some(pe), Some(qe)) => {
            let discriminant = Rational::int(4)
                .mul(&pe.pow(3).unwrap_or(Rational::ZERO))
                .add(&Rational::int(27).mul(&qe.mul(&qe)));
            (
                pe.is_negative() && !discriminant.is_positive(),
                qe.is_positive(),
            )
        }
        _ => (
            pv < 0.0 && 4.0 * pv.powi(3) + 27.0 * qv * qv <= 0.0,
            qv > 0.0,
        ),
    };
    let roots = if three_real {
        trigonometric_roots(&q, &minus_p_third, &shift)
    } else {
        vec![cardano_root(&p, &q, shift, q_positive)?]
    };
    Ok(Ok(roots))
}

/// Three real roots, in Viète's trigonometric form: shift + 2√(−p/3) cos((φ − 2πk)/3), with
/// cos φ = −(q/2)(−p/3)^(−3/2).
fn trigonometric_roots(q: &Expr, minus_p_third: &Expr, shift: &Expr) -> Vec<Expr> {
    // Left as −(q/2)·(−p/3)^(−3/2): expanded, each term would repeat the power.
    let cos_phi = Expr::mul(vec![
        Expr::rat(-1, 2),
        q.clone(),
        Expr::pow(minus_p_third.clone(), Expr::rat(-3, 2)),
    ]);
    let phi = Expr::call("acos", cos_phi);
    (0..3)
        .map(|k| {
            let angle = Expr::over(
                Expr::minus(
                    phi.clone(),
                    Expr::mul(vec![Expr::int(2 * k), Expr::sym("pi")]),
                ),
                Expr::int(3),
            );
            Expr::add(vec![
                shift.clone(),
                Expr::mul(vec![
                    Expr::int(2),
                    sqrt(minus_p_third.clone()),
                    Expr::call("cos", angle),
                ]),
            ])
        })
        .collect()
}

/// The one real root, by Cardano's formula, with the sign that q's sign chooses so that the two
/// terms under the cube root do not cancel.
fn cardano_root(p: &Expr, q: &Expr, shift: Expr, q_positive: bool) -> Result<Expr, EngineError> {
    let sign = if q_positive { -1 } else { 1 };
    let radicand = simplify(&Expr::add(vec![
        Expr::over(Expr::pow(q.clone(), Expr::int(2)), Expr::int(4)),
        Expr::over(Expr::pow(p.clone(), Expr::int(3)), Expr::int(27)),
    ]))?;
    let under_cube = Expr::add(vec![
        Expr::mul(vec![Expr::rat(-sign, 2), q.clone()]),
        sqrt(radicand),
    ]);
    let u = Expr::pow(under_cube, Expr::rat(1, 3));
    let t = Expr::minus(
        u.clone(),
        Expr::over(p.clone(), Expr::mul(vec![Expr::int(3), u])),
    );
    Ok(Expr::add(vec![shift, Expr::mul(vec![Expr::int(sign), t])]))
}

/// c₄x⁴ + … + c₀ with x = y − c₃/(4c₄): y⁴ + p y² + q y + r. With q = 0 a quadratic in y²;
/// otherwise y = (±₁√(2m) ±₂ √(−(2p + 2m ±₁ 2q/√(2m))))/2 for a positive root m of the
/// resolvent 8m³ + 8p m² + (2p² − 8r) m − q² (one exists: it is −q² < 0 at m = 0). The roots
/// real at the scene's values are kept.
fn quartic(
    c: &[Expr],
    values: &BTreeMap<String, f64>,
) -> Result<Result<Vec<Expr>, NoClosedForm>, EngineError> {
    let [b, k, d, e] = [3, 2, 1, 0].map(|i| Expr::over(c[i].clone(), c[4].clone()));
    let pow = |x: &Expr, n: i128| Expr::pow(x.clone(), Expr::int(n));
    let p = simplify(&Expr::add(vec![
        k.clone(),
        Expr::mul(vec![Expr::rat(-3, 8), pow(&b, 2)]),
    ]))?;
    let q = simplify(&Expr::add(vec![
        d.clone(),
        Expr::mul(vec![Expr::rat(-1, 2), b.clone(), k.clone()]),
        Expr::mul(vec![Expr::rat(1, 8), pow(&b, 3)]),
    ]))?;
    let r = simplify(&Expr::add(vec![
        e,
        Expr::mul(vec![Expr::rat(-1, 4), b.clone(), d]),
        Expr::mul(vec![Expr::rat(1, 16), pow(&b, 2), k]),
        Expr::mul(vec![Expr::rat(-3, 256), pow(&b, 4)]),
    ]))?;
    let shift = simplify(&Expr::mul(vec![Expr::rat(-1, 4), b]))?;
    let mut ys: Vec<Expr> = Vec::new();
    if q.is_zero() {
        // y² = (−p ± √(p² − 4r))/2.
        let root = sqrt(simplify(&Expr::minus(
            pow(&p, 2),
            Expr::mul(vec![Expr::int(4), r.clone()]),
        ))?);
        for s in [-1, 1] {
            let square = Expr::over(
                Expr::add(vec![
                    Expr::negate(p.clone()),
                    Expr::mul(vec![Expr::int(s), root.clone()]),
                ]),
                Expr::int(2),
            );
            ys.push(Expr::negate(sqrt(square.clone())));
            ys.push(sqrt(square));
        }
    } else {
        let m = match resolvent_root(&p, &q, &r, values)? {
            Ok(m) => m,
            Err(e) => return Ok(Err(e)),
        };
        let two_m = sqrt(simplify(&Expr::mul(vec![Expr::int(2), m.clone()]))?);
        for s1 in [-1, 1] {
            let inner = Expr::negate(Expr::add(vec![
                Expr::mul(vec![Expr::int(2), p.clone()]),
                Expr::mul(vec![Expr::int(2), m.clone()]),
                Expr::over(Expr::mul(vec![Expr::int(2 * s1), q.clone()]), two_m.clone()),
            ]));
            for s2 in [-1, 1] {
                ys.push(Expr::over(
                    Expr::add(vec![
                        Expr::mul(vec![Expr::int(s1), two_m.clone()]),
                        Expr::mul(vec![Expr::int(s2), sqrt(inner.clone())]),
                    ]),
                    Expr::int(2),
                ));
            }
        }
    }
    let mut roots = Vec::new();
    for y in ys {
        let x = Expr::add(vec![shift.clone(), y]);
        if value(&x, values).is_ok() {
            roots.push(x);
        }
    }
    Ok(Ok(roots))
}

/// The largest root m of the resolvent cubic, positive at the scene's values: a rational
/// factor's root when the engine finds one, else the cubic's closed form.
fn resolvent_root(
    p: &Expr,
    q: &Expr,
    r: &Expr,
    values: &BTreeMap<String, f64>,
) -> Result<Result<Expr, NoClosedForm>, EngineError> {
    const M: &str = "m__resolvent";
    let m = Expr::sym(M);
    let resolvent = Expr::add(vec![
        Expr::mul(vec![Expr::int(8), Expr::pow(m.clone(), Expr::int(3))]),
        Expr::mul(vec![
            Expr::int(8),
            p.clone(),
            Expr::pow(m.clone(), Expr::int(2)),
        ]),
        Expr::mul(vec![
            Expr::minus(
                Expr::mul(vec![Expr::int(2), Expr::pow(p.clone(), Expr::int(2))]),
                Expr::mul(vec![Expr::int(8), r.clone()]),
            ),
            m,
        ]),
        Expr::negate(Expr::pow(q.clone(), Expr::int(2))),
    ]);
    let factored = polynomial::roots(&resolvent, M)?;
    let mut candidates: Vec<Expr> = factored.roots.into_iter().map(|(m, _)| m).collect();
    for (factor, _) in factored.unsolved {
        match real_roots(&factor, M, values)? {
            Ok(found) => candidates.extend(found),
            Err(e) => return Ok(Err(e)),
        }
    }
    let mut best: Option<(f64, Expr)> = None;
    for m in candidates {
        let v = match value(&m, values) {
            Ok(v) => v,
            Err(_) => continue,
        };
        if v > 0.0 && best.as_ref().is_none_or(|(b, _)| v > *b) {
            best = Some((v, m));
        }
    }
    Ok(best
        .map(|(_, m)| m)
        .ok_or_else(|| NoClosedForm::NoValue(q.clone())))
}
