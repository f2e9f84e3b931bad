//! Fabricated parts: every slot and hole at its node's station on
//! its own lamella line, swept slot widths and centres against the closed
//! forms of docs/geometry.md (single and doubled, 90° and off 90°), shear blocks
//! within both spacing limits and clear of the nodes, every shipped profile
//! on every shipped sample, and one-line errors for combinations a profile
//! cannot build.

use crate::support::{self, analysed_sample, lamella_command, root, scratch};
use lamella::analysis::lines::LamellaLine;
use lamella::fabricate::part::{Feature, FeatureKind, HoleUse, Part, PartKind, SlotEdge};
use lamella::fabricate::{fabricate, Kit};
use lamella::formats::read::{read_network, ReadOptions};
use lamella::profile::Profile;
use lamella::{analyze, Analysis, AnalysisOptions, Family, Network};
use std::collections::HashMap;
use std::path::Path;
use std::process::Output;

/// A slot from a long edge where two strips cross (not an end slot an edge
/// strip runs through).
fn halving(f: &Feature) -> bool {
    f.kind == FeatureKind::Slot && f.edge != Some(SlotEdge::End)
}

fn load(sample: &str, profile: &str) -> (Network, Analysis, Profile) {
    let net = read_network(
        &root().join(format!("samples/{sample}.yaml")),
        ReadOptions::default(),
    )
    .unwrap();
    let an = analyze(&net, AnalysisOptions::for_network(&net)).unwrap();
    let p = support::profile(profile);
    (net, an, p)
}

/// The node stations of every lamella line, by (strip id, lamella number):
/// node id → station on the line (held to exact offset lines in
/// tests/it/offset.rs).
fn line_stations(an: &Analysis, p: &Profile) -> HashMap<(String, u32), HashMap<usize, f64>> {
    let mut out = HashMap::new();
    for s in an.lamella_strips() {
        for o in p.lamella_offsets(s.family) {
            let line = LamellaLine::new(s, &an.curves[s.curve], o);
            let map = line
                .nodes
                .iter()
                .map(|n| (an.topology.nodes[n.node].id, n.station_mm))
                .collect();
            out.insert((s.id.clone(), o.number), map);
        }
    }
    out
}

fn lamellas(kit: &Kit) -> impl Iterator<Item = &Part> {
    kit.parts.iter().filter(|p| p.kind == PartKind::Lamella)
}

/// The signed crossing angle (degrees) from strip `mine`'s direction to the
/// other strip's at node `id`, about the node normal.
fn angle_at(an: &Analysis, net: &Network, mine: &str, id: usize) -> f64 {
    let n = an.topology.nodes.iter().find(|n| n.id == id).unwrap();
    let (a, b) = if net.curves[n.a].id == mine {
        (n.tangent_a_world, n.tangent_b_world)
    } else {
        (n.tangent_b_world, n.tangent_a_world)
    };
    a.cross(b).dot(n.normal_world).atan2(a.dot(b)).to_degrees()
}

/// Sweep by dense sampling (an oracle independent of the library's search):
/// the union over φ of [c − w/2, c + w/2], c = (s·cos φ − σ·s_b)/sin φ,
/// w = (t_b + t·|cos φ|)/|sin φ|, for the crossing lamellas σ·s_b.
fn sampled_sweep(t: f64, s: f64, crossing: &[f64], lo_deg: f64, hi_deg: f64) -> Vec<(f64, f64)> {
    let mut spans: Vec<(f64, f64)> = crossing
        .iter()
        .map(|&sb| {
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for k in 0..=200_000 {
                let phi = (lo_deg + (hi_deg - lo_deg) * k as f64 / 200_000.0).to_radians();
                let c = (s * phi.cos() - sb) / phi.sin();
                let w = (t + t * phi.cos().abs()) / phi.sin().abs();
                lo = lo.min(c - w / 2.0);
                hi = hi.max(c + w / 2.0);
            }
            (lo, hi)
        })
        .collect();
    spans.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut merged: Vec<(f64, f64)> = Vec::new();
    for sp in spans {
        match merged.last_mut() {
            Some(m) if sp.0 <= m.1 => m.1 = m.1.max(sp.1),
            _ => merged.push(sp),
        }
    }
    merged
}

