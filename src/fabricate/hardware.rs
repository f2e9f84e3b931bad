//! What the workshop buys rather than cuts: every bolt with its nut and
//! plain washers, counted from the kit (docs/fabrication.md, "Joints"),
//! each bolt's length chosen from the standard series for its clamped
//! stack ([`super::fasteners`]: ISO 4017 bolts, ISO 4032 nuts, ISO 7089
//! washers, the tables and their sources). Star washers and studs are cut
//! by lamella: they are parts, not hardware.
//!
//! The grips follow the joint stacks:
//!
//! * node bolt (along the surface normal, through the gap square between
//!   the four lamellas): lamella height h + the star washers on it,
//!   `per_node` × washer thickness. The star washers are the washers under
//!   head and nut: no plain washer (a node bolt without star washers gets
//!   one under its head and one under its nut).
//! * shear-block bolt (across a doubled strip): lamella, block (as thick
//!   as the gap), lamella: 2t + gap;
//! * splice bolt (through a lamella and its plate): 2t;
//! * stud bolt (across one level's doubled strip and the stud, two per
//!   stud): 2t + gap.
//!
//! * edge bolt (along the surface normal through the gap of a doubled
//!   strip ending on a band, and the band's hole): the stack between the
//!   washers at that node ([`edge_grips_mm`]): the lamella height h (with
//!   the band where it lies beyond: two levels); where every lamella of
//!   the strip has its end slot opened into a rebate from one edge, the
//!   washer on that side bears on the band, which lies on the rebate's
//!   floor: floor + band thickness t (from the other edge). Edge bolts of
//!   one length are one line; those at rebates are `edge bolt at a rebate`.
//!
//! Every bolt but the node bolt bears on thin sheet or plywood through a
//! clearance hole, so it has a plain washer under its head and one under
//! its nut (EN 1995-1-1 asks for them under both in timber; on 1.5 mm steel
//! they spread the bearing around the oversized hole). Its length is the
//! shortest of the series ≥ grip + washers + nut + two pitches; a joint
//! that needs a longer bolt than its thread comes in is an error naming
//! the joint, as is a diameter that is no thread of the table.

use super::fasteners::{self, Thread};
use super::part::{Part, PartKind, SlotEdge};
use crate::error::{Error, Result};
use crate::profile::Profile;

/// The edge bolt's grip where nothing is cut away at its node, mm: along
/// the normal from the top to the bottom of the stack, the lamella's
/// height (lifted by the level offset in two levels) and the band through
/// its end slot, wherever it lies beyond.
pub fn full_edge_grip_mm(profile: &Profile) -> f64 {
    let (h, t) = (profile.section.height_mm, profile.section.thickness_mm);
    let (dz, half_t) = (profile.joint.level_offset_mm.abs(), 0.5 * t);
    (dz + 0.5 * h).max(half_t) - (dz - 0.5 * h).min(-half_t)
}

/// The edge bolts' grips at the bolted edge nodes `nodes` (node ids) where
/// it is less than [`full_edge_grip_mm`], mm, in node order: at a node
/// where every lamella of the strip ending there has its end slot opened
/// into a rebate from its top (bottom) edge, nothing of the lamellas is
/// left under the washer on that side, which bears on the band; the band
/// lies on the highest (lowest) rebate floor, so the stack ends a band
/// thickness past that floor. One lamella keeping its edge there holds
/// the washer at the full height.
pub fn edge_grips_mm(profile: &Profile, parts: &[Part], nodes: &[usize]) -> Vec<(usize, f64)> {
    let (h, t) = (profile.section.height_mm, profile.section.thickness_mm);
    let full = full_edge_grip_mm(profile);
    let eps = 1e-9;
    // Per node: the end slots' (y0, y1) across the lamellas.
    let mut slots: std::collections::BTreeMap<usize, Vec<(f64, f64)>> = Default::default();
    for p in parts.iter().filter(|p| p.kind == PartKind::Lamella) {
        for f in p.features.iter().filter(|f| f.edge == Some(SlotEdge::End)) {
            if let Some(node) = f.node {
                let (c, w) = (f.center_part_mm.y, 0.5 * f.width_mm);
                slots.entry(node).or_default().push((c - w, c + w));
            }
        }
    }
    nodes
        .iter()
        .filter_map(|id| {
            let s = slots.get(id)?;
            let top = if s.iter().all(|&(_, y1)| y1 >= h - eps) {
                s.iter()
                    .map(|&(y0, _)| y0)
                    .fold(f64::NEG_INFINITY, f64::max)
                    + t
            } else {
                h
            };
            let bottom = if s.iter().all(|&(y0, _)| y0 <= eps) {
                s.iter().map(|&(_, y1)| y1).fold(f64::INFINITY, f64::min) - t
            } else {
                0.0
            };
            let grip = top - bottom;
            (grip < full - eps).then_some((*id, grip))
        })
        .collect()
}

