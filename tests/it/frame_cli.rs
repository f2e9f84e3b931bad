//! `lamella frame` and `lamella build --loads` through the binary: the
//! printed verdict is the plan's (α_cr the smallest first factor of the ULS
//! combinations, the utilisation their largest, the deflection the largest
//! SLS translation against span/300 of the supports' plan spread), every
//! combination's reactions balance its loads, the OpenSees script and the
//! model's JSON are written and readable, exit status 3 when the grid does
//! not stand; bad loads files and mechanisms get one-line errors and
//! nothing written.

use crate::support::{build, lamella, scratch};
use serde_json::Value;
use std::path::Path;
use std::process::Command;

fn plan_of(dir: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("plan.json")).expect("plan.json"))
        .expect("plan.json parses")
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The number after `key` in `line` (e.g. `α_cr 4.28 (…)` → 4.28).
fn after(line: &str, key: &str) -> f64 {
    let rest = &line[line.find(key).unwrap_or_else(|| panic!("{key} in {line}")) + key.len()..];
    rest.split_whitespace()
        .next()
        .and_then(|w| w.parse().ok())
        .unwrap_or_else(|| panic!("a number after {key} in {line}"))
}

/// The printed verdict against the plan's own numbers, recomputed from its
/// per-combination and per-support tables.
fn verdict_is_the_plans(verdict: &str, st: &Value) {
    let combos = st["combinations"].as_array().expect("combinations");
    let uls = |c: &&Value| c["limit_state"] == "ULS";
    let alpha = combos
        .iter()
        .filter(uls)
        .filter_map(|c| c["alpha_cr"][0].as_f64())
        .fold(f64::INFINITY, f64::min);
    let utilisation = combos
        .iter()
        .filter(uls)
        .filter_map(|c| c["max_utilisation"].as_f64())
        .fold(0.0, f64::max);
    let deflection = combos
        .iter()
        .filter(|c| c["limit_state"] == "SLS")
        .map(|c| num(&c["max_translation_mm"]))
        .fold(0.0, f64::max);
    assert!(
        (after(verdict, "α_cr ") - alpha).abs() <= 0.005,
        "{verdict}"
    );
    assert!(
        (after(verdict, "utilisation ") - utilisation).abs() <= 0.005,
        "{verdict}"
    );
    assert!(
        (after(verdict, "deflection ") - deflection).abs() <= 0.05,
        "{verdict}"
    );
    // The limit: span/300, the span the largest plan distance between two
    // supports.
    let at: Vec<[f64; 2]> = st["reactions"]
        .as_array()
        .expect("reactions")
        .iter()
        .map(|r| [num(&r["position_mm"][0]), num(&r["position_mm"][1])])
        .collect();
    let mut span: f64 = 0.0;
    for a in &at {
        for b in &at {
            span = span.max((a[0] - b[0]).hypot(a[1] - b[1]));
        }
    }
    let limit = after(&verdict.replace('≤', ">"), "mm > ");
    assert!(
        (limit - span / 300.0).abs() <= 0.05,
        "{verdict}: span {span}"
    );
    let passes = alpha > 1.0 && utilisation <= 1.0 && deflection <= span / 300.0;
    assert_eq!(st["passes"].as_bool(), Some(passes), "{verdict}");
    assert!(verdict.starts_with(if passes {
        "structure PASS"
    } else {
        "structure FAIL"
    }));
    // Every combination: the supports' reactions, summed from the reaction
    // table, balance its loads.
    let reactions = st["reactions"].as_array().expect("reactions");
    for (k, c) in combos.iter().enumerate() {
        for axis in 0..3 {
            let sum: f64 = reactions.iter().map(|r| num(&r["forces_n"][k][axis])).sum();
            let load = num(&c["load_sum_n"][axis]);
            let scale = (0..3).map(|i| num(&c["load_sum_n"][i]).abs()).sum::<f64>();
            // The table's forces are rounded to 1e-3 N each.
            let tol = 1e-6 * scale + 1e-3 * reactions.len() as f64;
            assert!(
                (sum + load).abs() <= tol,
                "{} axis {axis}: reactions {sum} loads {load}",
                c["name"]
            );
        }
    }
}

