//! The analyses of a frame and their verdict, per load combination.
//!
//! For every combination: a linear static solve (one factorisation for
//! all). For every ultimate (ULS) combination, also the critical load
//! factor α_cr and its first modes; where α_cr < [`ALPHA_CR_LIMIT`]
//! (EN 1993-1-1 §5.2.1(3): second-order effects must be considered), a
//! second-order analysis on the geometry imperfect in the shape of the first
//! mode, scaled so that its largest translation is the imperfection
//! amplitude, whose results replace the linear ones for that combination.
//!
//! A frame with tension-only cables is solved per combination by
//! [`super::tension`]'s active set; its buckling and second order hold
//! the cables as that solve leaves them.
//!
//! The verdict per lamella element and ULS combination: the cross-section
//! and member checks of [`super::verdict`] on the section forces of the
//! load plus the element's erection state ([`InitialForces`]), the larger
//! of the two kept; per serviceability (SLS) combination the largest
//! translation of any node against the deflection limit. The structure
//! fails when a utilisation exceeds 1, the grid buckles below the load
//! (α_cr ≤ 1) or second order does not converge, or a deflection exceeds
//! its limit.

use super::buckling::{critical_factors_given, BucklingMode};
use super::model::{
    BeamRole, CableState, Combination, FrameModel, InitialForces, LimitState, LoadSet,
};
use super::second_order::second_order_of;
use super::solve::{FrameError, LinearFrame, Reaction, SectionForces, StaticResult};
use super::tension::settle;
use super::verdict::{member_check, section_stress, Code, Forces, Rectangle};
use glam::DVec3;

/// Below this α_cr a combination is analysed to second order
/// (EN 1993-1-1 §5.2.1(3), elastic analysis).
pub const ALPHA_CR_LIMIT: f64 = 10.0;

/// How the elements are judged and the analyses run.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// The lamella section.
    pub section: Rectangle,
    /// E, MPa.
    pub youngs_mpa: f64,
    /// G, MPa.
    pub shear_mpa: f64,
    /// f_d for the cross-section check, MPa.
    pub design_strength_mpa: f64,
    /// The member-buckling rules.
    pub code: Code,
    /// Buckling modes computed per ULS combination.
    pub modes: usize,
    /// Largest translation allowed under an SLS combination, mm.
    pub deflection_limit_mm: f64,
    /// Amplitude of the initial imperfection (the first mode's largest
    /// translation), mm.
    pub imperfection_mm: f64,
    /// Relative tolerance of the second-order iteration.
    pub tolerance: f64,
    /// Whether second order runs where α_cr < [`ALPHA_CR_LIMIT`] (the
    /// verdict needs it; a bracing design's α_cr-only steps do not).
    pub second_order: bool,
}

/// The element that governs a combination.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Governing {
    /// The beam element (index into the model's beams).
    pub beam: usize,
    /// Its utilisation.
    pub utilisation: f64,
    /// Whether the member check (buckling between nodes) governs rather
    /// than the cross-section.
    pub member: bool,
}

/// One combination's results.
#[derive(Debug, Clone, PartialEq)]
pub struct CombinationResult {
    /// The combination's name.
    pub name: String,
    /// Its limit state.
    pub limit_state: LimitState,
    /// Node displacements (second order where it ran), mm and rad.
    pub displacements: Vec<[f64; 6]>,
    /// Support reactions, global.
    pub reactions: Vec<Reaction>,
    /// Every cable's force, N (0: slack).
    pub cable_forces_n: Vec<f64>,
    /// The sum of the applied loads, N.
    pub load_sum_n: DVec3,
    /// The largest translation of any node and that node.
    pub max_translation_mm: f64,
    /// The node of [`Self::max_translation_mm`].
    pub max_translation_node: usize,
    /// The first buckling modes (ULS only), ascending α_cr.
    pub buckling: Vec<BucklingMode>,
    /// Whether second order ran, and the iterations it took (`Some(0)`:
    /// it ran and did not converge, so the combination fails).
    pub second_order_iterations: Option<usize>,
    /// Per beam element: the larger of section and member utilisation
    /// (ULS; 0 for connecting pieces and SLS).
    pub utilisation: Vec<f64>,
    /// The governing element (ULS), if any lamella element exists.
    pub governing: Option<Governing>,
}

