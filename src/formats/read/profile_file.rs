//! The material profile file (YAML, `version: 1`). Every length names its
//! unit (`_mm`), every stress `_mpa`, every angle `_deg`. Unknown fields are
//! errors, so a typo or a unit-less name (`thickness:`) never passes silently.

use serde::{Deserialize, Serialize};

/// The newest profile version this build reads.
pub const CURRENT_VERSION: u32 = 1;

/// A material profile file as written: material, lamella section, joint,
/// hardware, stock and cutting. Validated by conversion to
/// [`Profile`](crate::profile::Profile).
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ProfileFile {
    /// Format version; this build reads up to [`CURRENT_VERSION`].
    pub version: u32,
    /// The profile's name (as plan.json and the CLI show it).
    pub name: String,
    /// Free text for people; optional.
    #[serde(default)]
    pub description: String,
    /// The material: moduli, strength, safety factors, grain.
    pub material: Material,
    /// The lamella section and how many per strip.
    pub lamella: Lamella,
    /// How strips meet at the nodes.
    pub joint: Joint,
    /// Bolt through every node (interlocking systems), or none.
    pub node_bolt: Option<Bolt>,
    /// Star washer pair at every node, or none.
    pub washer: Option<Washer>,
    /// Shear blocks between the two lamellas of a doubled strip, or none.
    pub shear_block: Option<ShearBlock>,
    /// Square studs through the gaps of both levels (two-level systems), or none.
    pub stud: Option<Stud>,
    /// Splice plates where a strip is longer than the stock, or none.
    pub splice: Option<Splice>,
    /// What the strips are cut from.
    pub stock: Stock,
    /// Cutting allowances and allowed part rotations.
    pub cutting: Cutting,
}

/// `material:` the strip material.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// The material's name (e.g. `S235`, `larch`).
    pub name: String,
    /// Young's modulus E, MPa.
    pub youngs_modulus_mpa: f64,
    /// Shear modulus G, MPa (below E).
    pub shear_modulus_mpa: f64,
    /// Characteristic strength (yield for steel, bending strength for timber).
    pub characteristic_strength_mpa: f64,
    /// Partial factor γ_M.
    pub partial_factor: f64,
    /// Strength modification factor (timber k_mod for permanent load; 1 for steel).
    pub modification_factor: f64,
    /// Density, kg/m³.
    pub density_kg_per_m3: f64,
    /// `none`, or `along_strip` for timber: strips are cut along the grain.
    pub grain: Grain,
}

/// `grain:` whether the material has a grain direction.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Grain {
    /// No grain (steel, aluminium): any rotation in `cutting.allowed_rotations_deg`.
    None,
    /// Timber: strips are cut along the grain, so parts turn only by 0° or 180°.
    AlongStrip,
}

/// `lamella:` the cross-section of one lamella and how many make a strip.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Lamella {
    /// Thickness t, across the strip (along y, the weak axis in bending), mm; below the height.
    pub thickness_mm: f64,
    /// Height h, along the surface normal (z), mm.
    pub height_mm: f64,
    /// 1 (single) or 2 (doubled and coupled).
    pub per_strip: u32,
    /// Clear gap between the two lamellas of a doubled strip (0 when single).
    pub gap_mm: f64,
    /// Added at each end of every strip beyond the curve.
    pub end_allowance_mm: f64,
}

/// `joint:` how the strips meet at the nodes.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Joint {
    /// `interlocking` (one level, halving slots) or `two_level` (studs).
    pub system: JointSystem,
    /// Slot width beyond the crossing plate's width (interlocking).
    pub slot_clearance_mm: f64,
    /// How far a joint may rotate from 90° during flat assembly and erection.
    pub rotation_tolerance_deg: f64,
    /// Two-level systems: each level's lamella centre sits this far from the
    /// surface, family A above (+z), family B below (−z). 0 for one level.
    pub level_offset_mm: f64,
}

/// `joint.system:` how the strips of the two families meet.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum JointSystem {
    /// One level, halving slots: A from the top edge, B from the bottom.
    Interlocking,
    /// Two levels, continuous strips joined by studs.
    TwoLevel,
}

/// `node_bolt:` the bolt through every node.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Bolt {
    /// Bolt diameter, mm.
    pub diameter_mm: f64,
    /// Hole diameter beyond the bolt's, mm.
    pub hole_clearance_mm: f64,
    /// Trade name for the parts list (e.g. `M8`).
    pub designation: String,
}

