//! Tabular pages: the cover, the assembly order, the node and shear-block
//! schedules, parts / stock / hardware, the elastic check.
//!
//! A table is drawn in blocks side by side when it is narrow: as many
//! blocks as fit across the page (8 mm apart), [`ROW_MM`] rows, a header
//! row of [`HEADER_MM`]; rows run down the first block, then the next.

use super::canvas::{self, Align, Canvas, Rgb3, BLACK, BLUE, GREY, LIGHT, RED};
use super::{fixed, mm0, AssemblyInput, Frame, Page};
use crate::plan::takeoff::Takeoff;
use crate::plan::{Plan, PlanHoleUse, PlanPart};
use std::collections::HashMap;

/// Height of a table row, mm.
pub const ROW_MM: f64 = 4.5;
/// Height of a table's header row, mm.
pub const HEADER_MM: f64 = 6.0;
/// Gap between table blocks, mm.
pub const BLOCK_GAP_MM: f64 = 8.0;
/// Text size in tables, pt.
const TEXT_PT: f64 = 7.5;

/// A column: header, width (mm), alignment.
pub type Column = (&'static str, f64, Align);

/// One row: its cells and an optional text colour.
pub type Row = (Vec<String>, Option<Rgb3>);

/// Blocks across and rows per block of a table of `columns` in `frame`
/// with `height_mm` of it available.
pub fn table_capacity(columns: &[Column], frame: &Frame, height_mm: f64) -> (usize, usize) {
    let w: f64 = columns.iter().map(|c| c.1).sum();
    let blocks = (((frame.width_mm() + BLOCK_GAP_MM) / (w + BLOCK_GAP_MM)).floor() as usize).max(1);
    let rows = (((height_mm - HEADER_MM) / ROW_MM).floor() as usize).max(1);
    (blocks, rows)
}

/// Draw rows `rows` as a table whose top left is (x, top), one block.
pub fn draw_block(c: &mut Canvas, columns: &[Column], x: f64, top: f64, rows: &[Row]) {
    let w: f64 = columns.iter().map(|c| c.1).sum();
    c.fill(LIGHT);
    c.rect(x, top - HEADER_MM, w, HEADER_MM, true, false);
    c.fill(BLACK);
    let mut cx = x;
    for col in columns {
        cell(c, col, cx, top - HEADER_MM + 1.8, col.0, true);
        cx += col.1;
    }
    // Zebra rows for reading across.
    c.fill([0.94, 0.94, 0.94]);
    for (i, _) in rows.iter().enumerate().filter(|(i, _)| i % 2 == 1) {
        let y = top - HEADER_MM - (i as f64 + 1.0) * ROW_MM;
        c.rect(x, y, w, ROW_MM, true, false);
    }
    for (i, (cells, colour)) in rows.iter().enumerate() {
        let y = top - HEADER_MM - (i as f64 + 1.0) * ROW_MM + 1.3;
        c.fill(colour.unwrap_or(BLACK));
        let mut cx = x;
        for (col, s) in columns.iter().zip(cells) {
            cell(c, col, cx, y, s, false);
            cx += col.1;
        }
    }
    c.stroke(GREY);
    c.width(0.15);
    let bottom = top - HEADER_MM - rows.len() as f64 * ROW_MM;
    c.line([x, top], [x + w, top]);
    c.line([x, top - HEADER_MM], [x + w, top - HEADER_MM]);
    c.line([x, bottom], [x + w, bottom]);
}

fn cell(c: &mut Canvas, col: &Column, x: f64, y: f64, s: &str, bold: bool) {
    let pad = 1.2;
    let at = match col.2 {
        Align::Left => x + pad,
        Align::Center => x + 0.5 * col.1,
        Align::Right => x + col.1 - pad,
    };
    c.text([at, y], TEXT_PT, bold, col.2, 0.0, s);
}

/// A table over as many pages as it needs (at least one).
pub fn table_pages(
    frame: &Frame,
    section: &'static str,
    heading: &str,
    columns: &[Column],
    rows: &[Row],
) -> Vec<Page> {
    let (blocks, per_block) = table_capacity(columns, frame, frame.height_mm());
    let per_page = blocks * per_block;
    let w: f64 = columns.iter().map(|c| c.1).sum();
    let n_pages = rows.len().div_ceil(per_page).max(1);
    (0..n_pages)
        .map(|p| {
            let mut page = Page::new(
                section,
                if n_pages > 1 {
                    format!("{heading} ({} of {n_pages})", p + 1)
                } else {
                    heading.to_string()
                },
                None,
            );
            let chunk = &rows[(p * per_page).min(rows.len())..((p + 1) * per_page).min(rows.len())];
            for (b, block) in chunk.chunks(per_block).enumerate() {
                let x = frame.x0_mm + b as f64 * (w + BLOCK_GAP_MM);
                draw_block(&mut page.canvas, columns, x, frame.y1_mm, block);
            }
            page
        })
        .collect()
}

/// The node schedule's columns for strips of `lamellas` lamellas (1 or
/// 2): the node, then for each of its two strips the strip id and, per
/// lamella, the piece holding the node and the node's station on it.
pub fn node_columns(lamellas: u32) -> Vec<Column> {
    let mut cols: Vec<Column> = vec![("node", 12.0, Align::Right)];
    for _ in 0..2 {
        cols.push(("strip", 14.0, Align::Left));
        for n in 1..=lamellas.clamp(1, 2) {
            cols.push((if n == 1 { "piece" } else { "piece 2" }, 18.0, Align::Left));
            cols.push(("at", 11.0, Align::Right));
        }
    }
    cols.push(("angle", 14.0, Align::Right));
    cols.push(("joint", 16.0, Align::Left));
    cols
}

/// Lamellas per strip of the plan's parts (1 without a profile).
fn lamellas_per_strip(plan: &Plan) -> u32 {
    plan.profile
        .as_ref()
        .map_or(1, |p| p.lamellas_per_strip)
        .clamp(1, 2)
}

/// Where each node sits on each piece: (node, strip, lamella) → (piece id,
/// station from the piece's start end, mm). Lamellas and edge strips.
pub fn node_stations(plan: &Plan) -> HashMap<(usize, &str, u32), (&str, f64)> {
    let mut at = HashMap::new();
    for p in plan.parts.iter().flatten() {
        let Some(strip) = p.strip.as_deref() else {
            continue;
        };
        for f in &p.features {
            if let (Some(n), Some(st)) = (f.node, f.station_mm) {
                at.entry((n, strip, p.lamella.unwrap_or(1)))
                    .or_insert((p.id.as_str(), st));
            }
        }
    }
    at
}

/// The node schedule: every node of the plan, in id order, located on
/// the pieces: for each strip the piece that holds the node and the
/// station there, from the piece's cut start end.
pub fn node_pages(plan: &Plan, frame: &Frame) -> Vec<Page> {
    let lamellas = lamellas_per_strip(plan);
    let at = node_stations(plan);
    let rows: Vec<Row> = plan
        .nodes
        .iter()
        .map(|n| {
            let mut cells = vec![n.id.to_string()];
            for strip in [&n.a, &n.b] {
                cells.push(strip.clone());
                for l in 1..=lamellas {
                    // An edge strip's pieces are lamella 1's column.
                    match at.get(&(n.id, strip.as_str(), l)) {
                        Some((piece, st)) => {
                            cells.push((*piece).to_string());
                            cells.push(mm0(*st));
                        }
                        None => {
                            cells.push("-".into());
                            cells.push(String::new());
                        }
                    }
                }
            }
            cells.push(format!("{}°", fixed(n.angle_deg, 1)));
            cells.push(n.joint.clone());
            (cells, None)
        })
        .collect();
    table_pages(
        frame,
        "Node schedule",
        &format!(
            "Node schedule: {} nodes; the piece that holds each and its station, mm from the piece's cut start end (where its engraved arrow starts)",
            plan.nodes.len()
        ),
        &node_columns(lamellas),
        &rows,
    )
}

/// The setting-out table's columns.
pub const SETTING_OUT_COLUMNS: [Column; 9] = [
    ("node", 12.0, Align::Right),
    ("strip", 14.0, Align::Left),
    ("strip", 14.0, Align::Left),
    ("x mm", 20.0, Align::Right),
    ("y mm", 20.0, Align::Right),
    ("z mm", 20.0, Align::Right),
    ("normal x", 15.0, Align::Right),
    ("normal y", 15.0, Align::Right),
    ("normal z", 15.0, Align::Right),
];

/// The setting-out table: every node's position (mm, one decimal) and
/// unit surface normal (3 decimals) in the network's frame, in id order;
/// `setting-out.csv` holds the same at plan.json's precision.
pub fn setting_out_pages(plan: &Plan, frame: &Frame) -> Vec<Page> {
    let rows: Vec<Row> = plan
        .nodes
        .iter()
        .map(|n| {
            let mut cells = vec![n.id.to_string(), n.a.clone(), n.b.clone()];
            cells.extend(n.position_mm.iter().map(|v| fixed(*v, 1)));
            cells.extend(n.normal.iter().map(|v| fixed(*v, 3)));
            (cells, None)
        })
        .collect();
    table_pages(
        frame,
        "Setting out",
        &format!(
            "Setting out: {} nodes in the network's frame (position mm, unit surface normal); setting-out.csv",
            plan.nodes.len()
        ),
        &SETTING_OUT_COLUMNS,
        &rows,
    )
}

/// The shear-block schedule's columns.
pub const BLOCK_COLUMNS: [Column; 6] = [
    ("strip", 14.0, Align::Left),
    ("block", 12.0, Align::Right),
    ("lam. 1 piece", 20.0, Align::Left),
    ("at", 11.0, Align::Right),
    ("lam. 2 piece", 20.0, Align::Left),
    ("at", 11.0, Align::Right),
];

/// A strip's shear-block holes on lamella `n`, in order along its line:
/// the piece and the station from the piece's start end.
fn block_stations<'a>(parts: &[&'a PlanPart], n: u32) -> Vec<(f64, &'a str, f64)> {
    let mut v: Vec<(f64, &str, f64)> = parts
        .iter()
        .filter(|p| p.lamella == Some(n))
        .flat_map(|p| {
            p.features
                .iter()
                .filter(|f| f.hole_use == Some(PlanHoleUse::ShearBlock))
                .filter_map(|f| {
                    let st = f.station_mm?;
                    Some((f.line_station_mm.unwrap_or(st), p.id.as_str(), st))
                })
        })
        .collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v
}

