//! The connectivity of a triangle mesh, validated: an oriented, connected
//! 2-manifold (with or without boundary), with per-vertex ordered one-rings,
//! boundary loops and angle-weighted vertex normals.
//!
//! [`Topology::build`] checks, in this order, and stops at the first problem
//! with a one-line error naming the element (indices count from 0 in the
//! file's vertex and face order; positions in mm to 3 decimals):
//!
//! 1. at least one triangle, and every index names a vertex;
//! 2. finite coordinates;
//! 3. no degenerate triangle: no repeated index, and area at least
//!    1e-12 × (bounding-box diagonal)²;
//! 4. manifold edges (at most 2 triangles on an edge);
//! 5. manifold vertices (the triangles around a vertex form one fan);
//! 6. one connected piece;
//! 7. orientable: triangles traversing a shared edge the same way are
//!    flipped, by a breadth-first walk from triangle 0, so that neighbours
//!    agree; the orientation the majority of the triangles had is kept (that
//!    of triangle 0 on a tie). A non-orientable mesh (a Möbius strip) is an
//!    error.
//!
//! Vertices no triangle uses are dropped: the cleaned mesh is
//! [`Topology::mesh`], and [`Topology::source_vertex`] maps its vertices back
//! to the input's. Everything downstream uses the cleaned mesh.

use super::TriMesh;
use crate::error::{Error, Location, Result};
use glam::DVec3;
use rayon::prelude::*;
use std::collections::VecDeque;
use std::path::Path;

/// Relative area below which a triangle is degenerate: area < this ×
/// (bounding-box diagonal)².
pub const DEGENERATE_AREA_REL: f64 = 1e-12;

/// A validated, oriented, connected triangle mesh and its adjacency.
#[derive(Debug, Clone)]
pub struct Topology {
    mesh: TriMesh,
    source_vertex: Vec<u32>,
    flipped: Vec<u32>,
    dropped: usize,
    ring_start: Vec<u32>,
    ring_vertices: Vec<u32>,
    fan_start: Vec<u32>,
    fan_triangles: Vec<u32>,
    boundary: Vec<bool>,
    loops: Vec<Vec<u32>>,
    edge_count: usize,
}

/// `(x, y, z)` in mm to 3 decimals.
pub fn fmt_point(p: DVec3) -> String {
    format!("({:.3}, {:.3}, {:.3})", p.x, p.y, p.z)
}

/// `vertex 7 at (x, y, z) mm`.
fn vertex_at(v: u32, p: DVec3) -> Location {
    Location::Element(format!("vertex {v} at {} mm", fmt_point(p)))
}

