//! Units and dimensions: a symbol's declared unit (`"kg m^2"`, `"m/s^2"`, `"rad/s"`), its
//! dimension in the seven SI base quantities, and its size in the coherent SI unit (exact: a
//! power of ten from the prefixes). Plane angle is dimensionless, as in SI.

use crate::cas::{Expr, Rational};
use crate::notation::{Formula, Op};
use std::fmt;

/// The SI base quantities, in the order of [`Dimension`]'s exponents, with their units.
const BASE: [&str; 7] = ["kg", "m", "s", "A", "K", "mol", "cd"];

/// A product of powers of the base quantities: mass, length, time, current, temperature,
/// amount, luminous intensity.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Dimension(pub [Rational; 7]);

impl Default for Dimension {
    fn default() -> Self {
        Dimension::none()
    }
}

impl Dimension {
    /// A pure number (an angle, a ratio).
    pub fn none() -> Dimension {
        Dimension(std::array::from_fn(|_| Rational::ZERO))
    }

    fn base(k: usize) -> Dimension {
        let mut d = Dimension::none();
        d.0[k] = Rational::ONE;
        d
    }

    pub fn mass() -> Dimension {
        Dimension::base(0)
    }

    pub fn length() -> Dimension {
        Dimension::base(1)
    }

    pub fn time() -> Dimension {
        Dimension::base(2)
    }

    pub fn is_none(&self) -> bool {
        self.0.iter().all(Rational::is_zero)
    }

    pub fn times(&self, o: &Dimension) -> Dimension {
        Dimension(std::array::from_fn(|k| self.0[k].add(&o.0[k])))
    }

    pub fn power(&self, p: &Rational) -> Dimension {
        Dimension(std::array::from_fn(|k| self.0[k].mul(p)))
    }

    pub fn over(&self, o: &Dimension) -> Dimension {
        self.times(&o.power(&Rational::int(-1)))
    }
}

impl Dimension {
    /// As a unit in SI base units, whole powers only (`kg m^2 s^-1`); none for a pure number
    /// or a fractional power, which no reader writes as a unit.
    pub fn base_units(&self) -> Option<String> {
        if self.is_none() || self.0.iter().any(|p| !p.is_integer()) {
            return None;
        }
        Some(self.to_string())
    }
}

/// In SI base units: `kg m^2 s^-1`, or `1` for a pure number.
impl Dimension {
    /// As a unit is set: each base unit upright with its power, thin spaces between
    /// (kg⁻¹ m⁻²), as [`unit_formula`] sets an author's unit; `None` for a pure number.
    pub fn formula(&self) -> Option<Formula> {
        let mut row = Vec::new();
        for (u, p) in BASE.iter().zip(&self.0).filter(|(_, p)| !p.is_zero()) {
            if !row.is_empty() {
                row.push(Formula::Op(Op::Thin));
            }
            let symbol = Formula::Upright(u.to_string());
            row.push(if *p == Rational::ONE {
                symbol
            } else {
                Formula::Sup(Box::new(symbol), Box::new(Formula::Number(p.to_string())))
            });
        }
        (!row.is_empty()).then_some(Formula::Row(row))
    }
}

impl fmt::Display for Dimension {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_none() {
            return write!(f, "1 (a pure number)");
        }
        let parts: Vec<String> = BASE
            .iter()
            .zip(&self.0)
            .filter(|(_, p)| !p.is_zero())
            .map(|(u, p)| {
                if *p == Rational::ONE {
                    u.to_string()
                } else {
                    format!("{u}^{p}")
                }
            })
            .collect();
        write!(f, "{}", parts.join(" "))
    }
}

/// A unit as the author wrote it, with its dimension and its size in SI base units.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Unit {
    pub text: String,
    pub dimension: Dimension,
    /// How many coherent SI units one of it is: 1/100 for `cm`, 1/1000 for `g`.
    pub scale: Rational,
}

