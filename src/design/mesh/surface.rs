//! A triangle mesh seen as a [`Surface`], so that the same tracer, seeds,
//! spacing, alternation and clips work on meshes as on analytic surfaces.
//!
//! The parameter plane is a [`Chart`](crate::design::mesh::chart::Chart); a point
//! (u, v) is on the surface when it lies in a chart triangle.
//! * Each vertex i carries a local patch Xᵢ(u, v), a cubic in
//!   Δ = (u, v) − (uᵢ, vᵢ) through the vertex, fitted by weighted least
//!   squares to the vertices of its two rings (more at the rim, until 15).
//!   The patches need only the chart, not the curvature tensors
//!   ([`ChartPatches`]), so they are fitted while the tensors are.
//! * The surface is the patches blended by a partition of unity:
//!   X = Σ wᵢ Xᵢ / Σ wᵢ with wᵢ = (1 − r²/Rᵢ²)³ for r = |Δ| < Rᵢ, Rᵢ 1.5 ×
//!   the vertex's longest chart edge (so the patches of a triangle's corners
//!   cover it). The blend is C²; a cubic patch is O(h⁴) from the smooth
//!   surface the vertices sample (spacing h), and the blend's partials,
//!   exact derivatives of it, carry the patches' disagreement times ∂w ~
//!   1/h: positions O(h⁴), normals O(h³). The normals written into the
//!   network are these, so twist from them is as good as on the closed
//!   form (quadratic patches gave O(h²) normals and 1–4 % twist errors on
//!   70 mm Delaunay meshes; cubic ones 0.03–0.5 %).
//! * The curvature is the per-vertex shape operators (from
//!   [`vertex_curvatures`](crate::design::mesh::curvature): quartic or cubic jets, see there) of the chart
//!   triangle's corners, each turned by the smallest rotation taking its
//!   vertex normal to the point's normal (as Rusinkiewicz 2004 moves
//!   tensors between frames), interpolated barycentrically: continuous
//!   across edges and exact for a tensor field that varies linearly. (The
//!   blend's own second derivatives, or the tensors blended with the
//!   patches' weights, are smooth but reproduce only constants: their
//!   gradients oscillate from vertex to vertex, and the traced curves' bending
//!   radii came out 35–45 % low on the same meshes, against 1–5 % here.)
//!   The traced curves still wiggle a little at the mesh's scale where the
//!   interpolated field kinks at edges: the network carries a precision
//!   for that (`crate::design::mesh_source::mesh_precision_mm`). The jet's
//!   second derivatives are set to (II(∂u, ∂u),
//!   II(∂u, ∂v), II(∂v, ∂v)) · n, which is all
//!   [`curvature_of`](crate::geom::surface::curvature_of) reads, so the
//!   asymptotic and principal directions come out of the estimated tensor
//!   field.

use crate::design::mesh::TriMesh;
use crate::geom::surface::{Curvature, Surface, SurfaceJet};
use glam::{DMat3, DVec2, DVec3};
use rayon::prelude::*;

/// A mesh with a chart and curvature tensors, as a surface.
#[derive(Debug, Clone)]
pub struct MeshSurface {
    positions_mm: Vec<DVec3>,
    uv: Vec<DVec2>,
    triangles: Vec<[u32; 3]>,
    /// Per vertex unit normal.
    normals: Vec<DVec3>,
    /// Per vertex shape operator k1·d1d1ᵀ + k2·d2d2ᵀ.
    shape: Vec<DMat3>,
    /// Per vertex quadratic patch in the chart.
    patches: Vec<Patch>,
    grid: UvGrid,
    supports: SupportGrid,
}

/// A mesh's chart with its per-vertex patches ([`fit_patches`]) and the
/// grids that find a point's triangle and the patches that reach it: all
/// of a [`MeshSurface`] but its curvature tensors.
#[derive(Debug, Clone)]
pub struct ChartPatches {
    uv: Vec<DVec2>,
    patches: Vec<Patch>,
    grid: UvGrid,
    supports: SupportGrid,
}

impl ChartPatches {
    /// Fit every vertex's patch to at least `patch_neighbours` vertices
    /// besides its own, over the chart `uv` of `mesh` (every triangle
    /// counter-clockwise in uv, as the chart module guarantees).
    pub fn fit(mesh: &TriMesh, uv: Vec<DVec2>, patch_neighbours: usize) -> ChartPatches {
        // The triangles' grid while the patches are fitted.
        let (grid, patches) = rayon::join(
            || UvGrid::new(&uv, &mesh.triangles),
            || fit_patches(mesh, &uv, patch_neighbours),
        );
        let supports = SupportGrid::new(&patches);
        ChartPatches {
            uv,
            patches,
            grid,
            supports,
        }
    }
}

