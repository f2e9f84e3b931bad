//! The elastic check against hand-computed stresses (helicoid rulings: pure
//! twist; helicoid helices: kg and tg in closed form; Enneper: tg = 2/λ²),
//! `--suggest`, and the profiles.

use crate::support::synth::{self, Enneper, Helicoid, Sampling};
use crate::support::*;
use glam::DVec2;
use lamella::check::{check, max_utilization, suggest, Governs};
use lamella::profile::Profile;

/// Hand formulas of docs/geometry.md for a lamella with curvature kg and twist tg.
fn hand(p: &Profile, kg: f64, tg: f64) -> (f64, f64, f64, f64) {
    let (e, g, t, h) = (
        p.youngs_modulus_mpa(),
        p.shear_modulus_mpa(),
        p.thickness_mm(),
        p.height_mm(),
    );
    let sb = e * kg.abs() * t / 2.0;
    let tau = g * tg.abs() * t;
    let sw = e * tg * tg * h * h / 12.0;
    (sb, tau, sw, ((sb + sw).powi(2) + 3.0 * tau * tau).sqrt())
}

fn close(a: f64, b: f64, rel: f64, what: &str) {
    assert!(
        (a - b).abs() <= rel * b.abs().max(1e-9),
        "{what}: {a} vs {b}"
    );
}

const C: f64 = 1000.0;

fn helicoid() -> (lamella::Network, lamella::Analysis, Vec<f64>) {
    let us: Vec<f64> = synth::spread(0.6, 7).iter().map(|u| u + 0.6).collect();
    let vs: Vec<f64> = synth::spread(500.0, 6).iter().map(|v| v + 800.0).collect();
    let lines = synth::coordinate_lines(&us, &vs);
    let raw = synth::network(
        "helicoid",
        &Helicoid { c: C },
        &lines,
        1.0,
        Sampling {
            step_mm: 10.0,
            normals: true,
        },
    );
    let (net, an) = run(raw);
    (net, an, vs)
}

#[test]
fn helicoid_rulings_are_pure_twist() {
    let (net, an, vs) = helicoid();
    for p in [profile("steel-1.5"), profile("beech-veneer")] {
        let report = check(&an, &p, false).0;
        for sc in report
            .strips
            .iter()
            .filter(|s| net.curves[s.strip].family == lamella::Family::A)
        {
            for l in &sc.lamellas {
                // Twist is largest at the ruling's inner end, v = vs[0], station 0.
                let v = vs[0];
                let tg = C / (v * v + C * C);
                let stretch = (1.0 + (l.line.offset.dy_mm * tg).powi(2)).sqrt();
                let (sb, tau, sw, sv) = hand(&p, 0.0, tg / stretch);
                assert_eq!(sb, 0.0);
                assert!(
                    l.stresses.bending_stress_mpa < 1e-6,
                    "no bending on a ruling"
                );
                close(l.stresses.torsion_shear_mpa, tau, 1e-5, "St. Venant shear");
                close(l.stresses.trapeze_stress_mpa, sw, 1e-5, "trapeze stress");
                close(l.stresses.combined_stress_mpa, sv, 1e-5, "combined");
                close(
                    l.utilization,
                    sv / p.design_strength_mpa(),
                    1e-5,
                    "utilisation",
                );
                assert!(
                    l.governing_curve_station_mm < 1e-9,
                    "governs at the inner end"
                );
                assert_eq!(l.min_bending_radius_mm, None, "a ruling is straight");
            }
        }
    }
}

