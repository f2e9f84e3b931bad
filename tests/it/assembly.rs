//! The assembly sheets, `DIR/assembly.pdf`, read back by an
//! independent reader (pypdf, `tests/tools/pdf_text.py`): every strip id
//! and every node of the schedule on its pages, the page count the kit
//! implies — recomputed here from plan.json and the layout rules the
//! README states — "page i of N" on every page, the paper size, and
//! byte-identical rebuilds. Without pypdf the reading is skipped (CI
//! installs it and sets LAMELLA_REQUIRE_PYPDF).

use crate::support::tools::{lines, read_pdf, read_runs};
use crate::support::{build, lamella_command, ok, root, scratch};
use serde_json::Value;
use std::collections::HashMap;
use std::path::Path;
use std::process::Output;

/// `lamella build … --quiet`: the tests read the files, not the progress.
fn build_quiet(sample: &str, profile: &str, out: &Path, extra: &[&str]) -> Output {
    build(sample, profile, out, &[&["--quiet"], extra].concat())
}

/// The layout rules of the README's "Assembly sheets", written out again.
struct Rules {
    content_w: f64,
    content_h: f64,
}

impl Rules {
    fn new(paper: &str) -> Rules {
        let (w, h) = match paper {
            "a3" => (420.0, 297.0),
            _ => (297.0, 210.0),
        };
        // 10 mm margins, an 8 mm heading, a 10 mm title block + 2 mm.
        Rules {
            content_w: w - 20.0,
            content_h: h - 10.0 - 8.0 - 22.0,
        }
    }

    /// Pages of a table `width` mm wide with `n` rows: blocks side by side
    /// 8 mm apart, a 6 mm header, 4.5 mm rows.
    fn table(&self, width: f64, n: usize) -> usize {
        let blocks = (((self.content_w + 8.0) / (width + 8.0)).floor() as usize).max(1);
        let rows = ((self.content_h - 6.0) / 4.5).floor() as usize;
        n.div_ceil(blocks * rows).max(1)
    }

    /// Strip-sheet pages: scale, rows per lamella, strips flowing down pages.
    fn strips(&self, plan: &Value) -> usize {
        let height = plan["profile"]["height_mm"].as_f64().expect("height");
        let d = [20.0, 10.0, 5.0, 2.0, 1.0]
            .into_iter()
            .find(|d| height / d >= 4.0)
            .unwrap_or(1.0);
        let row_len = (self.content_w - 28.0) * d;
        let row_h = 20.0 + height / d + 9.0;
        let head = 6.0;
        let per_page = ((self.content_h - head) / row_h).floor() as usize;
        // Lamella spans by strip.
        let mut spans: HashMap<(String, u64), (f64, f64)> = HashMap::new();
        for p in plan["parts"].as_array().expect("parts") {
            if p["kind"] != "lamella" {
                continue;
            }
            let key = (
                p["strip"].as_str().expect("strip").to_string(),
                p["lamella"].as_u64().expect("lamella"),
            );
            let s0 = p["station_start_mm"].as_f64().expect("start");
            let s1 = s0 + p["length_mm"].as_f64().expect("length");
            let e = spans
                .entry(key)
                .or_insert((f64::INFINITY, f64::NEG_INFINITY));
            *e = (e.0.min(s0), e.1.max(s1));
        }
        let (mut pages, mut left) = (0usize, 0.0f64);
        for s in plan["strips"].as_array().expect("strips") {
            let id = s["id"].as_str().expect("id");
            let rows: usize = (1..=2)
                .filter_map(|n| spans.get(&(id.to_string(), n)))
                .map(|(a, b)| (((b - a) / row_len).ceil() as usize).max(1))
                .sum();
            if rows == 0 {
                continue;
            }
            let need = head + rows as f64 * row_h;
            if pages == 0 || (need > left + 1e-9 && left < self.content_h) {
                pages += 1;
                left = self.content_h;
            }
            let mut rest = rows;
            while rest > 0 {
                let chunk = rest.min(per_page);
                let need = head + chunk as f64 * row_h;
                if need > left + 1e-9 && left < self.content_h {
                    pages += 1;
                    left = self.content_h;
                }
                left -= need;
                rest -= chunk;
            }
        }
        pages
    }
}

/// The joint sections: one page, when the kit has a bolted joint (a bolt
/// line in the hardware) or halving slots (an interlocking grid), and one
/// for the edge joint when lamellas end on edge bands.
fn joint_sections(plan: &Value) -> usize {
    let bolts = plan["parts_summary"]["hardware"]
        .as_array()
        .is_some_and(|h| {
            h.iter()
                .any(|l| l["item"].as_str().is_some_and(|i| i.ends_with("bolt")))
        });
    // The edge joint on a page of its own, where lamellas end on bands.
    let edge = plan["parts"].as_array().is_some_and(|parts| {
        parts
            .iter()
            .flat_map(|p| p["features"].as_array().into_iter().flatten())
            .any(|f| f["edge"] == "end")
    });
    usize::from(bolts || plan["profile"]["joint_system"] == "interlocking") + usize::from(edge)
}

/// The standard scales 1, 2, 2.5, 5 × 10^k (whole numbers), ascending.
fn standard_scales() -> Vec<f64> {
    let mut v = Vec::new();
    for k in 0..9 {
        for m in [1.0, 2.0, 2.5, 5.0] {
            let s: f64 = m * 10f64.powi(k);
            if s.fract() == 0.0 {
                v.push(s);
            }
        }
    }
    v
}

