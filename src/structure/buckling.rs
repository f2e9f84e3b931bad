//! The critical load factor α_cr: the smallest λ > 0 for which
//! (K + K_G,0 + λ·K_G(N)) φ = 0, with K_G,0 the geometric stiffness of the
//! erection state's axial forces (it stays; it is not scaled), N the
//! axial forces of the linear solution under the load set, and following
//! pressures' load stiffness scaled with them.
//!
//! **Method.** Shift-invert Lanczos: with K_e = K + K_G,0 factorised
//! once (sparse Cholesky), the operator Op = K_e⁻¹·(−K_G) is self-adjoint
//! in the K_e inner product and its eigenvalues are μ = 1/λ; Lanczos in
//! that inner product (one solve per step, the new vector's cosine with
//! every basis vector computed and every one above 1e-9 taken out, so the
//! basis stays semi-orthogonal and no spurious copies appear; the basis
//! thick-restarted at a fixed
//! size, so every step costs the same) finds both ends of the spectrum
//! first, and the wanted end is the largest positive μ. That run stops
//! once the first factor is known roughly; the pencil is then shifted to
//! 0.98 of it (A = K_e + σ·K_G, factorised once more, ν = 1/(λ − σ)) and
//! the wanted modes are found on it, two vectors per step (a symmetric
//! grid's modes come in pairs of near-equal factors): the shift spreads a
//! clustered wanted end (a large grid's many near-equal local modes)
//! apart from the rest.
//! Eigenvalues of either sign appear (λ < 0: buckling under the reversed
//! load, members in tension); the m smallest positive λ are kept. A Ritz
//! pair is converged when its residual |β_j·s_j| is below [`TOLERANCE`]·μ
//! (the eigenvalue's error is of the order of its square); at least
//! 2m + 4 steps are taken so that a missing mode would have shown.

use super::model::{FrameModel, LoadSet};
use super::solve::{
    add, axial_forces, factorise_definite, Assembly, Dofs, Factor, FrameError, GeometricTerms,
    LinearFrame, StaticResult, SymSparse, PARALLEL_ROWS,
};
use crate::geom::dot;
use faer::{Mat, MatMut, MatRef, Side};

/// Relative residual of every wanted Ritz pair at convergence: the
/// eigenvalue's relative error is of the order of its square over the gap
/// to the next one (1e-8 for a gap of 1 %), the mode's of the residual
/// over the gap. At 1e-6 the benchmark grids took 82 vectors in place of
/// 76 (100 × 100 curves) and 62 in place of 56 (40 × 40), for factors the
/// same to 2e-13; 1e-8 about a third more steps again (the pavilion:
/// 85–160 steps at 1e-6).
pub const TOLERANCE: f64 = 1e-5;

/// Relative residual of the rough first factor the shift is taken from:
/// with |r| ≤ 0.02·θ some μ lies within 2 % of the Ritz value θ, and θ is
/// below the largest μ₁ (Lanczos approaches the end of the spectrum from
/// inside), so where that μ is μ₁ the shift 0.98/θ ([`SHIFT_FRACTIONS`])
/// is below λ₁ = 1/μ₁ (0.98 · 1.02 < 1). Where it is not, the shifted
/// pencil is not positive definite and the next fraction is tried. At
/// 1e-2 the 100 × 100 benchmark grid took 43 rough steps in place of 20
/// (the residual stalls near 1.1e-2 for 20 steps), for a shift further
/// from λ₁.
pub const PROBE_TOLERANCE: f64 = 0.02;

/// The shift as a fraction of the rough first factor, tried in turn until
/// the shifted pencil is positive definite (the shift below the smallest
/// factor): the nearer, the more the wanted end is spread.
pub const SHIFT_FRACTIONS: [f64; 3] = [0.98, 0.9, 0.5];

/// Most Lanczos vectors (solved for), over all restarts.
pub const MAX_ITERATIONS: usize = 3000;

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
    let first = linear.solve(loads)?;
    critical_factors_given(linear, loads, &first, modes)
}

/// As [`critical_factors_of`], given the static solution `first` of
/// `loads` on `linear` (the analysis has it already).
pub fn critical_factors_given(
    linear: &LinearFrame<'_>,
    loads: &LoadSet,
    first: &StaticResult,
    modes: usize,
) -> Result<Vec<BucklingMode>, FrameError> {
    critical_factors_with(linear, loads, first, modes, GeometricTerms::Full)
}

/// As [`critical_factors`] with the flexural geometric terms only (no
/// polar term of torsional buckling), as a frame program's P-Delta
/// transformation computes it: for comparing with one (OpenSees). On a
/// grid of timber strips, whose shear modulus is low, the polar term
/// lowers α_cr markedly (the two-level poplar hypar: 6.55 without it,
/// 5.54 with it).
pub fn critical_factors_flexural(
    model: &FrameModel,
    loads: &LoadSet,
    modes: usize,
) -> Result<Vec<BucklingMode>, FrameError> {
    let linear = LinearFrame::new(model)?;
    let first = linear.solve(loads)?;
    critical_factors_with(&linear, loads, &first, modes, GeometricTerms::Flexural)
}

