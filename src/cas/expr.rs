//! Our own exact expression tree. It crosses the `cas` boundary in both directions, so the rest
//! of the program never sees a Symbolica type.
//!
//! The same tree also carries the claim language of scene files: list literals `[a, b, c]`,
//! indexing `v[0]` and calls such as `cross(u, v)`. Those are resolved by `derive::algebra` into
//! scalars, vectors and matrices before anything reaches the engine.

use super::rational::Rational;
use std::fmt;

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

/// The scalar functions the engine and the evaluator understand.
pub const SCALAR_FUNCTIONS: &[&str] = &["sin", "cos", "sqrt"];

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

    /// Sum with light folding: flattens nested sums, drops zeros.
    pub fn add(terms: Vec<Expr>) -> Expr {
        let mut out = Vec::new();
        let mut constant = Rational::ZERO;
        for t in terms {
            match t {
                Expr::Add(inner) => out.extend(inner),
                Expr::Num(r) => constant = constant.add(&r),
                other => out.push(other),
            }
        }
        if !constant.is_zero() {
            out.push(Expr::Num(constant));
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

    fn walk(&self, f: &mut dyn FnMut(&Expr)) {
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
    pub fn diff(&self, x: &str) -> Result<Expr, String> {
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
                    return Err(format!(
                        "cannot differentiate a power whose exponent depends on `{x}`"
                    ));
                }
                let lower = Expr::pow(
                    a.as_ref().clone(),
                    Expr::minus(b.as_ref().clone(), Expr::int(1)),
                );
                Expr::mul(vec![b.as_ref().clone(), lower, a.diff(x)?])
            }
            Expr::Call(name, args) if args.len() == 1 => {
                let u = &args[0];
                let outer = match name.as_str() {
                    "sin" => Expr::call("cos", u.clone()),
                    "cos" => Expr::negate(Expr::call("sin", u.clone())),
                    "sqrt" => Expr::over(Expr::int(1), Expr::mul(vec![Expr::int(2), self.clone()])),
                    _ => return Err(format!("cannot differentiate `{name}`")),
                };
                Expr::mul(vec![outer, u.diff(x)?])
            }
            _ => return Err("only scalar expressions can be differentiated".into()),
        })
    }

    /// Evaluates a scalar expression in f64. `pi` is π unless the environment binds it.
    pub fn eval(&self, env: &dyn Fn(&str) -> Option<f64>) -> Result<f64, String> {
        Ok(match self {
            Expr::Num(r) => r.to_f64(),
            Expr::Sym(s) => match env(s) {
                Some(v) => v,
                None if s == "pi" => std::f64::consts::PI,
                None => return Err(format!("no value for symbol `{s}`")),
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
            Expr::Call(name, args) if args.len() == 1 => {
                let x = args[0].eval(env)?;
                match name.as_str() {
                    "sin" => x.sin(),
                    "cos" => x.cos(),
                    "sqrt" => x.sqrt(),
                    _ => return Err(format!("`{name}` is not a scalar function")),
                }
            }
            Expr::Call(name, _) => return Err(format!("`{name}` is not a scalar function")),
            Expr::List(_) | Expr::Index(..) => {
                return Err("a vector or matrix where a scalar was expected".into());
            }
        })
    }

    /// Plain text in the syntax the parser reads back (and that Symbolica reads).
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        write_text(self, &mut s, Prec::Sum, &|n| n.to_string());
        s
    }

    /// Text with every symbol renamed, for engines with reserved names.
    pub fn to_text_with(&self, rename: &dyn Fn(&str) -> String) -> String {
        let mut s = String::new();
        write_text(self, &mut s, Prec::Sum, rename);
        s
    }

    pub fn to_latex(&self) -> String {
        let mut s = String::new();
        write_latex(self, &mut s, Prec::Sum);
        s
    }
}

impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_text())
    }
}

