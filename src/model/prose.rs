//! A sentence with formulas in it. Each formula stays a tree ([`Formula`]) until an output
//! prints it: as text for the terminal and JSON, as LaTeX (then MathML) for the pages.

use crate::cas::Expr;
use crate::notation::{Formula, Names};

#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Prose(pub Vec<Piece>);

#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Piece {
    Text(String),
    Math(Formula),
}

impl Prose {
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    pub fn text(mut self, s: &str) -> Prose {
        self.0.push(Piece::Text(s.to_string()));
        self
    }

    /// Text with its mathematics in `$…$`, read as an author's is.
    pub fn words(mut self, s: &str) -> Prose {
        self.0.extend(author(s).0);
        self
    }

    /// A formula in the notation of [`Formula::parse`].
    pub fn math(self, notation: &str) -> Prose {
        self.formula(Formula::parse(notation, &[]))
    }

    /// An exact expression, as the expression printers print it.
    pub fn expr(self, e: &Expr) -> Prose {
        self.formula(Formula::Expr(e.clone()))
    }

    pub fn formula(mut self, f: Formula) -> Prose {
        self.0.push(Piece::Math(f));
        self
    }

    /// The sentence with its first letter a capital, as a lead or a heading: "the rod's
    /// moment" becomes "The rod's moment"; a sentence that opens with a formula is kept.
    pub fn capitalised(mut self) -> Prose {
        if let Some(Piece::Text(t)) = self.0.first_mut() {
            let mut c = t.chars();
            if let Some(f) = c.next() {
                *t = f.to_uppercase().chain(c).collect();
            }
        }
        self
    }

    /// Text run on into the last piece where that is text, as an author's sentence is one
    /// piece between its formulas: a heading built in parts sets as one written whole.
    pub fn run_on(mut self, s: &str) -> Prose {
        if s.is_empty() {
            return self;
        }
        match self.0.last_mut() {
            Some(Piece::Text(t)) => t.push_str(s),
            _ => self.0.push(Piece::Text(s.to_string())),
        }
        self
    }

    /// `other` after this sentence, its first text run on (see [`Prose::run_on`]).
    pub fn then(mut self, other: Prose) -> Prose {
        for piece in other.0 {
            self = match piece {
                Piece::Text(t) => self.run_on(&t),
                math => {
                    self.0.push(math);
                    self
                }
            };
        }
        self
    }

    /// The sentence as an author writes one: its formulas in `$…$` (an author's as written,
    /// mechbook's in its LaTeX with the scene's `names`), a dollar sign in the text as `\$`.
    /// `author` reads it back.
    pub fn to_author_text(&self, names: &Names) -> String {
        self.0
            .iter()
            .map(|p| match p {
                Piece::Text(s) => s.replace('$', "\\$"),
                Piece::Math(Formula::Tex(t)) => format!("${}$", t.source),
                Piece::Math(f) => format!("${}$", f.to_latex(names)),
            })
            .collect()
    }

    /// The sentence as plain Unicode, for where markup cannot go (see [`plain`]).
    pub fn to_plain(&self, names: &Names) -> String {
        self.0
            .iter()
            .map(|p| match p {
                Piece::Text(s) => s.clone(),
                Piece::Math(Formula::Text(s)) => s.clone(),
                Piece::Math(f) => f.to_tex(names).to_plain(),
            })
            .collect()
    }

    /// The sentence as plain text, formulas in their text form.
    pub fn to_text(&self) -> String {
        self.0
            .iter()
            .map(|p| match p {
                Piece::Text(s) => s.clone(),
                Piece::Math(f) => f.to_text(),
            })
            .collect()
    }
}

/// An author's text with its `$…$` spans: each span the LaTeX inside it (read as a [`Formula::Tex`]),
/// the rest text; `\$` is a dollar sign. Validation has seen that every `$` is closed.
pub fn author(text: &str) -> Prose {
    let mut out = Prose::default();
    for (k, part) in dollar_split(text).into_iter().enumerate() {
        if k % 2 == 0 {
            if !part.is_empty() {
                out = out.text(&part);
            }
        } else {
            out = out.formula(Formula::author(&part));
        }
    }
    out
}

/// The text between unescaped `$` signs: text, mathematics, text, ... (`\$` a dollar sign in
/// text). An odd count of parts means every `$` was closed.
/// An author's text as plain Unicode, for where markup cannot go (a page's `<title>`, a link,
/// alt text): each `$…$` as its formula's text (`$\alpha$` is α).
pub fn plain(text: &str) -> String {
    if !text.contains('$') {
        return text.to_string();
    }
    let mut out = String::new();
    for (k, part) in dollar_split(text).iter().enumerate() {
        if k % 2 == 1 {
            match crate::notation::Tex::read(part) {
                Ok(tex) => out.push_str(&tex.to_plain()),
                Err(_) => out.push_str(part),
            }
        } else {
            out.push_str(part);
        }
    }
    out
}

pub fn dollar_split(text: &str) -> Vec<String> {
    let mut parts = vec![String::new()];
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' if chars.peek() == Some(&'$') => {
                chars.next();
                parts.last_mut().expect("one part at least").push('$');
            }
            '$' => parts.push(String::new()),
            c => parts.last_mut().expect("one part at least").push(c),
        }
    }
    parts
}

impl From<String> for Prose {
    fn from(text: String) -> Prose {
        Prose(vec![Piece::Text(text)])
    }
}

impl std::fmt::Display for Prose {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.to_text())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cas::Expr;
    use crate::notation::{Formula, Names};

    /// An author's sentence printed back as an author writes it reads the same: its formulas
    /// as written, a dollar sign escaped.
    #[test]
    fn an_authors_sentence_prints_back_as_written() {
        for text in [
            r"Rate of $\vec L$ relative to the body",
            r"$H = (C - A)/C$ solved for $C$",
            r"costs \$3, with $x$",
            "no mathematics at all",
        ] {
            let prose = author(text);
            assert_eq!(prose.to_author_text(Names::none()), text);
            assert_eq!(author(&prose.to_author_text(Names::none())), prose);
        }
    }

    /// A heading built in parts is one text between its formulas, as the author's would be,
    /// and a name put in as an expression prints with the scene's own `tex`.
    #[test]
    fn a_heading_built_in_parts_runs_its_text_on() {
        let q = Prose::default().expr(&Expr::sym("q1"));
        let title = Prose::default()
            .text("L")
            .run_on(": ")
            .then(Prose::default().text("the equation of motion of ").then(q))
            .run_on("")
            .run_on(" (eq 3)");
        assert_eq!(title.0.len(), 3, "{title:?}");
        assert_eq!(
            title.to_author_text(Names::none()),
            "L: the equation of motion of $q_{1}$ (eq 3)"
        );
        assert_eq!(
            title.to_plain(Names::none()),
            "L: the equation of motion of q_1 (eq 3)"
        );
        let names = Names::of(&[("q1".to_string(), r"\theta".to_string())].into());
        assert_eq!(
            title.to_author_text(&names),
            r"L: the equation of motion of $\theta$ (eq 3)"
        );
        assert_eq!(
            title.to_plain(&names),
            "L: the equation of motion of θ (eq 3)"
        );
        // A formula the reader refused stays as written in plain text.
        let refused = Prose::default().formula(Formula::Text(r"\frac{".into()));
        assert_eq!(refused.to_plain(Names::none()), r"\frac{");
    }
}
