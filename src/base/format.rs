//! Deterministic number formatting, shared by captions, reports and pages.

/// The first letter in capitals: a label or a heading opens a row or a sentence.
pub fn capitalised(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_uppercase().chain(c).collect(),
        None => String::new(),
    }
}

/// `n` things, the noun in the plural unless there is one: "1 plot", "16 plots", "0 PDFs".
/// Every noun mechbook counts takes a plain -s.
pub fn count(n: impl std::fmt::Display, noun: &str) -> String {
    match n.to_string() {
        one if one == "1" => format!("1 {noun}"),
        n => format!("{n} {noun}s"),
    }
}

/// A relative error or a time in compact scientific form, as a reader writes it: 8.3×10⁻¹⁶
/// (never 8.3e-16, which reads as 8.3·e − 16); exact zero prints as 0.
pub fn sci(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else {
        text_number(&format!("{x:.1e}"))
    }
}

/// A tolerance or bound: 10⁻¹⁰ rather than 1.0×10⁻¹⁰.
pub fn short(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else {
        text_number(&format!("{x:.1e}").replace(".0e", "e"))
    }
}

/// A digit or a minus sign as a superscript (⁻¹⁶); any other character as it is.
pub fn superscript(c: char) -> char {
    match c {
        '-' => '⁻',
        '0' => '⁰',
        '1' => '¹',
        '2' => '²',
        '3' => '³',
        '4' => '⁴',
        '5' => '⁵',
        '6' => '⁶',
        '7' => '⁷',
        '8' => '⁸',
        '9' => '⁹',
        other => other,
    }
}

/// A number in e-notation split into its mantissa and power of ten (`8.3e-16` is 8.3 and −16);
/// `None` for any other number.
pub fn power_of_ten(s: &str) -> Option<(&str, i32)> {
    let (mantissa, exponent) = s.split_once(['e', 'E'])?;
    let power = exponent.parse::<i32>().ok()?;
    (!mantissa.is_empty()).then_some((mantissa, power))
}

/// A number in e-notation as text: `8.3e-16` as 8.3×10⁻¹⁶, `1e-10` as 10⁻¹⁰, `2.5e0` as 2.5;
/// other numbers as they are.
pub fn text_number(s: &str) -> String {
    let Some((mantissa, power)) = power_of_ten(s) else {
        return s.to_string();
    };
    if power == 0 {
        return mantissa.to_string();
    }
    let superscript: String = power.to_string().chars().map(superscript).collect();
    match mantissa {
        "1" => format!("10{superscript}"),
        "-1" => format!("-10{superscript}"),
        m => format!("{m}×10{superscript}"),
    }
}

/// A computed value to `digits` significant figures, in plain notation between 1e-4 and 1e6 (no
/// trailing zeros: 0.5, not 0.500000) and in scientific notation outside: 0.570436, 4.21566,
/// 1.2e-7 at three figures.
pub fn significant(x: f64, digits: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let magnitude = x.abs().log10().floor() as i32;
    if (-4..6).contains(&magnitude) {
        let decimals = (digits as i32 - 1 - magnitude).max(0) as usize;
        let plain = format!("{x:.decimals$}");
        if plain.contains('.') {
            plain
                .trim_end_matches('0')
                .trim_end_matches('.')
                .to_string()
        } else {
            plain
        }
    } else {
        // Trailing zeros dropped here too: 3.2e-5, not 3.20000e-5.
        let sci = format!("{x:.prec$e}", prec = digits.saturating_sub(1));
        match sci.split_once('e') {
            Some((mantissa, exponent)) if mantissa.contains('.') => format!(
                "{}e{exponent}",
                mantissa.trim_end_matches('0').trim_end_matches('.')
            ),
            _ => sci,
        }
    }
}

