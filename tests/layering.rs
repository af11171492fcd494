//! The layering rule, held as a test: the modules of `src/` are the pipeline, and every
//! `crate::` path in library code points to a module above its own in this list. Siblings on
//! one rank (derive and numeric) do not import each other either, so the
//! graph has no circle; nor do the children of one module (`figures/drift.rs` and
//! `figures/frame.rs`) import each other in a circle. Test code (`tests.rs`, `*_tests.rs`, `#[cfg(test)] mod` blocks) may
//! reach anywhere.

use std::collections::BTreeMap;
use std::path::Path;

/// The pipeline, top to bottom, as ranks: a module may import only lower ranks.
const LAYERS: &[&[&str]] = &[
    &["base"],
    &["cas"],
    &["notation"],
    &["model"],
    &["scene"],
    &["plan"],
    &["derive", "numeric"],
    &["steps"],
    &["figures"],
    &["verify"],
    &["pipeline"],
    &["document"],
    &["render"],
    &["report"],
    &["site"],
    &["serve"],
    &["cli"],
];

fn rank(module: &str) -> Option<usize> {
    LAYERS.iter().position(|layer| layer.contains(&module))
}

/// `foo.rs` and `foo/...` both belong to module `foo`.
fn top_module(relative: &str) -> String {
    let first = relative.split('/').next().unwrap_or(relative);
    first.strip_suffix(".rs").unwrap_or(first).to_string()
}

fn is_test_file(relative: &str) -> bool {
    let name = relative.rsplit('/').next().unwrap_or(relative);
    name == "tests.rs" || name.ends_with("_tests.rs")
}

/// The text without its `#[cfg(test)] mod name { ... }` blocks.
fn without_test_modules(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find("#[cfg(test)]") {
        let after = rest[at + "#[cfg(test)]".len()..].trim_start();
        let is_inline_mod = after.starts_with("mod ")
            && after
                .find(['{', ';'])
                .is_some_and(|k| after.as_bytes()[k] == b'{');
        if !is_inline_mod {
            out.push_str(&rest[..at + 1]);
            rest = &rest[at + 1..];
            continue;
        }
        out.push_str(&rest[..at]);
        let open = at + (rest[at..].len() - after.len()) + after.find('{').unwrap();
        let mut depth = 0usize;
        let mut end = rest.len();
        for (k, c) in rest[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = open + k + 1;
                        break;
                    }
                }
                _ => {}
            }
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// Every module `text` names through `crate::x` or `use crate::{x, y}`.
fn imported_modules(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    for (at, _) in text.match_indices("crate::") {
        let before = text[..at].chars().next_back();
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let rest = &text[at + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let group = &group[..group.find('}').unwrap_or(group.len())];
            for part in group.split(',') {
                let name = ident(part.trim());
                if !name.is_empty() {
                    found.push(name);
                }
            }
        } else {
            let name = ident(rest);
            if !name.is_empty() {
                found.push(name);
            }
        }
    }
    found
}

/// (from, to, file) for every import of another top-level module by library code.
fn edges(files: &BTreeMap<String, String>) -> Vec<(String, String, String)> {
    let mut out = Vec::new();
    for (relative, text) in files {
        if is_test_file(relative) || relative == "lib.rs" || relative == "main.rs" {
            continue;
        }
        let from = top_module(relative);
        for to in imported_modules(&without_test_modules(text)) {
            if to != from {
                out.push((from.clone(), to, relative.clone()));
            }
        }
    }
    out.sort();
    out.dedup();
    out
}

/// What breaks the rule: an unknown module, or an import that is not of a lower rank.
fn violations(files: &BTreeMap<String, String>) -> Vec<String> {
    let mut out = Vec::new();
    for relative in files.keys() {
        let m = top_module(relative);
        if !matches!(m.as_str(), "lib" | "main") && rank(&m).is_none() {
            out.push(format!("{relative}: module `{m}` is not in LAYERS"));
        }
    }
    for (from, to, file) in edges(files) {
        match (rank(&from), rank(&to)) {
            (Some(a), Some(b)) if b < a => {}
            (Some(_), Some(_)) => out.push(format!(
                "{file}: `{from}` imports `{to}`, which is not below it in the pipeline"
            )),
            _ => {}
        }
    }
    out
}

fn read_tree(root: &Path, dir: &Path, files: &mut BTreeMap<String, String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            read_tree(root, &path, files);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let relative = path
                .strip_prefix(root)
                .unwrap()
                .to_string_lossy()
                .into_owned();
            files.insert(relative, std::fs::read_to_string(&path).unwrap());
        }
    }
}

