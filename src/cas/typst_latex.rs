//! An author's own LaTeX (the `$…$` of a title, a meaning or a statement, and a symbol's
//! `tex`), read into Typst's math notation for the PDFs. This is the one place LaTeX text is
//! read: mechbook's own formulas reach Typst through the tree printers (`print_typst.rs`,
//! `formula_typst.rs`). It knows the commands an author of mechanics writes; any other is
//! refused, so scene validation names it at its line.

/// Why an author's LaTeX has no Typst form.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TexError {
    #[error("`\\{0}` is not among the commands the PDFs can set (see docs/scenes.md)")]
    Command(String),
    #[error("`\\begin{{{0}}}` is not among the environments the PDFs can set")]
    Environment(String),
    #[error("a `{0}` without its partner")]
    Unbalanced(char),
    #[error("groups nested more than {MAX_DEPTH} deep")]
    TooDeep,
}

/// The deepest nesting of groups read: a guard for the stack, far beyond what an author writes.
const MAX_DEPTH: usize = 64;

/// Commands that are one character in Typst's math.
const SYMBOLS: &[(&str, &str)] = &[
    ("alpha", "α"),
    ("beta", "β"),
    ("gamma", "γ"),
    ("delta", "δ"),
    ("epsilon", "ϵ"),
    ("varepsilon", "ε"),
    ("zeta", "ζ"),
    ("eta", "η"),
    ("theta", "θ"),
    ("vartheta", "ϑ"),
    ("iota", "ι"),
    ("kappa", "κ"),
    ("lambda", "λ"),
    ("mu", "μ"),
    ("nu", "ν"),
    ("xi", "ξ"),
    ("pi", "π"),
    ("varpi", "ϖ"),
    ("rho", "ρ"),
    ("varrho", "ϱ"),
    ("sigma", "σ"),
    ("varsigma", "ς"),
    ("tau", "τ"),
    ("upsilon", "υ"),
    ("phi", "ϕ"),
    ("varphi", "φ"),
    ("chi", "χ"),
    ("psi", "ψ"),
    ("omega", "ω"),
    ("Gamma", "Γ"),
    ("Delta", "Δ"),
    ("Theta", "Θ"),
    ("Lambda", "Λ"),
    ("Xi", "Ξ"),
    ("Pi", "Π"),
    ("Sigma", "Σ"),
    ("Upsilon", "Υ"),
    ("Phi", "Φ"),
    ("Psi", "Ψ"),
    ("Omega", "Ω"),
    ("cdot", "⋅"),
    ("times", "×"),
    ("pm", "±"),
    ("mp", "∓"),
    ("le", "≤"),
    ("leq", "≤"),
    ("ge", "≥"),
    ("geq", "≥"),
    ("ne", "≠"),
    ("neq", "≠"),
    ("approx", "≈"),
    ("sim", "∼"),
    ("simeq", "≃"),
    ("equiv", "≡"),
    ("propto", "∝"),
    ("infty", "∞"),
    ("partial", "∂"),
    ("nabla", "∇"),
    ("sum", "∑"),
    ("prod", "∏"),
    ("int", "∫"),
    ("oint", "∮"),
    ("to", "→"),
    ("rightarrow", "→"),
    ("leftarrow", "←"),
    ("Rightarrow", "⇒"),
    ("Leftrightarrow", "⇔"),
    ("mapsto", "↦"),
    ("perp", "⊥"),
    ("parallel", "∥"),
    ("ldots", "…"),
    ("dots", "…"),
    ("cdots", "⋯"),
    ("circ", "∘"),
    ("hbar", "ℏ"),
    ("ell", "ℓ"),
    ("prime", "′"),
    ("in", "∈"),
    ("langle", "⟨"),
    ("rangle", "⟩"),
    ("cross", "×"),
    ("degree", "°"),
];

