//! The flat state of an interlocking grid: the planar layout the
//! grid is assembled in before it is eased into its spatial shape.
//!
//! Model: every A/B strip an inextensible elastic strip standing upright on
//! the floor, bending only in the floor plane (about its weak axis),
//! untwisted; its node-to-node lengths are the erected ones; joints are pins
//! about the vertical. Unknowns: the grid nodes' floor positions p_i. A
//! strip through nodes p_0 … p_k has segments d_j = p_{j+1} − p_j and, at an
//! interior node, the turning angle φ_j = angle(d_{j−1}, d_j); its bending
//! energy is discretised per node interval as
//!
//! ```text
//! E = Σ EI φ_j² / ℓ_j,   ℓ_j = (L_{j−1} + L_j) / 2,   κ_j = φ_j / ℓ_j
//! ```
//!
//! (EI of all the strip's lamellas about their weak axes, n·h·t³/12). The
//! flat state minimises E subject to |d_j| = L_j. A grid of m × n cells keeps
//! m + n − 3 zero-energy mechanisms besides the rigid motions; they are
//! taken by a weak pull of each node's crossing angle towards its erected
//! angle (weight [`ANGLE_WEIGHT`]) and of every node towards its start
//! (weight [`ANCHOR_WEIGHT`], the rigid motions).
//!
//! Solver: Levenberg–Marquardt on the residuals (energy terms √(ℓ̄/ℓ_j)·φ_j,
//! lengths as a penalty (|d_j| − L_j)·[`LENGTH_WEIGHT`]/ℓ̄, the two weak
//! pulls), each step a sparse Cholesky solve (faer, fill-reducing ordering)
//! of JᵀJ + λ·diag(JᵀJ); then Gauss–Newton projection onto the length
//! constraints (minimum-norm steps through J_L J_Lᵀ) until every length
//! holds to [`LENGTH_TOLERANCE`] relative. Stationarity is reported as the
//! norm of the objective's gradient projected onto the constraints' tangent
//! space, relative to the gradient's own norm at the start.
//!
//! Start: the erected nodes projected onto their best-fit plane, seen from
//! the side the surface normals point to (so angles keep their sense).

use crate::analysis::Analysis;
use crate::error::{Error, Result};
use crate::network::Family;
use crate::profile::{JointSystem, Profile};
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};
use glam::DVec3;
use std::collections::HashMap;

/// Weight of the pull towards the erected crossing angles (per radian,
/// against bending residuals of order φ).
pub const ANGLE_WEIGHT: f64 = 1e-3;
/// Weight of the pull of each node towards its start (per mean interval).
pub const ANCHOR_WEIGHT: f64 = 1e-6;
/// Penalty weight of the lengths while minimising (per mean interval).
pub const LENGTH_WEIGHT: f64 = 1e3;
/// Every node-to-node length of the result holds to this, relative.
pub const LENGTH_TOLERANCE: f64 = 1e-9;
/// Iteration limit of the minimisation.
pub const MAX_ITERATIONS: usize = 200;

/// One grid node of the problem.
#[derive(Debug, Clone, PartialEq)]
pub struct FlatNodeIn {
    /// Its plan.json id.
    pub id: usize,
    /// Erected position, mm.
    pub position_world_mm: DVec3,
    /// Surface normal there.
    pub normal_world: DVec3,
    /// Oriented angle from A's tangent line to B's about the normal,
    /// degrees in [0, 180).
    pub erected_angle_deg: f64,
    /// Index of its A strip in [`FlatProblem::strips`].
    pub strip_a: usize,
    /// Index of its B strip.
    pub strip_b: usize,
}

/// One strip: its grid nodes in order and the lengths between them.
#[derive(Debug, Clone, PartialEq)]
pub struct FlatStripIn {
    /// Strip id.
    pub id: String,
    /// A or B.
    pub family: Family,
    /// Indices into [`FlatProblem::nodes`], by station.
    pub nodes: Vec<usize>,
    /// Erected node-to-node lengths along the strip, mm (one fewer).
    pub lengths_mm: Vec<f64>,
}

/// What the flat state is solved for: plain data.
#[derive(Debug, Clone, PartialEq)]
pub struct FlatProblem {
    /// The A×B nodes.
    pub nodes: Vec<FlatNodeIn>,
    /// The A and B strips with at least one node.
    pub strips: Vec<FlatStripIn>,
    /// Weak-axis bending stiffness of a whole strip, N·mm².
    pub ei_nmm2: f64,
    /// Young's modulus, MPa.
    pub youngs_modulus_mpa: f64,
    /// Lamella thickness, mm.
    pub thickness_mm: f64,
    /// Design strength, MPa.
    pub design_strength_mpa: f64,
}

/// The problem of an analysed network for a profile. Two-level grids have
/// no flat state (their studs fix the angles): an error saying so.
pub fn problem(an: &Analysis, profile: &Profile) -> Result<FlatProblem> {
    if profile.joint.system == JointSystem::TwoLevel {
        return Err(Error::input(
            &profile.source,
            crate::error::Location::Field("joint.system".into()),
            "a two-level grid cannot be assembled flat: its studs fix every crossing at 90°, so there is no flat state to erect from",
        ));
    }
    let mut index: HashMap<usize, usize> = HashMap::new();
    let mut nodes = Vec::new();
    let strip_index: HashMap<usize, usize> = an
        .lamella_strips()
        .enumerate()
        .map(|(i, s)| (s.curve, i))
        .collect();
    for n in &an.topology.nodes {
        let (fa, fb) = (an.strips[n.a].family, an.strips[n.b].family);
        if fa != Family::A || fb != Family::B {
            continue;
        }
        index.insert(n.id, nodes.len());
        nodes.push(FlatNodeIn {
            id: n.id,
            position_world_mm: n.position_world_mm,
            normal_world: n.normal_world,
            erected_angle_deg: n.oriented_angle_deg,
            strip_a: strip_index[&n.a],
            strip_b: strip_index[&n.b],
        });
    }
    let strips = an
        .lamella_strips()
        .map(|s| {
            let on: Vec<(usize, f64)> = s
                .nodes
                .iter()
                .filter_map(|cn| {
                    let id = an.topology.nodes[cn.node].id;
                    index.get(&id).map(|&i| (i, cn.station_mm))
                })
                .collect();
            FlatStripIn {
                id: s.id.clone(),
                family: s.family,
                nodes: on.iter().map(|p| p.0).collect(),
                lengths_mm: on.windows(2).map(|w| w[1].1 - w[0].1).collect(),
            }
        })
        .collect();
    let (t, h) = (profile.thickness_mm(), profile.height_mm());
    let e = profile.youngs_modulus_mpa();
    Ok(FlatProblem {
        nodes,
        strips,
        ei_nmm2: e * f64::from(profile.section.per_strip) * h * t.powi(3) / 12.0,
        youngs_modulus_mpa: e,
        thickness_mm: t,
        design_strength_mpa: profile.design_strength_mpa(),
    })
}

