//! `check --bless`: a scene's `[expect]` and its claims' verdicts rewritten to what was derived,
//! in place, with the file's comments, layout, line endings and byte-order mark kept
//! (toml_edit). The file is edited, not replaced: through a symbolic link, keeping its hard
//! links, mode and owner, never when it is read-only or changed since it was read.

use crate::model::catalogue::recorded_names;
use crate::pipeline::SceneReport;
use crate::scene::PINNED_VARIANTS;
use std::collections::BTreeMap;
use std::os::unix::fs::{MetadataExt, OpenOptionsExt};
use std::path::{Path, PathBuf};
use toml_edit::{DocumentMut, Item, TableLike, Value};

const EXPECT_COMMENT: &str = "\n# The results as derived when this scene was last reviewed: \
                              `check` fails if a derivation changes.\n";

#[derive(Debug, thiserror::Error)]
pub enum BlessError {
    #[error("{}: cannot be edited as TOML: {source}", path.display())]
    Parse {
        path: PathBuf,
        #[source]
        source: Box<toml_edit::TomlError>,
    },
    #[error("{}: `{field}` is not a table or a list of tables, so it cannot be blessed", path.display())]
    Shape { path: PathBuf, field: &'static str },
    #[error(
        "{}: the file is read-only, so nothing was recorded in it: make it writable \
         (chmod u+w) and run `mechbook check --bless` again, or leave it out of the paths",
        .0.display()
    )]
    ReadOnly(PathBuf),
    #[error(
        "{}: the file changed while it was being checked, so nothing was recorded in it (the \
         verdicts would be those of its old text): run `mechbook check --bless` again",
        .0.display()
    )]
    Changed(PathBuf),
    #[error(
        "{0}\n  (what `check --bless` would record here, `check` refuses: nothing was written; \
         state the result in the scene's own names, or report this)"
    )]
    WouldBeRefused(Box<crate::scene::SceneError>),
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}

fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> BlessError + '_ {
    move |source| BlessError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Records what `r` derived in its scene file and gives back the changes (none: the file is
/// left as it was). Refused, with nothing written: a file edited since it was checked (it would
/// get the verdicts of its old text), and a read-only one.
pub fn bless_scene(r: &SceneReport) -> Result<Vec<Blessed>, BlessError> {
    let path = &r.scene.source;
    let original = std::fs::read(path).map_err(io_error(path))?;
    if crate::base::hash::content_hash(&original) != r.scene.content_hash {
        return Err(BlessError::Changed(path.clone()));
    }
    let (new, blessed) = blessed_bytes(&original, r)?;
    if !blessed.is_empty() {
        // What --bless writes, `check` must read: a recorded result naming something the
        // scene does not declare would turn a passing scene into a refused one.
        let text = String::from_utf8_lossy(&new);
        if let Err(e) = crate::scene::Scene::parse(text.trim_start_matches('\u{feff}'), path) {
            return Err(BlessError::WouldBeRefused(Box::new(e)));
        }
        write_in_place(path, &original, &new)?;
    }
    Ok(blessed)
}

/// The file's bytes with `[expect]` and the verdicts set to what `r` derived, and the changes.
/// The text is edited with LF line ends and no byte-order mark, and given back both as the
/// file had them.
fn blessed_bytes(original: &[u8], r: &SceneReport) -> Result<(Vec<u8>, Vec<Blessed>), BlessError> {
    // The scene was read from these bytes, so they are UTF-8; a file that changed since is
    // refused by `write_in_place` before anything is written.
    let text = String::from_utf8_lossy(original);
    let (bom, body) = match text.strip_prefix('\u{feff}') {
        Some(rest) => ("\u{feff}", rest),
        None => ("", &text[..]),
    };
    let crlf = body.contains("\r\n") && !body.replace("\r\n", "").contains('\n');
    let (new, changes) = if crlf {
        let (new, changes) = blessed_text(&body.replace("\r\n", "\n"), r)?;
        (new.replace('\n', "\r\n"), changes)
    } else {
        blessed_text(body, r)?
    };
    Ok((format!("{bom}{new}").into_bytes(), changes))
}

/// Writes `new` over the file at `path`, which held `original` when the scene was read.
///
/// A link is written through to its target. A file with other hard links is overwritten in
/// place (a new file would leave the others behind), and restored if that fails; any other file
/// is replaced in one rename from a temporary file beside it with the same mode and owner, so it
/// is never half-written. Refused, with nothing written: a read-only file, and a file whose
/// bytes are no longer `original`.
fn write_in_place(path: &Path, original: &[u8], new: &[u8]) -> Result<(), BlessError> {
    let real = std::fs::canonicalize(path).map_err(io_error(path))?;
    let meta = std::fs::metadata(&real).map_err(io_error(path))?;
    if meta.permissions().readonly() {
        return Err(BlessError::ReadOnly(path.to_path_buf()));
    }
    let unchanged = || std::fs::read(&real).is_ok_and(|now| now == original);
    if !unchanged() {
        return Err(BlessError::Changed(path.to_path_buf()));
    }
    if meta.nlink() > 1 {
        return overwrite(&real, original, new).map_err(io_error(path));
    }
    let name = real
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let temp = real.with_file_name(format!(".{name}.bless-{}", std::process::id()));
    let written = (|| {
        let mut f = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .mode(meta.mode() & 0o7777)
            .open(&temp)?;
        std::io::Write::write_all(&mut f, new)?;
        f.sync_all()?;
        // The mode as it was, whatever the umask; the owner and group as they were.
        std::fs::set_permissions(&temp, meta.permissions())?;
        let owner = std::fs::metadata(&temp)?;
        if owner.uid() != meta.uid() || owner.gid() != meta.gid() {
            std::os::unix::fs::chown(&temp, Some(meta.uid()), Some(meta.gid()))?;
        }
        Ok(())
    })();
    let replaced = written.and_then(|()| {
        if unchanged() {
            std::fs::rename(&temp, &real)
        } else {
            Err(std::io::ErrorKind::Interrupted.into())
        }
    });
    match replaced {
        Ok(()) => Ok(()),
        Err(e) => {
            let _ = std::fs::remove_file(&temp);
            if e.kind() == std::io::ErrorKind::Interrupted {
                Err(BlessError::Changed(path.to_path_buf()))
            } else if e.kind() == std::io::ErrorKind::PermissionDenied {
                // Not ours to give away (another owner): edit the file itself.
                overwrite(&real, original, new).map_err(io_error(path))
            } else {
                Err(io_error(path)(e))
            }
        }
    }
}

/// Overwrites a file's bytes where they are, keeping the file itself (its links, mode and
/// owner); puts `original` back when writing `new` fails part way.
fn overwrite(path: &Path, original: &[u8], new: &[u8]) -> std::io::Result<()> {
    use std::io::{Seek, Write};
    let mut f = std::fs::OpenOptions::new().write(true).open(path)?;
    let write = |f: &mut std::fs::File, bytes: &[u8]| -> std::io::Result<()> {
        f.seek(std::io::SeekFrom::Start(0))?;
        f.write_all(bytes)?;
        f.set_len(bytes.len() as u64)?;
        f.sync_all()
    };
    write(&mut f, new).inspect_err(|_| {
        let _ = write(&mut f, original);
    })
}

/// One change `--bless` made, located: `file:line: claim (eq 36): agrees -> disagrees`.
#[derive(Debug, Clone, PartialEq)]
pub struct Blessed {
    pub line: usize,
    pub what: String,
}

/// The scene's text with `[expect]` and the verdicts set to what `r` derived, and the changes.
/// Claims whose check itself failed keep their verdict: there is nothing sound to record.
pub fn blessed_text(text: &str, r: &SceneReport) -> Result<(String, Vec<Blessed>), BlessError> {
    let path = &r.scene.source;
    let mut doc: DocumentMut = text.parse().map_err(|e| BlessError::Parse {
        path: path.clone(),
        source: Box::new(e),
    })?;
    let mut changes = Vec::new();
    bless_verdicts(&mut doc, r, &mut changes)?;
    bless_quantities(&mut doc, r, &mut changes)?;
    bless_step_records(&mut doc, r, &mut changes)?;
    bless_pinned_variants(&mut doc, r, &mut changes)?;
    Ok((doc.to_string(), changes))
}

/// The verdicts that changed: a `[[claim]]`'s in its table, a step's `gives` verdict in its
/// `[[step]]`.
fn bless_verdicts(
    doc: &mut DocumentMut,
    r: &SceneReport,
    changes: &mut Vec<Blessed>,
) -> Result<(), BlessError> {
    let path = &r.scene.source;
    for key in ["claim", "step"] {
        let mut tables = array_tables(doc, key).ok_or_else(|| BlessError::Shape {
            path: path.clone(),
            field: key,
        })?;
        let results = r
            .verification
            .claims
            .iter()
            .filter(|c| c.step.is_none())
            .enumerate()
            .filter(|_| key == "claim")
            .chain(
                r.verification
                    .claims
                    .iter()
                    .filter_map(|c| c.step.map(|k| (k, c)))
                    .filter(|_| key == "step"),
            );
        for (i, c) in results {
            if c.problem.is_some() || c.expected == Some(c.verdict) {
                continue;
            }
            let Some(table) = tables.get_mut(i) else {
                continue;
            };
            set_keeping_decor(*table, "expect", c.verdict.as_str());
            changes.push(Blessed {
                line: c.line,
                what: format!(
                    "{}: verdict {} -> {}",
                    if key == "claim" {
                        format!("claim (eq {})", c.eq)
                    } else {
                        c.statement.clone()
                    },
                    c.expected.map_or("(none)", |v| v.as_str()),
                    c.verdict.as_str()
                ),
            });
        }
    }
    Ok(())
}

/// The recorded quantities that changed, under `[expect]`; all of them in a new `[expect]`
/// where the scene has none.
fn bless_quantities(
    doc: &mut DocumentMut,
    r: &SceneReport,
    changes: &mut Vec<Blessed>,
) -> Result<(), BlessError> {
    let quantities = &r.derivation.quantities;
    if doc.get("expect").is_none() {
        first_expect(doc, quantities, changes);
        return Ok(());
    }
    let table = expect_table(doc, &r.scene.source)?;
    for g in r.verification.regressions.iter().filter(|g| !g.unchanged) {
        let was = g
            .recorded
            .as_ref()
            .map_or_else(|| "(none)".into(), |e| e.to_text());
        let what = match quantities.get(&g.quantity) {
            Some(v) => {
                let text = v.to_text();
                set_keeping_decor(table, &g.quantity, &text);
                format!("[expect] {}: {was} -> {text}", g.quantity)
            }
            None => {
                table.remove(&g.quantity);
                format!(
                    "[expect] {}: removed (no longer derived; was {was})",
                    g.quantity
                )
            }
        };
        changes.push(Blessed { line: g.line, what });
    }
    Ok(())
}

/// A scene with no `[expect]`: one, with its comment, of every recorded quantity it derives
/// (none where it derives none of them).
fn first_expect(
    doc: &mut DocumentMut,
    quantities: &BTreeMap<String, crate::model::value::Value>,
    changes: &mut Vec<Blessed>,
) {
    let mut table = toml_edit::Table::new();
    for name in recorded_names() {
        if let Some(v) = quantities.get(name) {
            let text = v.to_text();
            changes.push(Blessed {
                line: 0,
                what: format!("[expect] {name} = {text}"),
            });
            table.insert(name, toml_edit::value(text));
        }
    }
    if !table.is_empty() {
        table.decor_mut().set_prefix(EXPECT_COMMENT);
        doc.insert("expect", Item::Table(table));
    }
}

/// Each step's results under its name, after the quantities: `check` reports a change at the
/// step's line.
fn bless_step_records(
    doc: &mut DocumentMut,
    r: &SceneReport,
    changes: &mut Vec<Blessed>,
) -> Result<(), BlessError> {
    let path = &r.scene.source;
    let steps: Vec<_> = r
        .verification
        .step_records
        .iter()
        .filter(|s| !s.unchanged())
        .collect();
    if !steps.is_empty() {
        let table = expect_table(doc, path)?;
        for s in steps {
            let what = if s.derived.is_empty() {
                table.remove(&s.step);
                format!("[expect] {}: removed (no step of that name)", s.step)
            } else {
                set_record_keeping_decor(table, &s.step, &s.derived);
                let now = s.derived.join(", ");
                match &s.recorded {
                    None => format!("[expect] {} = {now}", s.step),
                    Some((then, _)) => format!("[expect] {}: {} -> {now}", s.step, then.join(", ")),
                }
            };
            changes.push(Blessed { line: s.line, what });
        }
    }
    Ok(())
}

/// The problem's variants, pinned: one hash a variant, so that `check` sees a sheet change.
fn bless_pinned_variants(
    doc: &mut DocumentMut,
    r: &SceneReport,
    changes: &mut Vec<Blessed>,
) -> Result<(), BlessError> {
    let path = &r.scene.source;
    if let Some(pin) = r.verification.pin.as_ref().filter(|p| !p.unchanged()) {
        let table = expect_table(doc, path)?;
        set_keeping_decor(table, PINNED_VARIANTS, &pin.derived.join(" "));
        changes.push(Blessed {
            line: pin.line,
            what: match &pin.recorded {
                None => format!("[expect] variants: {} pinned", pin.derived.len()),
                Some(_) => format!(
                    "[expect] variants: pinned again ({} of {} differed)",
                    pin.differing().len(),
                    pin.derived.len()
                ),
            },
        });
    }
    Ok(())
}

/// The scene's `[expect]`, made (with its comment) where there is none.
fn expect_table<'a>(
    doc: &'a mut DocumentMut,
    path: &Path,
) -> Result<&'a mut dyn TableLike, BlessError> {
    if doc.get("expect").is_none() {
        let mut table = toml_edit::Table::new();
        table.decor_mut().set_prefix(EXPECT_COMMENT);
        doc.insert("expect", Item::Table(table));
    }
    doc.get_mut("expect")
        .and_then(Item::as_table_like_mut)
        .ok_or_else(|| BlessError::Shape {
            path: path.to_path_buf(),
            field: "expect",
        })
}

