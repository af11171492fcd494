//! The build cache: each scene's computed results, stored by a key that hashes the scene's id,
//! the scene file's bytes, the fidelity and the program itself, so an unchanged scene is not
//! derived again and a rebuilt mechbook never reads an older one's results. Entries are written
//! whole (a temporary file renamed into place), so a crash mid-write leaves no half-written
//! entry.
//!
//! An entry is checked, not trusted: its first line names the key it was stored under and a
//! checksum of what follows, and only a regular file of bounded size is read. An entry moved
//! to another's name, edited, truncated, or replaced by a link, a FIFO or a device is
//! recomputed, and the build says so.

use super::SiteError;
use crate::model::fidelity::Fidelity;
use crate::pipeline::ResultStore;
use crate::render::memo::{Kept, Memo};
use crate::scene::Scene;
use std::path::{Path, PathBuf};

/// Bumped when the entry format changes (2: rationals of any size, stored as text; 3: a first
/// line with the entry's key and checksum; 4: a claim's sides and derived value as trees; 5: a
/// variant's values as trees; 6: the results of an author's steps; 7: a step's momentum or
/// energy, normal modes, equilibria and stability; 8: motion plots; 9: a problem's answers with
/// their labels and units, and the values the author wrote in decimals; 10: the checksum
/// taken over words, `base::hash::word_hash`; 11: a figure's caption as prose, its formulas as
/// trees).
const FORMAT: u64 = 11;

/// The largest entry read: the shipped scenes' largest report is about 200 KB.
pub const MAX_ENTRY_BYTES: u64 = 64 << 20;

/// Why a cache entry was not used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Damage {
    #[error("not a regular file")]
    NotAFile,
    #[error("{0} bytes, more than an entry may have ({MAX_ENTRY_BYTES})")]
    TooLarge(u64),
    #[error("unreadable: {0}")]
    Unreadable(String),
    #[error("no mechbook header")]
    NoHeader,
    #[error("it was stored for another scene or other inputs")]
    OtherKey,
    #[error("its checksum does not match its contents")]
    Checksum,
    #[error("its contents are not a result mechbook stored")]
    Contents,
}

/// What the build should hear about the cache: neither stops it.
#[derive(Debug, thiserror::Error)]
pub enum CacheWarning {
    #[error("the cache is not updated: {0}")]
    NotStored(SiteError),
    #[error("the cache entry {} is damaged ({why}): the scene was derived again", path.display())]
    Damaged { path: PathBuf, why: Damage },
}

/// The build cache is where a run keeps its results (`pipeline` decides what to keep).
impl ResultStore for Cache {
    type Warning = CacheWarning;

    fn get(
        &self,
        scene: &Scene,
        fidelity: Option<&Fidelity>,
        warnings: &mut Vec<CacheWarning>,
    ) -> Option<Vec<u8>> {
        self.hit(&scene.id, scene.content_hash, fidelity, &mut |path, why| {
            warnings.push(CacheWarning::Damaged { path, why });
        })
    }

    fn unreadable(&self, scene: &Scene, fidelity: Option<&Fidelity>) -> CacheWarning {
        let (path, _) = self.entry(&scene.id, scene.content_hash, fidelity);
        CacheWarning::Damaged {
            path,
            why: Damage::Contents,
        }
    }

    fn put(
        &self,
        scene: &Scene,
        fidelity: Option<&Fidelity>,
        bytes: &[u8],
    ) -> Result<(), CacheWarning> {
        self.store(&scene.id, scene.content_hash, fidelity, bytes)
            .map_err(CacheWarning::NotStored)
    }
}

/// A look-up's answer.
#[derive(Debug, PartialEq)]
pub enum Lookup {
    Hit(Vec<u8>),
    Miss,
    Damaged(PathBuf, Damage),
}

pub struct Cache {
    dir: PathBuf,
    /// This program: its version, and its executable's size and modification time.
    program: u64,
}

impl Cache {
    pub fn new(dir: &Path) -> Cache {
        let exe = std::env::current_exe()
            .and_then(std::fs::metadata)
            .map(|m| {
                let modified = m
                    .modified()
                    .ok()
                    .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
                    .map_or(0, |d| d.as_nanos());
                format!("{}:{modified}", m.len())
            })
            .unwrap_or_default();
        let program = format!("{FORMAT}:{}:{exe}", env!("CARGO_PKG_VERSION"));
        Cache {
            dir: dir.to_path_buf(),
            program: crate::base::hash::content_hash(program.as_bytes()),
        }
    }

    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The entry's file for a scene (`id`, `content_hash`), its symbolic results (no fidelity)
    /// or its whole report at a fidelity, and the key its first line must name.
    fn entry(&self, id: &str, content_hash: u64, fidelity: Option<&Fidelity>) -> (PathBuf, u64) {
        let (kind, key) = match fidelity {
            None => ("symbolic", format!("{}:{content_hash:016x}", self.program)),
            Some(f) => (
                "report",
                format!(
                    "{}:{content_hash:016x}:{}:{:016x}",
                    self.program,
                    f.name(),
                    f.tolerance.to_bits()
                ),
            ),
        };
        self.named_entry(id, kind, &key)
    }

