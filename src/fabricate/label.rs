//! Placing engraving on a part: text labels and the orientation mark.
//!
//! A part's cuts are its outline and its holes (part frame, mm). An
//! engraving is placed by its bounding box: grown by the clearance (the
//! caller passes kerf + part spacing), the box must lie inside the outline,
//! meet no cut edge (so it is clear of holes and of notches such as slots)
//! and, with a [`Placer`], overlap nothing placed before. Every stroke then
//! keeps at least the clearance from every cut edge
//! ([`super::invariants::engraving_inside_and_clear`] holds).
//!
//! The search: at the largest height first, from `max_height_mm` down in
//! steps of 10 % of it to `min_height_mm` (which is always tried), the box
//! centred on the anchor, then shifted along x by steps of a quarter of the
//! height (at least 1/200 of the search width), alternately right and left,
//! up to `search_mm` either side. The first box that fits wins: a larger
//! height beats staying close to the anchor.

use kurbo::{Point, Rect, Vec2};

use super::font;
use super::part::{Engraved, Engraving};
use crate::geom::plane::{point_in_polygon, segment_meets_rect};

/// How large an engraving may be and how far it may move to fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LabelSize {
    /// The height tried first, mm (text: the cap height; the orientation
    /// mark: its whole height).
    pub max_height_mm: f64,
    /// The smallest height accepted, mm.
    pub min_height_mm: f64,
    /// How far the box's centre may move along x from the anchor, either
    /// way, mm.
    pub search_mm: f64,
}

impl LabelSize {
    /// Heights from `max_height_mm` down to `min_height_mm` and the search
    /// width [`DEFAULT_SEARCH_HEIGHTS`] × `max_height_mm`.
    pub fn new(max_height_mm: f64, min_height_mm: f64) -> Self {
        LabelSize {
            max_height_mm,
            min_height_mm,
            search_mm: DEFAULT_SEARCH_HEIGHTS * max_height_mm,
        }
    }
}

/// The search width of [`LabelSize::new`], [`place_label`] and
/// [`orientation_mark`], in multiples of the largest height.
pub const DEFAULT_SEARCH_HEIGHTS: f64 = 10.0;

/// An engraving placed on a part.
#[derive(Debug, Clone, PartialEq)]
pub struct PlacedLabel {
    /// What it is, where and how high (its strokes are
    /// `engraving.strokes()`, the same as `strokes_part_mm`).
    pub engraving: Engraving,
    /// The strokes, open polylines, part frame, mm.
    pub strokes_part_mm: Vec<Vec<Point>>,
    /// The height it was set at, mm.
    pub height_mm: f64,
    /// Its bounding box (not grown by the clearance), part frame, mm.
    pub bbox_part_mm: Rect,
}

/// Places engravings on one part, each clear of the cuts and of those placed
/// before it.
#[derive(Debug, Clone)]
pub struct Placer<'a> {
    outline: &'a [Point],
    holes: &'a [Vec<Point>],
    clearance_mm: f64,
    edges: Vec<(Point, Point)>,
    taken: Vec<Rect>,
}

