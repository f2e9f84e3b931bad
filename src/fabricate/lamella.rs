//! Lamella parts: every lamella of every A/B strip as a flat, straight part
//! on its own offset line, with the slots (interlocking) or node holes (two
//! levels), the shear blocks' and splices' bolt holes, split where it is
//! longer than the stock.
//!
//! Positions along a strip are decided once on its centre line (node zones,
//! block centres, splice cuts) and then carried to each lamella's own line
//! (`StripLines::stations`: the check's integration of the lines when it is
//! given, else the strip's own); slots are placed from each node's station
//! on the lamella's own line.

use super::blocks;
use super::part::{Feature, FeatureKind, HoleUse, Part, PartKind, SlotEdge};
use super::slots::{node_slots_in, range_between_rad, sweep_range_rad, SlotSpan, SweepRange};
use crate::analysis::lines::{LamellaLine, StripLines};
use crate::analysis::strip::StripGeometry;
use crate::analysis::Analysis;
use crate::error::{Error, Result};
use crate::network::{Family, Network};
use crate::profile::{JointSystem, LamellaOffset, Profile, ShearBlock};
use kurbo::Point;
use std::collections::HashMap;

/// Clearance added to a bolt's diameter for its hole, mm (EN 1090-2:2018
/// Table 11, normal round holes for M12 and smaller), where the profile
/// names none.
pub const BOLT_HOLE_CLEARANCE_MM: f64 = 1.0;

/// A last splice piece shorter than this fraction of the stock's usable
/// length is a stub: the cuts are evened out instead.
const MIN_LAST_PIECE_FRACTION: f64 = 0.2;

/// Spacing of candidate splice cuts along long stretches between nodes, mm.
const CANDIDATE_STEP_MM: f64 = 50.0;

/// What fabricating one strip made.
#[derive(Debug, Clone, Default)]
pub struct StripParts {
    /// Lamella parts (pieces, if spliced), by lamella then piece.
    pub lamellas: Vec<Part>,
    /// Shear blocks along the strip (each couples its two lamellas).
    pub blocks: usize,
    /// Splice plates (one per cut per lamella).
    pub splice_plates: usize,
}

/// Why a strip cannot be made: the node it concerns, if any, and what is
/// wrong (one line); [`strip_parts`] names the profile and strip.
type Refusal = (Option<usize>, String);

/// A crossing of this strip with another A/B strip, seen from this strip.
#[derive(Debug, Clone)]
struct Crossing<'a> {
    /// Index into the strip's node list.
    k: usize,
    /// Node id (plan.json).
    node_id: usize,
    /// Crossing strip's id.
    crossing_id: &'a str,
    /// Signed angle from this strip's direction to the crossing one's,
    /// about the node normal, degrees.
    angle_deg: f64,
    /// The crossing strip's lamella offsets (by lamella number).
    crossing_offsets_mm: &'a [f64],
}

/// The slots of a strip's lamellas (none unless the joint interlocks).
#[derive(Debug, Clone)]
struct Slots {
    /// Per crossing, the angles its slots are swept over, radians.
    ranges_rad: Vec<(f64, f64)>,
    /// Per lamella: (crossing index, its slot spans relative to the node's
    /// station on that lamella's line).
    spans: Vec<Vec<(usize, Vec<SlotSpan>)>>,
    /// Depth of every slot from its edge, mm.
    depth_mm: f64,
}

/// Where things sit along the strip's centre line, mm from its start.
#[derive(Debug, Clone)]
struct CentreLine {
    /// Shear block centres.
    blocks: Vec<f64>,
    /// Splice cuts, ascending.
    cuts: Vec<f64>,
    /// Splice bolt holes, by cut then bolt pair.
    splice_holes: Vec<f64>,
}

/// The diameters of a strip's round holes, mm, where it has them.
#[derive(Debug, Clone, Copy)]
struct HoleSizes {
    /// At every node (two-level joints).
    node_mm: Option<f64>,
    /// For the shear blocks' bolts.
    block_mm: Option<f64>,
    /// For the splice plates' bolts.
    splice_mm: Option<f64>,
}

/// Where the strip ends on an edge strip: the band runs through an end
/// slot of each lamella there (docs/fabrication.md, "Edge joints").
#[derive(Debug, Clone)]
struct EdgeEnd<'a> {
    /// Index into the strip's node list.
    k: usize,
    /// Node id (plan.json).
    node_id: usize,
    /// The edge's id.
    edge_id: &'a str,
    /// Acute angle between the strip and the edge, degrees.
    angle_deg: f64,
}

/// The end slots' common sizes, mm.
#[derive(Debug, Clone, Copy)]
struct EndSlotSize {
    /// The band's height (its width across the edge curve).
    band_mm: f64,
    /// The opening across the lamella: band thickness + twice the slot
    /// clearance.
    opening_mm: f64,
    /// Slot clearance.
    clearance_mm: f64,
}

impl EndSlotSize {
    /// How far an end slot reaches from the node's station inward along a
    /// lamella line `dy_mm` off the strip's curve, crossing the band at
    /// `angle_deg`: the band's half height over sin φ, the offset line's
    /// shift |dy|·cot φ, and the clearance.
    fn reach_mm(&self, angle_deg: f64, dy_mm: f64) -> f64 {
        let (sin, cos) = angle_deg.to_radians().sin_cos();
        let sin = sin.max(1e-3);
        0.5 * self.band_mm / sin + dy_mm.abs() * cos.abs() / sin + self.clearance_mm
    }
}

/// A stretch of the centre line something takes, [lo, hi] mm.
type Zone = (f64, f64);

/// What is decided once for a strip, before its lamellas are made.
#[derive(Debug, Clone)]
struct Layout<'a> {
    /// The A×B crossings.
    crossings: Vec<Crossing<'a>>,
    /// Where the strip ends on edge strips.
    edge_ends: Vec<EdgeEnd<'a>>,
    /// The end slots' sizes.
    end_slot: EndSlotSize,
    /// The lamella's end allowance, mm.
    allowance_mm: f64,
    /// The slots at them.
    slots: Slots,
    /// The round holes' sizes.
    holes: HoleSizes,
    /// Blocks, cuts and splice holes on the centre line.
    centre: CentreLine,
}

/// Signed angle (degrees) from direction `a` to direction `b` about `n`.
fn signed_angle_deg(a: glam::DVec3, b: glam::DVec3, n: glam::DVec3) -> f64 {
    a.cross(b).dot(n).atan2(a.dot(b)).to_degrees()
}

