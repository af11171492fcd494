//! A printed formula read back into an expression: the tree the pages set (MathML, the spoken
//! form and the PDF's tags are all made from it), parsed as a reader would, so that what a page
//! shows can be checked equal to the result it stands for. A name is recognised by its printed
//! tree (ω₁ is `w1`, the scene's `tex` its step); a number beside a number with no sign between
//! is one product only when a `⋅` says so, as a reader takes "30.4⁴" for thirty point four.

use super::Names;
use super::expr_tree::symbol;
use super::latex::Node;
use crate::cas::Expr;
use pulldown_latex::event::{
    Content, EnvironmentFlow, Grouping, ScriptPosition, ScriptType, Visual,
};

/// Why a printed tree is no expression a reader could take back.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ReadBackError {
    #[error("`{0}` is no name of the result's")]
    Unknown(String),
    #[error("the formula ends where a term is wanted")]
    Incomplete,
    #[error("{0} cannot be read back")]
    Unreadable(&'static str),
}

/// The names a formula may print, each with its printed tree as the scene typesets it.
pub struct Readable(Vec<(Vec<Node>, String)>);

impl Readable {
    pub fn new<'a>(names: impl IntoIterator<Item = &'a str>, typeset: &Names) -> Readable {
        let mut table: Vec<(Vec<Node>, String)> = names
            .into_iter()
            .map(|n| (symbol(n, typeset, &|_| None), n.to_string()))
            .collect();
        // The longest printed form first: `m1` before `m`.
        table.sort_by_key(|(nodes, _)| std::cmp::Reverse(nodes.len()));
        Readable(table)
    }

    /// The name whose tree starts `nodes`, and how many nodes it takes.
    fn at(&self, nodes: &[Node]) -> Option<(&str, usize)> {
        self.0
            .iter()
            .find(|(tree, _)| nodes.starts_with(tree))
            .map(|(tree, name)| (name.as_str(), tree.len()))
    }
}

/// The expression a printed tree shows.
pub fn read_back(nodes: &[Node], names: &Readable) -> Result<Expr, ReadBackError> {
    Reader { names }.row(nodes)
}

/// A printed formula's sides at its top-level relations (`x = a`, `Ω₂ ≈ 5.2`): each side with
/// the relation before it, the first with none.
pub fn sides(nodes: &[Node]) -> Vec<(Option<String>, &[Node])> {
    let mut out = Vec::new();
    let (mut start, mut relation) = (0, None);
    for (i, n) in nodes.iter().enumerate() {
        if let Node::Atom(Content::Relation { content, .. }) = n {
            out.push((relation.take(), &nodes[start..i]));
            relation = Some(super::latex::relation_text(content));
            start = i + 1;
        }
    }
    out.push((relation, &nodes[start..]));
    out
}

enum Token {
    Term(Expr),
    Plus,
    Minus,
    Times,
    /// `×`: between numbers a product (2.5 × 10⁻⁶), between vectors a cross product, which
    /// the reader does not read.
    Cross,
    Over,
}

struct Reader<'a> {
    names: &'a Readable,
}

