//! Diagonal cable bracing: which quads of the grid get cables, their
//! pretension and their size.
//!
//! A quadrilateral grid with rotationally stiff joints is a shell only as
//! far as its joints and strips resist the quads' shearing into rhombi;
//! a cable on a quad's diagonal resists it axially. The candidates are
//! the diagonals of every quad cell of the grid ([`super::build::grid_cells`];
//! the edge strips' triangles need none), between the joints' nodes. Each
//! cable is fixed at both ends to an eye plate under the node bolt: its
//! axis there is `fitting_offset_mm` from the node along the surface
//! normal (turned up) and `eye_plate.hole_spacing_mm` from the bolt towards
//! the other end (in the tangent plane), a point tied rigidly to the node
//! (the cable's offsets).
//!
//! # Layouts
//!
//! * `all`: every quad; `alternate`: every other quad, as a chessboard's
//!   black squares (coloured breadth first over the quads that share a
//!   side); with `single` diagonals one per quad, its direction
//!   alternating with the parity of the quad's first A strip in file
//!   order; `crossed`: both;
//! * `designed`: greedy. Starting from none, each step evaluates the
//!   braced frame (every combination, cables held taut as bars: the
//!   pretension keeps them so, [`CableState::Held`]), picks the target
//!   furthest from its value (α_cr, deflection, utilisation, each as a
//!   ratio to its target), and adds the candidate whose first-order effect
//!   on it is largest: for α_cr the strain energy the cable would take in
//!   the first mode, k·(e·Δφ)² (the Rayleigh quotient's derivative); for a
//!   deflection (or the governing element's node, for utilisation) the
//!   compliance change k·(e·Δu)·(e·Δw), Δw the cable's lengthening under a
//!   unit load along the node's displacement (an adjoint solve). Ties go
//!   to the first candidate. When every target is met, the chosen cables
//!   are tried for removal, last chosen first, each removed if the targets
//!   still hold without it; then, once sized and pretensioned, cable by
//!   cable in the frame as built (tension-only): one of a crossed pair may
//!   be all its quad needs. So removing any one cable left breaks a target.
//!   A target that no step has brought nearer for [`STALL_STEPS`] steps
//!   stops the design (the targets stay missed, and nothing is pruned).
//!
//! # Pretension and size
//!
//! Designed with the table's smallest cable (a crossed pair held as two
//! bars of half its area each: under a shear of its quad one lengthens by
//! what the other shortens, so the two halves are the one taut cable; a
//! step analyses only the combinations its targets need, one buckling
//! mode, second order only for a utilisation target). Then, size by size,
//! up the table: the pretension (`auto`) of single diagonals is the least
//! that keeps every cable taut under every combination, found from the
//! held model's forces N_c under each combination (no pretension) and
//! every cable's force r_c per newton of a pretension in all of them (one
//! more solve): T₀ = max(−N_c / r_c) × [`PRETENSION_MARGIN`]; a crossed
//! pair is snug (the design relies on the diagonal the load tightens);
//! either at least [`PRETENSION_FLOOR`] of the cable's design resistance
//! (a cable hangs visibly slack below that), rounded up to
//! [`PRETENSION_STEP_N`]. The frame is then analysed with its cables
//! tension-only; the size holds when no cable's force under a ULS
//! combination exceeds F_Rd = F_uk / γ (EN 1993-1-11 §6.3), else the next
//! size is tried; after the cable-by-cable pruning the remaining cables
//! are sized again from there up.

use super::analyse::{analyse, analyse_as, Settings, StructureResults};
use super::model::{BeamRole, Cable, CableState, Combination, FrameModel, LoadSet, NodeLoad};
use super::solve::{FrameError, LinearFrame};
use crate::analysis::Analysis;
use crate::loads::{BracingLayout, BracingSpec, Diagonals, Pretension};
use crate::network::{Family, Network};
use crate::profile::{Bracing, CableSize};
use glam::DVec3;
use std::collections::BTreeMap;

/// The automatic pretension is the least that keeps every cable taut,
/// times this.
pub const PRETENSION_MARGIN: f64 = 1.25;

/// The automatic pretension is at least this fraction of the cable's
/// design resistance.
pub const PRETENSION_FLOOR: f64 = 0.05;

/// Pretensions are rounded up to this, N.
pub const PRETENSION_STEP_N: f64 = 100.0;

