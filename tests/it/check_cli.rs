//! `lamella check` through the binary: exit status 0 / 3, plan.json gains the
//! profile and the check, and every bad profile gets a one-line error naming
//! the profile file and the field, with exit status 1.

use crate::support::{lamella, root, scratch};
use std::path::Path;

fn steel() -> String {
    std::fs::read_to_string(root().join("profiles/steel-1.5.yaml")).unwrap()
}

#[test]
fn passing_network_exits_0_and_writes_the_check_into_plan_json() {
    let dir = scratch("pass");
    let out = dir.to_str().unwrap();
    let (code, stdout, _) = lamella(&[
        "check",
        "samples/enneper-4m.yaml",
        "--profile",
        "profiles/steel-1.5.yaml",
        "--out",
        out,
    ]);
    assert_eq!(code, Some(0), "{stdout}");
    assert!(
        stdout.lines().any(|l| l.starts_with("PASS: all 22 strips")),
        "{stdout}"
    );
    let plan: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("plan.json")).unwrap()).unwrap();
    let profile = &plan["profile"];
    for field in [
        "thickness_mm",
        "height_mm",
        "lamellas_per_strip",
        "gap_mm",
        "youngs_modulus_mpa",
        "shear_modulus_mpa",
        "design_strength_mpa",
    ] {
        assert!(profile[field].is_number(), "profile.{field}");
    }
    let strip = &plan["strips"][0];
    for field in [
        "utilization",
        "governing_station_mm",
        "bending_stress_mpa",
        "torsion_shear_mpa",
        "trapeze_stress_mpa",
    ] {
        assert!(strip["check"][field].is_number(), "check.{field}");
    }
    let lamellas = strip["lamellas"].as_array().unwrap();
    assert_eq!(lamellas.len(), 2);
    assert!(lamellas[0]["check"]["utilization"].is_number());
    // Each lamella on its own line: the strip's nodes, in order, at stations
    // that differ from the curve's (dy = ∓5.75 mm on a curved strip).
    let strip_nodes = strip["nodes"].as_array().unwrap();
    for l in lamellas {
        let nodes = l["nodes"].as_array().unwrap();
        assert_eq!(nodes.len(), strip_nodes.len());
        for (n, sn) in nodes.iter().zip(strip_nodes) {
            assert_eq!(n["node"], sn["node"]);
        }
        let last = nodes.last().unwrap()["station_mm"].as_f64().unwrap();
        assert!(last <= l["length_mm"].as_f64().unwrap() + 1e-4);
    }
    let (s1, s2) = (
        lamellas[0]["nodes"][1]["station_mm"].as_f64().unwrap(),
        lamellas[1]["nodes"][1]["station_mm"].as_f64().unwrap(),
    );
    assert!((s1 - s2).abs() > 0.01, "{s1} vs {s2}");
    assert_eq!(profile["resolved"]["lamella"]["thickness_mm"], 1.5);
    assert_eq!(plan["check"]["passes"], true);
    // The node fields of `nodes` stay as they were.
    assert!(strip["nodes"][0]["station_mm"].is_number());
    assert_eq!(plan["schema"], "lamella-plan/3");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn overstressed_network_exits_3_and_suggests() {
    let dir = scratch("fail");
    let p = dir.join("steel-9.yaml");
    std::fs::write(
        &p,
        steel().replace("thickness_mm: 1.5", "thickness_mm: 9.0"),
    )
    .unwrap();
    let (code, stdout, stderr) = lamella(&[
        "check",
        "samples/enneper-4m.yaml",
        "--profile",
        p.to_str().unwrap(),
        "--suggest",
    ]);
    assert_eq!(code, Some(3), "{stdout}{stderr}");
    assert!(
        stdout
            .lines()
            .any(|l| l.starts_with("FAIL: 22 of 22 strips overstressed")),
        "{stdout}"
    );
    assert!(stdout.contains("OVERSTRESSED"));
    assert!(
        stdout
            .lines()
            .any(|l| l.starts_with("suggest: every strip passes with lamellas at most 5.56")),
        "{stdout}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

/// A bad profile: exit 1, one line naming the profile file and `fragments`.
fn bad(name: &str, text: &str, fragments: &[&str]) {
    let dir = scratch(name);
    let p = dir.join(format!("{name}.yaml"));
    std::fs::write(&p, text).unwrap();
    let out = dir.join("out");
    let (code, stdout, stderr) = lamella(&[
        "check",
        "samples/hypar-small.yaml",
        "--profile",
        p.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(1), "{name}: {stdout}{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{name}: one line: {stderr}");
    assert!(
        stderr.starts_with("error: ") && stderr.contains(&format!("{name}.yaml")),
        "{name}: {stderr}"
    );
    for f in fragments {
        assert!(stderr.contains(f), "{name}: `{f}` not in {stderr}");
    }
    assert!(
        !Path::new(&out).join("plan.json").exists(),
        "{name}: nothing written"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn bad_profiles_name_the_field() {
    let s = steel();
    bad(
        "zero-sagitta",
        &format!("{s}check:\n  max_sagitta_mm: 0.0\n"),
        &["check.max_sagitta_mm", "positive"],
    );
    bad(
        "unknown-check-field",
        &format!("{s}check:\n  max_bow_mm: 1.0\n"),
        &["max_bow_mm"],
    );
    bad(
        "negative-thickness",
        &s.replace("thickness_mm: 1.5", "thickness_mm: -1.5"),
        &["lamella.thickness_mm", "positive"],
    );
    bad(
        "zero-thickness",
        &s.replace("thickness_mm: 1.5", "thickness_mm: 0"),
        &["lamella.thickness_mm", "positive"],
    );
    bad(
        "zero-height",
        &s.replace("height_mm: 50.0", "height_mm: 0.0"),
        &["lamella.height_mm", "positive"],
    );
    bad(
        "zero-modulus",
        &s.replace("youngs_modulus_mpa: 210000", "youngs_modulus_mpa: 0"),
        &["material.youngs_modulus_mpa"],
    );
    bad(
        "negative-shear",
        &s.replace("shear_modulus_mpa: 81000", "shear_modulus_mpa: -81000"),
        &["material.shear_modulus_mpa"],
    );
    bad(
        "zero-strength",
        &s.replace(
            "characteristic_strength_mpa: 355",
            "characteristic_strength_mpa: 0",
        ),
        &["material.characteristic_strength_mpa"],
    );
    bad(
        "negative-gap",
        &s.replace("gap_mm: 10.0", "gap_mm: -2.0"),
        &["lamella.gap_mm"],
    );
    bad(
        "missing-field",
        &s.replace("  height_mm: 50.0\n", ""),
        &["missing field `height_mm`", "line"],
    );
    bad(
        "unknown-field",
        &s.replace("  height_mm: 50.0\n", "  height_mm: 50.0\n  colour_mm: 3\n"),
        &["unknown field `colour_mm`"],
    );
    bad(
        "unitless",
        &s.replace("thickness_mm: 1.5", "thickness: 1.5"),
        &["`lamella.thickness` has no unit", "thickness_mm"],
    );
    bad(
        "unitless-value",
        &s.replace("thickness_mm: 1.5", "thickness_mm: 1.5 mm"),
        &["invalid type", "line"],
    );
    bad(
        "version-2",
        &s.replace("version: 1", "version: 2"),
        &["version", "newer"],
    );
    bad(
        "no-version",
        &s.replace("version: 1\n", ""),
        &["version", "missing"],
    );
    bad(
        "broken-yaml",
        &s.replace("lamella:\n", "lamella: [\n"),
        &["line"],
    );
    bad("empty", "", &["empty"]);
    bad(
        "doubled-without-gap",
        &s.replace("gap_mm: 10.0", "gap_mm: 0.0"),
        &["lamella.gap_mm", "doubled"],
    );
    bad(
        "bad-rotation",
        &s.replace("[0, 90, 180, 270]", "[0, 45]"),
        &["cutting.allowed_rotations_deg", "45"],
    );
    let ply = std::fs::read_to_string(root().join("profiles/poplar-ply-4.yaml")).unwrap();
    bad(
        "across-grain",
        &ply.replace("[0, 180]", "[0, 90, 180]"),
        &["cutting.allowed_rotations_deg", "grain"],
    );
    bad("two-level-without-studs", &ply.replace("stud:\n  length_mm: 120.0                  # spans both levels (2 x 60 mm)\n  fastener_diameter_mm: 4.0\n  bar_length_mm: 2000.0\n", "stud: null\n"), &["stud"]);
}

#[test]
fn missing_profile_file() {
    let (code, _, stderr) = lamella(&[
        "check",
        "samples/hypar-small.yaml",
        "--profile",
        "profiles/nope.yaml",
    ]);
    assert_eq!(code, Some(1));
    assert!(
        stderr.contains("nope.yaml") && stderr.contains("no such file"),
        "{stderr}"
    );
}

#[test]
fn nodes_writes_centre_line_lamellas_oriented_angles_and_typed_warnings() {
    let dir = scratch("nodes-model");
    // The hypar sample plus a B line far away (crosses nothing).
    let mut text = std::fs::read_to_string(root().join("samples/hypar-small.yaml")).unwrap();
    text.push_str(
        "  - id: B-lost\n    family: B\n    points: [[9000, 0, 0], [9000, 500, 0], [9000, 1000, 0]]\n",
    );
    let net = dir.join("net.yaml");
    std::fs::write(&net, text).unwrap();
    let out = dir.join("out");
    let (code, _stdout, stderr) = lamella(&[
        "nodes",
        net.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        stderr.contains("warning: curve B-lost: crosses no other curve"),
        "{stderr}"
    );
    let plan: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
    let warnings = plan["warnings"].as_array().unwrap();
    let lost = warnings
        .iter()
        .find(|w| w["kind"] == "isolated_curve")
        .expect("typed warning");
    assert_eq!(lost["curves"], serde_json::json!(["B-lost"]));
    assert!(lost["station_mm"].is_null());
    assert_eq!(lost["message"], "curve B-lost: crosses no other curve");
    for strip in plan["strips"].as_array().unwrap() {
        if strip["family"] == "edge" {
            assert!(strip.get("lamellas").is_none());
            continue;
        }
        let lamellas = strip["lamellas"].as_array().unwrap();
        assert_eq!(lamellas.len(), 1, "{}", strip["id"]);
        let l = &lamellas[0];
        assert_eq!(
            (
                l["lamella"].as_u64(),
                l["dy_mm"].as_f64(),
                l["dz_mm"].as_f64()
            ),
            (Some(1), Some(0.0), Some(0.0))
        );
        assert_eq!(l["length_mm"], strip["length_mm"]);
        assert!(l.get("check").is_none(), "no check without a profile");
        let nodes: Vec<(u64, f64)> = l["nodes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|n| {
                (
                    n["node"].as_u64().unwrap(),
                    n["station_mm"].as_f64().unwrap(),
                )
            })
            .collect();
        let on_curve: Vec<(u64, f64)> = strip["nodes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|n| {
                (
                    n["node"].as_u64().unwrap(),
                    n["station_mm"].as_f64().unwrap(),
                )
            })
            .collect();
        assert_eq!(
            nodes, on_curve,
            "{}: the centre line is the curve",
            strip["id"]
        );
    }
    for n in plan["nodes"].as_array().unwrap() {
        let (acute, oriented) = (
            n["angle_deg"].as_f64().unwrap(),
            n["oriented_angle_deg"].as_f64().unwrap(),
        );
        assert!((0.0..180.0).contains(&oriented));
        assert!((oriented.min(180.0 - oriented) - acute).abs() < 2e-6, "{n}");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// A hand-written network on a sphere of radius 5000 mm (normals radial):
/// A strips are meridians, B strips latitude circles, at −10°, 0° and 10°,
/// each over ±20°. No curve is asymptotic: kn = 1/R on all of them, so a
/// meridian, unrolled flat, bows R·(1 − cos 20°) = 301.5 mm off its chord,
/// while kg (0 on the meridians, tan(lat)/R on the latitudes) and tg (0)
/// stress the steel lamellas little.
fn sphere_network() -> String {
    let r = 5000.0f64;
    let point = |lat_deg: f64, lon_deg: f64| {
        let (lat, lon) = (lat_deg.to_radians(), lon_deg.to_radians());
        [lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin()]
    };
    let mut yaml = String::from("name: sphere\nunits: mm\ncurves:\n");
    for (family, meridian) in [("A", true), ("B", false)] {
        for (k, fixed) in [-10.0, 0.0, 10.0].into_iter().enumerate() {
            yaml += &format!("  - id: {family}{k}\n    family: {family}\n    points:\n");
            let along: Vec<[f64; 3]> = (0..=40)
                .map(|i| {
                    let t = -20.0 + f64::from(i);
                    if meridian {
                        point(t, fixed)
                    } else {
                        point(fixed, t)
                    }
                })
                .collect();
            for n in &along {
                yaml += &format!(
                    "      - [{:.6}, {:.6}, {:.6}]\n",
                    r * n[0],
                    r * n[1],
                    r * n[2]
                );
            }
            yaml += "    normals:\n";
            for n in &along {
                yaml += &format!("      - [{:.9}, {:.9}, {:.9}]\n", n[0], n[1], n[2]);
            }
        }
    }
    yaml
}

#[test]
fn a_network_off_the_asymptotic_lines_fails_on_its_sagitta() {
    let dir = scratch("sphere");
    let net = dir.join("sphere.yaml");
    std::fs::write(&net, sphere_network()).unwrap();
    let out = dir.join("out");
    let (code, stdout, stderr) = lamella(&[
        "check",
        net.to_str().unwrap(),
        "--profile",
        "profiles/steel-1.5.yaml",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(3), "{stdout}{stderr}");
    // Not for the stresses: for the bow, named with the strip, its
    // sagitta and the limit.
    assert!(!stdout.contains("overstressed"), "{stdout}");
    let fail: Vec<&str> = stdout.lines().filter(|l| l.starts_with("FAIL")).collect();
    assert_eq!(fail.len(), 1, "{stdout}");
    assert!(
        fail[0].starts_with("FAIL: 6 of 6 strips bowed; A")
            && fail[0].contains("over the 1.000 mm limit (check.max_sagitta_mm)"),
        "{stdout}"
    );
    let plan: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
    let check = &plan["check"];
    assert_eq!(check["passes"], false);
    assert_eq!(check["strips_overstressed"], 0);
    assert_eq!(check["strips_bowed"], 6);
    assert_eq!(check["limit_sagitta_mm"], 1.0);
    // The meridians: R·(1 − cos 20°) = 5000 × 0.0603074 = 301.537 mm.
    let want = 5000.0 * (1.0 - 20f64.to_radians().cos());
    let got = check["max_sagitta_mm"].as_f64().unwrap();
    assert!((got - want).abs() < 0.5, "{got} against {want}");
    let strip = &plan["strips"][0];
    assert_eq!(strip["id"], "A0");
    let sagitta = strip["check"]["sagitta_mm"].as_f64().unwrap();
    assert!((sagitta - want).abs() < 0.5, "{sagitta}");
    for l in strip["lamellas"].as_array().unwrap() {
        assert!(l["sagitta_mm"].as_f64().unwrap() > 290.0, "{l}");
    }
    // A limit above the bow passes.
    let loose = dir.join("loose.yaml");
    std::fs::write(
        &loose,
        format!("{}check:\n  max_sagitta_mm: 400\n", steel()),
    )
    .unwrap();
    let (code, stdout, _) = lamella(&[
        "check",
        net.to_str().unwrap(),
        "--profile",
        loose.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(0), "{stdout}");
    assert!(stdout.contains("PASS: all 6 strips"), "{stdout}");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn shipped_asymptotic_samples_still_pass_with_their_sagitta_reported() {
    for sample in [
        "catenoid",
        "hypar-small",
        "scherk",
        "film-saddle",
        "mesh-enneper",
    ] {
        let (code, stdout, _) = lamella(&[
            "check",
            &format!("samples/{sample}.yaml"),
            "--profile",
            "profiles/steel-1.5.yaml",
        ]);
        assert_eq!(code, Some(0), "{sample}: {stdout}");
        let pass = stdout.lines().find(|l| l.starts_with("PASS")).unwrap();
        let sagitta: f64 = pass
            .rsplit("largest sagitta ")
            .next()
            .and_then(|t| t.trim_end_matches(" mm").parse().ok())
            .unwrap();
        assert!(sagitta < 0.1, "{sample}: {pass}");
    }
}

/// `nest` (and `parts`) make and nest the parts of a network the check
/// fails, but say so: one warning with the check's own count of
/// overstressed strips; a network that passes gets no such warning.
#[test]
fn nest_of_an_overstressed_network_says_the_check_fails() {
    let sample = root().join("samples/film-oculus.yaml");
    let veneer = root().join("profiles/beech-veneer.yaml");
    let dir = scratch("nest-overstressed");
    let (code, out, _) = lamella(&[
        "check".as_ref(),
        sample.as_os_str(),
        "--profile".as_ref(),
        veneer.as_os_str(),
        "--out".as_ref(),
        dir.join("check").as_os_str(),
    ]);
    assert_eq!(code, Some(3), "{out}");
    // "FAIL: 2 of 45 strips overstressed; …"
    let fail = out
        .lines()
        .find(|l| l.starts_with("FAIL:") && l.contains("overstressed"))
        .expect("the check's FAIL line");
    let counted = fail
        .trim_start_matches("FAIL: ")
        .split(" strips overstressed")
        .next()
        .unwrap()
        .to_string();
    for command in ["nest", "parts"] {
        let (code, out, err) = lamella(&[
            command.as_ref(),
            sample.as_os_str(),
            "--profile".as_ref(),
            veneer.as_os_str(),
            "--out".as_ref(),
            dir.join(command).as_os_str(),
        ]);
        assert_eq!(code, Some(0), "{out}{err}");
        let warning = format!("warning: the check fails ({counted} strips overstressed;");
        assert_eq!(err.matches(&warning).count(), 1, "{command}: {err}");
        assert!(err.contains("--allow-overstress"), "{err}");
    }
    let enneper = root().join("samples/enneper-4m.yaml");
    let (code, _, err) = lamella(&[
        "nest".as_ref(),
        enneper.as_os_str(),
        "--profile".as_ref(),
        veneer.as_os_str(),
        "--out".as_ref(),
        dir.join("passing").as_os_str(),
    ]);
    assert_eq!(code, Some(0));
    assert!(!err.contains("the check fails"), "{err}");
}
