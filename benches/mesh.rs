//! Benchmark of the mesh stages on generated Enneper meshes (× 1000 mm over
//! [−1, 1]², n × n jittered cells, 0.001 mm OBJ): reading, topology,
//! curvature jets and the anticlastic report with its singular points, each
//! size in a fresh child process.
//!
//!     cargo bench --bench mesh            # n = 100, 200, 400
//!     cargo bench --bench mesh -- 200     # one size

mod support;

use lamella::design::mesh::{anticlastic_report, vertex_jets, Topology};
use lamella::design::surface::{Enneper, Surface};
use lamella::formats::read::mesh::read_mesh;
use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

fn main() {
    if let Some(path) = support::child_network() {
        measure(&path);
        return;
    }
    println!(
        "{:>5} {:>9} {:>8} {:>10} {:>9} {:>9} {:>10}",
        "n", "vertices", "read s", "topology s", "jets s", "report s", "peak MiB"
    );
    for n in support::sizes() {
        let path = support::generated(&format!("enneper-mesh-{n}.obj"), || enneper_obj(n));
        support::run_child(&path);
    }
}

/// Enneper × 1000 mm on n × n cells, interior parameters jittered by ±0.3
/// of a cell, alternate diagonals, coordinates to 0.001 mm.
fn enneper_obj(n: usize) -> String {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut jitter = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        0.6 * ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5)
    };
    let d = 2.0 / n as f64;
    let mut s = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let (mut u, mut v) = (-1.0 + i as f64 * d, -1.0 + j as f64 * d);
            let (ju, jv) = (jitter(), jitter());
            if i > 0 && i < n {
                u += ju * d;
            }
            if j > 0 && j < n {
                v += jv * d;
            }
            let p = Enneper.point(glam::DVec2::new(u, v)) * 1000.0;
            writeln!(s, "v {:.3} {:.3} {:.3}", p.x, p.y, p.z).expect("write");
        }
    }
    let id = |i: usize, j: usize| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, e) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                writeln!(s, "f {a} {b} {c}\nf {a} {c} {e}").expect("write");
            } else {
                writeln!(s, "f {a} {b} {e}\nf {b} {c} {e}").expect("write");
            }
        }
    }
    s
}

fn measure(path: &Path) {
    let t0 = Instant::now();
    let mesh = read_mesh(path).expect("read");
    let t1 = Instant::now();
    let topo = Topology::build(&mesh, path).expect("topology");
    let t2 = Instant::now();
    let jets = vertex_jets(topo.mesh(), &topo);
    let t3 = Instant::now();
    let report = anticlastic_report(&topo, &jets);
    let t4 = Instant::now();
    let n = ((topo.vertex_count() as f64).sqrt() - 1.0).round();
    println!(
        "{:>5} {:>9} {:>8.3} {:>10.3} {:>9.3} {:>9.3} {:>10.0}",
        n,
        topo.vertex_count(),
        (t1 - t0).as_secs_f64(),
        (t2 - t1).as_secs_f64(),
        (t3 - t2).as_secs_f64(),
        (t4 - t3).as_secs_f64(),
        support::peak_mib()
    );
    assert!(report.singularities.is_empty(), "{:?}", report.warnings());
}
