//! The material profile file (YAML, `version: 1`). Every length names its
//! unit (`_mm`), every stress `_mpa`, every angle `_deg`. Unknown fields are
//! errors, so a typo or a unit-less name (`thickness:`) never passes silently.
//!
//! [`load`] reads a file into the working [`Profile`]: the YAML guard, the
//! version (older versions upgraded), the file types here, then
//! [`RawProfile`] and [`Profile::new`]'s checks. `From<&Profile>` turns a
//! profile back into the file form.

use crate::error::{one_line, Error, Location, Result};
use crate::profile::{self, Profile, RawProfile, RawStock};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The newest profile version this build reads.
pub const CURRENT_VERSION: u32 = 1;

/// Declares a file section with the size and price fields of `stock:`
/// (one sheet size, several `sizes`, or a coil) between fields of its
/// own: `stock:` and every `stocks.<piece>:` entry share them this way,
/// as serde's `flatten` would lose `deny_unknown_fields`. `price and
/// currency` is those two fields' serde attribute (the lamella stock
/// writes them when empty).
macro_rules! sized_stock {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            $($(#[$bmeta:meta])* pub $before:ident: $bty:ty,)*
        }
        price and currency: #[$price:meta]
        then {
            $($(#[$ameta:meta])* pub $after:ident: $aty:ty,)*
        }
    ) => {
        $(#[$meta])*
        pub struct $name {
            $($(#[$bmeta])* pub $before: $bty,)*
            /// One sheet size: its length; coil: the longest piece (optional), mm.
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub length_mm: Option<f64>,
            /// One sheet size: its width; coil: its width, mm.
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub width_mm: Option<f64>,
            /// Price of one sheet (or coil piece, or bar), in `currency`; optional.
            #[$price]
            pub price_per_unit: Option<f64>,
            /// Currency of the prices (e.g. `EUR`); optional.
            #[$price]
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
            $($(#[$ameta])* pub $after: $aty,)*
        }
    };
}

/// A section of type `$to` with the other fields given and the size and
/// price fields of [`sized_stock`] moved from `$from`.
macro_rules! stock_sizes {
    ($from:expr => $to:ident { $($field:ident $(: $value:expr)?),* $(,)? }) => {{
        let from = $from;
        $to {
            $($field $(: $value)?,)*
            length_mm: from.length_mm,
            width_mm: from.width_mm,
            price_per_unit: from.price_per_unit,
            currency: from.currency,
            max_count: from.max_count,
            sizes: from.sizes,
            price_per_m: from.price_per_m,
            length_step_mm: from.length_step_mm,
        }
    }};
}

/// A material profile file as written: material, lamella section, joint,
/// hardware, stock and cutting. Validated by conversion to [`Profile`].
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
    /// Bracing cables and their fittings; optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bracing: Option<profile::Bracing>,
    /// The bought bolts' property class; optional.
    #[serde(default, skip_serializing_if = "Fasteners::is_empty")]
    pub hardware: Fasteners,
    /// What the strips are cut from.
    pub stock: Stock,
    /// Cutting allowances and allowed part rotations.
    pub cutting: Cutting,
    /// Limits of the elastic check beyond the stresses; optional.
    #[serde(default, skip_serializing_if = "CheckLimits::is_empty")]
    pub check: CheckLimits,
    /// How lamellas meet the edge strips; optional.
    #[serde(default, skip_serializing_if = "EdgeJoint::is_empty")]
    pub edge_joint: EdgeJoint,
    /// What the other parts are cut from, where not the default; optional.
    #[serde(default, skip_serializing_if = "Stocks::is_empty")]
    pub stocks: Stocks,
}

/// `stocks:` the stock of each part that is not a lamella, where it is
/// not the default ([`crate::profile::groups`]); every entry optional.
#[derive(Debug, Clone, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Stocks {
    /// Edge bands.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edge: Option<PieceStock>,
    /// Splice plates.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub splice: Option<PieceStock>,
    /// Star washers.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub washer: Option<PieceStock>,
    /// Shear blocks.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_block: Option<PieceStock>,
    /// Bracing cables' eye plates.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub eye_plate: Option<PieceStock>,
    /// Studs (bars).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stud: Option<PieceStock>,
}

impl Stocks {
    /// No entry given (the section is then not written).
    pub fn is_empty(&self) -> bool {
        *self == Stocks::default()
    }
}

sized_stock! {
    /// `stocks.<piece>:` what one kind of part is cut from: a group name, a
    /// material, sizes in any form `stock:` takes (`kind`, `length_mm`,
    /// `width_mm`, `sizes`, …), a price and the cutting allowances; every
    /// field optional.
    #[derive(Debug, Clone, Default, Deserialize, Serialize, PartialEq)]
    #[serde(deny_unknown_fields)]
    pub struct PieceStock {
        /// The group's name (sheet file names); default `ROLE-THICKNESS`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub name: Option<String>,
        /// The material, if not the profile's `material.name`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub material: Option<String>,
        /// `sheet` or `coil` (with sizes of its own).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub kind: Option<StockKind>,
    }
    price and currency: #[serde(default, skip_serializing_if = "Option::is_none")]
    then {
        /// Kerf, mm; default `cutting.kerf_mm`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub kerf_mm: Option<f64>,
        /// Part spacing, mm; default `cutting.part_spacing_mm` (bars: 0).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub part_spacing_mm: Option<f64>,
        /// Edge margin, mm; default `cutting.edge_margin_mm` (bars: 0).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub edge_margin_mm: Option<f64>,
        /// Allowed rotations, degrees; default `cutting.allowed_rotations_deg`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub allowed_rotations_deg: Option<Vec<u32>>,
    }
}

impl PieceStock {
    /// The entry as the model keeps it: the sizes as a stock of their
    /// own where any size field is given (the price and currency then
    /// with them), else only the price of one default sheet or bar.
    fn into_model(self, piece: profile::Piece) -> profile::PieceStock {
        let sized = self.kind.is_some()
            || self.length_mm.is_some()
            || self.width_mm.is_some()
            || self.sizes.is_some()
            || self.max_count.is_some()
            || self.price_per_m.is_some()
            || self.length_step_mm.is_some();
        let mut entry = profile::PieceStock {
            piece,
            name: self.name.clone(),
            material: self.material.clone(),
            stock: None,
            price_per_unit: None,
            currency: None,
            kerf_mm: self.kerf_mm,
            part_spacing_mm: self.part_spacing_mm,
            edge_margin_mm: self.edge_margin_mm,
            allowed_rotations_deg: self.allowed_rotations_deg.clone(),
        };
        if sized {
            let kind = self.kind.unwrap_or_default();
            entry.stock = Some(stock_sizes!(self => Stock { kind }).into());
        } else {
            (entry.price_per_unit, entry.currency) = (self.price_per_unit, self.currency);
        }
        entry
    }

    /// The model's entry back in the file's form.
    fn from_model(e: &profile::PieceStock) -> PieceStock {
        let st = match &e.stock {
            Some(s) => Stock::from(&profile::Stock::from(s.clone())),
            None => Stock {
                price_per_unit: e.price_per_unit,
                currency: e.currency.clone(),
                ..Stock::default()
            },
        };
        // `sheet` is the default a file may leave out.
        let kind = Some(st.kind).filter(|k| *k != StockKind::Sheet);
        stock_sizes!(st => PieceStock {
            name: e.name.clone(),
            material: e.material.clone(),
            kind,
            kerf_mm: e.kerf_mm,
            part_spacing_mm: e.part_spacing_mm,
            edge_margin_mm: e.edge_margin_mm,
            allowed_rotations_deg: e.allowed_rotations_deg.clone(),
        })
    }
}

impl Stocks {
    /// The entries in the model's form, in piece order.
    fn into_model(self) -> Vec<profile::PieceStock> {
        use profile::Piece;
        [
            (Piece::EdgeBand, self.edge),
            (Piece::SplicePlate, self.splice),
            (Piece::Washer, self.washer),
            (Piece::ShearBlock, self.shear_block),
            (Piece::EyePlate, self.eye_plate),
            (Piece::Stud, self.stud),
        ]
        .into_iter()
        .filter_map(|(piece, e)| e.map(|e| e.into_model(piece)))
        .collect()
    }

    /// The model's entries in the file's form.
    fn from_model(list: &[profile::PieceStock]) -> Stocks {
        use profile::Piece;
        let get = |piece: Piece| {
            list.iter()
                .find(|e| e.piece == piece)
                .map(PieceStock::from_model)
        };
        Stocks {
            edge: get(Piece::EdgeBand),
            splice: get(Piece::SplicePlate),
            washer: get(Piece::Washer),
            shear_block: get(Piece::ShearBlock),
            eye_plate: get(Piece::EyePlate),
            stud: get(Piece::Stud),
        }
    }
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

/// `hardware:` what the bought bolts are; every field optional.
#[derive(Debug, Clone, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Fasteners {
    /// Property class of every bolt (ISO 898-1), `8.8` or `10.9` (quoted or
    /// not); the takeoff gives nuts and washers to match and a tightening
    /// torque per bolt.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "class_text"
    )]
    pub bolt_class: Option<String>,
}

impl Fasteners {
    /// No field given (the section is then not written).
    pub fn is_empty(&self) -> bool {
        self.bolt_class.is_none()
    }
}

/// A property class as text, written quoted (`"8.8"`) or as a number (`8.8`).
fn class_text<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> std::result::Result<Option<String>, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Class {
        Text(String),
        Number(f64),
    }
    Ok(Some(match Class::deserialize(d)? {
        Class::Text(s) => s,
        Class::Number(x) => format!("{x}"),
    }))
}

sized_stock! {
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
    /// [`Profile`]'s validation ([`crate::profile::validate`]) says which field
    /// of which form is missing or misplaced.
    #[derive(Debug, Clone, Default, Deserialize, Serialize, PartialEq)]
    #[serde(deny_unknown_fields)]
    pub struct Stock {
        /// `sheet` or `coil`.
        pub kind: StockKind,
    }
    price and currency: #[serde(default)]
    then {}
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
#[derive(Debug, Clone, Copy, Default, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum StockKind {
    /// Flat sheets of `length_mm` × `width_mm`, or of several `sizes`
    /// (flat bars of a fixed length are sheets too).
    #[default]
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

/// `check:` limits of the elastic check beyond the stresses; every field
/// optional.
#[derive(Debug, Clone, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CheckLimits {
    /// Largest sagitta of a lamella's unrolled line, mm; default
    /// [`profile::DEFAULT_MAX_SAGITTA_MM`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_sagitta_mm: Option<f64>,
}

/// `edge_joint:` how lamellas meet the edge strips; every field optional
/// (docs/fabrication.md, "Edge joints").
#[derive(Debug, Clone, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct EdgeJoint {
    /// `bolt` or `slot`; default: a bolt where the strip is doubled and
    /// its gap takes the bolt, else a slot.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<EdgeJointKind>,
    /// The edge bolt's diameter, mm; default the node bolt's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bolt_diameter_mm: Option<f64>,
    /// Largest bow of an edge band piece, mm; default none (bands are
    /// split only where they fit no stock size).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_band_bow_mm: Option<f64>,
}

/// `edge_joint.kind`.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum EdgeJointKind {
    /// A bolt through the band at every edge node.
    Bolt,
    /// The lamella's end slot alone.
    Slot,
}

