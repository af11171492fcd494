//! The motion plot of the physical pendulum: the linear swing against its closed form
//! φ0 cos(Ωt), the full swing slower than the linear one, and the plot's fields checked where
//! they are written.

use crate::pipeline::run_scene;
use crate::scene::Scene;
use std::path::Path;

fn pendulum(plot: &str) -> Result<crate::pipeline::SceneReport, String> {
    let text = std::fs::read_to_string("tests/course/dynamics/01-physical-pendulum.toml").unwrap();
    let at = text.find("[[plot]]").unwrap();
    let end = text.find("[numeric]").unwrap();
    let text = format!("{}{plot}\n{}", &text[..at], &text[end..]);
    let s = Scene::parse(&text, Path::new("p.toml")).map_err(|e| e.to_string())?;
    run_scene(s, None).map_err(|e| e.to_string())
}

#[test]
fn the_linear_swing_is_its_closed_form_and_the_full_one_lags() {
    let r = pendulum(
        "[[plot]]\nkind = \"motion\"\nstep = \"eom\"\nlinear = \"small\"\nstart = { phi = 0.8 }\nt = 10.0",
    )
    .unwrap();
    let f = r
        .figures
        .iter()
        .find(|f| f.slug == "motion-eom")
        .expect("the motion plot");
    // A student reads the coordinates as symbols, not the scene's names or its step's.
    assert_eq!(f.title, "The motion of ϕ");
    assert!(
        f.desc.to_text().contains("from ϕ = 0.8, ϕ̇ = 0 over"),
        "{}",
        f.desc
    );
    assert!(
        !f.desc.to_text().contains("eom") && !f.desc.to_text().contains("phi"),
        "{}",
        f.desc
    );
    let names: Vec<&str> = f.series.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["ϕ", "ϕ (linear)"]);
    let (full, linear) = (&f.series[0].points, &f.series[1].points);
    // Ω² = M g (L/2) / (M L²/3) = 3g/(2L) at g = 9.81, L = 1.5.
    let omega = (3.0 * 9.81 / (2.0 * 1.5f64)).sqrt();
    let worst = linear
        .iter()
        .map(|(t, y)| (y - 0.8 * (omega * t).cos()).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-7, "linear against 0.8 cos(Ωt): {worst}");
    // The full pendulum swings more slowly (its period longer by about a²/16 = 4 %): it is
    // back at its start later than the linear one, near t = 2π/Ω ≈ 2.0.
    let back = |pts: &[(f64, f64)]| {
        pts.iter()
            .filter(|(t, _)| (1.0..3.0).contains(t))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap()
            .0
    };
    assert!(
        back(full) > back(linear) + 0.05,
        "{} {}",
        back(full),
        back(linear)
    );
    assert!(f.accuracy[0].estimated_error.unwrap() < 1e-6);
    assert!(f.desc.to_text().contains("at most") && f.desc.to_text().contains("right-hand sides"));
}

#[test]
fn a_motion_plots_fields_are_checked_where_they_are_written() {
    let e = pendulum("[[plot]]\nkind = \"motion\"\nstep = \"Lag\"\nt = 5.0").unwrap_err();
    assert!(
        e.contains("`Lag` is not a step of equations of motion"),
        "{e}"
    );
    let e = pendulum("[[plot]]\nkind = \"motion\"\nstep = \"eom\"\nlinear = \"eom\"\nt = 5.0")
        .unwrap_err();
    assert!(e.contains("`eom` is not a step of linear equations"), "{e}");
    let e = pendulum("[[plot]]\nkind = \"motion\"\nstep = \"eom\"\nstart = { psi = 1.0 }\nt = 5.0")
        .unwrap_err();
    assert!(e.contains("`psi` is not a coordinate or its rate"), "{e}");
    let e = pendulum("[[plot]]\nkind = \"motion\"\nstep = \"eom\"").unwrap_err();
    assert!(e.contains("needs `t`"), "{e}");
    let e = pendulum("[[plot]]\nkind = \"convergence\"\nstep = \"eom\"").unwrap_err();
    assert!(e.contains("belong to a motion plot"), "{e}");
}
