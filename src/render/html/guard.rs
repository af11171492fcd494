//! The build's guard: before a page is set, each formula it shows for a result is read back
//! from its printed tree (`notation::read_back`, the tree MathML, the spoken form and the
//! handouts are made from) into an expression, and checked to be that result
//! (`verify::shown_is_result`: random points, then the engine). A page that would show what was
//! not derived fails the build at the scene's line, as mechbook's bug, never a published page.

use crate::cas::Expr;
use crate::derive::step_names::Stands;
use crate::document::Page;
use crate::model::value::Value;
use crate::notation::Names;
use crate::notation::Tex;
use crate::notation::read_back::{Readable, read_back, sides};
use crate::render::RenderError;
use std::collections::{BTreeMap, BTreeSet};

/// The page's reader: the names its formulas may print, what the results among them stand
/// for, and how many formulas it read.
pub struct Guard<'a> {
    page: &'a Page,
    /// The scene's own names (symbols, coordinates and their rates, definitions, `t`, `π`).
    names: Vec<String>,
    /// Each result a formula may name (a step's, `Omega_2`), as derived.
    results: BTreeMap<String, Expr>,
    varying: BTreeSet<String>,
    pub counts: Counts,
}

/// How many formulas the guard read back and found equal, and how many it could not read (a
/// vector, a matrix, an integral, a name it does not know).
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct Counts {
    pub checked: usize,
    pub unread: usize,
}

