//! `check` and `derive` on the real lectures: the table, the JSON, the plan, and the regression
//! behaviour (a changed verdict or result fails).

use super::{lecture, mechbook, scratch, stderr, stdout};

#[test]
fn check_passes_on_every_lecture_scene_and_prints_the_table() {
    let out = mechbook(&["check"]);
    let text = stdout(&out);
    assert_eq!(out.status.code(), Some(0), "{text}{}", stderr(&out));
    let mut ids = Vec::new();
    for f in std::fs::read_dir("lectures/lecture-3-4").unwrap() {
        let s = std::fs::read_to_string(f.unwrap().path()).unwrap();
        let id = s
            .lines()
            .find_map(|l| l.strip_prefix("id = \""))
            .unwrap()
            .trim_end_matches('"')
            .to_string();
        ids.push(id);
    }
    assert!(ids.len() >= 10);
    for id in ids {
        assert!(
            text.lines()
                .any(|l| l.starts_with(&format!("{id} ")) && l.ends_with("ok")),
            "{id} missing or failing:\n{text}"
        );
    }
    assert!(text.contains("all as recorded"));
    assert!(text.contains("Where the notes disagree with the derivation"));
    // The shipped lectures write their mathematics between `$` signs.
    assert!(!stderr(&out).contains("warning"), "{}", stderr(&out));
}

/// ASCII mathematics in a claim's statement loads and checks, with a warning at its place
/// that says how to write it.
#[test]
fn ascii_mathematics_in_prose_is_warned_of_at_its_line() {
    let out = check_modified("ascii-math", |s| {
        s.replacen(
            r#"statement = "$I_{xx} = \\frac{2}{3} \\rho a^5 = \\frac{2}{3} m a^2$.""#,
            "statement = \"I_xx = (2/3) rho a^5 = (2/3) m a^2.\"",
            1,
        )
    });
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let err = stderr(&out);
    let warning = err
        .lines()
        .find(|l| l.starts_with("mechbook: warning: "))
        .unwrap_or_else(|| panic!("no warning: {err}"));
    assert!(
        warning.contains("scene.toml:43:14: field `claim[2].statement`: `I_xx` is mathematics"),
        "{warning}"
    );
    assert!(warning.contains("`$I_{xx}$`"), "{warning}");
    assert_eq!(err.matches("warning").count(), 1, "one a field: {err}");
}

#[test]
fn check_json_has_the_documented_shape() {
    let out = mechbook(&["check", "--json", "lectures"]);
    assert_eq!(out.status.code(), Some(0));
    let v: serde_json::Value = serde_json::from_str(&stdout(&out)).expect("valid JSON");
    let scenes = v["scenes"].as_array().unwrap();
    assert!(scenes.len() >= 10);
    let mut disagreements = 0;
    for s in scenes {
        assert!(s["id"].is_string() && s["source"].as_str().unwrap().starts_with("lectures/"));
        assert!(s["quantities"].is_object());
        for c in s["claims"].as_array().unwrap() {
            for k in ["eq", "statement", "derived", "verdict"] {
                assert!(c[k].is_string(), "claim without {k}: {c}");
            }
            let verdict = c["verdict"].as_str().unwrap();
            assert!(["agrees", "disagrees", "not-checkable"].contains(&verdict));
            disagreements += (verdict == "disagrees") as usize;
        }
        for n in s["numeric_checks"].as_array().unwrap() {
            assert!(n["method"].is_string() && n["points"].is_u64());
            for k in ["error", "predicted_error", "seconds"] {
                assert!(n[k].is_number(), "{k} in {n}");
            }
        }
    }
    assert!(disagreements >= 10);
    let cube = scenes.iter().find(|s| s["id"] == "cube-corner").unwrap();
    let t = &cube["quantities"]["inertia_tensor"];
    assert!(t["exact"].as_str().unwrap().contains("m*a^2"));
    // At m = a = 1 the corner tensor's diagonal is 2/3, from the numbers alone.
    assert!((t["numeric"][0][0].as_f64().unwrap() - 2.0 / 3.0).abs() < 1e-15);
}

