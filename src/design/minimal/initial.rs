//! The initial coarse mesh and its chart: a refined constrained Delaunay
//! triangulation of a planar domain, or a loft between two loops.

use super::boundary::{self, Frame, PlanarDomain};
use super::Film;
use glam::{DVec2, DVec3};
use spade::{
    AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation,
};
use std::collections::HashSet;
use std::f64::consts::TAU;

/// Smallest angle the refinement of the planar domain aims for, degrees.
pub const CDT_MIN_ANGLE_DEG: f64 = 28.0;

/// The coarse mesh of a planar domain: the loops resampled (`pieces`),
/// projected, oriented, triangulated with a constrained Delaunay
/// triangulation refined to triangles of at most `max_area_mm2` in the
/// chart. Interior positions are left at the chart's points on the plane
/// (the harmonic extension replaces them). `None` if spade could not
/// triangulate the loops (they were checked simple and disjoint before).
pub fn planar(
    loops: &[Vec<DVec3>],
    pieces: &[Vec<usize>],
    domain: &PlanarDomain,
    max_area_mm2: f64,
) -> Option<Film> {
    let frame: Frame = domain.frame;
    let rings: Vec<Vec<DVec3>> = loops
        .iter()
        .enumerate()
        .map(|(l, pts)| {
            let mut ring = boundary::resample(pts, &pieces[l]);
            if domain.reversed[l] {
                ring.reverse();
            }
            ring
        })
        .collect();
    let charts: Vec<Vec<DVec2>> = rings
        .iter()
        .map(|r| r.iter().map(|&p| frame.project(p)).collect())
        .collect();
    triangulate(&rings, &charts, max_area_mm2, |q| {
        frame.origin + frame.u * q.x + frame.v * q.y
    })
}

/// The coarse mesh of a disk over a circle: the one loop resampled
/// (`pieces`; reversed when `reversed`, so that it runs as the planar
/// domain orients it) and placed on a circle as long as the loop, each
/// point at the angle 2π × its arc-length fraction, the disk triangulated
/// and refined like [`planar`]'s domain. A film steep over its plan keeps
/// its triangles' shapes over this chart (its arc length is the film's
/// own along the boundary), where the plan's squeeze into slivers.
/// Interior positions are left at the chart's points (the harmonic
/// extension replaces them).
pub fn disk(pts: &[DVec3], pieces: &[usize], reversed: bool, max_area_mm2: f64) -> Option<Film> {
    let mut ring = boundary::resample(pts, pieces);
    if reversed {
        ring.reverse();
    }
    let lengths = boundary::segment_lengths(&ring);
    let total: f64 = lengths.iter().sum();
    if total.is_nan() || total <= 0.0 {
        return None;
    }
    let radius = total / TAU;
    let mut acc = 0.0;
    let chart: Vec<DVec2> = lengths
        .iter()
        .map(|l| {
            let a = TAU * acc / total;
            acc += l;
            DVec2::new(radius * a.cos(), radius * a.sin())
        })
        .collect();
    triangulate(&[ring], &[chart], max_area_mm2, |q| q.extend(0.0))
}

/// The constrained Delaunay triangulation of the domain bounded by
/// `charts` (one ring of chart points per loop, the outer counter-clockwise,
/// holes clockwise; `rings` their 3D points), refined to triangles of at
/// most `max_area_mm2` and angles of at least [`CDT_MIN_ANGLE_DEG`];
/// Steiner points placed at `lift(chart point)`.
fn triangulate(
    rings: &[Vec<DVec3>],
    charts: &[Vec<DVec2>],
    max_area_mm2: f64,
    lift: impl Fn(DVec2) -> DVec3,
) -> Option<Film> {
    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
        ConstrainedDelaunayTriangulation::new();
    let mut positions = Vec::new();
    let mut chart: Vec<DVec2> = Vec::new();
    for (ring, ring_chart) in rings.iter().zip(charts) {
        let mut handles = Vec::with_capacity(ring.len());
        for (&p, &q) in ring.iter().zip(ring_chart) {
            let h = cdt.insert(Point2::new(q.x, q.y)).ok()?;
            if h.index() != positions.len() {
                return None; // two boundary points project onto one
            }
            handles.push(h);
            positions.push(p);
            chart.push(q);
        }
        let n = handles.len();
        for i in 0..n {
            if cdt
                .try_add_constraint(handles[i], handles[(i + 1) % n])
                .is_empty()
            {
                return None;
            }
        }
    }
    let n_boundary = positions.len();
    let result = cdt.refine(
        RefinementParameters::<f64>::new()
            .exclude_outer_faces(true)
            .keep_constraint_edges()
            .with_angle_limit(AngleLimit::from_deg(CDT_MIN_ANGLE_DEG))
            .with_max_allowed_area(max_area_mm2)
            .with_max_additional_vertices(50 * n_boundary + 10_000),
    );
    let excluded: HashSet<usize> = result.excluded_faces.iter().map(|f| f.index()).collect();
    // Faces in spade's order; vertices renumbered: boundary first, then
    // Steiner points in order of first use.
    let mut index: Vec<Option<u32>> = vec![None; cdt.num_vertices()];
    for (i, slot) in index.iter_mut().enumerate().take(n_boundary) {
        *slot = Some(i as u32);
    }
    let mut triangles = Vec::new();
    for f in cdt.inner_faces() {
        if excluded.contains(&f.fix().index()) {
            continue;
        }
        let mut t = [0u32; 3];
        for (k, v) in f.vertices().iter().enumerate() {
            let vi = v.fix().index();
            t[k] = match index[vi] {
                Some(i) => i,
                None => {
                    let i = positions.len() as u32;
                    let p = v.position();
                    let q = DVec2::new(p.x, p.y);
                    chart.push(q);
                    positions.push(lift(q));
                    index[vi] = Some(i);
                    i
                }
            };
        }
        let (a, b, c) = (
            chart[t[0] as usize],
            chart[t[1] as usize],
            chart[t[2] as usize],
        );
        if (b - a).perp_dot(c - a) < 0.0 {
            t.swap(1, 2);
        }
        triangles.push(t);
    }
    let mut fixed = vec![false; positions.len()];
    fixed[..n_boundary].fill(true);
    Some(Film {
        positions,
        chart,
        triangles,
        fixed,
    })
}

