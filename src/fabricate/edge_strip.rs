//! Edge strips (family `edge`, docs/fabrication.md "Strips"): bands tangential
//! to the surface, cut flat as planar curved bands and bent into place about
//! their width.
//!
//! Unrolling: the band's centre line is the plane curve whose curvature is
//! the edge curve's geodesic curvature kg(s). kg is interpolated linearly
//! between the strip's samples (held at the end samples' values up to 0 and
//! the length) and is 0 on the end allowances, where the centre line runs
//! straight on. The heading θ(s) = ∫kg ds is then piecewise quadratic and
//! integrated in closed form; the position ∫(cos θ, sin θ) ds by 3-point
//! Gauss–Legendre on steps of at most [`EDGE_STEP_MM`] that never straddle
//! a sample, a node or an end of the curve. Its remainder is
//! h⁷·f⁽⁶⁾/2 016 000 per step (f = cos θ or sin θ, |f⁽⁶⁾| ≲ κ⁶ for a slowly
//! varying κ = |kg|): below 1e-8 mm over 10 m for radii of 50 mm and more,
//! far inside [`ARC_TOLERANCE_MM`]. Steps are also short enough that every
//! chord of the band's inner edge (curvature κ/(1 − κ·h/2)) stays within
//! [`ARC_TOLERANCE_MM`] of the arc.
//!
//! The band is the centre line offset by ±h/2 (h = the profile's lamella
//! height) along its plane normal (−sin θ, cos θ): the +h/2 side is the
//! surface frame's +y side (y = z × x, seen from the normal's side kg > 0
//! turns the band counter-clockwise). Outline counter-clockwise: the −y edge
//! from start to end, the +y edge back; the ends are square to the centre
//! line. Collinear vertices are dropped (a straight band is 4 vertices).
//!
//! Holes: where the edge joint is bolted ([`crate::profile::EdgeJointKind`],
//! docs/fabrication.md "Edge joints"), one at every node of the edge (where
//! an A or B strip ends on it), on the centre line at the node's station, of
//! diameter edge bolt + hole clearance; none where the lamellas' end slots
//! alone hold the band. Nodes closer than [`SHARED_HOLE_MM`] along the edge
//! share one hole (each keeps its feature). A band split into pieces has a
//! splice plate at every cut (the band itself over the plate's length) and
//! the splice's bolt holes on the centre line in the plate and both pieces.
//!
//! Part frame: the band is turned so that the chord from the start of its
//! centre line (station −allowance) to its end runs along +x, then shifted
//! so that its outline's bounding box starts at the origin; `length_mm` and
//! `height_mm` are that box. For a straight band x = station + allowance and
//! the centre line is y = h/2. `station_start_mm` is −allowance: the
//! station at the band's start end (every hole's feature carries its own
//! station). Part id `E-<edge id>`; no labels (added later).

use crate::analysis::strip::Curvatures;
use crate::analysis::Analysis;
use crate::error::{Error, Result};
use crate::fabricate::lamella::BOLT_HOLE_CLEARANCE_MM;
use crate::fabricate::part::{Feature, FeatureKind, HoleUse, Part, PartKind, ARC_TOLERANCE_MM};
use crate::geom::plane::{bounds, segments_intersect, Arithmetic};
use crate::network::Family;
use crate::profile::Profile;
use kurbo::{Point, Vec2};
use std::path::Path;

/// Longest integration step along the centre line, mm.
pub const EDGE_STEP_MM: f64 = 5.0;

/// Nodes closer than this along an edge share one hole, mm.
pub const SHARED_HOLE_MM: f64 = 0.1;

/// Shortest integration step, mm (reached only at radii near 1 mm).
const MIN_STEP_MM: f64 = 0.05;

/// Where a strip ends on (crosses) an edge.
#[derive(Debug, Clone, PartialEq)]
pub struct EdgeNode {
    /// The node's id (its plan.json id).
    pub id: usize,
    /// Id of the A or B strip crossing the edge there.
    pub crossing: String,
    /// Station of the node on the edge curve, mm.
    pub station_mm: f64,
    /// Acute angle between the strip and the edge there, degrees.
    pub angle_deg: f64,
}

/// An edge curve as the unroller needs it: plain data from its strip.
#[derive(Debug, Clone, PartialEq)]
pub struct EdgeCurve {
    /// The edge's curve id.
    pub id: String,
    /// Arc length of the curve, mm.
    pub length_mm: f64,
    /// Geodesic curvature samples, sorted by station.
    pub samples: Vec<Curvatures>,
    /// The edge's nodes, by station.
    pub nodes: Vec<EdgeNode>,
}

/// The edge curves of an analysis, in strip order.
pub fn edge_curves(analysis: &Analysis) -> Vec<EdgeCurve> {
    analysis
        .strips
        .iter()
        .filter(|s| s.family == Family::Edge)
        .map(|s| EdgeCurve {
            id: s.id.clone(),
            length_mm: s.length_mm,
            samples: s.samples.clone(),
            nodes: s
                .nodes
                .iter()
                .map(|cn| EdgeNode {
                    id: analysis
                        .topology
                        .nodes
                        .get(cn.node)
                        .map_or(cn.node, |n| n.id),
                    crossing: analysis
                        .strips
                        .get(cn.crossing)
                        .map_or_else(String::new, |c| c.id.clone()),
                    station_mm: cn.station_mm,
                    angle_deg: analysis
                        .topology
                        .nodes
                        .get(cn.node)
                        .map_or(90.0, |n| n.angle_deg),
                })
                .collect(),
        })
        .collect()
}

/// Part id of an edge strip: `E-` and the edge's id.
pub fn edge_strip_id(edge_id: &str) -> String {
    format!("E-{edge_id}")
}

