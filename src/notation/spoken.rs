//! A formula's spoken form, made from its tree: what a screen reader says for it (the MathML's
//! `alttext`, the PDF's alternative description). "2 pi times the square root of 2 L over 3 g"
//! is read from the same nodes the page and the paper set.

use super::latex::{Node, Tex};
use pulldown_latex::event::{
    Content, EnvironmentFlow, Font, Grouping, ScriptPosition, ScriptType, StateChange, Visual,
};

impl Tex {
    /// The formula in words.
    pub fn spoken(&self) -> String {
        spoken(&self.nodes)
    }
}

/// The nodes in words, single-spaced.
pub fn spoken(nodes: &[Node]) -> String {
    let mut words = Vec::new();
    say(&super::tree::upright_words(nodes), &mut words);
    let text = words.join(" ");
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

fn say(nodes: &[Node], out: &mut Vec<String>) {
    for (k, n) in nodes.iter().enumerate() {
        // 5.4 × 10⁻⁵ is a number "times" a power of ten, not a cross product; so is a piece
        // of a broken line that opens with "× 10⁻⁵".
        if is_cross(n)
            && matches!(
                k.checked_sub(1).map(|j| &nodes[j]),
                None | Some(Node::Number(_))
            )
            && nodes.get(k + 1).is_some_and(is_power_of_ten)
        {
            out.push("times".into());
            continue;
        }
        // A slash between two units is "per": "m per s squared".
        if is_slash(n)
            && k.checked_sub(1).is_some_and(|j| is_unit(&nodes[j]))
            && nodes.get(k + 1).is_some_and(is_unit)
        {
            out.push("per".into());
            continue;
        }
        node(n, out);
    }
}

fn is_slash(n: &Node) -> bool {
    matches!(
        n,
        Node::Atom(Content::BinaryOp { content: '/', .. } | Content::Ordinary { content: '/', .. })
    )
}

/// An upright symbol, or one raised to a power: a unit's factor (`model::units::unit_formula`).
fn is_unit(n: &Node) -> bool {
    match n {
        Node::Group(_, inner) => matches!(
            inner.first(),
            Some(Node::State(StateChange::Font(Some(Font::UpRight))))
        ),
        Node::Script { parts, .. } => parts.first().is_some_and(is_unit),
        _ => false,
    }
}

fn is_cross(n: &Node) -> bool {
    matches!(n, Node::Atom(Content::BinaryOp { content: '×', .. }))
}

/// 10 to a power: the second half of a number in scientific notation.
fn is_power_of_ten(n: &Node) -> bool {
    matches!(n, Node::Script { ty: ScriptType::Superscript, parts, .. }
        if matches!(parts.first(), Some(Node::Number(d)) if d == "10"))
}

/// The words of a part (a numerator, a radicand) and whether it is more than one item, which
/// a listener needs told where it ends.
fn part(n: &Node) -> (String, bool) {
    let inner = match n {
        Node::Group(Grouping::Normal, inner) => inner.as_slice(),
        other => std::slice::from_ref(other),
    };
    let words = spoken(inner);
    // A negative number ("minus 5") is one item to a listener.
    let long = words
        .strip_prefix("minus ")
        .unwrap_or(&words)
        .split(' ')
        .count()
        > 1;
    (words, long)
}

fn node(n: &Node, out: &mut Vec<String>) {
    match n {
        Node::Text(t) => out.push(if t == "&nbsp;" { " ".into() } else { t.clone() }),
        Node::Number(d) => out.push(d.clone()),
        Node::Function(f) => out.push(function(f)),
        Node::Atom(c) => out.push(atom(c)),
        Node::Group(Grouping::LeftRight(open, close), inner) => {
            out.extend(open.map(|c| delimiter(c, true)));
            say(inner, out);
            out.extend(close.map(|c| delimiter(c, false)));
        }
        // A column vector's entries are read as a list: "x, y, z", not as a matrix's rows.
        Node::Group(_, inner)
            if !inner
                .iter()
                .any(|n| matches!(n, Node::Flow(EnvironmentFlow::Alignment))) =>
        {
            for n in inner {
                match n {
                    Node::Flow(_) => out.push(",".into()),
                    other => node(other, out),
                }
            }
        }
        Node::Group(_, inner) => say(inner, out),
        Node::Visual(Visual::Fraction(_), parts) if parts.len() == 2 => {
            let (top, long_top) = part(&parts[0]);
            let (bottom, long_bottom) = part(&parts[1]);
            if long_top || long_bottom {
                out.push(format!("fraction {top} over {bottom}, end fraction"));
            } else {
                out.push(format!("{top} over {bottom}"));
            }
        }
        Node::Visual(Visual::SquareRoot, parts) if !parts.is_empty() => {
            let (inner, long) = part(&parts[0]);
            let end = if long { ", end root" } else { "" };
            out.push(format!("the square root of {inner}{end}"));
        }
        Node::Visual(Visual::Root, parts) if parts.len() == 2 => {
            let (inner, _) = part(&parts[0]);
            let (index, _) = part(&parts[1]);
            out.push(format!("the root of order {index} of {inner}, end root"));
        }
        Node::Visual(Visual::Negation, parts) => {
            out.push("not".into());
            say(parts, out);
        }
        Node::Visual(_, parts) => say(parts, out),
        Node::Script {
            ty,
            position,
            parts,
        } => script(*ty, *position, parts, out),
        Node::Space(_) => out.push(" ".into()),
        Node::State(_) => {}
        Node::Flow(EnvironmentFlow::Alignment) => out.push(",".into()),
        Node::Flow(_) => out.push(";".into()),
    }
}

fn script(ty: ScriptType, position: ScriptPosition, parts: &[Node], out: &mut Vec<String>) {
    let Some((base, scripts)) = parts.split_first() else {
        return;
    };
    // An accent over a letter: φ̇ is "phi dot".
    if position == ScriptPosition::AboveBelow
        && let [Node::Atom(Content::Ordinary { content, .. })] = scripts
        && let Some(accent) = accent(*content)
    {
        node(base, out);
        out.push(accent.into());
        return;
    }
    node(base, out);
    let (sub, sup) = match (ty, scripts) {
        (ScriptType::Subscript, [s]) => (Some(s), None),
        (ScriptType::Superscript, [s]) => (None, Some(s)),
        (ScriptType::SubSuperscript, [a, b]) => (Some(a), Some(b)),
        _ => (None, None),
    };
    // An integral's or a sum's limits: "the integral from 0 to L of".
    if matches!(base, Node::Atom(Content::LargeOp { .. })) {
        if let Some(s) = sub {
            out.push(format!("from {}", part(s).0));
        }
        if let Some(s) = sup {
            out.push(format!("to {}", part(s).0));
        }
        out.push("of".into());
        return;
    }
    if let Some(s) = sub {
        let (words, long) = part(s);
        out.push(if long {
            format!("sub {words}, end sub")
        } else {
            format!("sub {words}")
        });
    }
    if let Some(s) = sup {
        let (words, long) = part(s);
        out.push(match words.as_str() {
            "2" => "squared".into(),
            "3" => "cubed".into(),
            "T" => "transpose".into(),
            "minus 1" => "inverse".into(),
            "prime" => "prime".into(),
            _ if long => format!("to the power {words}, end power"),
            _ => format!("to the power {words}"),
        });
    }
}

fn accent(c: char) -> Option<&'static str> {
    Some(match c {
        '˙' | '\u{307}' => "dot",
        '¨' | '\u{308}' => "double dot",
        '→' | '\u{20d7}' => "vector",
        '↔' | '\u{20e1}' => "tensor",
        '^' | '\u{302}' | 'ˆ' => "hat",
        '~' | '\u{303}' | '˜' => "tilde",
        '¯' | '\u{304}' | '‾' => "bar",
        _ => return None,
    })
}

