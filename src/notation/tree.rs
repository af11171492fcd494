//! The pieces of the formula tree ([`Node`]) that mechbook's own printers build: letters,
//! numbers, operators, groups, fractions, roots, scripts and accents, each as the one LaTeX
//! reader would have read it, so that an author's `$…$` and a printed result are one tree.

use super::latex::{Node, Tex};
use pulldown_latex::event::{
    Content, DelimiterType, Dimension, DimensionUnit, EnvironmentFlow, Font, Grouping,
    ScriptPosition, ScriptType, StateChange, Visual,
};
use std::collections::BTreeMap;
use std::sync::OnceLock;

pub fn ord(c: char) -> Node {
    Node::Atom(Content::Ordinary {
        content: c,
        stretchy: false,
    })
}

pub fn num(digits: impl Into<String>) -> Node {
    Node::Number(digits.into())
}

/// A binary operator: `+`, `−`, `⋅`, `×`, `/`.
pub fn bin(c: char) -> Node {
    Node::Atom(Content::BinaryOp {
        content: c,
        small: false,
    })
}

pub const MINUS: char = '−';

/// A relation (`=`, `≈`, `≤`, `:`). pulldown-latex keeps a relation's constructor to itself, so
/// each is taken once from its parser, from the one command that writes it.
pub fn rel(c: char) -> Node {
    static RELATIONS: OnceLock<BTreeMap<char, Node>> = OnceLock::new();
    let table = RELATIONS.get_or_init(|| {
        [
            "=",
            "<",
            ">",
            ":",
            "\\approx",
            "\\le",
            "\\parallel",
            "\\perp",
        ]
        .into_iter()
        .filter_map(|latex| {
            let node = Tex::read(latex).ok()?.nodes.pop()?;
            let Node::Atom(Content::Relation { content, .. }) = &node else {
                return None;
            };
            let text = super::latex::relation_text(content);
            Some((text.chars().next()?, node))
        })
        .collect()
    });
    table
        .get(&c)
        .cloned()
        .unwrap_or_else(|| panic!("`{c}` is not among the relations the printers write"))
}

pub fn punct(c: char) -> Node {
    Node::Atom(Content::Punctuation(c))
}

/// A delimiter that keeps its size: `(` or `)`.
pub fn delim(c: char, ty: DelimiterType) -> Node {
    Node::Atom(Content::Delimiter {
        content: c,
        size: None,
        ty,
    })
}

pub fn large(c: char) -> Node {
    Node::Atom(Content::LargeOp {
        content: c,
        small: false,
    })
}

/// `{…}`.
pub fn group(inner: Vec<Node>) -> Node {
    Node::Group(Grouping::Normal, inner)
}

/// `\left( … \right)` and the like; `None` for an invisible side (`\left.`).
pub fn grown(open: Option<char>, close: Option<char>, inner: Vec<Node>) -> Node {
    Node::Group(Grouping::LeftRight(open, close), inner)
}

pub fn parens(inner: Vec<Node>) -> Node {
    grown(Some('('), Some(')'), inner)
}

pub fn frac(num: Vec<Node>, den: Vec<Node>) -> Node {
    Node::Visual(Visual::Fraction(None), vec![group(num), group(den)])
}

pub fn sqrt(inner: Vec<Node>) -> Node {
    Node::Visual(Visual::SquareRoot, vec![group(inner)])
}

/// A space of `em` ems: `\,` is 1/6, `\;` 5/18, `\quad` 1.
pub fn space(em: f32) -> Node {
    Node::Space(Some(Dimension {
        value: em,
        unit: DimensionUnit::Em,
    }))
}

pub const THIN: f32 = 1.0 / 6.0;
pub const MEDIUM: f32 = 5.0 / 18.0;

/// A font for what follows in its group: `\mathrm{…}` is a group that starts so.
pub fn in_font(font: Font, inner: Vec<Node>) -> Node {
    let mut nodes = vec![Node::State(StateChange::Font(Some(font)))];
    nodes.extend(inner);
    group(nodes)
}

/// Letters as written in a name: a run of digits is one number, anything else a letter.
pub fn letters(s: &str) -> Vec<Node> {
    let mut out = Vec::new();
    let mut digits = String::new();
    for c in s.chars() {
        if c.is_ascii_digit() {
            digits.push(c);
            continue;
        }
        if !digits.is_empty() {
            out.push(num(std::mem::take(&mut digits)));
        }
        out.push(ord(c));
    }
    if !digits.is_empty() {
        out.push(num(digits));
    }
    out
}

pub fn upright(s: &str) -> Node {
    in_font(Font::UpRight, letters(s))
}

