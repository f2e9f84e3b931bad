//! Plane predicates and measures on points, segments, rectangles and
//! polygons (mm, in whatever 2D frame the caller works in): orientation,
//! segment intersection and distance, point in polygon, segment against
//! rectangle, bounding boxes, signed areas, the distance between polygons,
//! and polygons simplified or offset.
//!
//! They are evaluated in plain `f64` with exact zero tests (no tolerance):
//! two segments that touch at a point or overlap along a line intersect; a
//! polygon is a closed ring of points, the last joined to the first.

use kurbo::{Point, Rect, Vec2};

/// Twice the signed area of the triangle a, b, c: positive when c lies to
/// the left of a→b (counter-clockwise), 0 when collinear, mm².
pub fn orient(a: Point, b: Point, c: Point) -> f64 {
    (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)
}

/// Whether `p`, known to be collinear with a–b, lies on the closed segment.
pub fn within_box(a: Point, b: Point, p: Point) -> bool {
    p.x >= a.x.min(b.x) && p.x <= a.x.max(b.x) && p.y >= a.y.min(b.y) && p.y <= a.y.max(b.y)
}

/// How orientations are evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Arithmetic {
    /// Plain `f64` ([`orient`]): fast; for nearly collinear points the sign
    /// may be wrong or 0.
    Float,
    /// The exact sign (adaptive precision, `robust::orient2d`): 0 exactly
    /// when the points are collinear.
    Exact,
}

impl Arithmetic {
    /// Twice the signed area of the triangle a, b, c, positive when c lies
    /// to the left of a→b (see [`orient`]), mm².
    #[inline]
    pub fn orient(self, a: Point, b: Point, c: Point) -> f64 {
        match self {
            Arithmetic::Float => orient(a, b, c),
            Arithmetic::Exact => robust::orient2d(
                robust::Coord { x: a.x, y: a.y },
                robust::Coord { x: b.x, y: b.y },
                robust::Coord { x: c.x, y: c.y },
            ),
        }
    }

    /// Whether the closed segments a–b and c–d share at least one point:
    /// proper crossings, an endpoint touching the other segment, and
    /// collinear overlaps (also of a single point) all count. A degenerate
    /// segment (a = b) is the point a.
    #[inline]
    pub fn segments_intersect(self, a: Point, b: Point, c: Point, d: Point) -> bool {
        let d1 = self.orient(c, d, a);
        let d2 = self.orient(c, d, b);
        let d3 = self.orient(a, b, c);
        let d4 = self.orient(a, b, d);
        if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
            && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
        {
            return true;
        }
        (d1 == 0.0 && within_box(c, d, a))
            || (d2 == 0.0 && within_box(c, d, b))
            || (d3 == 0.0 && within_box(a, b, c))
            || (d4 == 0.0 && within_box(a, b, d))
    }

    /// Whether c and d lie on the line through a and b and c→d runs against
    /// a→b: of two consecutive edges a→b, b→c of a polyline, whether the
    /// second folds back over the first (`collinear_opposite(a, b, b, c)`).
    #[inline]
    pub fn collinear_opposite(self, a: Point, b: Point, c: Point, d: Point) -> bool {
        self.orient(a, b, c) == 0.0 && self.orient(a, b, d) == 0.0 && (b - a).dot(d - c) < 0.0
    }
}

/// [`Arithmetic::segments_intersect`] in plain `f64`.
pub fn segments_intersect(a: Point, b: Point, c: Point, d: Point) -> bool {
    Arithmetic::Float.segments_intersect(a, b, c, d)
}

/// Whether `p` lies on the closed segment a–b (in plain `f64`).
pub fn on_segment(p: Point, a: Point, b: Point) -> bool {
    orient(a, b, p) == 0.0 && within_box(a, b, p)
}

