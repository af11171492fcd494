//! `[coordinates]` and `[[step]]`: the author's own derivation. Each step names the result of one
//! operation on the scene's names, its coordinates (with their rates `q'`, `q''` and the time
//! `t`) and the steps before it, so a step can only use what comes earlier: no cycle.

use super::{Validator, content_start, is_identifier};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::raw::{RawScene, RawStep, Text};
use crate::scene::types::{AuthorStep, Operation};
use std::collections::{BTreeMap, BTreeSet};

/// The operations a step may name, one per step.
const OPERATIONS: [&str; 5] = ["be", "differentiate", "lagrange", "linearise", "frequency"];

/// What an earlier step holds, for the operations that take a step by name.
#[derive(Clone, Copy, PartialEq)]
enum Holds {
    Expression,
    /// Equations of motion from `lagrange`.
    Motion,
    /// Linear equations of motion from `linearise`.
    Linear,
}

/// Each coordinate and its meaning.
type Coordinates = BTreeMap<String, String>;

/// The most steps in one scene: a derivation of a page or two.
pub const MAX_STEPS: usize = 64;

impl Validator<'_> {
    /// `[coordinates]`: names not taken by anything else in the scene.
    pub(super) fn coordinates(
        &self,
        raw: &RawScene,
        taken: &BTreeSet<String>,
    ) -> Result<Coordinates, SceneError> {
        let mut out = BTreeMap::new();
        for (name, meaning) in &raw.coordinates {
            let n = name.get_ref();
            let field = format!("coordinates.{n}");
            if !is_identifier(n) || n == "t" {
                return Err(self.err(
                    name.span().start,
                    &field,
                    "a coordinate's name is a letter followed by letters, digits or single \
                     underscores, and not `t` (the time)",
                ));
            }
            if taken.contains(n) {
                return Err(self.err(
                    name.span().start,
                    &field,
                    format!(
                        "`{n}` is already a symbol, definition or derived quantity of this \
                         scene; a coordinate needs a name of its own"
                    ),
                ));
            }
            out.insert(n.clone(), meaning.get_ref().clone());
        }
        Ok(out)
    }

    /// Every `[[step]]`, each using only the names before it.
    pub(super) fn steps(
        &self,
        raw: &RawScene,
        names: &BTreeSet<String>,
        coordinates: &BTreeMap<String, String>,
    ) -> Result<Vec<AuthorStep>, SceneError> {
        if raw.steps.len() > MAX_STEPS {
            return Err(self.err(
                raw.steps[MAX_STEPS].span().start,
                "step",
                format!(
                    "{} steps; a scene holds at most {MAX_STEPS}: split the derivation into \
                     scenes",
                    raw.steps.len()
                ),
            ));
        }
        let mut scope = names.clone();
        for q in coordinates.keys() {
            scope.extend([q.clone(), format!("{q}'"), format!("{q}''")]);
        }
        scope.insert("t".into());
        let mut earlier: BTreeMap<String, Holds> = BTreeMap::new();
        let mut steps = Vec::new();
        for (i, s) in raw.steps.iter().enumerate() {
            let field = format!("step[{i}]");
            let step = self.step(
                s.get_ref(),
                s.span().start,
                &field,
                &scope,
                &earlier,
                coordinates,
            )?;
            let holds = match step.op {
                Operation::Lagrange { .. } => Holds::Motion,
                Operation::Linearise { .. } => Holds::Linear,
                _ => Holds::Expression,
            };
            earlier.insert(step.name.clone(), holds);
            scope.insert(step.name.clone());
            steps.push(step);
        }
        Ok(steps)
    }

    fn step(
        &self,
        s: &RawStep,
        offset: usize,
        field: &str,
        scope: &BTreeSet<String>,
        earlier: &BTreeMap<String, Holds>,
        coordinates: &BTreeMap<String, String>,
    ) -> Result<AuthorStep, SceneError> {
        let name = s.name.get_ref();
        if !is_identifier(name) || scope.contains(name) {
            return Err(self.err(
                content_start(&s.name),
                &format!("{field}.name"),
                format!(
                    "`{name}` cannot name a step: a step's name is a letter followed by letters, \
                     digits or single underscores, not yet used in this scene (not a symbol, \
                     coordinate, quantity or earlier step)"
                ),
            ));
        }
        let given: Vec<&str> = [
            s.be.as_ref().map(|_| "be"),
            s.differentiate.as_ref().map(|_| "differentiate"),
            s.lagrange.as_ref().map(|_| "lagrange"),
            s.linearise.as_ref().map(|_| "linearise"),
            s.frequency.as_ref().map(|_| "frequency"),
        ]
        .into_iter()
        .flatten()
        .collect();
        if given.len() != 1 {
            return Err(self.err(
                offset,
                field,
                format!(
                    "a step does one thing: give exactly one of {} (this one gives {})",
                    OPERATIONS.join(", "),
                    if given.is_empty() {
                        "none".to_string()
                    } else {
                        given.join(" and ")
                    }
                ),
            ));
        }
        let expr = |t: &Text, key: &str| {
            self.rates_of_coordinates(t, &format!("{field}.{key}"), coordinates)?;
            self.claim_expr(t, &format!("{field}.{key}"), scope)
        };
        let op = if let Some(be) = &s.be {
            Operation::Be(expr(be, "be")?)
        } else if let Some(of) = &s.differentiate {
            let Some(by) = &s.by else {
                return Err(self.err(
                    offset,
                    field,
                    "`differentiate` needs `by`: a symbol, a coordinate or its rate, or `t` for \
                     the time derivative",
                ));
            };
            if !scope.contains(by.get_ref()) || earlier.contains_key(by.get_ref()) {
                return Err(self.err(
                    content_start(by),
                    &format!("{field}.by"),
                    format!(
                        "cannot differentiate by `{}`: not a symbol, coordinate, rate or `t` \
                         of this scene",
                        by.get_ref()
                    ),
                ));
            }
            Operation::Differentiate {
                of: expr(of, "differentiate")?,
                by: by.get_ref().clone(),
            }
        } else if let Some(of) = &s.lagrange {
            self.earlier(of, field, "lagrange", Holds::Expression, earlier)?;
            if coordinates.is_empty() {
                return Err(self.err(
                    content_start(of),
                    &format!("{field}.lagrange"),
                    "`lagrange` needs generalised coordinates: name them under [coordinates]",
                ));
            }
            Operation::Lagrange {
                of: of.get_ref().clone(),
            }
        } else if let Some(of) = &s.linearise {
            self.earlier(of, field, "linearise", Holds::Motion, earlier)?;
            let mut about = BTreeMap::new();
            for (q, value) in &s.about {
                if !coordinates.contains_key(q.get_ref()) {
                    return Err(self.err(
                        q.span().start,
                        &format!("{field}.about.{}", q.get_ref()),
                        format!(
                            "`{}` is not a coordinate; `about` gives each coordinate's value at \
                             the state of rest (the coordinates are {})",
                            q.get_ref(),
                            coordinates.keys().cloned().collect::<Vec<_>>().join(", ")
                        ),
                    ));
                }
                about.insert(
                    q.get_ref().clone(),
                    self.claim_expr(
                        value,
                        &format!("{field}.about.{}", q.get_ref()),
                        &names_only(scope, coordinates),
                    )?,
                );
            }
            Operation::Linearise {
                of: of.get_ref().clone(),
                about,
            }
        } else {
            let of = s.frequency.as_ref().expect("one operation is given");
            self.earlier(of, field, "frequency", Holds::Linear, earlier)?;
            Operation::Frequency {
                of: of.get_ref().clone(),
            }
        };
        if !s.about.is_empty() && !matches!(op, Operation::Linearise { .. }) {
            return Err(self.err(
                offset,
                &format!("{field}.about"),
                "`about` is the state a `linearise` step expands about; this step has none",
            ));
        }
        if !matches!(op, Operation::Lagrange { .. }) && !s.start.is_empty() {
            return Err(self.err(
                offset,
                &format!("{field}.start"),
                "`start` is the initial state of a `lagrange` step's numeric check; this step \
                 has none",
            ));
        }
        let mut start = BTreeMap::new();
        for (k, v) in &s.start {
            if !scope.contains(k.get_ref()) || !v.get_ref().is_finite() {
                return Err(self.err(
                    k.span().start,
                    &format!("{field}.start.{}", k.get_ref()),
                    "`start` gives finite values of the coordinates and their rates (`\"phi'\" = \
                     0.1`)",
                ));
            }
            start.insert(k.get_ref().clone(), *v.get_ref());
        }
        let gives = match &s.gives {
            None => None,
            Some(g) => Some(self.gives(g, &format!("{field}.gives"), scope)?),
        };
        Ok(AuthorStep {
            name: name.clone(),
            why: s
                .why
                .as_ref()
                .map(|w| w.get_ref().clone())
                .unwrap_or_default(),
            eq: s
                .eq
                .as_ref()
                .map(|e| self.equation_number(e, field))
                .transpose()?,
            gives,
            expect: self.verdict(s.expect.as_ref(), field)?,
            role: self.role(s.role.as_ref(), field)?,
            start,
            line: self.loc.line_col(offset).0,
            op,
        })
    }

    /// A rate `x'` names a coordinate `x`: said plainly, before "undefined name".
    fn rates_of_coordinates(
        &self,
        t: &Text,
        field: &str,
        coordinates: &BTreeMap<String, String>,
    ) -> Result<(), SceneError> {
        let Ok(parsed) = crate::cas::parse_input(t.get_ref()) else {
            return Ok(());
        };
        for (name, offset) in &parsed.symbols {
            let base = name.trim_end_matches('\'');
            if base != name && !coordinates.contains_key(base) {
                return Err(self.err(
                    content_start(t) + offset,
                    field,
                    format!(
                        "`{name}` is a rate of `{base}`, which is not a coordinate: name `{base}` \
                         under [coordinates] (a function of the time t)"
                    ),
                ));
            }
        }
        Ok(())
    }

    /// An earlier step that an operation takes by name, holding what the operation needs.
    fn earlier(
        &self,
        of: &Text,
        field: &str,
        op: &str,
        needs: Holds,
        earlier: &BTreeMap<String, Holds>,
    ) -> Result<(), SceneError> {
        let what = |h: Holds| match h {
            Holds::Expression => "an expression (a Lagrangian L = T - V)",
            Holds::Motion => "equations of motion (from `lagrange`)",
            Holds::Linear => "linear equations of motion (from `linearise`)",
        };
        let name = of.get_ref();
        let message = match earlier.get(name) {
            Some(h) if *h == needs => return Ok(()),
            Some(h) => format!(
                "`{name}` holds {}, but `{op}` takes {}",
                what(*h),
                what(needs)
            ),
            None => format!(
                "`{name}` is not an earlier step{}: `{op}` takes the name of one that gives {}",
                crate::base::suggest::did_you_mean(name, earlier.keys().map(String::as_str)),
                what(needs)
            ),
        };
        Err(self.err(content_start(of), &format!("{field}.{op}"), message))
    }

    /// The notes' form of a result: an expression, or an equation `lhs = rhs` as `lhs - rhs`.
    fn gives(&self, g: &Text, field: &str, scope: &BTreeSet<String>) -> Result<Expr, SceneError> {
        let text = g.get_ref();
        let Some((lhs, rhs)) = text.split_once('=') else {
            return self.claim_expr(g, field, scope);
        };
        let start = content_start(g);
        let side = |t: &str, at: usize| self.parse_checked(t, at, field, scope, true);
        if rhs.contains('=') {
            return Err(self.err(start, field, "an equation has one `=`"));
        }
        let l = side(lhs, start)?;
        let r = side(rhs, start + lhs.len() + 1)?;
        Ok(Expr::minus(l, r))
    }
}

/// The scene's names without the coordinates, their rates and the time: a state of rest is
/// given in them.
fn names_only(
    scope: &BTreeSet<String>,
    coordinates: &BTreeMap<String, String>,
) -> BTreeSet<String> {
    scope
        .iter()
        .filter(|n| *n != "t" && !n.ends_with('\'') && !coordinates.contains_key(*n))
        .cloned()
        .collect()
}