impl EdgeJoint {
    /// No field given (the section is then not written).
    pub fn is_empty(&self) -> bool {
        self.kind.is_none() && self.bolt_diameter_mm.is_none() && self.max_band_bow_mm.is_none()
    }
}

impl CheckLimits {
    /// No field given (the section is then not written).
    pub fn is_empty(&self) -> bool {
        self.max_sagitta_mm.is_none()
    }
}

/// Read and validate a profile file.
pub fn load(path: &Path) -> Result<Profile> {
    if !path.exists() {
        return Err(Error::input(path, Location::File, "no such file"));
    }
    let text = crate::formats::read::read_text(path)?;
    parse(&text, path)
}

/// Parse and validate profile text (`path` names it in messages and
/// becomes the profile's `source`).
pub fn parse(text: &str, path: &Path) -> Result<Profile> {
    if text.trim().is_empty() {
        return Err(Error::input(path, Location::File, "the file is empty"));
    }
    crate::formats::read::yaml_guard::check(text, path)?;
    let value: serde_yaml::Value = serde_yaml::from_str(text).map_err(|e| yaml_error(path, &e))?;
    let version = match value.get("version") {
        None => {
            return Err(Error::input(
                path,
                Location::Field("version".into()),
                format!("missing; this lamella reads profile version {CURRENT_VERSION}"),
            ))
        }
        Some(v) => v.as_u64().ok_or_else(|| {
            Error::input(
                path,
                Location::Field("version".into()),
                "must be a whole number",
            )
        })?,
    };
    let value = upgrade(value, version, path)?;
    let file: ProfileFile = serde_yaml::from_value(value).map_err(|e| {
        // from_value has no location: re-parse the text for it.
        match serde_yaml::from_str::<ProfileFile>(text) {
            Err(located) => yaml_error(path, &located),
            Ok(_) => Error::input(path, Location::File, one_line(&e.to_string())),
        }
    })?;
    let mut profile = Profile::try_from(file)
        .map_err(|e| Error::input(path, Location::Field(e.field), e.message))?;
    profile.source = path.to_path_buf();
    Ok(profile)
}

