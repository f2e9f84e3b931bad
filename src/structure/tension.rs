//! Statics of a frame with tension-only cables (bracing).
//!
//! A cable carries N = T₀ + k·δ while taut and nothing while slack
//! ([`Cable`]), so the frame is no longer linear: which cables are taut
//! depends on the load, and superposition no longer holds (every load set
//! is solved as a whole). The active set is iterated: every cable starts
//! taut; the frame is solved with the taut cables' stiffness and their
//! pretensions' pull; every cable whose force would be negative is slack
//! in the next solve, and every slack cable whose chord has lengthened
//! past its unstressed length is taut again; until the set repeats. Each
//! step is a linear solve (a new factorisation), so the solution is exact
//! for its active set: the slack cables are shorter than their unstressed
//! length, the taut ones in tension.
//!
//! A frame that needs a slack cable to stand is a mechanism without it,
//! and is reported as one ([`FrameError::Mechanism`], naming the node).
//!
//! Buckling of a braced frame ([`critical_factors_braced`]) holds the
//! cables in the state the load set leaves them (a linear frame in which
//! the taut ones are bars, [`LinearFrame::with_cables`]); a taut cable's
//! tension adds the geometric stiffness of a string, N/L·(I − e·eᵀ).

use super::buckling::{critical_factors_of, BucklingMode};
use super::model::{Cable, FrameModel, LoadSet};
use super::solve::{
    add, factorise, solve_refined, validate_loads, Assembly, FrameError, LinearFrame, StaticResult,
};

/// Most active-set steps before giving up (a set that keeps changing).
pub const MAX_STEPS: usize = 50;

/// A solution with its cables' state.
#[derive(Debug, Clone, PartialEq)]
pub struct TensionOnlyResult {
    /// Displacements, reactions, section forces, cable forces
    /// ([`StaticResult::cable_forces_n`]: 0 for the slack ones).
    pub result: StaticResult,
    /// Per cable: taut.
    pub taut: Vec<bool>,
    /// Active-set steps taken (linear solves).
    pub steps: usize,
}

/// The static solution of `model` under `loads` with its cables taut or
/// slack as the load makes them.
pub fn solve_tension_only(
    model: &FrameModel,
    loads: &LoadSet,
) -> Result<TensionOnlyResult, FrameError> {
    validate_loads(model, loads)?;
    let assembly = Assembly::new(model, &model.nodes_mm)?;
    let mut frame = assembly.stiffness(model);
    let initial_axial: Vec<f64> = model.beams.iter().map(|b| b.initial.axial_n).collect();
    if initial_axial.iter().any(|&n| n != 0.0) {
        frame = add(
            &frame,
            &assembly.geometric(model, &initial_axial, None),
            1.0,
        );
    }
    let (p, _) = assembly.load_vector(model, loads);
    let mut taut = vec![true; model.cables.len()];
    for step in 1..=MAX_STEPS {
        let k = add(&frame, &assembly.cable_stiffness(model, &taut), 1.0);
        let pull = assembly.cable_pull(model, &taut);
        let rhs: Vec<f64> = p.iter().zip(&pull).map(|(a, b)| a + b).collect();
        let (factor, _) = factorise(&k, &assembly.dofs, None)?;
        let x = solve_refined(&factor, &k, &rhs)?;
        let would_be = assembly.cable_forces(model, &x);
        let next: Vec<bool> = would_be.iter().map(|&n| n > 0.0).collect();
        if next == taut {
            let forces: Vec<f64> = would_be
                .iter()
                .zip(&taut)
                .map(|(&n, &t)| if t { n } else { 0.0 })
                .collect();
            return Ok(TensionOnlyResult {
                result: assembly.results(model, loads, &x, None, &forces),
                taut,
                steps: step,
            });
        }
        taut = next;
    }
    Err(FrameError::NotConverged {
        what: format!("the cables' taut set under {}", loads.name),
        iterations: MAX_STEPS,
    })
}

/// The `modes` smallest critical load factors of `loads` on the braced
/// `model`: its cables held in the state the tension-only solve finds
/// under `loads` (taut ones as bars, slack ones absent), the geometric
/// stiffness of the members' and the taut cables' forces under the load
/// set scaled by λ. The pretension's share of those forces is scaled with
/// the load, which is exact for a cable set that only the load tightens
/// and slightly conservative for members the pretension compresses.
pub fn critical_factors_braced(
    model: &FrameModel,
    loads: &LoadSet,
    modes: usize,
) -> Result<Vec<BucklingMode>, FrameError> {
    let state = solve_tension_only(model, loads)?;
    let linear = LinearFrame::with_cables(model, &state.taut)?;
    critical_factors_of(&linear, loads, modes)
}

/// The unstressed length of each of `model`'s cables, mm
/// ([`Cable::unstressed_length_mm`]).
pub fn unstressed_lengths_mm(model: &FrameModel) -> Vec<f64> {
    model
        .cables
        .iter()
        .map(|c: &Cable| c.unstressed_length_mm(&model.nodes_mm))
        .collect()
}