/// A Greek letter by its LaTeX name (`phi` is ϕ, `varphi` φ, as LaTeX sets them), for the
/// Typst printers: the character itself, whatever Typst names it.
pub(super) fn greek(name: &str) -> Option<&'static str> {
    SYMBOLS
        .iter()
        .find(|(n, c)| *n == name && c.chars().all(char::is_alphabetic))
        .map(|(_, c)| *c)
}

/// Operator names Typst's math knows by the same name.
const FUNCTIONS: &[&str] = &[
    "sin", "cos", "tan", "cot", "sec", "csc", "arcsin", "arccos", "arctan", "sinh", "cosh", "tanh",
    "exp", "ln", "log", "det", "max", "min", "lim", "sup", "inf",
];

/// Accents: LaTeX's command, Typst's function.
const ACCENTS: &[(&str, &str)] = &[
    ("vec", "arrow"),
    ("dot", "dot"),
    ("ddot", "dot.double"),
    ("hat", "hat"),
    ("bar", "overline"),
    ("overline", "overline"),
    ("tilde", "tilde"),
    ("widehat", "hat"),
    ("mathbf", "bold"),
    ("boldsymbol", "bold"),
    ("mathbb", "bb"),
    ("mathcal", "cal"),
    ("mathit", "italic"),
    ("sqrt", "sqrt"),
];

/// LaTeX math (as between `$` signs) in Typst's math notation.
pub fn latex_to_typst(latex: &str) -> Result<String, TexError> {
    let mut tokens = tokens(latex);
    escape_unbalanced_parentheses(&mut tokens);
    let mut reader = Reader {
        tokens,
        at: 0,
        depth: 0,
        upright: false,
    };
    let out = reader.until(None)?;
    Ok(out.trim().to_string())
}

/// Marks as `\(` and `\)` the parentheses of every brace group (and of the whole) in which
/// they do not pair up: the group may become an argument of a call that the printer writes,
/// `sqrt(…)`, whose `)` an author's lone `)` would otherwise close (`\sqrt{)}`).
fn escape_unbalanced_parentheses(tokens: &mut [String]) {
    // Per open group: the indices of its parentheses, its depth, and whether it went below 0.
    let mut groups: Vec<(Vec<usize>, i64, bool)> = vec![(Vec::new(), 0, false)];
    let mut unbalanced: Vec<usize> = Vec::new();
    let close = |g: (Vec<usize>, i64, bool), unbalanced: &mut Vec<usize>| {
        if g.2 || g.1 != 0 {
            unbalanced.extend(g.0);
        }
    };
    for (i, t) in tokens.iter().enumerate() {
        match t.as_str() {
            "{" => groups.push((Vec::new(), 0, false)),
            "}" if groups.len() > 1 => {
                let g = groups.pop().expect("an open group");
                close(g, &mut unbalanced);
            }
            "(" | ")" => {
                let g = groups.last_mut().expect("the whole is a group");
                g.0.push(i);
                g.1 += if t == "(" { 1 } else { -1 };
                g.2 |= g.1 < 0;
            }
            _ => {}
        }
    }
    while let Some(g) = groups.pop() {
        close(g, &mut unbalanced);
    }
    for i in unbalanced {
        tokens[i] = format!("\\{}", tokens[i]);
    }
}

fn tokens(latex: &str) -> Vec<String> {
    let chars: Vec<char> = latex.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c == '\\' && i + 1 < chars.len() {
            let mut j = i + 1;
            if chars[j].is_ascii_alphabetic() {
                while j < chars.len() && chars[j].is_ascii_alphabetic() {
                    j += 1;
                }
            } else {
                j += 1;
            }
            out.push(chars[i..j].iter().collect());
            i = j;
        } else if c.is_ascii_digit() {
            // A number is one item: 2.5 stays one atom.
            let mut j = i;
            while j < chars.len() && (chars[j].is_ascii_digit() || chars[j] == '.') {
                j += 1;
            }
            out.push(chars[i..j].iter().collect());
            i = j;
        } else {
            out.push(c.to_string());
            i += 1;
        }
    }
    out
}

