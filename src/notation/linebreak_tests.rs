//! The line breaker's cuts, checked on formulas built to need them: each expected piece is
//! written in LaTeX and read by the one reader, so a piece is compared as a tree.

use super::latex::{Node, Tex};
use super::linebreak::*;
use pulldown_latex::event::{Dimension, DimensionUnit, EnvironmentFlow, Grouping};

fn tex(s: &str) -> Vec<Node> {
    Tex::read(s).unwrap_or_else(|e| panic!("{s}: {e}")).nodes
}

fn cut(formula: &str, limit: f32) -> Vec<Vec<Node>> {
    pieces(&tex(formula), limit)
}

fn phone(formula: &str) -> Vec<Vec<Node>> {
    phone_pieces(&tex(formula))
}

fn contains(hay: &[Node], needle: &[Node]) -> bool {
    hay.windows(needle.len()).any(|w| w == needle)
}

/// The tables of stacked cells anywhere in the nodes.
fn aligned(nodes: &[Node]) -> Vec<Vec<Node>> {
    let mut out = Vec::new();
    for n in nodes {
        match n {
            Node::Group(Grouping::Aligned, body) => out.push(body.clone()),
            Node::Group(_, v) | Node::Visual(_, v) | Node::Script { parts: v, .. } => {
                out.extend(aligned(v))
            }
            _ => {}
        }
    }
    out
}

/// `x_{0} + x_{1} + …`, `n` terms: a sum too long for one line.
fn sum_of(x: &str, n: usize) -> String {
    let terms: Vec<String> = (0..n).map(|k| format!("{x}_{{{k}}}")).collect();
    terms.join(" + ")
}

#[test]
fn a_short_formula_is_one_piece() {
    assert_eq!(cut("a + b = c", LINE), vec![tex("a + b = c")]);
}

#[test]
fn a_long_sum_is_cut_before_its_operators_and_loses_nothing() {
    let terms: Vec<String> = (0..30).map(|k| format!("a_{{{k}}} x^{{2}}")).collect();
    let formula = format!("T = {}", terms.join(" - "));
    let p = cut(&formula, LINE);
    assert_eq!(p.len(), 31, "{p:?}");
    assert_eq!(p[0], tex("T"));
    assert_eq!(p[1], tex("= a_{0} x^{2}"));
    assert_eq!(p[2], tex("- a_{1} x^{2}"));
    assert_eq!(p.concat(), tex(&formula));
}

#[test]
fn a_leading_minus_and_a_minus_in_an_exponent_are_not_cuts() {
    let s = segments(&tex("-a + b^{-1} - c"));
    assert_eq!(s.len(), 3);
    assert_eq!(s[0], tex("-a"));
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
    let p = cut(&formula, LINE);
    assert_eq!(p[0], tex("L"));
    assert_eq!(p[1], tex("= \\frac{m}{3}\\Bigl(\\frac{x_{0}}{2}"));
    assert_eq!(p.last().unwrap(), &tex("+ \\frac{x_{19}}{2}\\Bigr)^{2}"));
    assert_eq!(p.len(), 21);
}

#[test]
fn a_long_numerator_leaves_its_denominator_in_front() {
    let formula = format!("\\frac{{{}}}{{12}}", sum_of("b", 20));
    let p = cut(&formula, LINE);
    assert_eq!(p[0], tex("\\frac{1}{12}\\bigl(b_{0}"));
    assert_eq!(p.last().unwrap(), &tex("+ b_{19}\\bigr)"));
}

#[test]
fn a_long_square_root_becomes_a_power_of_a_half() {
    let p = cut(&format!("k = \\sqrt{{{}}}", sum_of("c", 30)), LINE);
    assert_eq!(p[1], tex("= \\bigl(c_{0}"));
    assert_eq!(p.last().unwrap(), &tex("+ c_{29}\\bigr)^{1/2}"));
}

#[test]
fn a_root_of_a_factored_sum_opens_both_brackets() {
    let formula = format!(
        "k = \\sqrt{{\\frac{{1}}{{12}}\\left({}\\right)}}",
        sum_of("c", 30)
    );
    let p = cut(&formula, LINE);
    assert_eq!(p[1], tex("= \\Bigl(\\frac{1}{12}\\bigl(c_{0}"));
    assert_eq!(p.last().unwrap(), &tex("+ c_{29}\\bigr)\\Bigr)^{1/2}"));
}

#[test]
fn a_long_denominator_becomes_a_power_of_minus_one() {
    let p = cut(&format!("\\frac{{12}}{{{}}}", sum_of("d", 30)), LINE);
    assert_eq!(p[0], tex("12\\bigl(d_{0}"));
    assert_eq!(p.last().unwrap(), &tex("+ d_{29}\\bigr)^{-1}"));
}