/// Every slot of every lamella: centred and as wide as the sampled sweep
/// around its node's station on the lamella's own line (0.01 mm).
fn check_slots(sample: &str, profile: &str) -> usize {
    let (net, an, p) = load(sample, profile);
    let kit = fabricate(&net, &an, &p, None, Default::default()).unwrap();
    let stations = line_stations(&an, &p);
    let t = p.section.thickness_mm;
    let clearance = p.joint.slot_clearance_mm;
    let tol = p.joint.rotation_tolerance_deg;
    let mut checked = 0;
    for part in lamellas(&kit) {
        let strip = part.strip.clone().unwrap();
        let number = part.lamella.unwrap();
        let family = net.curves[net.curve_index(&strip).unwrap()].family;
        let offsets = p.lamella_offsets(family);
        let s = offsets.iter().find(|o| o.number == number).unwrap().dy_mm;
        let crossing_family = if family == Family::A {
            Family::B
        } else {
            Family::A
        };
        let crossing: Vec<f64> = p
            .lamella_offsets(crossing_family)
            .iter()
            .map(|o| o.dy_mm)
            .collect();
        let start = part.station_start_mm.unwrap();
        let mut by_node: HashMap<usize, Vec<(f64, f64)>> = HashMap::new();
        for f in part.features.iter().filter(|f| halving(f)) {
            let id = f.node.unwrap();
            let x0 = f.center_part_mm.x - f.width_mm / 2.0 + start;
            let x1 = f.center_part_mm.x + f.width_mm / 2.0 + start;
            by_node.entry(id).or_default().push((x0, x1));
            // Slots from the top edge for A, the bottom for B, half the
            // height plus the clearance deep.
            assert!((f.depth_mm - (p.section.height_mm / 2.0 + clearance)).abs() < 1e-9);
            let (a0, a1) = f.angle_range_deg.unwrap();
            let phi = angle_at(&an, &net, &strip, id);
            assert!(
                a0 <= phi + 1e-9 && phi <= a1 + 1e-9,
                "{strip}: {phi} not in [{a0}, {a1}]"
            );
        }
        for (id, mut got) in by_node {
            got.sort_by(|a, b| a.0.total_cmp(&b.0));
            let node_station = stations[&(strip.clone(), number)][&id];
            let phi = angle_at(&an, &net, &strip, id);
            let (lo, hi) = if phi > 0.0 {
                ((phi - tol).max(15.0), (phi + tol).min(165.0))
            } else {
                ((phi - tol).max(-165.0), (phi + tol).min(-15.0))
            };
            let want = sampled_sweep(t, s, &crossing, lo, hi);
            assert_eq!(
                got.len(),
                want.len(),
                "{strip}-{number} node {id}: slot count"
            );
            for (g, w) in got.iter().zip(&want) {
                let (w0, w1) = (
                    node_station + w.0 - clearance / 2.0,
                    node_station + w.1 + clearance / 2.0,
                );
                assert!(
                    (g.0 - w0).abs() < 0.01 && (g.1 - w1).abs() < 0.01,
                    "{strip}-{number} node {id}: slot [{:.3}, {:.3}] vs [{w0:.3}, {w1:.3}]",
                    g.0,
                    g.1
                );
                checked += 1;
            }
        }
    }
    checked
}

#[test]
fn doubled_steel_slots_at_90_degrees() {
    // Enneper crossings are 90°; 60° of rotation: the two slots of each
    // crossing lamella merge into one, ±(s·cot 15° + (t + t·cos 30°)/(2 sin 30°)).
    let n = check_slots("enneper-4m", "steel-1.5");
    assert!(n > 300, "{n} slots");
    let (net, an, p) = load("enneper-4m", "steel-1.5");
    let kit = fabricate(&net, &an, &p, None, Default::default()).unwrap();
    let s = 5.75;
    let half = s / 15f64.to_radians().tan() + 1.5 * (1.0 + 30f64.to_radians().cos()) / 1.0 + 0.15;
    let widths: Vec<f64> = lamellas(&kit)
        .flat_map(|p| p.features.iter())
        .filter(|f| halving(f))
        .map(|f| f.width_mm)
        .collect();
    assert!(
        widths.iter().all(|w| (w - 2.0 * half).abs() < 0.01),
        "{:?}",
        &widths[..4]
    );
}

