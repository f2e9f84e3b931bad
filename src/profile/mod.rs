//! Material profiles: read, validate, and the quantities derived from them
//! (design strength, lamella offset lines, equivalent elastic limits).
//!
//! Guarantees after [`Profile::load`]: every length, modulus and strength is
//! finite and positive where it must be (gaps and allowances ≥ 0); the joint
//! system has the parts it needs (studs for two levels, a gap for doubling);
//! rotations are quarter turns; timber cut along the grain allows only 0/180°.

use crate::error::{one_line, Error, Location, Result};
use crate::formats::read::profile_file::{
    self, Bolt, Cutting, Grain, JointSystem, ProfileFile, ShearBlock, Splice, StockKind, Stud,
    Washer, CURRENT_VERSION,
};
use crate::network::Family;
use std::path::{Path, PathBuf};

/// A validated material profile: the working type every stage reads, built
/// from the file type ([`ProfileFile`]) by `TryFrom` (which validates) and
/// turned back into it by `From` (the `resolved` profile of plan.json).
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    /// The profile's name.
    pub name: String,
    /// Free text from the file (may be empty).
    pub description: String,
    /// The file it was read from (empty when built in memory).
    pub source: PathBuf,
    /// Elastic and strength values.
    pub material: Material,
    /// The lamella section and lamellas per strip.
    pub section: Section,
    /// How strips meet at the nodes.
    pub joint: Joint,
    /// The parts later stages size (plain data, as in the file).
    pub node_bolt: Option<Bolt>,
    /// Star washers at the nodes, if the system has them.
    pub washer: Option<Washer>,
    /// Shear blocks of a doubled strip, if any.
    pub shear_block: Option<ShearBlock>,
    /// Studs of a two-level joint (present for `two_level`).
    pub stud: Option<Stud>,
    /// Splice plates for strips longer than the stock, if any.
    pub splice: Option<Splice>,
    /// What parts are cut from.
    pub stock: Stock,
    /// Cutting allowances and allowed rotations (quarter turns).
    pub cutting: Cutting,
}

/// The material's elastic and strength values.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// The material's name.
    pub name: String,
    /// Young's modulus E, MPa (positive).
    pub youngs_modulus_mpa: f64,
    /// Shear modulus G, MPa (positive, below E).
    pub shear_modulus_mpa: f64,
    /// Characteristic strength f_k, MPa (positive).
    pub characteristic_strength_mpa: f64,
    /// γ_M.
    pub partial_factor: f64,
    /// k_mod.
    pub modification_factor: f64,
    /// Density, kg/m³ (positive).
    pub density_kg_per_m3: f64,
    /// Grain direction: none, or along the strip (timber).
    pub grain: Grain,
}

/// The lamella section and how many lamellas make a strip.
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    /// Lamella thickness t, mm (positive, below the height).
    pub thickness_mm: f64,
    /// Lamella height h, along the surface normal, mm (positive).
    pub height_mm: f64,
    /// 1 (single) or 2 (doubled).
    pub per_strip: u32,
    /// Clear gap between the lamellas of a doubled strip.
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
    /// How far a joint may turn from 90° during assembly, degrees (≥ 0).
    pub rotation_tolerance_deg: f64,
    /// Two levels: family A sits this far above the surface, B below.
    pub level_offset_mm: f64,
}

/// What parts are cut from: one or several sheet sizes, or a coil (the
/// working form of the file's `stock:`, whichever way it was written).
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

