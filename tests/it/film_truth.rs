//! Soap films with known answers: the film between two coaxial rings is a
//! catenoid, the film over the image of a circle of radius 0.8 on Enneper's
//! surface is Enneper's surface. Their asymptotic lines are known in closed
//! form (catenoid X = c(cosh v cos u, cosh v sin u, v): u ± v = const,
//! twist 1/(c cosh² v), geodesic curvature sinh|v| / (√2 c cosh² v),
//! length √2 c Δ(sinh v); Enneper at scale a: u ± v = const, twist
//! 2 / (a (1 + u² + v²)²), geodesic curvature √2 |u ± v| / (a (1 + u² + v²)²)),
//! so every traced strip is held to them: its smallest bending radius within
//! 5 %, its largest twist within 3 %, its length within 0.5 %, and every A×B
//! crossing within 0.5° of 90°. And every shipped film's crossings within
//! 0.5°.

use crate::support::*;
use glam::{DVec2, DVec3};
use lamella::design::surface::{Enneper, Placed, Surface};
use lamella::formats::read::{read_network, ReadOptions};
use lamella::network::Network;
use lamella::{analyze, Analysis, AnalysisOptions, Family};
use std::path::Path;
use std::sync::Arc;

/// Trace a spec (written to `dir`) with the binary and analyse the result.
fn trace(dir: &Path, spec: &str) -> (Network, Analysis) {
    let spec_path = dir.join("film.trace.yaml");
    std::fs::write(&spec_path, spec).unwrap();
    let net_path = dir.join("film.yaml");
    let (code, out, err) = lamella(&[
        "trace",
        spec_path.to_str().unwrap(),
        "--out",
        net_path.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(0), "trace: {out}{err}");
    let net = read_network(&net_path, ReadOptions::default()).expect("traced film");
    let an = analyze(&net, AnalysisOptions::for_network(&net)).expect("analysis");
    (net, an)
}

fn yaml_loop(points: &[DVec3]) -> String {
    let mut s = String::from("    -\n");
    for p in points {
        s.push_str(&format!("      - [{:.3}, {:.3}, {:.3}]\n", p.x, p.y, p.z));
    }
    s
}

/// The worst A×B crossing's distance from 90°, degrees, and how many.
fn worst_crossing_deg(net: &Network, an: &Analysis) -> (f64, usize) {
    let mut worst = 0.0f64;
    let mut count = 0;
    for n in &an.topology.nodes {
        let (fa, fb) = (net.curves[n.a].family, net.curves[n.b].family);
        if fa != Family::Edge && fb != Family::Edge && fa != fb {
            worst = worst.max((n.angle_deg - 90.0).abs());
            count += 1;
        }
    }
    (worst, count)
}

/// Every A×B crossing within 0.5° of 90° (when `claims.crossings`).
fn crossings_within_half_a_degree(
    what: &str,
    net: &Network,
    an: &Analysis,
    claims: Claims,
    failures: &mut Vec<String>,
) {
    let (worst, nodes) = worst_crossing_deg(net, an);
    eprintln!("{what}: {nodes} crossings, worst {worst:.3}° from 90°");
    if claims.crossings && worst > 0.5 {
        failures.push(format!("{what}: a crossing {worst:.2}° from 90°"));
    }
}

/// Per A/B strip of a traced film: (id, smallest bending radius mm, largest
/// twist rad/mm, length mm) as lamella measures them and as the closed form
/// gives them for the same stretch of the same line; the failures.
struct Strip {
    id: String,
    radius_mm: (f64, f64),
    /// The largest |kg| lamella measures, 1/mm (read where the closed form
    /// is straight: its radius is infinite there).
    max_kg_per_mm: f64,
    twist_per_mm: (f64, f64),
    length_mm: (f64, f64),
}

/// Which of the claims a test holds.
#[derive(Clone, Copy)]
struct Claims {
    radius: bool,
    crossings: bool,
}

/// A strip whose closed-form radius exceeds this is straight (lamella's own
/// threshold: `FrameOptions::straight_curvature_per_mm` = 1e-5 /mm): a 5 %
/// claim on an infinite radius is judged on its curvature instead, see
/// [`compare`].
const STRAIGHT_RADIUS_MM: f64 = 1e5;

/// Each strip against the closed form: twist within 3 %, length within
/// 0.5 %, and (when `claims.radius`) the smallest bending radius within
/// 5 %. On a strip straight in closed form (radius beyond
/// [`STRAIGHT_RADIUS_MM`]) the claim is on its curvature: the largest |kg|
/// lamella reads there within 5 % of the film's largest closed-form kg.
/// Bending stress is E·t·kg/2, so this says what the 5 % on radii says of
/// the strip that governs: no strip's bending stress is misread by more
/// than 5 % of the largest the film has.
fn compare(what: &str, strips: &[Strip], claims: Claims, failures: &mut Vec<String>) {
    let (mut wr, mut wt, mut wl, mut wk) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let kg_film = strips
        .iter()
        .map(|s| 1.0 / s.radius_mm.1)
        .fold(0.0f64, f64::max);
    for s in strips {
        if s.radius_mm.1 > STRAIGHT_RADIUS_MM {
            let ek = (s.max_kg_per_mm - 1.0 / s.radius_mm.1).abs() / kg_film;
            wk = wk.max(ek);
            eprintln!(
                "{what} {}: straight in closed form (R {:.0} m): largest kg {:.2e} /mm = {:.1} % of the film's largest ({:.2e} /mm)",
                s.id,
                s.radius_mm.1 * 1e-3,
                s.max_kg_per_mm,
                100.0 * ek,
                kg_film
            );
            if claims.radius && ek > 0.05 {
                failures.push(format!(
                    "{what} {}: kg on a straight strip {:.1} % of the film's largest",
                    s.id,
                    100.0 * ek
                ));
            }
        }
        let er = if s.radius_mm.1 > STRAIGHT_RADIUS_MM {
            0.0
        } else {
            (s.radius_mm.0 - s.radius_mm.1) / s.radius_mm.1
        };
        let et = (s.twist_per_mm.0 - s.twist_per_mm.1) / s.twist_per_mm.1;
        let el = (s.length_mm.0 - s.length_mm.1) / s.length_mm.1;
        wr = wr.max(er.abs());
        wt = wt.max(et.abs());
        wl = wl.max(el.abs());
        eprintln!(
            "{what} {}: R {:.0} vs {:.0} mm ({:+.1} %), twist {:.2} vs {:.2} °/m ({:+.2} %), length {:.1} vs {:.1} mm ({:+.2} %)",
            s.id,
            s.radius_mm.0,
            s.radius_mm.1,
            100.0 * er,
            s.twist_per_mm.0.to_degrees() * 1000.0,
            s.twist_per_mm.1.to_degrees() * 1000.0,
            100.0 * et,
            s.length_mm.0,
            s.length_mm.1,
            100.0 * el
        );
        if claims.radius && er.abs() > 0.05 {
            failures.push(format!(
                "{what} {}: bending radius {:+.1} %",
                s.id,
                100.0 * er
            ));
        }
        if et.abs() > 0.03 {
            failures.push(format!("{what} {}: twist {:+.1} %", s.id, 100.0 * et));
        }
        if el.abs() > 0.005 {
            failures.push(format!("{what} {}: length {:+.2} %", s.id, 100.0 * el));
        }
    }
    eprintln!(
        "{what}: {} strips, worst radius {:.2} % (straight strips' kg {:.2} % of the largest), twist {:.2} %, length {:.3} %",
        strips.len(),
        100.0 * wr,
        100.0 * wk,
        100.0 * wt,
        100.0 * wl
    );
}

fn polyline_length(p: &[DVec3]) -> f64 {
    p.windows(2).map(|w| w[1].distance(w[0])).sum()
}

/// The neck c of the stable catenoid through two rings of radius `r_mm`
/// at z = ±`h_mm`: the larger root of c cosh(h/c) = r.
fn catenoid_neck(r_mm: f64, h_mm: f64) -> f64 {
    let f = |c: f64| c * (h_mm / c).cosh() - r_mm;
    // f(r) > 0; f decreases to a minimum at c* (h/c* tanh-root) below r.
    let (mut lo, mut hi) = (0.5 * r_mm, r_mm);
    assert!(f(lo) < 0.0, "no stable catenoid for these rings");
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) < 0.0 {
            lo = mid
        } else {
            hi = mid
        }
    }
    0.5 * (lo + hi)
}

