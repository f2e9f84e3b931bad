//! Node finding on the awkward cases: a pair crossing twice, a crossing at a
//! curve's end, curves that pass near but do not meet, near-tangent crossings.

use crate::support::*;
use glam::DVec3;
use lamella::network::{Family, RawCurve, RawNetwork, Unit};

fn curve(id: &str, family: Family, f: impl Fn(f64) -> DVec3, n: usize) -> RawCurve {
    RawCurve {
        id: id.into(),
        family,
        points: (0..n).map(|i| f(i as f64 / (n - 1) as f64)).collect(),
        normals: None,
    }
}

fn net(curves: Vec<RawCurve>) -> RawNetwork {
    RawNetwork {
        name: "t".into(),
        unit: Unit::Mm,
        tolerance: Some(0.5),
        precision: None,
        curves,
    }
}

#[test]
fn a_pair_crossing_twice_has_two_nodes() {
    // An arc of radius 1000 mm and a chord line through it at y = 500.
    let arc = curve(
        "A0",
        Family::A,
        |t| {
            let a = std::f64::consts::PI * t;
            DVec3::new(1000.0 * a.cos(), 1000.0 * a.sin(), 0.0)
        },
        80,
    );
    let line = curve(
        "B0",
        Family::B,
        |t| DVec3::new(-1200.0 + 2400.0 * t, 500.0, 0.0),
        40,
    );
    let (_n, an) = run(net(vec![arc, line]));
    assert_eq!(an.topology.nodes.len(), 2);
    let xs: Vec<f64> = an
        .topology
        .nodes
        .iter()
        .map(|n| n.position_world_mm.x)
        .collect();
    let x = (1000.0f64 * 1000.0 - 500.0 * 500.0).sqrt();
    assert!(
        (xs[0] - x).abs() < 0.01 && (xs[1] + x).abs() < 0.01,
        "{xs:?}"
    );
    // Stations on the arc: R·angle.
    let s0 = 1000.0 * (500.0f64 / 1000.0).asin();
    assert!((an.topology.nodes[0].station_a_mm - s0).abs() < 0.01);
    assert!(
        (an.topology.nodes[1].station_a_mm - (std::f64::consts::PI * 1000.0 - s0)).abs() < 0.01
    );
    // Both at 60° (tangent of the arc at 30° from the x axis against the line).
    for n in &an.topology.nodes {
        assert!((n.angle_deg - 60.0).abs() < 0.01, "{}", n.angle_deg);
    }
}

#[test]
fn a_crossing_at_a_curve_end_is_a_node() {
    let a = curve("A0", Family::A, |t| DVec3::new(1000.0 * t, 0.0, 0.0), 21);
    // B ends exactly on A (a T-junction), and C starts on A's end.
    let b = curve(
        "B0",
        Family::B,
        |t| DVec3::new(400.0, 800.0 - 800.0 * t, 0.0),
        17,
    );
    let e = curve(
        "edge0",
        Family::Edge,
        |t| DVec3::new(1000.0, 600.0 * t, 0.0),
        13,
    );
    let (_n, an) = run(net(vec![a, b, e]));
    assert_eq!(an.topology.nodes.len(), 2);
    let n0 = &an.topology.nodes[0];
    assert!((n0.station_a_mm - 400.0).abs() < 1e-6 && (n0.station_b_mm - 800.0).abs() < 1e-6);
    let n1 = &an.topology.nodes[1];
    assert!((n1.station_a_mm - 1000.0).abs() < 1e-6 && n1.station_b_mm.abs() < 1e-6);
}