/// Most steps of a designed layout (each adds one cable).
pub const MAX_DESIGN_STEPS: usize = 400;

/// A designed layout stops when this many steps in a row have not brought
/// the worst target nearer than before (bracing cannot reach it: the
/// grid's local buckling between nodes bounds α_cr, say).
pub const STALL_STEPS: usize = 10;

/// One candidate diagonal of a quad.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagonal {
    /// The quad: index into the grid's quads (see [`diagonals`]).
    pub quad: usize,
    /// Which of its two diagonals (0: corners 0–2, 1: corners 1–3).
    pub which: usize,
    /// Its corners, topology node ids (network node ids).
    pub corners: [usize; 2],
    /// Their model nodes.
    pub nodes: [usize; 2],
    /// Whether the quad is black on the chessboard.
    pub black: bool,
    /// Whether this is the diagonal a single-diagonal pattern takes.
    pub patterned: bool,
}

/// Every quad's two diagonals, in the order of the quads (sorted by their
/// corner sets) and then 0, 1. `node_ids` maps a network node id to its
/// model node.
pub fn diagonals(
    net: &Network,
    an: &Analysis,
    node_ids: &BTreeMap<String, usize>,
) -> Vec<Diagonal> {
    let topo = &an.topology;
    // A curve's rank in its family, in file order.
    let mut rank = vec![0usize; net.curves.len()];
    let mut next: BTreeMap<Family, usize> = BTreeMap::new();
    for (i, c) in net.curves.iter().enumerate() {
        let r = next.entry(c.family).or_insert(0);
        rank[i] = *r;
        *r += 1;
    }
    let model_node = |id: usize| node_ids.get(&id.to_string()).copied();
    let mut out = Vec::new();
    let quads: Vec<Vec<usize>> = super::build::grid_cells(an)
        .into_iter()
        .filter(|(corners, _)| corners.len() == 4)
        .map(|(corners, _)| corners)
        .collect();
    let colour = chessboard(&quads);
    for (quad, corners) in quads.iter().enumerate() {
        let a_rank = corners
            .iter()
            .map(|&c| rank[topo.nodes[c].a])
            .min()
            .unwrap_or(0);
        let black = colour[quad];
        for (which, (p, q)) in [(0, 2), (1, 3)].into_iter().enumerate() {
            let (Some(m), Some(n)) = (model_node(corners[p]), model_node(corners[q])) else {
                continue;
            };
            if m == n {
                continue;
            }
            out.push(Diagonal {
                quad,
                which,
                corners: [corners[p], corners[q]],
                nodes: [m, n],
                black,
                patterned: which == a_rank % 2,
            });
        }
    }
    out
}

/// Each quad black or white, no two quads that share a side (two
/// corners) alike where the grid allows: each connected patch coloured
/// breadth first from its first quad, which is black.
fn chessboard(quads: &[Vec<usize>]) -> Vec<bool> {
    let mut by_side: BTreeMap<(usize, usize), Vec<usize>> = BTreeMap::new();
    for (q, corners) in quads.iter().enumerate() {
        for k in 0..corners.len() {
            let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
            by_side.entry((a.min(b), a.max(b))).or_default().push(q);
        }
    }
    let mut colour: Vec<Option<bool>> = vec![None; quads.len()];
    for start in 0..quads.len() {
        if colour[start].is_some() {
            continue;
        }
        colour[start] = Some(true);
        let mut queue = std::collections::VecDeque::from([start]);
        while let Some(q) = queue.pop_front() {
            let c = colour[q].unwrap_or(true);
            let corners = &quads[q];
            for k in 0..corners.len() {
                let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
                for &n in &by_side[&(a.min(b), a.max(b))] {
                    if colour[n].is_none() {
                        colour[n] = Some(!c);
                        queue.push_back(n);
                    }
                }
            }
        }
    }
    colour.into_iter().map(|c| c.unwrap_or(true)).collect()
}

/// The candidates a layout takes outright (`designed`: none).
pub fn layout(candidates: &[Diagonal], spec: &BracingSpec) -> Vec<usize> {
    let quad_ok = |d: &Diagonal| match spec.layout {
        BracingLayout::All => true,
        BracingLayout::Alternate => d.black,
        BracingLayout::Designed => false,
    };
    let diagonal_ok = |d: &Diagonal| spec.diagonals == Diagonals::Crossed || d.patterned;
    (0..candidates.len())
        .filter(|&i| quad_ok(&candidates[i]) && diagonal_ok(&candidates[i]))
        .collect()
}

