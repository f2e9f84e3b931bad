//! A planar chart of a mesh: one (u, v) per vertex in which every triangle
//! keeps its orientation, so the tracer can walk the mesh in a plane.
//!
//! Gridshell meshes are nearly always height fields over some plane, so the
//! first choice is the projection onto the best-fit plane (least-variance
//! normal of the vertices), kept when every triangle stays
//! counter-clockwise with a real area and no two boundary edges cross. A
//! mesh that folds over in every plane (a tube, a deep hood) gets a Tutte
//! embedding with Floater's mean-value weights instead: the boundary on a
//! circle by arc length, each interior vertex the weighted mean of its
//! neighbours (one sparse LU solve), which is injective for a disk
//! (Floater 2003). Annuli have their outer loop on a circle and the inner
//! one on a concentric circle; that map is not guaranteed injective, so it
//! is checked like the projection. Charts are in mm-like units: the
//! projection is in mm, the embedding is scaled to the boundary's length.

use crate::design::mesh::TriMesh;
use crate::geom::eigen::{symmetric_eigen3, Sweeps};
use crate::geom::plane::segments_intersect;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::Mat;
use glam::{DMat3, DVec2, DVec3};
use kurbo::Point;

/// How a chart was made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ChartKind {
    /// Projection onto the best-fit plane.
    Projection,
    /// Tutte embedding with mean-value weights (disk: one boundary loop; annulus: two).
    Embedding,
}

/// A chart: (u, v) per vertex.
#[derive(Debug, Clone)]
pub struct Chart {
    /// (u, v) of each vertex.
    pub uv: Vec<DVec2>,
    /// How it was made.
    pub kind: ChartKind,
}

/// Why no chart could be made.
#[derive(Debug, Clone, PartialEq)]
pub enum ChartError {
    /// The projection folds and the mesh has neither one nor two boundary loops.
    Topology {
        /// Number of boundary loops.
        loops: usize,
    },
    /// Every map tried folds a triangle over.
    Folded {
        /// A triangle that folds, by index.
        triangle: usize,
    },
}

/// Smallest signed area of a chart triangle, relative to the mean
/// triangle area, for the chart to count as unfolded.
pub const MIN_RELATIVE_AREA: f64 = 1e-9;

/// The chart of a mesh given its boundary loops (vertex indices in order,
/// each loop oriented like its triangles).
pub fn make_chart(mesh: &TriMesh, boundary_loops: &[Vec<u32>]) -> Result<Chart, ChartError> {
    if let Some(uv) = unfolded_projection(mesh, boundary_loops) {
        return Ok(Chart {
            uv,
            kind: ChartKind::Projection,
        });
    }
    let uv = match boundary_loops.len() {
        1 | 2 => embedding(mesh, boundary_loops),
        n => return Err(ChartError::Topology { loops: n }),
    };
    match folded_triangle(mesh, &uv) {
        Some(t) => Err(ChartError::Folded { triangle: t }),
        None => Ok(Chart {
            uv,
            kind: ChartKind::Embedding,
        }),
    }
}

/// The projection onto the best-fit plane when it is a chart (no triangle
/// folds, no two boundary edges cross), else None.
pub fn unfolded_projection(mesh: &TriMesh, boundary_loops: &[Vec<u32>]) -> Option<Vec<DVec2>> {
    let projected = projection(mesh);
    (folded_triangle(mesh, &projected).is_none() && !boundary_crosses(&projected, boundary_loops))
        .then_some(projected)
}

/// Vertices projected onto the best-fit plane, the plane's axes chosen so
/// that the triangles are counter-clockwise on the whole (the normal
/// points to the side of the summed triangle normals).
pub fn projection(mesh: &TriMesh) -> Vec<DVec2> {
    let n = mesh.positions_mm.len().max(1) as f64;
    let c = mesh.positions_mm.iter().copied().sum::<DVec3>() / n;
    let mut cov = DMat3::ZERO;
    for p in &mesh.positions_mm {
        let d = *p - c;
        cov += DMat3::from_cols(d * d.x, d * d.y, d * d.z);
    }
    let mut normal = smallest_eigenvector(cov);
    let area_normal: DVec3 = mesh
        .triangles
        .iter()
        .map(|t| {
            let [a, b, cc] = t.map(|i| mesh.positions_mm[i as usize]);
            (b - a).cross(cc - a)
        })
        .sum();
    if normal.dot(area_normal) < 0.0 {
        normal = -normal;
    }
    let e1 = normal.any_orthonormal_vector();
    let e2 = normal.cross(e1);
    mesh.positions_mm
        .iter()
        .map(|p| DVec2::new((*p - c).dot(e1), (*p - c).dot(e2)))
        .collect()
}

