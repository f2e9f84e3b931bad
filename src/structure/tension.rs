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
//! step is a linear frame holding one state of the cables
//! ([`LinearFrame::with_cables`]: a new factorisation), so the solution
//! is exact
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
use super::model::{FrameModel, LoadSet};
use super::solve::{FrameError, LinearFrame, StaticResult};

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
    settle(model, loads).map(|(_, state)| state)
}

/// The cables' state under `loads`, and the linear frame that holds it.
pub(crate) fn settle<'m>(
    model: &'m FrameModel,
    loads: &LoadSet,
) -> Result<(LinearFrame<'m>, TensionOnlyResult), FrameError> {
    let mut taut = vec![true; model.cables.len()];
    for step in 1..=MAX_STEPS {
        let linear = LinearFrame::with_cables(model, &taut)?;
        let (result, would_be) = linear.solve_with_cables(loads)?;
        let next: Vec<bool> = would_be.iter().map(|&n| n > 0.0).collect();
        if next == taut {
            let state = TensionOnlyResult {
                result,
                taut,
                steps: step,
            };
            return Ok((linear, state));
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
    let (linear, _) = settle(model, loads)?;
    critical_factors_of(&linear, loads, modes)
}
