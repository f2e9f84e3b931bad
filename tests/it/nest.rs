//! Nesting: every part of every buildable sample ×
//! profile placed exactly its count of times, inside the margins, in allowed
//! rotations, kerf + spacing apart (the named invariant `check_nest`, and an
//! independent pairwise check here); never fewer sheets than the lower
//! bound; deterministic; a part too large for the stock is a one-line error.

use crate::support::{self, lamella_command, root, scratch};
use lamella::fabricate::fabricate;
use lamella::formats::read::{read_network, ReadOptions};
use lamella::nest::{check_nest, nest, placed_bbox};
use lamella::{analyze, AnalysisOptions};

#[test]
fn every_buildable_kit_nests_within_the_rules() {
    let mut nested = 0;
    for sample in support::BUILDABLE_SAMPLES {
        let (net, an) = support::analysed_sample(sample);
        for profile in ["steel-1.5", "poplar-ply-4", "beech-veneer"] {
            let p = support::profile(profile);
            let kit = fabricate(&net, &an, &p, None, Default::default()).unwrap();
            let n = nest(&kit, &p).unwrap();
            assert_eq!(check_nest(&kit, &n, &p), Ok(()), "{sample} {profile}");
            let s = &n.summary;
            keeps(&n, promise(sample, profile), &format!("{sample} {profile}"));
            assert!(s.utilization > 0.0 && s.utilization <= 1.0);
            // Independently: parts on a sheet pairwise at least the gap
            // apart, by their boxes or else by their true outlines.
            let g = p.cutting.kerf_mm + p.cutting.part_spacing_mm;
            pairwise_apart(&kit, &n, g, &format!("{sample} {profile}"));
            // Deterministic.
            assert_eq!(nest(&kit, &p).unwrap().sheets, n.sheets);
            nested += 1;
        }
    }
    assert_eq!(nested, 18);
}

/// What the README's nesting table promises for a shipped sample × profile.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Promise {
    /// Sheets used equal the lower bound.
    AtBound,
    /// Above the bound, at most this many sheets (the table says why).
    AtMost(usize),
    /// The parts stage refuses the kit (the table says what), with this in
    /// its message.
    PartsRefuse(&'static str),
}

/// The README's table (sample, then steel-1.5, poplar-ply-4, beech-veneer).
const PROFILES: [&str; 3] = ["steel-1.5", "poplar-ply-4", "beech-veneer"];
const TABLE: [(&str, [Promise; 3]); 12] = {
    use Promise::{AtBound as B, AtMost, PartsRefuse};
    [
        ("enneper-4m", [B, B, B]),
        ("mesh-enneper", [B, B, B]),
        ("catenoid", [AtMost(2), B, AtMost(2)]),
        ("scherk", [B, B, B]),
        ("schwarz-d-patch", [B, B, B]),
        ("hypar-small", [B, B, B]),
        ("film-oculus", [PartsRefuse("slots leave"), B, B]),
        ("film-rings", [B, B, B]),
        ("film-saddle", [B, B, B]),
        ("film-three-peaks", [PartsRefuse("slots leave"), B, B]),
        (
            "schwarz-d-pavilion-1to5",
            [
                PartsRefuse("no room for a 160 mm splice plate"),
                PartsRefuse("no room for a 200 mm splice plate"),
                AtMost(4),
            ],
        ),
        ("schwarz-d-pavilion", [AtMost(16), AtMost(27), AtMost(16)]),
    ]
};

/// The groups other than the lamellas' above their bound, as the README's
/// table names them (sample, profile, group, sheets at most).
const GROUPS_ABOVE: [(&str, &str, &str, usize); 2] = [
    ("schwarz-d-pavilion", "steel-1.5", "washer-3", 3),
    ("schwarz-d-pavilion", "steel-1.5", "shear-block-10", 3),
];

