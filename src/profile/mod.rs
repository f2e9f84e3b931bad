//! Material profiles: the validated working model every stage reads, and
//! the quantities derived from it (design strength, lamella offset lines,
//! equivalent elastic limits). The model knows no file: a reader turns a
//! file into a [`RawProfile`], and [`Profile::new`] checks it ([`validate`])
//! and builds the [`Profile`].
//!
//! Guarantees of a [`Profile`] built by [`Profile::new`]: every length,
//! modulus and strength is finite and positive where it must be (gaps and
//! allowances ≥ 0); the joint system has the parts it needs (studs for two
//! levels, a gap for doubling); rotations are quarter turns; timber cut
//! along the grain allows only 0/180°.

pub mod groups;
pub mod validate;

pub use groups::{Piece, PieceStock, StockForm, StockGroup};

use crate::network::Family;
use std::path::PathBuf;

/// A validated material profile: the working type every stage reads, built
/// from a [`RawProfile`] by [`Profile::new`].
pub type Profile = ProfileOf<Stock>;

/// The sections of a material profile, with the stock as `S`: [`Stock`]
/// in the working [`Profile`], [`RawStock`] (as written) in a
/// [`RawProfile`].
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileOf<S> {
    /// The profile's name.
    pub name: String,
    /// Free text from the file (may be empty).
    pub description: String,
    /// The file it was read from (empty when built in memory, and until
    /// the reader sets it).
    pub source: PathBuf,
    /// Elastic and strength values.
    pub material: Material,
    /// The lamella section and lamellas per strip.
    pub section: Section,
    /// How strips meet at the nodes.
    pub joint: Joint,
    /// The bolt through every node (interlocking systems), if any.
    pub node_bolt: Option<Bolt>,
    /// Star washers at the nodes, if the system has them.
    pub washer: Option<Washer>,
    /// Shear blocks of a doubled strip, if any.
    pub shear_block: Option<ShearBlock>,
    /// Studs of a two-level joint (present for `two_level`).
    pub stud: Option<Stud>,
    /// Splice plates for strips longer than the stock, if any.
    pub splice: Option<Splice>,
    /// Bracing cables and their fittings, or none.
    pub bracing: Option<Bracing>,
    /// What the bought bolts are (property class); every field optional.
    pub hardware: Fasteners,
    /// What parts are cut from.
    pub stock: S,
    /// Cutting allowances and allowed rotations (quarter turns).
    pub cutting: Cutting,
    /// Limits of the elastic check beyond the stresses.
    pub check: CheckLimits,
    /// How lamellas meet the edge strips and how bands are split
    /// (`edge_joint:`; every field optional).
    pub edge_joint: EdgeJoint,
    /// The stocks of the parts that are not lamellas, where the file names
    /// them (`stocks:`); every other part takes a default ([`groups`]).
    pub stocks: Vec<PieceStock>,
}

/// A profile as a reader found it, before any check: every section as
/// given, the stock in whichever form it was written ([`RawStock`]).
/// [`Profile::new`] checks it and builds the working profile.
pub type RawProfile = ProfileOf<RawStock>;

/// The material's elastic and strength values.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// The material's name (e.g. `S235`, `larch`).
    pub name: String,
    /// Young's modulus E, MPa (positive).
    pub youngs_modulus_mpa: f64,
    /// Shear modulus G, MPa (positive, below E).
    pub shear_modulus_mpa: f64,
    /// Characteristic strength f_k, MPa (positive): yield for steel,
    /// bending strength for timber.
    pub characteristic_strength_mpa: f64,
    /// Partial factor γ_M (at least 1).
    pub partial_factor: f64,
    /// Strength modification factor k_mod (timber, permanent load; 1 for
    /// steel; at most 1.1).
    pub modification_factor: f64,
    /// Density, kg/m³ (positive).
    pub density_kg_per_m3: f64,
    /// Grain direction: none, or along the strip (timber).
    pub grain: Grain,
}

/// Whether the material has a grain direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Grain {
    /// No grain (steel, aluminium): any allowed quarter turn.
    None,
    /// Timber: strips are cut along the grain, so parts turn only by 0° or 180°.
    AlongStrip,
}

