//! Long formulas broken into pieces a browser can wrap, on the read tree ([`Node`]). Chromium's
//! MathML does not break lines, so a formula wider than the page is cut into pieces at its sums,
//! equals signs and commas, each set as its own `<math>`; the browser wraps between them, on
//! screen and on paper. A long parenthesised sum opens into `\Bigl( … \Bigr)` around its terms;
//! a long numerator over a short denominator becomes the factor 1/d before it; a wide matrix
//! stacks its long cells.
//!
//! Each formula wider than a phone's line is also cut for a phone (`phone_pieces`): shorter
//! pieces, a long factor before a bracket on a piece of its own, a sentence between its words.
//!
//! Widths are estimated in characters of a typical formula: about 0.66 em each.

use super::latex::cells;
use super::latex::{Node, relation_text};
pub use super::width::width;
use super::width::{matrix, node_width, relation_is, table_width};
use pulldown_latex::event::{
    Content, DelimiterSize, DelimiterType, Dimension, DimensionUnit, EnvironmentFlow, Grouping,
    ScriptPosition, ScriptType, Visual,
};

/// A formula this wide is set as one block; wider ones are cut into pieces. Measured in Chromium,
/// a unit is about 0.66 em, and a step's text column (A4 less margins, or the screen's 52 rem,
/// less the list's indent and the pieces' hanging indent) about 64 units.
pub const LINE: f32 = 56.0;
/// A phone's line: 390 px less the margins and the list's indent, about 330 px. Formulas wider
/// than this are set a second time for small screens (render/math.rs).
pub const PHONE: f32 = 28.0;
/// On a phone a piece that cannot be cut is scaled down to fit, but never below this; a matrix
/// that would need more is recast as the tuple of its rows, which can wrap, and a product is
/// cut between its factors.
pub const SMALLEST: f32 = 0.85;

/// The scale that fits a phone's piece `w` wide to its line, unbounded (below 1 when it is
/// wider). It fits 90 % of the line, as the estimate runs short on matrices (measured in
/// Chromium: a 3×3 matrix about 15 %).
pub fn phone_scale(w: f32) -> f32 {
    0.9 * PHONE / w
}
/// A numerator or radicand wider than this is worth opening (a phone's line takes less).
const CELL: f32 = 20.0;
const PHONE_CELL: f32 = 10.0;
/// What stands before an opened bracket and is at most this wide stays on its first piece.
const SHORT_BEFORE: f32 = 8.0;

/// How wide a piece may be, and from what width a fraction or root is worth opening.
#[derive(Clone, Copy)]
struct Fit {
    limit: f32,
    cell: f32,
}

/// A binary +, −, ·, × or a relation =, ≈, <, >: where a sum or an equation may be cut.
fn is_operator(n: &Node) -> bool {
    match n {
        Node::Atom(Content::BinaryOp { content, .. }) => matches!(content, '+' | '−' | '⋅' | '×'),
        Node::Atom(Content::Relation { content, .. }) => {
            relation_is(content, &['=', '≈', '<', '>'])
        }
        _ => false,
    }
}

fn is_comma(n: &Node) -> bool {
    matches!(n, Node::Atom(Content::Punctuation(',')))
}

/// Cuts a sequence before each binary +, −, =, · and × and after each comma at its own level. Each
/// segment keeps its operator, so that the pieces read as the whole.
pub fn segments(nodes: &[Node]) -> Vec<Vec<Node>> {
    let mut out: Vec<Vec<Node>> = vec![Vec::new()];
    let mut previous: Option<&Node> = None;
    for n in nodes {
        let binary = is_operator(n)
            && previous.is_some_and(|p| {
                !(is_operator(p)
                    || is_comma(p)
                    || matches!(p, Node::Flow(EnvironmentFlow::Alignment)))
            });
        if binary && !out.last().unwrap().is_empty() {
            out.push(Vec::new());
        }
        out.last_mut().unwrap().push(n.clone());
        if is_comma(n) {
            out.push(Vec::new());
        }
        previous = Some(n);
    }
    out.retain(|s| !s.is_empty());
    out
}

fn has_cut(nodes: &[Node]) -> bool {
    segments(nodes).len() > 1
}