#[test]
fn helicoid_helices_bend_and_twist_in_closed_form() {
    let (net, an, _vs) = helicoid();
    let p = profile("steel-1.5");
    let report = check(&an, &p, false).0;
    for sc in report
        .strips
        .iter()
        .filter(|s| net.curves[s.strip].family == lamella::Family::B)
    {
        let strip = &an.strips[sc.strip];
        let v = net.curves[sc.strip].points_world_mm[0].truncate().length();
        let (kg0, tg0) = (v / (v * v + C * C), C / (v * v + C * C));
        for l in &sc.lamellas {
            // The sign of kg on this lamella's side: from the computed frame.
            let kg_signed = strip.samples[10].kg_per_mm.signum() * kg0;
            let dy = l.line.offset.dy_mm;
            let stretch = ((1.0 - dy * kg_signed).powi(2) + (dy * tg0).powi(2)).sqrt();
            let (sb, tau, sw, sv) = hand(&p, kg0 / stretch, tg0 / stretch);
            close(l.stresses.bending_stress_mpa, sb, 1e-4, "bending");
            close(l.stresses.torsion_shear_mpa, tau, 1e-4, "shear");
            close(l.stresses.trapeze_stress_mpa, sw, 1e-4, "trapeze");
            close(
                l.utilization,
                sv / p.design_strength_mpa(),
                1e-4,
                "utilisation",
            );
            close(
                l.min_bending_radius_mm.unwrap(),
                stretch / kg0,
                1e-4,
                "lamella bending radius",
            );
            // The lamella's length: the helix length times the constant stretch.
            close(
                l.line.length_mm,
                strip.length_mm * stretch,
                1e-6,
                "lamella length",
            );
        }
        // The inner lamella (shorter, more curved) governs.
        let w = sc.worst();
        assert!(sc
            .lamellas
            .iter()
            .all(|l| l.line.length_mm >= w.line.length_mm - 1e-9));
    }
}

#[test]
fn enneper_twist_is_two_over_lambda_squared() {
    let lines = synth::diagonal_lines(0.5, 7, DVec2::ZERO);
    let scale = 4400.0;
    let raw = synth::network(
        "e",
        &Enneper,
        &lines,
        scale,
        Sampling {
            step_mm: 10.0,
            normals: true,
        },
    );
    let (net, an) = run(raw);
    let p = profile("steel-1.5");
    let report = check(&an, &p, false).0;
    // A03 and B03 are the straight lines through the centre (u = ±v), where
    // λ = 1: tg = 2/scale, kg = 0; that is the worst point of the network.
    for id in ["A03", "B03"] {
        let sc = report.strips.iter().find(|s| s.id == id).unwrap();
        for l in &sc.lamellas {
            let tg = 2.0 / scale;
            let stretch = (1.0 + (l.line.offset.dy_mm * tg).powi(2)).sqrt();
            let (_, tau, sw, sv) = hand(&p, 0.0, tg / stretch);
            // The worst sample lies within half a sample spacing of the centre.
            close(
                l.stresses.torsion_shear_mpa,
                tau,
                1e-5,
                "shear at the centre",
            );
            close(
                l.stresses.trapeze_stress_mpa,
                sw,
                2e-5,
                "trapeze at the centre",
            );
            close(
                l.utilization,
                sv / p.design_strength_mpa(),
                1e-5,
                "utilisation",
            );
            assert_eq!(l.governs, Governs::Torsion);
            // The centre is half way along.
            let half = an.strips[sc.strip].length_mm / 2.0;
            assert!(
                (l.governing_curve_station_mm - half).abs() < 10.0,
                "station {}",
                l.governing_curve_station_mm
            );
        }
        let _ = &net;
    }
    close(
        report.max_utilization(),
        report
            .strips
            .iter()
            .find(|s| s.id == "A03")
            .unwrap()
            .worst()
            .utilization,
        1e-12,
        "centre governs",
    );
}

#[test]
fn suggested_thickness_passes_and_five_percent_more_fails() {
    let raw = synth::enneper_4m(Sampling {
        step_mm: 25.0,
        normals: true,
    });
    let (_net, an) = run(raw);
    // Too thick a steel: overstressed.
    let thick = profile("steel-1.5").with_section(9.0, 50.0);
    assert!(!check(&an, &thick, false).0.passes());
    let s = suggest(&an, &thick);
    let t = s.max_thickness_mm.unwrap();
    assert!(t < 9.0);
    assert!(
        max_utilization(&an, &thick.with_section(t, 50.0)) <= 1.0,
        "the suggestion passes"
    );
    assert!(
        max_utilization(&an, &thick.with_section(1.05 * t, 50.0)) > 1.0,
        "5 % more fails"
    );
    // Too tall a lamella: the trapeze term alone fails at 400 mm, so no
    // thickness works; a height is suggested instead.
    let tall = profile("steel-1.5").with_section(1.5, 400.0);
    let s = suggest(&an, &tall);
    assert_eq!(s.max_thickness_mm, None);
    let h = s.max_height_mm.unwrap();
    assert!(max_utilization(&an, &tall.with_section(1.5, h)) <= 1.0);
    assert!(max_utilization(&an, &tall.with_section(1.5, 1.05 * h)) > 1.0);
    let (h2, t2) = s.height_and_thickness_mm.unwrap();
    assert!(max_utilization(&an, &tall.with_section(t2, h2)) <= 1.0);
}

