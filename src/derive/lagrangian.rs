//! Mechanics of a Lagrangian, exact and unsimplified: the time derivative through the
//! coordinates, the Euler–Lagrange equations, a generalised momentum and the energy function,
//! the equations to first order about rest, and the frequencies of linear equations.
//!
//! A coordinate q is a function of the time t; its rates are the names `q'` and `q''`, so an
//! expression in them is an ordinary expression and the time derivative is the chain rule
//! d/dt f = ∂f/∂t + Σ_q (∂f/∂q · q' + ∂f/∂q' · q'').

use super::DeriveError;
use crate::cas::{self, Expr};
use std::collections::BTreeMap;

/// d/dt of `f` through the coordinates: ∂f/∂t + Σ_q (∂f/∂q · q' + ∂f/∂q' · q''). A second
/// rate in `f` would need a third, which the language does not have.
pub fn time_derivative(
    f: &Expr,
    coordinates: &BTreeMap<String, String>,
) -> Result<Expr, DeriveError> {
    let mut terms = vec![f.diff("t")?];
    for q in coordinates.keys() {
        let (rate, accel) = (format!("{q}'"), format!("{q}''"));
        if f.symbols().contains(&accel) {
            return Err(DeriveError::NotDerivable(format!(
                "the time derivative of an expression in `{accel}` needs a third derivative"
            )));
        }
        terms.push(Expr::mul(vec![f.diff(q)?, Expr::sym(&rate)]));
        terms.push(Expr::mul(vec![f.diff(&rate)?, Expr::sym(&accel)]));
    }
    Ok(Expr::add(terms))
}

/// The Euler–Lagrange residual d/dt(∂L/∂q') − ∂L/∂q of each coordinate L depends on (one a
/// constraint has eliminated has no equation), unsimplified.
pub fn euler_lagrange(
    lagrangian: &Expr,
    coordinates: &BTreeMap<String, String>,
) -> Result<Vec<(String, Expr)>, DeriveError> {
    let names = lagrangian.symbols();
    let used: Vec<&String> = coordinates
        .keys()
        .filter(|q| names.contains(q) || names.contains(&format!("{q}'")))
        .collect();
    if used.is_empty() {
        return Err(DeriveError::NotDerivable(
            "the Lagrangian depends on no coordinate: there is no motion to describe".into(),
        ));
    }
    used.into_iter()
        .map(|q| {
            let momentum = lagrangian.diff(&format!("{q}'"))?;
            let rate = time_derivative(&momentum, coordinates)?;
            Ok((q.clone(), Expr::minus(rate, lagrangian.diff(q)?)))
        })
        .collect()
}

/// Each coordinate's value at the state of rest `about` (0 where not named); rates are 0.
fn rest_value(
    q: &str,
    about: &BTreeMap<String, Expr>,
    coordinates: &BTreeMap<String, String>,
) -> Option<Expr> {
    if coordinates.contains_key(q) {
        return Some(about.get(q).cloned().unwrap_or_else(|| Expr::int(0)));
    }
    let base = q.trim_end_matches('\'');
    (base != q && coordinates.contains_key(base)).then(|| Expr::int(0))
}

/// Each equation to first order about the state of rest: R(rest) (which must vanish) and
/// Σ_q ∂R/∂q·(q − q₀) + ∂R/∂q'·q' + ∂R/∂q''·q'', the derivatives taken at rest. Unsimplified.
#[allow(clippy::type_complexity)]
pub fn linearise(
    eqs: &[(String, Expr)],
    about: &BTreeMap<String, Expr>,
    coordinates: &BTreeMap<String, String>,
) -> Result<(Vec<Expr>, Vec<(String, Expr)>), DeriveError> {
    let at_rest = |e: &Expr| e.substitute(&|s| rest_value(s, about, coordinates));
    let mut rest = Vec::new();
    let mut linear = Vec::new();
    for (q, r) in eqs {
        rest.push(at_rest(r));
        let mut terms = Vec::new();
        for c in coordinates.keys() {
            let q0 = about.get(c).cloned().unwrap_or_else(|| Expr::int(0));
            terms.push(Expr::mul(vec![
                at_rest(&r.diff(c)?),
                Expr::minus(Expr::sym(c), q0),
            ]));
            for rate in [format!("{c}'"), format!("{c}''")] {
                terms.push(Expr::mul(vec![at_rest(&r.diff(&rate)?), Expr::sym(&rate)]));
            }
        }
        linear.push((q.clone(), Expr::add(terms)));
    }
    Ok((rest, linear))
}

