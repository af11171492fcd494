//! The torque-free rigid body in its principal frame: Euler's equations (eqs 63–65 with N = 0),
//! the invariants, and the exact solution in Jacobi elliptic functions (REFERENCE.md, "Free
//! asymmetric top"; Landau & Lifshitz §37), for any ordering of the moments, with the symmetric
//! and spherical cases in closed form.

use super::elliptic::{amplitude_to_u, complete_k, jacobi};
use crate::model::moments::{Moments, units};
use nalgebra::Vector3;

/// ω̇ for N = 0: I1 ω̇1 = (I2 − I3) ω2 ω3 and cyclically (eqs 63–65).
pub fn euler_rhs(i: &Moments, w: &Vector3<f64>) -> Vector3<f64> {
    let [a, b, c] = i.0;
    Vector3::new(
        (b - c) / a * w.y * w.z,
        (c - a) / b * w.z * w.x,
        (a - b) / c * w.x * w.y,
    )
}

/// 2T = Σ I ω² and |L| = √(Σ I² ω²).
pub fn invariants(i: &Moments, w: &Vector3<f64>) -> (f64, f64) {
    let l = Vector3::new(i.0[0] * w.x, i.0[1] * w.y, i.0[2] * w.z);
    (
        i.0[0] * w.x * w.x + i.0[1] * w.y * w.y + i.0[2] * w.z * w.z,
        l.norm(),
    )
}

#[derive(Debug, Clone)]
enum Motion {
    /// ω constant: a sphere, or a spin about a principal axis.
    Steady(Vector3<f64>),
    /// Two equal moments: the pair (p, q) of components turns at rate `rate` (cyclic labels).
    Symmetric {
        p: usize,
        q: usize,
        w0: Vector3<f64>,
        rate: f64,
    },
    Elliptic(Elliptic),
}

/// The asymmetric case in sorted labels I1 < I2 < I3 (`order` maps them to the user's axes).
#[derive(Debug, Clone)]
struct Elliptic {
    order: [usize; 3],
    /// −1 when `order` is an odd permutation: then the middle component is mirrored.
    mirror: f64,
    /// Case A (d > 0, around axis 3) or B (d < 0, around axis 1).
    around_3: bool,
    amp: [f64; 3],
    /// Sign factors of the (cn or dn) components, and of cn on the separatrix.
    s: f64,
    s_cn: f64,
    lambda: f64,
    u0: f64,
    m: f64,
    mc: f64,
    k: f64,
}

/// The exact solution ω(t) of the free body from ω(0).
#[derive(Debug, Clone)]
pub struct ExactSolution {
    /// The motion in units where the largest moment and |ω(0)| are near 1 (see `units`).
    motion: Motion,
    /// ω in those units is ω / `rate`, and t is t · `rate`.
    rate: f64,
}

impl ExactSolution {
    pub fn new(i: &Moments, w0: Vector3<f64>) -> ExactSolution {
        let (i, w0, rate) = units(i, &w0);
        ExactSolution {
            motion: Motion::new(&i, w0),
            rate,
        }
    }

    /// The period of ω(t), when it is periodic and not steady.
    pub fn period(&self) -> Option<f64> {
        self.motion.period().map(|p| p / self.rate)
    }

    /// m = k² of the asymmetric case (None for the symmetric and steady cases) and 1 − m.
    pub fn parameter(&self) -> Option<(f64, f64)> {
        match &self.motion {
            Motion::Elliptic(e) => Some((e.m, e.mc)),
            _ => None,
        }
    }

    pub fn omega(&self, t: f64) -> Vector3<f64> {
        self.motion.omega(t * self.rate) * self.rate
    }
}