/// `washer:` the star washer pair at every node.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Washer {
    /// Plate thickness, mm.
    pub thickness_mm: f64,
    /// From the node centre to the tip of each arm.
    pub arm_length_mm: f64,
    /// Width of each arm's slot-locating tongue (fits the strip gap).
    pub arm_width_mm: f64,
    /// Per node: a washer top and bottom.
    pub per_node: u32,
}

/// `shear_block:` blocks that couple the two lamellas of a doubled strip.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ShearBlock {
    /// Block length along the strip, mm.
    pub length_mm: f64,
    /// Largest centre-to-centre spacing of blocks along a strip.
    pub max_spacing_mm: f64,
    /// Largest slenderness (free length / radius of gyration) of one lamella between blocks.
    pub slenderness_limit: f64,
    /// Clear distance kept from slots and washers.
    pub clearance_mm: f64,
    /// Diameter of the bolt through each block, mm.
    pub bolt_diameter_mm: f64,
}

/// `stud:` square studs joining the levels of a two-level joint.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Stud {
    /// Section is gap × gap; length spans both levels.
    pub length_mm: f64,
    /// Diameter of the fastener through each stud, mm.
    pub fastener_diameter_mm: f64,
    /// Bar stock the studs are cut from.
    pub bar_length_mm: f64,
}

/// `splice:` plates joining strips longer than the stock.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Splice {
    /// Length of one splice plate, mm.
    pub plate_length_mm: f64,
    /// Bolts on each side of the joint.
    pub bolts_per_side: u32,
    /// Bolt diameter, mm.
    pub bolt_diameter_mm: f64,
}

/// `stock:` the material the parts are cut from, in one of three forms:
///
/// * one sheet size: `kind: sheet`, `length_mm`, `width_mm`, optional
///   `price_per_unit` and `max_count` (the form every version-1 profile has);
/// * several sheet sizes: `kind: sheet` and `sizes:` a list of
///   [`StockSize`] (then no `length_mm`, `width_mm`, `price_per_unit` or
///   `max_count` beside it);
/// * coil (or strip cut to length): `kind: coil`, `width_mm`, optional
///   `length_mm` (the longest piece cut from it, e.g. a coil's length or
///   the cutting bed's), `length_step_mm` (lengths are cut and sold in
///   multiples of it), and a price: `price_per_m` (per metre cut) or
///   `price_per_unit` (per piece, with `length_mm`).
///
/// [`Profile`](crate::profile::Profile)'s validation says which field of
/// which form is missing or misplaced.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Stock {
    /// `sheet` or `coil`.
    pub kind: StockKind,
    /// One sheet size: its length; coil: the longest piece (optional), mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length_mm: Option<f64>,
    /// One sheet size: its width; coil: its width, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width_mm: Option<f64>,
    /// Price of one sheet (or coil piece), in `currency`; optional.
    #[serde(default)]
    pub price_per_unit: Option<f64>,
    /// Currency of the prices (e.g. `EUR`); optional.
    #[serde(default)]
    pub currency: Option<String>,
    /// One sheet size (or coil pieces): how many there are at most; optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_count: Option<u32>,
    /// Several sheet sizes, instead of `length_mm` and `width_mm`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sizes: Option<Vec<StockSize>>,
    /// Coil: price per metre cut, in `currency`; optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub price_per_m: Option<f64>,
    /// Coil: lengths are cut (and sold) in multiples of this, mm; default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length_step_mm: Option<f64>,
}

/// `stock.sizes[]:` one sheet size of several.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct StockSize {
    /// A name for the size (plan.json and the CLI show it); default
    /// `length × width` (`3000 × 1500`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Sheet length, mm.
    pub length_mm: f64,
    /// Sheet width, mm.
    pub width_mm: f64,
    /// Price of one sheet, in the stock's `currency`; give it for every
    /// size or for none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub price_per_unit: Option<f64>,
    /// How many sheets of this size there are at most; optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_count: Option<u32>,
}

/// `stock.kind:` the form of the stock.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum StockKind {
    /// Flat sheets of `length_mm` × `width_mm`, or of several `sizes`
    /// (flat bars of a fixed length are sheets too).
    Sheet,
    /// A coil `width_mm` wide, cut to the length needed.
    Coil,
}

/// `cutting:` allowances of the cutting machine.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Cutting {
    /// Width the cut removes, mm.
    pub kerf_mm: f64,
    /// Clear distance between parts on the stock, mm.
    pub part_spacing_mm: f64,
    /// Clear distance from the stock's edge, mm.
    pub edge_margin_mm: f64,
    /// Rotations allowed on the stock, degrees, each one of 0, 90, 180, 270.
    pub allowed_rotations_deg: Vec<u32>,
}