/// On every shipped sample with each profile the nest
/// keeps its rules and uses the lower bound's sheets, or no more than the
/// README's table says (where it names why one more is needed), or the
/// parts stage refuses the kit as the table says. The samples the other
/// tests here nest already are left to them (the table's promise for those
/// is checked there).
#[test]
fn every_shipped_sample_keeps_the_readme_table() {
    let mut checked = 0;
    for (sample, promises) in TABLE {
        if support::BUILDABLE_SAMPLES.contains(&sample) {
            continue;
        }
        let (net, an) = support::analysed_sample(sample);
        for (profile, promise) in PROFILES.iter().zip(promises) {
            if sample == "schwarz-d-pavilion-1to5" && *profile == "beech-veneer" {
                continue;
            }
            let p = support::profile(profile);
            let what = format!("{sample} {profile}");
            match (fabricate(&net, &an, &p, None, Default::default()), promise) {
                (Err(e), Promise::PartsRefuse(msg)) => {
                    assert!(e.to_string().contains(msg), "{what}: {e}");
                }
                (Err(e), _) => panic!("{what}: {e}"),
                (Ok(_), Promise::PartsRefuse(_)) => panic!("{what}: parts made"),
                (Ok(kit), promise) => {
                    let n = nest(&kit, &p).unwrap();
                    assert_eq!(check_nest(&kit, &n, &p), Ok(()), "{what}");
                    keeps(&n, promise, &what);
                }
            }
            checked += 1;
        }
    }
    assert_eq!(checked, 17);
}

/// The table's promise for `sample` × `profile`.
fn promise(sample: &str, profile: &str) -> Promise {
    let (_, ps) = TABLE.iter().find(|(s, _)| *s == sample).unwrap();
    ps[PROFILES.iter().position(|p| *p == profile).unwrap()]
}

/// The nest keeps the promise: the lamellas' stock group (the first) as
/// the table says, every other group (one material and thickness each) at
/// its own bound; never fewer sheets than a bound.
fn keeps(n: &lamella::nest::Nest, promise: Promise, what: &str) {
    for (k, g) in n.groups.iter().enumerate() {
        let s = &g.summary;
        let what = format!("{what} {}", g.name);
        assert!(s.sheets_used >= s.lower_bound_sheets, "{what}");
        let above = GROUPS_ABOVE
            .iter()
            .find(|(sample, profile, group, _)| {
                what.starts_with(&format!("{sample} {profile} ")) && *group == g.name
            })
            .map(|x| Promise::AtMost(x.3));
        match if k == 0 {
            promise
        } else {
            above.unwrap_or(Promise::AtBound)
        } {
            Promise::AtBound => assert_eq!(
                s.sheets_used, s.lower_bound_sheets,
                "{what}: above the bound, and the README does not say why"
            ),
            Promise::AtMost(n) => {
                assert!(s.sheets_used <= n, "{what}: {} > {n}", s.sheets_used)
            }
            Promise::PartsRefuse(_) => panic!("{what}: nested, but the table says parts refuse"),
        }
    }
}

/// A placed part's outline in sheet coordinates (independent of the crate's).
fn sheet_outline(
    part: &lamella::fabricate::part::Part,
    pl: &lamella::nest::Placement,
) -> Vec<kurbo::Point> {
    part.outline_part_mm
        .iter()
        .map(|q| {
            let (x, y) = match pl.rotation_deg {
                90 => (-q.y, q.x),
                180 => (-q.x, -q.y),
                270 => (q.y, -q.x),
                _ => (q.x, q.y),
            };
            kurbo::Point::new(x + pl.x_mm, y + pl.y_mm)
        })
        .collect()
}

/// Brute-force distance of two closed polygons' filled areas (0 when they
/// cross or one holds the other).
fn brute_distance(a: &[kurbo::Point], b: &[kurbo::Point]) -> f64 {
    use kurbo::{Line, ParamCurveNearest, Point};
    let seg = |v: &[Point], i: usize| Line::new(v[i], v[(i + 1) % v.len()]);
    let cross =
        |o: Point, p: Point, q: Point| (p.x - o.x) * (q.y - o.y) - (p.y - o.y) * (q.x - o.x);
    let inside = |v: &[Point], p: Point| {
        let mut c = false;
        for i in 0..v.len() {
            let (s, t) = (v[i], v[(i + 1) % v.len()]);
            if (s.y > p.y) != (t.y > p.y) && p.x < s.x + (p.y - s.y) / (t.y - s.y) * (t.x - s.x) {
                c = !c;
            }
        }
        c
    };
    if inside(b, a[0]) || inside(a, b[0]) {
        return 0.0;
    }
    let mut best = f64::INFINITY;
    for i in 0..a.len() {
        let l = seg(a, i);
        for j in 0..b.len() {
            let m = seg(b, j);
            let (d1, d2) = (cross(l.p0, l.p1, m.p0), cross(l.p0, l.p1, m.p1));
            let (d3, d4) = (cross(m.p0, m.p1, l.p0), cross(m.p0, m.p1, l.p1));
            if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
                return 0.0;
            }
            for (p, s) in [(l.p0, m), (l.p1, m), (m.p0, l), (m.p1, l)] {
                best = best.min(s.nearest(p, 1e-9).distance_sq.sqrt());
            }
        }
    }
    best
}

