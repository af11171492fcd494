//! Which values a scene's symbols take: either sign (coordinates, the time, a symbol given a
//! negative value), or angles that matter only up to whole turns. The presentation pass takes
//! every other symbol positive.

use super::{Scene, Shape};
use crate::cas::Expr;
use std::collections::BTreeSet;

/// Where the random points of the random-point tests (`numeric::random_points`) lie: every symbol in [0.4, 1.4), positive
/// and away from 0, where a mass or a moment in a denominator vanishes, and within a factor
/// 3.5 of the others, so that no term of a degree-30 expression over- or underflows.
pub const SAMPLE_FROM: f64 = 0.4;

impl Scene {
    /// How the scene typesets its names (its `tex`), for the printers.
    pub fn names(&self) -> crate::notation::Names {
        crate::notation::Names::of(&self.tex)
    }

    /// The names of the several results of the step `step` (numbered, for a name that is no
    /// author's step).
    pub fn result_names<'a>(&'a self, step: &'a str) -> super::ResultNames<'a> {
        match self.steps.iter().find(|s| s.name == step) {
            Some(s) => s.result_names(),
            None => super::ResultNames::numbered(step),
        }
    }

    /// Whether `point` lies in the scene's domain: every assumption whose names the point
    /// gives holds there (the others say nothing of it).
    pub fn in_domain(&self, point: &std::collections::BTreeMap<String, f64>) -> bool {
        self.assumptions.iter().all(|a| {
            let gap = Expr::minus(a.larger.clone(), a.smaller.clone());
            match gap.eval(&|s| point.get(s).copied().filter(|_| s != "pi")) {
                Ok(x) => x > 0.0,
                // A name the point does not give: this assumption is not about it.
                Err(_) => !gap
                    .symbols()
                    .iter()
                    .all(|s| s == "pi" || point.contains_key(s)),
            }
        })
    }

    /// The names that take either sign: the coordinates, their rates and accelerations, the
    /// time, and a symbol the scene gives a negative value (in `[numeric]` or a variant: a
    /// position y = −0.7). Every other symbol of a scene is a mass, a length or a constant,
    /// taken positive, so that √(a²) is printed a only where a is never negative.
    pub fn signed_names(&self) -> BTreeSet<String> {
        let mut out: BTreeSet<String> = self
            .coordinates
            .keys()
            .flat_map(|q| [q.clone(), format!("{q}'"), format!("{q}''")])
            .collect();
        out.insert("t".into());
        let negative = |x: f64| x < 0.0;
        out.extend(
            self.values
                .iter()
                .filter(|(_, v)| negative(**v))
                .map(|(n, _)| n.clone()),
        );
        for v in self.problem.iter().flat_map(|p| &p.variants) {
            out.extend(
                v.values
                    .iter()
                    .filter(|(_, e)| e.eval(&|_| None).is_ok_and(negative))
                    .map(|(n, _)| n.clone()),
            );
        }
        out
    }

    /// The symbols that the scene uses only as whole-number multiples in angles (the bodies'
    /// rotations, and sines and cosines in `omega`, `axis`, vectors and definitions): their
    /// values matter only up to whole turns.
    pub fn whole_turn_symbols(&self) -> BTreeSet<String> {
        let mut angles = BTreeSet::new();
        let mut elsewhere: BTreeSet<String> = BTreeSet::new();
        for b in &self.bodies {
            for (_, a) in &b.rotations {
                match whole_multiple(a) {
                    Some(s) => {
                        angles.insert(s.clone());
                    }
                    None => elsewhere.extend(a.symbols()),
                }
            }
            for e in b.dimensions().into_iter().chain(&b.shift) {
                elsewhere.extend(e.symbols());
            }
            if let Shape::Points(pts) = &b.shape {
                for (_, at) in pts {
                    at.iter().for_each(|e| elsewhere.extend(e.symbols()));
                }
            }
        }
        for v in self
            .omega
            .iter()
            .chain(&self.axis)
            .chain(self.vectors.values())
        {
            v.iter()
                .for_each(|e| angle_uses(e, &mut angles, &mut elsewhere));
        }
        for e in self.definitions.values() {
            angle_uses(e, &mut angles, &mut elsewhere);
        }
        angles.retain(|s| !elsewhere.contains(s));
        angles
    }
}

/// `alpha` or `2*alpha`: a whole multiple of one symbol.
fn whole_multiple(e: &Expr) -> Option<&String> {
    match e {
        Expr::Sym(s) => Some(s),
        Expr::Mul(v) => match v.as_slice() {
            [Expr::Num(k), Expr::Sym(s)] if k.is_integer() => Some(s),
            _ => None,
        },
        _ => None,
    }
}

/// Sorts the symbols of `e`: those inside `sin` or `cos` as a whole multiple into `angles`,
/// every other use into `elsewhere`.
fn angle_uses(e: &Expr, angles: &mut BTreeSet<String>, elsewhere: &mut BTreeSet<String>) {
    match e {
        Expr::Call(f, args) if (f == "sin" || f == "cos") && args.len() == 1 => {
            match whole_multiple(&args[0]) {
                Some(s) => {
                    angles.insert(s.clone());
                }
                None => angle_uses(&args[0], angles, elsewhere),
            }
        }
        Expr::Sym(s) => {
            elsewhere.insert(s.clone());
        }
        Expr::Num(_) => {}
        Expr::Add(v) | Expr::Mul(v) | Expr::List(v) | Expr::Call(_, v) => {
            v.iter().for_each(|x| angle_uses(x, angles, elsewhere))
        }
        Expr::Pow(a, b) | Expr::Index(a, b) => {
            angle_uses(a, angles, elsewhere);
            angle_uses(b, angles, elsewhere);
        }
    }
}
