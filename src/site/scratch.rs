//! Scratch folders for `mechbook bench` (a copy of the lectures to edit, and a cache to empty
//! between runs) and for `serve` (its child builds' reports). Everything here lives under a temporary folder that the caller removes.

use std::path::{Path, PathBuf};

/// A new empty folder under the system's temporary folder.
pub fn folder(name: &str) -> std::io::Result<PathBuf> {
    let dir = std::env::temp_dir().join(format!("mechbook-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir)?;
    Ok(dir)
}

/// Copies a folder of files and subfolders.
pub fn copy_tree(from: &Path, to: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(to)?;
    for e in std::fs::read_dir(from)? {
        let p = e?.path();
        let dest = to.join(p.file_name().unwrap_or_default());
        if p.is_dir() {
            copy_tree(&p, &dest)?;
        } else {
            std::fs::copy(&p, &dest)?;
        }
    }
    Ok(())
}

/// Appends a line to a file: a change to a scene that changes nothing it derives.
pub fn append_line(path: &Path, line: &str) -> std::io::Result<()> {
    use std::io::Write;
    let mut f = std::fs::OpenOptions::new().append(true).open(path)?;
    writeln!(f, "{line}")
}

/// Removes the cache's whole-report entries and keeps its symbolic ones.
pub fn drop_reports(cache: &Path) -> std::io::Result<()> {
    for e in std::fs::read_dir(cache)? {
        let p = e?.path();
        if p.to_string_lossy().contains(".report.") {
            std::fs::remove_file(p)?;
        }
    }
    Ok(())
}

/// Removes a file if it is there.
pub fn remove_file(path: &Path) {
    let _ = std::fs::remove_file(path);
}

pub fn remove(dir: &Path) {
    let _ = std::fs::remove_dir_all(dir);
}

/// Writes a file of the bench's own (a roster, a scene) into its scratch folder, with the
/// folders it lies in.
pub fn write_file(path: &Path, text: &str) -> std::io::Result<()> {
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent)?;
    }
    std::fs::write(path, text)
}
