//! A formula tree as plain Unicode text, for where markup cannot go: a page's `<title>`, a
//! link's text, a figure's alt text, a Moodle question's name. `$\alpha$` is α, `$r^2$` r²,
//! `$I_{xx}$` I_xx, `$\frac{a}{b}$` a/b, `$\vec L$` L⃗.

use super::latex::{Node, Tex, relation_text};
use crate::base::format::superscript;
use pulldown_latex::event::{Content, EnvironmentFlow, Grouping, ScriptType, Visual};

impl Tex {
    pub fn to_plain(&self) -> String {
        let mut out = String::new();
        row(&self.nodes, &mut out);
        // One space where pieces meet with spaces of their own.
        out.split_whitespace().collect::<Vec<_>>().join(" ")
    }
}

fn row(nodes: &[Node], out: &mut String) {
    for n in nodes {
        node(n, out);
    }
}

/// A piece as one item: in parentheses when it is more than one character.
fn operand(nodes: &[Node]) -> String {
    let mut s = String::new();
    row(nodes, &mut s);
    operand_text(s.trim())
}

fn text_of(n: &Node) -> String {
    let mut s = String::new();
    node(n, &mut s);
    s.trim().to_string()
}

fn node(n: &Node, out: &mut String) {
    match n {
        Node::Text(t) => out.push_str(&t.replace("&nbsp;", " ")),
        Node::Number(s) | Node::Function(s) => out.push_str(s),
        Node::Atom(c) => atom(c, out),
        Node::Group(g, inner) => {
            let (open, close) = match g {
                Grouping::LeftRight(open, close) => (*open, *close),
                _ => (None, None),
            };
            out.extend(open);
            row(inner, out);
            // A fraction's space after it stops at the closing delimiter: (a/3), not (a/3 ).
            if close.is_some() {
                out.truncate(out.trim_end().len());
            }
            out.extend(close);
        }
        Node::Visual(v, parts) => visual(v, parts, out),
        Node::Script { ty, parts, .. } => script(*ty, parts, out),
        Node::Space(_) => out.push(' '),
        Node::State(_) => {}
        Node::Flow(EnvironmentFlow::Alignment) => out.push_str(", "),
        Node::Flow(_) => out.push_str("; "),
    }
}

/// An atom: operators spaced, except a sign that is a number's own.
fn atom(c: &Content, out: &mut String) {
    match c {
        Content::BinaryOp { content: '/', .. } => out.push('/'),
        // A sign with nothing before it to act on is a number's own: (−1, 1, 0), = −a.
        Content::BinaryOp { content, .. } if is_unary(out, *content) => out.push(*content),
        Content::BinaryOp { content, .. } => out.push_str(&format!(" {content} ")),
        Content::Relation { content, .. } => {
            out.push_str(&format!(" {} ", relation_text(content)));
        }
        Content::Punctuation(p) => out.push_str(&format!("{p} ")),
        Content::Ordinary { content, .. }
        | Content::LargeOp { content, .. }
        | Content::Delimiter { content, .. } => out.push(*content),
        other => out.push_str(&format!("{other:?}")),
    }
}

/// A fraction, a square root or a root.
fn visual(v: &Visual, parts: &[Node], out: &mut String) {
    match (v, parts) {
        // A space after: 2/3 m, not 2/3m. A product over a number needs no parentheses
        // (MR²/2); a sum above, or anything but one factor below, does ((a + b)/(2c)).
        (Visual::Fraction(_), [a, b]) => {
            let (top, bottom) = (text_of(a), text_of(b));
            let top = if top.contains(' ') || top.contains('/') {
                format!("({top})")
            } else {
                top
            };
            out.push_str(&format!("{top}/{} ", operand_text(&bottom)));
        }
        (Visual::SquareRoot, [a]) => {
            out.push_str(&format!("√{}", operand(std::slice::from_ref(a))));
        }
        (Visual::Root, [a, index]) => {
            let index: String = text_of(index).chars().map(superscript).collect();
            out.push_str(&format!("{index}√{}", operand(std::slice::from_ref(a))));
        }
        _ => row(parts, out),
    }
}

