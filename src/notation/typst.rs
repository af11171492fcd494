//! The read LaTeX tree ([`Tex`]) in Typst's math notation, for the PDFs: the same elements the
//! pages' MathML shows, so what loads prints in both. What Typst's math cannot set as the page
//! does (a colour) is refused, so scene validation names it at its line.

use super::latex::{Node, Tex, TexError, cells, relation_text};
use crate::base::typst::typst_string;
use pulldown_latex::event::{
    Content, DelimiterSize, DimensionUnit, Font, Grouping, ScriptPosition, ScriptType, StateChange,
    Style, Visual,
};

/// Operator names Typst's math knows by the same name; any other is `op("…")`.
pub const FUNCTIONS: &[&str] = &[
    "sin", "cos", "tan", "cot", "sec", "csc", "arcsin", "arccos", "arctan", "sinh", "cosh", "tanh",
    "coth", "exp", "ln", "log", "lg", "det", "dim", "ker", "deg", "arg", "gcd", "max", "min",
    "lim", "sup", "inf", "liminf", "limsup", "Pr",
];

impl Tex {
    pub fn to_typst(&self) -> Result<String, TexError> {
        let mut out = String::new();
        row(&self.nodes, false, &mut out)?;
        Ok(out.trim().to_string())
    }
}

/// LaTeX math (as between `$` signs) in Typst's math notation.
#[cfg(test)]
fn latex_to_typst(latex: &str) -> Result<String, TexError> {
    Tex::read(latex)?.to_typst()
}

/// A sequence of elements. `upright`: inside `\mathrm{…}`, where a run of letters is one
/// upright word (`"kg"`), not a product of italic letters.
fn row(nodes: &[Node], upright: bool, out: &mut String) -> Result<(), TexError> {
    let mut i = 0;
    while i < nodes.len() {
        let n = &nodes[i];
        if let Node::State(change) = n {
            // A change of font or style holds for the rest of its group.
            let (open, upright) = match change {
                StateChange::Font(font) => (font_function(*font), *font == Some(Font::UpRight)),
                StateChange::Style(style) => (style_function(*style), upright),
                StateChange::Color(_) => return Err(TexError::Unprintable("a colour")),
            };
            let mut inner = String::new();
            row(&nodes[i + 1..], upright, &mut inner)?;
            match open {
                // A switch with nothing after it in its group (`\rm` ending a cell) sets nothing.
                Some(f) if !inner.trim().is_empty() => push(out, &format!("{f}({})", inner.trim())),
                _ => push(out, inner.trim()),
            }
            return Ok(());
        }
        if upright && let Some(word) = letters(&nodes[i..]) {
            i += word.chars().count();
            push(out, &typst_string(&word));
            continue;
        }
        let piece = node(n, upright)?;
        push(out, &piece);
        i += 1;
    }
    Ok(())
}

/// The run of Latin letters that starts `nodes`, if any.
fn letters(nodes: &[Node]) -> Option<String> {
    let word: String = nodes
        .iter()
        .map_while(|n| match n {
            Node::Atom(Content::Ordinary { content, .. }) if content.is_ascii_alphabetic() => {
                Some(*content)
            }
            _ => None,
        })
        .collect();
    (!word.is_empty()).then_some(word)
}

fn font_function(font: Option<Font>) -> Option<&'static str> {
    font.map(|f| match f {
        Font::UpRight => "upright",
        Font::Bold | Font::BoldSymbol | Font::BoldItalic => "bold",
        Font::DoubleStruck | Font::DoubleStruckItalic => "bb",
        Font::Script | Font::BoldScript => "cal",
        Font::Fraktur | Font::BoldFraktur => "frak",
        Font::Italic => "italic",
        Font::Monospace => "mono",
        Font::SansSerif
        | Font::SansSerifBoldItalic
        | Font::SansSerifItalic
        | Font::BoldSansSerif => "sans",
    })
}

