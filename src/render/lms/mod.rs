//! Each lecture's problems for the learning-management systems that take one number a blank:
//! a QTI 2.1 package (`export/qti21/<lecture>.zip`, `<lecture>-2.zip`, … of 5,000 items each:
//! Blackboard, OpenOlat, ILIAS, Inspera),
//! a QTI 1.2 package of Canvas's calculated questions (`export/canvas/<lecture>.zip`), and
//! Blackboard's tab-separated upload (`export/blackboard/<lecture>.txt`). Each question is one
//! entry of one answer (`document::quiz`); its answers are mechbook's verified variants, the
//! same the key and Moodle show. A site whose answers are private (a roster build) has none.

mod blackboard;
mod canvas;
mod qti21;

use super::RenderError;
use super::renderer::{Context, Plots, Rendered, Renderer, add};
use crate::document::course::Documents;
use crate::document::quiz::lecture_quizzes;
use crate::model::prose::{Piece, Prose};
use crate::notation::Names;

/// The three exports of every lecture with problems.
pub struct Lms;

impl Renderer for Lms {
    fn render(&self, docs: &Documents, _: &Plots, cx: &Context) -> Result<Rendered, RenderError> {
        let mut out = Rendered::default();
        if cx.course.answers_private {
            return Ok(out);
        }
        for (lecture, parts) in lecture_quizzes(docs) {
            let slug = &lecture.slug;
            let title = crate::model::prose::plain(&lecture.heading);
            for (name, zip) in qti21::packages(slug, &parts)? {
                add(&mut out.files, format!("export/qti21/{name}"), zip)?;
            }
            add(
                &mut out.files,
                format!("export/canvas/{slug}.zip"),
                canvas::package(slug, &title, &parts)?,
            )?;
            for (name, text) in blackboard::files(slug, &parts) {
                add(&mut out.files, format!("export/blackboard/{name}"), text)?;
            }
        }
        Ok(out)
    }
}

/// A sentence as XHTML: its text escaped, each formula one MathML `<math>` element in
/// MathML's namespace (pulldown-latex's writer, as the pages').
fn xhtml(prose: &Prose, names: &Names) -> Result<String, RenderError> {
    let mut out = String::new();
    for piece in &prose.0 {
        match piece {
            Piece::Text(t) => out.push_str(&escape(t)),
            Piece::Math(f) => {
                let tex = f.to_tex(names);
                let math = tex.to_mathml(false).map_err(|e| RenderError::Math {
                    latex: tex.source.clone(),
                    message: e.to_string(),
                })?;
                out.push_str(&math.replacen(
                    "<math",
                    "<math xmlns=\"http://www.w3.org/1998/Math/MathML\"",
                    1,
                ));
            }
        }
    }
    Ok(out)
}

/// A unit as XHTML: `kg m^2/s` as kg m<sup>2</sup>/s, a `*` as a space.
fn unit_xhtml(text: &str) -> String {
    crate::base::format::unit_powers(&escape(text))
}

/// A number as every format here reads it back exactly: the shortest decimal that is the
/// same f64, `2` for 2.0, `1.5e-9` below 10⁻⁵ and from 10¹⁶, never `-0`.
fn number(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    if x.abs() < 1e-5 || x.abs() >= 1e16 {
        return format!("{x:e}");
    }
    format!("{x}")
}

/// Text for XML: what an author wrote never becomes markup.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_back_as_the_same_f64() {
        for x in [0.1, 1.0 / 3.0, 6.02e23, 1.5e-9, -2.5, 1e300] {
            assert_eq!(number(x).parse::<f64>().unwrap(), x, "{}", number(x));
        }
        assert_eq!(number(-0.0), "0");
        assert_eq!(number(3.0), "3");
        assert_eq!(number(1.5e-9), "1.5e-9");
    }

    #[test]
    fn an_authors_text_is_never_markup() {
        let prose = Prose::default().text("a <b> & \"c\"");
        assert_eq!(
            xhtml(&prose, Names::none()).unwrap(),
            "a &lt;b&gt; &amp; &quot;c&quot;"
        );
        assert_eq!(unit_xhtml("kg*m^2/s^-1"), "kg m<sup>2</sup>/s<sup>−1</sup>");
    }
}