/// The shear-block schedule: every block by strip, its bolt on the two
/// lamellas: the piece and the station from the piece's cut start end.
/// No pages when the kit has no shear blocks.
pub fn block_pages(plan: &Plan, frame: &Frame) -> Vec<Page> {
    let Some(parts) = &plan.parts else {
        return Vec::new();
    };
    let mut rows: Vec<Row> = Vec::new();
    let mut by_strip: HashMap<&str, Vec<&PlanPart>> = Default::default();
    for p in parts.iter().filter(|p| p.kind == "lamella") {
        if let Some(s) = &p.strip {
            by_strip.entry(s.as_str()).or_default().push(p);
        }
    }
    for s in &plan.strips {
        let Some(ps) = by_strip.get(s.id.as_str()) else {
            continue;
        };
        let (one, two) = (block_stations(ps, 1), block_stations(ps, 2));
        for (i, (_, piece, st)) in one.iter().enumerate() {
            let (p2, s2) = two
                .get(i)
                .map(|(_, p, x)| ((*p).to_string(), mm0(*x)))
                .unwrap_or_default();
            rows.push((
                vec![
                    s.id.clone(),
                    (i + 1).to_string(),
                    (*piece).to_string(),
                    mm0(*st),
                    p2,
                    s2,
                ],
                None,
            ));
        }
    }
    if rows.is_empty() {
        return Vec::new();
    }
    table_pages(
        frame,
        "Shear blocks",
        &format!(
            "Shear blocks: {} blocks (part SB); each bolt's piece and station, mm from the piece's cut start end",
            rows.len()
        ),
        &BLOCK_COLUMNS,
        &rows,
    )
}