/// The cable on `d` of size `size` and pretension `pretension_n`, fixed
/// at its eye plates.
pub fn cable_on(
    d: &Diagonal,
    an: &Analysis,
    model: &FrameModel,
    brace: &Bracing,
    size: &CableSize,
    pretension_n: f64,
) -> Cable {
    let ends = d.nodes.map(|n| model.nodes_mm[n]);
    let offsets_mm: [DVec3; 2] = std::array::from_fn(|i| {
        let n = an.topology.nodes[d.corners[i]].normal_world;
        let n = if n.z < 0.0 { -n } else { n };
        let toward = ends[1 - i] - ends[i];
        let along = (toward - n * n.dot(toward)).normalize_or_zero();
        n * brace.fitting_offset_mm + along * brace.eye_plate.hole_spacing_mm
    });
    Cable {
        nodes: d.nodes,
        offsets_mm,
        area_mm2: size.area_mm2,
        e_mpa: brace.cable.youngs_modulus_mpa,
        pretension_n,
    }
}

/// The three figures a bracing is judged by.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Measure {
    /// The smallest α_cr of any ULS combination.
    pub alpha_cr: Option<f64>,
    /// The largest SLS translation, mm.
    pub deflection_mm: Option<f64>,
    /// The largest ULS utilisation of a lamella element.
    pub utilisation: Option<f64>,
}

impl Measure {
    /// The figures of `results`.
    pub fn of(results: &StructureResults) -> Measure {
        Measure {
            alpha_cr: results.alpha_cr().map(|a| a.1),
            deflection_mm: results.deflection().map(|d| d.2),
            utilisation: results.governing().map(|g| g.2),
        }
    }
}

/// Which target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// α_cr.
    AlphaCr,
    /// The SLS deflection.
    Deflection,
    /// The ULS utilisation.
    Utilisation,
}

impl Target {
    /// Its name in reports.
    pub fn as_str(self) -> &'static str {
        match self {
            Target::AlphaCr => "α_cr",
            Target::Deflection => "deflection",
            Target::Utilisation => "utilisation",
        }
    }
}

/// The targets as numbers: each a ratio that must be at most 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Goals {
    /// α_cr at least this.
    pub alpha_cr: Option<f64>,
    /// Deflection at most this, mm.
    pub deflection_mm: Option<f64>,
    /// Utilisation at most this.
    pub utilisation: Option<f64>,
}

impl Goals {
    /// The goals of `spec` with the deflection limit `deflection_limit_mm`.
    pub fn of(spec: &BracingSpec, deflection_limit_mm: f64) -> Goals {
        Goals {
            alpha_cr: spec.targets.alpha_cr,
            deflection_mm: spec.targets.deflection.then_some(deflection_limit_mm),
            utilisation: spec.targets.utilisation,
        }
    }

    /// Each target with its ratio (> 1: missed). A missing figure (no ULS
    /// combination, say) meets its target.
    pub fn ratios(&self, m: &Measure) -> Vec<(Target, f64)> {
        let mut out = Vec::new();
        if let (Some(goal), Some(a)) = (self.alpha_cr, m.alpha_cr) {
            out.push((Target::AlphaCr, goal / a.max(f64::MIN_POSITIVE)));
        }
        if let (Some(goal), Some(d)) = (self.deflection_mm, m.deflection_mm) {
            out.push((Target::Deflection, d / goal));
        }
        if let (Some(goal), Some(u)) = (self.utilisation, m.utilisation) {
            out.push((Target::Utilisation, u / goal));
        }
        out
    }

    /// Whether `m` meets every target.
    pub fn met(&self, m: &Measure) -> bool {
        self.ratios(m).iter().all(|&(_, r)| r <= 1.0)
    }

    /// The target furthest from its goal, if one is missed.
    pub fn worst(&self, m: &Measure) -> Option<Target> {
        self.ratios(m)
            .into_iter()
            .filter(|&(_, r)| r > 1.0)
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(t, _)| t)
    }
}