/// A vertex's patch: the cubic X(Δ) = x + b[0] Δu + b[1] Δv
/// + ½ (c[0] Δu² + 2 c[1] Δu Δv + c[2] Δv²)
/// + ⅙ (d[0] Δu³ + 3 d[1] Δu² Δv + 3 d[2] Δu Δv² + d[3] Δv³).
#[derive(Debug, Clone, Copy)]
struct Patch {
    x: DVec3,
    uv: DVec2,
    radius: f64,
    b: [DVec3; 2],
    c: [DVec3; 3],
    d: [DVec3; 4],
}

/// A weight and its partials in the chart.
#[derive(Debug, Clone, Copy)]
struct Weight {
    w: f64,
    dw: DVec2,
}

/// A patch's value and its partials.
#[derive(Debug, Clone, Copy)]
struct PatchJet {
    p: DVec3,
    d: [DVec3; 2],
}

impl Patch {
    fn weight(&self, q: DVec2) -> Option<Weight> {
        let d = q - self.uv;
        let r2 = self.radius * self.radius;
        let t = 1.0 - d.length_squared() / r2;
        if t <= 0.0 {
            return None;
        }
        // w = t³, ∂w = 3t² ∂t, ∂t = −2 d / R².
        Some(Weight {
            w: t * t * t,
            dw: d * (-6.0 * t * t / r2),
        })
    }
    fn eval(&self, q: DVec2) -> PatchJet {
        let (u, v) = (q.x - self.uv.x, q.y - self.uv.y);
        let [b0, b1] = self.b;
        let [c0, c1, c2] = self.c;
        let [d0, d1, d2, d3] = self.d;
        let p = self.x
            + b0 * u
            + b1 * v
            + (c0 * (u * u) + c1 * (2.0 * u * v) + c2 * (v * v)) * 0.5
            + (d0 * (u * u * u)
                + d1 * (3.0 * u * u * v)
                + d2 * (3.0 * u * v * v)
                + d3 * (v * v * v))
                / 6.0;
        let pu = b0 + c0 * u + c1 * v + (d0 * (u * u) + d1 * (2.0 * u * v) + d2 * (v * v)) * 0.5;
        let pv = b1 + c1 * u + c2 * v + (d1 * (u * u) + d2 * (2.0 * u * v) + d3 * (v * v)) * 0.5;
        PatchJet { p, d: [pu, pv] }
    }
}

impl MeshSurface {
    /// A surface from a mesh, its chart (every triangle counter-clockwise
    /// in uv, as the chart module guarantees) and per-vertex curvatures
    /// (normals on the side of the counter-clockwise triangles).
    pub fn new(mesh: &TriMesh, uv: Vec<DVec2>, curvatures: &[Curvature]) -> MeshSurface {
        MeshSurface::with_patch_neighbours(mesh, uv, curvatures, PATCH_MIN_NEIGHBOURS)
    }

    /// As [`MeshSurface::new`], every patch fitted to at least
    /// `patch_neighbours` vertices besides its own (more averaging of noisy
    /// vertices, a form-found film's).
    pub fn with_patch_neighbours(
        mesh: &TriMesh,
        uv: Vec<DVec2>,
        curvatures: &[Curvature],
        patch_neighbours: usize,
    ) -> MeshSurface {
        MeshSurface::with_patches(
            mesh,
            curvatures,
            ChartPatches::fit(mesh, uv, patch_neighbours),
        )
    }

    /// A surface from a mesh, per-vertex curvatures (as for
    /// [`MeshSurface::new`]) and its chart with the patches fitted over it
    /// beforehand ([`ChartPatches::fit`], which needs no curvature, so that
    /// the two can be made side by side).
    pub fn with_patches(
        mesh: &TriMesh,
        curvatures: &[Curvature],
        patches: ChartPatches,
    ) -> MeshSurface {
        let normals: Vec<DVec3> = curvatures.iter().map(|c| c.normal).collect();
        let shape = curvatures.iter().map(Curvature::shape_tensor).collect();
        let ChartPatches {
            uv,
            patches,
            grid,
            supports,
        } = patches;
        MeshSurface {
            positions_mm: mesh.positions_mm.clone(),
            uv,
            triangles: mesh.triangles.clone(),
            normals,
            shape,
            patches,
            grid,
            supports,
        }
    }

    /// The chart triangle holding uv and its barycentric coordinates.
    pub fn locate(&self, q: DVec2) -> Option<(usize, [f64; 3])> {
        self.grid.locate(q, &self.uv, &self.triangles)
    }

