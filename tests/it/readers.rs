//! The input formats (YAML, JSON, OBJ, DXF) give the same network: one
//! closed-form network written in every format, read back and analysed, must
//! give the same nodes at the same stations. Also: DXF SPLINEs are evaluated
//! as NURBS, and units (OBJ override, DXF `$INSUNITS`) scale to mm.

use crate::support::scratch;
use crate::support::synth::{self, Hypar, Sampling};
use dxf::entities::{Entity, EntityType, Line, LwPolyline, Polyline, Spline, Vertex};
use dxf::enums::{AcadVersion, Units};
use dxf::{Drawing, LwPolylineVertex, Point, Vector};
use glam::DVec3;
use lamella::formats::read::{network_file, read_network, read_raw, ReadOptions};
use lamella::network::{Family, Network, RawNetwork, Unit};
use lamella::{analyze, AnalysisOptions};
use std::fmt::Write as _;
use std::path::Path;

/// Node stations must agree this closely between the polyline formats (mm).
const STATION_TOL_MM: f64 = 1e-6;

/// The hyperbolic paraboloid z = xy/1500 over ±600 mm, its rulings as the
/// A (x = const) and B (y = const) curves: 5 × 5 curves, 25 nodes.
fn reference() -> RawNetwork {
    let values = synth::spread(600.0, 5);
    let lines = synth::coordinate_lines(&values, &values);
    synth::network(
        "readers",
        &Hypar { c: 1500.0 },
        &lines,
        1.0,
        Sampling {
            step_mm: 40.0,
            normals: false,
        },
    )
}

// ---------------------------------------------------------------- writers

/// OBJ: one object per curve, named by its id; coordinates divided by `div`.
fn write_obj(raw: &RawNetwork, path: &Path, div: f64) {
    let mut out = String::from("# lamella readers test\n");
    let mut next = 1;
    for c in &raw.curves {
        let _ = writeln!(out, "o {}", c.id);
        for p in &c.points {
            let q = *p / div;
            let _ = writeln!(out, "v {} {} {}", q.x, q.y, q.z);
        }
        let indices: Vec<String> = (next..next + c.points.len())
            .map(|i| i.to_string())
            .collect();
        let _ = writeln!(out, "l {}", indices.join(" "));
        next += c.points.len();
    }
    std::fs::write(path, out).expect("write OBJ");
}

fn pt(p: DVec3) -> Point {
    Point::new(p.x, p.y, p.z)
}

fn on_layer(layer: &str, specific: EntityType) -> Entity {
    let mut e = Entity::new(specific);
    e.common.layer = layer.to_string();
    e
}

fn new_drawing(units: Units) -> Drawing {
    let mut drawing = Drawing::new();
    // SPLINE needs R13, LWPOLYLINE R14 and $INSUNITS R2000.
    drawing.header.version = AcadVersion::R2000;
    drawing.header.default_drawing_units = units;
    drawing
}

fn add_polyline3d(drawing: &mut Drawing, layer: &str, points: &[DVec3]) {
    let mut pl = Polyline::default();
    pl.set_is_3d_polyline(true);
    for &p in points {
        let mut v = Vertex::new(pt(p));
        v.set_is_3d_polyline_vertex(true);
        pl.add_vertex(drawing, v);
    }
    drawing.add_entity(on_layer(layer, EntityType::Polyline(pl)));
}

/// The DXF arbitrary-axis algorithm: the OCS axes of an extrusion direction.
fn ocs_axes(normal: DVec3) -> (DVec3, DVec3, DVec3) {
    let az = normal.normalize();
    let ax = if az.x.abs() < 1.0 / 64.0 && az.y.abs() < 1.0 / 64.0 {
        DVec3::Y.cross(az).normalize()
    } else {
        DVec3::Z.cross(az).normalize()
    };
    (ax, az.cross(ax).normalize(), az)
}

/// An LWPOLYLINE through `points`, which must lie in the plane through the
/// origin normal to `normal` (LWPOLYLINEs here carry no elevation).
fn add_lwpolyline(drawing: &mut Drawing, layer: &str, points: &[DVec3], normal: DVec3) {
    let (ax, ay, az) = ocs_axes(normal);
    let mut lw = LwPolyline {
        extrusion_direction: Vector::new(normal.x, normal.y, normal.z),
        ..Default::default()
    };
    for &p in points {
        assert!(p.dot(az).abs() < 1e-9, "point {p} is not in the OCS plane");
        lw.vertices.push(LwPolylineVertex {
            x: p.dot(ax),
            y: p.dot(ay),
            ..Default::default()
        });
    }
    drawing.add_entity(on_layer(layer, EntityType::LwPolyline(lw)));
}

