//! What an author wrote that reads as another language's mathematics (Python's `**`, SymPy's
//! `Eq`, `phidot`, `diff(phi, t)`): the message says how a scene writes it.

use crate::cas::Expr;
use std::collections::BTreeSet;

/// An undefined name's message: what to write for a coordinate's rate (`phidot`), else the
/// nearest name, and the names the scene has.
pub(super) fn undefined_name(name: &str, names: &BTreeSet<String>, claim: bool) -> String {
    let hint = rate(name, names).unwrap_or_else(|| {
        crate::base::suggest::did_you_mean(name, names.iter().map(String::as_str))
    });
    if !claim {
        let known = names.iter().cloned().collect::<Vec<_>>().join(", ");
        return format!(
            "undefined symbol `{name}`{hint}: declare it under [symbols] (declared: {known})"
        );
    }
    // The scene's own names; the derived quantities' are in docs/scenes.md.
    let own = names
        .iter()
        .filter(|n| !crate::model::catalogue::is_quantity(n))
        .cloned()
        .collect::<Vec<_>>()
        .join(", ");
    format!(
        "undefined name `{name}`{hint}: not a symbol, definition, vector or derived quantity of \
         this scene; its names are {own}, and the derived quantities (docs/scenes.md, \"Derived \
         quantities\")"
    )
}

/// For `phidot`, `phi_dot`, `phiddot` where `phi` is a coordinate: how its rates are written.
fn rate(name: &str, names: &BTreeSet<String>) -> Option<String> {
    let (stem, primes) = [("_ddot", "''"), ("ddot", "''"), ("_dot", "'"), ("dot", "'")]
        .into_iter()
        .find_map(|(end, primes)| Some((name.strip_suffix(end)?, primes)))?;
    let rate = format!("{stem}{primes}");
    names
        .contains(&rate)
        .then(|| format!(" (the rate of the coordinate `{stem}` is written `{rate}`)"))
}

/// In a scene with coordinates, a `diff(x, t)`, which would be 0: a coordinate is a name in an
/// expression, not a function of t.
pub(super) fn time_derivative(e: &Expr, names: &BTreeSet<String>) -> Option<String> {
    if !names.iter().any(|n| n.ends_with('\'')) {
        return None;
    }
    let of = first_time_derivative(e)?;
    Some(format!(
        "`diff({of}, t)` would be 0: in an expression a coordinate is a name, not a function of \
         t; write a rate as `phi'` (and `phi''`), or take a total time derivative with a step: \
         differentiate = \"…\", by = \"t\""
    ))
}

/// The first `diff(x, t)` in `e`, as `x` is written.
fn first_time_derivative(e: &Expr) -> Option<String> {
    match e {
        Expr::Call(name, args)
            if name == "diff" && matches!(args.get(1), Some(Expr::Sym(t)) if t == "t") =>
        {
            Some(args[0].to_text())
        }
        Expr::Add(v) | Expr::Mul(v) | Expr::Call(_, v) | Expr::List(v) => {
            v.iter().find_map(first_time_derivative)
        }
        Expr::Pow(b, x) | Expr::Index(b, x) => {
            first_time_derivative(b).or_else(|| first_time_derivative(x))
        }
        _ => None,
    }
}

/// SymPy's way of writing what a scene writes otherwise.
pub(super) fn sympy(name: &str) -> Option<&'static str> {
    match name {
        "Eq" => Some(
            " (SymPy's equation: in a `gives` write `lhs = rhs`, elsewhere the expression \
             `lhs - rhs`)",
        ),
        "Derivative" => Some(" (write a rate as `phi'`, a partial derivative as diff(f, x))"),
        "Rational" => Some(" (write a fraction as 1/3)"),
        _ => None,
    }
}
