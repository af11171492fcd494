//! One math notation for every output. A formula is a tree: mechbook's own [`Formula`] (whose
//! leaves are exact expressions), or LaTeX read once by the one reader ([`latex`], on
//! pulldown-latex's parser) into a [`Tex`]. Printers go from the trees: MathML for the pages,
//! Typst for the PDFs, text for the terminal, LaTeX for Moodle. A scene's own typesetting of
//! its names reaches every printer as one value, [`Names`].

mod expr_latex;
mod expr_tree;
mod formula;
mod formula_print;
mod formula_tree;
pub mod latex;
pub mod linebreak;
#[cfg(test)]
mod linebreak_tests;
pub mod mathml;
mod names;
mod product_cut;
#[cfg(test)]
pub mod random_expr;
pub mod read_back;
mod spoken;
mod tex_text;
mod tree;
pub mod typst;
mod width;

pub use expr_latex::printed_length;
pub use expr_tree::{expr_nodes, symbol_tex};
pub use formula::{Accent, Formula, Name, Op};
pub use latex::{Node, Tex, TexError};
pub use mathml::MathmlError;
pub use names::Names;