/// Sets a step's record: one string for one result, else a list with one result a line.
fn set_record_keeping_decor(table: &mut dyn TableLike, key: &str, values: &[String]) {
    if let [one] = values {
        return set_keeping_decor(table, key, one);
    }
    let mut list = toml_edit::Array::new();
    for v in values {
        let mut item = Value::from(v.as_str());
        item.decor_mut().set_prefix("\n    ");
        list.push_formatted(item);
    }
    list.set_trailing_comma(true);
    list.set_trailing("\n");
    set_value_keeping_decor(table, key, Value::Array(list));
}

/// The tables of `[[key]]` (claims, steps) or an inline `key = [{…}]`, in order; none when
/// absent.
fn array_tables<'a>(doc: &'a mut DocumentMut, key: &str) -> Option<Vec<&'a mut dyn TableLike>> {
    match doc.get_mut(key) {
        None => Some(Vec::new()),
        Some(Item::ArrayOfTables(a)) => {
            Some(a.iter_mut().map(|t| t as &mut dyn TableLike).collect())
        }
        Some(Item::Value(Value::Array(a))) => a
            .iter_mut()
            .map(|v| v.as_inline_table_mut().map(|t| t as &mut dyn TableLike))
            .collect(),
        Some(_) => None,
    }
}

/// Sets `key` to the string `text`, keeping the key's comment above it and the old value's
/// surrounding spaces and comment (`insert` would reformat the key).
fn set_keeping_decor(table: &mut dyn TableLike, key: &str, text: &str) {
    set_value_keeping_decor(table, key, Value::from(text));
}