impl Motion {
    fn new(i: &Moments, w0: Vector3<f64>) -> Motion {
        let v = i.0;
        let same = |a: f64, b: f64| a == b;

        if same(v[0], v[1]) && same(v[1], v[2]) {
            Motion::Steady(w0)
        } else if let Some(c) = (0..3).find(|&c| same(v[(c + 1) % 3], v[(c + 2) % 3])) {
            // Cyclic (p, q, c): ω̇p = −β ωc ωq, ω̇q = β ωc ωp with β = (Ic − Ip)/Ip (eqs 66–69).
            let (p, q) = ((c + 1) % 3, (c + 2) % 3);
            Motion::Symmetric {
                p,
                q,
                w0,
                rate: (v[c] - v[p]) / v[p] * w0[c],
            }
        } else {
            Motion::Elliptic(Elliptic::new(i, w0)).into_steady_if_trivial(w0)
        }
    }

    fn period(&self) -> Option<f64> {
        match self {
            Motion::Steady(_) => None,
            Motion::Symmetric { rate, .. } => {
                (*rate != 0.0).then(|| 2.0 * std::f64::consts::PI / rate.abs())
            }
            Motion::Elliptic(e) => e.k.is_finite().then(|| 4.0 * e.k / e.lambda),
        }
    }

    fn omega(&self, t: f64) -> Vector3<f64> {
        match self {
            Motion::Steady(w) => *w,
            Motion::Symmetric { p, q, w0, rate } => {
                let (s, c) = (rate * t).sin_cos();
                let mut w = *w0;
                w[*p] = w0[*p] * c - w0[*q] * s;
                w[*q] = w0[*p] * s + w0[*q] * c;
                w
            }
            Motion::Elliptic(e) => e.omega(t),
        }
    }
}

impl Motion {
    /// A spin about axis 1 or 3 of the sorted frame has zero amplitudes: keep it exactly steady.
    fn into_steady_if_trivial(self, w0: Vector3<f64>) -> Motion {
        match &self {
            Motion::Elliptic(e) if e.amp.iter().filter(|a| **a == 0.0).count() >= 2 => {
                Motion::Steady(w0)
            }
            Motion::Elliptic(e) if e.lambda == 0.0 || !e.lambda.is_finite() => Motion::Steady(w0),
            _ => self,
        }
    }
}

impl Elliptic {
    fn new(i: &Moments, w0: Vector3<f64>) -> Elliptic {
        let mut order = [0usize, 1, 2];
        order.sort_by(|a, b| i.0[*a].total_cmp(&i.0[*b]));
        // An odd relabelling reverses Euler's equations; mirroring ω2 undoes that.
        let odd = matches!(order, [0, 2, 1] | [1, 0, 2] | [2, 1, 0]);
        let mirror = if odd { -1.0 } else { 1.0 };
        let [i1, i2, i3] = order.map(|k| i.0[k]);
        let [w1, w2, w3] = [w0[order[0]], mirror * w0[order[1]], w0[order[2]]];
        // Gaps without cancellation (REFERENCE.md).
        let g3 = i1 * (i3 - i1) * w1 * w1 + i2 * (i3 - i2) * w2 * w2;
        let g1 = i2 * (i2 - i1) * w2 * w2 + i3 * (i3 - i1) * w3 * w3;
        let d = i3 * (i3 - i2) * w3 * w3 - i1 * (i2 - i1) * w1 * w1;
        let around_3 = d > 0.0;
        let (amp, lambda, m, mc, s);
        if around_3 {
            amp = [
                (g3 / (i1 * (i3 - i1))).sqrt(),
                (g3 / (i2 * (i3 - i2))).sqrt(),
                (g1 / (i3 * (i3 - i1))).sqrt(),
            ];
            lambda = ((i3 - i2) * g1 / (i1 * i2 * i3)).sqrt();
            m = (i2 - i1) * g3 / ((i3 - i2) * g1);
            mc = (i3 - i1) * d / ((i3 - i2) * g1);
            s = if w3 < 0.0 { -1.0 } else { 1.0 };
        } else {
            amp = [
                (g3 / (i1 * (i3 - i1))).sqrt(),
                (g1 / (i2 * (i2 - i1))).sqrt(),
                (g1 / (i3 * (i3 - i1))).sqrt(),
            ];
            lambda = ((i2 - i1) * g3 / (i1 * i2 * i3)).sqrt();
            m = (i3 - i2) * g1 / ((i2 - i1) * g3);
            mc = -(i3 - i1) * d / ((i2 - i1) * g3);
            s = if w1 < 0.0 { -1.0 } else { 1.0 };
        }
        let (m, mc) = (m.clamp(0.0, 1.0), mc.clamp(0.0, 1.0));
        let k = complete_k(mc);
        // sn u0 and cn u0 from ω(0); the cn component is ω1 (case A) or ω3 (case B).
        let sn0 = if amp[1] > 0.0 { w2 / amp[1] } else { 0.0 };
        let cn_comp = if around_3 { (w1, amp[0]) } else { (w3, amp[2]) };
        let mut cn0 = if cn_comp.1 > 0.0 {
            s * cn_comp.0 / cn_comp.1
        } else {
            1.0
        };
        // On the separatrix cn = sech > 0, so the branch's sign is carried separately.
        let s_cn = if mc == 0.0 && cn0 < 0.0 { -1.0 } else { 1.0 };
        cn0 *= s_cn;
        let u0 = amplitude_to_u(sn0, cn0, m, mc, k);
        Elliptic {
            order,
            mirror,
            around_3,
            amp,
            s,
            s_cn,
            lambda,
            u0,
            m,
            mc,
            k,
        }
    }

