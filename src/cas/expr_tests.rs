//! The expression tree, its printers and its parser.

use super::expr::Expr;
use super::parse::*;

fn p(s: &str) -> Expr {
    parse(s).unwrap().expr
}

#[test]
fn text_round_trips() {
    for s in [
        "m*a^2*(2/3)",
        "-1/4*a^2*m",
        "1/2*M*R^2*(2 - cos(alpha)^2)",
        "x^(-1)",
        "[[1, 0], [0, 1]]",
        "cross(r, w)[0]",
    ] {
        let e = p(s);
        assert_eq!(p(&e.to_text()), e, "{s} -> {}", e.to_text());
    }
}

#[test]
fn precedence_and_evaluation() {
    let env = |s: &str| match s {
        "a" => Some(2.0),
        "b" => Some(3.0),
        _ => None,
    };
    assert_eq!(p("a + b*a^2").eval(&env).unwrap(), 14.0);
    assert_eq!(p("-a^2").eval(&env).unwrap(), -4.0);
    assert_eq!(p("a/b/a").eval(&env).unwrap(), 1.0 / 3.0);
    assert_eq!(p("2^-1").eval(&env).unwrap(), 0.5);
    assert!((p("cos(pi)").eval(&env).unwrap() + 1.0).abs() < 1e-15);
    assert!(matches!(p("c").eval(&env), Err(crate::cas::EvalError::NoValue(c)) if c == "c"));
}

#[test]
fn errors_carry_offsets() {
    let e = parse("m*a^^2").unwrap_err();
    assert_eq!(e.offset, 4);
    let e = parse("(a + b").unwrap_err();
    assert_eq!(e.offset, 6);
    assert_eq!(parse("").unwrap_err().message, "empty expression");
    let syms = parse("m * alpha").unwrap().symbols;
    assert_eq!(syms, vec![("m".into(), 0), ("alpha".into(), 4)]);
}

#[test]
fn derivatives_match_difference_quotients() {
    for text in [
        "a*cos(b*t + c)^2",
        "sqrt(1 + t^2)*sin(t)",
        "t^3/(1 + t)",
        "w*t - 2",
    ] {
        let e = p(text);
        let d = e.diff("t").unwrap();
        let at = |e: &Expr, t: f64| {
            e.eval(&|s| {
                Some(match s {
                    "t" => t,
                    "a" => 1.3,
                    "b" => 0.7,
                    "c" => -0.2,
                    _ => 2.0,
                })
            })
            .unwrap()
        };
        let h = 1e-6;
        let fd = (at(&e, 0.4 + h) - at(&e, 0.4 - h)) / (2.0 * h);
        assert!(
            (at(&d, 0.4) - fd).abs() < 1e-8,
            "{text}: {} vs {fd}",
            at(&d, 0.4)
        );
    }
    let e = p("2^t").diff("t").unwrap_err();
    assert!(format!("{e:?}").starts_with("VariableExponent"), "{e:?}");
}

#[test]
fn nesting_and_length_are_limited() {
    let deep = format!("{}a{}", "(".repeat(6538), ")".repeat(6538));
    let e = parse_input(&deep[..MAX_EXPR_BYTES]).unwrap_err();
    assert!(e.message.contains("nested more than 64"), "{}", e.message);
    assert_eq!(e.offset, MAX_NESTING);
    let sines = format!("{}x{}", "sin(".repeat(966), ")".repeat(966));
    assert!(
        parse_input(&sines)
            .unwrap_err()
            .message
            .contains("limit is 4000")
    );
    let sines = format!("{}x{}", "sin(".repeat(100), ")".repeat(100));
    assert!(parse_input(&sines).unwrap_err().message.contains("nested"));
    assert!(
        parse_input(&"-".repeat(1000))
            .unwrap_err()
            .message
            .contains("nested")
    );
    assert!(
        parse_input(&format!("a{}", "^a".repeat(200)))
            .unwrap_err()
            .message
            .contains("nested")
    );
    let ok = format!("{}a{}", "(".repeat(60), ")".repeat(60));
    assert_eq!(parse_input(&ok).unwrap().expr, Expr::sym("a"));
    // Our own texts may be longer (a derived result), never deeper than 256.
    let long = vec!["a"; 3000].join(" + ");
    assert!(long.len() > MAX_EXPR_BYTES && parse(&long).is_ok());
    let e = parse(&format!("{}a{}", "(".repeat(300), ")".repeat(300))).unwrap_err();
    assert!(
        e.message.starts_with("nested more than 256 levels"),
        "{e:?}"
    );
}