fn has_fraction(nodes: &[Node]) -> bool {
    nodes.iter().any(|n| match n {
        Node::Visual(Visual::Fraction(_), _) => true,
        Node::Group(_, v) | Node::Visual(_, v) | Node::Script { parts: v, .. } => has_fraction(v),
        _ => false,
    })
}

/// A bracket `\left( … \right)` worth opening: its content can be cut or opened in turn.
fn openable_bracket(n: &Node, cell: f32) -> Option<&[Node]> {
    match n {
        Node::Group(Grouping::LeftRight(Some('('), _), inner)
            if matrix(n).is_none() && (has_cut(inner) || opening(inner, cell).is_some()) =>
        {
            Some(inner)
        }
        _ => None,
    }
}

/// Where a segment can open: a parenthesised sum or list (with its power, if any), a fraction
/// or root with a long part, or a vector (a one-row or one-column matrix). Returns the widest
/// such node's index.
fn opening(seg: &[Node], cell: f32) -> Option<usize> {
    let mut best: Option<(usize, f32)> = None;
    for (i, n) in seg.iter().enumerate() {
        let w = match n {
            Node::Script { parts, .. } => match openable_bracket(&parts[0], cell) {
                Some(inner) => width(inner),
                None => continue,
            },
            Node::Group(Grouping::LeftRight(..), _) => {
                if let Some(inner) = openable_bracket(n, cell) {
                    width(inner)
                } else if let Some((_, body)) = matrix(n)
                    && vector_entries(body).is_some()
                {
                    table_width(body, true)
                } else {
                    continue;
                }
            }
            Node::Visual(Visual::SquareRoot, parts) => match &parts[0] {
                Node::Group(Grouping::Normal, radicand) if width(radicand) > cell => {
                    width(radicand)
                }
                _ => continue,
            },
            Node::Visual(Visual::Fraction(_), parts) => match (&parts[0], &parts[1]) {
                (Node::Group(Grouping::Normal, num), Node::Group(Grouping::Normal, den))
                    if width(num).max(width(den)) > cell =>
                {
                    width(num).max(width(den))
                }
                _ => continue,
            },
            _ => continue,
        };
        if best.is_none_or(|(_, b)| w > b) {
            best = Some((i, w));
        }
    }
    best.map(|(i, _)| i)
}

fn group(inner: Vec<Node>) -> Node {
    Node::Group(Grouping::Normal, inner)
}

/// `x^{e}`.
fn power(base: Node, exponent: Vec<Node>) -> Node {
    Node::Script {
        ty: ScriptType::Superscript,
        position: ScriptPosition::Right,
        parts: vec![base, group(exponent)],
    }
}

fn binary(c: char) -> Node {
    Node::Atom(Content::BinaryOp {
        content: c,
        small: false,
    })
}

fn number(s: &str) -> Node {
    Node::Number(s.into())
}

/// `\bigl(` or `\Bigl(`, and their closing partners.
fn delimiter(content: char, size: DelimiterSize, ty: DelimiterType) -> Node {
    Node::Atom(Content::Delimiter {
        content,
        size: Some(size),
        ty,
    })
}

/// A single element to which a power can be put as it is (`d^{-1}`); anything longer, or
/// carrying scripts of its own, is bracketed first.
fn takes_a_power(nodes: &[Node]) -> bool {
    match nodes {
        [Node::Number(s)] => s.chars().count() == 1,
        [Node::Atom(_) | Node::Function(_) | Node::Group(..)] => true,
        _ => false,
    }
}

/// A bracket's scripts, put on its closing bracket when it opens: `(…)^{2}`.
type Scripts = (ScriptType, ScriptPosition, Vec<Node>);

