//! `lamella build` end to end: every DXF read back and held to
//! plan.json's parts moved by their placements (an independent reading of
//! plan.json as plain JSON); every DXF audited by ezdxf; every SVG rendered
//! by resvg with ink on the parts and nowhere else; byte-identical
//! rebuilds; kerf compensation at exactly half the kerf; the overstress
//! stop; safe output (foreign files kept, a killed build leaves DIR as it
//! was).

use crate::support::{build, lamella_command, ok, root, scratch, shipped_networks, tools};
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

/// The file of plan sheet `sheet` (the `i`-th): named by its stock group.
fn sheet_file(out: &Path, sheet: &Value, i: usize, ext: &str) -> PathBuf {
    let group = sheet["group"].as_str().expect("group");
    out.join(format!("sheets/{group}-sheet-{:03}.{ext}", i + 1))
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

/// The arc fit's default tolerance, mm (README).
const ARC_TOL_MM: f64 = 0.01;

/// A coordinate on a 1 nm grid, as a key.
fn key(p: [f64; 2]) -> [i64; 2] {
    [(p[0] * 1e6).round() as i64, (p[1] * 1e6).round() as i64]
}

/// The arc of a bulge from `a` to `b`: centre, radius, start angle, signed
/// sweep (derived here from the sweep θ = 4·atan(bulge): radius
/// chord / (2·sin|θ/2|), centre r·cos(θ/2) from the chord's middle, left
/// of it when counter-clockwise).
fn bulge_arc(a: [f64; 2], b: [f64; 2], bulge: f64) -> ([f64; 2], f64, f64, f64) {
    let theta = 4.0 * bulge.atan();
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let chord = dx.hypot(dy);
    let r = chord / (2.0 * (0.5 * theta).sin().abs());
    let d = r * (0.5 * theta).cos() * theta.signum();
    let c = [
        0.5 * (a[0] + b[0]) - d * dy / chord,
        0.5 * (a[1] + b[1]) + d * dx / chord,
    ];
    (c, r, (a[1] - c[1]).atan2(a[0] - c[0]), theta)
}

fn seg_dist(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l2 = dx * dx + dy * dy;
    let t = if l2 == 0.0 {
        0.0
    } else {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0)
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// The largest distance between one fitted span (from `a` to `b`, its
/// bulge) and the plan's polyline it replaces, both ways: every plan
/// vertex to the span, and 64 points along the span to the polyline.
fn span_deviation(a: [f64; 2], b: [f64; 2], bulge: f64, poly: &[[f64; 2]]) -> f64 {
    let along: Vec<[f64; 2]> = (0..=64)
        .map(|k| {
            let t = k as f64 / 64.0;
            if bulge == 0.0 {
                [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
            } else {
                let (c, r, start, sweep) = bulge_arc(a, b, bulge);
                let phi = start + t * sweep;
                [c[0] + r * phi.cos(), c[1] + r * phi.sin()]
            }
        })
        .collect();
    let to_span = |p: [f64; 2]| {
        if bulge == 0.0 {
            return seg_dist(p, a, b);
        }
        // Radially where the arc sweeps p's direction, else the nearer end.
        let (c, r, start, sweep) = bulge_arc(a, b, bulge);
        let phi = (p[1] - c[1]).atan2(p[0] - c[0]);
        let tau = std::f64::consts::TAU;
        let off = if sweep >= 0.0 {
            (phi - start).rem_euclid(tau)
        } else {
            (start - phi).rem_euclid(tau)
        };
        if off <= sweep.abs() {
            ((p[0] - c[0]).hypot(p[1] - c[1]) - r).abs()
        } else {
            (p[0] - a[0])
                .hypot(p[1] - a[1])
                .min((p[0] - b[0]).hypot(p[1] - b[1]))
        }
    };
    let to_poly = |p: [f64; 2]| {
        poly.windows(2)
            .map(|w| seg_dist(p, w[0], w[1]))
            .fold(f64::INFINITY, f64::min)
    };
    let one = poly.iter().map(|p| to_span(*p)).fold(0.0, f64::max);
    let other = along.iter().map(|p| to_poly(*p)).fold(0.0, f64::max);
    one.max(other)
}

/// A plan contour placed on a sheet.
struct Want {
    layer: &'static str,
    part: String,
    kind: String,
    placement: usize,
    pts: Vec<[f64; 2]>,
}

/// What one sheet's DXF was checked for.
#[derive(Default)]
struct SheetCheck {
    /// Entities matched.
    checked: usize,
    /// Largest distance between a fitted contour and plan.json's, mm.
    max_deviation_mm: f64,
    /// Shortest cut segment, mm.
    min_segment_mm: f64,
    /// Vertices of the cut contours.
    cut_vertices: usize,
    /// Vertices of the edge strips' (bands') outlines.
    band_vertices: usize,
}

/// Every DXF of `out` read back by the dxf crate (a reader independent of
/// ezdxf) and held to plan.json's parts moved by their placements: the
/// header (R2000, mm, `$EXTMIN`/`$EXTMAX` around every entity, `$HANDSEED`
/// past every handle); no sheet outline; the entities in cutting order
/// (all engraving, then all inner contours, then all outlines), the parts
/// in the same order in each and in fewer metres of travel than the
/// nest's order; the round holes as circles and the engraving exactly;
/// every cut contour a fit of its plan polygon: each vertex one of the
/// polygon's, each span within `tol_mm` of the polygon between its ends
/// both ways (exact vertices, when `tol_mm` is 0), no segment under
/// 0.05 mm when fitted. Returns what was checked, summed over the sheets.
fn dxf_matches_plan_within(out: &Path, tol_mm: f64) -> SheetCheck {
    let plan = json(&out.join("plan.json"));
    let parts = parts_by_id(&plan);
    let sheets = plan["sheets"].as_array().expect("sheets");
    assert!(!sheets.is_empty());
    let mut sum = SheetCheck {
        min_segment_mm: f64::INFINITY,
        ..Default::default()
    };
    for (i, sheet) in sheets.iter().enumerate() {
        let path = sheet_file(out, sheet, i, "dxf");
        let (d, ents) = read_dxf(&path);
        let name = path.display().to_string();
        assert_eq!(d.header.version, dxf::enums::AcadVersion::R2000);
        assert_eq!(
            d.header.default_drawing_units,
            dxf::enums::Units::Millimeters
        );
        assert_eq!(d.header.drawing_units, dxf::enums::DrawingUnits::Metric);
        let (lo, hi) = (
            &d.header.minimum_drawing_extents,
            &d.header.maximum_drawing_extents,
        );
        let mut max_handle = 0;
        for e in d.entities() {
            max_handle = max_handle.max(e.common.handle.0);
        }
        assert!(d.header.next_available_handle.0 > max_handle, "{name}");
        let mut wants: Vec<Want> = Vec::new();
        let mut circles: Vec<([i64; 2], i64, usize)> = Vec::new();
        let mut strokes: BTreeMap<Vec<[i64; 2]>, usize> = BTreeMap::new();
        let placements = sheet["placements"].as_array().expect("placements");
        for (pi, pl) in placements.iter().enumerate() {
            let part = parts[pl["part"].as_str().expect("part")];
            let id = part["id"].as_str().expect("id").to_string();
            let kind = part["kind"].as_str().expect("kind").to_string();
            let rot = pl["rotation_deg"].as_u64().expect("rot");
            let (tx, ty) = (
                pl["x_mm"].as_f64().expect("x"),
                pl["y_mm"].as_f64().expect("y"),
            );
            let map = |v: &Value| placed(pt(v), rot, tx, ty);
            for f in part["features"].as_array().expect("features") {
                if f["kind"] == "hole" {
                    let r = 0.5 * f["width_mm"].as_f64().expect("w");
                    circles.push((key(map(&f["center_mm"])), (r * 1e6).round() as i64, pi));
                }
            }
            for hole in part["holes"].as_array().expect("holes") {
                let pts = hole.as_array().expect("hole").iter().map(map).collect();
                wants.push(Want {
                    layer: "CUT-INNER",
                    part: id.clone(),
                    kind: kind.clone(),
                    placement: pi,
                    pts: dedup(pts, true),
                });
            }
            let pts = part["outline"]
                .as_array()
                .expect("outline")
                .iter()
                .map(map)
                .collect();
            wants.push(Want {
                layer: "CUT-OUTER",
                part: id.clone(),
                kind: kind.clone(),
                placement: pi,
                pts: dedup(pts, true),
            });
            for e in part["engraving"].as_array().expect("engraving") {
                for stroke in engraving_strokes(&plan["engraving_font"], e) {
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
                    if want.len() >= 2 {
                        *strokes
                            .entry(want.iter().map(|p| key(*p)).collect())
                            .or_default() += 1;
                    }
                }
            }
        }
        // Every vertex of a wanted contour, to its contour and index.
        let mut at: BTreeMap<[i64; 2], (usize, usize)> = BTreeMap::new();
        for (w, want) in wants.iter().enumerate() {
            for (k, p) in want.pts.iter().enumerate() {
                at.insert(key(*p), (w, k));
            }
        }
        let rank = |layer: &str| match layer {
            "ENGRAVE" => 1,
            "CUT-INNER" => 2,
            "CUT-OUTER" => 3,
            other => panic!("{name}: entity on layer {other}"),
        };
        let mut last_rank = 0;
        let mut matched = vec![false; wants.len()];
        // The placements in the order of each operation's entities.
        let mut order: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
        for e in &ents {
            let layer = match e {
                Ent::Poly { layer, .. } | Ent::Circle { layer, .. } => layer.as_str(),
            };
            let r = rank(layer);
            assert!(r >= last_rank, "{name}: {layer} after a later operation");
            last_rank = r;
            let inside = |p: [f64; 2]| {
                p[0] >= lo.x - 1e-6
                    && p[0] <= hi.x + 1e-6
                    && p[1] >= lo.y - 1e-6
                    && p[1] <= hi.y + 1e-6
            };
            match e {
                Ent::Circle { c, r, .. } => {
                    assert!(
                        inside([c[0] - r, c[1] - r]) && inside([c[0] + r, c[1] + r]),
                        "{name}: extents"
                    );
                    assert_eq!(layer, "CUT-INNER");
                    let (k, rr) = (key(*c), (r * 1e6).round() as i64);
                    let found = circles
                        .iter()
                        .position(|q| q.0 == k && q.1 == rr)
                        .unwrap_or_else(|| panic!("{name}: circle {c:?} r {r} not in the plan"));
                    order.entry("CUT-INNER").or_default().push(circles[found].2);
                    circles.swap_remove(found);
                    sum.checked += 1;
                }
                Ent::Poly {
                    closed,
                    pts,
                    bulges,
                    ..
                } => {
                    assert!(
                        pts.iter().all(|p| inside(*p)),
                        "{name}: a vertex outside the extents"
                    );
                    if layer == "ENGRAVE" {
                        assert!(!closed);
                        let k: Vec<[i64; 2]> = pts.iter().map(|p| key(*p)).collect();
                        let n = strokes
                            .get_mut(&k)
                            .unwrap_or_else(|| panic!("{name}: a stroke not in the plan"));
                        assert!(*n > 0, "{name}: a stroke twice");
                        *n -= 1;
                        sum.checked += 1;
                        continue;
                    }
                    assert!(closed, "{name}: an open cut contour");
                    let (w, first) = *at.get(&key(pts[0])).unwrap_or_else(|| {
                        panic!("{name}: a {layer} contour starts off every plan vertex")
                    });
                    let want = &wants[w];
                    assert_eq!(layer, want.layer, "{name}: {}", want.part);
                    assert!(!matched[w], "{name}: {} twice", want.part);
                    matched[w] = true;
                    order.entry(want.layer).or_default().push(want.placement);
                    let n = want.pts.len();
                    if tol_mm == 0.0 {
                        let mut rotated = want.pts.clone();
                        rotated.rotate_left(first);
                        assert!(close_to(pts, &rotated, 1e-6), "{name}: {}", want.part);
                        assert!(bulges.iter().all(|b| *b == 0.0));
                    }
                    // Each span against the plan's polyline between its ends.
                    let m = pts.len();
                    let idx: Vec<usize> = pts
                        .iter()
                        .map(|p| match at.get(&key(*p)) {
                            Some(&(ww, k)) if ww == w => k,
                            _ => panic!("{name}: {}: vertex {p:?} is not the plan's", want.part),
                        })
                        .collect();
                    for s in 0..m {
                        let (i0, i1) = (idx[s], idx[(s + 1) % m]);
                        let steps = (i1 + n - i0) % n;
                        let steps = if steps == 0 { n } else { steps };
                        let poly: Vec<[f64; 2]> =
                            (0..=steps).map(|j| want.pts[(i0 + j) % n]).collect();
                        let (a, b) = (pts[s], pts[(s + 1) % m]);
                        let dev = span_deviation(a, b, bulges[s], &poly);
                        assert!(
                            dev <= tol_mm + 1e-6,
                            "{name}: {} span {s}: {dev} mm off the plan",
                            want.part
                        );
                        sum.max_deviation_mm = sum.max_deviation_mm.max(dev);
                        let chord = (a[0] - b[0]).hypot(a[1] - b[1]);
                        sum.min_segment_mm = sum.min_segment_mm.min(chord);
                        if tol_mm > 0.0 {
                            assert!(chord >= 0.05, "{name}: {}: a {chord} mm segment", want.part);
                        }
                        // Arcs and lines alike stay inside the extents.
                        if bulges[s] != 0.0 {
                            let (c, r, start, sweep) = bulge_arc(a, b, bulges[s]);
                            for k in 0..=16 {
                                let phi = start + sweep * k as f64 / 16.0;
                                let q = [c[0] + r * phi.cos(), c[1] + r * phi.sin()];
                                assert!(inside(q), "{name}: an arc outside the extents");
                            }
                        }
                    }
                    sum.cut_vertices += m;
                    if want.kind == "edge_strip" && want.layer == "CUT-OUTER" {
                        sum.band_vertices += m;
                    }
                    sum.checked += 1;
                }
            }
        }
        assert!(
            matched.iter().all(|m| *m),
            "{name}: a plan contour is missing"
        );
        assert!(circles.is_empty(), "{name}: a round hole is missing");
        assert!(
            strokes.values().all(|n| *n == 0),
            "{name}: a stroke is missing"
        );
        // One travel order for every operation; shorter than the nest's.
        let outer = order.get("CUT-OUTER").cloned().unwrap_or_default();
        let mut seen = std::collections::BTreeSet::new();
        let dedup_order = |v: &Vec<usize>| -> Vec<usize> {
            let mut s = std::collections::BTreeSet::new();
            v.iter().copied().filter(|p| s.insert(*p)).collect()
        };
        let inner = dedup_order(order.get("CUT-INNER").unwrap_or(&Vec::new()));
        let outer_with_inner: Vec<usize> = outer
            .iter()
            .copied()
            .filter(|p| inner.contains(p))
            .collect();
        assert_eq!(
            inner, outer_with_inner,
            "{name}: inner contours in another part order"
        );
        for p in &outer {
            assert!(seen.insert(*p), "{name}: a placement twice");
        }
        let centre = |p: usize| {
            let want = wants
                .iter()
                .find(|w| w.placement == p && w.layer == "CUT-OUTER")
                .expect("outline");
            let (mut a, mut b) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for q in &want.pts {
                a = [a[0].min(q[0]), a[1].min(q[1])];
                b = [b[0].max(q[0]), b[1].max(q[1])];
            }
            [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]
        };
        let travel = |v: &[usize]| -> f64 {
            v.windows(2)
                .map(|w| {
                    let (a, b) = (centre(w[0]), centre(w[1]));
                    (a[0] - b[0]).hypot(a[1] - b[1])
                })
                .sum()
        };
        let nest_order: Vec<usize> = (0..placements.len()).collect();
        assert!(
            travel(&outer) <= travel(&nest_order) + 1e-6,
            "{name}: travel {} mm vs the nest's order {} mm",
            travel(&outer),
            travel(&nest_order)
        );
    }
    sum
}

/// [`dxf_matches_plan_within`] the default arc tolerance; the number of
/// entities checked.
fn dxf_matches_plan(out: &Path) -> usize {
    let c = dxf_matches_plan_within(out, ARC_TOL_MM);
    assert!(c.max_deviation_mm <= ARC_TOL_MM + 1e-6);
    c.checked
}

/// ezdxf's audit of every DXF, the sheets' and the parts': no errors. Runs where ezdxf is installed;
/// CI installs it and sets LAMELLA_REQUIRE_EZDXF so a missing ezdxf fails.
fn ezdxf_audit(out: &Path) {
    ezdxf_audit_of(out, &["sheets", "parts"]);
}

/// [`ezdxf_audit`] on the DXF files of `folders` of a kit only.
fn ezdxf_audit_of(out: &Path, folders: &[&str]) {
    ezdxf_audit_files(&dxf_files_of(out, folders));
}

/// The DXF files of `folders` of a kit, sorted.
fn dxf_files_of(out: &Path, folders: &[&str]) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = folders
        .iter()
        .flat_map(|d| std::fs::read_dir(out.join(d)).expect("folder"))
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "dxf"))
        .collect();
    files.sort();
    files
}

