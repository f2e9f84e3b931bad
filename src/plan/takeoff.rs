//! The material takeoff: per part kind, count, length, area and mass (the
//! made parts); the stock per group (material and thickness) and size,
//! sheets and bars, with utilisation and
//! cost; the bought hardware (bolts with their standard lengths, nuts,
//! plain washers; see `fabricate::hardware`); totals per section. Plain data in ([`Kit`], [`Nest`], [`Profile`]), plain data out
//! ([`Takeoff`]), which `formats::write::takeoff` writes as JSON and CSV.
//! Numbers are rounded to fixed decimals so equal kits give equal bytes.

use crate::fabricate::part::PartKind;
use crate::fabricate::{net_area_mm2, part_mass_kg, Kit};
use crate::nest::Nest;
use crate::plan::round;
use crate::profile::{Profile, StockForm};
use serde::{Deserialize, Serialize};

/// The whole takeoff.
#[derive(Debug, Clone, Default, Serialize, PartialEq)]
pub struct Takeoff {
    /// Network name.
    pub project: String,
    /// Profile name.
    pub profile: String,
    /// Currency of every price and cost, when the profile prices its stock.
    pub currency: Option<String>,
    /// One line per part kind.
    pub parts: Vec<PartLine>,
    /// One line per stock group and size (the stud bars too).
    pub stock: Vec<StockLine>,
    /// What is bought rather than cut: bolts by joint, nuts and plain
    /// washers by size (star washers and studs are parts).
    pub hardware: Vec<HardwareLine>,
    /// The bracing, when the grid is braced: the wire by diameter (count
    /// and total cut length), fork terminals, turnbuckles (the eye plates
    /// are parts).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub bracing: Vec<BracingLine>,
    /// Sums.
    pub totals: Totals,
}

/// Parts of one kind.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct PartLine {
    /// `lamella`, `shear_block`, …
    pub kind: String,
    /// The material's name.
    pub material: String,
    /// Thickness it is cut from, mm.
    pub thickness_mm: f64,
    /// Distinct parts.
    pub distinct: usize,
    /// Pieces.
    pub count: u64,
    /// Sum of every piece's length (its extent along x), mm.
    pub length_mm: f64,
    /// Net area (outline less holes) of every piece, m².
    pub area_m2: f64,
    /// Mass of every piece, kg.
    pub mass_kg: f64,
}

/// Stock of one size.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct StockLine {
    /// `sheet 3000 × 1500 × 1.5 mm`, `bar 20 × 20 × 2000 mm`.
    pub item: String,
    /// The stock group it is bought for (`lamella-1.5`).
    pub group: String,
    /// Its material.
    pub material: String,
    /// Its thickness (a bar: its section's side), mm.
    pub thickness_mm: f64,
    /// How many.
    pub count: u64,
    /// Net part area over the stock area (sheets only).
    pub utilization: Option<f64>,
    /// Price of one, when the profile gives it.
    pub unit_price: Option<f64>,
    /// count × unit price.
    pub cost: Option<f64>,
}

/// One line of bought hardware (also plan.json's
/// `parts_summary.hardware`).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct HardwareLine {
    /// `node bolt`, `shear-block bolt`, `splice bolt`, `stud bolt`, `nut`,
    /// `plain washer`.
    pub item: String,
    /// As ordered: `M8 × 70 ISO 4017 8.8`, `M8 ISO 4032 8`, `M5 ISO 7089 200 HV`.
    pub designation: String,
    /// `ISO 4017`, `ISO 4032` or `ISO 7089`.
    pub standard: String,
    /// Thread diameter, mm.
    pub diameter_mm: f64,
    /// Bolts: nominal length, mm (from the standard series).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length_mm: Option<f64>,
    /// Bolts: clamped thickness of the joint's parts, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grip_mm: Option<f64>,
    /// Bolts: grip + plain washers + nut + two thread pitches, mm: the
    /// shortest length the bolt may have.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub needed_mm: Option<f64>,
    /// How many.
    pub count: u64,
    /// Bolts: tightening torque, N·m, when the profile gives the property class.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torque_nm: Option<f64>,
}

/// One line of the bracing.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct BracingLine {
    /// `cable`, `fork terminal`, `turnbuckle`.
    pub item: String,
    /// As ordered (the strand, with its diameter; the fittings by the
    /// diameter they take).
    pub designation: String,
    /// How many.
    pub count: u64,
    /// Cables: Σ of the wires' cut lengths, mm (1 decimal).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length_mm: Option<f64>,
    /// `bought`.
    pub source: String,
}

/// The kit's bought hardware as lines, rounded.
pub fn hardware_lines(kit: &Kit) -> Vec<HardwareLine> {
    kit.summary
        .hardware
        .iter()
        .map(|h| HardwareLine {
            item: h.item.clone(),
            designation: h.designation.clone(),
            standard: h.standard.into(),
            diameter_mm: round(h.diameter_mm, 3),
            length_mm: h.length_mm.map(|g| round(g, 3)),
            grip_mm: h.grip_mm.map(|g| round(g, 3)),
            needed_mm: h.needed_mm.map(|g| round(g, 3)),
            count: h.count,
            torque_nm: h.torque_nm.map(|g| round(g, 2)),
        })
        .collect()
}

