//! A page being drawn: paper millimetres (origin bottom left, y up) written
//! as a PDF content stream. Strokes, fills, text in the built-in Helvetica
//! (WinAnsi only: [`winansi`] maps what it lacks), with the state (colour,
//! line width, font) emitted only when it changes and consecutive text
//! kept in one text object, so big pages stay small.

use crate::formats::text::{push_decimal, push_scaled};

/// Points per millimetre.
const PT_PER_MM: f64 = 72.0 / 25.4;

/// An RGB colour, components in 0..=1.
pub type Rgb3 = [f32; 3];

/// Black.
pub const BLACK: Rgb3 = [0.0, 0.0, 0.0];
/// Mid grey.
pub const GREY: Rgb3 = [0.55, 0.55, 0.55];
/// Light grey.
pub const LIGHT: Rgb3 = [0.85, 0.85, 0.85];
/// Red (overstress, warnings).
pub const RED: Rgb3 = [0.8, 0.0, 0.0];
/// Blue (engraving, dimensions).
pub const BLUE: Rgb3 = [0.0, 0.2, 0.75];

/// The resource name of the built-in Helvetica (the page resources of
/// [`super::pdf`]).
pub const HELVETICA_RES: &str = "F5";
/// The resource name of the built-in Helvetica-Bold.
pub const HELVETICA_BOLD_RES: &str = "F6";

/// Horizontal anchor of a text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Align {
    /// The text starts at the point.
    Left,
    /// The text is centred on the point.
    Center,
    /// The text ends at the point.
    Right,
}

/// One page's content stream, written directly as PDF operators
/// ([`super::pdf`] writes the document around it).
#[derive(Debug, Default)]
pub struct Canvas {
    out: Vec<u8>,
    in_text: bool,
    /// The text line start, tenths of a point, when unrotated.
    line_at: Option<(i64, i64)>,
    font: Option<(bool, u32)>,
    fill: Option<Rgb3>,
    stroke: Option<Rgb3>,
    width_pt: Option<i64>,
    dashed: bool,
}

/// Millimetres to tenths of a point (0.035 mm, finer than print).
fn hpt(mm: f64) -> i64 {
    crate::formats::text::round_to_i64(mm * PT_PER_MM * 10.0)
}

impl Canvas {
    /// An empty page.
    pub fn new() -> Canvas {
        Canvas::default()
    }

    /// The content stream drawn, ending any open text object.
    pub fn into_content(mut self) -> Vec<u8> {
        self.end_text();
        self.out
    }

    /// Bytes written so far.
    pub fn len(&self) -> usize {
        self.out.len()
    }

    /// Whether nothing is drawn.
    pub fn is_empty(&self) -> bool {
        self.out.is_empty()
    }

    fn num(&mut self, tenths: i64) {
        push_scaled(&mut self.out, tenths < 0, tenths.unsigned_abs(), 1, false);
        self.out.push(b' ');
    }

    fn xy(&mut self, p: [f64; 2]) {
        self.num(hpt(p[0]));
        self.num(hpt(p[1]));
    }

    fn end_text(&mut self) {
        if self.in_text {
            self.out.extend_from_slice(b"ET\n");
            self.in_text = false;
            self.line_at = None;
        }
    }

    fn rgb(&mut self, c: Rgb3, op: &str) {
        for v in c {
            push_decimal(&mut self.out, f64::from(v), 3, false);
            self.out.push(b' ');
        }
        self.out.extend_from_slice(op.as_bytes());
        self.out.push(b'\n');
    }

    /// Stroke colour.
    pub fn stroke(&mut self, c: Rgb3) {
        if self.stroke != Some(c) {
            self.end_text();
            self.rgb(c, "RG");
            self.stroke = Some(c);
        }
    }

    /// Fill (and text) colour.
    pub fn fill(&mut self, c: Rgb3) {
        if self.fill != Some(c) {
            self.rgb(c, "rg");
            self.fill = Some(c);
        }
    }

    /// Line width, mm.
    pub fn width(&mut self, mm: f64) {
        let w = hpt(mm);
        if self.width_pt != Some(w) {
            self.end_text();
            self.num(w);
            self.out.extend_from_slice(b"w\n");
            self.width_pt = Some(w);
        }
    }

