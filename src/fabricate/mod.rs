//! Fabrication: every strip turned into the flat parts a laser or waterjet
//! cuts, for a material profile (docs/fabrication.md): lamellas with swept slots
//! or node holes, shear blocks, splice plates (and, as the stage grows,
//! washers, studs, edge strips and labels).
//!
//! Plain data in (`Network`, `Analysis`, `Profile`), plain data out
//! ([`Kit`]); a profile that cannot build the network is an
//! [`Error::Fabrication`](crate::Error::Fabrication) naming strip and node.

pub mod blocks;
pub mod edge_strip;
pub mod engrave;
pub mod eye_plate;
pub mod fasteners;
pub mod font;
pub mod hardware;
pub mod invariants;
pub mod label;
pub mod lamella;
pub mod part;
pub mod slots;
pub mod stud;
pub mod washer;

use crate::analysis::lines::{NetworkLines, StripLines};
use crate::analysis::Analysis;
use crate::error::Result;
use crate::geom::plane::signed_area_mm2;
use crate::network::Network;
use crate::profile::Profile;
use kurbo::Point;
use part::{Feature, FeatureKind, HoleUse, Part, PartKind};
use rayon::prelude::*;

/// Every part of a network for one profile.
#[derive(Debug, Clone)]
pub struct Kit {
    /// Lamellas by strip (in strip order) and lamella, then the shared
    /// parts (shear blocks, splice plates, …) once each with their counts.
    pub parts: Vec<Part>,
    /// Counts, lengths and mass.
    pub summary: KitSummary,
    /// What could not be engraved, one line each (the parts are still
    /// right; a label is missing).
    pub warnings: Vec<String>,
}

/// How many of each kind, and what they weigh.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct KitSummary {
    /// Per kind (in [`PartKind`] order): distinct parts and pieces to make.
    pub kinds: Vec<(PartKind, usize, u64)>,
    /// Total length of lamella parts (allowances included), mm.
    pub lamella_length_mm: f64,
    /// Mass of everything cut or sawn, kg.
    pub mass_kg: f64,
    /// Bars of stud stock to saw the studs from (two-level grids).
    pub stud_bars: u32,
    /// Bolts, nuts and plain washers, counted (bought).
    pub hardware: Vec<hardware::Hardware>,
    /// The joints the hardware is counted from.
    pub joints: hardware::Counts,
    /// The A×B nodes (ids) and the edge nodes with a bolt: where a bolt
    /// can take a bracing cable's eye plate.
    pub bolted_nodes: BoltedNodes,
}

/// The nodes whose joint has a bolt, by id, ascending.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BoltedNodes {
    /// A×B nodes with a node bolt.
    pub grid: Vec<usize>,
    /// Edge nodes with an edge bolt.
    pub edge: Vec<usize>,
}

