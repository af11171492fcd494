//! The line breaker's last resort (`linebreak.rs`): a product with nothing left to open, cut
//! between its factors as a typesetter cuts one at a multiplication sign.

use super::latex::Node;
use super::width::width;
use pulldown_latex::event::{Content, Grouping};

/// A function's name, alone or with a power (`{\cos}^{2}`): its argument follows it.
fn names_a_function(n: &Node) -> bool {
    match n {
        Node::Function(_) => true,
        Node::Group(Grouping::Normal, inner) => matches!(inner.as_slice(), [Node::Function(_)]),
        Node::Script { parts, .. } => names_a_function(&parts[0]),
        _ => false,
    }
}

/// `\int`, `\sum`, alone or with its limits: its operand follows it.
fn large_operator(n: &Node) -> bool {
    match n {
        Node::Atom(Content::LargeOp { .. }) => true,
        Node::Script { parts, .. } => large_operator(&parts[0]),
        _ => false,
    }
}

/// Whether a product may be cut after `n`: a complete factor, not a function's name or a large
/// operator waiting for what it applies to.
fn ends_a_factor(n: &Node) -> bool {
    !names_a_function(n)
        && !large_operator(n)
        && matches!(
            n,
            Node::Group(..)
                | Node::Visual(..)
                | Node::Script { .. }
                | Node::Number(_)
                | Node::Atom(Content::Ordinary { .. })
        )
}

/// Whether a product may be cut before `n`: a factor starts there.
fn starts_a_factor(n: &Node) -> bool {
    !large_operator(n)
        && matches!(
            n,
            Node::Group(..)
                | Node::Visual(..)
                | Node::Script { .. }
                | Node::Number(_)
                | Node::Function(_)
                | Node::Atom(Content::Ordinary { .. })
        )
}

/// A segment still wider than its line with nothing left to open: a product, cut between two
/// of its factors as a typesetter breaks a long product at a multiplication sign, each later
/// piece starting with ⋅. Never between a function and its argument, after a large operator,
/// or inside a differential (`\,d\phi`, a space before its d).
pub(super) fn cut_product(seg: Vec<Node>, limit: f32) -> Vec<Vec<Node>> {
    if width(&seg) <= limit {
        return vec![seg];
    }
    let is_d = |n: &Node| matches!(n, Node::Atom(Content::Ordinary { content: 'd', .. }));
    let is_space = |n: &Node| matches!(n, Node::Space(_));
    // A cut before `seg[i]`: a factor starts there and one ends before it (a thin space
    // between them stays with the first), and neither is a differential's d or its variable.
    let may_cut_before = |i: usize| {
        let differential = (i >= 1 && is_d(&seg[i]) && is_space(&seg[i - 1]))
            || (i >= 2 && is_d(&seg[i - 1]) && is_space(&seg[i - 2]));
        let before = seg[..i].iter().rev().find(|n| !is_space(n));
        starts_a_factor(&seg[i]) && !differential && before.is_some_and(ends_a_factor)
    };
    let allowed: Vec<usize> = (1..seg.len()).filter(|&i| may_cut_before(i)).collect();
    let mut out = Vec::new();
    let mut start = 0;
    while width(&seg[start..]) > limit {
        // The last cut that keeps this piece within the line, else the first one after it.
        let dot = if start > 0 { 1.0 } else { 0.0 };
        let after: Vec<usize> = allowed.iter().copied().filter(|&i| i > start).collect();
        let fits = after
            .iter()
            .copied()
            .take_while(|&i| dot + width(&seg[start..i]) <= limit)
            .last();
        let Some(end) = fits.or(after.first().copied()) else {
            break;
        };
        out.push(seg[start..end].to_vec());
        start = end;
    }
    out.push(seg[start..].to_vec());
    for piece in out.iter_mut().skip(1) {
        piece.insert(
            0,
            Node::Atom(Content::BinaryOp {
                content: '⋅',
                small: false,
            }),
        );
    }
    out
}
