//! plan.json `structure`: the erected grid as a frame under a loads file
//! (added by `lamella frame`, and by `lamella build --loads`).
//!
//! Plain data made once from a [`FrameReport`]: the verdict, the
//! governing items (utilisation, α_cr, deflection) named by strip,
//! station, network node and combination, one line per combination, the
//! envelope per strip, and the reactions at every support per combination
//! (for the foundation design). Forces in N, moments in N·mm, lengths in
//! mm. The drawing data of the assembly sheets' structure pages (every
//! lamella element, the deformed shape, the first buckling mode) is kept
//! beside it and not written to plan.json.

use super::convert::round;
use super::takeoff::BracingLine;
use crate::network::Network;
use crate::structure::model::LimitState;
use crate::structure::stage::FrameReport;
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The structure section of plan.json.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanStructure {
    /// The loads file's name (without its directory).
    pub loads: String,
    /// Every ULS utilisation ≤ 1, α_cr > 1 and second order converged for
    /// every ULS combination, every SLS deflection within its limit.
    pub passes: bool,
    /// The one-line verdict, as printed.
    pub verdict: String,
    /// The frame model's size.
    pub model: PlanFrameModel,
    /// The span the deflection limit and the imperfection refer to, mm.
    pub span_mm: f64,
    /// The SLS deflection limit, mm.
    pub deflection_limit_mm: f64,
    /// The second-order imperfection's amplitude (first mode), mm.
    pub imperfection_mm: f64,
    /// The smallest critical load factor over the ULS combinations.
    pub alpha_cr: Option<PlanAlphaCr>,
    /// The largest ULS utilisation (load plus erection).
    pub governing: Option<PlanGoverning>,
    /// The largest SLS translation.
    pub deflection: Option<PlanDeflection>,
    /// The characteristic load cases, in the loads file's order.
    pub load_cases: Vec<PlanLoadCase>,
    /// One per combination, in the order analysed (ULS first).
    pub combinations: Vec<PlanCombination>,
    /// Per A/B strip: its largest ULS utilisation over every combination,
    /// in plan strip order (strips without elements are left out).
    pub strips: Vec<PlanStripStructure>,
    /// Every support with its reaction under every combination.
    pub reactions: Vec<PlanReaction>,
    /// The diagonal cables, when the loads file asks for them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bracing: Option<PlanBracing>,
    /// What the structure pages draw. Not in plan.json.
    #[serde(skip)]
    pub drawing: Option<StructureDrawing>,
}

/// The bracing: layout, cable, figures before and after, the schedule.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanBracing {
    /// `all`, `alternate` or `designed`.
    pub layout: String,
    /// `single` or `crossed`.
    pub diagonals: String,
    /// The quads' diagonals it chose from.
    pub candidates: usize,
    /// Diagonals left out, no longer pin to pin than a cable's fittings.
    pub too_short: usize,
    /// Diagonals left out, ending at an edge joint without a bolt.
    pub no_bolt: usize,
    /// The strand.
    pub designation: String,
    /// Its diameter, mm.
    pub diameter_mm: f64,
    /// Its design resistance F_Rd = F_uk/γ, kN (3 decimals).
    pub design_resistance_kn: f64,
    /// The largest cable force under a ULS combination, kN.
    pub max_force_kn: f64,
    /// Whether that exceeds F_Rd of the table's largest size.
    pub overstressed: bool,
    /// The pretension of every cable, kN.
    pub pretension_kn: f64,
    /// Σ of the pin-to-pin lengths, m (3 decimals).
    pub total_length_m: f64,
    /// Σ of the wires' cut lengths, m.
    pub total_wire_m: f64,
    /// The targets (absent: not a target).
    pub targets: PlanFigures,
    /// The unbraced grid's figures.
    pub before: PlanFigures,
    /// The braced grid's.
    pub after: PlanFigures,
    /// How the designed layout went: every cable added (and the target it
    /// was added for) or removed, with the figures after it.
    pub steps: Vec<PlanBracingStep>,
    /// Every cable.
    pub cables: Vec<PlanCable>,
    /// What fixes them (the profile's `bracing`).
    pub fittings: PlanFittings,
}