/// A node of the flat state.
#[derive(Debug, Clone, PartialEq)]
pub struct FlatNode {
    /// Its plan.json id.
    pub node: usize,
    /// Floor position, mm.
    pub position_mm: [f64; 2],
    /// Oriented angle from A to B in the flat state, degrees in [0, 180).
    pub angle_deg: f64,
    /// The erected oriented angle, degrees.
    pub erected_angle_deg: f64,
    /// Erected − flat, degrees in (−90, 90]: how far the joint turns.
    pub rotation_deg: f64,
}

/// A strip of the flat state.
#[derive(Debug, Clone, PartialEq)]
pub struct FlatStrip {
    /// Strip id.
    pub strip: String,
    /// Largest in-plane curvature, 1/mm.
    pub max_curvature_per_mm: f64,
    /// E·κ·t/2 at that curvature, MPa.
    pub max_bending_stress_mpa: f64,
    /// That stress over the design strength.
    pub utilization: f64,
}

/// The solved flat state.
#[derive(Debug, Clone, PartialEq)]
pub struct FlatState {
    /// The gradient and the lengths met their tolerances.
    pub converged: bool,
    /// Levenberg–Marquardt iterations plus projection steps.
    pub iterations: usize,
    /// Bending energy Σ EI φ²/ℓ of the result, N·mm.
    pub energy_nmm: f64,
    /// The same of the start (the erected nodes projected onto their plane,
    /// lengths then made right; after a continuation its start, see
    /// [`solve`]), N·mm.
    pub start_energy_nmm: f64,
    /// The objective at the result and at the start (energy and the weak
    /// pulls, lengths met at the result).
    pub objective: (f64, f64),
    /// Projected gradient norm over the start's gradient norm (or over
    /// 1e-6 per mean node interval, when the start is already at rest).
    pub gradient_norm: f64,
    /// Largest relative node-to-node length error.
    pub max_length_error: f64,
    /// Per node, in problem order.
    pub nodes: Vec<FlatNode>,
    /// Per strip, in problem order.
    pub strips: Vec<FlatStrip>,
    /// Extent of the layout along its x and y, mm.
    pub footprint_mm: [f64; 2],
    /// Set when no least-bending flat state was found (the minimisation
    /// stopped, or folded a joint past 0° or 180°, from the projected start
    /// and along the continuation from it): this state is then the layout
    /// that holds the joints nearest their erected angles, and this its
    /// largest rotation, degrees (90 when even it folds a joint).
    pub least_rotation_deg: Option<f64>,
}

impl FlatState {
    /// Each node's rotation from flat to erected, degrees, by node id (what
    /// [`crate::fabricate::fabricate`] sizes slots from).
    pub fn rotations(&self) -> HashMap<usize, f64> {
        self.nodes
            .iter()
            .map(|n| (n.node, n.rotation_deg))
            .collect()
    }

    /// The node that turns most (index into `nodes`), if any.
    pub fn max_rotation(&self) -> Option<usize> {
        (0..self.nodes.len()).max_by(|&a, &b| {
            self.nodes[a]
                .rotation_deg
                .abs()
                .total_cmp(&self.nodes[b].rotation_deg.abs())
                .then(b.cmp(&a))
        })
    }
}

/// Residual bookkeeping: each row's entries (column, value) and value.
struct Rows {
    r: Vec<f64>,
    entries: Vec<Vec<(usize, f64)>>,
}

impl Rows {
    fn new() -> Rows {
        Rows {
            r: Vec::new(),
            entries: Vec::new(),
        }
    }
    fn push(&mut self, r: f64, e: Vec<(usize, f64)>) {
        self.r.push(r);
        self.entries.push(e);
    }
    fn sum_sq(&self) -> f64 {
        self.r.iter().map(|x| x * x).sum()
    }
    /// Jᵀr.
    fn gradient(&self, n: usize) -> Vec<f64> {
        let mut g = vec![0.0; n];
        for (r, e) in self.r.iter().zip(&self.entries) {
            for &(c, v) in e {
                g[c] += v * r;
            }
        }
        g
    }
    /// JᵀJ as triplets (lower triangle), and its diagonal.
    fn normal_matrix(&self, n: usize) -> (Vec<Triplet<usize, usize, f64>>, Vec<f64>) {
        let mut t = Vec::new();
        let mut diag = vec![0.0; n];
        for e in &self.entries {
            for &(ci, vi) in e {
                for &(cj, vj) in e {
                    if ci >= cj {
                        t.push(Triplet::new(ci, cj, vi * vj));
                    }
                    if ci == cj {
                        diag[ci] += vi * vj;
                    }
                }
            }
        }
        (t, diag)
    }
}

fn perp_over_sq(d: [f64; 2]) -> [f64; 2] {
    let q = d[0] * d[0] + d[1] * d[1];
    [-d[1] / q, d[0] / q]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// Signed angle from `a` to `b`, radians.
fn turn(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] * b[1] - a[1] * b[0]).atan2(a[0] * b[0] + a[1] * b[1])
}

/// An angle wrapped into (−π/2, π/2] (tangent lines are undirected).
fn wrap_half(a: f64) -> f64 {
    let p = std::f64::consts::PI;
    let mut x = a.rem_euclid(p);
    if x > 0.5 * p {
        x -= p;
    }
    x
}

