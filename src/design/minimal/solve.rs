//! The cotangent Laplacian: the Dirichlet problem for the interior
//! positions (harmonic extension, one Pinkall–Polthier step), the discrete
//! mean curvature, areas and angles.

use super::Film;
use crate::geom::mesh::bucketed;
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, Mat, Par, Side};
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
/// the `fixed` ones keep their positions. The matrix's pattern depends on
/// the connectivity only, so it is laid out once per mesh with the slot
/// each triangle's weights are summed into; the symbolic factorisation,
/// the factor's values and the solver's workspace are made at the first
/// solve and reused by every later solve on the mesh.
pub struct Dirichlet {
    unknown: Vec<u32>,
    n: usize,
    /// The lower triangle's pattern, column by column, rows ascending (so
    /// each column's diagonal comes first).
    col_start: Vec<usize>,
    rows: Vec<usize>,
    /// Per triangle and corner: the slot of the entry coupling the two
    /// ends of the opposite edge, [`NONE`] if either end is fixed.
    edge_slot: Vec<[u32; 3]>,
    /// Which of faer's factorisations: by the flops per entry of the
    /// factor ([`SupernodalThreshold::AUTO`]) or, in tests, forced.
    threshold: SupernodalThreshold,
    factor: Option<Factor>,
}

/// A symbolic factorisation with the room its numeric factorisation and
/// its solves work in.
struct Factor {
    symbolic: SymbolicCholesky<usize>,
    l_values: Vec<f64>,
    memory: MemBuffer,
}

const NONE: u32 = u32::MAX;

