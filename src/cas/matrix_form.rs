//! A matrix as a textbook prints it: the entries' common factor in front and what is left in
//! the matrix, m a²/12 (52 −6 −9; −6 40 −18; −9 −18 20) for a box about its corner (the notes'
//! eqs (31) and (39) print tensors so). Nine entries each over its own denominator run past a
//! page's edge; the factor out keeps a tensor inside it.

use super::engine::{self, EngineError};
use super::expr::Expr;
use super::positive::is_zero;
use super::present::{Positive, PrintedLength, present, size};
use super::print::split_sign;
use super::written::as_written;

/// A matrix with its entries' common factor taken out: `factor` times `rows`.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MatrixForm {
    pub factor: Expr,
    pub rows: Vec<Vec<Expr>>,
}

impl MatrixForm {
    /// The matrix it stands for, each entry the factor times the printed entry (not expanded).
    pub fn product(&self) -> Vec<Vec<Expr>> {
        self.rows
            .iter()
            .map(|row| {
                row.iter()
                    .map(|e| Expr::mul(vec![self.factor.clone(), e.clone()]))
                    .collect()
            })
            .collect()
    }
}

/// A matrix written as a factor times a list of rows (`m*a^2*[[2/3, -1/4, …], …]`, or the rows
/// alone with the factor 1): the factor and the rows.
pub fn factor_and_rows(e: &Expr) -> Option<(Expr, Vec<Vec<Expr>>)> {
    let (factor, rows) = match e {
        Expr::List(rows) => (Expr::int(1), rows),
        Expr::Mul(factors) => {
            let mut lists = factors.iter().filter_map(|f| match f {
                Expr::List(rows) => Some(rows),
                _ => None,
            });
            let rows = lists.next()?;
            if lists.next().is_some() {
                return None;
            }
            let rest = factors.iter().filter(|f| !matches!(f, Expr::List(_)));
            (Expr::mul(rest.cloned().collect()), rows)
        }
        _ => return None,
    };
    let rows = rows
        .iter()
        .map(|row| match row {
            Expr::List(cells) => Some(cells.clone()),
            _ => None,
        })
        .collect::<Option<Vec<_>>>()?;
    Some((factor, rows))
}

/// The matrix with its common factor out, each part in its presented form; `None` where there
/// is no factor but 1 or fewer than two entries are not zero (a factor in front of one entry
/// says nothing). The factor is positive where its number is: a tensor's diagonal stays
/// positive inside. An author's `written` form (an agreeing claim's value) wins where the
/// engine proves it equal entry by entry, as written.
pub fn matrix_form(
    rows_as_derived: &[Vec<Expr>],
    written: Option<&Expr>,
    positive: Positive,
    length: PrintedLength,
) -> Result<Option<MatrixForm>, EngineError> {
    if let Some((factor, cells)) = written.and_then(factor_and_rows)
        && !factor.is_one()
        && cells.len() == rows_as_derived.len()
        && equal_entries(&factor, &cells, rows_as_derived, positive)?
    {
        return Ok(Some(MatrixForm {
            factor: as_written(&factor, positive),
            rows: cells
                .iter()
                .map(|r| r.iter().map(|c| as_written(c, positive)).collect())
                .collect(),
        }));
    }
    let nonzero: Vec<Expr> = rows_as_derived
        .iter()
        .flatten()
        .filter(|e| !e.is_zero())
        .cloned()
        .collect();
    if nonzero.len() < 2 {
        return Ok(None);
    }
    let content = engine::simplify(&engine::content(&nonzero)?)?;
    let (_, factor) = split_sign(&content);
    if factor.is_one() {
        return Ok(None);
    }
    let rows = rows_as_derived
        .iter()
        .map(|row| {
            row.iter()
                .map(|e| {
                    let entry = engine::simplify(&Expr::over(e.clone(), factor.clone()))?;
                    present(&entry, positive, length)
                })
                .collect::<Result<Vec<_>, _>>()
        })
        .collect::<Result<Vec<_>, _>>()?;
    // A number alone goes in front only of numbers: 1/60 before 30kHh + 60kH² + … runs wider
    // than the fractions it replaces, which the measure below undercounts.
    if factor.symbols().is_empty() && rows.iter().flatten().any(|e| !e.symbols().is_empty()) {
        return Ok(None);
    }
    let factor = present(&factor, positive, length)?;
    // Taken out only where the matrix prints narrower.
    let narrower = size(&factor, length) + width(&rows, length) < width(rows_as_derived, length);
    Ok(narrower.then_some(MatrixForm { factor, rows }))
}

/// A matrix's printed width, roughly: its columns' widest entries side by side.
fn width(rows: &[Vec<Expr>], length: PrintedLength) -> usize {
    let columns = rows.iter().map(Vec::len).max().unwrap_or(0);
    (0..columns)
        .map(|j| {
            rows.iter()
                .filter_map(|r| r.get(j))
                .map(|e| size(e, length))
                .max()
                .unwrap_or(0)
        })
        .sum()
}

/// Whether `factor` times each of `cells` is the entry of `rows` in its place.
fn equal_entries(
    factor: &Expr,
    cells: &[Vec<Expr>],
    rows: &[Vec<Expr>],
    positive: Positive,
) -> Result<bool, EngineError> {
    for (cell_row, row) in cells.iter().zip(rows) {
        if cell_row.len() != row.len() {
            return Ok(false);
        }
        for (c, e) in cell_row.iter().zip(row) {
            let product = Expr::mul(vec![factor.clone(), c.clone()]);
            if !is_zero(&Expr::minus(product, e.clone()), positive)? {
                return Ok(false);
            }
        }
    }
    Ok(true)
}
