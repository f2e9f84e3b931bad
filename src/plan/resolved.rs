//! The `resolved` profile of plan.json: the whole profile in the shape of a
//! profile file of the current version, so a later stage can read it back
//! as one. The plan's own types, field for field the profile file's (a
//! test holds the two equal for every shipped profile).

use crate::profile::{self, Grain, JointSystem, Profile, StockKind};
use serde::Serialize;

/// The profile file version the `resolved` profile is written as.
pub const PROFILE_VERSION: u32 = 1;

/// The whole profile as plan.json's `resolved` (its keys sorted, as a JSON
/// value's are).
pub fn resolved(p: &Profile) -> serde_json::Value {
    serde_json::to_value(Resolved::of(p)).unwrap_or(serde_json::Value::Null)
}

/// The profile file's top level.
#[derive(Serialize)]
struct Resolved<'a> {
    version: u32,
    name: &'a str,
    description: &'a str,
    material: Material<'a>,
    lamella: Lamella,
    joint: Joint,
    node_bolt: Option<Bolt<'a>>,
    washer: Option<Washer>,
    shear_block: Option<ShearBlock>,
    stud: Option<Stud>,
    splice: Option<Splice>,
    stock: Stock<'a>,
    cutting: Cutting<'a>,
}

/// `material:`
#[derive(Serialize)]
struct Material<'a> {
    name: &'a str,
    youngs_modulus_mpa: f64,
    shear_modulus_mpa: f64,
    characteristic_strength_mpa: f64,
    partial_factor: f64,
    modification_factor: f64,
    density_kg_per_m3: f64,
    grain: &'static str,
}

/// `lamella:` (the profile's section).
#[derive(Serialize)]
struct Lamella {
    thickness_mm: f64,
    height_mm: f64,
    per_strip: u32,
    gap_mm: f64,
    end_allowance_mm: f64,
}

/// `joint:`
#[derive(Serialize)]
struct Joint {
    system: &'static str,
    slot_clearance_mm: f64,
    rotation_tolerance_deg: f64,
    level_offset_mm: f64,
}

/// `node_bolt:`
#[derive(Serialize)]
struct Bolt<'a> {
    diameter_mm: f64,
    hole_clearance_mm: f64,
    designation: &'a str,
}

/// `washer:`
#[derive(Serialize)]
struct Washer {
    thickness_mm: f64,
    arm_length_mm: f64,
    arm_width_mm: f64,
    per_node: u32,
}

/// `shear_block:`
#[derive(Serialize)]
struct ShearBlock {
    length_mm: f64,
    max_spacing_mm: f64,
    slenderness_limit: f64,
    clearance_mm: f64,
    bolt_diameter_mm: f64,
}

/// `stud:`
#[derive(Serialize)]
struct Stud {
    length_mm: f64,
    fastener_diameter_mm: f64,
    bar_length_mm: f64,
}

/// `splice:`
#[derive(Serialize)]
struct Splice {
    plate_length_mm: f64,
    bolts_per_side: u32,
    bolt_diameter_mm: f64,
}

/// `stock:` one size inline, or the list under `sizes`; the fields a form
/// does not use are left out, except the price per unit and the currency
/// (null).
#[derive(Serialize)]
struct Stock<'a> {
    kind: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    length_mm: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    width_mm: Option<f64>,
    price_per_unit: Option<f64>,
    currency: Option<&'a str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_count: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    sizes: Option<Vec<StockSize<'a>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    price_per_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    length_step_mm: Option<f64>,
}

/// `stock.sizes[]:`
#[derive(Serialize)]
struct StockSize<'a> {
    #[serde(skip_serializing_if = "Option::is_none")]
    name: Option<&'a str>,
    length_mm: f64,
    width_mm: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    price_per_unit: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_count: Option<u32>,
}

/// `cutting:`
#[derive(Serialize)]
struct Cutting<'a> {
    kerf_mm: f64,
    part_spacing_mm: f64,
    edge_margin_mm: f64,
    allowed_rotations_deg: &'a [u32],
}