/// The lamella section and how many lamellas make a strip.
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    /// Lamella thickness t, across the strip (along y, the weak axis in
    /// bending), mm (positive, below the height).
    pub thickness_mm: f64,
    /// Lamella height h, along the surface normal (z), mm (positive).
    pub height_mm: f64,
    /// 1 (single) or 2 (doubled and coupled).
    pub per_strip: u32,
    /// Clear gap between the lamellas of a doubled strip, mm (0 when single).
    pub gap_mm: f64,
    /// Added at each end of every strip beyond the curve, mm (≥ 0).
    pub end_allowance_mm: f64,
}

/// How strips are joined at the nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Interlocking (one level) or two-level.
    pub system: JointSystem,
    /// Slot width beyond the crossing lamella's thickness, mm (≥ 0).
    pub slot_clearance_mm: f64,
    /// How far a joint may turn from 90° during flat assembly and erection,
    /// degrees (≥ 0, below 90).
    pub rotation_tolerance_deg: f64,
    /// Two levels: each level's lamella centre sits this far from the
    /// surface, family A above (+z), family B below (−z), mm. 0 for one level.
    pub level_offset_mm: f64,
}

/// How the strips of the two families meet.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointSystem {
    /// One level, halving slots: A from the top edge, B from the bottom.
    Interlocking,
    /// Two levels, continuous strips joined by studs.
    TwoLevel,
}

/// The bolt through every node.
#[derive(Debug, Clone, PartialEq)]
pub struct Bolt {
    /// Bolt diameter, mm.
    pub diameter_mm: f64,
    /// Hole diameter beyond the bolt's, mm.
    pub hole_clearance_mm: f64,
    /// Trade name for the parts list (e.g. `M8`).
    pub designation: String,
}

/// The star washer pair at every node.
#[derive(Debug, Clone, PartialEq)]
pub struct Washer {
    /// Plate thickness, mm.
    pub thickness_mm: f64,
    /// From the node centre to the tip of each arm, mm.
    pub arm_length_mm: f64,
    /// Width of each arm's slot-locating tongue (fits the strip gap), mm.
    pub arm_width_mm: f64,
    /// Per node: a washer top and bottom.
    pub per_node: u32,
}

/// Blocks that couple the two lamellas of a doubled strip.
#[derive(Debug, Clone, PartialEq)]
pub struct ShearBlock {
    /// Block length along the strip, mm.
    pub length_mm: f64,
    /// Largest centre-to-centre spacing of blocks along a strip, mm.
    pub max_spacing_mm: f64,
    /// Largest slenderness (free length / radius of gyration) of one
    /// lamella between blocks.
    pub slenderness_limit: f64,
    /// Clear distance kept from slots and washers, mm.
    pub clearance_mm: f64,
    /// Diameter of the bolt through each block, mm.
    pub bolt_diameter_mm: f64,
}

/// Square studs joining the levels of a two-level joint.
#[derive(Debug, Clone, PartialEq)]
pub struct Stud {
    /// Section is gap × gap; length spans both levels, mm.
    pub length_mm: f64,
    /// Diameter of the fastener through each stud, mm.
    pub fastener_diameter_mm: f64,
    /// Bar stock the studs are cut from, mm.
    pub bar_length_mm: f64,
}

/// The bought bolts' grade (`hardware:` in a profile file; optional, as
/// is every field of it).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Fasteners {
    /// Property class of every bolt (ISO 898-1): `8.8` or `10.9`; nuts and
    /// washers follow it, and the takeoff gives a tightening torque. None:
    /// no class, no torque.
    pub bolt_class: Option<String>,
}

/// The bolt property classes the takeoff knows a tightening torque for.
pub const BOLT_CLASSES: [&str; 2] = ["8.8", "10.9"];

/// `bracing:` the cables that brace the grid's quads, and what fixes them
/// (read as the file writes it; the structure stage designs with it).
///
/// A cable runs between two joints, fixed at each end to an eye plate
/// under the node bolt, `fitting_offset_mm` from the node along the
/// surface normal (on the side the normal points up to). Its assembly
/// from pin to pin: a swaged fork terminal (`terminal_mm` from its pin to
/// where the wire enters), the wire, and a turnbuckle at the other end
/// (`turnbuckle.mid_length_mm` from its pin to the wire at the middle of
/// its take-up `turnbuckle.take_up_mm`).
#[derive(Debug, Clone, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Bracing {
    /// The strand.
    pub cable: CableMaterial,
    /// From the node along the surface normal to the cable's axis at the
    /// eye plate, mm.
    pub fitting_offset_mm: f64,
    /// The eye plate under each node bolt that takes a cable (cut from
    /// plate: a kit part).
    pub eye_plate: EyePlate,
    /// Pin to wire of the fixed end's swaged terminal, mm.
    pub terminal_mm: f64,
    /// The turnbuckle at the other end.
    pub turnbuckle: Turnbuckle,
}

