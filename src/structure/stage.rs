//! The structure stage: a network's frame under a loads file, every
//! combination analysed, and the verdict.
//!
//! The model is [`super::build`]'s (from the analysis and the kit), the
//! supports, load cases and combinations are [`super::loads`]'s, the
//! analyses and the element verdict are [`super::analyse`]'s. Settings
//! taken from the profile:
//!
//! * the lamella section t × h, E and G;
//! * the design strength f_d = k_mod·f_k/γ_M (k_mod = 1 for steel);
//! * the member rules: EN 1993-1-1 for a material without grain (f_y = f_k,
//!   γ_M1 = γ_M), EN 1995-1-1 for timber (k_mod, γ_M);
//! * the first [`MODES`] buckling modes per ULS combination;
//! * the second-order imperfection: the first mode scaled to span/300
//!   ([`IMPERFECTION_SPAN_OVER`]; the order of EN 1993-1-1 §5.3.2's bow
//!   imperfections e0/L = 1/300…1/150 for elastic analysis, taken over the
//!   grid's span because the first mode of a grid is global).

use super::analyse::{analyse, Settings, StructureResults};
use super::bracing::{design, BracingDesign, Frame, Goals};
use super::build::{build_frame, BuiltFrame, FrameOptions};
use super::loads::{
    combinations, combine, deflection_limit_mm, deflection_span_mm, load_cases, supports,
};
use super::model::{Combination, LoadSet};
use super::verdict::{Code, Rectangle};
use crate::analysis::Analysis;
use crate::error::{Error, Result};
use crate::fabricate::Kit;
use crate::loads::{Action, BracingSpec, LoadSpec};
use crate::network::Network;
use crate::profile::{Bracing, Grain, Profile};
use std::sync::Arc;

/// Buckling modes computed per ULS combination.
pub const MODES: usize = 6;

/// The second-order imperfection's amplitude: span over this.
pub const IMPERFECTION_SPAN_OVER: f64 = 300.0;

/// Relative tolerance of the second-order iteration (axial forces).
pub const SECOND_ORDER_TOLERANCE: f64 = 1e-4;

/// Everything the structure stage found.
#[derive(Debug, Clone)]
pub struct FrameReport {
    /// The model, its elements' roles and the load targets.
    pub built: BuiltFrame,
    /// How the model was meshed.
    pub options: FrameOptions,
    /// The characteristic load cases, in the loads file's order, with
    /// their actions.
    pub cases: Vec<(Arc<LoadSet>, Action)>,
    /// The combinations, as analysed.
    pub combinations: Vec<Combination>,
    /// How the elements were judged.
    pub settings: Settings,
    /// The span the deflection limit and the imperfection refer to, mm.
    pub span_mm: f64,
    /// Every combination's results (braced, when bracing was asked for).
    pub results: StructureResults,
    /// The bracing, when the loads file asks for it (its model and
    /// results are `built.model` and `results`).
    pub bracing: Option<BracedReport>,
}

/// A bracing as the structure stage designed it.
#[derive(Debug, Clone)]
pub struct BracedReport {
    /// What the loads file asked for.
    pub spec: BracingSpec,
    /// The targets.
    pub goals: Goals,
    /// The profile's cables and fittings.
    pub profile: Bracing,
    /// The layout, size, pretension and figures (its `model` and
    /// `results` moved into the report's).
    pub design: BracingDesign,
    /// The eye plates' design resistance to a cable's pull, N
    /// ([`Profile::eye_plate_resistance_n`]).
    pub eye_plate_resistance_n: f64,
    /// The node bolt's hole in an eye plate, mm (bolt and clearance).
    pub eye_plate_bolt_hole_mm: f64,
    /// The eye plates' part id on the node bolt (`EP8`).
    pub eye_plate_id: String,
}

impl BracedReport {
    /// Whether every cable and eye plate carries its largest ULS force
    /// (`force_n`).
    pub fn holds(&self, force_n: f64) -> bool {
        !self.design.overstressed && force_n <= self.eye_plate_resistance_n
    }
}

impl FrameReport {
    /// The largest ULS utilisation, its combination and element.
    pub fn governing(&self) -> Option<(usize, usize, f64)> {
        self.results.governing()
    }

