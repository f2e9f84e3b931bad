//! Networks as designers export them: OBJ and DXF polylines, no normals,
//! coordinates rounded to 0.001 mm, sampled every 5, 10, 25 and 50 mm. The
//! largest twist and the utilisation of every A/B strip must match what the
//! same network gives with exact surface normals in the file, within 3 %,
//! ends included, and the verdict must be the same.

use crate::support::synth::{self, Catenoid, Enneper, Helicoid, ParamLine, ParamSurface, Sampling};
use crate::support::{profile, scratch};
use dxf::entities::{Entity, EntityType, Polyline, Vertex};
use dxf::enums::{AcadVersion, Units};
use dxf::{Drawing, Point};
use glam::{DVec2, DVec3};
use lamella::check::check;
use lamella::formats::read::{read_network, ReadOptions};
use lamella::network::{Family, Network, RawNetwork};
use lamella::profile::Profile;
use lamella::{analyze, AnalysisOptions};
use std::fmt::Write as _;
use std::path::Path;

/// Export rounding, mm (Rhino's default display precision of 3 decimals).
const ROUND_MM: f64 = 0.001;
/// Allowed relative difference of max twist and utilisation to the result
/// with exact file normals.
const REL_TOL: f64 = 0.03;

fn round(p: DVec3) -> DVec3 {
    (p / ROUND_MM).round() * ROUND_MM
}

/// OBJ as Rhino writes polylines: `o` per curve, `v` with 3 decimals, one `l`.
fn write_obj(raw: &RawNetwork, path: &Path) {
    let mut out = String::from("# Rhino\n");
    let mut next = 1;
    for c in &raw.curves {
        let _ = writeln!(out, "o {}", c.id);
        for p in &c.points {
            let q = round(*p);
            let _ = writeln!(out, "v {:.3} {:.3} {:.3}", q.x, q.y, q.z);
        }
        let idx: Vec<String> = (next..next + c.points.len())
            .map(|i| i.to_string())
            .collect();
        let _ = writeln!(out, "l {}", idx.join(" "));
        next += c.points.len();
    }
    std::fs::write(path, out).expect("write OBJ");
}

/// DXF R2000, one 3D POLYLINE per curve on layer A, B or edge, rounded.
fn write_dxf(raw: &RawNetwork, path: &Path) {
    let mut drawing = Drawing::new();
    drawing.header.version = AcadVersion::R2000;
    drawing.header.default_drawing_units = Units::Millimeters;
    for c in &raw.curves {
        let mut pl = Polyline::default();
        pl.set_is_3d_polyline(true);
        for p in &c.points {
            let q = round(*p);
            let mut v = Vertex::new(Point::new(q.x, q.y, q.z));
            v.set_is_3d_polyline_vertex(true);
            pl.add_vertex(&mut drawing, v);
        }
        let mut e = Entity::new(EntityType::Polyline(pl));
        e.common.layer = match c.family {
            Family::A => "A",
            Family::B => "B",
            Family::Edge => "edge",
        }
        .to_string();
        drawing.add_entity(e);
    }
    drawing.save_file(path).expect("write DXF");
}

/// Per A/B strip (by id): largest |tg| (rad/mm) and utilisation.
struct Result {
    ids: Vec<String>,
    max_tg: Vec<f64>,
    util: Vec<f64>,
    passes: bool,
}

fn evaluate(net: &Network, profile: &Profile) -> Result {
    let an = analyze(net, AnalysisOptions::for_network(net)).expect("analysis");
    let report = check(&an, profile, false).0;
    let mut r = Result {
        ids: Vec::new(),
        max_tg: Vec::new(),
        util: Vec::new(),
        passes: report.passes(),
    };
    for sc in &report.strips {
        let strip = &an.strips[sc.strip];
        if strip.family == Family::Edge {
            continue;
        }
        r.ids.push(strip.id.clone());
        r.max_tg.push(strip.max_abs_tg_per_mm);
        r.util.push(sc.worst().utilization);
    }
    r
}

struct Case {
    name: &'static str,
    surface: Box<dyn ParamSurface>,
    lines: Vec<ParamLine>,
    scale_mm: f64,
}

fn enneper(scale_mm: f64) -> Case {
    Case {
        name: if scale_mm > 3000.0 {
            "enneper-4.4m"
        } else {
            "enneper-1.8m"
        },
        surface: Box::new(Enneper),
        lines: synth::diagonal_lines(0.5, 13, DVec2::ZERO),
        scale_mm,
    }
}

fn catenoid() -> Case {
    Case {
        name: "catenoid",
        surface: Box::new(Catenoid { c: 1000.0 }),
        lines: synth::diagonal_lines(1.0, 11, DVec2::new(0.3, 0.1)),
        scale_mm: 1.0,
    }
}