impl Rules {
    /// Node plan pages: the view (content less an 8 mm key, inset 6 mm),
    /// the scale that fits the nodes' plan extent, or finer while the
    /// 10th-percentile node spacing is under 8 mm on paper (at most 12
    /// tiles); tiles centred on the extent, those without a node left out.
    fn node_plan(&self, plan: &Value) -> usize {
        let nodes: Vec<[f64; 2]> = plan["nodes"]
            .as_array()
            .expect("nodes")
            .iter()
            .map(|n| {
                let p = &n["position_mm"];
                [p[0].as_f64().expect("x"), p[1].as_f64().expect("y")]
            })
            .collect();
        if nodes.is_empty() {
            return 0;
        }
        let lo = [0, 1].map(|k| nodes.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min));
        let hi = [0, 1].map(|k| nodes.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max));
        let ext = [(hi[0] - lo[0]).max(1.0), (hi[1] - lo[1]).max(1.0)];
        let view = [self.content_w - 12.0, self.content_h - 8.0 - 12.0];
        let series = standard_scales();
        let den = (ext[0] / view[0]).max(ext[1] / view[1]);
        let fit = *series.iter().find(|&&s| s >= den - 1e-9).expect("scale");
        let mut gaps: Vec<f64> = plan["strips"]
            .as_array()
            .expect("strips")
            .iter()
            .flat_map(|s| s["node_to_node_mm"].as_array().expect("gaps").clone())
            .map(|v| v.as_f64().expect("gap"))
            .filter(|v| *v > 0.0)
            .collect();
        gaps.sort_by(f64::total_cmp);
        let read = gaps.get((gaps.len().max(1) - 1) / 10).map_or(fit, |g| {
            *series.iter().rev().find(|&&s| s <= g / 8.0).unwrap_or(&1.0)
        });
        let mut scale = read.min(fit);
        let tiles = |s: f64| {
            (
                ((ext[0] / (view[0] * s)) - 1e-9).ceil().max(1.0) as usize,
                ((ext[1] / (view[1] * s)) - 1e-9).ceil().max(1.0) as usize,
            )
        };
        while tiles(scale).0 * tiles(scale).1 > 12 && scale < fit {
            scale = *series.iter().find(|&&s| s > scale).expect("coarser");
        }
        let (cols, rows) = tiles(scale);
        let tile = [view[0] * scale, view[1] * scale];
        let origin = [
            lo[0] - 0.5 * (cols as f64 * tile[0] - ext[0]),
            lo[1] - 0.5 * (rows as f64 * tile[1] - ext[1]),
        ];
        let mut pages = 0;
        for r in 0..rows {
            for c in 0..cols {
                let (x0, y0) = (
                    origin[0] + c as f64 * tile[0],
                    origin[1] + r as f64 * tile[1],
                );
                let last = |i: usize, n: usize| if i + 1 == n { 1e-6 } else { 0.0 };
                if nodes.iter().any(|p| {
                    p[0] >= x0 - 1e-9
                        && p[0] < x0 + tile[0] + last(c, cols)
                        && p[1] >= y0 - 1e-9
                        && p[1] < y0 + tile[1] + last(r, rows)
                }) {
                    pages += 1;
                }
            }
        }
        pages
    }
}

/// The page count plan.json and the takeoff imply.
fn expected_pages(plan: &Value, paper: &str) -> usize {
    let r = Rules::new(paper);
    let strips = plan["strips"].as_array().expect("strips");
    let two_level = plan["profile"]["joint_system"] == "two_level";
    let parts = plan["parts"].as_array().expect("parts");
    let blocks = parts
        .iter()
        .filter(|p| p["kind"] == "lamella" && p["lamella"] == 1)
        .flat_map(|p| p["features"].as_array().expect("features"))
        .filter(|f| f["hole_use"] == "shear_block")
        .count();
    let checked = strips.iter().filter(|s| s.get("check").is_some()).count();
    let cover = 1;
    let overview = 1 + r.node_plan(plan);
    let setting_out = r.table(144.0, plan["nodes"].as_array().expect("nodes").len());
    // The order table, and one flat layout page when the flat state was
    // computed (`--slots-from-flat`).
    let order = r.table(108.0, strips.len() + usize::from(two_level))
        + usize::from(plan.get("flat").is_some());
    let strip_pages = r.strips(plan);
    // Per node: its id; per strip its id, and per lamella the piece and
    // the station on it; the angle and the joint.
    let lamellas = plan["profile"]["lamellas_per_strip"]
        .as_f64()
        .unwrap_or(1.0);
    let node_w = 12.0 + 2.0 * (14.0 + lamellas * (18.0 + 11.0)) + 14.0 + 16.0;
    let nodes = r.table(node_w, plan["nodes"].as_array().expect("nodes").len());
    let block_pages = if blocks == 0 {
        0
    } else {
        r.table(88.0, blocks)
    };
    let takeoff = 1;
    let sheets = plan["sheets"].as_array().expect("sheets").len();
    let check = r.table(169.0, checked);
    cover
        + overview
        + order
        + joint_sections(plan)
        + strip_pages
        + nodes
        + setting_out
        + block_pages
        + takeoff
        + sheets
        + check
}