impl Topology {
    /// Validate `mesh` (read from `path`, named in errors) and build its
    /// topology; see the module documentation for the checks.
    pub fn build(mesh: &TriMesh, path: &Path) -> Result<Topology> {
        let pos = &mesh.positions_mm;
        let tris = &mesh.triangles;
        if tris.is_empty() {
            return Err(Error::input(
                path,
                Location::File,
                "the mesh has no triangles",
            ));
        }
        let n_in = pos.len();
        for (t, tri) in tris.iter().enumerate() {
            if let Some(&k) = tri.iter().find(|&&k| k as usize >= n_in) {
                return Err(Error::input(
                    path,
                    Location::Element(format!("triangle {t}")),
                    format!("vertex index {k} out of range (0..={})", n_in as i64 - 1),
                ));
            }
        }
        if let Some((v, _)) = pos.iter().enumerate().find(|(_, p)| !p.is_finite()) {
            return Err(Error::input(
                path,
                Location::Element(format!("vertex {v}")),
                "a coordinate is not finite",
            ));
        }
        if let Some((v, p)) = pos
            .iter()
            .enumerate()
            .find(|(_, p)| p.abs().max_element() > MAX_COORDINATE_MM)
        {
            return Err(Error::input(
                path,
                Location::Element(format!("vertex {v}")),
                format!(
                    "a coordinate is {:.3e} mm, beyond ±{MAX_COORDINATE_MM:.0e} mm (a wrong unit or a stray point?)",
                    p.abs().max_element()
                ),
            ));
        }
        check_degenerate(mesh, path)?;

        // Drop unreferenced vertices (keeping the order of the rest).
        let mut new_index = vec![u32::MAX; n_in];
        for tri in tris {
            for &k in tri {
                new_index[k as usize] = 0;
            }
        }
        let mut source_vertex = Vec::new();
        for (v, slot) in new_index.iter_mut().enumerate() {
            if *slot == 0 {
                *slot = source_vertex.len() as u32;
                source_vertex.push(v as u32);
            }
        }
        let positions: Vec<DVec3> = source_vertex.iter().map(|&v| pos[v as usize]).collect();
        let mut triangles: Vec<[u32; 3]> = tris
            .iter()
            .map(|t| t.map(|k| new_index[k as usize]))
            .collect();
        let nv = positions.len();
        // Names in errors use the input's vertex numbers.
        let name_vertex = |v: u32| vertex_at(source_vertex[v as usize], positions[v as usize]);
        let name_edge = |a: u32, b: u32| {
            let (sa, sb) = (source_vertex[a as usize], source_vertex[b as usize]);
            let mid = 0.5 * (positions[a as usize] + positions[b as usize]);
            Location::Element(format!(
                "edge {}–{} at {} mm",
                sa.min(sb),
                sa.max(sb),
                fmt_point(mid)
            ))
        };

        let half = sorted_edges(&triangles, nv);
        // Per triangle and corner i: the triangle across edge (tri[i], tri[i+1]).
        let mut across = vec![[u32::MAX; 3]; triangles.len()];
        let mut edge_count = 0;
        let mut i = 0;
        while i < half.len() {
            let (a, b, _) = half[i];
            let mut j = i;
            while j < half.len() && half[j].0 == a && half[j].1 == b {
                j += 1;
            }
            if j - i > 2 {
                return Err(Error::input(
                    path,
                    name_edge(a, b),
                    format!(
                        "the edge is shared by {} triangles (non-manifold edge; at most 2 may share one)",
                        j - i
                    ),
                ));
            }
            if j - i == 2 {
                let (t, u) = (half[i].2, half[i + 1].2);
                across[t as usize][corner_of_edge(&triangles[t as usize], a, b)] = u;
                across[u as usize][corner_of_edge(&triangles[u as usize], a, b)] = t;
            }
            edge_count += 1;
            i = j;
        }

        // Triangles around each vertex (CSR), in triangle order.
        let (inc_start, inc) = incidence(&triangles, nv);
        // The first vertex (in order) whose triangles form more than one fan.
        let several = (0..nv)
            .into_par_iter()
            .map(|v| {
                let around = &inc[inc_start[v]..inc_start[v + 1]];
                (v, count_fans(&triangles, around, v as u32))
            })
            .find_first(|&(_, fans)| fans > 1);
        if let Some((v, fans)) = several {
            return Err(Error::input(
                path,
                name_vertex(v as u32),
                format!(
                    "the triangles around the vertex form {fans} separate fans (non-manifold vertex)"
                ),
            ));
        }

        // Connected pieces and orientation, by one breadth-first walk per piece.
        let mut flip: Vec<Option<bool>> = vec![None; triangles.len()];
        let mut pieces = 0usize;
        let mut second_piece_triangle = None;
        for seed in 0..triangles.len() {
            if flip[seed].is_some() {
                continue;
            }
            pieces += 1;
            if pieces == 2 {
                second_piece_triangle = Some(seed);
            }
            flip[seed] = Some(false);
            let mut queue = VecDeque::from([seed]);
            while let Some(t) = queue.pop_front() {
                let ft = flip[t].unwrap_or(false);
                for (c, &u) in across[t].iter().enumerate() {
                    if u == u32::MAX {
                        continue;
                    }
                    let u = u as usize;
                    let (a, b) = (triangles[t][c], triangles[t][(c + 1) % 3]);
                    // u must traverse the edge b→a when t (as flipped) traverses a→b.
                    let same_way = traverses(&triangles[u], a, b);
                    let want = ft ^ same_way;
                    match flip[u] {
                        None => {
                            flip[u] = Some(want);
                            queue.push_back(u);
                        }
                        Some(f) if f != want => {
                            return Err(Error::input(
                                path,
                                name_edge(a, b),
                                format!(
                                    "the mesh is not orientable (a Möbius strip): triangles {t} and {u} on this edge cannot be oriented consistently"
                                ),
                            ));
                        }
                        Some(_) => {}
                    }
                }
            }
        }
        if let Some(t) = second_piece_triangle {
            let v = triangles[t][0];
            return Err(Error::input(
                path,
                Location::File,
                format!(
                    "the mesh has {pieces} separate pieces (edge-connected); the second contains {}: keep one surface per file",
                    name_vertex(v)
                ),
            ));
        }
        let flips: Vec<bool> = flip.iter().map(|f| f.unwrap_or(false)).collect();
        let n_flip = flips.iter().filter(|&&f| f).count();
        // Keep the majority's orientation.
        let invert = 2 * n_flip > triangles.len();
        let mut flipped = Vec::new();
        for (t, &f) in flips.iter().enumerate() {
            if f != invert {
                triangles[t].swap(1, 2);
                flipped.push(t as u32);
            }
        }

        // Ordered one-rings.
        let mut ring_start = Vec::with_capacity(nv + 1);
        let mut fan_start = Vec::with_capacity(nv + 1);
        let mut ring_vertices = Vec::new();
        let mut fan_triangles = Vec::new();
        let mut boundary = vec![false; nv];
        ring_start.push(0u32);
        fan_start.push(0u32);
        let mut steps: Vec<(u32, u32, u32)> = Vec::new();
        for v in 0..nv {
            let around = &inc[inc_start[v]..inc_start[v + 1]];
            // (a, b, t) with triangle t = (v, a, b) counter-clockwise.
            steps.clear();
            steps.extend(around.iter().map(|&t| {
                let tri = triangles[t as usize];
                let k = tri.iter().position(|&x| x == v as u32).unwrap_or(0);
                (tri[(k + 1) % 3], tri[(k + 2) % 3], t)
            }));
            // A boundary vertex's fan starts at the `a` that is no step's `b`.
            let start = steps
                .iter()
                .position(|s| !steps.iter().any(|o| o.1 == s.0))
                .unwrap_or(0);
            boundary[v] = steps.iter().any(|s| !steps.iter().any(|o| o.1 == s.0));
            let mut cur = start;
            ring_vertices.push(steps[cur].0);
            for _ in 0..steps.len() {
                fan_triangles.push(steps[cur].2);
                let b = steps[cur].1;
                match steps.iter().position(|o| o.0 == b) {
                    Some(next) if next != start => {
                        ring_vertices.push(b);
                        cur = next;
                    }
                    _ => {
                        if boundary[v] {
                            ring_vertices.push(b);
                        }
                        break;
                    }
                }
            }
            ring_start.push(ring_vertices.len() as u32);
            fan_start.push(fan_triangles.len() as u32);
        }

        // Boundary loops: each boundary vertex's outgoing boundary edge runs
        // to the first vertex of its ring.
        let mut loops = Vec::new();
        let mut seen = vec![false; nv];
        for v0 in 0..nv {
            if !boundary[v0] || seen[v0] {
                continue;
            }
            let mut lp = Vec::new();
            let mut v = v0;
            while !seen[v] {
                seen[v] = true;
                lp.push(v as u32);
                v = ring_vertices[ring_start[v] as usize] as usize;
            }
            loops.push(lp);
        }

        Ok(Topology {
            mesh: TriMesh {
                positions_mm: positions,
                triangles,
            },
            source_vertex,
            flipped,
            dropped: n_in - nv,
            ring_start,
            ring_vertices,
            fan_start,
            fan_triangles,
            boundary,
            loops,
            edge_count,
        })
    }