/// The angular frequency Ω = √(k/m) of one linear equation m q'' + k (q − q₀) = 0.
pub fn frequency(eqs: &[(String, Expr)]) -> Result<Expr, DeriveError> {
    let [(q, r)] = eqs else {
        return Err(DeriveError::Inconsistent(format!(
            "`frequency` of one coordinate was given {} equations",
            eqs.len()
        )));
    };
    let m = cas::simplify(&r.diff(&format!("{q}''"))?)?;
    let c = cas::simplify(&r.diff(&format!("{q}'"))?)?;
    let k = cas::simplify(&r.diff(q)?)?;
    if !c.is_zero() {
        return Err(DeriveError::NotDerivable(format!(
            "the equation has a term in `{q}'` ({}): a damped or driven motion has no single \
             frequency",
            c.to_text()
        )));
    }
    if m.is_zero() {
        return Err(DeriveError::NotDerivable(format!(
            "the equation has no term in `{q}''`: it is not an equation of motion"
        )));
    }
    let omega = Expr::pow(Expr::over(k, m), Expr::rat(1, 2));
    Ok(cas::simplify(&omega)?)
}

/// Values in the order of their numbers at `values` (one without a number, last).
pub fn sort_by_value(exprs: &mut [Expr], values: &BTreeMap<String, f64>) {
    let at = |e: &Expr| crate::model::value::eval_at(e, values).unwrap_or(f64::NAN);
    exprs.sort_by(|a, b| at(a).total_cmp(&at(b)));
}

/// `e` at rest in the coordinate `q`: its rate and acceleration 0.
fn at_rest(e: &Expr, q: &str) -> Expr {
    let (rate, accel) = (format!("{q}'"), format!("{q}''"));
    e.substitute(&|s| (s == rate || s == accel).then(|| Expr::int(0)))
}

/// Two expressions simplified in one call to the engine.
pub fn simplify_two(a: Expr, b: Expr) -> Result<(Expr, Expr), DeriveError> {
    let mut both = cas::simplify_all(vec![a, b])?.into_iter();
    match (both.next(), both.next()) {
        (Some(a), Some(b)) => Ok((a, b)),
        _ => Err(DeriveError::Inconsistent(
            "two expressions simplified, not two back".into(),
        )),
    }
}

/// The determinant of an n×n matrix (row-major), by expansion along the first row; n ≤ 4.
pub(super) fn determinant(m: &[Expr], n: usize) -> Expr {
    if n == 1 {
        return m[0].clone();
    }
    let mut terms = Vec::new();
    for j in 0..n {
        let minor: Vec<Expr> = (1..n)
            .flat_map(|i| (0..n).filter(move |&c| c != j).map(move |c| (i, c)))
            .map(|(i, c)| m[i * n + c].clone())
            .collect();
        let sign = if j % 2 == 0 { 1 } else { -1 };
        terms.push(Expr::mul(vec![
            Expr::int(sign),
            m[j].clone(),
            determinant(&minor, n - 1),
        ]));
    }
    Expr::add(terms)
}

/// The generalised momentum ∂L/∂q' and the generalised force ∂L/∂q (the momentum is conserved
/// when the force is identically zero), unsimplified.
pub fn momentum(lagrangian: &Expr, q: &str) -> Result<(Expr, Expr), DeriveError> {
    Ok((lagrangian.diff(&format!("{q}'"))?, lagrangian.diff(q)?))
}

/// The energy function Σ_q q'·∂L/∂q' − L over the coordinates L depends on, and ∂L/∂t (the
/// energy is conserved when it is identically zero), unsimplified.
pub fn energy(
    lagrangian: &Expr,
    coordinates: &BTreeMap<String, String>,
) -> Result<(Expr, Expr), DeriveError> {
    let mut terms = vec![Expr::negate(lagrangian.clone())];
    for q in coordinates.keys() {
        let rate = format!("{q}'");
        terms.push(Expr::mul(vec![Expr::sym(&rate), lagrangian.diff(&rate)?]));
    }
    Ok((Expr::add(terms), lagrangian.diff("t")?))
}