fn check_kit(sample: &str, profile: &str, paper: &str) {
    let out = scratch(&format!("{sample}-{paper}"));
    ok(&build_quiet(sample, profile, &out, &["--paper", paper]));
    let pdf = out.join("assembly.pdf");
    let bytes = std::fs::read(&pdf).expect("assembly.pdf written");
    assert!(bytes.starts_with(b"%PDF-"), "a PDF");
    let manifest = std::fs::read_to_string(out.join(".lamella-manifest")).expect("manifest");
    let pdf_bytes = std::fs::metadata(&pdf).expect("pdf").len();
    assert!(
        manifest
            .lines()
            .any(|l| l.starts_with(&format!("{pdf_bytes} ")) && l.ends_with(" assembly.pdf")),
        "{manifest}"
    );
    let plan: Value = serde_json::from_slice(&std::fs::read(out.join("plan.json")).expect("plan"))
        .expect("plan json");
    let expected = expected_pages(&plan, paper);
    let Some(doc) = read_pdf(&pdf) else {
        return;
    };
    let pages = doc["page"].as_array().expect("pages");
    assert_eq!(
        doc["pages"].as_u64(),
        Some(expected as u64),
        "{sample} on {paper}"
    );
    let (w, h) = if paper == "a3" {
        (420.0, 297.0)
    } else {
        (297.0, 210.0)
    };
    let texts: Vec<String> = pages
        .iter()
        .map(|p| p["text"].as_str().expect("text").to_string())
        .collect();
    for (i, p) in pages.iter().enumerate() {
        assert!((p["width_mm"].as_f64().expect("w") - w).abs() < 0.5);
        assert!((p["height_mm"].as_f64().expect("h") - h).abs() < 0.5);
        let title = format!("page {} of {expected}", i + 1);
        assert!(texts[i].contains(&title), "page {}: no '{title}'", i + 1);
        assert!(texts[i].contains(plan["network"]["name"].as_str().expect("name")));
        assert!(texts[i].contains("scale 1:") || texts[i].contains("not to scale"));
    }
    // The cover's legend fits the joint system: slots only where there are.
    let two_level = plan["profile"]["joint_system"] == "two_level";
    assert_eq!(
        texts[0].contains("slot"),
        !two_level,
        "{sample}: the cover's legend and the joint system"
    );
    // Every strip id as a word somewhere; A and B strips on a strip sheet.
    let words = |t: &str| -> Vec<String> {
        t.split(|c: char| c.is_whitespace() || c == ',' || c == '(' || c == ')')
            .map(str::to_string)
            .collect()
    };
    let all: std::collections::HashSet<String> = texts.iter().flat_map(|t| words(t)).collect();
    let strip_text: String = texts
        .iter()
        .filter(|t| t.contains("Strip sheets"))
        .cloned()
        .collect();
    for s in plan["strips"].as_array().expect("strips") {
        let id = s["id"].as_str().expect("id");
        assert!(all.contains(id), "strip {id} is on no page");
        if s["family"] != "edge" {
            assert!(
                strip_text.contains(&format!("Strip {id} (family")),
                "strip {id} has no strip sheet"
            );
        }
    }
    // Every node in the schedule: its id, then its first strip.
    let schedule: String = texts
        .iter()
        .filter(|t| t.contains("Node schedule"))
        .cloned()
        .collect::<Vec<_>>()
        .join("\n");
    let cells: Vec<String> = words(&schedule)
        .into_iter()
        .filter(|w| !w.is_empty())
        .collect();
    let mut found = std::collections::HashSet::new();
    for pair in cells.windows(2) {
        if let Ok(id) = pair[0].parse::<u64>() {
            found.insert((id, pair[1].clone()));
        }
    }
    for n in plan["nodes"].as_array().expect("nodes") {
        let id = n["id"].as_u64().expect("id");
        let a = n["a"].as_str().expect("a").to_string();
        assert!(
            found.contains(&(id, a.clone())),
            "node {id} ({a}) not in the schedule"
        );
    }
}

#[test]
fn interlocking_kit_on_a3() {
    check_kit("enneper-4m", "steel-1.5", "a3");
}

#[test]
fn two_level_kit_on_a4() {
    check_kit("hypar-small", "poplar-ply-4", "a4");
}

#[test]
fn same_input_same_bytes() {
    let (a, b) = (scratch("same-a"), scratch("same-b"));
    ok(&build_quiet("hypar-small", "steel-1.5", &a, &[]));
    // Another time zone and another process: nothing may leak in.
    let network = "samples/hypar-small.yaml";
    let out_s = b.to_string_lossy().into_owned();
    let o = lamella_command()
        .args([
            "build",
            network,
            "--profile",
            "profiles/steel-1.5.yaml",
            "--out",
            &out_s,
            "--quiet",
        ])
        .env("TZ", "Asia/Kathmandu")
        .output()
        .expect("run");
    ok(&o);
    let pa = std::fs::read(a.join("assembly.pdf")).expect("a");
    let pb = std::fs::read(b.join("assembly.pdf")).expect("b");
    assert!(pa == pb, "assembly.pdf differs between identical builds");
}