/// Sums over the takeoff.
#[derive(Debug, Clone, Default, Serialize, PartialEq)]
pub struct Totals {
    /// Pieces to cut or saw (made).
    pub pieces: u64,
    /// Sum of every made piece's length (its extent along x), m.
    pub parts_length_m: f64,
    /// Total lamella length, m.
    pub lamella_length_m: f64,
    /// Mass of every part, kg.
    pub mass_kg: f64,
    /// Stock sheets.
    pub sheets: u64,
    /// Cost of the stock, where priced.
    pub stock_cost: Option<f64>,
    /// Pieces of stock: sheets (or coil pieces) and bars.
    pub stock_pieces: u64,
    /// Pieces of bought hardware: bolts, nuts and plain washers.
    pub hardware_pieces: u64,
}

/// The takeoff of a kit and its nest.
pub fn takeoff(project: &str, kit: &Kit, nest: &Nest, profile: &Profile) -> Takeoff {
    let mut parts: Vec<PartLine> = Vec::new();
    for p in &kit.parts {
        let n = f64::from(p.count);
        let line = match parts.iter_mut().find(|l| l.kind == p.kind.as_str()) {
            Some(l) => l,
            None => {
                parts.push(PartLine {
                    kind: p.kind.as_str().into(),
                    material: profile.piece_material(p.kind.piece()),
                    thickness_mm: crate::fabricate::part_thickness_mm(p.kind, profile),
                    distinct: 0,
                    count: 0,
                    length_mm: 0.0,
                    area_m2: 0.0,
                    mass_kg: 0.0,
                });
                parts.last_mut().expect("just pushed")
            }
        };
        line.distinct += 1;
        line.count += u64::from(p.count);
        line.length_mm += p.length_mm * n;
        line.area_m2 += net_area_mm2(p) * n * 1e-6;
        line.mass_kg += part_mass_kg(p, profile) * n;
    }
    for l in &mut parts {
        l.length_mm = round(l.length_mm, 1);
        l.area_m2 = round(l.area_m2, 4);
        l.mass_kg = round(l.mass_kg, 3);
    }
    // Stock per group (one material and thickness each), by size in the
    // nest's order of first use; a coil's pieces are priced by the length
    // cut, so their unit price is given only when every piece costs the
    // same. Bars (studs) are the bar group's: listed here once.
    let mut stock: Vec<StockLine> = Vec::new();
    struct Size<'a> {
        label: &'a str,
        count: u64,
        part_area: f64,
        stock_area: f64,
        prices: Vec<Option<f64>>,
    }
    for g in &nest.groups {
        let mut sizes: Vec<Size> = Vec::new();
        for s in &nest.sheets[g.sheets.clone()] {
            let i = match sizes.iter().position(|z| z.label == s.stock) {
                Some(i) => i,
                None => {
                    sizes.push(Size {
                        label: &s.stock,
                        count: 0,
                        part_area: 0.0,
                        stock_area: 0.0,
                        prices: Vec::new(),
                    });
                    sizes.len() - 1
                }
            };
            let z = &mut sizes[i];
            z.count += 1;
            z.part_area += s.part_area_mm2;
            z.stock_area += s.length_mm * s.width_mm;
            z.prices.push(s.price_per_unit);
        }
        let t = fmt(g.thickness_mm);
        for Size {
            label,
            count,
            part_area,
            stock_area,
            prices,
        } in sizes
        {
            let cost = prices
                .iter()
                .copied()
                .collect::<Option<Vec<f64>>>()
                .map(|p| round(p.iter().sum(), 2));
            let unit_price = match prices.first() {
                Some(&Some(p)) if prices.iter().all(|q| *q == Some(p)) => Some(p),
                _ => None,
            };
            let item = match g.form {
                StockForm::Bar => format!("bar {label} mm"),
                StockForm::Sheet => format!("sheet {label} × {t} mm"),
                StockForm::Coil => format!("coil {label} × {t} mm"),
            };
            stock.push(StockLine {
                item,
                group: g.name.clone(),
                material: g.material.clone(),
                thickness_mm: round(g.thickness_mm, 4),
                count,
                utilization: Some(round(part_area / stock_area, 4)),
                unit_price,
                cost,
            });
        }
    }
    let hardware = hardware_lines(kit);
    let sheets = nest.sheets.len() as u64;
    let stock_cost = stock
        .iter()
        .filter_map(|s| s.cost)
        .reduce(|a, b| a + b)
        .map(|c| round(c, 2));
    Takeoff {
        project: project.into(),
        profile: profile.name.clone(),
        bracing: Vec::new(),
        currency: stock_cost.and(profile.stock.currency.clone()),
        totals: Totals {
            pieces: parts.iter().map(|l| l.count).sum(),
            parts_length_m: round(parts.iter().map(|l| l.length_mm).sum::<f64>() / 1000.0, 3),
            lamella_length_m: round(
                parts
                    .iter()
                    .filter(|l| l.kind == PartKind::Lamella.as_str())
                    .map(|l| l.length_mm)
                    .sum::<f64>()
                    / 1000.0,
                3,
            ),
            mass_kg: round(parts.iter().map(|l| l.mass_kg).sum(), 3),
            sheets,
            stock_cost,
            stock_pieces: stock.iter().map(|s| s.count).sum(),
            hardware_pieces: hardware.iter().map(|h| h.count).sum(),
        },
        parts,
        stock,
        hardware,
    }
}

/// A length without trailing zeros.
fn fmt(x: f64) -> String {
    let s = format!("{x:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}