impl<'a> Guard<'a> {
    /// The guard of one page, its names read as the scene typesets them.
    pub fn for_page(page: &'a Page) -> Guard<'a> {
        let coordinates = page.coordinates.iter().map(|(q, _)| q);
        let varying: BTreeSet<String> = coordinates
            .clone()
            .flat_map(|q| [q.clone(), format!("{q}'"), format!("{q}''")])
            .chain(["t".to_string()])
            .collect();
        let mut names: Vec<String> = page.symbols.iter().map(|(s, _)| s.clone()).collect();
        names.extend(varying.iter().cloned());
        names.extend(page.definitions.iter().map(|(d, _)| d.clone()));
        names.push("pi".into());
        let results = page
            .quantities
            .iter()
            .filter_map(|q| match &q.derived {
                Value::Scalar(e) if q.symbol.is_some() => Some((q.name.clone(), e.clone())),
                _ => None,
            })
            .collect();
        Guard {
            page,
            names,
            results,
            varying,
            counts: Counts::default(),
        }
    }

    /// The expression a printed piece shows: the result's own names first (where a step's
    /// symbol prints as a scene's, `L`, the result's reading wins), then the scene's, then the
    /// other results', each put in by its derived value. `None` where it cannot be read.
    fn shown(&self, nodes: &[crate::notation::Node], of: &[&Expr]) -> Option<Expr> {
        // A product of vectors prints `⋅` and `×` as a product of numbers does, and a matrix
        // (𝟙) as a number: only a scalar the random points can evaluate is read.
        if of.iter().any(|e| !evaluable_scalar(e)) {
            return None;
        }
        let own: Vec<String> = of.iter().flat_map(|e| e.symbols()).collect();
        let table = Readable::new(
            own.iter()
                .chain(&self.names)
                .chain(self.results.keys())
                .map(String::as_str),
            &self.page.names,
        );
        let e = read_back(nodes, &table).ok()?;
        Some(e.substitute(&|n| {
            (!own.iter().any(|o| o == n))
                .then(|| self.results.get(n).cloned())
                .flatten()
        }))
    }

    /// One line of the derivation: an author's step's against what it stands for, a built-in
    /// one's last side against the last result it derived.
    pub fn step(&mut self, st: &crate::document::Step, tex: &Tex) -> Result<(), RenderError> {
        match &st.stands_for {
            Some(stands) => self.step_line(tex, stands, st.line),
            None => {
                let exact = st.exact.as_ref().unwrap_or(&st.statement);
                match last_result(exact) {
                    Some(last) => self.printed(tex, last, self.page.line),
                    None if crate::derive::present::is_matrix_statement(exact) => self
                        .printed_matrix(
                            tex,
                            &crate::derive::present::shown_entries(exact),
                            self.page.line,
                        ),
                    None => Ok(()),
                }
            }
        }
    }

    /// One line of an author's step against what it stands for. `line` is the step's line in
    /// the scene.
    fn step_line(&mut self, tex: &Tex, stands: &Stands, line: usize) -> Result<(), RenderError> {
        let parts = sides(&tex.nodes);
        let (relation, last) = parts.last().cloned().unwrap_or((None, &[]));
        let verdict = match stands {
            // The last side, and every middle side a reader can take back: `T_beat =
            // 2π/(Ω₂ − Ω₁) = …` proves its middle too (an integral with its limits is not read).
            Stands::Value(result) => self.shown(last, &[result]).map(|last| {
                let middles = parts[1.min(parts.len() - 1)..parts.len() - 1]
                    .iter()
                    .filter_map(|(_, side)| self.shown(side, &[result]));
                middles.chain([last]).try_for_each(|shown| {
                    crate::verify::shown_is_result(&shown, result, &self.page.signed)
                        .map_err(|d| (shown, Some(result.clone()), d.by))
                })
            }),
            // Printed to six figures: within half a unit of the sixth.
            Stands::Number(w) => self
                .shown(last, &[])
                .and_then(|e| e.eval(&|_| None).ok())
                .filter(|_| matches!(relation.as_deref(), Some("≈" | "=")))
                .map(|x| {
                    let by = (x - w).abs() / w.abs().max(f64::MIN_POSITIVE);
                    match by <= 5e-6 {
                        true => Ok(()),
                        false => Err((Expr::numeral(&x.to_string()), None, by)),
                    }
                }),
            Stands::Residual(residual) => match parts.as_slice() {
                [(None, lhs), (Some(_), rhs)] => self
                    .shown(lhs, &[residual])
                    .zip(self.shown(rhs, &[residual]))
                    .map(|(a, b)| {
                        let shown = Expr::minus(a, b);
                        crate::verify::shown_is_equation(&shown, residual, &self.varying)
                            .map_err(|d| (shown, Some(residual.clone()), d.by))
                    }),
                _ => None,
            },
        };
        let Some(verdict) = verdict else {
            self.counts.unread += 1;
            return Ok(());
        };
        self.counts.checked += 1;
        verdict.map_err(|(shown, result, by)| RenderError::Misprinted {
            line,
            printed: tex.source.clone(),
            read: shown.to_text(),
            result: result.map_or_else(|| format!("{stands:?}"), |r| r.to_text()),
            by,
        })
    }

    /// A formula printed for `result` (a claim's side, a result's value): the printer's own
    /// round trip, which a wrong printer ("3 0.4⁴" for 3·0.4⁴) fails.
    pub fn printed(&mut self, tex: &Tex, result: &Expr, line: usize) -> Result<(), RenderError> {
        let parts = sides(&tex.nodes);
        let Some(shown) = parts
            .last()
            .and_then(|(_, last)| self.shown(last, &[result]))
        else {
            self.counts.unread += 1;
            return Ok(());
        };
        self.counts.checked += 1;
        self.is_result(tex, &shown, result, line)
    }

    /// `shown`, read back from `tex`, against the result it stands for: a misprint at `line`
    /// where they differ.
    fn is_result(
        &self,
        tex: &Tex,
        shown: &Expr,
        result: &Expr,
        line: usize,
    ) -> Result<(), RenderError> {
        crate::verify::shown_is_result(shown, result, &self.page.signed).map_err(|d| {
            RenderError::Misprinted {
                line,
                printed: tex.source.clone(),
                read: shown.to_text(),
                result: result.to_text(),
                by: d.by,
            }
        })
    }
}

impl Guard<'_> {
    /// A value printed under its heading (the inertia tensor): a matrix read back entry by
    /// entry, its factor in front put into each; a scalar or vector is not read here.
    pub fn printed_value(
        &mut self,
        tex: &Tex,
        derived: &Value,
        line: usize,
    ) -> Result<(), RenderError> {
        match derived {
            Value::Matrix(_) => self.printed_matrix(tex, &derived.entries(), line),
            _ => Ok(()),
        }
    }

