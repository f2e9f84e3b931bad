//! Named invariant checks on parts, for tests and `debug_assert!`s
//! standing on the plane predicates of
//! [`crate::geom::plane`].
//!
//! Each check returns `Ok(())` or an `Err` whose message names the part, the
//! rule broken and where (edge indices and coordinates, mm), so a builder
//! can say `debug_assert_eq!(check_part(&part, clearance_mm), Ok(()))` and a
//! failure reads as the reason.

use kurbo::Point;

use super::part::{FeatureKind, Part, ROUND_HOLE_MM};
use crate::geom::plane::{
    on_boundary, on_segment, point_in_polygon, segment_distance, segments_intersect,
    signed_area_mm2,
};

// ---------------------------------------------------------------------------
// Edge sets

/// One edge of one ring: ring index (0 the outline, k + 1 hole k), edge
/// index in the ring, its ends and the ring's length.
#[derive(Clone, Copy)]
struct Edge {
    ring: usize,
    index: usize,
    ring_len: usize,
    a: Point,
    b: Point,
}

impl Edge {
    fn x_range(&self) -> (f64, f64) {
        (self.a.x.min(self.b.x), self.a.x.max(self.b.x))
    }

    fn y_range(&self) -> (f64, f64) {
        (self.a.y.min(self.b.y), self.a.y.max(self.b.y))
    }

    /// Whether `other` is the next or previous edge of the same ring.
    fn adjacent(&self, other: &Edge) -> bool {
        self.ring == other.ring
            && ((self.index + 1) % self.ring_len == other.index
                || (other.index + 1) % other.ring_len == self.index)
    }
}

fn ring_edges(ring: usize, poly: &[Point]) -> impl Iterator<Item = Edge> + '_ {
    let n = poly.len();
    (0..n).map(move |i| Edge {
        ring,
        index: i,
        ring_len: n,
        a: poly[i],
        b: poly[(i + 1) % n],
    })
}

/// Whether two edges meet where they must not. Adjacent edges of a ring
/// share their common vertex and nothing else: they conflict when one
/// folds back over the other (the far end of one lies on the other). Any
/// other two edges conflict when they share any point.
fn conflict(e: &Edge, f: &Edge) -> bool {
    if e.adjacent(f) {
        if e.ring_len < 3 {
            return true;
        }
        // Order them so e.b is f.a (in a triangle both orders hold; a
        // fold-back shows in either).
        let (e, f) = if (e.index + 1) % e.ring_len == f.index {
            (e, f)
        } else {
            (f, e)
        };
        return on_segment(f.b, e.a, e.b) || on_segment(e.a, f.a, f.b);
    }
    segments_intersect(e.a, e.b, f.a, f.b)
}

/// The first pair of edges (by the sweep's order) that conflict, among the
/// pairs `consider` accepts (by ring). Edges are sorted by their lowest x and
/// each is tested against the following ones whose x range starts before it
/// ends, after a y-range test: near-linear for outlines of parts, quadratic
/// only when many edges span the same x.
fn first_conflict(
    edges: &mut [Edge],
    consider: impl Fn(usize, usize) -> bool,
) -> Option<(Edge, Edge)> {
    edges.sort_by(|e, f| e.x_range().0.total_cmp(&f.x_range().0));
    for (i, e) in edges.iter().enumerate() {
        let (_, ex1) = e.x_range();
        let (ey0, ey1) = e.y_range();
        for f in &edges[i + 1..] {
            if f.x_range().0 > ex1 {
                break;
            }
            let (fy0, fy1) = f.y_range();
            if fy0 > ey1 || fy1 < ey0 || !consider(e.ring, f.ring) {
                continue;
            }
            if conflict(e, f) {
                return Some((*e, *f));
            }
        }
    }
    None
}

fn ring_name(ring: usize) -> String {
    if ring == 0 {
        "outline".to_string()
    } else {
        format!("hole {}", ring - 1)
    }
}