#[test]
fn shipped_profiles_load_and_derive_limits() {
    let steel = profile("steel-1.5");
    close(steel.design_strength_mpa(), 355.0, 1e-12, "f_d steel");
    close(
        steel.min_bending_radius_mm(),
        210000.0 * 1.5 / (2.0 * 355.0),
        1e-12,
        "R_min",
    );
    let offs = steel.lamella_offsets(lamella::Family::A);
    assert_eq!(offs.len(), 2);
    close(offs[1].dy_mm, (10.0 + 1.5) / 2.0, 1e-12, "dy");
    let ply = profile("poplar-ply-4");
    close(
        ply.design_strength_mpa(),
        0.6 * 20.0 / 1.2,
        1e-12,
        "f_d plywood",
    );
    assert_eq!(ply.lamella_offsets(lamella::Family::A)[0].dz_mm, 30.0);
    assert_eq!(ply.lamella_offsets(lamella::Family::B)[0].dz_mm, -30.0);
    let beech = profile("beech-veneer");
    assert_eq!(beech.lamella_offsets(lamella::Family::B).len(), 1);
    assert_eq!(beech.lamella_offsets(lamella::Family::B)[0].dy_mm, 0.0);
}

/// The steel profile as a single lamella (E = 210 GPa, G = 81 GPa,
/// t = 1.5 mm, h = 50 mm, f_d = 355 MPa), built in memory.
fn single_steel() -> Profile {
    let mut p = profile("steel-1.5");
    p.section.per_strip = 1;
    p.section.gap_mm = 0.0;
    p.shear_block = None;
    assert_eq!(p.lamella_offsets(lamella::Family::A).len(), 1);
    p
}

fn raw_curve(
    id: &str,
    family: lamella::Family,
    n: usize,
    f: impl Fn(f64) -> glam::DVec3,
) -> lamella::network::RawCurve {
    lamella::network::RawCurve {
        id: id.into(),
        family,
        points: (0..n).map(|i| f(i as f64 / (n - 1) as f64)).collect(),
        normals: Some(vec![glam::DVec3::Z; n]),
    }
}

/// In the plane z = 0 (normal +z): A0 an arc of radius R = 1000 mm (kg =
/// 1/R, kn = tg = 0), crossed by three radial straight B lines.
fn planar_arc() -> lamella::network::RawNetwork {
    use glam::DVec3;
    let r = 1000.0;
    let mut curves = vec![raw_curve("A0", lamella::Family::A, 61, |t| {
        let a = (60.0 * t).to_radians();
        DVec3::new(r * a.cos(), r * a.sin(), 0.0)
    })];
    for (k, deg) in [15.0f64, 30.0, 45.0].iter().enumerate() {
        let a = deg.to_radians();
        curves.push(raw_curve(&format!("B{k}"), lamella::Family::B, 21, |t| {
            DVec3::new(a.cos(), a.sin(), 0.0) * (900.0 + 200.0 * t)
        }));
    }
    lamella::network::RawNetwork {
        name: "arc".into(),
        unit: lamella::network::Unit::Mm,
        tolerance: Some(0.5),
        precision: None,
        curves,
    }
}

