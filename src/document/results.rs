//! A page's results: each derived quantity (with its value at the scene's numbers), the exact
//! principal axes, and the principal moments at the scene's values by both routes.

use crate::cas::Expr;
use crate::derive::ExactBasis;
use crate::model::catalogue::quantity;
use crate::model::value::{Value, eval_at};
use crate::numeric::eigen::Eigenspace;
use crate::pipeline::SceneReport;

#[derive(Debug, Clone)]
pub struct Quantity {
    pub name: String,
    /// For a result of the author's steps, what the page calls it: the step's name, a mode's
    /// (`Omega_1`), or the unknown a `solve` found (`x1''`, not `acc_1`); printed as `symbol =
    /// value` under no heading of its own. `None` for the catalogue's quantities, which the
    /// page heads with their names in words ("Inertia tensor").
    pub symbol: Option<Expr>,
    /// The value in the form the page prints it.
    pub value: Value,
    /// The value as derived, which the build checks `value` shows (`render/guard.rs`).
    pub derived: Value,
    /// Each entry at the scene's values, row-major (`None` where a symbol has no value).
    pub numbers: Vec<Option<f64>>,
    /// The value at the scene's numbers, when that says something the exact form does not.
    pub at: Option<At>,
    /// Whether a page lists it: the integrand and the position are working, not results.
    pub is_result: bool,
    /// A matrix with its entries' common factor out, as the page prints it.
    pub matrix: Option<crate::cas::MatrixForm>,
}

impl Quantity {
    /// The value as the page prints it: a matrix with its factor out, else `value`.
    pub fn formula(&self) -> crate::notation::Formula {
        match &self.matrix {
            Some(form) => crate::derive::present::matrix_formula(form),
            None => crate::notation::Formula::Expr(self.value.to_expr()),
        }
    }
}

/// A result at the scene's numbers: the values of the symbols it contains, and its entries.
#[derive(Debug, Clone)]
pub struct At {
    pub symbols: Vec<(String, f64)>,
    pub numbers: Vec<f64>,
    /// Each of those symbols' unit, where the scene gives one.
    pub units: std::collections::BTreeMap<String, String>,
    /// The unit of a scalar result's number (see `verify::dimensions::unit_of`).
    pub unit: Option<String>,
}

/// An exact principal moment, its multiplicity and its axis or plane.
#[derive(Debug, Clone)]
pub struct PrincipalAxis {
    pub value: Expr,
    /// At the scene's values.
    pub number: Option<f64>,
    pub multiplicity: u32,
    pub basis: ExactBasis,
}

/// The principal moments at the scene's values: exact (or from the closed form), and from the
/// eigen-solver on the exact tensor, with how far apart they are.
#[derive(Debug, Clone)]
pub struct PrincipalValues {
    /// The eigenvalue's letter, by its TeX name (`lambda`).
    pub letter: String,
    /// Ascending, each repeated by its multiplicity.
    pub exact: Vec<f64>,
    pub numeric: Vec<Eigenspace>,
    /// The largest difference, relative to the largest moment.
    pub error: f64,
    /// Whether `exact` comes from the trigonometric closed form (then the axes are numeric).
    pub closed_form: bool,
    /// The scene's values they are taken at, and those values' units where the scene gives
    /// them.
    pub values: Vec<(String, f64)>,
    pub units: std::collections::BTreeMap<String, String>,
}

/// The derived quantities, then the expressions of the author's steps (their equations of
/// motion are steps, not values).
pub(super) fn quantities(r: &SceneReport) -> Vec<Quantity> {
    let values = &r.scene.values;
    // Each normal mode under its own name, `Omega_1`, `Omega_2`, as the page states them; a
    // step's result in the form its derivation prints (the textbook's, proven equal), its
    // numbers from the exact result.
    // In the derivation's order, as the page derives them (not alphabetically).
    let in_order = r
        .scene
        .steps
        .iter()
        .filter_map(|step| r.derivation.named.get_key_value(&step.name));
    let named = in_order.flat_map(|(name, s)| {
        let names = r.scene.result_names(name);
        let printed = r.derivation.printed.get(name).map(|p| p.values(names));
        let exact = s.values(names);
        let shown = printed
            .filter(|p| p.len() == exact.len())
            .unwrap_or_else(|| exact.clone());
        // What each result is called where the derivation states it, by the result's name: a
        // solution's unknown, a state of rest's coordinate, the squared frequency Ω_k² about
        // the k-th state.
        use crate::derive::step_names::StepResult;
        use crate::scene::mode_name;
        let symbols: std::collections::BTreeMap<String, Expr> = match s {
            StepResult::Solution(pairs) => pairs
                .iter()
                .enumerate()
                .map(|(k, (u, _))| (names.kth(k), Expr::sym(u)))
                .collect(),
            StepResult::Equilibria {
                coordinate, zeros, ..
            } => (0..zeros.len())
                .map(|k| (names.kth(k), Expr::sym(coordinate)))
                .collect(),
            StepResult::Stability { cases, .. } => (0..cases.len())
                .map(|k| {
                    let omega = Expr::sym(&mode_name("Omega", k));
                    (names.kth(k), Expr::pow(omega, Expr::int(2)))
                })
                .collect(),
            _ => Default::default(),
        };
        exact
            .into_iter()
            .zip(shown)
            .map(move |((name, e), (_, p))| {
                let symbol = symbols
                    .get(&name)
                    .cloned()
                    .unwrap_or_else(|| Expr::sym(&name));
                (name, Some(symbol), Value::Scalar(e), Value::Scalar(p))
            })
    });
    r.derivation
        .quantities
        .iter()
        .map(|(name, v)| (name.clone(), None, v.clone(), v.clone()))
        .chain(named)
        .map(|(name, symbol, v, shown)| Quantity {
            name: name.clone(),
            symbol,
            numbers: v
                .entries()
                .iter()
                .map(|e| eval_at(e, values).ok())
                .collect(),
            at: at_numbers(&v, values).map(|at| with_units(at, &r.scene, &v)),
            derived: v,
            value: shown,
            is_result: name != quantity::INTEGRAND && name != quantity::POSITION,
            matrix: r.derivation.matrices.get(&name).cloned(),
        })
        .collect()
}