impl<'a> Placer<'a> {
    /// A placer for the part with this outline (closed, CCW) and these holes
    /// (closed, CW), part frame, mm, keeping `clearance_mm` (kerf + part
    /// spacing) from every cut edge and from every engraving it placed.
    pub fn new(outline: &'a [Point], holes: &'a [Vec<Point>], clearance_mm: f64) -> Self {
        let ring = |poly: &'a [Point]| {
            let n = poly.len();
            (0..n).map(move |i| (poly[i], poly[(i + 1) % n]))
        };
        let edges = ring(outline)
            .chain(holes.iter().flat_map(|h| ring(h)))
            .collect();
        Placer {
            outline,
            holes,
            clearance_mm,
            edges,
            taken: Vec::new(),
        }
    }

    /// The boxes taken so far (engravings placed and areas reserved), mm.
    pub fn taken(&self) -> &[Rect] {
        &self.taken
    }

    /// Keeps `rect` (part frame, mm) free of later engravings.
    pub fn reserve(&mut self, rect: Rect) {
        self.taken.push(rect);
    }

    /// Whether `rect`, grown by the clearance, lies inside the outline,
    /// meets no outline or hole edge, lies in no hole and overlaps (or
    /// touches) no taken box.
    pub fn is_clear(&self, rect: Rect) -> bool {
        self.clear_among(rect, &self.edges)
    }

    fn clear_among(&self, rect: Rect, edges: &[(Point, Point)]) -> bool {
        let g = rect.inflate(self.clearance_mm, self.clearance_mm);
        if ![g.x0, g.y0, g.x1, g.y1].iter().all(|v| v.is_finite()) || g.x0 > g.x1 || g.y0 > g.y1 {
            return false;
        }
        if self
            .taken
            .iter()
            .any(|t| g.x0 <= t.x1 && t.x0 <= g.x1 && g.y0 <= t.y1 && t.y0 <= g.y1)
        {
            return false;
        }
        if edges.iter().any(|&(a, b)| segment_meets_rect(a, b, g)) {
            return false;
        }
        // No cut edge meets the box, so all of it lies on one side of each:
        // one corner tells.
        let corner = Point::new(g.x0, g.y0);
        point_in_polygon(corner, self.outline)
            && !self.holes.iter().any(|h| point_in_polygon(corner, h))
    }

    /// Places `strokes(h)` (drawn at height h, its box [0, width(h)] ×
    /// [0, h]) by the search in the module doc; records its box as taken.
    fn place(
        &mut self,
        anchor: Point,
        size: &LabelSize,
        width: impl Fn(f64) -> f64,
        what: Engraved,
    ) -> Option<PlacedLabel> {
        let LabelSize {
            max_height_mm: max,
            min_height_mm: min,
            search_mm: search,
        } = *size;
        if !(min > 0.0 && max >= min && max.is_finite() && search >= 0.0 && search.is_finite()) {
            return None;
        }
        if !(anchor.x.is_finite() && anchor.y.is_finite()) {
            return None;
        }
        // Only the edges near the corridor the search sweeps can matter.
        let reach = search + width(max) / 2.0 + self.clearance_mm;
        let corridor = Rect::new(
            anchor.x - reach,
            anchor.y - max / 2.0 - self.clearance_mm,
            anchor.x + reach,
            anchor.y + max / 2.0 + self.clearance_mm,
        );
        let edges: Vec<(Point, Point)> = self
            .edges
            .iter()
            .copied()
            .filter(|&(a, b)| segment_meets_rect(a, b, corridor))
            .collect();
        for h in heights(max, min) {
            let w = width(h);
            let step = (h / 4.0).max(search / 200.0);
            let base = Point::new(anchor.x - w / 2.0, anchor.y - h / 2.0);
            for k in 0u64.. {
                let shift = step * k.div_ceil(2) as f64 * if k % 2 == 1 { 1.0 } else { -1.0 };
                if shift.abs() > search {
                    break;
                }
                let origin = base + Vec2::new(shift, 0.0);
                let rect = Rect::new(origin.x, origin.y, origin.x + w, origin.y + h);
                if self.clear_among(rect, &edges) {
                    let engraving = Engraving {
                        what,
                        at_part_mm: origin,
                        height_mm: h,
                    };
                    let strokes_part_mm = engraving.strokes();
                    self.taken.push(rect);
                    return Some(PlacedLabel {
                        engraving,
                        strokes_part_mm,
                        height_mm: h,
                        bbox_part_mm: rect,
                    });
                }
            }
        }
        None
    }

    /// Places `text` (cap height from `size`, single-stroke font) centred
    /// on `anchor` or shifted along x, clear of the cuts and of everything
    /// placed before; `None` when no height and shift in `size` fits.
    pub fn text(&mut self, text: &str, anchor: Point, size: &LabelSize) -> Option<PlacedLabel> {
        if text.is_empty() {
            return None;
        }
        self.place(
            anchor,
            size,
            |h| font::text_width_mm(text, h),
            Engraved::Text(text.to_string()),
        )
    }

    /// Places the orientation mark ([`font::orientation_mark_strokes`]; height
    /// from `size`) like [`Placer::text`].
    pub fn orientation_mark(&mut self, anchor: Point, size: &LabelSize) -> Option<PlacedLabel> {
        self.place(
            anchor,
            size,
            |h| font::ORIENTATION_MARK_LENGTH * h,
            Engraved::OrientationMark,
        )
    }
}

/// Heights to try: `max`, then down in steps of 10 % of `max`, then `min`.
fn heights(max: f64, min: f64) -> Vec<f64> {
    let mut out = Vec::new();
    for k in 0..10 {
        let h = max * (1.0 - 0.1 * k as f64);
        if h < min * (1.0 + 1e-9) {
            break;
        }
        out.push(h);
    }
    if out.last().is_none_or(|&h| h > min * (1.0 + 1e-9)) {
        out.push(min);
    }
    out
}