/// One step of a designed layout.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// The candidate added (index into the candidates), or removed.
    pub candidate: usize,
    /// Added (true) or removed in the pruning (false).
    pub added: bool,
    /// The target it was chosen for (added ones).
    pub target: Option<Target>,
    /// The figures after it.
    pub after: Measure,
}

/// What the frame and its loads are, for the bracing's analyses.
pub struct Frame<'a> {
    /// The network.
    pub net: &'a Network,
    /// Its analysis.
    pub an: &'a Analysis,
    /// The unbraced model, with its supports.
    pub model: &'a FrameModel,
    /// The beams' roles.
    pub roles: &'a [Option<BeamRole>],
    /// The combinations.
    pub combinations: &'a [Combination],
    /// The verdict's settings.
    pub settings: &'a Settings,
    /// Network node id → model node.
    pub node_ids: &'a BTreeMap<String, usize>,
    /// Whether the edge joints have a bolt (an eye plate needs one; the
    /// A×B nodes always have the node bolt a braced profile must give).
    pub edge_bolted: bool,
}

/// A bracing designed and sized.
#[derive(Debug, Clone)]
pub struct BracingDesign {
    /// The candidates: every quad's diagonals long enough for a cable's
    /// fittings ([`fittings_length_mm`]).
    pub candidates: Vec<Diagonal>,
    /// Diagonals left out: pin to pin no longer than the fittings (the
    /// terminal and the turnbuckle at mid take-up), so no wire between.
    pub too_short: usize,
    /// Diagonals left out: ending at an edge joint without a bolt to hold
    /// an eye plate.
    pub no_bolt: usize,
    /// The chosen ones, ascending, one cable each (the model's cables).
    pub chosen: Vec<usize>,
    /// The designed layout's steps (empty for a pattern).
    pub steps: Vec<Step>,
    /// The size, an index into the profile's table.
    pub size: usize,
    /// Whether even the table's largest size is overstressed.
    pub overstressed: bool,
    /// The pretension, N.
    pub pretension_n: f64,
    /// The braced model (cables tension-only).
    pub model: FrameModel,
    /// Its results, cables tension-only.
    pub results: StructureResults,
    /// The unbraced figures and the braced ones.
    pub before: Measure,
    /// The braced figures.
    pub after: Measure,
}

impl BracingDesign {
    /// Every cable's id: `C1`, `C2`, … in the order of the model's cables.
    pub fn cable_id(index: usize) -> String {
        format!("C{}", index + 1)
    }

    /// Both ends of every cable, (network node id, cable id), cable by
    /// cable: where the eye plates go.
    pub fn cable_ends(&self) -> Vec<(usize, String)> {
        self.chosen
            .iter()
            .enumerate()
            .flat_map(|(i, &d)| {
                self.candidates[d]
                    .corners
                    .map(|n| (n, BracingDesign::cable_id(i)))
            })
            .collect()
    }
}

/// `frame.model` with the cables on `chosen` of size `size`, pretension
/// `pretension_n`.
fn braced(
    frame: &Frame,
    candidates: &[Diagonal],
    chosen: &[usize],
    brace: &Bracing,
    size: &CableSize,
    pretension_n: f64,
) -> FrameModel {
    let mut model = frame.model.clone();
    model.cables = chosen
        .iter()
        .map(|&c| {
            cable_on(
                &candidates[c],
                frame.an,
                frame.model,
                brace,
                size,
                pretension_n,
            )
        })
        .collect();
    model
}

/// The design's model of `chosen`: held cables of `size`, crossed pairs
/// each at half the area (a pair under a shear of its quad: one lengthens
/// by what the other shortens, so two held halves are the one taut cable).
fn held(
    frame: &Frame,
    candidates: &[Diagonal],
    chosen: &[usize],
    brace: &Bracing,
    size: &CableSize,
    crossed: bool,
) -> FrameModel {
    let mut model = braced(frame, candidates, chosen, brace, size, 0.0);
    if crossed {
        for c in model.cables.iter_mut() {
            c.area_mm2 *= 0.5;
        }
    }
    model
}

