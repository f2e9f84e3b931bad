//! The cotangent Laplacian: the Dirichlet problem for the interior
//! positions (harmonic extension, one Pinkall–Polthier step), the discrete
//! mean curvature, areas and angles.

use super::Film;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};
use glam::DVec3;

/// A triangle whose area is below this fraction of its two edges' product
/// (sine of its angle) is degenerate: its cotangents are not defined.
pub const DEGENERATE_SINE: f64 = 1e-12;

/// Cotangents of the angles at the three corners of a triangle (corner k
/// faces the edge (k+1, k+2)); `None` if it is degenerate.
pub fn cotangents(p: [DVec3; 3]) -> Option<[f64; 3]> {
    let mut c = [0.0; 3];
    for k in 0..3 {
        let a = p[(k + 1) % 3] - p[k];
        let b = p[(k + 2) % 3] - p[k];
        let cross = a.cross(b).length();
        if cross.is_nan() || cross <= DEGENERATE_SINE * a.length() * b.length() {
            return None;
        }
        c[k] = a.dot(b) / cross;
    }
    Some(c)
}

/// Why a Dirichlet solve failed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SolveFailure {
    /// This triangle is degenerate in the metric the weights are taken from.
    Degenerate(usize),
    /// The factorisation failed (the matrix is not positive definite in
    /// floating point).
    NotPositiveDefinite,
    /// A triangle angle fell below [`super::COLLAPSE_ANGLE_DEG`] (degrees).
    Collapsed(f64),
}

/// The Dirichlet problem on a fixed mesh: interior vertices are unknown,
/// the `fixed` ones keep their positions. The symbolic factorisation is
/// made once per mesh (the pattern depends on the connectivity only).
pub struct Dirichlet {
    unknown: Vec<u32>,
    n: usize,
    symbolic: Option<SymbolicLlt<usize>>,
}

const NONE: u32 = u32::MAX;

impl Dirichlet {
    /// The problem for `film`'s connectivity and fixed vertices.
    pub fn new(film: &Film) -> Self {
        let mut n = 0;
        let unknown = film
            .fixed
            .iter()
            .map(|&f| {
                if f {
                    NONE
                } else {
                    n += 1;
                    (n - 1) as u32
                }
            })
            .collect();
        Dirichlet {
            unknown,
            n,
            symbolic: None,
        }
    }

    /// Positions that minimise the Dirichlet energy Σ_T ½ Σ cot·|Δx|² with
    /// the cotangent weights of the mesh at `metric` (the chart lifted to
    /// z = 0, or the current positions), the fixed vertices at `fixed_at`.
    /// Exact cotangents, obtuse or not: the energy is that of piecewise-linear
    /// maps on non-degenerate triangles, positive definite with the
    /// boundary fixed, so the Cholesky factorisation exists.
    pub fn solve(
        &mut self,
        film: &Film,
        metric: &[DVec3],
        fixed_at: &[DVec3],
    ) -> Result<Vec<DVec3>, SolveFailure> {
        let mut out = fixed_at.to_vec();
        if self.n == 0 {
            return Ok(out);
        }
        let mut trip: Vec<Triplet<usize, usize, f64>> =
            Vec::with_capacity(film.triangles.len() * 9);
        let mut rhs = Mat::<f64>::zeros(self.n, 3);
        for (ti, t) in film.triangles.iter().enumerate() {
            let p = t.map(|v| metric[v as usize]);
            let cot = cotangents(p).ok_or(SolveFailure::Degenerate(ti))?;
            for k in 0..3 {
                let w = 0.5 * cot[k];
                let (i, j) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
                let (ui, uj) = (self.unknown[i], self.unknown[j]);
                for (u, other, uo) in [(ui, j, uj), (uj, i, ui)] {
                    if u == NONE {
                        continue;
                    }
                    let u = u as usize;
                    trip.push(Triplet::new(u, u, w));
                    if uo == NONE {
                        let x = fixed_at[other];
                        rhs[(u, 0)] += w * x.x;
                        rhs[(u, 1)] += w * x.y;
                        rhs[(u, 2)] += w * x.z;
                    } else if (uo as usize) < u {
                        trip.push(Triplet::new(u, uo as usize, -w));
                    }
                }
            }
        }
        let a = SparseColMat::<usize, f64>::try_new_from_triplets(self.n, self.n, &trip)
            .map_err(|_| SolveFailure::NotPositiveDefinite)?;
        if self.symbolic.is_none() {
            self.symbolic = Some(
                SymbolicLlt::try_new(a.symbolic(), Side::Lower)
                    .map_err(|_| SolveFailure::NotPositiveDefinite)?,
            );
        }
        let symbolic = self
            .symbolic
            .clone()
            .ok_or(SolveFailure::NotPositiveDefinite)?;
        let llt = Llt::try_new_with_symbolic(symbolic, a.as_ref(), Side::Lower)
            .map_err(|_| SolveFailure::NotPositiveDefinite)?;
        llt.solve_in_place(rhs.as_mut());
        for (v, &u) in self.unknown.iter().enumerate() {
            if u != NONE {
                let u = u as usize;
                let x = DVec3::new(rhs[(u, 0)], rhs[(u, 1)], rhs[(u, 2)]);
                if !x.is_finite() {
                    return Err(SolveFailure::NotPositiveDefinite);
                }
                out[v] = x;
            }
        }
        Ok(out)
    }
}

