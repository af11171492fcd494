//! An equation of motion `… = 0` in the form a textbook prints it: a factor of the scene's
//! parameters alone divided out (l(mgφ₁ + klφ₁ − klφ₂ + mlφ̈₁) = 0 is mlφ̈₁ + mgφ₁ + klφ₁ −
//! klφ₂ = 0), the coordinate's own acceleration first, then the other accelerations, then the
//! forces, and a leading minus sign taken into the equation. Dividing by a factor free of the
//! coordinates is what the build's guard allows of a printed equation (`render/guard.rs`), and
//! it reads every such line back.

use crate::cas::{Expr, Rational, common_factor};

/// `e = 0` as a page prints it. `parameter` says which names are the scene's symbols (masses,
/// lengths, g): only a factor of those and numbers is divided out, never a coordinate, a rate
/// or a multiplier. `own` is the coordinate the equation is of.
pub fn equation_form(e: &Expr, own: &str, parameter: &dyn Fn(&str) -> bool) -> Expr {
    let fixed = |x: &Expr| x.symbols().iter().all(|s| parameter(s));
    // A product of the equation's one sum and fixed factors: the sum alone.
    let mut e = match e {
        Expr::Mul(factors) => {
            // 1/(m r³) as m⁻¹ r⁻³: a fixed factor and a coordinate's power apart.
            let factors: Vec<Expr> = factors
                .iter()
                .flat_map(|f| match f {
                    Expr::Pow(b, k)
                        if matches!(**b, Expr::Mul(_)) && matches!(**k, Expr::Num(_)) =>
                    {
                        let Expr::Mul(inner) = b.as_ref() else {
                            unreachable!()
                        };
                        inner
                            .iter()
                            .map(|g| Expr::pow(g.clone(), (**k).clone()))
                            .collect()
                    }
                    other => vec![other.clone()],
                })
                .collect();
            let moving: Vec<&Expr> = factors.iter().filter(|f| !fixed(f)).collect();
            match moving.as_slice() {
                [sum @ Expr::Add(_)] => (*sum).clone(),
                // A sum over a coordinate's power, (… − p² + …)/(m r³): each term divided, as
                // a textbook writes the radial equation, (M + m)r̈ + M g − p²/(m r³) = 0.
                _ => distributed(&factors.iter().collect::<Vec<_>>()).unwrap_or_else(|| e.clone()),
            }
        }
        _ => e.clone(),
    };
    if let Expr::Add(terms) = &e
        && let Some((factor, rest)) = common_factor(terms)
        && fixed(&factor)
    {
        e = Expr::Add(rest);
    }
    let Expr::Add(terms) = &e else {
        return e;
    };
    let acceleration = format!("{own}''");
    let rank = |t: &Expr| {
        let names = t.symbols();
        match () {
            _ if names.contains(&acceleration) => 0,
            _ if names.iter().any(|n| n.ends_with("''")) => 1,
            _ => 2,
        }
    };
    let mut ordered = terms.clone();
    ordered.sort_by_key(rank);
    if crate::cas::split_sign(&ordered[0]).0 {
        ordered = ordered.into_iter().map(Expr::negate).collect();
    }
    Expr::Add(collected(ordered, &fixed))
}

/// The terms of each acceleration collected into one, in the place of the first: 7Rφ̈ − 7rφ̈
/// is 7(R − r)φ̈, Mẍ + mẍ is (M + m)ẍ. A term collects only where the acceleration is a factor
/// of its own.
fn collected(terms: Vec<Expr>, fixed: &dyn Fn(&Expr) -> bool) -> Vec<Expr> {
    let mut out: Vec<Expr> = Vec::new();
    let mut taken = vec![false; terms.len()];
    for i in 0..terms.len() {
        if taken[i] {
            continue;
        }
        let Some((a, first)) = acceleration_factor(&terms[i], fixed) else {
            out.push(terms[i].clone());
            continue;
        };
        let mut coefficients = vec![first];
        for j in i + 1..terms.len() {
            if let Some((b, c)) = acceleration_factor(&terms[j], fixed)
                && b == a
                && !taken[j]
            {
                coefficients.push(c);
                taken[j] = true;
            }
        }
        if coefficients.len() == 1 {
            out.push(terms[i].clone());
            continue;
        }
        let sum = match common_factor(&coefficients) {
            Some((f, rest)) => Expr::mul(vec![f, Expr::Add(rest)]),
            None => number_out(coefficients),
        };
        out.push(Expr::mul(vec![sum, Expr::sym(&a)]));
    }
    out
}

/// The one sum among `factors` times the others, each a number or a power of a name, put into
/// each of its terms with like powers merged (m M r³ r̈ ⋅ m⁻¹ r⁻³ is M r̈); `None` where the
/// factors are not so.
fn distributed(factors: &[&Expr]) -> Option<Expr> {
    let power = |e: &Expr| match e {
        Expr::Pow(b, k) => match (b.as_ref(), k.as_ref()) {
            (Expr::Sym(_), Expr::Num(k)) => Some(((**b).clone(), k.clone())),
            _ => None,
        },
        Expr::Sym(_) => Some((e.clone(), Rational::ONE)),
        _ => None,
    };
    let mut sums = factors.iter().filter(|f| matches!(f, Expr::Add(_)));
    let (Some(Expr::Add(terms)), None) = (sums.next(), sums.next()) else {
        return None;
    };
    let number = Expr::mul(
        factors
            .iter()
            .filter(|f| matches!(f, Expr::Num(_)))
            .map(|f| (*f).clone())
            .collect(),
    );
    let by: Vec<(Expr, Rational)> = factors
        .iter()
        .filter(|f| !matches!(f, Expr::Add(_) | Expr::Num(_)))
        .map(|f| power(f))
        .collect::<Option<_>>()?;
    // Only over a denominator: θ(mlθ̈ + mg) keeps its factor.
    if !by.iter().any(|(_, k)| k.is_negative()) {
        return None;
    }
    let times = |t: &Expr| {
        let mut own: Vec<Expr> = match t {
            Expr::Mul(f) => f.clone(),
            other => vec![other.clone()],
        };
        own.push(number.clone());
        for (base, k) in &by {
            match own
                .iter()
                .position(|f| power(f).is_some_and(|(b, _)| b == *base))
            {
                Some(i) => {
                    let (_, j) = power(&own[i]).expect("a power of the base");
                    own[i] = Expr::pow(base.clone(), Expr::Num(j.add(k)));
                }
                None => own.push(Expr::pow(base.clone(), Expr::Num(k.clone()))),
            }
        }
        Expr::mul(own)
    };
    Some(Expr::Add(terms.iter().map(times).collect()))
}