    /// Dashed (`true`) or solid lines from now on.
    pub fn dash(&mut self, dashed: bool) {
        if self.dashed != dashed {
            self.end_text();
            self.out
                .extend_from_slice(if dashed { b"[4 2] 0 d\n" } else { b"[] 0 d\n" });
            self.dashed = dashed;
        }
    }

    fn path(&mut self, pts: &[[f64; 2]]) {
        self.end_text();
        let mut last = None;
        for (k, &p) in pts.iter().enumerate() {
            let q = (hpt(p[0]), hpt(p[1]));
            if last == Some(q) {
                continue;
            }
            last = Some(q);
            self.num(q.0);
            self.num(q.1);
            self.out
                .extend_from_slice(if k == 0 { b"m\n" } else { b"l\n" });
        }
    }

    /// A stroked polyline through `pts` (paper mm); closed joins the last
    /// point to the first.
    pub fn polyline(&mut self, pts: &[[f64; 2]], closed: bool) {
        if pts.len() < 2 {
            return;
        }
        self.path(pts);
        self.out
            .extend_from_slice(if closed { b"s\n" } else { b"S\n" });
    }

    /// A straight segment.
    pub fn line(&mut self, a: [f64; 2], b: [f64; 2]) {
        self.polyline(&[a, b], false);
    }

    /// A filled polygon (current fill colour), no outline.
    pub fn fill_polygon(&mut self, pts: &[[f64; 2]]) {
        if pts.len() < 3 {
            return;
        }
        self.path(pts);
        self.out.extend_from_slice(b"h f\n");
    }

    /// An axis-aligned rectangle from (x, y), `w` × `h` mm: filled with the
    /// current fill colour and/or stroked.
    pub fn rect(&mut self, x: f64, y: f64, w: f64, h: f64, fill: bool, stroke: bool) {
        if !fill && !stroke {
            return;
        }
        self.end_text();
        self.xy([x, y]);
        self.num(hpt(x + w) - hpt(x));
        self.num(hpt(y + h) - hpt(y));
        self.out.extend_from_slice(match (fill, stroke) {
            (true, true) => b"re B\n",
            (true, false) => b"re f\n",
            _ => b"re S\n",
        });
    }

    /// A dot: a filled square `side_mm` wide centred on `c` (cheaper than a
    /// circle where thousands are drawn).
    pub fn dot(&mut self, c: [f64; 2], side_mm: f64) {
        let h = 0.5 * side_mm;
        self.rect(c[0] - h, c[1] - h, side_mm, side_mm, true, false);
    }

    /// From here until [`Canvas::clip_end`], draw only inside the
    /// rectangle from (x, y), `w` × `h` mm (the graphics state is saved).
    pub fn clip_begin(&mut self, x: f64, y: f64, w: f64, h: f64) {
        self.dash(false);
        self.end_text();
        self.out.extend_from_slice(
            b"q
",
        );
        self.xy([x, y]);
        self.num(hpt(x + w) - hpt(x));
        self.num(hpt(y + h) - hpt(y));
        self.out.extend_from_slice(
            b"re W n
",
        );
    }

    /// End a [`Canvas::clip_begin`]: the graphics state before it returns
    /// (colours, width, dash), so they are set again when next used.
    pub fn clip_end(&mut self) {
        self.end_text();
        self.out.extend_from_slice(
            b"Q
",
        );
        self.fill = None;
        self.stroke = None;
        self.width_pt = None;
        self.dashed = false;
        self.font = None;
    }

    /// A circle of radius `r` mm (four Bézier arcs): stroked, or filled.
    /// Holes are drawn as circles however small.
    pub fn circle(&mut self, c: [f64; 2], r: f64, filled: bool) {
        const K: f64 = 0.552_284_749_8;
        let k = K * r;
        let [x, y] = c;
        self.end_text();
        self.xy([x + r, y]);
        self.out.extend_from_slice(b"m\n");
        let arcs = [
            [[x + r, y + k], [x + k, y + r], [x, y + r]],
            [[x - k, y + r], [x - r, y + k], [x - r, y]],
            [[x - r, y - k], [x - k, y - r], [x, y - r]],
            [[x + k, y - r], [x + r, y - k], [x + r, y]],
        ];
        for a in arcs {
            for p in a {
                self.xy(p);
            }
            self.out.extend_from_slice(b"c\n");
        }
        self.out
            .extend_from_slice(if filled { b"h f\n" } else { b"h S\n" });
    }

