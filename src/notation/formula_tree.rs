//! A [`Formula`] as the tree the pages set, built from its parts: its exact expressions by
//! `expr_tree`, an author's `$…$` as read at load. Nothing here reads LaTeX; a test holds the
//! tree equal to what the reader makes of the formula's LaTeX (`formula_print.rs`).

use super::Names;
use super::expr_tree::expr_nodes;
use super::formula::{Accent, Formula, GREEK, Name, Op};
use super::latex::{Node, Tex};
use super::tree::{
    MEDIUM, MINUS, THIN, accent, attach, bin, delim, frac, grown, in_font, large, letters, num,
    ord, parens, pmatrix, punct, rel, space, sqrt, upright,
};
use crate::cas::greek_letter;
use pulldown_latex::event::{DelimiterType, Font, ScriptPosition, ScriptType};

impl Formula {
    /// The formula as the one tree every page printer sets, with its LaTeX (for messages,
    /// Moodle and `--json`) as its source.
    pub fn to_tex(&self, names: &Names) -> Tex {
        match self {
            Formula::Tex(t) => t.clone(),
            other => Tex {
                source: other.to_latex(names),
                nodes: nodes(other, names),
            },
        }
    }
}

/// The tree of a formula.
pub fn nodes(f: &Formula, names: &Names) -> Vec<Node> {
    let mut out = Vec::new();
    write(f, names, &mut out);
    out
}

fn write(f: &Formula, names: &Names, out: &mut Vec<Node>) {
    match f {
        Formula::Expr(e) => out.extend(expr_nodes(e, names, &|_| None)),
        Formula::Name(n) => name(n, out),
        Formula::Number(s) => match s.strip_prefix('-') {
            Some(digits) => out.extend([bin(MINUS), num(digits)]),
            None => out.push(num(s.as_str())),
        },
        Formula::Text(s) => out.push(Node::Text(s.clone())),
        Formula::Upright(s) => out.push(upright(s)),
        Formula::Row(items) => items.iter().for_each(|item| write(item, names, out)),
        Formula::Op(op) => out.push(operator(*op)),
        Formula::Frac(a, b) => out.push(frac(nodes(a, names), nodes(b, names))),
        Formula::Sqrt(a) => out.push(sqrt(nodes(a, names))),
        Formula::Sup(a, b) => {
            write(a, names, out);
            attach(out, ScriptType::Superscript, nodes(b, names));
        }
        Formula::Paren(a, true) => out.push(parens(nodes(a, names))),
        Formula::Paren(a, false) => {
            out.push(delim('(', DelimiterType::Open));
            write(a, names, out);
            out.push(delim(')', DelimiterType::Close));
        }
        Formula::Bracket(a) => out.push(grown(Some('['), Some(']'), nodes(a, names))),
        Formula::Abs(a) => out.push(grown(Some('|'), Some('|'), nodes(a, names))),
        Formula::Identity => out.push(in_font(Font::DoubleStruck, vec![num("1")])),
        Formula::Matrix(rows) => out.push(pmatrix(
            rows.iter()
                .map(|row| row.iter().map(|c| nodes(c, names)).collect())
                .collect(),
        )),
        Formula::Function(name) => out.push(Node::Function(name.clone())),
        Formula::Sum(index) => {
            out.push(large('∑'));
            if let Some(i) = index {
                // A big operator's limits sit below it in display, beside it inline.
                super::tree::attach_at(
                    out,
                    ScriptType::Subscript,
                    ScriptPosition::Movable,
                    letters(i),
                );
            }
        }
        Formula::Integral(limits) => {
            out.push(large('∫'));
            if let Some(limits) = limits {
                attach(out, ScriptType::Subscript, nodes(&limits.0, names));
                attach(out, ScriptType::Superscript, nodes(&limits.1, names));
            }
        }
        Formula::Nabla(by) => {
            out.push(ord('∇'));
            if let Some(by) = by {
                attach(out, ScriptType::Subscript, base(by));
            }
        }
        Formula::At(a, frame) => {
            out.push(grown(None, Some('|'), nodes(a, names)));
            attach(out, ScriptType::Subscript, vec![upright(frame)]);
        }
        Formula::Tex(t) => out.extend(t.nodes.iter().cloned()),
    }
}