/// A file's module path: `render/pdf/sheet.rs` is render::pdf::sheet, `render/pdf/mod.rs` is
/// render::pdf.
fn module_path(relative: &str) -> Vec<String> {
    let mut parts: Vec<String> = relative.split('/').map(str::to_string).collect();
    let last = parts.pop().unwrap_or_default();
    let name = last.strip_suffix(".rs").unwrap_or(&last);
    if name != "mod" {
        parts.push(name.to_string());
    }
    parts
}

/// Whether `path` names a module of the tree: a file `a/b.rs` or a folder `a/b/`.
fn is_module(files: &BTreeMap<String, String>, path: &[String]) -> bool {
    let joined = path.join("/");
    files.contains_key(&format!("{joined}.rs"))
        || files.keys().any(|k| k.starts_with(&format!("{joined}/")))
}

/// The first names of each path a `use` or a call writes after a prefix: `a::b::{c, d::e}`
/// gives [a, b, c] and [a, b, d, e].
fn paths_after(rest: &str) -> Vec<Vec<String>> {
    let ident = |t: &str| -> String {
        t.trim()
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    let mut head = Vec::new();
    let mut rest = rest;
    loop {
        if let Some(group) = rest.strip_prefix('{') {
            // The group's top-level items, each a path of its own.
            let (mut depth, mut end) = (0, group.len());
            for (k, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => {
                        end = k;
                        break;
                    }
                    '}' => depth -= 1,
                    _ => {}
                }
            }
            let mut out = Vec::new();
            let (mut depth, mut start) = (0, 0);
            let inner = &group[..end];
            for (k, c) in inner.char_indices().chain([(inner.len(), ',')]) {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        for tail in paths_after(inner[start..k].trim()) {
                            out.push(head.iter().cloned().chain(tail).collect());
                        }
                        start = k + 1;
                    }
                    _ => {}
                }
            }
            return out;
        }
        let name = ident(rest);
        if name.is_empty() {
            return vec![head];
        }
        rest = &rest[rest.find(&name).unwrap_or(0) + name.len()..];
        head.push(name);
        match rest.strip_prefix("::") {
            Some(more) => rest = more,
            None => return vec![head],
        }
    }
}

/// (folder, from, to, file) for every import between two children of one module folder, at
/// any depth: `super::x` or `crate::a::x` in `a/y.rs` (children y and x of `a`), `super::x` in
/// `a/b/mod.rs` (children b and x of `a`), `crate::a::b::x` in `a/b/c.rs` (c and x of `a/b`).
fn inner_edges(files: &BTreeMap<String, String>) -> Vec<(String, String, String, String)> {
    let mut out = Vec::new();
    for (relative, text) in files {
        if is_test_file(relative) {
            continue;
        }
        let own = module_path(relative);
        let text = without_test_modules(text);
        let mut targets: Vec<Vec<String>> = Vec::new();
        for prefix in ["crate::", "super::"] {
            for (at, _) in text.match_indices(prefix) {
                let before = text[..at].chars().next_back();
                if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                    continue;
                }
                let mut base: Vec<String> = match prefix {
                    "crate::" => Vec::new(),
                    _ => own[..own.len().saturating_sub(1)].to_vec(),
                };
                let mut rest = &text[at + prefix.len()..];
                while let Some(more) = rest.strip_prefix("super::") {
                    base.pop();
                    rest = more;
                }
                for tail in paths_after(rest) {
                    let mut path = base.clone();
                    for name in tail {
                        path.push(name);
                        if !is_module(files, &path) {
                            path.pop();
                            break;
                        }
                    }
                    targets.push(path);
                }
            }
        }
        for to in targets {
            // The folder both lie in: the edge between its two children.
            let shared = own.iter().zip(&to).take_while(|(a, b)| a == b).count();
            if shared == 0 || shared >= own.len() || shared >= to.len() {
                continue;
            }
            out.push((
                own[..shared].join("/"),
                own[shared].clone(),
                to[shared].clone(),
                relative.clone(),
            ));
        }
    }
    out.sort();
    out.dedup();
    out
}

