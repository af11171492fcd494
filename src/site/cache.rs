//! The build cache: each scene's computed results, stored by a key that hashes the scene file's
//! bytes, the fidelity and the program itself, so an unchanged scene is not derived again and a
//! rebuilt mechbook never reads an older one's results. Entries are written whole (a temporary
//! file renamed into place), so a crash mid-write leaves no half-written entry.

use super::SiteError;
use crate::model::fidelity::Fidelity;
use crate::pipeline::{self, FromCache, RunError, SceneReport};
use crate::scene::Scene;
use std::path::{Path, PathBuf};

/// Bumped when the entry format changes (2: rationals of any size, stored as text).
const FORMAT: u64 = 2;

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

    /// The entry's file for a scene (`id`, `content_hash`): its symbolic results (no fidelity),
    /// or its whole report at a fidelity.
    fn entry(&self, id: &str, content_hash: u64, fidelity: Option<&Fidelity>) -> PathBuf {
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
        let hash = crate::base::hash::content_hash(key.as_bytes());
        self.dir.join(format!("{id}.{kind}.{hash:016x}.json"))
    }

    /// Runs one scene, or takes it from the cache: the whole report when the cache holds it
    /// for this fidelity, else the symbolic results when it holds those, with only the numeric
    /// stage run again. Comes back with the report and, when the new results could not be
    /// stored, why (the build goes on without them).
    pub fn run_scene(
        &self,
        scene: Scene,
        fidelity: Option<Fidelity>,
    ) -> Result<(SceneReport, Option<SiteError>), RunError> {
        let (id, hash) = (scene.id.clone(), scene.content_hash);
        let fid = fidelity.or(scene.fidelity).unwrap_or_default();
        let whole = self
            .load(&id, hash, Some(&fid))
            .and_then(|bytes| pipeline::from_cache(scene.clone(), &bytes));
        if let Some(r) = whole {
            return Ok((r, None));
        }
        let symbolic = self
            .load(&id, hash, None)
            .and_then(|bytes| serde_json::from_slice(&bytes).ok());
        let r = pipeline::run_scene_with(scene, Some(fid), symbolic)?;
        let mut stored = self.store(&id, hash, Some(&fid), &pipeline::to_cache(&r));
        if r.from_cache == FromCache::Nothing && stored.is_ok() {
            let symbolic =
                serde_json::to_vec(&pipeline::symbolic_part(&r)).expect("a report serializes");
            stored = self.store(&id, hash, None, &symbolic);
        }
        Ok((r, stored.err()))
    }

    /// The stored bytes, or `None` on a miss (including an unreadable entry).
    pub fn load(
        &self,
        id: &str,
        content_hash: u64,
        fidelity: Option<&Fidelity>,
    ) -> Option<Vec<u8>> {
        std::fs::read(self.entry(id, content_hash, fidelity)).ok()
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
        let path = self.entry(id, content_hash, fidelity);
        let io = |p: &Path| {
            let p = p.to_path_buf();
            move |source| SiteError::Io { path: p, source }
        };
        std::fs::create_dir_all(&self.dir).map_err(io(&self.dir))?;
        super::replace_file(&path, bytes)?;
        let name = path.file_name().map(|n| n.to_os_string());
        let kind = if fidelity.is_some() {
            "report"
        } else {
            "symbolic"
        };
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_change_with_content_and_fidelity_and_old_entries_go() {
        let dir = std::env::temp_dir().join(format!("mechbook-cache-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let c = Cache::new(&dir);
        let std = Some(&Fidelity::STANDARD);
        assert_eq!(c.load("a", 1, std), None);
        c.store("a", 1, std, b"one").unwrap();
        assert_eq!(c.load("a", 1, std).as_deref(), Some(&b"one"[..]));
        assert_eq!(c.load("a", 2, std), None, "another content hash hit");
        assert_eq!(
            c.load("a", 1, Some(&Fidelity::DRAFT)),
            None,
            "another fidelity hit"
        );
        assert_eq!(
            c.load("a", 1, None),
            None,
            "a report read as symbolic results"
        );
        c.store("a", 1, None, b"symbolic").unwrap();
        c.store("ab", 1, std, b"other scene").unwrap();
        c.store("a", 2, std, b"two").unwrap();
        assert_eq!(c.load("a", 1, std), None, "the stale entry stayed");
        assert_eq!(c.load("a", 2, std).as_deref(), Some(&b"two"[..]));
        assert_eq!(c.load("a", 1, None).as_deref(), Some(&b"symbolic"[..]));
        assert_eq!(c.load("ab", 1, std).as_deref(), Some(&b"other scene"[..]));
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 3);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