fn operator(op: Op) -> Node {
    match op {
        Op::Equals => rel('='),
        Op::Approx => rel('≈'),
        Op::Less => rel('<'),
        Op::LessEqual => rel('≤'),
        Op::Greater => rel('>'),
        Op::Plus => bin('+'),
        Op::Minus => bin(MINUS),
        Op::Dot => bin('⋅'),
        Op::Cross => bin('×'),
        Op::Parallel => rel('∥'),
        Op::Perp => rel('⟂'),
        Op::Comma => punct(','),
        Op::Colon => rel(':'),
        Op::Semicolon => punct(';'),
        Op::Slash => bin('/'),
        Op::Thin => space(THIN),
        Op::Medium => space(MEDIUM),
        Op::Quad => space(1.0),
    }
}

/// A letter: a Greek one by its name, else as written.
fn base(s: &str) -> Vec<Node> {
    if GREEK.iter().any(|(name, _)| *name == s)
        && let Some(c) = greek_letter(s).and_then(|g| g.chars().next())
    {
        return vec![ord(c)];
    }
    letters(s)
}

fn name(n: &Name, out: &mut Vec<Node>) {
    let b = base(&n.base);
    match n.accent {
        Accent::None => out.extend(b),
        Accent::Vector => out.push(accent(b, '→', false)),
        Accent::Tensor => out.push(accent(b, '↔', true)),
        Accent::Dot => out.push(accent(b, '˙', false)),
        Accent::DoubleDot => out.push(accent(b, '¨', false)),
        Accent::VectorDot => out.push(accent(vec![accent(b, '→', false)], '˙', false)),
    }
    if let Some(sub) = n.sub.as_deref() {
        let script = match sub {
            "min" | "max" => vec![Node::Function(sub.to_string())],
            // A word is upright (I_cm); a pair of axes (I_xy) or a number is not.
            s if s.len() > 1 && !s.chars().all(|c| c.is_ascii_digit() || "xyz".contains(c)) => {
                vec![upright(s)]
            }
            s => letters(s),
        };
        attach(out, ScriptType::Subscript, script);
    }
    if n.prime {
        out.extend([space(THIN), ord('′')]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kind of formula node, built as a tree, is what the reader makes of its LaTeX.
    #[test]
    fn each_formula_is_the_tree_its_latex_reads_as() {
        let e = [
            crate::cas::parse("a^2/12 + b^2/12").unwrap().expr,
            crate::cas::parse("-3*x").unwrap().expr,
        ];
        for src in [
            "vec(L) = ten(I) vec(omega)",
            "dot(vec(L)) = vec(N)",
            "ddot(theta) + Omega^2 sin theta = 0",
            "I_cm = I_xy + I_min + I_max",
            "T = sum_i L_i^2/(2I_i)",
            "((nabla_rho F)/vec(L))^2",
            "int_0^(2pi) $0 ~ dphi",
            "|vec(a)| <= sqrt($1) ; rm(day) // rm(sidereal)",
            "one - det(A) , [0, 2pi] : omega || L quad vec(a) perp vec(b)",
            "big(1/2 m v^2) ~= $0 ~~ x > 0",
            "(dL/dt)|_body · x × y",
            "-x = 2.5",
            "r' = omega_3'",
        ] {
            let f = Formula::parse(src, &e);
            let latex = f.to_latex(crate::notation::Names::none());
            let read = Tex::read(&latex).unwrap_or_else(|e| panic!("{latex}: {e}"));
            assert_eq!(
                nodes(&f, crate::notation::Names::none()),
                read.nodes,
                "{src}\n{latex}"
            );
        }
        // A computed number is the tree of its LaTeX (4.6875 × 10⁻⁶, never e-notation).
        for s in ["4.6875e-6", "-1.5e+07", "1e-12", "0.25", "-3", "NaN", "inf"] {
            let latex = crate::base::format::latex_number(s);
            let read = Tex::read(&latex).unwrap().nodes;
            assert_eq!(
                nodes(&Formula::decimal(s), crate::notation::Names::none()),
                read,
                "{s}: {latex}"
            );
        }
        let f = Formula::Row(vec![
            Formula::Number("-2.25".into()),
            Formula::Text("words".into()),
        ]);
        assert_eq!(
            nodes(&f, crate::notation::Names::none()),
            Tex::read(&f.to_latex(crate::notation::Names::none()))
                .unwrap()
                .nodes
        );
    }
}