/// The structure folder's files: the script compiles, the JSON is the
/// model the plan counts.
fn model_files_are_readable(dir: &Path, st: &Value) {
    let script = dir.join("structure/opensees.py");
    // Parsed, not compiled: py_compile would leave a __pycache__ beside it.
    let compiled = Command::new("python3")
        .args(["-c", "import ast, sys; ast.parse(open(sys.argv[1]).read())"])
        .arg(&script)
        .status()
        .expect("python3");
    assert!(compiled.success(), "{} compiles", script.display());
    let text = std::fs::read_to_string(dir.join("structure/model.json")).expect("model.json");
    assert!(
        text.starts_with("{\n  \"$schema\": \"lamella-frame-model/1\""),
        "{}",
        &text[..80]
    );
    let model: Value = serde_json::from_str(&text).expect("model.json parses");
    assert_eq!(
        model["nodes_mm"].as_array().map(Vec::len),
        st["model"]["nodes"].as_u64().map(|n| n as usize)
    );
    assert_eq!(
        model["beams"].as_array().map(Vec::len),
        st["model"]["beams"].as_u64().map(|n| n as usize)
    );
    // Every characteristic case and every combination is a load set.
    let sets = model["load_sets"].as_array().expect("load_sets").len();
    let want = st["load_cases"].as_array().map_or(0, Vec::len)
        + st["combinations"].as_array().map_or(0, Vec::len);
    assert_eq!(sets, want);
}

