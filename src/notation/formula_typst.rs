//! The Typst printer of a [`Formula`], for the PDFs: the tree in Typst's math notation, as
//! `formula_print.rs` prints it in LaTeX for the pages.

use super::Names;
use super::formula::{Accent, Formula, GREEK, Name, Op};
use super::latex::TexError;
use crate::base::typst::typst_string;

impl Formula {
    /// Typst's math; `Err` only for an author's LaTeX that has no Typst form (scene
    /// validation refuses it first).
    pub fn to_typst(&self, names: &Names) -> Result<String, TexError> {
        let mut out = String::new();
        typst(self, names, &mut out, false)?;
        Ok(out)
    }

    /// Typst's math for a formula wider than its line, which Typst breaks after its relations
    /// and operators: its vectors as tuples, whose entries' sums can break (a matrix's row
    /// cannot).
    pub fn to_typst_breakable(&self, names: &Names) -> Result<String, TexError> {
        let mut out = String::new();
        typst(self, names, &mut out, true)?;
        Ok(out)
    }
}

/// Appends a piece, with a space where two names would run into one name.
fn join(out: &mut String, piece: &str) {
    let ends_word = out.ends_with(|c: char| c.is_alphanumeric() || c == ')' || c == '"');
    let starts_word = piece.starts_with(|c: char| c.is_alphanumeric() || c == '"');
    if ends_word && starts_word {
        out.push(' ');
    }
    out.push_str(piece);
}

fn typst(f: &Formula, names: &Names, out: &mut String, breakable: bool) -> Result<(), TexError> {
    let piece = match f {
        Formula::Expr(e) if breakable => e.to_typst_breakable(names),
        Formula::Expr(e) => e.to_typst(names),
        Formula::Name(n) => typst_name(n),
        // A decimal or an integer; a minus sign is Typst's too.
        Formula::Number(s) => s.replace('-', "−"),
        Formula::Text(s) => typst_string(s),
        Formula::Upright(s) => format!("upright({})", typst_string(s)),
        Formula::Row(items) => {
            for item in items {
                match item {
                    Formula::Op(op) => join(out, typst_op(*op)),
                    other => typst(other, names, out, breakable)?,
                }
            }
            return Ok(());
        }
        Formula::Op(op) => typst_op(*op).to_string(),
        Formula::Frac(a, b) => format!("frac({}, {})", a.to_typst(names)?, b.to_typst(names)?),
        Formula::Sqrt(a) => format!("sqrt({})", a.to_typst(names)?),
        Formula::Sup(a, b) => match a.as_ref() {
            // A paired group with an exponent is one piece: to be broken, its parentheses go
            // unpaired, the exponent on the closing one.
            Formula::Paren(inner, _) if breakable => {
                let mut opened = String::new();
                typst(inner, names, &mut opened, true)?;
                format!("\\({opened}\\)^({})", b.to_typst(names)?)
            }
            _ => format!("{}^({})", a.to_typst(names)?, b.to_typst(names)?),
        },
        // Typst breaks a line inside parentheses too.
        Formula::Paren(a, _) => {
            let mut inner = String::new();
            typst(a, names, &mut inner, breakable)?;
            format!("({inner})")
        }
        Formula::Bracket(a) => format!("[{}]", a.to_typst(names)?),
        Formula::Abs(a) => format!("abs({})", a.to_typst(names)?),
        Formula::Identity => "bb(1)".into(),
        Formula::Matrix(rows) => typst_matrix(rows, names)?,
        Formula::Function(name) => format!("{name} "),
        Formula::Sum(Some(i)) => format!("sum_({})", typst_base(i)),
        Formula::Sum(None) => "sum ".into(),
        Formula::Integral(None) => "integral ".into(),
        Formula::Integral(Some(limits)) => typst_integral(&limits.0, &limits.1, names)?,
        Formula::Nabla(None) => "nabla ".into(),
        Formula::Nabla(Some(by)) => format!("nabla_({}) ", typst_base(by)),
        Formula::At(a, frame) => {
            format!(
                "lr({} |)_(upright({}))",
                a.to_typst(names)?,
                typst_string(frame)
            )
        }
        Formula::Tex(t) => t.to_typst()?,
    };
    join(out, &piece);
    Ok(())
}

/// A matrix, or a column vector when it has one row.
fn typst_matrix(rows: &[Vec<Formula>], names: &Names) -> Result<String, TexError> {
    let mut cells = Vec::new();
    for row in rows {
        let row: Result<Vec<String>, TexError> = row.iter().map(|f| cell(f, names)).collect();
        cells.push(row?.join(", "));
    }
    // A column is one row written down.
    if let [one] = rows {
        let column: Result<Vec<String>, TexError> = one.iter().map(|f| f.to_typst(names)).collect();
        Ok(format!("vec({})", column?.join(", ")))
    } else {
        Ok(format!("mat({})", cells.join("; ")))
    }
}

