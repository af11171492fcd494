//! Which folders `build` may replace. A site is replaced whole, so the output folder must be new,
//! empty, or one that mechbook wrote (it carries the marker file); and it must not contain what
//! the build reads (the scenes, the templates, the course itself). Checked before anything is
//! derived, so a refused build has touched nothing.

use super::SiteError;
use std::path::{Component, Path, PathBuf};

/// The file that marks a folder as a site mechbook wrote and may replace.
pub const MARKER: &str = ".mechbook-site";

/// What the marker says to a person who finds it.
pub const MARKER_TEXT: &str = "This folder was written by `mechbook build`, which replaces it \
whole on the next build. Delete this file to keep mechbook from ever replacing the folder.\n";

/// Whether `dir` carries the marker: a site that mechbook wrote.
pub fn is_marked(dir: &Path) -> bool {
    std::fs::symlink_metadata(dir.join(MARKER)).is_ok_and(|m| m.is_file())
}

/// `path` made absolute, with symbolic links resolved as far as the path exists and `..`
/// applied to what follows, so that two spellings of one folder compare equal.
pub fn resolve(path: &Path) -> PathBuf {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut existing = absolute.as_path();
    // The trailing components that do not exist yet, last first; `None` stands for `..`.
    let mut rest: Vec<Option<std::ffi::OsString>> = Vec::new();
    loop {
        if let Ok(mut out) = existing.canonicalize() {
            for c in rest.iter().rev() {
                match c {
                    None => {
                        out.pop();
                    }
                    Some(name) => out.push(name),
                }
            }
            return out;
        }
        let Some(parent) = existing.parent() else {
            return absolute;
        };
        match existing.components().next_back() {
            Some(Component::ParentDir) => rest.push(None),
            Some(Component::Normal(name)) => rest.push(Some(name.to_owned())),
            _ => {}
        }
        existing = parent;
    }
}

/// What a course is read from: its files (the scenes, `mechbook.toml`, a roster, the
/// templates) and the folders that hold its scenes or templates. Nothing mechbook writes may
/// be one of them or lie inside one: a slip of `--json-file lectures/x/a.toml` for the scene
/// itself would replace the author's file.
#[derive(Debug, Default)]
pub struct Sources {
    files: Vec<PathBuf>,
    folders: Vec<PathBuf>,
}

impl Sources {
    /// The sources of a course whose scenes are `scene_files`, found under `named` (the files
    /// and folders given on the command line), with its course file and, when given, its
    /// templates folder and roster. A folder that holds the course file is the course's own
    /// folder, where the site and the cache belong: it is not itself a source folder, but the
    /// folders of its scenes are.
    pub fn of_course(
        named: &[PathBuf],
        scene_files: &[PathBuf],
        course_file: &Path,
        templates: Option<&Path>,
        roster: Option<&Path>,
    ) -> Sources {
        let course_root = resolve(course_file.parent().unwrap_or(Path::new(".")));
        let here = resolve(Path::new("."));
        let mut folders: Vec<PathBuf> = named
            .iter()
            .filter(|p| p.is_dir())
            .map(|p| resolve(p))
            .chain(
                scene_files
                    .iter()
                    .filter_map(|f| resolve(f).parent().map(Path::to_path_buf)),
            )
            .filter(|f| *f != course_root && *f != here)
            .collect();
        folders.extend(templates.map(resolve));
        folders.sort();
        folders.dedup();
        let mut files: Vec<PathBuf> = scene_files.iter().map(|f| resolve(f)).collect();
        files.push(resolve(course_file));
        files.extend(roster.map(resolve));
        files.sort();
        files.dedup();
        Sources { files, folders }
    }

    /// Refuses `written` (what the option `flag` names) when it is one of the sources or lies
    /// inside one of their folders. `suggest` names a place that is fine.
    pub fn check_apart(
        &self,
        flag: &'static str,
        written: &Path,
        suggest: &'static str,
    ) -> Result<(), SiteError> {
        let at = resolve(written);
        let hit = self
            .files
            .iter()
            .find(|f| **f == at)
            .or_else(|| self.folders.iter().find(|d| at.starts_with(d)));
        match hit {
            Some(input) => Err(SiteError::InsideInput {
                flag,
                written: written.to_path_buf(),
                input: input.clone(),
                suggest,
            }),
            None => Ok(()),
        }
    }
}

/// Refuses a folder that mechbook writes (and prunes) when it is or holds one of `inputs`.
pub fn check_holds_no_input(out: &Path, inputs: &[PathBuf]) -> Result<(), SiteError> {
    let resolved = resolve(out);
    for input in inputs {
        if resolve(input).starts_with(&resolved) {
            return Err(SiteError::ContainsInput {
                out: out.to_path_buf(),
                input: input.clone(),
            });
        }
    }
    Ok(())
}

