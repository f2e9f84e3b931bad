//! The frame solver against closed forms: cantilevers (both axes),
//! simply supported strips under a uniform load, torsion, Euler columns
//! (with the refinement converging), a circular arch under radial
//! pressure, a grillage solved by hand, second-order amplification,
//! equilibrium and mechanisms.

use glam::{DMat3, DVec3};
use lamella::structure::buckling::critical_factors;
use lamella::structure::model::{
    Beam, CableState, ElementLoad, FrameModel, InitialForces, Link, LoadSet, NodeLoad,
    PressureLoad, Section, Support,
};
use lamella::structure::second_order::{second_order, second_order_of};
use lamella::structure::solve::{solve_static, FrameError, LinearFrame};
use std::f64::consts::PI;

const E: f64 = 210_000.0;
const G: f64 = 81_000.0;

/// A steel strip 1.5 × 50 mm (t × h): I_y = t·h³/12, I_z = h·t³/12,
/// J = h·t³/3·(1 − 0.63·t/h) (thin rectangle).
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

fn pinned(node: usize) -> Support {
    Support {
        node,
        fixed: [true, true, true, false, false, false],
        along: None,
    }
}

fn support(node: usize, fixed: [bool; 6]) -> Support {
    Support {
        node,
        fixed,
        along: None,
    }
}

/// A straight member from `a` to `b` in `n` elements, its height along
/// `z_axis`; returns the model (no supports) with nodes 0..=n.
fn member(a: DVec3, b: DVec3, n: usize, z_axis: DVec3, section: Section) -> FrameModel {
    FrameModel {
        nodes_mm: (0..=n).map(|i| a.lerp(b, i as f64 / n as f64)).collect(),
        sections: vec![section],
        beams: (0..n)
            .map(|i| Beam {
                nodes: [i, i + 1],
                section: 0,
                z_axis,
                initial: InitialForces::default(),
                offsets_mm: [DVec3::ZERO; 2],
            })
            .collect(),
        links: vec![],
        cables: vec![],
        supports: vec![],
    }
}

fn node_load(node: usize, force_n: DVec3, moment_nmm: DVec3) -> LoadSet {
    LoadSet {
        name: "P".into(),
        nodes: vec![NodeLoad {
            node,
            force_n,
            moment_nmm,
        }],
        ..Default::default()
    }
}

fn close(got: f64, want: f64, rel: f64, what: &str) {
    assert!(
        (got - want).abs() <= rel * want.abs(),
        "{what}: {got} against {want} (relative {:.2e}, allowed {rel:.0e})",
        (got - want) / want
    );
}

fn translation(d: &[f64; 6]) -> DVec3 {
    DVec3::new(d[0], d[1], d[2])
}

fn rotation(d: &[f64; 6]) -> DVec3 {
    DVec3::new(d[3], d[4], d[5])
}

/// The local axes the solver uses for a member along `x` with height `z_axis`.
fn axes(x: DVec3, z_axis: DVec3) -> (DVec3, DVec3, DVec3) {
    let x = x.normalize();
    let y = z_axis.cross(x).normalize();
    (x, y, x.cross(y))
}

#[test]
fn an_oblique_cantilever_deflects_as_pl3_over_3ei_about_both_axes() {
    let l = 1200.0;
    let dir = DVec3::new(1.0, 2.0, 2.0) / 3.0;
    let z_axis = DVec3::new(0.3, -0.2, 1.0);
    let (_, y, z) = axes(dir, z_axis);
    let mut m = member(
        DVec3::new(100.0, -50.0, 20.0),
        DVec3::new(100.0, -50.0, 20.0) + dir * l,
        3,
        z_axis,
        strip(),
    );
    m.supports.push(support(0, [true; 6]));
    let s = strip();
    let p = 2.0;
    // Weak axis: the tip load across the strip.
    let r = solve_static(&m, &node_load(3, y * p, DVec3::ZERO)).unwrap();
    let tip = &r.displacements[3];
    close(
        translation(tip).dot(y),
        p * l.powi(3) / (3.0 * E * s.i_z_mm4),
        1e-9,
        "weak-axis tip deflection",
    );
    close(
        rotation(tip).dot(z),
        p * l * l / (2.0 * E * s.i_z_mm4),
        1e-9,
        "weak-axis tip rotation",
    );
    close(
        r.beam_forces[0].start.moment_z_nmm,
        p * l,
        1e-9,
        "root moment M_z = P·L",
    );
    close(
        r.beam_forces[0].start.shear_y_n,
        p,
        1e-9,
        "root shear: the load beyond the section",
    );
    // Strong axis: the tip load along the height.
    let p = 50.0;
    let r = solve_static(&m, &node_load(3, z * p, DVec3::ZERO)).unwrap();
    let tip = &r.displacements[3];
    close(
        translation(tip).dot(z),
        p * l.powi(3) / (3.0 * E * s.i_y_mm4),
        1e-9,
        "strong-axis tip deflection",
    );
    close(
        rotation(tip).dot(y),
        -p * l * l / (2.0 * E * s.i_y_mm4),
        1e-9,
        "strong-axis tip rotation",
    );
    // The reaction holds the load and its moment about the root.
    let reaction = &r.reactions[0];
    close(reaction.force_n.dot(z), -p, 1e-9, "reaction");
    close(reaction.moment_nmm.dot(y), p * l, 1e-9, "reaction moment");
}

