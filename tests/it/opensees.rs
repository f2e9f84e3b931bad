//! lamella's frame solver against OpenSees: each model is exported as an
//! OpenSeesPy script (`structure::opensees::script`), run with python3,
//! and every node's displacements and every support's reaction are held
//! to lamella's `solve_static` within 1 % of the load set's largest
//! displacement (translations and rotations apart) and reaction (forces
//! and moments apart), per component. The models: an oblique cantilever,
//! a simply supported strip under a uniform load, a two-strip grillage
//! with a link, a space frame with an inclined roller, and a shallow 4 × 4
//! dome of two layers of strips on rigid end offsets, bolted by links.
//! Without openseespy the comparison is skipped (CI sets
//! `LAMELLA_REQUIRE_OPENSEES` and fails instead).

use crate::support::{scratch, tools};
use glam::{DMat3, DVec3};
use lamella::structure::model::{
    Beam, Cable, ElementLoad, FrameModel, InitialForces, Link, LoadSet, NodeLoad, PressureLoad,
    Section, Support,
};
use lamella::structure::opensees::{model_json, script};
use lamella::structure::solve::solve_static;
use lamella::structure::tension::solve_tension_only;
use serde_json::Value;
use std::process::Command;

const E: f64 = 210_000.0;
const G: f64 = 81_000.0;

fn strip() -> Section {
    let (t, h) = (1.5, 50.0);
    Section {
        e_mpa: E,
        g_mpa: G,
        area_mm2: t * h,
        i_y_mm4: t * h * h * h / 12.0,
        i_z_mm4: h * t * t * t / 12.0,
        j_mm4: h * t * t * t / 3.0 * (1.0 - 0.63 * t / h),
    }
}

fn support(node: usize, fixed: [bool; 6]) -> Support {
    Support {
        node,
        fixed,
        along: None,
    }
}

fn beam(a: usize, b: usize, z_axis: DVec3) -> Beam {
    Beam {
        nodes: [a, b],
        section: 0,
        z_axis,
        initial: InitialForces::default(),
        offsets_mm: [DVec3::ZERO; 2],
    }
}

fn member(a: DVec3, b: DVec3, n: usize, z_axis: DVec3) -> FrameModel {
    FrameModel {
        nodes_mm: (0..=n).map(|i| a.lerp(b, i as f64 / n as f64)).collect(),
        sections: vec![strip()],
        beams: (0..n).map(|i| beam(i, i + 1, z_axis)).collect(),
        links: vec![],
        cables: vec![],
        supports: vec![],
    }
}

fn node_load(name: &str, node: usize, force_n: DVec3, moment_nmm: DVec3) -> LoadSet {
    LoadSet {
        name: name.into(),
        nodes: vec![NodeLoad {
            node,
            force_n,
            moment_nmm,
        }],
        ..Default::default()
    }
}

fn cantilever() -> (FrameModel, Vec<LoadSet>) {
    let dir = DVec3::new(1.0, 2.0, 2.0) / 3.0;
    let a = DVec3::new(100.0, -50.0, 20.0);
    let mut m = member(a, a + dir * 1200.0, 3, DVec3::new(0.3, -0.2, 1.0));
    m.supports.push(support(0, [true; 6]));
    let loads = vec![
        node_load("across", 3, DVec3::new(2.0, -1.0, 0.0), DVec3::ZERO),
        node_load(
            "mixed",
            3,
            DVec3::new(-3.0, 5.0, 40.0),
            DVec3::new(100.0, 0.0, -50.0),
        ),
    ];
    (m, loads)
}

fn simply_supported() -> (FrameModel, Vec<LoadSet>) {
    let n = 4;
    let mut m = member(DVec3::ZERO, DVec3::X * 2000.0, n, DVec3::Z);
    m.supports = vec![
        support(0, [true, true, true, true, false, false]),
        support(n, [false, true, true, false, false, false]),
    ];
    let loads = LoadSet {
        name: "q".into(),
        beams: (0..n)
            .map(|beam| ElementLoad {
                beam,
                force_n_per_mm: DVec3::new(0.0, 0.002, -0.01),
            })
            .collect(),
        ..Default::default()
    };
    (m, vec![loads])
}

