//! Edge joints: every node where a lamella strip ends on an edge band has
//! its end slot in every lamella of the strip and (bolted) its hole in the
//! band, at the node's stations as the analysis found them; every cut of a
//! band has its splice plate with the same holes as the two pieces; the
//! takeoff's edge bolts are the edge nodes counted from the topology.

use crate::support::{analysed_sample, profile};
use lamella::analysis::Analysis;
use lamella::fabricate::fabricate;
use lamella::fabricate::hardware::HardwareKind;
use lamella::fabricate::part::{FeatureKind, HoleUse, Part, PartKind, SlotEdge};
use lamella::network::{Family, Network};
use lamella::profile::{EdgeJointKind, Profile};
use std::collections::HashMap;

/// An edge node as the topology has it: node id, the strip's curve index,
/// its station on the strip, the edge's id and the station on the edge.
struct EdgeNode {
    id: usize,
    strip: String,
    strip_station_mm: f64,
    strip_length_mm: f64,
    edge: String,
    edge_station_mm: f64,
}

/// The nodes where an A or B curve meets an edge curve, straight from the
/// topology (not from the parts).
fn edge_nodes(net: &Network, an: &Analysis) -> Vec<EdgeNode> {
    an.topology
        .nodes
        .iter()
        .filter_map(|n| {
            let (fa, fb) = (net.curves[n.a].family, net.curves[n.b].family);
            let (strip, s, edge, e) = match (fa, fb) {
                (Family::A | Family::B, Family::Edge) => (n.a, n.station_a_mm, n.b, n.station_b_mm),
                (Family::Edge, Family::A | Family::B) => (n.b, n.station_b_mm, n.a, n.station_a_mm),
                _ => return None,
            };
            let length = an.strips.iter().find(|x| x.curve == strip)?.length_mm;
            Some(EdgeNode {
                id: n.id,
                strip: net.curves[strip].id.clone(),
                strip_station_mm: s,
                strip_length_mm: length,
                edge: net.curves[edge].id.clone(),
                edge_station_mm: e,
            })
        })
        .collect()
}

fn kit(sample: &str, p: &Profile) -> (Vec<EdgeNode>, lamella::fabricate::Kit) {
    let (net, an) = analysed_sample(sample);
    let nodes = edge_nodes(&net, &an);
    let kit = fabricate(&net, &an, p, None, Default::default()).expect("kit");
    (nodes, kit)
}

