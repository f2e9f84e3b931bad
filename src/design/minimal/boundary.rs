//! Boundary loops: validation, the best-fit plane, whether the projected
//! loops bound a planar domain (simple, disjoint, nested), and resampling.

use crate::error::{Error, Location, Result};
use crate::geom::eigen::{symmetric_eigen3, Sweeps};
use crate::geom::plane::{point_in_polygon, point_segment_distance, signed_area_mm2, Arithmetic};
use glam::{DVec2, DVec3};
use kurbo::Point;
use std::collections::BTreeSet;
use std::path::Path;

/// Two points closer than this are one point (a repeated closing point is
/// dropped; coincident consecutive points are an error), mm.
pub const COINCIDENT_MM: f64 = 1e-6;

/// Largest |coordinate| of a boundary point, mm: 10 km from the origin, as
/// for a network ([`crate::network::MAX_COORDINATE_MM`]).
pub const MAX_COORDINATE_MM: f64 = crate::network::MAX_COORDINATE_MM;

/// The loops as given, checked: finite, within [`MAX_COORDINATE_MM`] of the
/// origin, at least 3 points, no repeated
/// closing point, no coincident consecutive points.
pub fn clean_loops(boundaries_mm: &[Vec<DVec3>], path: &Path) -> Result<Vec<Vec<DVec3>>> {
    if boundaries_mm.is_empty() {
        return Err(Error::input(
            path,
            Location::Field("boundaries".into()),
            "no boundary loop given: a soap film needs at least one closed polyline",
        ));
    }
    let mut out = Vec::with_capacity(boundaries_mm.len());
    for (i, b) in boundaries_mm.iter().enumerate() {
        let at = || Location::Field(format!("boundaries[{i}]"));
        if let Some(j) = b.iter().position(|p| !p.is_finite()) {
            return Err(Error::input(
                path,
                at(),
                format!("point {j} has a coordinate that is not a finite number"),
            ));
        }
        if let Some(j) = b
            .iter()
            .position(|p| p.abs().max_element() > MAX_COORDINATE_MM)
        {
            return Err(Error::input(
                path,
                at(),
                format!(
                    "point {j} has a coordinate of {:e} mm; boundary coordinates are limited to {MAX_COORDINATE_MM:e} mm (10 km) from the origin",
                    b[j].abs().max_element()
                ),
            ));
        }
        let mut pts = b.clone();
        if pts.len() >= 2 && pts[0].distance(pts[pts.len() - 1]) <= COINCIDENT_MM {
            pts.pop();
        }
        if pts.len() < 3 {
            return Err(Error::input(
                path,
                at(),
                format!(
                    "a closed boundary loop needs at least 3 distinct points, this one has {}",
                    pts.len()
                ),
            ));
        }
        for j in 0..pts.len() {
            let k = (j + 1) % pts.len();
            if pts[j].distance(pts[k]) <= COINCIDENT_MM {
                return Err(Error::input(
                    path,
                    at(),
                    format!(
                        "points {j} and {k} coincide at ({:.3}, {:.3}, {:.3}) mm",
                        pts[j].x, pts[j].y, pts[j].z
                    ),
                ));
            }
        }
        out.push(pts);
    }
    Ok(out)
}

/// An orthonormal right-handed frame: origin, in-plane axes `u`, `v` and
/// the normal `n = u × v`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Origin, mm.
    pub origin: DVec3,
    /// First in-plane axis.
    pub u: DVec3,
    /// Second in-plane axis.
    pub v: DVec3,
    /// Normal, u × v.
    pub n: DVec3,
}

impl Frame {
    /// Coordinates of `p` in the plane.
    pub fn project(&self, p: DVec3) -> DVec2 {
        let d = p - self.origin;
        DVec2::new(d.dot(self.u), d.dot(self.v))
    }
    /// Coordinates of every point of `points` in the plane, as plane points
    /// for [`crate::geom::plane`].
    pub fn project_all(&self, points: &[DVec3]) -> Vec<Point> {
        points
            .iter()
            .map(|&p| {
                let q = self.project(p);
                Point::new(q.x, q.y)
            })
            .collect()
    }
    /// The same plane seen from the other side (v and n reversed).
    pub fn flipped(&self) -> Frame {
        Frame {
            origin: self.origin,
            u: self.u,
            v: -self.v,
            n: -self.n,
        }
    }
}

