//! Stations, lengths, angles, geodesic curvature and torsion held to the
//! closed forms of docs/geometry.md on Enneper, catenoid, helicoid and hypar.

use crate::support::synth::{self, Catenoid, Enneper, Helicoid, Hypar, ParamSurface, Sampling};
use crate::support::*;
use glam::DVec2;
use lamella::analysis::strip::NormalSource;

const SCALE: f64 = synth::ENNEPER_4M_SCALE_MM;
const HALF: f64 = synth::ENNEPER_4M_HALF;

fn enneper(
    step_mm: f64,
    normals: bool,
    rounded: bool,
) -> (lamella::Network, lamella::Analysis, Vec<synth::ParamLine>) {
    let lines = synth::diagonal_lines(HALF, 13, DVec2::ZERO);
    let raw = synth::network("e", &Enneper, &lines, SCALE, Sampling { step_mm, normals });
    let (net, an) = run(export(raw, rounded));
    (net, an, lines)
}

/// Every node station on every strip against the closed-form arc length.
fn check_enneper_stations(step_mm: f64, normals: bool, rounded: bool, tol_mm: f64) {
    let (net, an, _) = enneper(step_mm, normals, rounded);
    let values = synth::spread(HALF, 13);
    assert_eq!(an.topology.nodes.len(), 169);
    let mut worst: f64 = 0.0;
    for node in &an.topology.nodes {
        let ia: usize = net.curves[node.a].id[1..].parse().unwrap();
        let jb: usize = net.curves[node.b].id[1..].parse().unwrap();
        let (p, q) = (values[ia], values[jb]);
        let sa = SCALE * synth::enneper_arc_length(p, -HALF, q);
        let sb = SCALE * synth::enneper_arc_length(q, -HALF, p);
        worst = worst
            .max((node.station_a_mm - sa).abs())
            .max((node.station_b_mm - sb).abs());
        assert!(
            (node.angle_deg - 90.0).abs() < 0.01,
            "angle {}",
            node.angle_deg
        );
    }
    for (strip, c) in an.strips.iter().zip(&net.curves) {
        let i: usize = c.id[1..].parse().unwrap();
        let len = SCALE * synth::enneper_arc_length(values[i], -HALF, HALF);
        worst = worst.max((strip.length_mm - len).abs());
    }
    assert!(
        worst < tol_mm,
        "worst station/length error {worst} mm at {step_mm} mm sampling, rounded {rounded}"
    );
}

#[test]
fn enneper_stations_dense_with_normals() {
    check_enneper_stations(10.0, true, false, 0.01);
}
#[test]
fn enneper_stations_dense_without_normals() {
    check_enneper_stations(10.0, false, false, 0.01);
    check_enneper_stations(10.0, false, true, 0.01);
}
#[test]
fn enneper_stations_50mm_with_normals() {
    check_enneper_stations(50.0, true, false, 0.01);
}
#[test]
fn enneper_stations_50mm_without_normals() {
    check_enneper_stations(50.0, false, false, 0.01);
    check_enneper_stations(50.0, false, true, 0.01);
}