    /// The chart point of the surface point nearest to `p` (mm), and its
    /// distance (mm): the nearest point of the facets (brute force over
    /// the triangles: for seeds), then from there the nearest point of the
    /// blended surface the tracer walks (`nearest_on_surface`).
    /// The facets' nearest point alone is ill-posed at the facets' scale:
    /// seen from inside a ring, the two facets either side of a row of
    /// vertices are equally near, and which one wins moves the foot by a
    /// fraction of an edge (a film's seed, and with it the whole net, by
    /// 4 mm on 50 mm edges when the film changed by 1e-9 mm).
    pub fn nearest_uv(&self, p: DVec3) -> Option<(DVec2, f64)> {
        let mut best: Option<(DVec2, f64)> = None;
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| self.positions_mm[i as usize]);
            let (x, l) = closest_on_triangle(p, a, b, c);
            let d = x.distance(p);
            if best.is_none_or(|(_, bd)| d < bd) {
                let q = t
                    .iter()
                    .zip(l)
                    .map(|(&i, w)| self.uv[i as usize] * w)
                    .sum::<DVec2>();
                best = Some((q, d));
            }
        }
        let (q, d) = best?;
        Some(self.nearest_on_surface(p, q).unwrap_or((q, d)))
    }

    /// The nearest point to `p` of the blended surface from the chart
    /// point `q` on: Gauss–Newton steps on |X(q) − p|², each kept only
    /// where it stays in the chart and brings the point closer (halved
    /// until it does), until a step moves less than [`FOOT_STEP_MM`]:
    /// (chart point, distance in mm); None where `q` is not in the chart.
    fn nearest_on_surface(&self, p: DVec3, mut q: DVec2) -> Option<(DVec2, f64)> {
        let mut at = self.locate(q).map(|_| self.blend(q))?;
        let mut d = at.0.distance(p);
        for _ in 0..FOOT_MAX_STEPS {
            let (x, [xu, xv]) = at;
            let r = p - x;
            let (a, b, c) = (xu.dot(xu), xu.dot(xv), xv.dot(xv));
            let det = a * c - b * b;
            if det.is_nan() || det <= 0.0 {
                break;
            }
            let (gu, gv) = (xu.dot(r), xv.dot(r));
            let mut step = DVec2::new(c * gu - b * gv, a * gv - b * gu) / det;
            let mut taken = false;
            for _ in 0..FOOT_HALVINGS {
                let next = q + step;
                if self.locate(next).is_some() {
                    let there = self.blend(next);
                    let dn = there.0.distance(p);
                    if dn < d {
                        (q, at, d, taken) = (next, there, dn, true);
                        break;
                    }
                }
                step *= 0.5;
            }
            let moved_mm = (xu * step.x + xv * step.y).length();
            if !taken || moved_mm < FOOT_STEP_MM {
                break;
            }
        }
        Some((q, d))
    }

    /// The blended point and its partials: X = S / W with S = Σ wᵢ Xᵢ,
    /// W = Σ wᵢ, so ∂X = (∂S − X ∂W) / W. Positions are taken relative to
    /// the first patch's vertex, so nothing cancels.
    fn blend(&self, q: DVec2) -> (DVec3, [DVec3; 2]) {
        let mut origin: Option<DVec3> = None;
        let (mut w_sum, mut dw_sum) = (0.0, DVec2::ZERO);
        let (mut x, mut dx) = (DVec3::ZERO, [DVec3::ZERO; 2]);
        for &i in self.supports.candidates(q) {
            let patch = &self.patches[i as usize];
            let Some(Weight { w, dw }) = patch.weight(q) else {
                continue;
            };
            let o = *origin.get_or_insert(patch.x);
            let PatchJet { p, d } = patch.eval(q);
            let p = p - o;
            w_sum += w;
            dw_sum += dw;
            x += p * w;
            dx[0] += d[0] * w + p * dw.x;
            dx[1] += d[1] * w + p * dw.y;
        }
        let Some(o) = origin.filter(|_| w_sum > 0.0) else {
            return (DVec3::ZERO, [DVec3::X, DVec3::Y]);
        };
        let p = x / w_sum;
        let pu = (dx[0] - p * dw_sum.x) / w_sum;
        let pv = (dx[1] - p * dw_sum.y) / w_sum;
        (p + o, [pu, pv])
    }

    /// Named check: at each triangle's centroid the surface normal (from
    /// the chart's partials) lies on the side of its vertices' normals.
    /// Returns the triangle with the smallest cosine between them, and
    /// that cosine; a negative one means the chart and the curvature
    /// tensors disagree about the side, which swaps the families there.
    pub fn worst_normal_agreement(&self) -> Option<(usize, f64)> {
        (0..self.triangles.len())
            .map(|t| {
                let centroid = self.triangles[t]
                    .iter()
                    .map(|&i| self.uv[i as usize])
                    .sum::<DVec2>()
                    / 3.0;
                let (_, [pu, pv]) = self.blend(centroid);
                let n = pu.cross(pv).normalize_or_zero();
                let c = self.triangles[t]
                    .iter()
                    .map(|&i| n.dot(self.normals[i as usize]))
                    .fold(f64::INFINITY, f64::min);
                (t, c)
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// The chart coordinates of the vertices.
    pub fn chart(&self) -> &[DVec2] {
        &self.uv
    }

    fn jet(&self, q: DVec2) -> SurfaceJet {
        if self.locate(q).is_none() {
            // Outside the chart: a flat jet (the tracer asks only inside;
            // this keeps evaluation total).
            return SurfaceJet {
                p: DVec3::ZERO,
                pu: DVec3::X,
                pv: DVec3::Y,
                puu: DVec3::ZERO,
                puv: DVec3::ZERO,
                pvv: DVec3::ZERO,
            };
        }
        let (p, [pu, pv]) = self.blend(q);
        let n = pu.cross(pv).normalize_or(DVec3::Z);
        let mut s = DMat3::ZERO;
        if let Some((tri, bary)) = self.locate(q) {
            for (&i, w) in self.triangles[tri].iter().zip(bary) {
                let r = rotation_between(self.normals[i as usize], n);
                s += r * self.shape[i as usize] * r.transpose() * w;
            }
        }
        let ii = |a: DVec3, b: DVec3| a.dot(s * b);
        SurfaceJet {
            p,
            pu,
            pv,
            puu: n * ii(pu, pu),
            puv: n * ii(pu, pv),
            pvv: n * ii(pv, pv),
        }
    }
}

impl Surface for MeshSurface {
    fn eval(&self, q: DVec2) -> SurfaceJet {
        self.jet(q)
    }
    fn derivatives(&self, q: DVec2) -> SurfaceJet {
        self.jet(q)
    }
    fn point(&self, q: DVec2) -> DVec3 {
        match self.locate(q) {
            Some(_) => self.blend(q).0,
            None => DVec3::ZERO,
        }
    }
    fn in_domain(&self, q: DVec2) -> bool {
        self.locate(q).is_some()
    }
}

/// The smallest rotation taking unit `from` to unit `to` (identity when
/// they agree; a half turn about any perpendicular when opposite).
fn rotation_between(from: DVec3, to: DVec3) -> DMat3 {
    let c = from.dot(to);
    let axis = from.cross(to);
    if c < -1.0 + 1e-12 {
        let a = from.any_orthonormal_vector();
        return DMat3::from_axis_angle(a, std::f64::consts::PI);
    }
    // Rodrigues with k = axis (unnormalised): R = I + [k]× + [k]×²/(1 + c).
    let k = DMat3::from_cols(
        DVec3::new(0.0, axis.z, -axis.y),
        DVec3::new(-axis.z, 0.0, axis.x),
        DVec3::new(axis.y, -axis.x, 0.0),
    );
    DMat3::IDENTITY + k + k * k * (1.0 / (1.0 + c))
}

/// Closest point of triangle abc to p, and its barycentric coordinates
/// (Ericson, Real-Time Collision Detection, 5.1.5).
fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> (DVec3, [f64; 3]) {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, [1.0, 0.0, 0.0]);
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return (b, [0.0, 1.0, 0.0]);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (a + ab * v, [1.0 - v, v, 0.0]);
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return (c, [0.0, 0.0, 1.0]);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (a + ac * w, [1.0 - w, 0.0, w]);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (b + (c - b) * w, [0.0, 1.0 - w, w]);
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    (a + ab * v + ac * w, [1.0 - v - w, v, w])
}

/// Radius of a vertex's patch support, in its longest chart edges.
pub const SUPPORT_EDGES: f64 = 1.5;

/// A seed's foot on the blended surface ([`MeshSurface::nearest_uv`]) is
/// final when a step moves it less than this, mm.
pub const FOOT_STEP_MM: f64 = 1e-9;

/// Gauss–Newton steps towards a seed's foot, at most (each converges
/// linearly at the rate distance × curvature, quadratically on the
/// surface: a handful do).
const FOOT_MAX_STEPS: usize = 50;

/// Halvings of a Gauss–Newton step that does not bring the foot closer.
const FOOT_HALVINGS: usize = 30;

/// Unknowns of a cubic patch per coordinate: 2 linear, 3 quadratic, 4 cubic.
const PATCH_UNKNOWNS: usize = 9;

/// A patch's terms (coefficient, power of Δu, power of Δv), in the order
/// of its unknowns: Δu, Δv, ½Δu², ΔuΔv, ½Δv², ⅙Δu³, ½Δu²Δv, ½ΔuΔv²,
/// ⅙Δv³.
const PATCH_TERMS: [(f64, usize, usize); PATCH_UNKNOWNS] = [
    (1.0, 1, 0),
    (1.0, 0, 1),
    (0.5, 2, 0),
    (1.0, 1, 1),
    (0.5, 0, 2),
    (1.0 / 6.0, 3, 0),
    (0.5, 2, 1),
    (0.5, 1, 2),
    (1.0 / 6.0, 0, 3),
];

/// A patch's neighbourhood grows ring by ring until it holds at least this
/// many vertices besides its own (the 2-ring inside a mesh, 3 rings at the
/// rim), so the cubic is fitted with some redundancy.
pub const PATCH_MIN_NEIGHBOURS: usize = 15;

/// The neighbourhood grows by at most this many rings.
const PATCH_MAX_RINGS: usize = 6;

/// Fit every vertex's cubic chart patch to the vertices of its rings (two,
/// more at the rim until [`PATCH_MIN_NEIGHBOURS`]), by least squares through
/// the vertex itself, weighted (1 − ½ r²/ρ²) (ρ the neighbourhood's chart
/// radius), on Δ scaled by ρ. The vertices in parallel, each patch its
/// own vertex's alone (the same for any number of threads).
fn fit_patches(mesh: &TriMesh, uv: &[DVec2], min_neighbours: usize) -> Vec<Patch> {
    let nv = mesh.positions_mm.len();
    let mut ring: Vec<Vec<u32>> = vec![Vec::new(); nv];
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            ring[a as usize].push(b);
            ring[b as usize].push(a);
        }
    }
    for r in &mut ring {
        r.sort_unstable();
        r.dedup();
    }
    // Each thread keeps its visit marks and lists from vertex to vertex.
    let scratch = || {
        (
            crate::geom::mesh::VisitMarks::new(nv),
            Vec::<u32>::new(),
            Vec::<u32>::new(),
            Vec::<u32>::new(),
        )
    };
    (0..nv)
        .into_par_iter()
        .map_init(scratch, |(visited, seen, frontier, next), i| {
            let q0 = uv[i];
            let longest = ring[i]
                .iter()
                .map(|&j| uv[j as usize].distance(q0))
                .fold(0.0, f64::max)
                .max(1e-9);
            let radius = SUPPORT_EDGES * longest;
            seen.clear();
            seen.push(i as u32);
            visited.clear();
            visited.insert(i as u32);
            frontier.clear();
            frontier.push(i as u32);
            for depth in 0..PATCH_MAX_RINGS {
                if depth >= 2 && seen.len() > min_neighbours {
                    break;
                }
                next.clear();
                for &v in frontier.iter() {
                    for &w in &ring[v as usize] {
                        if visited.insert(w) {
                            seen.push(w);
                            next.push(w);
                        }
                    }
                }
                std::mem::swap(frontier, next);
            }
            let x = mesh.positions_mm[i];
            let scale = seen
                .iter()
                .map(|&j| uv[j as usize].distance(q0))
                .fold(0.0, f64::max)
                .max(1e-9);
            // The normal equations from the points' weighted power sums:
            // every product of two terms is one monomial of degree ≤ 6.
            let mut sums = [[0.0; 7]; 7];
            let mut heights = [[DVec3::ZERO; 4]; 4];
            let inverse = 1.0 / scale;
            for &j in &seen[1..] {
                let d = (uv[j as usize] - q0) * inverse;
                let w = (1.0 - 0.5 * d.length_squared()).max(0.05);
                let mut us = [w; 7];
                let mut vs = [1.0; 7];
                for k in 1..7 {
                    us[k] = us[k - 1] * d.x;
                    vs[k] = vs[k - 1] * d.y;
                }
                for (a, row) in sums.iter_mut().enumerate() {
                    for (b, sum) in row[..7 - a].iter_mut().enumerate() {
                        *sum += us[a] * vs[b];
                    }
                }
                let rhs = mesh.positions_mm[j as usize] - x;
                for (a, row) in heights.iter_mut().enumerate() {
                    for (b, sum) in row[..4 - a].iter_mut().enumerate() {
                        *sum += rhs * (us[a] * vs[b]);
                    }
                }
            }
            let mut ata = [[0.0; PATCH_UNKNOWNS]; PATCH_UNKNOWNS];
            let mut atb = [DVec3::ZERO; PATCH_UNKNOWNS];
            for (a, &(ca, ua, va)) in PATCH_TERMS.iter().enumerate() {
                for (b, &(cb, ub, vb)) in PATCH_TERMS.iter().enumerate() {
                    ata[a][b] = ca * cb * sums[ua + ub][va + vb];
                }
                atb[a] = heights[ua][va] * ca;
            }
            let sol = solve(ata, atb);
            let (s1, s2, s3) = (scale, scale * scale, scale * scale * scale);
            Patch {
                x,
                uv: q0,
                radius,
                b: [sol[0] / s1, sol[1] / s1],
                c: [sol[2] / s2, sol[3] / s2, sol[4] / s2],
                d: [sol[5] / s3, sol[6] / s3, sol[7] / s3, sol[8] / s3],
            }
        })
        .collect()
}