#[test]
fn unknown_paper_is_a_usage_error() {
    let out = scratch("paper");
    let o = build_quiet("hypar-small", "steel-1.5", &out, &["--paper", "letter"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("letter"), "{err}");
    assert!(!err.contains("panicked"));
}

/// A plan without parts (not a built kit) is a one-line error, not a panic.
#[test]
fn a_plan_without_parts_is_an_error() {
    let out = scratch("noparts");
    ok(&build_quiet("hypar-small", "steel-1.5", &out, &[]));
    let mut plan: lamella::plan::Plan =
        serde_json::from_slice(&std::fs::read(out.join("plan.json")).expect("plan")).expect("plan");
    plan.parts = None;
    plan.takeoff = Some(lamella::plan::takeoff::Takeoff {
        project: "x".into(),
        profile: "y".into(),
        currency: None,
        parts: vec![],
        stock: vec![],
        hardware: vec![],
        bracing: vec![],
        totals: lamella::plan::takeoff::Totals {
            pieces: 0,
            lamella_length_m: 0.0,
            mass_kg: 0.0,
            sheets: 0,
            stock_cost: None,
            ..Default::default()
        },
    });
    let e = lamella::formats::write::assembly::assembly_pdf(
        &lamella::formats::write::assembly::AssemblyInput {
            plan: &plan,
            paper: lamella::formats::write::assembly::Paper::A4,
            plan_path: Path::new("plan.json"),
        },
    )
    .expect_err("no parts");
    let msg = e.to_string();
    assert!(!msg.contains('\n') && msg.contains("parts"), "{msg}");
}

/// With the flat state computed, the assembly order gains the flat layout
/// page: its heading states the footprint and the largest rotation, and
/// every A×B node's id is on it.
#[test]
fn flat_layout_page_when_the_flat_state_is_computed() {
    let out = scratch("flat-layout");
    ok(&build_quiet(
        "enneper-4m",
        "steel-1.5",
        &out,
        &["--slots-from-flat"],
    ));
    let plan: Value =
        serde_json::from_slice(&std::fs::read(out.join("plan.json")).expect("plan")).expect("json");
    let flat = &plan["flat"];
    let Some(pdf) = read_pdf(&out.join("assembly.pdf")) else {
        return;
    };
    assert_eq!(
        pdf["pages"].as_u64(),
        Some(expected_pages(&plan, "a3") as u64)
    );
    let page = pdf["page"]
        .as_array()
        .expect("pages")
        .iter()
        .find(|p| {
            p["text"]
                .as_str()
                .is_some_and(|t| t.contains("Flat assembly layout"))
        })
        .expect("a flat layout page");
    let text = page["text"].as_str().expect("text");
    let max_rot = flat["max_rotation_deg"].as_f64().expect("max");
    assert!(text.contains(&format!("up to {max_rot:.1} deg")), "{text}");
    for n in flat["nodes"].as_array().expect("nodes") {
        let label = format!(
            "{} {:+.1}",
            n["node"],
            n["rotation_deg"].as_f64().expect("rot")
        );
        assert!(text.contains(&label), "node label {label} missing");
    }
}

/// A printed whole number of millimetres (`1 216`).
fn printed_mm(s: &str) -> Option<f64> {
    s.chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .parse()
        .ok()
}

/// The text runs of the pages whose title block names `section`.
fn section_runs<'a>(doc: &'a Value, section: &str) -> Vec<Vec<&'a Value>> {
    doc["page"]
        .as_array()
        .expect("pages")
        .iter()
        .map(|p| {
            p["runs"]
                .as_array()
                .expect("runs")
                .iter()
                .collect::<Vec<_>>()
        })
        .filter(|runs| {
            runs.iter().any(|r| {
                r["text"]
                    .as_str()
                    .is_some_and(|t| t.starts_with(&format!("{section}  |")))
            })
        })
        .collect()
}

/// Table rows of a page: runs on one baseline, left to right, cut into
/// rows after each angle cell (`90.0°`) and the joint cell that follows it.
fn schedule_rows(runs: &[&Value]) -> Vec<Vec<String>> {
    let mut rows = Vec::new();
    for cells in lines(
        runs.iter()
            .copied()
            .filter(|r| r["rot_deg"].as_f64() == Some(0.0)),
    ) {
        let mut row: Vec<String> = Vec::new();
        let mut after_angle = false;
        for (_, t) in cells {
            let angle = t.ends_with('°');
            row.push(t);
            if after_angle {
                rows.push(std::mem::take(&mut row));
            }
            after_angle = angle;
        }
        if !row.is_empty() {
            rows.push(row);
        }
    }
    rows
}