/// The cables' fittings, mm.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanFittings {
    /// The cable's axis from the node along the surface normal.
    pub offset_mm: f64,
    /// Eye plates: one under the node bolt at each cable end.
    pub eye_plates: usize,
    /// Their thickness.
    pub eye_plate_thickness_mm: f64,
    /// Their width.
    pub eye_plate_width_mm: f64,
    /// Node bolt to the cable's pin.
    pub eye_plate_hole_spacing_mm: f64,
    /// The pin's hole.
    pub pin_hole_mm: f64,
    /// The node bolt's hole in the plate (the bolt and its clearance).
    pub bolt_hole_mm: f64,
    /// The eye plates' part id on the node bolt (`EP8`).
    pub eye_plate_part: String,
    /// The eye plate's design resistance to its cable's pull, kN (EN
    /// 1993-1-8 Table 3.9; 3 decimals).
    pub eye_plate_resistance_kn: f64,
    /// Swaged fork terminals (one per cable), pin to wire.
    pub terminal_mm: f64,
    /// Turnbuckles (one per cable), pin to wire at mid take-up.
    pub turnbuckle_mid_mm: f64,
    /// Their take-up, total.
    pub take_up_mm: f64,
}

/// α_cr, deflection, utilisation.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanFigures {
    /// The smallest ULS α_cr (4 decimals).
    pub alpha_cr: Option<f64>,
    /// The largest SLS translation, mm (4 decimals).
    pub deflection_mm: Option<f64>,
    /// The largest ULS utilisation (6 decimals).
    pub utilisation: Option<f64>,
}

/// A step of a designed layout.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanBracingStep {
    /// `add` or `remove`.
    pub action: String,
    /// The diagonal's joints, network node ids.
    pub nodes: [String; 2],
    /// The target it was added for.
    pub target: Option<String>,
    /// The figures after it (the design's model: cables held taut).
    pub after: PlanFigures,
}

/// One cable of the schedule.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanCable {
    /// `C1`, `C2`, …
    pub id: String,
    /// Its joints: the fixed terminal's, the turnbuckle's.
    pub nodes: [String; 2],
    /// Pin to pin in the erected grid, mm (2 decimals).
    pub length_mm: f64,
    /// The wire's unstressed cut length, mm (1 decimal).
    pub wire_cut_mm: f64,
    /// Pretension, kN.
    pub pretension_kn: f64,
    /// Largest ULS force, kN.
    pub max_force_kn: f64,
    /// The combinations it is slack under.
    pub slack_in: Vec<String>,
}

impl PlanFigures {
    fn of(m: &crate::structure::bracing::Measure) -> PlanFigures {
        PlanFigures {
            alpha_cr: m.alpha_cr.map(|a| round(a, 4)),
            deflection_mm: m.deflection_mm.map(|d| round(d, 4)),
            utilisation: m.utilisation.map(|u| round(u, 6)),
        }
    }
}

impl PlanBracing {
    /// The takeoff's bracing lines: one cable line (every cable is one
    /// size), a fork terminal and a turnbuckle per cable (the eye plates
    /// are parts, cut and nested: the takeoff's part lines).
    pub fn takeoff_lines(&self) -> Vec<BracingLine> {
        let b = self;
        let n = b.cables.len() as u64;
        let d = &b.diameter_mm;
        let f = &b.fittings;
        let line =
            |item: &str, designation: String, count: u64, length_mm, source: &str| BracingLine {
                item: item.into(),
                designation,
                count,
                length_mm,
                source: source.into(),
            };
        vec![
            line(
                "cable",
                format!("{} {d} mm", b.designation),
                n,
                Some(round(b.cables.iter().map(|c| c.wire_cut_mm).sum(), 1)),
                "bought",
            ),
            line(
                "fork terminal",
                format!(
                    "swaged fork for {d} mm strand, pin to wire {} mm",
                    f.terminal_mm
                ),
                n,
                None,
                "bought",
            ),
            line(
                "turnbuckle",
                format!(
                    "fork and swage for {d} mm strand, {} mm at mid take-up, take-up {} mm",
                    f.turnbuckle_mid_mm, f.take_up_mm
                ),
                n,
                None,
                "bought",
            ),
        ]
    }

