//! The linear frame: element matrices, assembly, one sparse Cholesky
//! factorisation of the stiffness, static solves, section forces and
//! reactions; a mechanism is found and named by the node that moves.
//!
//! **Elements.** 3D Euler–Bernoulli beams (cubic transverse, linear axial
//! and torsion: exact nodal displacements for end loads and, with
//! consistent nodal loads, for uniform loads), local axes as in
//! [`super::model`]. The geometric stiffness of an element under an axial
//! force N (tension positive) is the consistent one of the same cubic
//! shape functions (Przemieniecki), with the polar term N·(I_y + I_z)/(A·L)
//! on the twist; with several elements per span it converges on flexural
//! and flexural–torsional buckling through and between nodes (error
//! ∝ 1/n⁴ in the elements per half-wave; the tests show it). Lateral–
//! torsional buckling of a strip by its bending moments is not in the
//! geometric stiffness: it is the member check of [`super::verdict`].
//!
//! **Sign of section forces.** At a section, the force and moment the
//! part beyond it exerts on the part before it, in local axes: N tension
//! positive, and every moment equals E·I (G·J for the torque) times the
//! rate of rotation about its axis along x, so a strip's erection state
//! (E·I·κ, G·J·τ) is in the same convention.
//!
//! **Supports** remove their fixed degrees of freedom; a roller on an
//! inclined bearing (a fixed translation along one direction) is a spring
//! of [`PENALTY`] times its node's largest translational stiffness along it.
//!
//! **Sparse algebra.** Matrices are lower triangles in compressed columns
//! ([`SymSparse`]); every element adds its whole 12 × 12 block, zeros
//! included, at places found once per model ([`ScatterPlan`]: no
//! triplets to sort), so the stiffness, the geometric stiffness, a shifted pencil
//! and a tangent of one model share one pattern, their sums add values,
//! and one symbolic factorisation is computed per model and kept in its
//! [`Dofs`]. A column of that pattern holds its node's own unknowns and
//! its later neighbours' whole, so its rows are kept as those runs
//! ([`Pattern`]), listed only for faer's own routines. The unknowns are numbered from the start in the order they
//! are eliminated in: faer's approximate minimum degree ordering of the
//! model's nodes, each node's unknowns together, in a postorder of the
//! nodes' elimination tree ([`ordering`]), so the matrix is factorised as
//! it stands, with no permuted copy, and the factor's supernodal structure
//! is faer's symbolic factorisation of the nodes' graph, each node widened
//! to its unknowns ([`layout`]). The numeric factorisation is
//! [`supernodal`]'s, left-looking, with the factor's subtrees on the two
//! threads (faer's own, on one thread and with a workspace as large as the
//! largest separator's update, still makes every factor with a
//! permutation of its own, such as a stiffness summed with the cables'
//! matrices, ordered by [`ordering::by_nodes`]); the triangular
//! solves are [`triangular`]'s, over the supernodes' dense blocks with up
//! to eight right-hand sides side by side, so each entry of the factor is
//! read once per eight, and from [`PARALLEL_ROWS`] unknowns on the
//! factor's two halves (whole subtrees) on the two threads (faer's
//! per-supernode kernels cost more than they do on a frame's small
//! supernodes: 0.23 s against 0.08 s for one solve of the 100 × 100
//! benchmark grid's 761,688 unknowns; on two threads 0.042 s).
//!
//! **Statics.** Every solution is held to a componentwise backward error
//! of 1e-13 and refined where it is above ([`solve_refined`]). Load sets
//! that are factored sums of fewer shared parts (the combinations of a
//! few load cases) are solved as those sums of the parts' solutions, the
//! parts solved together once, each sum held to its own backward error
//! ([`Statics`]).
//!
//! **Mechanisms.** A degree of freedom with no stiffness at all, a failed
//! factorisation, or a Jacobi-scaled smallest eigenvalue below
//! [`MECHANISM_RATIO`] (a few inverse iterations after the factorisation)
//! is a mechanism: the node whose motion dominates the near-null vector is
//! named, never a singular-matrix panic.

use super::model::{Beam, FrameModel, InitialForces, LoadSet, Section, DOF_PER_NODE};
use crate::geom::mesh::bucketed;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::CholeskySymbolicParams;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::{SupernodalThreshold, SymbolicSupernodalParams};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, Mat, MatMut, MatRef, Par, Side};
use glam::{DMat3, DVec3};
use rayon::prelude::*;
use std::sync::{Arc, Mutex, OnceLock};

mod layout;
mod ordering;
mod supernodal;
mod triangular;
use layout::Layout;
use supernodal::{Lower, Updates};
use triangular::{solve_scheduled, solve_serial, Schedule};

/// A roller's inclined restraint: a spring of this many times the largest
/// translational stiffness of its node, along the bearing's direction (its
/// node moves along it by about 1/PENALTY of the free motion; a larger
/// factor would cost the node's other directions their digits in the
/// factorisation).
pub const PENALTY: f64 = 1e6;

/// Below this smallest eigenvalue of the Jacobi-scaled stiffness
/// (D^-½·K·D^-½, unit diagonal) the model is a mechanism: round-off of a
/// true mechanism is near 1e-16, while a sound frame of slender strips
/// with rigid joints stays far above (measured on the benchmark's Enneper
/// grids of 1.5-mm steel strips: 1.2e-8 at 40 × 40 curves, 5.8e-10 at
/// 100 × 100, its softest mode a 26-m grid's global bending). Stiff
/// elements for the rigid joints would lower it by their stiffness over
/// the lamellas' (they took the 100 × 100 grid to 1.6e-14); the model
/// eliminates rigid ties instead ([`super::build`]).
pub const MECHANISM_RATIO: f64 = 1e-13;

/// Names of the six degrees of freedom of a node.
pub const DOF_NAMES: [&str; 6] = ["ux", "uy", "uz", "rx", "ry", "rz"];

/// Why a frame cannot be solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FrameError {
    /// An index in the model points nowhere, or a value is not finite.
    #[error("frame model: {0}")]
    Invalid(String),
    /// An element of zero length, or whose `z_axis` is along it.
    #[error("beam {beam}: {what}")]
    Degenerate {
        /// The element.
        beam: usize,
        /// What is wrong.
        what: String,
    },
    /// The frame is a mechanism under its supports: this node moves
    /// freely, most in this degree of freedom.
    #[error("the frame is a mechanism under its supports: node {node} moves freely ({})", DOF_NAMES[*dof])]
    Mechanism {
        /// The node (index into the model's nodes).
        node: usize,
        /// The degree of freedom it moves most in (0..6: ux … rz).
        dof: usize,
    },
    /// The stiffness under the load is not positive definite: the load
    /// exceeds the critical load (second order), or buckling cannot start.
    #[error("the frame is unstable under {0}")]
    Unstable(String),
    /// An iteration did not converge.
    #[error("{what} did not converge in {iterations} iterations")]
    NotConverged {
        /// Which analysis.
        what: String,
        /// Iterations run.
        iterations: usize,
    },
}

/// Section forces at one section of an element, local axes (N, N·mm), in
/// the convention of the module doc.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SectionForces {
    /// Axial force, N (tension positive).
    pub axial_n: f64,
    /// Shear along local y, N.
    pub shear_y_n: f64,
    /// Shear along local z, N.
    pub shear_z_n: f64,
    /// Torque about local x, N·mm.
    pub torque_nmm: f64,
    /// Moment about local y (strong axis), N·mm.
    pub moment_y_nmm: f64,
    /// Moment about local z (weak axis), N·mm.
    pub moment_z_nmm: f64,
}

impl SectionForces {
    fn from_vectors(force: DVec3, moment: DVec3) -> Self {
        SectionForces {
            axial_n: force.x,
            shear_y_n: force.y,
            shear_z_n: force.z,
            torque_nmm: moment.x,
            moment_y_nmm: moment.y,
            moment_z_nmm: moment.z,
        }
    }

    /// Adds an element's erection state.
    pub fn with_initial(&self, initial: &InitialForces) -> SectionForces {
        SectionForces {
            axial_n: self.axial_n + initial.axial_n,
            torque_nmm: self.torque_nmm + initial.torque_nmm,
            moment_y_nmm: self.moment_y_nmm + initial.moment_y_nmm,
            moment_z_nmm: self.moment_z_nmm + initial.moment_z_nmm,
            ..*self
        }
    }
}

/// Section forces of an element at its ends and its middle (where a
/// uniform load's moment peaks between nodes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BeamEndForces {
    /// At the first node.
    pub start: SectionForces,
    /// Halfway.
    pub middle: SectionForces,
    /// At the second node.
    pub end: SectionForces,
}

/// A support's reaction, global: what the support exerts on the frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reaction {
    /// The supported node.
    pub node: usize,
    /// Force, N.
    pub force_n: DVec3,
    /// Moment, N·mm.
    pub moment_nmm: DVec3,
}

/// A static solution.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticResult {
    /// Per node `[ux, uy, uz, rx, ry, rz]`, mm and rad.
    pub displacements: Vec<[f64; 6]>,
    /// Per support, in the order of the model's supports (one per node:
    /// supports of the same node are summed into the first).
    pub reactions: Vec<Reaction>,
    /// Per beam element (load only: add the erection state with
    /// [`SectionForces::with_initial`]).
    pub beam_forces: Vec<BeamEndForces>,
    /// Per cable: its force, N (its pretension included; 0 when slack).
    pub cable_forces_n: Vec<f64>,
}

/// An element's local frame: rows are local x, y, z in global components.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementFrame {
    /// Rows: local x, y, z (u_local = rotation · u_global).
    pub rotation: DMat3,
    /// Length, mm.
    pub length_mm: f64,
}

type Mat12 = [[f64; 12]; 12];

/// `a > b`, false when either is NaN.
fn exceeds(a: f64, b: f64) -> bool {
    a > b
}

/// The local frame of `beam` with its nodes at `nodes_mm`.
pub fn element_frame(
    nodes_mm: &[DVec3],
    index: usize,
    beam: &Beam,
) -> Result<ElementFrame, FrameError> {
    let [a, b] = beam.ends_mm(nodes_mm);
    let d = b - a;
    let length_mm = d.length();
    if !exceeds(length_mm, 1e-9) {
        return Err(FrameError::Degenerate {
            beam: index,
            what: format!(
                "zero length (nodes {} and {})",
                beam.nodes[0], beam.nodes[1]
            ),
        });
    }
    let x = d / length_mm;
    let y = beam.z_axis.cross(x);
    if !exceeds(y.length(), 1e-9 * beam.z_axis.length()) || !y.is_finite() {
        return Err(FrameError::Degenerate {
            beam: index,
            what: "its z axis is along the element or zero".into(),
        });
    }
    let y = y.normalize();
    let z = x.cross(y);
    Ok(ElementFrame {
        rotation: DMat3::from_cols(x, y, z).transpose(),
        length_mm,
    })
}

/// The elastic stiffness in local axes.
pub fn local_stiffness(s: &Section, l: f64) -> Mat12 {
    let mut k = [[0.0; 12]; 12];
    let ea = s.e_mpa * s.area_mm2 / l;
    let gj = s.g_mpa * s.j_mm4 / l;
    put2(&mut k, [0, 6], ea);
    put2(&mut k, [3, 9], gj);
    // Bending in x–y (v, θz) and in x–z (w, θy; θy = −w').
    bend(&mut k, [1, 5, 7, 11], s.e_mpa * s.i_z_mm4, l, 1.0);
    bend(&mut k, [2, 4, 8, 10], s.e_mpa * s.i_y_mm4, l, -1.0);
    k
}

fn put2(k: &mut Mat12, d: [usize; 2], v: f64) {
    k[d[0]][d[0]] += v;
    k[d[1]][d[1]] += v;
    k[d[0]][d[1]] -= v;
    k[d[1]][d[0]] -= v;
}

fn bend(k: &mut Mat12, d: [usize; 4], ei: f64, l: f64, sign: f64) {
    let m = bending_block(ei, l, sign);
    for a in 0..4 {
        for b in 0..4 {
            k[d[a]][d[b]] += m[a][b];
        }
    }
}

/// The Euler–Bernoulli element's 4 × 4 bending block (displacement,
/// rotation at either end) of stiffness `ei` over length `l`; `sign` −1
/// for the x–z plane, where θy = −w'.
fn bending_block(ei: f64, l: f64, sign: f64) -> [[f64; 4]; 4] {
    let c = ei / (l * l * l);
    let s = sign * l;
    [
        [12.0 * c, 6.0 * s * c, -12.0 * c, 6.0 * s * c],
        [6.0 * s * c, 4.0 * l * l * c, -6.0 * s * c, 2.0 * l * l * c],
        [-12.0 * c, -6.0 * s * c, 12.0 * c, -6.0 * s * c],
        [6.0 * s * c, 2.0 * l * l * c, -6.0 * s * c, 4.0 * l * l * c],
    ]
}

/// [`local_stiffness`] times the local end displacements `u`, term by
/// term (axial, torsion, the two bending blocks) with no 12 × 12 matrix
/// made: an element's end forces in every static result.
fn local_stiffness_times(s: &Section, l: f64, u: &[f64; 12]) -> [f64; 12] {
    let mut f = [0.0; 12];
    // As the matrix's rows sum them (the same bits).
    let (ea, gj) = (s.e_mpa * s.area_mm2 / l, s.g_mpa * s.j_mm4 / l);
    (f[0], f[6]) = (ea * u[0] - ea * u[6], ea * u[6] - ea * u[0]);
    (f[3], f[9]) = (gj * u[3] - gj * u[9], gj * u[9] - gj * u[3]);
    for (d, ei, sign) in [
        ([1, 5, 7, 11], s.e_mpa * s.i_z_mm4, 1.0),
        ([2, 4, 8, 10], s.e_mpa * s.i_y_mm4, -1.0),
    ] {
        let m = bending_block(ei, l, sign);
        for a in 0..4 {
            f[d[a]] = (0..4).map(|b| m[a][b] * u[d[b]]).sum();
        }
    }
    f
}

/// Which terms a geometric stiffness holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GeometricTerms {
    /// The flexural terms and the polar term N·(I_y + I_z)/(A·L) of
    /// torsional buckling: what lamella's analyses use.
    Full,
    /// The flexural terms only, as a frame program's P-Delta
    /// transformation has them (OpenSees'): for comparing with one.
    Flexural,
}

/// The geometric stiffness in local axes under axial force `axial_n`
/// (tension positive).
pub fn local_geometric(s: &Section, l: f64, axial_n: f64) -> Mat12 {
    local_geometric_terms(s, l, axial_n, GeometricTerms::Full)
}

/// [`local_geometric`] with the chosen `terms`.
pub fn local_geometric_terms(s: &Section, l: f64, axial_n: f64, terms: GeometricTerms) -> Mat12 {
    let mut k = [[0.0; 12]; 12];
    let c = axial_n / (30.0 * l);
    for (d, sign) in [([1, 5, 7, 11], 1.0), ([2, 4, 8, 10], -1.0)] {
        let s3 = sign * 3.0 * l;
        let m = [
            [36.0, s3, -36.0, s3],
            [s3, 4.0 * l * l, -s3, -l * l],
            [-36.0, -s3, 36.0, -s3],
            [s3, -l * l, -s3, 4.0 * l * l],
        ];
        for a in 0..4 {
            for b in 0..4 {
                k[d[a]][d[b]] += c * m[a][b];
            }
        }
    }
    if terms == GeometricTerms::Full {
        put2(
            &mut k,
            [3, 9],
            axial_n * (s.i_y_mm4 + s.i_z_mm4) / (s.area_mm2 * l),
        );
    }
    k
}

/// T^T·k·T for T = diag(R, R, R, R).
fn to_global(k: &Mat12, r: &DMat3) -> Mat12 {
    // R as rows: r[row][col] = component col of local axis row.
    let rr = [r.row(0), r.row(1), r.row(2)];
    let rm = |a: usize, b: usize| rr[a][b];
    let mut kr = [[0.0; 12]; 12]; // k·T
    for i in 0..12 {
        for bj in 0..4 {
            for c in 0..3 {
                let mut v = 0.0;
                for a in 0..3 {
                    v += k[i][3 * bj + a] * rm(a, c);
                }
                kr[i][3 * bj + c] = v;
            }
        }
    }
    let mut out = [[0.0; 12]; 12];
    for bi in 0..4 {
        for c in 0..3 {
            for j in 0..12 {
                let mut v = 0.0;
                for a in 0..3 {
                    v += rm(a, c) * kr[3 * bi + a][j];
                }
                out[3 * bi + c][j] = v;
            }
        }
    }
    out
}

/// The rigid-offset transformation of an element (ends from nodes:
/// u_end = u_node + θ_node × offset), `None` without offsets.
fn offset_matrix(offsets: &[DVec3; 2]) -> Option<Mat12> {
    if offsets.iter().all(|o| *o == DVec3::ZERO) {
        return None;
    }
    let mut h = [[0.0; 12]; 12];
    for (i, row) in h.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for (a, r) in offsets.iter().enumerate() {
        // θ × r = −[r]×·θ.
        let skew = [[0.0, -r.z, r.y], [r.z, 0.0, -r.x], [-r.y, r.x, 0.0]];
        for p in 0..3 {
            for q in 0..3 {
                h[6 * a + p][6 * a + 3 + q] = -skew[p][q];
            }
        }
    }
    Some(h)
}

/// Hᵀ·k·H.
fn sandwich(h: &Mat12, k: &Mat12) -> Mat12 {
    let mut kh = [[0.0; 12]; 12];
    for i in 0..12 {
        for j in 0..12 {
            kh[i][j] = (0..12).map(|m| k[i][m] * h[m][j]).sum();
        }
    }
    let mut out = [[0.0; 12]; 12];
    for i in 0..12 {
        for j in 0..12 {
            out[i][j] = (0..12).map(|m| h[m][i] * kh[m][j]).sum();
        }
    }
    out
}

/// H·u (node displacements → element end displacements) for the rigid
/// end offsets r of [`offset_matrix`], in closed form: each end moves
/// with its node, u_end = u_node + θ_node × r, and turns with it.
fn apply_h(offsets: &[DVec3; 2], mut u: [f64; 12]) -> [f64; 12] {
    for (a, r) in offsets.iter().enumerate() {
        if *r != DVec3::ZERO {
            let b = 6 * a;
            let theta = DVec3::new(u[b + 3], u[b + 4], u[b + 5]);
            let moved = theta.cross(*r);
            u[b] += moved.x;
            u[b + 1] += moved.y;
            u[b + 2] += moved.z;
        }
    }
    u
}

/// Hᵀ·f (element end forces → node forces), in closed form: each end's
/// force acts on its node with its moment about the node added,
/// m_node = m_end + r × f_end.
fn apply_ht(offsets: &[DVec3; 2], mut f: [f64; 12]) -> [f64; 12] {
    for (a, r) in offsets.iter().enumerate() {
        if *r != DVec3::ZERO {
            let b = 6 * a;
            let force = DVec3::new(f[b], f[b + 1], f[b + 2]);
            let moment = r.cross(force);
            f[b + 3] += moment.x;
            f[b + 4] += moment.y;
            f[b + 5] += moment.z;
        }
    }
    f
}

/// Local ← global for an element's 12 displacements.
fn localise(r: &DMat3, u: &[f64; 12]) -> [f64; 12] {
    let mut out = [0.0; 12];
    for b in 0..4 {
        let v = *r * DVec3::new(u[3 * b], u[3 * b + 1], u[3 * b + 2]);
        out[3 * b..3 * b + 3].copy_from_slice(&v.to_array());
    }
    out
}

/// Global ← local for 12 forces.
fn globalise(r: &DMat3, f: &[f64; 12]) -> [f64; 12] {
    let rt = r.transpose();
    let mut out = [0.0; 12];
    for b in 0..4 {
        let v = rt * DVec3::new(f[3 * b], f[3 * b + 1], f[3 * b + 2]);
        out[3 * b..3 * b + 3].copy_from_slice(&v.to_array());
    }
    out
}

/// Equivalent nodal loads (local) of a uniform load `q` (local, N/mm) on
/// an element of length `l`: the reactions of the clamped element, reversed.
fn uniform_nodal_loads(q: DVec3, l: f64) -> [f64; 12] {
    let (h, m) = (0.5 * l, l * l / 12.0);
    let mut p = [0.0; 12];
    p[0] = q.x * h;
    p[6] = q.x * h;
    p[1] = q.y * h;
    p[7] = q.y * h;
    p[5] = q.y * m;
    p[11] = -q.y * m;
    p[2] = q.z * h;
    p[8] = q.z * h;
    p[4] = -q.z * m;
    p[10] = q.z * m;
    p
}

const NONE: usize = usize::MAX;

/// Below this many unknowns the block operations stay on one thread.
pub(crate) const PARALLEL_ROWS: usize = 20_000;

/// Elements per task when a result's section forces are shared between
/// the threads.
const PARALLEL_BEAMS: usize = 4096;

/// Elements from which a load vector is made on both cores
/// ([`Assembly::load_vector`]): 100 × 100 benchmark curves have 158,400.
const PARALLEL_LOAD_BEAMS: usize = 100_000;

/// A product's groups of columns, (first, width): eights, then at most one
/// group each of four, two and one.
fn column_groups(columns: usize) -> Vec<(usize, usize)> {
    let mut groups = Vec::new();
    let mut first = 0;
    while first < columns {
        let width = match columns - first {
            8.. => 8,
            4..=7 => 4,
            2..=3 => 2,
            _ => 1,
        };
        groups.push((first, width));
        first += width;
    }
    groups
}

/// The sparsity pattern of a symmetric matrix's lower triangle, by
/// columns.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Pattern {
    /// Column j's entries are `start[j]..start[j + 1]` (n + 1 of them).
    pub start: Vec<usize>,
    /// Their rows, ascending within a column, each at least the column.
    rows: Rows,
    /// The unknowns are numbered in the fill-reducing order of the graph
    /// this pattern is of (the scatter plan's, of [`Dofs`] numbered in
    /// order), so it is factorised as it stands. Such a pattern is of
    /// nodes' blocks: every column of a node's run of unknowns holds the
    /// node's own from it on and all of each later neighbour's, which
    /// [`Dofs::layout_on_nodes`] reads from the run's first column.
    pub in_order: bool,
}

