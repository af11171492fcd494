//! A class roster (`build --roster students.csv`): a CSV file whose first line names the
//! columns `name` and `id` (in either order, other columns ignored), then one student a line.
//! Fields may be quoted (`"Lovelace, Ada"`, a quote inside doubled). Errors name the line.

use std::path::{Path, PathBuf};

/// The most students a roster may list: a class, not a registry.
pub const MAX_STUDENTS: usize = 5000;

/// The largest roster read: 5,000 students of 200 bytes a line.
pub const MAX_ROSTER_BYTES: u64 = 1 << 20;

#[derive(Debug, Clone, PartialEq)]
pub struct Student {
    pub name: String,
    pub id: String,
    /// Its line in the file.
    pub line: usize,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Roster {
    pub source: PathBuf,
    pub students: Vec<Student>,
}

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RosterError {
    #[error("{}: cannot read the roster: {why}", path.display())]
    Unreadable { path: PathBuf, why: String },
    #[error("{}:{line}: {what}", path.display())]
    At {
        path: PathBuf,
        line: usize,
        what: String,
    },
}

impl Roster {
    pub fn from_file(path: &Path) -> Result<Roster, RosterError> {
        // A regular file of bounded size: a FIFO would block and /dev/zero never end.
        use crate::scene::load::ReadError;
        let bytes = crate::scene::load::read_regular_file(path, MAX_ROSTER_BYTES, "the roster")
            .map_err(|e| RosterError::Unreadable {
                path: path.to_path_buf(),
                why: match e {
                    ReadError::Unreadable(_, why) => why,
                    other => other.to_string(),
                },
            })?;
        let text = String::from_utf8(bytes).map_err(|_| RosterError::Unreadable {
            path: path.to_path_buf(),
            why: "it is not UTF-8 text: save it as CSV UTF-8".into(),
        })?;
        Roster::parse(&text, path)
    }

    pub fn parse(text: &str, path: &Path) -> Result<Roster, RosterError> {
        let at = |line: usize, what: String| RosterError::At {
            path: path.to_path_buf(),
            line,
            what,
        };
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim_end_matches('\r')))
            .filter(|(_, l)| !l.trim().is_empty());
        let Some((header_line, header)) = lines.next() else {
            return Err(at(
                1,
                "the roster is empty: its first line names the columns `name,id`, then one \
                 student a line"
                    .into(),
            ));
        };
        let columns = fields(header).map_err(|e| at(header_line, e.to_string()))?;
        let find = |want: &str| {
            columns
                .iter()
                .position(|c| c.trim().eq_ignore_ascii_case(want))
                .ok_or_else(|| {
                    at(
                        header_line,
                        format!(
                            "no column `{want}`: the first line names the columns, as \
                             `name,id` (it has {})",
                            columns
                                .iter()
                                .map(|c| format!("`{}`", c.trim()))
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    )
                })
        };
        let (name_at, id_at) = (find("name")?, find("id")?);
        let mut students: Vec<Student> = Vec::new();
        for (line, text) in lines {
            let f = fields(text).map_err(|e| at(line, e.to_string()))?;
            let get = |k: usize, what: &str| {
                f.get(k)
                    .map(|s| s.trim().to_string())
                    .filter(|s| !s.is_empty())
                    .ok_or_else(|| at(line, format!("the student has no {what}")))
            };
            let (name, id) = (get(name_at, "name")?, get(id_at, "id")?);
            if let Some(c) = name.chars().chain(id.chars()).find(|c| c.is_control()) {
                return Err(at(line, format!("a control character ({c:?}) in a field")));
            }
            if let Some(first) = students.iter().find(|s| s.id == id) {
                return Err(at(
                    line,
                    format!(
                        "the id `{id}` is listed twice (first at line {}): each student needs \
                         an id of their own",
                        first.line
                    ),
                ));
            }
            if students.len() == MAX_STUDENTS {
                return Err(at(
                    line,
                    format!("more than {MAX_STUDENTS} students: split the roster"),
                ));
            }
            students.push(Student { name, id, line });
        }
        if students.is_empty() {
            return Err(at(header_line, "the roster lists no student".into()));
        }
        Ok(Roster {
            source: path.to_path_buf(),
            students,
        })
    }
}

/// A quoted CSV field with no closing quote on its line.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("a quoted field is not closed: end it with `\"`")]
pub struct UnclosedQuote;

/// One CSV line's fields: comma-separated, each optionally in double quotes.
fn fields(line: &str) -> Result<Vec<String>, UnclosedQuote> {
    let mut out = Vec::new();
    let mut field = String::new();
    let mut chars = line.chars().peekable();
    let mut quoted = false;
    let mut was_quoted = false;
    while let Some(c) = chars.next() {
        match (quoted, c) {
            (true, '"') if chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            (true, '"') => quoted = false,
            (true, c) => field.push(c),
            (false, '"') if field.trim().is_empty() && !was_quoted => {
                field.clear();
                quoted = true;
                was_quoted = true;
            }
            (false, ',') => {
                out.push(std::mem::take(&mut field));
                was_quoted = false;
            }
            (false, c) => field.push(c),
        }
    }
    if quoted {
        return Err(UnclosedQuote);
    }
    out.push(field);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Roster, RosterError> {
        Roster::parse(text, Path::new("students.csv"))
    }

    #[test]
    fn names_and_ids_in_either_order_with_quotes_and_crlf() {
        let r = parse(
            "id,Name,email\r\n1001,\"Lovelace, Ada\",a@x\r\n\r\n1002,Alan \"Turing\",t@x\r\n",
        )
        .unwrap();
        assert_eq!(r.students.len(), 2);
        assert_eq!(r.students[0].name, "Lovelace, Ada");
        assert_eq!(r.students[0].id, "1001");
        assert_eq!(r.students[1].name, "Alan \"Turing\"");
        assert_eq!(r.students[1].line, 4);
    }

    #[test]
    fn a_bad_roster_is_refused_at_its_line() {
        let e = parse("name,email\nAda,a@x\n").unwrap_err().to_string();
        assert!(e.starts_with("students.csv:1: no column `id`"), "{e}");
        let e = parse("name,id\nAda,1\nAlan,1\n").unwrap_err().to_string();
        assert!(
            e.contains("students.csv:3: the id `1` is listed twice (first at line 2)"),
            "{e}"
        );
        let e = parse("name,id\nAda,\n").unwrap_err().to_string();
        assert_eq!(e, "students.csv:2: the student has no id");
        let e = parse("name,id\n\"Ada,1\n").unwrap_err().to_string();
        assert!(e.contains(":2: a quoted field is not closed"), "{e}");
        assert!(
            parse("")
                .unwrap_err()
                .to_string()
                .contains(":1: the roster is empty")
        );
        assert!(
            parse("name,id\n")
                .unwrap_err()
                .to_string()
                .contains("lists no student")
        );
    }
}