/// Every pair of parts on every sheet: boxes at least `g` apart, or else
/// true outlines at least `g` apart (brute force).
fn pairwise_apart(kit: &lamella::fabricate::Kit, n: &lamella::nest::Nest, g: f64, what: &str) {
    for (k, sheet) in n.sheets.iter().enumerate() {
        // Bars are sawn end to end a kerf apart (no spacing).
        let group = &n.groups[n.group_of_sheet(k)];
        let g = if group.form == lamella::profile::StockForm::Bar {
            group.cutting.kerf_mm
        } else {
            g
        };
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
                if apart {
                    continue;
                }
                let (pi, pj) = (&sheet.placements[i], &sheet.placements[j]);
                let d = brute_distance(
                    &sheet_outline(&kit.parts[pi.part], pi),
                    &sheet_outline(&kit.parts[pj.part], pj),
                );
                assert!(d >= g - 1e-6, "{what} {}: {d} mm: {a:?} {b:?}", sheet.id);
            }
        }
    }
}

/// The sample that only the veneer profile builds: the outline pass keeps
/// the invariants there too (its edge bands are what it moves).
#[test]
fn the_small_pavilion_nests_within_the_rules_by_outline() {
    let net = read_network(
        &root().join("samples/schwarz-d-pavilion-1to5.yaml"),
        ReadOptions::default(),
    )
    .unwrap();
    let an = analyze(&net, AnalysisOptions::for_network(&net)).unwrap();
    let p = support::profile("beech-veneer");
    let kit = fabricate(&net, &an, &p, None, Default::default()).unwrap();
    let n = nest(&kit, &p).unwrap();
    assert_eq!(check_nest(&kit, &n, &p), Ok(()));
    let g = p.cutting.kerf_mm + p.cutting.part_spacing_mm;
    pairwise_apart(&kit, &n, g, "pavilion-1to5 veneer");
    // By bounding box it took 9 sheets; by outline no more than the table's.
    keeps(
        &n,
        promise("schwarz-d-pavilion-1to5", "beech-veneer"),
        "pavilion-1to5 veneer",
    );
    assert_eq!(nest(&kit, &p).unwrap().sheets, n.sheets);
}

/// A band bowed like an arch: an annular sector of outer radius `r`, width
/// `w`, whose outer chord is `chord` (counter-clockwise).
fn bowed_band(id: &str, r: f64, w: f64, chord: f64) -> lamella::fabricate::part::Part {
    use kurbo::Point;
    use lamella::fabricate::part::{Part, PartKind};
    let half = (0.5 * chord / r).asin();
    let n = 120;
    let mut v: Vec<Point> = Vec::new();
    let arc = |rad: f64, k: usize| {
        let a = std::f64::consts::FRAC_PI_2 - half + 2.0 * half * k as f64 / n as f64;
        Point::new(rad * a.cos(), rad * a.sin())
    };
    for k in 0..=n {
        v.push(arc(r, k));
    }
    for k in (0..=n).rev() {
        v.push(arc(r - w, k));
    }
    // Into the positive quadrant.
    let (x0, y0) = v.iter().fold((f64::INFINITY, f64::INFINITY), |(a, b), q| {
        (a.min(q.x), b.min(q.y))
    });
    let v: Vec<Point> = v.iter().map(|q| Point::new(q.x - x0, q.y - y0)).collect();
    let (x1, y1) = v
        .iter()
        .fold((0.0f64, 0.0f64), |(a, b), q| (a.max(q.x), b.max(q.y)));
    Part {
        id: id.into(),
        kind: PartKind::EdgeStrip,
        strip: None,
        lamella: None,
        count: 1,
        length_mm: x1,
        height_mm: y1,
        station_start_mm: Some(0.0),
        outline_part_mm: v,
        holes_part_mm: Vec::new(),
        engraving: Vec::new(),
        features: Vec::new(),
    }
}