fn critical_factors_with(
    linear: &LinearFrame<'_>,
    loads: &LoadSet,
    first: &StaticResult,
    modes: usize,
    terms: GeometricTerms,
) -> Result<Vec<BucklingMode>, FrameError> {
    let model = linear.model();
    // The load's share: the pretension's state is in the stiffness.
    let less = |total: Vec<f64>, pre: &[f64]| -> Vec<f64> {
        if pre.is_empty() {
            total
        } else {
            total.iter().zip(pre).map(|(a, b)| a - b).collect()
        }
    };
    let axial = less(axial_forces(first), &linear.pre_axial);
    let cable_n = less(first.cable_forces_n.clone(), &linear.pre_cable_n);
    let mut kg = linear
        .assembly
        .geometric_terms(model, &axial, Some(loads), terms);
    if cable_n.iter().any(|&n| n != 0.0) {
        kg = add(
            &kg,
            &linear.assembly.cable_geometric_signed(model, &cable_n),
            1.0,
        );
    }
    if modes == 0 || kg.values.iter().all(|&v| v == 0.0) {
        return Ok(Vec::new());
    }
    // The pretension's state stiffens (or softens) the frame the load
    // then buckles.
    let stiffened = match &linear.pre_geometric {
        None => None,
        Some(g) => {
            let a = add(&linear.stiffness, g, 1.0);
            match factorise_definite(&a, &linear.assembly.dofs)? {
                Some(factor) => Some((a, factor)),
                // The pretension alone buckles the frame: no load can
                // be added, α_cr = 0 (the mode is not computed).
                None => {
                    return Ok(vec![BucklingMode {
                        factor: 0.0,
                        shape: vec![[0.0; 6]; model.nodes_mm.len()],
                    }])
                }
            }
        }
    };
    let (base, base_factor) = match &stiffened {
        Some((a, f)) => (a, f),
        None => (&linear.stiffness, &linear.factor),
    };
    let found = shifted_lanczos(base, base_factor, &kg, &linear.assembly.dofs, modes)?;
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

/// The pencil shifted by σ: A = K_e + σ·K_G, factorised. Its
/// eigenproblem K_e·φ = −λ·K_G·φ reads A⁻¹·(−K_G)·φ = ν·φ with
/// ν = 1/(λ − σ): self-adjoint in the A inner product while A is positive
/// definite, i.e. while σ is below the smallest positive λ.
struct Pencil<'a> {
    /// The unshifted matrix K_e (A = K_e + σ·K_G is not kept: only the
    /// start vector is multiplied by it).
    stiffness: &'a SymSparse,
    /// The factor of A.
    factor: &'a Factor,
    shift: f64,
}

/// The `modes` smallest positive critical factors and their vectors.
///
/// A first Lanczos run on the unshifted pencil finds the smallest factor
/// roughly ([`PROBE_TOLERANCE`]); the pencil is then shifted to
/// [`SHIFT_FRACTIONS`] of it and factorised once more, which spreads the
/// wanted end of the spectrum (ν = 1/(λ − σ)) and takes a clustered
/// spectrum (a large grid's many near-equal local modes) in a fraction of
/// the steps. Should the shifted pencil not be positive definite (the
/// shift above the smallest factor), the next fraction is tried, and
/// without one below the smallest factor the unshifted pencil is run to
/// the end.
fn shifted_lanczos(
    stiffness: &SymSparse,
    factor: &Factor,
    kg: &SymSparse,
    dofs: &Dofs,
    modes: usize,
) -> Result<Vec<(f64, Vec<f64>)>, FrameError> {
    let sizes = (basis_size(modes), kept(modes), BLOCK);
    let paired = (basis_size(modes), kept(modes), SHIFTED_BLOCK);
    let plain = Pencil {
        stiffness,
        factor,
        shift: 0.0,
    };
    // Room for the shifted run's wider blocks from the start: the rough
    // run's space is then the shifted run's, allocated once.
    let mut space = Space::default();
    space.fit(kg.n, paired.0.min(kg.n) + paired.2);
    let rough = lanczos_restarted(&plain, kg, 1, sizes, PROBE_TOLERANCE, &mut space)?;
    let Some(&(estimate, _)) = rough.first() else {
        return Ok(Vec::new());
    };
    for fraction in SHIFT_FRACTIONS {
        let shift = fraction * estimate;
        // A itself is dropped once factorised.
        let factor = factorise_definite(&add(stiffness, kg, shift), dofs)?;
        if let Some(factor) = factor {
            let pencil = Pencil {
                stiffness,
                factor: &factor,
                shift,
            };
            return lanczos_restarted(&pencil, kg, modes, paired, TOLERANCE, &mut space);
        }
    }
    lanczos_restarted(&plain, kg, modes, paired, TOLERANCE, &mut space)
}

