//! An expression in LaTeX: the printing walk (`cas/print.rs`: signs, parentheses, a
//! product's fraction bar, a sum's common factor) in the pages' LaTeX style, each name as the
//! scene typesets it ([`Names`]). What Moodle's quizzes, `--json` and a formula's source show,
//! and what the presentation pass measures a form by ([`printed_length`]). The pages set the
//! same walk as a tree (`expr_tree.rs`), which a test holds equal to this LaTeX read.

use super::Names;
use crate::cas::{
    Expr, GREEK, Head, NameForm, Prec, Rational, SCALAR_FUNCTIONS, Style, index_chain, name_form,
    numbered, page_factors, page_fraction, textbook_name, write, write_separated,
};

/// A name's own LaTeX, where the scene gives it one (`Names::latex`).
type OwnLatex<'a> = &'a dyn Fn(&str) -> Option<String>;

impl Expr {
    pub fn to_latex(&self, names: &Names) -> String {
        self.to_latex_named(names, &|_| None)
    }

    /// LaTeX with some symbols given a catalogue symbol: a claim's `inertia_tensor[0][1]`
    /// prints as I_{xy} when `named("inertia_tensor")` is `I`.
    pub fn to_latex_named(
        &self,
        names: &Names,
        named: &dyn Fn(&str) -> Option<&'static str>,
    ) -> String {
        latex(self, &|s| names.latex(s).map(str::to_string), named)
    }
}

/// How long a form prints, for the presentation pass (`cas::PrintedLength`): the characters
/// of its LaTeX by the conventions (the pass runs before any page, whatever the scene's own
/// names), without spaces and `\left`/`\right`.
pub fn printed_length(e: &Expr) -> usize {
    let latex = latex(e, &|_| None, &|_| None);
    let latex = latex.replace("\\left", "").replace("\\right", "");
    latex.chars().filter(|c| !c.is_whitespace()).count()
}

/// LaTeX with each name as `own` gives it, else by the conventions, and some symbols given a
/// catalogue symbol (`named`).
fn latex(e: &Expr, own: OwnLatex<'_>, named: &dyn Fn(&str) -> Option<&'static str>) -> String {
    let mut s = String::new();
    write(e, &mut s, Prec::Sum, &Latex { own, named });
    s
}

/// Puts braces around the base written at `out[start..]` when it already ends with a script of
/// `kind` (`_` or `^`), which LaTeX refuses to add twice: `r_{1}` indexed is `{r_{1}}_{2}`.
fn brace_if_scripted(out: &mut String, start: usize, kind: char) {
    if trailing_scripts(&out[start..]).contains(&kind) {
        out.insert(start, '{');
        out.push('}');
    }
}

/// The kinds of the scripts (`_{…}`, `^{…}`) at the end of a piece of LaTeX, last first.
fn trailing_scripts(latex: &str) -> Vec<char> {
    let mut kinds = Vec::new();
    let mut rest = latex;
    loop {
        // A script of one character, as an author may write it: `m_1`.
        let mut chars = rest.chars().rev();
        if let (Some(last), Some(k @ ('_' | '^'))) = (chars.next(), chars.next())
            && last.is_ascii_alphanumeric()
        {
            kinds.push(k);
            rest = &rest[..rest.len() - 2];
            continue;
        }
        if !rest.ends_with('}') {
            break;
        }
        // The brace that opens the last group.
        let mut depth = 0;
        let mut open = None;
        for (i, c) in rest.char_indices().rev() {
            match c {
                '}' => depth += 1,
                '{' => {
                    depth -= 1;
                    if depth == 0 {
                        open = Some(i);
                        break;
                    }
                }
                _ => {}
            }
        }
        let Some(open) = open else { break };
        let before = &rest[..open];
        match before.chars().last() {
            Some(k @ ('_' | '^')) if !before[..before.len() - 1].ends_with('\\') => {
                kinds.push(k);
                rest = &before[..before.len() - 1];
            }
            _ => break,
        }
    }
    kinds
}

/// LaTeX for the pages (converted to MathML at build time).
struct Latex<'a> {
    own: OwnLatex<'a>,
    named: &'a dyn Fn(&str) -> Option<&'static str>,
}

