//! Curvatures and verdicts on meshes as a mesher leaves them: irregular
//! Delaunay triangles over jittered points, every vertex exactly on the
//! surface, 0.001 mm, no normals. The same spec traced on the analytic
//! surface and on its mesh must give the same strips, each strip's smallest
//! bending radius within 5 % and largest twist within 3 % of the analytic
//! trace, and the same verdict.

use crate::support::meshes::{delaunay_mesh, obj_text};
use crate::support::*;
use glam::{DMat3, DVec2, DVec3};
use lamella::check::check;
use lamella::design::surface::{Catenoid, Enneper, Helicoid, Surface};
use lamella::formats::read::{read_network, ReadOptions};
use lamella::{analyze, AnalysisOptions};
use std::path::Path;

/// Per strip: id, smallest bending radius (mm), largest twist (°/m); the
/// overstressed strips per profile; the points traced.
struct Measured {
    strips: Vec<(String, f64, f64)>,
    /// Overstressed strips under every shipped profile.
    overstressed: Vec<(String, usize)>,
    /// Per profile, every strip's utilisation (its worst lamella's).
    utilisation: Vec<Vec<f64>>,
    points: usize,
}

fn trace_and_measure(dir: &Path, name: &str, spec: &str) -> Measured {
    let spec_path = dir.join(format!("{name}.trace.yaml"));
    std::fs::write(&spec_path, spec).unwrap();
    let net_path = dir.join(format!("{name}.yaml"));
    let (code, out, err) = lamella(&[
        "trace",
        spec_path.to_str().unwrap(),
        "--out",
        net_path.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(0), "trace {name}: {out}{err}");
    let net = read_network(&net_path, ReadOptions::default()).expect("traced network");
    let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analysis");
    let reports: Vec<_> = PROFILES
        .iter()
        .map(|p| check(&an, &profile(p), false).0)
        .collect();
    let overstressed = PROFILES
        .iter()
        .zip(&reports)
        .map(|(p, r)| (p.to_string(), r.overstressed()))
        .collect();
    let utilisation = reports
        .iter()
        .map(|r| {
            r.strips
                .iter()
                .map(|s| s.lamellas[s.worst].utilization)
                .collect()
        })
        .collect();
    let strips = an
        .lamella_strips()
        .map(|s| {
            (
                s.id.clone(),
                s.min_bending_radius_mm().unwrap_or(f64::INFINITY),
                s.max_abs_tg_per_mm.to_degrees() * 1000.0,
            )
        })
        .collect();
    Measured {
        strips,
        overstressed,
        utilisation,
        points: net.curves.iter().map(|c| c.points_world_mm.len()).sum(),
    }
}

/// Compare the mesh trace with the analytic one; the failures, one line each.
fn compare(what: &str, exact: &Measured, mesh: &Measured) -> Vec<String> {
    let mut failures = Vec::new();
    let ids = |m: &Measured| m.strips.iter().map(|s| s.0.clone()).collect::<Vec<_>>();
    if ids(exact) != ids(mesh) {
        failures.push(format!(
            "{what}: strips differ: {:?} vs {:?}",
            ids(exact),
            ids(mesh)
        ));
        return failures;
    }
    let (mut worst_r, mut worst_t) = (0.0f64, 0.0f64);
    for (e, m) in exact.strips.iter().zip(&mesh.strips) {
        let er = if e.1.is_finite() {
            (m.1 - e.1) / e.1
        } else {
            0.0
        };
        let et = (m.2 - e.2) / e.2;
        eprintln!(
            "{what} {}: R {:.0} vs {:.0} mm ({:+.1} %), twist {:.2} vs {:.2} °/m ({:+.2} %)",
            e.0,
            m.1,
            e.1,
            100.0 * er,
            m.2,
            e.2,
            100.0 * et
        );
        worst_r = worst_r.max(er.abs());
        worst_t = worst_t.max(et.abs());
        if er.abs() > 0.05 {
            failures.push(format!(
                "{what} {}: smallest bending radius {:.0} mm, analytic {:.0} mm",
                e.0, m.1, e.1
            ));
        }
        if et.abs() > 0.03 {
            failures.push(format!(
                "{what} {}: largest twist {:.2} °/m, analytic {:.2} °/m",
                e.0, m.2, e.2
            ));
        }
    }
    eprintln!(
        "{what}: worst radius {:.2} %, worst twist {:.2} %, overstressed {:?} vs {:?}, points {} vs {}",
        100.0 * worst_r,
        100.0 * worst_t,
        mesh.overstressed,
        exact.overstressed,
        mesh.points,
        exact.points
    );
    for ((p, e), m) in PROFILES
        .iter()
        .zip(&exact.utilisation)
        .zip(&mesh.utilisation)
    {
        let worst = e
            .iter()
            .zip(m)
            .map(|(e, m)| ((m - e) / e).abs())
            .fold(0.0f64, f64::max);
        eprintln!("{what} {p}: utilisation within {:.2} %", 100.0 * worst);
        if worst > 0.05 {
            failures.push(format!(
                "{what} {p}: a strip's utilisation {:.1} % off the analytic",
                100.0 * worst
            ));
        }
    }
    if mesh.overstressed != exact.overstressed {
        failures.push(format!(
            "{what}: strips overstressed {:?}, analytic {:?}",
            mesh.overstressed, exact.overstressed
        ));
    }
    failures
}

/// The spec of `analytic` (its `surface:` lines replaced) on a mesh file.
fn mesh_spec(analytic: &str, surface_lines: &[&str], seed_mm: DVec3) -> String {
    let mut out = String::from("surface: mesh\nmesh: surface.obj\n");
    out.push_str(&format!(
        "seed_mm: [{:.6}, {:.6}, {:.6}]\n",
        seed_mm.x, seed_mm.y, seed_mm.z
    ));
    'line: for line in analytic.lines() {
        for s in surface_lines {
            if line.starts_with(s) {
                continue 'line;
            }
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}

struct Case {
    name: &'static str,
    analytic_spec: String,
    surface_keys: &'static [&'static str],
    seed_uv: DVec2,
    lo: DVec2,
    hi: DVec2,
    place: Box<dyn Fn(DVec2) -> DVec3>,
}

/// The shipped profiles: the verdict must agree under each.
const PROFILES: [&str; 3] = ["steel-1.5", "beech-veneer", "poplar-ply-4"];

fn cases() -> Vec<Case> {
    let analytic_keys: &[&str] = &[
        "surface:",
        "scale_mm:",
        "seed:",
        "placement:",
        "  rotate_deg",
        "c:",
    ];
    let enneper = std::fs::read_to_string(root().join("samples/enneper-4m.trace.yaml")).unwrap();
    let rot = DMat3::from_rotation_z(45f64.to_radians());
    let catenoid = std::fs::read_to_string(root().join("samples/catenoid.trace.yaml")).unwrap();
    let helicoid = "surface: helicoid\nc: 0.5\nscale_mm: 2000\nseed: [0.0, 1.0]\nspacing_mm: 300\n\
                    design: central\nclip:\n  box:\n    min_mm: [700, -1600, -700]\n    max_mm: [3400, 1600, 700]\n\
                    sampling:\n  step_mm: 25\n  tolerance_mm: 1.0e-7\n"
        .to_string();
    vec![
        Case {
            name: "enneper",
            analytic_spec: enneper,
            surface_keys: analytic_keys,
            seed_uv: DVec2::ZERO,
            lo: DVec2::splat(-0.62),
            hi: DVec2::splat(0.62),
            place: Box::new(move |q| rot * (Enneper.point(q) * 4400.0)),
        },
        Case {
            name: "catenoid",
            analytic_spec: catenoid,
            surface_keys: analytic_keys,
            seed_uv: DVec2::ZERO,
            lo: DVec2::new(-1.0, -0.62),
            hi: DVec2::new(1.0, 0.62),
            place: Box::new(|q| Catenoid { c: 1.0 }.point(q) * 1500.0),
        },
        Case {
            name: "helicoid",
            analytic_spec: helicoid,
            surface_keys: analytic_keys,
            seed_uv: DVec2::new(0.0, 1.0),
            lo: DVec2::new(-0.85, 0.3),
            hi: DVec2::new(0.85, 1.75),
            place: Box::new(|q| Helicoid { c: 0.5 }.point(q) * 2000.0),
        },
    ]
}

/// Trace every case on a Delaunay mesh of `cell_mm` cells jittered by
/// `jitter` of a cell and compare; the failures, one line each.
fn mesh_against_closed_form(cell_mm: f64, jitter: f64, only: Option<&str>) -> Vec<String> {
    let mut failures = Vec::new();
    for case in cases() {
        if only.is_some_and(|o| o != case.name) {
            continue;
        }
        let tag = format!("{}-{cell_mm}-{jitter}", case.name);
        let dir = scratch(&tag);
        let exact = trace_and_measure(&dir, "exact", &case.analytic_spec);
        // The parameter step giving cells of about cell_mm at the seed.
        let step = {
            let p0 = (case.place)(case.seed_uv);
            let du = (case.place)(case.seed_uv + DVec2::X * 1e-4).distance(p0) / 1e-4;
            let dv = (case.place)(case.seed_uv + DVec2::Y * 1e-4).distance(p0) / 1e-4;
            cell_mm / du.max(dv)
        };
        let (v, t) = delaunay_mesh(case.lo, case.hi, step, jitter, 7, &case.place);
        std::fs::write(dir.join("surface.obj"), obj_text(&v, &t)).unwrap();
        let seed = (case.place)(case.seed_uv);
        let spec = mesh_spec(&case.analytic_spec, case.surface_keys, seed);
        let mesh = trace_and_measure(&dir, "mesh", &spec);
        failures.extend(compare(&tag, &exact, &mesh));
        std::fs::remove_dir_all(&dir).unwrap();
    }
    failures
}

/// Enneper's surface, the catenoid and the helicoid as Delaunay meshes of
/// 80 mm cells jittered by 15 % and of 70 mm cells jittered by 35 %: the
/// same strips as on the closed form, each strip's smallest bending radius
/// within 5 %, its largest twist within 3 %, its utilisation under every
/// shipped profile within 5 %, the same overstressed strips. Measured:
/// radius within 1.6–3.8 %, twist 0.02–0.6 %, utilisation within 3.6 %.
#[test]
fn delaunay_meshes_bend_and_twist_like_the_closed_form() {
    let mut failures = mesh_against_closed_form(80.0, 0.15, None);
    failures.extend(mesh_against_closed_form(70.0, 0.35, None));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The same at the ends of the cell range, each jittered by 15 % and by
/// 35 %: 40 mm cells, where the coordinates' 0.001 mm rounding is the
/// larger error in the curvature tensors (the jets grow their
/// neighbourhoods), and 100 mm cells, where truncation is (quartic jets).
/// Measured: radius within 1.6–4.3 % at 40 mm, 0.9–4.4 % at 100 mm (the
/// catenoid's short strips, which twist three to five times faster than
/// they bend, 3.5–4.4 % at their ends); twist within 0.4 % and 1.5 %.
/// About 15 s.
#[test]
fn delaunay_meshes_at_40_and_100_mm_cells_bend_and_twist_like_the_closed_form() {
    let mut failures = Vec::new();
    for jitter in [0.15, 0.35] {
        failures.extend(mesh_against_closed_form(40.0, jitter, None));
        failures.extend(mesh_against_closed_form(100.0, jitter, None));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Any cell size and jitter (`CELL_MM`, `JITTER`, `CASE`): run with
/// `--ignored --nocapture` to see the figures.
#[test]
#[ignore]
fn measure_mesh_truth() {
    let var = |name: &str, default: f64| {
        std::env::var(name)
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(default)
    };
    let only = std::env::var("CASE").ok();
    let failures =
        mesh_against_closed_form(var("CELL_MM", 70.0), var("JITTER", 0.25), only.as_deref());
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
