use super::*;
use crate::model::prose::Piece;
use std::path::Path;

fn hoop() -> SceneReport {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("lectures/lecture-3-4/06-hoop.toml");
    let scene = crate::scene::load_all(&[path]).unwrap().remove(0);
    crate::pipeline::run_scene(scene, None).unwrap()
}

/// The page, `derive`, `derive --json` and the HTML view all print the one `Page`: a change made
/// to it (and not to the report) reaches each of them.
#[test]
fn every_printer_reads_the_page_not_the_report() {
    let r = hoop();
    let mut page = page(&r, None, None);
    assert!(
        !page.steps.is_empty() && !page.claims.is_empty(),
        "{page:?}"
    );
    page.steps[0].title = Prose::from("STEP-MARK".to_string());
    page.steps[0].why = Prose::from("WHY-MARK".to_string());
    page.claims[0].statement = "CLAIM-MARK".into();
    page.title = "TITLE-MARK".into();
    let text = crate::report::derivation_text(&page);
    let json = crate::report::scene_json(&page).to_string();
    let view = crate::render::html::page_view(&page, false).unwrap();
    let html = serde_json::to_string(&view).unwrap();
    for mark in ["STEP-MARK", "WHY-MARK", "CLAIM-MARK", "TITLE-MARK"] {
        assert!(text.contains(mark), "derive text lacks {mark}");
        assert!(json.contains(mark), "derive --json lacks {mark}");
        assert!(html.contains(mark), "the page view lacks {mark}");
    }
}

#[test]
fn a_cited_step_gives_its_reason_after_the_citation() {
    let step = Step {
        title: Prose::from("t".to_string()),
        statement: Formula::parse("x = 1", &[]),
        why: Prose::from("expand".to_string()),
        key: "k".into(),
        citation: Some("eq (51)".into()),
        check: None,
        author: None,
        eq: None,
        claims: Vec::new(),
        exact: None,
        second_route: false,
        working: false,
        stands_for: None,
        result: None,
        line: 0,
        student_why: None,
    };
    assert_eq!(step.why_cited().to_text(), "eq (51): expand");
    let uncited = Step {
        citation: None,
        ..step
    };
    assert_eq!(uncited.why_cited().to_text(), "expand");
}

fn problem_of(id: &str, variants: usize) -> Problem {
    Problem {
        id: id.into(),
        source: format!("{id}.toml").into(),
        line: 1,
        title: id.into(),
        page: format!("{id}.html"),
        tolerance: 0.01,
        answers: Vec::new(),
        tex: Default::default(),
        names: Default::default(),
        template: Prose::default(),
        variants: (1..=variants)
            .map(|number| Variant {
                number,
                statement: Prose::default(),
                given: Vec::new(),
                answers: Vec::new(),
            })
            .collect(),
    }
}

/// Sheet variant k gives each problem its variant k, cycling through a problem's fewer; the key
/// answers such a problem's variants once each, naming the sheet variants that use them.
#[test]
fn a_sheet_cycles_a_short_problem_and_shares_its_answers() {
    let sheet = sheet(vec![
        problem_of("a", 3),
        problem_of("none", 0),
        problem_of("b", 2),
    ])
    .unwrap();
    // The problem without variants is left out: "b" is number 2.
    assert_eq!(sheet.problems.len(), 2);
    assert_eq!(sheet.problem(1).0, 2);
    let on_sheet: Vec<Vec<(usize, usize, bool)>> = sheet
        .variants
        .iter()
        .map(|v| {
            v.problems
                .iter()
                .map(|p| (p.problem, p.variant, p.shared))
                .collect()
        })
        .collect();
    assert_eq!(
        on_sheet,
        vec![
            vec![(0, 0, false), (1, 0, true)],
            vec![(0, 1, false), (1, 1, true)],
            vec![(0, 2, false), (1, 0, true)],
        ]
    );
    let shared: Vec<(usize, usize, Vec<usize>)> = sheet
        .shared
        .iter()
        .map(|a| (a.problem, a.variant, a.serves.clone()))
        .collect();
    assert_eq!(shared, vec![(1, 0, vec![1, 3]), (1, 1, vec![2])]);
    assert!(super::sheet(vec![problem_of("none", 0)]).is_none());
}