/// The cable's lengthening under `displacements`, per unit (e·Δu at its
/// fixing points).
fn lengthening(c: &Cable, nodes_mm: &[DVec3], displacements: &[[f64; 6]]) -> f64 {
    let [a, b] = c.ends_mm(nodes_mm);
    let e = (b - a).normalize_or_zero();
    let at = |end: usize| {
        let d = &displacements[c.nodes[end]];
        let u = DVec3::new(d[0], d[1], d[2]);
        let theta = DVec3::new(d[3], d[4], d[5]);
        u + theta.cross(c.offsets_mm[end])
    };
    e.dot(at(1) - at(0))
}

/// The adjoint displacements: under a unit force on `node` along its
/// displacement `d` (zero if it does not move).
fn adjoint(
    linear: &LinearFrame,
    node: usize,
    d: &[f64; 6],
) -> Result<Option<Vec<[f64; 6]>>, FrameError> {
    let dir = DVec3::new(d[0], d[1], d[2]).normalize_or_zero();
    if dir == DVec3::ZERO {
        return Ok(None);
    }
    let loads = LoadSet {
        name: "unit".into(),
        nodes: vec![NodeLoad {
            node,
            force_n: dir,
            moment_nmm: DVec3::ZERO,
        }],
        ..LoadSet::default()
    };
    // The design's held model has no pretension to pull with.
    Ok(Some(linear.solve(&loads)?.displacements))
}

/// Each candidate's first-order effect on `target` in the frame `model`
/// (the held model of the current layout) with results `results`:
/// larger is better; `None` where the target has nothing to act on.
fn scores(
    model: &FrameModel,
    results: &StructureResults,
    target: Target,
    trial: &[Cable],
) -> Result<Vec<f64>, FrameError> {
    let nodes = &model.nodes_mm;
    let stiffness = |c: &Cable| c.stiffness_n_per_mm(nodes);
    match target {
        Target::AlphaCr => {
            let Some((c, _)) = results.alpha_cr() else {
                return Ok(vec![0.0; trial.len()]);
            };
            let shape = &results.combinations[c].buckling[0].shape;
            Ok(trial
                .iter()
                .map(|t| stiffness(t) * lengthening(t, nodes, shape).powi(2))
                .collect())
        }
        Target::Deflection | Target::Utilisation => {
            let (combination, node) = if target == Target::Deflection {
                match results.deflection() {
                    Some((c, node, _)) => (c, node),
                    None => return Ok(vec![0.0; trial.len()]),
                }
            } else {
                match results.governing() {
                    Some((c, beam, _)) => (c, model.beams[beam].nodes[0]),
                    None => return Ok(vec![0.0; trial.len()]),
                }
            };
            let u = &results.combinations[combination].displacements;
            let linear = LinearFrame::with_cables(model, &vec![true; model.cables.len()])?;
            let Some(w) = adjoint(&linear, node, &u[node])? else {
                return Ok(vec![0.0; trial.len()]);
            };
            Ok(trial
                .iter()
                .map(|t| stiffness(t) * lengthening(t, nodes, u) * lengthening(t, nodes, &w))
                .collect())
        }
    }
}

/// The analysis of `model` for the goals, its cables as `cables` says: only the serviceability
/// combinations when the deflection is the only target, no second order
/// unless the utilisation is one, one buckling mode.
fn evaluate(
    frame: &Frame,
    model: &FrameModel,
    goals: &Goals,
    cables: CableState,
) -> Result<StructureResults, FrameError> {
    let uls = goals.alpha_cr.is_some() || goals.utilisation.is_some();
    let combinations: Vec<Combination> = frame
        .combinations
        .iter()
        .filter(|c| uls || c.limit_state == super::model::LimitState::Serviceability)
        .cloned()
        .collect();
    let settings = Settings {
        modes: 1,
        second_order: goals.utilisation.is_some(),
        ..frame.settings.clone()
    };
    analyse_as(model, frame.roles, &combinations, &settings, cables)
}

