//! How a symbol's name is typeset: the conventions a scene's names follow (a Greek letter's
//! name is the letter, `w1` is ω₁, `Ixx` is I_xx, a longer name upright), or the scene's own
//! LaTeX for it (`tex = "\\Omega"`), in force while its page is rendered.

use std::cell::RefCell;
use std::collections::BTreeMap;

thread_local! {
    /// The names the scene being rendered typesets itself (`tex = "\\Omega"`), read by the
    /// LaTeX printer; empty outside [`typeset_as`].
    static TYPESET: RefCell<BTreeMap<String, String>> = const { RefCell::new(BTreeMap::new()) };
}

/// Runs `f` with the scene's own typesetting of its names (name -> LaTeX), so that every
/// formula of its page prints them so; the table before is put back after.
pub fn typeset_as<R>(names: &BTreeMap<String, String>, f: impl FnOnce() -> R) -> R {
    let before = TYPESET.with(|t| t.replace(names.clone()));
    let out = f();
    TYPESET.with(|t| t.replace(before));
    out
}

const GREEK: &[&str] = &[
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
    "lambda", "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "phi", "chi", "psi", "omega", "Gamma",
    "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Phi", "Psi", "Omega",
];

/// `alpha` -> `\alpha`, `w1` -> `\omega_{1}`, `wd1` -> `\dot{\omega}_{1}`, `Ixx` -> `I_{xx}`,
/// `inertia_tensor` -> upright text.
pub(super) fn latex_symbol(s: &str) -> String {
    if let Some(tex) = TYPESET.with(|t| t.borrow().get(s).cloned()) {
        return tex;
    }
    // A coordinate's rates: `phi'` is φ̇, `phi''` φ̈.
    if let Some(base) = s.strip_suffix("''") {
        return format!("\\ddot{{{}}}", latex_symbol(base));
    }
    if let Some(base) = s.strip_suffix('\'') {
        return format!("\\dot{{{}}}", latex_symbol(base));
    }
    if let Some((_, tail)) = s.split_once('_')
        && !tail.chars().all(|c| c.is_ascii_digit())
    {
        return format!("\\mathrm{{{}}}", s.replace('_', "\\_"));
    }
    let split = s
        .char_indices()
        .find(|(i, c)| *i > 0 && (c.is_ascii_digit() || *c == '_'))
        .map(|(i, _)| i);
    let (head, tail) = match split {
        Some(i) => (&s[..i], s[i..].trim_start_matches('_')),
        None => (s, ""),
    };
    // ω is written w in scene files: w1 is ω₁ and wd1 its rate.
    let numbered = !tail.is_empty() && tail.chars().all(|c| c.is_ascii_digit());
    let head = if numbered && head == "w" {
        "\\omega".to_string()
    } else if numbered && head == "wd" {
        "\\dot{\\omega}".to_string()
    } else if GREEK.contains(&head) {
        format!("\\{head}")
    } else if head.len() > 1
        && head.starts_with('I')
        && head[1..].chars().all(|c| "xyz".contains(c))
    {
        return format!("I_{{{}}}", &head[1..]);
    } else if head.len() > 1 {
        format!("\\mathrm{{{head}}}")
    } else {
        head.to_string()
    };
    if tail.is_empty() {
        head
    } else {
        format!("{head}_{{{tail}}}")
    }
}
