//! LaTeX -> MathML at build time, so pages need no JavaScript and no network.

use super::RenderError;
use super::linebreak;
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
    // Cells in display style: a fraction in a matrix at the size of the text, not a script's
    // (MathML Core sets tables compact).
    let out = out.replace("<mtable", "<mtable displaystyle=\"true\"");
    // Only mathematics reaches the page: an author's `\operatorname{</math><script>…}` is
    // copied by the converter as it is, and refused here.
    let safe = crate::base::markup::safe_mathml(&out).map_err(|e| RenderError::Math {
        latex: latex.into(),
        message: e.to_string(),
    })?;
    Ok(space_attributes(&safe))
}

/// A display formula: one block `<math>` when it fits a line; else its pieces, each an inline
/// `<math>` in display style, in a `<div class="formula">` that the browser wraps between them.
/// A formula wider than a phone's line is set twice, for paper and wide screens and for phones;
/// the style sheet shows one (`.wide`, `.narrow`).
pub fn block(latex: &str) -> Result<String, RenderError> {
    for_both_screens(latex, linebreak::LINE, set_block, "div")
}

/// The formula set for paper and wide screens (cut at `line`), and, when it is wider than a
/// phone's line and the phone's setting differs, for phones too: each in a `tag` of class
/// `wide` or `narrow`.
fn for_both_screens(
    latex: &str,
    line: f32,
    set: fn(&[String], bool) -> Result<String, RenderError>,
    tag: &str,
) -> Result<String, RenderError> {
    let wide = set(&linebreak::pieces(latex, line), false)?;
    if linebreak::width_of(latex) <= linebreak::PHONE {
        return Ok(wide);
    }
    let narrow = set(&linebreak::phone_pieces(latex), true)?;
    if narrow == wide {
        return Ok(wide);
    }
    Ok(format!(
        "<{tag} class=\"wide\">{wide}</{tag}><{tag} class=\"narrow\">{narrow}</{tag}>"
    ))
}

fn set_block(pieces: &[String], phone: bool) -> Result<String, RenderError> {
    if let [one] = pieces {
        return Ok(scaled(mathml(one, true)?, one, phone));
    }
    let mut out = String::from("<div class=\"formula\">");
    for (k, piece) in pieces.iter().enumerate() {
        if k > 0 {
            out.push(' ');
        }
        let m = mathml(&binary(k, piece), false)?;
        let m = m.replacen("<math", "<math displaystyle=\"true\"", 1);
        out.push_str(&scaled(m, piece, phone));
    }
    out.push_str("</div>");
    Ok(out)
}

/// A phone's piece that is still wider than its line, set smaller to fit (not below SMALLEST).
/// It is fitted to 90% of the line, as the estimate runs short on matrices (measured in
/// Chromium: a 3×3 matrix about 15%).
fn scaled(mathml: String, latex: &str, phone: bool) -> String {
    let w = linebreak::width_of(latex);
    if !phone || w <= linebreak::PHONE {
        return mathml;
    }
    let percent = (100.0 * (0.9 * linebreak::PHONE / w).max(linebreak::SMALLEST)).floor();
    mathml.replacen(
        "<math",
        &format!("<math style=\"font-size: {percent}%\""),
        1,
    )
}

/// A piece after the first that starts with +, −, =, ·, × or ≈ keeps the spacing of a binary operator:
/// `{}` before it, else MathML sets it as a sign.
fn binary(k: usize, piece: &str) -> String {
    let operator = piece.starts_with(['+', '-', '='])
        || ["\\cdot", "\\times", "\\approx"]
            .iter()
            .any(|o| piece.starts_with(o));
    if k > 0 && operator {
        format!("{{}}{piece}")
    } else {
        piece.to_string()
    }
}

/// A formula within a sentence: inline `<math>` pieces separated by spaces, where the line may
/// wrap, once it is wider than half a line. Set twice, as a display formula is, when it is
/// wider than a phone's line.
pub fn inline(latex: &str) -> Result<String, RenderError> {
    for_both_screens(latex, linebreak::LINE / 2.0, set_inline, "span")
}

fn set_inline(pieces: &[String], phone: bool) -> Result<String, RenderError> {
    let mut out = Vec::with_capacity(pieces.len());
    for (k, piece) in pieces.iter().enumerate() {
        out.push(scaled(mathml(&binary(k, piece), false)?, piece, phone));
    }
    Ok(out.join(" "))
}