/// Two strongly bowed edge bands: their bounding boxes (each about 800 mm
/// high) cannot share the 1480 mm usable width of a steel sheet, so the
/// bounding-box nest needs two sheets; by outline the second nests in the
/// first's bow and one sheet holds both, the true outlines at least the
/// gap apart. Moving one band 1 mm closer breaks `check_nest`.
#[test]
fn two_bowed_bands_share_one_sheet_by_outline() {
    use lamella::fabricate::{Kit, KitSummary};
    use lamella::geom::plane::signed_area_mm2;
    let steel = support::profile("steel-1.5");
    let g = steel.cutting.kerf_mm + steel.cutting.part_spacing_mm;
    let m = steel.cutting.edge_margin_mm;
    let z = &steel.stock.sizes[0];
    let (lu, wu) = (z.usable_length_mm(m), z.usable_width_mm(m));
    let parts = vec![
        bowed_band("E1", 1700.0, 100.0, 2800.0),
        bowed_band("E2", 1700.0, 100.0, 2800.0),
    ];
    assert!(signed_area_mm2(&parts[0].outline_part_mm) > 0.0);
    let (w, h) = (parts[0].length_mm, parts[0].height_mm);
    // By bounding box: no two on one sheet in any quarter turn.
    assert!(2.0 * h + g > wu && 2.0 * w + g > lu && w > wu, "{w} × {h}");
    let kit = Kit {
        parts,
        summary: KitSummary::default(),
        warnings: Vec::new(),
    };
    let n = nest(&kit, &steel).unwrap();
    assert_eq!(check_nest(&kit, &n, &steel), Ok(()));
    pairwise_apart(&kit, &n, g, "bands");
    assert_eq!(n.summary.sheets_used, 1);
    assert_eq!(n.sheets[0].placements.len(), 2);
    assert_eq!(nest(&kit, &steel).unwrap().sheets, n.sheets);
    // The second band sits in the first's bow: how close they are is the
    // gap (to the refinement's step), not more than a few mm.
    let (a, b) = (&n.sheets[0].placements[0], &n.sheets[0].placements[1]);
    let d = brute_distance(
        &sheet_outline(&kit.parts[a.part], a),
        &sheet_outline(&kit.parts[b.part], b),
    );
    assert!(d >= g - 1e-6 && d < g + 5.0, "{d}");
    // One millimetre closer along the line between them: check_nest says so.
    let mut bad = n.clone();
    let ya = placed_bbox(&kit.parts[a.part], a).1;
    let yb = placed_bbox(&kit.parts[b.part], b).1;
    let k = usize::from(yb > ya);
    let dy = if yb > ya { -1.0 } else { 1.0 };
    bad.sheets[0].placements[k].y_mm += dy * (d - g + 1.0).max(1.0);
    let e = check_nest(&kit, &bad, &steel).unwrap_err();
    assert!(e.contains("closer than"), "{e}");
}

