//! The one LaTeX reader. An author's `$…$`, a symbol's `tex`, and the LaTeX that the pages'
//! printers hand on are read here, by pulldown-latex's parser, into one tree ([`Tex`]); the
//! MathML, Typst and line-breaking code work on that tree and never on text. What the parser
//! cannot read is refused with its reason, so scene validation names it at its line.

use pulldown_latex::event::{
    Content, Dimension, EnvironmentFlow, Event, Grouping, RelationContent, ScriptPosition,
    ScriptType, StateChange, Visual,
};
use pulldown_latex::{Parser, Storage};

/// Why LaTeX cannot be read or set.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TexError {
    /// The parser's own reason, first line.
    #[error("{0}")]
    Parse(String),
    #[error("groups nested more than {MAX_DEPTH} deep")]
    TooDeep,
    #[error(
        "more than {MAX_CHAIN} commands in a chain, each the argument of the one before: give \
         each argument its braces, `\\vec{{\\vec{{x}}}}`"
    )]
    Chain,
    #[error("{0} is not among what the PDFs can set (see docs/scenes.md)")]
    Unprintable(&'static str),
    #[error(
        "`\\{0}` takes a number written in ASCII (`\\char65`, `\\char\"41`): write the \
         character itself instead"
    )]
    NotANumber(&'static str),
    #[error("it gives the control character U+{0:04X}, which no page or file can show")]
    Control(u32),
    /// The parser failed where mechbook does not yet steer around it: a located refusal
    /// rather than a crash (the fuzz suite treats it as a defect to steer around).
    #[error("{READER_FAULT}; rewrite the formula, and please report it as a mechbook bug")]
    ReaderFault,
}

/// What [`TexError::ReaderFault`] says: the fuzz suite looks for it.
pub const READER_FAULT: &str = "the LaTeX reader (pulldown-latex) failed on this formula";

/// The deepest nesting read: a guard for the stack, far beyond what an author writes or
/// mechbook's printers write.
pub const MAX_DEPTH: usize = 200;

/// The levels a script set above or below its base counts for (see [`element`]).
const ABOVE_BELOW_LEVELS: usize = 3;

/// The longest chain of commands each the argument of the one before (`\vec\vec…x`,
/// `\frac1\frac1…`), which the parser reads by recursion: 2,000 overflow a test thread's
/// stack (measured), 500 do not.
pub const MAX_CHAIN: usize = 250;

/// LaTeX read into a tree: each node one element of pulldown-latex's event stream, its operands
/// (a fraction's two parts, a script's base and scripts, a group's content) as its children.
///
/// It keeps the LaTeX it was read from, for Moodle, `--json` and the terminal, which show an
/// author's mathematics as written; it is stored (the build cache) as that text, read again.
#[derive(Debug, Clone, PartialEq)]
pub struct Tex {
    pub source: String,
    pub nodes: Vec<Node>,
}

impl serde::Serialize for Tex {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.source)
    }
}

