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
use crate::analysis::lines::StripLines;
use crate::analysis::Analysis;
use crate::error::{Error, Result};
use crate::network::{Family, Network};
use crate::profile::{JointSystem, Profile};
use kurbo::Point;

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
pub fn strip_parts(
    net: &Network,
    an: &Analysis,
    profile: &Profile,
    i: usize,
    rotations: Option<&std::collections::HashMap<usize, f64>>,
    lines: Option<StripLines>,
) -> Result<StripParts> {
    let strip = &an.strips[i];
    let smooth = &an.curves[i];
    let topo = &an.topology;
    let sec = &profile.section;
    let (t, h) = (sec.thickness_mm, sec.height_mm);
    let allowance = sec.end_allowance_mm;
    let fail = |node: Option<usize>, what: String| {
        Error::fabrication(&profile.source, &strip.id, node, what)
    };
    let offsets = profile.lamella_offsets(strip.family);
    let interlocking = profile.joint.system == JointSystem::Interlocking;

    // The lamella offsets of either family, taken once.
    let dy_of = |family| -> Vec<f64> {
        profile
            .lamella_offsets(family)
            .iter()
            .map(|o| o.dy_mm)
            .collect()
    };
    let (dy_a, dy_b) = (dy_of(Family::A), dy_of(Family::B));
    // The A×B crossings, with the angle seen from this strip.
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
                &dy_a
            } else {
                &dy_b
            },
        })
    }));

    // Slots of every lamella at every crossing (relative to the node's
    // station on that lamella's line).
    let tolerance = profile.joint.rotation_tolerance_deg;
    // The directed angle mine → theirs turns by the rotation on A strips
    // (A → B) and by its opposite on B strips.
    let turn_sign = if strip.family == Family::A { 1.0 } else { -1.0 };
    if let Some(rot) = rotations {
        for c in &crossings {
            if let Some(r) = rot.get(&c.node_id) {
                if r.abs() > tolerance {
                    return Err(fail(
                        Some(c.node_id),
                        format!(
                            "the joint turns {:.2}° between the flat state and the erected one, past the profile's rotation tolerance {tolerance}°",
                            r.abs()
                        ),
                    ));
                }
            }
        }
    }
    let range_of = |c: &Crossing| match rotations.and_then(|r| r.get(&c.node_id)) {
        Some(&r) => range_between_rad(c.angle_deg - turn_sign * r, c.angle_deg),
        None => sweep_range_rad(c.angle_deg, tolerance),
    };
    // Each crossing's sweep (its ends' trigonometry), shared by the lamellas.
    let sweeps: Vec<SweepRange> = if interlocking {
        crossings
            .iter()
            .map(|c| SweepRange::new(range_of(c)))
            .collect()
    } else {
        Vec::new()
    };
    let slots: Vec<Vec<(usize, Vec<SlotSpan>)>> = offsets
        .iter()
        .map(|o| {
            if !interlocking {
                return Vec::new();
            }
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
    let slot_depth = 0.5 * h + profile.joint.slot_clearance_mm;
    if interlocking && !crossings.is_empty() && slot_depth >= h {
        return Err(fail(
            Some(crossings[0].node_id),
            format!("slots {slot_depth:.2} mm deep would cut through the {h} mm lamella"),
        ));
    }
    let node_hole_mm = (!interlocking)
        .then(|| profile.stud.as_ref().map(|s| s.fastener_diameter_mm))
        .flatten()
        .map(|d| d + BOLT_HOLE_CLEARANCE_MM);

    // Node zones on the centre line: what sits at each crossing.
    let zone = |ci: usize| -> (f64, f64) {
        let mut lo: f64 = 0.0;
        let mut hi: f64 = 0.0;
        for per_lamella in &slots {
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
            let half = 0.5 * sec.gap_mm.max(node_hole_mm.unwrap_or(0.0));
            lo = lo.min(-half);
            hi = hi.max(half);
        }
        (lo, hi)
    };
    let zones: Vec<(f64, f64)> = (0..crossings.len())
        .map(|ci| {
            let s = strip.nodes[crossings[ci].k].station_mm;
            let (lo, hi) = zone(ci);
            (s + lo, s + hi)
        })
        .collect();

    // How much longer than the centre line a lamella line can be, per unit:
    // ds'/ds ≤ √((1 + |dy|·kg + |dz|·kn)² + ((|dy| + |dz|)·tg)²) at the
    // strip's largest |kg|, |kn|, |tg|. Lengths decided on the centre line
    // (stock pieces, block spacing) are divided by it so they hold on every
    // lamella.
    let (dy_max, dz_max) = offsets.iter().fold((0.0f64, 0.0f64), |(a, b), o| {
        (a.max(o.dy_mm.abs()), b.max(o.dz_mm.abs()))
    });
    let stretch = ((1.0 + dy_max * strip.max_abs_kg_per_mm + dz_max * strip.max_abs_kn_per_mm)
        .powi(2)
        + ((dy_max + dz_max) * strip.max_abs_tg_per_mm).powi(2))
    .sqrt();

    // Splices first (where a lamella is longer than the stock), clear of
    // the node zones; then the shear blocks around them.
    // On the centre line: a middle piece stretches to at most
    // stretch × its length, an end piece's allowance does not stretch, so
    // (stock − margins)/stretch bounds every piece on every lamella line.
    // The stock is the longest usable length of any size (a lamella needs
    // only one size it fits); a coil cut to any length never splices.
    let usable = profile
        .stock
        .longest_usable_mm(profile.cutting.edge_margin_mm, sec.height_mm)
        / stretch;
    let total = strip.length_mm + 2.0 * allowance;
    let mut cuts: Vec<f64> = Vec::new();
    if total > usable {
        let Some(sp) = &profile.splice else {
            return Err(fail(
                None,
                format!(
                    "a {total:.0} mm lamella is longer than the stock's usable {usable:.0} mm and the \
                     profile has no splice"
                ),
            ));
        };
        // Candidate cuts: the middle of every stretch between node zones
        // that leaves room for the plate (`need` each side), and along long
        // stretches every `CANDIDATE_STEP_MM` where that room is kept.
        let need = 0.5 * sp.plate_length_mm + profile.joint.slot_clearance_mm;
        let mut busy: Vec<(f64, f64)> = zones.clone();
        busy.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut free: Vec<(f64, f64)> = Vec::new();
        let mut from = 0.0f64;
        for &(lo, hi) in &busy {
            if lo > from {
                free.push((from, lo));
            }
            from = from.max(hi);
        }
        if strip.length_mm > from {
            free.push((from, strip.length_mm));
        }
        let mut candidates: Vec<f64> = Vec::new();
        for (lo, hi) in free {
            let (a, b) = (lo + need, hi - need);
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
        // Greedy forward: each piece as long as the stock allows, cut at the
        // farthest candidate within reach: the fewest pieces, and for each
        // cut the latest place it can be. Those cuts are kept (full stock
        // lengths nest best) unless the last piece is a stub; then greedy
        // backward from the end gives the earliest place of each cut, and
        // each goes to the candidate nearest the middle of its range, so the
        // pieces come out even. Every plate stays clear of the nodes.
        let no_room = |at: f64| {
            fail(
                None,
                format!(
                    "no room for a {:.0} mm splice plate within {usable:.0} mm of {:.0} mm: the node \
                     zones leave no stretch of {:.0} mm",
                    sp.plate_length_mm,
                    at.max(0.0),
                    2.0 * need
                ),
            )
        };
        let mut latest: Vec<f64> = Vec::new();
        let mut prev = -allowance;
        while strip.length_mm + allowance - prev > usable {
            let reach = prev + usable;
            let Some(i) = candidates
                .iter()
                .rposition(|&c| c <= reach && c > prev + 1.0)
            else {
                return Err(no_room(prev));
            };
            latest.push(candidates[i]);
            prev = candidates[i];
        }
        let mut earliest: Vec<f64> = Vec::new();
        let mut next = strip.length_mm + allowance;
        for _ in 0..latest.len() {
            let reach = next - usable;
            let Some(i) = candidates
                .iter()
                .position(|&c| c >= reach && c < next - 1.0)
            else {
                return Err(no_room(next - usable));
            };
            earliest.push(candidates[i]);
            next = candidates[i];
        }
        earliest.reverse();
        // Full stock lengths nest best (the short rests pair up in lanes):
        // keep the latest cuts unless the last piece would be a stub, then
        // even the pieces out.
        let last_piece = strip.length_mm + allowance - latest.last().copied().unwrap_or(-allowance);
        let keep_latest = last_piece >= MIN_LAST_PIECE_FRACTION * usable;
        if keep_latest {
            cuts = latest.clone();
        }
        let mut prev = -allowance;
        for (k, (&lo, &hi)) in earliest.iter().zip(&latest).enumerate() {
            if keep_latest {
                break;
            }
            let hi = hi.min(prev + usable);
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
    }
    let block = profile.shear_block.as_ref().filter(|_| sec.per_strip == 2);
    // Shear blocks, on the centre line.
    let mut block_stations: Vec<f64> = Vec::new();
    if let Some(b) = block {
        let spacing = blocks::max_spacing_mm(b.max_spacing_mm, b.slenderness_limit, t) / stretch;
        let half = 0.5 * b.length_mm + b.clearance_mm;
        // Supports: the line's ends, every crossing, and every splice (its
        // plate couples the pieces; blocks keep clear of it).
        let mut supports: Vec<(f64, f64, f64, Option<usize>)> = vec![(0.0, 0.0, 0.0, None)];
        for (ci, c) in crossings.iter().enumerate() {
            let s = strip.nodes[c.k].station_mm;
            supports.push((s, zones[ci].0, zones[ci].1, Some(c.node_id)));
        }
        if let Some(sp) = &profile.splice {
            for &c in &cuts {
                let half = 0.5 * sp.plate_length_mm;
                supports.push((c, c - half, c + half, None));
            }
        }
        supports.sort_by(|x, y| x.0.total_cmp(&y.0));
        supports.push((strip.length_mm, strip.length_mm, strip.length_mm, None));
        for w in supports.windows(2) {
            let (a, b2) = (w[0], w[1]);
            let iv = blocks::Interval {
                start_mm: a.0,
                end_mm: b2.0,
                free_lo_mm: a.2 + half,
                free_hi_mm: b2.1 - half,
            };
            let placed = blocks::place(iv, spacing, b.length_mm, 2.0 * b.clearance_mm)
                .map_err(|e| fail(a.3.or(b2.3), e))?;
            block_stations.extend(placed);
        }
    }

    // Splice bolt holes, on the centre line; the innermost must keep clear
    // of the cut.
    if let (Some(sp), false) = (&profile.splice, cuts.is_empty()) {
        let n = sp.bolts_per_side.max(1) as f64;
        let inner = 0.5 * sp.plate_length_mm * 0.5 / n;
        let radius = 0.5 * (sp.bolt_diameter_mm + BOLT_HOLE_CLEARANCE_MM);
        if inner <= radius + 1.0 {
            return Err(fail(
                None,
                format!(
                    "a {} mm splice plate with {} bolts a side puts its inner holes {inner:.1} mm from \
                     the cut: they would cross it",
                    sp.plate_length_mm, sp.bolts_per_side
                ),
            ));
        }
    }
    // Splice bolt holes, on the centre line.
    let splice_holes: Vec<f64> = profile.splice.as_ref().map_or(Vec::new(), |sp| {
        let n = sp.bolts_per_side.max(1) as usize;
        let half = 0.5 * sp.plate_length_mm;
        cuts.iter()
            .flat_map(|&c| {
                (0..n).flat_map(move |j| {
                    let d = half * (j as f64 + 0.5) / n as f64;
                    [c - d, c + d]
                })
            })
            .collect()
    });

    // Carry everything to each lamella's own line, and build its parts.
    let mut out = StripParts {
        blocks: block_stations.len(),
        splice_plates: cuts.len() * offsets.len(),
        ..StripParts::default()
    };
    let mut wanted: Vec<f64> = Vec::new();
    wanted.extend(&block_stations);
    wanted.extend(&cuts);
    wanted.extend(&splice_holes);
    let lines = match lines {
        Some(l) if l.are_of(i, &offsets) => l,
        _ => StripLines::new(strip, smooth, &offsets),
    };
    let on_lines = lines.stations(strip, smooth, &wanted);
    for (j, (o, (line, on_line))) in offsets
        .iter()
        .zip(lines.lines.iter().zip(on_lines))
        .enumerate()
    {
        let (b_line, rest) = on_line.split_at(block_stations.len());
        let (cut_line, hole_line) = rest.split_at(cuts.len());
        let slot_count: usize = slots[j].iter().map(|(_, spans)| spans.len()).sum();
        let node_holes = if node_hole_mm.is_some() {
            crossings.len()
        } else {
            0
        };
        let block_holes = if block.is_some() { b_line.len() } else { 0 };
        let splice_holes = if profile.splice.is_some() {
            hole_line.len()
        } else {
            0
        };
        let mut features: Vec<Feature> =
            Vec::with_capacity(slot_count + node_holes + block_holes + splice_holes);
        let edge = if strip.family == Family::A {
            SlotEdge::Top
        } else {
            SlotEdge::Bottom
        };
        for (ci, spans) in &slots[j] {
            let c = &crossings[*ci];
            let node_line = line.nodes[c.k].station_mm;
            let (a0, a1) = range_of(c);
            for s in spans {
                features.push(Feature {
                    kind: FeatureKind::Slot,
                    hole_use: None,
                    node: Some(c.node_id),
                    crossing: Some(c.crossing_id.to_string()),
                    center_part_mm: Point::new(
                        node_line + s.centre_mm(),
                        if edge == SlotEdge::Top {
                            h - 0.5 * slot_depth
                        } else {
                            0.5 * slot_depth
                        },
                    ),
                    width_mm: s.width_mm(),
                    depth_mm: slot_depth,
                    edge: Some(edge),
                    angle_range_deg: Some((a0.to_degrees(), a1.to_degrees())),
                    station_mm: Some(node_line + s.centre_mm()),
                });
            }
        }
        let mut hole = |station: f64,
                        d: f64,
                        usage: HoleUse,
                        node: Option<usize>,
                        crossing: Option<String>| {
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
        if let Some(d) = node_hole_mm {
            for c in &crossings {
                hole(
                    line.nodes[c.k].station_mm,
                    d,
                    HoleUse::Node,
                    Some(c.node_id),
                    Some(c.crossing_id.to_string()),
                );
            }
        }
        if let Some(b) = block {
            for &s in b_line {
                hole(
                    s,
                    b.bolt_diameter_mm + BOLT_HOLE_CLEARANCE_MM,
                    HoleUse::ShearBlock,
                    None,
                    None,
                );
            }
        }
        if let Some(sp) = &profile.splice {
            for &s in hole_line {
                hole(
                    s,
                    sp.bolt_diameter_mm + BOLT_HOLE_CLEARANCE_MM,
                    HoleUse::Splice,
                    None,
                    None,
                );
            }
        }
        // Pieces: [−allowance, cut₁], [cut₁, cut₂], …, [cutₙ, length + allowance].
        let mut bounds = vec![-allowance];
        bounds.extend_from_slice(cut_line);
        bounds.push(line.length_mm + allowance);
        let pieces = bounds.len() - 1;
        // Each feature goes to the piece [start, end) that holds its
        // station (none when outside them all), in the order made, moved.
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
        for (p, mine) in per_piece.into_iter().enumerate() {
            let (start, end) = (bounds[p], bounds[p + 1]);
            let id = if pieces == 1 {
                format!("{}-{}", strip.id, o.number)
            } else {
                format!("{}-{}.{}", strip.id, o.number, p + 1)
            };
            let part = lamella_part(id, &strip.id, o.number, start, end - start, h, mine)
                .map_err(|(node, what)| fail(node, what))?;
            out.lamellas.push(part);
        }
    }
    Ok(out)
}

/// One lamella piece: the rectangle length × h with its slots notched from
/// their edges (its round holes are its `hole` features alone); features
/// sorted by x. Err (node,
/// what) when a slot runs past an end or two slots leave less than 1 mm
/// of material between them.
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
    let notches = |edge: SlotEdge| {
        features
            .iter()
            .filter(move |f| f.kind == FeatureKind::Slot && f.edge == Some(edge))
    };
    let slots = features
        .iter()
        .filter(|f| f.kind == FeatureKind::Slot && f.edge.is_some())
        .count();
    let mut outline = Vec::with_capacity(5 + 4 * slots);
    outline.push(Point::new(0.0, 0.0));
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
    outline.push(Point::new(length_mm, 0.0));
    outline.push(Point::new(length_mm, h));
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
    outline.push(Point::new(0.0, h));
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
