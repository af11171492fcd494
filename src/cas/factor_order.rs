//! A product's factors in the order a physicist writes them: the number, roots of numbers,
//! π, the scene's symbols in the order the scene declares them (the author controls M g l and
//! m₁ m₂ g), other names by power and name, a sum of those alone (R − r), the coordinates and
//! their rates in the order declared, functions (sin θ), then the rest (a sum in parentheses). The engine returns its
//! factors by name (g l M, 2 g m₁ m₂); only the order of factors changes, never a value.

use super::expr::Expr;

/// The names a scene declares, in the order its file declares them.
#[derive(Debug, Clone, Default)]
pub struct Declared {
    pub symbols: Vec<String>,
    pub coordinates: Vec<String>,
}

/// `e` with the factors of every product in the declared order.
pub fn order_factors(e: &Expr, declared: &Declared) -> Expr {
    let each = |v: &[Expr]| v.iter().map(|x| order_factors(x, declared)).collect();
    match e {
        Expr::Mul(f) => {
            let mut f: Vec<Expr> = each(f);
            f.sort_by(|a, b| {
                key(a, declared)
                    .partial_cmp(&key(b, declared))
                    .unwrap_or(std::cmp::Ordering::Equal)
            });
            Expr::Mul(f)
        }
        Expr::Add(t) => Expr::Add(each(t)),
        Expr::Pow(b, x) => Expr::Pow(
            Box::new(order_factors(b, declared)),
            Box::new(order_factors(x, declared)),
        ),
        Expr::Call(name, args) => Expr::Call(name.clone(), each(args)),
        Expr::List(v) => Expr::List(each(v)),
        Expr::Index(a, i) => Expr::Index(
            Box::new(order_factors(a, declared)),
            Box::new(order_factors(i, declared)),
        ),
        Expr::Num(_) | Expr::Sym(_) => e.clone(),
    }
}

/// No coordinate, rate or function in `e`.
fn of_parameters(e: &Expr, declared: &Declared) -> bool {
    let mut plain = true;
    e.walk(&mut |x| {
        plain &= match x {
            Expr::Sym(s) => !declared
                .coordinates
                .iter()
                .any(|c| c == s.trim_end_matches('\'')),
            Expr::Call(..) | Expr::List(_) | Expr::Index(..) => false,
            _ => true,
        }
    });
    plain
}

/// (kind, exponent, place in the declared order, name) of a factor.
fn key(e: &Expr, declared: &Declared) -> (u8, f64, usize, String) {
    let (base, exponent) = match e {
        Expr::Pow(b, x) => (b.as_ref(), x.eval(&|_| None).unwrap_or(f64::MAX)),
        other => (other, 1.0),
    };
    let last = usize::MAX;
    match (e, base) {
        (Expr::Num(_), _) => (0, 0.0, 0, String::new()),
        (_, Expr::Num(_)) => (1, exponent, 0, base.to_text()),
        (_, Expr::Sym(s)) if s == "pi" => (2, exponent, 0, String::new()),
        (_, Expr::Sym(s)) => {
            let coordinate = s.trim_end_matches('\'');
            match declared.coordinates.iter().position(|c| c == coordinate) {
                // A coordinate before its rate, each after the parameters: L² φ̈, not φ̈ L².
                Some(k) => (5, 0.0, 3 * k + (s.len() - coordinate.len()), s.clone()),
                // A declared symbol by its place alone (M R² ω₃ where the scene declares M, R,
                // ω₃); any other name after them, by power and name.
                None => match declared.symbols.iter().position(|d| d == s) {
                    Some(place) => (3, 0.0, place, String::new()),
                    None => (3, exponent, last, s.to_lowercase()),
                },
            }
        }
        // A sum or a product of parameters alone (under a power) before the coordinates, by
        // power: 7m(R − r)²φ̇², g(m₁ − m₂)x, 2π√(gl)(1 + a²/16).
        (_, Expr::Add(_) | Expr::Mul(_)) if of_parameters(base, declared) => {
            (4, exponent, 0, base.to_text())
        }
        (_, Expr::Call(..)) => (6, exponent, 0, base.to_text()),
        _ => (7, exponent, 0, base.to_text()),
    }
}
