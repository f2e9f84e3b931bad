//! The takeoff as JSON for tools and as CSV for spreadsheets (one header
//! row, units in the column names, one `section` column, a `source`
//! column: `made` for parts cut from stock, `bought` for stock and
//! hardware).

use crate::plan::round;
use crate::plan::takeoff::Takeoff;
use serde::Serialize;

/// The takeoff as pretty JSON.
pub fn to_json(t: &Takeoff) -> String {
    let mut s = serde_json::to_string_pretty(t).unwrap_or_default();
    s.push('\n');
    s
}

/// One CSV row; every section fills the columns that apply.
#[derive(Serialize, Default)]
struct Row<'a> {
    section: &'a str,
    item: &'a str,
    designation: &'a str,
    material: &'a str,
    thickness_mm: Option<f64>,
    distinct: Option<usize>,
    count: Option<u64>,
    length_mm: Option<f64>,
    area_m2: Option<f64>,
    mass_kg: Option<f64>,
    grip_mm: Option<f64>,
    utilization: Option<f64>,
    unit_price: Option<f64>,
    cost: Option<f64>,
    currency: &'a str,
    source: &'a str,
    torque_nm: Option<f64>,
}

/// The takeoff as CSV: one header row, then parts, stock, hardware, the
/// bracing (when braced) and a
/// total row per section (made parts: pieces, length, area, mass; bought
/// hardware: pieces; stock: pieces and cost).
pub fn to_csv(t: &Takeoff) -> std::result::Result<Vec<u8>, String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let cur = t.currency.as_deref().unwrap_or("");
    let mut rows: Vec<Row> = Vec::new();
    for p in &t.parts {
        rows.push(Row {
            section: "part",
            item: &p.kind,
            material: &p.material,
            thickness_mm: Some(p.thickness_mm),
            distinct: Some(p.distinct),
            count: Some(p.count),
            length_mm: Some(p.length_mm),
            area_m2: Some(p.area_m2),
            mass_kg: Some(p.mass_kg),
            source: "made",
            ..Default::default()
        });
    }
    for s in &t.stock {
        rows.push(Row {
            section: "stock",
            item: &s.item,
            material: &s.material,
            thickness_mm: Some(s.thickness_mm),
            count: Some(s.count),
            utilization: s.utilization,
            unit_price: s.unit_price,
            cost: s.cost,
            currency: if s.cost.is_some() { cur } else { "" },
            source: "bought",
            ..Default::default()
        });
    }
    for h in &t.hardware {
        rows.push(Row {
            section: "hardware",
            item: &h.item,
            designation: &h.designation,
            count: Some(h.count),
            grip_mm: h.grip_mm,
            source: "bought",
            torque_nm: h.torque_nm,
            ..Default::default()
        });
    }
    for b in &t.bracing {
        rows.push(Row {
            section: "bracing",
            item: &b.item,
            designation: &b.designation,
            count: Some(b.count),
            length_mm: b.length_mm,
            source: &b.source,
            ..Default::default()
        });
    }
    let tt = &t.totals;
    rows.push(Row {
        section: "total",
        item: "made parts",
        count: Some(tt.pieces),
        length_mm: Some(round(tt.parts_length_m * 1000.0, 1)),
        area_m2: Some(round(t.parts.iter().map(|p| p.area_m2).sum(), 4)),
        mass_kg: Some(tt.mass_kg),
        source: "made",
        ..Default::default()
    });
    rows.push(Row {
        section: "total",
        item: "bought hardware",
        count: Some(tt.hardware_pieces),
        source: "bought",
        ..Default::default()
    });
    rows.push(Row {
        section: "total",
        item: "stock",
        count: Some(tt.stock_pieces),
        cost: tt.stock_cost,
        currency: if tt.stock_cost.is_some() { cur } else { "" },
        source: "bought",
        ..Default::default()
    });
    for r in rows {
        w.serialize(r).map_err(|e| e.to_string())?;
    }
    w.into_inner().map_err(|e| e.to_string())
}

/// One row of `parts/parts.csv`.
#[derive(Serialize)]
struct PartRow<'a> {
    part: &'a str,
    kind: &'a str,
    material: &'a str,
    thickness_mm: Option<f64>,
    quantity: u32,
    length_mm: f64,
    width_mm: f64,
    area_mm2: f64,
    file: String,
}

/// `parts/parts.csv`: one row per distinct part of `parts` (plan.json's
/// order): id, kind, material and thickness (the takeoff's line of its
/// kind, where there is one), quantity, size (the part frame's extent),
/// net area (outline less inner contours and round holes, mm², 2
/// decimals) and its DXF in `parts/` (`file_stem` gives the stem).
pub fn parts_csv(
    parts: &[crate::plan::PlanPart],
    t: &Takeoff,
    file_stem: impl Fn(&str) -> String,
) -> std::result::Result<Vec<u8>, String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let shoelace = |p: &[[f64; 2]]| {
        let n = p.len();
        0.5 * (0..n)
            .map(|i| p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1])
            .sum::<f64>()
    };
    for p in parts {
        let kind = p.kind.as_ref();
        let line = t.parts.iter().find(|l| l.kind == kind);
        let round_holes: f64 = p
            .features
            .iter()
            .filter(|f| f.kind == crate::plan::PlanFeatureKind::Hole)
            .map(|f| std::f64::consts::PI * (0.5 * f.width_mm).powi(2))
            .sum();
        let inner: f64 = p.holes.iter().map(|h| shoelace(h).abs()).sum();
        let area = shoelace(&p.outline).abs() - inner - round_holes;
        w.serialize(PartRow {
            part: &p.id,
            kind,
            material: line.map(|l| l.material.as_str()).unwrap_or(""),
            thickness_mm: line.map(|l| l.thickness_mm),
            quantity: p.count,
            length_mm: p.length_mm,
            width_mm: p.height_mm,
            area_mm2: round(area, 2),
            file: format!("{}.dxf", file_stem(&p.id)),
        })
        .map_err(|e| e.to_string())?;
    }
    w.into_inner().map_err(|e| e.to_string())
}
