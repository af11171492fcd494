//! `check --bless`: a scene's `[expect]` and its claims' verdicts rewritten to what was derived,
//! in place, with the file's comments and layout kept (toml_edit). `check` writes the file with
//! `site::replace_file`, in one rename, so it is never half-written.

use crate::model::catalogue::{DYNAMICS_QUANTITIES, QUANTITIES, quantity};
use crate::pipeline::SceneReport;
use std::path::PathBuf;
use toml_edit::{DocumentMut, Item, TableLike, Value};

/// What `[expect]` records in a scene that has none: every derived result, but the
/// intermediate integrands and positions.
fn recorded_by_default(name: &str) -> bool {
    name != quantity::INTEGRAND && name != quantity::POSITION
}

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

    let mut tables = claim_tables(&mut doc).ok_or_else(|| BlessError::Shape {
        path: path.clone(),
        field: "claim",
    })?;
    for (i, c) in r.verification.claims.iter().enumerate() {
        if c.problem.is_some() || c.expected == Some(c.verdict) {
            continue;
        }
        if let Some(table) = tables.get_mut(i) {
            set_keeping_decor(*table, "expect", c.verdict.as_str());
            changes.push(Blessed {
                line: c.line,
                what: format!(
                    "claim (eq {}): verdict {} -> {}",
                    c.eq,
                    c.expected.map_or("(none)", |v| v.as_str()),
                    c.verdict.as_str()
                ),
            });
        }
    }

    let quantities = &r.derivation.quantities;
    match doc.get_mut("expect") {
        Some(item) => {
            let table = item.as_table_like_mut().ok_or_else(|| BlessError::Shape {
                path: path.clone(),
                field: "expect",
            })?;
            for g in r.verification.regressions.iter().filter(|g| !g.unchanged) {
                match quantities.get(&g.quantity) {
                    Some(v) => {
                        let text = v.to_text();
                        set_keeping_decor(table, &g.quantity, &text);
                        changes.push(Blessed {
                            line: 0,
                            what: format!("[expect] {}: {} -> {text}", g.quantity, g.recorded),
                        });
                    }
                    None => {
                        table.remove(&g.quantity);
                        changes.push(Blessed {
                            line: 0,
                            what: format!(
                                "[expect] {}: removed (no longer derived; was {})",
                                g.quantity, g.recorded
                            ),
                        });
                    }
                }
            }
        }
        None => {
            let mut table = toml_edit::Table::new();
            for name in QUANTITIES.iter().chain(DYNAMICS_QUANTITIES) {
                if let Some(v) = quantities.get(*name).filter(|_| recorded_by_default(name)) {
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
    }
    Ok((doc.to_string(), changes))
}

/// The claims' tables, `[[claim]]` or an inline `claim = [{…}]`, in order; none when absent.
fn claim_tables(doc: &mut DocumentMut) -> Option<Vec<&mut dyn TableLike>> {
    match doc.get_mut("claim") {
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

/// Sets `key` to the string `text`, keeping the old value's surrounding spaces and comment.
fn set_keeping_decor(table: &mut dyn TableLike, key: &str, text: &str) {
    let mut value = Value::from(text);
    if let Some(old) = table.get(key).and_then(Item::as_value) {
        *value.decor_mut() = old.decor().clone();
    }
    table.insert(key, Item::Value(value));
}
