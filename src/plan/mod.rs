//! plan.json, schema `lamella-plan/3`: the single source of truth every later
//! output is drawn from. Later stages add fields; they never rename these.
//! Numbers are rounded to fixed precision so the file is byte-stable.

use crate::analysis::Analysis;
use crate::check::{CheckReport, LamellaCheck, StripCheck, Suggestion};
use crate::error::{Error, Result};
use crate::network::Network;
use crate::plan::model::Model;
use crate::profile::{JointSystem, Profile};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::Path;

pub mod model;
pub mod resolved;
pub mod sparrow;
pub mod takeoff;

/// The schema name written into every plan; later stages add fields, never rename.
pub const SCHEMA: &str = "lamella-plan/3";

/// The whole plan.json: what the network is, every strip and node, the
/// warnings and, after `check`, the profile and the verdict. Lengths in mm,
/// angles in degrees, stresses in MPa, curvature and twist per metre; numbers
/// rounded to fixed decimals (lengths 4, angles 6) so equal inputs give equal bytes.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Plan {
    /// Always [`SCHEMA`] (`lamella-plan/3`).
    pub schema: String,
    /// `lamella` and the version that wrote the file.
    pub generator: String,
    /// Always `mm`: every length in the file.
    pub units: String,
    /// The network read: name, file, units, tolerance.
    pub network: NetworkSummary,
    /// Counts and extremes over the whole network.
    pub summary: Summary,
    /// One per curve, in network file order (edges included).
    pub strips: Vec<PlanStrip>,
    /// Every node, in node id order.
    pub nodes: Vec<PlanNode>,
    /// The topology warnings, in the order found.
    pub warnings: Vec<PlanWarning>,
    /// The resolved material profile (added by `check`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<PlanProfile>,
    /// The elastic check's verdict (added by `check`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub check: Option<PlanCheckSummary>,
    /// Every part to cut (added by `parts`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parts: Option<Vec<PlanPart>>,
    /// Counts by kind, lamella length and mass (added by `parts`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parts_summary: Option<PlanKitSummary>,
    /// The single-stroke font the parts' engraving is set in: every
    /// character and mark engraved (added by `parts`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub engraving_font: Option<PlanFont>,
    /// The sheets the parts are nested on (added by `nest`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sheets: Option<Vec<PlanSheet>>,
    /// The nest's figures (added by `nest`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nesting: Option<PlanNesting>,
    /// The flat assembly state (added by `flat`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flat: Option<PlanFlat>,
}

/// The flat state of an interlocking grid (`lamella flat`).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanFlat {
    /// Lengths held and the projected gradient at rest.
    pub converged: bool,
    /// Solver iterations (minimisation and projection steps).
    pub iterations: usize,
    /// Bending energy of the flat state, N·mm.
    pub energy: f64,
    /// The same of the starting guess, N·mm.
    pub start_energy: f64,
    /// Projected gradient norm, relative to the start's.
    pub gradient_norm: f64,
    /// Largest relative node-to-node length error.
    pub max_length_error: f64,
    /// Largest |rotation| from flat to erected, degrees.
    pub max_rotation_deg: f64,
    /// Extent of the layout, [x, y] mm.
    pub footprint_mm: [f64; 2],
    /// Per A×B node.
    pub nodes: Vec<PlanFlatNode>,
    /// Per A/B strip.
    pub strips: Vec<PlanFlatStrip>,
}

/// A node of the flat state.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanFlatNode {
    /// Node id.
    pub node: usize,
    /// Floor position, [x, y] mm.
    pub position_mm: [f64; 2],
    /// Oriented angle A → B while flat, degrees in [0, 180).
    pub angle_deg: f64,
    /// Erected − flat, degrees.
    pub rotation_deg: f64,
    /// The angles A → B the joint passes through from flat to erected,
    /// [low, high] degrees.
    pub angle_range_deg: [f64; 2],
}

/// A strip of the flat state.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanFlatStrip {
    /// Strip id.
    pub strip: String,
    /// Largest in-plane bending stress while flat, MPa.
    pub max_bending_stress_mpa: f64,
    /// That over the design strength.
    pub utilization: f64,
}

/// Add the flat state to a plan.
pub fn add_flat(plan: &mut Plan, st: &crate::flat::FlatState) {
    plan.flat = Some(PlanFlat {
        converged: st.converged,
        iterations: st.iterations,
        energy: round(st.energy_nmm, 6),
        start_energy: round(st.start_energy_nmm, 6),
        gradient_norm: st.gradient_norm,
        max_length_error: st.max_length_error,
        max_rotation_deg: round(
            st.max_rotation()
                .map_or(0.0, |i| st.nodes[i].rotation_deg.abs()),
            DEG,
        ),
        footprint_mm: [round(st.footprint_mm[0], MM), round(st.footprint_mm[1], MM)],
        nodes: st
            .nodes
            .iter()
            .map(|n| PlanFlatNode {
                node: n.node,
                position_mm: [round(n.position_mm[0], MM), round(n.position_mm[1], MM)],
                angle_deg: round(n.angle_deg, DEG),
                rotation_deg: round(n.rotation_deg, DEG),
                angle_range_deg: {
                    let (a, b) = (n.angle_deg, n.angle_deg + n.rotation_deg);
                    [round(a.min(b), DEG), round(a.max(b), DEG)]
                },
            })
            .collect(),
        strips: st
            .strips
            .iter()
            .map(|s| PlanFlatStrip {
                strip: s.strip.clone(),
                max_bending_stress_mpa: round(s.max_bending_stress_mpa, MPA),
                utilization: round(s.utilization, UTIL),
            })
            .collect(),
    });
}

