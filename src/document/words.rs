//! What every renderer says of a page in the same words: a result's heading and equation, a
//! numeric check's sentence, the scene's values, the entries of a result at its numbers, and
//! how a claim leads into its formula. Decided here once, so that the page and the paper agree.

use super::{At, Page, PrincipalAxis, PrincipalValues, Quantity};
use crate::base::format::sci;
use crate::cas::Expr;
use crate::derive::ExactBasis;
use crate::model::value::Value;
use crate::notation::{Formula, Op};
use std::collections::BTreeMap;

/// A result's heading: a catalogue quantity's name in words; none for a step's result, whose
/// equation names it (`ẍ₁ = …`).
pub fn result_heading(q: &Quantity) -> String {
    match q.symbol {
        Some(_) => String::new(),
        None => crate::model::catalogue::heading(&q.name),
    }
}

/// A step's result as the page states it: `symbol = value`.
pub fn result_equation(symbol: &Expr, value: &Value) -> Formula {
    Formula::equation(Formula::Expr(symbol.clone()), value.to_expr())
}

/// A computed number to `digits` significant figures as a formula: its digits, and its power
/// of ten as a power (4.6875 × 10⁻⁶, never e-notation).
pub fn number(x: f64, digits: usize) -> Formula {
    Formula::decimal(&crate::base::format::significant(x, digits))
}

/// A principal moment's heading.
pub fn principal_axis_heading(sp: &PrincipalAxis) -> String {
    format!("Principal moment (multiplicity {})", sp.multiplicity)
}

/// A principal moment with its axis, its plane of axes, or every axis: `λ along (1, 0, 0)`.
pub fn principal_axis(sp: &PrincipalAxis) -> Formula {
    let vector = |v: &[Expr; 3]| Formula::Expr(Value::Vector(v.clone()).to_expr());
    let mut row = vec![Formula::Expr(sp.value.clone())];
    match &sp.basis {
        ExactBasis::Axis(a) => row.extend([Formula::Text(" along ".into()), vector(a)]),
        ExactBasis::PlaneNormalTo(n) => row.extend([
            Formula::Text(", every axis ".into()),
            Formula::Op(Op::Perp),
            vector(n),
        ]),
        ExactBasis::All => row.push(Formula::Text(", every axis".into())),
    }
    Formula::Row(row)
}

/// The heading of the principal moments at the scene's values.
pub const PRINCIPAL_VALUES_HEADING: &str = "Principal moments at the scene's values";

/// The principal moments at the scene's values, `λ = 1, 2, 3`, and where they come from the
/// closed form, the eigen-solver's axes to four figures.
pub fn principal_values(p: &PrincipalValues) -> Formula {
    use crate::numeric::eigen::Space;
    let letter = Formula::Name(crate::notation::Name::letter(&p.letter));
    let mut row = vec![
        letter,
        Formula::Op(Op::Equals),
        listed(p.exact.iter().map(|v| number(*v, 6))),
    ];
    if p.closed_form {
        let axes: Vec<Formula> = p
            .numeric
            .iter()
            .filter_map(|e| match &e.space {
                Space::Axis(v) => Some(Formula::Paren(
                    Box::new(Formula::Row(vec![
                        number(v.x, 4),
                        Formula::Op(Op::Comma),
                        number(v.y, 4),
                        Formula::Op(Op::Comma),
                        number(v.z, 4),
                    ])),
                    true,
                )),
                _ => None,
            })
            .collect();
        if !axes.is_empty() {
            row.extend([
                Formula::Op(Op::Quad),
                Formula::Text("axes ".into()),
                listed(axes),
            ]);
        }
    }
    Formula::Row(row)
}

/// How the principal moments at the scene's values were found, and how well the eigen-solver
/// agrees with them.
pub fn principal_values_agree(p: &PrincipalValues) -> String {
    let route = match p.closed_form {
        true => "the closed form above",
        false => "the exact roots",
    };
    format!(
        "{route} evaluated, and the eigen-solver on the exact tensor agrees to {} (relative)",
        sci(p.error)
    )
}

/// Formulas one after another, set apart by a comma and a space: `a = 1,\; b = 2`.
pub fn listed(items: impl IntoIterator<Item = Formula>) -> Formula {
    let mut row = Vec::new();
    for item in items {
        if !row.is_empty() {
            row.extend([Formula::Op(Op::Comma), Formula::Op(Op::Medium)]);
        }
        row.push(item);
    }
    Formula::Row(row)
}

