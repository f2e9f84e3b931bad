//! The plan: the single model every writer formats (plan.json, the cutting
//! files, the takeoff, the assembly sheets), schema `lamella-plan/3`. Later
//! stages add fields; they never rename these. Numbers are rounded to fixed
//! precision when the plan is made ([`convert`]), so equal inputs give equal
//! bytes in every file drawn from it.

use serde::{Deserialize, Serialize};
use takeoff::Takeoff;

mod convert;
pub mod joints;
pub mod model;
pub mod shape;
pub mod sparrow;
pub mod structure;
pub mod takeoff;

pub use convert::{
    add_curves, add_flat, add_nest, add_parts, add_takeoff, build, plan_parts, round, set_parts,
};
pub use shape::{add_shape, ShapeOptions};

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
    /// The erected grid as a frame under a loads file (added by `frame`,
    /// and by `build --loads`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub structure: Option<structure::PlanStructure>,
    /// The network's curves as read, for drawings of the whole grid (the
    /// assembly sheets' overview). Not in plan.json, which holds the
    /// strips' figures, not their points.
    #[serde(skip)]
    pub curves: Vec<PlanCurve>,
    /// The material takeoff (added with the nest). Not in plan.json: it
    /// is written beside it as takeoff.csv and takeoff.json.
    #[serde(skip)]
    pub takeoff: Option<Takeoff>,
    /// The grid's shape in space, for the 3D model (added by
    /// [`add_shape`]). Not in plan.json.
    #[serde(skip)]
    pub shape: Option<PlanShape>,
    /// The kit's joints in section, for the assembly sheets (added with
    /// the takeoff). Not in plan.json.
    #[serde(skip)]
    pub joints: Vec<joints::PlanJoint>,
}

/// The grid's shape in space (world frame, mm): every lamella's frames on
/// its own offset line, the edge strips' on their curves, the strips'
/// tangents at every node, the section and the hardware's sizes.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanShape {
    /// Lamella height h, along the normal, mm.
    pub height_mm: f64,
    /// Lamella thickness t, across, mm.
    pub thickness_mm: f64,
    /// The star washers, when the profile has them.
    pub washer: Option<ShapeWasher>,
    /// The studs of a two-level joint.
    pub stud: Option<ShapeStud>,
    /// Every lamella line (A and B strips, in plan order, lamellas in
    /// order), and each edge strip's curve (`lamella` 0).
    pub lines: Vec<ShapeLine>,
    /// Per plan node (by id): the strips' unit tangents there.
    pub nodes: Vec<ShapeNode>,
    /// The largest distance between two frames along a curve, mm.
    pub step_mm: f64,
}

/// The star washer's sizes, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeWasher {
    /// Plate thickness, mm.
    pub thickness_mm: f64,
    /// Arm length from the node, mm.
    pub arm_length_mm: f64,
    /// Arm width, mm.
    pub arm_width_mm: f64,
    /// Washers per node (2: on top and below).
    pub per_node: u32,
}

/// A two-level joint's stud, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeStud {
    /// Square section, mm.
    pub section_mm: f64,
    /// Length along the normal, mm.
    pub length_mm: f64,
}

/// One lamella line (or an edge strip's curve) as frames by station.
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeLine {
    /// Index of its strip in the plan's `strips`.
    pub strip: usize,
    /// Lamella number (0: an edge strip's curve).
    pub lamella: u32,
    /// Frames by ascending station (ends, nodes and between).
    pub frames: Vec<ShapeFrame>,
    /// The same frames in the flat layout, when the flat state holds the strip.
    pub flat: Option<Vec<ShapeFrame>>,
}

/// A point on a line with its unit frame (world, mm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeFrame {
    /// Station on the line's own arc length, mm.
    pub station_mm: f64,
    /// The point, mm.
    pub point_mm: [f64; 3],
    /// Unit tangent x.
    pub tangent: [f64; 3],
    /// Unit surface normal z (the lamella's height).
    pub normal: [f64; 3],
    /// Unit y = z × x (the lamella's thickness).
    pub across: [f64; 3],
}

/// The two strips' unit tangents at a node (world).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeNode {
    /// Tangent of the node's `a` strip.
    pub tangent_a: [f64; 3],
    /// Tangent of the node's `b` strip.
    pub tangent_b: [f64; 3],
    /// Where the node lies in the flat layout (world, mm), when it is in it.
    pub flat_mm: Option<[f64; 3]>,
}

/// A curve's points in the world frame, mm (the network's, as read).
#[derive(Debug, Clone, PartialEq)]
pub struct PlanCurve {
    /// The curve's id (a strip id of the plan).
    pub id: String,
    /// Its points, world frame, mm.
    pub points_mm: Vec<[f64; 3]>,
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
    /// The flat state's own numbers for drawing it (`flat.svg`), not
    /// rounded; not in plan.json.
    #[serde(skip)]
    pub drawing: FlatDrawing,
}

/// The flat state as drawn: its strips through their nodes and each
/// node's floor position and rotation, unrounded.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FlatDrawing {
    /// Per A/B strip of the flat problem.
    pub strips: Vec<FlatDrawingStrip>,
    /// Per A×B node of the flat problem (indexed by the strips' `nodes`).
    pub nodes: Vec<FlatDrawingNode>,
}

/// A strip of the flat state as drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct FlatDrawingStrip {
    /// Strip id.
    pub id: String,
    /// Family A (else B).
    pub family_a: bool,
    /// Its nodes in order, indices into [`FlatDrawing::nodes`].
    pub nodes: Vec<usize>,
    /// Its node-to-node lengths, mm.
    pub lengths_mm: Vec<f64>,
}