    /// The cleaned mesh: unreferenced vertices dropped, triangles oriented
    /// consistently (counter-clockwise seen from the normals' side).
    pub fn mesh(&self) -> &TriMesh {
        &self.mesh
    }
    /// Number of vertices of the cleaned mesh.
    pub fn vertex_count(&self) -> usize {
        self.mesh.positions_mm.len()
    }
    /// The input's index of a cleaned vertex.
    pub fn source_vertex(&self, v: u32) -> u32 {
        self.source_vertex[v as usize]
    }
    /// Input triangles that were flipped to agree with their neighbours.
    pub fn flipped_triangles(&self) -> &[u32] {
        &self.flipped
    }
    /// How many unreferenced vertices were dropped.
    pub fn dropped_vertices(&self) -> usize {
        self.dropped
    }
    /// The neighbours of `v` in counter-clockwise order around its normal;
    /// at a boundary vertex the first and last are on the boundary (the
    /// boundary runs last → v → first).
    pub fn neighbours(&self, v: u32) -> &[u32] {
        let v = v as usize;
        &self.ring_vertices[self.ring_start[v] as usize..self.ring_start[v + 1] as usize]
    }
    /// The triangles around `v`, in the same order: triangle i has corners
    /// v, neighbours\[i\], neighbours\[i + 1\] (cyclically at an interior vertex).
    pub fn triangles_around(&self, v: u32) -> &[u32] {
        let v = v as usize;
        &self.fan_triangles[self.fan_start[v] as usize..self.fan_start[v + 1] as usize]
    }
    /// Whether `v` is on the boundary.
    pub fn is_boundary(&self, v: u32) -> bool {
        self.boundary[v as usize]
    }
    /// The boundary loops, each in the direction its triangles traverse it
    /// (the surface on the left, seen from the normals' side), each starting
    /// at its lowest vertex, in order of that vertex.
    pub fn boundary_loops(&self) -> &[Vec<u32>] {
        &self.loops
    }
    /// Number of edges.
    pub fn edge_count(&self) -> usize {
        self.edge_count
    }
    /// Euler characteristic V − E + F (1 for a disk, 0 for an annulus, 2
    /// for a sphere).
    pub fn euler_characteristic(&self) -> i64 {
        self.vertex_count() as i64 - self.edge_count as i64 + self.mesh.triangles.len() as i64
    }
    /// Unit vertex normals: the triangles' normals weighted by their angles
    /// at the vertex (Thürmer & Wüthrich), on the side the triangles'
    /// counter-clockwise order points to.
    pub fn vertex_normals(&self) -> Vec<DVec3> {
        let p = &self.mesh.positions_mm;
        (0..self.vertex_count() as u32)
            .into_par_iter()
            .map(|v| {
                let mut n = DVec3::ZERO;
                for &t in self.triangles_around(v) {
                    let tri = self.mesh.triangles[t as usize];
                    let k = tri.iter().position(|&x| x == v).unwrap_or(0);
                    let (a, b, c) = (
                        p[v as usize],
                        p[tri[(k + 1) % 3] as usize],
                        p[tri[(k + 2) % 3] as usize],
                    );
                    let (e1, e2) = (b - a, c - a);
                    let face = e1.cross(e2).normalize_or_zero();
                    n += face * e1.angle_between(e2);
                }
                n.normalize_or_zero()
            })
            .collect()
    }
    /// Notes on what was repaired, one line each (flipped triangles,
    /// dropped vertices); empty when nothing was.
    pub fn warnings(&self) -> Vec<String> {
        let mut w = Vec::new();
        if !self.flipped.is_empty() {
            w.push(format!(
                "{} triangle(s) were flipped to agree with their neighbours (the first: triangle {})",
                self.flipped.len(),
                self.flipped[0]
            ));
        }
        if self.dropped > 0 {
            w.push(format!(
                "{} vertex(es) used by no triangle were dropped",
                self.dropped
            ));
        }
        w
    }
}