/// Solve an N × N system (three right-hand sides) by Gaussian elimination
/// with partial pivoting; a singular system (a vertex with too few
/// neighbours) drops the terms it cannot determine.
#[allow(clippy::needless_range_loop)] // elimination reads as index algebra
fn solve<const N: usize>(mut a: [[f64; N]; N], mut b: [DVec3; N]) -> [DVec3; N] {
    let norm = a
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()))
        .max(1e-300);
    for col in 0..N {
        let piv = (col..N)
            .max_by(|&r, &s| a[r][col].abs().total_cmp(&a[s][col].abs()))
            .unwrap_or(col);
        a.swap(col, piv);
        b.swap(col, piv);
        if a[col][col].abs() < 1e-12 * norm {
            // Undetermined: leave this unknown zero.
            for r in 0..N {
                a[r][col] = 0.0;
                a[col][r] = 0.0;
            }
            a[col][col] = 1.0;
            b[col] = DVec3::ZERO;
            continue;
        }
        for r in col + 1..N {
            let f = a[r][col] / a[col][col];
            if f == 0.0 {
                continue;
            }
            for k in col..N {
                a[r][k] -= f * a[col][k];
            }
            b[r] -= b[col] * f;
        }
    }
    let mut x = [DVec3::ZERO; N];
    for r in (0..N).rev() {
        let mut acc = b[r];
        for k in r + 1..N {
            acc -= x[k] * a[r][k];
        }
        x[r] = acc / a[r][r];
    }
    x
}

