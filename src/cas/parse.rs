//! The expression parser: scene text and our own printed text back into an [`Expr`], within
//! limits on length and nesting.

use super::expr::Expr;
use super::rational::Rational;

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

/// The largest constant power a scene writes (`x^1000`): every exact power of a scene's numbers
/// then has at most a thousand times their digits.
pub const MAX_POWER: f64 = 1000.0;

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
    parse_with(text, MAX_NESTING, super::rational::MAX_DIGITS, MAX_POWER)
}

/// Parses text that mechbook made itself: no length limit, and a generous nesting limit.
pub fn parse(text: &str) -> Result<Parsed, ParseError> {
    parse_with(
        text,
        MAX_INTERNAL_NESTING,
        super::rational::MAX_ENGINE_DIGITS,
        f64::INFINITY,
    )
}

fn parse_with(
    text: &str,
    max_depth: usize,
    max_digits: usize,
    max_power: f64,
) -> Result<Parsed, ParseError> {
    let mut p = Parser {
        src: text.as_bytes(),
        pos: 0,
        depth: 0,
        max_depth,
        max_digits,
        max_power,
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
        // Python's power: `l**2`.
        _ if first == b'*' => "unexpected `*`: write a power with `^` (l^2), not `**`".into(),
        _ => format!("unexpected `{}`", first as char),
    }
}

/// What to write instead when the text at `pos` looks like LaTeX (`\frac`, `x^{2}`) or like a
/// product written without `*` (`2R`, `2 l`, `(a+b)(a-b)`); empty otherwise.
fn hint(src: &[u8], pos: usize) -> String {
    let Some(&c) = src.get(pos) else {
        return String::new();
    };
    if matches!(c, b'\\' | b'{' | b'}') {
        return "; LaTeX is not accepted: write plain text such as sin(x), a/b, sqrt(x), x^2, pi"
            .into();
    }
    let word = |b: u8| b.is_ascii_alphanumeric() || b == b'_' || b == b'.';
    let mut end = pos;
    while end > 0 && src[end - 1].is_ascii_whitespace() {
        end -= 1;
    }
    let Some(&last) = end.checked_sub(1).and_then(|i| src.get(i)) else {
        return String::new();
    };
    if !(word(last) || last == b')' || last == b']') || !(c.is_ascii_alphanumeric() || c == b'(') {
        return String::new();
    }
    let mut start = end;
    while start > 0 && word(src[start - 1]) {
        start -= 1;
    }
    let before = if word(last) {
        String::from_utf8_lossy(&src[start..end]).into_owned()
    } else {
        "…)".into()
    };
    let mut after_end = pos;
    while after_end < src.len() && word(src[after_end]) {
        after_end += 1;
    }
    let after = if c == b'(' {
        "(…".into()
    } else {
        String::from_utf8_lossy(&src[pos..after_end]).into_owned()
    };
    format!("; a product needs `*`: write `{before}*{after}`")
}

/// A long text cut to its start, for a message.
fn short(text: &str) -> String {
    match text.char_indices().nth(40) {
        Some((at, _)) => format!("{}… ({} characters)", &text[..at], text.len()),
        None => text.to_string(),
    }
}

struct Parser<'a> {
    src: &'a [u8],
    pos: usize,
    /// How deep the recursion is: every nesting passes through `unary`.
    depth: usize,
    max_depth: usize,
    /// A scene's numbers are short; the engine's products of them may be long.
    max_digits: usize,
    /// The largest constant power a scene may write ([`MAX_POWER`]).
    max_power: f64,
    symbols: Vec<(String, usize)>,
}

impl Parser<'_> {
    fn error(&self, message: &str) -> ParseError {
        ParseError {
            offset: self.pos,
            message: format!("{message}{}", hint(self.src, self.pos)),
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
            let at = self.pos;
            let exponent = self.unary()?;
            // An exact power is taken of every number a scene substitutes: (3/10)^(10^12)
            // would not fit in memory.
            if let Ok(k) = exponent.eval(&|_| None)
                && (k.is_nan() || k.abs() > self.max_power)
            {
                return Err(ParseError {
                    offset: at,
                    message: format!(
                        "a power of {} is too large: a constant power is at most {MAX_POWER} \
                         (in size)",
                        short(&exponent.to_text())
                    ),
                });
            }
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
            Some(c) if c.is_ascii_digit() || c == b'.' => self.number(),
            Some(c) if c.is_ascii_alphabetic() => self.name_or_call(),
            Some(c) => {
                self.pos = start.max(self.pos);
                Err(self.error(&unexpected(&self.src[self.pos..], c)))
            }
        }
    }

    /// A decimal number, with an exponent (`e-3`) only when a digit follows the `e`.
    fn number(&mut self) -> Result<Expr, ParseError> {
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
        Rational::parse_decimal_within(text, self.max_digits)
            .map(Expr::Num)
            .ok_or(ParseError {
                offset: s,
                message: format!(
                    "malformed number `{}` (at most {} digits, exponents within ±{})",
                    short(text),
                    self.max_digits,
                    super::rational::MAX_EXPONENT
                ),
            })
    }

    /// A name, with a coordinate's rate primes, or a function's call.
    fn name_or_call(&mut self) -> Result<Expr, ParseError> {
        let s = self.pos;
        while self.pos < self.src.len()
            && (self.src[self.pos].is_ascii_alphanumeric() || self.src[self.pos] == b'_')
        {
            self.pos += 1;
        }
        // A coordinate's rates: `phi'` and `phi''` (d/dt and d²/dt²).
        let mut primes = 0;
        while primes < 2 && self.src.get(self.pos) == Some(&b'\'') {
            self.pos += 1;
            primes += 1;
        }
        let name = String::from_utf8_lossy(&self.src[s..self.pos]).into_owned();
        if primes == 0 && self.peek() == Some(b'(') {
            return self.call(name);
        }
        self.symbols.push((name.clone(), s));
        Ok(Expr::Sym(name))
    }

    /// A call of `name`: its arguments in parentheses, read on from the opening one.
    fn call(&mut self, name: String) -> Result<Expr, ParseError> {
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
        // tan x is read as sin x / cos x, tanh x as sinh x / cosh x, ln as log, so
        // that every later stage knows them.
        if let ("tan" | "tanh", 1) = (name.as_str(), args.len()) {
            let x = args.remove(0);
            let h = if name == "tanh" { "h" } else { "" };
            return Ok(Expr::over(
                Expr::call(&format!("sin{h}"), x.clone()),
                Expr::call(&format!("cos{h}"), x),
            ));
        }
        let name = if name == "ln" {
            "log".to_string()
        } else {
            name
        };
        Ok(Expr::Call(name, args))
    }
}
