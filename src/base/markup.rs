//! MathML as the LaTeX converter writes it, made safe for a page: every `<` that opens no tag
//! escaped, and then every tag, attribute and entity checked against what MathML needs. The
//! converter escapes `\text{…}` and `\mathrm{…}` but copies `\operatorname{…}` as it is, so an
//! author's `\operatorname{</math><script>…}` would otherwise reach the page as markup.

/// The elements the converter writes for mathematics.
const ELEMENTS: &[&str] = &[
    "math",
    "semantics",
    "annotation",
    "mrow",
    "mi",
    "mo",
    "mn",
    "mtext",
    "mspace",
    "ms",
    "msup",
    "msub",
    "msubsup",
    "mover",
    "munder",
    "munderover",
    "mmultiscripts",
    "mprescripts",
    "none",
    "mfrac",
    "msqrt",
    "mroot",
    "mstyle",
    "mpadded",
    "mphantom",
    "menclose",
    "merror",
    "mtable",
    "mtr",
    "mtd",
];

/// The attributes it writes; none runs script or loads anything.
const ATTRIBUTES: &[&str] = &[
    "display",
    "xmlns",
    "displaystyle",
    "scriptlevel",
    "style",
    "class",
    "stretchy",
    "mathvariant",
    "linethickness",
    "width",
    "height",
    "depth",
    "largeop",
    "movablelimits",
    "symmetric",
    "minsize",
    "maxsize",
    "lspace",
    "rspace",
    "accent",
    "accentunder",
    "columnalign",
    "rowalign",
    "columnspan",
    "rowspan",
    "fence",
    "separator",
    "form",
    "notation",
    "encoding",
    "voffset",
    "columnlines",
    "rowlines",
    "frame",
];

/// Why the converter's MathML would put markup other than mathematics on a page.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MarkupError {
    #[error("it would write the element `<{0}>` into the page")]
    Element(String),
    #[error("it would write the attribute `{attribute}` into the page's `<{element}>`")]
    Attribute { element: String, attribute: String },
    #[error("the attribute `{0}` has no quoted value")]
    Unquoted(String),
    #[error("the attribute `{attribute}` holds `{value}`")]
    Value { attribute: String, value: String },
    #[error("a `&` that starts no entity: write it as \\& or leave it out")]
    Ampersand,
}

/// The converter's MathML with every bare `<` escaped, or why it would put markup other than
/// mathematics on a page: an element or attribute MathML does not need, a `&` that starts no
/// entity, a style that loads something.
pub fn safe_mathml(raw: &str) -> Result<String, MarkupError> {
    let escaped = escape_bare_less_than(raw);
    check(&escaped)?;
    Ok(escaped)
}

/// The converter writes `a < b` as `<mo><</mo>`, which is not valid HTML: escape every `<` that
/// does not open a tag.
fn escape_bare_less_than(mathml: &str) -> String {
    let mut out = String::with_capacity(mathml.len());
    let mut chars = mathml.chars().peekable();
    while let Some(c) = chars.next() {
        let opens_tag = chars
            .peek()
            .is_some_and(|n| n.is_ascii_alphabetic() || *n == '/');
        if c == '<' && !opens_tag {
            out.push_str("&lt;");
        } else {
            out.push(c);
        }
    }
    out
}

fn check(mathml: &str) -> Result<(), MarkupError> {
    let bytes = mathml.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'<' => i = tag(mathml, i)?,
            b'&' => i = entity(mathml, i)?,
            _ => i += 1,
        }
    }
    Ok(())
}

/// Checks the tag that starts at `start` and returns where it ends.
fn tag(s: &str, start: usize) -> Result<usize, MarkupError> {
    let rest = &s[start + 1..];
    let closing = rest.starts_with('/');
    let body = if closing { &rest[1..] } else { rest };
    let name_len = body
        .find(|c: char| !c.is_ascii_alphanumeric())
        .unwrap_or(body.len());
    let name = &body[..name_len];
    if !ELEMENTS.contains(&name) {
        return Err(MarkupError::Element(name.to_string()));
    }
    let mut at = start + 1 + usize::from(closing) + name_len;
    loop {
        let rest = &s[at..];
        let trimmed = rest.trim_start();
        at += rest.len() - trimmed.len();
        if trimmed.starts_with('>') {
            return Ok(at + 1);
        }
        if trimmed.starts_with("/>") && !closing {
            return Ok(at + 2);
        }
        let attr_len = trimmed
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
            .unwrap_or(trimmed.len());
        let attr = &trimmed[..attr_len];
        if closing || attr.is_empty() || !ATTRIBUTES.contains(&attr) {
            return Err(MarkupError::Attribute {
                element: name.to_string(),
                attribute: attr.to_string(),
            });
        }
        let value = trimmed[attr_len..]
            .strip_prefix("=\"")
            .ok_or_else(|| MarkupError::Unquoted(attr.to_string()))?;
        let end = value
            .find('"')
            .ok_or_else(|| MarkupError::Unquoted(attr.to_string()))?;
        let value = &value[..end];
        if value.contains(['<', '>']) || value.to_ascii_lowercase().contains("url(") {
            return Err(MarkupError::Value {
                attribute: attr.to_string(),
                value: value.to_string(),
            });
        }
        at += attr_len + 2 + end + 1;
    }
}

/// Checks the entity that starts at `start` (`&lt;`, `&#x2061;`) and returns where it ends.
fn entity(s: &str, start: usize) -> Result<usize, MarkupError> {
    let rest = &s[start + 1..];
    let len = rest
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '#'))
        .unwrap_or(rest.len());
    if len == 0 || !rest[len..].starts_with(';') {
        return Err(MarkupError::Ampersand);
    }
    Ok(start + 1 + len + 1)
}

#[cfg(test)]
mod tests {
    use super::safe_mathml;

    #[test]
    fn mathematics_passes_and_a_bare_less_than_is_escaped() {
        let m = safe_mathml(
            "<math display=\"block\"><mrow><mi>a</mi><mo><</mo><mn>2</mn>\
             <mspace width=\"0.1667em\" /><mo>&#x2061;</mo></mrow></math>",
        )
        .unwrap();
        assert!(m.contains("<mo>&lt;</mo>"), "{m}");
        // A `>` in text is text to HTML, and stays.
        assert!(safe_mathml("<math><mo>></mo></math>").is_ok());
    }

    #[test]
    fn markup_that_is_not_mathematics_is_refused() {
        for hostile in [
            "<math><mi></math><script>alert(1)</script></mi></math>",
            "<math><mi><svg onload=\"x\"></svg></mi></math>",
            "<math><mi><img src=x onerror=alert(1)></mi></math>",
            "<math onclick=\"x\"><mi>a</mi></math>",
            "<math><mi style=\"background: url(x)\">a</mi></math>",
            "<math><mi>a&b</mi></math>",
        ] {
            let e = safe_mathml(hostile).unwrap_err();
            let expected = match hostile {
                h if h.contains("onclick") => matches!(e, super::MarkupError::Attribute { .. }),
                h if h.contains("style") => matches!(e, super::MarkupError::Value { .. }),
                h if h.contains("a&b") => matches!(e, super::MarkupError::Ampersand),
                _ => matches!(e, super::MarkupError::Element(_)),
            };
            assert!(expected, "{hostile}: {e:?}");
        }
    }
}