/// tg = ±2/λ² (per surface unit) and |kg| = the curve's curvature, everywhere
/// along every strip. `rel_tol` holds where normals come from the file or the
/// binormal; the straight lines u = ±v take theirs from the nodes (about 260 mm
/// apart), held to `nodes_tol`.
fn check_enneper_frames(step_mm: f64, normals: bool, rounded: bool, rel_tol: f64, nodes_tol: f64) {
    let (_net, an, lines) = enneper(step_mm, normals, rounded);
    for (strip, line) in an.strips.iter().zip(&lines) {
        let mut worst_tg: f64 = 0.0;
        let mut worst_kg: f64 = 0.0;
        let smooth = &an.curves[strip.curve];
        let p = (line.start.x + line.start.y)
            * if line.family == lamella::Family::A {
                1.0
            } else {
                0.0
            }
            + (line.start.x - line.start.y)
                * if line.family == lamella::Family::B {
                    1.0
                } else {
                    0.0
                };
        for k in 0..=40 {
            let t = -HALF + 2.0 * HALF * k as f64 / 40.0;
            let s = SCALE * synth::enneper_arc_length(p, -HALF, t);
            let f = strip.frame_at(smooth, s);
            let uv = line.uv(t);
            let lambda = 1.0 + uv.length_squared();
            let tg = 2.0 / (lambda * lambda * SCALE);
            let (kappa, _) = curvature_torsion(&Enneper, line, SCALE, t);
            worst_tg = worst_tg.max((f.tg_per_mm.abs() - tg).abs() / tg);
            worst_kg = worst_kg.max((f.kg_per_mm.abs() - kappa).abs() / tg);
        }
        let tol = if strip.normal_source == NormalSource::Nodes {
            nodes_tol
        } else {
            rel_tol
        };
        assert!(
            worst_tg < tol,
            "{}: tg relative error {worst_tg} (step {step_mm}, normals {normals}, rounded {rounded})",
            strip.id
        );
        assert!(
            worst_kg < tol,
            "{}: kg error relative to tg {worst_kg} (step {step_mm}, rounded {rounded})",
            strip.id
        );
    }
}

#[test]
fn enneper_torsion_and_curvature_dense() {
    check_enneper_frames(10.0, true, false, 1e-6, 1e-6);
    check_enneper_frames(10.0, false, false, 2e-4, 3e-3);
    check_enneper_frames(10.0, false, true, 1e-2, 1e-2);
}
#[test]
fn enneper_torsion_and_curvature_50mm() {
    check_enneper_frames(50.0, true, false, 1e-4, 1e-4);
    check_enneper_frames(50.0, false, false, 3e-3, 3e-3);
    check_enneper_frames(50.0, false, true, 1e-2, 1e-2);
}

/// Helicoid X = (v cos u, v sin u, c·u): rulings (A, u = const) are straight
/// with kg = 0 and tg = c/(v² + c²); helices (B, v = const) have
/// kg = v/(v² + c²), the same tg, and length sqrt(v² + c²)·Δu.
fn check_helicoid(step_mm: f64, normals: bool, rounded: bool, tg_tol: f64) {
    let c = 1000.0;
    let us = synth::spread(0.75, 9)
        .iter()
        .map(|u| u + 0.75)
        .collect::<Vec<_>>();
    let vs = synth::spread(600.0, 9)
        .iter()
        .map(|v| v + 900.0)
        .collect::<Vec<_>>();
    let lines = synth::coordinate_lines(&us, &vs);
    let raw = synth::network(
        "helicoid",
        &Helicoid { c },
        &lines,
        1.0,
        Sampling { step_mm, normals },
    );
    let (net, an) = run(export(raw, rounded));
    assert_eq!(an.topology.nodes.len(), 81);
    for node in &an.topology.nodes {
        let i: usize = net.curves[node.a].id[1..].parse().unwrap();
        let j: usize = net.curves[node.b].id[1..].parse().unwrap();
        let (u, v) = (us[i], vs[j]);
        assert!(
            (node.station_a_mm - (v - vs[0])).abs() < 0.01,
            "ruling station"
        );
        let helix = (v * v + c * c).sqrt() * (u - us[0]);
        assert!(
            (node.station_b_mm - helix).abs() < 0.01,
            "helix station {} vs {helix}",
            node.station_b_mm
        );
        assert!((node.angle_deg - 90.0).abs() < 0.01);
    }
    for (strip, line) in an.strips.iter().zip(&lines) {
        let smooth = &an.curves[strip.curve];
        for k in 0..=20 {
            let frac = k as f64 / 20.0;
            let (s, v) = if line.family == lamella::Family::A {
                (frac * 1200.0, vs[0] + frac * 1200.0)
            } else {
                let v = line.start.y;
                ((v * v + c * c).sqrt() * 1.5 * frac, v)
            };
            let f = strip.frame_at(smooth, s);
            let tg = c / (v * v + c * c);
            let kg = if line.family == lamella::Family::A {
                0.0
            } else {
                v / (v * v + c * c)
            };
            assert!(
                (f.tg_per_mm.abs() - tg).abs() < tg_tol * tg,
                "{} tg {} vs {tg} at {s} normals {normals} step {step_mm} rounded {rounded}",
                strip.id,
                f.tg_per_mm
            );
            assert!(
                (f.kg_per_mm.abs() - kg).abs() < tg_tol * tg,
                "{} kg {} vs {kg}",
                strip.id,
                f.kg_per_mm
            );
        }
        if line.family == lamella::Family::B {
            let v = line.start.y;
            assert!((strip.length_mm - (v * v + c * c).sqrt() * 1.5).abs() < 0.01);
            assert!(strip.min_bending_radius_mm().is_some());
        } else {
            assert!((strip.length_mm - 1200.0).abs() < 0.01);
            assert_eq!(strip.min_bending_radius_mm(), None, "a ruling is straight");
        }
    }
}

