//! Earth's polar motion over one Euler period, with the Chandler period beside it.

use super::accuracy::exact_accuracy;
use super::frame::{fig, times};
use super::{FigureError, colour};
use crate::derive::earth;
use crate::model::fidelity::Fidelity;
use crate::model::figure::{Figure, Mark, Series};
use crate::model::moments::Moments;
use crate::numeric::free_body::ExactSolution;
use nalgebra::Vector3;
use std::f64::consts::PI;

/// Mean solar days per sidereal day: a tropical year holds one more sidereal day than solar days.
pub(super) const SOLAR_PER_SIDEREAL: f64 = {
    let year = earth::TROPICAL_YEAR_DAYS.0 as f64 / earth::TROPICAL_YEAR_DAYS.1 as f64;
    year / (year + 1.0)
};

/// The dynamical ellipticity H = (C − A)/C and the observed Chandler period in days, as cited in
/// `derive::earth`.
pub const EARTH_H: f64 =
    earth::DYNAMICAL_ELLIPTICITY.0 as f64 / earth::DYNAMICAL_ELLIPTICITY.1 as f64;
pub const CHANDLER_DAYS: f64 = earth::CHANDLER_DAYS as f64;

/// ω in radians per sidereal day: ω3 = 2π is one turn per sidereal day.
pub(super) fn polar_motion(
    i: &Moments,
    w0: Vector3<f64>,
    fid: &Fidelity,
) -> Result<Figure, FigureError> {
    let sol = ExactSolution::new(i, w0);
    let period = sol.period().ok_or(FigureError::NoWobble)?;
    let (ia, ic) = (i.0[0], i.0[2]);
    let beta = (ic - ia) / ia;
    let euler_sidereal = period * w0.z / (2.0 * PI);
    let euler_solar = euler_sidereal * SOLAR_PER_SIDEREAL;
    let n = fid.samples(200);
    let pts: Vec<(f64, f64)> = (0..=n)
        .map(|k| {
            let w = sol.omega(period * k as f64 / n as f64);
            (w.x / w.z, w.y / w.z)
        })
        .collect();
    let months: Vec<(f64, f64)> = (0..12)
        .map(|k| {
            let days = 30.4375 * k as f64 / SOLAR_PER_SIDEREAL;
            let w = sol.omega(days * 2.0 * PI / w0.z);
            (w.x / w.z, w.y / w.z)
        })
        .collect();
    let desc = format!(
        "Earth's free (Euler) wobble: the rotation axis in the body frame, (ω1/ω3, ω2/ω3), for \
         I = ({}, {}, {}) (so β = (C − A)/A = {}) and one turn per sidereal day. The exact \
         solution closes after {euler_sidereal:.3} sidereal days = {euler_solar:.3} mean solar days \
         (1/β sidereal days); dots mark 12 months. The observed Chandler period is about \
         {CHANDLER_DAYS} days, {:.3} times longer, because Earth is not rigid.",
        i.0[0],
        i.0[1],
        i.0[2],
        crate::base::format::text_number(&format!("{beta:.7e}")),
        CHANDLER_DAYS / euler_solar
    );
    let mut f = fig(
        "polar-motion",
        "Euler's free precession of Earth's axis".into(),
        desc,
        "ω1/ω3",
        "ω2/ω3",
        vec![
            Series {
                name: "one Euler period".into(),
                mark: Mark::Line,
                colour: colour::PRIMARY,
                points: pts,
            },
            Series {
                name: "monthly".into(),
                mark: Mark::Points,
                colour: colour::CONTRAST,
                points: months,
            },
        ],
    );
    f.equal_aspect = true;
    f.accuracy = vec![exact_accuracy("wobble path", i, &w0, &times(period, n))];
    Ok(f)
}
