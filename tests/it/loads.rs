//! The loads file and its application to a frame model: EN 1990
//! combinations against a table written out by hand; load totals on a
//! hand-made 2 × 2 grid (level and tilted on a 3-4-5 slope) against the
//! areas worked out by hand; support selections; the reader's one-line
//! errors, one per bad field; the shipped pavilion file.

use crate::support::root;
use glam::DVec3;
use lamella::formats::read::loads_file;
use lamella::loads::{Action, Deflection, LoadSpec};
use lamella::structure::loads::{
    combinations, combine, deflection_limit_mm, deflection_span_mm, flattened, load_cases,
    supports, CombinationSpec,
};
use lamella::structure::model::{
    Beam, FrameModel, InitialForces, LimitState, LoadSet, LoadTargets, Section, Support,
};
use std::collections::BTreeMap;
use std::path::Path;

/// Sums agree with hand values this closely (N, relative to 1 kN).
const TOL_N: f64 = 1e-9;

// ------------------------------------------------------------ the grid

/// A 2 × 2 grid of 1 m cells, 3 × 3 joints `N{i}{j}` at (i, j) m in its own
/// plane, tilted about x so that a step along j rises 0.6 and runs 0.8 (a
/// 3-4-5 slope; `tilted = false`: level). Strips `A{j}` run along i (two
/// elements each), `B{i}` along j; the tributary areas are the cells'
/// quarters: 0.25 m² at a corner, 0.5 m² on an edge, 1 m² in the middle,
/// 4 m² in all. Every element weighs 0.1 N/mm, every joint's hardware 5 N.
fn grid(tilted: bool) -> (FrameModel, LoadTargets) {
    let (cos, sin) = if tilted { (0.8, 0.6) } else { (1.0, 0.0) };
    let normal = DVec3::new(0.0, -sin, cos);
    let index = |i: usize, j: usize| 3 * j + i;
    let mut nodes_mm = Vec::new();
    let mut tributary_mm2 = Vec::new();
    let mut node_ids = BTreeMap::new();
    for j in 0..3 {
        for i in 0..3 {
            let (x, t) = (1000.0 * i as f64, 1000.0 * j as f64);
            nodes_mm.push(DVec3::new(x, t * cos, t * sin));
            let share = |k: usize| if k == 1 { 1.0 } else { 0.5 };
            tributary_mm2.push(normal * (1e6 * share(i) * share(j)));
            node_ids.insert(format!("N{i}{j}"), index(i, j));
        }
    }
    let mut beams = Vec::new();
    let mut strip_beams = BTreeMap::new();
    for j in 0..3 {
        let mut list = Vec::new();
        for i in 0..2 {
            list.push(beams.len());
            beams.push(beam(index(i, j), index(i + 1, j), normal));
        }
        strip_beams.insert(format!("A{j}"), list);
    }
    for i in 0..3 {
        let mut list = Vec::new();
        for j in 0..2 {
            list.push(beams.len());
            beams.push(beam(index(i, j), index(i, j + 1), normal));
        }
        strip_beams.insert(format!("B{i}"), list);
    }
    let n_beams = beams.len();
    let model = FrameModel {
        nodes_mm,
        sections: vec![Section {
            e_mpa: 210_000.0,
            g_mpa: 81_000.0,
            area_mm2: 60.0,
            i_y_mm4: 18_000.0,
            i_z_mm4: 11.25,
            j_mm4: 45.0,
        }],
        beams,
        links: Vec::new(),
        cables: vec![],
        supports: Vec::new(),
    };
    let targets = LoadTargets {
        tributary_mm2,
        node_ids,
        strip_beams,
        beam_weight_n_per_mm: vec![0.1; n_beams],
        node_weight_n: vec![5.0; 9],
        // The corner's weight acts 12 mm beside it (a part on a lamella
        // tied to it).
        node_weight_lever_mm: (0..9)
            .map(|n| {
                if n == 0 {
                    DVec3::new(0.0, 12.0, 0.0)
                } else {
                    DVec3::ZERO
                }
            })
            .collect(),
        boundary_nodes: (0..9).filter(|&n| n != index(1, 1)).collect(),
    };
    (model, targets)
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

/// The total force of a load set, N: node forces plus element loads times
/// the elements' lengths.
fn total_n(set: &LoadSet, model: &FrameModel) -> DVec3 {
    let nodes: DVec3 = set.nodes.iter().map(|l| l.force_n).sum();
    let beams: DVec3 = set
        .beams
        .iter()
        .map(|l| {
            let [a, b] = model.beams[l.beam].nodes;
            l.force_n_per_mm * model.nodes_mm[a].distance(model.nodes_mm[b])
        })
        .sum();
    nodes + beams
}

fn close(got: DVec3, want: DVec3, what: &str) {
    assert!(
        (got - want).length() < TOL_N * 1e3,
        "{what}: got {got}, want {want}"
    );
}

fn spec(text: &str) -> LoadSpec {
    loads_file::parse(text, Path::new("t.yaml")).unwrap_or_else(|e| panic!("{e}"))
}

/// Cases G (self-weight and 0.05 kN/m² of cover), S 0.68, W+ 0.35,
/// W− −0.42 kN/m², then Q: a point load on the middle joint and a line
/// load on the middle A strip.
const CASES: &str = "version: 1
cases:
  - {name: G, action: permanent, surface_kn_per_m2: 0.05}
  - {name: S, action: snow, snow_kn_per_m2: 0.68}
  - {name: W+, action: wind, wind_kn_per_m2: 0.35}
  - {name: W-, action: wind, wind_kn_per_m2: -0.42}
  - name: Q
    action: imposed
    point_loads: [{node: N11, force_kn: [0, 0, -1.0]}]
    line_loads: [{strip: A1, force_kn_per_m: [0.2, 0, -0.5]}]
";

// ------------------------------------------------------------ totals

#[test]
fn load_totals_on_a_level_grid_are_the_areas_times_the_loads() {
    let (model, targets) = grid(false);
    let sets = load_cases(&spec(CASES), &model, &targets).expect("cases");
    let names: Vec<&str> = sets.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["G", "S", "W+", "W-", "Q"]);
    // G: 12 elements of 1000 mm at 0.1 N/mm = 1200 N, 9 joints of 5 N =
    // 45 N, cover 0.05 kN/m² on 4 m² = 200 N.
    close(
        total_n(&sets[0], &model),
        DVec3::new(0.0, 0.0, -1445.0),
        "G",
    );
    // S: 0.68 kN/m² on 4 m² of plan = 2.72 kN.
    close(
        total_n(&sets[1], &model),
        DVec3::new(0.0, 0.0, -2720.0),
        "S",
    );
    // W+: 0.35 kN/m² on 4 m², downward on a level roof = 1.4 kN.
    close(
        total_n(&sets[2], &model),
        DVec3::new(0.0, 0.0, -1400.0),
        "W+",
    );
    // W−: 0.42 kN/m² of suction, upward = 1.68 kN.
    close(
        total_n(&sets[3], &model),
        DVec3::new(0.0, 0.0, 1680.0),
        "W-",
    );
    // Q: 1 kN down at N11; 2 m of strip A1 at (0.2, 0, −0.5) kN/m.
    close(
        total_n(&sets[4], &model),
        DVec3::new(400.0, 0.0, -2000.0),
        "Q",
    );
    // The middle joint carries 1 m² of the 4: a quarter of the snow.
    let mid = sets[1].nodes.iter().find(|l| l.node == 4).expect("N11");
    close(mid.force_n, DVec3::new(0.0, 0.0, -680.0), "snow at N11");
    // The point load sits at N11 on top of nothing else in Q.
    let q_mid = sets[4].nodes.iter().find(|l| l.node == 4).expect("N11");
    close(q_mid.force_n, DVec3::new(0.0, 0.0, -1000.0), "Q at N11");
    // The corner's weight of 5 N acts 12 mm along +y of it: it also
    // turns the node by (0, 12, 0) × (0, 0, −5) = (−60, 0, 0) N·mm; the
    // other joints take no moment.
    for l in &sets[0].nodes {
        let want = if l.node == 0 {
            DVec3::new(-60.0, 0.0, 0.0)
        } else {
            DVec3::ZERO
        };
        close(l.moment_nmm, want, "the weight's moment");
    }
    // Self-weight: every element along −z at its weight.
    assert_eq!(sets[0].beams.len(), 12);
    assert!(sets[0]
        .beams
        .iter()
        .all(|l| l.force_n_per_mm == DVec3::new(0.0, 0.0, -0.1)));
    // Lists sorted by index.
    for s in &sets {
        assert!(s.nodes.windows(2).all(|w| w[0].node < w[1].node));
        assert!(s.beams.windows(2).all(|w| w[0].beam < w[1].beam));
    }
}