/// The assembly order's columns.
pub const ORDER_COLUMNS: [Column; 6] = [
    ("step", 10.0, Align::Right),
    ("strip", 16.0, Align::Left),
    ("family", 12.0, Align::Left),
    ("what", 40.0, Align::Left),
    ("nodes", 12.0, Align::Right),
    ("length", 18.0, Align::Right),
];

/// The assembly order: interlocking grids lay family A (slots up) first,
/// in strip order, then slot family B in from above; two-level grids lay
/// the lower level (A), set the studs, then the upper level (B); edge
/// strips last.
pub fn order_pages(plan: &Plan, frame: &Frame) -> Vec<Page> {
    let two_level = plan
        .profile
        .as_ref()
        .is_some_and(|p| p.joint_system == "two_level");
    let mut rows: Vec<Row> = Vec::new();
    let push = |rows: &mut Vec<Row>, s: &crate::plan::PlanStrip, what: &str| {
        let step = rows.len() + 1;
        rows.push((
            vec![
                step.to_string(),
                s.id.clone(),
                s.family.clone(),
                what.to_string(),
                s.nodes.len().to_string(),
                mm0(s.length_mm),
            ],
            None,
        ));
    };
    let (a_what, b_what) = if two_level {
        ("lower level", "upper level, on the studs")
    } else {
        ("lay flat, slots up", "slot in from above, slots down")
    };
    for s in plan.strips.iter().filter(|s| s.family == "A") {
        push(&mut rows, s, a_what);
    }
    if two_level {
        let family: std::collections::HashMap<&str, &str> = plan
            .strips
            .iter()
            .map(|s| (s.id.as_str(), s.family.as_str()))
            .collect();
        let nodes = plan
            .nodes
            .iter()
            .filter(|n| {
                family.get(n.a.as_str()) == Some(&"A") && family.get(n.b.as_str()) == Some(&"B")
            })
            .count();
        let step = rows.len() + 1;
        rows.push((
            vec![
                step.to_string(),
                "ST".into(),
                String::new(),
                format!("a stud on every A x B node ({nodes})"),
                String::new(),
                String::new(),
            ],
            Some(BLUE),
        ));
    }
    for s in plan.strips.iter().filter(|s| s.family == "B") {
        push(&mut rows, s, b_what);
    }
    for s in plan.strips.iter().filter(|s| s.family == "edge") {
        push(&mut rows, s, &edge_what(plan, &s.id));
    }
    let heading = if two_level {
        "Assembly order: lower level (family A), studs, upper level (family B), edges"
    } else {
        "Assembly order: family A down first (slots up), then family B slotted in, edges last"
    };
    table_pages(frame, "Assembly order", heading, &ORDER_COLUMNS, &rows)
}

