//! `check --bless` records each author's step's results: a blessed scene of steps alone fails
//! `check` at the step's line when its physics changes, and passes when only its words do.

use super::{mechbook, scratch, stdout};

/// A pendulum of steps alone (no body, so no catalogue quantity to record): its Lagrangian, its
/// equation of motion, the linear equation and its frequency.
const PENDULUM: &str = r#"id = "steps-pendulum"
title = "A simple pendulum, step by step"
notes = { lecture = "Oscillations", section = "1", equations = ["1"] }

[symbols]
m = { meaning = "mass of the bob", unit = "kg" }
l = { meaning = "length of the string", unit = "m" }
g = { meaning = "gravitational acceleration", unit = "m/s^2" }
k = { meaning = "stiffness of a spring", unit = "N/m" }

[coordinates]
phi = { meaning = "angle from the downward vertical", unit = "rad" }

[[step]]
name = "Lag"
be = "m*l^2*phi'^2/2 + m*g*l*cos(phi)"
why = "$T - V$"

[[step]]
name = "eom"
lagrange = "Lag"
why = "the Euler-Lagrange equation"

[[step]]
name = "small"
linearise = "eom"
about = { phi = "0" }
why = "small angles"

[[step]]
name = "Omega"
frequency = "small"
why = "the frequency of the linear equation"

[numeric]
values = { m = 1.0, l = 2.0, g = 9.81, k = 3.0 }
"#;

/// The line of the `[[step]]` that names `step`, where `check` reports it.
fn step_line(text: &str, step: &str) -> usize {
    text.lines()
        .position(|l| l == format!("name = \"{step}\""))
        .expect("the step is in the scene")
}

#[test]
fn a_blessed_scene_of_steps_fails_at_its_line_when_its_physics_changes() {
    let dir = scratch("step-records");
    let path = dir.join("pendulum.toml");
    let at = path.to_str().unwrap();
    std::fs::write(&path, PENDULUM).unwrap();

    // Nothing recorded yet: each step waits for review, at its own line.
    let out = mechbook(&["check", at]);
    assert_eq!(out.status.code(), Some(1), "{}", stdout(&out));
    let text = stdout(&out);
    for step in ["Lag", "eom", "small", "Omega"] {
        let line = step_line(PENDULUM, step);
        assert!(
            text.contains(&format!(
                "pendulum.toml:{line}: step `{step}` not yet recorded"
            )),
            "{step}: {text}"
        );
    }

    let blessed = mechbook(&["check", "--bless", at]);
    assert_eq!(blessed.status.code(), Some(0), "{}", stdout(&blessed));
    let recorded = std::fs::read_to_string(&path).unwrap();
    assert!(recorded.starts_with(PENDULUM), "the author's text is kept");
    assert!(recorded.contains("\n[expect]\n"), "{recorded}");
    assert!(recorded.contains("Omega = "), "{recorded}");
    let out = mechbook(&["check", at]);
    assert_eq!(out.status.code(), Some(0), "{}", stdout(&out));
    assert!(stdout(&out).contains("all as recorded"), "{}", stdout(&out));

    // Words alone: a reason and a title.
    let reworded = recorded
        .replace(
            "why = \"$T - V$\"",
            "why = \"the kinetic less the potential energy\"",
        )
        .replace("step by step", "derived in four steps");
    std::fs::write(&path, &reworded).unwrap();
    let out = mechbook(&["check", at]);
    assert_eq!(out.status.code(), Some(0), "{}", stdout(&out));

    // A spring term: every step from the Lagrangian on changes, each at its own line.
    let sprung = recorded.replace("m*g*l*cos(phi)\"", "m*g*l*cos(phi) - k*l^2*phi^2/2\"");
    std::fs::write(&path, &sprung).unwrap();
    let out = mechbook(&["check", at]);
    assert_eq!(out.status.code(), Some(1), "{}", stdout(&out));
    let text = stdout(&out);
    for step in ["Lag", "eom", "small", "Omega"] {
        let line = step_line(&sprung, step);
        assert!(
            text.contains(&format!(
                "pendulum.toml:{line}: step `{step}` changed since it was recorded"
            )),
            "{step}: {text}"
        );
    }

    // Doubled gravity: the same four lines.
    let heavier = recorded.replace("m*g*l*cos(phi)\"", "2*m*g*l*cos(phi)\"");
    std::fs::write(&path, &heavier).unwrap();
    let out = mechbook(&["check", at]);
    assert_eq!(out.status.code(), Some(1), "{}", stdout(&out));
    assert!(
        stdout(&out).contains(&format!(
            "pendulum.toml:{}: step `Omega` changed since it was recorded",
            step_line(&heavier, "Omega")
        )) && stdout(&out).contains("step `Lag` changed"),
        "{}",
        stdout(&out)
    );

    // A record changed by hand names the result that differs.
    let tampered = recorded.replacen("Omega = \"", "Omega = \"2*", 1);
    std::fs::write(&path, &tampered).unwrap();
    let out = mechbook(&["check", at]);
    assert_eq!(out.status.code(), Some(1), "{}", stdout(&out));
    assert!(
        stdout(&out).contains(&format!(
            "pendulum.toml:{}: step `Omega` changed",
            step_line(&tampered, "Omega")
        )) && !stdout(&out).contains("step `Lag` changed"),
        "{}",
        stdout(&out)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A step renamed after its record: `check` names the new step as not yet recorded and the old
/// record as naming no step; one `--bless` settles both, and `check` passes.
#[test]
fn a_renamed_step_is_recorded_again_in_one_bless() {
    let dir = scratch("step-renamed");
    std::fs::create_dir(dir.join("scenes")).unwrap();
    let path = dir.join("scenes").join("pendulum.toml");
    let at = path.to_str().unwrap();
    std::fs::write(&path, PENDULUM).unwrap();
    let blessed = mechbook(&["check", "--bless", at]);
    assert_eq!(blessed.status.code(), Some(0), "{}", stdout(&blessed));
    let renamed = std::fs::read_to_string(&path)
        .unwrap()
        .replace("name = \"small\"", "name = \"linear\"")
        .replace("frequency = \"small\"", "frequency = \"linear\"");
    std::fs::write(&path, &renamed).unwrap();
    let out = mechbook(&["check", at]);
    assert_eq!(out.status.code(), Some(1), "{}", stdout(&out));
    let text = stdout(&out);
    let record = renamed
        .lines()
        .position(|l| l.starts_with("small = "))
        .unwrap()
        + 1;
    assert!(
        text.contains(&format!(
            "pendulum.toml:{}: step `linear` not yet recorded",
            step_line(&renamed, "linear")
        )) && text.contains(&format!(
            "pendulum.toml:{record}: [expect] records `small`, which names no step"
        )),
        "{text}"
    );
    // A build does not fail on a new step, only `check` does.
    let site = dir.join("site");
    let built = mechbook(&["build", at, "--out", site.to_str().unwrap()]);
    assert!(
        super::stderr(&built).contains("1 step not yet recorded"),
        "{}",
        super::stderr(&built)
    );
    let blessed = mechbook(&["check", "--bless", at]);
    assert_eq!(blessed.status.code(), Some(0), "{}", stdout(&blessed));
    let after = std::fs::read_to_string(&path).unwrap();
    assert!(
        !after.contains("\nsmall = ") && after.contains("\nlinear = "),
        "{after}"
    );
    let out = mechbook(&["check", at]);
    assert_eq!(out.status.code(), Some(0), "{}", stdout(&out));
    std::fs::remove_dir_all(&dir).unwrap();
}