/// Make every part of the network's A/B strips for `profile`.
///
/// Slots are swept over the profile's blanket rotation tolerance, or, where
/// `rotations` are given, over each A×B node's rotation from the flat state
/// to the erected one (degrees A → B by node id, from [`crate::flat`]); a
/// rotation past the profile's tolerance is an error naming the node.
///
/// `lines` are the lamella lines the check integrated for this profile
/// ([`crate::check::check`] keeping its lines): each strip's blocks, cuts
/// and holes are carried onto them with one short integral each, and its
/// lines are dropped once its parts are made. A strip whose lines are
/// missing (or another profile's; pass `NetworkLines::default()` for none)
/// integrates its own; the parts are the same either way.
pub fn fabricate(
    net: &Network,
    an: &Analysis,
    profile: &Profile,
    rotations: Option<&std::collections::HashMap<usize, f64>>,
    mut lines: NetworkLines,
) -> Result<Kit> {
    let jobs: Vec<(usize, Option<StripLines>)> = an
        .lamella_strips()
        .map(|s| (s.curve, lines.take(s.curve)))
        .collect();
    drop(lines);
    // Every strip's result, then the first error in strip order: a
    // parallel collect into `Result` would report whichever strip failed
    // first in time, so the refusal would vary from run to run.
    let per_strip: Vec<lamella::StripParts> = jobs
        .into_par_iter()
        .map(|(i, l)| lamella::strip_parts(net, an, profile, i, rotations, l))
        .collect::<Vec<Result<_>>>()
        .into_iter()
        .collect::<Result<Vec<_>>>()?;
    let mut parts: Vec<Part> = Vec::new();
    let (mut blocks, mut plates) = (0usize, 0usize);
    for sp in per_strip {
        blocks += sp.blocks;
        plates += sp.splice_plates;
        parts.extend(sp.lamellas);
    }
    let h = profile.section.height_mm;
    if let (Some(b), true) = (&profile.shear_block, blocks > 0) {
        let d = b.bolt_diameter_mm + lamella::BOLT_HOLE_CLEARANCE_MM;
        parts.push(rectangle_part(
            "SB",
            PartKind::ShearBlock,
            blocks as u32,
            b.length_mm,
            0.5 * h,
            &[(
                Point::new(0.5 * b.length_mm, 0.25 * h),
                d,
                HoleUse::ShearBlock,
            )],
        ));
    }
    if let (Some(sp), true) = (&profile.splice, plates > 0) {
        let d = sp.bolt_diameter_mm + lamella::BOLT_HOLE_CLEARANCE_MM;
        let n = sp.bolts_per_side.max(1) as usize;
        let half = 0.5 * sp.plate_length_mm;
        let holes: Vec<(Point, f64, HoleUse)> = (0..n)
            .flat_map(|j| {
                let off = half * (j as f64 + 0.5) / n as f64;
                [half - off, half + off]
            })
            .map(|x| (Point::new(x, 0.25 * h), d, HoleUse::Splice))
            .collect();
        parts.push(rectangle_part(
            "SP",
            PartKind::SplicePlate,
            plates as u32,
            sp.plate_length_mm,
            0.5 * h,
            &holes,
        ));
    }
    let grid = washer::grid_nodes(an);
    parts.extend(washer::washers(profile, &grid)?);
    let stud_cut = stud::studs(profile, grid.len())?;
    let stud_bars = stud_cut.as_ref().map_or(0, |s| s.bars);
    parts.extend(stud_cut.map(|s| s.part));
    let edges = edge_strip::edge_curves(an);
    let bands = edge_strip::edge_strips(profile, an)?;
    let band_plates = bands
        .iter()
        .filter(|p| p.kind == PartKind::SplicePlate)
        .count();
    parts.extend(bands);
    let clearance = profile.cutting.kerf_mm + profile.cutting.part_spacing_mm;
    let warnings = engrave::engrave_all(&mut parts, clearance);
    for p in &parts {
        debug_assert_eq!(
            invariants::check_part(p, clearance),
            Ok(()),
            "part {}",
            p.id
        );
    }
    let mut summary = summarise(&parts, profile);
    summary.stud_bars = stud_bars;
    let pieces = |kind| {
        parts
            .iter()
            .filter(|p| p.kind == kind)
            .map(|p| u64::from(p.count))
            .sum::<u64>()
    };
    let bolted_edge_nodes: Vec<usize> = if profile.edge_bolt_mm().is_some() {
        edges
            .iter()
            .flat_map(|e| e.nodes.iter().map(|n| n.id))
            .collect()
    } else {
        Vec::new()
    };
    summary.joints = hardware::Counts {
        grid_nodes: grid.len() as u64,
        shear_blocks: blocks as u64,
        splice_plates: plates as u64,
        studs: pieces(PartKind::Stud),
        edge_nodes: bolted_edge_nodes.len() as u64,
        edge_rebate_grips_mm: hardware::edge_grips_mm(profile, &parts, &bolted_edge_nodes),
        band_splice_plates: band_plates as u64,
        eye_plates: Vec::new(),
    };
    summary.hardware = hardware::hardware(profile, summary.joints.clone())?;
    let mut bolted_grid: Vec<usize> = match &profile.node_bolt {
        Some(_) => grid.iter().map(|n| n.id).collect(),
        None => Vec::new(),
    };
    let mut bolted_edge = bolted_edge_nodes;
    bolted_grid.sort_unstable();
    bolted_edge.sort_unstable();
    bolted_edge.dedup();
    summary.bolted_nodes = BoltedNodes {
        grid: bolted_grid,
        edge: bolted_edge,
    };
    Ok(Kit {
        parts,
        summary,
        warnings,
    })
}

