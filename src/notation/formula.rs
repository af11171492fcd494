//! A formula as the pages show it: the notation of a step's statement or reason (ω × L,
//! ½ ωᵀIω, ∑ᵢ Lᵢ²/(2Iᵢ)), as a tree that each output format prints with its own printer
//! (`formula_print.rs`), never translated from another format's text.
//!
//! An exact [`Expr`] is a leaf: a derived value inside a formula is printed by the expression
//! printers. The rest is written in a small notation, read once where the formula is made:
//!
//! - names: `I_n`, `omega_3`, `alpha_b`, `I_min` (Greek by name, one subscript after `_`);
//! - accents: `vec(L)`, `ten(I)` (a tensor), `dot(omega_2)`, `ddot(omega_1)`; a prime `r'`;
//! - `a/b` is a fraction (its operands lose one pair of parentheses); `(x)` grows around a
//!   fraction, `big(x)` always; `sqrt(x)`; `x^2`, `x^T`,
//!   `e^(sigma t)`; `|x|`; `[a, b]`; `sin`, `cos`, `tan`, `sum_i`, `int`, `nabla`, `one` (𝟙);
//! - operators `= ~= < <= > + - · × || , : ; //` (`//` divides on the line); `~` is a thin space,
//!   `~~` a medium one; `"text"`; `rm(day)` an upright name; `quad`; `perp`; `det`; `nabla_rho`;
//!   `int_(a)^(b)`; `(x)|_body` a value in a frame; `$0`, `$1`… the exact expressions handed in.

use super::latex::Tex;
use crate::cas::Expr;

#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Formula {
    /// An exact expression, printed by the expression printers.
    Expr(Expr),
    Name(Name),
    Number(String),
    /// Upright words inside a formula.
    Text(String),
    /// An upright name, such as a unit: `\mathrm{day}`.
    Upright(String),
    /// Items side by side.
    Row(Vec<Formula>),
    Op(Op),
    Frac(Box<Formula>, Box<Formula>),
    Sqrt(Box<Formula>),
    /// A base and its superscript.
    Sup(Box<Formula>, Box<Formula>),
    /// Parentheses; `true` when they grow with their content (`\\left( … \\right)`).
    Paren(Box<Formula>, bool),
    /// A closed interval's brackets, `[0, 2π]`.
    Bracket(Box<Formula>),
    Abs(Box<Formula>),
    /// The identity tensor 𝟙.
    Identity,
    /// A column (one row of entries) or a matrix (rows of entries) in parentheses: numbers
    /// computed at the scene's values.
    Matrix(Vec<Vec<Formula>>),
    /// An operator name: `sin`, `cos`, `tan`.
    Function(String),
    /// `∑`, with its index if any.
    Sum(Option<String>),
    /// `∫`, with its limits if any.
    Integral(Option<Box<(Formula, Formula)>>),
    /// `∇`, with the variable it differentiates by, if named.
    Nabla(Option<String>),
    /// A value taken in a frame: `(dL/dt)|_body`.
    At(Box<Formula>, String),
    /// Mathematics an author wrote in LaTeX between `$` signs (the author's own notation, not
    /// another printer's output), read once by the one LaTeX reader.
    Tex(Tex),
}

#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Name {
    /// A Latin letter (or letters) or a Greek letter's name.
    pub base: String,
    pub sub: Option<String>,
    pub accent: Accent,
    pub prime: bool,
}