/// The corner i of `tri` whose edge (tri\[i\], tri\[i+1\]) is {a, b}.
fn corner_of_edge(tri: &[u32; 3], a: u32, b: u32) -> usize {
    (0..3)
        .find(|&i| {
            let (x, y) = (tri[i], tri[(i + 1) % 3]);
            (x == a && y == b) || (x == b && y == a)
        })
        .unwrap_or(0)
}

/// Whether `tri` traverses a→b.
fn traverses(tri: &[u32; 3], a: u32, b: u32) -> bool {
    (0..3).any(|i| tri[i] == a && tri[(i + 1) % 3] == b)
}

/// Every triangle's edges as (low vertex, high vertex, triangle), sorted:
/// bucketed by the low vertex (a counting sort), each bucket (the edges
/// from one vertex, a dozen) sorted on its own.
fn sorted_edges(triangles: &[[u32; 3]], nv: usize) -> Vec<(u32, u32, u32)> {
    let edges = triangles.iter().enumerate().flat_map(|(t, tri)| {
        (0..3).map(move |i| {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            (a.min(b) as usize, (a.min(b), a.max(b), t as u32))
        })
    });
    let (start, mut half) = crate::geom::mesh::bucketed(nv, edges);
    for v in 0..nv {
        half[start[v]..start[v + 1]].sort_unstable();
    }
    half
}

