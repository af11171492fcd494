//! Our own exact expression tree. It crosses the `cas` boundary in both directions, so the rest
//! of the program never sees a Symbolica type.
//!
//! The same tree also carries the claim language of scene files: list literals `[a, b, c]`,
//! indexing `v[0]` and calls such as `cross(u, v)`. Those are resolved by `derive::algebra` into
//! scalars, vectors and matrices before anything reaches the engine.

use super::rational::Rational;

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Expr {
    Num(Rational),
    Sym(String),
    Add(Vec<Expr>),
    Mul(Vec<Expr>),
    Pow(Box<Expr>, Box<Expr>),
    /// `sin`, `cos`, `sqrt` in scalars; any name in the claim language.
    Call(String, Vec<Expr>),
    List(Vec<Expr>),
    Index(Box<Expr>, Box<Expr>),
}

/// Why an expression has no derivative here.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DiffError {
    #[error("cannot differentiate a power whose exponent depends on `{var}`")]
    VariableExponent { var: String },
    #[error("cannot differentiate `{name}`")]
    Function { name: String },
    #[error("only scalar expressions can be differentiated")]
    NotScalar,
}

/// Why an expression has no f64 value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EvalError {
    #[error("no value for symbol `{0}`")]
    NoValue(String),
    #[error("`{0}` is not a scalar function")]
    NotScalarFunction(String),
    #[error("a vector or matrix where a scalar was expected")]
    NotScalar,
    #[error("{found} where {expected} was expected")]
    Shape {
        expected: &'static str,
        found: &'static str,
    },
}

impl Expr {
    pub fn int(n: i128) -> Expr {
        Expr::Num(Rational::int(n))
    }

    pub fn rat(n: i128, d: i128) -> Expr {
        Expr::Num(Rational::new(n, d).expect("nonzero denominator"))
    }

    pub fn sym(name: &str) -> Expr {
        Expr::Sym(name.to_string())
    }

    pub fn call(name: &str, arg: Expr) -> Expr {
        Expr::Call(name.to_string(), vec![arg])
    }

    pub fn is_zero(&self) -> bool {
        matches!(self, Expr::Num(r) if r.is_zero())
    }

    pub fn is_one(&self) -> bool {
        matches!(self, Expr::Num(r) if *r == Rational::ONE)
    }

    /// A number as its author wrote it (`9.81`, `0.0000729`), kept for the printers: a symbol
    /// named by its digits, which no scene name can be. No engine and no evaluation sees one.
    pub fn numeral(digits: &str) -> Expr {
        debug_assert!(digits.starts_with(|c: char| c.is_ascii_digit()));
        Expr::Sym(digits.to_string())
    }

    /// Whether `self`, printed as a factor, starts with a numeral: a number, or a whole power
    /// of one (a variant's 0.4⁴). Beside the factor before it, it takes a times sign, or 3 and
    /// 0.4⁴ would read 30.4⁴.
    pub fn leads_with_numeral(&self) -> bool {
        match self {
            Expr::Pow(base, exp) => {
                base.is_number_like() && matches!(&**exp, Expr::Num(r) if r.is_integer())
            }
            _ => self.is_number_like(),
        }
    }

    /// A number, or a [`Expr::numeral`]: a factor that takes a `⋅` after another (`3 ⋅ 9.81`).
    pub fn is_number_like(&self) -> bool {
        match self {
            Expr::Num(_) => true,
            Expr::Sym(s) => s.starts_with(|c: char| c.is_ascii_digit()),
            _ => false,
        }
    }

    /// Sum with light folding: flattens nested sums, drops zeros.
    pub fn add(terms: Vec<Expr>) -> Expr {
        let mut out = Vec::new();
        let mut constant = Rational::ZERO;
        // The numbers summed where the first stands, as an author writes 1 + cos θ.
        let mut at = None;
        for t in terms {
            match t {
                Expr::Add(inner) => out.extend(inner),
                Expr::Num(r) => {
                    at.get_or_insert(out.len());
                    constant = constant.add(&r);
                }
                other => out.push(other),
            }
        }
        if !constant.is_zero() {
            out.insert(at.unwrap_or(out.len()), Expr::Num(constant));
        }
        match out.len() {
            0 => Expr::int(0),
            1 => out.pop().unwrap(),
            _ => Expr::Add(out),
        }
    }