/// Ten copies of a strongly bowed band: by bounding box each takes a steel
/// sheet of its own, and the sheet-elimination pass alone (at most six
/// sheets tried) leaves at least four; placed by outline the bands stack
/// like bananas. How many stack on one sheet, by hand: the copy above,
/// shifted up by d, is clear of the one below where every point of its
/// inner arc (radius r − w) is at least r + g from the lower centre, i.e.
/// (r − w)² + d² + 2 d (r − w) cos θ ≥ (r + g)² at the arc's end angle θ
/// (the smallest cos θ); so n = ⌊(usable width − box height) / d⌋ + 1 per
/// sheet and ⌈10 / n⌉ sheets at most (here 5 a sheet, 2 sheets).
#[test]
fn bowed_bands_stack_by_outline_onto_few_sheets() {
    use lamella::fabricate::{Kit, KitSummary};
    let steel = support::profile("steel-1.5");
    let g = steel.cutting.kerf_mm + steel.cutting.part_spacing_mm;
    let m = steel.cutting.edge_margin_mm;
    let z = &steel.stock.sizes[0];
    let wu = z.usable_width_mm(m);
    let (r, w, chord) = (1700.0, 90.0, 2800.0);
    let mut band = bowed_band("E1", r, w, chord);
    band.count = 10;
    let h = band.height_mm;
    assert!(2.0 * h + g > wu, "{h}");
    // The method keeps the outlines up to 2 (SAFETY_MM + 2 SIMPLIFY_MM)
    // more apart (its engine's polygons: grown, then simplified) and slides
    // to within 0.05 mm.
    use lamella::nest::outline::{SAFETY_MM, SIMPLIFY_MM};
    let ge = g + 2.0 * (SAFETY_MM + 2.0 * SIMPLIFY_MM);
    let c = (1.0 - (0.5 * chord / r).powi(2)).sqrt();
    let (a, q) = (r - w, (r + ge).powi(2) - (r - w).powi(2));
    let d = -a * c + ((a * c).powi(2) + q).sqrt() + 0.05;
    let per_sheet = ((wu - h) / d).floor() as usize + 1;
    let most = 10usize.div_ceil(per_sheet);
    assert!(most < 4, "{d} {per_sheet}");
    let kit = Kit {
        parts: vec![band],
        summary: KitSummary::default(),
        warnings: Vec::new(),
    };
    let n = nest(&kit, &steel).unwrap();
    assert_eq!(check_nest(&kit, &n, &steel), Ok(()));
    pairwise_apart(&kit, &n, g, "stacked bands");
    assert!(
        n.summary.sheets_used <= most,
        "{} > {most}",
        n.summary.sheets_used
    );
    assert_eq!(nest(&kit, &steel).unwrap().sheets, n.sheets);
}