#[test]
fn a_simply_supported_strip_under_a_uniform_load_has_ql2_over_8_at_midspan() {
    let l = 2000.0;
    let q = 0.01;
    let s = strip();
    for n in [1, 2, 4, 8] {
        let mut m = member(DVec3::ZERO, DVec3::X * l, n, DVec3::Z, strip());
        m.supports = vec![
            support(0, [true, true, true, true, false, false]),
            support(n, [false, true, true, false, false, false]),
        ];
        let loads = LoadSet {
            name: "q".into(),
            beams: (0..n)
                .map(|beam| ElementLoad {
                    beam,
                    force_n_per_mm: -DVec3::Z * q,
                })
                .collect(),
            ..Default::default()
        };
        let r = solve_static(&m, &loads).unwrap();
        // Midspan: a node for even n, an element's middle for n = 1.
        let (moment, deflection) = if n % 2 == 0 {
            (
                r.beam_forces[n / 2 - 1].end.moment_y_nmm,
                Some(r.displacements[n / 2][2]),
            )
        } else {
            (r.beam_forces[0].middle.moment_y_nmm, None)
        };
        close(
            moment,
            -q * l * l / 8.0,
            1e-9,
            &format!("midspan moment, {n} elements"),
        );
        if let Some(w) = deflection {
            close(
                w,
                -5.0 * q * l.powi(4) / (384.0 * E * s.i_y_mm4),
                1e-9,
                &format!("midspan deflection, {n} elements"),
            );
        }
        let total: f64 = r.reactions.iter().map(|r| r.force_n.z).sum();
        close(total, q * l, 1e-12, "reactions");
    }
}

#[test]
fn a_bar_in_torsion_turns_by_tl_over_gj() {
    let l = 800.0;
    let mut m = member(DVec3::ZERO, DVec3::new(0.0, l, 0.0), 4, DVec3::Z, strip());
    m.supports.push(support(0, [true; 6]));
    let t = 30.0;
    let r = solve_static(&m, &node_load(4, DVec3::ZERO, DVec3::Y * t)).unwrap();
    close(
        r.displacements[4][4],
        t * l / (G * strip().j_mm4),
        1e-9,
        "twist at the free end",
    );
    for f in &r.beam_forces {
        close(f.start.torque_nmm, t, 1e-9, "torque");
    }
}

/// α_cr of a compressed strip (unit load) with `n` elements.
fn euler(n: usize, fixed_free: bool) -> f64 {
    let l = 1000.0;
    let mut m = member(DVec3::ZERO, DVec3::X * l, n, DVec3::Z, strip());
    m.supports = if fixed_free {
        vec![support(0, [true; 6])]
    } else {
        vec![
            support(0, [true, true, true, true, false, false]),
            support(n, [false, true, true, false, false, false]),
        ]
    };
    let modes = critical_factors(&m, &node_load(n, -DVec3::X, DVec3::ZERO), 2).unwrap();
    modes[0].factor
}

