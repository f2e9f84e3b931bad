//! Topology stage: find the nodes of a network.
//!
//! Input: the validated [`Network`] and one [`SmoothCurve`] per curve.
//! Output: [`Topology`], every crossing of an A curve with a B curve, and of
//! either with an edge curve. Candidates come from an R-tree join over
//! bounding boxes of chord chunks (inflated by the tolerance and by how far
//! the smooth curve strays from its chords); each candidate is refined on the
//! smooth curves to the point of closest approach, and a pair closer than the
//! tolerance is a node.
//!
//! Guarantees: nodes are sorted by (first curve, station on it); a curve pair
//! that crosses twice has two nodes; no two nodes of one curve pair are
//! closer than the merge distance; every node normal is a unit vector,
//! oriented consistently along each curve and with file normals where given.

use crate::geom::closest::closest_segment_params;
use crate::geom::curve::{CurvePoint, SmoothCurve};
use crate::network::{Family, Network};
use glam::DVec3;
use rayon::prelude::*;
use rstar::{RTree, RTreeObject, AABB};
use std::collections::VecDeque;

/// Nodes closer than this along a curve get a warning (a slot cannot sit there).
pub const CLOSE_NODES_MM: f64 = 5.0;

/// A curve pair with this many near-tangent contacts overlaps (runs together).
pub const OVERLAP_CONTACTS: usize = 3;

/// Near-tangent contacts of one curve pair closer than this (mm, along the
/// first curve) belong to one overlap.
pub const OVERLAP_GAP_MM: f64 = 100.0;

/// Segments per bounding box in the spatial index.
const CHUNK_SEGMENTS: usize = 8;

/// Options of the topology stage.
#[derive(Debug, Clone, Copy)]
pub struct NodeOptions {
    /// Largest gap (mm) between two curves that is still a node.
    pub tolerance_mm: f64,
    /// Crossings at a smaller angle (degrees) than this get a warning.
    pub near_tangent_deg: f64,
}

impl NodeOptions {
    /// Options with a node tolerance (mm, the largest gap that is a node) and a
    /// near-tangent warning below 15°.
    pub fn new(tolerance_mm: f64) -> NodeOptions {
        NodeOptions {
            tolerance_mm,
            near_tangent_deg: 15.0,
        }
    }
}

/// One crossing of two curves.
///
/// Guarantees: `gap_mm` ≤ the node tolerance; tangents and normal are unit
/// vectors, the normal ±(tangent_a × tangent_b) unless the file gave
/// normals, oriented consistently along every curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    /// Index of this node in `Topology::nodes`.
    pub id: usize,
    /// Curve index of the first curve (family A, or B in a B×edge node).
    pub a: usize,
    /// Curve index of the second curve (family B or edge).
    pub b: usize,
    /// Station of the node on curve `a`: arc length from its first point, mm.
    pub station_a_mm: f64,
    /// Station of the node on curve `b`, mm.
    pub station_b_mm: f64,
    /// Midpoint of the closest approach.
    pub position_world_mm: DVec3,
    /// Distance between the curves at the node.
    pub gap_mm: f64,
    /// Unit tangent of curve `a` at the node, along increasing station, world frame.
    pub tangent_a_world: DVec3,
    /// Unit tangent of curve `b` at the node, along increasing station, world frame.
    pub tangent_b_world: DVec3,
    /// Unit surface normal (from file normals, else tangent_a × tangent_b).
    pub normal_world: DVec3,
    /// Acute angle between the tangents, degrees.
    pub angle_deg: f64,
    /// Oriented angle from A's tangent line to B's tangent line,
    /// counter-clockwise about `normal`, degrees in [0, 180): above 90 when
    /// B turns from A by more than a right angle (B crosses A from the right,
    /// seen from the normal's side with A pointing forward).
    pub oriented_angle_deg: f64,
}

/// What a warning is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum WarningKind {
    /// Two curves cross at less than `NodeOptions::near_tangent_deg`.
    NearTangent,
    /// Two curves run together: no nodes taken there.
    Overlap,
    /// Two nodes of one curve closer than [`CLOSE_NODES_MM`].
    CloseNodes,
    /// A curve that crosses no other curve.
    IsolatedCurve,
}