/// A uniform grid of `nx` × `ny` square cells of side `cell` from `origin`
/// in the chart, listing per cell the items (patches, triangles) whose box
/// meets it: the items of cell k (row-major) are
/// `items[start[k]..start[k + 1]]`, in item order.
#[derive(Debug, Clone)]
struct CellGrid {
    origin: DVec2,
    cell: f64,
    nx: usize,
    ny: usize,
    start: Vec<u32>,
    items: Vec<u32>,
}

/// A box of cells, (x0, y0) to (x1, y1) inclusive.
type CellSpan = ((usize, usize), (usize, usize));

impl CellGrid {
    /// The grid of no cells (for no items or a chart not finite).
    fn empty() -> CellGrid {
        CellGrid {
            origin: DVec2::ZERO,
            cell: 1.0,
            nx: 0,
            ny: 0,
            start: vec![0],
            items: Vec::new(),
        }
    }

    /// The grid listing item i in every cell of `span(i)` for i in
    /// 0..`count`.
    fn new(
        origin: DVec2,
        cell: f64,
        (nx, ny): (usize, usize),
        count: usize,
        span: impl Fn(&CellGrid, usize) -> CellSpan,
    ) -> CellGrid {
        let mut grid = CellGrid {
            origin,
            cell,
            nx,
            ny,
            start: vec![0u32; nx * ny + 1],
            items: Vec::new(),
        };
        let spans: Vec<CellSpan> = (0..count).map(|i| span(&grid, i)).collect();
        for &((x0, y0), (x1, y1)) in &spans {
            for y in y0..=y1 {
                for x in x0..=x1 {
                    grid.start[y * nx + x + 1] += 1;
                }
            }
        }
        for k in 1..grid.start.len() {
            grid.start[k] += grid.start[k - 1];
        }
        let mut fill = grid.start.clone();
        grid.items = vec![0u32; grid.start[nx * ny] as usize];
        for (i, &((x0, y0), (x1, y1))) in spans.iter().enumerate() {
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let k = y * nx + x;
                    grid.items[fill[k] as usize] = i as u32;
                    fill[k] += 1;
                }
            }
        }
        grid
    }

    /// The cell of a point, clamped to the grid.
    fn cell_of(&self, q: DVec2) -> (usize, usize) {
        let c = ((q - self.origin) / self.cell).floor();
        (
            (c.x.max(0.0) as usize).min(self.nx - 1),
            (c.y.max(0.0) as usize).min(self.ny - 1),
        )
    }

    /// The items listed in cell (x, y).
    fn items_at(&self, (x, y): (usize, usize)) -> &[u32] {
        let k = y * self.nx + x;
        &self.items[self.start[k] as usize..self.start[k + 1] as usize]
    }
}