/// The value at the scene's numbers: none when it is a number or a bare symbol already, a
/// symbol in it has no value, or it is not a finite real number there.
fn at_numbers(v: &Value, values: &crate::model::value::Values) -> Option<At> {
    // π is a number, not one of the scene's symbols.
    let symbols: std::collections::BTreeSet<String> = v
        .entries()
        .iter()
        .flat_map(|e| e.symbols())
        .filter(|s| values.contains_key(s))
        .collect();
    let numbers = v.numbers_at(values).ok()?;
    // A state of rest that is not real at these values (an arccos past ±1) has no number to
    // show: NaN would be printed.
    if numbers.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let plain = v
        .entries()
        .iter()
        .all(|e| matches!(e, Expr::Num(_) | Expr::Sym(_)));
    if symbols.is_empty() || plain {
        return None;
    }
    Some(At {
        symbols: symbols
            .into_iter()
            .map(|k| (k.clone(), values[&k]))
            .collect(),
        numbers,
        units: Default::default(),
        unit: None,
    })
}

/// The units of a result at the scene's numbers: its symbols', and a scalar's own.
fn with_units(mut at: At, scene: &crate::scene::Scene, v: &Value) -> At {
    at.units = at
        .symbols
        .iter()
        .filter_map(|(k, _)| Some((k.clone(), scene.units.get(k)?.text.clone())))
        .collect();
    at.unit = match v {
        Value::Scalar(e) => crate::verify::dimensions::unit_of(scene, e),
        _ => None,
    };
    at
}

pub(super) fn principal_axes(r: &SceneReport) -> Vec<PrincipalAxis> {
    r.derivation
        .eigen
        .iter()
        .flat_map(|e| e.spaces.iter())
        .map(|sp| PrincipalAxis {
            value: sp.value.clone(),
            number: eval_at(&sp.value, &r.scene.values).ok(),
            multiplicity: sp.multiplicity,
            basis: sp.basis.clone(),
        })
        .collect()
}

pub(super) fn principal_values(r: &SceneReport) -> Option<PrincipalValues> {
    let p = r.verification.principal.as_ref()?;
    Some(PrincipalValues {
        letter: r
            .derivation
            .eigen
            .as_ref()
            .map_or("lambda", |e| &e.letter)
            .to_string(),
        exact: p.exact.clone(),
        numeric: p.numeric.clone(),
        error: p.error,
        closed_form: p.closed_form,
        values: r
            .scene
            .values
            .iter()
            .map(|(k, v)| (k.clone(), *v))
            .collect(),
        units: r
            .scene
            .values
            .keys()
            .filter_map(|k| Some((k.clone(), r.scene.units.get(k)?.text.clone())))
            .collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_result_at_the_numbers_names_its_symbols_but_not_pi() {
        let values = [("R".to_string(), 2.0), ("M".to_string(), 3.0)].into();
        let two_pi_r = Expr::mul(vec![Expr::int(2), Expr::sym("pi"), Expr::sym("R")]);
        let at = at_numbers(&Value::Scalar(two_pi_r), &values).unwrap();
        assert_eq!(at.symbols, vec![("R".to_string(), 2.0)]);
        assert_eq!(at.numbers, vec![4.0 * std::f64::consts::PI]);
        // A bare symbol or a number has nothing to add, nor has a symbol without a value.
        assert!(at_numbers(&Value::Scalar(Expr::sym("M")), &values).is_none());
        assert!(at_numbers(&Value::Scalar(Expr::int(4)), &values).is_none());
        let unknown = Expr::mul(vec![Expr::sym("R"), Expr::sym("h")]);
        assert!(at_numbers(&Value::Scalar(unknown), &values).is_none());
    }
}

/// A result of several entries that is no vector of space: a state of rest of several
/// coordinates (each one's value, in the scene's order of coordinates), or the leading principal
/// minors of the stiffness about it. `rest_1`, `upright_1`: the step's name and the state's
/// number, as the page lists them.
#[derive(Debug, Clone)]
pub struct ListResult {
    pub name: String,
    pub entries: Vec<Expr>,
    /// Each entry at the scene's values; none where it is not a finite real number there.
    pub numbers: Vec<Option<f64>>,
}

/// Each state of rest of several coordinates, and the minors about each, in the derivation's
/// order.
pub(super) fn list_results(r: &SceneReport) -> Vec<ListResult> {
    use crate::derive::step_names::StepResult;
    let mut out = Vec::new();
    for step in &r.scene.steps {
        let lists: Vec<Vec<Expr>> = match r.derivation.named.get(&step.name) {
            Some(StepResult::RestStates { states, .. }) => states
                .iter()
                .map(|state| state.iter().map(|z| z.value.clone()).collect())
                .collect(),
            Some(StepResult::RestStability { cases, .. }) => {
                cases.iter().map(|c| c.minors.clone()).collect()
            }
            _ => continue,
        };
        for (k, entries) in lists.into_iter().enumerate() {
            let numbers = entries
                .iter()
                .map(|e| eval_at(e, &r.scene.values).ok().filter(|x| x.is_finite()))
                .collect();
            out.push(ListResult {
                name: step.result_names().kth(k),
                entries,
                numbers,
            });
        }
    }
    out
}
