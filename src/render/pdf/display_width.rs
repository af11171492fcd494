//! An upper bound on how wide Typst sets a formula on a line of its own, measured on the tree
//! the page sets and the PDF prints (`notation::typst`), with the math font's glyphs. A formula
//! surely narrower than the narrowest line is set without `measure` (`Markup::block`), which
//! saves a second layout of every short formula: about a sixth of the typesetting time of
//! tests/course (docs/performance.md, "Short formulas set without measuring").
//!
//! The bound is a sum over the formula's pieces, as the Typst printer sets them, since Typst
//! never sets a construct wider than its parts side by side (a fraction is as wide as its wider
//! part, a script stands beside its base, a matrix's columns each as wide as their widest
//! entry): each character counts the widest glyph the font may set for it (any letter style,
//! any size of a delimiter, radical or large operator), each neighbour in a row the most Typst
//! puts between two, each script its base's italic correction, and each construct what it
//! draws itself (a radical, a matrix's brackets and gaps). A character the font lacks gives no
//! bound, and the formula is measured.

use super::glyphs::{Glyphs, glyphs};
use crate::notation::Tex;
use crate::notation::latex::{Node, cells, relation_text};
use crate::notation::typst::bracketed_on_the_line;
use pulldown_latex::event::{
    Content, Dimension, DimensionUnit, Font, Grouping, ScriptPosition, ScriptType, StateChange,
    Visual,
};

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

/// The upper bound on the width of `tex` set as a display formula, in em; `None` when it holds
/// a character the math font lacks.
pub fn widest_em(tex: &Tex) -> Option<f64> {
    // A gap more than between the elements: room at the line's ends.
    Some(Bound { g: glyphs()? }.row(&tex.nodes, Place::default())? + GAP)
}

/// Where an element stands, as the Typst printer tells it apart: in `\mathrm{…}` a run of
/// letters is one word; in a fraction's part or a script a fraction goes on the line (`a\/b`).
#[derive(Clone, Copy, Default)]
struct Place {
    upright: bool,
    on_the_line: bool,
}

struct Bound {
    g: &'static Glyphs,
}

impl Bound {
    fn char(&self, c: char) -> Option<f64> {
        self.g.widest(c)
    }

    fn chars(&self, s: &str) -> Option<f64> {
        s.chars()
            .map(|c| if c == ' ' { Some(SPACE) } else { self.char(c) })
            .sum()
    }

    /// A row: each element, and a gap between neighbours. A change of font holds for the
    /// rest of it.
    fn row(&self, nodes: &[Node], place: Place) -> Option<f64> {
        let (mut w, mut elements) = (0.0, 0_usize);
        let mut i = 0;
        while i < nodes.len() {
            match &nodes[i] {
                Node::State(StateChange::Font(font)) => {
                    let upright = *font == Some(Font::UpRight);
                    let rest = self.row(&nodes[i + 1..], Place { upright, ..place })?;
                    return Some(w + rest + if elements > 0 { GAP } else { 0.0 });
                }
                Node::State(_) => {}
                Node::Atom(Content::Ordinary { content, .. })
                    if place.upright && content.is_ascii_alphabetic() =>
                {
                    // One upright word, one string in Typst.
                    while let Some(Node::Atom(Content::Ordinary { content, .. })) = nodes.get(i)
                        && content.is_ascii_alphabetic()
                    {
                        w += self.char(*content)?;
                        i += 1;
                    }
                    elements += 1;
                    continue;
                }
                n => {
                    w += self.node(n, place)?;
                    elements += 1;
                }
            }
            i += 1;
        }
        Some(w + elements.saturating_sub(1) as f64 * GAP)
    }

    /// A part of a construct (a numerator, a script, a radicand): its group's content.
    fn part(&self, n: &Node, place: Place) -> Option<f64> {
        match n {
            Node::Group(Grouping::Normal, inner) => self.row(inner, place),
            other => self.row(std::slice::from_ref(other), place),
        }
    }