impl<'de> serde::Deserialize<'de> for Tex {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Tex, D::Error> {
        let source = String::deserialize(d)?;
        Tex::read(&source).map_err(serde::de::Error::custom)
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum Node {
    /// Words in text mode (`\text{…}`); `&nbsp;` for a `~` or `\ `.
    Text(String),
    Number(String),
    /// An operator name: `\sin`, `\operatorname{tr}`.
    Function(String),
    /// Any other atom: a letter, an operator, a relation, a delimiter, punctuation.
    Atom(Content<'static>),
    /// `{…}`, `\left…\right`, an environment: the content, with its rows' `&` and `\\` as
    /// [`Node::Flow`] items.
    Group(Grouping, Vec<Node>),
    /// A fraction (numerator, denominator), a root (radicand, index), a square root or a
    /// negation (one operand).
    Visual(Visual, Vec<Node>),
    /// A base and its scripts: subscript, superscript, or both in that order.
    Script {
        ty: ScriptType,
        position: ScriptPosition,
        parts: Vec<Node>,
    },
    Space(Option<Dimension>),
    State(StateChange),
    Flow(EnvironmentFlow),
}

impl Tex {
    /// Reads LaTeX math (as between `$` signs).
    pub fn read(latex: &str) -> Result<Tex, TexError> {
        if chained_commands(latex) > MAX_CHAIN {
            return Err(TexError::Chain);
        }
        let text = parser_text(latex)?;
        let nodes = without_panic_messages(|| {
            std::panic::catch_unwind(|| {
                let storage = Storage::new();
                let mut events = Parser::new(&text, &storage);
                let mut nodes = Vec::new();
                while let Some(node) = element(&mut events, 0)? {
                    nodes.push(node);
                }
                Ok(nodes)
            })
        })
        .map_err(|_| TexError::ReaderFault)??;
        Ok(Tex {
            source: latex.to_string(),
            nodes,
        })
    }
}

/// The text handed to the parser, on which it never slices inside a character.
///
/// pulldown-latex 0.8 steps one byte past the optional space after a number or a unit
/// (`\kern1em`, `\char"41`), and past the first character of a number it cannot read
/// (`\char é`, `\begin{alignat}{é}`), and cuts a colour `#rrggbb` at bytes; each panics inside
/// a character of more than one byte. So every non-ASCII white space is given to it as an
/// ASCII space (math mode skips both; in `\text{…}` it is then a plain space), and a number
/// or colour that starts with a non-ASCII character is refused here, with what to write.
fn parser_text(latex: &str) -> Result<String, TexError> {
    let text: String = latex
        .chars()
        .map(|c| {
            if c.is_whitespace() && !c.is_ascii() {
                ' '
            } else {
                c
            }
        })
        .collect();
    for (at, _) in text.match_indices("\\char") {
        let after = text[at + 5..].trim_start_matches(|c: char| c.is_ascii_whitespace());
        if after.chars().next().is_some_and(|c| !c.is_ascii()) {
            return Err(TexError::NotANumber("char"));
        }
    }
    for env in ["alignat}", "alignat*}", "alignedat}"] {
        for (at, _) in text.match_indices(env) {
            let after = text[at + env.len()..].trim_start();
            if let Some(arg) = after.strip_prefix('{')
                && arg
                    .trim_start()
                    .chars()
                    .next()
                    .is_some_and(|c| !c.is_ascii())
            {
                return Err(TexError::NotANumber("begin{alignat}"));
            }
        }
    }
    for (at, _) in text.match_indices("{#") {
        let colour = text[at + 2..].split('}').next().unwrap_or("");
        if !colour.is_ascii() {
            return Err(TexError::Unprintable("a colour"));
        }
    }
    Ok(text)
}

/// A control character that XML 1.0 (and so every page and export) cannot hold: all but tab,
/// line feed and carriage return.
fn forbidden_control(c: char) -> bool {
    c.is_control() && !matches!(c, '\t' | '\n' | '\r')
}

thread_local! {
    /// Set while this thread runs the parser, whose panics [`Tex::read`] catches and refuses.
    static QUIET: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Runs `f` with the panic message of this thread kept off standard error: the panic is
/// caught and reported as a located error instead. Other threads' panics print as before.
fn without_panic_messages<T>(f: impl FnOnce() -> T) -> T {
    static HOOK: std::sync::Once = std::sync::Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !QUIET.with(std::cell::Cell::get) {
                previous(info);
            }
        }));
    });
    QUIET.with(|q| q.set(true));
    let out = f();
    QUIET.with(|q| q.set(false));
    out
}

/// The nodes rewritten by `f`, children first: each node is handed to `f` with its operands and
/// content already rewritten.
pub fn rewrite(nodes: &[Node], f: &dyn Fn(Node) -> Node) -> Vec<Node> {
    nodes
        .iter()
        .map(|n| {
            let n = match n {
                Node::Group(g, inner) => Node::Group(g.clone(), rewrite(inner, f)),
                Node::Visual(v, parts) => Node::Visual(*v, rewrite(parts, f)),
                Node::Script {
                    ty,
                    position,
                    parts,
                } => Node::Script {
                    ty: *ty,
                    position: *position,
                    parts: rewrite(parts, f),
                },
                other => other.clone(),
            };
            f(n)
        })
        .collect()
}