fn function(name: &str) -> String {
    let name = name.trim_start_matches('\\');
    match name {
        "arccos" => "arc cosine".into(),
        "arcsin" => "arc sine".into(),
        "arctan" => "arc tangent".into(),
        "cos" => "cosine".into(),
        "sin" => "sine".into(),
        "tan" => "tangent".into(),
        "sinh" => "hyperbolic sine".into(),
        "cosh" => "hyperbolic cosine".into(),
        "exp" => "exponential".into(),
        "det" => "determinant".into(),
        "tr" => "trace".into(),
        "ln" => "log".into(),
        other => other.into(),
    }
}

fn delimiter(c: char, open: bool) -> String {
    match (c, open) {
        ('(' | '[' | '{', true) => "open paren".into(),
        (')' | ']' | '}', false) => "close paren".into(),
        ('|', _) => "bar".into(),
        ('‖', _) => "norm".into(),
        _ => String::new(),
    }
}

fn atom(c: &Content) -> String {
    match c {
        Content::Ordinary { content, .. } => letter(*content),
        Content::BinaryOp { content, .. } => match content {
            '+' => "plus".into(),
            '−' | '-' => "minus".into(),
            '⋅' | '·' => "times".into(),
            '×' => "cross".into(),
            '/' => "over".into(),
            '±' => "plus or minus".into(),
            other => other.to_string(),
        },
        Content::Relation { content, .. } => {
            let text = super::latex::relation_text(content);
            match text.as_str() {
                "=" => "equals".into(),
                "≈" => "is approximately".into(),
                "<" => "is less than".into(),
                ">" => "is greater than".into(),
                "≤" => "is at most".into(),
                "≥" => "is at least".into(),
                "→" => "tends to".into(),
                ":" => ":".into(),
                "∥" => "is parallel to".into(),
                "⊥" | "⟂" => "is perpendicular to".into(),
                other => other.into(),
            }
        }
        Content::LargeOp { content, .. } => match content {
            '∫' => "the integral".into(),
            '∑' => "the sum".into(),
            '∏' => "the product".into(),
            other => other.to_string(),
        },
        Content::Delimiter { content, ty, .. } => {
            let open = matches!(ty, pulldown_latex::event::DelimiterType::Open);
            delimiter(*content, open)
        }
        Content::Punctuation(p) => p.to_string(),
        _ => String::new(),
    }
}

