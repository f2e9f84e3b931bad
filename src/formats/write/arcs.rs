//! Closed contours fitted by lines and circular arcs (DXF bulges, SVG
//! `A`), within a tolerance of the polygon plan.json gives.
//!
//! Greedy from a corner: each span is the longest run of the polygon's
//! vertices that one line, or one arc through its two ends and its middle
//! vertex, follows within the tolerance. For a line: every vertex of the
//! run within `tol` of the chord (so every edge is, and the chord is within
//! `tol` of the run, which crosses every normal of it). For an arc: every
//! vertex within `tol` of the circle radially, every edge's point nearest
//! the centre too (an edge's distance from the centre lies between that
//! and its farther end's, so the whole edge is within `tol` of the
//! circle), the vertices turning one way about the centre and less than
//! a full turn (so each edge spans the arc between its ends' directions,
//! and every point of the arc has an edge point on its radius within
//! `tol`): the fitted contour and the polygon are within `tol` of each
//! other both ways. Spans shorter than [`MIN_SEGMENT_MM`] are then joined
//! to a neighbour: a vertex that ends one is dropped and its neighbours
//! refitted; where the neighbours cannot be refitted within `tol` (a
//! feature smaller than the shortest segment) the shorter span's end moves
//! onto its neighbour, which changes the contour by less than that
//! segment.

/// A polyline vertex, sheet frame, mm; `bulge` = tan(¼ of the arc's
/// included angle) of the segment to the next vertex (0: straight,
/// positive: counter-clockwise), as DXF's LWPOLYLINE stores it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vertex {
    /// x along the sheet's length, mm.
    pub x_mm: f64,
    /// y across the sheet's width, mm.
    pub y_mm: f64,
    /// Bulge of the segment that starts here.
    pub bulge: f64,
}

/// The default fitting tolerance, mm.
pub const DEFAULT_TOLERANCE_MM: f64 = 0.01;

/// No fitted segment (chord) is shorter than this, mm.
pub const MIN_SEGMENT_MM: f64 = 0.05;

/// An arc from a bulge: centre, radius, start angle and signed sweep
/// (positive counter-clockwise), rad.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BulgeArc {
    /// Centre, mm.
    pub center: [f64; 2],
    /// Radius, mm.
    pub radius: f64,
    /// Angle of the start point about the centre, rad.
    pub start: f64,
    /// Signed sweep to the end point, rad (|sweep| < 2π).
    pub sweep: f64,
}

impl BulgeArc {
    /// The arc of `a`'s bulge from `a` to `b`, or `None` when straight (or
    /// the points coincide).
    pub fn of(a: Vertex, b: Vertex) -> Option<BulgeArc> {
        if a.bulge == 0.0 {
            return None;
        }
        let (dx, dy) = (b.x_mm - a.x_mm, b.y_mm - a.y_mm);
        let chord = dx.hypot(dy);
        if chord == 0.0 {
            return None;
        }
        let sweep = 4.0 * a.bulge.atan();
        // Radius from the chord and the half sweep; the centre lies on the
        // chord's normal, left of it for a counter-clockwise arc, at
        // (1 − b²)/(4b) of the chord from its middle.
        let radius = chord * (1.0 + a.bulge * a.bulge) / (4.0 * a.bulge.abs());
        let k = (1.0 - a.bulge * a.bulge) / (4.0 * a.bulge);
        let center = [
            0.5 * (a.x_mm + b.x_mm) - k * dy,
            0.5 * (a.y_mm + b.y_mm) + k * dx,
        ];
        let start = (a.y_mm - center[1]).atan2(a.x_mm - center[0]);
        Some(BulgeArc {
            center,
            radius,
            start,
            sweep,
        })
    }

    /// Whether the direction `phi` (rad) is swept.
    pub fn contains_angle(&self, phi: f64) -> bool {
        let tau = std::f64::consts::TAU;
        let d = if self.sweep >= 0.0 {
            (phi - self.start).rem_euclid(tau)
        } else {
            (self.start - phi).rem_euclid(tau)
        };
        d <= self.sweep.abs()
    }

    /// The point at fraction `t` of the sweep.
    pub fn point(&self, t: f64) -> [f64; 2] {
        let phi = self.start + t * self.sweep;
        [
            self.center[0] + self.radius * phi.cos(),
            self.center[1] + self.radius * phi.sin(),
        ]
    }
}

