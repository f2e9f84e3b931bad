//! The 3D model (`model.glb`) and its page (`view.html`): the GLB read
//! back here by hand (header, JSON chunk, BIN chunk) against plan.json;
//! the bytes stable; the Khronos glTF-Validator on every shipped sample's
//! model; the page drawn and picked in headless Chromium.

use crate::support::{build, lamella, ok, root, scratch, shipped_networks, tools};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A GLB read back: its JSON and its binary chunk.
struct Glb {
    json: Value,
    bin: Vec<u8>,
}

fn u32_at(b: &[u8], at: usize) -> usize {
    u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]]) as usize
}

/// Read a GLB by the glTF 2.0 specification's binary layout.
fn read_glb(path: &Path) -> Glb {
    let b = std::fs::read(path).expect("read model.glb");
    assert_eq!(&b[0..4], b"glTF", "magic");
    assert_eq!(u32_at(&b, 4), 2, "version");
    assert_eq!(u32_at(&b, 8), b.len(), "length");
    let json_len = u32_at(&b, 12);
    assert_eq!(&b[16..20], b"JSON");
    assert_eq!(json_len % 4, 0);
    let json: Value = serde_json::from_slice(&b[20..20 + json_len]).expect("JSON chunk");
    let bin_len = u32_at(&b, 20 + json_len);
    assert_eq!(&b[24 + json_len..28 + json_len], b"BIN\0");
    assert_eq!(28 + json_len + bin_len, b.len(), "one BIN chunk to the end");
    let bin = b[28 + json_len..].to_vec();
    assert_eq!(
        json["buffers"][0]["byteLength"].as_u64(),
        Some(bin.len() as u64)
    );
    Glb { json, bin }
}

impl Glb {
    /// A VEC3 float accessor's values.
    fn vec3(&self, accessor: &Value) -> Vec<[f64; 3]> {
        let a = &self.json["accessors"][accessor.as_u64().expect("index") as usize];
        assert_eq!(a["componentType"], 5126);
        assert_eq!(a["type"], "VEC3");
        let v = &self.json["bufferViews"][a["bufferView"].as_u64().expect("view") as usize];
        let start = v["byteOffset"].as_u64().unwrap_or(0) as usize
            + a["byteOffset"].as_u64().unwrap_or(0) as usize;
        let count = a["count"].as_u64().expect("count") as usize;
        (0..count)
            .map(|i| {
                let f = |k: usize| {
                    let o = start + 12 * i + 4 * k;
                    f64::from(f32::from_le_bytes([
                        self.bin[o],
                        self.bin[o + 1],
                        self.bin[o + 2],
                        self.bin[o + 3],
                    ]))
                };
                [f(0), f(1), f(2)]
            })
            .collect()
    }

    fn root(&self) -> &Value {
        let i = self.json["scenes"][0]["nodes"][0].as_u64().expect("root") as usize;
        &self.json["nodes"][i]
    }

    /// The root's children.
    fn children(&self) -> Vec<&Value> {
        self.root()["children"]
            .as_array()
            .expect("children")
            .iter()
            .map(|i| &self.json["nodes"][i.as_u64().expect("child") as usize])
            .collect()
    }

    fn child(&self, name: &str) -> &Value {
        self.children()
            .into_iter()
            .find(|n| n["name"] == name)
            .unwrap_or_else(|| panic!("no node {name}"))
    }

    fn primitive(&self, node: &Value) -> &Value {
        &self.json["meshes"][node["mesh"].as_u64().expect("mesh") as usize]["primitives"][0]
    }

    /// A glTF point (m, about the root) in the network's frame, mm.
    fn to_network_mm(&self, p: [f64; 3]) -> [f64; 3] {
        let t = &self.root()["translation"];
        let g = [0, 1, 2].map(|k| t[k].as_f64().expect("translation") + p[k]);
        [g[0] * 1000.0, -g[2] * 1000.0, g[1] * 1000.0]
    }
}

fn plan_json(dir: &Path) -> Value {
    serde_json::from_slice(&std::fs::read(dir.join("plan.json")).expect("plan.json"))
        .expect("parse plan.json")
}

fn xyz(v: &Value) -> [f64; 3] {
    [0, 1, 2].map(|k| v[k].as_f64().expect("number"))
}

