//! The printers of a [`Formula`]: plain text for the terminal and JSON, LaTeX for the pages
//! (which turn it into MathML). Each prints the tree; neither reads the other's output.

use super::Names;
use super::formula::{Accent, Formula, GREEK, Name, Op};
use crate::base::format::superscript;

impl Formula {
    pub fn to_latex(&self, names: &Names) -> String {
        let mut out = String::new();
        latex(self, names, &mut out);
        out
    }

    pub fn to_text(&self) -> String {
        let mut out = String::new();
        text(self, &mut out);
        out
    }
}

/// Appends a piece of LaTeX, with a space where a control word would run into a letter.
fn join(out: &mut String, piece: &str) {
    let control_word = out.rfind('\\').is_some_and(|i| {
        out.len() > i + 1 && out[i + 1..].chars().all(|c| c.is_ascii_alphabetic())
    });
    if control_word && piece.starts_with(|c: char| c.is_ascii_alphabetic()) {
        out.push(' ');
    }
    out.push_str(piece);
}

fn latex(f: &Formula, names: &Names, out: &mut String) {
    let piece = match f {
        Formula::Expr(e) => e.to_latex(names),
        Formula::Name(n) => latex_name(n),
        Formula::Number(s) => s.clone(),
        Formula::Text(s) => format!("\\text{{{s}}}"),
        Formula::Upright(s) => format!("\\mathrm{{{s}}}"),
        Formula::Row(items) => {
            for (i, item) in items.iter().enumerate() {
                match item {
                    Formula::Op(Op::Minus) if unary(items, i) => join(out, "-"),
                    Formula::Op(op) => join(out, latex_op(*op)),
                    other => latex(other, names, out),
                }
            }
            return;
        }
        Formula::Op(op) => latex_op(*op).to_string(),
        Formula::Frac(a, b) => format!("\\frac{{{}}}{{{}}}", a.to_latex(names), b.to_latex(names)),
        Formula::Sqrt(a) => format!("\\sqrt{{{}}}", a.to_latex(names)),
        Formula::Sup(a, b) => format!("{}^{{{}}}", a.to_latex(names), b.to_latex(names)),
        Formula::Paren(a, true) => format!("\\left({}\\right)", a.to_latex(names)),
        Formula::Paren(a, false) => format!("({})", a.to_latex(names)),
        Formula::Bracket(a) => format!("\\left[{}\\right]", a.to_latex(names)),
        Formula::Abs(a) => format!("\\left|{}\\right|", a.to_latex(names)),
        Formula::Identity => "\\mathbb{1}".into(),
        Formula::Matrix(rows) => format!(
            "\\begin{{pmatrix}}{}\\end{{pmatrix}}",
            rows.iter()
                .map(|row| row
                    .iter()
                    .map(|f| f.to_latex(names))
                    .collect::<Vec<_>>()
                    .join(" & "))
                .collect::<Vec<_>>()
                .join(" \\\\ ")
        ),
        Formula::Function(name) => format!("\\{name}"),
        Formula::Sum(Some(i)) => format!("\\sum_{{{i}}}"),
        Formula::Sum(None) => "\\sum".into(),
        Formula::Integral(None) => "\\int".into(),
        Formula::Integral(Some(limits)) => {
            format!(
                "\\int_{{{}}}^{{{}}}",
                limits.0.to_latex(names),
                limits.1.to_latex(names)
            )
        }
        Formula::Nabla(None) => "\\nabla".into(),
        Formula::Nabla(Some(by)) => format!("\\nabla_{{{}}}", latex_base(by)),
        Formula::At(a, frame) => format!(
            "\\left.{}\\right|_{{\\mathrm{{{frame}}}}}",
            a.to_latex(names)
        ),
        Formula::Tex(t) => t.source.clone(),
    };
    join(out, &piece);
}

/// A minus sign that begins a row or follows another operator negates what follows.
fn unary(items: &[Formula], i: usize) -> bool {
    i == 0 || matches!(items[i - 1], Formula::Op(_))
}

fn is_number(f: &Formula, digits: &str) -> bool {
    matches!(f, Formula::Number(s) if s == digits)
}

fn latex_op(op: Op) -> &'static str {
    match op {
        Op::Equals => " = ",
        Op::Approx => " \\approx ",
        Op::Less => " < ",
        Op::LessEqual => " \\le ",
        Op::Greater => " > ",
        Op::Plus => " + ",
        Op::Minus => " - ",
        Op::Dot => "\\cdot",
        Op::Cross => "\\times",
        Op::Parallel => " \\parallel ",
        Op::Perp => " \\perp ",
        Op::Comma => ", ",
        Op::Colon => ":",
        Op::Semicolon => ";",
        Op::Slash => " / ",
        Op::Thin => "\\,",
        Op::Medium => "\\;",
        Op::Quad => " \\quad ",
    }
}