/// A pattern's rows: every entry's listed, or, for a pattern of nodes'
/// blocks, the blocks' runs.
#[derive(Debug, Clone, PartialEq)]
enum Rows {
    Listed(Vec<usize>),
    Blocks(NodeBlocks),
}

impl Default for Rows {
    fn default() -> Self {
        Rows::Listed(Vec::new())
    }
}

/// The rows of a pattern of nodes' blocks ([`ScatterPlan`]), a node's
/// unknowns numbered together: column j of node y holds y's own unknowns
/// from j on, then each of y's neighbours numbered after it, whole. A
/// column's rows are a few runs: at 400 × 400 benchmark curves 135 million
/// rows were 1.08 GB listed, 0.17 GB as runs.
#[derive(Debug, Clone, PartialEq)]
struct NodeBlocks {
    /// Per column: its node's number, in the order of the unknowns.
    node_of: Vec<u32>,
    /// Per node: one past its last unknown, and where its neighbours'
    /// runs are in `runs` (begin, end).
    nodes: Vec<(usize, usize, usize)>,
    /// The neighbours' runs of unknowns, (first, one past the last), each
    /// node's ascending.
    runs: Vec<(usize, usize)>,
}

/// The rows of one column of a [`Pattern`], ascending.
#[derive(Clone)]
pub(crate) struct ColumnRows<'a> {
    current: std::ops::Range<usize>,
    listed: &'a [usize],
    runs: &'a [(usize, usize)],
}

impl Iterator for ColumnRows<'_> {
    type Item = usize;

    fn next(&mut self) -> Option<usize> {
        loop {
            if let Some(i) = self.current.next() {
                return Some(i);
            }
            if let Some((&i, rest)) = self.listed.split_first() {
                self.listed = rest;
                return Some(i);
            }
            let (&(from, to), rest) = self.runs.split_first()?;
            self.runs = rest;
            self.current = from..to;
        }
    }
}

impl Pattern {
    /// A pattern of listed rows.
    pub(crate) fn listed(start: Vec<usize>, rows: Vec<usize>, in_order: bool) -> Pattern {
        Pattern {
            start,
            rows: Rows::Listed(rows),
            in_order,
        }
    }

    /// The number of entries.
    pub(crate) fn len(&self) -> usize {
        self.start.last().copied().unwrap_or(0)
    }

    /// Column j's rows, ascending.
    pub(crate) fn column(&self, j: usize) -> ColumnRows<'_> {
        match &self.rows {
            Rows::Listed(rows) => ColumnRows {
                current: 0..0,
                listed: &rows[self.start[j]..self.start[j + 1]],
                runs: &[],
            },
            Rows::Blocks(b) => {
                let (end, from, to) = b.nodes[b.node_of[j] as usize];
                ColumnRows {
                    current: j..end,
                    listed: &[],
                    runs: &b.runs[from..to],
                }
            }
        }
    }

    /// Calls `f(entry, row)` for every entry of column j, rows ascending
    /// (the loop of the products and the factorisation: a run's rows
    /// counted, not read).
    #[inline]
    pub(crate) fn for_each_in(&self, j: usize, mut f: impl FnMut(usize, usize)) {
        let mut k = self.start[j];
        match &self.rows {
            Rows::Listed(rows) => {
                for &i in &rows[k..self.start[j + 1]] {
                    f(k, i);
                    k += 1;
                }
            }
            Rows::Blocks(b) => {
                let (end, from, to) = b.nodes[b.node_of[j] as usize];
                for i in j..end {
                    f(k, i);
                    k += 1;
                }
                for &(first, last) in &b.runs[from..to] {
                    for i in first..last {
                        f(k, i);
                        k += 1;
                    }
                }
            }
        }
        debug_assert_eq!(k, self.start[j + 1], "column {j}'s entries");
    }

    /// Calls `f(entry, rows)` for every run of consecutive rows of column
    /// j, in order (its first entry, its rows): the products' loops, over
    /// slices of the values and the vectors side by side.
    #[inline]
    pub(crate) fn for_each_run_in(
        &self,
        j: usize,
        mut f: impl FnMut(usize, std::ops::Range<usize>),
    ) {
        let (begin, end) = (self.start[j], self.start[j + 1]);
        match &self.rows {
            Rows::Listed(rows) => {
                let mut k = begin;
                while k < end {
                    let mut last = k + 1;
                    while last < end && rows[last] == rows[last - 1] + 1 {
                        last += 1;
                    }
                    f(k, rows[k]..rows[last - 1] + 1);
                    k = last;
                }
            }
            Rows::Blocks(b) => {
                let (own_end, from, to) = b.nodes[b.node_of[j] as usize];
                let mut k = begin;
                f(k, j..own_end);
                k += own_end - j;
                for &(first, last) in &b.runs[from..to] {
                    f(k, first..last);
                    k += last - first;
                }
                debug_assert_eq!(k, end, "column {j}'s entries");
            }
        }
    }

    /// Every entry's row, listed (made where the rows are runs: for
    /// faer's routines).
    pub(crate) fn rows(&self) -> std::borrow::Cow<'_, [usize]> {
        match &self.rows {
            Rows::Listed(rows) => std::borrow::Cow::Borrowed(rows),
            Rows::Blocks(_) => {
                let mut rows = Vec::with_capacity(self.len());
                for j in 0..self.start.len() - 1 {
                    rows.extend(self.column(j));
                }
                std::borrow::Cow::Owned(rows)
            }
        }
    }

    /// The upper triangle of the same matrix by columns (this triangle's
    /// rows), rows ascending.
    fn transposed(&self) -> Pattern {
        let n = self.start.len() - 1;
        let (start, rows) = bucketed(n, (0..n).flat_map(|j| self.column(j).map(move |i| (i, j))));
        Pattern::listed(start, rows, self.in_order)
    }
}

/// A symmetric sparse matrix's lower triangle as faer reads it (its rows
/// listed).
pub(crate) struct FaerLower<'a> {
    n: usize,
    start: &'a [usize],
    rows: std::borrow::Cow<'a, [usize]>,
    values: &'a [f64],
}

impl FaerLower<'_> {
    pub(crate) fn symbolic(&self) -> SymbolicSparseColMatRef<'_, usize> {
        SymbolicSparseColMatRef::new_checked(self.n, self.n, self.start, None, &self.rows)
    }

    pub(crate) fn matrix(&self) -> SparseColMatRef<'_, usize, f64> {
        SparseColMatRef::new(self.symbolic(), self.values)
    }
}

/// A symmetric sparse matrix: its lower triangle in compressed columns.
/// Matrices of one model share their pattern (every element scatters its
/// whole block, zeros included), so a sum is a sum of values and one
/// symbolic factorisation serves them all.
#[derive(Debug, Clone, Default)]
pub(crate) struct SymSparse {
    pub n: usize,
    pub pattern: Arc<Pattern>,
    /// One per entry of the pattern.
    pub values: Vec<f64>,
    /// The diagonal without support penalties, which scales the
    /// mechanism test (a penalty would make its node's other directions
    /// look free); `None`: the diagonal itself.
    pub scaling: Option<Vec<f64>>,
}

impl SymSparse {
    /// The matrix of (row, column, value) triplets with row ≥ column,
    /// duplicates summed: sorted by column in one counting pass, then
    /// each column by row.
    fn from_triplets(n: usize, t: Vec<(usize, usize, f64)>) -> Self {
        let mut first = vec![0usize; n + 1];
        for &(_, j, _) in &t {
            first[j + 1] += 1;
        }
        for j in 0..n {
            first[j + 1] += first[j];
        }
        let mut slot = first.clone();
        let mut by_column = vec![(0usize, 0.0f64); t.len()];
        for (i, j, v) in t {
            by_column[slot[j]] = (i, v);
            slot[j] += 1;
        }
        let mut start = Vec::with_capacity(n + 1);
        start.push(0);
        let mut rows = Vec::with_capacity(by_column.len() / 2);
        let mut values = Vec::with_capacity(by_column.len() / 2);
        for j in 0..n {
            let column = &mut by_column[first[j]..first[j + 1]];
            column.sort_unstable_by_key(|e| e.0);
            let begin = rows.len();
            for &(i, v) in column.iter() {
                if rows.len() > begin && rows[rows.len() - 1] == i {
                    let last = values.len() - 1;
                    values[last] += v;
                } else {
                    rows.push(i);
                    values.push(v);
                }
            }
            start.push(rows.len());
        }
        SymSparse {
            n,
            pattern: Arc::new(Pattern::listed(start, rows, false)),
            values,
            scaling: None,
        }
    }

    /// Where entry (row, column), row ≥ column, is stored, if it is.
    pub(crate) fn place(&self, row: usize, column: usize) -> Option<usize> {
        let p = &*self.pattern;
        p.column(column)
            .position(|i| i == row)
            .map(|k| p.start[column] + k)
    }

    /// Every stored entry (row, column, value), row ≥ column.
    pub(crate) fn entries(&self) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
        let p = &*self.pattern;
        (0..self.n).flat_map(move |j| {
            (p.column(j).zip(p.start[j]..)).map(move |(i, k)| (i, j, self.values[k]))
        })
    }

    /// The lower triangle as faer reads it (its rows listed, made where
    /// the pattern holds runs).
    pub(crate) fn to_faer(&self) -> Result<FaerLower<'_>, FrameError> {
        let p = &*self.pattern;
        Ok(FaerLower {
            n: self.n,
            start: &p.start,
            rows: p.rows(),
            values: &self.values,
        })
    }

    /// Y = A·X for a block of columns: in groups of up to eight columns
    /// side by side per row ([`SymSparse::mul_group`]), A read once per
    /// group.
    pub(crate) fn mul_block(&self, x: MatRef<'_, f64>) -> Mat<f64> {
        let mut y = Mat::<f64>::zeros(self.n, x.ncols());
        for (first, width) in column_groups(x.ncols()) {
            let group = x.subcols(first, width);
            let out = y.as_mut().subcols_mut(first, width);
            match width {
                8 => self.mul_group::<8>(group, out),
                4 => self.mul_group::<4>(group, out),
                2 => self.mul_group::<2>(group, out),
                _ => self.mul_group::<1>(group, out),
            }
        }
        y
    }

    /// A·x and |A|·|x| (entry by entry: the scale of A·x's rounding) for
    /// one column x, each row's two values side by side, A read once for
    /// both, the columns of A split between two threads above
    /// [`PARALLEL_ROWS`] (as [`SymSparse::mul_group`]). One column at a
    /// time, not in groups as [`SymSparse::mul_block`]: the 19
    /// combinations' residuals at 100 × 100 curves took 1.66 s in groups
    /// of eight (each row's 16 sums, 97 MB per thread, reached in the
    /// pattern's scattered order), 0.56 s one by one, and at 40 × 40
    /// 0.126 s against 0.073 s.
    ///
    /// x is read where it lies and the second thread's sums are added into
    /// the first's: at 400 × 400 curves a copy of x beside |x| and a third
    /// array for the total were 394 MB more per column. The second
    /// thread's columns reach only the rows from their first on (the
    /// lower triangle), so its array holds those rows alone (98 MB less).
    fn mul_column_and_abs(&self, x: &[f64]) -> Vec<[f64; 2]> {
        let n = self.n;
        let part = |columns: std::ops::Range<usize>| -> Vec<[f64; 2]> {
            let pattern = &*self.pattern;
            let base = columns.start;
            let mut out = vec![[0.0; 2]; n - base];
            for j in columns {
                let xj = x[j];
                let aj = xj.abs();
                let (mut sum, mut sum_abs) = (0.0, 0.0);
                pattern.for_each_run_in(j, |k, rows| {
                    let (mut from, mut values) = (rows.start, &self.values[k..k + rows.len()]);
                    if from == j {
                        // The diagonal, a column's first entry, once.
                        let d = values[0];
                        sum = d * xj;
                        sum_abs = d.abs() * aj;
                        (from, values) = (from + 1, &values[1..]);
                    }
                    let out = &mut out[from - base..rows.end - base];
                    for ((o, &v), &xi) in out.iter_mut().zip(values).zip(&x[from..rows.end]) {
                        let a = v.abs();
                        o[0] += v * xj;
                        o[1] += a * aj;
                        sum += v * xi;
                        sum_abs += a * xi.abs();
                    }
                });
                out[j - base][0] += sum;
                out[j - base][1] += sum_abs;
            }
            out
        };
        if n >= PARALLEL_ROWS {
            let (mut a, b) = rayon::join(|| part(0..n / 2), || part(n / 2..n));
            for (a, b) in a[n / 2..].iter_mut().zip(&b) {
                a[0] += b[0];
                a[1] += b[1];
            }
            a
        } else {
            part(0..n)
        }
    }

    /// Y = A·X for P columns, each row's P values side by side: the lower
    /// triangle's entry a_ij (i > j) adds a_ij·x_j to y_i and a_ij·x_i to
    /// y_j. Above [`PARALLEL_ROWS`] the columns of A are split between two
    /// threads, each summing into its own Y.
    fn mul_group<const P: usize>(&self, x: MatRef<'_, f64>, mut y: MatMut<'_, f64>) {
        let n = self.n;
        let rows_x: Vec<[f64; P]> = (0..n).map(|i| std::array::from_fn(|c| x[(i, c)])).collect();
        let part = |columns: std::ops::Range<usize>| -> Vec<[f64; P]> {
            let pattern = &*self.pattern;
            let mut out = vec![[0.0; P]; n];
            for j in columns {
                let xj = rows_x[j];
                let mut sum = [0.0; P];
                pattern.for_each_run_in(j, |k, rows| {
                    let (mut from, mut values) = (rows.start, &self.values[k..k + rows.len()]);
                    if from == j {
                        // The diagonal, a column's first entry, once.
                        let d = values[0];
                        for c in 0..P {
                            sum[c] = d * xj[c];
                        }
                        (from, values) = (from + 1, &values[1..]);
                    }
                    let (out, x) = (&mut out[from..rows.end], &rows_x[from..rows.end]);
                    for ((yi, &v), xi) in out.iter_mut().zip(values).zip(x) {
                        for c in 0..P {
                            yi[c] += v * xj[c];
                            sum[c] += v * xi[c];
                        }
                    }
                });
                for c in 0..P {
                    out[j][c] += sum[c];
                }
            }
            out
        };
        let write = |y: &mut MatMut<'_, f64>, i: usize, row: [f64; P]| {
            for (c, v) in row.into_iter().enumerate() {
                y[(i, c)] = v;
            }
        };
        if n >= PARALLEL_ROWS {
            let (a, b) = rayon::join(|| part(0..n / 2), || part(n / 2..n));
            for (i, (a, b)) in a.into_iter().zip(b).enumerate() {
                write(&mut y, i, std::array::from_fn(|c| a[c] + b[c]));
            }
        } else {
            for (i, row) in part(0..n).into_iter().enumerate() {
                write(&mut y, i, row);
            }
        }
    }

    pub(crate) fn diagonal(&self) -> Vec<f64> {
        let p = &*self.pattern;
        (0..self.n)
            .map(|j| {
                if p.column(j).next() == Some(j) {
                    self.values[p.start[j]]
                } else {
                    0.0
                }
            })
            .collect()
    }

    /// A ← A + s·diag(d).
    fn add_to_diagonal(&mut self, s: f64, d: &[f64]) {
        let p = self.pattern.clone();
        for (j, dj) in d.iter().enumerate().take(self.n) {
            if p.column(j).next() == Some(j) {
                self.values[p.start[j]] += s * dj;
            }
        }
    }

    /// Whether every entry of `other` has a place in this pattern.
    fn holds(&self, other: &SymSparse) -> bool {
        if Arc::ptr_eq(&self.pattern, &other.pattern) {
            return true;
        }
        let (a, b) = (&*self.pattern, &*other.pattern);
        (0..self.n).all(|j| {
            let mut rows = a.column(j).peekable();
            b.column(j).all(|want| {
                while rows.next_if(|&i| i < want).is_some() {}
                rows.peek() == Some(&want)
            })
        })
    }
}

/// Which global degrees of freedom are unknown, and the model's element
/// frames; shared by every analysis of one model.
#[derive(Debug, Clone)]
pub struct Dofs {
    /// Global dof (node·6 + k) → unknown index, or `usize::MAX` if fixed.
    pub index: Vec<usize>,
    /// Number of unknowns.
    pub free: usize,
    /// The unknowns are numbered node by node in a fill-reducing order of
    /// the nodes the model's elements join ([`ordering::number_in_order`]).
    in_order: bool,
    /// The last symbolic factorisation and the pattern it is of: every
    /// matrix of one model has the same pattern, so the ordering and the
    /// factor's structure are computed once (shared by clones).
    symbolic: Arc<Mutex<Option<KeptSymbolic>>>,
}

/// A symbolic factorisation and the pattern it is of.
type KeptSymbolic = (Arc<Pattern>, Symbolic);

impl Dofs {
    /// The unknowns of `model` (its supports' fixed degrees removed).
    pub fn of(model: &FrameModel) -> Dofs {
        let mut fixed = vec![false; model.nodes_mm.len() * DOF_PER_NODE];
        for s in &model.supports {
            for k in 0..6 {
                if s.fixed[k] {
                    fixed[s.node * DOF_PER_NODE + k] = true;
                }
            }
        }
        let mut free = 0;
        let index = fixed
            .iter()
            .map(|&f| {
                if f {
                    NONE
                } else {
                    free += 1;
                    free - 1
                }
            })
            .collect();
        let mut dofs = Dofs {
            index,
            free,
            in_order: false,
            symbolic: Arc::default(),
        };
        let pairs =
            (model.beams.iter().map(|b| b.nodes)).chain(model.links.iter().map(|l| l.nodes));
        ordering::number_in_order(&mut dofs, pairs);
        dofs
    }

    /// The symbolic factorisation of `a`: the one kept when `a` has its
    /// pattern, else a new one (approximate minimum degree on the nodes,
    /// [`ordering`]; on the unknowns where `a` is not of these nodes),
    /// kept.
    fn symbolic_of(&self, a: &SymSparse) -> Result<Symbolic, FrameError> {
        let mut kept = self.symbolic.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((pattern, symbolic)) = &*kept {
            if Arc::ptr_eq(pattern, &a.pattern) || **pattern == *a.pattern {
                return Ok(symbolic.clone());
            }
        }
        if a.pattern.in_order {
            // The structure made on the nodes, if it comes out postordered
            // (it does, the nodes being numbered in a postorder of their
            // elimination tree; faer's on the unknowns otherwise).
            if let Some(layout) = self.layout_on_nodes(a)? {
                if triangular::postorder(&layout).is_none() {
                    let symbolic = Arc::new(Structure::with(None, Some(layout), false));
                    *kept = Some((a.pattern.clone(), symbolic.clone()));
                    return Ok(symbolic);
                }
            }
        }
        let pattern = a.to_faer()?;
        let cholesky = if a.pattern.in_order {
            // Numbered in order already: factorised as it stands, with no
            // permuted copy of the matrix (faer makes one, of every
            // entry, where it is given an order). faer analyses the upper
            // triangle when it is given no order, whatever side it is told.
            let upper = a.pattern.transposed();
            let upper_rows = upper.rows();
            factorize_symbolic_cholesky(
                SymbolicSparseColMatRef::new_checked(a.n, a.n, &upper.start, None, &upper_rows),
                Side::Upper,
                SymmetricOrdering::Identity,
                Default::default(),
            )
            .map_err(ordering_failed)?
        } else {
            match ordering::by_nodes(&a.pattern, a.n, self) {
                Some(forward) => symbolic_in_order(pattern.symbolic(), &forward)?,
                None => factorize_symbolic_cholesky(
                    pattern.symbolic(),
                    Side::Lower,
                    SymmetricOrdering::Amd,
                    Default::default(),
                )
                .map_err(ordering_failed)?,
            }
        };
        // Where faer made the structure (the unknowns ordered on their own,
        // or, numbered in order, not made on the nodes above), only a
        // factor large enough to share between the threads
        // ([`Structure::of`]) is worth a second symbolic factorisation in
        // a postorder ([`postordered`]).
        let cholesky = if a.n >= PARALLEL_ROWS {
            postordered(pattern.symbolic(), cholesky)?
        } else {
            cholesky
        };
        let symbolic = Arc::new(Structure::of(cholesky));
        *kept = Some((a.pattern.clone(), symbolic.clone()));
        Ok(symbolic)
    }
}

/// faer's supernode amalgamation thresholds for a symbolic factorisation
/// on the nodes: its defaults for (16, 0.8), (48, 0.1) and (any, 0.05)
/// in columns of unknowns, in nodes of six, less the merging of the
/// smallest supernodes at up to 80 % zeros (faer's (4, 1.0) and (16,
/// 0.8), here (2, 0.8)). At 400 × 400 benchmark curves that merging made
/// the factor 483 million values instead of 427 (430 MiB more), with no
/// change in the factorisation's time that one day's runs could tell
/// (24–28 s either way); METIS's nested dissection (pymetis) of the same
/// nodes gave 490 million with it.
const NODE_RELAX: &[(usize, f64)] = &[(8, 0.1), (usize::MAX, 0.05)];