/// (kind, exponent, lower-case name, name) of a factor; numbers sort first.
fn factor_key(e: &Expr) -> (u8, f64, String, String) {
    let (base, exponent) = match e {
        Expr::Pow(b, x) => (b.as_ref(), x.eval(&|_| None).unwrap_or(f64::MAX)),
        other => (other, 1.0),
    };
    let rank = match base {
        Expr::Num(_) => 0,
        Expr::Sym(_) => 1,
        Expr::Call(..) => 2,
        _ => 3,
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

#[derive(Clone, Copy, PartialEq, PartialOrd)]
enum Prec {
    Sum,
    Product,
    /// A factor of a product.
    Factor,
    /// The base or exponent of a power.
    Power,
}

/// Splits product factors into the numerator and the inverted denominator factors.
fn split_fraction(v: &[Expr]) -> (Vec<Expr>, Vec<Expr>) {
    let (mut num, mut den) = (Vec::new(), Vec::new());
    for f in v {
        match f {
            Expr::Pow(b, x) if matches!(x.as_ref(), Expr::Num(r) if r.is_negative() && r.is_integer()) =>
            {
                let Expr::Num(r) = x.as_ref() else {
                    unreachable!()
                };
                den.push(Expr::pow(b.as_ref().clone(), Expr::Num(r.negated())));
            }
            other => num.push(other.clone()),
        }
    }
    (num, den)
}

/// A term of a sum printed with its sign: `(negative, magnitude)`.
fn split_sign(e: &Expr) -> (bool, Expr) {
    match e {
        Expr::Num(r) if r.is_negative() => (true, Expr::Num(r.negated())),
        Expr::Mul(v) => match v.first() {
            Some(Expr::Num(r)) if r.is_negative() => {
                let mut rest = v.clone();
                rest[0] = Expr::Num(r.negated());
                (true, Expr::mul(rest))
            }
            _ => (false, e.clone()),
        },
        _ => (false, e.clone()),
    }
}

fn write_text(e: &Expr, out: &mut String, ctx: Prec, rename: &dyn Fn(&str) -> String) {
    match e {
        Expr::Num(r) => {
            let needs =
                (!r.is_integer() && ctx > Prec::Product) || (r.is_negative() && ctx > Prec::Sum);
            let needs = needs || (!r.is_integer() && ctx == Prec::Power);
            if needs {
                out.push('(');
            }
            out.push_str(&r.to_string());
            if needs {
                out.push(')');
            }
        }
        Expr::Sym(s) => out.push_str(&rename(s)),
        Expr::Add(v) => {
            if ctx > Prec::Sum {
                out.push('(');
            }
            for (i, t) in v.iter().enumerate() {
                let (negative, mag) = split_sign(t);
                if i == 0 {
                    if negative {
                        out.push('-');
                    }
                } else {
                    out.push_str(if negative { " - " } else { " + " });
                }
                write_text(&mag, out, Prec::Product, rename);
            }
            if ctx > Prec::Sum {
                out.push(')');
            }
        }
        Expr::Mul(v) => {
            let (negative, mag) = split_sign(e);
            if negative {
                if ctx > Prec::Sum {
                    out.push('(');
                }
                out.push('-');
                write_text(&mag, out, Prec::Product, rename);
                if ctx > Prec::Sum {
                    out.push(')');
                }
                return;
            }
            if ctx > Prec::Product {
                out.push('(');
            }
            // Factors with negative integer exponents go below a fraction bar: (y^2 + z^2)/a^3.
            let (num, den) = split_fraction(v);
            for (i, f) in num.iter().enumerate() {
                if i > 0 {
                    out.push('*');
                }
                // A leading positive fraction reads correctly without parentheses: 1/2*M.
                let ctx = if i == 0 && matches!(f, Expr::Num(_)) {
                    Prec::Product
                } else {
                    Prec::Factor
                };
                write_text(f, out, ctx, rename);
            }
            if num.is_empty() {
                out.push('1');
            }
            if !den.is_empty() {
                out.push('/');
                let d = Expr::mul(den);
                write_text(
                    &d,
                    out,
                    if matches!(d, Expr::Mul(_)) {
                        Prec::Power
                    } else {
                        Prec::Factor
                    },
                    rename,
                );
            }
            if ctx > Prec::Product {
                out.push(')');
            }
        }
        Expr::Pow(a, b) => {
            if ctx > Prec::Factor {
                out.push('(');
            }
            write_text(a, out, Prec::Power, rename);
            out.push('^');
            write_text(b, out, Prec::Power, rename);
            if ctx > Prec::Factor {
                out.push(')');
            }
        }
        Expr::Call(n, args) => {
            out.push_str(n);
            out.push('(');
            for (i, a) in args.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                write_text(a, out, Prec::Sum, rename);
            }
            out.push(')');
        }
        Expr::List(v) => {
            out.push('[');
            for (i, a) in v.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                write_text(a, out, Prec::Sum, rename);
            }
            out.push(']');
        }
        Expr::Index(a, i) => {
            write_text(a, out, Prec::Power, rename);
            out.push('[');
            write_text(i, out, Prec::Sum, rename);
            out.push(']');
        }
    }
}

