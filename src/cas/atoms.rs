//! Our expressions as the engine's atoms and back: built directly (no text in between, it is
//! the hot path), each scene name prefixed, each elementary function the engine does not know
//! an opaque function of its own (`functions.rs`).

use super::engine_error::EngineError;
use super::expr::Expr;
use super::parse::parse;
use super::rational::Rational;
use symbolica::coefficient::CoefficientView;
use symbolica::prelude::*;

/// The prefix of every name the engine holds for us: a scene's names never clash with the
/// engine's own.
pub(super) const PREFIX: &str = "mb";

/// Builds the engine's expression directly from ours (no text in between: it is the hot path).
pub(super) fn to_atom(e: &Expr) -> Atom {
    // sin(asin u) = u, exp(log u) = u: the engine holds the inverses opaque.
    if let Expr::Call(name, args) = e
        && let Some(undone) = super::exact_values::undo_inverse(name, args)
    {
        return to_atom(&undone);
    }
    match e {
        Expr::Num(r) => match r.to_i64_pair() {
            Some(pair) => Atom::num(pair),
            None => large_number(r),
        },
        Expr::Sym(s) => var_atom(s),
        Expr::Add(v) => v.iter().fold(Atom::num(0), |acc, x| acc + &to_atom(x)),
        Expr::Mul(v) => v.iter().fold(Atom::num(1), |acc, x| acc * &to_atom(x)),
        Expr::Pow(b, x) => to_atom(b).pow(to_atom(x)),
        Expr::Call(name, args) if args.len() == 1 && name == "sin" => {
            Symbol::SIN.call(to_atom(&args[0]))
        }
        Expr::Call(name, args) if args.len() == 1 && name == "cos" => {
            Symbol::COS.call(to_atom(&args[0]))
        }
        Expr::Call(name, args) if args.len() == 1 && name == "sqrt" => {
            to_atom(&args[0]).pow(Atom::num((1, 2)))
        }
        // The other elementary functions (an equilibrium's angle, a Morse potential's
        // exponential) are opaque to the engine: each call one indeterminate, the same for equal
        // arguments. Their derivatives are taken before (`Expr::diff`), their values by the
        // random points.
        Expr::Call(name, args) if super::functions::arity(name) == Some(args.len()) => {
            let atoms: Vec<Atom> = args.iter().map(to_atom).collect();
            // The arguments as the engine has them, where x − x is already 0.
            let numbers: Option<Vec<Expr>> = atoms
                .iter()
                .map(|a| match a.as_view() {
                    AtomView::Num(_) => from_atom(a).ok(),
                    _ => None,
                })
                .collect();
            if let Some(value) = numbers.and_then(|n| super::exact_values::exact_at(name, &n)) {
                return to_atom(&value);
            }
            symbol!(format!("{PREFIX}{name}").as_str()).call_args(atoms.iter())
        }
        other => unreachable!("`{other}` is resolved before the engine"),
    }
}

/// A number beyond `i64`, built by exact arithmetic from base-2³² digits (no text in between).
fn large_number(r: &Rational) -> Atom {
    let (num, den) = r.abs_parts_base_2_32();
    let horner = |limbs: &[u32]| {
        limbs.iter().rev().fold(Atom::num(0), |acc, &l| {
            acc * &Atom::num(1i64 << 32) + &Atom::num(i64::from(l))
        })
    };
    let sign = if r.is_negative() { -1 } else { 1 };
    Atom::num(sign) * &horner(&num) / &horner(&den)
}

fn from_text(text: &str) -> Result<Expr, EngineError> {
    let text = strip_ansi(text);
    // The engine's indeterminate (0/0) and complex infinity (x/0).
    if text.contains('¿') {
        return Err(EngineError::ZeroOverZero);
    }
    if text.contains('⧞') {
        return Err(EngineError::DivisionByZero);
    }
    let parsed = parse(&text).map_err(|_| EngineError::Unreadable { text: text.clone() })?;
    if let Some((name, _)) = parsed.symbols.iter().find(|(s, _)| !s.starts_with(PREFIX)) {
        return Err(EngineError::UnexpectedNameIn {
            name: name.clone(),
            text,
        });
    }
    Ok(parsed
        .expr
        .substitute(&|s| s.strip_prefix(PREFIX).map(our_name)))
}

/// Text without terminal colour codes (ESC [ ... m), which the engine's printer may add.
fn strip_ansi(text: &str) -> String {
    let mut out = String::new();
    let mut chars = text.chars();
    while let Some(c) = chars.next() {
        if c == '\u{1b}' {
            for d in chars.by_ref() {
                if d.is_ascii_alphabetic() {
                    break;
                }
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// Reads the engine's expression back into ours by walking it.
fn from_view(v: AtomView<'_>) -> Result<Expr, EngineError> {
    let all = |it: &mut dyn Iterator<Item = AtomView<'_>>| {
        it.map(from_view).collect::<Result<Vec<_>, _>>()
    };
    Ok(match v {
        AtomView::Num(n) => match n.get_coeff_view() {
            CoefficientView::Natural(num, den, 0, _) => Expr::Num(
                Rational::new(num as i128, den as i128).ok_or(EngineError::ZeroDenominator)?,
            ),
            CoefficientView::Natural(..) => {
                return Err(EngineError::Complex);
            }
            // Large or complex numbers: the printed form says what they are.
            _ => return from_text(&v.to_string()),
        },
        AtomView::Var(x) => {
            let name = x.get_symbol().get_stripped_name().to_string();
            match name.strip_prefix(PREFIX) {
                Some(n) => our_name(n),
                None => return Err(EngineError::UnexpectedName { name }),
            }
        }
        AtomView::Fun(f) => {
            let s = f.get_symbol();
            let name = if s == Symbol::SIN {
                "sin"
            } else if s == Symbol::COS {
                "cos"
            } else if s == Symbol::SQRT {
                "sqrt"
            } else if let Some(elementary) = s
                .get_stripped_name()
                .strip_prefix(PREFIX)
                .filter(|n| super::functions::arity(n).is_some())
            {
                elementary
            } else {
                return Err(EngineError::UnexpectedFunction {
                    name: s.get_stripped_name().to_string(),
                });
            };
            let args = all(&mut f.iter())?;
            super::exact_values::exact_at(name, &args).unwrap_or(Expr::Call(name.into(), args))
        }
        AtomView::Pow(p) => {
            let (b, x) = p.get_base_exp();
            Expr::pow(from_view(b)?, from_view(x)?)
        }
        // Symbolica orders by symbol creation, which varies between runs: impose our own order.
        AtomView::Mul(m) => Expr::ordered_product(all(&mut m.iter())?),
        AtomView::Add(a) => Expr::ordered_sum(all(&mut a.iter())?),
    })
}

pub(super) fn from_atom(a: &Atom) -> Result<Expr, EngineError> {
    from_view(a.as_view())
}

/// A name as the engine holds it: prefixed, and a coordinate's rate `phi'` as `phi__d` (a
/// scene's own names never hold `__`).
pub(super) fn var_atom(name: &str) -> Atom {
    Atom::var(symbol!(
        format!("{PREFIX}{}", name.replace('\'', "__d")).as_str()
    ))
}

/// Our name for the engine's (without the prefix).
fn our_name(engine: &str) -> Expr {
    Expr::sym(&engine.replace("__d", "'"))
}
