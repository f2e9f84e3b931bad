//! What the test modules share: the repository root, scratch directories,
//! the CLI binary, shipped profiles and samples, closed-form networks
//! analysed through the library, and numerical oracles on the analytic
//! curves.

use glam::{DVec2, DVec3};
use lamella::analysis::{analyze, Analysis, AnalysisOptions};
use lamella::network::{Network, RawNetwork};
use lamella::profile::Profile;
pub mod meshes;
pub mod tools;
/// Networks made from closed forms (shared with the benchmarks).
pub use lamella_synth as synth;

use std::collections::BTreeSet;
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::Mutex;
use synth::{ParamLine, ParamSurface};

/// The repository root: samples/, profiles/ and tests/tools/ are read from
/// here, and the CLI runs here.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Scratch directories handed out in this run.
static SCRATCH: Mutex<BTreeSet<PathBuf>> = Mutex::new(BTreeSet::new());

/// A fresh, empty scratch directory `target/tmp/it/<module>-<name>`, the
/// module being the test file that asks (through any helper in it).
///
/// The tests run as threads of one process, so a directory must belong to
/// one test: asking twice for the same one in a run panics.
#[track_caller]
pub fn scratch(name: &str) -> PathBuf {
    let file = std::panic::Location::caller().file();
    let module = Path::new(file)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .expect("caller file");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("it")
        .join(format!("{module}-{name}"));
    let fresh = SCRATCH
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .insert(dir.clone());
    assert!(
        fresh,
        "scratch directory {} asked for twice (from {file})",
        dir.display()
    );
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create scratch dir");
    dir
}

/// The CLI binary, to run in the repository root.
pub fn lamella_command() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_lamella"));
    c.current_dir(root());
    c
}

/// Run the CLI with `args` in the repository root: (exit code, `None` when
/// killed by a signal; stdout; stderr).
pub fn lamella<S: AsRef<OsStr>>(args: &[S]) -> (Option<i32>, String, String) {
    lamella_in(&root(), args)
}