impl Dofs {
    /// The supernodal structure of the factor of `a` (its unknowns
    /// numbered in order, node by node) made on its nodes and widened to
    /// their unknowns ([`Layout::widened`]); `None` where some node's
    /// unknowns are not one run.
    fn layout_on_nodes(&self, a: &SymSparse) -> Result<Option<Layout>, FrameError> {
        let n = a.n;
        let mut node_of = vec![u32::MAX; n];
        for (g, &u) in self.index.iter().enumerate() {
            if u != NONE && u < n {
                node_of[u] = (g / DOF_PER_NODE) as u32;
            }
        }
        // The runs of unknowns, in order: the nodes' order.
        let mut first = Vec::new();
        let mut run_of = vec![0u32; n];
        for u in 0..n {
            if u == 0 || node_of[u] != node_of[u - 1] {
                first.push(u);
            }
            run_of[u] = (first.len() - 1) as u32;
        }
        first.push(n);
        let runs = first.len() - 1;
        let mut seen = vec![false; self.index.len().div_ceil(DOF_PER_NODE)];
        for &f in &first[..runs] {
            let node = node_of[f] as usize;
            if node >= seen.len() || std::mem::replace(&mut seen[node], true) {
                return Ok(None);
            }
        }
        drop(node_of);
        // The nodes' graph, upper triangle (faer reads it when given no
        // order): a node's first unknown's column holds its own unknowns
        // and every later neighbour's.
        let p = &*a.pattern;
        let (run_of, first_of) = (&run_of, &first);
        let later = |k: usize| {
            let mut last = u32::MAX;
            p.column(first_of[k]).filter_map(move |r| {
                let run = run_of[r];
                (run != last).then(|| {
                    last = run;
                    run as usize
                })
            })
        };
        let (start, rows) = bucketed(runs, (0..runs).flat_map(|k| later(k).map(move |r| (r, k))));
        let upper = SymbolicSparseColMatRef::new_checked(runs, runs, &start, None, &rows);
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            supernodal_params: SymbolicSupernodalParams {
                relax: Some(NODE_RELAX),
            },
            ..Default::default()
        };
        let nodes =
            factorize_symbolic_cholesky(upper, Side::Upper, SymmetricOrdering::Identity, params)
                .map_err(ordering_failed)?;
        let SymbolicCholeskyRaw::Supernodal(supernodal) = nodes.raw() else {
            return Ok(None);
        };
        Ok(Layout::widened(supernodal, &first))
    }
}

fn ordering_failed(e: faer::sparse::FaerError) -> FrameError {
    FrameError::Invalid(format!("ordering: {e:?}"))
}

/// `cholesky` (of `pattern`) with its supernodes in a postorder, so the
/// triangular solves can deal whole subtrees to the threads
/// ([`triangular`]): the same elimination in another order of its
/// independent steps, so the same fill.
fn postordered(
    pattern: SymbolicSparseColMatRef<'_, usize>,
    cholesky: SymbolicCholesky<usize>,
) -> Result<SymbolicCholesky<usize>, FrameError> {
    let SymbolicCholeskyRaw::Supernodal(supernodal) = cholesky.raw() else {
        return Ok(cholesky);
    };
    let Some(order) = Layout::of_faer(supernodal).and_then(|l| triangular::postorder(&l)) else {
        return Ok(cholesky);
    };
    let forward: Vec<usize> = match cholesky.perm() {
        Some(perm) => {
            let (old, _) = perm.arrays();
            order.iter().map(|&c| old[c]).collect()
        }
        None => order,
    };
    symbolic_in_order(pattern, &forward)
}

/// The symbolic factorisation of `pattern` with its unknowns eliminated
/// in the order `forward` (`forward[k]` the k-th).
fn symbolic_in_order(
    pattern: SymbolicSparseColMatRef<'_, usize>,
    forward: &[usize],
) -> Result<SymbolicCholesky<usize>, FrameError> {
    let mut inverse = vec![0; forward.len()];
    for (i, &f) in forward.iter().enumerate() {
        inverse[f] = i;
    }
    factorize_symbolic_cholesky(
        pattern,
        Side::Lower,
        SymmetricOrdering::Custom(PermRef::new_checked(forward, &inverse, forward.len())),
        Default::default(),
    )
    .map_err(ordering_failed)
}

/// Checks indices and values of a model.
pub fn validate(model: &FrameModel) -> Result<(), FrameError> {
    let n = model.nodes_mm.len();
    if let Some(i) = model.nodes_mm.iter().position(|p| !p.is_finite()) {
        return Err(FrameError::Invalid(format!(
            "node {i} has a non-finite position"
        )));
    }
    for (i, s) in model.sections.iter().enumerate() {
        let v = [s.e_mpa, s.g_mpa, s.area_mm2, s.i_y_mm4, s.i_z_mm4, s.j_mm4];
        if v.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
            return Err(FrameError::Invalid(format!(
                "section {i}: E, G, A, I_y, I_z and J must be positive"
            )));
        }
    }
    for (i, b) in model.beams.iter().enumerate() {
        if b.nodes.iter().any(|&v| v >= n) || b.section >= model.sections.len() {
            return Err(FrameError::Invalid(format!(
                "beam {i} names a node or section that does not exist"
            )));
        }
    }
    for (i, l) in model.links.iter().enumerate() {
        if l.nodes.iter().any(|&v| v >= n) {
            return Err(FrameError::Invalid(format!(
                "link {i} names a node that does not exist"
            )));
        }
        let k = l.translation_n_per_mm.iter().chain(&l.rotation_nmm_per_rad);
        if k.clone().any(|x| !(x.is_finite() && *x >= 0.0)) {
            return Err(FrameError::Invalid(format!(
                "link {i}: stiffnesses must be finite and ≥ 0"
            )));
        }
    }
    for (i, c) in model.cables.iter().enumerate() {
        if c.nodes.iter().any(|&v| v >= n) {
            return Err(FrameError::Invalid(format!(
                "cable {i} names a node that does not exist"
            )));
        }
        if !(c.area_mm2.is_finite() && c.area_mm2 > 0.0 && c.e_mpa.is_finite() && c.e_mpa > 0.0) {
            return Err(FrameError::Invalid(format!(
                "cable {i}: E and A must be positive"
            )));
        }
        if !(c.pretension_n.is_finite() && c.pretension_n >= 0.0) {
            return Err(FrameError::Invalid(format!(
                "cable {i}: the pretension must be finite and ≥ 0"
            )));
        }
        if !(c.offsets_mm.iter().all(|o| o.is_finite())
            && exceeds(c.length_mm(&model.nodes_mm), 1e-9))
        {
            return Err(FrameError::Invalid(format!("cable {i} has no length")));
        }
    }
    for s in &model.supports {
        if s.node >= n {
            return Err(FrameError::Invalid(format!(
                "a support names node {} that does not exist",
                s.node
            )));
        }
        if let Some(d) = s.along {
            if !exceeds(d.length(), 0.0) || !d.is_finite() {
                return Err(FrameError::Invalid(format!(
                    "the support of node {} has a zero direction",
                    s.node
                )));
            }
        }
    }
    Ok(())
}

pub(crate) fn validate_loads(model: &FrameModel, loads: &LoadSet) -> Result<(), FrameError> {
    let bad = |what: &str| {
        Err(FrameError::Invalid(format!(
            "load set {}: {what}",
            loads.name
        )))
    };
    let (mut node_outside, mut beam_outside, mut finite) = (false, false, true);
    loads.for_each_node_load(|l, k| {
        node_outside |= l.node >= model.nodes_mm.len();
        finite &= (l.force_n * k).is_finite() && (l.moment_nmm * k).is_finite();
    });
    loads.for_each_beam_load(|l, k| {
        beam_outside |= l.beam >= model.beams.len();
        finite &= (l.force_n_per_mm * k).is_finite();
    });
    loads.for_each_pressure(|l, k| {
        beam_outside |= l.beam >= model.beams.len();
        finite &= (l.n_per_mm * k).is_finite();
    });
    if node_outside {
        return bad("a node load names a node that does not exist");
    }
    if beam_outside {
        return bad("an element load names an element that does not exist");
    }
    if !finite {
        return bad("a load is not finite");
    }
    Ok(())
}

/// Everything about a model's geometry that the analyses reuse.
#[derive(Debug, Clone)]
pub struct Assembly {
    /// The unknowns.
    pub dofs: Dofs,
    /// Per beam: its local frame.
    pub frames: Vec<ElementFrame>,
    /// The node positions the frames were taken at (imperfect geometry in
    /// second order).
    pub nodes_mm: Vec<DVec3>,
    /// Per cable: its unit axis (first end to second) and its stiffness
    /// while taut, N/mm.
    cable_axes: Vec<(DVec3, f64)>,
    /// Where the elements' entries go, made at the first assembly.
    plan: OnceLock<Arc<ScatterPlan>>,
}

/// Where every element's entries go in its model's pattern (the lower
/// triangles of all beams' and links' blocks): a matrix of the model is
/// assembled by adding each element's entries at their places, with no
/// triplets to sort.
///
/// The pattern couples whole nodes (every element adds its whole block,
/// and a node's unknowns are numbered together), so it is made from the
/// node graph: column j of node y holds y's own unknowns from j on, then
/// the unknowns of each neighbour x of y numbered after y, in order. An
/// entry's place is then arithmetic: in column j, row i of y itself at
/// `start[j] + (i − j)`, and row i of neighbour x at
/// `start[j] + (end(y) − j) + offset(y, x) + (i − first(x))`, with
/// offset(y, x) the unknowns of y's neighbours before x. An element keeps
/// only the number of its node pair in the graph. At 400 × 400 curves the
/// places of every entry (78 per element) had taken 800 MB, and sorting
/// them 3.2 GB more.
#[derive(Debug)]
struct ScatterPlan {
    pattern: Arc<Pattern>,
    /// Per element (beams, then links), the number of its node pair among
    /// the graph's edges ([`NONE`]: no pair, one end has no unknowns).
    edge: Vec<usize>,
    /// Per edge (y, x), the unknowns of y's neighbours before x.
    offset: Vec<u32>,
}

/// Beams whose matrices are computed side by side (in parallel) before
/// being added to the values in order.
const SCATTER_CHUNK: usize = 4096;

impl ScatterPlan {
    /// The plan of `assembly`'s elements.
    fn of(assembly: &Assembly, model: &FrameModel) -> ScatterPlan {
        let index = &assembly.dofs.index;
        let nodes = index.len() / DOF_PER_NODE;
        // Each node's unknowns, first..end (first = NONE: none).
        let mut first = vec![NONE; nodes];
        let mut end = vec![0; nodes];
        for (p, six) in index.chunks(DOF_PER_NODE).enumerate() {
            for &u in six.iter().filter(|&&u| u != NONE) {
                first[p] = first[p].min(u);
                end[p] = end[p].max(u + 1);
            }
        }
        // The elements' node pairs (y, x), y's unknowns first, counted by y.
        let elements: Vec<[usize; 2]> = (model.beams.iter().map(|b| b.nodes))
            .chain(model.links.iter().map(|l| l.nodes))
            .collect();
        let pair = |[p, q]: [usize; 2]| -> Option<(usize, usize)> {
            (p != q && first[p] != NONE && first[q] != NONE).then(|| {
                if first[p] < first[q] {
                    (p, q)
                } else {
                    (q, p)
                }
            })
        };
        let mut by_node = vec![0usize; nodes + 1];
        for &e in &elements {
            if let Some((y, _)) = pair(e) {
                by_node[y + 1] += 1;
            }
        }
        for p in 0..nodes {
            by_node[p + 1] += by_node[p];
        }
        let mut fill = by_node.clone();
        let mut ends = vec![(0usize, 0usize, 0usize); by_node[nodes]];
        for (e, &nodes_of) in elements.iter().enumerate() {
            if let Some((y, x)) = pair(nodes_of) {
                ends[fill[y]] = (first[x], x, e);
                fill[y] += 1;
            }
        }
        // Each node's neighbours in the order of their unknowns, each
        // once (the graph's edges: their runs of unknowns), with the
        // unknowns before each.
        let mut edge = vec![NONE; elements.len()];
        let mut offset: Vec<u32> = Vec::with_capacity(ends.len());
        let mut runs: Vec<(usize, usize)> = Vec::with_capacity(ends.len());
        let mut runs_of = vec![0usize; nodes + 1];
        let mut entries = 0;
        for y in 0..nodes {
            let list = &mut ends[by_node[y]..by_node[y + 1]];
            list.sort_unstable();
            let mut before = 0;
            for k in 0..list.len() {
                let (x_first, x, e) = list[k];
                if k == 0 || list[k - 1].0 != x_first {
                    offset.push(before);
                    runs.push((x_first, end[x]));
                    before += (end[x] - x_first) as u32;
                }
                edge[e] = offset.len() - 1;
            }
            runs_of[y + 1] = runs.len();
            if first[y] != NONE {
                let own = end[y] - first[y];
                entries += own * (own + 1) / 2 + own * before as usize;
            }
        }
        drop(ends);
        // The columns, node by node: the node's own unknowns from the
        // column's on, then its neighbours' runs, kept as runs.
        let n = assembly.dofs.free;
        let mut start = Vec::with_capacity(n + 1);
        start.push(0);
        let mut numbered: Vec<usize> = (0..nodes).filter(|&y| first[y] != NONE).collect();
        numbered.sort_unstable_by_key(|&y| first[y]);
        let mut node_of: Vec<u32> = Vec::with_capacity(n);
        let mut blocks = Vec::with_capacity(numbered.len());
        for (number, &y) in numbered.iter().enumerate() {
            debug_assert_eq!(first[y], start.len() - 1, "unknowns numbered node by node");
            let neighbours: usize = (runs[runs_of[y]..runs_of[y + 1]].iter())
                .map(|&(from, to)| to - from)
                .sum();
            for j in first[y]..end[y] {
                let last = start[start.len() - 1];
                start.push(last + (end[y] - j) + neighbours);
                node_of.push(u32::try_from(number).expect("fewer than 2³² nodes"));
            }
            blocks.push((end[y], runs_of[y], runs_of[y + 1]));
        }
        assert_eq!(start.len(), n + 1, "every unknown a node's");
        debug_assert_eq!(start[n], entries, "the entries counted");
        ScatterPlan {
            pattern: Arc::new(Pattern {
                start,
                rows: Rows::Blocks(NodeBlocks {
                    node_of,
                    nodes: blocks,
                    runs,
                }),
                in_order: assembly.dofs.in_order,
            }),
            edge,
            offset,
        }
    }

    /// Adds element `e`'s block `k` over its unknowns `d` (its first node's
    /// six, then its second's; `NONE` where fixed) to `values`.
    fn add(&self, values: &mut [f64], e: usize, d: &[usize; 12], k: &Mat12) {
        let start = &self.pattern.start;
        // Each half's (first, end) unknowns.
        let span = |half: &[usize]| -> (usize, usize) {
            half.iter()
                .filter(|&&u| u != NONE)
                .fold((NONE, 0), |(f, t), &u| (f.min(u), t.max(u + 1)))
        };
        let halves = [span(&d[..6]), span(&d[6..])];
        let across = self.edge[e];
        for_each_lower(d, |i, j, a, b| {
            let (row_half, column_half) = (halves[a / 6], halves[b / 6]);
            let place = if i < column_half.1 {
                // Row i is of column j's own node.
                start[j] + (i - j)
            } else {
                start[j] + (column_half.1 - j) + self.offset[across] as usize + (i - row_half.0)
            };
            values[place] += k[a][b];
        });
    }

    /// Values of zero over the pattern, every page written.
    fn zeros(&self) -> Vec<f64> {
        written_zeros(self.pattern.len())
    }
}

/// `len` zeros, every page written (by both threads) before anything
/// reads it. A large allocation is fresh memory, whose pages the kernel
/// maps when they are first touched: a page first read is mapped twice
/// (the shared zero page, then its own at the first write), and summing
/// into zeros reads first. On this benchmark machine a page's first
/// mapping cost 2 to 20 µs: the 400 × 400 grid's factor (3.9 GB), summed
/// into fresh zeros, took 1.78 million page faults for its 0.95 million
/// pages.
pub(crate) fn written_zeros(len: usize) -> Vec<f64> {
    let mut values = vec![0.0; len];
    values
        .par_chunks_mut(1 << 16)
        .for_each(|chunk| chunk.fill(0.0));
    values
}

/// Calls `f(row, column, a, b)` for every entry of an element's 12 × 12
/// block `d` puts in the lower triangle (both dofs free, row ≥ column), in
/// the order every assembly follows.
fn for_each_lower(d: &[usize; 12], mut f: impl FnMut(usize, usize, usize, usize)) {
    for a in 0..12 {
        if d[a] == NONE {
            continue;
        }
        for b in 0..12 {
            if d[b] == NONE || d[b] > d[a] {
                continue;
            }
            f(d[a], d[b], a, b);
        }
    }
}

impl Assembly {
    /// Frames of `model`'s elements at `nodes_mm`.
    pub fn new(model: &FrameModel, nodes_mm: &[DVec3]) -> Result<Assembly, FrameError> {
        validate(model)?;
        Assembly {
            dofs: Dofs::of(model),
            frames: Vec::new(),
            nodes_mm: Vec::new(),
            cable_axes: Vec::new(),
            plan: OnceLock::new(),
        }
        .at(model, nodes_mm)
    }

    /// The same model's assembly at `nodes_mm` (an imperfect geometry):
    /// its unknowns, offsets, kept symbolic factorisation and scatter plan
    /// shared, its element frames and cables' axes taken anew.
    pub fn moved(&self, model: &FrameModel, nodes_mm: &[DVec3]) -> Result<Assembly, FrameError> {
        Assembly {
            dofs: self.dofs.clone(),
            frames: Vec::new(),
            nodes_mm: Vec::new(),
            cable_axes: Vec::new(),
            plan: self.plan.clone(),
        }
        .at(model, nodes_mm)
    }

    /// The element frames and cables' axes of `model` at `nodes_mm`.
    fn at(mut self, model: &FrameModel, nodes_mm: &[DVec3]) -> Result<Assembly, FrameError> {
        self.frames = model
            .beams
            .iter()
            .enumerate()
            .map(|(i, b)| element_frame(nodes_mm, i, b))
            .collect::<Result<Vec<_>, _>>()?;
        self.cable_axes = model
            .cables
            .iter()
            .map(|c| {
                let [a, b] = c.ends_mm(nodes_mm);
                ((b - a).normalize(), c.stiffness_n_per_mm(nodes_mm))
            })
            .collect();
        self.nodes_mm = nodes_mm.to_vec();
        Ok(self)
    }

    /// The model's scatter plan (made once).
    fn plan(&self, model: &FrameModel) -> Arc<ScatterPlan> {
        self.plan
            .get_or_init(|| Arc::new(ScatterPlan::of(self, model)))
            .clone()
    }

    /// Adds every beam's matrix `matrix(i)` (at its ends, global axes;
    /// `None`: nothing) to `values` at the plan's places: the matrices of
    /// [`SCATTER_CHUNK`] beams at a time computed in parallel, then added
    /// in beam order (the sums are the same whatever the threads).
    fn scatter_beams(
        &self,
        plan: &ScatterPlan,
        model: &FrameModel,
        values: &mut [f64],
        matrix: impl Fn(usize) -> Option<Mat12> + Sync,
    ) {
        let count = model.beams.len();
        let mut start = 0;
        while start < count {
            let end = (start + SCATTER_CHUNK).min(count);
            let blocks: Vec<Option<Mat12>> = (start..end)
                .into_par_iter()
                .map(|i| {
                    matrix(i).map(|k| match &offset_matrix(&model.beams[i].offsets_mm) {
                        None => k,
                        Some(h) => sandwich(h, &k),
                    })
                })
                .collect();
            for (i, k) in (start..end).zip(&blocks) {
                if let Some(k) = k {
                    let d = self.element_dofs(&model.beams[i]);
                    plan.add(values, i, &d, k);
                }
            }
            start = end;
        }
    }

    /// A matrix over the plan's pattern.
    fn over_plan(&self, plan: &ScatterPlan, values: Vec<f64>) -> SymSparse {
        SymSparse {
            n: self.dofs.free,
            pattern: plan.pattern.clone(),
            values,
            scaling: None,
        }
    }

    fn element_dofs(&self, b: &Beam) -> [usize; 12] {
        let mut d = [NONE; 12];
        for k in 0..6 {
            d[k] = self.dofs.index[b.nodes[0] * 6 + k];
            d[6 + k] = self.dofs.index[b.nodes[1] * 6 + k];
        }
        d
    }

    /// An element's block `k` over dofs `d` as triplets (cables, which
    /// the plan does not hold).
    fn scatter(&self, t: &mut Vec<(usize, usize, f64)>, d: &[usize; 12], k: &Mat12) {
        // Zeros too: every matrix of the model then has the same pattern
        // (one symbolic factorisation for all).
        for_each_lower(d, |row, column, a, b| t.push((row, column, k[a][b])));
    }

    /// The elastic stiffness (elements, links, inclined supports).
    pub(crate) fn stiffness(&self, model: &FrameModel) -> SymSparse {
        let plan = self.plan(model);
        let mut values = plan.zeros();
        self.scatter_beams(&plan, model, &mut values, |i| {
            let (b, f) = (&model.beams[i], &self.frames[i]);
            Some(to_global(
                &local_stiffness(&model.sections[b.section], f.length_mm),
                &f.rotation,
            ))
        });
        for (index, l) in model.links.iter().enumerate() {
            let mut k = [[0.0; 12]; 12];
            for (offset, stiff) in [(0, &l.translation_n_per_mm), (3, &l.rotation_nmm_per_rad)] {
                for (axis, &ks) in stiff.iter().enumerate() {
                    let a = l.frame.col(axis);
                    for p in 0..3 {
                        for q in 0..3 {
                            let v = ks * a[p] * a[q];
                            k[offset + p][offset + q] += v;
                            k[6 + offset + p][6 + offset + q] += v;
                            k[offset + p][6 + offset + q] -= v;
                            k[6 + offset + p][offset + q] -= v;
                        }
                    }
                }
            }
            plan.add(
                &mut values,
                model.beams.len() + index,
                &self.node_dofs(l.nodes),
                &k,
            );
        }
        let mut sym = self.over_plan(&plan, values);
        let inclined: Vec<_> = model
            .supports
            .iter()
            .filter(|s| s.along.is_some())
            .collect();
        if !inclined.is_empty() {
            let diagonal = sym.diagonal();
            let mut extra: Vec<(usize, usize, f64)> = Vec::new();
            for s in inclined {
                let a = s.along.unwrap_or(DVec3::Z).normalize();
                let own = (0..3)
                    .map(|p| self.dofs.index[s.node * 6 + p])
                    .filter(|&d| d != NONE)
                    .map(|d| diagonal[d])
                    .fold(0.0, f64::max)
                    .max(1.0);
                for p in 0..3 {
                    for q in 0..=p {
                        let (dp, dq) = (
                            self.dofs.index[s.node * 6 + p],
                            self.dofs.index[s.node * 6 + q],
                        );
                        if dp != NONE && dq != NONE {
                            let (r, c) = if dp >= dq { (dp, dq) } else { (dq, dp) };
                            extra.push((r, c, PENALTY * own * a[p] * a[q]));
                        }
                    }
                }
            }
            // In place where the pattern has the entries (a node with an
            // element has its own block), else a matrix with them added.
            let places: Option<Vec<usize>> =
                extra.iter().map(|&(r, c, _)| sym.place(r, c)).collect();
            match places {
                Some(places) => {
                    for (place, (_, _, v)) in places.into_iter().zip(&extra) {
                        sym.values[place] += v;
                    }
                }
                None => {
                    let mut all: Vec<(usize, usize, f64)> = sym.entries().collect();
                    all.extend(extra);
                    sym = SymSparse::from_triplets(self.dofs.free, all);
                }
            }
            sym.scaling = Some(diagonal);
        }
        sym
    }