/// What marks the place of a value in LaTeX to be filled on the tree: `{\text{\u{e000}3}}` is
/// the fourth value. (A private-use character, which no author writes.)
pub const MARK: char = '\u{e000}';

/// The LaTeX that marks the place of value `k`.
pub fn mark(k: usize) -> String {
    format!("{{\\text{{{MARK}{k}}}}}")
}

/// The nodes with each marked place (`mark(k)`) given `values[k]`, in the braces it stands in.
pub fn fill_marks(nodes: &[Node], values: &[Vec<Node>]) -> Vec<Node> {
    rewrite(nodes, &|n| match n {
        Node::Group(Grouping::Normal, inner) => match inner.as_slice() {
            [Node::Text(t)] if t.starts_with(MARK) => {
                let k: Option<usize> = t[MARK.len_utf8()..].parse().ok();
                match k.and_then(|k| values.get(k)) {
                    Some(v) => Node::Group(Grouping::Normal, v.clone()),
                    None => Node::Group(Grouping::Normal, inner),
                }
            }
            _ => Node::Group(Grouping::Normal, inner),
        },
        other => other,
    })
}

/// The nodes with every script on a bare operator name put on a group, `\cos^{2}` as
/// `{\cos}^{2}`: pulldown-latex's writer sets the first, when an argument follows, as an
/// `<msup>` of three children, which browsers draw as a small "cos2".
pub fn braced_operators(nodes: &[Node]) -> Vec<Node> {
    rewrite(nodes, &|n| match n {
        Node::Script {
            ty,
            position,
            mut parts,
        } if matches!(parts[0], Node::Function(_)) => {
            let name = parts.remove(0);
            parts.insert(0, Node::Group(Grouping::Normal, vec![name]));
            Node::Script {
                ty,
                position,
                parts,
            }
        }
        other => other,
    })
}

/// A relation's text: one character, or two (`≠` may be a pair).
pub fn relation_text(content: &RelationContent) -> String {
    let mut buf = [0u8; 8];
    String::from_utf8_lossy(content.encode_utf8_to_buf(&mut buf)).into_owned()
}

/// An environment's rows (split at `\\`) of cells (split at `&`).
pub fn cells(body: &[Node]) -> Vec<Vec<Vec<Node>>> {
    let mut rows = vec![vec![Vec::new()]];
    for n in body {
        match n {
            Node::Flow(EnvironmentFlow::NewLine { .. }) => rows.push(vec![Vec::new()]),
            Node::Flow(EnvironmentFlow::Alignment) => rows.last_mut().unwrap().push(Vec::new()),
            _ => rows.last_mut().unwrap().last_mut().unwrap().push(n.clone()),
        }
    }
    rows
}

/// Nodes as pulldown-latex's events, for its MathML writer.
pub fn events(nodes: &[Node]) -> Vec<Event<'_>> {
    let mut out = Vec::new();
    flatten(nodes, &mut out);
    out
}

type Events<'a> = Parser<'a>;

/// The longest run of commands that may each be the argument of the one before: a brace or a
/// character that cannot be an argument (a bracket, an operator) ends a run; spaces, and a
/// letter or digit after a command (`\frac1`, `\vec x`), do not.
fn chained_commands(latex: &str) -> usize {
    let (mut run, mut longest, mut after_command) = (0usize, 0usize, false);
    let mut chars = latex.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' => {
                // A control word, or a control symbol (`\\,`).
                if chars.peek().is_some_and(char::is_ascii_alphabetic) {
                    while chars.peek().is_some_and(char::is_ascii_alphabetic) {
                        chars.next();
                    }
                } else {
                    chars.next();
                }
                run += 1;
                longest = longest.max(run);
                after_command = true;
            }
            c if c.is_whitespace() => {}
            c if after_command && c.is_alphanumeric() => after_command = false,
            _ => {
                run = 0;
                after_command = false;
            }
        }
    }
    longest
}

