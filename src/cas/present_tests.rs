//! The presentation pass's rewrites and candidates, each proven equal.

use super::tidy;
use crate::cas::{Expr, parse, present_all};

fn p(s: &str) -> Expr {
    parse(s).unwrap().expr
}

fn tidied(s: &str) -> String {
    tidy(&p(s), &|name| name != "theta").to_text()
}

fn at(e: &Expr) -> f64 {
    e.eval(&|n| {
        Some(match n {
            "theta" => -0.7,
            "g" => 9.8,
            "L" => 1.3,
            "l" => 0.6,
            "M" | "m" => 2.1,
            "R" => 0.9,
            "r" => 0.2,
            _ => 1.7,
        })
    })
    .unwrap()
}

/// Each tree rewrite on its own, and the value kept: a rewrite is a pure change of form.
#[test]
fn each_rewrite_gives_the_form_a_physicist_writes_and_the_same_value() {
    for (from, to) in [
        ("2*pi*(3/2*g/L)^(-1/2)", "2*pi*(2/3*L/g)^(1/2)"),
        ("m*l^2*(1 - cos(theta)^2)", "m*l^2*sin(theta)^2"),
        ("a/(-1 + cos(theta)^2)", "-a/sin(theta)^2"),
        ("(-R*w^2 + g)/R", "(g - R*w^2)/R"),
        ("(a - a*cos(theta))^2/I1", "a^2*(1 - cos(theta))^2/I1"),
        ("I3*w3*(g*M)^(1/2)/(g*M) - 1", "I3*w3*(g*M)^(-1/2) - 1"),
        ("-w3^2*(-I2 + I3)*(I1 - I3)", "w3^2*(I2 - I3)*(I1 - I3)"),
        (
            "-1/2*x/(I1*cos(theta)) + 1/2*y/(I1*cos(theta))",
            "1/2*(y - x)/(I1*cos(theta))",
        ),
    ] {
        assert_eq!(tidied(from), to, "{from}");
        assert!((at(&p(from)) - at(&p(to))).abs() < 1e-12, "{from}");
    }
}

/// The engine's forms, where the tree alone cannot: a mass cancelled under a root, a
/// fraction factored, one divided out in cos θ; each proven equal before it is taken.
#[test]
fn the_engines_forms_are_taken_where_clearly_shorter() {
    let cases = [
        (
            "(g*m/((7*m/5)*(R^2 - 2*r*R + r^2))*(R - r))^(1/2)",
            "(5/7*g/(R - r))^(1/2)",
        ),
        ("d*g*M/((M/12)*(L^2 + 12*d^2))", "12*d*g/(L^2 + 12*d^2)"),
        (
            "(2*I1*I3*A^2*w3^2 + I1^2*A^4 + I3^2*w3^4)/(A^2*I1^2*w3^2 + A^2*I3^2*w3^2 + I1^2*A^4 + I3^2*w3^4)",
            "(I1*A^2 + I3*w3^2)^2/((A^2 + w3^2)*(A^2*I1^2 + I3^2*w3^2))",
        ),
        (
            "(I3^2*w3^2 - I3^2*w3^2*cos(theta) + 2*g*I1*l*M*cos(theta) + 2*g*I1*l*M*cos(theta)^2)/(2*I1 + 2*I1*cos(theta))",
            "1/2*I3^2*w3^2*(1 - cos(theta))/(I1*(cos(theta) + 1)) + g*l*M*cos(theta)",
        ),
        // A series in the amplitude, as its leading term times 1 + …
        (
            "1/1536*pi*(g*l)^(1/2)*(3072 + 192*a^2 + 11*a^4)/g",
            "2*pi*(g*l)^(1/2)*(1 + 1/16*a^2 + 11/3072*a^4)/g",
        ),
        // Decimals' fractions stay term by term: no number is taken out of the sum.
        (
            "3627/10*u - 344*u^2 + 981/10*u^3 - 2984/25",
            "3627/10*u - 344*u^2 + 981/10*u^3 - 2984/25",
        ),
    ];
    let signed = ["theta".to_string()].into_iter().collect();
    let exprs: Vec<Expr> = cases.iter().map(|(from, _)| p(from)).collect();
    let out = present_all(
        exprs,
        signed,
        Default::default(),
        crate::notation::printed_length,
    )
    .unwrap();
    for ((from, to), got) in cases.iter().zip(&out) {
        assert_eq!(got.to_text(), *to, "{from}");
        assert!(
            (at(&p(from)) - at(got)).abs() < 1e-9 * at(got).abs().max(1.0),
            "{from}"
        );
    }
}