/// The nodes with each run of two or more letters set upright (`\mathrm{body}`, a unit's `kg`)
/// as one piece of text: one identifier on the page and one word to a listener, not four
/// italic-less letters read one by one.
pub fn upright_words(nodes: &[Node]) -> Vec<Node> {
    super::latex::rewrite(nodes, &|n| match n {
        Node::Group(g, inner)
            if matches!(
                inner.first(),
                Some(Node::State(StateChange::Font(Some(Font::UpRight))))
            ) =>
        {
            Node::Group(g, joined_letters(inner))
        }
        other => other,
    })
}

/// A run of two or more Latin letters as one text node, with the underscores and digits
/// within it (a name set as a word, `w_min2`); anything else as it is.
fn joined_letters(nodes: Vec<Node>) -> Vec<Node> {
    let mut out = Vec::new();
    let mut run: Vec<Node> = Vec::new();
    let flush = |run: &mut Vec<Node>, out: &mut Vec<Node>| {
        let letters = run
            .iter()
            .filter(|n| matches!(n, Node::Atom(Content::Ordinary { content, .. }) if content.is_ascii_alphabetic()))
            .count();
        if letters >= 2 {
            let word: String = run
                .iter()
                .map(|n| match n {
                    Node::Atom(Content::Ordinary { content, .. }) => content.to_string(),
                    Node::Number(digits) => digits.clone(),
                    _ => String::new(),
                })
                .collect();
            out.push(Node::Text(word));
            run.clear();
        } else {
            out.append(run);
        }
    };
    for n in nodes {
        let joins = match &n {
            Node::Atom(Content::Ordinary { content, .. }) => {
                content.is_ascii_alphabetic() || (*content == '_' && !run.is_empty())
            }
            Node::Number(_) => !run.is_empty(),
            _ => false,
        };
        if joins {
            run.push(n);
        } else {
            flush(&mut run, &mut out);
            out.push(n);
        }
    }
    flush(&mut run, &mut out);
    out
}

/// An accent over `base`: `\dot{x}` is `˙`, `\ddot` `¨`, `\vec` `→`.
pub fn accent(base: Vec<Node>, mark: char, stretchy: bool) -> Node {
    Node::Script {
        ty: ScriptType::Superscript,
        position: ScriptPosition::AboveBelow,
        parts: vec![
            group(base),
            Node::Atom(Content::Ordinary {
                content: mark,
                stretchy,
            }),
        ],
    }
}

/// A script put on the last node written, as LaTeX's `^{…}` and `_{…}` bind: a superscript on
/// a subscripted base, or a subscript on a raised one, makes one node with both (`m_1^{2}`).
/// Nothing written yet: on an empty base. (A base that already has a script of the kind is
/// braced first by the caller, `expr_tree::script`, as the LaTeX printer braces it.)
pub fn attach(out: &mut Vec<Node>, ty: ScriptType, script: Vec<Node>) {
    attach_at(out, ty, ScriptPosition::Right, script);
}

pub fn attach_at(out: &mut Vec<Node>, ty: ScriptType, position: ScriptPosition, script: Vec<Node>) {
    let base = out.pop().unwrap_or_else(|| group(Vec::new()));
    let node = match (base, ty) {
        (
            Node::Script {
                ty: ScriptType::Subscript,
                position: p,
                mut parts,
            },
            ScriptType::Superscript,
        ) if p == position => {
            parts.push(group(script));
            Node::Script {
                ty: ScriptType::SubSuperscript,
                position,
                parts,
            }
        }
        (
            Node::Script {
                ty: ScriptType::Superscript,
                position: p,
                mut parts,
            },
            ScriptType::Subscript,
        ) if p == position => {
            parts.insert(1, group(script));
            Node::Script {
                ty: ScriptType::SubSuperscript,
                position,
                parts,
            }
        }
        (base, ty) => Node::Script {
            ty,
            position,
            parts: vec![base, group(script)],
        },
    };
    out.push(node);
}

/// A matrix's cells (rows of cells) in `( … )`, as `pmatrix` sets them.
pub fn pmatrix(rows: Vec<Vec<Vec<Node>>>) -> Node {
    let mut body = Vec::new();
    for (i, row) in rows.into_iter().enumerate() {
        if i > 0 {
            body.push(Node::Flow(EnvironmentFlow::NewLine {
                spacing: None,
                horizontal_lines: Box::new([]),
            }));
        }
        for (j, cell) in row.into_iter().enumerate() {
            if j > 0 {
                body.push(Node::Flow(EnvironmentFlow::Alignment));
            }
            body.extend(cell);
        }
    }
    parens(vec![Node::Group(
        Grouping::Matrix {
            alignment: pulldown_latex::event::ColumnAlignment::Center,
        },
        body,
    )])
}