fn parse_error(e: impl std::fmt::Display) -> TexError {
    let text = e.to_string();
    TexError::Parse(
        text.lines()
            .next()
            .unwrap_or("unreadable")
            .trim()
            .to_string(),
    )
}

/// One element and its operands; `None` at the end or at a group's `End` (consumed).
fn element(events: &mut Events<'_>, depth: usize) -> Result<Option<Node>, TexError> {
    if depth > MAX_DEPTH {
        return Err(TexError::TooDeep);
    }
    let Some(event) = events.next() else {
        return Ok(None);
    };
    let event = event.map_err(parse_error)?;
    let operands = |events: &mut Events<'_>, n: usize, levels: usize| {
        (0..n)
            .map(|_| {
                element(events, depth + levels)?
                    .ok_or_else(|| TexError::Parse("a missing operand".into()))
            })
            .collect::<Result<Vec<Node>, TexError>>()
    };
    Ok(Some(match event {
        Event::End => return Ok(None),
        Event::Content(c) => content_node(c)?,
        Event::Begin(g) => {
            let mut inner = Vec::new();
            while let Some(n) = element(events, depth + 1)? {
                inner.push(n);
            }
            Node::Group(g, inner)
        }
        Event::Visual(v) => {
            let n = match v {
                Visual::Fraction(_) | Visual::Root => 2,
                Visual::SquareRoot | Visual::Negation => 1,
            };
            Node::Visual(v, operands(events, n, 1)?)
        }
        Event::Script { ty, position } => {
            let n = match ty {
                ScriptType::SubSuperscript => 3,
                ScriptType::Subscript | ScriptType::Superscript => 2,
            };
            // Typst sets a script above or below its base (`\\underset`, `\\overbrace`,
            // `\\sum\\limits`) through a deeper recursion than any other element: nested 78
            // deep, within the reader's limit, it overflowed a layout thread's stack, which
            // no setting of mechbook's reaches (measured: 76 built). Each counts three
            // levels, four with its base's braces: `\\underset{a}{…}` nests at most 50 deep.
            let levels = if position == ScriptPosition::AboveBelow {
                ABOVE_BELOW_LEVELS
            } else {
                1
            };
            let parts = operands(events, n, levels)?;
            Node::Script {
                ty,
                position,
                parts,
            }
        }
        Event::Space { width, .. } => Node::Space(width),
        Event::StateChange(s) => Node::State(s),
        Event::EnvironmentFlow(f) => Node::Flow(f),
    }))
}

/// A piece of content as a node: text and characters without control characters, and `\mu`
/// as the Greek letter.
fn content_node(c: Content<'_>) -> Result<Node, TexError> {
    Ok(match c {
        Content::Text(s) => match s.chars().find(|c| forbidden_control(*c)) {
            Some(c) => return Err(TexError::Control(c as u32)),
            None => Node::Text(s.to_string()),
        },
        Content::Number(s) => Node::Number(s.to_string()),
        Content::Function(s) => Node::Function(s.to_string()),
        // pulldown-latex sets `\mu` as U+00B5, the micro sign; mechbook's printers and
        // the PDFs set the Greek letter, U+03BC, as Unicode recommends for both.
        Content::Ordinary {
            content: '\u{b5}',
            stretchy,
        } => Node::Atom(Content::Ordinary {
            content: 'μ',
            stretchy,
        }),
        Content::Ordinary { content, .. } if forbidden_control(content) => {
            return Err(TexError::Control(content as u32));
        }
        Content::Ordinary { content, stretchy } => {
            Node::Atom(Content::Ordinary { content, stretchy })
        }
        Content::LargeOp { content, small } => Node::Atom(Content::LargeOp { content, small }),
        Content::BinaryOp { content, small } => Node::Atom(Content::BinaryOp { content, small }),
        Content::Relation { content, small } => Node::Atom(Content::Relation { content, small }),
        Content::Delimiter { content, size, ty } => {
            Node::Atom(Content::Delimiter { content, size, ty })
        }
        Content::Punctuation(c) => Node::Atom(Content::Punctuation(c)),
    })
}

