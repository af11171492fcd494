//! mechbook: rigid-body lecture scenes -> a verified workbook.
//!
//! The pipeline, one module per stage: `scene` (TOML -> Scene) -> `plan` (what to compute) ->
//! `derive` (symbolic, through `cas`, the only module that touches Symbolica) -> `numeric`
//! (nalgebra, including the data of plots) -> `verify` (verdicts) -> `render` (HTML, MathML, SVG
//! in memory) -> `site` (the only writer). `report` prints to the terminal and JSON; `pipeline`
//! runs the stages.

pub mod bench;
pub mod cas;
pub mod cli;
pub mod derive;
pub mod figure;
pub mod numeric;
pub mod pipeline;
pub mod plan;
pub mod render;
pub mod report;
pub mod scene;
pub mod site;
pub mod spin;
pub mod verify;

#[cfg(test)]
mod extremes;
