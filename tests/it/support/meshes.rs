//! Triangle meshes sampled from closed forms, written as designers export
//! them: OBJ, coordinates at 0.001 mm, no normals, irregular triangles.

use glam::{DMat3, DVec2, DVec3};
use lamella::design::surface::Surface;

/// A deterministic jitter in [−1, 1] per grid vertex (a hash, no RNG state).
fn jitter(i: usize, j: usize, k: u64) -> f64 {
    let mut x = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (j as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
        ^ k.wrapping_mul(0x1656_67B1_9E37_79F9);
    x ^= x >> 31;
    x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x ^= x >> 29;
    (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
}

/// Vertices (mm) and counter-clockwise triangles of `surface` scaled by
/// `scale_mm` and turned about z by `rot_z_deg` (a spec's placement), over
/// the parameter square [−r, r]² in n × n cells; interior vertices moved by
/// up to `jitter_cells` of a cell, cells split along alternating diagonals.
pub fn param_mesh(
    surface: &dyn Surface,
    scale_mm: f64,
    rot_z_deg: f64,
    r: f64,
    n: usize,
    jitter_cells: f64,
) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let rot = DMat3::from_rotation_z(rot_z_deg.to_radians());
    let h = 2.0 * r / n as f64;
    let mut v = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let mut q = DVec2::new(-r + i as f64 * h, -r + j as f64 * h);
            if i > 0 && j > 0 && i < n && j < n {
                q += DVec2::new(jitter(i, j, 1), jitter(i, j, 2)) * (jitter_cells * h);
            }
            v.push(rot * (surface.point(q) * scale_mm));
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut t = Vec::new();
    for j in 0..n {
        for i in 0..n {
            if (i + j) % 2 == 0 {
                t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            } else {
                t.push([id(i, j), id(i + 1, j), id(i, j + 1)]);
                t.push([id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
    }
    (v, t)
}

/// OBJ text as Rhino exports a mesh: `v` at three decimals, `f` 1-based.
pub fn obj_text(v: &[DVec3], t: &[[u32; 3]]) -> String {
    let mut s = String::from("# lamella test mesh\n");
    for p in v {
        s.push_str(&format!("v {:.3} {:.3} {:.3}\n", p.x, p.y, p.z));
    }
    for f in t {
        s.push_str(&format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1));
    }
    s
}

/// Vertices (mm) and counter-clockwise triangles of the saddle
/// z = (x² − y²) / (2 `r_mm`) over the square [−`half_mm`, `half_mm`]² on a
/// regular n × n grid (no jitter), every cell split along the same
/// diagonal: a mesh with straight rim sides, as a grid exported from a
/// modeller.
pub fn saddle_grid(n: usize, half_mm: f64, r_mm: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let h = 2.0 * half_mm / n as f64;
    let mut v = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (-half_mm + i as f64 * h, -half_mm + j as f64 * h);
            v.push(DVec3::new(x, y, (x * x - y * y) / (2.0 * r_mm)));
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut t = Vec::new();
    for j in 0..n {
        for i in 0..n {
            t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (v, t)
}

/// A triangle mesh as a mesher leaves it: points over the parameter
/// rectangle `lo`–`hi` about `h` apart, moved at random by up to `jitter`
/// of `h` (a seeded generator), those on the rectangle's sides kept on them,
/// triangulated by Delaunay in the parameter plane (the `delaunator` crate,
/// independent of lamella) and placed on `surface` through `place`: every
/// vertex exactly on the surface (rounded when written). Triangles are
/// counter-clockwise in the parameter plane.
pub fn delaunay_mesh(
    lo: DVec2,
    hi: DVec2,
    h: f64,
    jitter: f64,
    seed: u64,
    place: impl Fn(DVec2) -> DVec3,
) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let nu = ((hi.x - lo.x) / h).round().max(1.0) as usize;
    let nv = ((hi.y - lo.y) / h).round().max(1.0) as usize;
    let (hu, hv) = ((hi.x - lo.x) / nu as f64, (hi.y - lo.y) / nv as f64);
    let mut uv = Vec::with_capacity((nu + 1) * (nv + 1));
    for j in 0..=nv {
        for i in 0..=nu {
            let (ju, jv) = (
                jitter * jitter_seeded(i, j, 2 * seed + 1),
                jitter * jitter_seeded(i, j, 2 * seed + 2),
            );
            let on_u_side = i == 0 || i == nu;
            let on_v_side = j == 0 || j == nv;
            let du = if on_u_side { 0.0 } else { ju * hu };
            let dv = if on_v_side { 0.0 } else { jv * hv };
            uv.push(DVec2::new(
                lo.x + i as f64 * hu + du,
                lo.y + j as f64 * hv + dv,
            ));
        }
    }
    let points: Vec<delaunator::Point> = uv
        .iter()
        .map(|q| delaunator::Point { x: q.x, y: q.y })
        .collect();
    let tri = delaunator::triangulate(&points);
    let mut t = Vec::with_capacity(tri.triangles.len() / 3);
    for c in tri.triangles.chunks(3) {
        let [a, b, d] = [c[0], c[1], c[2]];
        let area = (uv[b] - uv[a]).perp_dot(uv[d] - uv[a]);
        if area.abs() < 1e-12 * h * h {
            continue;
        }
        if area > 0.0 {
            t.push([a as u32, b as u32, d as u32]);
        } else {
            t.push([a as u32, d as u32, b as u32]);
        }
    }
    (uv.into_iter().map(place).collect(), t)
}

/// [`jitter`] with a seed folded in.
fn jitter_seeded(i: usize, j: usize, k: u64) -> f64 {
    jitter(i, j, k.wrapping_mul(0x2545_F491_4F6C_DD1D))
}
