//! ASCII mathematics in prose: `r^2`, `omega`, `sqrt(`, `I_xx` written as text where `$…$`
//! would typeset them. It is not an error (the text prints as written), so `check` and `build`
//! warn at its line, once a field, with the way to write it.

use super::{Validator, content_start};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawScene, Text};

/// Greek letters' names, which in prose are almost always a symbol written out.
const GREEK: &[&str] = &[
    "alpha", "beta", "gamma", "delta", "epsilon", "theta", "lambda", "mu", "nu", "rho", "sigma",
    "tau", "phi", "psi", "omega", "Gamma", "Delta", "Theta", "Lambda", "Sigma", "Phi", "Psi",
    "Omega",
];

/// Functions a page sets upright, which LaTeX writes as commands: `\sin(\alpha)`.
const FUNCTIONS: &[&str] = &["sin", "cos", "tan", "exp", "log", "ln"];

/// The first ASCII mathematics in `text` outside its `$…$` and its backticks: its byte offset
/// and the characters around it, as the author wrote them.
pub fn ascii_math(text: &str) -> Option<(usize, String)> {
    let bytes = text.as_bytes();
    let (mut in_math, mut in_code) = (false, false);
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        match c {
            b'\\' if bytes.get(i + 1) == Some(&b'$') => {
                i += 2;
                continue;
            }
            b'$' if !in_code => in_math = !in_math,
            b'`' if !in_math => in_code = !in_code,
            // A problem's `{name}`, which the variant's value replaces.
            b'{' if !in_math && !in_code => {
                if let Some(close) = text[i..].find('}') {
                    i += close + 1;
                    continue;
                }
            }
            _ if in_math || in_code || !text.is_char_boundary(i) => {}
            _ => {
                if let Some(found) = math_at(text, i) {
                    return Some((i, found));
                }
            }
        }
        i += 1;
    }
    None
}

/// ASCII mathematics starting at byte `i`, if any: the word around it.
fn math_at(text: &str, i: usize) -> Option<String> {
    let bytes = text.as_bytes();
    let word_char = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    let starts_word = i == 0 || !word_char(bytes[i - 1]);
    let rest = &text[i..];
    let found = if bytes[i] == b'^' {
        // A power or a transpose: r^2, A^T, A^-1, (…)^2.
        let before =
            i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || b")]}".contains(&bytes[i - 1]));
        let after = bytes
            .get(i + 1)
            .is_some_and(|b| b.is_ascii_alphanumeric() || b"-({".contains(b));
        before && after
    } else if starts_word && rest.starts_with("sqrt(") {
        true
    } else if starts_word && bytes[i].is_ascii_alphanumeric() {
        let word: &str = &rest[..rest
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .unwrap_or(rest.len())];
        let after = &rest[word.len()..];
        // A rate written with a prime: x', u'' (but not the top's).
        let primed = word.len() == 1
            && after.starts_with('\'')
            && !after[1..].starts_with(|c: char| c.is_ascii_alphabetic());
        // `phi1`, `w3`: a Greek name or a small letter with a number for its index.
        let stem = word.trim_end_matches(|c: char| c.is_ascii_digit());
        let indexed = stem.len() < word.len()
            && (GREEK.contains(&stem)
                || (stem.len() == 1 && stem.as_bytes()[0].is_ascii_lowercase()));
        if let Some(len) = operation(word, after) {
            let end = i + word.len() + len;
            return Some(text[i..end + more_math(&text[end..])].to_string());
        }
        GREEK.contains(&word) || subscripted(word) || primed || indexed
    } else {
        false
    };
    found.then(|| around(text, i))
}

/// `T - V`, `x = 1`, `L/2`, `1/w3`: a letter or a number, an operator, and another, where
/// one side of a `/` is a number. The length of what follows `word`, if it is one.
fn operation(word: &str, after: &str) -> Option<usize> {
    let operand = |w: &str| {
        (w.len() == 1 && w.as_bytes()[0].is_ascii_alphabetic())
            || (!w.is_empty() && w.bytes().all(|b| b.is_ascii_digit()))
    };
    let next = |rest: &str| -> String {
        rest.chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect()
    };
    let ends = |rest: &str, w: &str| {
        rest[w.len()..]
            .chars()
            .next()
            .is_none_or(|c| c.is_whitespace() || ",.;:)".contains(c))
    };
    if !operand(word) {
        return None;
    }
    if let Some(rest) = [" - ", " + ", " = "]
        .iter()
        .find_map(|op| after.strip_prefix(op))
    {
        let w = next(rest);
        let letter = |w: &str| w.bytes().any(|b| b.is_ascii_alphabetic());
        return (operand(&w) && ends(rest, &w) && (letter(word) || letter(&w)))
            .then_some(3 + w.len());
    }
    if let Some(rest) = after.strip_prefix('/') {
        let w = next(rest);
        let number = |w: &str| !w.is_empty() && w.bytes().all(|b| b.is_ascii_digit());
        let short = w.len() <= 3 && w.starts_with(|c: char| c.is_ascii_alphabetic());
        let letter = word.len() == 1 && word.as_bytes()[0].is_ascii_alphabetic();
        return ((number(word) && short) || (number(&w) && letter && ends(rest, &w)))
            .then_some(1 + w.len());
    }
    None
}