/// Refuses an output folder that `build` must not replace: a file, a symbolic link, a folder
/// with content that mechbook did not write, or one that contains any of `inputs`.
pub fn check_output(out: &Path, inputs: &[PathBuf]) -> Result<(), SiteError> {
    check_holds_no_input(out, inputs)?;
    let meta = match std::fs::symlink_metadata(out) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(source) => {
            return Err(SiteError::Io {
                path: out.to_path_buf(),
                source,
            });
        }
    };
    if meta.file_type().is_symlink() {
        return Err(SiteError::Symlink(out.to_path_buf()));
    }
    if !meta.is_dir() {
        return Err(SiteError::NotAFolder(out.to_path_buf()));
    }
    let mut entries = std::fs::read_dir(out).map_err(|source| SiteError::Io {
        path: out.to_path_buf(),
        source,
    })?;
    let empty = entries.next().is_none();
    if empty || is_marked(out) {
        Ok(())
    } else {
        Err(SiteError::NotASite(out.to_path_buf()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("mechbook-guard-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn only_new_empty_or_marked_folders_are_replaced() {
        let dir = scratch("kinds");
        assert!(check_output(&dir.join("new"), &[]).is_ok());
        std::fs::create_dir(dir.join("empty")).unwrap();
        assert!(check_output(&dir.join("empty"), &[]).is_ok());
        std::fs::create_dir(dir.join("mine")).unwrap();
        std::fs::write(dir.join("mine/index.html"), "x").unwrap();
        assert!(matches!(
            check_output(&dir.join("mine"), &[]),
            Err(SiteError::NotASite(_))
        ));
        std::fs::write(dir.join("mine").join(MARKER), MARKER_TEXT).unwrap();
        assert!(check_output(&dir.join("mine"), &[]).is_ok());
        std::fs::write(dir.join("notes.txt"), "keep me").unwrap();
        assert!(matches!(
            check_output(&dir.join("notes.txt"), &[]),
            Err(SiteError::NotAFolder(_))
        ));
        std::os::unix::fs::symlink(dir.join("mine"), dir.join("link")).unwrap();
        assert!(matches!(
            check_output(&dir.join("link"), &[]),
            Err(SiteError::Symlink(_))
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_folder_that_holds_an_input_is_refused_however_it_is_spelled() {
        let dir = scratch("inputs");
        let scenes = dir.join("course/lectures");
        std::fs::create_dir_all(&scenes).unwrap();
        std::fs::write(dir.join("course").join(MARKER), "").unwrap();
        for out in [
            dir.join("course"),
            dir.join("course/lectures"),
            dir.join("course/lectures/.."),
            dir.join("course/./lectures/../lectures"),
            dir.clone(),
        ] {
            assert!(
                matches!(
                    check_output(&out, std::slice::from_ref(&scenes)),
                    Err(SiteError::ContainsInput { .. })
                ),
                "{} was accepted",
                out.display()
            );
        }
        assert!(check_output(&dir.join("course/site"), &[scenes]).is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn nothing_written_is_a_source_or_lies_inside_a_source_folder() {
        let dir = scratch("sources");
        let course = dir.join("course");
        let week = course.join("lectures/week-1");
        std::fs::create_dir_all(&week).unwrap();
        std::fs::create_dir_all(course.join("templates")).unwrap();
        let scene = week.join("01-book.toml");
        std::fs::write(&scene, "").unwrap();
        let course_file = course.join("mechbook.toml");
        std::fs::write(&course_file, "").unwrap();
        let roster = course.join("roster.csv");
        std::fs::write(&roster, "").unwrap();
        let sources = Sources::of_course(
            &[course.join("lectures")],
            std::slice::from_ref(&scene),
            &course_file,
            Some(&course.join("templates")),
            Some(&roster),
        );
        for refused in [
            scene.clone(),
            week.join("../week-1/01-book.toml"),
            course_file.clone(),
            roster.clone(),
            week.join("report.json"),
            course.join("lectures"),
            course.join("lectures/site"),
            course.join("templates/out"),
        ] {
            assert!(
                matches!(
                    sources.check_apart("--json-file", &refused, "report.json"),
                    Err(SiteError::InsideInput { .. })
                ),
                "{} was accepted",
                refused.display()
            );
        }
        // The course's own folder holds the site, the cache and reports.
        for fine in [
            course.join("site"),
            course.join(".mechbook-cache"),
            course.join("report.json"),
            dir.join("elsewhere.json"),
        ] {
            assert!(
                sources.check_apart("--out", &fine, "site/").is_ok(),
                "{} was refused",
                fine.display()
            );
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