/// Sets `key` to `value`, keeping the old value's surrounding spaces and comment.
fn set_value_keeping_decor(table: &mut dyn TableLike, key: &str, mut value: Value) {
    match table.get_mut(key).and_then(Item::as_value_mut) {
        Some(old) => {
            *value.decor_mut() = old.decor().clone();
            *old = value;
        }
        None => {
            table.insert(key, Item::Value(value));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("mechbook-bless-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_value_set_keeps_the_comment_above_its_key() {
        let text = "[expect]\n# reviewed by hand\nI = \"1\" # old\n[[claim]]\n# eq 4\nexpect = \"agrees\"\n";
        let mut doc: DocumentMut = text.parse().unwrap();
        let t = doc.get_mut("expect").unwrap().as_table_like_mut().unwrap();
        set_keeping_decor(t, "I", "2");
        set_keeping_decor(t, "J", "3");
        let mut claims = array_tables(&mut doc, "claim").unwrap();
        set_keeping_decor(claims[0], "expect", "disagrees");
        assert_eq!(
            doc.to_string(),
            "[expect]\n# reviewed by hand\nI = \"2\" # old\nJ = \"3\"\n[[claim]]\n# eq 4\nexpect = \"disagrees\"\n"
        );
    }

    #[test]
    fn a_changed_or_read_only_file_is_refused_and_nothing_is_left_behind() {
        use std::os::unix::fs::PermissionsExt;
        let dir = scratch("refused");
        let f = dir.join("a.toml");
        std::fs::write(&f, "x = 1\n").unwrap();
        let err = write_in_place(&f, b"x = 0\n", b"x = 2\n").unwrap_err();
        assert!(matches!(err, BlessError::Changed(_)), "{err}");
        assert_eq!(std::fs::read(&f).unwrap(), b"x = 1\n");
        std::fs::set_permissions(&f, std::fs::Permissions::from_mode(0o444)).unwrap();
        let err = write_in_place(&f, b"x = 1\n", b"x = 2\n").unwrap_err();
        assert!(matches!(err, BlessError::ReadOnly(_)), "{err}");
        assert!(err.to_string().contains("chmod u+w"), "{err}");
        assert_eq!(std::fs::read(&f).unwrap(), b"x = 1\n");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn links_hard_links_and_the_mode_are_kept() {
        use std::os::unix::fs::PermissionsExt;
        let dir = scratch("links");
        let real = dir.join("real.toml");
        std::fs::write(&real, "x = 1\n").unwrap();
        std::fs::set_permissions(&real, std::fs::Permissions::from_mode(0o640)).unwrap();
        let link = dir.join("link.toml");
        std::os::unix::fs::symlink(&real, &link).unwrap();
        write_in_place(&link, b"x = 1\n", b"x = 2\n").unwrap();
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read(&real).unwrap(), b"x = 2\n");
        let mode = std::fs::metadata(&real).unwrap().permissions().mode() & 0o7777;
        assert_eq!(mode, 0o640);
        let hard = dir.join("hard.toml");
        std::fs::hard_link(&real, &hard).unwrap();
        write_in_place(&hard, b"x = 2\n", b"x = 33\n").unwrap();
        assert_eq!(std::fs::read(&real).unwrap(), b"x = 33\n");
        write_in_place(&real, b"x = 33\n", b"x = 4\n").unwrap();
        assert_eq!(std::fs::read(&hard).unwrap(), b"x = 4\n");
        assert_eq!(std::fs::metadata(&hard).unwrap().nlink(), 2);
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            3,
            "a temporary file was left"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