fn style_function(style: Style) -> Option<&'static str> {
    Some(match style {
        Style::Display => "display",
        Style::Text => "inline",
        Style::Script => "script",
        Style::ScriptScript => "sscript",
    })
}

/// One element in Typst.
fn node(n: &Node, upright: bool) -> Result<String, TexError> {
    Ok(match n {
        Node::Text(s) if s == "&nbsp;" => "space".into(),
        Node::Text(s) => typst_string(s),
        // `1,000`: a comma in a number would end a call's argument.
        Node::Number(s) => s.replace(',', "\\,"),
        Node::Function(f) if FUNCTIONS.contains(&f.as_str()) => f.clone(),
        Node::Function(f) => format!("op({})", typst_string(f)),
        Node::Atom(c) => atom(c),
        Node::Group(g, inner) => group(g, inner, upright)?,
        Node::Visual(v, parts) => {
            let part = |k: usize| operand(&parts[k], upright);
            match v {
                Visual::Fraction(_) => format!("frac({}, {})", part(0)?, part(1)?),
                Visual::SquareRoot => format!("sqrt({})", part(0)?),
                Visual::Root => format!("root({}, {})", part(1)?, part(0)?),
                Visual::Negation => negated(&parts[0], upright)?,
            }
        }
        Node::Script {
            ty,
            position,
            parts,
        } => script(*ty, *position, parts, upright)?,
        Node::Space(width) => space(*width),
        // Handled by `row`; a stray one sets nothing.
        Node::State(_) | Node::Flow(_) => String::new(),
    })
}

/// An element as a call's argument: its content, never empty.
fn operand(n: &Node, upright: bool) -> Result<String, TexError> {
    let mut out = String::new();
    match n {
        Node::Group(Grouping::Normal, inner) => row(inner, upright, &mut out)?,
        other => row(std::slice::from_ref(other), upright, &mut out)?,
    }
    let out = out.trim();
    Ok(if out.is_empty() {
        "\"\"".into()
    } else {
        out.to_string()
    })
}

fn atom(c: &Content<'static>) -> String {
    match *c {
        Content::Ordinary { content, .. } => match content {
            // A prime attaches to what stands before it.
            '′' => "'".into(),
            c => character(c),
        },
        Content::LargeOp { content, .. } => content.to_string(),
        Content::BinaryOp { content, .. } | Content::Punctuation(content) => character(content),
        Content::Relation { content, .. } => {
            relation_text(&content).chars().map(character).collect()
        }
        // `\Bigl(`: the delimiter at LaTeX's size for it, as the pages' MathML sets it.
        Content::Delimiter {
            content,
            size: Some(size),
            ..
        } => {
            let em = match size {
                DelimiterSize::Big => "1.2",
                DelimiterSize::BIG => "1.8",
                DelimiterSize::Bigg => "2.4",
                DelimiterSize::BIGG => "3",
            };
            format!("lr({}, size: #{em}em)", character(content))
        }
        Content::Delimiter { content, .. } => character(content),
        Content::Text(_) | Content::Number(_) | Content::Function(_) => String::new(),
    }
}

/// A character as itself. Every ASCII punctuation character is escaped, since Typst's math
/// reads much of it as syntax (`/` a fraction, `,` an argument's end, `(` a group, `"` a
/// string, `a:` a named argument, `<=` and `->` shorthands); an escaped one is set as the
/// character, with the same spacing.
fn character(c: char) -> String {
    if c.is_ascii_punctuation() {
        format!("\\{c}")
    } else {
        c.to_string()
    }
}