impl Kit {
    /// Add the eye plates of bracing cables ending at `cable_ends` (node
    /// ids, one per cable end; [`eye_plate`]): the parts (engraved), their
    /// mass, and the longer bolts under their stacks. Each end must be at a
    /// bolted joint: an A×B node with a node bolt or an edge node with an
    /// edge bolt, else an error naming the node (`cable` names the cable
    /// ending there, for the message). Replaces eye plates added before.
    pub fn add_eye_plates(
        &mut self,
        profile: &Profile,
        cable_ends: &[(usize, String)],
    ) -> Result<()> {
        // Plates added before go, with their engraving warnings (which
        // start with the part's id).
        let old: Vec<String> = self
            .parts
            .iter()
            .filter(|p| p.kind == PartKind::EyePlate)
            .map(|p| format!("{}:", p.id))
            .collect();
        self.warnings
            .retain(|w| !old.iter().any(|id| w.starts_with(id.as_str())));
        self.parts.retain(|p| p.kind != PartKind::EyePlate);
        self.summary.joints.eye_plates.clear();
        let Some(brace) = &profile.bracing else {
            return Ok(());
        };
        let bolted = &self.summary.bolted_nodes;
        let mut stacks: std::collections::BTreeMap<usize, (u32, bool)> = Default::default();
        for (node, cable) in cable_ends {
            let at_edge = if bolted.grid.binary_search(node).is_ok() {
                false
            } else if bolted.edge.binary_search(node).is_ok() {
                true
            } else {
                return Err(crate::error::Error::fabrication_part(
                    &profile.source,
                    &format!("eye plate of cable {cable}"),
                    format!(
                        "node {node} has no bolt to take the eye plate \
                         (an A×B node needs node_bolt; an edge node a bolted edge joint)"
                    ),
                ));
            };
            let e = stacks.entry(*node).or_insert((0, at_edge));
            e.0 += 1;
        }
        // Eye plates by the bolt's diameter (the node bolt's, the edge
        // bolt's).
        let mut by_bolt: Vec<(f64, u32)> = Vec::new();
        for &(plates, at_edge) in stacks.values() {
            let d = if at_edge {
                profile.edge_bolt_diameter_mm()
            } else {
                profile.node_bolt.as_ref().map(|b| b.diameter_mm)
            }
            .unwrap_or(0.0);
            match by_bolt.iter_mut().find(|b| b.0 == d) {
                Some(b) => b.1 += plates,
                None => by_bolt.push((d, plates)),
            }
        }
        by_bolt.sort_by(|a, b| a.0.total_cmp(&b.0));
        let clearance = profile.edge_bolt_clearance_mm();
        let mut plates: Vec<Part> = by_bolt
            .iter()
            .map(|&(d, n)| eye_plate::eye_plate_part(&brace.eye_plate, d, clearance, n))
            .collect();
        let cut = profile.cutting.kerf_mm + profile.cutting.part_spacing_mm;
        self.warnings.extend(engrave::engrave_all(&mut plates, cut));
        for p in &plates {
            debug_assert_eq!(invariants::check_part(p, cut), Ok(()), "part {}", p.id);
        }
        self.parts.extend(plates);
        self.summary.joints.eye_plates = stacks
            .iter()
            .map(|(&node, &(plates, at_edge))| hardware::EyePlateStack {
                node,
                plates,
                at_edge,
            })
            .collect();
        let (joints, bolted, stud_bars) = (
            self.summary.joints.clone(),
            self.summary.bolted_nodes.clone(),
            self.summary.stud_bars,
        );
        let hardware = hardware::hardware(profile, joints.clone())?;
        self.summary = summarise(&self.parts, profile);
        self.summary.stud_bars = stud_bars;
        self.summary.hardware = hardware;
        self.summary.joints = joints;
        self.summary.bolted_nodes = bolted;
        Ok(())
    }
}

