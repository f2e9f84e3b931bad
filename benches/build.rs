//! Benchmark of `lamella build` on generated Enneper networks of n × n
//! curves with the prototype's cell size (n = 100, 200, 400; the largest is
//! a 100 m grid with 160,000 nodes) and the steel prototype's profile: every
//! stage from reading the network to the files moved into place (plan.json,
//! takeoff, a DXF and an SVG per sheet, assembly.pdf; its pages, size and
//! time in the last columns). Each size runs in a fresh child
//! process so its peak memory (VmHWM) is its own. Under each size's line:
//! the MiB written per kind of file, the wall time per stage, and the load
//! average before and after (other work on the machine slows the build).
//!
//!     cargo bench --bench build            # all sizes
//!     cargo bench --bench build -- 400     # one size

mod support;
use lamella_synth as synth;

use lamella::formats::read as io;
use lamella::pipeline::build::{build, BuildOptions};
use std::path::Path;
use std::time::Instant;

fn main() {
    if let Some(path) = support::child_network() {
        measure(&path);
        return;
    }
    println!(
        "{:>5} {:>8} {:>9} {:>7} {:>9} {:>10} {:>9} {:>10} {:>7} {:>8} {:>6}",
        "n",
        "nodes",
        "pieces",
        "sheets",
        "files",
        "files MiB",
        "build s",
        "peak MiB",
        "pages",
        "pdf MiB",
        "pdf s"
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
    // Output in the system's temporary folder, not beside the network in
    // target/: on this machine's ext4 (no journal) the inode tables near
    // target/'s hundreds of thousands of build files are dense with used
    // and recently deleted inodes, and creating 5,316 files there cost
    // 1.1–1.5 s more system time than in /tmp (`find_get_block_common`,
    // `recently_deleted`): that is the file system's state, not the build.
    let stem = path
        .file_stem()
        .map_or("network".into(), |s| s.to_string_lossy());
    let out = std::env::temp_dir().join(format!("lamella-bench-{stem}.build"));
    let _ = std::fs::remove_dir_all(&out);
    // Earlier runs' files deleted, flushed and out of the kernel's caches
    // before the clock starts: ext4 without a journal (this machine's)
    // avoids reusing inodes deleted recently while their blocks are cached,
    // scanning past each of them for every file it creates, so a build
    // started within minutes of deleting 5,316 files pays about 1.3 s of
    // system time for that deletion (measured with 5,316 small files: 0.2 s
    // to create them on clean caches, 1.2–1.6 s after deleting as many, even
    // 20 s later). Dropping the caches needs root; elsewhere only `sync`.
    support::sync_and_drop_caches();
    let load0 = support::load_average();
    // The build's CPU, without the deleting and cache dropping above.
    let (user0, sys0) = support::cpu_s();
    let t0 = Instant::now();
    let r = build(
        lamella::pipeline::Inputs {
            network: path.to_path_buf(),
            profile: Some(profile.clone()),
            ..Default::default()
        },
        &out,
        &BuildOptions::default(),
        &indicatif::ProgressBar::hidden(),
    )
    .expect("build");
    let secs = t0.elapsed().as_secs_f64();
    let size = |f: &String| std::fs::metadata(out.join(f)).map_or(0, |m| m.len());
    let bytes: u64 = r.files.iter().map(size).sum();
    let mib = |b: u64| b as f64 / (1024.0 * 1024.0);
    let kinds = [
        ("plan.json", "plan.json"),
        ("dxf", ".dxf"),
        ("svg", ".svg"),
        ("pdf", ".pdf"),
        ("takeoff", "takeoff."),
        ("model.glb", "model.glb"),
        ("view.html", "view.html"),
    ];
    let by_kind: Vec<String> = kinds
        .iter()
        .map(|(name, ends)| {
            let b: u64 = r
                .files
                .iter()
                .filter(|f| f.ends_with(ends) || f.starts_with(ends))
                .map(size)
                .sum();
            format!("{name} {:.1}", mib(b))
        })
        .collect();
    let pdf_mib = mib(std::fs::metadata(out.join("assembly.pdf")).map_or(0, |m| m.len()));
    let assembly_s = r
        .stages
        .iter()
        .find(|t| t.stage == "write: assembly.pdf")
        .map_or(0.0, |t| t.wall_s);
    println!(
        "{:>5} {:>8} {:>9} {:>7} {:>9} {:>10.0} {:>9.2} {:>10.0} {:>7} {:>8.1} {:>6.2}",
        r.strips / 2,
        r.nodes,
        r.takeoff.totals.pieces,
        r.sheets_used,
        r.files.len(),
        mib(bytes),
        secs,
        support::peak_mib(),
        r.assembly_pages,
        pdf_mib,
        assembly_s
    );
    println!("      MiB: {}", by_kind.join(", "));
    let stages: Vec<String> = r
        .stages
        .iter()
        .map(|t| match t.cpu_s {
            Some(cpu) => format!("{} {:.2} (cpu {cpu:.2})", t.stage, t.wall_s),
            None => format!("{} {:.2}", t.stage, t.wall_s),
        })
        .collect();
    println!("      s: {}", stages.join(", "));
    let (user, sys) = support::cpu_s();
    let (user, sys) = (user - user0, sys - sys0);
    println!(
        "      cpu: user {user:.2} s, sys {sys:.2} s; load before {load0}, after {}",
        support::load_average()
    );
    let _ = std::fs::remove_dir_all(&out);
}