#[test]
fn a_long_root_in_a_denominator_gets_one_power_at_a_time() {
    // Found by the fuzz suite: (s)^{1/2}^{-1} is a double superscript, which no renderer takes.
    let p = cut(
        &format!("\\frac{{1}}{{\\sqrt{{{}}}}}", sum_of("d", 30)),
        LINE,
    );
    let all = p.concat();
    // The root is a power of its own, inside the bracket that is inverted.
    assert!(all.starts_with(&tex("\\bigl(\\bigl(d_{0}")), "{p:?}");
    assert!(
        all.ends_with(&tex("+ d_{29}\\bigr)^{1/2}\\bigr)^{-1}")),
        "{p:?}"
    );
    // A long product below the line is inverted whole, not its last factor alone (the erratum
    // of eq (81) read (2π)(Iω)·(Iω)^{-1}).
    let factors: Vec<String> = (0..30).map(|k| format!("d_{{{k}}}")).collect();
    let p = cut(&format!("\\frac{{1}}{{{}}}", factors.join(" ")), LINE);
    assert_eq!(
        p.concat(),
        tex(&format!("\\left({}\\right)^{{-1}}", factors.join(" "))),
        "{p:?}"
    );
}

#[test]
fn a_matrix_too_wide_to_stack_becomes_the_tuple_of_its_rows() {
    let cell =
        "f_{1} g_{2} \\cos\\left(\\chi\\right) \\cos\\left(\\psi\\right) \\sin\\left(\\psi\\right)";
    let long = format!("{cell} - {cell} + {cell}");
    let row = format!("{long} & {long} & {long}");
    let formula = format!("\\begin{{pmatrix}}{row} \\\\ {row} \\\\ {row}\\end{{pmatrix}}");
    let p = cut(&formula, LINE);
    assert!(p[0].starts_with(&tex("\\bigl(\\bigl(f_{1}")), "{p:?}");
    assert!(p.last().unwrap().ends_with(&tex("\\bigr)\\bigr)")), "{p:?}");
    assert_eq!(
        p.iter().filter(|s| s.ends_with(&tex("\\bigr),"))).count(),
        2,
        "{p:?}"
    );
    for piece in &p {
        assert!(width(piece) <= LINE, "{piece:?}");
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
    let p = cut(&formula, LINE);
    assert_eq!(p.len(), 1, "{p:?}");
    let tables = aligned(&p[0]);
    assert_eq!(tables.len(), 3, "{p:?}");
    let mut first = vec![Node::Flow(EnvironmentFlow::Alignment)];
    first.extend(tex("m a_{0}"));
    assert!(tables[0].starts_with(&first), "{:?}", tables[0]);
    // Each later line of a cell starts aligned, a quad in, with its operator.
    let mut later = vec![
        Node::Flow(EnvironmentFlow::NewLine {
            spacing: None,
            horizontal_lines: Box::new([]),
        }),
        Node::Flow(EnvironmentFlow::Alignment),
        Node::Space(Some(Dimension::new(1.0, DimensionUnit::Em))),
    ];
    later.extend(tex("+ m"));
    assert!(contains(&tables[0], &later), "{:?}", tables[0]);
    assert!(width(&p[0]) <= LINE, "{}", width(&p[0]));
}

#[test]
fn a_sum_over_a_wider_sum_keeps_its_numerator_in_brackets() {
    // (a_0 + … + a_5)(b_0 + … + b_11)^{-1}: without the first bracket it would read
    // a_0 + … + a_5 (b…)^{-1}, another formula (found on a phone, in the tumbling box).
    let num: Vec<String> = (0..6).map(|k| format!("a_{{{k}}}")).collect();
    let den: Vec<String> = (0..12).map(|k| format!("b_{{{k}}}")).collect();
    let formula = format!("\\frac{{{}}}{{{}}}", num.join(" + "), den.join(" + "));
    for p in [cut(&formula, 20.0), phone(&formula)] {
        let all = p.concat();
        let whole = tex(&format!("\\left({}\\right)", num.join(" + ")));
        let opened = all.starts_with(&tex("\\bigl(a_{0}")) && contains(&all, &tex("a_{5}\\bigr)"));
        assert!(all.starts_with(&whole) || opened, "{p:?}");
        assert!(all.ends_with(&tex("b_{11}\\bigr)^{-1}")), "{p:?}");
    }
}

#[test]
fn on_a_phone_a_long_factor_before_a_bracket_is_a_piece_of_its_own() {
    // The sleeping cone's potential: 1/(a long denominator) before the numerator's bracket.
    let formula = "U = \\frac{3 M \\left(2 \\omega_{3}^{2} R^{4} - 2 \\omega_{3}^{2} R^{4} \\cos\\left(\\theta\\right) + 20 g h^{3} \\cos\\left(\\theta\\right) + 5 g h R^{2} \\cos\\left(\\theta\\right)\\right)}{20 R^{2} + 20 R^{2} \\cos\\left(\\theta\\right) + 80 h^{2} + 80 h^{2} \\cos\\left(\\theta\\right)}";
    let p = phone(formula);
    for piece in &p {
        assert!(width(piece) <= PHONE, "{piece:?} in {p:?}");
    }
    assert_eq!(p[0], tex("U"));
    assert!(p[1].starts_with(&tex("= \\bigl(20 R^{2}")), "{p:?}");
    let k = p
        .iter()
        .position(|s| s.ends_with(&tex("\\bigr)^{-1}3 M")))
        .unwrap();
    assert!(
        p[k + 1].starts_with(&tex("\\bigl(2 \\omega_{3}^{2}")),
        "{p:?}"
    );
    // On paper the same formula is no different: it fits the line.
    assert_eq!(cut(formula, LINE), vec![tex(formula)]);
}

#[test]
fn on_a_phone_a_sentence_breaks_between_its_words() {
    let formula = "I_{3} < I_{1}:\\;\\text{positive for some choices and negative for others}";
    let p = phone(formula);
    assert_eq!(p[0], tex("I_{3}"));
    assert_eq!(p[1], tex("< I_{1}:\\;\\text{positive}"));
    assert_eq!(p.last().unwrap(), &tex("\\text{others}"));
    assert_eq!(p.len(), 9, "{p:?}");
    assert_eq!(cut(formula, LINE), vec![tex(formula)]);
}

#[test]
fn on_a_phone_no_piece_is_wider_than_it_may_be_scaled_to() {
    // The widest formulas of tests/course, each as the derivation prints it.
    for formula in [
        "I_{xy} = \\int_{0}^{R}\\int_{0}^{\\frac{\\pi}{2}}\\int_{0}^{2\\pi}\\frac{3 M r^{4} \\cos\\left(\\phi\\right) \\sin\\left(\\phi\\right) \\sin\\left(\\theta\\right) \\left(-1 + \\,{\\cos}^{2}\\left(\\theta\\right)\\right)}{2 \\pi R^{3}}\\,d\\phi\\,d\\theta\\,dr = 0",
        "\\Omega = \\sqrt{\\frac{60 M}{\\left(20 R^{2} + 80 h^{2}\\right) \\left(3 M R^{2} + 12 M h^{2}\\right)} \\left(\\omega_{3}^{2} R^{4} - 20 g h^{3} - 5 g h R^{2}\\right)}",
        "\\mathrm{turn}_{1} = 2 \\sqrt{\\frac{1159339}{8661249}} \\cos\\left(\\frac{\\arccos\\left(\\frac{5677487248}{127450279035 \\frac{1159339}{8661249}^{\\frac{3}{2}}}\\right) - 4 \\pi}{3}\\right) + \\frac{3440}{2943}",
        "\\overleftrightarrow{I} = \\begin{pmatrix}\\frac{m}{3} \\left(d^{2} + h^{2}\\right) & -\\frac{h m w}{4} & -\\frac{d m w}{4} \\\\ -\\frac{h m w}{4} & \\frac{m}{3} \\left(d^{2} + w^{2}\\right) & -\\frac{d h m}{4} \\\\ -\\frac{d m w}{4} & -\\frac{d h m}{4} & \\frac{m}{3} \\left(h^{2} + w^{2}\\right)\\end{pmatrix}",
    ] {
        let p = phone(formula);
        assert!(p.len() > 1 || formula.contains("pmatrix"), "{p:?}");
        for piece in &p {
            assert!(phone_scale(width(piece)) >= SMALLEST, "{piece:?}");
        }
    }
}

/// A product with nothing left to open is cut between its factors, each later piece starting
/// with ⋅; never between a function and its argument, nor before or inside a differential.
#[test]
fn a_long_product_is_cut_between_its_factors() {
    let formula = "I_{xz} = \\int_{0}^{2\\pi}\\frac{M R^{2} \\cos\\left(\\alpha\\right) \\sin\\left(\\alpha\\right) \\,{\\cos}^{2}\\left(\\theta\\right)}{2 \\pi}\\,d\\theta = \\frac{M R^{2}}{2}";
    let p = phone(formula);
    assert_eq!(
        p,
        vec![
            tex("I_{xz}"),
            tex(
                "= \\int_{0}^{2\\pi}\\frac{1}{2 \\pi} M R^{2} \\cos\\left(\\alpha\\right) \\sin\\left(\\alpha\\right) \\,"
            ),
            tex("\\cdot {\\cos}^{2}\\left(\\theta\\right)\\,d\\theta"),
            tex("= \\frac{M R^{2}}{2}"),
        ],
        "{p:?}"
    );
    for piece in &p {
        assert!(width(piece) <= PHONE, "{piece:?}");
    }
}