/// An angle wrapped into (−π, π].
fn wrap_full(a: f64) -> f64 {
    let p = std::f64::consts::PI;
    let mut x = a.rem_euclid(2.0 * p);
    if x > p {
        x -= 2.0 * p;
    }
    x
}

/// The chord of a strip at its k-th node: next − previous (one-sided at the
/// ends), and the two node indices.
fn chord(s: &FlatStripIn, k: usize) -> (usize, usize) {
    let last = s.nodes.len() - 1;
    (s.nodes[k.saturating_sub(1)], s.nodes[(k + 1).min(last)])
}

/// Whether the joint at node `i` is free: a strip through it that crosses
/// no other strip has no direction of its own in the flat state, so it can
/// be laid at the erected angle (no rotation) whatever the rest does.
fn free_joint(pr: &FlatProblem, su: &Setup, i: usize) -> bool {
    su.on[i]
        .iter()
        .any(|&(strip, _)| pr.strips[strip].nodes.len() < 2)
}

struct Setup {
    /// Mean node interval, mm.
    l_mean: f64,
    /// Per node: (strip A, position on it), (strip B, position on it).
    on: Vec<[(usize, usize); 2]>,
    start: Vec<[f64; 2]>,
}

fn p(x: &[f64], i: usize) -> [f64; 2] {
    [x[2 * i], x[2 * i + 1]]
}

/// The weights of a minimisation and the lengths it holds the strips to.
struct Terms<'a> {
    /// Factor on the bending residuals.
    bend: f64,
    /// Weight of the pull towards the erected angles.
    angle: f64,
    /// Target node-to-node lengths per strip, mm.
    lengths: &'a [Vec<f64>],
    /// Penalty weight of the lengths (per mean interval).
    length: f64,
    /// Per node, the erected angle from A's chord to B's as directed
    /// (radians in (−π, π]): when given, the angle pull tells a folded
    /// joint from an unfolded one (otherwise lines, modulo π).
    directed: Option<&'a [f64]>,
}

impl<'a> Terms<'a> {
    /// The flat state's own: bending, [`ANGLE_WEIGHT`], the erected lengths.
    fn standard(lengths: &'a [Vec<f64>]) -> Terms<'a> {
        Terms {
            bend: 1.0,
            angle: ANGLE_WEIGHT,
            lengths,
            length: LENGTH_WEIGHT,
            directed: None,
        }
    }
}

/// Residuals at `x`: bending, (optionally) lengths, angle pull, anchors,
/// with the weights and target lengths of `terms`.
fn weighted_residuals(
    pr: &FlatProblem,
    su: &Setup,
    x: &[f64],
    with_lengths: bool,
    terms: &Terms,
) -> Rows {
    let mut rows = Rows::new();
    let lm = su.l_mean;
    for (s, target) in pr.strips.iter().zip(terms.lengths) {
        for j in 1..s.nodes.len().saturating_sub(1) {
            let (a, b, c) = (s.nodes[j - 1], s.nodes[j], s.nodes[j + 1]);
            let (d1, d2) = (sub(p(x, b), p(x, a)), sub(p(x, c), p(x, b)));
            let ell = 0.5 * (s.lengths_mm[j - 1] + s.lengths_mm[j]);
            let w = terms.bend * (lm / ell).sqrt();
            let (g1, g2) = (perp_over_sq(d1), perp_over_sq(d2));
            rows.push(
                w * turn(d1, d2),
                vec![
                    (2 * a, w * g1[0]),
                    (2 * a + 1, w * g1[1]),
                    (2 * b, -w * (g1[0] + g2[0])),
                    (2 * b + 1, -w * (g1[1] + g2[1])),
                    (2 * c, w * g2[0]),
                    (2 * c + 1, w * g2[1]),
                ],
            );
        }
        if with_lengths {
            length_rows(&mut rows, s, target, x, terms.length / lm);
        }
    }
    for (i, n) in pr.nodes.iter().enumerate() {
        if !free_joint(pr, su, i) {
            let [(sa, ka), (sb, kb)] = su.on[i];
            let (a0, a1) = chord(&pr.strips[sa], ka);
            let (b0, b1) = chord(&pr.strips[sb], kb);
            let (da, db) = (sub(p(x, a1), p(x, a0)), sub(p(x, b1), p(x, b0)));
            let psi = turn(da, db);
            let w = terms.angle;
            let (ga, gb) = (perp_over_sq(da), perp_over_sq(db));
            let mut e = Vec::with_capacity(8);
            for (node, sign, g) in [(a1, -1.0, ga), (a0, 1.0, ga), (b1, 1.0, gb), (b0, -1.0, gb)] {
                e.push((2 * node, w * sign * g[0]));
                e.push((2 * node + 1, w * sign * g[1]));
            }
            let miss = match terms.directed {
                Some(d) => wrap_full(psi - d[i]),
                None => wrap_half(psi - n.erected_angle_deg.to_radians()),
            };
            rows.push(w * miss, e);
        }
        let wa = ANCHOR_WEIGHT / lm;
        let q = p(x, i);
        rows.push(wa * (q[0] - su.start[i][0]), vec![(2 * i, wa)]);
        rows.push(wa * (q[1] - su.start[i][1]), vec![(2 * i + 1, wa)]);
    }
    rows
}

/// Length residuals (|d| − L)·w of a strip.
fn length_rows(rows: &mut Rows, s: &FlatStripIn, target: &[f64], x: &[f64], w: f64) {
    for (j, &length) in target.iter().enumerate() {
        let (a, b) = (s.nodes[j], s.nodes[j + 1]);
        let d = sub(p(x, b), p(x, a));
        let len = d[0].hypot(d[1]);
        let u = [d[0] / len, d[1] / len];
        rows.push(
            w * (len - length),
            vec![
                (2 * a, -w * u[0]),
                (2 * a + 1, -w * u[1]),
                (2 * b, w * u[0]),
                (2 * b + 1, w * u[1]),
            ],
        );
    }
}

fn lengths_only(pr: &FlatProblem, x: &[f64]) -> Rows {
    let mut rows = Rows::new();
    for s in &pr.strips {
        length_rows(&mut rows, s, &s.lengths_mm, x, 1.0);
    }
    rows
}

/// Solve (Σ triplets + shift·diag) y = rhs by sparse Cholesky.
fn solve_spd(
    n: usize,
    mut t: Vec<Triplet<usize, usize, f64>>,
    diag: &[f64],
    shift: f64,
    rhs: &[f64],
) -> Option<Vec<f64>> {
    for (i, d) in diag.iter().enumerate() {
        // A floor keeps columns without entries (none here) regular.
        t.push(Triplet::new(i, i, shift * d.max(1e-12) + 1e-14));
    }
    let a = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &t).ok()?;
    let llt = a.sp_cholesky(Side::Lower).ok()?;
    let mut b = Mat::<f64>::from_fn(n, 1, |i, _| rhs[i]);
    llt.solve_in_place(b.as_mut());
    let y: Vec<f64> = (0..n).map(|i| b[(i, 0)]).collect();
    y.iter().all(|v| v.is_finite()).then_some(y)
}

