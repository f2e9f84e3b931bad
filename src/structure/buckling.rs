//! The critical load factor α_cr: the smallest λ > 0 for which
//! (K + K_G,0 + λ·K_G(N)) φ = 0, with K_G,0 the geometric stiffness of the
//! erection state's axial forces (it stays; it is not scaled), N the
//! axial forces of the linear solution under the load set, and following
//! pressures' load stiffness scaled with them.
//!
//! **Method.** Shift-invert subspace iteration (Bathe): with K_e = K +
//! K_G,0 factorised once (sparse Cholesky), iterate Y = K_e⁻¹·(−K_G)·X
//! on a block of p = 2m + 8 vectors; after every step the Rayleigh–Ritz
//! problem (Yᵀ·(−K_G)·Y)·v = μ·(Yᵀ·K_e·Y)·v gives μ = 1/λ. Eigenvalues of
//! either sign appear (λ < 0: buckling under the reversed load, members in
//! tension); the m smallest positive λ are kept. Converged when each of
//! them changes by less than [`TOLERANCE`] relative in one step.

use super::model::{FrameModel, LoadSet};
use super::solve::{axial_forces, Assembly, FrameError, LinearFrame, SymSparse};
use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

/// Relative change of every wanted α_cr in one step at convergence.
pub const TOLERANCE: f64 = 1e-8;

/// Most subspace steps.
pub const MAX_ITERATIONS: usize = 200;

/// A buckling mode.
#[derive(Debug, Clone, PartialEq)]
pub struct BucklingMode {
    /// The critical load factor α_cr.
    pub factor: f64,
    /// The mode shape per node `[ux, uy, uz, rx, ry, rz]`, scaled so that
    /// the largest translation is 1.
    pub shape: Vec<[f64; 6]>,
}

/// The `modes` smallest positive critical load factors of `loads` on
/// `model`, ascending (fewer if fewer exist: a load that only stretches
/// the frame has none).
pub fn critical_factors(
    model: &FrameModel,
    loads: &LoadSet,
    modes: usize,
) -> Result<Vec<BucklingMode>, FrameError> {
    let linear = LinearFrame::new(model)?;
    critical_factors_of(&linear, loads, modes)
}

/// As [`critical_factors`], on a frame already factorised.
pub fn critical_factors_of(
    linear: &LinearFrame<'_>,
    loads: &LoadSet,
    modes: usize,
) -> Result<Vec<BucklingMode>, FrameError> {
    let model = linear.model();
    let first = linear.solve(loads)?;
    let axial = axial_forces(&first);
    let kg = linear.assembly.geometric(model, &axial, Some(loads));
    if modes == 0 || kg.entries.iter().all(|e| e.2 == 0.0) {
        return Ok(Vec::new());
    }
    let found = subspace(linear, &kg, modes)?;
    Ok(found
        .into_iter()
        .map(|(factor, v)| BucklingMode {
            factor,
            shape: shape_of(&linear.assembly, &v),
        })
        .collect())
}

fn shape_of(assembly: &Assembly, v: &[f64]) -> Vec<[f64; 6]> {
    let n = assembly.dofs.index.len() / 6;
    let mut shape: Vec<[f64; 6]> = (0..n)
        .map(|node| {
            let mut d = [0.0; 6];
            for (k, dk) in d.iter_mut().enumerate() {
                let i = assembly.dofs.index[node * 6 + k];
                if i != usize::MAX {
                    *dk = v[i];
                }
            }
            d
        })
        .collect();
    let largest = shape
        .iter()
        .map(|d| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt())
        .fold(0.0, f64::max);
    // Sign: the largest translation component positive (deterministic).
    let mut sign = 1.0;
    let mut best = 0.0;
    for d in &shape {
        for &c in &d[..3] {
            if c.abs() > best {
                best = c.abs();
                sign = c.signum();
            }
        }
    }
    if largest > 0.0 {
        for d in shape.iter_mut() {
            for c in d.iter_mut() {
                *c *= sign / largest;
            }
        }
    }
    shape
}