/// A uniform grid over the chart listing, per cell, the vertices whose
/// patch support meets it.
#[derive(Debug, Clone)]
struct SupportGrid(CellGrid);

impl SupportGrid {
    fn new(patches: &[Patch]) -> SupportGrid {
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        let mut mean_r = 0.0;
        for p in patches {
            lo = lo.min(p.uv - DVec2::splat(p.radius));
            hi = hi.max(p.uv + DVec2::splat(p.radius));
            mean_r += p.radius;
        }
        if patches.is_empty() || !lo.is_finite() {
            return SupportGrid(CellGrid::empty());
        }
        let cell = (mean_r / patches.len() as f64).max(1e-9);
        let size = hi - lo;
        let nx = ((size.x / cell).ceil() as usize).clamp(1, 4096);
        let ny = ((size.y / cell).ceil() as usize).clamp(1, 4096);
        let cell = (size.x / nx as f64).max(size.y / ny as f64).max(1e-9);
        SupportGrid(CellGrid::new(lo, cell, (nx, ny), patches.len(), |g, i| {
            let p = &patches[i];
            (
                g.cell_of(p.uv - DVec2::splat(p.radius)),
                g.cell_of(p.uv + DVec2::splat(p.radius)),
            )
        }))
    }

    fn candidates(&self, q: DVec2) -> &[u32] {
        let g = &self.0;
        if g.nx == 0 || !q.is_finite() {
            return &[];
        }
        let c = ((q - g.origin) / g.cell).floor();
        if c.x < 0.0 || c.y < 0.0 || c.x >= g.nx as f64 || c.y >= g.ny as f64 {
            return &[];
        }
        g.items_at((c.x as usize, c.y as usize))
    }
}

