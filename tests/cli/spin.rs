//! `spin`: the JSON contract, agreement between methods, and clear errors for bad bodies.

use super::{mechbook, stderr, stdout};

fn spin_json(args: &[&str]) -> serde_json::Value {
    let mut all = vec![
        "spin",
        "--inertia",
        "1,2,3",
        "--omega",
        "1,0.1,0.5",
        "--json",
    ];
    all.extend_from_slice(args);
    let r = mechbook(&all);
    assert_eq!(r.status.code(), Some(0), "{}", stderr(&r));
    serde_json::from_str(&stdout(&r)).expect("one JSON object")
}

#[test]
fn spin_json_has_the_promised_fields_and_methods_agree() {
    let exact = spin_json(&["--t", "100"]);
    for key in [
        "energy_drift",
        "momentum_drift",
        "rhs_evaluations",
        "seconds",
    ] {
        assert!(exact.get(key).is_some(), "missing {key}");
    }
    let omega = |j: &serde_json::Value| -> Vec<f64> {
        j["omega"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    // REFERENCE.md's check value ω(100).
    let want = [
        0.508_145_071_027_923_3,
        -0.867_057_429_926_084_4,
        -0.052_317_661_804_191_33,
    ];
    let got = omega(&exact);
    assert_eq!(got.len(), 3);
    for k in 0..3 {
        assert!((got[k] - want[k]).abs() < 1e-13, "{got:?}");
    }
    let dopri = spin_json(&["--t", "100", "--method", "dopri", "--tol", "1e-11"]);
    let d = omega(&dopri);
    for k in 0..3 {
        assert!((d[k] - want[k]).abs() < 1e-8, "{d:?}");
    }
    assert!(dopri["rhs_evaluations"].as_u64().unwrap() > 1000);
    let split = spin_json(&["--t", "100", "--method", "splitting", "--step", "0.01"]);
    assert!(split["momentum_drift"].as_f64().unwrap() < 1e-14);
}

#[test]
fn spin_rejects_impossible_bodies_and_bad_numbers() {
    for (args, want) in [
        (
            vec!["--inertia", "1,1,3", "--omega", "1,0,0", "--t", "1"],
            "triangle inequality",
        ),
        (
            vec!["--inertia", "0,1,1", "--omega", "1,0,0", "--t", "1"],
            "must be positive",
        ),
        (
            vec!["--inertia", "-1,1,1", "--omega", "1,0,0", "--t", "1"],
            "must be positive",
        ),
        (
            vec!["--inertia", "1,2,NaN", "--omega", "1,0,0", "--t", "1"],
            "not a finite number",
        ),
        (
            vec!["--inertia", "1,2,3", "--omega", "1,inf,0", "--t", "1"],
            "not a finite number",
        ),
        (
            vec!["--inertia", "1,2,3", "--omega", "1,0", "--t", "1"],
            "3 comma-separated",
        ),
        (
            vec!["--inertia", "1,2,3", "--omega", "1,0,0", "--t", "-1"],
            "end time",
        ),
        (
            vec![
                "--inertia",
                "1,2,3",
                "--omega",
                "1,0,0",
                "--t",
                "1",
                "--method",
                "euler",
            ],
            "unknown method",
        ),
        (
            vec![
                "--inertia",
                "1,2,3",
                "--omega",
                "1,0,0",
                "--t",
                "1",
                "--method",
                "rk4",
                "--step",
                "0",
            ],
            "positive",
        ),
    ] {
        let mut all = vec!["spin"];
        all.extend(args.iter().copied());
        let r = mechbook(&all);
        assert_eq!(r.status.code(), Some(1), "{all:?}: {}", stderr(&r));
        assert!(stderr(&r).contains(want), "{all:?}: {}", stderr(&r));
        assert!(r.stdout.is_empty() || !stdout(&r).contains('{'));
    }
}

/// The hostile-input trial's spin requests: each is refused at once with what to change,
/// instead of running for years or printing NaN.
#[test]
fn unbounded_or_meaningless_requests_are_refused() {
    let cases: [(&str, &str, &str); 11] = [
        ("1,2,3", "1,0.1,0.5", "--t 1e300 --method rk4"),
        ("1,2,3", "1,0.1,0.5", "--t 1e300 --method dopri"),
        ("1,2,3", "1,0.1,0.5", "--t 1e300 --method splitting4"),
        ("1,2,3", "1,0.1,0.5", "--t 1e300 --method exact"),
        ("1,2,3", "1,0.1,0.5", "--t 10 --method rk4 --step 1e-300"),
        ("1,2,3", "1,0.1,0.5", "--t 10 --method dopri --tol 1e-300"),
        ("1,2,3", "1,0.1,0.5", "--t 1e9 --method rk4 --step 1e-6"),
        ("1,2,3", "5e-324,0,0", "--t 1 --method exact"),
        ("1,2,3", "1e308,1e308,1e308", "--t 1 --method rk4"),
        ("5e-324,1e-323,1.5e-323", "1,0.1,0.5", "--t 1 --method rk4"),
        ("1,2,3", "0,1,1e-300", "--t 1e6 --method exact"),
    ];
    let wants = [
        "needs 1.000e302 steps",
        "2^52",
        "needs",
        "2^52",
        "needs 1.000e301 steps",
        "below what double precision",
        "needs 1.000e15 steps",
        "below 2.2250738585072014e-308",
        "2^52",
        "below 2.2250738585072014e-308",
        "beyond double precision",
    ];
    for ((inertia, omega, rest), want) in cases.iter().zip(wants) {
        let mut args = vec!["spin", "--inertia", inertia, "--omega", omega];
        args.extend(rest.split(' '));
        let started = std::time::Instant::now();
        let r = mechbook(&args);
        assert_eq!(r.status.code(), Some(1), "{args:?}: {}", stderr(&r));
        assert!(stderr(&r).contains(want), "{args:?}: {}", stderr(&r));
        assert!(!stdout(&r).contains("NaN"), "{args:?}");
        // Refused before any integration: well under a second even on a loaded machine.
        assert!(started.elapsed().as_secs_f64() < 10.0, "{args:?} ran");
    }
}

/// A cap the request needs more than is refused with the count; within the cap it runs.
#[test]
fn max_steps_bounds_a_run() {
    let base = [
        "spin",
        "--inertia",
        "1,2,3",
        "--omega",
        "1,0.1,0.5",
        "--t",
        "10",
        "--method",
        "rk4",
        "--step",
        "0.01",
    ];
    let mut capped = base.to_vec();
    capped.extend(["--max-steps", "999"]);
    let r = mechbook(&capped);
    assert_eq!(r.status.code(), Some(1));
    assert!(
        stderr(&r).contains("needs 1.000e3 steps, more than the cap of 999"),
        "{}",
        stderr(&r)
    );
    let mut enough = base.to_vec();
    enough.extend(["--max-steps", "1000"]);
    assert_eq!(mechbook(&enough).status.code(), Some(0));
}
