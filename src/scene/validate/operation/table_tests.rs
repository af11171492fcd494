//! The table of operations drives the validator: each operation in a well-formed step loads,
//! and each field of another operation on it is refused with the table's sentence.

use crate::scene::operations::{OPERATION_FIELDS, OPERATIONS, OperationId, stray_field_message};
use crate::scene::{Operation, Scene};
use std::path::Path;

/// A pendulum with its Lagrangian, equations, linear equations and states of rest, and a last
/// step `X` of the caller's.
fn scene_with(step: &str) -> String {
    include_str!("../../../../tests/fixtures/unit/operation-table-pendulum.toml")
        .replace("{step}", step)
}

/// A well-formed step of each operation, by name.
fn well_formed(name: &str) -> &'static str {
    match name {
        "be" => "be = \"Lag\"",
        "differentiate" => "differentiate = \"Lag\"\nby = \"th'\"",
        "substitute" => "substitute = \"Lag\"\nset = { \"ph'\" = \"0\" }",
        "lagrange" => "lagrange = \"Lag\"\nconstraints = { T = \"th - ph\" }\nstart = { th = 0.1 }",
        "routh" => "routh = \"Lag\"\ncyclic = { ph = \"p\" }\nstart = { th = 0.1 }",
        "momentum" => "momentum = \"ph\"\nof = \"Lag\"\nstart = { th = 0.1 }",
        "energy" => "energy = \"Lag\"\nstart = { th = 0.1 }",
        "linearise" => "linearise = \"eom\"\nabout = { th = \"0\" }",
        "frequency" => "frequency = \"lin\"",
        "solve" => "solve = \"eom\"\nfor = \"th''\"",
        "series" => "series = \"Lag\"\nabout = { th = \"0\" }\norder = 2",
        "integrate" => "integrate = \"x\"\nover = [[\"x\", \"0\", \"l\"]]",
        "equilibria" => "equilibria = \"eom\"",
        "stability" => "stability = \"rest\"",
        other => panic!("no well-formed step of `{other}`: add one"),
    }
}

/// A value of each field that another operation would accept.
fn stray(field: &str) -> &'static str {
    match field {
        "by" => "by = \"th\"",
        "set" => "set = { th = \"0\" }",
        "for" => "for = \"th''\"",
        "about" => "about = { th = \"0\" }",
        "over" => "over = [[\"x\", \"0\", \"l\"]]",
        "order" => "order = 2",
        "cyclic" => "cyclic = { ph = \"p\" }",
        "constraints" => "constraints = { T = \"th\" }",
        "of" => "of = \"Lag\"",
        "start" => "start = { th = 0.1 }",
        other => panic!("no value of `{other}`: add one"),
    }
}

fn parse(text: &str) -> Result<Scene, String> {
    Scene::parse(text, Path::new("x.toml")).map_err(|e| e.to_string())
}

#[test]
fn each_operation_of_the_table_loads_in_a_well_formed_step() {
    assert_eq!(OperationId::ALL.len(), OPERATIONS.len());
    for (id, kind) in OperationId::ALL.iter().zip(OPERATIONS) {
        let scene = parse(&scene_with(well_formed(kind.name)))
            .unwrap_or_else(|e| panic!("`{}`: {e}", kind.name));
        let op: &Operation = &scene.steps.last().unwrap().op;
        assert_eq!(op.name(), kind.name);
        assert_eq!(op.id(), *id);
        assert!(
            std::ptr::eq(id.kind(), kind),
            "`{}` not at its id's place",
            kind.name
        );
    }
}

#[test]
fn each_field_of_another_operation_is_refused_with_the_tables_sentence() {
    let mut refused = 0;
    for kind in OPERATIONS {
        for field in OPERATION_FIELDS.map(|f| f.name) {
            if kind.fields.contains(&field) {
                continue;
            }
            let text = scene_with(&format!("{}\n{}", well_formed(kind.name), stray(field)));
            let e = parse(&text).expect_err(&format!("`{field}` on `{}` loads", kind.name));
            let sentence = stray_field_message(field).unwrap();
            assert!(
                e.contains(&sentence),
                "`{field}` on `{}`: {e}\nwanted: {sentence}",
                kind.name
            );
            refused += 1;
        }
    }
    // 14 operations × 10 fields, less the 14 that their own operations take (`start` by four,
    // `about` by two, the others by one).
    assert_eq!(refused, 14 * 10 - 14);
}

#[test]
fn a_step_of_no_operation_or_two_lists_the_table() {
    let none = parse(&scene_with("why = \"nothing\"")).unwrap_err();
    let names: Vec<&str> = OPERATIONS.iter().map(|k| k.name).collect();
    assert!(none.contains(&names.join(", ")), "{none}");
    assert!(none.contains("this one gives none"), "{none}");
    let two = parse(&scene_with("be = \"Lag\"\nenergy = \"Lag\"")).unwrap_err();
    assert!(two.contains("this one gives be and energy"), "{two}");
}