#[test]
fn frame_on_the_enneper_pavilion_prints_the_plans_verdict_and_exits_3() {
    let dir = scratch("enneper");
    let (code, stdout, stderr) = lamella(&[
        "frame",
        "samples/enneper-4m.yaml",
        "--profile",
        "profiles/steel-1.5.yaml",
        "--loads",
        "samples/loads/pavilion.yaml",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let verdict = stdout
        .lines()
        .find(|l| l.starts_with("structure "))
        .unwrap_or_else(|| panic!("no verdict in {stdout}\n{stderr}"));
    let plan = plan_of(&dir);
    let st = &plan["structure"];
    assert_eq!(st["verdict"].as_str(), Some(verdict));
    verdict_is_the_plans(verdict, st);
    // 1.5 mm steel does not carry a lowland snow load over 4 m.
    assert_eq!(st["passes"].as_bool(), Some(false));
    assert_eq!(code, Some(3), "{stdout}{stderr}");
    model_files_are_readable(&dir, st);
    // The network's strips and nodes are there too.
    assert_eq!(
        plan["strips"].as_array().map(Vec::len),
        plan["summary"]["curves"].as_u64().map(|n| n as usize)
    );
}

#[test]
fn build_with_loads_stops_when_the_grid_does_not_stand_and_writes_it_all_when_allowed() {
    let dir = scratch("build");
    let out = dir.join("kit");
    let loads = ["--loads", "samples/loads/pavilion.yaml"];
    let o = build("hypar-small", "poplar-ply-4", &out, &loads);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(3), "{stderr}");
    assert!(!out.exists(), "nothing written");
    let line = stderr
        .lines()
        .find(|l| l.starts_with("error: the grid does not stand: structure FAIL"))
        .unwrap_or_else(|| panic!("{stderr}"));
    assert!(line.contains("--allow-overstress"), "{line}");

    let o = build(
        "hypar-small",
        "poplar-ply-4",
        &out,
        &[loads[0], loads[1], "--allow-overstress", "-q"],
    );
    assert_eq!(o.status.code(), Some(0));
    let plan = plan_of(&out);
    let st = &plan["structure"];
    let verdict = st["verdict"].as_str().expect("verdict");
    assert!(line.ends_with(&format!(
        "{verdict}: nothing written; see `lamella frame`, or pass --allow-overstress"
    )));
    verdict_is_the_plans(verdict, st);
    model_files_are_readable(&out, st);
    let manifest = std::fs::read_to_string(out.join(".lamella-manifest")).expect("manifest");
    for f in ["structure/opensees.py", "structure/model.json"] {
        assert!(
            manifest.lines().any(|l| l.ends_with(f)),
            "{f} in the manifest"
        );
    }

    structure_pages_are_the_plans(&out, st);

    // `lamella frame` is the same stage: the same section, byte for byte.
    let alone = dir.join("frame");
    let (code, _, _) = lamella(&[
        "frame",
        "samples/hypar-small.yaml",
        "--profile",
        "profiles/poplar-ply-4.yaml",
        "--loads",
        "samples/loads/pavilion.yaml",
        "--out",
        alone.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(3));
    assert_eq!(plan_of(&alone)["structure"], *st);
    for f in ["structure/opensees.py", "structure/model.json"] {
        assert_eq!(
            std::fs::read(alone.join(f)).unwrap(),
            std::fs::read(out.join(f)).unwrap(),
            "{f}"
        );
    }

    // A build without loads takes the old model's files away with the old kit.
    let o = build("hypar-small", "poplar-ply-4", &out, &["-q"]);
    assert_eq!(o.status.code(), Some(0));
    assert!(!out.join("structure").exists());
    assert!(plan_of(&out).get("structure").is_none_or(Value::is_null));
}

/// assembly.pdf's structure section, read back by pypdf: its five kinds of
/// page, the verdict as in the plan (Greek spelt out), and a row per
/// support with the governing combination's Rz from the plan.
fn structure_pages_are_the_plans(dir: &Path, st: &Value) {
    let Some(pdf) = crate::support::tools::read_pdf(&dir.join("assembly.pdf")) else {
        return;
    };
    let texts: Vec<String> = pdf["page"]
        .as_array()
        .expect("pages")
        .iter()
        .map(|p| p["text"].as_str().unwrap_or_default().to_string())
        .collect();
    let first = |heading: &str| {
        texts
            .iter()
            .position(|t| t.contains(heading))
            .unwrap_or_else(|| panic!("no page \"{heading}\""))
    };
    let summary = first("Structure: supports, loads and verdict");
    let deformed = first("Structure: deformed shape under SLS");
    let utilisation = first("Structure: utilisation of every lamella");
    let mode = first("Structure: first buckling mode under ULS");
    let reactions = first("Structure: reactions on the supports");
    assert!(summary < deformed && deformed < utilisation && utilisation < mode);
    assert!(mode < reactions && reactions >= texts.len() - 3);
    // The cover lists the section.
    assert!(texts[0].contains("Structure"), "{}", texts[0]);
    let verdict = st["verdict"]
        .as_str()
        .unwrap()
        .replace("α", "alpha")
        .replace("≤", "<=");
    assert!(texts[summary].contains(&verdict), "{verdict}");
    let limit = format!("limit of {:.1} mm", num(&st["deflection_limit_mm"]));
    assert!(texts[deformed].contains(&limit), "{limit}");
    let alpha = format!("alpha_cr = {:.2}", num(&st["alpha_cr"]["factor"]));
    assert!(texts[mode].contains(&alpha), "{alpha}");
    let g = &st["governing"];
    assert!(texts[utilisation].contains(&format!(
        "governing: strip {} lamella {}",
        g["strip"].as_str().unwrap(),
        g["lamella"]
    )));
    let combos = st["combinations"].as_array().unwrap();
    let k = combos
        .iter()
        .position(|c| c["name"] == g["combination"])
        .expect("the governing combination");
    let rows: Vec<&str> = texts[reactions..].iter().flat_map(|t| t.lines()).collect();
    for r in st["reactions"].as_array().unwrap() {
        let start = format!(
            "{} {} ",
            r["node"].as_str().unwrap(),
            r["kind"].as_str().unwrap()
        );
        let row = rows
            .iter()
            .find(|l| l.starts_with(&start))
            .unwrap_or_else(|| panic!("no row {start}"));
        let rz = format!("{:.2}", num(&r["forces_n"][k][2]) / 1000.0);
        let rz = rz.trim_start_matches("-0.00").to_string();
        let cells: Vec<&str> = row.split_whitespace().collect();
        assert!(
            cells[7] == rz || (rz.is_empty() && cells[7] == "0.00"),
            "{row}: Rz {rz}"
        );
    }
}

fn frame_with(loads_text: &str, name: &str) -> (Option<i32>, String, String, std::path::PathBuf) {
    let dir = scratch(name);
    let loads = dir.join("loads.yaml");
    std::fs::write(&loads, loads_text).unwrap();
    let out = dir.join("out");
    let (code, stdout, stderr) = lamella(&[
        "frame",
        "samples/hypar-small.yaml",
        "--profile",
        "profiles/poplar-ply-4.yaml",
        "--loads",
        loads.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    (code, stdout, stderr, out)
}

const CASES: &str =
    "version: 1\ncases:\n  - name: G\n    action: permanent\n    self_weight: 1.0\n";

#[test]
fn a_bad_loads_file_is_one_line_naming_the_field_and_nothing_is_written() {
    let text = format!("{CASES}supports:\n  - at: boundary\n    kind: hinged\n");
    let (code, stdout, stderr, out) = frame_with(&text, "bad");
    assert_eq!(code, Some(1), "{stdout}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("loads.yaml") && stderr.contains("supports[0]"),
        "{stderr}"
    );
    assert!(!out.exists());
}

#[test]
fn a_grid_held_at_one_node_is_a_mechanism_named_by_its_node() {
    let text = format!("{CASES}supports:\n  - at: lowest\n    band_mm: 0\n    kind: pinned\n");
    let (code, stdout, stderr, out) = frame_with(&text, "mechanism");
    assert_eq!(code, Some(1), "{stdout}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("mechanism under its supports") && stderr.contains("moves freely"),
        "{stderr}"
    );
    assert!(!out.exists());
}