    /// The geometric stiffness under per-element axial forces (tension
    /// positive), plus the load stiffness of following pressures × `pressure_scale`.
    pub(crate) fn geometric(
        &self,
        model: &FrameModel,
        axial_n: &[f64],
        pressures: Option<&LoadSet>,
    ) -> SymSparse {
        self.geometric_terms(model, axial_n, pressures, GeometricTerms::Full)
    }

    /// [`Assembly::geometric`] with the chosen `terms`.
    pub(crate) fn geometric_terms(
        &self,
        model: &FrameModel,
        axial_n: &[f64],
        pressures: Option<&LoadSet>,
        terms: GeometricTerms,
    ) -> SymSparse {
        let plan = self.plan(model);
        let mut values = plan.zeros();
        self.scatter_beams(&plan, model, &mut values, |i| {
            (axial_n[i] != 0.0).then(|| {
                let (b, f) = (&model.beams[i], &self.frames[i]);
                to_global(
                    &local_geometric_terms(
                        &model.sections[b.section],
                        f.length_mm,
                        axial_n[i],
                        terms,
                    ),
                    &f.rotation,
                )
            })
        });
        if let Some(loads) = pressures {
            self.pressure_stiffness(model, loads, &plan, &mut values);
        }
        self.over_plan(&plan, values)
    }

    /// The load stiffness −∂f/∂u of pressures that turn with their chord:
    /// the element's force q·L·e_z changes with the chord c by
    /// q·(e_z·e_xᵀ − e_x·e_zᵀ)·δc, shared equally by its two nodes; the
    /// symmetric part is kept (exact where neighbouring elements' terms
    /// cancel, as on an arch or a surface under hydrostatic pressure).
    fn pressure_stiffness(
        &self,
        model: &FrameModel,
        loads: &LoadSet,
        plan: &ScatterPlan,
        values: &mut [f64],
    ) {
        loads.for_each_pressure(|p, factor| {
            let b = &model.beams[p.beam];
            let r = &self.frames[p.beam].rotation;
            let (ex, ez) = (r.row(0), r.row(2));
            let h = 0.5 * (p.n_per_mm * factor);
            let mut k = [[0.0; 12]; 12];
            for a in 0..3 {
                for c in 0..3 {
                    let m = h * (ez[a] * ex[c] - ex[a] * ez[c]);
                    // −∂f_i/∂u_i = +m, −∂f_i/∂u_j = −m, −∂f_j/∂u_i = +m, −∂f_j/∂u_j = −m.
                    k[a][c] += m;
                    k[a][6 + c] -= m;
                    k[6 + a][c] += m;
                    k[6 + a][6 + c] -= m;
                }
            }
            let mut sym = [[0.0; 12]; 12];
            for a in 0..12 {
                for c in 0..12 {
                    sym[a][c] = 0.5 * (k[a][c] + k[c][a]);
                }
            }
            let k = match &offset_matrix(&model.beams[p.beam].offsets_mm) {
                None => sym,
                Some(h) => sandwich(h, &sym),
            };
            plan.add(values, p.beam, &self.element_dofs(b), &k);
        });
    }

    /// The taut cables' stiffness k·e·eᵀ between their ends, as a matrix
    /// over the unknowns.
    pub(crate) fn cable_stiffness(&self, model: &FrameModel, taut: &[bool]) -> SymSparse {
        self.cable_matrix(model, |i, e| {
            let k = self.cable_axes[i].1;
            taut[i].then(|| std::array::from_fn(|p| std::array::from_fn(|q| k * e[p] * e[q])))
        })
    }

    /// The geometric stiffness of cables under `forces_n` (tension
    /// positive; 0 for slack ones): a taut string resists moving its ends
    /// across its axis by N/L·(I − e·eᵀ). A cable never pushes: a
    /// compressive force (a held cable whose pretension is left out, see
    /// `CableState::Held`) adds nothing.
    pub(crate) fn cable_geometric(&self, model: &FrameModel, forces_n: &[f64]) -> SymSparse {
        let taut: Vec<f64> = forces_n.iter().map(|&n| n.max(0.0)).collect();
        self.cable_geometric_signed(model, &taut)
    }

    /// The string term N/L·(I − e·eᵀ) of force changes `forces_n`, either
    /// sign (a load's share of a taut cable's force, which may lessen it).
    pub(crate) fn cable_geometric_signed(&self, model: &FrameModel, forces_n: &[f64]) -> SymSparse {
        self.cable_matrix(model, |i, e| {
            let n = forces_n[i];
            let g = n / model.cables[i].length_mm(&self.nodes_mm);
            let unit = |p: usize, q: usize| if p == q { 1.0 } else { 0.0 };
            (n != 0.0).then(|| {
                std::array::from_fn(|p| std::array::from_fn(|q| g * (unit(p, q) - e[p] * e[q])))
            })
        })
    }

    /// Σ over cables of the two-end matrix [B −B; −B B] of the 3 × 3 block
    /// B that `block(cable, its axis)` gives (None: none), on the ends'
    /// translations, through the cable's end offsets.
    fn cable_matrix(
        &self,
        model: &FrameModel,
        block: impl Fn(usize, DVec3) -> Option<[[f64; 3]; 3]>,
    ) -> SymSparse {
        let mut t = Vec::with_capacity(model.cables.len() * 78);
        for (i, c) in model.cables.iter().enumerate() {
            let Some(b) = block(i, self.cable_axes[i].0) else {
                continue;
            };
            let mut m = [[0.0; 12]; 12];
            for p in 0..3 {
                for q in 0..3 {
                    m[p][q] = b[p][q];
                    m[6 + p][6 + q] = b[p][q];
                    m[p][6 + q] = -b[p][q];
                    m[6 + p][q] = -b[p][q];
                }
            }
            let d = self.node_dofs(c.nodes);
            match offset_matrix(&c.offsets_mm) {
                None => self.scatter(&mut t, &d, &m),
                Some(h) => self.scatter(&mut t, &d, &sandwich(&h, &m)),
            }
        }
        SymSparse::from_triplets(self.dofs.free, t)
    }

    /// The taut cables' pretensions as loads on their nodes: each pulls
    /// its ends towards each other with T₀ (over the unknowns).
    pub(crate) fn cable_pull(&self, model: &FrameModel, taut: &[bool]) -> Vec<f64> {
        let mut p = vec![0.0; self.dofs.free];
        for (i, c) in model.cables.iter().enumerate() {
            if !taut[i] || c.pretension_n == 0.0 {
                continue;
            }
            let (e, _) = self.cable_axes[i];
            let f = e * c.pretension_n;
            let mut end = [0.0; 12];
            end[..3].copy_from_slice(&f.to_array());
            end[6..9].copy_from_slice(&(-f).to_array());
            let g = apply_ht(&c.offsets_mm, end);
            for (k, &dof) in self.node_dofs(c.nodes).iter().enumerate() {
                if dof != NONE {
                    p[dof] += g[k];
                }
            }
        }
        p
    }

    /// Every cable's force were it taut, N: T₀ + k·δ, δ the lengthening of
    /// its chord under the displacements `x` (over the unknowns).
    pub(crate) fn cable_forces(&self, model: &FrameModel, x: &[f64]) -> Vec<f64> {
        if model.cables.is_empty() {
            return Vec::new();
        }
        let displacements = self.expand(x);
        model
            .cables
            .iter()
            .zip(&self.cable_axes)
            .map(|(c, &(e, k))| {
                let mut u = [0.0; 12];
                u[..6].copy_from_slice(&displacements[c.nodes[0]]);
                u[6..].copy_from_slice(&displacements[c.nodes[1]]);
                let u = apply_h(&c.offsets_mm, u);
                let delta = e.dot(DVec3::new(u[6], u[7], u[8]) - DVec3::new(u[0], u[1], u[2]));
                c.pretension_n + k * delta
            })
            .collect()
    }

    /// The unknowns of two nodes' 12 degrees of freedom (`NONE` where
    /// fixed).
    fn node_dofs(&self, nodes: [usize; 2]) -> [usize; 12] {
        let mut d = [NONE; 12];
        for k in 0..6 {
            d[k] = self.dofs.index[nodes[0] * 6 + k];
            d[6 + k] = self.dofs.index[nodes[1] * 6 + k];
        }
        d
    }

    /// Every element's uniform load in its own axes, N/mm: its loads
    /// turned into its frame, its pressures along its local z.
    fn local_uniform_loads(&self, model: &FrameModel, loads: &LoadSet) -> Vec<DVec3> {
        let mut q = vec![DVec3::ZERO; model.beams.len()];
        loads.for_each_beam_load(|l, factor| {
            q[l.beam] += self.frames[l.beam].rotation * (l.force_n_per_mm * factor);
        });
        loads.for_each_pressure(|l, factor| q[l.beam].z += l.n_per_mm * factor);
        q
    }

    /// The load vector over the unknowns: the node loads, and each
    /// element's consistent nodal loads of its uniform load (linear in the
    /// load, so made once of the element's loads summed, with no
    /// 12-entry array per element held: 245 MB a load set at 400 × 400).
    /// From [`PARALLEL_LOAD_BEAMS`] elements on, each half of them is
    /// added on its own core (the second half into an array of its own,
    /// added last): the elements' unknowns are scattered in the order of
    /// elimination, and a load vector at 400 × 400 benchmark curves took
    /// 0.3–0.45 s on one.
    pub(crate) fn load_vector(&self, model: &FrameModel, loads: &LoadSet) -> Vec<f64> {
        let halves = model.beams.len() >= PARALLEL_LOAD_BEAMS;
        self.load_vector_in(model, loads, halves)
    }

    /// [`Assembly::load_vector`], the elements in two halves on the two
    /// cores where `halves`, else in one pass.
    fn load_vector_in(&self, model: &FrameModel, loads: &LoadSet, halves: bool) -> Vec<f64> {
        let n = self.dofs.free;
        let mut p = vec![0.0; n];
        let index = &self.dofs.index;
        let add = |p: &mut [f64], node: usize, k: usize, v: f64| {
            let d = index[node * 6 + k];
            if d != NONE {
                p[d] += v;
            }
        };
        loads.for_each_node_load(|l, factor| {
            let (f, m) = (l.force_n * factor, l.moment_nmm * factor);
            for k in 0..3 {
                add(&mut p, l.node, k, f[k]);
                add(&mut p, l.node, 3 + k, m[k]);
            }
        });
        let local_q = self.local_uniform_loads(model, loads);
        let elements = |p: &mut [f64], range: std::ops::Range<usize>| {
            for i in range {
                let q = local_q[i];
                if q == DVec3::ZERO {
                    continue;
                }
                let (b, f) = (&model.beams[i], &self.frames[i]);
                let g = apply_ht(
                    &b.offsets_mm,
                    globalise(&f.rotation, &uniform_nodal_loads(q, f.length_mm)),
                );
                for k in 0..6 {
                    add(p, b.nodes[0], k, g[k]);
                    add(p, b.nodes[1], k, g[6 + k]);
                }
            }
        };
        let count = model.beams.len();
        if !halves {
            elements(&mut p, 0..count);
            return p;
        }
        let half = count / 2;
        let (_, second) = rayon::join(
            || elements(&mut p, 0..half),
            || {
                let mut second = vec![0.0; n];
                elements(&mut second, half..count);
                second
            },
        );
        p.par_iter_mut()
            .with_min_len(PARALLEL_ROWS)
            .zip(&second)
            .for_each(|(a, b)| *a += b);
        p
    }

    /// Displacements of every node from the unknowns.
    fn expand(&self, x: &[f64]) -> Vec<[f64; 6]> {
        let n = self.dofs.index.len() / 6;
        (0..n)
            .map(|v| {
                let mut d = [0.0; 6];
                for (k, dk) in d.iter_mut().enumerate() {
                    let i = self.dofs.index[v * 6 + k];
                    if i != NONE {
                        *dk = x[i];
                    }
                }
                d
            })
            .collect()
    }

    /// Section forces, reactions; `axial_n` adds each element's geometric
    /// stiffness to its end forces (second order).
    /// `cable_forces_n`: every cable's force (0 when slack; empty
    /// without cables).
    pub(crate) fn results(
        &self,
        model: &FrameModel,
        loads: &LoadSet,
        x: &[f64],
        axial_n: Option<&[f64]>,
        cable_forces_n: &[f64],
    ) -> StaticResult {
        self.results_of(model, loads, self.expand(x), axial_n, cable_forces_n)
    }

    /// [`Assembly::results`] of the displacements of every node (the
    /// unknowns expanded, [`Assembly::expand`]): the caller may let the
    /// unknowns go first (98 MB at 400 × 400 benchmark curves).
    fn results_of(
        &self,
        model: &FrameModel,
        loads: &LoadSet,
        displacements: Vec<[f64; 6]>,
        axial_n: Option<&[f64]>,
        cable_forces_n: &[f64],
    ) -> StaticResult {
        let local_q = self.local_uniform_loads(model, loads);
        // Each element's end forces, local (N, N·mm), on either core.
        let local_end_forces = |i: usize| -> [f64; 12] {
            let b = &model.beams[i];
            let f = &self.frames[i];
            let s = &model.sections[b.section];
            let mut ug = [0.0; 12];
            ug[..6].copy_from_slice(&displacements[b.nodes[0]]);
            ug[6..].copy_from_slice(&displacements[b.nodes[1]]);
            let ul = localise(&f.rotation, &apply_h(&b.offsets_mm, ug));
            let mut fl = local_stiffness_times(s, f.length_mm, &ul);
            if let Some(n) = axial_n {
                let kg = local_geometric(s, f.length_mm, n[i]);
                for a in 0..12 {
                    fl[a] += (0..12).map(|c| kg[a][c] * ul[c]).sum::<f64>();
                }
            }
            let equivalent = uniform_nodal_loads(local_q[i], f.length_mm);
            for a in 0..12 {
                fl[a] -= equivalent[a];
            }
            fl
        };
        let beam_forces: Vec<BeamEndForces> = (0..model.beams.len())
            .into_par_iter()
            .with_min_len(PARALLEL_BEAMS)
            .map(|i| {
                let fl = local_end_forces(i);
                let v3 = |o: usize| DVec3::new(fl[o], fl[o + 1], fl[o + 2]);
                let (f0, m0) = (-v3(0), -v3(3));
                let h = 0.5 * self.frames[i].length_mm;
                let q = local_q[i];
                let fm = f0 - q * h;
                let mm = m0 - DVec3::X.cross(f0 * h - q * (0.5 * h * h));
                BeamEndForces {
                    start: SectionForces::from_vectors(f0, m0),
                    middle: SectionForces::from_vectors(fm, mm),
                    end: SectionForces::from_vectors(v3(6), v3(9)),
                }
            })
            .collect();
        // The nodes' internal forces, where the reactions read them: at
        // the supported nodes only (each its place in `internal`), from
        // the elements reaching them.
        const UNSUPPORTED: u32 = u32::MAX;
        let mut place = vec![UNSUPPORTED; model.nodes_mm.len()];
        let mut held = 0;
        for s in &model.supports {
            if place[s.node] == UNSUPPORTED {
                place[s.node] = held;
                held += 1;
            }
        }
        let at = |node: usize| (place[node] != UNSUPPORTED).then(|| place[node] as usize);
        // v added to a supported node's sums from `offset` on.
        let add_to = |sums: &mut [[f64; 6]], node: usize, offset: usize, v: &[f64]| {
            if let Some(s) = at(node) {
                for (sum, v) in sums[s][offset..offset + v.len()].iter_mut().zip(v) {
                    *sum += v;
                }
            }
        };
        let mut internal = vec![[0.0; 6]; held as usize];
        let mut add =
            |node: usize, offset: usize, v: &[f64]| add_to(&mut internal, node, offset, v);
        for (i, b) in model.beams.iter().enumerate() {
            if at(b.nodes[0]).is_none() && at(b.nodes[1]).is_none() {
                continue;
            }
            let g = apply_ht(
                &b.offsets_mm,
                globalise(&self.frames[i].rotation, &local_end_forces(i)),
            );
            add(b.nodes[0], 0, &g[..6]);
            add(b.nodes[1], 0, &g[6..]);
        }
        for l in &model.links {
            let (a, b) = (l.nodes[0], l.nodes[1]);
            for (offset, stiff) in [(0, &l.translation_n_per_mm), (3, &l.rotation_nmm_per_rad)] {
                let da = DVec3::from_slice(&displacements[a][offset..offset + 3]);
                let db = DVec3::from_slice(&displacements[b][offset..offset + 3]);
                let mut force = DVec3::ZERO;
                for (axis, &ks) in stiff.iter().enumerate() {
                    let e = l.frame.col(axis);
                    force += e * (ks * e.dot(da - db));
                }
                add(a, offset, &force.to_array());
                add(b, offset, &(-force).to_array());
            }
        }
        for ((c, &(e, _)), &n) in model
            .cables
            .iter()
            .zip(&self.cable_axes)
            .zip(cable_forces_n)
        {
            // The node holds its end of the cable against the cable's pull.
            for (end, sign) in [(0, -1.0), (1, 1.0)] {
                let f = e * (sign * n);
                let m = c.offsets_mm[end].cross(f);
                let node = c.nodes[end];
                add(node, 0, &f.to_array());
                add(node, 3, &m.to_array());
            }
        }
        let mut applied = vec![[0.0; 6]; held as usize];
        loads.for_each_node_load(|l, factor| {
            add_to(&mut applied, l.node, 0, &(l.force_n * factor).to_array());
            add_to(&mut applied, l.node, 3, &(l.moment_nmm * factor).to_array());
        });
        let mut reactions: Vec<Reaction> = Vec::with_capacity(held as usize);
        for s in &model.supports {
            let slot = place[s.node] as usize;
            if slot < reactions.len() {
                continue;
            }
            let r: Vec<f64> = (0..6)
                .map(|k| internal[slot][k] - applied[slot][k])
                .collect();
            reactions.push(Reaction {
                node: s.node,
                force_n: DVec3::new(r[0], r[1], r[2]),
                moment_nmm: DVec3::new(r[3], r[4], r[5]),
            });
        }
        StaticResult {
            displacements,
            reactions,
            beam_forces,
            cable_forces_n: cable_forces_n.to_vec(),
        }
    }
}

/// A factorised stiffness.
pub(crate) struct Factor {
    symbolic: Symbolic,
    values: Vec<f64>,
}

/// A factorisation's structure: the elimination order and the factor's
/// pattern, shared by every matrix of the same pattern.
pub(crate) type Symbolic = Arc<Structure>;

/// A factor's structure and the two threads' shares of its triangular
/// solves.
#[derive(Debug)]
pub(crate) struct Structure {
    /// faer's symbolic factorisation, where faer made it (a matrix whose
    /// unknowns faer ordered, or one numbered in order whose structure was
    /// not made on the nodes: a node's unknowns not one run, or no
    /// unknowns at all); `None` for a supernodal structure made on the
    /// nodes ([`Layout::widened`]).
    cholesky: Option<SymbolicCholesky<usize>>,
    /// The supernodes, where the factor is supernodal.
    layout: Option<Layout>,
    /// `None`: the factor is not supernodal, too small to share, or its
    /// tree does not split.
    schedule: Option<Schedule>,
    /// Which supernodes update which, for this module's numeric
    /// factorisation ([`supernodal`]); `None` where faer's makes the
    /// factor (not supernodal, or with a permutation of its own).
    updates: Option<Updates>,
}

impl Structure {
    fn of(cholesky: SymbolicCholesky<usize>) -> Structure {
        let layout = match cholesky.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => Layout::of_faer(s),
            SymbolicCholeskyRaw::Simplicial(_) => None,
        };
        let permuted = cholesky.perm().is_some();
        Structure::with(Some(cholesky), layout, permuted)
    }

    fn with(
        cholesky: Option<SymbolicCholesky<usize>>,
        layout: Option<Layout>,
        permuted: bool,
    ) -> Structure {
        let schedule = match &layout {
            Some(l) if l.nrows() >= PARALLEL_ROWS => Schedule::of(l),
            _ => None,
        };
        let updates = match &layout {
            Some(l) if !permuted => Updates::of(l),
            _ => None,
        };
        Structure {
            cholesky,
            layout,
            schedule,
            updates,
        }
    }

    /// The elimination order, where it is not the unknowns' own.
    pub(crate) fn perm(&self) -> Option<PermRef<'_, usize>> {
        self.cholesky.as_ref().and_then(|c| c.perm())
    }

    /// The number of the factor's values.
    #[cfg(test)]
    pub(crate) fn len_val(&self) -> usize {
        match (&self.layout, &self.cholesky) {
            (Some(l), _) => l.len_val(),
            (None, Some(c)) => c.len_val(),
            (None, None) => 0,
        }
    }

    /// The supernodes, where the factor is supernodal.
    #[cfg(test)]
    pub(crate) fn layout(&self) -> Option<&Layout> {
        self.layout.as_ref()
    }
}