/// Points along a polyline with bulges, arcs split so no chord is more
/// than `sagitta_mm` from its arc (for drawings that take only lines).
pub fn flatten(vertices: &[Vertex], closed: bool, sagitta_mm: f64) -> Vec<[f64; 2]> {
    let n = vertices.len();
    let mut out = Vec::with_capacity(n);
    for (i, a) in vertices.iter().enumerate() {
        out.push([a.x_mm, a.y_mm]);
        if i + 1 == n && !closed {
            break;
        }
        let b = vertices[(i + 1) % n];
        if let Some(arc) = BulgeArc::of(*a, b) {
            // A chord over an angle φ of radius r is r(1 − cos φ/2) off.
            let step = 2.0 * (1.0 - (sagitta_mm / arc.radius).min(1.0)).acos();
            let k = (arc.sweep.abs() / step.max(1e-6)).ceil().clamp(1.0, 4096.0) as usize;
            for j in 1..k {
                out.push(arc.point(j as f64 / k as f64));
            }
        }
    }
    out
}

/// A closed polygon (no repeated last point, at least three points)
/// fitted by lines and arcs within `tol_mm`: vertices with the bulge of
/// the segment each starts.
pub fn fit_closed(points: &[[f64; 2]], tol_mm: f64) -> Vec<Vertex> {
    let n = points.len();
    if n < 4 {
        return points.iter().map(|p| vertex(*p, 0.0)).collect();
    }
    // Start at the sharpest corner: a smooth closed curve may start
    // anywhere, a contour with corners should not have a span across one.
    let start = (0..n)
        .max_by(|&a, &b| turn(points, a).total_cmp(&turn(points, b)).then(b.cmp(&a)))
        .unwrap_or(0);
    let ring: Vec<[f64; 2]> = (0..=n).map(|k| points[(start + k) % n]).collect();
    let mut spans: Vec<(usize, f64)> = Vec::new();
    let mut i = 0;
    while i < n {
        let (j, bulge) = longest(&ring, i, n, tol_mm);
        spans.push((i, bulge));
        i = j;
    }
    let spans = join_short(&ring, spans, n, tol_mm);
    spans
        .into_iter()
        .map(|(i, bulge)| vertex(ring[i], bulge))
        .collect()
}

fn vertex(p: [f64; 2], bulge: f64) -> Vertex {
    Vertex {
        x_mm: p[0],
        y_mm: p[1],
        bulge,
    }
}

/// |turn| at vertex `k` of a closed polygon, rad.
fn turn(p: &[[f64; 2]], k: usize) -> f64 {
    let n = p.len();
    let (a, b, c) = (p[(k + n - 1) % n], p[k], p[(k + 1) % n]);
    let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - b[0], c[1] - b[1]]);
    (u[0] * v[1] - u[1] * v[0])
        .atan2(u[0] * v[0] + u[1] * v[1])
        .abs()
}

/// The end of the longest span from `i` (at most `last`) that one line or
/// arc follows within `tol`, and its bulge.
fn longest(ring: &[[f64; 2]], i: usize, last: usize, tol: f64) -> (usize, f64) {
    // Grow by doubling while it fits, then bisect between the last fit and
    // the first miss.
    let mut good = (i + 1, 0.0);
    let mut step = 1;
    let mut bad = None;
    loop {
        let j = (i + 2 * step).min(last);
        if j <= good.0 {
            break;
        }
        match fits(ring, i, j, tol) {
            Some(b) => {
                good = (j, b);
                if j == last {
                    break;
                }
                step *= 2;
            }
            None => {
                bad = Some(j);
                break;
            }
        }
    }
    if let Some(mut hi) = bad {
        let mut lo = good.0;
        while hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            match fits(ring, i, mid, tol) {
                Some(b) => {
                    good = (mid, b);
                    lo = mid;
                }
                None => hi = mid,
            }
        }
    }
    good
}

