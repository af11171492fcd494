//! An upper bound on how wide Typst sets a formula on a line of its own, read from its Typst
//! math and the math font's glyphs. A formula surely narrower than the narrowest line is set
//! without `measure` (`Markup::block`), which saves a second layout of every short formula:
//! about a sixth of the typesetting time of tests/course (docs/performance.md, "Short formulas set without
//! measuring").
//!
//! The bound is a sum over the formula's pieces, since Typst never sets a construct wider than
//! its parts side by side (a fraction is as wide as its wider part, a script stands beside its
//! base, a matrix's columns each as wide as their widest entry): each character counts the
//! widest glyph the font may set for it (any letter style, any size of a delimiter, radical
//! or large operator), each neighbour in a row the most Typst puts between two, each script
//! its base's italic correction, and each function what it draws itself (a radical, a
//! matrix's brackets and gaps). Anything else, a name or a construct not known here, gives no
//! bound, and the formula is measured as before.

use super::glyphs::{Glyphs, glyphs};
use typst::foundations::Value;
use typst::syntax::{SyntaxKind, SyntaxNode};

/// The widest a formula may be, in em of the body's 10.5 pt, to be set without measuring: the
/// narrowest line a display formula is set on is A4's 174 mm inside a claim's box (6 pt of
/// inset each side), 45.8 em; the rest is room for what the bound leaves out.
pub const NARROWER_THAN_ANY_LINE: f64 = 42.0;

/// The body's size, which the preamble sets for formulas too: a length in points over it is in em.
const BODY_PT: f64 = 10.5;

/// The most Typst puts between two neighbours in a row: a thick space (5/18 em) around a
/// relation, or a space of the markup beside a word (the font's, 0.332 em); never both.
const GAP: f64 = 0.34;

/// A space in a string (the font's word space, 0.332 em), rounded up.
const SPACE: f64 = 0.34;

/// A fraction's padding each side (Typst's `FRAC_PADDING`, 0.1 em), rounded up.
const FRACTION: f64 = 0.25;

/// A matrix's gap between columns (Typst's default, 0.5 em).
const COLUMN_GAP: f64 = 0.5;

/// The upper bound on the width of `math` set as a display formula, in em; `None` when the
/// math holds anything the bound does not know.
pub fn widest_em(math: &str) -> Option<f64> {
    let root = typst::syntax::parse_math(math);
    if root.diagnosis().errors {
        return None;
    }
    width(&root, glyphs()?)
}

fn width(n: &SyntaxNode, g: &Glyphs) -> Option<f64> {
    use SyntaxKind::*;
    Some(match n.kind() {
        // A row: each piece, and a gap beside each.
        Math | MathDelimited => n
            .children()
            .filter(|c| c.kind() != Space)
            .map(|c| Some(width(c, g)? + GAP))
            .sum::<Option<f64>>()?,
        // `x_1^2`: the base and its italic correction, then the wider script, then its primes.
        MathAttach => {
            let mut parts = n
                .children()
                .filter(|c| !matches!(c.kind(), Underscore | Hat));
            let base_node = parts.next()?;
            let base = width(base_node, g)? + g.italic_of(base_node);
            let mut scripts: f64 = 0.0;
            let mut primes = 0.0;
            for p in parts {
                if p.kind() == MathPrimes {
                    primes += width(p, g)?;
                } else {
                    scripts = scripts.max(grouped(p, g)?);
                }
            }
            base + scripts + primes
        }
        MathPrimes | MathRoot => children(n, g)?,
        // `a/b`: the wider part.
        MathFrac => {
            let mut w: f64 = 0.0;
            for c in n.children().filter(|c| c.kind() != Slash) {
                w = w.max(grouped(c, g)?);
            }
            w + FRACTION
        }
        // A number, digit by digit; a letter; an operator.
        MathText => n
            .leaf_text()
            .chars()
            .map(|c| g.widest(c))
            .sum::<Option<f64>>()?,
        // A bracket of `(…)` at whatever size the content asks, a radical sign, an escaped
        // character, a shorthand (`->`).
        LeftParen | RightParen | Root | Escape | MathShorthand | Shorthand => {
            g.widest(leaf_char(n)?)?
        }
        Str => {
            let s = n.leaf_text();
            let inner = s.strip_prefix('"')?.strip_suffix('"')?;
            if inner.contains('\\') {
                return Option::None;
            }
            inner
                .chars()
                .map(|c| if c == ' ' { Some(SPACE) } else { g.widest(c) })
                .sum::<Option<f64>>()?
        }
        // Set only beside a word, within the gap counted for it.
        Space => 0.0,
        MathIdent => named(n.leaf_text(), g)?,
        // `dot.op`, `arrow.l.r`: the symbol with those modifiers.
        MathFieldAccess => modified(n, g)?,
        MathCall => call(n, g)?,
        // What sets nothing: an alignment, a line break, the syntax of scripts and of embedded
        // code (`#h(1em);`, `#1.8em`, `#none`).
        MathAlignPoint | Linebreak | Underscore | Hat | Slash | Hash | Semicolon | None | Bool
        | Numeric => 0.0,
        // `#h(1em);`, the only code the printers write in a formula but a bracket's size.
        FuncCall => spacing(n)?,
        _ => return Option::None,
    })
}

