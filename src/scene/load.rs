//! Finding and reading scene files: the folder walk, only regular files of bounded size, TOML
//! errors made into one located line with the field they are about, and the checks across
//! files (unique ids, distinct handout names).

use super::error::{Locator, SceneError};
use super::types::{Scene, lecture_slug};
use std::path::{Path, PathBuf};

/// The largest scene file read: a hundred times the largest shipped scene.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;

/// A file's bytes: only a regular file (never a device or a FIFO, which could block or never
/// end), and at most `limit` bytes. `what` names the file in the messages ("a scene file").
pub(crate) fn read_regular_file(
    path: &Path,
    limit: u64,
    what: &'static str,
) -> Result<Vec<u8>, ReadError> {
    use std::io::Read;
    let unreadable = |e: std::io::Error| ReadError::Unreadable(what, e.to_string());
    let meta = std::fs::metadata(path).map_err(unreadable)?;
    if !meta.is_file() {
        return Err(ReadError::NotAFile(what));
    }
    if meta.len() > limit {
        return Err(ReadError::TooLarge(what, meta.len(), limit));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(limit + 1).read_to_end(&mut bytes))
        .map_err(unreadable)?;
    if bytes.len() as u64 > limit {
        return Err(ReadError::Grew(what, limit));
    }
    Ok(bytes)
}

/// A scene file's bytes: a regular file of at most [`MAX_SCENE_BYTES`].
pub(super) fn read_scene_file(path: &Path) -> Result<Vec<u8>, ReadError> {
    read_regular_file(path, MAX_SCENE_BYTES, "the scene file")
}