/// Distance from `p` to the closed segment a–b, mm (to a when a = b).
pub fn point_segment_distance(p: Point, a: Point, b: Point) -> f64 {
    let ab = b - a;
    let len2 = ab.hypot2();
    if len2 == 0.0 {
        return p.distance(a);
    }
    let t = ((p - a).dot(ab) / len2).clamp(0.0, 1.0);
    p.distance(a + ab * t)
}

/// Distance between the closed segments a–b and c–d, mm: 0 when they
/// intersect, else the smallest of the four endpoint-to-segment distances.
pub fn segment_distance(a: Point, b: Point, c: Point, d: Point) -> f64 {
    if segments_intersect(a, b, c, d) {
        return 0.0;
    }
    point_segment_distance(a, c, d)
        .min(point_segment_distance(b, c, d))
        .min(point_segment_distance(c, a, b))
        .min(point_segment_distance(d, a, b))
}

/// Whether `p` lies inside the closed polygon `poly` (either orientation),
/// by the crossing rule. Points on the boundary may go either way: callers
/// that care test the boundary apart ([`on_boundary`]).
pub fn point_in_polygon(p: Point, poly: &[Point]) -> bool {
    let n = poly.len();
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if p.x < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// Signed area of a closed polyline (positive counter-clockwise), mm².
pub fn signed_area_mm2(poly: &[Point]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            a.x * b.y - b.x * a.y
        })
        .sum::<f64>()
        * 0.5
}

/// Whether `p` lies on an edge of the closed polygon `poly`.
pub fn on_boundary(p: Point, poly: &[Point]) -> bool {
    let n = poly.len();
    (0..n).any(|i| segments_intersect(p, p, poly[i], poly[(i + 1) % n]))
}

/// The bounding box of points (for none, the empty box from +∞ to −∞).
pub fn bounds(points: &[Point]) -> Rect {
    let (x0, y0, x1, y1) = points.iter().fold(
        (
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), q| (a.min(q.x), b.min(q.y), c.max(q.x), d.max(q.y)),
    );
    Rect::new(x0, y0, x1, y1)
}

/// Distance between two closed polygons (their filled areas), mm: 0 where
/// they touch, cross or one holds the other; ∞ when either has no point.
/// Segment pairs whose boxes are farther apart than `limit` are skipped, so
/// a result at or above `limit` only says "at least `limit`". A sweep: b's
/// segments near a's box sorted by their lowest x, each segment of a tested
/// against those whose x range can reach it.
pub fn polygon_distance(a: &[Point], b: &[Point], limit: f64) -> f64 {
    if a.is_empty() || b.is_empty() {
        return f64::INFINITY;
    }
    let (na, nb) = (a.len(), b.len());
    let ba = bounds(a);
    // b's segments near a's box, by their lowest x.
    let mut segs: Vec<(f64, usize)> = Vec::new();
    let mut span = 0.0f64;
    for j in 0..nb {
        let (r, s) = (b[j], b[(j + 1) % nb]);
        if r.x.max(s.x) < ba.x0 - limit
            || r.x.min(s.x) > ba.x1 + limit
            || r.y.max(s.y) < ba.y0 - limit
            || r.y.min(s.y) > ba.y1 + limit
        {
            continue;
        }
        segs.push((r.x.min(s.x), j));
        span = span.max((r.x - s.x).abs());
    }
    segs.sort_by(|p, q| p.0.total_cmp(&q.0).then(p.1.cmp(&q.1)));
    let mut best = f64::INFINITY;
    for i in 0..na {
        let (p, q) = (a[i], a[(i + 1) % na]);
        let (x0, x1) = (p.x.min(q.x) - limit, p.x.max(q.x) + limit);
        let (y0, y1) = (p.y.min(q.y) - limit, p.y.max(q.y) + limit);
        // Segments whose lowest x is in [x0 - span, x1].
        let from = segs.partition_point(|e| e.0 < x0 - span);
        for &(sx, j) in &segs[from..] {
            if sx > x1 {
                break;
            }
            let (r, s) = (b[j], b[(j + 1) % nb]);
            if r.x.max(s.x) < x0 || r.y.max(s.y) < y0 || r.y.min(s.y) > y1 {
                continue;
            }
            best = best.min(segment_distance(p, q, r, s));
            if best == 0.0 {
                return 0.0;
            }
        }
    }
    if point_in_polygon(a[0], b) || point_in_polygon(b[0], a) {
        return 0.0;
    }
    best
}