/// A uniform grid over the chart: each cell lists the triangles whose
/// bounding box meets it, so a point is located among a handful.
#[derive(Debug, Clone)]
struct UvGrid(CellGrid);

/// Barycentric slack of point location: points this far outside a
/// triangle (relative) still count as inside, so the chart has no cracks
/// along its edges from rounding.
const LOCATE_SLACK: f64 = 1e-12;

impl UvGrid {
    fn new(uv: &[DVec2], triangles: &[[u32; 3]]) -> UvGrid {
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for q in uv {
            lo = lo.min(*q);
            hi = hi.max(*q);
        }
        if triangles.is_empty() || !lo.is_finite() {
            return UvGrid(CellGrid::empty());
        }
        let size = (hi - lo).max(DVec2::splat(1e-9));
        let cells = (triangles.len() as f64 / 2.0).max(1.0);
        let cell = (size.x * size.y / cells).sqrt().max(1e-12);
        let nx = ((size.x / cell).ceil() as usize).clamp(1, 4096);
        let ny = ((size.y / cell).ceil() as usize).clamp(1, 4096);
        let cell = (size.x / nx as f64).max(size.y / ny as f64);
        UvGrid(CellGrid::new(
            lo,
            cell,
            (nx, ny),
            triangles.len(),
            |g, i| {
                let [a, b, c] = triangles[i].map(|k| uv[k as usize]);
                (g.cell_of(a.min(b).min(c)), g.cell_of(a.max(b).max(c)))
            },
        ))
    }