impl WarningKind {
    /// The name plan.json uses: `near_tangent`, `overlap`, `close_nodes` or `isolated_curve`.
    pub fn as_str(self) -> &'static str {
        match self {
            WarningKind::NearTangent => "near_tangent",
            WarningKind::Overlap => "overlap",
            WarningKind::CloseNodes => "close_nodes",
            WarningKind::IsolatedCurve => "isolated_curve",
        }
    }
}

/// A warning of the topology stage: what, a one-line message, the curves
/// concerned (indices into `Network::curves`) and, where it has one, the
/// station (mm) on the first of them.
#[derive(Debug, Clone, PartialEq)]
pub struct Warning {
    /// What the warning is about.
    pub kind: WarningKind,
    /// One line for a person, naming the curves and, where there is one, the place.
    pub message: String,
    /// The curves concerned, indices into `Network::curves` (the first is the one
    /// `station_mm` is on).
    pub curves: Vec<usize>,
    /// Station on the first curve, mm, where the warning has a place.
    pub station_mm: Option<f64>,
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// Oriented angle (degrees, in [0, 180)) from the line of `ta` to the line
/// of `tb`, counter-clockwise about `normal`.
pub fn oriented_angle_deg(ta: DVec3, tb: DVec3, normal: DVec3) -> f64 {
    let theta = normal.dot(ta.cross(tb)).atan2(ta.dot(tb)).to_degrees();
    let theta = if theta < 0.0 { theta + 180.0 } else { theta };
    // atan2 of (+0, -1) is 180: the same line as 0.
    if theta >= 180.0 {
        0.0
    } else {
        theta
    }
}

/// A node seen from one of its curves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveNode {
    /// The node's index in `Topology::nodes`.
    pub node: usize,
    /// The other curve through the node (index into `Network::curves`).
    pub crossing: usize,
    /// Station of the node on this curve, mm.
    pub station_mm: f64,
    /// Where the station lies on this curve's smooth interpolant: the
    /// segment and local u that `SmoothCurve::locate_station(station_mm)`
    /// gives (found once here, so no later stage searches for it again).
    pub segment: usize,
    /// Local coordinate of the station in `segment`, [0, 1].
    pub u: f64,
}

/// The output of the topology stage.
///
/// Guarantees: nodes sorted by (first curve, second curve, station on the
/// first); `per_curve` has one list per network curve, sorted by station; no
/// two nodes of one curve pair within the merge distance (1 mm + 10 × the
/// tolerance); near-tangent contacts of a pair that run together (at least
/// [`OVERLAP_CONTACTS`] within [`OVERLAP_GAP_MM`]) are an overlap warning,
/// not nodes.
#[derive(Debug, Clone, Default)]
pub struct Topology {
    /// Every node, sorted by (first curve, second curve, station on the first);
    /// `nodes[i].id == i`.
    pub nodes: Vec<Node>,
    /// Per curve, its nodes sorted by station.
    pub per_curve: Vec<Vec<CurveNode>>,
    /// Near-tangent crossings, overlaps, close nodes and isolated curves.
    pub warnings: Vec<Warning>,
}

#[derive(Debug, Clone)]
struct Chunk {
    env: AABB<[f64; 3]>,
    curve: u32,
    first: u32,
    end: u32,
}

impl RTreeObject for Chunk {
    type Envelope = AABB<[f64; 3]>;
    fn envelope(&self) -> Self::Envelope {
        self.env
    }
}

