//! An exact expression as the formula tree the pages set: the same walk as its LaTeX printer
//! (`cas/print.rs`: signs, parentheses, a product's fraction bar, a sum's common factor), built
//! as nodes, so that no page reads back LaTeX that mechbook printed. A test holds the two equal.

use super::Names;
use super::latex::{Node, Tex};
use super::tree::{
    MINUS, THIN, accent, attach, bin, frac, group, letters, num, ord, parens, pmatrix, punct, rel,
    space, sqrt, upright,
};
use crate::cas::{
    Expr, Head, NameForm, Prec, Rational, greek_letter, index_chain, name_form, page_fraction,
    printed_common_factor, split_sign,
};
use pulldown_latex::event::{Font, ScriptPosition, ScriptType};
use std::collections::BTreeMap;
use std::sync::Mutex;

/// A catalogue symbol's LaTeX as a tree, read once (the catalogue's symbols are constants);
/// what the reader refuses is set as upright text.
fn catalogue(latex: &'static str) -> Vec<Node> {
    static READ: Mutex<BTreeMap<&'static str, Vec<Node>>> = Mutex::new(BTreeMap::new());
    let mut read = READ
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    read.entry(latex)
        .or_insert_with(|| Tex::read(latex).map_or_else(|_| vec![upright(latex)], |t| t.nodes))
        .clone()
}

type Named<'a> = &'a dyn Fn(&str) -> Option<&'static str>;

/// The tree of `e`; `named` gives some symbols a catalogue symbol (as `Expr::to_latex_named`).
pub fn expr_nodes(e: &Expr, names: &Names, named: Named<'_>) -> Vec<Node> {
    let mut out = Vec::new();
    Walk { names, named }.write(e, Prec::Sum, &mut out);
    out
}

impl Expr {
    /// The expression as the tree the pages set, with its LaTeX as the source.
    pub fn to_tex(&self, names: &Names) -> Tex {
        self.to_tex_named(names, &|_| None)
    }

    /// [`Expr::to_tex`], with some symbols given a catalogue symbol (`Expr::to_latex_named`).
    pub fn to_tex_named(&self, names: &Names, named: Named<'_>) -> Tex {
        Tex {
            source: self.to_latex_named(names, named),
            nodes: expr_nodes(self, names, named),
        }
    }
}

/// A catalogue symbol's tree (`quantity_symbol`): a constant of mechbook's, read once.
pub fn symbol_tex(latex: &'static str) -> Tex {
    Tex {
        source: latex.to_string(),
        nodes: catalogue(latex),
    }
}

struct Walk<'a> {
    names: &'a Names,
    named: Named<'a>,
}