impl Dirichlet {
    /// The problem for `film`'s connectivity and fixed vertices.
    pub fn new(film: &Film) -> Self {
        let mut n = 0;
        let unknown: Vec<u32> = film
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
        let ends = |t: &[u32; 3], k: usize| {
            let (a, b) = (
                unknown[t[(k + 1) % 3] as usize],
                unknown[t[(k + 2) % 3] as usize],
            );
            (a != NONE && b != NONE).then(|| (a.min(b) as usize, a.max(b) as usize))
        };
        // Every unknown's diagonal, and each edge between two unknowns in
        // the column of its smaller end (an interior edge twice, once per
        // triangle: each column is sorted and its repeats dropped).
        let couples = film
            .triangles
            .iter()
            .flat_map(|t| (0..3).filter_map(move |k| ends(t, k)));
        let (start, mut rows) = bucketed(n, (0..n).map(|u| (u, u)).chain(couples));
        let mut col_start = vec![0; n + 1];
        let mut kept = 0;
        for c in 0..n {
            let first = kept;
            rows[start[c]..start[c + 1]].sort_unstable();
            // In place: `kept` never passes the entry being read.
            for i in start[c]..start[c + 1] {
                if kept == first || rows[kept - 1] != rows[i] {
                    rows[kept] = rows[i];
                    kept += 1;
                }
            }
            col_start[c + 1] = kept;
        }
        rows.truncate(kept);
        let edge_slot = film
            .triangles
            .iter()
            .map(|t| {
                std::array::from_fn(|k| match ends(t, k) {
                    Some((c, r)) => {
                        let column = &rows[col_start[c]..col_start[c + 1]];
                        let at = column
                            .binary_search(&r)
                            .expect("every couple is in its column");
                        (col_start[c] + at) as u32
                    }
                    None => NONE,
                })
            })
            .collect();
        Dirichlet {
            unknown,
            n,
            col_start,
            rows,
            edge_slot,
            threshold: SupernodalThreshold::AUTO,
            factor: None,
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
        let mut values = vec![0.0; self.rows.len()];
        let mut rhs = Mat::<f64>::zeros(self.n, 3);
        for (ti, t) in film.triangles.iter().enumerate() {
            let p = t.map(|v| metric[v as usize]);
            let cot = cotangents(p).ok_or(SolveFailure::Degenerate(ti))?;
            for k in 0..3 {
                let w = 0.5 * cot[k];
                let (i, j) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
                let (ui, uj) = (self.unknown[i], self.unknown[j]);
                let slot = self.edge_slot[ti][k];
                if slot != NONE {
                    values[slot as usize] -= w;
                }
                for (u, other, uo) in [(ui, j, uj), (uj, i, ui)] {
                    if u == NONE {
                        continue;
                    }
                    let u = u as usize;
                    values[self.col_start[u]] += w;
                    if uo == NONE {
                        let x = fixed_at[other];
                        rhs[(u, 0)] += w * x.x;
                        rhs[(u, 1)] += w * x.y;
                        rhs[(u, 2)] += w * x.z;
                    }
                }
            }
        }
        let pattern =
            SymbolicSparseColMatRef::new_checked(self.n, self.n, &self.col_start, None, &self.rows);
        let a = SparseColMatRef::new(pattern, &values);
        if self.factor.is_none() {
            // faer picks the simplicial or the supernodal factorisation
            // by the flops per entry of the factor: simplicial on the
            // catenoid's ring, supernodal on the six-point film (each the
            // faster of the two there, by 20 % and 45 %).
            let symbolic = factorize_symbolic_cholesky(
                pattern,
                Side::Lower,
                SymmetricOrdering::Amd,
                CholeskySymbolicParams {
                    supernodal_flop_ratio_threshold: self.threshold,
                    ..Default::default()
                },
            )
            .map_err(|_| SolveFailure::NotPositiveDefinite)?;
            // Sized for one thread (the supernodal factorisation's room
            // depends on the parallelism).
            let memory = MemBuffer::new(StackReq::any_of(&[
                symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()),
                symbolic.solve_in_place_scratch::<f64>(3, Par::Seq),
            ]));
            self.factor = Some(Factor {
                l_values: vec![0.0; symbolic.len_val()],
                symbolic,
                memory,
            });
        }
        let Some(Factor {
            symbolic,
            l_values,
            memory,
        }) = self.factor.as_mut()
        else {
            return Err(SolveFailure::NotPositiveDefinite);
        };
        let llt = symbolic
            .factorize_numeric_llt(
                l_values,
                a,
                Side::Lower,
                LltRegularization::default(),
                Par::Seq,
                MemStack::new(memory),
                Default::default(),
            )
            .map_err(|_| SolveFailure::NotPositiveDefinite)?;
        llt.solve_in_place_with_conj(Conj::No, rhs.as_mut(), Par::Seq, MemStack::new(memory));
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
        // A triangle's smallest angle faces its shortest edge.
        let edge2 = [0, 1, 2].map(|k| p[(k + 1) % 3].distance_squared(p[(k + 2) % 3]));
        let k = (0..3)
            .min_by(|&i, &j| edge2[i].total_cmp(&edge2[j]))
            .unwrap_or(0);
        let a = p[(k + 1) % 3] - p[k];
        let b = p[(k + 2) % 3] - p[k];
        m = m.min(a.cross(b).length().atan2(a.dot(b)).to_degrees());
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

    /// A unit square of `n` × `n` cells, its inner vertices jittered,
    /// each cell split along alternating diagonals; the rim fixed.
    fn jittered_square(n: usize) -> Film {
        let mut state = 11u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let h = 1.0 / n as f64;
        let (mut positions, mut fixed) = (Vec::new(), Vec::new());
        for j in 0..=n {
            for i in 0..=n {
                let rim = i == 0 || j == 0 || i == n || j == n;
                let jitter = if rim {
                    DVec3::ZERO
                } else {
                    DVec3::new(next(), next(), 0.0) * 0.4 * h
                };
                positions.push(DVec3::new(i as f64 * h, j as f64 * h, 0.0) + jitter);
                fixed.push(rim);
            }
        }
        let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
        let mut triangles = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                if (i + j) % 2 == 0 {
                    triangles.extend([[a, b, c], [a, c, d]]);
                } else {
                    triangles.extend([[a, b, d], [b, c, d]]);
                }
            }
        }
        Film {
            chart: positions.iter().map(|p| p.truncate()).collect(),
            positions,
            triangles,
            fixed,
        }
    }

    /// The cotangent Laplacian of a planar mesh reproduces affine maps
    /// (each triangle's gradient is constant, and the weights are those of
    /// the exact energy): with the rim at an affine map's values, every
    /// inner vertex comes back at its own, whatever the triangles' shapes.
    /// The metric may be any affine image of the mesh (a map affine in the
    /// mesh is affine in its image): solved again with a stretched and
    /// turned copy (other weights, the factor made again in the same
    /// room) and with the mesh itself once more, each comes back at its
    /// map, with faer's simplicial and supernodal factorisations alike.
    #[test]
    fn the_dirichlet_solve_reproduces_affine_maps_and_reuses_its_factor() {
        let film = jittered_square(24);
        let maps = [
            |p: DVec3| DVec3::new(2.0 * p.x + 3.0 * p.y, p.x - p.y, 0.5 * p.x + 7.0),
            |p: DVec3| DVec3::new(-p.y, 4.0 * p.x + 1.0, 3.0 * p.x - 2.0 * p.y),
            |p: DVec3| DVec3::new(p.x + 0.25, 0.0, -5.0 * p.y),
        ];
        let stretched = glam::DMat3::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7)
            * glam::DMat3::from_diagonal(DVec3::new(3.0, 1.0, 1.0))
            * 250.0;
        let metrics = [
            film.positions.clone(),
            film.positions.iter().map(|&p| stretched * p).collect(),
            film.positions.clone(),
        ];
        for threshold in [
            SupernodalThreshold::FORCE_SIMPLICIAL,
            SupernodalThreshold::FORCE_SUPERNODAL,
        ] {
            let mut dirichlet = Dirichlet::new(&film);
            dirichlet.threshold = threshold;
            for (map, metric) in maps.iter().zip(&metrics) {
                let rim: Vec<DVec3> = film.positions.iter().map(|&p| map(p)).collect();
                let x = dirichlet.solve(&film, metric, &rim).expect("solves");
                let worst = film
                    .positions
                    .iter()
                    .zip(&x)
                    .map(|(&p, &x)| (x - map(p)).length())
                    .fold(0.0, f64::max);
                assert!(worst < 1e-12, "an inner vertex {worst} off the affine map");
            }
        }
        let mut dirichlet = Dirichlet::new(&film);
        // A degenerate triangle in the metric is named.
        let mut flat = film.positions.clone();
        let [a, b, c] = film.triangles[5].map(|v| v as usize);
        flat[c] = flat[a] + (flat[b] - flat[a]) * 0.5;
        assert_eq!(
            dirichlet.solve(&film, &flat, &film.positions).map(|_| ()),
            Err(SolveFailure::Degenerate(5))
        );
    }

    /// The smallest angle, held to the law of cosines at every corner.
    #[test]
    fn the_smallest_angle_is_the_least_of_every_corners() {
        let film = jittered_square(6);
        let mut x = film.positions.clone();
        for (i, p) in x.iter_mut().enumerate() {
            p.z = (i as f64 * 0.37).sin() * 0.05;
        }
        let mut least = 180.0f64;
        for t in &film.triangles {
            let p = t.map(|v| x[v as usize]);
            for k in 0..3 {
                let (a, b, c) = (
                    p[(k + 1) % 3].distance(p[(k + 2) % 3]),
                    p[k].distance(p[(k + 1) % 3]),
                    p[k].distance(p[(k + 2) % 3]),
                );
                least = least.min(
                    ((b * b + c * c - a * a) / (2.0 * b * c))
                        .acos()
                        .to_degrees(),
                );
            }
        }
        let found = min_angle_deg(&film, &x);
        assert!((found - least).abs() < 1e-9, "{found} vs {least}");
        assert!(least < 40.0, "{least}");
    }

    #[test]
    fn cotangents_of_a_right_isosceles_triangle() {
        let c = cotangents([DVec3::ZERO, DVec3::X, DVec3::Y]).expect("cot");
        assert!(c[0].abs() < 1e-15 && (c[1] - 1.0).abs() < 1e-15 && (c[2] - 1.0).abs() < 1e-15);
        assert!(cotangents([DVec3::ZERO, DVec3::X, DVec3::X * 2.0]).is_none());
    }
}