fn ring_film(dir: &Path, r_mm: f64, h_mm: f64, claims: Claims) -> Vec<String> {
    let c = catenoid_neck(r_mm, h_mm);
    let n = 360;
    let ring = |z: f64| -> Vec<DVec3> {
        (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                DVec3::new(r_mm * a.cos(), r_mm * a.sin(), z)
            })
            .collect()
    };
    let spec = format!(
        "surface: minimal\nboundaries_mm:\n{}{}film_edge_mm: 50\nseed_mm: [{c:.3}, 0, 0]\nspacing_mm: 300\n\
         design: central\nfill: true\nmax_curves_per_side: 15\nsampling:\n  step_mm: 25\n  tolerance_mm: 1.0e-4\n",
        yaml_loop(&ring(h_mm)),
        yaml_loop(&ring(-h_mm))
    );
    let (net, an) = trace(dir, &spec);
    let what = format!("rings {r_mm} mm ±{h_mm} mm (c = {c:.1} mm)");
    let mut failures = Vec::new();
    crossings_within_half_a_degree(&what, &net, &an, claims, &mut failures);
    let mut strips = Vec::new();
    for s in an.lamella_strips() {
        let curve = net.curves.iter().find(|c| c.id == s.id).unwrap();
        let pts = &curve.points_world_mm;
        let vs: Vec<f64> = pts.iter().map(|p| p.z / c).collect();
        let (v0, v1) = (vs[0], vs[vs.len() - 1]);
        let (vlo, vhi) = (v0.min(v1), v0.max(v1));
        // Largest |kg| = sinh|v| / (√2 c cosh² v) over [vlo, vhi]: it grows
        // with |v| up to sinh v = 1; sample it finely.
        let kg = |v: f64| v.abs().sinh() / (2f64.sqrt() * c * v.cosh().powi(2));
        let kg_max = (0..=2000)
            .map(|i| kg(vlo + (vhi - vlo) * i as f64 / 2000.0))
            .fold(0.0f64, f64::max);
        let v_near = if vlo <= 0.0 && vhi >= 0.0 {
            0.0
        } else {
            vlo.abs().min(vhi.abs())
        };
        let twist = 1.0 / (c * v_near.cosh().powi(2));
        let length = 2f64.sqrt() * c * (v1.sinh() - v0.sinh()).abs();
        strips.push(Strip {
            id: s.id.clone(),
            radius_mm: (
                s.min_bending_radius_mm().unwrap_or(f64::INFINITY),
                1.0 / kg_max,
            ),
            max_kg_per_mm: s.max_abs_kg_per_mm,
            twist_per_mm: (s.max_abs_tg_per_mm, twist),
            length_mm: (polyline_length(pts), length),
        });
    }
    compare(&what, &strips, claims, &mut failures);
    failures
}