/// `tests/tools/audit_dxf.py` on `files`, in one Python process (it
/// names each file with a problem).
fn ezdxf_audit_files(files: &[PathBuf]) {
    if !tools::present(
        tools::runs("python3", &["-c", "import ezdxf"]),
        "LAMELLA_REQUIRE_EZDXF",
        "ezdxf",
        "pip install ezdxf",
        "DXF audit",
    ) {
        return;
    }
    let o = Command::new("python3")
        .arg(root().join("tests/tools/audit_dxf.py"))
        .args(files)
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
        let path = sheet_file(out, sheet, i, "svg");
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
        "sheets: 5 (lower bound 5)",
        "by stock group: lamella-1.5 3, washer-3 1, shear-block-10 1",
        "elastic check: PASS",
        "node bolt",
        "wrote 224 files",
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

/// Every sample × profile that builds (the rest, the README's refused
/// combinations, are refused as overstressed, exit 3): every sheet's DXF
/// passes ezdxf's audit without an error or a fix, reads back with the
/// dxf crate and holds to plan.json in cutting order (see
/// [`dxf_matches_plan_within`]). The per-part files (parts/*.dxf) are
/// audited on the first sample each profile builds: every part's contours
/// are on the sheets too, moved rigidly, which leaves closure and segment
/// lengths as they are, and the files are written by the same writer; the
/// part files of every build are ten times the sheets' and took most of
/// this test's time.
#[test]
fn every_shipped_build_passes_both_readers() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    let refused = crate::readme::refused(&readme);
    let mut built = 0;
    let mut parts_audited = std::collections::BTreeSet::new();
    let mut to_audit = Vec::new();
    let samples: Vec<PathBuf> = shipped_networks()
        .iter()
        .map(|n| root().join("samples").join(format!("{n}.yaml")))
        .collect();
    for sample in &samples {
        let name = sample
            .file_stem()
            .expect("stem")
            .to_string_lossy()
            .into_owned();
        for profile in [
            "steel-1.5",
            "steel-1.5-mixed",
            "poplar-ply-4",
            "beech-veneer",
        ] {
            let out = scratch(&format!("all-{name}-{profile}")).join("kit");
            let o = build(&name, profile, &out, &["--quiet"]);
            let said = refused.iter().any(|r| r.0 == name && r.1 == profile);
            assert_eq!(
                o.status.code() == Some(3),
                said,
                "{name} with {profile}: refused or not as the README says"
            );
            if said {
                continue;
            }
            ok(&o);
            // Every kit's sheets, and one kit's parts per profile, audited
            // together after the builds (one Python process).
            if parts_audited.insert(profile) {
                to_audit.extend(dxf_files_of(&out, &["sheets", "parts"]));
            } else {
                to_audit.extend(dxf_files_of(&out, &["sheets"]));
            }
            let c = dxf_matches_plan_within(&out, ARC_TOL_MM);
            assert!(c.checked > 0, "{name} {profile}");
            built += 1;
        }
    }
    assert!(built >= 20, "{built} builds");
    ezdxf_audit_files(&to_audit);
}