/// Energy Σ EI φ²/ℓ, N·mm.
fn energy(pr: &FlatProblem, x: &[f64]) -> f64 {
    let mut e = 0.0;
    for s in &pr.strips {
        for j in 1..s.nodes.len().saturating_sub(1) {
            let (a, b, c) = (s.nodes[j - 1], s.nodes[j], s.nodes[j + 1]);
            let phi = turn(sub(p(x, b), p(x, a)), sub(p(x, c), p(x, b)));
            let ell = 0.5 * (s.lengths_mm[j - 1] + s.lengths_mm[j]);
            e += pr.ei_nmm2 * phi * phi / ell;
        }
    }
    e
}

/// The start: erected nodes on their best-fit plane, seen from the normals' side.
fn start_positions(pr: &FlatProblem) -> Vec<[f64; 2]> {
    let n = pr.nodes.len() as f64;
    let c = pr.nodes.iter().map(|q| q.position_world_mm).sum::<DVec3>() / n;
    let mean_normal = pr.nodes.iter().map(|q| q.normal_world).sum::<DVec3>();
    // Best-fit plane normal: the smallest principal axis of the scatter,
    // by power iteration on (trace·I − C), oriented along the mean normal.
    let mut cov = [[0.0f64; 3]; 3];
    for q in &pr.nodes {
        let d = q.position_world_mm - c;
        let v = [d.x, d.y, d.z];
        for (r, row) in cov.iter_mut().enumerate() {
            for (k, cell) in row.iter_mut().enumerate() {
                *cell += v[r] * v[k];
            }
        }
    }
    let tr = cov[0][0] + cov[1][1] + cov[2][2];
    let mut v = if mean_normal.length() > 1e-9 {
        mean_normal.normalize()
    } else {
        DVec3::Z
    };
    for _ in 0..200 {
        let w = DVec3::new(
            tr * v.x - (cov[0][0] * v.x + cov[0][1] * v.y + cov[0][2] * v.z),
            tr * v.y - (cov[1][0] * v.x + cov[1][1] * v.y + cov[1][2] * v.z),
            tr * v.z - (cov[2][0] * v.x + cov[2][1] * v.y + cov[2][2] * v.z),
        );
        if w.length() < 1e-300 {
            break;
        }
        v = w.normalize();
    }
    if v.dot(mean_normal) < 0.0 {
        v = -v;
    }
    let e1 = v.any_orthonormal_vector();
    let e2 = v.cross(e1);
    pr.nodes
        .iter()
        .map(|q| {
            let d = q.position_world_mm - c;
            [d.dot(e1), d.dot(e2)]
        })
        .collect()
}

/// The least-energy minimisation from the projected start: the state, its
/// setup and its node positions.
fn solve_least_energy(pr: &FlatProblem) -> (FlatState, Setup, Vec<f64>) {
    let n = 2 * pr.nodes.len();
    let mut on = vec![[(usize::MAX, 0usize); 2]; pr.nodes.len()];
    let mut total_len = 0.0;
    let mut count = 0usize;
    for (si, s) in pr.strips.iter().enumerate() {
        for (k, &node) in s.nodes.iter().enumerate() {
            let slot = usize::from(s.family == Family::B);
            on[node][slot] = (si, k);
        }
        total_len += s.lengths_mm.iter().sum::<f64>();
        count += s.lengths_mm.len();
    }
    let start = start_positions(pr);
    let su = Setup {
        l_mean: if count > 0 {
            total_len / count as f64
        } else {
            1.0
        },
        on,
        start: Vec::new(),
    };
    let mut x: Vec<f64> = start.iter().flat_map(|q| [q[0], q[1]]).collect();
    // The start proper: the projection with its lengths made right.
    let (_, mut iterations) = project_lengths(pr, &mut x);
    let start_x = x.clone();
    let su = Setup {
        start: start_x.chunks(2).map(|c| [c[0], c[1]]).collect(),
        ..su
    };
    let lengths: Vec<Vec<f64>> = pr.strips.iter().map(|s| s.lengths_mm.clone()).collect();
    let standard = Terms::standard(&lengths);
    let start_energy = energy(pr, &x);
    let objective = |x: &[f64]| weighted_residuals(pr, &su, x, false, &standard).sum_sq();
    let start_objective = objective(&x);
    iterations += minimise(pr, &su, &mut x, &standard, None, MAX_ITERATIONS);
    let (length_ok, steps) = project_lengths(pr, &mut x);
    iterations += steps;
    // Relative to the start's gradient; a start already at rest (a planar
    // grid) is measured against 1e-6 per mean interval instead.
    // Stationarity: the objective's gradient projected onto the tangent
    // space of the length constraints.
    let g_start = norm(&weighted_residuals(pr, &su, &start_x, false, &standard).gradient(n))
        .max(1e-6 / su.l_mean);
    let gradient_norm = projected_gradient(pr, &su, &x, &standard) / g_start;
    let st = finish(
        pr,
        &su,
        &x,
        iterations,
        start_energy,
        start_objective,
        objective(&x),
        gradient_norm,
        length_ok,
    );
    (st, su, x)
}

