//! String literals for the languages mechbook writes into: Typst's and CSS's.

/// `s` in double quotes, its quotes and backslashes escaped, line breaks as spaces, and each
/// character `special` rewrites as it says.
fn quoted(s: &str, special: impl Fn(char) -> Option<&'static str>) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match (c, special(c)) {
            (_, Some(written)) => out.push_str(written),
            ('"' | '\\', None) => {
                out.push('\\');
                out.push(c);
            }
            ('\n' | '\r', None) => out.push(' '),
            (c, None) => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A Typst string literal: quotes and backslashes escaped, line breaks and tabs as spaces.
pub fn typst_string(s: &str) -> String {
    quoted(s, |c| (c == '\t').then_some(" "))
}

/// A CSS string literal: quotes and backslashes escaped, and `<` so that no `</style>` ends it.
pub fn css_string(s: &str) -> String {
    quoted(s, |c| (c == '<').then_some("\\3C "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_language_escapes_its_own() {
        assert_eq!(typst_string("a \"b\"\\\tc\nd"), "\"a \\\"b\\\"\\\\ c d\"");
        assert_eq!(
            css_string("x</style>\t\"q\""),
            "\"x\\3C /style>\t\\\"q\\\"\""
        );
    }
}