/// Block Lanczos on Op = A⁻¹·(−K_G) (A the shifted pencil), self-adjoint
/// in the A inner product, with selective reorthogonalisation and thick
/// restarts; returns (λ = σ + 1/ν, vector) for the `modes` largest
/// positive ν (the smallest λ above the shift σ), each converged to a
/// residual of `tolerance`·ν.
///
/// The basis V grows by blocks of `block` vectors ([`BLOCK`],
/// [`SHIFTED_BLOCK`]): a block W = A⁻¹·(−K_G·Q_j) is one solve of that
/// many right-hand sides.
/// A·V is kept beside V, and A·W is −K_G·Q_j itself (the solve is
/// backward stable, where a product with A, stiff joints beside slender
/// strips, would lose digits). W is made A-orthogonal to the basis by
/// classical Gram–Schmidt through matrix products (C = Vᵀ·A·W, then
/// W −= V_S·C_S and A·W −= (A·V)_S·C_S over the basis vectors S whose
/// cosine with W exceeds [`SEMI_ORTHOGONAL`]), a second time where the
/// first cancelled all but [`CANCELLED`] of a column; the sum of the C_S
/// is column block j of the projected operator H = Vᵀ·A·Op·V. The block is then made A-orthonormal within
/// itself through the eigen-decomposition of its Gram matrix
/// G = Wᵀ·A·W = U·Λ·Uᵀ (Q_{j+1} = W·U·Λ^-½, W = Q_{j+1}·B with
/// B = Λ^½·Uᵀ; directions with a negligible Λ are dropped: the Krylov
/// space is exhausted there). The Ritz pair (ν_i, V·s_i) of H has the
/// residual Q_{j+1}·B·s_i, whose A-norm is |B·s_i| over s_i's last block.
/// When the basis reaches `basis_max` vectors, it is cut to the `keep`
/// Ritz vectors of largest positive ν (the wanted ones and a margin) and
/// the new block, with H = diag(ν) bordered by B·s_i (Wu & Simon's thick
/// restart), so every step costs O(basis·n) however many a clustered
/// spectrum needs.
fn lanczos_restarted(
    pencil: &Pencil<'_>,
    kg: &SymSparse,
    modes: usize,
    (basis_max, keep, block): (usize, usize, usize),
    tolerance: f64,
    space: &mut Space,
) -> Result<Vec<(f64, Vec<f64>)>, FrameError> {
    let n = kg.n;
    let basis_max = basis_max.min(n);
    let keep = keep.min(basis_max.saturating_sub(2));
    let block = block.min((basis_max - keep) / 2).clamp(1, n.max(1));
    // A deterministic start: pseudo-random, A-orthonormalised.
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let start = Mat::<f64>::from_fn(n, block, |_, _| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    });
    let mut a_start = pencil.stiffness.mul_block(start.as_ref());
    if pencil.shift != 0.0 {
        a_start += kg.mul_block(start.as_ref()) * faer::Scale(pencil.shift);
    }
    let (first, a_first, _) = a_orthonormal(&start, &a_start, 0.0);
    if first.ncols() == 0 {
        return Ok(Vec::new());
    }
    // The basis V (its first `size` columns) and H over it.
    let capacity = basis_max + block;
    let Space { v, av } = space.fit(n, capacity);
    let mut h = Mat::<f64>::zeros(capacity, capacity);
    v.as_mut()
        .subcols_mut(0, first.ncols())
        .copy_from(first.as_ref());
    av.as_mut()
        .subcols_mut(0, first.ncols())
        .copy_from(a_first.as_ref());
    let mut current = 0..first.ncols();
    let mut vectors = 0;
    while vectors < MAX_ITERATIONS {
        let size = current.end;
        let q = v.as_ref().subcols(current.start, current.len());
        // W = A⁻¹·(−K_G·Q_j): A·W is −K_G·Q_j.
        let mut aw = kg.mul_block(q);
        aw = -aw;
        let mut w = aw.clone();
        pencil.factor.solve_in_place(w.as_mut());
        if !w.as_ref().is_all_finite() {
            return Err(FrameError::Unstable(
                "a solve gave non-finite displacements".into(),
            ));
        }
        // A-orthogonal to the basis (classical Gram–Schmidt), A·W
        // carried along from A·V: the solve is backward stable, so −K_G·Q_j
        // is W's A-image to round-off, where a product with A (stiff joints
        // beside slender strips) would lose digits. C is H's column block.
        let basis = v.as_ref().subcols(0, size);
        let a_basis = av.as_ref().subcols(0, size);
        // Each pass subtracts only the basis vectors W leans on (a cosine
        // above [`SEMI_ORTHOGONAL`]): those against W as it was, then any
        // W without them still leans on; the rest of the basis is not
        // read again. A second pass only where the first cancelled nearly
        // all of a column ([`CANCELLED`]), since only then can its
        // round-off have left W leaning on the basis.
        let mut c = Mat::<f64>::zeros(size, current.len());
        let mut before = a_norms(&w, &aw);
        for _pass in 0..2 {
            let step = transpose_times(basis, aw.as_ref());
            let leans = |i: usize, norms: &[f64]| {
                (0..step.ncols()).any(|k| step[(i, k)].abs() > SEMI_ORTHOGONAL * norms[k])
            };
            let mut taken: Vec<usize> = (0..size).filter(|&i| leans(i, &before)).collect();
            subtract_products(
                w.as_mut(),
                aw.as_mut(),
                (basis, a_basis),
                step.as_ref(),
                &taken,
            );
            let mut after = a_norms(&w, &aw);
            let more: Vec<usize> = (0..size)
                .filter(|&i| !taken.contains(&i) && leans(i, &after))
                .collect();
            if !more.is_empty() {
                subtract_products(
                    w.as_mut(),
                    aw.as_mut(),
                    (basis, a_basis),
                    step.as_ref(),
                    &more,
                );
                after = a_norms(&w, &aw);
                taken.extend(more);
            }
            for &i in &taken {
                for k in 0..step.ncols() {
                    c[(i, k)] += step[(i, k)];
                }
            }
            if after.iter().zip(&before).all(|(a, b)| *a > CANCELLED * b) {
                break;
            }
            before = after;
        }
        h.as_mut()
            .submatrix_mut(0, current.start, size, current.len())
            .copy_from(c.as_ref());
        let scale = (current.clone())
            .map(|i| h[(i, i)].abs())
            .fold(0.0, f64::max);
        let (next, a_next, b) = a_orthonormal(&w, &aw, scale);
        vectors += current.len();
        let (mu, s) = ritz_values(&h, size)?;
        // B·s_i over the last block: the residual's coordinates in the
        // next block (its A-norm is their length).
        let coupling = |i: usize| -> Vec<f64> {
            (0..b.nrows())
                .map(|r| {
                    current
                        .clone()
                        .enumerate()
                        .map(|(k, row)| b[(r, k)] * s[(row, i)])
                        .sum::<f64>()
                })
                .collect()
        };
        let residual = |i: usize| -> f64 { coupling(i).iter().map(|x| x * x).sum::<f64>().sqrt() };
        let wanted = wanted_of(&mu, modes);
        let exhausted = next.ncols() == 0 || size + next.ncols() > n;
        // Enough vectors that a missing mode would have shown (at least
        // twice the modes), unless the space is exhausted.
        let converged = vectors >= 2 * modes + 4
            && wanted.iter().all(|&i| {
                let r = if exhausted { 0.0 } else { residual(i) };
                r <= tolerance * mu[i]
            });
        if converged || exhausted {
            return Ok(wanted
                .iter()
                .map(|&i| (pencil.shift + 1.0 / mu[i], ritz_vector(basis, &s, i)))
                .collect());
        }
        let grown = next.ncols();
        if size + grown > basis_max {
            // Thick restart: the kept Ritz vectors, then the new block;
            // H = diag(μ) bordered by B·s_i.
            let keep_ids = wanted_of(&mu, keep);
            let kept = keep_ids.len();
            let mut picked = Mat::<f64>::zeros(size, kept);
            for (k, &i) in keep_ids.iter().enumerate() {
                for row in 0..size {
                    picked[(row, k)] = s[(row, i)];
                }
            }
            let couplings: Vec<Vec<f64>> = keep_ids.iter().map(|&i| coupling(i)).collect();
            combine_in_place(v.as_mut(), size, &picked);
            combine_in_place(av.as_mut(), size, &picked);
            h.fill(0.0);
            for (k, &i) in keep_ids.iter().enumerate() {
                h[(k, k)] = mu[i];
                for (r, &coupling) in couplings[k].iter().enumerate() {
                    h[(kept + r, k)] = coupling;
                    h[(k, kept + r)] = coupling;
                }
            }
            current = kept..kept + grown;
        } else {
            for r in 0..grown {
                for (k, col) in current.clone().enumerate() {
                    h[(size + r, col)] = b[(r, k)];
                    h[(col, size + r)] = b[(r, k)];
                }
            }
            current = size..size + grown;
        }
        v.as_mut()
            .subcols_mut(current.start, grown)
            .copy_from(next.as_ref());
        av.as_mut()
            .subcols_mut(current.start, grown)
            .copy_from(a_next.as_ref());
    }
    Err(FrameError::NotConverged {
        what: "the buckling analysis (Lanczos)".into(),
        iterations: MAX_ITERATIONS,
    })
}

