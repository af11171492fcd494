//! What the renderers made before, kept between builds: one unit of output (a scene's page,
//! its JSON, a plot, a problem sheet, a PDF's markup) stored under the hash of everything it
//! was made from, so that a build after an edit renders only what the edit changed. `site`
//! keeps the units in the build cache; the renderers only ask for them ([`Memo`]) and hand
//! back what they made fresh ([`Kept`]).
//!
//! A unit's key hashes the `Debug` form of each of its inputs: every field of a document takes
//! part, so a change anywhere in them misses. The program itself is in the cache's own key.

use super::RenderError;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::fmt::Debug;

/// Where units made by an earlier build are found.
pub trait Memo: Sync {
    /// The bytes kept for unit `name` under `key`, if they are there and whole.
    fn recall(&self, name: &str, key: u64) -> Option<Vec<u8>>;
}

/// No memory: every unit is made (`--no-cache`, and the tests).
pub struct Forget;

impl Memo for Forget {
    fn recall(&self, _: &str, _: u64) -> Option<Vec<u8>> {
        None
    }
}

/// A unit made in this build, for `site` to keep.
#[derive(Debug, Clone, PartialEq)]
pub struct Kept {
    /// A file-name-safe name, one per unit of the course (`<scene id>.page`).
    pub name: String,
    pub key: u64,
    pub bytes: Vec<u8>,
}

/// The key of a unit made from `inputs`: FNV-1a of their `Debug` forms, each closed by a
/// separator so that no two lists of inputs print alike.
pub fn key(inputs: &[&dyn Debug]) -> u64 {
    use std::fmt::Write;
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    for input in inputs {
        // Writing into a hasher cannot fail.
        let _ = write!(h, "{input:?}\u{0}");
    }
    h.0
}

/// Each page's key, hashed once for every unit made from the page (its HTML, its JSON, the
/// handouts and PDFs it is part of): hashing a page's `Debug` form is most of what a key costs.
/// One context renders one course's documents, so the keys are made on first use.
#[derive(Default)]
pub struct PageKeys(std::sync::OnceLock<Vec<u64>>);

impl PageKeys {
    /// The key of `docs.pages[i]` (for every page, on both cores, the first time).
    pub fn of(&self, docs: &crate::document::course::Documents, i: usize) -> u64 {
        self.0
            .get_or_init(|| crate::base::in_order::map_in_order(&docs.pages, |page| key(&[page])))
            [i]
    }

    /// A handout's parts, each with the key of the page it is a part of.
    pub fn of_parts<'p>(
        &self,
        docs: &crate::document::course::Documents,
        parts: &'p [crate::document::handout::Part],
    ) -> Vec<(&'p crate::document::handout::Part, u64)> {
        parts.iter().map(|p| (p, self.of(docs, p.page))).collect()
    }
}

/// FNV-1a over what is written into it (`base::hash::content_hash`, streamed).
struct Fnv(u64);

impl std::fmt::Write for Fnv {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        for b in s.bytes() {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
        Ok(())
    }
}

/// Unit `name` from `memo` when it is kept under `key` and reads back.
pub fn recall<T: DeserializeOwned>(memo: &dyn Memo, name: &str, key: u64) -> Option<T> {
    serde_json::from_slice(&memo.recall(name, key)?).ok()
}

/// Unit `name` from `memo` when it is kept under `key`, else `make`'s, with what to keep. A
/// kept unit that does not read back is made again.
pub fn recall_or<T, E>(
    memo: &dyn Memo,
    name: String,
    key: u64,
    make: impl FnOnce() -> Result<T, E>,
) -> Result<(T, Option<Kept>), E>
where
    T: Serialize + DeserializeOwned,
{
    if let Some(unit) = recall(memo, &name, key) {
        return Ok((unit, None));
    }
    let unit = make()?;
    let bytes = serde_json::to_vec(&unit).expect("a rendered unit serialises");
    Ok((unit, Some(Kept { name, key, bytes })))
}

