//! `lamella build` end to end: every DXF read back and held to
//! plan.json's parts moved by their placements (an independent reading of
//! plan.json as plain JSON); every DXF audited by ezdxf; every SVG rendered
//! by resvg with ink on the parts and nowhere else; byte-identical
//! rebuilds; kerf compensation at exactly half the kerf; the overstress
//! stop; safe output (foreign files kept, a killed build leaves DIR as it
//! was).

use crate::support::{build, lamella_command, ok, root, scratch};
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn json(path: &Path) -> Value {
    serde_json::from_slice(&std::fs::read(path).expect("read json")).expect("json")
}

/// Every file under `dir` with its bytes.
fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).expect("ls").flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let rel = p
                    .strip_prefix(dir)
                    .expect("rel")
                    .to_string_lossy()
                    .into_owned();
                out.insert(rel, std::fs::read(&p).expect("read"));
            }
        }
    }
    out
}

/// plan.json's parts by id.
fn parts_by_id(plan: &Value) -> BTreeMap<&str, &Value> {
    plan["parts"]
        .as_array()
        .expect("parts")
        .iter()
        .map(|p| (p["id"].as_str().expect("id"), p))
        .collect()
}

fn pt(v: &Value) -> [f64; 2] {
    [v[0].as_f64().expect("x"), v[1].as_f64().expect("y")]
}

/// A placement: turn by a quarter-turn multiple, then move.
fn placed(p: [f64; 2], rot: u64, tx: f64, ty: f64) -> [f64; 2] {
    let (c, s) = match rot {
        0 => (1.0, 0.0),
        90 => (0.0, 1.0),
        180 => (-1.0, 0.0),
        270 => (0.0, -1.0),
        r => panic!("rotation {r}"),
    };
    [c * p[0] - s * p[1] + tx, s * p[0] + c * p[1] + ty]
}

/// Points with consecutive duplicates (≤ 1e-6 mm) dropped, and a closing
/// duplicate of the first when closed.
fn dedup(mut v: Vec<[f64; 2]>, closed: bool) -> Vec<[f64; 2]> {
    let d = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    v.dedup_by(|b, a| d(*a, *b) <= 1e-6);
    while closed && v.len() > 1 && d(v[0], v[v.len() - 1]) <= 1e-6 {
        v.pop();
    }
    v
}

/// The strokes of one plan.json engraving, part frame, mm: its text's
/// glyphs (or its mark) from the plan's `engraving_font`, by the schema's
/// rule (README, plan.json).
fn engraving_strokes(font: &Value, e: &Value) -> Vec<Vec<[f64; 2]>> {
    let at = pt(&e["at_mm"]);
    let h = e["height_mm"].as_f64().expect("height");
    let set = |g: &Value, x: f64| -> Vec<Vec<[f64; 2]>> {
        g["strokes"]
            .as_array()
            .expect("strokes")
            .iter()
            .map(|s| {
                s.as_array()
                    .expect("stroke")
                    .iter()
                    .map(|q| {
                        let q = pt(q);
                        [at[0] + (x + q[0]) * h, at[1] + q[1] * h]
                    })
                    .collect()
            })
            .collect()
    };
    match (e["text"].as_str(), e["mark"].as_str()) {
        (Some(text), None) => {
            let spacing = font["letter_spacing"].as_f64().expect("spacing");
            let mut x = 0.0;
            let mut out = Vec::new();
            for c in text.chars() {
                let g = &font["glyphs"][c.to_string()];
                assert!(g.is_object(), "no glyph for {c:?}");
                out.extend(set(g, x));
                x += g["width"].as_f64().expect("width") + spacing;
            }
            out
        }
        (None, Some(mark)) => {
            let g = &font["marks"][mark];
            assert!(g.is_object(), "no mark {mark:?}");
            set(g, 0.0)
        }
        _ => panic!("an engraving is neither a text nor a mark: {e}"),
    }
}

/// A sheet coordinate of the engraving: rounded to 1 µm.
fn grid(v: f64) -> f64 {
    (v * 1000.0).round() / 1000.0
}

enum Ent {
    Poly {
        layer: String,
        closed: bool,
        pts: Vec<[f64; 2]>,
        bulges: Vec<f64>,
    },
    Circle {
        layer: String,
        c: [f64; 2],
        r: f64,
    },
}