    fn node(&self, n: &Node, place: Place) -> Option<f64> {
        Some(match n {
            Node::Text(s) if s == "&nbsp;" => SPACE,
            Node::Text(s) | Node::Number(s) => self.chars(s)?,
            // `sin`, or any other name as `op("…")`: its letters, upright.
            Node::Function(f) => self.chars(f)?,
            Node::Atom(c) => self.atom(c)?,
            Node::Group(g, inner) => self.group(g, inner, place)?,
            Node::Visual(Visual::Fraction(_), parts) if parts.len() == 2 => {
                let inner = Place {
                    on_the_line: true,
                    ..place
                };
                let (top, bottom) = (self.part(&parts[0], inner)?, self.part(&parts[1], inner)?);
                if !place.on_the_line {
                    return Some(top.max(bottom) + FRACTION);
                }
                // `a\/b`, a part bracketed as the printer brackets it.
                let brackets = |n: &Node, below: bool| -> Option<f64> {
                    Some(match bracketed_on_the_line(n, below) {
                        true => self.char('(')? + self.char(')')? + 2.0 * GAP,
                        false => 0.0,
                    })
                };
                top + bottom
                    + self.char('/')?
                    + 2.0 * GAP
                    + brackets(&parts[0], false)?
                    + brackets(&parts[1], true)?
            }
            Node::Visual(Visual::SquareRoot, parts) => {
                self.char('√')? + self.part(parts.first()?, place)?
            }
            Node::Visual(Visual::Root, parts) if parts.len() == 2 => {
                self.char('√')? + self.part(&parts[0], place)? + self.part(&parts[1], place)?
            }
            // A negated relation is one character (≠), at most as wide as the relation and its
            // stroke side by side; anything else is cancelled, as wide as itself.
            Node::Visual(Visual::Negation, parts) => self.row(parts, place)? + self.char('/')?,
            Node::Visual(_, parts) => self.row(parts, place)?,
            Node::Script {
                ty,
                position,
                parts,
            } => self.script(*ty, *position, parts, place)?,
            Node::Space(d) => space(*d),
            Node::State(_) | Node::Flow(_) => 0.0,
        })
    }

    fn atom(&self, c: &Content) -> Option<f64> {
        match *c {
            Content::Ordinary { content, .. }
            | Content::LargeOp { content, .. }
            | Content::BinaryOp { content, .. }
            | Content::Punctuation(content)
            | Content::Delimiter { content, .. } => self.char(content),
            Content::Relation { content, .. } => self.chars(&relation_text(&content)),
            Content::Text(_) | Content::Number(_) | Content::Function(_) => Some(0.0),
        }
    }

    /// `x_1^2`: the base and its italic correction, then the wider script. An accent over
    /// the base (`accent(x, dot)`) is as wide as the wider of the two; a line, a brace or
    /// limits above and below are counted beside it.
    fn script(
        &self,
        ty: ScriptType,
        position: ScriptPosition,
        parts: &[Node],
        place: Place,
    ) -> Option<f64> {
        let (base, scripts) = parts.split_first()?;
        if position == ScriptPosition::AboveBelow
            && ty == ScriptType::Superscript
            && let [Node::Atom(Content::Ordinary { content, .. })] = scripts
        {
            return Some(self.part(base, place)?.max(self.char(*content)?));
        }
        let inner = Place {
            on_the_line: true,
            ..place
        };
        let mut widest: f64 = 0.0;
        for s in scripts.iter().take(match ty {
            ScriptType::SubSuperscript => 2,
            _ => 1,
        }) {
            widest = widest.max(self.part(s, inner)?);
        }
        Some(self.part(base, place)? + self.italic(base) + widest)
    }

    /// The italic correction after a script's base: a lone character's own, else the largest.
    fn italic(&self, base: &Node) -> f64 {
        match base {
            Node::Atom(Content::Ordinary { content, .. } | Content::LargeOp { content, .. }) => {
                self.g.italic_of(*content)
            }
            _ => self.g.most_italic,
        }
    }