/// A letter: `\\alpha` for a Greek one's name, else as written.
fn latex_base(base: &str) -> String {
    if GREEK.iter().any(|(name, _)| *name == base) {
        format!("\\{base}")
    } else {
        base.to_string()
    }
}

fn latex_name(n: &Name) -> String {
    let base = latex_base(&n.base);
    let base = match n.accent {
        Accent::None => base,
        Accent::Vector => format!("\\vec{{{base}}}"),
        Accent::Tensor => format!("\\overleftrightarrow{{{base}}}"),
        Accent::Dot => format!("\\dot{{{base}}}"),
        Accent::DoubleDot => format!("\\ddot{{{base}}}"),
        Accent::VectorDot => format!("\\dot{{\\vec{{{base}}}}}"),
    };
    let sub = match n.sub.as_deref() {
        None => String::new(),
        Some("min") => "_{\\min}".into(),
        Some("max") => "_{\\max}".into(),
        // A word is upright (I_cm); a pair of axes (I_xy) or a number is not.
        Some(s) if s.len() > 1 && !s.chars().all(|c| c.is_ascii_digit() || "xyz".contains(c)) => {
            format!("_{{\\mathrm{{{s}}}}}")
        }
        Some(s) => format!("_{{{s}}}"),
    };
    let prime = if n.prime { "\\,'" } else { "" };
    format!("{base}{sub}{prime}")
}

fn text(f: &Formula, out: &mut String) {
    match f {
        Formula::Expr(e) => out.push_str(&e.to_text()),
        Formula::Name(n) => out.push_str(&text_name(n)),
        Formula::Number(s) | Formula::Text(s) | Formula::Upright(s) => out.push_str(s),
        Formula::Row(items) => text_row(items, out),
        Formula::Op(op) => out.push_str(text_op(*op)),
        Formula::Frac(a, b) if is_number(a, "1") && is_number(b, "2") => out.push('½'),
        Formula::Frac(a, b) => {
            text_operand(a, out);
            out.push('/');
            text_operand(b, out);
        }
        Formula::Sqrt(a) => {
            out.push('√');
            text_operand(a, out);
        }
        Formula::Sup(a, b) => text_sup(a, b, out),
        Formula::Paren(a, _) => {
            out.push('(');
            text(a, out);
            out.push(')');
        }
        Formula::Bracket(a) => {
            out.push('[');
            text(a, out);
            out.push(']');
        }
        Formula::Identity => out.push('𝟙'),
        Formula::Matrix(rows) => text_matrix(rows, out),
        Formula::Abs(a) => {
            out.push('|');
            text(a, out);
            out.push('|');
        }
        Formula::Function(name) => out.push_str(name),
        Formula::Sum(Some(i)) => {
            out.push_str("Σ_");
            out.push_str(i);
        }
        Formula::Sum(None) => out.push('Σ'),
        Formula::Integral(None) => out.push('∫'),
        Formula::Integral(Some(limits)) => {
            out.push_str("∫[");
            text(&limits.0, out);
            out.push_str(", ");
            text(&limits.1, out);
            out.push(']');
        }
        Formula::Nabla(by) => {
            out.push('∇');
            if let Some(by) = by {
                out.push('_');
                out.push_str(&text_base(by));
            }
        }
        Formula::At(a, frame) => {
            text_operand(a, out);
            out.push('|');
            out.push_str(frame);
        }
        Formula::Tex(t) => {
            out.push('$');
            out.push_str(&t.source);
            out.push('$');
        }
    }
}

/// A row's items side by side, its operators spaced.
fn text_row(items: &[Formula], out: &mut String) {
    for (i, item) in items.iter().enumerate() {
        match item {
            Formula::Op(Op::Minus) if unary(items, i) => out.push('−'),
            Formula::Op(op) => push_spaced(out, text_op(*op)),
            other => {
                // Side by side, factors are set apart by a space, but a number
                // runs into what it multiplies (2T), and a function or ∇ into its
                // argument: det(A), ∇F.
                let joined = i == 0
                    || out.ends_with(' ')
                    || matches!(
                        items[i - 1],
                        Formula::Op(_) | Formula::Number(_) | Formula::Nabla(_)
                    )
                    || matches!(
                        (&items[i - 1], other),
                        (Formula::Function(_), Formula::Paren(..))
                    );
                if !joined {
                    out.push(' ');
                }
                text(other, out);
            }
        }
    }
}