/// A sheet's units in the memo, named `<sheet>-<problem number>` and keyed by their inputs,
/// and those made fresh.
pub struct Recall<'a> {
    pub memo: &'a dyn Memo,
    /// The sheet's file, as its unit names start (`lecture-1-problems-key`).
    pub sheet: String,
    pub kept: Vec<Kept>,
}

impl<'a> Recall<'a> {
    /// The units of the sheet written to `path` (a site path: its `/` become `.`).
    pub fn of(memo: &'a dyn Memo, path: &str) -> Recall<'a> {
        Recall {
            memo,
            sheet: path.replace('/', "."),
            kept: Vec::new(),
        }
    }

    pub(crate) fn recall_or<T: Serialize + DeserializeOwned>(
        &mut self,
        unit: &str,
        inputs: &[&dyn std::fmt::Debug],
        make: impl FnOnce() -> Result<T, RenderError>,
    ) -> Result<T, RenderError> {
        let mut all: Vec<&dyn std::fmt::Debug> = vec![&"sheet-column", &self.sheet];
        all.extend_from_slice(inputs);
        let key = key(&all);
        let name = format!("{}-{unit}", self.sheet);
        let (made, kept) = recall_or(self.memo, name, key, make)?;
        self.kept.extend(kept);
        Ok(made)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;
    use std::sync::Mutex;

    /// A memory in a map, counting what it was asked.
    #[derive(Default)]
    struct Map(Mutex<BTreeMap<(String, u64), Vec<u8>>>);

    impl Memo for Map {
        fn recall(&self, name: &str, key: u64) -> Option<Vec<u8>> {
            self.0
                .lock()
                .unwrap()
                .get(&(name.to_string(), key))
                .cloned()
        }
    }

    #[test]
    fn a_key_changes_with_any_input_and_with_how_inputs_are_split() {
        let a = key(&[&"page", &vec![1.0f64, 2.0], &Some("x")]);
        assert_eq!(a, key(&[&"page", &vec![1.0f64, 2.0], &Some("x")]));
        assert_ne!(
            a,
            key(&[&"page", &vec![1.0f64, 2.000000000000001], &Some("x")])
        );
        assert_ne!(a, key(&[&"page", &vec![1.0f64, 2.0], &None::<&str>]));
        assert_ne!(key(&[&"ab", &"c"]), key(&[&"a", &"bc"]));
    }

    #[test]
    fn a_unit_is_made_once_then_recalled_and_a_damaged_one_is_made_again() {
        let memo = Map::default();
        let made = std::cell::Cell::new(0);
        let make = || {
            made.set(made.get() + 1);
            Ok::<_, ()>(vec!["<p>page</p>".to_string()])
        };
        let (first, kept) = recall_or(&memo, "s.page".into(), 7, make).unwrap();
        let kept = kept.expect("a fresh unit is kept");
        assert_eq!(made.get(), 1);
        memo.0
            .lock()
            .unwrap()
            .insert((kept.name.clone(), kept.key), kept.bytes.clone());
        let (again, none) = recall_or(&memo, "s.page".into(), 7, make).unwrap();
        assert_eq!((again, none), (first.clone(), None));
        assert_eq!(made.get(), 1, "recalled, not made");
        // Another key is another unit.
        let (_, kept) = recall_or(&memo, "s.page".into(), 8, make).unwrap();
        assert!(kept.is_some());
        assert_eq!(made.get(), 2);
        // Bytes that do not read back are made again.
        memo.0
            .lock()
            .unwrap()
            .insert(("s.page".into(), 7), b"not json".to_vec());
        let (remade, kept) = recall_or(&memo, "s.page".into(), 7, make).unwrap();
        assert_eq!((remade, kept.is_some()), (first, true));
        assert_eq!(made.get(), 3);
    }
}