/// A statement's `{name}` becomes the variant's exact value; text around it, and a name with no
/// value, stay as written.
#[test]
fn a_statement_takes_each_value_as_a_formula() {
    let v = VariantCheck {
        number: 1,
        values: vec![("m".into(), Expr::int(3))],
        decimal: Vec::new(),
        answers: Vec::new(),
    };
    let filled = problems::fill_statement("A mass {m} kg on {q}.", &v);
    assert_eq!(filled.to_text(), "A mass 3 kg on {q}.");
    let formulas: Vec<&Piece> = filled
        .0
        .iter()
        .filter(|p| matches!(p, Piece::Math(_)))
        .collect();
    assert_eq!(formulas, vec![&Piece::Math(Formula::Expr(Expr::int(3)))]);
}

/// Results follow the derivation's order, and a step's result is the form its derivation
/// prints (the heavy top's Ω as
/// √(I₃²ω₃² − 4 g I₁ l M)/(2 I₁), not the engine's expanded root), its number taken from the
/// exact result; a state of rest that is not real at the scene's values shows no number (NaN
/// was printed).
#[test]
fn results_follow_the_derivation_in_its_printed_form_and_no_number_where_none_is_real() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/course/dynamics/04-heavy-top.toml");
    let scene = crate::scene::load_all(&[path]).unwrap().remove(0);
    let r = crate::pipeline::run_scene(scene, None).unwrap();
    let quantities = results::quantities(&r);
    let omega = quantities.iter().find(|q| q.name == "Omega").unwrap();
    let printed = r.derivation.printed["Omega"].scalar().unwrap();
    let exact = r.derivation.named["Omega"].scalar().unwrap();
    assert_ne!(printed, exact);
    assert_eq!(
        omega.value,
        crate::model::value::Value::Scalar(printed.clone())
    );
    let at = |e: &crate::cas::Expr| crate::model::value::eval_at(e, &r.scene.values).unwrap();
    assert_eq!(omega.numbers, vec![Some(at(exact))]);
    assert!((at(printed) - at(exact)).abs() < 1e-12 * at(exact));
    // In the derivation's order: each step's result after the steps before it (alphabetically
    // `E` came first and `Lag` second).
    let position = |name: &str| quantities.iter().position(|q| q.name == name);
    let order: Vec<usize> = r
        .scene
        .steps
        .iter()
        .filter_map(|s| position(&s.name))
        .collect();
    assert!(
        order.len() > 5 && order.windows(2).all(|w| w[0] < w[1]),
        "{order:?}"
    );
    let rest = quantities.iter().find(|q| q.name == "rest_2").unwrap();
    assert!(
        rest.numbers[0].is_some_and(f64::is_nan),
        "{:?}",
        rest.numbers
    );
    assert!(rest.at.is_none());
}

/// A step's result is named as its derivation states it, never by the step's internal name: a
/// solution by its unknown (ẍ₁, not `acc_1`), a state of rest by its coordinate, the squared
/// frequency about the k-th state as Ω_k²; a catalogue quantity keeps its name in words.
#[test]
fn results_are_named_as_the_derivation_states_them() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let run = |file: &str| {
        let scene = crate::scene::load_all(&[root.join(file)])
            .unwrap()
            .remove(0);
        crate::pipeline::run_scene(scene, None).unwrap()
    };
    let symbol_of = |r: &crate::pipeline::SceneReport, name: &str| {
        let q = results::quantities(r);
        let q = q.iter().find(|q| q.name == name).unwrap();
        q.symbol.as_ref().map(|s| s.to_text())
    };
    let atwood = run("tests/course/dynamics/13-atwood.toml");
    assert_eq!(symbol_of(&atwood, "acc_1").as_deref(), Some("x1''"));
    assert_eq!(symbol_of(&atwood, "acc_3").as_deref(), Some("T"));
    assert_eq!(symbol_of(&atwood, "Lag").as_deref(), Some("Lag"));
    let hoop = run("tests/course/dynamics/05-bead-on-hoop.toml");
    assert_eq!(symbol_of(&hoop, "rest_3").as_deref(), Some("theta"));
    assert_eq!(symbol_of(&hoop, "stable_2").as_deref(), Some("Omega_2^2"));
    let box123 = run("tests/course/bodies/01-box-123.toml");
    assert_eq!(symbol_of(&box123, "inertia_tensor"), None);
}

/// The principal moments at the scene's values say the values with their units, as every
/// other result's numbers do ("at M = 1 kg, R = 1 m"), on the page and on paper alike.
#[test]
fn the_principal_moments_give_their_values_with_units() {
    let r = hoop();
    let page = page(&r, None, None);
    let p = page
        .principal_values
        .as_ref()
        .expect("the hoop's principal moments");
    let said = words::values_at(&p.values, &p.units)
        .to_tex(&page.names)
        .spoken();
    assert_eq!(said, "M equals 1 kg , R equals 1 m");
}
