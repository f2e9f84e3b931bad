//! The flat state: a planar grid comes back unchanged; on the
//! Enneper sample every length holds, the result is stationary, its energy
//! is below the start's, and it is deterministic; two-level grids have none.

use crate::support::{lamella_command, profile, root, scratch};
use glam::DVec3;
use lamella::flat::{problem, solve};
use lamella::formats::read::{self as io, ReadOptions};
use lamella::network::{Family, RawCurve, RawNetwork, Unit};
use std::path::Path;

/// Straight strips in the plane z = 0: family A along x every 300 mm,
/// family B at 70° to it, sampled every 10 mm, with file normals +z.
fn planar_70() -> RawNetwork {
    let dir_b = DVec3::new(70f64.to_radians().cos(), 70f64.to_radians().sin(), 0.0);
    let line = |id: String, family, p0: DVec3, d: DVec3, len: f64| {
        let n = (len / 10.0).round() as usize;
        RawCurve {
            id,
            family,
            points: (0..=n)
                .map(|k| p0 + d * (len * k as f64 / n as f64))
                .collect(),
            normals: Some(vec![DVec3::Z; n + 1]),
        }
    };
    let mut curves = Vec::new();
    for i in 0..5 {
        curves.push(line(
            format!("A{i}"),
            Family::A,
            DVec3::new(-400.0, 300.0 * i as f64, 0.0),
            DVec3::X,
            2600.0,
        ));
    }
    for j in 0..6 {
        // Through (300 j, 0) and on across every A line.
        let p0 = DVec3::new(300.0 * j as f64, 0.0, 0.0) - dir_b * 150.0;
        curves.push(line(format!("B{j}"), Family::B, p0, dir_b, 1600.0));
    }
    RawNetwork {
        name: "planar-70".into(),
        unit: Unit::Mm,
        tolerance: None,
        precision: None,
        curves,
    }
}

#[test]
fn a_planar_grid_comes_back_unchanged_with_zero_rotations() {
    let (_, an) = crate::support::run(planar_70());
    let pr = problem(&an, &profile("steel-1.5")).expect("problem");
    assert_eq!(pr.nodes.len(), 30);
    let st = solve(&pr);
    assert!(st.converged, "{st:?}");
    for n in &st.nodes {
        assert!(
            (n.angle_deg - 70.0).abs() < 1e-6,
            "node {}: {}",
            n.node,
            n.angle_deg
        );
        assert!(
            n.rotation_deg.abs() < 1e-6,
            "node {}: {}",
            n.node,
            n.rotation_deg
        );
    }
    assert!(st.energy_nmm < 1e-9, "{}", st.energy_nmm);
    // Congruent to the erected grid: every pairwise distance kept.
    for (i, a) in pr.nodes.iter().enumerate() {
        for (j, b) in pr.nodes.iter().enumerate().skip(i + 1) {
            let (p, q) = (st.nodes[i].position_mm, st.nodes[j].position_mm);
            let flat = (p[0] - q[0]).hypot(p[1] - q[1]);
            let erected = a.position_world_mm.distance(b.position_world_mm);
            assert!(
                (flat - erected).abs() < 1e-6,
                "{i}-{j}: {flat} vs {erected}"
            );
        }
    }
}

#[test]
fn enneper_flat_state_keeps_lengths_is_stationary_and_lowers_the_energy() {
    let path = root().join("samples/enneper-4m.yaml");
    let net = io::read_network(&path, ReadOptions::default()).expect("read");
    let an = lamella::analyze(&net, lamella::AnalysisOptions::for_network(&net)).expect("analyze");
    let pr = problem(&an, &profile("steel-1.5")).expect("problem");
    let st = solve(&pr);
    // Every node-to-node length, measured independently on the result.
    let pos: std::collections::HashMap<usize, [f64; 2]> =
        st.nodes.iter().map(|n| (n.node, n.position_mm)).collect();
    let mut checked = 0;
    for s in &pr.strips {
        for (k, l) in s.lengths_mm.iter().enumerate() {
            let (a, b) = (
                pos[&pr.nodes[s.nodes[k]].id],
                pos[&pr.nodes[s.nodes[k + 1]].id],
            );
            let d = (a[0] - b[0]).hypot(a[1] - b[1]);
            assert!(
                ((d - l) / l).abs() < 1e-6,
                "{} segment {k}: {d} vs {l}",
                s.id
            );
            checked += 1;
        }
    }
    assert!(checked > 100);
    assert!(
        st.gradient_norm < 1e-6,
        "projected gradient {}",
        st.gradient_norm
    );
    assert!(st.converged);
    assert!(
        st.energy_nmm <= st.start_energy_nmm,
        "{} > {}",
        st.energy_nmm,
        st.start_energy_nmm
    );
    assert!(st.objective.0 <= st.objective.1);
    // Deterministic.
    assert_eq!(solve(&pr), st);
    let worst = st
        .max_rotation()
        .map(|i| st.nodes[i].rotation_deg.abs())
        .expect("nodes");
    eprintln!(
        "enneper-4m flat: energy {:.6} N·mm (start {:.6}), largest rotation {worst:.2}°, footprint {:.0} × {:.0} mm, {} iterations, gradient {:.1e}",
        st.energy_nmm, st.start_energy_nmm, st.footprint_mm[0], st.footprint_mm[1], st.iterations, st.gradient_norm
    );
    assert!(worst > 1.0 && worst < 90.0);
}

