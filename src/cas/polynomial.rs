//! The exact roots of a polynomial, from its factors over the rationals: linear and quadratic
//! factors, and quartics in the variable's square.

use super::Roots;
use super::engine::{EngineError, coefficients, expand, from_atom, simplify, variables_by_name};
use super::expr::Expr;
use super::trig;
use symbolica::prelude::*;

/// The roots in `var` of a polynomial whose other symbols are parameters (sines and cosines
/// of other angles through their half-angle tangents), with the factors it cannot solve.
pub fn roots(poly: &Expr, var: &str) -> Result<Roots, EngineError> {
    let (h, args) = trig::to_half_angle(poly);
    let atom = expand(&h)?;
    let rat: RationalPolynomial<_, u16> =
        atom.to_rational_polynomial(&Q, &Z, variables_by_name(&atom));
    let mut out = Roots {
        roots: Vec::new(),
        unsolved: Vec::new(),
    };
    let back =
        |e: Expr| -> Result<Expr, EngineError> { simplify(&trig::from_half_angle(&e, &args)) };
    // (−b ± √(b² − 4ac)) / 2a, the − root first.
    let quadratic = |a: &Expr, b: &Expr, c: &Expr| -> Result<[Expr; 2], EngineError> {
        let disc = Expr::minus(
            Expr::pow(b.clone(), Expr::int(2)),
            Expr::mul(vec![Expr::int(4), a.clone(), c.clone()]),
        );
        let sqrt = Expr::pow(simplify(&disc)?, Expr::rat(1, 2));
        Ok([-1, 1].map(|sign| {
            let num = Expr::add(vec![
                Expr::negate(b.clone()),
                Expr::mul(vec![Expr::int(sign), sqrt.clone()]),
            ]);
            Expr::over(num, Expr::mul(vec![Expr::int(2), a.clone()]))
        }))
    };
    for (factor, mult) in rat.numerator.factor() {
        let factor = from_atom(&factor.to_expression())?;
        let mut c = vec![Expr::int(0); 5];
        let terms = coefficients(&factor, var)?;
        let degree = terms.iter().map(|(k, _)| *k).max().unwrap_or(0);
        // A quartic in var² is a quadratic in v = var²: var = ±√v for each of its roots.
        let in_square = degree == 4 && terms.iter().all(|(k, _)| k % 2 == 0);
        if degree == 0 {
            continue;
        }
        if degree > 2 && !in_square {
            out.unsolved.push((back(factor)?, mult as u32));
            continue;
        }
        for (k, coeff) in terms {
            c[k as usize] = coeff;
        }
        let mult = mult as u32;
        if degree == 1 {
            out.roots.push((
                back(Expr::negate(Expr::over(c[0].clone(), c[1].clone())))?,
                mult,
            ));
        } else if degree == 2 {
            for root in quadratic(&c[2], &c[1], &c[0])? {
                out.roots.push((back(root)?, mult));
            }
        } else {
            for square in quadratic(&c[4], &c[2], &c[0])? {
                let root = Expr::pow(simplify(&square)?, Expr::rat(1, 2));
                out.roots.push((back(Expr::negate(root.clone()))?, mult));
                out.roots.push((back(root)?, mult));
            }
        }
    }
    Ok(out)
}