    /// The smallest α_cr over the ULS combinations and its combination.
    pub fn alpha_cr(&self) -> Option<(usize, f64)> {
        self.results.alpha_cr()
    }

    /// The largest SLS translation, its combination and node.
    pub fn deflection(&self) -> Option<(usize, usize, f64)> {
        self.results.deflection()
    }

    /// The one-line verdict: PASS or FAIL with α_cr, the governing
    /// utilisation (strip, combination) and the largest deflection against
    /// its limit, e.g. `structure PASS: α_cr 4.28 (ULS …), utilisation
    /// 0.74 (A3, ULS …), deflection 21.0 mm ≤ 41.7 mm (SLS …)`.
    pub fn verdict_line(&self, strip_id: impl Fn(usize) -> String) -> String {
        let results = &self.results.combinations;
        let mut parts = Vec::new();
        match self.alpha_cr() {
            Some((c, a)) => parts.push(format!("α_cr {a:.2} ({})", results[c].name)),
            None => parts.push("α_cr not computed (no ULS combination)".into()),
        }
        if let Some((c, beam, u)) = self.governing() {
            let strip = self.built.roles[beam]
                .as_ref()
                .map(|r| strip_id(r.strip))
                .unwrap_or_else(|| format!("element {beam}"));
            parts.push(format!("utilisation {u:.2} ({strip}, {})", results[c].name));
        }
        if let Some((c, _, d)) = self.deflection() {
            let limit = self.settings.deflection_limit_mm;
            let sign = if d <= limit { "≤" } else { ">" };
            parts.push(format!(
                "deflection {d:.1} mm {sign} {limit:.1} mm ({})",
                results[c].name
            ));
        }
        if results.iter().any(|r| r.second_order_iterations == Some(0)) {
            parts.push("second order did not converge".into());
        }
        if let Some(b) = &self.bracing {
            let d = &b.design;
            let size = &b.profile.cable.sizes[d.size];
            let force = super::bracing::largest_uls_force_n(&self.results) / 1000.0;
            let resistance = size.design_resistance_n(b.profile.cable.partial_factor) / 1000.0;
            let sign = if force <= resistance { "≤" } else { ">" };
            let plate = b.eye_plate_resistance_n / 1000.0;
            let plate_sign = if force <= plate { "≤" } else { ">" };
            parts.push(format!(
                "{} cables ⌀{} mm, force {force:.2} kN {sign} {resistance:.2} kN, \
                 eye plate {plate_sign} {plate:.2} kN",
                d.chosen.len(),
                size.diameter_mm
            ));
        }
        let verdict = if self.passes() { "PASS" } else { "FAIL" };
        format!("structure {verdict}: {}", parts.join(", "))
    }

    /// Whether the grid stands: every ULS utilisation ≤ 1, α_cr > 1 for
    /// every ULS combination, every SLS deflection within the limit, every
    /// cable and its eye plates within their design resistance.
    pub fn passes(&self) -> bool {
        let strength = self.governing().is_none_or(|g| g.2 <= 1.0);
        let stability = self.alpha_cr().is_none_or(|a| a.1 > 1.0)
            && self
                .results
                .combinations
                .iter()
                .all(|r| r.second_order_iterations != Some(0));
        let deflection = self
            .deflection()
            .is_none_or(|d| d.2 <= self.settings.deflection_limit_mm);
        let cables = self
            .bracing
            .as_ref()
            .is_none_or(|b| b.holds(super::bracing::largest_uls_force_n(&self.results)));
        strength && stability && deflection && cables
    }
}

/// The settings a profile and a deflection limit give.
pub fn settings_of(profile: &Profile, deflection_limit_mm: f64, span_mm: f64) -> Settings {
    let m = &profile.material;
    let code = match m.grain {
        Grain::None => Code::Steel {
            yield_mpa: m.characteristic_strength_mpa,
            gamma_m1: m.partial_factor,
        },
        Grain::AlongStrip => Code::Timber {
            strength_mpa: m.characteristic_strength_mpa,
            k_mod: m.modification_factor,
            gamma_m: m.partial_factor,
        },
    };
    let k_mod = match m.grain {
        Grain::None => 1.0,
        Grain::AlongStrip => m.modification_factor,
    };
    Settings {
        section: Rectangle {
            thickness_mm: profile.section.thickness_mm,
            height_mm: profile.section.height_mm,
        },
        youngs_mpa: m.youngs_modulus_mpa,
        shear_mpa: m.shear_modulus_mpa,
        design_strength_mpa: k_mod * m.characteristic_strength_mpa / m.partial_factor,
        code,
        modes: MODES,
        deflection_limit_mm,
        imperfection_mm: span_mm / IMPERFECTION_SPAN_OVER,
        tolerance: SECOND_ORDER_TOLERANCE,
        second_order: true,
    }
}