impl Factor {
    /// Solves in place for right-hand sides held row by row (row i's
    /// values side by side), as the triangular solves work on them, where
    /// the factor is supernodal and in the unknowns' own order; false, the
    /// rows untouched, where it is not.
    pub(crate) fn solve_rows<const P: usize>(&self, y: &mut [[f64; P]]) -> bool {
        if !self.solves_rows() {
            return false;
        }
        let Some(layout) = &self.symbolic.layout else {
            return false;
        };
        match &self.symbolic.schedule {
            Some(schedule) => solve_scheduled::<P>(layout, &self.values, schedule, y),
            None => solve_serial::<P>(layout, &self.values, y),
        }
        true
    }

    /// Whether [`Factor::solve_rows`] solves: a supernodal factor in the
    /// unknowns' own order, shared between the threads where it is large
    /// enough to be (else [`Factor::solve_in_place`] shares the columns).
    pub(crate) fn solves_rows(&self) -> bool {
        let s = &self.symbolic;
        s.layout.is_some()
            && s.perm().is_none()
            && (s.schedule.is_some()
                || s.layout.as_ref().is_some_and(|l| l.nrows() < PARALLEL_ROWS))
    }

    /// x ← A⁻¹·x for every column of x. A factor of [`PARALLEL_ROWS`]
    /// unknowns or more is shared between two threads: each solves its
    /// share of the factor's subtrees for every column ([`triangular`]),
    /// or where the factor has no such shares each solves half of the
    /// columns (with two or more). A smaller one is solved on this thread.
    pub(crate) fn solve_in_place(&self, x: MatMut<'_, f64>) {
        let p = x.ncols();
        if self.symbolic.schedule.is_none() && p >= 2 && x.nrows() >= PARALLEL_ROWS {
            let (left, right) = x.split_at_col_mut(p / 2);
            rayon::join(|| self.solve_columns(left), || self.solve_columns(right));
        } else {
            self.solve_columns(x);
        }
    }

    /// [`Factor::solve_in_place`] for the columns of x together.
    fn solve_columns(&self, mut x: MatMut<'_, f64>) {
        let p = x.ncols();
        if p == 0 {
            return;
        }
        let Some(supernodal) = &self.symbolic.layout else {
            let Some(cholesky) = &self.symbolic.cholesky else {
                return;
            };
            let llt = LltRef::new(cholesky, &self.values);
            let mut memory = MemBuffer::new(cholesky.solve_in_place_scratch::<f64>(p, Par::Seq));
            llt.solve_in_place_with_conj(Conj::No, x, Par::Seq, MemStack::new(&mut memory));
            return;
        };
        // In blocks of up to eight right-hand sides, permuted into the
        // factor's order with a row's values side by side, so each entry
        // of L is read once per block. Three columns are solved as a
        // block of four and five to seven as one of eight, the spare
        // places zero: a pass of the factor costs more than the arithmetic
        // of the spare places (19 load sets: three passes, not four).
        let (forward, inverse) = match self.symbolic.perm() {
            Some(perm) => {
                let (f, i) = perm.arrays();
                (Some(f), Some(i))
            }
            None => (None, None),
        };
        let mut first = 0;
        while first < p {
            let width = match p - first {
                w if w > 4 => 8,
                w if w > 2 => 4,
                w => w,
            };
            let columns = first..(first + width).min(p);
            let block = Block {
                layout: supernodal,
                schedule: self.symbolic.schedule.as_ref(),
                values: &self.values,
                forward,
                inverse,
            };
            match width {
                8 => block.solve::<8>(&mut x, columns),
                4 => block.solve::<4>(&mut x, columns),
                2 => block.solve::<2>(&mut x, columns),
                _ => block.solve::<1>(&mut x, columns),
            }
            first += width.min(p - first);
        }
    }
}

/// A factor's triangular solves for a block of right-hand sides.
struct Block<'a> {
    layout: &'a Layout,
    schedule: Option<&'a Schedule>,
    values: &'a [f64],
    /// The factor's order: row i of the permuted system is row
    /// `forward[i]` of x, and row i of x is row `inverse[i]` of it.
    forward: Option<&'a [usize]>,
    inverse: Option<&'a [usize]>,
}

impl Block<'_> {
    /// Solves for the columns `columns` (P of them) of x in place,
    /// permuted into the factor's order with a row's values side by side.
    fn solve<const P: usize>(&self, x: &mut MatMut<'_, f64>, columns: std::ops::Range<usize>) {
        let n = x.nrows();
        let mut y = vec![[0.0; P]; n];
        for (c, column) in columns.clone().enumerate() {
            let from = x.as_ref().col(column);
            for (i, row) in y.iter_mut().enumerate() {
                row[c] = from[self.forward.map_or(i, |f| f[i])];
            }
        }
        match self.schedule {
            Some(schedule) => solve_scheduled::<P>(self.layout, self.values, schedule, &mut y),
            None => solve_serial::<P>(self.layout, self.values, &mut y),
        }
        for (c, column) in columns.enumerate() {
            let mut to = x.as_mut().col_mut(column);
            for i in 0..n {
                to[i] = y[self.inverse.map_or(i, |v| v[i])][c];
            }
        }
    }
}

/// The numeric factor of `a` on `symbolic`; `None` when a pivot is not
/// positive.
fn numeric(symbolic: &Symbolic, a: &SymSparse) -> Result<Option<Factor>, FrameError> {
    if let (Some(supernodal), Some(updates)) = (&symbolic.layout, &symbolic.updates) {
        let lower = Lower {
            pattern: &a.pattern,
            values: &a.values,
        };
        let values = supernodal::factorise(supernodal, updates, symbolic.schedule.as_ref(), lower);
        return Ok(values.map(|values| Factor {
            symbolic: symbolic.clone(),
            values,
        }));
    }
    let Some(cholesky) = &symbolic.cholesky else {
        return Err(FrameError::Invalid(
            "a factor's structure without faer's or its own numeric factorisation".into(),
        ));
    };
    let mut values = vec![0.0; cholesky.len_val()];
    let mut memory =
        MemBuffer::new(cholesky.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()));
    let ok = cholesky
        .factorize_numeric_llt(
            &mut values,
            a.to_faer()?.matrix(),
            Side::Lower,
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut memory),
            Default::default(),
        )
        .is_ok();
    Ok(ok.then(|| Factor {
        symbolic: symbolic.clone(),
        values,
    }))
}

/// Factorises `k`; a failure or a near-null vector is reported as a
/// mechanism naming the node.
pub(crate) fn factorise(k: &SymSparse, dofs: &Dofs) -> Result<Factor, FrameError> {
    let diag = k.scaling.clone().unwrap_or_else(|| k.diagonal());
    if let Some(i) = diag.iter().position(|&d| !exceeds(d, 0.0)) {
        let (node, dof) = node_of(dofs, i);
        return Err(FrameError::Mechanism { node, dof });
    }
    let symbolic = dofs.symbolic_of(k)?;
    match numeric(&symbolic, k)? {
        Some(factor) => {
            if let Some(unknown) = near_null(k, &diag, &factor) {
                let (node, dof) = node_of(dofs, unknown);
                return Err(FrameError::Mechanism { node, dof });
            }
            Ok(factor)
        }
        None => {
            // Regularise by a tiny multiple of the diagonal to find the
            // null vector by inverse iteration.
            let mut reg = k.clone();
            reg.add_to_diagonal(1e-9, &diag);
            let factor = numeric(&symbolic, &reg)?.ok_or_else(|| {
                let (node, dof) = node_of(dofs, 0);
                FrameError::Mechanism { node, dof }
            })?;
            let v = inverse_iteration(&reg, &diag, &factor, 6).1;
            let (node, dof) = dominant(dofs, &v);
            Err(FrameError::Mechanism { node, dof })
        }
    }
}

/// Factorises `k` when it is positive definite (`None` when a pivot is not
/// positive), with no test for a near-null vector: for a matrix known to
/// be nonsingular where it is definite, such as a stiffness shifted by
/// part of its critical load, or a tangent stiffness once the model has
/// passed that test.
pub(crate) fn factorise_definite(k: &SymSparse, dofs: &Dofs) -> Result<Option<Factor>, FrameError> {
    let symbolic = dofs.symbolic_of(k)?;
    numeric(&symbolic, k)
}

fn node_of(dofs: &Dofs, unknown: usize) -> (usize, usize) {
    let g = dofs.index.iter().position(|&i| i == unknown).unwrap_or(0);
    (g / 6, g % 6)
}

/// The node and degree of freedom where `v` (over the unknowns) is
/// largest.
fn dominant(dofs: &Dofs, v: &[f64]) -> (usize, usize) {
    let (mut best, mut at) = (-1.0, 0);
    for (i, x) in v.iter().enumerate() {
        if x.abs() > best {
            (best, at) = (x.abs(), i);
        }
    }
    node_of(dofs, at)
}

/// A few inverse iterations on the Jacobi-scaled stiffness: the smallest
/// eigenvalue's estimate and its vector (unscaled: x = D^-½·y).
fn inverse_iteration(
    k: &SymSparse,
    diag: &[f64],
    factor: &Factor,
    iterations: usize,
) -> (f64, Vec<f64>) {
    let n = k.n;
    let mut x = Mat::<f64>::zeros(n, 1);
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
    for i in 0..n {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        x[(i, 0)] = ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5) / diag[i].sqrt();
    }
    let mut lambda = f64::INFINITY;
    for _ in 0..iterations {
        // x ← K⁻¹·D·x, normalised in the D-norm.
        for i in 0..n {
            x[(i, 0)] *= diag[i];
        }
        factor.solve_in_place(x.as_mut());
        let norm = (0..n)
            .map(|i| diag[i] * x[(i, 0)] * x[(i, 0)])
            .sum::<f64>()
            .sqrt();
        if !exceeds(norm, 0.0) || !norm.is_finite() {
            break;
        }
        for i in 0..n {
            x[(i, 0)] /= norm;
        }
        let kx = k.mul_block(x.as_ref());
        lambda = (0..n).map(|i| x[(i, 0)] * kx[(i, 0)]).sum::<f64>();
    }
    let scaled: Vec<f64> = (0..n).map(|i| x[(i, 0)] * diag[i].sqrt()).collect();
    (lambda, scaled)
}

/// `Some(unknown)` when the factorised `k` is a mechanism in floating
/// point (its scaled smallest eigenvalue below [`MECHANISM_RATIO`]): the
/// unknown that moves most in the near-null vector.
fn near_null(k: &SymSparse, diag: &[f64], factor: &Factor) -> Option<usize> {
    let (lambda, v) = inverse_iteration(k, diag, factor, 4);
    if lambda < MECHANISM_RATIO || !lambda.is_finite() {
        let (mut best, mut at) = (-1.0, 0);
        for (i, x) in v.iter().enumerate() {
            if x.abs() > best {
                (best, at) = (x.abs(), i);
            }
        }
        return Some(at);
    }
    None
}

/// A model assembled and factorised once for linear static solves.
pub struct LinearFrame<'m> {
    model: &'m FrameModel,
    pub(crate) assembly: Assembly,
    pub(crate) stiffness: SymSparse,
    pub(crate) factor: Factor,
    initial_axial: Vec<f64>,
    /// Per cable: taut (held so).
    taut: Vec<bool>,
    /// The taut cables' pretensions as loads, over the unknowns (empty
    /// where there are none).
    pull: Vec<f64>,
    /// The members' axial forces under the pretension alone (empty: none).
    pub(crate) pre_axial: Vec<f64>,
    /// The cables' forces under the pretension alone (empty: none).
    pub(crate) pre_cable_n: Vec<f64>,
    /// The geometric stiffness of the pretension's state (None: none).
    pub(crate) pre_geometric: Option<SymSparse>,
}

impl<'m> LinearFrame<'m> {
    /// Assembles and factorises `model`'s stiffness (with the geometric
    /// stiffness of its elements' initial axial forces).
    pub fn new(model: &'m FrameModel) -> Result<LinearFrame<'m>, FrameError> {
        if !model.cables.is_empty() {
            return Err(FrameError::Invalid(
                "a frame with tension-only cables is not linear: solve it with tension::solve_tension_only".into(),
            ));
        }
        LinearFrame::with_cables(model, &[])
    }

    /// As [`LinearFrame::new`] with `model`'s cables held in the state
    /// `taut` (one flag per cable): the taut ones are bars of their
    /// stiffness pulling with their pretension, the slack ones are not
    /// there. Linear for as long as that state holds (the state a
    /// tension-only solve found for a load set).
    pub fn with_cables(
        model: &'m FrameModel,
        taut: &[bool],
    ) -> Result<LinearFrame<'m>, FrameError> {
        if taut.len() != model.cables.len() {
            return Err(FrameError::Invalid(format!(
                "{} cable states for {} cables",
                taut.len(),
                model.cables.len()
            )));
        }
        let assembly = Assembly::new(model, &model.nodes_mm)?;
        let initial_axial: Vec<f64> = model.beams.iter().map(|b| b.initial.axial_n).collect();
        let mut stiffness = assembly.stiffness(model);
        if initial_axial.iter().any(|&n| n != 0.0) {
            let g = assembly.geometric(model, &initial_axial, None);
            stiffness = add(&stiffness, &g, 1.0);
        }
        if !model.cables.is_empty() {
            stiffness = add(&stiffness, &assembly.cable_stiffness(model, taut), 1.0);
        }
        let factor = factorise(&stiffness, &assembly.dofs)?;
        let mut pull = assembly.cable_pull(model, taut);
        if pull.iter().all(|&p| p == 0.0) {
            pull = Vec::new();
        }
        // The pretension's own state (the frame under the cables' pull
        // alone) is, like the erection state, a state the frame stands in
        // before any load: a buckling analysis adds its geometric
        // stiffness to the stiffness and scales only the load's share.
        // The statics stay linear (as a frame program computes them).
        let (mut pre_axial, mut pre_cable_n, mut pre_geometric) = (Vec::new(), Vec::new(), None);
        if !pull.is_empty() {
            let x = solve_refined(&factor, &stiffness, &pull)?;
            let cable_n: Vec<f64> = assembly
                .cable_forces(model, &x)
                .iter()
                .zip(taut)
                .map(|(&n, &t)| if t { n } else { 0.0 })
                .collect();
            let state = assembly.results(model, &LoadSet::default(), &x, None, &cable_n);
            pre_axial = axial_forces(&state);
            pre_geometric = Some(add(
                &assembly.geometric(model, &pre_axial, None),
                &assembly.cable_geometric(model, &cable_n),
                1.0,
            ));
            pre_cable_n = cable_n;
        }
        Ok(LinearFrame {
            model,
            assembly,
            stiffness,
            factor,
            initial_axial,
            taut: taut.to_vec(),
            pull,
            pre_axial,
            pre_cable_n,
            pre_geometric,
        })
    }

    /// The model.
    pub fn model(&self) -> &FrameModel {
        self.model
    }

    /// The erection state's axial forces, per element.
    pub fn initial_axial(&self) -> &[f64] {
        &self.initial_axial
    }

    /// The linear static solution under `loads`.
    pub fn solve(&self, loads: &LoadSet) -> Result<StaticResult, FrameError> {
        self.solve_with_cables(loads).map(|(result, _)| result)
    }

    /// [`LinearFrame::solve`] for every load set, eight at a time (one
    /// pass of the factor per eight).
    pub fn solve_all(&self, loads: &[&LoadSet]) -> Result<Vec<StaticResult>, FrameError> {
        Ok(self
            .solve_all_with_cables(loads)?
            .into_iter()
            .map(|(result, _)| result)
            .collect())
    }

    /// [`LinearFrame::solve`], and every cable's force were it taut
    /// (T₀ + k·δ, negative where the solution shortens it past its
    /// unstressed length): what tells whether the cables' state holds.
    pub(crate) fn solve_with_cables(
        &self,
        loads: &LoadSet,
    ) -> Result<(StaticResult, Vec<f64>), FrameError> {
        self.solve_all_with_cables(&[loads])?
            .pop()
            .ok_or_else(|| FrameError::Invalid("a static solution is missing".into()))
    }

    /// [`LinearFrame::solve_with_cables`] for every load set, a block of
    /// them at a time.
    fn solve_all_with_cables(
        &self,
        loads: &[&LoadSet],
    ) -> Result<Vec<(StaticResult, Vec<f64>)>, FrameError> {
        let statics = self.solve_each(loads)?;
        (0..loads.len())
            .map(|c| statics.result_with_cables(c))
            .collect()
    }

    /// Every load set solved when its result is first asked for
    /// ([`Statics::result`]), its section forces and reactions made then:
    /// load sets that are sums of fewer shared parts (combinations of load
    /// cases) as those sums of the parts' solutions, the parts solved
    /// together once ([`Superposition`]); others [`STATICS_BLOCK`] at a
    /// time (one pass of the factor per block), only one block's solutions
    /// held. At 400 × 400 curves a load set's solution takes 98 MB.
    pub fn solve_each<'a>(&'a self, loads: &[&'a LoadSet]) -> Result<Statics<'a, 'm>, FrameError> {
        for set in loads {
            validate_loads(self.model, set)?;
        }
        Ok(Statics {
            frame: self,
            loads: loads.to_vec(),
            superposed: Superposition::of(loads, !self.pull.is_empty()),
            solved: Mutex::new(None),
            parts: Mutex::new(None),
        })
    }

    /// The right-hand side of a load set: its load vector plus the taut
    /// cables' pretensions.
    fn rhs(&self, set: &LoadSet) -> Vec<f64> {
        let mut v = self.assembly.load_vector(self.model, set);
        for (vi, pull) in v.iter_mut().zip(&self.pull) {
            *vi += pull;
        }
        v
    }

    /// The solutions of a superposition's parts, each refined, row by row
    /// ([`Parts`]). Each part's right-hand side is made again for its
    /// backward error rather than kept beside the solutions (393 MB at
    /// 400 × 400 benchmark curves, at the statics' peak).
    fn solve_parts(&self, parts: &[Option<&LoadSet>]) -> Result<Parts, FrameError> {
        let n = self.stiffness.n;
        let width = match parts.len() {
            0..=1 => 1,
            2 => 2,
            3..=4 => 4,
            _ => STATICS_BLOCK,
        };
        let rhs = |part: &Option<&LoadSet>| match part {
            Some(set) => self.assembly.load_vector(self.model, set),
            None => self.pull.clone(),
        };
        // Each part's right-hand side (the pretensions alone for `None`),
        // two at a time on the two cores, written into its place in the
        // rows, where it is solved.
        let mut x = vec![0.0; n * width];
        for (pair, two) in parts.chunks(2).enumerate() {
            let made: Vec<Vec<f64>> = two.par_iter().map(rhs).collect();
            for (k, v) in made.iter().enumerate() {
                for (row, &vi) in x.chunks_exact_mut(width).zip(v) {
                    row[2 * pair + k] = vi;
                }
            }
        }
        let solved_in_rows = match width {
            1 => self.factor.solve_rows::<1>(x.as_chunks_mut::<1>().0),
            2 => self.factor.solve_rows::<2>(x.as_chunks_mut::<2>().0),
            4 => self.factor.solve_rows::<4>(x.as_chunks_mut::<4>().0),
            _ => self
                .factor
                .solve_rows::<STATICS_BLOCK>(x.as_chunks_mut::<STATICS_BLOCK>().0),
        };
        // Each part refined on its own (and solved so, where the factor
        // does not solve rows); the spare places stay zero.
        for (c, part) in parts.iter().enumerate() {
            let mut one = Mat::from_fn(n, 1, |i, _| x[i * width + c]);
            if !solved_in_rows {
                self.factor.solve_in_place(one.as_mut());
            }
            let p = rhs(part);
            solve_refined_after(&self.factor, &self.stiffness, one.as_mut(), |_| {
                p.as_slice()
            })?;
            for (i, &v) in one.col(0).iter().enumerate() {
                x[i * width + c] = v;
            }
        }
        Ok(Parts { width, x })
    }

    /// The solution of `set`, the sum Σ factor·part (`weights`) over a
    /// superposition's solved `parts`, refined where the sum is not
    /// backward stable for the set's own right-hand side (a sum of
    /// nearly cancelling parts is not), made here.
    fn superpose(
        &self,
        parts: &Parts,
        set: &LoadSet,
        weights: &[(usize, f64)],
    ) -> Result<Vec<f64>, FrameError> {
        let n = self.stiffness.n;
        let mut x: Vec<f64> = parts
            .x
            .chunks_exact(parts.width)
            .map(|row| weights.iter().map(|&(c, f)| f * row[c]).sum())
            .collect();
        let p = self.rhs(set);
        solve_refined_after(
            &self.factor,
            &self.stiffness,
            MatMut::from_column_major_slice_mut(&mut x, n, 1),
            |_| p.as_slice(),
        )?;
        Ok(x)
    }

    /// The solutions of `loads` (at most [`STATICS_BLOCK`]), refined.
    /// More than half a block is solved where it lies, in the rows the
    /// triangular solves work on ([`Factor::solve_rows`]): a block made in
    /// columns and copied to rows and back for the solve took 786 MB more
    /// at 400 × 400 curves. Fewer load sets (a single one from the
    /// cables' iterations, the last of the 19 combinations) are solved in
    /// columns, as narrow as they are.
    fn solve_block(&self, loads: &[&LoadSet]) -> Result<Solved, FrameError> {
        let n = self.stiffness.n;
        let rhs = |set: &LoadSet| self.rhs(set);
        if 2 * loads.len() <= STATICS_BLOCK || !self.factor.solves_rows() {
            // The load sets side by side on the two cores, each written
            // into its own column.
            let mut x = Mat::<f64>::zeros(n, loads.len());
            let columns: Vec<_> = x.as_mut().col_iter_mut().collect();
            columns
                .into_par_iter()
                .zip(loads.par_iter())
                .for_each(|(mut column, set)| {
                    for (i, v) in rhs(set).into_iter().enumerate() {
                        column[i] = v;
                    }
                });
            // Each right-hand side remade for its backward error rather
            // than kept beside the solutions.
            solve_refined_in_place(&self.factor, &self.stiffness, &mut x, |c| rhs(loads[c]))?;
            return Ok(Solved::Columns(x));
        }
        // The load sets two at a time on the two cores, each written into
        // its place in the rows.
        let mut rows = vec![[0.0; STATICS_BLOCK]; n];
        for (pair, sets) in loads.chunks(2).enumerate() {
            let made: Vec<Vec<f64>> = sets.par_iter().map(|set| rhs(set)).collect();
            for (k, v) in made.iter().enumerate() {
                for (row, &vi) in rows.iter_mut().zip(v) {
                    row[2 * pair + k] = vi;
                }
            }
        }
        self.factor.solve_rows(&mut rows);
        // Each solution refined where it is not backward stable, its
        // right-hand side remade for its backward error, two at a time on
        // the two cores (a load vector is read and written in the
        // scattered order of the elements' unknowns: 15 ms at 100 × 100
        // curves, 0.3 s at 400 × 400, one at a time).
        for (pair, sets) in loads.chunks(2).enumerate() {
            let made: Vec<Vec<f64>> = sets.par_iter().map(|set| rhs(set)).collect();
            for (k, p) in made.iter().enumerate() {
                let c = 2 * pair + k;
                let mut x = Mat::from_fn(n, 1, |i, _| rows[i][c]);
                solve_refined_after(&self.factor, &self.stiffness, x.as_mut(), |_| p.as_slice())?;
                for (row, &v) in rows.iter_mut().zip(x.col(0).iter()) {
                    row[c] = v;
                }
            }
        }
        Ok(Solved::Rows(rows))
    }
}

