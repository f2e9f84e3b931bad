//! Benchmark of `lamella trace`: curves traced per second, and the time to
//! trace each shipped spec (network design, edges included).
//!
//!     cargo bench --bench trace

use glam::DVec2;
use lamella::design::trace::{trace_through, Everywhere, Field, TraceOptions};
use lamella::design::{design, placed_surface};
use lamella::formats::read::trace_spec;
use std::path::Path;
use std::time::Instant;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    println!(
        "{:<18} {:>7} {:>8} {:>10} {:>12}",
        "spec", "curves", "points", "time s", "curves/s"
    );
    for name in [
        "enneper-4m",
        "catenoid",
        "scherk",
        "schwarz-d-patch",
        "hypar-small",
        "schwarz-d-pavilion-1to5",
        "schwarz-d-pavilion",
    ] {
        let path = root.join("samples").join(format!("{name}.trace.yaml"));
        let spec = trace_spec::load(&path).expect("spec");
        let reps = 5;
        let t0 = Instant::now();
        let mut curves = 0;
        let mut points = 0;
        for _ in 0..reps {
            let (net, _) =
                design(&spec, &path, &lamella::formats::read::mesh::read_mesh).expect("design");
            curves = net.curves.len();
            points = net.curves.iter().map(|c| c.points.len()).sum::<usize>();
        }
        let t = t0.elapsed().as_secs_f64() / reps as f64;
        println!(
            "{name:<18} {curves:>7} {points:>8} {t:>10.4} {:>12.0}",
            curves as f64 / t
        );
    }
    // Raw integrator throughput: 4 m asymptotic lines on Enneper and Schwarz D.
    for name in ["enneper-4m", "schwarz-d-patch"] {
        let path = root.join("samples").join(format!("{name}.trace.yaml"));
        let spec = trace_spec::load(&path).expect("spec");
        let surface = placed_surface(&spec);
        let opts = TraceOptions {
            max_length_mm: 2000.0,
            ..TraceOptions::default()
        };
        let n = 200;
        let t0 = Instant::now();
        let mut steps = 0;
        for i in 0..n {
            let seed = DVec2::new(0.001 * i as f64, -0.0005 * i as f64);
            let t = trace_through(&surface, Field::AsymptoticA, seed, &Everywhere, opts)
                .expect("trace");
            steps += t.uv.len();
        }
        let t = t0.elapsed().as_secs_f64();
        println!(
            "{name}: {n} asymptotic lines (≤ 4 m each, {steps} steps) in {t:.3} s: {:.0} curves/s",
            n as f64 / t
        );
    }
}
