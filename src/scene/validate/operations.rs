//! What a `[[step]]` does: exactly one operation, its operands checked against the scene's
//! names, the coordinates and the earlier steps, and no field of another operation.

use super::{Validator, content_start};
use crate::cas::Expr;
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, RawUnknowns, Text};
use crate::scene::step::{MAX_UNKNOWNS, Operation};
use std::collections::{BTreeMap, BTreeSet};

/// The operations a step may name, one per step, in the order the error lists them, and
/// whether this step gives each: the one list of them.
fn operations(s: &RawStep) -> [(&'static str, bool); 14] {
    [
        ("be", s.be.is_some()),
        ("differentiate", s.differentiate.is_some()),
        ("substitute", s.substitute.is_some()),
        ("lagrange", s.lagrange.is_some()),
        ("routh", s.routh.is_some()),
        ("momentum", s.momentum.is_some()),
        ("energy", s.energy.is_some()),
        ("linearise", s.linearise.is_some()),
        ("frequency", s.frequency.is_some()),
        ("solve", s.solve.is_some()),
        ("series", s.series.is_some()),
        ("integrate", s.integrate.is_some()),
        ("equilibria", s.equilibria.is_some()),
        ("stability", s.stability.is_some()),
    ]
}

/// The highest order of a `series`: each order is one more derivative of the expression.
const MAX_ORDER: i64 = 6;

/// What an earlier step holds, for the operations that take a step by name.
#[derive(Clone, Copy, PartialEq)]
pub(super) enum Holds {
    Expression,
    /// Equations of motion from `lagrange`.
    Motion,
    /// Linear equations of motion from `linearise`.
    Linear,
    /// States of rest from `equilibria`.
    Equilibria,
}

impl Validator<'_> {
    /// The one operation of a step.
    pub(super) fn operation(
        &self,
        s: &RawStep,
        offset: usize,
        field: &str,
        scope: &BTreeSet<String>,
        earlier: &BTreeMap<String, Holds>,
        coordinates: &BTreeMap<String, String>,
    ) -> Result<Operation, SceneError> {
        let all = operations(s);
        let given: Vec<&str> = all.iter().filter(|(_, g)| *g).map(|(n, _)| *n).collect();
        if given.len() != 1 {
            return Err(self.err(
                offset,
                field,
                format!(
                    "a step does one thing: give exactly one of {} (this one gives {})",
                    all.map(|(n, _)| n).join(", "),
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
            Operation::Lagrange {
                of: self.lagrangian(of, field, "lagrange", earlier, coordinates)?,
                constraints: self.constraints(s, field, scope, coordinates)?,
            }
        } else if let Some(of) = &s.routh {
            Operation::Routh {
                of: self.lagrangian(of, field, "routh", earlier, coordinates)?,
                cyclic: self.cyclic(s, offset, field, coordinates)?,
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
        } else if let Some(of) = &s.frequency {
            self.earlier(of, field, "frequency", Holds::Linear, earlier)?;
            Operation::Frequency {
                of: of.get_ref().clone(),
            }
        } else if let Some(of) = &s.substitute {
            if s.set.is_empty() {
                return Err(self.err(
                    offset,
                    field,
                    "`substitute` needs `set`: each name and its replacement, as \
                     set = { \"theta'\" = \"x'/R\" }",
                ));
            }
            let mut set = BTreeMap::new();
            for (name, value) in &s.set {
                let key = format!("{field}.set.{}", name.get_ref());
                if !scope.contains(name.get_ref()) || earlier.contains_key(name.get_ref()) {
                    return Err(self.err(
                        name.span().start,
                        &key,
                        format!(
                            "cannot substitute for `{}`: not a symbol, coordinate or rate of this \
                             scene",
                            name.get_ref()
                        ),
                    ));
                }
                set.insert(
                    name.get_ref().clone(),
                    expr(value, &format!("set.{}", name.get_ref()))?,
                );
            }
            Operation::Substitute {
                of: expr(of, "substitute")?,
                set,
            }
        } else if let Some(q) = &s.momentum {
            if !coordinates.contains_key(q.get_ref()) {
                return Err(self.err(
                    content_start(q),
                    &format!("{field}.momentum"),
                    format!(
                        "`{}` is not a coordinate{}: `momentum` names the coordinate whose \
                         momentum it is (its Lagrangian under `of`)",
                        q.get_ref(),
                        crate::base::suggest::did_you_mean(
                            q.get_ref(),
                            coordinates.keys().map(String::as_str)
                        )
                    ),
                ));
            }
            let Some(of) = &s.of else {
                return Err(self.err(
                    offset,
                    field,
                    "`momentum` needs `of`: the step that holds the Lagrangian, such as of = \
                     \"Lag\"",
                ));
            };
            self.earlier(of, field, "of", Holds::Expression, earlier)?;
            Operation::Momentum {
                of: of.get_ref().clone(),
                coordinate: q.get_ref().clone(),
            }
        } else if let Some(of) = &s.energy {
            Operation::Energy {
                of: self.lagrangian(of, field, "energy", earlier, coordinates)?,
            }
        } else if let Some(of) = &s.integrate {
            let over = self.ranges(s, offset, field, scope)?;
            let mut inner = scope.clone();
            inner.extend(over.iter().map(|(v, _, _)| v.clone()));
            Operation::Integrate {
                of: self.claim_expr(of, &format!("{field}.integrate"), &inner)?,
                over,
            }
        } else if let Some(of) = &s.series {
            let [(var, value)] = s.about.iter().collect::<Vec<_>>()[..] else {
                return Err(self.err(
                    offset,
                    &format!("{field}.about"),
                    "`series` needs `about` with one name and its value, such as about = { eps \
                     = \"0\" }",
                ));
            };
            let key = format!("{field}.about.{}", var.get_ref());
            if !scope.contains(var.get_ref()) || earlier.contains_key(var.get_ref()) {
                return Err(self.err(
                    var.span().start,
                    &key,
                    format!(
                        "cannot expand in `{}`: not a symbol, coordinate, rate or `t` of this scene",
                        var.get_ref()
                    ),
                ));
            }
            let order = match &s.order {
                None => 1,
                Some(o) if (0..=MAX_ORDER).contains(o.get_ref()) => *o.get_ref() as u32,
                Some(o) => {
                    return Err(self.err(
                        o.span().start,
                        &format!("{field}.order"),
                        format!("`order` is a whole number from 0 to {MAX_ORDER}"),
                    ));
                }
            };
            Operation::Series {
                of: expr(of, "series")?,
                var: var.get_ref().clone(),
                about: self.claim_expr(value, &key, &names_only(scope, coordinates))?,
                order,
            }
        } else if let Some(of) = &s.equilibria {
            self.earlier(of, field, "equilibria", Holds::Motion, earlier)?;
            Operation::Equilibria {
                of: of.get_ref().clone(),
            }
        } else if let Some(of) = &s.stability {
            self.earlier(of, field, "stability", Holds::Equilibria, earlier)?;
            Operation::Stability {
                of: of.get_ref().clone(),
            }
        } else {
            let of = s.solve.as_ref().expect("one operation is given");
            // Equations of motion, linear ones, or an expression e (solved as e = 0).
            match earlier.get(of.get_ref()) {
                Some(Holds::Motion | Holds::Linear | Holds::Expression) => {}
                Some(Holds::Equilibria) => {
                    return Err(self.err(
                        content_start(of),
                        &format!("{field}.solve"),
                        format!(
                            "`{}` holds states of rest (from `equilibria`), but `solve` takes \
                             equations, or an expression to solve for where it is zero",
                            of.get_ref()
                        ),
                    ));
                }
                None => self.earlier(of, field, "solve", Holds::Motion, earlier)?,
            }
            let Some(given) = &s.unknown else {
                return Err(self.err(
                    offset,
                    field,
                    "`solve` needs `for`: the unknown, such as for = \"x''\", or a list of them \
                     for a linear system, such as for = [\"x''\", \"F\"]",
                ));
            };
            let (at, key) = (content_start(given), format!("{field}.for"));
            let unknowns: Vec<&String> = match given.get_ref() {
                RawUnknowns::One(u) => vec![u],
                RawUnknowns::Many(list) => {
                    if list.is_empty() || list.len() > MAX_UNKNOWNS {
                        return Err(self.err(
                            given.span().start,
                            &key,
                            format!(
                                "`for` lists one to {MAX_UNKNOWNS} unknowns; this lists {}",
                                list.len()
                            ),
                        ));
                    }
                    list.iter().collect()
                }
            };
            let mut names: Vec<String> = Vec::new();
            for u in unknowns {
                if !scope.contains(u) || earlier.contains_key(u) || names.contains(u) {
                    return Err(self.err(
                        at,
                        &key,
                        format!(
                            "cannot solve for `{u}`: not a symbol, coordinate or rate of this \
                             scene, or listed twice"
                        ),
                    ));
                }
                names.push(u.clone());
            }
            Operation::Solve {
                of: of.get_ref().clone(),
                unknowns: names,
            }
        };
        // A field of another operation than this step's: said before anything else about it.
        let stray = |given: bool, belongs: bool, key: &str, message: &str| {
            if given && !belongs {
                return Err(self.err(offset, &format!("{field}.{key}"), message));
            }
            Ok(())
        };
        let is = |names: &[&str]| names.contains(&op.name());
        stray(
            !s.set.is_empty(),
            is(&["substitute"]),
            "set",
            "`set` gives the replacements of a `substitute` step; this step has none",
        )?;
        stray(
            s.unknown.is_some(),
            is(&["solve"]),
            "for",
            "`for` names the unknown of a `solve` step; this step has none",
        )?;
        stray(
            !s.about.is_empty(),
            is(&["linearise", "series"]),
            "about",
            "`about` is the state a `linearise` or `series` step expands about; this step has none",
        )?;
        stray(
            !s.over.is_empty(),
            is(&["integrate"]),
            "over",
            "`over` gives the ranges of an `integrate` step; this step has none",
        )?;
        stray(
            s.order.is_some(),
            is(&["series"]),
            "order",
            "`order` is the last power of a `series` step; this step has none",
        )?;
        // (A `frequency` of several coordinates is known only once derived: its `gives` is
        // then a claim with a problem that says to use the modes' names.)
        if let (true, Some(g)) = (is(&["equilibria", "stability"]), &s.gives) {
            return Err(self.err(
                g.span().start,
                &format!("{field}.gives"),
                format!(
                    "`gives` states one result, and `{}` finds one per state of rest: leave \
                     `gives` out and state each in a [[claim]] on its name ({name}_1, \
                     {name}_2, …, for one coordinate)",
                    op.name(),
                    name = s.name.get_ref(),
                ),
            ));
        }
        stray(
            !s.cyclic.is_empty(),
            is(&["routh"]),
            "cyclic",
            "`cyclic` names the cyclic coordinates of a `routh` step; this step has none",
        )?;
        stray(
            !s.constraints.is_empty(),
            is(&["lagrange"]),
            "constraints",
            "`constraints` gives the constraints of a `lagrange` step, each under its multiplier's \
             name; this step has none",
        )?;
        stray(
            s.of.is_some(),
            is(&["momentum"]),
            "of",
            "`of` names the Lagrangian of a `momentum` step; this step has none",
        )?;
        stray(
            !s.start.is_empty(),
            is(&["lagrange", "routh", "momentum", "energy"]),
            "start",
            "`start` is the initial state of the motion a `lagrange`, `routh`, `momentum` or \
             `energy` step's numeric check integrates; this step has none",
        )?;
        Ok(op)
    }
}

/// The most nested integrals of one `integrate` step.
const MAX_RANGES: usize = 3;

impl Validator<'_> {
    /// An `integrate` step's `over`: [variable, from, to], innermost first, each variable a new
    /// name, each range's limits in the scene's names and the variables after it.
    fn ranges(
        &self,
        s: &RawStep,
        offset: usize,
        field: &str,
        scope: &BTreeSet<String>,
    ) -> Result<Vec<(String, Expr, Expr)>, SceneError> {
        let key = format!("{field}.over");
        if s.over.is_empty() || s.over.len() > MAX_RANGES {
            return Err(self.err(
                offset,
                &key,
                format!(
                    "`integrate` needs `over`: one to {MAX_RANGES} ranges [variable, from, to], \
                     innermost first, such as over = [[\"x\", \"0\", \"a\"]]"
                ),
            ));
        }
        let mut vars: Vec<String> = Vec::new();
        for range in &s.over {
            let [var, ..] = &range.get_ref()[..] else {
                return Err(self.err(range.span().start, &key, "a range is [variable, from, to]"));
            };
            let v = var.get_ref();
            // A symbol declared for it (x, "distance along the rod", with its unit) is bound by
            // the integral: the result does not depend on it.
            let taken = scope.contains(v) && !self.declared.contains(v);
            if !super::is_identifier(v) || taken || vars.contains(v) {
                return Err(self.err(
                    content_start(var),
                    &key,
                    format!(
                        "`{v}` cannot be an integration variable: it needs a name of its own or \
                         one declared in [symbols], not a definition, coordinate or step of this \
                         scene, nor another range's"
                    ),
                ));
            }
            vars.push(v.clone());
        }
        let mut out = Vec::new();
        for (k, range) in s.over.iter().enumerate() {
            let [_, lo, hi] = &range.get_ref()[..] else {
                return Err(self.err(range.span().start, &key, "a range is [variable, from, to]"));
            };
            // Limits use the scene's names and the variables integrated after this one.
            let mut names = scope.clone();
            names.extend(vars[k + 1..].iter().cloned());
            out.push((
                vars[k].clone(),
                self.claim_expr(lo, &key, &names)?,
                self.claim_expr(hi, &key, &names)?,
            ));
        }
        Ok(out)
    }

    /// The earlier step holding the Lagrangian that `op` takes, in a scene with coordinates.
    fn lagrangian(
        &self,
        of: &Text,
        field: &str,
        op: &str,
        earlier: &BTreeMap<String, Holds>,
        coordinates: &BTreeMap<String, String>,
    ) -> Result<String, SceneError> {
        self.earlier(of, field, op, Holds::Expression, earlier)?;
        if coordinates.is_empty() {
            return Err(self.err(
                content_start(of),
                &format!("{field}.{op}"),
                format!("`{op}` needs generalised coordinates: name them under [coordinates]"),
            ));
        }
        Ok(of.get_ref().clone())
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
