//! mechbook: rigid-body lecture scenes -> a verified workbook.
//!
//! The modules are the pipeline, in order; each imports only the ones above it (the layering
//! test in `tests/layering.rs` holds the code to that):
//!
//! - `base`: number formatting, the content hash, the seeded generator; imports no stage.
//! - `cas`: the only module that touches Symbolica; our own exact expression tree.
//! - `notation`: one math notation: formula trees, the one LaTeX reader, and their printers.
//! - `model`: the shared vocabulary: the catalogue of outputs, stages and quantities, exact
//!   values, fidelity, validated moments, figure data.
//! - `scene`: TOML -> a validated `Scene`. `plan`: what to compute, and nothing more.
//! - `derive` (symbolic steps) and `numeric` (quadrature, eigen, integrators, the exact
//!   solution): numbers with their error and cost.
//! - `figures`: one file per plot kind, data -> `Figure` with captions written from the data.
//! - `verify`: symbolic vs numeric vs the notes' claims -> verdicts.
//! - `steps`: the author's step operations, one file each: its exact rule beside its numeric
//!   route, on the mechanics of `derive` and the checks of `verify`.
//! - `pipeline`: runs the stages for one scene, and the build cache's orchestration.
//! - `document`: the format-neutral view of a scene's page that every printer reads.
//! - `render`: the documents' printers, siblings behind one trait: HTML (MathML, SVG), Moodle,
//!   the JSON report, PDF (Typst sources), all in memory.
//! - `report`: `check`'s and `derive`'s terminal summaries and `check --json`.
//! - `site`: the only code that writes files (the site, a new course, a blessed scene).
//! - `serve`: the HTTP server of `mechbook serve`; it reads the written site.
//! - `cli`: one file per command.

pub mod base;

pub mod cas;

pub mod notation;

pub mod model;

pub mod scene;

pub mod plan;

pub mod derive;
pub mod numeric;

pub mod steps;

pub mod figures;

pub mod verify;

pub mod pipeline;

pub mod document;

pub mod render;

pub mod report;

pub mod site;

pub mod serve;

pub mod cli;