/// One sheet of stock with its placements.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanSheet {
    /// `S01`, `S02`, …
    pub id: String,
    /// Sheet width (its y), mm.
    pub width_mm: f64,
    /// Sheet length (its x), mm (a coil piece: the length cut).
    pub length_mm: f64,
    /// Net part area over the sheet's area.
    pub utilization: f64,
    /// The stock size: its name, else `length × width` (`3000 × 1500`).
    pub stock: String,
    /// What the sheet costs, if priced (a coil per metre: the length cut).
    pub price_per_unit: Option<f64>,
    /// Every part cut from it: part-local (x, y) turned by `rotation_deg`
    /// counter-clockwise about the origin, then moved by (x_mm, y_mm).
    pub placements: Vec<PlanPlacement>,
}

/// One copy of a part on a sheet.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanPlacement {
    /// Part id.
    pub part: String,
    /// Which copy, from 0.
    pub copy: u32,
    /// Translation, mm.
    pub x_mm: f64,
    /// Translation, mm.
    pub y_mm: f64,
    /// Rotation, degrees counter-clockwise.
    pub rotation_deg: u32,
}

/// The nest's figures (the time is printed, not written: plan.json stays
/// byte-stable).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanNesting {
    /// Sheets with parts on them.
    pub sheets_used: usize,
    /// The larger of the two bounds below.
    pub lower_bound_sheets: usize,
    /// ⌈Σ part area / usable sheet area⌉.
    pub area_bound_sheets: usize,
    /// ⌈Martello–Toth L2 of the lamella lanes / lanes per sheet⌉.
    pub lane_bound_sheets: usize,
    /// Lanes across one sheet.
    pub lanes_per_sheet: usize,
    /// Lanes the lamellas fill, and L2's bound on them.
    pub lanes_used: usize,
    /// Martello–Toth L2 on the lanes.
    pub lane_bound_lanes: usize,
    /// Part area over the area of the sheets used.
    pub utilization: f64,
    /// Sheets per stock size used, in the profile's order.
    pub stock_used: Vec<PlanStockUse>,
    /// Σ of the sheets' prices, when every size is priced.
    pub total_cost: Option<f64>,
    /// A lower bound on that cost (README, *Nesting*).
    pub cost_bound: Option<f64>,
    /// Currency of the prices.
    pub currency: Option<String>,
    /// A coil: the length cut from it, mm, in whole length steps.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coil_length_mm: Option<f64>,
    /// A coil: a lower bound on that length, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coil_length_bound_mm: Option<f64>,
}

/// The sheets of one stock size in a nest.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanStockUse {
    /// The size's name, else `length × width`.
    pub stock: String,
    /// Sheets (coil: pieces) of it.
    pub sheets: usize,
    /// Their width, mm.
    pub width_mm: f64,
    /// Σ of their lengths, mm.
    pub length_mm: f64,
    /// Price of one sheet, if priced.
    pub price_per_unit: Option<f64>,
    /// What they cost, if priced.
    pub cost: Option<f64>,
}

/// One part in plan.json: part-local mm, outline counter-clockwise; round
/// holes are its `hole` features (cut as circles), other inner contours
/// its `holes`, clockwise; engraving texts and marks in the plan's
/// [`PlanFont`].
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanPart {
    /// Unique part id (also engraved).
    pub id: String,
    /// `lamella`, `shear_block`, `washer`, `stud`, `splice_plate` or `edge_strip`.
    pub kind: Name,
    /// The strip it belongs to, if any.
    pub strip: Option<String>,
    /// Lamella number within the strip, if any.
    pub lamella: Option<u32>,
    /// How many identical parts.
    pub count: u32,
    /// Extent along the part's x, mm.
    pub length_mm: f64,
    /// Extent along the part's y, mm.
    pub height_mm: f64,
    /// Station on the part's own line at x = 0, mm (lamellas, edge strips).
    pub station_start_mm: Option<f64>,
    /// Closed outline, counter-clockwise, [x, y] mm.
    pub outline: Vec<[f64; 2]>,
    /// Closed inner contours other than the round holes (those are the
    /// `hole` features), clockwise, [x, y] mm.
    pub holes: Vec<Vec<[f64; 2]>>,
    /// Texts and marks engraved, in the plan's `engraving_font`.
    pub engraving: Vec<PlanEngraving>,
    /// Slots and holes, by x.
    pub features: Vec<PlanFeature>,
}

/// One engraving of a part: a text or a mark of the plan's
/// [`PlanFont`] at `height_mm`, its box's lower left at `at_mm`. The k-th
/// glyph of a text starts at x_k (x_0 = 0, x_(k+1) = x_k + (width_k +
/// letter_spacing)); each stroke point (gx, gy) of it is engraved at
/// `at_mm` + `height_mm` × (x_k + gx, gy); a mark's at `at_mm` +
/// `height_mm` × (gx, gy).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanEngraving {
    /// The text, if a text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub text: Option<String>,
    /// The mark (`orientation`), if a mark.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mark: Option<Name>,
    /// Lower left of its box (a text's baseline start), part frame, mm.
    pub at_mm: [f64; 2],
    /// Cap height of a text, whole height of a mark, mm.
    pub height_mm: f64,
}

