//! The material profile file (YAML, `version: 1`). Every length names its
//! unit (`_mm`), every stress `_mpa`, every angle `_deg`. Unknown fields are
//! errors, so a typo or a unit-less name (`thickness:`) never passes silently.

use serde::{Deserialize, Serialize};

/// The newest profile version this build reads.
pub const CURRENT_VERSION: u32 = 1;

#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ProfileFile {
    pub version: u32,
    pub name: String,
    #[serde(default)]
    pub description: String,
    pub material: Material,
    pub lamella: Lamella,
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
    pub stock: Stock,
    pub cutting: Cutting,
}

#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Material {
    pub name: String,
    pub youngs_modulus_mpa: f64,
    pub shear_modulus_mpa: f64,
    /// Characteristic strength (yield for steel, bending strength for timber).
    pub characteristic_strength_mpa: f64,
    /// Partial factor γ_M.
    pub partial_factor: f64,
    /// Strength modification factor (timber k_mod for permanent load; 1 for steel).
    pub modification_factor: f64,
    pub density_kg_per_m3: f64,
    /// `none`, or `along_strip` for timber: strips are cut along the grain.
    pub grain: Grain,
}

#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Grain {
    None,
    AlongStrip,
}

#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Lamella {
    pub thickness_mm: f64,
    pub height_mm: f64,
    /// 1 (single) or 2 (doubled and coupled).
    pub per_strip: u32,
    /// Clear gap between the two lamellas of a doubled strip (0 when single).
    pub gap_mm: f64,
    /// Added at each end of every strip beyond the curve.
    pub end_allowance_mm: f64,
}

#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Joint {
    pub system: JointSystem,
    /// Slot width beyond the crossing plate's width (interlocking).
    pub slot_clearance_mm: f64,
    /// How far a joint may rotate from 90° during flat assembly and erection.
    pub rotation_tolerance_deg: f64,
    /// Two-level systems: each level's lamella centre sits this far from the
    /// surface, family A above (+z), family B below (−z). 0 for one level.
    pub level_offset_mm: f64,
}

#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum JointSystem {
    /// One level, halving slots: A from the top edge, B from the bottom.
    Interlocking,
    /// Two levels, continuous strips joined by studs.
    TwoLevel,
}

#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Bolt {
    pub diameter_mm: f64,
    pub hole_clearance_mm: f64,
    pub designation: String,
}

#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Washer {
    pub thickness_mm: f64,
    /// From the node centre to the tip of each arm.
    pub arm_length_mm: f64,
    /// Width of each arm's slot-locating tongue (fits the strip gap).
    pub arm_width_mm: f64,
    /// Per node: a washer top and bottom.
    pub per_node: u32,
}

#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ShearBlock {
    pub length_mm: f64,
    /// Largest centre-to-centre spacing of blocks along a strip.
    pub max_spacing_mm: f64,
    /// Largest slenderness (free length / radius of gyration) of one lamella between blocks.
    pub slenderness_limit: f64,
    /// Clear distance kept from slots and washers.
    pub clearance_mm: f64,
    pub bolt_diameter_mm: f64,
}

#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Stud {
    /// Section is gap × gap; length spans both levels.
    pub length_mm: f64,
    pub fastener_diameter_mm: f64,
    /// Bar stock the studs are cut from.
    pub bar_length_mm: f64,
}

#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Splice {
    pub plate_length_mm: f64,
    pub bolts_per_side: u32,
    pub bolt_diameter_mm: f64,
}

#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Stock {
    pub kind: StockKind,
    pub length_mm: f64,
    pub width_mm: f64,
    #[serde(default)]
    pub price_per_unit: Option<f64>,
    #[serde(default)]
    pub currency: Option<String>,
}

#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum StockKind {
    Sheet,
    Coil,
}

#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Cutting {
    pub kerf_mm: f64,
    pub part_spacing_mm: f64,
    pub edge_margin_mm: f64,
    /// Rotations allowed on the stock, degrees, each one of 0, 90, 180, 270.
    pub allowed_rotations_deg: Vec<u32>,
}
