//! The stacks of the kit's joints, as the assembly sheets draw them in
//! section (not in plan.json): for each kind of bolted joint the parts
//! the bolt passes through, head side first, with their thicknesses from
//! the profile; the bolt as the takeoff orders it (length from the ISO
//! 4017 series for the grip, `fabricate::fasteners`), its nut and plain
//! washers (ISO 4032, ISO 7089) and torque; and which lamella of a
//! doubled strip lies on which side.

use super::takeoff::HardwareLine;
use crate::fabricate::fasteners;
use crate::profile::{JointSystem, Profile};

/// One kind of joint in section.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanJoint {
    /// What it is (`node joint`, `shear block`, `splice`, `stud joint`,
    /// `halving slots`).
    pub title: String,
    /// The parts the bolt clamps, from under its head to its nut.
    pub stack: Vec<JointLayer>,
    /// The node joint: the doubled strip standing beside the bolt
    /// (lamella thickness t, gap, height h, mm), between the star washers.
    pub beside: Option<[f64; 3]>,
    /// The bolt, when the joint has one.
    pub bolt: Option<JointBolt>,
    /// What the crew must know besides (sides, slots, count).
    pub notes: Vec<String>,
    /// The edge joint: a lamella's end on its band (drawn on a page of its
    /// own, in section and in elevation).
    pub edge: Option<EdgeSection>,
}

/// A lamella strip ending on an edge band, mm: the band in the lamellas'
/// end slots and, bolted, the edge bolt along the surface normal through
/// the strip's gap and the band's hole.
#[derive(Debug, Clone, PartialEq)]
pub struct EdgeSection {
    /// Lamella thickness t (the band is as thick), mm.
    pub thickness_mm: f64,
    /// Lamella height h (the band is as wide), mm.
    pub height_mm: f64,
    /// Gap between the lamellas of a doubled strip, mm.
    pub gap_mm: f64,
    /// Lamellas per strip.
    pub per_strip: u32,
    /// The end slot's opening across: t + twice the slot clearance, mm.
    pub slot_mm: f64,
    /// Height of the end slot's centre (where the surface passes) above
    /// the lamella's bottom edge: h/2 − level offset, mm.
    pub slot_centre_mm: f64,
    /// End allowance past the node, mm.
    pub allowance_mm: f64,
    /// The end slot's reach from the lamella's end where the strip meets
    /// the band at a right angle: allowance + h/2 + clearance, mm (more at
    /// an oblique node: (h/2)/sin φ).
    pub slot_depth_mm: f64,
    /// The band's hole for the edge bolt (bolt + clearance), mm, when
    /// bolted.
    pub hole_mm: Option<f64>,
    /// Bolts at rebates (both lamellas' end slots opened to one edge):
    /// their order line, count and grip.
    pub rebate: Option<(String, u64, f64)>,
}

/// A part the bolt passes through.
#[derive(Debug, Clone, PartialEq)]
pub struct JointLayer {
    /// What it is (`lamella 1`, `shear block`, `star washer`).
    pub what: String,
    /// Along the bolt, mm.
    pub thickness_mm: f64,
    /// Across the bolt as drawn, mm.
    pub width_mm: f64,
    /// A lamella (drawn hatched), else a plate or block.
    pub lamella: bool,
}

/// A joint's bolt, nut and plain washers.
#[derive(Debug, Clone, PartialEq)]
pub struct JointBolt {
    /// As ordered (`M8 × 70 ISO 4017 8.8`).
    pub designation: String,
    /// Thread diameter d, mm.
    pub diameter_mm: f64,
    /// Nominal length under the head, mm.
    pub length_mm: f64,
    /// Clamped thickness, mm.
    pub grip_mm: f64,
    /// Nut height m, mm (ISO 4032).
    pub nut_mm: f64,
    /// Plain washer thickness, mm (ISO 7089), and outside diameter.
    pub washer_mm: [f64; 2],
    /// A plain washer under the head and one under the nut.
    pub plain_washers: bool,
    /// Tightening torque, N·m, when the profile gives the class.
    pub torque_nm: Option<f64>,
    /// Bolts of this joint in the kit.
    pub count: u64,
}

