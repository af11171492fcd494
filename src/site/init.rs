//! `mechbook init`: a new course that builds at once. The starter files are part of the
//! program; they are written into an empty or new folder, and removed again if any fails.

use std::path::{Path, PathBuf};

/// The starter course, by path inside the new folder.
pub const STARTER: &[(&str, &str)] = &[
    ("mechbook.toml", include_str!("starter/mechbook.toml")),
    ("README.md", include_str!("starter/README.md")),
    (".gitignore", include_str!("starter/gitignore")),
    (
        "lectures/lecture-1/01-book.toml",
        include_str!("starter/01-book.toml"),
    ),
    (
        "lectures/lecture-1/02-problem-box.toml",
        include_str!("starter/02-problem-box.toml"),
    ),
];

#[derive(Debug, thiserror::Error)]
pub enum InitError {
    #[error(
        "`{}` is not empty: `mechbook init` starts a course only in a new or empty folder, so \
         that nothing of yours is overwritten; name a new folder, such as `mechbook init my-course`",
        .0.display()
    )]
    NotEmpty(PathBuf),
    #[error("`{}` is a file, not a folder: name a new folder for the course", .0.display())]
    NotAFolder(PathBuf),
    #[error("cannot write {path} (nothing was left behind): {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}

/// Writes the starter course into `dir`, which must be new or empty, and returns the files
/// written. On any failure, what was written is removed and `dir` is as it was. A folder that
/// holds only what a killed `init` left (starter files, whole or cut short) counts as empty:
/// those are removed and written again.
pub fn init_course(dir: &Path) -> Result<Vec<PathBuf>, InitError> {
    match std::fs::metadata(dir) {
        Ok(m) if !m.is_dir() => return Err(InitError::NotAFolder(dir.to_path_buf())),
        Ok(_) => {
            let io = |source| InitError::Io {
                path: dir.to_path_buf(),
                source,
            };
            let mut entries = std::fs::read_dir(dir).map_err(io)?;
            if entries.next().is_some() {
                let left = leftovers(dir).ok_or_else(|| InitError::NotEmpty(dir.to_path_buf()))?;
                for (path, is_dir) in left.iter().rev() {
                    if *is_dir {
                        std::fs::remove_dir(path).map_err(io)?;
                    } else {
                        std::fs::remove_file(path).map_err(io)?;
                    }
                }
            }
        }
        Err(_) => {}
    }
    // Everything made here, in order, so that a failure can undo it in reverse.
    let mut made: Vec<(PathBuf, bool)> = Vec::new();
    let result = (|| {
        make_folders(dir, &mut made)?;
        let mut files = Vec::new();
        for (rel, text) in STARTER {
            let path = dir.join(rel);
            make_folders(path.parent().unwrap_or(dir), &mut made)?;
            let written = std::fs::File::create_new(&path)
                .and_then(|mut f| std::io::Write::write_all(&mut f, text.as_bytes()));
            if std::fs::metadata(&path).is_ok() {
                made.push((path.clone(), false));
            }
            written.map_err(|source| InitError::Io {
                path: path.clone(),
                source,
            })?;
            files.push(path);
        }
        Ok(files)
    })();
    if result.is_err() {
        for (path, is_dir) in made.iter().rev() {
            let _ = if *is_dir {
                std::fs::remove_dir(path)
            } else {
                std::fs::remove_file(path)
            };
        }
    }
    result
}

/// Everything under `dir`, folders before what they hold, when all of it is what an interrupted
/// `init` writes: starter files whose bytes begin the starter's, and their folders, with one
/// at least missing or cut short. `None` when anything else is there, or the course is whole.
fn leftovers(dir: &Path) -> Option<Vec<(PathBuf, bool)>> {
    fn walk(d: &Path, dir: &Path, out: &mut Vec<(PathBuf, bool)>) -> Option<()> {
        let mut entries: Vec<PathBuf> = std::fs::read_dir(d)
            .ok()?
            .map(|e| e.map(|e| e.path()))
            .collect::<Result<_, _>>()
            .ok()?;
        entries.sort();
        for p in entries {
            let rel = p.strip_prefix(dir).ok()?.to_string_lossy().into_owned();
            let meta = std::fs::symlink_metadata(&p).ok()?;
            if meta.is_dir() {
                let prefix = format!("{rel}/");
                STARTER
                    .iter()
                    .any(|(f, _)| f.starts_with(&prefix))
                    .then_some(())?;
                out.push((p.clone(), true));
                walk(&p, dir, out)?;
            } else {
                let (_, text) = STARTER.iter().find(|(f, _)| *f == rel)?;
                let bytes = std::fs::read(&p).ok()?;
                (meta.is_file() && text.as_bytes().starts_with(&bytes)).then_some(())?;
                out.push((p, false));
            }
        }
        Some(())
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out)?;
    let whole = STARTER
        .iter()
        .all(|(f, text)| std::fs::read(dir.join(f)).is_ok_and(|b| b == text.as_bytes()));
    (!whole).then_some(out)
}

/// Creates `dir` and whichever of its parents are missing, recording each in `made`.
fn make_folders(dir: &Path, made: &mut Vec<(PathBuf, bool)>) -> Result<(), InitError> {
    let missing: Vec<&Path> = dir
        .ancestors()
        .take_while(|d| !d.as_os_str().is_empty() && std::fs::metadata(d).is_err())
        .collect();
    for d in missing.into_iter().rev() {
        std::fs::create_dir(d).map_err(|source| InitError::Io {
            path: d.to_path_buf(),
            source,
        })?;
        made.push((d.to_path_buf(), true));
    }
    Ok(())
}