fn helicoid() -> Case {
    let us: Vec<f64> = synth::spread(0.75, 9).iter().map(|u| u + 0.75).collect();
    let vs: Vec<f64> = synth::spread(600.0, 9).iter().map(|v| v + 900.0).collect();
    Case {
        name: "helicoid",
        surface: Box::new(Helicoid { c: 1000.0 }),
        lines: synth::coordinate_lines(&us, &vs),
        scale_mm: 1.0,
    }
}

fn raw(case: &Case, step_mm: f64, normals: bool) -> RawNetwork {
    synth::network(
        case.name,
        case.surface.as_ref(),
        &case.lines,
        case.scale_mm,
        Sampling { step_mm, normals },
    )
}

/// Max twist and utilisation of every A/B strip from OBJ and DXF exports at
/// each sampling against the file-normals result.
fn check_exports(case: Case, profile_name: &str) {
    let profile = profile(profile_name);
    let dir = scratch(case.name);
    let exact = Network::new(raw(&case, 10.0, true), Path::new("exact.yaml")).unwrap();
    let want = evaluate(&exact, &profile);
    let mut report = String::new();
    let mut failures = Vec::new();
    for step_mm in [5.0, 10.0, 25.0, 50.0] {
        let r = raw(&case, step_mm, false);
        for ext in ["obj", "dxf"] {
            let path = dir.join(format!("{}-{step_mm}.{ext}", case.name));
            if ext == "obj" {
                write_obj(&r, &path);
            } else {
                write_dxf(&r, &path);
            }
            let net = read_network(&path, ReadOptions::default()).unwrap();
            let got = evaluate(&net, &profile);
            assert_eq!(got.ids.len(), want.ids.len(), "strips read from {ext}");
            let (mut worst_tg, mut worst_u) = (0.0f64, 0.0f64);
            for i in 0..want.ids.len() {
                let etg = (got.max_tg[i] - want.max_tg[i]).abs() / want.max_tg[i];
                let eu = (got.util[i] - want.util[i]).abs() / want.util[i];
                worst_tg = worst_tg.max(etg);
                worst_u = worst_u.max(eu);
                if etg > REL_TOL || eu > REL_TOL {
                    failures.push(format!(
                        "{} {step_mm} mm {ext} {}: max tg {:.3} vs {:.3} °/m, utilisation {:.4} vs {:.4}",
                        case.name,
                        want.ids[i],
                        got.max_tg[i].to_degrees() * 1000.0,
                        want.max_tg[i].to_degrees() * 1000.0,
                        got.util[i],
                        want.util[i]
                    ));
                }
            }
            let _ = writeln!(
                report,
                "{} {step_mm:>4} mm {ext}: worst max-tg error {:.4}, utilisation error {:.4}",
                case.name, worst_tg, worst_u
            );
            if got.passes != want.passes {
                failures.push(format!(
                    "{} {step_mm} mm {ext}: verdict {} vs {}",
                    case.name, got.passes, want.passes
                ));
            }
        }
    }
    eprintln!("{report}");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn enneper_4m_exports() {
    check_exports(enneper(4400.0), "steel-1.5");
}

#[test]
fn enneper_1_8m_exports() {
    check_exports(enneper(1800.0), "steel-1.5");
}

#[test]
fn catenoid_exports() {
    check_exports(catenoid(), "steel-1.5");
}

#[test]
fn helicoid_exports() {
    check_exports(helicoid(), "steel-1.5");
}

/// The smoothing is what makes this work: the same 5 mm export read as exact
/// coordinates (`--precision 0`) gives a twist many times too large.
#[test]
fn precision_option_switches_the_smoothing() {
    let profile = profile("steel-1.5");
    let case = enneper(4400.0);
    let dir = scratch("precision");
    let path = dir.join("enneper-5.obj");
    write_obj(&raw(&case, 5.0, false), &path);
    let exact = Network::new(raw(&case, 10.0, true), Path::new("exact.yaml")).unwrap();
    let want = evaluate(&exact, &profile).max_tg;
    let worst = |opts: ReadOptions| {
        let net = read_network(&path, opts).unwrap();
        let got = evaluate(&net, &profile).max_tg;
        got.iter()
            .zip(&want)
            .map(|(g, w)| (g - w).abs() / w)
            .fold(0.0, f64::max)
    };
    let implied = read_network(&path, ReadOptions::default()).unwrap();
    assert_eq!(implied.precision_mm, 0.001, "precision from the decimals");
    assert!(worst(ReadOptions::default()) < REL_TOL);
    let unsmoothed = worst(ReadOptions {
        precision_mm: Some(0.0),
        ..Default::default()
    });
    assert!(
        unsmoothed > 1.0,
        "exact reading of rounded samples: {unsmoothed}"
    );
}