/// The single-stroke engraving font, as far as the plan's parts use it.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanFont {
    /// The font's name.
    pub name: String,
    /// The gap between two glyph boxes, in cap heights.
    pub letter_spacing: f64,
    /// Every character engraved (a character without a glyph of its own
    /// has the fallback box), by character.
    pub glyphs: std::collections::BTreeMap<String, PlanGlyph>,
    /// Every mark engraved, by name (`orientation`).
    pub marks: std::collections::BTreeMap<String, PlanGlyph>,
}

/// A glyph or mark at height 1: its box is [0, width] × [0, 1].
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanGlyph {
    /// Width, in heights.
    pub width: f64,
    /// Open polylines, [x, y] in heights.
    pub strokes: Vec<Vec<[f64; 2]>>,
}

/// A name from a fixed set (a kind, a use, an edge): borrowed from the
/// program's own strings when the plan is made (a big kit's parts have
/// millions, each its own allocation as a `String`), owned when read.
pub type Name = std::borrow::Cow<'static, str>;

/// What a feature is, as plan.json names it. (Feature fields are enums,
/// not strings: a big kit has about a million features, and three strings
/// each were a fifth of the plan's memory.)
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum PlanFeatureKind {
    /// `slot`: a notch from a long edge.
    Slot,
    /// `hole`: a round hole.
    Hole,
}

/// What a hole is for, as plan.json names it.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum PlanHoleUse {
    /// `node`: the node bolt, or a stud fastener at a node.
    Node,
    /// `shear_block`: a shear block's bolt.
    ShearBlock,
    /// `splice`: a splice plate's bolt.
    Splice,
    /// `edge_node`: where a lamella ends on an edge strip.
    EdgeNode,
}

/// The edge a slot is cut from, as plan.json names it.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum PlanSlotEdge {
    /// `top`.
    Top,
    /// `bottom`.
    Bottom,
}

/// A slot or hole of a part.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanFeature {
    /// `slot` or `hole`.
    pub kind: PlanFeatureKind,
    /// For holes: `node`, `shear_block`, `splice` or `edge_node`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hole_use: Option<PlanHoleUse>,
    /// The node id it belongs to, if any.
    pub node: Option<usize>,
    /// The crossing strip's id, if any.
    pub crossing: Option<String>,
    /// Centre in the part frame, [x, y] mm.
    pub center_mm: [f64; 2],
    /// Along x: slot width or hole diameter, mm.
    pub width_mm: f64,
    /// Slot depth from its edge, mm (0 for holes).
    pub depth_mm: f64,
    /// `top` or `bottom` for slots.
    pub edge: Option<PlanSlotEdge>,
    /// Crossing angles a slot was swept over, degrees.
    pub angle_range_deg: Option<[f64; 2]>,
    /// Station on the part's own line, mm, where it has one.
    pub station_mm: Option<f64>,
}

/// Counts by kind, lamella length and mass.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanKitSummary {
    /// Per kind: distinct parts and pieces to make.
    pub kinds: Vec<PlanKindCount>,
    /// Total length of lamella parts, allowances included, mm.
    pub lamella_length_mm: f64,
    /// Mass of everything cut or sawn, kg.
    pub mass_kg: f64,
}

/// How many parts of one kind.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanKindCount {
    /// The kind.
    pub kind: String,
    /// Distinct parts.
    pub parts: usize,
    /// Pieces to make (sum of counts).
    pub count: u64,
}

/// The profile a network was checked against, as used (`check` only).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanProfile {
    /// The profile's name.
    pub name: String,
    /// The profile's file name (no directory).
    pub source: String,
    /// The material's name.
    pub material: String,
    /// Lamella thickness t, mm.
    pub thickness_mm: f64,
    /// Lamella height h, along the surface normal, mm.
    pub height_mm: f64,
    /// Lamellas per strip: 1 or 2.
    pub lamellas_per_strip: u32,
    /// Gap between the two lamellas of a doubled strip, mm (0 for one lamella).
    pub gap_mm: f64,
    /// Young's modulus E, MPa.
    pub youngs_modulus_mpa: f64,
    /// Shear modulus G, MPa.
    pub shear_modulus_mpa: f64,
    /// Characteristic strength f_k, MPa.
    pub characteristic_strength_mpa: f64,
    /// Partial safety factor γ_M (dimensionless).
    pub partial_factor: f64,
    /// Modification factor k_mod (dimensionless; 1 for steel).
    pub modification_factor: f64,
    /// Design strength f_d = k_mod·f_k/γ_M, MPa (4 decimals).
    pub design_strength_mpa: f64,
    /// `interlocking` or `two_level`.
    pub joint_system: String,
    /// Height offset between the two levels of a two-level joint, mm (0 otherwise).
    pub level_offset_mm: f64,
    /// The whole profile as read (every field, for later stages).
    pub resolved: serde_json::Value,
}

/// The elastic check's verdict over all A and B strips (`check` only).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanCheckSummary {
    /// Every lamella of every A and B strip has utilisation ≤ 1.
    pub passes: bool,
    /// Number of strips with a lamella above utilisation 1.
    pub strips_overstressed: usize,
    /// Highest utilisation σv/f_d over all lamellas (6 decimals).
    pub max_utilization: f64,
    /// The profile's limits: bending radius in pure bending, twist in pure twist.
    pub limit_bending_radius_mm: f64,
    /// Largest twist in pure torsion, °/m.
    pub limit_twist_deg_per_m: f64,
    /// The section changes that would pass (`check --suggest` only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub suggestion: Option<PlanSuggestion>,
}

