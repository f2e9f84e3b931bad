//! Benchmark of form finding: soap films of about 20,000
//! triangles spanning the catenoid's two rings (R = 1 m, 0.8 m apart) and a
//! six-point spatial boundary (three high, three low points on a 3 m
//! circle), each in a fresh child process (its own peak memory).
//!
//!     cargo bench --bench minimal                 # both
//!     cargo bench --bench minimal -- catenoid     # one case
//!
//! Then the asymptotic net is traced on each film as `lamella trace` does
//! (a `surface: minimal` spec: 300 mm spacing, `fill`, 25 mm samples,
//! 1e-4 mm tolerance): the time to validate, chart and estimate the
//! curvature of the film (the surface step, `mesh_source::surface_of`, the
//! least of nine runs, each on a film form-found before it) and the time to
//! trace (the design less the preparation, the least of nine and five)
//! are printed after the form finding's (the least of nine), with the
//! whole case's (the design, which form-finds, prepares and traces). The
//! bench fails when a surface step or a whole case takes longer than it
//! did when the bench was first published (`CASES`).

// The network helpers are not used here: the cases are made in code.
#[allow(dead_code)]
mod support;

use glam::DVec3;
use lamella::design::minimal::{form_find, FormFindOptions, FormFound};
use std::f64::consts::TAU;
use std::path::Path;
use std::time::Instant;

/// The cases: name, target edge length (mm) giving about 20,000 triangles,
/// and the times the surface step and the whole case (form finding,
/// surface and trace) may take, s: what they took when this benchmark was
/// first published (0.13 + 0.03 + 0.02 s and 0.09 + 0.06 + 0.14 s, with
/// two-ring jets; the bench fails past them).
const CASES: [(&str, f64, (f64, f64)); 2] = [
    ("catenoid", 22.5, (0.03, 0.18)),
    ("six-point", 60.0, (0.06, 0.29)),
];

/// The boundary loops of a case, coordinates rounded to 0.001 mm as a
/// designer's export.
fn boundaries(case: &str, target_mm: f64) -> Vec<Vec<DVec3>> {
    let rounded = |p: DVec3| (p * 1000.0).round() / 1000.0;
    match case {
        "catenoid" => {
            let n = (TAU * 1000.0 / target_mm).ceil() as usize;
            [-400.0, 400.0]
                .iter()
                .map(|&z| {
                    (0..n)
                        .map(|i| {
                            let t = TAU * i as f64 / n as f64;
                            rounded(DVec3::new(1000.0 * t.cos(), 1000.0 * t.sin(), z))
                        })
                        .collect()
                })
                .collect()
        }
        _ => vec![(0..6)
            .map(|i| {
                let t = TAU * i as f64 / 6.0;
                let z = if i % 2 == 0 { 1500.0 } else { 0.0 };
                rounded(DVec3::new(3000.0 * t.cos(), 3000.0 * t.sin(), z))
            })
            .collect()],
    }
}

/// The form-found film of a case.
pub fn film(case: &str) -> FormFound {
    let (_, target_mm, _) = CASES
        .iter()
        .find(|c| c.0 == case)
        .copied()
        .expect("known case");
    form_find(
        &boundaries(case, target_mm),
        &FormFindOptions::with_target_edge_mm(target_mm),
        Path::new(case),
    )
    .expect("form finding")
}

fn main() {
    if let Some(case) = support::child_network() {
        measure(&case.to_string_lossy());
        return;
    }
    println!(
        "{:>10} {:>9} {:>9} {:>8} {:>11} {:>10} {:>11} {:>11} {:>8} {:>9}",
        "case",
        "vertices",
        "triangles",
        "time s",
        "iterations",
        "levels",
        "max |H|/mm",
        "mean |H|/mm",
        "min ang°",
        "peak MiB"
    );
    println!("then per case: surface (topology, curvature, chart) s, trace s, curves, points");
    let named: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| CASES.iter().any(|c| c.0 == a))
        .collect();
    for (case, _, _) in CASES {
        if named.is_empty() || named.iter().any(|n| n == case) {
            support::run_child(Path::new(case));
        }
    }
}