fn grillage() -> (FrameModel, Vec<LoadSet>) {
    let (la, lb) = (3000.0, 2000.0);
    let m = FrameModel {
        nodes_mm: vec![
            DVec3::new(-la / 2.0, 0.0, 0.0),
            DVec3::ZERO,
            DVec3::new(la / 2.0, 0.0, 0.0),
            DVec3::new(0.0, -lb / 2.0, 0.0),
            DVec3::new(0.0, lb / 2.0, 0.0),
            DVec3::ZERO,
        ],
        sections: vec![strip()],
        beams: vec![
            beam(0, 1, DVec3::Z),
            beam(1, 2, DVec3::Z),
            beam(3, 5, DVec3::Z),
            beam(5, 4, DVec3::Z),
        ],
        links: vec![Link {
            nodes: [1, 5],
            frame: DMat3::IDENTITY,
            translation_n_per_mm: [1e9; 3],
            rotation_nmm_per_rad: [1e13; 3],
        }],
        cables: vec![],
        supports: vec![
            support(0, [true, true, true, true, false, false]),
            support(2, [false, true, true, false, false, false]),
            support(3, [true, true, true, false, true, false]),
            support(4, [true, false, true, false, false, false]),
        ],
    };
    let loads = vec![
        node_load("P", 1, -DVec3::Z * 40.0, DVec3::ZERO),
        node_load(
            "eccentric",
            5,
            DVec3::new(1.0, 2.0, -30.0),
            DVec3::X * 500.0,
        ),
    ];
    (m, loads)
}

fn space_frame() -> (FrameModel, Vec<LoadSet>) {
    let m = FrameModel {
        nodes_mm: vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2000.0, 0.0, 0.0),
            DVec3::new(1000.0, 1700.0, 0.0),
            DVec3::new(1000.0, 600.0, 1500.0),
            DVec3::new(1000.0, 600.0, 1500.0),
        ],
        sections: vec![strip()],
        beams: vec![
            beam(0, 3, DVec3::Y),
            beam(1, 3, DVec3::Y),
            beam(2, 4, DVec3::X),
            beam(0, 1, DVec3::Z),
            beam(1, 2, DVec3::Z),
        ],
        links: vec![Link {
            nodes: [3, 4],
            frame: DMat3::from_axis_angle(DVec3::new(1.0, 1.0, 0.0).normalize(), 0.4),
            translation_n_per_mm: [1e6; 3],
            rotation_nmm_per_rad: [1e9; 3],
        }],
        cables: vec![],
        supports: vec![
            support(0, [true; 6]),
            support(1, [true, true, true, false, false, false]),
            Support {
                node: 2,
                fixed: [false, false, true, false, false, false],
                along: Some(DVec3::new(1.0, -1.0, 0.3)),
            },
        ],
    };
    let loads = LoadSet {
        name: "mixed".into(),
        nodes: vec![NodeLoad {
            node: 3,
            force_n: DVec3::new(20.0, -10.0, -60.0),
            moment_nmm: DVec3::new(500.0, 0.0, -300.0),
        }],
        beams: vec![
            ElementLoad {
                beam: 0,
                force_n_per_mm: DVec3::new(0.0, 0.0, -0.02),
            },
            ElementLoad {
                beam: 4,
                force_n_per_mm: DVec3::new(0.01, 0.0, -0.01),
            },
        ],
        ..Default::default()
    };
    (m, vec![loads])
}

