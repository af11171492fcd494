//! The only code that writes files. A site is built in a temporary folder beside the output and
//! renamed into place, so a failed build leaves the previous site untouched; files are written
//! in sorted order with no timestamps, so the same input gives the same bytes.

pub mod cache;
pub mod scratch;

use std::collections::BTreeMap;
use std::path::{Component, Path, PathBuf};

/// The site as relative path -> contents, sorted.
pub type SiteFiles = BTreeMap<PathBuf, Vec<u8>>;

#[derive(Debug, thiserror::Error)]
pub enum SiteError {
    #[error("`{0}` is not a relative path inside the site")]
    BadPath(PathBuf),
    #[error("cannot write {path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> SiteError + '_ {
    move |source| SiteError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Writes `files` as the folder `out`, replacing what was there only once everything is written.
pub fn write_site(out: &Path, files: &SiteFiles) -> Result<(), SiteError> {
    for p in files.keys() {
        if p.components().any(|c| !matches!(c, Component::Normal(_))) {
            return Err(SiteError::BadPath(p.clone()));
        }
    }
    let name = out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "site".into());
    let parent = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(parent).map_err(io(parent))?;
    let staging = parent.join(format!(".{name}.building-{}", std::process::id()));
    let previous = parent.join(format!(".{name}.previous-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&staging);

    let written = (|| {
        for (rel, bytes) in files {
            let path = staging.join(rel);
            if let Some(dir) = path.parent() {
                std::fs::create_dir_all(dir).map_err(io(dir))?;
            }
            std::fs::write(&path, bytes).map_err(io(&path))?;
        }
        std::fs::create_dir_all(&staging).map_err(io(&staging))
    })();
    if let Err(e) = written {
        let _ = std::fs::remove_dir_all(&staging);
        return Err(e);
    }
    // Swap: the old site moves aside, the new one takes its name, the old one is removed.
    let had_previous = out.exists();
    if had_previous {
        std::fs::rename(out, &previous).map_err(io(out))?;
    }
    if let Err(source) = std::fs::rename(&staging, out) {
        if had_previous {
            let _ = std::fs::rename(&previous, out);
        }
        let _ = std::fs::remove_dir_all(&staging);
        return Err(SiteError::Io {
            path: out.to_path_buf(),
            source,
        });
    }
    if had_previous {
        std::fs::remove_dir_all(&previous).map_err(io(&previous))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("mechbook-site-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn files(pairs: &[(&str, &str)]) -> SiteFiles {
        pairs
            .iter()
            .map(|(p, c)| (PathBuf::from(p), c.as_bytes().to_vec()))
            .collect()
    }

    #[test]
    fn writes_and_replaces_a_site() {
        let dir = scratch("replace");
        let out = dir.join("site");
        write_site(&out, &files(&[("index.html", "one"), ("a/b.html", "two")])).unwrap();
        assert_eq!(
            std::fs::read_to_string(out.join("a/b.html")).unwrap(),
            "two"
        );
        write_site(&out, &files(&[("index.html", "three")])).unwrap();
        assert_eq!(
            std::fs::read_to_string(out.join("index.html")).unwrap(),
            "three"
        );
        assert!(
            !out.join("a").exists(),
            "stale files from the previous build remain"
        );
        let leftovers: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(leftovers, vec![std::ffi::OsString::from("site")]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failed_build_leaves_the_previous_site() {
        let dir = scratch("fail");
        let out = dir.join("site");
        write_site(&out, &files(&[("index.html", "good")])).unwrap();
        // A file and a folder of the same name cannot both be written: the build fails midway.
        let bad = files(&[("page", "x"), ("page/inner.html", "y")]);
        assert!(write_site(&out, &bad).is_err());
        assert_eq!(
            std::fs::read_to_string(out.join("index.html")).unwrap(),
            "good"
        );
        assert!(!out.join("page").exists());
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            1,
            "staging folder left behind"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn paths_must_stay_inside_the_site() {
        let dir = scratch("paths");
        for p in ["../escape.html", "/etc/x"] {
            assert!(matches!(
                write_site(&dir.join("site"), &files(&[(p, "x")])),
                Err(SiteError::BadPath(_))
            ));
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
