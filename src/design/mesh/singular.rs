//! Where a mesh's asymptotic net exists, and its singular points.
//!
//! Asymptotic directions exist where the surface is anticlastic (K < 0). A
//! vertex counts as anticlastic when its fitted principal curvatures have
//! opposite signs, each beyond [`SIGNIFICANT`] standard errors of the fit
//! ([`VertexJet::sigma_per_mm`]); elsewhere (synclastic, or flat within the
//! fit's error) the net has no direction. [`anticlastic_report`] counts and
//! clusters such vertices, [`require_anticlastic`] refuses a mesh with no
//! anticlastic vertex at all (a sphere cap), and
//! [`AnticlasticReport::warnings`] says where the rest lie.
//!
//! Singular points are found as those of the principal line field d1 (a
//! line field: directions modulo π). Its index around an interior vertex is
//! the turning of d1 along the vertex's one-ring: each ring vertex's d1 is
//! carried into the centre's tangent plane by the rotation taking its
//! normal to the centre's (discrete parallel transport), and the angle
//! steps between consecutive ring vertices, each reduced to (−π/2, π/2],
//! add up to 2π × index, a multiple of π. The index is defined only where
//! d1 is: at every ring vertex k1 − k2 must exceed [`SIGNIFICANT`] standard
//! errors, and no step may exceed [`MAX_STEP_RAD`] (a coarser ring cannot be
//! told from noise). Adjacent vertices with the same non-zero index enclose
//! one singular point: they are merged, and the point reported at their
//! centroid, within a mesh spacing of the true one.
//!
//! A singular point of the principal field is where k1 = k2: a flat point
//! (k1 = k2 = 0; on a minimal surface every singular point, where the
//! asymptotic net changes valence: index −1/2 at a monkey saddle, where six
//! asymptotic half-lines meet) or an umbilic (k1 = k2 ≠ 0, synclastic, no
//! asymptotic directions near it). Singular points within one ring of the
//! boundary are not found (boundary vertices have no closed ring).

use super::curvature::{VertexJet, SIGNIFICANT};
use super::topology::{fmt_point, Topology};
use crate::error::{Error, Location, Result};
use glam::{DQuat, DVec3};
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;

/// The largest turning of d1 between two adjacent ring vertices for the
/// index to count (3π/8 = 67.5°); valence-3 vertices around a half-index
/// singular point turn by 60°.
pub const MAX_STEP_RAD: f64 = 3.0 * PI / 8.0;

/// What kind of singular point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SingularKind {
    /// k1 = k2 = 0: the asymptotic net changes valence (a monkey saddle's
    /// centre, Enneper-type flat points of minimal surfaces).
    FlatPoint,
    /// k1 = k2 ≠ 0: a synclastic umbilic, where there are no asymptotic
    /// directions anyway.
    Umbilic,
}

/// A singular point of the principal (and asymptotic) net.
#[derive(Debug, Clone, PartialEq)]
pub struct Singularity {
    /// The merged vertex nearest to the point.
    pub vertex: u32,
    /// The centroid of the merged vertices, mm.
    pub position_mm: DVec3,
    /// Index of the principal line field, a multiple of 1/2 (−1/2 at a
    /// monkey saddle, +1/2 at an ellipsoid's umbilic).
    pub index: f64,
    /// Flat point or umbilic.
    pub kind: SingularKind,
    /// The vertices whose rings enclose it.
    pub vertices: Vec<u32>,
}

/// Whether d1 at a vertex is defined beyond the fit's error.
fn d1_defined(j: &VertexJet) -> bool {
    let c = &j.curvature;
    c.k1 - c.k2 > SIGNIFICANT * j.sigma_per_mm
}

/// Whether a vertex is anticlastic beyond the fit's error.
pub fn is_anticlastic(j: &VertexJet) -> bool {
    let (c, s) = (&j.curvature, SIGNIFICANT * j.sigma_per_mm);
    c.k1 > s && c.k2 < -s
}

/// Whether a vertex is synclastic beyond the fit's error.
fn is_synclastic(j: &VertexJet) -> bool {
    let (c, s) = (&j.curvature, SIGNIFICANT * j.sigma_per_mm);
    (c.k2 > s) || (c.k1 < -s)
}

