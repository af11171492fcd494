//! Numbers and units as the PDFs print them, shared by the handouts and the problem sheets.

use crate::model::value::Value;

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

/// A unit in words, after its number: " m per s squared".
pub(super) fn said_unit(text: &str) -> String {
    let words = text
        .replace('*', " ")
        .replace('/', " per ")
        .replace("^2", " squared")
        .replace("^3", " cubed")
        .replace('^', " to the power ");
    format!(" {words}")
}

/// A unit in Typst's math, upright: `kg m^2/s` as kg m²/s, each power raised after the text
/// before it.
pub(super) fn unit_typst(text: &str) -> String {
    let text = text.replace('*', " ");
    let mut out = String::new();
    let mut rest = text.as_str();
    while let Some(i) = rest.find('^') {
        let power: String = rest[i + 1..]
            .chars()
            .take_while(|c| c.is_ascii_digit() || *c == '-')
            .collect();
        out.push_str(&format!(
            "upright({})^({}) ",
            crate::base::typst::typst_string(&rest[..i]),
            power.replace('-', "−")
        ));
        rest = &rest[i + 1 + power.len()..];
    }
    if !rest.is_empty() {
        out.push_str(&format!(
            "upright({})",
            crate::base::typst::typst_string(rest)
        ));
    }
    out.trim_end().to_string()
}
