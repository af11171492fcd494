//! A sentence with formulas in it. Each formula stays a tree ([`Formula`]) until an output
//! prints it: as text for the terminal and JSON, as LaTeX (then MathML) for the pages.

use crate::cas::{Expr, Formula};

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