/// What a hardware line is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HardwareKind {
    /// A hexagon head bolt, ISO 4017.
    Bolt,
    /// A hexagon nut, ISO 4032.
    Nut,
    /// A plain washer, ISO 7089.
    Washer,
}

/// One line of bought hardware.
#[derive(Debug, Clone, PartialEq)]
pub struct Hardware {
    /// What it is: `node bolt`, `shear-block bolt`, `splice bolt`, `stud
    /// bolt` (one line per joint), `nut`, `plain washer` (one line per size).
    pub item: String,
    /// Bolt, nut or washer.
    pub kind: HardwareKind,
    /// As ordered: `M8 × 70 ISO 4017 8.8`, `M8 ISO 4032 8`, `M5 ISO 7089 200 HV`.
    pub designation: String,
    /// The standard: `ISO 4017`, `ISO 4032`, `ISO 7089`.
    pub standard: &'static str,
    /// Thread (nominal) diameter, mm.
    pub diameter_mm: f64,
    /// Bolts: nominal length, mm.
    pub length_mm: Option<f64>,
    /// Bolts: clamped thickness (the joint's parts, without plain washers), mm.
    pub grip_mm: Option<f64>,
    /// Bolts: the length the stack needs (grip + plain washers + nut + two
    /// pitches), mm.
    pub needed_mm: Option<f64>,
    /// How many.
    pub count: u64,
    /// Bolts: tightening torque, N·m, when the profile gives a property class.
    pub torque_nm: Option<f64>,
}

/// What the kit counts: grid nodes, shear blocks, splice plates and studs
/// (pieces).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Counts {
    /// A×B nodes of the grid.
    pub grid_nodes: u64,
    /// Shear blocks.
    pub shear_blocks: u64,
    /// Splice plates (one per lamella per splice).
    pub splice_plates: u64,
    /// Studs.
    pub studs: u64,
    /// Edge nodes with a bolt (a lamella strip ending on a bolted edge
    /// strip).
    pub edge_nodes: u64,
    /// The edge bolts' grips where a rebate leaves less than the full
    /// stack, mm, one per such node (of the `edge_nodes`, by node id;
    /// [`edge_grips_mm`]).
    pub edge_rebate_grips_mm: Vec<(usize, f64)>,
    /// Splice plates joining edge band pieces.
    pub band_splice_plates: u64,
    /// The bracing cables' eye plates stacked under bolts, one entry per
    /// joint that has any ([`super::eye_plate`]).
    pub eye_plates: Vec<EyePlateStack>,
}

/// Eye plates under one joint's bolt.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EyePlateStack {
    /// The node, by id.
    pub node: usize,
    /// How many plates (cables ending there).
    pub plates: u32,
    /// Whether the bolt is an edge bolt (else the node bolt of an A×B
    /// node).
    pub at_edge: bool,
}

/// One kind of bolted joint: its bolt, grip, plain washers and count.
struct Joint {
    item: &'static str,
    diameter_mm: f64,
    grip_mm: f64,
    plain_washers: u64,
    count: u64,
}