/// The bulge of one line (0) or arc that follows `ring[i..=j]` within
/// `tol`, if any.
pub(crate) fn fits(ring: &[[f64; 2]], i: usize, j: usize, tol: f64) -> Option<f64> {
    let (a, b) = (ring[i], ring[j]);
    if j == i + 1 {
        return Some(0.0);
    }
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let chord = dx.hypot(dy);
    if chord > 0.0 {
        // A line: every vertex within tol of the chord, and in its extent.
        let line = ring[i + 1..j].iter().all(|p| {
            let (px, py) = (p[0] - a[0], p[1] - a[1]);
            let along = (px * dx + py * dy) / chord;
            (px * dy - py * dx).abs() / chord <= tol && along >= -tol && along <= chord + tol
        });
        if line {
            return Some(0.0);
        }
    }
    let m = ring[(i + j) / 2];
    let c = circle(a, m, b)?;
    let r = (a[0] - c[0]).hypot(a[1] - c[1]);
    let angle = |p: [f64; 2]| (p[1] - c[1]).atan2(p[0] - c[0]);
    // Signed sweep, vertex by vertex: every step turns the same way.
    let mut sweep = 0.0;
    let mut prev = angle(a);
    let mut sign = 0.0;
    for k in i + 1..=j {
        let p = ring[k];
        if ((p[0] - c[0]).hypot(p[1] - c[1]) - r).abs() > tol {
            return None;
        }
        // The edge's nearest point to the centre: the edge's distance from
        // the centre runs between it and the farther end, so the whole edge
        // is within tol of the circle when it and both ends are.
        let q = ring[k - 1];
        if r - point_segment(c, q, p) > tol {
            return None;
        }
        let phi = angle(p);
        let mut d = phi - prev;
        if d > std::f64::consts::PI {
            d -= std::f64::consts::TAU;
        } else if d < -std::f64::consts::PI {
            d += std::f64::consts::TAU;
        }
        if d != 0.0 {
            if sign == 0.0 {
                sign = d.signum();
            } else if d.signum() != sign {
                return None;
            }
        }
        sweep += d;
        prev = phi;
    }
    // Less than a full turn, and a whole arc (not a line in disguise).
    if sweep.abs() >= 1.9 * std::f64::consts::PI || sweep == 0.0 {
        return None;
    }
    Some((0.25 * sweep).tan())
}

