//! The grid's shape in space, for 3D models: every lamella on its own
//! offset line as a run of frames (point, tangent, normal, across), each
//! edge strip on its curve, the tangents of both strips at every node and
//! the hardware's sizes; after the flat state, the same frames in the flat
//! layout. Computed here once from the analysis (the frames) and the
//! profile (the offsets and sizes); the model writer only places solids on
//! them. World frame, mm (the network's; z up).

use super::{Plan, PlanShape, ShapeFrame, ShapeLine, ShapeNode, ShapeStud, ShapeWasher};
use crate::analysis::lines::{LamellaLine, NetworkLines};
use crate::analysis::Analysis;
use crate::network::Family;
use crate::profile::{JointSystem, LamellaOffset, Profile};
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// How finely the shape is sampled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeOptions {
    /// Largest distance between two frames along a curve, mm (the node
    /// stations and both ends are always frames).
    pub max_step_mm: f64,
}

impl ShapeOptions {
    /// Nodes above which a network is "big": frames only at the nodes and
    /// at most [`BIG_STEP_MM`] apart (the level of detail the model writer
    /// follows too).
    pub const BIG_NODES: usize = 20_000;

    /// The sampling for a network of `nodes` nodes: 50 mm, or
    /// [`BIG_STEP_MM`] past [`ShapeOptions::BIG_NODES`].
    pub fn for_nodes(nodes: usize) -> ShapeOptions {
        ShapeOptions {
            max_step_mm: if nodes > Self::BIG_NODES {
                BIG_STEP_MM
            } else {
                50.0
            },
        }
    }
}

/// The longest step between frames of a big network, mm.
pub const BIG_STEP_MM: f64 = 1000.0;

