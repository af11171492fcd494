//! "Did you mean": the nearest valid name to a misspelt one, for error messages.

/// The candidate closest to `name` by edit distance (optimal string alignment, so a swapped
/// pair of letters counts once), when it is close enough to be a likely typo: at most one edit
/// in four letters, and never the whole word. Case is ignored, so `Sin` finds `sin`; ties go to
/// the earlier candidate.
pub fn nearest<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let lower = name.to_lowercase();
    let limit = (lower.chars().count() / 4).max(1);
    candidates
        .into_iter()
        .map(|c| (strsim::osa_distance(&lower, &c.to_lowercase()), c))
        .filter(|&(d, c)| c != name && d <= limit && d < c.chars().count())
        .min_by_key(|&(d, _)| d)
        .map(|(_, c)| c)
}

/// " (did you mean `x`?)" when a candidate is near `name`, else nothing: to follow the name.
pub fn did_you_mean<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> String {
    nearest(name, candidates)
        .map(|c| format!(" (did you mean `{c}`?)"))
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    const OUTPUTS: &[&str] = &["inertia_tensor", "principal_axes", "parallel_axis"];

    #[test]
    fn a_typo_finds_its_word_and_a_stranger_finds_nothing() {
        assert_eq!(
            nearest("quanity", ["eq", "quantity", "value"]),
            Some("quantity")
        );
        assert_eq!(
            nearest("principal_axis", OUTPUTS.iter().copied()),
            Some("principal_axes")
        );
        assert_eq!(nearest("hop", ["hoop", "rod", "box"]), Some("hoop"));
        // A transposition is one edit.
        assert_eq!(nearest("agerees", ["agrees", "disagrees"]), Some("agrees"));
        assert_eq!(nearest("Sin", ["sin", "cos"]), Some("sin"));
        assert_eq!(nearest("velocity", OUTPUTS.iter().copied()), None);
        // The name itself is no suggestion, and a two-letter word is not "one edit" from any
        // other two-letter word.
        assert_eq!(nearest("quantity", ["quantity"]), None);
        assert_eq!(nearest("xy", ["eq"]), None);
        assert_eq!(
            did_you_mean("sinn", ["sin", "sqrt"]),
            " (did you mean `sin`?)"
        );
        assert_eq!(did_you_mean("zzz", ["sin", "sqrt"]), "");
    }
}