/// Each circle among the children of a module folder, at any depth, as `top: a -> b -> a`.
fn inner_circles(files: &BTreeMap<String, String>) -> Vec<String> {
    let edges = inner_edges(files);
    let mut graph: BTreeMap<(String, String), Vec<String>> = BTreeMap::new();
    for (top, from, to, _) in &edges {
        graph
            .entry((top.clone(), from.clone()))
            .or_default()
            .push(to.clone());
    }
    let mut out = Vec::new();
    for (top, start) in graph.keys() {
        // A path from `start` back to itself, found depth-first; reported once, from its
        // smallest member.
        let mut stack = vec![(start.clone(), vec![start.clone()])];
        let mut seen = std::collections::BTreeSet::new();
        while let Some((node, path)) = stack.pop() {
            for next in graph
                .get(&(top.clone(), node.clone()))
                .into_iter()
                .flatten()
            {
                if next == start {
                    if path.iter().all(|p| p >= start) {
                        out.push(format!("{top}: {} -> {start}", path.join(" -> ")));
                    }
                } else if seen.insert(next.clone()) {
                    let mut longer = path.clone();
                    longer.push(next.clone());
                    stack.push((next.clone(), longer));
                }
            }
        }
    }
    out.sort();
    out.dedup();
    out
}

#[test]
fn no_circle_between_the_children_of_a_module() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = BTreeMap::new();
    read_tree(&root, &root, &mut files);
    let circles = inner_circles(&files);
    assert!(circles.is_empty(), "{}", circles.join("\n"));
    // The walk sees the real inner graph: the figures use their shared frame.
    let edges = inner_edges(&files);
    assert!(
        edges
            .iter()
            .any(|(top, from, to, _)| top == "figures" && from == "drift" && to == "frame"),
        "{edges:?}"
    );
}

#[test]
fn the_checker_finds_a_circle_between_the_children_of_a_module() {
    // As `figures/` was: a dispatcher among the children, whose figures import its helpers.
    let files = BTreeMap::from([
        (
            "figures/mod.rs".to_string(),
            "mod free_body;\nmod drift;\nuse crate::figures::drift::go;\n".to_string(),
        ),
        (
            "figures/free_body.rs".to_string(),
            "pub fn figure() { super::drift::drift() }\npub fn fig() {}\n".to_string(),
        ),
        (
            "figures/drift.rs".to_string(),
            "use super::free_body::{body_text, fig};\nuse super::FigureError;\n".to_string(),
        ),
        // Deeper files reach their siblings through the crate path.
        (
            "scene/validate/text.rs".to_string(),
            "use crate::scene::load::read;\n".to_string(),
        ),
        (
            "scene/load.rs".to_string(),
            "fn f() { crate::scene::validate::text::check() }\n".to_string(),
        ),
        // Nested: two files of render/pdf, and a folder's mod.rs with a sibling of its folder.
        (
            "render/pdf/handout.rs".to_string(),
            "use super::sheet::said_unit;\n".to_string(),
        ),
        (
            "render/pdf/sheet.rs".to_string(),
            "fn f() { super::handout::numbers() }\n".to_string(),
        ),
        (
            "render/pdf/mod.rs".to_string(),
            "mod handout;\nmod sheet;\nuse super::renderer::{Context, Rendered};\n".to_string(),
        ),
        (
            "render/renderer.rs".to_string(),
            "use super::{RenderError, pdf::PdfSource};\n".to_string(),
        ),
        // Not a circle: a child using its parent's types, and test code.
        (
            "figures/flip.rs".to_string(),
            "use super::FigureError;\n#[cfg(test)]\nmod tests {\n    use super::super::drift;\n}\n"
                .to_string(),
        ),
    ]);
    let circles = inner_circles(&files);
    assert_eq!(
        circles,
        [
            "figures: drift -> free_body -> drift",
            "render/pdf: handout -> sheet -> handout",
            "render: pdf -> renderer -> pdf",
            "scene: load -> validate -> load"
        ],
        "{circles:#?}"
    );
}

/// The renderers, each a child of `render/`: none may import another, so that each prints
/// the documents alone (what they share is `renderer`, `memo` and `plot`).
const RENDERERS: &[&str] = &["html", "json", "lms", "moodle", "pdf"];

/// Every import from one renderer into another, as `from -> to (file)`.
fn between_renderers(files: &BTreeMap<String, String>) -> Vec<String> {
    inner_edges(files)
        .into_iter()
        .filter(|(top, from, to, _)| {
            top == "render"
                && RENDERERS.contains(&from.as_str())
                && RENDERERS.contains(&to.as_str())
        })
        .map(|(_, from, to, file)| format!("{from} -> {to} ({file})"))
        .collect()
}

