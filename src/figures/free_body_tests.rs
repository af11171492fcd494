use super::free_body_figure as figure;
use crate::figures::FigureError;
use crate::model::fidelity::Fidelity;
use crate::scene::FreeBodyPlot;

/// Why a plot of these moments and initial rates is refused.
fn refusal(plot: FreeBodyPlot, i: [f64; 3], w: [f64; 3]) -> FigureError {
    figure(plot, i, w, 1.0, &Fidelity::STANDARD).unwrap_err()
}

/// The cone inequality worked out from tan θ_L = (I1/I3) tan α_b, measured on the integrated
/// attitude: oblate bodies always have α_b > α_s; prolate ones can have either.
#[test]
fn cone_angles_oblate_always_bigger_body_cone_prolate_either() {
    for (i, w, relation) in [
        ([2.0, 2.0, 3.0], [0.5, 0.0, 1.0], "α_b > α_s"),
        ([2.0, 2.0, 1.9], [0.5, 0.0, 1.0], "α_b > α_s"),
        ([2.0, 2.0, 0.8], [0.2, 0.0, 1.0], "α_b < α_s"),
    ] {
        let f = figure(FreeBodyPlot::Cones, i, w, 20.0, &Fidelity::STANDARD).unwrap();
        assert!(f.desc.to_text().contains(relation), "{i:?}: {}", f.desc);
    }
    let e = refusal(FreeBodyPlot::Cones, [1.0, 2.0, 2.5], [1.0, 0.0, 0.0]);
    assert!(matches!(e, FigureError::NotSymmetric), "{e:?}");
}

#[test]
fn only_the_intermediate_axis_departs() {
    let f = figure(
        FreeBodyPlot::AxisSpins,
        [1.0, 2.0, 3.0],
        [1.0, 0.01, 0.01],
        60.0,
        &Fidelity::STANDARD,
    )
    .unwrap();
    let top = |k: usize| {
        f.series[k]
            .points
            .iter()
            .map(|p| p.1)
            .fold(0.0f64, f64::max)
    };
    // A 0.01 wobble about a stable axis stays within a couple of degrees; the middle axis
    // reverses (flip time about 2K/λ ≈ 14 here).
    assert!(top(0) < 3.0 && top(2) < 3.0, "{} {}", top(0), top(2));
    assert!(top(1) > 170.0, "{}", top(1));
    let e = refusal(FreeBodyPlot::AxisSpins, [1.0, 2.0, 3.0], [1.0, 1.0, 0.0]);
    assert!(matches!(e, FigureError::NoLargestComponent), "{e:?}");
}

/// `inertia = "principal"` draws the scene's own body: a box a × 2a × 3a with its corner at the
/// origin, whose moments about its centre of mass are m/12 (5, 10, 13) a² by the table. The plot
/// matches the same plot given those numbers, and expressions of the symbols give them too.
#[test]
fn a_free_body_plot_takes_the_scenes_own_principal_moments() {
    use crate::pipeline::run_scene;
    use crate::scene::Scene;
    let scene = |inertia: &str| {
        let text = format!(
            "id = \"t\"\ntitle = \"t\"\nnotes = {{ lecture = \"x\" }}\n\
             symbols = {{ m = \"m\", a = \"a\" }}\n\
             [[body]]\nkind = \"box\"\nsize = [\"a\", \"2*a\", \"3*a\"]\nmass = \"m\"\n\
             [outputs]\nwant = []\n[numeric]\nvalues = {{ m = 1.5, a = 0.5 }}\n\
             [[plot]]\nkind = \"polhodes\"\ninertia = {inertia}\nomega = [0.2, 1.0, \"a/5\"]\nt = 5.0\n"
        );
        let scene = Scene::parse(&text, std::path::Path::new("t.toml")).unwrap();
        run_scene(scene, None).unwrap().figures.remove(0)
    };
    let own = scene("\"principal\"");
    let table = scene("[\"5*m*a^2/12\", \"10*m*a^2/12\", \"13*m*a^2/12\"]");
    let k = 1.5 * 0.25 / 12.0;
    let numbers = scene(&format!("[{}, {}, {}]", 5.0 * k, 10.0 * k, 13.0 * k));
    assert_eq!(table.desc, numbers.desc);
    // The numeric route to the moments (tensor about the corner, shifted, eigen-solved) rounds
    // differently from the table, so compare the curves, not the text.
    assert_eq!(own.series.len(), table.series.len());
    for (a, b) in own.series.iter().zip(&table.series) {
        for (p, q) in a.points.iter().zip(&b.points) {
            assert!(
                (p.0 - q.0).abs() < 1e-9 && (p.1 - q.1).abs() < 1e-9,
                "{p:?} vs {q:?}"
            );
        }
    }
}