/// Bolts of one joint whose grips differ from node to node (`grips_mm`,
/// one per bolt): one line per bolt length, each at the largest grip it
/// takes (ascending); one line at the largest grip for a diameter that is
/// no thread of the table (refused with the joint named below).
fn by_length(
    item: &'static str,
    diameter_mm: f64,
    plain_washers: u64,
    mut grips_mm: Vec<f64>,
) -> Vec<Joint> {
    grips_mm.sort_by(f64::total_cmp);
    let Some(th) = fasteners::thread(diameter_mm) else {
        return grips_mm
            .last()
            .map(|&g| Joint {
                item,
                diameter_mm,
                grip_mm: g,
                plain_washers,
                count: grips_mm.len() as u64,
            })
            .into_iter()
            .collect();
    };
    let extra = plain_washers as f64 * th.washer_mm + th.nut_mm + 2.0 * th.pitch_mm;
    let mut lines: Vec<(Option<f64>, Joint)> = Vec::new();
    for g in grips_mm {
        let length = fasteners::bolt_length_mm(th, g + extra);
        match lines.last_mut() {
            Some((l, j)) if *l == length => {
                j.grip_mm = g;
                j.count += 1;
            }
            _ => lines.push((
                length,
                Joint {
                    item,
                    diameter_mm,
                    grip_mm: g,
                    plain_washers,
                    count: 1,
                },
            )),
        }
    }
    lines.into_iter().map(|(_, j)| j).collect()
}