#[test]
fn the_model_holds_the_plans_nodes_and_every_strip_once() {
    let out = scratch("enneper");
    ok(&build("enneper-4m", "steel-1.5", &out, &[]));
    let plan = plan_json(&out);
    let glb = read_glb(&out.join("model.glb"));
    // Every node, in plan order, where plan.json has it (to 1e-6 m).
    let nodes = glb.child("nodes");
    let prim = glb.primitive(nodes);
    assert_eq!(prim["mode"], 0, "points");
    let points = glb.vec3(&prim["attributes"]["POSITION"]);
    let plan_nodes = plan["nodes"].as_array().expect("nodes");
    assert_eq!(points.len(), plan_nodes.len());
    for (p, n) in points.iter().zip(plan_nodes) {
        let got = glb.to_network_mm(*p);
        let want = xyz(&n["position_mm"]);
        for k in 0..3 {
            assert!(
                (got[k] - want[k]).abs() <= 1e-3,
                "node {}: {got:?} against {want:?}",
                n["id"]
            );
        }
    }
    // Every strip once, with its figures; its nodes inside its solid.
    let strips = plan["strips"].as_array().expect("strips");
    let mut seen = std::collections::BTreeMap::new();
    for n in glb.children() {
        if let Some(id) = n["extras"]["id"].as_str() {
            *seen.entry(id.to_string()).or_insert(0) += 1;
        }
    }
    assert_eq!(seen.len(), strips.len());
    assert!(seen.values().all(|&c| c == 1), "{seen:?}");
    let h = plan["profile"]["height_mm"].as_f64().expect("h");
    for s in strips {
        let id = s["id"].as_str().expect("id");
        let node = glb.child(id);
        let e = &node["extras"];
        assert_eq!(e["family"], s["family"], "{id}");
        assert_eq!(e["length_mm"], s["length_mm"], "{id}");
        assert_eq!(e["material"], plan["profile"]["material"], "{id}");
        assert_eq!(e["utilisation"], s["check"]["utilization"], "{id}");
        let prim = glb.primitive(node);
        let pos = glb.vec3(&prim["attributes"]["POSITION"]);
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in &pos {
            let q = glb.to_network_mm(*p);
            for k in 0..3 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        for sn in s["nodes"].as_array().expect("strip nodes") {
            let p = xyz(&plan_nodes[sn["node"].as_u64().expect("node") as usize]["position_mm"]);
            assert!(
                (0..3).all(|k| p[k] >= lo[k] - 1.0 && p[k] <= hi[k] + 1.0),
                "{id}: node {} outside its solid",
                sn["node"]
            );
        }
        // A solid as high as the profile's lamellas, no higher.
        let diag =
            ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2)).sqrt();
        assert!(diag >= h, "{id}: {diag} mm");
    }
    // The slots are cut: a steel lamella's section steps at each slot, so
    // its mesh has more vertices than 4 per frame.
    let a = glb.primitive(glb.child("A05"));
    assert!(glb.vec3(&a["attributes"]["POSITION"]).len() > 100);
    assert!(glb.children().iter().any(|n| n["name"] == "washers"));
}

#[test]
fn the_flat_state_is_a_rigid_placement_of_the_plans_layout() {
    let out = scratch("flat");
    ok(&build(
        "enneper-4m",
        "steel-1.5",
        &out,
        &["--slots-from-flat"],
    ));
    let plan = plan_json(&out);
    let glb = read_glb(&out.join("model.glb"));
    let prim = glb.primitive(glb.child("nodes"));
    let base = glb.vec3(&prim["attributes"]["POSITION"]);
    let d = glb.vec3(&prim["targets"][0]["POSITION"]);
    let flat: Vec<[f64; 3]> = base
        .iter()
        .zip(&d)
        .map(|(b, d)| glb.to_network_mm([b[0] + d[0], b[1] + d[1], b[2] + d[2]]))
        .collect();
    let floor = plan["flat"]["nodes"].as_array().expect("flat nodes");
    assert!(floor.len() > 100);
    let first = &floor[0];
    let f0 = flat[first["node"].as_u64().expect("node") as usize];
    let p0 = [0, 1].map(|k| first["position_mm"][k].as_f64().expect("x"));
    for n in floor {
        let f = flat[n["node"].as_u64().expect("node") as usize];
        let p = [0, 1].map(|k| n["position_mm"][k].as_f64().expect("x"));
        // On one level, at the layout's distances.
        assert!((f[2] - f0[2]).abs() < 1e-3, "{}", n["node"]);
        let got = ((f[0] - f0[0]).powi(2) + (f[1] - f0[1]).powi(2)).sqrt();
        let want = ((p[0] - p0[0]).powi(2) + (p[1] - p0[1]).powi(2)).sqrt();
        assert!(
            (got - want).abs() < 2e-3,
            "{}: {got} against {want}",
            n["node"]
        );
    }
    // Every A and B strip morphs; the edges do not.
    for n in glb.children() {
        let fam = n["extras"]["family"].as_str().unwrap_or("");
        let has = glb.primitive(n)["targets"].is_array();
        match fam {
            "A" | "B" => assert!(has, "{}", n["name"]),
            "edge" => assert!(!has, "{}", n["name"]),
            _ => {}
        }
    }
}