#[test]
fn a_part_larger_than_the_stock_is_a_one_line_error() {
    let net = read_network(
        &root().join("samples/catenoid.yaml"),
        ReadOptions::default(),
    )
    .unwrap();
    let an = analyze(&net, AnalysisOptions::for_network(&net)).unwrap();
    let mut p = support::profile("beech-veneer");
    // Stock narrower than a lamella is high, grain forbids turning it.
    p.stock.sizes[0].width_mm = 20.0;
    // Edge bands are split to fit the stock when the parts are made; when
    // no split can, that stage says so; lamellas are caught by the nest.
    let e = fabricate(&net, &an, &p, None, Default::default())
        .and_then(|kit| nest(&kit, &p).map(|_| ()))
        .unwrap_err()
        .to_string();
    assert!(e.contains("does not fit"), "{e}");
    assert!(e.contains("strip edge") || e.contains("part "), "{e}");
    assert!(!e.contains('\n'));
    // Without edges in the way: the lamellas themselves.
    let mut wide = p.clone();
    wide.stock.sizes[0].width_mm = 300.0;
    let kit = fabricate(&net, &an, &wide, None, Default::default()).unwrap();
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
    let mut p = support::profile("steel-1.5");
    let kit = fabricate(&net, &an, &p, None, Default::default()).unwrap();
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
    let steel = support::profile("steel-1.5");
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
                    engraving: Vec::new(),
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

/// `nest --export-instance DIR/instance.json`: one sparrow strip-packing
/// instance per stock group nested in two dimensions, `instance.GROUP.json`
/// (none for a bar group, nothing at the named path): its items exactly
/// the parts placed on that group's sheets (ids are plan.json's part
/// indices), each once with its count as demand (so the demands add up to
/// the group's placements), an outline grown beyond the part's, the
/// group's rotations, and as strip height the group's sheet width less
/// its margins, read here from the profile file.
#[test]
fn the_sparrow_instances_hold_each_groups_parts_grown() {
    let (mut total, mut bars) = (0, 0);
    for (sample, profile) in [("catenoid", "steel-1.5"), ("enneper-4m", "poplar-ply-4")] {
        let what = format!("{sample} × {profile}");
        let dir = scratch(&format!("instance-{sample}"));
        let out = lamella_command()
            .args(["nest", &format!("samples/{sample}.yaml"), "--profile"])
            .arg(format!("profiles/{profile}.yaml"))
            .arg("--out")
            .arg(&dir)
            .arg("--export-instance")
            .arg(dir.join("instance.json"))
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{what}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text =
            std::fs::read_to_string(root().join(format!("profiles/{profile}.yaml"))).unwrap();
        let yaml: serde_yaml::Value = serde_yaml::from_str(&text).unwrap();
        let plan: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.join("plan.json")).unwrap()).unwrap();
        let parts = plan["parts"].as_array().unwrap();
        let index = |id: &str| parts.iter().position(|p| p["id"] == id).unwrap();
        // Each group's parts and placements, from its sheets.
        let mut placed: std::collections::BTreeMap<
            String,
            (std::collections::BTreeSet<usize>, u64),
        > = Default::default();
        for s in plan["sheets"].as_array().unwrap() {
            let e = placed
                .entry(s["group"].as_str().unwrap().to_string())
                .or_default();
            for pl in s["placements"].as_array().unwrap() {
                e.0.insert(index(pl["part"].as_str().unwrap()));
                e.1 += 1;
            }
        }
        let mut written = 0;
        for g in plan["nesting"]["groups"].as_array().unwrap() {
            let name = g["group"].as_str().unwrap();
            let file = dir.join(format!("instance.{name}.json"));
            if g["form"] == "bar" {
                assert!(!file.exists(), "{what}: {name} is a cut list");
                bars += 1;
                continue;
            }
            written += 1;
            let v: serde_json::Value =
                serde_json::from_slice(&std::fs::read(&file).unwrap()).unwrap();
            let items = v["items"].as_array().unwrap();
            let ids: std::collections::BTreeSet<usize> = items
                .iter()
                .map(|i| i["id"].as_u64().unwrap() as usize)
                .collect();
            let (own_parts, placements) = &placed[name];
            assert_eq!(&ids, own_parts, "{what}: {name}");
            assert_eq!(ids.len(), items.len(), "{what}: {name}: each part once");
            let demand: u64 = items.iter().map(|i| i["demand"].as_u64().unwrap()).sum();
            assert_eq!(demand, *placements, "{what}: {name}");
            // The stock and cutting of the group's first kind, from the file.
            let key = match g["kinds"][0].as_str().unwrap() {
                "washer" => "washer",
                "shear_block" => "shear_block",
                _ => "",
            };
            let entry = &yaml["stocks"][key];
            let width = entry["width_mm"]
                .as_f64()
                .or(yaml["stock"]["width_mm"].as_f64())
                .unwrap();
            let margin = entry["edge_margin_mm"]
                .as_f64()
                .or(yaml["cutting"]["edge_margin_mm"].as_f64())
                .unwrap();
            assert_eq!(
                v["strip_height"].as_f64().unwrap(),
                width - 2.0 * margin,
                "{what}: {name}"
            );
            let rotations: Vec<f64> = entry["allowed_rotations_deg"]
                .as_sequence()
                .or(yaml["cutting"]["allowed_rotations_deg"].as_sequence())
                .unwrap()
                .iter()
                .map(|r| r.as_f64().unwrap())
                .collect();
            let mut area_own = 0.0;
            for item in items {
                let part = &parts[item["id"].as_u64().unwrap() as usize];
                assert_eq!(item["demand"], part["count"], "{what}: {}", part["id"]);
                assert_eq!(item["shape"]["type"], "simple_polygon");
                let got: Vec<f64> = item["allowed_orientations"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|r| r.as_f64().unwrap())
                    .collect();
                assert_eq!(got, rotations, "{what}: {}", part["id"]);
                let grown = shoelace(item["shape"]["data"].as_array().unwrap());
                let own = shoelace(part["outline"].as_array().unwrap());
                assert!(grown > own, "{what}: {}: {grown} vs {own}", part["id"]);
                // Net of its inner contours and round holes.
                let inner: f64 = part["holes"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|h| shoelace(h.as_array().unwrap()))
                    .sum::<f64>()
                    + part["features"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .filter(|f| f["kind"] == "hole")
                        .map(|f| {
                            std::f64::consts::PI * (0.5 * f["width_mm"].as_f64().unwrap()).powi(2)
                        })
                        .sum::<f64>();
                area_own += (own - inner) * part["count"].as_f64().unwrap();
            }
            // The instance's net part area is the group's: its utilisation
            // × its sheets' area (plan.json rounds the utilisation).
            let sheets_area: f64 = plan["sheets"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|s| s["group"] == name)
                .map(|s| s["width_mm"].as_f64().unwrap() * s["length_mm"].as_f64().unwrap())
                .sum();
            let u = g["utilization"].as_f64().unwrap();
            assert!(
                (area_own / sheets_area - u).abs() < 1e-3,
                "{what}: {name}: {area_own} over {sheets_area} against {u}"
            );
        }
        total += written;
        let files = std::fs::read_dir(&dir)
            .unwrap()
            .flatten()
            .filter(|e| e.file_name().to_string_lossy().starts_with("instance"))
            .count();
        assert_eq!(
            files, written,
            "{what}: one file per group, none at the named path"
        );
    }
    // Steel: lamellas, washers, shear blocks; poplar: lamellas (and studs).
    assert_eq!((total, bars), (4, 1));
}