fn describe(e: &Edge) -> String {
    format!(
        "{} edge {} ({:.4}, {:.4})–({:.4}, {:.4})",
        ring_name(e.ring),
        e.index,
        e.a.x,
        e.a.y,
        e.b.x,
        e.b.y
    )
}

/// A ring's own rules: at least 3 points, finite, no two consecutive ones
/// equal (the last and the first included).
fn ring_points_ok(part: &Part, ring: usize, poly: &[Point]) -> Result<(), String> {
    let name = ring_name(ring);
    if poly.len() < 3 {
        return Err(format!(
            "part {}: {name} has {} points (< 3)",
            part.id,
            poly.len()
        ));
    }
    let n = poly.len();
    for (i, p) in poly.iter().enumerate() {
        if !(p.x.is_finite() && p.y.is_finite()) {
            return Err(format!("part {}: {name} point {i} is not finite", part.id));
        }
        let q = poly[(i + 1) % n];
        if *p == q {
            return Err(format!(
                "part {}: {name} points {i} and {} repeat ({:.4}, {:.4})",
                part.id,
                (i + 1) % n,
                p.x,
                p.y
            ));
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// Checks

/// The outline is a closed simple counter-clockwise polygon: at least 3
/// points, finite, no two consecutive points equal (nor the last and the
/// first: the closing point is not repeated), no two non-adjacent edges that
/// cross or touch, no edge folding back over its neighbour, positive signed
/// area.
pub fn outline_is_closed_simple_ccw(part: &Part) -> Result<(), String> {
    let outline = &part.outline_part_mm;
    ring_points_ok(part, 0, outline)?;
    let mut edges: Vec<Edge> = ring_edges(0, outline).collect();
    if let Some((e, f)) = first_conflict(&mut edges, |_, _| true) {
        return Err(format!(
            "part {}: outline is not simple: {} meets {}",
            part.id,
            describe(&e),
            describe(&f)
        ));
    }
    let area = signed_area_mm2(outline);
    if area <= 0.0 {
        return Err(format!(
            "part {}: outline is not counter-clockwise (signed area {area:.4} mm²)",
            part.id
        ));
    }
    Ok(())
}

/// Every hole (the round ones as the polygons the cutter's tolerance
/// allows, [`Part::hole_polygons`]) is a closed simple clockwise polygon
/// (at least 3 points, no repeated consecutive points, no self-contact,
/// negative signed area), every hole vertex lies strictly inside the
/// outline, no hole edge meets the outline or another hole, and no hole
/// lies inside another. Assumes the outline itself is simple
/// ([`outline_is_closed_simple_ccw`]).
pub fn holes_are_simple_cw_inside(part: &Part) -> Result<(), String> {
    holes_ok(part, &part.hole_polygons())
}

/// [`holes_are_simple_cw_inside`] with the part's hole polygons given.
fn holes_ok(part: &Part, holes: &[Vec<Point>]) -> Result<(), String> {
    let outline = &part.outline_part_mm;
    for (k, hole) in holes.iter().enumerate() {
        ring_points_ok(part, k + 1, hole)?;
        let area = signed_area_mm2(hole);
        if area >= 0.0 {
            return Err(format!(
                "part {}: hole {k} is not clockwise (signed area {area:.4} mm²)",
                part.id
            ));
        }
        for (i, &p) in hole.iter().enumerate() {
            if !point_in_polygon(p, outline) || on_boundary(p, outline) {
                return Err(format!(
                    "part {}: hole {k} point {i} ({:.4}, {:.4}) is not strictly inside the outline",
                    part.id, p.x, p.y
                ));
            }
        }
    }
    let mut edges: Vec<Edge> = holes
        .iter()
        .enumerate()
        .flat_map(|(k, h)| ring_edges(k + 1, h))
        .chain(ring_edges(0, outline))
        .collect();
    // Every pair but outline × outline (that is the outline's own check).
    if let Some((e, f)) = first_conflict(&mut edges, |r, s| r != 0 || s != 0) {
        let what = if e.ring == f.ring {
            "is not simple"
        } else {
            "crosses"
        };
        return Err(format!(
            "part {}: {} {what}: {} meets {}",
            part.id,
            ring_name(e.ring.max(f.ring)),
            describe(&e),
            describe(&f)
        ));
    }
    // No edges meet, so a hole is inside another exactly when its first
    // vertex is.
    for (k, hole) in holes.iter().enumerate() {
        for (j, other) in holes.iter().enumerate() {
            if j != k && point_in_polygon(hole[0], other) {
                return Err(format!("part {}: hole {k} lies inside hole {j}", part.id));
            }
        }
    }
    Ok(())
}

/// Every engraving polyline has at least one point, every vertex is finite,
/// inside the outline and outside every hole, and every segment (a
/// one-point polyline: its point) keeps at least `clearance_mm` from every
/// outline and hole edge (segment-to-segment distance; the round holes as
/// [`Part::hole_polygons`]) and crosses none. Assumes the outline and holes
/// pass their own checks.
pub fn engraving_inside_and_clear(part: &Part, clearance_mm: f64) -> Result<(), String> {
    strokes_clear(
        part,
        &part.hole_polygons(),
        &part.engraving_strokes(),
        clearance_mm,
    )
}

/// [`engraving_inside_and_clear`] for the open polylines `strokes` (part
/// frame, mm) on `part`.
pub fn strokes_inside_and_clear(
    part: &Part,
    strokes: &[Vec<Point>],
    clearance_mm: f64,
) -> Result<(), String> {
    strokes_clear(part, &part.hole_polygons(), strokes, clearance_mm)
}

/// [`strokes_inside_and_clear`] with the part's hole polygons given.
fn strokes_clear(
    part: &Part,
    holes: &[Vec<Point>],
    strokes: &[Vec<Point>],
    clearance_mm: f64,
) -> Result<(), String> {
    let cuts: Vec<Edge> = ring_edges(0, &part.outline_part_mm)
        .chain(
            holes
                .iter()
                .enumerate()
                .flat_map(|(k, h)| ring_edges(k + 1, h)),
        )
        .collect();
    for (s, line) in strokes.iter().enumerate() {
        if line.is_empty() {
            return Err(format!("part {}: engraving {s} has no points", part.id));
        }
        for (i, p) in line.iter().enumerate() {
            let at = format!("engraving {s} point {i} ({:.4}, {:.4})", p.x, p.y);
            if !(p.x.is_finite() && p.y.is_finite()) {
                return Err(format!("part {}: {at} is not finite", part.id));
            }
            if !point_in_polygon(*p, &part.outline_part_mm) {
                return Err(format!("part {}: {at} is outside the outline", part.id));
            }
            if let Some(k) = holes.iter().position(|h| point_in_polygon(*p, h)) {
                return Err(format!("part {}: {at} is inside hole {k}", part.id));
            }
        }
        let segments: Vec<(Point, Point)> = if line.len() == 1 {
            vec![(line[0], line[0])]
        } else {
            line.windows(2).map(|w| (w[0], w[1])).collect()
        };
        for (i, &(a, b)) in segments.iter().enumerate() {
            let (x0, x1) = (a.x.min(b.x) - clearance_mm, a.x.max(b.x) + clearance_mm);
            let (y0, y1) = (a.y.min(b.y) - clearance_mm, a.y.max(b.y) + clearance_mm);
            for e in &cuts {
                let (ex0, ex1) = e.x_range();
                let (ey0, ey1) = e.y_range();
                if ex0 > x1 || ex1 < x0 || ey0 > y1 || ey1 < y0 {
                    continue;
                }
                let d = segment_distance(a, b, e.a, e.b);
                if d == 0.0 || d < clearance_mm {
                    return Err(format!(
                        "part {}: engraving {s} segment {i} ({:.4}, {:.4})–({:.4}, {:.4}) is {d:.4} mm from {} (clearance {clearance_mm} mm)",
                        part.id,
                        a.x,
                        a.y,
                        b.x,
                        b.y,
                        describe(e)
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Every `hole` feature is a round hole: its centre finite and its
/// diameter positive and finite, so that its circle is a hole of the part
/// ([`Part::round_holes`]; checked as such by
/// [`holes_are_simple_cw_inside`] and [`engraving_inside_and_clear`]), and
/// no other hole polygon lies on its circle (within [`ROUND_HOLE_MM`]: the
/// same hole cut twice). plan.json writes round holes as their features
/// only, and the cutting files cut them as circles.
pub fn hole_features_are_holes(part: &Part) -> Result<(), String> {
    for (i, f) in part.features.iter().enumerate() {
        if f.kind != FeatureKind::Hole {
            continue;
        }
        let (c, r) = (f.center_part_mm, 0.5 * f.width_mm);
        if !(c.x.is_finite() && c.y.is_finite() && r.is_finite() && r > 0.0) {
            return Err(format!(
                "part {}: hole feature {i} at ({:.4}, {:.4}), {:.4} mm, is not a circle",
                part.id, c.x, c.y, f.width_mm
            ));
        }
        if let Some(k) = part
            .holes_part_mm
            .iter()
            .position(|h| h.iter().all(|q| (q.distance(c) - r).abs() <= ROUND_HOLE_MM))
        {
            return Err(format!(
                "part {}: hole feature {i} at ({:.4}, {:.4}), {:.4} mm, is also the polygon hole {k}",
                part.id, c.x, c.y, f.width_mm
            ));
        }
    }
    Ok(())
}

/// All four checks: [`outline_is_closed_simple_ccw`],
/// [`holes_are_simple_cw_inside`], [`hole_features_are_holes`],
/// [`engraving_inside_and_clear`] with `clearance_mm` (kerf and part
/// spacing, mm); the first failure. The round holes' polygons are built
/// once for both checks that need them.
pub fn check_part(part: &Part, clearance_mm: f64) -> Result<(), String> {
    outline_is_closed_simple_ccw(part)?;
    hole_features_are_holes(part)?;
    let holes = part.hole_polygons();
    holes_ok(part, &holes)?;
    strokes_clear(part, &holes, &part.engraving_strokes(), clearance_mm)
}

#[cfg(test)]
mod tests {
    use super::super::part::{circle_cw, PartKind, ARC_TOLERANCE_MM};
    use super::*;
    use crate::geom::plane::tests::notched;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    fn part(outline: Vec<Point>, holes: Vec<Vec<Point>>) -> Part {
        Part {
            id: "T1".into(),
            kind: PartKind::Lamella,
            strip: None,
            lamella: None,
            count: 1,
            length_mm: 0.0,
            height_mm: 0.0,
            station_start_mm: None,
            outline_part_mm: outline,
            holes_part_mm: holes,
            engraving: Vec::new(),
            features: vec![],
        }
    }

    #[test]
    fn a_good_part_passes() {
        let hole = circle_cw(p(150.0, 25.0), 3.0, ARC_TOLERANCE_MM);
        let engraving = vec![
            vec![p(10.0, 10.0), p(40.0, 10.0), p(40.0, 20.0)],
            vec![p(60.0, 30.0)],
        ];
        let part = part(notched(), vec![hole]);
        assert_eq!(check_part(&part, 0.5), Ok(()));
        assert_eq!(strokes_inside_and_clear(&part, &engraving, 0.5), Ok(()));
    }

    #[test]
    fn outline_faults_are_named() {
        let ok = notched();
        // Clockwise.
        let mut cw = ok.clone();
        cw.reverse();
        let e = outline_is_closed_simple_ccw(&part(cw, vec![])).unwrap_err();
        assert!(e.contains("T1") && e.contains("counter-clockwise"), "{e}");
        // Repeated closing point.
        let mut closed = ok.clone();
        closed.push(ok[0]);
        let e = outline_is_closed_simple_ccw(&part(closed, vec![])).unwrap_err();
        assert!(e.contains("repeat"), "{e}");
        // Too few.
        let e = outline_is_closed_simple_ccw(&part(ok[..2].to_vec(), vec![])).unwrap_err();
        assert!(e.contains("< 3"), "{e}");
        // A bow tie.
        let bow = vec![p(0.0, 0.0), p(10.0, 10.0), p(10.0, 0.0), p(0.0, 10.0)];
        let e = outline_is_closed_simple_ccw(&part(bow, vec![])).unwrap_err();
        assert!(e.contains("not simple"), "{e}");
        // A notch so deep it touches the bottom edge (touching, not crossing).
        let mut deep = ok.clone();
        deep[8] = p(101.5, 0.0);
        deep[9] = p(98.5, 0.0);
        let e = outline_is_closed_simple_ccw(&part(deep, vec![])).unwrap_err();
        assert!(e.contains("not simple"), "{e}");
        // A spike: an edge folding back over its neighbour.
        let spike = vec![
            p(0.0, 0.0),
            p(10.0, 0.0),
            p(10.0, 10.0),
            p(10.0, 5.0),
            p(0.0, 10.0),
        ];
        let e = outline_is_closed_simple_ccw(&part(spike, vec![])).unwrap_err();
        assert!(e.contains("not simple"), "{e}");
        // A vertex touching a non-adjacent edge.
        let pinch = vec![
            p(0.0, 0.0),
            p(10.0, 0.0),
            p(10.0, 10.0),
            p(5.0, 0.0),
            p(0.0, 10.0),
        ];
        assert!(outline_is_closed_simple_ccw(&part(pinch, vec![])).is_err());
        // A collinear middle point is fine.
        let mid = vec![
            p(0.0, 0.0),
            p(5.0, 0.0),
            p(10.0, 0.0),
            p(10.0, 10.0),
            p(0.0, 10.0),
        ];
        assert_eq!(outline_is_closed_simple_ccw(&part(mid, vec![])), Ok(()));
        // A triangle, and a degenerate (flat) one.
        let tri = vec![p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0)];
        assert_eq!(outline_is_closed_simple_ccw(&part(tri, vec![])), Ok(()));
        let flat = vec![p(0.0, 0.0), p(1.0, 0.0), p(2.0, 0.0)];
        assert!(outline_is_closed_simple_ccw(&part(flat, vec![])).is_err());
    }

    #[test]
    fn hole_faults_are_named() {
        let outline = notched();
        let c = |x: f64, y: f64, r: f64| circle_cw(p(x, y), r, ARC_TOLERANCE_MM);
        let check =
            |holes: Vec<Vec<Point>>| holes_are_simple_cw_inside(&part(outline.clone(), holes));
        assert_eq!(check(vec![c(150.0, 25.0, 3.0), c(50.0, 25.0, 3.0)]), Ok(()));
        // Counter-clockwise.
        let mut ccw = c(150.0, 25.0, 3.0);
        ccw.reverse();
        assert!(check(vec![ccw]).unwrap_err().contains("not clockwise"));
        // Outside the part, and inside a notch.
        assert!(check(vec![c(350.0, 25.0, 3.0)])
            .unwrap_err()
            .contains("strictly inside"));
        assert!(check(vec![c(100.0, 40.0, 1.0)])
            .unwrap_err()
            .contains("strictly inside"));
        // Crossing the bottom edge (some vertices still inside).
        let e = check(vec![c(150.0, 2.0, 3.0)]).unwrap_err();
        assert!(
            e.contains("strictly inside") || e.contains("crosses"),
            "{e}"
        );
        // A square hole whose vertices are all inside but whose edge crosses
        // a notch.
        // (clockwise: along the top to the right, then down)
        let sq = vec![p(95.0, 30.0), p(105.0, 30.0), p(105.0, 20.0), p(95.0, 20.0)];
        assert!(signed_area_mm2(&sq) < 0.0);
        let outline2 = vec![
            p(0.0, 0.0),
            p(300.0, 0.0),
            p(300.0, 50.0),
            p(101.0, 50.0),
            p(101.0, 25.0),
            p(99.0, 25.0),
            p(99.0, 50.0),
            p(0.0, 50.0),
        ];
        let e = holes_are_simple_cw_inside(&part(outline2, vec![sq])).unwrap_err();
        assert!(e.contains("crosses"), "{e}");
        // Two overlapping holes, two touching, one inside another.
        let e = check(vec![c(150.0, 25.0, 3.0), c(154.0, 25.0, 3.0)]).unwrap_err();
        assert!(e.contains("crosses"), "{e}");
        let s1 = vec![p(10.0, 10.0), p(10.0, 20.0), p(20.0, 20.0), p(20.0, 10.0)];
        let s2 = vec![p(20.0, 10.0), p(20.0, 20.0), p(30.0, 20.0), p(30.0, 10.0)];
        assert!(check(vec![s1.clone(), s2]).unwrap_err().contains("crosses"));
        let e = check(vec![c(150.0, 25.0, 8.0), c(150.0, 25.0, 3.0)]).unwrap_err();
        assert!(e.contains("inside hole 0"), "{e}");
        // A self-intersecting hole (a bow tie with negative area overall).
        let bow = vec![p(10.0, 10.0), p(20.0, 20.0), p(22.0, 10.0), p(10.0, 20.0)];
        let e = check(vec![bow]).unwrap_err();
        assert!(
            e.contains("not simple") || e.contains("not clockwise"),
            "{e}"
        );
    }

    #[test]
    fn engraving_faults_are_named() {
        let hole = circle_cw(p(150.0, 25.0), 3.0, ARC_TOLERANCE_MM);
        let check = |eng: Vec<Vec<Point>>, c: f64| {
            strokes_inside_and_clear(&part(notched(), vec![hole.clone()]), &eng, c)
        };
        assert_eq!(check(vec![vec![p(10.0, 1.0), p(90.0, 1.0)]], 0.9), Ok(()));
        // Too close to the bottom edge.
        let e = check(vec![vec![p(10.0, 1.0), p(90.0, 1.0)]], 1.1).unwrap_err();
        assert!(
            e.contains("engraving 0 segment 0") && e.contains("outline edge 0"),
            "{e}"
        );
        // Both ends inside, the segment runs under... through a notch.
        let e = check(vec![vec![p(90.0, 30.0), p(110.0, 30.0)]], 0.0).unwrap_err();
        assert!(e.contains("0.0000 mm"), "{e}");
        // A vertex in the notch, outside the outline.
        let e = check(vec![vec![p(100.0, 30.0)]], 0.0).unwrap_err();
        assert!(e.contains("outside the outline"), "{e}");
        // A vertex in the hole; a segment passing near it.
        let e = check(vec![vec![p(150.0, 25.0), p(160.0, 25.0)]], 0.0).unwrap_err();
        assert!(e.contains("inside hole 0"), "{e}");
        let e = check(vec![vec![p(140.0, 28.5), p(160.0, 28.5)]], 1.0).unwrap_err();
        assert!(e.contains("hole 0 edge"), "{e}");
        assert_eq!(
            check(vec![vec![p(140.0, 29.5), p(160.0, 29.5)]], 0.45),
            Ok(())
        );
        // Empty polyline.
        assert!(check(vec![vec![]], 0.0).unwrap_err().contains("no points"));
    }

    /// A `hole` feature: a round hole at (x, y) of radius r.
    fn round(x: f64, y: f64, r: f64) -> super::super::part::Feature {
        super::super::part::Feature {
            kind: FeatureKind::Hole,
            hole_use: Some(super::super::part::HoleUse::Node),
            node: None,
            crossing: None,
            center_part_mm: p(x, y),
            width_mm: 2.0 * r,
            depth_mm: 0.0,
            edge: None,
            angle_range_deg: None,
            station_mm: None,
        }
    }

    /// The notched part with round holes held only as their features.
    fn with_round(holes: &[(f64, f64, f64)]) -> Part {
        let mut part = part(notched(), vec![]);
        part.features = holes.iter().map(|&(x, y, r)| round(x, y, r)).collect();
        part
    }

    #[test]
    fn round_holes_are_checked_as_their_circles() {
        // The polygons built on demand are the ones the parts used to hold.
        let ok = with_round(&[(150.0, 25.0, 3.0), (50.0, 25.0, 3.0)]);
        assert!(ok.holes_part_mm.is_empty());
        assert_eq!(
            ok.hole_polygons(),
            [
                circle_cw(p(150.0, 25.0), 3.0, ARC_TOLERANCE_MM),
                circle_cw(p(50.0, 25.0), 3.0, ARC_TOLERANCE_MM)
            ]
        );
        assert_eq!(check_part(&ok, 0.5), Ok(()));
        // Two features on one circle are one hole (an edge strip's shared
        // node hole), not two crossing ones.
        let shared = with_round(&[(150.0, 25.0, 3.0), (150.0, 25.0, 3.0)]);
        assert_eq!(shared.round_holes().len(), 1);
        assert_eq!(check_part(&shared, 0.5), Ok(()));
        // A round hole crossing the bottom edge, inside a notch, outside.
        for bad in [(150.0, 2.0, 3.0), (100.0, 40.0, 1.0), (350.0, 25.0, 3.0)] {
            let e = check_part(&with_round(&[bad]), 0.5).unwrap_err();
            assert!(
                e.contains("strictly inside") || e.contains("crosses"),
                "{bad:?}: {e}"
            );
        }
        // Another round hole too close: overlapping, overlapping by 0.05 mm
        // (more than the polygons' 0.01 mm sagitta), or inside it.
        let e =
            check_part(&with_round(&[(150.0, 25.0, 3.0), (154.0, 25.0, 3.0)]), 0.5).unwrap_err();
        assert!(e.contains("crosses"), "{e}");
        let e =
            check_part(&with_round(&[(150.0, 25.0, 3.0), (155.95, 25.0, 3.0)]), 0.5).unwrap_err();
        assert!(e.contains("crosses"), "{e}");
        let e =
            check_part(&with_round(&[(150.0, 25.0, 8.0), (150.0, 25.0, 3.0)]), 0.5).unwrap_err();
        assert!(e.contains("inside hole 0"), "{e}");
        // A polygon hole too close to a round one, and one that is the
        // round hole over again.
        let mut near = with_round(&[(150.0, 25.0, 3.0)]);
        near.holes_part_mm = vec![vec![
            p(152.0, 30.0),
            p(160.0, 30.0),
            p(160.0, 20.0),
            p(152.0, 20.0),
        ]];
        let e = check_part(&near, 0.5).unwrap_err();
        assert!(e.contains("crosses"), "{e}");
        let mut twice = with_round(&[(150.0, 25.0, 3.0)]);
        twice.holes_part_mm = vec![circle_cw(p(150.0, 25.0), 3.0, ARC_TOLERANCE_MM)];
        let e = check_part(&twice, 0.5).unwrap_err();
        assert!(e.contains("also the polygon hole 0"), "{e}");
        // A feature that is no circle.
        let e = check_part(&with_round(&[(150.0, 25.0, 0.0)]), 0.5).unwrap_err();
        assert!(e.contains("is not a circle"), "{e}");
        let e = check_part(&with_round(&[(f64::NAN, 25.0, 3.0)]), 0.5).unwrap_err();
        assert!(e.contains("is not a circle"), "{e}");
    }

    #[test]
    fn engraving_too_close_to_a_round_hole_is_caught() {
        let hole = with_round(&[(150.0, 25.0, 3.0)]);
        let check = |eng: Vec<Vec<Point>>, c: f64| strokes_inside_and_clear(&hole, &eng, c);
        // Inside the hole; crossing it; 0.5 mm above it (clearance 1).
        let e = check(vec![vec![p(150.0, 25.0)]], 0.0).unwrap_err();
        assert!(e.contains("inside hole 0"), "{e}");
        let e = check(vec![vec![p(140.0, 25.5), p(160.0, 25.5)]], 0.0).unwrap_err();
        assert!(e.contains("hole 0 edge") && e.contains("0.0000 mm"), "{e}");
        let e = check(vec![vec![p(140.0, 28.5), p(160.0, 28.5)]], 1.0).unwrap_err();
        assert!(e.contains("hole 0 edge"), "{e}");
        // Diagonally off the hole: 3.6 mm from its centre, 0.6 mm from
        // the circle.
        let d = 3.6 / 2f64.sqrt();
        let e = check(vec![vec![p(150.0 + d, 25.0 + d)]], 0.7).unwrap_err();
        assert!(e.contains("hole 0 edge"), "{e}");
        assert_eq!(check(vec![vec![p(150.0 + d, 25.0 + d)]], 0.5), Ok(()));
        assert_eq!(
            check(vec![vec![p(140.0, 29.5), p(160.0, 29.5)]], 0.45),
            Ok(())
        );
        // The placed engraving is checked the same way.
        let mut placed = with_round(&[(150.0, 25.0, 3.0)]);
        placed.engraving = vec![super::super::part::Engraving {
            what: super::super::part::Engraved::OrientationMark,
            at_part_mm: p(148.0, 28.2),
            height_mm: 1.0,
        }];
        let e = engraving_inside_and_clear(&placed, 0.5).unwrap_err();
        assert!(e.contains("hole 0 edge"), "{e}");
        let e = check_part(&placed, 0.5).unwrap_err();
        assert!(e.contains("hole 0 edge"), "{e}");
        placed.engraving[0].at_part_mm = p(148.0, 29.0);
        assert_eq!(check_part(&placed, 0.5), Ok(()));
    }

    /// A star-shaped outline of `n` vertices (radius alternating), CCW.
    fn star(n: usize) -> Vec<Point> {
        (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                let r = if k % 2 == 0 { 100.0 } else { 90.0 };
                p(r * a.cos(), r * a.sin())
            })
            .collect()
    }

    /// A lamella-like comb: `slots` notches from the top, CCW.
    fn comb(slots: usize) -> Vec<Point> {
        let mut pts = vec![p(0.0, 0.0), p(100.0 * (slots + 1) as f64, 0.0)];
        for k in (1..=slots).rev() {
            let x = 100.0 * k as f64;
            pts.extend([
                p(x + 1.5, 50.0),
                p(x + 1.5, 24.0),
                p(x - 1.5, 24.0),
                p(x - 1.5, 50.0),
            ]);
        }
        pts.insert(2, p(100.0 * (slots + 1) as f64, 50.0));
        pts.push(p(0.0, 50.0));
        pts
    }

    #[test]
    fn large_outlines_are_fast() {
        for (name, outline) in [("star", star(2000)), ("comb", comb(500))] {
            assert!(outline.len() >= 2000);
            let part = part(outline, vec![]);
            let t = std::time::Instant::now();
            assert_eq!(outline_is_closed_simple_ccw(&part), Ok(()), "{name}");
            let dt = t.elapsed();
            // Under 1 ms here (2,000 edges); the bound leaves room for a
            // loaded machine.
            assert!(dt.as_millis() < 50, "{name}: {dt:?}");
        }
        // And the sweep still finds a fault near the end.
        let mut bad = comb(500);
        let n = bad.len();
        bad[n - 3].y = -1.0; // the last notch cuts through the bottom edge
        assert!(outline_is_closed_simple_ccw(&part(bad, vec![])).is_err());
    }
}