/// One datum: every slot's station, as its strip sheet and the node
/// schedule print it, is its distance from its piece's cut start end —
/// the slot's x in the part (plan.json's outline frame, x = 0 at the
/// start end), not its station on the curve; every shear-block bolt's on
/// the shear-block page likewise; and plan.json's feature stations are
/// those distances, with the line's station beside them.
#[test]
fn every_station_from_the_pieces_start_end() {
    let out = scratch("datum");
    ok(&build_quiet("enneper-4m", "steel-1.5", &out, &[]));
    let plan: Value =
        serde_json::from_slice(&std::fs::read(out.join("plan.json")).expect("plan")).expect("json");
    // (lamella name, crossing) → slot x; (node, piece) → slot x; piece → block x.
    let mut slots: Vec<(String, String, usize, String, f64)> = Vec::new();
    let mut blocks: Vec<(String, f64)> = Vec::new();
    for p in plan["parts"].as_array().expect("parts") {
        if p["kind"] != "lamella" {
            continue;
        }
        let id = p["id"].as_str().expect("id").to_string();
        let name = format!("{}-{}", p["strip"].as_str().expect("strip"), p["lamella"]);
        let start = p["station_start_mm"].as_f64().expect("start");
        for f in p["features"].as_array().expect("features") {
            let x = f["center_mm"][0].as_f64().expect("x");
            let st = f["station_mm"].as_f64().expect("station");
            let line = f["line_station_mm"].as_f64().expect("line station");
            assert!((st - x).abs() < 1e-3, "{id}: station {st} at x {x}");
            assert!((line - (start + x)).abs() < 2e-3, "{id}: line {line}");
            if f["kind"] == "slot" {
                let cross = f["crossing"].as_str().expect("crossing").to_string();
                let node = f["node"].as_u64().expect("node") as usize;
                slots.push((name.clone(), cross, node, id.clone(), x));
            } else if f["hole_use"] == "shear_block" {
                blocks.push((id.clone(), x));
            }
        }
    }
    assert!(slots.len() > 200 && !blocks.is_empty());
    assert!(
        slots.iter().any(|s| s.3.ends_with(".2")),
        "the sample has spliced lamellas"
    );
    let Some(doc) = read_runs(&out.join("assembly.pdf")) else {
        return;
    };
    // Strip sheets: the upright station under each upright crossing id,
    // on the row of the lamella named left of it (just below).
    let mut sheet: HashMap<(String, String), Vec<f64>> = HashMap::new();
    for runs in section_runs(&doc, "Strip sheets") {
        let f = |r: &Value, k: &str| r[k].as_f64().expect(k);
        let names: Vec<&&Value> = runs
            .iter()
            .filter(|r| r["bold"] == true && f(r, "size_pt") == 10.0 && f(r, "rot_deg") == 0.0)
            .collect();
        let upright: Vec<&&Value> = runs
            .iter()
            .filter(|r| (f(r, "rot_deg") - 90.0).abs() < 1e-6)
            .collect();
        for st in upright.iter().filter(|r| r["bold"] == false) {
            let Some(id) = upright.iter().find(|r| {
                r["bold"] == true
                    && (f(r, "x_mm") - f(st, "x_mm")).abs() < 0.05
                    && f(r, "y_mm") > f(st, "y_mm")
                    && f(r, "y_mm") < f(st, "y_mm") + 20.0
            }) else {
                continue;
            };
            let row = names
                .iter()
                .filter(|n| f(n, "y_mm") <= f(st, "y_mm"))
                .max_by(|a, b| f(a, "y_mm").total_cmp(&f(b, "y_mm")))
                .expect("a lamella row");
            sheet
                .entry((
                    row["text"].as_str().expect("t").to_string(),
                    id["text"].as_str().expect("t").to_string(),
                ))
                .or_default()
                .push(printed_mm(st["text"].as_str().expect("t")).expect("a station"));
        }
    }
    // The node schedule: (node, piece) → the station printed after the piece.
    let mut schedule: HashMap<(usize, String), f64> = HashMap::new();
    for runs in section_runs(&doc, "Node schedule") {
        for row in schedule_rows(&runs) {
            let Ok(node) = row[0].parse::<usize>() else {
                continue;
            };
            for w in row.windows(2) {
                if let Some(v) = printed_mm(&w[1]).filter(|_| w[0].contains('.')) {
                    schedule.insert((node, w[0].clone()), v);
                }
            }
        }
    }
    for (name, cross, node, piece, x) in &slots {
        let printed = sheet
            .get(&(name.clone(), cross.clone()))
            .unwrap_or_else(|| panic!("{name} × {cross}: no station on its strip sheet"));
        assert!(
            printed.iter().any(|v| (v - x).abs() <= 0.5 + 1e-6),
            "{piece} × {cross}: strip sheet prints {printed:?}, the slot is at x = {x}"
        );
        let v = schedule
            .get(&(*node, piece.clone()))
            .unwrap_or_else(|| panic!("node {node}: {piece} not in the schedule"));
        assert!(
            (v - x).abs() <= 0.5 + 1e-6,
            "node {node} on {piece}: schedule {v}, x = {x}"
        );
    }
    // The shear blocks: each bolt's piece and the station printed after it.
    let mut printed: HashMap<String, Vec<f64>> = HashMap::new();
    for runs in section_runs(&doc, "Shear blocks") {
        for cells in lines(runs.iter().copied()) {
            for w in cells.windows(2) {
                if let Some(v) = printed_mm(&w[1].1).filter(|_| w[0].1.contains('.')) {
                    printed.entry(w[0].1.clone()).or_default().push(v);
                }
            }
        }
    }
    for (piece, x) in &blocks {
        let v = printed.get(piece).map(Vec::as_slice).unwrap_or_default();
        assert!(
            v.iter().any(|v| (v - x).abs() <= 0.5 + 1e-6),
            "shear block on {piece} at x = {x}: page prints {v:?}"
        );
    }
}

