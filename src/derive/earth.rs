//! Earth's free (Euler) precession, after eqs (88)–(89): β = (C − A)/A from the dynamical
//! ellipticity, the Euler period in sidereal and in mean solar days, its ratio to the observed
//! Chandler period, and the size of the equatorial bulge. All exact rationals from cited data.

use super::algebra::Value;
use super::{Derivation, DeriveError, Step, cited};
use crate::cas::{self, Expr};
use crate::model::catalogue::quantity;
use crate::model::prose::Prose;
use crate::notation::Formula;

/// Dynamical ellipticity H = (C − A)/C = 3.2737949e-3 (REFERENCE.md: IERS Conventions 2010,
/// Table 1.1).
pub const DYNAMICAL_ELLIPTICITY: (i128, i128) = (32_737_949, 10_000_000_000);
/// Mean solar days in a tropical year; the year holds one more sidereal day than solar days.
pub const TROPICAL_YEAR_DAYS: (i128, i128) = (3_652_422, 10_000);
/// The observed Chandler period in days (REFERENCE.md: Malkin & Miller, Earth Planets Space 62
/// (2010) 943).
pub const CHANDLER_DAYS: i128 = 433;
/// WGS84 (REFERENCE.md, NGA.STND.0036): equatorial radius in km and inverse flattening.
pub const EQUATORIAL_RADIUS_KM: (i128, i128) = (6_378_137, 1_000);
pub const INVERSE_FLATTENING: (i128, i128) = (298_257, 1_000);

fn rat((n, d): (i128, i128)) -> Expr {
    Expr::rat(n, d)
}

/// A step for an exact number, with its decimal value.
fn number_step(
    d: &mut Derivation,
    name: &str,
    title: &str,
    lhs: &str,
    value: Expr,
    why: &str,
) -> Result<(), DeriveError> {
    let v = value.eval(&|_| None)?;
    let statement = format!("{lhs} = $0 ~= {}", decimal_notation(v));
    d.steps.push(Step::note(
        title,
        Formula::parse(&statement, std::slice::from_ref(&value)),
        why,
    ));
    d.set(name, Value::Scalar(value))?;
    Ok(())
}

/// The decimal as a formula: 3.284548 × 10⁻³ rather than 3.284548e-3.
fn decimal_notation(v: f64) -> String {
    let text = fmt_decimal(v);
    match text.split_once('e') {
        Some((mantissa, exponent)) => format!("{mantissa} × 10^({exponent})"),
        None => text,
    }
}

/// Seven significant figures, without an exponent for ordinary sizes.
fn fmt_decimal(v: f64) -> String {
    if (1e-2..1e5).contains(&v.abs()) {
        let digits = 6 - v.abs().log10().floor() as i32;
        format!("{v:.*}", digits.max(0) as usize)
    } else {
        format!("{v:.6e}")
    }
}

pub fn earth_precession(d: &mut Derivation) -> Result<(), DeriveError> {
    let beta = beta_from_ellipticity(d)?;
    let at_h = |e: &Expr| {
        cas::simplify(&e.substitute(&|n| (n == "H").then(|| rat(DYNAMICAL_ELLIPTICITY))))
    };
    let beta_value = at_h(&beta)?;
    number_step(
        d,
        quantity::EARTH_BETA,
        "$\\beta$ from the measured $H$",
        "beta",
        beta_value.clone(),
        "$H = 3.2737949 \\times 10^{-3}$ (IERS Conventions 2010, Table 1.1, via REFERENCE.md)",
    )?;
    euler_periods(d, beta_value)?;
    bulge(d)?;
    Ok(())
}