fn measure(case: &str) {
    let t0 = Instant::now();
    let f = film(case);
    let secs = t0.elapsed().as_secs_f64();
    let r = &f.report;
    println!(
        "{:>10} {:>9} {:>9} {:>8.3} {:>11} {:>10} {:>11.2e} {:>11.2e} {:>8.1} {:>9.0}",
        case,
        r.vertices,
        r.triangles,
        secs,
        r.iterations,
        r.iterations_per_level.len(),
        r.max_mean_curvature_per_mm,
        r.mean_mean_curvature_per_mm,
        r.min_angle_deg,
        support::peak_mib()
    );
    assert!(r.converged, "not converged: {r:?}");
    trace_on(case);
}

/// Trace the asymptotic net on a case's film through a `surface: minimal`
/// spec, timing the surface step (`mesh_source::surface_of` on the film
/// just form-found) and the trace.
fn trace_on(case: &str) {
    let (_, target_mm, _) = CASES
        .iter()
        .find(|c| c.0 == case)
        .copied()
        .expect("known case");
    let loops: Vec<String> = boundaries(case, target_mm)
        .iter()
        .map(|l| {
            let pts: Vec<String> = l
                .iter()
                .map(|p| format!("[{}, {}, {}]", p.x, p.y, p.z))
                .collect();
            format!("  - [{}]", pts.join(", "))
        })
        .collect();
    let seed = if case == "catenoid" {
        "[910, 0, 0]"
    } else {
        "[600, 300, 750]"
    };
    let spec_text = format!(
        "surface: minimal\nboundaries_mm:\n{}\nfilm_edge_mm: {target_mm}\nseed_mm: {seed}\nspacing_mm: 300\nfill: true\nsampling:\n  step_mm: 25\n  tolerance_mm: 1.0e-4\n",
        loops.join("\n")
    );
    let dir = std::env::temp_dir().join(format!("lamella-bench-minimal-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(format!("{case}.trace.yaml"));
    std::fs::write(&path, spec_text).expect("spec");
    let spec = lamella::formats::read::trace_spec::load(&path).expect("spec reads");
    // The form finding and the surface step on its film, each the least of
    // nine runs; the peak memory is over all of them.
    let (mut t_film, mut t_surface, mut t_prepare) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
    for _ in 0..9 {
        let t0 = Instant::now();
        let found = film(case);
        t_film = t_film.min(t0.elapsed().as_secs_f64());
        let (mesh, chart_uv) = (found.mesh, Some(found.chart_uv));
        let t1 = Instant::now();
        let surface = lamella::design::mesh_source::surface_of(&spec, &path, mesh, chart_uv, &path)
            .expect("surface");
        t_surface = t_surface.min(t1.elapsed().as_secs_f64());
        drop(surface);
        let t2 = Instant::now();
        let prepared = lamella::design::prepare_surface(
            &spec,
            &path,
            &lamella::formats::read::mesh::read_mesh,
        )
        .expect("surface");
        t_prepare = t_prepare.min(t2.elapsed().as_secs_f64());
        drop(prepared);
    }
    // The trace is the design less the preparation, the least of five
    // runs.
    let mut t_design = f64::INFINITY;
    let mut designed = None;
    for _ in 0..5 {
        let t2 = Instant::now();
        let made = lamella::design::design(&spec, &path, &lamella::formats::read::mesh::read_mesh)
            .expect("design");
        t_design = t_design.min(t2.elapsed().as_secs_f64());
        designed = Some(made);
    }
    let (net, report) = designed.expect("five designs");
    let points: usize = net.curves.iter().map(|c| c.points.len()).sum();
    let (budget_s, total_budget_s) = CASES
        .iter()
        .find(|c| c.0 == case)
        .map_or((0.0, 0.0), |c| c.2);
    let surface_s = t_surface;
    // Form finding, surface and trace: the design's least time.
    let total_s = t_design;
    println!(
        "{:>10} form finding {:.3} s, surface {:.3} s (at most {budget_s:.3} s), trace {:.3} s, all {total_s:.3} s (at most {total_budget_s:.2} s), {} A + {} B curves, {} points, peak {:.0} MiB, load average {}",
        case,
        t_film,
        surface_s,
        t_design - t_prepare,
        report.a_curves,
        report.b_curves,
        points,
        support::peak_mib(),
        support::load_average()
    );
    std::fs::remove_dir_all(dir).expect("clean up");
    if surface_s > budget_s || total_s > total_budget_s {
        eprintln!(
            "{case}: the surface step took {surface_s:.3} s (at most {budget_s:.3} s), the case {total_s:.3} s (at most {total_budget_s:.2} s)"
        );
        std::process::exit(1);
    }
}