#[test]
fn helicoid_dense_with_and_without_normals() {
    check_helicoid(10.0, true, false, 1e-5);
    check_helicoid(10.0, false, false, 5e-3);
    check_helicoid(10.0, false, true, 1e-2);
}
#[test]
fn helicoid_50mm_with_and_without_normals() {
    check_helicoid(50.0, true, false, 1e-4);
    check_helicoid(50.0, false, false, 1e-2);
    check_helicoid(50.0, false, true, 1e-2);
}

/// Catenoid: asymptotic lines u ± v = const, arc length √2·c·|sinh v₁ − sinh v₀|,
/// tg² = −K = 1/(c² cosh⁴ v).
fn check_catenoid(step_mm: f64, normals: bool, rounded: bool, tg_tol: f64, station_tol: f64) {
    let c = 1000.0;
    let half = 1.0;
    let center = DVec2::new(0.3, 0.1);
    let lines = synth::diagonal_lines(half, 11, center);
    let raw = synth::network(
        "catenoid",
        &Catenoid { c },
        &lines,
        1.0,
        Sampling { step_mm, normals },
    );
    let (net, an) = run(export(raw, rounded));
    assert_eq!(an.topology.nodes.len(), 121);
    let vals = synth::spread(half, 11);
    // v along A_i (p fixed, q = t): v = cv + (p − q)/2; along B_j (q fixed, p = t) likewise.
    let v_of = |p: f64, q: f64| center.y + (p - q) / 2.0;
    for node in &an.topology.nodes {
        let i: usize = net.curves[node.a].id[1..].parse().unwrap();
        let j: usize = net.curves[node.b].id[1..].parse().unwrap();
        let (p, q) = (vals[i], vals[j]);
        let sa = std::f64::consts::SQRT_2 * c * (v_of(p, q).sinh() - v_of(p, -half).sinh()).abs();
        let sb = std::f64::consts::SQRT_2 * c * (v_of(p, q).sinh() - v_of(-half, q).sinh()).abs();
        assert!(
            (node.station_a_mm - sa).abs() < station_tol,
            "{} vs {sa}",
            node.station_a_mm
        );
        assert!(
            (node.station_b_mm - sb).abs() < station_tol,
            "{} vs {sb}",
            node.station_b_mm
        );
        assert!((node.angle_deg - 90.0).abs() < 0.01);
    }
    for (strip, line) in an.strips.iter().zip(&lines) {
        let smooth = &an.curves[strip.curve];
        for k in 0..=20 {
            let t = -half + 2.0 * half * k as f64 / 20.0;
            let uv = line.uv(t);
            let s = arc_length(&Catenoid { c }, line, 1.0, -half, t);
            let f = strip.frame_at(smooth, s);
            let minus_k = 1.0 / (c * c * uv.y.cosh().powi(4));
            assert!(
                (f.tg_per_mm * f.tg_per_mm - minus_k).abs() < tg_tol * minus_k,
                "{}: tg² {} vs −K {minus_k} step {step_mm} normals {normals} rounded {rounded} t {t}",
                strip.id,
                f.tg_per_mm * f.tg_per_mm
            );
            let (kappa, _) = curvature_torsion(&Catenoid { c }, line, 1.0, t);
            // kg from the curve itself: one-sided fits at the ends cost ~1e-3·tg at 50 mm.
            assert!(
                (f.kg_per_mm.abs() - kappa).abs() < tg_tol.max(1e-3) * minus_k.sqrt(),
                "{} kg {} vs {kappa} step {step_mm} normals {normals}",
                strip.id,
                f.kg_per_mm
            );
        }
    }
}