/// What the crew does with an edge strip: slide it into the lamellas' end
/// slots, bolt it at its nodes where its band has the edge bolts' holes,
/// and join its pieces with their splice plates.
fn edge_what(plan: &Plan, edge: &str) -> String {
    fn mine<'a>(
        plan: &'a Plan,
        edge: &'a str,
        kind: &'a str,
    ) -> impl Iterator<Item = &'a crate::plan::PlanPart> {
        plan.parts
            .iter()
            .flatten()
            .filter(move |p| p.kind == kind && p.strip.as_deref() == Some(edge))
    }
    let bolted = mine(plan, edge, "edge_strip")
        .flat_map(|p| &p.features)
        .any(|f| f.hole_use == Some(crate::plan::PlanHoleUse::EdgeNode));
    let plates = mine(plan, edge, "splice_plate").count();
    let mut what = String::from("end slots");
    if bolted {
        what.push_str(", bolts");
    }
    match plates {
        0 => {}
        1 => what.push_str(", 1 splice"),
        n => what.push_str(&format!(", {n} splices")),
    }
    what
}

/// The elastic check's columns.
pub const CHECK_COLUMNS: [Column; 12] = [
    ("rank", 10.0, Align::Right),
    ("strip", 14.0, Align::Left),
    ("lam.", 9.0, Align::Right),
    ("util.", 13.0, Align::Right),
    ("governs", 16.0, Align::Left),
    ("station", 15.0, Align::Right),
    ("sb MPa", 15.0, Align::Right),
    ("tau MPa", 15.0, Align::Right),
    ("sw MPa", 15.0, Align::Right),
    ("sv MPa", 15.0, Align::Right),
    ("R min", 16.0, Align::Right),
    ("twist °/m", 16.0, Align::Right),
];