/// Unit eigenvector of the smallest eigenvalue of a symmetric 3×3 matrix
/// (Jacobi rotations down to 1e-300; exact enough for a plane fit).
fn smallest_eigenvector(m: DMat3) -> DVec3 {
    let (values, v) = symmetric_eigen3(
        m.transpose().to_cols_array_2d(),
        Sweeps {
            relative: 0.0,
            negligible: 1e-300,
        },
    );
    let k = (0..3)
        .min_by(|&i, &j| values[i].total_cmp(&values[j]))
        .unwrap_or(2);
    DVec3::new(v[0][k], v[1][k], v[2][k]).normalize_or(DVec3::Z)
}

/// Signed area of a chart triangle (positive: counter-clockwise).
pub fn chart_area(uv: &[DVec2], t: [u32; 3]) -> f64 {
    let [a, b, c] = t.map(|i| uv[i as usize]);
    0.5 * (b - a).perp_dot(c - a)
}

/// The first triangle whose chart area is not clearly positive.
pub fn folded_triangle(mesh: &TriMesh, uv: &[DVec2]) -> Option<usize> {
    let total: f64 = mesh.triangles.iter().map(|t| chart_area(uv, *t)).sum();
    let floor = MIN_RELATIVE_AREA * total.abs() / mesh.triangles.len().max(1) as f64;
    mesh.triangles
        .iter()
        .position(|t| chart_area(uv, *t).partial_cmp(&floor) != Some(std::cmp::Ordering::Greater))
}

/// Whether two boundary edges of the chart cross (the projection of a mesh
/// whose rim overlaps itself in plan).
fn boundary_crosses(uv: &[DVec2], loops: &[Vec<u32>]) -> bool {
    let edges: Vec<(u32, u32)> = loops
        .iter()
        .flat_map(|l| (0..l.len()).map(move |i| (l[i], l[(i + 1) % l.len()])))
        .collect();
    // Sort by the lower x of each edge and sweep.
    let mut order: Vec<usize> = (0..edges.len()).collect();
    let lo = |e: (u32, u32)| uv[e.0 as usize].x.min(uv[e.1 as usize].x);
    let hi = |e: (u32, u32)| uv[e.0 as usize].x.max(uv[e.1 as usize].x);
    order.sort_by(|&a, &b| lo(edges[a]).total_cmp(&lo(edges[b])));
    for (k, &i) in order.iter().enumerate() {
        let e = edges[i];
        for &j in &order[k + 1..] {
            let f = edges[j];
            if lo(f) > hi(e) {
                break;
            }
            if e.0 == f.0 || e.0 == f.1 || e.1 == f.0 || e.1 == f.1 {
                continue;
            }
            let [a, b, c, d] = [e.0, e.1, f.0, f.1].map(|v| {
                let q = uv[v as usize];
                Point::new(q.x, q.y)
            });
            // Closed segments: touching and collinear overlap count as
            // crossing (a rim in doubt is not charted by projection), but
            // two collinear edges apart (one straight side of the rim) do not.
            if segments_intersect(a, b, c, d) {
                return true;
            }
        }
    }
    false
}

