//! Tracing on meshes and films (`surface: mesh`, `surface: minimal`): the
//! traced net on a triangulated Enneper surface against the closed form,
//! converging as the mesh is refined; the shipped film specs regenerate
//! their samples and run through `nodes` and `check`; bad meshes get
//! one-line errors.

use crate::support::meshes::{obj_text, param_mesh, saddle_grid};
use crate::support::*;
use glam::{DMat3, DVec2, DVec3};
use lamella::design::design;
use lamella::design::surface::{Enneper, Placed, Surface};
use lamella::formats::read::mesh::read_mesh;
use lamella::formats::read::trace_spec;
use std::sync::Arc;

/// The Enneper surface of the 4 m sample: scale 4400 mm, turned 45° about z.
fn enneper_4m() -> Placed {
    Placed {
        surface: Arc::new(Enneper),
        scale_mm: 4400.0,
        rotation: DMat3::from_rotation_z(45f64.to_radians()),
        translation_mm: DVec3::ZERO,
    }
}

/// Trace the 4 m Enneper net on an n × n-cell mesh of the surface over
/// (u, v) ∈ [−0.45, 0.45]² (jittered, written as OBJ at 0.001 mm, no
/// normals) and return the largest distance (mm) of a traced point from the
/// closed-form asymptotic line u ± v = const through its curve's start, and
/// the number of traced points.
fn enneper_mesh_error(n: usize) -> (f64, usize) {
    let dir = scratch(&format!("enneper{n}"));
    let (v, t) = param_mesh(&Enneper, 4400.0, 45.0, 0.45, n, 0.25);
    std::fs::write(dir.join("enneper.obj"), obj_text(&v, &t)).unwrap();
    let spec_path = dir.join("enneper.trace.yaml");
    std::fs::write(
        &spec_path,
        "surface: mesh\nmesh: enneper.obj\nseed_mm: [0, 0, 0]\nspacing_mm: 270\n\
         clip:\n  box:\n    min_mm: [-1200, -1200, -3000]\n    max_mm: [1200, 1200, 3000]\n\
         sampling:\n  step_mm: 25\n  tolerance_mm: 1.0e-4\n",
    )
    .unwrap();
    let spec = trace_spec::load(&spec_path).unwrap();
    let (net, _) = design(&spec, &spec_path, &read_mesh).unwrap();
    let surface = enneper_4m();
    let (mut worst, mut points) = (0.0f64, 0);
    for c in net
        .curves
        .iter()
        .filter(|c| c.family != lamella::Family::Edge)
    {
        let uvs: Vec<DVec2> = c.points.iter().map(|p| invert(&surface, *p)).collect();
        let start = uvs[0];
        // The family: the diagonal coordinate that varies least along it.
        let along_p = keeps_u_plus_v(&uvs);
        for (q, pt) in uvs.iter().zip(&c.points) {
            let exact = diagonal_closed_form(start, *q, along_p);
            let e = pt.distance(surface.point(exact));
            worst = worst.max(e);
            points += 1;
        }
    }
    std::fs::remove_dir_all(dir).unwrap();
    (worst, points)
}

/// The traced net on the mesh follows the closed form, and refining the
/// mesh (cells 99 mm → 50 mm along u, jittered by a quarter cell, rounded
/// to 0.001 mm) shrinks the error. Measured: 0.161 mm → 0.082 mm over
/// curves up to 3.4 m long: order 0.96 for the largest error. The points
/// are O(h³) off the surface and the curvature tensors O(h²) inside, so the
/// direction error (× the curve's length) dominates; the one-sided fits at
/// the mesh's rim (the clip reaches within two cells of it) and the
/// tensors' linear interpolation keep the largest error's order near 1.
/// Finer than ~40 mm the coordinates' rounding (0.001 mm, noise
/// 0.001/(2h)² in curvature) overtakes the truncation error (README).
#[test]
fn traced_enneper_mesh_converges_to_the_closed_form() {
    let (coarse, n1) = enneper_mesh_error(40);
    let (fine, n2) = enneper_mesh_error(80);
    let order = (coarse / fine).log2();
    eprintln!("Enneper mesh: {coarse:.4} mm (40², {n1} points), {fine:.4} mm (80², {n2} points), order {order:.2}");
    assert!(n1 > 1500 && n2 > 1500);
    assert!(coarse < 0.2, "{coarse} mm on the 40² mesh");
    assert!(fine < 0.1, "{fine} mm on the 80² mesh");
    assert!(order > 0.8, "order {order:.2}");
}