impl Reader<'_> {
    /// A sequence of nodes: terms and signs, side by side a product.
    fn row(&self, nodes: &[Node]) -> Result<Expr, ReadBackError> {
        let nodes = &joined_numbers(nodes);
        let mut tokens = Vec::new();
        let mut i = 0;
        while i < nodes.len() {
            if let Some((name, taken)) = self.names.at(&nodes[i..]) {
                tokens.push(Token::Term(Expr::sym(name)));
                i += taken;
                continue;
            }
            match &nodes[i] {
                Node::Space(_) | Node::State(_) => {}
                Node::Atom(Content::BinaryOp { content, .. }) => tokens.push(match content {
                    '+' => Token::Plus,
                    '−' | '-' => Token::Minus,
                    '⋅' | '*' => Token::Times,
                    '×' => Token::Cross,
                    '/' => Token::Over,
                    _ => return Err(ReadBackError::Unreadable("an operator")),
                }),
                // An operator's name, its power (sin²) and its argument in parentheses.
                Node::Function(_) | Node::Group(Grouping::Normal, _) | Node::Script { .. }
                    if function_at(&nodes[i..]).is_some() =>
                {
                    let (f, power, taken) = function_at(&nodes[i..]).unwrap();
                    let arg = match nodes.get(i + taken) {
                        Some(Node::Group(Grouping::LeftRight(Some('('), Some(')')), inner)) => {
                            self.row(inner)?
                        }
                        _ => return Err(ReadBackError::Unreadable("a function without (…)")),
                    };
                    let call = Expr::call(&function_name(&f), arg);
                    tokens.push(Token::Term(match power {
                        Some(p) => Expr::pow(call, self.row(&p)?),
                        None => call,
                    }));
                    i += taken + 1;
                    continue;
                }
                n => tokens.push(Token::Term(self.term(n)?)),
            }
            i += 1;
        }
        sum(tokens)
    }

    /// One node that is a term on its own.
    fn term(&self, n: &Node) -> Result<Expr, ReadBackError> {
        match n {
            Node::Number(digits) => crate::cas::parse(digits)
                .map(|p| p.expr)
                .map_err(|_| ReadBackError::Unreadable("a number")),
            Node::Group(Grouping::Normal, inner) => self.row(inner),
            Node::Group(Grouping::LeftRight(Some('('), Some(')')), inner) => match inner.as_slice()
            {
                [Node::Group(Grouping::Matrix { .. }, body)] => self.matrix(body),
                _ => self.row(inner),
            },
            Node::Visual(Visual::Fraction(_), parts) if parts.len() == 2 => {
                Ok(Expr::over(self.part(&parts[0])?, self.part(&parts[1])?))
            }
            Node::Visual(Visual::SquareRoot, parts) if parts.len() == 1 => {
                Ok(Expr::call("sqrt", self.part(&parts[0])?))
            }
            Node::Visual(Visual::Root, parts) if parts.len() == 2 => Ok(Expr::pow(
                self.part(&parts[0])?,
                Expr::over(Expr::int(1), self.part(&parts[1])?),
            )),
            Node::Script {
                ty,
                position: ScriptPosition::Right,
                parts,
            } => self.script(*ty, parts),
            Node::Atom(Content::Ordinary { content, .. }) => {
                Err(ReadBackError::Unknown(content.to_string()))
            }
            Node::Text(t) => Err(ReadBackError::Unknown(t.clone())),
            _ => Err(ReadBackError::Unreadable("a piece of the formula")),
        }
    }

    /// A matrix's body (`pmatrix`): rows at each new line, cells at each alignment; a list of
    /// rows, each a list of its cells.
    fn matrix(&self, body: &[Node]) -> Result<Expr, ReadBackError> {
        let rows = body.split(|n| matches!(n, Node::Flow(EnvironmentFlow::NewLine { .. })));
        rows.map(|row| {
            row.split(|n| matches!(n, Node::Flow(EnvironmentFlow::Alignment)))
                .map(|cell| self.row(cell))
                .collect::<Result<Vec<_>, _>>()
                .map(Expr::List)
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Expr::List)
    }

    /// A fraction's or a script's part: a name (an upright word is a group of its own), else
    /// what the group holds.
    fn part(&self, n: &Node) -> Result<Expr, ReadBackError> {
        self.row(std::slice::from_ref(n))
    }

    /// A power (`x²`), or a name with its subscript and a power (`ω₁²`).
    fn script(&self, ty: ScriptType, parts: &[Node]) -> Result<Expr, ReadBackError> {
        match (ty, parts) {
            (ScriptType::Superscript, [base, power]) => {
                Ok(Expr::pow(self.part(base)?, self.part(power)?))
            }
            (ScriptType::SubSuperscript, [base, sub, power]) => {
                let named = Node::Script {
                    ty: ScriptType::Subscript,
                    position: ScriptPosition::Right,
                    parts: vec![base.clone(), sub.clone()],
                };
                Ok(Expr::pow(self.part(&named)?, self.part(power)?))
            }
            // A subscript is part of a name, which the table did not know.
            _ => Err(ReadBackError::Unknown(super::spoken::spoken(&[
                Node::Script {
                    ty,
                    position: ScriptPosition::Right,
                    parts: parts.to_vec(),
                },
            ]))),
        }
    }
}