/// The section changes that make every strip pass (mm, 4 decimals).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanSuggestion {
    /// Largest thickness at the profile's height at which every strip passes, mm; null if none.
    pub max_thickness_mm: Option<f64>,
    /// Largest height at the profile's thickness at which every strip passes, mm;
    /// null when height does not matter (no twist) or none works.
    pub max_height_mm: Option<f64>,
    /// When no thickness works at the profile's height: [height, thickness] in mm that does.
    pub height_mm_with_thickness_mm: Option<[f64; 2]>,
}

/// The stresses of one lamella at its governing point (MPa, 4 decimals).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanStress {
    /// σv/f_d at the governing point (6 decimals; above 1 fails).
    pub utilization: f64,
    /// On the lamella's own line.
    pub governing_station_mm: f64,
    /// Bending about the weak axis σb = E·|kg|·t/2, MPa.
    pub bending_stress_mpa: f64,
    /// St. Venant shear τ = G·|tg|·t, MPa.
    pub torsion_shear_mpa: f64,
    /// Trapeze stress of twist σw = E·tg²·h²/12, MPa.
    pub trapeze_stress_mpa: f64,
    /// σv = √((σb + σw)² + 3τ²), MPa.
    pub combined_stress_mpa: f64,
    /// bending, torsion or trapeze.
    pub governs: String,
}

/// A strip's worst lamella and its stresses (`check` only).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanStripCheck {
    /// The worst lamella's number.
    pub lamella: u32,
    /// The worst lamella's stresses (flattened into this object).
    #[serde(flatten)]
    pub stress: PlanStress,
}

/// One topology warning.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanWarning {
    /// near_tangent, overlap, close_nodes or isolated_curve.
    pub kind: String,
    /// One line for a person.
    pub message: String,
    /// Ids of the curves concerned.
    pub curves: Vec<String>,
    /// Station on the first curve, where the warning has one.
    pub station_mm: Option<f64>,
}

/// One lamella of a strip on its own offset line.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanLamella {
    /// Lamella number: 1 on −y, 2 on +y (1 for the centre line without a profile).
    pub lamella: u32,
    /// Offset from the strip's curve across the surface (along y), mm.
    pub dy_mm: f64,
    /// Offset along the surface normal z, mm.
    pub dz_mm: f64,
    /// Length of the lamella's own line, mm.
    pub length_mm: f64,
    /// The strip's nodes at their stations on this lamella's own line.
    pub nodes: Vec<PlanLamellaNode>,
    /// The elastic check of this lamella (added by `check`).
    #[serde(flatten, default, skip_serializing_if = "Option::is_none")]
    pub checked: Option<PlanLamellaCheck>,
}

/// A node on a lamella's own line.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanLamellaNode {
    /// Node id (index into `nodes`).
    pub node: usize,
    /// Arc length along the lamella's line from its start, mm.
    pub station_mm: f64,
}

/// The elastic check of one lamella.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanLamellaCheck {
    /// Smallest bending radius of this lamella, mm; null when straight.
    pub min_bending_radius_mm: Option<f64>,
    /// Largest twist of this lamella on its own line, °/m.
    pub max_twist_deg_per_m: f64,
    /// The stresses at its governing point.
    pub check: PlanStress,
}

/// The network a plan was made from.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct NetworkSummary {
    /// The network's name.
    pub name: String,
    /// The file name (not the full path, so plans are portable).
    pub source: String,
    /// The unit the network file was written in (`mm`, `cm`, `m`, `in`, `ft`).
    pub file_units: String,
    /// Node tolerance, mm.
    pub tolerance_mm: f64,
}

/// Counts and extremes over the whole network.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Summary {
    /// Number of curves, edges included.
    pub curves: usize,
    /// Number of nodes.
    pub nodes: usize,
    /// Total curve length, edges included, mm.
    pub total_length_mm: f64,
    /// Shortest distance between consecutive nodes along any curve, mm; null without one.
    pub shortest_node_to_node_mm: Option<f64>,
    /// Longest distance between consecutive nodes along any curve, mm; null without one.
    pub longest_node_to_node_mm: Option<f64>,
    /// Largest |kn| residual over A and B strips, 1/m (zero on exact asymptotic curves).
    pub max_normal_curvature_per_m: f64,
    /// Smallest acute crossing angle over A×B nodes, degrees; null without one.
    pub min_angle_deg: Option<f64>,
    /// Largest acute crossing angle over A×B nodes, degrees; null without one.
    pub max_angle_deg: Option<f64>,
}

/// One strip (curve) of the network.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanStrip {
    /// The curve's id.
    pub id: String,
    /// `A`, `B` or `edge`.
    pub family: String,
    /// Arc length of the curve, mm.
    pub length_mm: f64,
    /// The strip's nodes by station along the curve.
    pub nodes: Vec<PlanStripNode>,
    /// Lengths between consecutive nodes.
    pub node_to_node_mm: Vec<f64>,
    /// From the strip's start to its first node, and from its last node to its end.
    pub start_to_first_node_mm: Option<f64>,
    /// From the last node to the strip's end, mm; null without nodes.
    pub last_node_to_end_mm: Option<f64>,
    /// None for a straight strip.
    pub min_bending_radius_mm: Option<f64>,
    /// Largest geodesic torsion |tg| along the curve, °/m.
    pub max_twist_deg_per_m: f64,
    /// Largest |kn| residual, 1/m (per sample with file normals, at the nodes otherwise).
    pub max_normal_curvature_per_m: f64,
    /// Where the surface normals came from: file, binormal, binormal+nodes, nodes.
    pub normals: String,
    /// The worst lamella's elastic check (added by `check`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub check: Option<PlanStripCheck>,
    /// Every lamella on its own offset line (A and B strips): the centre line
    /// without a profile, the profile's lamellas with `check`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lamellas: Option<Vec<PlanLamella>>,
}