    fn omega(&self, t: f64) -> Vector3<f64> {
        let (sn, cn, dn) = jacobi(self.lambda * t + self.u0, self.m, self.mc, self.k);
        let cn = self.s_cn * cn;
        let sorted = if self.around_3 {
            [
                self.s * self.amp[0] * cn,
                self.amp[1] * sn,
                self.s * self.amp[2] * dn,
            ]
        } else {
            [
                self.s * self.amp[0] * dn,
                self.amp[1] * sn,
                self.s * self.amp[2] * cn,
            ]
        };
        let mut w = Vector3::zeros();
        w[self.order[0]] = sorted[0];
        w[self.order[1]] = self.mirror * sorted[1];
        w[self.order[2]] = sorted[2];
        w
    }
}

/// The six orderings of three axes, for tests.
#[cfg(test)]
use crate::model::moments::ORDERINGS as PERMUTATIONS;

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
        (a - b).norm() / b.norm()
    }

    /// REFERENCE.md's check value: I = (1, 2, 3), ω(0) = (1, 0.1, 0.5).
    #[test]
    fn exact_solution_matches_the_reference_check_value() {
        let i = Moments::new([1.0, 2.0, 3.0]).unwrap();
        let sol = ExactSolution::new(&i, Vector3::new(1.0, 0.1, 0.5));
        let (m, mc) = sol.parameter().unwrap();
        assert!((m - 76.0 / 101.0).abs() < 1e-15 && (mc - 25.0 / 101.0).abs() < 1e-15);
        let period = sol.period().unwrap();
        assert!(
            (period - 14.897_368_369_859_113).abs() < 1e-13 * period,
            "{period}"
        );
        let want = Vector3::new(
            0.508_145_071_027_923_3,
            -0.867_057_429_926_084_4,
            -0.052_317_661_804_191_33,
        );
        let got = sol.omega(100.0);
        assert!(
            rel(&got, &want) < 1e-13,
            "{got} vs {want}: {}",
            rel(&got, &want)
        );
    }

    /// Every ordering of the same body gives the same motion, relabelled. An odd relabelling
    /// makes the frame left-handed, where the same body runs the motion backwards in time.
    #[test]
    fn any_ordering_of_the_moments_gives_the_same_motion() {
        let base = [1.0, 2.0, 3.0];
        let w = [1.0, 0.1, 0.5];
        let reference = ExactSolution::new(&Moments::new(base).unwrap(), Vector3::from(w));
        for perm in PERMUTATIONS {
            let i = Moments::new(perm.map(|k| base[k])).unwrap();
            let sol = ExactSolution::new(&i, Vector3::from(perm.map(|k| w[k])));
            let odd = matches!(perm, [0, 2, 1] | [1, 0, 2] | [2, 1, 0]);
            for t in [0.0, 3.3, 57.0] {
                let want = reference.omega(if odd { -t } else { t });
                let got = sol.omega(t);
                let back = Vector3::from(std::array::from_fn(|j| {
                    got[perm.iter().position(|&p| p == j).unwrap()]
                }));
                assert!(
                    rel(&back, &want) < 1e-13,
                    "{perm:?} t {t}: {back} vs {want}"
                );
            }
        }
    }

    /// The solution satisfies Euler's equations (a difference quotient) and keeps T and |L|.
    #[test]
    fn exact_solution_satisfies_euler_and_keeps_the_invariants() {
        for (i, w) in [
            ([1.0, 2.0, 3.0], [0.2, 0.1, 1.0]),  // case A
            ([3.0, 1.0, 2.0], [0.3, -1.0, 0.2]), // case B, cyclic order
            ([1.0, 3.0, 2.0], [1.0, 0.2, -0.4]), // odd order
            ([2.5, 1.5, 1.2], [0.1, 1.0, 0.05]), // near the intermediate axis, odd order
            ([2.0, 2.0, 3.0], [0.3, -0.4, 1.0]), // symmetric
            ([1.0, 2.0, 3.0], [0.0, 0.0, 2.0]),  // steady about axis 3
        ] {
            let i = Moments::new(i).unwrap();
            let w0 = Vector3::from(w);
            let sol = ExactSolution::new(&i, w0);
            let (t0, l0) = invariants(&i, &w0);
            for t in [0.5, 7.0, 31.0] {
                let h = 1e-5;
                let d = (sol.omega(t + h) - sol.omega(t - h)) / (2.0 * h);
                let f = euler_rhs(&i, &sol.omega(t));
                assert!(
                    (d - f).norm() < 1e-8 * (1.0 + f.norm()),
                    "{i:?} t {t}: {d} vs {f}"
                );
                let (tt, ll) = invariants(&i, &sol.omega(t));
                assert!((tt - t0).abs() < 1e-14 * t0 && (ll - l0).abs() < 1e-14 * l0);
            }
        }
    }
}