impl Name {
    /// A bare letter (or word set letter by letter): `lambda` is λ.
    pub fn letter(base: &str) -> Name {
        Name {
            base: base.to_string(),
            sub: None,
            accent: Accent::None,
            prime: false,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Accent {
    None,
    Vector,
    Tensor,
    Dot,
    DoubleDot,
    /// The rate of a vector: a dot over its arrow.
    VectorDot,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Op {
    Equals,
    Approx,
    Less,
    LessEqual,
    Greater,
    Plus,
    Minus,
    Dot,
    Cross,
    Parallel,
    Perp,
    Comma,
    Colon,
    Semicolon,
    /// Division written on the line: `P / day`.
    Slash,
    /// A thin space between factors.
    Thin,
    /// A medium space, after a colon.
    Medium,
    /// A wide space between two statements.
    Quad,
}

/// Greek letters by name, with their characters.
pub(super) const GREEK: &[(&str, &str)] = &[
    ("alpha", "α"),
    ("beta", "β"),
    ("gamma", "γ"),
    ("delta", "δ"),
    ("Delta", "Δ"),
    ("epsilon", "ε"),
    ("theta", "θ"),
    ("lambda", "λ"),
    ("mu", "μ"),
    ("pi", "π"),
    ("rho", "ρ"),
    ("sigma", "σ"),
    ("tau", "τ"),
    ("phi", "φ"),
    ("varphi", "φ"),
    ("psi", "ψ"),
    ("omega", "ω"),
    ("Omega", "Ω"),
];

impl Formula {
    /// A formula in the notation above, with `$k` standing for `exprs[k]`. The notation is
    /// mechbook's own source, so a mistake in it is a bug: it panics, naming the formula.
    pub fn parse(src: &str, exprs: &[Expr]) -> Formula {
        let mut p = Reader {
            src: src.as_bytes(),
            pos: 0,
            exprs,
        };
        let f = p.row(&[]);
        assert!(
            p.pos == p.src.len(),
            "formula `{src}`: unexpected text at byte {}",
            p.pos
        );
        f
    }

    /// An author's mathematics, read by the one LaTeX reader. Validation has read every `$…$`
    /// of a scene already, so it reads; should it not, it is shown as the text written.
    pub fn author(latex: &str) -> Formula {
        match Tex::read(latex) {
            Ok(tex) => Formula::Tex(tex),
            Err(_) => Formula::Text(latex.to_string()),
        }
    }

    /// A computed number as written to some significant figures (`significant`): `4.6875e-6`
    /// is 4.6875 × 10⁻⁶, `1e-4` 10⁻⁴; `NaN` and `inf` as they are.
    pub fn decimal(s: &str) -> Formula {
        match crate::base::format::power_of_ten(s) {
            Some((mantissa, power)) => {
                let ten = Formula::Sup(
                    Box::new(Formula::Number("10".into())),
                    Box::new(Formula::Number(power.to_string())),
                );
                if mantissa == "1" {
                    ten
                } else {
                    Formula::Row(vec![
                        Formula::Number(mantissa.to_string()),
                        Formula::Op(Op::Cross),
                        ten,
                    ])
                }
            }
            None if s
                .trim_start_matches('-')
                .parse::<f64>()
                .is_ok_and(f64::is_finite) =>
            {
                Formula::Number(s.to_string())
            }
            None => Formula::Name(Name::letter(s)),
        }
    }

    /// `lhs = value`: a statement whose right side is an exact expression.
    pub fn equation(lhs: Formula, value: Expr) -> Formula {
        Formula::Row(vec![lhs, Formula::Op(Op::Equals), Formula::Expr(value)])
    }
}

struct Reader<'a> {
    src: &'a [u8],
    pos: usize,
    exprs: &'a [Expr],
}

impl Reader<'_> {
    fn rest(&self) -> &str {
        std::str::from_utf8(&self.src[self.pos..]).expect("formulas are UTF-8")
    }

    fn skip_ws(&mut self) {
        while self.pos < self.src.len() && self.src[self.pos] == b' ' {
            self.pos += 1;
        }
    }

    fn eat(&mut self, s: &str) -> bool {
        if self.rest().starts_with(s) {
            self.pos += s.len();
            true
        } else {
            false
        }
    }

    /// Items up to one of `stops` (not consumed) or the end, with `/` and `^` binding tightest.
    fn row(&mut self, stops: &[&str]) -> Formula {
        let mut items = Vec::new();
        loop {
            self.skip_ws();
            if self.pos >= self.src.len() || stops.iter().any(|s| self.rest().starts_with(s)) {
                break;
            }
            if let Some(op) = self.op() {
                items.push(Formula::Op(op));
                continue;
            }
            let mut item = self.postfix();
            loop {
                self.skip_ws();
                if !self.rest().starts_with("//") && self.eat("/") {
                    let den = self.postfix();
                    item = Formula::Frac(Box::new(unwrap_paren(item)), Box::new(unwrap_paren(den)));
                } else {
                    break;
                }
            }
            items.push(item);
        }
        if items.len() == 1 {
            items.pop().expect("one item")
        } else {
            Formula::Row(items)
        }
    }

    fn op(&mut self) -> Option<Op> {
        const OPS: &[(&str, Op)] = &[
            ("<=", Op::LessEqual),
            ("||", Op::Parallel),
            ("//", Op::Slash),
            ("~=", Op::Approx),
            ("~~", Op::Medium),
            ("=", Op::Equals),
            ("<", Op::Less),
            (">", Op::Greater),
            (":", Op::Colon),
            (";", Op::Semicolon),
            ("+", Op::Plus),
            ("-", Op::Minus),
            ("·", Op::Dot),
            ("×", Op::Cross),
            (",", Op::Comma),
            ("~", Op::Thin),
        ];
        for (s, op) in OPS {
            if self.eat(s) {
                return Some(*op);
            }
        }
        None
    }

    /// An atom with its superscripts and primes.
    fn postfix(&mut self) -> Formula {
        let mut f = self.atom();
        loop {
            if self.eat("|_") {
                let frame = self.take(|c| c.is_ascii_alphanumeric());
                f = Formula::At(Box::new(unwrap_paren(f)), frame);
            } else if self.eat("^") {
                let sup = self.group();
                f = Formula::Sup(Box::new(f), Box::new(sup));
            } else if let Formula::Name(n) = &mut f
                && self.src.get(self.pos) == Some(&b'\'')
            {
                self.pos += 1;
                n.prime = true;
            } else {
                return f;
            }
        }
    }

    /// `(…)` as its content, or one atom.
    fn group(&mut self) -> Formula {
        if self.eat("(") {
            self.closed_by(")", "(")
        } else {
            self.atom()
        }
    }

    /// The items up to `close`, which must follow (`open` began them).
    fn closed_by(&mut self, close: &str, open: &str) -> Formula {
        let inner = self.row(&[close]);
        assert!(self.eat(close), "formula: `{open}` is not closed");
        inner
    }

    /// The `(…)` after a function's name.
    fn argument(&mut self, name: &str) -> Formula {
        assert!(self.eat("("), "formula: `{name}` takes (…)");
        self.closed_by(")", &format!("{name}("))
    }

    /// `_i` after a name: its subscript, if any.
    fn subscript(&mut self) -> Option<String> {
        self.eat("_")
            .then(|| self.take(|c| c.is_ascii_alphanumeric()))
    }

    fn atom(&mut self) -> Formula {
        self.skip_ws();
        if self.eat("(") {
            let inner = self.closed_by(")", "(");
            let tall = contains_fraction(&inner);
            return Formula::Paren(Box::new(inner), tall);
        }
        if self.eat("[") {
            return Formula::Bracket(Box::new(self.closed_by("]", "[")));
        }
        if self.eat("|") {
            return Formula::Abs(Box::new(self.closed_by("|", "|")));
        }
        let c = self
            .rest()
            .chars()
            .next()
            .expect("formula: an item is missing at the end");
        if self.eat("\"") {
            let text = self.take(|c| c != '"');
            assert!(self.eat("\""), "formula: a text is not closed");
            return Formula::Text(text);
        }
        if c == '$' {
            self.pos += 1;
            let digits = self.take(|c| c.is_ascii_digit());
            let k: usize = digits.parse().expect("formula: `$` takes an index");
            return Formula::Expr(self.exprs[k].clone());
        }
        if c.is_ascii_digit() {
            return Formula::Number(self.take(|c| c.is_ascii_digit() || c == '.'));
        }
        assert!(c.is_ascii_alphabetic(), "formula: unexpected `{c}`");
        let word = self.take(|c| c.is_ascii_alphabetic());
        self.word(word)
    }

    /// What a word read by `atom` stands for: an accent on a name, a function, a command
    /// (`big`, `sqrt`, `rm`, `sum`, `int`, …), else a name with its subscript.
    fn word(&mut self, word: String) -> Formula {
        let accent = match word.as_str() {
            "vec" => Some(Accent::Vector),
            "ten" => Some(Accent::Tensor),
            "dot" => Some(Accent::Dot),
            "ddot" => Some(Accent::DoubleDot),
            _ => None,
        };
        if let Some(accent) = accent
            && self.eat("(")
        {
            let mut inner = self.postfix();
            assert!(self.eat(")"), "formula: `{word}(` is not closed");
            // The accent sits on the name, under its superscript.
            if let Formula::Name(n) = &mut inner {
                n.accent = match (accent, n.accent) {
                    (Accent::Dot, Accent::Vector) => Accent::VectorDot,
                    _ => accent,
                };
            } else {
                panic!("formula: `{word}` takes a name");
            }
            return inner;
        }
        match word.as_str() {
            "big" => return Formula::Paren(Box::new(self.argument(&word)), true),
            "sqrt" => return Formula::Sqrt(Box::new(self.argument(&word))),
            "sin" | "cos" | "tan" | "det" => return Formula::Function(word),
            "rm" => {
                assert!(self.eat("("), "formula: `rm` takes (…)");
                let name = self.take(|c| c != ')');
                assert!(self.eat(")"), "formula: `rm(` is not closed");
                return Formula::Upright(name);
            }
            "sum" => return Formula::Sum(self.subscript()),
            "int" => {
                let limits = self.eat("_").then(|| {
                    let lo = self.group();
                    assert!(self.eat("^"), "formula: `int_` takes both limits");
                    Box::new((lo, self.group()))
                });
                return Formula::Integral(limits);
            }
            "nabla" => return Formula::Nabla(self.subscript()),
            "one" => return Formula::Identity,
            "quad" => return Formula::Op(Op::Quad),
            "perp" => return Formula::Op(Op::Perp),
            _ => {}
        }
        let sub = self.subscript();
        Formula::Name(Name {
            base: word,
            sub,
            accent: Accent::None,
            prime: false,
        })
    }

    fn take(&mut self, keep: impl Fn(char) -> bool) -> String {
        let rest = self.rest();
        let n = rest.find(|c| !keep(c)).unwrap_or(rest.len());
        let taken = rest[..n].to_string();
        self.pos += n;
        taken
    }
}

/// Parentheses grow around a fraction.
fn contains_fraction(f: &Formula) -> bool {
    match f {
        Formula::Frac(..) => true,
        Formula::Row(items) => items.iter().any(|i| matches!(i, Formula::Frac(..))),
        _ => false,
    }
}

/// A fraction's operand needs no parentheses of its own.
fn unwrap_paren(f: Formula) -> Formula {
    match f {
        Formula::Paren(inner, _) => *inner,
        other => other,
    }
}