/// A node seen from one strip.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanStripNode {
    /// Node id (index into `nodes`).
    pub node: usize,
    /// Id of the crossing curve.
    pub crossing: String,
    /// Arc length along the strip's curve from its first point, mm.
    pub station_mm: f64,
    /// Acute crossing angle, degrees.
    pub angle_deg: f64,
}

/// One node: where two curves cross.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanNode {
    /// Node id: its index in `nodes`.
    pub id: usize,
    /// The A curve (or the B curve of a B×edge node).
    pub a: String,
    /// The B curve (or the edge curve).
    pub b: String,
    /// Station of the node on curve `a`, mm.
    pub station_a_mm: f64,
    /// Station of the node on curve `b`, mm.
    pub station_b_mm: f64,
    /// Midpoint of the closest approach, world frame, mm.
    pub position_mm: [f64; 3],
    /// Unit surface normal, world frame (7 decimals), oriented consistently along every curve.
    pub normal: [f64; 3],
    /// Acute angle between the two tangents, degrees, in [0, 90].
    pub angle_deg: f64,
    /// From A's tangent line to B's, counter-clockwise about the normal, [0, 180).
    pub oriented_angle_deg: f64,
    /// Distance between the two curves at the node, mm (at most the tolerance).
    pub gap_mm: f64,
}

/// Round to `decimals` places (and drop negative zero) for stable output.
pub fn round(x: f64, decimals: i32) -> f64 {
    let f = 10f64.powi(decimals);
    let r = (x * f).round() / f;
    if r == 0.0 {
        0.0
    } else {
        r
    }
}

const MM: i32 = 4;
const DEG: i32 = 6;
const CURV: i32 = 6;

fn v3(v: glam::DVec3, d: i32) -> [f64; 3] {
    [round(v.x, d), round(v.y, d), round(v.z, d)]
}

/// Format a finished model as a plan: ids for indices, rounded numbers.
/// Nothing is computed here (see [`crate::analysis::lines`]).
pub fn build(net: &Network, an: &Analysis, model: &Model) -> Plan {
    let per_m = 1000.0;
    let id = |i: usize| net.curves[i].id.clone();
    let checks: Vec<Option<&StripCheck>> = {
        let mut v = vec![None; an.strips.len()];
        if let Some(c) = &model.check {
            for sc in &c.report.strips {
                v[sc.strip] = Some(sc);
            }
        }
        v
    };
    // Strips and nodes formatted in parallel (in order).
    let strips: Vec<PlanStrip> = an
        .strips
        .par_iter()
        .zip(model.strips.par_iter())
        .zip(checks.par_iter())
        .map(|((s, m), sc)| {
            let nodes = s
                .nodes
                .iter()
                .map(|cn| PlanStripNode {
                    node: cn.node,
                    crossing: id(cn.crossing),
                    station_mm: round(cn.station_mm, MM),
                    angle_deg: round(an.topology.nodes[cn.node].angle_deg, DEG),
                })
                .collect();
            let lamellas: Vec<PlanLamella> = m
                .lamellas
                .iter()
                .enumerate()
                .map(|(k, line)| PlanLamella {
                    lamella: line.offset.number,
                    dy_mm: round(line.offset.dy_mm, MM),
                    dz_mm: round(line.offset.dz_mm, MM),
                    length_mm: round(line.length_mm, MM),
                    nodes: line
                        .nodes
                        .iter()
                        .map(|n| PlanLamellaNode {
                            node: n.node,
                            station_mm: round(n.station_mm, MM),
                        })
                        .collect(),
                    checked: sc
                        .and_then(|sc| sc.lamellas.get(k))
                        .map(|l| PlanLamellaCheck {
                            min_bending_radius_mm: l.min_bending_radius_mm.map(|r| round(r, MM)),
                            max_twist_deg_per_m: round(l.max_twist_deg_per_m, DEG),
                            check: plan_stress(l),
                        }),
                })
                .collect();
            PlanStrip {
                id: s.id.clone(),
                family: s.family.as_str().to_string(),
                length_mm: round(s.length_mm, MM),
                nodes,
                node_to_node_mm: m.node_to_node_mm.iter().map(|&l| round(l, MM)).collect(),
                start_to_first_node_mm: m.start_to_first_node_mm.map(|x| round(x, MM)),
                last_node_to_end_mm: m.last_node_to_end_mm.map(|x| round(x, MM)),
                min_bending_radius_mm: s.min_bending_radius_mm().map(|r| round(r, MM)),
                max_twist_deg_per_m: round(s.max_abs_tg_per_mm.to_degrees() * per_m, DEG),
                max_normal_curvature_per_m: round(s.max_abs_kn_per_mm * per_m, CURV),
                normals: s.normal_source.as_str().to_string(),
                check: sc.map(|sc| {
                    let worst = sc.worst();
                    PlanStripCheck {
                        lamella: worst.line.offset.number,
                        stress: plan_stress(worst),
                    }
                }),
                lamellas: (!lamellas.is_empty()).then_some(lamellas),
            }
        })
        .collect();
    let nodes: Vec<PlanNode> = an
        .topology
        .nodes
        .par_iter()
        .map(|n| PlanNode {
            id: n.id,
            a: id(n.a),
            b: id(n.b),
            station_a_mm: round(n.station_a_mm, MM),
            station_b_mm: round(n.station_b_mm, MM),
            position_mm: v3(n.position_world_mm, MM),
            normal: v3(n.normal_world, 7),
            angle_deg: round(n.angle_deg, DEG),
            oriented_angle_deg: round(n.oriented_angle_deg, DEG),
            gap_mm: round(n.gap_mm, MM),
        })
        .collect();
    let sm = &model.summary;
    let summary = Summary {
        curves: sm.curves,
        nodes: sm.nodes,
        total_length_mm: round(sm.total_length_mm, MM),
        shortest_node_to_node_mm: sm.shortest_node_to_node_mm.map(|x| round(x, MM)),
        longest_node_to_node_mm: sm.longest_node_to_node_mm.map(|x| round(x, MM)),
        max_normal_curvature_per_m: round(sm.max_normal_curvature_per_mm * per_m, CURV),
        min_angle_deg: sm.min_angle_deg.map(|x| round(x, DEG)),
        max_angle_deg: sm.max_angle_deg.map(|x| round(x, DEG)),
    };
    let warnings = an
        .warnings()
        .iter()
        .map(|w| PlanWarning {
            kind: w.kind.as_str().into(),
            message: w.message.clone(),
            curves: w.curves.iter().map(|&c| id(c)).collect(),
            station_mm: w.station_mm.map(|x| round(x, MM)),
        })
        .collect();
    let (profile, check) = match &model.check {
        Some(c) => (
            Some(plan_profile(&c.profile)),
            Some(plan_check(&c.report, c.suggestion.as_ref())),
        ),
        None => (None, None),
    };
    Plan {
        schema: SCHEMA.into(),
        generator: format!("lamella {}", env!("CARGO_PKG_VERSION")),
        units: "mm".into(),
        network: NetworkSummary {
            name: net.name.clone(),
            source: file_name(&net.source),
            file_units: net.file_unit.as_str().into(),
            tolerance_mm: round(net.tolerance_mm, MM),
        },
        summary,
        strips,
        nodes,
        warnings,
        profile,
        check,
        parts: None,
        parts_summary: None,
        engraving_font: None,
        sheets: None,
        nesting: None,
        flat: None,
    }
}