/// The text boxes of runs (level or turned a quarter left), mm: x0, y0,
/// x1, y1, with Helvetica's descender below the baseline and its cap
/// height above.
fn run_boxes<'a>(runs: &[&'a Value]) -> Vec<([f64; 4], &'a str)> {
    runs.iter()
        .filter_map(|r| {
            let f = |k: &str| r[k].as_f64().expect(k);
            let size_mm = f("size_pt") * 25.4 / 72.0;
            let (x, y, w) = (f("x_mm"), f("y_mm"), f("width_mm"));
            let (down, up) = (0.21 * size_mm, 0.72 * size_mm);
            let rot = f("rot_deg");
            let b = if rot.abs() < 1e-6 {
                [x, y - down, x + w, y + up]
            } else if (rot - 90.0).abs() < 1e-6 {
                [x - up, y, x + down, y + w]
            } else {
                return None;
            };
            Some((b, r["text"].as_str().expect("text")))
        })
        .collect()
}

/// No two labels of the overview, the node plan and the nested sheets
/// overprint (their text boxes, from the drawn page as pypdf reads it, are
/// disjoint), on the pavilion, whose strips crowd where the surface's
/// saddles meet, and on enneper, whose star washers interleave; and the
/// node plan names every node.
#[test]
fn labels_never_overprint() {
    for (sample, profile) in [
        ("schwarz-d-pavilion", "steel-1.5"),
        ("enneper-4m", "steel-1.5"),
    ] {
        let out = scratch(&format!("labels-{sample}"));
        ok(&build_quiet(sample, profile, &out, &["--allow-overstress"]));
        let plan: Value =
            serde_json::from_slice(&std::fs::read(out.join("plan.json")).expect("plan"))
                .expect("json");
        let Some(doc) = read_runs(&out.join("assembly.pdf")) else {
            return;
        };
        let pages = section_runs(&doc, "Overview");
        assert!(pages.len() >= 2, "{sample}: an overview and a node plan");
        let nested = section_runs(&doc, "Sheets as nested");
        assert!(!nested.is_empty());
        for runs in &nested {
            let boxes = run_boxes(runs);
            for (i, (a, ta)) in boxes.iter().enumerate() {
                for (b, tb) in &boxes[i + 1..] {
                    let (ox, oy) = (
                        a[2].min(b[2]) - a[0].max(b[0]),
                        a[3].min(b[3]) - a[1].max(b[1]),
                    );
                    assert!(
                        ox <= 0.05 || oy <= 0.05,
                        "{sample}, a nested sheet: '{ta}' at {a:?} overprints '{tb}' at {b:?}"
                    );
                }
            }
        }
        let mut ids = std::collections::HashSet::new();
        for runs in &pages {
            let boxes = run_boxes(runs);
            for (i, (a, ta)) in boxes.iter().enumerate() {
                for (b, tb) in &boxes[i + 1..] {
                    let (ox, oy) = (
                        a[2].min(b[2]) - a[0].max(b[0]),
                        a[3].min(b[3]) - a[1].max(b[1]),
                    );
                    assert!(
                        ox <= 0.05 || oy <= 0.05,
                        "{sample}: '{ta}' at {a:?} overprints '{tb}' at {b:?}"
                    );
                }
            }
            let heading = runs.iter().find_map(|r| r["text"].as_str()).unwrap_or("");
            let node_plan = runs.iter().any(|r| {
                r["text"]
                    .as_str()
                    .is_some_and(|t| t.starts_with("Node plan"))
            });
            if node_plan {
                for r in runs.iter() {
                    let t = r["text"].as_str().unwrap_or("");
                    if let Ok(n) = t.parse::<u64>() {
                        ids.insert(n);
                    }
                    // Nodes too close to label are listed in the key.
                    if let Some(list) = t.split("too close to label here: ").nth(1) {
                        ids.extend(list.split(' ').filter_map(|w| w.parse::<u64>().ok()));
                    }
                }
            }
            let _ = heading;
        }
        for n in plan["nodes"].as_array().expect("nodes") {
            let id = n["id"].as_u64().expect("id");
            assert!(
                ids.contains(&id),
                "{sample}: node {id} not on the node plan"
            );
        }
    }
}

