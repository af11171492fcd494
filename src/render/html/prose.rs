//! An author's words and mechbook's numbers and units as HTML, for every page of the site.

use super::math;
use crate::notation::Names;
use crate::render::RenderError;

/// A sentence as HTML: its text escaped, its formulas as MathML.
pub fn prose_html(
    prose: &crate::model::prose::Prose,
    names: &Names,
) -> Result<String, RenderError> {
    use crate::model::prose::Piece;
    let mut out = String::new();
    for piece in &prose.0 {
        match piece {
            Piece::Text(t) => out.push_str(&tera::escape_html(t)),
            // An author's mathematics is set from the tree read at load, mechbook's from the
            // tree it builds.
            Piece::Math(f) => out.push_str(&math::inline(&f.to_tex(names))?),
        }
    }
    Ok(out)
}

/// An author's text as HTML: escaped, its `$…$` mathematics as MathML (read at load, so set
/// as the author wrote it).
pub fn author_html(text: &str) -> Result<String, RenderError> {
    prose_html(&crate::model::prose::author(text), Names::none())
}

/// A unit as HTML: `kg m^2/s` as kg m<sup>2</sup>/s, a `*` as a space.
pub fn unit_html(text: &str) -> String {
    let units = crate::base::format::unit_powers(&tera::escape_html(text));
    format!("<span class=\"unit\">{units}</span>")
}