/// How much of `rest` continues a formula found before it, word by word: `L = I omega` is
/// suggested whole, not as `$L = I$`. A word continues it when it is a letter, a Greek name
/// (with an index), a number, an operator, or holds a power.
fn more_math(rest: &str) -> usize {
    let mut taken = 0;
    while let Some(after_space) = rest[taken..].strip_prefix(' ') {
        let word: &str = after_space
            .split(|c: char| c.is_whitespace() || ",;:".contains(c))
            .next()
            .unwrap_or("");
        let word = word.trim_end_matches('.');
        let bare = word.trim_matches(['(', ')']);
        let stem = bare.trim_end_matches(|c: char| c.is_ascii_digit());
        let mathy = !bare.is_empty()
            && ((bare.len() == 1 && bare.is_ascii())
                || GREEK.contains(&stem)
                || bare.bytes().all(|b| b.is_ascii_digit())
                || bare.contains('^'));
        if !mathy || word.matches('(').count() != word.matches(')').count() {
            break;
        }
        taken += 1 + word.len();
    }
    taken
}

/// `I_xx`, `omega_z`, `delta_jk`: letters, `_`, then a letter or digit.
fn subscripted(word: &str) -> bool {
    word.split_once('_').is_some_and(|(head, tail)| {
        !head.is_empty()
            && head.chars().all(|c| c.is_ascii_alphabetic())
            && tail
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_alphanumeric())
    })
}

/// A first LaTeX for ASCII mathematics, for the message: Greek names as commands, a subscript
/// in braces, `sqrt(x)` as `\sqrt{x}`.
fn latex_for(found: &str) -> String {
    let mut out = String::new();
    let mut rest = found;
    while let Some(start) = rest.find(|c: char| c.is_ascii_alphabetic()) {
        out.push_str(&rest[..start]);
        rest = &rest[start..];
        let end = rest
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .unwrap_or(rest.len());
        let word = &rest[..end];
        rest = &rest[end..];
        let stem = word.trim_end_matches(|c: char| c.is_ascii_digit());
        let (head, sub) = match word.split_once('_') {
            Some((h, s)) if subscripted(word) => (h, Some(s)),
            // `phi1`, `w3`: the number as an index.
            _ if !stem.is_empty() && stem.len() < word.len() => (stem, Some(&word[stem.len()..])),
            _ => (word, None),
        };
        if head == "sqrt" && rest.starts_with('(') {
            let close = rest.find(')').unwrap_or(rest.len() - 1);
            out.push_str(&format!("\\sqrt{{{}}}", &rest[1..close]));
            rest = rest.get(close + 1..).unwrap_or("");
            continue;
        }
        let command = |w: &str| match GREEK.contains(&w) || FUNCTIONS.contains(&w) {
            true => format!("\\{w}"),
            false => w.to_string(),
        };
        out.push_str(&command(head));
        if let Some(sub) = sub {
            out.push_str(&format!("_{{{}}}", command(sub)));
        }
    }
    out.push_str(rest);
    out
}

/// The run of characters without spaces around byte `i`, without the punctuation that ends a
/// sentence or a clause.
fn around(text: &str, i: usize) -> String {
    let start = text[..i].rfind(char::is_whitespace).map_or(0, |s| s + 1);
    let end = text[i..]
        .find(char::is_whitespace)
        .map_or(text.len(), |e| i + e);
    let mut found = text[start..end].trim_end_matches(['.', ',', ';', ':']);
    // A bracket the run opens or closes beyond it: `(R^2` of "(R^2 + r^2)" is `R^2`.
    let (open, close) = (found.matches('(').count(), found.matches(')').count());
    if open > close {
        found = found.strip_prefix('(').unwrap_or(found);
    } else if close > open {
        found = found.strip_suffix(')').unwrap_or(found);
    }
    found.to_string()
}

