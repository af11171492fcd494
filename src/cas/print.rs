//! Printing an expression: one walk over the tree, shared by the plain text the parser and the
//! engine read back (here) and by `notation`'s LaTeX style (`expr_latex.rs`). The walk decides
//! what they agree on (signs in sums, negative products, where parentheses go); a [`Style`]
//! writes each node's own syntax. The pages' tree (`notation/expr_tree.rs`) follows the same
//! walk.

use super::expr::Expr;
use super::factor::printed_common_factor;
use super::rational::Rational;
use std::fmt;

impl Expr {
    /// Plain text in the syntax the parser reads back (and that Symbolica reads).
    pub fn to_text(&self) -> String {
        self.to_text_with(&|n| n.to_string())
    }

    /// Text with every symbol renamed, for engines with reserved names.
    pub fn to_text_with(&self, rename: &dyn Fn(&str) -> String) -> String {
        let mut s = String::new();
        write(self, &mut s, Prec::Sum, &Text { rename });
        s
    }
}

impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_text())
    }
}

#[derive(Clone, Copy, PartialEq, PartialOrd)]
pub enum Prec {
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

/// A product as the pages set it: negative powers and the denominators of rationals below one
/// fraction bar, the rest above it.
pub fn page_fraction(v: &[Expr]) -> (Vec<Expr>, Vec<Expr>) {
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
    (num, den)
}

/// The factors above or below a page's fraction bar, side by side; `times` before a number
/// (`2 · 3`, where `2 3` would read as 23). A lone factor needs no parentheses:
/// \frac{a + b}{c}, not \frac{(a + b)}{c}.
pub fn page_factors(fs: &[Expr], times: &str, out: &mut String, style: &dyn Style) {
    let fs: Vec<&Expr> = fs.iter().filter(|f| !f.is_one()).collect();
    if fs.is_empty() {
        out.push('1');
    }
    let ctx = if fs.len() == 1 {
        Prec::Sum
    } else {
        Prec::Power
    };
    for (i, f) in fs.iter().enumerate() {
        if i > 0 {
            out.push_str(if f.leads_with_numeral() { times } else { " " });
        }
        write(f, out, ctx, style);
    }
}

/// An index chain `v[0][2]`: its base and its indices in the order written; and, when they are all
/// 0, 1 or 2, the axes they name (`xz`).
pub fn index_chain(e: &Expr) -> (&Expr, Vec<&Expr>, Option<Vec<char>>) {
    let mut indices = Vec::new();
    let mut base = e;
    while let Expr::Index(b, i) = base {
        indices.push(i.as_ref());
        base = b;
    }
    indices.reverse();
    let axes = indices
        .iter()
        .map(|i| match i {
            Expr::Num(r) if r.is_integer() => ["0", "1", "2"]
                .iter()
                .position(|d| r.to_string() == *d)
                .map(|k| ['x', 'y', 'z'][k]),
            _ => None,
        })
        .collect();
    (base, indices, axes)
}

/// A term of a sum printed with its sign: `(negative, magnitude)`.
pub fn split_sign(e: &Expr) -> (bool, Expr) {
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

/// One output syntax: how parentheses open and close, and how each kind of node is written.
/// Sums and negative products are the walk's own.
pub trait Style {
    fn open(&self) -> &'static str;
    fn close(&self) -> &'static str;
    fn symbol(&self, name: &str, out: &mut String);
    fn number(&self, r: &Rational, ctx: Prec, out: &mut String);
    /// A product with no leading minus sign; `factors` are its factors.
    fn product(&self, factors: &[Expr], ctx: Prec, out: &mut String);
    fn power(&self, a: &Expr, b: &Expr, ctx: Prec, out: &mut String);
    fn call(&self, n: &str, args: &[Expr], out: &mut String);
    /// Whether a sum is written as its common factor times the rest (pages only: the text
    /// form is read back by the parser and the engine).
    fn factors_sums(&self) -> bool {
        false
    }
    fn list(&self, v: &[Expr], out: &mut String);
    fn index(&self, e: &Expr, out: &mut String);
}

/// Each of `items` as a sum would be, `separator` between them (a call's arguments, a list).
pub fn write_separated(items: &[Expr], separator: &str, out: &mut String, style: &dyn Style) {
    for (i, a) in items.iter().enumerate() {
        if i > 0 {
            out.push_str(separator);
        }
        write(a, out, Prec::Sum, style);
    }
}

pub fn write(e: &Expr, out: &mut String, ctx: Prec, style: &dyn Style) {
    match e {
        Expr::Num(r) => style.number(r, ctx, out),
        Expr::Sym(s) => style.symbol(s, out),
        Expr::Add(v) => {
            if ctx == Prec::Sum
                && style.factors_sums()
                && let Some((factor, rest)) = printed_common_factor(v)
            {
                // c (a + b): the factor, then the sum left in parentheses.
                let (negative, factor) = split_sign(&factor);
                if negative {
                    out.push('-');
                }
                if !factor.is_one() {
                    write(&factor, out, Prec::Product, style);
                    // A space between the factor and the sum's parentheses: c (a + b).
                    out.push(' ');
                }
                out.push_str(style.open());
                write(&Expr::Add(rest), out, Prec::Sum, style);
                out.push_str(style.close());
                return;
            }
            if ctx > Prec::Sum {
                out.push_str(style.open());
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
                write(&mag, out, Prec::Product, style);
            }
            if ctx > Prec::Sum {
                out.push_str(style.close());
            }
        }
        Expr::Mul(v) => {
            let (negative, mag) = split_sign(e);
            if !negative {
                return style.product(v, ctx, out);
            }
            if ctx > Prec::Sum {
                out.push_str(style.open());
            }
            out.push('-');
            write(&mag, out, Prec::Product, style);
            if ctx > Prec::Sum {
                out.push_str(style.close());
            }
        }
        Expr::Pow(a, b) => style.power(a, b, ctx, out),
        // The pages write a · b and a × b between their operands: a factor of a product takes
        // parentheses, B (A · C), never B A · C.
        Expr::Call(n, args)
            if style.factors_sums()
                && ctx >= Prec::Factor
                && matches!(n.as_str(), "dot" | "cross") =>
        {
            out.push_str(style.open());
            style.call(n, args, out);
            out.push_str(style.close());
        }
        Expr::Call(n, args) => style.call(n, args, out),
        Expr::List(v) => style.list(v, out),
        Expr::Index(..) => style.index(e, out),
    }
}

/// The parser's syntax, with symbols renamed on the way out.
struct Text<'a> {
    rename: &'a dyn Fn(&str) -> String,
}

impl Style for Text<'_> {
    fn open(&self) -> &'static str {
        "("
    }
    fn close(&self) -> &'static str {
        ")"
    }
    fn symbol(&self, name: &str, out: &mut String) {
        out.push_str(&(self.rename)(name));
    }
    fn number(&self, r: &Rational, ctx: Prec, out: &mut String) {
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
    fn product(&self, v: &[Expr], ctx: Prec, out: &mut String) {
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
            write(f, out, ctx, self);
        }
        if num.is_empty() {
            out.push('1');
        }
        if !den.is_empty() {
            out.push('/');
            let d = Expr::mul(den);
            write(
                &d,
                out,
                if matches!(d, Expr::Mul(_)) {
                    Prec::Power
                } else {
                    Prec::Factor
                },
                self,
            );
        }
        if ctx > Prec::Product {
            out.push(')');
        }
    }
    fn power(&self, a: &Expr, b: &Expr, ctx: Prec, out: &mut String) {
        if ctx > Prec::Factor {
            out.push('(');
        }
        write(a, out, Prec::Power, self);
        out.push('^');
        write(b, out, Prec::Power, self);
        if ctx > Prec::Factor {
            out.push(')');
        }
    }
    fn call(&self, n: &str, args: &[Expr], out: &mut String) {
        out.push_str(n);
        out.push('(');
        write_separated(args, ", ", out, self);
        out.push(')');
    }
    fn list(&self, v: &[Expr], out: &mut String) {
        out.push('[');
        write_separated(v, ", ", out, self);
        out.push(']');
    }
    fn index(&self, e: &Expr, out: &mut String) {
        let Expr::Index(a, i) = e else {
            unreachable!("an index")
        };
        write(a, out, Prec::Power, self);
        out.push('[');
        write(i, out, Prec::Sum, self);
        out.push(']');
    }
}