/// The index of the principal line field around interior vertex `v` (a
/// multiple of 1/2), or None at a boundary vertex or where d1 is not
/// defined well enough along the ring (see the module documentation).
pub fn vertex_index(topo: &Topology, jets: &[VertexJet], v: u32) -> Option<f64> {
    if topo.is_boundary(v) {
        return None;
    }
    let ring = topo.neighbours(v);
    if ring.iter().any(|&w| !d1_defined(&jets[w as usize])) {
        return None;
    }
    let n = jets[v as usize].curvature.normal;
    let e1 = n.any_orthonormal_vector();
    let e2 = n.cross(e1);
    let angle = |w: u32| {
        let c = &jets[w as usize].curvature;
        let d = DQuat::from_rotation_arc(c.normal, n) * c.d1;
        d.dot(e2).atan2(d.dot(e1))
    };
    let Some(&w0) = ring.first() else {
        return Some(0.0);
    };
    // Around the ring and back to its first vertex.
    let first = angle(w0);
    let (mut total, mut previous) = (0.0, first);
    for next in ring[1..].iter().map(|&w| angle(w)).chain([first]) {
        let step = line_step(next - previous);
        if step.abs() > MAX_STEP_RAD {
            return None;
        }
        total += step;
        previous = next;
    }
    Some((total / PI).round() / 2.0)
}

/// An angle difference between two lines, reduced to (−π/2, π/2].
fn line_step(d: f64) -> f64 {
    let r = d - PI * (d / PI).round();
    if r <= -FRAC_PI_2 {
        r + PI
    } else {
        r
    }
}

/// The singular points of the principal net of the mesh `topo.mesh()`
/// from its jets ([`crate::design::mesh::curvature::vertex_jets`]), in order of
/// their first vertex.
pub fn singularities(topo: &Topology, jets: &[VertexJet]) -> Vec<Singularity> {
    let nv = topo.vertex_count();
    let index: Vec<f64> = (0..nv as u32)
        .into_par_iter()
        .map(|v| vertex_index(topo, jets, v).unwrap_or(0.0))
        .collect();
    let pos = &topo.mesh().positions_mm;
    clusters(
        topo,
        |v| index[v as usize] != 0.0,
        |a, b| index[a as usize] == index[b as usize],
    )
    .into_iter()
    .map(|vertices| {
        let (centroid, vertex) = centre(pos, &vertices);
        // The cluster's most isotropic vertex is nearest to k1 = k2.
        let iso = vertices
            .iter()
            .copied()
            .min_by(|&a, &b| {
                let an = |v: u32| {
                    let c = &jets[v as usize].curvature;
                    c.k1 - c.k2
                };
                an(a).total_cmp(&an(b)).then(a.cmp(&b))
            })
            .unwrap_or(vertex);
        let kind = if is_synclastic(&jets[iso as usize]) {
            SingularKind::Umbilic
        } else {
            SingularKind::FlatPoint
        };
        Singularity {
            vertex,
            position_mm: centroid,
            index: index[vertex as usize],
            kind,
            vertices,
        }
    })
    .collect()
}

/// Connected groups of the vertices with `member`, adjacent vertices joined
/// when `same`; each sorted, in order of the first vertex.
fn clusters(
    topo: &Topology,
    member: impl Fn(u32) -> bool,
    same: impl Fn(u32, u32) -> bool,
) -> Vec<Vec<u32>> {
    let nv = topo.vertex_count();
    let mut seen = vec![false; nv];
    let mut out = Vec::new();
    for v0 in 0..nv as u32 {
        if seen[v0 as usize] || !member(v0) {
            continue;
        }
        seen[v0 as usize] = true;
        let mut group = vec![v0];
        let mut i = 0;
        while i < group.len() {
            let v = group[i];
            for &w in topo.neighbours(v) {
                if !seen[w as usize] && member(w) && same(v, w) {
                    seen[w as usize] = true;
                    group.push(w);
                }
            }
            i += 1;
        }
        group.sort_unstable();
        out.push(group);
    }
    out
}

