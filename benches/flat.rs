//! Benchmark of the flat state on generated Enneper networks of n × n
//! curves with the prototype's cells (n = 50, 100, 200; n = 100 is a
//! 10,000-node grid) and the steel profile: the solve alone (the
//! analysis before it is timed apart), each size in a fresh child process.
//!
//!     cargo bench --bench flat            # 50, 100, 200
//!     cargo bench --bench flat -- 100     # one size

mod support;
use lamella_synth as synth;

use lamella::formats::read::profile_file;
use lamella::formats::read::{self as io, ReadOptions};
use lamella::{analyze, AnalysisOptions};
use std::path::Path;
use std::time::Instant;

fn main() {
    if let Some(path) = support::child_network() {
        measure(&path);
        return;
    }
    println!(
        "{:>5} {:>8} {:>10} {:>8} {:>11} {:>10} {:>12} {:>10}",
        "n", "nodes", "analyse s", "flat s", "iterations", "max rot °", "proj. grad", "peak MiB"
    );
    let sizes: Vec<usize> = if std::env::args().skip(1).any(|a| a.parse::<usize>().is_ok()) {
        support::sizes()
    } else {
        vec![50, 100, 200]
    };
    for n in sizes {
        let path = support::generated(&format!("enneper-parts-{n}.json"), || {
            io::network_file::to_json(&synth::enneper_prototype_grid(n), 3)
        });
        support::run_child(&path);
    }
}

fn measure(path: &Path) {
    let profile =
        profile_file::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("profiles/steel-1.5.yaml"))
            .expect("profile");
    let t0 = Instant::now();
    let net = io::read_network(path, ReadOptions::default()).expect("read");
    let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analyze");
    let t1 = Instant::now();
    let pr = lamella::flat::problem(&an, &profile).expect("problem");
    let st = lamella::flat::solve(&pr);
    let t2 = Instant::now();
    let worst = st
        .max_rotation()
        .map_or(0.0, |i| st.nodes[i].rotation_deg.abs());
    println!(
        "{:>5} {:>8} {:>10.3} {:>8.3} {:>11} {:>10.2} {:>12.1e} {:>10.0}",
        net.curves.len() / 2,
        st.nodes.len(),
        (t1 - t0).as_secs_f64(),
        (t2 - t1).as_secs_f64(),
        st.iterations,
        worst,
        st.gradient_norm,
        support::peak_mib()
    );
    assert!(st.converged, "not converged");
}