/// A script or a part of `a/b`: Typst drops the brackets of `(…)` there (`x^(2)`).
fn grouped(n: &SyntaxNode, g: &Glyphs) -> Option<f64> {
    let mut parts = n.children();
    if matches!(n.kind(), SyntaxKind::Math | SyntaxKind::MathDelimited)
        && let (Some(open), Some(body), Some(close), Option::None) =
            (parts.next(), parts.next(), parts.next(), parts.next())
        && open.leaf_text() == "("
        && close.leaf_text() == ")"
    {
        return width(body, g);
    }
    width(n, g)
}

fn children(n: &SyntaxNode, g: &Glyphs) -> Option<f64> {
    n.children().map(|c| width(c, g)).sum()
}

/// A symbol with modifiers (`arrow.l.r`).
fn modified(n: &SyntaxNode, g: &Glyphs) -> Option<f64> {
    let path = n.full_text();
    let mut parts = path.split('.');
    let name = parts.next()?;
    let modifiers: Vec<&str> = parts.collect();
    symbol(name, &modifiers, g)
}

/// The character a leaf sets: itself, an escape's, or a shorthand's (`->`, `<=`).
fn leaf_char(n: &SyntaxNode) -> Option<char> {
    let t = n.leaf_text();
    if n.kind() == SyntaxKind::Escape {
        let mut c = t.strip_prefix('\\')?.chars();
        return match (c.next(), c.next()) {
            (Some(ch), Option::None) => Some(ch),
            _ => Option::None,
        };
    }
    if matches!(n.kind(), SyntaxKind::MathShorthand | SyntaxKind::Shorthand) {
        return typst::syntax::ast::MathShorthand::LIST
            .iter()
            .find(|(s, _)| *s == t.as_str())
            .map(|(_, c)| *c);
    }
    let mut c = t.chars();
    match (c.next(), c.next()) {
        (Some(ch), Option::None) => Some(ch),
        _ => Option::None,
    }
}

/// A name in the formula: a symbol, an operator's name (`sin`) or a space (`quad`).
fn named(name: &str, g: &Glyphs) -> Option<f64> {
    if let Some(w) = SPACES.iter().find(|(s, _)| *s == name).map(|(_, w)| *w) {
        return Some(w);
    }
    if crate::notation::typst::FUNCTIONS.contains(&name) {
        return name.chars().map(|c| g.widest(c)).sum();
    }
    symbol(name, &[], g)
}

/// Typst's named spaces, in em.
const SPACES: &[(&str, f64)] = &[
    ("thin", 1.0 / 6.0),
    ("med", 2.0 / 9.0),
    ("thick", 5.0 / 18.0),
    ("quad", 1.0),
    ("wide", 2.0),
    ("space", SPACE),
];

/// A symbol of Typst's math by name, with `modifiers` as Typst resolves them.
fn symbol(name: &str, modifiers: &[&str], g: &Glyphs) -> Option<f64> {
    let Value::Symbol(s) = math_scope().get(name)?.read() else {
        return Option::None;
    };
    let mut s = s.clone();
    for m in modifiers {
        s = s.modified((), m).ok()?;
    }
    s.get().chars().map(|c| g.widest(c)).sum()
}

fn math_scope() -> &'static typst::foundations::Scope {
    super::typeset::library().math.scope()
}