/// A point of the unrolled centre line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CentrePoint {
    /// Station on the edge curve, mm (negative on the start allowance).
    pub station_mm: f64,
    /// Heading of the tangent, radians, 0 at the start.
    pub heading_rad: f64,
    /// Position in the unrolling frame (the start at the origin, heading
    /// along +x), mm.
    pub point: Point,
}

/// Geodesic curvature at `s` on the linear piece that holds `piece` (a
/// station inside the piece, to pick the side of a knot): 0 outside
/// [0, length], the samples' linear interpolation inside (held at the end
/// samples' values).
fn kg_at(samples: &[Curvatures], length_mm: f64, piece: f64, s: f64) -> f64 {
    if piece < 0.0 || piece > length_mm || samples.is_empty() {
        return 0.0;
    }
    let i = samples.partition_point(|c| c.station_mm <= piece);
    if i == 0 {
        return samples[0].kg_per_mm;
    }
    if i == samples.len() {
        return samples[i - 1].kg_per_mm;
    }
    let (a, b) = (samples[i - 1], samples[i]);
    let span = b.station_mm - a.station_mm;
    if span <= 0.0 {
        return b.kg_per_mm;
    }
    let t = (s - a.station_mm) / span;
    a.kg_per_mm + t * (b.kg_per_mm - a.kg_per_mm)
}

/// The unrolled centre line from station `from_mm` to `to_mm`: a point at
/// every sample, every station of `knots_mm` in range, both ends, and
/// between them at most `max_step_mm` apart (see the module doc for the
/// integration and its accuracy). The curvature is that of [`EdgeCurve`]:
/// linear between `samples`, 0 outside [0, `length_mm`].
pub fn unroll_centre_line(
    samples: &[Curvatures],
    length_mm: f64,
    from_mm: f64,
    to_mm: f64,
    knots_mm: &[f64],
    max_step_mm: f64,
) -> Vec<CentrePoint> {
    let mut knots: Vec<f64> = samples
        .iter()
        .map(|c| c.station_mm)
        .chain(knots_mm.iter().copied())
        .chain([0.0, length_mm, from_mm, to_mm])
        .filter(|s| s.is_finite() && *s >= from_mm && *s <= to_mm)
        .collect();
    knots.sort_by(f64::total_cmp);
    knots.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let step = max_step_mm.max(MIN_STEP_MM);
    // Gauss–Legendre, 3 points on [0, 1].
    let r = 0.5 * (0.6f64).sqrt();
    let gauss = [
        (0.5 - r, 5.0 / 18.0),
        (0.5, 8.0 / 18.0),
        (0.5 + r, 5.0 / 18.0),
    ];
    let mut out = vec![CentrePoint {
        station_mm: knots.first().copied().unwrap_or(from_mm),
        heading_rad: 0.0,
        point: Point::ORIGIN,
    }];
    for w in knots.windows(2) {
        let (a, b) = (w[0], w[1]);
        let n = ((b - a) / step).ceil().max(1.0) as usize;
        let mid = 0.5 * (a + b);
        for k in 0..n {
            let last = out[out.len() - 1];
            let s0 = last.station_mm;
            let s1 = if k + 1 == n {
                b
            } else {
                a + (b - a) * (k + 1) as f64 / n as f64
            };
            let h = s1 - s0;
            let (k0, k1) = (
                kg_at(samples, length_mm, mid, s0),
                kg_at(samples, length_mm, mid, s1),
            );
            let theta = |u: f64| last.heading_rad + k0 * u + 0.5 * (k1 - k0) * u * u / h;
            let mut d = Vec2::ZERO;
            for (x, wt) in gauss {
                let th = theta(x * h);
                d += Vec2::new(th.cos(), th.sin()) * (wt * h);
            }
            out.push(CentrePoint {
                station_mm: s1,
                heading_rad: theta(h),
                point: last.point + d,
            });
        }
    }
    out
}

/// The hole diameter at an edge's nodes where the edge joint is bolted
/// ([`Profile::edge_bolt_mm`]): the edge bolt + its hole clearance; none
/// for an end slot alone.
pub fn edge_hole_diameter_mm(profile: &Profile) -> Option<f64> {
    profile
        .edge_bolt_mm()
        .map(|d| d + profile.edge_bolt_clearance_mm())
}

/// The diameter of a band splice's bolt holes, mm (the profile's splice
/// bolt + [`BOLT_HOLE_CLEARANCE_MM`]), where the profile has splices.
pub fn band_splice_hole_mm(profile: &Profile) -> Option<f64> {
    profile
        .splice
        .as_ref()
        .map(|sp| sp.bolt_diameter_mm + BOLT_HOLE_CLEARANCE_MM)
}

/// The stations of a splice's bolt holes about a cut at `cut_mm`:
/// `bolts_per_side` pairs evenly over the plate, as on lamellas.
pub fn splice_hole_stations_mm(profile: &Profile, cut_mm: f64) -> Vec<f64> {
    let Some(sp) = &profile.splice else {
        return Vec::new();
    };
    let n = sp.bolts_per_side.max(1) as usize;
    let half = 0.5 * sp.plate_length_mm;
    let mut out: Vec<f64> = (0..n)
        .flat_map(|j| {
            let d = half * (j as f64 + 0.5) / n as f64;
            [cut_mm - d, cut_mm + d]
        })
        .collect();
    out.sort_by(f64::total_cmp);
    out
}