/// Why a unit could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UnitError {
    #[error(
        "`{0}` is not an SI unit; write units such as kg, m, s, N, J, rad, with prefixes (cm, mm, g) and powers (m^2, s^-1)"
    )]
    Unknown(String),
    #[error("the power in `{0}` is not a whole number such as ^2 or ^-1")]
    Power(String),
    #[error("a unit has at most one `/`: write `kg m^2/s` or `kg m^2 s^-1`")]
    Slashes,
    #[error("the unit is empty")]
    Empty,
}

/// The named SI units: symbol, dimension exponents (kg, m, s, A, K, mol, cd).
const UNITS: &[(&str, [i8; 7])] = &[
    ("g", [1, 0, 0, 0, 0, 0, 0]),
    ("m", [0, 1, 0, 0, 0, 0, 0]),
    ("s", [0, 0, 1, 0, 0, 0, 0]),
    ("A", [0, 0, 0, 1, 0, 0, 0]),
    ("K", [0, 0, 0, 0, 1, 0, 0]),
    ("mol", [0, 0, 0, 0, 0, 1, 0]),
    ("cd", [0, 0, 0, 0, 0, 0, 1]),
    ("rad", [0; 7]),
    ("sr", [0; 7]),
    ("Hz", [0, 0, -1, 0, 0, 0, 0]),
    ("N", [1, 1, -2, 0, 0, 0, 0]),
    ("Pa", [1, -1, -2, 0, 0, 0, 0]),
    ("J", [1, 2, -2, 0, 0, 0, 0]),
    ("W", [1, 2, -3, 0, 0, 0, 0]),
    ("C", [0, 0, 1, 1, 0, 0, 0]),
    ("V", [1, 2, -3, -1, 0, 0, 0]),
];

/// SI prefixes and their powers of ten (`u` stands for µ).
const PREFIXES: &[(&str, i64)] = &[
    ("Y", 24),
    ("Z", 21),
    ("E", 18),
    ("P", 15),
    ("T", 12),
    ("G", 9),
    ("M", 6),
    ("k", 3),
    ("h", 2),
    ("da", 1),
    ("d", -1),
    ("c", -2),
    ("m", -3),
    ("µ", -6),
    ("u", -6),
    ("n", -9),
    ("p", -12),
    ("f", -15),
    ("a", -18),
];

fn ten_to(k: i64) -> Rational {
    Rational::int(10).pow(k).expect("ten is not zero")
}

/// One unit symbol, with or without a prefix: `m`, `mm`, `kg`, `µs`. A whole symbol is read
/// before a prefix, so `m` is the metre and `cd` the candela.
fn one(symbol: &str) -> Option<(Dimension, Rational)> {
    let named = |s: &str| {
        UNITS.iter().find(|(u, _)| *u == s).map(|(_, e)| {
            let d = Dimension(std::array::from_fn(|k| Rational::int(e[k] as i128)));
            // The kilogram is the base unit, so the gram is a thousandth of it.
            let scale = if s == "g" { ten_to(-3) } else { Rational::ONE };
            (d, scale)
        })
    };
    if let Some(found) = named(symbol) {
        return Some(found);
    }
    PREFIXES.iter().find_map(|(p, k)| {
        let rest = symbol.strip_prefix(p)?;
        let (d, scale) = named(rest)?;
        Some((d, scale.mul(&ten_to(*k))))
    })
}

impl Unit {
    /// Reads `kg m^2`, `m/s^2`, `kg*m^2*s^-1`, `rad/s`, `m²`. Factors are separated by spaces,
    /// `*` or `·`; everything after the one `/` divides.
    pub fn parse(text: &str) -> Result<Unit, UnitError> {
        let mut parts = text.split('/');
        let top = parts.next().unwrap_or("");
        let bottom = parts.next();
        if parts.next().is_some() {
            return Err(UnitError::Slashes);
        }
        let mut dimension = Dimension::none();
        let mut scale = Rational::ONE;
        let mut factors = 0;
        for (part, sign) in [(top, 1i64), (bottom.unwrap_or(""), -1)] {
            for factor in part
                .split(|c: char| c.is_whitespace() || c == '*' || c == '·')
                .filter(|f| !f.is_empty())
            {
                if factor == "1" && sign == 1 {
                    continue;
                }
                let (symbol, power) = split_power(factor)?;
                let (d, s) = one(symbol).ok_or_else(|| UnitError::Unknown(symbol.to_string()))?;
                let p = power * sign;
                dimension = dimension.times(&d.power(&Rational::int(p as i128)));
                scale = scale.mul(&s.pow(p).expect("a unit's scale is not zero"));
                factors += 1;
            }
        }
        if factors == 0 && !text.trim().starts_with('1') {
            return Err(UnitError::Empty);
        }
        Ok(Unit {
            text: text.trim().to_string(),
            dimension,
            scale,
        })
    }
}