/// A power: its exponent in superscript digits where it is a number, ᵀ for a transpose.
fn text_sup(a: &Formula, b: &Formula, out: &mut String) {
    text_operand(a, out);
    match b {
        // An integer wholly in superscript (s⁻²); otherwise digits only, a minus and a slash
        // staying as written.
        Formula::Number(s) if s.parse::<i64>().is_ok() => out.extend(s.chars().map(superscript)),
        Formula::Number(s) => out.extend(s.chars().map(|c| {
            if c.is_ascii_digit() {
                superscript(c)
            } else {
                c
            }
        })),
        Formula::Name(n) if n.base == "T" && n.sub.is_none() => out.push('ᵀ'),
        other => {
            out.push('^');
            text_operand(other, out);
        }
    }
}

/// A matrix row by row in parentheses, a single row as one tuple.
fn text_matrix(rows: &[Vec<Formula>], out: &mut String) {
    let row = |r: &Vec<Formula>| {
        let cells: Vec<String> = r.iter().map(Formula::to_text).collect();
        format!("({})", cells.join(", "))
    };
    match rows {
        [one] => out.push_str(&row(one)),
        rows => {
            let rows: Vec<String> = rows.iter().map(row).collect();
            out.push_str(&format!("({})", rows.join(", ")));
        }
    }
}

/// Appends an operator's text, with one space where two would meet.
fn push_spaced(out: &mut String, piece: &str) {
    if out.ends_with(' ') {
        out.push_str(piece.trim_start());
    } else {
        out.push_str(piece);
    }
}

/// An operand of `/`, `√` or `^`: in parentheses unless it is one item.
fn text_operand(f: &Formula, out: &mut String) {
    // A unit's symbol is one item (kg², not (kg)²).
    let upright_symbol = matches!(f, Formula::Upright(s) if !s.contains(' '));
    let single = upright_symbol
        || matches!(
            f,
            Formula::Name(_)
                | Formula::Number(_)
                | Formula::Sup(..)
                | Formula::Paren(..)
                | Formula::Abs(_)
                | Formula::Bracket(_)
                | Formula::Matrix(_)
                | Formula::Identity
                | Formula::Sqrt(_)
                | Formula::Function(_)
        );
    if single {
        text(f, out);
    } else {
        out.push('(');
        text(f, out);
        out.push(')');
    }
}

fn text_op(op: Op) -> &'static str {
    match op {
        Op::Equals => " = ",
        Op::Approx => " ≈ ",
        Op::Less => " < ",
        Op::LessEqual => " ≤ ",
        Op::Greater => " > ",
        Op::Plus => " + ",
        Op::Minus => " − ",
        Op::Dot => "·",
        Op::Cross => " × ",
        Op::Parallel => " ∥ ",
        Op::Perp => " ⊥ ",
        Op::Comma => ", ",
        Op::Colon => ":",
        Op::Semicolon => ";",
        Op::Slash => "/",
        Op::Thin => " ",
        Op::Medium => " ",
        Op::Quad => "  ",
    }
}

/// A letter: `α` for a Greek one's name, else as written.
fn text_base(base: &str) -> String {
    GREEK
        .iter()
        .find(|(name, _)| *name == base)
        .map_or_else(|| base.to_string(), |(_, c)| c.to_string())
}