#[test]
fn on_a_tilted_grid_snow_takes_the_plan_and_wind_the_normal() {
    // 4 m² of surface on a 3-4-5 slope: 3.2 m² of plan; the upward unit
    // normal is (0, −0.6, 0.8).
    let (model, targets) = grid(true);
    let sets = load_cases(&spec(CASES), &model, &targets).expect("cases");
    // G: the elements are still 12 m long, the cover on 4 m² of surface.
    close(
        total_n(&sets[0], &model),
        DVec3::new(0.0, 0.0, -1445.0),
        "G",
    );
    // S: 0.68 kN/m² × 3.2 m² = 2.176 kN, vertical.
    close(
        total_n(&sets[1], &model),
        DVec3::new(0.0, 0.0, -2176.0),
        "S",
    );
    // W+: 0.35 × 4 = 1.4 kN against the normal: (0, +0.84, −1.12) kN.
    close(
        total_n(&sets[2], &model),
        DVec3::new(0.0, 840.0, -1120.0),
        "W+",
    );
    // W−: 0.42 × 4 = 1.68 kN along the normal: (0, −1.008, +1.344) kN.
    close(
        total_n(&sets[3], &model),
        DVec3::new(0.0, -1008.0, 1344.0),
        "W-",
    );
}

#[test]
fn a_combination_is_the_factored_sum_of_its_cases() {
    let (model, targets) = grid(false);
    let s = spec(CASES);
    let sets = load_cases(&s, &model, &targets).expect("cases");
    let all = combinations(&s);
    let pick = |name: &str| all.iter().find(|c| c.name == name).expect(name);
    // 1.35 × 1445 + 1.5 × 2720 + 0.9 × 1400 = 1950.75 + 4080 + 1260 N.
    let c = combine(&sets, pick("ULS S + 0.6W+"));
    assert_eq!(c.loads.name, "ULS S + 0.6W+");
    assert_eq!(c.limit_state, LimitState::Ultimate);
    close(
        total_n(&flattened(&c.loads), &model),
        DVec3::new(0.0, 0.0, -7290.75),
        "ULS S + 0.6W+",
    );
    // 1.0 × 1445 down, 1.5 × 1680 up: 1075 N of uplift.
    let c = combine(&sets, pick("ULS W- (G inf)"));
    close(
        total_n(&flattened(&c.loads), &model),
        DVec3::new(0.0, 0.0, 1075.0),
        "ULS W- (G inf)",
    );
    // SLS: 1445 + 1400 + 0.5 × 2720 = 4205 N.
    let c = combine(&sets, pick("SLS W+ + 0.5S"));
    assert_eq!(c.limit_state, LimitState::Serviceability);
    close(
        total_n(&flattened(&c.loads), &model),
        DVec3::new(0.0, 0.0, -4205.0),
        "SLS W+ + 0.5S",
    );
}

