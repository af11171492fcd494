//! A claim's two sides as a box prints them: a claim on a result the page states (`Omega`,
//! `acc_3`) takes that line's symbol and form, so that "Correct:" reads as the step above it
//! does (Ω = √(5g/(7(R − r))), T = 2g m₁m₂/(m₁ + m₂)); any other claim takes its quantity and
//! the derived side in a textbook's form (`ClaimResult::shown`).

use super::Page;
use crate::model::catalogue::quantity_symbol;
use crate::notation::{Formula, Op};

impl Page {
    /// The line that states result `name` as `symbol = value`: the line of the author's step
    /// `name`, or the k-th line of a step of several results (`acc_3`, `Omega_2`).
    fn result_line(&self, name: &str) -> Option<(&Formula, &Formula)> {
        let mut i = 0;
        while i < self.steps.len() {
            let Some(author) = self.steps[i].author.as_deref() else {
                i += 1;
                continue;
            };
            let lines = self.steps[i..]
                .iter()
                .take_while(|s| s.author.as_deref() == Some(author))
                .count();
            let k = match lines {
                1 if author == name => Some(0),
                1 => None,
                _ => (0..lines).find(|&k| self.steps[i + k].result.as_deref() == Some(name)),
            };
            if let Some(k) = k {
                return match &self.steps[i + k].statement {
                    Formula::Row(row) => match row.as_slice() {
                        [lhs, Formula::Op(Op::Equals), rhs @ Formula::Expr(_)]
                            if !matches!(lhs, Formula::Number(_)) =>
                        {
                            Some((lhs, rhs))
                        }
                        _ => None,
                    },
                    _ => None,
                };
            }
            i += lines;
        }
        None
    }

    /// The line of result a claim's `quantity` names alone, if the page states it.
    fn claim_line(&self, i: usize) -> Option<(&Formula, &Formula)> {
        match &self.claims[i].quantity {
            Some(crate::cas::Expr::Sym(name)) => self.result_line(name),
            _ => None,
        }
    }

    /// Claim `i`'s left side: the symbol its author gives it, else the symbol of the line that
    /// states its result (T for `acc_3`), else its quantity where every name in it prints as a
    /// symbol (I₁₁, L², the scene's own), else none, and the page prints the claim's formula
    /// alone: never a name of mechbook's (`plane_distance_squared`) as a word.
    pub fn claim_left(&self, i: usize) -> Option<Formula> {
        let c = &self.claims[i];
        if let Some(tex) = &c.tex {
            return Some(Formula::Tex(tex.clone()));
        }
        if let Some((symbol, _)) = self.claim_line(i) {
            return Some(symbol.clone());
        }
        // Each result the page states by its line's symbol: acc₁ + acc₂ is ẍ₁ + ẍ₂.
        let q = c.quantity.as_ref().map(|q| {
            q.substitute(&|name| match self.result_line(name) {
                Some((Formula::Expr(symbol), _)) => Some(symbol.clone()),
                _ => None,
            })
        });
        match q {
            Some(q) if !names_a_word(&q, &self.names) => {
                Some(Formula::Tex(q.to_tex_named(&self.names, &quantity_symbol)))
            }
            _ => None,
        }
    }

    /// `left = side` for claim `i` (its left side by [`Page::claim_left`]), or `side` alone
    /// where it has none: the row both handouts display for each side of a scalar claim.
    pub fn claim_row(&self, i: usize, side: Formula) -> Formula {
        match self.claim_left(i) {
            Some(left) => Formula::Row(vec![left, Formula::Op(Op::Equals), side]),
            None => side,
        }
    }

    /// Claim `i`'s derived side as the page prints it: the form of the line that states its
    /// result, else the textbook's form of the derived value, else `None` (the value as it is).
    pub fn claim_derived(&self, i: usize) -> Option<Formula> {
        if let Some((_, rhs)) = self.claim_line(i) {
            return Some(rhs.clone());
        }
        // A matrix as its result prints: its factor out.
        if let Some(crate::cas::Expr::Sym(name)) = &self.claims[i].quantity
            && let Some(q) = self
                .quantities
                .iter()
                .find(|q| q.symbol.is_none() && &q.name == name && q.matrix.is_some())
        {
            return Some(q.formula());
        }
        self.claims[i].shown.clone().map(Formula::Expr)
    }
}

/// Whether an expression names something that would print as a word: a derived quantity with
/// no symbol, or a step's result the scene gives no `tex`.
fn names_a_word(e: &crate::cas::Expr, names: &crate::notation::Names) -> bool {
    e.symbols().iter().any(|s| {
        quantity_symbol(s).is_none() && crate::cas::prints_as_word(s, &|n| names.typesets(n))
    })
}