/// Load sets solved on one factorisation at a time
/// ([`LinearFrame::solve_each`]): eight share a pass of the factor.
pub const STATICS_BLOCK: usize = 8;

/// Load sets solved on one [`LinearFrame`] ([`LinearFrame::solve_each`]):
/// as factored sums of their shared parts' solutions where they are sums
/// of fewer parts ([`Superposition`]: combinations of load cases), else
/// [`STATICS_BLOCK`] at a time as their results are asked for. Ask for
/// them in order and from one thread: then each block is solved once (a
/// block or the parts are solved under a lock, so a result asked for from
/// within that solve's own threads would wait on itself).
pub struct Statics<'a, 'm> {
    frame: &'a LinearFrame<'m>,
    loads: Vec<&'a LoadSet>,
    /// Where the load sets are sums of fewer shared parts: those parts.
    superposed: Option<Superposition<'a>>,
    /// The block last solved: its first load set, and its solutions.
    solved: Mutex<Option<(usize, Solved)>>,
    /// A superposition's parts, solved at the first result asked for.
    parts: Mutex<Option<Parts>>,
}

/// Load sets that are each a sum of factored parts shared between them
/// and nothing else (the combinations of a few load cases, [`super::loads::combine`]),
/// with fewer parts than sets, at most [`STATICS_BLOCK`]: the statics are
/// linear, so the parts are solved together, once (one pass of the
/// factor), and each set's solution is its factored sum of theirs, held
/// to the set's own backward error (for its own load vector, made then).
/// At 400 × 400 benchmark curves the 19 combinations of the pavilion's
/// four cases had taken 38 load vectors and 3 passes of the factor (each
/// set's load vector made for its solve and again for its backward
/// error); now one pass, and 27 load vectors on both cores (the cases'
/// for their solve and their refinement, each combination's for its
/// backward error), none of them kept.
#[derive(Debug)]
struct Superposition<'a> {
    /// The parts: load sets, and `None` for the taut cables' pretensions
    /// (in every set's right-hand side, factor 1).
    parts: Vec<Option<&'a LoadSet>>,
    /// Per load set: its (part, factor)s.
    weights: Vec<Vec<(usize, f64)>>,
}

impl<'a> Superposition<'a> {
    /// The superposition of `loads`, where they are sums of fewer parts
    /// (with the pretensions one more where `pull`); `None` where they are
    /// not.
    fn of(loads: &[&'a LoadSet], pull: bool) -> Option<Superposition<'a>> {
        let mut parts: Vec<Option<&'a LoadSet>> = Vec::new();
        if pull {
            parts.push(None);
        }
        let mut weights = Vec::with_capacity(loads.len());
        for set in loads {
            let own = !(set.nodes.is_empty() && set.beams.is_empty() && set.pressures.is_empty());
            if own || set.parts.is_empty() {
                return None;
            }
            let mut w: Vec<(usize, f64)> = Vec::with_capacity(set.parts.len() + 1);
            if pull {
                w.push((0, 1.0));
            }
            for (part, factor) in &set.parts {
                let at = match parts
                    .iter()
                    .position(|p| p.is_some_and(|p| std::ptr::eq(p, &**part)))
                {
                    Some(at) => at,
                    None => {
                        parts.push(Some(&**part));
                        parts.len() - 1
                    }
                };
                w.push((at, *factor));
            }
            weights.push(w);
        }
        (parts.len() < loads.len() && parts.len() <= STATICS_BLOCK)
            .then_some(Superposition { parts, weights })
    }
}

/// A superposition's parts solved: their solutions, row by row (`width`
/// values a row, the parts' then zeros).
#[derive(Debug)]
struct Parts {
    width: usize,
    x: Vec<f64>,
}

/// A block's solutions: row by row as the triangular solves work on them
/// (a block of more than half of [`STATICS_BLOCK`] load sets on a factor
/// that solves rows, [`Factor::solve_rows`]), else one column per load set.
enum Solved {
    Rows(Vec<[f64; STATICS_BLOCK]>),
    Columns(Mat<f64>),
}

impl Solved {
    /// The solution of the block's load set `c`.
    fn column(&self, c: usize) -> Vec<f64> {
        match self {
            Solved::Rows(rows) => rows.iter().map(|row| row[c]).collect(),
            Solved::Columns(x) => x.col(c).iter().copied().collect(),
        }
    }
}

impl Statics<'_, '_> {
    /// How many load sets.
    pub fn len(&self) -> usize {
        self.loads.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.loads.is_empty()
    }

    /// The whole result of load set `c`: displacements, reactions,
    /// section forces, cable forces. Its block is solved first, unless it
    /// is the one last solved.
    pub fn result(&self, c: usize) -> Result<StaticResult, FrameError> {
        Ok(self.result_with_cables(c)?.0)
    }

    /// The unknowns of load set `c`.
    fn solution(&self, c: usize) -> Result<Vec<f64>, FrameError> {
        if c >= self.loads.len() {
            return Err(FrameError::Invalid(format!(
                "load set {c} of {} asked for",
                self.loads.len()
            )));
        }
        if let Some(superposed) = &self.superposed {
            let mut held = self.parts.lock().unwrap_or_else(|e| e.into_inner());
            if held.is_none() {
                *held = Some(self.frame.solve_parts(&superposed.parts)?);
            }
            let parts = held.as_ref().expect("solved above");
            return self
                .frame
                .superpose(parts, self.loads[c], &superposed.weights[c]);
        }
        let first = c - c % STATICS_BLOCK;
        let mut solved = self.solved.lock().unwrap_or_else(|e| e.into_inner());
        if !matches!(&*solved, Some((f, _)) if *f == first) {
            // The last block's solutions go before the next's are made.
            *solved = None;
            let end = (first + STATICS_BLOCK).min(self.loads.len());
            *solved = Some((first, self.frame.solve_block(&self.loads[first..end])?));
        }
        let (_, x) = solved.as_ref().expect("solved above");
        Ok(x.column(c - first))
    }

    /// [`Statics::result`], and every cable's force were it taut.
    fn result_with_cables(&self, c: usize) -> Result<(StaticResult, Vec<f64>), FrameError> {
        let frame = self.frame;
        let x = self.solution(c)?;
        let would_be = frame.assembly.cable_forces(frame.model, &x);
        let forces: Vec<f64> = would_be
            .iter()
            .zip(&frame.taut)
            .map(|(&f, &t)| if t { f } else { 0.0 })
            .collect();
        let displacements = frame.assembly.expand(&x);
        drop(x);
        let result =
            frame
                .assembly
                .results_of(frame.model, self.loads[c], displacements, None, &forces);
        Ok((result, would_be))
    }
}

/// Solves k·x = p with the factor of k, refined ([`REFINEMENTS`] steps at
/// most, the residual recomputed from k) only while the solution's
/// componentwise backward error is above [`BACKWARD_STABLE`]. Stiff joints
/// beside slender strips leave a condition number near 1e10, but the
/// Cholesky solve is backward stable: on the shipped Enneper under the
/// pavilion's 30 solves ω was 6e-16 to 2.2e-14 and on the 100 × 100
/// benchmark grid 7e-16, so no step is taken there (the residual is at the
/// round-off of forming k·x, and a refinement step had left it so).
pub(crate) fn solve_refined(
    factor: &Factor,
    k: &SymSparse,
    p: &[f64],
) -> Result<Vec<f64>, FrameError> {
    let x = solve_refined_all(factor, k, &Mat::from_fn(p.len(), 1, |i, _| p[i]))?;
    Ok(x.col(0).iter().copied().collect())
}

/// [`solve_refined`] for every column of `p`.
pub(crate) fn solve_refined_all(
    factor: &Factor,
    k: &SymSparse,
    p: &Mat<f64>,
) -> Result<Mat<f64>, FrameError> {
    let mut x = p.clone();
    solve_refined_in_place(factor, k, &mut x, |c| p.col(c).iter().copied().collect())?;
    Ok(x)
}

/// [`solve_refined_all`] in place: `x` holds the right-hand sides and is
/// left holding the solutions, `rhs(c)` making column c again for its
/// backward error. Each column is refined on its own, while its own error
/// is above [`BACKWARD_STABLE`].
pub(crate) fn solve_refined_in_place(
    factor: &Factor,
    k: &SymSparse,
    x: &mut Mat<f64>,
    rhs: impl Fn(usize) -> Vec<f64>,
) -> Result<(), FrameError> {
    factor.solve_in_place(x.as_mut());
    solve_refined_after(factor, k, x.as_mut(), rhs)
}

/// [`solve_refined_in_place`] once `x` holds the plain solutions.
fn solve_refined_after<P: AsRef<[f64]>>(
    factor: &Factor,
    k: &SymSparse,
    mut x: MatMut<'_, f64>,
    rhs: impl Fn(usize) -> P,
) -> Result<(), FrameError> {
    for c in 0..x.ncols() {
        let p = rhs(c);
        for _ in 0..REFINEMENTS {
            let column = x.as_ref().col(c);
            let (_, residual) = backward_error(k, column_slice(column), p.as_ref());
            let Some(mut r) = residual else {
                break;
            };
            factor.solve_in_place(r.as_mut());
            let mut column = x.as_mut().subcols_mut(c, 1);
            column += r;
        }
    }
    if (0..x.ncols()).any(|c| x.as_ref().col(c).iter().any(|v| !v.is_finite())) {
        return Err(FrameError::Unstable(
            "a solve gave non-finite displacements".into(),
        ));
    }
    Ok(())
}

/// A column of a matrix as a slice (a [`Mat`]'s columns are contiguous).
fn column_slice(column: faer::ColRef<'_, f64>) -> &[f64] {
    column
        .try_as_col_major()
        .expect("a matrix's column is contiguous")
        .as_slice()
}

/// Steps of iterative refinement at most ([`solve_refined_all`]).
const REFINEMENTS: usize = 2;

/// The componentwise backward error below which a solution is not
/// refined: x solves (K + ΔK)·x = p + Δp exactly with |ΔK| ≤ ω·|K| and
/// |Δp| ≤ ω·|p|, so a refinement step in the same precision has nothing
/// left to take out.
const BACKWARD_STABLE: f64 = 1e-13;

/// The componentwise backward error ω = max_i |r_i| / (|K|·|x| + |p|)_i
/// (Oettli and Prager) of the solution x of K·x = p, with r = p − K·x,
/// K read once for K·x and |K|·|x|; rows where the scale is zero have no
/// error to show. The residual r itself only when ω exceeds
/// [`BACKWARD_STABLE`] (a refinement step needs it).
fn backward_error(k: &SymSparse, x: &[f64], p: &[f64]) -> (f64, Option<Mat<f64>>) {
    let sums = k.mul_column_and_abs(x);
    let mut omega = 0.0f64;
    for (&[kx, scale], &pi) in sums.iter().zip(p) {
        let s = scale + pi.abs();
        if s > 0.0 {
            omega = omega.max((pi - kx).abs() / s);
        }
    }
    let residual =
        (omega > BACKWARD_STABLE).then(|| Mat::from_fn(p.len(), 1, |i, _| p[i] - sums[i][0]));
    (omega, residual)
}

/// a + s·b, on a's pattern when it holds b's (one model's matrices).
pub(crate) fn add(a: &SymSparse, b: &SymSparse, s: f64) -> SymSparse {
    let mut sum = if a.holds(b) {
        let mut sum = a.clone();
        accumulate(&mut sum, b, s);
        sum
    } else if b.holds(a) {
        let mut sum = b.clone();
        sum.values.iter_mut().for_each(|v| *v *= s);
        accumulate(&mut sum, a, 1.0);
        sum
    } else {
        let t: Vec<(usize, usize, f64)> = a
            .entries()
            .chain(b.entries().map(|(i, j, v)| (i, j, s * v)))
            .collect();
        SymSparse::from_triplets(a.n, t)
    };
    sum.scaling = a.scaling.clone();
    sum
}

/// target += s·source, where target's pattern holds source's.
fn accumulate(target: &mut SymSparse, source: &SymSparse, s: f64) {
    if Arc::ptr_eq(&target.pattern, &source.pattern) {
        target
            .values
            .iter_mut()
            .zip(&source.values)
            .for_each(|(x, y)| *x += s * y);
        return;
    }
    let (pa, pb) = (&*target.pattern, &*source.pattern);
    for j in 0..target.n {
        let mut rows = pa.column(j).zip(pa.start[j]..).peekable();
        for (want, m) in pb.column(j).zip(pb.start[j]..) {
            while rows.next_if(|&(i, _)| i < want).is_some() {}
            let (_, k) = rows
                .peek()
                .copied()
                .expect("the target's pattern holds the source's");
            target.values[k] += s * source.values[m];
        }
    }
}

/// The linear static solution of `model` under `loads` (one
/// factorisation; use [`LinearFrame`] for several load sets; a model with
/// tension-only cables is solved by `tension::solve_tension_only`).
pub fn solve_static(model: &FrameModel, loads: &LoadSet) -> Result<StaticResult, FrameError> {
    LinearFrame::new(model)?.solve(loads)
}

/// Per element, the axial force of a static result (load only).
pub fn axial_forces(result: &StaticResult) -> Vec<f64> {
    result
        .beam_forces
        .iter()
        .map(|f| 0.5 * (f.start.axial_n + f.end.axial_n))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_elements_end_forces_term_by_term_are_its_stiffness_times_its_displacements() {
        // A doubled-strip-like section, unequal in every stiffness.
        let section = Section {
            e_mpa: 210_000.0,
            g_mpa: 81_000.0,
            area_mm2: 120.0,
            i_y_mm4: 160_000.0,
            i_z_mm4: 90.0,
            j_mm4: 340.0,
        };
        let u: [f64; 12] = std::array::from_fn(|i| ((i * 5 + 1) % 7) as f64 * 0.013 - 0.04);
        for l in [37.5, 412.0] {
            let k = local_stiffness(&section, l);
            let by_matrix: [f64; 12] =
                std::array::from_fn(|a| (0..12).map(|c| k[a][c] * u[c]).sum());
            let term_by_term = local_stiffness_times(&section, l, &u);
            for a in 0..12 {
                let scale = by_matrix.iter().fold(1.0f64, |m, v| m.max(v.abs()));
                assert!(
                    (term_by_term[a] - by_matrix[a]).abs() <= 1e-12 * scale,
                    "L = {l}: force {a}: {} against {}",
                    term_by_term[a],
                    by_matrix[a]
                );
            }
        }
    }

    #[test]
    fn rigid_offsets_in_closed_form_are_the_offset_matrix_products() {
        // H·u and Hᵀ·f against the 12 × 12 matrix of u_end = u_node +
        // θ_node × r: one end offset, both, and none.
        let u: [f64; 12] = std::array::from_fn(|i| ((i * 7 + 3) % 11) as f64 - 4.5);
        let f: [f64; 12] = std::array::from_fn(|i| ((i * 5 + 2) % 13) as f64 * 0.7 - 3.0);
        for offsets in [
            [DVec3::new(12.0, -30.0, 4.5), DVec3::ZERO],
            [DVec3::new(-2.0, 0.5, 80.0), DVec3::new(7.0, 3.0, -1.0)],
            [DVec3::ZERO; 2],
        ] {
            let by_matrix = |transposed: bool, v: &[f64; 12]| -> [f64; 12] {
                match offset_matrix(&offsets) {
                    None => *v,
                    Some(h) => std::array::from_fn(|i| {
                        (0..12)
                            .map(|j| if transposed { h[j][i] } else { h[i][j] } * v[j])
                            .sum()
                    }),
                }
            };
            let (hu, htf) = (apply_h(&offsets, u), apply_ht(&offsets, f));
            let (hu_m, htf_m) = (by_matrix(false, &u), by_matrix(true, &f));
            for i in 0..12 {
                assert!((hu[i] - hu_m[i]).abs() < 1e-12, "H·u[{i}]");
                assert!((htf[i] - htf_m[i]).abs() < 1e-12, "Hᵀ·f[{i}]");
            }
            // The same work either side of the offsets: f·(H·u) = (Hᵀ·f)·u.
            let (a, b): (f64, f64) = (
                (0..12).map(|i| f[i] * hu[i]).sum(),
                (0..12).map(|i| htf[i] * u[i]).sum(),
            );
            assert!((a - b).abs() < 1e-9 * a.abs().max(1.0));
        }
    }

    /// A symmetric positive definite matrix on an m × m grid of nodes
    /// with `per` unknowns each, every node coupled to its four
    /// neighbours by a dense block (a frame's pattern, in small).
    fn grid_matrix(m: usize, per: usize) -> SymSparse {
        let n = m * m * per;
        let mut t = Vec::new();
        let mut seed: u64 = 0x1234_5678_9abc_def1;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for node in 0..m * m {
            let (r, c) = (node / m, node % m);
            let mut neighbours = vec![];
            if c + 1 < m {
                neighbours.push(node + 1);
            }
            if r + 1 < m {
                neighbours.push(node + m);
            }
            for other in neighbours {
                for a in 0..per {
                    for b in 0..per {
                        let (i, j) = (other * per + a, node * per + b);
                        t.push((i.max(j), i.min(j), 0.1 * next()));
                    }
                }
            }
            for a in 0..per {
                for b in 0..=a {
                    let v = if a == b { 10.0 } else { 0.1 * next() };
                    t.push((node * per + a, node * per + b, v));
                }
            }
        }
        SymSparse::from_triplets(n, t)
    }

    /// A small space frame with every kind of entry the plan places: four
    /// beams round a square (one with rigid end offsets), a fifth to a
    /// node beside a corner, a link tying that node to the corner, a
    /// fixed support, an inclined roller, and pressures on two beams.
    fn plan_model() -> (FrameModel, LoadSet) {
        use super::super::model::{Link, PressureLoad, Support};
        let section = Section::steel_strip();
        let nodes_mm = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1000.0, 0.0, 100.0),
            DVec3::new(1000.0, 1000.0, 0.0),
            DVec3::new(0.0, 1000.0, 50.0),
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(-500.0, -300.0, 0.0),
        ];
        let beam = |a: usize, b: usize, offsets_mm: [DVec3; 2]| Beam {
            nodes: [a, b],
            section: 0,
            z_axis: DVec3::Z,
            initial: InitialForces::default(),
            offsets_mm,
        };
        let none = [DVec3::ZERO; 2];
        let model = FrameModel {
            nodes_mm,
            sections: vec![section],
            beams: vec![
                beam(0, 1, none),
                beam(
                    1,
                    2,
                    [DVec3::new(0.0, 20.0, 5.0), DVec3::new(-10.0, 0.0, 5.0)],
                ),
                beam(2, 3, none),
                beam(3, 0, none),
                beam(4, 5, none),
                // A second element between nodes 1 and 2, listed the
                // other way round.
                beam(2, 1, none),
            ],
            links: vec![Link {
                nodes: [0, 4],
                frame: DMat3::IDENTITY,
                translation_n_per_mm: [1e5, 2e5, 3e5],
                rotation_nmm_per_rad: [1e7, 0.0, 5e6],
            }],
            cables: vec![],
            supports: vec![
                Support {
                    node: 5,
                    fixed: [true; 6],
                    along: None,
                },
                Support {
                    node: 2,
                    fixed: [false; 6],
                    along: Some(DVec3::new(1.0, 1.0, 0.0)),
                },
                // Three of node 3's six held.
                Support {
                    node: 3,
                    fixed: [true, false, true, false, false, true],
                    along: None,
                },
            ],
        };
        let loads = LoadSet {
            name: "pressure".into(),
            pressures: vec![
                PressureLoad {
                    beam: 1,
                    n_per_mm: 0.3,
                },
                PressureLoad {
                    beam: 2,
                    n_per_mm: -0.2,
                },
            ],
            ..Default::default()
        };
        (model, loads)
    }

    /// The full matrix (both triangles) of a lower triangle.
    fn dense(a: &SymSparse) -> Vec<Vec<f64>> {
        let mut m = vec![vec![0.0; a.n]; a.n];
        for (i, j, v) in a.entries() {
            m[i][j] += v;
            if i != j {
                m[j][i] += v;
            }
        }
        m
    }

    /// Each element's whole 12 × 12 block added into a full matrix by its
    /// dofs, both triangles (the plain definition of assembly).
    fn add_block(m: &mut [Vec<f64>], d: &[usize; 12], k: &Mat12) {
        for a in 0..12 {
            for b in 0..12 {
                if d[a] != NONE && d[b] != NONE {
                    m[d[a]][d[b]] += k[a][b];
                }
            }
        }
    }

