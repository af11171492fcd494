//! Long formulas broken into pieces a browser can wrap. Chromium's MathML does not break lines,
//! so a formula wider than the page is cut into pieces at its sums, equals signs and commas, each
//! set as its own `<math>`; the browser wraps between them, on screen and on paper. A long
//! parenthesised sum opens into `\Bigl( … \Bigr)` around its terms; a long numerator over a
//! short denominator becomes the factor 1/d before it; a wide matrix stacks its long cells.
//!
//! Each formula wider than a phone's line is also cut for a phone (`phone_pieces`): shorter
//! pieces, a long factor before a bracket on a piece of its own, a sentence between its words.
//!
//! Widths are estimated in characters of a typical formula: about 0.66 em each.

use super::latex_tree::tok;
pub(super) use super::latex_tree::{Node, latex, tree};

/// A formula this wide is set as one block; wider ones are cut into pieces. Measured in Chromium,
/// a unit is about 0.66 em, and a step's text column (A4 less margins, or the screen's 52 rem,
/// less the list's indent and the pieces' hanging indent) about 64 units.
pub const LINE: f32 = 56.0;
/// A phone's line: 390 px less the margins and the list's indent, about 330 px. Formulas wider
/// than this are set a second time for small screens (render/math.rs).
pub const PHONE: f32 = 28.0;
/// On a phone a piece that cannot be cut is scaled down to fit, but never below this; a matrix
/// that would need more is recast as the tuple of its rows, which can wrap.
pub const SMALLEST: f32 = 0.7;
/// A numerator or radicand wider than this is worth opening (a phone's line takes less).
const CELL: f32 = 20.0;
const PHONE_CELL: f32 = 10.0;

/// How wide a piece may be, and from what width a fraction or root is worth opening.
#[derive(Clone, Copy)]
struct Fit {
    limit: f32,
    cell: f32,
}

/// The estimated width of a sequence of nodes, in characters.
pub(super) fn width(nodes: &[Node]) -> f32 {
    let mut w = 0.0;
    let mut i = 0;
    while i < nodes.len() {
        let n = &nodes[i];
        let script = i > 0 && matches!(tok(&nodes[i - 1]), Some("^" | "_"));
        w += match n {
            Node::Tok(t) => match t.as_str() {
                "\\frac" => {
                    let part = |k: usize| match nodes.get(i + k) {
                        Some(Node::Group(v)) => width(v),
                        Some(other) => width(std::slice::from_ref(other)),
                        None => 0.0,
                    };
                    let w = part(1).max(part(2)) + 0.5;
                    i += 2;
                    w
                }
                "\\text" | "\\mathrm" | "\\operatorname" | "\\mathbb" => {
                    let w = match nodes.get(i + 1) {
                        Some(Node::Group(v)) => latex(v).chars().count() as f32,
                        _ => 1.0,
                    };
                    i += 1;
                    w
                }
                "+" | "-" | "=" | "<" | ">" | "\\approx" | "\\perp" | "\\times" => 2.0,
                "\\sin" | "\\cos" | "\\det" | "\\tan" => 4.0,
                "\\quad" => 2.0,
                "\\;"
                | "\\,"
                | "\\left"
                | "\\right"
                | "\\vec"
                | "\\dot"
                | "\\ddot"
                | "^"
                | "_"
                | "{"
                | "}"
                | "&"
                | "\\\\"
                | "\\overleftrightarrow" => 0.0,
                " " => 0.0,
                "," => 1.0,
                t if t.starts_with('\\') => 1.0,
                t => t.chars().count() as f32,
            },
            Node::Group(v) => width(v) * if script { 0.7 } else { 1.0 },
            Node::Delim { inner, .. } => width(inner) + 1.0,
            Node::Env { name, body } => env_width(name, body),
        };
        i += 1;
    }
    w
}

/// Rows (split at `\\`) of cells (split at `&`).
fn cells(body: &[Node]) -> Vec<Vec<Vec<Node>>> {
    let mut rows = vec![vec![Vec::new()]];
    for n in body {
        match tok(n) {
            Some("\\\\") => rows.push(vec![Vec::new()]),
            Some("&") => rows.last_mut().unwrap().push(Vec::new()),
            _ => rows.last_mut().unwrap().last_mut().unwrap().push(n.clone()),
        }
    }
    rows
}