/// The coarse loft between two loops resampled to the same count
/// (`pieces` sum to the same number): loop 1 aligned to loop 0 (the cyclic
/// shift and direction of least total distance), `rows` intervals between
/// them, the quads split along alternating diagonals (a checkerboard, so
/// the mesh has no handedness: with one diagonal throughout, the film's
/// asymptotic families bent 4–6 % apart at the rims of a catenoid). Chart:
/// an annulus, loop 0
/// on the inner circle, angle = 2π × arc-length fraction (blended between
/// the loops across the rows), radii scaled so that the mid circle is as
/// long as the loops on average.
pub fn loft(loops: &[Vec<DVec3>], pieces: &[Vec<usize>], h0_mm: f64) -> Film {
    let a = boundary::resample(&loops[0], &pieces[0]);
    let b0 = boundary::resample(&loops[1], &pieces[1]);
    let n = a.len();
    debug_assert_eq!(n, b0.len());
    // Alignment: b[i] = b0[(shift ± i) mod n].
    let mut best = (f64::INFINITY, false, 0usize);
    for rev in [false, true] {
        for shift in 0..n {
            let cost: f64 = (0..n)
                .map(|i| a[i].distance(b0[index_of(shift, i, rev, n)]))
                .sum();
            if cost < best.0 {
                best = (cost, rev, shift);
            }
        }
    }
    let b: Vec<DVec3> = (0..n).map(|i| b0[index_of(best.2, i, best.1, n)]).collect();
    let gap_mm = best.0 / n as f64;
    let rows = ((gap_mm / h0_mm).round() as usize).max(1);
    let fractions = |r: &[DVec3]| -> (Vec<f64>, f64) {
        let len: Vec<f64> = boundary::segment_lengths(r);
        let total: f64 = len.iter().sum();
        let mut acc = 0.0;
        let f = len
            .iter()
            .map(|l| {
                let x = acc / total;
                acc += l;
                x
            })
            .collect();
        (f, total)
    };
    let (fa, la) = fractions(&a);
    let (fb, lb) = fractions(&b);
    let mid_radius = (la + lb) / 2.0 / TAU;
    let inner = (mid_radius - gap_mm / 2.0).max(mid_radius / 2.0);
    let outer = 2.0 * mid_radius - inner;
    let mut positions = Vec::with_capacity(n * (rows + 1));
    let mut chart = Vec::with_capacity(n * (rows + 1));
    for r in 0..=rows {
        let t = r as f64 / rows as f64;
        let radius = inner + (outer - inner) * t;
        for i in 0..n {
            positions.push(a[i].lerp(b[i], t));
            let theta = TAU * ((1.0 - t) * fa[i] + t * fb[i]);
            chart.push(DVec2::new(radius * theta.cos(), radius * theta.sin()));
        }
    }
    let id = |r: usize, i: usize| (r * n + i % n) as u32;
    let mut triangles = Vec::with_capacity(2 * n * rows);
    for r in 0..rows {
        for i in 0..n {
            // Counter-clockwise in the chart: angle grows with i, radius with r.
            let (p00, p10, p11, p01) = (id(r, i), id(r, i + 1), id(r + 1, i + 1), id(r + 1, i));
            if (r + i) % 2 == 0 || n % 2 == 1 {
                triangles.push([p00, p11, p10]);
                triangles.push([p00, p01, p11]);
            } else {
                triangles.push([p00, p01, p10]);
                triangles.push([p10, p01, p11]);
            }
        }
    }
    let mut fixed = vec![false; positions.len()];
    fixed[..n].fill(true);
    fixed[rows * n..].fill(true);
    Film {
        positions,
        chart,
        triangles,
        fixed,
    }
}

fn index_of(shift: usize, i: usize, rev: bool, n: usize) -> usize {
    if rev {
        (shift + n - i % n) % n
    } else {
        (shift + i) % n
    }
}
