//! Stock groups: every sheet of every shipped sample × profile holds parts
//! of one material and thickness only, and says which (plan.json's sheet,
//! the sheet files' names, the DXF header, the SVG title, the takeoff);
//! every part of plan.json says the same as the sheets it is placed on;
//! the material and thickness each part kind should have are read here
//! from the profile file itself, not from the code that grouped them.
//! Bad `stocks:` fields are one-line errors naming the field.

use crate::support::{self, lamella, root, scratch};
use serde_json::Value;
use std::collections::BTreeMap;

/// The (material, thickness) a part kind is cut from, from the profile
/// file as written (README, "Stock groups").
fn expected(profile: &serde_yaml::Value, kind: &str) -> (String, f64) {
    let num = |v: &serde_yaml::Value| v.as_f64().expect("number");
    let lamella = &profile["lamella"];
    let (key, t) = match kind {
        "lamella" => ("", num(&lamella["thickness_mm"])),
        "edge_strip" => ("edge", num(&lamella["thickness_mm"])),
        "splice_plate" => ("splice", num(&lamella["thickness_mm"])),
        "washer" => ("washer", num(&profile["washer"]["thickness_mm"])),
        "shear_block" => ("shear_block", num(&lamella["gap_mm"])),
        "stud" => ("stud", num(&lamella["gap_mm"])),
        other => panic!("unknown part kind {other}"),
    };
    let material = profile
        .get("stocks")
        .and_then(|s| s.get(key))
        .and_then(|e| e.get("material"))
        .unwrap_or(&profile["material"]["name"])
        .as_str()
        .expect("material")
        .to_string();
    (material, t)
}

/// The shipped samples (networks, not trace specs) and profiles.
fn shipped(dir: &str, skip: &str) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(root().join(dir))
        .expect("dir")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".yaml") && !n.ends_with(skip))
        .map(|n| n.trim_end_matches(".yaml").to_string())
        .collect();
    v.sort();
    v
}

#[test]
fn every_shipped_sheet_holds_one_material_and_thickness() {
    let samples = shipped("samples", ".trace.yaml");
    let profiles = shipped("profiles", "\u{0}");
    assert!(samples.len() >= 12 && profiles.len() >= 4);
    let out = scratch("every");
    let mut nested = 0;
    for profile in &profiles {
        let text = std::fs::read_to_string(root().join(format!("profiles/{profile}.yaml")))
            .expect("profile");
        let yaml: serde_yaml::Value = serde_yaml::from_str(&text).expect("yaml");
        for sample in &samples {
            let what = format!("{sample} × {profile}");
            let dir = out.join(format!("{sample}-{profile}"));
            let (code, _, err) = lamella(&[
                "nest",
                &format!("samples/{sample}.yaml"),
                "--profile",
                &format!("profiles/{profile}.yaml"),
                "--out",
                dir.to_str().expect("utf-8"),
            ]);
            if code != Some(0) {
                // The parts stage refuses a few (the nesting table says
                // which); nothing else may fail.
                assert!(
                    err.contains("splice plate") || err.contains("slots leave"),
                    "{what}: {err}"
                );
                continue;
            }
            let plan: Value = serde_json::from_str(
                &std::fs::read_to_string(dir.join("plan.json")).expect("plan.json"),
            )
            .expect("json");
            let kinds: BTreeMap<&str, &str> = plan["parts"]
                .as_array()
                .expect("parts")
                .iter()
                .map(|p| (p["id"].as_str().unwrap(), p["kind"].as_str().unwrap()))
                .collect();
            // Every part says its material and thickness (the file's) and
            // its group (the one whose sheets it is placed on, below).
            let part_groups: BTreeMap<&str, &str> = plan["parts"]
                .as_array()
                .expect("parts")
                .iter()
                .map(|p| {
                    let (m, want) = expected(&yaml, p["kind"].as_str().unwrap());
                    assert_eq!(
                        (p["material"].as_str().unwrap(), p["thickness_mm"].as_f64()),
                        (m.as_str(), Some(want)),
                        "{what}: part {}",
                        p["id"]
                    );
                    (p["id"].as_str().unwrap(), p["group"].as_str().unwrap())
                })
                .collect();
            let sheets = plan["sheets"].as_array().expect("sheets");
            assert!(!sheets.is_empty(), "{what}");
            for s in sheets {
                let id = s["id"].as_str().unwrap();
                let (material, t) = (
                    s["material"].as_str().unwrap(),
                    s["thickness_mm"].as_f64().unwrap(),
                );
                for pl in s["placements"].as_array().unwrap() {
                    let kind = kinds[pl["part"].as_str().unwrap()];
                    let (m, want) = expected(&yaml, kind);
                    assert_eq!(
                        (material, t),
                        (m.as_str(), want),
                        "{what}: {id} holds {} ({kind})",
                        pl["part"]
                    );
                    assert_eq!(s["form"] == "bar", kind == "stud", "{what}: {id}");
                    assert_eq!(
                        s["group"].as_str(),
                        Some(part_groups[pl["part"].as_str().unwrap()]),
                        "{what}: {id} holds {}",
                        pl["part"]
                    );
                }
            }
            // Never fewer sheets than a group's bound (each group's
            // promise is the nesting table's: checked in `nest`).
            for g in plan["nesting"]["groups"].as_array().expect("groups") {
                let used = g["sheets_used"].as_u64().unwrap();
                let bound = g["lower_bound_sheets"].as_u64().unwrap();
                assert!(used >= bound, "{what}: {g}");
            }
            nested += 1;
        }
    }
    // 12 samples × 4 profiles less the kits the parts stage refuses.
    assert!(nested >= 40, "{nested}");
}