/// A matrix's columns with their gaps; `aligned` (our stacked cells) has none.
fn env_width(name: &str, body: &[Node]) -> f32 {
    let (gap, sides) = if name == "aligned" {
        (0.0, 0.0)
    } else {
        (1.5, 1.0)
    };
    let rows = cells(body);
    let columns = rows.iter().map(Vec::len).max().unwrap_or(0);
    let widest = |j: usize| {
        rows.iter()
            .filter_map(|r| r.get(j))
            .map(|c| width(c))
            .fold(0.0, f32::max)
    };
    (0..columns).map(|j| widest(j) + gap).sum::<f32>() + sides
}

fn is_operator(t: &str) -> bool {
    matches!(
        t,
        "+" | "-" | "=" | "\\approx" | "<" | ">" | "\\cdot" | "\\times"
    )
}

/// Cuts a sequence before each binary +, −, =, · and × and after each comma at its own level. Each
/// segment keeps its operator, so that the pieces read as the whole.
pub(super) fn segments(nodes: &[Node]) -> Vec<Vec<Node>> {
    let mut out: Vec<Vec<Node>> = vec![Vec::new()];
    let mut previous: Option<&Node> = None; // the last node that is not a space
    for n in nodes {
        let t = tok(n);
        let binary = t.is_some_and(is_operator)
            && previous.is_some_and(|p| {
                !tok(p).is_some_and(|p| is_operator(p) || matches!(p, "^" | "_" | "," | "&"))
            });
        if binary && !out.last().unwrap().is_empty() {
            out.push(Vec::new());
        }
        out.last_mut().unwrap().push(n.clone());
        if t == Some(",") {
            out.push(Vec::new());
        }
        if t != Some(" ") {
            previous = Some(n);
        }
    }
    out.retain(|s| s.iter().any(|n| tok(n) != Some(" ")));
    out
}

fn has_cut(nodes: &[Node]) -> bool {
    segments(nodes).len() > 1
}

fn has_fraction(nodes: &[Node]) -> bool {
    nodes.iter().any(|n| match n {
        Node::Tok(t) => t == "\\frac",
        Node::Group(v) | Node::Delim { inner: v, .. } | Node::Env { body: v, .. } => {
            has_fraction(v)
        }
    })
}

/// Where a segment can open: a parenthesised sum or list, a fraction with a long numerator, or
/// a one-row matrix (a vector). Returns the widest such node's index.
fn opening(seg: &[Node], cell: f32) -> Option<usize> {
    let mut best: Option<(usize, f32)> = None;
    for (i, n) in seg.iter().enumerate() {
        let w = match n {
            Node::Delim { open, inner, .. }
                if open == "\\left(" && (has_cut(inner) || opening(inner, cell).is_some()) =>
            {
                width(inner)
            }
            Node::Tok(t) if t == "\\sqrt" => match seg.get(i + 1) {
                Some(Node::Group(num)) if width(num) > cell => width(num),
                _ => continue,
            },
            Node::Tok(t) if t == "\\frac" => match (seg.get(i + 1), seg.get(i + 2)) {
                (Some(Node::Group(num)), Some(Node::Group(den)))
                    if width(num).max(width(den)) > cell =>
                {
                    width(num).max(width(den))
                }
                _ => continue,
            },
            Node::Env { name, body } if name == "pmatrix" && cells(body).len() == 1 => {
                env_width(name, body)
            }
            _ => continue,
        };
        if best.is_none_or(|(_, b)| w > b) {
            best = Some((i, w));
        }
    }
    best.map(|(i, _)| i)
}