/// `bracing.cable:` the strand's modulus, safety factor and sizes.
#[derive(Debug, Clone, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct CableMaterial {
    /// What it is, for the takeoff.
    pub designation: String,
    /// The strand's modulus over its metallic area, MPa.
    pub youngs_modulus_mpa: f64,
    /// F_Rd = F_uk / this (EN 1993-1-11 §6.3: 1.5·γ_R).
    pub partial_factor: f64,
    /// The sizes, ascending by diameter (at least one).
    pub sizes: Vec<CableSize>,
}

/// One size of `bracing.cable.sizes`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct CableSize {
    /// Nominal diameter, mm.
    pub diameter_mm: f64,
    /// Metallic area, mm².
    pub area_mm2: f64,
    /// Minimum breaking load F_uk, kN.
    pub breaking_load_kn: f64,
}

impl CableSize {
    /// The design resistance F_Rd = F_uk/γ, N.
    pub fn design_resistance_n(&self, partial_factor: f64) -> f64 {
        self.breaking_load_kn * 1000.0 / partial_factor
    }
}

/// `bracing.eye_plate:` a flat plate under the node bolt, its hole on the
/// bolt and a second hole for the cable's pin.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct EyePlate {
    /// Plate thickness, mm.
    pub thickness_mm: f64,
    /// Width, mm.
    pub width_mm: f64,
    /// Between the two holes' centres, mm.
    pub hole_spacing_mm: f64,
    /// The cable pin's hole, mm.
    pub pin_hole_mm: f64,
    /// The plate's yield strength f_y, MPa: by default the profile's
    /// material's characteristic strength (a steel profile; a timber one
    /// must give it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub yield_mpa: Option<f64>,
}

impl EyePlate {
    /// What is left of the plate between a hole of `hole_mm` and its
    /// rim, mm: w/2 − d/2 every way round (the plate's ends are half
    /// circles about its holes, its sides w/2 from their centres).
    pub fn ligament_mm(&self, hole_mm: f64) -> f64 {
        0.5 * (self.width_mm - hole_mm)
    }

    /// Its design resistance to its cable's pull, N, by the pin
    /// connection geometry of EN 1993-1-8 Table 3.9 (type A, thickness t
    /// given): the plate carries F_Ed where the rim beyond the pin hole
    /// (along the pull) is a ≥ F_Ed·γ_M0/(2·t·f_y) + 2·d₀/3 and beside it
    /// c ≥ F_Ed·γ_M0/(2·t·f_y) + d₀/3; both are the ligament a = c =
    /// (w − d₀)/2 here, so F_Rd = 2·t·f_y/γ_M0 · (a − 2·d₀/3). The pin's
    /// own shear and bending are the terminal's rating, not the plate's.
    /// Zero when the ligament is too small for any pull.
    pub fn pin_resistance_n(&self, yield_mpa: f64, gamma_m0: f64) -> f64 {
        let d0 = self.pin_hole_mm;
        let a = self.ligament_mm(d0);
        (2.0 * self.thickness_mm * yield_mpa / gamma_m0 * (a - 2.0 * d0 / 3.0)).max(0.0)
    }
}

/// γ_M0 of an eye plate (EN 1993-1-1 §6.1, the recommended value).
pub const EYE_PLATE_GAMMA_M0: f64 = 1.0;

impl<S> ProfileOf<S> {
    /// The eye plates' yield strength, MPa: `bracing.eye_plate.yield_mpa`,
    /// else the material's characteristic strength where it is steel (no
    /// grain); `None` without bracing, or for timber without one.
    pub fn eye_plate_yield_mpa(&self) -> Option<f64> {
        let e = &self.bracing.as_ref()?.eye_plate;
        e.yield_mpa.or(match self.material.grain {
            Grain::None => Some(self.material.characteristic_strength_mpa),
            Grain::AlongStrip => None,
        })
    }