/// A unit as LaTeX, upright: `kg m^2/s` as `\mathrm{kg}\,\mathrm{m}^{2}/\mathrm{s}`. The pages
/// set units from [`unit_formula`]; this is the tests' second route to the same tree.
#[cfg(test)]
fn unit_latex(text: &str) -> String {
    let side = |part: &str| -> String {
        part.split(|c: char| c.is_whitespace() || c == '*' || c == '·')
            .filter(|f| !f.is_empty())
            .map(|f| {
                let (symbol, power) = match split_power(f) {
                    Ok((s, 1)) => (s, String::new()),
                    Ok((s, p)) => (s, format!("^{{{p}}}")),
                    Err(_) => (f, String::new()),
                };
                let symbol = symbol.replace('µ', "\\mu ");
                format!("\\mathrm{{{symbol}}}{power}")
            })
            .collect::<Vec<_>>()
            .join("\\,")
    };
    match text.split_once('/') {
        Some((top, bottom)) => format!("{}/{}", side(top), side(bottom)),
        None => side(text),
    }
}

/// A unit as a formula: each symbol upright with its power, thin spaces between, one `/`.
pub fn unit_formula(text: &str) -> Formula {
    let side = |part: &str| -> Vec<Formula> {
        let mut out = Vec::new();
        for f in part
            .split(|c: char| c.is_whitespace() || c == '*' || c == '·')
            .filter(|f| !f.is_empty())
        {
            if !out.is_empty() {
                out.push(Formula::Op(Op::Thin));
            }
            let (symbol, power) = split_power(f).unwrap_or((f, 1));
            // µ (the micro sign) is set as the Greek letter mu.
            let symbol = Formula::Upright(symbol.replace('µ', "μ"));
            out.push(match power {
                1 => symbol,
                p => Formula::Sup(Box::new(symbol), Box::new(Formula::Number(p.to_string()))),
            });
        }
        out
    };
    match text.split_once('/') {
        Some((top, bottom)) => {
            let mut row = side(top);
            row.push(Formula::Op(Op::Slash));
            row.extend(side(bottom));
            Formula::Row(row)
        }
        None => Formula::Row(side(text)),
    }
}

/// `m^2` -> (`m`, 2), `s^-1` -> (`s`, -1), `m²` -> (`m`, 2), `kg` -> (`kg`, 1).
fn split_power(factor: &str) -> Result<(&str, i64), UnitError> {
    let bad = || UnitError::Power(factor.to_string());
    if let Some((symbol, p)) = factor.split_once('^') {
        let p: i64 = p
            .trim_matches(|c| c == '(' || c == ')')
            .parse()
            .map_err(|_| bad())?;
        if p == 0 || p.abs() > 12 {
            return Err(bad());
        }
        return Ok((symbol, p));
    }
    for (sup, p) in [('²', 2), ('³', 3)] {
        if let Some(symbol) = factor.strip_suffix(sup) {
            return Ok((symbol, p));
        }
    }
    Ok((factor, 1))
}

/// What an expression measures: its dimension, and the size of its unit in SI base units
/// (the product of its symbols' units: a length in `cm` times a mass in `g` is 1e-5 kg m).
#[derive(Debug, Clone, PartialEq)]
pub struct Measure {
    pub dimension: Dimension,
    pub scale: Rational,
}

impl Measure {
    pub fn none() -> Measure {
        Measure {
            dimension: Dimension::none(),
            scale: Rational::ONE,
        }
    }

    pub fn of(unit: &Unit) -> Measure {
        Measure {
            dimension: unit.dimension.clone(),
            scale: unit.scale.clone(),
        }
    }