struct Reader {
    tokens: Vec<String>,
    at: usize,
    depth: usize,
    /// Inside `\mathrm{…}`: a run of letters is one upright word (`"kg"`), not a product of
    /// italic letters.
    upright: bool,
}

/// A Typst string literal: quotes and backslashes escaped.
pub fn typst_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' | '\\' => {
                out.push('\\');
                out.push(c);
            }
            '\n' | '\r' | '\t' => out.push(' '),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

impl Reader {
    fn next(&mut self) -> Option<String> {
        let t = self.tokens.get(self.at).cloned();
        self.at += 1;
        t
    }

    fn peek(&self) -> Option<&str> {
        self.tokens.get(self.at).map(String::as_str)
    }

    fn skip_spaces(&mut self) {
        while self.peek().is_some_and(|t| t.trim().is_empty()) {
            self.at += 1;
        }
    }

    /// Everything up to the token `end` (consumed), or to the end.
    fn until(&mut self, end: Option<&str>) -> Result<String, TexError> {
        let mut out = String::new();
        loop {
            match self.peek() {
                None if end.is_none() => return Ok(out),
                None => return Err(TexError::Unbalanced('{')),
                Some(t) if Some(t) == end => {
                    self.at += 1;
                    return Ok(out);
                }
                Some("}") => return Err(TexError::Unbalanced('}')),
                _ => {}
            }
            let piece = self.item()?;
            push(&mut out, &piece);
        }
    }

    /// One argument: a brace group or a single token.
    fn argument(&mut self) -> Result<String, TexError> {
        self.skip_spaces();
        match self.peek() {
            Some("{") => {
                self.at += 1;
                self.until(Some("}"))
            }
            Some(_) => self.item(),
            None => Ok(String::new()),
        }
    }

    /// An argument's raw text, for `\text{…}`: an escaped character (`\%`) as itself.
    fn raw_argument(&mut self) -> Result<String, TexError> {
        Ok(self
            .argument_tokens()?
            .iter()
            .map(|t| t.strip_prefix('\\').filter(|s| s.len() == 1).unwrap_or(t))
            .collect())
    }

    /// An argument's tokens as they are, its inner braces kept.
    fn argument_tokens(&mut self) -> Result<Vec<String>, TexError> {
        self.skip_spaces();
        if self.peek() != Some("{") {
            return Ok(self.next().into_iter().collect());
        }
        self.at += 1;
        let mut depth = 1;
        let mut out = Vec::new();
        while let Some(t) = self.next() {
            match t.as_str() {
                "{" => depth += 1,
                "}" => {
                    depth -= 1;
                    if depth == 0 {
                        return Ok(out);
                    }
                }
                _ => {}
            }
            out.push(t);
        }
        Err(TexError::Unbalanced('{'))
    }

