//! Nesting (issue 9, first version): every part of every buildable sample ×
//! profile placed exactly its count of times, inside the margins, in allowed
//! rotations, kerf + spacing apart (the named invariant `check_nest`, and an
//! independent pairwise check here); never fewer sheets than the lower
//! bound; deterministic; a part too large for the stock is a one-line error.

#![allow(clippy::unwrap_used)] // tests may panic on broken invariants

use lamella::fabricate::fabricate;
use lamella::io::{read_network, ReadOptions};
use lamella::nest::{check_nest, nest, placed_bbox};
use lamella::profile::Profile;
use lamella::{analyze, AnalysisOptions};
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn every_buildable_kit_nests_within_the_rules() {
    let mut nested = 0;
    for sample in [
        "enneper-4m",
        "catenoid",
        "scherk",
        "schwarz-d-patch",
        "hypar-small",
        "schwarz-d-pavilion",
    ] {
        let net = read_network(
            &root().join(format!("samples/{sample}.yaml")),
            ReadOptions::default(),
        )
        .unwrap();
        let an = analyze(&net, AnalysisOptions::for_network(&net)).unwrap();
        for profile in ["steel-1.5", "poplar-ply-4", "beech-veneer"] {
            let p = Profile::load(&root().join(format!("profiles/{profile}.yaml"))).unwrap();
            let kit = fabricate(&net, &an, &p).unwrap();
            let n = nest(&kit, &p).unwrap();
            assert_eq!(check_nest(&kit, &n, &p), Ok(()), "{sample} {profile}");
            let s = &n.summary;
            assert!(s.sheets_used >= s.lower_bound_sheets, "{sample} {profile}");
            assert!(s.utilization > 0.0 && s.utilization <= 1.0);
            // Independently: boxes on a sheet pairwise at least the gap apart.
            let g = p.cutting.kerf_mm + p.cutting.part_spacing_mm;
            for sheet in &n.sheets {
                let boxes: Vec<_> = sheet
                    .placements
                    .iter()
                    .map(|pl| placed_bbox(&kit.parts[pl.part], pl))
                    .collect();
                if boxes.len() > 2000 {
                    continue; // the sweep in check_nest covers the large ones
                }
                for i in 0..boxes.len() {
                    for j in i + 1..boxes.len() {
                        let (a, b) = (boxes[i], boxes[j]);
                        let apart = a.2 + g <= b.0 + 1e-6
                            || b.2 + g <= a.0 + 1e-6
                            || a.3 + g <= b.1 + 1e-6
                            || b.3 + g <= a.1 + 1e-6;
                        assert!(apart, "{sample} {profile} {}: {a:?} {b:?}", sheet.id);
                    }
                }
            }
            // Deterministic.
            assert_eq!(nest(&kit, &p).unwrap().sheets, n.sheets);
            nested += 1;
        }
    }
    assert_eq!(nested, 18);
}

#[test]
fn a_part_larger_than_the_stock_is_a_one_line_error() {
    let net = read_network(
        &root().join("samples/catenoid.yaml"),
        ReadOptions::default(),
    )
    .unwrap();
    let an = analyze(&net, AnalysisOptions::for_network(&net)).unwrap();
    let mut p = Profile::load(&root().join("profiles/beech-veneer.yaml")).unwrap();
    // Stock narrower than a lamella is high, grain forbids turning it.
    p.stock.sizes[0].width_mm = 20.0;
    // Edge bands are split to fit the stock when the parts are made; when
    // no split can, that stage says so; lamellas are caught by the nest.
    let e = fabricate(&net, &an, &p)
        .and_then(|kit| nest(&kit, &p).map(|_| ()))
        .unwrap_err()
        .to_string();
    assert!(e.contains("does not fit"), "{e}");
    assert!(e.contains("strip edge") || e.contains("part "), "{e}");
    assert!(!e.contains('\n'));
    // Without edges in the way: the lamellas themselves.
    let mut wide = p.clone();
    wide.stock.sizes[0].width_mm = 300.0;
    let kit = fabricate(&net, &an, &wide).unwrap();
    let mut narrow = wide.clone();
    narrow.stock.sizes[0].width_mm = 20.0;
    let e = nest(&kit, &narrow).unwrap_err().to_string();
    assert!(e.contains("part ") && e.contains("does not fit"), "{e}");
}

/// Only rotations that turn lamellas across the sheet: an error naming the
/// part, never an endless search for a sheet that fits.
#[test]
fn rotations_that_fit_nothing_are_an_error_not_a_hang() {
    let net = read_network(
        &root().join("samples/catenoid.yaml"),
        ReadOptions::default(),
    )
    .unwrap();
    let an = analyze(&net, AnalysisOptions::for_network(&net)).unwrap();
    let mut p = Profile::load(&root().join("profiles/steel-1.5.yaml")).unwrap();
    let kit = fabricate(&net, &an, &p).unwrap();
    p.cutting.allowed_rotations_deg = vec![90];
    let e = nest(&kit, &p).unwrap_err().to_string();
    assert!(e.contains("part ") && !e.contains('\n'), "{e}");
    p.cutting.allowed_rotations_deg = vec![180];
    let n = nest(&kit, &p).unwrap();
    assert_eq!(check_nest(&kit, &n, &p), Ok(()));
}