/// A and B strips by utilisation, the governing ones first (ties by id).
pub fn check_pages(plan: &Plan, frame: &Frame) -> Vec<Page> {
    let mut strips: Vec<_> = plan
        .strips
        .iter()
        .filter_map(|s| s.check.as_ref().map(|c| (s, c)))
        .collect();
    strips.sort_by(|a, b| {
        b.1.stress
            .utilization
            .total_cmp(&a.1.stress.utilization)
            .then_with(|| a.0.id.cmp(&b.0.id))
    });
    let rows: Vec<Row> = strips
        .iter()
        .enumerate()
        .map(|(i, (s, c))| {
            let u = c.stress.utilization;
            let colour = if u > 1.0 {
                Some(RED)
            } else if u >= 0.9 {
                Some([0.75, 0.4, 0.0])
            } else {
                None
            };
            (
                vec![
                    (i + 1).to_string(),
                    s.id.clone(),
                    c.lamella.to_string(),
                    fixed(u, 3),
                    c.stress.governs.clone(),
                    mm0(c.stress.governing_station_mm),
                    fixed(c.stress.bending_stress_mpa, 1),
                    fixed(c.stress.torsion_shear_mpa, 1),
                    fixed(c.stress.trapeze_stress_mpa, 1),
                    fixed(c.stress.combined_stress_mpa, 1),
                    s.min_bending_radius_mm
                        .map(mm0)
                        .unwrap_or_else(|| "-".into()),
                    fixed(s.max_twist_deg_per_m, 1),
                ],
                colour,
            )
        })
        .collect();
    let verdict = match &plan.check {
        Some(c) if c.passes => format!("PASS, highest utilisation {}", fixed(c.max_utilization, 3)),
        Some(c) => format!(
            "FAIL: {} strips over 1, highest {}",
            c.strips_overstressed,
            fixed(c.max_utilization, 3)
        ),
        None => "not checked".into(),
    };
    table_pages(
        frame,
        "Elastic check",
        &format!("Elastic check, governing strips first: {verdict}"),
        &CHECK_COLUMNS,
        &rows,
    )
}