fn add_line(drawing: &mut Drawing, layer: &str, p0: DVec3, p1: DVec3) {
    drawing.add_entity(on_layer(layer, EntityType::Line(Line::new(pt(p0), pt(p1)))));
}

fn spline(degree: i32, knots: &[f64], ctrl: &[DVec3], weights: Option<&[f64]>) -> Spline {
    let mut s = Spline {
        degree_of_curve: degree,
        knot_values: knots.to_vec(),
        control_points: ctrl.iter().map(|&p| pt(p)).collect(),
        ..Default::default()
    };
    if let Some(w) = weights {
        s.weight_values = w.to_vec();
        s.set_is_rational(true);
    }
    s
}

/// Control points of a clamped cubic B-spline along the straight segment
/// p0–p1, unevenly but monotonically spaced: the curve is the segment itself,
/// but its evaluated points are not the control points.
const LINE_SPLINE_KNOTS: [f64; 10] = [0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0];
fn line_spline(p0: DVec3, p1: DVec3) -> Spline {
    let fractions = [0.0, 0.1, 0.45, 0.5, 0.8, 1.0];
    let ctrl: Vec<DVec3> = fractions.iter().map(|&f| p0.lerp(p1, f)).collect();
    spline(3, &LINE_SPLINE_KNOTS, &ctrl, None)
}

/// The reference network as DXF, every entity kind in use, in curve order:
/// A01 and A02 as LWPOLYLINEs (A01 in a tilted OCS), B01 as a cubic SPLINE,
/// B04 as a LINE, the rest as 3D POLYLINEs. Coordinates divided by `div`.
fn write_dxf(raw: &RawNetwork, path: &Path, units: Units, div: f64) {
    let mut drawing = new_drawing(units);
    for c in &raw.curves {
        let pts: Vec<DVec3> = c.points.iter().map(|&p| p / div).collect();
        let layer = match c.family {
            Family::A => "A",
            Family::B => "B",
            Family::Edge => "edge",
        };
        let (first, last) = (pts[0], pts[pts.len() - 1]);
        match c.id.as_str() {
            "A01" => {
                // x = x1: the plane through the origin and this ruling.
                let n = first.cross(last - first);
                add_lwpolyline(&mut drawing, layer, &pts, n);
            }
            "A02" => add_lwpolyline(&mut drawing, layer, &pts, DVec3::Z), // x = 0: z = 0
            "B01" => {
                let s = line_spline(first, last);
                drawing.add_entity(on_layer(layer, EntityType::Spline(s)));
            }
            "B04" => add_line(&mut drawing, layer, first, last),
            _ => add_polyline3d(&mut drawing, layer, &pts),
        }
    }
    drawing.save_file(path).expect("write DXF");
}

// ---------------------------------------------------------------- checks

struct Analysed {
    net: Network,
    /// (a, b, station on a, station on b, position), sorted.
    nodes: Vec<(usize, usize, f64, f64, DVec3)>,
    lengths: Vec<f64>,
}

fn read_and_analyze(path: &Path, opts: ReadOptions) -> Analysed {
    let net = read_network(path, opts).unwrap_or_else(|e| panic!("read {}: {e}", path.display()));
    let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analysis");
    let mut nodes: Vec<_> = an
        .topology
        .nodes
        .iter()
        .map(|n| {
            (
                n.a,
                n.b,
                n.station_a_mm,
                n.station_b_mm,
                n.position_world_mm,
            )
        })
        .collect();
    nodes.sort_by(|x, y| (x.0, x.1).cmp(&(y.0, y.1)).then(x.2.total_cmp(&y.2)));
    let lengths = an.strips.iter().map(|s| s.length_mm).collect();
    Analysed {
        net,
        nodes,
        lengths,
    }
}

