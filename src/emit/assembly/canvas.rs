//! A page being drawn: paper millimetres (origin bottom left, y up) turned
//! into printpdf operations. Strokes, fills, text in the built-in Helvetica
//! (WinAnsi only: [`winansi`] maps what it lacks), with the state (colour,
//! line width, font) emitted only when it changes and consecutive text
//! kept in one text object, so big pages stay small.

use printpdf::{
    BuiltinFont, Color, Line, LinePoint, Op, PaintMode, PdfFontHandle, Point, Polygon, PolygonRing,
    Pt, Rgb, TextItem, TextMatrix, WindingOrder,
};

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

/// One page's operations.
#[derive(Debug, Default)]
pub struct Canvas {
    ops: Vec<Op>,
    in_text: bool,
    font: Option<(bool, u32)>,
    fill: Option<Rgb3>,
    stroke: Option<Rgb3>,
    width_pt: Option<f32>,
    dashed: bool,
}

/// Millimetres to points, rounded to 0.01 pt (short numbers in the file).
fn pt(mm: f64) -> f32 {
    ((mm * PT_PER_MM * 100.0).round() / 100.0) as f32
}

fn point(p: [f64; 2]) -> Point {
    Point {
        x: Pt(pt(p[0])),
        y: Pt(pt(p[1])),
    }
}

fn color(c: Rgb3) -> Color {
    Color::Rgb(Rgb {
        r: c[0],
        g: c[1],
        b: c[2],
        icc_profile: None,
    })
}

impl Canvas {
    /// An empty page.
    pub fn new() -> Canvas {
        Canvas::default()
    }

    /// The operations drawn, ending any open text object.
    pub fn into_ops(mut self) -> Vec<Op> {
        self.end_text();
        self.ops
    }

    /// How many operations so far.
    pub fn len(&self) -> usize {
        self.ops.len()
    }

    fn end_text(&mut self) {
        if self.in_text {
            self.ops.push(Op::EndTextSection);
            self.in_text = false;
        }
    }

    /// Stroke colour.
    pub fn stroke(&mut self, c: Rgb3) {
        if self.stroke != Some(c) {
            self.end_text();
            self.ops.push(Op::SetOutlineColor { col: color(c) });
            self.stroke = Some(c);
        }
    }

    /// Fill (and text) colour.
    pub fn fill(&mut self, c: Rgb3) {
        if self.fill != Some(c) {
            self.ops.push(Op::SetFillColor { col: color(c) });
            self.fill = Some(c);
        }
    }

    /// Line width, mm.
    pub fn width(&mut self, mm: f64) {
        let w = pt(mm);
        if self.width_pt != Some(w) {
            self.end_text();
            self.ops.push(Op::SetOutlineThickness { pt: Pt(w) });
            self.width_pt = Some(w);
        }
    }

    /// Dashed (`true`) or solid lines from now on.
    pub fn dash(&mut self, dashed: bool) {
        if self.dashed != dashed {
            self.end_text();
            let pattern: &[f32] = if dashed { &[4.0, 2.0] } else { &[] };
            self.ops.push(Op::SetLineDashPattern {
                dash: printpdf::LineDashPattern {
                    offset: 0.0,
                    pattern: pattern.iter().copied().collect(),
                },
            });
            self.dashed = dashed;
        }
    }

    /// A stroked polyline through `pts` (paper mm); closed joins the last
    /// point to the first.
    pub fn polyline(&mut self, pts: &[[f64; 2]], closed: bool) {
        if pts.len() < 2 {
            return;
        }
        self.end_text();
        self.ops.push(Op::DrawLine {
            line: Line {
                points: pts
                    .iter()
                    .map(|&p| LinePoint {
                        p: point(p),
                        bezier: false,
                    })
                    .collect(),
                is_closed: closed,
            },
        });
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
        self.end_text();
        self.ops.push(Op::DrawPolygon {
            polygon: Polygon {
                rings: vec![PolygonRing {
                    points: pts
                        .iter()
                        .map(|&p| LinePoint {
                            p: point(p),
                            bezier: false,
                        })
                        .collect(),
                }],
                mode: PaintMode::Fill,
                winding_order: WindingOrder::NonZero,
            },
        });
    }

    /// An axis-aligned rectangle from (x, y), `w` × `h` mm: filled with the
    /// current fill colour and/or stroked.
    pub fn rect(&mut self, x: f64, y: f64, w: f64, h: f64, fill: bool, stroke: bool) {
        let pts = [[x, y], [x + w, y], [x + w, y + h], [x, y + h]];
        if fill {
            self.fill_polygon(&pts);
        }
        if stroke {
            self.polyline(&pts, true);
        }
    }

    /// A circle of radius `r` mm (four Bézier arcs): stroked, or filled.
    pub fn circle(&mut self, c: [f64; 2], r: f64, filled: bool) {
        const K: f64 = 0.552_284_749_8;
        let k = K * r;
        let [x, y] = c;
        let seq = [
            ([x + r, y], false),
            ([x + r, y + k], true),
            ([x + k, y + r], true),
            ([x, y + r], false),
            ([x - k, y + r], true),
            ([x - r, y + k], true),
            ([x - r, y], false),
            ([x - r, y - k], true),
            ([x - k, y - r], true),
            ([x, y - r], false),
            ([x + k, y - r], true),
            ([x + r, y - k], true),
            ([x + r, y], false),
        ];
        let points: Vec<LinePoint> = seq
            .iter()
            .map(|&(p, bezier)| LinePoint {
                p: point(p),
                bezier,
            })
            .collect();
        self.end_text();
        if filled {
            self.ops.push(Op::DrawPolygon {
                polygon: Polygon {
                    rings: vec![PolygonRing { points }],
                    mode: PaintMode::Fill,
                    winding_order: WindingOrder::NonZero,
                },
            });
        } else {
            self.ops.push(Op::DrawLine {
                line: Line {
                    points,
                    is_closed: true,
                },
            });
        }
    }

    /// Text at `at` (its baseline), `size_pt` points, anchored by `align`,
    /// turned `rot_deg` counter-clockwise about the anchor; current fill
    /// colour. Characters outside WinAnsi are mapped by [`winansi`].
    pub fn text(&mut self, at: [f64; 2], size_pt: f64, bold: bool, align: Align, rot_deg: f64, s: &str) {
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
        let x = at[0] - shift * cos;
        let y = at[1] - shift * sin;
        if !self.in_text {
            self.ops.push(Op::StartTextSection);
            self.in_text = true;
        }
        let size = (size_pt * 100.0).round() as u32;
        if self.font != Some((bold, size)) {
            self.ops.push(Op::SetFont {
                font: PdfFontHandle::Builtin(if bold {
                    BuiltinFont::HelveticaBold
                } else {
                    BuiltinFont::Helvetica
                }),
                size: Pt(size as f32 / 100.0),
            });
            self.font = Some((bold, size));
        }
        let r = |v: f64| ((v * 10_000.0).round() / 10_000.0) as f32;
        self.ops.push(Op::SetTextMatrix {
            matrix: TextMatrix::Raw([r(cos), r(sin), r(-sin), r(cos), pt(x), pt(y)]),
        });
        self.ops.push(Op::ShowText {
            items: vec![TextItem::Text(s)],
        });
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
    fn widths_follow_helvetica() {
        // "0" is 556/1000 em: at 10 pt, 5.56 pt.
        assert!((text_width_mm("0", 10.0, false) - 5.56 / PT_PER_MM).abs() < 1e-9);
        assert!(text_width_mm("W", 10.0, true) > text_width_mm("i", 10.0, true));
    }
}
