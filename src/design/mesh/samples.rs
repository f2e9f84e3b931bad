//! Test meshes sampled from closed forms, as a designer's export would give
//! them: irregular (jittered parameters, random quad diagonals), coordinates
//! rounded to 0.001 mm, no normals.

use super::TriMesh;
use glam::{DVec2, DVec3};

/// A small deterministic generator (splitmix64).
pub struct Rng(pub u64);

impl Rng {
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [−1, 1).
    pub fn sym(&mut self) -> f64 {
        2.0 * self.unit() - 1.0
    }
}

/// The quad `a b c d` (in order round it) as two triangles, split along
/// the diagonal `rng` picks.
fn split_quad(tris: &mut Vec<[u32; 3]>, [a, b, c, d]: [u32; 4], rng: &mut Rng) {
    if rng.unit() < 0.5 {
        tris.push([a, b, c]);
        tris.push([a, c, d]);
    } else {
        tris.push([a, b, d]);
        tris.push([b, c, d]);
    }
}

/// Round to 0.001 mm, as exported coordinates are.
pub fn round_mm(p: DVec3) -> DVec3 {
    (p * 1000.0).round() / 1000.0
}

/// A grid of `nu` × `nv` intervals over [u0, u1] × [v0, v1]: interior
/// parameters jittered by ±`jitter` of a cell in each direction, boundary
/// ones along the boundary only, corners fixed; each cell split along a
/// random diagonal. Triangles are counter-clockwise in (u, v).
pub fn grid(
    nu: usize,
    nv: usize,
    (u0, u1): (f64, f64),
    (v0, v1): (f64, f64),
    jitter: f64,
    seed: u64,
) -> (Vec<DVec2>, Vec<[u32; 3]>) {
    let mut rng = Rng(seed);
    let (du, dv) = ((u1 - u0) / nu as f64, (v1 - v0) / nv as f64);
    let mut uv = Vec::new();
    for j in 0..=nv {
        for i in 0..=nu {
            let mut u = u0 + i as f64 * du;
            let mut v = v0 + j as f64 * dv;
            let (ju, jv) = (rng.sym() * jitter, rng.sym() * jitter);
            if i > 0 && i < nu {
                u += ju * du;
            }
            if j > 0 && j < nv {
                v += jv * dv;
            }
            uv.push(DVec2::new(u, v));
        }
    }
    let id = |i: usize, j: usize| (j * (nu + 1) + i) as u32;
    let mut tris = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            split_quad(&mut tris, [a, b, c, d], &mut rng);
        }
    }
    (uv, tris)
}

/// A mesh of the parameter samples placed by `f` and rounded to 0.001 mm.
pub fn place(uv: &[DVec2], tris: &[[u32; 3]], f: impl Fn(DVec2) -> DVec3) -> TriMesh {
    TriMesh {
        positions_mm: uv.iter().map(|&q| round_mm(f(q))).collect(),
        triangles: tris.to_vec(),
    }
}

/// A flat disk (r0 = 0: centre vertex 0, then `n_r` rings) or annulus
/// (rings from r0 to r1) in z = 0 with `n_theta` vertices per ring; interior
/// rings jittered by ±`jitter` of a step in r and θ; counter-clockwise from
/// +z. Returns the mesh and each vertex's (r, θ).
pub fn polar(
    r0: f64,
    r1: f64,
    n_r: usize,
    n_theta: usize,
    jitter: f64,
    seed: u64,
) -> (TriMesh, Vec<DVec2>) {
    let mut rng = Rng(seed);
    let tau = std::f64::consts::TAU;
    let dt = tau / n_theta as f64;
    let mut rt = Vec::new();
    let first = if r0 == 0.0 {
        rt.push(DVec2::ZERO);
        1
    } else {
        0
    };
    let dr = (r1 - r0) / n_r as f64;
    for i in first..=n_r {
        for k in 0..n_theta {
            let (mut r, mut t) = (r0 + i as f64 * dr, k as f64 * dt);
            let (jr, jt) = (rng.sym() * jitter, rng.sym() * jitter);
            if i > 0 && i < n_r {
                r += jr * dr;
                t += jt * dt;
            }
            rt.push(DVec2::new(r, t));
        }
    }
    let ring = |i: usize, k: usize| (first + (i - first) * n_theta + k % n_theta) as u32;
    let mut tris = Vec::new();
    if first == 1 {
        for k in 0..n_theta {
            tris.push([0, ring(1, k), ring(1, k + 1)]);
        }
    }
    for i in first..n_r {
        for k in 0..n_theta {
            let (a, b, c, d) = (
                ring(i, k),
                ring(i + 1, k),
                ring(i + 1, k + 1),
                ring(i, k + 1),
            );
            split_quad(&mut tris, [a, b, c, d], &mut rng);
        }
    }
    let positions = rt
        .iter()
        .map(|q| round_mm(DVec3::new(q.x * q.y.cos(), q.x * q.y.sin(), 0.0)))
        .collect();
    (
        TriMesh {
            positions_mm: positions,
            triangles: tris,
        },
        rt,
    )
}