    /// Text at `at` (its baseline), `size_pt` points, anchored by `align`,
    /// turned `rot_deg` counter-clockwise about the anchor; current fill
    /// colour. Characters outside WinAnsi are mapped by [`winansi`].
    pub fn text(
        &mut self,
        at: [f64; 2],
        size_pt: f64,
        bold: bool,
        align: Align,
        rot_deg: f64,
        s: &str,
    ) {
        if s.is_empty() {
            return;
        }
        let s = winansi(s);
        let w = text_width_mm(&s, size_pt, bold);
        let shift = match align {
            Align::Left => 0.0,
            Align::Center => 0.5 * w,
            Align::Right => w,
        };
        let (sin, cos) = rot_deg.to_radians().sin_cos();
        let (x, y) = (hpt(at[0] - shift * cos), hpt(at[1] - shift * sin));
        if !self.in_text {
            self.out.extend_from_slice(b"BT\n");
            self.in_text = true;
            self.line_at = Some((0, 0));
        }
        let size = (size_pt * 10.0).round() as u32;
        if self.font != Some((bold, size)) {
            self.out.push(b'/');
            self.out.extend_from_slice(
                if bold {
                    HELVETICA_BOLD_RES
                } else {
                    HELVETICA_RES
                }
                .as_bytes(),
            );
            self.out.push(b' ');
            self.num(i64::from(size));
            self.out.extend_from_slice(b"Tf\n");
            self.font = Some((bold, size));
        }
        if rot_deg == 0.0 {
            match self.line_at {
                // Relative to the last line start: short numbers, exact
                // (whole tenths of a point).
                Some((lx, ly)) => {
                    self.num(x - lx);
                    self.num(y - ly);
                    self.out.extend_from_slice(b"Td\n");
                }
                None => {
                    self.out.extend_from_slice(b"1 0 0 1 ");
                    self.num(x);
                    self.num(y);
                    self.out.extend_from_slice(b"Tm\n");
                }
            }
            self.line_at = Some((x, y));
        } else {
            for v in [cos, sin, -sin, cos] {
                push_decimal(&mut self.out, v, 4, false);
                self.out.push(b' ');
            }
            self.num(x);
            self.num(y);
            self.out.extend_from_slice(b"Tm\n");
            self.line_at = None;
        }
        self.out.push(b'(');
        for c in s.chars() {
            match c {
                '(' | ')' | '\\' => {
                    self.out.push(b'\\');
                    self.out.push(c as u8);
                }
                ' '..='~' => self.out.push(c as u8),
                _ => {
                    let b = win_ansi_byte(c).unwrap_or(b'?');
                    self.out.extend_from_slice(format!("\\{b:03o}").as_bytes());
                }
            }
        }
        self.out.extend_from_slice(b") Tj\n");
    }
}

/// The WinAnsi byte of a character [`winansi`] lets through.
fn win_ansi_byte(c: char) -> Option<u8> {
    match c as u32 {
        cp @ 0x20..=0x7e | cp @ 0xa0..=0xff => Some(cp as u8),
        _ => Some(match c {
            '€' => 0x80,
            '…' => 0x85,
            '‘' => 0x91,
            '’' => 0x92,
            '“' => 0x93,
            '”' => 0x94,
            '•' => 0x95,
            '–' => 0x96,
            '—' => 0x97,
            _ => return None,
        }),
    }
}