/// A saddle z = (x² − y²)/(2R) on a regular grid with straight rim
/// sides, written as OBJ at 0.001 mm, traces at every cell count (it was
/// refused at 80 × 80 and 150 × 150: its symmetric best-fit plane puts two
/// rim sides exactly along a chart axis, their collinear edges counted as
/// crossing, and the mesh was charted onto a circle instead, whose corners
/// folded the traced normals). Its asymptotic lines are its rulings
/// x ± y = const: every traced curve is straight and keeps its x ± y.
#[test]
fn a_regular_grid_saddle_traces_at_fine_cells() {
    let (half_mm, r_mm) = (1500.0, 3000.0);
    for n in [80, 150] {
        let dir = scratch(&format!("saddle{n}"));
        let (v, t) = saddle_grid(n, half_mm, r_mm);
        std::fs::write(dir.join("saddle.obj"), obj_text(&v, &t)).unwrap();
        std::fs::write(
            dir.join("saddle.trace.yaml"),
            "surface: mesh\nmesh: saddle.obj\nseed_mm: [0, 0, 0]\nspacing_mm: 300\n\
             sampling:\n  step_mm: 25\n",
        )
        .unwrap();
        let (code, stdout, stderr) =
            lamella_in(&dir, &["trace", "saddle.trace.yaml", "--out", "net.yaml"]);
        assert_eq!(code, Some(0), "{n} × {n}: {stderr}");
        assert!(
            stdout.contains("charted by its best-fit plane"),
            "{n} × {n}: {stdout}"
        );
        let spec_path = dir.join("saddle.trace.yaml");
        let spec = trace_spec::load(&spec_path).unwrap();
        let (net, report) = design(&spec, &spec_path, &read_mesh).unwrap();
        assert!(report.a_curves >= 10 && report.b_curves >= 10, "{report:?}");
        let mut worst = 0.0f64;
        for c in net
            .curves
            .iter()
            .filter(|c| c.family != lamella::Family::Edge)
        {
            let (p0, p1) = (c.points[0], *c.points.last().unwrap());
            // The ruling through the first point: x ∓ y constant.
            let sum = (p1.x + p1.y - p0.x - p0.y).abs() < (p1.x - p1.y - p0.x + p0.y).abs();
            let key = |p: DVec3| if sum { p.x + p.y } else { p.x - p.y };
            for p in &c.points {
                worst = worst.max((key(*p) - key(p0)).abs());
            }
        }
        eprintln!("saddle {n} × {n}: curves within {worst:.4} mm of their rulings");
        assert!(
            worst < 0.2,
            "{n} × {n}: a curve leaves its ruling by {worst} mm"
        );
        std::fs::remove_dir_all(dir).unwrap();
    }
}

const FILMS: [&str; 5] = [
    "film-saddle",
    "film-three-peaks",
    "film-rings",
    "film-oculus",
    "mesh-enneper",
];

