//! The LMS exports read back: every problem of tests/course and the lectures is in the QTI 2.1
//! package, the Canvas package and the Blackboard upload of its lecture, and each variant's
//! values, answers, tolerance and unit read from them equal the key's (the JSON export of the
//! problem's page) to 1e-12. The readers here are this test's own: a zip reader with its own
//! CRC, roxmltree for the XML, and a split on tabs; none of the writer's code. Every QTI 2.1
//! item is validated against the QTI 2.1 schema with xmllint, which CI installs.

use super::{mechbook, scratch, stderr};
use serde_json::Value as Json;
use std::collections::BTreeMap;
use std::path::Path;

/// Each (problem, variant, answer, entry) of the key, and whether an export holds it.
type Seen = BTreeMap<(String, u64, usize, usize), bool>;

/// A Blackboard record read back: its answer, tolerance and unit.
type Record = (f64, f64, Option<String>);

/// One variant of one problem as the key gives it.
struct KeyVariant {
    values: BTreeMap<String, f64>,
    /// Each answer's entries, its relative quiz tolerance and its unit.
    answers: Vec<(Vec<f64>, f64, Option<String>)>,
}

/// A problem of the key: its id, plain title and variants by number.
struct KeyProblem {
    id: String,
    title: String,
    variants: BTreeMap<u64, KeyVariant>,
}

fn key(site: &Path) -> Vec<KeyProblem> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(site.join("export/json")).unwrap() {
        let path = entry.unwrap().path();
        let json: Json = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let Some(variants) = json["variants"].as_array().filter(|v| !v.is_empty()) else {
            continue;
        };
        let variants = variants
            .iter()
            .map(|v| {
                let values = v["values"]
                    .as_object()
                    .unwrap()
                    .iter()
                    .map(|(k, x)| (k.clone(), x["numeric"].as_f64().unwrap()))
                    .collect();
                let answers = v["answers"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|a| {
                        let numbers = a["numeric"]
                            .as_array()
                            .unwrap()
                            .iter()
                            .map(|x| x.as_f64().unwrap())
                            .collect();
                        let unit = a["unit"].as_str().map(|u| u.replace('*', " "));
                        (numbers, a["quiz_tolerance"].as_f64().unwrap(), unit)
                    })
                    .collect();
                (
                    v["number"].as_u64().unwrap(),
                    KeyVariant { values, answers },
                )
            })
            .collect();
        // The title as plain text, as the problem's page gives it.
        let id = json["id"].as_str().unwrap().to_string();
        let page = std::fs::read_to_string(site.join(format!("{id}.html"))).unwrap();
        let title = page
            .split("<title>")
            .nth(1)
            .unwrap()
            .split(" — ")
            .next()
            .unwrap();
        out.push(KeyProblem {
            title: title.replace("&amp;", "&").replace("&#x27;", "'"),
            id,
            variants,
        });
    }
    out.sort_by(|a, b| a.id.cmp(&b.id));
    out
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()) || a == b
}