/// A letter or sign in words: Greek letters by name, a prime as "prime".
fn letter(c: char) -> String {
    const GREEK: &[(char, &str)] = &[
        ('α', "alpha"),
        ('β', "beta"),
        ('γ', "gamma"),
        ('δ', "delta"),
        ('ε', "epsilon"),
        ('ϵ', "epsilon"),
        ('ζ', "zeta"),
        ('η', "eta"),
        ('θ', "theta"),
        ('ϑ', "theta"),
        ('ι', "iota"),
        ('κ', "kappa"),
        ('λ', "lambda"),
        ('μ', "mu"),
        ('ν', "nu"),
        ('ξ', "xi"),
        ('π', "pi"),
        ('ρ', "rho"),
        ('σ', "sigma"),
        ('τ', "tau"),
        ('υ', "upsilon"),
        ('φ', "phi"),
        ('ϕ', "phi"),
        ('χ', "chi"),
        ('ψ', "psi"),
        ('ω', "omega"),
        ('Γ', "capital gamma"),
        ('Δ', "capital delta"),
        ('Θ', "capital theta"),
        ('Λ', "capital lambda"),
        ('Ξ', "capital xi"),
        ('Π', "capital pi"),
        ('Σ', "capital sigma"),
        ('Φ', "capital phi"),
        ('Ψ', "capital psi"),
        ('Ω', "capital omega"),
    ];
    if let Some((_, name)) = GREEK.iter().find(|(g, _)| *g == c) {
        return (*name).into();
    }
    match c {
        '′' | '\'' => "prime".into(),
        '″' => "double prime".into(),
        '∞' => "infinity".into(),
        '∂' => "partial".into(),
        '∇' => "del".into(),
        '𝟙' => "the identity".into(),
        '…' | '⋯' => "and so on".into(),
        '|' => "bar".into(),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::super::Tex;
    use crate::cas::parse;

    fn said(latex: &str) -> String {
        Tex::read(latex).unwrap().spoken()
    }

    /// Both perpendicular signs are said: mechbook's own rows set ⟂ (U+27C2), LaTeX's `\perp`
    /// is ⊥; the principal axes' "every axis ⟂ (0, 0, 1)" was read out as the bare sign.
    #[test]
    fn both_perpendicular_signs_are_said() {
        let row = crate::notation::Formula::Row(vec![
            crate::notation::Formula::Text("every axis".into()),
            crate::notation::Formula::Op(crate::notation::Op::Perp),
            crate::notation::Formula::Name(crate::notation::Name::letter("n")),
        ]);
        let said_row = row.to_tex(crate::notation::Names::none()).spoken();
        assert!(said_row.contains("is perpendicular to"), "{said_row}");
        assert!(said(r"a \perp b").contains("is perpendicular to"));
    }

    /// A unit's slash is "per", as a unit is read aloud; a slash between symbols stays "over".
    #[test]
    fn a_slash_between_units_is_per() {
        use crate::notation::{Formula, Name, Names, Op};
        let up = |s: &str| Formula::Upright(s.into());
        let unit = Formula::Row(vec![
            up("kg"),
            Formula::Op(Op::Thin),
            Formula::Sup(Box::new(up("m")), Box::new(Formula::Number("2".into()))),
            Formula::Op(Op::Slash),
            up("s"),
        ]);
        assert_eq!(unit.to_tex(Names::none()).spoken(), "kg m squared per s");
        let ratio = Formula::Row(vec![
            Formula::Name(Name::letter("L")),
            Formula::Op(Op::Slash),
            Formula::Name(Name::letter("g")),
        ]);
        assert_eq!(ratio.to_tex(Names::none()).spoken(), "L over g");
    }

    /// An upright word is one identifier on the page, one text run in Typst, and one word to a
    /// listener: `\mathrm{body}` was four `<mi>` and "b o d y".
    #[test]
    fn an_upright_word_is_one_identifier_and_spoken_as_the_word() {
        assert_eq!(said(r"\Omega_{\mathrm{body}}"), "capital omega sub body");
        assert_eq!(said(r"3\,\mathrm{kg}"), "3 kg");
        let tex = Tex::read(r"\Omega_{\mathrm{body}} = \mathrm{d} x").unwrap();
        let page = tex.to_mathml(false).unwrap();
        assert!(page.contains("<mtext>body</mtext>"), "{page}");
        assert!(!page.contains(">b</mi>"), "{page}");
        // One letter upright stays a letter.
        assert!(
            page.contains(r#"<mi mathvariant="normal">d</mi>"#),
            "{page}"
        );
        assert!(tex.to_typst().unwrap().contains(r#""body""#));
        // A result named as a word (no `tex`) is one identifier too, spoken as the word.
        let word = parse("slow_eps + Lfree")
            .unwrap()
            .expr
            .to_tex(crate::notation::Names::none());
        assert_eq!(word.spoken(), "slow_eps plus Lfree");
        assert!(
            word.to_mathml(false)
                .unwrap()
                .contains("<mtext>Lfree</mtext>")
        );
        // The second result of a step `acc` with `tex = "a"` is a₂ on the page too.
        let names = [("acc".to_string(), "a".to_string())].into();
        let second = parse("acc_2")
            .unwrap()
            .expr
            .to_tex(&crate::notation::Names::of(&names));
        assert_eq!(second.spoken(), "a sub 2");
    }

    #[test]
    fn formulas_are_read_out_from_their_trees() {
        assert_eq!(said(r"x^2 + y_1"), "x squared plus y sub 1");
        assert_eq!(said(r"\frac{a}{b}"), "a over b");
        assert_eq!(
            said(r"\frac{2 L}{3 g}"),
            "fraction 2 L over 3 g, end fraction"
        );
        assert_eq!(said(r"\sqrt{g}"), "the square root of g");
        assert_eq!(said(r"\dot{\phi} = \omega"), "phi dot equals omega");
        assert_eq!(
            said(r"\cos\left(\theta\right)"),
            "cosine open paren theta close paren"
        );
        assert_eq!(said(r"A^{T}"), "A transpose");
        assert_eq!(said(r"\overleftrightarrow{I}"), "I tensor");
        assert_eq!(
            said(r"\begin{pmatrix}x \\ y\end{pmatrix}"),
            "open paren x , y close paren"
        );
        assert_eq!(
            said(r"\begin{pmatrix}a & b \\ c & d\end{pmatrix}"),
            "open paren a , b ; c , d close paren"
        );
        assert_eq!(
            said(r"\int_{0}^{L} s \, d s"),
            "the integral from 0 to L of s d s"
        );
    }

    /// A number in scientific notation is a number times a power of ten: "cross" and "end
    /// power" had been said for 5.4 × 10⁻⁵ on every page and paper.
    #[test]
    fn a_number_times_a_power_of_ten_is_said_as_a_number() {
        let number = crate::notation::Formula::decimal("5.4e-5");
        assert_eq!(
            number.to_tex(crate::notation::Names::none()).spoken(),
            "5.4 times 10 to the power minus 5"
        );
        assert_eq!(said(r"10^{-12}"), "10 to the power minus 12");
        // A cross product stays one, and a longer power still says where it ends.
        assert_eq!(said(r"a \times b"), "a cross b");
        assert_eq!(said(r"2 \times 10"), "2 cross 10");
        assert_eq!(said(r"\times 10^{-3}"), "times 10 to the power minus 3");
        assert_eq!(
            said(r"e^{-t/T}"),
            "e to the power minus t over T, end power"
        );
    }

    #[test]
    fn the_pages_mathml_carries_the_spoken_form() {
        let mathml = Tex::read(r"\frac{a}{b} < \sqrt{x}")
            .unwrap()
            .to_mathml(true)
            .unwrap();
        assert!(
            mathml.starts_with(
                r#"<math display="block" alttext="a over b is less than the square root of x">"#
            ),
            "{mathml}"
        );
    }

    #[test]
    fn a_printed_result_is_read_as_it_is_set() {
        let period = parse("2*pi*(2/3*L/g)^(1/2)").unwrap().expr;
        assert_eq!(
            period.to_tex(crate::notation::Names::none()).spoken(),
            "2 pi the square root of fraction 2 L over 3 g, end fraction, end root"
        );
    }
}