#[test]
fn euler_columns_converge_on_pi2_ei_over_l2() {
    let p_e = PI * PI * E * strip().i_z_mm4 / (1000.0 * 1000.0);
    for (fixed_free, want) in [(false, p_e), (true, p_e / 4.0)] {
        let errors: Vec<f64> = [1, 2, 4, 8]
            .iter()
            .map(|&n| (euler(n, fixed_free) - want) / want)
            .collect();
        // The consistent geometric stiffness bounds from above and converges as 1/n⁴.
        for w in errors.windows(2) {
            assert!(
                w[1] >= 0.0 && w[1] < w[0] / 8.0,
                "not converging: {errors:?}"
            );
        }
        assert!(errors[2] < 0.005, "4 elements: {errors:?}");
        assert!(errors[3] < 2e-4, "8 elements: {errors:?}");
    }
}

#[test]
fn the_second_euler_mode_is_four_times_the_first() {
    let l = 1000.0;
    let n = 16;
    let mut m = member(DVec3::ZERO, DVec3::X * l, n, DVec3::Z, strip());
    m.supports = vec![
        support(0, [true, true, true, true, false, false]),
        support(n, [false, true, true, false, false, false]),
    ];
    let modes = critical_factors(&m, &node_load(n, -DVec3::X, DVec3::ZERO), 3).unwrap();
    let p_e = PI * PI * E * strip().i_z_mm4 / (l * l);
    close(modes[0].factor, p_e, 1e-4, "first mode");
    close(modes[1].factor, 4.0 * p_e, 1e-3, "second mode");
    close(modes[2].factor, 9.0 * p_e, 5e-3, "third mode");
    // The first mode is a half sine across the strip.
    let mid = &modes[0].shape[n / 2];
    close(mid[1].abs(), 1.0, 1e-9, "mode shape normalised at midspan");
    let quarter = modes[0].shape[n / 4][1].abs();
    close(quarter, (PI / 4.0).sin(), 1e-3, "half sine");
}

#[test]
fn an_erection_compression_lowers_the_critical_factor_by_itself() {
    let l = 1000.0;
    let n = 8;
    let p_e = PI * PI * E * strip().i_z_mm4 / (l * l);
    let mut m = member(DVec3::ZERO, DVec3::X * l, n, DVec3::Z, strip());
    m.supports = vec![
        support(0, [true, true, true, true, false, false]),
        support(n, [false, true, true, false, false, false]),
    ];
    let alone = critical_factors(&m, &node_load(n, -DVec3::X, DVec3::ZERO), 1).unwrap()[0].factor;
    for b in m.beams.iter_mut() {
        b.initial.axial_n = -0.5 * p_e;
    }
    let with = critical_factors(&m, &node_load(n, -DVec3::X, DVec3::ZERO), 1).unwrap()[0].factor;
    close(
        with,
        alone - 0.5 * p_e,
        1e-6,
        "α_cr with half the Euler load already in the strip",
    );
}

/// A circular arch of radius `r`, half-angle `alpha`, in the x–z plane,
/// pinned at its springings, in `n` elements; out-of-plane motion held.
fn arch(r: f64, alpha: f64, n: usize) -> FrameModel {
    let at = |i: usize| {
        let phi = -alpha + 2.0 * alpha * i as f64 / n as f64;
        DVec3::new(r * phi.sin(), 0.0, r * phi.cos())
    };
    let nodes: Vec<DVec3> = (0..=n).map(at).collect();
    let beams = (0..n)
        .map(|i| Beam {
            nodes: [i, i + 1],
            section: 0,
            // Height radial: in-plane bending is about local y (I_y).
            z_axis: (nodes[i] + nodes[i + 1]).normalize(),
            initial: InitialForces::default(),
            offsets_mm: [DVec3::ZERO; 2],
        })
        .collect();
    let mut supports: Vec<Support> = (0..=n)
        .map(|i| support(i, [false, true, false, true, false, true]))
        .collect();
    supports[0] = support(0, [true, true, true, true, false, true]);
    supports[n] = support(n, [true, true, true, true, false, true]);
    FrameModel {
        nodes_mm: nodes,
        sections: vec![strip()],
        beams,
        links: vec![],
        cables: vec![],
        supports,
    }
}