/// Tangential relaxation: every interior vertex moves to the area-weighted
/// centroid of its incident triangles' centroids projected into its
/// tangent plane (normal to the area-weighted vertex normal). The move is
/// tangent to first order; its normal error (curvature × move²) is removed
/// by the next Pinkall–Polthier step.
pub fn relax(film: &Film, x: &[DVec3]) -> Vec<DVec3> {
    let nv = x.len();
    let mut centroid = vec![DVec3::ZERO; nv];
    let mut weight = vec![0.0; nv];
    let mut normal = vec![DVec3::ZERO; nv];
    for t in &film.triangles {
        let p = t.map(|v| x[v as usize]);
        let cross = (p[1] - p[0]).cross(p[2] - p[0]);
        let a = 0.5 * cross.length();
        let c = (p[0] + p[1] + p[2]) / 3.0;
        for &v in t {
            let v = v as usize;
            centroid[v] += a * c;
            weight[v] += a;
            normal[v] += cross;
        }
    }
    (0..nv)
        .map(|v| {
            if film.fixed[v] || weight[v] <= 0.0 {
                return x[v];
            }
            let n = normal[v].normalize_or_zero();
            let d = centroid[v] / weight[v] - x[v];
            x[v] + (d - n * n.dot(d))
        })
        .collect()
}

/// The step from `x` to `next` along the vertex normals of `x` only
/// (area-weighted normals): the tangential part of the step is dropped.
pub fn normal_only(film: &Film, x: &[DVec3], next: &[DVec3]) -> Vec<DVec3> {
    let nv = x.len();
    let mut normal = vec![DVec3::ZERO; nv];
    for t in &film.triangles {
        let p = t.map(|v| x[v as usize]);
        let cross = (p[1] - p[0]).cross(p[2] - p[0]);
        for &v in t {
            normal[v as usize] += cross;
        }
    }
    (0..nv)
        .map(|v| {
            if film.fixed[v] {
                return x[v];
            }
            let n = normal[v].normalize_or_zero();
            x[v] + n * n.dot(next[v] - x[v])
        })
        .collect()
}

/// Area of the mesh at `x`, mm².
pub fn area_mm2(film: &Film, x: &[DVec3]) -> f64 {
    film.triangles
        .iter()
        .map(|t| {
            let p = t.map(|v| x[v as usize]);
            0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length()
        })
        .sum()
}

/// |H| at every interior vertex from the cotangent Laplacian:
/// 2H·n = (1/A_i) Σ_j w_ij (x_i − x_j), w_ij = ½(cot α_ij + cot β_ij), A_i
/// the mixed Voronoi area of Meyer, Desbrun, Schröder & Barr (2003): the
/// Voronoi part of each non-obtuse incident triangle, half of an obtuse one
/// at its obtuse corner and a quarter at the others, 1/mm. Returns
/// (|H|, A_i) per interior vertex in vertex order; `None` on a degenerate
/// triangle.
pub fn mean_curvature(film: &Film, x: &[DVec3]) -> Option<Vec<(f64, f64)>> {
    let nv = x.len();
    let mut lap = vec![DVec3::ZERO; nv];
    let mut area = vec![0.0; nv];
    for t in &film.triangles {
        let p = t.map(|v| x[v as usize]);
        let cot = cotangents(p)?;
        let a = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
        let obtuse = (0..3).find(|&k| cot[k] < 0.0);
        for k in 0..3 {
            let w = 0.5 * cot[k];
            let (i, j) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
            lap[i] += w * (x[i] - x[j]);
            lap[j] += w * (x[j] - x[i]);
            area[t[k] as usize] += match obtuse {
                // Voronoi part at corner k: the edges from k weighted by the
                // cotangents of the angles facing them.
                None => {
                    let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
                    (p[k].distance_squared(p[k1]) * cot[k2]
                        + p[k].distance_squared(p[k2]) * cot[k1])
                        / 8.0
                }
                Some(o) if o == k => a / 2.0,
                Some(_) => a / 4.0,
            };
        }
    }
    Some(
        (0..nv)
            .filter(|&v| !film.fixed[v])
            .map(|v| (lap[v].length() / (2.0 * area[v]), area[v]))
            .collect(),
    )
}

