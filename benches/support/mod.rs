//! What the benchmark binaries share: sizes from the command line, one
//! child process per size (so each size's peak memory is its own), and the
//! peak resident memory of the process.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Set in a child: the network file it measures.
pub const CHILD_ENV: &str = "LAMELLA_BENCH_CHILD";

/// The network this process is to measure, when it is a child.
///
/// The child sets the memory policy the CLI sets
/// ([`lamella::tune_allocator`]).
pub fn child_network() -> Option<PathBuf> {
    let path = std::env::var(CHILD_ENV).ok().map(PathBuf::from);
    if path.is_some() {
        lamella::tune_allocator();
    }
    path
}

/// The sizes named on the command line, else 100, 200 and 400.
pub fn sizes() -> Vec<usize> {
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    if sizes.is_empty() {
        vec![100, 200, 400]
    } else {
        sizes
    }
}

/// Where generated networks are kept between runs.
pub fn network_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench-networks");
    std::fs::create_dir_all(&dir).expect("bench dir");
    dir
}

/// Measure `network` in a fresh child process; print its line, stop on failure.
pub fn run_child(network: &Path) {
    let out = Command::new(std::env::current_exe().expect("exe"))
        .env(CHILD_ENV, network)
        .output()
        .expect("child");
    print!("{}", String::from_utf8_lossy(&out.stdout));
    if !out.status.success() {
        eprint!("{}", String::from_utf8_lossy(&out.stderr));
        std::process::exit(1);
    }
}

/// Peak resident memory of this process (VmHWM), MiB.
pub fn peak_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines().find(|l| l.starts_with("VmHWM:")).and_then(|l| {
                l.split_whitespace()
                    .nth(1)
                    .and_then(|k| k.parse::<f64>().ok())
            })
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// The load average over 1, 5 and 15 minutes (`/proc/loadavg`), as text.
#[allow(dead_code)]
pub fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|| "?".into())
}

/// User and system CPU time of this process so far, s (`/proc/self/stat`,
/// clock ticks of 1/100 s): unlike wall time, hardly changed by other work
/// on the machine.
#[allow(dead_code)]
pub fn cpu_s() -> (f64, f64) {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // Fields after the command name in parentheses (which may hold spaces).
    let rest = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let f: Vec<f64> = rest
        .split_whitespace()
        .map(|x| x.parse().unwrap_or(f64::NAN))
        .collect();
    // utime and stime are fields 14 and 15 of the line, 11 and 12 from the state.
    let tick = |i: usize| f.get(i).copied().unwrap_or(f64::NAN) / 100.0;
    (tick(11), tick(12))
}

/// The generated network file `name` (kept between runs), written by `make`
/// (the network file's text) the first time it is asked for.
pub fn generated(name: &str, make: impl FnOnce() -> String) -> PathBuf {
    let path = network_dir().join(name);
    if !path.exists() {
        std::fs::write(&path, make()).expect("write network");
    }
    path
}

/// Flush the file system (`sync`) and, where allowed (root), drop the
/// kernel's clean caches (`/proc/sys/vm/drop_caches`): what earlier runs
/// wrote or deleted no longer weighs on the next measurement.
#[allow(dead_code)]
pub fn sync_and_drop_caches() {
    let _ = Command::new("sync").status();
    let _ = std::fs::write("/proc/sys/vm/drop_caches", "3");
}
