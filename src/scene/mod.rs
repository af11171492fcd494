//! Scene files: TOML text -> a validated [`Scene`].
//!
//! Parsing is separate from reading (`Scene::parse` / `Scene::from_file`), so tests need no disk.
//! Every error names the file, line, column and field. `types` holds what a scene is, `load`
//! finds and reads the files, `validate` checks them part by part.

mod course;
mod error;
mod load;
pub mod operations;
mod raw;
pub mod roster;
mod step;
mod symbol_domains;
pub use symbol_domains::SAMPLE_FROM;
mod types;
mod validate;
pub mod variants;
mod verdict;

pub use course::{Course, CourseError, LectureTitle, Paper};
pub use error::{Locator, SceneError};
pub use load::{MAX_DEPTH, MAX_SCENE_BYTES, find_scenes, load_all};
pub use operations::Operation;
pub use step::{AuthorStep, MAX_NAMED_STATES, ResultNames, mode_name};
pub use types::{
    Answer, Assumption, Axis, Body, Claim, ClaimRole, ConeOrigin, FreeBodyPlot, FreeInertia,
    NOT_DERIVED, NotesRef, PlotRequest, Problem, RecordedStep, Scene, Shape, Variant, Verdict,
    lecture_slug,
};
pub use validate::{
    CLAIM_FUNCTIONS, MAX_INPUT_DEGREE, MAX_INPUT_TERMS, MAX_NAME, MAX_PLOT_RADIANS, MAX_PLOT_TIME,
    PINNED_VARIANTS, RESERVED_IDS, control_character, prints_its_name, step_has_route, step_named,
    suggested_tex,
};
pub use variants::{shown_value, terminating_decimal};

use load::{read_scene_file, toml_error};
use raw::RawScene;
use std::path::Path;
use validate::Validator;

impl Scene {
    /// Reads and parses a scene file: a regular file of at most [`MAX_SCENE_BYTES`], in UTF-8.
    pub fn from_file(path: &Path) -> Result<Scene, SceneError> {
        let bytes = read_scene_file(path).map_err(|e| SceneError {
            path: path.to_path_buf(),
            line: 1,
            column: 1,
            field: String::new(),
            message: e.to_string(),
        })?;
        match std::str::from_utf8(&bytes) {
            Ok(text) => Scene::parse(text, path),
            Err(e) => {
                let valid = std::str::from_utf8(&bytes[..e.valid_up_to()]).unwrap_or("");
                let loc = Locator { path, text: valid };
                Err(loc.error(
                    valid.len(),
                    "",
                    format!(
                        "invalid UTF-8 (byte 0x{:02x} at byte offset {}): save the file as UTF-8",
                        bytes[e.valid_up_to()],
                        e.valid_up_to()
                    ),
                ))
            }
        }
    }

    pub fn parse(text: &str, path: &Path) -> Result<Scene, SceneError> {
        let loc = Locator { path, text };
        let raw: RawScene = toml::from_str(text).map_err(|e| {
            let offset = e.span().map(|s| s.start).unwrap_or(0);
            toml_error(&loc, offset, e.message())
        })?;
        let declared = raw.symbols.keys().map(|k| k.get_ref().clone()).collect();
        Validator {
            loc: &loc,
            declared,
        }
        .scene(raw)
    }
}

#[cfg(test)]
mod tests;