fn assert_same_nodes(what: &str, got: &Analysed, want: &Analysed, tol: f64) {
    assert_eq!(
        got.net.curves.len(),
        want.net.curves.len(),
        "{what}: curve count"
    );
    for (g, w) in got.net.curves.iter().zip(&want.net.curves) {
        assert_eq!(g.family, w.family, "{what}: family of {} / {}", g.id, w.id);
    }
    assert_eq!(got.nodes.len(), want.nodes.len(), "{what}: node count");
    for (g, w) in got.nodes.iter().zip(&want.nodes) {
        assert_eq!((g.0, g.1), (w.0, w.1), "{what}: node curves");
        assert!(
            (g.2 - w.2).abs() < tol && (g.3 - w.3).abs() < tol,
            "{what}: node on curves {}×{}: stations ({}, {}) vs ({}, {})",
            w.0,
            w.1,
            g.2,
            g.3,
            w.2,
            w.3
        );
        assert!(
            g.4.distance(w.4) < tol,
            "{what}: node position {} vs {}",
            g.4,
            w.4
        );
    }
    for (k, (g, w)) in got.lengths.iter().zip(&want.lengths).enumerate() {
        assert!(
            (g - w).abs() < tol,
            "{what}: length of curve {k}: {g} vs {w}"
        );
    }
}

fn assert_points_close(what: &str, got: &[DVec3], want: &[DVec3], tol: f64) {
    assert_eq!(got.len(), want.len(), "{what}: point count");
    for (k, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(g.distance(*w) < tol, "{what}: point {k}: {g} vs {w}");
    }
}

// ---------------------------------------------------------------- tests