    /// The eye plate's design resistance to its cable's pull, N
    /// ([`EyePlate::pin_resistance_n`]); `None` without bracing.
    pub fn eye_plate_resistance_n(&self) -> Option<f64> {
        let e = &self.bracing.as_ref()?.eye_plate;
        Some(e.pin_resistance_n(self.eye_plate_yield_mpa()?, EYE_PLATE_GAMMA_M0))
    }
}

/// `bracing.turnbuckle:` its length and take-up.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Turnbuckle {
    /// Pin to the wire at the middle of the take-up, mm.
    pub mid_length_mm: f64,
    /// Total take-up (± half about the middle), mm.
    pub take_up_mm: f64,
}

/// Plates joining strips longer than the stock.
#[derive(Debug, Clone, PartialEq)]
pub struct Splice {
    /// Length of one splice plate, mm.
    pub plate_length_mm: f64,
    /// Bolts on each side of the joint.
    pub bolts_per_side: u32,
    /// Bolt diameter, mm.
    pub bolt_diameter_mm: f64,
}

/// Allowances of the cutting machine.
#[derive(Debug, Clone, PartialEq)]
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

/// Sagitta limit when the profile gives none, mm ([`CheckLimits`]).
pub const DEFAULT_MAX_SAGITTA_MM: f64 = 1.0;

/// Limits of the elastic check beyond the stresses (`check:` in a profile
/// file; optional, as is every field of it).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CheckLimits {
    /// Largest in-plane bow of a lamella's unrolled line, mm: how far the
    /// normal-curvature residual kn bends the line off its chord
    /// (docs/geometry.md, "Sagitta"). None: [`DEFAULT_MAX_SAGITTA_MM`].
    pub max_sagitta_mm: Option<f64>,
}

/// How a lamella that ends on an edge strip is joined to it
/// (docs/fabrication.md, "Edge joints").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EdgeJointKind {
    /// The band runs through the end slot of every lamella ending on it, and
    /// a bolt along the surface normal passes through the gap of the
    /// doubled strip and the band's hole at the node.
    Bolt,
    /// The end slot alone (glued or pinned on site): no hole, no bolt.
    Slot,
}

/// `edge_joint:` in a profile file; every field optional, with the
/// defaults [`Profile::edge_joint_kind`] and [`Profile::edge_bolt_mm`]
/// give.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EdgeJoint {
    /// Bolt or slot; None: a bolt where the strip is doubled and its gap
    /// takes the bolt, else a slot.
    pub kind: Option<EdgeJointKind>,
    /// The edge bolt's diameter, mm; None: the node bolt's.
    pub bolt_diameter_mm: Option<f64>,
    /// Largest bow of an edge band piece (its box across the chord less
    /// the band height), mm: a band that bows more is split. None: bands
    /// are split only where they fit no stock size.
    pub max_band_bow_mm: Option<f64>,
}

/// The form of the stock.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StockKind {
    /// Flat sheets of one or several sizes (flat bars of a fixed length
    /// are sheets too).
    Sheet,
    /// A coil of one width, cut to the length needed.
    Coil,
}

/// What parts are cut from: one or several sheet sizes, or a coil (the
/// working form of the stock, whichever way it was written).
#[derive(Debug, Clone, PartialEq)]
pub struct Stock {
    /// Sheets or coil.
    pub kind: StockKind,
    /// The sizes, in file order; at least one. A coil has exactly one: its
    /// width, and the longest piece if the file gives one.
    pub sizes: Vec<StockSize>,
    /// The file lists the sizes under `sizes:` (else one size inline).
    pub listed: bool,
    /// Currency of the prices, if given.
    pub currency: Option<String>,
    /// Coil: price per metre cut, if given.
    pub price_per_m: Option<f64>,
    /// Coil: lengths are cut in multiples of this, mm (as in the file;
    /// [`Stock::length_step`] gives the default).
    pub length_step_mm: Option<f64>,
}