/// The distance from `p` to the segment `a`–`b`.
fn point_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l2 = dx * dx + dy * dy;
    let t = if l2 == 0.0 {
        0.0
    } else {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0)
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// The centre of the circle through three points, if not collinear.
fn circle(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Option<[f64; 2]> {
    let (bx, by) = (b[0] - a[0], b[1] - a[1]);
    let (cx, cy) = (c[0] - a[0], c[1] - a[1]);
    let d = 2.0 * (bx * cy - by * cx);
    let scale = (bx * bx + by * by).max(cx * cx + cy * cy);
    if d.abs() <= 1e-12 * scale {
        return None;
    }
    let (b2, c2) = (bx * bx + by * by, cx * cx + cy * cy);
    Some([
        a[0] + (cy * b2 - by * c2) / d,
        a[1] + (bx * c2 - cx * b2) / d,
    ])
}

/// Spans (start index into `ring`, bulge) with no chord shorter than
/// [`MIN_SEGMENT_MM`] (see the module doc); `n` closes the ring.
fn join_short(
    ring: &[[f64; 2]],
    mut spans: Vec<(usize, f64)>,
    n: usize,
    tol: f64,
) -> Vec<(usize, f64)> {
    let chord = |a: usize, b: usize| {
        let (p, q) = (ring[a], ring[b]);
        (p[0] - q[0]).hypot(p[1] - q[1])
    };
    let end = |spans: &[(usize, f64)], k: usize| {
        if k + 1 < spans.len() {
            spans[k + 1].0
        } else {
            n
        }
    };
    let mut k = 0;
    while spans.len() > 3 && k < spans.len() {
        let (s, e) = (spans[k].0, end(&spans, k));
        if chord(s, e) >= MIN_SEGMENT_MM {
            k += 1;
            continue;
        }
        // Drop the span's end vertex (the next span's start), joining it
        // to the next span, or its start, joining it to the previous one;
        // the ring's first vertex stays.
        let next = k + 1 < spans.len();
        if next {
            let e2 = end(&spans, k + 1);
            if let Some(b) = fits(ring, s, e2, tol) {
                spans[k].1 = b;
                spans.remove(k + 1);
                continue;
            }
        }
        if k > 0 {
            let s0 = spans[k - 1].0;
            if let Some(b) = fits(ring, s0, e, tol) {
                spans[k - 1].1 = b;
                spans.remove(k);
                k -= 1;
                continue;
            }
        }
        // No refit within tol: a feature below the shortest segment.
        // Join it to the neighbour as a straight segment.
        if next {
            spans[k].1 = 0.0;
            spans.remove(k + 1);
        } else {
            spans[k - 1].1 = 0.0;
            spans.remove(k);
            k -= 1;
        }
    }
    spans
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The distance from `p` to a fitted contour, by its segments (arcs
    /// exactly: the radial distance where the direction is swept, else the
    /// nearer end).
    fn dist_to_fit(p: [f64; 2], v: &[Vertex]) -> f64 {
        let n = v.len();
        (0..n)
            .map(|i| {
                let (a, b) = (v[i], v[(i + 1) % n]);
                match BulgeArc::of(a, b) {
                    Some(arc) => {
                        let phi = (p[1] - arc.center[1]).atan2(p[0] - arc.center[0]);
                        if arc.contains_angle(phi) {
                            ((p[0] - arc.center[0]).hypot(p[1] - arc.center[1]) - arc.radius).abs()
                        } else {
                            (p[0] - a.x_mm)
                                .hypot(p[1] - a.y_mm)
                                .min((p[0] - b.x_mm).hypot(p[1] - b.y_mm))
                        }
                    }
                    None => seg_dist(p, [a.x_mm, a.y_mm], [b.x_mm, b.y_mm]),
                }
            })
            .fold(f64::INFINITY, f64::min)
    }

    fn seg_dist(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let l2 = dx * dx + dy * dy;
        let t = if l2 == 0.0 {
            0.0
        } else {
            (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0)
        };
        (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
    }

    /// A stadium (a washer's rounded-end outline): two half circles of
    /// radius 10 joined by 50 mm straights, sampled at 400 points a half
    /// circle with jitter-free exact points; fitted, it is two lines and
    /// two arcs (or a few arcs per half circle), every sample within the
    /// tolerance of the fit and every fitted point within it of the
    /// exact stadium.
    #[test]
    fn a_stadium_is_two_lines_and_its_arcs() {
        let r = 10.0;
        let mut pts = Vec::new();
        for k in 0..=400 {
            let t = std::f64::consts::PI * (k as f64 / 400.0 - 0.5);
            pts.push([50.0 + r * t.cos(), r * t.sin()]);
        }
        for k in 0..=400 {
            let t = std::f64::consts::PI * (k as f64 / 400.0 + 0.5);
            pts.push([r * t.cos(), r * t.sin()]);
        }
        let v = fit_closed(&pts, 0.01);
        assert!(v.len() <= 6, "{} vertices", v.len());
        // The exact stadium's distance from a point.
        let exact = |p: [f64; 2]| {
            let x = p[0].clamp(0.0, 50.0);
            ((p[0] - x).hypot(p[1]) - r).abs()
        };
        for p in &pts {
            assert!(dist_to_fit(*p, &v) <= 0.01 + 1e-9);
        }
        for w in &flatten(&v, true, 1e-4) {
            assert!(exact(*w) <= 0.01 + 1e-9, "{w:?}: {}", exact(*w));
        }
        let n = v.len();
        for i in 0..n {
            let (a, b) = (v[i], v[(i + 1) % n]);
            assert!((a.x_mm - b.x_mm).hypot(a.y_mm - b.y_mm) >= MIN_SEGMENT_MM);
        }
    }

    /// A rectangle keeps its four corners, straight.
    #[test]
    fn corners_stay() {
        let mut pts = Vec::new();
        for k in 0..100 {
            pts.push([k as f64, 0.0]);
        }
        for k in 0..20 {
            pts.push([100.0, k as f64]);
        }
        for k in 0..100 {
            pts.push([100.0 - k as f64, 20.0]);
        }
        for k in 0..20 {
            pts.push([0.0, 20.0 - k as f64]);
        }
        let v = fit_closed(&pts, 0.01);
        let corners: Vec<[f64; 2]> = v.iter().map(|q| [q.x_mm, q.y_mm]).collect();
        assert_eq!(corners.len(), 4, "{corners:?}");
        assert!(v.iter().all(|q| q.bulge == 0.0));
        for c in [[0.0, 0.0], [100.0, 0.0], [100.0, 20.0], [0.0, 20.0]] {
            assert!(corners.contains(&c), "{c:?} in {corners:?}");
        }
    }

    /// Segments far below the shortest allowed (µm steps along a curve)
    /// are absorbed.
    #[test]
    fn micro_segments_are_absorbed() {
        let mut pts = vec![[0.0, 0.0], [10.0, 0.0], [10.0, 5.0]];
        for k in 0..50 {
            pts.push([10.0 - 0.0034 * k as f64, 5.0]);
        }
        pts.push([0.0, 5.0]);
        let v = fit_closed(&pts, 0.01);
        assert_eq!(v.len(), 4);
    }

    /// A bulge of 1 from (0, 0) to (10, 0): the half circle below, centre
    /// (5, 0), radius 5.
    #[test]
    fn bulge_arcs() {
        let arc = BulgeArc::of(
            Vertex {
                x_mm: 0.0,
                y_mm: 0.0,
                bulge: 1.0,
            },
            Vertex {
                x_mm: 10.0,
                y_mm: 0.0,
                bulge: 0.0,
            },
        )
        .expect("arc");
        assert!((arc.center[0] - 5.0).abs() < 1e-12 && arc.center[1].abs() < 1e-12);
        assert!((arc.radius - 5.0).abs() < 1e-12);
        let mid = arc.point(0.5);
        assert!((mid[0] - 5.0).abs() < 1e-12 && (mid[1] + 5.0).abs() < 1e-12);
    }
}