/// Rings of 1.5 m radius 1.2 m apart (neck 1366 mm) and 0.8 m apart (neck
/// 1444 mm): every strip's smallest bending radius within 5 %, twist within
/// 3 %, length within 0.5 %, every crossing within 0.5° of 90°. Measured:
/// radius 1.1 % and 3.7 %, twist 0.05 %, lengths below 0.001 %, crossings
/// 0.003° and 0.007°. (With every quad of the loft split along the same diagonal the
/// near rings' A family bent 4.4 % less and the B family 5.7 % more at the
/// rim: the triangulation's handedness.)
#[test]
fn films_between_coaxial_rings_are_the_catenoid() {
    let mut failures = Vec::new();
    let all = Claims {
        radius: true,
        crossings: true,
    };
    for (h_mm, tag) in [(600.0, "far"), (400.0, "near")] {
        let dir = scratch(tag);
        failures.extend(ring_film(&dir, 1500.0, h_mm, all));
        std::fs::remove_dir_all(&dir).unwrap();
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

fn enneper_film(tag: &str, claims: Claims) -> Vec<String> {
    let scale_mm = 2500.0;
    let surface = Placed {
        surface: Arc::new(Enneper),
        scale_mm,
        rotation: glam::DMat3::IDENTITY,
        translation_mm: DVec3::ZERO,
    };
    let n = 400;
    let rim: Vec<DVec3> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            surface.point(DVec2::new(0.8 * a.cos(), 0.8 * a.sin()))
        })
        .collect();
    let spec = format!(
        "surface: minimal\nboundaries_mm:\n{}film_edge_mm: 50\nseed_mm: [0, 0, 0]\nspacing_mm: 300\n\
         design: central\nsampling:\n  step_mm: 25\n  tolerance_mm: 1.0e-4\n",
        yaml_loop(&rim)
    );
    let dir = scratch(tag);
    let (net, an) = trace(&dir, &spec);
    let what = "Enneper r = 0.8";
    let mut failures = Vec::new();
    crossings_within_half_a_degree(what, &net, &an, claims, &mut failures);
    let mut strips = Vec::new();
    for s in an.lamella_strips() {
        let curve = net.curves.iter().find(|c| c.id == s.id).unwrap();
        let pts = &curve.points_world_mm;
        let uvs: Vec<DVec2> = pts.iter().map(|p| invert(&surface, *p)).collect();
        // The family: the diagonal coordinate that varies least along it.
        let along_p = keeps_u_plus_v(&uvs);
        type Coordinate = fn(DVec2) -> f64;
        let (fixed, moving): (Coordinate, Coordinate) = if along_p {
            (|q| q.x + q.y, |q| q.x - q.y)
        } else {
            (|q| q.x - q.y, |q| q.x + q.y)
        };
        let p = uvs.iter().map(|q| fixed(*q)).sum::<f64>() / uvs.len() as f64;
        let (q0, q1) = (moving(uvs[0]), moving(uvs[uvs.len() - 1]));
        let (qlo, qhi) = (q0.min(q1), q0.max(q1));
        // On the line: u² + v² = (p² + q²)/2, λ = 1 + (p² + q²)/2;
        // kg = √2 |p| / (a λ²), tg = 2 / (a λ²), ds = λ dq / √2 · a.
        let lambda = |q: f64| 1.0 + 0.5 * (p * p + q * q);
        let q_near = if qlo <= 0.0 && qhi >= 0.0 {
            0.0
        } else {
            qlo.abs().min(qhi.abs())
        };
        let kg_max = 2f64.sqrt() * p.abs() / (scale_mm * lambda(q_near).powi(2));
        let twist = 2.0 / (scale_mm * lambda(q_near).powi(2));
        // ∫ λ dq / √2 = (q (1 + p²/2) + q³/6) / √2.
        let prim = |q: f64| (q * (1.0 + 0.5 * p * p) + q * q * q / 6.0) / 2f64.sqrt();
        let length = scale_mm * (prim(qhi) - prim(qlo));
        strips.push(Strip {
            id: s.id.clone(),
            radius_mm: (
                s.min_bending_radius_mm().unwrap_or(f64::INFINITY),
                1.0 / kg_max,
            ),
            max_kg_per_mm: s.max_abs_kg_per_mm,
            twist_per_mm: (s.max_abs_tg_per_mm, twist),
            length_mm: (polyline_length(pts), length),
        });
    }
    compare(what, &strips, claims, &mut failures);
    std::fs::remove_dir_all(&dir).unwrap();
    failures
}

