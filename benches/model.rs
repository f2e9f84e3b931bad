//! Benchmark of the 3D model on generated Enneper networks of n × n curves
//! with the prototype's cells and the steel profile (n = 100, 200, 400;
//! the largest a 100 m grid with 160,000 nodes): the analysis and the
//! check (timed apart), the plan's shape, then `model.glb` and `view.html`
//! written from the plan, their sizes and times. Past 20,000 nodes the
//! model is drawn at the lower level of detail (ribbons, no slots or
//! hardware; `formats::write::gltf`). Each size in a fresh child process.
//!
//!     cargo bench --bench model            # 100, 200, 400
//!     cargo bench --bench model -- 400     # one size

mod support;
use lamella_synth as synth;

use lamella::formats::read as io;
use lamella::formats::write::{gltf, view};
use lamella::pipeline::{Inputs, Session};
use std::path::Path;
use std::time::Instant;

fn main() {
    if let Some(path) = support::child_network() {
        measure(&path);
        return;
    }
    println!(
        "{:>5} {:>8} {:>10} {:>8} {:>8} {:>10} {:>8} {:>10} {:>8} {:>9}",
        "n",
        "nodes",
        "analyse s",
        "shape s",
        "glb s",
        "glb MiB",
        "html s",
        "html MiB",
        "detail",
        "peak MiB"
    );
    for n in support::sizes() {
        let path = support::generated(&format!("enneper-parts-{n}.json"), || {
            io::network_file::to_json(&synth::enneper_prototype_grid(n), 3)
        });
        support::run_child(&path);
    }
}

fn measure(path: &Path) {
    let profile = Path::new(env!("CARGO_MANIFEST_DIR")).join("profiles/steel-1.5.yaml");
    let t0 = Instant::now();
    let mut session = Session::open(Inputs {
        network: path.to_path_buf(),
        profile: Some(profile),
        ..Default::default()
    })
    .expect("open");
    session.check(true).expect("check");
    let mut plan = session.plan(false).expect("plan");
    let t1 = Instant::now();
    session.add_shape(&mut plan).expect("shape");
    let t2 = Instant::now();
    let glb = gltf::to_glb(&plan).expect("glb");
    let t3 = Instant::now();
    let html = view::to_html("bench", &glb);
    let t4 = Instant::now();
    let mib = |b: usize| b as f64 / (1024.0 * 1024.0);
    println!(
        "{:>5} {:>8} {:>10.2} {:>8.2} {:>8.2} {:>10.1} {:>8.2} {:>10.1} {:>8} {:>9.0}",
        plan.strips.len() / 2,
        plan.nodes.len(),
        (t1 - t0).as_secs_f64(),
        (t2 - t1).as_secs_f64(),
        (t3 - t2).as_secs_f64(),
        mib(glb.len()),
        (t4 - t3).as_secs_f64(),
        mib(html.len()),
        if gltf::full_detail(&plan) {
            "solids"
        } else {
            "ribbons"
        },
        support::peak_mib()
    );
}
