//! A sheet drawing as SVG: `width`/`height` in mm with a matching `viewBox`
//! (one user unit = 1 mm), the sheet's y up (SVG's y = width − y), one group
//! per operation with its colour (the DXF layer's), hairline strokes
//! ([`STROKE_MM`]), no fills; the same geometry as the DXF in the same
//! cutting order (groups `ENGRAVE`, `CUT-INNER`, `CUT-OUTER`, parts in
//! travel order in each; bulges as circular `A` arcs, round holes as
//! circles). Only when asked: a first group `SHEET` with the sheet's
//! outline (reference, not cut) and a last group, `LABELS`, with each
//! part's id as screen text over the part, a third of its short side high
//! (laser software would import it as text to engrave: the engraved labels
//! are in `ENGRAVE`). Written by hand with fixed decimals, so equal sheets
//! give equal bytes.

use super::drawing::{
    engrave_mm, engrave_units, strokes, Layer, Shape, SheetDrawing, SheetFileOptions, Vertex,
    ENGRAVE_DECIMALS,
};
use std::io::Write;

/// Stroke width of every contour, mm.
pub const STROKE_MM: f64 = 0.1;

/// Decimals of every coordinate (0.1 µm).
const DECIMALS: u32 = 4;

/// Screen label height: at most this, mm.
const LABEL_MAX_MM: f64 = 40.0;

/// The SVG text of one sheet; `title` names the project and sheet.
pub fn to_svg(sheet: &SheetDrawing, title: &str, opts: SheetFileOptions) -> String {
    let mut s = Vec::new();
    write_svg(sheet, title, opts, &mut s);
    // Written from `str`s and ASCII only.
    String::from_utf8(s).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())
}

/// The SVG text of one sheet into `s` (cleared first; a buffer used again
/// for the next sheet keeps its memory).
pub fn write_svg(sheet: &SheetDrawing, title: &str, opts: SheetFileOptions, s: &mut Vec<u8>) {
    let (l, w) = (sheet.length_mm, sheet.width_mm);
    let bytes: usize = sheet
        .parts
        .iter()
        .flat_map(|p| &p.shapes)
        .map(|sh| match sh {
            Shape::Polyline { vertices, .. } => 24 + 16 * vertices.len(),
            Shape::Strokes { points_um, .. } => 24 + 16 * points_um.len(),
            Shape::Circle { .. } => 60,
        })
        .sum();
    s.clear();
    s.reserve(4096 + 200 * sheet.parts.len() + bytes);
    let _ = writeln!(s, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{}mm" height="{}mm" viewBox="0 0 {} {}">"#,
        num(l),
        num(w),
        num(l),
        num(w)
    );
    let _ = writeln!(s, "<title>{}</title>", escape(title));
    for layer in Layer::ALL {
        if layer == Layer::Sheet && !opts.sheet_outline {
            continue;
        }
        let _ = writeln!(
            s,
            r#"<g id="{}" fill="none" stroke="{}" stroke-width="{}" stroke-linecap="round" stroke-linejoin="round">"#,
            layer.name(),
            layer.rgb(),
            num(STROKE_MM)
        );
        if layer == Layer::Sheet {
            shape(s, &sheet.outline(), w);
        }
        for part in &sheet.parts {
            if layer == Layer::Engrave {
                engraving(s, &part.shapes, w);
                continue;
            }
            for sh in part.shapes.iter().filter(|sh| shape_layer(sh) == layer) {
                shape(s, sh, w);
            }
        }
        let _ = writeln!(s, "</g>");
    }
    if opts.labels {
        labels(sheet, s);
    }
    let _ = writeln!(s, "</svg>");
}

/// The `LABELS` group: each part's id over it.
fn labels(sheet: &SheetDrawing, s: &mut Vec<u8>) {
    let w = sheet.width_mm;
    let _ = writeln!(
        s,
        r##"<g id="LABELS" fill="#808080" fill-opacity="0.6" stroke="none" font-family="sans-serif" text-anchor="middle">"##
    );
    for part in &sheet.parts {
        let [x0, y0, x1, y1] = part.bbox_mm;
        let text = &part.part;
        // A third of the part's short side, and no wider than the part (a
        // glyph ≈ 0.7 of the height wide).
        let size = (0.3 * (y1 - y0).min(x1 - x0))
            .min((x1 - x0) / (0.7 * text.chars().count().max(1) as f64))
            .min(LABEL_MAX_MM);
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" font-size="{}">{}</text>"#,
            num(cx),
            num(w - cy + 0.35 * size),
            num(size),
            escape(text)
        );
    }
    let _ = writeln!(s, "</g>");
}

