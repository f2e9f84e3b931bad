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