/// The converter writes `\bigl(` as `<mo … stretchy="true"minsize="1.2em" …>`, with no space
/// between two attributes, which HTML does not allow: put one after every attribute value that
/// another attribute follows directly.
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
            "{I}_{xy} = \\left.R_{z}\\left(\\psi\\right)^{T} \\mathbb{1}\\right|_{x = 0}",
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
    fn a_long_formula_is_set_in_pieces_that_keep_binary_spacing() {
        let terms: Vec<String> = (0..40).map(|k| format!("a_{{{k}}}")).collect();
        let m = block(&format!("T = {}", terms.join(" + "))).unwrap();
        assert!(
            m.starts_with("<div class=\"formula\"><math displaystyle=\"true\""),
            "{m}"
        );
        assert_eq!(m.matches("<math").count(), 41, "{m}");
        // The pieces after the first start with an empty row, so + is an infix operator.
        assert_eq!(m.matches("<mrow></mrow><mo>+</mo>").count(), 39, "{m}");
        let short = block("T = a + b").unwrap();
        assert!(short.starts_with("<math display=\"block\""), "{short}");
    }

    #[test]
    fn a_formula_wider_than_a_phone_is_set_for_both_screens() {
        let terms: Vec<String> = (0..12).map(|k| format!("a_{{{k}}}")).collect();
        let m = block(&format!("T = {}", terms.join(" + "))).unwrap();
        // One block for paper and wide screens, pieces for phones.
        let (wide, narrow) = m.split_once("</div><div class=\"narrow\">").unwrap();
        assert!(
            wide.starts_with("<div class=\"wide\"><math display=\"block\""),
            "{m}"
        );
        assert_eq!(wide.matches("<math").count(), 1, "{m}");
        assert!(narrow.starts_with("<div class=\"formula\">"), "{m}");
        assert_eq!(narrow.matches("<math").count(), 13, "{m}");
        // A sentence within a paragraph, likewise, in spans.
        let words = "I_{3} < I_{1}:\\;\\text{positive for some choices and negative for others}";
        let m = inline(words).unwrap();
        assert!(m.starts_with("<span class=\"wide\"><math"), "{m}");
        assert_eq!(m.matches("<mtext>").count(), 1 + 8, "{m}");
        // Short formulas are set once.
        assert_eq!(block("T = a + b").unwrap().matches("<math").count(), 1);
    }

    #[test]
    fn a_phone_piece_that_cannot_be_cut_is_scaled_to_fit() {
        let matrix = "\\begin{pmatrix}\\frac{m}{12} \\left(b^{2} + c^{2}\\right) & 0 & 0 \\\\ 0 & \\frac{m}{12} \\left(a^{2} + c^{2}\\right) & 0 \\\\ 0 & 0 & \\frac{m}{12} \\left(a^{2} + b^{2}\\right)\\end{pmatrix}";
        let w = linebreak::width_of(matrix);
        assert!(w > linebreak::PHONE, "{w}");
        let m = block(matrix).unwrap();
        let narrow = m.split_once("<div class=\"narrow\">").unwrap().1;
        let percent = (100.0 * 0.9 * linebreak::PHONE / w).floor();
        assert!(
            narrow.starts_with(&format!(
                "<math style=\"font-size: {percent}%\" display=\"block\""
            )),
            "{narrow}"
        );
        assert!(percent >= 100.0 * linebreak::SMALLEST, "{percent}");
    }

    #[test]
    fn attributes_of_a_sized_bracket_are_spaced() {
        let m = mathml("\\Bigl(a + b\\Bigr) \\bigl(c\\bigr) < d", false).unwrap();
        assert!(m.contains("stretchy=\"true\" minsize=\"1.8em\""), "{m}");
        assert!(m.contains("stretchy=\"true\" minsize=\"1.2em\""), "{m}");
        // No attribute value anywhere is followed directly by a letter.
        let glued = m
            .split('"')
            .skip(2)
            .step_by(2)
            .any(|after| after.starts_with(|c: char| c.is_ascii_alphabetic()));
        assert!(!glued, "{m}");
    }

    #[test]
    fn unreadable_latex_is_an_error() {
        assert!(mathml("\\frac{1}{", true).is_err());
    }
}
