//! The line breaker's cuts, checked on formulas built to need them.

use super::linebreak::*;

#[test]
fn the_tree_writes_back_what_it_read() {
    for s in [
        "\\frac{M R^{2}}{2}",
        "\\left.\\frac{d\\vec L}{dt}\\right|_{\\mathrm{body}} + \\vec\\omega\\times\\vec L",
        "\\overleftrightarrow{I} = \\begin{pmatrix}1 & 0 \\\\ 0 & 1\\end{pmatrix}",
        "\\,{\\cos}^{2}\\left(\\alpha\\right)",
    ] {
        assert_eq!(latex(&tree(s)), s);
    }
}

#[test]
fn a_short_formula_is_one_piece() {
    assert_eq!(pieces("a + b = c", LINE), vec!["a + b = c"]);
}

#[test]
fn a_long_sum_is_cut_before_its_operators_and_loses_nothing() {
    let terms: Vec<String> = (0..30).map(|k| format!("a_{{{k}}} x^{{2}}")).collect();
    let formula = format!("T = {}", terms.join(" - "));
    let p = pieces(&formula, LINE);
    assert_eq!(p.len(), 31, "{p:?}");
    assert_eq!(p[0], "T");
    assert_eq!(p[1], "= a_{0} x^{2}");
    assert_eq!(p[2], "- a_{1} x^{2}");
    assert_eq!(p.join(" "), formula);
}

#[test]
fn a_leading_minus_and_a_minus_in_an_exponent_are_not_cuts() {
    let s = segments(&tree("-a + b^{-1} - c"));
    assert_eq!(s.len(), 3);
    assert_eq!(latex(&s[0]).trim(), "-a");
}

#[test]
fn a_long_parenthesised_sum_opens_into_big_parentheses() {
    let terms: Vec<String> = (0..20)
        .map(|k| format!("\\frac{{x_{{{k}}}}}{{2}}"))
        .collect();
    let formula = format!(
        "L = \\frac{{m}}{{3}}\\left({}\\right)^{{2}}",
        terms.join(" + ")
    );
    let p = pieces(&formula, LINE);
    assert_eq!(p[0], "L");
    assert_eq!(p[1], "= \\frac{m}{3}\\Bigl(\\frac{x_{0}}{2}");
    assert_eq!(p.last().unwrap(), "+ \\frac{x_{19}}{2}\\Bigr)^{2}");
    assert_eq!(p.len(), 21);
}

#[test]
fn a_long_numerator_leaves_its_denominator_in_front() {
    let terms: Vec<String> = (0..20).map(|k| format!("b_{{{k}}}")).collect();
    let formula = format!("\\frac{{{}}}{{12}}", terms.join(" + "));
    let p = pieces(&formula, LINE);
    assert_eq!(p[0], "\\frac{1}{12}\\bigl(b_{0}");
    assert_eq!(p.last().unwrap(), "+ b_{19}\\bigr)");
}

#[test]
fn a_long_square_root_becomes_a_power_of_a_half() {
    let terms: Vec<String> = (0..30).map(|k| format!("c_{{{k}}}")).collect();
    let p = pieces(&format!("k = \\sqrt{{{}}}", terms.join(" + ")), LINE);
    assert_eq!(p[1], "= \\bigl(c_{0}");
    assert_eq!(p.last().unwrap(), "+ c_{29}\\bigr)^{1/2}");
}

#[test]
fn a_root_of_a_factored_sum_opens_both_brackets() {
    let terms: Vec<String> = (0..30).map(|k| format!("c_{{{k}}}")).collect();
    let formula = format!(
        "k = \\sqrt{{\\frac{{1}}{{12}}\\left({}\\right)}}",
        terms.join(" + ")
    );
    let p = pieces(&formula, LINE);
    assert_eq!(p[1], "= \\Bigl(\\frac{1}{12}\\bigl(c_{0}");
    assert_eq!(p.last().unwrap(), "+ c_{29}\\bigr)\\Bigr)^{1/2}");
}

#[test]
fn a_long_denominator_becomes_a_power_of_minus_one() {
    let terms: Vec<String> = (0..30).map(|k| format!("d_{{{k}}}")).collect();
    let p = pieces(&format!("\\frac{{12}}{{{}}}", terms.join(" + ")), LINE);
    assert_eq!(p[0], "12\\bigl(d_{0}");
    assert_eq!(p.last().unwrap(), "+ d_{29}\\bigr)^{-1}");
}

#[test]
fn a_long_root_in_a_denominator_gets_one_power_at_a_time() {
    // Found by the fuzz suite: (s)^{1/2}^{-1} is a double superscript, which no renderer takes.
    let terms: Vec<String> = (0..30).map(|k| format!("d_{{{k}}}")).collect();
    let p = pieces(
        &format!("\\frac{{1}}{{\\sqrt{{{}}}}}", terms.join(" + ")),
        LINE,
    );
    let all = p.join(" ");
    assert!(!all.contains("^{1/2}^{-1}"), "{p:?}");
    assert!(all.ends_with("\\bigr)^{-1}"), "{p:?}");
    // A long product below the line is inverted whole, not its last factor alone (the erratum
    // of eq (81) read (2π)(Iω)·(Iω)^{-1}).
    let factors: Vec<String> = (0..30).map(|k| format!("d_{{{k}}}")).collect();
    let p = pieces(&format!("\\frac{{1}}{{{}}}", factors.join(" ")), LINE);
    let all = p.join(" ");
    assert!(all.starts_with("\\left(d_{0}"), "{p:?}");
    assert!(all.ends_with("d_{29}\\right)^{-1}"), "{p:?}");
}

#[test]
fn a_matrix_too_wide_to_stack_becomes_the_tuple_of_its_rows() {
    let cell =
        "f_{1} g_{2} \\cos\\left(\\chi\\right) \\cos\\left(\\psi\\right) \\sin\\left(\\psi\\right)";
    let long = format!("{cell} - {cell} + {cell}");
    let row = format!("{long} & {long} & {long}");
    let formula = format!("\\begin{{pmatrix}}{row} \\\\ {row} \\\\ {row}\\end{{pmatrix}}");
    let p = pieces(&formula, LINE);
    assert!(p[0].starts_with("\\bigl(\\bigl(f_{1}"), "{p:?}");
    assert!(p.last().unwrap().ends_with("\\bigr)\\bigr)"), "{p:?}");
    assert!(
        p.iter().filter(|s| s.ends_with("\\bigr),")).count() == 2,
        "{p:?}"
    );
    for piece in &p {
        assert!(width(&tree(piece)) <= LINE, "{piece}");
    }
}

#[test]
fn a_wide_matrix_stacks_its_long_cells() {
    let long = (0..8)
        .map(|k| format!("m a_{{{k}}}"))
        .collect::<Vec<_>>()
        .join(" + ");
    let formula = format!(
        "I = \\begin{{pmatrix}}{long} & {long} & 0 \\\\ 0 & {long} & 0 \\\\ 0 & 0 & 1\\end{{pmatrix}}"
    );
    let p = pieces(&formula, LINE);
    assert_eq!(p.len(), 1, "{p:?}");
    assert!(p[0].contains("\\begin{aligned}&m a_{0}"), "{}", p[0]);
    assert!(p[0].contains("\\\\ &\\quad + m a_{"), "{}", p[0]);
    assert!(width(&tree(&p[0])) <= LINE, "{}", width(&tree(&p[0])));
}