    /// The file of an entry of `kind` for `id` under `key`, and the key its first line names.
    fn named_entry(&self, id: &str, kind: &str, key: &str) -> (PathBuf, u64) {
        let hash = crate::base::hash::content_hash(key.as_bytes());
        let key = crate::base::hash::content_hash(format!("{id}\n{kind}\n{key}").as_bytes());
        (self.dir.join(format!("{id}.{kind}.{hash:016x}.json")), key)
    }

    /// A typeset PDF, stored under its document's name and the hash of its markup and
    /// pictures (`inputs`): a changed document, or another mechbook, misses.
    pub fn load_pdf(&self, name: &str, inputs: u64) -> Lookup {
        let (path, key) = self.pdf_entry(name, inputs);
        self.load_at(path, key)
    }

    pub fn store_pdf(&self, name: &str, inputs: u64, pdf: &[u8]) -> Result<(), SiteError> {
        let (path, key) = self.pdf_entry(name, inputs);
        self.store_at(&path, key, name, "pdf", pdf)
    }

    fn pdf_entry(&self, name: &str, inputs: u64) -> (PathBuf, u64) {
        self.named_entry(name, "pdf", &format!("{}:{inputs:016x}", self.program))
    }

    /// What a build said of a typeset PDF (text past the paper's edge, a missing glyph), one
    /// warning a line, kept beside it so that a warm build says it again without typesetting.
    /// Stored before the PDF: a PDF in the cache always has its warnings there too.
    pub fn load_pdf_warnings(&self, name: &str, inputs: u64) -> Lookup {
        let (path, key) = self.pdf_warnings_entry(name, inputs);
        self.load_at(path, key)
    }

    pub fn store_pdf_warnings(
        &self,
        name: &str,
        inputs: u64,
        warnings: &[String],
    ) -> Result<(), SiteError> {
        let (path, key) = self.pdf_warnings_entry(name, inputs);
        let text = warnings.join("\n");
        self.store_at(&path, key, name, "pdf-warnings", text.as_bytes())
    }

    fn pdf_warnings_entry(&self, name: &str, inputs: u64) -> (PathBuf, u64) {
        self.named_entry(
            name,
            "pdf-warnings",
            &format!("{}:{inputs:016x}", self.program),
        )
    }

    /// A unit the renderers made (`render::memo`), under its name and the hash of its inputs.
    fn render_entry(&self, name: &str, inputs: u64) -> (PathBuf, u64) {
        self.named_entry(name, "render", &format!("{}:{inputs:016x}", self.program))
    }

    /// Keeps the units the renderers made fresh, each replacing its unit's older entry.
    pub fn keep_rendered(&self, kept: &[Kept]) -> Result<(), SiteError> {
        if kept.is_empty() {
            return Ok(());
        }
        std::fs::create_dir_all(&self.dir).map_err(|source| SiteError::Io {
            path: self.dir.clone(),
            source,
        })?;
        let mut names = std::collections::BTreeSet::new();
        for k in kept {
            let (path, key) = self.render_entry(&k.name, k.key);
            super::replace_file(&path, &wrap_entry(key, &k.bytes))?;
            names.insert(path.file_name().map(|n| n.to_os_string()));
        }
        // One pass over the folder for the older entries: a build keeps a hundred units.
        let units: std::collections::BTreeSet<String> =
            kept.iter().map(|k| format!("{}.render.", k.name)).collect();
        let listing = std::fs::read_dir(&self.dir).map_err(|source| SiteError::Io {
            path: self.dir.clone(),
            source,
        })?;
        for e in listing.flatten() {
            let n = e.file_name();
            let s = n.to_string_lossy();
            // `<name>.render.<hash>.json`: the unit's prefix, and the hash of its key.
            let Some((unit, hash)) = s.strip_suffix(".json").and_then(|s| s.rsplit_once('.'))
            else {
                continue;
            };
            let stale = hash.len() == 16
                && units.contains(&format!("{unit}."))
                && !names.contains(&Some(n.clone()));
            if stale {
                let _ = std::fs::remove_file(e.path());
            }
        }
        Ok(())
    }