/// Parts, stock, hardware and totals on one page.
pub fn takeoff_page(t: &Takeoff, frame: &Frame) -> Page {
    let mut page = Page::new(
        "Parts, stock and hardware",
        "Parts, stock and hardware (takeoff.csv)",
        None,
    );
    let c = &mut page.canvas;
    let mut top = frame.y1_mm;
    let parts_cols: [Column; 7] = [
        ("part kind", 30.0, Align::Left),
        ("material", 40.0, Align::Left),
        ("t mm", 14.0, Align::Right),
        ("distinct", 16.0, Align::Right),
        ("pieces", 18.0, Align::Right),
        ("length m", 20.0, Align::Right),
        ("mass kg", 20.0, Align::Right),
    ];
    let rows: Vec<Row> = t
        .parts
        .iter()
        .map(|l| {
            (
                vec![
                    l.kind.replace('_', " "),
                    l.material.clone(),
                    fixed(l.thickness_mm, 1),
                    l.distinct.to_string(),
                    l.count.to_string(),
                    fixed(l.length_mm / 1000.0, 1),
                    fixed(l.mass_kg, 1),
                ],
                None,
            )
        })
        .collect();
    top = small_table(c, frame, top, "Parts", &parts_cols, &rows);
    let stock_cols: [Column; 5] = [
        ("stock", 70.0, Align::Left),
        ("count", 16.0, Align::Right),
        ("utilisation", 22.0, Align::Right),
        ("unit price", 22.0, Align::Right),
        ("cost", 22.0, Align::Right),
    ];
    let money = |x: Option<f64>| x.map(|v| fixed(v, 2)).unwrap_or_else(|| "-".into());
    let rows: Vec<Row> = t
        .stock
        .iter()
        .map(|l| {
            (
                vec![
                    l.item.clone(),
                    l.count.to_string(),
                    l.utilization
                        .map(|u| format!("{} %", fixed(100.0 * u, 1)))
                        .unwrap_or_else(|| "-".into()),
                    money(l.unit_price),
                    money(l.cost),
                ],
                None,
            )
        })
        .collect();
    top = small_table(c, frame, top, "Stock", &stock_cols, &rows);
    let hw_cols: [Column; 5] = [
        ("hardware (bought)", 40.0, Align::Left),
        ("designation", 60.0, Align::Left),
        ("grip mm", 18.0, Align::Right),
        ("count", 18.0, Align::Right),
        ("torque N·m", 24.0, Align::Right),
    ];
    let rows: Vec<Row> = t
        .hardware
        .iter()
        .map(|h| {
            (
                vec![
                    h.item.clone(),
                    h.designation.clone(),
                    h.grip_mm.map(|g| fixed(g, 1)).unwrap_or_default(),
                    h.count.to_string(),
                    h.torque_nm.map(|m| fixed(m, 1)).unwrap_or_default(),
                ],
                None,
            )
        })
        .collect();
    top = small_table(c, frame, top, "Hardware", &hw_cols, &rows);
    let tt = &t.totals;
    let cur = t.currency.clone().unwrap_or_default();
    let lines = [
        format!("pieces to cut or saw (made): {}", tt.pieces),
        format!("hardware to buy: {} pieces", tt.hardware_pieces),
        format!("lamella length: {} m", fixed(tt.lamella_length_m, 1)),
        format!("mass: {} kg", fixed(tt.mass_kg, 1)),
        format!("stock sheets: {}", tt.sheets),
        format!(
            "stock cost: {}",
            tt.stock_cost
                .map(|v| format!("{} {cur}", fixed(v, 2)))
                .unwrap_or_else(|| "not priced".into())
        ),
    ];
    c.fill(BLACK);
    c.text(
        [frame.x0_mm, top - 4.0],
        9.0,
        true,
        Align::Left,
        0.0,
        "Totals",
    );
    for (i, l) in lines.iter().enumerate() {
        c.text(
            [frame.x0_mm, top - 9.0 - 4.5 * i as f64],
            8.0,
            false,
            Align::Left,
            0.0,
            l,
        );
    }
    page
}

/// A titled table from `top`, all rows in one block; returns the y below it.
fn small_table(
    c: &mut Canvas,
    frame: &Frame,
    top: f64,
    title: &str,
    cols: &[Column],
    rows: &[Row],
) -> f64 {
    c.fill(BLACK);
    c.text([frame.x0_mm, top - 4.0], 9.0, true, Align::Left, 0.0, title);
    draw_block(c, cols, frame.x0_mm, top - 6.0, rows);
    top - 6.0 - HEADER_MM - rows.len() as f64 * ROW_MM - 5.0
}