/// The designed layout: greedy, then pruned (see the module doc). A unit
/// is one diagonal, or with crossed diagonals a quad's two.
fn design_layout(
    frame: &Frame,
    candidates: &[Diagonal],
    spec: &BracingSpec,
    goals: &Goals,
    brace: &Bracing,
    size: &CableSize,
) -> Result<(Vec<usize>, Vec<Step>), FrameError> {
    let crossed = spec.diagonals == Diagonals::Crossed;
    let mut units: Vec<Vec<usize>> = Vec::new();
    for (i, d) in candidates.iter().enumerate() {
        match units.last_mut() {
            Some(u) if crossed && candidates[u[0]].quad == d.quad => u.push(i),
            _ => units.push(vec![i]),
        }
    }
    let cables_of = |set: &[usize]| -> Vec<usize> {
        let mut v: Vec<usize> = set.iter().flat_map(|&u| units[u].iter().copied()).collect();
        v.sort_unstable();
        v
    };
    let mut chosen: Vec<usize> = Vec::new();
    let mut steps = Vec::new();
    let mut model = frame.model.clone();
    let mut results = evaluate(frame, &model, goals, CableState::Held)?;
    let (mut best_ratio, mut since_best) = (f64::INFINITY, 0);
    for _ in 0..MAX_DESIGN_STEPS {
        let m = Measure::of(&results);
        let Some(target) = goals.worst(&m) else {
            break;
        };
        let ratio = goals.ratios(&m).iter().map(|r| r.1).fold(0.0f64, f64::max);
        if ratio < best_ratio {
            (best_ratio, since_best) = (ratio, 0);
        } else {
            since_best += 1;
            if since_best >= STALL_STEPS {
                break;
            }
        }
        let open: Vec<usize> = (0..units.len())
            .filter(|&u| {
                !chosen.contains(&u)
                    && (crossed
                        || !chosen
                            .iter()
                            .any(|&c| candidates[units[c][0]].quad == candidates[units[u][0]].quad))
            })
            .collect();
        if open.is_empty() {
            break;
        }
        let trial_model = held(frame, candidates, &cables_of(&open), brace, size, crossed);
        let per_cable = scores(&model, &results, target, &trial_model.cables)?;
        // Each open unit's score: the sum over its cables (in the order
        // cables_of laid them out).
        let order = cables_of(&open);
        let mut unit_score = vec![0.0; open.len()];
        for (k, &u) in open.iter().enumerate() {
            for c in &units[u] {
                if let Ok(at) = order.binary_search(c) {
                    unit_score[k] += per_cable[at];
                }
            }
        }
        let mut best = 0;
        for (k, v) in unit_score.iter().enumerate() {
            if *v > unit_score[best] {
                best = k;
            }
        }
        let pick = open[best];
        chosen.push(pick);
        model = held(frame, candidates, &cables_of(&chosen), brace, size, crossed);
        results = evaluate(frame, &model, goals, CableState::Held)?;
        steps.push(Step {
            candidate: pick,
            added: true,
            target: Some(target),
            after: Measure::of(&results),
        });
    }
    // Prune, last chosen first (when the targets are met: otherwise no
    // cable can go).
    let met = goals.met(&Measure::of(&results));
    for pick in chosen.clone().into_iter().rev().filter(|_| met) {
        let without: Vec<usize> = chosen.iter().copied().filter(|&c| c != pick).collect();
        let model = held(
            frame,
            candidates,
            &cables_of(&without),
            brace,
            size,
            crossed,
        );
        let m = Measure::of(&evaluate(frame, &model, goals, CableState::Held)?);
        if goals.met(&m) {
            chosen = without;
            steps.push(Step {
                candidate: pick,
                added: false,
                target: None,
                after: m,
            });
        }
    }
    let cables = cables_of(&chosen);
    for s in steps.iter_mut() {
        s.candidate = units[s.candidate][0];
    }
    Ok((cables, steps))
}

/// The least pretension that keeps every cable of `model` (held, no
/// pretension) taut under every combination, with the margin, floor and
/// rounding of the module doc, N.
fn auto_pretension(
    model: &FrameModel,
    combinations: &[Combination],
    floor_n: f64,
) -> Result<f64, FrameError> {
    let held = vec![true; model.cables.len()];
    let linear = LinearFrame::with_cables(model, &held)?;
    let mut unit = model.clone();
    for c in unit.cables.iter_mut() {
        c.pretension_n = 1.0;
    }
    let unit_frame = LinearFrame::with_cables(&unit, &held)?;
    let per_newton = unit_frame.solve(&LoadSet::default())?.cable_forces_n;
    let mut need = 0.0f64;
    for combination in combinations {
        let forces = linear.solve(&combination.loads)?.cable_forces_n;
        for (n, r) in forces.iter().zip(&per_newton) {
            if *n < 0.0 && *r > 0.0 {
                need = need.max(-n / r);
            }
        }
    }
    Ok(snug((need * PRETENSION_MARGIN).max(floor_n)))
}