/// A call: what a function sets of its arguments, and what it draws itself. A symbol called
/// is an accent (`arrow(r)`), set over its argument; any other name (`sin(x)`) is set with its
/// brackets.
fn call(n: &SyntaxNode, g: &Glyphs) -> Option<f64> {
    let mut parts = n.children();
    let callee = parts.next()?;
    let args = parts.next()?;
    let name = match callee.kind() {
        SyntaxKind::MathIdent => callee.leaf_text().as_str(),
        SyntaxKind::MathFieldAccess => {
            return Some(modified(callee, g)?.max(Table::of(args, g)?.side_by_side()));
        }
        _ => return Option::None,
    };
    if name == "attach" {
        // By side, not as a table: each script once, since scripts nest (a table counted
        // twice would be 2^depth of them).
        return attached(args, g);
    }
    let Some((_, set)) = FUNCTIONS.iter().find(|f| f.0 == name) else {
        if let Some(Value::Symbol(_)) = math_scope().get(name).map(|b| b.read()) {
            return Some(symbol(name, &[], g)?.max(Table::of(args, g)?.side_by_side()));
        }
        return Some(width(callee, g)? + shown_arguments(args, g)?);
    };
    let table = Table::of(args, g)?;
    let cells = || table.rows.iter().flatten().copied();
    let widest = || cells().fold(0.0_f64, f64::max);
    let brackets = || g.widest_bracket();
    Some(match set {
        Set::Side => table.side_by_side(),
        Set::Over => widest(),
        Set::Fraction => widest() + FRACTION,
        Set::Binomial => widest() + FRACTION + 2.0 * brackets()?,
        Set::Radical => g.widest('√')? + cells().sum::<f64>(),
        Set::Matrix => table.columns() + 2.0 * brackets()?,
        Set::Column => widest() + 2.0 * brackets()?,
        Set::Bracketed => cells().sum::<f64>() + 2.0 * brackets()?,
    })
}

/// `attach(base, b: …, t: …)`: the base with its italic correction, the wider script on each
/// side (`tl`, `bl` before it; `t`, `b`, `tr`, `br` after it), as `x_1^2` is set.
fn attached(args: &SyntaxNode, g: &Glyphs) -> Option<f64> {
    let (mut base, mut before, mut after) = (Option::None, 0.0_f64, 0.0_f64);
    for a in args.children() {
        match a.kind() {
            SyntaxKind::Named => {
                let mut parts = a.children();
                let side = parts.next()?.leaf_text().clone();
                let w = width(a.children().last()?, g)?;
                match side.as_str() {
                    "tl" | "bl" => before = before.max(w),
                    "t" | "b" | "tr" | "br" => after = after.max(w),
                    _ => return Option::None,
                }
            }
            SyntaxKind::LeftParen | SyntaxKind::RightParen | SyntaxKind::Space => {}
            SyntaxKind::Comma => {}
            _ if base.is_none() => base = Some(width(a, g)? + g.italic_of(a)),
            _ => return Option::None,
        }
    }
    Some(before + base? + after)
}

/// A call's arguments: the positional ones in rows (split by `;`) of cells (split by `,`), and
/// the values of the named ones (`b: x`; a bracket's `size` sets nothing).
struct Table {
    rows: Vec<Vec<f64>>,
    named: Vec<f64>,
}

impl Table {
    fn of(args: &SyntaxNode, g: &Glyphs) -> Option<Table> {
        let mut rows = vec![Vec::new()];
        let mut named = Vec::new();
        for a in args.children() {
            match a.kind() {
                SyntaxKind::LeftParen | SyntaxKind::RightParen | SyntaxKind::Space => {}
                SyntaxKind::Comma => {}
                SyntaxKind::Semicolon => rows.push(Vec::new()),
                SyntaxKind::Named => named.push(width(a.children().last()?, g)?),
                _ => rows.last_mut()?.push(width(a, g)?),
            }
        }
        Some(Table { rows, named })
    }

    /// Every argument side by side, the named ones' values too.
    fn side_by_side(&self) -> f64 {
        self.rows.iter().flatten().sum::<f64>() + self.named.iter().sum::<f64>()
    }

    /// A matrix's width: each column as wide as its widest entry, with the gaps between.
    fn columns(&self) -> f64 {
        let n = self.rows.iter().map(Vec::len).max().unwrap_or(0);
        let widest = |j: usize| {
            self.rows
                .iter()
                .filter_map(|r| r.get(j))
                .fold(0.0_f64, |w, c| w.max(*c))
        };
        (0..n).map(widest).sum::<f64>() + n.saturating_sub(1) as f64 * COLUMN_GAP
    }
}

