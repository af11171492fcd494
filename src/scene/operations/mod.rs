//! The step operations. The table below gives each its row: its type and key, its heading,
//! the fields it takes besides its key, what it holds for later steps, the names it gives
//! besides its own and whether an answer can grade it; the `Operation` enum, the rows and each
//! dispatch on an operation are made from it. Each operation's file here holds its type and the
//! checks of its fields when the scene is read; what it does (its exact rule and its numeric
//! route) is its file of the same name under `src/steps/`.

mod be;
mod differentiate;
mod energy;
mod equilibria;
mod frequency;
mod integrate;
mod lagrange;
mod linearise;
mod momentum;
mod routh;
mod series;
mod solve;
mod stability;
mod substitute;

pub use solve::MAX_UNKNOWNS;

use super::error::SceneError;
use super::raw::{RawStep, Text};
use crate::cas::Expr;
use std::collections::{BTreeMap, BTreeSet};

/// The table: every operation once, in the order an error lists them, its type, its key (the
/// name of its files here and under `src/steps/`) and its row. `with_operations!(m)` hands the
/// table to the macro `m`, which writes what names every operation (the enum below, the rows,
/// the dispatches in `validate/` and `steps/`); the files are declared above, where `cargo fmt`
/// sees them.
macro_rules! with_operations {
    ($then:ident) => {
        $then! {
            // Its type and its key (its files' name); (its heading, the fields it takes
            // besides its key, what it holds, the names it gives besides its own, graded).
            Be be ("Definition", [], Expression, None, true),
            Differentiate differentiate ("Derivative", ["by"], Expression, None, false),
            Substitute substitute ("Substitution", ["set"], Operand, None, false),
            Lagrange lagrange ("Equations of motion", ["constraints", "start"], Motion, None, false),
            Routh routh ("Routhian", ["cyclic", "start"], Expression, None, false),
            Momentum momentum ("Generalised momentum", ["of", "start"], Expression, None, false),
            Energy energy ("Energy function", ["start"], Expression, None, false),
            Linearise linearise ("Linearised equations of motion", ["about"], Linear, None, false),
            Frequency frequency ("Frequency of small oscillations", [], Expression, Modes, true),
            Solve solve ("Solution", ["for"], Expression, Roots, true),
            Series series ("Series", ["about", "order"], Expression, None, false),
            Integrate integrate ("Integral", ["over"], Expression, None, true),
            Equilibria equilibria ("States of rest", [], Equilibria, States, false),
            Stability stability ("Stability", [], Expression, States, false),
        }
    };
}
pub(crate) use with_operations;

/// The enum of the operations, their ids and their table, from the list.
macro_rules! operations {
    ($($op:ident $file:ident ($heading:literal, [$($field:literal),*], $holds:ident,
        $several:ident, $graded:literal),)*) => {
        $(pub use $file::$op;)*

        /// What a step does: one of the operations, with its fields.
        #[derive(Debug, Clone, PartialEq)]
        pub enum Operation {
            $($op($op),)*
        }

        /// Which operation it is, without its fields.
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum OperationId {
            $($op,)*
        }

        /// Every operation's row, in the order an error lists them, each at its id's place.
        pub const OPERATIONS: &[OperationKind] = &[$(OperationKind {
            name: stringify!($file),
            heading: $heading,
            key: |s| s.$file.as_ref(),
            fields: &[$($field),*],
            holds: Holds::$holds,
            several: Several::$several,
            graded: $graded,
        },)*];

        impl OperationId {
            /// Every operation, in the table's order.
            pub const ALL: &[OperationId] = &[$(OperationId::$op,)*];
        }

        impl Operation {
            /// Which operation it is.
            pub fn id(&self) -> OperationId {
                match self {
                    $(Operation::$op(_) => OperationId::$op,)*
                }
            }

            /// The expressions the author wrote as its operands (an integral's limits, a
            /// series' point, a substitution's replacements): an operation that takes an
            /// earlier step by name has none.
            pub fn operands(&self) -> Vec<&Expr> {
                match self {
                    $(Operation::$op(op) => op.operands(),)*
                }
            }
        }

        /// The step's operation `id`, its fields read from the step by its own file; `key`
        /// is the text of its key.
        pub fn read_operation(
            id: OperationId,
            key: &Text,
            step: &RawStep,
            f: &impl StepFields,
        ) -> Result<Operation, SceneError> {
            Ok(match id {
                $(OperationId::$op => Operation::$op($op::read(key, step, f)?),)*
            })
        }
    };
}
with_operations!(operations);

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

