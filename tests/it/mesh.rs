//! Mesh stages end to end on files as a designer exports them: OBJ with
//! coordinates to 0.001 mm, no normals, quads and triangles mixed, 1-based
//! indices; the same surface as binary STL.

use crate::support::scratch;
use lamella::design::mesh::curvature::{vertex_jets_over, MIN_POINTS, SIGNIFICANT};
use lamella::design::mesh::{
    anticlastic_report, require_anticlastic, vertex_curvatures, vertex_jets, SingularKind, Topology,
};
use lamella::formats::read::mesh::read_mesh;
use std::fmt::Write;
use std::path::PathBuf;

/// `z(x, y)` over ±500 mm on a 21 × 21 grid with wavy (irregular) lines,
/// quads in one half and triangles in the other, as OBJ text.
fn obj(z: impl Fn(f64, f64) -> f64) -> String {
    let n = 20;
    let mut s = String::from("# exported\no surface\n");
    let at = |i: usize, j: usize| -> (f64, f64) {
        let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
        // Interior lines bent by up to a fifth of a cell, edges straight.
        let (bu, bv) = (
            0.2 / n as f64 * (7.0 * v).sin() * (std::f64::consts::PI * u).sin(),
            0.2 / n as f64 * (5.0 * u).cos() * (std::f64::consts::PI * v).sin(),
        );
        (1000.0 * (u + bu) - 500.0, 1000.0 * (v + bv) - 500.0)
    };
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = at(i, j);
            writeln!(s, "v {x:.3} {y:.3} {:.3}", z(x, y)).expect("write");
        }
    }
    s += "vn 0 0 1\ns 1\n";
    let id = |i: usize, j: usize| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if i < n / 2 {
                writeln!(s, "f {a}//1 {b}//1 {c}//1 {d}//1").expect("write");
            } else {
                writeln!(s, "f {a} {b} {d}\nf {b} {c} {d}").expect("write");
            }
        }
    }
    s
}

/// `text` written to `name` in a scratch directory of its own.
#[track_caller]
fn file(name: &str, text: &str) -> PathBuf {
    let p = scratch(name).join(name);
    std::fs::write(&p, text).expect("write");
    p
}

#[test]
fn monkey_saddle_obj_has_its_flat_point() {
    let path = file(
        "monkey.obj",
        &obj(|x, y| (x * x * x - 3.0 * x * y * y) / 1e6),
    );
    let mesh = read_mesh(&path).expect("read");
    let topo = Topology::build(&mesh, &path).expect("valid");
    assert_eq!(topo.euler_characteristic(), 1);
    assert_eq!(topo.boundary_loops().len(), 1);
    let jets = vertex_jets(topo.mesh(), &topo);
    let report = anticlastic_report(&topo, &jets);
    require_anticlastic(&report, &path).expect("anticlastic");
    assert_eq!(report.singularities.len(), 1, "{:?}", report.warnings());
    let s = &report.singularities[0];
    assert_eq!((s.index, s.kind), (-0.5, SingularKind::FlatPoint));
    assert!(s.position_mm.length() < 50.0, "{s:?}");
    // Away from the flat point the asymptotic directions exist and bisect
    // the principal ones where k1 = −k2 (the monkey saddle is harmonic:
    // nearly minimal where its slope is small).
    let c = vertex_curvatures(topo.mesh(), &topo);
    let far = (0..c.len())
        .filter(|&v| {
            let p = topo.mesh().positions_mm[v];
            p.truncate().length() > 100.0 && p.truncate().length() < 200.0
        })
        .collect::<Vec<_>>();
    assert!(!far.is_empty());
    for v in far {
        let (a, b) = c[v].asymptotic(0.0).expect("anticlastic");
        assert!(c[v].normal_curvature(a).abs() < 1e-12 && c[v].normal_curvature(b).abs() < 1e-12);
    }
}

#[test]
fn sphere_cap_obj_is_refused_in_one_line() {
    let path = file("cap.obj", &obj(|x, y| (4e6 - x * x - y * y).sqrt()));
    let mesh = read_mesh(&path).expect("read");
    let topo = Topology::build(&mesh, &path).expect("valid");
    let report = anticlastic_report(&topo, &vertex_jets(topo.mesh(), &topo));
    let e = require_anticlastic(&report, &path)
        .expect_err("synclastic")
        .to_string();
    assert!(
        e.starts_with(&format!("{}: vertex ", path.display())),
        "{e}"
    );
    assert!(e.contains(" mm: no anticlastic region"), "{e}");
    assert_eq!(e.lines().count(), 1);
}

/// The saddle z = xy/1000 as OBJ and as binary STL (written here): the
/// same curvatures to within the f32 rounding of STL.
#[test]
fn obj_and_stl_give_the_same_curvature() {
    let path = file("saddle.obj", &obj(|x, y| x * y / 1000.0));
    let mesh = read_mesh(&path).expect("read");
    let mut stl = vec![0u8; 80];
    let tris: Vec<[u32; 3]> = mesh.triangles.clone();
    stl.extend((tris.len() as u32).to_le_bytes());
    for t in &tris {
        stl.extend([0u8; 12]);
        for &k in t {
            for x in mesh.positions_mm[k as usize].to_array() {
                stl.extend((x as f32).to_le_bytes());
            }
        }
        stl.extend([0u8; 2]);
    }
    let stl_path = path.with_extension("stl");
    std::fs::write(&stl_path, &stl).expect("write");
    let from_stl = read_mesh(&stl_path).expect("read stl");
    let (ta, tb) = (
        Topology::build(&mesh, &path).expect("valid"),
        Topology::build(&from_stl, &stl_path).expect("valid"),
    );
    assert_eq!(ta.vertex_count(), tb.vertex_count());
    // The same fit on both (`vertex_jets` sizes its neighbourhoods by the
    // file's rounding, 0.001 mm here and the f32 spacing there).
    let ca: Vec<_> = vertex_jets_over(ta.mesh(), &ta, MIN_POINTS)
        .into_iter()
        .map(|j| j.curvature)
        .collect();
    let jb = vertex_jets_over(tb.mesh(), &tb, MIN_POINTS);
    // Match vertices by position (STL numbers them by first appearance).
    let mut by_pos = std::collections::HashMap::new();
    for (v, p) in tb.mesh().positions_mm.iter().enumerate() {
        by_pos.insert(p.to_array().map(f64::to_bits), v);
    }
    let mut worst_s = 0.0f64;
    for (v, p) in ta.mesh().positions_mm.iter().enumerate() {
        let key = (p.as_vec3().as_dvec3() + 0.0).to_array().map(f64::to_bits); // −0 is +0
        let w = by_pos[&key];
        // f32 moves points by up to 3e-5 mm here: the STL jets' standard
        // error (from the f32 spacing) bounds the difference.
        let (cb, s) = (jb[w].curvature, SIGNIFICANT * jb[w].sigma_per_mm);
        worst_s = worst_s.max(s / cb.k1.abs().min(cb.k2.abs()));
        assert!((ca[v].k1 - cb.k1).abs() < s, "{} {} {s}", ca[v].k1, cb.k1);
        assert!((ca[v].k2 - cb.k2).abs() < s);
    }
    // ... which is small: measured at most 4.7e-4 of |k|.
    assert!(worst_s < 1e-3, "{worst_s}");
}