/// `t` rounded up to [`PRETENSION_STEP_N`].
fn snug(t: f64) -> f64 {
    (t / PRETENSION_STEP_N).ceil() * PRETENSION_STEP_N
}

/// The bracing `spec` asks for on `frame`, with the profile's cables
/// `brace`; `unbraced` the frame's results without cables.
pub fn design(
    frame: &Frame,
    spec: &BracingSpec,
    goals: &Goals,
    brace: &Bracing,
    unbraced: &StructureResults,
) -> Result<BracingDesign, FrameError> {
    let sizes = &brace.cable.sizes;
    let (bolted, no_bolt): (Vec<Diagonal>, Vec<Diagonal>) =
        diagonals(frame.net, frame.an, frame.node_ids)
            .into_iter()
            .partition(|d| frame.edge_bolted || !d.corners.iter().any(|&n| at_edge(frame.an, n)));
    let (candidates, too_short): (Vec<Diagonal>, Vec<Diagonal>) =
        bolted.into_iter().partition(|d| {
            let c = cable_on(d, frame.an, frame.model, brace, &sizes[0], 0.0);
            c.length_mm(&frame.model.nodes_mm) > fittings_length_mm(brace)
        });
    let (chosen, steps) = match spec.layout {
        BracingLayout::Designed => {
            design_layout(frame, &candidates, spec, goals, brace, &sizes[0])?
        }
        _ => (layout(&candidates, spec), Vec::new()),
    };
    let (size, pretension_n, mut model, mut results) =
        sized(frame, spec, brace, &candidates, &chosen, 0)?;
    let mut chosen = chosen;
    let mut steps = steps;
    if spec.layout == BracingLayout::Designed && goals.met(&Measure::of(&results)) {
        // Cable by cable, as built (tension-only, pretensioned): one of a
        // crossed pair may be all its quad needs.
        let mut removed = false;
        for i in (0..chosen.len()).rev() {
            let mut without = model.clone();
            without.cables.remove(i);
            let m = Measure::of(&evaluate(frame, &without, goals, CableState::TensionOnly)?);
            if goals.met(&m) {
                steps.push(Step {
                    candidate: chosen[i],
                    added: false,
                    target: None,
                    after: m,
                });
                chosen.remove(i);
                model = without;
                removed = true;
            }
        }
        if removed {
            results = analyse(&model, frame.roles, frame.combinations, frame.settings)?;
        }
    }
    // Fewer cables may carry more each: size again from this size up.
    let (mut size, mut pretension_n) = (size, pretension_n);
    if largest_uls_force_n(&results) > sizes[size].design_resistance_n(brace.cable.partial_factor) {
        (size, pretension_n, model, results) =
            sized(frame, spec, brace, &candidates, &chosen, size)?;
    }
    let overstressed =
        largest_uls_force_n(&results) > sizes[size].design_resistance_n(brace.cable.partial_factor);
    Ok(BracingDesign {
        candidates,
        too_short: too_short.len(),
        no_bolt: no_bolt.len(),
        chosen,
        steps,
        size,
        overstressed,
        pretension_n,
        before: Measure::of(unbraced),
        after: Measure::of(&results),
        model,
        results,
    })
}

/// The cables on `chosen` sized: from the table's size `from` up, the
/// first that takes the largest ULS force (else the largest), with its
/// pretension; its index, the pretension, the model and its results
/// (cables tension-only).
fn sized(
    frame: &Frame,
    spec: &BracingSpec,
    brace: &Bracing,
    candidates: &[Diagonal],
    chosen: &[usize],
    from: usize,
) -> Result<(usize, f64, FrameModel, StructureResults), FrameError> {
    let mut last = None;
    for (k, size) in brace.cable.sizes.iter().enumerate().skip(from) {
        let resistance_n = size.design_resistance_n(brace.cable.partial_factor);
        let pretension_n = match spec.pretension {
            Pretension::Kn(t) => t * 1000.0,
            // A crossed pair needs no more than snug: the design relies on
            // whichever of the two the load tightens.
            Pretension::Auto if spec.diagonals == Diagonals::Crossed => {
                snug(PRETENSION_FLOOR * resistance_n)
            }
            Pretension::Auto => {
                let held = braced(frame, candidates, chosen, brace, size, 0.0);
                auto_pretension(&held, frame.combinations, PRETENSION_FLOOR * resistance_n)?
            }
        };
        let model = braced(frame, candidates, chosen, brace, size, pretension_n);
        let results = analyse(&model, frame.roles, frame.combinations, frame.settings)?;
        let holds = largest_uls_force_n(&results) <= resistance_n;
        last = Some((k, pretension_n, model, results));
        if holds {
            break;
        }
    }
    last.ok_or_else(|| FrameError::Invalid("the profile lists no cable size".into()))
}