impl CombinationResult {
    /// The smallest critical load factor, if buckling was computed.
    pub fn alpha_cr(&self) -> Option<f64> {
        self.buckling.first().map(|m| m.factor)
    }
}

/// Every combination's results.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StructureResults {
    /// In the order of the combinations given.
    pub combinations: Vec<CombinationResult>,
}

impl StructureResults {
    /// The largest ULS utilisation: its combination, element and value.
    pub fn governing(&self) -> Option<(usize, usize, f64)> {
        let mut best: Option<(usize, usize, f64)> = None;
        for (c, r) in self.combinations.iter().enumerate() {
            if let Some(g) = r.governing {
                if best.is_none_or(|b| g.utilisation > b.2) {
                    best = Some((c, g.beam, g.utilisation));
                }
            }
        }
        best
    }

    /// The smallest α_cr over the ULS combinations and its combination.
    pub fn alpha_cr(&self) -> Option<(usize, f64)> {
        self.combinations
            .iter()
            .enumerate()
            .filter_map(|(c, r)| r.alpha_cr().map(|a| (c, a)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// The largest SLS translation: its combination, node and value.
    pub fn deflection(&self) -> Option<(usize, usize, f64)> {
        self.combinations
            .iter()
            .enumerate()
            .filter(|(_, r)| r.limit_state == LimitState::Serviceability)
            .map(|(c, r)| (c, r.max_translation_node, r.max_translation_mm))
            .max_by(|a, b| a.2.total_cmp(&b.2))
    }
}

/// Runs every analysis of every combination. `roles[i]` says what beam i
/// is (`None`: a connecting piece). Cables are tension-only.
pub fn analyse(
    model: &FrameModel,
    roles: &[Option<BeamRole>],
    combinations: &[Combination],
    settings: &Settings,
) -> Result<StructureResults, FrameError> {
    analyse_as(
        model,
        roles,
        combinations,
        settings,
        CableState::TensionOnly,
    )
}

/// [`analyse`] with the cables as `cables` says.
pub fn analyse_as(
    model: &FrameModel,
    roles: &[Option<BeamRole>],
    combinations: &[Combination],
    settings: &Settings,
    cables: CableState,
) -> Result<StructureResults, FrameError> {
    // Without cables, or with them held, one factorisation serves every
    // combination; tension-only cables settle their state per combination.
    let unbraced = if model.cables.is_empty() || cables == CableState::Held {
        Some(LinearFrame::with_cables(
            model,
            &vec![true; model.cables.len()],
        )?)
    } else {
        None
    };
    // The unbraced statics as the combinations are judged in turn: the
    // load cases solved together once and each combination their
    // factored sum (`solve::Statics`); each one's section forces made
    // then.
    let sets: Vec<&LoadSet> = combinations.iter().map(|c| &c.loads).collect();
    let statics = match &unbraced {
        Some(linear) => Some(linear.solve_each(&sets)?),
        None => None,
    };
    let mut out = Vec::with_capacity(combinations.len());
    for (index, combination) in combinations.iter().enumerate() {
        let braced;
        let (linear, first) = match (&unbraced, &statics) {
            (Some(linear), Some(statics)) => (linear, statics.result(index)?),
            _ => {
                let state;
                (braced, state) = settle(model, &combination.loads)?;
                (&braced, state.result)
            }
        };
        let (mut result, mut buckling, mut iterations) = (first, Vec::new(), None);
        if combination.limit_state == LimitState::Ultimate {
            buckling = critical_factors_given(linear, &combination.loads, &result, settings.modes)?;
            if let Some(mode) = buckling.first() {
                if settings.second_order && mode.factor > 1.0 && mode.factor < ALPHA_CR_LIMIT {
                    let imperfection = imperfection_of(mode, settings.imperfection_mm);
                    match second_order_of(
                        linear,
                        &combination.loads,
                        &imperfection,
                        settings.tolerance,
                        cables,
                    ) {
                        Ok(second) => {
                            iterations = Some(second.iterations);
                            result = second.result;
                        }
                        // Not shown stable to second order: the verdict fails
                        // (the linear results stay for the report).
                        Err(FrameError::NotConverged { .. } | FrameError::Unstable(_)) => {
                            iterations = Some(0);
                        }
                        Err(other) => return Err(other),
                    }
                }
            }
        }
        out.push(judge(
            model,
            roles,
            combination,
            settings,
            result,
            buckling,
            iterations,
        ));
    }
    Ok(StructureResults { combinations: out })
}

/// The first mode's translations scaled so the largest is `amplitude_mm`.
pub fn imperfection_of(mode: &BucklingMode, amplitude_mm: f64) -> Vec<DVec3> {
    let translation = |d: &[f64; 6]| DVec3::new(d[0], d[1], d[2]);
    let largest = mode
        .shape
        .iter()
        .map(|d| translation(d).length())
        .fold(0.0, f64::max);
    let scale = if largest > 0.0 {
        amplitude_mm / largest
    } else {
        0.0
    };
    mode.shape.iter().map(|d| translation(d) * scale).collect()
}

/// Load plus erection at one end of an element.
fn total(load: &SectionForces, initial: &InitialForces) -> Forces {
    Forces {
        axial_n: load.axial_n + initial.axial_n,
        torque_nmm: load.torque_nmm + initial.torque_nmm,
        moment_y_nmm: load.moment_y_nmm + initial.moment_y_nmm,
        moment_z_nmm: load.moment_z_nmm + initial.moment_z_nmm,
    }
}

fn judge(
    model: &FrameModel,
    roles: &[Option<BeamRole>],
    combination: &Combination,
    settings: &Settings,
    result: StaticResult,
    buckling: Vec<BucklingMode>,
    second_order_iterations: Option<usize>,
) -> CombinationResult {
    let load_sum_n = load_sum(model, &combination.loads);
    let (mut max_translation_mm, mut max_translation_node) = (0.0, 0);
    for (node, d) in result.displacements.iter().enumerate() {
        let t = DVec3::new(d[0], d[1], d[2]).length();
        if t > max_translation_mm {
            (max_translation_mm, max_translation_node) = (t, node);
        }
    }
    let mut utilisation = vec![0.0; model.beams.len()];
    let mut governing: Option<Governing> = None;
    if combination.limit_state == LimitState::Ultimate {
        for (i, beam) in model.beams.iter().enumerate() {
            let Some(role) = roles.get(i).and_then(|r| r.as_ref()) else {
                continue;
            };
            let forces = &result.beam_forces[i];
            let mut worst = (0.0, false);
            for end in [&forces.start, &forces.middle, &forces.end] {
                let f = total(end, &beam.initial);
                let section = section_stress(&settings.section, &f, role.trapeze_mpa).von_mises_mpa
                    / settings.design_strength_mpa;
                let member = member_check(
                    &settings.section,
                    settings.youngs_mpa,
                    settings.shear_mpa,
                    role.member_span_mm,
                    &f,
                    settings.code,
                )
                .utilisation;
                if section > worst.0 {
                    worst = (section, false);
                }
                if member > worst.0 {
                    worst = (member, true);
                }
            }
            utilisation[i] = worst.0;
            if governing.is_none_or(|g| worst.0 > g.utilisation) {
                governing = Some(Governing {
                    beam: i,
                    utilisation: worst.0,
                    member: worst.1,
                });
            }
        }
    }
    CombinationResult {
        name: combination.loads.name.clone(),
        limit_state: combination.limit_state,
        displacements: result.displacements,
        reactions: result.reactions,
        cable_forces_n: result.cable_forces_n,
        load_sum_n,
        max_translation_mm,
        max_translation_node,
        buckling,
        second_order_iterations,
        utilisation,
        governing,
    }
}

/// The resultant of a load set, N.
pub fn load_sum(model: &FrameModel, loads: &LoadSet) -> DVec3 {
    let mut sum = DVec3::ZERO;
    loads.for_each_node_load(|l, factor| sum += l.force_n * factor);
    let mut beams = DVec3::ZERO;
    loads.for_each_beam_load(|l, factor| {
        let b = &model.beams[l.beam];
        beams += l.force_n_per_mm * factor * b.length_mm(&model.nodes_mm);
    });
    sum + beams
}