/// The absolute tolerance the key asks of an answer: relative to its largest entry.
fn absolute(numbers: &[f64], relative: f64) -> f64 {
    relative * numbers.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// A zip's stored files, read from its central directory, each checked against its CRC.
pub fn unzip(bytes: &[u8]) -> BTreeMap<String, String> {
    let u16_at = |i: usize| u16::from_le_bytes([bytes[i], bytes[i + 1]]) as usize;
    let u32_at = |i: usize| u32::from_le_bytes(bytes[i..i + 4].try_into().unwrap()) as usize;
    let end = bytes.len() - 22;
    assert_eq!(u32_at(end), 0x0605_4b50, "no end of central directory");
    let (count, mut at) = (u16_at(end + 10), u32_at(end + 16));
    let mut files = BTreeMap::new();
    for _ in 0..count {
        assert_eq!(u32_at(at), 0x0201_4b50, "a central entry");
        assert_eq!(u16_at(at + 10), 0, "stored, not compressed");
        let (crc, size, name_len) = (u32_at(at + 16), u32_at(at + 20), u16_at(at + 28));
        let skip = u16_at(at + 30) + u16_at(at + 32);
        let name = String::from_utf8(bytes[at + 46..at + 46 + name_len].to_vec()).unwrap();
        let local = u32_at(at + 42);
        assert_eq!(u32_at(local), 0x0403_4b50, "{name}: a local header");
        let start = local + 30 + u16_at(local + 26) + u16_at(local + 28);
        let data = &bytes[start..start + size];
        assert_eq!(crc32(data), crc as u32, "{name}: its CRC");
        files.insert(name, String::from_utf8(data.to_vec()).unwrap());
        at += 46 + name_len + skip;
    }
    files
}

fn crc32(data: &[u8]) -> u32 {
    let table: Vec<u32> = (0..256u32)
        .map(|n| {
            (0..8).fold(n, |c, _| {
                if c & 1 == 1 {
                    0xEDB8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                }
            })
        })
        .collect();
    !data.iter().fold(!0u32, |c, &b| {
        table[((c ^ u32::from(b)) & 0xff) as usize] ^ (c >> 8)
    })
}

/// An element's text with `<sup>k</sup>` as `^k` (and `−` as `-`): a unit as written.
fn unit_text(node: roxmltree::Node) -> String {
    node.children()
        .map(|c| match c.tag_name().name() {
            "sup" => format!("^{}", c.text().unwrap_or("").replace('−', "-")),
            _ => c.text().unwrap_or("").to_string(),
        })
        .collect::<String>()
        .trim()
        .to_string()
}

/// The problem, answer and entry a part's identifier names (`problem-box-1-5`): the key's
/// problem whose id it starts with, longest first.
fn part_of<'a>(problems: &'a [KeyProblem], id: &str) -> (&'a KeyProblem, usize, usize) {
    let p = problems
        .iter()
        .filter(|p| id.starts_with(&format!("{}-", p.id)))
        .max_by_key(|p| p.id.len())
        .unwrap_or_else(|| panic!("{id}: no problem of the key"));
    let rest: Vec<usize> = id[p.id.len() + 1..]
        .split('-')
        .map(|k| k.parse().unwrap())
        .collect();
    (p, rest[0] - 1, rest.get(1).map_or(0, |e| e - 1))
}

/// What every export must hold: each (problem, variant, answer, entry) of the key once.
fn every_entry(problems: &[KeyProblem]) -> Seen {
    let mut all = BTreeMap::new();
    for p in problems {
        for (n, v) in &p.variants {
            for (k, (numbers, _, _)) in v.answers.iter().enumerate() {
                for e in 0..numbers.len() {
                    all.insert((p.id.clone(), *n, k, e), false);
                }
            }
        }
    }
    all
}

fn read_qti21(site: &Path, problems: &[KeyProblem], seen: &mut Seen) -> usize {
    let mut items = 0;
    for entry in std::fs::read_dir(site.join("export/qti21")).unwrap() {
        let files = unzip(&std::fs::read(entry.unwrap().path()).unwrap());
        let manifest = roxmltree::Document::parse(&files["imsmanifest.xml"]).unwrap();
        let listed: Vec<&str> = manifest
            .descendants()
            .filter(|n| n.has_tag_name("file"))
            .map(|n| n.attribute("href").unwrap())
            .collect();
        assert_eq!(
            listed.len() + 1,
            files.len(),
            "the manifest lists every item"
        );
        for href in listed {
            let doc = roxmltree::Document::parse(&files[href]).unwrap();
            let root = doc.root_element();
            let id = root.attribute("identifier").unwrap();
            let (stem, n) = id.strip_prefix("item-").unwrap().rsplit_once("-v").unwrap();
            let (p, k, e) = part_of(problems, stem);
            let n: u64 = n.parse().unwrap();
            let v = &p.variants[&n];
            let (numbers, relative, unit) = &v.answers[k];
            let find = |tag: &str| root.descendants().find(|d| d.has_tag_name(tag)).unwrap();
            let value = |node: roxmltree::Node| -> f64 {
                let value = node
                    .descendants()
                    .find(|d| d.has_tag_name("value"))
                    .unwrap();
                value.text().unwrap().parse().unwrap()
            };
            assert!(
                close(value(find("correctResponse")), numbers[e]),
                "{id}: answer"
            );
            let tol: f64 = find("equal")
                .attribute("tolerance")
                .unwrap()
                .split(' ')
                .next()
                .unwrap()
                .parse()
                .unwrap();
            assert!(close(tol, absolute(numbers, *relative)), "{id}: tolerance");
            for t in root
                .descendants()
                .filter(|d| d.has_tag_name("templateDeclaration"))
            {
                let name = t
                    .attribute("identifier")
                    .unwrap()
                    .strip_prefix("given_")
                    .unwrap();
                assert!(close(value(t), v.values[name]), "{id}: value of {name}");
            }
            let shown = root
                .descendants()
                .find(|d| d.attribute("class") == Some("unit"))
                .map(unit_text);
            assert_eq!(shown.as_ref(), unit.as_ref(), "{id}: unit");
            assert!(
                !seen.insert((p.id.clone(), n, k, e), true).unwrap(),
                "{id} twice"
            );
            items += 1;
        }
    }
    items
}