/// Find every node of the network. `curves[i]` interpolates `net.curves[i]`.
pub fn find_nodes(net: &Network, curves: &[SmoothCurve], opts: NodeOptions) -> Topology {
    let tol = opts.tolerance_mm;
    // How far each smooth segment strays from its chord (bounded above).
    let deviation: Vec<Vec<f64>> = curves.par_iter().map(segment_deviation).collect::<Vec<_>>();
    let chunks_of = |family: Family| -> Vec<Chunk> {
        let mut out = Vec::new();
        for (ci, c) in net.curves.iter().enumerate() {
            if c.family != family {
                continue;
            }
            let pts = curves[ci].samples();
            let nseg = pts.len() - 1;
            let mut first = 0;
            while first < nseg {
                let end = (first + CHUNK_SEGMENTS).min(nseg);
                let mut lo = pts[first];
                let mut hi = pts[first];
                let mut dev: f64 = 0.0;
                for k in first..end {
                    lo = lo.min(pts[k + 1]);
                    hi = hi.max(pts[k + 1]);
                    dev = dev.max(deviation[ci][k]);
                }
                let pad = DVec3::splat(0.5 * tol + dev + 1e-9);
                out.push(Chunk {
                    env: AABB::from_corners((lo - pad).to_array(), (hi + pad).to_array()),
                    curve: ci as u32,
                    first: first as u32,
                    end: end as u32,
                });
                first = end;
            }
        }
        out
    };
    let tree_a = RTree::bulk_load(chunks_of(Family::A));
    let tree_b = RTree::bulk_load(chunks_of(Family::B));
    let tree_e = RTree::bulk_load(chunks_of(Family::Edge));

    let mut pairs: Vec<(&Chunk, &Chunk)> = Vec::new();
    for (t1, t2) in [(&tree_a, &tree_b), (&tree_a, &tree_e), (&tree_b, &tree_e)] {
        if t1.size() == 0 || t2.size() == 0 {
            continue;
        }
        pairs.extend(t1.intersection_candidates_with_other_tree(t2));
    }
    // Refine on all cores; the sort below makes the result order-independent.
    let batches: Vec<&[(&Chunk, &Chunk)]> = pairs.chunks(4096).collect();
    let mut raw: Vec<RawNode> = batches
        .par_iter()
        .map(|batch| {
            let mut out = Vec::new();
            for (c1, c2) in batch.iter() {
                collect_candidates(c1, c2, curves, &deviation, tol, &mut out);
            }
            out
        })
        .collect::<Vec<_>>()
        .into_iter()
        .flatten()
        .collect();
    // Deduplicate: sort by curve pair and station, merge near-identical hits.
    raw.sort_by(|p, q| {
        (p.a, p.b)
            .cmp(&(q.a, q.b))
            .then(p.sa.total_cmp(&q.sa))
            .then(p.sb.total_cmp(&q.sb))
    });
    let merge_mm = 1.0 + 10.0 * tol;
    // On a closed curve, stations 0 and L are one point.
    let closed: Vec<Option<f64>> = curves
        .iter()
        .map(|c| {
            let s = c.samples();
            (s.len() > 2 && s[0].distance(s[s.len() - 1]) <= tol).then(|| c.length_mm())
        })
        .collect();
    let apart = |s1: f64, s2: f64, ci: usize| {
        let d = (s1 - s2).abs();
        match closed[ci] {
            Some(len) => d.min((len - d).abs()),
            None => d,
        }
    };
    let mut kept: Vec<RawNode> = Vec::with_capacity(raw.len() / 2);
    for r in raw {
        let dup = kept
            .iter()
            .rev()
            .take_while(|k| k.a == r.a && k.b == r.b)
            .position(|k| apart(k.sa, r.sa, r.a) < merge_mm && apart(k.sb, r.sb, r.b) < merge_mm);
        match dup {
            Some(back) => {
                let idx = kept.len() - 1 - back;
                if r.gap < kept[idx].gap {
                    kept[idx] = r;
                }
            }
            None => kept.push(r),
        }
    }
    build_topology(net, curves, kept, opts)
}

#[derive(Debug, Clone, Copy)]
struct RawNode {
    a: usize,
    b: usize,
    sa: f64,
    sb: f64,
    gap: f64,
}

/// Upper bound on the distance between each smooth segment and its chord.
fn segment_deviation(c: &SmoothCurve) -> Vec<f64> {
    let pts = c.samples();
    (0..pts.len() - 1)
        .map(|k| {
            let mut worst: f64 = 0.0;
            let piece = c.piece(k);
            for u in [0.25, 0.5, 0.75] {
                let p = piece.value(u);
                let chord = pts[k].lerp(pts[k + 1], u);
                worst = worst.max(p.distance(chord));
            }
            1.5 * worst
        })
        .collect()
}