/// How a function sets its arguments.
enum Set {
    /// Side by side (`upright`, `lr`, `op`, `cancel`).
    Side,
    /// One over another (`accent`, `limits`, `overbrace`).
    Over,
    Fraction,
    Binomial,
    /// After a radical sign (`sqrt`, `root` with its index).
    Radical,
    /// In columns, between brackets.
    Matrix,
    /// One above another, between brackets (`vec`, `cases`).
    Column,
    /// Side by side between brackets (`abs`, `norm`).
    Bracketed,
}

/// The functions the printers call, and how each sets its arguments.
const FUNCTIONS: &[(&str, Set)] = &[
    ("frac", Set::Fraction),
    ("binom", Set::Binomial),
    ("sqrt", Set::Radical),
    ("root", Set::Radical),
    ("mat", Set::Matrix),
    ("vec", Set::Column),
    ("cases", Set::Column),
    ("abs", Set::Bracketed),
    ("norm", Set::Bracketed),
    ("floor", Set::Bracketed),
    ("ceil", Set::Bracketed),
    ("accent", Set::Over),
    ("limits", Set::Side),
    ("scripts", Set::Side),
    ("overline", Set::Side),
    ("underline", Set::Side),
    ("overbrace", Set::Over),
    ("underbrace", Set::Over),
    ("lr", Set::Side),
    ("upright", Set::Side),
    ("italic", Set::Side),
    ("bold", Set::Side),
    ("op", Set::Side),
    ("display", Set::Side),
    ("inline", Set::Side),
    ("script", Set::Side),
    ("cancel", Set::Side),
    ("cal", Set::Side),
    ("bb", Set::Side),
    ("frak", Set::Side),
    ("sans", Set::Side),
    ("mono", Set::Side),
    ("serif", Set::Side),
];

/// The arguments of a name that is not a function (`sin(x)`): side by side, with their
/// brackets and commas set as written.
fn shown_arguments(args: &SyntaxNode, g: &Glyphs) -> Option<f64> {
    let marks = args
        .children()
        .filter(|a| {
            matches!(
                a.kind(),
                SyntaxKind::LeftParen | SyntaxKind::RightParen | SyntaxKind::Comma
            )
        })
        .map(|a| Some(g.widest(leaf_char(a)?)? + GAP))
        .sum::<Option<f64>>()?;
    Some(marks + Table::of(args, g)?.side_by_side())
}

/// `#h(…)`: its width in em, a negative one as none; a length in points at the body's 10.5 pt.
fn spacing(n: &SyntaxNode) -> Option<f64> {
    let mut parts = n.children();
    let callee = parts.next()?;
    if callee.kind() != SyntaxKind::Ident || callee.leaf_text() != "h" {
        return Option::None;
    }
    let args = parts.next()?;
    let value = args.children().find(|c| c.kind() == SyntaxKind::Numeric)?;
    let t = value.leaf_text();
    let split = t.find(|c: char| c.is_ascii_alphabetic() || c == '%')?;
    let (number, unit) = t.split_at(split);
    let number: f64 = number.parse().ok()?;
    let em = match unit {
        "em" => number,
        "pt" => number / BODY_PT,
        "mm" => number * 72.0 / 25.4 / BODY_PT,
        "cm" => number * 72.0 / 2.54 / BODY_PT,
        "in" => number * 72.0 / BODY_PT,
        _ => return Option::None,
    };
    Some(em.max(0.0))
}

#[cfg(test)]
mod tests {
    use super::{NARROWER_THAN_ANY_LINE, widest_em};