/// The centroid of `vertices` and the vertex nearest to it.
fn centre(pos: &[DVec3], vertices: &[u32]) -> (DVec3, u32) {
    let c = vertices.iter().map(|&v| pos[v as usize]).sum::<DVec3>() / vertices.len() as f64;
    let nearest = vertices
        .iter()
        .copied()
        .min_by(|&a, &b| {
            let d = |v: u32| pos[v as usize].distance_squared(c);
            d(a).total_cmp(&d(b)).then(a.cmp(&b))
        })
        .unwrap_or(vertices[0]);
    (c, nearest)
}

/// A connected group of vertices without asymptotic directions.
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    /// The vertices (of the cleaned mesh), sorted.
    pub vertices: Vec<u32>,
    /// How many of them are synclastic beyond the fit's error (the rest are
    /// flat within it).
    pub synclastic: usize,
    /// Their centroid, mm.
    pub centroid_mm: DVec3,
    /// The vertex nearest to the centroid.
    pub vertex: u32,
}

/// Where the mesh is anticlastic, where not, and its singular points.
#[derive(Debug, Clone, PartialEq)]
pub struct AnticlasticReport {
    /// Vertices of the mesh.
    pub vertices: usize,
    /// Vertices with asymptotic directions (K < 0 beyond the fit's error).
    pub anticlastic: usize,
    /// Vertices without (K ≥ 0, or K ≈ 0 within the fit's error).
    pub without_asymptotic: usize,
    /// Connected regions of the vertices without, largest first.
    pub regions: Vec<Region>,
    /// Singular points of the principal net.
    pub singularities: Vec<Singularity>,
    /// The vertex nearest to anticlastic (lowest K), its position (mm) and
    /// k1, k2 (1/mm): named when the mesh has no anticlastic vertex.
    pub lowest_k: (u32, DVec3, f64, f64),
    /// Input vertex numbers (see [`Topology::source_vertex`]) for messages.
    source: Vec<u32>,
}

/// Count and cluster the vertices of `topo.mesh()` without asymptotic
/// directions, and find the singular points, from the vertices' jets.
pub fn anticlastic_report(topo: &Topology, jets: &[VertexJet]) -> AnticlasticReport {
    let nv = topo.vertex_count();
    let pos = &topo.mesh().positions_mm;
    let anticlastic = jets.iter().filter(|j| is_anticlastic(j)).count();
    let mut regions: Vec<Region> =
        clusters(topo, |v| !is_anticlastic(&jets[v as usize]), |_, _| true)
            .into_iter()
            .map(|vertices| {
                let (centroid_mm, vertex) = centre(pos, &vertices);
                Region {
                    synclastic: vertices
                        .iter()
                        .filter(|&&v| is_synclastic(&jets[v as usize]))
                        .count(),
                    vertices,
                    centroid_mm,
                    vertex,
                }
            })
            .collect();
    regions.sort_by(|a, b| {
        b.vertices
            .len()
            .cmp(&a.vertices.len())
            .then(a.vertices[0].cmp(&b.vertices[0]))
    });
    let lowest = (0..nv)
        .min_by(|&a, &b| {
            jets[a]
                .curvature
                .gaussian()
                .total_cmp(&jets[b].curvature.gaussian())
                .then(a.cmp(&b))
        })
        .unwrap_or(0);
    let c = &jets[lowest].curvature;
    AnticlasticReport {
        vertices: nv,
        anticlastic,
        without_asymptotic: nv - anticlastic,
        regions,
        singularities: singularities(topo, jets),
        lowest_k: (lowest as u32, pos[lowest], c.k1, c.k2),
        source: (0..nv as u32).map(|v| topo.source_vertex(v)).collect(),
    }
}