/// The frame of `net` under `spec`: built, supported, loaded, analysed and
/// judged. A frame that is a mechanism under its supports is an error
/// naming the network node (or the model node) that moves.
pub fn run(
    net: &Network,
    an: &Analysis,
    profile: &Profile,
    kit: &Kit,
    spec: &LoadSpec,
    opts: &FrameOptions,
) -> Result<FrameReport> {
    let asked = match (&spec.bracing, &profile.bracing) {
        (Some(b), Some(cables)) => Some((b, cables)),
        (None, _) => None,
        (Some(_), None) => return Err(Error::input(
            &spec.source,
            crate::error::Location::Field("bracing".into()),
            format!(
                "asks for cables, but the profile {} has no `bracing` section (cable sizes and fittings)",
                profile.source.display()
            ),
        )),
    };
    let mut built = build_frame(net, an, profile, kit, opts)?;
    built.model.supports = supports(spec, &built.model, &built.targets)?;
    let cases = load_cases(spec, &built.model, &built.targets)?;
    let combinations: Vec<Combination> = combinations(spec)
        .iter()
        .map(|c| combine(&cases, c))
        .collect();
    let span_mm = deflection_span_mm(&built.model, &built.model.supports);
    let limit = deflection_limit_mm(spec, &built.model, &built.model.supports);
    let settings = settings_of(profile, limit, span_mm);
    let named = |e| named_error(e, &built, spec);
    let mut results =
        analyse(&built.model, &built.roles, &combinations, &settings).map_err(named)?;
    let mut bracing = None;
    if let Some((bspec, brace)) = asked {
        let goals = Goals::of(bspec, limit);
        let frame = Frame {
            net,
            an,
            model: &built.model,
            roles: &built.roles,
            combinations: &combinations,
            settings: &settings,
            node_ids: &built.targets.node_ids,
            edge_bolted: profile.edge_bolt_mm().is_some(),
        };
        let mut design = design(&frame, bspec, &goals, brace, &results).map_err(named)?;
        built.model = std::mem::take(&mut design.model);
        results = std::mem::take(&mut design.results);
        bracing = Some(BracedReport {
            spec: *bspec,
            goals,
            profile: brace.clone(),
            design,
            eye_plate_resistance_n: profile.eye_plate_resistance_n().unwrap_or(0.0),
            eye_plate_id: crate::fabricate::eye_plate::eye_plate_id(
                profile.node_bolt.as_ref().map_or(0.0, |b| b.diameter_mm),
            ),
            eye_plate_bolt_hole_mm: profile
                .node_bolt
                .as_ref()
                .map_or(0.0, |b| b.diameter_mm + b.hole_clearance_mm),
        });
    }
    let cases = cases
        .into_iter()
        .zip(&spec.cases)
        .map(|(set, case)| (set, case.action))
        .collect();
    Ok(FrameReport {
        built,
        options: *opts,
        cases,
        combinations,
        settings,
        span_mm,
        results,
        bracing,
    })
}

/// A frame error as the loads file's error, a mechanism named by its
/// network node.
fn named_error(e: super::solve::FrameError, built: &BuiltFrame, spec: &LoadSpec) -> Error {
    let what = match &e {
        super::solve::FrameError::Mechanism { node, dof } => {
            let id = built
                .targets
                .node_ids
                .iter()
                .find(|(_, &m)| m == *node)
                .map(|(id, _)| format!("network node {id}"))
                .unwrap_or_else(|| format!("model node {node} (a lamella or connector node)"));
            format!(
                "the frame is a mechanism under its supports: {id} moves freely ({})",
                super::solve::DOF_NAMES[*dof]
            )
        }
        other => other.to_string(),
    };
    Error::input(&spec.source, crate::error::Location::File, what)
}
