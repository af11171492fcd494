//! Reading a scene file: only a regular file of bounded size, and TOML errors made into one
//! located line with the field they are about.

use super::error::{Locator, SceneError};
use std::path::Path;

/// The largest scene file read: a hundred times the largest shipped scene.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;

/// A scene file's bytes: only a regular file (never a device or a FIFO, which could block or
/// never end), and at most [`MAX_SCENE_BYTES`].
pub(super) fn read_scene_file(path: &Path) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot read the scene file: {e}"))?;
    if !meta.is_file() {
        return Err("not a regular file: a scene is a .toml file".into());
    }
    if meta.len() > MAX_SCENE_BYTES {
        return Err(format!(
            "the file has {} bytes; a scene file has at most {MAX_SCENE_BYTES}",
            meta.len()
        ));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_SCENE_BYTES + 1).read_to_end(&mut bytes))
        .map_err(|e| format!("cannot read the scene file: {e}"))?;
    if bytes.len() as u64 > MAX_SCENE_BYTES {
        return Err(format!("a scene file has at most {MAX_SCENE_BYTES} bytes"));
    }
    Ok(bytes)
}

/// A TOML error, located, with the field it is about when the message does not say, and a
/// message where the TOML reader gives none (a control character).
pub(super) fn toml_error(loc: &Locator, offset: usize, message: &str) -> SceneError {
    let message = message.trim();
    if message.is_empty() || message.contains("invalid comment character") {
        if let Some((at, c)) = loc
            .text
            .char_indices()
            .find(|(_, c)| c.is_control() && !matches!(c, '\t' | '\n' | '\r'))
        {
            return loc.error(
                at,
                "",
                format!(
                    "control character U+{:04X} is not allowed anywhere in TOML, comments \
                     included: delete it",
                    c as u32
                ),
            );
        }
        return loc.error(offset, "", "the TOML reader rejected this");
    }
    let field = if message.starts_with("invalid type") || message.starts_with("invalid value") {
        key_at(loc.text, offset)
    } else {
        String::new()
    };
    // The TOML reader's message can take two lines ("invalid array" / "expected `]`"): one.
    let one_line = message
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(": ");
    loc.error(offset, &field, one_line)
}

/// The dotted key written on the line of `offset` (`body.size`), with its table's name.
fn key_at(text: &str, offset: usize) -> String {
    let offset = offset.min(text.len());
    let before = &text[..offset];
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let line = text[line_start..].lines().next().unwrap_or("");
    let key = line
        .split_once('=')
        .map(|(k, _)| k.trim().trim_matches('"').to_string())
        .filter(|k| !k.is_empty() && !k.contains(['[', '{', '#']));
    let headers: Vec<&str> = before[..line_start]
        .lines()
        .map(str::trim)
        .filter(|l| l.starts_with('['))
        .collect();
    // `[[body]]` is an array of tables: name the element, `body[1]`.
    let table = headers.last().map(|h| {
        let name = h.trim_matches(['[', ']']).trim();
        if h.starts_with("[[") {
            let index = headers.iter().filter(|x| **x == *h).count() - 1;
            format!("{name}[{index}]")
        } else {
            name.to_string()
        }
    });
    match (table, key) {
        (Some(t), Some(k)) => format!("{t}.{k}"),
        (None, Some(k)) => k,
        _ => String::new(),
    }
}