/// Places `text` on the part with this outline and these holes (part frame,
/// mm): centred on `anchor` or shifted along x up to
/// [`DEFAULT_SEARCH_HEIGHTS`] × `max_height_mm` either way, at the largest
/// cap height from `max_height_mm` down to `min_height_mm` whose box, grown
/// by `clearance_mm`, lies inside the outline and clear of every cut. The
/// strokes, or `None` when nothing fits.
pub fn place_label(
    part_outline: &[Point],
    holes: &[Vec<Point>],
    text: &str,
    anchor: Point,
    max_height_mm: f64,
    min_height_mm: f64,
    clearance_mm: f64,
) -> Option<Vec<Vec<Point>>> {
    Placer::new(part_outline, holes, clearance_mm)
        .text(text, anchor, &LabelSize::new(max_height_mm, min_height_mm))
        .map(|l| l.strokes_part_mm)
}

#[cfg(test)]
mod tests {
    use super::super::invariants::{check_part, strokes_inside_and_clear};
    use super::super::part::{circle_cw, Part, PartKind, ARC_TOLERANCE_MM};
    use super::*;
    use crate::geom::plane::segments_intersect;
    use crate::geom::plane::tests::notched;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    /// 300 × 50 with two 3 × 26 notches from the top at x = 100 and 200 and
    /// a 6 mm hole at (150, 25).
    fn lamella() -> (Vec<Point>, Vec<Vec<Point>>) {
        (
            notched(),
            vec![circle_cw(p(150.0, 25.0), 3.0, ARC_TOLERANCE_MM)],
        )
    }

    const CLEARANCE: f64 = 0.7;

    /// The part with `engraving`, checked by the invariants.
    fn check(engraving: Vec<Vec<Point>>) {
        let (outline, holes) = lamella();
        let part = Part {
            id: "A05-1".into(),
            kind: PartKind::Lamella,
            strip: Some("A05".into()),
            lamella: Some(1),
            count: 1,
            length_mm: 300.0,
            height_mm: 50.0,
            station_start_mm: Some(0.0),
            outline_part_mm: outline,
            holes_part_mm: holes,
            engraving: Vec::new(),
            features: vec![],
        };
        assert_eq!(check_part(&part, CLEARANCE), Ok(()));
        assert_eq!(
            strokes_inside_and_clear(&part, &engraving, CLEARANCE),
            Ok(())
        );
    }

    fn bbox(strokes: &[Vec<Point>]) -> Rect {
        let mut r = Rect::new(
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        );
        for q in strokes.iter().flatten() {
            r = Rect::new(r.x0.min(q.x), r.y0.min(q.y), r.x1.max(q.x), r.y1.max(q.y));
        }
        r
    }

    #[test]
    fn fits_centred_at_full_height() {
        let (outline, holes) = lamella();
        let s = place_label(
            &outline,
            &holes,
            "A05-1",
            p(50.0, 25.0),
            10.0,
            3.0,
            CLEARANCE,
        )
        .expect("fits");
        let b = bbox(&s);
        assert!((b.height() - 10.0).abs() < 1e-9, "{b:?}");
        assert!(
            (b.center().x - 50.0).abs() < 1e-9 && (b.center().y - 25.0).abs() < 1e-9,
            "{b:?}"
        );
        assert_eq!(s, {
            let w = font::text_width_mm("A05-1", 10.0);
            let o = Vec2::new(50.0 - w / 2.0, 20.0);
            font::text_strokes("A05-1", 10.0)
                .into_iter()
                .map(|s| s.into_iter().map(|q| q + o).collect::<Vec<_>>())
                .collect::<Vec<_>>()
        });
        check(s);
    }

