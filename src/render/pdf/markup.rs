//! Writing Typst markup: every piece of text goes in as a string literal (`#"…"`), so nothing an
//! author writes is read as markup, and every formula is printed by the Typst printers of the
//! expression tree.

use super::super::RenderError;
use crate::base::literal::typst_string;
use crate::cas::Expr;
use crate::model::prose::{Piece, Prose};
use crate::notation::{Formula, Names, Tex, linebreak};
use crate::scene::{Course, Paper};

/// A document being written, and where each scene's part of it starts (for Typst's errors).
#[derive(Default)]
pub struct Markup {
    pub text: String,
    origins: Vec<(usize, String)>,
    /// Whether the sheets' heading rules are set (`sheet::sheet_headings`): once a document.
    pub sheet_headings: bool,
    /// The names of the scene whose part is being written ([`Markup::scene_part`]), as it
    /// typesets them; none between scenes.
    names: Names,
}

impl Markup {
    pub fn new(preamble: String) -> Markup {
        Markup {
            text: preamble,
            origins: Vec::new(),
            sheet_headings: false,
            names: Names::default(),
        }
    }

    /// An empty part of a scene's markup, its formulas setting the scene's names as `names`.
    pub fn of_scene(names: &Names) -> Markup {
        Markup {
            names: names.clone(),
            ..Markup::default()
        }
    }

    /// The markup `write` adds comes from the scene at `source`, line `line`, whose formulas
    /// set its names as `names`.
    pub fn scene_part<T>(
        &mut self,
        source: &std::path::Path,
        line: usize,
        names: &Names,
        write: impl FnOnce(&mut Self) -> T,
    ) -> T {
        self.origins
            .push((self.text.len(), format!("{}:{line}", source.display())));
        self.names = names.clone();
        let out = write(self);
        // What follows is mechbook's own, until the next scene.
        self.names = Names::default();
        self.origins.push((self.text.len(), String::new()));
        out
    }

    /// The document to typeset at `path`, with the pictures it shows.
    pub fn source(self, path: &str, images: Vec<(String, Vec<u8>)>) -> super::PdfSource {
        super::PdfSource {
            path: path.to_string(),
            markup: self.text,
            images,
            origins: self.origins,
        }
    }

    /// Text, as written: a string literal, so no character of it is markup.
    pub fn text(&mut self, s: &str) -> &mut Self {
        if !s.is_empty() {
            self.text.push('#');
            self.text.push_str(&typst_string(s));
            // A following `(` or `[` would read as the string's arguments.
            self.text.push_str("#[]");
        }
        self
    }

    /// Markup of mechbook's own (`#v(2em)`, `*…*`, a newline).
    pub fn raw(&mut self, s: &str) -> &mut Self {
        self.text.push_str(s);
        self
    }

    pub fn line(&mut self) -> &mut Self {
        self.text.push('\n');
        self
    }

    /// A formula in the line, with its spoken form (`alt`) as the PDF's alternative
    /// description. One with a fraction is set in the display style (`tall`, in the preamble):
    /// in the text style a fraction's indices are half the body's size, too small to read on
    /// paper.
    pub fn inline(&mut self, typst_math: &str, alt: &str) -> &mut Self {
        self.alt(alt);
        let tall = typst_math.contains("frac(") && !typst_math.starts_with("display(");
        if tall {
            self.text.push_str("#tall($display(");
            self.text.push_str(typst_math);
            // A following `(` or `[` would read as the call's arguments.
            self.text.push_str(")$)#[]");
        } else {
            self.text.push('$');
            self.text.push_str(typst_math);
            self.text.push('$');
        }
        self.text.push_str("]#[]");
        self
    }

    /// A formula in the line, set at its full size (a matrix or a column, which the line would
    /// shrink).
    pub fn display(&mut self, typst_math: &str, alt: &str) -> &mut Self {
        self.inline(&format!("display({typst_math})"), alt)
    }

    /// A formula on a line of its own, centred. One wider than the line is set in the pieces the
    /// page cuts it into (`linebreak::pieces`: at its sums and equals signs, a long bracket
    /// opened, a long numerator as a factor), in a paragraph with a hanging indent that wraps
    /// between them (`fit`, in the preamble): one line breaker for the page and the paper.
    /// A formula surely narrower than any line is set as a fitting one is, without measuring it
    /// first (`narrow`, in the preamble): the same bytes, one layout fewer.
    pub fn block(&mut self, tex: &Tex, alt: &str) -> Result<&mut Self, RenderError> {
        let whole = math(tex)?;
        self.text.push('\n');
        self.alt(alt);
        if surely_narrow(tex) {
            self.text.push_str("\n#narrow($ ");
            self.text.push_str(&whole);
            self.text.push_str(" $)\n]\n");
            return Ok(self);
        }
        self.text.push_str("\n#fit($ ");
        self.text.push_str(&whole);
        self.text.push_str(" $, [");
        for (k, piece) in linebreak::pieces(&tex.nodes, linebreak::LINE)
            .iter()
            .enumerate()
        {
            let nodes = linebreak::set_apart(k, piece);
            if k > 0 {
                // Where the paragraph may break: before an operator, which brings its own
                // space, with none; after a comma, with a word space, as the page does.
                let operator = nodes.len() > piece.len();
                self.text.push_str(if operator { "#sym.zws" } else { " " });
            }
            let piece = Tex {
                source: tex.source.clone(),
                nodes,
            };
            self.alt(&piece.spoken());
            self.text.push_str("$display(");
            self.text.push_str(&math(&piece)?);
            self.text.push_str(")$]");
        }
        self.text.push_str("])\n]\n");
        Ok(self)
    }