/// A build's files say the material and thickness: the sheet files are
/// named by group, the DXF header and the SVG title name the material and
/// thickness, the takeoff's stock lines carry them, and the studs are one
/// stock line of bars (no "stud bar" line beside it).
#[test]
fn a_builds_files_name_their_group_material_and_thickness() {
    let out = scratch("files");
    let o = support::build("enneper-4m", "poplar-ply-4", &out, &[]);
    support::ok(&o);
    let plan: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
    let mut files = 0;
    for (k, s) in plan["sheets"].as_array().unwrap().iter().enumerate() {
        let group = s["group"].as_str().unwrap();
        let stem = format!("{group}-sheet-{:03}", k + 1);
        let t = s["thickness_mm"].as_f64().unwrap();
        let t_text = format!("{t}").trim_end_matches(".0").to_string();
        let dxf = std::fs::read_to_string(out.join(format!("sheets/{stem}.dxf"))).expect("dxf");
        let note = dxf
            .split("$PROJECTNAME\n  1\n")
            .nth(1)
            .and_then(|r| r.lines().next())
            .expect("$PROJECTNAME");
        assert!(
            note.contains(&format!("{t_text} mm")) && note.contains(group),
            "{stem}: {note}"
        );
        let svg = std::fs::read_to_string(out.join(format!("sheets/{stem}.svg"))).expect("svg");
        let title = svg
            .split("<title>")
            .nth(1)
            .unwrap()
            .split("</title>")
            .next()
            .unwrap();
        assert!(
            title.contains(&format!("{t_text} mm")) && title.contains(group),
            "{stem}: {title}"
        );
        files += 1;
    }
    assert!(files >= 2);
    let takeoff: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("takeoff.json")).unwrap()).unwrap();
    let stock = takeoff["stock"].as_array().unwrap();
    for line in stock {
        assert!(
            line["material"].as_str().is_some_and(|m| !m.is_empty()),
            "{line}"
        );
        assert!(
            line["thickness_mm"].as_f64().is_some_and(|t| t > 0.0),
            "{line}"
        );
    }
    let bars: Vec<&Value> = stock
        .iter()
        .filter(|l| l["item"].as_str().unwrap().contains("20 × 20 × 2000"))
        .collect();
    assert_eq!(bars.len(), 1, "{stock:?}");
    // 121 studs of 120 mm, 16 to a 2000 mm bar at a 0.3 mm kerf
    // (16 × 120 + 15 × 0.3 = 1924.5 ≤ 2000 < 17 × 120 + 16 × 0.3): 8 bars.
    let studs = plan["parts"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["kind"] == "stud")
        .unwrap();
    let n = studs["count"].as_u64().unwrap();
    assert_eq!(bars[0]["count"].as_u64().unwrap(), n.div_ceil(16));
    assert_eq!(bars[0]["thickness_mm"], 20.0);
}

#[test]
fn bad_stock_fields_are_one_line_errors_naming_the_field() {
    let base = std::fs::read_to_string(root().join("profiles/steel-1.5.yaml")).unwrap();
    let dir = scratch("bad");
    let cases: [(&str, &str, &str); 8] = [
        // Unknown fields in an entry stay errors naming them (in the
        // size fields' place and in the entry's own).
        (
            "    kerf_mm: 0.4                    # fibre laser in 10 mm steel\n",
            "    kerf_mm: 0.4\n    colour: red\n",
            "colour",
        ),
        (
            "  washer:                           # star washers, 3 mm\n    length_mm: 2000.0\n",
            "  washer:\n    length: 2000.0\n",
            "stocks.washer.length",
        ),
        (
            "  washer:                           # star washers, 3 mm\n    length_mm: 2000.0\n",
            "  washer:\n    length_mm: -5\n",
            "stocks.washer.length_mm",
        ),
        (
            "    kerf_mm: 0.4                    # fibre laser in 10 mm steel\n",
            "    kerf_mm: 0.4\n    name: \"a/b\"\n",
            "stocks.shear_block.name",
        ),
        (
            "    kerf_mm: 0.4                    # fibre laser in 10 mm steel\n",
            "    kerf_mm: 0.4\n    allowed_rotations_deg: [45]\n",
            "stocks.shear_block.allowed_rotations_deg",
        ),
        (
            "    kerf_mm: 0.4                    # fibre laser in 10 mm steel\n",
            "    kerf_mm: 0.4\n    currency: USD\n",
            "stocks.shear_block.currency",
        ),
        (
            "stocks:                             # the other parts' stock (one material and thickness each)\n",
            "stocks:\n  stud:\n    price_per_unit: 3\n",
            "stocks.stud",
        ),
        (
            "stocks:                             # the other parts' stock (one material and thickness each)\n",
            "stocks:\n  splice:\n    length_mm: 1000\n    width_mm: 500\n",
            "stocks.splice",
        ),
    ];
    for (k, (from, to, field)) in cases.iter().enumerate() {
        assert!(base.contains(from), "{from}");
        let path = dir.join(format!("bad-{k}.yaml"));
        std::fs::write(&path, base.replacen(from, to, 1)).unwrap();
        let (code, _, err) = lamella(&[
            "check",
            "samples/hypar-small.yaml",
            "--profile",
            path.to_str().unwrap(),
        ]);
        assert_eq!(code, Some(1), "{field}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{field}: {err}");
        assert!(err.contains(field), "{field}: {err}");
    }
}