#[cfg(test)]
mod separatrix_tests {
    use super::*;
    use crate::numeric::integrators::{Method, Resolution, integrate};

    /// ω(0) on the circle of 1 − m = `mc` around axis 1 of I = (1, 2, 3): choose ω2 = 1, ω3 = 0.3
    /// and solve for ω1 so that 1 − m = −(I3−I1) d / ((I2−I1) g3) equals mc.
    fn near_separatrix(mc: f64) -> (Moments, Vector3<f64>) {
        let (i1, i2, i3) = (1.0, 2.0, 3.0);
        let (w2, w3) = (1.0, 0.3);
        // d = I3(I3−I2)w3² − I1(I2−I1)w1² and g3 = I1(I3−I1)w1² + I2(I3−I2)w2²; solve for w1².
        // mc·(I2−I1)·g3 = −(I3−I1)·d is linear in x = w1².
        let a = i3 * (i3 - i2) * w3 * w3;
        let b = i2 * (i3 - i2) * w2 * w2;
        let x = ((i3 - i1) * a + mc * (i2 - i1) * b)
            / ((i3 - i1) * i1 * (i2 - i1) - mc * (i2 - i1) * i1 * (i3 - i1));
        (
            Moments::new([i1, i2, i3]).unwrap(),
            Vector3::new(x.sqrt(), w2, w3),
        )
    }