    /// Matrices added at the plan's places equal the full blocks summed
    /// entry by entry: the stiffness (beams with and without offsets, a
    /// link, an inclined support's penalty, a node held in every
    /// direction and one in three, two beams between the same nodes) and
    /// the geometric stiffness (one beam without axial force, pressures);
    /// both on one pattern, the sorted triplets' of the same blocks.
    #[test]
    fn matrices_added_at_their_places_equal_the_summed_blocks() {
        let (model, loads) = plan_model();
        let assembly = Assembly::new(&model, &model.nodes_mm).unwrap();
        let n = assembly.dofs.free;
        let with_offsets = |i: usize, k: Mat12| match &offset_matrix(&model.beams[i].offsets_mm) {
            None => k,
            Some(h) => sandwich(h, &k),
        };
        // The stiffness.
        let mut want = vec![vec![0.0; n]; n];
        for (i, b) in model.beams.iter().enumerate() {
            let f = &assembly.frames[i];
            let k = to_global(
                &local_stiffness(&model.sections[0], f.length_mm),
                &f.rotation,
            );
            add_block(&mut want, &assembly.element_dofs(b), &with_offsets(i, k));
        }
        let l = &model.links[0];
        let d = assembly.node_dofs(l.nodes);
        for (p, (kt, kr)) in l
            .translation_n_per_mm
            .iter()
            .zip(&l.rotation_nmm_per_rad)
            .enumerate()
        {
            for (offset, k) in [(0, kt), (3, kr)] {
                let (i, j) = (d[offset + p], d[6 + offset + p]);
                want[i][i] += k;
                want[j][j] += k;
                want[i][j] -= k;
                want[j][i] -= k;
            }
        }
        let unpenalised = want.clone();
        let roller: Vec<usize> = (0..3).map(|p| assembly.dofs.index[2 * 6 + p]).collect();
        let own = roller.iter().map(|&d| want[d][d]).fold(0.0, f64::max);
        let axis = DVec3::new(1.0, 1.0, 0.0).normalize();
        for p in 0..3 {
            for q in 0..3 {
                want[roller[p]][roller[q]] += PENALTY * own * axis[p] * axis[q];
            }
        }
        let k = assembly.stiffness(&model);
        let got = dense(&k);
        let scale = own * PENALTY;
        for i in 0..n {
            for j in 0..n {
                assert!(
                    (got[i][j] - want[i][j]).abs() <= 1e-12 * scale,
                    "K[{i}][{j}] = {} against {}",
                    got[i][j],
                    want[i][j]
                );
            }
        }
        let diagonal: Vec<f64> = (0..n).map(|i| unpenalised[i][i]).collect();
        let scaling = k.scaling.clone().unwrap();
        for (g, w) in scaling.iter().zip(&diagonal) {
            assert!((g - w).abs() <= 1e-9 * w.abs().max(1.0));
        }
        // The geometric stiffness: beam 3 carries no force.
        let axial = [-1000.0, 500.0, -250.0, 0.0, 2000.0, 700.0];
        let mut want = vec![vec![0.0; n]; n];
        for (i, b) in model.beams.iter().enumerate() {
            let f = &assembly.frames[i];
            let g = local_geometric_terms(
                &model.sections[0],
                f.length_mm,
                axial[i],
                GeometricTerms::Full,
            );
            add_block(
                &mut want,
                &assembly.element_dofs(b),
                &with_offsets(i, to_global(&g, &f.rotation)),
            );
        }
        let mut pressures_only = loads.clone();
        let kg = assembly.geometric(&model, &axial, Some(&loads));
        pressures_only
            .pressures
            .iter_mut()
            .for_each(|p| p.n_per_mm *= 2.0);
        let kg2 = assembly.geometric(&model, &axial, Some(&pressures_only));
        // The pressures' share doubles with them: kg2 − kg is that share.
        let (got, got2) = (dense(&kg), dense(&kg2));
        let largest = want.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        for i in 0..n {
            for j in 0..n {
                let share = got2[i][j] - got[i][j];
                assert!(
                    (got[i][j] - share - want[i][j]).abs() <= 1e-12 * largest,
                    "K_G[{i}][{j}] = {} − {share} against {}",
                    got[i][j],
                    want[i][j]
                );
            }
        }
        assert!(
            got2.iter().zip(&got).any(|(a, b)| a != b),
            "the pressures add nothing"
        );
        // One pattern, shared: the triplets' of the same blocks.
        assert!(Arc::ptr_eq(&k.pattern, &kg.pattern));
        let mut t = Vec::new();
        for b in &model.beams {
            assembly.scatter(&mut t, &assembly.element_dofs(b), &[[1.0; 12]; 12]);
        }
        assembly.scatter(&mut t, &assembly.node_dofs(l.nodes), &[[1.0; 12]; 12]);
        let triplets = SymSparse::from_triplets(n, t);
        assert_eq!(
            (&triplets.pattern.start, triplets.pattern.rows()),
            (&k.pattern.start, k.pattern.rows())
        );
        assert!(k.pattern.in_order, "numbered in the nodes' order");
    }

    #[test]
    fn triplets_merge_into_sorted_columns() {
        let t = vec![
            (2, 0, 1.0),
            (0, 0, 4.0),
            (2, 0, 0.5),
            (1, 1, 3.0),
            (2, 2, 5.0),
            (2, 1, -1.0),
        ];
        let a = SymSparse::from_triplets(3, t);
        assert_eq!(a.pattern.start, vec![0, 2, 4, 5]);
        assert_eq!(*a.pattern.rows(), [0, 2, 1, 2, 2]);
        assert_eq!(a.values, vec![4.0, 1.5, 3.0, -1.0, 5.0]);
        // y = A·x against the dense product by hand.
        let y = a.mul_block(Mat::from_fn(3, 1, |i, _| (i + 1) as f64).as_ref());
        let y: Vec<f64> = y.col(0).iter().copied().collect();
        assert_eq!(y, vec![4.0 + 4.5, 6.0 - 3.0, 1.5 - 2.0 + 15.0]);
        assert_eq!(a.diagonal(), vec![4.0, 3.0, 5.0]);
    }

    /// A stiffness's rows kept as its nodes' runs read as the same rows
    /// listed one by one: the same entries (as sorted triplets of its
    /// blocks would give, in `matrices_added_at_their_places_equal_the_summed_blocks`),
    /// places, diagonal, and the same products to the bit, on one thread
    /// and on two (a grillage above [`PARALLEL_ROWS`] unknowns).
    #[test]
    fn rows_as_runs_read_as_the_same_rows_listed() {
        for m in [6, 60] {
            let model = grillage(m);
            let assembly = Assembly::new(&model, &model.nodes_mm).unwrap();
            let runs = assembly.stiffness(&model);
            assert!(matches!(runs.pattern.rows, Rows::Blocks(_)));
            let listed = SymSparse {
                pattern: Arc::new(Pattern::listed(
                    runs.pattern.start.clone(),
                    runs.pattern.rows().into_owned(),
                    runs.pattern.in_order,
                )),
                ..runs.clone()
            };
            assert_eq!(runs.n >= PARALLEL_ROWS, m == 60);
            let n = runs.n;
            // Every column's rows ascending, from its diagonal on, and as
            // many as its entries.
            for j in 0..n {
                let rows: Vec<usize> = runs.pattern.column(j).collect();
                assert_eq!(rows.first(), Some(&j));
                assert!(rows.windows(2).all(|w| w[0] < w[1]));
                assert_eq!(
                    rows.len(),
                    runs.pattern.start[j + 1] - runs.pattern.start[j]
                );
                let mut visited = Vec::new();
                runs.pattern
                    .for_each_run_in(j, |k, r| visited.extend(r.zip(k..)));
                let want: Vec<(usize, usize)> =
                    rows.iter().copied().zip(runs.pattern.start[j]..).collect();
                assert_eq!(visited, want);
            }
            assert!(runs.entries().eq(listed.entries()));
            assert_eq!(runs.diagonal(), listed.diagonal());
            for (i, j) in [(0, 0), (7, 1), (n - 1, n - 1), (n / 2 + 3, n / 2)] {
                assert_eq!(runs.place(i, j), listed.place(i, j));
            }
            let x = Mat::from_fn(n, 3, |i, c| ((i * 7 + c * 13) % 17) as f64 - 8.0);
            assert!(runs.mul_block(x.as_ref()) == listed.mul_block(x.as_ref()));
            let column = column_slice(x.col(0));
            assert_eq!(
                runs.mul_column_and_abs(column),
                listed.mul_column_and_abs(column)
            );
        }
    }

