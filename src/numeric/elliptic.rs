//! Jacobi elliptic functions and integrals for parameter m = k² (DLMF ch. 22), robust as m → 1.
//!
//! Every routine takes the complementary parameter mc = 1 − m as well as m, and never forms
//! 1 − m itself: near the separatrix 1 − m carries all the information (REFERENCE.md, "Near the
//! separatrix"). sn, cn come from the AGM started at √mc (descending Landen transformation,
//! DLMF 22.20(ii)) after reducing u modulo 2K; dn = √(mc + m cn²); F(φ|m) uses Carlson's R_F.

use std::f64::consts::PI;

/// Carlson's symmetric integral R_F(x, y, z) by duplication (DLMF 19.36.1), relative error ~ε.
pub fn carlson_rf(x: f64, y: f64, z: f64) -> f64 {
    let (mut x, mut y, mut z) = (x, y, z);
    for _ in 0..60 {
        let mean = (x + y + z) / 3.0;
        let (dx, dy, dz) = (1.0 - x / mean, 1.0 - y / mean, 1.0 - z / mean);
        if dx.abs().max(dy.abs()).max(dz.abs()) < 1e-4 {
            // DLMF 19.36.1 series to fifth order: the truncation error is below ε here.
            let e2 = dx * dy - dz * dz;
            let e3 = dx * dy * dz;
            return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0)
                / mean.sqrt();
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lam = sx * sy + sy * sz + sz * sx;
        x = (x + lam) / 4.0;
        y = (y + lam) / 4.0;
        z = (z + lam) / 4.0;
    }
    let mean = (x + y + z) / 3.0;
    1.0 / mean.sqrt()
}

/// The complete integral K(m) = π / (2 AGM(1, √mc)); infinite on the separatrix (mc = 0).
pub fn complete_k(mc: f64) -> f64 {
    if mc <= 0.0 {
        return f64::INFINITY;
    }
    let (mut a, mut b) = (1.0f64, mc.sqrt());
    for _ in 0..64 {
        if (a - b).abs() <= 1e-16 * a {
            break;
        }
        (a, b) = ((a + b) / 2.0, (a * b).sqrt());
    }
    PI / (2.0 * a)
}

/// The incomplete integral F(φ|m) for any real φ, with K supplied: F(φ + jπ) = F(φ) + 2jK.
pub fn incomplete_f(phi: f64, m: f64, mc: f64, k: f64) -> f64 {
    let j = (phi / PI).round();
    let r = phi - j * PI;
    let (s, c) = r.sin_cos();
    let f = s * carlson_rf(c * c, mc + m * c * c, 1.0);
    if j == 0.0 { f } else { f + 2.0 * j * k }
}

/// The u with sn u = `sn`, cn u = `cn` and |u| ≤ 2K (the inverse of the amplitude).
///
/// Near u = K, F(φ) has slope 1/dn = 1/√mc, so instead u = K − F(ψ) with tan ψ = cn/(√mc sn)
/// (DLMF 19.7.7 in amplitude form): every quantity stays well conditioned up to the separatrix.
pub fn amplitude_to_u(sn: f64, cn: f64, m: f64, mc: f64, k: f64) -> f64 {
    if sn < 0.0 {
        return -amplitude_to_u(-sn, cn, m, mc, k);
    }
    if cn < 0.0 {
        return 2.0 * k - amplitude_to_u(sn, -cn, m, mc, k);
    }
    if sn <= cn || mc <= 0.0 {
        incomplete_f(sn.atan2(cn), m, mc, k)
    } else {
        k - incomplete_f(cn.atan2(mc.sqrt() * sn), m, mc, k)
    }
}