/// Bring an older profile to the current version. Version 1 is the first;
/// a later version adds its step here, and a test per version keeps it.
fn upgrade(value: serde_yaml::Value, version: u64, path: &Path) -> Result<serde_yaml::Value> {
    match version {
        1 => Ok(value),
        v if v > u64::from(CURRENT_VERSION) => Err(Error::input(
            path,
            Location::Field("version".into()),
            format!("profile version {v} is newer than this lamella reads ({CURRENT_VERSION}): update lamella"),
        )),
        v => Err(Error::input(
            path,
            Location::Field("version".into()),
            format!("unknown profile version {v} (this lamella reads {CURRENT_VERSION})"),
        )),
    }
}

/// A YAML error as one line with its location, and a hint when a field was
/// written without its unit (`thickness:` for `thickness_mm:`).
fn yaml_error(path: &Path, e: &serde_yaml::Error) -> Error {
    let (at, msg) = crate::error::yaml_error_parts(e);
    // serde_yaml writes "section: unknown field `x`, expected one of ...".
    if let Some(i) = msg.find("unknown field `") {
        let prefix = msg[..i].trim_end_matches([' ', ':']);
        let name = msg[i + "unknown field `".len()..]
            .split('`')
            .next()
            .unwrap_or("");
        for unit in ["_mm", "_mpa", "_deg", "_kg_per_m3"] {
            let with_unit = format!("`{name}{unit}`");
            if msg.contains(&with_unit) {
                let dotted = if prefix.is_empty() {
                    name.to_string()
                } else {
                    format!("{prefix}.{name}")
                };
                return Error::input(
                    path,
                    at,
                    format!("field `{dotted}` has no unit in its name: write {with_unit}"),
                );
            }
        }
    }
    Error::input(path, at, msg)
}