/// The joints of a kit made to `profile`, with the takeoff's bolt lines
/// (`hardware`): one per bolt line whose joint is known, the halving
/// slots of an interlocking grid without a node bolt, and last, when
/// lamellas end on edge bands (`edge_nodes`), the edge joint.
pub fn joints(profile: &Profile, hardware: &[HardwareLine], edge_nodes: bool) -> Vec<PlanJoint> {
    let (t, h, gap) = (
        profile.section.thickness_mm,
        profile.section.height_mm,
        profile.section.gap_mm,
    );
    let doubled = profile.section.per_strip == 2;
    let bolt = |item: &str, plain: bool| -> Option<JointBolt> {
        let line = hardware.iter().find(|l| l.item == item)?;
        let th = fasteners::thread(line.diameter_mm)?;
        Some(JointBolt {
            designation: line.designation.clone(),
            diameter_mm: line.diameter_mm,
            length_mm: line.length_mm?,
            grip_mm: line.grip_mm?,
            nut_mm: th.nut_mm,
            washer_mm: [th.washer_mm, th.washer_outside_mm],
            plain_washers: plain,
            torque_nm: line.torque_nm,
            count: line.count,
        })
    };
    let lamella = |n: u32, w: f64| JointLayer {
        what: if doubled {
            format!("lamella {n}, t = {}", fasteners::trim(t))
        } else {
            format!("lamella, t = {}", fasteners::trim(t))
        },
        thickness_mm: t,
        width_mm: w,
        lamella: true,
    };
    let sides = "looking from a strip's start end to its end, top edge up: lamella 1 on the right, lamella 2 on the left";
    let mut out = Vec::new();
    match (&profile.node_bolt, profile.joint.system) {
        (Some(_), _) => {
            if let Some(b) = bolt("node bolt", profile.washer.is_none()) {
                let (stars, arm) = profile.washer.as_ref().map_or((Vec::new(), 0.0), |w| {
                    let layer = JointLayer {
                        what: format!(
                            "star washer, {} thick, arms {} long",
                            fasteners::trim(w.thickness_mm),
                            fasteners::trim(w.arm_length_mm)
                        ),
                        thickness_mm: w.thickness_mm,
                        width_mm: 2.0 * w.arm_length_mm,
                        lamella: false,
                    };
                    (vec![layer; w.per_node.div_ceil(2) as usize], w.arm_length_mm)
                });
                let mut stack = stars.clone();
                stack.push(JointLayer {
                    what: format!("four lamellas, h = {}", fasteners::trim(h)),
                    thickness_mm: h,
                    width_mm: (2.0 * arm).max(gap + 2.0 * t + 20.0),
                    lamella: true,
                });
                stack.extend(stars);
                out.push(PlanJoint {
                    title: "Node joint".into(),
                    stack,
                    beside: Some([t, gap, h]),
                    bolt: Some(b),
                    notes: vec![
                        "the bolt runs along the surface normal, through the square between the four lamellas".into(),
                        "family A lies with its slots up, B is slotted in from above (slots down)".into(),
                        "the star washers' arms lie along the two strips, on the top and bottom edges".into(),
                        sides.into(),
                    ],
                    edge: None,
                });
            }
        }
        (None, JointSystem::Interlocking) => out.push(PlanJoint {
            title: "Halving slots".into(),
            stack: Vec::new(),
            beside: Some([t, gap, h]),
            bolt: None,
            notes: vec![
                format!(
                    "no node bolt: family A is slotted from its top edge, B from its bottom edge, each to about half the height h = {}",
                    fasteners::trim(h)
                ),
                "lay family A slots up, then slot family B in from above".into(),
            ],
            edge: None,
        }),
        (None, JointSystem::TwoLevel) => {
            if let Some(b) = bolt("stud bolt", true) {
                out.push(PlanJoint {
                    title: "Stud joint".into(),
                    stack: vec![
                        lamella(1, h),
                        JointLayer {
                            what: format!("stud, {} square", fasteners::trim(gap)),
                            thickness_mm: gap,
                            width_mm: gap,
                            lamella: false,
                        },
                        lamella(2, h),
                    ],
                    beside: None,
                    bolt: Some(b),
                    notes: vec![
                        "the stud stands along the surface normal in the gaps of both levels' strips; one bolt across each level".into(),
                        "lower level: family A; upper level: family B".into(),
                        sides.into(),
                    ],
                    edge: None,
                });
            }
        }
    }
    if let Some(b) = bolt("shear-block bolt", true) {
        let block_h = profile
            .shear_block
            .as_ref()
            .map_or(h, |s| s.length_mm.min(h));
        out.push(PlanJoint {
            title: "Shear block".into(),
            stack: vec![
                lamella(1, h),
                JointLayer {
                    what: format!("shear block SB, {} thick", fasteners::trim(gap)),
                    thickness_mm: gap,
                    width_mm: block_h,
                    lamella: false,
                },
                lamella(2, h),
            ],
            beside: None,
            bolt: Some(b),
            notes: vec![
                "across the doubled strip, between its two lamellas, at the stations of the shear-block schedule".into(),
                sides.into(),
            ],
            edge: None,
        });
    }
    if let Some(b) = bolt("splice bolt", true) {
        out.push(PlanJoint {
            title: "Splice".into(),
            stack: vec![
                lamella(1, h),
                JointLayer {
                    what: format!("splice plate SP, t = {}", fasteners::trim(t)),
                    thickness_mm: t,
                    width_mm: h,
                    lamella: false,
                },
            ],
            beside: None,
            bolt: Some(b),
            notes: vec![
                format!(
                    "the plate joins two pieces of one lamella end to end, {} bolts each side",
                    profile.splice.as_ref().map_or(2, |s| s.bolts_per_side)
                ),
                "piece .1's far end meets piece .2's start end (stations restart at 0 there)"
                    .into(),
            ],
            edge: None,
        });
    }
    if edge_nodes {
        out.push(edge_joint(profile, hardware, bolt("edge bolt", true)));
    }
    out
}