#[test]
fn every_edge_node_has_its_end_slot_and_its_band_hole() {
    let p = profile("steel-1.5");
    assert_eq!(p.edge_joint_kind(), EdgeJointKind::Bolt);
    let (nodes, kit) = kit("enneper-4m", &p);
    assert_eq!(nodes.len(), 44);
    let allowance = p.section.end_allowance_mm;
    let h = p.section.height_mm;
    for n in &nodes {
        // The strip ends on the edge: the node is at one of its ends.
        let at_start = n.strip_station_mm < 0.5 * n.strip_length_mm;
        let from_end = if at_start {
            n.strip_station_mm
        } else {
            n.strip_length_mm - n.strip_station_mm
        };
        assert!(from_end.abs() < 0.01, "node {} at {from_end}", n.id);
        // Both lamellas of the strip: an end slot at the node, the
        // allowance in from the piece's end, around the band's height.
        for lamella in 1..=2 {
            let slot = kit
                .parts
                .iter()
                .filter(|q| q.strip.as_deref() == Some(&n.strip) && q.lamella == Some(lamella))
                .flat_map(|q| q.features.iter().map(move |f| (q, f)))
                .find(|(_, f)| f.node == Some(n.id))
                .unwrap_or_else(|| panic!("node {}: no feature in {}-{lamella}", n.id, n.strip));
            let (part, f) = slot;
            assert_eq!((f.kind, f.edge), (FeatureKind::Slot, Some(SlotEdge::End)));
            assert_eq!(f.crossing.as_deref(), Some(n.edge.as_str()));
            let x_want = if at_start {
                allowance
            } else {
                part.length_mm - allowance
            };
            assert!(
                (f.center_part_mm.x - x_want).abs() < 0.01,
                "{}: {} vs {x_want}",
                part.id,
                f.center_part_mm.x
            );
            // The slot holds the band: the surface (mid-height) inside its
            // opening, and it reaches past the band's far edge (h/2 over
            // sin φ ≥ h/2 from the node).
            let (y0, y1) = (
                f.center_part_mm.y - 0.5 * f.width_mm,
                f.center_part_mm.y + 0.5 * f.width_mm,
            );
            assert!(y0 < 0.5 * h - 0.75 && y1 > 0.5 * h + 0.75, "{}", part.id);
            assert!(f.depth_mm > allowance + 0.5 * h, "{}", part.id);
            // The outline is open at that end across the band's height.
            let end_x = if at_start { 0.0 } else { part.length_mm };
            let closed_at_mid = part.outline_part_mm.windows(2).any(|w| {
                (w[0].x - end_x).abs() < 1e-9
                    && (w[1].x - end_x).abs() < 1e-9
                    && w[0].y.min(w[1].y) < 0.5 * h
                    && w[0].y.max(w[1].y) > 0.5 * h
            });
            assert!(
                !closed_at_mid,
                "{}: its end is closed at mid-height",
                part.id
            );
        }
        // The band: a 9 mm hole (M8 + 1) at the node's station on the edge.
        let (band, hole) = kit
            .parts
            .iter()
            .filter(|q| q.kind == PartKind::EdgeStrip && q.strip.as_deref() == Some(&n.edge))
            .flat_map(|q| q.features.iter().map(move |f| (q, f)))
            .find(|(_, f)| f.node == Some(n.id))
            .unwrap_or_else(|| panic!("node {}: no hole in the band {}", n.id, n.edge));
        assert_eq!(hole.hole_use, Some(HoleUse::EdgeNode));
        assert_eq!(hole.width_mm, 9.0);
        let station = hole.station_mm.expect("station");
        assert!(
            (station - n.edge_station_mm).abs() < 0.01,
            "node {}: {station} vs {}",
            n.id,
            n.edge_station_mm
        );
        // On the band's centre line: h/2 from both long edges.
        let d = distance_to_outline(band, hole.center_part_mm);
        assert!((d - 0.5 * h).abs() < 0.01, "{}: {d}", band.id);
    }
}