fn negated(n: &Node, upright: bool) -> Result<String, TexError> {
    if let Node::Atom(Content::Relation { content, .. }) = n {
        let negation = match relation_text(content).as_str() {
            "=" => Some('≠'),
            "<" => Some('≮'),
            ">" => Some('≯'),
            "≤" => Some('≰'),
            "≥" => Some('≱'),
            "∈" => Some('∉'),
            "≡" => Some('≢'),
            "∼" => Some('≁'),
            "≈" => Some('≉'),
            "⊂" => Some('⊄'),
            "∥" => Some('∦'),
            _ => None,
        };
        if let Some(c) = negation {
            return Ok(c.to_string());
        }
    }
    Ok(format!("cancel({})", operand(n, upright)?))
}

fn script(
    ty: ScriptType,
    position: ScriptPosition,
    parts: &[Node],
    upright: bool,
) -> Result<String, TexError> {
    let base = operand(&parts[0], upright)?;
    let (sub, sup) = match ty {
        ScriptType::Subscript => (Some(&parts[1]), None),
        ScriptType::Superscript => (None, Some(&parts[1])),
        ScriptType::SubSuperscript => (Some(&parts[1]), Some(&parts[2])),
    };
    // A lone mark over or under the base: an accent, a line or a brace.
    let mark = match (sub, sup) {
        (None, Some(Node::Atom(Content::Ordinary { content, .. }))) => Some((false, *content)),
        (Some(Node::Atom(Content::Ordinary { content, .. })), None) => Some((true, *content)),
        _ => None,
    };
    if position == ScriptPosition::AboveBelow
        && let Some((under, mark)) = mark
        && let Some(marked) = marked(&base, under, mark)
    {
        return Ok(marked);
    }
    let base = match position {
        ScriptPosition::AboveBelow => format!("limits({base})"),
        ScriptPosition::Right if matches!(parts[0], Node::Atom(Content::LargeOp { .. })) => {
            format!("scripts({base})")
        }
        _ => base,
    };
    let mut out = format!("attach({base}");
    if let Some(s) = sub {
        out.push_str(&format!(", b: {}", operand(s, upright)?));
    }
    if let Some(s) = sup {
        out.push_str(&format!(", t: {}", operand(s, upright)?));
    }
    out.push(')');
    Ok(out)
}

/// The base with the mark pulldown-latex puts over (or `under`) it, in Typst.
fn marked(base: &str, under: bool, mark: char) -> Option<String> {
    let accent = match (under, mark) {
        (true, '⏟') => return Some(format!("underbrace({base})")),
        (false, '⏞') => return Some(format!("overbrace({base})")),
        (false, '‾' | '¯') => return Some(format!("overline({base})")),
        (true, _) => return None,
        (false, '→') => "arrow",
        (false, '←') => "arrow.l",
        (false, '↔') => "arrow.l.r",
        (false, '˙') => "dot",
        (false, '¨') => "dot.double",
        (false, '^' | 'ˆ') => "hat",
        (false, '~' | '˜') => "tilde",
        (false, 'ˇ') => "caron",
        (false, '´') => "acute",
        (false, '`') => "grave",
        (false, '˘') => "breve",
        _ => return None,
    };
    Some(format!("accent({base}, {accent})"))
}

fn group(g: &Grouping, inner: &[Node], upright: bool) -> Result<String, TexError> {
    Ok(match g {
        Grouping::Normal => {
            let mut out = String::new();
            row(inner, upright, &mut out)?;
            out
        }
        Grouping::LeftRight(open, close) => {
            // A matrix's brackets are the matrix's own.
            if let [Node::Group(Grouping::Matrix { .. }, body)] = inner {
                let delim = match (open, close) {
                    (Some('('), _) => "",
                    (Some('['), _) => "delim: \"[\", ",
                    (Some('{'), _) => "delim: \"{\", ",
                    (Some('|'), _) => "delim: \"|\", ",
                    (Some('‖' | '∥'), _) => "delim: \"‖\", ",
                    _ => "delim: #none, ",
                };
                return Ok(format!("mat({delim}{})", rows(body, "; ", ", ", upright)?));
            }
            let mut out = String::from("lr(");
            if let Some(c) = open {
                out.push_str(&character(*c));
            }
            row(inner, upright, &mut out)?;
            if let Some(c) = close {
                push(&mut out, &character(*c));
            }
            out.push(')');
            out
        }
        Grouping::Matrix { .. } | Grouping::Array(_) => {
            format!("mat(delim: #none, {})", rows(inner, "; ", ", ", upright)?)
        }
        Grouping::Cases { left } => format!(
            "cases({}{})",
            if *left { "" } else { "reverse: #true, " },
            // LaTeX sets a quad between a case's value and its condition.
            rows(inner, ", ", "&quad ", upright)?
        ),
        // The equation environments: lines and alignment points, as Typst writes them.
        _ => rows(inner, " \\ ", " & ", upright)?,
    })
}