/// The static equation of one coordinate (every rate and acceleration 0) and its zeros.
pub fn equilibria(
    eqs: &[(String, Expr)],
    values: &BTreeMap<String, f64>,
) -> Result<Equilibria, DeriveError> {
    let [(q, r)] = eqs else {
        return Err(DeriveError::NotDerivable(format!(
            "`equilibria` takes the equation of one coordinate for now; these are {}",
            eqs.len()
        )));
    };
    let at_rest = cas::simplify(&at_rest(r, q))?;
    polynomial_in_trig(&at_rest, q)?;
    let mut found = cas::zeros(&at_rest, q)?;
    close_factors(&mut found, q, values)?;
    // A root that is real for no positive values (√(−3r₀²)) is no state of rest: set aside,
    // named. One real for some values only (arccos(I₃ω₃/√(MglI₁) − 1)) stays.
    let mut zeros = Vec::new();
    let mut excluded = Vec::new();
    for z in found.zeros {
        if never_real(&z.value) {
            excluded.push(z);
        } else {
            zeros.push(z);
        }
    }
    if zeros.is_empty() {
        let besides = match excluded.is_empty() {
            true => String::new(),
            false => " (its roots are real for no values of the symbols)".to_string(),
        };
        return Err(DeriveError::NotDerivable(format!(
            "the static equation {} = 0 has no real solution{besides}: there is no equilibrium",
            at_rest.to_text()
        )));
    }
    // Every symbol of a scene is positive: √(4 b a²) = 2 a √b.
    let positive = |e: &Expr| cas::pull_squares(e, &|_| true);
    let zeros = zeros
        .into_iter()
        .map(|z| cas::Zero {
            value: positive(&z.value),
            trig: z.trig.map(|(c, s)| (positive(&c), positive(&s))),
        })
        .collect();
    Ok(Equilibria {
        coordinate: q.clone(),
        zeros,
        excluded: excluded.into_iter().map(|z| z.value).collect(),
    })
}

/// Refuses a static equation that is not a polynomial in q, sin q and cos q: zeros are found
/// of those only (exp(−a(x − x₀)) = 1 is solved by no rule here).
fn polynomial_in_trig(at_rest: &Expr, q: &str) -> Result<(), DeriveError> {
    let mut other = None;
    at_rest.walk(&mut |e| {
        if let Expr::Call(f, args) = e
            && !["sin", "cos", "sqrt"].contains(&f.as_str())
            && args.iter().any(|a| a.symbols().iter().any(|s| s == q))
        {
            other.get_or_insert_with(|| e.to_text());
        }
    });
    if let Some(call) = other {
        return Err(DeriveError::NotDerivable(format!(
            "the static equation {} = 0 holds `{call}`: its states of rest are found for a \
             polynomial in `{q}`, sin({q}) and cos({q}) only; give the state in a `linearise` \
             step's `about` (an error there says when it is not at rest)",
            at_rest.to_text()
        )));
    }
    Ok(())
}

/// The roots of each cubic or quartic factor of a polynomial left unsolved, real at the
/// scene's values, in the closed form `solve` gives (r³ = p: r = ∛p), among the zeros.
fn close_factors(
    found: &mut cas::Zeros,
    q: &str,
    values: &BTreeMap<String, f64>,
) -> Result<(), DeriveError> {
    for f in std::mem::take(&mut found.unsolved) {
        let polynomial = f.symbols().iter().any(|s| s == q) && !has_call_of(&f, q);
        let closed = if polynomial {
            closed_roots(&f, q, values)?.ok()
        } else {
            None
        };
        match closed {
            Some(roots) => found.zeros.extend(
                roots
                    .into_iter()
                    .map(|value| cas::Zero { value, trig: None }),
            ),
            None => {
                return Err(DeriveError::NotDerivable(format!(
                    "the static equation has the factor {} = 0, whose solutions have no closed \
                     form here (a polynomial of degree at most 4 in `{q}`, or of degree 2 in \
                     sin({q}) or cos({q}))",
                    f.to_text()
                )));
            }
        }
    }
    Ok(())
}

/// The states of rest of one coordinate, and the roots of its static equation that are not
/// real at the scene's values.
pub struct Equilibria {
    pub coordinate: String,
    pub zeros: Vec<cas::Zero>,
    pub excluded: Vec<Expr>,
}

/// The real roots at `values` of a cubic or quartic factor in `var`, in the closed form `solve`
/// gives: every symbol positive first (√(p²/4) = p/2), then simplified (∛p, not ∛(p/2 + p/2)).
pub(super) fn closed_roots(
    factor: &Expr,
    var: &str,
    values: &BTreeMap<String, f64>,
) -> Result<Result<Vec<Expr>, cas::NoClosedForm>, cas::CasError> {
    Ok(match cas::closed_form_roots(factor, var, values)? {
        Ok(found) => Ok(cas::simplify_all(
            found
                .iter()
                .map(|e| cas::pull_squares(e, &|_| true))
                .collect(),
        )?),
        Err(why) => Err(why),
    })
}

