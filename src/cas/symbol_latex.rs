//! The conventions a scene's names follow, read from the name alone (a Greek letter's name is
//! the letter, `w1` is ω₁, `Ixx` is I_xx, a longer name upright), for each printer in
//! `notation` to set in its own notation beside the scene's own `tex` (`notation::Names`).

/// A name and its number, for a name of the form `step_k` (`acc_2` is `acc` and `2`).
pub fn numbered(s: &str) -> Option<(&str, &str)> {
    s.rsplit_once('_')
        .filter(|(_, k)| !k.is_empty() && k.chars().all(|c| c.is_ascii_digit()))
}

/// Greek letters by their LaTeX names, as LaTeX sets them (`phi` is ϕ, `varphi` φ).
const GREEK_LETTERS: &[(&str, &str)] = &[
    ("alpha", "α"),
    ("beta", "β"),
    ("gamma", "γ"),
    ("delta", "δ"),
    ("epsilon", "ϵ"),
    ("varepsilon", "ε"),
    ("zeta", "ζ"),
    ("eta", "η"),
    ("theta", "θ"),
    ("vartheta", "ϑ"),
    ("iota", "ι"),
    ("kappa", "κ"),
    ("lambda", "λ"),
    ("mu", "μ"),
    ("nu", "ν"),
    ("xi", "ξ"),
    ("pi", "π"),
    ("varpi", "ϖ"),
    ("rho", "ρ"),
    ("varrho", "ϱ"),
    ("sigma", "σ"),
    ("varsigma", "ς"),
    ("tau", "τ"),
    ("upsilon", "υ"),
    ("phi", "ϕ"),
    ("varphi", "φ"),
    ("chi", "χ"),
    ("psi", "ψ"),
    ("omega", "ω"),
    ("Gamma", "Γ"),
    ("Delta", "Δ"),
    ("Theta", "Θ"),
    ("Lambda", "Λ"),
    ("Xi", "Ξ"),
    ("Pi", "Π"),
    ("Sigma", "Σ"),
    ("Upsilon", "Υ"),
    ("Phi", "Φ"),
    ("Psi", "Ψ"),
    ("Omega", "Ω"),
];

/// A Greek letter by its LaTeX name, for the Typst printers: the character itself.
pub fn greek_letter(name: &str) -> Option<&'static str> {
    GREEK_LETTERS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, c)| *c)
}

pub const GREEK: &[&str] = &[
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
    "lambda", "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "phi", "chi", "psi", "omega", "Gamma",
    "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Phi", "Psi", "Omega",
];

/// A symbol's name read by the conventions, for each printer to set in its own notation.
pub enum NameForm<'a> {
    /// A number as its author wrote it ([`super::Expr::numeral`]): `9.81`.
    Numeral(&'a str),
    /// A coordinate's rate: `phi'` (the first) or `phi''` (the second, `true`).
    Rate(&'a str, bool),
    /// A name with a word after `_` (`inertia_tensor`): upright, whole.
    Word(&'a str),
    /// I with its axes as a subscript: `Ixx`.
    Inertia(&'a str),
    /// A head and its subscript (empty for none): `w1`, `theta`, `m2`, `Om`.
    Head(Head<'a>, &'a str),
}

pub enum Head<'a> {
    /// ω is written w in scene files: w1 is ω₁ ...
    Omega,
    /// ... and wd1 its rate.
    OmegaRate,
    Greek(&'a str),
    /// A longer name, upright.
    Upright(&'a str),
    Letter(&'a str),
}

/// A subscript that names one letter: `x` in `acc_x`, `phi` in `p_phi` (a Greek letter's name).
pub fn is_letter_index(tail: &str) -> bool {
    (tail.len() == 1 && tail.as_bytes()[0].is_ascii_alphabetic()) || GREEK.contains(&tail)
}

pub fn name_form(s: &str) -> NameForm<'_> {
    if s.starts_with(|c: char| c.is_ascii_digit()) {
        return NameForm::Numeral(s);
    }
    if let Some(base) = s.strip_suffix("''") {
        return NameForm::Rate(base, true);
    }
    if let Some(base) = s.strip_suffix('\'') {
        return NameForm::Rate(base, false);
    }
    if let Some((_, tail)) = s.split_once('_')
        && !tail.chars().all(|c| c.is_ascii_digit())
        && !is_letter_index(tail)
    {
        return NameForm::Word(s);
    }
    let split = s
        .char_indices()
        .find(|(i, c)| *i > 0 && (c.is_ascii_digit() || *c == '_'))
        .map(|(i, _)| i);
    let (head, tail) = match split {
        Some(i) => (&s[..i], s[i..].trim_start_matches('_')),
        None => (s, ""),
    };
    let numbered = !tail.is_empty() && tail.chars().all(|c| c.is_ascii_digit());
    let head = if numbered && head == "w" {
        Head::Omega
    } else if numbered && head == "wd" {
        Head::OmegaRate
    } else if GREEK.contains(&head) {
        Head::Greek(head)
    } else if head.len() > 1
        && head.starts_with('I')
        && head[1..].chars().all(|c| "xyz".contains(c))
    {
        return NameForm::Inertia(&head[1..]);
    } else if head.len() > 1 {
        Head::Upright(head)
    } else {
        Head::Letter(head)
    };
    NameForm::Head(head, tail)
}

/// Whether a name prints as a word rather than a symbol (`Lag`, `space_rate`, `acc_1`, `Lag'`):
/// more than one letter set upright, which a reader takes for mechbook's own name. `own` says
/// whether the scene typesets a name itself (a `tex`), which makes it a symbol.
pub fn prints_as_word(s: &str, own: &dyn Fn(&str) -> bool) -> bool {
    if own(s) {
        return false;
    }
    if numbered(s).is_some_and(|(base, _)| own(base)) {
        return false;
    }
    match name_form(s) {
        NameForm::Rate(base, _) => prints_as_word(base, own),
        NameForm::Word(_) | NameForm::Head(Head::Upright(_), _) => true,
        NameForm::Numeral(_) | NameForm::Inertia(_) | NameForm::Head(..) => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `acc_2` of a step `acc` the scene typesets is no word; without its `tex` it is the word
    /// `acc` with its subscript, which `check` warns of.
    #[test]
    fn a_numbered_result_of_a_typeset_step_is_no_word() {
        let typesets = |n: &str| n == "acc";
        assert!(!prints_as_word("acc_2", &typesets));
        assert!(prints_as_word("acc_2", &|_| false));
        assert!(prints_as_word("space_rate", &|_| false));
        assert!(prints_as_word("acc_x", &|_| false));
        assert!(prints_as_word("Lag'", &|_| false));
        for symbol in ["phi1", "w3", "Ixx", "Omega_2", "p_phi", "x_c", "m2"] {
            assert!(!prints_as_word(symbol, &|_| false), "{symbol}");
        }
    }
}