const GREEK: &[&str] = &[
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
    "lambda", "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "phi", "chi", "psi", "omega", "Gamma",
    "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Phi", "Psi", "Omega",
];

/// `alpha` -> `\alpha`, `w1` -> `\omega_{1}`, `wd1` -> `\dot{\omega}_{1}`, `Ixx` -> `I_{xx}`,
/// `inertia_tensor` -> upright text.
fn latex_symbol(s: &str) -> String {
    if let Some((_, tail)) = s.split_once('_')
        && !tail.chars().all(|c| c.is_ascii_digit())
    {
        return format!("\\mathrm{{{}}}", s.replace('_', "\\_"));
    }
    let split = s
        .char_indices()
        .find(|(i, c)| *i > 0 && (c.is_ascii_digit() || *c == '_'))
        .map(|(i, _)| i);
    let (head, tail) = match split {
        Some(i) => (&s[..i], s[i..].trim_start_matches('_')),
        None => (s, ""),
    };
    // ω is written w in scene files: w1 is ω₁ and wd1 its rate.
    let numbered = !tail.is_empty() && tail.chars().all(|c| c.is_ascii_digit());
    let head = if numbered && head == "w" {
        "\\omega".to_string()
    } else if numbered && head == "wd" {
        "\\dot{\\omega}".to_string()
    } else if GREEK.contains(&head) {
        format!("\\{head}")
    } else if head.len() > 1
        && head.starts_with('I')
        && head[1..].chars().all(|c| "xyz".contains(c))
    {
        return format!("I_{{{}}}", &head[1..]);
    } else if head.len() > 1 {
        format!("\\mathrm{{{head}}}")
    } else {
        head.to_string()
    };
    if tail.is_empty() {
        head
    } else {
        format!("{head}_{{{tail}}}")
    }
}

