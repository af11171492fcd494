//! The build's note on a page whose formulas a phone sets smaller to fit (`math::scaled`): each
//! such piece's size, and the piece in plain text, read from its MathML as the page has it.
//!
//! Only `math::scaled` knows a piece is set smaller, and it writes MathML; the note reads the
//! page back rather than carry a second result through every view. It is a note to the author,
//! never printed on a page.

use crate::base::format::superscript;
use crate::document::Page;

/// The note for a page, or `None` where no formula piece is set smaller.
pub fn phone_scaled(page: &Page, html: &str) -> Option<String> {
    let scaled = scaled_formulas(html);
    if scaled.is_empty() {
        return None;
    }
    let list: Vec<String> = scaled
        .iter()
        .map(|(percent, text)| format!("{percent} % `{text}`"))
        .collect();
    let pieces = match scaled.len() {
        1 => "1 formula piece is set smaller to fit its line".to_string(),
        n => format!("{n} formula pieces are set smaller to fit their line"),
    };
    Some(format!(
        "{}: on phones {pieces}: {}",
        page.source.display(),
        list.join(", ")
    ))
}

/// How much of a piece the note quotes, in characters.
const NOTE_LENGTH: usize = 72;

/// The formula pieces of a page that are set smaller: each one's size in percent and its plain
/// text (cut at [`NOTE_LENGTH`] characters), in the page's order.
fn scaled_formulas(html: &str) -> Vec<(u32, String)> {
    let mut out = Vec::new();
    for part in html.split("<math style=\"font-size: ").skip(1) {
        let Some((percent, rest)) = part.split_once('%') else {
            continue;
        };
        let Ok(percent) = percent.parse() else {
            continue;
        };
        let body = rest.split_once('>').map_or("", |(_, body)| body);
        let body = body.split("</math>").next().unwrap_or("");
        let text = plain(&parse(body));
        let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
        let cut: String = text.chars().take(NOTE_LENGTH).collect();
        let more = if cut.len() < text.len() { "…" } else { "" };
        out.push((percent, format!("{cut}{more}")));
    }
    out
}

/// One MathML element with its children, or a run of text.
#[derive(Debug)]
enum Element {
    Tag(String, Vec<Element>),
    Text(String),
}

/// The elements of MathML as `notation::mathml` writes it: start and end tags, `<…/>` empty
/// ones, text with the writer's entities.
fn parse(mathml: &str) -> Vec<Element> {
    let mut stack: Vec<(String, Vec<Element>)> = vec![(String::new(), Vec::new())];
    let mut rest = mathml;
    while !rest.is_empty() {
        let Some(open) = rest.find('<') else {
            push(&mut stack, Element::Text(unescape(rest)));
            break;
        };
        if open > 0 {
            push(&mut stack, Element::Text(unescape(&rest[..open])));
        }
        let Some(close) = rest[open..].find('>') else {
            break;
        };
        let tag = &rest[open + 1..open + close];
        rest = &rest[open + close + 1..];
        let name: String = tag
            .trim_start_matches('/')
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric())
            .collect();
        if tag.starts_with('/') {
            if stack.len() > 1 {
                let (name, children) = stack.pop().unwrap_or_default();
                push(&mut stack, Element::Tag(name, children));
            }
        } else if tag.ends_with('/') {
            push(&mut stack, Element::Tag(name, Vec::new()));
        } else {
            stack.push((name, Vec::new()));
        }
    }
    while stack.len() > 1 {
        let (name, children) = stack.pop().unwrap_or_default();
        push(&mut stack, Element::Tag(name, children));
    }
    stack
        .pop()
        .map(|(_, children)| children)
        .unwrap_or_default()
}

fn push(stack: &mut [(String, Vec<Element>)], e: Element) {
    if let Some((_, children)) = stack.last_mut() {
        children.push(e);
    }
}

fn unescape(text: &str) -> String {
    text.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&#x27;", "'")
        .replace("&amp;", "&")
}

/// The elements as a reader writes them on one line: a/b, x², a_(i j), √(x).
fn plain(elements: &[Element]) -> String {
    elements.iter().map(plain_one).collect()
}

fn plain_one(e: &Element) -> String {
    let (name, children) = match e {
        // The invisible function application is no character of the note's.
        Element::Text(text) => return text.replace('\u{2061}', ""),
        Element::Tag(name, children) => (name, children),
    };
    let part = |k: usize| children.get(k).map(plain_one).unwrap_or_default();
    match name.as_str() {
        "mspace" => " ".into(),
        "mfrac" => format!("{}/{}", grouped(&part(0)), grouped(&part(1))),
        "msup" => format!("{}{}", part(0), raised(&part(1))),
        "msub" => format!("{}_{}", part(0), grouped(&part(1))),
        "msubsup" => format!("{}_{}{}", part(0), grouped(&part(1)), raised(&part(2))),
        "mover" => format!("{}{}", part(0), accent(&part(1))),
        "msqrt" => format!("√{}", grouped(&plain(children))),
        "mtable" => children
            .iter()
            .map(|row| match row {
                Element::Tag(_, cells) => {
                    cells.iter().map(plain_one).collect::<Vec<_>>().join(", ")
                }
                text => plain_one(text),
            })
            .collect::<Vec<_>>()
            .join("; "),
        _ => plain(children),
    }
}

