//! The read LaTeX tree ([`Tex`]) in Typst's math notation, for the PDFs: the same elements the
//! pages' MathML shows, so what loads prints in both. What Typst's math cannot set as the page
//! does (a colour) is refused, so scene validation names it at its line.

use super::latex::{Node, Tex, TexError, cells, relation_text};
use crate::base::literal::typst_string;
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
        row(&self.nodes, Place::default(), &mut out)?;
        Ok(out.trim().to_string())
    }
}

/// Where an element stands, for what paper sets differently from a screen.
#[derive(Clone, Copy, Default)]
struct Place {
    /// Inside `\mathrm{…}`, where a run of letters is one upright word (`"kg"`), not a
    /// product of italic letters.
    upright: bool,
    /// In a fraction's part or a script, where a fraction goes on the line (`3\/2`), as
    /// textbooks write it: stacked, it would be set at half the body's size.
    on_the_line: bool,
    /// In a script, where a script of its own is kept at the script's size (`script(2)`):
    /// a script's script is half the body, too small to read on paper.
    in_script: bool,
}

impl Place {
    fn upright(self, upright: bool) -> Place {
        Place { upright, ..self }
    }
    fn on_the_line(self) -> Place {
        Place {
            on_the_line: true,
            ..self
        }
    }
    fn in_script(self) -> Place {
        Place {
            on_the_line: true,
            in_script: true,
            ..self
        }
    }
}

/// LaTeX math (as between `$` signs) in Typst's math notation.
#[cfg(test)]
fn latex_to_typst(latex: &str) -> Result<String, TexError> {
    Tex::read(latex)?.to_typst()
}

/// A sequence of elements.
fn row(nodes: &[Node], place: Place, out: &mut String) -> Result<(), TexError> {
    let mut i = 0;
    while i < nodes.len() {
        let n = &nodes[i];
        if let Node::State(change) = n {
            // A change of font or style holds for the rest of its group.
            let (open, upright) = match change {
                StateChange::Font(font) => (font_function(*font), *font == Some(Font::UpRight)),
                StateChange::Style(style) => (style_function(*style), place.upright),
                StateChange::Color(_) => return Err(TexError::Unprintable("a colour")),
            };
            let mut inner = String::new();
            row(&nodes[i + 1..], place.upright(upright), &mut inner)?;
            match open {
                // A switch with nothing after it in its group (`\rm` ending a cell) sets nothing.
                Some(f) if !inner.trim().is_empty() => push(out, &format!("{f}({})", inner.trim())),
                _ => push(out, inner.trim()),
            }
            return Ok(());
        }
        if place.upright
            && let Some(word) = letters(&nodes[i..])
        {
            i += word.chars().count();
            push(out, &typst_string(&word));
            continue;
        }
        if spaced_by_typst(&nodes[i..]) {
            i += 1;
            continue;
        }
        let piece = node(n, place)?;
        push(out, &piece);
        i += 1;
    }
    Ok(())
}