/// The largest |coordinate| a mesh may have, mm: a thousand kilometres.
/// Squared distances and areas then stay far from overflow, which the
/// curvature fits and their weights rely on.
pub const MAX_COORDINATE_MM: f64 = 1e9;

/// Triangles around each vertex in CSR form (start offsets, triangle ids).
fn incidence(triangles: &[[u32; 3]], nv: usize) -> (Vec<usize>, Vec<u32>) {
    crate::geom::mesh::bucketed(
        nv,
        triangles
            .iter()
            .enumerate()
            .flat_map(|(t, tri)| tri.iter().map(move |&k| (k as usize, t as u32))),
    )
}

/// How many fans the triangles `around` vertex `v` form: triangles sharing
/// an edge (v, w) are in one fan. Orientation-free.
fn count_fans(triangles: &[[u32; 3]], around: &[u32], v: u32) -> usize {
    // On the stack for the usual vertex (up to 16 triangles).
    const SMALL: usize = 16;
    let n = around.len();
    if n <= SMALL {
        let (mut parent, mut spokes) = ([0usize; SMALL], [(0u32, 0usize); 2 * SMALL]);
        fans_in(triangles, around, v, &mut parent[..n], &mut spokes[..2 * n])
    } else {
        fans_in(
            triangles,
            around,
            v,
            &mut vec![0; n],
            &mut vec![(0, 0); 2 * n],
        )
    }
}