/// The film over the image of the circle r = 0.8 on Enneper's surface
/// (scale 2.5 m, 400 boundary points, 50 mm film edges): every strip's
/// largest twist within 3 % and length within 0.5 % of the closed form's.
/// Measured: twist 1.8 %, lengths below 0.001 %.
#[test]
fn a_film_over_an_enneper_boundary_twists_like_enneper() {
    let failures = enneper_film(
        "enneper",
        Claims {
            radius: false,
            crossings: false,
        },
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The same film's bending radii within 5 % (the straight middle strips'
/// curvature within 5 % of the film's largest, see [`compare`]) and its
/// crossings within 0.5° of 90°. Measured: radii within 4.8 % (B07, next
/// to the straight middle strips; the short strips at the rim within
/// 2 %), the straight strips' largest kg 3.2 % of the film's largest,
/// crossings 0.008°. The film is steep over its
/// plan at the rim (its normal 77° from the plan's): over the plan its
/// triangles squeezed into 6.8° slivers and one-sided cubic fits there bent
/// the rim strips 11–50 % too much and crossed 0.98° off 90°; the film is
/// now made over a disk chart there and its tensors fitted as a minimal
/// surface's (`design::minimal`, `mesh::curvature::vertex_jets_minimal`).
#[test]
fn an_enneper_film_bends_like_enneper() {
    let failures = enneper_film(
        "enneper-strict",
        Claims {
            radius: true,
            crossings: true,
        },
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every shipped film's A×B crossings within 0.5° of 90° (a soap film is
/// minimal, its asymptotic families orthogonal).
#[test]
fn shipped_films_cross_at_right_angles() {
    let mut failures = Vec::new();
    for name in [
        "film-saddle",
        "film-rings",
        "film-oculus",
        "film-three-peaks",
    ] {
        let (net, an) = analysed_sample(name);
        let (worst, nodes) = worst_crossing_deg(&net, &an);
        eprintln!("{name}: {nodes} crossings, worst {worst:.3}° from 90°");
        if worst > 0.5 {
            failures.push(format!("{name}: a crossing {worst:.2}° from 90°"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
