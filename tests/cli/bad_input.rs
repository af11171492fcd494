//! Every invalid fixture gives its expected error: file, line, column and field, exit 1, no panic
//! and nothing on standard output.

use super::{mechbook, stderr};
use std::path::Path;

/// The scene files of a fixture folder, each with its expected message (its `.expected`).
pub fn fixtures(dir: &Path) -> Vec<(std::path::PathBuf, String)> {
    super::toml_files(dir)
        .into_iter()
        .map(|f| {
            let expected = std::fs::read_to_string(f.with_extension("expected"))
                .unwrap_or_else(|_| panic!("{} has no .expected", f.display()));
            (f, expected.trim().to_string())
        })
        .collect()
}

/// The fixture `stem` of tests/fixtures/invalid gives its expected error: exit 1, nothing on
/// standard output, no panic.
fn gives_its_message(stem: &str) {
    let f = Path::new("tests/fixtures/invalid").join(format!("{stem}.toml"));
    let expected = std::fs::read_to_string(f.with_extension("expected"))
        .unwrap_or_else(|_| panic!("{} has no .expected", f.display()));
    let out = mechbook(&["check", f.to_str().unwrap()]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{}: {err}", f.display());
    assert!(
        out.stdout.is_empty(),
        "{}: partial output {:?}",
        f.display(),
        String::from_utf8_lossy(&out.stdout)
    );
    assert!(
        err.contains(expected.trim()),
        "{}:\n want: {}\n got:  {err}",
        f.display(),
        expected.trim()
    );
    assert!(!err.contains("panicked"), "{err}");
}

/// One test per fixture, named after it, so that a failure names its fixture.
macro_rules! invalid_fixtures {
    ($($name:ident => $stem:literal,)*) => {
        /// Every fixture of the folder has its test here, and every test its fixture.
        const STEMS: &[&str] = &[$($stem),*];
        mod invalid {
            $(
                #[test]
                fn $name() {
                    super::gives_its_message($stem);
                }
            )*
        }
    };
}

invalid_fixtures! {
    answer_step_without_route => "answer-step-without-route",
    answer_tolerance => "answer-tolerance",
    answer_unit_unknown => "answer-unit-unknown",
    assume_broken_by_values => "assume-broken-by-values",
    assume_not_an_inequality => "assume-not-an-inequality",
    assume_without_room => "assume-without-room",
    axis_not_unit => "axis-not-unit",
    bad_equation_number => "bad-equation-number",
    bad_fidelity => "bad-fidelity",
    bad_figures => "bad-figures",
    cone_origin => "cone-origin",
    control_character => "control-character",
    cyclic_as_a_list => "cyclic-as-a-list",
    deep_nesting => "deep-nesting",
    definition_beyond_the_budget => "definition-beyond-the-budget",
    diff_by_time => "diff-by-time",
    dollar_unclosed => "dollar-unclosed",
    dynamics_undeclared_symbol => "dynamics-undeclared-symbol",
    expect_variants_malformed => "expect-variants-malformed",
    expect_variants_without_problem => "expect-variants-without-problem",
    fast_plot => "fast-plot",
    free_body_bad_omega => "free-body-bad-omega",
    free_body_no_value => "free-body-no-value",
    free_body_principal_no_body => "free-body-principal-no-body",
    free_body_triangle => "free-body-triangle",
    gives_equation_on_expression => "gives-equation-on-expression",
    high_degree => "high-degree",
    hole_too_heavy => "hole-too-heavy",
    huge_exponent => "huge-exponent",
    implicit_product => "implicit-product",
    infinite_value => "infinite-value",
    inner_radius_too_large => "inner-radius-too-large",
    latex_input => "latex-input",
    latex_no_pdf => "latex-no-pdf",
    latex_unreadable => "latex-unreadable",
    long_expression => "long-expression",
    long_id => "long-id",
    long_number => "long-number",
    long_plot => "long-plot",
    long_title => "long-title",
    malformed_expression => "malformed-expression",
    mathml_script => "mathml-script",
    missing_field => "missing-field",
    missing_title => "missing-title",
    nan_value => "nan-value",
    negative_size => "negative-size",
    nested_sin => "nested-sin",
    noncharacter => "noncharacter",
    not_utf8 => "not-utf8",
    power_too_large => "power-too-large",
    power_written_twice_star => "power-written-twice-star",
    problem_answer_not_wanted => "problem-answer-not-wanted",
    problem_answer_unchecked => "problem-answer-unchecked",
    problem_float_value => "problem-float-value",
    problem_impossible_require => "problem-impossible-require",
    problem_placeholder_no_value => "problem-placeholder-no-value",
    problem_public_variant => "problem-public-variant",
    problem_unknown_placeholder => "problem-unknown-placeholder",
    problem_vary_undeclared => "problem-vary-undeclared",
    rate_written_dot => "rate-written-dot",
    renamed_expect => "renamed-expect",
    renamed_quantity => "renamed-quantity",
    reserved_id => "reserved-id",
    short_vector => "short-vector",
    step_cycle => "step-cycle",
    step_frequency_of_lagrangian => "step-frequency-of-lagrangian",
    step_gives_on_equilibria => "step-gives-on-equilibria",
    step_integration_variable_taken => "step-integration-variable-taken",
    step_momentum_of_a_symbol => "step-momentum-of-a-symbol",
    step_rate_of_a_symbol => "step-rate-of-a-symbol",
    step_solve_for_a_number => "step-solve-for-a-number",
    step_solve_for_twice => "step-solve-for-twice",
    step_solve_states_of_rest => "step-solve-states-of-rest",
    step_stability_of_motion => "step-stability-of-motion",
    step_two_operations => "step-two-operations",
    step_unknown_name => "step-unknown-name",
    sweep_bad_range => "sweep-bad-range",
    symbol_tex_unreadable => "symbol-tex-unreadable",
    symbol_unit_unknown => "symbol-unit-unknown",
    sympy_equation => "sympy-equation",
    tex_escape_meaning => "tex-escape-meaning",
    tex_escape_statement => "tex-escape-statement",
    tex_escape_title => "tex-escape-title",
    toml_syntax => "toml-syntax",
    too_many_coordinates => "too-many-coordinates",
    too_many_plots => "too-many-plots",
    type_error => "type-error",
    typo_field => "typo-field",
    typo_function => "typo-function",
    typo_kind => "typo-kind",
    typo_quantity => "typo-quantity",
    undefined_claim_name => "undefined-claim-name",
    undefined_symbol => "undefined-symbol",
    unknown_cite => "unknown-cite",
    unknown_key => "unknown-key",
    unknown_kind => "unknown-kind",
    unknown_output => "unknown-output",
    unknown_plot => "unknown-plot",
    unknown_verdict => "unknown-verdict",
    variant_beyond_double => "variant-beyond-double",
    variant_hole_too_heavy => "variant-hole-too-heavy",
    variant_inner_radius => "variant-inner-radius",
    variant_negative_mass => "variant-negative-mass",
    variant_require_unevaluable => "variant-require-unevaluable",
    variants_without_problem => "variants-without-problem",
    zero_mass => "zero-mass",
}

#[test]
fn each_invalid_fixture_has_its_own_test() {
    let mut found: Vec<String> = fixtures(Path::new("tests/fixtures/invalid"))
        .into_iter()
        .map(|(f, _)| f.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    found.sort();
    assert_eq!(found, STEMS, "add the new fixture to invalid_fixtures!");
}

#[test]
fn one_bad_scene_stops_the_whole_run_before_any_output() {
    let out = mechbook(&[
        "check",
        "lectures",
        "tests/fixtures/invalid/negative-size.toml",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(out.stdout.is_empty());
    assert!(stderr(&out).contains("1 bad scene file; nothing was derived"));
}

#[test]
fn a_missing_file_is_named() {
    let out = mechbook(&["derive", "lectures/no-such-scene.toml"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("lectures/no-such-scene.toml:1:1: cannot read the scene file"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn command_line_misuse_exits_with_2() {
    for args in [
        vec!["frobnicate"],
        vec!["check", "--nope"],
        vec!["derive"],
        vec![],
    ] {
        let out = mechbook(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
    }
}

#[test]
fn help_explains_the_commands() {
    let out = mechbook(&["--help"]);
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8(out.stdout).unwrap();
    for word in ["check", "derive", "Exit status"] {
        assert!(text.contains(word), "{text}");
    }
    let out = mechbook(&["check", "--help"]);
    assert!(
        String::from_utf8(out.stdout)
            .unwrap()
            .contains("regression test")
    );
}