    /// The plan section of a report's bracing.
    pub fn of(report: &FrameReport) -> Option<PlanBracing> {
        use crate::structure::bracing::{largest_uls_force_n, schedule};
        let b = report.bracing.as_ref()?;
        let d = &b.design;
        let size = &b.profile.cable.sizes[d.size];
        let rows = schedule(d, &report.built.model, &report.results, &b.profile);
        let kn = |n: f64| round(n / 1000.0, 3);
        let corners = |c: usize| d.candidates[c].corners.map(|n| n.to_string());
        Some(PlanBracing {
            layout: b.spec.layout.as_str().into(),
            diagonals: match b.spec.diagonals {
                crate::loads::Diagonals::Single => "single".into(),
                crate::loads::Diagonals::Crossed => "crossed".into(),
            },
            candidates: d.candidates.len(),
            too_short: d.too_short,
            no_bolt: d.no_bolt,
            designation: b.profile.cable.designation.clone(),
            diameter_mm: size.diameter_mm,
            design_resistance_kn: kn(size.design_resistance_n(b.profile.cable.partial_factor)),
            max_force_kn: kn(largest_uls_force_n(&report.results)),
            overstressed: d.overstressed,
            pretension_kn: kn(d.pretension_n),
            total_length_m: round(rows.iter().map(|r| r.length_mm).sum::<f64>() / 1000.0, 3),
            total_wire_m: round(rows.iter().map(|r| r.wire_mm).sum::<f64>() / 1000.0, 3),
            targets: PlanFigures {
                alpha_cr: b.goals.alpha_cr,
                deflection_mm: b.goals.deflection_mm.map(|x| round(x, 4)),
                utilisation: b.goals.utilisation,
            },
            before: PlanFigures::of(&d.before),
            after: PlanFigures::of(&d.after),
            steps: d
                .steps
                .iter()
                .map(|s| PlanBracingStep {
                    action: if s.added { "add" } else { "remove" }.into(),
                    nodes: corners(s.candidate),
                    target: s.target.map(|t| t.as_str().to_string()),
                    after: PlanFigures::of(&s.after),
                })
                .collect(),
            fittings: {
                let f = &b.profile;
                PlanFittings {
                    offset_mm: f.fitting_offset_mm,
                    eye_plates: 2 * rows.len(),
                    eye_plate_thickness_mm: f.eye_plate.thickness_mm,
                    eye_plate_width_mm: f.eye_plate.width_mm,
                    eye_plate_hole_spacing_mm: f.eye_plate.hole_spacing_mm,
                    pin_hole_mm: f.eye_plate.pin_hole_mm,
                    bolt_hole_mm: b.eye_plate_bolt_hole_mm,
                    eye_plate_part: b.eye_plate_id.clone(),
                    eye_plate_resistance_kn: kn(b.eye_plate_resistance_n),
                    terminal_mm: f.terminal_mm,
                    turnbuckle_mid_mm: f.turnbuckle.mid_length_mm,
                    take_up_mm: f.turnbuckle.take_up_mm,
                }
            },
            cables: rows
                .into_iter()
                .map(|r| PlanCable {
                    id: r.id,
                    nodes: r.nodes,
                    length_mm: round(r.length_mm, 2),
                    wire_cut_mm: round(r.wire_mm, 1),
                    pretension_kn: kn(r.pretension_n),
                    max_force_kn: kn(r.max_force_n),
                    slack_in: r.slack_in,
                })
                .collect(),
        })
    }
}

/// Counts of the frame model.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanFrameModel {
    /// Model nodes (joints, lamella and connector nodes).
    pub nodes: usize,
    /// Beam elements (lamella elements and stiff connecting pieces).
    pub beams: usize,
    /// Zero-length links (springs).
    pub links: usize,
    /// Supported nodes.
    pub supports: usize,
    /// Lamella elements per node-to-node span.
    pub elements_per_span: usize,
}

/// The smallest critical load factor.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanAlphaCr {
    /// α_cr (4 decimals).
    pub factor: f64,
    /// The ULS combination it belongs to.
    pub combination: String,
}