/// The hardware list of a kit for `profile`: the bolts by joint (node,
/// shear block, splice, stud), then the nuts and the plain washers by
/// size, ascending; lines with a zero count are left out.
pub fn hardware(profile: &Profile, n: Counts) -> Result<Vec<Hardware>> {
    let (t, h, gap) = (
        profile.section.thickness_mm,
        profile.section.height_mm,
        profile.section.gap_mm,
    );
    // Every eye plate under a bolt adds its thickness to the grip.
    let eye_mm = profile
        .bracing
        .as_ref()
        .map_or(0.0, |b| b.eye_plate.thickness_mm);
    let mut joints = Vec::new();
    if let Some(b) = &profile.node_bolt {
        let (stars, plain) = match &profile.washer {
            Some(w) => (f64::from(w.per_node) * w.thickness_mm, 0),
            None => (0.0, 2),
        };
        let plated: Vec<f64> = n
            .eye_plates
            .iter()
            .filter(|e| !e.at_edge)
            .map(|e| h + stars + f64::from(e.plates) * eye_mm)
            .collect();
        joints.push(Joint {
            item: "node bolt",
            diameter_mm: b.diameter_mm,
            grip_mm: h + stars,
            plain_washers: plain,
            count: n.grid_nodes.saturating_sub(plated.len() as u64),
        });
        joints.extend(by_length(
            "node bolt under eye plates",
            b.diameter_mm,
            plain,
            plated,
        ));
    }
    if let Some(b) = &profile.shear_block {
        joints.push(Joint {
            item: "shear-block bolt",
            diameter_mm: b.bolt_diameter_mm,
            grip_mm: 2.0 * t + gap,
            plain_washers: 2,
            count: n.shear_blocks,
        });
    }
    if let Some(s) = &profile.splice {
        joints.push(Joint {
            item: "splice bolt",
            diameter_mm: s.bolt_diameter_mm,
            grip_mm: 2.0 * t,
            plain_washers: 2,
            count: n.splice_plates * 2 * u64::from(s.bolts_per_side.max(1)),
        });
    }
    if let Some(d) = profile.edge_bolt_mm() {
        let full = full_edge_grip_mm(profile);
        let rebate_of = |node: usize| {
            n.edge_rebate_grips_mm
                .iter()
                .find(|r| r.0 == node)
                .map(|r| r.1)
        };
        let stacks: Vec<&EyePlateStack> = n.eye_plates.iter().filter(|e| e.at_edge).collect();
        let plated = |node: usize| stacks.iter().any(|e| e.node == node);
        let rebated: Vec<f64> = n
            .edge_rebate_grips_mm
            .iter()
            .filter(|r| !plated(r.0))
            .map(|r| r.1)
            .collect();
        let under_plates: Vec<f64> = stacks
            .iter()
            .map(|e| rebate_of(e.node).unwrap_or(full) + f64::from(e.plates) * eye_mm)
            .collect();
        joints.push(Joint {
            item: "edge bolt",
            diameter_mm: d,
            grip_mm: full,
            plain_washers: 2,
            count: n
                .edge_nodes
                .saturating_sub((rebated.len() + under_plates.len()) as u64),
        });
        joints.extend(by_length("edge bolt at a rebate", d, 2, rebated));
        joints.extend(by_length("edge bolt under eye plates", d, 2, under_plates));
    }
    if let Some(s) = &profile.splice {
        joints.push(Joint {
            item: "band splice bolt",
            diameter_mm: s.bolt_diameter_mm,
            grip_mm: 2.0 * t,
            plain_washers: 2,
            count: n.band_splice_plates * 2 * u64::from(s.bolts_per_side.max(1)),
        });
    }
    if let Some(s) = &profile.stud {
        joints.push(Joint {
            item: "stud bolt",
            diameter_mm: s.fastener_diameter_mm,
            grip_mm: 2.0 * t + gap,
            plain_washers: 2,
            count: 2 * n.studs,
        });
    }
    let class = profile.hardware.bolt_class.as_deref();
    let mut bolts = Vec::new();
    // Nuts and plain washers by thread, in table order.
    let mut nuts = vec![0u64; fasteners::THREADS.len()];
    let mut washers = vec![0u64; fasteners::THREADS.len()];
    for j in joints.iter().filter(|j| j.count > 0) {
        let fail = |what: String| Error::fabrication_joint(&profile.source, j.item, what);
        let Some(k) = fasteners::thread_index(j.diameter_mm) else {
            return Err(fail(format!(
                "a {} mm bolt is no metric coarse thread the takeoff knows ({})",
                fasteners::trim(j.diameter_mm),
                fasteners::thread_names()
            )));
        };
        let th: &Thread = &fasteners::THREADS[k];
        let washer_mm = j.plain_washers as f64 * th.washer_mm;
        let needed = j.grip_mm + washer_mm + th.nut_mm + 2.0 * th.pitch_mm;
        let Some(length) = fasteners::bolt_length_mm(th, needed) else {
            return Err(fail(format!(
                "an {} bolt needs {} mm (grip {} + {} washers {} + nut {} + 2 pitches {}), longer than ISO 4017's longest {} ({} mm)",
                fasteners::name(th.diameter_mm),
                fasteners::trim(needed),
                fasteners::trim(j.grip_mm),
                j.plain_washers,
                fasteners::trim(washer_mm),
                fasteners::trim(th.nut_mm),
                fasteners::trim(2.0 * th.pitch_mm),
                fasteners::name(th.diameter_mm),
                fasteners::trim(th.lengths_mm.1),
            )));
        };
        let m = fasteners::name(th.diameter_mm);
        bolts.push(Hardware {
            item: j.item.into(),
            kind: HardwareKind::Bolt,
            designation: match class {
                Some(c) => format!("{m} × {} ISO 4017 {c}", fasteners::trim(length)),
                None => format!("{m} × {} ISO 4017", fasteners::trim(length)),
            },
            standard: "ISO 4017",
            diameter_mm: th.diameter_mm,
            length_mm: Some(length),
            grip_mm: Some(j.grip_mm),
            needed_mm: Some(needed),
            count: j.count,
            torque_nm: class.and_then(|c| fasteners::torque_nm(th, c)),
        });
        nuts[k] += j.count;
        washers[k] += j.plain_washers * j.count;
    }
    let mut out = bolts;
    for (k, th) in fasteners::THREADS.iter().enumerate() {
        if nuts[k] == 0 {
            continue;
        }
        let m = fasteners::name(th.diameter_mm);
        out.push(Hardware {
            item: "nut".into(),
            kind: HardwareKind::Nut,
            designation: match class.and_then(fasteners::nut_class) {
                Some(c) => format!("{m} ISO 4032 {c}"),
                None => format!("{m} ISO 4032"),
            },
            standard: "ISO 4032",
            diameter_mm: th.diameter_mm,
            length_mm: None,
            grip_mm: None,
            needed_mm: None,
            count: nuts[k],
            torque_nm: None,
        });
    }
    for (k, th) in fasteners::THREADS.iter().enumerate() {
        if washers[k] == 0 {
            continue;
        }
        let m = fasteners::name(th.diameter_mm);
        out.push(Hardware {
            item: "plain washer".into(),
            kind: HardwareKind::Washer,
            designation: match class.and_then(fasteners::washer_grade) {
                Some(g) => format!("{m} ISO 7089 {g}"),
                None => format!("{m} ISO 7089"),
            },
            standard: "ISO 7089",
            diameter_mm: th.diameter_mm,
            length_mm: None,
            grip_mm: None,
            needed_mm: None,
            count: washers[k],
            torque_nm: None,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::read::profile_file;

    fn load(name: &str) -> Profile {
        profile_file::load(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(name))
            .expect("profile")
    }

    /// The steel prototype, by hand: M8 node bolts through 50 mm lamellas
    /// and two 3 mm star washers: grip 56, with nut 6.8 and two pitches
    /// 2.5 needs 65.3, so 70. M5 shear-block bolts through 1.5, 10 and
    /// 1.5: grip 13, with washers 2, nut 4.7 and pitches 1.6 needs 21.3,
    /// so 25. M6 splice bolts through 1.5 and 1.5: grip 3, with washers
    /// 3.2, nut 5.2 and pitches 2 needs 13.4, so 16; 2 per side of each
    /// plate. Class 8.8 from the profile: 25, 5.9 and 10 N·m (VDI 2230).
    #[test]
    fn steel_profile_hardware_by_hand() {
        let p = load("profiles/steel-1.5.yaml");
        let hw = hardware(
            &p,
            Counts {
                grid_nodes: 10,
                shear_blocks: 7,
                splice_plates: 3,
                studs: 0,
                ..Counts::default()
            },
        )
        .expect("hardware");
        let lines: Vec<(&str, &str, u64, Option<f64>)> = hw
            .iter()
            .map(|h| {
                (
                    h.item.as_str(),
                    h.designation.as_str(),
                    h.count,
                    h.torque_nm,
                )
            })
            .collect();
        assert_eq!(
            lines,
            vec![
                ("node bolt", "M8 × 70 ISO 4017 8.8", 10, Some(25.0)),
                ("shear-block bolt", "M5 × 25 ISO 4017 8.8", 7, Some(5.9)),
                ("splice bolt", "M6 × 16 ISO 4017 8.8", 12, Some(10.0)),
                ("nut", "M5 ISO 4032 8", 7, None),
                ("nut", "M6 ISO 4032 8", 12, None),
                ("nut", "M8 ISO 4032 8", 10, None),
                ("plain washer", "M5 ISO 7089 200 HV", 14, None),
                ("plain washer", "M6 ISO 7089 200 HV", 24, None),
            ]
        );
        assert_eq!(hw[0].grip_mm, Some(56.0));
        assert_eq!(hw[1].grip_mm, Some(13.0));
        assert!((hw[2].needed_mm.expect("needed") - 13.4).abs() < 1e-9);
    }

    /// The timber prototype, no class: M5 shear-block bolts through 4, 20
    /// and 4: grip 28, with washers 2, nut 4.7 and pitches 1.6 needs 36.3,
    /// so 40; M4 stud bolts: grip 28, with washers 1.6, nut 3.2 and
    /// pitches 1.4 needs 34.2, so 35; M5 splice bolts: grip 8, needs 16.3,
    /// so 20. No torque.
    #[test]
    fn timber_profile_hardware_by_hand() {
        let p = load("profiles/poplar-ply-4.yaml");
        let hw = hardware(
            &p,
            Counts {
                grid_nodes: 4,
                shear_blocks: 2,
                splice_plates: 1,
                studs: 4,
                ..Counts::default()
            },
        )
        .expect("hardware");
        let lines: Vec<(&str, &str, u64)> = hw
            .iter()
            .map(|h| (h.item.as_str(), h.designation.as_str(), h.count))
            .collect();
        assert_eq!(
            lines,
            vec![
                ("shear-block bolt", "M5 × 40 ISO 4017", 2),
                ("splice bolt", "M5 × 20 ISO 4017", 6),
                ("stud bolt", "M4 × 35 ISO 4017", 8),
                ("nut", "M4 ISO 4032", 8),
                ("nut", "M5 ISO 4032", 8),
                ("plain washer", "M4 ISO 7089", 16),
                ("plain washer", "M5 ISO 7089", 16),
            ]
        );
        assert!(hw.iter().all(|h| h.torque_nm.is_none()));
    }

    /// `hardware.bolt_class` quoted or as a number; a class without a
    /// torque table is a one-line error naming the field; without one, no
    /// class in the designations and no torque.
    #[test]
    fn the_bolt_class_is_read_and_checked() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("profiles/steel-1.5.yaml");
        let text = std::fs::read_to_string(&path).expect("profile");
        assert!(text.contains("bolt_class: \"8.8\""));
        let p = profile_file::parse(&text.replace("\"8.8\"", "10.9"), &path).expect("10.9");
        assert_eq!(p.hardware.bolt_class.as_deref(), Some("10.9"));
        let counts = Counts {
            grid_nodes: 1,
            ..Counts::default()
        };
        let hw = hardware(&p, counts.clone()).expect("hardware");
        assert_eq!(hw[0].designation, "M8 × 70 ISO 4017 10.9");
        assert_eq!(hw[0].torque_nm, Some(36.0));
        assert_eq!(hw[1].designation, "M8 ISO 4032 10");
        let e = profile_file::parse(&text.replace("\"8.8\"", "\"5.6\""), &path)
            .expect_err("5.6")
            .to_string();
        assert!(
            e.contains("hardware.bolt_class") && e.contains("5.6"),
            "{e}"
        );
        let none = text.replace("hardware:\n  bolt_class: \"8.8\"", "hardware: {}");
        let p = profile_file::parse(&none, &path).expect("no class");
        let hw = hardware(&p, counts).expect("hardware");
        assert_eq!(hw[0].designation, "M8 × 70 ISO 4017");
        assert_eq!(hw[0].torque_nm, None);
    }

    /// Grips just below and just above a series value: an M8 node bolt
    /// needs its grip + nut 6.8 + two pitches 2.5 = grip + 9.3 mm, so a
    /// grip of 60.7 mm (lamella 54.7 + star washers 6) takes 70 mm and
    /// 60.71 mm takes 80; an M5 shear-block bolt needs grip + 8.3 (washers
    /// 2, nut 4.7, pitches 1.6): a 16.7 mm grip takes 25 mm, 16.71 takes 30.
    #[test]
    fn grips_either_side_of_a_series_length() {
        let length = |h: f64, gap: f64| {
            let mut p = load("profiles/steel-1.5.yaml");
            p.section.height_mm = h;
            p.section.gap_mm = gap;
            let counts = Counts {
                grid_nodes: 1,
                shear_blocks: 1,
                ..Counts::default()
            };
            let hw = hardware(&p, counts).expect("hardware");
            (hw[0].length_mm, hw[1].length_mm)
        };
        assert_eq!(length(54.7, 13.7), (Some(70.0), Some(25.0)));
        assert_eq!(length(54.71, 13.71), (Some(80.0), Some(30.0)));
    }

    /// A grip past the thread's longest bolt, and a diameter that is no
    /// thread: one line each, naming the joint.
    #[test]
    fn a_bolt_beyond_the_series_names_its_joint() {
        let mut p = load("profiles/steel-1.5.yaml");
        p.section.gap_mm = 40.0;
        let counts = Counts {
            shear_blocks: 1,
            ..Counts::default()
        };
        let e = hardware(&p, counts).expect_err("too long").to_string();
        assert!(
            e.contains("joint shear-block bolt:") && e.contains("50 mm") && !e.contains('\n'),
            "{e}"
        );
        let mut p = load("profiles/steel-1.5.yaml");
        if let Some(s) = p.splice.as_mut() {
            s.bolt_diameter_mm = 7.0;
        }
        let counts = Counts {
            splice_plates: 1,
            ..Counts::default()
        };
        let e = hardware(&p, counts).expect_err("no thread").to_string();
        assert!(
            e.contains("joint splice bolt:") && e.contains("7 mm"),
            "{e}"
        );
    }

    /// Eye plates (4 mm, steel profile) stack under their bolts: an M8
    /// node bolt's grip 56 grows to 60 under one plate (needs 69.3, so
    /// 70) and to 64 under two (73.3, so 80); an edge bolt's full grip 50
    /// to 54 under one (with washers 1.6·2, nut 6.8 and pitches 2.5:
    /// 66.5, so 70), and at a rebate of grip 25.45 to 29.45 (41.95, so
    /// 45). The plain lines keep the nodes without plates; nuts and
    /// washers count every bolt.
    #[test]
    fn eye_plates_lengthen_the_bolts_they_sit_under() {
        let p = load("profiles/steel-1.5.yaml");
        let stack = |node, plates, at_edge| EyePlateStack {
            node,
            plates,
            at_edge,
        };
        let hw = hardware(
            &p,
            Counts {
                grid_nodes: 10,
                edge_nodes: 6,
                edge_rebate_grips_mm: vec![(20, 25.45), (21, 25.45)],
                eye_plates: vec![
                    stack(1, 1, false),
                    stack(2, 2, false),
                    stack(3, 1, false),
                    stack(20, 1, true),
                    stack(22, 1, true),
                ],
                ..Counts::default()
            },
        )
        .expect("hardware");
        let lines: Vec<(&str, &str, u64, Option<f64>)> = hw
            .iter()
            .map(|h| (h.item.as_str(), h.designation.as_str(), h.count, h.grip_mm))
            .collect();
        assert_eq!(
            lines,
            vec![
                ("node bolt", "M8 × 70 ISO 4017 8.8", 7, Some(56.0)),
                (
                    "node bolt under eye plates",
                    "M8 × 70 ISO 4017 8.8",
                    2,
                    Some(60.0)
                ),
                (
                    "node bolt under eye plates",
                    "M8 × 80 ISO 4017 8.8",
                    1,
                    Some(64.0)
                ),
                ("edge bolt", "M8 × 65 ISO 4017 8.8", 3, Some(50.0)),
                (
                    "edge bolt at a rebate",
                    "M8 × 40 ISO 4017 8.8",
                    1,
                    Some(25.45)
                ),
                (
                    "edge bolt under eye plates",
                    "M8 × 45 ISO 4017 8.8",
                    1,
                    Some(29.45)
                ),
                (
                    "edge bolt under eye plates",
                    "M8 × 70 ISO 4017 8.8",
                    1,
                    Some(54.0)
                ),
                ("nut", "M8 ISO 4032 8", 16, None),
                ("plain washer", "M8 ISO 7089 200 HV", 12, None),
            ]
        );
    }

    /// Edge bolts by hand on the steel profile: the full stack h = 50 with
    /// two M8 plain washers 1.6, nut 6.8 and two pitches 1.25 needs 62.5,
    /// so 65; at rebates a grip of 25.45 needs 37.95, so 40, and one of 30
    /// needs 42.5, so 45: one line per length, the rest at the full grip.
    #[test]
    fn edge_bolts_at_rebates_by_length() {
        let p = load("profiles/steel-1.5.yaml");
        let hw = hardware(
            &p,
            Counts {
                edge_nodes: 5,
                edge_rebate_grips_mm: vec![(1, 25.45), (2, 30.0), (3, 25.45)],
                ..Counts::default()
            },
        )
        .expect("hardware");
        let lines: Vec<(&str, &str, u64, Option<f64>)> = hw
            .iter()
            .map(|h| (h.item.as_str(), h.designation.as_str(), h.count, h.grip_mm))
            .collect();
        assert_eq!(
            lines,
            vec![
                ("edge bolt", "M8 × 65 ISO 4017 8.8", 2, Some(50.0)),
                (
                    "edge bolt at a rebate",
                    "M8 × 40 ISO 4017 8.8",
                    2,
                    Some(25.45)
                ),
                (
                    "edge bolt at a rebate",
                    "M8 × 45 ISO 4017 8.8",
                    1,
                    Some(30.0)
                ),
                ("nut", "M8 ISO 4032 8", 5, None),
                ("plain washer", "M8 ISO 7089 200 HV", 10, None),
            ]
        );
    }
}