fn write_latex(e: &Expr, out: &mut String, ctx: Prec) {
    match e {
        Expr::Num(r) => {
            let body = if r.is_integer() {
                r.to_string()
            } else {
                let (num, den) = r.abs_parts();
                format!("\\frac{{{num}}}{{{den}}}")
            };
            let negative = r.is_negative();
            if negative && ctx > Prec::Sum {
                out.push_str("\\left(");
            }
            if negative && !r.is_integer() {
                out.push('-');
            }
            out.push_str(&body);
            if negative && ctx > Prec::Sum {
                out.push_str("\\right)");
            }
        }
        Expr::Sym(s) => out.push_str(&latex_symbol(s)),
        Expr::Add(v) => {
            if ctx > Prec::Sum {
                out.push_str("\\left(");
            }
            for (i, t) in v.iter().enumerate() {
                let (negative, mag) = split_sign(t);
                if i == 0 {
                    if negative {
                        out.push('-');
                    }
                } else {
                    out.push_str(if negative { " - " } else { " + " });
                }
                write_latex(&mag, out, Prec::Product);
            }
            if ctx > Prec::Sum {
                out.push_str("\\right)");
            }
        }
        Expr::Mul(v) => {
            let (negative, mag) = split_sign(e);
            if negative {
                if ctx > Prec::Sum {
                    out.push_str("\\left(");
                }
                out.push('-');
                write_latex(&mag, out, Prec::Product);
                if ctx > Prec::Sum {
                    out.push_str("\\right)");
                }
                return;
            }
            // Collect negative powers into a fraction.
            let (mut num, mut den) = (Vec::new(), Vec::new());
            for f in v {
                match f {
                    Expr::Pow(b, x) if matches!(x.as_ref(), Expr::Num(r) if r.is_negative()) => {
                        let Expr::Num(r) = x.as_ref() else {
                            unreachable!()
                        };
                        den.push(Expr::pow(b.as_ref().clone(), Expr::Num(r.negated())));
                    }
                    Expr::Num(r) if !r.is_integer() => {
                        let (n, d) = r.abs_parts();
                        num.push(Expr::Num(if r.is_negative() { n.negated() } else { n }));
                        den.push(Expr::Num(d));
                    }
                    other => num.push(other.clone()),
                }
            }
            if ctx > Prec::Product {
                out.push_str("\\left(");
            }
            let write_factors = |fs: &[Expr], out: &mut String| {
                let fs: Vec<&Expr> = fs.iter().filter(|f| !f.is_one()).collect();
                if fs.is_empty() {
                    out.push('1');
                }
                // A lone factor needs no parentheses: \frac{a + b}{c}, not \frac{(a + b)}{c}.
                let ctx = if fs.len() == 1 {
                    Prec::Sum
                } else {
                    Prec::Power
                };
                for (i, f) in fs.iter().enumerate() {
                    if i > 0 {
                        out.push_str(if matches!(f, Expr::Num(_)) {
                            " \\cdot "
                        } else {
                            " "
                        });
                    }
                    write_latex(f, out, ctx);
                }
            };
            if den.is_empty() {
                write_factors(&num, out);
            } else {
                out.push_str("\\frac{");
                write_factors(&num, out);
                out.push_str("}{");
                write_factors(&den, out);
                out.push('}');
            }
            if ctx > Prec::Product {
                out.push_str("\\right)");
            }
        }
        Expr::Pow(a, b) => {
            if let Expr::Num(r) = b.as_ref() {
                if *r == Rational::new(1, 2).unwrap() {
                    out.push_str("\\sqrt{");
                    write_latex(a, out, Prec::Sum);
                    out.push('}');
                    return;
                }
                if r.is_negative() {
                    out.push_str("\\frac{1}{");
                    write_latex(
                        &Expr::pow(a.as_ref().clone(), Expr::Num(r.negated())),
                        out,
                        Prec::Sum,
                    );
                    out.push('}');
                    return;
                }
            }
            // sin(x)^2 prints as {\sin}^{2}(x): the braces keep the converter's MathML valid.
            if let Expr::Call(n, args) = a.as_ref()
                && (n == "sin" || n == "cos")
            {
                out.push_str(&format!("\\,{{\\{n}}}^{{"));
                write_latex(b, out, Prec::Sum);
                out.push_str("}\\left(");
                write_latex(&args[0], out, Prec::Sum);
                out.push_str("\\right)");
                return;
            }
            write_latex(a, out, Prec::Power);
            out.push_str("^{");
            write_latex(b, out, Prec::Sum);
            out.push('}');
        }
        Expr::Call(n, args) => {
            if n == "sqrt" && args.len() == 1 {
                out.push_str("\\sqrt{");
                write_latex(&args[0], out, Prec::Sum);
                out.push('}');
                return;
            }
            if n == "sin" || n == "cos" {
                out.push_str(&format!("\\{n}\\left("));
            } else {
                out.push_str(&format!("\\operatorname{{{n}}}\\left("));
            }
            for (i, a) in args.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                write_latex(a, out, Prec::Sum);
            }
            out.push_str("\\right)");
        }
        Expr::List(v) => {
            let is_matrix = v.iter().all(|r| matches!(r, Expr::List(_)));
            out.push_str("\\begin{pmatrix}");
            for (i, row) in v.iter().enumerate() {
                if i > 0 {
                    out.push_str(if is_matrix { " \\\\ " } else { " & " });
                }
                match row {
                    Expr::List(cells) if is_matrix => {
                        for (j, c) in cells.iter().enumerate() {
                            if j > 0 {
                                out.push_str(" & ");
                            }
                            write_latex(c, out, Prec::Sum);
                        }
                    }
                    other => write_latex(other, out, Prec::Sum),
                }
            }
            out.push_str("\\end{pmatrix}");
        }
        Expr::Index(..) => {
            // v[0][2] -> v_{0 2}: one subscript for the whole chain.
            let mut indices = Vec::new();
            let mut base = e;
            while let Expr::Index(b, i) = base {
                indices.push(i.as_ref());
                base = b;
            }
            write_latex(base, out, Prec::Power);
            out.push_str("_{");
            for (k, i) in indices.iter().rev().enumerate() {
                if k > 0 {
                    out.push(' ');
                }
                write_latex(i, out, Prec::Sum);
            }
            out.push('}');
        }
    }
}

