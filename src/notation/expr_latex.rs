//! An expression in LaTeX with the scene's names: the printing walk's LaTeX style
//! (`cas/print_latex.rs`) given each name the scene typesets from [`Names`].

use super::Names;
use crate::cas::Expr;

impl Expr {
    pub fn to_latex(&self, names: &Names) -> String {
        self.to_latex_named(names, &|_| None)
    }

    /// LaTeX with some symbols given a catalogue symbol: a claim's `inertia_tensor[0][1]`
    /// prints as I_{xy} when `named("inertia_tensor")` is `I`.
    pub fn to_latex_named(
        &self,
        names: &Names,
        named: &dyn Fn(&str) -> Option<&'static str>,
    ) -> String {
        self.latex_with(&|s| names.latex(s).map(str::to_string), named)
    }
}