/// The best-fit plane of all points: PCA, normal = the direction of least
/// variance (eigenvectors of the covariance by cyclic Jacobi rotations).
pub fn best_fit_frame(loops: &[Vec<DVec3>]) -> Frame {
    let count = loops.iter().map(Vec::len).sum::<usize>() as f64;
    let origin = loops.iter().flatten().fold(DVec3::ZERO, |a, &p| a + p) / count;
    let mut c = [[0.0f64; 3]; 3];
    for p in loops.iter().flatten() {
        let d = (*p - origin).to_array();
        for (r, row) in c.iter_mut().enumerate() {
            for (s, x) in row.iter_mut().enumerate() {
                *x += d[r] * d[s];
            }
        }
    }
    let (values, vectors) = symmetric_eigen3(
        c,
        Sweeps {
            relative: 1e-17,
            negligible: 0.0,
        },
    );
    let mut order = [0usize, 1, 2];
    order.sort_by(|&a, &b| values[b].total_cmp(&values[a]));
    let col = |k: usize| DVec3::new(vectors[0][k], vectors[1][k], vectors[2][k]).normalize();
    let u = col(order[0]);
    let v0 = col(order[1]);
    let v = (v0 - u * u.dot(v0)).normalize();
    Frame {
        origin,
        u,
        v,
        n: u.cross(v),
    }
}

/// How the projected loops fail to bound a planar domain.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum DomainProblem {
    /// A loop crosses or touches itself: (loop, segment, segment).
    SelfIntersection(usize, usize, usize),
    /// Two loops cross or touch: (loop, loop).
    Crossing(usize, usize),
    /// The loops are disjoint but not one outer loop around holes:
    /// (loop, loop) that are not nested as required.
    NotNested(usize, usize),
}

impl DomainProblem {
    /// The loop to name in an error.
    pub fn first_loop(&self) -> usize {
        match *self {
            DomainProblem::SelfIntersection(l, ..)
            | DomainProblem::Crossing(l, _)
            | DomainProblem::NotNested(l, _) => l,
        }
    }
    /// One line saying what is wrong.
    pub fn message(&self) -> String {
        match *self {
            DomainProblem::SelfIntersection(l, s, t) => format!(
                "loop {l} intersects itself in projection onto the boundaries' best-fit plane (its segments {s} and {t} meet), so the film has no planar chart"
            ),
            DomainProblem::Crossing(a, b) => format!(
                "loops {a} and {b} cross or touch in projection onto the boundaries' best-fit plane; with more than two loops the film needs one outer loop around disjoint holes"
            ),
            DomainProblem::NotNested(a, b) => format!(
                "loops {a} and {b} are not nested as one outer loop around holes in projection onto the boundaries' best-fit plane"
            ),
        }
    }
}

/// A planar domain: which loop is outer, all loops projected, oriented so
/// that the outer loop runs counter-clockwise and the holes clockwise.
#[derive(Debug, Clone)]
pub struct PlanarDomain {
    /// The frame, oriented so that the outer loop as given runs
    /// counter-clockwise in (u, v).
    pub frame: Frame,
    /// Index of the outer loop.
    pub outer: usize,
    /// Per loop: whether its order was reversed to orient it.
    pub reversed: Vec<bool>,
}

