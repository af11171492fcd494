//! What expanding an expression can cost, bounded from its tree alone, so that the engine is
//! never handed an expansion beyond its budget (see `engine::expand`) and a scene's inputs stay
//! small.

use super::expr::Expr;

/// What expanding an expression can cost, bounded from its tree: the total degree and the
/// number of terms of its expansion (each at most, saturating). Function calls count as one
/// variable; a negative or fractional power as its base's size, unexpanded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExpansionSize {
    pub degree: f64,
    pub terms: f64,
}

impl Expr {
    pub fn expansion_size(&self) -> ExpansionSize {
        let size = |degree: f64, terms: f64| ExpansionSize { degree, terms };
        match self {
            Expr::Num(_) => size(0.0, 1.0),
            Expr::Sym(_) | Expr::Index(..) => size(1.0, 1.0),
            Expr::Call(_, args) | Expr::List(args) => {
                let inner = args.iter().map(Expr::expansion_size);
                let terms = inner.map(|s| s.terms).sum::<f64>().max(1.0);
                size(1.0, terms)
            }
            Expr::Add(v) => v
                .iter()
                .map(Expr::expansion_size)
                .fold(size(0.0, 0.0), |a, b| {
                    size(a.degree.max(b.degree), a.terms + b.terms)
                }),
            Expr::Mul(v) => v
                .iter()
                .map(Expr::expansion_size)
                .fold(size(0.0, 1.0), |a, b| {
                    size(a.degree + b.degree, a.terms * b.terms)
                }),
            Expr::Pow(b, x) => {
                let base = b.expansion_size();
                match x.as_ref() {
                    Expr::Num(k) if k.is_integer() => {
                        let k = k.to_f64().abs();
                        // Expanding a sum of n terms to the k-th power gives at most
                        // C(n + k − 1, k) terms.
                        let n = base.terms;
                        let mut terms = 1.0f64;
                        for j in 0..(k.min(1e6) as u64) {
                            terms = terms * (n + j as f64) / (j as f64 + 1.0);
                            if terms > 1e300 {
                                break;
                            }
                        }
                        size(base.degree * k, terms.max(1.0))
                    }
                    exponent => {
                        let e = exponent.expansion_size();
                        size(base.degree + e.degree, base.terms * e.terms)
                    }
                }
            }
        }
    }
}