    fn times(&self, o: &Measure) -> Measure {
        Measure {
            dimension: self.dimension.times(&o.dimension),
            scale: self.scale.mul(&o.scale),
        }
    }

    /// To a rational power; the scale only where it stays exact (a whole power, or a prefix
    /// power of ten that the root divides).
    fn power(&self, p: &Rational) -> Option<Measure> {
        let scale = match p.to_i64() {
            Some(k) => self.scale.pow(k)?,
            None => exact_root(&self.scale, p)?,
        };
        Some(Measure {
            dimension: self.dimension.power(p),
            scale,
        })
    }

    /// Time's unit divides: the rate of a coordinate.
    pub fn per_second(&self) -> Measure {
        Measure {
            dimension: self.dimension.over(&Dimension::time()),
            scale: self.scale.clone(),
        }
    }
}

/// s^p for a non-integer p, when s is a power of ten the root divides (10^-4 under a square
/// root is 10^-2); `None` otherwise.
fn exact_root(s: &Rational, p: &Rational) -> Option<Rational> {
    let (n, d) = p.to_i64_pair()?;
    for k in -60i64..=60 {
        if ten_to(k) == *s {
            return ((k * n) % d == 0).then(|| ten_to(k * n / d));
        }
    }
    None
}

/// What to do about a sum of unlike terms: the terminal's error and the page's note end with it.
pub const UNLIKE_SUM_ADVICE: &str =
    "a sum's terms must have one dimension: check that term, or the symbols' units";

/// Two terms of one sum in different dimensions, kept as expressions so a page can set them.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "`{left}` is in {left_dim} but `{right}` is in {right_dim}: {advice}",
    advice = UNLIKE_SUM_ADVICE
)]
pub struct UnlikeTerms {
    pub left: Expr,
    pub left_dim: Dimension,
    pub right: Expr,
    pub right_dim: Dimension,
}

/// Why an expression has no consistent dimension (the dimensions in words, as SI base units).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DimensionError {
    #[error("{0}")]
    UnlikeSum(Box<UnlikeTerms>),
    #[error(
        "`{left}` and `{right}` have one dimension ({dimension}) but different units: give the \
         symbols in one unit"
    )]
    UnlikeUnits {
        left: String,
        right: String,
        dimension: String,
    },
    #[error(
        "`{function}` of `{argument}`, which is in {dimension}: its argument must be a pure number \
         (an angle in rad)"
    )]
    Function {
        function: String,
        argument: String,
        dimension: String,
    },
    #[error("the power `{power}` of `{base}`, which is in {dimension}, must be a number")]
    Power {
        base: String,
        power: String,
        dimension: String,
    },
}

/// The measure of a scalar expression, from its names' (`None` for a name with no unit);
/// `None` when it depends on such a name. Numbers are pure.
pub fn measure_of(
    e: &Expr,
    names: &dyn Fn(&str) -> Option<Measure>,
) -> Result<Option<Measure>, DimensionError> {
    Ok(match e {
        Expr::Num(_) => Some(Measure::none()),
        Expr::Sym(s) if s == "pi" => Some(Measure::none()),
        Expr::Sym(s) => names(s),
        Expr::Add(terms) => sum_measure(terms, names)?,
        Expr::Mul(factors) => {
            let mut out = Some(Measure::none());
            for f in factors {
                let m = measure_of(f, names)?;
                out = match (out, m) {
                    (Some(a), Some(b)) => Some(a.times(&b)),
                    _ => None,
                };
            }
            out
        }
        Expr::Pow(b, x) => power_measure(b, x, names)?,
        Expr::Call(f, args) if args.len() == 1 => function_measure(f, &args[0], names)?,
        // atan2(y, x): the angle of a point, whose two coordinates share a unit, as a sum's terms.
        Expr::Call(f, args) if f == "atan2" => {
            measure_of(&Expr::add(args.clone()), names)?;
            Some(Measure::none())
        }
        _ => None,
    })
}