/// The pieces of one segment, opening its widest group while it is wider than `limit`.
fn open_segment(seg: Vec<Node>, fit: Fit) -> Vec<Vec<Node>> {
    if width(&seg) <= fit.limit {
        return vec![seg];
    }
    let Some(i) = opening(&seg, fit.cell) else {
        return super::product_cut::cut_product(seg, fit.limit);
    };
    let (before, rest) = seg.split_at(i);
    let (node, after) = (&rest[0], &rest[1..]);
    // The bracket's content, and the scripts on its closing bracket.
    let (inner, scripts): (Vec<Node>, Option<Scripts>) = match node {
        Node::Visual(Visual::SquareRoot, parts) => {
            // \sqrt{s} → (s)^{1/2}: a radical cannot break, a bracket can.
            let Node::Group(_, radicand) = &parts[0] else {
                return vec![seg];
            };
            let mut reshaped = before.to_vec();
            let half = vec![number("1"), binary('/'), number("2")];
            reshaped.push(power(bracket(radicand.clone()), half));
            reshaped.extend(after.iter().cloned());
            return open_segment(reshaped, fit);
        }
        Node::Visual(_, parts) => {
            let (Node::Group(_, num), Node::Group(_, den)) = (&parts[0], &parts[1]) else {
                return vec![seg];
            };
            let mut reshaped = before.to_vec();
            reshaped.extend(fraction_reshaped(num, den));
            reshaped.extend(after.iter().cloned());
            return open_segment(reshaped, fit);
        }
        Node::Script {
            ty,
            position,
            parts,
        } => {
            let Node::Group(_, inner) = &parts[0] else {
                return vec![seg];
            };
            (inner.clone(), Some((*ty, *position, parts[1..].to_vec())))
        }
        Node::Group(_, inner) => match matrix(node) {
            // A vector (a one-row or one-column matrix) as a tuple: its entries separated by
            // commas.
            Some((_, body)) => match vector_entries(body) {
                Some(entries) => (comma_separated(entries), None),
                None => (inner.clone(), None),
            },
            None => (inner.clone(), None),
        },
        _ => return vec![seg],
    };
    let size = if has_fraction(&inner) {
        DelimiterSize::BIG
    } else {
        DelimiterSize::Big
    };
    // A power stays on its bracket.
    let open = delimiter('(', size, DelimiterType::Open);
    let close = closing(size, scripts);
    // The content is cut to leave room on its first piece for the opening bracket, and for
    // a short factor before it (`A cos`), which stays with it.
    let short_before = width(before) <= SHORT_BEFORE;
    let room = fit.limit - node_width(&open) - if short_before { width(before) } else { 0.0 };
    let inner_fit = Fit {
        limit: room.max(fit.limit / 2.0),
        ..fit
    };
    let inner_pieces = pieces_of(&inner, inner_fit);
    placed(before, (open, inner_pieces, close), after, fit)
}

/// A fraction reshaped so that a bracket can break: \frac{n}{d} → \frac{1}{d} (n) when the
/// numerator is the wider, else n (d)^{-1}; a part that can be cut goes in brackets.
fn fraction_reshaped(num: &[Node], den: &[Node]) -> Vec<Node> {
    let bracketed_if_cut = |v: &[Node]| {
        if has_cut(v) {
            vec![bracket(v.to_vec())]
        } else {
            v.to_vec()
        }
    };
    let mut reshaped = Vec::new();
    if width(num) >= width(den) {
        // \frac{n}{d} → \frac{1}{d} (n): the numerator's terms can then wrap.
        reshaped.push(Node::Visual(
            Visual::Fraction(None),
            vec![group(vec![number("1")]), group(den.to_vec())],
        ));
        reshaped.extend(bracketed_if_cut(num));
    } else {
        // \frac{n}{d} → n (d)^{-1}, a sum n in brackets.
        if num != [number("1")] {
            reshaped.extend(bracketed_if_cut(num));
        }
        let base = if takes_a_power(den) {
            den[0].clone()
        } else {
            bracket(den.to_vec())
        };
        reshaped.push(power(base, vec![binary('−'), number("1")]));
    }
    reshaped
}

/// The closing bracket of `size`, carrying the scripts its content had.
fn closing(size: DelimiterSize, scripts: Option<Scripts>) -> Node {
    let close = delimiter(')', size, DelimiterType::Close);
    match scripts {
        Some((ty, position, scripts)) => {
            let mut parts = vec![close];
            parts.extend(scripts);
            Node::Script {
                ty,
                position,
                parts,
            }
        }
        None => close,
    }
}