#[test]
fn a_pinned_arch_under_radial_pressure_buckles_at_the_closed_form() {
    let (r, alpha): (f64, f64) = (1000.0, PI / 3.0);
    let q_cr = (PI * PI / (alpha * alpha) - 1.0) * E * strip().i_y_mm4 / r.powi(3);
    let mut errors = Vec::new();
    for n in [8, 16, 32, 64] {
        let m = arch(r, alpha, n);
        let loads = LoadSet {
            name: "pressure".into(),
            pressures: (0..n)
                .map(|beam| PressureLoad {
                    beam,
                    n_per_mm: -1.0,
                })
                .collect(),
            ..Default::default()
        };
        let modes = critical_factors(&m, &loads, 1).unwrap();
        errors.push((modes[0].factor - q_cr) / q_cr);
    }
    assert!(errors[3].abs() < 0.005, "64 elements: {errors:?}");
    assert!(
        errors[3].abs() < errors[1].abs(),
        "not converging: {errors:?}"
    );
}

#[test]
fn a_two_strip_grillage_shares_its_load_by_stiffness() {
    // Strip A along x (span 3 m), strip B along y (span 2 m), crossing at
    // their middles, upright; a load P at the crossing. The crossing's
    // deflection is P / (48·E·I/L_A³ + 48·E·I/L_B³) and A carries its share
    // k_A/(k_A + k_B) (by symmetry neither twists the other).
    let (la, lb, p): (f64, f64, f64) = (3000.0, 2000.0, 40.0);
    let s = strip();
    let (ka, kb) = (
        48.0 * E * s.i_y_mm4 / la.powi(3),
        48.0 * E * s.i_y_mm4 / lb.powi(3),
    );
    for linked in [false, true] {
        let mut nodes = vec![
            DVec3::new(-la / 2.0, 0.0, 0.0),
            DVec3::ZERO,
            DVec3::new(la / 2.0, 0.0, 0.0),
            DVec3::new(0.0, -lb / 2.0, 0.0),
            DVec3::new(0.0, lb / 2.0, 0.0),
        ];
        let centre_b = if linked {
            nodes.push(DVec3::ZERO);
            5
        } else {
            1
        };
        let beam = |a, b| Beam {
            nodes: [a, b],
            section: 0,
            z_axis: DVec3::Z,
            initial: InitialForces::default(),
            offsets_mm: [DVec3::ZERO; 2],
        };
        let links = if linked {
            vec![Link {
                nodes: [1, 5],
                frame: DMat3::IDENTITY,
                translation_n_per_mm: [1e9; 3],
                rotation_nmm_per_rad: [1e13; 3],
            }]
        } else {
            vec![]
        };
        let m = FrameModel {
            nodes_mm: nodes,
            sections: vec![s.clone()],
            beams: vec![beam(0, 1), beam(1, 2), beam(3, centre_b), beam(centre_b, 4)],
            links,
            cables: vec![],
            supports: vec![
                support(0, [true, true, true, true, false, false]),
                support(2, [false, true, true, false, false, false]),
                support(3, [true, true, true, false, true, false]),
                support(4, [true, false, true, false, false, false]),
            ],
        };
        let r = solve_static(&m, &node_load(1, -DVec3::Z * p, DVec3::ZERO)).unwrap();
        let rel = if linked { 1e-5 } else { 1e-9 };
        close(
            r.displacements[1][2],
            -p / (ka + kb),
            rel,
            "crossing deflection",
        );
        let share_a = p * ka / (ka + kb);
        close(
            r.beam_forces[0].end.moment_y_nmm.abs(),
            share_a * la / 4.0,
            rel,
            "strip A's moment at the crossing",
        );
        close(
            r.beam_forces[2].end.moment_y_nmm.abs(),
            (p - share_a) * lb / 4.0,
            rel,
            "strip B's moment",
        );
    }
}