/// The cover: what the kit is, the verdict, the totals, the legend of the
/// engraved marks and the contents (`first`: section, first page, pages).
pub fn cover_page(input: &AssemblyInput, frame: &Frame, first: &[(&str, usize, usize)]) -> Page {
    let plan = input.plan;
    // A plan with sheets has its takeoff ([`super::sections`] refuses one without).
    let none = Takeoff::default();
    let t = input.plan.takeoff.as_ref().unwrap_or(&none);
    let mut page = Page::new("Cover", "Assembly sheets", None);
    let c = &mut page.canvas;
    let x0 = frame.x0_mm;
    let top = frame.y1_mm;
    c.fill(BLACK);
    c.text(
        [x0, top - 12.0],
        24.0,
        true,
        Align::Left,
        0.0,
        &plan.network.name,
    );
    let count = |f: &str| plan.strips.iter().filter(|s| s.family == f).count();
    let mut facts: Vec<(String, String)> = vec![
        (
            "network".into(),
            format!(
                "{} ({}, tolerance {} mm)",
                plan.network.source, plan.network.file_units, plan.network.tolerance_mm
            ),
        ),
        (
            "strips".into(),
            format!("{} A, {} B, {} edge", count("A"), count("B"), count("edge")),
        ),
        ("nodes".into(), plan.nodes.len().to_string()),
    ];
    if let Some(p) = &plan.profile {
        facts.push(("profile".into(), format!("{} ({})", p.name, p.source)));
        facts.push((
            "section".into(),
            format!(
                "{}: {} lamella{} {} × {} mm{}, {} joints",
                p.material,
                p.lamellas_per_strip,
                if p.lamellas_per_strip == 1 { "" } else { "s" },
                p.thickness_mm,
                p.height_mm,
                if p.lamellas_per_strip == 2 {
                    format!(", gap {} mm", p.gap_mm)
                } else {
                    String::new()
                },
                p.joint_system.replace('_', "-")
            ),
        ));
    }
    if let Some(k) = &plan.parts_summary {
        let kinds: Vec<String> = k
            .kinds
            .iter()
            .map(|kc| format!("{} {}", kc.count, kc.kind.replace('_', " ")))
            .collect();
        facts.push(("parts".into(), kinds.join(", ")));
    }
    let (verdict, colour) = match &plan.check {
        Some(ch) if ch.passes => (
            format!(
                "PASS: every lamella within its strength, highest utilisation {}",
                fixed(ch.max_utilization, 3)
            ),
            BLACK,
        ),
        Some(ch) => (
            format!(
                "FAIL: {} strips overstressed, highest utilisation {}",
                ch.strips_overstressed,
                fixed(ch.max_utilization, 3)
            ),
            RED,
        ),
        None => ("not checked".into(), RED),
    };
    let tt = &t.totals;
    facts.push((
        "takeoff".into(),
        format!(
            "{} pieces, {} m of lamella, {} kg, {} stock sheets{}",
            tt.pieces,
            fixed(tt.lamella_length_m, 1),
            fixed(tt.mass_kg, 1),
            tt.sheets,
            tt.stock_cost
                .map(|v| format!(
                    ", {} {}",
                    fixed(v, 2),
                    t.currency.clone().unwrap_or_default()
                ))
                .unwrap_or_default()
        ),
    ));
    let mut y = top - 24.0;
    for (k, v) in &facts {
        c.fill(GREY);
        c.text([x0, y], 10.0, false, Align::Left, 0.0, k);
        c.fill(BLACK);
        c.text([x0 + 28.0, y], 10.0, false, Align::Left, 0.0, v);
        y -= 6.5;
    }
    c.fill(GREY);
    c.text([x0, y], 10.0, false, Align::Left, 0.0, "elastic check");
    c.fill(colour);
    c.text([x0 + 28.0, y], 10.0, true, Align::Left, 0.0, &verdict);
    y -= 12.0;
    // Contents.
    c.fill(BLACK);
    c.text([x0, y], 11.0, true, Align::Left, 0.0, "Contents");
    y -= 6.0;
    for (name, p, n) in first {
        c.text([x0, y], 9.0, false, Align::Left, 0.0, name);
        let pages = if *n == 1 {
            format!("page {p}")
        } else {
            format!("pages {p}-{}", p + n - 1)
        };
        c.text([x0 + 70.0, y], 9.0, false, Align::Right, 0.0, &pages);
        y -= 4.8;
    }
    legend(c, frame, plan);
    page
}

