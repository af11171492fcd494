//! The only code that writes files. A site is built in a temporary folder beside the output and
//! swapped into place in one step, so a failed or killed build leaves the previous site whole;
//! files carry no timestamps, so the same input gives the same bytes.
//! Only an empty folder, or one that mechbook wrote, is ever replaced (`guard`).

pub mod bless;
pub mod cache;
pub mod guard;
pub mod init;
pub mod pdfs;
pub mod scratch;

pub use guard::{Sources, check_output};

use std::path::{Component, Path, PathBuf};

use crate::render::SiteFiles;

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
    #[error(
        "the output folder `{}` is not empty and was not written by mechbook (it has no {} file); \
         a build replaces its output folder whole, so choose a new or empty folder, or delete \
         this one yourself",
        .0.display(), guard::MARKER
    )]
    NotASite(PathBuf),
    #[error("the output `{}` is a file, not a folder: choose a folder for --out", .0.display())]
    NotAFolder(PathBuf),
    #[error(
        "the output `{}` is a symbolic link: give the folder it points to, or a new folder",
        .0.display()
    )]
    Symlink(PathBuf),
    #[error(
        "the output folder `{}` is or contains `{}`, which the build reads, and a build replaces its \
         output whole: choose a folder outside it, such as site/",
        out.display(), input.display()
    )]
    ContainsInput { out: PathBuf, input: PathBuf },
    #[error(
        "the {flag} `{}` is or lies inside `{}`, which mechbook reads, and what mechbook writes \
         there would replace the course's own files: choose a path outside it, such as {suggest}",
        written.display(), input.display()
    )]
    InsideInput {
        flag: &'static str,
        written: PathBuf,
        input: PathBuf,
        suggest: &'static str,
    },
    #[error("cannot read {}: {error}", path.display())]
    Read {
        path: PathBuf,
        error: std::io::Error,
    },
}

/// A user's template folder: the text of each template it replaces, by name (`render` knows
/// the names and the defaults). No folder, no replacements.
pub fn read_templates(dir: Option<&Path>) -> Result<crate::render::TemplateTexts, SiteError> {
    let mut found = crate::render::TemplateTexts::new();
    let Some(dir) = dir else {
        return Ok(found);
    };
    for name in crate::render::template_names() {
        let path = dir.join(name);
        if path.exists() {
            let text =
                std::fs::read_to_string(&path).map_err(|error| SiteError::Read { path, error })?;
            found.insert(name.to_string(), text);
        }
    }
    Ok(found)
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> SiteError + '_ {
    move |source| SiteError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Replaces the file `path` with `bytes` in one rename from a hidden temporary file beside it,
/// so that it is never half-written (and `serve`, which ignores hidden names, never sees the
/// temporary one); the temporary file is removed if the rename fails.
pub fn replace_file(path: &Path, bytes: &[u8]) -> Result<(), SiteError> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let temp = path.with_file_name(format!(".{name}.tmp-{}", std::process::id()));
    std::fs::write(&temp, bytes).map_err(io(&temp))?;
    std::fs::rename(&temp, path).map_err(|e| {
        let _ = std::fs::remove_file(&temp);
        io(path)(e)
    })
}

/// Writes `files` as the folder `out`, replacing what was there only once everything is written
/// (a [`Staging`] folder, swapped in whole). A path outside the folder is refused before anything
/// is written.
pub fn write_site(out: &Path, files: &SiteFiles) -> Result<(), SiteError> {
    for p in files.keys() {
        inside(p)?;
    }
    let staging = Staging::begin(out)?;
    for (rel, bytes) in files {
        staging.write(rel, bytes)?;
    }
    staging.finish()
}

fn inside(rel: &Path) -> Result<(), SiteError> {
    if rel.components().any(|c| !matches!(c, Component::Normal(_))) {
        return Err(SiteError::BadPath(rel.to_path_buf()));
    }
    Ok(())
}

/// A folder being written, to take the place of `out` only once it is whole: files go into it as
/// they are made (a roster's papers one at a time, rather than all held), and [`Staging::finish`]
/// swaps it into place. Dropped unfinished, as when a build fails, it is removed and `out` keeps
/// what it had.
///
/// The new folder is written beside `out` (with the marker file first), then swapped with the
/// old one in one atomic exchange, so the old folder or the new one is in place at every
/// instant; the old one is then removed. Folders left beside `out` by a build that was killed
/// are removed first. The caller checks `out` with [`check_output`] before deriving anything;
/// this checks again, in case the folder changed meanwhile.
pub struct Staging {
    out: PathBuf,
    dir: PathBuf,
    finished: bool,
}