/// An integral with its limits, set small: their fractions go on the line.
fn typst_integral(lo: &Formula, hi: &Formula, names: &Names) -> Result<String, TexError> {
    let limit = |f: &Formula| match f {
        Formula::Expr(e) => Ok(e.to_typst_on_the_line(names)),
        Formula::Frac(a, b) => Ok(format!("{}\\/{}", a.to_typst(names)?, b.to_typst(names)?)),
        other => other.to_typst(names),
    };
    Ok(format!("integral_({})^({}) ", limit(lo)?, limit(hi)?))
}

/// A matrix's cell: a fraction at the size of the line, as the expression printer sets one
/// (Typst sets a matrix's cells a size smaller, 2/3 too small to read on paper).
fn cell(f: &Formula, names: &Names) -> Result<String, TexError> {
    let cell = f.to_typst(names)?;
    Ok(match cell.contains("frac(") {
        true => format!("display({cell})"),
        false => cell,
    })
}

fn typst_op(op: Op) -> &'static str {
    match op {
        Op::Equals => " = ",
        Op::Approx => " approx ",
        Op::Less => " < ",
        Op::LessEqual => " <= ",
        Op::Greater => " > ",
        Op::Plus => " + ",
        Op::Minus => " - ",
        Op::Dot => " dot.op ",
        Op::Cross => " times ",
        Op::Parallel => " parallel ",
        Op::Perp => " perp ",
        Op::Comma => "\\, ",
        Op::Colon => ": ",
        Op::Semicolon => "\\; ",
        Op::Slash => " \\/ ",
        Op::Thin => " thin ",
        Op::Medium => " med ",
        Op::Quad => " quad ",
    }
}

/// A letter: a Greek one by its name (Typst's names are LaTeX's), else as written, a word
/// upright.
fn typst_base(base: &str) -> String {
    if let Some(letter) = crate::cas::greek_letter(base) {
        letter.to_string()
    } else if GREEK.iter().any(|(name, _)| *name == base) || base.chars().count() == 1 {
        base.to_string()
    } else {
        format!("upright({})", typst_string(base))
    }
}

fn typst_name(n: &Name) -> String {
    let base = typst_base(&n.base);
    let base = match n.accent {
        Accent::None => base,
        Accent::Vector => format!("arrow({base})"),
        Accent::Tensor => format!("accent({base}, arrow.l.r)"),
        Accent::Dot => format!("dot({base})"),
        Accent::DoubleDot => format!("dot.double({base})"),
        Accent::VectorDot => format!("dot(arrow({base}))"),
    };
    let sub = match n.sub.as_deref() {
        None => String::new(),
        Some(s @ ("min" | "max")) => format!("_({s})"),
        // A word is upright (I_cm); a pair of axes (I_xy) or a number is not.
        Some(s) if s.len() > 1 && !s.chars().all(|c| c.is_ascii_digit() || "xyz".contains(c)) => {
            format!("_(upright({}))", typst_string(s))
        }
        Some(s) if s.chars().all(|c| c.is_ascii_digit()) => format!("_({s})"),
        Some(s) => {
            let letters: Vec<String> = s.chars().map(|c| typst_base(&c.to_string())).collect();
            format!("_({})", letters.join(" "))
        }
    };
    let prime = if n.prime { "'" } else { "" };
    format!("{base}{sub}{prime}")
}

#[cfg(test)]
mod tests {
    use super::{Formula, Names};

    fn t(notation: &str) -> String {
        Formula::parse(notation, &[])
            .to_typst(Names::none())
            .unwrap()
    }

    /// Printed to be broken, a parenthesised sum with an exponent opens its parentheses (a
    /// paired group with an exponent is one piece Typst cannot break); whole, it is as before.
    #[test]
    fn a_power_of_a_group_opens_where_it_must_break() {
        let f = Formula::parse("(a + b)^2", &[]);
        assert_eq!(f.to_typst(Names::none()).unwrap(), "(a + b)^(2)");
        assert_eq!(
            f.to_typst_breakable(Names::none()).unwrap(),
            "\\(a + b\\)^(2)"
        );
    }

    #[test]
    fn names_accents_and_operators_in_typst() {
        assert_eq!(
            t("vec(L) = ten(I) ~ vec(omega)"),
            "arrow(L) = accent(I, arrow.l.r) thin arrow(ω)"
        );
        assert_eq!(t("2T ~ I_min <= L^2"), "2 T thin I_(min) <= L^(2)");
        assert_eq!(t("I_cm"), "I_(upright(\"cm\"))");
        assert_eq!(t("I_xy"), "I_(x y)");
        assert_eq!(
            t("beta = (I_3 - I_1)/I_1"),
            "β = frac(I_(3) - I_(1), I_(1))"
        );
    }
}
