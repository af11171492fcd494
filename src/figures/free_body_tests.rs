use super::free_body::figure;
use crate::model::fidelity::Fidelity;
use crate::scene::FreeBodyPlot;

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
        assert!(f.desc.contains(relation), "{i:?}: {}", f.desc);
    }
    assert!(
        figure(
            FreeBodyPlot::Cones,
            [1.0, 2.0, 2.5],
            [1.0, 0.0, 0.0],
            1.0,
            &Fidelity::STANDARD
        )
        .is_err()
    );
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
    assert!(
        figure(
            FreeBodyPlot::AxisSpins,
            [1.0, 2.0, 3.0],
            [1.0, 1.0, 0.0],
            1.0,
            &Fidelity::STANDARD
        )
        .is_err()
    );
}