/// The smallest interior angle of any triangle at `x`, degrees.
pub fn min_angle_deg(film: &Film, x: &[DVec3]) -> f64 {
    let mut m = 180.0f64;
    for t in &film.triangles {
        let p = t.map(|v| x[v as usize]);
        for k in 0..3 {
            let a = p[(k + 1) % 3] - p[k];
            let b = p[(k + 2) % 3] - p[k];
            m = m.min(a.cross(b).length().atan2(a.dot(b)).to_degrees());
        }
    }
    m
}

/// Mean length of the mesh's edges at `x` (each interior edge counted
/// twice, each boundary edge once), mm.
pub fn mean_edge_mm(film: &Film, x: &[DVec3]) -> f64 {
    let mut sum = 0.0;
    for t in &film.triangles {
        for k in 0..3 {
            sum += x[t[k] as usize].distance(x[t[(k + 1) % 3] as usize]);
        }
    }
    sum / (3 * film.triangles.len()).max(1) as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    /// An icosahedron subdivided `levels` times, projected onto a sphere.
    fn icosphere(radius: f64, levels: usize) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let g = (1.0 + 5f64.sqrt()) / 2.0;
        let mut p: Vec<DVec3> = [
            (-1.0, g, 0.0),
            (1.0, g, 0.0),
            (-1.0, -g, 0.0),
            (1.0, -g, 0.0),
            (0.0, -1.0, g),
            (0.0, 1.0, g),
            (0.0, -1.0, -g),
            (0.0, 1.0, -g),
            (g, 0.0, -1.0),
            (g, 0.0, 1.0),
            (-g, 0.0, -1.0),
            (-g, 0.0, 1.0),
        ]
        .iter()
        .map(|&(a, b, c)| DVec3::new(a, b, c).normalize())
        .collect();
        let mut t: Vec<[u32; 3]> = vec![
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        for _ in 0..levels {
            let mut mid = std::collections::HashMap::new();
            let mut nt = Vec::new();
            for tri in &t {
                let mut m = [0u32; 3];
                for k in 0..3 {
                    let (a, b) = (tri[k], tri[(k + 1) % 3]);
                    m[k] = *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                        p.push((p[a as usize] + p[b as usize]).normalize());
                        (p.len() - 1) as u32
                    });
                }
                nt.push([tri[0], m[0], m[2]]);
                nt.push([m[0], tri[1], m[1]]);
                nt.push([m[2], m[1], tri[2]]);
                nt.push([m[0], m[1], m[2]]);
            }
            t = nt;
        }
        (p.into_iter().map(|q| q * radius).collect(), t)
    }

    #[test]
    fn mean_curvature_of_a_sphere_is_one_over_its_radius() {
        let r = 250.0;
        let (x, t) = icosphere(r, 4);
        let film = Film {
            chart: vec![DVec2::ZERO; x.len()],
            fixed: vec![false; x.len()],
            positions: x.clone(),
            triangles: t,
        };
        let h = mean_curvature(&film, &x).expect("h");
        let worst = h
            .iter()
            .map(|&(h, _)| (h * r - 1.0).abs())
            .fold(0.0, f64::max);
        assert!(worst < 0.02, "|H|·R − 1 up to {worst}");
        // Area converges to 4πR² from below.
        let a = area_mm2(&film, &x);
        let exact = 4.0 * std::f64::consts::PI * r * r;
        assert!(a < exact && a > 0.995 * exact, "{a} vs {exact}");
    }

    #[test]
    fn cotangents_of_a_right_isosceles_triangle() {
        let c = cotangents([DVec3::ZERO, DVec3::X, DVec3::Y]).expect("cot");
        assert!(c[0].abs() < 1e-15 && (c[1] - 1.0).abs() < 1e-15 && (c[2] - 1.0).abs() < 1e-15);
        assert!(cotangents([DVec3::ZERO, DVec3::X, DVec3::X * 2.0]).is_none());
    }
}