impl Validator<'_> {
    /// A warning for the first ASCII mathematics of a prose field, at its place.
    fn ascii_math_in(&self, t: &Text, field: &str, out: &mut Vec<SceneError>) {
        if let Some((at, found)) = ascii_math(t.get_ref()) {
            out.push(self.err(
                content_start(t) + at,
                field,
                format!(
                    "`{found}` is mathematics written as text: write it in LaTeX between `$` \
                     signs, `${}$`, so that the page and the PDF typeset it",
                    latex_for(&found)
                ),
            ));
        }
    }

    /// Warnings for the ASCII mathematics in the scene's prose: its title, its bodies' and
    /// answers' labels, its claims' statements, its steps' reasons and its problem's statement.
    pub(super) fn ascii_math_warnings(&self, raw: &RawScene) -> Vec<SceneError> {
        let mut out = Vec::new();
        self.ascii_math_in(&raw.title, "title", &mut out);
        for (i, b) in raw.bodies.iter().enumerate() {
            if let Some(label) = &b.get_ref().label {
                self.ascii_math_in(label, &format!("body[{i}].label"), &mut out);
            }
        }
        for (table, names) in [("symbols", &raw.symbols), ("coordinates", &raw.coordinates)] {
            for (name, meaning) in names {
                let field = format!("{table}.{}", name.get_ref());
                self.ascii_math_in(&crate::scene::raw::meaning_of(meaning), &field, &mut out);
            }
        }
        for (i, c) in raw.claims.iter().enumerate() {
            let field = format!("claim[{i}].statement");
            self.ascii_math_in(&c.get_ref().statement, &field, &mut out);
        }
        for (i, s) in raw.steps.iter().enumerate() {
            if let Some(why) = &s.get_ref().why {
                self.ascii_math_in(why, &format!("step[{i}].why"), &mut out);
            }
        }
        if let Some(p) = &raw.problem {
            let p = p.get_ref();
            self.ascii_math_in(&p.statement, "problem.statement", &mut out);
            for (i, a) in p.answers.get_ref().iter().enumerate() {
                if let Some(label) = &a.get_ref().label {
                    self.ascii_math_in(label, &format!("problem.answers[{i}].label"), &mut out);
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::ascii_math;

    #[test]
    fn powers_greek_names_roots_and_subscripts_are_found_outside_dollars() {
        let found = |t: &str| ascii_math(t).map(|(_, s)| s);
        assert_eq!(found("L = m r^2 omega."), Some("L = m r^2 omega".into()));
        assert_eq!(found("then m r^2 omega."), Some("r^2".into()));
        assert_eq!(found("so A T A^-1 = A T A^T"), Some("A^-1".into()));
        assert_eq!(found("tilted by theta, about x"), Some("theta".into()));
        assert_eq!(
            found("the period is 2 pi sqrt(l/g)"),
            Some("sqrt(l/g)".into())
        );
        assert_eq!(found("I_xx = m (r^2 - x^2)"), Some("I_xx".into()));
        assert_eq!(found("(a + b)^2 grows"), Some("a + b".into()));
        assert_eq!(found("(ab)^2 grows"), Some("(ab)^2".into()));
        // Typeset, quoted as code, escaped or English: nothing.
        assert_eq!(found("$L = m r^2 \\omega$, about $I_{xx}$"), None);
        assert_eq!(found("the step `acc_x`, at \\$5"), None);
        assert_eq!(found("the omegaless alphabet, a deltoid"), None);
        assert_eq!(found("a snake_ case and x_ alone"), None);
        assert_eq!(found("turned by {alpha} about y, mass {M_1}"), None);
        assert_eq!(found("the tilt turns where u' = 0"), Some("u'".into()));
        assert_eq!(found("the top's spin and a 'quoted' word"), None);
        // Within a character of two bytes or more, nothing is looked for.
        assert_eq!(found("kg m² about, kg·m², a ² alone"), None);
        assert_eq!(found("µ omega"), Some("omega".into()));
    }

    #[test]
    fn indexed_names_and_operations_between_letters_are_found() {
        let found = |t: &str| ascii_math(t).map(|(_, s)| s);
        assert_eq!(found("the equations of phi1 and phi2"), Some("phi1".into()));
        assert_eq!(found("a top spinning at w3"), Some("w3".into()));
        assert_eq!(found("T - V, as always"), Some("T - V".into()));
        assert_eq!(found("where x = 0."), Some("x = 0".into()));
        assert_eq!(found("the centre at L/2 below"), Some("L/2".into()));
        assert_eq!(found("small, as 1/w3 is"), Some("1/w3".into()));
        // English, units and paper sizes: nothing.
        assert_eq!(found("A4 paper, a step, and/or 9.81 m/s"), None);
        assert_eq!(found("a - as in a dash - here"), None);
        assert_eq!(found("lecture 3/4, in 2 - 3 weeks"), None);
    }

    /// Each suggestion is a whole formula whose brackets pair, that the pages' reader reads.
    #[test]
    fn a_suggestion_is_whole_latex_that_reads_back() {
        let suggested = |t: &str| super::latex_for(&ascii_math(t).unwrap().1);
        assert_eq!(suggested("a moment of (R^2 + r^2)/4"), "R^2");
        assert_eq!(suggested("the slope sin(alpha) sets it"), "\\sin(\\alpha)");
        assert_eq!(suggested("so L = I omega, along the axis"), "L = I \\omega");
        assert_eq!(suggested("the momentum p_phi is conserved"), "p_{\\phi}");
        for latex in ["R^2", "\\sin(\\alpha)", "L = I \\omega", "p_{\\phi}"] {
            assert!(crate::notation::Tex::read(latex).is_ok(), "{latex}");
        }
    }

    #[test]
    fn the_message_suggests_the_latex() {
        assert_eq!(super::latex_for("omega_z^2"), "\\omega_{z}^2");
        assert_eq!(super::latex_for("sqrt(l/g)"), "\\sqrt{l/g}");
        assert_eq!(super::latex_for("A^T"), "A^T");
    }
}
