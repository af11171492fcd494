//! Claims as a student reads them, on scenes of tests/course: a box prints the claim's
//! quantity on its left and the derived side in the form the page prints the result; a claim
//! that agrees prints its formula. Each printed side is compared, as a tree, with the form a
//! textbook writes (its MathML is made from the same tree, so equal MathML is an equal tree).

use super::{ClaimView, math};
use crate::notation::Tex;
use crate::scene::Scene;
use std::path::Path;

/// The page view of a scene of tests/course.
fn view(file: &str) -> super::PageView {
    page_and_view(file).1
}

fn claim<'a>(view: &'a super::PageView, eq: &str) -> &'a ClaimView {
    view.claims
        .iter()
        .find(|c| c.eq == eq)
        .unwrap_or_else(|| panic!("no claim ({eq}) on {}", view.id))
}

/// `printed` is the textbook's `latex`, tree for tree.
fn assert_prints(printed: &str, latex: &str) {
    let textbook = math::inline(&Tex::read(latex).unwrap()).unwrap();
    assert_eq!(printed, textbook, "not the textbook's {latex}");
}

#[test]
fn a_box_on_a_steps_result_names_it_as_the_step_does() {
    let atwood = view("dynamics/13-atwood.toml");
    let tension = claim(&atwood, "9.3");
    assert_eq!(tension.role, "mistake");
    // The solve's third result is T on its line; the box says so on both sides.
    assert_prints(&tension.quantity, "T");
    assert_prints(&tension.notes, "m_{1} g");
    // In the order the scene declares m₁, m₂, g, as a textbook writes it.
    assert_prints(&tension.derived, "\\frac{2 m_{1} m_{2} g}{m_{1} + m_{2}}");
}

#[test]
fn a_box_on_a_formula_of_results_prints_it_in_a_textbooks_form() {
    let pendulum = view("dynamics/01-physical-pendulum.toml");
    let period = claim(&pendulum, "6.6");
    assert_prints(&period.quantity, "\\frac{2 \\pi}{\\Omega}");
    assert_prints(&period.notes, "2 \\pi \\sqrt{\\frac{L}{g}}");
    // Not 2π/√(3g/(2L)), the raw substitution of Ω.
    assert_prints(&period.derived, "2 \\pi \\sqrt{\\frac{2 L}{3 g}}");
}

#[test]
fn an_agreeing_claim_prints_its_quantity_and_the_notes_form() {
    let rolling = view("dynamics/02-rolling-cylinder.toml");
    let a = claim(&rolling, "7.2");
    assert_eq!(a.verdict, "agrees");
    assert_prints(&a.quantity, "a");
    assert_prints(&a.notes, "\\frac{2 g \\sin\\left(\\alpha\\right)}{3}");
    let lead = a.lead_html.as_deref().unwrap();
    assert!(lead.starts_with("The solid cylinder") && !lead.ends_with('.'));
    let atwood = view("dynamics/13-atwood.toml");
    // A sum of results the page states, by the symbols of their lines.
    let opposite = claim(&atwood, "9.4");
    assert_prints(&opposite.quantity, "\\ddot{x_{1}} + \\ddot{x_{2}}");
    assert_prints(&opposite.notes, "0");
}

#[test]
fn a_statement_that_writes_its_equation_is_not_followed_by_it_again() {
    use super::claim_view::lead;
    assert_eq!(
        lead("the tension in the string.").as_deref(),
        Some("The tension in the string")
    );
    assert_eq!(lead("$\\beta^2 = x$: the linearised equations"), None);
    assert_eq!(
        lead("The tension $T$ in the string").as_deref(),
        Some("The tension $T$ in the string")
    );
}

/// The formula of the line stating the `k`-th result of the author's step `name`.
fn line<'a>(
    view: &'a super::PageView,
    page: &crate::document::Page,
    name: &str,
    k: usize,
) -> &'a str {
    let i = page
        .steps
        .iter()
        .enumerate()
        .filter(|(_, s)| s.author.as_deref() == Some(name))
        .nth(k)
        .unwrap_or_else(|| panic!("no line {k} of {name}"))
        .0;
    &view.steps[i].math
}

fn page_and_view(file: &str) -> (crate::document::Page, super::PageView) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/course")
        .join(file);
    let text = std::fs::read_to_string(&path).unwrap();
    let report = crate::pipeline::run_scene(Scene::parse(&text, &path).unwrap(), None).unwrap();
    let page = crate::document::page(&report, None, None);
    let view = super::page_view(&page, false).unwrap();
    (page, view)
}

/// A derived line is the textbook's `latex`, tree for tree.
fn assert_line(printed: &str, latex: &str) {
    let textbook = math::block(&Tex::read(latex).unwrap()).unwrap();
    assert_eq!(printed, textbook, "not the textbook's {latex}");
}

#[test]
fn derived_products_take_the_order_the_scene_declares() {
    // The engine returns 3ω₃MR²/10, 2g m₁m₂/(m₁ + m₂), g l m: the scenes declare M, R, …, ω₃;
    // m₁, m₂, g; m, l, g.
    let (page, view) = page_and_view("dynamics/09-sleeping-cone.toml");
    assert_line(
        line(&view, &page, "a", 0),
        "a = \\frac{3 M R^{2} \\omega_{3}}{10}",
    );
    let (page, view) = page_and_view("dynamics/13-atwood.toml");
    assert_line(
        line(&view, &page, "acc", 2),
        "T = \\frac{2 m_{1} m_{2} g}{m_{1} + m_{2}}",
    );
    let (page, view) = page_and_view("dynamics/03-double-pendulum.toml");
    // A linearised equation of motion: the parameters before the coordinates and rates.
    assert_line(
        line(&view, &page, "small", 0),
        "m l \\left(2 g \\phi_{1} + 2 l \\ddot{\\phi_{1}} + l \\ddot{\\phi_{2}}\\right) = 0",
    );
    let (page, view) = page_and_view("dynamics/01-physical-pendulum.toml");
    assert_line(
        line(&view, &page, "p_phi", 0),
        "p_{\\phi} = \\frac{M L^{2} \\dot{\\phi}}{3}",
    );
}