/// A closed polygon simplified (Douglas–Peucker) to within `tolerance_mm`:
/// split at vertex 0 and the vertex farthest from it, each half kept to its
/// farthest vertex while that lies more than the tolerance off the chord.
/// Polygons of fewer than 8 points are returned as they are.
pub fn simplify_closed(poly: &[Point], tolerance_mm: f64) -> Vec<Point> {
    let n = poly.len();
    if n < 8 {
        return poly.to_vec();
    }
    let far = (1..n)
        .max_by(|&a, &b| {
            poly[a]
                .distance(poly[0])
                .total_cmp(&poly[b].distance(poly[0]))
        })
        .unwrap_or(n / 2);
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[far] = true;
    let mut stack = vec![(0, far), (far, n)];
    while let Some((a, b)) = stack.pop() {
        let (pa, pb) = (poly[a], poly[b % n]);
        let mut worst = (0.0, a);
        for (k, &q) in poly.iter().enumerate().take(b).skip(a + 1) {
            let d = point_segment_distance(q, pa, pb);
            if d > worst.0 {
                worst = (d, k);
            }
        }
        if worst.0 > tolerance_mm {
            keep[worst.1] = true;
            stack.push((a, worst.1));
            stack.push((worst.1, b));
        }
    }
    (0..n).filter(|&k| keep[k]).map(|k| poly[k]).collect()
}

/// A counter-clockwise polygon offset outwards by `d_mm` with miter joins:
/// each vertex moved along the sum of its two edges' outward normals, so
/// that both edges move by `d_mm`; where the edges turn back on each other
/// (the normals nearly opposite), along the incoming edge's normal alone.
/// Exact for right angles and smooth turns; a sharp corner's miter reaches
/// far.
pub fn miter_offset(poly: &[Point], d_mm: f64) -> Vec<Point> {
    let n = poly.len();
    (0..n)
        .map(|i| {
            let (a, b, c) = (poly[(i + n - 1) % n], poly[i], poly[(i + 1) % n]);
            let e1 = (b - a).normalize();
            let e2 = (c - b).normalize();
            // Outward normals of a counter-clockwise polygon: (dy, −dx).
            let n1 = Vec2::new(e1.y, -e1.x);
            let n2 = Vec2::new(e2.y, -e2.x);
            let m = n1 + n2;
            let k = 1.0 + n1.dot(n2);
            if k < 1e-6 {
                b + n1 * d_mm
            } else {
                b + m * (d_mm / k)
            }
        })
        .collect()
}