    /// Formulas as the printers write them, one of each construct the bound knows.
    const FORMULAS: &[&str] = &[
        "I_(x x) = frac(2, 5) m a^(2)",
        "frac(A^(2), ω_(3)^(2))",
        "accent(I, arrow.l.r) = mat(16 m d^(2), -6 m d^(2), 0; -6 m d^(2), 6 m d^(2), -2 m d^(2); 0, -2 m d^(2), 18 m d^(2))",
        "arrow(r) = mat(display(frac(R s z cos (θ), h)); display(frac(R s z sin (θ), h)); z)",
        "I_(x y) = integral_(0)^(3 a) integral_(0)^(2 a) integral_(0)^(a) -frac(m x y, 6 a^(3)) thin d x thin d y thin d z = -frac(m a^(2), 2)",
        "Ω^(2) = frac(3 attach(p, b: ϕ)^(2) (g M m\\/attach(p, b: ϕ)^(2))^(4\\/3), m (M + m))",
        "p_(ψ) = I_(3) (dot(ψ) + dot(ϕ) cos (θ))",
        "I_(3) (dot.double(ϕ) cos (θ) - dot(ϕ) dot(θ) sin (θ) + dot.double(ψ)) = 0",
        "upright(\"dm\") = ρ dot.op 1\\,  quad ρ = frac(m, 6 a^(3))",
        "sqrt(frac(g, l)) + root(3, x^(2) + y^(2)) + abs(v) + norm(w)",
        "f(x) = cases(x^(2) &quad x > 0, 0 &quad \"otherwise\")",
        "lr(\\(, size: #1.8em) b lr(\\), size: #1.8em) #h(2em); vec(a, b, c)",
        "x' + y'' = sum_(k = 1)^(n) k^(2) = product_(k) W M Q",
        "cal(M) + bb(R) + bold(W) + frak(Z) = ℏ ω",
        "upright(\"leave\")_(1) = -arccos (frac(2 cos (attach(θ, b: 0)), 3))",
        // As the tree's printer writes them: every script an `attach`, every operator escaped.
        "attach(I, b: x y)\\=attach(scripts(∫), b: 0, t: 3 a) attach(scripts(∫), b: −a\\/2, t: a)−frac(m x y, 6 attach(a, t: 3)) thin d x thin d y\\=−frac(m attach(a, t: 2), 2)",
        "λ\\=frac(m, 12) lr(\\(attach(a, t: 2)\\+attach(b, t: 2)\\))\\:thick\"axis along \"mat(0; 0; display(frac(1, 2)))",
        "attach(accent(ω, dot), b: 3)\\=attach(lr(\\(frac(8661249, 1159339)\\)), t: 3\\/2) attach(e, t: attach(x, t: script(2)))",
        "attach(R, tl: 2, bl: 1, t: 3, b: 4) attach(I, b: x x, t: 2)",
    ];

    /// Typst's own width of each formula, in em of 10.5 pt.
    fn measured(formulas: &[&str]) -> Vec<f64> {
        let mut m = String::from(
            "#set page(width: 3000pt, height: auto, margin: 10pt)\n\
             #set text(font: \"New Computer Modern\", size: 10.5pt)\n",
        );
        for f in formulas {
            m.push_str(&format!("#context [W#(measure($ {f} $).width.pt())]\n\n"));
        }
        super::super::typeset::texts(&m)
            .iter()
            .filter_map(|t| t.strip_prefix('W'))
            .map(|pt| pt.parse::<f64>().unwrap() / 10.5)
            .collect()
    }

    #[test]
    fn the_bound_is_never_narrower_than_typst_sets_the_formula() {
        let widths = measured(FORMULAS);
        assert_eq!(widths.len(), FORMULAS.len());
        for (f, typst) in FORMULAS.iter().zip(widths) {
            let bound = widest_em(f).unwrap_or_else(|| panic!("no bound for {f}"));
            assert!(typst > 0.5, "{f}: measured {typst} em");
            assert!(
                bound >= typst,
                "{f}: the bound {bound:.2} em is below Typst's {typst:.2} em"
            );
            // Loose enough to be of no use would be a bound that measures nothing.
            assert!(bound <= 3.0 * typst, "{f}: {bound:.2} em for {typst:.2}");
        }
    }

    /// Scripts nest: each is measured once, so an author's 50-deep `\\underset` is bounded at
    /// once (counted twice per level it took 2^50 steps, and the build never ended).
    #[test]
    fn nested_scripts_are_measured_once_each() {
        let mut math = String::from("M");
        for _ in 0..50 {
            math = format!("attach({math}, b: a)");
        }
        // Each level sets one more `a` beside the rest (at least 0.4 em wide).
        let bound = widest_em(&math).unwrap();
        assert!(bound > 50.0 * 0.4, "{bound}");
    }

    #[test]
    fn what_the_bound_does_not_know_gives_none() {
        assert_eq!(widest_em("unknownname(x)"), None);
        assert_eq!(widest_em("x #text(red)[y]"), None);
        assert_eq!(widest_em("frac(a"), None);
        assert_eq!(widest_em("arrow.nomodifier"), None);
        assert!(widest_em("x + y").unwrap() < NARROWER_THAN_ANY_LINE);
    }
}
