//! Twelve classic problems of our own (tests/classics: Morse's potential, a spring pendulum,
//! spring-coupled pendulums, a rolling cylinder, Atwood's machine with a massive pulley, a bead
//! on a spring along a turning rod, a double pendulum of unequal masses, a physical pendulum,
//! two masses and three springs, a cylinder rolling in a cylinder, a spherical pendulum's wobble
//! about its cone, a heavy top's slow and fast precession), each derived by SymPy from its
//! Lagrangian alone (tests/sympy/classics.py, into tests/fixtures/classics_sympy.json).

use super::{mechbook, scratch, stdout, toml_files};
use std::path::Path;

/// Every claim and `gives` decided and every step's check passing, for each seed 1 to 4: the
/// verdicts and records of tests/classics are the same whatever the random points.
#[test]
fn classic_problems_pass_for_every_seed() {
    for seed in 1..=4 {
        let dir = scratch(&format!("classics-{seed}"));
        for f in toml_files(Path::new("tests/classics")) {
            let text = std::fs::read_to_string(&f).unwrap();
            let seeded = text
                .lines()
                .map(|l| {
                    if l.starts_with("values = ") {
                        format!("{l}\nseed = {seed}")
                    } else {
                        l.to_string()
                    }
                })
                .collect::<Vec<_>>()
                .join("\n");
            assert!(
                seeded.contains(&format!("seed = {seed}")),
                "{}",
                f.display()
            );
            std::fs::write(dir.join(f.file_name().unwrap()), seeded).unwrap();
        }
        let out = mechbook(&["check", dir.to_str().unwrap()]);
        let text = stdout(&out);
        assert_eq!(out.status.code(), Some(0), "seed {seed}: {text}");
        assert!(
            text.contains("12 scenes, 19 claims: 19 agree, 0 disagree, 0 not checkable;")
                && text.contains("all as recorded"),
            "seed {seed}: {text}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// Each number SymPy derives equals mechbook's exact result at the scene's values to 1e-9.
#[test]
fn classic_problems_match_sympys_numbers() {
    let sympy: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string("tests/fixtures/classics_sympy.json").unwrap(),
    )
    .unwrap();
    let mut compared = 0;
    for f in toml_files(Path::new("tests/classics")) {
        let out = mechbook(&["derive", "--json", f.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(0), "{}", f.display());
        let json: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
        let id = json["id"].as_str().unwrap();
        let reference = sympy[id]
            .as_object()
            .unwrap_or_else(|| panic!("no SymPy numbers for {id}"));
        for (name, want) in reference {
            let want = want.as_f64().unwrap();
            let got = json["quantities"][name]["numeric"]
                .as_f64()
                .unwrap_or_else(|| panic!("{id}: no {name} in {}", json["quantities"]));
            assert!(
                (got - want).abs() <= 1e-9 * want.abs(),
                "{id}: {name} = {got}, SymPy {want}"
            );
            compared += 1;
        }
    }
    assert_eq!(compared, 20);
}
