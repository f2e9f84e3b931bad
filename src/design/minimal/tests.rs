//! Form finding on inputs whose answer is known by hand.

use super::*;
use std::f64::consts::TAU;

fn ring(radius: f64, z: f64, n: usize, start: usize, reverse: bool) -> Vec<DVec3> {
    (0..n)
        .map(|i| {
            let k = if reverse { n - i } else { i } + start;
            let t = TAU * k as f64 / n as f64;
            DVec3::new(radius * t.cos(), radius * t.sin(), z)
        })
        .collect()
}

fn spec() -> &'static Path {
    Path::new("film.yaml")
}

fn chart_is_valid(f: &FormFound) -> bool {
    f.mesh.triangles.iter().all(|t| {
        let [a, b, c] = t.map(|v| f.chart_uv[v as usize]);
        (b - a).perp_dot(c - a) > 0.0
    })
}

/// An L-shaped hexagon in a tilted plane: the film is the planar region.
#[test]
fn a_planar_polygon_spans_its_own_plane_with_the_polygon_area() {
    // Plane coordinates by hand; area = 2000·800 + 900·700 = 2,230,000 mm².
    let plane = [
        (0.0, 0.0),
        (2000.0, 0.0),
        (2000.0, 800.0),
        (900.0, 800.0),
        (900.0, 1500.0),
        (0.0, 1500.0),
    ];
    let shoelace: f64 = (0..6)
        .map(|i| {
            let (a, b) = (plane[i], plane[(i + 1) % 6]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum::<f64>()
        / 2.0;
    assert_eq!(shoelace, 2_230_000.0);
    let n = DVec3::new(0.3, -0.4, 1.0).normalize();
    let u = DVec3::new(1.0, 0.0, -0.3).normalize();
    let u = (u - n * n.dot(u)).normalize();
    let v = n.cross(u);
    let origin = DVec3::new(150.0, -75.0, 1200.0);
    let pts: Vec<DVec3> = plane.iter().map(|&(x, y)| origin + u * x + v * y).collect();
    let f = form_find(&[pts], &FormFindOptions::with_target_edge_mm(60.0), spec())
        .expect("planar film");
    assert_eq!(f.report.initial, InitialMesh::PlanarDomain);
    assert!(f.report.converged);
    let off = f
        .mesh
        .positions_mm
        .iter()
        .map(|&p| (p - origin).dot(n).abs())
        .fold(0.0, f64::max);
    assert!(off < 1e-9, "a vertex {off} mm off the plane");
    let rel = (f.report.area_mm2 - shoelace).abs() / shoelace;
    assert!(rel < 1e-12, "area {} vs {shoelace}", f.report.area_mm2);
    // The loop runs counter-clockwise about n: every normal is +n.
    for t in &f.mesh.triangles {
        let [a, b, c] = t.map(|i| f.mesh.positions_mm[i as usize]);
        assert!((b - a).cross(c - a).normalize().dot(n) > 1.0 - 1e-9);
    }
    assert!(chart_is_valid(&f));
    // A plane has H = 0: the residual is rounding.
    assert!(f.report.max_mean_curvature_per_mm < 1e-12);
    assert!(f.report.min_angle_deg > 15.0, "{}", f.report.min_angle_deg);
    // Target reached: the mean edge is within √2 of 60 mm.
    assert!(
        f.report.mean_edge_mm <= 60.0 * 2f64.sqrt() && f.report.mean_edge_mm > 60.0 / 2f64.sqrt()
    );
}

/// The loft aligns the second ring whatever its start and direction:
/// the same film (area) as with aligned rings, normals towards the axis.
#[test]
fn a_loft_aligns_a_shifted_reversed_ring() {
    let opts = FormFindOptions::with_target_edge_mm(100.0);
    let a = form_find(
        &[
            ring(1000.0, -400.0, 64, 0, false),
            ring(1000.0, 400.0, 64, 0, false),
        ],
        &opts,
        spec(),
    )
    .expect("aligned");
    let b = form_find(
        &[
            ring(1000.0, -400.0, 64, 0, false),
            ring(1000.0, 400.0, 64, 17, true),
        ],
        &opts,
        spec(),
    )
    .expect("shifted, reversed");
    assert_eq!(a.report.initial, InitialMesh::Loft);
    assert!((a.report.area_mm2 - b.report.area_mm2).abs() < 1e-9 * a.report.area_mm2);
    for f in [&a, &b] {
        assert!(chart_is_valid(f));
        for t in &f.mesh.triangles {
            let [p, q, r] = t.map(|i| f.mesh.positions_mm[i as usize]);
            let c = (p + q + r) / 3.0;
            let outward = DVec3::new(c.x, c.y, 0.0).normalize();
            assert!(
                (q - p).cross(r - p).dot(outward) < 0.0,
                "a normal points away from the axis"
            );
        }
    }
}

#[test]
fn rings_too_far_apart_for_a_catenoid_are_a_one_line_error() {
    // 0.7 R apart on either side, beyond the critical 0.6627 R.
    let e = form_find(
        &[
            ring(1000.0, -700.0, 64, 0, false),
            ring(1000.0, 700.0, 64, 0, false),
        ],
        &FormFindOptions::with_target_edge_mm(100.0),
        spec(),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("film.yaml: field `boundaries`: form finding failed"),
        "{e}"
    );
    assert!(
        e.contains("no stable soap film") && !e.contains('\n'),
        "{e}"
    );
}

#[test]
fn bad_loops_are_one_line_errors_naming_the_loop() {
    let sq = |c: f64, h: f64| -> Vec<DVec3> {
        vec![
            DVec3::new(c - h, -h, 0.0),
            DVec3::new(c + h, -h, 0.0),
            DVec3::new(c + h, h, 0.0),
            DVec3::new(c - h, h, 0.0),
        ]
    };
    let opts = FormFindOptions::with_target_edge_mm(50.0);
    let e = form_find(
        &[sq(0.0, 1000.0), vec![DVec3::ZERO, DVec3::X]],
        &opts,
        spec(),
    )
    .unwrap_err()
    .to_string();
    assert_eq!(
        e,
        "film.yaml: field `boundaries[1]`: a closed boundary loop needs at least 3 distinct points, this one has 2"
    );
    // Two holes that cross each other.
    let e = form_find(
        &[sq(0.0, 1000.0), sq(-100.0, 300.0), sq(300.0, 300.0)],
        &opts,
        spec(),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("film.yaml: field `boundaries[1]`: loops 1 and 2 cross"),
        "{e}"
    );
    // A hole outside the outer loop.
    let e = form_find(
        &[sq(0.0, 1000.0), sq(0.0, 300.0), sq(5000.0, 300.0)],
        &opts,
        spec(),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("loops 0 and 2 are not nested"), "{e}");
    // A bow tie: self-intersecting in projection.
    let bow = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1000.0, 1000.0, 50.0),
        DVec3::new(1000.0, 0.0, 0.0),
        DVec3::new(0.0, 1000.0, 50.0),
    ];
    let e = form_find(&[bow], &opts, spec()).unwrap_err().to_string();
    assert!(
        e.starts_with("film.yaml: field `boundaries[0]`: loop 0 intersects itself"),
        "{e}"
    );
    assert!(e.lines().count() == 1);
    let e = form_find(
        &[sq(0.0, 1000.0)],
        &FormFindOptions::with_target_edge_mm(0.0),
        spec(),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("target_edge_mm"), "{e}");
}

#[test]
fn a_repeated_closing_point_is_dropped() {
    let mut a = ring(1000.0, 0.0, 40, 0, false);
    let opts = FormFindOptions::with_target_edge_mm(200.0);
    let open = form_find(std::slice::from_ref(&a), &opts, spec()).expect("open");
    a.push(a[0]);
    let closed = form_find(&[a], &opts, spec()).expect("closed");
    assert_eq!(open, closed);
}

#[test]
fn two_runs_give_identical_bits() {
    let six: Vec<DVec3> = (0..6)
        .map(|i| {
            let t = TAU * i as f64 / 6.0;
            DVec3::new(
                2000.0 * t.cos(),
                2000.0 * t.sin(),
                if i % 2 == 0 { 800.0 } else { 0.0 },
            )
        })
        .collect();
    let opts = FormFindOptions::with_target_edge_mm(80.0);
    let a = form_find(std::slice::from_ref(&six), &opts, spec()).expect("a");
    let b = form_find(&[six], &opts, spec()).expect("b");
    let bits = |f: &FormFound| -> Vec<u64> {
        f.mesh
            .positions_mm
            .iter()
            .flat_map(|p| p.to_array())
            .chain(f.chart_uv.iter().flat_map(|q| q.to_array()))
            .map(f64::to_bits)
            .collect()
    };
    assert_eq!(bits(&a), bits(&b));
    assert_eq!(a.mesh.triangles, b.mesh.triangles);
    assert_eq!(a.report, b.report);
}