/// The cosine (in the A inner product) between W and a basis vector
/// below which Gram–Schmidt leaves that vector out: well below √ε
/// (1.5e-8), the semi-orthogonality under which the projected operator is
/// the Lanczos relation's to working precision (Simon, 1984), so the Ritz
/// values are as accurate as with the whole basis subtracted. In exact
/// arithmetic W leans on the last two blocks only (and after a restart on
/// the kept Ritz vectors); subtracting the whole basis twice per step
/// read it six times, where computing the cosines reads it once.
pub const SEMI_ORTHOGONAL: f64 = 1e-9;

/// The fraction of W's A-norm below which Gram–Schmidt's first pass is
/// followed by a second. The first pass leaves W leaning on the basis by
/// its round-off, about ε·|W before|/|W after| (ε = 1.1e-16), so below
/// [`SEMI_ORTHOGONAL`] with a margin of 10⁴ until W falls below 1e-3 of
/// what it was. Daniel, Gragg, Kaufman and Stewart's 1/√2 makes W
/// orthogonal to working precision, more than Lanczos needs: on the
/// benchmark's grids it called a second pass at nearly every step (the
/// first pass takes off half to two thirds of W), and that pass found
/// nothing above 2e-9.
pub const CANCELLED: f64 = 1e-3;

/// The room for a Lanczos basis V and its image A·V, shared by the rough
/// and the shifted run: at 100 × 100 curves the two are 316 MB, whose
/// first touch (the kernel zeroing every page) took 0.5 s per run. Only
/// the columns a run has written are read.
struct Space {
    v: Mat<f64>,
    av: Mat<f64>,
}

impl Default for Space {
    fn default() -> Space {
        Space {
            v: Mat::zeros(0, 0),
            av: Mat::zeros(0, 0),
        }
    }
}