/// A value to exactly `digits` significant figures, trailing zeros kept (0.5000 at four), as
/// an answer key gives it; scientific notation below 1e-4 and from 10^digits up.
pub fn figures(x: f64, digits: usize) -> String {
    if x == 0.0 {
        return format!("{:.prec$}", 0.0, prec = digits.saturating_sub(1));
    }
    if !x.is_finite() {
        return format!("{x}");
    }
    // Rounding may carry into the next power of ten (9.9996 → 10.00): measure after rounding.
    let rounded: f64 = format!("{x:.prec$e}", prec = digits.saturating_sub(1))
        .parse()
        .unwrap_or(x);
    let magnitude = rounded.abs().log10().floor() as i32;
    if (-4..digits as i32).contains(&magnitude) {
        let decimals = (digits as i32 - 1 - magnitude) as usize;
        format!("{rounded:.decimals$}")
    } else {
        format!("{x:.prec$e}", prec = digits.saturating_sub(1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_thing_is_singular_and_any_other_count_plural() {
        assert_eq!(count(1usize, "plot"), "1 plot");
        assert_eq!(count(0usize, "PDF"), "0 PDFs");
        assert_eq!(count(16u64, "ODE integration"), "16 ODE integrations");
        assert_eq!(count(11usize, "scene"), "11 scenes");
    }

    #[test]
    fn exact_figures_keep_their_zeros() {
        assert_eq!(figures(0.5, 4), "0.5000");
        assert_eq!(figures(14.083333, 4), "14.08");
        assert_eq!(figures(9.99996, 4), "10.00");
        assert_eq!(figures(-0.625, 4), "-0.6250");
        assert_eq!(figures(1234.56, 4), "1235");
        assert_eq!(figures(12345.6, 4), "1.235e4");
        assert_eq!(figures(2.5e-7, 4), "2.500e-7");
        assert_eq!(figures(0.0, 4), "0.000");
    }

    #[test]
    fn significant_figures() {
        assert_eq!(significant(0.5704361, 6), "0.570436");
        assert_eq!(significant(4.215662, 6), "4.21566");
        assert_eq!(significant(-18.75, 3), "-18.8");
        assert_eq!(significant(1.2e-7, 3), "1.2e-7");
        assert_eq!(significant(3.2e-5, 6), "3.2e-5");
        assert_eq!(significant(1.0e-14, 2), "1e-14");
        assert_eq!(significant(0.0, 6), "0");
        assert_eq!(significant(0.5, 6), "0.5");
        assert_eq!(significant(1200.0, 3), "1200");
    }
}

/// A number as LaTeX: `4.6875e-6` as `4.6875 \times 10^{-6}`, so that no page reads an italic e
/// and a spaced minus; other numbers as they are. The pages set numbers from
/// `notation::Formula::decimal`; this is the tests' second route to the same tree.
#[cfg(test)]
pub fn latex_number(s: &str) -> String {
    match power_of_ten(s) {
        Some(("1", power)) => format!("10^{{{power}}}"),
        Some((mantissa, power)) => format!("{mantissa} \\times 10^{{{power}}}"),
        None => s.to_string(),
    }
}

/// Text with each negative number's hyphen written as a minus sign, as a textbook sets it:
/// `slope -0.67` is `slope −0.67`; a hyphen between words or numbers (`Dormand-Prince`, `3-4`)
/// stays.
pub fn minus_signs(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    for (i, &c) in chars.iter().enumerate() {
        let before = i == 0 || chars[i - 1].is_whitespace() || "([{,;=/:".contains(chars[i - 1]);
        let after = chars.get(i + 1).is_some_and(|n| n.is_ascii_digit())
            || (chars.get(i + 1) == Some(&'.')
                && chars.get(i + 2).is_some_and(|n| n.is_ascii_digit()));
        out.push(if c == '-' && before && after {
            '−'
        } else {
            c
        });
    }
    out
}

#[cfg(test)]
mod latex_number_tests {
    use super::{latex_number, sci, short, text_number};

    #[test]
    fn negative_numbers_in_text_take_a_minus_sign() {
        assert_eq!(
            super::minus_signs("slope -0.67, at (-1, -.5); Dormand-Prince, 3-4, x=-2"),
            "slope −0.67, at (−1, −.5); Dormand-Prince, 3-4, x=−2"
        );
    }

    #[test]
    fn text_numbers_use_powers_of_ten() {
        assert_eq!(sci(8.34e-16), "8.3×10⁻¹⁶");
        assert_eq!(sci(1.0), "1.0");
        assert_eq!(sci(123.0), "1.2×10²");
        assert_eq!(sci(0.0), "0");
        assert_eq!(short(1e-10), "10⁻¹⁰");
        assert_eq!(short(5e-9), "5×10⁻⁹");
        crate::base::assert_each(
            text_number,
            &[
                ("-2.5e+07", "-2.5×10⁷"),
                ("0.25", "0.25"),
                ("NaN", "NaN"),
                // Every digit has its superscript.
                ("1e-1234567890", "10⁻¹²³⁴⁵⁶⁷⁸⁹⁰"),
            ],
        );
    }

    #[test]
    fn exponents_become_powers_of_ten() {
        crate::base::assert_each(
            latex_number,
            &[
                ("4.6875e-6", "4.6875 \\times 10^{-6}"),
                ("-1.5e+07", "-1.5 \\times 10^{7}"),
                ("1e-12", "10^{-12}"),
                ("0.25", "0.25"),
                ("-3", "-3"),
            ],
        );
    }
}

/// A unit's text, already escaped for markup, with its powers raised: `kg m^2/s` as
/// `kg m<sup>2</sup>/s`, a power's minus as −, a `*` as a space.
pub fn unit_powers(escaped: &str) -> String {
    let escaped = escaped.replace('*', " ");
    let mut out = String::new();
    let mut rest = escaped.as_str();
    while let Some(i) = rest.find('^') {
        out.push_str(&rest[..i]);
        let power: String = rest[i + 1..]
            .chars()
            .take_while(|c| c.is_ascii_digit() || *c == '-')
            .collect();
        out.push_str(&format!("<sup>{}</sup>", power.replace('-', "−")));
        rest = &rest[i + 1 + power.len()..];
    }
    out.push_str(rest);
    out
}
