//! The LaTeX our printer writes, read back as a tree, for the line breaker (linebreak.rs): a
//! cut never falls inside a brace group, a `\left…\right` pair or an environment.

/// The LaTeX our printer writes, as a tree: brace groups, `\left…\right` pairs and environments
/// are single nodes, so that a cut never falls inside one.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Node {
    Tok(String),
    Group(Vec<Node>),
    Delim {
        open: String,
        inner: Vec<Node>,
        close: String,
    },
    Env {
        name: String,
        body: Vec<Node>,
    },
}

fn tokens(latex: &str) -> Vec<String> {
    let chars: Vec<char> = latex.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c == '\\' && i + 1 < chars.len() {
            let mut j = i + 1;
            if chars[j].is_ascii_alphabetic() {
                while j < chars.len() && chars[j].is_ascii_alphabetic() {
                    j += 1;
                }
            } else {
                j += 1;
            }
            out.push(chars[i..j].iter().collect());
            i = j;
        } else {
            out.push(c.to_string());
            i += 1;
        }
    }
    out
}

/// Reads nodes until `stop` (a closing brace, `\right` or `\end`), which is left unread.
fn parse(toks: &[String], pos: &mut usize) -> Vec<Node> {
    let mut out = Vec::new();
    while *pos < toks.len() {
        let t = toks[*pos].as_str();
        match t {
            "}" | "\\right" | "\\end" => return out,
            "{" => {
                *pos += 1;
                let inner = parse(toks, pos);
                *pos += 1; // the `}`
                out.push(Node::Group(inner));
            }
            "\\left" => {
                let open = format!("\\left{}", toks.get(*pos + 1).map_or("", |s| s));
                *pos += 2;
                let inner = parse(toks, pos);
                let close = format!("\\right{}", toks.get(*pos + 1).map_or("", |s| s));
                *pos += 2;
                out.push(Node::Delim { open, inner, close });
            }
            "\\begin" => {
                let name = env_name(toks, pos);
                let body = parse(toks, pos);
                env_name(toks, pos); // the matching \end{name}
                out.push(Node::Env { name, body });
            }
            _ => {
                out.push(Node::Tok(t.to_string()));
                *pos += 1;
            }
        }
    }
    out
}

/// Reads `\begin{name}` or `\end{name}` at `pos` and returns the name.
fn env_name(toks: &[String], pos: &mut usize) -> String {
    *pos += 1;
    let mut name = String::new();
    if toks.get(*pos).is_some_and(|t| t == "{") {
        *pos += 1;
        while let Some(t) = toks.get(*pos) {
            *pos += 1;
            if t == "}" {
                break;
            }
            name.push_str(t);
        }
    }
    name
}

pub(super) fn tree(latex: &str) -> Vec<Node> {
    let toks = tokens(latex);
    let mut pos = 0;
    let mut out = Vec::new();
    // A stray closer (unbalanced input) is kept as text, so that nothing is lost.
    while pos < toks.len() {
        out.extend(parse(&toks, &mut pos));
        if pos < toks.len() {
            out.push(Node::Tok(toks[pos].clone()));
            pos += 1;
        }
    }
    out
}

fn write(nodes: &[Node], out: &mut String) {
    for n in nodes {
        match n {
            Node::Tok(t) => out.push_str(t),
            Node::Group(v) => {
                out.push('{');
                write(v, out);
                out.push('}');
            }
            Node::Delim { open, inner, close } => {
                out.push_str(open);
                write(inner, out);
                out.push_str(close);
            }
            Node::Env { name, body } => {
                out.push_str(&format!("\\begin{{{name}}}"));
                write(body, out);
                out.push_str(&format!("\\end{{{name}}}"));
            }
        }
    }
}

pub(super) fn latex(nodes: &[Node]) -> String {
    let mut s = String::new();
    write(nodes, &mut s);
    s
}

pub(super) fn tok(n: &Node) -> Option<&str> {
    match n {
        Node::Tok(t) => Some(t),
        _ => None,
    }
}