fn text_name(n: &Name) -> String {
    let mut s = text_base(&n.base);
    match n.accent {
        Accent::Dot | Accent::VectorDot => s.push('\u{307}'),
        Accent::DoubleDot => s.push('\u{308}'),
        _ => {}
    }
    match n.sub.as_deref() {
        Some(d) if d.chars().all(|c| c.is_ascii_digit()) => s.push_str(d),
        Some(sub) => {
            s.push('_');
            s.push_str(sub);
        }
        None => {}
    }
    if n.prime {
        s.push('\'');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::{Formula, Names};
    use crate::cas::Expr;

    fn both(notation: &str) -> (String, String) {
        let f = Formula::parse(notation, &[]);
        (f.to_text(), f.to_latex(Names::none()))
    }

    #[test]
    fn names_accents_and_subscripts_print_in_each_notation() {
        assert_eq!(
            both("vec(L) = ten(I) ~ vec(omega)"),
            (
                "L = I ω".into(),
                r"\vec{L} = \overleftrightarrow{I}\,\vec{\omega}".into()
            )
        );
        assert_eq!(
            both("2T ~ I_min <= L^2 <= 2T ~ I_max"),
            (
                "2T I_min ≤ L² ≤ 2T I_max".into(),
                r"2T\,I_{\min} \le L^{2} \le 2T\,I_{\max}".into()
            )
        );
        assert_eq!(both("dot(omega_2)").1, r"\dot{\omega}_{2}");
        assert_eq!(both("I_cm").1, r"I_{\mathrm{cm}}");
        assert_eq!(both("sum m ~ vec(r)' = 0").1, r"\sum m\,\vec{r}\,' = 0");
    }

    #[test]
    fn fractions_drop_their_parentheses_and_parentheses_grow_around_fractions() {
        assert_eq!(
            both("beta = (I_3 - I_1)/I_1"),
            (
                "β = (I3 − I1)/I1".into(),
                r"\beta = \frac{I_{3} - I_{1}}{I_{1}}".into()
            )
        );
        assert_eq!(
            both("sum_i I_i big(I_i - I_k) omega_i^2").1,
            r"\sum_{i}I_{i}\left(I_{i} - I_{k}\right)\omega_{i}^{2}"
        );
        assert_eq!(
            both("vec(L) = sum m ~ vec(r) × (vec(omega) × vec(r))").1,
            r"\vec{L} = \sum m\,\vec{r}\times(\vec{\omega}\times\vec{r})"
        );
        assert_eq!(
            both("T = 1/2 vec(omega)^T ten(I) ~ vec(omega)").0,
            "T = ½ ωᵀ I ω"
        );
        assert_eq!(
            both("sqrt(2/T)"),
            ("√(2/T)".into(), r"\sqrt{\frac{2}{T}}".into())
        );
    }

    #[test]
    fn a_minus_after_an_operator_negates() {
        assert_eq!(
            both("sigma^2 = -Omega_2^2"),
            ("σ² = −Ω2²".into(), r"\sigma^{2} = -\Omega_{2}^{2}".into())
        );
        assert_eq!(both("c_i = 1 - I_k/I_i").0, "c_i = 1 − I_k/I_i");
    }

    #[test]
    fn a_control_word_is_kept_apart_from_a_following_letter() {
        assert_eq!(both("nabla F || vec(L)").1, r"\nabla F \parallel \vec{L}");
        assert_eq!(both("tan alpha_b").1, r"\tan\alpha_{b}");
        assert_eq!(both("sin^2 + cos^2 = 1").1, r"\sin^{2} + \cos^{2} = 1");
    }

    #[test]
    fn exact_expressions_are_printed_by_the_expression_printers() {
        let e = Expr::over(Expr::sym("a"), Expr::int(2));
        let f = Formula::parse("(a/b)^2 = $0", std::slice::from_ref(&e));
        assert_eq!(
            f.to_latex(Names::none()),
            format!(
                r"\left(\frac{{a}}{{b}}\right)^{{2}} = {}",
                e.to_latex(Names::none())
            )
        );
        assert_eq!(f.to_text(), format!("(a/b)² = {}", e.to_text()));
    }

    #[test]
    fn frames_units_limits_and_rates_print_as_the_notes_write_them() {
        assert_eq!(
            both("((d vec(L))/(dt))|_body").1,
            r"\left.\frac{d\vec{L}}{dt}\right|_{\mathrm{body}}"
        );
        assert_eq!(
            both("P // rm(sidereal) ~ rm(day)"),
            (
                "P/sidereal day".into(),
                r"P / \mathrm{sidereal}\,\mathrm{day}".into()
            )
        );
        assert_eq!(
            both("dot(vec(omega))"),
            ("ω̇".into(), r"\dot{\vec{\omega}}".into())
        );
        assert_eq!(
            both("int_(0)^(2pi) f ~ d theta"),
            ("∫[0, 2π] f d θ".into(), r"\int_{0}^{2\pi}f\,d\theta".into())
        );
        assert_eq!(
            both("\"every axis\" perp v; quad I_xy ~= 1.5 × 10^(-3)").1,
            r"\text{every axis} \perp v; \quad I_{xy} \approx 1.5\times10^{-3}"
        );
        assert_eq!(both("nabla_rho F").1, r"\nabla_{\rho}F");
    }

    #[test]
    #[should_panic(expected = "is not closed")]
    fn a_malformed_formula_is_a_bug_that_names_itself() {
        Formula::parse("sqrt(2", &[]);
    }
}