    fn group(&self, g: &Grouping, inner: &[Node], place: Place) -> Option<f64> {
        let brackets = || Some(2.0 * self.g.widest_bracket()?);
        Some(match g {
            Grouping::Normal => self.row(inner, place)?,
            Grouping::LeftRight(open, close) => {
                if let [Node::Group(Grouping::Matrix { .. }, body)] = inner {
                    return Some(self.columns(body, place, COLUMN_GAP)? + brackets()?);
                }
                let mut w = self.row(inner, place)? + 2.0 * GAP;
                for c in open.iter().chain(close.iter()) {
                    w += self.char(*c)?;
                }
                w
            }
            Grouping::Matrix { .. } | Grouping::Array(_) => {
                self.columns(inner, place, COLUMN_GAP)?
            }
            // A case's value and condition with a quad between them, after a brace.
            Grouping::Cases { .. } => self.columns(inner, place, 1.0 + GAP)? + brackets()?,
            // The equation environments: their widest line.
            _ => self.columns(inner, place, 0.0)?,
        })
    }

    /// A table's width: each column as wide as its widest cell, `gap` between columns.
    fn columns(&self, body: &[Node], place: Place, gap: f64) -> Option<f64> {
        let mut widths: Vec<f64> = Vec::new();
        for row in cells(body) {
            for (j, cell) in row.iter().enumerate() {
                let w = self.row(cell, place)?;
                match widths.get_mut(j) {
                    Some(widest) => *widest = widest.max(w),
                    None => widths.push(w),
                }
            }
        }
        Some(widths.iter().sum::<f64>() + widths.len().saturating_sub(1) as f64 * gap)
    }
}

/// A space's width in em, a negative one as none.
fn space(d: Option<Dimension>) -> f64 {
    let Some(d) = d else { return 0.0 };
    let v = f64::from(d.value);
    let em = match d.unit {
        DimensionUnit::Em => v,
        DimensionUnit::Mu => v / 18.0,
        DimensionUnit::Ex => v * 0.5,
        DimensionUnit::Pt | DimensionUnit::Bp | DimensionUnit::Dd => v / BODY_PT,
        DimensionUnit::Sp => v / 65536.0 / BODY_PT,
        DimensionUnit::Pc | DimensionUnit::Cc => v * 12.0 / BODY_PT,
        DimensionUnit::In => v * 72.0 / BODY_PT,
        DimensionUnit::Cm => v * 72.0 / 2.54 / BODY_PT,
        DimensionUnit::Mm => v * 72.0 / 25.4 / BODY_PT,
    };
    em.max(0.0)
}

#[cfg(test)]
mod tests {
    use super::{NARROWER_THAN_ANY_LINE, widest_em};
    use crate::notation::Tex;

    /// Formulas as the pages set them, one of each construct the printers write.
    const FORMULAS: &[&str] = &[
        r"I_{xx} = \frac{2}{5} m a^{2}",
        r"\frac{A^{2}}{\omega_{3}^{2}}",
        r"\overleftrightarrow{I} = \begin{pmatrix}16 m d^{2} & -6 m d^{2} & 0 \\ -6 m d^{2} & 6 m d^{2} & -2 m d^{2} \\ 0 & -2 m d^{2} & 18 m d^{2}\end{pmatrix}",
        r"\vec{r} = \begin{pmatrix}\frac{R s z \cos\left(\theta\right)}{h} \\ \frac{R s z \sin\left(\theta\right)}{h} \\ z\end{pmatrix}",
        r"I_{xy} = \int_{0}^{3 a} \int_{0}^{2 a} \int_{0}^{a} -\frac{m x y}{6 a^{3}} \, dx \, dy \, dz = -\frac{m a^{2}}{2}",
        r"\Omega^{2} = \frac{3 p_{\phi}^{2} \left(\frac{g M m}{p_{\phi}^{2}}\right)^{\frac{4}{3}}}{m \left(M + m\right)}",
        r"p_{\psi} = I_{3} \left(\dot{\psi} + \dot{\phi} \cos\left(\theta\right)\right)",
        r"I_{3} \left(\ddot{\phi} \cos\theta - \dot{\phi} \dot{\theta} \sin\theta + \ddot{\psi}\right) = 0",
        r"\mathrm{dm} = \rho \cdot 1 \, \quad \rho = \frac{m}{6 a^{3}}",
        r"\sqrt{\frac{g}{l}} + \sqrt[3]{x^{2} + y^{2}} + \left|v\right| + \left\|w\right\|",
        r"f(x) = \begin{cases}x^{2} & x > 0 \\ 0 & \text{otherwise}\end{cases}",
        r"\Bigl( b \Bigr) \hspace{2em} \begin{pmatrix}a \\ b \\ c\end{pmatrix}",
        r"x' + y'' = \sum_{k = 1}^{n} k^{2} = \prod_{k} W M Q",
        r"\mathcal{M} + \mathbb{R} + \mathbf{W} + \mathfrak{Z} = \hbar \omega",
        r"\mathrm{leave}_{1} = -\arccos\left(\frac{2 \cos\left(\theta_{0}\right)}{3}\right)",
        r"{}^{2}_{1}R^{3}_{4} \, I_{xx}^{2} \ne 0 \le \omega_{\mathrm{min2}}",
        r"\lambda = \frac{m}{12} \left(a^{2} + b^{2}\right) \; \text{axis along } \begin{pmatrix}0 \\ 0 \\ \frac{1}{2}\end{pmatrix}",
        r"\dot{\omega}_{3} = \left(\frac{8661249}{1159339}\right)^{3/2} e^{x^{2}}",
        r"\underbrace{a + b}_{n} + \overline{z} + \hat{n} \perp \tilde{x}",
    ];