#[test]
fn no_renderer_imports_another() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = BTreeMap::new();
    read_tree(&root, &root, &mut files);
    for r in RENDERERS {
        assert!(
            is_module(&files, &["render".to_string(), r.to_string()]),
            "render/{r} is not a module"
        );
    }
    let edges = between_renderers(&files);
    assert!(edges.is_empty(), "{}", edges.join("\n"));
    // The checker sees the renderers' imports of what they share.
    assert!(
        inner_edges(&files)
            .iter()
            .any(|(top, from, to, _)| top == "render" && from == "pdf" && to == "memo"),
        "the walk sees no edge from render/pdf"
    );
}

#[test]
fn the_checker_finds_one_renderer_importing_another() {
    let files = BTreeMap::from([
        (
            "render/html/mod.rs".to_string(),
            "mod page;\nfn f() { super::pdf::lecture_pdfs() }\n".to_string(),
        ),
        (
            "render/html/page.rs".to_string(),
            "use super::super::memo;\n".to_string(),
        ),
        (
            "render/pdf/sheet.rs".to_string(),
            "use crate::render::html::problems::Recall;\n".to_string(),
        ),
        ("render/pdf/mod.rs".to_string(), "mod sheet;\n".to_string()),
        ("render/memo.rs".to_string(), String::new()),
        ("render/html/problems.rs".to_string(), String::new()),
    ]);
    assert_eq!(
        between_renderers(&files),
        [
            "html -> pdf (render/html/mod.rs)",
            "pdf -> html (render/pdf/sheet.rs)"
        ]
    );
}

#[test]
fn every_import_points_down_the_pipeline() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = BTreeMap::new();
    read_tree(&root, &root, &mut files);
    assert!(files.len() > 40, "read {} files", files.len());
    let problems = violations(&files);
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    // The walk found the real graph: the pipeline reads the scene, cli reads the pipeline.
    let found = edges(&files);
    for (a, b) in [
        ("pipeline", "scene"),
        ("cli", "pipeline"),
        ("figures", "numeric"),
    ] {
        assert!(
            found.iter().any(|(f, t, _)| f == a && t == b),
            "no edge {a} -> {b}"
        );
    }
}

#[test]
fn lib_declares_the_modules_in_pipeline_order() {
    let lib =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs")).unwrap();
    let ranks: Vec<usize> = lib
        .lines()
        .filter_map(|l| l.strip_prefix("pub mod "))
        .map(|m| rank(m.trim_end_matches(';')).expect("a module of LAYERS"))
        .collect();
    assert_eq!(ranks.len(), LAYERS.iter().map(|l| l.len()).sum::<usize>());
    assert!(ranks.windows(2).all(|w| w[0] <= w[1]), "{ranks:?}");
}

#[test]
fn the_checker_finds_backward_edges_circles_and_strays() {
    let files = BTreeMap::from([
        // Backward: numeric reaching up into figures.
        (
            "numeric/plots.rs".to_string(),
            "use crate::figures::Figure;\n".to_string(),
        ),
        // A circle between siblings, one side through a `use crate::{..}` group.
        (
            "derive/mod.rs".to_string(),
            "use crate::{cas, numeric};\n".to_string(),
        ),
        (
            "numeric/mod.rs".to_string(),
            "fn f() { crate::derive::go() }\n".to_string(),
        ),
        // Allowed: downward, and anything in test code.
        (
            "verify.rs".to_string(),
            "use crate::scene::Scene;\n#[cfg(test)]\nmod tests {\n    use crate::cli::run;\n}\n"
                .to_string(),
        ),
        (
            "scene/tests.rs".to_string(),
            "use crate::site::write;\n".to_string(),
        ),
        ("stray.rs".to_string(), String::new()),
    ]);
    let problems = violations(&files);
    assert_eq!(problems.len(), 4, "{problems:#?}");
    assert!(problems[0].contains("module `stray`"));
    assert!(
        problems
            .iter()
            .any(|p| p.contains("`derive` imports `numeric`"))
    );
    assert!(
        problems
            .iter()
            .any(|p| p.contains("`numeric` imports `derive`"))
    );
    assert!(
        problems
            .iter()
            .any(|p| p.contains("`numeric` imports `figures`"))
    );
}