/// `s` with every character WinAnsi lacks replaced by an ASCII spelling
/// (`→` as `->`, `≤` as `<=`, Greek letters by name, anything else `?`).
pub fn winansi(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            ' '..='~' | '\u{a0}'..='\u{ff}' => out.push(c),
            '–' | '—' | '…' | '•' | '‘' | '’' | '“' | '”' | '€' => out.push(c),
            '→' => out.push_str("->"),
            '←' => out.push_str("<-"),
            '≤' => out.push_str("<="),
            '≥' => out.push_str(">="),
            '−' => out.push('-'),
            '≈' => out.push('~'),
            'σ' => out.push_str("sigma"),
            'τ' => out.push_str("tau"),
            'γ' => out.push_str("gamma"),
            'κ' => out.push_str("kappa"),
            'φ' => out.push_str("phi"),
            'α' => out.push_str("alpha"),
            'λ' => out.push_str("lambda"),
            'Σ' => out.push_str("sum "),
            _ => out.push('?'),
        }
    }
    out
}

/// Advance widths of Helvetica, 1/1000 em, for ' '..='~'.
const HELVETICA: [u16; 95] = [
    278, 278, 355, 556, 556, 889, 667, 191, 333, 333, 389, 584, 278, 333, 278, 278, 556, 556, 556,
    556, 556, 556, 556, 556, 556, 556, 278, 278, 584, 584, 584, 556, 1015, 667, 667, 722, 722, 667,
    611, 778, 722, 278, 500, 667, 556, 833, 722, 778, 667, 778, 722, 667, 611, 722, 667, 944, 667,
    667, 611, 278, 278, 278, 469, 556, 333, 556, 556, 500, 556, 556, 278, 556, 556, 222, 222, 500,
    222, 833, 556, 556, 556, 556, 333, 500, 278, 556, 500, 722, 500, 500, 500, 334, 260, 334, 584,
];

/// Advance widths of Helvetica-Bold, 1/1000 em, for ' '..='~'.
const HELVETICA_BOLD: [u16; 95] = [
    278, 333, 474, 556, 556, 889, 722, 238, 333, 333, 389, 584, 278, 333, 278, 278, 556, 556, 556,
    556, 556, 556, 556, 556, 556, 556, 333, 333, 584, 584, 584, 611, 975, 722, 722, 722, 722, 667,
    611, 778, 722, 278, 556, 722, 611, 833, 722, 778, 667, 778, 722, 667, 611, 722, 667, 944, 667,
    667, 611, 333, 278, 333, 584, 556, 333, 556, 611, 556, 611, 556, 333, 611, 611, 278, 278, 556,
    278, 889, 611, 611, 611, 611, 389, 556, 333, 611, 556, 778, 556, 556, 500, 389, 280, 389, 584,
];

/// The width of `s` (already WinAnsi) in Helvetica at `size_pt`, mm.
pub fn text_width_mm(s: &str, size_pt: f64, bold: bool) -> f64 {
    let table = if bold { &HELVETICA_BOLD } else { &HELVETICA };
    let units: u32 = s
        .chars()
        .map(|c| match c {
            ' '..='~' => u32::from(table[c as usize - 32]),
            '—' => 1000,
            '°' => 400,
            '·' => 278,
            _ => 556,
        })
        .sum();
    f64::from(units) / 1000.0 * size_pt / PT_PER_MM
}

/// Cap height of Helvetica at `size_pt`, mm.
pub fn cap_mm(size_pt: f64) -> f64 {
    0.718 * size_pt / PT_PER_MM
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn maps_what_winansi_lacks() {
        assert_eq!(winansi("A → B ≤ 1 × 2 °"), "A -> B <= 1 × 2 °");
        assert_eq!(winansi("σv"), "sigmav");
    }

    #[test]
    fn text_is_escaped_winansi() {
        let mut c = Canvas::new();
        c.text([10.0, 10.0], 8.0, false, Align::Left, 0.0, "a (b) 90° \\");
        let s = String::from_utf8(c.into_content()).expect("ascii");
        assert!(s.contains("(a \\(b\\) 90\\260 \\\\) Tj"), "{s}");
        assert!(s.starts_with("BT\n/F5 8 Tf\n"), "{s}");
    }

    #[test]
    fn widths_follow_helvetica() {
        // "0" is 556/1000 em: at 10 pt, 5.56 pt.
        assert!((text_width_mm("0", 10.0, false) - 5.56 / PT_PER_MM).abs() < 1e-9);
        assert!(text_width_mm("W", 10.0, true) > text_width_mm("i", 10.0, true));
    }
}