/// A base with its scripts: an accent as a combining mark, a subscript after `_`, a
/// superscript of digits in superscript digits.
fn script(ty: ScriptType, parts: &[Node], out: &mut String) {
    let base = parts.first().map(text_of).unwrap_or_default();
    // An accent: the base with the accent's combining mark.
    if let (ScriptType::Superscript, Some(Node::Atom(Content::Ordinary { content, .. }))) =
        (ty, parts.get(1))
        && let Some(mark) = combining(*content)
    {
        out.push_str(&base);
        out.push(mark);
        return;
    }
    out.push_str(&base);
    let (sub, sup) = match (ty, &parts[1..]) {
        (ScriptType::Subscript, [s]) => (Some(s), None),
        (ScriptType::Superscript, [s]) => (None, Some(s)),
        (ScriptType::SubSuperscript, [s, t]) => (Some(s), Some(t)),
        _ => (None, None),
    };
    if let Some(s) = sub {
        out.push('_');
        out.push_str(&text_of(s));
    }
    if let Some(s) = sup {
        let s = text_of(s);
        let tight: String = s.chars().filter(|c| !c.is_whitespace()).collect();
        if tight
            .chars()
            .all(|c| c.is_ascii_digit() || c == '−' || c == '-')
        {
            let s = tight;
            out.extend(
                s.chars()
                    .map(|c| if c == '−' { '⁻' } else { superscript(c) }),
            );
        } else {
            out.push('^');
            out.push_str(&operand_text(&s));
        }
    }
}

/// Whether a sign written after `out` acts on what follows alone: nothing, an opening bracket,
/// a comma or another operator comes before it.
fn is_unary(out: &str, sign: char) -> bool {
    let before = out.trim_end();
    matches!(sign, '−' | '-' | '+' | '±')
        && (before.is_empty()
            || before.ends_with([
                '(', '[', '{', ',', ';', '=', '<', '>', '≤', '≥', '≈', '+', '−', '±', '×', '·',
            ]))
}

/// Text as one item: in parentheses unless it is one character or one number (12, 0.5).
fn operand_text(s: &str) -> String {
    let number = !s.is_empty() && s.chars().all(|c| c.is_ascii_digit() || c == '.');
    if s.chars().count() > 1 && !number {
        format!("({s})")
    } else {
        s.to_string()
    }
}

/// The combining mark of an accent that pulldown-latex sets over its base.
fn combining(accent: char) -> Option<char> {
    Some(match accent {
        '→' => '\u{20d7}',
        '˙' => '\u{307}',
        '¨' => '\u{308}',
        '^' | 'ˆ' => '\u{302}',
        '¯' | '‾' => '\u{304}',
        '~' | '˜' => '\u{303}',
        '↔' => '\u{20e1}',
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plain(latex: &str) -> String {
        Tex::read(latex).unwrap().to_plain()
    }

    #[test]
    fn formulas_as_plain_text() {
        crate::base::assert_each(
            plain,
            &[
                ("\\alpha", "α"),
                ("r^2 + x^{-1}", "r² + x⁻¹"),
                ("I_{xx} = \\frac{2}{3} m a^2", "I_xx = 2/3 ma²"),
                ("\\frac{M R^2}{2}", "MR²/2"),
                ("\\frac{11}{12} m a^{2}", "11/12 ma²"),
                ("\\frac{a + b}{2 c}", "(a + b)/(2c)"),
                ("\\left(-1, 1, 0\\right) = -a + b", "(−1, 1, 0) = −a + b"),
                ("a - b", "a − b"),
                ("\\sqrt{g/l}", "√(g/l)"),
                ("\\vec L = \\dot\\theta", "L\u{20d7} = θ\u{307}"),
                ("A^{T}, \\left(a, b\\right)", "A^T, (a, b)"),
                ("\\mathrm{kg\\,m^2}", "kg m²"),
                (
                    "\\rho a \\left(\\frac{z y^3}{3} + \\frac{y z^3}{a}\\right)",
                    "ρa(zy³/3 + yz³/a)",
                ),
            ],
        );
    }
}