#[test]
fn two_level_grids_have_no_flat_state() {
    let (_, an) = crate::support::run(planar_70());
    let e = problem(&an, &profile("poplar-ply-4"))
        .expect_err("two-level")
        .to_string();
    assert!(e.contains("two-level") && e.contains("flat"), "{e}");
}

/// `lamella flat` writes plan.json with `flat` and flat.svg, the same bytes
/// twice; a two-level profile exits 1 with one line.
#[test]
fn flat_command_writes_the_same_bytes_twice() {
    let tmp = scratch("command");
    let run = |profile: &str, out: &Path| {
        lamella_command()
            .args(["flat", "samples/enneper-4m.yaml", "--profile"])
            .arg(format!("profiles/{profile}.yaml"))
            .arg("--out")
            .arg(out)
            .output()
            .expect("run")
    };
    let (a, b) = (tmp.join("flat-a"), tmp.join("flat-b"));
    for d in [&a, &b] {
        let o = run("steel-1.5", d);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let stdout = String::from_utf8_lossy(&o.stdout);
        assert!(
            stdout.contains("largest rotation") && stdout.contains("PASS"),
            "{stdout}"
        );
    }
    for f in ["plan.json", "flat.svg"] {
        let (x, y) = (
            std::fs::read(a.join(f)).expect("a"),
            std::fs::read(b.join(f)).expect("b"),
        );
        assert!(x == y, "{f} differs");
    }
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(a.join("plan.json")).expect("plan")).expect("json");
    let flat = &plan["flat"];
    assert_eq!(flat["converged"], true);
    assert_eq!(flat["nodes"].as_array().expect("nodes").len(), 121);
    let o = run("poplar-ply-4", &tmp.join("flat-c"));
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("joint.system") && err.contains("two-level"),
        "{err}"
    );
}

/// Slots swept over each node's own rotation (flat → erected) are narrower
/// than those swept over the blanket ±60° wherever the node turns less; the
/// swept range is exactly the rotation.
#[test]
fn slots_from_the_flat_state_are_narrower_where_joints_turn_less() {
    let path = root().join("samples/enneper-4m.yaml");
    let net = io::read_network(&path, ReadOptions::default()).expect("read");
    let an = lamella::analyze(&net, lamella::AnalysisOptions::for_network(&net)).expect("analyze");
    let steel = profile("steel-1.5");
    let st = solve(&problem(&an, &steel).expect("problem"));
    let rot = st.rotations();
    let blanket = lamella::fabricate::fabricate(&net, &an, &steel, None, Default::default())
        .expect("blanket");
    let flat = lamella::fabricate::fabricate(&net, &an, &steel, Some(&rot), Default::default())
        .expect("from flat");
    let mut compared = 0;
    for (a, b) in blanket.parts.iter().zip(&flat.parts) {
        assert_eq!(a.id, b.id);
        let slots = |p: &lamella::fabricate::part::Part| {
            p.features
                .iter()
                .filter(|f| f.kind == lamella::fabricate::part::FeatureKind::Slot)
                // End slots (edge strips) do not turn with the joints.
                .filter(|f| f.edge != Some(lamella::fabricate::part::SlotEdge::End))
                .cloned()
                .collect::<Vec<_>>()
        };
        // Per node: the total slot width (a wide sweep may merge spans).
        let width_at = |fs: &[lamella::fabricate::part::Feature]| {
            let mut m: std::collections::BTreeMap<usize, f64> = Default::default();
            for f in fs {
                *m.entry(f.node.expect("slot node")).or_default() += f.width_mm;
            }
            m
        };
        let (sa, sb) = (slots(a), slots(b));
        for f in &sb {
            let node = f.node.expect("slot node");
            let r = rot[&node];
            let (lo, hi) = f.angle_range_deg.expect("range");
            assert!(
                ((hi - lo) - r.abs()).abs() < 1e-6,
                "node {node}: {lo}..{hi} vs {r}"
            );
        }
        let (wa, wb) = (width_at(&sa), width_at(&sb));
        assert_eq!(wa.keys().collect::<Vec<_>>(), wb.keys().collect::<Vec<_>>());
        for (node, w_blanket) in &wa {
            if rot[node].abs() < steel.joint.rotation_tolerance_deg {
                assert!(
                    wb[node] < w_blanket - 0.01,
                    "{} node {node}: {} vs {w_blanket}",
                    a.id,
                    wb[node]
                );
            }
            compared += 1;
        }
    }
    assert!(compared > 300, "{compared}");
}