#[test]
fn shipped_film_and_mesh_specs_regenerate_their_samples_and_run_through_nodes_and_check() {
    let dir = scratch("films");
    for name in FILMS {
        let out = dir.join(format!("{name}.yaml"));
        let spec = format!("samples/{name}.trace.yaml");
        let (code, stdout, stderr) = lamella(&["trace", &spec, "--out", out.to_str().unwrap()]);
        assert_eq!(code, Some(0), "{name}: {stderr}");
        assert!(stdout.contains("mesh:"), "{name}: {stdout}");
        let strip = |t: String| {
            t.lines()
                .filter(|l| !l.starts_with('#'))
                .collect::<Vec<_>>()
                .join("\n")
        };
        let made = strip(std::fs::read_to_string(&out).unwrap());
        let shipped =
            strip(std::fs::read_to_string(root().join(format!("samples/{name}.yaml"))).unwrap());
        assert!(
            made == shipped,
            "{name}: samples/{name}.yaml is not what its spec traces"
        );
        let (code, _, stderr) = lamella(&[
            "nodes",
            out.to_str().unwrap(),
            "--out",
            dir.join(name).to_str().unwrap(),
        ]);
        assert_eq!(code, Some(0), "{name}: nodes: {stderr}");
        // The elastic check runs to a verdict: 0 (all strips bend
        // elastically) or 3 (some overstressed), never an input error.
        let (code, _, stderr) = lamella(&[
            "check",
            out.to_str().unwrap(),
            "--profile",
            "profiles/steel-1.5.yaml",
        ]);
        assert!(matches!(code, Some(0 | 3)), "{name}: check: {stderr}");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// The film over a curve with three high and three low points has one flat
/// point, a monkey saddle at its centre (index −1/2), and `trace` reports it.
#[test]
fn the_three_peak_film_reports_its_monkey_saddle() {
    let dir = scratch("peaks");
    let out = dir.join("net.yaml");
    let (code, stdout, stderr) = lamella(&[
        "trace",
        "samples/film-three-peaks.trace.yaml",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(0), "{stderr}");
    let lines: Vec<&str> = stdout
        .lines()
        .filter(|l| l.contains("singular point"))
        .collect();
    assert_eq!(lines.len(), 1, "{stdout}");
    assert!(lines[0].contains("index -1/2"), "{stdout}");
    // At the centre (the boundary is symmetric under a third of a turn, so
    // the film's flat point is on the axis): within two mesh edges (100 mm).
    let at = lines[0]
        .split("at (")
        .nth(1)
        .unwrap()
        .split(')')
        .next()
        .unwrap()
        .split(", ")
        .map(|x| x.trim_end_matches(" mm").parse::<f64>().unwrap())
        .collect::<Vec<_>>();
    assert!(at[0].hypot(at[1]) < 100.0, "{:?}", at);
    std::fs::remove_dir_all(dir).unwrap();
}

fn bad_mesh(name: &str, obj: &str, fragments: &[&str]) {
    let dir = scratch(name);
    std::fs::write(dir.join("m.obj"), obj).unwrap();
    std::fs::write(
        dir.join("m.trace.yaml"),
        "surface: mesh\nmesh: m.obj\nspacing_mm: 300\n",
    )
    .unwrap();
    let (code, _, stderr) = lamella_in(&dir, &["trace", "m.trace.yaml", "--out", "net.yaml"]);
    assert_ne!(code, Some(0), "{name}: accepted");
    assert_eq!(stderr.trim().lines().count(), 1, "{name}: {stderr}");
    for f in fragments {
        assert!(stderr.contains(f), "{name}: {stderr} lacks {f}");
    }
    assert!(!dir.join("net.yaml").exists(), "{name}: wrote a network");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn bad_meshes_get_one_line_errors() {
    // Three triangles on one edge.
    bad_mesh(
        "nonmanifold",
        "v 0 0 0\nv 1000 0 0\nv 0 1000 0\nv 0 -1000 0\nv 0 0 1000\nf 1 2 3\nf 2 1 4\nf 1 2 5\n",
        &["m.obj", "edge"],
    );
    // A triangle with no area.
    bad_mesh(
        "degenerate",
        "v 0 0 0\nv 1000 0 0\nv 2000 0 0\nv 0 1000 0\nf 1 2 3\nf 1 2 4\n",
        &["m.obj", "triangle"],
    );
    // A sphere cap: synclastic, no asymptotic directions anywhere.
    let mut obj = String::new();
    let (n, r) = (12usize, 1000.0f64);
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (
                -400.0 + 800.0 * i as f64 / n as f64,
                -400.0 + 800.0 * j as f64 / n as f64,
            );
            obj.push_str(&format!(
                "v {x:.3} {y:.3} {:.3}\n",
                (r * r - x * x - y * y).sqrt()
            ));
        }
    }
    for j in 0..n {
        for i in 0..n {
            let id = |i: usize, j: usize| j * (n + 1) + i + 1;
            obj.push_str(&format!(
                "f {} {} {}\n",
                id(i, j),
                id(i + 1, j),
                id(i + 1, j + 1)
            ));
            obj.push_str(&format!(
                "f {} {} {}\n",
                id(i, j),
                id(i + 1, j + 1),
                id(i, j + 1)
            ));
        }
    }
    bad_mesh("sphere", &obj, &["m.obj", "no anticlastic region"]);
}

/// A spec in a folder with the Enneper sample mesh; the one-line error.
fn bad_spec(name: &str, spec: &str, fragments: &[&str]) {
    let dir = scratch(name);
    std::fs::copy(
        root().join("samples/meshes/enneper-4m.obj"),
        dir.join("m.obj"),
    )
    .unwrap();
    std::fs::write(dir.join("s.trace.yaml"), spec).unwrap();
    let (code, _, stderr) = lamella_in(&dir, &["trace", "s.trace.yaml", "--out", "net.yaml"]);
    assert_ne!(code, Some(0), "{name}: accepted");
    assert_eq!(stderr.trim().lines().count(), 1, "{name}: {stderr}");
    for f in fragments {
        assert!(stderr.contains(f), "{name}: {stderr} lacks {f}");
    }
    assert!(!dir.join("net.yaml").exists());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn bad_mesh_and_film_specs_get_one_line_errors() {
    let base = "spacing_mm: 300\n";
    bad_spec(
        "nomesh",
        &format!("surface: mesh\n{base}"),
        &["`mesh`", "OBJ, PLY or STL"],
    );
    bad_spec(
        "nofile",
        &format!("surface: mesh\nmesh: gone.obj\n{base}"),
        &["`mesh`", "no such file"],
    );
    bad_spec(
        "uvseed",
        &format!("surface: mesh\nmesh: m.obj\nseed: [0, 0]\n{base}"),
        &["`seed`", "seed_mm"],
    );
    bad_spec(
        "scaled",
        &format!("surface: mesh\nmesh: m.obj\nscale_mm: 1000\n{base}"),
        &["`scale_mm`", "in mm"],
    );
    bad_spec(
        "far",
        &format!("surface: mesh\nmesh: m.obj\nseed_mm: [0, 0, 5000]\n{base}"),
        &["`seed_mm`", "from the surface"],
    );
    bad_spec(
        "uvclip",
        &format!("surface: mesh\nmesh: m.obj\nclip:\n  parameters:\n    polygon: [[0, 0], [1, 0], [0, 1]]\n{base}"),
        &["`clip`", "no parameters"],
    );
    bad_spec(
        "noboundary",
        &format!("surface: minimal\n{base}"),
        &["`boundaries_mm`"],
    );
    bad_spec(
        "twopoints",
        &format!("surface: minimal\nboundaries_mm:\n  - [[0, 0, 0], [1000, 0, 0]]\n{base}"),
        &["boundaries[0]"],
    );
    bad_spec(
        "meshonanalytic",
        &format!("surface: enneper\nscale_mm: 1000\nseed: [0, 0]\nmesh: m.obj\n{base}"),
        &["`mesh`", "surface: mesh"],
    );
}

/// A mesh with some triangles wound against their neighbours is
/// reoriented, and `trace` says so (how many, and the first in file
/// order) in its warnings, on stderr and in the design report; the net is
/// the one traced on the consistently wound mesh.
#[test]
fn inconsistent_winding_is_repaired_with_a_warning() {
    let dir = scratch("winding");
    let (v, mut t) = saddle_grid(20, 1500.0, 3000.0);
    std::fs::write(dir.join("good.obj"), obj_text(&v, &t)).unwrap();
    for k in [4, 76, 299] {
        t[k].swap(1, 2);
    }
    std::fs::write(dir.join("bad.obj"), obj_text(&v, &t)).unwrap();
    let spec =
        |mesh: &str| format!("surface: mesh\nmesh: {mesh}\nseed_mm: [0, 0, 0]\nspacing_mm: 300\n");
    std::fs::write(dir.join("good.trace.yaml"), spec("good.obj")).unwrap();
    std::fs::write(dir.join("bad.trace.yaml"), spec("bad.obj")).unwrap();
    let warning =
        "3 triangle(s) were flipped to agree with their neighbours (the first: triangle 4)";
    let (code, _, stderr) = lamella_in(&dir, &["trace", "bad.trace.yaml", "--out", "bad.yaml"]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stderr.contains(&format!("warning: {warning}")), "{stderr}");
    let (code, _, stderr) = lamella_in(&dir, &["trace", "good.trace.yaml", "--out", "good.yaml"]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(!stderr.contains("flipped"), "{stderr}");
    let body = |f: &str| {
        std::fs::read_to_string(dir.join(f))
            .unwrap()
            .lines()
            .filter(|l| !l.starts_with('#') && !l.starts_with("name:"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert!(
        body("bad.yaml") == body("good.yaml"),
        "the repaired mesh traces another net"
    );
    let spec_path = dir.join("bad.trace.yaml");
    let (_, report) = design(
        &trace_spec::load(&spec_path).unwrap(),
        &spec_path,
        &read_mesh,
    )
    .unwrap();
    assert!(
        report.warnings.iter().any(|w| w == warning),
        "{:?}",
        report.warnings
    );
    std::fs::remove_dir_all(dir).unwrap();
}
