//! The width of a formula, estimated on the read tree in characters of a typical formula
//! (about 0.66 em each), for the line breaker (`linebreak.rs`).

use super::latex::{Node, cells, relation_text};
use pulldown_latex::event::{
    Content, Dimension, DimensionUnit, Font, Grouping, RelationContent, ScriptPosition,
    StateChange, Visual,
};

/// The estimated width of a sequence of nodes, in characters.
pub fn width(nodes: &[Node]) -> f32 {
    let mut w = 0.0;
    for n in nodes {
        add(n, &mut w);
    }
    w
}

pub(super) fn node_width(n: &Node) -> f32 {
    let mut w = 0.0;
    add(n, &mut w);
    w
}

fn near(a: f32, b: f32) -> bool {
    (a - b).abs() < 1e-4
}

/// Adds a node's width to `w`, term by term in the order the LaTeX is written (a number digit
/// by digit, a script after its base), so that the sum rounds the same however the tree nests.
fn add(n: &Node, w: &mut f32) {
    *w += match n {
        Node::Text(s) if s == "&nbsp;" => 1.0,
        Node::Text(s) => s.chars().count() as f32,
        Node::Number(s) => {
            for _ in s.chars() {
                *w += 1.0;
            }
            return;
        }
        Node::Function(f) => function_width(f),
        Node::Atom(c) => atom_width(c, w),
        Node::Group(Grouping::Normal, inner) => normal_group_width(inner, w),
        Node::Group(Grouping::LeftRight(..), inner) => stretched_width(n, inner),
        Node::Group(Grouping::Aligned, body) => table_width(body, false),
        Node::Group(_, body) => table_width(body, true),
        Node::Visual(v, parts) => match v {
            Visual::Fraction(_) => operand_width(&parts[0]).max(operand_width(&parts[1])) + 0.5,
            Visual::SquareRoot | Visual::Negation => {
                *w += 1.0;
                add(&parts[0], w);
                return;
            }
            Visual::Root => 3.0 + node_width(&parts[0]) + node_width(&parts[1]),
        },
        Node::Script {
            position, parts, ..
        } => {
            add_script(*position, parts, w);
            return;
        }
        Node::Space(Some(Dimension {
            value,
            unit: DimensionUnit::Em,
        })) if near(*value, 1.0 / 6.0) || near(*value, 5.0 / 18.0) => 0.0,
        Node::Space(Some(Dimension {
            value,
            unit: DimensionUnit::Em,
        })) if near(*value, 1.0) => 2.0,
        Node::Space(_) => 1.0,
        Node::State(_) | Node::Flow(_) => 0.0,
    };
}

/// An operator name: four for the common ones, one for LaTeX's other commands, else its letters.
fn function_width(f: &str) -> f32 {
    match f {
        "sin" | "cos" | "det" | "tan" => 4.0,
        // LaTeX's other operator names, `\arccos`, `\min`: one command each.
        "arccos" | "arcsin" | "arctan" | "arg" | "cosh" | "cot" | "coth" | "csc" | "deg"
        | "dim" | "exp" | "gcd" | "hom" | "inf" | "ker" | "lg" | "lim" | "liminf" | "limsup"
        | "ln" | "log" | "max" | "min" | "Pr" | "sec" | "sinh" | "sup" | "tanh" => 1.0,
        // `\operatorname{…}`: its letters.
        other => other.chars().count() as f32,
    }
}

/// An atom: two for `+`, `−`, `×` and the wide relations; a sized delimiter adds one for its
/// `\Bigl` (to `w`).
fn atom_width(c: &Content, w: &mut f32) -> f32 {
    match c {
        Content::BinaryOp {
            content: '+' | '−' | '×',
            ..
        } => 2.0,
        Content::Relation { content, .. } if relation_is(content, &['=', '<', '>', '≈', '⟂']) => {
            2.0
        }
        // `\Bigl` and its bracket.
        Content::Delimiter { size: Some(_), .. } => {
            *w += 1.0;
            1.0
        }
        _ => 1.0,
    }
}

/// A group: a font's word by its letters, another font adding one (to `w`).
fn normal_group_width(inner: &[Node], w: &mut f32) -> f32 {
    match inner.first() {
        // `\mathrm{…}`, `\mathbb{…}`: the letters of the word.
        Some(Node::State(StateChange::Font(Some(Font::UpRight | Font::DoubleStruck)))) => {
            written_length(&inner[1..])
        }
        Some(Node::State(StateChange::Font(Some(_)))) => {
            *w += 1.0;
            width(&inner[1..])
        }
        _ => width(inner),
    }
}