/// Check that the loops projected with `frame` are simple, disjoint and
/// nested as one outer loop around holes.
pub fn planar_domain(loops: &[Vec<DVec3>], frame: Frame) -> Result<PlanarDomain, DomainProblem> {
    let proj: Vec<Vec<Point>> = loops.iter().map(|l| frame.project_all(l)).collect();
    // Every segment, swept by its smallest x.
    struct Seg {
        lo: f64,
        hi: f64,
        l: usize,
        s: usize,
    }
    let mut segs: Vec<Seg> = Vec::new();
    for (l, p) in proj.iter().enumerate() {
        for s in 0..p.len() {
            let (a, b) = (p[s], p[(s + 1) % p.len()]);
            segs.push(Seg {
                lo: a.x.min(b.x),
                hi: a.x.max(b.x),
                l,
                s,
            });
        }
    }
    segs.sort_by(|a, b| {
        a.lo.total_cmp(&b.lo)
            .then(a.l.cmp(&b.l))
            .then(a.s.cmp(&b.s))
    });
    let mut selfs: BTreeSet<(usize, usize, usize)> = BTreeSet::new();
    let mut crossings: BTreeSet<(usize, usize)> = BTreeSet::new();
    for i in 0..segs.len() {
        for j in i + 1..segs.len() {
            if segs[j].lo > segs[i].hi {
                break;
            }
            let (x, y) = (&segs[i], &segs[j]);
            let (px, py) = (&proj[x.l], &proj[y.l]);
            let (a, b) = (px[x.s], px[(x.s + 1) % px.len()]);
            let (c, d) = (py[y.s], py[(y.s + 1) % py.len()]);
            if x.l == y.l {
                let n = px.len();
                let (s, t) = (x.s.min(y.s), x.s.max(y.s));
                let adjacent = t == s + 1 || (s == 0 && t == n - 1);
                if adjacent {
                    // Sharing one end: they meet elsewhere only when they
                    // fold back onto each other (collinear, opposite), or
                    // in a triangle-like loop of 3 where both ends are shared.
                    let (p, q, r) = if t == s + 1 {
                        (px[s], px[t], px[(t + 1) % n])
                    } else {
                        (px[t], px[0], px[1])
                    };
                    if Arithmetic::Exact.collinear_opposite(p, q, q, r) {
                        selfs.insert((x.l, s, t));
                    }
                } else if Arithmetic::Exact.segments_intersect(a, b, c, d) {
                    selfs.insert((x.l, s, t));
                }
            } else if Arithmetic::Exact.segments_intersect(a, b, c, d) {
                crossings.insert((x.l.min(y.l), x.l.max(y.l)));
            }
        }
    }
    if let Some(&(l, s, t)) = selfs.iter().next() {
        return Err(DomainProblem::SelfIntersection(l, s, t));
    }
    if let Some(&(a, b)) = crossings.iter().next() {
        return Err(DomainProblem::Crossing(a, b));
    }
    // Disjoint simple loops: nesting by one vertex each.
    let n = loops.len();
    let inside = |i: usize, j: usize| point_in_polygon(proj[i][0], &proj[j]);
    let outers: Vec<usize> = (0..n)
        .filter(|&i| (0..n).all(|j| j == i || !inside(i, j)))
        .collect();
    match outers[..] {
        [_] => {}
        [a, b, ..] => return Err(DomainProblem::NotNested(a, b)),
        // Disjoint simple loops always have an outermost one; rounding in
        // the containment test aside.
        [] => return Err(DomainProblem::NotNested(0, 1.min(n - 1))),
    }
    let outer = outers[0];
    for i in 0..n {
        for j in 0..n {
            if i != j && j != outer && inside(i, j) {
                return Err(DomainProblem::NotNested(j, i));
            }
        }
    }
    let frame = if signed_area_mm2(&proj[outer]) < 0.0 {
        frame.flipped()
    } else {
        frame
    };
    // Areas change sign with the frame: recompute in the oriented frame.
    let reversed = (0..n)
        .map(|i| {
            let ccw = signed_area_mm2(&frame.project_all(&loops[i])) > 0.0;
            if i == outer {
                !ccw
            } else {
                ccw
            }
        })
        .collect();
    Ok(PlanarDomain {
        frame,
        outer,
        reversed,
    })
}

/// The first place where two loops cross or touch in projection with
/// `frame`: (loop, loop, the crossing point on the first loop, mm), pairs
/// and segments in order; `None` when no two loops meet in projection.
pub fn plan_crossing(loops: &[Vec<DVec3>], frame: Frame) -> Option<(usize, usize, DVec3)> {
    let proj: Vec<Vec<Point>> = loops.iter().map(|l| frame.project_all(l)).collect();
    let exact = Arithmetic::Exact;
    for i in 0..loops.len() {
        for j in i + 1..loops.len() {
            let (p, q) = (&proj[i], &proj[j]);
            for s in 0..p.len() {
                let (a, b) = (p[s], p[(s + 1) % p.len()]);
                for t in 0..q.len() {
                    let (c, d) = (q[t], q[(t + 1) % q.len()]);
                    if !exact.segments_intersect(a, b, c, d) {
                        continue;
                    }
                    // Where a–b meets the line c–d (its start when they
                    // are collinear, its end when only that touches).
                    let (da, db) = (exact.orient(c, d, a), exact.orient(c, d, b));
                    let f = if da == db {
                        0.0
                    } else {
                        (da / (da - db)).clamp(0.0, 1.0)
                    };
                    let (x, y) = (loops[i][s], loops[i][(s + 1) % loops[i].len()]);
                    return Some((i, j, x + (y - x) * f));
                }
            }
        }
    }
    None
}