/// (sn, cn, dn)(u | m) with m = 1 − mc; `k` is K(m) (infinite when mc = 0).
pub fn jacobi(u: f64, m: f64, mc: f64, k: f64) -> (f64, f64, f64) {
    if mc <= 0.0 {
        // m = 1: sn = tanh, cn = dn = sech (DLMF 22.5.iii).
        let sech = 1.0 / u.cosh();
        return (u.tanh(), sech, sech);
    }
    if m <= 0.0 {
        let (s, c) = u.sin_cos();
        return (s, c, 1.0);
    }
    // u = r + 2Kj with |r| ≤ K; sn and cn change sign with each half period 2K.
    let j = (u / (2.0 * k)).round();
    let r = u - 2.0 * k * j;
    let sign = if j.rem_euclid(2.0) == 0.0 { 1.0 } else { -1.0 };
    // Descending AGM: a₀ = 1, b₀ = √mc, c₀ = √m; then back-substitute the amplitude.
    let mut a = [0.0f64; 32];
    let mut c = [0.0f64; 32];
    a[0] = 1.0;
    c[0] = m.sqrt();
    let mut b = mc.sqrt();
    let mut n = 0;
    while n < 31 && c[n].abs() > 1e-17 * a[n] {
        a[n + 1] = (a[n] + b) / 2.0;
        c[n + 1] = (a[n] - b) / 2.0;
        b = (a[n] * b).sqrt();
        n += 1;
    }
    let mut phi = 2f64.powi(n as i32) * a[n] * r;
    for i in (1..=n).rev() {
        phi = (phi + (c[i] / a[i] * phi.sin()).asin()) / 2.0;
    }
    let (sn, cn) = phi.sin_cos();
    let dn = (mc + m * cn * cn).sqrt();
    (sign * sn, sign * cn, dn)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rf_and_k_against_closed_forms() {
        // R_F(0, 1, 1) = π/2 and R_F(x, x, x) = 1/√x (DLMF 19.20.1).
        assert!((carlson_rf(0.0, 1.0, 1.0) - PI / 2.0).abs() < 1e-15);
        assert!((carlson_rf(4.0, 4.0, 4.0) - 0.5).abs() < 1e-16);
        // K(1/2) = Γ(1/4)² / (4√π) (DLMF 19.20.2 at k² = 1/2).
        let k_half = 3.625_609_908_221_908_f64.powi(2) / (4.0 * PI.sqrt());
        assert!((complete_k(0.5) - k_half).abs() < 2e-15 * k_half);
        // Two routes to K: the AGM and F(π/2 | m) = R_F(0, mc, 1).
        for mc in [0.9, 0.3, 1e-3, 1e-8, 1e-14] {
            let by_rf = carlson_rf(0.0, mc, 1.0);
            assert!((complete_k(mc) - by_rf).abs() < 4e-15 * by_rf, "mc = {mc}");
        }
        // Near m = 1, K ≈ ln(4/√mc) (DLMF 19.12.1).
        let mc: f64 = 1e-14;
        assert!((complete_k(mc) - (4.0 / mc.sqrt()).ln()).abs() < 1e-13);
    }

    #[test]
    fn jacobi_identities_and_inverse_hold_to_the_separatrix() {
        for mc in [0.7, 0.1, 1e-4, 1e-8, 1e-12, 1e-14] {
            let m = 1.0 - mc;
            let k = complete_k(mc);
            for u in [0.1, 0.7, 0.99 * k, k, 1.3 * k, 3.0 * k, -2.2 * k, 17.5] {
                let (sn, cn, dn) = jacobi(u, m, mc, k);
                assert!((sn * sn + cn * cn - 1.0).abs() < 4e-16, "mc {mc} u {u}");
                assert!((dn * dn + m * sn * sn - 1.0).abs() < 4e-16, "mc {mc} u {u}");
                // The inverse recovers u. Next to u = K the forward map's absolute error ε in
                // cn becomes ε/dn in u, which bounds what a round trip can show; past K, where
                // that amplification compounds, the exact solution's tests take over.
                if u.abs() <= k {
                    let back = amplitude_to_u(sn, cn, m, mc, k);
                    let bound = 1e-13 * (1.0 + u.abs()) + 4.0 * f64::EPSILON / dn;
                    assert!((back - u).abs() < bound, "mc {mc} u {u}: {back}");
                }
            }
            // sn(K) = 1, cn(K) = 0, dn(K) = √mc.
            let (sn, cn, dn) = jacobi(k, m, mc, k);
            assert!((sn - 1.0).abs() < 1e-15 && cn.abs() < 1e-14);
            assert!((dn - mc.sqrt()).abs() < 1e-14 * (1.0 + mc.sqrt()) + 1e-15);
        }
    }

    #[test]
    fn jacobi_derivative_matches_a_difference_quotient() {
        // d sn/du = cn dn: an independent check of the phase, by central differences.
        for mc in [0.5, 1e-6, 1e-12] {
            let (m, k) = (1.0 - mc, complete_k(mc));
            for u in [0.3, 0.8 * k, 1.7 * k] {
                let h = 1e-5;
                let d = (jacobi(u + h, m, mc, k).0 - jacobi(u - h, m, mc, k).0) / (2.0 * h);
                let (_, cn, dn) = jacobi(u, m, mc, k);
                assert!(
                    (d - cn * dn).abs() < 1e-9,
                    "mc {mc} u {u}: {d} vs {}",
                    cn * dn
                );
            }
        }
    }
}