fn read_dxf(path: &Path) -> (dxf::Drawing, Vec<Ent>) {
    let d = dxf::Drawing::load_file(path).expect("DXF reads back");
    let mut ents = Vec::new();
    for e in d.entities() {
        let layer = e.common.layer.clone();
        match &e.specific {
            dxf::entities::EntityType::LwPolyline(p) => ents.push(Ent::Poly {
                layer,
                closed: p.is_closed(),
                pts: p.vertices.iter().map(|v| [v.x, v.y]).collect(),
                bulges: p.vertices.iter().map(|v| v.bulge).collect(),
            }),
            dxf::entities::EntityType::Circle(c) => ents.push(Ent::Circle {
                layer,
                c: [c.center.x, c.center.y],
                r: c.radius,
            }),
            other => panic!("{}: unexpected entity {other:?}", path.display()),
        }
    }
    (d, ents)
}

fn close_to(a: &[[f64; 2]], b: &[[f64; 2]], tol: f64) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(p, q)| (p[0] - q[0]).abs() <= tol && (p[1] - q[1]).abs() <= tol)
}

/// Every DXF of `out` against plan.json: the sheet outline, then per
/// placement in order its holes (circles where a hole feature has that
/// circle), its outline, its engraving; nothing else. Returns the number
/// of entities checked.
fn dxf_matches_plan(out: &Path) -> usize {
    let plan = json(&out.join("plan.json"));
    let parts = parts_by_id(&plan);
    let sheets = plan["sheets"].as_array().expect("sheets");
    assert!(!sheets.is_empty());
    let mut checked = 0;
    for (i, sheet) in sheets.iter().enumerate() {
        let path = out.join(format!("sheets/sheet-{:03}.dxf", i + 1));
        let (d, ents) = read_dxf(&path);
        assert_eq!(d.header.version, dxf::enums::AcadVersion::R2000);
        assert_eq!(
            d.header.default_drawing_units,
            dxf::enums::Units::Millimeters
        );
        assert_eq!(d.header.drawing_units, dxf::enums::DrawingUnits::Metric);
        let (l, w) = (
            sheet["length_mm"].as_f64().expect("l"),
            sheet["width_mm"].as_f64().expect("w"),
        );
        let mut it = ents.iter();
        match it.next() {
            Some(Ent::Poly {
                layer, closed, pts, ..
            }) => {
                assert_eq!(layer, "SHEET");
                assert!(closed);
                assert!(close_to(
                    pts,
                    &[[0.0, 0.0], [l, 0.0], [l, w], [0.0, w]],
                    1e-9
                ));
            }
            _ => panic!("{}: the sheet outline comes first", path.display()),
        }
        for pl in sheet["placements"].as_array().expect("placements") {
            let part = parts[pl["part"].as_str().expect("part")];
            let rot = pl["rotation_deg"].as_u64().expect("rot");
            let (tx, ty) = (
                pl["x_mm"].as_f64().expect("x"),
                pl["y_mm"].as_f64().expect("y"),
            );
            let map = |v: &Value| placed(pt(v), rot, tx, ty);
            // Round holes: the hole features, as circles, in feature order.
            for f in part["features"].as_array().expect("features") {
                if f["kind"] != "hole" {
                    continue;
                }
                let (fc, fr) = (
                    pt(&f["center_mm"]),
                    0.5 * f["width_mm"].as_f64().expect("w"),
                );
                match it.next() {
                    Some(Ent::Circle { layer, c, r }) => {
                        assert_eq!(layer, "CUT-INNER");
                        let want = placed(fc, rot, tx, ty);
                        assert!(
                            close_to(&[*c], &[want], 1e-6),
                            "{}: circle {c:?} vs {want:?}",
                            path.display()
                        );
                        assert!((r - fr).abs() <= 1e-6);
                    }
                    _ => panic!("{}: part {} hole out of order", path.display(), part["id"]),
                }
                checked += 1;
            }
            // Other inner contours.
            for hole in part["holes"].as_array().expect("holes") {
                let pts: Vec<[f64; 2]> = hole.as_array().expect("hole").iter().map(pt).collect();
                match it.next() {
                    Some(Ent::Poly {
                        layer,
                        closed,
                        pts: got,
                        ..
                    }) => {
                        assert_eq!(layer, "CUT-INNER");
                        assert!(closed);
                        let want =
                            dedup(pts.iter().map(|p| placed(*p, rot, tx, ty)).collect(), true);
                        assert!(
                            close_to(got, &want, 1e-6),
                            "{}: hole of {}",
                            path.display(),
                            part["id"]
                        );
                    }
                    _ => panic!("{}: part {} hole out of order", path.display(), part["id"]),
                }
                checked += 1;
            }
            match it.next() {
                Some(Ent::Poly {
                    layer,
                    closed,
                    pts,
                    bulges,
                }) => {
                    assert_eq!(layer, "CUT-OUTER", "{}: {}", path.display(), part["id"]);
                    assert!(closed);
                    assert!(bulges.iter().all(|b| *b == 0.0));
                    let want = dedup(
                        part["outline"]
                            .as_array()
                            .expect("outline")
                            .iter()
                            .map(map)
                            .collect(),
                        true,
                    );
                    assert!(
                        close_to(pts, &want, 1e-6),
                        "{}: outline of {}",
                        path.display(),
                        part["id"]
                    );
                }
                _ => panic!("{}: part {} outline missing", path.display(), part["id"]),
            }
            checked += 1;
            let strokes = part["engraving"]
                .as_array()
                .expect("engraving")
                .iter()
                .flat_map(|e| engraving_strokes(&plan["engraving_font"], e));
            for stroke in strokes {
                // Placed, then on the engraving's 1 µm grid.
                let want = dedup(
                    stroke
                        .iter()
                        .map(|p| {
                            let [x, y] = placed(*p, rot, tx, ty);
                            [grid(x), grid(y)]
                        })
                        .collect(),
                    false,
                );
                if want.len() < 2 {
                    continue;
                }
                match it.next() {
                    Some(Ent::Poly {
                        layer, closed, pts, ..
                    }) => {
                        assert_eq!(layer, "ENGRAVE");
                        assert!(!closed);
                        assert!(
                            close_to(pts, &want, 1e-6),
                            "{}: engraving of {}",
                            path.display(),
                            part["id"]
                        );
                    }
                    _ => panic!("{}: part {} engraving missing", path.display(), part["id"]),
                }
                checked += 1;
            }
        }
        assert!(
            it.next().is_none(),
            "{}: entities beyond the plan",
            path.display()
        );
        // No zero-length segments anywhere.
        for e in &ents {
            if let Ent::Poly { pts, closed, .. } = e {
                let n = pts.len();
                let segs = if *closed { n } else { n - 1 };
                for k in 0..segs {
                    let (a, b) = (pts[k], pts[(k + 1) % n]);
                    assert!(
                        (a[0] - b[0]).hypot(a[1] - b[1]) > 1e-6,
                        "{}: zero-length segment",
                        path.display()
                    );
                }
            }
        }
    }
    checked
}