#[test]
fn view_and_build_write_the_same_model_byte_for_byte() {
    let dir = scratch("same");
    let (a, b, k) = (dir.join("a"), dir.join("b"), dir.join("kit"));
    for out in [&a, &b] {
        let (code, stdout, stderr) = lamella(&[
            "view",
            "samples/enneper-4m.yaml",
            "--profile",
            "profiles/steel-1.5.yaml",
            "--out",
            out.to_str().expect("path"),
        ]);
        assert_eq!(code, Some(0), "{stdout}{stderr}");
        assert!(stdout.contains("165 nodes"), "{stdout}");
    }
    ok(&build("enneper-4m", "steel-1.5", &k, &[]));
    for f in ["model.glb", "view.html"] {
        let x = std::fs::read(a.join(f)).expect("a");
        assert!(x == std::fs::read(b.join(f)).expect("b"), "{f} differs");
        assert!(
            x == std::fs::read(k.join(f)).expect("kit"),
            "{f}: build differs"
        );
    }
    // Written again over its own files; a file not lamella's is refused.
    let (code, _, _) = lamella(&[
        "view",
        "samples/hypar-small.yaml",
        "--profile",
        "profiles/steel-1.5.yaml",
        "--out",
        a.to_str().expect("path"),
    ]);
    assert_eq!(code, Some(0));
    std::fs::write(b.join("view.html"), "<html>mine</html>").expect("write");
    let (code, _, stderr) = lamella(&[
        "view",
        "samples/hypar-small.yaml",
        "--profile",
        "profiles/steel-1.5.yaml",
        "--out",
        b.to_str().expect("path"),
    ]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains("view.html") && stderr.contains("not written by lamella"),
        "{stderr}"
    );
}

#[test]
fn every_sample_model_holds_its_plans_nodes() {
    let dir = scratch("samples");
    for sample in shipped_networks() {
        let out = dir.join(&sample);
        let net = format!("samples/{sample}.yaml");
        let o = out.to_str().expect("path");
        let (code, stdout, stderr) = lamella(&["nodes", &net, "--out", o]);
        assert_eq!(code, Some(0), "{sample}: {stdout}{stderr}");
        let args = [
            "view",
            &net,
            "--profile",
            "profiles/steel-1.5.yaml",
            "--out",
            o,
        ];
        let (code, stdout, stderr) = lamella(&args);
        assert_eq!(code, Some(0), "{sample}: {stdout}{stderr}");
        let plan = plan_json(&out);
        let glb = read_glb(&out.join("model.glb"));
        let prim = glb.primitive(glb.child("nodes"));
        let points = glb.vec3(&prim["attributes"]["POSITION"]);
        let nodes = plan["nodes"].as_array().expect("nodes");
        assert_eq!(points.len(), nodes.len(), "{sample}");
        for (p, n) in points.iter().zip(nodes) {
            let (got, want) = (glb.to_network_mm(*p), xyz(&n["position_mm"]));
            let off = (0..3).map(|k| (got[k] - want[k]).abs()).fold(0.0, f64::max);
            assert!(off <= 1e-3, "{sample} node {}: {off} mm", n["id"]);
        }
        let strips = plan["strips"].as_array().expect("strips").len();
        let named = glb
            .children()
            .iter()
            .filter(|n| n["extras"]["id"].is_string())
            .count();
        assert_eq!(named, strips, "{sample}");
    }
}

/// The validator's runner, where node and the npm package are installed
/// (`npm ci --prefix tests/tools/gltf`); CI installs them and sets
/// LAMELLA_REQUIRE_GLTF_VALIDATOR so a missing one fails.
fn validator() -> Option<PathBuf> {
    let dir = root().join("tests/tools/gltf");
    if !tools::present(
        dir.join("node_modules/gltf-validator").is_dir() && tools::runs("node", &["--version"]),
        "LAMELLA_REQUIRE_GLTF_VALIDATOR",
        "the glTF-Validator",
        "npm ci --prefix tests/tools/gltf",
        "validating the model",
    ) {
        return None;
    }
    Some(dir.join("validate.js"))
}