#[test]
fn all_formats_give_the_same_network() {
    let dir = scratch("all_formats");
    let raw = reference();
    let yaml = dir.join("net.yaml");
    let json = dir.join("net.json");
    let obj = dir.join("net.obj");
    let dxf = dir.join("net.dxf");
    std::fs::write(&yaml, network_file::to_yaml(&raw, 12, "readers test")).expect("write YAML");
    std::fs::write(&json, network_file::to_json(&raw, 12)).expect("write JSON");
    write_obj(&raw, &obj, 1.0);
    write_dxf(&raw, &dxf, Units::Millimeters, 1.0);

    let opts = ReadOptions::default();
    let from_yaml = read_and_analyze(&yaml, opts);
    let from_json = read_and_analyze(&json, opts);
    let from_obj = read_and_analyze(&obj, opts);
    let from_dxf = read_and_analyze(&dxf, opts);

    // The reference network itself: a 5 × 5 grid of rulings, 25 nodes.
    assert_eq!(from_yaml.net.curves.len(), 10);
    assert_eq!(from_yaml.nodes.len(), 25, "A×B nodes of the 5 × 5 grid");
    let ids: Vec<&str> = from_yaml.net.curves.iter().map(|c| c.id.as_str()).collect();
    let want_ids: Vec<&str> = raw.curves.iter().map(|c| c.id.as_str()).collect();
    assert_eq!(ids, want_ids);
    for (c, r) in from_yaml.net.curves.iter().zip(&raw.curves) {
        assert_points_close(
            &format!("YAML {}", c.id),
            &c.points_world_mm,
            &r.points,
            1e-9,
        );
    }

    // JSON and OBJ carry the same polylines.
    assert_eq!(from_json.net.curves, from_yaml.net.curves, "JSON curves");
    let obj_ids: Vec<&str> = from_obj.net.curves.iter().map(|c| c.id.as_str()).collect();
    assert_eq!(obj_ids, want_ids, "OBJ object names are the curve ids");
    assert_eq!(from_obj.net.file_unit, Unit::Mm, "OBJ defaults to mm");
    for (c, r) in from_obj.net.curves.iter().zip(&from_yaml.net.curves) {
        assert_eq!(c.family, r.family);
        assert_points_close(
            &format!("OBJ {}", c.id),
            &c.points_world_mm,
            &r.points_world_mm,
            1e-9,
        );
    }
    assert_same_nodes("JSON", &from_json, &from_yaml, STATION_TOL_MM);
    assert_same_nodes("OBJ", &from_obj, &from_yaml, STATION_TOL_MM);

    // DXF: the polylines (3D POLYLINE, LWPOLYLINE in world and tilted OCS)
    // come back point for point; the LINE and the SPLINE are the same
    // straight rulings sampled differently.
    assert_eq!(from_dxf.net.file_unit, Unit::Mm, "$INSUNITS = mm");
    assert_eq!(
        from_dxf.net.curves.len(),
        raw.curves.len(),
        "every DXF entity is read"
    );
    for (c, r) in from_dxf.net.curves.iter().zip(&raw.curves) {
        assert_eq!(c.family, r.family, "DXF layer gives the family of {}", r.id);
        let layer = if r.family == Family::A { "A-" } else { "B-" };
        assert!(
            c.id.starts_with(layer),
            "DXF curve id {} names its layer",
            c.id
        );
        match r.id.as_str() {
            "B01" => {
                // The cubic SPLINE is sampled along its 3 knot spans, not
                // taken as its 6 control points, and stays on the ruling.
                let n = 3 * lamella::formats::read::dxf::SPLINE_SAMPLES_PER_SPAN + 1;
                assert_eq!(c.points_world_mm.len(), n, "spline samples");
                let (a, b) = (r.points[0], r.points[r.points.len() - 1]);
                assert!(c.points_world_mm[0].distance(a) < 1e-9);
                assert!(c.points_world_mm[n - 1].distance(b) < 1e-9);
                for p in &c.points_world_mm {
                    let off = (*p - a).cross((b - a).normalize()).length();
                    assert!(off < 1e-9, "spline point {p} is {off} mm off the ruling");
                }
            }
            "B04" => {
                let want = [r.points[0], r.points[r.points.len() - 1]];
                assert_points_close("DXF LINE", &c.points_world_mm, &want, 1e-9);
            }
            _ => assert_points_close(
                &format!("DXF {}", r.id),
                &c.points_world_mm,
                &r.points,
                1e-9,
            ),
        }
    }
    assert_same_nodes("DXF", &from_dxf, &from_yaml, STATION_TOL_MM);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn dxf_spline_is_evaluated_not_its_control_points() {
    let dir = scratch("dxf_spline");
    let path = dir.join("spline.dxf");
    let mut drawing = new_drawing(Units::Millimeters);
    // A cubic Bézier (one span) with a non-collinear control polygon.
    let bezier = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(100.0, 200.0, 0.0),
        DVec3::new(300.0, 200.0, 50.0),
        DVec3::new(400.0, 0.0, 0.0),
    ];
    let knots = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    drawing.add_entity(on_layer(
        "A",
        EntityType::Spline(spline(3, &knots, &bezier, None)),
    ));
    // A rational quadratic quarter circle of radius 100 about (0, 0, 10).
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let arc = [
        DVec3::new(100.0, 0.0, 10.0),
        DVec3::new(100.0, 100.0, 10.0),
        DVec3::new(0.0, 100.0, 10.0),
    ];
    let knots2 = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let weights = [1.0, w, 1.0];
    drawing.add_entity(on_layer(
        "B",
        EntityType::Spline(spline(2, &knots2, &arc, Some(&weights))),
    ));
    // A two-span cubic B-spline with a non-uniform knot vector.
    let bspline = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(50.0, 80.0, 0.0),
        DVec3::new(150.0, -40.0, 20.0),
        DVec3::new(220.0, 60.0, -10.0),
        DVec3::new(300.0, 0.0, 0.0),
    ];
    let knots3 = [0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0];
    drawing.add_entity(on_layer(
        "A",
        EntityType::Spline(spline(3, &knots3, &bspline, None)),
    ));
    drawing.save_file(&path).expect("write DXF");

    let raw = read_raw(&path, ReadOptions::default()).expect("read DXF");
    assert_eq!(raw.curves.len(), 3);
    let per_span = lamella::formats::read::dxf::SPLINE_SAMPLES_PER_SPAN;

    // Bézier: points at u = j/per_span against the Bernstein form.
    let c = &raw.curves[0];
    assert_eq!(c.family, Family::A);
    assert_eq!(
        c.points.len(),
        per_span + 1,
        "sampled, not the 4 control points"
    );
    for (j, p) in c.points.iter().enumerate() {
        let u = j as f64 / per_span as f64;
        let v = 1.0 - u;
        let want = bezier[0] * v * v * v
            + bezier[1] * 3.0 * u * v * v
            + bezier[2] * 3.0 * u * u * v
            + bezier[3] * u * u * u;
        assert!(p.distance(want) < 1e-9, "Bézier at u = {u}: {p} vs {want}");
    }
    // The midpoint (P0 + 3 P1 + 3 P2 + P3)/8 is on the curve, far from
    // every control point.
    let mid = c.points[per_span / 2];
    assert!(
        mid.distance(DVec3::new(200.0, 150.0, 18.75)) < 1e-9,
        "{mid}"
    );
    for q in &bezier[1..3] {
        assert!(
            c.points.iter().all(|p| p.distance(*q) > 1.0),
            "inner control point {q} is not on the curve"
        );
    }

    // Rational quarter circle: every sample at radius 100, ends exact.
    let c = &raw.curves[1];
    assert_eq!(c.family, Family::B);
    assert_eq!(c.points.len(), per_span + 1);
    let center = DVec3::new(0.0, 0.0, 10.0);
    for p in &c.points {
        assert!(
            ((*p - center).length() - 100.0).abs() < 1e-9,
            "weights ignored? {p}"
        );
    }
    assert!(c.points[0].distance(arc[0]) < 1e-9);
    assert!(c.points[per_span].distance(arc[2]) < 1e-9);
    assert!(c.points.iter().all(|p| p.distance(arc[1]) > 1.0));

    // Two-span B-spline against Cox–de Boor, written out independently.
    let c = &raw.curves[2];
    assert_eq!(c.points.len(), 2 * per_span + 1, "two knot spans");
    let mut params = Vec::new();
    for (a, b) in [(0.0, 0.4), (0.4, 1.0)] {
        for j in 0..per_span {
            params.push(a + (b - a) * j as f64 / per_span as f64);
        }
    }
    params.push(1.0);
    for (p, &u) in c.points.iter().zip(&params) {
        let want = cox_de_boor(3, &knots3, &bspline, u);
        assert!(
            p.distance(want) < 1e-9,
            "B-spline at u = {u}: {p} vs {want}"
        );
    }
    assert!(c.points[per_span].distance(cox_de_boor(3, &knots3, &bspline, 0.4)) < 1e-9);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Σ N_{i,p}(u) P_i by the Cox–de Boor recursion (u = last knot: the end point).