impl Space {
    /// The space with room for `columns` vectors of `n`.
    fn fit(&mut self, n: usize, columns: usize) -> &mut Space {
        if self.v.nrows() != n || self.v.ncols() < columns {
            self.v = Mat::zeros(n, columns);
            self.av = Mat::zeros(n, columns);
        }
        self
    }
}

/// Vectors per block of [`lanczos_restarted`] on the unshifted pencil
/// (the rough first factor): one. Blocks of more share the reads of the
/// factor and the basis between their vectors (a solve of two right-hand
/// sides costs about one of one at 100 × 100, eight about four), but the
/// rough run wants one mode, and the benchmark's 40 × 40 grid took 29
/// vectors with one, 58 with two and 124 with four, each run longer.
pub const BLOCK: usize = 1;

/// Vectors per block on the shifted pencil: two. A symmetric grid's modes
/// come in pairs of near-equal factors (the benchmark's Enneper grids,
/// with their fourfold symmetry: 0.195411223 and 0.195411257 at 40 × 40),
/// and one vector's Krylov space holds one direction of such a pair: the
/// other appears only as round-off brings it in, many steps on. A block
/// of two holds both from the start. On the 40 × 40 grid the six modes
/// took 54 vectors one by one, 64 two by two (32 solves) in 0.7 of the
/// time, 96 three or four at a time; the 100 × 100 grid 93 against 102,
/// 14.3 s against 10.8 s.
pub const SHIFTED_BLOCK: usize = 2;

/// Q, A·Q and B with W = Q·B, Q A-orthonormal (given A·W): from the Gram
/// matrix G = Wᵀ·A·W = U·Λ·Uᵀ, Q = W·U·Λ^-½ and B = Λ^½·Uᵀ, keeping the
/// directions whose Λ^½ exceeds 1e-13 × `scale` (and any positive one
/// when `scale` is 0).
fn a_orthonormal(w: &Mat<f64>, aw: &Mat<f64>, scale: f64) -> (Mat<f64>, Mat<f64>, Mat<f64>) {
    let p = w.ncols();
    let g = transpose_times(w.as_ref(), aw.as_ref());
    let mut sym = Mat::<f64>::zeros(p, p);
    for i in 0..p {
        for k in 0..p {
            sym[(i, k)] = 0.5 * (g[(i, k)] + g[(k, i)]);
        }
    }
    let Ok(e) = sym.self_adjoint_eigen(Side::Lower) else {
        return (
            Mat::zeros(w.nrows(), 0),
            Mat::zeros(w.nrows(), 0),
            Mat::zeros(0, p),
        );
    };
    let largest = (0..p)
        .map(|i| e.S().column_vector()[i])
        .fold(0.0, f64::max)
        .sqrt();
    let floor = if scale > 0.0 {
        1e-13 * scale
    } else {
        1e-13 * largest
    };
    let kept: Vec<usize> = (0..p)
        .rev()
        .filter(|&i| {
            let l = e.S().column_vector()[i];
            l > 0.0 && l.sqrt() > floor
        })
        .collect();
    let u = e.U();
    let mut to_q = Mat::<f64>::zeros(p, kept.len());
    let mut b = Mat::<f64>::zeros(kept.len(), p);
    for (k, &i) in kept.iter().enumerate() {
        let root = e.S().column_vector()[i].sqrt();
        for r in 0..p {
            to_q[(r, k)] = u[(r, i)] / root;
            b[(k, r)] = u[(r, i)] * root;
        }
    }
    (w * &to_q, aw * &to_q, b)
}

/// The A-norm of every column of W (given A·W).
fn a_norms(w: &Mat<f64>, aw: &Mat<f64>) -> Vec<f64> {
    (0..w.ncols())
        .map(|c| {
            w.col(c)
                .iter()
                .zip(aw.col(c).iter())
                .map(|(a, b)| a * b)
                .sum::<f64>()
                .max(0.0)
                .sqrt()
        })
        .collect()
}

/// Rows per pass of [`transpose_times`] and [`subtract_products`]: a pass
/// keeps its rows of the few columns it updates or reads for every basis
/// vector in the first-level cache, so the basis is read once per product.
const ROWS_PER_PASS: usize = 512;

/// The columns of a matrix whose columns are contiguous (a `Mat` and its
/// column ranges), as slices.
fn columns(m: MatRef<'_, f64>) -> Vec<&[f64]> {
    m.col_iter()
        .map(|c| {
            c.try_as_col_major()
                .expect("columns are contiguous")
                .as_slice()
        })
        .collect()
}

/// Xᵀ·Y (Y of a few columns) in passes of [`ROWS_PER_PASS`] rows, the
/// rows split between two threads.
fn transpose_times(x: MatRef<'_, f64>, y: MatRef<'_, f64>) -> Mat<f64> {
    let (n, k, p) = (x.nrows(), x.ncols(), y.ncols());
    let (xs, ys) = (columns(x), columns(y));
    let rows = |range: std::ops::Range<usize>| -> Vec<f64> {
        let mut out = vec![0.0; k * p];
        let mut start = range.start;
        while start < range.end {
            let end = (start + ROWS_PER_PASS).min(range.end);
            for (c, yc) in ys.iter().enumerate() {
                let yc = &yc[start..end];
                for (i, xi) in xs.iter().enumerate() {
                    out[c * k + i] += dot(&xi[start..end], yc);
                }
            }
            start = end;
        }
        out
    };
    let out = if n < PARALLEL_ROWS {
        rows(0..n)
    } else {
        let (top, bottom) = rayon::join(|| rows(0..n / 2), || rows(n / 2..n));
        top.iter().zip(&bottom).map(|(a, b)| a + b).collect()
    };
    Mat::from_fn(k, p, |i, c| out[c * k + i])
}