    fn locate(&self, q: DVec2, uv: &[DVec2], triangles: &[[u32; 3]]) -> Option<(usize, [f64; 3])> {
        let g = &self.0;
        if g.nx == 0 || !q.is_finite() {
            return None;
        }
        let c = (q - g.origin) / g.cell;
        let slack = 1e-9;
        if c.x < -slack || c.y < -slack || c.x > g.nx as f64 + slack || c.y > g.ny as f64 + slack {
            return None;
        }
        let mut best: Option<(usize, [f64; 3], f64)> = None;
        for &ti in g.items_at(g.cell_of(q)) {
            let [a, b, cc] = triangles[ti as usize].map(|i| uv[i as usize]);
            let area = (b - a).perp_dot(cc - a);
            if area.abs() < 1e-300 {
                continue;
            }
            let l0 = (cc - b).perp_dot(q - b) / area;
            let l1 = (a - cc).perp_dot(q - cc) / area;
            let l2 = 1.0 - l0 - l1;
            let worst = l0.min(l1).min(l2);
            if worst >= 0.0 {
                return Some((ti as usize, [l0, l1, l2]));
            }
            if worst >= -LOCATE_SLACK && best.is_none_or(|b| worst > b.2) {
                best = Some((ti as usize, [l0, l1, l2], worst));
            }
        }
        best.map(|(t, l, _)| (t, l))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::mesh::samples;
    use crate::design::surface::{curvature_of, Surface};

    /// A mesh of the paraboloid z = (a x² + b y²)/2 with exact curvatures
    /// at the vertices: the surface must hand them back at the vertices
    /// and interpolate between.
    #[test]
    fn vertex_tensors_come_back_through_the_jet() {
        let n = 10;
        let (a, b) = (1.0 / 2000.0, -1.0 / 3000.0);
        let f = |x: f64, y: f64| DVec3::new(x, y, 0.5 * (a * x * x + b * y * y));
        let mut mesh = TriMesh::default();
        for j in 0..=n {
            for i in 0..=n {
                mesh.positions_mm
                    .push(f(i as f64 * 50.0 - 250.0, j as f64 * 50.0 - 250.0));
            }
        }
        let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
        for j in 0..n {
            for i in 0..n {
                mesh.triangles
                    .push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                mesh.triangles
                    .push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        // Exact curvature of the graph at each vertex, from its own jet.
        let exact = |x: f64, y: f64| {
            curvature_of(&SurfaceJet {
                p: f(x, y),
                pu: DVec3::new(1.0, 0.0, a * x),
                pv: DVec3::new(0.0, 1.0, b * y),
                puu: DVec3::new(0.0, 0.0, a),
                puv: DVec3::ZERO,
                pvv: DVec3::new(0.0, 0.0, b),
            })
        };
        let curv: Vec<Curvature> = mesh.positions_mm.iter().map(|p| exact(p.x, p.y)).collect();
        let uv: Vec<DVec2> = mesh.positions_mm.iter().map(|p| p.truncate()).collect();
        let s = MeshSurface::new(&mesh, uv, &curv);
        // At the centre vertex (symmetric neighbourhood) the jet's normal is
        // the exact one and the curvatures come back to rounding.
        let c = curvature_of(&s.derivatives(DVec2::ZERO));
        assert!(
            (c.k1 - a).abs() < 1e-12 && (c.k2 - b).abs() < 1e-12,
            "{c:?}"
        );
        // Between vertices: within the interpolation error O(h²·k''), far
        // below 1 % here.
        let q = DVec2::new(37.0, -81.0);
        let c = curvature_of(&s.derivatives(q));
        let e = exact(q.x, q.y);
        assert!((c.k1 - e.k1).abs() < 0.01 * a.abs(), "{} vs {}", c.k1, e.k1);
        assert!((c.k2 - e.k2).abs() < 0.01 * b.abs(), "{} vs {}", c.k2, e.k2);
        // The facet is 0.02 mm off the paraboloid here; the blended patches
        // (quadratics in the chart, which is (x, y)) reproduce it exactly.
        let p = s.point(q);
        let z = |p: DVec3| 0.5 * (a * p.x * p.x + b * p.y * p.y);
        let t = s.locate(q).unwrap();
        let facet: DVec3 = mesh.triangles[t.0]
            .iter()
            .zip(t.1)
            .map(|(&i, w)| mesh.positions_mm[i as usize] * w)
            .sum();
        assert!((facet.z - z(facet)).abs() > 0.01, "{}", facet.z - z(facet));
        assert!((p.z - z(p)).abs() < 1e-9, "{}", p.z - z(p));
        assert!((p.truncate() - q).length() < 1e-9);
        // And its partials are the closed form's.
        let j = s.derivatives(q);
        assert!((j.pu - DVec3::new(1.0, 0.0, a * q.x)).length() < 1e-12);
        assert!((j.pv - DVec3::new(0.0, 1.0, b * q.y)).length() < 1e-12);
        assert!(!s.in_domain(DVec2::new(251.0, 0.0)));
        assert!(s.in_domain(DVec2::new(250.0, 250.0)));
        // 5 mm above the paraboloid at (10, 20), along z: the foot is
        // within the surface's tilt there (< 0.03) times 5 mm of (10, 20),
        // the distance 5 mm to 0.1 %.
        let above = f(10.0, 20.0) + DVec3::Z * 5.0;
        let (near, d) = s.nearest_uv(above).unwrap();
        assert!((near - DVec2::new(10.0, 20.0)).length() < 0.15, "{near}");
        assert!((d - 5.0).abs() < 0.005, "{d}");
        // 40 mm along the paraboloid's own normal at (-60, 110), between
        // vertices: the foot is (-60, 110) on the blended surface, which is
        // the paraboloid here (the facets' foot is not).
        let q0 = DVec2::new(-60.0, 110.0);
        let normal = DVec3::new(0.0, 1.0, b * q0.y)
            .cross(DVec3::new(1.0, 0.0, a * q0.x))
            .normalize();
        let (near, d) = s.nearest_uv(f(q0.x, q0.y) - normal * 40.0).unwrap();
        assert!((near - q0).length() < 1e-6, "{near}");
        assert!((d - 40.0).abs() < 1e-9, "{d}");
    }

    /// A seed inside a ring lands on its own meridian: on a cylinder of
    /// radius 1 m (50 mm facets, a row of vertices on the seed's
    /// meridian) the facets either side are equally near, their feet
    /// 25 mm either side, but the blended surface's foot is the
    /// cylinder's own.
    #[test]
    fn a_seed_inside_a_ring_lands_on_its_meridian() {
        let r = 1000.0;
        let at = |s: f64, z: f64| DVec3::new(r * (s / r).cos(), r * (s / r).sin(), z);
        // 50 mm cells from s = −600 mm: a row of vertices at s = 0.
        let (uv, triangles) = samples::grid(24, 12, (-600.0, 600.0), (-300.0, 300.0), 0.0, 5);
        let mesh = samples::place(&uv, &triangles, |q| at(q.x, q.y));
        let curv: Vec<Curvature> = uv
            .iter()
            .map(|q| {
                let (c, sn) = ((q.x / r).cos(), (q.x / r).sin());
                curvature_of(&SurfaceJet {
                    p: at(q.x, q.y),
                    pu: DVec3::new(-sn, c, 0.0),
                    pv: DVec3::Z,
                    puu: DVec3::new(-c, -sn, 0.0) / r,
                    puv: DVec3::ZERO,
                    pvv: DVec3::ZERO,
                })
            })
            .collect();
        let s = MeshSurface::new(&mesh, uv, &curv);
        let (near, d) = s.nearest_uv(DVec3::new(800.0, 0.0, 17.0)).unwrap();
        assert!((near - DVec2::new(0.0, 17.0)).length() < 0.01, "{near}");
        assert!((d - 200.0).abs() < 0.01, "{d}");
    }

    #[test]
    fn rotation_between_takes_one_normal_to_the_other() {
        let (a, b) = (
            DVec3::new(0.1, 0.2, 1.0).normalize(),
            DVec3::new(-0.3, 0.1, 1.0).normalize(),
        );
        let r = rotation_between(a, b);
        assert!((r * a - b).length() < 1e-14);
        assert!((r.determinant() - 1.0).abs() < 1e-14);
        let axis = a.cross(b).normalize();
        assert!((r * axis - axis).length() < 1e-14);
    }
}