fn arr(v: DVec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// Curve stations at which a strip is sampled: both ends, every node,
/// and evenly in between at most `step` apart, ascending.
fn stations(length_mm: f64, nodes: &[f64], step: f64) -> Vec<f64> {
    let mut knots: Vec<f64> = std::iter::once(0.0)
        .chain(nodes.iter().map(|s| s.clamp(0.0, length_mm)))
        .chain(std::iter::once(length_mm))
        .collect();
    knots.sort_by(f64::total_cmp);
    knots.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let mut out = Vec::new();
    for w in knots.windows(2) {
        let n = ((w[1] - w[0]) / step).ceil().max(1.0) as usize;
        for i in 0..n {
            out.push(w[0] + (w[1] - w[0]) * i as f64 / n as f64);
        }
    }
    out.push(*knots.last().unwrap_or(&0.0));
    out
}

/// Add the shape of an analysed network to its plan (strips in plan
/// order): the profile's lamellas (the centre line without one), edge
/// strips on their curves; then the flat layout's frames when the plan
/// holds the flat state ([`super::add_flat`] first). The lamella lines
/// the check integrated serve where given (`lines`; they are the
/// profile's), else each strip's are integrated again.
pub fn add_shape(
    plan: &mut Plan,
    an: &Analysis,
    profile: Option<&Profile>,
    lines: Option<&NetworkLines>,
    opts: ShapeOptions,
) {
    let kept = lines;
    let step = opts.max_step_mm.max(1.0);
    let lines: Vec<Vec<ShapeLine>> = an
        .strips
        .par_iter()
        .enumerate()
        .map(|(i, s)| {
            let smooth = &an.curves[s.curve];
            let node_stations: Vec<f64> = s.nodes.iter().map(|n| n.station_mm).collect();
            let curve_st = stations(s.length_mm, &node_stations, step);
            let frames: Vec<_> = curve_st.iter().map(|&c| s.frame_at(smooth, c)).collect();
            if s.family == Family::Edge {
                return vec![ShapeLine {
                    strip: i,
                    lamella: 0,
                    frames: frames
                        .iter()
                        .map(|f| ShapeFrame {
                            station_mm: f.station_mm,
                            point_mm: arr(f.point_world_mm),
                            tangent: arr(f.x),
                            normal: arr(f.z),
                            across: arr(f.y),
                        })
                        .collect(),
                    flat: None,
                }];
            }
            let on_lines: Vec<(LamellaOffset, Vec<f64>)> = match kept.and_then(|k| k.get(i)) {
                Some(sl) => sl
                    .lines
                    .iter()
                    .map(|l| l.offset)
                    .zip(sl.stations(s, smooth, &curve_st))
                    .collect(),
                None => {
                    let offsets = match profile {
                        Some(p) => p.lamella_offsets(s.family),
                        None => vec![LamellaOffset::CENTRE],
                    };
                    LamellaLine::with_stations_many(s, smooth, &offsets, &curve_st)
                        .into_iter()
                        .map(|(l, st)| (l.offset, st))
                        .collect()
                }
            };
            on_lines
                .into_iter()
                .map(|(offset, line_st)| ShapeLine {
                    strip: i,
                    lamella: offset.number,
                    frames: frames
                        .iter()
                        .zip(line_st)
                        .map(|(f, st)| ShapeFrame {
                            station_mm: st,
                            point_mm: arr(f.point_world_mm
                                + f.y * offset.dy_mm
                                + f.z * offset.dz_mm),
                            tangent: arr(f.x),
                            normal: arr(f.z),
                            across: arr(f.y),
                        })
                        .collect(),
                    flat: None,
                })
                .collect()
        })
        .collect();
    let nodes = an
        .topology
        .nodes
        .iter()
        .map(|n| ShapeNode {
            tangent_a: arr(n.tangent_a_world),
            tangent_b: arr(n.tangent_b_world),
            flat_mm: None,
        })
        .collect();
    let (height_mm, thickness_mm, washer, stud) = match profile {
        Some(p) => (
            p.section.height_mm,
            p.section.thickness_mm,
            p.washer.as_ref().map(|w| ShapeWasher {
                thickness_mm: w.thickness_mm,
                arm_length_mm: w.arm_length_mm,
                arm_width_mm: w.arm_width_mm,
                per_node: w.per_node,
            }),
            match (p.joint.system, &p.stud) {
                (JointSystem::TwoLevel, Some(st)) => Some(ShapeStud {
                    section_mm: p.section.gap_mm.max(p.section.thickness_mm),
                    length_mm: st.length_mm,
                }),
                _ => None,
            },
        ),
        None => (50.0, 2.0, None, None),
    };
    plan.shape = Some(PlanShape {
        height_mm,
        thickness_mm,
        washer,
        stud,
        lines: lines.into_iter().flatten().collect(),
        nodes,
        step_mm: step,
    });
    add_flat_frames(plan);
}

/// The flat layout's frames of every lamella line whose strip is in the
/// flat state: the layout turned (about its centroid, a rotation fitted
/// to the erected nodes seen from above) to lie under the erected grid on
/// the level of its lowest node; along each lamella its nodes' floor
/// positions joined by straight pieces (by the stations on its own
/// line), the height vertical, the offsets across as erected.
fn add_flat_frames(plan: &mut Plan) {
    let (Some(flat), Some(shape)) = (&plan.flat, &mut plan.shape) else {
        return;
    };
    let d = &flat.drawing;
    if d.nodes.is_empty() {
        return;
    }
    // Rotation and translation from the floor layout to the plan view.
    let erected: Vec<DVec2> = d
        .nodes
        .iter()
        .map(|n| {
            let p = plan.nodes[n.node].position_mm;
            DVec2::new(p[0], p[1])
        })
        .collect();
    let floor: Vec<DVec2> = d
        .nodes
        .iter()
        .map(|n| DVec2::new(n.position_mm[0], n.position_mm[1]))
        .collect();
    let k = erected.len() as f64;
    let ce = erected.iter().copied().sum::<DVec2>() / k;
    let cf = floor.iter().copied().sum::<DVec2>() / k;
    let (mut sd, mut sc) = (0.0, 0.0);
    for (e, f) in erected.iter().zip(&floor) {
        let (e, f) = (*e - ce, *f - cf);
        sd += f.dot(e);
        sc += f.perp_dot(e);
    }
    let rot = DVec2::from_angle(sc.atan2(sd));
    let z_floor = d
        .nodes
        .iter()
        .map(|n| plan.nodes[n.node].position_mm[2])
        .fold(f64::INFINITY, f64::min);
    let mut at = vec![None; plan.nodes.len()];
    for (n, f) in d.nodes.iter().zip(&floor) {
        let p = ce + rot.rotate(*f - cf);
        at[n.node] = Some(p);
        if let Some(sn) = shape.nodes.get_mut(n.node) {
            sn.flat_mm = Some([p.x, p.y, z_floor]);
        }
    }
    let in_flat: std::collections::HashSet<&str> = d.strips.iter().map(|s| s.id.as_str()).collect();
    for line in &mut shape.lines {
        let strip = &plan.strips[line.strip];
        if line.lamella == 0 || !in_flat.contains(strip.id.as_str()) {
            continue;
        }
        let Some(lam) = strip
            .lamellas
            .as_ref()
            .and_then(|ls| ls.iter().find(|l| l.lamella == line.lamella))
        else {
            continue;
        };
        // (station on the lamella's line, floor position) of its flat nodes.
        let knots: Vec<(f64, DVec2)> = lam
            .nodes
            .iter()
            .filter_map(|n| at.get(n.node).copied().flatten().map(|p| (n.station_mm, p)))
            .collect();
        if knots.len() < 2 {
            continue;
        }
        let dir = |i: usize| (knots[i + 1].1 - knots[i].1).normalize_or(DVec2::X);
        let last = knots.len() - 2;
        // The floor position at station s (the nodes joined by straight
        // pieces, continued straight past the ends) and its piece.
        let base_at = |s: f64| {
            let i = knots
                .partition_point(|k| k.0 <= s)
                .saturating_sub(1)
                .min(last);
            let (s0, p0) = knots[i];
            let (s1, p1) = knots[i + 1];
            let p = if s < s0 {
                p0 + dir(i) * (s - s0)
            } else if s > s1 {
                p1 + dir(i) * (s - s1)
            } else {
                let t = if s1 > s0 { (s - s0) / (s1 - s0) } else { 0.0 };
                p0.lerp(p1, t)
            };
            (p, i, s0, s1)
        };
        // A node off the flat problem (on an edge) lies where its lamellas
        // are continued to it.
        for n in &lam.nodes {
            if let Some(sn) = shape.nodes.get_mut(n.node) {
                if at.get(n.node).copied().flatten().is_none() && sn.flat_mm.is_none() {
                    let p = base_at(n.station_mm).0;
                    sn.flat_mm = Some([p.x, p.y, z_floor]);
                }
            }
        }
        let frames = line
            .frames
            .iter()
            .map(|f| {
                let s = f.station_mm;
                let (base, i, s0, s1) = base_at(s);
                // At a node the direction halves the turn.
                let mut t2 = dir(i);
                if (s - s1).abs() < 1e-6 && i < last {
                    t2 = (t2 + dir(i + 1)).normalize_or(t2);
                } else if (s - s0).abs() < 1e-6 && i > 0 {
                    t2 = (t2 + dir(i - 1)).normalize_or(t2);
                }
                let tangent = DVec3::new(t2.x, t2.y, 0.0);
                let normal = DVec3::Z;
                let across = normal.cross(tangent);
                let p =
                    DVec3::new(base.x, base.y, z_floor) + across * lam.dy_mm + normal * lam.dz_mm;
                ShapeFrame {
                    station_mm: s,
                    point_mm: arr(p),
                    tangent: arr(tangent),
                    normal: arr(normal),
                    across: arr(across),
                }
            })
            .collect();
        line.flat = Some(frames);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stations_hold_ends_and_nodes_and_the_step() {
        let s = stations(1000.0, &[300.0, 310.0], 100.0);
        assert_eq!(s.first(), Some(&0.0));
        assert_eq!(s.last(), Some(&1000.0));
        assert!(s.contains(&300.0) && s.contains(&310.0));
        assert!(s
            .windows(2)
            .all(|w| w[1] > w[0] && w[1] - w[0] <= 100.0 + 1e-9));
        // 0..300: 3 steps, 300..310: 1, 310..1000: 7 steps, + the end.
        assert_eq!(s.len(), 3 + 1 + 7 + 1);
    }
}