    /// The stored bytes on a hit; a damaged entry is told to `damaged` and is a miss.
    fn hit(
        &self,
        id: &str,
        content_hash: u64,
        fidelity: Option<&Fidelity>,
        damaged: &mut impl FnMut(PathBuf, Damage),
    ) -> Option<Vec<u8>> {
        match self.load(id, content_hash, fidelity) {
            Lookup::Hit(bytes) => Some(bytes),
            Lookup::Miss => None,
            Lookup::Damaged(path, why) => {
                damaged(path, why);
                None
            }
        }
    }

    /// The stored bytes, checked against the key and checksum of their first line.
    pub fn load(&self, id: &str, content_hash: u64, fidelity: Option<&Fidelity>) -> Lookup {
        let (path, key) = self.entry(id, content_hash, fidelity);
        self.load_at(path, key)
    }

    fn load_at(&self, path: PathBuf, key: u64) -> Lookup {
        use std::io::Read;
        let damaged = |why| Lookup::Damaged(path.clone(), why);
        let meta = match std::fs::symlink_metadata(&path) {
            Ok(m) => m,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Lookup::Miss,
            Err(e) => return damaged(Damage::Unreadable(e.to_string())),
        };
        if !meta.file_type().is_file() {
            return damaged(Damage::NotAFile);
        }
        if meta.len() > MAX_ENTRY_BYTES {
            return damaged(Damage::TooLarge(meta.len()));
        }
        let mut bytes = Vec::new();
        let read = std::fs::File::open(&path)
            .and_then(|f| f.take(MAX_ENTRY_BYTES + 1).read_to_end(&mut bytes));
        match read {
            Err(e) => damaged(Damage::Unreadable(e.to_string())),
            Ok(n) if n as u64 > MAX_ENTRY_BYTES => damaged(Damage::TooLarge(n as u64)),
            Ok(_) => match unwrap_entry(&bytes, key) {
                Ok(payload) => Lookup::Hit(payload.to_vec()),
                Err(why) => damaged(why),
            },
        }
    }

    /// Stores an entry and removes the scene's older ones of the same kind: the folder holds at
    /// most one symbolic entry and one report per scene, for its last content and fidelity.
    pub fn store(
        &self,
        id: &str,
        content_hash: u64,
        fidelity: Option<&Fidelity>,
        bytes: &[u8],
    ) -> Result<(), SiteError> {
        let (path, key) = self.entry(id, content_hash, fidelity);
        let kind = if fidelity.is_some() {
            "report"
        } else {
            "symbolic"
        };
        self.store_at(&path, key, id, kind, bytes)
    }

    /// Writes an entry whole and removes the older entries of the same `id` and `kind`.
    fn store_at(
        &self,
        path: &Path,
        key: u64,
        id: &str,
        kind: &str,
        bytes: &[u8],
    ) -> Result<(), SiteError> {
        let io = |p: &Path| {
            let p = p.to_path_buf();
            move |source| SiteError::Io { path: p, source }
        };
        std::fs::create_dir_all(&self.dir).map_err(io(&self.dir))?;
        super::replace_file(path, &wrap_entry(key, bytes))?;
        let name = path.file_name().map(|n| n.to_os_string());
        let prefix = format!("{id}.{kind}.");
        for e in std::fs::read_dir(&self.dir)
            .map_err(io(&self.dir))?
            .flatten()
        {
            let n = e.file_name();
            let s = n.to_string_lossy();
            let stale = s.starts_with(&prefix)
                && s.ends_with(".json")
                && s[prefix.len()..s.len() - 5].len() == 16
                && Some(&n) != name.as_ref();
            if stale {
                let _ = std::fs::remove_file(e.path());
            }
        }
        Ok(())
    }
}

/// The build cache keeps what the renderers made: a damaged or missing unit is made again.
impl Memo for Cache {
    fn recall(&self, name: &str, key: u64) -> Option<Vec<u8>> {
        let (path, key) = self.render_entry(name, key);
        match self.load_at(path, key) {
            Lookup::Hit(bytes) => Some(bytes),
            Lookup::Miss | Lookup::Damaged(..) => None,
        }
    }
}

/// An entry's bytes: a first line naming the format, the key and the payload's checksum.
fn wrap_entry(key: u64, payload: &[u8]) -> Vec<u8> {
    let sum = crate::base::hash::word_hash(payload);
    let mut out = format!("mechbook-cache {FORMAT} {key:016x} {sum:016x}\n").into_bytes();
    out.extend_from_slice(payload);
    out
}