/// The flat band of one edge (see the module doc).
///
/// Errors (one line naming the profile, the edge and, where there is one,
/// the node): a geodesic curvature radius at or below half the band height
/// (the inner edge would fold), a hole as wide as the band or wider, holes
/// of two nodes that overlap without coinciding, and a band that overlaps
/// itself once unrolled.
pub fn edge_strip(profile: &Profile, edge: &EdgeCurve) -> Result<Part> {
    let allowance = profile.section.end_allowance_mm;
    edge_piece(
        profile,
        edge,
        (-allowance, edge.length_mm + allowance),
        edge_strip_id(&edge.id),
        PartKind::EdgeStrip,
        &[],
    )
}

/// The flat band of the piece of one edge between two stations (the ends
/// of the edge extended straight by the end allowance), with the holes of
/// the nodes inside it (a band piece, when bolted) and the splice holes at
/// `splice_mm` (stations inside it): a band piece (`kind` edge strip) or a
/// band splice plate (`kind` splice plate, no node holes).
fn edge_piece(
    profile: &Profile,
    edge: &EdgeCurve,
    (from_mm, to_mm): (f64, f64),
    id: String,
    kind: PartKind,
    splice_mm: &[f64],
) -> Result<Part> {
    let fail = |node: Option<usize>, what: String| {
        Error::fabrication(&profile.source, &edge.id, node, what)
    };
    let h = profile.section.height_mm;
    let half = 0.5 * h;
    let length = edge.length_mm;
    let max_kg = edge
        .samples
        .iter()
        .max_by(|a, b| a.kg_per_mm.abs().total_cmp(&b.kg_per_mm.abs()));
    let kappa = max_kg.map_or(0.0, |c| c.kg_per_mm.abs());
    if let Some(c) = max_kg.filter(|_| kappa * half >= 1.0 || kappa.is_nan()) {
        return Err(fail(
            None,
            format!(
                "its geodesic curvature radius {:.1} mm at station {:.1} mm is not above half the {h} mm band height: the band's inner edge folds over",
                1.0 / kappa,
                c.station_mm
            ),
        ));
    }
    let diameter = edge_hole_diameter_mm(profile).filter(|_| kind == PartKind::EdgeStrip);
    if let (Some(n), Some(d)) = (edge.nodes.first(), diameter.filter(|&d| d >= h)) {
        return Err(fail(
            Some(n.id),
            format!("the {d} mm hole does not fit the {h} mm band height"),
        ));
    }
    // Steps: EDGE_STEP_MM, shorter where a chord of the inner edge would
    // stray beyond the arc tolerance (sagitta Δ²·κ/8).
    let inner = kappa / (1.0 - kappa * half);
    let step = if inner > 0.0 {
        EDGE_STEP_MM.min((8.0 * ARC_TOLERANCE_MM / inner).sqrt())
    } else {
        EDGE_STEP_MM
    };
    let nodes: Vec<&EdgeNode> = edge
        .nodes
        .iter()
        .filter(|n| diameter.is_some() && n.station_mm > from_mm && n.station_mm < to_mm)
        .collect();
    let splice_mm: Vec<f64> = splice_mm
        .iter()
        .copied()
        .filter(|&s| s > from_mm && s < to_mm)
        .collect();
    let stations: Vec<f64> = nodes
        .iter()
        .map(|n| n.station_mm)
        .chain(splice_mm.iter().copied())
        .collect();
    let line = unroll_centre_line(&edge.samples, length, from_mm, to_mm, &stations, step);
    // Turn the chord onto +x.
    let (first, last) = (line[0].point, line[line.len() - 1].point);
    let chord = last - first;
    let turn = if chord.hypot() > 1e-9 * (to_mm - from_mm) {
        -chord.y.atan2(chord.x)
    } else {
        0.0
    };
    let (sin, cos) = turn.sin_cos();
    let place = |p: Point| Point::new(cos * p.x - sin * p.y, sin * p.x + cos * p.y);
    let side = |c: &CentrePoint, sign: f64| {
        let n = Vec2::new(-c.heading_rad.sin(), c.heading_rad.cos());
        place(c.point + n * (sign * half))
    };
    let mut outline: Vec<Point> = line.iter().map(|c| side(c, -1.0)).collect();
    outline.extend(line.iter().rev().map(|c| side(c, 1.0)));
    let outline = drop_collinear(outline);
    if !is_simple(&outline) {
        return Err(fail(
            None,
            format!(
                "the unrolled band overlaps itself (it turns through {:.0}°): split the edge",
                (line[line.len() - 1].heading_rad - line[0].heading_rad)
                    .abs()
                    .to_degrees()
            ),
        ));
    }
    let bbox = bounds(&outline);
    let shift = Vec2::new(-bbox.x0, -bbox.y0);
    let outline: Vec<Point> = outline.into_iter().map(|p| p + shift).collect();
    // Hole centres on the centre line at the node stations (knots of the line).
    let centre_at = |s: f64| {
        let i = line
            .partition_point(|c| c.station_mm < s - 1e-9)
            .min(line.len() - 1);
        place(line[i].point) + shift
    };
    let hole = |s: f64, d: f64, usage: HoleUse, node: Option<&EdgeNode>| Feature {
        kind: FeatureKind::Hole,
        hole_use: Some(usage),
        node: node.map(|n| n.id),
        crossing: node.map(|n| n.crossing.clone()),
        center_part_mm: centre_at(s),
        width_mm: d,
        depth_mm: 0.0,
        edge: None,
        angle_range_deg: None,
        station_mm: Some(s),
    };
    let mut features: Vec<Feature> = nodes
        .iter()
        .map(|n| {
            hole(
                n.station_mm,
                diameter.unwrap_or_default(),
                HoleUse::EdgeNode,
                Some(n),
            )
        })
        .collect();
    let splice_d = band_splice_hole_mm(profile).unwrap_or_default();
    features.extend(
        splice_mm
            .iter()
            .map(|&s| hole(s, splice_d, HoleUse::Splice, None)),
    );
    features.sort_by(|a, b| {
        a.center_part_mm
            .x
            .total_cmp(&b.center_part_mm.x)
            .then(a.center_part_mm.y.total_cmp(&b.center_part_mm.y))
    });
    holes_apart(&profile.source, &edge.id, &features)?;
    Ok(Part {
        id,
        kind,
        strip: Some(edge.id.clone()),
        lamella: None,
        count: 1,
        length_mm: bbox.width(),
        height_mm: bbox.height(),
        station_start_mm: Some(from_mm),
        outline_part_mm: outline,
        holes_part_mm: Vec::new(),
        engraving: Vec::new(),
        features,
    })
}

