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
    use crate::document::words::claim_lead as lead;
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
        // The author's I₃ω₃ first, I₃ being a step's result.
        "a = I_{3} \\omega_{3} = \\frac{3 M R^{2} \\omega_{3}}{10}",
    );
    let (page, view) = page_and_view("dynamics/13-atwood.toml");
    assert_line(
        line(&view, &page, "acc", 2),
        "T = \\frac{2 m_{1} m_{2} g}{m_{1} + m_{2}}",
    );
    let (page, view) = page_and_view("dynamics/03-double-pendulum.toml");
    // A linearised equation of motion: m l divided out, the accelerations first, the
    // parameters before the coordinates and rates.
    assert_line(
        line(&view, &page, "small", 0),
        "2 l \\ddot{\\phi_{1}} + l \\ddot{\\phi_{2}} + 2 g \\phi_{1} = 0",
    );
    let (page, view) = page_and_view("dynamics/01-physical-pendulum.toml");
    assert_line(
        line(&view, &page, "p_phi", 0),
        "p_{\\phi} = \\frac{M L^{2} \\dot{\\phi}}{3}",
    );
}

/// The sine and cosine of φₖ as the pages set them.
fn sin_cos(f: &str, k: u8) -> String {
    format!("\\{f}\\left(\\phi_{{{k}}}\\right)")
}

#[test]
fn an_authors_energies_print_as_written_with_squares_of_differences_kept() {
    let (page, view) = page_and_view("dynamics/22-coupled-pendulums.toml");
    let (s1, s2, c1, c2) = (
        sin_cos("sin", 1),
        sin_cos("sin", 2),
        sin_cos("cos", 1),
        sin_cos("cos", 2),
    );
    let spring = format!("\\frac{{k l^{{2}} \\left({s1} - {s2}\\right)^{{2}}}}{{2}}");
    let gravity = format!("m g l \\left({c1} + {c2}\\right)");
    // Not l/2 (2kl − 2mg cos φ₁ − … − kl cos²φ₁ − …), the engine's expansion with 1 − cos².
    assert_line(
        line(&view, &page, "V", 0),
        &format!("V = {spring} - {gravity}"),
    );
    // The Lagrangian: T − V, then T and V put in as the page states them.
    let kinetic = "\\frac{m l^{2} \\left(\\dot{\\phi_{1}}^{2} + \\dot{\\phi_{2}}^{2}\\right)}{2}";
    assert_line(
        line(&view, &page, "Lag", 0),
        &format!("\\mathcal{{L}} = T - V = {kinetic} - {spring} + {gravity}"),
    );
}

#[test]
fn an_equation_of_motion_prints_one_term_per_force() {
    let (page, view) = page_and_view("dynamics/22-coupled-pendulums.toml");
    // The bob's inertia, gravity, the spring, l divided out: not l(mg sin φ₁ + kl cos φ₁ sin φ₁
    // − …), nor mgl sin φ₁ + … + ml²φ̈₁ with the acceleration last.
    assert_line(
        line(&view, &page, "eom", 0),
        &format!(
            "m l \\ddot{{\\phi_{{1}}}} + m g {} + k l {} \\left({} - {}\\right) = 0",
            sin_cos("sin", 1),
            sin_cos("cos", 1),
            sin_cos("sin", 1),
            sin_cos("sin", 2)
        ),
    );
    // Linearised: m l φ̈₁ + m g φ₁ + k l φ₁ − k l φ₂ = 0.
    assert_line(
        line(&view, &page, "small", 0),
        "m l \\ddot{\\phi_{1}} + m g \\phi_{1} + k l \\phi_{1} - k l \\phi_{2} = 0",
    );
}

