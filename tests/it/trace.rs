//! `lamella trace`: traced asymptotic lines against closed forms, orthogonal
//! crossings and Beltrami–Enneper on minimal surfaces, the shipped specs
//! regenerate their samples and run through `nodes` without a warning, and
//! bad specs get one-line errors.

use crate::support::*;
use glam::DVec2;
use lamella::design::surface::Surface;
use lamella::design::{design, placed_surface};
use lamella::formats::read::mesh::read_mesh;
use lamella::formats::read::trace_spec;
use lamella::spec::TraceSpec;
#[allow(unused_imports)]
use serde_yaml as _;
use std::path::{Path, PathBuf};

fn spec(name: &str) -> (TraceSpec, PathBuf) {
    let p = root().join("samples").join(format!("{name}.trace.yaml"));
    (trace_spec::load(&p).unwrap(), p)
}

const SPECS: [&str; 5] = [
    "enneper-4m",
    "catenoid",
    "scherk",
    "schwarz-d-patch",
    "hypar-small",
];

/// Distance from each traced point to the closed-form asymptotic line
/// u ± v = const through its curve's first point (Enneper and catenoid).
fn closed_form_error(name: &str) -> (f64, f64) {
    let (s, p) = spec(name);
    let (net, _) = design(&s, &p, &read_mesh).unwrap();
    let surface = placed_surface(&s);
    let mut worst: f64 = 0.0;
    let mut longest: f64 = 0.0;
    for c in net
        .curves
        .iter()
        .filter(|c| c.family != lamella::Family::Edge)
    {
        // Recover (u, v) of each point by Newton on the surface (from the seed).
        let uvs: Vec<DVec2> = c.points.iter().map(|p| invert(&surface, *p)).collect();
        let start = uvs[0];
        let (p0, q0) = (start.x + start.y, start.x - start.y);
        let along_p = uvs.iter().all(|q| ((q.x + q.y) - p0).abs() < 1e-4);
        let along_q = uvs.iter().all(|q| ((q.x - q.y) - q0).abs() < 1e-4);
        assert!(
            along_p || along_q,
            "{name} {}: not on a line u ± v = const",
            c.id
        );
        for (q, pt) in uvs.iter().zip(&c.points) {
            let exact = diagonal_closed_form(start, *q, along_p);
            worst = worst.max(pt.distance(surface.point(exact)));
        }
        let len: f64 = c.points.windows(2).map(|w| w[1].distance(w[0])).sum();
        longest = longest.max(len);
    }
    (worst, longest)
}

#[test]
fn traced_enneper_and_catenoid_follow_the_closed_form() {
    let (worst, longest) = closed_form_error("enneper-4m");
    assert!(worst < 0.01, "Enneper: {worst} mm");
    assert!(
        longest > 3000.0,
        "a 4 m span: the longest strip is {longest} mm"
    );
    let (worst, _) = closed_form_error("catenoid");
    assert!(worst < 0.01, "catenoid: {worst} mm");
}

#[test]
fn minimal_surface_nets_cross_at_90_degrees_and_satisfy_beltrami_enneper() {
    for name in ["enneper-4m", "catenoid", "scherk", "schwarz-d-patch"] {
        let (s, p) = spec(name);
        let (raw, _) = design(&s, &p, &read_mesh).unwrap();
        let surface = placed_surface(&s);
        // tg² = −K along every traced curve: the surface's geodesic torsion in
        // the direction of the traced curve (its smooth interpolant's tangent).
        for c in raw
            .curves
            .iter()
            .filter(|c| c.family != lamella::Family::Edge)
        {
            let smooth = lamella::geom::curve::SmoothCurve::new(&c.points);
            for (i, pt) in c.points.iter().enumerate().step_by(3) {
                let q = invert(&surface, *pt);
                let curv = surface.curvature(q);
                let s_mm = smooth.sample_stations_mm()[i];
                let tg = curv.geodesic_torsion(smooth.tangent(s_mm));
                let minus_k = -curv.gaussian();
                assert!(
                    (tg * tg - minus_k).abs() < 1e-6 * minus_k,
                    "{name} {} sample {i}: tg² {} vs −K {minus_k}",
                    c.id,
                    tg * tg
                );
            }
        }
        let (net, an) = run(raw);
        assert!(assert_ab_orthogonal(&net, &an, name) > 0);
    }
}