/// W ← W − X_S·C_S and A·W ← A·W − (A·X)_S·C_S, S the columns of X
/// (rows of C) `among`, in passes of [`ROWS_PER_PASS`] rows, the rows
/// split between two threads: only the basis vectors named are read.
fn subtract_products(
    w: MatMut<'_, f64>,
    aw: MatMut<'_, f64>,
    (x, ax): (MatRef<'_, f64>, MatRef<'_, f64>),
    c: MatRef<'_, f64>,
    among: &[usize],
) {
    if among.is_empty() {
        return;
    }
    let n = w.nrows();
    let update = |w: MatMut<'_, f64>, x: MatRef<'_, f64>| {
        let xs: Vec<&[f64]> = among
            .iter()
            .map(|&i| {
                x.col(i)
                    .try_as_col_major()
                    .expect("columns are contiguous")
                    .as_slice()
            })
            .collect();
        let mut ws: Vec<&mut [f64]> = w
            .col_iter_mut()
            .map(|col| {
                col.try_as_col_major_mut()
                    .expect("columns are contiguous")
                    .as_slice_mut()
            })
            .collect();
        let rows = xs.first().map_or(0, |x| x.len());
        let mut start = 0;
        while start < rows {
            let end = (start + ROWS_PER_PASS).min(rows);
            for (j, wj) in ws.iter_mut().enumerate() {
                let wj = &mut wj[start..end];
                for (&i, xi) in among.iter().zip(&xs) {
                    let a = c[(i, j)];
                    wj.iter_mut()
                        .zip(&xi[start..end])
                        .for_each(|(w, x)| *w -= a * x);
                }
            }
            start = end;
        }
    };
    let both = |w: MatMut<'_, f64>, aw: MatMut<'_, f64>, rows: std::ops::Range<usize>| {
        update(w, x.subrows(rows.start, rows.len()));
        update(aw, ax.subrows(rows.start, rows.len()));
    };
    if n < PARALLEL_ROWS {
        both(w, aw, 0..n);
        return;
    }
    let half = n / 2;
    let (top, bottom) = w.split_at_row_mut(half);
    let (a_top, a_bottom) = aw.split_at_row_mut(half);
    rayon::join(
        || both(top, a_top, 0..half),
        || both(bottom, a_bottom, half..n),
    );
}

/// X's first columns ← X's first `size` columns times `c` (size × k),
/// row by row in place, in passes of [`ROWS_PER_PASS`] rows split
/// between two threads: a restart's Ritz vectors made where the basis is,
/// with no n × k product allocated and copied in (at 100 × 100 curves two
/// of 73 MB per restart, on one thread).
fn combine_in_place(x: MatMut<'_, f64>, size: usize, c: &Mat<f64>) {
    let k = c.ncols();
    let rows = |mut x: MatMut<'_, f64>| {
        let n = x.nrows();
        let mut old = vec![0.0; ROWS_PER_PASS * size];
        let mut new = vec![0.0; ROWS_PER_PASS * k];
        let mut start = 0;
        while start < n {
            let len = (start + ROWS_PER_PASS).min(n) - start;
            for col in 0..size {
                let from = x.as_ref().col(col).subrows(start, len);
                old[col * len..(col + 1) * len]
                    .iter_mut()
                    .zip(from.iter())
                    .for_each(|(o, f)| *o = *f);
            }
            for out in 0..k {
                let target = &mut new[out * len..(out + 1) * len];
                target.fill(0.0);
                for col in 0..size {
                    let a = c[(col, out)];
                    if a != 0.0 {
                        target
                            .iter_mut()
                            .zip(&old[col * len..(col + 1) * len])
                            .for_each(|(t, o)| *t += a * o);
                    }
                }
            }
            for out in 0..k {
                let mut to = x.as_mut().col_mut(out).subrows_mut(start, len);
                for (i, v) in new[out * len..(out + 1) * len].iter().enumerate() {
                    to[i] = *v;
                }
            }
            start += len;
        }
    };
    let n = x.nrows();
    if n < PARALLEL_ROWS {
        rows(x);
    } else {
        let (top, bottom) = x.split_at_row_mut(n / 2);
        rayon::join(|| rows(top), || rows(bottom));
    }
}

/// The Ritz vector V·s_i.
fn ritz_vector(basis: MatRef<'_, f64>, s: &Mat<f64>, i: usize) -> Vec<f64> {
    let column = basis * s.as_ref().subrows(0, basis.ncols()).col(i);
    column.iter().copied().collect()
}

/// The basis size at which the Lanczos basis is restarted, for `modes`
/// wanted modes: 24 for six. At 4·modes + 24 (48, keeping 20) the
/// benchmark's 40 × 40 grid took the same 29 + 53 steps as at 24
/// (keeping 12), and the 100 × 100 grid 64 shifted steps against 93, in
/// the same time (each step's orthogonalisation half as long) and 380 MB
/// more.
fn basis_size(modes: usize) -> usize {
    2 * modes + 12
}