    /// Typst's own width of each formula's Typst, in em of 10.5 pt.
    fn measured(formulas: &[String]) -> Vec<f64> {
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

    fn read(latex: &str) -> Tex {
        Tex::read(latex).unwrap_or_else(|e| panic!("{latex}: {e}"))
    }

    #[test]
    fn the_bound_is_never_narrower_than_typst_sets_the_formula() {
        let trees: Vec<Tex> = FORMULAS.iter().map(|f| read(f)).collect();
        let typst: Vec<String> = trees.iter().map(|t| t.to_typst().unwrap()).collect();
        let widths = measured(&typst);
        assert_eq!(widths.len(), FORMULAS.len());
        for ((f, tree), typst) in FORMULAS.iter().zip(&trees).zip(widths) {
            let bound = widest_em(tree).unwrap_or_else(|| panic!("no bound for {f}"));
            assert!(typst > 0.5, "{f}: measured {typst} em");
            assert!(
                bound >= typst,
                "{f}: the bound {bound:.2} em is below Typst's {typst:.2} em"
            );
            // Loose enough to be of no use would be a bound that measures nothing.
            assert!(bound <= 3.0 * typst, "{f}: {bound:.2} em for {typst:.2}");
        }
    }

    /// Random expressions of every kind of node, as `Expr::to_tex` builds their trees: the
    /// bound is never below Typst's width, and not so loose that it measures everything.
    #[test]
    fn the_bound_holds_over_random_expressions() {
        let mut g = crate::notation::random_expr::Gen(0x2545_F491_4F6C_DD1D);
        let trees: Vec<Tex> = (0..300)
            .map(|_| g.expr(4).to_tex(crate::notation::Names::none()))
            .collect();
        let typst: Vec<String> = trees.iter().map(|t| t.to_typst().unwrap()).collect();
        let widths = measured(&typst);
        assert_eq!(widths.len(), trees.len());
        let mut narrow = 0;
        for ((tree, typst), width) in trees.iter().zip(&typst).zip(widths) {
            let bound = widest_em(tree).unwrap_or_else(|| panic!("no bound for {typst}"));
            assert!(
                bound >= width,
                "{typst}: the bound {bound:.2} em is below {width:.2}"
            );
            narrow += usize::from(bound <= NARROWER_THAN_ANY_LINE);
        }
        // Most of them are short: a bound that let few through would measure them all again.
        assert!(narrow > 150, "{narrow} of 300 surely narrow");
    }

    /// Scripts nest: an author's 50-deep subscript is bounded at once, each level once.
    #[test]
    fn nested_scripts_are_measured_once_each() {
        let mut latex = String::from("M");
        for _ in 0..50 {
            latex = format!("{{{latex}}}_{{a}}");
        }
        // Each level sets one more `a` beside the rest (at least 0.4 em wide).
        let bound = widest_em(&read(&latex)).unwrap();
        assert!(bound > 50.0 * 0.4, "{bound}");
    }

    #[test]
    fn a_character_the_font_lacks_gives_no_bound() {
        assert_eq!(widest_em(&read(r"x + \text{漢}")), None);
        assert!(widest_em(&read("x + y")).unwrap() < NARROWER_THAN_ANY_LINE);
    }
}
