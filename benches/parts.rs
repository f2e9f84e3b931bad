//! Benchmark of the parts stage on generated Enneper networks of n × n
//! curves with the prototype's cell size (n = 100, 200, 400; the largest has
//! 160,000 nodes): read, analyse,
//! then fabricate every part for the steel prototype's profile (doubled
//! lamellas with swept slots, shear blocks, splices, star washers, edge-less
//! grid) including the engraving, then nest them onto its sheets (wall
//! time, and the process's CPU time, user + system, per stage). Each size runs in a fresh child process so
//! its peak memory (VmHWM) is its own.
//!
//!     cargo bench --bench parts            # all sizes
//!     cargo bench --bench parts -- 400     # one size

mod support;
use lamella_synth as synth;

use lamella::fabricate::fabricate;
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
    let sizes = support::sizes();
    println!(
        "{:>5} {:>8} {:>9} {:>9} {:>9} {:>10} {:>8} {:>8} {:>8} {:>7} {:>7} {:>6} {:>10}",
        "n",
        "nodes",
        "parts",
        "pieces",
        "analyse s",
        "fabricate s",
        "cpu s",
        "nest s",
        "cpu s",
        "sheets",
        "bound",
        "util",
        "peak MiB"
    );
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
    let cpu = || {
        let (user, sys) = support::cpu_s();
        user + sys
    };
    let (t1, c1) = (Instant::now(), cpu());
    let kit = fabricate(&net, &an, &profile, None, Default::default()).expect("fabricate");
    let (t2, c2) = (Instant::now(), cpu());
    let nested = lamella::nest::nest(&kit, &profile).expect("nest");
    let (t3, c3) = (Instant::now(), cpu());
    let pieces: u64 = kit.parts.iter().map(|p| u64::from(p.count)).sum();
    std::hint::black_box(&kit);
    println!(
        "{:>5} {:>8} {:>9} {:>9} {:>9.3} {:>10.3} {:>8.2} {:>8.3} {:>8.2} {:>7} {:>7} {:>6.3} {:>10.0}",
        net.curves.len() / 2,
        an.topology.nodes.len(),
        kit.parts.len(),
        pieces,
        (t1 - t0).as_secs_f64(),
        (t2 - t1).as_secs_f64(),
        c2 - c1,
        (t3 - t2).as_secs_f64(),
        c3 - c2,
        nested.summary.sheets_used,
        nested.summary.lower_bound_sheets,
        nested.summary.utilization,
        support::peak_mib()
    );
}