#[test]
fn catenoid_dense_and_50mm() {
    check_catenoid(10.0, true, false, 1e-5, 0.01);
    check_catenoid(50.0, true, false, 3e-4, 0.01);
    // Without normals, the whole curve, ends included (they are inflection
    // points here), exact and rounded to 0.001 mm; tg² carries twice tg's error.
    check_catenoid(10.0, false, false, 2e-2, 0.01);
    check_catenoid(10.0, false, true, 2e-2, 0.01);
    check_catenoid(50.0, false, false, 2e-2, 0.01);
    check_catenoid(50.0, false, true, 2e-2, 0.01);
}

/// Hyperbolic paraboloid z = xy/c: rulings of length sqrt(1 + x²/c²)·Δy,
/// crossing at cos φ = xy/c² / (sqrt(1 + x²/c²) sqrt(1 + y²/c²)),
/// |tg| = (1/c) / (1 + (x² + y²)/c²), kg = 0.
#[test]
fn hypar_lengths_angles_twist() {
    let c = 1500.0;
    let xs = synth::spread(600.0, 7);
    let lines = synth::coordinate_lines(&xs, &xs);
    for (step_mm, normals, rounded) in [
        (10.0, true, false),
        (10.0, false, false),
        (10.0, false, true),
        (50.0, false, false),
        (50.0, false, true),
    ] {
        let raw = synth::network(
            "hypar",
            &Hypar { c },
            &lines,
            1.0,
            Sampling { step_mm, normals },
        );
        let (net, an) = run(export(raw, rounded));
        assert_eq!(an.topology.nodes.len(), 49);
        for node in &an.topology.nodes {
            let i: usize = net.curves[node.a].id[1..].parse().unwrap();
            let j: usize = net.curves[node.b].id[1..].parse().unwrap();
            let (x, y) = (xs[i], xs[j]);
            let (fx, fy) = (
                (1.0 + x * x / (c * c)).sqrt(),
                (1.0 + y * y / (c * c)).sqrt(),
            );
            assert!((node.station_a_mm - fx * (y - xs[0])).abs() < 0.01);
            assert!((node.station_b_mm - fy * (x - xs[0])).abs() < 0.01);
            let phi = (x * y / (c * c) / (fx * fy)).abs().acos().to_degrees();
            assert!(
                (node.angle_deg - phi).abs() < 0.01,
                "{} vs {phi}",
                node.angle_deg
            );
        }
        for (strip, line) in an.strips.iter().zip(&lines) {
            let smooth = &an.curves[strip.curve];
            assert_eq!(strip.min_bending_radius_mm(), None);
            let fixed = if line.family == lamella::Family::A {
                line.start.x
            } else {
                line.start.y
            };
            let stretch = (1.0 + fixed * fixed / (c * c)).sqrt();
            for k in 0..=12 {
                let run_coord = xs[0] + 100.0 * k as f64;
                let s = stretch * (run_coord - xs[0]);
                let f = strip.frame_at(smooth, s);
                let tg = (1.0 / c) / (1.0 + (fixed * fixed + run_coord * run_coord) / (c * c));
                let tol = match (normals, rounded) {
                    (true, _) => 1e-6,
                    (false, false) => 5e-3,
                    (false, true) => 1e-2,
                };
                assert!(
                    (f.tg_per_mm.abs() - tg).abs() < tol * tg,
                    "{} tg {} vs {tg} at {s} step {step_mm} rounded {rounded}",
                    strip.id,
                    f.tg_per_mm
                );
            }
        }
    }
}