/// Random lane-only kits (lamella rectangles of one height, lengths from a
/// few hundred mm to the full usable length, random counts): the
/// invariants hold and the nest never uses more than one sheet over the
/// lane bound ⌈L2 / lanes per sheet⌉. A fixed-seed generator keeps the test
/// deterministic.
#[test]
fn random_lane_only_kits_stay_within_a_sheet_of_the_bound() {
    use kurbo::Point;
    use lamella::fabricate::part::{Part, PartKind};
    use lamella::fabricate::{Kit, KitSummary};
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = || {
        // xorshift64*
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    };
    let steel = Profile::load(&root().join("profiles/steel-1.5.yaml")).unwrap();
    let usable = steel.stock.sizes[0].usable_length_mm(steel.cutting.edge_margin_mm);
    let h = steel.section.height_mm;
    let mut over = 0;
    for case in 0..60 {
        let kinds = 5 + (next() * 60.0) as usize;
        let parts: Vec<Part> = (0..kinds)
            .map(|k| {
                let len = 150.0 + next() * (usable - 150.0);
                Part {
                    id: format!("L{case}-{k}"),
                    kind: PartKind::Lamella,
                    strip: None,
                    lamella: Some(1),
                    count: 1 + (next() * 6.0) as u32,
                    length_mm: len,
                    height_mm: h,
                    station_start_mm: Some(0.0),
                    outline_part_mm: vec![
                        Point::new(0.0, 0.0),
                        Point::new(len, 0.0),
                        Point::new(len, h),
                        Point::new(0.0, h),
                    ],
                    holes_part_mm: Vec::new(),
                    engraving_part_mm: Vec::new(),
                    features: Vec::new(),
                }
            })
            .collect();
        let kit = Kit {
            parts,
            summary: KitSummary::default(),
            warnings: Vec::new(),
        };
        let n = nest(&kit, &steel).unwrap();
        assert_eq!(check_nest(&kit, &n, &steel), Ok(()), "case {case}");
        let s = &n.summary;
        assert!(
            s.sheets_used <= s.lane_bound_sheets + 1,
            "case {case}: {} sheets, lane bound {}",
            s.sheets_used,
            s.lane_bound_sheets
        );
        assert!(s.sheets_used >= s.lower_bound_sheets);
        over += usize::from(s.sheets_used > s.lower_bound_sheets);
    }
    // How often the nest is a sheet over the bound (reported, not held).
    eprintln!("random lane-only kits: {over} of 60 one sheet over the bound");
}

/// `nest --export-instance`: a sparrow strip-packing instance with every
/// part once, its count as demand, the profile's rotations, and an outline
/// grown by half the kerf plus spacing (so larger than the part's).
#[test]
fn the_sparrow_instance_holds_every_part_grown() {
    let dir = std::env::temp_dir().join(format!("lamella-nest-instance-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let inst = dir.join("instance.json");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_lamella"))
        .args([
            "nest",
            "samples/catenoid.yaml",
            "--profile",
            "profiles/steel-1.5.yaml",
            "--out",
        ])
        .arg(&dir)
        .arg("--export-instance")
        .arg(&inst)
        .current_dir(root())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&inst).unwrap()).unwrap();
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("plan.json")).unwrap()).unwrap();
    let parts = plan["parts"].as_array().unwrap();
    let items = v["items"].as_array().unwrap();
    assert_eq!(items.len(), parts.len());
    assert_eq!(v["strip_height"].as_f64().unwrap(), 1480.0);
    let area = |pts: &[serde_json::Value]| {
        let p: Vec<(f64, f64)> = pts
            .iter()
            .map(|q| (q[0].as_f64().unwrap(), q[1].as_f64().unwrap()))
            .collect();
        (0..p.len())
            .map(|i| {
                let (a, b) = (p[i], p[(i + 1) % p.len()]);
                a.0 * b.1 - b.0 * a.1
            })
            .sum::<f64>()
            / 2.0
    };
    for (item, part) in items.iter().zip(parts) {
        assert_eq!(item["demand"], part["count"]);
        assert_eq!(item["shape"]["type"], "simple_polygon");
        assert_eq!(item["allowed_orientations"].as_array().unwrap().len(), 4);
        let grown = area(item["shape"]["data"].as_array().unwrap());
        let own = area(part["outline"].as_array().unwrap());
        assert!(grown > own, "{}: {grown} vs {own}", part["id"]);
    }
}