/// The payload of an entry stored under `key`, if its first line says so and its checksum holds.
fn unwrap_entry(bytes: &[u8], key: u64) -> Result<&[u8], Damage> {
    let end = bytes
        .iter()
        .take(80)
        .position(|&b| b == b'\n')
        .ok_or(Damage::NoHeader)?;
    let head = std::str::from_utf8(&bytes[..end]).map_err(|_| Damage::NoHeader)?;
    let words: Vec<&str> = head.split(' ').collect();
    let [magic, format, stored_key, sum] = words[..] else {
        return Err(Damage::NoHeader);
    };
    if magic != "mechbook-cache" || format != FORMAT.to_string() {
        return Err(Damage::NoHeader);
    }
    if stored_key != format!("{key:016x}") {
        return Err(Damage::OtherKey);
    }
    let payload = &bytes[end + 1..];
    if sum != format!("{:016x}", crate::base::hash::word_hash(payload)) {
        return Err(Damage::Checksum);
    }
    Ok(payload)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_change_with_content_and_fidelity_and_old_entries_go() {
        let dir = std::env::temp_dir().join(format!("mechbook-cache-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let c = Cache::new(&dir);
        let std = Some(&Fidelity::STANDARD);
        assert_eq!(c.load("a", 1, std), Lookup::Miss);
        c.store("a", 1, std, b"one").unwrap();
        assert_eq!(c.load("a", 1, std), Lookup::Hit(b"one".to_vec()));
        assert_eq!(
            c.load("a", 2, std),
            Lookup::Miss,
            "another content hash hit"
        );
        assert_eq!(
            c.load("a", 1, Some(&Fidelity::DRAFT)),
            Lookup::Miss,
            "another fidelity hit"
        );
        assert_eq!(
            c.load("a", 1, None),
            Lookup::Miss,
            "a report read as symbolic results"
        );
        c.store("a", 1, None, b"symbolic").unwrap();
        c.store("ab", 1, std, b"other scene").unwrap();
        c.store("a", 2, std, b"two").unwrap();
        assert_eq!(c.load("a", 1, std), Lookup::Miss, "the stale entry stayed");
        assert_eq!(c.load("a", 2, std), Lookup::Hit(b"two".to_vec()));
        assert_eq!(c.load("a", 1, None), Lookup::Hit(b"symbolic".to_vec()));
        assert_eq!(c.load("ab", 1, std), Lookup::Hit(b"other scene".to_vec()));
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 3);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_swapped_edited_linked_or_special_entry_is_damaged_never_a_hit() {
        let dir = std::env::temp_dir().join(format!("mechbook-cache-bad-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let c = Cache::new(&dir);
        let std = Some(&Fidelity::STANDARD);
        c.store("cube", 1, std, b"{\"cube\": 1}").unwrap();
        c.store("hoop", 2, std, b"{\"hoop\": 2}").unwrap();
        let (cube, _) = c.entry("cube", 1, std);
        let (hoop, _) = c.entry("hoop", 2, std);
        let damage = |l: Lookup| match l {
            Lookup::Damaged(_, why) => why,
            other => panic!("not damaged: {other:?}"),
        };
        // Swapped: each file names the other's key.
        let (a, b) = (std::fs::read(&cube).unwrap(), std::fs::read(&hoop).unwrap());
        std::fs::write(&cube, &b).unwrap();
        std::fs::write(&hoop, &a).unwrap();
        assert_eq!(damage(c.load("cube", 1, std)), Damage::OtherKey);
        assert_eq!(damage(c.load("hoop", 2, std)), Damage::OtherKey);
        // A value edited inside.
        let text = String::from_utf8(a.clone()).unwrap();
        std::fs::write(&cube, text.replace("\"cube\": 1", "\"cube\": 7")).unwrap();
        assert_eq!(damage(c.load("cube", 1, std)), Damage::Checksum);
        std::fs::write(&cube, &a[..a.len() - 1]).unwrap();
        assert_eq!(damage(c.load("cube", 1, std)), Damage::Checksum);
        std::fs::write(&cube, b"{\"cube\": 1}").unwrap();
        assert_eq!(damage(c.load("cube", 1, std)), Damage::NoHeader);
        // A link (to a device that never ends) and a FIFO are not read.
        std::fs::remove_file(&cube).unwrap();
        std::os::unix::fs::symlink("/dev/zero", &cube).unwrap();
        assert_eq!(damage(c.load("cube", 1, std)), Damage::NotAFile);
        std::fs::remove_file(&cube).unwrap();
        let made = std::process::Command::new("mkfifo")
            .arg(&cube)
            .status()
            .unwrap();
        assert!(made.success());
        assert_eq!(damage(c.load("cube", 1, std)), Damage::NotAFile);
        // Storing again mends it.
        c.store("cube", 1, std, b"{\"cube\": 1}").unwrap();
        assert_eq!(
            c.load("cube", 1, std),
            Lookup::Hit(b"{\"cube\": 1}".to_vec())
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