/// The bracket's pieces with what stands before and after it: each on a piece of its own
/// (opened in turn) where it would make the bracket's first or last piece too wide.
fn placed(
    before: &[Node],
    (open, mut inner_pieces, close): (Node, Vec<Vec<Node>>, Node),
    after: &[Node],
    fit: Fit,
) -> Vec<Vec<Node>> {
    let last = inner_pieces.len() - 1;
    let after_width = width(after) + node_width(&close);
    let mut out = Vec::new();
    if !before.is_empty() && width(before) + node_width(&open) + width(&inner_pieces[0]) > fit.limit
    {
        out.extend(open_segment(before.to_vec(), fit));
        inner_pieces[0].insert(0, open);
    } else {
        let mut first = before.to_vec();
        first.push(open);
        first.append(&mut inner_pieces[0]);
        inner_pieces[0] = first;
    }
    if !after.is_empty() && after_width + width(&inner_pieces[last]) > fit.limit {
        inner_pieces[last].push(close);
        out.extend(inner_pieces);
        out.extend(open_segment(after.to_vec(), fit));
    } else {
        inner_pieces[last].push(close);
        inner_pieces[last].extend(after.iter().cloned());
        out.extend(inner_pieces);
    }
    out
}

fn pieces_of(nodes: &[Node], fit: Fit) -> Vec<Vec<Node>> {
    segments(nodes)
        .into_iter()
        .flat_map(|s| open_segment(s, fit))
        .filter(|s| !s.is_empty())
        .collect()
}

/// A matrix whose cells are long, with each long cell stacked on short lines (left-aligned,
/// later lines indented).
/// `room` is the widest a matrix may stay: the line, or more when the piece may be scaled down.
fn stack_cells(nodes: Vec<Node>, limit: f32, room: f32) -> Vec<Node> {
    nodes
        .into_iter()
        .map(|n| {
            if let Some((kind, body)) = matrix(&n)
                && cells(body).len() > 1
                && vector_entries(body).is_none()
            {
                let rows = cells(body);
                // The columns share a line, less room for a name and an equals sign.
                let columns = rows.iter().map(Vec::len).max().unwrap_or(1) as f32;
                // Each column: its gap (1.5) and the \quad of a continued line (2).
                let cell_width = ((limit - 6.0) / columns - 3.5).max(12.0);
                let mut body = Vec::new();
                for (r, row) in rows.iter().enumerate() {
                    if r > 0 {
                        body.push(new_line());
                    }
                    for (c, cell) in row.iter().enumerate() {
                        if c > 0 {
                            body.push(Node::Flow(EnvironmentFlow::Alignment));
                        }
                        body.extend(stacked(cell, cell_width));
                    }
                }
                if table_width(&body, true) <= room - 6.0 {
                    bracket(vec![Node::Group(kind.clone(), body)])
                } else {
                    // Too wide even stacked: the rows as a tuple of tuples, which can wrap.
                    as_tuples(&rows)
                }
            } else {
                match n {
                    Node::Group(Grouping::Normal, v) => group(stack_cells(v, limit, room)),
                    Node::Script {
                        ty,
                        position,
                        parts,
                    } => Node::Script {
                        ty,
                        position,
                        parts: stack_cells(parts, limit, room),
                    },
                    // A fraction's parts and a root's radicand, as groups.
                    Node::Visual(v, parts) => Node::Visual(v, stack_cells(parts, limit, room)),
                    other => other,
                }
            }
        })
        .collect()
}

fn new_line() -> Node {
    Node::Flow(EnvironmentFlow::NewLine {
        spacing: None,
        horizontal_lines: Box::new([]),
    })
}

/// A vector's entries: those of a one-row matrix, or of a one-column one (a column vector,
/// which a phone's line takes as a tuple that can wrap).
fn vector_entries(body: &[Node]) -> Option<Vec<Vec<Node>>> {
    let mut rows = cells(body);
    if rows.len() == 1 {
        return Some(rows.remove(0));
    }
    rows.iter()
        .all(|r| r.len() == 1)
        .then(|| rows.into_iter().map(|mut r| r.remove(0)).collect())
}

/// ((a, b), (c, d)): a matrix as the tuple of its rows, in brackets that open when wide.
fn as_tuples(rows: &[Vec<Vec<Node>>]) -> Node {
    let tuple = |items: Vec<Vec<Node>>| bracket(comma_separated(items));
    tuple(rows.iter().map(|r| vec![tuple(r.clone())]).collect())
}

/// `\left( … \right)` around `inner`.
fn bracket(inner: Vec<Node>) -> Node {
    Node::Group(Grouping::LeftRight(Some('('), Some(')')), inner)
}

