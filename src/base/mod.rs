//! The bottom layer: neutral utilities that know nothing of mechanics or of any stage.

pub mod float;
pub mod format;
pub mod hash;
pub mod in_order;
pub mod literal;
pub mod markup;
pub mod natural;
pub mod pencil;
pub mod rng;
pub mod suggest;
pub mod zip;

/// A table test: `f` of each row's input is its expected text; a failure names the input.
#[cfg(test)]
pub fn assert_each(f: impl Fn(&str) -> String, rows: &[(&str, &str)]) {
    for (input, expected) in rows {
        assert_eq!(f(input), *expected, "from {input:?}");
    }
}

/// Asserts that `text` says each of `parts`, naming the first it lacks.
#[cfg(test)]
pub fn assert_says(text: &str, parts: &[&str]) {
    for part in parts {
        assert!(text.contains(part), "{text}\n(lacks {part:?})");
    }
}