#[test]
fn every_sample_model_passes_the_gltf_validator() {
    let Some(script) = validator() else {
        return;
    };
    let dir = scratch("validator");
    let mut runs: Vec<(String, &str, bool)> = shipped_networks()
        .into_iter()
        .map(|s| (s, "steel-1.5", false))
        .collect();
    runs.push(("enneper-4m".into(), "steel-1.5", true));
    runs.push(("hypar-small".into(), "poplar-ply-4", false));
    runs.push(("hypar-small".into(), "beech-veneer", false));
    let mut files = Vec::new();
    for (sample, profile, flat) in &runs {
        let out = dir.join(format!("{sample}-{profile}-{flat}"));
        let mut args = vec![
            "view".to_string(),
            format!("samples/{sample}.yaml"),
            "--profile".into(),
            format!("profiles/{profile}.yaml"),
            "--out".into(),
            out.to_string_lossy().into_owned(),
        ];
        if *flat {
            args.push("--flat".into());
        }
        let (code, stdout, stderr) = lamella(&args);
        assert_eq!(code, Some(0), "{sample} {profile}: {stdout}{stderr}");
        files.push(out.join("model.glb"));
    }
    let o = Command::new("node")
        .arg(&script)
        .args(&files)
        .output()
        .expect("run node");
    let text = String::from_utf8_lossy(&o.stdout);
    let reports: Vec<Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).expect("report line"))
        .collect();
    assert_eq!(reports.len(), files.len());
    for r in &reports {
        assert_eq!(r["errors"], 0, "{r}");
        assert_eq!(r["warnings"], 0, "{r}");
    }
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// Debian's chromium, run headless with no network (in a network
/// namespace of its own where `unshare` allows, and every host name
/// unresolvable besides); None when it is not installed and
/// LAMELLA_REQUIRE_CHROMIUM is unset.
fn chromium(args: &[String]) -> Option<std::process::Output> {
    if !tools::present(
        tools::runs("chromium", &["--version"]),
        "LAMELLA_REQUIRE_CHROMIUM",
        "chromium",
        "apt-get install chromium",
        "the page test",
    ) {
        return None;
    }
    let flags = [
        "--headless",
        "--no-sandbox",
        "--use-angle=swiftshader",
        "--enable-unsafe-swiftshader",
        "--window-size=1000,700",
        "--host-resolver-rules=MAP * ~NOTFOUND",
        "--proxy-server=127.0.0.1:9",
    ];
    let isolated = Command::new("unshare")
        .args(["-n", "true"])
        .output()
        .is_ok_and(|o| o.status.success());
    let mut c = if isolated {
        let mut c = Command::new("unshare");
        c.args(["-n", "chromium"]);
        c
    } else {
        Command::new("chromium")
    };
    let o = c.args(flags).args(args).output().expect("run chromium");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    Some(o)
}

#[test]
fn the_page_draws_the_grid_and_picks_a_strip() {
    let dir = scratch("page");
    let (code, stdout, stderr) = lamella(&[
        "view",
        "samples/enneper-4m.yaml",
        "--profile",
        "profiles/steel-1.5.yaml",
        "--out",
        dir.to_str().expect("path"),
    ]);
    assert_eq!(code, Some(0), "{stdout}{stderr}");
    let page = format!("file://{}", dir.join("view.html").display());
    let shot = dir.join("shot.png");
    let Some(_) = chromium(&[format!("--screenshot={}", shot.display()), page.clone()]) else {
        return;
    };
    let png = std::fs::read(&shot).expect("screenshot");
    let img = resvg::tiny_skia::Pixmap::decode_png(&png).expect("decode png");
    let (w, h) = (img.width() as usize, img.height() as usize);
    let px = |x: usize, y: usize| {
        let c = img.pixel(x as u32, y as u32).expect("pixel");
        [c.red(), c.green(), c.blue()]
    };
    // The grid: ink right of the panel, where only the canvas is.
    let background = [244u8, 244, 242];
    let far = |a: [u8; 3], b: [u8; 3]| (0..3).map(|k| a[k].abs_diff(b[k]) as u32).sum::<u32>() > 40;
    let mut ink = 0;
    let mut total = 0;
    for y in 0..h {
        for x in (w * 2 / 5)..w {
            total += 1;
            if far(px(x, y), background) {
                ink += 1;
            }
        }
    }
    assert!(ink * 100 > total * 2, "only {ink} of {total} pixels drawn");
    // The utilisation bar: its end colours are there.
    let stops = lamella::formats::write::gltf::UTILISATION_STOPS;
    for (_, want) in [stops[0], stops[stops.len() - 1]] {
        let found = (0..h).any(|y| {
            (0..w).any(|x| {
                let c = px(x, y);
                (0..3).all(|k| c[k].abs_diff(want[k]) <= 3)
            })
        });
        assert!(found, "no bar colour {want:?}");
    }
    // Picking: the page picks the strip drawn nearest its centre and says
    // which (id, utilisation and length as the model has them).
    let Some(o) = chromium(&["--dump-dom".into(), format!("{page}#pick=auto")]) else {
        return;
    };
    let dom = String::from_utf8_lossy(&o.stdout);
    let picked = dom
        .split("data-picked=\"")
        .nth(1)
        .and_then(|r| r.split('"').next())
        .unwrap_or_else(|| panic!("nothing picked"));
    let glb = read_glb(&dir.join("model.glb"));
    let e = &glb.child(picked)["extras"];
    let line = dom
        .split("<div id=\"picked\">")
        .nth(1)
        .and_then(|r| r.split('<').next())
        .expect("picked line");
    let u = e["utilisation"].as_f64().expect("utilisation");
    let l = e["length_mm"].as_f64().expect("length") / 1000.0;
    assert!(
        line.starts_with(&format!("{picked} (family "))
            && line.contains(&format!("utilisation {u:.3}"))
            && line.contains(&format!("length {l:.3} m")),
        "{line}"
    );
}