/// Add a nest to a plan (formatting only).
pub fn add_nest(plan: &mut Plan, kit: &crate::fabricate::Kit, nest: &crate::nest::Nest) {
    plan.sheets = Some(
        nest.sheets
            .iter()
            .map(|s| PlanSheet {
                id: s.id.clone(),
                width_mm: round(s.width_mm, MM),
                length_mm: round(s.length_mm, MM),
                utilization: round(s.utilization(), 6),
                stock: s.stock.clone(),
                price_per_unit: s.price_per_unit.map(money),
                placements: s
                    .placements
                    .iter()
                    .map(|p| PlanPlacement {
                        part: kit.parts[p.part].id.clone(),
                        copy: p.copy,
                        x_mm: round(p.x_mm, MM),
                        y_mm: round(p.y_mm, MM),
                        rotation_deg: p.rotation_deg,
                    })
                    .collect(),
            })
            .collect(),
    );
    let n = &nest.summary;
    plan.nesting = Some(PlanNesting {
        sheets_used: n.sheets_used,
        lower_bound_sheets: n.lower_bound_sheets,
        area_bound_sheets: n.area_bound_sheets,
        lane_bound_sheets: n.lane_bound_sheets,
        lanes_per_sheet: n.lanes_per_sheet,
        lanes_used: n.lanes_used,
        lane_bound_lanes: n.lane_bound_lanes,
        utilization: round(n.utilization, 6),
        stock_used: nest
            .stock_used
            .iter()
            .map(|u| PlanStockUse {
                stock: u.stock.clone(),
                sheets: u.sheets,
                width_mm: round(u.width_mm, MM),
                length_mm: round(u.length_mm, MM),
                price_per_unit: u.price_per_unit.map(money),
                cost: u.cost.map(money),
            })
            .collect(),
        total_cost: n.cost.map(money),
        cost_bound: n.cost_bound.map(money),
        currency: nest.currency.clone(),
        coil_length_mm: n.length_used_mm.map(|x| round(x, MM)),
        coil_length_bound_mm: n.length_bound_mm.map(|x| round(x, MM)),
    });
}

/// A price rounded to 1e-4 of its unit (cents and below stay exact).
fn money(x: f64) -> f64 {
    round(x, 4)
}

/// Add a kit's parts to a plan (formatting only: rounding to 1e-4 mm).
pub fn add_parts(plan: &mut Plan, kit: &crate::fabricate::Kit) {
    set_parts(plan, plan_parts(kit), kit);
}

/// The font entry of every character and mark the parts engrave.
fn engraving_font(parts: &[PlanPart]) -> PlanFont {
    use crate::fabricate::font;
    let glyph = |width: f64, strokes: Vec<Vec<kurbo::Point>>| PlanGlyph {
        width,
        strokes: strokes
            .iter()
            .map(|s| s.iter().map(|p| [p.x, p.y]).collect())
            .collect(),
    };
    let mut chars = std::collections::BTreeSet::new();
    let mut marks = std::collections::BTreeMap::new();
    for e in parts.iter().flat_map(|p| &p.engraving) {
        chars.extend(e.text.iter().flat_map(|t| t.chars()));
        if e.mark.as_deref() == Some(ORIENTATION_MARK) && marks.is_empty() {
            marks.insert(
                ORIENTATION_MARK.to_string(),
                glyph(
                    font::ORIENTATION_MARK_LENGTH,
                    font::orientation_mark_strokes(1.0),
                ),
            );
        }
    }
    let glyphs = chars
        .into_iter()
        .map(|c| {
            (
                c.to_string(),
                glyph(font::glyph_width(c), font::glyph_strokes(c)),
            )
        })
        .collect();
    PlanFont {
        name: font::NAME.into(),
        letter_spacing: font::LETTER_SPACING,
        glyphs,
        marks,
    }
}