/// Brackets stretched around their content, or a matrix.
fn stretched_width(n: &Node, inner: &[Node]) -> f32 {
    match matrix(n) {
        Some((_, body)) => table_width(body, true),
        // Brackets stretched around a fraction are wider (measured in Chromium: a phone's
        // (5ma²/4 − λ)(19ma²/4 − λ)(6ma² − λ) ran 1.3 % past its line).
        None if inner
            .iter()
            .any(|n| matches!(n, Node::Visual(Visual::Fraction(_), _))) =>
        {
            width(inner) + 2.0
        }
        None => width(inner) + 1.0,
    }
}

/// A base with its scripts: sub- and superscripts at 0.7 of their width, an accent at none.
fn add_script(position: ScriptPosition, parts: &[Node], w: &mut f32) {
    add(&parts[0], w);
    for s in &parts[1..] {
        match s {
            _ if position == ScriptPosition::AboveBelow && accent_mark(s) => {}
            Node::Group(Grouping::Normal, inner) => *w += width(inner) * 0.7,
            other => add(other, w),
        }
    }
}

/// A fraction's part: a group's content, else the element.
fn operand_width(n: &Node) -> f32 {
    match n {
        Node::Group(Grouping::Normal, inner) => width(inner),
        other => node_width(other),
    }
}

/// The length of a word as written in LaTeX: an escaped character (`\_`) two, a thin space two.
fn written_length(nodes: &[Node]) -> f32 {
    nodes
        .iter()
        .map(|n| match n {
            Node::Atom(Content::Ordinary { content, .. })
                if content.is_ascii_punctuation() && "_%#&$".contains(*content) =>
            {
                2.0
            }
            Node::Atom(_) => 1.0,
            Node::Text(s) | Node::Number(s) | Node::Function(s) => s.chars().count() as f32,
            Node::Space(_) => 2.0,
            Node::Group(_, inner) => 2.0 + written_length(inner),
            Node::Script { parts, .. } => {
                written_length(&parts[..1])
                    + parts[1..]
                        .iter()
                        .map(|p| 1.0 + written_length(std::slice::from_ref(p)))
                        .sum::<f32>()
            }
            other => node_width(other),
        })
        .sum()
}

pub(super) fn relation_is(content: &RelationContent, chars: &[char]) -> bool {
    let text = relation_text(content);
    let mut s = text.chars();
    matches!((s.next(), s.next()), (Some(c), None) if chars.contains(&c))
}

/// The mark an accent puts over its base (`\vec`, `\dot`, `\ddot`, `\overleftrightarrow`).
fn accent_mark(n: &Node) -> bool {
    matches!(
        n,
        Node::Atom(Content::Ordinary {
            content: '→' | '˙' | '¨' | '↔' | '^' | '~' | '‾',
            ..
        })
    )
}

/// The kind and rows of a matrix in round brackets (`pmatrix`), if `n` is one.
pub(super) fn matrix(n: &Node) -> Option<(&Grouping, &[Node])> {
    match n {
        Node::Group(Grouping::LeftRight(Some('('), Some(')')), inner) => match inner.as_slice() {
            [Node::Group(kind @ Grouping::Matrix { .. }, body)] => Some((kind, body)),
            _ => None,
        },
        _ => None,
    }
}

/// A table's columns with their gaps; our stacked cells (`aligned`) have none.
pub(super) fn table_width(body: &[Node], gaps: bool) -> f32 {
    let (gap, sides) = if gaps { (1.5, 1.0) } else { (0.0, 0.0) };
    let rows = cells(body);
    let columns = rows.iter().map(Vec::len).max().unwrap_or(0);
    let widest = |j: usize| {
        rows.iter()
            .filter_map(|r| r.get(j))
            .map(|c| width(c))
            .fold(0.0, f32::max)
    };
    let w = (0..columns).map(|j| widest(j) + gap).sum::<f32>() + sides;
    // A column vector's entries are each set as wide as Chromium sets a line's (measured: the
    // entries of a vector of sums, 15 % over their estimate).
    if columns == 1 && rows.len() > 1 {
        w * 1.15
    } else {
        w
    }
}