fn read_canvas(site: &Path, problems: &[KeyProblem], seen: &mut Seen) {
    for entry in std::fs::read_dir(site.join("export/canvas")).unwrap() {
        let files = unzip(&std::fs::read(entry.unwrap().path()).unwrap());
        let manifest = roxmltree::Document::parse(&files["imsmanifest.xml"]).unwrap();
        let href = manifest
            .descendants()
            .find(|n| n.has_tag_name("file"))
            .unwrap()
            .attribute("href")
            .unwrap();
        let doc = roxmltree::Document::parse(&files[href]).unwrap();
        for item in doc.descendants().filter(|n| n.has_tag_name("item")) {
            let id = item.attribute("ident").unwrap();
            let (p, k, e) = part_of(problems, id);
            let text = |tag: &str| {
                item.descendants()
                    .find(|d| d.has_tag_name(tag))
                    .unwrap()
                    .text()
                    .unwrap()
                    .to_string()
            };
            let kind = item
                .descendants()
                .find(|d| d.has_tag_name("fieldentry"))
                .unwrap();
            assert_eq!(kind.text(), Some("calculated_question"), "{id}");
            // The question's HTML, parsed as XML: its unit.
            let wrapped = format!("<t>{}</t>", text("mattext"));
            let html = roxmltree::Document::parse(&wrapped).unwrap();
            let unit = html
                .descendants()
                .find(|d| d.attribute("class") == Some("unit"))
                .map(unit_text);
            let tolerance = text("answer_tolerance");
            let mut least = f64::INFINITY;
            for set in item.descendants().filter(|d| d.has_tag_name("var_set")) {
                let n: u64 = set.attribute("ident").unwrap().parse().unwrap();
                let v = &p.variants[&n];
                let (numbers, relative, key_unit) = &v.answers[k];
                assert_eq!(unit.as_ref(), key_unit.as_ref(), "{id}: unit");
                for var in set.children().filter(|d| d.has_tag_name("var")) {
                    let name = var.attribute("name").unwrap();
                    let x: f64 = var.text().unwrap().parse().unwrap();
                    assert!(close(x, v.values[name]), "{id} variant {n}: {name}");
                    // Canvas puts each value in the text at `[name]`.
                    assert!(
                        text("mattext").contains(&format!("[{name}]")),
                        "{id}: [{name}]"
                    );
                }
                let answer: f64 = set
                    .children()
                    .find(|d| d.has_tag_name("answer"))
                    .unwrap()
                    .text()
                    .unwrap()
                    .parse()
                    .unwrap();
                assert!(close(answer, numbers[e]), "{id} variant {n}: answer");
                match tolerance.strip_suffix('%') {
                    // A percentage is the key's tolerance exactly where the entry is the
                    // answer's largest.
                    Some(percent) => {
                        let r: f64 = percent.parse().unwrap();
                        assert!(close(r / 100.0, *relative), "{id}: {tolerance}");
                        assert!(
                            close(
                                absolute(&numbers[e..=e], r / 100.0),
                                absolute(numbers, *relative)
                            ),
                            "{id} variant {n}: {tolerance}"
                        );
                    }
                    None => least = least.min(absolute(numbers, *relative)),
                }
                assert!(
                    !seen.insert((p.id.clone(), n, k, e), true).unwrap(),
                    "{id} {n} twice"
                );
            }
            if !tolerance.ends_with('%') {
                let t: f64 = tolerance.parse().unwrap();
                assert!(
                    close(t, least),
                    "{id}: {t} is not the least of the key's, {least}"
                );
            }
        }
    }
}