/// The parts of strip `i` (an A or B strip). `rotations`: each A×B node's
/// rotation from the flat state to the erected one (degrees, A → B, by
/// node id), when the flat state has been computed: its slots are swept
/// over that range instead of the profile's blanket tolerance. `lines`: the
/// strip's lamella lines for this profile, when already integrated (by the
/// check); otherwise, or when they are another strip's or another
/// profile's, they are integrated here.
///
/// The phases: the crossings; the slots (or node holes) at each; the node
/// zones they take on the centre line; splice cuts clear of the zones,
/// shear blocks between zones and splices, the splices' bolt holes; then
/// each lamella's features on its own line, cut into pieces.
pub fn strip_parts(
    net: &Network,
    an: &Analysis,
    profile: &Profile,
    i: usize,
    rotations: Option<&HashMap<usize, f64>>,
    lines: Option<StripLines>,
) -> Result<StripParts> {
    let strip = &an.strips[i];
    let fail = |(node, what): Refusal| Error::fabrication(&profile.source, &strip.id, node, what);
    let offsets = profile.lamella_offsets(strip.family);
    // The lamella offsets of either family, taken once.
    let dy_of = |family| -> Vec<f64> {
        profile
            .lamella_offsets(family)
            .iter()
            .map(|o| o.dy_mm)
            .collect()
    };
    let (dy_a, dy_b) = (dy_of(Family::A), dy_of(Family::B));
    let crossings = crossings(net, an, i, (&dy_a, &dy_b));
    if let Some(rot) = rotations {
        within_tolerance(&crossings, rot, profile.joint.rotation_tolerance_deg).map_err(fail)?;
    }
    let slots = slots(profile, strip.family, &offsets, &crossings, rotations).map_err(fail)?;
    let node_hole_mm = node_hole_mm(profile);
    let zones = node_zones(profile, strip, &crossings, &slots, node_hole_mm);
    let stretch = stretch(strip, &offsets);
    let edge_ends = edge_ends(net, an, i);
    let end_slot = EndSlotSize {
        band_mm: profile.section.height_mm,
        opening_mm: profile.section.thickness_mm + 2.0 * profile.joint.slot_clearance_mm,
        clearance_mm: profile.joint.slot_clearance_mm,
    };
    // The end slots' zones on the centre line (for the widest offset),
    // kept clear by splice cuts and shear blocks like the node zones.
    let dy_max = offsets.iter().map(|o| o.dy_mm.abs()).fold(0.0, f64::max);
    let end_zones: Vec<(f64, f64)> = edge_ends
        .iter()
        .map(|e| {
            let s = strip.nodes[e.k].station_mm;
            let r = end_slot.reach_mm(e.angle_deg, dy_max) * stretch;
            (s - r, s + r)
        })
        .collect();
    let cuts = splice_cuts(profile, strip, (&zones, &end_zones), stretch).map_err(fail)?;
    let blocks = block_stations(
        profile,
        strip,
        &crossings,
        (&zones, &end_zones),
        &cuts,
        stretch,
    )
    .map_err(fail)?;
    let splice_holes = splice_hole_stations(profile, &cuts).map_err(fail)?;
    let layout = Layout {
        crossings,
        edge_ends,
        end_slot,
        allowance_mm: profile.section.end_allowance_mm,
        slots,
        holes: HoleSizes {
            node_mm: node_hole_mm,
            block_mm: shear_block(profile).map(|b| b.bolt_diameter_mm + BOLT_HOLE_CLEARANCE_MM),
            splice_mm: profile
                .splice
                .as_ref()
                .map(|sp| sp.bolt_diameter_mm + BOLT_HOLE_CLEARANCE_MM),
        },
        centre: CentreLine {
            blocks,
            cuts,
            splice_holes,
        },
    };
    lamella_pieces(an, profile, i, &offsets, lines, &layout).map_err(fail)
}

/// The strip's A×B crossings (its nodes with edges left out), with the
/// angle seen from this strip and the crossing strip's lamella offsets
/// (`dy`: family A's, family B's).
fn crossings<'a>(
    net: &'a Network,
    an: &Analysis,
    i: usize,
    dy: (&'a [f64], &'a [f64]),
) -> Vec<Crossing<'a>> {
    let strip = &an.strips[i];
    let topo = &an.topology;
    let mut crossings: Vec<Crossing> = Vec::with_capacity(strip.nodes.len());
    crossings.extend(strip.nodes.iter().enumerate().filter_map(|(k, cn)| {
        let other = &net.curves[cn.crossing];
        if other.family == Family::Edge {
            return None;
        }
        let node = &topo.nodes[cn.node];
        let (mine, theirs) = if node.a == i {
            (node.tangent_a_world, node.tangent_b_world)
        } else {
            (node.tangent_b_world, node.tangent_a_world)
        };
        Some(Crossing {
            k,
            node_id: node.id,
            crossing_id: &other.id,
            angle_deg: signed_angle_deg(mine, theirs, node.normal_world),
            crossing_offsets_mm: if other.family == Family::A {
                dy.0
            } else {
                dy.1
            },
        })
    }));
    crossings
}

/// The strip's nodes on edge strips, with the crossing angle.
fn edge_ends<'a>(net: &'a Network, an: &Analysis, i: usize) -> Vec<EdgeEnd<'a>> {
    let topo = &an.topology;
    an.strips[i]
        .nodes
        .iter()
        .enumerate()
        .filter(|(_, cn)| net.curves[cn.crossing].family == Family::Edge)
        .map(|(k, cn)| EdgeEnd {
            k,
            node_id: topo.nodes[cn.node].id,
            edge_id: &net.curves[cn.crossing].id,
            angle_deg: topo.nodes[cn.node].angle_deg,
        })
        .collect()
}

