//! `[outputs]`: what the scene asks for, and `inertia = "principal"`, the Lecture 3/9 families'
//! moments taken from the scene's own bodies.

use super::{Validator, content_start};
use crate::model::catalogue::Output;
use crate::scene::error::SceneError;
use crate::scene::raw::RawScene;
use crate::scene::types::Body;
use std::collections::BTreeMap;

/// The moments an output is written in, which `inertia = "principal"` takes from the bodies:
/// the free top's I1 = I2 and I3; Euler's equations', the axes' stability's and Poinsot's I1,
/// I2 and I3 about x, y and z.
pub fn body_moments(output: Output) -> &'static [&'static str] {
    match output {
        Output::SymmetricTop => &["I1", "I3"],
        Output::EulerEquations | Output::AxisStability | Output::Poinsot => &["I1", "I2", "I3"],
        _ => &[],
    }
}

impl Validator<'_> {
    /// The outputs asked for, by name.
    pub(super) fn wants(&self, raw: &RawScene) -> Result<Vec<Output>, SceneError> {
        let mut wants = Vec::new();
        for (i, w) in raw.wanted().iter().enumerate() {
            let Some((_, o)) = Output::ALL.iter().find(|(n, _)| n == w.get_ref()) else {
                let names: Vec<&str> = Output::ALL.iter().map(|(n, _)| *n).collect();
                return Err(self.err(
                    content_start(w),
                    &format!("outputs.want[{i}]"),
                    format!(
                        "unknown output `{}`{}; the outputs are {}",
                        w.get_ref(),
                        crate::base::suggest::did_you_mean(w.get_ref(), names.iter().copied()),
                        names.join(", ")
                    ),
                ));
            };
            wants.push(*o);
        }
        wants.sort();
        wants.dedup();
        Ok(wants)
    }

    /// `[outputs] inertia`: only `"principal"`, for the outputs written in principal moments,
    /// with a body, and without symbols of the moments it replaces.
    pub(super) fn moments_from_bodies(
        &self,
        raw: &RawScene,
        symbols: &BTreeMap<String, String>,
        bodies: &[Body],
        wants: &[Output],
    ) -> Result<bool, SceneError> {
        let Some(inertia) = raw.outputs.as_ref().and_then(|o| o.inertia.as_ref()) else {
            return Ok(false);
        };
        let (at, field) = (content_start(inertia), "outputs.inertia");
        if inertia.get_ref() != "principal" {
            return Err(self.err(
                at,
                field,
                format!(
                    "`{}`: the one choice is \"principal\", the bodies' own moments",
                    inertia.get_ref()
                ),
            ));
        }
        let mut moments: Vec<&str> = wants
            .iter()
            .flat_map(|w| body_moments(*w).iter().copied())
            .collect();
        moments.sort();
        moments.dedup();
        if moments.is_empty() {
            return Err(self.err(
                at,
                field,
                "`inertia = \"principal\"` gives the principal moments of symmetric_top, \
                 euler_equations, axis_stability or poinsot: add one of them to want",
            ));
        }
        if bodies.is_empty() {
            return Err(self.err(
                at,
                field,
                "`inertia = \"principal\"` takes the moments of the scene's bodies, but there \
                 is no [[body]]",
            ));
        }
        if let Some(n) = moments.iter().find(|n| symbols.contains_key(**n)) {
            return Err(self.err(
                at,
                field,
                format!(
                    "with `inertia = \"principal\"` the bodies give {}: `{n}` cannot also be a \
                     symbol; remove it from [symbols]",
                    moments.join(" and ")
                ),
            ));
        }
        Ok(true)
    }
}