#[test]
fn bending_stress_by_hand_on_a_one_metre_arc() {
    let (net, an) = run(planar_arc());
    let a0 = net.curve_index("A0").unwrap();
    // σb = E·|kg|·t/2 = 210 000 MPa × (1/1000 mm) × 1.5 mm / 2 = 157.5 MPa.
    let report = check(&an, &single_steel(), false).0;
    let l = report
        .strips
        .iter()
        .find(|s| s.strip == a0)
        .unwrap()
        .worst();
    assert!(
        (l.stresses.bending_stress_mpa - 157.5).abs() < 0.01,
        "σb {}",
        l.stresses.bending_stress_mpa
    );
    assert!(l.stresses.torsion_shear_mpa < 0.01 && l.stresses.trapeze_stress_mpa < 0.01);
    assert!((l.stresses.combined_stress_mpa - 157.5).abs() < 0.01);
    assert!((l.utilization - 157.5 / 355.0).abs() < 1e-4);
    assert_eq!(l.governs, Governs::Bending);
    assert!((l.min_bending_radius_mm.unwrap() - 1000.0).abs() < 0.01);
    // Doubled (dy = ±(10 + 1.5)/2 = ±5.75 mm): the lamellas are arcs of radius
    // 1000 ∓ 5.75 mm, so σb = 315 000 / (2 × 994.25) = 158.4109 MPa on the
    // inner one and 315 000 / (2 × 1005.75) = 156.5996 MPa on the outer one.
    let report = check(&an, &profile("steel-1.5"), false).0;
    let sc = report.strips.iter().find(|s| s.strip == a0).unwrap();
    let mut sb: Vec<f64> = sc
        .lamellas
        .iter()
        .map(|l| l.stresses.bending_stress_mpa)
        .collect();
    sb.sort_by(f64::total_cmp);
    assert!((sb[0] - 156.5996).abs() < 0.01, "{sb:?}");
    assert!((sb[1] - 158.4109).abs() < 0.01, "{sb:?}");
    // The inner lamella is 60° of a 994.25 mm radius: 1041.1762 mm.
    let inner = sc
        .lamellas
        .iter()
        .max_by(|a, b| {
            a.stresses
                .bending_stress_mpa
                .total_cmp(&b.stresses.bending_stress_mpa)
        })
        .unwrap();
    assert!(
        (inner.line.length_mm - 1041.1762).abs() < 0.01,
        "{}",
        inner.line.length_mm
    );
}

#[test]
fn torsion_and_trapeze_stress_by_hand_on_a_helicoid_ruling() {
    // Helicoid X = (v cos u, v sin u, c·u), c = 1000 mm: a ruling u = const
    // is straight (kg = 0) with tg = c/(v² + c²), largest on the axis v = 0:
    // tg = 1/1000 per mm. Single steel lamella:
    //   τ  = G·|tg|·t      = 81 000 × 0.001 × 1.5          = 121.5 MPa
    //   σw = E·tg²·h²/12   = 210 000 × 1e-6 × 50² / 12     = 43.75 MPa
    //   σv = √(43.75² + 3 × 121.5²)                         = 214.9437 MPa
    let lines = synth::coordinate_lines(&[0.0, 0.3, 0.6], &[-400.0, -200.0, 200.0, 400.0]);
    let raw = synth::network(
        "ruling",
        &Helicoid { c: C },
        &lines,
        1.0,
        Sampling {
            step_mm: 10.0,
            normals: true,
        },
    );
    let (net, an) = run(raw);
    let report = check(&an, &single_steel(), false).0;
    let mut rulings = 0;
    for sc in report
        .strips
        .iter()
        .filter(|s| net.curves[s.strip].family == lamella::Family::A)
    {
        let l = sc.worst();
        assert!(
            (l.stresses.torsion_shear_mpa - 121.5).abs() < 0.01,
            "{}: τ {}",
            sc.id,
            l.stresses.torsion_shear_mpa
        );
        assert!(
            (l.stresses.trapeze_stress_mpa - 43.75).abs() < 0.01,
            "{}: σw {}",
            sc.id,
            l.stresses.trapeze_stress_mpa
        );
        assert!(l.stresses.bending_stress_mpa < 0.01);
        assert!((l.stresses.combined_stress_mpa - 214.9437).abs() < 0.01);
        // On the axis (half way along the 800 mm ruling), within the
        // sample spacing (the check scans the samples).
        assert!(
            (l.governing_station_mm - 400.0).abs() < 10.0,
            "{}: governs at {} of {}",
            sc.id,
            l.governing_station_mm,
            an.strips[sc.strip].length_mm
        );
        rulings += 1;
    }
    assert_eq!(rulings, 3);
}

