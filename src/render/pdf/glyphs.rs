//! The math fonts' glyph widths, read once from the fonts built into the binary: what the bound
//! on a formula's width (`display_width.rs`) counts each character as.

use std::collections::HashMap;
use std::sync::OnceLock;

/// The math fonts' glyph widths: for each character, in em, the widest glyph any style of it
/// has (italic, bold, script, double-struck, …) at any size (a delimiter's, a radical's and a
/// large operator's larger forms and the pieces they are built of).
pub(super) struct Glyphs {
    widest: HashMap<char, f64>,
    /// Each character's largest italic correction, which a script is set after (a large
    /// integral's, 0.59 em, is the font's largest).
    italic: HashMap<char, f64>,
    pub(super) most_italic: f64,
}

impl Glyphs {
    pub(super) fn widest(&self, c: char) -> Option<f64> {
        // A variation selector (the text form of `arrow.l.r`, ↔ U+FE0E) picks a glyph and
        // sets none of its own.
        if ('\u{FE00}'..='\u{FE0F}').contains(&c) {
            return Some(0.0);
        }
        self.widest.get(&c).copied()
    }

    /// The italic correction after a script's base `c`: its own, else the largest.
    pub(super) fn italic_of(&self, c: char) -> f64 {
        self.italic.get(&c).copied().unwrap_or(self.most_italic)
    }

    /// The widest bracket a function may draw, at any size.
    pub(super) fn widest_bracket(&self) -> Option<f64> {
        BRACKETS
            .iter()
            .map(|&c| self.widest(c))
            .try_fold(0.0_f64, |w, b| Some(w.max(b?)))
    }
}

const BRACKETS: &[char] = &[
    '(', ')', '[', ']', '{', '}', '|', '‖', '⟨', '⟩', '⌊', '⌋', '⌈', '⌉',
];

/// Read once from the fonts built into the binary; `None` if no math font is among them.
pub(super) fn glyphs() -> Option<&'static Glyphs> {
    static GLYPHS: OnceLock<Option<Glyphs>> = OnceLock::new();
    GLYPHS.get_or_init(read_glyphs).as_ref()
}

fn read_glyphs() -> Option<Glyphs> {
    let faces: Vec<ttf_parser::Face> = super::typeset::font_files()
        .iter()
        .filter_map(|data| ttf_parser::Face::parse(data, 0).ok())
        .filter(|f| f.tables().math.is_some())
        .collect();
    if faces.is_empty() {
        return Option::None;
    }
    let mut widest = HashMap::new();
    let mut italic = HashMap::new();
    // Every character of the Basic Latin to Mathematical Operators blocks, arrows, brackets and
    // the letter-like symbols, as the font has it.
    let ranges = [
        0x20..=0x2FF_u32,
        0x370..=0x3FF,
        0x2000..=0x2BFF,
        0x1D400..=0x1D7FF,
    ];
    for c in ranges.into_iter().flatten().filter_map(char::from_u32) {
        if let Some((w, i)) = glyph(&faces, c) {
            widest.insert(c, w);
            italic.insert(c, i);
        }
    }
    // A letter counts its widest style: Typst sets a letter in the Mathematical Alphanumeric
    // Symbols, or in the letter-like symbols that fill their gaps.
    let mut styled: Vec<(char, f64, f64)> = Vec::new();
    for (c, forms) in styled_forms() {
        let all: Vec<char> = std::iter::once(c).chain(forms).collect();
        let most = |of: &HashMap<char, f64>| {
            all.iter()
                .filter_map(|f| of.get(f).copied())
                .fold(0.0_f64, f64::max)
        };
        let w = most(&widest);
        if w > 0.0 {
            styled.push((c, w, most(&italic)));
        }
    }
    for (c, w, i) in styled {
        widest.insert(c, w);
        italic.insert(c, i);
    }
    let most_italic = italic.values().copied().fold(0.0_f64, f64::max);
    Some(Glyphs {
        widest,
        italic,
        most_italic,
    })
}