impl Walk<'_> {
    fn nodes(&self, e: &Expr, ctx: Prec) -> Vec<Node> {
        let mut out = Vec::new();
        self.write(e, ctx, &mut out);
        out
    }

    fn write(&self, e: &Expr, ctx: Prec, out: &mut Vec<Node>) {
        match e {
            Expr::Num(r) => self.number(r, ctx, out),
            Expr::Sym(s) => out.extend(symbol(s, self.names, self.named)),
            Expr::Add(v) => {
                if ctx == Prec::Sum
                    && let Some((factor, rest)) = printed_common_factor(v)
                {
                    // c (a + b): the factor, then the sum left in parentheses.
                    let (negative, factor) = split_sign(&factor);
                    if negative {
                        out.push(bin(MINUS));
                    }
                    if !factor.is_one() {
                        self.write(&factor, Prec::Product, out);
                    }
                    out.push(parens(self.nodes(&Expr::Add(rest), Prec::Sum)));
                    return;
                }
                let mut terms = Vec::new();
                for (i, t) in v.iter().enumerate() {
                    let (negative, mag) = split_sign(t);
                    if negative || i > 0 {
                        terms.push(bin(if negative { MINUS } else { '+' }));
                    }
                    self.write(&mag, Prec::Product, &mut terms);
                }
                wrap(ctx > Prec::Sum, terms, out);
            }
            Expr::Mul(v) => {
                let (negative, mag) = split_sign(e);
                if !negative {
                    return self.product(v, ctx, out);
                }
                let mut inner = vec![bin(MINUS)];
                self.write(&mag, Prec::Product, &mut inner);
                wrap(ctx > Prec::Sum, inner, out);
            }
            Expr::Pow(a, b) => self.power(a, b, out),
            // a · b and a × b as a factor of a product take parentheses: B (A · C), never B A · C.
            Expr::Call(n, _) if ctx >= Prec::Factor && matches!(n.as_str(), "dot" | "cross") => {
                out.push(parens(self.nodes(e, Prec::Sum)));
            }
            Expr::Call(n, args) => self.call(n, args, out),
            Expr::List(v) => out.push(self.list(v)),
            Expr::Index(..) => self.index(e, out),
        }
    }

    fn number(&self, r: &Rational, ctx: Prec, out: &mut Vec<Node>) {
        let (n, d) = r.abs_parts();
        let body = if r.is_integer() {
            num(n.to_string())
        } else {
            frac(vec![num(n.to_string())], vec![num(d.to_string())])
        };
        let mut inner = Vec::new();
        if r.is_negative() {
            inner.push(bin(MINUS));
        }
        inner.push(body);
        // A fraction under a power is bracketed: (8661249/1159339)^{3/2}.
        let bracket = r.is_negative() && ctx > Prec::Sum || !r.is_integer() && ctx == Prec::Power;
        wrap(bracket, inner, out);
    }

    fn product(&self, v: &[Expr], ctx: Prec, out: &mut Vec<Node>) {
        let (num, den) = page_fraction(v);
        let inner = if den.is_empty() {
            self.factors(&num)
        } else {
            vec![frac(self.factors(&num), self.factors(&den))]
        };
        wrap(ctx > Prec::Product, inner, out);
    }

    /// The factors above or below a fraction bar, side by side; `⋅` before a number.
    fn factors(&self, fs: &[Expr]) -> Vec<Node> {
        let fs: Vec<&Expr> = fs.iter().filter(|f| !f.is_one()).collect();
        let mut out = Vec::new();
        if fs.is_empty() {
            out.push(num("1"));
        }
        let ctx = if fs.len() == 1 {
            Prec::Sum
        } else {
            Prec::Power
        };
        for (i, f) in fs.iter().enumerate() {
            if i > 0 && f.leads_with_numeral() {
                out.push(bin('⋅'));
            }
            self.write(f, ctx, &mut out);
        }
        out
    }

    fn power(&self, a: &Expr, b: &Expr, out: &mut Vec<Node>) {
        if let Expr::Num(r) = b {
            if *r == Rational::new(1, 2).unwrap() {
                out.push(sqrt(self.nodes(a, Prec::Sum)));
                return;
            }
            if r.is_negative() {
                let positive = Expr::pow(a.clone(), Expr::Num(r.negated()));
                out.push(frac(vec![num("1")], self.nodes(&positive, Prec::Sum)));
                return;
            }
        }
        // sin(x)^2 as sin²(x).
        if let Expr::Call(n, args) = a
            && (n == "sin" || n == "cos")
        {
            out.push(space(THIN));
            out.push(group(vec![Node::Function(n.clone())]));
            attach(out, ScriptType::Superscript, self.nodes(b, Prec::Sum));
            out.push(parens(self.nodes(&args[0], Prec::Sum)));
            return;
        }
        let start = out.len();
        self.write(a, Prec::Power, out);
        script(
            out,
            start,
            ScriptType::Superscript,
            self.nodes(b, Prec::Sum),
        );
    }

    fn call(&self, n: &str, args: &[Expr], out: &mut Vec<Node>) {
        match (n, args) {
            ("sqrt", [a]) => out.push(sqrt(self.nodes(a, Prec::Sum))),
            ("dot" | "cross", [a, b]) => {
                self.write(a, Prec::Factor, out);
                out.push(bin(if n == "dot" { '⋅' } else { '×' }));
                self.write(b, Prec::Factor, out);
            }
            ("outer", [a, b]) => {
                self.write(a, Prec::Power, out);
                out.push(space(THIN));
                let start = out.len();
                self.write(b, Prec::Power, out);
                script(out, start, ScriptType::Superscript, vec![ord('T')]);
            }
            ("transpose", [a]) => {
                let start = out.len();
                self.write(a, Prec::Power, out);
                script(out, start, ScriptType::Superscript, vec![ord('T')]);
            }
            ("eye", []) => out.push(super::tree::in_font(Font::DoubleStruck, vec![num("1")])),
            ("rot_x" | "rot_y" | "rot_z", [angle]) => {
                out.push(ord('R'));
                attach(out, ScriptType::Subscript, letters(&n[4..]));
                out.push(parens(self.nodes(angle, Prec::Sum)));
            }
            ("diff", [f, x]) => {
                let mut den = vec![ord('∂')];
                self.write(x, Prec::Power, &mut den);
                out.push(frac(vec![ord('∂')], den));
                self.write(f, Prec::Power, out);
            }
            ("subs", [f, x, v]) => {
                out.push(super::tree::grown(
                    None,
                    Some('|'),
                    self.nodes(f, Prec::Sum),
                ));
                let mut at = self.nodes(x, Prec::Sum);
                at.push(rel('='));
                self.write(v, Prec::Sum, &mut at);
                attach(out, ScriptType::Subscript, at);
            }
            ("abs", [x]) => out.push(super::tree::grown(
                Some('|'),
                Some('|'),
                self.nodes(x, Prec::Sum),
            )),
            _ => {
                out.push(Node::Function(crate::cas::textbook_name(n).to_string()));
                let mut inner = Vec::new();
                for (i, a) in args.iter().enumerate() {
                    if i > 0 {
                        inner.push(punct(','));
                    }
                    self.write(a, Prec::Sum, &mut inner);
                }
                out.push(parens(inner));
            }
        }
    }

    fn list(&self, v: &[Expr]) -> Node {
        let is_matrix = v.iter().all(|r| matches!(r, Expr::List(_)));
        let rows = if is_matrix {
            v.iter()
                .map(|row| match row {
                    Expr::List(cells) => cells.iter().map(|c| self.nodes(c, Prec::Sum)).collect(),
                    _ => unreachable!("every row of a matrix is a list"),
                })
                .collect()
        } else {
            // A vector is a column, as a textbook sets it.
            v.iter().map(|c| vec![self.nodes(c, Prec::Sum)]).collect()
        };
        pmatrix(rows)
    }

    fn index(&self, e: &Expr, out: &mut Vec<Node>) {
        // v[0][2] -> v_{0 2}: one subscript for the whole chain.
        let (base, indices, axes) = index_chain(e);
        // A named vector or tensor takes axis letters: I_{xy}, L_{z}.
        if let Expr::Sym(name) = base
            && let Some(symbol) = (self.named)(name)
            && let Some(axes) = axes
        {
            out.push(group(catalogue(symbol)));
            attach(
                out,
                ScriptType::Subscript,
                axes.into_iter().map(ord).collect(),
            );
            return;
        }
        let start = out.len();
        self.write(base, Prec::Power, out);
        let mut sub = Vec::new();
        for i in indices {
            self.write(i, Prec::Sum, &mut sub);
        }
        script(out, start, ScriptType::Subscript, sub);
    }
}