/// A shallow dome z = f·(1 − (x² + y²)/r²) on a 4 × 4 grid of 500 mm bays:
/// strips along x above the surface and along y below it, each joint a
/// node per layer, the strips meeting their nodes through rigid end
/// offsets of half their height along the normal, the two nodes of a joint
/// bound by a bolt (a link: stiff across, soft in its own rotation), each
/// bay in two elements. Boundary joints pinned (both layers), one corner
/// on an inclined roller instead.
fn dome() -> (FrameModel, Vec<LoadSet>) {
    let (bay, f, r) = (500.0, 300.0, 2000.0);
    let n = 4usize;
    let surface = |x: f64, y: f64| {
        let (x, y) = (x - 0.5 * n as f64 * bay, y - 0.5 * n as f64 * bay);
        DVec3::new(x, y, f * (1.0 - (x * x + y * y) / (r * r)))
    };
    let normal =
        |p: DVec3| DVec3::new(2.0 * f * p.x / (r * r), 2.0 * f * p.y / (r * r), 1.0).normalize();
    let half_h = 25.0;
    let mut m = FrameModel {
        sections: vec![strip()],
        ..Default::default()
    };
    // Joint (i, j): node of layer 0 (x strips) and of layer 1 (y strips).
    let mut joint = vec![[0usize; 2]; (n + 1) * (n + 1)];
    let at = |i: usize, j: usize| surface(i as f64 * bay, j as f64 * bay);
    for j in 0..=n {
        for i in 0..=n {
            let p = at(i, j);
            let a = m.nodes_mm.len();
            m.nodes_mm.push(p);
            m.nodes_mm.push(p);
            joint[j * (n + 1) + i] = [a, a + 1];
            let nz = normal(p);
            let tx = DVec3::X.reject_from(nz).normalize();
            m.links.push(Link {
                nodes: [a, a + 1],
                frame: DMat3::from_cols(tx, nz.cross(tx), nz),
                translation_n_per_mm: [2e4, 2e4, 1e5],
                rotation_nmm_per_rad: [5e6, 5e6, 2e4],
            });
            let boundary = i == 0 || j == 0 || i == n || j == n;
            if boundary && !(i == n && j == n) {
                for node in [a, a + 1] {
                    m.supports
                        .push(support(node, [true, true, true, false, false, false]));
                }
            }
            if i == n && j == n {
                m.supports
                    .push(support(a, [false, false, true, false, false, false]));
                m.supports.push(Support {
                    node: a,
                    fixed: [false; 6],
                    along: Some(DVec3::new(1.0, 1.0, 0.0)),
                });
                m.supports.push(Support {
                    node: a,
                    fixed: [false; 6],
                    along: Some(DVec3::new(1.0, -1.0, 0.2)),
                });
                m.supports
                    .push(support(a + 1, [true, true, true, false, false, false]));
            }
        }
    }
    // Strips: layer 0 along x (offset +h/2), layer 1 along y (−h/2); a
    // middle node on the strip's own line halves each bay.
    for (layer, side) in [(0usize, half_h), (1, -half_h)] {
        for line in 0..=n {
            for k in 0..n {
                let (ij0, ij1) = if layer == 0 {
                    ((k, line), (k + 1, line))
                } else {
                    ((line, k), (line, k + 1))
                };
                let (p0, p1) = (at(ij0.0, ij0.1), at(ij1.0, ij1.1));
                let (o0, o1) = (normal(p0) * side, normal(p1) * side);
                let mid_surface = surface(
                    0.5 * (ij0.0 + ij1.0) as f64 * bay,
                    0.5 * (ij0.1 + ij1.1) as f64 * bay,
                );
                let mid = mid_surface + normal(mid_surface) * side;
                let mid_node = m.nodes_mm.len();
                m.nodes_mm.push(mid);
                let a = joint[ij0.1 * (n + 1) + ij0.0][layer];
                let b = joint[ij1.1 * (n + 1) + ij1.0][layer];
                let nz = normal(mid_surface);
                m.beams.push(Beam {
                    nodes: [a, mid_node],
                    section: 0,
                    z_axis: nz,
                    initial: InitialForces::default(),
                    offsets_mm: [o0, DVec3::ZERO],
                });
                m.beams.push(Beam {
                    nodes: [mid_node, b],
                    section: 0,
                    z_axis: nz,
                    initial: InitialForces::default(),
                    offsets_mm: [DVec3::ZERO, o1],
                });
            }
        }
    }
    let weight = LoadSet {
        name: "G+S".into(),
        beams: (0..m.beams.len())
            .map(|beam| ElementLoad {
                beam,
                force_n_per_mm: DVec3::new(0.0, 0.0, -0.0006),
            })
            .collect(),
        nodes: joint
            .iter()
            .map(|j| NodeLoad {
                node: j[0],
                force_n: DVec3::new(0.0, 0.0, -20.0),
                moment_nmm: DVec3::ZERO,
            })
            .collect(),
        ..Default::default()
    };
    let wind = LoadSet {
        name: "W".into(),
        pressures: (0..m.beams.len())
            .filter(|b| b % 3 == 0)
            .map(|beam| PressureLoad {
                beam,
                n_per_mm: 0.004,
            })
            .collect(),
        nodes: vec![NodeLoad {
            node: joint[2 * (n + 1) + 1][1],
            force_n: DVec3::new(15.0, -5.0, 0.0),
            moment_nmm: DVec3::new(0.0, 200.0, 0.0),
        }],
        ..Default::default()
    };
    (m, vec![weight, wind])
}