    /// Opens a scope whose equations carry `alt` as their alternative description (a tagged
    /// PDF's, which PDF/UA-1 asks of every formula); the caller closes it with `]`.
    fn alt(&mut self, alt: &str) {
        self.text.push_str("#[#set math.equation(alt: ");
        self.text.push_str(&typst_string(alt));
        // The semicolon ends the rule: what follows is markup again.
        self.text.push_str(");");
    }

    /// A sentence: its text as text, its formulas printed from their trees.
    pub fn prose(&mut self, prose: &Prose) -> Result<&mut Self, RenderError> {
        for piece in &prose.0 {
            match piece {
                Piece::Text(t) => self.text(t),
                Piece::Math(f) => {
                    let (typst, said) = (formula(f, &self.names)?, f.to_tex(&self.names).spoken());
                    self.inline(&typst, &said)
                }
            };
        }
        Ok(self)
    }

    /// An author's text with its `$…$` mathematics.
    pub fn author(&mut self, text: &str) -> Result<&mut Self, RenderError> {
        self.prose(&crate::model::prose::author(text))
    }

    /// A heading at `level` (1 is the document's title).
    pub fn heading(&mut self, level: usize, title: &str) -> Result<&mut Self, RenderError> {
        // The document's title is not in its own contents.
        let outlined = if level == 1 { ", outlined: false" } else { "" };
        self.text
            .push_str(&format!("\n#heading(level: {level}{outlined})["));
        self.author(title)?;
        self.text.push_str("]\n");
        Ok(self)
    }

    /// A paragraph break.
    pub fn par(&mut self) -> &mut Self {
        self.text.push_str("\n\n");
        self
    }
}

/// A formula in Typst's math, printed from its tree.
pub fn formula(f: &Formula, names: &Names) -> Result<String, RenderError> {
    math(&f.to_tex(names))
}

/// A tree in Typst's math; what Typst's math cannot set (an author's colour) is an error naming
/// the formula.
pub fn math(t: &Tex) -> Result<String, RenderError> {
    t.to_typst().map_err(|e| RenderError::Math {
        latex: t.source.clone(),
        message: e.to_string(),
    })
}

/// An exact expression in Typst's math, printed from its tree.
pub fn expr(e: &Expr, names: &Names) -> String {
    typst(&e.to_tex(names))
}

/// A tree mechbook built, in Typst's math. It holds nothing Typst's math refuses: only an
/// author's colour is, and scene validation refuses that first.
pub(super) fn typst(t: &Tex) -> String {
    t.to_typst().unwrap_or_else(|_| typst_string(&t.source))
}

/// A symbol's name in words.
pub fn said_symbol(name: &str, names: &Names) -> String {
    Expr::sym(name).to_tex(names).spoken()
}

/// `name = value` in words.
pub fn said_equation(name: &str, value: &str, names: &Names) -> String {
    format!("{} equals {value}", said_symbol(name, names))
}

/// A symbol's name in Typst's math.
pub fn symbol(name: &str, names: &Names) -> String {
    expr(&Expr::sym(name), names)
}

/// A number's formula in Typst's math: digits, signs and powers, which every printer sets.
pub fn decimal_typst(f: &Formula) -> String {
    typst(&f.to_tex(Names::none()))
}

/// Whether Typst surely sets `tex` narrower than any line (`display_width`).
#[cfg(feature = "pdf")]
fn surely_narrow(tex: &Tex) -> bool {
    super::display_width::widest_em(tex)
        .is_some_and(|em| em <= super::display_width::NARROWER_THAN_ANY_LINE)
}

/// Without the PDFs nothing is typeset, and every formula is measured as before.
#[cfg(not(feature = "pdf"))]
fn surely_narrow(_: &Tex) -> bool {
    false
}

/// The page, fonts and running head and foot of every document: `head` at the top left of
/// each page, `right` at its top right, the page number and count at the foot.
pub fn preamble(course: &Course, title: &str, head: &str, right: &str) -> String {
    let paper = match course.paper {
        Paper::A4 => "a4",
        Paper::Letter => "us-letter",
    };
    format!(
        "#set document(title: {title}, author: {author})\n\
         #set page(paper: \"{paper}\", margin: (x: 18mm, top: 22mm, bottom: 20mm), \
         header: [#set text(8.5pt); #{head}#h(1fr)*#{right}*], \
         footer: context [#set text(8.5pt); #h(1fr)#counter(page).display(\"1 of 1\", both: true)])\n\
         #set text(font: \"New Computer Modern\", size: 10.5pt, lang: \"en\")\n\
         #set par(justify: false)\n\
         #show heading: set block(above: 1.4em, below: 0.7em)\n\
         #show heading.where(level: 1): set text(15pt)\n\
         #show heading.where(level: 2): set text(12.5pt)\n\
         #show heading.where(level: 3): set text(10.5pt)\n\
         #let tall(body) = {{ set text(top-edge: \"bounds\", bottom-edge: \"bounds\"); body }}\n\
         #let fit(whole, broken) = layout(size => {{ if measure(whole).width <= size.width {{ whole }} \
         else {{ block(width: 100%)[#set text(top-edge: \"bounds\", bottom-edge: \"bounds\"); \
         #par(hanging-indent: 2em, leading: 0.6em)[#sym.zws#broken]] }} }})\n\
         #let narrow(whole) = layout(size => whole)\n",
        title = typst_string(title),
        author = typst_string(&course.author),
        head = typst_string(head),
        right = typst_string(right),
    )
}
