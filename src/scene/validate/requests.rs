//! What a scene's requests need from the rest of it: a body, symbols, `omega`, `axis`.

use super::Validator;
use super::outputs::body_moments;
use crate::model::catalogue::{Output, find};
use crate::scene::error::SceneError;
use crate::scene::raw::RawScene;
use crate::scene::types::{Body, Claim, PlotRequest};
use std::collections::BTreeMap;

/// What the scene asks for, as validated.
pub(super) struct Requests<'a> {
    pub symbols: &'a BTreeMap<String, String>,
    pub bodies: &'a [Body],
    pub claims: &'a [Claim],
    pub wants: &'a [Output],
    pub plots: &'a [PlotRequest],
    pub has_omega: bool,
    pub has_axis: bool,
}

impl Validator<'_> {
    /// Each request has what it needs; the first one that does not is the error.
    pub(super) fn requests(&self, raw: &RawScene, r: &Requests) -> Result<(), SceneError> {
        self.plots_have_a_body(raw, r)?;
        if r.wants.is_empty() && r.claims.is_empty() && r.plots.is_empty() && raw.steps.is_empty() {
            return Err(self.err(
                raw.outputs_span(),
                "outputs.want",
                "the scene asks for nothing: list at least one output, claim or step",
            ));
        }
        self.outputs_have_their_symbols(raw, r)?;
        if r.bodies.is_empty() {
            self.nothing_needs_a_body(raw, r)?;
        }
        let wants = |a, b| r.wants.contains(&a) || r.wants.contains(&b);
        if wants(Output::AngularMomentum, Output::KineticEnergy) && !r.has_omega {
            return Err(self.err(
                raw.outputs_span(),
                "omega",
                "angular_momentum and kinetic_energy need `omega = [..]`",
            ));
        }
        if wants(Output::MomentAboutAxis, Output::Gyration) && !r.has_axis {
            return Err(self.err(
                raw.outputs_span(),
                "axis",
                "moment_about_axis and gyration need `axis = [..]`",
            ));
        }
        Ok(())
    }

    fn plots_have_a_body(&self, raw: &RawScene, r: &Requests) -> Result<(), SceneError> {
        let Some(k) = r.plots.iter().position(|p| p.needs_body()) else {
            return Ok(());
        };
        if !r.bodies.is_empty() {
            return Ok(());
        }
        let message = if r.plots[k].is_free_body() {
            "`inertia = \"principal\"` takes the moments of the scene's body, but there is \
             no [[body]]: add one, or give the moments as `inertia = [I1, I2, I3]`"
                .to_string()
        } else {
            format!("the {} plot needs at least one [[body]]", r.plots[k].kind())
        };
        Err(self.err(raw.plots[k].span().start, &format!("plot[{k}]"), message))
    }

    /// An output written in a free body's symbols has them declared (the principal moments may
    /// come from the bodies instead).
    fn outputs_have_their_symbols(&self, raw: &RawScene, r: &Requests) -> Result<(), SceneError> {
        let from_bodies = raw.outputs.as_ref().is_some_and(|o| o.inertia.is_some());
        for w in r.wants {
            let Some(needed) = w.free_body_symbols() else {
                continue;
            };
            let given = |n: &str| from_bodies && body_moments(*w).contains(&n);
            if let Some(missing) = needed
                .iter()
                .find(|n| !r.symbols.contains_key(**n) && !given(n))
            {
                return Err(self.err(
                    raw.outputs_span(),
                    "outputs.want",
                    format!(
                        "output `{}` writes its results in {}; declare `{missing}` under [symbols]",
                        w.name(),
                        needed.join(", ")
                    ),
                ));
            }
        }
        Ok(())
    }

    /// A scene without a body asks for no output or claim that needs one.
    fn nothing_needs_a_body(&self, raw: &RawScene, r: &Requests) -> Result<(), SceneError> {
        if let Some(w) = r.wants.iter().find(|w| w.free_body_symbols().is_none()) {
            return Err(self.err(
                raw.outputs_span(),
                "outputs.want",
                format!("output `{}` needs at least one [[body]]", w.name()),
            ));
        }
        let uses_body = |c: &&Claim| {
            c.quantity.iter().chain(c.value.iter()).any(|e| {
                e.symbols()
                    .iter()
                    .any(|s| find(s).is_some_and(|q| q.stage.needs_body()))
            })
        };
        match r.claims.iter().find(uses_body) {
            Some(c) => Err(self.err(
                self.line_offset(c.line),
                "claim",
                format!(
                    "claim ({}) uses a derived quantity, but the scene has no [[body]]",
                    c.eq
                ),
            )),
            None => Ok(()),
        }
    }
}