#[test]
fn curves_passing_near_do_not_make_a_node() {
    let a = curve("A0", Family::A, |t| DVec3::new(1000.0 * t, 0.0, 0.0), 21);
    let b = curve(
        "B0",
        Family::B,
        |t| DVec3::new(500.0, -500.0 + 1000.0 * t, 0.0),
        21,
    );
    // B1 passes 2 mm above A0 (tolerance 0.5 mm): no node.
    let b1 = curve(
        "B1",
        Family::B,
        |t| DVec3::new(700.0, -500.0 + 1000.0 * t, 2.0),
        21,
    );
    // B2 passes 0.3 mm above: a node, with its gap reported.
    let b2 = curve(
        "B2",
        Family::B,
        |t| DVec3::new(300.0, -500.0 + 1000.0 * t, 0.3),
        21,
    );
    let (_n, an) = run(net(vec![a, b, b1, b2]));
    assert_eq!(an.topology.nodes.len(), 2);
    let gaps: Vec<f64> = an.topology.nodes.iter().map(|n| n.gap_mm).collect();
    assert!(gaps[0] < 1e-9 && (gaps[1] - 0.3).abs() < 1e-9, "{gaps:?}");
    assert!(an
        .warnings()
        .iter()
        .any(|w| w.message.contains("B1") && w.message.contains("crosses no other curve")));
}

#[test]
fn a_near_tangent_crossing_warns() {
    let a = curve("A0", Family::A, |t| DVec3::new(1000.0 * t, 0.0, 0.0), 21);
    // 5° crossing.
    let d = DVec3::new(5f64.to_radians().cos(), 5f64.to_radians().sin(), 0.0);
    let b = curve(
        "B0",
        Family::B,
        |t| DVec3::new(500.0, 0.0, 0.0) + d * (-300.0 + 600.0 * t),
        31,
    );
    let c = curve(
        "B1",
        Family::B,
        |t| DVec3::new(200.0, -300.0 + 600.0 * t, 0.0),
        31,
    );
    let (_n, an) = run(net(vec![a, b, c]));
    assert_eq!(an.topology.nodes.len(), 2);
    let near = an
        .topology
        .nodes
        .iter()
        .find(|n| n.angle_deg < 10.0)
        .expect("the 5° node");
    assert!((near.angle_deg - 5.0).abs() < 1e-6);
    assert!((near.station_a_mm - 500.0).abs() < 1e-6 && (near.station_b_mm - 300.0).abs() < 1e-6);
    assert!(an
        .warnings()
        .iter()
        .any(|w| w.message.contains("near-tangent") && w.message.contains("B0")));
    assert!(!an
        .warnings()
        .iter()
        .any(|w| w.message.contains("B1") && w.message.contains("near-tangent")));
}

#[test]
fn dense_grid_finds_every_node_once() {
    // A 40 × 40 hypar: 1600 nodes, none twice.
    let xs = crate::support::synth::spread(2000.0, 40);
    let lines = crate::support::synth::coordinate_lines(&xs, &xs);
    let raw = crate::support::synth::network(
        "g",
        &crate::support::synth::Hypar { c: 3000.0 },
        &lines,
        1.0,
        crate::support::synth::Sampling {
            step_mm: 30.0,
            normals: false,
        },
    );
    let (_n, an) = run(raw);
    assert_eq!(an.topology.nodes.len(), 1600);
    for list in &an.topology.per_curve {
        assert_eq!(list.len(), 40);
    }
}

/// A straight A line along +x and a straight B line through (500, 0, 0)
/// along (cos β, sin β, 0), with file normals `n` on both.
fn two_lines(beta_deg: f64, n: DVec3, reverse_b: bool) -> RawNetwork {
    let with_normals = |mut c: RawCurve| {
        c.normals = Some(vec![n; c.points.len()]);
        c
    };
    let a = with_normals(curve(
        "A0",
        Family::A,
        |t| DVec3::new(1000.0 * t, 0.0, 0.0),
        21,
    ));
    let d = DVec3::new(
        beta_deg.to_radians().cos(),
        beta_deg.to_radians().sin(),
        0.0,
    );
    let mut b = with_normals(curve(
        "B0",
        Family::B,
        |t| DVec3::new(500.0, 0.0, 0.0) + d * (-300.0 + 600.0 * t),
        21,
    ));
    if reverse_b {
        b.points.reverse();
    }
    net(vec![a, b])
}