impl AnticlasticReport {
    /// The input's number of a cleaned vertex.
    fn name(&self, v: u32) -> u32 {
        self.source[v as usize]
    }
    /// One line per region without asymptotic directions and per singular
    /// point; empty on a mesh anticlastic everywhere without singular points.
    pub fn warnings(&self) -> Vec<String> {
        let mut w = Vec::new();
        for r in &self.regions {
            let what = if r.synclastic == r.vertices.len() {
                "K > 0: synclastic".to_string()
            } else if r.synclastic == 0 {
                "K ≈ 0 within the curvature estimate's error".to_string()
            } else {
                format!("{} synclastic, the rest K ≈ 0", r.synclastic)
            };
            w.push(format!(
                "{} vertex(es) around {} mm (vertex {}) have no asymptotic directions ({what})",
                r.vertices.len(),
                fmt_point(r.centroid_mm),
                self.name(r.vertex)
            ));
        }
        for s in &self.singularities {
            let what = match s.kind {
                SingularKind::FlatPoint => "flat point: the asymptotic net changes valence there",
                SingularKind::Umbilic => "umbilic (synclastic: no asymptotic directions there)",
            };
            w.push(format!(
                "{what}: at {} mm (vertex {}), principal-line index {:+}",
                fmt_point(s.position_mm),
                self.name(s.vertex),
                s.index
            ));
        }
        w
    }
}