fn collect_candidates(
    c1: &Chunk,
    c2: &Chunk,
    curves: &[SmoothCurve],
    deviation: &[Vec<f64>],
    tol: f64,
    out: &mut Vec<RawNode>,
) {
    let (ia, ib) = (c1.curve as usize, c2.curve as usize);
    let (pa, pb) = (curves[ia].samples(), curves[ib].samples());
    for i in c1.first as usize..c1.end as usize {
        let (a0, a1) = (pa[i], pa[i + 1]);
        let reach_a = deviation[ia][i] + tol;
        let (alo, ahi) = (
            a0.min(a1) - DVec3::splat(reach_a),
            a0.max(a1) + DVec3::splat(reach_a),
        );
        for j in c2.first as usize..c2.end as usize {
            let (b0, b1) = (pb[j], pb[j + 1]);
            let reach = reach_a + deviation[ib][j];
            let (blo, bhi) = (b0.min(b1), b0.max(b1));
            if blo.cmpgt(ahi + DVec3::splat(deviation[ib][j])).any()
                || bhi.cmplt(alo - DVec3::splat(deviation[ib][j])).any()
            {
                continue;
            }
            let (u, v, d2) = closest_segment_params(a0, a1, b0, b1);
            if d2 > reach * reach {
                continue;
            }
            let (ta, tb) = (
                curves[ia].sample_param(i)
                    + u * (curves[ia].sample_param(i + 1) - curves[ia].sample_param(i)),
                curves[ib].sample_param(j)
                    + v * (curves[ib].sample_param(j + 1) - curves[ib].sample_param(j)),
            );
            if let Some((ka, ua, kb, ub, gap)) = refine(&curves[ia], &curves[ib], ta, tb) {
                if gap <= tol {
                    out.push(RawNode {
                        a: ia,
                        b: ib,
                        sa: curves[ia].station_at(ka, ua),
                        sb: curves[ib].station_at(kb, ub),
                        gap,
                    });
                }
            }
        }
    }
}

/// Gauss–Newton on the chord parameters of both smooth curves towards their
/// closest approach, clamped to the curves. Returns (segment, u) on each
/// curve and the distance.
fn refine(
    ca: &SmoothCurve,
    cb: &SmoothCurve,
    ta0: f64,
    tb0: f64,
) -> Option<(usize, f64, usize, f64, f64)> {
    let ha = ca.hermite();
    let hb = cb.hermite();
    let (la, lb) = (*ha.knots().last()?, *hb.knots().last()?);
    let (mut ta, mut tb) = (ta0, tb0);
    for _ in 0..60 {
        let ja = ha.jet(ta);
        let jb = hb.jet(tb);
        let d = ja.value - jb.value;
        // Minimise |d + A Δa − B Δb|².
        let (aa, bb, ab) = (ja.d1.dot(ja.d1), jb.d1.dot(jb.d1), ja.d1.dot(jb.d1));
        let (ra, rb) = (-d.dot(ja.d1), d.dot(jb.d1));
        // Levenberg damping keeps near-tangent crossings stable.
        let damp = 1e-9 * (aa + bb);
        let m11 = aa + damp;
        let m22 = bb + damp;
        let m12 = -ab;
        let det = m11 * m22 - m12 * m12;
        if !(det.is_finite()) || det <= 0.0 {
            break;
        }
        let da = (ra * m22 - m12 * rb) / det;
        let db = (m11 * rb - m12 * ra) / det;
        let (na, nb) = ((ta + da).clamp(0.0, la), (tb + db).clamp(0.0, lb));
        let moved = (na - ta).abs() + (nb - tb).abs();
        ta = na;
        tb = nb;
        if moved < 1e-11 * (1.0 + la + lb) {
            break;
        }
    }
    let (ka, ua) = ha.locate(ta);
    let (kb, ub) = hb.locate(tb);
    let gap = ha.jet_at(ka, ua).value.distance(hb.jet_at(kb, ub).value);
    gap.is_finite().then_some((ka, ua, kb, ub, gap))
}

/// A raw node's two stations located on their curves: on `a`, the point
/// and tangent and the (segment, u) they lie at, then the same on `b`.
type Located = (CurvePoint, (usize, f64), CurvePoint, (usize, f64));