/// A profile whose slots allow only ±10°, and one whose 40 mm lamellas
/// cannot bend flat: `flat` fails naming the node or the strip (exit 3);
/// `parts --slots-from-flat` stops naming the node (exit 1, one line).
#[test]
fn joints_past_the_tolerance_and_strips_that_break_flat_are_named() {
    let tmp = scratch("limits");
    let steel = std::fs::read_to_string(root().join("profiles/steel-1.5.yaml")).expect("steel");
    let tight = tmp.join("steel-tight.yaml");
    std::fs::write(
        &tight,
        steel.replace(
            "rotation_tolerance_deg: 60.0",
            "rotation_tolerance_deg: 10.0",
        ),
    )
    .expect("write");
    let thick = tmp.join("steel-thick.yaml");
    std::fs::write(
        &thick,
        steel.replace("thickness_mm: 1.5\n", "thickness_mm: 40.0\n"),
    )
    .expect("write");
    let run = |args: &[&str]| lamella_command().args(args).output().expect("run");
    let out = tmp.join("o").to_string_lossy().into_owned();
    let o = run(&[
        "flat",
        "samples/enneper-4m.yaml",
        "--profile",
        &tight.to_string_lossy(),
        "--out",
        &out,
    ]);
    assert_eq!(o.status.code(), Some(3));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("FAIL: node 140 turns 15.22°") && stdout.contains("tolerance 10°"),
        "{stdout}"
    );
    let o = run(&[
        "parts",
        "samples/enneper-4m.yaml",
        "--profile",
        &tight.to_string_lossy(),
        "--out",
        &out,
        "--slots-from-flat",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("node") && err.contains("past the profile's rotation tolerance 10°"),
        "{err}"
    );
    let o = run(&[
        "flat",
        "samples/enneper-4m.yaml",
        "--profile",
        &thick.to_string_lossy(),
        "--out",
        &out,
    ]);
    assert_eq!(o.status.code(), Some(3));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("is overstressed while flat"), "{stdout}");
}