impl<'a> Resolved<'a> {
    /// The profile in the file's shape.
    fn of(p: &'a Profile) -> Self {
        let (m, l, j) = (&p.material, &p.section, &p.joint);
        Resolved {
            version: PROFILE_VERSION,
            name: &p.name,
            description: &p.description,
            material: Material {
                name: &m.name,
                youngs_modulus_mpa: m.youngs_modulus_mpa,
                shear_modulus_mpa: m.shear_modulus_mpa,
                characteristic_strength_mpa: m.characteristic_strength_mpa,
                partial_factor: m.partial_factor,
                modification_factor: m.modification_factor,
                density_kg_per_m3: m.density_kg_per_m3,
                grain: match m.grain {
                    Grain::None => "none",
                    Grain::AlongStrip => "along_strip",
                },
            },
            lamella: Lamella {
                thickness_mm: l.thickness_mm,
                height_mm: l.height_mm,
                per_strip: l.per_strip,
                gap_mm: l.gap_mm,
                end_allowance_mm: l.end_allowance_mm,
            },
            joint: Joint {
                system: match j.system {
                    JointSystem::Interlocking => "interlocking",
                    JointSystem::TwoLevel => "two_level",
                },
                slot_clearance_mm: j.slot_clearance_mm,
                rotation_tolerance_deg: j.rotation_tolerance_deg,
                level_offset_mm: j.level_offset_mm,
            },
            node_bolt: p.node_bolt.as_ref().map(|b| Bolt {
                diameter_mm: b.diameter_mm,
                hole_clearance_mm: b.hole_clearance_mm,
                designation: &b.designation,
            }),
            washer: p.washer.as_ref().map(|w| Washer {
                thickness_mm: w.thickness_mm,
                arm_length_mm: w.arm_length_mm,
                arm_width_mm: w.arm_width_mm,
                per_node: w.per_node,
            }),
            shear_block: p.shear_block.as_ref().map(|s| ShearBlock {
                length_mm: s.length_mm,
                max_spacing_mm: s.max_spacing_mm,
                slenderness_limit: s.slenderness_limit,
                clearance_mm: s.clearance_mm,
                bolt_diameter_mm: s.bolt_diameter_mm,
            }),
            stud: p.stud.as_ref().map(|s| Stud {
                length_mm: s.length_mm,
                fastener_diameter_mm: s.fastener_diameter_mm,
                bar_length_mm: s.bar_length_mm,
            }),
            splice: p.splice.as_ref().map(|s| Splice {
                plate_length_mm: s.plate_length_mm,
                bolts_per_side: s.bolts_per_side,
                bolt_diameter_mm: s.bolt_diameter_mm,
            }),
            stock: Stock::of(&p.stock),
            cutting: Cutting {
                kerf_mm: p.cutting.kerf_mm,
                part_spacing_mm: p.cutting.part_spacing_mm,
                edge_margin_mm: p.cutting.edge_margin_mm,
                allowed_rotations_deg: &p.cutting.allowed_rotations_deg,
            },
        }
    }
}

impl<'a> Stock<'a> {
    /// The stock as the file wrote it: one size inline, or the list.
    fn of(s: &'a profile::Stock) -> Self {
        let one = s.sizes.first().filter(|_| !s.listed);
        Stock {
            kind: match s.kind {
                StockKind::Sheet => "sheet",
                StockKind::Coil => "coil",
            },
            length_mm: one.and_then(|z| z.length_mm),
            width_mm: one.map(|z| z.width_mm),
            price_per_unit: one.and_then(|z| z.price_per_unit),
            currency: s.currency.as_deref(),
            max_count: one.and_then(|z| z.max_count),
            sizes: s.listed.then(|| {
                s.sizes
                    .iter()
                    .map(|z| StockSize {
                        name: z.name.as_deref(),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::read::profile_file::{self, ProfileFile, CURRENT_VERSION};

    #[test]
    fn resolved_is_the_profile_file_of_every_shipped_profile() {
        assert_eq!(PROFILE_VERSION, CURRENT_VERSION);
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("profiles");
        let mut names: Vec<_> = std::fs::read_dir(&dir)
            .expect("profiles")
            .map(|e| e.expect("entry").path())
            .filter(|p| p.extension().is_some_and(|e| e == "yaml"))
            .collect();
        names.sort();
        assert!(names.len() >= 4, "{names:?}");
        for path in names {
            let p = profile_file::load(&path).expect("profile");
            let file = ProfileFile::from(&p);
            assert_eq!(
                resolved(&p),
                serde_json::to_value(&file).expect("json"),
                "{}",
                path.display()
            );
        }
    }

    #[test]
    fn resolved_is_the_profile_file_of_every_stock_form() {
        let steel = std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("profiles/steel-1.5.yaml"),
        )
        .expect("profile");
        let (a, b) = (
            steel.find("stock:\n").expect("stock"),
            steel.find("cutting:\n").expect("cutting"),
        );
        for stock in [
            "stock:\n  kind: sheet\n  length_mm: 3000\n  width_mm: 1500\n  max_count: 4\n",
            "stock:\n  kind: sheet\n  sizes:\n    - {name: large, length_mm: 3000, width_mm: 1500, max_count: 2}\n    - {length_mm: 2000, width_mm: 1000}\n",
            "stock:\n  kind: coil\n  width_mm: 130\n  price_per_m: 12.5\n  currency: EUR\n  length_step_mm: 10\n",
            "stock:\n  kind: coil\n  width_mm: 130\n  length_mm: 6000\n  price_per_unit: 40\n",
        ] {
            let text = format!("{}{stock}{}", &steel[..a], &steel[b..]);
            let p = profile_file::parse(&text, std::path::Path::new("test.yaml")).expect(stock);
            let file: ProfileFile = serde_yaml::from_str(&text).expect("yaml");
            assert_eq!(
                resolved(&p),
                serde_json::to_value(&file).expect("json"),
                "{stock}"
            );
        }
    }
}