/// Features closer than [`SHARED_HOLE_MM`] share one hole; holes that
/// overlap otherwise are an error.
fn holes_apart(profile: &Path, edge: &str, features: &[Feature]) -> Result<()> {
    let mut centres: Vec<(Point, usize, f64)> = Vec::new();
    for f in features {
        let node = f.node.unwrap_or_default();
        let diameter = f.width_mm;
        match centres
            .iter()
            .find(|(c, _, d)| c.distance(f.center_part_mm) < 0.5 * (diameter + d))
        {
            Some((c, _, _)) if c.distance(f.center_part_mm) < SHARED_HOLE_MM => {}
            Some((_, other, _)) => {
                return Err(Error::fabrication(
                    profile,
                    edge,
                    Some(node),
                    format!("its {diameter} mm hole overlaps the hole of node {other}"),
                ))
            }
            None => centres.push((f.center_part_mm, node, diameter)),
        }
    }
    Ok(())
}

/// Drop the vertices of a closed polyline that lie within 1e-9 mm of the
/// line through their neighbours (kept ones).
fn drop_collinear(poly: Vec<Point>) -> Vec<Point> {
    let mut out: Vec<Point> = Vec::with_capacity(poly.len());
    let n = poly.len();
    for i in 0..n {
        let p = poly[i];
        let next = poly[(i + 1) % n];
        if let Some(&prev) = out.last() {
            let (d, e) = (next - prev, p - prev);
            let len = d.hypot();
            if len > 0.0
                && (d.cross(e) / len).abs() < 1e-9
                && e.dot(d) > 0.0
                && e.dot(d) < len * len
            {
                continue;
            }
        }
        out.push(p);
    }
    // The first vertex, against the last kept and the second.
    if out.len() > 3 {
        let (prev, p, next) = (out[out.len() - 1], out[0], out[1]);
        let (d, e) = (next - prev, p - prev);
        let len = d.hypot();
        if len > 0.0 && (d.cross(e) / len).abs() < 1e-9 && e.dot(d) > 0.0 && e.dot(d) < len * len {
            out.remove(0);
        }
    }
    out
}

/// Whether a closed polyline is simple: no two non-neighbouring edges
/// touch and no two neighbouring ones overlap. A sweep over x: edges sorted
/// by their smallest x, each tested against the earlier ones still open.
pub fn is_simple(poly: &[Point]) -> bool {
    let n = poly.len();
    if n < 3 {
        return false;
    }
    let seg = |i: usize| (poly[i], poly[(i + 1) % n]);
    let mut order: Vec<usize> = (0..n).collect();
    let min_x = |i: usize| seg(i).0.x.min(seg(i).1.x);
    let max_x = |i: usize| seg(i).0.x.max(seg(i).1.x);
    order.sort_by(|&a, &b| min_x(a).total_cmp(&min_x(b)));
    let mut active: Vec<usize> = Vec::new();
    for &i in &order {
        let lo = min_x(i);
        active.retain(|&j| max_x(j) >= lo);
        for &j in &active {
            let adjacent = (i + 1) % n == j || (j + 1) % n == i;
            if segments_touch(seg(i), seg(j), adjacent) {
                return false;
            }
        }
        active.push(i);
    }
    true
}

/// Whether two segments meet; neighbours (sharing an end) only when they
/// overlap along a line or one folds back onto the other.
fn segments_touch((a, b): (Point, Point), (c, d): (Point, Point), adjacent: bool) -> bool {
    if adjacent {
        // Shared vertex: touching elsewhere means collinear and folding back.
        return Arithmetic::Float.collinear_opposite(a, b, c, d);
    }
    segments_intersect(a, b, c, d)
}

/// The most pieces an edge is split into before giving up.
const MAX_EDGE_PIECES: usize = 500;

/// How far a band cut keeps from an edge node along the band, mm: the
/// splice plate's half length (when the profile has splices) plus the
/// crossing strip's footprint on the band (its width, per_strip × t + gap,
/// over sin φ, and the band's height × |cot φ| as the strip crosses it
/// obliquely) and the slot clearance; without a splice, the node hole's
/// diameter (or the footprint alone when the band has no holes).
pub fn band_cut_keep_mm(profile: &Profile, node: &EdgeNode) -> f64 {
    let l = &profile.section;
    let (sin, cos) = node.angle_deg.to_radians().sin_cos();
    let sin = sin.max(1e-3);
    let strip_w = f64::from(l.per_strip) * l.thickness_mm + l.gap_mm;
    let footprint =
        0.5 * strip_w / sin + 0.5 * l.height_mm * cos.abs() / sin + profile.joint.slot_clearance_mm;
    match &profile.splice {
        Some(sp) => 0.5 * sp.plate_length_mm + footprint,
        None => edge_hole_diameter_mm(profile).map_or(footprint, |d| d.max(footprint)),
    }
}

/// Part id of the splice plate at the `k`-th cut (1-based) of an edge's
/// band: `SP-<edge id>.<k>` (it joins pieces k and k + 1).
pub fn band_splice_id(edge_id: &str, k: usize) -> String {
    format!("SP-{edge_id}.{k}")
}