/// A rectangular part with round holes (its `hole` features).
fn rectangle_part(
    id: &str,
    kind: PartKind,
    count: u32,
    length_mm: f64,
    height_mm: f64,
    holes: &[(Point, f64, HoleUse)],
) -> Part {
    Part {
        id: id.to_string(),
        kind,
        strip: None,
        lamella: None,
        count,
        length_mm,
        height_mm,
        station_start_mm: None,
        outline_part_mm: vec![
            Point::new(0.0, 0.0),
            Point::new(length_mm, 0.0),
            Point::new(length_mm, height_mm),
            Point::new(0.0, height_mm),
        ],
        holes_part_mm: Vec::new(),
        engraving: Vec::new(),
        features: holes
            .iter()
            .map(|&(c, d, u)| Feature {
                kind: FeatureKind::Hole,
                hole_use: Some(u),
                node: None,
                crossing: None,
                center_part_mm: c,
                width_mm: d,
                depth_mm: 0.0,
                edge: None,
                angle_range_deg: None,
                station_mm: None,
            })
            .collect(),
    }
}

/// Net area of a part (outline less holes), mm²: a round hole
/// ([`Part::round_holes`]) takes its circle's area, as it is cut; any
/// other hole its polygon's.
pub fn net_area_mm2(p: &Part) -> f64 {
    signed_area_mm2(&p.outline_part_mm)
        - p.round_holes()
            .into_iter()
            .map(|(_, r)| std::f64::consts::PI * r.powi(2))
            .chain(p.holes_part_mm.iter().map(|h| signed_area_mm2(h).abs()))
            .sum::<f64>()
}

/// Thickness a part is made in, mm: shear blocks and studs as thick as the
/// gap they fill, washers at the washer thickness, the rest at the lamella
/// thickness.
pub fn part_thickness_mm(kind: PartKind, profile: &Profile) -> f64 {
    match kind {
        PartKind::ShearBlock | PartKind::Stud => profile.section.gap_mm,
        PartKind::Washer => profile.washer.as_ref().map_or(0.0, |w| w.thickness_mm),
        PartKind::EyePlate => profile.piece_thickness_mm(crate::profile::Piece::EyePlate),
        _ => profile.section.thickness_mm,
    }
}

/// Mass of one piece of a part, kg.
pub fn part_mass_kg(p: &Part, profile: &Profile) -> f64 {
    net_area_mm2(p) * part_thickness_mm(p.kind, profile) * profile.material.density_kg_per_m3 * 1e-9
}

/// Count by kind, lamella length, mass (plates at the lamella thickness,
/// shear blocks at the gap's thickness).
fn summarise(parts: &[Part], profile: &Profile) -> KitSummary {
    let mut s = KitSummary::default();
    for p in parts {
        match s.kinds.iter_mut().find(|k| k.0 == p.kind) {
            Some(k) => {
                k.1 += 1;
                k.2 += u64::from(p.count);
            }
            None => s.kinds.push((p.kind, 1, u64::from(p.count))),
        }
        if p.kind == PartKind::Lamella {
            s.lamella_length_mm += p.length_mm * f64::from(p.count);
        }
        s.mass_kg += part_mass_kg(p, profile) * f64::from(p.count);
    }
    s.kinds.sort_by_key(|k| k.0);
    s
}