/// The governing utilisation.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanGoverning {
    /// Utilisation (6 decimals).
    pub utilisation: f64,
    /// The ULS combination.
    pub combination: String,
    /// The strip's id.
    pub strip: String,
    /// The lamella's number within its strip.
    pub lamella: u32,
    /// Station of the element's middle along the lamella, mm.
    pub station_mm: f64,
    /// `section` (EN 1993-1-1 §6.2 / EN 1995-1-1 §6.1) or `member`
    /// (buckling between nodes).
    pub check: String,
}

/// The largest SLS translation.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanDeflection {
    /// The translation, mm (4 decimals).
    pub translation_mm: f64,
    /// The SLS combination.
    pub combination: String,
    /// The network node nearest the model node that moves most.
    pub node: String,
}

/// One characteristic load case.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanLoadCase {
    /// Its name in the loads file.
    pub name: String,
    /// `permanent`, `snow`, `wind` or `imposed`.
    pub action: String,
    /// Σ of its loads, N.
    pub load_sum_n: [f64; 3],
}

/// One combination's results.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanCombination {
    /// Its name, e.g. `ULS 1.35G+1.5S+0.9W+`.
    pub name: String,
    /// `ULS` or `SLS`.
    pub limit_state: String,
    /// Σ applied loads, N.
    pub load_sum_n: [f64; 3],
    /// Σ support reactions, N (balances `load_sum_n`).
    pub reaction_sum_n: [f64; 3],
    /// Largest translation of any node, mm.
    pub max_translation_mm: f64,
    /// The network node nearest the model node that moves most.
    pub max_translation_node: String,
    /// The critical load factors of the first modes, ascending (ULS).
    pub alpha_cr: Vec<f64>,
    /// Second-order iterations where second order ran (α_cr < 10); null
    /// where it did not run.
    pub second_order_iterations: Option<usize>,
    /// Whether second order, where it ran, converged.
    pub second_order_converged: bool,
    /// Largest utilisation (ULS), 6 decimals.
    pub max_utilisation: Option<f64>,
    /// The strip of the largest utilisation (ULS).
    pub governing_strip: Option<String>,
}

/// One strip's envelope.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanStripStructure {
    /// The strip's id.
    pub id: String,
    /// Largest ULS utilisation of its elements (6 decimals).
    pub max_utilisation: f64,
    /// The combination of it.
    pub combination: String,
    /// The lamella of it.
    pub lamella: u32,
    /// Station of that element's middle along the lamella, mm.
    pub station_mm: f64,
}

/// A support and its reactions.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanReaction {
    /// The network node supported (or `model N` for a model node that is
    /// not a network node).
    pub node: String,
    /// Where, mm.
    pub position_mm: [f64; 3],
    /// What is held: `fixed`, `pinned`, `roller` or a list of DOF names.
    pub kind: String,
    /// Per combination (in `combinations` order): force N, moment N·mm.
    pub forces_n: Vec<[f64; 3]>,
    /// Per combination: moment, N·mm.
    pub moments_nmm: Vec<[f64; 3]>,
}

/// What the structure pages draw: every lamella element between two model
/// nodes, the deformed shape of the governing SLS combination and the
/// first buckling mode of the ULS combination with the smallest α_cr,
/// per model node (translations, mm; the mode normalised to a largest
/// translation of 1).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StructureDrawing {
    /// Model node positions, mm.
    pub nodes_mm: Vec<DVec3>,
    /// Lamella elements: their two model nodes, their largest ULS
    /// utilisation over every combination.
    pub elements: Vec<([usize; 2], f64)>,
    /// Supported model nodes and their kind (as in [`PlanReaction::kind`]).
    pub supports: Vec<(usize, String)>,
    /// The SLS combination drawn deformed, and its translations.
    pub deflection: Option<(String, Vec<DVec3>)>,
    /// The ULS combination whose first mode is drawn, α_cr, the mode.
    pub mode: Option<(String, f64, Vec<DVec3>)>,
    /// Every cable's pins (the schedule's order), mm.
    pub cables: Vec<[DVec3; 2]>,
    /// The eye plate's outline in its own frame (bolt hole at (w/2, w/2)),
    /// mm, when braced ([`crate::fabricate::eye_plate::eye_plate_outline`]).
    pub eye_plate_mm: Vec<[f64; 2]>,
}

fn limit_state_name(l: LimitState) -> &'static str {
    match l {
        LimitState::Ultimate => "ULS",
        LimitState::Serviceability => "SLS",
    }
}