#[test]
fn second_order_amplifies_a_compressed_strips_bending_exactly() {
    // Pinned strip under P = P_E/2 and a uniform load across it: the exact
    // midspan deflection is δ0·12·(2·sec u − 2 − u²)/(5·u⁴), u = (L/2)·√(P/EI).
    let (l, n, q) = (1000.0, 16, 0.001);
    let s = strip();
    let ei = E * s.i_z_mm4;
    let p = 0.5 * PI * PI * ei / (l * l);
    let mut m = member(DVec3::ZERO, DVec3::X * l, n, DVec3::Z, strip());
    m.supports = vec![
        support(0, [true, true, true, true, false, false]),
        support(n, [false, true, true, false, false, false]),
    ];
    let loads = LoadSet {
        name: "P+q".into(),
        nodes: vec![NodeLoad {
            node: n,
            force_n: -DVec3::X * p,
            moment_nmm: DVec3::ZERO,
        }],
        beams: (0..n)
            .map(|beam| ElementLoad {
                beam,
                force_n_per_mm: DVec3::Y * q,
            })
            .collect(),
        ..Default::default()
    };
    let first = solve_static(&m, &loads).unwrap();
    let delta0 = 5.0 * q * l.powi(4) / (384.0 * ei);
    close(first.displacements[n / 2][1], delta0, 1e-9, "first order");
    let second = second_order(&m, &loads, &[], 1e-10).unwrap();
    let u = 0.5 * l * (p / ei).sqrt();
    let amplified = delta0 * 12.0 * (2.0 / u.cos() - 2.0 - u * u) / (5.0 * u.powi(4));
    close(
        second.result.displacements[n / 2][1],
        amplified,
        1e-3,
        "second order",
    );
    // The moment at midspan includes P·δ.
    let m_mid = second.result.beam_forces[n / 2 - 1].end.moment_z_nmm.abs();
    let exact_moment = q * ei / p * (1.0 / u.cos() - 1.0);
    close(m_mid, exact_moment, 2e-3, "second-order midspan moment");
    // On the linear frame's symbolic factorisation and scatter plan, with
    // an imperfection: the same iteration as on a model of its own.
    let bow: Vec<DVec3> = (0..=n)
        .map(|i| DVec3::Y * 2.0 * (PI * i as f64 / n as f64).sin())
        .collect();
    let own = second_order(&m, &loads, &bow, 1e-10).unwrap();
    let linear = LinearFrame::new(&m).unwrap();
    let shared = second_order_of(&linear, &loads, &bow, 1e-10, CableState::TensionOnly).unwrap();
    assert_eq!(shared.iterations, own.iterations);
    assert!(own.result.displacements[n / 2][1] > 1.01 * second.result.displacements[n / 2][1]);
    let largest = own.result.displacements[n / 2][1].abs();
    for (a, b) in shared
        .result
        .displacements
        .iter()
        .zip(&own.result.displacements)
    {
        for k in 0..6 {
            assert!(
                (a[k] - b[k]).abs() <= 1e-12 * largest,
                "shared {a:?} against own {b:?}"
            );
        }
    }
}