/// Stages of the continuation on the lengths (see [`solve`]).
const CONTINUATION_STAGES: usize = 24;
/// Penalty weight of the lengths along the continuation.
const FIRM_LENGTH_WEIGHT: f64 = 1e5;
/// Rounds of minimisation and projection after the continuation.
const POLISH_ROUNDS: usize = 3;
/// Levenberg–Marquardt iterations per continuation stage.
const STAGE_ITERATIONS: usize = 60;

/// Solve the flat state.
///
/// First Levenberg–Marquardt from the projected start (module docs). When
/// that stops short of the tolerances, or folds a joint (its strips' chords
/// turn through 0° or 180° against the erected sense), again by
/// continuation: from the raw projection (or, where that folds joints, the
/// grid as a spring net with its rim on a circle, when that folds fewer),
/// the angle pull made dominant to unfold it, then through
/// lengths moved from its own towards the erected ones in
/// [`CONTINUATION_STAGES`] stages, every step rejected that leaves more
/// joints folded, then [`POLISH_ROUNDS`] rounds of minimisation at the
/// ordinary length weight and projection. When that fails
/// too, the layout that holds the joints nearest their erected angles (the
/// angle pull made dominant, still no step folding a joint) is returned
/// with [`FlatState::least_rotation_deg`] set.
pub fn solve(pr: &FlatProblem) -> FlatState {
    let (st, su, x) = solve_least_energy(pr);
    let sense = erected_senses(pr, &su);
    if st.converged && !any_folded(pr, &su, &sense, &x) {
        return st;
    }
    let mut iterations = st.iterations;
    let target: Vec<Vec<f64>> = pr.strips.iter().map(|s| s.lengths_mm.clone()).collect();
    // Continuation from the raw projection.
    let mut raw: Vec<f64> = start_positions(pr)
        .iter()
        .flat_map(|q| [q[0], q[1]])
        .collect();
    // Where the projection folds joints (the surface turns past vertical),
    // a start that folds fewer: the grid as a spring net with its rim on a
    // circle.
    let folds = |x: &[f64]| {
        folded(pr, &su, &sense, x)
            .into_iter()
            .filter(|&f| f)
            .count()
    };
    if folds(&raw) > 0 {
        if let Some(net) = spring_net(pr, &raw) {
            if folds(&net) < folds(&raw) {
                raw = net;
            }
        }
    }
    let su = Setup {
        start: raw.chunks(2).map(|c| [c[0], c[1]]).collect(),
        ..su
    };
    let from: Vec<Vec<f64>> = pr
        .strips
        .iter()
        .map(|s| {
            s.nodes
                .windows(2)
                .map(|w| {
                    let d = sub(p(&raw, w[1]), p(&raw, w[0]));
                    d[0].hypot(d[1]).max(1e-9)
                })
                .collect()
        })
        .collect();
    let directed = erected_directed(pr, &su);
    let mut x = raw.clone();
    // Unfold the projection where it folds (past a vertical tangent plane):
    // the angle pull dominant, on the projection's own lengths.
    let unfold = Terms {
        bend: 1e-3,
        angle: 1.0,
        lengths: &from,
        length: FIRM_LENGTH_WEIGHT,
        directed: Some(&directed),
    };
    iterations += minimise(pr, &su, &mut x, &unfold, Some(&sense), MAX_ITERATIONS);
    let start_energy = energy(pr, &raw);
    for k in 1..=CONTINUATION_STAGES {
        let t = k as f64 / CONTINUATION_STAGES as f64;
        let lengths: Vec<Vec<f64>> = from
            .iter()
            .zip(&target)
            .map(|(a, b)| a.iter().zip(b).map(|(a, b)| a + t * (b - a)).collect())
            .collect();
        let iters = if k == CONTINUATION_STAGES {
            MAX_ITERATIONS
        } else {
            STAGE_ITERATIONS
        };
        let terms = Terms {
            directed: Some(&directed),
            length: FIRM_LENGTH_WEIGHT,
            ..Terms::standard(&lengths)
        };
        iterations += minimise(pr, &su, &mut x, &terms, Some(&sense), iters);
    }
    let standard = Terms {
        directed: Some(&directed),
        ..Terms::standard(&target)
    };
    // Polish: the lengths back to their ordinary penalty weight, a
    // projection onto them after each round.
    let mut y = x.clone();
    let (mut length_ok, mut steps) = project_lengths(pr, &mut y);
    for _ in 0..POLISH_ROUNDS {
        iterations += steps;
        let mut z = y.clone();
        iterations += minimise(pr, &su, &mut z, &standard, Some(&sense), MAX_ITERATIONS);
        (length_ok, steps) = project_lengths(pr, &mut z);
        y = z;
    }
    iterations += steps;
    let g_start = norm(&weighted_residuals(pr, &su, &raw, false, &standard).gradient(raw.len()))
        .max(1e-6 / su.l_mean);
    let gradient_norm = projected_gradient(pr, &su, &y, &standard) / g_start;
    let objective = |x: &[f64]| weighted_residuals(pr, &su, x, false, &standard).sum_sq();
    let st = finish(
        pr,
        &su,
        &y,
        iterations,
        start_energy,
        objective(&raw),
        objective(&y),
        gradient_norm,
        length_ok,
    );
    if st.converged && !any_folded(pr, &su, &sense, &y) {
        return st;
    }
    // The layout of least rotation: the angle pull dominant, from the
    // continuation's result (no joint folded by it).
    let relaxed = Terms {
        bend: 1e-3,
        angle: 1.0,
        lengths: &target,
        length: FIRM_LENGTH_WEIGHT,
        directed: Some(&directed),
    };
    iterations += minimise(pr, &su, &mut x, &relaxed, Some(&sense), MAX_ITERATIONS);
    let (length_ok, steps) = project_lengths(pr, &mut x);
    iterations += steps;
    let g_start = norm(&weighted_residuals(pr, &su, &raw, false, &relaxed).gradient(raw.len()))
        .max(1e-6 / su.l_mean);
    let gradient_norm = projected_gradient(pr, &su, &x, &relaxed) / g_start;
    let objective = |x: &[f64]| weighted_residuals(pr, &su, x, false, &relaxed).sum_sq();
    let mut st = finish(
        pr,
        &su,
        &x,
        iterations,
        start_energy,
        objective(&raw),
        objective(&x),
        gradient_norm,
        length_ok,
    );
    let worst = st
        .max_rotation()
        .map_or(0.0, |i| st.nodes[i].rotation_deg.abs());
    st.least_rotation_deg = Some(if any_folded(pr, &su, &sense, &x) {
        90.0
    } else {
        worst
    });
    st
}