/// Whether `e` has an even root of a quantity negative for every positive value of its
/// symbols (√(−3r₀²)): it is real for none.
pub(super) fn never_real(e: &Expr) -> bool {
    let mut radicands = Vec::new();
    e.walk(&mut |x| {
        if let Expr::Pow(b, k) = x
            && let Expr::Num(k) = k.as_ref()
            && k.to_i64_pair().is_some_and(|(_, d)| d % 2 == 0)
        {
            radicands.push((**b).clone());
        }
    });
    // A sign the test cannot decide keeps the root.
    !radicands.is_empty()
        && super::sign::signs_over_positive(&radicands)
            .is_ok_and(|signs| signs.contains(&super::sign::Sign::Negative))
}

/// Whether `q` appears inside a function call of `e` (sin q): not a polynomial in it.
pub(super) fn has_call_of(e: &Expr, q: &str) -> bool {
    match e {
        Expr::Call(_, args) => args.iter().any(|a| a.symbols().iter().any(|s| s == q)),
        Expr::Add(v) | Expr::Mul(v) | Expr::List(v) => v.iter().any(|x| has_call_of(x, q)),
        Expr::Pow(a, b) | Expr::Index(a, b) => has_call_of(a, q) || has_call_of(b, q),
        Expr::Num(_) | Expr::Sym(_) => false,
    }
}

/// The squared frequency of small oscillations about each equilibrium, k/m with k = ∂R/∂q and
/// m = ∂R/∂q'' at rest there: the equilibrium is stable where it is positive. `None` where the
/// exact Ω² would expand beyond the engine's budget (an equilibrium with a root in it).
pub fn stability(
    eqs: &[(String, Expr)],
    zeros: &[cas::Zero],
) -> Result<Vec<Option<Expr>>, DeriveError> {
    let [(q, r)] = eqs else {
        return Err(DeriveError::Inconsistent(
            "the equilibria were found for one coordinate".into(),
        ));
    };
    // Simplified before an equilibrium goes in, which keeps the expansion small.
    let (k, m) = simplify_two(
        at_rest(&r.diff(q)?, q),
        at_rest(&r.diff(&format!("{q}''"))?, q),
    )?;
    let mut out = Vec::new();
    for z in zeros {
        let ratio = Expr::over(z.put_into(&k, q), z.put_into(&m, q));
        if ratio.symbols().contains(q) {
            return Err(DeriveError::NotDerivable(format!(
                "`{q}` enters the equation both inside and outside sin and cos: its stability \
                 has no closed form here"
            )));
        }
        match cas::simplify(&ratio) {
            Ok(w2) => out.push(Some(w2)),
            Err(cas::CasError {
                reason: cas::CasFailure::Engine(cas::EngineError::OverBudget { .. }),
            }) => out.push(None),
            Err(e) => return Err(e.into()),
        }
    }
    Ok(out)
}

/// The roots of a polynomial at the scene's values, as text: the eigenvalues of its companion
/// matrix, or Aberth's roots. `None` when a coefficient has no value there.
pub(super) fn numeric_roots(
    terms: &[(u32, Expr)],
    values: &BTreeMap<String, f64>,
) -> Option<String> {
    let degree = terms.iter().map(|(k, _)| *k as usize).max()?;
    let mut c = vec![0.0; degree + 1];
    for (k, coeff) in terms {
        c[*k as usize] = crate::model::value::eval_at(coeff, values).ok()?;
    }
    let lead = *c.last()?;
    if lead == 0.0 || !c.iter().all(|v| v.is_finite()) {
        return None;
    }
    // x^n = −Σ c_k/c_n x^k: the companion matrix's eigenvalues are the roots.
    let companion = nalgebra::DMatrix::from_fn(degree, degree, |i, j| {
        if j == degree - 1 {
            -c[i] / lead
        } else if i == j + 1 {
            1.0
        } else {
            0.0
        }
    });
    // Where the Schur form does not settle (equal moduli: r⁶ − 2 s⁶), Aberth's iteration does.
    let roots = crate::base::float::complex_eigenvalues(companion)
        .or_else(|| crate::base::float::polynomial_roots(&c))?;
    let mut roots: Vec<(f64, f64)> = roots.iter().map(|z| (z.re, z.im)).collect();
    roots.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let scale = roots
        .iter()
        .map(|(re, im)| re.hypot(*im))
        .fold(1.0, f64::max);
    Some(
        roots
            .iter()
            .map(|&(re, im)| {
                if im.abs() <= 1e-12 * scale {
                    format!("{re:.6}")
                } else {
                    format!(
                        "{re:.6} {} {:.6}i",
                        if im < 0.0 { "-" } else { "+" },
                        im.abs()
                    )
                }
            })
            .collect::<Vec<_>>()
            .join(", "),
    )
}