/// The pieces of one segment, opening its widest group while it is wider than `limit`.
fn open_segment(seg: Vec<Node>, fit: Fit) -> Vec<String> {
    if width(&seg) <= fit.limit {
        return vec![latex(&seg)];
    }
    let Some(i) = opening(&seg, fit.cell) else {
        return vec![latex(&seg)];
    };
    let (before, rest) = seg.split_at(i);
    let (node, after) = (&rest[0], &rest[1..]);
    let (inner, after): (Vec<Node>, &[Node]) = match node {
        Node::Tok(t) if t == "\\sqrt" => {
            // \sqrt{s} → (s)^{1/2}: a radical cannot break, a bracket can.
            let Some(Node::Group(radicand)) = rest.get(1) else {
                return vec![latex(&seg)];
            };
            let mut reshaped = before.to_vec();
            reshaped.push(bracket(radicand.clone()));
            reshaped.extend(tree("^{1/2}"));
            reshaped.extend(rest[2..].iter().cloned());
            return open_segment(reshaped, fit);
        }
        Node::Tok(_) => {
            let (Some(Node::Group(num)), Some(Node::Group(den))) = (rest.get(1), rest.get(2))
            else {
                return vec![latex(&seg)];
            };
            let bracketed_if_cut = |v: &[Node]| {
                if has_cut(v) {
                    vec![bracket(v.to_vec())]
                } else {
                    v.to_vec()
                }
            };
            let mut reshaped = before.to_vec();
            if width(num) >= width(den) {
                // \frac{n}{d} → \frac{1}{d} (n): the numerator's terms can then wrap.
                reshaped.extend(tree("\\frac{1}"));
                reshaped.push(Node::Group(den.clone()));
                reshaped.extend(bracketed_if_cut(num));
            } else {
                // \frac{n}{d} → n (d)^{-1}, a sum n in brackets.
                if latex(num).trim() != "1" {
                    reshaped.extend(bracketed_if_cut(num));
                }
                // More than one atom takes a bracket before its power: `R^{2}` or a root that
                // opens into (s)^{1/2} would otherwise get a second superscript.
                if den.len() > 1 {
                    reshaped.push(bracket(den.clone()));
                } else {
                    reshaped.extend(den.iter().cloned());
                }
                reshaped.extend(tree("^{-1}"));
            }
            reshaped.extend(rest[3..].iter().cloned());
            return open_segment(reshaped, fit);
        }
        Node::Delim { inner, .. } => (inner.clone(), after),
        Node::Env { body, .. } => {
            // A vector (a one-row matrix) as a tuple: its entries separated by commas.
            (comma_separated(cells(body).remove(0)), after)
        }
        Node::Group(_) => return vec![latex(&seg)],
    };
    let big = if has_fraction(&inner) { "Big" } else { "big" };
    let mut inner_pieces = pieces_of(&inner, fit);
    let last = inner_pieces.len() - 1;
    // What stands before the bracket, and after it, goes on a piece of its own (opened in
    // turn) when it would make the bracket's first or last piece too wide; a power stays on
    // its bracket.
    let scripts = after
        .iter()
        .position(|n| !matches!(tok(n), Some("^" | "_")) && !matches!(n, Node::Group(_)))
        .unwrap_or(after.len());
    let (power, rest) = after.split_at(scripts);
    let mut out = Vec::new();
    let wide = |a: &[Node], piece: &str| width(a) + width(&tree(piece)) > fit.limit;
    if !before.is_empty() && wide(before, &inner_pieces[0]) {
        out.extend(open_segment(before.to_vec(), fit));
        inner_pieces[0] = format!("\\{big}l({}", inner_pieces[0]);
    } else {
        inner_pieces[0] = format!("{}\\{big}l({}", latex(before), inner_pieces[0]);
    }
    if !rest.is_empty() && wide(after, &inner_pieces[last]) {
        inner_pieces[last] = format!("{}\\{big}r){}", inner_pieces[last], latex(power));
        out.extend(inner_pieces);
        out.extend(open_segment(rest.to_vec(), fit));
    } else {
        inner_pieces[last] = format!("{}\\{big}r){}", inner_pieces[last], latex(after));
        out.extend(inner_pieces);
    }
    out
}

fn pieces_of(nodes: &[Node], fit: Fit) -> Vec<String> {
    segments(nodes)
        .into_iter()
        .flat_map(|s| open_segment(s, fit))
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .collect()
}

/// A matrix whose cells are long, with each long cell stacked on short lines (left-aligned,
/// later lines indented).
/// `room` is the widest a matrix may stay: the line, or more when the piece may be scaled down.
fn stack_cells(nodes: Vec<Node>, limit: f32, room: f32) -> Vec<Node> {
    nodes
        .into_iter()
        .map(|n| match n {
            Node::Env { name, body } if name == "pmatrix" && cells(&body).len() > 1 => {
                let rows = cells(&body);
                // The columns share a line, less room for a name and an equals sign.
                let columns = rows.iter().map(Vec::len).max().unwrap_or(1) as f32;
                // Each column: its gap (1.5) and the \quad of a continued line (2).
                let cell_width = ((limit - 6.0) / columns - 3.5).max(12.0);
                let mut out = String::new();
                for (r, row) in rows.iter().enumerate() {
                    if r > 0 {
                        out.push_str(" \\\\ ");
                    }
                    for (c, cell) in row.iter().enumerate() {
                        if c > 0 {
                            out.push_str(" & ");
                        }
                        out.push_str(&stacked(cell, cell_width));
                    }
                }
                let body = tree(&out);
                if env_width(&name, &body) <= room - 6.0 {
                    Node::Env { name, body }
                } else {
                    // Too wide even stacked: the rows as a tuple of tuples, which can wrap.
                    as_tuples(&rows)
                }
            }
            Node::Group(v) => Node::Group(stack_cells(v, limit, room)),
            other => other,
        })
        .collect()
}

