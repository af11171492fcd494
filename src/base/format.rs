//! Deterministic number formatting, shared by captions, reports and pages.

/// A relative error or a time in compact scientific form; exact zero prints as 0.
pub fn sci(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else {
        format!("{x:.1e}")
    }
}

/// A tolerance or bound: `1e-10` rather than `1.0e-10`.
pub fn short(x: f64) -> String {
    sci(x).replace(".0e", "e")
}
