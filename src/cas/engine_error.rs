//! What the engine could not do, and the budgets it is given.

/// The largest expansion the engine is given: total degree and number of terms. The shipped
/// lectures, fixtures and SymPy scenes reach degree 15 and 432 terms (measured); a sphere of radius (a+b+c)^8, degree 40,
/// took 27 s and 270 MB, and a box of side (a+b+c)^40 passed 2 GB.
pub const MAX_DEGREE: f64 = 30.0;
pub const MAX_TERMS: f64 = 20_000.0;

/// The most digits a number under a root may have. The engine simplifies `n^(1/2)` by
/// factoring n, which for a large n with no small factors can take longer than any budget (a
/// fuzzed tensor with entries 1e30 and 1.1e308 did not finish in two minutes).
pub const MAX_ROOT_DIGITS: usize = 30;

/// What the engine could not do, or gave back in a form we do not read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EngineError {
    #[error(
        "a root of a number with {digits} digits, which the engine would have to factor (more \
         than {MAX_ROOT_DIGITS} digits can take longer than any budget): give the values (and a \
         problem's variants) fewer digits, for example in other units"
    )]
    LargeRoot { digits: usize },
    #[error(
        "an expression whose expansion could reach degree {degree} with {terms:.0e} terms, beyond \
         the engine's budget of degree {MAX_DEGREE} and {MAX_TERMS:.0e} terms: give the body's \
         dimensions as simpler expressions (a single symbol each, with [definitions] for the \
         rest)"
    )]
    OverBudget { degree: f64, terms: f64 },
    #[error(
        "the engine produced `{}`, which is not an exact real number or expression",
        if text.len() > 200 { format!("{}… ({} characters)", text.chars().take(120).collect::<String>(), text.len()) } else { text.clone() }
    )]
    Unreadable { text: String },
    #[error(
        "0/0 where a value was put in: the expression has no value there, only a limit, which a \
         `series` step about that value with `order = 0` takes"
    )]
    ZeroOverZero,
    #[error(
        "a division by zero where a value was put in: the expression has a pole there, with no \
         finite value"
    )]
    DivisionByZero,
    #[error("unexpected name `{name}` in the engine's output `{text}`")]
    UnexpectedNameIn { name: String, text: String },
    #[error("zero denominator")]
    ZeroDenominator,
    #[error("the result is a complex number (a square root of a negative quantity?)")]
    Complex,
    #[error("unexpected name `{name}` from the engine")]
    UnexpectedName { name: String },
    #[error("unexpected function `{name}` from the engine")]
    UnexpectedFunction { name: String },
    #[error("not a rational function: `{expr}`")]
    NotRational { expr: String },
    #[error("not a polynomial in {var}: `{key}`")]
    NotPolynomial { var: String, key: String },
    #[error("cannot integrate: {var} also appears as `{coeff}`")]
    VariableInCoefficient { var: String, coeff: String },
    #[error("cannot integrate over {var}: `{coeff}` is not a polynomial in cos {var}, sin {var}")]
    NotTrigPolynomial { var: String, coeff: String },
}
