//! A sentence with formulas in it: each formula as text, for the terminal and JSON, and as
//! LaTeX, for the pages' MathML.

#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Prose(pub Vec<Piece>);

#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Piece {
    Text(String),
    Math { text: String, latex: String },
}

impl Prose {
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    pub fn text(mut self, s: &str) -> Prose {
        self.0.push(Piece::Text(s.to_string()));
        self
    }

    pub fn math(mut self, text: impl Into<String>, latex: impl Into<String>) -> Prose {
        self.0.push(Piece::Math {
            text: text.into(),
            latex: latex.into(),
        });
        self
    }

    /// The sentence as plain text, formulas in their text form.
    pub fn to_text(&self) -> String {
        self.0
            .iter()
            .map(|p| match p {
                Piece::Text(s) => s.as_str(),
                Piece::Math { text, .. } => text.as_str(),
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