/// Distance from `p` to the polyline `pts`, mm.
fn to_polyline(p: [f64; 3], pts: &[[f64; 3]]) -> f64 {
    pts.windows(2)
        .map(|w| {
            let d: Vec<f64> = (0..3).map(|k| w[1][k] - w[0][k]).collect();
            let v: Vec<f64> = (0..3).map(|k| p[k] - w[0][k]).collect();
            let dd: f64 = d.iter().map(|x| x * x).sum();
            let t = if dd > 0.0 {
                (d.iter().zip(&v).map(|(a, b)| a * b).sum::<f64>() / dd).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (0..3)
                .map(|k| (v[k] - t * d[k]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The setting-out table: setting-out.csv has a row per node of the plan,
/// each point on both of its strips' curves as the network file gives
/// them (read here with a YAML reader, the polylines through the file's
/// points) within the node tolerance, its normal a unit vector across
/// both; the PDF's table prints the same coordinates.
#[test]
fn setting_out_is_the_networks_nodes() {
    let out = scratch("setting-out");
    ok(&build_quiet("enneper-4m", "steel-1.5", &out, &[]));
    let net: serde_yaml::Value = serde_yaml::from_str(
        &std::fs::read_to_string(root().join("samples/enneper-4m.yaml")).expect("sample"),
    )
    .expect("yaml");
    let tol = net["tolerance"].as_f64().expect("tolerance");
    let curves: HashMap<String, Vec<[f64; 3]>> = net["curves"]
        .as_sequence()
        .expect("curves")
        .iter()
        .map(|c| {
            let pts = c["points"]
                .as_sequence()
                .expect("points")
                .iter()
                .map(|p| {
                    let q: Vec<f64> = p
                        .as_sequence()
                        .expect("point")
                        .iter()
                        .map(|v| v.as_f64().expect("number"))
                        .collect();
                    [q[0], q[1], q[2]]
                })
                .collect();
            (c["id"].as_str().expect("id").to_string(), pts)
        })
        .collect();
    let mut rd = csv::Reader::from_path(out.join("setting-out.csv")).expect("csv");
    let header: Vec<String> = rd
        .headers()
        .expect("header")
        .iter()
        .map(str::to_string)
        .collect();
    assert_eq!(
        header,
        [
            "node", "strip_a", "strip_b", "x_mm", "y_mm", "z_mm", "normal_x", "normal_y",
            "normal_z", "joint"
        ]
    );
    let plan: Value =
        serde_json::from_slice(&std::fs::read(out.join("plan.json")).expect("plan")).expect("json");
    let mut rows: HashMap<u64, [f64; 3]> = HashMap::new();
    for (i, r) in rd.records().enumerate() {
        let r = r.expect("row");
        let num = |k: usize| r[k].parse::<f64>().expect("number");
        assert_eq!(r[0].parse::<usize>().expect("id"), i, "rows in id order");
        let p = [num(3), num(4), num(5)];
        let n = [num(6), num(7), num(8)];
        for strip in [&r[1], &r[2]] {
            let d = to_polyline(p, &curves[strip]);
            assert!(d <= tol + 0.05, "node {i}: {d} mm off {strip}");
        }
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-5, "node {i}: |n| = {len}");
        for strip in [&r[1], &r[2]] {
            // The curve's chord through the node is across the normal.
            let c = &curves[strip];
            let k = (0..c.len())
                .min_by(|&a, &b| {
                    let d = |q: [f64; 3]| (0..3).map(|j| (q[j] - p[j]).powi(2)).sum::<f64>();
                    d(c[a]).total_cmp(&d(c[b]))
                })
                .expect("points");
            let (a, b) = (c[k.saturating_sub(1)], c[(k + 1).min(c.len() - 1)]);
            let t: Vec<f64> = (0..3).map(|j| b[j] - a[j]).collect();
            let tl = t.iter().map(|x| x * x).sum::<f64>().sqrt();
            let dot = (0..3).map(|j| t[j] / tl * n[j]).sum::<f64>();
            assert!(
                dot.abs() < 0.02,
                "node {i}: normal · tangent of {strip} = {dot}"
            );
        }
        rows.insert(i as u64, p);
    }
    assert_eq!(rows.len(), plan["nodes"].as_array().expect("nodes").len());
    let Some(doc) = read_runs(&out.join("assembly.pdf")) else {
        return;
    };
    let mut seen = 0;
    for runs in section_runs(&doc, "Setting out") {
        for cells in lines(runs.iter().copied()) {
            // Blocks of 9 cells: node, strip, strip, x, y, z, normal.
            for row in cells.chunks(9).filter(|c| c.len() == 9) {
                let Ok(id) = row[0].1.parse::<u64>() else {
                    continue;
                };
                let Ok(x) = row[3].1.parse::<f64>() else {
                    continue;
                };
                let p = rows[&id];
                let y: f64 = row[4].1.parse().expect("y");
                let z: f64 = row[5].1.parse().expect("z");
                for (a, b) in [(x, p[0]), (y, p[1]), (z, p[2])] {
                    assert!((a - b).abs() <= 0.05 + 1e-9, "node {id}: page {a}, csv {b}");
                }
                seen += 1;
            }
        }
    }
    assert_eq!(seen, rows.len(), "every node on the setting-out pages");
}

/// The joint sections of the steel kit, by hand from steel-1.5.yaml: the
/// node bolt clamps two 3 mm star washers and the 50 mm lamella height
/// (grip 56, M8: + nut 6.8 + two pitches 2.5 = 65.3, so 70 from the ISO
/// 4017 series); the shear-block bolt 1.5 + 10 + 1.5 (13); the splice
/// bolt 1.5 + 1.5 (3); and the page says which lamella lies where.
#[test]
fn joint_sections_show_each_stack() {
    let out = scratch("joints");
    ok(&build_quiet("enneper-4m", "steel-1.5", &out, &[]));
    let Some(doc) = read_pdf(&out.join("assembly.pdf")) else {
        return;
    };
    let page = doc["page"]
        .as_array()
        .expect("pages")
        .iter()
        .filter_map(|p| p["text"].as_str())
        .find(|t| t.contains("Joint sections  |"))
        .expect("a joint sections page");
    for want in [
        "Node joint",
        "grip 56.0",
        "L = 70",
        "M8 × 70",
        "Shear block",
        "grip 13.0",
        "Splice",
        "grip 3.0",
        "nut ISO 4032, m = 6.8",
        "lamella 1 on the right, lamella 2 on the left",
    ] {
        assert!(
            page.contains(want),
            "no '{want}' on the joint sections:\n{page}"
        );
    }
    assert!(
        !page.contains("Stud joint"),
        "no studs in an interlocking kit"
    );
}

/// The profile file's number at `path` (`lamella.height_mm`).
fn yaml_mm(doc: &serde_yaml::Value, path: &str) -> f64 {
    path.split('.')
        .fold(doc, |v, k| &v[k])
        .as_f64()
        .unwrap_or_else(|| panic!("{path}"))
}

/// The texts of the edge joint's page (its heading names the edge joint).
fn edge_joint_page(out: &Path) -> Option<Vec<String>> {
    let doc = read_runs(&out.join("assembly.pdf"))?;
    let page = section_runs(&doc, "Joint sections")
        .into_iter()
        .find(|runs| {
            runs.iter().any(|r| {
                r["text"]
                    .as_str()
                    .is_some_and(|t| t.starts_with("Edge joint"))
            })
        })
        .expect("an edge joint page");
    Some(
        page.iter()
            .filter_map(|r| r["text"].as_str().map(String::from))
            .collect(),
    )
}

/// The edge joint drawn in section and elevation, its figures re-derived
/// here from the profile file: on steel-1.5 (bolted; hypar-small, which has
/// rebates) the end slot t + 2 × clearance, its depth at a right angle
/// allowance + h/2 + clearance, the band hole node bolt + hole clearance,
/// the grip h and the bolt length from the ISO 4017 series (h + two M8
/// plain washers 1.6 + nut 6.8 + two 1.25 pitches, rounded up to the
/// series 60, 65, 70); on poplar-ply-4 (two levels, no bolt) the end slots
/// alone.
#[test]
fn edge_joint_page_prints_the_profiles_figures() {
    let out = scratch("edge-joint");
    ok(&build_quiet("hypar-small", "steel-1.5", &out, &[]));
    let Some(texts) = edge_joint_page(&out) else {
        return;
    };
    let yaml: serde_yaml::Value = serde_yaml::from_str(
        &std::fs::read_to_string(root().join("profiles/steel-1.5.yaml")).expect("profile"),
    )
    .expect("yaml");
    let t = yaml_mm(&yaml, "lamella.thickness_mm");
    let h = yaml_mm(&yaml, "lamella.height_mm");
    let gap = yaml_mm(&yaml, "lamella.gap_mm");
    let c = yaml_mm(&yaml, "joint.slot_clearance_mm");
    let allowance = yaml_mm(&yaml, "lamella.end_allowance_mm");
    let d = yaml_mm(&yaml, "node_bolt.diameter_mm");
    let hole = d + yaml_mm(&yaml, "node_bolt.hole_clearance_mm");
    assert_eq!(d, 8.0, "the M8 figures below");
    let needed = h + 2.0 * 1.6 + 6.8 + 2.0 * 1.25;
    let length = [60.0, 65.0, 70.0, 80.0]
        .into_iter()
        .find(|&l| l >= needed)
        .expect("series");
    let has = |want: &str| texts.iter().any(|x| x.contains(want));
    for want in [
        "Edge joint, bolted".to_string(),
        format!("lamellas 2 | 1, t = {t:.1}, gap {gap:.1}, h = {h:.1}"),
        format!("in the end slots {:.1}", t + 2.0 * c),
        format!("end slot {:.1} deep", allowance + 0.5 * h + c),
        format!("allowance {allowance:.1}"),
        format!("band {h:.1} wide"),
        format!("band hole Ø {hole:.1}"),
        format!("grip {h:.1}"),
        format!("L = {length:.0}"),
        format!("M8 × {length:.0} ISO 4017 8.8"),
        // At a rebate: the band on the end slot's floor (h/2 - t/2 - c),
        // the washer on the band.
        format!("grip {:.2}", 0.5 * h - 0.5 * t - c + t),
        "M8 × 40 ISO 4017 8.8".to_string(),
    ] {
        assert!(
            has(&want),
            "no '{want}' on the edge joint page:\n{texts:#?}"
        );
    }

    let out = scratch("edge-joint-slots");
    ok(&build_quiet("enneper-4m", "poplar-ply-4", &out, &[]));
    let Some(texts) = edge_joint_page(&out) else {
        return;
    };
    let yaml: serde_yaml::Value = serde_yaml::from_str(
        &std::fs::read_to_string(root().join("profiles/poplar-ply-4.yaml")).expect("profile"),
    )
    .expect("yaml");
    let t = yaml_mm(&yaml, "lamella.thickness_mm");
    let h = yaml_mm(&yaml, "lamella.height_mm");
    let c = yaml_mm(&yaml, "joint.slot_clearance_mm");
    let allowance = yaml_mm(&yaml, "lamella.end_allowance_mm");
    let has = |want: &str| texts.iter().any(|x| x.contains(want));
    for want in [
        "Edge joint, end slots".to_string(),
        format!("in the end slots {:.1}", t + 2.0 * c),
        format!("end slot {:.1} deep", allowance + 0.5 * h + c),
        format!("h = {h:.1}"),
        "no bolt: the end slots alone hold the band".to_string(),
    ] {
        assert!(
            has(&want),
            "no '{want}' on the edge joint page:\n{texts:#?}"
        );
    }
    assert!(!has("grip"), "no bolt, no grip");
}