fn build_topology(
    net: &Network,
    curves: &[SmoothCurve],
    raw: Vec<RawNode>,
    opts: NodeOptions,
) -> Topology {
    let mut warnings = Vec::new();
    // Each station located once on its curve, for the angle, the node and
    // every later stage (`CurveNode::segment`, `CurveNode::u`).
    let located: Vec<Located> = raw
        .iter()
        .map(|r| {
            let (la, lb) = (
                curves[r.a].locate_station(r.sa),
                curves[r.b].locate_station(r.sb),
            );
            (
                curves[r.a].at_located(r.sa, la),
                la,
                curves[r.b].at_located(r.sb, lb),
                lb,
            )
        })
        .collect();
    // Curves that run together (several near-tangent contacts of one pair)
    // overlap: no node is taken there, one warning says where.
    let angle_of = |i: usize| {
        let (ta, tb) = (located[i].0.tangent, located[i].2.tangent);
        ta.dot(tb).abs().min(1.0).acos().to_degrees()
    };
    let mut keep = vec![true; raw.len()];
    let mut start = 0;
    while start < raw.len() {
        let end = start
            + raw[start..]
                .iter()
                .take_while(|r| (r.a, r.b) == (raw[start].a, raw[start].b))
                .count();
        // Runs of consecutive near-tangent contacts, each within the overlap
        // gap of the previous one.
        let mut run: Vec<usize> = Vec::new();
        let flush = |run: &mut Vec<usize>, keep: &mut Vec<bool>, warnings: &mut Vec<Warning>| {
            if run.len() >= OVERLAP_CONTACTS {
                let (lo, hi) = (raw[run[0]].sa, raw[run[run.len() - 1]].sa);
                let (a, b) = (raw[start].a, raw[start].b);
                warnings.push(Warning {
                    kind: WarningKind::Overlap,
                    message: format!(
                        "curves {} and {} overlap from station {lo:.1} to {hi:.1} mm of {}: no nodes taken there",
                        net.curves[a].id, net.curves[b].id, net.curves[a].id
                    ),
                    curves: vec![a, b],
                    station_mm: Some(lo),
                });
                for &i in run.iter() {
                    keep[i] = false;
                }
            }
            run.clear();
        };
        for i in start..end {
            if angle_of(i) < opts.near_tangent_deg {
                if run
                    .last()
                    .is_some_and(|&j| raw[i].sa - raw[j].sa > OVERLAP_GAP_MM)
                {
                    flush(&mut run, &mut keep, &mut warnings);
                }
                run.push(i);
            } else {
                flush(&mut run, &mut keep, &mut warnings);
            }
        }
        flush(&mut run, &mut keep, &mut warnings);
        start = end;
    }
    let (raw, located): (Vec<RawNode>, Vec<_>) = raw
        .into_iter()
        .zip(located)
        .zip(keep)
        .filter(|(_, k)| *k)
        .map(|(r, _)| r)
        .unzip();
    let mut nodes: Vec<Node> = raw
        .iter()
        .zip(&located)
        .enumerate()
        .map(|(id, (r, &(pa, la, pb, lb)))| {
            let cos = pa.tangent.dot(pb.tangent).abs().min(1.0);
            let angle_deg = cos.acos().to_degrees();
            let cross = pa.tangent.cross(pb.tangent);
            let normal = file_normal(net, r.a, la)
                .or_else(|| file_normal(net, r.b, lb))
                .map(|n| {
                    if cross.length() > 1e-9 && cross.dot(n) < 0.0 {
                        -cross.normalize()
                    } else if cross.length() > 1e-9 {
                        cross.normalize()
                    } else {
                        n
                    }
                })
                .unwrap_or_else(|| cross.try_normalize().unwrap_or(DVec3::Z));
            Node {
                id,
                a: r.a,
                b: r.b,
                station_a_mm: r.sa,
                station_b_mm: r.sb,
                position_world_mm: 0.5 * (pa.point_mm + pb.point_mm),
                gap_mm: r.gap,
                tangent_a_world: pa.tangent,
                tangent_b_world: pb.tangent,
                normal_world: normal,
                angle_deg,
                oriented_angle_deg: 0.0, // once the normals are oriented
            }
        })
        .collect();
    let mut per_curve: Vec<Vec<CurveNode>> = vec![Vec::new(); net.curves.len()];
    for (n, &(_, (ka, ua), _, (kb, ub))) in nodes.iter().zip(&located) {
        per_curve[n.a].push(CurveNode {
            node: n.id,
            crossing: n.b,
            station_mm: n.station_a_mm,
            segment: ka,
            u: ua,
        });
        per_curve[n.b].push(CurveNode {
            node: n.id,
            crossing: n.a,
            station_mm: n.station_b_mm,
            segment: kb,
            u: ub,
        });
    }
    for list in &mut per_curve {
        list.sort_by(|p, q| {
            p.station_mm
                .total_cmp(&q.station_mm)
                .then(p.node.cmp(&q.node))
        });
    }
    orient_normals(net, &mut nodes, &per_curve);
    for n in &mut nodes {
        n.oriented_angle_deg =
            oriented_angle_deg(n.tangent_a_world, n.tangent_b_world, n.normal_world);
    }
    for n in &nodes {
        if n.angle_deg < opts.near_tangent_deg {
            warnings.push(Warning {
                kind: WarningKind::NearTangent,
                message: format!(
                    "node {} ({} × {}): near-tangent crossing at {:.2}°; its station is ill-defined",
                    n.id, net.curves[n.a].id, net.curves[n.b].id, n.angle_deg
                ),
                curves: vec![n.a, n.b],
                station_mm: Some(n.station_a_mm),
            });
        }
    }
    for (ci, list) in per_curve.iter().enumerate() {
        if list.is_empty() {
            warnings.push(Warning {
                kind: WarningKind::IsolatedCurve,
                message: format!("curve {}: crosses no other curve", net.curves[ci].id),
                curves: vec![ci],
                station_mm: None,
            });
        }
        for w in list.windows(2) {
            let gap = w[1].station_mm - w[0].station_mm;
            if gap < CLOSE_NODES_MM {
                warnings.push(Warning {
                    kind: WarningKind::CloseNodes,
                    message: format!(
                        "curve {}: nodes {} and {} are only {gap:.2} mm apart (crossing {} and {} at one point?)",
                        net.curves[ci].id,
                        w[0].node,
                        w[1].node,
                        net.curves[w[0].crossing].id,
                        net.curves[w[1].crossing].id
                    ),
                    curves: vec![ci, w[0].crossing, w[1].crossing],
                    station_mm: Some(w[0].station_mm),
                });
            }
        }
    }
    Topology {
        nodes,
        per_curve,
        warnings,
    }
}

