//! One math notation for every output. A formula is a tree: mechbook's own [`Formula`] (whose
//! leaves are exact expressions), or LaTeX read once by the one reader ([`latex`], on
//! pulldown-latex's parser) into a [`Tex`]. Printers go from the trees: MathML for the pages,
//! Typst for the PDFs, text for the terminal, LaTeX for Moodle.

mod expr_tree;
mod formula;
mod formula_print;
mod formula_tree;
mod formula_typst;
pub mod latex;
pub mod linebreak;
#[cfg(test)]
mod linebreak_tests;
pub mod mathml;
mod product_cut;
pub mod read_back;
mod spoken;
mod tex_text;
mod tree;
pub mod typst;
mod width;

pub use expr_tree::{expr_nodes, symbol_tex};
pub use formula::{Accent, Formula, Name, Op};
pub use latex::{Node, Tex, TexError};
pub use mathml::MathmlError;

use crate::base::typst::typst_string;
use crate::cas::SymbolTex;
use std::collections::BTreeMap;

/// Runs `f` with the scene's own typesetting of its names (name -> LaTeX), read here into the
/// forms each printer writes, so that every formula of its page prints them so.
pub fn typeset_as<R>(names: &BTreeMap<String, String>, f: impl FnOnce() -> R) -> R {
    let mut trees = BTreeMap::new();
    let names = names
        .iter()
        .map(|(name, latex)| {
            // Scene validation refuses a `tex` the reader cannot read or set, so the fallbacks
            // (the LaTeX as text) are never printed.
            let (typst, nodes) = match Tex::read(latex) {
                Ok(tex) => (
                    tex.to_typst().unwrap_or_else(|_| typst_string(latex)),
                    tex.nodes,
                ),
                Err(_) => (typst_string(latex), vec![Node::Text(latex.clone())]),
            };
            trees.insert(name.clone(), nodes);
            let tex = SymbolTex {
                latex: latex.clone(),
                typst,
            };
            (name.clone(), tex)
        })
        .collect();
    expr_tree::with_scene_names(trees, || crate::cas::typeset_as(names, f))
}
