//! `assume`: the physics' domain, as inequalities between the scene's names (`"R > r"`,
//! `"0 < beta < beta0"`), each read, checked against the scene's values, and checked to leave
//! room for the random points.

use super::{Validator, content_start};
use crate::base::rng::Rng;
use crate::cas::Expr;
use crate::scene::SAMPLE_FROM;
use crate::scene::error::SceneError;
use crate::scene::raw::RawScene;
use crate::scene::types::Assumption;
use std::collections::{BTreeMap, BTreeSet};

/// Points drawn, at most, to find one inside the domain: where none of these is, the
/// random-point tests could test nothing.
const ROOM_TRIES: usize = 2000;

/// The comparison signs, the longer first; `true` where the left side is the smaller.
const SIGNS: &[(&str, bool)] = &[
    ("<=", true),
    (">=", false),
    ("≤", true),
    ("≥", false),
    ("<", true),
    (">", false),
];

impl Validator<'_> {
    /// Every `assume` entry: a chain `a < b < c` is two inequalities.
    pub(super) fn assumptions(
        &self,
        raw: &RawScene,
        names: &BTreeSet<String>,
        values: &BTreeMap<String, f64>,
    ) -> Result<Vec<Assumption>, SceneError> {
        let mut out = Vec::new();
        for (i, t) in raw.assume.iter().enumerate() {
            let field = format!("assume[{i}]");
            let start = content_start(t);
            let text = t.get_ref();
            let (sides, smaller_first) = split(text);
            if sides.len() < 2 {
                return Err(self.err(
                    start,
                    &field,
                    format!(
                        "`{text}` is not an inequality: write one such as \"R > r\", or a chain \
                         such as \"0 < beta < beta0\""
                    ),
                ));
            }
            let mut parsed = Vec::new();
            for (at, side) in &sides {
                parsed.push(self.parse_checked(side, start + at, &field, names, true)?);
            }
            for (k, pair) in parsed.windows(2).enumerate() {
                let (smaller, larger) = if smaller_first[k] {
                    (pair[0].clone(), pair[1].clone())
                } else {
                    (pair[1].clone(), pair[0].clone())
                };
                let a = Assumption {
                    smaller,
                    larger,
                    text: text.clone(),
                    line: self.loc.line_col(start).0,
                };
                self.holds_at_the_values(&a, values, start, &field)?;
                out.push(a);
            }
        }
        if let Some(first) = raw.assume.first() {
            self.leaves_room(&out, content_start(first))?;
        }
        Ok(out)
    }

    /// The scene's own values must lie in its domain.
    fn holds_at_the_values(
        &self,
        a: &Assumption,
        values: &BTreeMap<String, f64>,
        start: usize,
        field: &str,
    ) -> Result<(), SceneError> {
        let gap = Expr::minus(a.larger.clone(), a.smaller.clone());
        let Ok(x) = gap.eval(&|s| values.get(s).copied().filter(|_| s != "pi")) else {
            return Ok(());
        };
        if x > 0.0 {
            return Ok(());
        }
        Err(self.err(
            start,
            field,
            format!(
                "the scene's values under [numeric] break `{}`: {} is {x:.6} there, not positive; \
                 change the values or the assumption",
                a.text,
                gap.to_text()
            ),
        ))
    }

    /// Some point with each name in the random points' range, [0.4, 1.4), must satisfy every
    /// assumption, or the random-point tests could test nothing.
    fn leaves_room(&self, all: &[Assumption], start: usize) -> Result<(), SceneError> {
        let mut names: Vec<String> = all
            .iter()
            .flat_map(|a| [&a.smaller, &a.larger])
            .flat_map(|e| e.symbols())
            .filter(|s| s != "pi")
            .collect();
        names.sort();
        names.dedup();
        let mut rng = Rng::new(1);
        let inside = (0..ROOM_TRIES).any(|_| {
            let point: BTreeMap<String, f64> = names
                .iter()
                .map(|n| (n.clone(), SAMPLE_FROM + rng.uniform()))
                .collect();
            all.iter().all(|a| {
                Expr::minus(a.larger.clone(), a.smaller.clone())
                    .eval(&|s| point.get(s).copied().filter(|_| s != "pi"))
                    .is_ok_and(|x| x > 0.0)
            })
        });
        if inside {
            return Ok(());
        }
        Err(self.err(
            start,
            "assume",
            format!(
                "no values of {} between {SAMPLE_FROM} and {} satisfy every assumption, and the \
                 random-point tests draw each name there: they could test nothing; state a \
                 domain with room in that range (R > r, not R > 10*r)",
                names.join(", "),
                SAMPLE_FROM + 1.0
            ),
        ))
    }
}

/// The sides of `text` at their byte offsets, and for each sign between two sides whether the
/// left side is the smaller.
fn split(text: &str) -> (Vec<(usize, &str)>, Vec<bool>) {
    let mut sides = Vec::new();
    let mut smaller_first = Vec::new();
    let mut from = 0;
    let mut i = 0;
    while i < text.len() {
        let found = SIGNS.iter().find(|(sign, _)| text[i..].starts_with(sign));
        match found {
            Some((sign, left_smaller)) => {
                sides.push((from, &text[from..i]));
                smaller_first.push(*left_smaller);
                i += sign.len();
                from = i;
            }
            None => i += text[i..].chars().next().map_or(1, char::len_utf8),
        }
    }
    sides.push((from, &text[from..]));
    (sides, smaller_first)
}

#[cfg(test)]
mod tests {
    use super::split;

    #[test]
    fn a_chain_splits_into_its_sides_and_signs() {
        let (sides, signs) = split("0 < beta <= beta0");
        assert_eq!(sides, vec![(0, "0 "), (3, " beta "), (11, " beta0")]);
        assert_eq!(signs, vec![true, true]);
        let (sides, signs) = split("R > r");
        assert_eq!(sides, vec![(0, "R "), (3, " r")]);
        assert_eq!(signs, vec![false]);
        assert_eq!(split("R = r").0.len(), 1);
    }
}
