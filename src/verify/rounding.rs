//! A number the notes give roughly ("about 300 days"): both sides rounded to the notes' figures.

use crate::base::format::{significant, text_number};
use crate::cas::EvalError;
use crate::model::value::Value;
use std::collections::BTreeMap;

/// `x` rounded to `figures` significant figures.
pub fn round_to_figures(x: f64, figures: u32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let exponent = x.abs().log10().floor() as i32;
    let scale = 10f64.powi(figures as i32 - 1 - exponent);
    (x * scale).round() / scale
}

/// A side of a claim given to significant figures that is not a number.
#[derive(Debug, thiserror::Error)]
pub(super) enum NotANumber {
    #[error("the {side} side is not a number: {error}")]
    Eval {
        side: &'static str,
        error: EvalError,
    },
    #[error("the {side} side is {kind}, not a number")]
    Kind {
        side: &'static str,
        kind: &'static str,
    },
}

/// Do two numbers agree at the precision the notes give? Both sides must be numbers once the
/// scene's `[numeric]` values are put in (a period of 2.0 s "about 2 s" at L = 1.5 m).
pub(super) fn rounded_agreement(
    derived: &Value,
    notes: &Value,
    figures: u32,
    values: &BTreeMap<String, f64>,
) -> Result<(bool, String), NotANumber> {
    let mut used = false;
    let mut number = |v: &Value, side: &'static str| -> Result<f64, NotANumber> {
        match v {
            Value::Scalar(e) => e
                .eval(&|s| values.get(s).copied())
                .inspect(|_| used |= e.symbols().iter().any(|s| values.contains_key(s)))
                .map_err(|error| NotANumber::Eval { side, error }),
            other => Err(NotANumber::Kind {
                side,
                kind: other.kind(),
            }),
        }
    };
    let (d, n) = (number(derived, "derived")?, number(notes, "notes'")?);
    let at = if used { " at the scene's values" } else { "" };
    let (rd, rn) = (round_to_figures(d, figures), round_to_figures(n, figures));
    // Both rounded the same way (a scaling by 10^k and back): equal decimals differ by a few
    // ulps at most, unequal ones by at least a unit in the last figure kept, 10^-figures of
    // the value or more. A tenth of that unit, and never more than 1e-12, tells them apart up
    // to the 15 figures a claim may state.
    let within = 1e-12_f64.min(0.1 * 10f64.powi(-(figures as i32)));
    let agrees = (rd - rn).abs() <= within * rd.abs().max(rn.abs());
    let unit = if figures == 1 { "figure" } else { "figures" };
    Ok((
        agrees,
        format!(
            "{}{at} rounds to {} at {figures} significant {unit}; the notes give {}",
            text_number(&significant(d, 7)),
            text_number(&format!("{rd}")),
            text_number(&format!("{n}"))
        ),
    ))
}