/// Every crossing's joint turns, from the flat state to the erected one,
/// within the profile's rotation tolerance (degrees).
fn within_tolerance(
    crossings: &[Crossing],
    rotations: &HashMap<usize, f64>,
    tolerance_deg: f64,
) -> std::result::Result<(), Refusal> {
    for c in crossings {
        if let Some(r) = rotations.get(&c.node_id) {
            if r.abs() > tolerance_deg {
                return Err((
                    Some(c.node_id),
                    format!(
                        "the joint turns {:.2}° between the flat state and the erected one, past the profile's rotation tolerance {tolerance_deg}°",
                        r.abs()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The slots of every lamella at every crossing (interlocking joints; none
/// otherwise): each crossing's range of angles (from the flat state's
/// rotation where given, else the angle ± the tolerance), the slots swept
/// over it, and their depth, which must leave the lamella whole.
fn slots(
    profile: &Profile,
    family: Family,
    offsets: &[LamellaOffset],
    crossings: &[Crossing],
    rotations: Option<&HashMap<usize, f64>>,
) -> std::result::Result<Slots, Refusal> {
    let h = profile.section.height_mm;
    let t = profile.section.thickness_mm;
    let depth_mm = 0.5 * h + profile.joint.slot_clearance_mm;
    if profile.joint.system != JointSystem::Interlocking {
        return Ok(Slots {
            ranges_rad: Vec::new(),
            spans: vec![Vec::new(); offsets.len()],
            depth_mm,
        });
    }
    let tolerance = profile.joint.rotation_tolerance_deg;
    // The directed angle mine → theirs turns by the rotation on A strips
    // (A → B) and by its opposite on B strips.
    let turn_sign = if family == Family::A { 1.0 } else { -1.0 };
    let ranges_rad: Vec<(f64, f64)> = crossings
        .iter()
        .map(|c| match rotations.and_then(|r| r.get(&c.node_id)) {
            Some(&r) => range_between_rad(c.angle_deg - turn_sign * r, c.angle_deg),
            None => sweep_range_rad(c.angle_deg, tolerance),
        })
        .collect();
    // Each crossing's sweep (its ends' trigonometry), shared by the lamellas.
    let sweeps: Vec<SweepRange> = ranges_rad.iter().map(|&r| SweepRange::new(r)).collect();
    let spans = offsets
        .iter()
        .map(|o| {
            crossings
                .iter()
                .zip(&sweeps)
                .enumerate()
                .map(|(ci, (c, sweep))| {
                    (
                        ci,
                        node_slots_in(
                            t,
                            t,
                            o.dy_mm,
                            c.crossing_offsets_mm,
                            sweep,
                            profile.joint.slot_clearance_mm,
                        ),
                    )
                })
                .collect()
        })
        .collect();
    if !crossings.is_empty() && depth_mm >= h {
        return Err((
            Some(crossings[0].node_id),
            format!("slots {depth_mm:.2} mm deep would cut through the {h} mm lamella"),
        ));
    }
    Ok(Slots {
        ranges_rad,
        spans,
        depth_mm,
    })
}

/// The diameter of the hole at each node, mm: the stud's fastener plus
/// clearance, in two-level joints (interlocking joints have slots).
fn node_hole_mm(profile: &Profile) -> Option<f64> {
    (profile.joint.system != JointSystem::Interlocking)
        .then(|| profile.stud.as_ref().map(|s| s.fastener_diameter_mm))
        .flatten()
        .map(|d| d + BOLT_HOLE_CLEARANCE_MM)
}

/// Each crossing's zone on the centre line, [lo, hi] mm from the strip's
/// start: what sits at the node (the slots of every lamella, the washer's
/// arms, in two-level joints the gap or the node hole, whichever is wider).
fn node_zones(
    profile: &Profile,
    strip: &StripGeometry,
    crossings: &[Crossing],
    slots: &Slots,
    node_hole_mm: Option<f64>,
) -> Vec<(f64, f64)> {
    let interlocking = profile.joint.system == JointSystem::Interlocking;
    let zone = |ci: usize| -> (f64, f64) {
        let mut lo: f64 = 0.0;
        let mut hi: f64 = 0.0;
        for per_lamella in &slots.spans {
            for s in per_lamella.get(ci).map_or(&[][..], |x| &x.1[..]) {
                lo = lo.min(s.lo_mm);
                hi = hi.max(s.hi_mm);
            }
        }
        if let Some(w) = &profile.washer {
            lo = lo.min(-w.arm_length_mm);
            hi = hi.max(w.arm_length_mm);
        }
        if !interlocking {
            let half = 0.5 * profile.section.gap_mm.max(node_hole_mm.unwrap_or(0.0));
            lo = lo.min(-half);
            hi = hi.max(half);
        }
        (lo, hi)
    };
    (0..crossings.len())
        .map(|ci| {
            let s = strip.nodes[crossings[ci].k].station_mm;
            let (lo, hi) = zone(ci);
            (s + lo, s + hi)
        })
        .collect()
}

/// How much longer than the centre line a lamella line can be, per unit:
/// ds'/ds ≤ √((1 + |dy|·kg + |dz|·kn)² + ((|dy| + |dz|)·tg)²) at the
/// strip's largest |kg|, |kn|, |tg|. Lengths decided on the centre line
/// (stock pieces, block spacing) are divided by it so they hold on every
/// lamella.
fn stretch(strip: &StripGeometry, offsets: &[LamellaOffset]) -> f64 {
    let (dy_max, dz_max) = offsets.iter().fold((0.0f64, 0.0f64), |(a, b), o| {
        (a.max(o.dy_mm.abs()), b.max(o.dz_mm.abs()))
    });
    ((1.0 + dy_max * strip.max_abs_kg_per_mm + dz_max * strip.max_abs_kn_per_mm).powi(2)
        + ((dy_max + dz_max) * strip.max_abs_tg_per_mm).powi(2))
    .sqrt()
}

/// Splice cuts on the centre line, where a lamella is longer than the
/// stock; none when it fits. On the centre line a middle piece stretches
/// to at most stretch × its length and an end piece's allowance does not
/// stretch, so (stock − margins)/stretch bounds every piece on every
/// lamella line. The stock is the longest usable length of any size (a
/// lamella needs only one size it fits); a coil cut to any length never
/// splices. Cuts come from the stretches between node `zones`; a cut
/// whose plate would reach into an end slot (`end_zones`) is dropped.
fn splice_cuts(
    profile: &Profile,
    strip: &StripGeometry,
    (zones, end_zones): (&[Zone], &[Zone]),
    stretch: f64,
) -> std::result::Result<Vec<f64>, Refusal> {
    let allowance = profile.section.end_allowance_mm;
    let usable = profile
        .stock
        .longest_usable_mm(profile.cutting.edge_margin_mm, profile.section.height_mm)
        / stretch;
    let total = strip.length_mm + 2.0 * allowance;
    if total > usable {
        let Some(sp) = &profile.splice else {
            return Err((
                None,
                format!(
                    "a {total:.0} mm lamella is longer than the stock's usable {usable:.0} mm and the \
                     profile has no splice"
                ),
            ));
        };
        let need = 0.5 * sp.plate_length_mm + profile.joint.slot_clearance_mm;
        // The candidates between the node zones, less those whose plate
        // would reach into an end slot.
        let mut candidates = cut_candidates(zones, strip.length_mm, need);
        candidates.retain(|&c| end_zones.iter().all(|z| c <= z.0 - need || c >= z.1 + need));
        place_cuts(&candidates, strip.length_mm, allowance, usable).map_err(|at| {
            (
                None,
                format!(
                    "no room for a {:.0} mm splice plate within {usable:.0} mm of {:.0} mm: the node \
                     zones leave no stretch of {:.0} mm",
                    sp.plate_length_mm,
                    at.max(0.0),
                    2.0 * need
                ),
            )
        })
    } else {
        Ok(Vec::new())
    }
}

/// Candidate splice cuts, ascending: the middle of every stretch between
/// node `zones` on a line `length_mm` long that leaves room for the plate
/// (`need_mm` each side), and along long stretches every
/// [`CANDIDATE_STEP_MM`] where that room is kept.
fn cut_candidates(zones: &[(f64, f64)], length_mm: f64, need_mm: f64) -> Vec<f64> {
    let mut busy: Vec<(f64, f64)> = zones.to_vec();
    busy.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut free: Vec<(f64, f64)> = Vec::new();
    let mut from = 0.0f64;
    for &(lo, hi) in &busy {
        if lo > from {
            free.push((from, lo));
        }
        from = from.max(hi);
    }
    if length_mm > from {
        free.push((from, length_mm));
    }
    let mut candidates: Vec<f64> = Vec::new();
    for (lo, hi) in free {
        let (a, b) = (lo + need_mm, hi - need_mm);
        if a > b {
            continue;
        }
        let steps = ((b - a) / CANDIDATE_STEP_MM).ceil() as usize;
        candidates.push(0.5 * (a + b));
        for j in 0..=steps {
            candidates.push(a + (b - a) * j as f64 / steps.max(1) as f64);
        }
    }
    candidates.sort_by(f64::total_cmp);
    candidates.dedup();
    candidates
}

/// The cuts among `candidates` (ascending) that keep every piece of a line
/// `length_mm` long, plus `allowance_mm` at each end, within `usable_mm`.
/// Greedy forward: each piece as long as the stock allows, cut at the
/// farthest candidate within reach: the fewest pieces, and for each cut the
/// latest place it can be. Those cuts are kept (full stock lengths nest
/// best: the short rests pair up in lanes) unless the last piece is a stub
/// (below [`MIN_LAST_PIECE_FRACTION`] of the stock); then greedy backward
/// from the end gives the earliest place of each cut, and each goes to the
/// candidate nearest the middle of its range, so the pieces come out even.
/// Err(where a piece starts) when no candidate is within reach.
fn place_cuts(
    candidates: &[f64],
    length_mm: f64,
    allowance_mm: f64,
    usable_mm: f64,
) -> std::result::Result<Vec<f64>, f64> {
    let mut latest: Vec<f64> = Vec::new();
    let mut prev = -allowance_mm;
    while length_mm + allowance_mm - prev > usable_mm {
        let reach = prev + usable_mm;
        let Some(i) = candidates
            .iter()
            .rposition(|&c| c <= reach && c > prev + 1.0)
        else {
            return Err(prev);
        };
        latest.push(candidates[i]);
        prev = candidates[i];
    }
    let mut earliest: Vec<f64> = Vec::new();
    let mut next = length_mm + allowance_mm;
    for _ in 0..latest.len() {
        let reach = next - usable_mm;
        let Some(i) = candidates
            .iter()
            .position(|&c| c >= reach && c < next - 1.0)
        else {
            return Err(next - usable_mm);
        };
        earliest.push(candidates[i]);
        next = candidates[i];
    }
    earliest.reverse();
    let last_piece = length_mm + allowance_mm - latest.last().copied().unwrap_or(-allowance_mm);
    if last_piece >= MIN_LAST_PIECE_FRACTION * usable_mm {
        return Ok(latest);
    }
    let mut cuts = Vec::with_capacity(latest.len());
    let mut prev = -allowance_mm;
    for (k, (&lo, &hi)) in earliest.iter().zip(&latest).enumerate() {
        let hi = hi.min(prev + usable_mm);
        let mid = 0.5 * (lo + hi);
        let best = candidates
            .iter()
            .copied()
            .filter(|&c| c >= lo.min(hi) && c <= hi && c > prev + 1.0)
            .min_by(|a, b| (a - mid).abs().total_cmp(&(b - mid).abs()))
            .unwrap_or(latest[k]);
        cuts.push(best);
        prev = best;
    }
    Ok(cuts)
}

/// Most shear blocks one strip may need (counted from its intervals between
/// supports and the spacing before any is placed).
pub const MAX_SHEAR_BLOCKS_PER_STRIP: usize = 10_000;

/// The profile's shear blocks, where the strip is doubled.
fn shear_block(profile: &Profile) -> Option<&ShearBlock> {
    profile
        .shear_block
        .as_ref()
        .filter(|_| profile.section.per_strip == 2)
}

/// Shear block centres on the centre line (none without blocks): in every
/// interval between supports (the line's ends, every crossing, and every
/// splice, whose plate couples the pieces; blocks keep clear of it), no
/// farther apart than the spacing allows.
fn block_stations(
    profile: &Profile,
    strip: &StripGeometry,
    crossings: &[Crossing],
    (zones, end_zones): (&[Zone], &[Zone]),
    cuts: &[f64],
    stretch: f64,
) -> std::result::Result<Vec<f64>, Refusal> {
    let Some(b) = shear_block(profile) else {
        return Ok(Vec::new());
    };
    let t = profile.section.thickness_mm;
    let spacing = blocks::max_spacing_mm(b.max_spacing_mm, b.slenderness_limit, t) / stretch;
    let half = 0.5 * b.length_mm + b.clearance_mm;
    // (station, zone lo, zone hi, node id) of every support.
    // The line's ends, each as wide as an end slot there.
    let start_hi = end_zones
        .iter()
        .filter(|z| z.0 + z.1 < strip.length_mm)
        .map(|z| z.1)
        .fold(0.0, f64::max);
    let end_lo = end_zones
        .iter()
        .filter(|z| z.0 + z.1 >= strip.length_mm)
        .map(|z| z.0)
        .fold(strip.length_mm, f64::min);
    let mut supports: Vec<(f64, f64, f64, Option<usize>)> = vec![(0.0, 0.0, start_hi, None)];
    for (ci, c) in crossings.iter().enumerate() {
        let s = strip.nodes[c.k].station_mm;
        supports.push((s, zones[ci].0, zones[ci].1, Some(c.node_id)));
    }
    if let Some(sp) = &profile.splice {
        for &c in cuts {
            let half = 0.5 * sp.plate_length_mm;
            supports.push((c, c - half, c + half, None));
        }
    }
    supports.sort_by(|x, y| x.0.total_cmp(&y.0));
    supports.push((strip.length_mm, end_lo, strip.length_mm, None));
    let needed: f64 = supports
        .windows(2)
        .map(|w| ((w[1].0 - w[0].0) / spacing).ceil() - 1.0)
        .filter(|&n| n > 0.0)
        .sum();
    if needed > MAX_SHEAR_BLOCKS_PER_STRIP as f64 {
        return Err((
            None,
            format!(
                "shear blocks at most {spacing:.3e} mm apart (shear_block.max_spacing_mm, or \
                 shear_block.slenderness_limit × lamella.thickness_mm / √12) along {:.0} mm mean \
                 ~{needed:.1e} blocks; the limit is {MAX_SHEAR_BLOCKS_PER_STRIP} a strip",
                strip.length_mm
            ),
        ));
    }
    let mut stations = Vec::new();
    for w in supports.windows(2) {
        let (a, b2) = (w[0], w[1]);
        let iv = blocks::Interval {
            start_mm: a.0,
            end_mm: b2.0,
            free_lo_mm: a.2 + half,
            free_hi_mm: b2.1 - half,
        };
        let placed = blocks::place(iv, spacing, b.length_mm, 2.0 * b.clearance_mm)
            .map_err(|e| (a.3.or(b2.3), e))?;
        stations.extend(placed);
    }
    Ok(stations)
}

/// Splice bolt holes on the centre line: `bolts_per_side` pairs about each
/// cut, evenly over the plate; the innermost must keep clear of the cut.
fn splice_hole_stations(profile: &Profile, cuts: &[f64]) -> std::result::Result<Vec<f64>, Refusal> {
    let Some(sp) = &profile.splice else {
        return Ok(Vec::new());
    };
    if !cuts.is_empty() {
        let n = sp.bolts_per_side.max(1) as f64;
        let inner = 0.5 * sp.plate_length_mm * 0.5 / n;
        let radius = 0.5 * (sp.bolt_diameter_mm + BOLT_HOLE_CLEARANCE_MM);
        if inner <= radius + 1.0 {
            return Err((
                None,
                format!(
                    "a {} mm splice plate with {} bolts a side puts its inner holes {inner:.1} mm from \
                     the cut: they would cross it",
                    sp.plate_length_mm, sp.bolts_per_side
                ),
            ));
        }
    }
    let n = sp.bolts_per_side.max(1) as usize;
    let half = 0.5 * sp.plate_length_mm;
    Ok(cuts
        .iter()
        .flat_map(|&c| {
            (0..n).flat_map(move |j| {
                let d = half * (j as f64 + 0.5) / n as f64;
                [c - d, c + d]
            })
        })
        .collect())
}

/// Everything carried from the centre line to each lamella's own line
/// (`lines` when they are this strip's for these offsets, else integrated
/// here), and each lamella's features placed and cut into pieces.
fn lamella_pieces(
    an: &Analysis,
    profile: &Profile,
    i: usize,
    offsets: &[LamellaOffset],
    lines: Option<StripLines>,
    layout: &Layout,
) -> std::result::Result<StripParts, Refusal> {
    let strip = &an.strips[i];
    let smooth = &an.curves[i];
    let centre = &layout.centre;
    let mut out = StripParts {
        blocks: centre.blocks.len(),
        splice_plates: centre.cuts.len() * offsets.len(),
        ..StripParts::default()
    };
    let mut wanted: Vec<f64> = Vec::new();
    wanted.extend(&centre.blocks);
    wanted.extend(&centre.cuts);
    wanted.extend(&centre.splice_holes);
    let lines = match lines {
        Some(l) if l.are_of(i, offsets) => l,
        _ => StripLines::new(strip, smooth, offsets),
    };
    let on_lines = lines.stations(strip, smooth, &wanted);
    let edge = if strip.family == Family::A {
        SlotEdge::Top
    } else {
        SlotEdge::Bottom
    };
    let h = profile.section.height_mm;
    for (j, (o, (line, on_line))) in offsets
        .iter()
        .zip(lines.lines.iter().zip(on_lines))
        .enumerate()
    {
        let (block_line, rest) = on_line.split_at(centre.blocks.len());
        let (cut_line, hole_line) = rest.split_at(centre.cuts.len());
        let features = lamella_features(line, layout, j, edge, h, (block_line, hole_line));
        out.lamellas.extend(cut_into_pieces(
            &strip.id,
            o.number,
            line.length_mm,
            profile.section.end_allowance_mm,
            cut_line,
            h,
            features,
        )?);
    }
    Ok(out)
}

/// Lamella `j`'s features along its own `line` (x the line's station, y
/// across its height `h`): its slots at every crossing (from the node's
/// station on this line, opening to `edge`), then the node holes, the
/// shear blocks' and the splices' bolt holes (`stations`: blocks, splice
/// holes, on this line).
fn lamella_features(
    line: &LamellaLine,
    layout: &Layout,
    j: usize,
    edge: SlotEdge,
    h: f64,
    stations: (&[f64], &[f64]),
) -> Vec<Feature> {
    let (crossings, slots, holes) = (&layout.crossings, &layout.slots, &layout.holes);
    let spans = &slots.spans[j];
    let (block_line, hole_line) = stations;
    let slot_count: usize = spans.iter().map(|(_, s)| s.len()).sum();
    let node_holes = if holes.node_mm.is_some() {
        crossings.len()
    } else {
        0
    };
    let block_holes = if holes.block_mm.is_some() {
        block_line.len()
    } else {
        0
    };
    let splice_holes = if holes.splice_mm.is_some() {
        hole_line.len()
    } else {
        0
    };
    let mut features: Vec<Feature> =
        Vec::with_capacity(slot_count + node_holes + block_holes + splice_holes);
    let depth = slots.depth_mm;
    for (ci, spans) in spans {
        let c = &crossings[*ci];
        let node_line = line.nodes[c.k].station_mm;
        let (a0, a1) = slots.ranges_rad[*ci];
        for s in spans {
            features.push(Feature {
                kind: FeatureKind::Slot,
                hole_use: None,
                node: Some(c.node_id),
                crossing: Some(c.crossing_id.to_string()),
                center_part_mm: Point::new(
                    node_line + s.centre_mm(),
                    if edge == SlotEdge::Top {
                        h - 0.5 * depth
                    } else {
                        0.5 * depth
                    },
                ),
                width_mm: s.width_mm(),
                depth_mm: depth,
                edge: Some(edge),
                angle_range_deg: Some((a0.to_degrees(), a1.to_degrees())),
                station_mm: Some(node_line + s.centre_mm()),
            });
        }
    }
    let mut hole =
        |station: f64, d: f64, usage: HoleUse, node: Option<usize>, crossing: Option<String>| {
            features.push(Feature {
                kind: FeatureKind::Hole,
                hole_use: Some(usage),
                node,
                crossing,
                center_part_mm: Point::new(station, 0.5 * h),
                width_mm: d,
                depth_mm: 0.0,
                edge: None,
                angle_range_deg: None,
                station_mm: Some(station),
            });
        };
    if let Some(d) = holes.node_mm {
        for c in crossings {
            hole(
                line.nodes[c.k].station_mm,
                d,
                HoleUse::Node,
                Some(c.node_id),
                Some(c.crossing_id.to_string()),
            );
        }
    }
    if let Some(d) = holes.block_mm {
        for &s in block_line {
            hole(s, d, HoleUse::ShearBlock, None, None);
        }
    }
    if let Some(d) = holes.splice_mm {
        for &s in hole_line {
            hole(s, d, HoleUse::Splice, None, None);
        }
    }
    features.extend(end_slots(line, layout, h));
    features
}

/// The end slots of a lamella `line` at the strip's edge nodes: centred on
/// the node's station and on the band's height in the lamella (the
/// surface, y = h/2 − dz), `opening` across, reaching from the nearer end
/// of the lamella (with its allowance) to past the band's far edge. None
/// where the band clears the lamella's height.
fn end_slots(line: &LamellaLine, layout: &Layout, h: f64) -> Vec<Feature> {
    let size = layout.end_slot;
    let y = 0.5 * h - line.offset.dz_mm;
    let half = 0.5 * size.opening_mm;
    if y + half <= 0.0 || y - half >= h {
        return Vec::new();
    }
    layout
        .edge_ends
        .iter()
        .map(|e| {
            let s = line.nodes[e.k].station_mm;
            let reach = size.reach_mm(e.angle_deg, line.offset.dy_mm);
            let depth = if s < 0.5 * line.length_mm {
                s + layout.allowance_mm + reach
            } else {
                line.length_mm + layout.allowance_mm - (s - reach)
            };
            Feature {
                kind: FeatureKind::Slot,
                hole_use: None,
                node: Some(e.node_id),
                crossing: Some(e.edge_id.to_string()),
                center_part_mm: Point::new(s, y),
                width_mm: size.opening_mm,
                depth_mm: depth,
                edge: Some(SlotEdge::End),
                angle_range_deg: None,
                station_mm: Some(s),
            }
        })
        .collect()
}

/// A lamella `line_length_mm` long on its own line, plus `allowance_mm` at
/// each end, cut at `cuts` (its own line's stations) into pieces
/// [−allowance, cut₁], [cut₁, cut₂], …, [cutₙ, length + allowance]: each
/// feature goes to the piece [start, end) that holds its station (none
/// when outside them all), in the order made, moved into the piece's
/// frame. Ids `A05-1`, or `A05-1.2` for the second of several pieces.
fn cut_into_pieces(
    strip: &str,
    lamella: u32,
    line_length_mm: f64,
    allowance_mm: f64,
    cuts: &[f64],
    h: f64,
    features: Vec<Feature>,
) -> std::result::Result<Vec<Part>, Refusal> {
    let mut bounds = vec![-allowance_mm];
    bounds.extend_from_slice(cuts);
    bounds.push(line_length_mm + allowance_mm);
    let pieces = bounds.len() - 1;
    let piece_of = |f: &Feature| {
        let s = f.station_mm.unwrap_or(f64::NAN);
        let p = bounds.partition_point(|&b| b <= s);
        (1..=pieces).contains(&p).then(|| p - 1)
    };
    let mut per_piece: Vec<Vec<Feature>> = {
        let mut counts = vec![0usize; pieces];
        for f in &features {
            if let Some(p) = piece_of(f) {
                counts[p] += 1;
            }
        }
        counts.into_iter().map(Vec::with_capacity).collect()
    };
    for mut f in features {
        if let Some(p) = piece_of(&f) {
            f.center_part_mm.x -= bounds[p];
            per_piece[p].push(f);
        }
    }
    per_piece
        .into_iter()
        .enumerate()
        .map(|(p, mine)| {
            let (start, end) = (bounds[p], bounds[p + 1]);
            let id = if pieces == 1 {
                format!("{strip}-{lamella}")
            } else {
                format!("{strip}-{lamella}.{}", p + 1)
            };
            lamella_part(id, strip, lamella, start, end - start, h, mine)
        })
        .collect()
}

/// Where a slot from the top or bottom edge runs into an end slot (x
/// within `min_web`, and the heights overlapping), the two cuts would cut
/// off the corner between them: the end slot takes the slot in and becomes
/// a rebate from that edge over both (its reach to the slot's far side,
/// its height from the slot's root or its own far side, whichever is
/// farther, to the edge), repeated until no other slot runs into it.
fn merge_end_slots(features: &mut [Feature], length_mm: f64, h: f64, min_web: f64) {
    let notches: Vec<(f64, f64, f64, f64, SlotEdge)> = features
        .iter()
        .filter(|f| f.kind == FeatureKind::Slot && f.edge != Some(SlotEdge::End))
        .filter_map(|f| {
            let (x0, x1) = (
                f.center_part_mm.x - 0.5 * f.width_mm,
                f.center_part_mm.x + 0.5 * f.width_mm,
            );
            match f.edge {
                Some(SlotEdge::Top) => Some((x0, x1, h - f.depth_mm, h, SlotEdge::Top)),
                Some(SlotEdge::Bottom) => Some((x0, x1, 0.0, f.depth_mm, SlotEdge::Bottom)),
                _ => None,
            }
        })
        .collect();
    for e in features
        .iter_mut()
        .filter(|f| f.kind == FeatureKind::Slot && f.edge == Some(SlotEdge::End))
    {
        let at_start = e.center_part_mm.x < 0.5 * length_mm;
        loop {
            let (y0, y1) = (
                e.center_part_mm.y - 0.5 * e.width_mm,
                e.center_part_mm.y + 0.5 * e.width_mm,
            );
            let reach = if at_start {
                e.depth_mm
            } else {
                length_mm - e.depth_mm
            };
            let hit = notches.iter().find(|n| {
                let into = if at_start {
                    n.0 < reach + min_web && n.1 > reach
                } else {
                    n.1 > reach - min_web && n.0 < reach
                };
                into && n.2 < y1 && n.3 > y0
            });
            let Some(&(x0, x1, n0, n1, edge)) = hit else {
                break;
            };
            let (y0, y1) = if edge == SlotEdge::Top {
                (y0.min(n0), h)
            } else {
                (0.0, y1.max(n1))
            };
            e.depth_mm = if at_start { x1 } else { length_mm - x0 };
            e.center_part_mm.y = 0.5 * (y0 + y1);
            e.width_mm = y1 - y0;
        }
    }
}

/// One lamella piece: the rectangle length × h with its slots notched from
/// their edges and its end slots from its ends (its round holes are its
/// `hole` features alone); features sorted by x. Err (node, what) when a
/// slot runs past an end or into an end slot, or two slots leave less than
/// 1 mm of material between them.
fn lamella_part(
    id: String,
    strip: &str,
    lamella: u32,
    station_start_mm: f64,
    length_mm: f64,
    h: f64,
    mut features: Vec<Feature>,
) -> std::result::Result<Part, (Option<usize>, String)> {
    features.sort_by(|a, b| a.center_part_mm.x.total_cmp(&b.center_part_mm.x));
    // Minimum material between two notches on one edge, mm (a laser keeps
    // a 1 mm web whole; thinner ones burn through).
    let min_web = 1.0;
    merge_end_slots(&mut features, length_mm, h, min_web);
    // The notches from an edge, less those an end slot took in.
    let taken_in = |f: &Feature| {
        features.iter().any(|e| {
            e.edge == Some(SlotEdge::End)
                && if e.center_part_mm.x < 0.5 * length_mm {
                    f.center_part_mm.x + 0.5 * f.width_mm <= e.depth_mm
                } else {
                    f.center_part_mm.x - 0.5 * f.width_mm >= length_mm - e.depth_mm
                }
        })
    };
    let notches = |edge: SlotEdge| {
        features.iter().filter(move |f| {
            f.kind == FeatureKind::Slot
                && f.edge == Some(edge)
                && (edge == SlotEdge::End || !taken_in(f))
        })
    };
    let slots = features
        .iter()
        .filter(|f| f.kind == FeatureKind::Slot && f.edge.is_some())
        .count();
    // End slots: (x of the closed end, y0, y1) at the start and the end.
    let end_slot = |at_start: bool| {
        notches(SlotEdge::End)
            .find(|f| (f.center_part_mm.x < 0.5 * length_mm) == at_start)
            .map(|f| {
                let x = if at_start {
                    f.depth_mm
                } else {
                    length_mm - f.depth_mm
                };
                let (y0, y1) = (
                    f.center_part_mm.y - 0.5 * f.width_mm,
                    f.center_part_mm.y + 0.5 * f.width_mm,
                );
                (x, y0, y1, f.node)
            })
    };
    let (start, end) = (end_slot(true), end_slot(false));
    for (x, _, _, node) in start.iter().chain(&end) {
        if *x <= 0.0 || *x >= length_mm || start.zip(end).is_some_and(|(a, b)| a.0 >= b.0) {
            return Err((
                *node,
                format!("lamella {id}: its {length_mm:.1} mm are too short for its end slots"),
            ));
        }
    }
    let mut outline = Vec::with_capacity(13 + 4 * slots);
    match start {
        Some((x, y0, _, _)) if y0 <= 0.0 => outline.push(Point::new(x, 0.0)),
        _ => outline.push(Point::new(0.0, 0.0)),
    }
    for edge in [SlotEdge::Bottom, SlotEdge::Top] {
        let mut last_end = 0.0;
        for f in notches(edge) {
            let (x0, x1) = (
                f.center_part_mm.x - 0.5 * f.width_mm,
                f.center_part_mm.x + 0.5 * f.width_mm,
            );
            if x0 <= 0.0 || x1 >= length_mm {
                return Err((
                    f.node,
                    format!(
                        "lamella {id}: a {:.2} mm slot at {:.1} mm runs past the lamella's end",
                        f.width_mm, f.center_part_mm.x
                    ),
                ));
            }
            if x0 - last_end < min_web && last_end > 0.0 {
                return Err((
                    f.node,
                    format!(
                        "lamella {id}: slots leave {:.2} mm of material between them at {:.1} mm",
                        x0 - last_end,
                        x0
                    ),
                ));
            }
            // Into an end slot's reach and height.
            let (y0, y1) = if edge == SlotEdge::Top {
                (h - f.depth_mm, h)
            } else {
                (0.0, f.depth_mm)
            };
            let into = |e: Option<(f64, f64, f64, Option<usize>)>, at_start: bool| {
                e.is_some_and(|(x, e0, e1, _)| {
                    let reach = if at_start {
                        x0 < x + min_web
                    } else {
                        x1 > x - min_web
                    };
                    reach && y0 < e1 && y1 > e0
                })
            };
            if into(start, true) || into(end, false) {
                return Err((
                    f.node,
                    format!(
                        "lamella {id}: a {:.2} mm slot at {:.1} mm runs into the end slot of an edge strip",
                        f.width_mm, f.center_part_mm.x
                    ),
                ));
            }
            last_end = x1;
        }
    }
    for f in notches(SlotEdge::Bottom) {
        let (x0, x1) = (
            f.center_part_mm.x - 0.5 * f.width_mm,
            f.center_part_mm.x + 0.5 * f.width_mm,
        );
        outline.extend([
            Point::new(x0, 0.0),
            Point::new(x0, f.depth_mm),
            Point::new(x1, f.depth_mm),
            Point::new(x1, 0.0),
        ]);
    }
    match end {
        Some((x, y0, y1, _)) => {
            if y0 > 0.0 {
                outline.extend([
                    Point::new(length_mm, 0.0),
                    Point::new(length_mm, y0),
                    Point::new(x, y0),
                ]);
            } else {
                outline.push(Point::new(x, 0.0));
            }
            if y1 < h {
                outline.extend([
                    Point::new(x, y1),
                    Point::new(length_mm, y1),
                    Point::new(length_mm, h),
                ]);
            } else {
                outline.push(Point::new(x, h));
            }
        }
        None => outline.extend([Point::new(length_mm, 0.0), Point::new(length_mm, h)]),
    }
    for f in notches(SlotEdge::Top).rev() {
        let (x0, x1) = (
            f.center_part_mm.x - 0.5 * f.width_mm,
            f.center_part_mm.x + 0.5 * f.width_mm,
        );
        outline.extend([
            Point::new(x1, h),
            Point::new(x1, h - f.depth_mm),
            Point::new(x0, h - f.depth_mm),
            Point::new(x0, h),
        ]);
    }
    match start {
        Some((x, y0, y1, _)) => {
            if y1 < h {
                outline.extend([Point::new(0.0, h), Point::new(0.0, y1), Point::new(x, y1)]);
            } else {
                outline.push(Point::new(x, h));
            }
            if y0 > 0.0 {
                outline.extend([Point::new(x, y0), Point::new(0.0, y0)]);
            }
        }
        None => outline.push(Point::new(0.0, h)),
    }
    Ok(Part {
        id,
        kind: PartKind::Lamella,
        strip: Some(strip.to_string()),
        lamella: Some(lamella),
        count: 1,
        length_mm,
        height_mm: h,
        station_start_mm: Some(station_start_mm),
        outline_part_mm: outline,
        holes_part_mm: Vec::new(),
        engraving: Vec::new(),
        features,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::{analyze, AnalysisOptions};
    use crate::network::{RawCurve, RawNetwork, Unit};
    use crate::profile::{
        Cutting, Grain, Joint, Material, RawProfile, RawStock, Section, Splice, StockKind,
    };
    use glam::DVec3;
    use std::path::{Path, PathBuf};

    /// A straight A strip along x from the origin, 1000 mm, crossed at
    /// x = 300 and x = 700 by straight B strips along y from y = −100 to
    /// y = 100; every normal +z. Strips 0 (A0), 1 (B0), 2 (B1).
    fn straight_grid() -> (Network, Analysis) {
        let line = |id: &str, family, p0: DVec3, p1: DVec3, n: usize| {
            let points: Vec<DVec3> = (0..=n).map(|k| p0.lerp(p1, k as f64 / n as f64)).collect();
            RawCurve {
                id: id.into(),
                family,
                normals: Some(vec![DVec3::Z; points.len()]),
                points,
            }
        };
        let raw = RawNetwork {
            name: "straight".into(),
            unit: Unit::Mm,
            tolerance: None,
            precision: None,
            curves: vec![
                line(
                    "A0",
                    Family::A,
                    DVec3::ZERO,
                    DVec3::new(1000.0, 0.0, 0.0),
                    20,
                ),
                line(
                    "B0",
                    Family::B,
                    DVec3::new(300.0, -100.0, 0.0),
                    DVec3::new(300.0, 100.0, 0.0),
                    8,
                ),
                line(
                    "B1",
                    Family::B,
                    DVec3::new(700.0, -100.0, 0.0),
                    DVec3::new(700.0, 100.0, 0.0),
                    8,
                ),
            ],
        };
        let net = Network::new(raw, Path::new("straight.yaml")).expect("network");
        let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analysis");
        (net, an)
    }

    /// Steel lamellas 1.5 × 50 mm, one per strip, interlocking with a
    /// 0.3 mm slot clearance swept ±30°, 25 mm end allowance; sheets
    /// `stock_length_mm` × 1500 with a 10 mm edge margin; no hardware but
    /// the `splice`.
    fn steel(stock_length_mm: f64, splice: Option<Splice>) -> Profile {
        Profile::new(RawProfile {
            name: "steel".into(),
            description: String::new(),
            source: PathBuf::new(),
            material: Material {
                name: "S355".into(),
                youngs_modulus_mpa: 210_000.0,
                shear_modulus_mpa: 81_000.0,
                characteristic_strength_mpa: 355.0,
                partial_factor: 1.0,
                modification_factor: 1.0,
                density_kg_per_m3: 7850.0,
                grain: Grain::None,
            },
            section: Section {
                thickness_mm: 1.5,
                height_mm: 50.0,
                per_strip: 1,
                gap_mm: 0.0,
                end_allowance_mm: 25.0,
            },
            joint: Joint {
                system: JointSystem::Interlocking,
                slot_clearance_mm: 0.3,
                rotation_tolerance_deg: 30.0,
                level_offset_mm: 0.0,
            },
            node_bolt: None,
            washer: None,
            shear_block: None,
            stud: None,
            splice,
            hardware: Default::default(),
            stock: RawStock {
                kind: StockKind::Sheet,
                length_mm: Some(stock_length_mm),
                width_mm: Some(1500.0),
                price_per_unit: None,
                currency: None,
                max_count: None,
                sizes: None,
                price_per_m: None,
                length_step_mm: None,
            },
            cutting: Cutting {
                kerf_mm: 0.2,
                part_spacing_mm: 3.0,
                edge_margin_mm: 10.0,
                allowed_rotations_deg: vec![0, 180],
            },
            check: Default::default(),
            edge_joint: Default::default(),
            bracing: None,
            stocks: Vec::new(),
        })
        .expect("a valid profile")
    }

    // The slot through a 1.5 mm lamella crossed at 90° ± 30° by another
    // 1.5 mm one, both on their strips' curves (no offsets): the plates
    // overlap over w(φ) = (1.5 + 1.5·|cos φ|) / |sin φ| centred on the node,
    // widest at the ends of the sweep, φ = 60° and 120°:
    // w = (1.5 + 0.75) / (√3/2) = 4.5/√3 = 2.598076 mm; with the 0.3 mm
    // clearance the slot is 2.898076 mm wide, 1.449038 mm either side of
    // the node. Its depth is half the height plus the clearance,
    // 25 + 0.3 = 25.3 mm, so its centre sits 12.65 mm from its edge.
    const SLOT_WIDTH_MM: f64 = 2.898_076_211_353_316;
    const SLOT_DEPTH_MM: f64 = 25.3;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-6
    }

    #[test]
    fn the_hand_numbers_hold() {
        assert!((4.5 / 3f64.sqrt() + 0.3 - SLOT_WIDTH_MM).abs() < 1e-12);
    }

    #[test]
    fn a_straight_strip_with_two_nodes_is_one_piece_slotted_at_its_nodes() {
        let (net, an) = straight_grid();
        let out = strip_parts(&net, &an, &steel(3000.0, None), 0, None, None).expect("parts");
        assert_eq!((out.blocks, out.splice_plates), (0, 0));
        assert_eq!(out.lamellas.len(), 1);
        let p = &out.lamellas[0];
        assert_eq!(p.id, "A0-1");
        assert_eq!((p.strip.as_deref(), p.lamella), (Some("A0"), Some(1)));
        // 1000 mm of strip plus 25 mm at either end; x = 0 at station −25.
        assert!(close(p.length_mm, 1050.0), "{}", p.length_mm);
        assert_eq!(p.height_mm, 50.0);
        assert_eq!(p.station_start_mm, Some(-25.0));
        // Two slots from the top edge (family A), at the node stations
        // 300 and 700, i.e. x = 325 and 725 in the part.
        assert_eq!(p.features.len(), 2);
        for (f, (station, x, crossing)) in p
            .features
            .iter()
            .zip([(300.0, 325.0, "B0"), (700.0, 725.0, "B1")])
        {
            assert_eq!(f.kind, FeatureKind::Slot);
            assert_eq!(f.edge, Some(SlotEdge::Top));
            assert_eq!(f.crossing.as_deref(), Some(crossing));
            assert!(close(f.station_mm.expect("station"), station), "{f:?}");
            assert!(close(f.center_part_mm.x, x), "{f:?}");
            // Centre 12.65 mm below the top edge: 50 − 12.65 = 37.35.
            assert!(close(f.center_part_mm.y, 37.35), "{f:?}");
            assert!(close(f.width_mm, SLOT_WIDTH_MM), "{f:?}");
            assert!(close(f.depth_mm, SLOT_DEPTH_MM), "{f:?}");
            // Swept over 90° ± 30°, whichever way round B lies from A.
            let (a0, a1) = f.angle_range_deg.expect("range");
            assert!(close(a0.abs().min(a1.abs()), 60.0), "{a0} {a1}");
            assert!(close(a0.abs().max(a1.abs()), 120.0), "{a0} {a1}");
        }
        // The outline: the rectangle, the two notches from the top, from
        // the right: 725 ± 1.449038 and 325 ± 1.449038, down to
        // 50 − 25.3 = 24.7.
        let o = &p.outline_part_mm;
        assert_eq!(o.len(), 12);
        let want = [
            (0.0, 0.0),
            (1050.0, 0.0),
            (1050.0, 50.0),
            (726.449038, 50.0),
            (726.449038, 24.7),
            (723.550962, 24.7),
            (723.550962, 50.0),
            (326.449038, 50.0),
            (326.449038, 24.7),
            (323.550962, 24.7),
            (323.550962, 50.0),
            (0.0, 50.0),
        ];
        for (q, (x, y)) in o.iter().zip(want) {
            assert!(
                (q.x - x).abs() < 1e-5 && close(q.y, y),
                "{q:?} for ({x}, {y})"
            );
        }
    }

    #[test]
    fn a_crossing_strip_is_slotted_from_the_bottom() {
        let (net, an) = straight_grid();
        let out = strip_parts(&net, &an, &steel(3000.0, None), 1, None, None).expect("parts");
        assert_eq!(out.lamellas.len(), 1);
        let p = &out.lamellas[0];
        // 200 mm plus 2 × 25; its node, A0, at station 100: x = 125.
        assert_eq!(p.id, "B0-1");
        assert!(close(p.length_mm, 250.0), "{}", p.length_mm);
        assert_eq!(p.features.len(), 1);
        let f = &p.features[0];
        assert_eq!(f.edge, Some(SlotEdge::Bottom));
        assert_eq!(f.crossing.as_deref(), Some("A0"));
        assert!(close(f.center_part_mm.x, 125.0), "{f:?}");
        // Centre 12.65 mm above the bottom edge.
        assert!(close(f.center_part_mm.y, 12.65), "{f:?}");
        assert!(close(f.width_mm, SLOT_WIDTH_MM), "{f:?}");
    }

    #[test]
    fn a_strip_longer_than_the_stock_is_spliced_clear_of_its_nodes() {
        // Sheets 700 mm long, 680 mm usable inside the 10 mm margins; the
        // straight strip does not stretch its lamella, so a piece is at
        // most 680 mm: 1050 mm needs one cut.
        let splice = Splice {
            plate_length_mm: 160.0,
            bolts_per_side: 2,
            bolt_diameter_mm: 6.0,
        };
        let (net, an) = straight_grid();
        let out =
            strip_parts(&net, &an, &steel(700.0, Some(splice)), 0, None, None).expect("parts");
        assert_eq!((out.blocks, out.splice_plates), (0, 1));
        assert_eq!(out.lamellas.len(), 2);
        // A cut keeps half a plate plus the slot clearance, 80.3 mm, from
        // the node zones (the slots, 1.449038 mm either side of 300 and
        // 700). The first piece reaches to station −25 + 680 = 655; the
        // last candidate before it ends the stretch between the nodes:
        // 700 − 1.449038 − 80.3 = 618.250962. The rest, 1025 − 618.250962
        // = 406.749038 mm, fits the stock and is no stub (above
        // 0.2 × 680 = 136 mm), so the cut stays there.
        let cut = 618.250_962;
        let (p1, p2) = (&out.lamellas[0], &out.lamellas[1]);
        assert_eq!((p1.id.as_str(), p2.id.as_str()), ("A0-1.1", "A0-1.2"));
        assert!(
            (p1.length_mm - (cut + 25.0)).abs() < 1e-5,
            "{}",
            p1.length_mm
        );
        assert!(
            (p2.length_mm - (1025.0 - cut)).abs() < 1e-5,
            "{}",
            p2.length_mm
        );
        assert_eq!(p1.station_start_mm, Some(-25.0));
        assert!((p2.station_start_mm.expect("start") - cut).abs() < 1e-5);
        // Two bolts a side, at 80 × (j + ½)/2 = 20 and 60 mm from the cut,
        // holes 6 + 1 = 7 mm across, on the lamella's middle (y = 25).
        let x = |p: &Part| -> Vec<(FeatureKind, f64)> {
            p.features
                .iter()
                .map(|f| (f.kind, f.center_part_mm.x))
                .collect()
        };
        let want1 = [
            (FeatureKind::Slot, 325.0),
            (FeatureKind::Hole, cut - 60.0 + 25.0),
            (FeatureKind::Hole, cut - 20.0 + 25.0),
        ];
        let want2 = [
            (FeatureKind::Hole, 20.0),
            (FeatureKind::Hole, 60.0),
            (FeatureKind::Slot, 700.0 - cut),
        ];
        for (p, want) in [(p1, &want1), (p2, &want2)] {
            let got = x(p);
            assert_eq!(got.len(), want.len(), "{got:?}");
            for ((k, gx), (wk, wx)) in got.iter().zip(want.iter()) {
                assert_eq!(k, wk);
                assert!((gx - wx).abs() < 1e-5, "{got:?} vs {want:?}");
            }
            for f in p.features.iter().filter(|f| f.kind == FeatureKind::Hole) {
                assert_eq!(f.hole_use, Some(HoleUse::Splice));
                assert_eq!(f.width_mm, 7.0);
                assert_eq!(f.center_part_mm.y, 25.0);
            }
        }
    }

    #[test]
    fn a_strip_longer_than_the_stock_without_a_splice_is_refused() {
        let (net, an) = straight_grid();
        let e = strip_parts(&net, &an, &steel(700.0, None), 0, None, None)
            .expect_err("too long")
            .to_string();
        // 1000 + 2 × 25 = 1050 mm against 700 − 2 × 10 = 680 mm.
        assert!(
            e.contains("a 1050 mm lamella is longer than the stock's usable 680 mm"),
            "{e}"
        );
    }

    #[test]
    fn cut_candidates_are_the_stretches_between_zones_less_the_plate() {
        // Zones [90, 110] and [490, 510] on a 600 mm line, 50 mm kept
        // either side: the stretches [0, 90], [110, 490], [510, 600] leave
        // [50, 40] (none), [160, 440] and [560, 550] (none). The middle,
        // 300, and the ends split into ⌈280/50⌉ = 6 steps of 46.67 mm; the
        // third step is the middle again, kept once.
        let c = cut_candidates(&[(490.0, 510.0), (90.0, 110.0)], 600.0, 50.0);
        let step = 280.0 / 6.0;
        let want: Vec<f64> = (0..=6).map(|j| 160.0 + step * j as f64).collect();
        assert_eq!(c.len(), 7, "{c:?}");
        for (g, w) in c.iter().zip(&want) {
            assert!((g - w).abs() < 1e-9, "{c:?}");
        }
    }

    #[test]
    fn cuts_are_even_when_the_last_piece_would_be_a_stub() {
        // A 1000 mm line, no allowance, 600 mm pieces, a cut possible
        // every 10 mm. Greedy forward cuts at 600 and leaves 400 mm: kept
        // (above 0.2 × 600 = 120). At 580 mm pieces on a 600 mm line the
        // rest would be 20 mm: the cut goes to the candidate nearest the
        // middle of [20, 580], 300.
        let candidates: Vec<f64> = (1..100).map(|k| 10.0 * k as f64).collect();
        assert_eq!(place_cuts(&candidates, 1000.0, 0.0, 600.0), Ok(vec![600.0]));
        assert_eq!(place_cuts(&candidates, 600.0, 0.0, 580.0), Ok(vec![300.0]));
        // Nothing within reach: the piece starting at 0 cannot end.
        assert_eq!(place_cuts(&[700.0], 1000.0, 0.0, 600.0), Err(0.0));
    }
}