#[test]
fn shipped_specs_regenerate_their_samples_and_run_clean() {
    let dir = scratch("shipped");
    for name in SPECS {
        let out = dir.join(format!("{name}.yaml"));
        let spec = format!("samples/{name}.trace.yaml");
        let status = lamella_command()
            .args(["trace", &spec, "--out", out.to_str().unwrap()])
            .output()
            .unwrap();
        assert!(
            status.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&status.stderr)
        );
        let trace_stderr = String::from_utf8_lossy(&status.stderr);
        assert!(!trace_stderr.contains("warning"), "{name}: {trace_stderr}");
        // Deterministic: the same bytes as the shipped sample (but for the
        // regenerate comment, which names the output path).
        let strip = |t: String| {
            t.lines()
                .filter(|l| !l.starts_with('#'))
                .collect::<Vec<_>>()
                .join("\n")
        };
        let made = strip(std::fs::read_to_string(&out).unwrap());
        let shipped =
            strip(std::fs::read_to_string(root().join(format!("samples/{name}.yaml"))).unwrap());
        assert!(
            made == shipped,
            "{name}: samples/{name}.yaml is not what its spec traces"
        );
        let nodes = lamella_command()
            .args([
                "nodes",
                out.to_str().unwrap(),
                "--out",
                dir.join(name).to_str().unwrap(),
            ])
            .output()
            .unwrap();
        assert!(nodes.status.success());
        let stderr = String::from_utf8_lossy(&nodes.stderr);
        assert!(!stderr.contains("warning"), "{name}: {stderr}");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

fn bad(name: &str, text: &str, fragments: &[&str]) {
    let dir = scratch(&format!("bad-{name}"));
    let p = dir.join(format!("{name}.trace.yaml"));
    std::fs::write(&p, text).unwrap();
    let out = dir.join("net.yaml");
    let o = lamella_command()
        .args(["trace", p.to_str().unwrap(), "--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{name}: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{name}: {stderr}");
    assert!(
        stderr.contains(&format!("{name}.trace.yaml")),
        "{name}: {stderr}"
    );
    for f in fragments {
        assert!(stderr.contains(f), "{name}: `{f}` not in {stderr}");
    }
    assert!(!Path::new(&out).exists(), "{name}: nothing written");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn bad_specs_get_clear_errors() {
    let good = std::fs::read_to_string(root().join("samples/enneper-4m.trace.yaml")).unwrap();
    bad(
        "unknown-surface",
        &good.replace("surface: enneper", "surface: gyroid"),
        &["unknown variant `gyroid`", "line"],
    );
    bad(
        "seed-outside",
        &good.replace("seed: [0.0, 0.0]", "seed: [2.0, 1.0]"),
        &["seed", "outside", "domain"],
    );
    bad(
        "zero-spacing",
        &good.replace("spacing_mm: 270", "spacing_mm: 0"),
        &["spacing_mm", "positive"],
    );
    bad(
        "clip-removes-everything",
        &good
            .replace(
                "min_mm: [-1500, -1500, -3000]",
                "min_mm: [5000, 5000, -3000]",
            )
            .replace("max_mm: [1500, 1500, 3000]", "max_mm: [6000, 6000, 3000]"),
        &["clip", "seed", "lies outside the clip"],
    );
    bad(
        "two-clips",
        &good.replace(
            "clip:\n",
            "clip:\n  plane: {point_mm: [0, 0, 0], normal: [1, 0, 0]}\n",
        ),
        &["clip", "exactly one"],
    );
    bad("empty", "", &["empty"]);
    bad(
        "tiny-spacing",
        &good.replace("spacing_mm: 270", "spacing_mm: 0.001"),
        &["spacing_mm", "too small"],
    );
    bad(
        "nan-seed",
        &good.replace("seed: [0.0, 0.0]", "seed: [.nan, 0.0]"),
        &["seed", "finite"],
    );
    bad(
        "nan-rotation",
        &good.replace("rotate_deg: [0, 0, 45]", "rotate_deg: [.nan, 0, 45]"),
        &["placement", "finite"],
    );
    bad(
        "huge-scale",
        &good.replace("scale_mm: 4400 ", "scale_mm: 1.0e300 "),
        &["scale_mm", "beyond"],
    );
    bad(
        "too-many-curves",
        &good.replace(
            "design: central",
            "design: central\nmax_curves_per_side: 99999999",
        ),
        &["max_curves_per_side", "1 to 1000"],
    );
    bad(
        "fill-without-periodic",
        &good.replace("design: central", "design: central\nfill: true"),
        &["fill", "periodic"],
    );
}

#[test]
fn principal_net_is_orthogonal_and_bisected_by_the_asymptotic_one() {
    // The façade web: principal curvature lines cross at 90° everywhere and
    // make 45° with the asymptotic lines on a minimal surface.
    let (mut s, p) = spec("enneper-4m");
    s.net = lamella::spec::Net::Principal;
    s.seed = Some([0.05, 0.02]); // the saddle itself is not umbilic, but keep off the axes
    let (raw, _) = design(&s, &p, &read_mesh).unwrap();
    let (net, an) = run(raw);
    let ab: Vec<_> = an
        .topology
        .nodes
        .iter()
        .filter(|n| {
            net.curves[n.a].family == lamella::Family::A
                && net.curves[n.b].family == lamella::Family::B
        })
        .collect();
    assert!(ab.len() > 50);
    for n in ab {
        assert!((n.angle_deg - 90.0).abs() < 0.01);
        let c = placed_surface(&s).curvature(invert(&placed_surface(&s), n.position_world_mm));
        let (a, _) = c.asymptotic(0.0).unwrap();
        let ang = n.tangent_a_world.dot(a).abs().acos().to_degrees();
        assert!((ang - 45.0).abs() < 0.01, "principal vs asymptotic: {ang}°");
    }
}

mod stops {
    use glam::{DVec2, DVec3};
    use lamella::design::surface::{Catenoid, Hypar, Scherk, Surface, SurfaceJet};
    use lamella::design::trace::{trace_through, Everywhere, Field, Stop, TraceOptions};

    #[test]
    fn a_level_set_around_the_catenoid_closes_its_loop() {
        // The plane z = 300 cuts the catenoid (c = 1000) in a circle.
        let s = Catenoid { c: 1000.0 };
        let v = (0.3f64).asinh().min(0.3);
        let seed = DVec2::new(0.0, v);
        let plane = Field::Level {
            point_mm: DVec3::new(0.0, 0.0, 1000.0 * v),
            normal: DVec3::Z,
        };
        let t = trace_through(&s, plane, seed, &Everywhere, TraceOptions::default()).unwrap();
        assert_eq!(t.stop_end, Stop::ClosedLoop);
        let r = 1000.0 * v.cosh();
        assert!(
            (t.length_mm() - 2.0 * std::f64::consts::PI * r).abs() < 0.01,
            "{} vs {}",
            t.length_mm(),
            2.0 * std::f64::consts::PI * r
        );
        assert!(t
            .points_world_mm
            .iter()
            .all(|p| (p.z - 1000.0 * v).abs() < 1e-6));
    }

    #[test]
    fn scherk_traces_stop_at_the_domain_edge() {
        let t = trace_through(
            &Scherk,
            Field::AsymptoticA,
            DVec2::new(0.1, 0.0),
            &Everywhere,
            TraceOptions {
                max_step_mm: 0.02,
                ..TraceOptions::default()
            },
        )
        .unwrap();
        assert_eq!(
            (t.stop_start, t.stop_end),
            (Stop::DomainEdge, Stop::DomainEdge)
        );
        let end = t.uv[t.uv.len() - 1];
        assert!(
            end.x.abs().max(end.y.abs()) > std::f64::consts::FRAC_PI_2 - 1e-3,
            "{end}"
        );
    }

    /// z = x³ − 3xy² (the monkey saddle): flat (K = 0) at the origin.
    struct Monkey;
    impl Surface for Monkey {
        fn eval(&self, q: DVec2) -> SurfaceJet {
            let (x, y) = (q.x, q.y);
            SurfaceJet {
                p: DVec3::new(x, y, x * x * x - 3.0 * x * y * y),
                pu: DVec3::new(1.0, 0.0, 3.0 * x * x - 3.0 * y * y),
                pv: DVec3::new(0.0, 1.0, -6.0 * x * y),
                puu: DVec3::new(0.0, 0.0, 6.0 * x),
                puv: DVec3::new(0.0, 0.0, -6.0 * y),
                pvv: DVec3::new(0.0, 0.0, -6.0 * x),
            }
        }
    }

    #[test]
    fn no_asymptotic_curve_through_a_flat_point() {
        assert_eq!(
            trace_through(
                &Monkey,
                Field::AsymptoticA,
                DVec2::ZERO,
                &Everywhere,
                TraceOptions::default()
            ),
            Err(Stop::FlatPoint)
        );
        // A hypar is nowhere flat.
        assert!(trace_through(
            &Hypar { c: 1.0 },
            Field::AsymptoticA,
            DVec2::ZERO,
            &Everywhere,
            TraceOptions {
                max_length_mm: 10.0,
                ..TraceOptions::default()
            }
        )
        .is_ok());
    }
}

#[test]
fn a_plane_clip_cuts_with_an_edge_on_the_plane() {
    let (mut s, p) = spec("enneper-4m");
    s.clip =
        Some(serde_yaml::from_str("plane: {point_mm: [0, 0, 600], normal: [0, 0, 1]}").unwrap());
    s.max_curves_per_side = 6;
    let (raw, report) = design(&s, &p, &read_mesh).unwrap();
    assert!(report.edges >= 1);
    for c in raw
        .curves
        .iter()
        .filter(|c| c.family == lamella::Family::Edge)
    {
        assert!(
            c.points.iter().all(|q| (q.z - 600.0).abs() < 1e-5),
            "{} off the plane",
            c.id
        );
    }
    for c in raw.curves.iter() {
        assert!(
            c.points.iter().all(|q| q.z <= 600.0 + 1e-5),
            "{} beyond the plane",
            c.id
        );
    }
}

#[test]
fn alternating_design_keeps_diagonal_cells_square() {
    let (s, p) = spec("scherk");
    assert_eq!(s.design, lamella::spec::Design::Alternating);
    let (raw, report) = design(&s, &p, &read_mesh).unwrap();
    assert_eq!(
        report.a_curves, report.b_curves,
        "alternating adds A and B curves in pairs"
    );
    let (net, an) = run(raw);
    // Curve i of each family is the i-th by offset, so A_i × B_i runs along
    // the diagonal. Every diagonal cell has all four sides close to the spacing.
    let station = |a: usize, b: usize| -> Option<(f64, f64)> {
        let (ia, ib) = (
            net.curve_index(&format!("A{a:02}"))?,
            net.curve_index(&format!("B{b:02}"))?,
        );
        let n = an.topology.nodes.iter().find(|n| n.a == ia && n.b == ib)?;
        Some((n.station_a_mm, n.station_b_mm))
    };
    let mut worst: f64 = 0.0;
    let mut cells = 0;
    for i in 0..report.a_curves - 1 {
        // Cells cut by the clip are not whole.
        let corners = [
            station(i, i),
            station(i, i + 1),
            station(i + 1, i),
            station(i + 1, i + 1),
        ];
        if corners.iter().any(Option::is_none) {
            continue;
        }
        let station = |a: usize, b: usize| station(a, b).unwrap();
        cells += 1;
        let sides = [
            (station(i, i + 1).0 - station(i, i).0).abs(),
            (station(i + 1, i + 1).0 - station(i + 1, i).0).abs(),
            (station(i + 1, i).1 - station(i, i).1).abs(),
            (station(i + 1, i + 1).1 - station(i, i + 1).1).abs(),
        ];
        for side in sides {
            worst = worst.max((side / s.spacing_mm - 1.0).abs());
        }
    }
    assert!(cells >= 6, "{cells} whole diagonal cells");
    assert!(
        worst < 0.15,
        "a diagonal cell side differs from the spacing by {:.1} %",
        100.0 * worst
    );
}

#[test]
fn the_unfolded_pavilion_is_an_orthogonal_asymptotic_net() {
    // Traced on one skew quadrilateral of Schwarz D and unfolded by half-turns
    // about its edges: the copies join into one asymptotic net.
    let (s, p) = spec("schwarz-d-pavilion-1to5");
    assert!(s.periodic);
    let (raw, report) = design(&s, &p, &read_mesh).unwrap();
    assert!(report.a_curves > 20 && report.b_curves > 20 && report.edges > 4);
    // The net spans several copies of the patch: far beyond the quadrilateral
    // (edge 715 mm) around the seed.
    let far = raw
        .curves
        .iter()
        .flat_map(|c| &c.points)
        .map(|q| q.length())
        .fold(0.0, f64::max);
    assert!(far > 1000.0, "{far}");
    let (net, an) = run(raw);
    assert!(an.warnings().is_empty(), "{:?}", an.warnings());
    let ab = assert_ab_orthogonal(&net, &an, "pavilion");
    assert!(ab > 300, "{ab} A×B nodes");
    // kn = 0: the normals carried across copies stay the surface's, and the
    // strips asymptotic (the residual from the normals' rotation).
    for st in an
        .strips
        .iter()
        .filter(|st| st.family != lamella::Family::Edge)
    {
        assert!(
            st.max_abs_kn_per_mm < 1e-6,
            "{}: kn {}",
            st.id,
            st.max_abs_kn_per_mm
        );
    }
}

#[test]
fn a_4_m_catenoid_asymptotic_line_follows_the_closed_form() {
    use lamella::design::surface::{Catenoid, Placed};
    use lamella::design::trace::{trace_through, Everywhere, Field, TraceOptions};
    let s = Placed {
        surface: std::sync::Arc::new(Catenoid { c: 1.0 }),
        scale_mm: 1500.0,
        rotation: glam::DMat3::IDENTITY,
        translation_mm: glam::DVec3::ZERO,
    };
    let seed = DVec2::new(0.3, 0.1);
    let opts = TraceOptions {
        max_length_mm: 2000.0,
        ..TraceOptions::default()
    };
    for field in [Field::AsymptoticA, Field::AsymptoticB] {
        let t = trace_through(&s, field, seed, &Everywhere, opts).unwrap();
        assert!(
            (t.length_mm() - 4000.0).abs() < 1e-6,
            "a 4 m line: {}",
            t.length_mm()
        );
        let start = seed;
        let p0 = seed.x + seed.y;
        let along_p = t.uv.iter().all(|q| ((q.x + q.y) - p0).abs() < 1e-3);
        let mut worst: f64 = 0.0;
        for q in &t.uv {
            let exact = diagonal_closed_form(start, *q, along_p);
            worst = worst.max(s.point(*q).distance(s.point(exact)));
        }
        assert!(worst < 0.01, "{field:?}: {worst} mm from the closed form");
        // And its length is the closed form's: √2·c·|sinh v₁ − sinh v₀|.
        let (v0, v1) = (t.uv[0].y, t.uv[t.uv.len() - 1].y);
        let exact_len = std::f64::consts::SQRT_2 * 1500.0 * (v1.sinh() - v0.sinh()).abs();
        assert!(
            (t.length_mm() - exact_len).abs() < 0.01,
            "{} vs {exact_len}",
            t.length_mm()
        );
    }
}

#[test]
fn fill_covers_the_gaps_the_central_design_leaves() {
    let (mut s, p) = spec("schwarz-d-pavilion-1to5");
    let (plain, plain_report) = design(&s, &p, &read_mesh).unwrap();
    s.fill = true;
    let (filled, report) = design(&s, &p, &read_mesh).unwrap();
    assert!(
        report.a_curves > 2 * plain_report.a_curves && report.b_curves > 2 * plain_report.b_curves
    );
    let total = |n: &lamella::network::RawNetwork| -> f64 {
        n.curves
            .iter()
            .filter(|c| c.family != lamella::Family::Edge)
            .map(|c| {
                c.points
                    .windows(2)
                    .map(|w| w[1].distance(w[0]))
                    .sum::<f64>()
            })
            .sum()
    };
    assert!(total(&filled) > 1.5 * total(&plain));
    let (net, an) = run(filled);
    // Filled curves pass within millimetres of flat vertices, where they
    // turn at radii of 15 mm: sampling refines there (at most 0.1 rad
    // between chords), so every crossing still holds 90° ± 0.01°.
    assert!(assert_ab_orthogonal(&net, &an, "filled pavilion") > 300);
    // Filling is only for periodic designs.
    let (mut flat, fp) = spec("enneper-4m");
    flat.fill = true;
    assert!(design(&flat, &fp, &read_mesh).is_err());
}

/// Tangents of traced asymptotic lines (the smooth interpolant of finely
/// traced points, away from the ends) at their samples, with the samples'
/// parameters: (uv, unit tangent) pairs.
fn traced_tangents(
    surface: &lamella::design::surface::Placed,
    seeds: &[DVec2],
    max_length_mm: f64,
) -> Vec<(DVec2, glam::DVec3)> {
    use lamella::design::trace::{trace_through, Everywhere, Field, TraceOptions};
    let opts = TraceOptions {
        max_step_mm: 4.0,
        max_length_mm,
        ..TraceOptions::default()
    };
    let mut out = Vec::new();
    for &seed in seeds {
        for field in [Field::AsymptoticA, Field::AsymptoticB] {
            let t = trace_through(surface, field, seed, &Everywhere, opts).unwrap();
            let smooth = lamella::geom::curve::SmoothCurve::new(&t.points_world_mm);
            let stations = smooth.sample_stations_mm();
            let n = stations.len();
            assert!(n > 40, "{seed:?} {field:?}: {n} samples");
            for i in (8..n - 8).step_by(5) {
                out.push((t.uv[i], smooth.tangent(stations[i])));
            }
        }
    }
    out
}

/// Angle (rad) between the line of `t` and the nearest of the lines of `ds`.
fn angle_to_nearest(t: glam::DVec3, ds: &[glam::DVec3]) -> f64 {
    ds.iter()
        .map(|d| {
            let d = d.normalize();
            t.cross(d).length().atan2(t.dot(d).abs())
        })
        .fold(f64::INFINITY, f64::min)
}

/// First order in the direction (tg² = −K is flat at the asymptotic
/// direction and cannot see a small error): on Scherk's surface
/// z = ln cos y − ln cos x, II = sec²x dx² − sec²y dy², so the asymptotic
/// directions are (dx, dy) ∝ (cos x, ±cos y) (docs/geometry.md), mapped to space
/// by the partials. The traced tangent must lie on one of them.
#[test]
fn traced_scherk_tangents_follow_the_closed_form_directions() {
    use lamella::design::surface::{Placed, Scherk};
    let s = Placed {
        surface: std::sync::Arc::new(Scherk),
        scale_mm: 1000.0,
        rotation: glam::DMat3::from_rotation_z(0.4),
        translation_mm: glam::DVec3::new(100.0, -50.0, 20.0),
    };
    let seeds = [
        DVec2::new(0.0, 0.0),
        DVec2::new(0.3, -0.2),
        DVec2::new(-0.5, 0.4),
    ];
    let mut worst: f64 = 0.0;
    let samples = traced_tangents(&s, &seeds, 1200.0);
    for (q, t) in &samples {
        let (pu, pv) = s.partials(*q);
        let (cx, cy) = (q.x.cos(), q.y.cos());
        worst = worst.max(angle_to_nearest(
            *t,
            &[pu * cx + pv * cy, pu * cx - pv * cy],
        ));
    }
    assert!(samples.len() > 300, "{} samples", samples.len());
    assert!(worst < 1e-6, "Scherk: traced tangent {worst:e} rad off");
}

/// Schwarz D from its Weierstrass data (f, g = z): the Hopf differential is
/// f·g'·dz² = f dz², and II ∝ Re(f dz²); asymptotic directions have f dz²
/// imaginary: arg dz = (π/2 − arg f)/2 mod π/2, independent of the surface
/// module's shape operator. Also from the surface module's principal
/// directions: kn = k1·cos 2θ = 0 needs θ = 45° to d1.
#[test]
fn traced_schwarz_d_tangents_are_asymptotic_to_first_order() {
    use lamella::design::surface::{Placed, SchwarzD};
    let s = Placed {
        surface: std::sync::Arc::new(SchwarzD),
        scale_mm: 1000.0,
        rotation: glam::DMat3::IDENTITY,
        translation_mm: glam::DVec3::ZERO,
    };
    let seeds = [
        DVec2::new(0.0, 0.0),
        DVec2::new(0.1, 0.05),
        DVec2::new(-0.15, 0.12),
    ];
    let samples = traced_tangents(&s, &seeds, 250.0);
    assert!(samples.len() > 100, "{} samples", samples.len());
    let (mut worst_closed, mut worst_theta): (f64, f64) = (0.0, 0.0);
    for (q, t) in &samples {
        // w = 1 − 14 z⁴ + z⁸, f = w^(−½): arg f = −arg(w)/2 (mod π).
        let (x, y) = (q.x, q.y);
        let z2 = (x * x - y * y, 2.0 * x * y);
        let z4 = (z2.0 * z2.0 - z2.1 * z2.1, 2.0 * z2.0 * z2.1);
        let z8 = (z4.0 * z4.0 - z4.1 * z4.1, 2.0 * z4.0 * z4.1);
        let w = (1.0 - 14.0 * z4.0 + z8.0, -14.0 * z4.1 + z8.1);
        let arg_f = -0.5 * w.1.atan2(w.0);
        let phi = 0.5 * (std::f64::consts::FRAC_PI_2 - arg_f);
        let (pu, pv) = s.partials(*q);
        let dirs: Vec<glam::DVec3> = (0..2)
            .map(|k| {
                let a = phi + k as f64 * std::f64::consts::FRAC_PI_2;
                pu * a.cos() + pv * a.sin()
            })
            .collect();
        worst_closed = worst_closed.max(angle_to_nearest(*t, &dirs));
        // θ from the principal direction d1: 45° on an asymptotic line.
        let c = s.curvature(*q);
        let theta = t.dot(c.d2).abs().atan2(t.dot(c.d1).abs());
        worst_theta = worst_theta.max((theta - std::f64::consts::FRAC_PI_4).abs());
    }
    assert!(
        worst_closed < 1e-6,
        "Schwarz D: traced tangent {worst_closed:e} rad off the Hopf-differential direction"
    );
    assert!(
        worst_theta < 1e-6,
        "Schwarz D: traced tangent {worst_theta:e} rad off 45° to the principal direction"
    );
}

#[test]
fn each_bad_clip_and_sampling_gets_its_own_message() {
    let good = std::fs::read_to_string(root().join("samples/enneper-4m.trace.yaml")).unwrap();
    let clip = "  box:                    # a 4 m x 4 m plan, rotated so the strips run diagonally\n    min_mm: [-1500, -1500, -3000]\n    max_mm: [1500, 1500, 3000]\n";
    assert!(good.contains(clip));
    let with_clip = |c: &str| good.replace(clip, c);
    bad(
        "zero-block",
        &with_clip("  block: {center_mm: [0, 0, 0], size_mm: [0, 3000, 3000]}\n"),
        &["clip.block.size_mm", "degenerate"],
    );
    bad(
        "flat-polygon",
        &with_clip("  polygon: {points_mm: [[0, 0], [1, 1], [2, 2]]}\n"),
        &["clip.polygon.points_mm", "no area"],
    );
    bad(
        "empty-prism",
        &with_clip(
            "  polygon: {points_mm: [[-9, -9], [9, -9], [0, 9]], z_min_mm: 5, z_max_mm: 1}\n",
        ),
        &["clip.polygon", "empty", "z_min_mm"],
    );
    bad(
        "empty-box",
        &with_clip("  box: {min_mm: [0, 0, 0], max_mm: [0, 10, 10]}\n"),
        &["clip.box", "empty"],
    );
    bad(
        "no-clip-named",
        &with_clip("  {}\n"),
        &["clip", "exactly one of box, block"],
    );
    bad(
        "nan-box",
        &with_clip("  box: {min_mm: [.nan, 0, 0], max_mm: [1, 10, 10]}\n"),
        &["clip.box", "finite"],
    );
    // A step of 1e-9 mm used to be blamed on tolerance_mm.
    bad(
        "tiny-step",
        &good.replace("step_mm: 25", "step_mm: 1.0e-9"),
        &["sampling.step_mm", "0.1 to 1000 mm"],
    );
    bad(
        "coarse-tolerance",
        &good.replace("tolerance_mm: 1.0e-7", "tolerance_mm: 5"),
        &["sampling.tolerance_mm", "too coarse"],
    );
    bad(
        "dup-key",
        &format!("{good}\nspacing_mm: 300\n"),
        &[
            "line 19, column 1",
            "duplicate key `spacing_mm` (first at line 9)",
        ],
    );
}

#[test]
fn a_design_without_both_families_is_an_error() {
    // A spacing far beyond the clip: no curve is 5 % of it long, and an
    // empty network used to be written with exit status 0.
    let good = std::fs::read_to_string(root().join("samples/enneper-4m.trace.yaml")).unwrap();
    bad(
        "huge-spacing",
        &good.replace("spacing_mm: 270", "spacing_mm: 100000"),
        &["clip", "no A curve", "5 % of spacing_mm"],
    );
}

#[test]
fn a_traced_network_is_validated_as_it_would_be_read() {
    // Placed 20 km from the origin: the design runs, but a network file
    // that far out is refused when read, so it is not written.
    let good = std::fs::read_to_string(root().join("samples/enneper-4m.trace.yaml")).unwrap();
    let text = good
        .replace(
            "rotate_deg: [0, 0, 45]",
            "rotate_deg: [0, 0, 45]\n  translate_mm: [20000000, 0, 0]",
        )
        .replace("[-1500, -1500, -3000]", "[19998500, -1500, -3000]")
        .replace("[1500, 1500, 3000]", "[20001500, 1500, 3000]");
    bad("km", &text, &["would not read back", "curve A00", "10 km"]);
}

#[test]
fn design_loops_are_bounded() {
    // `fill` on a 200 m periodic block ran for minutes.
    let (_, p) = spec("schwarz-d-pavilion");
    let text = std::fs::read_to_string(&p)
        .unwrap()
        .replace("periodic: true", "periodic: true\nfill: true")
        .replace(
            "size_mm: [10000, 10000, 5000]",
            "size_mm: [200000, 200000, 100000]",
        );
    let t0 = std::time::Instant::now();
    bad("big-fill", &text, &["clip", "grows beyond"]);
    assert!(t0.elapsed().as_secs_f64() < 20.0, "{:?}", t0.elapsed());
    // `fill` keeps to max_curves_per_side.
    let (_, p) = spec("schwarz-d-pavilion-1to5");
    let text = std::fs::read_to_string(&p).unwrap().replace(
        "periodic: true",
        "periodic: true\nfill: true\nmax_curves_per_side: 6",
    );
    bad("fill-count", &text, &["fill", "more than 13 curves"]);
    // Central designs on an endless surface: bounded by points.
    let good = std::fs::read_to_string(root().join("samples/enneper-4m.trace.yaml")).unwrap();
    let i = good.find("clip:").unwrap();
    let j = good.find("sampling:").unwrap();
    let text = format!("{}{}", &good[..i], &good[j..]).replace(
        "spacing_mm: 270",
        "spacing_mm: 30\nmax_curves_per_side: 1000",
    );
    bad("endless", &text, &["clip", "grows beyond 500000 points"]);
}

#[test]
fn enneper_without_a_clip_warns_about_its_self_intersections() {
    let good = std::fs::read_to_string(root().join("samples/enneper-4m.trace.yaml")).unwrap();
    let i = good.find("clip:").unwrap();
    let j = good.find("sampling:").unwrap();
    let dir = scratch("noclip");
    let p = dir.join("noclip.trace.yaml");
    std::fs::write(&p, format!("{}{}", &good[..i], &good[j..])).unwrap();
    let out = dir.join("noclip.yaml");
    let o = lamella_command()
        .args(["trace", p.to_str().unwrap(), "--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{stderr}");
    assert!(
        stderr.contains("warning: ")
            && stderr.contains("not at 90°")
            && stderr.contains("passes through itself")
            && stderr.contains("no clip"),
        "{stderr}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn traced_curves_are_sampled_uniformly() {
    // Every traced curve used to restart at its seed with 1 mm and 5 mm
    // steps, and to end with whatever the bisection for the clip left.
    for name in ["enneper-4m", "catenoid", "scherk", "schwarz-d-pavilion"] {
        let (s, p) = spec(name);
        let (raw, _) = design(&s, &p, &read_mesh).unwrap();
        let step = s.sampling.step_mm;
        for c in &raw.curves {
            let chords: Vec<f64> = c.points.windows(2).map(|w| w[1].distance(w[0])).collect();
            let (lo, hi) = chords.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), x| {
                (lo.min(*x), hi.max(*x))
            });
            assert!(hi <= step + 1e-9, "{name} {}: a chord of {hi} mm", c.id);
            if c.family != lamella::Family::Edge || name != "schwarz-d-pavilion" {
                assert!(lo > 0.98 * hi, "{name} {}: chords {lo} to {hi} mm", c.id);
            }
        }
    }
    // Through the tracer: equal stations, the ends on the clip.
    use lamella::design::trace::{trace_through, Everywhere, Field, TraceOptions};
    let (s, _) = spec("enneper-4m");
    let surface = placed_surface(&s);
    let opts = TraceOptions {
        max_length_mm: 1234.5,
        ..TraceOptions::default()
    };
    let t = trace_through(
        &surface,
        Field::AsymptoticA,
        DVec2::new(0.01, 0.02),
        &Everywhere,
        opts,
    )
    .unwrap();
    let n = t.stations_mm.len() - 1;
    assert_eq!(n, (2.0f64 * 1234.5 / 25.0).ceil() as usize);
    for (i, st) in t.stations_mm.iter().enumerate() {
        assert!(
            (st - 2469.0 * i as f64 / n as f64).abs() < 1e-9,
            "{i}: {st}"
        );
    }
    // The samples lie on the closed-form line through the seed.
    let along_p = (t.uv[0].x + t.uv[0].y - 0.03).abs() < 1e-6;
    for q in &t.uv {
        let exact = diagonal_closed_form(DVec2::new(0.01, 0.02), *q, along_p);
        assert!(surface.point(*q).distance(surface.point(exact)) < 1e-6);
    }
}
