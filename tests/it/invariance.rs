//! Rigid motion, curve reversal and unit change leave the results unchanged.

use crate::support::synth::{self, Enneper, Sampling};
use crate::support::*;
use glam::DVec2;
use lamella::network::{RawNetwork, Unit};
use lamella::plan::model::Model;

fn base(normals: bool) -> RawNetwork {
    let lines = synth::diagonal_lines(0.5, 9, DVec2::new(0.05, -0.03));
    synth::network(
        "inv",
        &Enneper,
        &lines,
        4400.0,
        Sampling {
            step_mm: 50.0,
            normals,
        },
    )
}

/// One lamella: (number, dy, length, node stations on its own line).
type LamellaSummary = (u32, f64, f64, Vec<f64>);
/// Per strip: (id, length, node stations, max |kg|, max |tg|, lamellas of
/// the doubled steel profile).
type StripSummary = (String, f64, Vec<f64>, f64, f64, Vec<LamellaSummary>);
/// Strips, and the sorted node angles.
type Summary = (Vec<StripSummary>, Vec<f64>);

/// Per strip: (length, sorted node stations, max |kg|, max |tg|), per node: angle.
fn summary(raw: RawNetwork) -> Summary {
    let (net, an) = run(raw);
    let steel = profile("steel-1.5");
    let report = lamella::check::check(&an, &steel, false).0;
    let model = Model::new(
        &net,
        &an,
        Some(lamella::plan::model::Checked {
            profile: &steel,
            report: &report,
            suggestion: None,
            resolved: &serde_json::Value::Null,
        }),
    );
    let strips = an
        .strips
        .iter()
        .zip(&model.strips)
        .map(|(s, m)| {
            (
                net.curves[s.curve].id.clone(),
                s.length_mm,
                s.nodes.iter().map(|n| n.station_mm).collect(),
                s.max_abs_kg_per_mm,
                s.max_abs_tg_per_mm,
                m.lamellas
                    .iter()
                    .map(|l| {
                        (
                            l.offset.number,
                            l.offset.dy_mm,
                            l.length_mm,
                            l.nodes.iter().map(|n| n.station_mm).collect(),
                        )
                    })
                    .collect(),
            )
        })
        .collect();
    let mut angles: Vec<f64> = an.topology.nodes.iter().map(|n| n.angle_deg).collect();
    angles.sort_by(f64::total_cmp);
    (strips, angles)
}

fn assert_same(a: &Summary, b: &Summary) {
    assert_eq!(a.0.len(), b.0.len());
    for (x, y) in a.0.iter().zip(&b.0) {
        assert_eq!(x.0, y.0);
        assert!(
            (x.1 - y.1).abs() < 1e-6,
            "{}: length {} vs {}",
            x.0,
            x.1,
            y.1
        );
        assert_eq!(x.2.len(), y.2.len(), "{}: node count", x.0);
        for (s, t) in x.2.iter().zip(&y.2) {
            assert!((s - t).abs() < 1e-6, "{}: station {s} vs {t}", x.0);
        }
        assert!(
            (x.3 - y.3).abs() < 1e-9 + 1e-6 * x.3,
            "{}: kg {} vs {}",
            x.0,
            x.3,
            y.3
        );
        assert!(
            (x.4 - y.4).abs() < 1e-9 + 1e-6 * x.4,
            "{}: tg {} vs {}",
            x.0,
            x.4,
            y.4
        );
        assert_eq!(x.5.len(), y.5.len(), "{}: lamella count", x.0);
        for (l, m) in x.5.iter().zip(&y.5) {
            assert_eq!((l.0, l.1), (m.0, m.1), "{}: lamella", x.0);
            assert!(
                (l.2 - m.2).abs() < 1e-6,
                "{} lamella {}: length {} vs {} ({:?} vs {:?})",
                x.0,
                l.0,
                l.2,
                m.2,
                x.5.iter().map(|l| l.2).collect::<Vec<_>>(),
                y.5.iter().map(|l| l.2).collect::<Vec<_>>()
            );
            assert_eq!(l.3.len(), m.3.len(), "{} lamella {}: node count", x.0, l.0);
            for (s, t) in l.3.iter().zip(&m.3) {
                assert!((s - t).abs() < 1e-6, "{} lamella {}: {s} vs {t}", x.0, l.0);
            }
        }
    }
    assert_eq!(a.1.len(), b.1.len());
    for (p, q) in a.1.iter().zip(&b.1) {
        assert!((p - q).abs() < 1e-7, "angle {p} vs {q}");
    }
}

