//! `solve = "eom"`, `for = "x''"` or `for = ["x''", "T"]`: equations of motion, linear ones, or
//! an expression e (solved as e = 0), for one unknown or a linear system of several.

use super::{StepContext, Validator, content_start};
use crate::scene::error::SceneError;
use crate::scene::operations::Holds;
use crate::scene::raw::{RawStep, RawUnknowns, Text};
use crate::scene::step::{MAX_UNKNOWNS, Operation};

impl Validator<'_> {
    pub(super) fn solve(
        &self,
        of: &Text,
        s: &RawStep,
        cx: &StepContext,
    ) -> Result<Operation, SceneError> {
        let field = cx.field;
        match cx.earlier.get(of.get_ref()) {
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
            Some(_) => {}
            None => {
                self.taken(of, "solve", Holds::Motion, cx)?;
            }
        }
        let Some(given) = &s.unknown else {
            return Err(self.err(
                cx.offset,
                field,
                "`solve` needs `for`: the unknown, such as for = \"x''\", or a list of them for \
                 a linear system, such as for = [\"x''\", \"F\"]",
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
            if !self.own_name(u, cx) || names.contains(u) {
                return Err(self.err(
                    at,
                    &key,
                    format!(
                        "cannot solve for `{u}`: not a symbol, coordinate or rate of this scene, \
                         or listed twice"
                    ),
                ));
            }
            names.push(u.clone());
        }
        Ok(Operation::Solve {
            of: of.get_ref().clone(),
            unknowns: names,
        })
    }
}