// ---------------------------------------------------------------------------
// File form → model

impl TryFrom<ProfileFile> for Profile {
    type Error = profile::FieldError;

    /// Validate a profile file and build the working profile (`source` empty).
    fn try_from(f: ProfileFile) -> std::result::Result<Profile, profile::FieldError> {
        Profile::new(RawProfile::from(f))
    }
}

impl From<ProfileFile> for RawProfile {
    /// The file's sections as the model's, unchecked (the version is the
    /// reader's business).
    fn from(f: ProfileFile) -> RawProfile {
        RawProfile {
            name: f.name,
            description: f.description,
            source: std::path::PathBuf::new(),
            material: f.material.into(),
            section: f.lamella.into(),
            joint: f.joint.into(),
            node_bolt: f.node_bolt.map(Into::into),
            washer: f.washer.map(Into::into),
            shear_block: f.shear_block.map(Into::into),
            stud: f.stud.map(Into::into),
            splice: f.splice.map(Into::into),
            bracing: f.bracing,
            hardware: f.hardware.into(),
            stock: f.stock.into(),
            cutting: f.cutting.into(),
            check: f.check.into(),
            edge_joint: f.edge_joint.into(),
            stocks: f.stocks.into_model(),
        }
    }
}

/// `From` both ways between a file's enum and the model's enum of the same
/// name and variants.
macro_rules! same_variants {
    ($name:ident { $($variant:ident),+ $(,)? }) => {
        impl From<$name> for profile::$name {
            fn from(v: $name) -> profile::$name {
                match v {
                    $($name::$variant => profile::$name::$variant,)+
                }
            }
        }

        impl From<profile::$name> for $name {
            fn from(v: profile::$name) -> $name {
                match v {
                    $(profile::$name::$variant => $name::$variant,)+
                }
            }
        }
    };
}