/// The name of the orientation mark in plan.json.
pub const ORIENTATION_MARK: &str = "orientation";

/// Every part of `kit` as plan.json writes it, in order (converted in
/// parallel; the kit is left as it is).
pub fn plan_parts(kit: &crate::fabricate::Kit) -> Vec<PlanPart> {
    use rayon::prelude::*;
    kit.parts.par_iter().map(plan_part).collect()
}

/// Put `parts` (from [`plan_parts`] of `kit`) into the plan, with the
/// engraving font and the kit's summary: what [`add_parts`] does.
pub fn set_parts(plan: &mut Plan, parts: Vec<PlanPart>, kit: &crate::fabricate::Kit) {
    plan.parts = Some(parts);
    add_kit_summary(plan, kit);
}

/// One part as plan.json writes it (rounded); its round holes only as
/// its `hole` features.
fn plan_part(p: &crate::fabricate::part::Part) -> PlanPart {
    use crate::fabricate::part::{round_hole, Engraved, FeatureKind, HoleUse, SlotEdge};
    let pt = |p: &kurbo::Point| [round(p.x, MM), round(p.y, MM)];
    let poly = |v: &[kurbo::Point]| v.iter().map(pt).collect::<Vec<_>>();
    PlanPart {
        id: p.id.clone(),
        kind: p.kind.as_str().into(),
        strip: p.strip.clone(),
        lamella: p.lamella,
        count: p.count,
        length_mm: round(p.length_mm, MM),
        height_mm: round(p.height_mm, MM),
        station_start_mm: p.station_start_mm.map(|s| round(s, MM)),
        outline: poly(&p.outline_part_mm),
        holes: p
            .holes_part_mm
            .iter()
            .filter(|h| round_hole(p, h).is_none())
            .map(|h| poly(h))
            .collect(),
        engraving: p
            .engraving
            .iter()
            .map(|e| {
                let (text, mark) = match &e.what {
                    Engraved::Text(t) => (Some(t.clone()), None),
                    Engraved::OrientationMark => (None, Some(ORIENTATION_MARK.into())),
                };
                PlanEngraving {
                    text,
                    mark,
                    at_mm: pt(&e.at_part_mm),
                    height_mm: round(e.height_mm, MM),
                }
            })
            .collect(),
        features: p
            .features
            .iter()
            .map(|f| PlanFeature {
                kind: match f.kind {
                    FeatureKind::Slot => PlanFeatureKind::Slot,
                    FeatureKind::Hole => PlanFeatureKind::Hole,
                },
                hole_use: f.hole_use.map(|u| match u {
                    HoleUse::Node => PlanHoleUse::Node,
                    HoleUse::ShearBlock => PlanHoleUse::ShearBlock,
                    HoleUse::Splice => PlanHoleUse::Splice,
                    HoleUse::EdgeNode => PlanHoleUse::EdgeNode,
                }),
                node: f.node,
                crossing: f.crossing.clone(),
                center_mm: pt(&f.center_part_mm),
                width_mm: round(f.width_mm, MM),
                depth_mm: round(f.depth_mm, MM),
                edge: f.edge.map(|e| match e {
                    SlotEdge::Top => PlanSlotEdge::Top,
                    SlotEdge::Bottom => PlanSlotEdge::Bottom,
                }),
                angle_range_deg: f
                    .angle_range_deg
                    .map(|(a, b)| [round(a, DEG), round(b, DEG)]),
                station_mm: f.station_mm.map(|s| round(s, MM)),
            })
            .collect(),
    }
}

fn add_kit_summary(plan: &mut Plan, kit: &crate::fabricate::Kit) {
    plan.engraving_font = plan.parts.as_deref().map(engraving_font);
    plan.parts_summary = Some(PlanKitSummary {
        kinds: kit
            .summary
            .kinds
            .iter()
            .map(|&(k, parts, count)| PlanKindCount {
                kind: k.as_str().into(),
                parts,
                count,
            })
            .collect(),
        lamella_length_mm: round(kit.summary.lamella_length_mm, MM),
        mass_kg: round(kit.summary.mass_kg, 3),
    });
}