#[test]
fn single_veneer_slots_match_the_closed_form() {
    // Single strips at 90° ± 10°: t·(1 + sin 10°)/cos 10° + clearance.
    let n = check_slots("enneper-4m", "beech-veneer");
    assert!(n > 150, "{n} slots");
    let (net, an, p) = load("enneper-4m", "beech-veneer");
    let kit = fabricate(&net, &an, &p, None, Default::default()).unwrap();
    let th = 10f64.to_radians();
    let want = 0.6 * (1.0 + th.sin()) / th.cos() + 0.1;
    for f in lamellas(&kit).flat_map(|p| p.features.iter()) {
        if halving(f) {
            assert!((f.width_mm - want).abs() < 0.01, "{} vs {want}", f.width_mm);
        }
    }
}

#[test]
fn slots_off_90_degrees() {
    // The hyperbolic paraboloid's rulings cross at 82°–90°: single and
    // doubled strips, each slot against the sampled sweep.
    assert!(check_slots("hypar-small", "beech-veneer") > 40);
    assert!(check_slots("hypar-small", "steel-1.5") > 40);
}

/// Two-level grids: no slots; a fastener hole through each lamella at its
/// node's station on its own line (0.01 mm), at mid-height, one per A×B
/// node, each naming the crossing strip.
#[test]
fn two_level_node_holes_sit_at_the_nodes() {
    let (net, an, p) = load("catenoid", "poplar-ply-4");
    let kit = fabricate(&net, &an, &p, None, Default::default()).unwrap();
    let stations = line_stations(&an, &p);
    let mut holes = 0;
    for part in lamellas(&kit) {
        assert!(part.features.iter().all(|f| !halving(f)));
        let key = (part.strip.clone().unwrap(), part.lamella.unwrap());
        let start = part.station_start_mm.unwrap();
        for f in &part.features {
            if f.hole_use != Some(HoleUse::Node) {
                continue;
            }
            holes += 1;
            let want = stations[&key][&f.node.unwrap()];
            assert!(
                (f.center_part_mm.x + start - want).abs() < 0.01,
                "{}: hole at {} vs node at {want}",
                part.id,
                f.center_part_mm.x + start
            );
            assert!((f.center_part_mm.y - p.section.height_mm / 2.0).abs() < 1e-9);
            assert!(f.crossing.is_some());
            let d = p.stud.as_ref().unwrap().fastener_diameter_mm;
            assert!((f.width_mm - (d + 1.0)).abs() < 1e-9);
        }
    }
    // Every A×B node: one hole in each of the 2 lamellas of both strips.
    let ab = an
        .topology
        .nodes
        .iter()
        .filter(|n| net.curves[n.b].family == Family::B)
        .count();
    assert_eq!(holes, 4 * ab);
    let studs = kit.parts.iter().find(|p| p.kind == PartKind::Stud).unwrap();
    assert_eq!(studs.count as usize, ab);
}

/// Fabrication on the check's lamella lines (what `lamella build` does)
/// makes exactly the parts it makes integrating its own lines: no station
/// depends on which others were asked for with it.
#[test]
fn parts_on_the_checks_lines_are_the_same() {
    for (sample, profile) in [("enneper-4m", "steel-1.5"), ("catenoid", "poplar-ply-4")] {
        let (net, an, p) = load(sample, profile);
        let own = fabricate(&net, &an, &p, None, Default::default()).unwrap();
        let (report, lines) = lamella::check::check(&an, &p, true);
        assert_eq!(report, lamella::check::check(&an, &p, false).0, "{sample}");
        let shared = lamella::fabricate::fabricate(&net, &an, &p, None, lines).unwrap();
        assert_eq!(own.parts, shared.parts, "{sample} with {profile}");
        // The nodes where the parts put them: where the check's lines have them.
        for sc in &report.strips {
            for l in &sc.lamellas {
                let s = &an.strips[sc.strip];
                assert_eq!(
                    l.line,
                    LamellaLine::new(s, &an.curves[s.curve], l.line.offset)
                );
            }
        }
    }
}

