//! Rigid motion, curve reversal and unit change leave the results unchanged.

#![allow(clippy::unwrap_used)] // tests may panic on broken invariants

mod common;
use common::*;
use glam::DVec2;
use lamella::network::{RawNetwork, Unit};
use lamella::synth::{self, Enneper, Sampling};

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

/// Per strip: (id, length, node stations, max |kg|, max |tg|).
type StripSummary = (String, f64, Vec<f64>, f64, f64);
/// Strips, and the sorted node angles.
type Summary = (Vec<StripSummary>, Vec<f64>);

/// Per strip: (length, sorted node stations, max |kg|, max |tg|), per node: angle.
fn summary(raw: RawNetwork) -> Summary {
    let (net, an) = run(raw);
    let strips = an
        .strips
        .iter()
        .map(|s| {
            (
                net.curves[s.curve].id.clone(),
                s.length_mm,
                s.nodes.iter().map(|n| n.station_mm).collect(),
                s.max_abs_kg_per_mm,
                s.max_abs_tg_per_mm,
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
        for (k, (x, y)) in a.0.iter().zip(&b.0).enumerate() {
            assert!((x.1 - y.1).abs() < 1e-6);
            let expected: Vec<f64> = if k % 2 == 0 {
                let mut m: Vec<f64> = x.2.iter().map(|s| x.1 - s).collect();
                m.reverse();
                m
            } else {
                x.2.clone()
            };
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
