//! A claim between two sides that are never negative by their form (principal square roots
//! and other roots of even index, positive symbols and numbers, even powers, exp, cosh, |u|, and
//! sums and products of these), decided by their squares:
//! where both are real, a ≥ 0, b ≥ 0 and a² = b² give a = b. The engine cannot take
//! √(g/(l cos θ₀))·√(1 + 3cos²θ₀) apart without the sign of cos θ₀, but squared the claim is a
//! rational identity in cos θ₀ (the spherical pendulum's wobble about its cone).

use crate::cas::{self, Expr};
use std::collections::BTreeSet;

/// Whether `e` is ≥ 0 wherever it is real, by its form alone: the `signed` names take either
/// sign, every other symbol is positive.
pub(crate) fn never_negative(e: &Expr, signed: &BTreeSet<String>) -> bool {
    match e {
        Expr::Num(r) => !r.is_negative(),
        Expr::Sym(s) => !signed.contains(s),
        Expr::Pow(b, k) => match k.as_ref() {
            // A principal root of even index (x^(1/2), x^(3/2)) is real only where x ≥ 0,
            // and then ≥ 0; an even power is ≥ 0 always.
            Expr::Num(r) => {
                let even = r
                    .to_i64_pair()
                    .is_some_and(|(n, d)| (d == 1 && n % 2 == 0) || d % 2 == 0);
                even || never_negative(b, signed)
            }
            _ => false,
        },
        Expr::Mul(v) | Expr::Add(v) => v.iter().all(|x| never_negative(x, signed)),
        Expr::Call(f, _) => ["sqrt", "exp", "cosh", "abs"].contains(&f.as_str()),
        _ => false,
    }
}

/// Each entry the engine has not proved zero but the random points found zero, decided by
/// [`equal_by_squares`]: `symbolic[k]` set where it holds; whether any was.
pub(crate) fn third_chance(
    derived: &[Expr],
    notes: &[Expr],
    numeric: &[bool],
    symbolic: &mut [bool],
    signed: &BTreeSet<String>,
) -> Result<bool, cas::CasError> {
    let open: Vec<usize> = (0..symbolic.len())
        .filter(|&k| !symbolic[k] && numeric[k])
        .collect();
    if open.is_empty() {
        return Ok(false);
    }
    let pairs: Vec<(Expr, Expr)> = derived.iter().cloned().zip(notes.iter().cloned()).collect();
    let decided = equal_by_squares(&pairs, &open, signed)?;
    for &k in &decided {
        symbolic[k] = true;
    }
    Ok(!decided.is_empty())
}

/// For each entry the engine has not proved but the random points found zero (`undecided`),
/// whether both sides are never negative and their squares are equal over the scene's
/// domain.
pub(crate) fn equal_by_squares(
    pairs: &[(Expr, Expr)],
    undecided: &[usize],
    signed: &BTreeSet<String>,
) -> Result<Vec<usize>, cas::CasError> {
    let candidates: Vec<usize> = undecided
        .iter()
        .copied()
        .filter(|&k| {
            let (a, b) = &pairs[k];
            never_negative(a, signed) && never_negative(b, signed)
        })
        .collect();
    if candidates.is_empty() {
        return Ok(Vec::new());
    }
    let squared = |e: &Expr| Expr::pow(e.clone(), Expr::int(2));
    let diffs: Vec<Expr> = candidates
        .iter()
        .map(|&k| Expr::minus(squared(&pairs[k].0), squared(&pairs[k].1)))
        .collect();
    let plain = cas::is_zero_all(diffs.clone())?;
    let positive = cas::is_zero_over_positive(diffs, signed.clone())?;
    Ok(candidates
        .into_iter()
        .zip(plain.into_iter().zip(positive))
        .filter(|(_, (a, b))| *a || *b)
        .map(|(k, _)| k)
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Expr {
        crate::cas::parse(s).unwrap().expr
    }

    /// The spherical pendulum's wobble in two forms: equal by their squares. A form with 2
    /// for 3, or the negative root, is not decided equal.
    #[test]
    fn roots_of_unknown_sign_are_equal_by_their_squares_and_wrong_forms_are_not() {
        let signed: BTreeSet<String> = ["theta".to_string()].into();
        let derived = parse("(3*g*cos(theta0)/l + g/(l*cos(theta0)))^(1/2)");
        let pairs: Vec<(Expr, Expr)> = [
            "sqrt(g/(l*cos(theta0)))*sqrt(1 + 3*cos(theta0)^2)",
            "sqrt(g/(l*cos(theta0)))*sqrt(1 + 2*cos(theta0)^2)",
            "-sqrt(g/(l*cos(theta0)))*sqrt(1 + 3*cos(theta0)^2)",
        ]
        .iter()
        .map(|notes| (derived.clone(), parse(notes)))
        .collect();
        assert_eq!(equal_by_squares(&pairs, &[0, 1, 2], &signed).unwrap(), [0]);
        // The engine alone does not decide the first: the reason for this route.
        let diff = Expr::minus(pairs[0].0.clone(), pairs[0].1.clone());
        assert_eq!(cas::is_zero_all(vec![diff]).unwrap(), [false]);
    }

    #[test]
    fn a_coordinate_or_an_odd_power_of_one_may_be_negative() {
        let signed: BTreeSet<String> = ["theta".to_string()].into();
        assert!(never_negative(&parse("sqrt(a)*b^3*exp(theta)"), &signed));
        assert!(never_negative(&parse("theta^2 + (a - b)^(1/2)"), &signed));
        assert!(!never_negative(&parse("theta*sqrt(a)"), &signed));
        assert!(!never_negative(&parse("a - b"), &signed));
        assert!(!never_negative(&parse("cos(a)^(1/3)"), &signed));
    }
}