    /// One item, its arguments with it; every nested group or argument passes through here.
    fn item(&mut self) -> Result<String, TexError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(TexError::TooDeep);
        }
        let out = self.one_item();
        self.depth -= 1;
        out
    }

    fn one_item(&mut self) -> Result<String, TexError> {
        let Some(t) = self.next() else {
            return Ok(String::new());
        };
        Ok(match t.as_str() {
            // A brace group only groups: its content, with no brackets.
            "{" => self.until(Some("}"))?,
            "^" | "_" => format!("{t}({})", self.argument()?),
            // What Typst's math reads as syntax (a fraction, an argument's end, code) is
            // escaped to stand for itself.
            "/" | "," | ";" | "#" | "$" | "\"" | "&" => format!("\\{t}"),
            "~" => " space ".into(),
            s if s.starts_with('\\') => self.command(&s[1..])?,
            s if self.upright && s.chars().all(char::is_alphabetic) => {
                let mut word = s.to_string();
                while let Some(next) = self.peek().filter(|n| n.chars().all(char::is_alphabetic)) {
                    word.push_str(next);
                    self.at += 1;
                }
                typst_string(&word)
            }
            s if s.chars().all(|c| c.is_ascii_alphabetic()) => format!(" {s} "),
            s => s.to_string(),
        })
    }

    fn command(&mut self, name: &str) -> Result<String, TexError> {
        if let Some((_, c)) = SYMBOLS.iter().find(|(n, _)| *n == name) {
            return Ok(format!(" {c} "));
        }
        if FUNCTIONS.contains(&name) {
            return Ok(format!(" {name} "));
        }
        if let Some((_, f)) = ACCENTS.iter().find(|(n, _)| *n == name) {
            return Ok(format!("{f}({})", self.argument()?));
        }
        Ok(match name {
            "frac" | "dfrac" | "tfrac" => {
                let a = self.argument()?;
                let b = self.argument()?;
                format!("frac({a}, {b})")
            }
            "overleftrightarrow" => format!("accent({}, arrow.l.r)", self.argument()?),
            "text" | "textrm" | "mbox" | "textit" => typst_string(&self.raw_argument()?),
            "mathrm" | "operatorname" | "rm" => {
                let inner = self.argument_tokens()?;
                if inner
                    .iter()
                    .all(|t| t.chars().all(|c| c.is_alphabetic() || c == ' '))
                {
                    format!("upright({})", typst_string(&inner.concat()))
                } else {
                    // `\mathrm{kg\,m^2}`: its spaces, powers and symbols read as LaTeX.
                    let mut inner = Reader {
                        tokens: inner,
                        at: 0,
                        depth: self.depth,
                        upright: true,
                    };
                    format!("upright({})", inner.until(None)?)
                }
            }
            "left" | "right" | "big" | "Big" | "bigl" | "bigr" | "Bigl" | "Bigr" => {
                self.skip_spaces();
                match self.next().as_deref() {
                    Some(".") | None => String::new(),
                    Some("\\{") => "\\{".into(),
                    Some("\\}") => "\\}".into(),
                    Some("\\|") => "‖".into(),
                    Some("\\langle") => "⟨".into(),
                    Some("\\rangle") => "⟩".into(),
                    Some(d) => d.to_string(),
                }
            }
            "begin" => self.environment()?,
            "," | ":" | ";" | ">" => " thin ".into(),
            "!" => String::new(),
            " " => " space ".into(),
            "quad" => " quad ".into(),
            "qquad" => " wide ".into(),
            "\\" => " \\ ".into(),
            "{" | "}" | "$" | "#" | "&" | "_" | "%" | "(" | ")" => format!("\\{name}"),
            "|" => "‖".into(),
            other => return Err(TexError::Command(other.to_string())),
        })
    }

    /// `\begin{pmatrix} a & b \\ c & d \end{pmatrix}` as `mat(a, b; c, d)`.
    fn environment(&mut self) -> Result<String, TexError> {
        let name = self.raw_argument()?;
        let delim = match name.as_str() {
            "pmatrix" => "",
            "bmatrix" => "delim: \"[\", ",
            "vmatrix" => "delim: \"|\", ",
            "matrix" => "delim: #none, ",
            "cases" => "",
            _ => return Err(TexError::Environment(name)),
        };
        let mut rows: Vec<Vec<String>> = vec![vec![String::new()]];
        loop {
            self.skip_spaces();
            match self.peek() {
                None => return Err(TexError::Unbalanced('{')),
                Some("\\end") => {
                    self.at += 1;
                    self.raw_argument()?;
                    break;
                }
                Some("&") => {
                    self.at += 1;
                    rows.last_mut().expect("a row").push(String::new());
                }
                Some("\\\\") => {
                    self.at += 1;
                    rows.push(vec![String::new()]);
                }
                Some(_) => {
                    let piece = self.item()?;
                    let cell = rows.last_mut().and_then(|r| r.last_mut()).expect("a cell");
                    push(cell, &piece);
                }
            }
        }
        if rows
            .last()
            .is_some_and(|r| r.len() == 1 && r[0].trim().is_empty())
        {
            rows.pop();
        }
        let body = rows
            .iter()
            .map(|r| {
                r.iter()
                    .map(|c| c.trim().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            })
            .collect::<Vec<_>>()
            .join("; ");
        Ok(if name == "cases" {
            format!("cases({})", body.replace("; ", ", "))
        } else {
            format!("mat({delim}{body})")
        })
    }
}