#[test]
fn unknown_nodes_and_strips_name_the_field_and_the_id() {
    let (model, targets) = grid(false);
    let text = CASES.replace("node: N11", "node: N77");
    let e = load_cases(&spec(&text), &model, &targets)
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "t.yaml: field `cases[4].point_loads[0].node`: no joint `N77` in the network"
    );
    let text = CASES.replace("strip: A1", "strip: C9");
    let e = load_cases(&spec(&text), &model, &targets)
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "t.yaml: field `cases[4].line_loads[0].strip`: no strip `C9` in the network"
    );
}

// ------------------------------------------------------------ combinations

/// The table for G, S, W+, W− with EN 1990's default factors, by hand.
#[test]
fn combinations_of_snow_and_wind_follow_en_1990() {
    let s = spec(
        "version: 1
cases:
  - {name: G, action: permanent}
  - {name: S, action: snow, snow_kn_per_m2: 0.68}
  - {name: W+, action: wind, wind_kn_per_m2: 0.35}
  - {name: W-, action: wind, wind_kn_per_m2: -0.42}
",
    );
    let u = LimitState::Ultimate;
    let v = LimitState::Serviceability;
    let want: Vec<Row> = vec![
        ("ULS G", u, vec![(0, 1.35)]),
        ("ULS S", u, vec![(0, 1.35), (1, 1.5)]),
        ("ULS S + 0.6W+", u, vec![(0, 1.35), (1, 1.5), (2, 0.9)]),
        ("ULS S + 0.6W-", u, vec![(0, 1.35), (1, 1.5), (3, 0.9)]),
        (
            "ULS S + 0.6W- (G inf)",
            u,
            vec![(0, 1.0), (1, 1.5), (3, 0.9)],
        ),
        ("ULS W+", u, vec![(0, 1.35), (2, 1.5)]),
        ("ULS W+ + 0.5S", u, vec![(0, 1.35), (1, 0.75), (2, 1.5)]),
        ("ULS W-", u, vec![(0, 1.35), (3, 1.5)]),
        ("ULS W- (G inf)", u, vec![(0, 1.0), (3, 1.5)]),
        ("ULS W- + 0.5S", u, vec![(0, 1.35), (1, 0.75), (3, 1.5)]),
        (
            "ULS W- + 0.5S (G inf)",
            u,
            vec![(0, 1.0), (1, 0.75), (3, 1.5)],
        ),
        ("SLS G", v, vec![(0, 1.0)]),
        ("SLS S", v, vec![(0, 1.0), (1, 1.0)]),
        ("SLS S + 0.6W+", v, vec![(0, 1.0), (1, 1.0), (2, 0.6)]),
        ("SLS S + 0.6W-", v, vec![(0, 1.0), (1, 1.0), (3, 0.6)]),
        ("SLS W+", v, vec![(0, 1.0), (2, 1.0)]),
        ("SLS W+ + 0.5S", v, vec![(0, 1.0), (1, 0.5), (2, 1.0)]),
        ("SLS W-", v, vec![(0, 1.0), (3, 1.0)]),
        ("SLS W- + 0.5S", v, vec![(0, 1.0), (1, 0.5), (3, 1.0)]),
    ];
    assert_table(&combinations(&s), &want);
}