#[test]
fn second_order_above_the_critical_load_is_unstable() {
    // The same strip at 1.5 times Euler's load: the second tangent,
    // stiffened by the first step's compression, is not definite.
    let (l, n) = (1000.0, 16);
    let ei = E * strip().i_z_mm4;
    let mut m = member(DVec3::ZERO, DVec3::X * l, n, DVec3::Z, strip());
    m.supports = vec![
        support(0, [true, true, true, true, false, false]),
        support(n, [false, true, true, false, false, false]),
    ];
    let loads = LoadSet {
        name: "1.5 P_E".into(),
        nodes: vec![NodeLoad {
            node: n,
            force_n: -DVec3::X * (1.5 * PI * PI * ei / (l * l)),
            moment_nmm: DVec3::ZERO,
        }],
        ..Default::default()
    };
    match second_order(&m, &loads, &[], 1e-10) {
        Err(FrameError::Unstable(name)) => assert_eq!(name, "1.5 P_E"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn loads_and_reactions_balance_on_a_space_frame() {
    // A tripod of strips with a linked top and an inclined roller.
    let nodes = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(2000.0, 0.0, 0.0),
        DVec3::new(1000.0, 1700.0, 0.0),
        DVec3::new(1000.0, 600.0, 1500.0),
        DVec3::new(1000.0, 600.0, 1500.0),
    ];
    let beam = |a, b, z: DVec3| Beam {
        nodes: [a, b],
        section: 0,
        z_axis: z,
        initial: InitialForces::default(),
        offsets_mm: [DVec3::ZERO; 2],
    };
    let m = FrameModel {
        nodes_mm: nodes.clone(),
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
            pinned(1),
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
    let r = solve_static(&m, &loads).unwrap();
    let mut force = DVec3::ZERO;
    let mut moment = DVec3::ZERO;
    for re in &r.reactions {
        force += re.force_n;
        moment += nodes[re.node].cross(re.force_n) + re.moment_nmm;
    }
    for l in &loads.nodes {
        force += l.force_n;
        moment += nodes[l.node].cross(l.force_n) + l.moment_nmm;
    }
    for l in &loads.beams {
        let [a, b] = m.beams[l.beam].nodes;
        let total = l.force_n_per_mm * (nodes[b] - nodes[a]).length();
        force += total;
        moment += (0.5 * (nodes[a] + nodes[b])).cross(total);
    }
    assert!(force.length() < 1e-8 * 100.0, "Σ forces {force}");
    assert!(
        moment.length() < 1e-8 * 100.0 * 2000.0,
        "Σ moments {moment}"
    );
}

#[test]
fn a_strip_free_to_spin_about_its_axis_is_a_mechanism_named_by_its_node() {
    let n = 4;
    let mut m = member(DVec3::ZERO, DVec3::X * 1000.0, n, DVec3::Z, strip());
    m.supports = vec![
        pinned(0),
        support(n, [false, true, true, false, false, false]),
    ];
    let err = solve_static(&m, &node_load(2, -DVec3::Z, DVec3::ZERO)).unwrap_err();
    match err {
        FrameError::Mechanism { dof, .. } => assert_eq!(dof, 3, "{err}"),
        other => panic!("{other}"),
    }
    assert!(err.to_string().contains("rx"), "{err}");
}

#[test]
fn a_node_tied_to_nothing_is_named() {
    let mut m = member(DVec3::ZERO, DVec3::X * 1000.0, 2, DVec3::Z, strip());
    m.supports = vec![support(0, [true; 6])];
    m.nodes_mm.push(DVec3::new(0.0, 500.0, 0.0));
    let err = solve_static(&m, &LoadSet::default()).unwrap_err();
    assert!(
        matches!(err, FrameError::Mechanism { node: 3, .. }),
        "{err}"
    );
}

#[test]
fn a_rigid_end_offset_acts_as_a_rigid_arm() {
    // A cantilever whose free end meets its node through a 40 mm offset,
    // against the same cantilever with an explicit arm a thousand times
    // stiffer: every displacement of the loaded node agrees.
    let (l, e) = (900.0, 40.0);
    let s = strip();
    let arm = Section {
        area_mm2: s.area_mm2 * 1e3,
        i_y_mm4: s.i_y_mm4 * 1e3,
        i_z_mm4: s.i_y_mm4 * 1e3,
        j_mm4: s.i_y_mm4 * 1e3,
        ..s.clone()
    };
    let offset = DVec3::new(0.0, 10.0, 40.0).normalize() * e;
    let tip = DVec3::new(l, 0.0, 0.0) - offset;
    let beam = |nodes, section, offsets_mm| Beam {
        nodes,
        section,
        z_axis: DVec3::Z,
        initial: InitialForces::default(),
        offsets_mm,
    };
    let with_offset = FrameModel {
        nodes_mm: vec![DVec3::ZERO, tip],
        sections: vec![s.clone()],
        beams: vec![beam([0, 1], 0, [DVec3::ZERO, offset])],
        links: vec![],
        cables: vec![],
        supports: vec![support(0, [true; 6])],
    };
    let with_arm = FrameModel {
        nodes_mm: vec![DVec3::ZERO, DVec3::new(l, 0.0, 0.0), tip],
        sections: vec![s.clone(), arm],
        beams: vec![
            beam([0, 1], 0, [DVec3::ZERO; 2]),
            beam([1, 2], 1, [DVec3::ZERO; 2]),
        ],
        links: vec![],
        cables: vec![],
        supports: vec![support(0, [true; 6])],
    };
    let force = DVec3::new(30.0, 0.5, -2.0);
    let moment = DVec3::new(40.0, -300.0, 20.0);
    let a = solve_static(&with_offset, &node_load(1, force, moment)).unwrap();
    let b = solve_static(&with_arm, &node_load(2, force, moment)).unwrap();
    for k in 0..6 {
        let (x, y) = (a.displacements[1][k], b.displacements[2][k]);
        // The explicit arm bends and twists by about 1e-3 × (40 mm / 900 mm) of
        // the strip: 1e-4 between the two.
        assert!(
            (x - y).abs() <= 1e-4 * y.abs().max(1e-3),
            "dof {k}: {x} against {y}"
        );
    }
    // The root holds the load's force and moment about it, exactly.
    let reaction = &a.reactions[0];
    let about_root = moment + tip.cross(force);
    assert!((reaction.force_n + force).length() < 1e-9 * force.length());
    assert!(
        (reaction.moment_nmm + about_root).length() < 1e-9 * about_root.length(),
        "{}",
        reaction.moment_nmm
    );
}