/// A polygon's area, mm², from plan.json's [x, y] pairs.
fn shoelace(pts: &[serde_json::Value]) -> f64 {
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
        .abs()
        / 2.0
}

/// 1500 right-angled star washers (the steel profile's: arms 45 mm from
/// the centre, 9.6 mm wide). By their 93.2 mm boxes a usable sheet holds
/// ⌊2983.2 / 93.2⌋ × ⌊1483.2 / 93.2⌋ = 32 × 15 = 480, so boxes need 4
/// sheets. With the arms interleaved the cell is (w + g)² + (L + w/2 + g)²
/// = 12.8² + 53² = 2973 mm² (+ the µm of safety), so one sheet (4.41 m²)
/// cannot hold 1500 but two can: the nest uses exactly 2, every pair of
/// true outlines at least the gap apart (brute force), deterministic.
#[test]
fn star_washers_interleave_onto_half_the_sheets_of_their_boxes() {
    use kurbo::Point;
    use lamella::fabricate::part::{Part, PartKind};
    use lamella::fabricate::washer::star_outline;
    use lamella::fabricate::{Kit, KitSummary};
    // Washers on the lamella stock's sheets (no `stocks:` of their own).
    let mut steel = support::profile("steel-1.5");
    steel.stocks.clear();
    let g = steel.cutting.kerf_mm + steel.cutting.part_spacing_mm;
    let m = steel.cutting.edge_margin_mm;
    let z = &steel.stock.sizes[0];
    let (lu, wu) = (z.usable_length_mm(m), z.usable_width_mm(m));
    let star = star_outline(90.0, 45.0, 9.6);
    let (x0, y0) = star
        .iter()
        .fold((f64::INFINITY, f64::INFINITY), |(a, b), q| {
            (a.min(q.x), b.min(q.y))
        });
    let outline: Vec<Point> = star
        .iter()
        .map(|q| Point::new(q.x - x0, q.y - y0))
        .collect();
    let count = 1500u32;
    let by_boxes = ((lu + g) / (90.0 + g)).floor() * ((wu + g) / (90.0 + g)).floor();
    assert_eq!(by_boxes, 480.0);
    let cell = (9.6 + g).powi(2) + (45.0 + 4.8 + g).powi(2);
    assert!(
        f64::from(count) * cell > lu * wu,
        "one sheet could hold them"
    );
    let kit = Kit {
        parts: vec![Part {
            id: "W90".into(),
            kind: PartKind::Washer,
            strip: None,
            lamella: None,
            count,
            length_mm: 90.0,
            height_mm: 90.0,
            station_start_mm: None,
            outline_part_mm: outline,
            holes_part_mm: Vec::new(),
            engraving: Vec::new(),
            features: Vec::new(),
        }],
        summary: KitSummary::default(),
        warnings: Vec::new(),
    };
    let n = nest(&kit, &steel).unwrap();
    assert_eq!(check_nest(&kit, &n, &steel), Ok(()));
    pairwise_apart(&kit, &n, g, "washers");
    assert_eq!(n.summary.sheets_used, 2);
    assert_eq!(nest(&kit, &steel).unwrap().sheets, n.sheets);
}