/// The grid as a net of springs (stiffness 1/length) with its rim nodes
/// (fewer than four neighbours) on a circle about the centroid of `x`, in
/// their angular order about it, the others at rest: a planar embedding
/// whose cells are convex where the rim is (Tutte), as positions.
fn spring_net(pr: &FlatProblem, x: &[f64]) -> Option<Vec<f64>> {
    let n = pr.nodes.len();
    let mut nb: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    for s in &pr.strips {
        for (w, l) in s.nodes.windows(2).zip(&s.lengths_mm) {
            let k = 1.0 / l.max(1e-9);
            nb[w[0]].push((w[1], k));
            nb[w[1]].push((w[0], k));
        }
    }
    let c = (0..n).fold([0.0, 0.0], |a, i| [a[0] + x[2 * i], a[1] + x[2 * i + 1]]);
    let c = [c[0] / n as f64, c[1] / n as f64];
    let radius = (0..n)
        .map(|i| {
            let d = sub(p(x, i), c);
            d[0].hypot(d[1])
        })
        .fold(0.0, f64::max);
    let rim: Vec<bool> = nb.iter().map(|v| v.len() < 4).collect();
    let mut out = x.to_vec();
    let mut index = vec![usize::MAX; n];
    let mut inner = 0;
    for i in 0..n {
        if rim[i] {
            let d = sub(p(x, i), c);
            let a = d[1].atan2(d[0]);
            out[2 * i] = c[0] + radius * a.cos();
            out[2 * i + 1] = c[1] + radius * a.sin();
        } else {
            index[i] = inner;
            inner += 1;
        }
    }
    if inner == 0 || inner == n {
        return (inner == 0).then_some(out);
    }
    let mut t = Vec::new();
    let mut rhs = [vec![0.0; inner], vec![0.0; inner]];
    for i in (0..n).filter(|&i| !rim[i]) {
        let r = index[i];
        let mut diag = 0.0;
        for &(j, k) in &nb[i] {
            diag += k;
            if rim[j] {
                rhs[0][r] += k * out[2 * j];
                rhs[1][r] += k * out[2 * j + 1];
            } else if index[j] < r {
                t.push(Triplet::new(r, index[j], -k));
            }
        }
        t.push(Triplet::new(r, r, diag));
    }
    let zero = vec![0.0; inner];
    let xs = solve_spd(inner, t.clone(), &zero, 0.0, &rhs[0])?;
    let ys = solve_spd(inner, t, &zero, 0.0, &rhs[1])?;
    for i in (0..n).filter(|&i| !rim[i]) {
        out[2 * i] = xs[index[i]];
        out[2 * i + 1] = ys[index[i]];
    }
    Some(out)
}

/// Per node, the erected angle from A's chord to B's, directed, radians:
/// the erected line angle plus the multiple of π nearest the angle of the
/// erected chords about the normal (0 for free joints).
fn erected_directed(pr: &FlatProblem, su: &Setup) -> Vec<f64> {
    let pi = std::f64::consts::PI;
    (0..pr.nodes.len())
        .map(|i| {
            if free_joint(pr, su, i) {
                return 0.0;
            }
            let [(sa, ka), (sb, kb)] = su.on[i];
            let (a0, a1) = chord(&pr.strips[sa], ka);
            let (b0, b1) = chord(&pr.strips[sb], kb);
            let w = |k: usize| pr.nodes[k].position_world_mm;
            let (da, db) = (w(a1) - w(a0), w(b1) - w(b0));
            let chords = pr.nodes[i].normal_world.dot(da.cross(db)).atan2(da.dot(db));
            let line = pr.nodes[i].erected_angle_deg.to_radians();
            wrap_full(line + ((chords - line) / pi).round() * pi)
        })
        .collect()
}

/// Per node, the sense in which B's chord turns from A's about the erected
/// normal (+1 or −1; 0 for free joints and degenerate chords).
fn erected_senses(pr: &FlatProblem, su: &Setup) -> Vec<f64> {
    (0..pr.nodes.len())
        .map(|i| {
            if free_joint(pr, su, i) {
                return 0.0;
            }
            let [(sa, ka), (sb, kb)] = su.on[i];
            let (a0, a1) = chord(&pr.strips[sa], ka);
            let (b0, b1) = chord(&pr.strips[sb], kb);
            let w = |k: usize| pr.nodes[k].position_world_mm;
            let c = pr.nodes[i]
                .normal_world
                .dot((w(a1) - w(a0)).cross(w(b1) - w(b0)));
            if c > 0.0 {
                1.0
            } else if c < 0.0 {
                -1.0
            } else {
                0.0
            }
        })
        .collect()
}

/// Per node, whether its joint is folded at `x`: the chords turn against
/// the erected sense (or lie on one line).
fn folded(pr: &FlatProblem, su: &Setup, sense: &[f64], x: &[f64]) -> Vec<bool> {
    (0..pr.nodes.len())
        .map(|i| {
            if sense[i] == 0.0 {
                return false;
            }
            let [(sa, ka), (sb, kb)] = su.on[i];
            let (a0, a1) = chord(&pr.strips[sa], ka);
            let (b0, b1) = chord(&pr.strips[sb], kb);
            let (da, db) = (sub(p(x, a1), p(x, a0)), sub(p(x, b1), p(x, b0)));
            sense[i] * (da[0] * db[1] - da[1] * db[0]) <= 0.0
        })
        .collect()
}

fn any_folded(pr: &FlatProblem, su: &Setup, sense: &[f64], x: &[f64]) -> bool {
    folded(pr, su, sense, x).into_iter().any(|f| f)
}