same_variants!(Grain { None, AlongStrip });
same_variants!(JointSystem {
    Interlocking,
    TwoLevel
});
same_variants!(StockKind { Sheet, Coil });

/// `From` both ways between a file's section and the model's of the same
/// fields: by value into the model, by reference back (each field cloned);
/// an enum field converts by [`same_variants`].
macro_rules! same_fields {
    ($file:ident = $model:ident { $($field:ident),+ $(,)? }) => {
        impl From<$file> for profile::$model {
            fn from(v: $file) -> profile::$model {
                profile::$model {
                    $($field: v.$field.into(),)+
                }
            }
        }

        impl From<&profile::$model> for $file {
            fn from(v: &profile::$model) -> $file {
                $file {
                    $($field: v.$field.clone().into(),)+
                }
            }
        }
    };
}

same_fields!(
    Material = Material {
        name,
        youngs_modulus_mpa,
        shear_modulus_mpa,
        characteristic_strength_mpa,
        partial_factor,
        modification_factor,
        density_kg_per_m3,
        grain
    }
);
same_fields!(
    Lamella = Section {
        thickness_mm,
        height_mm,
        per_strip,
        gap_mm,
        end_allowance_mm
    }
);
same_fields!(
    Joint = Joint {
        system,
        slot_clearance_mm,
        rotation_tolerance_deg,
        level_offset_mm
    }
);
same_fields!(
    Bolt = Bolt {
        diameter_mm,
        hole_clearance_mm,
        designation
    }
);
same_fields!(
    Washer = Washer {
        thickness_mm,
        arm_length_mm,
        arm_width_mm,
        per_node
    }
);
same_fields!(
    ShearBlock = ShearBlock {
        length_mm,
        max_spacing_mm,
        slenderness_limit,
        clearance_mm,
        bolt_diameter_mm
    }
);
same_fields!(
    Stud = Stud {
        length_mm,
        fastener_diameter_mm,
        bar_length_mm
    }
);
same_fields!(
    Splice = Splice {
        plate_length_mm,
        bolts_per_side,
        bolt_diameter_mm
    }
);
same_fields!(CheckLimits = CheckLimits { max_sagitta_mm });
same_variants!(EdgeJointKind { Bolt, Slot });