    /// Close to the separatrix, 1 − m from 1e-6 to 1e-14, the exact solution returns to ω(0)
    /// after each of 4 periods to 1e-10, satisfies Euler's equations and keeps T and |L| along the way, and at 1 − m = 1e-6
    /// agrees with Dormand–Prince at a tight tolerance. (At 1 − m = 1e-12 a time-stepper cannot
    /// serve as the reference: its energy error would have to stay far below 1 − m.)
    #[test]
    fn exact_solution_stays_right_next_to_the_separatrix() {
        for mc in [1e-6, 1e-8, 1e-10, 1e-12, 1e-14] {
            let (i, w0) = near_separatrix(mc);
            let sol = ExactSolution::new(&i, w0);
            let (_, got_mc) = sol.parameter().unwrap();
            // Forming d from ω(0) rounds 1 − m by ~1e-16 absolutely: at 1e-14 that is 1e-2 of it.
            assert!((got_mc - mc).abs() < 1e-3 * mc + 1e-16, "1 − m = {got_mc}");
            let period = sol.period().unwrap();
            // Near the saddle a perturbation grows by about 1/√(1 − m) in each passage, so the
            // round-off of one period scales so: 1e-10 at 1 − m = 1e-12, 1e-9 at 1e-14.
            let bound = 1e-10 * (1e-12 / mc).sqrt().max(1.0);
            for k in 1..=4 {
                let back = sol.omega(k as f64 * period);
                assert!(
                    (back - w0).norm() < bound * w0.norm(),
                    "mc {mc}: after {k} periods {back} vs {w0}"
                );
            }
            let (t0, l0) = invariants(&i, &w0);
            for k in 1..=40 {
                let t = k as f64 * period / 10.0 + 0.37;
                let w = sol.omega(t);
                let (tt, ll) = invariants(&i, &w);
                assert!((tt / t0 - 1.0).abs() < 1e-13 && (ll / l0 - 1.0).abs() < 1e-13);
                let h = 1e-5;
                let d = (sol.omega(t + h) - sol.omega(t - h)) / (2.0 * h);
                let f = euler_rhs(&i, &w);
                assert!(
                    (d - f).norm() < 1e-8 * w0.norm(),
                    "mc {mc} t {t}: {d} vs {f}"
                );
            }
            if mc >= 1e-6 {
                let run = integrate(
                    &i,
                    w0,
                    4.0 * period,
                    Method::Dopri,
                    Resolution::Tolerance(1e-13),
                    0,
                )
                .unwrap();
                let err = (run.omega - sol.omega(4.0 * period)).norm() / w0.norm();
                assert!(err < 1e-7, "mc {mc}: dopri vs exact {err}");
            }
        }
    }
}

#[cfg(test)]
mod stability_tests {
    use super::*;

    /// Eqs (72)–(73) and the three cases after them: for every ordering of the moments, a spin
    /// about the largest or smallest axis perturbed by 1e-6 stays within a small multiple of it,
    /// and a spin about the middle axis grows to order one (it flips). Checked on the exact
    /// solution, against Ω² = ω_k² (I_k − I_a)(I_k − I_b)/(I_a I_b) of the linearization.
    #[test]
    fn only_the_middle_axis_is_unstable_for_every_ordering() {
        let base = [1.0, 2.0, 3.0];
        for perm in PERMUTATIONS {
            let i = Moments::new(perm.map(|k| base[k])).unwrap();
            for axis in 0..3 {
                let (p, q) = ((axis + 1) % 3, (axis + 2) % 3);
                let omega_sq = (i.0[axis] - i.0[p]) * (i.0[axis] - i.0[q]) / (i.0[p] * i.0[q]);
                let mut w0 = Vector3::repeat(1e-6);
                w0[axis] = 1.0;
                let sol = ExactSolution::new(&i, w0);
                let worst = (0..2000)
                    .map(|k| {
                        let w = sol.omega(k as f64 * 0.05);
                        (w - Vector3::ith(axis, w[axis])).norm()
                    })
                    .fold(0.0, f64::max);
                let middle = i.0[axis] != i.0.iter().cloned().fold(f64::MIN, f64::max)
                    && i.0[axis] != i.0.iter().cloned().fold(f64::MAX, f64::min);
                assert_eq!(omega_sq < 0.0, middle, "{:?} axis {axis}", i.0);
                if middle {
                    assert!(worst > 0.1, "{:?} axis {axis}: stayed within {worst}", i.0);
                } else {
                    assert!(worst < 1e-5, "{:?} axis {axis}: wandered to {worst}", i.0);
                }
            }
        }
    }
}