#[test]
fn oriented_angle_turns_from_a_to_b_about_the_normal() {
    // Seen from +z (normal up), A runs along +x. B along 60° turns
    // counter-clockwise from A by 60°: oriented 60° (B, crossing from A's
    // right to its left, leans forward along A). B along 120° leans back
    // against A: oriented 120°, though both cross at an acute 60°. The
    // angle is between lines: B's direction does not matter, the normal's
    // side does.
    for (beta, up, down) in [
        (60.0, 60.0, 120.0),
        (120.0, 120.0, 60.0),
        (90.0, 90.0, 90.0),
    ] {
        for reverse_b in [false, true] {
            let (_n, an) = run(two_lines(beta, DVec3::Z, reverse_b));
            assert_eq!(an.topology.nodes.len(), 1);
            let node = &an.topology.nodes[0];
            assert!(node.normal_world.dot(DVec3::Z) > 0.999);
            assert!((node.angle_deg - beta.min(180.0 - beta)).abs() < 1e-6);
            assert!(
                (node.oriented_angle_deg - up).abs() < 1e-6,
                "B at {beta}° (reversed: {reverse_b}), normal +z: {}",
                node.oriented_angle_deg
            );
            // Seen from below (normal −z) the turn goes the other way.
            let (_n, an) = run(two_lines(beta, -DVec3::Z, reverse_b));
            let node = &an.topology.nodes[0];
            assert!(node.normal_world.dot(DVec3::Z) < -0.999);
            assert!(
                (node.oriented_angle_deg - down).abs() < 1e-6,
                "B at {beta}° (reversed: {reverse_b}), normal −z: {}",
                node.oriented_angle_deg
            );
        }
    }
    // The function itself, on hand vectors.
    use lamella::analysis::topology::oriented_angle_deg;
    let (x, y) = (DVec3::X, DVec3::Y);
    assert!((oriented_angle_deg(x, y, DVec3::Z) - 90.0).abs() < 1e-12);
    assert!((oriented_angle_deg(x, x + y, DVec3::Z) - 45.0).abs() < 1e-12);
    assert!((oriented_angle_deg(x, -x + y, DVec3::Z) - 135.0).abs() < 1e-12);
    assert!((oriented_angle_deg(x, x - y, DVec3::Z) - 135.0).abs() < 1e-12);
    assert!((oriented_angle_deg(x, -x, DVec3::Z)).abs() < 1e-12);
}

#[test]
fn warnings_are_typed() {
    use lamella::analysis::topology::WarningKind;
    // An isolated B line and a near-tangent crossing.
    let a = curve("A0", Family::A, |t| DVec3::new(1000.0 * t, 0.0, 0.0), 21);
    let d = DVec3::new(5f64.to_radians().cos(), 5f64.to_radians().sin(), 0.0);
    let b = curve(
        "B0",
        Family::B,
        |t| DVec3::new(500.0, 0.0, 0.0) + d * (-300.0 + 600.0 * t),
        31,
    );
    let c = curve(
        "B1",
        Family::B,
        |t| DVec3::new(200.0, -300.0 + 600.0 * t, 0.0),
        31,
    );
    let far = curve(
        "B2",
        Family::B,
        |t| DVec3::new(5000.0, -300.0 + 600.0 * t, 0.0),
        31,
    );
    let (net, an) = run(net(vec![a, b, c, far]));
    let near: Vec<_> = an
        .warnings()
        .iter()
        .filter(|w| w.kind == WarningKind::NearTangent)
        .collect();
    assert_eq!(near.len(), 1);
    assert_eq!(near[0].curves, vec![0, 1]);
    assert!((near[0].station_mm.unwrap() - 500.0).abs() < 1e-6);
    assert_eq!(near[0].to_string(), near[0].message);
    let isolated: Vec<_> = an
        .warnings()
        .iter()
        .filter(|w| w.kind == WarningKind::IsolatedCurve)
        .collect();
    assert_eq!(isolated.len(), 1);
    assert_eq!(isolated[0].curves, vec![net.curve_index("B2").unwrap()]);
    assert_eq!(isolated[0].station_mm, None);
    assert_eq!(WarningKind::IsolatedCurve.as_str(), "isolated_curve");
}