/// A combination's expected name, limit state and (case, factor) list.
type Row = (&'static str, LimitState, Vec<(usize, f64)>);

fn assert_table(got: &[CombinationSpec], want: &[Row]) {
    let got_names: Vec<&str> = got.iter().map(|c| c.name.as_str()).collect();
    let want_names: Vec<&str> = want.iter().map(|w| w.0).collect();
    assert_eq!(got_names, want_names);
    for (g, (name, ls, factors)) in got.iter().zip(want) {
        assert_eq!(g.limit_state, *ls, "{name}");
        let cases: Vec<usize> = g.factors.iter().map(|f| f.0).collect();
        let want_cases: Vec<usize> = factors.iter().map(|f| f.0).collect();
        assert_eq!(cases, want_cases, "{name}");
        for (a, b) in g.factors.iter().zip(factors) {
            assert!(
                (a.1 - b.1).abs() < 1e-12,
                "{name}: case {} {} ≠ {}",
                a.0,
                a.1,
                b.1
            );
        }
    }
}

#[test]
fn roof_imposed_loads_stand_alone_unless_told_otherwise() {
    let cases = "cases:
  - {name: G, action: permanent}
  - {name: S, action: snow, snow_kn_per_m2: 0.68}
  - {name: Q, action: imposed, point_loads: [{node: N11, force_kn: [0, 0, -1]}]}
";
    let u = LimitState::Ultimate;
    let v = LimitState::Serviceability;
    // Category H: ψ0 = 0 and no snow or wind with it.
    let s = spec(&format!("version: 1\n{cases}"));
    assert_table(
        &combinations(&s),
        &[
            ("ULS G", u, vec![(0, 1.35)]),
            ("ULS S", u, vec![(0, 1.35), (1, 1.5)]),
            ("ULS Q", u, vec![(0, 1.35), (2, 1.5)]),
            ("SLS G", v, vec![(0, 1.0)]),
            ("SLS S", v, vec![(0, 1.0), (1, 1.0)]),
            ("SLS Q", v, vec![(0, 1.0), (2, 1.0)]),
        ],
    );
    // Told to combine, with ψ0 = 0.7 (a floor's, category A).
    let s = spec(&format!(
        "version: 1\n{cases}factors: {{psi0_imposed: 0.7, imposed_with_snow_or_wind: true, gamma_q: 1.4}}\n"
    ));
    assert_table(
        &combinations(&s),
        &[
            ("ULS G", u, vec![(0, 1.35)]),
            ("ULS S", u, vec![(0, 1.35), (1, 1.4)]),
            ("ULS S + 0.7Q", u, vec![(0, 1.35), (1, 1.4), (2, 0.98)]),
            ("ULS Q", u, vec![(0, 1.35), (2, 1.4)]),
            ("ULS Q + 0.5S", u, vec![(0, 1.35), (1, 0.7), (2, 1.4)]),
            ("SLS G", v, vec![(0, 1.0)]),
            ("SLS S", v, vec![(0, 1.0), (1, 1.0)]),
            ("SLS S + 0.7Q", v, vec![(0, 1.0), (1, 1.0), (2, 0.7)]),
            ("SLS Q", v, vec![(0, 1.0), (2, 1.0)]),
            ("SLS Q + 0.5S", v, vec![(0, 1.0), (1, 0.5), (2, 1.0)]),
        ],
    );
}

// ------------------------------------------------------------ supports

fn held(list: &[Support]) -> Vec<(usize, [bool; 6], Option<DVec3>)> {
    list.iter().map(|s| (s.node, s.fixed, s.along)).collect()
}

const PIN: [bool; 6] = [true, true, true, false, false, false];

#[test]
fn without_a_supports_section_every_boundary_joint_is_pinned() {
    let (model, targets) = grid(false);
    let s = spec("version: 1\ncases: [{name: G, action: permanent}]\n");
    let got = supports(&s, &model, &targets).expect("supports");
    let want: Vec<_> = [0, 1, 2, 3, 5, 6, 7, 8]
        .into_iter()
        .map(|n| (n, PIN, None))
        .collect();
    assert_eq!(held(&got), want);
    // Span: the plan diagonal of the 2 m square, 2828.43 mm; /300.
    let span = deflection_span_mm(&model, &got);
    assert!((span - 2000.0 * 2f64.sqrt()).abs() < 1e-9, "{span}");
    let limit = deflection_limit_mm(&s, &model, &got);
    assert!((limit - 9.428_090_415_820_634).abs() < 1e-9, "{limit}");
    // Tilted, the plan shrinks along y: √(2000² + 1600²) = 2561.25 mm.
    let (tilted, t_targets) = grid(true);
    let got = supports(&s, &tilted, &t_targets).expect("supports");
    let span = deflection_span_mm(&tilted, &got);
    assert!((span - 2_561.249_694_973_139).abs() < 1e-9, "{span}");
    // No boundary joints: the default cannot hold anything.
    let mut none = targets.clone();
    none.boundary_nodes.clear();
    let e = supports(&s, &model, &none).unwrap_err().to_string();
    assert!(
        e.starts_with("t.yaml: field `supports`: the network has no boundary joint"),
        "{e}"
    );
}

#[test]
fn supports_select_the_lowest_or_listed_joints_and_later_entries_win() {
    let (model, targets) = grid(true);
    // The j = 0 row lies at z = 0, the j = 1 row at 600 mm.
    let s = spec(
        "version: 1
cases: [{name: G, action: permanent}]
supports:
  - {at: lowest, band_mm: 1, kind: pinned}
  - {at: nodes, nodes: [N02], kind: roller, direction: [0, 0, 2]}
  - {at: nodes, nodes: [N22], kind: roller, direction: [1, 1, 0]}
  - {at: nodes, nodes: [N10], kind: fixed}
",
    );
    let got = supports(&s, &model, &targets).expect("supports");
    let diag = DVec3::new(1.0, 1.0, 0.0) / 2f64.sqrt();
    let z_only = [false, false, true, false, false, false];
    assert_eq!(
        held(&got),
        vec![
            (0, PIN, None),
            (1, [true; 6], None),
            (2, PIN, None),
            (6, z_only, None),
            (8, [false; 6], Some(diag)),
        ]
    );
    // Span: between the lowest row and the rollers, the plan diagonal.
    assert!((deflection_span_mm(&model, &got) - 2_561.249_694_973_139).abs() < 1e-9);
    // A wider band takes the second row as well.
    let s = spec(
        "version: 1
cases: [{name: G, action: permanent}]
supports: [{at: lowest, band_mm: 700, kind: pinned}]
deflection: {limit_mm: 12.5}
",
    );
    let got = supports(&s, &model, &targets).expect("supports");
    let nodes: Vec<usize> = got.iter().map(|s| s.node).collect();
    assert_eq!(nodes, [0, 1, 2, 3, 4, 5]);
    assert_eq!(deflection_limit_mm(&s, &model, &got), 12.5);
    // Unknown ids name the entry and the id.
    let s = spec(
        "version: 1
cases: [{name: G, action: permanent}]
supports: [{at: nodes, nodes: [N00, X1], kind: pinned}]
",
    );
    let e = supports(&s, &model, &targets).unwrap_err().to_string();
    assert_eq!(
        e,
        "t.yaml: field `supports[0].nodes[1]`: no joint `X1` in the network"
    );
}

#[test]
fn a_single_support_is_a_cantilever_of_twice_its_reach() {
    let (model, targets) = grid(false);
    let s = spec(
        "version: 1
cases: [{name: G, action: permanent}]
supports: [{at: nodes, nodes: [N00], kind: fixed}]
",
    );
    let got = supports(&s, &model, &targets).expect("supports");
    // From N00 the farthest joint is N22, 2828.43 mm away: span 5656.85 mm.
    let span = deflection_span_mm(&model, &got);
    assert!((span - 4000.0 * 2f64.sqrt()).abs() < 1e-9, "{span}");
}

// ------------------------------------------------------------ the reader

/// A valid file whose lines the error tests change one at a time.
const GOOD: &str = "version: 1
cases:
  - name: G
    action: permanent
  - name: S
    action: snow
    snow_kn_per_m2: 0.68
  - name: W-
    action: wind
    wind_kn_per_m2: -0.42
supports:
  - at: boundary
    kind: pinned
factors:
  psi0_snow: 0.5
  gamma_q: 1.5
deflection:
  span_over: 300
";

/// `GOOD` with `from` replaced by `to`, read: its error.
fn refused(from: &str, to: &str) -> String {
    assert!(GOOD.contains(from), "{from}");
    let text = GOOD.replacen(from, to, 1);
    match loads_file::parse(&text, Path::new("loads/bad.yaml")) {
        Ok(_) => panic!("accepted: {to}"),
        Err(e) => {
            let e = e.to_string();
            assert!(!e.contains('\n'), "one line: {e}");
            assert!(e.starts_with("loads/bad.yaml: "), "{e}");
            e
        }
    }
}

#[test]
fn the_good_file_reads_with_its_values() {
    let s = spec(GOOD);
    assert_eq!(s.cases.len(), 3);
    assert_eq!(s.cases[0].action, Action::Permanent);
    assert_eq!(s.cases[0].self_weight, 1.0, "self-weight by default in G");
    assert_eq!(s.cases[1].self_weight, 0.0);
    assert_eq!(s.cases[2].wind_kn_per_m2, -0.42);
    assert_eq!(s.deflection, Deflection::SpanOver(300.0));
}

#[test]
fn negative_snow_is_refused() {
    let e = refused("snow_kn_per_m2: 0.68", "snow_kn_per_m2: -0.2");
    assert_eq!(
        e,
        "loads/bad.yaml: field `cases[1].snow_kn_per_m2`: must be ≥ 0, got -0.2"
    );
}

#[test]
fn snow_in_a_wind_case_is_refused() {
    let e = refused("wind_kn_per_m2: -0.42", "snow_kn_per_m2: 0.5");
    assert_eq!(
        e,
        "loads/bad.yaml: field `cases[2].snow_kn_per_m2`: belongs to a case with `action: snow`, this one is `wind`"
    );
}

#[test]
fn an_unknown_action_is_refused() {
    let e = refused("action: snow", "action: rain");
    assert!(
        e.contains("line 6, column 13") && e.contains("cases[1].action: unknown variant `rain`"),
        "{e}"
    );
}

#[test]
fn an_unknown_field_is_refused() {
    let e = refused("snow_kn_per_m2: 0.68", "snow: 0.68");
    assert!(
        e.contains("line 7") && e.contains("cases[1]: unknown field `snow`"),
        "{e}"
    );
}

#[test]
fn an_unknown_support_kind_is_refused() {
    let e = refused("kind: pinned", "kind: glued");
    assert!(
        e.contains("line 13") && e.contains("supports[0].kind: unknown variant `glued`"),
        "{e}"
    );
}

#[test]
fn a_roller_without_a_direction_is_refused() {
    let e = refused("kind: pinned", "kind: roller");
    assert!(
        e.starts_with("loads/bad.yaml: field `supports[0].direction`: missing"),
        "{e}"
    );
}

#[test]
fn a_zero_direction_is_refused() {
    let e = refused("kind: pinned", "kind: roller\n    direction: [0, 0, 0]");
    assert_eq!(
        e,
        "loads/bad.yaml: field `supports[0].direction`: must not be zero"
    );
}

#[test]
fn a_direction_on_a_pin_is_refused() {
    let e = refused("kind: pinned", "kind: pinned\n    direction: [0, 0, 1]");
    assert_eq!(
        e,
        "loads/bad.yaml: field `supports[0].direction`: belongs to `kind: roller`, this entry is `kind: pinned`"
    );
}

#[test]
fn lowest_without_a_band_is_refused() {
    let e = refused("at: boundary", "at: lowest");
    assert!(
        e.starts_with("loads/bad.yaml: field `supports[0].band_mm`: missing"),
        "{e}"
    );
}

#[test]
fn psi_outside_zero_to_one_is_refused() {
    let e = refused("psi0_snow: 0.5", "psi0_snow: 1.2");
    assert_eq!(
        e,
        "loads/bad.yaml: field `factors.psi0_snow`: must be between 0 and 1, got 1.2"
    );
}

#[test]
fn gamma_below_one_is_refused() {
    let e = refused("gamma_q: 1.5", "gamma_q: 0.9");
    assert_eq!(
        e,
        "loads/bad.yaml: field `factors.gamma_q`: must be between 1 and 3, got 0.9"
    );
}

#[test]
fn empty_cases_are_refused() {
    let text = "version: 1\ncases: []\n";
    let e = loads_file::parse(text, Path::new("loads/bad.yaml"))
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "loads/bad.yaml: field `cases`: lists no load case: give at least one"
    );
}