/// How many Ritz vectors a restart keeps, for `modes` wanted modes.
fn kept(modes: usize) -> usize {
    modes + 6
}

/// The eigenvalues (ascending) and vectors of the leading m×m block of
/// the projected operator, symmetrised.
fn ritz_values(h: &Mat<f64>, m: usize) -> Result<(Vec<f64>, Mat<f64>), FrameError> {
    let mut t = Mat::<f64>::zeros(m, m);
    for i in 0..m {
        for k in 0..m {
            t[(i, k)] = 0.5 * (h[(i, k)] + h[(k, i)]);
        }
    }
    let e = t
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| FrameError::Invalid(format!("buckling: {e:?}")))?;
    let mu: Vec<f64> = (0..m).map(|i| e.S().column_vector()[i]).collect();
    Ok((mu, e.U().to_owned()))
}

/// The indices of the `count` largest positive μ, largest first.
fn wanted_of(mu: &[f64], count: usize) -> Vec<usize> {
    (0..mu.len())
        .rev()
        .filter(|&i| mu[i] > 0.0)
        .take(count)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::structure::model::{Beam, InitialForces, NodeLoad, Section, Support};
    use glam::DVec3;

    /// A fixed–free column of `n` elements, 1 m, the steel strip's
    /// section; the compressive tip load of 100 N.
    fn cantilever(n: usize) -> (FrameModel, LoadSet) {
        let section = Section::steel_strip();
        let length_mm = 1000.0;
        let model = FrameModel {
            nodes_mm: (0..=n)
                .map(|i| DVec3::new(length_mm * i as f64 / n as f64, 0.0, 0.0))
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
            cables: vec![],
            supports: vec![Support {
                node: 0,
                fixed: [true; 6],
                along: None,
            }],
        };
        let loads = LoadSet {
            name: "P".into(),
            nodes: vec![NodeLoad {
                node: n,
                force_n: -DVec3::X * 100.0,
                moment_nmm: DVec3::ZERO,
            }],
            ..Default::default()
        };
        (model, loads)
    }

    /// Restarting the basis keeps the answer, and so do blocks and the
    /// shift: a cantilever's six smallest factors with a basis of 14
    /// vectors restarted to 8 (many restarts), with blocks of four vectors
    /// in a basis of 24, and those of the shifted pencil,
    /// equal those of an unshifted basis that never restarts, to 1e-8, and
    /// the first is Euler's π²·E·I_z/(4·L²·P) within 0.1 %.
    #[test]
    fn a_restarted_basis_and_a_shift_find_the_factors_of_an_unrestarted_one() {
        let (model, loads) = cantilever(40);
        let linear = LinearFrame::new(&model).unwrap();
        let first = linear.solve(&loads).unwrap();
        let kg = linear
            .assembly
            .geometric(&model, &axial_forces(&first), Some(&loads));
        let plain = Pencil {
            stiffness: &linear.stiffness,
            factor: &linear.factor,
            shift: 0.0,
        };
        // One space for all three: a run leaves what it does not use as it was.
        let space = &mut Space::default();
        let restarted = lanczos_restarted(&plain, &kg, 6, (14, 8, 1), TOLERANCE, space).unwrap();
        let blocks = lanczos_restarted(&plain, &kg, 6, (24, 8, 4), TOLERANCE, space).unwrap();
        let whole =
            lanczos_restarted(&plain, &kg, 6, (MAX_ITERATIONS, 0, 1), TOLERANCE, space).unwrap();
        let shifted = shifted_lanczos(
            &linear.stiffness,
            &linear.factor,
            &kg,
            &linear.assembly.dofs,
            6,
        )
        .unwrap();
        assert_eq!(restarted.len(), 6);
        assert_eq!(blocks.len(), 6);
        assert_eq!(whole.len(), 6);
        for (b, w) in blocks.iter().zip(&whole) {
            assert!((b.0 - w.0).abs() <= 1e-8 * w.0, "{} vs {}", b.0, w.0);
        }
        assert_eq!(shifted.len(), 6);
        for ((r, s), w) in restarted.iter().zip(&shifted).zip(&whole) {
            assert!((r.0 - w.0).abs() <= 1e-8 * w.0, "{} vs {}", r.0, w.0);
            assert!((s.0 - w.0).abs() <= 1e-8 * w.0, "{} vs {}", s.0, w.0);
        }
        let euler = std::f64::consts::PI.powi(2) * 210_000.0 * 14.0625 / (4.0 * 1e6 * 100.0);
        assert!(
            (restarted[0].0 - euler).abs() <= 1e-3 * euler,
            "{} vs {euler}",
            restarted[0].0
        );
        // The shift's premise: K_e + σ·K_G factorises below the first
        // factor and not above it (then the shift is lowered).
        let lambda = whole[0].0;
        for (sigma, definite) in [(0.99 * lambda, true), (1.01 * lambda, false)] {
            let a = add(&linear.stiffness, &kg, sigma);
            assert_eq!(
                factorise_definite(&a, &linear.assembly.dofs)
                    .unwrap()
                    .is_some(),
                definite,
                "σ {sigma}"
            );
        }
    }

    /// The polar term N·(I_y + I_z)/(A·L) is torsional buckling: a column
    /// whose St. Venant stiffness is low buckles in torsion at
    /// N_T = G·J·A/I_p (no warping: for any length and any mesh, the
    /// torsional stiffness and the polar term having the same shape),
    /// below Euler's load; without the term
    /// ([`critical_factors_flexural`]) at Euler's π²·E·I_z/(4·L²).
    #[test]
    fn a_column_soft_in_torsion_buckles_at_the_torsional_load() {
        let (mut model, loads) = cantilever(16);
        model.sections[0].j_mm4 = 0.01;
        let s = model.sections[0].clone();
        let p = 100.0;
        let torsional = s.g_mpa * s.j_mm4 * s.area_mm2 / (s.i_y_mm4 + s.i_z_mm4) / p;
        let euler =
            std::f64::consts::PI.powi(2) * s.e_mpa * s.i_z_mm4 / (4.0 * 1000.0 * 1000.0) / p;
        assert!(torsional < 0.6 * euler);
        let full = critical_factors(&model, &loads, 1).unwrap()[0].factor;
        let flexural = critical_factors_flexural(&model, &loads, 1).unwrap()[0].factor;
        assert!(
            (full - torsional).abs() <= 1e-6 * torsional,
            "torsional: {full} against {torsional}"
        );
        assert!(
            (flexural - euler).abs() <= 5e-3 * euler,
            "flexural: {flexural} against Euler's {euler}"
        );
    }

    /// W − X_S·C_S and Y − Z_S·C_S over a subset S of the basis, on one
    /// thread and split between two, against the sums by hand; the
    /// columns outside S are not used (they are NaN here).
    #[test]
    fn only_the_named_basis_vectors_are_subtracted() {
        for n in [37, PARALLEL_ROWS + 3] {
            let among = [1, 4, 5];
            let value = |i: usize, c: usize| ((i * 7 + c * 13) % 17) as f64 - 8.0;
            let x = Mat::from_fn(n, 6, |i, c| {
                if among.contains(&c) {
                    value(i, c)
                } else {
                    f64::NAN
                }
            });
            let ax = Mat::from_fn(n, 6, |i, c| {
                if among.contains(&c) {
                    0.5 * value(i, c + 1)
                } else {
                    f64::NAN
                }
            });
            let c = Mat::from_fn(6, 2, |i, k| {
                if among.contains(&i) {
                    0.25 * (i + 3 * k) as f64 - 1.0
                } else {
                    f64::NAN
                }
            });
            let w0 = Mat::from_fn(n, 2, |i, k| value(i + 3, k + 2));
            let aw0 = Mat::from_fn(n, 2, |i, k| value(i + 5, k));
            let (mut w, mut aw) = (w0.clone(), aw0.clone());
            subtract_products(
                w.as_mut(),
                aw.as_mut(),
                (x.as_ref(), ax.as_ref()),
                c.as_ref(),
                &among,
            );
            for i in 0..n {
                for k in 0..2 {
                    let want_w =
                        w0[(i, k)] - among.iter().map(|&j| x[(i, j)] * c[(j, k)]).sum::<f64>();
                    let want_aw =
                        aw0[(i, k)] - among.iter().map(|&j| ax[(i, j)] * c[(j, k)]).sum::<f64>();
                    assert!(
                        (w[(i, k)] - want_w).abs() <= 1e-12 * want_w.abs().max(1.0),
                        "n {n}: W[{i}, {k}]"
                    );
                    assert!(
                        (aw[(i, k)] - want_aw).abs() <= 1e-12 * want_aw.abs().max(1.0),
                        "n {n}: AW[{i}, {k}]"
                    );
                }
            }
        }
    }

    /// The restart's Ritz vectors made in place equal the product of the
    /// basis and the kept coefficients, on one thread and on two (rows
    /// from [`PARALLEL_ROWS`] on), over a partial last pass of rows.
    #[test]
    fn ritz_vectors_made_in_place_are_the_basis_times_the_coefficients() {
        for n in [1000, PARALLEL_ROWS + 777] {
            let (size, k) = (7, 4);
            let basis = Mat::<f64>::from_fn(n, size + 2, |i, j| {
                ((i * 31 + j * 17) % 101) as f64 / 50.0 - 1.0
            });
            let c = Mat::<f64>::from_fn(size, k, |i, j| {
                if (i + j) % 5 == 0 {
                    0.0
                } else {
                    (i as f64 - 2.0 * j as f64) / 3.0
                }
            });
            let want = basis.as_ref().subcols(0, size) * &c;
            let mut x = basis.clone();
            combine_in_place(x.as_mut(), size, &c);
            for j in 0..k {
                for i in 0..n {
                    assert!(
                        (x[(i, j)] - want[(i, j)]).abs() <= 1e-13,
                        "n {n}: ({i}, {j}) {} against {}",
                        x[(i, j)],
                        want[(i, j)]
                    );
                }
            }
            // The columns past the kept ones are left as they were.
            for j in k..size + 2 {
                assert!((0..n).all(|i| x[(i, j)] == basis[(i, j)]));
            }
        }
    }

    #[test]
    fn a_column_in_tension_has_no_buckling_mode() {
        let (model, mut loads) = cantilever(4);
        loads.nodes[0].force_n = -loads.nodes[0].force_n;
        let modes = critical_factors(&model, &loads, 3).unwrap();
        assert!(
            modes.is_empty(),
            "{:?}",
            modes.iter().map(|m| m.factor).collect::<Vec<_>>()
        );
    }
}