/// Why a file's bytes could not be read; each names the kind of file.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    #[error("cannot read {0}: {1}")]
    Unreadable(&'static str, String),
    #[error("not a regular file: {0} must be a file of text, not a device, a FIFO or a folder")]
    NotAFile(&'static str),
    #[error("the file has {1} bytes; {0} may have at most {2}")]
    TooLarge(&'static str, u64, u64),
    /// The file grew past the limit while it was read.
    #[error("{0} may have at most {1} bytes")]
    Grew(&'static str, u64),
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
    let hint = unknown_name_hint(&one_line) + shape_hint(&one_line, &field).as_str();
    loc.error(offset, &field, one_line + hint.as_str())
}

/// Each field whose value is a table or a list, by its key, with an example of its shape
/// (docs/scenes.md has each in full).
const SHAPES: &[(&str, &str)] = &[
    (
        "symbols",
        "[symbols] m = { meaning = \"mass of the bob\", unit = \"kg\" }",
    ),
    (
        "coordinates",
        "[coordinates] phi = { meaning = \"angle from the vertical\", unit = \"rad\" }",
    ),
    ("vectors", "[vectors] r = [\"x\", \"y\", \"0\"]"),
    ("omega", "omega = [\"w1\", \"w2\", \"w3\"]"),
    ("axis", "axis = [\"0\", \"0\", \"1\"]"),
    ("size", "size = [\"a\", \"b\", \"c\"]"),
    ("shift", "shift = [\"a/2\", \"a/2\", \"0\"]"),
    (
        "at",
        "at = [\"x\", \"y\", \"z\"] (a point's place), or at = { \"phi'\" = 0.5 } (a plot's values)",
    ),
    (
        "points",
        "points = [{ mass = \"m\", at = [\"a\", \"0\", \"0\"] }]",
    ),
    ("rotate", "rotate = [{ axis = \"z\", angle = \"pi/4\" }]"),
    (
        "cyclic",
        "cyclic = { phi = \"p\" } (each cyclic coordinate and the symbol of its momentum)",
    ),
    (
        "constraints",
        "constraints = { T = \"l - x1 - x2\" } (each multiplier and its constraint)",
    ),
    ("about", "about = { phi = \"0\" }"),
    ("set", "set = { \"theta'\" = \"x'/R\" }"),
    ("start", "start = { phi = 0.3, \"phi'\" = 0 }"),
    (
        "over",
        "over = [[\"r\", \"0\", \"R\"], [\"theta\", \"0\", \"2*pi\"]] (a step's ranges), or over = \"alpha\" (a plot's)",
    ),
    ("for", "for = \"x''\", or for = [\"x''\", \"T\"]"),
    (
        "gives",
        "gives = \"sqrt(g/l)\", or gives = [\"sqrt(g/l)\", \"sqrt(3*g/l)\"] for several results",
    ),
    ("range", "range = [\"0\", \"pi\"]"),
    ("values", "values = { m = 1.0, l = 2.0 }"),
    ("want", "want = [\"inertia_tensor\", \"principal_moments\"]"),
    ("equations", "equations = [\"31\", \"32\"]"),
    (
        "answers",
        "answers = [{ value = \"omega\", label = \"the angular frequency\", unit = \"1/s\" }]",
    ),
];

/// For serde's "invalid type: sequence, expected a map" on a field whose shape is known: an
/// example of the right one.
fn shape_hint(message: &str, field: &str) -> String {
    if !message.starts_with("invalid type") {
        return String::new();
    }
    let key = field.rsplit('.').next().unwrap_or(field);
    let key = key.split('[').next().unwrap_or(key);
    SHAPES
        .iter()
        .find(|(name, _)| *name == key)
        .map(|(_, example)| format!("; write it as {example}"))
        .unwrap_or_default()
}

/// For serde's "unknown field `quanity`, expected one of `eq`, `quantity`, …" (and "unknown
/// variant"): "; did you mean `quantity`?" when one of the expected names is near.
fn unknown_name_hint(message: &str) -> String {
    let Some(rest) = message
        .strip_prefix("unknown field `")
        .or_else(|| message.strip_prefix("unknown variant `"))
    else {
        return String::new();
    };
    let Some((name, expected)) = rest.split_once('`') else {
        return String::new();
    };
    let candidates = expected.split('`').skip(1).step_by(2);
    let near = crate::base::suggest::did_you_mean(name, candidates);
    // A key of the scene itself written after a [table] header lands in that table.
    if near.is_empty() && TOP_LEVEL.contains(&name) && message.starts_with("unknown field") {
        return format!(
            "; `{name}` is a key of the scene itself: write it above the first [table] header"
        );
    }
    near
}

/// The scene's own keys that are not tables (`[symbols]`, `[[step]]`).
const TOP_LEVEL: &[&str] = &["id", "title", "notes", "assume", "axis", "omega"];

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

/// The most folder levels `find_scenes` descends.
pub const MAX_DEPTH: usize = 16;

/// The course's settings file in a scene folder: not a scene.
pub const COURSE_FILE: &str = "mechbook.toml";

/// Every `.toml` scene under the given folders, plus the files named directly (taken as given,
/// so a missing or unreadable one is reported), sorted and without duplicates. A symbolic link
/// to a folder is followed only when the folder lies inside the one being searched and was not
/// visited yet (so `up -> ..` or `here -> .` add nothing); only regular files are taken, and
/// the walk goes at most [`MAX_DEPTH`] folders deep.
pub fn find_scenes(paths: &[PathBuf]) -> std::io::Result<Vec<PathBuf>> {
    use std::collections::BTreeSet;
    fn collect(
        dir: &Path,
        root: &Path,
        depth: usize,
        seen: &mut BTreeSet<PathBuf>,
        out: &mut Vec<PathBuf>,
    ) -> std::io::Result<()> {
        let real = dir.canonicalize()?;
        if depth > MAX_DEPTH || !real.starts_with(root) || !seen.insert(real) {
            return Ok(());
        }
        for entry in std::fs::read_dir(dir)? {
            let path = entry?.path();
            // A dangling link or an unreadable entry is skipped, as `find` would.
            let Ok(meta) = std::fs::metadata(&path) else {
                continue;
            };
            if meta.is_dir() {
                collect(&path, root, depth + 1, seen, out)?;
            } else if meta.is_file()
                && path.extension().is_some_and(|x| x == "toml")
                && path.file_name().is_some_and(|n| n != COURSE_FILE)
            {
                out.push(path);
            }
        }
        Ok(())
    }
    let mut out = Vec::new();
    let mut seen = BTreeSet::new();
    for p in paths {
        if p.is_dir() {
            collect(p, &p.canonicalize()?, 0, &mut seen, &mut out)?;
        } else {
            out.push(p.clone());
        }
    }
    // Natural order, folder by folder: `week-6/` before `week-10/`.
    out.sort_by(|a, b| natural_path_order(a, b));
    out.dedup();
    Ok(out)
}

/// Two paths compared component by component, each in natural order.
fn natural_path_order(a: &Path, b: &Path) -> std::cmp::Ordering {
    let (mut x, mut y) = (a.components(), b.components());
    loop {
        match (x.next(), y.next()) {
            (None, None) => return a.cmp(b),
            (None, Some(_)) => return std::cmp::Ordering::Less,
            (Some(_), None) => return std::cmp::Ordering::Greater,
            (Some(c), Some(d)) => {
                let order = crate::base::natural::compare(
                    &c.as_os_str().to_string_lossy(),
                    &d.as_os_str().to_string_lossy(),
                );
                if order != std::cmp::Ordering::Equal {
                    return order;
                }
            }
        }
    }
}

/// Loads every scene first, so that one bad file stops the run before any output; every bad one
/// is reported. Ids must be unique, and two lecture names must not make the same handout file
/// name.
pub fn load_all(paths: &[PathBuf]) -> Result<Vec<Scene>, Vec<SceneError>> {
    let mut scenes = Vec::new();
    let mut errors = Vec::new();
    for p in paths {
        match Scene::from_file(p) {
            Ok(s) => scenes.push(s),
            Err(e) => errors.push(e),
        }
    }
    let located =
        |s: &Scene, (line, column): (usize, usize), field: &str, message: String| SceneError {
            path: s.source.clone(),
            line,
            column,
            field: field.into(),
            message,
        };
    // Compared without case: file names that differ only in case are one file on macOS and
    // Windows.
    let mut by_id: Vec<&Scene> = scenes.iter().collect();
    by_id.sort_by(|a, b| (a.id.to_lowercase(), &a.source).cmp(&(b.id.to_lowercase(), &b.source)));
    for w in by_id.windows(2) {
        if w[0].id == w[1].id {
            let message = format!(
                "duplicate scene id `{}` (also in {}): page file names come from ids",
                w[0].id,
                w[0].source.display()
            );
            errors.push(located(w[1], w[1].id_at, "id", message));
        } else if w[0].id.to_lowercase() == w[1].id.to_lowercase() {
            let message = format!(
                "scene ids `{}` and `{}` (in {}) differ only in case: their pages would be one \
                 file on a case-insensitive file system (macOS, Windows); rename one",
                w[1].id,
                w[0].id,
                w[0].source.display()
            );
            errors.push(located(w[1], w[1].id_at, "id", message));
        }
    }
    // Each lecture writes four files named from its slug (`lecture-1-student.html`, …,
    // `lecture-1-problems-student.html`): no two lectures may share one, case aside. Lectures
    // `1` and `1 problems` would (the second's student handout is the first's sheet).
    let mut by_file: std::collections::BTreeMap<String, &Scene> = Default::default();
    for s in by_id {
        let slug = lecture_slug(&s.notes.lecture).to_lowercase();
        let files = LECTURE_FILES.map(|kind| format!("{slug}-{kind}"));
        let clash = files.iter().find_map(|f| {
            by_file
                .get(f)
                .filter(|first| first.notes.lecture != s.notes.lecture)
                .map(|first| (f, *first))
        });
        if let Some((file, first)) = clash {
            let message = format!(
                "lecture `{}` and lecture `{}` (in {}) would share the handout file name \
                 `{file}`: name them so that they differ in a letter or digit",
                s.notes.lecture,
                first.notes.lecture,
                first.source.display()
            );
            errors.push(located(s, s.lecture_at, "notes.lecture", message));
            continue;
        }
        for f in files {
            by_file.entry(f).or_insert(s);
        }
    }
    errors.extend(sheet_over_budget(&scenes));
    errors.extend(course_over_budget(&scenes));
    if errors.is_empty() {
        Ok(scenes)
    } else {
        Err(errors)
    }
}

/// The files each lecture writes, after its slug: handouts, problem sheet and key (the site's
/// `.html` and the `.pdf`).
const LECTURE_FILES: [&str; 4] = ["student", "instructor", "problems-student", "problems-key"];

/// The most pages a lecture's problem sheet may have: a variant of the sheet per variant of its
/// largest problem, a page per problem in each. 200 students with 50 problems each fit; one
/// problem of 10,000 variants beside 20 small ones (210,000 pages, a 520 MB key) does not.
pub const MAX_SHEET_PAGES: usize = 10_000;

/// A problem's variant count (0 for a scene that is no problem).
fn variant_count(s: &Scene) -> usize {
    s.problem.as_ref().map_or(0, |p| p.variants.len())
}

/// The problems of each lecture: its problem sheet.
fn sheets(scenes: &[Scene]) -> std::collections::BTreeMap<&str, Vec<&Scene>> {
    let mut by_lecture: std::collections::BTreeMap<&str, Vec<&Scene>> = Default::default();
    for s in scenes.iter().filter(|s| s.problem.is_some()) {
        by_lecture.entry(&s.notes.lecture).or_default().push(s);
    }
    by_lecture
}

/// Of a list of problems, the one with the most variants (the last of equals).
fn largest<'a>(problems: &[&'a Scene]) -> Option<&'a Scene> {
    problems.iter().copied().max_by_key(|s| variant_count(s))
}