/// ezdxf's audit of every DXF: no errors. Runs where ezdxf is installed;
/// CI installs it and sets LAMELLA_REQUIRE_EZDXF so a missing ezdxf fails.
fn ezdxf_audit(out: &Path) {
    let have = Command::new("python3")
        .args(["-c", "import ezdxf"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !have {
        assert!(
            std::env::var_os("LAMELLA_REQUIRE_EZDXF").is_none(),
            "ezdxf is required (pip install ezdxf)"
        );
        eprintln!("ezdxf not installed: DXF audit skipped (CI runs it)");
        return;
    }
    let mut files: Vec<PathBuf> = std::fs::read_dir(out.join("sheets"))
        .expect("sheets")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "dxf"))
        .collect();
    files.sort();
    let o = Command::new("python3")
        .arg(root().join("tests/tools/audit_dxf.py"))
        .args(&files)
        .output()
        .expect("python3");
    assert!(
        o.status.success(),
        "ezdxf audit failed:\n{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// Render every SVG with resvg at 1 px per `mm_per_px` mm: every part's box
/// has ink, and there is none away from the parts (outside every part's
/// box grown by 2 px, and 2 px inside the sheet's edge).
fn svg_ink_where_parts_are(out: &Path, mm_per_px: f64) {
    let plan = json(&out.join("plan.json"));
    let parts = parts_by_id(&plan);
    for (i, sheet) in plan["sheets"]
        .as_array()
        .expect("sheets")
        .iter()
        .enumerate()
    {
        let path = out.join(format!("sheets/sheet-{:03}.svg", i + 1));
        let text = std::fs::read_to_string(&path).expect("svg");
        let (l, w) = (
            sheet["length_mm"].as_f64().expect("l"),
            sheet["width_mm"].as_f64().expect("w"),
        );
        assert!(text.contains(&format!(
            r#"width="{l}mm" height="{w}mm" viewBox="0 0 {l} {w}""#
        )));
        let tree = resvg::usvg::Tree::from_str(&text, &resvg::usvg::Options::default())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        // usvg sizes the document in CSS px, 96 per inch.
        let size = tree.size();
        let px_per_mm = 96.0 / 25.4;
        assert!((f64::from(size.width()) - l * px_per_mm).abs() < 1e-2 * px_per_mm);
        assert!((f64::from(size.height()) - w * px_per_mm).abs() < 1e-2 * px_per_mm);
        let (pw, ph) = ((l / mm_per_px).ceil() as u32, (w / mm_per_px).ceil() as u32);
        let mut pix = resvg::tiny_skia::Pixmap::new(pw, ph).expect("pixmap");
        let s = (1.0 / (mm_per_px * px_per_mm)) as f32;
        resvg::render(
            &tree,
            resvg::tiny_skia::Transform::from_scale(s, s),
            &mut pix.as_mut(),
        );
        let ink = |x: u32, y: u32| pix.pixel(x, y).is_some_and(|p| p.alpha() > 0);
        // Part boxes in pixels (SVG y down: row = (w − y) / mm_per_px).
        let mut boxes: Vec<[f64; 4]> = Vec::new();
        for pl in sheet["placements"].as_array().expect("placements") {
            let part = parts[pl["part"].as_str().expect("part")];
            let rot = pl["rotation_deg"].as_u64().expect("rot");
            let (tx, ty) = (
                pl["x_mm"].as_f64().expect("x"),
                pl["y_mm"].as_f64().expect("y"),
            );
            let mut b = [
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ];
            for v in part["outline"].as_array().expect("outline") {
                let p = placed(pt(v), rot, tx, ty);
                b = [
                    b[0].min(p[0]),
                    b[1].min(p[1]),
                    b[2].max(p[0]),
                    b[3].max(p[1]),
                ];
            }
            let px = [
                b[0] / mm_per_px,
                (w - b[3]) / mm_per_px,
                b[2] / mm_per_px,
                (w - b[1]) / mm_per_px,
            ];
            let mut found = false;
            'scan: for y in (px[1].floor().max(0.0) as u32)..(px[3].ceil() as u32).min(ph) {
                for x in (px[0].floor().max(0.0) as u32)..(px[2].ceil() as u32).min(pw) {
                    if ink(x, y) {
                        found = true;
                        break 'scan;
                    }
                }
            }
            assert!(found, "{}: no ink on part {}", path.display(), part["id"]);
            boxes.push(px);
        }
        let mut stray = 0;
        for y in 2..ph.saturating_sub(2) {
            for x in 2..pw.saturating_sub(2) {
                let (fx, fy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                let near = boxes.iter().any(|b| {
                    fx >= b[0] - 2.0 && fx <= b[2] + 2.0 && fy >= b[1] - 2.0 && fy <= b[3] + 2.0
                });
                if !near && ink(x, y) {
                    stray += 1;
                }
            }
        }
        assert_eq!(stray, 0, "{}: ink away from the parts", path.display());
    }
}

#[test]
fn steel_enneper_kit_files_match_the_plan_and_pass_readers() {
    let out = scratch("steel").join("kit");
    let o = build("enneper-4m", "steel-1.5", &out, &[]);
    ok(&o);
    let stdout = String::from_utf8_lossy(&o.stdout);
    for want in [
        "sheets: 3 (lower bound 3)",
        "elastic check: PASS",
        "node bolt",
        "wrote 12 files",
    ] {
        assert!(stdout.contains(want), "summary lacks {want:?}:\n{stdout}");
    }
    let checked = dxf_matches_plan(&out);
    assert!(checked > 1000, "{checked}");
    ezdxf_audit(&out);
    svg_ink_where_parts_are(&out, 1.0);
    // Byte-identical when built again, also under another time zone.
    let again = scratch("steel-again").join("kit");
    let network = "samples/enneper-4m.yaml";
    ok(&lamella_command()
        .args(["build", network, "--profile", "profiles/steel-1.5.yaml"])
        .arg("--out")
        .arg(&again)
        .env("TZ", "Pacific/Auckland")
        .output()
        .expect("run lamella"));
    assert!(snapshot(&out) == snapshot(&again), "rebuild differs");
}

#[test]
fn two_level_timber_kit_with_studs() {
    let out = scratch("poplar").join("kit");
    ok(&build("hypar-small", "poplar-ply-4", &out, &[]));
    dxf_matches_plan(&out);
    ezdxf_audit(&out);
    svg_ink_where_parts_are(&out, 1.0);
    let t = json(&out.join("takeoff.json"));
    let hw = t["hardware"].as_array().expect("hardware");
    let count = |item: &str| {
        hw.iter()
            .find(|h| h["item"] == item)
            .and_then(|h| h["count"].as_u64())
            .unwrap_or(0)
    };
    // One stud per A×B node (a part, not hardware), two stud bolts per
    // stud, each with its nut and two plain washers; no node bolts.
    let plan = json(&out.join("plan.json"));
    let studs = plan["parts"]
        .as_array()
        .expect("parts")
        .iter()
        .find(|p| p["kind"] == "stud")
        .and_then(|p| p["count"].as_u64())
        .expect("studs");
    assert_eq!(count("stud"), 0);
    assert_eq!(count("stud bolt"), 2 * studs);
    assert_eq!(count("node bolt"), 0);
    let line = |item: &str| hw.iter().find(|h| h["item"] == item).expect(item);
    // 4 + 20 + 4 mm grip, 2 × 0.8 washers, nut 3.2, 2 × 0.7 pitches: 34.2 → 35.
    assert_eq!(line("stud bolt")["designation"], "M4 × 35 ISO 4017");
    let m4 = |item: &str| {
        hw.iter()
            .filter(|h| h["item"] == item && h["diameter_mm"] == 4.0)
            .map(|h| h["count"].as_u64().expect("n"))
            .sum::<u64>()
    };
    assert_eq!(m4("nut"), 2 * studs);
    assert_eq!(m4("plain washer"), 4 * studs);
}

/// The takeoff against the plan it came with, summed independently.
#[test]
fn takeoff_sums_the_plan() {
    let out = scratch("takeoff").join("kit");
    ok(&build("enneper-4m", "steel-1.5", &out, &[]));
    let plan = json(&out.join("plan.json"));
    let t = json(&out.join("takeoff.json"));
    let parts = plan["parts"].as_array().expect("parts");
    let area = |poly: &Value| {
        let p: Vec<[f64; 2]> = poly.as_array().expect("poly").iter().map(pt).collect();
        let n = p.len();
        0.5 * (0..n)
            .map(|i| p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1])
            .sum::<f64>()
    };
    for line in t["parts"].as_array().expect("lines") {
        let kind = line["kind"].as_str().expect("kind");
        let of_kind: Vec<&Value> = parts.iter().filter(|p| p["kind"] == kind).collect();
        let count: u64 = of_kind
            .iter()
            .map(|p| p["count"].as_u64().expect("n"))
            .sum();
        let net_m2: f64 = of_kind
            .iter()
            .map(|p| {
                // Round holes are the hole features, cut as circles.
                let round: f64 = p["features"]
                    .as_array()
                    .expect("f")
                    .iter()
                    .filter(|f| f["kind"] == "hole")
                    .map(|f| {
                        std::f64::consts::PI * (0.5 * f["width_mm"].as_f64().expect("d")).powi(2)
                    })
                    .sum();
                let holes: f64 = p["holes"]
                    .as_array()
                    .expect("h")
                    .iter()
                    .map(|h| area(h).abs())
                    .sum();
                (area(&p["outline"]) - round - holes) * p["count"].as_f64().expect("n") * 1e-6
            })
            .sum();
        assert_eq!(line["count"].as_u64(), Some(count), "{kind}");
        assert!(
            (line["area_m2"].as_f64().expect("a") - net_m2).abs() < 1e-4,
            "{kind}"
        );
        // Steel at 7850 kg/m³, cut from the lamella thickness except
        // blocks (the 10 mm gap) and washers (3 mm).
        let t_mm = match kind {
            "shear_block" => 10.0,
            "washer" => 3.0,
            _ => 1.5,
        };
        let mass = net_m2 * t_mm * 1e-3 * 7850.0;
        assert!(
            (line["mass_kg"].as_f64().expect("m") - mass).abs() < 2e-3,
            "{kind}: {mass}"
        );
    }
    let sheets = plan["sheets"].as_array().expect("sheets").len() as f64;
    assert_eq!(t["totals"]["stock_cost"].as_f64(), Some(95.0 * sheets));
    let csv = std::fs::read_to_string(out.join("takeoff.csv")).expect("csv");
    let header = csv.lines().next().expect("header");
    assert!(header.starts_with(
        "section,item,designation,material,thickness_mm,distinct,count,length_mm,area_m2,mass_kg"
    ));
    assert_eq!(csv.lines().filter(|l| l.starts_with("section,")).count(), 1);
    assert!(csv
        .lines()
        .any(|l| l.starts_with("hardware,node bolt,M8 × 70 ISO 4017 8.8")));
}

/// The steel Enneper kit's bought hardware re-derived by hand from its
/// plan.json: bolts per joint from the nodes, the lamellas' slots and
/// holes; lengths from the stacks and the ISO 4017 series; one ISO 4032
/// nut per bolt; two ISO 7089 washers per shear-block and splice bolt
/// (the node bolts bear on the star washers); VDI 2230 torques for 8.8.
#[test]
fn takeoff_hardware_by_hand() {
    let out = scratch("hardware").join("kit");
    ok(&build("enneper-4m", "steel-1.5", &out, &[]));
    let plan = json(&out.join("plan.json"));
    let family: BTreeMap<&str, &str> = plan["strips"]
        .as_array()
        .expect("strips")
        .iter()
        .map(|s| {
            (
                s["id"].as_str().expect("id"),
                s["family"].as_str().expect("f"),
            )
        })
        .collect();
    let grid_nodes = plan["nodes"]
        .as_array()
        .expect("nodes")
        .iter()
        .filter(|n| {
            let f = |k: &str| family.get(n[k].as_str().unwrap_or("")).copied();
            (f("a"), f("b")) == (Some("A"), Some("B"))
        })
        .count() as u64;
    // Pieces of lamella features: a slot per lamella of both strips at a
    // node (4 per node, doubled strips); a shear-block bolt passes two
    // lamellas, a splice bolt one lamella and its plate.
    let mut lamella = BTreeMap::<String, u64>::new();
    for p in plan["parts"].as_array().expect("parts") {
        if p["kind"] != "lamella" {
            continue;
        }
        let n = p["count"].as_u64().expect("n");
        for f in p["features"].as_array().expect("f") {
            let key = f["hole_use"]
                .as_str()
                .unwrap_or(f["kind"].as_str().expect("k"));
            *lamella.entry(key.to_string()).or_default() += n;
        }
    }
    assert_eq!(lamella["slot"], 4 * grid_nodes);
    let shear_bolts = lamella["shear_block"] / 2;
    let splice_bolts = lamella["splice"];
    assert!(grid_nodes > 100 && shear_bolts > 0 && splice_bolts > 0);
    // The stacks, mm: lamellas 1.5, gap 10, height 50, star washers 3.
    // Node M8: 50 + 2 × 3 = 56 grip, nut 6.8, 2 × 1.25 pitch: 65.3 → 70.
    // Shear block M5: 1.5 + 10 + 1.5 = 13, washers 2 × 1, nut 4.7, 2 ×
    // 0.8: 21.3 → 25. Splice M6: 1.5 + 1.5 = 3, washers 2 × 1.6, nut 5.2,
    // 2 × 1: 13.4 → 16.
    let want: Vec<(&str, &str, u64, &str)> = vec![
        ("node bolt", "M8 × 70 ISO 4017 8.8", grid_nodes, "25.0"),
        (
            "shear-block bolt",
            "M5 × 25 ISO 4017 8.8",
            shear_bolts,
            "5.9",
        ),
        ("splice bolt", "M6 × 16 ISO 4017 8.8", splice_bolts, "10.0"),
        ("nut", "M5 ISO 4032 8", shear_bolts, ""),
        ("nut", "M6 ISO 4032 8", splice_bolts, ""),
        ("nut", "M8 ISO 4032 8", grid_nodes, ""),
        ("plain washer", "M5 ISO 7089 200 HV", 2 * shear_bolts, ""),
        ("plain washer", "M6 ISO 7089 200 HV", 2 * splice_bolts, ""),
    ];
    let csv = std::fs::read_to_string(out.join("takeoff.csv")).expect("csv");
    let mut rows = csv::Reader::from_reader(csv.as_bytes());
    let header = rows.headers().expect("header").clone();
    let col = |name: &str| header.iter().position(|h| h == name).expect(name);
    let (item, designation, count, source, torque) = (
        col("item"),
        col("designation"),
        col("count"),
        col("source"),
        col("torque_nm"),
    );
    let records: Vec<csv::StringRecord> = rows.records().map(|r| r.expect("row")).collect();
    let got: Vec<(String, String, u64, String)> = records
        .iter()
        .filter(|r| &r[0] == "hardware")
        .map(|r| {
            assert_eq!(&r[source], "bought");
            (
                r[item].to_string(),
                r[designation].to_string(),
                r[count].parse().expect("count"),
                r[torque].to_string(),
            )
        })
        .collect();
    let want: Vec<(String, String, u64, String)> = want
        .into_iter()
        .map(|(a, b, c, d)| (a.into(), b.into(), c, d.into()))
        .collect();
    assert_eq!(got, want);
    // Star washers are made (a part line), never bought.
    assert!(records
        .iter()
        .any(|r| &r[0] == "part" && &r[item] == "washer" && &r[source] == "made"));
    assert!(!csv.contains("star washer"));
    // One total per section; the hardware total is the sum of its lines.
    let total = |what: &str| -> u64 {
        records
            .iter()
            .find(|r| &r[0] == "total" && &r[item] == what)
            .map(|r| r[count].parse().expect("n"))
            .expect(what)
    };
    let bought: u64 = want.iter().map(|w| w.2).sum();
    assert_eq!(total("bought hardware"), bought);
    assert_eq!(
        total("stock"),
        plan["sheets"].as_array().expect("sheets").len() as u64
    );
    // plan.json carries the same lines.
    let in_plan: Vec<(String, String, u64)> = plan["parts_summary"]["hardware"]
        .as_array()
        .expect("hardware")
        .iter()
        .map(|h| {
            (
                h["item"].as_str().expect("i").to_string(),
                h["designation"].as_str().expect("d").to_string(),
                h["count"].as_u64().expect("n"),
            )
        })
        .collect();
    let got3: Vec<(String, String, u64)> = got.into_iter().map(|(a, b, c, _)| (a, b, c)).collect();
    assert_eq!(in_plan, got3);
}

/// With --kerf-compensation every vertex of an outer contour lies half the
/// kerf (0.1 mm) from the nominal outline and outside it; round holes
/// shrink by half the kerf.
#[test]
fn kerf_compensation_offsets_by_half_the_kerf() {
    let out = scratch("kerf").join("kit");
    ok(&build(
        "enneper-4m",
        "steel-1.5",
        &out,
        &["--kerf-compensation"],
    ));
    ezdxf_audit(&out);
    let plan = json(&out.join("plan.json"));
    let parts = parts_by_id(&plan);
    let sheet = &plan["sheets"][0];
    let (_, ents) = read_dxf(&out.join("sheets/sheet-001.dxf"));
    let outers: Vec<&Vec<[f64; 2]>> = ents
        .iter()
        .filter_map(|e| match e {
            Ent::Poly { layer, pts, .. } if layer == "CUT-OUTER" => Some(pts),
            _ => None,
        })
        .collect();
    let placements = sheet["placements"].as_array().expect("placements");
    assert_eq!(outers.len(), placements.len());
    let mut arcs = 0;
    for e in &ents {
        if let Ent::Poly { layer, bulges, .. } = e {
            if layer == "CUT-OUTER" {
                arcs += bulges.iter().filter(|b| **b != 0.0).count();
            }
        }
    }
    assert!(arcs > 0, "convex corners become arcs");
    for (pl, got) in placements.iter().zip(outers) {
        let part = parts[pl["part"].as_str().expect("part")];
        let rot = pl["rotation_deg"].as_u64().expect("rot");
        let (tx, ty) = (
            pl["x_mm"].as_f64().expect("x"),
            pl["y_mm"].as_f64().expect("y"),
        );
        let nominal: Vec<[f64; 2]> = part["outline"]
            .as_array()
            .expect("outline")
            .iter()
            .map(|v| placed(pt(v), rot, tx, ty))
            .collect();
        for q in got {
            let d = distance_to_polygon(*q, &nominal);
            assert!(
                (d - 0.1).abs() < 1e-6,
                "part {}: vertex {q:?} at {d} mm",
                part["id"]
            );
            assert!(!inside(*q, &nominal), "part {}: vertex inside", part["id"]);
        }
    }
    let steel_hole = 8.0 + 1.0; // M8 with 1 mm clearance
    let circles: Vec<f64> = ents
        .iter()
        .filter_map(|e| match e {
            Ent::Circle { r, .. } => Some(*r),
            _ => None,
        })
        .collect();
    assert!(circles
        .iter()
        .any(|r| (r - (0.5 * steel_hole - 0.1)).abs() < 1e-9));
}

fn distance_to_polygon(p: [f64; 2], poly: &[[f64; 2]]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let t =
                (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
            (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
        })
        .fold(f64::INFINITY, f64::min)
}

fn inside(p: [f64; 2], poly: &[[f64; 2]]) -> bool {
    let n = poly.len();
    let mut c = false;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1])
        {
            c = !c;
        }
    }
    c
}