#[test]
fn rigid_motion_changes_nothing() {
    for normals in [true, false] {
        let a = summary(base(normals));
        let mut moved = base(normals);
        for c in &mut moved.curves {
            for p in &mut c.points {
                *p = rigid(*p);
            }
            if let Some(ns) = &mut c.normals {
                for n in ns {
                    *n = rigid(*n) - rigid(glam::DVec3::ZERO);
                }
            }
        }
        assert_same(&a, &summary(moved));
    }
}

#[test]
fn unit_change_changes_nothing() {
    let a = summary(base(true));
    let mut metres = base(true);
    metres.unit = Unit::M;
    for c in &mut metres.curves {
        for p in &mut c.points {
            *p /= 1000.0;
        }
    }
    assert_same(&a, &summary(metres));
    let mut inches = base(true);
    inches.unit = Unit::In;
    for c in &mut inches.curves {
        for p in &mut c.points {
            *p /= 25.4;
        }
    }
    assert_same(&a, &summary(inches));
}

#[test]
fn reversing_a_curve_mirrors_its_stations() {
    for normals in [true, false] {
        let a = summary(base(normals));
        let mut rev = base(normals);
        for c in rev.curves.iter_mut().step_by(2) {
            c.points.reverse();
            if let Some(ns) = &mut c.normals {
                ns.reverse();
            }
        }
        let b = summary(rev);
        // Counts first: a reversed curve that lost a node must fail.
        assert_eq!(a.0.len(), b.0.len(), "strip count");
        for (k, (x, y)) in a.0.iter().zip(&b.0).enumerate() {
            assert!((x.1 - y.1).abs() < 1e-6);
            assert_eq!(x.2.len(), y.2.len(), "{}: node count", x.0);
            let reversed = k % 2 == 0;
            let mirror = |len: f64, stations: &[f64]| -> Vec<f64> {
                stations.iter().rev().map(|s| len - s).collect()
            };
            let expected: Vec<f64> = if reversed {
                mirror(x.1, &x.2)
            } else {
                x.2.clone()
            };
            // Reversing flips x and so y (z stays): lamella 1 at −y becomes
            // lamella 2 at +y. Their lengths swap, their stations mirror.
            assert_eq!(x.5.len(), 2, "{}: doubled steel", x.0);
            assert_eq!(y.5.len(), 2, "{}: doubled steel", y.0);
            for (l, m) in x.5.iter().zip(&y.5) {
                assert_eq!(l.0, m.0);
                assert_eq!(l.1, m.1, "lamella {} keeps its side of y", l.0);
            }
            for (i, m) in y.5.iter().enumerate() {
                let l = if reversed { &x.5[1 - i] } else { &x.5[i] };
                assert!(
                    (l.2 - m.2).abs() < 1e-6,
                    "{} lamella {}: length {} vs {}",
                    x.0,
                    m.0,
                    l.2,
                    m.2
                );
                let want = if reversed {
                    mirror(l.2, &l.3)
                } else {
                    l.3.clone()
                };
                assert_eq!(want.len(), m.3.len(), "{} lamella {}: node count", x.0, m.0);
                for (s, t) in want.iter().zip(&m.3) {
                    assert!(
                        (s - t).abs() < 1e-6,
                        "{} lamella {}: mirrored station {s} vs {t}",
                        x.0,
                        m.0
                    );
                }
            }
            // The doubled lamellas differ (else the swap would test nothing).
            assert!((x.5[0].2 - x.5[1].2).abs() > 0.1, "{}", x.0);
            for (s, t) in expected.iter().zip(&y.2) {
                assert!((s - t).abs() < 1e-6, "{}: mirrored station {s} vs {t}", x.0);
            }
            assert!(
                (x.3 - y.3).abs() < 1e-6 * x.3.max(1e-6),
                "{}: kg {} vs {}",
                x.0,
                x.3,
                y.3
            );
            assert!(
                (x.4 - y.4).abs() < 1e-6 * x.4.max(1e-6),
                "{}: tg {} vs {}",
                x.0,
                x.4,
                y.4
            );
        }
        assert_same(&(vec![], a.1), &(vec![], b.1));
    }
}