/// A node of the flat state as drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct FlatDrawingNode {
    /// Node id (plan.json's).
    pub node: usize,
    /// Floor position, [x, y] mm.
    pub position_mm: [f64; 2],
    /// Erected − flat, degrees.
    pub rotation_deg: f64,
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
    /// The stock group it belongs to (`lamella-1.5`): every part on it is
    /// of that group's material and thickness.
    #[serde(default)]
    pub group: String,
    /// The material of the sheet (and of every part on it).
    #[serde(default)]
    pub material: String,
    /// The thickness of the sheet (a bar: its section's side), mm.
    #[serde(default)]
    pub thickness_mm: f64,
    /// `sheet`, `coil` (a piece cut from it) or `bar`.
    #[serde(default)]
    pub form: String,
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
    /// Per stock group (one material and thickness each): its sheets,
    /// bounds and cost; the figures above are their sums.
    #[serde(default)]
    pub groups: Vec<PlanGroupNesting>,
}

/// The nest of one stock group.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlanGroupNesting {
    /// The group's name (`lamella-1.5`, `washer-3`, `stud-20x20`).
    pub group: String,
    /// Its material.
    pub material: String,
    /// Its thickness (a bar: its section's side), mm.
    pub thickness_mm: f64,
    /// `sheet`, `coil` or `bar`.
    pub form: String,
    /// What its parts are: `lamella`, `edge_strip`, … (plan part kinds).
    pub kinds: Vec<String>,
    /// Its sheets' ids, first and last (`S01`, `S03`).
    pub sheet_ids: Vec<String>,
    /// Sheets (bars, coil pieces) it uses.
    pub sheets_used: usize,
    /// The larger of its area and lane bounds.
    pub lower_bound_sheets: usize,
    /// Its area bound.
    pub area_bound_sheets: usize,
    /// Its lane bound (lamellas only).
    pub lane_bound_sheets: usize,
    /// Part area over the area of its sheets.
    pub utilization: f64,
    /// Its sheets per stock size.
    pub stock_used: Vec<PlanStockUse>,
    /// Σ of its sheets' prices, when priced.
    pub total_cost: Option<f64>,
    /// A lower bound on that cost.
    pub cost_bound: Option<f64>,
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
    /// The stock group it is cut from (`washer-3`): its sheets carry the
    /// same name.
    #[serde(default)]
    pub group: String,
    /// The material it is made of (its group's).
    #[serde(default)]
    pub material: String,
    /// Its thickness (a stud: its bar section's side), mm.
    #[serde(default)]
    pub thickness_mm: f64,
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
    /// `cable_pin`: an eye plate's hole for a bracing cable's pin.
    CablePin,
}

/// The edge a slot is cut from, as plan.json names it.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum PlanSlotEdge {
    /// `top`.
    Top,
    /// `bottom`.
    Bottom,
    /// `end`: an end slot, open to the nearer end of the lamella (its
    /// width across y, its depth along x from that end).
    End,
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
    /// `top`, `bottom` or `end` for slots.
    pub edge: Option<PlanSlotEdge>,
    /// Crossing angles a slot was swept over, degrees.
    pub angle_range_deg: Option<[f64; 2]>,
    /// Where it sits along the piece, measured from the piece's own cut
    /// start end (x = 0, the end the engraved orientation arrow points
    /// from), mm: the one zero every station a crew reads is measured from.
    /// For a lamella it equals the feature's x.
    pub station_mm: Option<f64>,
    /// The same feature's station on the line the piece was cut along (a
    /// lamella's own centre line, an edge strip's curve), from that line's
    /// start, mm: `station_start_mm + station_mm`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub line_station_mm: Option<f64>,
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
    /// The bought hardware: bolts by joint (size, standard length, grip,
    /// torque where the profile gives a class), nuts and plain washers by
    /// size; the takeoff's hardware lines.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hardware: Vec<takeoff::HardwareLine>,
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
    /// Every lamella of every A and B strip has utilisation ≤ 1 and a
    /// sagitta within `limit_sagitta_mm`.
    pub passes: bool,
    /// Number of strips with a lamella above utilisation 1.
    pub strips_overstressed: usize,
    /// Number of strips with a lamella whose sagitta is above `limit_sagitta_mm`.
    #[serde(default)]
    pub strips_bowed: usize,
    /// Largest sagitta of any lamella, mm (4 decimals).
    #[serde(default)]
    pub max_sagitta_mm: f64,
    /// The profile's `check.max_sagitta_mm` (or its default), mm.
    #[serde(default)]
    pub limit_sagitta_mm: f64,
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
    /// The largest sagitta of the strip's lamellas, unrolled into their own
    /// planes, mm (4 decimals; absent in plans written before it was reported).
    #[serde(default)]
    pub sagitta_mm: f64,
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
    /// How far its line, unrolled into its own plane, bows off its chord
    /// under kn, mm (4 decimals; absent in plans written before it was reported).
    #[serde(default)]
    pub sagitta_mm: f64,
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
    /// What joins the two curves, as the node schedule names it: the
    /// star washer's part id (`W90`), `ST` (a stud), `slots`, `bolt`, or
    /// for a node on an edge strip `edge bolt` (its band has the edge
    /// bolt's hole there) or `edge slot`; empty before the parts are made.
    /// Not in plan.json.
    #[serde(skip)]
    pub joint: String,
}

/// The name of the orientation mark in plan.json.
pub const ORIENTATION_MARK: &str = "orientation";
