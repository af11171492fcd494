//! Which changed paths call for a build, and what `serve` watches to see them.

use crate::serve::is_hidden;
use std::path::{Path, PathBuf};

/// The folder holding `path`, or `.` for a bare file name.
fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Which changed paths call for a build: inside a watched folder or the course file itself,
/// never in what the builds write (the output, the cache, the papers), and never under a hidden
/// name (the default cache, the site's staging folders, an editor's swap files) or an editor's
/// backup.
pub(super) struct Relevant {
    folders: Vec<PathBuf>,
    files: Vec<PathBuf>,
    written: Vec<PathBuf>,
}

impl Relevant {
    pub(super) fn new(watched: &[PathBuf], written: &[PathBuf]) -> Relevant {
        let absolute = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
        let (folders, files): (Vec<PathBuf>, Vec<PathBuf>) = watched
            .iter()
            .map(|p| absolute(p))
            .partition(|p| p.is_dir());
        Relevant {
            folders,
            files,
            written: written.iter().map(|p| absolute(p)).collect(),
        }
    }

    /// What to watch: each folder with all below it, and the folder holding each file or
    /// folder (without what is below), which sees a folder deleted and made again, and an
    /// editor replacing a file when it saves it. A parent inside a watched folder is left
    /// out: one watch of a path replaces another.
    pub(super) fn watches(&self) -> Vec<(PathBuf, notify::RecursiveMode)> {
        let mut w: Vec<(PathBuf, notify::RecursiveMode)> = self
            .folders
            .iter()
            .map(|d| (d.clone(), notify::RecursiveMode::Recursive))
            .collect();
        for p in self.folders.iter().chain(&self.files) {
            let parent = folder_of(p);
            let covered = self.folders.iter().any(|d| parent.starts_with(d))
                || w.iter().any(|(q, _)| *q == parent);
            if !covered {
                w.push((parent, notify::RecursiveMode::NonRecursive));
            }
        }
        w
    }

    pub(super) fn any(&self, paths: &[PathBuf]) -> bool {
        paths.iter().any(|p| self.is_relevant(p))
    }

    fn is_relevant(&self, path: &Path) -> bool {
        let backup = path
            .file_name()
            .is_some_and(|n| n.to_string_lossy().ends_with('~'));
        if backup || self.written.iter().any(|w| path.starts_with(w)) {
            return false;
        }
        self.files.iter().any(|f| f == path)
            || self
                .folders
                .iter()
                .any(|d| path.strip_prefix(d).is_ok_and(|rel| !is_hidden(rel)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_edits_of_inputs_call_for_a_build() {
        // `serve .`: the output, the cache and the build's staging folders are inside the
        // watched folder, and must not start a build (each build writes them: a loop), nor a
        // cache or papers' folder given a name that is not hidden.
        let r = Relevant {
            folders: vec![PathBuf::from("/c"), PathBuf::from("/c/templates")],
            files: vec![PathBuf::from("/c/mechbook.toml")],
            written: ["/c/site", "/c/cache", "/c/papers"]
                .map(PathBuf::from)
                .to_vec(),
        };
        assert!(r.is_relevant(Path::new("/c/lectures/l1/01-book.toml")));
        assert!(r.is_relevant(Path::new("/c/./mechbook.toml")));
        assert!(r.is_relevant(Path::new("/c/templates/page.html")));
        for ignored in [
            "/c/site/index.html",
            "/c/.site.building-42/index.html",
            "/c/.mechbook-cache/ab12/report.json",
            "/c/cache/book.report.0123456789abcdef.json",
            "/c/papers/001.pdf",
            "/c/lectures/.01-book.toml.swp",
            "/c/lectures/01-book.toml~",
            "/elsewhere/x.toml",
        ] {
            assert!(!r.is_relevant(Path::new(ignored)), "{ignored}");
        }
    }
}