fn read_blackboard(site: &Path, problems: &[KeyProblem], seen: &mut Seen) {
    // Each (title, variant)'s records in file order are its answers' entries in order.
    let mut records: BTreeMap<(String, u64), Vec<Record>> = BTreeMap::new();
    let mut names: Vec<_> = std::fs::read_dir(site.join("export/blackboard"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    names.sort_by_key(|p| (p.to_string_lossy().len(), p.clone()));
    for path in names {
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(
            text.lines().count() <= 250,
            "{}: over 250 records",
            path.display()
        );
        // The question is HTML: its entities read back.
        let text = text
            .replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&amp;", "&");
        for line in text.lines() {
            let fields: Vec<&str> = line.split('\t').collect();
            assert_eq!((fields.len(), fields[0]), (4, "NUM"), "{line}");
            let (question, reference) = fields[1].rsplit_once(" [").unwrap();
            let (title, n) = reference
                .strip_suffix(']')
                .unwrap()
                .rsplit_once(", variant ")
                .unwrap();
            let unit = question
                .strip_suffix(").")
                .and_then(|q| q.rsplit_once(" (in "))
                .map(|(_, u)| u.to_string());
            records
                .entry((title.to_string(), n.parse().unwrap()))
                .or_default()
                .push((fields[2].parse().unwrap(), fields[3].parse().unwrap(), unit));
        }
    }
    for p in problems {
        for (n, v) in &p.variants {
            let got = &records[&(p.title.clone(), *n)];
            let mut i = 0;
            for (k, (numbers, relative, unit)) in v.answers.iter().enumerate() {
                for (e, x) in numbers.iter().enumerate() {
                    let (answer, tol, shown) = &got[i];
                    assert!(
                        close(*answer, *x),
                        "{} variant {n}: answer {k} entry {e}",
                        p.id
                    );
                    assert!(
                        close(*tol, absolute(numbers, *relative)),
                        "{} variant {n}: tolerance",
                        p.id
                    );
                    assert_eq!(shown.as_ref(), unit.as_ref(), "{} variant {n}: unit", p.id);
                    seen.insert((p.id.clone(), *n, k, e), true);
                    i += 1;
                }
            }
            assert_eq!(i, got.len(), "{} variant {n}: records", p.id);
        }
    }
}

/// xmllint on every item of the site's QTI 2.1 packages; CI must have it.
fn validate_qti21(site: &Path, dir: &Path) {
    if std::process::Command::new("xmllint")
        .arg("--version")
        .output()
        .is_err()
    {
        assert!(
            std::env::var_os("CI").is_none(),
            "CI needs libxml2-utils (xmllint) for the QTI 2.1 schema"
        );
        return;
    }
    let schema = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/qti21/imsqti_v2p1p2.xsd");
    let mut paths = Vec::new();
    for entry in std::fs::read_dir(site.join("export/qti21")).unwrap() {
        for (name, text) in unzip(&std::fs::read(entry.unwrap().path()).unwrap()) {
            if name.starts_with("items/") {
                let path = dir.join(&name);
                std::fs::create_dir_all(path.parent().unwrap()).unwrap();
                std::fs::write(&path, text).unwrap();
                paths.push(path);
            }
        }
    }
    let run = std::process::Command::new("xmllint")
        .arg("--noout")
        .arg("--schema")
        .arg(&schema)
        .args(&paths)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&run.stderr);
    let valid = said.lines().filter(|l| l.ends_with(" validates")).count();
    assert!(
        run.status.success() && valid == paths.len(),
        "{valid} of {} items valid:\n{said}",
        paths.len()
    );
}

fn round_trip(course: &str, name: &str) {
    let dir = scratch(name);
    let site = dir.join("site");
    let out = mechbook(&[
        "build",
        course,
        "--no-cache",
        "--out",
        site.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let problems = key(&site);
    assert!(!problems.is_empty());
    for read in [
        read_qti21 as fn(&Path, &[KeyProblem], &mut _) -> usize,
        |s, p, seen| {
            read_canvas(s, p, seen);
            0
        },
        |s, p, seen| {
            read_blackboard(s, p, seen);
            0
        },
    ] {
        let mut seen = every_entry(&problems);
        read(&site, &problems, &mut seen);
        let missing: Vec<_> = seen.iter().filter(|(_, s)| !**s).map(|(k, _)| k).collect();
        assert!(missing.is_empty(), "not exported: {missing:?}");
    }
    validate_qti21(&site, &dir);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn every_problem_of_the_test_course_reads_back_from_each_lms_export() {
    round_trip("tests/course", "lms-course");
}

#[test]
fn every_problem_of_the_lectures_reads_back_from_each_lms_export() {
    round_trip("lectures", "lms-lectures");
}