/// ((a, b), (c, d)): a matrix as the tuple of its rows, in brackets that open when wide.
fn as_tuples(rows: &[Vec<Vec<Node>>]) -> Node {
    let tuple = |items: Vec<Vec<Node>>| bracket(comma_separated(items));
    tuple(rows.iter().map(|r| vec![tuple(r.clone())]).collect())
}

/// `\left( … \right)` around `inner`.
fn bracket(inner: Vec<Node>) -> Node {
    Node::Delim {
        open: "\\left(".into(),
        inner,
        close: "\\right)".into(),
    }
}

/// a, b, c: the items with a comma and a space between them.
fn comma_separated(items: Vec<Vec<Node>>) -> Vec<Node> {
    let mut out = Vec::new();
    for (k, item) in items.into_iter().enumerate() {
        if k > 0 {
            out.push(Node::Tok(",".into()));
            out.push(Node::Tok(" ".into()));
        }
        out.extend(item);
    }
    out
}

/// One cell on lines of at most `most` characters: `\begin{aligned}` with `&` at each line's
/// start.
fn stacked(cell: &[Node], most: f32) -> String {
    if width(cell) <= most {
        return latex(cell);
    }
    let mut lines: Vec<String> = Vec::new();
    for piece in pieces_of(
        cell,
        Fit {
            limit: most,
            cell: CELL,
        },
    ) {
        let w = width(&tree(&piece));
        match lines.last_mut() {
            Some(line) if width(&tree(line)) + w <= most => {
                line.push(' ');
                line.push_str(&piece);
            }
            _ => lines.push(piece),
        }
    }
    if lines.len() < 2 {
        return latex(cell);
    }
    let body: Vec<String> = lines
        .iter()
        .enumerate()
        .map(|(k, l)| {
            if k == 0 {
                format!("&{l}")
            } else {
                format!("&\\quad {l}")
            }
        })
        .collect();
    format!("\\begin{{aligned}}{}\\end{{aligned}}", body.join(" \\\\ "))
}

/// A phone's piece still too wide for its line that holds words in `\text{…}`: each word ends a
/// piece, so that the sentence wraps as prose does.
fn split_words(piece: String) -> Vec<String> {
    if width_of(&piece) <= PHONE {
        return vec![piece];
    }
    let nodes = tree(&piece);
    let mut out = Vec::new();
    let mut current: Vec<Node> = Vec::new();
    let mut i = 0;
    while i < nodes.len() {
        if let (Some("\\text"), Some(Node::Group(g))) = (tok(&nodes[i]), nodes.get(i + 1)) {
            let text = latex(g);
            if !text.contains(['{', '}', '\\']) && text.trim().contains(' ') {
                for word in text.split_whitespace() {
                    current.extend(tree(&format!("\\text{{{word}}}")));
                    out.push(latex(&current).trim().to_string());
                    current.clear();
                }
                i += 2;
                continue;
            }
        }
        current.push(nodes[i].clone());
        i += 1;
    }
    out.push(latex(&current).trim().to_string());
    out.retain(|p| !p.is_empty());
    out
}

/// The estimated width of a formula, in characters.
pub fn width_of(formula: &str) -> f32 {
    width(&tree(formula))
}

/// A formula as the pieces to set: one piece when it is at most `limit` wide, else its pieces
/// at sums, equals signs and commas, long groups opened, long matrix cells stacked. Display
/// formulas take `LINE`; formulas within a sentence a shorter limit, as they start mid-line.
pub fn pieces(formula: &str, limit: f32) -> Vec<String> {
    let fit = Fit { limit, cell: CELL };
    pieces_within(formula, fit, limit)
}

/// A formula as the pieces to set on a phone's line: as `pieces`, with shorter numerators and
/// radicands opened, a matrix up to 1/SMALLEST of the line wide (its piece will be scaled
/// down), and a sentence in `\text` broken between its words.
pub fn phone_pieces(formula: &str) -> Vec<String> {
    let fit = Fit {
        limit: PHONE,
        cell: PHONE_CELL,
    };
    pieces_within(formula, fit, PHONE / SMALLEST)
        .into_iter()
        .flat_map(split_words)
        .collect()
}

fn pieces_within(formula: &str, fit: Fit, room: f32) -> Vec<String> {
    let nodes = tree(formula);
    if width(&nodes) <= fit.limit {
        return vec![formula.to_string()];
    }
    let nodes = stack_cells(nodes, fit.limit, room);
    if width(&nodes) <= fit.limit {
        return vec![latex(&nodes)];
    }
    pieces_of(&nodes, fit)
}