#[test]
fn every_cited_step_is_in_the_catalogue_and_back() {
    // The keys the derivations give their steps (`cited("key", …)`) against the list that
    // validates a scene's `[cite]` table: a key missing from either would be uncitable or dead.
    let mut used = std::collections::BTreeSet::new();
    for entry in std::fs::read_dir("src/derive").unwrap() {
        let text = std::fs::read_to_string(entry.unwrap().path()).unwrap();
        for part in text.split("cited(").skip(1) {
            if let Some(rest) = part.trim_start().strip_prefix('"') {
                let key = rest.split('"').next().unwrap();
                if !key.is_empty() {
                    used.insert(key.to_string());
                }
            }
        }
    }
    let catalogue = std::fs::read_to_string("src/model/catalogue.rs").unwrap();
    let list = &catalogue[catalogue.find("CITABLE_STEPS").unwrap()..];
    let list = &list[..list.find("];").unwrap()];
    let listed: std::collections::BTreeSet<String> = list
        .lines()
        .filter_map(|l| {
            l.trim()
                .strip_prefix('"')?
                .strip_suffix("\",")
                .map(String::from)
        })
        .collect();
    assert!(used.len() >= 28, "{used:?}");
    assert_eq!(used, listed);
}

/// Lines of `files` under `folder/` (or the file `folder.rs`), outside test modules, that
/// contain any of `needles`.
fn uses_in(files: &BTreeMap<String, String>, folder: &str, needles: &[&str]) -> Vec<String> {
    files
        .iter()
        .filter(|(f, _)| {
            (f.starts_with(&format!("{folder}/")) || *f == &format!("{folder}.rs"))
                && !is_test_file(f)
        })
        .flat_map(|(f, text)| {
            without_test_modules(text)
                .lines()
                .filter(|l| needles.iter().any(|n| l.contains(n)))
                .map(|l| format!("{f}: {}", l.trim()))
                .collect::<Vec<_>>()
        })
        .collect()
}

#[test]
fn render_and_report_read_no_file_and_parse_no_expression() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = BTreeMap::new();
    read_tree(&root, &root, &mut files);
    let io = ["std::fs", "File::", "read_to_string", "read_dir"];
    let parsing = ["cas::parse", "parse_input", ", parse}", "{parse,", "Parsed"];
    let mut found = uses_in(&files, "render", &io);
    for folder in ["render", "report"] {
        found.extend(uses_in(&files, folder, &parsing));
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
    // The search sees the code: the site reads the template folder, the claims parse text.
    assert!(!uses_in(&files, "site", &io).is_empty());
    assert!(!uses_in(&files, "scene", &parsing).is_empty());
}

/// docs/architecture.md's folder tree names every module of `src/`, in the order of [`LAYERS`]:
/// the document a newcomer reads is the rule this test holds.
#[test]
fn the_architecture_document_lists_the_modules_in_their_order() {
    let doc = std::fs::read_to_string("docs/architecture.md").unwrap();
    let tree = doc
        .split("```")
        .nth(1)
        .expect("docs/architecture.md has its folder tree");
    let listed: Vec<String> = tree
        .lines()
        .filter_map(|l| l.strip_prefix("src/"))
        .map(|l| top_module(l.split_whitespace().next().unwrap().trim_end_matches('/')))
        .collect();
    let ordered: Vec<String> = LAYERS
        .iter()
        .flat_map(|layer| layer.iter().map(|m| m.to_string()))
        .collect();
    assert_eq!(listed, ordered, "docs/architecture.md's folder tree");
    let mut modules: Vec<String> = std::fs::read_dir("src")
        .unwrap()
        .map(|e| top_module(&e.unwrap().file_name().to_string_lossy()))
        .filter(|m| m != "lib" && m != "main")
        .collect();
    modules.sort();
    modules.dedup();
    let mut sorted = ordered.clone();
    sorted.sort();
    assert_eq!(modules, sorted, "the modules of src/ and LAYERS");
}

/// Every file docs/architecture.md names by its path (`render/pdf/glyphs.rs`) is in `src/` or
/// the repository: a file moved or removed leaves no claim behind.
#[test]
fn every_file_the_architecture_document_names_exists() {
    let doc = std::fs::read_to_string("docs/architecture.md").unwrap();
    let mut named = 0;
    for piece in doc.split('`').skip(1).step_by(2) {
        let is_path = piece.ends_with(".rs")
            && piece.contains('/')
            && piece
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || "_/.".contains(c));
        if !is_path {
            continue;
        }
        named += 1;
        assert!(
            Path::new("src").join(piece).exists() || Path::new(piece).exists(),
            "docs/architecture.md names `{piece}`, which is not a file"
        );
    }
    assert!(
        named > 40,
        "only {named} paths found: the test reads the document wrongly"
    );
}
