//! The elementary functions an expression may call: each one's number of arguments, printed
//! name, unit rule and value. The parser, the engine, the evaluators and the checks of units
//! all read it, so that a function known to one stage is known to all; each one's derivative is
//! `Expr::diff`'s (`expr.rs`), its exact values and inverses `exact_values.rs`'s.
//!
//! `tan x` and `tanh x` are read as `sin x / cos x` and `sinh x / cosh x` (see `parse`), `ln` as
//! `log`: every later stage sees only these.

/// The scalar functions the engine and the evaluators understand.
pub const SCALAR_FUNCTIONS: &[&str] = &[
    "sin", "cos", "sqrt", "exp", "log", "asin", "acos", "atan", "atan2", "sinh", "cosh", "abs",
];

/// The number of arguments of elementary function `name`; `None` for any other name.
pub fn arity(name: &str) -> Option<usize> {
    match name {
        "atan2" => Some(2),
        n if SCALAR_FUNCTIONS.contains(&n) => Some(1),
        _ => None,
    }
}

/// The function's name as a textbook sets it: arcsin, arccos, arctan, ln; the others as
/// written.
pub fn textbook_name(name: &str) -> &str {
    match name {
        "asin" => "arcsin",
        "acos" => "arccos",
        "atan" => "arctan",
        "log" => "ln",
        other => other,
    }
}

/// Whether the function takes only a pure number (an angle, a ratio) and gives one: `sqrt` and
/// `abs` keep their argument's unit, `atan2` takes two of one unit.
pub fn needs_dimensionless(name: &str) -> bool {
    matches!(
        name,
        "sin" | "cos" | "exp" | "log" | "asin" | "acos" | "atan" | "sinh" | "cosh"
    )
}

/// The value of `name` at `args`; `None` for a name that is not elementary or a wrong number of
/// arguments. Outside a function's real domain the value is NaN, as f64's own.
pub fn value(name: &str, args: &[f64]) -> Option<f64> {
    Some(match (name, args) {
        ("sin", [x]) => x.sin(),
        ("cos", [x]) => x.cos(),
        ("sqrt", [x]) => x.sqrt(),
        ("exp", [x]) => x.exp(),
        ("log", [x]) => x.ln(),
        ("asin", [x]) => x.asin(),
        ("acos", [x]) => x.acos(),
        ("atan", [x]) => x.atan(),
        ("atan2", [y, x]) => y.atan2(*x),
        ("sinh", [x]) => x.sinh(),
        ("cosh", [x]) => x.cosh(),
        ("abs", [x]) => x.abs(),
        _ => return None,
    })
}