impl Latex<'_> {
    /// The claim language's vector and matrix functions in their usual notation: a · b, a × b,
    /// f gᵀ, Aᵀ, 𝟙, R_z(ψ), ∂f/∂x, f|ₓ₌ᵥ. Returns false for any other call.
    fn claim_call(&self, n: &str, args: &[Expr], out: &mut String) -> bool {
        let put = |e: &Expr, ctx: Prec, out: &mut String| write(e, out, ctx, self);
        match (n, args) {
            ("dot" | "cross", [a, b]) => {
                put(a, Prec::Factor, out);
                out.push_str(if n == "dot" { " \\cdot " } else { " \\times " });
                put(b, Prec::Factor, out);
            }
            ("outer", [a, b]) => {
                put(a, Prec::Power, out);
                out.push_str("\\, ");
                let start = out.len();
                put(b, Prec::Power, out);
                brace_if_scripted(out, start, '^');
                out.push_str("^{T}");
            }
            ("transpose", [a]) => {
                let start = out.len();
                put(a, Prec::Power, out);
                brace_if_scripted(out, start, '^');
                out.push_str("^{T}");
            }
            ("eye", []) => out.push_str("\\mathbb{1}"),
            ("rot_x" | "rot_y" | "rot_z", [angle]) => {
                out.push_str(&format!("R_{{{}}}\\left(", &n[4..]));
                put(angle, Prec::Sum, out);
                out.push_str("\\right)");
            }
            ("diff", [f, x]) => {
                out.push_str("\\frac{\\partial}{\\partial ");
                put(x, Prec::Power, out);
                out.push('}');
                put(f, Prec::Power, out);
            }
            ("subs", [f, x, v]) => {
                out.push_str("\\left.");
                put(f, Prec::Sum, out);
                out.push_str("\\right|_{");
                put(x, Prec::Sum, out);
                out.push_str(" = ");
                put(v, Prec::Sum, out);
                out.push('}');
            }
            _ => return false,
        }
        true
    }
}