impl From<profile_file::Stock> for Stock {
    /// The working form of a file's stock (validated first: see `validate`).
    fn from(f: profile_file::Stock) -> Stock {
        let listed = f.sizes.is_some();
        let sizes = match f.sizes {
            Some(list) => list
                .into_iter()
                .map(|s| StockSize {
                    name: s.name,
                    length_mm: Some(s.length_mm),
                    width_mm: s.width_mm,
                    price_per_unit: s.price_per_unit,
                    max_count: s.max_count,
                })
                .collect(),
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

impl From<&Stock> for profile_file::Stock {
    /// The stock as the file wrote it.
    fn from(s: &Stock) -> profile_file::Stock {
        let one = s.sizes.first().filter(|_| !s.listed);
        profile_file::Stock {
            kind: s.kind,
            length_mm: one.and_then(|z| z.length_mm),
            width_mm: one.map(|z| z.width_mm),
            price_per_unit: one.and_then(|z| z.price_per_unit),
            currency: s.currency.clone(),
            max_count: one.and_then(|z| z.max_count),
            sizes: s.listed.then(|| {
                s.sizes
                    .iter()
                    .map(|z| profile_file::StockSize {
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

impl TryFrom<ProfileFile> for Profile {
    type Error = FieldError;

    /// Validate a profile file and build the working profile (`source` empty).
    fn try_from(f: ProfileFile) -> std::result::Result<Profile, FieldError> {
        validate(&f)?;
        let m = f.material;
        let l = f.lamella;
        let j = f.joint;
        Ok(Profile {
            name: f.name,
            description: f.description,
            source: PathBuf::new(),
            material: Material {
                name: m.name,
                youngs_modulus_mpa: m.youngs_modulus_mpa,
                shear_modulus_mpa: m.shear_modulus_mpa,
                characteristic_strength_mpa: m.characteristic_strength_mpa,
                partial_factor: m.partial_factor,
                modification_factor: m.modification_factor,
                density_kg_per_m3: m.density_kg_per_m3,
                grain: m.grain,
            },
            section: Section {
                thickness_mm: l.thickness_mm,
                height_mm: l.height_mm,
                per_strip: l.per_strip,
                gap_mm: l.gap_mm,
                end_allowance_mm: l.end_allowance_mm,
            },
            joint: Joint {
                system: j.system,
                slot_clearance_mm: j.slot_clearance_mm,
                rotation_tolerance_deg: j.rotation_tolerance_deg,
                level_offset_mm: j.level_offset_mm,
            },
            node_bolt: f.node_bolt,
            washer: f.washer,
            shear_block: f.shear_block,
            stud: f.stud,
            splice: f.splice,
            stock: Stock::from(f.stock),
            cutting: f.cutting,
        })
    }
}

impl From<&Profile> for ProfileFile {
    /// The profile as a file (current version): what plan.json keeps as
    /// `resolved`.
    fn from(p: &Profile) -> ProfileFile {
        let (m, l, j) = (&p.material, &p.section, &p.joint);
        ProfileFile {
            version: CURRENT_VERSION,
            name: p.name.clone(),
            description: p.description.clone(),
            material: profile_file::Material {
                name: m.name.clone(),
                youngs_modulus_mpa: m.youngs_modulus_mpa,
                shear_modulus_mpa: m.shear_modulus_mpa,
                characteristic_strength_mpa: m.characteristic_strength_mpa,
                partial_factor: m.partial_factor,
                modification_factor: m.modification_factor,
                density_kg_per_m3: m.density_kg_per_m3,
                grain: m.grain,
            },
            lamella: profile_file::Lamella {
                thickness_mm: l.thickness_mm,
                height_mm: l.height_mm,
                per_strip: l.per_strip,
                gap_mm: l.gap_mm,
                end_allowance_mm: l.end_allowance_mm,
            },
            joint: profile_file::Joint {
                system: j.system,
                slot_clearance_mm: j.slot_clearance_mm,
                rotation_tolerance_deg: j.rotation_tolerance_deg,
                level_offset_mm: j.level_offset_mm,
            },
            node_bolt: p.node_bolt.clone(),
            washer: p.washer.clone(),
            shear_block: p.shear_block.clone(),
            stud: p.stud.clone(),
            splice: p.splice.clone(),
            stock: profile_file::Stock::from(&p.stock),
            cutting: p.cutting.clone(),
        }
    }
}

impl Profile {
    /// Read and validate a profile file.
    pub fn load(path: &Path) -> Result<Profile> {
        if !path.exists() {
            return Err(Error::input(path, Location::File, "no such file"));
        }
        let text = crate::formats::read::read_text(path)?;
        Profile::parse(&text, path)
    }

    /// Parse and validate profile text (`path` names it in messages).
    pub fn parse(text: &str, path: &Path) -> Result<Profile> {
        if text.trim().is_empty() {
            return Err(Error::input(path, Location::File, "the file is empty"));
        }
        crate::formats::read::yaml_guard::check(text, path)?;
        let value: serde_yaml::Value =
            serde_yaml::from_str(text).map_err(|e| yaml_error(path, &e))?;
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

    /// The whole profile as a file would hold it (plan.json's `resolved`).
    pub fn resolved(&self) -> ProfileFile {
        ProfileFile::from(self)
    }
}

/// Check every field of a profile file (see the module's guarantees).
fn validate(f: &ProfileFile) -> std::result::Result<(), FieldError> {
    let err = |field: &str, what: String| {
        Err(FieldError {
            field: field.into(),
            message: what,
        })
    };
    // Every number has a sane upper bound, checked under its own name
    // (a length beyond 10 km is a typo, not a part).
    let at_most = |field: &str, x: f64| -> std::result::Result<(), FieldError> {
        let (max, unit) = if field.ends_with("_mm") {
            (1e7, " mm")
        } else {
            (1e12, "")
        };
        if x <= max {
            Ok(())
        } else {
            err(field, format!("must be at most {max:e}{unit}, got {x:e}"))
        }
    };
    let positive = |field: &str, x: f64| -> std::result::Result<(), FieldError> {
        if x.is_finite() && x > 0.0 {
            at_most(field, x)
        } else {
            err(field, format!("must be positive, got {x}"))
        }
    };
    let non_negative = |field: &str, x: f64| -> std::result::Result<(), FieldError> {
        if x.is_finite() && x >= 0.0 {
            at_most(field, x)
        } else {
            err(field, format!("must be zero or more, got {x}"))
        }
    };
    if f.name.trim().is_empty() {
        return err("name", "must not be empty".into());
    }
    let m = &f.material;
    positive("material.youngs_modulus_mpa", m.youngs_modulus_mpa)?;
    positive("material.shear_modulus_mpa", m.shear_modulus_mpa)?;
    positive(
        "material.characteristic_strength_mpa",
        m.characteristic_strength_mpa,
    )?;
    positive("material.partial_factor", m.partial_factor)?;
    positive("material.modification_factor", m.modification_factor)?;
    positive("material.density_kg_per_m3", m.density_kg_per_m3)?;
    if m.partial_factor < 1.0 {
        return err(
            "material.partial_factor",
            format!("must be at least 1, got {}", m.partial_factor),
        );
    }
    if m.modification_factor > 1.1 {
        return err(
            "material.modification_factor",
            format!("must be at most 1.1, got {}", m.modification_factor),
        );
    }
    if m.shear_modulus_mpa >= m.youngs_modulus_mpa {
        return err(
            "material.shear_modulus_mpa",
            format!(
                "{} is not below Young's modulus {}",
                m.shear_modulus_mpa, m.youngs_modulus_mpa
            ),
        );
    }
    let l = &f.lamella;
    positive("lamella.thickness_mm", l.thickness_mm)?;
    positive("lamella.height_mm", l.height_mm)?;
    non_negative("lamella.gap_mm", l.gap_mm)?;
    non_negative("lamella.end_allowance_mm", l.end_allowance_mm)?;
    if l.thickness_mm >= l.height_mm {
        return err(
            "lamella.thickness_mm",
            format!("{} is not below the height {}", l.thickness_mm, l.height_mm),
        );
    }
    match l.per_strip {
        1 => {}
        2 => positive("lamella.gap_mm", l.gap_mm).map_err(|_| FieldError {
            field: "lamella.gap_mm".into(),
            message: "a doubled strip (per_strip: 2) needs a gap above 0".into(),
        })?,
        n => return err("lamella.per_strip", format!("must be 1 or 2, got {n}")),
    }
    let j = &f.joint;
    non_negative("joint.slot_clearance_mm", j.slot_clearance_mm)?;
    non_negative("joint.level_offset_mm", j.level_offset_mm)?;
    if !(0.0..90.0).contains(&j.rotation_tolerance_deg) {
        return err(
            "joint.rotation_tolerance_deg",
            format!("must be in [0, 90), got {}", j.rotation_tolerance_deg),
        );
    }
    match j.system {
        JointSystem::TwoLevel => {
            if f.stud.is_none() {
                return err("stud", "a two-level joint needs studs".into());
            }
            if l.per_strip != 2 {
                return err(
                    "lamella.per_strip",
                    "a two-level joint puts its stud in the gap of a doubled strip: use 2".into(),
                );
            }
            positive("joint.level_offset_mm", j.level_offset_mm)?;
        }
        JointSystem::Interlocking => {
            if j.level_offset_mm != 0.0 {
                return err(
                    "joint.level_offset_mm",
                    "an interlocking joint has one level: use 0".into(),
                );
            }
        }
    }
    if let Some(b) = &f.node_bolt {
        positive("node_bolt.diameter_mm", b.diameter_mm)?;
        non_negative("node_bolt.hole_clearance_mm", b.hole_clearance_mm)?;
        if l.per_strip == 2 && b.diameter_mm > l.gap_mm {
            return err(
                "node_bolt.diameter_mm",
                format!(
                    "{} does not pass through the {} mm gap between the lamellas",
                    b.diameter_mm, l.gap_mm
                ),
            );
        }
    }
    if let Some(w) = &f.washer {
        positive("washer.thickness_mm", w.thickness_mm)?;
        positive("washer.arm_length_mm", w.arm_length_mm)?;
        positive("washer.arm_width_mm", w.arm_width_mm)?;
        if w.per_node == 0 {
            return err("washer.per_node", "must be at least 1".into());
        }
        if f.node_bolt.is_none() {
            return err(
                "washer",
                "washers are tightened by a node bolt: add node_bolt".into(),
            );
        }
    }
    if let Some(s) = &f.shear_block {
        positive("shear_block.length_mm", s.length_mm)?;
        positive("shear_block.max_spacing_mm", s.max_spacing_mm)?;
        positive("shear_block.slenderness_limit", s.slenderness_limit)?;
        non_negative("shear_block.clearance_mm", s.clearance_mm)?;
        positive("shear_block.bolt_diameter_mm", s.bolt_diameter_mm)?;
        if l.per_strip != 2 {
            return err(
                "shear_block",
                "shear blocks couple two lamellas: needs lamella.per_strip 2".into(),
            );
        }
    }
    if let Some(s) = &f.stud {
        positive("stud.length_mm", s.length_mm)?;
        positive("stud.fastener_diameter_mm", s.fastener_diameter_mm)?;
        positive("stud.bar_length_mm", s.bar_length_mm)?;
    }
    if let Some(s) = &f.splice {
        positive("splice.plate_length_mm", s.plate_length_mm)?;
        positive("splice.bolt_diameter_mm", s.bolt_diameter_mm)?;
        if s.bolts_per_side == 0 {
            return err("splice.bolts_per_side", "must be at least 1".into());
        }
    }
    validate_stock(&f.stock, l.height_mm, &positive, &non_negative)?;
    let c = &f.cutting;
    non_negative("cutting.kerf_mm", c.kerf_mm)?;
    non_negative("cutting.part_spacing_mm", c.part_spacing_mm)?;
    non_negative("cutting.edge_margin_mm", c.edge_margin_mm)?;
    if c.allowed_rotations_deg.is_empty() {
        return err(
            "cutting.allowed_rotations_deg",
            "must allow at least one rotation".into(),
        );
    }
    if let Some(r) = c
        .allowed_rotations_deg
        .iter()
        .find(|r| ![0, 90, 180, 270].contains(*r))
    {
        return err(
            "cutting.allowed_rotations_deg",
            format!("{r} is not one of 0, 90, 180, 270"),
        );
    }
    if m.grain == Grain::AlongStrip {
        if let Some(r) = c
            .allowed_rotations_deg
            .iter()
            .find(|r| **r == 90 || **r == 270)
        {
            return err(
                    "cutting.allowed_rotations_deg",
                    format!("{r}° turns a strip across the grain (material.grain: along_strip allows 0 and 180)"),
                );
        }
    }
    Ok(())
}

/// A number check of `validate` (the field's dotted name, its value).
type NumberCheck<'a> = &'a dyn Fn(&str, f64) -> std::result::Result<(), FieldError>;

/// Check the `stock:` section: which fields each form (one sheet size,
/// several sizes, coil) needs and allows, and their values.
fn validate_stock(
    st: &profile_file::Stock,
    height_mm: f64,
    positive: NumberCheck,
    non_negative: NumberCheck,
) -> std::result::Result<(), FieldError> {
    let err = |field: &str, what: &str| {
        Err(FieldError {
            field: field.into(),
            message: what.into(),
        })
    };
    let wide_enough = |field: &str, w: f64| {
        if w < height_mm {
            err(
                field,
                &format!("{w} is narrower than a lamella ({height_mm} mm)"),
            )
        } else {
            Ok(())
        }
    };
    let count = |field: &str, n: Option<u32>| {
        if n == Some(0) {
            err(field, "must be at least 1")
        } else {
            Ok(())
        }
    };
    if let Some(p) = st.price_per_unit {
        non_negative("stock.price_per_unit", p)?;
    }
    if let Some(p) = st.price_per_m {
        non_negative("stock.price_per_m", p)?;
    }
    if let Some(x) = st.length_step_mm {
        positive("stock.length_step_mm", x)?;
    }
    count("stock.max_count", st.max_count)?;
    if st.currency.as_deref().is_some_and(|c| c.trim().is_empty()) {
        return err("stock.currency", "must not be empty");
    }
    match st.kind {
        StockKind::Sheet => {
            if st.price_per_m.is_some() {
                return err(
                    "stock.price_per_m",
                    "is for a coil (kind: coil); a sheet has price_per_unit",
                );
            }
            if st.length_step_mm.is_some() {
                return err(
                    "stock.length_step_mm",
                    "is for a coil (kind: coil); a sheet is not cut to length",
                );
            }
            let Some(list) = &st.sizes else {
                let Some(l) = st.length_mm else {
                    return err(
                        "stock.length_mm",
                        "missing: a sheet needs length_mm and width_mm, or a list of sizes",
                    );
                };
                let Some(w) = st.width_mm else {
                    return err(
                        "stock.width_mm",
                        "missing: a sheet needs length_mm and width_mm, or a list of sizes",
                    );
                };
                positive("stock.length_mm", l)?;
                positive("stock.width_mm", w)?;
                return wide_enough("stock.width_mm", w);
            };
            for (field, present) in [
                ("stock.length_mm", st.length_mm.is_some()),
                ("stock.width_mm", st.width_mm.is_some()),
                ("stock.price_per_unit", st.price_per_unit.is_some()),
                ("stock.max_count", st.max_count.is_some()),
            ] {
                if present {
                    return err(field, "give it per size in stock.sizes, not beside them");
                }
            }
            if list.is_empty() {
                return err("stock.sizes", "must list at least one size");
            }
            let mut labels: Vec<String> = Vec::with_capacity(list.len());
            for (i, z) in list.iter().enumerate() {
                let f = |name: &str| format!("stock.sizes[{i}].{name}");
                if z.name.as_deref().is_some_and(|n| n.trim().is_empty()) {
                    return err(&f("name"), "must not be empty");
                }
                positive(&f("length_mm"), z.length_mm)?;
                positive(&f("width_mm"), z.width_mm)?;
                wide_enough(&f("width_mm"), z.width_mm)?;
                if let Some(p) = z.price_per_unit {
                    non_negative(&f("price_per_unit"), p)?;
                }
                count(&f("max_count"), z.max_count)?;
                if z.price_per_unit.is_some() != list[0].price_per_unit.is_some() {
                    return err(
                        &f("price_per_unit"),
                        "give a price for every size or for none (costs compare only between priced sizes)",
                    );
                }
                let label = StockSize {
                    name: z.name.clone(),
                    length_mm: Some(z.length_mm),
                    width_mm: z.width_mm,
                    price_per_unit: None,
                    max_count: None,
                }
                .label();
                if let Some(j) = labels.iter().position(|x| *x == label) {
                    return err(
                        &f(if z.name.is_some() {
                            "name"
                        } else {
                            "length_mm"
                        }),
                        &format!("`{label}` is stock.sizes[{j}] again: give each size once"),
                    );
                }
                labels.push(label);
            }
            Ok(())
        }
        StockKind::Coil => {
            if st.sizes.is_some() {
                return err(
                    "stock.sizes",
                    "a coil has one width: give width_mm (and length_mm for the longest piece)",
                );
            }
            let Some(w) = st.width_mm else {
                return err("stock.width_mm", "missing: a coil needs its width");
            };
            positive("stock.width_mm", w)?;
            wide_enough("stock.width_mm", w)?;
            match st.length_mm {
                Some(l) => {
                    positive("stock.length_mm", l)?;
                    if st.length_step_mm.is_some_and(|x| x > l) {
                        return err(
                            "stock.length_step_mm",
                            "is longer than a piece (stock.length_mm)",
                        );
                    }
                }
                None => {
                    if st.price_per_unit.is_some() {
                        return err(
                            "stock.price_per_unit",
                            "is per piece: give the piece length (length_mm), or price_per_m",
                        );
                    }
                    if st.max_count.is_some() {
                        return err(
                            "stock.max_count",
                            "counts pieces: give the piece length (length_mm)",
                        );
                    }
                }
            }
            if st.price_per_unit.is_some() && st.price_per_m.is_some() {
                return err(
                    "stock.price_per_m",
                    "give price_per_m or price_per_unit, not both",
                );
            }
            Ok(())
        }
    }
}

impl Profile {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn twist_limit_solves_the_combined_equation() {
        let p = Profile::load(Path::new(concat!(
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