#[test]
fn derive_explain_shows_the_skipped_stages() {
    let out = mechbook(&[
        "derive",
        lecture("06-hoop.toml").to_str().unwrap(),
        "--explain",
    ]);
    assert_eq!(out.status.code(), Some(0));
    let text = stdout(&out);
    assert!(text.contains("ran      tensor"), "{text}");
    assert!(text.contains("skipped  parallel-axis"));
    assert!(text.contains("skipped  angular-momentum"));
    assert!(text.contains("Symbolic engine:"));
}

#[test]
fn derive_json_is_one_scene() {
    let out = mechbook(&[
        "derive",
        lecture("07-tilted-hoop.toml").to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0));
    let v: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(v["id"], "tilted-hoop");
    assert!(v["steps"].as_array().unwrap().len() > 5);
}

/// Writes a modified copy of a lecture scene and runs `check` on it.
fn check_modified(name: &str, edit: impl Fn(String) -> String) -> std::process::Output {
    let dir = scratch(name);
    let original = std::fs::read_to_string(lecture("05-cube-corner.toml")).unwrap();
    let changed = edit(original.clone());
    assert_ne!(changed, original, "the edit must change the scene");
    let path = dir.join("scene.toml");
    std::fs::write(&path, changed).unwrap();
    let out = mechbook(&["check", path.to_str().unwrap()]);
    std::fs::remove_dir_all(&dir).unwrap();
    out
}

#[test]
fn a_changed_verdict_fails_check() {
    let out = check_modified("verdict", |s| {
        s.replacen("expect = \"disagrees\"", "expect = \"agrees\"", 1)
    });
    assert_eq!(out.status.code(), Some(1));
    let text = stdout(&out);
    assert!(
        text.contains("claim (28): verdict disagrees but the scene records agrees"),
        "{text}"
    );
}

#[test]
fn a_changed_derivation_fails_check() {
    // The recorded tensor stays; the body changes, so the derived tensor no longer matches.
    let out = check_modified("result", |s| {
        s.replace(
            "size = [\"a\", \"a\", \"a\"]",
            "size = [\"a\", \"a\", \"2*a\"]",
        )
    });
    assert_eq!(out.status.code(), Some(1));
    let text = stdout(&out);
    assert!(text.contains("`inertia_tensor` changed"), "{text}");
}

/// Removes the fields that measure time, which legitimately vary between runs.
fn without_timings(v: &mut serde_json::Value) {
    match v {
        serde_json::Value::Object(map) => {
            map.retain(|k, _| k != "seconds" && k != "symbolic_seconds");
            map.values_mut().for_each(without_timings);
        }
        serde_json::Value::Array(items) => items.iter_mut().for_each(without_timings),
        _ => {}
    }
}

#[test]
fn the_same_input_gives_the_same_output() {
    // Once alone and once after other scenes: the engine's internal symbol order differs, the
    // printed results must not.
    let alone = mechbook(&[
        "derive",
        lecture("05-cube-corner.toml").to_str().unwrap(),
        "--json",
    ]);
    let all = mechbook(&["check", "--json", "lectures"]);
    let mut a: serde_json::Value = serde_json::from_str(&stdout(&alone)).unwrap();
    let mut b: serde_json::Value = serde_json::from_str(&stdout(&all)).unwrap();
    let mut b = b["scenes"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|s| s["id"] == "cube-corner")
        .unwrap()
        .take();
    without_timings(&mut a);
    without_timings(&mut b);
    assert_eq!(a, b);
    let again = mechbook(&["check", "--json", "lectures"]);
    let (mut x, mut y): (serde_json::Value, serde_json::Value) = (
        serde_json::from_str(&stdout(&all)).unwrap(),
        serde_json::from_str(&stdout(&again)).unwrap(),
    );
    without_timings(&mut x);
    without_timings(&mut y);
    assert_eq!(x, y);
}