/// Whether the closed segment a–b meets the closed rectangle `r` (an
/// endpoint inside, or a crossing of its boundary), by Liang–Barsky
/// clipping.
pub fn segment_meets_rect(a: Point, b: Point, r: Rect) -> bool {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.x - r.x0),
        (dx, r.x1 - a.x),
        (-dy, a.y - r.y0),
        (dy, r.y1 - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
            if t0 > t1 {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    /// The square [x, x + s] × [y, y + s], counter-clockwise.
    fn square(x: f64, y: f64, s: f64) -> Vec<Point> {
        vec![p(x, y), p(x + s, y), p(x + s, y + s), p(x, y + s)]
    }

    /// 300 × 50 with two 3 × 26 notches from the top at x = 100 and 200
    /// (counter-clockwise; the parts' tests use it too).
    pub(crate) fn notched() -> Vec<Point> {
        vec![
            p(0.0, 0.0),
            p(300.0, 0.0),
            p(300.0, 50.0),
            p(201.5, 50.0),
            p(201.5, 24.0),
            p(198.5, 24.0),
            p(198.5, 50.0),
            p(101.5, 50.0),
            p(101.5, 24.0),
            p(98.5, 24.0),
            p(98.5, 50.0),
            p(0.0, 50.0),
        ]
    }

    #[test]
    fn intersections_proper_touching_collinear() {
        let (a, b) = (p(0.0, 0.0), p(2.0, 2.0));
        // Proper crossing.
        assert!(segments_intersect(a, b, p(0.0, 2.0), p(2.0, 0.0)));
        // Disjoint, parallel.
        assert!(!segments_intersect(a, b, p(1.0, 0.0), p(3.0, 2.0)));
        // An endpoint touching the other's interior (T).
        assert!(segments_intersect(a, b, p(1.0, 1.0), p(2.0, 0.0)));
        assert!(segments_intersect(p(1.0, 1.0), p(2.0, 0.0), a, b));
        // Sharing an endpoint.
        assert!(segments_intersect(a, b, b, p(3.0, 0.0)));
        // Collinear overlapping, collinear touching at one point, collinear
        // apart.
        assert!(segments_intersect(a, b, p(1.0, 1.0), p(3.0, 3.0)));
        assert!(segments_intersect(a, b, p(2.0, 2.0), p(3.0, 3.0)));
        assert!(!segments_intersect(a, b, p(2.5, 2.5), p(3.0, 3.0)));
        // Collinear, one containing the other.
        assert!(segments_intersect(a, b, p(0.5, 0.5), p(1.0, 1.0)));
        // On the line but beyond the end (the orientation is 0, the box
        // test must reject it).
        assert!(!segments_intersect(a, b, p(3.0, 3.0), p(4.0, 0.0)));
        // Near miss.
        assert!(!segments_intersect(a, b, p(1.0, 1.0 + 1e-9), p(0.0, 5.0)));
        // Degenerate: a point on, and off, a segment.
        assert!(segments_intersect(p(1.0, 1.0), p(1.0, 1.0), a, b));
        assert!(!segments_intersect(p(1.0, 1.5), p(1.0, 1.5), a, b));
        // Axis-parallel, the way outlines are.
        assert!(segments_intersect(
            p(0.0, 0.0),
            p(10.0, 0.0),
            p(5.0, 0.0),
            p(5.0, 5.0)
        ));
        assert!(!segments_intersect(
            p(0.0, 0.0),
            p(10.0, 0.0),
            p(5.0, 1e-12),
            p(5.0, 5.0)
        ));
    }

    #[test]
    fn distances() {
        let (a, b) = (p(0.0, 0.0), p(10.0, 0.0));
        assert_eq!(point_segment_distance(p(5.0, 3.0), a, b), 3.0);
        assert_eq!(point_segment_distance(p(-3.0, 4.0), a, b), 5.0);
        assert_eq!(point_segment_distance(p(13.0, -4.0), a, b), 5.0);
        assert_eq!(point_segment_distance(p(1.0, 1.0), a, a), 2f64.sqrt());
        // Parallel, overlapping in x.
        assert_eq!(segment_distance(a, b, p(2.0, 2.0), p(20.0, 2.0)), 2.0);
        // Collinear, apart.
        assert_eq!(segment_distance(a, b, p(12.0, 0.0), p(20.0, 0.0)), 2.0);
        // Crossing, touching.
        assert_eq!(segment_distance(a, b, p(5.0, -1.0), p(5.0, 1.0)), 0.0);
        assert_eq!(segment_distance(a, b, p(10.0, 0.0), p(10.0, 1.0)), 0.0);
        // Skew: the closest points are an endpoint and an interior point.
        let d = segment_distance(a, b, p(3.0, 1.0), p(6.0, 4.0));
        assert!((d - 1.0).abs() < 1e-15);
        // Symmetric.
        let (c, e) = (p(-1.0, 3.0), p(4.0, 7.0));
        assert_eq!(segment_distance(a, b, c, e), segment_distance(c, e, b, a));
    }

    #[test]
    fn polygon_and_rect_predicates() {
        let outline = notched();
        assert!(point_in_polygon(p(50.0, 25.0), &outline));
        assert!(!point_in_polygon(p(100.0, 40.0), &outline)); // in a notch
        assert!(point_in_polygon(p(100.0, 10.0), &outline)); // under it
        assert!(!point_in_polygon(p(-1.0, 10.0), &outline));
        assert!(on_boundary(p(100.0, 24.0), &outline));
        assert!(!on_boundary(p(100.0, 23.0), &outline));

        let r = Rect::new(0.0, 0.0, 10.0, 5.0);
        assert!(segment_meets_rect(p(2.0, 2.0), p(3.0, 3.0), r)); // inside
        assert!(segment_meets_rect(p(-5.0, 2.0), p(15.0, 2.0), r)); // through
        assert!(segment_meets_rect(p(-5.0, 5.0), p(0.0, 5.0), r)); // touches a corner
        assert!(segment_meets_rect(p(10.0, -1.0), p(10.0, 9.0), r)); // along a side
        assert!(!segment_meets_rect(p(-5.0, 6.0), p(15.0, 6.0), r)); // above
        assert!(!segment_meets_rect(p(-2.0, 4.0), p(4.0, 10.0), r)); // skims the corner
        assert!(!segment_meets_rect(p(11.0, 1.0), p(11.0, 1.0), r)); // a point outside
    }

    #[test]
    fn orientation_is_twice_the_signed_triangle_area() {
        // The right triangle (0, 0), (4, 0), (0, 3) has area 4·3/2 = 6.
        let (a, b) = (p(0.0, 0.0), p(4.0, 0.0));
        assert_eq!(orient(a, b, p(0.0, 3.0)), 12.0); // left of a→b
        assert_eq!(orient(a, b, p(0.0, -3.0)), -12.0); // right of it
        assert_eq!(orient(a, b, p(8.0, 0.0)), 0.0); // on its line
                                                    // Any c at height 3 above the base gives the same area.
        assert_eq!(orient(a, b, p(17.0, 3.0)), 12.0);
    }

    #[test]
    fn points_in_a_triangle_either_way_round() {
        // x/4 + y/3 < 1 inside the triangle (0, 0), (4, 0), (0, 3).
        let ccw = vec![p(0.0, 0.0), p(4.0, 0.0), p(0.0, 3.0)];
        let cw: Vec<Point> = ccw.iter().rev().copied().collect();
        for poly in [&ccw, &cw] {
            assert!(point_in_polygon(p(1.0, 1.0), poly)); // 1/4 + 1/3 < 1
            assert!(!point_in_polygon(p(3.0, 2.0), poly)); // 3/4 + 2/3 > 1
            assert!(!point_in_polygon(p(-1.0, 1.0), poly)); // left of it
            assert!(!point_in_polygon(p(1.0, -0.5), poly)); // below it
            assert!(on_boundary(p(2.0, 1.5), poly)); // 2/4 + 1.5/3 = 1
            assert!(!on_boundary(p(1.0, 1.0), poly));
        }
    }

    #[test]
    fn distance_of_apart_touching_crossing_and_nested_polygons() {
        let a = square(0.0, 0.0, 10.0);
        assert!((polygon_distance(&a, &square(15.0, 0.0, 10.0), 10.0) - 5.0).abs() < 1e-12);
        // Diagonal: corner to corner.
        let d = polygon_distance(&a, &square(13.0, 14.0, 10.0), 10.0);
        assert!((d - 5.0).abs() < 1e-12, "{d}");
        assert_eq!(polygon_distance(&a, &square(10.0, 0.0, 10.0), 10.0), 0.0);
        assert_eq!(polygon_distance(&a, &square(5.0, 5.0, 10.0), 10.0), 0.0);
        assert_eq!(polygon_distance(&a, &square(2.0, 2.0, 3.0), 10.0), 0.0);
        assert_eq!(polygon_distance(&square(2.0, 2.0, 3.0), &a, 10.0), 0.0);
        // Farther than the limit: at least the limit.
        assert!(polygon_distance(&a, &square(100.0, 0.0, 10.0), 10.0) >= 10.0);
    }

    #[test]
    fn simplified_outlines_stay_within_the_tolerance() {
        let v: Vec<Point> = (0..400)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 400.0;
                p(100.0 * a.cos(), 100.0 * a.sin())
            })
            .collect();
        let s = simplify_closed(&v, 0.25);
        assert!(s.len() < 100, "{}", s.len());
        for q in &v {
            let n = s.len();
            let d = (0..n)
                .map(|i| point_segment_distance(*q, s[i], s[(i + 1) % n]))
                .fold(f64::INFINITY, f64::min);
            assert!(d <= 0.25 + 1e-9, "{d}");
        }
    }

    #[test]
    fn distance_between_a_triangle_and_squares() {
        // The hypotenuse 3x + 4y = 12 of (0, 0), (4, 0), (0, 3) is
        // |3·10 + 4·10 − 12| / 5 = 11.6 from (10, 10), whose foot
        // (3.04, 0.72) lies on it.
        let t = vec![p(0.0, 0.0), p(4.0, 0.0), p(0.0, 3.0)];
        let d = polygon_distance(&t, &square(10.0, 10.0, 2.0), 20.0);
        assert!((d - 11.6).abs() < 1e-12, "{d}");
        assert!(polygon_distance(&t, &square(10.0, 10.0, 2.0), 5.0) >= 5.0);
        // Touching at the corner (4, 0).
        assert_eq!(polygon_distance(&t, &square(4.0, -2.0, 2.0), 1.0), 0.0);
        // Nothing to measure.
        assert_eq!(polygon_distance(&t, &[], 1.0), f64::INFINITY);
    }

    #[test]
    fn bounds_of_points_and_of_none() {
        let r = bounds(&[p(3.0, -1.0), p(-2.0, 4.0), p(1.0, 1.0)]);
        assert_eq!(r, Rect::new(-2.0, -1.0, 3.0, 4.0));
        let e = bounds(&[]);
        assert_eq!(
            (e.x0, e.y0, e.x1, e.y1),
            (
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY
            )
        );
    }

    #[test]
    fn simplifying_drops_points_within_the_tolerance() {
        // A 10 × 10 square with its edges' midpoints, the bottom one 0.05
        // below the edge.
        let v = vec![
            p(0.0, 0.0),
            p(5.0, -0.05),
            p(10.0, 0.0),
            p(10.0, 5.0),
            p(10.0, 10.0),
            p(5.0, 10.0),
            p(0.0, 10.0),
            p(0.0, 5.0),
        ];
        let corners = vec![p(0.0, 0.0), p(10.0, 0.0), p(10.0, 10.0), p(0.0, 10.0)];
        assert_eq!(simplify_closed(&v, 0.1), corners);
        let mut kept = corners.clone();
        kept.insert(1, p(5.0, -0.05));
        assert_eq!(simplify_closed(&v, 0.01), kept);
        // Fewer than 8 points: as they are.
        assert_eq!(simplify_closed(&v[..7], 100.0), v[..7].to_vec());
    }

    #[test]
    fn miter_offsets_move_every_edge_by_d() {
        assert_eq!(
            miter_offset(&square(0.0, 0.0, 10.0), 2.0),
            vec![p(-2.0, -2.0), p(12.0, -2.0), p(12.0, 12.0), p(-2.0, 12.0)]
        );
        // The hypotenuse x + y = 4 moves to x + y = 4 + √2, the legs to
        // y = −1 and x = −1: the corners (5 + √2, −1) and (−1, 5 + √2).
        let o = miter_offset(&[p(0.0, 0.0), p(4.0, 0.0), p(0.0, 4.0)], 1.0);
        let s = 5.0 + 2f64.sqrt();
        for (got, want) in o.iter().zip([p(-1.0, -1.0), p(s, -1.0), p(-1.0, s)]) {
            assert!(got.distance(want) < 1e-12, "{got:?} {want:?}");
        }
        // A needle's tip, where the edges turn back: along the incoming
        // edge's normal.
        let o = miter_offset(&[p(0.0, 0.0), p(10.0, 0.0), p(5.0, 0.0)], 1.0);
        assert_eq!(o[1], p(10.0, -1.0));
    }

    #[test]
    fn exact_arithmetic_sees_what_float_rounds_away() {
        // (0.5, 0.5 + 2⁻⁵³) lies just above the line y = x through
        // (12, 12) and (24, 24): exactly, orient((24, 24), (12, 12), a) =
        // (12 − 24)(0.5 + 2⁻⁵³ − 24) − (12 − 24)(0.5 − 24) = −12 · 2⁻⁵³;
        // in f64 the 2⁻⁵³ is lost against 23.5 and the result is 0.
        let a = p(0.5, 0.5 + 2f64.powi(-53));
        let (b, c) = (p(24.0, 24.0), p(12.0, 12.0));
        assert_eq!(Arithmetic::Float.orient(a, b, c), 0.0);
        assert_eq!(orient(a, b, c), 0.0);
        assert!(Arithmetic::Exact.orient(a, b, c) < 0.0);
        assert!(Arithmetic::Exact.orient(a, c, b) > 0.0);
        // So the point (12, 12) is on the segment a–(24, 24) in f64 only,
        assert!(Arithmetic::Float.segments_intersect(c, c, a, b));
        assert!(on_segment(c, a, b));
        assert!(!Arithmetic::Exact.segments_intersect(c, c, a, b));
        // and a→(24, 24)→(12, 12) folds back in f64 only.
        assert!(Arithmetic::Float.collinear_opposite(a, b, b, c));
        assert!(!Arithmetic::Exact.collinear_opposite(a, b, b, c));
        // Both agree away from rounding: a proper crossing, an endpoint
        // touching, collinear apart.
        for arith in [Arithmetic::Float, Arithmetic::Exact] {
            let (o, e) = (p(0.0, 0.0), p(2.0, 2.0));
            assert!(arith.segments_intersect(o, e, p(0.0, 2.0), p(2.0, 0.0)));
            assert!(arith.segments_intersect(o, e, p(1.0, 1.0), p(2.0, 0.0)));
            assert!(!arith.segments_intersect(o, e, p(2.5, 2.5), p(3.0, 3.0)));
            assert_eq!(arith.orient(o, p(4.0, 0.0), p(0.0, 3.0)), 12.0);
        }
    }

    #[test]
    fn folding_back_and_points_on_segments() {
        let (a, b) = (p(0.0, 0.0), p(10.0, 0.0));
        // a→b→(4, 0) turns back along itself; a→b→(14, 0) goes straight
        // on; a→b→(4, 1) turns.
        assert!(Arithmetic::Float.collinear_opposite(a, b, b, p(4.0, 0.0)));
        assert!(!Arithmetic::Float.collinear_opposite(a, b, b, p(14.0, 0.0)));
        assert!(!Arithmetic::Float.collinear_opposite(a, b, b, p(4.0, 1.0)));
        // A segment anywhere on the line, against a→b.
        assert!(Arithmetic::Float.collinear_opposite(a, b, p(30.0, 0.0), p(20.0, 0.0)));
        assert!(on_segment(p(3.0, 0.0), a, b));
        assert!(on_segment(b, a, b));
        assert!(!on_segment(p(11.0, 0.0), a, b));
        assert!(!on_segment(p(3.0, 0.5), a, b));
    }
}