/// Numbers side by side as a reader sees them: one number (`3` then `0.4⁴` is 30.4⁴).
fn joined_numbers(nodes: &[Node]) -> Vec<Node> {
    let mut out: Vec<Node> = Vec::with_capacity(nodes.len());
    for n in nodes {
        if let Some(Node::Number(before)) = out.last() {
            let before = before.clone();
            match n {
                Node::Number(d) => {
                    *out.last_mut().unwrap() = Node::Number(before.clone() + d.as_str());
                    continue;
                }
                Node::Script {
                    ty,
                    position: ScriptPosition::Right,
                    parts,
                } => {
                    if let Some(Node::Number(d)) = parts.first() {
                        let mut parts = parts.clone();
                        parts[0] = Node::Number(before.clone() + d.as_str());
                        *out.last_mut().unwrap() = Node::Script {
                            ty: *ty,
                            position: ScriptPosition::Right,
                            parts,
                        };
                        continue;
                    }
                }
                _ => {}
            }
        }
        out.push(n.clone());
    }
    out
}

/// An operator name starting `nodes` (`\sin`, or `{\sin}^{2}` with its power) and how many
/// nodes it takes.
fn function_at(nodes: &[Node]) -> Option<(String, Option<Vec<Node>>, usize)> {
    match nodes.first()? {
        Node::Function(f) => Some((f.clone(), None, 1)),
        Node::Script {
            ty: ScriptType::Superscript,
            position: ScriptPosition::Right,
            parts,
        } => match parts.as_slice() {
            [Node::Group(Grouping::Normal, inner), power] => match inner.as_slice() {
                [Node::Function(f)] => {
                    let p = match power {
                        Node::Group(Grouping::Normal, p) => p.clone(),
                        other => vec![other.clone()],
                    };
                    Some((f.clone(), Some(p), 1))
                }
                _ => None,
            },
            _ => None,
        },
        _ => None,
    }
}

/// The engine's name of a printed operator name (`arccos` is `acos`).
fn function_name(printed: &str) -> String {
    match printed.strip_prefix("arc") {
        Some(rest) => format!("a{rest}"),
        None => printed.to_string(),
    }
}

/// A number, or a power of numbers (10⁻⁶).
fn numeric(e: &Expr) -> bool {
    e.symbols().is_empty()
}