#[test]
fn a_repeated_case_name_is_refused() {
    let e = refused("name: S\n", "name: G\n");
    assert_eq!(
        e,
        "loads/bad.yaml: field `cases[1].name`: `G` is also the name of cases[0]"
    );
}

#[test]
fn a_case_without_load_is_refused() {
    let e = refused("    wind_kn_per_m2: -0.42\n", "");
    assert_eq!(
        e,
        "loads/bad.yaml: field `cases[2].name`: case `W-` carries no load: give `wind_kn_per_m2`, `point_loads` or `line_loads`"
    );
}

#[test]
fn two_deflection_limits_are_refused() {
    let e = refused("span_over: 300", "span_over: 300\n  limit_mm: 20");
    assert_eq!(
        e,
        "loads/bad.yaml: field `deflection`: give `span_over` or `limit_mm`, not both"
    );
}

#[test]
fn a_missing_or_newer_version_is_refused() {
    let e = refused("version: 1\n", "");
    assert!(e.contains("field `version`: missing"), "{e}");
    let e = refused("version: 1\n", "version: 2\n");
    assert!(
        e.contains("field `version`: unknown loads version 2"),
        "{e}"
    );
}

// ------------------------------------------------------------ the sample

#[test]
fn the_pavilion_file_reads() {
    let path = root().join("samples/loads/pavilion.yaml");
    let s = loads_file::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let cases: Vec<(&str, Action)> = s
        .cases
        .iter()
        .map(|c| (c.name.as_str(), c.action))
        .collect();
    assert_eq!(
        cases,
        [
            ("G", Action::Permanent),
            ("S", Action::Snow),
            ("W+", Action::Wind),
            ("W-", Action::Wind)
        ]
    );
    // s = 0.8 × 1 × 1 × 0.85; w = ±cp,net × qp with qp = 0.70 kN/m².
    assert!((s.cases[1].snow_kn_per_m2 - 0.8 * 0.85).abs() < 1e-12);
    assert!((s.cases[2].wind_kn_per_m2 - 0.5 * 0.70).abs() < 1e-12);
    assert!((s.cases[3].wind_kn_per_m2 + 0.6 * 0.70).abs() < 1e-12);
    assert_eq!(s.source, path);
    assert_eq!(s.deflection, Deflection::SpanOver(300.0));
    assert_eq!(combinations(&s).len(), 19);
}