fn v3(v: DVec3, decimals: i32) -> [f64; 3] {
    [
        round(v.x, decimals),
        round(v.y, decimals),
        round(v.z, decimals),
    ]
}

/// What a support holds, in words.
pub fn support_kind(fixed: &[bool; 6], along: Option<DVec3>) -> String {
    match (fixed, along) {
        (_, Some(_)) => "roller".into(),
        ([true, true, true, true, true, true], None) => "fixed".into(),
        ([true, true, true, false, false, false], None) => "pinned".into(),
        _ => crate::structure::solve::DOF_NAMES
            .iter()
            .zip(fixed)
            .filter(|(_, f)| **f)
            .map(|(n, _)| *n)
            .collect::<Vec<_>>()
            .join(" "),
    }
}

impl PlanStructure {
    /// The plan section of a frame report on `net`, its verdict line
    /// `verdict` and the loads file's name `loads`.
    pub fn of(report: &FrameReport, net: &Network, loads: &str, verdict: &str) -> PlanStructure {
        let model = &report.built.model;
        let roles = &report.built.roles;
        let results = &report.results.combinations;
        // Model node → network node id (joint nodes), and the nearest
        // network node for any other model node.
        let by_model: BTreeMap<usize, &str> = report
            .built
            .targets
            .node_ids
            .iter()
            .map(|(id, &m)| (m, id.as_str()))
            .collect();
        let joints: Vec<(DVec3, &str)> = by_model
            .iter()
            .map(|(&m, id)| (model.nodes_mm[m], *id))
            .collect();
        let node_name = |m: usize| -> String {
            if let Some(id) = by_model.get(&m) {
                return (*id).to_string();
            }
            let p = model.nodes_mm[m];
            joints
                .iter()
                .min_by(|a, b| a.0.distance_squared(p).total_cmp(&b.0.distance_squared(p)))
                .map(|j| j.1.to_string())
                .unwrap_or_else(|| format!("model {m}"))
        };
        let strip_id = |curve: usize| net.curves[curve].id.clone();
        let element = |beam: usize| roles.get(beam).and_then(|r| r.as_ref());

        let combinations: Vec<PlanCombination> = results
            .iter()
            .map(|r| {
                let reaction_sum: DVec3 = r.reactions.iter().map(|x| x.force_n).sum();
                PlanCombination {
                    name: r.name.clone(),
                    limit_state: limit_state_name(r.limit_state).into(),
                    load_sum_n: v3(r.load_sum_n, 3),
                    reaction_sum_n: v3(reaction_sum, 3),
                    max_translation_mm: round(r.max_translation_mm, 4),
                    max_translation_node: node_name(r.max_translation_node),
                    alpha_cr: r.buckling.iter().map(|m| round(m.factor, 4)).collect(),
                    second_order_iterations: r.second_order_iterations,
                    second_order_converged: r.second_order_iterations != Some(0),
                    max_utilisation: r.governing.map(|g| round(g.utilisation, 6)),
                    governing_strip: r
                        .governing
                        .and_then(|g| element(g.beam))
                        .map(|role| strip_id(role.strip)),
                }
            })
            .collect();

        let alpha_cr = report.alpha_cr().map(|(c, a)| PlanAlphaCr {
            factor: round(a, 4),
            combination: results[c].name.clone(),
        });
        let governing = report.governing().and_then(|(c, beam, u)| {
            let role = element(beam)?;
            let member = results[c].governing.is_some_and(|g| g.member);
            Some(PlanGoverning {
                utilisation: round(u, 6),
                combination: results[c].name.clone(),
                strip: strip_id(role.strip),
                lamella: role.lamella,
                station_mm: round(role.station_mm, 2),
                check: if member { "member" } else { "section" }.into(),
            })
        });
        let deflection = report.deflection().map(|(c, node, t)| PlanDeflection {
            translation_mm: round(t, 4),
            combination: results[c].name.clone(),
            node: node_name(node),
        });

        // The envelope per strip and per element over the ULS combinations.
        let mut per_element = vec![0.0f64; model.beams.len()];
        let mut per_strip: BTreeMap<usize, (f64, usize, usize)> = BTreeMap::new();
        for (c, r) in results.iter().enumerate() {
            if r.limit_state != LimitState::Ultimate {
                continue;
            }
            for (beam, &u) in r.utilisation.iter().enumerate() {
                let Some(role) = element(beam) else { continue };
                per_element[beam] = per_element[beam].max(u);
                let e = per_strip.entry(role.strip).or_insert((u, c, beam));
                if u > e.0 {
                    *e = (u, c, beam);
                }
            }
        }
        let strips = per_strip
            .iter()
            .filter_map(|(&strip, &(u, c, beam))| {
                let role = element(beam)?;
                Some(PlanStripStructure {
                    id: strip_id(strip),
                    max_utilisation: round(u, 6),
                    combination: results[c].name.clone(),
                    lamella: role.lamella,
                    station_mm: round(role.station_mm, 2),
                })
            })
            .collect();

        let reactions = model
            .supports
            .iter()
            .map(|s| {
                let at = |r: &crate::structure::analyse::CombinationResult| {
                    r.reactions
                        .iter()
                        .find(|x| x.node == s.node)
                        .map(|x| (x.force_n, x.moment_nmm))
                        .unwrap_or((DVec3::ZERO, DVec3::ZERO))
                };
                PlanReaction {
                    node: node_name(s.node),
                    position_mm: v3(model.nodes_mm[s.node], 3),
                    kind: support_kind(&s.fixed, s.along),
                    forces_n: results.iter().map(|r| v3(at(r).0, 3)).collect(),
                    moments_nmm: results.iter().map(|r| v3(at(r).1, 1)).collect(),
                }
            })
            .collect();

        let translation = |d: &[f64; 6]| DVec3::new(d[0], d[1], d[2]);
        let drawing = StructureDrawing {
            eye_plate_mm: report
                .bracing
                .as_ref()
                .map(|b| {
                    crate::fabricate::eye_plate::eye_plate_outline(&b.profile.eye_plate)
                        .into_iter()
                        .map(|p| [p.x, p.y])
                        .collect()
                })
                .unwrap_or_default(),
            cables: model
                .cables
                .iter()
                .map(|c| c.ends_mm(&model.nodes_mm))
                .collect(),
            nodes_mm: model.nodes_mm.clone(),
            elements: model
                .beams
                .iter()
                .enumerate()
                .filter(|(i, _)| element(*i).is_some())
                .map(|(i, b)| (b.nodes, per_element[i]))
                .collect(),
            supports: model
                .supports
                .iter()
                .map(|s| (s.node, support_kind(&s.fixed, s.along)))
                .collect(),
            deflection: report.deflection().map(|(c, _, _)| {
                (
                    results[c].name.clone(),
                    results[c].displacements.iter().map(translation).collect(),
                )
            }),
            mode: report.alpha_cr().and_then(|(c, a)| {
                let mode = results[c].buckling.first()?;
                let shape: Vec<DVec3> = mode.shape.iter().map(translation).collect();
                let largest = shape.iter().map(|v| v.length()).fold(0.0, f64::max);
                let scale = if largest > 0.0 { 1.0 / largest } else { 0.0 };
                Some((
                    results[c].name.clone(),
                    a,
                    shape.iter().map(|v| *v * scale).collect(),
                ))
            }),
        };

        let load_cases = report
            .cases
            .iter()
            .map(|(set, action)| PlanLoadCase {
                name: set.name.clone(),
                action: action.as_str().into(),
                load_sum_n: v3(crate::structure::analyse::load_sum(model, set), 3),
            })
            .collect();
        PlanStructure {
            loads: loads.to_string(),
            load_cases,
            passes: report.passes(),
            verdict: verdict.to_string(),
            model: PlanFrameModel {
                nodes: model.nodes_mm.len(),
                beams: model.beams.len(),
                links: model.links.len(),
                supports: model.supports.len(),
                elements_per_span: report.options.elements_per_span,
            },
            span_mm: round(report.span_mm, 2),
            deflection_limit_mm: round(report.settings.deflection_limit_mm, 4),
            imperfection_mm: round(report.settings.imperfection_mm, 4),
            alpha_cr,
            governing,
            deflection,
            combinations,
            strips,
            reactions,
            bracing: PlanBracing::of(report),
            drawing: Some(drawing),
        }
    }
}
