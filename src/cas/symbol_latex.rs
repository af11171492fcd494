//! How a symbol's name is typeset: the conventions a scene's names follow (a Greek letter's
//! name is the letter, `w1` is ω₁, `Ixx` is I_xx, a longer name upright), or the scene's own
//! LaTeX for it (`tex = "\\Omega"`), in force while its page is rendered.

use std::cell::RefCell;
use std::collections::BTreeMap;

/// A name's own typesetting, as the scene's author wrote it (`tex = "\\Omega"`) and as the
/// one LaTeX reader (`notation/latex.rs`) set it in Typst's math.
#[derive(Debug, Clone, PartialEq)]
pub struct SymbolTex {
    pub latex: String,
    pub typst: String,
}

thread_local! {
    /// The names the scene being rendered typesets itself, read by the LaTeX and Typst
    /// printers; empty outside [`typeset_as`].
    static TYPESET: RefCell<BTreeMap<String, SymbolTex>> = const { RefCell::new(BTreeMap::new()) };
}

/// Runs `f` with the scene's own typesetting of its names, so that every formula of its page
/// prints them so; the table before is put back after.
pub fn typeset_as<R>(names: BTreeMap<String, SymbolTex>, f: impl FnOnce() -> R) -> R {
    let before = TYPESET.with(|t| t.replace(names));
    let out = f();
    TYPESET.with(|t| t.replace(before));
    out
}

/// The scene's own LaTeX for a name, while its page is rendered.
pub(super) fn scene_tex(s: &str) -> Option<String> {
    TYPESET.with(|t| t.borrow().get(s).map(|x| x.latex.clone()))
}

/// Whether the scene being rendered typesets a name itself (a `tex`).
pub fn typesets(s: &str) -> bool {
    TYPESET.with(|t| t.borrow().contains_key(s))
}

/// The scene's own Typst for a name, while its page is rendered.
pub(super) fn scene_typst(s: &str) -> Option<String> {
    TYPESET.with(|t| t.borrow().get(s).map(|x| x.typst.clone()))
}

/// A numbered result of a step the scene typesets (`acc_2` of a step `acc` with `tex = "a"`):
/// the step's own typesetting and the number, which prints as its subscript (a₂).
pub fn numbered_result(s: &str) -> Option<(SymbolTex, &str)> {
    let (base, k) = numbered(s)?;
    TYPESET
        .with(|t| t.borrow().get(base).cloned())
        .map(|tex| (tex, k))
}

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

const GREEK: &[&str] = &[
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

/// `alpha` -> `\alpha`, `w1` -> `\omega_{1}`, `wd1` -> `\dot{\omega}_{1}`, `Ixx` -> `I_{xx}`,
/// `inertia_tensor` -> upright text.
pub(super) fn latex_symbol(s: &str) -> String {
    if let Some(tex) = scene_tex(s) {
        return tex;
    }
    if let Some((own, k)) = numbered_result(s) {
        return format!("{{{}}}_{{{k}}}", own.latex);
    }
    match name_form(s) {
        // A coordinate's rates: `phi'` is φ̇, `phi''` φ̈.
        NameForm::Rate(base, second) => format!(
            "\\{}{{{}}}",
            if second { "ddot" } else { "dot" },
            latex_symbol(base)
        ),
        NameForm::Numeral(digits) => digits.to_string(),
        NameForm::Word(w) => format!("\\mathrm{{{}}}", w.replace('_', "\\_")),
        NameForm::Inertia(axes) => format!("I_{{{axes}}}"),
        NameForm::Head(head, tail) => {
            let head = match head {
                Head::Omega => "\\omega".to_string(),
                Head::OmegaRate => "\\dot{\\omega}".to_string(),
                Head::Greek(g) => format!("\\{g}"),
                Head::Upright(u) => format!("\\mathrm{{{u}}}"),
                Head::Letter(l) => l.to_string(),
            };
            if tail.is_empty() {
                head
            } else if GREEK.contains(&tail) {
                format!("{head}_{{\\{tail}}}")
            } else {
                format!("{head}_{{{tail}}}")
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn own(names: &[(&str, &str)]) -> BTreeMap<String, SymbolTex> {
        names
            .iter()
            .map(|(n, latex)| {
                let tex = SymbolTex {
                    latex: latex.to_string(),
                    typst: latex.to_string(),
                };
                (n.to_string(), tex)
            })
            .collect()
    }

    /// `acc_2` of a step `acc` with `tex = "a"` prints a₂ in every printer, and is no word;
    /// without the `tex` it is the word `acc` with its subscript, which `check` warns of.
    #[test]
    fn a_numbered_result_prints_with_its_steps_symbol() {
        let steps = own(&[("acc", "a")]);
        let typesets = |n: &str| steps.contains_key(n);
        assert!(!prints_as_word("acc_2", &typesets));
        assert!(prints_as_word("acc_2", &|_| false));
        assert!(prints_as_word("space_rate", &|_| false));
        assert!(prints_as_word("acc_x", &|_| false));
        assert!(prints_as_word("Lag'", &|_| false));
        for symbol in ["phi1", "w3", "Ixx", "Omega_2", "p_phi", "x_c", "m2"] {
            assert!(!prints_as_word(symbol, &|_| false), "{symbol}");
        }
        let (latex, typst) = typeset_as(steps, || {
            let e = crate::cas::Expr::sym("acc_2");
            (e.to_latex(), e.to_typst())
        });
        assert_eq!(latex, "{a}_{2}");
        assert_eq!(typst, "attach(a, b: 2)");
    }
}