/// a, b, c: the items with a comma between them.
fn comma_separated(items: Vec<Vec<Node>>) -> Vec<Node> {
    let mut out = Vec::new();
    for (k, item) in items.into_iter().enumerate() {
        if k > 0 {
            out.push(Node::Atom(Content::Punctuation(',')));
        }
        out.extend(item);
    }
    out
}

/// One cell on lines of at most `most` characters: an `aligned` table with each line aligned
/// at its start, the later ones indented by a quad.
fn stacked(cell: &[Node], most: f32) -> Vec<Node> {
    if width(cell) <= most {
        return cell.to_vec();
    }
    let mut lines: Vec<Vec<Node>> = Vec::new();
    for piece in pieces_of(
        cell,
        Fit {
            limit: most,
            cell: CELL,
        },
    ) {
        let w = width(&piece);
        match lines.last_mut() {
            Some(line) if width(line) + w <= most => line.extend(piece),
            _ => lines.push(piece),
        }
    }
    if lines.len() < 2 {
        return cell.to_vec();
    }
    let mut body = Vec::new();
    for (k, line) in lines.into_iter().enumerate() {
        if k > 0 {
            body.push(new_line());
        }
        body.push(Node::Flow(EnvironmentFlow::Alignment));
        if k > 0 {
            body.push(Node::Space(Some(Dimension::new(1.0, DimensionUnit::Em))));
        }
        body.extend(line);
    }
    vec![Node::Group(Grouping::Aligned, body)]
}

/// A phone's piece still too wide for its line that holds words in `\text{…}`: each word ends a
/// piece, so that the sentence wraps as prose does.
fn split_words(piece: Vec<Node>) -> Vec<Vec<Node>> {
    if width(&piece) <= PHONE {
        return vec![piece];
    }
    let mut out = Vec::new();
    let mut current: Vec<Node> = Vec::new();
    for n in piece {
        if let Node::Text(text) = &n
            && text != "&nbsp;"
            && text.trim().contains(' ')
        {
            for word in text.split_whitespace() {
                current.push(Node::Text(word.into()));
                out.push(std::mem::take(&mut current));
            }
            continue;
        }
        current.push(n);
    }
    out.push(current);
    out.retain(|p| !p.is_empty());
    out
}

/// A formula as the pieces to set: one piece when it is at most `limit` wide, else its pieces
/// at sums, equals signs and commas, long groups opened, long matrix cells stacked. Display
/// formulas take `LINE`; formulas within a sentence a shorter limit, as they start mid-line.
pub fn pieces(formula: &[Node], limit: f32) -> Vec<Vec<Node>> {
    let fit = Fit { limit, cell: CELL };
    pieces_within(formula, fit, limit)
}

/// A formula as the pieces to set on a phone's line: as `pieces`, with shorter numerators and
/// radicands opened, a matrix up to 1/SMALLEST of the line wide (its piece will be scaled
/// down), and a sentence in `\text` broken between its words.
pub fn phone_pieces(formula: &[Node]) -> Vec<Vec<Node>> {
    let fit = Fit {
        limit: PHONE,
        cell: PHONE_CELL,
    };
    pieces_within(formula, fit, PHONE / SMALLEST)
        .into_iter()
        .flat_map(split_words)
        .collect()
}

/// A piece after the first that starts with +, −, =, ·, × or ≈ keeps the spacing of a binary
/// operator: an empty group before it, else MathML and Typst set it as a sign.
pub fn set_apart(k: usize, piece: &[Node]) -> Vec<Node> {
    let operator = match piece.first() {
        Some(Node::Atom(Content::BinaryOp { content, .. })) => {
            matches!(content, '+' | '−' | '⋅' | '×')
        }
        Some(Node::Atom(Content::Relation { content, .. })) => {
            matches!(relation_text(content).as_str(), "=" | "≈")
        }
        _ => false,
    };
    let mut out = Vec::with_capacity(piece.len() + 1);
    if k > 0 && operator {
        out.push(Node::Group(Grouping::Normal, Vec::new()));
    }
    out.extend(piece.iter().cloned());
    out
}

fn pieces_within(formula: &[Node], fit: Fit, room: f32) -> Vec<Vec<Node>> {
    if width(formula) <= fit.limit {
        return vec![formula.to_vec()];
    }
    let nodes = stack_cells(formula.to_vec(), fit.limit, room);
    if width(&nodes) <= fit.limit {
        return vec![nodes];
    }
    pieces_of(&nodes, fit)
}