/// A braced grid's cables in the model: the small hypar on the steel
/// profile with every other quad crossed. The `cables` node lists the
/// plan's cable ids; each cable is a square rod (8 vertices) of the
/// strand's diameter whose axis runs pin to pin: its length is the
/// schedule's, and each end lies 30 mm up the normal and 30 mm along the
/// tangent plane from its joint's node in plan.json, so √(30² + 30²) =
/// 42.43 mm from it. The model passes the glTF-Validator.
#[test]
fn a_braced_grids_cables_are_in_the_model_pin_to_pin() {
    let out = crate::bracing::braced_build(&scratch("cables"), "hypar-small", "alternate", &[]);
    let plan = plan_json(&out);
    let bracing = &plan["structure"]["bracing"];
    let cables = bracing["cables"].as_array().expect("cables");
    let nodes: std::collections::BTreeMap<String, [f64; 3]> = plan["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| (n["id"].to_string(), xyz(&n["position_mm"])))
        .collect();
    let glb = read_glb(&out.join("model.glb"));
    let node = glb.child("cables");
    let ids: Vec<&str> = node["extras"]["ids"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    let want: Vec<&str> = cables.iter().map(|c| c["id"].as_str().unwrap()).collect();
    assert_eq!(ids, want);
    let pos: Vec<[f64; 3]> = glb
        .vec3(&glb.primitive(node)["attributes"]["POSITION"])
        .into_iter()
        .map(|p| glb.to_network_mm(p))
        .collect();
    assert_eq!(pos.len(), 8 * cables.len());
    let dist = |a: [f64; 3], b: [f64; 3]| {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    };
    let mean = |ps: &[[f64; 3]]| {
        let n = ps.len() as f64;
        [0, 1, 2].map(|k| ps.iter().map(|p| p[k]).sum::<f64>() / n)
    };
    let d = bracing["diameter_mm"].as_f64().unwrap();
    for (c, rod) in cables.iter().zip(pos.chunks(8)) {
        // Vertex k's bit 0 is the end along the axis, bits 1 and 2 across.
        let start: Vec<[f64; 3]> = (0..8).filter(|k| k & 1 == 0).map(|k| rod[k]).collect();
        let end: Vec<[f64; 3]> = (0..8).filter(|k| k & 1 == 1).map(|k| rod[k]).collect();
        let (a, b) = (mean(&start), mean(&end));
        let length = c["length_mm"].as_f64().unwrap();
        assert!((dist(a, b) - length).abs() < 0.01, "{c}: {}", dist(a, b));
        assert!((dist(rod[0], rod[2]) - d).abs() < 1e-3, "{c}");
        let joints = c["nodes"].as_array().unwrap();
        for (pin, joint) in [a, b].into_iter().zip(joints) {
            let at = nodes[&joint.as_str().unwrap().to_string()];
            let off = dist(pin, at);
            assert!((off - 30.0 * 2f64.sqrt()).abs() < 0.01, "{c}: {off}");
        }
    }
    if let Some(script) = validator() {
        let o = Command::new("node")
            .arg(&script)
            .arg(out.join("model.glb"))
            .output()
            .expect("run node");
        let r: Value = serde_json::from_slice(&o.stdout).expect("report");
        assert_eq!(
            (r["errors"].as_u64(), r["warnings"].as_u64()),
            (Some(0), Some(0)),
            "{r}"
        );
    }
}