#[test]
fn the_earth_scene_runs_only_its_plot_and_claims() {
    let r = super::mechbook(&["derive", "lectures/lecture-3-9/05-earth.toml", "--explain"]);
    assert_eq!(r.status.code(), Some(0), "{}", super::stderr(&r));
    let out = super::stdout(&r);
    let ran: Vec<&str> = out
        .lines()
        .filter_map(|l| l.trim_start().strip_prefix("ran "))
        .map(|l| l.split_whitespace().next().unwrap())
        .collect();
    assert_eq!(
        ran,
        ["earth-precession", "plots", "claims", "regression"],
        "{out}"
    );
    // Only its own exact arithmetic reaches the engine: no integrals, no other derivation.
    assert!(out.contains("skipped  tensor") && out.contains("skipped  symmetric-top"));
    // Its plot uses the exact solution: no ODE is integrated, and there is no body to integrate.
    assert!(
        out.contains(
            "Numeric work: 0 ODE integrations, 0 right-hand-side evaluations; 0 quadrature runs, 0 points"
        ),
        "{out}"
    );
}

/// The counters of `--explain` follow what a scene asks for: plots that integrate count their
/// integrations, a scene without plots or `numeric` counts none.
#[test]
fn numeric_work_counts_only_what_was_asked_for() {
    let work = |scene: &str| -> serde_json::Value {
        let r = super::mechbook(&["derive", scene, "--json"]);
        assert_eq!(r.status.code(), Some(0), "{}", super::stderr(&r));
        let v: serde_json::Value = serde_json::from_str(&super::stdout(&r)).unwrap();
        v["numeric_work"].clone()
    };
    let euler = work("lectures/lecture-3-9/01-euler-equations.toml");
    assert_eq!(euler["ode_integrations"], 0);
    assert_eq!(euler["quadrature_runs"], 0);
    // The asymmetric top's drift plot runs every integrator, its flip plot Dormand–Prince.
    let top = work("lectures/lecture-3-9/03-asymmetric-top.toml");
    assert!(top["ode_integrations"].as_u64().unwrap() >= 5, "{top}");
    assert!(top["rhs_evaluations"].as_u64().unwrap() > 1000, "{top}");
    assert_eq!(top["quadrature_runs"], 0);
    // The cube about its centre asks for `numeric`: quadrature, and no ODE.
    let cube = work("lectures/lecture-3-4/05b-cube-centre.toml");
    assert!(cube["quadrature_runs"].as_u64().unwrap() > 0, "{cube}");
    assert_eq!(cube["ode_integrations"], 0);
}

#[test]
fn the_sympy_comparison_set_derives() {
    // tests/sympy/compare.sh times these scenes against SymPy; keep them deriving.
    let r = super::mechbook(&["check", "tests/sympy/scenes"]);
    assert_eq!(r.status.code(), Some(0), "{}", super::stderr(&r));
    let out = super::stdout(&r);
    assert!(out.contains("4 scenes, 0 claims"), "{out}");
    for id in [
        "sympy-cube-corner",
        "sympy-hoop",
        "sympy-tilted-hoop",
        "sympy-symmetric-top",
    ] {
        assert!(out.contains(id), "{out}");
    }
}