#[test]
fn big_and_tiny_numbers_stay_exact() {
    assert_eq!(p("1e-10").to_text(), "1/10000000000");
    assert_eq!(p("1e20*1e20").to_text(), format!("1{}", "0".repeat(40)));
    assert!(
        parse("1e5000")
            .unwrap_err()
            .message
            .contains("malformed number")
    );
}

#[test]
fn unexpected_characters_are_named_whole() {
    assert_eq!(
        parse("a \u{1} b").unwrap_err().message,
        "unexpected control character U+0001"
    );
    assert_eq!(parse("a é").unwrap_err().message, "unexpected `é`");
    assert!(
        parse("\\sin x")
            .unwrap_err()
            .message
            .starts_with("unexpected `\\`; LaTeX is not accepted")
    );
}

#[test]
fn latex_forms() {
    crate::base::assert_each(
        |text| p(text).to_latex(crate::notation::Names::none()),
        &[
            ("1/2*M*R^2", "\\frac{M R^{2}}{2}"),
            ("sin(alpha)^2", "\\,{\\sin}^{2}\\left(\\alpha\\right)"),
            ("w1", "\\omega_{1}"),
            ("wd2", "\\dot{\\omega}_{2}"),
            ("w", "w"),
        ],
    );
}

#[test]
fn a_product_puts_its_coefficient_before_a_root_of_a_number() {
    // As the engine returns √3/8: the root and the coefficient, in either order.
    let root = Expr::pow(Expr::int(3), p("1/2"));
    for factors in [vec![root.clone(), p("1/8")], vec![p("1/8"), root.clone()]] {
        let e = Expr::ordered_product(factors);
        assert_eq!(e.to_text(), "1/8*3^(1/2)");
        assert_eq!(
            e.to_latex(crate::notation::Names::none()),
            "\\frac{\\sqrt{3}}{8}"
        );
    }
    let e = Expr::ordered_product(vec![Expr::sym("M"), root, p("27/32")]);
    assert_eq!(e.to_text(), "27/32*3^(1/2)*M");
}

/// Each function's derivative (`Expr::diff`, by each argument) against a central difference of
/// its value, at points inside every domain: an independent route, which a wrong sign or factor
/// fails.
#[test]
fn each_derivative_is_the_slope_of_its_value() {
    use super::functions::{SCALAR_FUNCTIONS, arity, value};
    for &name in SCALAR_FUNCTIONS {
        let n = arity(name).unwrap();
        let vars = ["x", "y"];
        let call = Expr::Call(
            name.into(),
            vars[..n].iter().map(|s| Expr::sym(s)).collect(),
        );
        for (x, y) in [(0.3, 0.7), (0.55, -0.4), (0.8, 1.9)] {
            for (k, var) in vars[..n].iter().enumerate() {
                let d = call.diff(var).unwrap();
                let exact = d
                    .eval(&|s| match s {
                        "x" => Some(x),
                        "y" => Some(y),
                        _ => None,
                    })
                    .unwrap();
                let h = 1e-6;
                let shift = |s: f64| {
                    let mut p = [x, y];
                    p[k] += s;
                    value(name, &p[..n]).unwrap()
                };
                let slope = (shift(h) - shift(-h)) / (2.0 * h);
                assert!(
                    (slope - exact).abs() < 1e-7 * exact.abs().max(1.0),
                    "d{name}/d{var} at ({x}, {y}): {exact} by the rule, {slope} by the slope"
                );
            }
        }
    }
}
