//! `solve = "eom"`, `for = "x''"` or `for = ["x''", "T"]`: equations of motion, linear ones, or
//! an expression e (solved as e = 0), for one unknown or a linear system of several.

use super::{Holds, OperationType, StepFields};
use crate::scene::error::SceneError;
use crate::scene::raw::{RawStep, RawUnknowns, Text, content_start};

/// The most unknowns of one `solve` (a rolling disk's five coordinates and two multipliers,
/// and one more), and of the roots it names: `x_1` to `x_8`.
pub const MAX_UNKNOWNS: usize = 8;

/// The named equations of motion solved: for one unknown, the equation that contains it
/// (every root); for several, the linear system of the equations that contain them.
#[derive(Debug, Clone, PartialEq)]
pub struct Solve {
    pub of: String,
    pub unknowns: Vec<String>,
}

impl OperationType for Solve {
    fn read(of: &Text, s: &RawStep, f: &impl StepFields) -> Result<Self, SceneError> {
        let field = f.field();
        match f.earlier().get(of.get_ref()) {
            Some(Holds::Equilibria) => {
                return Err(f.err(
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
                f.taken(of, "solve", Holds::Motion)?;
            }
        }
        let Some(given) = &s.unknown else {
            return Err(f.err(
                f.offset(),
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
                    return Err(f.err(
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
            if !f.own_name(u) || names.contains(u) {
                return Err(f.err(
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
        Ok(Solve {
            of: of.get_ref().clone(),
            unknowns: names,
        })
    }
}