/// Whether openseespy is there (or required).
fn have_opensees() -> bool {
    tools::present(
        tools::runs("python3", &["-c", "import openseespy.opensees"]),
        "LAMELLA_REQUIRE_OPENSEES",
        "openseespy",
        "python3 -m pip install openseespy",
        "the comparison with OpenSees",
    )
}

fn vec3(v: &Value) -> DVec3 {
    DVec3::new(
        v[0].as_f64().unwrap(),
        v[1].as_f64().unwrap(),
        v[2].as_f64().unwrap(),
    )
}

/// Runs `model`'s script and compares with lamella; returns the largest
/// difference relative to its scale over every load set.
fn compare(name: &str, model: &FrameModel, load_sets: &[LoadSet]) -> f64 {
    let dir = scratch(name);
    let path = dir.join("opensees.py");
    std::fs::write(&path, script(model, load_sets).unwrap()).unwrap();
    std::fs::write(
        dir.join("model.json"),
        model_json(model, load_sets).unwrap(),
    )
    .unwrap();
    let results = dir.join("results.json");
    let o = Command::new("python3")
        .arg(&path)
        .arg(&results)
        .current_dir(&dir)
        .output()
        .expect("python3");
    assert!(
        o.status.success(),
        "{name}: OpenSees failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let got: Value = serde_json::from_slice(&std::fs::read(&results).unwrap()).unwrap();
    let sets = got["load_sets"].as_array().unwrap();
    assert_eq!(sets.len(), load_sets.len());
    let (lo, hi) = model.nodes_mm.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let extent = (hi - lo).length();
    let mut worst: f64 = 0.0;
    for (set, loads) in sets.iter().zip(load_sets) {
        assert_eq!(set["name"], loads.name.as_str());
        let ours = if model.cables.is_empty() {
            solve_static(model, loads).unwrap()
        } else {
            solve_tension_only(model, loads).unwrap().result
        };
        let theirs = set["displacements"].as_array().unwrap();
        assert_eq!(theirs.len(), model.nodes_mm.len());
        for part in [0..3, 3..6] {
            let scale = ours
                .displacements
                .iter()
                .map(|d| DVec3::from_slice(&d[part.clone()]).length())
                .fold(0.0, f64::max);
            assert!(scale > 0.0, "{name}/{}: nothing moves", loads.name);
            for (node, (d, t)) in ours.displacements.iter().zip(theirs).enumerate() {
                for k in part.clone() {
                    let t = t[k].as_f64().unwrap();
                    let rel = (d[k] - t).abs() / scale;
                    worst = worst.max(rel);
                    assert!(
                        rel <= 0.01,
                        "{name}/{}: node {node} dof {k}: lamella {} against OpenSees {t} \
                         (largest {scale})",
                        loads.name,
                        d[k]
                    );
                }
            }
        }
        let reactions = set["reactions"].as_array().unwrap();
        assert_eq!(reactions.len(), ours.reactions.len());
        let force_scale = ours
            .reactions
            .iter()
            .map(|r| r.force_n.length())
            .fold(0.0, f64::max);
        // Pinned supports carry no moment: round-off below 1e-9 of the
        // largest force times the model's size is zero.
        let moment_scale = ours
            .reactions
            .iter()
            .map(|r| r.moment_nmm.length())
            .fold(1e-9 * force_scale * extent, f64::max);
        let mut ours_sorted = ours.reactions.clone();
        ours_sorted.sort_by_key(|r| r.node);
        for (r, t) in ours_sorted.iter().zip(reactions) {
            assert_eq!(t["node"].as_u64().unwrap() as usize, r.node);
            for (mine, other, scale, what) in [
                (r.force_n, vec3(&t["force_n"]), force_scale, "force"),
                (r.moment_nmm, vec3(&t["moment_nmm"]), moment_scale, "moment"),
            ] {
                if scale == 0.0 {
                    continue;
                }
                for k in 0..3 {
                    let rel = (mine[k] - other[k]).abs() / scale;
                    worst = worst.max(rel);
                    assert!(
                        rel <= 0.01,
                        "{name}/{}: reaction {what} at node {}: lamella {mine} against \
                         OpenSees {other} (largest {scale})",
                        loads.name,
                        r.node
                    );
                }
            }
        }
    }
    eprintln!("{name}: largest difference from OpenSees {worst:.1e} of the largest value");
    worst
}

#[test]
fn the_export_is_deterministic_and_names_every_element() {
    let (m, loads) = dome();
    let a = script(&m, &loads).unwrap();
    assert_eq!(a, script(&m, &loads).unwrap());
    assert_eq!(
        a.matches("ops.element('elasticBeamColumn'").count(),
        m.beams.len()
    );
    // Links plus the two inclined rollers.
    assert_eq!(
        a.matches("ops.element('zeroLength'").count(),
        m.links.len() + 2
    );
    assert_eq!(a.matches("'-jntOffset'").count(), m.beams.len());
    let j: Value = serde_json::from_str(&model_json(&m, &loads).unwrap()).unwrap();
    assert_eq!(j["beams"].as_array().unwrap().len(), m.beams.len());
    assert_eq!(j["roller_springs"].as_array().unwrap().len(), 2);
    // A load on an element that does not exist is an error, not a script.
    let bad = LoadSet {
        name: "bad".into(),
        beams: vec![ElementLoad {
            beam: m.beams.len(),
            force_n_per_mm: DVec3::Z,
        }],
        ..Default::default()
    };
    let err = script(&m, std::slice::from_ref(&bad))
        .unwrap_err()
        .to_string();
    assert!(err.contains("load set bad"), "{err}");
    // So is a combination whose case does (its parts are checked before
    // they are summed for the files).
    let combination = |name: &str, part: LoadSet, factor: f64| LoadSet {
        name: name.into(),
        parts: vec![(std::sync::Arc::new(part), factor)],
        ..Default::default()
    };
    let far = LoadSet {
        beams: vec![ElementLoad {
            beam: usize::MAX,
            force_n_per_mm: DVec3::Z,
        }],
        ..bad
    };
    let err = model_json(&m, &[combination("worse", far, 1.5)])
        .unwrap_err()
        .to_string();
    assert!(err.contains("load set worse"), "{err}");
    // A combination is written as its factored loads.
    let case = node_load(
        "P",
        3,
        DVec3::new(1.0, -2.0, 3.0),
        DVec3::new(0.0, 0.5, 0.0),
    );
    let listed = node_load(
        "C",
        3,
        DVec3::new(1.5, -3.0, 4.5),
        DVec3::new(0.0, 0.75, 0.0),
    );
    assert_eq!(
        script(&m, &[combination("C", case.clone(), 1.5)]).unwrap(),
        script(&m, std::slice::from_ref(&listed)).unwrap()
    );
    assert_eq!(
        model_json(&m, &[combination("C", case, 1.5)]).unwrap(),
        model_json(&m, &[listed]).unwrap()
    );
}

#[test]
fn opensees_agrees_on_closed_form_models() {
    if !have_opensees() {
        return;
    }
    for (name, (m, loads)) in [
        ("cantilever", cantilever()),
        ("simply-supported", simply_supported()),
        ("grillage", grillage()),
        ("space-frame", space_frame()),
    ] {
        compare(name, &m, &loads);
    }
}

#[test]
fn opensees_agrees_on_a_dome_of_offset_strips_and_bolts() {
    if !have_opensees() {
        return;
    }
    let (m, loads) = dome();
    compare("dome", &m, &loads);
}

/// A square portal of 1 m in the x–z plane braced by its two diagonal
/// cables (6 mm² of 165 GPa, pretensioned to 1 kN), pinned at its feet and
/// held in its plane, its corners free to turn in it; the cables fixed at
/// `beside` from their nodes. Pushed sideways both ways by 5 kN (one
/// diagonal slackens), and pressed down by 3 kN a corner (both stay taut).
fn braced_portal(beside: DVec3) -> (FrameModel, Vec<LoadSet>) {
    let a = 1000.0;
    let bar = Section {
        e_mpa: E,
        g_mpa: G,
        area_mm2: 700.0,
        i_y_mm4: 5e4,
        i_z_mm4: 5e4,
        j_mm4: 1e5,
    };
    let cable = |i: usize, j: usize| Cable {
        nodes: [i, j],
        offsets_mm: [beside; 2],
        area_mm2: 6.0,
        e_mpa: 165_000.0,
        pretension_n: 1000.0,
    };
    let m = FrameModel {
        nodes_mm: vec![
            DVec3::ZERO,
            DVec3::new(a, 0.0, 0.0),
            DVec3::new(a, 0.0, a),
            DVec3::new(0.0, 0.0, a),
        ],
        sections: vec![bar],
        beams: vec![
            beam(0, 3, DVec3::Y),
            beam(1, 2, DVec3::Y),
            beam(3, 2, DVec3::Y),
        ],
        links: vec![],
        cables: vec![cable(0, 2), cable(1, 3)],
        supports: vec![
            support(0, [true, true, true, true, false, true]),
            support(1, [true, true, true, true, false, true]),
            support(2, [false, true, false, true, false, true]),
            support(3, [false, true, false, true, false, true]),
        ],
    };
    let push = |name: &str, h: f64| node_load(name, 3, DVec3::new(h, 0.0, 0.0), DVec3::ZERO);
    let mut down = node_load("down", 2, DVec3::new(0.0, 0.0, -3000.0), DVec3::ZERO);
    down.nodes
        .extend(node_load("", 3, DVec3::new(0.0, 0.0, -3000.0), DVec3::ZERO).nodes);
    (m, vec![push("push", 5000.0), push("pull", -5000.0), down])
}

/// Tension-only cables, pretensioned, exported as OpenSees trusses of an
/// elastic material with no stiffness in compression and an initial
/// strain (solved by Newton): the same displacements, reactions and taut
/// set as lamella's, with the cables at their nodes and on fittings
/// beside them (rigid links).
#[test]
fn opensees_agrees_on_a_portal_braced_by_tension_only_cables() {
    let (m, loads) = braced_portal(DVec3::ZERO);
    // Pushed, one diagonal goes slack; pressed down, both stay taut.
    let taut = |l: &LoadSet| solve_tension_only(&m, l).unwrap().taut;
    assert_eq!(taut(&loads[0]), [true, false]);
    assert_eq!(taut(&loads[1]), [false, true]);
    assert_eq!(taut(&loads[2]), [true, true]);
    if !have_opensees() {
        return;
    }
    compare("braced-portal", &m, &loads);
    let (m, loads) = braced_portal(DVec3::new(0.0, 15.0, 0.0));
    compare("braced-portal-beside", &m, &loads);
}

/// A pinned (or fixed–free) strip of 1 m in `n` elements under a unit
/// compression at its end.
fn column(n: usize, fixed_free: bool) -> (FrameModel, LoadSet) {
    let mut m = member(DVec3::ZERO, DVec3::X * 1000.0, n, DVec3::Z);
    m.supports = if fixed_free {
        vec![support(0, [true; 6])]
    } else {
        vec![
            support(0, [true, true, true, true, false, false]),
            support(n, [false, true, true, false, false, false]),
        ]
    };
    (m, node_load("P", n, -DVec3::X, DVec3::ZERO))
}

#[test]
fn opensees_finds_the_critical_factor_of_euler_columns() {
    use lamella::structure::buckling::critical_factors;
    if !have_opensees() {
        return;
    }
    for fixed_free in [false, true] {
        // lamella: 4 elements; OpenSees: each subdivided into 4 (P-Δ).
        let (m, loads) = column(4, fixed_free);
        let ours = critical_factors(&m, &loads, 1).unwrap()[0].factor;
        let (fine, fine_loads) = column(16, fixed_free);
        let name = if fixed_free {
            "euler-fixed-free"
        } else {
            "euler-pinned"
        };
        let path = scratch(name).join("opensees.py");
        std::fs::write(&path, script(&fine, &[fine_loads]).unwrap()).unwrap();
        let theirs = tools::python_json("opensees_buckling.py", &path)["alpha_cr"]
            .as_f64()
            .unwrap();
        let rel = (ours - theirs) / theirs;
        eprintln!("{name}: α_cr lamella {ours:.4} OpenSees {theirs:.4} ({rel:+.1e})");
        assert!(
            rel.abs() <= 0.02,
            "{name}: lamella {ours} against OpenSees {theirs}"
        );
    }
}

/// The shipped grids as `lamella frame` builds them (lamella chains on
/// their offset lines, joints, shear blocks or studs as links, the pavilion's
/// supports), under the pavilion's characteristic load cases (every
/// combination is a sum of them in a linear analysis): every node's
/// displacements and every support's reaction within 1 % of OpenSees'.
/// The erection state is in lamella's model and not in the script; it
/// changes a linear solve only through the elements' axial forces, which
/// the erection leaves at zero (held here).
#[test]
fn opensees_agrees_on_the_shipped_enneper_and_a_two_level_grid() {
    if !have_opensees() {
        return;
    }
    for (sample, profile) in [("enneper-4m", "steel-1.5"), ("hypar-small", "poplar-ply-4")] {
        let (built, cases, _) = crate::equilibrium::loaded_frame(
            &format!("samples/{sample}.yaml"),
            &format!("profiles/{profile}.yaml"),
        )
        .expect("the frame");
        let model = &built.model;
        assert!(
            model.beams.iter().all(|b| b.initial.axial_n == 0.0),
            "{sample}: the erection leaves an axial force"
        );
        assert!(model.links.len() + model.beams.len() > 1000, "{sample}");
        let cases: Vec<LoadSet> = cases.iter().map(|set| LoadSet::clone(set)).collect();
        let worst = compare(&format!("{sample}-{profile}"), model, &cases);
        assert!(worst <= 0.01);
    }
}

/// The shipped grids (the steel Enneper pavilion and the two-level poplar
/// hypar) under their ULS snow combination (self-weight and snow: no
/// following pressure, whose load stiffness an OpenSees nodal load
/// lacks): lamella's α_cr converges as each span is split into 4, 8 and
/// 16 elements (each refinement moves it less than half as much as the
/// one before), and OpenSees' linear buckling factor of the 16-element
/// model (`tests/tools/opensees_buckling.py`: P-Delta, the tangent's
/// definiteness bisected) is within 2 % of lamella's on that model.
/// OpenSees' P-Delta has the flexural geometric terms only, without the
/// polar term N·I_p/(A·L) of torsional buckling: lamella's flexural
/// factor ([`critical_factors_flexural`]) is what it is held to, and
/// lamella's full factor is held below it. On the steel pavilion the polar
/// term moves α_cr by 0.01 %; on the poplar hypar (a low shear modulus)
/// by 15 %. P-Delta also has no P-δ within an element, so its factor
/// converges from above, as the square of the element length. Measured:
/// the pavilion, lamella 5.533, 5.687, 5.717, OpenSees 6.604, 5.971,
/// 5.791 (+1.3 % at 16; Richardson's limits 5.725 and 5.718); the hypar,
/// lamella 5.508, 5.535, 5.542 (flexural 6.543 at 16), OpenSees 6.627
/// (+1.3 %).
#[test]
fn opensees_finds_the_critical_factor_of_the_shipped_grids() {
    use lamella::structure::buckling::{critical_factors, critical_factors_flexural};
    use lamella::structure::build::FrameOptions;
    if !have_opensees() {
        return;
    }
    for (sample, profile) in [("enneper-4m", "steel-1.5"), ("hypar-small", "poplar-ply-4")] {
        let mut factors = Vec::new();
        let mut finest = None;
        for per_span in [4, 8, 16] {
            let (built, _, combos) = crate::equilibrium::loaded_frame_with(
                &format!("samples/{sample}.yaml"),
                &format!("profiles/{profile}.yaml"),
                &FrameOptions {
                    elements_per_span: per_span,
                },
            )
            .expect("the frame");
            let combo = combos
                .into_iter()
                .find(|c| c.loads.name == "ULS S")
                .expect("the ULS snow combination");
            let alpha = critical_factors(&built.model, &combo.loads, 1).unwrap()[0].factor;
            factors.push(alpha);
            finest = Some((built.model, combo.loads, alpha));
        }
        eprintln!("{sample}: α_cr with 4, 8, 16 elements per span {factors:.4?}");
        let (d1, d2) = (factors[1] - factors[0], factors[2] - factors[1]);
        assert!(
            d2.abs() <= 0.5 * d1.abs(),
            "{sample}: α_cr does not converge: {factors:?}"
        );
        let (model, loads, full) = finest.expect("three models");
        let ours = critical_factors_flexural(&model, &loads, 1).unwrap()[0].factor;
        assert!(
            full <= ours * (1.0 + 1e-6),
            "{sample}: the polar term raised α_cr from {ours} to {full}"
        );
        let path = scratch(&format!("{sample}-alpha")).join("opensees.py");
        std::fs::write(&path, script(&model, &[loads]).unwrap()).unwrap();
        let (lo, hi) = (format!("{}", 0.9 * ours), format!("{}", 1.1 * ours));
        let theirs = tools::python_json_with("opensees_buckling.py", &path, &[&lo, &hi, "1e-3"])
            ["alpha_cr"]
            .as_f64()
            .unwrap();
        let rel = (ours - theirs) / theirs;
        eprintln!(
            "{sample}: α_cr lamella {full:.4} (flexural terms {ours:.4}) OpenSees {theirs:.4} ({rel:+.1e})"
        );
        assert!(
            rel.abs() <= 0.02,
            "{sample}: lamella {ours} against OpenSees {theirs}"
        );
    }
}

/// The braced pavilion as its loads file designs it (the Enneper in steel,
/// its cables tension-only with their pretension and fittings' offsets),
/// under the pavilion's characteristic load cases, each solved whole
/// (a cable the load slackens carries nothing): every node's displacements
/// and every support's reaction within 1 % of OpenSees' (Newton on the
/// cables' elastic-no-tension trusses).
#[test]
fn opensees_agrees_on_the_braced_enneper() {
    if !have_opensees() {
        return;
    }
    let (report, _) = crate::bracing::braced_pavilion();
    let model = &report.built.model;
    assert!(!model.cables.is_empty());
    let cases: Vec<LoadSet> = report
        .cases
        .iter()
        .map(|(set, _)| LoadSet::clone(set))
        .collect();
    let worst = compare("enneper-braced", model, &cases);
    assert!(worst <= 0.01);
}
