//! The step operations as data: one row per operation, with the fields it takes besides its own
//! key, what it holds for later steps, the names it gives besides its own, and whether an answer
//! can grade it. The validator, the scope of later steps, the graded answers and the list of
//! fields in an error all read this table; a new operation is one row here, its validation
//! under `validate/operation/`, and its exact rule beside its numeric route in one file under
//! `src/steps/`.

use super::raw::{RawStep, Text};

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

/// Which operation a row is: the one list the compiler checks each dispatch against (a
/// `match` on it names every operation, or fails to build).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OperationId {
    Be,
    Differentiate,
    Substitute,
    Lagrange,
    Routh,
    Momentum,
    Energy,
    Linearise,
    Frequency,
    Solve,
    Series,
    Integrate,
    Equilibria,
    Stability,
}

/// One step operation.
#[derive(Debug, Clone, Copy)]
pub struct OperationKind {
    pub id: OperationId,
    /// The key that names it in a `[[step]]`.
    pub name: &'static str,
    /// What the step does, in words: its heading on a page where its name is no symbol.
    pub heading: &'static str,
    /// The key's text in a step, where the step gives it.
    pub key: fn(&RawStep) -> Option<&Text>,
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

/// Every operation, in the order an error lists them, each row at its id's place.
pub const OPERATIONS: [OperationKind; 14] = [
    OperationKind {
        id: OperationId::Be,
        name: "be",
        heading: "Definition",
        key: |s| s.be.as_ref(),
        fields: &[],
        holds: Holds::Expression,
        several: Several::None,
        graded: true,
    },
    OperationKind {
        id: OperationId::Differentiate,
        name: "differentiate",
        heading: "Derivative",
        key: |s| s.differentiate.as_ref(),
        fields: &["by"],
        holds: Holds::Expression,
        several: Several::None,
        graded: false,
    },
    OperationKind {
        id: OperationId::Substitute,
        name: "substitute",
        heading: "Substitution",
        key: |s| s.substitute.as_ref(),
        fields: &["set"],
        holds: Holds::Operand,
        several: Several::None,
        graded: false,
    },
    OperationKind {
        id: OperationId::Lagrange,
        name: "lagrange",
        heading: "Equations of motion",
        key: |s| s.lagrange.as_ref(),
        fields: &["constraints", "start"],
        holds: Holds::Motion,
        several: Several::None,
        graded: false,
    },
    OperationKind {
        id: OperationId::Routh,
        name: "routh",
        heading: "Routhian",
        key: |s| s.routh.as_ref(),
        fields: &["cyclic", "start"],
        holds: Holds::Expression,
        several: Several::None,
        graded: false,
    },
    OperationKind {
        id: OperationId::Momentum,
        name: "momentum",
        heading: "Generalised momentum",
        key: |s| s.momentum.as_ref(),
        fields: &["of", "start"],
        holds: Holds::Expression,
        several: Several::None,
        graded: false,
    },
    OperationKind {
        id: OperationId::Energy,
        name: "energy",
        heading: "Energy function",
        key: |s| s.energy.as_ref(),
        fields: &["start"],
        holds: Holds::Expression,
        several: Several::None,
        graded: false,
    },
    OperationKind {
        id: OperationId::Linearise,
        name: "linearise",
        heading: "Linearised equations of motion",
        key: |s| s.linearise.as_ref(),
        fields: &["about"],
        holds: Holds::Linear,
        several: Several::None,
        graded: false,
    },
    OperationKind {
        id: OperationId::Frequency,
        name: "frequency",
        heading: "Frequency of small oscillations",
        key: |s| s.frequency.as_ref(),
        fields: &[],
        holds: Holds::Expression,
        several: Several::Modes,
        graded: true,
    },
    OperationKind {
        id: OperationId::Solve,
        name: "solve",
        heading: "Solution",
        key: |s| s.solve.as_ref(),
        fields: &["for"],
        holds: Holds::Expression,
        several: Several::Roots,
        graded: true,
    },
    OperationKind {
        id: OperationId::Series,
        name: "series",
        heading: "Series",
        key: |s| s.series.as_ref(),
        fields: &["about", "order"],
        holds: Holds::Expression,
        several: Several::None,
        graded: false,
    },
    OperationKind {
        id: OperationId::Integrate,
        name: "integrate",
        heading: "Integral",
        key: |s| s.integrate.as_ref(),
        fields: &["over"],
        holds: Holds::Expression,
        several: Several::None,
        graded: true,
    },
    OperationKind {
        id: OperationId::Equilibria,
        name: "equilibria",
        heading: "States of rest",
        key: |s| s.equilibria.as_ref(),
        fields: &[],
        holds: Holds::Equilibria,
        several: Several::States,
        graded: false,
    },
    OperationKind {
        id: OperationId::Stability,
        name: "stability",
        heading: "Stability",
        key: |s| s.stability.as_ref(),
        fields: &[],
        holds: Holds::Expression,
        several: Several::States,
        graded: false,
    },
];

/// A field that belongs to some operations and not others: its key, what it is (`{ops}` is
/// replaced by the operations that take it, from the table: "a `linearise` or `series`"), and
/// whether a step gives it. A step that gives one and has another operation is refused with
/// its sentence, in this order.
pub struct OperationField {
    pub name: &'static str,
    pub what: &'static str,
    pub given: fn(&RawStep) -> bool,
}

pub const OPERATION_FIELDS: [OperationField; 10] = [
    OperationField {
        name: "by",
        what: "`by` names what {ops} step differentiates by",
        given: |s| s.by.is_some(),
    },
    OperationField {
        name: "set",
        what: "`set` gives the replacements of {ops} step",
        given: |s| !s.set.is_empty(),
    },
    OperationField {
        name: "for",
        what: "`for` names the unknown of {ops} step",
        given: |s| s.unknown.is_some(),
    },
    OperationField {
        name: "about",
        what: "`about` is the state {ops} step expands about",
        given: |s| !s.about.is_empty(),
    },
    OperationField {
        name: "over",
        what: "`over` gives the ranges of {ops} step",
        given: |s| !s.over.is_empty(),
    },
    OperationField {
        name: "order",
        what: "`order` is the last power of {ops} step",
        given: |s| s.order.is_some(),
    },
    OperationField {
        name: "cyclic",
        what: "`cyclic` names the cyclic coordinates of {ops} step",
        given: |s| !s.cyclic.is_empty(),
    },
    OperationField {
        name: "constraints",
        what: "`constraints` gives the constraints of {ops} step, each under its multiplier's name",
        given: |s| !s.constraints.is_empty(),
    },
    OperationField {
        name: "of",
        what: "`of` names the Lagrangian of {ops} step",
        given: |s| s.of.is_some(),
    },
    OperationField {
        name: "start",
        what: "`start` is the initial state of the motion {ops} step's numeric check integrates",
        given: |s| !s.start.is_empty(),
    },
];

impl OperationId {
    /// Its row of the table.
    pub fn kind(self) -> &'static OperationKind {
        &OPERATIONS[self as usize]
    }
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
    let f = OPERATION_FIELDS.iter().find(|f| f.name == field)?;
    Some(format!(
        "{}; this step has none",
        f.what.replace("{ops}", &taken_by(field))
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_operation_field_is_taken_by_an_operation_and_every_taken_field_is_listed() {
        for f in OPERATION_FIELDS {
            assert!(
                !taken_by(f.name).is_empty(),
                "`{}` belongs to no operation",
                f.name
            );
            assert!(
                f.what.contains("{ops}"),
                "`{}`'s sentence names no operation",
                f.name
            );
        }
        for (i, k) in OPERATIONS.iter().enumerate() {
            assert_eq!(k.id as usize, i, "`{}` is not at its id's place", k.name);
            assert!(std::ptr::eq(k.id.kind(), k));
            for f in k.fields {
                assert!(
                    OPERATION_FIELDS.iter().any(|g| g.name == *f),
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