/// A script on the base written at `out[start..]`; a base that already ends with a script of
/// that kind is braced whole first, as the LaTeX printer braces it (`{r_{1}}_{2}`).
fn script(out: &mut Vec<Node>, start: usize, ty: ScriptType, script: Vec<Node>) {
    let kinds = |t: &ScriptType| match t {
        ScriptType::SubSuperscript => [true, true],
        ScriptType::Subscript => [true, false],
        ScriptType::Superscript => [false, true],
    };
    if let Some(Node::Script {
        ty: had,
        position: ScriptPosition::Right,
        ..
    }) = out.last()
        && kinds(had).iter().zip(kinds(&ty)).any(|(a, b)| *a && b)
    {
        let base = out.split_off(start);
        out.push(group(base));
    }
    attach(out, ty, script);
}

/// `inner`, in `( … )` when `parenthesised`.
fn wrap(parenthesised: bool, inner: Vec<Node>, out: &mut Vec<Node>) {
    if parenthesised {
        out.push(parens(inner));
    } else {
        out.extend(inner);
    }
}

/// A symbol's tree: the catalogue's, the scene's own, or by the naming conventions (`alpha` is
/// α, `w1` ω₁, `wd1` ω̇₁, `Ixx` I_xx, `phi'` φ̇, a longer name upright).
pub fn symbol(s: &str, names: &Names, named: Named<'_>) -> Vec<Node> {
    if let Some(latex) = named(s) {
        return catalogue(latex);
    }
    if let Some(nodes) = names.nodes(s) {
        return nodes.to_vec();
    }
    // A numbered result of a step the scene typesets: `acc_2` of `tex = "a"` is a₂.
    if let Some((base, k)) = crate::cas::numbered(s)
        && let Some(nodes) = names.nodes(base)
    {
        let nodes = nodes.to_vec();
        let mut out = if nodes.len() == 1 {
            nodes
        } else {
            vec![group(nodes)]
        };
        attach(&mut out, ScriptType::Subscript, vec![num(k)]);
        return out;
    }
    match name_form(s) {
        NameForm::Rate(base, second) => {
            vec![accent(
                symbol(base, names, &|_| None),
                if second { '¨' } else { '˙' },
                false,
            )]
        }
        NameForm::Numeral(digits) => vec![num(digits)],
        NameForm::Word(w) => vec![upright(w)],
        NameForm::Inertia(axes) => {
            let mut out = vec![ord('I')];
            attach(&mut out, ScriptType::Subscript, letters(axes));
            out
        }
        NameForm::Head(head, tail) => {
            let mut out = vec![match head {
                Head::Omega => ord('ω'),
                Head::OmegaRate => accent(vec![ord('ω')], '˙', false),
                Head::Greek(g) => ord(greek(g)),
                Head::Upright(u) => upright(u),
                Head::Letter(l) => letters(l).remove(0),
            }];
            if greek_letter(tail).is_some() {
                attach(&mut out, ScriptType::Subscript, vec![ord(greek(tail))]);
            } else if !tail.is_empty() {
                attach(&mut out, ScriptType::Subscript, letters(tail));
            }
            out
        }
    }
}