/// [`count_fans`] in the buffers `parent` (one per triangle) and `spokes`
/// (two per triangle: its vertices besides `v`, which a triangle that is
/// not degenerate has).
fn fans_in(
    triangles: &[[u32; 3]],
    around: &[u32],
    v: u32,
    parent: &mut [usize],
    spokes: &mut [(u32, usize)],
) -> usize {
    fn find(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for (i, p) in parent.iter_mut().enumerate() {
        *p = i;
    }
    // (w, local triangle) pairs; triangles with the same w share edge (v, w).
    let mut k = 0;
    for (i, &t) in around.iter().enumerate() {
        for &w in &triangles[t as usize] {
            if w != v && k < spokes.len() {
                spokes[k] = (w, i);
                k += 1;
            }
        }
    }
    let spokes = &mut spokes[..k];
    spokes.sort_unstable();
    for pair in spokes.windows(2) {
        if pair[0].0 == pair[1].0 {
            let (a, b) = (find(parent, pair[0].1), find(parent, pair[1].1));
            parent[a] = b;
        }
    }
    (0..parent.len()).filter(|&i| find(parent, i) == i).count()
}

/// Degenerate triangles: a repeated vertex, or (near) zero area.
fn check_degenerate(mesh: &TriMesh, path: &Path) -> Result<()> {
    let pos = &mesh.positions_mm;
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for tri in &mesh.triangles {
        for &k in tri {
            lo = lo.min(pos[k as usize]);
            hi = hi.max(pos[k as usize]);
        }
    }
    let min_area = DEGENERATE_AREA_REL * (hi - lo).length_squared();
    for (t, &[a, b, c]) in mesh.triangles.iter().enumerate() {
        let at =
            |what: String| Error::input(path, Location::Element(format!("triangle {t}")), what);
        if a == b || b == c || a == c {
            let r = if a == b || a == c { a } else { b };
            return Err(at(format!(
                "vertices {a}, {b}, {c}: the triangle repeats vertex {r} (degenerate)"
            )));
        }
        let (pa, pb, pc) = (pos[a as usize], pos[b as usize], pos[c as usize]);
        let area = 0.5 * (pb - pa).cross(pc - pa).length();
        if area < min_area || area == 0.0 {
            return Err(at(format!(
                "vertices {a}, {b}, {c} at {} mm: zero area ({area:.3e} mm², below {:.0e} × the bounding box diagonal²; the corners are collinear)",
                fmt_point((pa + pb + pc) / 3.0),
                DEGENERATE_AREA_REL
            )));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::mesh::samples;

    fn build(m: &TriMesh) -> Result<Topology> {
        Topology::build(m, Path::new("m.obj"))
    }
    fn err(m: &TriMesh) -> String {
        match build(m) {
            Ok(_) => panic!("expected an error"),
            Err(e) => e.to_string(),
        }
    }
    fn mesh(p: &[[f64; 3]], t: &[[u32; 3]]) -> TriMesh {
        TriMesh {
            positions_mm: p.iter().map(|&a| DVec3::from_array(a)).collect(),
            triangles: t.to_vec(),
        }
    }
    /// Signed area of a loop in the xy plane.
    fn signed_area(m: &TriMesh, lp: &[u32]) -> f64 {
        let mut a = 0.0;
        for i in 0..lp.len() {
            let p = m.positions_mm[lp[i] as usize];
            let q = m.positions_mm[lp[(i + 1) % lp.len()] as usize];
            a += 0.5 * (p.x * q.y - q.x * p.y);
        }
        a
    }

    #[test]
    fn disk_has_one_counter_clockwise_loop() {
        let (m, _) = samples::polar(0.0, 10.0, 4, 12, 0.3, 7);
        let topo = build(&m).expect("valid");
        assert_eq!(topo.euler_characteristic(), 1);
        assert_eq!(topo.boundary_loops().len(), 1);
        let lp = &topo.boundary_loops()[0];
        assert_eq!(lp.len(), 12);
        // The disk's rim, counter-clockwise like the triangles: the inscribed
        // 12-gon's area 3 r² (up to the 0.001 mm rounding).
        assert!((signed_area(topo.mesh(), lp) - 300.0).abs() < 0.05);
        for &v in lp {
            assert!(topo.is_boundary(v));
            assert_eq!(topo.neighbours(v).len(), topo.triangles_around(v).len() + 1);
        }
        // The centre: interior, its ring the 12 first-ring vertices in
        // counter-clockwise order.
        assert!(!topo.is_boundary(0));
        let ring = topo.neighbours(0);
        assert_eq!(ring.len(), 12);
        let ang: Vec<f64> = ring
            .iter()
            .map(|&w| {
                let p = topo.mesh().positions_mm[w as usize];
                p.y.atan2(p.x)
            })
            .collect();
        for i in 0..12 {
            let d = (ang[(i + 1) % 12] - ang[i]).rem_euclid(std::f64::consts::TAU);
            assert!(d > 0.0 && d < std::f64::consts::PI, "step {i}: {d}");
        }
        for (i, &t) in topo.triangles_around(0).iter().enumerate() {
            let tri = topo.mesh().triangles[t as usize];
            let (a, b) = (ring[i], ring[(i + 1) % 12]);
            assert!(traverses(&tri, 0, a) && traverses(&tri, a, b), "{tri:?}");
        }
        // Normals of a flat disk: +z.
        for n in topo.vertex_normals() {
            assert!((n - DVec3::Z).length() < 1e-12);
        }
    }

    #[test]
    fn annulus_has_two_loops_outer_ccw_inner_cw() {
        let (m, _) = samples::polar(5.0, 10.0, 3, 16, 0.3, 3);
        let topo = build(&m).expect("valid");
        assert_eq!(topo.euler_characteristic(), 0);
        let loops = topo.boundary_loops();
        assert_eq!(loops.len(), 2);
        let areas: Vec<f64> = loops.iter().map(|l| signed_area(topo.mesh(), l)).collect();
        // Inscribed 16-gons: 16/2 · r² · sin(2π/16).
        let polygon = |r: f64| 8.0 * r * r * (std::f64::consts::TAU / 16.0).sin();
        // Loop 0 starts at vertex 0, on the inner circle: clockwise.
        assert!((areas[0] + polygon(5.0)).abs() < 0.05, "{areas:?}");
        assert!((areas[1] - polygon(10.0)).abs() < 0.05, "{areas:?}");
        assert!(topo.warnings().is_empty());
    }

    #[test]
    fn closed_sphere_has_euler_two_and_no_boundary() {
        // An octahedron.
        let m = mesh(
            &[
                [1., 0., 0.],
                [-1., 0., 0.],
                [0., 1., 0.],
                [0., -1., 0.],
                [0., 0., 1.],
                [0., 0., -1.],
            ],
            &[
                [0, 2, 4],
                [2, 1, 4],
                [1, 3, 4],
                [3, 0, 4],
                [2, 0, 5],
                [1, 2, 5],
                [3, 1, 5],
                [0, 3, 5],
            ],
        );
        let topo = build(&m).expect("valid");
        assert_eq!(topo.euler_characteristic(), 2);
        assert!(topo.boundary_loops().is_empty());
        // Outward normals: along the position.
        for (n, p) in topo.vertex_normals().iter().zip(&m.positions_mm) {
            assert!((*n - *p).length() < 1e-12, "{n} {p}");
        }
    }

    #[test]
    fn inconsistent_triangles_are_flipped_to_the_majority() {
        let (mut m, _) = samples::polar(0.0, 10.0, 3, 8, 0.2, 1);
        let good = build(&m).expect("valid").mesh().clone();
        m.triangles[0].swap(1, 2);
        m.triangles[5].swap(1, 2);
        let topo = build(&m).expect("repaired");
        assert_eq!(topo.flipped_triangles(), &[0, 5]);
        assert_eq!(topo.mesh(), &good);
        assert_eq!(
            topo.warnings(),
            vec![
                "2 triangle(s) were flipped to agree with their neighbours (the first: triangle 0)"
            ]
        );
    }

    #[test]
    fn unreferenced_vertices_are_dropped_with_a_map() {
        let m = mesh(
            &[
                [9., 9., 9.],
                [0., 0., 0.],
                [5., 5., 5.],
                [1., 0., 0.],
                [0., 1., 0.],
            ],
            &[[1, 3, 4]],
        );
        let topo = build(&m).expect("valid");
        assert_eq!(topo.vertex_count(), 3);
        assert_eq!(topo.mesh().triangles, vec![[0, 1, 2]]);
        assert_eq!(
            (0..3).map(|v| topo.source_vertex(v)).collect::<Vec<_>>(),
            vec![1, 3, 4]
        );
        assert_eq!(topo.dropped_vertices(), 2);
        assert_eq!(topo.boundary_loops(), &[vec![0, 1, 2]]);
    }

    #[test]
    fn errors_name_the_element() {
        let sq = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]];
        assert_eq!(err(&mesh(&sq, &[])), "m.obj: the mesh has no triangles");
        assert_eq!(
            err(&mesh(&sq, &[[0, 1, 4]])),
            "m.obj: triangle 0: vertex index 4 out of range (0..=3)"
        );
        let mut nan = sq;
        nan[2][1] = f64::INFINITY;
        assert_eq!(
            err(&mesh(&nan, &[[0, 1, 2]])),
            "m.obj: vertex 2: a coordinate is not finite"
        );
        let mut far = sq;
        far[1][0] = 2e9;
        assert_eq!(
            err(&mesh(&far, &[[0, 1, 2]])),
            "m.obj: vertex 1: a coordinate is 2.000e9 mm, beyond ±1e9 mm (a wrong unit or a stray point?)"
        );
        assert_eq!(
            err(&mesh(&sq, &[[0, 1, 2], [0, 2, 2]])),
            "m.obj: triangle 1: vertices 0, 2, 2: the triangle repeats vertex 2 (degenerate)"
        );
        let line = [
            [0., 0., 0.],
            [1., 1., 1.],
            [2., 2., 2.000_000_000_000_1],
            [0., 1., 0.],
        ];
        let e = err(&mesh(&line, &[[0, 3, 1], [0, 1, 2]]));
        assert!(
            e.starts_with(
                "m.obj: triangle 1: vertices 0, 1, 2 at (1.000, 1.000, 1.000) mm: zero area"
            ),
            "{e}"
        );
        // Three triangles on edge 0–1.
        let fin = [
            [0., 0., 0.],
            [0., 0., 2.],
            [1., 0., 0.],
            [0., 1., 0.],
            [-1., 0., 0.],
        ];
        assert_eq!(
            err(&mesh(&fin, &[[0, 1, 2], [1, 0, 3], [0, 1, 4]])),
            "m.obj: edge 0–1 at (0.000, 0.000, 1.000) mm: the edge is shared by 3 triangles (non-manifold edge; at most 2 may share one)"
        );
        // Two fans meeting at vertex 0 (a bow tie).
        let bow = [
            [0., 0., 0.],
            [1., 0., 0.],
            [1., 1., 0.],
            [-1., 0., 0.],
            [-1., -1., 0.],
        ];
        assert_eq!(
            err(&mesh(&bow, &[[0, 1, 2], [0, 3, 4]])),
            "m.obj: vertex 0 at (0.000, 0.000, 0.000) mm: the triangles around the vertex form 2 separate fans (non-manifold vertex)"
        );
        // Two separate triangles.
        let two = [
            [0., 0., 0.],
            [1., 0., 0.],
            [0., 1., 0.],
            [5., 0., 0.],
            [6., 0., 0.],
            [5., 1., 0.],
        ];
        assert_eq!(
            err(&mesh(&two, &[[0, 1, 2], [3, 4, 5]])),
            "m.obj: the mesh has 2 separate pieces (edge-connected); the second contains vertex 3 at (5.000, 0.000, 0.000) mm: keep one surface per file"
        );
        // Error names use the input's vertex numbers, before dropping.
        let mut spare = vec![[7., 7., 7.]];
        spare.extend_from_slice(&two);
        assert!(err(&mesh(&spare, &[[1, 2, 3], [4, 5, 6]])).contains("vertex 4 at (5.000"));
    }

    #[test]
    fn mobius_strip_is_refused() {
        // A strip of 2n quads closed with a half twist.
        let n = 12;
        let mut p = Vec::new();
        for i in 0..n {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let (s, c) = (a.sin(), a.cos());
            let h = 0.5 * a;
            for w in [-1.0, 1.0] {
                let r = 10.0 + w * h.cos();
                p.push([r * c, r * s, w * h.sin()]);
            }
        }
        let mut t = Vec::new();
        for i in 0..n as u32 {
            let (a, b) = (2 * i, 2 * i + 1);
            let (c, d) = if i + 1 < n as u32 {
                (2 * i + 2, 2 * i + 3)
            } else {
                (1, 0) // the twist: the strip's sides swap
            };
            t.push([a, c, d]);
            t.push([a, d, b]);
        }
        let e = err(&mesh(&p, &t));
        assert!(
            e.contains("the mesh is not orientable (a Möbius strip)"),
            "{e}"
        );
        assert!(e.starts_with("m.obj: edge "), "{e}");
    }
}