/// A parse error: what went wrong and the byte offset in the text.
#[derive(Debug, Clone, PartialEq)]
pub struct ParseError {
    pub offset: usize,
    pub message: String,
}

/// A parsed expression with the byte offset of every symbol, so that callers can point at an
/// undefined one.
#[derive(Debug, Clone)]
pub struct Parsed {
    pub expr: Expr,
    pub symbols: Vec<(String, usize)>,
}

/// The longest expression, in bytes, a scene may write: eight times the longest in the shipped
/// lectures (501), and short enough that parsing and printing stay instant.
pub const MAX_EXPR_BYTES: usize = 4000;

/// The deepest nesting of parentheses, brackets, calls, signs and powers: real expressions
/// nest a few levels, and every stage that walks the tree recurses once a level.
pub const MAX_NESTING: usize = 64;

/// The nesting limit for our own texts read back (the engine's output, a derived result):
/// they can be longer than any scene's input, but never deeper than this, and the recursion
/// stays far inside a thread's stack.
const MAX_INTERNAL_NESTING: usize = 256;

/// Parses a scene's `text` in the scene expression language (numbers, names, `+ - * / ^`,
/// calls, `[..]` lists and `v[i]` indexing), within the input limits: [`MAX_EXPR_BYTES`] and
/// [`MAX_NESTING`].
pub fn parse_input(text: &str) -> Result<Parsed, ParseError> {
    if text.len() > MAX_EXPR_BYTES {
        return Err(ParseError {
            offset: 0,
            message: format!(
                "expression of {} bytes; the limit is {MAX_EXPR_BYTES}: split it with [definitions]",
                text.len()
            ),
        });
    }
    parse_with(text, MAX_NESTING)
}

/// Parses text that mechbook made itself: no length limit, and a generous nesting limit.
pub fn parse(text: &str) -> Result<Parsed, ParseError> {
    parse_with(text, MAX_INTERNAL_NESTING)
}

fn parse_with(text: &str, max_depth: usize) -> Result<Parsed, ParseError> {
    let mut p = Parser {
        src: text.as_bytes(),
        pos: 0,
        depth: 0,
        max_depth,
        symbols: Vec::new(),
    };
    p.skip_ws();
    if p.pos >= p.src.len() {
        return Err(p.error("empty expression"));
    }
    let expr = p.sum()?;
    p.skip_ws();
    if p.pos < p.src.len() {
        return Err(p.error(&unexpected(&p.src[p.pos..], p.src[p.pos])));
    }
    Ok(Parsed {
        expr,
        symbols: p.symbols,
    })
}