fn shape_layer(sh: &Shape) -> Layer {
    sh.layer()
}

fn shape(s: &mut Vec<u8>, sh: &Shape, w: f64) {
    match sh {
        Shape::Circle {
            center_mm,
            radius_mm,
            ..
        } => {
            s.extend_from_slice(br#"<circle cx=""#);
            crate::formats::text::push_decimal(s, center_mm[0], DECIMALS, false);
            s.extend_from_slice(br#"" cy=""#);
            crate::formats::text::push_decimal(s, w - center_mm[1], DECIMALS, false);
            s.extend_from_slice(br#"" r=""#);
            crate::formats::text::push_decimal(s, *radius_mm, DECIMALS, false);
            s.extend_from_slice(b"\"/>\n");
        }
        Shape::Polyline {
            closed, vertices, ..
        } => {
            s.extend_from_slice(br#"<path d=""#);
            let n = vertices.len();
            s.push(b'M');
            crate::formats::text::push_decimal(s, vertices[0].x_mm, DECIMALS, false);
            s.push(b' ');
            crate::formats::text::push_decimal(s, w - vertices[0].y_mm, DECIMALS, false);
            let segments = if *closed { n } else { n - 1 };
            for i in 0..segments {
                let (a, b) = (vertices[i], vertices[(i + 1) % n]);
                if *closed && i + 1 == n && a.bulge == 0.0 {
                    break; // `Z` draws the closing straight segment
                }
                segment(s, a, b, w);
            }
            if *closed {
                s.push(b'Z');
            }
            s.extend_from_slice(b"\"/>\n");
        }
        Shape::Strokes {
            points_um, ends, ..
        } => {
            for stroke in strokes(points_um, ends) {
                let vertices = stroke
                    .iter()
                    .map(|&[x, y]| Vertex {
                        x_mm: engrave_mm(x),
                        y_mm: engrave_mm(y),
                        bulge: 0.0,
                    })
                    .collect();
                shape(
                    s,
                    &Shape::Polyline {
                        layer: sh.layer(),
                        closed: false,
                        vertices,
                    },
                    w,
                );
            }
        }
    }
}

/// A part's engraving strokes as one path of open subpaths, relative
/// after its first point: `M x y h dx v dy l dx dy … m dx dy …`
/// (horizontal and vertical steps as `h` and `v`, a command letter only
/// where it changes, no zero before a decimal point, no space before a
/// minus sign). The strokes' points lie on the engraving's grid of
/// [`ENGRAVE_DECIMALS`] decimals ([`super::drawing`]), so every step is a
/// whole number of grid units, written exactly: the positions it adds up
/// to are the DXF's.
fn engraving(s: &mut Vec<u8>, shapes: &[Shape], w: f64) {
    let mut path = RelativePath::new(s);
    let mut at: Option<(i64, i64)> = None;
    // One stroke, in grid units (y down as SVG draws it).
    let mut draw = |points: &mut dyn Iterator<Item = (i64, i64)>, path: &mut RelativePath| {
        let Some(first) = points.next() else {
            return;
        };
        match at {
            None => path.start(engrave_mm(first.0), w + engrave_mm(first.1)),
            Some(last) => path.step(b'm', last, first),
        }
        let mut last = first;
        for p in points {
            path.step(b'l', last, p);
            last = p;
        }
        at = Some(last);
    };
    for sh in shapes.iter().filter(|sh| sh.layer() == Layer::Engrave) {
        match sh {
            Shape::Polyline { vertices, .. } => draw(
                &mut vertices
                    .iter()
                    .map(|v| (engrave_units(v.x_mm), -engrave_units(v.y_mm))),
                &mut path,
            ),
            Shape::Strokes {
                points_um, ends, ..
            } => {
                for stroke in strokes(points_um, ends) {
                    draw(&mut stroke.iter().map(|&[x, y]| (x, -y)), &mut path);
                }
            }
            Shape::Circle { .. } => {}
        }
    }
    if at.is_some() {
        path.s.extend_from_slice(b"\"/>\n");
    }
}

/// An SVG path written with relative steps (see [`engraving`]).
struct RelativePath<'a> {
    s: &'a mut Vec<u8>,
    /// The command the next numbers continue without a letter.
    command: u8,
    /// Whether a number was written last (a separator may be due).
    after_number: bool,
}

impl<'a> RelativePath<'a> {
    fn new(s: &'a mut Vec<u8>) -> RelativePath<'a> {
        RelativePath {
            s,
            command: 0,
            after_number: false,
        }
    }

    /// `<path d="M x y` (absolute, mm).
    fn start(&mut self, x: f64, y: f64) {
        self.s.extend_from_slice(br#"<path d="M"#);
        crate::formats::text::push_decimal(self.s, x, DECIMALS, false);
        self.s.push(b' ');
        crate::formats::text::push_decimal(self.s, y, DECIMALS, false);
        // Numbers after an `M` pair would be absolute lines.
        self.command = b'L';
        self.after_number = true;
    }

    /// The step from `a` to `b` (grid units): a move (`m`), or a line as
    /// `h`, `v` or `l`.
    fn step(&mut self, kind: u8, a: (i64, i64), b: (i64, i64)) {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        match kind {
            b'm' => {
                self.letter(b'm');
                self.number(dx);
                self.number(dy);
                // Pairs after an `m` pair are relative lines.
                self.command = b'l';
            }
            _ if dy == 0 => {
                self.letter(b'h');
                self.number(dx);
            }
            _ if dx == 0 => {
                self.letter(b'v');
                self.number(dy);
            }
            _ => {
                self.letter(b'l');
                self.number(dx);
                self.number(dy);
            }
        }
    }

    fn letter(&mut self, c: u8) {
        if self.command != c || c == b'm' {
            self.s.push(c);
            self.command = c;
            self.after_number = false;
        }
    }

    /// A whole number of grid units as a decimal, without the zero before
    /// the point (`-.75`, `.5`, `12`).
    fn number(&mut self, units: i64) {
        // A minus sign separates; a number after a number needs a space.
        if self.after_number && units >= 0 {
            self.s.push(b' ');
        }
        crate::formats::text::push_digits(
            self.s,
            units < 0,
            units.unsigned_abs(),
            ENGRAVE_DECIMALS as u32,
            false,
            false,
        );
        self.after_number = true;
    }
}

/// The segment from `a` to `b`: a line, or the arc of `a`'s bulge.
fn segment(s: &mut Vec<u8>, a: Vertex, b: Vertex, w: f64) {
    if a.bulge == 0.0 {
        s.extend_from_slice(b" L");
        crate::formats::text::push_decimal(s, b.x_mm, DECIMALS, false);
        s.push(b' ');
        crate::formats::text::push_decimal(s, w - b.y_mm, DECIMALS, false);
        return;
    }
    let (bx, by) = (num(b.x_mm), num(w - b.y_mm));
    let chord = (b.x_mm - a.x_mm).hypot(b.y_mm - a.y_mm);
    // Bulge b = tan(θ/4): radius = chord·(1 + b²)/(4|b|); more than a half
    // turn when |b| > 1. Counter-clockwise (b > 0) in the sheet's y-up
    // frame stays counter-clockwise to the eye once y is flipped (the
    // picture is not mirrored), and SVG's positive sweep (flag 1) is
    // clockwise to the eye (angles grow with y down): so b > 0 is flag 0.
    let r = chord * (1.0 + a.bulge * a.bulge) / (4.0 * a.bulge.abs());
    let large = u8::from(a.bulge.abs() > 1.0);
    let sweep = u8::from(a.bulge < 0.0);
    let _ = write!(s, " A{} {} 0 {large} {sweep} {bx} {by}", num(r), num(r));
}

/// A number with at most [`DECIMALS`] decimals, trailing zeros dropped,
/// never `-0`.
fn num(x: f64) -> String {
    let mut t = String::with_capacity(16);
    crate::formats::text::push_decimal_str(&mut t, x, DECIMALS, false);
    t
}

fn escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_fixed() {
        assert_eq!(num(3000.0), "3000");
        assert_eq!(num(0.1), "0.1");
        assert_eq!(num(-0.00001), "0");
        assert_eq!(num(12.345678), "12.3457");
    }

    /// Two strokes on a 100 mm wide sheet (SVG y = 100 − y): the first
    /// point absolute, then a horizontal, a vertical and a slanted step, a
    /// move to the second stroke and its step continuing the move's
    /// implicit line; by hand.
    #[test]
    fn engraving_is_relative_and_compact() {
        let v = |x_mm, y_mm| Vertex {
            x_mm,
            y_mm,
            bulge: 0.0,
        };
        let stroke = |vertices| Shape::Polyline {
            layer: Layer::Engrave,
            closed: false,
            vertices,
        };
        let shapes = [
            stroke(vec![
                v(10.0, 10.0),
                v(12.5, 10.0),
                v(12.5, 9.25),
                v(11.75, 8.5),
            ]),
            stroke(vec![v(20.0, 10.0), v(19.5, 10.75)]),
        ];
        let mut s = Vec::new();
        engraving(&mut s, &shapes, 100.0);
        assert_eq!(
            s,
            b"<path d=\"M10 90h2.5v.75l-.75 .75m8.25-1.5-.5-.75\"/>\n"
        );
    }

    /// Grid numbers (µm) one after another: a space only between two
    /// numbers where no minus sign separates them, no zero before a point.
    #[test]
    fn grid_numbers_are_separated_only_where_needed() {
        let mut s = Vec::new();
        let mut path = RelativePath::new(&mut s);
        for units in [0, 500, -500, 12_000, -12_000, 1, -1, 1_234_567, 0] {
            path.number(units);
        }
        assert_eq!(s, b"0 .5-.5 12-12 .001-.001 1234.567 0");
    }

    /// A half circle of radius 5 from (0, 0) to (10, 0) counter-clockwise
    /// (bulge 1): radius 5, small arc flag 0, negative sweep (it passes
    /// below the chord, y up: (5, −5)).
    #[test]
    fn bulges_become_arcs() {
        let mut s = Vec::new();
        let v = |x_mm, bulge| Vertex {
            x_mm,
            y_mm: 0.0,
            bulge,
        };
        segment(&mut s, v(0.0, 1.0), v(10.0, 0.0), 100.0);
        assert_eq!(s, b" A5 5 0 0 0 10 100");
    }

    /// Arcs land where the bulges put them, as an independent renderer
    /// (resvg) draws them: a stadium 40 × 20 mm (y up, from (10, 10)),
    /// fitted by lines and two counter-clockwise half circles, and the
    /// same turned clockwise (negative bulges), filled: ink 3 mm inside
    /// each end's tip, none 3 mm outside it, and none where an end arc
    /// drawn on the wrong side of its chord would put it.
    #[test]
    fn arcs_render_on_the_side_their_bulge_gives() {
        use crate::formats::write::arcs::fit_closed;
        let (r, len, w) = (10.0, 20.0, 40.0);
        let mut ring: Vec<[f64; 2]> = Vec::new();
        for k in 0..=64 {
            let a = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * f64::from(k) / 64.0;
            ring.push([10.0 + r + len + r * a.cos(), 10.0 + r + r * a.sin()]);
        }
        for k in 0..=64 {
            let a = std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * f64::from(k) / 64.0;
            ring.push([10.0 + r + r * a.cos(), 10.0 + r + r * a.sin()]);
        }
        for clockwise in [false, true] {
            let pts: Vec<[f64; 2]> = if clockwise {
                ring.iter().rev().copied().collect()
            } else {
                ring.clone()
            };
            let vertices = fit_closed(&pts, 0.01);
            assert!(vertices.iter().any(|v| v.bulge != 0.0), "arcs fitted");
            let mut s = Vec::new();
            s.extend_from_slice(
                br#"<svg xmlns="http://www.w3.org/2000/svg" width="60" height="40" viewBox="0 0 60 40">"#,
            );
            let mut body = Vec::new();
            shape(
                &mut body,
                &Shape::Polyline {
                    layer: Layer::CutOuter,
                    closed: true,
                    vertices,
                },
                w,
            );
            let body = String::from_utf8(body)
                .expect("utf8")
                .replace("<path ", r##"<path fill="#000" "##);
            s.extend_from_slice(body.as_bytes());
            s.extend_from_slice(b"</svg>");
            let text = String::from_utf8(s).expect("utf8");
            let tree =
                resvg::usvg::Tree::from_str(&text, &resvg::usvg::Options::default()).expect("svg");
            let mut pix = resvg::tiny_skia::Pixmap::new(600, 400).expect("pixmap");
            resvg::render(
                &tree,
                resvg::tiny_skia::Transform::from_scale(10.0, 10.0),
                &mut pix.as_mut(),
            );
            // Sheet mm (y up) to the 10 px/mm image (y down).
            let ink = |x: f64, y: f64| {
                pix.pixel((x * 10.0) as u32, ((w - y) * 10.0) as u32)
                    .is_some_and(|p| p.alpha() > 0)
            };
            let (left, right, mid) = (10.0, 10.0 + 2.0 * r + len, 10.0 + r);
            assert!(ink(left + 3.0, mid) && ink(right - 3.0, mid), "{text}");
            assert!(!ink(left - 3.0, mid) && !ink(right + 3.0, mid), "{text}");
            // An arc on the wrong side of its chord bulges into the
            // straight part: 3 mm short of the far chord's middle, and
            // outside the stadium beyond the ends' chords.
            assert!(ink(left + r + 3.0, mid + 0.5 * r), "{text}");
        }
    }
}