/// Refuse a mesh without any anticlastic vertex (read from `path`): a
/// one-line error naming the vertex nearest to anticlastic.
pub fn require_anticlastic(report: &AnticlasticReport, path: &Path) -> Result<()> {
    if report.anticlastic > 0 {
        return Ok(());
    }
    let (v, p, k1, k2) = report.lowest_k;
    Err(Error::input(
        path,
        Location::Element(format!("vertex {} at {} mm", report.name(v), fmt_point(p))),
        format!(
            "no anticlastic region: K ≥ 0 (or ≈ 0 within the curvature estimate's error) at all {} vertices (here k1 = {k1:.3e}, k2 = {k2:.3e} 1/mm, the lowest K); asymptotic curves need a saddle-shaped surface",
            report.vertices
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::mesh::curvature::vertex_jets;
    use crate::design::mesh::samples;
    use glam::DVec2;

    /// The report of a jittered, rounded grid of `n`² cells over
    /// [x0, x1] × [y0, y1] lifted by `z`.
    fn report(
        n: usize,
        x: (f64, f64),
        y: (f64, f64),
        seed: u64,
        z: impl Fn(f64, f64) -> f64,
    ) -> (AnticlasticReport, Topology, f64) {
        let (uv, tris) = samples::grid(n, n, x, y, 0.3, seed);
        let mesh = samples::place(&uv, &tris, |q: DVec2| DVec3::new(q.x, q.y, z(q.x, q.y)));
        let topo = Topology::build(&mesh, Path::new("s.obj")).expect("valid");
        let jets = vertex_jets(topo.mesh(), &topo);
        let h = (x.1 - x.0) / n as f64;
        (anticlastic_report(&topo, &jets), topo, h)
    }

    #[test]
    fn line_steps_reduce_to_a_half_open_interval() {
        assert_eq!(line_step(0.3), 0.3);
        assert!((line_step(PI - 0.3) + 0.3).abs() < 1e-15);
        assert!((line_step(-PI + 0.3) - 0.3).abs() < 1e-15);
        assert_eq!(line_step(-FRAC_PI_2), FRAC_PI_2);
        assert_eq!(line_step(FRAC_PI_2), FRAC_PI_2);
    }

    /// The monkey saddle z = (x³ − 3xy²)/(1000 mm)² over ±500 mm, 20² cells
    /// (h = 50 mm): one flat point, at the origin, index −1/2 (the Hessian
    /// 6[[x, −y], [−y, −x]] has its eigenvector at −θ/2).
    #[test]
    fn monkey_saddle_has_one_flat_point_of_index_minus_half() {
        for seed in [1, 2, 3] {
            let (r, _, h) = report(20, (-500.0, 500.0), (-500.0, 500.0), seed, |x, y| {
                (x * x * x - 3.0 * x * y * y) / 1e6
            });
            eprintln!("monkey seed {seed}: {:?}", r.warnings());
            assert_eq!(r.singularities.len(), 1, "{:?}", r.singularities);
            let s = &r.singularities[0];
            assert_eq!(s.index, -0.5);
            assert_eq!(s.kind, SingularKind::FlatPoint);
            assert!(s.position_mm.length() < h, "{s:?}");
            require_anticlastic(&r, Path::new("s.obj")).expect("anticlastic");
            // Only vertices near the flat point lack asymptotic directions.
            for reg in &r.regions {
                assert!(reg.centroid_mm.length() < 2.0 * h, "{reg:?}");
            }
        }
    }

    /// The saddle z = xy/1000 mm: anticlastic everywhere, no singular point.
    #[test]
    fn saddle_has_none() {
        let (r, _, _) = report(20, (-500.0, 500.0), (-500.0, 500.0), 4, |x, y| {
            x * y / 1000.0
        });
        assert!(r.singularities.is_empty(), "{:?}", r.singularities);
        assert_eq!(r.anticlastic, r.vertices);
        assert!(r.warnings().is_empty(), "{:?}", r.warnings());
    }

    /// Enneper's surface × 1000 mm over [−1, 1]²: minimal, its only flat
    /// point at infinity: anticlastic everywhere, no singular point.
    #[test]
    fn enneper_has_none() {
        use crate::design::surface::{Enneper, Surface};
        let (uv, tris) = samples::grid(20, 20, (-1.0, 1.0), (-1.0, 1.0), 0.3, 5);
        let mesh = samples::place(&uv, &tris, |q| Enneper.point(q) * 1000.0);
        let topo = Topology::build(&mesh, Path::new("e.obj")).expect("valid");
        let r = anticlastic_report(&topo, &vertex_jets(topo.mesh(), &topo));
        assert!(r.singularities.is_empty(), "{:?}", r.singularities);
        assert_eq!(r.anticlastic, r.vertices);
        assert!(r.warnings().is_empty(), "{:?}", r.warnings());
    }

    /// A sphere cap (R = 1000 mm) is refused in one line naming the file
    /// and a vertex.
    #[test]
    fn sphere_cap_is_refused() {
        let (r, _, _) = report(10, (-500.0, 500.0), (-500.0, 500.0), 6, |x, y| {
            (1e6 - x * x - y * y).sqrt()
        });
        assert_eq!(r.anticlastic, 0);
        let e = require_anticlastic(&r, Path::new("cap.obj"))
            .expect_err("synclastic")
            .to_string();
        assert!(e.starts_with("cap.obj: vertex "), "{e}");
        assert!(e.contains("no anticlastic region"), "{e}");
        assert!(!e.contains('\n'));
        assert_eq!(r.regions.len(), 1);
        assert_eq!(r.regions[0].synclastic, r.vertices);
    }

    /// A plane: flat within the fit's error everywhere: refused, and no
    /// singular point made of noise.
    #[test]
    fn plane_is_refused_without_noise_singularities() {
        let (r, _, _) = report(16, (0.0, 800.0), (0.0, 800.0), 7, |x, y| {
            0.3 * x - 0.2 * y + 5.0
        });
        assert!(r.singularities.is_empty(), "{:?}", r.singularities);
        assert_eq!(r.anticlastic, 0);
        assert!(require_anticlastic(&r, Path::new("p.obj")).is_err());
        assert_eq!(r.regions[0].synclastic, 0);
    }

    /// The ellipsoid x²/a² + y²/b² + z²/c² = 1 (a, b, c = 1000, 800, 600 mm)
    /// has an umbilic at x = a√((a²−b²)/(a²−c²)) = 750 mm, y = 0: a lemon,
    /// index +1/2. A patch around it, 12² cells of 25 mm.
    #[test]
    fn ellipsoid_umbilic() {
        let (a, b, c) = (1000.0f64, 800.0f64, 600.0f64);
        let (r, _, h) = report(12, (600.0, 900.0), (-150.0, 150.0), 8, |x, y| {
            c * (1.0 - x * x / (a * a) - y * y / (b * b)).sqrt()
        });
        eprintln!("ellipsoid: {:?}", r.warnings());
        assert_eq!(r.singularities.len(), 1, "{:?}", r.singularities);
        let s = &r.singularities[0];
        let xu = a * ((a * a - b * b) / (a * a - c * c)).sqrt();
        let zu = c * ((b * b - c * c) / (a * a - c * c)).sqrt();
        assert!(
            (s.position_mm - DVec3::new(xu, 0.0, zu)).length() < h,
            "{s:?}"
        );
        assert_eq!(s.index, 0.5);
        assert_eq!(s.kind, SingularKind::Umbilic);
    }
}