/// Whether two loops project onto each other with `frame` (coaxial rings
/// of one plan, sampled alike or not): every vertex of each lies within
/// half the longest projected segment of the two of the other's
/// projection. Two samplings of one plan curve differ by less than their
/// chords' sagitta, far below that; loops whose plans cross do not.
pub fn project_onto_each_other(a: &[DVec3], b: &[DVec3], frame: Frame) -> bool {
    let (p, q) = (frame.project_all(a), frame.project_all(b));
    let longest = |l: &[Point]| {
        (0..l.len())
            .map(|i| l[i].distance(l[(i + 1) % l.len()]))
            .fold(0.0, f64::max)
    };
    let tol = 0.5 * longest(&p).max(longest(&q));
    let near = |x: Point, l: &[Point]| {
        (0..l.len()).any(|i| point_segment_distance(x, l[i], l[(i + 1) % l.len()]) <= tol)
    };
    p.iter().all(|&x| near(x, &q)) && q.iter().all(|&x| near(x, &p))
}

/// Whether two loops bounding a planar annulus are better lofted: the
/// difference of their mean heights over the plane exceeds the difference
/// of their equivalent radii √(A/π) in it (the film rises more than 45° on
/// average, so the projection squeezes it).
pub fn steep_annulus(loops: &[Vec<DVec3>], domain: &PlanarDomain) -> bool {
    let f = domain.frame;
    let height =
        |l: &[DVec3]| l.iter().map(|&p| (p - f.origin).dot(f.n)).sum::<f64>() / l.len() as f64;
    let radius =
        |l: &[DVec3]| (signed_area_mm2(&f.project_all(l)).abs() / std::f64::consts::PI).sqrt();
    (height(&loops[0]) - height(&loops[1])).abs() > (radius(&loops[0]) - radius(&loops[1])).abs()
}

/// Segment lengths of a closed loop, mm.
pub fn segment_lengths(pts: &[DVec3]) -> Vec<f64> {
    (0..pts.len())
        .map(|i| pts[i].distance(pts[(i + 1) % pts.len()]))
        .collect()
}

/// A piece may be this much longer than the spacing before its segment is
/// split once more (so a polyline whose chords are about the spacing keeps
/// them whole).
pub const PIECE_SLACK: f64 = 1.1;

/// Number of pieces per segment at spacing `h0_mm`: the fewest equal
/// pieces no longer than [`PIECE_SLACK`] × h0, at least 1.
pub fn pieces(lengths_mm: &[f64], h0_mm: f64) -> Vec<usize> {
    lengths_mm
        .iter()
        .map(|&l| (l / (PIECE_SLACK * h0_mm)).ceil().max(1.0) as usize)
        .collect()
}

/// Add pieces to the segments with the longest pieces (lowest index on a
/// tie) until there are `total` pieces.
pub fn add_pieces(lengths_mm: &[f64], pieces: &mut [usize], total: usize) {
    while pieces.iter().sum::<usize>() < total {
        let mut best = 0;
        for s in 1..pieces.len() {
            if lengths_mm[s] / pieces[s] as f64 > lengths_mm[best] / pieces[best] as f64 {
                best = s;
            }
        }
        pieces[best] += 1;
    }
}