    /// A matrix's last side read back, `factor (rows)` or `(rows)`, each entry against the
    /// result's in row-major order.
    fn printed_matrix(
        &mut self,
        tex: &Tex,
        entries: &[Expr],
        line: usize,
    ) -> Result<(), RenderError> {
        let parts = sides(&tex.nodes);
        let of: Vec<&Expr> = entries.iter().collect();
        let Some(shown) = parts
            .last()
            .and_then(|(_, last)| self.shown(last, &of))
            .and_then(|e| matrix_entries(&e))
            .filter(|shown| shown.len() == entries.len())
        else {
            self.counts.unread += 1;
            return Ok(());
        };
        self.counts.checked += 1;
        shown
            .iter()
            .zip(entries)
            .try_for_each(|(shown, result)| self.is_result(tex, shown, result, line))
    }
}

/// The entries of a matrix read back, row-major: a list of rows, or a factor times one, the
/// factor put into each entry.
fn matrix_entries(e: &Expr) -> Option<Vec<Expr>> {
    let (factor, rows) = crate::cas::factor_and_rows(e)?;
    let entries = rows.into_iter().flatten();
    Some(
        entries
            .map(|c| Expr::mul(vec![factor.clone(), c]))
            .collect(),
    )
}

/// The result a built-in line ends with (`… = M/(2πR)`), which its last side prints: a scalar
/// expression after the row's last relation.
pub fn last_result(f: &crate::notation::Formula) -> Option<&Expr> {
    use crate::notation::{Formula, Op};
    match f {
        Formula::Row(items) => match items.as_slice() {
            [.., Formula::Op(Op::Equals), Formula::Expr(e)] if !matches!(e, Expr::List(_)) => {
                Some(e)
            }
            _ => None,
        },
        _ => None,
    }
}

/// A number a key or a sheet prints for `value` (a variant's answer), read back: exact to
/// 1e-9, or within half a unit of its last figure where it is rounded to `figures`. `Ok(false)`
/// where the formula is no scalar the reader reads (a vector's entries).
pub fn printed_number(
    tex: &Tex,
    value: f64,
    figures: Option<usize>,
    line: usize,
) -> Result<bool, RenderError> {
    let parts = sides(&tex.nodes);
    let Some(shown) = parts
        .last()
        .and_then(|(_, last)| read_back(last, &Readable::new(["pi"], Names::none())).ok())
    else {
        return Ok(false);
    };
    let Ok(x) = shown.eval(&|_| None) else {
        return Ok(false);
    };
    let scale = value.abs().max(f64::MIN_POSITIVE);
    let within = match figures {
        Some(n) => 0.5 * 10f64.powi(1 - n as i32) * 10f64.powi(scale.log10().floor() as i32),
        None => crate::numeric::random_points::NUMERICALLY_ZERO * scale.max(1.0),
    };
    match (x - value).abs() <= within * (1.0 + 1e-9) {
        true => Ok(true),
        false => Err(RenderError::Misprinted {
            line,
            printed: tex.source.clone(),
            read: shown.to_text(),
            result: value.to_string(),
            by: (x - value).abs() / scale,
        }),
    }
}

/// Whether a result is a scalar of the functions the random points evaluate (no vector, no
/// matrix, no `dot` or `cross`).
fn evaluable_scalar(e: &Expr) -> bool {
    let mut ok = true;
    e.walk(&mut |x| {
        ok &= match x {
            Expr::Call(f, args) => crate::cas::arity(f) == Some(args.len()),
            Expr::List(_) | Expr::Index(..) => false,
            _ => true,
        }
    });
    ok
}