/// Deterministic start vectors: the diagonal ratio and pseudo-random.
fn start(n: usize, p: usize, kg: &SymSparse, ke: &SymSparse) -> Mat<f64> {
    let (dg, de) = (kg.diagonal(), ke.diagonal());
    let mut x = Mat::<f64>::zeros(n, p);
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    for i in 0..n {
        x[(i, 0)] = if de[i] > 0.0 {
            dg[i].abs() / de[i]
        } else {
            0.0
        };
    }
    for c in 1..p {
        for i in 0..n {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            x[(i, c)] = (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        }
    }
    x
}

fn gram(a: &Mat<f64>, b: &Mat<f64>) -> Mat<f64> {
    a.transpose() * b
}

/// Subspace iteration; returns (λ, vector) for the smallest positive λ.
fn subspace(
    linear: &LinearFrame<'_>,
    kg: &SymSparse,
    modes: usize,
) -> Result<Vec<(f64, Vec<f64>)>, FrameError> {
    let n = kg.n;
    let p = (2 * modes + 8).min(n);
    let mut x = start(n, p, kg, &linear.stiffness);
    let mut previous: Vec<f64> = Vec::new();
    for iteration in 0..MAX_ITERATIONS {
        // Y = K_e⁻¹ · (−K_G) · X.
        let mut gx = kg.mul(&x);
        for c in 0..p {
            for i in 0..n {
                gx[(i, c)] = -gx[(i, c)];
            }
        }
        let mut y = gx.clone();
        linear.factor.llt.solve_in_place(y.as_mut());
        // Rayleigh–Ritz: Ke_r = Yᵀ·K_e·Y = Yᵀ·(−K_G·X); G_r = Yᵀ·(−K_G)·Y.
        let ke_r = symmetric(&gram(&y, &gx));
        let mut gy = kg.mul(&y);
        for c in 0..p {
            for i in 0..n {
                gy[(i, c)] = -gy[(i, c)];
            }
        }
        let g_r = symmetric(&gram(&y, &gy));
        // Whiten Ke_r = U·S·Uᵀ (drop directions the block has lost).
        let e = ke_r
            .self_adjoint_eigen(Side::Lower)
            .map_err(|e| FrameError::Invalid(format!("buckling: {e:?}")))?;
        let (s, u) = (e.S().column_vector(), e.U());
        let smax = (0..p).map(|i| s[i]).fold(0.0, f64::max);
        let keep: Vec<usize> = (0..p).filter(|&i| s[i] > 1e-13 * smax).collect();
        let mut w = Mat::<f64>::zeros(p, keep.len());
        for (c, &i) in keep.iter().enumerate() {
            let f = 1.0 / s[i].sqrt();
            for r in 0..p {
                w[(r, c)] = u[(r, i)] * f;
            }
        }
        let c_r = symmetric(&(w.transpose() * &g_r * &w));
        let ec = c_r
            .self_adjoint_eigen(Side::Lower)
            .map_err(|e| FrameError::Invalid(format!("buckling: {e:?}")))?;
        let (mu, v) = (ec.S().column_vector(), ec.U());
        let q = keep.len();
        // Order by μ descending (largest positive μ = smallest positive λ).
        let mut order: Vec<usize> = (0..q).collect();
        order.sort_by(|&a, &b| mu[b].total_cmp(&mu[a]));
        let vv = &w * v;
        let mut next = Mat::<f64>::zeros(n, p);
        let ritz = &y * &vv;
        for (c, &k) in order.iter().enumerate() {
            for i in 0..n {
                next[(i, c)] = ritz[(i, k)];
            }
        }
        // Refill lost directions with fresh vectors.
        for c in q..p {
            let mut seed: u64 = 0x9e37_79b9 ^ (c as u64 * 7919 + iteration as u64);
            for i in 0..n {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                next[(i, c)] = (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            }
        }
        x = next;
        let lambdas: Vec<f64> = order
            .iter()
            .map(|&k| mu[k])
            .filter(|&m| m > 0.0)
            .map(|m| 1.0 / m)
            .take(modes)
            .collect();
        let converged = lambdas.len() == previous.len()
            && lambdas
                .iter()
                .zip(&previous)
                .all(|(a, b)| ((a - b) / a).abs() < TOLERANCE);
        // Only trust eigenpairs deep inside the block: the wanted ones sit
        // in the first `modes` positive slots of p ≥ 2·modes + 8.
        if converged && iteration > 1 {
            let mut out = Vec::with_capacity(lambdas.len());
            for (c, lambda) in lambdas.iter().enumerate() {
                let col: Vec<f64> = (0..n).map(|i| x[(i, c)]).collect();
                out.push((*lambda, col));
            }
            return Ok(out);
        }
        previous = lambdas;
    }
    Err(FrameError::NotConverged {
        what: "the buckling analysis".into(),
        iterations: MAX_ITERATIONS,
    })
}

fn symmetric(a: &Mat<f64>) -> Mat<f64> {
    let n = a.nrows();
    let mut s = Mat::<f64>::zeros(n, n);
    for i in 0..n {
        for j in 0..n {
            s[(i, j)] = 0.5 * (a[(i, j)] + a[(j, i)]);
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::structure::model::{Beam, InitialForces, NodeLoad, Section, Support};
    use glam::DVec3;

    #[test]
    fn a_column_in_tension_has_no_buckling_mode() {
        let section = Section {
            e_mpa: 210_000.0,
            g_mpa: 81_000.0,
            area_mm2: 75.0,
            i_y_mm4: 15_625.0,
            i_z_mm4: 14.0625,
            j_mm4: 52.0,
        };
        let n = 4;
        let model = FrameModel {
            nodes_mm: (0..=n)
                .map(|i| DVec3::new(250.0 * i as f64, 0.0, 0.0))
                .collect(),
            sections: vec![section],
            beams: (0..n)
                .map(|i| Beam {
                    nodes: [i, i + 1],
                    section: 0,
                    z_axis: DVec3::Z,
                    initial: InitialForces::default(),
                    offsets_mm: [DVec3::ZERO; 2],
                })
                .collect(),
            links: vec![],
            supports: vec![Support {
                node: 0,
                fixed: [true; 6],
                along: None,
            }],
        };
        let loads = LoadSet {
            name: "T".into(),
            nodes: vec![NodeLoad {
                node: n,
                force_n: DVec3::X * 100.0,
                moment_nmm: DVec3::ZERO,
            }],
            ..Default::default()
        };
        let modes = critical_factors(&model, &loads, 3).unwrap();
        assert!(
            modes.is_empty(),
            "{:?}",
            modes.iter().map(|m| m.factor).collect::<Vec<_>>()
        );
    }
}