#[test]
fn shear_blocks_keep_both_limits_and_clear_the_nodes() {
    for (sample, profile) in [
        ("catenoid", "steel-1.5"),
        ("scherk", "poplar-ply-4"),
        ("schwarz-d-pavilion", "steel-1.5"),
    ] {
        let (net, an, p) = load(sample, profile);
        let kit = fabricate(&net, &an, &p, None, Default::default()).unwrap();
        let b = p.shear_block.clone().unwrap();
        let limit = b
            .max_spacing_mm
            .min(b.slenderness_limit * p.section.thickness_mm / 12f64.sqrt());
        let stations = line_stations(&an, &p);
        let mut blocks = 0;
        for part in lamellas(&kit) {
            let key = (part.strip.clone().unwrap(), part.lamella.unwrap());
            let start = part.station_start_mm.unwrap();
            let holes: Vec<f64> = part
                .features
                .iter()
                .filter(|f| f.hole_use == Some(HoleUse::ShearBlock))
                .map(|f| f.center_part_mm.x + start)
                .collect();
            blocks += holes.len();
            let nodes: Vec<f64> = stations[&key].values().copied().collect();
            // Clear of every node's zone: slots, washer arms, studs.
            let zone = p
                .washer
                .as_ref()
                .map_or(0.5 * p.section.gap_mm, |w| w.arm_length_mm);
            for &h in &holes {
                for &n in &nodes {
                    let need = zone + b.clearance_mm + b.length_mm / 2.0;
                    let slots_near = part.features.iter().any(|f| {
                        halving(f)
                            && ((f.center_part_mm.x + start) - h).abs()
                                < f.width_mm / 2.0 + b.clearance_mm + b.length_mm / 2.0
                    });
                    assert!(!slots_near, "{} block at {h} overlaps a slot", part.id);
                    assert!(
                        (h - n).abs() >= need - 0.05,
                        "{} block at {h:.2} is {:.2} mm from the node at {n:.2} (needs {need})",
                        part.id,
                        (h - n).abs()
                    );
                }
            }
            // Supports (nodes and blocks) no farther apart than the limit,
            // measured along this lamella's own line, within its extent.
            let mut supports: Vec<f64> = nodes
                .iter()
                .copied()
                .filter(|&n| n >= start && n <= start + part.length_mm)
                .chain(holes.iter().copied())
                .collect();
            supports.sort_by(f64::total_cmp);
            for w in supports.windows(2) {
                assert!(
                    w[1] - w[0] <= limit + 1e-6,
                    "{}: supports {:?} {limit}",
                    part.id,
                    w
                );
            }
        }
        let sb = kit.parts.iter().find(|p| p.kind == PartKind::ShearBlock);
        if blocks > 0 {
            // Each block couples both lamellas: one hole per lamella.
            assert_eq!(sb.unwrap().count as usize * 2, blocks, "{sample}");
        }
    }
}

