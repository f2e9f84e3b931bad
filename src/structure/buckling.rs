//! The critical load factor α_cr: the smallest λ > 0 for which
//! (K + K_G,0 + λ·K_G(N)) φ = 0, with K_G,0 the geometric stiffness of the
//! erection state's axial forces (it stays; it is not scaled), N the
//! axial forces of the linear solution under the load set, and following
//! pressures' load stiffness scaled with them.
//!
//! **Method.** Shift-invert Lanczos: with K_e = K + K_G,0 factorised
//! once (sparse Cholesky), the operator Op = K_e⁻¹·(−K_G) is self-adjoint
//! in the K_e inner product and its eigenvalues are μ = 1/λ; Lanczos in
//! that inner product (one solve and two sparse products per step, full
//! reorthogonalisation twice, so no spurious copies) finds both ends of
//! the spectrum first, and the wanted end is the largest positive μ.
//! Eigenvalues of either sign appear (λ < 0: buckling under the reversed
//! load, members in tension); the m smallest positive λ are kept. A Ritz
//! pair is converged when its residual |β_j·s_j| is below [`TOLERANCE`]·μ
//! (the eigenvalue's error is of the order of its square); at least
//! 2m + 4 steps are taken so that a missing mode would have shown.

use super::model::{FrameModel, LoadSet};
use super::solve::{axial_forces, solve_with, Assembly, FrameError, LinearFrame, SymSparse};
use faer::{Mat, Side};

/// Relative residual of every wanted Ritz pair at convergence: the
/// eigenvalue's relative error is of the order of its square over the gap
/// to the next one (1e-12 for a gap of 1 %). 1e-8 took about a third more
/// steps for no visible digit (the pavilion: 85–160 steps at 1e-6).
pub const TOLERANCE: f64 = 1e-6;

/// Most Lanczos steps.
pub const MAX_ITERATIONS: usize = 400;

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
    let found = lanczos(linear, &kg, modes)?;
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

/// A critical factor and its mode over the unknowns.
type Pair = (f64, Vec<f64>);

/// Lanczos on Op = K_e⁻¹·(−K_G), self-adjoint in the K_e inner product,
/// with full reorthogonalisation (twice); returns (λ, vector) for the
/// smallest positive λ = 1/μ.
fn lanczos(
    linear: &LinearFrame<'_>,
    kg: &SymSparse,
    modes: usize,
) -> Result<Vec<(f64, Vec<f64>)>, FrameError> {
    let ke = &linear.stiffness;
    let n = kg.n;
    let steps = MAX_ITERATIONS.min(n);
    let k_dot = |x: &[f64], y: &[f64]| -> f64 {
        let kx = ke.mul_vec(x);
        kx.iter().zip(y).map(|(a, b)| a * b).sum()
    };
    // A deterministic start: pseudo-random, K_e-normalised.
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut r: Vec<f64> = (0..n)
        .map(|_| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect();
    let norm = k_dot(&r, &r).sqrt();
    r.iter_mut().for_each(|v| *v /= norm);
    let mut q: Vec<Vec<f64>> = vec![r];
    let (mut alpha, mut beta): (Vec<f64>, Vec<f64>) = (Vec::new(), Vec::new());
    for j in 0..steps {
        // w = K_e⁻¹·(−K_G·q_j); α_j = q_jᵀ·(−K_G·q_j).
        let g: Vec<f64> = kg.mul_vec(&q[j]).into_iter().map(|v| -v).collect();
        alpha.push(g.iter().zip(&q[j]).map(|(a, b)| a * b).sum());
        let mut w = solve_with(&linear.factor, &g)?;
        for _pass in 0..2 {
            let kw = ke.mul_vec(&w);
            for qi in &q {
                let c: f64 = kw.iter().zip(qi).map(|(a, b)| a * b).sum();
                w.iter_mut().zip(qi).for_each(|(a, b)| *a -= c * b);
            }
        }
        let b = k_dot(&w, &w).max(0.0).sqrt();
        let exhausted = b.is_nan() || b <= 1e-14 * alpha[j].abs().max(1e-300);
        let check = (j + 1) % 5 == 0 || j + 1 == steps || exhausted;
        if check {
            if let Some(found) = ritz(&q, &alpha, &beta, b, modes)? {
                return Ok(found);
            }
        }
        if exhausted {
            // An invariant subspace: every Ritz pair is exact.
            return Ok(ritz(&q, &alpha, &beta, 0.0, modes)?.unwrap_or_default());
        }
        beta.push(b);
        w.iter_mut().for_each(|v| *v /= b);
        q.push(w);
    }
    Err(FrameError::NotConverged {
        what: "the buckling analysis (Lanczos)".into(),
        iterations: steps,
    })
}

/// The Ritz pairs of the tridiagonal (α, β); `Some` when the wanted ones
/// (the `modes` largest positive μ) have residuals |b·s_last| below
/// [`TOLERANCE`]·μ.
fn ritz(
    q: &[Vec<f64>],
    alpha: &[f64],
    beta: &[f64],
    b: f64,
    modes: usize,
) -> Result<Option<Vec<Pair>>, FrameError> {
    let m = alpha.len();
    let mut t = Mat::<f64>::zeros(m, m);
    for i in 0..m {
        t[(i, i)] = alpha[i];
        if i + 1 < m {
            t[(i + 1, i)] = beta[i];
            t[(i, i + 1)] = beta[i];
        }
    }
    let e = t
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| FrameError::Invalid(format!("buckling: {e:?}")))?;
    let (mu, s) = (e.S().column_vector(), e.U());
    // Ascending μ: the wanted are the last, positive ones.
    let wanted: Vec<usize> = (0..m).rev().filter(|&i| mu[i] > 0.0).take(modes).collect();
    let converged = wanted
        .iter()
        .all(|&i| (b * s[(m - 1, i)]).abs() <= TOLERANCE * mu[i]);
    // Enough steps that a missing mode would have shown (at least twice
    // the modes), unless the space is exhausted.
    if !converged || (m < 2 * modes + 4 && b != 0.0) {
        return Ok(None);
    }
    let n = q[0].len();
    Ok(Some(
        wanted
            .iter()
            .map(|&i| {
                let mut x = vec![0.0; n];
                for (k, qk) in q.iter().enumerate().take(m) {
                    let c = s[(k, i)];
                    x.iter_mut().zip(qk).for_each(|(a, b)| *a += c * b);
                }
                (1.0 / mu[i], x)
            })
            .collect(),
    ))
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