/// Fidelity buys accuracy with cost: from draft to reference each scene does more work, the
/// finest lattice gets closer to the exact tensor, the integrations behind the plots get closer
/// to the exact solution, and every plotted result reports an error and a cost.
#[test]
fn fidelity_trades_cost_for_error() {
    let derive = |scene: &str, fidelity: &str| -> serde_json::Value {
        let r = super::mechbook(&["derive", scene, "--json", "--fidelity", fidelity]);
        assert_eq!(r.status.code(), Some(0), "{}", super::stderr(&r));
        serde_json::from_str(&super::stdout(&r)).unwrap()
    };
    let finest = |v: &serde_json::Value, method: &str| -> f64 {
        let runs = v["numeric_checks"].as_array().unwrap();
        let last = runs.iter().rev().find(|r| r["method"] == method).unwrap();
        last["error"].as_f64().unwrap()
    };
    let cube = "lectures/lecture-3-4/05b-cube-centre.toml";
    let [d, s, r] = ["draft", "standard", "reference"].map(|f| derive(cube, f));
    let points = |v: &serde_json::Value| v["numeric_work"]["quadrature_points"].as_u64().unwrap();
    assert!(points(&d) < points(&s) && points(&s) < points(&r));
    let lattice = [&d, &s, &r].map(|v| finest(v, "midpoint-lattice"));
    assert!(
        lattice[0] > lattice[1] && lattice[1] > lattice[2],
        "{lattice:?}"
    );
    for (v, name) in [(&d, "draft"), (&s, "standard"), (&r, "reference")] {
        assert_eq!(v["fidelity"]["name"], name);
        assert!(
            finest(v, "gauss-legendre") < 1e-14,
            "the exact rule is exact at every level"
        );
        let stops: Vec<&str> = v["numeric_checks"]
            .as_array()
            .unwrap()
            .iter()
            .map(|q| q["stop"].as_str().unwrap())
            .filter(|s| !s.is_empty())
            .collect();
        assert_eq!(stops.len(), 4, "one stop per method: {stops:?}");
        assert_eq!(stops[0], "target met", "Gauss–Legendre meets every target");
    }
    assert_eq!(r["fidelity"]["tolerance"], 1e-12);

    let top = "lectures/lecture-3-9/03-asymmetric-top.toml";
    let [d, r] = ["draft", "reference"].map(|f| derive(top, f));
    let dots = |v: &serde_json::Value| -> f64 {
        let fig = v["figures"].as_array().unwrap();
        let omega = fig.iter().find(|f| f["slug"] == "omega-vs-time").unwrap();
        omega["accuracy"][1]["true_error"].as_f64().unwrap()
    };
    assert!(dots(&d) > 100.0 * dots(&r), "{} {}", dots(&d), dots(&r));
    let rhs = |v: &serde_json::Value| v["numeric_work"]["rhs_evaluations"].as_u64().unwrap();
    assert!(rhs(&d) < rhs(&r));
    for v in [&d, &r] {
        for f in v["figures"].as_array().unwrap() {
            let acc = f["accuracy"].as_array().unwrap();
            assert!(!acc.is_empty(), "{} reports no error", f["slug"]);
            for a in acc {
                assert!(
                    a["true_error"].is_f64() || a["estimated_error"].is_f64(),
                    "{a}"
                );
                assert!(a["cost"].as_u64().unwrap() > 0, "{a}");
            }
        }
    }
}

