//! A whole scene: its content validated in the order a reader meets it, then its records,
//! problem and typesetting against that content, put together.

use super::{Validator, content_start};
use crate::cas::Expr;
use crate::model::catalogue::Output;
use crate::scene::error::SceneError;
use crate::scene::raw::RawScene;
use crate::scene::step::AuthorStep;
use crate::scene::types::{Assumption, Body, Claim, NotesRef, PlotRequest, Scene};
use std::collections::{BTreeMap, BTreeSet};

/// An ω or an axis, where the scene gives one.
type Direction = Option<[Expr; 3]>;

/// A scene's content, validated, with the names its records may use.
struct Content {
    warnings: Vec<SceneError>,
    symbols: BTreeMap<String, String>,
    /// The symbols and `pi`.
    allowed: BTreeSet<String>,
    /// The bodies' integration variables.
    variables: BTreeSet<String>,
    /// The names a claim may use.
    claim_names: BTreeSet<String>,
    definitions: BTreeMap<String, Expr>,
    vectors: BTreeMap<String, [Expr; 3]>,
    omega: Direction,
    axis: Direction,
    bodies: Vec<Body>,
    claims: Vec<Claim>,
    coordinates: BTreeMap<String, String>,
    steps: Vec<AuthorStep>,
    wants: Vec<Output>,
    plots: Vec<PlotRequest>,
    values: BTreeMap<String, f64>,
    assumptions: Vec<Assumption>,
}