/// The pavilion's edge bands: arcs bring their outlines' vertices down
/// at least tenfold from plan.json's polygons (the same files with
/// `--arc-tolerance 0`), every fitted span within 0.01 mm of the polygon
/// and no cut segment under 0.05 mm; the polygons' own shortest
/// segment is far below that.
#[test]
fn pavilion_bands_are_fitted_by_arcs() {
    let fitted = scratch("bands-fitted").join("kit");
    ok(&build(
        "schwarz-d-pavilion",
        "steel-1.5",
        &fitted,
        &["--quiet"],
    ));
    let raw = scratch("bands-raw").join("kit");
    ok(&build(
        "schwarz-d-pavilion",
        "steel-1.5",
        &raw,
        &["--quiet", "--arc-tolerance", "0"],
    ));
    let f = dxf_matches_plan_within(&fitted, ARC_TOL_MM);
    let r = dxf_matches_plan_within(&raw, 0.0);
    assert!(f.band_vertices > 0);
    assert!(
        10 * f.band_vertices <= r.band_vertices,
        "bands: {} vertices fitted vs {} polygon",
        f.band_vertices,
        r.band_vertices
    );
    assert!(f.max_deviation_mm <= ARC_TOL_MM + 1e-6);
    assert!(f.min_segment_mm >= 0.05, "{}", f.min_segment_mm);
    assert!(r.min_segment_mm < 0.05, "{}", r.min_segment_mm);
    // A tolerance above a quarter of the part spacing is refused.
    let o = build(
        "hypar-small",
        "steel-1.5",
        &scratch("bands-coarse").join("kit"),
        &["--quiet", "--arc-tolerance", "5"],
    );
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("--arc-tolerance") && err.contains("part_spacing"),
        "{err}"
    );
}