/// The edge joint of a kit with edge bands: its figures from the profile,
/// the edge bolt (`bolt`) where the joint is bolted, the bolts at rebates.
fn edge_joint(profile: &Profile, hardware: &[HardwareLine], bolt: Option<JointBolt>) -> PlanJoint {
    let (t, h, gap) = (
        profile.section.thickness_mm,
        profile.section.height_mm,
        profile.section.gap_mm,
    );
    let c = profile.joint.slot_clearance_mm;
    let allowance = profile.section.end_allowance_mm;
    let bolted = profile.edge_bolt_mm();
    let rebate = hardware
        .iter()
        .filter(|l| l.item == "edge bolt at a rebate")
        .map(|l| (l.designation.clone(), l.count, l.grip_mm.unwrap_or(0.0)))
        .next();
    let edge = EdgeSection {
        thickness_mm: t,
        height_mm: h,
        gap_mm: gap,
        per_strip: profile.section.per_strip,
        slot_mm: t + 2.0 * c,
        slot_centre_mm: 0.5 * h - profile.joint.level_offset_mm,
        allowance_mm: allowance,
        slot_depth_mm: allowance + 0.5 * h + c,
        hole_mm: bolted.map(|d| d + profile.edge_bolt_clearance_mm()),
        rebate,
    };
    let mut notes = vec![
        "the band lies in the surface; every lamella ending on it has an end slot at the height where the surface passes, and the band slides into the slots".into(),
        "the slot reaches past the band's far edge (end slot depth = allowance + h/2 + clearance at a right angle; (h/2)/sin φ instead of h/2 where the strip meets the band at φ); each slot's depth is in plan.json".into(),
    ];
    if profile.joint.level_offset_mm != 0.0 {
        notes.push(format!(
            "two levels: drawn for family A, standing {} above the surface; family B stands as far below it, its end slot as far from its top edge",
            fasteners::trim(profile.joint.level_offset_mm.abs())
        ));
    }
    match (&bolt, bolted) {
        (Some(_), _) | (None, Some(_)) => notes.push(
            "the edge bolt runs along the surface normal through the gap between the strip's lamellas and the band's hole at the node; a plain washer on the lamellas' edges top and bottom".into(),
        ),
        (None, None) => notes.push(
            "no bolt: the end slots alone hold the band (glue or pin it on site); the band has no holes".into(),
        ),
    }
    if let Some((designation, count, grip)) = &edge.rebate {
        notes.push(format!(
            "at {count} nodes both lamellas' end slots open into a rebate from one edge: the washer bears on the band on the rebate's floor, grip {}, {designation}",
            fasteners::trim(*grip)
        ));
    }
    PlanJoint {
        title: if bolted.is_some() {
            "Edge joint, bolted".into()
        } else {
            "Edge joint, end slots".into()
        },
        stack: Vec::new(),
        beside: None,
        bolt,
        notes,
        edge: Some(edge),
    }
}