/// A thin space that Typst sets itself: before an operator's name with a power (`{\sin}^2`,
/// whose braces make LaTeX need it), or before a prime.
fn spaced_by_typst(nodes: &[Node]) -> bool {
    let [Node::Space(Some(d)), next, ..] = nodes else {
        return false;
    };
    let thin = d.unit == DimensionUnit::Em && (d.value - 1.0 / 6.0).abs() < 1e-4;
    let named_power = matches!(next, Node::Script { parts, .. }
        if matches!(parts.first(), Some(Node::Group(Grouping::Normal, g))
            if matches!(g.as_slice(), [Node::Function(_)])));
    let prime = matches!(next, Node::Atom(Content::Ordinary { content: '′', .. }));
    thin && (named_power || prime)
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
fn node(n: &Node, place: Place) -> Result<String, TexError> {
    Ok(match n {
        Node::Text(s) if s == "&nbsp;" => "space".into(),
        Node::Text(s) => typst_string(s),
        // `1,000`: a comma in a number would end a call's argument.
        Node::Number(s) => s.replace(',', "\\,"),
        Node::Function(f) if FUNCTIONS.contains(&f.as_str()) => f.clone(),
        Node::Function(f) => format!("op({})", typst_string(f)),
        Node::Atom(c) => atom(c),
        Node::Group(g, inner) => group(g, inner, place)?,
        Node::Visual(Visual::Fraction(_), parts) if place.on_the_line => slashed(parts, place)?,
        Node::Visual(v, parts) => {
            let inner = match v {
                Visual::Fraction(_) => place.on_the_line(),
                _ => place,
            };
            let part = |k: usize| operand(&parts[k], inner);
            match v {
                Visual::Fraction(_) => format!("frac({}, {})", part(0)?, part(1)?),
                Visual::SquareRoot => format!("sqrt({})", part(0)?),
                Visual::Root => format!("root({}, {})", part(1)?, part(0)?),
                Visual::Negation => negated(&parts[0], place)?,
            }
        }
        Node::Script {
            ty,
            position,
            parts,
        } => script(*ty, *position, parts, place)?,
        Node::Space(width) => space(*width),
        // Handled by `row`; a stray one sets nothing.
        Node::State(_) | Node::Flow(_) => String::new(),
    })
}

/// A fraction on the line: `a\/b`, its numerator bracketed when it is a sum, its denominator
/// when it is a sum or a product (`I\/(M R^2)`).
fn slashed(parts: &[Node], place: Place) -> Result<String, TexError> {
    let part = |n: &Node, below: bool| -> Result<String, TexError> {
        let text = operand(n, place)?;
        Ok(if bracketed_on_the_line(n, below) {
            format!("lr(\\({text}\\))")
        } else {
            text
        })
    };
    Ok(format!(
        "{}\\/{}",
        part(&parts[0], false)?,
        part(&parts[1], true)?
    ))
}

/// Whether a part of a fraction on the line is bracketed: a numerator that is a sum, a
/// denominator (`below`) that is a sum or a product.
pub fn bracketed_on_the_line(n: &Node, below: bool) -> bool {
    let items: Vec<&Node> = match n {
        Node::Group(Grouping::Normal, inner) => inner.iter().collect(),
        other => vec![other],
    };
    let items: Vec<&Node> = items
        .into_iter()
        .filter(|n| !matches!(n, Node::Space(_)))
        .collect();
    let sum = items.iter().enumerate().any(|(k, n)| {
        k > 0
            && matches!(
                n,
                Node::Atom(Content::BinaryOp { .. } | Content::Relation { .. })
            )
    });
    sum || below && items.len() > 1
}

/// An element as a call's argument: its content, never empty.
fn operand(n: &Node, place: Place) -> Result<String, TexError> {
    let mut out = String::new();
    match n {
        Node::Group(Grouping::Normal, inner) => row(inner, place, &mut out)?,
        other => row(std::slice::from_ref(other), place, &mut out)?,
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

fn negated(n: &Node, place: Place) -> Result<String, TexError> {
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
    Ok(format!("cancel({})", operand(n, place)?))
}

fn script(
    ty: ScriptType,
    position: ScriptPosition,
    parts: &[Node],
    place: Place,
) -> Result<String, TexError> {
    let base = operand(&parts[0], place)?;
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
    let scripted = |s: &Node| -> Result<String, TexError> {
        let text = operand(s, place.in_script())?;
        Ok(if place.in_script {
            format!("script({text})")
        } else {
            text
        })
    };
    if let Some(s) = sub {
        out.push_str(&format!(", b: {}", scripted(s)?));
    }
    if let Some(s) = sup {
        out.push_str(&format!(", t: {}", scripted(s)?));
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

fn group(g: &Grouping, inner: &[Node], place: Place) -> Result<String, TexError> {
    Ok(match g {
        // An empty group is something to stand beside: `{} + b` keeps the `+` binary.
        Grouping::Normal if inner.is_empty() => "\"\"".into(),
        Grouping::Normal => {
            let mut out = String::new();
            row(inner, place, &mut out)?;
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
                return Ok(format!("mat({delim}{})", cells_of(body, place)?));
            }
            let mut out = String::from("lr(");
            if let Some(c) = open {
                out.push_str(&character(*c));
            }
            row(inner, place, &mut out)?;
            if let Some(c) = close {
                push(&mut out, &character(*c));
            }
            out.push(')');
            out
        }
        Grouping::Matrix { .. } | Grouping::Array(_) => {
            format!("mat(delim: #none, {})", cells_of(inner, place)?)
        }
        Grouping::Cases { left } => format!(
            "cases({}{})",
            if *left { "" } else { "reverse: #true, " },
            // LaTeX sets a quad between a case's value and its condition.
            rows(inner, ", ", "&quad ", place, false)?
        ),
        // The equation environments: lines and alignment points, as Typst writes them.
        _ => rows(inner, " \\ ", " & ", place, false)?,
    })
}

/// A matrix's cells. Typst sets them in the text style, where a fraction's parts are script-sized
/// (2/3 of the body, too small to read on paper): a cell with a fraction is set in the display
/// style, as a textbook sets it.
fn cells_of(body: &[Node], place: Place) -> Result<String, TexError> {
    rows(body, "; ", ", ", place, true)
}

/// An environment's content: its rows (split at `\\`) joined by `row_sep`, each row's cells
/// (split at `&`) by `cell_sep`; `displayed`: a cell with a fraction in the display style.
fn rows(
    body: &[Node],
    row_sep: &str,
    cell_sep: &str,
    place: Place,
    displayed: bool,
) -> Result<String, TexError> {
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
            row(cell, place, &mut out)?;
            let out = out.trim();
            cells.push(match displayed && out.contains("frac(") {
                true => format!("display({out})"),
                false => out.to_string(),
            });
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
        crate::base::assert_each(
            t,
            &[
                ("ab", "a b"),
                ("\\omega_{x}", "attach(ω, b: x)"),
                ("\\vec{\\omega}", "accent(ω, arrow)"),
                (
                    "\\dot{x} \\ddot\\theta",
                    "accent(x, dot) accent(θ, dot.double)",
                ),
                ("\\overleftrightarrow{I}", "accent(I, arrow.l.r)"),
                ("\\Omega f'", "Ω f'"),
            ],
        );
    }

    #[test]
    fn fractions_units_text_and_matrices() {
        crate::base::assert_each(
            t,
            &[
                ("\\frac{1}{2} m", "frac(1, 2) m"),
                (
                    "g = 9.81\\,\\mathrm{m/s^2}",
                    "g\\=9.81 thin upright(\"m\"\\/attach(\"s\", t: 2))",
                ),
                (
                    "\\mathrm{kg\\,m^2}",
                    "upright(\"kg\"thin attach(\"m\", t: 2))",
                ),
                ("R^{\\mathrm{cm}}", "attach(R, t: upright(\"cm\"))"),
                ("\\text{every axis}", "\"every axis\""),
                (
                    "\\begin{pmatrix}a & b \\\\ c & d\\end{pmatrix}",
                    "mat(a, b; c, d)",
                ),
                ("\\left(x\\right)^{2}", "attach(lr(\\(x\\)), t: 2)"),
                ("f(x, y)", "f\\(x\\,y\\)"),
                (
                    "\\sum_{i} \\int_0^1",
                    "attach(∑, b: i) attach(scripts(∫), b: 0, t: 1)",
                ),
                ("\\sqrt[3]{x} \\not= y", "root(3, x)≠y"),
            ],
        );
    }

    #[test]
    fn what_an_author_writes_cannot_close_a_call_or_lose_a_base() {
        // A lone `)` is a character, never the end of the call it is printed in.
        crate::base::assert_each(
            t,
            &[
                ("\\sqrt{)}", "sqrt(\\))"),
                ("\\frac{(}{)}", "frac(\\(, \\))"),
                // A ratio at the start of an argument is a character, never a named argument.
                ("\\frac{a:b}{c}", "frac(a\\:b, c)"),
                ("\\vec{x:y}", "accent(x\\:y, arrow)"),
                ("\\begin{pmatrix}a:b & c\\end{pmatrix}", "mat(a\\:b, c)"),
                // Two characters stay two: no shorthand (`<=` is ≤ in Typst, two signs in LaTeX).
                ("a<=b -> c", "a\\<\\=b−\\>c"),
                // A power with no base gets an empty one (`m/s$^2$`).
                ("^2", "attach(\"\", t: 2)"),
            ],
        );
    }

    /// On paper a fraction inside a fraction or a script goes on the line, as textbooks write
    /// it (stacked, Typst would set it at half the body's size); a denominator of more than one
    /// factor, and any part that is a sum, is bracketed.
    #[test]
    fn a_fraction_inside_a_fraction_or_a_script_is_on_the_line() {
        crate::base::assert_each(
            t,
            &[
                ("\\frac{a}{b}", "frac(a, b)"),
                ("\\frac{a}{\\frac{b}{c} + d}", "frac(a, b\\/c\\+d)"),
                (
                    "\\frac{g}{1 + \\frac{I}{M R^2}}",
                    "frac(g, 1\\+I\\/lr(\\(M attach(R, t: 2)\\)))",
                ),
                ("\\frac{1}{\\frac{a+b}{2}}", "frac(1, lr(\\(a\\+b\\))\\/2)"),
                ("x^{\\frac{3}{2}}", "attach(x, t: 3\\/2)"),
                (
                    "\\int_{-\\frac{a}{2}}^{a} x",
                    "attach(scripts(∫), b: −a\\/2, t: a) x",
                ),
                // A script's script stays at the script's size (half the body is too small to read).
                ("e^{x^{2}}", "attach(e, t: attach(x, t: script(2)))"),
                ("x^{2}", "attach(x, t: 2)"),
            ],
        );
    }

    /// Typst sets a matrix's cells a size smaller: a cell with a fraction is displayed.
    #[test]
    fn a_matrix_cell_with_a_fraction_is_displayed() {
        assert_eq!(
            t("\\begin{pmatrix}\\frac{1}{2} + x \\\\ y\\end{pmatrix}"),
            "mat(display(frac(1, 2)\\+x); y)"
        );
        // Cases and aligned lines are set as written.
        assert_eq!(
            t("\\begin{cases}\\frac{1}{2} & x\\end{cases}"),
            "cases(frac(1, 2)&quad x)"
        );
    }

    /// A thin space LaTeX needs and Typst sets itself is not set twice: before an operator's
    /// name with a power (`\\,{\\sin}^{2}`, as mechbook prints sin²θ) and before a prime.
    #[test]
    fn a_thin_space_typst_sets_itself_is_not_doubled() {
        crate::base::assert_each(
            t,
            &[
                (
                    "2 - \\,{\\sin}^{2}\\left(x\\right)",
                    "2−attach(sin, t: 2) lr(\\(x\\))",
                ),
                ("\\vec{r}\\,'", "accent(r, arrow)'"),
                // An author's thin space elsewhere stays.
                ("a\\,b", "a thin b"),
            ],
        );
    }

    #[test]
    fn a_colour_is_refused() {
        assert_eq!(
            latex_to_typst("\\color{red} x"),
            Err(TexError::Unprintable("a colour"))
        );
    }
}

/// The PDFs print an exact expression from the tree the pages set (`Expr::to_tex`), with the
/// paper's rules above: no second printer to differ from the page.
#[cfg(test)]
mod expressions {
    use crate::cas::{Expr, parse};
    use crate::notation::Names;

    fn typst(text: &str) -> String {
        let e = parse(text).unwrap().expr;
        e.to_tex(Names::none()).to_typst().unwrap()
    }

    /// A variant's decimal is a numeral: after a number, a power of it takes a dot (3 and
    /// 0.4⁴ side by side read as 30.4⁴).
    #[test]
    fn a_number_before_a_power_of_a_decimal_takes_a_dot() {
        let e = Expr::mul(vec![
            Expr::int(3),
            Expr::pow(Expr::numeral("0.4"), Expr::int(4)),
        ]);
        assert_eq!(
            e.to_tex(Names::none()).to_typst().unwrap(),
            "3⋅attach(0.4, t: 4)"
        );
    }

    #[test]
    fn fractions_powers_and_names() {
        assert_eq!(typst("m*a^2/12"), "frac(m attach(a, t: 2), 12)");
        assert_eq!(
            typst("w1 + Ixx + phi + Omega"),
            "attach(ω, b: 1)\\+attach(I, b: x x)\\+ϕ\\+Ω"
        );
        assert_eq!(typst("-3/4"), "−frac(3, 4)");
        assert_eq!(typst("sin(x)^2"), "attach(sin, t: 2) lr(\\(x\\))");
        // A digit then letters: each letter apart, never a variable `cone`.
        assert_eq!(
            typst("I1cone + d2U + w12"),
            "attach(I, b: 1 c o n e)\\+attach(d, b: 2 U)\\+attach(ω, b: 12)"
        );
        assert_eq!(typst("B*dot(A, C)"), "B lr(\\(A⋅C\\))");
    }

    /// Inside a fraction or an exponent a fraction goes on the line; a matrix's cell with a
    /// fraction is displayed (the roots of a cubic, in tests/course's top, were set at half
    /// the body's size).
    #[test]
    fn the_papers_rules_hold_for_expressions() {
        assert_eq!(typst("x^(3/2)"), "attach(x, t: 3\\/2)");
        assert_eq!(typst("a/(b/c + d)"), "frac(a, b\\/c\\+d)");
        assert_eq!(
            typst("a/(7*(3/5)^(3/2))"),
            "frac(a, 7 attach(lr(\\(3\\/5\\)), t: 3\\/2))"
        );
        assert_eq!(
            typst("[a/2 + x, b, 1]"),
            "mat(display(frac(a, 2)\\+x); b; 1)"
        );
        assert_eq!(typst("[[1, 0], [0, 1]]"), "mat(1, 0; 0, 1)");
    }
}