#[test]
fn every_profile_builds_every_sample_or_says_why() {
    let samples = [
        "enneper-4m",
        "catenoid",
        "scherk",
        "schwarz-d-patch",
        "hypar-small",
        "schwarz-d-pavilion-1to5",
        "schwarz-d-pavilion",
    ];
    let mut failed = Vec::new();
    for profile in ["steel-1.5", "poplar-ply-4", "beech-veneer"] {
        for sample in samples {
            let (net, an, p) = load(sample, profile);
            match fabricate(&net, &an, &p, None, Default::default()) {
                Ok(kit) => {
                    assert!(lamellas(&kit).count() >= an.lamella_strips().count());
                    // Every outline closed, simple, counter-clockwise; holes
                    // clockwise inside it; every label inside and clear of
                    // the cuts by kerf + spacing; nothing left unlabelled.
                    let clearance = p.cutting.kerf_mm + p.cutting.part_spacing_mm;
                    for part in &kit.parts {
                        assert_eq!(
                            lamella::fabricate::invariants::check_part(part, clearance),
                            Ok(()),
                            "{profile} on {sample}"
                        );
                        assert!(!part.engraving.is_empty(), "{} unlabelled", part.id);
                    }
                    assert!(kit.warnings.is_empty(), "{:?}", kit.warnings);
                    // Every lamella part within the stock's usable length;
                    // every part (edge bands split where needed) fits the
                    // usable sheet in an allowed rotation.
                    let usable = p.stock.sizes[0].usable_length_mm(p.cutting.edge_margin_mm);
                    let width = p.stock.sizes[0].usable_width_mm(p.cutting.edge_margin_mm);
                    let quarter = p
                        .cutting
                        .allowed_rotations_deg
                        .iter()
                        .any(|r| r % 180 == 90);
                    for part in lamellas(&kit) {
                        assert!(part.length_mm <= usable + 1e-6, "{}", part.id);
                    }
                    for part in &kit.parts {
                        let along = part.length_mm <= usable && part.height_mm <= width;
                        let across = quarter && part.height_mm <= usable && part.length_mm <= width;
                        assert!(
                            along || across,
                            "{} {}×{}",
                            part.id,
                            part.length_mm,
                            part.height_mm
                        );
                    }
                }
                Err(e) => {
                    let msg = e.to_string();
                    assert!(!msg.contains('\n'));
                    assert!(msg.contains("strip "), "{msg}");
                    failed.push(format!("{profile} on {sample}: {msg}"));
                }
            }
        }
    }
    // Only the full-size profiles on the 1:5 model (nodes 80 mm apart leave
    // no room for a 160 or 200 mm splice plate) cannot be built.
    assert_eq!(failed.len(), 2, "{failed:#?}");
    assert!(failed
        .iter()
        .all(|f| f.contains("pavilion-1to5") && f.contains("splice")));
}

fn run_parts(network: &Path, profile: &Path, out: &Path) -> Output {
    lamella_command()
        .arg("parts")
        .arg(network)
        .arg("--profile")
        .arg(profile)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap()
}