#[test]
fn overstressed_kit_stops_with_exit_3_and_writes_nothing() {
    let out = scratch("overstress").join("kit");
    let o = build("schwarz-d-pavilion-1to5", "beech-veneer", &out, &[]);
    assert_eq!(
        o.status.code(),
        Some(3),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("overstressed") && err.contains("--allow-overstress"),
        "{err}"
    );
    assert!(!out.exists(), "nothing written");
    assert_eq!(
        std::fs::read_dir(out.parent().expect("parent"))
            .expect("ls")
            .count(),
        0
    );
}

#[test]
fn foreign_files_are_kept_and_a_foreign_plan_is_refused() {
    let dir = scratch("foreign");
    let out = dir.join("kit");
    ok(&build("hypar-small", "steel-1.5", &out, &[]));
    std::fs::write(out.join("notes.txt"), "keep me").expect("foreign");
    std::fs::write(out.join("sheets/extra.dxf"), "mine").expect("foreign");
    ok(&build("hypar-small", "steel-1.5", &out, &[]));
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).expect("kept"),
        "keep me"
    );
    assert_eq!(
        std::fs::read_to_string(out.join("sheets/extra.dxf")).expect("kept"),
        "mine"
    );
    // A plan.json lamella did not write stops the build before any work.
    let other = dir.join("other");
    std::fs::create_dir_all(&other).expect("dir");
    std::fs::write(other.join("plan.json"), "{\"theirs\": true}\n").expect("foreign");
    let o = build("hypar-small", "steel-1.5", &other, &[]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("plan.json") && err.contains("not written by lamella"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    assert_eq!(
        std::fs::read_to_string(other.join("plan.json")).expect("kept"),
        "{\"theirs\": true}\n"
    );
    // An output that is a file.
    let file = dir.join("afile");
    std::fs::write(&file, "x").expect("file");
    let o = build("hypar-small", "steel-1.5", &file, &[]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(std::fs::read_to_string(&file).expect("kept"), "x");
}

/// Kill the build once everything is staged, before anything moves: DIR
/// holds the earlier build byte for byte; the next build clears the
/// staging folder the killed one left.
#[test]
fn killing_the_build_midway_leaves_the_output_as_it_was() {
    let dir = scratch("kill");
    let out = dir.join("kit");
    ok(&build("hypar-small", "steel-1.5", &out, &[]));
    let before = snapshot(&out);
    let mut child = lamella_command()
        .args([
            "build",
            "samples/enneper-4m.yaml",
            "--profile",
            "profiles/steel-1.5.yaml",
            "--out",
            &out.to_string_lossy(),
        ])
        .env("LAMELLA_PAUSE_BEFORE_COMMIT_MS", "60000")
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("spawn");
    let staging = dir.join(format!(".kit.lamella-build-{}", child.id()));
    let staged = staging.join("sheets/sheet-003.svg");
    let t0 = std::time::Instant::now();
    while !staged.exists() {
        assert!(
            t0.elapsed().as_secs() < 60,
            "the build never staged its sheets"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    std::thread::sleep(std::time::Duration::from_millis(200));
    child.kill().expect("kill");
    child.wait().expect("wait");
    assert!(snapshot(&out) == before, "DIR changed by a killed build");
    assert!(
        staging.exists(),
        "the killed build's staging folder is left"
    );
    ok(&build("enneper-4m", "steel-1.5", &out, &[]));
    assert!(!staging.exists(), "the next build removes it");
    assert_eq!(std::fs::read_dir(&dir).expect("ls").count(), 1);
}

/// With two sheet sizes, the takeoff's stock lines are the plan's sheets
/// grouped by size, each size's cost its sheets' prices, and the total the
/// nest's cost.
#[test]
fn takeoff_prices_each_sheet_size() {
    let dir = scratch("mixed");
    let out = dir.join("kit");
    // The full-size pavilion needs 18 large sheets (once its edge bands
    // nest by outline, the small size no longer pays); with at most 19
    // large ones it buys both sizes.
    let text = std::fs::read_to_string(root().join("profiles/steel-1.5-mixed.yaml"))
        .expect("profile")
        .replace(
            "      price_per_unit: 95.0 ",
            "      max_count: 19\n      price_per_unit: 95.0 ",
        );
    assert!(text.contains("max_count: 19"));
    let profile = dir.join("mixed-limited.yaml");
    std::fs::write(&profile, text).expect("write profile");
    ok(&lamella_command()
        .args(["build", "samples/schwarz-d-pavilion.yaml", "--profile"])
        .arg(&profile)
        .arg("--out")
        .arg(&out)
        .output()
        .expect("run lamella"));
    let plan = json(&out.join("plan.json"));
    let t = json(&out.join("takeoff.json"));
    let mut by_size: BTreeMap<String, (u64, f64)> = BTreeMap::new();
    for s in plan["sheets"].as_array().expect("sheets") {
        let e = by_size
            .entry(s["stock"].as_str().expect("stock").to_string())
            .or_default();
        e.0 += 1;
        e.1 += s["price_per_unit"].as_f64().expect("price");
    }
    assert!(by_size.len() >= 2, "{by_size:?}");
    let lines = t["stock"].as_array().expect("stock");
    assert_eq!(lines.len(), by_size.len());
    for l in lines {
        let item = l["item"].as_str().expect("item");
        let (n, cost) = by_size
            .iter()
            .find(|(k, _)| item == format!("sheet {k} mm"))
            .map(|(_, v)| *v)
            .unwrap_or_else(|| panic!("{item} not in the plan"));
        assert_eq!(l["count"].as_u64(), Some(n));
        assert!((l["cost"].as_f64().expect("cost") - cost).abs() < 1e-9);
    }
    let total = plan["nesting"]["total_cost"].as_f64().expect("total");
    assert!((t["totals"]["stock_cost"].as_f64().expect("cost") - total).abs() < 1e-9);
}