/// A sum with its terms' whole-number factor in front: 7R − 7r is 7(R − r).
fn number_out(terms: Vec<Expr>) -> Expr {
    let number = |t: &Expr| match t {
        Expr::Mul(f) => match f.first() {
            Some(Expr::Num(r)) => r.clone(),
            _ => Rational::ONE,
        },
        Expr::Num(r) => r.clone(),
        _ => Rational::ONE,
    };
    let gcd = terms
        .iter()
        .skip(1)
        .fold(number(&terms[0]).abs(), |g, t| g.gcd(&number(t)));
    match gcd.is_integer() && gcd != Rational::ONE {
        true => {
            let inverse = Expr::Num(gcd.recip().expect("a whole number not 0"));
            let rest = terms
                .into_iter()
                .map(|t| Expr::mul(vec![inverse.clone(), t]));
            Expr::mul(vec![Expr::Num(gcd), Expr::Add(rest.collect())])
        }
        false => Expr::Add(terms),
    }
}

/// A term's acceleration (a name ending in ″) where it is a factor to the first power, and the
/// term without it.
fn acceleration_factor(term: &Expr, fixed: &dyn Fn(&Expr) -> bool) -> Option<(String, Expr)> {
    let factors = match term {
        Expr::Mul(f) => f.as_slice(),
        _ => return None,
    };
    let k = factors
        .iter()
        .position(|f| matches!(f, Expr::Sym(s) if s.ends_with("''")))?;
    let Expr::Sym(a) = &factors[k] else {
        unreachable!()
    };
    let rest: Vec<Expr> = (0..factors.len())
        .filter(|&j| j != k)
        .map(|j| factors[j].clone())
        .collect();
    // Only a coefficient of parameters: l φ̈₂ cos(φ₁ − φ₂) stays a term of its own.
    let coefficient = Expr::mul(rest);
    fixed(&coefficient).then(|| (a.clone(), coefficient))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Expr {
        crate::cas::parse(s).unwrap().expr
    }

    fn form(e: &str, own: &str) -> String {
        let parameters = ["m", "g", "l", "k", "R", "r", "M", "I1", "I3", "w3", "L"];
        equation_form(&p(e), own, &|s| parameters.contains(&s)).to_text()
    }

    #[test]
    fn a_factor_of_parameters_is_divided_out_and_the_acceleration_comes_first() {
        assert_eq!(
            form(
                "m*g*l*phi1 + k*l^2*phi1 - k*l^2*phi2 + m*l^2*phi1''",
                "phi1"
            ),
            "m*l*phi1'' + m*g*phi1 + k*l*phi1 - k*l*phi2"
        );
        // The equation of φ: φ̈'s term before ẍ's, then gravity.
        assert_eq!(
            form("m*l*g*sin(phi) + m*l*x''*cos(phi) + m*l^2*phi''", "phi"),
            "l*phi'' + x''*cos(phi) + g*sin(phi)"
        );
        // A product of fixed factors and the one sum: the sum, its minus sign taken in.
        // ... the terms of one acceleration collected: 7(R − r)φ̈, not 7Rφ̈ − 7rφ̈.
        assert_eq!(
            form(
                "1/5*m*(R - r)*(-5*g*sin(phi) - 7*R*phi'' + 7*r*phi'')",
                "phi"
            ),
            "7*(R - r)*phi'' + 5*g*sin(phi)"
        );
        assert_eq!(
            form(
                "M*x'' + m*l*phi''*cos(phi) - m*l*phi'^2*sin(phi) + m*x''",
                "x"
            ),
            "(M + m)*x'' + m*l*phi''*cos(phi) - m*l*phi'^2*sin(phi)"
        );
        assert_eq!(form("-x1'' - x2''", "x1"), "x1'' + x2''");
    }

    #[test]
    fn a_sum_over_a_power_of_a_coordinate_is_divided_term_by_term() {
        // The puck and hanging mass: (m M r³ r̈ + m M g r³ − p² + m² r³ r̈)/(m r³) = 0.
        let form = |e: &str| {
            let parameters = ["m", "M", "g", "p"];
            equation_form(&p(e), "r", &|s| parameters.contains(&s)).to_text()
        };
        assert_eq!(
            form("(m*M*r^3*r'' + m*M*g*r^3 - p^2 + m^2*r^3*r'')/(m*r^3)"),
            "(M + m)*r'' + M*g - p^2/(m*r^3)"
        );
    }

    #[test]
    fn a_coordinate_or_a_multiplier_is_never_divided_out() {
        // T is a multiplier, θ a coordinate: nothing is divided, the terms only reordered.
        assert_eq!(form("T - m*g + m*x''", "x"), "m*x'' + T - m*g");
        assert_eq!(
            form("theta*(m*l*theta'' + m*g)", "theta"),
            "theta*(m*l*theta'' + m*g)"
        );
    }
}