/// The edge strips of an analysis, in strip order: each edge as one band,
/// or, where that band fits no stock size's usable area in an allowed
/// rotation (too long, or too bowed), or bows more than the profile's
/// `edge_joint.max_band_bow_mm`, split into the fewest pieces of about
/// equal length that do (`E-edge00.1`, `E-edge00.2`, …; end allowances only
/// at the edge's ends). Every cut keeps [`band_cut_keep_mm`] from every
/// edge node; where the profile has splices each cut has a splice plate
/// (`SP-edge00.1`, the band itself between cut ± half the plate length,
/// so it lies on both pieces exactly) with the splice's bolt holes on the
/// centre line, at the same stations as in the two pieces.
pub fn edge_strips(profile: &Profile, analysis: &Analysis) -> Result<Vec<Part>> {
    let c = &profile.cutting;
    let h = profile.section.height_mm;
    // Some size must hold the band (the nest picks which), and it bows no
    // more than the profile allows.
    let fits = |p: &Part| {
        profile.stock.holds(
            p.length_mm,
            p.height_mm,
            c.edge_margin_mm,
            &c.allowed_rotations_deg,
        ) && profile
            .edge_joint
            .max_band_bow_mm
            .is_none_or(|b| p.height_mm - h <= b + 1e-9)
    };
    let allowance = profile.section.end_allowance_mm;
    let plate_mm = profile.splice.as_ref().map(|sp| sp.plate_length_mm);
    let mut out = Vec::new();
    for e in edge_curves(analysis) {
        // A whole band that folds or overlaps itself may still be cut into
        // pieces that do not: only a curvature too tight for the band (which
        // no split cures) stops here.
        match edge_strip(profile, &e) {
            Ok(whole) if fits(&whole) => {
                out.push(whole);
                continue;
            }
            Err(err) if err.to_string().contains("folds over") => return Err(err),
            _ => {}
        }
        let (start, end) = (-allowance, e.length_mm + allowance);
        // Where a cut may go: the band less every node's keep and, with a
        // plate, half a plate at either end.
        let end_keep = plate_mm.map_or(0.0, |l| 0.5 * l) + 1.0;
        let mut busy: Vec<(f64, f64)> = e
            .nodes
            .iter()
            .map(|n| {
                let k = band_cut_keep_mm(profile, n);
                (n.station_mm - k, n.station_mm + k)
            })
            .collect();
        busy.push((f64::NEG_INFINITY, start + end_keep));
        busy.push((end - end_keep, f64::INFINITY));
        busy.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut free: Vec<(f64, f64)> = Vec::new();
        let mut from = f64::NEG_INFINITY;
        for &(lo, hi) in &busy {
            if lo > from {
                free.push((from, lo));
            }
            from = from.max(hi);
        }
        // The free point nearest `x`.
        let snap = |x: f64| -> Option<f64> {
            free.iter()
                .map(|&(lo, hi)| x.clamp(lo, hi))
                .min_by(|a, b| (a - x).abs().total_cmp(&(b - x).abs()))
        };
        let mut done = false;
        for n in 2..=MAX_EDGE_PIECES {
            // Even cuts, each moved to the nearest place it may go.
            let cuts: Option<Vec<f64>> = (1..n)
                .map(|k| snap(start + (end - start) * k as f64 / n as f64))
                .collect();
            let Some(mut cuts) = cuts else {
                break;
            };
            cuts.dedup_by(|a, b| (*a - *b).abs() < 1.0);
            if cuts.is_empty() {
                continue;
            }
            let mut bounds = vec![start];
            bounds.extend(cuts.iter().copied());
            bounds.push(end);
            let shortest = plate_mm.unwrap_or(0.0).max(1.0);
            if bounds.windows(2).any(|w| w[1] - w[0] < shortest) {
                continue;
            }
            let splice_mm: Vec<f64> = if plate_mm.is_some() {
                cuts.iter()
                    .flat_map(|&cut| splice_hole_stations_mm(profile, cut))
                    .collect()
            } else {
                Vec::new()
            };
            let pieces = bounds
                .windows(2)
                .enumerate()
                .map(|(k, w)| {
                    edge_piece(
                        profile,
                        &e,
                        (w[0], w[1]),
                        format!("{}.{}", edge_strip_id(&e.id), k + 1),
                        PartKind::EdgeStrip,
                        &splice_mm,
                    )
                })
                .collect::<Result<Vec<Part>>>();
            // A piece that still overlaps itself: try more pieces.
            let Ok(pieces) = pieces else {
                continue;
            };
            if !pieces.iter().all(fits) {
                continue;
            }
            let plates = match plate_mm {
                Some(l) => cuts
                    .iter()
                    .enumerate()
                    .map(|(k, &cut)| {
                        edge_piece(
                            profile,
                            &e,
                            (cut - 0.5 * l, cut + 0.5 * l),
                            band_splice_id(&e.id, k + 1),
                            PartKind::SplicePlate,
                            &splice_hole_stations_mm(profile, cut),
                        )
                    })
                    .collect::<Result<Vec<Part>>>()?,
                None => Vec::new(),
            };
            out.extend(pieces);
            out.extend(plates);
            done = true;
            break;
        }
        if !done {
            return Err(Error::fabrication(
                &profile.source,
                &e.id,
                None,
                format!(
                    "the edge band does not fit the usable area of any stock size (the longest \
                     usable {:.0} mm, the widest {:.0} mm{}) in pieces spliced clear of its nodes",
                    profile.stock.longest_usable_mm(c.edge_margin_mm, 0.0),
                    profile.stock.widest_usable_mm(c.edge_margin_mm),
                    profile
                        .edge_joint
                        .max_band_bow_mm
                        .map_or_else(String::new, |b| format!(", a bow of at most {b} mm"))
                ),
            ));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::read::profile_file;
    use crate::geom::plane::signed_area_mm2;

    fn steel() -> Profile {
        let mut p = profile_file::load(Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/profiles/steel-1.5.yaml"
        )))
        .expect("steel profile");
        p.source = "steel.yaml".into();
        p
    }

    /// Samples of kg(s) every 50 mm over [0, length] (and at the end).
    fn curve(id: &str, length_mm: f64, kg: impl Fn(f64) -> f64, nodes: &[f64]) -> EdgeCurve {
        let n = (length_mm / 50.0).ceil() as usize;
        EdgeCurve {
            id: id.into(),
            length_mm,
            samples: (0..=n)
                .map(|i| {
                    let s = length_mm * i as f64 / n as f64;
                    Curvatures {
                        station_mm: s,
                        kg_per_mm: kg(s),
                        kn_per_mm: 0.0,
                        tg_per_mm: 0.0,
                    }
                })
                .collect(),
            nodes: nodes
                .iter()
                .enumerate()
                .map(|(i, &s)| EdgeNode {
                    id: 100 + i,
                    crossing: format!("A{i:02}"),
                    station_mm: s,
                    angle_deg: 90.0,
                })
                .collect(),
        }
    }

    /// Every pair of non-neighbouring edges apart, by brute force.
    fn simple_brute_force(poly: &[Point]) -> bool {
        let n = poly.len();
        (0..n).all(|i| {
            (0..n).all(|j| {
                let adjacent = i == j || (i + 1) % n == j || (j + 1) % n == i;
                adjacent
                    || !segments_touch(
                        (poly[i], poly[(i + 1) % n]),
                        (poly[j], poly[(j + 1) % n]),
                        false,
                    )
            })
        })
    }

    #[test]
    fn a_constant_kg_edge_unrolls_to_a_circle_arc() {
        // 2 m of arc, R = 1.5 m, turning left (kg > 0) and right (kg < 0).
        for r in [1500.0, -1500.0] {
            let line = unroll_centre_line(
                &curve("e", 2000.0, |_| 1.0 / r, &[]).samples,
                2000.0,
                0.0,
                2000.0,
                &[],
                EDGE_STEP_MM,
            );
            let centre = Point::new(0.0, r);
            for c in &line {
                let err = (c.point.distance(centre) - r.abs()).abs();
                assert!(err < 1e-6, "R {r}, s {}: {err}", c.station_mm);
                assert!((c.heading_rad - c.station_mm / r).abs() < 1e-12);
                // On the circle at the arc length s: angle s/R.
                let want =
                    centre + Vec2::new((c.station_mm / r).sin(), -(c.station_mm / r).cos()) * r;
                assert!(c.point.distance(want) < 1e-6);
            }
            assert!(line
                .windows(2)
                .all(|w| w[1].station_mm - w[0].station_mm <= EDGE_STEP_MM + 1e-9));
        }
    }

    #[test]
    fn an_arc_band_has_its_holes_at_the_node_stations() {
        let p = steel();
        let (r, len, a, h) = (1500.0, 2000.0, 25.0, 50.0);
        let stations = [0.0, 333.3, 1000.0, 1777.7, 2000.0];
        let edge = curve("edge03", len, |_| 1.0 / r, &stations);
        let part = edge_strip(&p, &edge).expect("band");
        assert_eq!(part.id, "E-edge03");
        assert_eq!(part.kind, PartKind::EdgeStrip);
        assert_eq!(part.strip.as_deref(), Some("edge03"));
        assert_eq!(part.station_start_mm, Some(-a));
        assert!(part.engraving.is_empty());
        let o = &part.outline_part_mm;
        assert!(signed_area_mm2(o) > 0.0);
        assert!(is_simple(o) && simple_brute_force(o));
        // Area: h × centre-line length (straight ends included), less the
        // chords' shortfall (within the arc tolerance along both edges).
        let area = signed_area_mm2(o);
        assert!((area - h * (len + 2.0 * a)).abs() < 2.0 * ARC_TOLERANCE_MM * (len + 2.0 * a));
        // Bounding box at the origin, and the part's extents.
        let min_x = o.iter().map(|q| q.x).fold(f64::INFINITY, f64::min);
        let min_y = o.iter().map(|q| q.y).fold(f64::INFINITY, f64::min);
        assert!(min_x.abs() < 1e-9 && min_y.abs() < 1e-9);
        // Holes: on one circle of radius R, their chords those of the stations.
        assert_eq!(part.features.len(), 5);
        assert!(part.holes_part_mm.is_empty());
        assert_eq!(part.round_holes().len(), 5);
        let f = &part.features;
        let by_station = |s: f64| {
            f.iter()
                .find(|x| x.station_mm == Some(s))
                .map(|x| x.center_part_mm)
                .expect("hole")
        };
        for i in 0..stations.len() {
            for j in i + 1..stations.len() {
                let chord = 2.0 * r * ((stations[j] - stations[i]) / (2.0 * r)).sin();
                let got = by_station(stations[i]).distance(by_station(stations[j]));
                assert!((got - chord).abs() < 0.01, "{i}-{j}: {got} vs {chord}");
            }
        }
        // Every hole is 9 mm (M8 + 1 mm), clockwise, inside the band.
        for (x, hole) in f.iter().zip(&part.hole_polygons()) {
            assert_eq!(x.hole_use, Some(HoleUse::EdgeNode));
            assert!(x.node.is_some() && x.crossing.is_some());
            assert_eq!(x.width_mm, 9.0);
            assert!(signed_area_mm2(hole) < 0.0);
            assert!(hole
                .iter()
                .all(|q| (q.distance(x.center_part_mm) - 4.5).abs() < 1e-9));
        }
        // Features by x.
        assert!(f
            .windows(2)
            .all(|w| w[0].center_part_mm.x <= w[1].center_part_mm.x));
        // The band's edges lie on the circles R ± h/2 about the centre the
        // holes imply (through three of them).
        let centre = circumcentre(by_station(0.0), by_station(1000.0), by_station(2000.0));
        assert!((by_station(333.3).distance(centre) - r).abs() < 0.01);
        let on_arc = o
            .iter()
            .filter(|q| {
                let d = q.distance(centre);
                (d - (r - h / 2.0)).abs() < 0.01 || (d - (r + h / 2.0)).abs() < 0.01
            })
            .count();
        // All but the four corners of the straight ends lie on the arcs.
        assert!(on_arc + 4 >= o.len(), "{on_arc} of {}", o.len());
    }

    fn circumcentre(a: Point, b: Point, c: Point) -> Point {
        let d = 2.0 * (a.x * (b.y - c.y) + b.x * (c.y - a.y) + c.x * (a.y - b.y));
        let sq = |p: Point| p.x * p.x + p.y * p.y;
        Point::new(
            (sq(a) * (b.y - c.y) + sq(b) * (c.y - a.y) + sq(c) * (a.y - b.y)) / d,
            (sq(a) * (c.x - b.x) + sq(b) * (a.x - c.x) + sq(c) * (b.x - a.x)) / d,
        )
    }

    #[test]
    fn a_straight_edge_is_a_rectangle() {
        let p = steel();
        let (len, a, h) = (1234.5, 25.0, 50.0);
        let part = edge_strip(&p, &curve("e1", len, |_| 0.0, &[0.0, 400.0, len])).expect("band");
        let want = [
            Point::new(0.0, 0.0),
            Point::new(len + 2.0 * a, 0.0),
            Point::new(len + 2.0 * a, h),
            Point::new(0.0, h),
        ];
        assert_eq!(part.outline_part_mm.len(), 4, "{:?}", part.outline_part_mm);
        for (got, want) in part.outline_part_mm.iter().zip(want) {
            assert!(got.distance(want) < 1e-9, "{got:?} vs {want:?}");
        }
        assert!((part.length_mm - (len + 2.0 * a)).abs() < 1e-9);
        assert!((part.height_mm - h).abs() < 1e-9);
        for (x, s) in part.features.iter().zip([0.0, 400.0, len]) {
            assert!(x.center_part_mm.distance(Point::new(a + s, h / 2.0)) < 1e-9);
        }
    }

    #[test]
    fn linear_kg_matches_a_fine_reference_integration() {
        // A clothoid-like edge: kg from −1/800 to 1/600 over 1.8 m.
        let (len, a) = (1800.0, 25.0);
        let kg = |s: f64| -1.0 / 800.0 + (1.0 / 600.0 + 1.0 / 800.0) * s / len;
        let edge = curve("c", len, kg, &[900.0]);
        let line = unroll_centre_line(&edge.samples, len, -a, len + a, &[900.0], EDGE_STEP_MM);
        // Reference: midpoint rule on 0.01 mm steps of the exact heading.
        let theta = |s: f64| {
            let s = s.clamp(0.0, len);
            -s / 800.0 + 0.5 * (1.0 / 600.0 + 1.0 / 800.0) * s * s / len
        };
        let (mut s, mut q) = (-a, Point::ORIGIN);
        let ds: f64 = 0.01;
        let mut worst: f64 = 0.0;
        for c in &line {
            while s < c.station_mm - 1e-9 {
                let step = ds.min(c.station_mm - s);
                let th = theta(s + 0.5 * step);
                q += Vec2::new(th.cos(), th.sin()) * step;
                s += step;
            }
            worst = worst.max(q.distance(c.point));
            assert!((c.heading_rad - theta(c.station_mm)).abs() < 1e-12);
        }
        assert!(worst < 1e-4, "{worst}");
        let part = edge_strip(&steel(), &edge).expect("band");
        assert!(signed_area_mm2(&part.outline_part_mm) > 0.0);
        assert!(simple_brute_force(&part.outline_part_mm));
    }

    #[test]
    fn hole_diameter_follows_the_profile() {
        let mut p = steel();
        // The node bolt M8 + 1 mm, in the 10 mm gap of the doubled strip.
        assert_eq!(edge_hole_diameter_mm(&p), Some(9.0));
        p.edge_joint.bolt_diameter_mm = Some(6.0);
        assert_eq!(edge_hole_diameter_mm(&p), Some(7.0));
        // An M10 hole (11 mm) does not fit the 10 mm gap: an end slot alone.
        p.edge_joint.bolt_diameter_mm = Some(10.0);
        assert_eq!(edge_hole_diameter_mm(&p), None);
        p.edge_joint.bolt_diameter_mm = None;
        p.node_bolt = None;
        assert_eq!(edge_hole_diameter_mm(&p), None);
        let poplar = profile_file::load(Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/profiles/poplar-ply-4.yaml"
        )))
        .expect("poplar");
        // No node bolt, no edge bolt: the poplar lamellas' end slots alone.
        assert_eq!(edge_hole_diameter_mm(&poplar), None);
    }

    #[test]
    fn nodes_at_one_point_share_a_hole() {
        let part =
            edge_strip(&steel(), &curve("e", 1000.0, |_| 1e-3, &[500.0, 500.0])).expect("band");
        assert_eq!(part.features.len(), 2);
        assert!(part.holes_part_mm.is_empty());
        assert_eq!(part.round_holes().len(), 1);
        assert_eq!(part.hole_polygons().len(), 1);
    }

    /// A flat grid (z = 0): A lines along x, B lines at 60°, and an arc
    /// edge of radius 700 mm that both cross; file normals +z.
    fn planar_analysis() -> Analysis {
        use crate::network::{Network, RawCurve, RawNetwork, Unit};
        use glam::DVec3;
        let line = |id: String, family, p0: DVec3, d: DVec3, len: f64| {
            let n = (len / 10.0) as usize;
            let points: Vec<DVec3> = (0..=n)
                .map(|i| p0 + d * (len * i as f64 / n as f64))
                .collect();
            RawCurve {
                id,
                family,
                normals: Some(vec![DVec3::Z; points.len()]),
                points,
            }
        };
        let mut curves = Vec::new();
        for (i, y) in [0.0, 100.0, 200.0].into_iter().enumerate() {
            curves.push(line(
                format!("A{i:02}"),
                Family::A,
                DVec3::new(-100.0, y, 0.0),
                DVec3::X,
                500.0,
            ));
        }
        let d = DVec3::new(0.5, 0.75f64.sqrt(), 0.0);
        for (i, x) in [0.0, 115.0, 230.0].into_iter().enumerate() {
            curves.push(line(
                format!("B{i:02}"),
                Family::B,
                DVec3::new(x, 0.0, 0.0) - d * 150.0,
                d,
                500.0,
            ));
        }
        let (c, r) = (DVec3::new(-400.0, 100.0, 0.0), 700.0);
        let points: Vec<DVec3> = (0..=300)
            .map(|i| {
                let a = -0.35 + 0.7 * i as f64 / 300.0;
                c + DVec3::new(a.cos(), a.sin(), 0.0) * r
            })
            .collect();
        curves.push(RawCurve {
            id: "edge00".into(),
            family: Family::Edge,
            normals: Some(vec![DVec3::Z; points.len()]),
            points,
        });
        let raw = RawNetwork {
            name: "flat".into(),
            unit: Unit::Mm,
            tolerance: None,
            precision: None,
            curves,
        };
        let net = Network::new(raw, Path::new("flat.yaml")).expect("network");
        crate::analysis::analyze(&net, crate::analysis::AnalysisOptions::for_network(&net))
            .expect("analysis")
    }

    #[test]
    fn a_flat_edge_unrolls_onto_itself() {
        let an = planar_analysis();
        // The A×B nodes of the grid, all at 60°.
        let grid = crate::fabricate::washer::grid_nodes(&an);
        assert_eq!(grid.len(), 9);
        assert!(grid.iter().all(|n| (n.angle_deg - 60.0).abs() < 1e-6));
        let w = crate::fabricate::washer::washers(&steel(), &grid).expect("washers");
        assert_eq!((w.len(), w[0].id.as_str(), w[0].count), (1, "W60", 18));
        // The edge crosses the three A strips, B01 and B02.
        let edges = edge_curves(&an);
        assert_eq!(edges.len(), 1);
        let e = &edges[0];
        assert_eq!(e.nodes.len(), 5);
        assert!((e.length_mm - 700.0 * 0.7).abs() < 0.01);
        let parts = edge_strips(&steel(), &an).expect("bands");
        assert_eq!(parts.len(), 1);
        let part = &parts[0];
        assert_eq!(part.id, "E-edge00");
        // On a plane the unrolled band is congruent to the curve: hole
        // centres as far apart as the nodes.
        let world = |f: &Feature| {
            an.topology
                .nodes
                .iter()
                .find(|n| Some(n.id) == f.node)
                .map(|n| n.position_world_mm)
                .expect("node")
        };
        for f in &part.features {
            let crossing = f.crossing.as_deref().unwrap_or_default();
            assert!(crossing.starts_with('A') || crossing.starts_with('B'));
            for g in &part.features {
                let want = world(f).distance(world(g));
                let got = f.center_part_mm.distance(g.center_part_mm);
                assert!((got - want).abs() < 0.01, "{got} vs {want}");
            }
        }
        // Not mirrored: seen from the normal (+z), the part frame turns
        // like the world's x, y.
        let f = &part.features;
        let (a, b, c) = (&f[0], &f[2], &f[4]);
        let turn_part =
            (b.center_part_mm - a.center_part_mm).cross(c.center_part_mm - a.center_part_mm);
        let turn_world = (world(b) - world(a)).cross(world(c) - world(a)).z;
        assert!(turn_world.abs() > 1.0 && turn_part * turn_world > 0.0);
        assert!(is_simple(&part.outline_part_mm));
        assert!(signed_area_mm2(&part.outline_part_mm) > 0.0);
    }

    #[test]
    fn errors_name_the_edge() {
        let p = steel();
        let msg = |e: &EdgeCurve, p: &Profile| edge_strip(p, e).expect_err("must fail").to_string();
        // Radius 20 mm under half the 50 mm band.
        let m = msg(&curve("e7", 500.0, |_| 1.0 / 20.0, &[]), &p);
        assert!(
            m.starts_with("steel.yaml: strip e7: ") && m.contains("folds"),
            "{m}"
        );
        // Turning through more than a full circle: the band overlaps itself.
        let m = msg(&curve("e8", 8000.0, |_| 1.0 / 1000.0, &[]), &p);
        assert!(m.contains("overlaps itself"), "{m}");
        // A hole wider than the band.
        let mut big = p.clone();
        big.section.height_mm = 8.0;
        let m = msg(&curve("e9", 500.0, |_| 0.0, &[100.0]), &big);
        assert!(m.starts_with("steel.yaml: strip e9, node 100: "), "{m}");
        // Holes that overlap without coinciding.
        let m = msg(&curve("e10", 500.0, |_| 0.0, &[100.0, 105.0]), &p);
        assert!(m.contains("overlaps the hole of node 100"), "{m}");
        assert!(!m.contains('\n'));
    }
}