impl Style for Latex<'_> {
    fn factors_sums(&self) -> bool {
        true
    }
    fn open(&self) -> &'static str {
        "\\left("
    }
    fn close(&self) -> &'static str {
        "\\right)"
    }
    fn symbol(&self, name: &str, out: &mut String) {
        match (self.named)(name) {
            Some(symbol) => out.push_str(symbol),
            None => out.push_str(&latex_symbol(name, self.own)),
        }
    }
    fn number(&self, r: &Rational, ctx: Prec, out: &mut String) {
        let body = if r.is_integer() {
            r.to_string()
        } else {
            let (num, den) = r.abs_parts();
            format!("\\frac{{{num}}}{{{den}}}")
        };
        let negative = r.is_negative();
        // A fraction under a power is bracketed: (8661249/1159339)^{3/2}.
        let bracket = negative && ctx > Prec::Sum || !r.is_integer() && ctx == Prec::Power;
        if bracket {
            out.push_str("\\left(");
        }
        if negative && !r.is_integer() {
            out.push('-');
        }
        out.push_str(&body);
        if bracket {
            out.push_str("\\right)");
        }
    }
    fn product(&self, v: &[Expr], ctx: Prec, out: &mut String) {
        let (num, den) = page_fraction(v);
        if ctx > Prec::Product {
            out.push_str("\\left(");
        }
        let write_factors = |fs: &[Expr], out: &mut String| page_factors(fs, " \\cdot ", out, self);
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
    fn power(&self, a: &Expr, b: &Expr, _ctx: Prec, out: &mut String) {
        if let Expr::Num(r) = b {
            if *r == Rational::new(1, 2).unwrap() {
                out.push_str("\\sqrt{");
                write(a, out, Prec::Sum, self);
                out.push('}');
                return;
            }
            if r.is_negative() {
                out.push_str("\\frac{1}{");
                write(
                    &Expr::pow(a.clone(), Expr::Num(r.negated())),
                    out,
                    Prec::Sum,
                    self,
                );
                out.push('}');
                return;
            }
        }
        // sin(x)^2 prints as {\sin}^{2}(x): the braces keep the converter's MathML valid.
        if let Expr::Call(n, args) = a
            && (n == "sin" || n == "cos")
        {
            out.push_str(&format!("\\,{{\\{n}}}^{{"));
            write(b, out, Prec::Sum, self);
            out.push_str("}\\left(");
            write(&args[0], out, Prec::Sum, self);
            out.push_str("\\right)");
            return;
        }
        let start = out.len();
        write(a, out, Prec::Power, self);
        brace_if_scripted(out, start, '^');
        out.push_str("^{");
        write(b, out, Prec::Sum, self);
        out.push('}');
    }
    fn call(&self, n: &str, args: &[Expr], out: &mut String) {
        if n == "sqrt" && args.len() == 1 {
            out.push_str("\\sqrt{");
            write(&args[0], out, Prec::Sum, self);
            out.push('}');
            return;
        }
        if self.claim_call(n, args, out) {
            return;
        }
        if n == "abs" && args.len() == 1 {
            out.push_str("\\left|");
            write(&args[0], out, Prec::Sum, self);
            out.push_str("\\right|");
            return;
        }
        if n != "atan2" && SCALAR_FUNCTIONS.contains(&n) {
            // \sin, \arcsin, \ln, \sinh: LaTeX's own operator names.
            out.push_str(&format!("\\{}\\left(", textbook_name(n)));
        } else {
            out.push_str(&format!("\\operatorname{{{n}}}\\left("));
        }
        write_separated(args, ", ", out, self);
        out.push_str("\\right)");
    }
    fn list(&self, v: &[Expr], out: &mut String) {
        let is_matrix = v.iter().all(|r| matches!(r, Expr::List(_)));
        out.push_str("\\begin{pmatrix}");
        for (i, row) in v.iter().enumerate() {
            if i > 0 {
                // A vector is a column, as a textbook sets it.
                out.push_str(" \\\\ ");
            }
            match row {
                Expr::List(cells) if is_matrix => write_separated(cells, " & ", out, self),
                other => write(other, out, Prec::Sum, self),
            }
        }
        out.push_str("\\end{pmatrix}");
    }
    fn index(&self, e: &Expr, out: &mut String) {
        // v[0][2] -> v_{0 2}: one subscript for the whole chain.
        let (base, indices, axes) = index_chain(e);
        // A named vector or tensor takes axis letters: I_{xy}, L_{z}.
        if let Expr::Sym(name) = base
            && let Some(symbol) = (self.named)(name)
            && let Some(axes) = axes
        {
            let axes: String = axes.into_iter().collect();
            out.push_str(&format!("{{{symbol}}}_{{{axes}}}"));
            return;
        }
        let start = out.len();
        write(base, out, Prec::Power, self);
        brace_if_scripted(out, start, '_');
        out.push_str("_{");
        for (k, i) in indices.iter().enumerate() {
            if k > 0 {
                out.push(' ');
            }
            write(i, out, Prec::Sum, self);
        }
        out.push('}');
    }
}

/// `alpha` -> `\alpha`, `w1` -> `\omega_{1}`, `wd1` -> `\dot{\omega}_{1}`, `Ixx` -> `I_{xx}`,
/// `inertia_tensor` -> upright text; a name the scene typesets as it says.
fn latex_symbol(s: &str, own: OwnLatex<'_>) -> String {
    if let Some(tex) = own(s) {
        return tex;
    }
    // A numbered result of a step the scene typesets: `acc_2` of `tex = "a"` is a₂.
    if let Some((base, k)) = numbered(s)
        && let Some(own) = own(base)
    {
        return format!("{{{own}}}_{{{k}}}");
    }
    match name_form(s) {
        // A coordinate's rates: `phi'` is φ̇, `phi''` φ̈.
        NameForm::Rate(base, second) => format!(
            "\\{}{{{}}}",
            if second { "ddot" } else { "dot" },
            latex_symbol(base, own)
        ),
        NameForm::Numeral(digits) => digits.to_string(),
        NameForm::Word(w) => format!("\\mathrm{{{}}}", w.replace('_', "\\_")),
        NameForm::Inertia(axes) => format!("I_{{{axes}}}"),
        NameForm::Head(head, tail) => {
            let head = match head {
                Head::Omega => "\\omega".to_string(),
                Head::OmegaRate => "\\dot{\\omega}".to_string(),
                Head::Greek(g) => format!("\\{g}"),
                Head::Upright(u) => format!("\\mathrm{{{u}}}"),
                Head::Letter(l) => l.to_string(),
            };
            if tail.is_empty() {
                head
            } else if GREEK.contains(&tail) {
                format!("{head}_{{\\{tail}}}")
            } else {
                format!("{head}_{{{tail}}}")
            }
        }
    }
}
