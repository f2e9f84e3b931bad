//! Inputs that once broke lamella (from review): they now get a one-line
//! error with exit 1, or are read correctly.

#![allow(clippy::unwrap_used)] // tests may panic on broken invariants

use dxf::entities::{Entity, EntityType, Line, LwPolyline};
use dxf::enums::{AcadVersion, Units};
use dxf::{Drawing, LwPolylineVertex, Point};
use lamella::io::{read_network, ReadOptions};
use lamella::{analyze, AnalysisOptions};
use std::path::PathBuf;
use std::process::Command;

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("lamella-robust-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Run `lamella nodes` on a file with `contents`; expect exit 1 and one line
/// containing every fragment.
fn rejects(name: &str, file: &str, contents: &str, fragments: &[&str]) {
    let dir = scratch(name);
    let p = dir.join(file);
    std::fs::write(&p, contents).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_lamella"))
        .args([
            "nodes",
            p.to_str().unwrap(),
            "--out",
            dir.join("out").to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{name}: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{name}: {stderr}");
    for f in fragments {
        assert!(stderr.contains(f), "{name}: `{f}` not in {stderr}");
    }
    assert!(!dir.join("out/plan.json").exists());
    std::fs::remove_dir_all(dir).unwrap();
}

const B_LINE: &str = "  - id: B00\n    family: B\n    points: [[50, -100, 0], [50, 100, 0]]\n";

#[test]
fn obj_polyline_without_vertices() {
    rejects(
        "obj-empty-l",
        "x.obj",
        "o A1\nv 0 0 0\nv 1 0 0\nl\nl\n",
        &["line 4", "at least 2"],
    );
}

#[test]
fn non_ascii_names_do_not_panic() {
    rejects(
        "obj-umlaut",
        "x.obj",
        "o Aää\nv 0 0 0\nv 1 0 0\nl 1 2\n",
        &["Aää", "A, B or edge"],
    );
}

#[test]
fn folded_curve_is_rejected() {
    let text = format!("units: mm\ncurves:\n  - id: A00\n    family: A\n    points: [[0, 0, 0], [100, 0, 0], [0, 0, 0]]\n{B_LINE}");
    rejects(
        "fold",
        "fold.yaml",
        &text,
        &["curve A00", "turns back on itself at point 1"],
    );
}

#[test]
fn flipping_normals_are_rejected() {
    let text = format!(
        "units: mm\ncurves:\n  - id: A00\n    family: A\n    points: [[0, 0, 0], [50, 0, 0], [100, 0, 0]]\n    normals: [[0, 0, 1], [0, 0, -1], [0, 0, 1]]\n{B_LINE}"
    );
    rejects(
        "flip",
        "flip.yaml",
        &text,
        &["curve A00", "normal 1 points the other way"],
    );
}

#[test]
fn overflow_in_mm_is_rejected() {
    let text = format!("units: m\ncurves:\n  - id: A00\n    family: A\n    points: [[0, 0, 0], [1.0e306, 0, 0]]\n{B_LINE}");
    rejects("overflow", "big.yaml", &text, &["curve A00", "overflows"]);
}

#[test]
fn out_dir_that_is_a_file() {
    let dir = scratch("outfile");
    let file = dir.join("taken");
    std::fs::write(&file, "keep me").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_lamella"))
        .args([
            "nodes",
            "samples/hypar-small.yaml",
            "--out",
            file.to_str().unwrap(),
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr.contains("not a directory") && stderr.lines().count() == 1,
        "{stderr}"
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "keep me");
    std::fs::remove_dir_all(dir).unwrap();
}

fn entity(layer: &str, specific: EntityType) -> Entity {
    let mut e = Entity::new(specific);
    e.common.layer = layer.into();
    e
}

#[test]
fn dxf_lwpolyline_elevation_bulges_and_other_layers() {
    let dir = scratch("dxf");
    let mut d = Drawing::new();
    d.header.version = AcadVersion::R2000;
    d.header.default_drawing_units = Units::Millimeters;
    // An LWPOLYLINE at elevation 500: a straight run, then a semicircle (bulge 1).
    let mut lw = LwPolyline::default();
    lw.vertices.push(LwPolylineVertex {
        x: -100.0,
        y: 0.0,
        ..Default::default()
    });
    lw.vertices.push(LwPolylineVertex {
        x: 100.0,
        y: 0.0,
        bulge: 1.0,
        ..Default::default()
    });
    lw.vertices.push(LwPolylineVertex {
        x: 300.0,
        y: 0.0,
        ..Default::default()
    });
    let mut e = entity("A", EntityType::LwPolyline(lw));
    e.common.elevation = 500.0;
    d.add_entity(e);
    // B crosses the straight run at (0, 0, 500) and the arc's apex at (200, -100, 500).
    d.add_entity(entity(
        "B",
        EntityType::Line(Line::new(
            Point::new(0.0, -50.0, 500.0),
            Point::new(0.0, 50.0, 500.0),
        )),
    ));
    d.add_entity(entity(
        "B",
        EntityType::Line(Line::new(
            Point::new(150.0, -100.0, 500.0),
            Point::new(250.0, -100.0, 500.0),
        )),
    ));
    // Layers that are not curves of the network are skipped, not read as A or B.
    d.add_entity(entity(
        "Annotations",
        EntityType::Line(Line::new(
            Point::new(-50.0, -10.0, 500.0),
            Point::new(-50.0, 10.0, 500.0),
        )),
    ));
    d.add_entity(entity(
        "Boundary",
        EntityType::Line(Line::new(
            Point::new(-60.0, -10.0, 500.0),
            Point::new(-60.0, 10.0, 500.0),
        )),
    ));
    let path = dir.join("elev.dxf");
    d.save_file(&path).unwrap();
    let net = read_network(&path, ReadOptions::default()).unwrap();
    assert_eq!(net.curves.len(), 3, "Annotations and Boundary skipped");
    assert!(
        net.curves[0]
            .points_mm
            .iter()
            .all(|p| (p.z - 500.0).abs() < 1e-9),
        "elevation applied"
    );
    // The arc is sampled on its circle: centre (200, 0), radius 100.
    let arc: Vec<_> = net.curves[0]
        .points_mm
        .iter()
        .filter(|p| p.x > 100.0 + 1e-9)
        .collect();
    assert!(arc.len() > 10);
    for p in arc {
        assert!(((p.x - 200.0).hypot(p.y) - 100.0).abs() < 1e-9, "{p}");
    }
    let an = analyze(&net, AnalysisOptions::for_network(&net)).unwrap();
    assert_eq!(an.topology.nodes.len(), 2);
    let apex = an
        .topology
        .nodes
        .iter()
        .find(|n| n.position_mm.x > 100.0)
        .unwrap();
    assert!(
        (apex.position_mm.y + 100.0).abs() < 0.01,
        "the bulge goes clockwise below: {}",
        apex.position_mm
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn edge_strips_are_not_checked_as_bent_lamellas() {
    // A flat circular edge of radius 300 mm would "fail" a weak-axis check,
    // but an edge is cut as a curved band: only A and B strips are checked.
    let dir = scratch("edge");
    let mut text = String::from("units: mm\ncurves:\n  - id: A00\n    family: A\n    points: [[-400, 0, 0], [400, 0, 0]]\n  - id: B00\n    family: B\n    points: [[0, -400, 0], [0, 400, 0]]\n  - id: edge00\n    family: edge\n    points:\n");
    for k in 0..=72 {
        let a = (k as f64 * 5.0).to_radians();
        text.push_str(&format!(
            "      - [{:.6}, {:.6}, 0]\n",
            300.0 * a.cos(),
            300.0 * a.sin()
        ));
    }
    let p = dir.join("ring.yaml");
    std::fs::write(&p, text).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_lamella"))
        .args([
            "check",
            p.to_str().unwrap(),
            "--profile",
            "profiles/steel-1.5.yaml",
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(!stdout.contains("edge00"), "{stdout}");
    assert!(stdout.contains("PASS: all 2 strips"), "{stdout}");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn sparse_curves_get_curvature_between_their_samples() {
    // A 1 m arc of radius 500 mm given by 5 points: the frames are evaluated
    // at most 50 mm apart, and the bending radius is found between samples.
    use glam::DVec3;
    use lamella::network::{Family, Network, RawCurve, RawNetwork, Unit};
    let arc: Vec<DVec3> = (0..5)
        .map(|i| {
            let a = 2.0 * i as f64 / 4.0;
            DVec3::new(500.0 * a.sin(), 500.0 * (1.0 - a.cos()), 0.0)
        })
        .collect();
    let raw = RawNetwork {
        name: "sparse".into(),
        unit: Unit::Mm,
        tolerance: None,
        curves: vec![
            RawCurve {
                id: "A0".into(),
                family: Family::A,
                points: arc,
                normals: None,
            },
            RawCurve {
                id: "B0".into(),
                family: Family::B,
                points: vec![
                    DVec3::new(400.0, -200.0, 0.0),
                    DVec3::new(400.0, 600.0, 0.0),
                ],
                normals: None,
            },
        ],
    };
    let net = Network::new(raw, std::path::Path::new("sparse.yaml")).unwrap();
    let an = analyze(&net, AnalysisOptions::for_network(&net)).unwrap();
    for s in &an.strips {
        assert!(
            s.samples
                .windows(2)
                .all(|w| w[1].station_mm - w[0].station_mm
                    <= lamella::strip::MAX_CURVATURE_SPACING_MM + 1e-9),
            "{}",
            s.id
        );
    }
    let r = an.strips[0].min_bending_radius_mm().unwrap();
    // 5 samples 0.5 rad apart: the interpolant holds the radius to ~10 %.
    assert!(
        (r - 500.0).abs() < 50.0,
        "radius {r} from 5 samples of a 500 mm arc"
    );
}