impl Validator<'_> {
    /// The scene: its content, then what is checked against it.
    pub(in crate::scene) fn scene(&self, raw: RawScene) -> Result<Scene, SceneError> {
        let content = self.content(&raw)?;
        self.with_records(raw, content)
    }

    /// The scene's content, its parts validated in the order a reader meets them, so that the
    /// first error reported is the first in the file's logic.
    fn content(&self, raw: &RawScene) -> Result<Content, SceneError> {
        self.names(raw)?;
        self.prose_fields(raw)?;
        let warnings = self.ascii_math_warnings(raw);
        let symbols = self.symbols(raw)?;
        let mut allowed: BTreeSet<String> = symbols.keys().cloned().collect();
        allowed.insert("pi".into());
        // Bodies first: their integration variables are names a claim may use.
        let bodies = self.bodies(raw, &allowed)?;
        let variables: BTreeSet<String> = bodies
            .iter()
            .flat_map(|b| b.variables.iter().cloned())
            .collect();
        let (definitions, vectors, mut claim_names) =
            self.definitions_and_vectors(raw, &allowed, &variables)?;
        let (omega, axis) = self.omega_and_axis(raw, &allowed, &mut claim_names)?;
        let coordinates = self.coordinates(raw, &claim_names)?;
        let steps = self.steps(raw, &claim_names, &coordinates)?;
        // A claim may name a step's result.
        claim_names.extend(steps.iter().flat_map(|s| s.names_given(coordinates.len())));
        let claims = self.claims(raw, &with_rates(&claim_names, &coordinates))?;
        let wants = self.wants(raw)?;
        // Values before plots: a free-body plot's inertia and omega may be expressions.
        let values = self.values(raw, &symbols, &bodies, omega.iter().chain(axis.iter()))?;
        let plots = self.plots(raw, &symbols, &values, &steps, &coordinates)?;
        let domain_names: BTreeSet<String> =
            allowed.iter().chain(coordinates.keys()).cloned().collect();
        let assumptions = self.assumptions(raw, &domain_names, &values)?;
        self.requests(
            raw,
            &super::requests::Requests {
                symbols: &symbols,
                bodies: &bodies,
                claims: &claims,
                wants: &wants,
                plots: &plots,
                has_omega: omega.is_some(),
                has_axis: axis.is_some(),
            },
        )?;
        if let (Some(n), Some(raw_axis)) = (&axis, &raw.axis) {
            self.unit_axis(n, raw_axis.span().start, &values)?;
        }
        Ok(Content {
            warnings,
            symbols,
            allowed,
            variables,
            claim_names,
            definitions,
            vectors,
            omega,
            axis,
            bodies,
            claims,
            coordinates,
            steps,
            wants,
            plots,
            values,
            assumptions,
        })
    }

    /// The scene from its content, with its recorded results, citations, problem, units and
    /// typesetting checked against it.
    fn with_records(&self, raw: RawScene, mut c: Content) -> Result<Scene, SceneError> {
        let fidelity = self.fidelity(&raw)?;
        let step_names: Vec<String> = c.steps.iter().map(|s| s.name.clone()).collect();
        let (expect, expect_lines, step_records) =
            self.expect(&raw, &c.allowed, &c.variables, &step_names)?;
        let cite = self.cites(&raw)?;
        let problem = self.problem(
            &raw,
            &c.symbols,
            &c.values,
            &c.wants,
            &c.bodies,
            (&c.claim_names, &c.steps, c.coordinates.len()),
        )?;
        let units = self.units(&raw)?;
        let tex = self.typesetting(&raw)?;
        c.warnings
            .extend(self.symbol_name_warnings(&raw, &c.steps, &tex));
        let moments_from_bodies =
            self.moments_from_bodies(&raw, &c.symbols, &c.bodies, &c.wants)?;
        let pinned_variants = self.pinned_variants(&raw, problem.is_some())?;
        let declared = super::symbols::declared_order(&raw);
        Ok(Scene {
            declared,
            id_at: self.loc.line_col(content_start(&raw.id)),
            lecture_at: self.loc.line_col(content_start(&raw.notes.lecture)),
            id: raw.id.into_inner(),
            title: raw.title.into_inner(),
            warnings: c.warnings,
            source: self.loc.path.to_path_buf(),
            content_hash: crate::base::hash::content_hash(self.loc.text.as_bytes()),
            notes: NotesRef {
                lecture: raw.notes.lecture.into_inner(),
                section: raw.notes.section,
                equations: raw.notes.equations,
            },
            symbols: c.symbols,
            definitions: c.definitions,
            vectors: c.vectors,
            omega: c.omega,
            axis: c.axis,
            bodies: c.bodies,
            claims: c.claims,
            coordinates: c.coordinates,
            steps: c.steps,
            wants: c.wants,
            plots: c.plots,
            expect_lines,
            plot_at: raw
                .plots
                .iter()
                .map(|p| self.loc.line_col(p.span().start))
                .collect(),
            values: c.values,
            seed: raw.numeric.seed.unwrap_or(1),
            fidelity,
            expect,
            step_records,
            cite,
            problem,
            moments_from_bodies,
            pinned_variants,
            units,
            tex,
            assumptions: c.assumptions,
        })
    }

    /// ω and the axis where the scene gives them, each then a name a claim may use.
    fn omega_and_axis(
        &self,
        raw: &RawScene,
        allowed: &BTreeSet<String>,
        claim_names: &mut BTreeSet<String>,
    ) -> Result<(Direction, Direction), SceneError> {
        let omega = raw
            .omega
            .as_ref()
            .map(|v| self.vec3(v, "omega", allowed))
            .transpose()?;
        let axis = raw
            .axis
            .as_ref()
            .map(|v| self.vec3(v, "axis", allowed))
            .transpose()?;
        if omega.is_some() {
            claim_names.insert("omega".into());
        }
        if axis.is_some() {
            claim_names.insert("axis".into());
        }
        Ok((omega, axis))
    }

    /// The scene's numeric fidelity, where it sets one.
    fn fidelity(
        &self,
        raw: &RawScene,
    ) -> Result<Option<crate::model::fidelity::Fidelity>, SceneError> {
        Ok(match &raw.numeric.fidelity {
            Some(f) => Some(
                crate::model::fidelity::Fidelity::parse(f.get_ref())
                    .map_err(|m| self.err(content_start(f), "numeric.fidelity", m.to_string()))?,
            ),
            None => None,
        })
    }
}

/// The names a claim may use, with each coordinate and its rates: it is checked at random
/// values of them (p = M L² φ'/3), as a step's `gives` is. An answer, one number, may not.
fn with_rates(
    claim_names: &BTreeSet<String>,
    coordinates: &BTreeMap<String, String>,
) -> BTreeSet<String> {
    let mut with_coordinates = claim_names.clone();
    with_coordinates.extend(
        coordinates
            .keys()
            .flat_map(|q| [q.clone(), format!("{q}'"), format!("{q}''")]),
    );
    with_coordinates
}