#[test]
fn enneper_beltrami_enneper_at_every_sample() {
    // tg² = −K = 4/λ⁴ (per surface unit²) at every sample of every strip,
    // with λ taken from the sample's closed-form parameters.
    let (net, an, lines) = enneper(20.0, true, false);
    for ((strip, line), curve) in an.strips.iter().zip(&lines).zip(&net.curves) {
        let n = curve.points_world_mm.len();
        for (i, cv) in strip.samples.iter().enumerate() {
            let t = line.t0 + (line.t1 - line.t0) * i as f64 / (n - 1) as f64;
            let lambda = 1.0 + line.uv(t).length_squared();
            let minus_k = 4.0 / (lambda.powi(4) * SCALE * SCALE);
            assert!(
                (cv.tg_per_mm.powi(2) - minus_k).abs() < 1e-5 * minus_k,
                "{} sample {i}",
                strip.id
            );
            assert!(cv.kn_per_mm.abs() < 1e-8, "kn residual {}", cv.kn_per_mm);
        }
    }
    let _ = Enneper.point(DVec2::ZERO);
}

/// Edge curves are not asymptotic: their normal comes from their nodes. On
/// the catenoid, parallels v = v₀ (circles) and meridians u = u₀ (catenaries)
/// are lines of curvature, so tg = 0 on them; a meridian is a geodesic
/// (kg = 0) and a parallel has |kg| = tanh v₀ / (c cosh v₀). Their binormals
/// lie in the tangent plane (meridian) or 45°–90° off the normal: taking the
/// binormal as the normal would give twist and bending that are not there.
fn check_catenoid_edges(step_mm: f64, rounded: bool) {
    let c = 1000.0;
    let center = DVec2::new(0.3, 0.1);
    let mut lines = synth::diagonal_lines(1.0, 11, center);
    for (k, dv) in [-0.4, 0.4].into_iter().enumerate() {
        lines.push(synth::ParamLine {
            id: format!("edge-parallel{k}"),
            family: lamella::Family::Edge,
            start: center + DVec2::new(-0.5, dv),
            dir: DVec2::new(1.0, 0.0),
            t0: 0.0,
            t1: 1.0,
        });
        lines.push(synth::ParamLine {
            id: format!("edge-meridian{k}"),
            family: lamella::Family::Edge,
            start: center + DVec2::new(dv, -0.5),
            dir: DVec2::new(0.0, 1.0),
            t0: 0.0,
            t1: 1.0,
        });
    }
    let raw = synth::network(
        "catenoid-edges",
        &Catenoid { c },
        &lines,
        1.0,
        Sampling {
            step_mm,
            normals: false,
        },
    );
    let (_net, an) = run(export(raw, rounded));
    let mut edges = 0;
    for (strip, line) in an.strips.iter().zip(&lines) {
        if strip.family != lamella::Family::Edge {
            continue;
        }
        edges += 1;
        assert_eq!(strip.normal_source, NormalSource::Nodes, "{}", strip.id);
        assert!(
            strip.nodes.len() >= 5,
            "{}: {} nodes",
            strip.id,
            strip.nodes.len()
        );
        let smooth = &an.curves[strip.curve];
        let parallel = line.dir.y == 0.0;
        for k in 0..=20 {
            let t = k as f64 / 20.0;
            let s = arc_length(&Catenoid { c }, line, 1.0, 0.0, t);
            let v = line.uv(t).y;
            let k1 = 1.0 / (c * v.cosh().powi(2));
            let f = strip.frame_at(smooth, s);
            let kg = if parallel {
                v.tanh() / (c * v.cosh())
            } else {
                0.0
            };
            assert!(
                f.tg_per_mm.abs() < 0.01 * k1,
                "{} tg {} at {s} (k1 {k1}) step {step_mm} rounded {rounded}",
                strip.id,
                f.tg_per_mm
            );
            assert!(
                (f.kg_per_mm.abs() - kg.abs()).abs() < 0.01 * k1,
                "{} kg {} vs {kg} at {s} step {step_mm} rounded {rounded}",
                strip.id,
                f.kg_per_mm
            );
            assert!(f.z.dot(Catenoid { c }.normal(line.uv(t))).abs() > 0.9999);
        }
    }
    assert_eq!(edges, 4);
}

#[test]
fn catenoid_edges_take_their_normal_from_nodes() {
    for step_mm in [10.0, 50.0] {
        check_catenoid_edges(step_mm, false);
        check_catenoid_edges(step_mm, true);
    }
}