/// Tutte embedding with mean-value weights: the longest loop on a circle
/// by arc length, a second loop on a concentric circle of radius in
/// proportion to its length.
fn embedding(mesh: &TriMesh, loops: &[Vec<u32>]) -> Vec<DVec2> {
    let nv = mesh.positions_mm.len();
    let p = &mesh.positions_mm;
    let mut fixed: Vec<Option<DVec2>> = vec![None; nv];
    let loop_len = |l: &Vec<u32>| -> f64 {
        (0..l.len())
            .map(|i| p[l[i] as usize].distance(p[l[(i + 1) % l.len()] as usize]))
            .sum()
    };
    let mut order: Vec<usize> = (0..loops.len()).collect();
    order.sort_by(|&a, &b| loop_len(&loops[b]).total_cmp(&loop_len(&loops[a])));
    let outer_len = loop_len(&loops[order[0]]);
    let radius_outer = outer_len / std::f64::consts::TAU;
    for (rank, &li) in order.iter().enumerate() {
        let l = &loops[li];
        let len = loop_len(l);
        let radius = if rank == 0 {
            radius_outer
        } else {
            // An inner loop as a concentric circle, clockwise (it bounds a hole).
            (len / std::f64::consts::TAU).min(0.5 * radius_outer)
        };
        let mut s = 0.0;
        for i in 0..l.len() {
            let angle = std::f64::consts::TAU * s / len;
            let angle = if rank == 0 { angle } else { -angle };
            fixed[l[i] as usize] = Some(DVec2::new(angle.cos(), angle.sin()) * radius);
            s += p[l[i] as usize].distance(p[l[(i + 1) % l.len()] as usize]);
        }
    }
    // Mean-value weights w_ij = (tan(α/2) + tan(β/2)) / |x_i − x_j| over
    // the two angles at i beside edge ij.
    let mut weights: std::collections::BTreeMap<(u32, u32), f64> = Default::default();
    for t in &mesh.triangles {
        for k in 0..3 {
            let (i, j, l) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            let (xi, xj, xl) = (p[i as usize], p[j as usize], p[l as usize]);
            let (a, b) = (xj - xi, xl - xi);
            let angle = a.angle_between(b);
            let half_tan = (0.5 * angle).tan();
            *weights.entry((i, j)).or_default() += half_tan / a.length().max(1e-300);
            *weights.entry((i, l)).or_default() += half_tan / b.length().max(1e-300);
        }
    }
    let free: Vec<usize> = (0..nv).filter(|&v| fixed[v].is_none()).collect();
    let mut slot = vec![usize::MAX; nv];
    for (k, &v) in free.iter().enumerate() {
        slot[v] = k;
    }
    let n = free.len();
    let mut uv: Vec<DVec2> = fixed.iter().map(|f| f.unwrap_or(DVec2::ZERO)).collect();
    if n == 0 {
        return uv;
    }
    let mut triplets = Vec::new();
    let mut rhs = vec![DVec2::ZERO; n];
    let mut diag = vec![0.0; n];
    for (&(i, j), &w) in &weights {
        let si = slot[i as usize];
        if si == usize::MAX {
            continue;
        }
        diag[si] += w;
        match fixed[j as usize] {
            Some(q) => rhs[si] += q * w,
            None => triplets.push(Triplet::new(si, slot[j as usize], -w)),
        }
    }
    for (k, d) in diag.iter().enumerate() {
        triplets.push(Triplet::new(k, k, *d));
    }
    let solved = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets)
        .ok()
        .and_then(|a| a.sp_lu().ok())
        .map(|lu| {
            let mut b = Mat::<f64>::from_fn(n, 2, |i, c| if c == 0 { rhs[i].x } else { rhs[i].y });
            lu.solve_in_place(b.as_mut());
            b
        });
    if let Some(b) = solved {
        for (k, &v) in free.iter().enumerate() {
            uv[v] = DVec2::new(b[(k, 0)], b[(k, 1)]);
        }
    }
    uv
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A (n+1)² grid over [0, 1]² mapped by `f`, two triangles per cell.
    pub(crate) fn grid(n: usize, f: impl Fn(f64, f64) -> DVec3) -> TriMesh {
        let mut positions_mm = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                positions_mm.push(f(i as f64 / n as f64, j as f64 / n as f64));
            }
        }
        let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
        let mut triangles = Vec::new();
        for j in 0..n {
            for i in 0..n {
                triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        TriMesh {
            positions_mm,
            triangles,
        }
    }

    fn square_loop(n: usize) -> Vec<u32> {
        let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
        let mut l = Vec::new();
        l.extend((0..n).map(|i| id(i, 0)));
        l.extend((0..n).map(|j| id(n, j)));
        l.extend((0..n).map(|i| id(n - i, n)));
        l.extend((0..n).map(|j| id(0, n - j)));
        l
    }

    #[test]
    fn a_height_field_is_charted_by_its_projection() {
        let m = grid(8, |u, v| DVec3::new(1000.0 * u, 1000.0 * v, 300.0 * u * v));
        let c = make_chart(&m, &[square_loop(8)]).unwrap();
        assert_eq!(c.kind, ChartKind::Projection);
        // The projection keeps in-plane distances of a nearly flat mesh: the
        // x extent is 1000 mm, tilted by at most atan(0.3).
        let w = c.uv.iter().map(|q| q.length()).fold(0.0, f64::max);
        assert!(w > 600.0 && w < 800.0, "{w}");
        assert!(folded_triangle(&m, &c.uv).is_none());
    }

    /// A rim with straight sides (a regular grid, exported at 0.001 mm)
    /// has collinear boundary edges: apart, they do not cross, and the
    /// height field keeps its projection even when a side lies exactly
    /// along a chart axis. Collinear edges that overlap or touch still do.
    #[test]
    fn straight_rim_sides_do_not_cross_but_overlapping_ones_do() {
        let n = 6;
        let flat = grid(n, |u, v| DVec3::new(1000.0 * u, 1000.0 * v, 0.0));
        let uv: Vec<DVec2> = flat.positions_mm.iter().map(|p| p.truncate()).collect();
        let rim = square_loop(n);
        assert!(!boundary_crosses(&uv, std::slice::from_ref(&rim)));
        // The rim's last vertex moved onto its first side (the rim folds
        // back along it): two collinear edges overlap.
        let mut folded = uv.clone();
        folded[rim[rim.len() - 1] as usize] = DVec2::new(500.0, 0.0);
        assert!(boundary_crosses(&folded, std::slice::from_ref(&rim)));
        // A saddle symmetric under x ↔ y with z ↦ −z: its best-fit normal
        // is exactly z, so the sides are exactly vertical or horizontal in
        // the chart.
        let saddle = grid(n, |u, v| {
            let (x, y) = (1000.0 * u - 500.0, 1000.0 * v - 500.0);
            DVec3::new(x, y, (x * x - y * y) / 6000.0)
        });
        let c = make_chart(&saddle, &[rim]).unwrap();
        assert_eq!(c.kind, ChartKind::Projection);
    }

    #[test]
    fn a_folded_disk_gets_an_injective_embedding() {
        // A hood: a strip bent through 300° about the y axis, so every
        // projection folds it.
        let m = grid(12, |u, v| {
            let a = (u - 0.5) * 300f64.to_radians();
            DVec3::new(500.0 * a.sin(), 800.0 * v, 500.0 * a.cos())
        });
        assert!(folded_triangle(&m, &projection(&m)).is_some());
        let c = make_chart(&m, &[square_loop(12)]).unwrap();
        assert_eq!(c.kind, ChartKind::Embedding);
        // Every interior vertex is the mean-value average of its
        // neighbours, and the boundary lies on a circle of the rim's length.
        let rim: f64 = {
            let l = square_loop(12);
            (0..l.len())
                .map(|i| {
                    m.positions_mm[l[i] as usize]
                        .distance(m.positions_mm[l[(i + 1) % l.len()] as usize])
                })
                .sum()
        };
        let r = rim / std::f64::consts::TAU;
        for &v in &square_loop(12) {
            assert!((c.uv[v as usize].length() - r).abs() < 1e-9 * r);
        }
    }

    #[test]
    fn smallest_eigenvector_of_a_diagonal_and_a_rotated_matrix() {
        let d = DMat3::from_diagonal(DVec3::new(3.0, 1.0, 2.0));
        assert!((smallest_eigenvector(d).abs() - DVec3::Y).length() < 1e-12);
        let r = DMat3::from_rotation_x(0.3) * DMat3::from_rotation_z(0.7);
        let m = r * d * r.transpose();
        let e = smallest_eigenvector(m);
        assert!((e.dot(r * DVec3::Y)).abs() > 1.0 - 1e-12);
    }
}