    #[test]
    fn moves_off_a_notch_and_a_hole() {
        let (outline, holes) = lamella();
        // On the first notch: shifted clear of it, still 10 mm high.
        let mut placer = Placer::new(&outline, &holes, CLEARANCE);
        let size = LabelSize::new(10.0, 3.0);
        let l = placer.text("A05-1", p(100.0, 25.0), &size).expect("fits");
        assert_eq!(l.height_mm, 10.0);
        let b = l.bbox_part_mm;
        assert!(b.x1 + CLEARANCE < 98.5 || b.x0 - CLEARANCE > 101.5, "{b:?}");
        assert!((b.center().x - 100.0).abs() <= size.search_mm);
        check(l.strokes_part_mm.clone());

        // On the hole.
        let l2 = placer.text("B13", p(150.0, 25.0), &size).expect("fits");
        let b2 = l2.bbox_part_mm;
        assert!(
            b2.x1 + CLEARANCE < 147.0 || b2.x0 - CLEARANCE > 153.0,
            "{b2:?}"
        );
        // Nothing placed overlaps.
        assert!(
            b.x1 < b2.x0 || b2.x1 < b.x0 || b.y1 < b2.y0 || b2.y1 < b.y0,
            "{b:?} {b2:?}"
        );
        // Every stroke of both stays clear: no segment meets a cut.
        let all: Vec<Vec<Point>> = l
            .strokes_part_mm
            .iter()
            .chain(&l2.strokes_part_mm)
            .cloned()
            .collect();
        for s in &all {
            for w in s.windows(2) {
                for i in 0..outline.len() {
                    let (a, c) = (outline[i], outline[(i + 1) % outline.len()]);
                    assert!(!segments_intersect(w[0], w[1], a, c));
                }
            }
        }
        check(all);
    }

    #[test]
    fn shrinks_to_fit_between_notches() {
        let (outline, holes) = lamella();
        // Centred 12 mm above the bottom edge, from 40 mm down: the first
        // height that fits is 20 mm (40, 36, ..., 24 reach the bottom edge
        // or, shifted, never clear the notch within the 30 mm search).
        let mut placer = Placer::new(&outline, &holes, CLEARANCE);
        let size = LabelSize {
            max_height_mm: 40.0,
            min_height_mm: 4.0,
            search_mm: 30.0,
        };
        let l = placer.text("A05-1.2", p(100.0, 12.0), &size).expect("fits");
        assert!((l.height_mm - 20.0).abs() < 1e-9, "{}", l.height_mm);
        assert!((l.bbox_part_mm.center().x - 100.0).abs() < 1e-9);
        check(l.strokes_part_mm);
    }

    #[test]
    fn none_when_nothing_fits() {
        let (outline, holes) = lamella();
        // 30 mm text is 102 mm wide and reaches above the notches' bottoms:
        // no gap between the notches and the ends is wide enough.
        assert_eq!(
            place_label(
                &outline,
                &holes,
                "A05-1",
                p(100.0, 25.0),
                40.0,
                30.0,
                CLEARANCE
            ),
            None
        );
        // Higher than the part.
        assert_eq!(
            place_label(&outline, &holes, "X", p(50.0, 25.0), 80.0, 50.0, CLEARANCE),
            None
        );
        // Outside the part, and the search too short to reach it.
        let mut placer = Placer::new(&outline, &holes, CLEARANCE);
        let size = LabelSize {
            max_height_mm: 5.0,
            min_height_mm: 3.0,
            search_mm: 10.0,
        };
        assert_eq!(placer.text("X", p(-50.0, 25.0), &size), None);
        // Nonsense sizes and empty text.
        assert_eq!(
            place_label(&outline, &holes, "X", p(50.0, 25.0), 3.0, 5.0, CLEARANCE),
            None
        );
        assert_eq!(
            place_label(&outline, &holes, "X", p(50.0, 25.0), 5.0, 0.0, CLEARANCE),
            None
        );
        assert_eq!(
            place_label(&outline, &holes, "", p(50.0, 25.0), 5.0, 3.0, CLEARANCE),
            None
        );
        assert_eq!(
            place_label(
                &outline,
                &holes,
                "X",
                p(f64::NAN, 25.0),
                5.0,
                3.0,
                CLEARANCE
            ),
            None
        );
    }

