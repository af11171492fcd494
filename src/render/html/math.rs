//! Formulas on the pages: MathML at build time (notation/mathml.rs), a long one in pieces a
//! browser can wrap, so pages need no JavaScript and no network.

use crate::notation::latex::Node;
use crate::notation::linebreak;
use crate::notation::{self, MathmlError, Tex};
use crate::render::RenderError;

/// MathML for a formula or a piece of it, displayed as a block or inline. A formula that
/// cannot be set is an error naming it (`latex`, the whole), never a silently broken page.
fn set(latex: &str, nodes: &[Node], block: bool) -> Result<String, RenderError> {
    notation::mathml::mathml(nodes, block).map_err(|e| match e {
        MathmlError::MalformedPower => RenderError::MalformedPower {
            latex: latex.into(),
        },
        other => RenderError::Math {
            latex: latex.into(),
            message: other.to_string(),
        },
    })
}

/// MathML for one formula, displayed as a block or inline.
pub fn mathml(tex: &Tex, block: bool) -> Result<String, RenderError> {
    set(&tex.source, &tex.nodes, block)
}

/// The estimated width of a formula, in characters (notation/linebreak.rs).
pub fn width(tex: &Tex) -> f32 {
    linebreak::width(&tex.nodes)
}

/// A display formula: one block `<math>` when it fits a line; else its pieces, each an inline
/// `<math>` in display style, in a `<div class="formula">` that the browser wraps between them.
/// A formula wider than a phone's line is set twice, for paper and wide screens and for phones;
/// the style sheet shows one (`.wide`, `.narrow`).
pub fn block(tex: &Tex) -> Result<String, RenderError> {
    for_both_screens(tex, linebreak::LINE, set_block, "div")
}

type Setter = fn(&str, &[Vec<Node>], bool) -> Result<String, RenderError>;

/// The formula set for paper and wide screens (cut at `line`), and, when it is wider than a
/// phone's line and the phone's setting differs, for phones too: each in a `tag` of class
/// `wide` or `narrow`.
fn for_both_screens(tex: &Tex, line: f32, set: Setter, tag: &str) -> Result<String, RenderError> {
    let latex = tex.source.as_str();
    let wide = set(latex, &linebreak::pieces(&tex.nodes, line), false)?;
    if linebreak::width(&tex.nodes) <= linebreak::PHONE {
        return Ok(wide);
    }
    let narrow = set(latex, &linebreak::phone_pieces(&tex.nodes), true)?;
    if narrow == wide {
        return Ok(wide);
    }
    Ok(format!(
        "<{tag} class=\"wide\">{wide}</{tag}><{tag} class=\"narrow\">{narrow}</{tag}>"
    ))
}

fn set_block(latex: &str, pieces: &[Vec<Node>], phone: bool) -> Result<String, RenderError> {
    if let [one] = pieces {
        return Ok(scaled(set(latex, one, true)?, one, phone));
    }
    let mut out = String::from("<div class=\"formula\">");
    for (k, piece) in pieces.iter().enumerate() {
        if k > 0 {
            out.push(' ');
        }
        let m = set(latex, &linebreak::set_apart(k, piece), false)?;
        let m = m.replacen("<math", "<math displaystyle=\"true\"", 1);
        out.push_str(&scaled(m, piece, phone));
    }
    out.push_str("</div>");
    Ok(out)
}

/// A phone's piece that is still wider than its line, set smaller to fit (`phone_scale`, not
/// below SMALLEST).
fn scaled(mathml: String, piece: &[Node], phone: bool) -> String {
    let w = linebreak::width(piece);
    if !phone || w <= linebreak::PHONE {
        return mathml;
    }
    let percent = (100.0 * linebreak::phone_scale(w).max(linebreak::SMALLEST)).floor();
    mathml.replacen(
        "<math",
        &format!("<math style=\"font-size: {percent}%\""),
        1,
    )
}