/// Appends a piece, with a space where two names would run into one.
fn push(out: &mut String, piece: &str) {
    // A power or index with nothing before it (`m/s$^2$`) gets an empty base: Typst refuses a
    // bare `^`.
    if out.trim().is_empty() && (piece.starts_with('^') || piece.starts_with('_')) {
        out.push_str("\"\"");
    }
    let ends_word = out.ends_with(|c: char| c.is_alphanumeric() || c == ')' || c == '"');
    let starts_word = piece.starts_with(|c: char| c.is_alphanumeric() || c == '"');
    if ends_word && starts_word {
        out.push(' ');
    }
    out.push_str(piece);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(latex: &str) -> String {
        let s = latex_to_typst(latex).unwrap();
        s.split_whitespace().collect::<Vec<_>>().join(" ")
    }

    #[test]
    fn letters_greek_and_accents() {
        assert_eq!(t("ab"), "a b");
        assert_eq!(t("\\omega_{x}"), "ω _( x )");
        assert_eq!(t("\\vec{\\omega}"), "arrow( ω )");
        assert_eq!(t("\\Omega"), "Ω");
        assert_eq!(t("I_p"), "I _( p )");
    }

    #[test]
    fn fractions_units_text_and_matrices() {
        assert_eq!(t("\\frac{1}{2} m"), "frac(1, 2) m");
        assert_eq!(
            t("g = 9.81\\,\\mathrm{m/s^2}"),
            "g = 9.81 thin upright(\"m\"\\/\"s\"^(2))"
        );
        assert_eq!(t("\\text{every axis}"), "\"every axis\"");
        assert_eq!(
            t("\\begin{pmatrix}a & b \\\\ c & d\\end{pmatrix}"),
            "mat(a, b; c, d)"
        );
        assert_eq!(t("\\left(x\\right)^{2}"), "( x )^(2)");
        assert_eq!(t("f(x, y)"), "f ( x \\, y )");
    }

    #[test]
    fn what_an_author_writes_cannot_close_a_call_or_lose_a_base() {
        // A lone `)` inside an argument is escaped; paired ones stay delimiters.
        assert_eq!(t("\\sqrt{)}"), "sqrt(\\))");
        assert_eq!(t("\\sqrt{(a)}"), "sqrt(( a ))");
        assert_eq!(t("\\frac{(}{)}"), "frac(\\(, \\))");
        assert_eq!(t("[0, 1)"), "[0\\, 1\\)");
        // A power with no base gets an empty one.
        assert_eq!(t("^2"), "\"\"^(2)");
        // Units upright, their thin spaces and powers read.
        assert_eq!(t("\\mathrm{kg\\,m^2}"), "upright(\"kg\" thin \"m\"^(2))");
    }

    #[test]
    fn an_unknown_command_or_an_open_group_is_refused() {
        assert_eq!(
            latex_to_typst("\\foo x"),
            Err(TexError::Command("foo".into()))
        );
        assert_eq!(
            latex_to_typst("\\frac{1}{2"),
            Err(TexError::Unbalanced('{'))
        );
        assert!(latex_to_typst("\\begin{align}x\\end{align}").is_err());
        let deep = format!("{}x{}", "{".repeat(10_000), "}".repeat(10_000));
        assert_eq!(latex_to_typst(&deep), Err(TexError::TooDeep));
        let deep = format!("{}x{}", "\\frac{".repeat(5_000), "}{1}".repeat(5_000));
        assert_eq!(latex_to_typst(&deep), Err(TexError::TooDeep));
        assert_eq!(
            latex_to_typst(&"\\vec".repeat(10_000)),
            Err(TexError::TooDeep)
        );
    }
}