#[test]
fn an_equation_of_motion_collects_each_acceleration_and_leads_with_it() {
    // A ball rolling in a bowl: 7(R − r)φ̈ + 5g sin φ = 0, not 1/5 m (R − r)(5g sin φ + 7Rφ̈ −
    // 7rφ̈) = 0.
    let (page, view) = page_and_view("problems/11-ball-in-bowl.toml");
    assert_line(
        line(&view, &page, "eom", 0),
        "7 \\left(R - r\\right) \\ddot{\\phi} + 5 g \\sin\\left(\\phi\\right) = 0",
    );
}

#[test]
fn a_beat_period_prints_the_difference_of_the_named_modes() {
    let (page, view) = page_and_view("dynamics/22-coupled-pendulums.toml");
    // 2π/(Ω₂ − Ω₁) as the author wrote it, then each mode put in as its line prints it; not
    // 2πl/(√((mg + 2kl)lm)/m − √(gl)).
    assert_line(
        line(&view, &page, "beat", 0),
        "T_{\\mathrm{beat}} = \\frac{2 \\pi}{\\Omega_{2} - \\Omega_{1}} = \\frac{2 \\pi}{\\sqrt{\\frac{m g + 2 k l}{m l}} - \\sqrt{\\frac{g}{l}}}",
    );
}

#[test]
fn a_lagrangian_with_a_moment_put_in_collects_its_kinetic_terms() {
    let (page, view) = page_and_view("problems/11-ball-in-bowl.toml");
    // ½m(R − r)²φ̇² + ½I((R − r)φ̇/r)² with I = 2mr²/5: one kinetic term, 7/10 of it; not
    // m(7Rφ̇² + 10g cos φ − 7rφ̇²)(R − r)/10.
    let printed = line(&view, &page, "Lag", 0);
    let value = "\\frac{7 m \\left(R - r\\right)^{2} \\dot{\\phi}^{2}}{10} + m g \\left(R - r\\right) \\cos\\left(\\phi\\right)";
    let written = "\\frac{m \\left(R - r\\right)^{2} \\dot{\\phi}^{2}}{2} + \\frac{I \\left(R - r\\right)^{2} \\dot{\\phi}^{2}}{2 r^{2}} + m g \\left(R - r\\right) \\cos\\left(\\phi\\right)";
    assert_line(printed, &format!("L = {written} = {value}"));
}

#[test]
fn a_denominator_is_led_by_a_positive_term() {
    let (page, view) = page_and_view("dynamics/19-block-on-wedge.toml");
    let (cos, sin) = ("\\cos\\left(\\alpha\\right)", "\\sin\\left(\\alpha\\right)");
    // A power of a function is set after a thin space, as the printer sets sin²α.
    let below = "M + m \\, \\sin^{2}\\left(\\alpha\\right)";
    // Not m g cos α sin α/(−M − m sin²α): the sign taken out of the denominator.
    assert_line(
        line(&view, &page, "acc", 0),
        &format!("\\ddot{{X}} = -\\frac{{m g {cos} {sin}}}{{{below}}}"),
    );
    assert_line(
        line(&view, &page, "acc", 1),
        // Both signs gone: not −g sin α (M + m)/(−M − m sin²α).
        &format!("\\ddot{{s}} = \\frac{{g {sin} \\left(M + m\\right)}}{{{below}}}"),
    );
}

/// A step's `gives` that cites no equation of the notes is labelled by none: its claim's `eq`
/// is the step's name (`p_psi`), which the page printed as "(p_psi)".
#[test]
fn a_gives_without_an_equation_prints_no_step_name() {
    let (page, view) = page_and_view("dynamics/04-heavy-top.toml");
    let steps: Vec<&str> = page
        .steps
        .iter()
        .filter_map(|s| s.author.as_deref())
        .collect();
    assert!(steps.contains(&"p_psi"), "{steps:?}");
    let from_steps: Vec<&ClaimView> = view
        .claims
        .iter()
        .zip(&page.claims)
        .filter(|(_, c)| c.step.is_some())
        .map(|(v, _)| v)
        .collect();
    assert!(!from_steps.is_empty());
    for c in from_steps {
        assert!(!steps.contains(&c.eq.as_str()), "labelled ({})", c.eq);
    }
}