impl Staging {
    pub fn begin(out: &Path) -> Result<Staging, SiteError> {
        check_output(out, &[])?;
        let (parent, name) = parent_and_name(out);
        std::fs::create_dir_all(parent).map_err(io(parent))?;
        remove_stale(parent, &name);
        let dir = parent.join(format!(".{name}.building-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir(&dir).map_err(io(&dir))?;
        let staging = Staging {
            out: out.to_path_buf(),
            dir,
            finished: false,
        };
        let marker = staging.dir.join(guard::MARKER);
        std::fs::write(&marker, guard::MARKER_TEXT).map_err(io(&marker))?;
        Ok(staging)
    }

    /// Writes one file at `rel` inside the folder. A file that `out` already holds with the
    /// same bytes is linked rather than written: the folder then takes no new file from the
    /// file system, which on ext4 cost a quarter of a page-first build (`perf record`: finding
    /// a free inode among those the last build deleted).
    pub fn write(&self, rel: &Path, bytes: &[u8]) -> Result<(), SiteError> {
        inside(rel)?;
        let path = self.dir.join(rel);
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(io(dir))?;
        }
        let old = self.out.join(rel);
        if same_bytes(&old, bytes) && std::fs::hard_link(&old, &path).is_ok() {
            return Ok(());
        }
        std::fs::write(&path, bytes).map_err(io(&path))
    }

    /// Puts the folder in `out`'s place.
    pub fn finish(mut self) -> Result<(), SiteError> {
        // From here the folder is either swapped in or removed below, not by `drop`.
        self.finished = true;
        let (staging, out) = (&self.dir, &self.out);
        let swapped = if std::fs::symlink_metadata(out).is_ok() {
            exchange(staging, out)
        } else {
            std::fs::rename(staging, out)
        };
        if let Err(source) = swapped {
            let _ = std::fs::remove_dir_all(staging);
            return Err(SiteError::Io {
                path: out.clone(),
                source,
            });
        }
        // After an exchange the staging name holds the old folder; after a rename it is gone.
        match std::fs::remove_dir_all(staging) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(io(staging)(e)),
            _ => Ok(()),
        }
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.finished {
            let _ = std::fs::remove_dir_all(&self.dir);
        }
    }
}

/// Whether `path` is a regular file (not a link) holding exactly `bytes`, read a block at a
/// time; any error reading it says no.
fn same_bytes(path: &Path, bytes: &[u8]) -> bool {
    use std::io::Read;
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        return false;
    };
    if !meta.is_file() || meta.len() != bytes.len() as u64 {
        return false;
    }
    let Ok(mut file) = std::fs::File::open(path) else {
        return false;
    };
    let mut block = [0u8; 16 * 1024];
    let mut rest = bytes;
    loop {
        match file.read(&mut block) {
            Ok(0) => return rest.is_empty(),
            Ok(n) if n <= rest.len() && block[..n] == rest[..n] => rest = &rest[n..],
            Ok(_) => return false,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(_) => return false,
        }
    }
}

/// Swaps two folders in one step (Linux's `renameat2` with `RENAME_EXCHANGE`). Where the file
/// system cannot, it falls back to two renames, with a short instant in which `b` is missing.
#[cfg(target_os = "linux")]
#[allow(unsafe_code)]
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    use std::os::unix::ffi::OsStrExt;
    let c = |p: &Path| {
        std::ffi::CString::new(p.as_os_str().as_bytes())
            .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidInput, e))
    };
    let (ca, cb) = (c(a)?, c(b)?);
    // SAFETY: two valid NUL-terminated paths, relative to the current directory.
    let r = unsafe {
        libc::renameat2(
            libc::AT_FDCWD,
            ca.as_ptr(),
            libc::AT_FDCWD,
            cb.as_ptr(),
            libc::RENAME_EXCHANGE,
        )
    };
    if r == 0 {
        return Ok(());
    }
    let e = std::io::Error::last_os_error();
    match e.raw_os_error() {
        Some(libc::EINVAL) | Some(libc::ENOSYS) | Some(libc::ENOTSUP) => two_renames(a, b),
        _ => Err(e),
    }
}

#[cfg(not(target_os = "linux"))]
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    two_renames(a, b)
}

/// `b` moves aside, `a` takes its name, and the old `b` takes `a`'s.
fn two_renames(a: &Path, b: &Path) -> std::io::Result<()> {
    let mut aside = a.as_os_str().to_owned();
    aside.push(".old");
    let aside = PathBuf::from(aside);
    std::fs::rename(b, &aside)?;
    if let Err(e) = std::fs::rename(a, b) {
        let _ = std::fs::rename(&aside, b);
        return Err(e);
    }
    std::fs::rename(&aside, a)
}

/// The folder holding `out` (`.` for a bare name) and `out`'s own name, beside which a build
/// stages the site.
fn parent_and_name(out: &Path) -> (&Path, String) {
    let name = out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "site".into());
    let parent = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    (parent, name)
}

/// Removes what a stopped build of `out` left beside it (its staging folder), once that
/// build's process has ended: `serve` stops a build whose PDFs a later edit makes stale.
pub fn remove_leftovers(out: &Path) {
    let (parent, name) = parent_and_name(out);
    remove_stale(parent, &name);
}