/// Run the CLI with `args` in `dir`: (exit code; stdout; stderr).
pub fn lamella_in<S: AsRef<OsStr>>(dir: &Path, args: &[S]) -> (Option<i32>, String, String) {
    let o = lamella_command()
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run lamella");
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// `lamella build samples/SAMPLE.yaml --profile profiles/PROFILE.yaml --out
/// OUT EXTRA…` in the repository root.
pub fn build(sample: &str, profile: &str, out: &Path, extra: &[&str]) -> Output {
    lamella_command()
        .args(["build", &format!("samples/{sample}.yaml")])
        .args(["--profile", &format!("profiles/{profile}.yaml")])
        .arg("--out")
        .arg(out)
        .args(extra)
        .output()
        .expect("run lamella")
}

/// Assert that a run of the CLI succeeded, showing its output if not.
#[track_caller]
pub fn ok(o: &Output) {
    assert!(
        o.status.success(),
        "exit {:?}\nstdout: {}\nstderr: {}",
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// A shipped profile, `profiles/NAME.yaml`.
#[track_caller]
pub fn profile(name: &str) -> Profile {
    lamella::formats::read::profile_file::load(&root().join(format!("profiles/{name}.yaml")))
        .expect("shipped profile")
}

pub fn validate(raw: RawNetwork) -> Network {
    Network::new(raw, Path::new("test.yaml")).expect("valid network")
}

/// The network as a designer exports it when `rounded`: coordinates rounded
/// to 0.001 mm (Rhino's three decimals), no normals; else unchanged.
pub fn export(mut raw: RawNetwork, rounded: bool) -> RawNetwork {
    if rounded {
        for c in &mut raw.curves {
            for p in &mut c.points {
                *p = (*p * 1000.0).round() / 1000.0;
            }
            c.normals = None;
        }
    }
    raw
}

pub fn run(raw: RawNetwork) -> (Network, Analysis) {
    let net = validate(raw);
    let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analysis");
    (net, an)
}

/// Curvature and torsion of the space curve t ↦ scale·X(uv(t)), by central
/// differences of the closed form (step h in t).
pub fn curvature_torsion(
    surface: &dyn ParamSurface,
    line: &ParamLine,
    scale: f64,
    t: f64,
) -> (f64, f64) {
    let h = 1e-3;
    let g = |t: f64| surface.point(line.uv(t)) * scale;
    let d1 = (g(t + h) - g(t - h)) / (2.0 * h);
    let d2 = (g(t + h) - 2.0 * g(t) + g(t - h)) / (h * h);
    let d3 =
        (g(t + 2.0 * h) - 2.0 * g(t + h) + 2.0 * g(t - h) - g(t - 2.0 * h)) / (2.0 * h * h * h);
    let c = d1.cross(d2);
    (
        c.length() / d1.length().powi(3),
        c.dot(d3) / c.length_squared(),
    )
}

/// Arc length of t ↦ scale·X(uv(t)) over [t0, t1] by composite Gauss–Legendre
/// on the analytic derivative.
pub fn arc_length(
    surface: &dyn ParamSurface,
    line: &ParamLine,
    scale: f64,
    t0: f64,
    t1: f64,
) -> f64 {
    let n = 2000;
    let g = [-0.7745966692414834, 0.0, 0.7745966692414834];
    let w = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
    let h = (t1 - t0) / n as f64;
    let mut sum = 0.0;
    for i in 0..n {
        let mid = t0 + h * (i as f64 + 0.5);
        for k in 0..3 {
            let t = mid + 0.5 * h * g[k];
            let (xu, xv) = surface.partials(line.uv(t));
            let d = (xu * line.dir.x + xv * line.dir.y) * scale;
            sum += w[k] * d.length() * 0.5 * h;
        }
    }
    sum
}

/// A rigid motion for invariance tests.
pub fn rigid(p: DVec3) -> DVec3 {
    let q = glam::DQuat::from_euler(glam::EulerRot::ZYX, 0.7, -0.4, 1.9);
    q * p + DVec3::new(12_345.6, -7_890.1, 4_321.0)
}

/// The point of the closed-form asymptotic line u ± v = const (Enneper,
/// catenoid) through `start` that shares the other diagonal coordinate with
/// `q`: along p = u + v when `along_p`, else along q = u − v.
pub fn diagonal_closed_form(start: DVec2, q: DVec2, along_p: bool) -> DVec2 {
    let (p0, q0) = (start.x + start.y, start.x - start.y);
    if along_p {
        let qq = q.x - q.y;
        DVec2::new((p0 + qq) / 2.0, (p0 - qq) / 2.0)
    } else {
        let pp = q.x + q.y;
        DVec2::new((pp + q0) / 2.0, (pp - q0) / 2.0)
    }
}

/// Every A×B node crosses at 90° ± 0.01°; returns how many there are.
pub fn assert_ab_orthogonal(net: &Network, an: &Analysis, what: &str) -> usize {
    let mut ab = 0;
    for n in &an.topology.nodes {
        if net.curves[n.a].family == lamella::Family::A
            && net.curves[n.b].family == lamella::Family::B
        {
            assert!(
                (n.angle_deg - 90.0).abs() < 0.01,
                "{what}: node {} at {}°",
                n.id,
                n.angle_deg
            );
            ab += 1;
        }
    }
    ab
}

/// The shipped samples every profile can make parts for (the 1:5 pavilion
/// only with the veneer profile: full-size splice plates do not fit).
pub const BUILDABLE_SAMPLES: [&str; 6] = [
    "enneper-4m",
    "catenoid",
    "scherk",
    "schwarz-d-patch",
    "hypar-small",
    "schwarz-d-pavilion",
];

/// A shipped sample, read and analysed.
pub fn analysed_sample(name: &str) -> (Network, Analysis) {
    let path = root().join(format!("samples/{name}.yaml"));
    let net =
        lamella::formats::read::read_network(&path, lamella::formats::read::ReadOptions::default())
            .expect("read sample");
    let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analyse sample");
    (net, an)
}

/// (u, v) of a point on the surface, by Gauss–Newton from a coarse search.
pub fn invert(surface: &dyn lamella::design::surface::Surface, p: DVec3) -> DVec2 {
    let mut best = (f64::INFINITY, DVec2::ZERO);
    for i in -40..=40 {
        for j in -40..=40 {
            let q = DVec2::new(i as f64 * 0.02, j as f64 * 0.02);
            if surface.in_domain(q) {
                let d = surface.point(q).distance(p);
                if d < best.0 {
                    best = (d, q);
                }
            }
        }
    }
    let mut q = best.1;
    for _ in 0..50 {
        let j = surface.eval(q);
        let r = j.p - p;
        let (a, b, c) = (j.pu.dot(j.pu), j.pu.dot(j.pv), j.pv.dot(j.pv));
        let (g1, g2) = (j.pu.dot(r), j.pv.dot(r));
        let det = a * c - b * b;
        q -= DVec2::new((c * g1 - b * g2) / det, (a * g2 - b * g1) / det);
    }
    q
}

/// Whether a line of Enneper's or the catenoid's asymptotic net, given by
/// its parameters, keeps u + v (rather than u − v) the more nearly
/// constant: which of the two diagonal families it belongs to.
pub fn keeps_u_plus_v(uvs: &[DVec2]) -> bool {
    let spread = |f: &dyn Fn(DVec2) -> f64| {
        let (lo, hi) = uvs
            .iter()
            .map(|q| f(*q))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            });
        hi - lo
    };
    spread(&|q| q.x + q.y) < spread(&|q| q.x - q.y)
}

/// The shipped samples' networks (not their trace specs), by name
/// (`samples/NAME.yaml`), sorted.
pub fn shipped_networks() -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(root().join("samples"))
        .expect("samples")
        .flatten()
        .filter_map(|e| {
            let n = e.file_name().to_string_lossy().into_owned();
            (n.ends_with(".yaml") && !n.ends_with(".trace.yaml"))
                .then(|| n.trim_end_matches(".yaml").to_string())
        })
        .collect();
    v.sort();
    v
}