/// Levenberg–Marquardt on `terms` (lengths as a penalty) from `x`; with
/// the joints' erected `sense`, every step rejected that leaves more joints
/// folded than before it. Iterations taken.
fn minimise(
    pr: &FlatProblem,
    su: &Setup,
    x: &mut Vec<f64>,
    terms: &Terms,
    sense: Option<&[f64]>,
    max_iterations: usize,
) -> usize {
    let n = x.len();
    let mut rows = weighted_residuals(pr, su, x, true, terms);
    let mut cost = rows.sum_sq();
    let g0 = norm(&rows.gradient(n)).max(1e-300);
    let folds_in = |x: &[f64]| {
        sense.map_or(0, |sense| {
            folded(pr, su, sense, x).iter().filter(|&&b| b).count()
        })
    };
    let mut fold = folds_in(x);
    let mut lambda = 1e-3;
    let mut iterations = 0;
    for _ in 0..max_iterations {
        iterations += 1;
        let g = rows.gradient(n);
        if norm(&g) <= 1e-12 * g0 {
            break;
        }
        let (t, diag) = rows.normal_matrix(n);
        let neg: Vec<f64> = g.iter().map(|v| -v).collect();
        let Some(step) = solve_spd(n, t, &diag, lambda, &neg) else {
            lambda *= 10.0;
            continue;
        };
        let trial: Vec<f64> = x.iter().zip(&step).map(|(a, b)| a + b).collect();
        let trial_fold = folds_in(&trial);
        let folds = trial_fold > fold;
        let trial_rows = weighted_residuals(pr, su, &trial, true, terms);
        let trial_cost = trial_rows.sum_sq();
        if trial_cost < cost && !folds {
            let small = norm(&step) <= 1e-12 * (1.0 + norm(x));
            let gain = (cost - trial_cost) / cost.max(1e-300);
            *x = trial;
            rows = trial_rows;
            cost = trial_cost;
            fold = trial_fold;
            lambda = (lambda / 3.0).max(1e-12);
            if small || gain < 1e-15 {
                break;
            }
        } else {
            lambda *= 4.0;
            if lambda > 1e12 {
                break;
            }
        }
    }
    iterations
}

/// Norm of the gradient of the objective of `terms` (no lengths) projected
/// onto the tangent space of the length constraints at `x`.
fn projected_gradient(pr: &FlatProblem, su: &Setup, x: &[f64], terms: &Terms) -> f64 {
    let g = weighted_residuals(pr, su, x, false, terms).gradient(x.len());
    let lr = lengths_only(pr, x);
    let m = lr.r.len();
    let jg: Vec<f64> = lr
        .entries
        .iter()
        .map(|row| row.iter().map(|&(c, v)| v * g[c]).sum())
        .collect();
    match solve_spd(m, jjt(&lr), &vec![0.0; m], 0.0, &jg) {
        Some(y) => {
            let mut gt = g.clone();
            for (row, yi) in lr.entries.iter().zip(&y) {
                for &(c, v) in row {
                    gt[c] -= v * yi;
                }
            }
            norm(&gt)
        }
        None => norm(&g),
    }
}

/// Make every length hold: minimum-norm Gauss–Newton steps through
/// (J_L J_Lᵀ) y = r_L, Δx = −J_Lᵀ y. Whether they hold to
/// [`LENGTH_TOLERANCE`], and the steps taken.
fn project_lengths(pr: &FlatProblem, x: &mut [f64]) -> (bool, usize) {
    let n = x.len();
    for step in 0..50 {
        if worst_length_error(pr, x) <= LENGTH_TOLERANCE {
            return (true, step);
        }
        let lr = lengths_only(pr, x);
        let m = lr.r.len();
        let Some(y) = solve_spd(m, jjt(&lr), &vec![0.0; m], 0.0, &lr.r) else {
            return (false, step);
        };
        let mut dx = vec![0.0; n];
        for (row, yi) in lr.entries.iter().zip(&y) {
            for &(c, v) in row {
                dx[c] -= v * yi;
            }
        }
        for (a, d) in x.iter_mut().zip(&dx) {
            *a += d;
        }
    }
    (worst_length_error(pr, x) <= LENGTH_TOLERANCE, 50)
}