fn file_name(p: &Path) -> String {
    p.file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

const MPA: i32 = 4;
const UTIL: i32 = 6;

fn plan_stress(l: &LamellaCheck) -> PlanStress {
    PlanStress {
        utilization: round(l.utilization, UTIL),
        governing_station_mm: round(l.governing_station_mm, MM),
        bending_stress_mpa: round(l.stresses.bending_stress_mpa, MPA),
        torsion_shear_mpa: round(l.stresses.torsion_shear_mpa, MPA),
        trapeze_stress_mpa: round(l.stresses.trapeze_stress_mpa, MPA),
        combined_stress_mpa: round(l.stresses.combined_stress_mpa, MPA),
        governs: l.governs.as_str().into(),
    }
}

fn plan_profile(p: &Profile) -> PlanProfile {
    PlanProfile {
        name: p.name.clone(),
        source: file_name(&p.source),
        material: p.material.name.clone(),
        thickness_mm: p.section.thickness_mm,
        height_mm: p.section.height_mm,
        lamellas_per_strip: p.section.per_strip,
        gap_mm: p.section.gap_mm,
        youngs_modulus_mpa: p.material.youngs_modulus_mpa,
        shear_modulus_mpa: p.material.shear_modulus_mpa,
        characteristic_strength_mpa: p.material.characteristic_strength_mpa,
        partial_factor: p.material.partial_factor,
        modification_factor: p.material.modification_factor,
        design_strength_mpa: round(p.design_strength_mpa(), MPA),
        joint_system: match p.joint.system {
            JointSystem::Interlocking => "interlocking".into(),
            JointSystem::TwoLevel => "two_level".into(),
        },
        level_offset_mm: p.joint.level_offset_mm,
        resolved: resolved::resolved(p),
    }
}

fn plan_check(report: &CheckReport, suggestion: Option<&Suggestion>) -> PlanCheckSummary {
    PlanCheckSummary {
        passes: report.passes(),
        strips_overstressed: report.overstressed(),
        max_utilization: round(report.max_utilization(), UTIL),
        limit_bending_radius_mm: round(report.limit_bending_radius_mm, MM),
        limit_twist_deg_per_m: round(report.limit_twist_deg_per_m, DEG),
        suggestion: suggestion.map(|s| PlanSuggestion {
            max_thickness_mm: s.max_thickness_mm.map(|x| round(x, MM)),
            max_height_mm: s.max_height_mm.map(|x| round(x, MM)),
            height_mm_with_thickness_mm: s
                .height_and_thickness_mm
                .map(|(h, t)| [round(h, MM), round(t, MM)]),
        }),
    }
}

/// The dotted path of a NaN or infinite number in `plan`, if any
/// ([`crate::formats::write::finite::first_non_finite`]): the first outside its parts,
/// else the first in them (walked in parallel).
pub fn first_non_finite(plan: &mut Plan) -> Option<String> {
    use rayon::prelude::*;
    let parts = plan.parts.take();
    let rest = crate::formats::write::finite::first_non_finite(plan);
    plan.parts = parts;
    rest.or_else(|| {
        plan.parts.as_deref().and_then(|parts| {
            parts.par_iter().enumerate().find_map_first(|(i, p)| {
                crate::formats::write::finite::first_non_finite(p)
                    .map(|f| format!("parts[{i}].{f}"))
            })
        })
    })
}

/// Serialise a plan (pretty JSON, trailing newline).
pub fn to_json(plan: &Plan) -> String {
    let mut out = Vec::new();
    if let Err(e) = write_json(plan, &mut out) {
        return format!("{{\"error\":\"{e}\"}}\n");
    }
    String::from_utf8(out).unwrap_or_default()
}

/// Stream the plan as JSON into `w` (the layout of [`to_json`]).
pub fn write_json<W: std::io::Write + ?Sized>(plan: &Plan, w: &mut W) -> std::io::Result<()> {
    crate::formats::write::plan_json::write(plan, w)
}

/// Write `contents` to `path` atomically: a temporary file beside it, then a
/// rename, so a failure never leaves half a file.
pub fn write_atomic(path: &Path, contents: &[u8]) -> Result<()> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if dir.exists() && !dir.is_dir() {
        return Err(Error::io(
            dir,
            std::io::Error::other("is a file, not a directory: choose another output directory"),
        ));
    }
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dir.join(format!(".{name}.lamella-tmp"));
    std::fs::write(&tmp, contents).map_err(|e| Error::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        Error::io(path, e)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn part(id: &str, length_mm: f64) -> PlanPart {
        PlanPart {
            id: id.into(),
            kind: "washer".into(),
            strip: None,
            lamella: None,
            count: 1,
            length_mm,
            height_mm: 10.0,
            station_start_mm: None,
            outline: vec![[0.0, 0.0], [length_mm, 0.0], [0.0, 10.0]],
            holes: vec![],
            engraving: vec![],
            features: vec![],
        }
    }

    /// The parts are walked in parallel, the rest as a whole walk would.
    #[test]
    fn non_finite_numbers_named_in_the_parts_and_outside() {
        let mut plan: Plan = serde_json::from_value(serde_json::json!({
            "schema": SCHEMA, "generator": "t", "units": "mm",
            "network": {"name": "n", "source": "n.yaml", "file_units": "mm", "tolerance_mm": 0.5},
            "summary": {"curves": 0, "nodes": 0, "total_length_mm": 0.0,
                "shortest_node_to_node_mm": null, "longest_node_to_node_mm": null,
                "max_normal_curvature_per_m": 0.0, "min_angle_deg": null, "max_angle_deg": null},
            "strips": [], "nodes": [], "warnings": []
        }))
        .expect("plan");
        plan.parts = Some((0..50).map(|i| part(&format!("P{i}"), 10.0)).collect());
        assert_eq!(first_non_finite(&mut plan), None);
        let parts = plan.parts.as_mut().expect("parts");
        parts[40].outline[2][1] = f64::INFINITY;
        parts[7].length_mm = f64::NAN;
        assert_eq!(
            first_non_finite(&mut plan).as_deref(),
            Some("parts[7].length_mm")
        );
        plan.network.tolerance_mm = f64::NAN;
        assert_eq!(
            first_non_finite(&mut plan).as_deref(),
            Some("network.tolerance_mm")
        );
        assert_eq!(plan.parts.as_ref().map(Vec::len), Some(50));
    }
}