/// A Greek letter's character, by its name, as the reader sets `\phi` (ϕ) and `\epsilon` (ϵ).
fn greek(name: &str) -> char {
    greek_letter(name)
        .and_then(|s| s.chars().next())
        .unwrap_or_else(|| panic!("`{name}` is among the Greek names the conventions know"))
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::notation::random_expr::Gen;

    /// The tree built from an expression is what the one reader makes of the LaTeX printed
    /// from it, over thousands of expressions of every kind of node, with a scene's own names
    /// and a catalogue symbol in force.
    const CASES: usize = 4000;

    #[test]
    fn the_tree_of_an_expression_is_its_latex_read() {
        let named = |s: &str| (s == "tensor_of").then_some("\\overleftrightarrow{I}");
        let scene: BTreeMap<String, String> = [
            ("m1", "m_1"),
            ("OmE", "\\Omega_{\\mathrm{E}}"),
            ("L", "\\vec{L}"),
        ]
        .into_iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
        let mut g = Gen(0x9E37_79B9_7F4A_7C15);
        let (mut compared, mut unreadable) = (0, Vec::new());
        let names = Names::of(&scene);
        {
            for case in 0..CASES {
                let e = g.expr(4);
                let latex = e.to_latex_named(&names, &named);
                let read = match Tex::read(&latex) {
                    Ok(read) => read,
                    Err(err) => {
                        unreadable.push(format!("{err}: {latex}"));
                        continue;
                    }
                };
                if expr_nodes(&e, &names, &named) != read.nodes {
                    let e = smallest_mismatch(&e, &names, &named).unwrap_or(e);
                    let latex = e.to_latex_named(&names, &named);
                    panic!(
                        "case {case}: {e:?}\n{latex}\nbuilt {:?}\nread  {:?}",
                        expr_nodes(&e, &names, &named),
                        Tex::read(&latex).map(|t| t.nodes)
                    );
                }
                compared += 1;
            }
        }
        // Every LaTeX the printer writes reads (a script is never put twice on one base).
        assert_eq!(unreadable, Vec::<String>::new());
        assert_eq!(compared, CASES);
    }

    /// The smallest part of `e` whose tree and read LaTeX differ, to name a failure plainly.
    fn smallest_mismatch(e: &Expr, names: &Names, named: Named<'_>) -> Option<Expr> {
        let children: Vec<Expr> = match e {
            Expr::Add(v) | Expr::Mul(v) | Expr::List(v) | Expr::Call(_, v) => v.clone(),
            Expr::Pow(a, b) | Expr::Index(a, b) => vec![a.as_ref().clone(), b.as_ref().clone()],
            _ => Vec::new(),
        };
        children
            .iter()
            .find_map(|c| smallest_mismatch(c, names, named))
            .or_else(|| {
                let latex = e.to_latex_named(names, named);
                let read = Tex::read(&latex).ok()?;
                (expr_nodes(e, names, named) != read.nodes).then(|| e.clone())
            })
    }
}
