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

/// Refuses an output folder that `build` must not replace: a file, a symbolic link, a folder
/// with content that mechbook did not write, or one that contains any of `inputs`.
pub fn check_output(out: &Path, inputs: &[PathBuf]) -> Result<(), SiteError> {
    let resolved = resolve(out);
    for input in inputs {
        let input_resolved = resolve(input);
        if input_resolved.starts_with(&resolved) {
            return Err(SiteError::ContainsInput {
                out: out.to_path_buf(),
                input: input.clone(),
            });
        }
    }
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
}