    /// Product with light folding: flattens, multiplies numbers, a zero factor gives zero.
    pub fn mul(factors: Vec<Expr>) -> Expr {
        let mut out = Vec::new();
        let mut coefficient = Rational::ONE;
        for f in factors {
            match f {
                Expr::Mul(inner) => {
                    for g in inner {
                        match g {
                            Expr::Num(r) => coefficient = coefficient.mul(&r),
                            other => out.push(other),
                        }
                    }
                }
                Expr::Num(r) => coefficient = coefficient.mul(&r),
                other => out.push(other),
            }
        }
        if coefficient.is_zero() {
            return Expr::int(0);
        }
        if coefficient != Rational::ONE {
            out.insert(0, Expr::Num(coefficient));
        }
        match out.len() {
            0 => Expr::int(1),
            1 => out.pop().unwrap(),
            _ => Expr::Mul(out),
        }
    }

    pub fn negate(e: Expr) -> Expr {
        Expr::mul(vec![Expr::int(-1), e])
    }

    pub fn minus(a: Expr, b: Expr) -> Expr {
        Expr::add(vec![a, Expr::negate(b)])
    }

    pub fn pow(base: Expr, exponent: Expr) -> Expr {
        if exponent.is_one() {
            return base;
        }
        if exponent.is_zero() {
            return Expr::int(1);
        }
        // (b^p)^q = b^(pq) holds for every real b when q is an integer.
        if let (Expr::Pow(b, p), Expr::Num(q)) = (&base, &exponent)
            && q.is_integer()
            && let Expr::Num(p) = p.as_ref()
        {
            return Expr::pow(b.as_ref().clone(), Expr::Num(p.mul(q)));
        }
        Expr::Pow(Box::new(base), Box::new(exponent))
    }

    pub fn over(a: Expr, b: Expr) -> Expr {
        if let Expr::Num(r) = &b
            && let Some(inv) = r.recip()
        {
            return Expr::mul(vec![Expr::Num(inv), a]);
        }
        Expr::mul(vec![a, Expr::pow(b, Expr::int(-1))])
    }