    #[test]
    fn placed_engravings_do_not_overlap() {
        let (outline, holes) = lamella();
        let mut placer = Placer::new(&outline, &holes, CLEARANCE);
        let size = LabelSize::new(8.0, 3.0);
        let mut all = Vec::new();
        for _ in 0..6 {
            let l = placer
                .text("A05", p(50.0, 12.0), &size)
                .expect("room for six");
            all.extend(l.strokes_part_mm);
        }
        let t = placer.taken();
        for (i, a) in t.iter().enumerate() {
            for b in &t[i + 1..] {
                let g = a.inflate(CLEARANCE, CLEARANCE);
                assert!(
                    g.x1 < b.x0 || b.x1 < g.x0 || g.y1 < b.y0 || b.y1 < g.y0,
                    "{a:?} {b:?}"
                );
            }
        }
        check(all);
        // A reserved area is avoided too.
        let mut placer = Placer::new(&outline, &holes, CLEARANCE);
        placer.reserve(Rect::new(30.0, 0.0, 70.0, 50.0));
        let l = placer
            .text("A05", p(50.0, 25.0), &size)
            .expect("fits beside");
        assert!(l.bbox_part_mm.x1 < 30.0 || l.bbox_part_mm.x0 > 70.0);
    }

    #[test]
    fn orientation_mark_is_placed_clear() {
        let (outline, holes) = lamella();
        let mark = |anchor: Point, max_height_mm: f64, min_height_mm: f64| {
            Placer::new(&outline, &holes, CLEARANCE)
                .orientation_mark(anchor, &LabelSize::new(max_height_mm, min_height_mm))
                .map(|l| l.strokes_part_mm)
        };
        let placed = mark(p(100.0, 12.0), 12.0, 4.0).expect("fits under the notch or beside it");
        check(placed.clone());
        assert_eq!(mark(p(100.0, 25.0), 80.0, 60.0), None);
        // With a label: both fit, apart.
        let mut placer = Placer::new(&outline, &holes, CLEARANCE);
        let size = LabelSize::new(8.0, 3.0);
        let l = placer.text("A05-1", p(50.0, 25.0), &size).expect("label");
        let o = placer.orientation_mark(p(50.0, 25.0), &size).expect("mark");
        assert!(l.bbox_part_mm.intersect(o.bbox_part_mm).area() == 0.0);
        check(
            l.strokes_part_mm
                .into_iter()
                .chain(o.strokes_part_mm)
                .collect(),
        );
    }

    #[test]
    fn heights_step_by_tenths_and_end_at_the_minimum() {
        let h = heights(10.0, 3.5);
        assert_eq!(h.len(), 8);
        assert_eq!(h[0], 10.0);
        assert!((h[6] - 4.0).abs() < 1e-12);
        assert_eq!(h[7], 3.5);
        assert_eq!(heights(5.0, 5.0), vec![5.0]);
        let h = heights(10.0, 4.0);
        assert_eq!(h.len(), 7);
        assert!((h[6] - 4.0).abs() < 1e-12);
    }

    #[test]
    fn renders_a_sample_svg() {
        // A proof sheet to look at: the test lamella with a label, node
        // marks at the notches and the hole, and the orientation mark.
        let (outline, holes) = lamella();
        let mut placer = Placer::new(&outline, &holes, CLEARANCE);
        let mut eng = Vec::new();
        let size = LabelSize::new(8.0, 3.0);
        let node = LabelSize {
            max_height_mm: 5.0,
            min_height_mm: 3.0,
            search_mm: 15.0,
        };
        eng.extend(
            placer
                .text("A05-1", p(150.0, 12.0), &size)
                .expect("label")
                .strokes_part_mm,
        );
        for (x, t) in [(100.0, "B12"), (200.0, "B13")] {
            eng.extend(
                placer
                    .text(t, p(x, 12.0), &node)
                    .expect("node mark")
                    .strokes_part_mm,
            );
        }
        eng.extend(
            placer
                .orientation_mark(p(30.0, 25.0), &size)
                .expect("mark")
                .strokes_part_mm,
        );
        check(eng.clone());
        let poly = |pts: &[Point], closed: bool, colour: &str| {
            let mut v: Vec<String> = pts
                .iter()
                .map(|q| format!("{:.3},{:.3}", 5.0 + q.x, 55.0 - q.y))
                .collect();
            if closed {
                v.push(v[0].clone());
            }
            format!("<polyline points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"0.3\"/>\n", v.join(" "))
        };
        let mut svg = String::from(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"310mm\" height=\"60mm\" viewBox=\"0 0 310 60\">\n",
        );
        svg += &poly(&outline, true, "red");
        for h in &holes {
            svg += &poly(h, true, "red");
        }
        for s in &eng {
            svg += &poly(s, false, "black");
        }
        svg += "</svg>\n";
        let dir = std::env::temp_dir().join(format!("lamella-label-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        std::fs::write(dir.join("label.svg"), svg).expect("write svg");
    }
}
