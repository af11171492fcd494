//! Prose: titles, statements, labels and meanings. A control character in them is refused at
//! its field, because it is almost always TeX that TOML read as an escape: in a "…" string
//! `\beta` is a backspace and `eta`, `\frac` a form feed and `rac`, `\theta`, `\nu` and `\rho`
//! a tab, a newline and a carriage return. On a page it reads "tilted by eta"; in a Moodle file
//! it is XML that Moodle refuses.

use super::{Validator, content_start};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawScene, Text};

/// Why `value` is refused, if it is: `source` is the field's TOML text (quotes included),
/// which tells an escape from a real line break; `lines` allows real line breaks (a statement
/// written as a multi-line string).
pub fn control_character(value: &str, source: &str, lines: bool) -> Option<String> {
    // Where line breaks are allowed, only the source tells `\nu` from a real break.
    if lines && let Some(rest) = basic_escape_before_letter(source, 'n') {
        return Some(tex_message('n', "a line break", &rest));
    }
    let (at, c) = value
        .char_indices()
        .find(|&(_, c)| (c.is_control() && !(lines && c == '\n')) || noncharacter(c))?;
    let escape = match c {
        '\u{8}' => Some(('b', "a backspace")),
        '\u{c}' => Some(('f', "a form feed")),
        '\t' => Some(('t', "a tab")),
        '\n' => Some(('n', "a line break")),
        '\r' => Some(('r', "a carriage return")),
        _ => None,
    };
    let rest: String = value[at + c.len_utf8()..]
        .chars()
        .take_while(char::is_ascii_alphabetic)
        .collect();
    Some(match escape {
        Some((letter, name)) if !rest.is_empty() => tex_message(letter, name, &rest),
        Some((_, name)) => format!(
            "the text holds {name} (a control character), which a page or a Moodle file cannot \
             carry: remove it"
        ),
        None if noncharacter(c) => format!(
            "the text holds U+{:04X}, a noncharacter, which a Moodle file (XML) cannot carry: \
             remove it",
            u32::from(c)
        ),
        None => format!(
            "the text holds the control character U+{:04X}, which a page or a Moodle file \
             cannot carry: remove it",
            u32::from(c)
        ),
    })
}

/// A combining mark (an accent over nothing sets nothing): the combining diacritical marks and
/// those for symbols, which is what the printers' accents are.
fn combining_mark(c: char) -> bool {
    matches!(u32::from(c), 0x0300..=0x036F | 0x20D0..=0x20FF)
}

/// A Unicode noncharacter (U+FDD0 to U+FDEF, and the last two of every plane, U+FFFE and
/// U+FFFF among them), which XML does not allow.
fn noncharacter(c: char) -> bool {
    let u = u32::from(c);
    (0xFDD0..=0xFDEF).contains(&u) || (u & 0xFFFE) == 0xFFFE
}

/// TeX that TOML read as the escape `\<letter>` (`name`) and the letters `rest`.
fn tex_message(letter: char, name: &str, rest: &str) -> String {
    format!(
        "`\\{letter}{rest}` was read as {name} and `{rest}`: in a \"...\" string TOML takes \
         `\\{letter}` as an escape. For the TeX command, write a literal string in single \
         quotes, '\\{letter}{rest}', or double the backslash, \"\\\\{letter}{rest}\""
    )
}

/// The letters after the first escape `\<letter>` in a basic ("…") TOML string's source that
/// is followed by a letter (`\nu`, `\nabla`): TeX, not a line break.
fn basic_escape_before_letter(source: &str, letter: char) -> Option<String> {
    if source.starts_with('\'') {
        return None;
    }
    let chars: Vec<char> = source.chars().collect();
    let mut i = 0;
    while i + 1 < chars.len() {
        if chars[i] == '\\' {
            if chars[i + 1] == letter && chars.get(i + 2).is_some_and(char::is_ascii_alphabetic) {
                return Some(
                    chars[i + 2..]
                        .iter()
                        .take_while(|c| c.is_ascii_alphabetic())
                        .collect(),
                );
            }
            i += 2;
        } else {
            i += 1;
        }
    }
    None
}

/// Why LaTeX between `$` signs cannot be typeset, if it cannot: empty, or what the one LaTeX
/// reader says of it, or why the page's MathML or the PDF's Typst cannot be made from it.
pub(super) fn latex_problem(latex: &str) -> Option<String> {
    if latex.trim().is_empty() {
        return Some("it is empty".into());
    }
    let tex = match crate::notation::Tex::read(latex) {
        Ok(tex) => tex,
        Err(e) => return Some(e.to_string()),
    };
    // Every formula is spoken (the page's alttext, the tagged PDF's alternative text, which
    // PDF/UA refuses empty): one that says nothing sets nothing a reader can see either.
    if tex.spoken().trim().is_empty() {
        return Some(if latex.contains('%') && !latex.contains("\\%") {
            "it sets nothing: `%` starts a LaTeX comment, which runs to the end; write `\\%` \
             for a percent sign"
                .into()
        } else {
            "it sets nothing but space: write what it stands for, or leave it out".into()
        });
    }
    if let Err(e) = tex.to_mathml(false) {
        return Some(e.to_string());
    }
    tex.to_typst().err().map(|e| e.to_string())
}

/// The longest title, meaning or label, in characters: a heading, not a page.
pub const MAX_LABEL_CHARS: usize = 500;
/// The longest statement (of a claim or a problem), in characters: a few printed pages.
pub const MAX_STATEMENT_CHARS: usize = 20_000;

