//! `[coordinates]` and `[[step]]`: the author's own derivation. Each step names the result of one
//! operation on the scene's names, its coordinates (with their rates `q'`, `q''` and the time
//! `t`) and the steps before it, so a step can only use what comes earlier: no cycle.

use super::operation::StepContext;
use super::{Validator, content_start, is_identifier};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::operations::Operation;
use crate::scene::operations::{Holds, Several};
use crate::scene::raw::{RawScene, RawStep, Text};
use crate::scene::step::AuthorStep;
use std::collections::{BTreeMap, BTreeSet};

/// Each coordinate and its meaning.
type Coordinates = BTreeMap<String, String>;

/// The most steps in one scene: a derivation of a page or two.
pub const MAX_STEPS: usize = 64;

/// The most coordinates a scene may have: a course's systems have a few (a triple pendulum,
/// three); each costs derivatives of every step and two equations in each integration.
pub const MAX_COORDINATES: usize = 12;

impl Validator<'_> {
    /// `[coordinates]`: names not taken by anything else in the scene.
    pub(super) fn coordinates(
        &self,
        raw: &RawScene,
        taken: &BTreeSet<String>,
    ) -> Result<Coordinates, SceneError> {
        let mut out = BTreeMap::new();
        for (k, (name, meaning)) in raw.coordinates.iter().enumerate() {
            let n = name.get_ref();
            let field = format!("coordinates.{n}");
            // Every Lagrangian step differentiates by each coordinate and rate, and the
            // numeric checks integrate 2n equations: 50 coordinates ran for over ten minutes.
            if k == MAX_COORDINATES {
                return Err(self.err(
                    name.span().start,
                    &field,
                    format!(
                        "a scene has at most {MAX_COORDINATES} coordinates: split the system, \
                         or fix some coordinates by a constraint"
                    ),
                ));
            }
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
                        "`{n}` is already a name in this scene (a symbol, a definition, a \
                         vector or a derived quantity); a coordinate needs a name of its own"
                    ),
                ));
            }
            out.insert(
                n.clone(),
                crate::scene::raw::meaning_of(meaning).into_inner(),
            );
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
            let holds = step.holding(&steps);
            // An equation `gives` is compared as an equation of motion; on a step that gives an
            // expression it would be read as `lhs - rhs` and compared with the expression.
            if let Some(g) = &s.get_ref().single_gives()
                && g.get_ref().contains('=')
                && !matches!(holds, Holds::Motion | Holds::Linear)
            {
                return Err(self.err(
                    content_start(g),
                    &format!("{field}.gives"),
                    format!(
                        "`gives` states an equation, but step `{}` gives an expression, not \
                         equations of motion: write the expression alone (what is right of \
                         the `=`)",
                        step.name
                    ),
                ));
            }
            earlier.insert(step.name.clone(), holds);
            scope.extend(step.names_given(coordinates.len()));
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
        let op = self.operation(
            s,
            &StepContext {
                offset,
                field,
                scope,
                earlier,
                coordinates,
            },
        )?;
        let start = self.step_start(s, field, scope)?;
        let gives = match &s.single_gives() {
            None => None,
            Some(g) => Some(self.gives(g, &format!("{field}.gives"), scope)?),
        };
        let gives_each = self.gives_each(s, &op, field, scope)?;
        let names = self.result_names(s, &op, field, scope)?;
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
            gives_each,
            names,
            expect: self.verdict(s.expect.as_ref(), field)?,
            role: self.role(s.role.as_ref(), field)?,
            start,
            line: self.loc.line_col(offset).0,
            op,
        })
    }

    /// A step's `start`: finite values of names in scope (the coordinates and their rates).
    fn step_start(
        &self,
        s: &RawStep,
        field: &str,
        scope: &BTreeSet<String>,
    ) -> Result<BTreeMap<String, f64>, SceneError> {
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
        Ok(start)
    }

    /// A `gives` list, one form a result, for a step with several results.
    fn gives_each(
        &self,
        s: &RawStep,
        op: &Operation,
        field: &str,
        scope: &BTreeSet<String>,
    ) -> Result<Vec<Expr>, SceneError> {
        let listed = s.listed_gives();
        if let Some(first) = listed.first()
            && !matches!(op.kind().several, Several::Modes | Several::Roots)
        {
            return Err(self.err(
                first.span().start,
                &format!("{field}.gives"),
                format!(
                    "a list in `gives` is for a step with several results (the modes of \
                     `frequency`, the roots or unknowns of `solve`); `{}` gives one: write its \
                     form alone",
                    op.name()
                ),
            ));
        }
        listed
            .iter()
            .enumerate()
            .map(|(k, g)| self.claim_expr(g, &format!("{field}.gives[{k}]"), scope))
            .collect()
    }

    /// The author's names for a step's several results: each new, for a step that gives
    /// several.
    fn result_names(
        &self,
        s: &RawStep,
        op: &Operation,
        field: &str,
        scope: &BTreeSet<String>,
    ) -> Result<Vec<String>, SceneError> {
        let Some(names) = &s.names else {
            return Ok(Vec::new());
        };
        let at = names.span().start;
        let field = format!("{field}.names");
        if matches!(op.kind().several, Several::None) {
            return Err(self.err(
                at,
                &field,
                format!(
                    "`names` names the several results of a step (the modes of `frequency`, the \
                     roots or unknowns of `solve`, the states of `equilibria` and `stability`); \
                     `{}` gives one, named by the step's `name`",
                    op.name()
                ),
            ));
        }
        let mut seen = BTreeSet::new();
        for name in names.get_ref() {
            if !is_identifier(name)
                || scope.contains(name)
                || name == s.name.get_ref()
                || !seen.insert(name)
            {
                return Err(self.err(
                    at,
                    &field,
                    format!(
                        "`{name}` cannot name a result: each of `names` is a letter followed by \
                         letters, digits or single underscores, used once, and not yet a name \
                         in this scene (`names = [\"slow\", \"fast\"]`)"
                    ),
                ));
            }
        }
        if names.get_ref().is_empty() {
            return Err(self.err(
                at,
                &field,
                "`names` lists a name for each of the step's results (`names = [\"slow\", \
                 \"fast\"]`), or is left out",
            ));
        }
        Ok(names.get_ref().clone())
    }

    /// A rate `x'` names a coordinate `x`: said plainly, before "undefined name".
    pub(super) fn rates_of_coordinates(
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
    pub(super) fn earlier(
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
            Holds::Equilibria => "states of rest (from `equilibria`)",
            Holds::Operand => unreachable!("a step's holding is resolved from its operand's"),
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