/// J Jᵀ of constraint rows as lower-triangle triplets.
fn jjt(lr: &Rows) -> Vec<Triplet<usize, usize, f64>> {
    // Rows sharing a column couple; index rows by column.
    let mut by_col: HashMap<usize, Vec<(usize, f64)>> = HashMap::new();
    for (ri, row) in lr.entries.iter().enumerate() {
        for &(c, v) in row {
            by_col.entry(c).or_default().push((ri, v));
        }
    }
    let mut cols: Vec<_> = by_col.into_iter().collect();
    cols.sort_by_key(|c| c.0);
    let mut t = Vec::new();
    for (_, list) in cols {
        for &(ri, vi) in &list {
            for &(rj, vj) in &list {
                if ri >= rj {
                    t.push(Triplet::new(ri, rj, vi * vj));
                }
            }
        }
    }
    t
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn worst_length_error(pr: &FlatProblem, x: &[f64]) -> f64 {
    let mut worst: f64 = 0.0;
    for s in &pr.strips {
        for j in 0..s.lengths_mm.len() {
            let d = sub(p(x, s.nodes[j + 1]), p(x, s.nodes[j]));
            worst = worst.max((d[0].hypot(d[1]) - s.lengths_mm[j]).abs() / s.lengths_mm[j]);
        }
    }
    worst
}

#[allow(clippy::too_many_arguments)]
fn finish(
    pr: &FlatProblem,
    su: &Setup,
    x: &[f64],
    iterations: usize,
    start_energy: f64,
    start_objective: f64,
    objective: f64,
    gradient_norm: f64,
    length_ok: bool,
) -> FlatState {
    let nodes = pr
        .nodes
        .iter()
        .enumerate()
        .map(|(i, n)| {
            let angle_deg = if free_joint(pr, su, i) {
                n.erected_angle_deg
            } else {
                let [(sa, ka), (sb, kb)] = su.on[i];
                let (a0, a1) = chord(&pr.strips[sa], ka);
                let (b0, b1) = chord(&pr.strips[sb], kb);
                let psi = turn(sub(p(x, a1), p(x, a0)), sub(p(x, b1), p(x, b0)));
                psi.to_degrees().rem_euclid(180.0)
            };
            let rotation_deg =
                wrap_half((n.erected_angle_deg - angle_deg).to_radians()).to_degrees();
            FlatNode {
                node: n.id,
                position_mm: p(x, i),
                angle_deg,
                erected_angle_deg: n.erected_angle_deg,
                rotation_deg,
            }
        })
        .collect();
    let strips = pr
        .strips
        .iter()
        .map(|s| {
            let mut kappa: f64 = 0.0;
            for j in 1..s.nodes.len().saturating_sub(1) {
                let (a, b, c) = (s.nodes[j - 1], s.nodes[j], s.nodes[j + 1]);
                let phi = turn(sub(p(x, b), p(x, a)), sub(p(x, c), p(x, b)));
                kappa = kappa.max(phi.abs() / (0.5 * (s.lengths_mm[j - 1] + s.lengths_mm[j])));
            }
            let sigma = pr.youngs_modulus_mpa * kappa * 0.5 * pr.thickness_mm;
            FlatStrip {
                strip: s.id.clone(),
                max_curvature_per_mm: kappa,
                max_bending_stress_mpa: sigma,
                utilization: sigma / pr.design_strength_mpa,
            }
        })
        .collect();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for i in 0..pr.nodes.len() {
        let q = p(x, i);
        for k in 0..2 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    let max_length_error = worst_length_error(pr, x);
    FlatState {
        converged: length_ok && gradient_norm < 1e-6,
        iterations,
        energy_nmm: energy(pr, x),
        start_energy_nmm: start_energy,
        objective: (objective, start_objective),
        gradient_norm,
        max_length_error,
        nodes,
        strips,
        footprint_mm: if pr.nodes.is_empty() {
            [0.0, 0.0]
        } else {
            [hi[0] - lo[0], hi[1] - lo[1]]
        },
        least_rotation_deg: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A plane grid of straight strips, built by hand: 3 A strips of 4 nodes
    /// 300 mm apart along `u`, 4 B strips of 3 nodes 250 mm apart along
    /// `w`, at 70° to `u` counter-clockwise about the plane's normal `n`
    /// (tilted: (1, 2, 3)/√14). The node normals are `n`, or −n when
    /// `flipped` (then B turns 180° − 70° = 110° from A about them).
    fn tilted_grid(flipped: bool) -> FlatProblem {
        let n = DVec3::new(1.0, 2.0, 3.0).normalize();
        let u = n.any_orthonormal_vector();
        let w = 70f64.to_radians().cos() * u + 70f64.to_radians().sin() * n.cross(u);
        let origin = DVec3::new(1000.0, -2000.0, 500.0);
        let (normal, angle) = if flipped { (-n, 110.0) } else { (n, 70.0) };
        let mut nodes = Vec::new();
        for j in 0..3 {
            for i in 0..4 {
                nodes.push(FlatNodeIn {
                    id: 100 + nodes.len(),
                    position_world_mm: origin + 300.0 * i as f64 * u + 250.0 * j as f64 * w,
                    normal_world: normal,
                    erected_angle_deg: angle,
                    strip_a: j,
                    strip_b: 3 + i,
                });
            }
        }
        let mut strips: Vec<FlatStripIn> = (0..3)
            .map(|j| FlatStripIn {
                id: format!("A{j}"),
                family: Family::A,
                nodes: (0..4).map(|i| 4 * j + i).collect(),
                lengths_mm: vec![300.0; 3],
            })
            .collect();
        strips.extend((0..4).map(|i| FlatStripIn {
            id: format!("B{i}"),
            family: Family::B,
            nodes: (0..3).map(|j| 4 * j + i).collect(),
            lengths_mm: vec![250.0; 2],
        }));
        FlatProblem {
            nodes,
            strips,
            // Two steel lamellas 1.5 × 50 mm: 2 × 210 000 × 50 × 1.5³ / 12.
            ei_nmm2: 5_906_250.0,
            youngs_modulus_mpa: 210_000.0,
            thickness_mm: 1.5,
            design_strength_mpa: 355.0,
        }
    }

    /// The flat state of a plane grid is the grid itself: the same node
    /// distances (a rigid motion of it), the same angles, no joint turns,
    /// no strip bends.
    fn is_the_grid_itself(pr: &FlatProblem, angle_deg: f64) {
        let st = solve(pr);
        assert!(st.converged, "{st:?}");
        assert!(st.energy_nmm < 1e-9, "{}", st.energy_nmm);
        assert!(st.max_length_error < 1e-9, "{}", st.max_length_error);
        for (k, n) in st.nodes.iter().enumerate() {
            assert_eq!(n.node, 100 + k);
            assert!((n.angle_deg - angle_deg).abs() < 1e-6, "{n:?}");
            assert_eq!(n.erected_angle_deg, angle_deg);
            assert!(n.rotation_deg.abs() < 1e-6, "{n:?}");
        }
        for s in &st.strips {
            assert!(s.max_curvature_per_mm < 1e-9, "{s:?}");
            assert!(s.utilization < 1e-6, "{s:?}");
        }
        for (i, a) in pr.nodes.iter().enumerate() {
            for (j, b) in pr.nodes.iter().enumerate().skip(i + 1) {
                let (p, q) = (st.nodes[i].position_mm, st.nodes[j].position_mm);
                let flat = (p[0] - q[0]).hypot(p[1] - q[1]);
                let erected = a.position_world_mm.distance(b.position_world_mm);
                assert!(
                    (flat - erected).abs() < 1e-6,
                    "{i}-{j}: {flat} against {erected}"
                );
            }
        }
    }

    #[test]
    fn a_plane_grid_is_its_own_flat_state() {
        is_the_grid_itself(&tilted_grid(false), 70.0);
    }

    #[test]
    fn seen_from_the_normals_side_the_angles_keep_their_sense() {
        // Normals −n: from their side B turns 110° from A, flat as erected.
        is_the_grid_itself(&tilted_grid(true), 110.0);
    }
}