/// Numbers (`n`, row-major) in the shape of `v`: a number, a column or a matrix.
pub fn numbers_formula(v: &Value, mut n: Vec<Formula>) -> Formula {
    match v {
        Value::Scalar(_) => n.swap_remove(0),
        Value::Vector(_) => Formula::Matrix(vec![n]),
        Value::Matrix(_) => Formula::Matrix(n.chunks(3).map(<[Formula]>::to_vec).collect()),
    }
}

/// An author's step's numeric check in one sentence, for every printer.
pub fn check_sentence(c: &crate::verify::StepCheck) -> String {
    match &c.problem {
        Some(p) => format!("Not checked numerically: {p}"),
        None => format!(
            "Checked numerically, by {}: {} {} (within {}), {} evaluations.",
            c.method,
            if c.passed() {
                "agrees to"
            } else {
                "FAILS, differs by"
            },
            sci(c.error),
            sci(c.tolerance),
            c.evaluations
        ),
    }
}

/// A result's entries at the scene's numbers, an entry below the rounding of the largest
/// (cos(π/2) in floats, 6e-17) made zero.
pub fn at_entries(at: &At) -> Vec<f64> {
    let largest = at.numbers.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    at.numbers
        .iter()
        .map(|x| {
            if x.abs() <= 64.0 * f64::EPSILON * largest {
                0.0
            } else {
                *x
            }
        })
        .collect()
}

/// The scene's values with their units, `M = 1 kg, α = 0.6`, as one formula.
pub fn values_at(values: &[(String, f64)], units: &BTreeMap<String, String>) -> Formula {
    listed(values.iter().map(|(name, x)| {
        let value = Formula::Row(vec![
            Formula::Expr(Expr::sym(name)),
            Formula::Op(Op::Equals),
            Formula::decimal(&x.to_string()),
        ]);
        with_unit(value, units.get(name))
    }))
}

/// A number followed by its unit, a thin space between: 9.81 m/s².
pub fn with_unit(f: Formula, unit: Option<&String>) -> Formula {
    match unit {
        Some(u) => Formula::Row(vec![
            f,
            Formula::Op(Op::Thin),
            crate::model::units::unit_formula(u),
        ]),
        None => f,
    }
}

/// The symbols of a result at the scene's numbers, each with its value and unit:
/// `d = 0.03 m, m = 0.4 kg`.
pub fn at_symbols(at: &At) -> Formula {
    listed(at.symbols.iter().map(|(k, x)| {
        with_unit(
            Formula::Row(vec![
                Formula::Expr(Expr::sym(k)),
                Formula::Op(Op::Equals),
                number(*x, 6),
            ]),
            at.units.get(k),
        )
    }))
}

/// A result's entries at the scene's numbers, to six figures, in its shape, with its unit.
pub fn at_value(v: &Value, at: &At) -> Formula {
    let n: Vec<Formula> = at_entries(at).into_iter().map(|x| number(x, 6)).collect();
    with_unit(numbers_formula(v, n), at.unit.as_ref())
}

/// A claim's statement as the lead of its formula ("The tension in the string: T = …"): its
/// first letter a capital, its closing full stop dropped; `None` where the statement writes an
/// equation of its own ("$\\beta^2 = …$: the linearised equations …"), which the formula
/// would repeat.
pub fn claim_lead(statement: &str) -> Option<String> {
    let math_has_equation = statement
        .split('$')
        .skip(1)
        .step_by(2)
        .any(|m| m.contains('=') || m.contains("\\approx"));
    if math_has_equation {
        return None;
    }
    let s = statement.trim_end();
    let s = s.strip_suffix('.').unwrap_or(s);
    let mut chars = s.chars();
    chars
        .next()
        .map(|first| first.to_uppercase().chain(chars).collect())
}

/// Whether an agreeing claim's list item prints its formula after its statement: a scalar
/// claim with a left side, or one whose statement holds no mathematics (a statement that
/// writes "$|\\vec L|^2$ is constant: $I_1^2 A^2 + …$" is not followed by "I₁²A² + …" again).
pub fn claim_shows_formula(page: &Page, i: usize) -> bool {
    let c = &page.claims[i];
    let has_left = page.claim_left(i).is_some();
    matches!(c.derived, Some(Value::Scalar(_))) && (has_left || !c.statement.contains('$'))
}