/// "unexpected `x`", naming the whole character (not its first byte) and never a control one.
fn unexpected(rest: &[u8], first: u8) -> String {
    let text = String::from_utf8_lossy(&rest[..rest.len().min(4)]);
    match text.chars().next() {
        Some(c) if c.is_control() => format!("unexpected control character U+{:04X}", c as u32),
        Some(c) if !first.is_ascii() => format!("unexpected `{c}`"),
        _ => format!("unexpected `{}`", first as char),
    }
}

struct Parser<'a> {
    src: &'a [u8],
    pos: usize,
    /// How deep the recursion is: every nesting passes through `unary`.
    depth: usize,
    max_depth: usize,
    symbols: Vec<(String, usize)>,
}

impl Parser<'_> {
    fn error(&self, message: &str) -> ParseError {
        ParseError {
            offset: self.pos,
            message: message.to_string(),
        }
    }

    fn skip_ws(&mut self) {
        while self.pos < self.src.len() && self.src[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    fn peek(&mut self) -> Option<u8> {
        self.skip_ws();
        self.src.get(self.pos).copied()
    }

    fn expect(&mut self, c: u8) -> Result<(), ParseError> {
        if self.peek() == Some(c) {
            self.pos += 1;
            Ok(())
        } else {
            Err(self.error(&format!("expected `{}`", c as char)))
        }
    }

    fn sum(&mut self) -> Result<Expr, ParseError> {
        let mut terms = vec![self.product()?];
        loop {
            match self.peek() {
                Some(b'+') => {
                    self.pos += 1;
                    terms.push(self.product()?);
                }
                Some(b'-') => {
                    self.pos += 1;
                    terms.push(Expr::negate(self.product()?));
                }
                _ => break,
            }
        }
        Ok(Expr::add(terms))
    }

    fn product(&mut self) -> Result<Expr, ParseError> {
        let mut factors = vec![self.unary()?];
        loop {
            match self.peek() {
                Some(b'*') => {
                    self.pos += 1;
                    factors.push(self.unary()?);
                }
                Some(b'/') => {
                    self.pos += 1;
                    let at = self.pos;
                    let d = self.unary()?;
                    if d.is_zero() {
                        return Err(ParseError {
                            offset: at,
                            message: "division by zero".into(),
                        });
                    }
                    factors.push(Expr::over(Expr::int(1), d));
                }
                _ => break,
            }
        }
        Ok(Expr::mul(factors))
    }

    fn unary(&mut self) -> Result<Expr, ParseError> {
        self.depth += 1;
        if self.depth > self.max_depth {
            return Err(self.error(&format!(
                "nested more than {} levels deep: simplify it, or split it with [definitions]",
                self.max_depth
            )));
        }
        let e = self.unary_inner();
        self.depth -= 1;
        e
    }

    fn unary_inner(&mut self) -> Result<Expr, ParseError> {
        match self.peek() {
            Some(b'-') => {
                self.pos += 1;
                Ok(Expr::negate(self.unary()?))
            }
            Some(b'+') => {
                self.pos += 1;
                self.unary()
            }
            _ => self.power(),
        }
    }

    fn power(&mut self) -> Result<Expr, ParseError> {
        let base = self.postfix()?;
        if self.peek() == Some(b'^') {
            self.pos += 1;
            // Right-associative; the exponent may carry its own sign.
            let exponent = self.unary()?;
            return Ok(Expr::pow(base, exponent));
        }
        Ok(base)
    }

    fn postfix(&mut self) -> Result<Expr, ParseError> {
        let mut e = self.atom()?;
        while self.peek() == Some(b'[') {
            self.pos += 1;
            let i = self.sum()?;
            self.expect(b']')?;
            e = Expr::Index(Box::new(e), Box::new(i));
        }
        Ok(e)
    }

    fn atom(&mut self) -> Result<Expr, ParseError> {
        let start = self.pos;
        match self.peek() {
            None => Err(self.error("unexpected end of expression")),
            Some(b'(') => {
                self.pos += 1;
                let e = self.sum()?;
                self.expect(b')')?;
                Ok(e)
            }
            Some(b'[') => {
                self.pos += 1;
                let mut items = vec![self.sum()?];
                while self.peek() == Some(b',') {
                    self.pos += 1;
                    items.push(self.sum()?);
                }
                self.expect(b']')?;
                Ok(Expr::List(items))
            }
            Some(c) if c.is_ascii_digit() || c == b'.' => {
                let s = self.pos;
                while self.pos < self.src.len()
                    && (self.src[self.pos].is_ascii_digit() || self.src[self.pos] == b'.')
                {
                    self.pos += 1;
                }
                // An exponent `e-3` only when a digit follows.
                if self.pos + 1 < self.src.len() && matches!(self.src[self.pos], b'e' | b'E') {
                    let mut q = self.pos + 1;
                    if matches!(self.src[q], b'+' | b'-') {
                        q += 1;
                    }
                    if q < self.src.len() && self.src[q].is_ascii_digit() {
                        self.pos = q;
                        while self.pos < self.src.len() && self.src[self.pos].is_ascii_digit() {
                            self.pos += 1;
                        }
                    }
                }
                let text = std::str::from_utf8(&self.src[s..self.pos]).unwrap_or("?");
                Rational::parse_decimal(text)
                    .map(Expr::Num)
                    .ok_or(ParseError {
                        offset: s,
                        message: format!(
                            "malformed number `{text}` (at most {} digits, exponents within ±{})",
                            super::rational::MAX_DIGITS,
                            super::rational::MAX_EXPONENT
                        ),
                    })
            }
            Some(c) if c.is_ascii_alphabetic() => {
                let s = self.pos;
                while self.pos < self.src.len()
                    && (self.src[self.pos].is_ascii_alphanumeric() || self.src[self.pos] == b'_')
                {
                    self.pos += 1;
                }
                let name = String::from_utf8_lossy(&self.src[s..self.pos]).into_owned();
                if self.peek() == Some(b'(') {
                    self.pos += 1;
                    if self.peek() == Some(b')') {
                        self.pos += 1;
                        return Ok(Expr::Call(name, Vec::new()));
                    }
                    let mut args = vec![self.sum()?];
                    while self.peek() == Some(b',') {
                        self.pos += 1;
                        args.push(self.sum()?);
                    }
                    self.expect(b')')?;
                    return Ok(Expr::Call(name, args));
                }
                self.symbols.push((name.clone(), s));
                Ok(Expr::Sym(name))
            }
            Some(c) => {
                self.pos = start.max(self.pos);
                Err(self.error(&unexpected(&self.src[self.pos..], c)))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Expr {
        parse(s).unwrap().expr
    }

    #[test]
    fn text_round_trips() {
        for s in [
            "m*a^2*(2/3)",
            "-1/4*a^2*m",
            "1/2*M*R^2*(2 - cos(alpha)^2)",
            "x^(-1)",
            "[[1, 0], [0, 1]]",
            "cross(r, w)[0]",
        ] {
            let e = p(s);
            assert_eq!(p(&e.to_text()), e, "{s} -> {}", e.to_text());
        }
    }

    #[test]
    fn precedence_and_evaluation() {
        let env = |s: &str| match s {
            "a" => Some(2.0),
            "b" => Some(3.0),
            _ => None,
        };
        assert_eq!(p("a + b*a^2").eval(&env).unwrap(), 14.0);
        assert_eq!(p("-a^2").eval(&env).unwrap(), -4.0);
        assert_eq!(p("a/b/a").eval(&env).unwrap(), 1.0 / 3.0);
        assert_eq!(p("2^-1").eval(&env).unwrap(), 0.5);
        assert!((p("cos(pi)").eval(&env).unwrap() + 1.0).abs() < 1e-15);
        assert!(p("c").eval(&env).is_err());
    }

    #[test]
    fn errors_carry_offsets() {
        let e = parse("m*a^^2").unwrap_err();
        assert_eq!(e.offset, 4);
        let e = parse("(a + b").unwrap_err();
        assert_eq!(e.offset, 6);
        assert!(parse("").is_err());
        let syms = parse("m * alpha").unwrap().symbols;
        assert_eq!(syms, vec![("m".into(), 0), ("alpha".into(), 4)]);
    }

    #[test]
    fn derivatives_match_difference_quotients() {
        for text in [
            "a*cos(b*t + c)^2",
            "sqrt(1 + t^2)*sin(t)",
            "t^3/(1 + t)",
            "w*t - 2",
        ] {
            let e = p(text);
            let d = e.diff("t").unwrap();
            let at = |e: &Expr, t: f64| {
                e.eval(&|s| {
                    Some(match s {
                        "t" => t,
                        "a" => 1.3,
                        "b" => 0.7,
                        "c" => -0.2,
                        _ => 2.0,
                    })
                })
                .unwrap()
            };
            let h = 1e-6;
            let fd = (at(&e, 0.4 + h) - at(&e, 0.4 - h)) / (2.0 * h);
            assert!(
                (at(&d, 0.4) - fd).abs() < 1e-8,
                "{text}: {} vs {fd}",
                at(&d, 0.4)
            );
        }
        assert!(p("2^t").diff("t").is_err());
    }

    #[test]
    fn nesting_and_length_are_limited() {
        let deep = format!("{}a{}", "(".repeat(6538), ")".repeat(6538));
        let e = parse_input(&deep[..MAX_EXPR_BYTES]).unwrap_err();
        assert!(e.message.contains("nested more than 64"), "{}", e.message);
        assert_eq!(e.offset, MAX_NESTING);
        let sines = format!("{}x{}", "sin(".repeat(966), ")".repeat(966));
        assert!(
            parse_input(&sines)
                .unwrap_err()
                .message
                .contains("limit is 4000")
        );
        let sines = format!("{}x{}", "sin(".repeat(100), ")".repeat(100));
        assert!(parse_input(&sines).unwrap_err().message.contains("nested"));
        assert!(
            parse_input(&"-".repeat(1000))
                .unwrap_err()
                .message
                .contains("nested")
        );
        assert!(
            parse_input(&format!("a{}", "^a".repeat(200)))
                .unwrap_err()
                .message
                .contains("nested")
        );
        let ok = format!("{}a{}", "(".repeat(60), ")".repeat(60));
        assert_eq!(parse_input(&ok).unwrap().expr, Expr::sym("a"));
        // Our own texts may be longer (a derived result), never deeper than 256.
        let long = vec!["a"; 3000].join(" + ");
        assert!(long.len() > MAX_EXPR_BYTES && parse(&long).is_ok());
        assert!(parse(&format!("{}a{}", "(".repeat(300), ")".repeat(300))).is_err());
    }

    #[test]
    fn big_and_tiny_numbers_stay_exact() {
        assert_eq!(p("1e-10").to_text(), "1/10000000000");
        assert_eq!(p("1e20*1e20").to_text(), format!("1{}", "0".repeat(40)));
        assert!(
            parse("1e5000")
                .unwrap_err()
                .message
                .contains("malformed number")
        );
    }

    #[test]
    fn unexpected_characters_are_named_whole() {
        assert_eq!(
            parse("a \u{1} b").unwrap_err().message,
            "unexpected control character U+0001"
        );
        assert_eq!(parse("a é").unwrap_err().message, "unexpected `é`");
        assert_eq!(parse("\\sin x").unwrap_err().message, "unexpected `\\`");
    }

    #[test]
    fn latex_forms() {
        assert_eq!(p("1/2*M*R^2").to_latex(), "\\frac{M R^{2}}{2}");
        assert_eq!(
            p("sin(alpha)^2").to_latex(),
            "\\,{\\sin}^{2}\\left(\\alpha\\right)"
        );
        assert_eq!(p("w1").to_latex(), "\\omega_{1}");
        assert_eq!(p("wd2").to_latex(), "\\dot{\\omega}_{2}");
        assert_eq!(p("w").to_latex(), "w");
    }
}