/// The sheet's outline and the SVG's screen labels only when asked: by
/// default neither; with --sheet-outline the outline first, on the
/// non-plotting layer SHEET, and a SHEET group in the SVG; with
/// --svg-labels a LABELS group of texts.
#[test]
fn sheet_outline_and_labels_only_when_asked() {
    let plain = scratch("plain").join("kit");
    ok(&build("hypar-small", "steel-1.5", &plain, &["--quiet"]));
    let (d, ents) = read_dxf(&plain.join("sheets/lamella-1.5-sheet-001.dxf"));
    assert!(ents
        .iter()
        .all(|e| !matches!(e, Ent::Poly { layer, .. } if layer == "SHEET")));
    let svg = std::fs::read_to_string(plain.join("sheets/lamella-1.5-sheet-001.svg")).expect("svg");
    assert!(!svg.contains(r#"id="SHEET""#) && !svg.contains("<text"));
    let sheet_layer = d.layers().find(|l| l.name == "SHEET").expect("SHEET layer");
    assert!(!sheet_layer.is_layer_plotted);
    let asked = scratch("asked").join("kit");
    ok(&build(
        "hypar-small",
        "steel-1.5",
        &asked,
        &["--quiet", "--sheet-outline", "--svg-labels"],
    ));
    let plan = json(&asked.join("plan.json"));
    let (l, w) = (
        plan["sheets"][0]["length_mm"].as_f64().expect("l"),
        plan["sheets"][0]["width_mm"].as_f64().expect("w"),
    );
    let (_, ents) = read_dxf(&asked.join("sheets/lamella-1.5-sheet-001.dxf"));
    match ents.first() {
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
        _ => panic!("the sheet outline comes first"),
    }
    let svg = std::fs::read_to_string(asked.join("sheets/lamella-1.5-sheet-001.svg")).expect("svg");
    assert!(svg.contains(r#"<g id="SHEET""#) && svg.contains(r#"<g id="LABELS""#));
    assert!(svg.contains("<text"));
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
    // Each stock group at its own price (profiles/steel-1.5.yaml): the
    // 1.5 mm sheets 95, the 3 mm washer sheets 85, the 10 mm plates 70.
    let cost: f64 = plan["sheets"]
        .as_array()
        .expect("sheets")
        .iter()
        .map(|s| match s["thickness_mm"].as_f64().expect("t") {
            1.5 => 95.0,
            3.0 => 85.0,
            10.0 => 70.0,
            t => panic!("a {t} mm sheet"),
        })
        .sum();
    assert_eq!(t["totals"]["stock_cost"].as_f64(), Some(cost));
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
    // Where an A or B strip ends on an edge strip: one edge bolt each.
    let edge_nodes = plan["nodes"]
        .as_array()
        .expect("nodes")
        .iter()
        .filter(|n| {
            let f = |k: &str| family.get(n[k].as_str().unwrap_or("")).copied();
            matches!(
                (f("a"), f("b")),
                (Some("A" | "B"), Some("edge")) | (Some("edge"), Some("A" | "B"))
            )
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
            let key = if f["edge"] == "end" {
                "end slot"
            } else {
                f["hole_use"]
                    .as_str()
                    .unwrap_or(f["kind"].as_str().expect("k"))
            };
            *lamella.entry(key.to_string()).or_default() += n;
        }
    }
    assert_eq!(lamella["slot"], 4 * grid_nodes);
    // Both lamellas of a strip have their end slot at an edge node.
    assert_eq!(lamella["end slot"], 2 * edge_nodes);
    // A band splice bolt passes one band piece and its plate.
    let band_splice_bolts: u64 = plan["parts"]
        .as_array()
        .expect("parts")
        .iter()
        .filter(|p| p["kind"] == "edge_strip")
        .flat_map(|p| p["features"].as_array().expect("f"))
        .filter(|f| f["hole_use"] == "splice")
        .count() as u64;
    assert!(edge_nodes == 44 && band_splice_bolts == 16);
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
        // Edge M8: 50 (the lamella height) + washers 2 × 1.6 + nut 6.8 +
        // 2 × 1.25 = 62.5 → 65. Band splice M6: as the splice bolt.
        ("edge bolt", "M8 × 65 ISO 4017 8.8", edge_nodes, "25.0"),
        (
            "band splice bolt",
            "M6 × 16 ISO 4017 8.8",
            band_splice_bolts,
            "10.0",
        ),
        ("nut", "M5 ISO 4032 8", shear_bolts, ""),
        ("nut", "M6 ISO 4032 8", splice_bolts + band_splice_bolts, ""),
        ("nut", "M8 ISO 4032 8", grid_nodes + edge_nodes, ""),
        ("plain washer", "M5 ISO 7089 200 HV", 2 * shear_bolts, ""),
        (
            "plain washer",
            "M6 ISO 7089 200 HV",
            2 * (splice_bolts + band_splice_bolts),
            "",
        ),
        ("plain washer", "M8 ISO 7089 200 HV", 2 * edge_nodes, ""),
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

/// With --kerf-compensation every vertex of an outer contour lies half
/// its stock group's kerf (within the arc fit's tolerance) from the
/// nominal outline and outside it, and every round hole shrinks by as
/// much. The profile is steel-1.5 with the washers given a kerf of their
/// own: three groups, three kerfs (lamellas 0.2 mm, washers 0.3, shear
/// blocks 0.4), each read here from the profile file by part kind.
#[test]
fn kerf_compensation_offsets_each_group_by_half_its_kerf() {
    let dir = scratch("kerf");
    let text = std::fs::read_to_string(root().join("profiles/steel-1.5.yaml")).expect("profile");
    let washer_price = "    price_per_unit: 85.0";
    assert!(text.contains(washer_price));
    let text = text.replacen(
        washer_price,
        &format!("{washer_price}\n    kerf_mm: 0.3"),
        1,
    );
    let profile = dir.join("steel-kerfs.yaml");
    std::fs::write(&profile, &text).expect("write");
    let yaml: serde_yaml::Value = serde_yaml::from_str(&text).expect("yaml");
    let kerf_of = |kind: &str| {
        let key = match kind {
            "washer" => "washer",
            "shear_block" => "shear_block",
            "edge_strip" => "edge",
            "splice_plate" => "splice",
            _ => "",
        };
        yaml["stocks"][key]["kerf_mm"]
            .as_f64()
            .or(yaml["cutting"]["kerf_mm"].as_f64())
            .expect("kerf")
    };
    let out = dir.join("kit");
    ok(&lamella_command()
        .args(["build", "samples/enneper-4m.yaml", "--profile"])
        .arg(&profile)
        .arg("--out")
        .arg(&out)
        .arg("--kerf-compensation")
        .output()
        .expect("run lamella"));
    ezdxf_audit(&out);
    let plan = json(&out.join("plan.json"));
    let parts = parts_by_id(&plan);
    let mut halves: Vec<f64> = Vec::new();
    let mut arcs = 0;
    for (i, sheet) in plan["sheets"]
        .as_array()
        .expect("sheets")
        .iter()
        .enumerate()
    {
        let half = |part: &Value| 0.5 * kerf_of(part["kind"].as_str().expect("kind"));
        arcs += offset_by_half_kerf(&sheet_file(&out, sheet, i, "dxf"), sheet, &parts, &half);
        for pl in sheet["placements"].as_array().expect("placements") {
            let h = half(parts[pl["part"].as_str().expect("part")]);
            if !halves.contains(&h) {
                halves.push(h);
            }
        }
    }
    assert!(arcs > 0, "convex corners become arcs");
    halves.sort_by(f64::total_cmp);
    assert_eq!(halves, [0.1, 0.15, 0.2]);
}

/// Checks one kerf-compensated sheet file against its plan sheet: every
/// outer contour (against the nominal outline nearest to it: the files
/// are in travel order, not the nest's) lies `half_mm(part)` outside it,
/// within the arc fit's tolerance; every circle is a placed round hole
/// shrunk by as much. Returns the outer contours' arcs.
fn offset_by_half_kerf(
    file: &Path,
    sheet: &Value,
    parts: &BTreeMap<&str, &Value>,
    half_mm: &dyn Fn(&Value) -> f64,
) -> usize {
    let (_, ents) = read_dxf(file);
    let placements = sheet["placements"].as_array().expect("placements");
    let mut nominals: Vec<(&Value, Vec<[f64; 2]>)> = Vec::new();
    let mut holes: Vec<([f64; 2], f64)> = Vec::new();
    for pl in placements {
        let part = parts[pl["part"].as_str().expect("part")];
        let rot = pl["rotation_deg"].as_u64().expect("rot");
        let (tx, ty) = (
            pl["x_mm"].as_f64().expect("x"),
            pl["y_mm"].as_f64().expect("y"),
        );
        let at = |v: &Value| placed(pt(v), rot, tx, ty);
        let outline = part["outline"].as_array().expect("outline");
        nominals.push((part, outline.iter().map(at).collect()));
        for f in part["features"].as_array().expect("features") {
            if f["kind"] == "hole" {
                let r = 0.5 * f["width_mm"].as_f64().expect("width");
                holes.push((at(&f["center_mm"]), r - half_mm(part)));
            }
        }
    }
    let (mut outers, mut circles, mut arcs) = (0, 0, 0);
    for e in &ents {
        match e {
            Ent::Poly {
                layer, pts, bulges, ..
            } if layer == "CUT-OUTER" => {
                outers += 1;
                arcs += bulges.iter().filter(|b| **b != 0.0).count();
                let (part, nominal) = nominals
                    .iter()
                    .min_by(|a, b| {
                        distance_to_polygon(pts[0], &a.1)
                            .total_cmp(&distance_to_polygon(pts[0], &b.1))
                    })
                    .expect("a placement");
                let want = half_mm(part);
                for q in pts {
                    let d = distance_to_polygon(*q, nominal);
                    assert!(
                        (d - want).abs() <= ARC_TOL_MM + 1e-6,
                        "{}: part {}: vertex {q:?} at {d} mm, not {want}",
                        file.display(),
                        part["id"]
                    );
                    assert!(!inside(*q, nominal), "part {}: vertex inside", part["id"]);
                }
            }
            Ent::Circle { c, r, .. } => {
                circles += 1;
                let (_, want) = holes
                    .iter()
                    .find(|(h, _)| (h[0] - c[0]).hypot(h[1] - c[1]) < 1e-6)
                    .unwrap_or_else(|| panic!("{}: a circle at {c:?}", file.display()));
                assert!(
                    (r - want).abs() < 1e-9,
                    "{}: r {r}, not {want}",
                    file.display()
                );
            }
            _ => {}
        }
    }
    assert_eq!(outers, placements.len(), "{}", file.display());
    assert_eq!(circles, holes.len(), "{}", file.display());
    arcs
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
    let staged = staging.join("sheets/lamella-1.5-sheet-003.svg");
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
            .entry(format!(
                "{} × {}",
                s["stock"].as_str().expect("stock"),
                s["thickness_mm"].as_f64().expect("t")
            ))
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

/// `parts/`: one DXF and SVG per distinct part and `parts.csv`, whose
/// quantities are plan.json's counts and add up to every placement of
/// every sheet; each part's file, moved by a placement of that part,
/// is that placement's cut contours on the sheet exactly (vertices and
/// bulges), its round holes, and its engraving to the 1 µm grid.
#[test]
fn per_part_files_are_the_nested_parts() {
    let out = scratch("parts-files").join("kit");
    ok(&build("enneper-4m", "steel-1.5", &out, &["--quiet"]));
    let plan = json(&out.join("plan.json"));
    let parts = plan["parts"].as_array().expect("parts");
    let sheets = plan["sheets"].as_array().expect("sheets");
    let placed_total: usize = sheets
        .iter()
        .map(|s| s["placements"].as_array().expect("p").len())
        .sum();
    let mut rd = csv::Reader::from_path(out.join("parts/parts.csv")).expect("parts.csv");
    let header: Vec<String> = rd
        .headers()
        .expect("header")
        .iter()
        .map(String::from)
        .collect();
    assert_eq!(
        header,
        [
            "part",
            "kind",
            "material",
            "thickness_mm",
            "quantity",
            "length_mm",
            "width_mm",
            "area_mm2",
            "file"
        ]
    );
    let rows: Vec<csv::StringRecord> = rd.records().map(|r| r.expect("row")).collect();
    assert_eq!(rows.len(), parts.len());
    let mut sum = 0;
    for (row, part) in rows.iter().zip(parts) {
        assert_eq!(&row[0], part["id"].as_str().expect("id"));
        assert_eq!(&row[1], part["kind"].as_str().expect("kind"));
        assert_eq!(&row[2], "S355 hot-rolled strip steel");
        let t: f64 = row[3].parse().expect("t");
        let want_t = match &row[1] {
            "shear_block" => 10.0,
            "washer" => 3.0,
            _ => 1.5,
        };
        assert_eq!(t, want_t, "{}", &row[0]);
        let q: u64 = row[4].parse().expect("q");
        assert_eq!(Some(q), part["count"].as_u64());
        sum += q as usize;
        assert!(out.join("parts").join(&row[8]).is_file());
        assert!(out
            .join("parts")
            .join(row[8].replace(".dxf", ".svg"))
            .is_file());
    }
    assert_eq!(sum, placed_total, "quantities add up to the kit");
    // Each part's file against its first placement.
    let mut done = std::collections::BTreeSet::new();
    for (i, sheet) in sheets.iter().enumerate() {
        let (_, sheet_ents) = read_dxf(&sheet_file(&out, sheet, i, "dxf"));
        for pl in sheet["placements"].as_array().expect("placements") {
            let id = pl["part"].as_str().expect("part");
            if !done.insert(id.to_string()) {
                continue;
            }
            let rot = pl["rotation_deg"].as_u64().expect("rot");
            let (tx, ty) = (
                pl["x_mm"].as_f64().expect("x"),
                pl["y_mm"].as_f64().expect("y"),
            );
            let row = rows.iter().find(|r| &r[0] == id).expect("row");
            let (_, ents) = read_dxf(&out.join("parts").join(&row[8]));
            assert!(!ents.is_empty());
            for e in &ents {
                match e {
                    Ent::Circle { c, r, .. } => {
                        let want = placed(*c, rot, tx, ty);
                        assert!(
                            sheet_ents
                                .iter()
                                .any(|s| matches!(s, Ent::Circle { c: sc, r: sr, .. }
                                if close_to(&[*sc], &[want], 1e-6) && (sr - r).abs() < 1e-9)),
                            "{id}: circle"
                        );
                    }
                    Ent::Poly {
                        layer, pts, bulges, ..
                    } => {
                        let want: Vec<[f64; 2]> =
                            pts.iter().map(|p| placed(*p, rot, tx, ty)).collect();
                        let tol = if layer == "ENGRAVE" { 1.5e-3 } else { 1e-6 };
                        let found = sheet_ents.iter().any(|s| match s {
                            Ent::Poly {
                                layer: sl,
                                pts: sp,
                                bulges: sb,
                                ..
                            } => {
                                sl == layer
                                    && close_to(sp, &want, tol)
                                    && sb.iter().zip(bulges).all(|(a, b)| (a - b).abs() < 1e-9)
                            }
                            _ => false,
                        });
                        assert!(found, "{id}: a {layer} polyline not on sheet {}", i + 1);
                    }
                }
            }
        }
    }
    assert_eq!(done.len(), parts.len());
}