/// A tight edge arc (R = 30 mm) far from the grid: as curved as no lamella
/// could be, and not a lamella at all.
fn with_tight_edge(mut raw: lamella::network::RawNetwork) -> lamella::network::RawNetwork {
    raw.curves.push(lamella::network::RawCurve {
        id: "edge-tight".into(),
        family: lamella::Family::Edge,
        points: (0..=54)
            .map(|i| {
                let a = (5.0 * i as f64).to_radians();
                glam::DVec3::new(9000.0 + 30.0 * a.cos(), 9000.0 + 30.0 * a.sin(), 0.0)
            })
            .collect(),
        normals: None,
    });
    raw
}

#[test]
fn suggest_ignores_edge_strips_as_check_does() {
    let (_n, plain, _vs) = helicoid();
    let (us, vs): (Vec<f64>, Vec<f64>) = (
        synth::spread(0.6, 7).iter().map(|u| u + 0.6).collect(),
        synth::spread(500.0, 6).iter().map(|v| v + 800.0).collect(),
    );
    let raw = synth::network(
        "helicoid",
        &Helicoid { c: C },
        &synth::coordinate_lines(&us, &vs),
        1.0,
        Sampling {
            step_mm: 10.0,
            normals: true,
        },
    );
    let (net, edged) = run(with_tight_edge(raw));
    let edge = net.curve_index("edge-tight").unwrap();
    assert!(edged.strips[edge].max_abs_kg_per_mm > 1.0 / 31.0);
    assert_eq!(edged.lamella_strips().count(), plain.strips.len());
    assert_eq!(edged.edge_strips().count(), 1);
    for p in [
        profile("steel-1.5"),
        profile("steel-1.5").with_section(6.0, 50.0),
        profile("beech-veneer"),
    ] {
        // The same verdict, the same worst lamella, the same suggestion.
        let (a, b) = (check(&plain, &p, false).0, check(&edged, &p, false).0);
        assert_eq!(a.strips.len(), b.strips.len());
        assert_eq!(a.max_utilization(), b.max_utilization());
        assert_eq!(max_utilization(&plain, &p), max_utilization(&edged, &p));
        assert_eq!(max_utilization(&edged, &p), b.max_utilization());
        assert_eq!(suggest(&plain, &p), suggest(&edged, &p));
    }
    // A passing grid keeps its headroom: edges do not make it thinner.
    let steel = profile("steel-1.5");
    assert!(check(&edged, &steel, false).0.passes());
    let t = suggest(&edged, &steel).max_thickness_mm.unwrap();
    assert!(t > 1.5, "suggested {t} mm for a passing 1.5 mm grid");
}

#[test]
fn profile_is_built_from_the_file_type_and_back() {
    use lamella::formats::read::profile_file::ProfileFile;
    for name in ["steel-1.5", "poplar-ply-4", "beech-veneer"] {
        let text = std::fs::read_to_string(root().join(format!("profiles/{name}.yaml"))).unwrap();
        let file: ProfileFile = serde_yaml::from_str(&text).unwrap();
        let p = Profile::try_from(file.clone()).unwrap();
        assert_eq!(p.thickness_mm(), file.lamella.thickness_mm);
        assert_eq!(p.material.name, file.material.name);
        // `resolved` is the whole profile as read.
        assert_eq!(ProfileFile::from(&p), file, "{name}");
        assert_eq!(ProfileFile::from(&profile(name)), file, "{name}");
        // Validation lives in TryFrom: a bad field is named.
        let mut bad = file.clone();
        bad.lamella.thickness_mm = -1.0;
        let e = Profile::try_from(bad).unwrap_err();
        assert_eq!(e.field, "lamella.thickness_mm");
    }
}
