//! LaTeX -> MathML at build time, so pages need no JavaScript and no network.

use super::RenderError;
use pulldown_latex::config::DisplayMode;
use pulldown_latex::{Parser, RenderConfig, Storage, push_mathml};

/// MathML for one formula, displayed as a block or inline. A formula the converter cannot read is
/// an error naming it, never a silently broken page.
pub fn mathml(latex: &str, block: bool) -> Result<String, RenderError> {
    let storage = Storage::new();
    let parser = Parser::new(latex, &storage);
    let config = RenderConfig {
        display_mode: if block {
            DisplayMode::Block
        } else {
            DisplayMode::Inline
        },
        ..RenderConfig::default()
    };
    let mut out = String::new();
    push_mathml(&mut out, parser, config).map_err(|e| RenderError::Math {
        latex: latex.into(),
        message: e.to_string(),
    })?;
    // The converter renders what it cannot parse in red inside <merror>: treat that as failure.
    if out.contains("<merror") {
        return Err(RenderError::Math {
            latex: latex.into(),
            message: out,
        });
    }
    // `\cos^{2}` comes out as an <msup> of three children (a space, `cos`, the exponent), which
    // browsers draw as a small "cos2": the printer writes `{\cos}^{2}` instead; catch any other.
    if out.contains("<msup><mspace") {
        return Err(RenderError::MalformedPower {
            latex: latex.into(),
        });
    }
    Ok(escape_bare_less_than(&out))
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_latex_our_derivations_print_renders() {
        for latex in [
            "\\frac{M R^{2}}{2}",
            "{\\sin}^{2}\\left(\\alpha\\right) + \\cos\\left(\\theta\\right)",
            "\\overleftrightarrow{I} = \\begin{pmatrix}1 & 0 \\\\ 0 & 1\\end{pmatrix}",
            "\\det\\left(\\overleftrightarrow{I} - \\lambda \\mathbb{1}\\right) = 0",
            "\\lambda = \\frac{1}{6}: \\; \\text{every axis} \\perp \\begin{pmatrix}1 & 1 & 1\\end{pmatrix}",
            "I_{\\mathrm{cm}} + M\\left(R^{2}\\mathbb{1} - \\vec R \\vec R^{T}\\right)",
            "\\sqrt{\\frac{I_{n}}{M}}",
            "\\int dm = m",
        ] {
            let m = mathml(latex, true).unwrap_or_else(|e| panic!("{e}"));
            assert!(
                m.starts_with("<math") && m.contains("display=\"block\""),
                "{m}"
            );
        }
    }

    #[test]
    fn a_power_of_an_operator_needs_braces() {
        assert!(mathml("M \\cos^{2}\\left(\\alpha\\right)", false).is_err());
        let ok = mathml("\\,{\\cos}^{2}\\left(\\alpha\\right)", false).unwrap();
        assert!(
            ok.contains("<msup><mrow><mi>cos</mi></mrow><mrow><mn>2</mn></mrow></msup>"),
            "{ok}"
        );
    }

    #[test]
    fn less_than_is_escaped() {
        let m = mathml("I_{1} < I_{2} > I_{3}", false).unwrap();
        assert!(m.contains("<mo>&lt;</mo>") && !m.contains("<mo><"), "{m}");
        assert!(m.starts_with("<math") && m.ends_with("</math>"), "{m}");
    }

    #[test]
    fn unreadable_latex_is_an_error() {
        assert!(mathml("\\frac{1}{", true).is_err());
    }
}