/// Terms and signs as a sum of products: side by side or `⋅` multiplies, `/` divides the
/// product so far by the next factor, a sign starts a term.
fn sum(tokens: Vec<Token>) -> Result<Expr, ReadBackError> {
    let mut terms = Vec::new();
    let mut product: Vec<Expr> = Vec::new();
    let mut negative = false;
    let mut divide = false;
    let mut crossed = false;
    let mut wants_term = true;
    let close = |product: &mut Vec<Expr>, negative: bool, terms: &mut Vec<Expr>| {
        if product.is_empty() {
            return;
        }
        let p = Expr::mul(std::mem::take(product));
        terms.push(if negative { Expr::negate(p) } else { p });
    };
    for t in tokens {
        match t {
            Token::Term(e) => {
                if std::mem::take(&mut crossed) && !(numeric(&e) && product.iter().all(numeric)) {
                    return Err(ReadBackError::Unreadable("a cross product"));
                }
                let e = if divide {
                    Expr::pow(e, Expr::int(-1))
                } else {
                    e
                };
                product.push(e);
                divide = false;
                wants_term = false;
            }
            Token::Plus | Token::Minus => {
                if !product.is_empty() {
                    close(&mut product, negative, &mut terms);
                    negative = false;
                }
                if matches!(t, Token::Minus) {
                    negative = !negative;
                }
                wants_term = true;
            }
            Token::Times | Token::Cross | Token::Over => {
                if wants_term {
                    return Err(ReadBackError::Incomplete);
                }
                divide = matches!(t, Token::Over);
                crossed = matches!(t, Token::Cross);
                wants_term = true;
            }
        }
    }
    if wants_term {
        return Err(ReadBackError::Incomplete);
    }
    close(&mut product, negative, &mut terms);
    Ok(Expr::add(terms))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::notation::Tex;

    /// Random results from the project's seeded stream, so that a failure names its case.
    struct Gen(crate::base::rng::Rng);

    const NAMES: &[&str] = &[
        "x", "m", "alpha", "phi", "w1", "wd2", "Ixx", "phi'", "theta''", "Om2", "m1", "R", "g",
        "l", "I3", "slow_eps",
    ];

    impl Gen {
        fn below(&mut self, n: usize) -> usize {
            (self.0.uniform() * n as f64) as usize
        }

        /// A scalar result as the derivations give them: sums, products, powers (whole, half,
        /// negative), roots, sines and cosines of names and numbers (whole, fractions, decimals).
        fn expr(&mut self, depth: usize) -> Expr {
            if depth == 0 || self.below(4) == 0 {
                return match self.below(4) {
                    0 | 1 => Expr::sym(NAMES[self.below(NAMES.len())]),
                    2 => Expr::int(self.below(30) as i128 - 9),
                    _ => Expr::rat(self.below(9) as i128 - 4, 2 + self.below(9) as i128),
                };
            }
            let d = depth - 1;
            let n = 2 + self.below(2);
            match self.below(7) {
                0 | 1 => Expr::add((0..n).map(|_| self.expr(d)).collect()),
                2 | 3 => Expr::mul((0..n).map(|_| self.expr(d)).collect()),
                4 => {
                    let k = [2, 3, -1, -2][self.below(4)];
                    let half = self.below(3) == 0;
                    let e = if half { Expr::rat(k, 2) } else { Expr::int(k) };
                    Expr::pow(self.expr(d), e)
                }
                5 => Expr::call(["sin", "cos"][self.below(2)], self.expr(d)),
                _ => Expr::call("sqrt", self.expr(d)),
            }
        }
    }

    /// Both sides at a few points: every name a value in [0.5, 2.5).
    fn same(a: &Expr, b: &Expr, g: &mut Gen) -> bool {
        (0..3).all(|_| {
            let values: Vec<(&str, f64)> = NAMES
                .iter()
                .map(|n| (*n, 0.5 + g.below(2000) as f64 / 1000.0))
                .collect();
            let at = |n: &str| values.iter().find(|(k, _)| *k == n).map(|(_, v)| *v);
            match (a.eval(&at), b.eval(&at)) {
                (Ok(x), Ok(y)) if x.is_finite() && y.is_finite() => {
                    (x - y).abs() <= 1e-9 * (1.0 + x.abs().max(y.abs()))
                }
                (x, y) => x.is_err() == y.is_err() || !x.is_ok_and(f64::is_finite),
            }
        })
    }

    /// Random results printed as the pages' tree, and as the LaTeX Moodle and the sources take
    /// (read by the one reader), each read back and equal to the result at random points.
    #[test]
    fn random_results_read_back_equal_through_the_tree_and_the_latex() {
        let names = Readable::new(NAMES.iter().copied(), Names::none());
        let mut g = Gen(crate::base::rng::Rng::new(0x5eed_1234_abcd));
        let mut checked = 0;
        for case in 0..400 {
            let e = g.expr(3);
            let tree = e.to_tex(crate::notation::Names::none());
            let from_tree = read_back(&tree.nodes, &names)
                .unwrap_or_else(|err| panic!("case {case}: {} ({err})", e.to_text()));
            assert!(
                same(&from_tree, &e, &mut g),
                "case {case}: {} read back as {}",
                e.to_text(),
                from_tree.to_text()
            );
            let latex = Tex::read(&tree.source).unwrap();
            let from_latex = read_back(&latex.nodes, &names)
                .unwrap_or_else(|err| panic!("case {case}: {} ({err})", tree.source));
            assert!(
                same(&from_latex, &e, &mut g),
                "case {case}: {}",
                tree.source
            );
            checked += 1;
        }
        assert_eq!(checked, 400);
    }

    /// The reader reads what a reader sees: "3 0.4⁴" with no sign is thirty point four to the
    /// fourth, which is not 3 ⋅ 0.4⁴; an unknown name is no result's.
    #[test]
    fn a_wrong_print_reads_back_as_what_it_shows() {
        let names = Readable::new(["x"], Names::none());
        let right = crate::cas::parse("3*0.4^4").unwrap().expr;
        let shown = read_back(&right.to_tex(crate::notation::Names::none()).nodes, &names).unwrap();
        assert!((shown.eval(&|_| None).unwrap() - 0.0768).abs() < 1e-12);
        let wrong = Tex::read("3 0.4^{4}").unwrap();
        let seen = read_back(&wrong.nodes, &names).unwrap();
        assert!((seen.eval(&|_| None).unwrap() - 30.4f64.powi(4)).abs() < 1e-6);
        let unknown = Tex::read("x + y").unwrap();
        assert_eq!(
            read_back(&unknown.nodes, &names),
            Err(ReadBackError::Unknown("y".into()))
        );
    }
}