/// A sum's measure: its terms' (those known), which must agree in dimension and unit.
fn sum_measure(
    terms: &[Expr],
    names: &dyn Fn(&str) -> Option<Measure>,
) -> Result<Option<Measure>, DimensionError> {
    let mut known: Option<(Measure, &Expr)> = None;
    for t in terms {
        let Some(m) = measure_of(t, names)? else {
            continue;
        };
        match &known {
            None => known = Some((m, t)),
            Some((k, first)) if k.dimension != m.dimension => {
                return Err(DimensionError::UnlikeSum(Box::new(UnlikeTerms {
                    left: (*first).clone(),
                    left_dim: k.dimension.clone(),
                    right: t.clone(),
                    right_dim: m.dimension.clone(),
                })));
            }
            Some((k, first)) if k.scale != m.scale => {
                return Err(DimensionError::UnlikeUnits {
                    left: first.to_text(),
                    right: t.to_text(),
                    dimension: m.dimension.to_string(),
                });
            }
            Some(_) => {}
        }
    }
    Ok(known.map(|(m, _)| m))
}

/// A power's measure: a rational power of a measure, or any power of a pure number; the power itself dimensionless.
fn power_measure(
    b: &Expr,
    x: &Expr,
    names: &dyn Fn(&str) -> Option<Measure>,
) -> Result<Option<Measure>, DimensionError> {
    let base = measure_of(b, names)?;
    let power = measure_of(x, names)?;
    if let Some(p) = &power
        && !p.dimension.is_none()
    {
        return Err(DimensionError::Power {
            base: b.to_text(),
            power: x.to_text(),
            dimension: p.dimension.to_string(),
        });
    }
    Ok(match (base, x) {
        (Some(m), Expr::Num(p)) => m.power(p),
        // A pure number to any power; its scale (c/L in cm over m) then is unknown.
        (Some(m), _) if m.dimension.is_none() => (m.scale == Rational::ONE).then(Measure::none),
        (Some(m), _) => {
            return Err(DimensionError::Power {
                base: b.to_text(),
                power: x.to_text(),
                dimension: m.dimension.to_string(),
            });
        }
        (None, _) => None,
    })
}

