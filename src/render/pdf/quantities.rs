//! Numbers and units as the PDFs print them, shared by the handouts and the problem sheets.

use crate::model::units::unit_formula;
use crate::model::value::Value;
use crate::notation::{Names, Tex};

/// Numbers in the shape of `v`: a number, a row or a matrix.
pub(super) fn numbers_typst(v: &Value, n: &[String]) -> String {
    match v {
        Value::Scalar(_) => n[0].clone(),
        Value::Vector(_) => format!("mat({})", n.join(", ")),
        Value::Matrix(_) => format!(
            "mat({})",
            n.chunks(3)
                .map(|row| row.join(", "))
                .collect::<Vec<_>>()
                .join("; ")
        ),
    }
}

/// A unit in words, after its number, said from the tree the page sets, as its alternative
/// text says it.
pub(super) fn said_unit(text: &str) -> String {
    format!(" {}", unit_tex(text).spoken())
}

/// A unit in Typst's math, printed from the tree the page sets (`model::units::unit_formula`):
/// each symbol upright with its power, thin spaces between.
pub(super) fn unit_typst(text: &str) -> String {
    super::markup::typst(&unit_tex(text))
}

fn unit_tex(text: &str) -> Tex {
    unit_formula(text).to_tex(Names::none())
}