/// A strip that crosses only one other has no direction of its own in the
/// flat state: its joint is free and lies flat at its erected angle. One
/// crossing alone, and one A strip crossing 15 B strips in a plane, have a
/// flat state with every joint at 0° rotation (they used to fail with "not a
/// finite number", and the slots from that flat state with "the joint turns
/// 90°").
#[test]
fn strips_with_one_node_lie_flat_at_their_erected_angle() {
    let dir = scratch("one-node-strips");
    let mut single = "units: mm\ncurves:\n".to_string();
    single += "  - id: A00\n    family: A\n    points: [[0, -1000, 0], [0, 1000, 0]]\n";
    single += "  - id: B00\n    family: B\n    points: [[-1000, 0, 0], [1000, 0, 0]]\n";
    let mut comb = "units: mm\ncurves:\n".to_string();
    comb += "  - id: A00\n    family: A\n    points: [[0, -100, 0], [3000, -100, 0]]\n";
    for k in 0..15 {
        let x = 100 + 180 * k;
        comb += &format!(
            "  - id: B{k:02}\n    family: B\n    points: [[{x}, -600, 0], [{x}, 600, 0]]\n"
        );
    }
    let steel = root().join("profiles/steel-1.5.yaml");
    for (name, text, nodes) in [("single", single, 1), ("comb", comb, 15)] {
        let network = dir.join(format!("{name}.yaml"));
        std::fs::write(&network, text).expect("write network");
        let net = io::read_network(&network, ReadOptions::default()).expect("read");
        let an =
            lamella::analyze(&net, lamella::AnalysisOptions::for_network(&net)).expect("analyse");
        let st = solve(&problem(&an, &profile("steel-1.5")).expect("problem"));
        assert!(st.converged, "{name}");
        assert_eq!(st.nodes.len(), nodes, "{name}");
        for n in &st.nodes {
            assert_eq!(n.rotation_deg, 0.0, "{name}: node {}", n.node);
            assert!((n.angle_deg - 90.0).abs() < 1e-9, "{name}: node {}", n.node);
        }
        assert!(
            st.gradient_norm.is_finite() && st.max_length_error < 1e-9,
            "{name}"
        );
        let out = dir.join(format!("{name}-flat"));
        let o = lamella_command()
            .args(["flat".as_ref(), network.as_os_str(), "--profile".as_ref()])
            .args([steel.as_os_str(), "--out".as_ref(), out.as_os_str()])
            .output()
            .expect("run");
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
        let o = lamella_command()
            .args(["parts".as_ref(), network.as_os_str(), "--profile".as_ref()])
            .args([
                steel.as_os_str(),
                "--out".as_ref(),
                dir.join(format!("{name}-parts")).as_os_str(),
            ])
            .arg("--slots-from-flat")
            .output()
            .expect("run");
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

/// A deep Enneper (1 m per unit over |u ± v| ≤ 1.1, strips 150 mm apart):
/// the projection onto its plane folds at the corners, where the surface
/// turns past vertical, and the minimisation from it stopped after 216
/// iterations "NOT converged" with a joint at 0.29°. Now it converges, no
/// joint folded, every rotation within the steel profile's ±60°; were it to
/// fail, `flat` would state in one line the least rotation it found (exit
/// 3), never "NOT converged".
#[test]
fn a_deep_enneper_converges_with_no_joint_folded() {
    let dir = scratch("deep-enneper");
    let spec = dir.join("deep.trace.yaml");
    std::fs::write(
        &spec,
        "name: enneper-deep\nsurface: enneper\nscale_mm: 1000\nseed: [0.0, 0.0]\nspacing_mm: 150\ndesign: central\nclip:\n  parameters:\n    polygon: [[1.1, 0], [0, 1.1], [-1.1, 0], [0, -1.1]]\nsampling:\n  step_mm: 25\n",
    )
    .expect("write spec");
    let network = dir.join("deep.yaml");
    let o = lamella_command()
        .args(["trace".as_ref(), spec.as_os_str(), "--out".as_ref()])
        .arg(&network)
        .output()
        .expect("trace");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let net = io::read_network(&network, ReadOptions::default()).expect("read");
    let an = lamella::analyze(&net, lamella::AnalysisOptions::for_network(&net)).expect("analyse");
    let pr = problem(&an, &profile("steel-1.5")).expect("problem");
    assert_eq!(pr.nodes.len(), 169);
    let st = solve(&pr);
    assert!(st.converged, "gradient {}", st.gradient_norm);
    assert_eq!(st.least_rotation_deg, None);
    assert!(st.max_length_error < 1e-9, "{}", st.max_length_error);
    for n in &st.nodes {
        // Folded would be a flat angle past 0° or 180°: a rotation near 90°.
        assert!(n.rotation_deg.abs() < 60.0, "node {}: {n:?}", n.node);
    }
    assert!(st.energy_nmm <= st.start_energy_nmm);
    assert_eq!(solve(&pr), st);
    let steel = root().join("profiles/steel-1.5.yaml");
    let o = lamella_command()
        .args(["flat".as_ref(), network.as_os_str(), "--profile".as_ref()])
        .args([steel.as_os_str(), "--out".as_ref()])
        .arg(dir.join("flat"))
        .output()
        .expect("flat");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.contains(", converged (") && !stdout.contains("NOT converged"),
        "{stdout}"
    );
    assert!(stdout.contains("\nPASS: "), "{stdout}");
}

/// The catenoid's grid (its strips close around the neck) reaches no
/// stationary flat state; the least-rotation layout holds its lengths
/// within the slots but is not at rest, so the verdict fails and says so.
#[test]
fn a_layout_not_at_rest_never_passes() {
    let out = scratch("flat-not-at-rest");
    let path = root().join("samples/catenoid.yaml");
    let prof = root().join("profiles/steel-1.5.yaml");
    let (code, stdout, stderr) = crate::support::lamella(&[
        "flat".as_ref(),
        path.as_os_str(),
        "--profile".as_ref(),
        prof.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert_eq!(code, Some(3), "{stdout}{stderr}");
    assert!(
        stdout.contains("laid out for least rotation"),
        "the first line says the fallback was used: {stdout}"
    );
    let verdict = stdout.lines().last().unwrap_or_default();
    assert!(
        verdict.starts_with("FAIL: no flat state at rest found: a layout within ±")
            && verdict.contains("not stationary"),
        "{verdict}"
    );
    assert!(!stdout.contains("PASS"), "{stdout}");
}