/// A sheet's pages: a variant of the sheet per variant of its largest problem, a page per
/// problem in each.
fn sheet_pages(problems: &[&Scene]) -> usize {
    largest(problems).map_or(0, variant_count) * problems.len()
}

/// An over-budget error at a problem's `[variants]` count.
fn at_count(problem: &Scene, message: String) -> SceneError {
    let (line, column) = problem.problem.as_ref().map_or((1, 1), |p| p.at);
    SceneError {
        path: problem.source.clone(),
        line,
        column,
        field: "variants.count".into(),
        message,
    }
}

/// Each lecture whose problem sheet would pass [`MAX_SHEET_PAGES`], located at its largest
/// problem.
fn sheet_over_budget(scenes: &[Scene]) -> Vec<SceneError> {
    let mut errors = Vec::new();
    for (lecture, problems) in sheets(scenes) {
        let (Some(largest), pages) = (largest(&problems), sheet_pages(&problems)) else {
            continue;
        };
        if pages > MAX_SHEET_PAGES {
            errors.push(at_count(
                largest,
                format!(
                    "lecture `{lecture}`'s problem sheet would have {} variants (this problem's \
                     count) of {} problems, {pages} pages; at most {MAX_SHEET_PAGES}: lower this \
                     count, or move problems to another lecture",
                    variant_count(largest),
                    problems.len()
                ),
            ));
        }
    }
    errors
}