#[test]
fn an_upward_load_is_also_combined_with_the_favourable_permanent_factor() {
    // A lifting force (a crane hook, say) relieves G like suction does.
    let s = spec(
        "version: 1
cases:
  - {name: G, action: permanent}
  - {name: Q, action: imposed, point_loads: [{node: N11, force_kn: [0, 0, 2]}]}
",
    );
    let u = LimitState::Ultimate;
    let v = LimitState::Serviceability;
    assert_table(
        &combinations(&s),
        &[
            ("ULS G", u, vec![(0, 1.35)]),
            ("ULS Q", u, vec![(0, 1.35), (1, 1.5)]),
            ("ULS Q (G inf)", u, vec![(0, 1.0), (1, 1.5)]),
            ("SLS G", v, vec![(0, 1.0)]),
            ("SLS Q", v, vec![(0, 1.0), (1, 1.0)]),
        ],
    );
    // Without permanent cases: no G combination, no γG,inf variant.
    let s = spec("version: 1\ncases: [{name: W-, action: wind, wind_kn_per_m2: -0.4}]\n");
    assert_table(
        &combinations(&s),
        &[("ULS W-", u, vec![(0, 1.5)]), ("SLS W-", v, vec![(0, 1.0)])],
    );
}

// ------------------------------------------------------------ bracing