/// A problem's variants are pinned: a new seed changes the students' sheets, and `check` fails
/// at the `variants` line saying how many differ; `--bless` records the new ones, after which
/// `check` passes. Without the record, `check` fails as for an unrecorded result.
#[test]
fn changed_variants_fail_check_until_blessed() {
    let dir = scratch("pinned-variants");
    let original = std::fs::read_to_string("lectures/lecture-3-4/10-problem-box.toml").unwrap();
    let line = original
        .lines()
        .position(|l| l.starts_with("variants = "))
        .expect("the lecture problem is pinned")
        + 1;
    let path = dir.join("scene.toml");
    let at = path.to_str().unwrap();
    std::fs::write(&path, original.replace("seed = 7", "seed = 8")).unwrap();
    let out = mechbook(&["check", at]);
    assert_eq!(out.status.code(), Some(1));
    let text = stdout(&out);
    assert!(
        text.contains(&format!(
            "scene.toml:{line}: the problem's variants changed since they were recorded: "
        )) && text.contains("of 12 students' sheets differ"),
        "{text}"
    );
    let blessed = mechbook(&["check", "--bless", at]);
    assert_eq!(blessed.status.code(), Some(0), "{}", stdout(&blessed));
    assert!(stdout(&blessed).contains("[expect] variants: pinned again"));
    let out = mechbook(&["check", at]);
    assert_eq!(out.status.code(), Some(0), "{}", stdout(&out));
    let unpinned: String = original
        .lines()
        .filter(|l| !l.starts_with("variants = "))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(&path, unpinned).unwrap();
    let out = mechbook(&["check", at]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stdout(&out).contains("the problem's 12 variants are not yet recorded"),
        "{}",
        stdout(&out)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Modes with no closed form are numbers in `derive --json`'s `quantities`, with no exact
/// text; an answer on them has none either. The five-link pendulum's are the textbook's (√λ of
/// its M⁻¹K, by nalgebra's Schur decomposition) to 1e-9.
#[test]
fn numeric_modes_are_numbers_in_the_json_and_never_an_exact_form() {
    let out = mechbook(&[
        "derive",
        "--json",
        "tests/course/problems/07-five-links.toml",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    let textbook = mechbook::verify::n_link::textbook_modes(5);
    for (k, w) in textbook.iter().enumerate() {
        let q = &v["quantities"][format!("Omega_{}", k + 1)];
        assert!(q["exact"].is_null() && q["numeric_only"] == true, "{q}");
        let x = q["numeric"][0].as_f64().unwrap();
        assert!(
            (x - w).abs() <= 1e-9 * w,
            "Omega_{}: {x} against {w}",
            k + 1
        );
    }
    for answer in v["variants"][0]["answers"].as_array().unwrap() {
        assert!(
            answer["exact"].is_null() && answer["numeric"][0].as_f64().is_some(),
            "{answer}"
        );
    }
}

/// A state of rest of several coordinates and the minors about it are lists in `derive
/// --json`'s `quantities`, with their numbers. The double pendulum's (m = l = 1, g = 9.81):
/// each string hangs down or stands up, and about each state the minors of the potential's
/// Hessian, diag(2mgl cos φ₁, mgl cos φ₂), computed here.
#[test]
fn states_of_rest_of_several_coordinates_and_their_minors_are_lists_in_the_json() {
    let out = mechbook(&[
        "derive",
        "--json",
        "tests/course/dynamics/03-double-pendulum.toml",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    let (m, l, g) = (1.0, 1.0, 9.81);
    let pi = std::f64::consts::PI;
    let states = [
        ("[0, 0]", 0.0, 0.0),
        ("[0, pi]", 0.0, pi),
        ("[pi, 0]", pi, 0.0),
        ("[pi, pi]", pi, pi),
    ];
    for (k, (text, p1, p2)) in states.into_iter().enumerate() {
        let rest = &v["quantities"][format!("rest_{}", k + 1)];
        assert_eq!(rest["exact"], text, "{rest}");
        let numbers: Vec<f64> = rest["numeric"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert_eq!(numbers, [p1, p2], "{rest}");
        let hessian = [2.0 * m * g * l * f64::cos(p1), m * g * l * f64::cos(p2)];
        let minors = [hessian[0], hessian[0] * hessian[1]];
        let upright = &v["quantities"][format!("upright_{}", k + 1)];
        let got = upright["numeric"].as_array().unwrap();
        assert_eq!(got.len(), 2, "{upright}");
        for (x, want) in got.iter().zip(minors) {
            let x = x.as_f64().unwrap();
            assert!(
                (x - want).abs() <= 1e-12 * want.abs(),
                "upright_{}: {x} against {want}",
                k + 1
            );
        }
    }
}

/// A claim that names a result its step did not give is not checkable, and says what the step
/// gives: it was "disagrees", with the name standing for itself.
#[test]
fn a_claim_on_a_result_no_step_gave_says_what_the_step_gives() {
    let dir = scratch("unbound-result");
    let cases = [
        (
            "tests/course/dynamics/19-block-on-wedge.toml",
            "quantity = \"acc_1\"",
            "quantity = \"acc_5\"",
            "`acc_5` is no result of step `acc`, which gives acc_1, acc_2",
        ),
        (
            "tests/course/dynamics/03-double-pendulum.toml",
            "quantity = \"Omega_1\"",
            "quantity = \"rest_2\"",
            "`rest_2` is no result of step `rest`, which gives none a claim can name",
        ),
    ];
    for (k, (scene, from, to, said)) in cases.into_iter().enumerate() {
        let text = std::fs::read_to_string(scene).unwrap();
        assert!(text.contains(from), "{scene}");
        let path = dir.join(format!("scene-{k}.toml"));
        std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
        let out = mechbook(&["check", path.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(1), "{}", stdout(&out));
        assert!(stdout(&out).contains(said), "{}", stdout(&out));
        assert!(
            !stdout(&out).contains("disagree with the derivation"),
            "{}",
            stdout(&out)
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