/// The stock as written, before its form is checked: the fields of the
/// three forms side by side. One sheet size gives `length_mm` and
/// `width_mm` (and optionally `price_per_unit`, `max_count`); several
/// sheet sizes give `sizes` instead; a coil gives `width_mm`, optionally
/// `length_mm` (the longest piece), `length_step_mm` and a price per metre
/// or per piece. [`validate`] says which field of which form is missing or
/// misplaced; [`Stock::from`] builds the working form.
#[derive(Debug, Clone, PartialEq)]
pub struct RawStock {
    /// Sheets or coil.
    pub kind: StockKind,
    /// One sheet size: its length; coil: the longest piece (optional), mm.
    pub length_mm: Option<f64>,
    /// One sheet size: its width; coil: its width, mm.
    pub width_mm: Option<f64>,
    /// Price of one sheet (or coil piece), in `currency`.
    pub price_per_unit: Option<f64>,
    /// Currency of the prices (e.g. `EUR`).
    pub currency: Option<String>,
    /// One sheet size (or coil pieces): how many there are at most.
    pub max_count: Option<u32>,
    /// Several sheet sizes, in file order, each with its length.
    pub sizes: Option<Vec<StockSize>>,
    /// Coil: price per metre cut, in `currency`.
    pub price_per_m: Option<f64>,
    /// Coil: lengths are cut (and sold) in multiples of this, mm.
    pub length_step_mm: Option<f64>,
}

/// One stock size.
#[derive(Debug, Clone, PartialEq)]
pub struct StockSize {
    /// The file's name for it, if any ([`StockSize::label`] gives the default).
    pub name: Option<String>,
    /// Length, mm; `None` only for a coil cut to any length.
    pub length_mm: Option<f64>,
    /// Width, mm.
    pub width_mm: f64,
    /// Price of one sheet (coil: of one piece), if given.
    pub price_per_unit: Option<f64>,
    /// How many there are at most, if limited.
    pub max_count: Option<u32>,
}

impl StockSize {
    /// The size's name, else `length × width` in mm (`3000 × 1500`; a coil
    /// cut to any length: `coil 1500`).
    pub fn label(&self) -> String {
        match (&self.name, self.length_mm) {
            (Some(n), _) => n.clone(),
            (None, Some(l)) => format!("{l} × {}", self.width_mm),
            (None, None) => format!("coil {}", self.width_mm),
        }
    }
    /// Length less the edge margin at both ends, mm (infinite for a coil
    /// cut to any length).
    pub fn usable_length_mm(&self, margin_mm: f64) -> f64 {
        self.length_mm
            .map_or(f64::INFINITY, |l| l - 2.0 * margin_mm)
    }
    /// Width less the edge margin on both sides, mm.
    pub fn usable_width_mm(&self, margin_mm: f64) -> f64 {
        self.width_mm - 2.0 * margin_mm
    }
    /// Whether a `length` × `height` box fits the usable area along the
    /// size (`along`) or turned a quarter (`across`).
    pub fn holds(
        &self,
        length: f64,
        height: f64,
        margin_mm: f64,
        along: bool,
        across: bool,
    ) -> bool {
        let (lu, wu) = (
            self.usable_length_mm(margin_mm),
            self.usable_width_mm(margin_mm),
        );
        (along && length <= lu && height <= wu) || (across && height <= lu && length <= wu)
    }
}

impl Stock {
    /// A coil, cut to length.
    pub fn is_coil(&self) -> bool {
        self.kind == StockKind::Coil
    }
    /// The coil's length step, mm (1 mm unless the file says).
    pub fn length_step(&self) -> f64 {
        self.length_step_mm.unwrap_or(1.0)
    }
    /// Whether every size has a price (a coil: per metre or per piece).
    pub fn priced(&self) -> bool {
        self.price_per_m.is_some() || self.sizes.iter().all(|s| s.price_per_unit.is_some())
    }
    /// The longest usable length of any size wide enough for a part
    /// `height` high (lamellas, splices): what a lamella piece may be at
    /// most. Infinite for a coil cut to any length; when no size is wide
    /// enough, the longest of any (the nest then says the part fits no size).
    pub fn longest_usable_mm(&self, margin_mm: f64, height: f64) -> f64 {
        let longest = |wide: bool| {
            self.sizes
                .iter()
                .filter(|s| !wide || s.usable_width_mm(margin_mm) >= height)
                .map(|s| s.usable_length_mm(margin_mm))
                .fold(0.0, f64::max)
        };
        match longest(true) {
            0.0 => longest(false),
            l => l,
        }
    }
    /// The widest usable width of any size, mm.
    pub fn widest_usable_mm(&self, margin_mm: f64) -> f64 {
        self.sizes
            .iter()
            .map(|s| s.usable_width_mm(margin_mm))
            .fold(0.0, f64::max)
    }
    /// Whether some size holds a `length` × `height` box in one of
    /// `rotations_deg` (quarter turns).
    pub fn holds(&self, length: f64, height: f64, margin_mm: f64, rotations_deg: &[u32]) -> bool {
        let along = rotations_deg.iter().any(|r| r % 180 == 0);
        let across = rotations_deg.iter().any(|r| r % 180 == 90);
        self.sizes
            .iter()
            .any(|s| s.holds(length, height, margin_mm, along, across))
    }
}

