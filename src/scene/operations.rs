//! The step operations as data: one row per operation, with the fields it takes besides its own
//! key, what it holds for later steps, the names it gives besides its own, and whether an answer
//! can grade it. The validator, the scope of later steps, the graded answers and the list of
//! fields in an error all read this table; a new operation is one row here, its validation
//! under `validate/operation/`, and its exact rule beside its numeric route in one file under
//! `src/steps/`.

/// What a step holds for the steps after it, which decides the operations that can take it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Holds {
    Expression,
    /// Equations of motion from `lagrange`.
    Motion,
    /// Linear equations of motion from `linearise`.
    Linear,
    /// States of rest from `equilibria`.
    Equilibria,
    /// What its operand holds: equations with names replaced are still equations of their kind.
    Operand,
}

/// The names a step gives besides its own.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Several {
    /// Only its own name.
    None,
    /// Of n ≥ 2 coordinates, one mode per coordinate (`Omega_1` … `Omega_n`).
    Modes,
    /// Its roots or unknowns when it has several (`x_1` … `x_8`).
    Roots,
    /// One per state of rest (`rest_1` … `rest_8`); `gives` cannot state them all.
    States,
}

/// One step operation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OperationKind {
    /// The key that names it in a `[[step]]`.
    pub name: &'static str,
    /// The fields it takes besides its own key and the ones every step has (`name`, `gives`,
    /// `why`, `eq`, `expect`, `role`, `tex`).
    pub fields: &'static [&'static str],
    pub holds: Holds,
    pub several: Several,
    /// Whether its result has a numeric value of its own at any values, so an answer can grade
    /// it: `be` (the expression as written), `frequency` (the modes' or the integrated motion's),
    /// `solve` (Newton's method on the equation), `integrate` (quadrature).
    pub graded: bool,
}

const fn kind(
    name: &'static str,
    fields: &'static [&'static str],
    holds: Holds,
    several: Several,
    graded: bool,
) -> OperationKind {
    OperationKind {
        name,
        fields,
        holds,
        several,
        graded,
    }
}

/// Every operation, in the order an error lists them.
pub const OPERATIONS: [OperationKind; 14] = [
    kind("be", &[], Holds::Expression, Several::None, true),
    kind(
        "differentiate",
        &["by"],
        Holds::Expression,
        Several::None,
        false,
    ),
    kind("substitute", &["set"], Holds::Operand, Several::None, false),
    kind(
        "lagrange",
        &["constraints", "start"],
        Holds::Motion,
        Several::None,
        false,
    ),
    kind(
        "routh",
        &["cyclic", "start"],
        Holds::Expression,
        Several::None,
        false,
    ),
    kind(
        "momentum",
        &["of", "start"],
        Holds::Expression,
        Several::None,
        false,
    ),
    kind(
        "energy",
        &["start"],
        Holds::Expression,
        Several::None,
        false,
    ),
    kind("linearise", &["about"], Holds::Linear, Several::None, false),
    kind("frequency", &[], Holds::Expression, Several::Modes, true),
    kind("solve", &["for"], Holds::Expression, Several::Roots, true),
    kind(
        "series",
        &["about", "order"],
        Holds::Expression,
        Several::None,
        false,
    ),
    kind(
        "integrate",
        &["over"],
        Holds::Expression,
        Several::None,
        true,
    ),
    kind("equilibria", &[], Holds::Equilibria, Several::States, false),
    kind("stability", &[], Holds::Expression, Several::States, false),
];

/// The fields that belong to some operations and not others, each with what it is: `{ops}` is
/// replaced by the operations that take it, from the table (`a `linearise` or `series``).
/// A step that gives one of them and has another operation is refused with this sentence, in
/// this order.
pub const OPERATION_FIELDS: [(&str, &str); 10] = [
    ("by", "`by` names what {ops} step differentiates by"),
    ("set", "`set` gives the replacements of {ops} step"),
    ("for", "`for` names the unknown of {ops} step"),
    ("about", "`about` is the state {ops} step expands about"),
    ("over", "`over` gives the ranges of {ops} step"),
    ("order", "`order` is the last power of {ops} step"),
    (
        "cyclic",
        "`cyclic` names the cyclic coordinates of {ops} step",
    ),
    (
        "constraints",
        "`constraints` gives the constraints of {ops} step, each under its multiplier's name",
    ),
    ("of", "`of` names the Lagrangian of {ops} step"),
    (
        "start",
        "`start` is the initial state of the motion {ops} step's numeric check integrates",
    ),
];

/// The row of the operation named `name`.
pub fn operation_kind(name: &str) -> Option<&'static OperationKind> {
    OPERATIONS.iter().find(|k| k.name == name)
}

/// The operations that take `field`, as a sentence's noun: "a `linearise` or `series`".
pub fn taken_by(field: &str) -> String {
    let names: Vec<String> = OPERATIONS
        .iter()
        .filter(|k| k.fields.contains(&field))
        .map(|k| format!("`{}`", k.name))
        .collect();
    match names.as_slice() {
        [] => String::new(),
        [one] => format!("a {one}"),
        [init @ .., last] => format!("a {} or {last}", init.join(", ")),
    }
}

/// The sentence that refuses `field` on a step of another operation.
pub fn stray_field_message(field: &str) -> Option<String> {
    let (_, what) = OPERATION_FIELDS.iter().find(|(f, _)| *f == field)?;
    Some(format!(
        "{}; this step has none",
        what.replace("{ops}", &taken_by(field))
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_operation_field_is_taken_by_an_operation_and_every_taken_field_is_listed() {
        for (field, what) in OPERATION_FIELDS {
            assert!(
                !taken_by(field).is_empty(),
                "`{field}` belongs to no operation"
            );
            assert!(
                what.contains("{ops}"),
                "`{field}`'s sentence names no operation"
            );
        }
        for k in OPERATIONS {
            for f in k.fields {
                assert!(
                    OPERATION_FIELDS.iter().any(|(g, _)| g == f),
                    "`{}` takes `{f}`, which has no sentence",
                    k.name
                );
            }
        }
        let names: std::collections::BTreeSet<_> = OPERATIONS.iter().map(|k| k.name).collect();
        assert_eq!(names.len(), OPERATIONS.len(), "an operation listed twice");
    }

    #[test]
    fn the_stray_sentences_name_the_operations_from_the_table() {
        assert_eq!(
            stray_field_message("about").unwrap(),
            "`about` is the state a `linearise` or `series` step expands about; this step has none"
        );
        assert_eq!(
            stray_field_message("start").unwrap(),
            "`start` is the initial state of the motion a `lagrange`, `routh`, `momentum` or \
             `energy` step's numeric check integrates; this step has none"
        );
        assert_eq!(stray_field_message("gives"), None);
    }
}
