//! The read LaTeX tree ([`Tex`]) as MathML, at build time, so pages need no JavaScript and no
//! network: pulldown-latex's MathML writer, fed the tree's events.

use super::latex::{Node, Tex, braced_operators, events, rewrite};
use crate::base::markup::{MarkupError, safe_mathml};
use pulldown_latex::config::DisplayMode;
use pulldown_latex::event::{Dimension, DimensionUnit};
use pulldown_latex::{RenderConfig, push_mathml};

/// Why a tree has no MathML a page may hold.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MathmlError {
    #[error("the MathML writer failed: {0}")]
    Writer(String),
    /// `\cos^{2}` as an `<msup>` of three children, which browsers draw as a small "cos2".
    #[error("a power of an operator name is set as a small run of text")]
    MalformedPower,
    /// Markup other than mathematics (an author's `\operatorname{</math><script>…}`).
    #[error("{0}")]
    Unsafe(MarkupError),
}

impl Tex {
    /// MathML for the formula, displayed as a block or inline.
    pub fn to_mathml(&self, block: bool) -> Result<String, MathmlError> {
        mathml(&self.nodes, block)
    }
}

/// MathML for a formula or a piece of one, displayed as a block or inline.
pub fn mathml(nodes: &[Node], block: bool) -> Result<String, MathmlError> {
    let config = || RenderConfig {
        display_mode: if block {
            DisplayMode::Block
        } else {
            DisplayMode::Inline
        },
        ..RenderConfig::default()
    };
    let write = |nodes: &[Node]| -> Result<String, MathmlError> {
        let mut out = String::new();
        let events = events(nodes)
            .into_iter()
            .map(Ok::<_, std::convert::Infallible>);
        push_mathml(&mut out, events, config()).map_err(|e| MathmlError::Writer(e.to_string()))?;
        Ok(out)
    };
    // An upright word is one identifier (`<mtext>body</mtext>`), spoken as the word.
    let nodes = super::tree::upright_words(&no_break_spaces(nodes));
    let mut out = write(&nodes)?;
    // An author's `\cos^2 x`: set as mechbook's printer writes it, `{\cos}^{2}`.
    if out.contains("<msup><mspace") {
        out = write(&braced_operators(&nodes))?;
    }
    if out.contains("<msup><mspace") {
        return Err(MathmlError::MalformedPower);
    }
    // Cells in display style: a fraction in a matrix at the size of the text, not a script's
    // (MathML Core sets tables compact).
    let out = out.replace("<mtable", "<mtable displaystyle=\"true\"");
    // Only mathematics reaches the page: the writer copies an operator's name as it is.
    let safe = safe_mathml(&escape_bare_ampersands(&out)).map_err(MathmlError::Unsafe)?;
    Ok(with_alttext(
        &space_attributes(&safe),
        &super::spoken::spoken(&nodes),
    ))
}

/// The `<math>` element with its spoken form as `alttext`, for a screen reader that does not
/// read MathML.
fn with_alttext(mathml: &str, spoken: &str) -> String {
    let escaped = spoken
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;");
    // After the writer's own attributes, at the end of the start tag.
    match mathml.find('>') {
        Some(end) if mathml.starts_with("<math") => {
            format!("{} alttext=\"{escaped}\"{}", &mathml[..end], &mathml[end..])
        }
        _ => mathml.to_string(),
    }
}

/// The nodes with the parser's `&nbsp;` text (a `~` or `\ `) as a space: the writer escapes
/// text, and the page would show "&nbsp;".
fn no_break_spaces(nodes: &[Node]) -> Vec<Node> {
    rewrite(nodes, &|n| match n {
        // An interword space, a third of an em.
        Node::Text(s) if s == "&nbsp;" => {
            Node::Space(Some(Dimension::new(1.0 / 3.0, DimensionUnit::Em)))
        }
        other => other,
    })
}

/// The writer copies a `\&` or a text's `&` as it is: each `&` that starts no entity
/// (`&nbsp;`, `&#x2212;`) becomes `&amp;`, the character on the page.
fn escape_bare_ampersands(mathml: &str) -> String {
    let mut out = String::with_capacity(mathml.len());
    for (k, part) in mathml.split('&').enumerate() {
        if k > 0 {
            let entity = part.split_once(';').is_some_and(|(name, _)| {
                let name = name.strip_prefix('#').unwrap_or(name);
                !name.is_empty()
                    && name.len() <= 32
                    && name.chars().all(|c| c.is_ascii_alphanumeric())
            });
            out.push_str(if entity { "&" } else { "&amp;" });
        }
        out.push_str(part);
    }
    out
}

/// The writer sets `\bigl(` as `<mo … stretchy="true"minsize="1.2em" …>`, with no space between
/// two attributes, which HTML does not allow: put one after every attribute value that another
/// attribute follows directly.
fn space_attributes(mathml: &str) -> String {
    let mut out = String::with_capacity(mathml.len());
    let (mut in_tag, mut in_value) = (false, false);
    let mut chars = mathml.chars().peekable();
    while let Some(c) = chars.next() {
        out.push(c);
        match c {
            '<' if !in_value => in_tag = true,
            '>' if !in_value => in_tag = false,
            '"' if in_tag => {
                in_value = !in_value;
                if !in_value && chars.peek().is_some_and(|n| n.is_ascii_alphabetic()) {
                    out.push(' ');
                }
            }
            _ => {}
        }
    }
    out
}