impl From<RawStock> for Stock {
    /// The working form of a stock as written (checked first: see
    /// [`validate`]).
    fn from(f: RawStock) -> Stock {
        let listed = f.sizes.is_some();
        let sizes = match f.sizes {
            Some(list) => list,
            None => vec![StockSize {
                name: None,
                length_mm: f.length_mm,
                width_mm: f.width_mm.unwrap_or(0.0),
                price_per_unit: f.price_per_unit,
                max_count: f.max_count,
            }],
        };
        Stock {
            kind: f.kind,
            sizes,
            listed,
            currency: f.currency,
            price_per_m: f.price_per_m,
            length_step_mm: f.length_step_mm,
        }
    }
}

/// What is wrong with a profile: the dotted field name and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FieldError {
    /// Dotted path of the field, as in the file (`lamella.thickness_mm`).
    pub field: String,
    /// What is wrong, one line.
    pub message: String,
}

/// One lamella's reference line relative to its strip's curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LamellaOffset {
    /// 1-based lamella number within the strip.
    pub number: u32,
    /// Tangential offset along y, mm.
    pub dy_mm: f64,
    /// Normal offset along z, mm.
    pub dz_mm: f64,
}

impl LamellaOffset {
    /// The single lamella on the centre line (no profile).
    pub const CENTRE: LamellaOffset = LamellaOffset {
        number: 1,
        dy_mm: 0.0,
        dz_mm: 0.0,
    };
}

impl Profile {
    /// Check a raw profile ([`validate::profile`]) and build the working
    /// profile (`source` as the raw one's: the reader sets it).
    pub fn new(raw: RawProfile) -> Result<Profile, FieldError> {
        validate::profile(&raw)?;
        Ok(Profile {
            name: raw.name,
            description: raw.description,
            source: raw.source,
            material: raw.material,
            section: raw.section,
            joint: raw.joint,
            node_bolt: raw.node_bolt,
            washer: raw.washer,
            shear_block: raw.shear_block,
            stud: raw.stud,
            splice: raw.splice,
            bracing: raw.bracing,
            hardware: raw.hardware,
            stock: Stock::from(raw.stock),
            cutting: raw.cutting,
            check: raw.check,
            edge_joint: raw.edge_joint,
            stocks: raw.stocks,
        })
    }

    /// The edge joint's bolt diameter, mm (`edge_joint.bolt_diameter_mm`,
    /// else the node bolt's), if there is one.
    pub fn edge_bolt_diameter_mm(&self) -> Option<f64> {
        self.edge_joint
            .bolt_diameter_mm
            .or(self.node_bolt.as_ref().map(|b| b.diameter_mm))
    }

    /// Hole clearance of the edge bolt, mm: the node bolt's, else 1 mm
    /// (EN 1090-2 normal round holes, M12 and smaller).
    pub fn edge_bolt_clearance_mm(&self) -> f64 {
        self.node_bolt.as_ref().map_or(1.0, |b| b.hole_clearance_mm)
    }

    /// How lamellas are joined to the edge strips: `edge_joint.kind`, else
    /// a bolt where the strip is doubled and the bolt's hole fits its gap,
    /// else a slot.
    pub fn edge_joint_kind(&self) -> EdgeJointKind {
        self.edge_joint
            .kind
            .unwrap_or_else(|| match self.edge_bolt_diameter_mm() {
                Some(d)
                    if self.section.per_strip == 2
                        && d + self.edge_bolt_clearance_mm() <= self.section.gap_mm =>
                {
                    EdgeJointKind::Bolt
                }
                _ => EdgeJointKind::Slot,
            })
    }

    /// The edge bolt's diameter where the joint is bolted, mm.
    pub fn edge_bolt_mm(&self) -> Option<f64> {
        (self.edge_joint_kind() == EdgeJointKind::Bolt)
            .then(|| self.edge_bolt_diameter_mm())
            .flatten()
    }