/// The most variants a course's problems may have together: each is derived exactly and checked
/// numerically (1 to 15 ms each here, up to seconds where a root's number must be factored).
pub const MAX_COURSE_VARIANTS: usize = 20_000;

/// The most pages all of a course's problem sheets may have together, each lecture's within
/// [`MAX_SHEET_PAGES`].
pub const MAX_COURSE_PAGES: usize = 50_000;

/// The course's problems over [`MAX_COURSE_VARIANTS`] or [`MAX_COURSE_PAGES`], located at its
/// problem with the most variants.
fn course_over_budget(scenes: &[Scene]) -> Vec<SceneError> {
    let problems: Vec<&Scene> = scenes.iter().filter(|s| s.problem.is_some()).collect();
    let variants: usize = problems.iter().map(|s| variant_count(s)).sum();
    let pages: usize = sheets(scenes).values().map(|p| sheet_pages(p)).sum();
    let Some(largest) = largest(&problems) else {
        return Vec::new();
    };
    let over = if variants > MAX_COURSE_VARIANTS {
        format!("{variants} variants in all; at most {MAX_COURSE_VARIANTS}")
    } else if pages > MAX_COURSE_PAGES {
        format!("problem sheets of {pages} pages in all; at most {MAX_COURSE_PAGES}")
    } else {
        return Vec::new();
    };
    vec![at_count(
        largest,
        format!(
            "the course's {} problems would have {over}: lower the counts, starting with this \
             problem's {}",
            problems.len(),
            variant_count(largest)
        ),
    )]
}