/// An environment's content: its rows (split at `\\`) joined by `row_sep`, each row's cells
/// (split at `&`) by `cell_sep`.
fn rows(body: &[Node], row_sep: &str, cell_sep: &str, upright: bool) -> Result<String, TexError> {
    let mut table = cells(body);
    if table.len() > 1
        && table
            .last()
            .is_some_and(|r| r.len() == 1 && r[0].is_empty())
    {
        table.pop();
    }
    let mut lines = Vec::with_capacity(table.len());
    for r in &table {
        let mut cells = Vec::with_capacity(r.len());
        for cell in r {
            // A cell is one group: a switch (`\rm`) holds to its end.
            let mut out = String::new();
            row(cell, upright, &mut out)?;
            cells.push(out.trim().to_string());
        }
        lines.push(cells.join(cell_sep));
    }
    Ok(lines.join(row_sep))
}

/// A space of the given width: Typst's own spaces where LaTeX's are (`\,` thin, `\:` med,
/// `\;` thick, `\quad`, `\qquad` wide), else `h`, ended by `;` so that nothing after it
/// continues the call.
fn space(width: Option<pulldown_latex::event::Dimension>) -> String {
    let Some(d) = width else {
        return String::new();
    };
    let (value, unit) = match d.unit {
        DimensionUnit::Em => (d.value, "em"),
        DimensionUnit::Mu => (d.value / 18.0, "em"),
        DimensionUnit::Ex => (d.value * 0.5, "em"),
        DimensionUnit::Pt | DimensionUnit::Bp | DimensionUnit::Dd => (d.value, "pt"),
        DimensionUnit::Sp => (d.value / 65536.0, "pt"),
        DimensionUnit::Pc | DimensionUnit::Cc => (d.value * 12.0, "pt"),
        DimensionUnit::In => (d.value, "in"),
        DimensionUnit::Cm => (d.value, "cm"),
        DimensionUnit::Mm => (d.value, "mm"),
    };
    let named = [
        (1.0 / 6.0, "thin"),
        (2.0 / 9.0, "med"),
        (5.0 / 18.0, "thick"),
        (1.0, "quad"),
        (2.0, "wide"),
    ];
    if unit == "em"
        && let Some((_, name)) = named.iter().find(|(w, _)| (w - value).abs() < 1e-4)
    {
        return name.to_string();
    }
    let value = format!("{value:.4}");
    let value = value.trim_end_matches('0').trim_end_matches('.');
    format!("#h({value}{unit});")
}