/// A formula within a sentence: inline `<math>` pieces separated by spaces, where the line may
/// wrap, once it is wider than half a line. Set twice, as a display formula is, when it is
/// wider than a phone's line.
pub fn inline(tex: &Tex) -> Result<String, RenderError> {
    for_both_screens(tex, linebreak::LINE / 2.0, set_inline, "span")
}

fn set_inline(latex: &str, pieces: &[Vec<Node>], phone: bool) -> Result<String, RenderError> {
    let mut out = Vec::with_capacity(pieces.len());
    for (k, piece) in pieces.iter().enumerate() {
        out.push(scaled(
            set(latex, &linebreak::set_apart(k, piece), false)?,
            piece,
            phone,
        ));
    }
    Ok(out.join(" "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(latex: &str) -> Result<Tex, crate::notation::TexError> {
        Tex::read(latex)
    }

    /// A formula as an author writes it, read.
    fn tex(latex: &str) -> Tex {
        read(latex).unwrap_or_else(|e| panic!("{latex}: {e}"))
    }

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
            let m = mathml(&tex(latex), true).unwrap_or_else(|e| panic!("{e}"));
            assert!(
                m.starts_with("<math") && m.contains("display=\"block\""),
                "{m}"
            );
        }
    }

    #[test]
    fn a_power_of_an_operator_is_set_on_a_group() {
        // `\cos^{2}` would be an <msup> of three children, a small "cos2": the reader sets
        // it as `{\cos}^{2}`, the form mechbook's printer writes.
        let braced = mathml(&tex("M {\\cos}^{2}\\left(\\alpha\\right)"), false).unwrap();
        assert!(
            braced.contains("<msup><mrow><mi>cos</mi></mrow><mrow><mn>2</mn></mrow></msup>"),
            "{braced}"
        );
        assert_eq!(
            mathml(&tex("M \\cos^{2}\\left(\\alpha\\right)"), false).unwrap(),
            braced
        );
    }

    #[test]
    fn less_than_is_escaped() {
        let m = mathml(&tex("I_{1} < I_{2} > I_{3}"), false).unwrap();
        assert!(m.contains("<mo>&lt;</mo>") && !m.contains("<mo><"), "{m}");
        assert!(m.starts_with("<math") && m.ends_with("</math>"), "{m}");
    }

    #[test]
    fn a_long_formula_is_set_in_pieces_that_keep_binary_spacing() {
        let terms: Vec<String> = (0..40).map(|k| format!("a_{{{k}}}")).collect();
        let m = block(&tex(&format!("T = {}", terms.join(" + ")))).unwrap();
        assert!(
            m.starts_with("<div class=\"formula\"><math displaystyle=\"true\""),
            "{m}"
        );
        assert_eq!(m.matches("<math").count(), 41, "{m}");
        // The pieces after the first start with an empty row, so + is an infix operator.
        assert_eq!(m.matches("<mrow></mrow><mo>+</mo>").count(), 39, "{m}");
        let short = block(&tex("T = a + b")).unwrap();
        assert!(short.starts_with("<math display=\"block\""), "{short}");
    }

    #[test]
    fn a_formula_wider_than_a_phone_is_set_for_both_screens() {
        let terms: Vec<String> = (0..12).map(|k| format!("a_{{{k}}}")).collect();
        let m = block(&tex(&format!("T = {}", terms.join(" + ")))).unwrap();
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
        let m = inline(&tex(words)).unwrap();
        assert!(m.starts_with("<span class=\"wide\"><math"), "{m}");
        assert_eq!(m.matches("<mtext>").count(), 1 + 8, "{m}");
        // Short formulas are set once.
        assert_eq!(
            block(&tex("T = a + b")).unwrap().matches("<math").count(),
            1
        );
    }

    /// The font sizes a setting scales its pieces to, in percent.
    fn scales(mathml: &str) -> Vec<f32> {
        mathml
            .split("font-size: ")
            .skip(1)
            .map(|s| s.split('%').next().unwrap().parse().unwrap())
            .collect()
    }

    #[test]
    fn a_phone_piece_that_cannot_be_cut_is_scaled_to_fit_never_below_85_percent() {
        // A matrix a little wider than a phone's line (tests/course's washer): its piece
        // `= (…)` is set smaller, to fit.
        let matrix = "I = \\begin{pmatrix}\\frac{325 M a^{2}}{1024} & -\\frac{15 M a^{2}}{64} & 0 \\\\ -\\frac{15 M a^{2}}{64} & \\frac{325 M a^{2}}{1024} & 0 \\\\ 0 & 0 & \\frac{325 M a^{2}}{512}\\end{pmatrix}";
        let m = block(&tex(matrix)).unwrap();
        let narrow = m.split_once("<div class=\"narrow\">").unwrap().1;
        let percent = scales(narrow);
        assert_eq!(percent.len(), 1, "{narrow}");
        assert!((85.0..100.0).contains(&percent[0]), "{percent:?}");
        assert!(scales(m.split_once("<div class=\"narrow\">").unwrap().0).is_empty());
        // One that would need less than 85 % has its long cells stacked, or becomes the tuple
        // of its rows; a long product is cut between its factors. (They were set at 70 %.)
        for latex in [
            "\\overleftrightarrow{I} = \\begin{pmatrix}\\frac{m}{12} \\left(b^{2} + c^{2}\\right) & 0 & 0 \\\\ 0 & \\frac{m}{12} \\left(a^{2} + c^{2}\\right) & 0 \\\\ 0 & 0 & \\frac{m}{12} \\left(a^{2} + b^{2}\\right)\\end{pmatrix}",
            "I_{xy} = \\int_{0}^{R}\\int_{0}^{\\frac{\\pi}{2}}\\int_{0}^{2\\pi}\\frac{3 M r^{4} \\cos\\left(\\phi\\right) \\sin\\left(\\phi\\right) \\sin\\left(\\theta\\right) \\left(-1 + \\,{\\cos}^{2}\\left(\\theta\\right)\\right)}{2 \\pi R^{3}}\\,d\\phi\\,d\\theta\\,dr = 0",
        ] {
            let m = block(&tex(latex)).unwrap();
            assert!(m.contains("class=\"narrow\""), "{m}");
            for s in scales(&m) {
                assert!(s >= 100.0 * linebreak::SMALLEST, "{s}: {latex}");
            }
        }
    }

    #[test]
    fn attributes_of_a_sized_bracket_are_spaced() {
        let m = mathml(&tex("\\Bigl(a + b\\Bigr) \\bigl(c\\bigr) < d"), false).unwrap();
        crate::base::assert_says(
            &m,
            &[
                "stretchy=\"true\" minsize=\"1.8em\"",
                "stretchy=\"true\" minsize=\"1.2em\"",
            ],
        );
        // No attribute value anywhere is followed directly by a letter.
        let glued = m
            .split('"')
            .skip(2)
            .step_by(2)
            .any(|after| after.starts_with(|c: char| c.is_ascii_alphabetic()));
        assert!(!glued, "{m}");
    }

    #[test]
    fn an_ampersand_is_the_character_on_the_page() {
        let m = mathml(&tex("R \\& D"), false).unwrap();
        assert!(m.contains("<mi>&amp;</mi>"), "{m}");
        // A `~` is a no-break space, not the text "&nbsp;".
        let m = mathml(&tex("a~b"), false).unwrap();
        assert!(
            m.contains("<mspace width=\"0.33333334em\"") && !m.contains("nbsp"),
            "{m}"
        );
    }

    #[test]
    fn unreadable_latex_is_an_error() {
        let e = read("\\frac{1}{").unwrap_err();
        assert!(e.to_string().contains("unbalanced group"), "{e:?}");
    }
}
