//! Inputs that once broke lamella (from review): they now get a one-line
//! error with exit 1, or are read correctly.

use crate::support::{lamella, root, scratch};
use dxf::entities::{Entity, EntityType, Line, LwPolyline};
use dxf::enums::{AcadVersion, Units};
use dxf::{Drawing, LwPolylineVertex, Point};
use lamella::formats::read::{read_network, ReadOptions};
use lamella::{analyze, AnalysisOptions};

/// Run `lamella nodes` on a file with `contents`; expect exit 1 and one line
/// containing every fragment.
fn rejects(name: &str, file: &str, contents: &str, fragments: &[&str]) {
    let dir = scratch(name);
    let p = dir.join(file);
    std::fs::write(&p, contents).unwrap();
    let (code, _, stderr) = lamella(&[
        "nodes",
        p.to_str().unwrap(),
        "--out",
        dir.join("out").to_str().unwrap(),
    ]);
    assert_eq!(code, Some(1), "{name}: {stderr}");
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
    let (code, _, stderr) = lamella(&[
        "nodes",
        "samples/hypar-small.yaml",
        "--out",
        file.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(1));
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
            .points_world_mm
            .iter()
            .all(|p| (p.z - 500.0).abs() < 1e-9),
        "elevation applied"
    );
    // The arc is sampled on its circle: centre (200, 0), radius 100.
    let arc: Vec<_> = net.curves[0]
        .points_world_mm
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
        .find(|n| n.position_world_mm.x > 100.0)
        .unwrap();
    assert!(
        (apex.position_world_mm.y + 100.0).abs() < 0.01,
        "the bulge goes clockwise below: {}",
        apex.position_world_mm
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
    let (code, stdout, stderr) = lamella(&[
        "check",
        p.to_str().unwrap(),
        "--profile",
        "profiles/steel-1.5.yaml",
    ]);
    assert_eq!(code, Some(0), "{stdout}{stderr}");
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
        precision: None,
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
                    <= lamella::analysis::strip::MAX_CURVATURE_SPACING_MM + 1e-9),
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

// ---- bad input ----

/// Two straight crossing curves in mm, and `extra` curves.
fn cross(extra: &str) -> String {
    format!("units: mm\ncurves:\n  - id: A00\n    family: A\n    points: [[0, -100, 0], [0, 100, 0]]\n{B_LINE}{extra}")
}

#[test]
fn coordinates_beyond_ten_km_are_refused_not_analysed() {
    // 1e300 mm once panicked `check` (clamp on NaN) and gave `nodes` a
    // null length and a "NaN m" summary.
    let text =
        cross("  - id: A01\n    family: A\n    points: [[20, -100, 0], [1.0e300, 100, 0]]\n");
    rejects(
        "huge",
        "huge.yaml",
        &text,
        &["curve A01", "point 1", "within ±1e7 mm"],
    );
    let dir = scratch("huge-check");
    let p = dir.join("huge.yaml");
    std::fs::write(&p, &text).unwrap();
    let (code, stdout, stderr) = lamella(&[
        "check",
        p.to_str().unwrap(),
        "--profile",
        "profiles/steel-1.5.yaml",
        "--out",
        dir.join("out").to_str().unwrap(),
    ]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stdout.is_empty() && !stderr.contains("panicked"),
        "{stderr}"
    );
    assert!(stderr.contains("within ±1e7 mm"), "{stderr}");
    assert!(!dir.join("out").exists());
    // In metres, 20 km is out of range too (after unit conversion).
    let text = "units: m\ncurves:\n  - id: A00\n    family: A\n    points: [[0, -1, 0], [0, 1, 0]]\n  - id: B00\n    family: B\n    points: [[-1, 0, 0], [20000, 0, 0]]\n";
    rejects(
        "huge-m",
        "huge-m.yaml",
        text,
        &["curve B00", "point 1", "10 km"],
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn networks_beyond_a_kilometre_are_refused() {
    // Every coordinate is in range, but the network spans 3 km: scaled-up
    // networks used to run for minutes.
    let text = "units: m\ncurves:\n  - id: A00\n    family: A\n    points: [[0, -1500, 0], [0, 1500, 0]]\n  - id: B00\n    family: B\n    points: [[-1500, 0, 0], [1500, 0, 0]]\n";
    rejects(
        "wide",
        "wide.yaml",
        text,
        &["spans 3000000 × 3000000", "1 km"],
    );
    // A node tolerance in the file beyond a metre is no joint.
    let text = cross("").replacen("units: mm\n", "units: mm\ntolerance: 1.0e300\n", 1);
    rejects(
        "wide-tol",
        "tol.yaml",
        &text,
        &["tolerance", "at most 1000 mm"],
    );
}

#[test]
fn deep_nesting_and_aliases_are_refused_fast() {
    let t0 = std::time::Instant::now();
    let deep = format!(
        "{}meta: {}{}\n",
        cross(""),
        "[".repeat(200_000),
        "]".repeat(200_000)
    );
    rejects(
        "deep",
        "deep.yaml",
        &deep,
        &["line 9, column 70", "deeper than 64"],
    );
    let block: String = (0..200)
        .map(|i| format!("{}k{i}:\n", " ".repeat(i + 1)))
        .collect();
    rejects(
        "deep-block",
        "deepb.yaml",
        &format!("{}meta:\n{block}", cross("")),
        &["deeper than 64"],
    );
    let mut lol = format!(
        "{}meta:\n  a0: &a0 [x, x, x, x, x, x, x, x, x]\n",
        cross("")
    );
    for i in 1..9 {
        lol.push_str(&format!(
            "  a{i}: &a{i} [{}]\n",
            vec![format!("*a{}", i - 1); 9].join(", ")
        ));
    }
    rejects("lol", "lol.yaml", &lol, &["line 10, column 7", "anchor"]);
    // Both used to take seconds (the 200,000 brackets about a minute).
    assert!(t0.elapsed().as_secs_f64() < 5.0, "{:?}", t0.elapsed());
}

#[test]
fn duplicate_keys_are_reported_at_their_line() {
    // serde_yaml put a repeated top-level key at line 1.
    let text = cross("").replacen("units: mm\n", "units: mm\ntolerance: 1\n", 1) + "tolerance: 2\n";
    rejects(
        "dupkey",
        "dupkey.yaml",
        &text,
        &[
            "line 10, column 1",
            "duplicate key `tolerance` (first at line 2)",
        ],
    );
    let text = cross("").replacen("    family: A\n", "    family: A\n    family: B\n", 1);
    rejects(
        "dupkey-nested",
        "dupkey2.yaml",
        &text,
        &[
            "line 5, column 5",
            "duplicate key `family` (first at line 4)",
        ],
    );
}

#[test]
fn duplicate_ids_name_both_curves_in_every_format() {
    let text = cross("  - id: A00\n    family: A\n    points: [[50, -100, 0], [50, 100, 0]]\n");
    rejects(
        "dup-yaml",
        "dup.yaml",
        &text,
        &["curve A00", "curves[0] and curves[2]"],
    );
    let json = r#"{"units": "mm", "curves": [
        {"id": "A", "family": "A", "points": [[0, -1, 0], [0, 1, 0]]},
        {"id": "B", "family": "B", "points": [[-1, 0, 0], [1, 0, 0]]},
        {"id": "B", "family": "B", "points": [[-1, 0.5, 0], [1, 0.5, 0]]}]}"#;
    rejects(
        "dup-json",
        "dup.json",
        json,
        &["curve B", "curves[1] and curves[2]"],
    );
    // OBJ: a second object with the same name was renamed A1.1, A1.2.
    let obj = "o A1\nv 0 -1 0\nv 0 1 0\nl 1 2\no B1\nv -1 0 0\nv 1 0 0\nl 3 4\no A1\nv 1 -1 0\nv 1 1 0\nl 5 6\n";
    rejects(
        "dup-obj",
        "dup.obj",
        obj,
        &[
            "line 12",
            "'A1' (line 9)",
            "same name as the object at line 1",
        ],
    );
    // ... and so was a second, disjoint polyline of one object.
    let obj = "o A1\nv 0 -1 0\nv 0 1 0\nv 1 -1 0\nv 1 1 0\nl 1 2\nl 3 4\no B1\nv -1 0 0\nv 1 0 0\nl 5 6\n";
    rejects(
        "dup-obj-piece",
        "piece.obj",
        obj,
        &["line 7", "'A1' (line 1)", "second polyline"],
    );
}

#[test]
fn truncated_obj_is_an_error_not_a_missing_curve() {
    // The last object lost its `l` line: it used to vanish silently.
    let obj =
        "o A1\nv 0 -1 0\nv 0 1 0\nl 1 2\no B1\nv -1 0 0\nv 1 0 0\no B2\nv -1 0.5 0\nv 1 0.5 0\n";
    rejects(
        "obj-cut",
        "cut.obj",
        obj,
        &["line 5", "'B1'", "no polyline", "cut short"],
    );
    let obj = "o A1\nv 0 -1 0\nv 0 1 0\nl 1 2\no B1\nv -1 0 0\nv 1 0 0\nl 3 4\no B2\nv -1 0.5 0\n";
    rejects(
        "obj-cut-last",
        "cut2.obj",
        obj,
        &["line 9", "'B2'", "cut short"],
    );
}

#[test]
fn a_byte_order_mark_is_accepted_by_every_reader() {
    let dir = scratch("bom");
    let json = "\u{feff}{\"units\": \"mm\", \"curves\": [{\"id\": \"A\", \"family\": \"A\", \"points\": [[0, -1, 0], [0, 1, 0]]}, {\"id\": \"B\", \"family\": \"B\", \"points\": [[-1, 0, 0], [1, 0, 0]]}]}";
    let obj = "\u{feff}o A1\nv 0 -1 0\nv 0 1 0\nl 1 2\no B1\nv -1 0 0\nv 1 0 0\nl 3 4\n";
    let yaml = format!("\u{feff}{}", cross(""));
    for (name, text) in [("n.json", json), ("n.obj", obj), ("n.yaml", yaml.as_str())] {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        let net = read_network(&p, ReadOptions::default());
        assert!(net.is_ok(), "{name}: {:?}", net.err());
    }
    // A profile and a trace spec with a BOM read too.
    let root = root();
    let profile = dir.join("p.yaml");
    let text = std::fs::read_to_string(root.join("profiles/steel-1.5.yaml")).unwrap();
    std::fs::write(&profile, format!("\u{feff}{text}")).unwrap();
    assert!(lamella::formats::read::profile_file::load(&profile).is_ok());
    let spec = dir.join("s.trace.yaml");
    let text = std::fs::read_to_string(root.join("samples/hypar-small.trace.yaml")).unwrap();
    std::fs::write(&spec, format!("\u{feff}{text}")).unwrap();
    assert!(lamella::formats::read::trace_spec::load(&spec).is_ok());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn profile_fields_are_bounded_under_their_own_names() {
    // height 1e300 used to be blamed on stock.width_mm.
    let dir = scratch("profile-huge");
    let root = root();
    let text = std::fs::read_to_string(root.join("profiles/steel-1.5.yaml")).unwrap();
    assert!(text.contains("height_mm: 50.0"));
    let p = dir.join("huge.yaml");
    std::fs::write(
        &p,
        text.replacen("height_mm: 50.0", "height_mm: 1.0e300", 1),
    )
    .unwrap();
    let (code, _, stderr) = lamella(&[
        "check",
        "samples/hypar-small.yaml",
        "--profile",
        p.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains("field `lamella.height_mm`: must be at most 1e7 mm"),
        "{stderr}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn deep_profiles_and_specs_are_refused() {
    let dir = scratch("deep-profile");
    let deep = format!(
        "version: 1\nname: {}{}\n",
        "{a: ".repeat(100),
        "}".repeat(100)
    );
    let p = dir.join("deep.yaml");
    std::fs::write(&p, deep).unwrap();
    let e = lamella::formats::read::profile_file::load(&p)
        .unwrap_err()
        .to_string();
    assert!(e.contains("line 2") && e.contains("deeper than 64"), "{e}");
    let s = dir.join("deep.trace.yaml");
    std::fs::write(&s, "name: x\nalias: *x\n").unwrap();
    let e = lamella::formats::read::trace_spec::load(&s)
        .unwrap_err()
        .to_string();
    assert!(e.contains("line 2, column 8") && e.contains("alias"), "{e}");
    // Specs and profiles are small: a 2 MiB one is refused before parsing.
    std::fs::write(&s, "#".repeat(2 << 20)).unwrap();
    let e = lamella::formats::read::trace_spec::load(&s)
        .unwrap_err()
        .to_string();
    assert!(e.contains("more than the 1 MiB"), "{e}");
    std::fs::remove_dir_all(dir).unwrap();
}

/// A device behind a file name (`/dev/zero` reports size 0 and never ends)
/// is read only up to the size limit of its kind of file, then refused in
/// one line: as a network, a profile, a trace spec and a spec's mesh.
#[cfg(unix)]
#[test]
fn endless_files_are_refused_at_their_size_limit() {
    let dir = scratch("endless");
    let link = |name: &str| {
        let p = dir.join(name);
        std::os::unix::fs::symlink("/dev/zero", &p).expect("symlink");
        p
    };
    let (network, profile, spec) = (link("net.yaml"), link("p.yaml"), link("s.trace.yaml"));
    let mesh = link("m.obj");
    let mesh_spec = dir.join("mesh.trace.yaml");
    let text = std::fs::read_to_string(root().join("samples/mesh-enneper.trace.yaml"))
        .expect("sample spec")
        .replace(
            "mesh: meshes/enneper-4m.obj",
            &format!("mesh: {}", mesh.display()),
        );
    std::fs::write(&mesh_spec, text).expect("write spec");
    let hypar = root().join("samples/hypar-small.yaml");
    let (out, traced) = (dir.join("out"), dir.join("t.yaml"));
    let args = |a: &[&std::path::Path]| -> Vec<std::ffi::OsString> {
        a.iter().map(|p| p.as_os_str().to_owned()).collect()
    };
    let p = |s: &'static str| std::path::Path::new(s);
    let cases = [
        (
            args(&[p("nodes"), &network, p("--out"), &out]),
            &network,
            "256 MiB",
        ),
        (
            args(&[p("check"), &hypar, p("--profile"), &profile]),
            &profile,
            "1 MiB",
        ),
        (
            args(&[p("trace"), &spec, p("--out"), &traced]),
            &spec,
            "1 MiB",
        ),
        (
            args(&[p("trace"), &mesh_spec, p("--out"), &traced]),
            &mesh,
            "MiB lamella reads in a mesh file",
        ),
    ];
    for (args, named, limit) in cases {
        let t = std::time::Instant::now();
        let (code, _, stderr) = lamella(&args);
        assert_eq!(code, Some(1), "{stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(
            stderr.contains(&named.display().to_string()) && stderr.contains(limit),
            "{stderr}"
        );
        assert!(stderr.contains("a stream of over"), "{stderr}");
        // Reading 256 MiB of zeros takes a fraction of a second; reading
        // until memory runs out took several seconds and gigabytes.
        assert!(t.elapsed().as_secs() < 20, "{:?}", t.elapsed());
    }
}