#[test]
fn a_bracing_section_reads_with_its_defaults() {
    use lamella::loads::{BracingLayout, BracingTargets, Diagonals, Pretension};
    assert_eq!(spec(GOOD).bracing, None, "no bracing unless asked for");
    let s = spec(&format!("{GOOD}bracing:\n  layout: designed\n"));
    let b = s.bracing.expect("bracing");
    assert_eq!(b.layout, BracingLayout::Designed);
    assert_eq!(b.diagonals, Diagonals::Single);
    assert_eq!(b.pretension, Pretension::Auto);
    assert_eq!(b.targets, BracingTargets::default());
    assert_eq!(b.targets.alpha_cr, Some(10.0));
    let s = spec(&format!(
        "{GOOD}bracing:\n  layout: alternate\n  diagonals: crossed\n  pretension_kn: 1.5\n  targets: {{deflection: true}}\n"
    ));
    let b = s.bracing.expect("bracing");
    assert_eq!(b.layout, BracingLayout::Alternate);
    assert_eq!(b.diagonals, Diagonals::Crossed);
    assert_eq!(b.pretension, Pretension::Kn(1.5));
    assert_eq!(
        b.targets,
        BracingTargets {
            alpha_cr: None,
            deflection: true,
            utilisation: None
        },
        "given targets are the only ones"
    );
}

#[test]
fn a_bad_bracing_section_is_refused_naming_its_field() {
    let bracing = |body: &str| {
        refused(
            "deflection:\n  span_over: 300\n",
            &format!("deflection:\n  span_over: 300\nbracing:\n{body}"),
        )
    };
    let e = bracing("  layout: designed\n  targets: {alpha_cr: 0.8}\n");
    assert!(
        e.contains("bracing.targets.alpha_cr") && e.contains("above 1"),
        "{e}"
    );
    let e = bracing("  layout: designed\n  targets: {deflection: false}\n");
    assert!(
        e.contains("bracing.targets") && e.contains("no target"),
        "{e}"
    );
    let e = bracing("  layout: designed\n  pretension_kn: -2\n");
    assert!(e.contains("bracing.pretension_kn"), "{e}");
    let e = bracing("  layout: every\n");
    assert!(e.contains("line") && e.contains("every"), "{e}");
    let e = bracing("  layout: all\n  cables: 3\n");
    assert!(e.contains("cables"), "{e}");
}
