//! `[outputs] inertia = "principal"`: the principal moments of the Lecture 3/9 families taken
//! from the scene's own bodies, their moments about the centre of mass, and put into every
//! result of those families, which are derived in I1, I2 and I3 first.

use super::{Derivation, DeriveError, Step, simplify_value};
use crate::cas::{self, Expr};
use crate::model::catalogue::{Stage, quantity, stage_for_quantity};
use crate::notation::Formula;

/// The families written in principal moments.
const FAMILIES: [Stage; 4] = [
    Stage::EulerEquations,
    Stage::SymmetricTop,
    Stage::AxisStability,
    Stage::Poinsot,
];

/// The moments from the diagonal of the bodies' tensor about their centre of mass, whose
/// off-diagonal entries must vanish. With Euler's equations, the axes' stability or Poinsot's
/// construction, I1, I2 and I3 are the moments about x, y and z (a symmetric top then needs
/// I1 = I2); with the free top alone, I1 = I2 are the two equal ones and I3 the third.
pub fn moments_from_bodies(d: &mut Derivation) -> Result<(), DeriveError> {
    let cm = d.matrix(quantity::INERTIA_CM)?.clone();
    let off = vec![cm[0][1].clone(), cm[0][2].clone(), cm[1][2].clone()];
    if !cas::is_zero_all(off)?.into_iter().all(|z| z) {
        return Err(DeriveError::NotDerivable(
            "`inertia = \"principal\"` takes the principal moments along the frame's axes, and \
             the bodies' tensor about their centre of mass is not diagonal there: turn the body \
             so that its symmetry axes are x, y and z"
                .into(),
        ));
    }
    let m = [cm[0][0].clone(), cm[1][1].clone(), cm[2][2].clone()];
    let (three, moments) = named_moments(d, &m)?;
    let values: Vec<Expr> = moments.iter().map(|(_, e)| e.clone()).collect();
    d.steps.push(if three {
        Step::note(
            "The bodies' own moments",
            Formula::parse("I_1 = $0, quad I_2 = $1, quad I_3 = $2", &values),
            "the moments are the bodies' own: the body turns about its centre of mass, where its \
             tensor is diagonal; $I_1$, $I_2$ and $I_3$ are its moments about $x$, $y$ and $z$, \
             and every result above takes them",
        )
    } else {
        Step::note(
            "The bodies' own moments",
            Formula::parse("I_1 = I_2 = $0, quad I_3 = $1", &values),
            "the moments are the bodies' own: the free top is the scene's body, turning about its \
             centre of mass; its moments come from the tensor there, and every result above takes \
             them",
        )
    });
    put_in_families(d, &moments)
}

/// Moments by the names the families' results use.
type Named = Vec<(&'static str, Expr)>;

/// The moments the families take, by name: I1, I2 and I3 about x, y and z when a family other
/// than the symmetric top's is derived (then `true`), else the top's I1 = I2 and I3.
fn named_moments(d: &Derivation, m: &[Expr; 3]) -> Result<(bool, Named), DeriveError> {
    let derived = |s: Stage| {
        d.quantities
            .keys()
            .any(|n| stage_for_quantity(n) == Some(s))
    };
    let three = FAMILIES
        .iter()
        .any(|s| *s != Stage::SymmetricTop && derived(*s));
    let top = derived(Stage::SymmetricTop);
    let equal = cas::is_zero_all(vec![
        Expr::minus(m[0].clone(), m[1].clone()),
        Expr::minus(m[1].clone(), m[2].clone()),
        Expr::minus(m[0].clone(), m[2].clone()),
    ])?;
    let not_a_top = || {
        DeriveError::NotDerivable(format!(
            "`symmetric_top` needs two equal moments{}, and the bodies' about their centre of \
             mass are {}, {} and {}: the body is not a symmetric top{}",
            if three { " about x and y" } else { "" },
            m[0].to_text(),
            m[1].to_text(),
            m[2].to_text(),
            if three {
                " about z (with the other families, I1, I2 and I3 are the moments about x, y \
                 and z)"
            } else {
                ""
            }
        ))
    };
    let moments: Vec<(&str, Expr)> = if three {
        if top && !equal[0] {
            return Err(not_a_top());
        }
        vec![
            ("I1", m[0].clone()),
            ("I2", m[1].clone()),
            ("I3", m[2].clone()),
        ]
    } else {
        // The two equal moments are I1 = I2; the third, about the symmetry axis, is I3.
        let (i1, i3) = match equal[..] {
            [true, _, _] => (m[0].clone(), m[2].clone()),
            [_, true, _] => (m[1].clone(), m[0].clone()),
            [_, _, true] => (m[0].clone(), m[1].clone()),
            _ => return Err(not_a_top()),
        };
        vec![("I1", i1), ("I3", i3)]
    };
    Ok((three, moments))
}

/// Every result of the families with the moments put in.
fn put_in_families(d: &mut Derivation, moments: &[(&str, Expr)]) -> Result<(), DeriveError> {
    let put = |e: &Expr| {
        e.substitute(&|s| {
            moments
                .iter()
                .find(|(n, _)| *n == s)
                .map(|(_, v)| v.clone())
        })
    };
    let names: Vec<String> = d
        .quantities
        .keys()
        .filter(|n| stage_for_quantity(n).is_some_and(|s| FAMILIES.contains(&s)))
        .cloned()
        .collect();
    for name in names {
        let v = &d.quantities[&name];
        let entries: Vec<Expr> = v
            .entries()
            .iter()
            .map(|e| simplify_arguments(&put(e)))
            .collect::<Result<_, _>>()?;
        let replaced = simplify_value(&v.with_entries(&entries))?;
        d.quantities.insert(name, replaced);
    }
    Ok(())
}

/// `e` with the argument of each call simplified: the phase β ω3 t + θ of the solution, once
/// the moments are put into β.
fn simplify_arguments(e: &Expr) -> Result<Expr, DeriveError> {
    let walk = |xs: &[Expr]| -> Result<Vec<Expr>, DeriveError> {
        xs.iter().map(simplify_arguments).collect()
    };
    Ok(match e {
        Expr::Call(f, args) => Expr::Call(
            f.clone(),
            args.iter().map(cas::simplify).collect::<Result<_, _>>()?,
        ),
        Expr::Add(xs) => Expr::add(walk(xs)?),
        Expr::Mul(xs) => Expr::mul(walk(xs)?),
        Expr::Pow(b, k) => Expr::pow(simplify_arguments(b)?, (**k).clone()),
        other => other.clone(),
    })
}