/// Removes `.NAME.building-PID` and `.NAME.previous-PID` folders whose process is gone: what a
/// killed build leaves. Only folders that carry the marker, or are empty, are removed.
fn remove_stale(parent: &Path, name: &str) {
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    for entry in entries.flatten() {
        let file_name = entry.file_name().to_string_lossy().into_owned();
        let Some(rest) = file_name.strip_prefix(&format!(".{name}.")) else {
            continue;
        };
        let pid = rest
            .strip_prefix("building-")
            .or_else(|| rest.strip_prefix("previous-"))
            .and_then(|p| p.split('.').next())
            .and_then(|p| p.parse::<u32>().ok());
        let Some(pid) = pid else { continue };
        if pid == std::process::id() || process_alive(pid) {
            continue;
        }
        let path = entry.path();
        if guard::is_marked(&path) {
            let _ = std::fs::remove_dir_all(&path);
        } else {
            let _ = std::fs::remove_dir(&path);
        }
    }
}

fn process_alive(pid: u32) -> bool {
    #[cfg(unix)]
    {
        let Ok(pid) = libc::pid_t::try_from(pid) else {
            return false;
        };
        // SAFETY: signal 0 only asks whether the process exists.
        #[allow(unsafe_code)]
        let r = unsafe { libc::kill(pid, 0) };
        r == 0 || std::io::Error::last_os_error().raw_os_error() == Some(libc::EPERM)
    }
    #[cfg(not(unix))]
    {
        let _ = pid;
        true
    }
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
        let e = write_site(&out, &bad).unwrap_err();
        assert!(e.to_string().contains("File exists"), "{e}");
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

    /// A folder written file by file (a roster's papers) replaces the old one only when
    /// finished; dropped unfinished, as when the build fails midway, it leaves no trace.
    #[test]
    fn a_staged_folder_takes_the_place_of_the_old_only_when_finished() {
        let dir = scratch("staging");
        let out = dir.join("papers");
        write_site(&out, &files(&[("001.pdf", "old")])).unwrap();
        let staging = Staging::begin(&out).unwrap();
        staging.write(Path::new("001.pdf"), b"new").unwrap();
        assert!(matches!(
            staging.write(Path::new("../002.pdf"), b"x"),
            Err(SiteError::BadPath(_))
        ));
        drop(staging);
        assert_eq!(std::fs::read_to_string(out.join("001.pdf")).unwrap(), "old");
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            1,
            "staging left behind"
        );
        let staging = Staging::begin(&out).unwrap();
        staging.write(Path::new("001.pdf"), b"new").unwrap();
        staging.write(Path::new("key.pdf"), b"key").unwrap();
        assert_eq!(std::fs::read_to_string(out.join("001.pdf")).unwrap(), "old");
        staging.finish().unwrap();
        assert_eq!(std::fs::read_to_string(out.join("001.pdf")).unwrap(), "new");
        assert_eq!(std::fs::read_to_string(out.join("key.pdf")).unwrap(), "key");
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            1,
            "staging left behind"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_file_the_old_folder_has_with_the_same_bytes_is_linked_and_no_other() {
        use std::os::unix::fs::MetadataExt;
        let dir = scratch("linked");
        let out = dir.join("site");
        let outside = dir.join("outside.html");
        std::fs::write(&outside, "<p>a</p>").unwrap();
        write_site(
            &out,
            &files(&[("same.html", "<p>a</p>"), ("edited.html", "<p>b</p>")]),
        )
        .unwrap();
        // A link in the old folder is not followed, even to a file with the same bytes.
        std::os::unix::fs::symlink(&outside, out.join("linked.html")).unwrap();
        let inode = |p: &Path| std::fs::symlink_metadata(p).unwrap().ino();
        let before = (
            inode(&out.join("same.html")),
            inode(&out.join("edited.html")),
        );
        write_site(
            &out,
            &files(&[
                ("same.html", "<p>a</p>"),
                ("edited.html", "<p>c</p>"),
                ("linked.html", "<p>a</p>"),
            ]),
        )
        .unwrap();
        assert_eq!(
            inode(&out.join("same.html")),
            before.0,
            "an unchanged file was written anew"
        );
        assert_ne!(
            inode(&out.join("edited.html")),
            before.1,
            "an edited file was linked"
        );
        assert_ne!(inode(&out.join("linked.html")), inode(&outside));
        for (name, text) in [
            ("same.html", "<p>a</p>"),
            ("edited.html", "<p>c</p>"),
            ("linked.html", "<p>a</p>"),
        ] {
            assert_eq!(std::fs::read_to_string(out.join(name)).unwrap(), text);
            assert!(std::fs::symlink_metadata(out.join(name)).unwrap().is_file());
        }
        assert_eq!(
            std::fs::metadata(out.join("same.html")).unwrap().nlink(),
            1,
            "the old name is left"
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