/// Distance from a point to a part's outline, mm.
fn distance_to_outline(p: &Part, q: kurbo::Point) -> f64 {
    let o = &p.outline_part_mm;
    (0..o.len())
        .map(|i| {
            let (a, b) = (o[i], o[(i + 1) % o.len()]);
            let ab = b - a;
            let t = ((q - a).dot(ab) / ab.hypot2()).clamp(0.0, 1.0);
            q.distance(a + ab * t)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Every band piece joint: piece k ends where piece k + 1 starts, and the
/// plate `SP-<edge>.k` is centred on that cut with the holes of both pieces
/// near it, at the same stations and the same distances apart.
fn assert_band_joints(kit: &lamella::fabricate::Kit, p: &Profile) -> usize {
    let sp = p.splice.as_ref().expect("splice");
    let per_joint = 2 * sp.bolts_per_side as usize;
    let mut pieces: HashMap<&str, Vec<&Part>> = HashMap::new();
    for q in kit.parts.iter().filter(|q| q.kind == PartKind::EdgeStrip) {
        pieces
            .entry(q.strip.as_deref().unwrap())
            .or_default()
            .push(q);
    }
    let mut joints = 0;
    for (edge, list) in pieces {
        for (k, w) in list.windows(2).enumerate() {
            let (a, b) = (w[0], w[1]);
            assert_eq!(a.id, format!("E-{edge}.{}", k + 1));
            let cut = b.station_start_mm.unwrap();
            let plate = kit
                .parts
                .iter()
                .find(|q| q.id == format!("SP-{edge}.{}", k + 1))
                .unwrap_or_else(|| panic!("no plate between {} and {}", a.id, b.id));
            assert_eq!(plate.kind, PartKind::SplicePlate);
            assert!(
                (plate.station_start_mm.unwrap() + 0.5 * sp.plate_length_mm - cut).abs() < 1e-6
            );
            let splice = |q: &Part| -> Vec<(f64, kurbo::Point)> {
                q.features
                    .iter()
                    .filter(|f| f.hole_use == Some(HoleUse::Splice))
                    .filter(|f| (f.station_mm.unwrap() - cut).abs() < 0.5 * sp.plate_length_mm)
                    .map(|f| (f.station_mm.unwrap(), f.center_part_mm))
                    .collect()
            };
            let (in_a, in_b, in_plate) = (splice(a), splice(b), splice(plate));
            assert_eq!(in_a.len(), per_joint / 2, "{}", a.id);
            assert_eq!(in_b.len(), per_joint / 2, "{}", b.id);
            assert_eq!(in_plate.len(), per_joint, "{}", plate.id);
            // The plate's holes are the pieces' holes: same stations, and
            // the same distances apart on each side.
            let mut both: Vec<f64> = in_a.iter().chain(&in_b).map(|x| x.0).collect();
            both.sort_by(f64::total_cmp);
            for (s, (t, _)) in both.iter().zip(&in_plate) {
                assert!((s - t).abs() < 1e-6, "{}: {s} vs {t}", plate.id);
            }
            for side in [&in_a, &in_b] {
                for i in 0..side.len() {
                    for j in i + 1..side.len() {
                        let at =
                            |s: f64| in_plate.iter().find(|x| (x.0 - s).abs() < 1e-6).unwrap().1;
                        let want = side[i].1.distance(side[j].1);
                        let got = at(side[i].0).distance(at(side[j].0));
                        assert!((got - want).abs() < 0.01, "{}: {got} vs {want}", plate.id);
                    }
                }
            }
            joints += 1;
        }
    }
    joints
}

#[test]
fn every_band_joint_has_its_plate_and_the_takeoff_counts_the_bolts() {
    let p = profile("steel-1.5");
    let (nodes, kit) = kit("enneper-4m", &p);
    let joints = assert_band_joints(&kit, &p);
    // The four edges of the 4 m Enneper patch are each longer than the
    // 2980 mm usable sheet: one joint each.
    assert_eq!(joints, 4);
    let bolts = |item: &str| {
        kit.summary
            .hardware
            .iter()
            .find(|x| x.item == item && x.kind == HardwareKind::Bolt)
            .map_or(0, |x| x.count)
    };
    // One edge bolt per edge node; two bolts a side per band splice.
    assert_eq!(bolts("edge bolt"), nodes.len() as u64);
    assert_eq!(bolts("band splice bolt"), 4 * joints as u64);
    // The edge bolt: the 50 mm lamella height clamped between two M8
    // washers (1.6 mm), an M8 nut (6.8 mm) and two 1.25 mm pitches:
    // 62.5 mm, so M8 × 65 of the ISO 4017 series.
    let edge = kit
        .summary
        .hardware
        .iter()
        .find(|x| x.item == "edge bolt")
        .unwrap();
    assert_eq!(edge.designation, "M8 × 65 ISO 4017 8.8");
}

#[test]
fn a_band_that_bows_too_much_is_split_and_spliced() {
    let mut p = profile("steel-1.5");
    p.edge_joint.max_band_bow_mm = Some(5.0);
    let (_, kit) = kit("enneper-4m", &p);
    let bands: Vec<&Part> = kit
        .parts
        .iter()
        .filter(|q| q.kind == PartKind::EdgeStrip)
        .collect();
    assert!(bands.len() > 8, "{}", bands.len());
    for b in &bands {
        assert!(
            b.height_mm <= p.section.height_mm + 5.0 + 1e-6,
            "{}: {}",
            b.id,
            b.height_mm
        );
    }
    assert_eq!(assert_band_joints(&kit, &p), bands.len() - 4);
}

#[test]
fn an_end_slot_alone_has_no_band_hole_and_no_edge_bolt() {
    // Poplar: no node bolt, so no edge bolt: the end slots alone (a rebate
    // at each lamella's edge on the surface, the levels standing off it).
    let p = profile("poplar-ply-4");
    assert_eq!(p.edge_joint_kind(), EdgeJointKind::Slot);
    let (nodes, kit) = kit("enneper-4m", &p);
    assert!(kit
        .parts
        .iter()
        .filter(|q| q.kind == PartKind::EdgeStrip)
        .all(|q| q
            .features
            .iter()
            .all(|f| f.hole_use != Some(HoleUse::EdgeNode))));
    assert!(kit.summary.hardware.iter().all(|x| x.item != "edge bolt"));
    let slots = kit
        .parts
        .iter()
        .flat_map(|q| &q.features)
        .filter(|f| f.edge == Some(SlotEdge::End))
        .count();
    assert_eq!(slots, 2 * nodes.len());
}

#[test]
fn a_bolted_edge_joint_needs_a_gap_for_its_bolt() {
    let text =
        std::fs::read_to_string(crate::support::root().join("profiles/beech-veneer.yaml")).unwrap();
    // The veneer profile has an `edge_joint:` section: the bolt goes into it.
    assert!(text.contains("\nedge_joint:\n"));
    let text = text.replace(
        "\nedge_joint:\n",
        "\nedge_joint:\n  kind: bolt\n  bolt_diameter_mm: 2.0\n",
    );
    let e = lamella::formats::read::profile_file::parse(&text, std::path::Path::new("v.yaml"))
        .expect_err("single lamellas have no gap")
        .to_string();
    assert!(e.contains("edge_joint.kind") && !e.contains('\n'), "{e}");
}

/// Where a halving slot runs into an end slot, the two become one rebate
/// from that edge; where both lamellas of a doubled strip have it, the
/// washer on that side bears on the band, not on the lamellas' edges. On
/// hypar-small / steel-1.5, by hand: the end slot is the band (t = 1.5)
/// plus 0.3 clearance each side, 2.1 mm, centred at h/2 = 25, so its floor
/// is at 23.95 and the band on it ends at 25.45: the grip. With two M8
/// plain washers (1.6), the nut (6.8) and two pitches (1.25): 37.95 mm, so
/// M8 × 40 (ISO 4017), not the M8 × 65 of the full 50 mm height.
#[test]
fn an_edge_bolt_at_a_rebate_grips_the_band_and_one_lamella_finger() {
    let p = profile("steel-1.5");
    assert_eq!(
        (
            p.section.height_mm,
            p.section.thickness_mm,
            p.joint.slot_clearance_mm
        ),
        (50.0, 1.5, 0.3)
    );
    let (nodes, kit) = kit("hypar-small", &p);
    // Rebated nodes, from the lamella parts: every lamella of the strip has
    // its end slot at that node open to the top or to the bottom edge.
    let mut ends: HashMap<usize, Vec<(f64, f64)>> = HashMap::new();
    for q in kit.parts.iter().filter(|q| q.kind == PartKind::Lamella) {
        for f in q.features.iter().filter(|f| f.edge == Some(SlotEdge::End)) {
            let (c, w) = (f.center_part_mm.y, 0.5 * f.width_mm);
            ends.entry(f.node.unwrap())
                .or_default()
                .push((c - w, c + w));
        }
    }
    let rebated = nodes
        .iter()
        .filter(|n| {
            let s = &ends[&n.id];
            assert_eq!(s.len(), 2, "node {}", n.id);
            s.iter().all(|y| y.1 > 50.0 - 1e-6) || s.iter().all(|y| y.0 < 1e-6)
        })
        .count() as u64;
    assert!(rebated > 0, "hypar-small has rebated edge nodes");
    let line = |item: &str| {
        kit.summary
            .hardware
            .iter()
            .find(|x| x.item == item && x.kind == HardwareKind::Bolt)
            .unwrap_or_else(|| panic!("no {item} line"))
    };
    let at = line("edge bolt at a rebate");
    assert!((at.grip_mm.unwrap() - 25.45).abs() < 1e-9, "{at:?}");
    assert_eq!(at.designation, "M8 × 40 ISO 4017 8.8");
    assert_eq!(at.count, rebated);
    let full = line("edge bolt");
    assert_eq!(full.designation, "M8 × 65 ISO 4017 8.8");
    assert_eq!(full.count + at.count, nodes.len() as u64);
}