/// The file normal of curve `ci` at a located station (segment k, local u),
/// if the file gave normals.
fn file_normal(net: &Network, ci: usize, (k, u): (usize, f64)) -> Option<DVec3> {
    let normals = net.curves[ci].normals_world.as_ref()?;
    let n = normals[k].lerp(normals[k + 1], u);
    n.try_normalize()
}

/// Orient node normals consistently: nodes whose normal came from a file keep
/// it; the others follow their neighbours along each curve (breadth first),
/// each component seeded to point up (+z) where nothing else decides.
fn orient_normals(net: &Network, nodes: &mut [Node], per_curve: &[Vec<CurveNode>]) {
    let n = nodes.len();
    let fixed: Vec<bool> = nodes
        .iter()
        .map(|nd| {
            net.curves[nd.a].normals_world.is_some() || net.curves[nd.b].normals_world.is_some()
        })
        .collect();
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); n];
    for list in per_curve {
        for w in list.windows(2) {
            neighbours[w[0].node].push(w[1].node);
            neighbours[w[1].node].push(w[0].node);
        }
    }
    let mut done = vec![false; n];
    let mut queue = VecDeque::new();
    let seeds: Vec<usize> = (0..n)
        .filter(|&i| fixed[i])
        .chain((0..n).filter(|&i| !fixed[i]))
        .collect();
    for seed in seeds {
        if done[seed] {
            continue;
        }
        if !fixed[seed] {
            let nm = nodes[seed].normal_world;
            let up = if nm.z.abs() > 1e-9 {
                nm.z
            } else if nm.y.abs() > 1e-9 {
                nm.y
            } else {
                nm.x
            };
            if up < 0.0 {
                nodes[seed].normal_world = -nm;
            }
        }
        done[seed] = true;
        queue.push_back(seed);
        while let Some(i) = queue.pop_front() {
            for &j in &neighbours[i] {
                if done[j] {
                    continue;
                }
                if !fixed[j] && nodes[j].normal_world.dot(nodes[i].normal_world) < 0.0 {
                    nodes[j].normal_world = -nodes[j].normal_world;
                }
                done[j] = true;
                queue.push_back(j);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::network::{RawCurve, RawNetwork, Unit};
    use std::path::Path;

    /// A straight curve from `p0` to `p1` in `n` equal steps.
    fn line(id: &str, family: Family, p0: DVec3, p1: DVec3, n: usize) -> RawCurve {
        RawCurve {
            id: id.into(),
            family,
            points: (0..=n).map(|k| p0.lerp(p1, k as f64 / n as f64)).collect(),
            normals: None,
        }
    }

    /// A0: the straight curve from the origin to (1000, 0, 0) in `n` steps.
    fn a0_along_x(n: usize) -> RawCurve {
        line(
            "A0",
            Family::A,
            DVec3::ZERO,
            DVec3::new(1000.0, 0.0, 0.0),
            n,
        )
    }

    /// The network of `curves` (tolerance 0.5 mm), its smooth curves and
    /// its topology.
    fn topology(curves: Vec<RawCurve>) -> (Network, Topology) {
        let raw = RawNetwork {
            name: "t".into(),
            unit: Unit::Mm,
            tolerance: Some(0.5),
            precision: None,
            curves,
        };
        let net = Network::new(raw, Path::new("t.yaml")).expect("valid network");
        let smooth: Vec<SmoothCurve> = net
            .curves
            .iter()
            .map(|c| SmoothCurve::new(&c.points_world_mm))
            .collect();
        let t = find_nodes(&net, &smooth, NodeOptions::new(net.tolerance_mm));
        (net, t)
    }

    #[test]
    fn two_straight_lines_cross_once_at_the_known_station_and_angle() {
        // A0 along +x from the origin; B0 at 60° to it through (300, 0, 0),
        // starting 400 mm before the crossing, 0.2 mm above A0.
        let d = DVec3::new(0.5, 0.75f64.sqrt(), 0.0);
        let lift = DVec3::new(0.0, 0.0, 0.2);
        let b0 = DVec3::new(300.0, 0.0, 0.0) - 400.0 * d + lift;
        let (_, t) = topology(vec![
            a0_along_x(20),
            line("B0", Family::B, b0, b0 + 700.0 * d, 14),
        ]);
        assert_eq!(t.nodes.len(), 1);
        let n = &t.nodes[0];
        assert_eq!((n.id, n.a, n.b), (0, 0, 1));
        assert!((n.station_a_mm - 300.0).abs() < 1e-9, "{}", n.station_a_mm);
        assert!((n.station_b_mm - 400.0).abs() < 1e-9, "{}", n.station_b_mm);
        assert!((n.gap_mm - 0.2).abs() < 1e-9, "{}", n.gap_mm);
        // The midpoint of the closest approach: (300, 0, 0.1).
        assert!(n.position_world_mm.distance(DVec3::new(300.0, 0.0, 0.1)) < 1e-9);
        assert!((n.angle_deg - 60.0).abs() < 1e-9, "{}", n.angle_deg);
        // x × d = +z: the normal, seeded upwards; B turns 60° counter-
        // clockwise from A about it.
        assert!(n.normal_world.distance(DVec3::Z) < 1e-12);
        assert!((n.oriented_angle_deg - 60.0).abs() < 1e-9);
        assert!(n.tangent_a_world.distance(DVec3::X) < 1e-12);
        assert!(n.tangent_b_world.distance(d) < 1e-12);
        // Each curve lists the node at its own station.
        assert_eq!(t.per_curve[0].len(), 1);
        assert_eq!(t.per_curve[1][0].crossing, 0);
        assert!((t.per_curve[1][0].station_mm - 400.0).abs() < 1e-9);
        assert!(t.warnings.is_empty(), "{:?}", t.warnings);
    }

    #[test]
    fn a_line_crossing_from_the_right_turns_past_a_right_angle() {
        // B0 at 120° to A0 (from the right, seen from above): the acute
        // angle is 60°, the oriented angle about +z 120°.
        let d = DVec3::new(-0.5, 0.75f64.sqrt(), 0.0);
        let b0 = DVec3::new(500.0, 0.0, 0.0) - 300.0 * d;
        let (_, t) = topology(vec![
            a0_along_x(20),
            line("B0", Family::B, b0, b0 + 600.0 * d, 12),
        ]);
        let n = &t.nodes[0];
        assert!((n.angle_deg - 60.0).abs() < 1e-9, "{}", n.angle_deg);
        assert!((n.oriented_angle_deg - 120.0).abs() < 1e-9);
        assert!((n.station_a_mm - 500.0).abs() < 1e-9);
        assert!((n.station_b_mm - 300.0).abs() < 1e-9);
    }

    #[test]
    fn a_pair_running_together_is_an_overlap_not_nodes() {
        // B0 weaves along A0 from x = 200 to 520 mm, 0.2 mm to either side
        // every 40 mm: it crosses A0 at x ≈ 220, 260, …, 500 mm at about
        // atan(0.4 / 40) = 0.57°, eight near-tangent contacts 40 mm apart
        // (within the 100 mm of one overlap). B1 crosses A0 at x = 800 mm
        // at right angles.
        let weave = RawCurve {
            id: "B0".into(),
            family: Family::B,
            points: (0..=8)
                .map(|k| {
                    DVec3::new(
                        200.0 + 40.0 * k as f64,
                        if k % 2 == 0 { 0.2 } else { -0.2 },
                        0.0,
                    )
                })
                .collect(),
            normals: None,
        };
        let (_, t) = topology(vec![
            a0_along_x(50),
            weave,
            line(
                "B1",
                Family::B,
                DVec3::new(800.0, -200.0, 0.0),
                DVec3::new(800.0, 200.0, 0.0),
                8,
            ),
        ]);
        // Only the right-angle node.
        assert_eq!(t.nodes.len(), 1, "{:?}", t.nodes);
        assert_eq!(t.nodes[0].b, 2);
        assert!((t.nodes[0].station_a_mm - 800.0).abs() < 1e-9);
        let overlaps: Vec<&Warning> = t
            .warnings
            .iter()
            .filter(|w| w.kind == WarningKind::Overlap)
            .collect();
        assert_eq!(overlaps.len(), 1, "{:?}", t.warnings);
        let w = overlaps[0];
        assert_eq!(w.curves, vec![0, 1]);
        // From the first contact (x ≈ 220 mm; the smooth curve's end
        // derivatives move the outer two crossings a little) to the last
        // (x ≈ 500 mm), on A0.
        let from = w.station_mm.expect("a station");
        assert!((200.0..230.0).contains(&from), "{from}");
        let to: f64 = w
            .message
            .split(" to ")
            .nth(1)
            .and_then(|r| r.split(' ').next())
            .and_then(|v| v.parse().ok())
            .expect("the last station");
        assert!((490.0..520.0).contains(&to), "{}", w.message);
        assert!(
            w.message
                .starts_with("curves A0 and B0 overlap from station ")
                && w.message.ends_with(" mm of A0: no nodes taken there"),
            "{}",
            w.message
        );
        // B0 has no node left: it is named as crossing nothing.
        assert!(t
            .warnings
            .iter()
            .any(|w| w.kind == WarningKind::IsolatedCurve && w.curves == vec![1]));
        assert_eq!(t.warnings.len(), 2, "{:?}", t.warnings);
    }

    #[test]
    fn a_single_near_tangent_crossing_is_a_node_with_a_warning() {
        // B0 crosses A0 at 5° at x = 500 mm: one contact, so a node (at
        // stations 500 and 300 mm) and a near-tangent warning, no overlap.
        let d = DVec3::new(5f64.to_radians().cos(), 5f64.to_radians().sin(), 0.0);
        let b0 = DVec3::new(500.0, 0.0, 0.0) - 300.0 * d;
        let (_, t) = topology(vec![
            a0_along_x(20),
            line("B0", Family::B, b0, b0 + 600.0 * d, 30),
        ]);
        assert_eq!(t.nodes.len(), 1);
        let n = &t.nodes[0];
        assert!((n.angle_deg - 5.0).abs() < 1e-9, "{}", n.angle_deg);
        assert!((n.station_a_mm - 500.0).abs() < 1e-6);
        assert!((n.station_b_mm - 300.0).abs() < 1e-6);
        let kinds: Vec<WarningKind> = t.warnings.iter().map(|w| w.kind).collect();
        assert_eq!(kinds, vec![WarningKind::NearTangent]);
    }
}
