//! Traced networks, as `lamella trace` writes them, carry curvature and twist
//! as accurately as the surface they come from: no clusters of samples at
//! the seed, no rounding that shows in kg or tg, at coarse and at very dense
//! sampling.

use crate::support::{lamella_command, profile, scratch};
use lamella::formats::read::{read_network, ReadOptions};
use lamella::{analyze, AnalysisOptions, Family, Network};
use std::path::Path;

/// Run `lamella trace` on a spec text; read the network it wrote.
fn trace(dir: &Path, name: &str, spec: &str) -> Network {
    let spec_path = dir.join(format!("{name}.trace.yaml"));
    std::fs::write(&spec_path, spec).unwrap();
    let out = dir.join(format!("{name}.yaml"));
    let run = lamella_command()
        .arg("trace")
        .arg(&spec_path)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    read_network(&out, ReadOptions::default()).unwrap()
}

/// Helicoid X = 1000·(v cos u, v sin u, u): its asymptotic lines are the
/// rulings and the helices v = const, with kg = v/(v² + 1) and
/// tg = 1/(v² + 1) per unit (÷ 1000 per mm). Every sample of every helix
/// holds kg and tg to 1e-4 relative, and the check's bending stress of the
/// worst helix is E·kg·t/2 to 2e-4 (a governing station on a cluster of
/// seed samples used to make it 1–2.5 % off).
#[test]
fn traced_helices_bend_and_twist_as_the_closed_form() {
    let dir = scratch("helicoid");
    let net = trace(
        &dir,
        "helicoid",
        "surface: helicoid\nc: 1.0\nscale_mm: 1000\nseed: [0.75, 0.9]\nspacing_mm: 200\n\
         clip:\n  parameters: {polygon: [[0.0, 0.3], [1.5, 0.3], [1.5, 1.5], [0.0, 1.5]]}\n\
         sampling: {step_mm: 25}\n",
    );
    let an = analyze(&net, AnalysisOptions::for_network(&net)).unwrap();
    let steel = profile("steel-1.5");
    let report = lamella::check::check(&an, &steel, false).0;
    let mut helices = 0;
    let mut worst_kg = (0.0f64, String::new());
    for (curve, strip) in net.curves.iter().zip(&an.strips) {
        if strip.family == Family::Edge {
            continue;
        }
        let radius = |p: &glam::DVec3| p.truncate().length();
        let r0 = radius(&curve.points_world_mm[0]);
        if curve
            .points_world_mm
            .iter()
            .any(|p| (radius(p) - r0).abs() > 1e-3)
        {
            continue; // a ruling
        }
        helices += 1;
        let v = r0 / 1000.0;
        let kg = v / (v * v + 1.0) / 1000.0;
        let tg = 1.0 / (v * v + 1.0) / 1000.0;
        for c in &strip.samples {
            assert!(
                (c.kg_per_mm.abs() - kg).abs() < 1e-4 * kg,
                "{} kg {} vs {kg} at {}",
                strip.id,
                c.kg_per_mm,
                c.station_mm
            );
            assert!(
                (c.tg_per_mm.abs() - tg).abs() < 1e-4 * tg,
                "{} tg {} vs {tg} at {}",
                strip.id,
                c.tg_per_mm,
                c.station_mm
            );
        }
        if kg > worst_kg.0 {
            worst_kg = (kg, strip.id.clone());
        }
    }
    assert!(helices >= 4, "{helices} helices");
    // The most bent helix: its centre line's bending stress (both lamellas
    // of the doubled strip sit ±5.75 mm off it, so compare the mean).
    let sc = report.strips.iter().find(|s| s.id == worst_kg.1).unwrap();
    let mean_sigma_b: f64 = sc
        .lamellas
        .iter()
        .map(|l| l.stresses.bending_stress_mpa)
        .sum::<f64>()
        / sc.lamellas.len() as f64;
    let want = 210_000.0 * worst_kg.0 * 1.5 / 2.0;
    assert!(
        (mean_sigma_b - want).abs() < 2e-4 * want,
        "σb {mean_sigma_b} vs {want} MPa"
    );
}

/// A trace sampled every 0.2 mm (with file normals, 6 decimals) gives the
/// same bending radius and twist as one sampled every 25 mm: the rounding
/// of dense samples does not show (it used to report R = 221 mm at a curve
/// end where the radius is 8.7 m).
#[test]
fn dense_traces_keep_their_curvature() {
    let dir = scratch("dense");
    let spec = |step: f64| {
        format!(
            "surface: enneper\nscale_mm: 4400\nplacement: {{rotate_deg: [0, 0, 45]}}\n\
             seed: [0.0, 0.0]\nspacing_mm: 270\n\
             clip:\n  box: {{min_mm: [-500, -500, -3000], max_mm: [500, 500, 3000]}}\n\
             sampling: {{step_mm: {step}}}\n"
        )
    };
    let coarse = trace(&dir, "coarse", &spec(25.0));
    let dense = trace(&dir, "dense", &spec(0.2));
    assert!(dense.point_count() > 50 * coarse.point_count() / 2);
    let a = analyze(&coarse, AnalysisOptions::for_network(&coarse)).unwrap();
    let b = analyze(&dense, AnalysisOptions::for_network(&dense)).unwrap();
    assert_eq!(a.strips.len(), b.strips.len());
    for (x, y) in a.strips.iter().zip(&b.strips) {
        assert_eq!(x.id, y.id);
        let rel = |p: f64, q: f64| (p - q).abs() / q.abs().max(1e-12);
        // Smoothing leaves curvature noise of CURVATURE_NOISE_TARGET (a
        // 10 km radius) by design; peaks reach a few times that, which
        // matters only on nearly straight strips (A00 here: R = 36 m).
        let noise = 4.0 * lamella::geom::curve::CURVATURE_NOISE_TARGET_PER_MM;
        assert!(
            (y.max_abs_kg_per_mm - x.max_abs_kg_per_mm).abs() < 1e-3 * x.max_abs_kg_per_mm + noise,
            "{}: max kg {} dense vs {} coarse",
            x.id,
            y.max_abs_kg_per_mm,
            x.max_abs_kg_per_mm
        );
        assert!(
            rel(y.max_abs_tg_per_mm, x.max_abs_tg_per_mm) < 1e-3,
            "{}: max tg {} dense vs {} coarse",
            x.id,
            y.max_abs_tg_per_mm,
            x.max_abs_tg_per_mm
        );
    }
}