/// β = (C − A)/A, from the dynamical ellipticity H = (C − A)/C solved for C.
fn beta_from_ellipticity(d: &mut Derivation) -> Result<Expr, DeriveError> {
    let (a, c, h) = (Expr::sym("A"), Expr::sym("C"), Expr::sym("H"));
    // H = (C − A)/C, solved for C: the root of H C − (C − A) = 0.
    let roots = cas::roots(
        &Expr::minus(
            Expr::mul(vec![h.clone(), c.clone()]),
            Expr::minus(c.clone(), a.clone()),
        ),
        "C",
    )?;
    let [(c_of_h, 1)] = roots.roots.as_slice() else {
        return Err(DeriveError::Inconsistent(
            "H = (C − A)/C has no single root C".into(),
        ));
    };
    d.steps.push(Step::equation(
        "The polar moment from the dynamical ellipticity",
        "C",
        &Value::Scalar(c_of_h.clone()),
        "$H = (C - A)/C$ solved for $C$",
    ));
    let beta = cas::simplify(&Expr::over(Expr::minus(c_of_h.clone(), a.clone()), a))?;
    d.steps.push(Step::equation(
        "$\\beta$ for an oblate Earth",
        "beta = (C - A)/A",
        &Value::Scalar(beta.clone()),
        cited(
            "earth-beta",
            Prose::default()
                .math("beta = (I_3 - I_1)/I_1")
                .text(" with ")
                .math("I_1 = I_2 = A")
                .text(" and ")
                .math("I_3 = C"),
        ),
    ));
    Ok(beta)
}

/// The Euler period, in sidereal and in solar days, and the observed Chandler period over it.
fn euler_periods(d: &mut Derivation, beta_value: Expr) -> Result<(), DeriveError> {
    // The body-frame wobble has angular frequency βω3 (eq 69), so its period is 2π/(βω3); with
    // ω3 = 2π per sidereal day that is 1/β sidereal days.
    let sidereal = cas::simplify(&Expr::over(Expr::int(1), beta_value))?;
    number_step(
        d,
        quantity::EULER_PERIOD_SIDEREAL_DAYS,
        "Euler period in sidereal days",
        "P // rm(sidereal) ~ rm(day)",
        sidereal.clone(),
        "$P = 2\\pi/(\\beta\\omega_3)$ with $\\omega_3 = 2\\pi$ per sidereal day",
    )?;
    let year = rat(TROPICAL_YEAR_DAYS);
    let solar_per_sidereal = Expr::over(year.clone(), Expr::add(vec![year, Expr::int(1)]));
    let solar = cas::simplify(&Expr::mul(vec![sidereal, solar_per_sidereal]))?;
    number_step(
        d,
        quantity::EULER_PERIOD_SOLAR_DAYS,
        "Euler period in mean solar days",
        "P // rm(day)",
        solar.clone(),
        "a tropical year of 365.2422 mean solar days holds 366.2422 sidereal days",
    )?;
    let ratio = cas::simplify(&Expr::over(Expr::int(CHANDLER_DAYS), solar))?;
    number_step(
        d,
        quantity::CHANDLER_RATIO,
        "Observed Chandler period over the Euler period",
        "433 ~ rm(d) // P",
        ratio,
        "the observed wobble (about 433 days, Malkin & Miller 2010) is slower: Earth is not rigid \
         (elastic mantle, oceans, fluid core)",
    )?;
    Ok(())
}

/// The equatorial bulge, in km and as a fraction of the radius.
fn bulge(d: &mut Derivation) -> Result<(), DeriveError> {
    let flattening = Expr::over(Expr::int(1), rat(INVERSE_FLATTENING));
    let bulge = cas::simplify(&Expr::mul(vec![
        rat(EQUATORIAL_RADIUS_KM),
        flattening.clone(),
    ]))?;
    number_step(
        d,
        quantity::BULGE_KM,
        "Equatorial bulge $a - c$ in km",
        "a - c",
        bulge,
        "$a - c = af$ with the WGS84 $a = 6378.137$ km and $1/f = 298.257$",
    )?;
    number_step(
        d,
        quantity::BULGE_FRACTION,
        "Bulge as a fraction of the radius",
        "(a - c) // a",
        cas::simplify(&flattening)?,
        "$(a - c)/a$ is the flattening $f$",
    )?;
    Ok(())
}