/// A glyph's widest advance and largest italic correction over the math fonts, its larger
/// forms and their pieces.
fn glyph(faces: &[ttf_parser::Face], c: char) -> Option<(f64, f64)> {
    let mut found: Option<(f64, f64)> = Option::None;
    for f in faces {
        let Some(id) = f.glyph_index(c) else { continue };
        let per_em = f64::from(f.units_per_em());
        let math = f.tables().math;
        let measure = |id| {
            let advance = f64::from(f.glyph_hor_advance(id).unwrap_or(0)) / per_em;
            let italic = math
                .and_then(|m| m.glyph_info)
                .and_then(|i| i.italic_corrections)
                .and_then(|i| i.get(id))
                .map_or(0.0, |v| f64::from(v.value).max(0.0) / per_em);
            (advance, italic)
        };
        let mut ids = vec![id];
        if let Some(v) = math.and_then(|m| m.variants)
            && let Some(c) = v.vertical_constructions.get(id)
        {
            ids.extend(c.variants.into_iter().map(|v| v.variant_glyph));
            ids.extend(
                c.assembly
                    .map(|a| a.parts)
                    .into_iter()
                    .flatten()
                    .map(|p| p.glyph_id),
            );
        }
        for id in ids {
            let (w, i) = measure(id);
            let (fw, fi) = found.unwrap_or((0.0, 0.0));
            found = Some((fw.max(w), fi.max(i)));
        }
    }
    found
}

/// Each letter and digit with its styled forms (Unicode's Mathematical Alphanumeric Symbols,
/// and for their gaps the letter-like symbols).
fn styled_forms() -> Vec<(char, Vec<char>)> {
    // Bold, italic, bold italic, script, bold script, Fraktur, double-struck, bold Fraktur,
    // sans-serif, sans-serif bold, sans-serif italic, sans-serif bold italic, monospace.
    const LATIN: [u32; 13] = [
        0x1D400, 0x1D434, 0x1D468, 0x1D49C, 0x1D4D0, 0x1D504, 0x1D538, 0x1D56C, 0x1D5A0, 0x1D5D4,
        0x1D608, 0x1D63C, 0x1D670,
    ];
    // The gaps of those styles, each letter before the letter-like symbol that fills it.
    const GAPS: &str = "hℎBℬEℰFℱHℋIℐLℒMℳRℛeℯgℊoℴCℭHℌIℑRℜZℨCℂHℍNℕPℙQℚRℝZℤ";
    // Bold, italic, bold italic, sans-serif bold, sans-serif bold italic.
    const GREEK: [u32; 5] = [0x1D6A8, 0x1D6E2, 0x1D71C, 0x1D756, 0x1D790];
    // Bold, double-struck, sans-serif, sans-serif bold, monospace.
    const DIGITS: [u32; 5] = [0x1D7CE, 0x1D7D8, 0x1D7E2, 0x1D7EC, 0x1D7F6];
    let at = |bases: &[u32], i: u32| -> Vec<char> {
        bases.iter().filter_map(|b| char::from_u32(b + i)).collect()
    };
    let mut out = Vec::new();
    for (i, c) in ('A'..='Z').chain('a'..='z').enumerate() {
        let mut forms = at(&LATIN, i as u32);
        let gaps: Vec<char> = GAPS.chars().collect();
        forms.extend(gaps.chunks(2).filter(|p| p[0] == c).map(|p| p[1]));
        out.push((c, forms));
    }
    // The dotless i and j, which an accent sits on.
    out.push(('ı', vec!['\u{1D6A4}']));
    out.push(('ȷ', vec!['\u{1D6A5}']));
    // Greek in the order of its styled forms: the capitals (with ϴ for the gap at U+03A2), ∇,
    // the small letters, then ∂ ϵ ϑ ϰ ϕ ϱ ϖ.
    let greek: Vec<char> = ('\u{391}'..='\u{3A9}')
        .map(|c| if c == '\u{3A2}' { 'ϴ' } else { c })
        .chain(['∇'])
        .chain('\u{3B1}'..='\u{3C9}')
        .chain(['∂', 'ϵ', 'ϑ', 'ϰ', 'ϕ', 'ϱ', 'ϖ'])
        .collect();
    for (i, c) in greek.into_iter().enumerate() {
        out.push((c, at(&GREEK, i as u32)));
    }
    for (i, c) in ('0'..='9').enumerate() {
        out.push((c, at(&DIGITS, i as u32)));
    }
    out
}