impl From<EdgeJoint> for profile::EdgeJoint {
    fn from(e: EdgeJoint) -> profile::EdgeJoint {
        profile::EdgeJoint {
            kind: e.kind.map(Into::into),
            bolt_diameter_mm: e.bolt_diameter_mm,
            max_band_bow_mm: e.max_band_bow_mm,
        }
    }
}

impl From<&profile::EdgeJoint> for EdgeJoint {
    fn from(e: &profile::EdgeJoint) -> EdgeJoint {
        EdgeJoint {
            kind: e.kind.map(Into::into),
            bolt_diameter_mm: e.bolt_diameter_mm,
            max_band_bow_mm: e.max_band_bow_mm,
        }
    }
}
same_fields!(Fasteners = Fasteners { bolt_class });
same_fields!(
    Cutting = Cutting {
        kerf_mm,
        part_spacing_mm,
        edge_margin_mm,
        allowed_rotations_deg
    }
);

impl From<Stock> for RawStock {
    fn from(s: Stock) -> RawStock {
        RawStock {
            kind: s.kind.into(),
            length_mm: s.length_mm,
            width_mm: s.width_mm,
            price_per_unit: s.price_per_unit,
            currency: s.currency,
            max_count: s.max_count,
            sizes: s
                .sizes
                .map(|list| list.into_iter().map(Into::into).collect()),
            price_per_m: s.price_per_m,
            length_step_mm: s.length_step_mm,
        }
    }
}

impl From<StockSize> for profile::StockSize {
    fn from(z: StockSize) -> profile::StockSize {
        profile::StockSize {
            name: z.name,
            length_mm: Some(z.length_mm),
            width_mm: z.width_mm,
            price_per_unit: z.price_per_unit,
            max_count: z.max_count,
        }
    }
}

// ---------------------------------------------------------------------------
// Model → file form

impl From<&Profile> for ProfileFile {
    /// The profile as a file (current version): what plan.json keeps as
    /// `resolved`.
    fn from(p: &Profile) -> ProfileFile {
        ProfileFile {
            version: CURRENT_VERSION,
            name: p.name.clone(),
            description: p.description.clone(),
            material: (&p.material).into(),
            lamella: (&p.section).into(),
            joint: (&p.joint).into(),
            node_bolt: p.node_bolt.as_ref().map(Into::into),
            washer: p.washer.as_ref().map(Into::into),
            shear_block: p.shear_block.as_ref().map(Into::into),
            stud: p.stud.as_ref().map(Into::into),
            splice: p.splice.as_ref().map(Into::into),
            bracing: p.bracing.clone(),
            hardware: (&p.hardware).into(),
            stock: (&p.stock).into(),
            cutting: (&p.cutting).into(),
            check: (&p.check).into(),
            edge_joint: (&p.edge_joint).into(),
            stocks: Stocks::from_model(&p.stocks),
        }
    }
}

impl From<&profile::Stock> for Stock {
    /// The stock as the file wrote it: one size inline, or the list.
    fn from(s: &profile::Stock) -> Stock {
        let one = s.sizes.first().filter(|_| !s.listed);
        Stock {
            kind: s.kind.into(),
            length_mm: one.and_then(|z| z.length_mm),
            width_mm: one.map(|z| z.width_mm),
            price_per_unit: one.and_then(|z| z.price_per_unit),
            currency: s.currency.clone(),
            max_count: one.and_then(|z| z.max_count),
            sizes: s.listed.then(|| {
                s.sizes
                    .iter()
                    .map(|z| StockSize {
                        name: z.name.clone(),
                        length_mm: z.length_mm.unwrap_or(0.0),
                        width_mm: z.width_mm,
                        price_per_unit: z.price_per_unit,
                        max_count: z.max_count,
                    })
                    .collect()
            }),
            price_per_m: s.price_per_m,
            length_step_mm: s.length_step_mm,
        }
    }
}
