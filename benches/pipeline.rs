//! Benchmark of the read → nodes → lengths pipeline on generated Enneper
//! networks of n × n curves (n = 100, 200, 400; the largest has 160,000 nodes
//! and about a million points). Each size runs in a fresh child process so
//! its peak memory (VmHWM) is its own.
//!
//!     cargo bench --bench pipeline            # all sizes
//!     cargo bench --bench pipeline -- 400     # one size

mod support;
use lamella_synth as synth;

use lamella::formats::read::{self as io, ReadOptions};
use lamella::plan;
use lamella::{analyze, AnalysisOptions};
use rayon::prelude::*;
use std::path::Path;
use std::time::Instant;

fn main() {
    if let Some(path) = support::child_network() {
        measure(&path);
        return;
    }
    let sizes = support::sizes();
    println!(
        "{:>5} {:>8} {:>9} {:>8} {:>9} {:>9} {:>9} {:>9} {:>10}",
        "n", "nodes", "points", "MB", "read s", "nodes s", "plan s", "total s", "peak MiB"
    );
    for n in sizes {
        // 400 lines per family over a 40 m Enneper: samples ~26 mm apart,
        // 1250 per curve at n = 400 (scaled so every size samples alike).
        let path = support::generated(&format!("enneper-{n}.json"), || {
            let scale_mm = 44_000.0 * n as f64 / 400.0;
            io::network_file::to_json(&synth::enneper_grid(n, scale_mm, 26.0), 3)
        });
        support::run_child(&path);
    }
}

fn measure(path: &Path) {
    let bytes = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
    let t0 = Instant::now();
    let net = io::read_network(path, ReadOptions::default()).expect("read");
    let t1 = Instant::now();
    let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analyze");
    let t2 = Instant::now();
    if std::env::var("LAMELLA_BENCH_STAGES").is_ok() {
        let opts = AnalysisOptions::for_network(&net);
        let a = Instant::now();
        let curves = net
            .curves
            .par_iter()
            .map(|c| {
                lamella::geom::curve::SmoothCurve::with_precision(
                    &c.points_world_mm,
                    opts.precision_mm,
                )
            })
            .collect::<Vec<_>>();
        let b = Instant::now();
        let topo = lamella::analysis::topology::find_nodes(&net, &curves, opts.nodes);
        let c = Instant::now();
        let idx: Vec<usize> = (0..net.curves.len()).collect();
        let strips = idx
            .par_iter()
            .map(|&i| {
                lamella::analysis::strip::StripGeometry::new(
                    i,
                    &net.curves[i],
                    &curves[i],
                    &topo.per_curve[i],
                    &topo.nodes,
                    opts.frames,
                )
            })
            .collect::<Vec<_>>();
        let d = Instant::now();
        let model = lamella::plan::model::Model::new(&net, &an, None);
        let e = Instant::now();
        let p = plan::build(&net, &an, &model);
        let f = Instant::now();
        let json = lamella::formats::write::plan_json::to_json(&p);
        let g = Instant::now();
        eprintln!(
            "stages: smooth {:.3} s, nodes {:.3} s, strips {:.3} s ({} strips), model {:.3} s, plan {:.3} s, json {:.3} s",
            (b - a).as_secs_f64(),
            (c - b).as_secs_f64(),
            (d - c).as_secs_f64(),
            strips.len(),
            (e - d).as_secs_f64(),
            (f - e).as_secs_f64(),
            (g - f).as_secs_f64(),
        );
        std::hint::black_box(json.len());
    }
    let model = lamella::plan::model::Model::new(&net, &an, None);
    let p = plan::build(&net, &an, &model);
    let json = lamella::formats::write::plan_json::to_json(&p);
    let t3 = Instant::now();
    let n = net.curves.len() / 2;
    assert_eq!(an.topology.nodes.len(), n * n, "every node found once");
    std::hint::black_box(json.len());
    println!(
        "{:>5} {:>8} {:>9} {:>8.1} {:>9.3} {:>9.3} {:>9.3} {:>9.3} {:>10.0}",
        n,
        an.topology.nodes.len(),
        net.point_count(),
        bytes as f64 / 1e6,
        (t1 - t0).as_secs_f64(),
        (t2 - t1).as_secs_f64(),
        (t3 - t2).as_secs_f64(),
        (t3 - t0).as_secs_f64(),
        support::peak_mib()
    );
}