/// Appends a piece, with a space only where two pieces would read as one: two names, or two
/// operators that Typst reads as one (`-` and `>` as an arrow). Never beside a string: in
/// Typst's math a space there is set as a space.
fn push(out: &mut String, piece: &str) {
    let (Some(last), Some(first)) = (out.chars().last(), piece.chars().next()) else {
        out.push_str(piece);
        return;
    };
    let word = |c: char| c.is_alphanumeric();
    let operator = |c: char| c.is_ascii_punctuation() && !"\"()[]{}\\#;'".contains(c);
    if ((word(last) || last == ')') && word(first)) || (operator(last) && operator(first)) {
        out.push(' ');
    }
    out.push_str(piece);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(latex: &str) -> String {
        let s = latex_to_typst(latex).unwrap_or_else(|e| panic!("{latex}: {e}"));
        s.split_whitespace().collect::<Vec<_>>().join(" ")
    }

    /// `\Bigl(` keeps LaTeX's size in the PDF (it was set at the body's size).
    #[test]
    fn a_sized_bracket_keeps_its_size() {
        assert_eq!(
            t(r"\Bigl( b \Bigr) \bigl[ c \bigr]"),
            r"lr(\(, size: #1.8em) b lr(\), size: #1.8em) lr(\[, size: #1.2em) c lr(\], size: #1.2em)"
        );
    }

    #[test]
    fn letters_greek_and_accents() {
        assert_eq!(t("ab"), "a b");
        assert_eq!(t("\\omega_{x}"), "attach(ω, b: x)");
        assert_eq!(t("\\vec{\\omega}"), "accent(ω, arrow)");
        assert_eq!(
            t("\\dot{x} \\ddot\\theta"),
            "accent(x, dot) accent(θ, dot.double)"
        );
        assert_eq!(t("\\overleftrightarrow{I}"), "accent(I, arrow.l.r)");
        assert_eq!(t("\\Omega f'"), "Ω f'");
    }

    #[test]
    fn fractions_units_text_and_matrices() {
        assert_eq!(t("\\frac{1}{2} m"), "frac(1, 2) m");
        assert_eq!(
            t("g = 9.81\\,\\mathrm{m/s^2}"),
            "g\\=9.81 thin upright(\"m\"\\/attach(\"s\", t: 2))"
        );
        assert_eq!(
            t("\\mathrm{kg\\,m^2}"),
            "upright(\"kg\"thin attach(\"m\", t: 2))"
        );
        assert_eq!(t("R^{\\mathrm{cm}}"), "attach(R, t: upright(\"cm\"))");
        assert_eq!(t("\\text{every axis}"), "\"every axis\"");
        assert_eq!(
            t("\\begin{pmatrix}a & b \\\\ c & d\\end{pmatrix}"),
            "mat(a, b; c, d)"
        );
        assert_eq!(t("\\left(x\\right)^{2}"), "attach(lr(\\(x\\)), t: 2)");
        assert_eq!(t("f(x, y)"), "f\\(x\\,y\\)");
        assert_eq!(
            t("\\sum_{i} \\int_0^1"),
            "attach(∑, b: i) attach(scripts(∫), b: 0, t: 1)"
        );
        assert_eq!(t("\\sqrt[3]{x} \\not= y"), "root(3, x)≠y");
    }

    #[test]
    fn what_an_author_writes_cannot_close_a_call_or_lose_a_base() {
        // A lone `)` is a character, never the end of the call it is printed in.
        assert_eq!(t("\\sqrt{)}"), "sqrt(\\))");
        assert_eq!(t("\\frac{(}{)}"), "frac(\\(, \\))");
        // A ratio at the start of an argument is a character, never a named argument.
        assert_eq!(t("\\frac{a:b}{c}"), "frac(a\\:b, c)");
        assert_eq!(t("\\vec{x:y}"), "accent(x\\:y, arrow)");
        assert_eq!(t("\\begin{pmatrix}a:b & c\\end{pmatrix}"), "mat(a\\:b, c)");
        // Two characters stay two: no shorthand (`<=` is ≤ in Typst, two signs in LaTeX).
        assert_eq!(t("a<=b -> c"), "a\\<\\=b−\\>c");
        // A power with no base gets an empty one (`m/s$^2$`).
        assert_eq!(t("^2"), "attach(\"\", t: 2)");
    }

    #[test]
    fn a_colour_is_refused() {
        assert_eq!(
            latex_to_typst("\\color{red} x"),
            Err(TexError::Unprintable("a colour"))
        );
    }
}
