//! A result's symbol: a step's name that would print as a word (`Lag`, `space_rate`: set
//! upright, read by a student as mechbook's own name), and two steps that print one symbol. Not
//! errors (the page still reads), so `check` and `build` warn at the step's line with a `tex`
//! to write, as the ASCII lint does.

use super::{Validator, content_start};
use crate::cas::{Expr, greek_letter, prints_as_word};
use crate::scene::error::SceneError;
use crate::scene::operations::Solve;
use crate::scene::operations::{Holds, Several};
use crate::scene::raw::RawScene;
use crate::scene::{AuthorStep, Operation};
use std::collections::BTreeMap;

impl Validator<'_> {
    /// Warnings for the steps whose result prints under a word, or under a symbol that another
    /// step or a symbol of the scene already prints as. `tex` is the scene's typesetting.
    pub(super) fn symbol_name_warnings(
        &self,
        raw: &RawScene,
        steps: &[AuthorStep],
        tex: &BTreeMap<String, String>,
    ) -> Vec<SceneError> {
        let own = |n: &str| tex.contains_key(n);
        let mut out = Vec::new();
        // Each printed symbol (its LaTeX) and who prints it first: the symbols, then the steps.
        let mut printed: BTreeMap<String, String> = BTreeMap::new();
        for name in raw.symbols.keys().chain(raw.coordinates.keys()) {
            let latex = printed_latex(name.get_ref(), tex);
            printed
                .entry(latex)
                .or_insert_with(|| format!("the symbol `{}`", name.get_ref()));
        }
        for (i, (s, step)) in raw.steps.iter().zip(steps).enumerate() {
            if let Some(word) = step.names.iter().find(|n| prints_as_word(n, &own)) {
                out.push(self.err(
                    s.get_ref().names.as_ref().map_or(0, |n| n.span().start),
                    &format!("step[{i}].names"),
                    format!(
                        "step `{}` has no `tex`: its result `{word}` would be printed as the \
                         word `{word}`; give the step the symbol the notes write (`tex = \
                         \"\\\\dot\\\\phi\"`), and each result prints as that symbol with \
                         its name below it",
                        step.name
                    ),
                ));
            }
            if !prints_its_name(step, steps) {
                continue;
            }
            let name = &s.get_ref().name;
            let field = format!("step[{i}].name");
            if prints_as_word(name.get_ref(), &own) {
                out.push(self.err(
                    content_start(name),
                    &field,
                    format!(
                        "step `{n}` has no `tex`: its result would be printed under the word \
                         `{n}`, which a student reads as a name of the program's; give it the \
                         symbol the notes write, such as `tex = \"{}\"`",
                        suggested_tex(name.get_ref()).replace('\\', "\\\\"),
                        n = name.get_ref()
                    ),
                ));
                continue;
            }
            let latex = printed_latex(name.get_ref(), tex);
            match printed.get(&latex) {
                Some(first) => out.push(self.err(
                    content_start(name),
                    &field,
                    format!(
                        "step `{}` prints as `{latex}`, as {first} does: a reader cannot tell \
                         the two apart; give one of them another `tex`",
                        name.get_ref()
                    ),
                )),
                None => {
                    printed.insert(latex, format!("step `{}`", name.get_ref()));
                }
            }
        }
        out
    }
}

/// Whether a step's page prints its name: `name = result`, or its results `name_1`, `name_2`, ….
/// Equations of motion print `… = 0`, states of rest and several unknowns their coordinates'
/// names, a stability its Ω². Read from the table of operations.
pub fn prints_its_name(step: &AuthorStep, steps: &[AuthorStep]) -> bool {
    let kind = step.op.kind();
    match (kind.holds, kind.several) {
        (Holds::Operand, _) => !matches!(step.holding(steps), Holds::Motion | Holds::Linear),
        (_, Several::States) => false,
        (_, Several::Roots) => {
            !matches!(&step.op, Operation::Solve(Solve { unknowns, .. }) if unknowns.len() > 1)
        }
        (Holds::Expression, _) => true,
        (Holds::Motion | Holds::Linear | Holds::Equilibria, _) => false,
    }
}

/// The LaTeX a name prints as: the scene's own, else the conventions' (`w1` is `\omega_{1}`).
fn printed_latex(name: &str, tex: &BTreeMap<String, String>) -> String {
    match tex.get(name) {
        Some(own) => own.split_whitespace().collect::<Vec<_>>().join(" "),
        None => Expr::sym(name).to_latex(crate::notation::Names::none()),
    }
}

/// A symbol to suggest for a name that prints as a word: a Greek letter it names, else its
/// first letter, with the rest of a longer name as an upright subscript (`slow_eps` is
/// `\epsilon_{\mathrm{slow}}`, `Lfree` `L_{\mathrm{free}}`, `Lag` `L`).
pub fn suggested_tex(name: &str) -> String {
    let name = name.trim_end_matches('\'');
    let words: Vec<&str> = name.split('_').filter(|w| !w.is_empty()).collect();
    let greek = words
        .iter()
        .position(|w| greek_letter(w).is_some() || matches!(*w, "eps" | "om" | "th"));
    let (head, rest): (String, Vec<&str>) = match greek {
        Some(k) => {
            let letter = match words[k] {
                "eps" => "epsilon",
                "om" => "omega",
                "th" => "theta",
                w => w,
            };
            let others = words
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != k)
                .map(|(_, w)| *w);
            (format!("\\{letter}"), others.collect())
        }
        None => {
            let first = words.first().copied().unwrap_or(name);
            let (letter, tail) = first.split_at(first.chars().next().map_or(0, char::len_utf8));
            // A word is its first letter (`acc` a, `period` p); a capital before a word
            // (`Lfree`) keeps the word as its subscript.
            let capital_then_word = letter.chars().all(|c| c.is_ascii_uppercase())
                && tail.len() >= 3
                && tail.chars().all(|c| c.is_ascii_lowercase());
            let mut rest: Vec<&str> = if words.len() == 1 && capital_then_word {
                vec![tail]
            } else {
                Vec::new()
            };
            rest.extend(words.iter().skip(1));
            (letter.to_string(), rest)
        }
    };
    match rest.as_slice() {
        [] => head,
        [digits] if digits.chars().all(|c| c.is_ascii_digit()) => format!("{head}_{{{digits}}}"),
        words => format!("{head}_{{\\mathrm{{{}}}}}", words.join("\\,")),
    }
}

#[cfg(test)]
mod tests {
    use super::suggested_tex;

    #[test]
    fn a_word_is_suggested_a_letter_with_the_rest_as_its_subscript() {
        crate::base::assert_each(
            suggested_tex,
            &[
                ("Lag", "L"),
                ("acc", "a"),
                ("period", "p"),
                ("Lfree", "L_{\\mathrm{free}}"),
                ("slow_eps", "\\epsilon_{\\mathrm{slow}}"),
                ("space_rate", "s_{\\mathrm{rate}}"),
                ("w_min", "w_{\\mathrm{min}}"),
                ("Omega_top", "\\Omega_{\\mathrm{top}}"),
            ],
        );
    }
}
