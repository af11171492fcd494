//! How a scene typesets its names, as one value built once per scene and handed to every
//! printer: each name the scene gives a `tex` (`Omega = "\\Omega"`) read once by the one LaTeX
//! reader into its tree and its LaTeX; every other name follows the conventions
//! (`w1` is ω₁, `Ixx` is I_xx, a longer name upright). No printer reads a name's form from
//! anywhere else.

use super::latex::{Node, Tex};
use std::collections::BTreeMap;

/// A name the scene typesets itself.
#[derive(Debug, Clone, PartialEq)]
struct Own {
    latex: String,
    nodes: Vec<Node>,
}

/// A scene's own typesetting of its names; [`Names::none`] where a formula belongs to no scene.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Names {
    own: BTreeMap<String, Own>,
}

impl Names {
    /// The names as the scene writes them (name -> LaTeX), each read once.
    pub fn of(tex: &BTreeMap<String, String>) -> Names {
        let own = tex
            .iter()
            .map(|(name, latex)| {
                // Scene validation refuses a `tex` the reader cannot read or set, so the
                // fallback (the LaTeX as text) is never printed.
                let own = match Tex::read(latex) {
                    Ok(tex) => Own {
                        latex: latex.clone(),
                        nodes: tex.nodes,
                    },
                    Err(_) => Own {
                        latex: latex.clone(),
                        nodes: vec![Node::Text(latex.clone())],
                    },
                };
                (name.clone(), own)
            })
            .collect();
        Names { own }
    }

    /// No name of a scene's own: every name by the conventions.
    pub fn none() -> &'static Names {
        static NONE: Names = Names {
            own: BTreeMap::new(),
        };
        &NONE
    }

    /// Whether the scene typesets `name` itself (a `tex`).
    pub fn typesets(&self, name: &str) -> bool {
        self.own.contains_key(name)
    }

    /// The scene's LaTeX for `name`, if it gives one.
    pub fn latex(&self, name: &str) -> Option<&str> {
        self.own.get(name).map(|o| o.latex.as_str())
    }

    /// The scene's tree for `name`, if it gives one.
    pub fn nodes(&self, name: &str) -> Option<&[Node]> {
        self.own.get(name).map(|o| o.nodes.as_slice())
    }
}

#[cfg(test)]
mod tests {
    use super::Names;
    use crate::cas::Expr;
    use std::collections::BTreeMap;

    fn scene(pairs: &[(&str, &str)]) -> Names {
        let tex: BTreeMap<String, String> = pairs
            .iter()
            .map(|(n, l)| (n.to_string(), l.to_string()))
            .collect();
        Names::of(&tex)
    }

    /// A scene's own name, and a numbered result of a step it typesets (`acc_2` of `acc` with
    /// `tex = "a"` is a₂), print so in LaTeX, in Typst and as the pages' tree; without the
    /// scene's names the same expressions print by the conventions.
    #[test]
    fn every_printer_takes_the_scenes_names_from_the_value_it_is_given() {
        let names = scene(&[("acc", "a"), ("OmE", "\\Omega_{\\mathrm{E}}")]);
        let e = Expr::add(vec![Expr::sym("acc_2"), Expr::sym("OmE")]);
        assert_eq!(e.to_latex(&names), "{a}_{2} + \\Omega_{\\mathrm{E}}");
        assert_eq!(
            e.to_tex(&names).to_typst().unwrap(),
            "attach(a, b: 2)\\+attach(Ω, b: upright(\"E\"))"
        );
        // The tree sets a one-node name without the group its LaTeX puts it in: a₂.
        let read = crate::notation::Tex::read("a_{2} + \\Omega_{\\mathrm{E}}").unwrap();
        assert_eq!(e.to_tex(&names).nodes, read.nodes);
        // The same expression with no scene: words, upright.
        let plain = e.to_latex(Names::none());
        assert!(plain.contains("\\mathrm{acc}"), "{plain}");
        assert!(!plain.contains("\\Omega"), "{plain}");
        assert!(names.typesets("acc") && !names.typesets("acc_2"));
        assert!(!Names::none().typesets("acc"));
    }
}