    /// The product in column groups of 8, 4, 2 and 1, on one thread and
    /// split between two, against the dense product summed by hand from
    /// the full (both triangles) matrix.
    #[test]
    fn products_of_any_number_of_columns_match_the_dense_product() {
        for n in [7, PARALLEL_ROWS + 5] {
            // A banded symmetric matrix with a missing diagonal entry.
            let mut t = Vec::new();
            for j in 0..n {
                if j != 3 {
                    t.push((j, j, 4.0 + (j % 5) as f64));
                }
                for d in [1, 3] {
                    if j + d < n {
                        t.push((j + d, j, -1.0 + 0.1 * ((j * d) % 7) as f64));
                    }
                }
            }
            let a = SymSparse::from_triplets(n, t);
            let full: Vec<Vec<(usize, f64)>> = {
                let mut rows = vec![Vec::new(); n];
                for (i, j, v) in a.entries() {
                    rows[i].push((j, v));
                    if i != j {
                        rows[j].push((i, v));
                    }
                }
                rows
            };
            for p in [1, 2, 3, 5, 8, 11, 19] {
                let x = Mat::from_fn(n, p, |i, c| ((i * 7 + c * 13) % 17) as f64 - 8.0);
                let y = a.mul_block(x.as_ref());
                let (y2, y_abs): (Vec<f64>, Vec<f64>) = (0..p)
                    .flat_map(|c| a.mul_column_and_abs(column_slice(x.col(c))))
                    .map(|[v, a]| (v, a))
                    .unzip();
                let (y2, y_abs) = (
                    Mat::from_fn(n, p, |i, c| y2[c * n + i]),
                    Mat::from_fn(n, p, |i, c| y_abs[c * n + i]),
                );
                for (i, row) in full.iter().enumerate() {
                    for c in 0..p {
                        let want: f64 = row.iter().map(|&(j, v)| v * x[(j, c)]).sum();
                        let want_abs: f64 = row.iter().map(|&(j, v)| (v * x[(j, c)]).abs()).sum();
                        for (got, want) in [
                            (y[(i, c)], want),
                            (y2[(i, c)], want),
                            (y_abs[(i, c)], want_abs),
                        ] {
                            assert!(
                                (got - want).abs() <= 1e-12 * want.abs().max(1.0),
                                "n {n}, {p} columns: row {i}, column {c}: {got} against {want}"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn sums_keep_the_larger_pattern_and_add_by_entry() {
        let a =
            SymSparse::from_triplets(3, vec![(0, 0, 1.0), (1, 0, 2.0), (1, 1, 3.0), (2, 2, 4.0)]);
        let b = SymSparse::from_triplets(3, vec![(1, 0, 10.0), (2, 2, 20.0)]);
        let c = SymSparse::from_triplets(3, vec![(2, 0, 7.0)]);
        let ab = add(&a, &b, 0.5);
        assert!(Arc::ptr_eq(&ab.pattern, &a.pattern));
        assert_eq!(ab.values, vec![1.0, 7.0, 3.0, 14.0]);
        let ba = add(&b, &a, 2.0);
        assert!(Arc::ptr_eq(&ba.pattern, &a.pattern));
        assert_eq!(ba.values, vec![2.0, 14.0, 6.0, 28.0]);
        let ac = add(&a, &c, 1.0);
        assert_eq!(
            ac.entries().collect::<Vec<_>>(),
            vec![
                (0, 0, 1.0),
                (1, 0, 2.0),
                (2, 0, 7.0),
                (1, 1, 3.0),
                (2, 2, 4.0)
            ]
        );
        // Zero factors keep their place (a pattern is structural).
        let a0 = add(&a, &b, 0.0);
        assert_eq!(a0.values, a.values);
    }

    #[test]
    fn supernodal_solves_any_number_of_right_hand_sides() {
        let k = grid_matrix(24, 6);
        let dofs = all_free(k.n);
        let factor = factorise_definite(&k, &dofs).unwrap().unwrap();
        assert!(
            factor.symbolic.layout().is_some(),
            "the test is of the supernodal solve"
        );
        for p in [1, 2, 3, 5, 6, 7, 8, 11, 19] {
            let b = Mat::<f64>::from_fn(k.n, p, |i, j| ((i * 7 + j * 13) % 17) as f64 - 8.0);
            let mut x = b.clone();
            factor.solve_in_place(x.as_mut());
            let r = &b - k.mul_block(x.as_ref());
            for c in 0..p {
                let worst = r.col(c).iter().fold(0.0f64, |m, v| m.max(v.abs()));
                assert!(worst < 1e-10, "{p} sides, column {c}: residual {worst:e}");
            }
        }
        // The pattern's symbolic factorisation is kept: a second matrix of
        // the same pattern reuses it.
        let shifted = add(&k, &k, 0.5);
        let again = factorise_definite(&shifted, &dofs).unwrap().unwrap();
        assert!(Arc::ptr_eq(&again.symbolic, &factor.symbolic));
    }

    /// The supernodes are put in a postorder (each subtree a range) at no
    /// cost in fill, the schedule deals the subtrees to two threads in
    /// near-equal shares, and the shared solve is the one-thread solve to
    /// round-off, bit for bit the same on one thread as on two.
    #[test]
    fn triangular_solves_share_the_factors_subtrees() {
        let k = grid_matrix(40, 6);
        let dofs = all_free(k.n);
        let factor = factorise_definite(&k, &dofs).unwrap().unwrap();
        let Some(supernodal) = factor.symbolic.layout() else {
            panic!("the test is of the supernodal solve");
        };
        assert_eq!(triangular::postorder(supernodal), None, "postordered");
        // A grid of 24 × 25 nodes cut by its middle column of nodes: the
        // two halves' nodes interleaved row by row, then the cut. The
        // halves are two subtrees of the elimination tree, their
        // supernodes interleaved, not a postorder; made one, with the
        // same fill.
        let (m, per) = (24, 6);
        let grid = grid_matrix(m, per);
        let mut order: Vec<usize> = Vec::new();
        let (left, right): (Vec<usize>, Vec<usize>) = (0..m * m)
            .filter(|q| q % m != m / 2)
            .partition(|q| q % m < m / 2);
        for pair in left.iter().zip(&right) {
            order.extend([*pair.0, *pair.1]);
        }
        order.extend(left.iter().skip(right.len()));
        order.extend(right.iter().skip(left.len()));
        order.extend((0..m).map(|r| r * m + m / 2));
        let forward: Vec<usize> = order
            .iter()
            .flat_map(|q| (0..per).map(move |a| q * per + a))
            .collect();
        let mut inverse = vec![0; forward.len()];
        for (i, &f) in forward.iter().enumerate() {
            inverse[f] = i;
        }
        let given = factorize_symbolic_cholesky(
            grid.to_faer().unwrap().symbolic(),
            Side::Lower,
            SymmetricOrdering::Custom(PermRef::new_checked(&forward, &inverse, grid.n)),
            Default::default(),
        )
        .unwrap();
        let supernodes = |c: &SymbolicCholesky<usize>| match c.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => {
                triangular::postorder(&Layout::of_faer(s).expect("few unknowns"))
            }
            _ => panic!("a supernodal factor"),
        };
        assert!(
            supernodes(&given).is_some(),
            "the given order is not a postorder"
        );
        let made = postordered(grid.to_faer().unwrap().symbolic(), given).unwrap();
        assert_eq!(supernodes(&made), None, "postordered");
        // The factor's entries in either order, one by one.
        let entries = |perm: PermRef<'_, usize>| {
            factorize_symbolic_cholesky(
                grid.to_faer().unwrap().symbolic(),
                Side::Lower,
                SymmetricOrdering::Custom(perm),
                faer::sparse::linalg::cholesky::CholeskySymbolicParams {
                    supernodal_flop_ratio_threshold:
                        faer::sparse::linalg::SupernodalThreshold::FORCE_SIMPLICIAL,
                    ..Default::default()
                },
            )
            .unwrap()
            .len_val()
        };
        assert_eq!(
            entries(made.perm().unwrap()),
            entries(PermRef::new_checked(&forward, &inverse, grid.n))
        );

        let schedule = Schedule::of(supernodal).expect("a schedule");
        let shares = schedule.shares(supernodal);
        assert!(
            shares.iter().all(|&s| s > 0.35) && (shares[0] - shares[1]).abs() < 0.05,
            "shares {shares:?}"
        );
        let b: Vec<[f64; 2]> = (0..k.n)
            .map(|i| [((i * 7) % 17) as f64 - 8.0, ((i * 5) % 13) as f64 - 6.0])
            .collect();
        let mut serial = b.clone();
        triangular::solve_serial::<2>(supernodal, &factor.values, &mut serial);
        let mut shared = b.clone();
        triangular::solve_scheduled::<2>(supernodal, &factor.values, &schedule, &mut shared);
        let scale = serial.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        for (i, (a, s)) in serial.iter().zip(&shared).enumerate() {
            for c in 0..2 {
                assert!(
                    (a[c] - s[c]).abs() <= 1e-12 * scale,
                    "row {i}, side {c}: {} against {}",
                    s[c],
                    a[c]
                );
            }
        }
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let mut alone = b.clone();
        one.install(|| {
            triangular::solve_scheduled::<2>(supernodal, &factor.values, &schedule, &mut alone)
        });
        assert!(alone == shared, "the same bits on one thread");
    }

    /// The frame's unknowns ordered on its nodes: the factor's
    /// supernodes come out in a postorder (no second symbolic
    /// factorisation), with about the fill of the minimum degree ordering
    /// of the unknowns themselves.
    #[test]
    fn ordered_on_the_nodes_the_factor_is_postordered_with_the_fill_of_the_unknowns() {
        let k = grid_matrix(40, 6);
        let dofs = all_free(k.n);
        let by_nodes = dofs.symbolic_of(&k).unwrap();
        let Some(supernodal) = by_nodes.layout() else {
            panic!("a supernodal factor");
        };
        assert_eq!(triangular::postorder(supernodal), None, "postordered");
        let of_unknowns = factorize_symbolic_cholesky(
            k.to_faer().unwrap().symbolic(),
            Side::Lower,
            SymmetricOrdering::Amd,
            Default::default(),
        )
        .unwrap();
        let (ours, theirs) = (by_nodes.len_val(), of_unknowns.len_val());
        assert!(
            (ours as f64) < 1.05 * theirs as f64,
            "{ours} entries against {theirs}"
        );
        // And it solves: K·x = b to round-off.
        let factor = factorise_definite(&k, &dofs).unwrap().unwrap();
        let b = Mat::<f64>::from_fn(k.n, 1, |i, _| ((i * 7) % 17) as f64 - 8.0);
        let mut x = b.clone();
        factor.solve_in_place(x.as_mut());
        let r = k.mul_block(x.as_ref()) - &b;
        let scale = b.norm_max();
        assert!(r.norm_max() <= 1e-10 * scale, "residual {}", r.norm_max());
    }

    /// An m × m grillage of steel strips on a 500 mm grid in a plane,
    /// fixed at its four corners (corner 0 first).
    fn grillage(m: usize) -> FrameModel {
        let beam = |a: usize, b: usize| Beam {
            nodes: [a, b],
            section: 0,
            z_axis: DVec3::Z,
            initial: InitialForces::default(),
            offsets_mm: [DVec3::ZERO; 2],
        };
        let mut beams = Vec::new();
        for y in 0..m {
            for x in 0..m {
                if x + 1 < m {
                    beams.push(beam(y * m + x, y * m + x + 1));
                }
                if y + 1 < m {
                    beams.push(beam(y * m + x, (y + 1) * m + x));
                }
            }
        }
        FrameModel {
            nodes_mm: (0..m * m)
                .map(|c| DVec3::new((c % m) as f64 * 500.0, (c / m) as f64 * 500.0, 0.0))
                .collect(),
            sections: vec![Section::steel_strip()],
            beams,
            supports: [0, m - 1, m * (m - 1), m * m - 1]
                .iter()
                .map(|&node| super::super::model::Support {
                    node,
                    fixed: [true; 6],
                    along: None,
                })
                .collect(),
            ..Default::default()
        }
    }

    /// A model's unknowns are numbered in its nodes' fill-reducing order
    /// from the start, so its stiffness is factorised as it stands: no
    /// order handed to faer (which would first make a permuted copy of
    /// every entry), its structure made on the nodes (a node without
    /// unknowns, one with three) holding every entry of the matrix, the
    /// fill of ordering the same matrix numbered node by node in the
    /// model's own order, the supernodes postordered, and it solves.
    #[test]
    fn a_models_stiffness_is_assembled_in_its_elimination_order() {
        // A 30 × 30 grillage: three corners fixed (no unknowns), one
        // pinned (three).
        let mut model = grillage(30);
        model.supports[0].fixed = [true, true, true, false, false, false];
        let assembly = Assembly::new(&model, &model.nodes_mm).unwrap();
        let k = assembly.stiffness(&model);
        assert!(k.pattern.in_order);
        let symbolic = assembly.dofs.symbolic_of(&k).unwrap();
        assert!(symbolic.perm().is_none(), "factorised as it stands");
        let Some(supernodal) = symbolic.layout() else {
            panic!("a supernodal factor");
        };
        assert_eq!(triangular::postorder(supernodal), None, "postordered");
        // The structure, made on the nodes, holds every entry of the
        // matrix: in its column's diagonal block or among its rows below.
        let (begin, end) = (supernodal.supernode_begin(), supernodal.supernode_end());
        let row_start = supernodal.col_ptr_for_row_idx();
        let mut owner = vec![0; k.n];
        for sn in 0..supernodal.n_supernodes() {
            owner[begin[sn]..end[sn]].fill(sn);
        }
        assert_eq!(end.last(), Some(&k.n), "every unknown in a supernode");
        for (i, j, _) in k.entries() {
            let sn = owner[j];
            let below = &supernodal.row_idx()[row_start[sn]..row_start[sn + 1]];
            assert!(
                i < end[sn] || below.binary_search(&(i as u32)).is_ok(),
                "entry ({i}, {j}) outside the factor's structure"
            );
        }
        // The same matrix with its unknowns numbered node by node in the
        // model's order, ordered on its own node graph.
        let mut natural = vec![NONE; k.n];
        let mut index = vec![NONE; assembly.dofs.index.len()];
        let mut free = 0;
        for (g, &u) in assembly.dofs.index.iter().enumerate() {
            if u != NONE {
                (natural[u], index[g]) = (free, free);
                free += 1;
            }
        }
        let t = k
            .entries()
            .map(|(i, j, v)| {
                let (a, b) = (natural[i], natural[j]);
                (a.max(b), a.min(b), v)
            })
            .collect();
        let renumbered = SymSparse::from_triplets(k.n, t);
        let node_by_node = Dofs {
            index,
            free,
            in_order: false,
            symbolic: Arc::default(),
        };
        let ordered = node_by_node.symbolic_of(&renumbered).unwrap();
        assert!(ordered.perm().is_some());
        // The same elimination; the supernodes, amalgamated on the nodes
        // with fewer zeros than faer's defaults allow on the unknowns
        // ([`NODE_RELAX`]), hold no fewer entries than the factor's own
        // (faer's with no amalgamation, in the same order) and no more
        // than faer's.
        let (forward, inverse) = ordered.perm().unwrap().arrays();
        let faer = renumbered.to_faer().unwrap();
        let unamalgamated = factorize_symbolic_cholesky(
            faer.symbolic(),
            Side::Lower,
            SymmetricOrdering::Custom(PermRef::new_checked(forward, inverse, k.n)),
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                supernodal_params: SymbolicSupernodalParams { relax: Some(&[]) },
                ..Default::default()
            },
        )
        .unwrap();
        let (ours, theirs) = (symbolic.len_val(), ordered.len_val());
        let exact = unamalgamated.len_val();
        assert!(
            exact <= ours && ours <= theirs && exact < theirs,
            "{ours} entries against {exact} to {theirs}"
        );
        // It solves.
        let factor = factorise(&k, &assembly.dofs).unwrap();
        let b = Mat::<f64>::from_fn(k.n, 1, |i, _| ((i * 7) % 17) as f64 - 8.0);
        let mut x = b.clone();
        factor.solve_in_place(x.as_mut());
        let r = k.mul_block(x.as_ref()) - &b;
        assert!(
            r.norm_max() <= 1e-9 * b.norm_max(),
            "residual {}",
            r.norm_max()
        );
    }

    /// This module's numeric factorisation ([`supernodal`]) against
    /// faer's on a 40 × 40 grillage, whose separators are wide enough for
    /// both of its kernels and for updates made as dense products (here
    /// in slices of 64 entries, so every product is sliced): the same
    /// factor to round-off, the same bits on one thread or two, and no
    /// factor of a matrix that is not positive definite.
    #[test]
    fn the_supernodal_factor_is_faers_on_one_thread_or_two() {
        let model = grillage(40);
        let assembly = Assembly::new(&model, &model.nodes_mm).unwrap();
        let k = assembly.stiffness(&model);
        // faer's structure of the matrix as it stands, and faer's factor.
        let upper = k.pattern.transposed();
        let upper_rows = upper.rows();
        let symbolic = factorize_symbolic_cholesky(
            SymbolicSparseColMatRef::new_checked(k.n, k.n, &upper.start, None, &upper_rows),
            Side::Upper,
            SymmetricOrdering::Identity,
            Default::default(),
        )
        .unwrap();
        let structure = Arc::new(Structure::of(symbolic));
        let (Some(symbolic), Some(supernodal)) = (&structure.cholesky, structure.layout()) else {
            panic!("a supernodal factor");
        };
        let widest = (0..supernodal.n_supernodes())
            .map(|s| supernodal.supernode_end()[s] - supernodal.supernode_begin()[s])
            .max()
            .unwrap();
        assert!(widest > 32, "a supernode {widest} wide for faer's kernels");
        let mut faers = vec![0.0; symbolic.len_val()];
        let mut memory = MemBuffer::new(
            symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()),
        );
        symbolic
            .factorize_numeric_llt(
                &mut faers,
                k.to_faer().unwrap().matrix(),
                Side::Lower,
                LltRegularization::default(),
                Par::Seq,
                MemStack::new(&mut memory),
                Default::default(),
            )
            .unwrap();
        let updates = supernodal::Updates::of(supernodal).unwrap();
        let (start, values) = (&k.pattern.start, &k.values);
        let a = Lower {
            pattern: &k.pattern,
            values,
        };
        let schedule = Schedule::of(supernodal).expect("the tree splits");
        for slice in [1 << 20, 64] {
            let one = supernodal::factorise_in_slices(supernodal, &updates, None, a, slice)
                .expect("positive definite");
            let two =
                supernodal::factorise_in_slices(supernodal, &updates, Some(&schedule), a, slice)
                    .expect("positive definite");
            assert!(one == two, "the same bits on one thread or two");
            // L is the diagonal blocks' lower triangles and the rows
            // below (faer leaves values of its own above the diagonal,
            // which no solve reads).
            let mut lower_entries = Vec::new();
            for sn in 0..supernodal.n_supernodes() {
                let width = supernodal.supernode_end()[sn] - supernodal.supernode_begin()[sn];
                let first = supernodal.col_ptr_for_val()[sn];
                let height = (supernodal.col_ptr_for_val()[sn + 1] - first) / width;
                for c in 0..width {
                    lower_entries.extend((c..height).map(|r| first + c * height + r));
                }
            }
            let largest = lower_entries
                .iter()
                .fold(0.0f64, |m, &i| m.max(faers[i].abs()));
            let off = lower_entries
                .iter()
                .fold(0.0f64, |m, &i| m.max((one[i] - faers[i]).abs()));
            // The factors differ by the rounding of sums taken in another
            // order, which the matrix's condition (slender beams at stiff
            // joints, about 1e10) magnifies in its smallest entries.
            assert!(
                off <= 1e-10 * largest,
                "slices of {slice}: {off} off faer's, largest {largest}"
            );
            // And it solves as faer's does.
            let factor = Factor {
                symbolic: structure.clone(),
                values: one,
            };
            let b = Mat::<f64>::from_fn(k.n, 1, |i, _| ((i * 7) % 17) as f64 - 8.0);
            let mut x = b.clone();
            factor.solve_in_place(x.as_mut());
            let r = k.mul_block(x.as_ref()) - &b;
            assert!(
                r.norm_max() <= 1e-9 * b.norm_max(),
                "residual {}",
                r.norm_max()
            );
        }
        // A negative pivot in the middle: no factor.
        let mut negative = values.clone();
        let middle = k.n / 2;
        negative[start[middle]] = -negative[start[middle]];
        let a = Lower {
            pattern: &k.pattern,
            values: &negative,
        };
        assert!(supernodal::factorise(supernodal, &updates, Some(&schedule), a).is_none());
    }

    /// The largest of a result's nodal displacements and rotations, in
    /// absolute value (mm or rad).
    fn largest_displacement(r: &StaticResult) -> f64 {
        (r.displacements.iter().flatten()).fold(0.0f64, |m, v| m.max(v.abs()))
    }

    /// A load vector made in two halves of the elements (as from
    /// [`PARALLEL_LOAD_BEAMS`] on) is the one made in one pass, to rounding.
    #[test]
    fn a_load_vector_made_in_halves_is_the_one_made_in_one_pass() {
        use super::super::model::{ElementLoad, NodeLoad, PressureLoad};
        let model = grillage(30);
        let linear = LinearFrame::new(&model).unwrap();
        let beams = model.beams.len();
        let loads = LoadSet {
            nodes: vec![NodeLoad {
                node: 5,
                force_n: DVec3::new(10.0, -20.0, 30.0),
                moment_nmm: DVec3::new(0.0, 500.0, -250.0),
            }],
            beams: (0..beams)
                .map(|beam| ElementLoad {
                    beam,
                    force_n_per_mm: DVec3::new(0.1, -0.2, -1.0 - (beam % 7) as f64 / 7.0),
                })
                .collect(),
            pressures: (0..beams)
                .step_by(3)
                .map(|beam| PressureLoad {
                    beam,
                    n_per_mm: 0.5,
                })
                .collect(),
            ..Default::default()
        };
        let one = linear.assembly.load_vector_in(&model, &loads, false);
        let halves = linear.assembly.load_vector_in(&model, &loads, true);
        let scale = one.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(scale > 0.0);
        for (i, (a, b)) in one.iter().zip(&halves).enumerate() {
            assert!((a - b).abs() <= 1e-14 * scale, "unknown {i}: {a} and {b}");
        }
        // Both halves hold loads of their own: the second half's array is
        // added, not dropped.
        let first_half = LoadSet {
            beams: loads.beams[..beams / 2].to_vec(),
            ..Default::default()
        };
        let first = linear.assembly.load_vector_in(&model, &first_half, false);
        assert!(first
            .iter()
            .zip(&halves)
            .any(|(a, b)| (a - b).abs() > 1e-3 * scale));
    }

    /// Combinations of a few shared load cases are solved as factored sums
    /// of the cases' solutions, each held to its own backward error (for
    /// its own load vector, made from the combination) and equal to the
    /// combination's own solve (one load set, solved for itself): on a
    /// small frame with an inclined roller (a penalty spring), the same
    /// with a pretensioned cable (its pull one more part of every
    /// right-hand side), and a grillage large enough for the triangular
    /// solves to share the factor's subtrees. One combination nearly
    /// cancels (case a less (1 − 2⁻²⁶) times a, exactly 2⁻²⁶·a in floating
    /// point): the sum of the two solutions is off by about 1e-8 of itself
    /// until it is refined. The small frames are conditioned so badly (the
    /// penalty) that two backward-stable solutions differ by up to 1e-4 of
    /// the cancelling set's scale. On the grillage the other sets agree to
    /// 1e-14 of theirs and the cancelling one, refined, to 1e-9 (its
    /// condition times the rounding; unrefined it was off by 3.5e-7).
    #[test]
    fn combinations_of_shared_cases_are_sums_of_the_cases_solutions() {
        use super::super::model::{Cable, NodeLoad};
        let node_loads = |nodes: &[usize], scale: f64| LoadSet {
            nodes: (nodes.iter().enumerate())
                .map(|(k, &node)| NodeLoad {
                    node,
                    force_n: DVec3::new(10.0 + k as f64, -20.0, 30.0) * scale,
                    moment_nmm: DVec3::new(0.0, 500.0, -250.0) * scale,
                })
                .collect(),
            ..Default::default()
        };
        let (small, pressure) = plan_model();
        let mut cabled = small.clone();
        cabled.cables.push(Cable {
            nodes: [1, 3],
            offsets_mm: [DVec3::ZERO; 2],
            area_mm2: 20.0,
            e_mpa: 160_000.0,
            pretension_n: 2_000.0,
        });
        let m = 60;
        let frames = [
            (small, vec![1, 4], Some(pressure), 1e-3),
            (cabled, vec![1, 4], None, 1e-3),
            (
                grillage(m),
                vec![m + 1, m * m / 2 + 7, m * m - 2],
                None,
                1e-8,
            ),
        ];
        for (model, at, extra, tolerance) in frames {
            let taut = vec![true; model.cables.len()];
            let linear = LinearFrame::with_cables(&model, &taut).unwrap();
            let a = Arc::new(node_loads(&at, 1.0));
            let b = Arc::new(node_loads(&at, -(1.0 - 2f64.powi(-26))));
            let c = Arc::new(extra.unwrap_or_else(|| node_loads(&at[1..], -3.0)));
            let sets: Vec<LoadSet> = [
                vec![(&a, 1.35), (&c, 1.5)],
                vec![(&a, 1.0), (&b, 1.0)],
                vec![(&b, 0.5), (&c, -2.0), (&a, 0.25)],
                vec![(&c, 1.0)],
                vec![(&a, 1.0)],
            ]
            .into_iter()
            .map(|parts| LoadSet {
                parts: (parts.into_iter())
                    .map(|(part, f)| (Arc::clone(part), f))
                    .collect(),
                ..Default::default()
            })
            .collect();
            let refs: Vec<&LoadSet> = sets.iter().collect();
            let statics = linear.solve_each(&refs).unwrap();
            let parts = statics.superposed.as_ref().map(|s| s.parts.len());
            assert_eq!(parts, Some(3 + usize::from(!taut.is_empty())));
            let index = &linear.assembly.dofs.index;
            for (i, set) in sets.iter().enumerate() {
                let own = linear.solve(set).unwrap();
                let got = statics.result(i).unwrap();
                let mut x = vec![0.0; linear.stiffness.n];
                for (node, d) in got.displacements.iter().enumerate() {
                    for k in 0..6 {
                        if index[node * 6 + k] != NONE {
                            x[index[node * 6 + k]] = d[k];
                        }
                    }
                }
                let (omega, _) = backward_error(&linear.stiffness, &x, &linear.rhs(set));
                assert!(omega <= BACKWARD_STABLE, "set {i}: ω = {omega:e}");
                let scale = largest_displacement(&own);
                assert!(scale > 0.0);
                for (g, w) in got.displacements.iter().zip(&own.displacements) {
                    for k in 0..6 {
                        assert!(
                            (g[k] - w[k]).abs() <= tolerance * scale,
                            "set {i}: {} against {} (scale {scale})",
                            g[k],
                            w[k]
                        );
                    }
                }
                // The inclined roller's reaction is its penalty spring's
                // force (displacements equal to 1e-16 of their scale give
                // it to about 1e-9 of itself).
                let size = (own.reactions.iter()).fold(0.0f64, |m, r| m.max(r.force_n.length()));
                assert!(size > 0.0);
                for (g, w) in got.reactions.iter().zip(&own.reactions) {
                    assert!(
                        (g.force_n - w.force_n).length() <= tolerance.max(1e-7) * size,
                        "set {i}: reaction {} against {}",
                        g.force_n,
                        w.force_n
                    );
                }
            }
        }
        // A set with loads of its own is solved for itself.
        let (model, pressure) = plan_model();
        let linear = LinearFrame::new(&model).unwrap();
        let a = Arc::new(pressure.clone());
        let mut own = LoadSet {
            parts: vec![(a.clone(), 2.0)],
            ..Default::default()
        };
        own.nodes.push(node_loads(&[1], 1.0).nodes[0]);
        let just_a = LoadSet {
            parts: vec![(a, 1.0)],
            ..Default::default()
        };
        let statics = linear.solve_each(&[&own, &just_a, &just_a]).unwrap();
        assert!(statics.superposed.is_none());
    }

    /// Load sets solved a block at a time, asked for in any order, give
    /// each one's own solution: here eleven multiples of one load set (two
    /// blocks), whose results are those multiples of its result.
    #[test]
    fn statics_solved_block_by_block_are_each_load_sets_own() {
        let (model, mut loads) = plan_model();
        loads.nodes.push(super::super::model::NodeLoad {
            node: 1,
            force_n: DVec3::new(10.0, -20.0, 30.0),
            moment_nmm: DVec3::new(0.0, 500.0, 0.0),
        });
        let linear = LinearFrame::new(&model).unwrap();
        let one = linear.solve(&loads).unwrap();
        let factors: Vec<f64> = (0..11).map(|c| (c as f64 - 4.5) * 0.75).collect();
        let sets: Vec<LoadSet> = factors
            .iter()
            .map(|&f| LoadSet {
                name: format!("{f}"),
                nodes: (loads.nodes.iter())
                    .map(|l| super::super::model::NodeLoad {
                        force_n: l.force_n * f,
                        moment_nmm: l.moment_nmm * f,
                        ..*l
                    })
                    .collect(),
                pressures: (loads.pressures.iter())
                    .map(|l| super::super::model::PressureLoad {
                        n_per_mm: l.n_per_mm * f,
                        ..*l
                    })
                    .collect(),
                ..Default::default()
            })
            .collect();
        let refs: Vec<&LoadSet> = sets.iter().collect();
        assert!(refs.len() > STATICS_BLOCK);
        let statics = linear.solve_each(&refs).unwrap();
        let scale = largest_displacement(&one);
        assert!(scale > 0.0);
        for c in [10, 0, 9, 1, 8, 7, 10, 3] {
            let r = statics.result(c).unwrap();
            for (got, want) in r.displacements.iter().zip(&one.displacements) {
                for k in 0..6 {
                    assert!(
                        (got[k] - factors[c] * want[k]).abs()
                            <= 1e-12 * scale * factors[c].abs().max(1.0),
                        "set {c}: {} against {}",
                        got[k],
                        factors[c] * want[k]
                    );
                }
            }
            let (got, want) = (
                r.reactions[0].force_n,
                one.reactions[0].force_n * factors[c],
            );
            assert!((got - want).length() <= 1e-9 * want.length().max(1.0));
        }
        assert!(matches!(statics.result(11), Err(FrameError::Invalid(_))));
    }

    /// A load set of shared parts (a combination of its cases) loads the
    /// frame as the same loads listed as one set: displacements,
    /// reactions, section forces, and the pressures' load stiffness.
    #[test]
    fn a_set_of_shared_parts_loads_as_its_loads_listed() {
        use super::super::model::{ElementLoad, NodeLoad};
        let (model, pressures) = plan_model();
        let weights = LoadSet {
            name: "G".into(),
            nodes: vec![NodeLoad {
                node: 1,
                force_n: DVec3::new(0.0, 0.0, -40.0),
                moment_nmm: DVec3::new(300.0, 0.0, 0.0),
            }],
            beams: (0..model.beams.len())
                .map(|beam| ElementLoad {
                    beam,
                    force_n_per_mm: DVec3::new(0.01, 0.0, -0.05 * (beam + 1) as f64),
                })
                .collect(),
            ..Default::default()
        };
        let (g, w) = (Arc::new(weights), Arc::new(pressures));
        // 1.35·G + 0.9·(W, within a part of its own at 1.5 · 0.6).
        let inner = LoadSet {
            name: "0.6 W".into(),
            parts: vec![(w.clone(), 0.6)],
            ..Default::default()
        };
        let combined = LoadSet {
            name: "ULS".into(),
            parts: vec![(g.clone(), 1.35), (Arc::new(inner), 1.5)],
            ..Default::default()
        };
        let listed = LoadSet {
            name: "ULS listed".into(),
            nodes: (g.nodes.iter())
                .map(|l| NodeLoad {
                    force_n: l.force_n * 1.35,
                    moment_nmm: l.moment_nmm * 1.35,
                    ..*l
                })
                .collect(),
            beams: (g.beams.iter())
                .map(|l| ElementLoad {
                    force_n_per_mm: l.force_n_per_mm * 1.35,
                    ..*l
                })
                .collect(),
            pressures: (w.pressures.iter())
                .map(|l| super::super::model::PressureLoad {
                    n_per_mm: l.n_per_mm * 0.9,
                    ..*l
                })
                .collect(),
            ..Default::default()
        };
        let linear = LinearFrame::new(&model).unwrap();
        let (a, b) = (
            linear.solve(&combined).unwrap(),
            linear.solve(&listed).unwrap(),
        );
        let scale = largest_displacement(&b);
        assert!(scale > 0.0);
        for (x, y) in a
            .displacements
            .iter()
            .flatten()
            .zip(b.displacements.iter().flatten())
        {
            assert!((x - y).abs() <= 1e-12 * scale, "{x} against {y}");
        }
        for (x, y) in a.reactions.iter().zip(&b.reactions) {
            assert!((x.force_n - y.force_n).length() <= 1e-9 * y.force_n.length().max(1.0));
        }
        for (x, y) in a.beam_forces.iter().zip(&b.beam_forces) {
            let (p, q) = (x.middle.moment_y_nmm, y.middle.moment_y_nmm);
            assert!((p - q).abs() <= 1e-9 * q.abs().max(1.0), "{p} against {q}");
        }
        // The pressures' load stiffness counts the part's.
        let assembly = &linear.assembly;
        let axial = vec![0.0; model.beams.len()];
        let (ka, kb) = (
            assembly.geometric(&model, &axial, Some(&combined)),
            assembly.geometric(&model, &axial, Some(&listed)),
        );
        assert!(ka.values.iter().any(|v| *v != 0.0));
        for (x, y) in ka.values.iter().zip(&kb.values) {
            assert!(
                (x - y).abs() <= 1e-12 * y.abs().max(1e-9),
                "{x} against {y}"
            );
        }
    }

    /// Every one of `n` unknowns free, no symbolic factorisation kept yet.
    fn all_free(n: usize) -> Dofs {
        Dofs {
            index: (0..n).collect(),
            free: n,
            in_order: false,
            symbolic: Arc::default(),
        }
    }

    /// A backward-stable solve is not refined (the refined solution is
    /// the plain one, bit for bit); a solve on the factor of a matrix 0.1 %
    /// off is, and refinement takes its backward error from above 1e-4 to
    /// below 1e-8 (each step multiplies the error by about 1e-3).
    #[test]
    fn only_a_solve_that_is_not_backward_stable_is_refined() {
        let k = grid_matrix(24, 6);
        let dofs = all_free(k.n);
        let b = Mat::<f64>::from_fn(k.n, 3, |i, j| ((i * 7 + j * 13) % 17) as f64 - 8.0);
        let omega = |x: &Mat<f64>| {
            (0..x.ncols())
                .map(|c| backward_error(&k, column_slice(x.col(c)), column_slice(b.col(c))).0)
                .fold(0.0f64, f64::max)
        };
        let exact = factorise_definite(&k, &dofs).unwrap().unwrap();
        let mut plain = b.clone();
        exact.solve_in_place(plain.as_mut());
        assert!(omega(&plain) <= BACKWARD_STABLE);
        let refined = solve_refined_all(&exact, &k, &b).unwrap();
        assert_eq!(refined, plain);
        let off = add(&k, &k, 1e-3);
        let inexact = factorise_definite(&off, &dofs).unwrap().unwrap();
        let mut rough = b.clone();
        inexact.solve_in_place(rough.as_mut());
        let before = omega(&rough);
        let refined = solve_refined_all(&inexact, &k, &b).unwrap();
        let after = omega(&refined);
        assert!(before > 1e-4 && after < 1e-8, "ω {before:e} → {after:e}");
    }
}