/// The loop resampled: segment s split into `pieces[s]` equal parts; the
/// given points are kept exactly.
pub fn resample(pts: &[DVec3], pieces: &[usize]) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(pieces.iter().sum());
    for (s, &m) in pieces.iter().enumerate() {
        let (a, b) = (pts[s], pts[(s + 1) % pts.len()]);
        out.push(a);
        for j in 1..m {
            out.push(a.lerp(b, j as f64 / m as f64));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(c: DVec2, h: f64, z: f64) -> Vec<DVec3> {
        [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .iter()
            .map(|&(x, y)| DVec3::new(c.x + h * x, c.y + h * y, z))
            .collect()
    }

    #[test]
    fn frame_of_a_tilted_plane_has_its_normal() {
        let n = DVec3::new(1.0, 2.0, 3.0).normalize();
        let u = n.any_orthonormal_vector();
        let v = n.cross(u);
        let pts: Vec<DVec3> = (0..7)
            .map(|i| {
                let t = i as f64;
                u * (100.0 * t.cos() + 3.0 * t) + v * (40.0 * t.sin()) + n * 5.0
            })
            .collect();
        let f = best_fit_frame(&[pts]);
        assert!(f.n.cross(n).length() < 1e-12, "{:?}", f.n);
        assert!((f.u.cross(f.v) - f.n).length() < 1e-12);
    }

    #[test]
    fn a_square_with_a_hole_is_a_domain_and_holes_turn_clockwise() {
        let outer = square(DVec2::ZERO, 10.0, 0.0);
        let hole = square(DVec2::new(1.0, 0.0), 3.0, 0.0); // counter-clockwise as given
        let f = best_fit_frame(&[outer.clone(), hole.clone()]);
        let d = planar_domain(&[outer, hole], f).expect("domain");
        assert_eq!(d.outer, 0);
        assert_eq!(d.reversed, vec![false, true]);
        assert!(d.frame.n.z > 0.0);
    }

    #[test]
    fn crossing_touching_and_self_intersecting_loops_are_found() {
        let f = Frame {
            origin: DVec3::ZERO,
            u: DVec3::X,
            v: DVec3::Y,
            n: DVec3::Z,
        };
        let a = square(DVec2::ZERO, 10.0, 0.0);
        let b = square(DVec2::new(10.0, 0.0), 5.0, 0.0);
        assert_eq!(
            planar_domain(&[a.clone(), b], f).unwrap_err(),
            DomainProblem::Crossing(0, 1)
        );
        // Touching at a vertex of the hole.
        let t = vec![
            DVec3::new(10.0, 0.0, 0.0),
            DVec3::new(5.0, 2.0, 0.0),
            DVec3::new(5.0, -2.0, 0.0),
        ];
        assert_eq!(
            planar_domain(&[a.clone(), t], f).unwrap_err(),
            DomainProblem::Crossing(0, 1)
        );
        let bow = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(10.0, 10.0, 0.0),
            DVec3::new(10.0, 0.0, 0.0),
            DVec3::new(0.0, 10.0, 0.0),
        ];
        assert!(matches!(
            planar_domain(&[bow], f).unwrap_err(),
            DomainProblem::SelfIntersection(0, _, _)
        ));
        let fold = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(10.0, 0.0, 0.0),
            DVec3::new(5.0, 0.0, 0.0),
            DVec3::new(5.0, 5.0, 0.0),
        ];
        assert!(matches!(
            planar_domain(&[fold], f).unwrap_err(),
            DomainProblem::SelfIntersection(0, _, _)
        ));
        let c = square(DVec2::new(30.0, 0.0), 5.0, 0.0);
        assert_eq!(
            planar_domain(&[a, c], f).unwrap_err(),
            DomainProblem::NotNested(0, 1)
        );
    }

    #[test]
    fn resampling_keeps_corners_and_splits_evenly() {
        let pts = vec![
            DVec3::ZERO,
            DVec3::new(10.0, 0.0, 0.0),
            DVec3::new(0.0, 3.0, 0.0),
        ];
        let l = segment_lengths(&pts);
        // 10/4.4 → 3, 10.44/4.4 → 3, 3/4.4 → 1.
        let mut p = pieces(&l, 4.0);
        assert_eq!(p, vec![3, 3, 1]);
        assert_eq!(pieces(&[4.4, 4.41], 4.0), vec![1, 2]);
        add_pieces(&l, &mut p, 8);
        // The added piece goes to the longest pieces: 10.44/3 > 10/3.
        assert_eq!(p, vec![3, 4, 1]);
        let r = resample(&pts, &p);
        assert_eq!(r.len(), 8);
        assert_eq!(r[0], pts[0]);
        assert_eq!(r[3], pts[1]);
        assert_eq!(r[7], pts[2]);
        assert!((r[2] - DVec3::new(20.0 / 3.0, 0.0, 0.0)).length() < 1e-12);
        assert!((r[5] - DVec3::new(5.0, 1.5, 0.0)).length() < 1e-12);
    }

    #[test]
    fn short_loops_and_bad_points_are_one_line_errors() {
        let p = Path::new("spec.yaml");
        let e = clean_loops(&[vec![DVec3::ZERO, DVec3::X, DVec3::ZERO]], p)
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "spec.yaml: field `boundaries[0]`: a closed boundary loop needs at least 3 distinct points, this one has 2"
        );
        let e = clean_loops(&[vec![DVec3::ZERO, DVec3::X, DVec3::X, DVec3::Y]], p)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("boundaries[0]") && e.contains("points 1 and 2 coincide"),
            "{e}"
        );
        let e = clean_loops(
            &[vec![DVec3::ZERO, DVec3::X, DVec3::new(f64::NAN, 0.0, 0.0)]],
            p,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("point 2"), "{e}");
    }
}