/// A part that is more than one name or number, in parentheses.
fn grouped(part: &str) -> String {
    let part = part.trim();
    let mut depth = 0i32;
    let mut bare = true;
    for c in part.chars() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            '+' | '−' | '-' | '=' | '/' | ',' | ' ' | '⋅' if depth == 0 => bare = false,
            _ => {}
        }
    }
    let leading_sign = part.starts_with('−') && part.chars().count() > 1;
    if bare && !leading_sign {
        part.to_string()
    } else {
        format!("({part})")
    }
}

/// A superscript: in superscript characters where each has one (x², a⁻¹), else `^(…)`.
fn raised(script: &str) -> String {
    let script = script.trim();
    let lifted = |c: char| if c == '−' { '⁻' } else { superscript(c) };
    if !script.is_empty() && script.chars().all(|c| lifted(c) != c) {
        script.chars().map(lifted).collect()
    } else {
        format!("^{}", grouped(script))
    }
}

/// An accent over a base, as the combining character a reader's text takes.
fn accent(mark: &str) -> String {
    match mark.trim() {
        "˙" | "." => "\u{307}".into(),
        "¨" => "\u{308}".into(),
        "→" | "⃗" => "\u{20D7}".into(),
        "^" | "ˆ" => "\u{302}".into(),
        "↔" => "\u{20E1}".into(),
        "‾" => "\u{305}".into(),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::notation::Tex;
    use crate::render::html::math;

    /// The pieces of `latex` a phone sets smaller, as the note quotes them.
    fn noted(latex: &str) -> Vec<(u32, String)> {
        scaled_formulas(&math::block(&Tex::read(latex).unwrap()).unwrap())
    }

    /// The three triple integrals of a box's moments, each cut for a phone to one piece that
    /// still needs 85 %: the note tells them apart (it once quoted `=∫−a2a2∫…`, their glyphs run
    /// together, the same for all three).
    #[test]
    fn a_scaled_piece_is_quoted_in_plain_text() {
        let integral = |a: &str, b: &str| {
            format!(
                "I_{{{a}{a}}} = \\int_{{-\\frac{{a}}{{2}}}}^{{\\frac{{a}}{{2}}}}\\int_{{-\\frac{{a}}{{2}}}}^{{\\frac{{a}}{{2}}}}\\int_{{-\\frac{{a}}{{2}}}}^{{\\frac{{a}}{{2}}}}\\frac{{m \\left({b}^{{2}} + z^{{2}}\\right)}}{{a^{{3}}}}\\,dx\\,dy\\,dz = \\frac{{m a^{{2}}}}{{6}}"
            )
        };
        let x = noted(&integral("x", "y"));
        let y = noted(&integral("y", "x"));
        assert_eq!(x.len(), 1, "{x:?}");
        assert_eq!(
            x[0],
            (
                85,
                "=∫_(−a/2)^(a/2)∫_(−a/2)^(a/2)∫_(−a/2)^(a/2)m(y²+z²)/a³ dx dy dz".into()
            )
        );
        assert_ne!(x, y);
    }

    #[test]
    fn fractions_scripts_roots_accents_and_matrices_read_as_a_reader_writes_them() {
        let read = |mathml: &str| plain(&parse(mathml));
        assert_eq!(
            read("<mfrac><mrow><mi>a</mi><mo>+</mo><mi>b</mi></mrow><mn>2</mn></mfrac>"),
            "(a+b)/2"
        );
        assert_eq!(
            read("<msup><mi>x</mi><mrow><mo>−</mo><mn>1</mn></mrow></msup>"),
            "x⁻¹"
        );
        assert_eq!(read("<msup><mi>e</mi><mi>t</mi></msup>"), "e^t");
        assert_eq!(
            read("<msub><mi>I</mi><mrow><mi>x</mi><mi>y</mi></mrow></msub>"),
            "I_xy"
        );
        assert_eq!(
            read("<msqrt><mi>g</mi><mo>/</mo><mi>l</mi></msqrt>"),
            "√(g/l)"
        );
        assert_eq!(read("<mover><mi>θ</mi><mo>˙</mo></mover>"), "θ\u{307}");
        assert_eq!(
            read(
                "<mtable><mtr><mtd><mn>1</mn></mtd><mtd><mn>0</mn></mtd></mtr><mtr><mtd><mn>0</mn></mtd><mtd><mn>1</mn></mtd></mtr></mtable>"
            ),
            "1, 0; 0, 1"
        );
        assert_eq!(
            read("<mi>a</mi><mspace width=\"1em\" /><mo>&lt;</mo>"),
            "a <"
        );
    }

    #[test]
    fn a_page_with_no_scaled_piece_has_no_note_and_one_piece_is_singular() {
        assert!(scaled_formulas("<math><mi>x</mi></math>").is_empty());
        let one = scaled_formulas("<math style=\"font-size: 88%\" alttext=\"x\"><mi>x</mi></math>");
        assert_eq!(one, vec![(88, "x".to_string())]);
    }
}