fn flatten<'a>(nodes: &'a [Node], out: &mut Vec<Event<'a>>) {
    for n in nodes {
        match n {
            Node::Text(s) => out.push(Event::Content(Content::Text(s))),
            Node::Number(s) => out.push(Event::Content(Content::Number(s))),
            Node::Function(s) => out.push(Event::Content(Content::Function(s))),
            Node::Atom(c) => out.push(Event::Content(*c)),
            Node::Group(g, inner) => {
                out.push(Event::Begin(g.clone()));
                flatten(inner, out);
                out.push(Event::End);
            }
            Node::Visual(v, parts) => {
                out.push(Event::Visual(*v));
                flatten(parts, out);
            }
            Node::Script {
                ty,
                position,
                parts,
            } => {
                out.push(Event::Script {
                    ty: *ty,
                    position: *position,
                });
                flatten(parts, out);
            }
            Node::Space(width) => out.push(Event::Space {
                width: *width,
                height: None,
                depth: None,
            }),
            Node::State(s) => out.push(Event::StateChange(*s)),
            Node::Flow(f) => out.push(Event::EnvironmentFlow(f.clone())),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fraction_and_a_script_hold_their_operands() {
        let t = Tex::read("\\frac{1}{2} x^{2}").unwrap();
        assert_eq!(t.nodes.len(), 2, "{t:?}");
        assert!(matches!(&t.nodes[0], Node::Visual(Visual::Fraction(None), p) if p.len() == 2));
        assert!(matches!(&t.nodes[1], Node::Script { parts, .. } if parts.len() == 2));
    }

    #[test]
    fn the_events_read_back_are_the_parsers() {
        for latex in [
            "\\mathrm{kg\\,m^2}",
            "\\begin{pmatrix}a & b \\\\ c & d\\end{pmatrix}",
            "\\left(\\frac{a}{b}\\right)^{2} \\sum_{i} \\vec{\\omega}_{x}",
        ] {
            let storage = Storage::new();
            let direct: Vec<Event> = Parser::new(latex, &storage).map(Result::unwrap).collect();
            assert_eq!(events(&Tex::read(latex).unwrap().nodes), direct, "{latex}");
        }
    }

    /// An author's `\mu` is the Greek letter that mechbook's printers and the PDFs set, not the
    /// micro sign the parser gives.
    #[test]
    fn mu_is_the_greek_letter() {
        let t = Tex::read("\\mu").unwrap();
        assert_eq!(
            t.nodes,
            vec![Node::Atom(Content::Ordinary {
                content: '\u{3bc}',
                stretchy: false
            })]
        );
    }

    /// A value filled in on the tree, at its mark, is what the reader makes of the LaTeX with
    /// the value's LaTeX pasted in its braces.
    #[test]
    fn a_marked_place_is_filled_with_its_value() {
        let values = ["\\frac{3}{2}", "\\frac{\\pi}{6}", "0.25", "m_{1}"];
        let template = format!(
            "\\frac{}{{2}} \\sin{}^{{2}} + x_{} - {{g}} + {}^{{2}}",
            mark(0),
            mark(1),
            mark(2),
            mark(3)
        );
        let filled = fill_marks(
            &Tex::read(&template).unwrap().nodes,
            &values.map(|v| Tex::read(v).unwrap().nodes),
        );
        let pasted =
            "\\frac{\\frac{3}{2}}{2} \\sin{\\frac{\\pi}{6}}^{2} + x_{0.25} - {g} + {m_{1}}^{2}";
        assert_eq!(filled, Tex::read(pasted).unwrap().nodes);
    }

    /// An author's formula is stored (the build cache) as the LaTeX written, as it was when
    /// it was that text, and read back into the same tree.
    #[test]
    fn a_formula_is_stored_as_its_latex_and_read_back() {
        let f = crate::notation::Formula::author("\\frac{1}{2} m v^2");
        let json = serde_json::to_string(&f).unwrap();
        assert_eq!(json, r#"{"Tex":"\\frac{1}{2} m v^2"}"#);
        let back: crate::notation::Formula = serde_json::from_str(&json).unwrap();
        assert_eq!(back, f);
        let e = serde_json::from_str::<Tex>(r#""\\frac{1}{""#).unwrap_err();
        assert!(e.to_string().contains("unbalanced group"), "{e}");
    }

    /// Each of these made pulldown-latex 0.8 slice inside a character and panic: a number or
    /// a unit followed by a non-ASCII space, a number that starts with a non-ASCII character.
    #[test]
    fn a_number_or_unit_before_a_wide_character_is_read_or_refused_never_a_panic() {
        for space in ['\u{a0}', '\u{2003}', '\u{3000}'] {
            for latex in [
                format!("\\char\"41{space}x"),
                format!("\\char65{space}x"),
                format!("a\\kern1em{space}b"),
                format!("a\\mkern1mu{space}b"),
                format!("a\\hskip1pt{space}b"),
                format!("a\\kern{space}1em{space}b"),
                format!("\\text{{a{space}b}}"),
            ] {
                let t = Tex::read(&latex).unwrap_or_else(|e| panic!("{latex:?}: {e}"));
                assert_eq!(t.source, latex, "the source is kept as written");
            }
        }
        assert_eq!(
            Tex::read("a\\kern1em\u{a0}b").unwrap().nodes,
            Tex::read("a\\kern1em b").unwrap().nodes
        );
    }

    #[test]
    fn unreadable_or_too_deep_latex_is_refused() {
        assert!(matches!(Tex::read("\\frac{1}{"), Err(TexError::Parse(_))));
        assert!(matches!(Tex::read("\\foo x"), Err(TexError::Parse(_))));
        let deep = format!("{}x{}", "{".repeat(10_000), "}".repeat(10_000));
        assert_eq!(Tex::read(&deep), Err(TexError::TooDeep));
        let deep = format!("{}x{}", "\\frac{".repeat(5_000), "}{1}".repeat(5_000));
        assert_eq!(Tex::read(&deep), Err(TexError::TooDeep));
        assert_eq!(Tex::read(&"\\vec".repeat(10_000)), Err(TexError::Chain));
        assert_eq!(Tex::read(&"\\frac1".repeat(10_000)), Err(TexError::Chain));
        assert_eq!(
            TexError::Chain.to_string(),
            "more than 250 commands in a chain, each the argument of the one before: give each \
             argument its braces, `\\vec{\\vec{x}}`"
        );
        assert_eq!(Tex::read("\\char é"), Err(TexError::NotANumber("char")));
        assert_eq!(
            Tex::read("\\char\u{3000}é"),
            Err(TexError::NotANumber("char"))
        );
        assert_eq!(
            Tex::read("\\begin{alignat}{é} a \\end{alignat}"),
            Err(TexError::NotANumber("begin{alignat}"))
        );
        assert_eq!(
            Tex::read("\\color{#aééb} x"),
            Err(TexError::Unprintable("a colour"))
        );
        for control in [
            "\\char0",
            "\\char8",
            "\\char27",
            "\\char\"",
            "\\text{a\u{7}b}",
        ] {
            assert!(
                matches!(Tex::read(control), Err(TexError::Control(_))),
                "{control}: {:?}",
                Tex::read(control)
            );
        }
        // A long formula of commands, each with its own brackets or braces, is read.
        let long = "\\sin\\left(\\theta\\right) \\omega_{3} ".repeat(500);
        assert!(Tex::read(&long).is_ok());
    }
}