    /// A product with its factors in a fixed order: the number first, then symbols, then
    /// functions, each by ascending exponent and name (m*a^2, M*R^2*cos(alpha)).
    pub fn ordered_product(factors: Vec<Expr>) -> Expr {
        let mut f = match Expr::mul(factors) {
            Expr::Mul(f) => f,
            other => return other,
        };
        f.sort_by(|x, y| {
            factor_key(x)
                .partial_cmp(&factor_key(y))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        Expr::Mul(f)
    }

    /// A sum with its terms in a fixed order: by their text without the numeric coefficient,
    /// constants last.
    pub fn ordered_sum(terms: Vec<Expr>) -> Expr {
        let mut t = match Expr::add(terms) {
            Expr::Add(t) => t,
            other => return other,
        };
        t.sort_by_cached_key(term_key);
        Expr::Add(t)
    }

    /// Every symbol name used, sorted and unique.
    pub fn symbols(&self) -> Vec<String> {
        let mut out = Vec::new();
        self.walk(&mut |e| {
            if let Expr::Sym(s) = e {
                out.push(s.clone());
            }
        });
        out.sort();
        out.dedup();
        out
    }

    /// Visits the expression and every sub-expression, parents first.
    pub fn walk(&self, f: &mut dyn FnMut(&Expr)) {
        f(self);
        match self {
            Expr::Num(_) | Expr::Sym(_) => {}
            Expr::Add(v) | Expr::Mul(v) | Expr::Call(_, v) | Expr::List(v) => {
                v.iter().for_each(|e| e.walk(f))
            }
            Expr::Pow(a, b) | Expr::Index(a, b) => {
                a.walk(f);
                b.walk(f);
            }
        }
    }

    /// Replaces symbols by expressions.
    pub fn substitute(&self, map: &dyn Fn(&str) -> Option<Expr>) -> Expr {
        match self {
            Expr::Num(_) => self.clone(),
            Expr::Sym(s) => map(s).unwrap_or_else(|| self.clone()),
            Expr::Add(v) => Expr::add(v.iter().map(|e| e.substitute(map)).collect()),
            Expr::Mul(v) => Expr::mul(v.iter().map(|e| e.substitute(map)).collect()),
            Expr::Pow(a, b) => Expr::pow(a.substitute(map), b.substitute(map)),
            Expr::Call(n, v) => {
                Expr::Call(n.clone(), v.iter().map(|e| e.substitute(map)).collect())
            }
            Expr::List(v) => Expr::List(v.iter().map(|e| e.substitute(map)).collect()),
            Expr::Index(a, b) => {
                Expr::Index(Box::new(a.substitute(map)), Box::new(b.substitute(map)))
            }
        }
    }

    /// The derivative with respect to `x` by the sum, product and chain rules (no simplification:
    /// the engine's zero test does that).
    pub fn diff(&self, x: &str) -> Result<Expr, DiffError> {
        Ok(match self {
            Expr::Num(_) => Expr::int(0),
            Expr::Sym(s) => Expr::int(i128::from(s == x)),
            Expr::Add(v) => Expr::add(v.iter().map(|t| t.diff(x)).collect::<Result<_, _>>()?),
            Expr::Mul(v) => {
                let mut terms = Vec::new();
                for i in 0..v.len() {
                    let mut f: Vec<Expr> = v.clone();
                    f[i] = v[i].diff(x)?;
                    terms.push(Expr::mul(f));
                }
                Expr::add(terms)
            }
            Expr::Pow(a, b) => {
                if b.symbols().iter().any(|s| s == x) {
                    return Err(DiffError::VariableExponent { var: x.into() });
                }
                let lower = Expr::pow(
                    a.as_ref().clone(),
                    Expr::minus(b.as_ref().clone(), Expr::int(1)),
                );
                Expr::mul(vec![b.as_ref().clone(), lower, a.diff(x)?])
            }
            Expr::Call(name, args) if super::functions::arity(name) == Some(args.len()) => {
                let mut terms = Vec::new();
                for (k, u) in args.iter().enumerate() {
                    let du = u.diff(x)?;
                    if du.is_zero() {
                        continue;
                    }
                    let outer = partial(name, args, k)
                        .ok_or_else(|| DiffError::Function { name: name.clone() })?;
                    terms.push(Expr::mul(vec![outer, du]));
                }
                Expr::add(terms)
            }
            Expr::Call(name, _) => return Err(DiffError::Function { name: name.clone() }),
            _ => return Err(DiffError::NotScalar),
        })
    }

    /// Evaluates a scalar expression in f64. `pi` is π unless the environment binds it.
    pub fn eval(&self, env: &dyn Fn(&str) -> Option<f64>) -> Result<f64, EvalError> {
        Ok(match self {
            Expr::Num(r) => r.to_f64(),
            Expr::Sym(s) => match env(s) {
                Some(v) => v,
                None if s == "pi" => std::f64::consts::PI,
                None => return Err(EvalError::NoValue(s.clone())),
            },
            Expr::Add(v) => v.iter().map(|e| e.eval(env)).sum::<Result<f64, _>>()?,
            Expr::Mul(v) => v.iter().map(|e| e.eval(env)).product::<Result<f64, _>>()?,
            Expr::Pow(a, b) => {
                let base = a.eval(env)?;
                match b.as_ref() {
                    Expr::Num(r) if r.to_i64().is_some_and(|k| k.unsigned_abs() < 64) => {
                        base.powi(r.to_i64().unwrap_or(1) as i32)
                    }
                    other => base.powf(other.eval(env)?),
                }
            }
            Expr::Call(name, args) => {
                let xs = args
                    .iter()
                    .map(|a| a.eval(env))
                    .collect::<Result<Vec<_>, _>>()?;
                super::functions::value(name, &xs)
                    .ok_or_else(|| EvalError::NotScalarFunction(name.clone()))?
            }
            Expr::List(_) | Expr::Index(..) => return Err(EvalError::NotScalar),
        })
    }
}

impl Expr {
    /// The exact value of a scalar built from numbers and symbols bound to rationals by `env`
    /// with `+`, `*` and integer powers; `None` for anything else (π, a root, a function, an
    /// unbound symbol) or a division by zero.
    pub fn eval_rational(&self, env: &dyn Fn(&str) -> Option<Rational>) -> Option<Rational> {
        match self {
            Expr::Num(r) => Some(r.clone()),
            Expr::Sym(s) => env(s),
            Expr::Add(v) => v.iter().try_fold(Rational::ZERO, |acc, e| {
                Some(acc.add(&e.eval_rational(env)?))
            }),
            Expr::Mul(v) => v.iter().try_fold(Rational::ONE, |acc, e| {
                Some(acc.mul(&e.eval_rational(env)?))
            }),
            Expr::Pow(a, b) => {
                let k = match b.as_ref() {
                    Expr::Num(r) => r.to_i64().filter(|k| k.unsigned_abs() <= 64)?,
                    _ => return None,
                };
                a.eval_rational(env)?.pow(k)
            }
            _ => None,
        }
    }
}

/// (kind, exponent, lower-case name, name) of a factor; numbers sort first.
fn factor_key(e: &Expr) -> (u8, f64, String, String) {
    let (base, exponent) = match e {
        Expr::Pow(b, x) => (b.as_ref(), x.eval(&|_| None).unwrap_or(f64::MAX)),
        other => (other, 1.0),
    };
    // The coefficient first, then roots of numbers (1/8*3^(1/2), not 3^(1/2)*(1/8)).
    let rank = match (e, base) {
        (Expr::Num(_), _) => 0,
        (_, Expr::Num(_)) => 1,
        (_, Expr::Sym(_)) => 2,
        (_, Expr::Call(..)) => 3,
        _ => 4,
    };
    let text = base.to_text();
    (rank, exponent, text.to_lowercase(), text)
}

/// (is a constant, text without the numeric coefficient, full text) of a term.
fn term_key(e: &Expr) -> (bool, String, String) {
    let monomial = match e {
        Expr::Mul(f) => Expr::Mul(
            f.iter()
                .filter(|x| !matches!(x, Expr::Num(_)))
                .cloned()
                .collect(),
        ),
        other => other.clone(),
    };
    (matches!(e, Expr::Num(_)), monomial.to_text(), e.to_text())
}

/// The derivative of `name(args)` with respect to its `k`-th argument, by the textbook rules;
/// `None` for a name that is not elementary. The chain rule is the caller's.
fn partial(name: &str, args: &[Expr], k: usize) -> Option<Expr> {
    let u = args.first()?.clone();
    let square = |e: Expr| Expr::pow(e, Expr::int(2));
    let one_minus_square_root =
        |u: Expr| Expr::pow(Expr::minus(Expr::int(1), square(u)), Expr::rat(1, 2));
    Some(match (name, k) {
        ("sin", 0) => Expr::call("cos", u),
        ("cos", 0) => Expr::negate(Expr::call("sin", u)),
        ("sqrt", 0) => Expr::over(
            Expr::int(1),
            Expr::mul(vec![Expr::int(2), Expr::call("sqrt", u)]),
        ),
        ("exp", 0) => Expr::call("exp", u),
        ("log", 0) => Expr::over(Expr::int(1), u),
        // d asin u = du/√(1 − u²), d acos u = −du/√(1 − u²).
        ("asin", 0) => Expr::over(Expr::int(1), one_minus_square_root(u)),
        ("acos", 0) => Expr::over(Expr::int(-1), one_minus_square_root(u)),
        ("atan", 0) => Expr::over(Expr::int(1), Expr::add(vec![Expr::int(1), square(u)])),
        ("sinh", 0) => Expr::call("cosh", u),
        ("cosh", 0) => Expr::call("sinh", u),
        // d|u| = u/|u| du, away from u = 0.
        ("abs", 0) => Expr::over(u.clone(), Expr::call("abs", u)),
        // atan2(y, x), the angle of the point (x, y): ∂/∂y = x/(x² + y²), ∂/∂x = −y/(x² + y²).
        ("atan2", 0 | 1) => {
            let x = args.get(1)?.clone();
            let r2 = Expr::add(vec![square(x.clone()), square(u.clone())]);
            if k == 0 {
                Expr::over(x, r2)
            } else {
                Expr::over(Expr::negate(u), r2)
            }
        }
        _ => return None,
    })
}
