//! Second-order analysis: equilibrium on the geometry imperfect in a given
//! shape, with every element's geometric stiffness under its own axial
//! force (load plus erection), iterated until the axial forces settle.
//!
//! Each step solves (K + K_G(N_k))·u = P on the imperfect geometry
//! (the model's one symbolic factorisation, a new numeric one per step)
//! and takes N_{k+1} from u. The iteration stops when no element's axial force
//! changes by more than `tolerance` times the largest one (plus 1e-9 N).
//! Tension-only cables start taut and each step holds the set the last
//! step left taut (a cable whose force would be negative goes slack), with
//! the string's geometric stiffness N/L·(I − e·eᵀ) of its last force; the
//! iteration stops only when that set and the cables' forces have settled
//! too.
//! Under a load above the critical load the tangent stiffness is not
//! positive definite: [`FrameError::Unstable`] names the load set. The
//! section forces include the geometric stiffness' share (the P–Δ and
//! P–δ moments), and the displacements are measured from the imperfect
//! geometry.

use super::model::{CableState, FrameModel, LoadSet};
use super::solve::{
    add, axial_forces, factorise, factorise_definite, solve_refined, Assembly, FrameError,
    LinearFrame, StaticResult,
};
use glam::DVec3;

/// Most iterations.
pub const MAX_ITERATIONS: usize = 200;

/// A second-order solution.
#[derive(Debug, Clone, PartialEq)]
pub struct SecondOrderResult {
    /// Displacements from the imperfect geometry, section forces with the
    /// second-order moments, reactions.
    pub result: StaticResult,
    /// Iterations taken.
    pub iterations: usize,
}

/// Second order of `loads` on `model` with each node displaced by
/// `imperfection_mm` (empty: none), its cables tension-only.
pub fn second_order(
    model: &FrameModel,
    loads: &LoadSet,
    imperfection_mm: &[DVec3],
    tolerance: f64,
) -> Result<SecondOrderResult, FrameError> {
    second_order_as(
        model,
        loads,
        imperfection_mm,
        tolerance,
        CableState::TensionOnly,
    )
}

/// [`second_order`] with the cables as `cables` says: tension-only, or
/// held taut as bars whatever their force.
pub fn second_order_as(
    model: &FrameModel,
    loads: &LoadSet,
    imperfection_mm: &[DVec3],
    tolerance: f64,
    cables: CableState,
) -> Result<SecondOrderResult, FrameError> {
    let nodes = imperfect(model, imperfection_mm);
    let assembly = Assembly::new(model, &nodes)?;
    iterate(model, assembly, loads, tolerance, cables, false)
}

/// [`second_order_as`] on the model of `linear`, whose symbolic
/// factorisation and scatter plan it reuses (the imperfect geometry moves
/// the nodes, not the pattern: at 100 × 100 curves a new ordering and
/// symbolic factorisation cost 0.55 s).
pub fn second_order_of(
    linear: &LinearFrame<'_>,
    loads: &LoadSet,
    imperfection_mm: &[DVec3],
    tolerance: f64,
    cables: CableState,
) -> Result<SecondOrderResult, FrameError> {
    let model = linear.model();
    let nodes = imperfect(model, imperfection_mm);
    let assembly = linear.assembly.moved(model, &nodes)?;
    iterate(model, assembly, loads, tolerance, cables, true)
}

/// The model's nodes displaced by `imperfection_mm` (missing: none).
fn imperfect(model: &FrameModel, imperfection_mm: &[DVec3]) -> Vec<DVec3> {
    model
        .nodes_mm
        .iter()
        .enumerate()
        .map(|(i, p)| *p + imperfection_mm.get(i).copied().unwrap_or(DVec3::ZERO))
        .collect()
}

/// The iteration on the imperfect geometry `assembly` holds;
/// `mechanism_tested`: the model's stiffness on its perfect geometry has
/// passed the mechanism test (a [`LinearFrame`] of it was made), so the
/// first tangent need only be definite.
fn iterate(
    model: &FrameModel,
    assembly: Assembly,
    loads: &LoadSet,
    tolerance: f64,
    cables: CableState,
    mechanism_tested: bool,
) -> Result<SecondOrderResult, FrameError> {
    let nodes = &assembly.nodes_mm;
    let k = assembly.stiffness(model);
    let initial: Vec<f64> = model.beams.iter().map(|b| b.initial.axial_n).collect();
    // The imperfect elements carry the same total load as the perfect ones.
    let mut scaled = super::loads::flattened(loads);
    for l in scaled.beams.iter_mut() {
        let beam = &model.beams[l.beam];
        let perfect = beam.length_mm(&model.nodes_mm);
        let imperfect = beam.length_mm(nodes);
        if imperfect > 0.0 {
            l.force_n_per_mm *= perfect / imperfect;
        }
    }
    let loads = &scaled;
    let p_loads = assembly.load_vector(model, loads);
    // Every cable starts taut; each step takes the set the last left.
    let mut taut = vec![true; model.cables.len()];
    let mut cable_n = vec![0.0; model.cables.len()];
    let mut axial_load = vec![0.0; model.beams.len()];
    for iteration in 1..=MAX_ITERATIONS {
        let total: Vec<f64> = initial
            .iter()
            .zip(&axial_load)
            .map(|(a, b)| a + b)
            .collect();
        let mut kt = add(&k, &assembly.geometric(model, &total, None), 1.0);
        let mut p = p_loads.clone();
        if !model.cables.is_empty() {
            kt = add(&kt, &assembly.cable_stiffness(model, &taut), 1.0);
            kt = add(&kt, &assembly.cable_geometric(model, &cable_n), 1.0);
            let pull = assembly.cable_pull(model, &taut);
            p.iter_mut().zip(&pull).for_each(|(a, b)| *a += b);
        }
        // The first tangent is the model's own stiffness on the imperfect
        // geometry: a mechanism there is named, unless the perfect
        // geometry's has been tested (an imperfection of a fraction of the
        // span does not make a mechanism; four inverse iterations, 0.37 s
        // at 100 × 100 curves, saved). Later ones only need to be
        // definite: one that is not is the load above the critical one.
        let factor = if iteration == 1 && !mechanism_tested {
            factorise(&kt, &assembly.dofs)?
        } else {
            factorise_definite(&kt, &assembly.dofs)?
                .ok_or_else(|| FrameError::Unstable(loads.name.clone()))?
        };
        let x = solve_refined(&factor, &kt, &p)?;
        let would_be = assembly.cable_forces(model, &x);
        let forces: Vec<f64> = would_be
            .iter()
            .zip(&taut)
            .map(|(&n, &t)| if t { n } else { 0.0 })
            .collect();
        let result = assembly.results(model, loads, &x, Some(&total), &forces);
        let next_taut: Vec<bool> = match cables {
            CableState::TensionOnly => would_be.iter().map(|&n| n > 0.0).collect(),
            CableState::Held => taut.clone(),
        };
        let cables_settled = next_taut == taut
            && forces
                .iter()
                .zip(&cable_n)
                .all(|(a, b)| (a - b).abs() <= tolerance * a.abs().max(b.abs()) + 1e-9);
        taut = next_taut;
        cable_n = forces;
        let next = axial_forces(&result);
        let largest = next.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let change = next
            .iter()
            .zip(&axial_load)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        axial_load = next;
        if iteration > 1 && change <= tolerance * largest + 1e-9 && cables_settled {
            return Ok(SecondOrderResult {
                result,
                iterations: iteration,
            });
        }
    }
    Err(FrameError::NotConverged {
        what: format!("second order under {}", loads.name),
        iterations: MAX_ITERATIONS,
    })
}