/// An operation's type: how its fields are read from a step, and the expressions among them.
pub trait OperationType: Sized {
    /// Its fields, from the step whose key for it holds `key`, each checked.
    fn read(key: &Text, step: &RawStep, f: &impl StepFields) -> Result<Self, SceneError>;

    /// The expressions the author wrote among its fields.
    fn operands(&self) -> Vec<&Expr> {
        Vec::new()
    }
}

/// What an operation's file checks its fields against, and reports through: the validator at
/// this step (`validate/operation/mod.rs`), so that the operations need not import it.
pub trait StepFields {
    /// An error at byte `at` of the scene file, under the field `field` (`step.3.by`).
    fn err(&self, at: usize, field: &str, message: impl Into<String>) -> SceneError;
    /// Where the step starts in the file.
    fn offset(&self) -> usize;
    /// The step's own field (`step.3`).
    fn field(&self) -> &str;
    /// The names in scope at the step: the scene's, the coordinates' and the earlier steps'.
    fn scope(&self) -> &BTreeSet<String>;
    /// What each earlier step holds.
    fn earlier(&self) -> &BTreeMap<String, Holds>;
    /// The coordinates with their meanings.
    fn coordinates(&self) -> &BTreeMap<String, String>;
    /// The names the author declared in [symbols].
    fn declared(&self) -> &BTreeSet<String>;
    /// An expression of `names`, at field `key`.
    fn expression(&self, t: &Text, key: &str, names: &BTreeSet<String>)
    -> Result<Expr, SceneError>;
    /// An operand written under the step's field `key`: an expression of the names in scope,
    /// in which a coordinate's rate is named as such.
    fn operand(&self, t: &Text, key: &str) -> Result<Expr, SceneError>;
    /// The earlier step that the operation `op` takes, holding what it needs.
    fn taken(&self, of: &Text, op: &str, needs: Holds) -> Result<String, SceneError>;
    /// The earlier step holding the Lagrangian that `op` takes, in a scene with coordinates.
    fn lagrangian(&self, of: &Text, op: &str) -> Result<String, SceneError>;

    /// A name the operation works in (`by`, a `set` name, a `series` variable): one of the
    /// scene's symbols, coordinates, rates or `t`, not an earlier step's.
    fn own_name(&self, name: &str) -> bool {
        self.scope().contains(name) && !self.earlier().contains_key(name)
    }

    /// The scene's names without the coordinates, their rates and the time: a state of rest
    /// is given in them.
    fn names_only(&self) -> BTreeSet<String> {
        self.scope()
            .iter()
            .filter(|n| *n != "t" && !n.ends_with('\'') && !self.coordinates().contains_key(*n))
            .cloned()
            .collect()
    }
}

/// One step operation.
#[derive(Debug, Clone, Copy)]
pub struct OperationKind {
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

impl Operation {
    /// The operation's row in the table of operations.
    pub fn kind(&self) -> &'static OperationKind {
        self.id().kind()
    }

    /// What the step does, in words: its heading on a page where its name is no symbol.
    pub fn heading(&self) -> &'static str {
        self.kind().heading
    }

    pub fn name(&self) -> &'static str {
        self.kind().name
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
        for k in OPERATIONS {
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

    /// docs/scenes.md has a row for every operation of the table, by its key.
    #[test]
    fn the_authors_guide_documents_every_operation() {
        let guide = include_str!("../../../docs/scenes.md");
        for k in OPERATIONS {
            assert!(
                guide.contains(&format!("\n| `{} = ", k.name)),
                "docs/scenes.md has no row for `{}`",
                k.name
            );
        }
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