/// The largest cable force under any ULS combination, N.
pub fn largest_uls_force_n(results: &StructureResults) -> f64 {
    results
        .combinations
        .iter()
        .filter(|r| r.limit_state == super::model::LimitState::Ultimate)
        .flat_map(|r| r.cable_forces_n.iter().copied())
        .fold(0.0, f64::max)
}

/// One cable as the workshop makes and fits it.
#[derive(Debug, Clone, PartialEq)]
pub struct CableRow {
    /// Its id, `C1`, `C2`, … in the order of the model's cables.
    pub id: String,
    /// Its two joints, network node ids (the fixed end first, the
    /// turnbuckle's end second).
    pub nodes: [String; 2],
    /// Between the eye plates' pins in the erected grid, mm.
    pub length_mm: f64,
    /// The wire's unstressed cut length, mm (see [`wire_cut_length_mm`]).
    pub wire_mm: f64,
    /// Its pretension, N.
    pub pretension_n: f64,
    /// Its largest force under a ULS combination, N.
    pub max_force_n: f64,
    /// The combinations under which it is slack.
    pub slack_in: Vec<String>,
}

/// Whether topology node `n` is an edge node (not an A×B crossing).
fn at_edge(an: &Analysis, n: usize) -> bool {
    let family = |s: usize| an.strips.get(s).map(|s| s.family);
    an.topology
        .nodes
        .get(n)
        .is_some_and(|node| family(node.a) != Some(Family::A) || family(node.b) != Some(Family::B))
}

/// A cable's fittings from pin to pin, mm: the fixed end's terminal and
/// the turnbuckle at the middle of its take-up. A diagonal no longer than
/// this leaves no wire between them: it takes no cable.
pub fn fittings_length_mm(brace: &Bracing) -> f64 {
    brace.terminal_mm + brace.turnbuckle.mid_length_mm
}

/// The wire's unstressed cut length between its swaged terminal and the
/// turnbuckle, mm: the pin-to-pin length `length_mm` less the fixed
/// terminal and the turnbuckle at the middle of its take-up, over
/// 1 + T₀/(E·A) (the fittings taken as rigid).
pub fn wire_cut_length_mm(
    length_mm: f64,
    brace: &Bracing,
    size: &CableSize,
    pretension_n: f64,
) -> f64 {
    let strain = pretension_n / (brace.cable.youngs_modulus_mpa * size.area_mm2);
    (length_mm - fittings_length_mm(brace)) / (1.0 + strain)
}

/// Every cable of `design` on its `model` (the braced model) with its
/// `results`, as a schedule row.
pub fn schedule(
    design: &BracingDesign,
    model: &FrameModel,
    results: &StructureResults,
    brace: &Bracing,
) -> Vec<CableRow> {
    let size = &brace.cable.sizes[design.size];
    model
        .cables
        .iter()
        .zip(&design.chosen)
        .enumerate()
        .map(|(i, (c, &d))| {
            let length_mm = c.length_mm(&model.nodes_mm);
            let uls = results
                .combinations
                .iter()
                .filter(|r| r.limit_state == super::model::LimitState::Ultimate);
            CableRow {
                id: BracingDesign::cable_id(i),
                nodes: design.candidates[d].corners.map(|n| n.to_string()),
                length_mm,
                wire_mm: wire_cut_length_mm(length_mm, brace, size, c.pretension_n),
                pretension_n: c.pretension_n,
                max_force_n: uls.map(|r| r.cable_forces_n[i]).fold(0.0, f64::max),
                slack_in: results
                    .combinations
                    .iter()
                    .filter(|r| r.cable_forces_n[i] <= 0.0)
                    .map(|r| r.name.clone())
                    .collect(),
            }
        })
        .collect()
}