    /// Largest sagitta a lamella's unrolled line may have, mm
    /// (`check.max_sagitta_mm`, else [`DEFAULT_MAX_SAGITTA_MM`]).
    pub fn max_sagitta_mm(&self) -> f64 {
        self.check.max_sagitta_mm.unwrap_or(DEFAULT_MAX_SAGITTA_MM)
    }

    /// Lamella thickness t, mm (positive, below the height).
    pub fn thickness_mm(&self) -> f64 {
        self.section.thickness_mm
    }
    /// Lamella height h, mm (positive).
    pub fn height_mm(&self) -> f64 {
        self.section.height_mm
    }
    /// Young's modulus E, MPa (positive).
    pub fn youngs_modulus_mpa(&self) -> f64 {
        self.material.youngs_modulus_mpa
    }
    /// Shear modulus G, MPa (positive, below E).
    pub fn shear_modulus_mpa(&self) -> f64 {
        self.material.shear_modulus_mpa
    }

    /// f_d = k_mod · f_k / γ_M.
    pub fn design_strength_mpa(&self) -> f64 {
        let m = &self.material;
        m.modification_factor * m.characteristic_strength_mpa / m.partial_factor
    }

    /// The lamellas of a strip of `family` and their offset lines: a doubled
    /// strip's lamella mid-planes sit at dy = ∓(g + t)/2 (lamella 1 on −y);
    /// two-level systems lift family A by +level offset, B by −level offset.
    pub fn lamella_offsets(&self, family: Family) -> Vec<LamellaOffset> {
        let l = &self.section;
        let dz_mm = match (self.joint.system, family) {
            (JointSystem::TwoLevel, Family::A) => self.joint.level_offset_mm,
            (JointSystem::TwoLevel, Family::B) => -self.joint.level_offset_mm,
            _ => 0.0,
        };
        if l.per_strip == 2 {
            let d = 0.5 * (l.gap_mm + l.thickness_mm);
            vec![
                LamellaOffset {
                    number: 1,
                    dy_mm: -d,
                    dz_mm,
                },
                LamellaOffset {
                    number: 2,
                    dy_mm: d,
                    dz_mm,
                },
            ]
        } else {
            vec![LamellaOffset {
                number: 1,
                dy_mm: 0.0,
                dz_mm,
            }]
        }
    }

    /// Smallest bending radius in pure weak-axis bending: E·t / (2·f_d).
    pub fn min_bending_radius_mm(&self) -> f64 {
        self.youngs_modulus_mpa() * self.thickness_mm() / (2.0 * self.design_strength_mpa())
    }

    /// Largest twist rate (rad/mm) in pure twist, St. Venant shear and the
    /// trapeze stress together: (E h²/12)² tg⁴ + 3 (G t)² tg² = f_d².
    pub fn max_twist_per_mm(&self) -> f64 {
        let a = (self.youngs_modulus_mpa() * self.height_mm().powi(2) / 12.0).powi(2);
        let b = 3.0 * (self.shear_modulus_mpa() * self.thickness_mm()).powi(2);
        let f2 = self.design_strength_mpa().powi(2);
        // a·x² + b·x − f² = 0 with x = tg².
        let x = 2.0 * f2 / (b + (b * b + 4.0 * a * f2).sqrt());
        x.sqrt()
    }

    /// The same profile with another lamella thickness or height (for `--suggest`).
    pub fn with_section(&self, thickness_mm: f64, height_mm: f64) -> Profile {
        let mut p = self.clone();
        p.section.thickness_mm = thickness_mm;
        p.section.height_mm = height_mm;
        p
    }
}

#[cfg(test)]
mod tests {
    use crate::formats::read::profile_file;
    use std::path::Path;

    #[test]
    fn twist_limit_solves_the_combined_equation() {
        let p = profile_file::load(Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/profiles/steel-1.5.yaml"
        )))
        .expect("profile");
        let tg = p.max_twist_per_mm();
        let sw = p.youngs_modulus_mpa() * tg * tg * p.height_mm().powi(2) / 12.0;
        let tau = p.shear_modulus_mpa() * tg * p.thickness_mm();
        assert!(((sw * sw + 3.0 * tau * tau).sqrt() - p.design_strength_mpa()).abs() < 1e-9);
    }
}