/// A profile cannot build the network: one line naming the profile, strip
/// and node, exit 1, no plan written.
#[test]
fn impossible_combinations_are_one_line_errors() {
    let dir = scratch("errors");
    let steel = std::fs::read_to_string(root().join("profiles/steel-1.5.yaml")).unwrap();
    let cases = [
        // A slot deeper than the lamella.
        ("slot_clearance_mm: 0.3", "slot_clearance_mm: 26.0", "deep"),
        // Shear blocks that cannot fit between two nodes.
        (
            "  clearance_mm: 15.0",
            "  clearance_mm: 140.0",
            "shear blocks",
        ),
    ];
    for (from, to, says) in cases {
        assert!(steel.contains(from), "{from}");
        let path = dir.join(format!("p-{}.yaml", says.replace(' ', "-")));
        std::fs::write(&path, steel.replace(from, to)).unwrap();
        let out = dir.join(format!("out-{}", says.replace(' ', "-")));
        let r = run_parts(&root().join("samples/enneper-4m.yaml"), &path, &out);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(1), "{err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains("strip "), "{err}");
        assert!(err.contains(says), "{err}");
        assert!(!out.join("plan.json").exists());
    }
    // Slots that leave no material between them: two B strips 3 mm apart
    // cross an A strip; veneer slots 0.72 mm + 2.5 mm clearance overlap.
    let net = dir.join("close.yaml");
    std::fs::write(
        &net,
        "units: mm\ncurves:\n\
         - {id: A00, family: A, points: [[0, 0, 0], [250, 0, 0], [500, 0, 0]]}\n\
         - {id: B00, family: B, points: [[200, -100, 0], [200, 0, 0], [200, 100, 0]]}\n\
         - {id: B01, family: B, points: [[203, -100, 0], [203, 0, 0], [203, 100, 0]]}\n",
    )
    .unwrap();
    let veneer = std::fs::read_to_string(root().join("profiles/beech-veneer.yaml")).unwrap();
    let path = dir.join("wide.yaml");
    std::fs::write(
        &path,
        veneer.replace("slot_clearance_mm: 0.1", "slot_clearance_mm: 2.5"),
    )
    .unwrap();
    let r = run_parts(&net, &path, &dir.join("out-wide"));
    let err_wide = String::from_utf8_lossy(&r.stderr).to_string();
    assert_eq!(r.status.code(), Some(1), "{err_wide}");
    assert!(
        err_wide.contains("node ") && err_wide.contains("material between"),
        "{err_wide}"
    );
    // A washer whose arms do not fit the gap between the lamellas; a stud
    // fastener that would cut the stud in two.
    for (profile, from, to, says) in [
        (
            "steel-1.5",
            "arm_width_mm: 9.6",
            "arm_width_mm: 12.0",
            "strip A00, node 0: washer arms",
        ),
        (
            "poplar-ply-4",
            "fastener_diameter_mm: 4.0",
            "fastener_diameter_mm: 24.0",
            "part ST:",
        ),
    ] {
        let text =
            std::fs::read_to_string(root().join(format!("profiles/{profile}.yaml"))).unwrap();
        assert!(text.contains(from));
        let path = dir.join(format!("{profile}-bad.yaml"));
        std::fs::write(&path, text.replace(from, to)).unwrap();
        let out = dir.join(format!("out-{profile}"));
        let r = run_parts(&root().join("samples/catenoid.yaml"), &path, &out);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(1), "{err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains(says), "{err}");
        assert!(!out.join("plan.json").exists());
    }
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(
        err.contains("node ") && err.contains("material between"),
        "{err}"
    );
}

#[test]
fn parts_writes_the_plan_and_a_summary() {
    let dir = scratch("cli");
    let r = run_parts(
        &root().join("samples/enneper-4m.yaml"),
        &root().join("profiles/steel-1.5.yaml"),
        &dir,
    );
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let stdout = String::from_utf8_lossy(&r.stdout);
    assert!(
        stdout.contains("lamella") && stdout.contains("kg"),
        "{stdout}"
    );
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("plan.json")).unwrap()).unwrap();
    let parts = plan["parts"].as_array().unwrap();
    assert!(parts.len() > 40);
    assert!(plan["check"].is_object(), "parts writes what check writes");
    let first = &parts[0];
    for field in [
        "id",
        "kind",
        "strip",
        "lamella",
        "count",
        "length_mm",
        "height_mm",
        "station_start_mm",
        "outline",
        "holes",
        "engraving",
        "features",
    ] {
        assert!(first.get(field).is_some(), "{field}");
    }
    // Deterministic: the same input gives the same bytes.
    let again = scratch("cli-again");
    run_parts(
        &root().join("samples/enneper-4m.yaml"),
        &root().join("profiles/steel-1.5.yaml"),
        &again,
    );
    assert_eq!(
        std::fs::read(dir.join("plan.json")).unwrap(),
        std::fs::read(again.join("plan.json")).unwrap()
    );
}

/// When several strips cannot be made, the refusal names the first in
/// strip order, every run: on the 1:5 pavilion with steel both A14 and
/// B14 leave no room for a splice plate (the strips are made in parallel;
/// the error must not be whichever finished first).
#[test]
fn the_first_strip_that_fails_is_the_one_named() {
    let (net, an) = analysed_sample("schwarz-d-pavilion-1to5");
    let p = support::profile("steel-1.5");
    for _ in 0..4 {
        let e = fabricate(&net, &an, &p, None, Default::default())
            .expect_err("A14 and B14 have no room for a splice plate")
            .to_string();
        assert!(e.contains("strip A14:"), "{e}");
    }
}