/// A function of one argument: √ halves the dimension, |x| keeps it, the others take and give pure numbers.
fn function_measure(
    f: &str,
    arg: &Expr,
    names: &dyn Fn(&str) -> Option<Measure>,
) -> Result<Option<Measure>, DimensionError> {
    let m = measure_of(arg, names)?;
    Ok(match f {
        "sqrt" => m.and_then(|m| m.power(&Rational::new(1, 2).expect("two is not zero"))),
        "abs" => m,
        f if crate::cas::needs_dimensionless(f) => {
            if let Some(m) = &m
                && !m.dimension.is_none()
            {
                return Err(DimensionError::Function {
                    function: f.to_string(),
                    argument: arg.to_text(),
                    dimension: m.dimension.to_string(),
                });
            }
            Some(Measure::none())
        }
        "sign" => Some(Measure::none()),
        _ => None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit's tree is what the reader makes of its LaTeX: the key's values and the pages
    /// set units from the tree, Moodle from the LaTeX.
    /// A dimension is set as the unit it is written as: the tree from its exponents equals
    /// the tree from the author's text, for units in SI base units in their order.
    #[test]
    fn a_dimension_is_set_as_its_unit_is() {
        for unit in [
            "kg",
            "kg m^2",
            "kg^-1 m^-2",
            "kg m^2 s^-2",
            "s^-2",
            "m s^-1",
        ] {
            let dimension = Unit::parse(unit).unwrap().dimension;
            assert_eq!(dimension.formula(), Some(unit_formula(unit)), "{unit}");
        }
        assert_eq!(Dimension::none().formula(), None);
    }

    #[test]
    fn a_units_tree_is_its_latex_read() {
        for unit in [
            "kg",
            "kg m^2",
            "kg*m^2/s^2",
            "m/s²",
            "s^-1",
            "µs",
            "rad/s",
            "N·m",
            "1/s",
        ] {
            let tree = unit_formula(unit)
                .to_tex(crate::notation::Names::none())
                .nodes;
            let read = crate::notation::Tex::read(&unit_latex(unit)).unwrap().nodes;
            assert_eq!(tree, read, "{unit}");
        }
    }

    fn dim(text: &str) -> String {
        Unit::parse(text).unwrap().dimension.to_string()
    }

    #[test]
    fn units_read_as_their_si_dimensions() {
        crate::base::assert_each(
            dim,
            &[
                ("kg m^2", "kg m^2"),
                ("m/s^2", "m s^-2"),
                ("rad/s", "s^-1"),
                ("N m", "kg m^2 s^-2"),
            ],
        );
        assert_eq!(dim("J s"), dim("kg*m^2*s^-1"));
        crate::base::assert_each(
            dim,
            &[("m²", "m^2"), ("rad", "1 (a pure number)"), ("1/s", "s^-1")],
        );
    }

    #[test]
    fn prefixes_scale_exactly_and_whole_symbols_come_first() {
        let cm = Unit::parse("cm").unwrap();
        assert_eq!(cm.scale, Rational::new(1, 100).unwrap());
        assert_eq!(
            Unit::parse("g cm^2").unwrap().scale,
            Rational::new(1, 10_000_000).unwrap()
        );
        assert_eq!(Unit::parse("kg").unwrap().scale, Rational::ONE);
        assert_eq!(
            Unit::parse("mm").unwrap().scale,
            Rational::new(1, 1000).unwrap()
        );
        // `m` is the metre, not a prefix; `ms` the millisecond.
        assert_eq!(dim("m"), "m");
        assert_eq!(dim("ms"), "s");
        assert_eq!(dim("cd"), "cd");
    }

    #[test]
    fn what_is_not_a_unit_says_why() {
        assert!(matches!(Unit::parse("furlong"), Err(UnitError::Unknown(u)) if u == "furlong"));
        assert!(matches!(Unit::parse("m^x"), Err(UnitError::Power(_))));
        assert_eq!(Unit::parse("m/s/s"), Err(UnitError::Slashes));
        assert_eq!(Unit::parse(" "), Err(UnitError::Empty));
    }
}

#[cfg(test)]
mod measure_tests {
    use super::*;
    use crate::cas::parse;

    fn names(s: &str) -> Option<Measure> {
        let unit = match s {
            "M" => "kg",
            "L" | "d" => "m",
            "c" => "cm",
            "g" => "m/s^2",
            "w" => "rad/s",
            _ => return None,
        };
        Some(Measure::of(&Unit::parse(unit).unwrap()))
    }

    fn measure(text: &str) -> Result<Option<Measure>, DimensionError> {
        measure_of(&parse(text).unwrap().expr, &names)
    }

    #[test]
    fn products_powers_and_roots_carry_dimensions() {
        let m = measure("M*L^2/3 + M*d^2").unwrap().unwrap();
        assert_eq!(m.dimension.to_string(), "kg m^2");
        let period = measure("2*pi*sqrt(L/g)").unwrap().unwrap();
        assert_eq!(period.dimension.to_string(), "s");
        assert_eq!(
            measure("M*x").unwrap(),
            None,
            "a name without a unit is not checked"
        );
        assert_eq!(
            measure("L + x").unwrap().unwrap().dimension,
            Dimension::length()
        );
        let c2 = measure("M*c^2").unwrap().unwrap();
        assert_eq!(c2.scale, Rational::new(1, 10_000).unwrap());
        assert_eq!(
            measure("sqrt(c^2)").unwrap().unwrap().scale,
            Rational::new(1, 100).unwrap()
        );
    }

    #[test]
    fn unlike_sums_functions_and_powers_are_refused() {
        assert!(matches!(
            measure("M + L"),
            Err(DimensionError::UnlikeSum(_))
        ));
        assert!(matches!(
            measure("sin(L)"),
            Err(DimensionError::Function { .. })
        ));
        assert!(matches!(measure("cos(L/d)"), Ok(Some(_))));
        assert!(matches!(
            measure("L + c"),
            Err(DimensionError::UnlikeUnits { .. })
        ));
        assert!(matches!(measure("L^M"), Err(DimensionError::Power { .. })));
        assert!(
            measure("sin(w*x)").unwrap().is_some(),
            "unknown arguments pass"
        );
    }
}