/// The legend of the engraved marks, drawn on a sample lamella of the
/// kit's joint system (an interlocking lamella with a slot, a two-level
/// one with its stud holes), naming only the parts the kit has.
fn legend(c: &mut Canvas, frame: &Frame, plan: &Plan) {
    let two_level = plan
        .profile
        .as_ref()
        .is_some_and(|p| p.joint_system == "two_level");
    let has = |kind: &str| {
        plan.parts_summary
            .as_ref()
            .is_some_and(|k| k.kinds.iter().any(|kc| kc.kind == kind && kc.count > 0))
    };
    let w = 150.0_f64.min(0.45 * frame.width_mm());
    let x = frame.x1_mm - w;
    let mut y = frame.y1_mm - 24.0;
    c.fill(BLACK);
    c.text(
        [x, y],
        11.0,
        true,
        Align::Left,
        0.0,
        "Engraved marks (blue on the parts)",
    );
    y -= 26.0;
    // A sample lamella 0.9 w long, 16 mm high, one slot from the top.
    let (lx, lw, lh) = (x + 2.0, 0.9 * w, 16.0);
    let slot_x = lx + 0.55 * lw;
    let (sw, sd) = (4.0, 8.0);
    let outline = [
        [lx, y],
        [lx + lw, y],
        [lx + lw, y + lh],
        [slot_x + 0.5 * sw, y + lh],
        [slot_x + 0.5 * sw, y + lh - sd],
        [slot_x - 0.5 * sw, y + lh - sd],
        [slot_x - 0.5 * sw, y + lh],
        [lx, y + lh],
    ];
    c.stroke(BLACK);
    c.width(0.3);
    if two_level {
        // No slots: a node's stud fastener hole.
        c.rect(lx, y, lw, lh, false, true);
        c.circle([slot_x, y + 0.5 * lh], 1.2, false);
    } else {
        c.polyline(&outline, true);
    }
    c.circle([lx + 0.85 * lw, y + 0.5 * lh], 1.2, false);
    c.fill(BLUE);
    c.stroke(BLUE);
    c.text(
        [lx + 4.0, y + 4.0],
        10.0,
        false,
        Align::Left,
        0.0,
        "A05-1.2",
    );
    c.text(
        [slot_x, y + if two_level { 9.5 } else { 2.5 }],
        8.0,
        false,
        Align::Center,
        0.0,
        "B12",
    );
    c.text(
        [lx + 0.85 * lw, y + 2.5],
        8.0,
        false,
        Align::Center,
        0.0,
        "B13",
    );
    // The orientation arrow with its tick toward the top edge.
    let (ax, ay) = (lx + 30.0, y + 6.0);
    c.width(0.3);
    c.line([ax, ay], [ax + 14.0, ay]);
    c.polyline(
        &[
            [ax + 11.0, ay + 1.5],
            [ax + 14.0, ay],
            [ax + 11.0, ay - 1.5],
        ],
        false,
    );
    c.line([ax, ay], [ax, ay + 3.0]);
    c.fill(BLACK);
    let mut notes: Vec<&str> = vec![
        "A05-1.2   part id: strip A05, lamella 1 (of 2), piece 2 (pieces are spliced)",
        if two_level {
            "B12       beside a node hole: the strip crossing there"
        } else {
            "B12       beside a slot or node hole: the strip crossing there"
        },
        "arrow     from the piece's cut start end (x = 0: every station is measured from it);",
        "          its tick points to the top edge",
        if two_level {
            "          (the surface normal side)"
        } else {
            "          (the surface normal side: family A's slots open there, B's opposite)"
        },
    ];
    if has("shear_block") {
        notes.push("SB        shear block between the two lamellas of a strip (bolted)");
    }
    if has("splice_plate") {
        notes.push("SP        splice plate joining two pieces of a lamella");
    }
    if has("washer") {
        notes.push("W87.5     star washer for nodes whose crossing angle rounds to 87.5°");
    }
    if has("stud") {
        notes.push("ST        stud joining the two levels of a two-level grid");
    }
    if has("edge_strip") {
        notes.push("E-edge00.1   edge strip edge00, piece 1");
        notes.push("SP-edge00.1  splice plate joining pieces 1 and 2 of edge strip edge00");
    }
    let mut ty = y - 7.0;
    for n in notes {
        let (k, v) = n.split_at(n.find(' ').unwrap_or(0));
        c.text([x, ty], 8.0, true, Align::Left, 0.0, k);
        c.text([x + 22.0, ty], 8.0, false, Align::Left, 0.0, v.trim_start());
        ty -= 4.6;
    }
    let _ = canvas::cap_mm;
}