impl Validator<'_> {
    /// One prose field, refused at its line when it holds a control character or is longer
    /// than its limit. `lines`: a statement, which may run over lines.
    pub(super) fn prose(&self, t: &Text, field: &str, lines: bool) -> Result<(), SceneError> {
        let limit = if lines {
            MAX_STATEMENT_CHARS
        } else {
            MAX_LABEL_CHARS
        };
        let length = t.get_ref().chars().count();
        if length > limit {
            return Err(self.err(
                content_start(t),
                field,
                format!(
                    "{length} characters; this field holds at most {limit}: shorten it \
                     (a long explanation belongs in a claim's or the problem's statement)"
                ),
            ));
        }
        let source = self.loc.text.get(t.span()).unwrap_or("");
        if let Some(why) = control_character(t.get_ref(), source, lines) {
            return Err(self.err(content_start(t), field, why));
        }
        let parts = crate::model::prose::dollar_split(t.get_ref());
        if parts.len().is_multiple_of(2) {
            let last = t.get_ref().rfind('$').unwrap_or(0);
            return Err(self.err(
                content_start(t) + last,
                field,
                "a `$` without its closing `$`: mathematics goes between two `$` signs; write a \
                 dollar sign as `\\$`",
            ));
        }
        for math in parts.iter().skip(1).step_by(2) {
            if let Some(why) = latex_problem(math) {
                let at = t.get_ref().find(math.as_str()).unwrap_or(0);
                return Err(self.err(
                    content_start(t) + at,
                    field,
                    format!("the mathematics `${math}$` cannot be typeset: {why}"),
                ));
            }
        }
        Ok(())
    }

    /// Every prose field of the scene: the title, the symbols' meanings, the bodies' labels,
    /// the claims' statements, the steps' reasons and the problem's statement (the statements
    /// and reasons may run over lines).
    pub(super) fn prose_fields(&self, raw: &RawScene) -> Result<(), SceneError> {
        self.prose(&raw.title, "title", false)?;
        // A title is every page's heading, and a PDF's: one that sets no character (all of
        // it `$\operatorname{}$` or `$\hat{}$`) is no heading, which the tagged PDF refuses.
        if !crate::model::prose::plain(raw.title.get_ref())
            .chars()
            .any(|c| !c.is_whitespace() && !combining_mark(c))
        {
            return Err(self.err(
                content_start(&raw.title),
                "title",
                "the title sets no visible character: give the scene a title in words",
            ));
        }
        for (name, meaning) in &raw.symbols {
            let meaning = crate::scene::raw::meaning_of(meaning);
            self.prose(&meaning, &format!("symbols.{}", name.get_ref()), false)?;
        }
        for (i, b) in raw.bodies.iter().enumerate() {
            if let Some(label) = &b.get_ref().label {
                self.prose(label, &format!("body[{i}].label"), false)?;
            }
        }
        for (i, c) in raw.claims.iter().enumerate() {
            self.prose(
                &c.get_ref().statement,
                &format!("claim[{i}].statement"),
                true,
            )?;
        }
        for (i, s) in raw.steps.iter().enumerate() {
            if let Some(why) = &s.get_ref().why {
                self.prose(why, &format!("step[{i}].why"), true)?;
            }
        }
        if let Some(p) = &raw.problem {
            self.prose(&p.get_ref().statement, "problem.statement", true)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::control_character;

    #[test]
    fn tex_read_as_escapes_is_refused_with_the_way_to_write_it() {
        let why = control_character("tilted by \u{8}eta", "\"tilted by \\beta\"", false).unwrap();
        assert!(
            why.contains("`\\beta` was read as a backspace and `eta`"),
            "{why}"
        );
        assert!(
            why.contains("'\\beta'") && why.contains("\"\\\\beta\""),
            "{why}"
        );
        let why = control_character("\u{c}rac{1}{2}", "\"\\frac{1}{2}\"", false).unwrap();
        assert!(why.contains("`\\frac`"), "{why}");
        for (value, source, tex) in [
            ("\theta", "\"\\theta\"", "\\theta"),
            ("\nu", "\"\\nu\"", "\\nu"),
            ("\rho", "\"\\rho\"", "\\rho"),
        ] {
            let why = control_character(value, source, true).unwrap();
            assert!(why.contains(&format!("`{tex}`")), "{why}");
        }
        assert!(
            control_character("a\u{7}b", "\"a\\u0007b\"", false)
                .unwrap()
                .contains("U+0007")
        );
        for c in ['\u{FFFE}', '\u{FFFF}', '\u{FDD0}', '\u{10FFFF}'] {
            let why = control_character(&format!("a{c}b"), "\"…\"", true).unwrap();
            assert!(why.contains("noncharacter"), "{why}");
        }
        assert_eq!(control_character("a\u{FFFD}b", "\"…\"", true), None);
    }

    #[test]
    fn plain_text_and_real_line_breaks_in_a_statement_pass() {
        assert_eq!(
            control_character("A hoop of radius R", "\"A hoop\"", false),
            None
        );
        assert_eq!(control_character("\\beta", "'\\beta'", false), None);
        let multi = "\"\"\"\nFirst line.\nSecond line.\"\"\"";
        assert_eq!(
            control_character("First line.\nSecond line.", multi, true),
            None
        );
        // A line break in a title is refused all the same.
        assert!(control_character("a\nb", "\"a\\nb\"", false).is_some());
        // `\n` then a letter in a statement is TeX, even where a real break would pass.
        assert!(control_character("a\nu", "\"a\\nu\"", true).is_some());
        // An escaped backslash is not an escape: "\\nu" is the text \nu.
        assert_eq!(control_character("\\nu", "\"\\\\nu\"", true), None);
    }
}