fn cox_de_boor(p: usize, knots: &[f64], ctrl: &[DVec3], u: f64) -> DVec3 {
    fn basis(i: usize, p: usize, knots: &[f64], u: f64) -> f64 {
        if p == 0 {
            let last = knots[knots.len() - 1];
            let inside = knots[i] <= u && u < knots[i + 1];
            let at_end = u == last && knots[i] < knots[i + 1] && knots[i + 1] == last;
            return if inside || at_end { 1.0 } else { 0.0 };
        }
        let mut sum = 0.0;
        let d1 = knots[i + p] - knots[i];
        if d1 > 0.0 {
            sum += (u - knots[i]) / d1 * basis(i, p - 1, knots, u);
        }
        let d2 = knots[i + p + 1] - knots[i + 1];
        if d2 > 0.0 {
            sum += (knots[i + p + 1] - u) / d2 * basis(i + 1, p - 1, knots, u);
        }
        sum
    }
    ctrl.iter()
        .enumerate()
        .map(|(i, &c)| c * basis(i, p, knots, u))
        .fold(DVec3::ZERO, |a, b| a + b)
}

#[test]
fn obj_unit_override_scales_to_mm() {
    let dir = scratch("obj_units");
    let raw = reference();
    let in_mm = dir.join("mm.obj");
    let in_m = dir.join("m.obj");
    write_obj(&raw, &in_mm, 1.0);
    write_obj(&raw, &in_m, 1000.0);
    let mm = read_and_analyze(&in_mm, ReadOptions::default());
    let m = read_and_analyze(
        &in_m,
        ReadOptions {
            unit: Some(Unit::M),
            ..Default::default()
        },
    );
    assert_eq!(m.net.file_unit, Unit::M);
    for (c, r) in m.net.curves.iter().zip(&raw.curves) {
        assert_points_close(
            &format!("OBJ in m, {}", c.id),
            &c.points_world_mm,
            &r.points,
            1e-9,
        );
    }
    assert_same_nodes("OBJ in m", &m, &mm, STATION_TOL_MM);
    // The default tolerance is in mm whatever the file unit.
    assert_eq!(m.net.tolerance_mm, mm.net.tolerance_mm);

    // Without the override the same file is read as mm: 1000 times smaller.
    let small = read_network(&in_m, ReadOptions::default()).expect("read OBJ as mm");
    assert_eq!(small.file_unit, Unit::Mm);
    let (a, b) = (&small.curves[0].points_world_mm, &raw.curves[0].points);
    assert!((a[a.len() - 1] * 1000.0).distance(b[b.len() - 1]) < 1e-6);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn dxf_insunits_meters_scales_to_mm() {
    let dir = scratch("dxf_units");
    let raw = reference();
    let in_mm = dir.join("mm.dxf");
    let in_m = dir.join("m.dxf");
    let unitless = dir.join("unitless.dxf");
    write_dxf(&raw, &in_mm, Units::Millimeters, 1.0);
    write_dxf(&raw, &in_m, Units::Meters, 1000.0);
    write_dxf(&raw, &unitless, Units::Unitless, 1.0);
    let mm = read_and_analyze(&in_mm, ReadOptions::default());
    let m = read_and_analyze(&in_m, ReadOptions::default());
    assert_eq!(m.net.file_unit, Unit::M, "$INSUNITS = meters");
    for (g, w) in m.net.curves.iter().zip(&mm.net.curves) {
        // Coordinates written with 12 decimals in m: 1e-9 mm resolution.
        assert_points_close(
            &format!("DXF in m, {}", g.id),
            &g.points_world_mm,
            &w.points_world_mm,
            1e-6,
        );
    }
    assert_same_nodes("DXF in m", &m, &mm, STATION_TOL_MM);

    // Unitless drawings are read as mm.
    let u = read_and_analyze(&unitless, ReadOptions::default());
    assert_eq!(u.net.file_unit, Unit::Mm);
    assert_same_nodes("unitless DXF", &u, &mm, STATION_TOL_MM);

    // --units overrides $INSUNITS: the meters file read as mm stays small,
    // and the mm file read as cm is ten times larger.
    let forced = read_network(
        &in_m,
        ReadOptions {
            unit: Some(Unit::Mm),
            ..Default::default()
        },
    )
    .expect("read DXF with override");
    assert_eq!(forced.file_unit, Unit::Mm);
    for (g, w) in forced.curves.iter().zip(&mm.net.curves) {
        let scaled: Vec<DVec3> = g.points_world_mm.iter().map(|&p| p * 1000.0).collect();
        assert_points_close(
            &format!("DXF in m read as mm, {}", g.id),
            &scaled,
            &w.points_world_mm,
            1e-6,
        );
    }
    let cm = read_network(
        &in_mm,
        ReadOptions {
            unit: Some(Unit::Cm),
            ..Default::default()
        },
    )
    .expect("read DXF as cm");
    assert_eq!(cm.file_unit, Unit::Cm);
    for (g, w) in cm.curves.iter().zip(&mm.net.curves) {
        let scaled: Vec<DVec3> = w.points_world_mm.iter().map(|&p| p * 10.0).collect();
        assert_points_close(
            &format!("DXF in mm read as cm, {}", g.id),
            &g.points_world_mm,
            &scaled,
            1e-6,
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn yaml_and_json_units_scale_to_mm() {
    let dir = scratch("file_units");
    let mut raw = reference();
    raw.unit = Unit::M;
    for c in &mut raw.curves {
        for p in &mut c.points {
            *p /= 1000.0;
        }
    }
    let yaml = dir.join("m.yaml");
    let json = dir.join("m.json");
    std::fs::write(&yaml, network_file::to_yaml(&raw, 12, "")).expect("write YAML");
    std::fs::write(&json, network_file::to_json(&raw, 12)).expect("write JSON");
    let want = reference();
    for path in [&yaml, &json] {
        // Network files always say their unit: `--units` does not apply.
        for unit in [None, Some(Unit::Mm)] {
            let net = read_network(
                path,
                ReadOptions {
                    unit,
                    ..Default::default()
                },
            )
            .expect("read");
            assert_eq!(net.file_unit, Unit::M);
            for (c, r) in net.curves.iter().zip(&want.curves) {
                assert_points_close(
                    &format!("{} {}", path.display(), c.id),
                    &c.points_world_mm,
                    &r.points,
                    1e-6,
                );
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
